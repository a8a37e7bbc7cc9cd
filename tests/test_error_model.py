"""The error model (autograder.engine.mutants): mutants of the reference, confirmed on the
student's own inputs, name mistakes nobody listed."""

from __future__ import annotations

import ast
import re
import types
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from autograder.engine.mutants import naming
from autograder.engine.mutants.helper import Helper, HelperFailed
from autograder.engine.mutants.operators import OPERATORS, Mutant, apply_edits, mutants_of, mutated_defs
from autograder.engine.registry import discover
from autograder.sandbox.supervisor import CallOutcome

ROOT = Path(__file__).resolve().parents[1]
LABS = discover()


def _api(lab) -> set[str]:
    return {name for exercise in lab.exercises.values() for name in exercise.signatures}


def _source(lab) -> str:
    return (ROOT / "reference_solutions" / f"{lab.module}.py").read_text()


@pytest.mark.parametrize("key", sorted(LABS))
def test_operators_make_valid_distinct_mutants_of_every_reference_function(key):
    """Every graded function of every lab has mutants; each (its edits once, where several graded
    functions share a helper) is valid Python, changes its def, and no two make the same code."""
    lab = LABS[key]
    source = _source(lab)
    tree = ast.parse(source)
    defs = {n.name for n in tree.body if isinstance(n, ast.FunctionDef)}
    every = mutants_of(source, _api(lab))
    assert set(every) == _api(lab) & defs
    unique = {}
    for function, mutants in every.items():
        assert mutants, f"{function}: no mutant"
        for mutant in mutants:
            assert mutant.operator in OPERATORS and mutant.function == function
            unique.setdefault(mutant.key, mutant)
    originals = {n.name: ast.unparse(n) for n in tree.body if isinstance(n, ast.FunctionDef)}
    made = set()
    for mutant in unique.values():
        module = mutated_defs(tree, mutant.edits, source)
        compile(module, "<mutant>", "exec")     # valid Python
        [changed] = module.body
        text = ast.unparse(changed)
        assert text != originals[mutant.where], f"{mutant.sentence}: changes nothing"
        assert text not in made, f"{mutant.sentence}: the same code as another mutant"
        made.add(text)


@pytest.mark.parametrize("key", sorted(LABS))
def test_sentences_speak_the_students_terms(key):
    """A sentence names the graded function, API parameters and functions, NumPy/OpenCV calls:
    never a local variable or a private helper of the reference, never its code."""
    lab = LABS[key]
    source = _source(lab)
    tree = ast.parse(source)
    defs = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    api = _api(lab)
    allowed = set(api) | {a.arg for name in api if name in defs for a in defs[name].args.args}
    for function, mutants in mutants_of(source, api).items():
        for mutant in mutants:
            assert mutant.sentence.startswith(f"in `{function}`")
            for quoted in re.findall(r"`([^`]+)`", mutant.sentence):
                assert quoted in allowed | {"min", "max"} or quoted.startswith(("cv2.", "np.")), (mutant.sentence, quoted)
            assert "=" not in mutant.sentence, mutant.sentence


def test_apply_edits_rebuilds_the_whole_module():
    lab = LABS["lab07"]
    source = _source(lab)
    [degrees] = [m for m in mutants_of(source, _api(lab))["rotation_matrix"] if m.operator == "degrees"
                 and "missing" in m.sentence]
    module = types.ModuleType("m")
    exec(apply_edits(source, degrees.edits), module.__dict__)  # noqa: S102 - the reference, changed
    theta = 30.0
    assert np.allclose(module.rotation_matrix(theta)[0, 1], np.sin(theta))   # degrees used as radians


def test_two_names_used_in_each_others_place_are_told_as_exchanged():
    lab = LABS["lab11"]
    mutants = naming.model_for(lab).mutants["essential_from_fundamental"]
    k1_for_k2 = next(m for m in mutants if m.sentence.endswith("`K1` is used where `K2` belongs"))
    k2_for_k1 = next(m for m in mutants if m.sentence.endswith("`K2` is used where `K1` belongs"))
    pair = k1_for_k2.combined(k2_for_k1)
    assert pair.operator == "swap_names" and len(pair.edits) == 2
    assert pair.sentence == ("in `essential_from_fundamental`, `K2` and `K1` are exchanged "
                             "(each is used where the other belongs)")
    plain = k1_for_k2.combined(next(m for m in mutants if m.operator != "other_name"))
    assert "; and " in plain.sentence and "+" in plain.operator


