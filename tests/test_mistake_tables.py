"""Every exercise has its table of realistic mistakes, each one named.

The lab test files hold the tables (``MISTAKES``: name -> exercise, wrong code,
fragments the diagnosis must contain) and grade each case: the mistake must be
named, and no check may name a different one (``conftest.assert_diagnosed``).
Here the tables themselves are held to the issue's bar: at least five realistic
mistakes per exercise, unless the lab test file says why its algorithm has fewer
(``FEWER_MISTAKES``: exercise -> reason).
"""

import importlib

import pytest

from autograder.engine.registry import discover

AT_LEAST = 5


@pytest.mark.parametrize("key", sorted(discover()))
def test_every_exercise_has_a_table_of_named_mistakes(key):
    tests = importlib.import_module(f"test_{key}")
    fewer = getattr(tests, "FEWER_MISTAKES", {})
    counts = {exercise.id: 0 for exercise in discover()[key].exercises.values()}
    for exercise_id, _source, fragments in tests.MISTAKES.values():
        assert fragments, f"{exercise_id}: a mistake case must say how its diagnosis reads"
        counts[exercise_id] += 1
    short = {e: n for e, n in counts.items() if n < AT_LEAST and not fewer.get(e)}
    assert not short, f"{key}: exercises with fewer than {AT_LEAST} named mistakes " \
                      f"(and no reason in FEWER_MISTAKES): {short}"
    stale = sorted(set(fewer) - set(counts))
    assert not stale, f"{key}: FEWER_MISTAKES names exercises that do not exist: {stale}"
