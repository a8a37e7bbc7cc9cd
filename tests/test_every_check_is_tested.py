"""Every check of every lab fails on at least one realistic wrong implementation.

The lab test files hold the wrong implementations (``MISTAKES``: exercise, code,
expected diagnosis); each is also graded there for its diagnosis. Here they are
graded together to show that no check, hidden ones included, is one that cannot
fail. An advice check (0 points) counts when some submission gets its advice:
the lab test files may list such submissions in ``ADVICE`` (same form).
"""

import importlib

import pytest

from autograder.engine.registry import discover
from conftest import graded_case


@pytest.mark.parametrize("key", [pytest.param(key, marks=pytest.mark.xdist_group(key))
                                 for key in sorted(discover())])
def test_every_check_fails_on_some_realistic_mistake(key):
    lab = discover()[key]
    tests = importlib.import_module(f"test_{key}")
    cases = [*tests.MISTAKES.values(), *getattr(tests, "ADVICE", {}).values()]
    failed = set()
    for exercise, source, _ in cases:
        result = graded_case(lab.module, exercise, source)
        failed |= {(e.id, c.name) for e in result.exercises for c in e.checks if not c.passed}
    never = [(e.id, c.name) for e in lab.exercises.values()
             for c in e.checks if (e.id, c.name) not in failed]
    assert never == [], "checks no realistic mistake in tests/test_labNN.py fails:\n" + \
        "\n".join(f"  {exercise}: {name}" for exercise, name in never)
