"""Advice: 0-point tips shown in every report, never a failure, never a lost point.

A toy lab registered for the duration of each test exercises the engine: an
advice check (``@exercise.advice``) and the worker's own detection of student
functions that modify their input arrays in place.
"""

import json

import jsonschema
import numpy as np
import pytest
from rich.console import Console

from autograder.instructor import gradescope
from autograder.instructor.course import CourseConfig
from autograder.engine.registry import REGISTRY, Lab
from autograder.reports import html, terminal
from autograder.engine.results import ADVICE, GradingResult
from autograder.engine.runner import grade
from conftest import submission_from_source
from test_gradescope import SCHEMA


@pytest.fixture
def toy_lab():
    lab = Lab("lab98", module="toy_scaling", title="Toy")
    ex1 = lab.exercise("ex1", "Scaling", functions=["scale(values, factor)"])

    @ex1.check("scale([1, 2, 3], 2)", points=2)
    def doubles(t):
        got = t.expect_array(t.call("scale", np.array([1.0, 2.0, 3.0]), 2.0), "scale()", shape=(3,))
        if not np.allclose(got, [2, 4, 6]):
            t.fail(f"scale() returned {got}")

    @ex1.advice("float64 results")
    def float64(t):
        got = t.call("scale", np.array([1.0, 2.0]), 2.0)
        if getattr(got, "dtype", None) != np.float64:
            t.advise(f"scale() returned dtype {got.dtype}; float64 keeps full precision",
                     hint="np.asarray(values, dtype=float)")

    yield lab
    REGISTRY.pop("lab98")


CORRECT = "def scale(values, factor):\n    return values * factor\n"
IN_PLACE_FLOAT32 = """
import numpy as np

def scale(values, factor):
    values[:] = values[::-1]          # reverses the caller's array: a second call answers the same
    return np.sort(values).astype(np.float32) * factor
"""


def test_a_correct_function_gets_no_advice(toy_lab, tmp_path):
    result = grade(submission_from_source(tmp_path, "toy_scaling", CORRECT), ["lab98"])
    [exercise] = result.exercises
    assert (exercise.score, exercise.max_score) == (2, 2)
    assert [c.status for c in exercise.checks] == ["passed", "passed"]


def test_advice_is_shown_in_every_report_and_costs_nothing(toy_lab, tmp_path):
    result = grade(submission_from_source(tmp_path, "toy_scaling", IN_PLACE_FLOAT32), ["lab98"])
    [exercise] = result.exercises
    assert (exercise.score, exercise.max_score) == (2, 2)
    tips = {c.name: c for c in exercise.checks if c.advice}
    assert set(tips) == {"float64 results", "inputs left unchanged"}
    assert all(c.status == ADVICE and c.score == c.max_score == 0 for c in tips.values())
    assert "dtype float32" in tips["float64 results"].message
    assert tips["float64 results"].hint == "np.asarray(values, dtype=float)"
    in_place = tips["inputs left unchanged"].message
    assert in_place == "scale() modified its input array `values` in place; callers do not expect that"

    data = json.loads(json.dumps(result.to_dict()))
    [advice] = [c for c in data["exercises"][0]["checks"] if c["name"] == "inputs left unchanged"]
    assert advice["advice"] and advice["status"] == "advice" and not advice["passed"]
    assert GradingResult.from_dict(data).to_dict() == result.to_dict()

    console = Console(record=True, width=200)
    terminal.render(result, console)
    text = console.export_text()
    assert "2 / 2" in text and "✗" not in text
    assert "tip lab98.ex1 inputs left unchanged (no points): scale() modified its input array `values`" in text

    page = html.render(result)
    assert "advice, no points" in page and "modified its input array <code>" not in page
    assert "scale() modified its input array `values` in place" in page

    results = gradescope.results_json(result, CourseConfig())
    jsonschema.validate(results, SCHEMA)
    assert results["score"] == 2
    assert {t["status"] for t in results["tests"]} == {"passed"}
    [tip] = [t for t in results["tests"] if t["name"].endswith("inputs left unchanged")]
    assert tip["max_score"] == 0 and tip["output"].startswith("<p>Tip (no points): scale() modified")


def test_advice_says_nothing_when_the_function_fails(toy_lab, tmp_path):
    broken = "def scale(values, factor):\n    raise ValueError('no')\n"
    result = grade(submission_from_source(tmp_path, "toy_scaling", broken), ["lab98"])
    [graded, advice] = result.exercises[0].checks
    assert graded.status == "failed" and "ValueError" in graded.message
    assert advice.status == "passed" and advice.message == "" and advice.max_score == 0


