"""A failure inherited from another of the student's functions is told as such, and no hint
describes a function that is right (issue 35; :mod:`autograder.engine.inherited`).

The buggy modules are the reference with one function redefined (the labs' mistake tables'
sources where they exist): the caller is the reference's, right; the callee is wrong.
"""

from __future__ import annotations

import re
import textwrap
import types
from pathlib import Path

import numpy as np
import pytest

from autograder.engine import inherited
from autograder.engine.hints import Hint, read_code
from autograder.engine.registry import discover
from autograder.engine.stubs import _mentions, functions_called
from autograder.labs.mistakes import lab08 as mistakes08, lab12 as mistakes12
from conftest import graded_case

ROOT = Path(__file__).resolve().parents[1]
LABS = discover()
ITSELF_RIGHT = "itself is right here"
SIMULATE = "simulate_structured_light matches the projector model"
SIMULATE_RECIPE = "sees projector column round(u - f*baseline/Z)"


def _api(lab) -> frozenset[str]:
    return frozenset(name for exercise in lab.exercises.values() for name in exercise.signatures)


def _reference_code(lab):
    return read_code((ROOT / "reference_solutions" / f"{lab.module}.py").read_text())


def _check(result, exercise_id: str, name: str):
    [found] = [c for e in result.exercises if e.id == exercise_id for c in e.checks if c.name == name]
    return found


# ------------------------------------------------------------------ reading which functions are called
def test_api_callees_follow_aliases_module_attributes_nested_functions_and_private_helpers():
    code = read_code(textwrap.dedent("""
        import numpy as np
        import lab12_stereo as me
        from lab12_stereo import depth_from_disparity as to_depth
        patterns_of = gray_code_patterns

        def gray_code_patterns(width, n_bits):
            return np.zeros((n_bits, width), np.uint8)

        def _lit(width, n_bits):
            return patterns_of(width, n_bits)

        def simulate_structured_light(depth, f, baseline, n_bits):
            def inner():
                return _lit(depth.shape[1], n_bits)
            return inner()

        def depth_from_structured_light(images, f, baseline):
            return to_depth(np.gradient(images), f, baseline) + me.block_matching(images, images)

        def depth_from_disparity(disparity, f, baseline):
            return f * baseline / disparity

        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return np.gradient(left) + depth_from_disparity(left, 1, 1)
        """))
    api = {"gray_code_patterns", "simulate_structured_light", "depth_from_structured_light", "depth_from_disparity",
           "block_matching", "gradient"}
    assert inherited.api_callees(code, "simulate_structured_light", api) == {"gray_code_patterns"}
    # an API callee's own callees are its own (block_matching's depth_from_disparity is not followed);
    # np.gradient is numpy's, not a function of the module
    assert inherited.api_callees(code, "depth_from_structured_light", api) == {"depth_from_disparity",
                                                                               "block_matching"}
    assert inherited.api_callees(code, "gray_code_patterns", api) == set()


def test_the_references_callers_are_found_in_every_lab_that_has_them():
    callers = {key: {f: inherited.api_callees(_reference_code(lab), f, _api(lab)) for f in _api(lab)}
               for key, lab in LABS.items()}
    assert callers["lab12"]["simulate_structured_light"] == {"gray_code_patterns"}
    assert callers["lab11"]["two_view_reconstruction"] == {"essential_from_fundamental", "triangulate"}
    # through _pairwise_homography and _compose
    assert callers["lab08"]["stitch"] == {"homography_ransac", "transform_points", "apply_homography"}
    assert callers["lab07"]["rotate"] == {"rotation_matrix"}
    assert callers["lab10"]["track_pose"] == {"estimate_pose"}


# ------------------------------------------------------------------ comparing answers
def test_same_answer_holds_images_to_a_pixel_in_a_thousand_and_numbers_to_float32_precision():
    image = np.random.default_rng(0).integers(0, 256, (100, 100), dtype=np.uint8)
    one_off = image.copy()
    one_off[0, 0] ^= 0x80
    assert inherited.same_answer(one_off, image)                   # 1 pixel in 10^4
    many_off = image.copy()
    many_off[:2] ^= 0x80
    assert not inherited.same_answer(many_off, image)              # 2% of the pixels
    x = np.array([[1000.0, 2.0], [np.nan, 4.0]])
    assert inherited.same_answer(x * (1 + 1e-9), x)
    assert not inherited.same_answer(x * (1 + 1e-4), x)            # a real difference
    assert not inherited.same_answer(np.nan_to_num(x), x)          # NaN in other places
    assert not inherited.same_answer((x, x), [x])                  # another structure
    assert inherited.same_answer((x.astype(np.float32), 3), [x, 3.0])
    assert not inherited.same_answer([None, x[0]], [x[0], None])   # an array where another kind of value is


