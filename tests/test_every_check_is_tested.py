"""Every check of every lab fails on at least one realistic wrong implementation.

The lab test files hold the wrong implementations (``MISTAKES``: exercise, code,
expected diagnosis); each is also graded there for its diagnosis. Here they are
graded together to show that no check, hidden ones included, is one that cannot
fail. An advice check (0 points) counts when some submission gets its advice:
the lab test files may list such submissions in ``ADVICE`` (same form).
"""

import importlib

import pytest

from autograder.registry import discover
from autograder.runner import grade
from conftest import mutant


@pytest.mark.parametrize("key", sorted(discover()))
def test_every_check_fails_on_some_realistic_mistake(tmp_path, key):
    lab = discover()[key]
    tests = importlib.import_module(f"test_{key}")
    cases = [*tests.MISTAKES.values(), *getattr(tests, "ADVICE", {}).values()]
    failed = set()
    for index, (exercise, source, _) in enumerate(cases):
        submission = mutant(tmp_path / f"{key}-{index}", lab.module, source)
        result = grade(submission, [exercise], pictures="none")
        failed |= {(e.id, c.name) for e in result.exercises for c in e.checks if not c.passed}
    never = [(e.id, c.name) for e in lab.exercises.values()
             for c in e.checks if (e.id, c.name) not in failed]
    assert never == [], "checks no realistic mistake in tests/test_labNN.py fails:\n" + \
        "\n".join(f"  {exercise}: {name}" for exercise, name in never)