# ------------------------------------------------------------------ naming, with a stand-in sandbox
class _InProcess:
    """A stand-in for the student's sandbox: the (test's own, trusted) student module called here."""

    def __init__(self, module):
        self.module, self.shared, self.asked = module, {}, []

    def call(self, module, function, args, kwargs, timeout=None, forbid=()):
        self.asked.append((function, args, kwargs))
        print("the student printed this")
        return CallOutcome(ok=True, value=getattr(self.module, function)(*args, **kwargs), output="hello")


def _trial(key: str, student_source: str, calls):
    """A failed trial: the student's module (the reference with ``student_source`` appended)
    called as ``calls`` [(function, args, kwargs)]."""
    lab = LABS[key]
    module = types.ModuleType("student")
    exec(_source(lab) + "\n\n" + student_source, module.__dict__)  # noqa: S102 - the test's own code
    recorded = [(f, a, k, getattr(module, f)(*a, **k)) for f, a, k in calls]
    return SimpleNamespace(lab=lab, calls=recorded, sandbox=_InProcess(module), check=SimpleNamespace(timeout=10),
                           forbid={}, student_seconds=0.0, outputs=[])


TINY = "import numpy as np\n\n\ndef f(x, k=2.0):\n    return np.array([[x * k + 1.0]])\n"


def test_the_confirmation_separates_two_candidates_and_names_the_true_one(monkeypatch):
    """At x = 0, -(x k + 1) and x k - 1 both give the student's -1: two candidates. The
    confirmation inputs (other x, other k) tell them apart; only the true one is named."""
    from autograder.engine.mutants.naming import ErrorModel, _numeric_defaults

    model = ErrorModel("tiny", TINY, mutants_of(TINY, {"f"}), _numeric_defaults(TINY))
    monkeypatch.setattr(naming, "model_for", lambda lab: model)
    student = types.ModuleType("student")
    exec(TINY.replace("x * k + 1.0", "x * k - 1.0"), student.__dict__)  # noqa: S102 - the test's own code
    lab = SimpleNamespace(module="tiny", forbidden={})
    trial = SimpleNamespace(lab=lab, calls=[("f", (0.0,), {}, student.f(0.0))], sandbox=_InProcess(student),
                            check=SimpleNamespace(timeout=10), forbid={}, student_seconds=0.0, outputs=[])
    runner = naming.helper()
    runner.prepare(model.source, model.module, [("f", (0.0,), {})], 10)
    [reference] = runner.run((), [0], 10)
    reproducing = {m.operator for m in model.mutants["f"]
                   if naming.reproduces(runner.run(m.edits, [0], 5)[0], trial.calls[0][3], reference)}
    assert {"sign", "add_sub"} <= reproducing        # on the failing input alone, both fit

    named = naming.name_failure(trial, seconds=60)
    assert named is not None and named.mutant.operator == "add_sub", named
    assert named.sentence == "in `f`, 1.0 is subtracted instead of added (`x` times `k` plus it)"
    assert named.confirmations >= 1 and trial.sandbox.asked           # the student was asked
    assert any(call[1] != (0.0,) for call in trial.sandbox.asked)      # on other inputs
    assert any("confirmation call" in output for output in trial.outputs)   # its printing labelled


def test_a_student_no_mutant_explains_is_not_named():
    """A rotation by a fixed wrong angle is no operator's: nothing is named."""
    trial = _trial("lab07", "def rotation_matrix(angle_deg, center=(0.0, 0.0)):\n"
                            "    return np.array([[0.3, 0.1, 2.0], [0.5, 0.9, 1.0], [0.0, 0.0, 1.0]])\n",
                   [("rotation_matrix", (30.0,), {"center": (3.0, -2.0)})])
    assert naming.name_failure(trial, seconds=60) is None


def test_a_mutant_dividing_by_zero_where_the_student_gives_a_number_is_not_named():
    """A depth map tested with d != 0 where d > 0 belongs: the mutant whose validity test is always
    true gives inf at d = 0, where the student (like the reference) gives 0; the NaN leniency is for
    the reference's own marks, so that mutant is not the student's mistake (it was told as "`f` is
    used where `disparity` belongs")."""
    student = ("def depth_from_disparity(disparity, f, baseline):\n"
               "    d = np.asarray(disparity, dtype=np.float64)\n"
               "    ok = np.isfinite(d) & (d != 0)\n"
               "    return np.where(ok, f * baseline / np.where(ok, d, 1.0), 0.0)\n")
    disparities = np.array([[0.0, -3.0, np.nan, 5.0], [10.0, 0.0, -1.0, 20.0]])
    trial = _trial("lab12", student, [("depth_from_disparity", (disparities, 400.0, 0.2), {})])
    assert naming.reproduces(np.array([[np.inf, -26.7, 0.0, 16.0], [8.0, np.inf, -80.0, 4.0]]),
                             np.array([[0.0, -26.7, 0.0, 16.0], [8.0, 0.0, -80.0, 4.0]]),
                             np.array([[0.0, 0.0, 0.0, 16.0], [8.0, 0.0, 0.0, 4.0]])) is False
    found = naming.name_failure(trial, seconds=60)
    assert found is None or "`f` is used" not in found.sentence