def test_calls_are_shown_as_the_student_writes_them():
    signature = "triangulate(P1, P2, pts1, pts2)"
    assert inherited.shown_call("gray_code_patterns(width, n_bits)", (160, 6), {}) == "gray_code_patterns(160, 6)"
    assert inherited.shown_call(signature, (np.eye(3, 4), np.eye(3, 4), np.zeros((9, 2)), np.zeros((9, 2))), {}) \
        == "triangulate(P1, P2, pts1, pts2) with arrays of shapes (3, 4), (3, 4), (9, 2), (9, 2)"
    assert inherited.shown_call("rotation_matrix(angle_deg, center=(0.0, 0.0))", (45, (199.5, 149.5)), {}) \
        == "rotation_matrix(45, (199.5, 149.5))"


# ------------------------------------------------------------------ lab 12: the patterns wrong, the simulation right
@pytest.mark.xdist_group("lab12")
@pytest.mark.parametrize("case", ["plain binary patterns", "patterns least significant bit first"])
def test_a_right_simulation_of_wrong_patterns_is_told_inherited(case):
    exercise, source, fragments = mistakes12.MISTAKES[case]
    result = graded_case("lab12_stereo", exercise, source)
    simulate = _check(result, exercise, SIMULATE)
    assert simulate.score == 0                      # the contract judges the images: the points stay lost
    assert simulate.message.startswith(f"Your `simulate_structured_light` {ITSELF_RIGHT}"), simulate.message
    assert "`gray_code_patterns` is wrong there (see its own checks)" in simulate.message
    assert "(gray_code_patterns(160, 6))" in simulate.message   # the call the check's own input makes
    # no recipe, no mistake of the simulation: it does all that already
    assert simulate.hint == "" and simulate.mistake == ""
    assert SIMULATE_RECIPE not in simulate.message and "looks like" not in simulate.message
    # the patterns' own checks still name the mistake
    patterns = [c for e in result.exercises for c in e.checks if c.name.startswith("gray_code_patterns")]
    assert patterns and all(c.score == 0 and fragments[0] in c.message for c in patterns)
    assert_every_hint_about_a_function_exercised(result)


@pytest.mark.xdist_group("lab12")
def test_a_wrong_simulation_with_right_patterns_keeps_its_own_diagnosis():
    exercise, source, fragments = mistakes12.MISTAKES["projector on the wrong side"]
    result = graded_case("lab12_stereo", exercise, source)
    simulate = _check(result, exercise, SIMULATE)
    assert simulate.score == 0 and fragments[0] in simulate.message.lower() and simulate.mistake
    assert ITSELF_RIGHT not in simulate.message and "fails its own checks" not in simulate.message


WRONG_SIDE = mistakes12.MISTAKES["projector on the wrong side"][1]
BINARY = mistakes12.MISTAKES["plain binary patterns"][1]


@pytest.mark.xdist_group("lab12")
def test_a_wrong_simulation_of_wrong_patterns_is_not_told_right_but_told_what_it_depends_on():
    result = graded_case("lab12_stereo", "lab12.ex6", BINARY + WRONG_SIDE)
    simulate = _check(result, "lab12.ex6", SIMULATE)
    assert simulate.score == 0 and ITSELF_RIGHT not in simulate.message
    assert ("Your `simulate_structured_light` calls your `gray_code_patterns`, which fails its own checks in this "
            "grading: fix it first, then see what this check says.") in simulate.message


@pytest.mark.xdist_group("lab12")
def test_without_the_reference_the_dependency_is_told_from_the_code(tmp_path, monkeypatch):
    """The static fallback (no reference in this copy of the grader): the callee failed its own checks."""
    from autograder.engine.runner import grade
    from conftest import mutant

    monkeypatch.setattr(inherited, "reference_of", lambda lab: None)
    result = grade(mutant(tmp_path, "lab12_stereo", BINARY), ["lab12.ex6"], pictures="none")
    simulate = _check(result, "lab12.ex6", SIMULATE)
    assert simulate.score == 0 and ITSELF_RIGHT not in simulate.message
    assert "calls your `gray_code_patterns`, which fails its own checks in this grading" in simulate.message