def test_a_stub_is_not_implemented_yet_whatever_its_advice_checks(toy_lab, tmp_path):
    stub = "def scale(values, factor):\n    raise NotImplementedError\n"
    result = grade(submission_from_source(tmp_path, "toy_scaling", stub), ["lab98"])
    assert result.exercises[0].message == "not implemented yet"
    assert [c.status for c in result.exercises[0].checks] == ["not implemented"] * 2
    assert all("not implemented yet" in c.message for c in result.exercises[0].checks)


def test_advise_belongs_in_advice_checks(toy_lab, tmp_path):
    @toy_lab.exercises["ex1"].check("misplaced tip", points=1)
    def misplaced(t):
        t.advise("a graded check cannot give advice")

    result = grade(submission_from_source(tmp_path, "toy_scaling", CORRECT), ["lab98"])
    [check] = [c for c in result.exercises[0].checks if c.name == "misplaced tip"]
    assert check.status == "grader error" and "@exercise.advice" in check.message


def test_an_advice_check_is_worth_no_points(toy_lab):
    assert [c.points for c in toy_lab.exercises["ex1"].checks if c.advice] == [0.0]
    assert toy_lab.exercises["ex1"].max_score() == 2


def test_arrays_inside_a_list_argument_are_watched_too(toy_lab, tmp_path):
    @toy_lab.exercises["ex1"].check("scale a list", points=1)
    def scales_a_list(t):
        t.call("scale", [np.zeros(2), np.ones(2)], 2.0)

    source = CORRECT + "\n_scale = scale\n" + """
def scale(values, factor):
    if isinstance(values, list):
        values[1] *= factor
        return values
    return _scale(values, factor)
"""
    result = grade(submission_from_source(tmp_path, "toy_scaling", source), ["lab98"])
    [tip] = [c for c in result.exercises[0].checks if c.name == "inputs left unchanged"]
    assert tip.message == "scale() modified its input array `values[1]` in place; callers do not expect that"


SCALES_IN_PLACE = """
def scale(values, factor):
    values *= factor                  # the caller's array is scaled too
    return values
"""


def test_a_change_in_place_that_shows_in_a_second_call_loses_the_check(toy_lab, tmp_path):
    """The first call answers rightly; called again on the caller's array (now doubled) it
    answers 4x: the check where that shows fails, naming the argument and what was done to it."""
    result = grade(submission_from_source(tmp_path, "toy_scaling", SCALES_IN_PLACE), ["lab98"])
    [exercise] = result.exercises
    [doubles] = [c for c in exercise.checks if c.name == "scale([1, 2, 3], 2)"]
    assert doubles.score == 0 and doubles.mistake == "the caller's array is changed in place"
    assert doubles.message.startswith("scale() multiplies (by 2) the caller's `values` in place: called a "
                                      "second time on that same array")
    assert "np.array(x, dtype=float)" in doubles.hint
    assert any(c.name == "inputs left unchanged" and c.advice for c in exercise.checks)


def test_a_change_in_place_costs_one_check_only(toy_lab, tmp_path):
    @toy_lab.exercises["ex1"].check("scale([1, 2], 3)", points=1)
    def triples(t):
        got = t.call("scale", np.array([1.0, 2.0]), 3.0)
        if not np.allclose(got, [3, 6]):
            t.fail(f"scale() returned {got}")

    result = grade(submission_from_source(tmp_path, "toy_scaling", SCALES_IN_PLACE), ["lab98"])
    scores = {c.name: c.score for c in result.exercises[0].checks if c.max_score > 0}
    assert scores == {"scale([1, 2, 3], 2)": 0, "scale([1, 2], 3)": 1}


NOISY = """
import numpy as np

def scale(values, factor):
    out = values * factor + np.random.default_rng().normal(0, {noise}, len(values))
    values *= factor                  # shows in a second call
    return out
"""