def test_a_right_answer_is_not_named():
    trial = _trial("lab07", "", [("rotation_matrix", (30.0,), {})])
    assert naming.name_failure(trial, seconds=60) is None
    assert not trial.sandbox.asked


def test_degrees_used_as_radians_is_named():
    trial = _trial("lab07", "def rotation_matrix(angle_deg, center=(0.0, 0.0)):\n"
                            "    c, s = np.cos(angle_deg), np.sin(angle_deg)\n"
                            "    cx, cy = center\n"
                            "    R = np.array([[c, s], [-s, c]])\n"
                            "    M = np.eye(3)\n    M[:2, :2] = R\n"
                            "    M[:2, 2] = np.array([cx, cy]) - R @ np.array([cx, cy])\n    return M\n",
                   [("rotation_matrix", (30.0,), {"center": (3.0, -2.0)})])
    named = naming.name_failure(trial, seconds=60)
    assert named is not None and named.mutant.operator == "degrees"
    assert "`angle_deg` is used in degrees where radians are needed" in named.sentence


def test_a_hand_written_name_keeps_precedence_in_the_grading(monkeypatch):
    from autograder.engine.checks import Verdict

    lab = LABS["lab07"]
    [degrees] = [m for m in naming.model_for(lab).mutants["rotation_matrix"] if m.operator == "degrees"][:1]
    asked = []
    monkeypatch.setattr(naming, "name_failure", lambda trial: asked.append(1) or naming.Naming(degrees, 1, 1))

    def trial(shared):
        return SimpleNamespace(calls=[("rotation_matrix", (30,), {}, None)], sandbox=SimpleNamespace(shared=shared))

    plain = Verdict(0.0, "rotation_matrix(30) is wrong\nmore")
    named = naming.named_by_error_model(plain, trial({}))
    assert named.mistake == "mutant:degrees" and named.message.endswith("\nmore")
    assert named.message.startswith("rotation_matrix(30) is wrong. The error model: it looks like in "
                                    "`rotation_matrix`, `angle_deg` is used in degrees where radians are needed")
    shared = {}
    by_hand = Verdict(0.0, "wrong: it looks like the translation column is c + R c", mistake="c + R c")
    asked.clear()
    assert naming.named_by_error_model(by_hand, trial(shared)) is by_hand and not asked
    assert naming.named_by_error_model(plain, trial(shared)) is plain and not asked   # later checks too


def test_an_exercise_named_by_hand_takes_back_the_error_models_names():
    from autograder.engine.results import FAILED, CheckResult

    by_hand = CheckResult("a", 0.0, 2.0, FAILED, "scaling_matrix(2, 3) is wrong: it looks like sy is ignored.",
                          mistake="sy is ignored")
    by_model = CheckResult("b", 0.0, 2.0, FAILED, "scaling_matrix(1, 5) is wrong " + naming.APPENDED
                           + "in `scaling_matrix`, `sx` is used where `sy` belongs (other name).\ndetails",
                           mistake="mutant:other_name")
    naming.defer_to_hand_written([by_model, by_hand])
    assert by_model.message == "scaling_matrix(1, 5) is wrong\ndetails" and by_model.mistake == ""
    assert by_hand.mistake == "sy is ignored"
    alone = CheckResult("c", 0.0, 2.0, FAILED, "wrong " + naming.APPENDED + "in `x`, y (sign).", mistake="mutant:sign")
    described = CheckResult("d", 0.0, 2.0, FAILED, "scaling_matrix(1, 5) is wrong in its second row")
    naming.defer_to_hand_written([alone, described])
    assert alone.mistake == "mutant:sign"                # nothing named by hand: it stays


# ------------------------------------------------------------------ in a grading
def _mutant_submission(tmp_path, key, function, operator, words):
    lab = LABS[key]
    model = naming.model_for(lab)
    [mutant] = [m for m in model.mutants[function] if m.operator == operator and words in m.sentence]
    folder = tmp_path / "submission"
    folder.mkdir()
    (folder / f"{lab.module}.py").write_text(apply_edits(model.source, mutant.edits))
    return folder, mutant