# ------------------------------------------------------------------ lab 8: a pipeline calling a wrong RANSAC
@pytest.mark.xdist_group("lab08")
def test_a_right_panorama_from_a_wrong_ransac_is_told_inherited():
    _, source, _ = mistakes08.MISTAKES["RANSAC fits all points"]
    result = graded_case("lab08_homographies", "lab08.ex5", source)
    failed = [c for e in result.exercises for c in e.checks if c.score < c.max_score]
    assert failed
    for check in failed:
        assert check.message.startswith(f"Your `stitch` {ITSELF_RIGHT}: given what your `homography_ransac` "
                                        "returns (homography_ransac(src, dst, threshold=3, seed=0)"), check.message
        assert check.hint == "" and check.mistake == ""
    assert_every_hint_about_a_function_exercised(result)


# ------------------------------------------------------------------ every lab: hints are about what is exercised
def _callees(lab, functions) -> set[str]:
    """The API functions the reference's ``functions`` call, directly or not."""
    code, api = _reference_code(lab), _api(lab)
    return {f.name for f in code.reachable(functions)} & api


def _mentioned(text: str, api) -> set[str]:
    """The API functions ``text`` names as code: `name` or name(...)."""
    return {name for name in api if re.search(rf"(`{name}`|\b{name}\()", text)}


def assert_every_hint_about_a_function_exercised(result):
    """Every failed check's message, hint and mistake name only functions the check exercises, or
    functions those call (the reference's callees: an inherited failure names its callee)."""
    for exercise in result.exercises:
        lab = LABS[exercise.id.split(".")[0]]
        checks = {c.name: c for c in lab.exercises[exercise.id.split(".")[1]].checks}
        for check in exercise.checks:
            if check.passed or check.name not in checks:
                continue   # (the engine's own advice)
            called = functions_called(checks[check.name])
            allowed = called | _callees(lab, called)
            for field in ("message", "hint", "mistake"):
                stray = _mentioned(getattr(check, field), _api(lab)) - allowed
                assert not stray, f"{exercise.id} {check.name!r}: its {field} is about {stray}: {getattr(check, field)}"


def _feedback(function) -> set[str]:
    """The strings a check's code (and the package's helpers it uses) can say: constants other than
    docstrings, and the module-level strings, Hints and tables of strings the labs' and fixtures'
    code names."""
    said, seen, todo = set(), set(), [function]
    while todo:
        func = todo.pop()
        if func in seen:
            continue
        seen.add(func)
        codes = [func.__code__]
        while codes:
            code = codes.pop()
            doc = code.co_consts[0] if code.co_consts and isinstance(code.co_consts[0], str) else None
            for constant in code.co_consts:
                if isinstance(constant, str) and constant is not doc:
                    said.add(constant)
                elif isinstance(constant, types.CodeType):
                    codes.append(constant)
            if func is not function and not func.__module__.startswith(("autograder.labs", "fixtures")):
                continue   # an engine function's module-level values are its registries, not feedback
            for name in code.co_names:
                value = func.__globals__.get(name)
                if isinstance(value, str):
                    said.add(value)
                elif isinstance(value, Hint):
                    said.update({value.text, value.instead or ""})
                elif isinstance(value, (dict, tuple, list, frozenset)):
                    said.update(v for v in (list(value) + list(value.values() if isinstance(value, dict) else []))
                                if isinstance(v, str))
        todo += _mentions(func)[1]
    return said


def stray_sentences(check) -> list[str]:
    """The feedback ``check``'s code can give (:func:`_feedback`) that names, as code, an API function
    the check neither calls nor reaches through the reference's callees."""
    lab = check.exercise.lab
    api = _api(lab)
    called = functions_called(check)
    allowed = called | _callees(lab, called)
    return [f"{check.id}: {sorted(_mentioned(text, api) - allowed)} in {text[:120]!r}"
            for text in sorted(_feedback(check.func)) if text not in api and _mentioned(text, api) - allowed]


@pytest.mark.parametrize("key", sorted(LABS))
def test_no_check_can_say_a_sentence_about_a_function_it_does_not_exercise(key):
    """Read statically, over every check of every lab (public and hidden): the feedback a check's code
    can give names, as code (`name` or name(...)), only the functions it calls or those they call."""
    problems = [problem for exercise in LABS[key].exercises.values() for check in exercise.checks
                for problem in stray_sentences(check)]
    assert not problems, "\n".join(problems)


STRAY_HINT = Hint("the disparities come from `block_matching`: check it first", asks=None)


