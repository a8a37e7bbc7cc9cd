"""Every check of every lab fails on at least one realistic wrong implementation.

The tables of wrong implementations live in ``autograder/labs/mistakes/labNN.py``; the
judgement is ``autograder verify``'s own (:func:`autograder.instructor.verify.failures`, which
its report's "failed by" column counts), which tests/test_verify.py runs on every lab. Here the judgement itself is held to account:
it finds a check that no case fails, and counts an advice check as failed when it gave its tip.
"""

from types import SimpleNamespace

from autograder.engine.results import ADVICE, ERROR, FAILED, PASSED, CheckResult, ExerciseResult, GradingResult
from autograder.instructor.verify import failures, unfailed_checks

NAMES = ("caught", "never failed", "a tip")
LAB = SimpleNamespace(exercises={"ex1": SimpleNamespace(id="lab98.ex1", checks=[SimpleNamespace(name=n)
                                                                              for n in NAMES])})


def graded(*statuses) -> GradingResult:
    result = GradingResult("s", "h", "0")
    result.exercises = [ExerciseResult("lab98.ex1", "One", ["f"], [
        CheckResult(name, 1.0 if status == PASSED else 0.0, 0.0 if name == "a tip" else 1.0, status)
        for name, status in zip(NAMES, statuses)])]
    return result


def test_a_check_no_case_fails_is_found():
    assert unfailed_checks(LAB, [graded(FAILED, PASSED, ADVICE), graded(PASSED, PASSED, PASSED)]) == [
        ("lab98.ex1", "never failed")]


def test_an_advice_check_counts_only_when_it_gives_its_tip():
    assert unfailed_checks(LAB, [graded(FAILED, FAILED, PASSED)]) == [("lab98.ex1", "a tip")]
    assert unfailed_checks(LAB, [graded(FAILED, FAILED, ADVICE)]) == []


def test_the_cases_failing_each_check_are_counted_and_a_grader_error_is_no_failure():
    assert failures([graded(FAILED, PASSED, ADVICE), graded(FAILED, ERROR, PASSED)]) == {
        ("lab98.ex1", "caught"): 2, ("lab98.ex1", "a tip"): 1}