def test_a_mutant_submission_fails_and_is_named_with_the_operators_sentence(tmp_path, monkeypatch):
    """The error model's own sentence (the repairs, which would show the change undoing it in its
    place, are off: tests/test_repair.py covers them)."""
    from autograder.engine.mutants import repair
    from autograder.engine.runner import grade

    monkeypatch.setattr(repair, "name_by_repair", lambda trial, seconds=0: None)
    folder, mutant = _mutant_submission(tmp_path, "lab10", "camera_matrix_dlt", "sign", "the first `np.hstack`")
    result = grade(folder, ["lab10.ex4"], pictures="none")
    failed = [c for e in result.exercises for c in e.checks if c.score < c.max_score]
    assert failed
    named = [c for c in failed if c.mistake == "mutant:sign"]
    assert named and all(mutant.sentence in c.message for c in named)
    assert ("The error model: it looks like in `camera_matrix_dlt`, a minus sign is missing in the third item of "
            "the first argument of the first `np.hstack`") in named[0].message


def test_a_correct_submission_is_never_run_through_naming(tmp_path, monkeypatch):
    from autograder.engine.runner import grade

    asked = []
    monkeypatch.setattr(naming, "name_failure", lambda trial, seconds=0: asked.append(trial.check.name))
    result = grade(ROOT / "reference_solutions", ["lab10.ex4"], pictures="none")
    assert all(c.score == c.max_score for e in result.exercises for c in e.checks) and not asked
    folder, _ = _mutant_submission(tmp_path, "lab10", "camera_matrix_dlt", "sign", "the first `np.hstack`")
    result = grade(folder, ["lab10.ex4"], pictures="none")
    failed = {c.name for e in result.exercises for c in e.checks if c.score < c.max_score and not c.failure}
    assert asked and set(asked) <= failed     # failed checks only


# ------------------------------------------------------------------ the helper process
def test_a_mutant_that_loops_forever_is_stopped_and_the_helper_restarts():
    helper = Helper()
    try:
        source = "def spin(n):\n    while n > 0:\n        n += 1\n    return n\n\ndef one(x):\n    return x + 1\n"
        helper.prepare(source, "looping", [("spin", (1,), {}), ("one", (np.arange(3.0),), {})], 5)
        with pytest.raises(HelperFailed):
            helper.run((), [0], 0.5)
        assert helper.kills == 1
        helper.prepare(source, "looping", [("one", (np.arange(3.0),), {})], 5)   # a new helper
        [value] = helper.run((), [0], 5)
        assert np.array_equal(value, [1.0, 2.0, 3.0])
    finally:
        helper.close()


def test_the_helper_answers_errors_as_values_and_never_pickles():
    helper = Helper()
    try:
        source = "def f(x):\n    raise ValueError('no')\n\ndef g(x):\n    return object()\n"
        helper.prepare(source, "errors", [("f", (1,), {}), ("g", (1,), {})], 5)
        first, second = helper.run((), [0, 1], 5)
        assert "ValueError" in first["__error__"] and "__error__" in second   # an object cannot cross
    finally:
        helper.close()


@pytest.mark.parametrize("answer, tells", [
    ("\ud800", False), (2**70, False), ([[[[]]]], False), (float("nan"), False), (np.full((3, 3), 7.0), False),
    (np.array([object()]), False), (np.arange(6.0).reshape(2, 3), True), (np.array(3.0), True),
    ((np.eye(3), np.array([1, 0, 1], bool)), True),
])
def test_answers_that_tell_nothing_are_not_modelled(answer, tells):
    """A reply no mutant of numeric code gives (a string, a huge integer, only NaN, a constant)
    is decided from the answer alone: the helper is not asked, and nothing is named."""
    assert naming._tells_nothing(answer) is not tells


@pytest.mark.parametrize("answer, reference, same", [
    (np.ones((2, 3)), np.ones((3, 2)), True),                     # transposed: a mutant's form
    (np.ones((4, 3)), np.ones((4, 2)), True),                     # not de-homogenised
    ([[1.0, 2.0], [3.0, 4.0]], np.eye(2), False),                 # rows as separate sequences
    (np.array(3.0), np.eye(3), False),                            # a scalar for a matrix
    ({"H": [[1.0]]}, np.eye(3), False),                           # a dict for a matrix
    ((np.eye(3), np.ones(3)), (np.eye(3), np.ones(3)), True),
    ((np.eye(3),), (np.eye(3), np.ones(3)), False),               # a result left out
])
def test_answers_of_another_kind_are_not_modelled(answer, reference, same):
    """No mutant turns a matrix into a scalar or a dict: such answers are not run against them."""
    assert naming._same_kind(answer, reference) is same