def test_a_check_with_a_hint_about_another_function_is_found():
    """The reading above finds a hint about a function the check does not exercise (in a string, a
    Hint named at module level), and not one about a callee."""
    from dataclasses import replace

    check = next(c for c in LABS["lab12"].exercises["ex6"].checks if c.name == SIMULATE)

    def stray(t):
        t.call("simulate_structured_light", None)
        t.fail("wrong", hint=STRAY_HINT.said(t) + " and rectify(...) your images")

    def about_a_callee(t):
        t.call("simulate_structured_light", None)
        t.fail("wrong", hint="your `gray_code_patterns` is called with the image's width")

    problems = stray_sentences(replace(check, func=stray))
    assert len(problems) == 2 and any("['rectify']" in p for p in problems) \
        and any("['block_matching']" in p for p in problems)
    assert stray_sentences(replace(check, func=about_a_callee)) == []
    assert stray_sentences(replace(check, func=lambda t: t.fail("`gray_code_patterns` is wrong"))) != []


# A wrong callee of each lab (the caller the reference's): the caller's checks are told inherited and
# no failed check names a function it does not exercise.
CHAINS = {
    "lab07": ("lab07_transformations", "lab07.ex2", "rotate", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
            c = np.asarray(center, dtype=np.float64)
            M = np.eye(3)
            M[:2, :2] = R
            M[:2, 2] = c - R @ c
            return M
        """),
    "lab08": ("lab08_homographies", "lab08.ex5", "stitch", mistakes08.MISTAKES["RANSAC fits all points"][1]),
    "lab09": ("lab09_camera", "lab09.ex4", "project_focal_lengths", """
        def pinhole_project(points, f):
            X = np.asarray(points, float)
            out = np.column_stack([f * X.reshape(-1, 3)[:, 1], f * X.reshape(-1, 3)[:, 0]]) / X.reshape(-1, 3)[:, 2:]
            return out[0] if X.ndim == 1 else out
        """),
    "lab10": ("lab10_camera2", "lab10.ext2", "dolly_zoom", """
        def perspective_project(points, f):
            X = np.asarray(points, float)
            out = f * X.reshape(-1, 3)[:, :2] / X.reshape(-1, 3)[:, 2:] + 1.0
            return out[0] if X.ndim == 1 else out
        """),
    "lab11": ("lab11_two_view", "lab11.ex6", "two_view_reconstruction", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[1]], axis=1)
            return np.linalg.svd(A)[2][:, -1, :3]
        """),
    "lab12": ("lab12_stereo", "lab12.ex6", "simulate_structured_light", BINARY),
}


@pytest.mark.parametrize("key", sorted(CHAINS))
def test_in_every_lab_a_right_caller_of_a_wrong_function_is_told_inherited(key):
    module, exercise, caller, source = CHAINS[key]
    result = graded_case(module, exercise, source)
    told = [c for e in result.exercises for c in e.checks if c.message.startswith(f"Your `{caller}` {ITSELF_RIGHT}")]
    assert told, [(c.name, c.message) for e in result.exercises for c in e.checks if not c.passed]
    assert all(c.hint == "" and c.mistake == "" and c.score < c.max_score for c in told)
    assert_every_hint_about_a_function_exercised(result)


# ------------------------------------------------------------------ a private helper two API functions share
@pytest.mark.xdist_group("lab08")
def test_a_caller_sharing_a_private_helper_with_a_failing_function_is_told_so(tmp_path):
    """`stitch` and `match_features` both detect with the private `_detect`: keypoints sorted after their
    positions were taken pair each position with another keypoint's descriptor. `match_features` fails its
    own checks; stitch's failures say that they share `_detect` (no API callee of stitch failed)."""
    from autograder.engine.runner import grade
    from conftest import check_results, edited_reference

    edit = ("keypoints, descriptors = detector.detectAndCompute(_grey(image), None)",
            "keypoints, descriptors = detector.detectAndCompute(_grey(image), None)\n"
            "    keypoints = sorted(keypoints, key=lambda k: -k.response)")
    folder = edited_reference(tmp_path, "lab08_homographies", edit)
    result = grade(folder, ["lab08.ex3", "lab08.ex5"], pictures="none")
    matching = [c for c in check_results(result, "lab08.ex3") if c.score < c.max_score]
    stitching = [c for c in check_results(result, "lab08.ex5") if c.score < c.max_score]
    assert matching and stitching
    for check in stitching:
        assert ("Your `stitch` goes through your `_detect`" in check.message
                and "which your `match_features` uses too, and it fails its own checks" in check.message), check.message


