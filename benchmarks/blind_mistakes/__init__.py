"""A blind set of single-bug submissions, for measuring how the grader names mistakes.

Written after the issue asked for it and before the naming mechanism was changed,
apart from the project's mistake tables (``tests/test_labNN.py`` ``MISTAKES``,
``fixtures/labNN.py`` ``*_mistakes``): each case is what a student following the lab
sheet could write, one bug in one function, appended to the reference module (its
``def`` wins, as ``tests/conftest.mutant`` does). Nothing here is tuned on: the truth
of each case was written with the case, before any measurement.

``benchmarks/blind_naming.py`` grades every case and classifies it.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Case:
    """One single-bug submission.

    name : what the student did, in a few words.
    exercise : the exercise graded (``"lab08.ex1"``).
    source : the function(s) redefined, as the student wrote them.
    truth : the cause, in words.
    accept : fragments (lower case); a name is right when it contains one of them.
    moves : whether the bug moves results beyond what legitimate variants do (then it
        must be caught); False for a bug whose returned values are right.
    """

    name: str
    exercise: str
    source: str
    truth: str
    accept: tuple[str, ...]
    moves: bool = True


def all_cases() -> dict[str, list[Case]]:
    """Every lab's cases, by lab key (``"lab08"``)."""
    from . import lab07, lab08, lab09, lab10, lab11, lab12

    return {module.__name__.rsplit(".", 1)[1]: module.CASES
            for module in (lab07, lab08, lab09, lab10, lab11, lab12)}
