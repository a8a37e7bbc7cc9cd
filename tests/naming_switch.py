"""Turning the grader's naming off in one process, for tests that assert nothing it writes.

The error model (``name_failure``, ``name_raised``, ``name_in_place``), repairs
(``name_by_repair``) and inherited-failure decisions (``inherited.decide``) then name
nothing: each spends up to seconds per failed check (``naming.GRADING_SECONDS``,
``inherited.GRADING_SECONDS``), which a test of what failing costs elsewhere -- pictures,
statuses, scores, containment -- does not need. Used by the ``no_naming`` fixture
(tests/conftest.py, this process) and by ``naming_off_site/sitecustomize.py`` (a
``grade.py`` subprocess started with that folder on its ``PYTHONPATH``).
"""

from __future__ import annotations

import os
from pathlib import Path

# On a subprocess's PYTHONPATH: its sitecustomize turns naming off there (the sandbox's
# workers get a scrubbed environment, so never this folder).
NAMING_OFF_SITE = Path(__file__).resolve().parent / "naming_off_site"


def turn_naming_off(setattr=setattr) -> None:
    """Replace each naming entry point by one that names nothing (``setattr``: pytest's
    ``monkeypatch.setattr`` to undo it after a test)."""
    from autograder.engine import inherited
    from autograder.engine.mutants import naming, repair

    # (any further arguments a caller gives -- ``said``, a number of tries -- are taken and ignored:
    # a signature narrower than the real one would make each call a logged grader error)
    for name in ("name_failure", "name_raised", "name_in_place"):
        setattr(naming, name, lambda trial, *args, **kwargs: None)
    setattr(repair, "name_by_repair", lambda trial, *args, **kwargs: None)
    setattr(inherited, "decide", lambda trial, function, substitutes, *args, **kwargs: None)


def pythonpath_without_naming(*paths: Path) -> str:
    """A ``PYTHONPATH`` of ``paths`` on which a Python process starts with naming off."""
    return os.pathsep.join(str(path) for path in (NAMING_OFF_SITE, *paths))