def test_private_helpers_stop_at_api_functions():
    from autograder.engine.hints import read_code

    code = read_code("""
def _grey(x):
    return x
def _detect(x):
    return _grey(x)
def match_features(a, b):
    return _detect(a), _detect(b)
def stitch(a, b):
    match_features(a, b)
    return _compose(a)
def _compose(a):
    return a
""")
    assert inherited.private_helpers(code, "stitch", {"stitch", "match_features"}) == {"_compose"}
    assert inherited.private_helpers(code, "match_features", {"stitch", "match_features"}) == {"_detect", "_grey"}


def test_a_function_right_itself_is_no_evidence_against_the_helpers_it_shares(tmp_path):
    """`rotate` told right itself on a check (its `rotation_matrix` wrong there; its own slip, whole degrees, fails
    another) and `warp_affine` ignoring dsize,
    both through the private `_warp`: warp_affine's failure was told "a mistake in `_warp` would fail this check as
    well" because rotate failed other checks (third-party round of 2026-12-07) -- a false lead. A function told right
    itself is not counted as failing for the helpers it shares."""
    from autograder.engine.runner import grade
    from conftest import check_results, mutant

    folder = mutant(tmp_path, "lab07_transformations", """
        def _turn(angle_deg):
            theta = np.deg2rad(angle_deg)
            return np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])

        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            R, c = _turn(angle_deg), np.asarray(center, dtype=np.float64)
            M = np.eye(3)
            M[:2, :2], M[:2, 2] = R, c - R @ c
            return M

        def rotate(image, angle_deg=45):
            height, width = image.shape[:2]
            centre = np.array([(width - 1) / 2.0, (height - 1) / 2.0])
            return _warp(image, rotation_matrix(round(angle_deg), centre))   # (a slip of its own: whole degrees)

        def warp_affine(image, A, dsize=None):
            return _warp(image, A)
        """)
    result = grade(folder, ["lab07.ex2", "lab07.ex5"], pictures="none", include_hidden=False)
    rotating = [c for c in check_results(result, "lab07.ex2") if c.score < c.max_score]
    warping = [c for c in check_results(result, "lab07.ex5") if c.score < c.max_score]
    assert any(c.message.startswith(f"Your `rotate` {ITSELF_RIGHT}") for c in rotating), [c.message for c in rotating]
    assert any(not c.message.startswith(f"Your `rotate` {ITSELF_RIGHT}") for c in rotating if c.name.startswith("rotate"))
    assert warping and not any("which your `rotate` uses too" in c.message for c in warping), [c.message for c in warping]


def test_a_check_judging_a_function_and_the_graded_function_it_calls_says_when_that_one_fails_its_own(tmp_path):
    """The RANSAC check over five seeds judges homography_ransac and the student's own homography_dlt (which it
    calls); with a wrong row in the DLT helper, its recipe hint ("look at how many samples ...") sent the student
    into a RANSAC that is right (07d lab08/02). It now says homography_dlt fails its own checks, as the others do."""
    from autograder.engine.runner import grade
    from conftest import check_results, edited_reference

    folder = edited_reference(tmp_path, "lab08_homographies", ("-v * x, -v * y, -v]", "-v * x, -v * y, -u]"))
    result = grade(str(folder), ["lab08.ex2", "lab08.ex4"])
    seeds = [c for c in check_results(result, "lab08.ex4") if "5 seeds" in c.name]
    assert seeds and seeds[0].score < seeds[0].max_score
    assert "Your `homography_ransac` calls your `homography_dlt`, which fails its own checks" in seeds[0].message


def test_a_check_waiting_for_a_failing_callee_keeps_no_recipe_hint_of_its_own(tmp_path):
    """RANSAC, the reference's, fitting with a DLT whose v rows end in -u (blind set 08a lab08/02): its checks say
    "fix it first, then see what this check says", so no recipe hint about RANSAC's own steps beside it."""
    from autograder.engine.runner import grade
    from conftest import edited_reference

    folder = edited_reference(tmp_path, "lab08_homographies", ("-v * x, -v * y, -v]", "-v * x, -v * y, -u]"))
    result = grade(str(folder), ["lab08.ex2", "lab08.ex4"], pictures="none")
    waiting = [c for e in result.exercises for c in e.checks
               if c.score < c.max_score and "fix it first, then see what this check says" in c.message]
    assert waiting and all(c.hint == "" for c in waiting if not c.mistake), [(c.name, c.hint) for c in waiting]