# ------------------------------------------------------------------ images: a mutant sharing part of a mistake
UINT8_PYRAMIDS = """
def blend_multiband(img1, img2, mask, levels=4):
    a = np.asarray(img1)
    b = np.asarray(img2)
    weights = _gaussian_pyramid(np.clip(np.asarray(mask, dtype=np.float32), 0, 1), levels)
    bands = []
    for band_a, band_b, w in zip(_laplacian_pyramid(a, levels), _laplacian_pyramid(b, levels), weights):
        if band_a.ndim == 3:
            w = w[..., None]
        bands.append(w * band_a + (1 - w) * band_b)
    result = bands[-1]
    for band in reversed(bands[:-1]):
        result = cv2.pyrUp(result, dstsize=(band.shape[1], band.shape[0])) + band
    return np.clip(np.round(result), 0, 255).astype(np.uint8)
"""

SATURATING_PYRAMIDS = """
def blend_multiband(img1, img2, mask, levels=4):
    weights = _gaussian_pyramid(np.clip(np.asarray(mask, dtype=np.float32), 0, 1), levels)

    def laplacian(image):
        gaussian = _gaussian_pyramid(image, levels)
        return [cv2.subtract(fine, cv2.pyrUp(coarse, dstsize=(fine.shape[1], fine.shape[0])))
                for fine, coarse in zip(gaussian[:-1], gaussian[1:])] + [gaussian[-1]]

    bands = []
    for band_a, band_b, w in zip(laplacian(img1), laplacian(img2), weights):
        w = w[..., None] if band_a.ndim == 3 else w
        bands.append(w * band_a + (1 - w) * band_b)
    result = bands[-1]
    for band in reversed(bands[:-1]):
        result = cv2.pyrUp(result, dstsize=(band.shape[1], band.shape[0])) + band
    return np.clip(np.round(result), 0, 255).astype(np.uint8)
"""


def _blend_itself():
    """lab 8's check "blending an image with itself": img1 is img2 (an exchange changes nothing)."""
    from autograder.labs.lab08 import photo

    image = photo("astronaut", (256, 192))
    ys, xs = np.mgrid[0:192, 0:256]
    return [("blend_multiband", (image, image, np.clip((xs - 80) / 100.0 + 0.2 * np.sin(ys / 15.0), 0, 1)), {})]


def test_pyramids_of_uint8_images_are_named_as_a_missing_float_conversion():
    trial = _trial("lab08", UINT8_PYRAMIDS, _blend_itself())
    named = naming.name_failure(trial, seconds=60)
    assert named is not None and named.mutant.operator == "drop_conversion", named
    assert named.sentence.startswith("in `blend_multiband`, `img1` and `img2` are not converted to float")


def test_a_mutant_sharing_only_part_of_the_mistake_is_not_named(monkeypatch):
    """The false name of the blind set: with img1 is img2, "the unconverted img2 for img1's float
    copy, and img1 for img2's" gives the uint8 student's very image (the exchange shows nothing);
    on confirmation inputs (two images) it is ten times closer than the reference on average, but
    a third of its pixels are not the student's. Without the operator that is the mistake, nothing
    may be named."""
    lab = LABS["lab08"]
    model = naming.model_for(lab)
    fn = next(n for n in ast.parse(model.source).body if isinstance(n, ast.FunctionDef) and n.name == "blend_multiband")
    ordinal = {node.id: k for k, node in enumerate(ast.walk(fn)) if isinstance(node, ast.Name)
               and node.id in ("a", "b") and isinstance(node.ctx, ast.Load)}
    place = "in `blend_multiband`, "
    crossed = [Mutant("other_name", "blend_multiband", "blend_multiband", fn.lineno,
                             (("blend_multiband", ordinal[local], "other_name", raw),),
                             f"{place}`{raw}` is used where `{own}` belongs", place)
               for local, raw, own in (("a", "img2", "img1"), ("b", "img1", "img2"))]
    mutants = [m for m in model.mutants["blend_multiband"] if m.operator != "drop_conversion"] + crossed
    monkeypatch.setattr(naming, "model_for", lambda lab: replace(model, mutants={"blend_multiband": mutants}))
    trial = _trial("lab08", UINT8_PYRAMIDS, _blend_itself())
    pair = crossed[0].combined(crossed[1])
    runner = naming.helper()
    runner.prepare(model.source, model.module, [c[:3] for c in trial.calls], 30)
    [reference], [crossing] = runner.run((), [0], 30), runner.run(pair.edits, [0], 30)
    assert naming.reproduces(crossing, trial.calls[0][3], reference)   # on the failing input, it fits
    assert naming.name_failure(trial, seconds=60) is None
    assert trial.sandbox.asked                                          # the confirmation told it apart


def test_a_student_no_operator_reproduces_in_images_is_not_named():
    """Saturating uint8 arithmetic (cv2.subtract clips the bands at 0): no mutant's, nothing named."""
    trial = _trial("lab08", SATURATING_PYRAMIDS, _blend_itself())
    assert naming.name_failure(trial, seconds=60) is None


