"""``autograder verify`` on every built-in lab: each is sound.

Each lab's verification grades its reference (twice), its skeleton and every case of its
mistakes table, through :class:`conftest.SharedGradings`: the whole reference and skeleton
gradings are the session's, and each case's grading is the one its own test in
tests/test_labNN.py makes (same ``xdist_group``, so the same process), graded once.
"""

import pytest

from autograder.engine.registry import discover
from autograder.instructor.verify import verify_lab
from conftest import SharedGradings

BUILT_IN = sorted(key for key, lab in discover().items() if lab.folder is None)


@pytest.mark.slow
@pytest.mark.parametrize("key", [pytest.param(key, marks=pytest.mark.xdist_group(key)) for key in BUILT_IN])
def test_every_built_in_lab_is_sound(key):
    report = verify_lab(discover()[key], SharedGradings())
    assert report.ok, f"{key} is not sound:\n" + "\n".join(report.problems)
    assert report.cases and all(check.failed_by for check in report.checks)
