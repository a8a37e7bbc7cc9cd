"""A call the grader could not make inside a property (its worker did not start in time on a
loaded machine: a ``grader_error`` outcome) is the grader's failure, reported as one.

It fails once and passes when Hypothesis replays the example, so Hypothesis calls the test
flaky; the check used to say the student's function "gave different answers for the same
input" (the reference under load, tests/test_precision.py's float32 grading).
"""

from __future__ import annotations

import pytest

from autograder.engine.results import ERROR
from autograder.engine.runner import grade
from autograder.sandbox import supervisor
from autograder.sandbox.supervisor import CallOutcome
from conftest import REFERENCE, check_results

PROPERTY = "intrinsic_matrix for any f, px, py"   # lab09.ex2: a property of 10 examples


@pytest.mark.slow
def test_a_grader_error_once_inside_a_property_is_a_grader_error(monkeypatch):
    original, calls = supervisor.Sandbox.call, []

    def call(self, module, function, *args, **kwargs):
        if function == "intrinsic_matrix":
            calls.append(function)
            if len(calls) == 6:   # one call of the property's, once: the next is served again
                return CallOutcome(ok=False, kind="grader_error", message="the grading worker did not start")
        return original(self, module, function, *args, **kwargs)

    monkeypatch.setattr(supervisor.Sandbox, "call", call)
    result = grade(REFERENCE, ["lab09.ex2"], pictures="none")
    [check] = [c for c in check_results(result, "lab09.ex2") if c.name == PROPERTY]
    assert len(calls) > 6, "the property was replayed after the failure"
    assert check.status == ERROR and "the grading worker did not start" in check.message, check
    assert "different answers" not in check.message
    others = [c for c in check_results(result, "lab09.ex2") if c.name != PROPERTY and not c.advice]
    assert others and all(c.passed for c in others)