# ------------------------------------------------------------------ inputs changed in place
IN_PLACE = ("import numpy as np\n\n\n"
            "def scaled(x, s=2.0):\n    out = x.copy()\n    out *= s\n    return out\n\n\n"
            "def shifted(x, c=1.0):\n    x = x - c\n    return x\n")


@pytest.mark.parametrize("function, student, said", [
    ("scaled", "out = x.copy()", "in `scaled`, `x` is written into in place (the copy of it is missing: the caller's "
                                 "array changes)"),
    ("shifted", "x = x - c", "in `shifted`, `x` is decreased in place (the caller's array changes)"),
])
def test_a_function_changing_its_callers_array_is_told_where(monkeypatch, function, student, said):
    """When a check fails because the caller's array changed (the engine's ChangedInPlace verdict),
    the in-place mutant that gives the student's answer *and* changes the same argument to the same
    values says where; a student whose change is another's (another factor) is told nothing more."""
    from autograder.engine.checks import Verdict
    from autograder.engine.inplace import MISTAKE
    from autograder.engine.mutants.naming import ErrorModel, _numeric_defaults

    model = ErrorModel("inplace", IN_PLACE, mutants_of(IN_PLACE, {"scaled", "shifted"}), _numeric_defaults(IN_PLACE))
    monkeypatch.setattr(naming, "model_for", lambda lab: model)
    assert {m.sentence for m in model.mutants[function] if m.operator == "in_place"} == {said}

    def trial(written):
        module = types.ModuleType("student")
        exec(IN_PLACE.replace(student, written), module.__dict__)  # noqa: S102 - the test's own code
        given = np.arange(6.0).reshape(3, 2)
        held = given.copy()
        answer = getattr(module, function)(held)
        changed = [[0, None, held]] if not np.array_equal(held, given) else []
        return SimpleNamespace(lab=SimpleNamespace(module="inplace", forbidden={}), calls=[(function, (given,), {}, answer)],
                               _last_changed=changed, sandbox=SimpleNamespace(shared={}))

    verdict = Verdict(0.0, f"{function}() writes into the caller's `x` in place: ...\nmore", mistake=MISTAKE)
    same = trial({"scaled": "out = x", "shifted": "x -= c"}[function])
    told = naming.named_by_error_model(verdict, same)
    assert told.mistake == MISTAKE and told.message.endswith("\nmore")
    assert f"{naming.APPENDED}{said} (in place)." in told.message
    other = trial({"scaled": "out = x; out += 0.5", "shifted": "x -= 2 * c"}[function])
    assert naming.named_by_error_model(verdict, other) is verdict


# ------------------------------------------------------------------ centring dropped
NCC_NOT_CENTRED = '''
def _ncc_volume(left, right, max_disparity, block_size):
    height, width = left.shape
    mean_l = _box_mean(left, block_size)
    std_l = np.sqrt(np.maximum(_box_mean(left * left, block_size) - mean_l ** 2, 0.0))
    costs = np.full((max_disparity + 1, height, width), np.inf)
    for d in range(min(max_disparity, width - 1) + 1):
        shifted = _shift_right(right, d)
        mean_r = _box_mean(shifted, block_size)
        std_r = np.sqrt(np.maximum(_box_mean(shifted * shifted, block_size) - mean_r ** 2, 0.0))
        numerator = _box_mean(left * shifted, block_size)
        denominator = std_l * std_r
        ncc = np.divide(numerator, denominator, out=np.zeros_like(numerator), where=denominator > 1e-6)
        costs[d] = -ncc
        costs[d, :, :d] = np.inf
    return costs
'''


def test_an_ncc_without_the_means_subtracted_is_named():
    """The blind set's NCC numerator mean(L R) without - mean(L) mean(R): the operator that drops a
    subtracted mean reaches the NCC cost, which block_matching picks with a conditional expression
    (``(_ssd_volume if ... else _ncc_volume)(...)``: a function named there counts as called)."""
    from fixtures import lab12 as truth

    lab = LABS["lab12"]
    centring = [m for m in naming.model_for(lab).mutants["block_matching"] if m.operator == "drop_centring"]
    assert {m.where for m in centring} == {"_ncc_volume"} and len(centring) == 3
    scene = truth.random_dot_scene(seed=12_016, n_boxes=2)
    left, right = np.array(scene.left)[40:100, :120], np.array(scene.right)[40:100, :120]
    lifted = (np.round(0.4 * right) + 120).astype(np.uint8)   # brightness moves this score, not an NCC
    trial = _trial("lab12", NCC_NOT_CENTRED, [("block_matching", (left, lifted),
                                                dict(max_disparity=scene.max_disparity, block_size=9, cost="ncc"))])
    named = naming.name_failure(trial, seconds=60)
    assert named is not None and named.mutant.operator == "drop_centring", named
    assert "the product of the two means is not subtracted" in named.sentence


