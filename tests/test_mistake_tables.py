"""Every exercise has its table of realistic mistakes, each one named.

The tables are ``autograder/labs/mistakes/labNN.py`` (``MISTAKES``: name -> exercise,
wrong code, fragments the diagnosis must contain), read as ``autograder verify`` reads
them (:func:`autograder.instructor.verify.parts_of`, which refuses a malformed case);
verify grades each case (tests/test_verify.py). Here the tables themselves are held to
the issue's bar: at least five realistic mistakes per exercise, unless the table says
why its algorithm has fewer (``FEWER_MISTAKES``: exercise -> reason).
"""

import pytest

from autograder.engine.registry import discover
from autograder.instructor.verify import parts_of

AT_LEAST = 5
BUILT_IN = sorted(key for key, lab in discover().items() if lab.folder is None)


@pytest.mark.parametrize("key", BUILT_IN)
def test_every_exercise_has_a_table_of_named_mistakes(key):
    parts = parts_of(discover()[key])
    counts = {exercise.id: 0 for exercise in discover()[key].exercises.values()}
    for case in parts.cases:
        assert case.fragments, f"{case.exercise}: a mistake case must say how its diagnosis reads"
        counts[case.exercise] += not case.advice
    short = {e: n for e, n in counts.items() if n < AT_LEAST and not parts.fewer.get(e)}
    assert not short, f"{key}: exercises with fewer than {AT_LEAST} named mistakes " \
                      f"(and no reason in FEWER_MISTAKES): {short}"
    stale = sorted(set(parts.fewer) - set(counts))
    assert not stale, f"{key}: FEWER_MISTAKES names exercises that do not exist: {stale}"