def test_answers_that_vary_for_the_same_input_are_not_blamed_on_a_change_within_their_spread(toy_lab, tmp_path):
    """Answers that differ from call to call (by a millionth, as a random draw without a seed would) say nothing of
    a change whose effect on the answer is within that spread."""
    drifting = """
import numpy as np

def scale(values, factor):
    out = values * factor + np.random.default_rng().normal(0, 1e-6, len(values))
    values += 1e-9                    # a change in place far within the answers' own spread
    return out
"""
    result = grade(submission_from_source(tmp_path, "toy_scaling", drifting), ["lab98"])
    [doubles] = [c for c in result.exercises[0].checks if c.name == "scale([1, 2, 3], 2)"]
    assert doubles.passed, doubles.message


@pytest.mark.parametrize("noise", [1e-6, 1e-5])
def test_answers_that_vary_do_not_hide_a_change_that_shows_far_beyond_their_spread(toy_lab, tmp_path, noise):
    """Jitter added to every answer (hostile round of 2026-12-07: 1e-5, within every accuracy check) made the second
    call's answer "another draw": the caller's array doubled doubles the answer, far beyond the jitter."""
    result = grade(submission_from_source(tmp_path, "toy_scaling", NOISY.format(noise=noise)), ["lab98"])
    [doubles] = [c for c in result.exercises[0].checks if c.name == "scale([1, 2, 3], 2)"]
    assert doubles.score == 0 and doubles.mistake == "the caller's array is changed in place", doubles.message


def test_noise_in_the_last_digits_does_not_hide_a_change_in_place(toy_lab, tmp_path):
    """The same answer but for its last digits is the same answer: noise of 1e-13 added to every answer does not
    make the second call's 4x an answer of its own (hostile round of 2026-12-07)."""
    result = grade(submission_from_source(tmp_path, "toy_scaling", NOISY.format(noise=1e-12)), ["lab98"])
    [doubles] = [c for c in result.exercises[0].checks if c.name == "scale([1, 2, 3], 2)"]
    assert doubles.score == 0 and doubles.mistake == "the caller's array is changed in place", doubles.message


def test_what_a_change_in_place_did_is_told_from_the_values():
    from autograder.engine.inplace import argument_name, how_changed, with_changed

    points = np.array([[1.0, 2.0], [3.0, 5.0]])
    assert how_changed(points, points / 4) == "divides (by 4)"
    assert how_changed(points, points * 3) == "multiplies (by 3)"
    assert how_changed(points, points - points.mean(axis=0)).startswith("shifts")
    # (the offset as the call added it, sign included: `p2[:, 0] += w1` adds, it does not subtract)
    assert how_changed(points, points + [400.0, 0.0]) == "shifts (adds [400, 0] to every row of)"
    assert how_changed(points[:, 0], points[:, 0] - 3) == "shifts (adds -3 to every entry of)"
    assert how_changed(points, np.zeros((2, 2))) == "writes into"
    assert argument_name("normalise_points(points, scale=1.0)", 0, None) == "points"
    assert argument_name("calibrate(images, pattern_size, square_size)", 0, 2) == "images[2]"
    assert argument_name("f(a)", "b", None) == "b"
    args, kwargs = with_changed(([np.zeros(1), np.ones(1)], 2.0), {"x": np.ones(2)},
                                [(0, 1, np.full(1, 7.0)), ("x", None, np.zeros(2))])
    assert args[0][1][0] == 7.0 and args[1] == 2.0 and not kwargs["x"].any()
    assert with_changed((np.ones(1),), {}, [(3, None, np.ones(1))]) is None


def test_a_value_computed_and_never_used_is_advice_where_every_check_passes(toy_lab, tmp_path):
    # (a step begun and not finished -- sub-pixel corners refined, the raw ones calibrated -- that no check asks
    # for: said at no cost, where the checks could not tell it; a function that fails says it in its failure)
    unused = "import numpy as np\n\ndef scale(values, factor):\n    ordered = np.sort(values)\n    return values * factor\n"
    result = grade(submission_from_source(tmp_path, "toy_scaling", unused), ["lab98"])
    [exercise] = result.exercises
    assert (exercise.score, exercise.max_score) == (2, 2)
    [tip] = [c for c in exercise.checks if c.name == "every value computed is used"]
    assert tip.status == ADVICE and tip.max_score == 0
    assert tip.message == "your `scale` computes `ordered` (line 4) and never uses it: a step that needs it may be missing"
    failing = unused.replace("values * factor", "values * factor + 1")
    result = grade(submission_from_source(tmp_path / "failing", "toy_scaling", failing), ["lab98"])
    assert not [c for c in result.exercises[0].checks if c.name == "every value computed is used"]