def test_a_reshape_in_the_other_order_is_named(tmp_path):
    """A null vector reshaped column by column (order='F') -- numbered by nobody's table for the
    camera matrix -- is a mutant of every reshape, and named where it reproduces."""
    from autograder.engine.runner import grade

    source = "import numpy as np\n\ndef f(v):\n    return v.reshape(3, 4) + np.ravel(v).reshape(3, 4, order='C') * 0\n"
    sentences = {m.sentence for m in mutants_of(source, {"f"})["f"] if m.operator == "reshape_order"}
    assert sentences == {"in `f`, `v` is reshaped column by column (Fortran order) instead of row by row",
                         "in `f`, `v` is flattened column by column (Fortran order) instead of row by row"}
    folder, mutant = _mutant_submission(tmp_path, "lab10", "camera_matrix_dlt", "reshape_order", "reshaped column")
    result = grade(folder, ["lab10.ex4"], pictures="none")
    named = [c for e in result.exercises for c in e.checks if c.mistake == "mutant:reshape_order"]
    # (or, the submission being the reference but for that reshape, its line made the reference's again:
    # a repair takes a mutant's place, the code the student wrote shown)
    repaired = [c for e in result.exercises for c in e.checks if c.mistake == "repair:aligned"
                and "order='F')` to `p.reshape(3, 4)`" in c.message]
    assert (named and mutant.sentence in named[0].message) or repaired


def test_a_name_a_later_check_of_the_function_refutes_is_taken_back_and_a_hidden_one_changes_no_public_word():
    """One account per function: the student's code is the same in every check, so a mutant named on one
    check whose answers another check's failing calls do not reproduce is no name there either."""
    from autograder.engine.mutants.naming import APPENDED, take_back_refuted
    from autograder.engine.results import CheckResult

    sentence = "in `draw_matches`, the width of `img1` is subtracted instead of added"
    told = lambda hidden: CheckResult("c", 0.0, 2.0, "failed", f"draw_matches(...) is wrong. {APPENDED}{sentence} "  # noqa: E731
                                      "(add sub).\nmore", mistake="mutant:add_sub", hidden=hidden)
    public, hidden = told(False), told(True)
    take_back_refuted([public, hidden], [(sentence, True)])   # refuted by a hidden check
    assert APPENDED in public.message and public.mistake and APPENDED not in hidden.message and not hidden.mistake
    take_back_refuted([public], [("another sentence", False)])
    assert APPENDED in public.message
    take_back_refuted([public], [(sentence, False)])
    assert public.message == "draw_matches(...) is wrong.\nmore" and public.mistake == ""


@pytest.mark.parametrize("sentence, operator, payload, makes, can", [
    # a name used in place of a floor's result, read only inside the floor itself in the student's code
    ("in `s`, `f` is used where the result of `np.floor` belongs", "other_name", "f", {"floor"}, False),
    ("in `s`, `width` is used where the result of `np.floor` belongs", "other_name", "width", {"floor"}, True),
    ("in `s`, the arguments of `cv2.remap` are swapped", "swap_args", None, {"remap"}, False),   # never called
    ("in `s`, the result of `np.floor` is used", "sign", None, {"floor"}, True),
    # a call the mutant takes out: the student's code lacks it by that very mistake
    ("in `s`, `np.atleast_2d` is missing", "single_point", None, set(), True),
])
def test_an_error_model_name_is_said_only_of_code_that_can_make_it(monkeypatch, sentence, operator, payload, makes,
                                                                   can):
    """The words of a mutant of the reference are checked against the student's code read with ast: a
    library call they quote that the mutant's code makes is called, and a name they say is used in
    another's place is read somewhere but inside the call that makes the other."""
    import textwrap

    from autograder.engine import hints
    from autograder.engine.mutants import naming
    from autograder.engine.mutants.operators import Mutant

    code = hints.read_code(textwrap.dedent("""
        def s(depth, f, b, width):
            cols = np.floor(np.arange(width)[None, :] - f * b / depth + 0.5).astype(int)
            return cols < width
        """))
    monkeypatch.setattr(hints, "code_of", lambda trial: code)
    monkeypatch.setattr(naming, "_mutant_calls", lambda trial, mutant: makes)
    mutant = Mutant(operator, "s", "s", 3, (("s", 5, operator, payload),), sentence)
    assert naming._code_can(naming.Naming(mutant, 1, 1), types.SimpleNamespace(), {"s"}) == can


