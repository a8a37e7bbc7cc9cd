"""One mistake, one account (issue 35): a recipe hint is not shown beside a named mistake of the
same function -- it describes code that is mostly right (the evaluator of blind set 28c read the
NCC formula told to a matcher whose NCC is right and whose search runs the wrong way)."""

from __future__ import annotations

from autograder.engine.registry import select
from autograder.engine.results import CheckResult
from autograder.engine.runner import _hints_beside_a_name, grade
from conftest import check_results, mutant

WRONG_WAY = """
    def _shift_right(image, d):
        if d == 0:
            return image
        out = np.empty_like(image)
        out[:, :-d] = image[:, d:]
        out[:, -d:] = image[:, -1:]
        return out
    """


def test_a_named_search_direction_takes_the_recipes_off_the_matchers_other_checks(tmp_path):
    result = grade(mutant(tmp_path, "lab12_stereo", WRONG_WAY), ["lab12.ex4", "lab12.ext1"], pictures="none")
    failed = [c for e in ("lab12.ex4", "lab12.ext1") for c in check_results(result, e) if not c.passed and c.max_score > 0]
    named = [c for c in failed if "wrong direction" in c.message]
    assert named, [c.message for c in failed]
    unnamed = [c for c in failed if not c.mistake]
    assert unnamed, "the test needs a check the name does not reach"
    for check in unnamed:
        assert "NCC =" not in check.hint and "compare its block" not in check.hint, check.hint
        assert "names the mistake found in your `block_matching`" in check.hint, check.hint


def _result(name, mistake="", hint="a recipe", hidden=False, passed=False):
    return CheckResult(name=name, score=1.0 if passed else 0.0, max_score=1.0, status="passed" if passed else "failed",
                       message="m", hint=hint, mistake=mistake, hidden=hidden)


class _Done:   # an exercise's result, as far as the rule reads it
    def __init__(self, *checks):
        self.checks = list(checks)


def test_the_error_models_name_drops_its_own_checks_recipe_and_a_public_check_never_points_at_a_hidden_one():
    exercise = select(["lab12.ex4"])[0]
    public = [c.name for c in exercise.checks if not c.hidden]
    hidden = [c.name for c in exercise.checks if c.hidden]
    modelled = _result(public[0], mistake="mutant:axis")
    other = _result(public[1])
    _hints_beside_a_name([(exercise, _Done(modelled, other))])
    assert modelled.hint == "" and other.hint.startswith(f"the check \u201c{public[0]}\u201d")
    if hidden:
        secret, shown = _result(hidden[0], mistake="a hand-written name", hidden=True), _result(public[1])
        _hints_beside_a_name([(exercise, _Done(secret, shown))])
        assert shown.hint == "a recipe" and secret.hint == "a recipe"
    alone = _result(public[1])
    _hints_beside_a_name([(exercise, _Done(alone))])
    assert alone.hint == "a recipe"                      # nothing named: the recipe stays