# A student's draw_epipolar_lines choosing its end points by `b != 0` answers as the reference with
# `abs(a) >= abs(a)`; a near copy of the reference writes that very test.
_BY_B = """
def draw_epipolar_lines(image, lines):
    canvas = image.copy()
    for a, b, c in lines:
        if b != 0:
            cv2.line(canvas, (0, int(-c / b)), (9, int(-(c + 9 * a) / b)), 255, 1)
    return canvas
"""
_COPIED = """
def draw_epipolar_lines(image, lines):
    canvas = np.array(image, dtype=np.uint8, copy=True)
    for i, (a, b, c) in enumerate(np.asarray(lines, np.float64).reshape(-1, 3)):
        if np.abs(a) >= np.abs(a):
            p, q = (0, int(-c / b)), (9, int(-(c + 9 * a) / b))
            cv2.line(canvas, p, q, 255, 1)
    return canvas
"""


@pytest.mark.parametrize("operator, words, code, said", [
    ("other_name", "the first entry of each item of `lines` is used where the second", _BY_B, False),
    ("other_name", "the first entry of each item of `lines` is used where the second", _COPIED, True),
    # a call is judged by its function and the arguments up to the last edited one
    ("swap_args", "`cv2.line` gets its first and third arguments", _COPIED.replace("(canvas, p, q,", "(q, p, canvas,"),
     True),
    ("swap_args", "`cv2.line` gets its first and third arguments", _COPIED, False),
])
def test_an_error_model_name_is_said_only_of_code_that_writes_the_mutated_expression(monkeypatch, operator, words,
                                                                                     code, said):
    """A mutant's words tell the reference's code: they are said of the student's only when it writes
    the expression the mutant makes, names aside (its own code that answers alike has the mistake
    elsewhere)."""
    from autograder.engine import hints

    lab = LABS["lab11"]
    [mutant] = [m for m in naming.model_for(lab).mutants["draw_epipolar_lines"]
                if m.operator == operator and words in m.sentence][:1]
    read = hints.read_code(code)
    monkeypatch.setattr(hints, "code_of", lambda trial: read)
    trial = SimpleNamespace(lab=lab)
    assert naming._code_can(naming.Naming(mutant, 1, 1), trial, {"draw_epipolar_lines"}) == said


def test_every_mutant_is_read_against_the_students_code_whatever_its_payload():
    # (06i: an `axis` mutant's payload holds a list; reading it as a cache key raised, and its check's naming was
    # lost to a grader error)
    labs = discover()
    for key in ("lab08", "lab11"):
        model = naming.model_for(labs[key])
        listed = [m for mutants in model.mutants.values() for m in mutants
                  if any(isinstance(part, list) for edit in m.edits for part in edit)]
        assert listed, key
        trial = SimpleNamespace(lab=labs[key])
        for mutant in listed[:5]:
            written = ast.parse(apply_edits(model.source, mutant.edits))   # the mutant's own code writes it
            fn = next(n for n in written.body if isinstance(n, ast.FunctionDef) and n.name == mutant.where)
            assert naming._written_alike(mutant, trial, [fn]) is True, mutant.sentence


COLUMNS_SCALED = '''
def triangulate(P1, P2, pts1, pts2):
    P1, P2 = np.asarray(P1, dtype=float), np.asarray(P2, dtype=float)
    pts1 = np.asarray(pts1, dtype=float)
    single = pts1.ndim == 1
    pts1, pts2 = pts1.reshape(-1, 2), np.asarray(pts2, dtype=float).reshape(-1, 2)
    result = np.zeros((len(pts1), 3))
    for i in range(len(pts1)):
        x, y = pts1[i]
        xp, yp = pts2[i]
        A = np.vstack([x * P1[2] - P1[0], y * P1[2] - P1[1], xp * P2[2] - P2[0], yp * P2[2] - P2[1]])
        A = A / np.linalg.norm(A, axis=0)
        X = np.linalg.svd(A)[2][-1]
        result[i] = X[:3] / X[3]
    return result[0] if single else result
'''


def test_an_axis_the_error_model_names_is_said_only_of_code_that_passes_that_axis(tmp_path):
    """The reference balances the rows of its (N, 4, 4) systems with `norm(A, axis=2, keepdims=True)`; its mutant
    `axis=1` reproduces a per-point loop that divides each 4 x 4 A by `norm(A, axis=0)` (its columns' norms).
    "runs over axis 1 where axis 2 belongs" is false of that code: a keyword's value is judged with its call."""
    from autograder.engine.runner import grade
    from conftest import check_results, mutant

    result = grade(str(mutant(tmp_path, "lab12_stereo", COLUMNS_SCALED)), ["lab12.ex1"])
    failed = [c for c in check_results(result, "lab12.ex1") if c.score < c.max_score]
    assert failed and not any("axis 1 where axis 2" in c.message for c in failed), [c.message for c in failed]
