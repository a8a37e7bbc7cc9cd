"""Hints never contradict the student's code (autograder/engine/hints.py).

The predicates read what is written (``ast``, never run); a hint whose predicate holds on the
functions a check calls says its neutral sentence instead. Graded cases: the third-party
mistakes of issue 35, each told to do what its code already does before the change.
"""

import ast
import textwrap

import pytest

from autograder.engine.hints import (NAN_WHERE, RATIO_TEST, TO_UINT8, Hint, calls, expr, fits_on_picked_points, keyword,
                                     matmul_of, mentions, passes_product, read_code, uses_attr)
from autograder.engine.runner import grade
from autograder.labs.lab08 import SECOND_WARP_HINT
from autograder.labs.lab11 import EIGHT_POINTS_HINT, IN_FRONT_HINT
from autograder.labs.lab12 import NCC_HINT
from conftest import check_results, edited_reference, mutant


def found(predicate, source: str, function: str = "f") -> str:
    return predicate.found(read_code(textwrap.dedent(source)).reachable([function]))


def test_calls_match_any_module_prefix_and_methods_only_when_asked():
    source = """
        def f(a):
            return np.argmax(a, axis=0), cv.recoverPose(a)
        """
    assert found(calls("np.argmax"), source) == "calls np.argmax"
    assert found(calls("cv2.recoverPose"), source) == "calls cv2.recoverPose"   # imported as cv
    assert found(calls(".argmax"), "def f(a):\n    return argmax(a)\n") == ""        # imported: no attribute
    assert found(calls(".argmax"), "def f(a):\n    return a.argmax(0)\n") == "calls argmax"
    assert found(calls("np.argmax"), "def f(a):\n    return a.argmax(0)\n") == "calls np.argmax"
    assert found(calls("np.argmin"), source) == ""


def test_a_helper_the_function_calls_is_read_too_and_the_last_definition_wins():
    source = """
        def helper(a):
            return np.argmax(a)
        def f(a):
            return helper(a)
        def g(a):
            return np.argmax(a)
        def g(a):
            return np.argmin(a)
        """
    assert found(calls("np.argmax"), source) == "calls np.argmax"
    assert found(calls("np.argmax"), source, "g") == ""
    assert found(calls("np.argmax"), source, "missing") == ""


def test_a_refit_is_read_from_points_a_mask_picks_not_from_how_many_fits_there_are():
    refits = fits_on_picked_points("homography_dlt")
    # a fit per random sample and a fallback on every point: two calls, no refit
    assert found(refits, """
        def f(src, dst, rng, n):
            for _ in range(100):
                idx = rng.permutation(n)
                sample = idx[:4]
                H = homography_dlt(src[sample], dst[sample])
            if n < 8:
                return homography_dlt(src, dst)
            return H
        """) == ""
    assert found(refits, """
        def f(src, dst, best_inliers):
            inliers = best_inliers
            return homography_dlt(src[inliers], dst[inliers])
        """) == "fits homography_dlt again on the points a mask picks"
    assert found(refits, "def f(src, dst, H):\n    return homography_dlt(src[errors(H) < 3], dst[errors(H) < 3])\n") != ""
    assert found(refits, """
        def f(src, dst, rng):
            samples = np.array([rng.choice(len(src), 4, replace=False) for _ in range(100)])
            for idx in samples:
                H = homography_dlt(src[idx], dst[idx])
            return H
        """) == ""   # (a loop over drawn samples: each is a draw)
    # (a mask kept as the best so far and refined after the loop is no draw, though measured from one: 07e lab08/06)
    assert found(refits, """
        def f(src, dst, rng, threshold):
            best_inliers = None
            for _ in range(100):
                sample = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[sample], dst[sample])
                inliers = errors(H, src, dst) < threshold
                best_inliers = inliers
            mask = best_inliers
            return homography_dlt(src[mask], dst[mask])
        """) == "fits homography_dlt again on the points a mask picks"


def test_products_expressions_keywords_and_attributes():
    source = """
        def f(img2, H, max_disparity):
            T = np.eye(3)
            M = T.dot(H)
            out = cv2.warpPerspective(img2, M, (10, 10))
            d = range(max_disparity + 1)
            u, s, vt = np.linalg.svd(H, full_matrices=False)
            return out.T, np.where(H > 0, H, np.nan)
        """
    assert found(matmul_of("T", "H"), source) == "computes T @ H"
    assert found(matmul_of("H", "T"), source) == ""
    assert found(passes_product("cv2.warpPerspective", 1), source) == "passes a matrix product to cv2.warpPerspective"
    assert found(expr("max_disparity + 1"), source) == "computes max_disparity + 1"
    assert found(expr("_ - 1"), source) == ""
    assert found(keyword("np.linalg.svd", "full_matrices", False), source)
    assert not found(keyword("np.linalg.svd", "full_matrices", True), source)
    assert found(uses_attr(".T"), source) and found(mentions("np.nan"), source) and found(NAN_WHERE, source)


def test_and_holds_across_the_functions_read_together_or_says_the_alternative_found():
    source = """
        def f(kp1, des1, des2):
            good = [m for m, n in matches(des1, des2) if m.distance < 0.75 * n.distance]
            return estimate(good)
        def estimate(good):
            return cv2.findFundamentalMat(good, good, cv2.FM_RANSAC)
        def matches(a, b):
            return cv2.BFMatcher().knnMatch(a, b, k=2)
        """
    ransac = calls("cv2.findFundamentalMat") | calls("cv2.findEssentialMat")
    assert found(ransac, source) == "calls cv2.findFundamentalMat"
    assert found(RATIO_TEST & ransac, source)
    assert not found(RATIO_TEST & ransac, source, "estimate")
    assert found(~calls("np.argmax"), source)
    assert found(TO_UINT8, "def f(x):\n    return np.clip(x, 0, 255).astype(np.uint8)\n") == "converts to uint8"


def test_code_that_cannot_be_read_keeps_every_hint():
    assert read_code("def f(:\n").functions == {}
    hint = Hint("keep the highest", asks=calls("np.argmax"))
    assert not hint.contradicts(read_code("def f(:\n"), ["f"])
    assert hint.contradicts(read_code("def f(a):\n    return a.argmax()\n"), ["f"]) == "calls np.argmax"
    assert hint.neutral("calls np.argmax") == "your code already calls np.argmax; the error is elsewhere"


@pytest.mark.parametrize("source, contradicted", [
    ("def fundamental_8point(p1, p2):\n    return np.linalg.svd(A)[2][-1].reshape(3, 3)\n", True),
    ("def fundamental_8point(p1, p2):\n    return np.linalg.svd(A, full_matrices=False)[2][-1]\n", False),
])
def test_the_eight_point_hint_is_kept_only_for_a_reduced_svd(source, contradicted):
    assert bool(EIGHT_POINTS_HINT.contradicts(read_code(source), ["fundamental_8point"])) == contradicted


@pytest.fixture
def no_repairs(monkeypatch):
    """The fixed hints themselves: a repair of the student's code found for the failure would take
    the hint's place (tests/test_repair.py)."""
    from autograder.engine.mutants import repair

    monkeypatch.setattr(repair, "name_by_repair", lambda trial, seconds=0: None)


NCC_ARGMAX_OFF_BY_TWO = """
    _bm_ref = block_matching
    def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
        if cost != "ncc":
            return _bm_ref(left, right, max_disparity, block_size, cost)
        score = -_ncc_volume(_grey_float(left), _grey_float(right), int(max_disparity), int(block_size))
        return np.maximum(np.{pick}({sign}score, axis=0) - 2, 0).astype(np.float64)
    """


def test_an_ncc_matcher_keeping_the_highest_score_is_not_told_to_keep_it(tmp_path, no_repairs):
    result = grade(mutant(tmp_path, "lab12_stereo", NCC_ARGMAX_OFF_BY_TWO.format(pick="argmax", sign="")),
                   ["lab12.ext1"], pictures="none")
    hints = [c.hint for c in check_results(result, "lab12.ext1") if not c.passed and c.hint]
    assert hints and all("HIGHEST" not in h and "keeps the highest score (argmax" in h for h in hints)
    assert NCC_HINT.text.startswith(hints[0].split(";")[0])     # the formula is still said


def test_the_argmin_of_the_score_negated_is_keeping_the_highest_too(tmp_path, no_repairs):
    """``score`` holds +NCC (the reference's helper returns -NCC, negated again): the argmin of
    ``-score`` keeps the highest NCC, as an argmax does."""
    result = grade(mutant(tmp_path / "negated", "lab12_stereo", NCC_ARGMAX_OFF_BY_TWO.format(pick="argmin", sign="-")),
                   ["lab12.ext1"], pictures="none")
    hints = [c.hint for c in check_results(result, "lab12.ext1") if not c.passed and c.hint]
    assert hints and all("HIGHEST" not in h and "keeps the highest score (argmax" in h for h in hints)


def test_a_matcher_keeping_the_lowest_ncc_keeps_the_hint(tmp_path, no_repairs):
    """The control: the argmin of ``score`` (+NCC after the helper's negation is undone) keeps the
    lowest NCC, so the hint to keep the highest is what the code needs."""
    result = grade(mutant(tmp_path / "control", "lab12_stereo", NCC_ARGMAX_OFF_BY_TWO.format(pick="argmin", sign="")),
                   ["lab12.ext1"], pictures="none")
    hints = [c.hint for c in check_results(result, "lab12.ext1") if not c.passed and c.hint]
    assert hints and all(h == NCC_HINT.text for h in hints)


def test_cameras_without_k_are_not_told_to_use_recover_pose_which_they_do(tmp_path):
    source = """
        _reference = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, _ = _reference(img1, img2, K)
            E = essential_from_fundamental(F, K, K)
            _, R, t, _ = cv2.recoverPose(E, pts1, pts2, np.asarray(K, float))
            P1 = np.hstack([np.eye(3), np.zeros((3, 1))])       # without K, used on pixels
            P2 = np.hstack([R, t.reshape(3, 1)])
            return F, pts1, pts2, triangulate(P1, P2, pts1, pts2)
        """
    result = grade(mutant(tmp_path, "lab11_two_view", source), ["lab11.ex6"], pictures="none")
    [structure] = [c for c in check_results(result, "lab11.ex6") if c.name.startswith("two_view_reconstruction: the 3D")]
    assert not structure.passed
    assert IN_FRONT_HINT.text not in structure.message
    # named now (issue 35: the points are those of [I | 0], [R | t] on pixels with the pipeline's own pose)
    assert "the cameras are built without K" in structure.message and structure.mistake


def test_a_half_bright_strip_is_not_told_to_warp_with_t_at_h_which_it_does(tmp_path):
    source = """
        def stitch(img1, img2):
            H = _pairwise_homography(img2, img1)
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            corners = cv2.perspectiveTransform(np.float32([[0, 0], [w2, 0], [w2, h2], [0, h2]]).reshape(-1, 1, 2), H)
            every = np.vstack([corners.reshape(-1, 2), [[0, 0], [w1, 0], [w1, h1], [0, h1]]])
            xmin, ymin = np.floor(every.min(axis=0)).astype(int)
            xmax, ymax = np.ceil(every.max(axis=0)).astype(int)
            T = np.array([[1, 0, -xmin], [0, 1, -ymin], [0, 0, 1]], float)
            size = (int(xmax - xmin), int(ymax - ymin))
            second = cv2.warpPerspective(img2, T @ H, size)
            first = cv2.warpPerspective(img1, T, size)
            out = first.copy()
            out[second > 0] = ((first[second > 0].astype(float) + second[second > 0]) / 2).astype(np.uint8)
            return out
        """
    result = grade(mutant(tmp_path, "lab08_homographies", source), ["lab08.ex5"], pictures="none")
    [strip] = [c for c in check_results(result, "lab08.ex5") if c.name.startswith("stitch: the part only img2")]
    assert not strip.passed and strip.hint == SECOND_WARP_HINT.neutral(
        "warps with a product of a shift and a homography")


def test_a_misplaced_strip_is_told_to_look_at_h_not_at_its_brightness(tmp_path, no_repairs):
    """H rounded to two decimals before the warp (the blind set 1206a's 08/04): img2's strip is as bright as the
    truth's but elsewhere -- its pixels do not follow the truth's -- so the hint that the code already warps with
    T @ H points at H itself, not at brightness or blending (code identical to the reference's)."""
    folder = edited_reference(tmp_path, "lab08_homographies", ("    H21 = _pairwise_homography(img2, img1)\n",
                                                                "    H21 = np.round(_pairwise_homography(img2, img1), 2)\n"))
    result = grade(folder, ["lab08.ex5"], pictures="none", include_hidden=False)
    [strip] = [c for c in check_results(result, "lab08.ex5") if c.name.startswith("stitch: the part only img2")]
    assert not strip.passed and "compare how the pixels" not in strip.hint and "the H itself" in strip.hint, strip.hint


def test_an_image_converted_to_uint8_then_back_is_not_told_to_convert_it(tmp_path, no_repairs):
    # (the hint itself: a repair -- dropping the `/ 1.0` -- would take its place)
    source = """
        _right = translate
        def translate(image, tx=100, ty=50):
            out = np.clip(_right(image, tx, ty), 0, 255).astype(np.uint8)
            return out / 1.0
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex1"], pictures="none")
    hints = {c.hint for c in check_results(result, "lab07.ex1") if "dtype float64" in c.message}
    assert hints == {"your code converts to uint8 somewhere, but not the array it returns"}
    plain = grade(mutant(tmp_path / "plain", "lab07_transformations", source.replace(
        "np.clip(_right(image, tx, ty), 0, 255).astype(np.uint8)", "_right(image, tx, ty)")),
        ["lab07.ex1"], pictures="none")
    assert {c.hint for c in check_results(plain, "lab07.ex1") if "dtype float64" in c.message} == {
        "images stay uint8: convert with np.clip(x, 0, 255).astype(np.uint8)"}


@pytest.mark.parametrize("body, converts", [
    ("x = np.array(a, dtype=np.float64)", True), ("x = np.asarray(a, dtype=float)", True),
    ("x = np.zeros(3, dtype=np.float32)", True), ("x = np.array(a, dtype=int)", False),
    ("x = np.zeros(3, dtype=np.uint8)", False),
])
def test_to_float_counts_only_float_dtypes(body, converts):
    """An integer dtype is no conversion to float: a float hint is not withheld from such code."""
    import ast

    from autograder.engine.hints import TO_FLOAT

    tree = ast.parse(f"import numpy as np\ndef f(a):\n    {body}\n    return x\n")
    assert bool(TO_FLOAT.found([tree.body[1]])) is converts


_RUNNING_BEST = """
def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
    best = np.full(left.shape, np.inf)
    disp = np.zeros(left.shape)
    for d in range(max_disparity + 1):
        shifted = np.roll(right, d, axis=1)
        if cost == "ssd":
            c = cv2.boxFilter((left - shifted) ** 2, -1, (block_size, block_size))
        else:
            c = {sign}_ncc(left, shifted, block_size)
        better = c < best
        best[better] = c[better]
        disp[better] = d
    return disp
"""


@pytest.mark.parametrize("sign, keeps_highest", [("-", True), ("", False)])
def test_a_vectorised_running_minimum_of_the_negated_ncc_keeps_the_highest(sign, keeps_highest):
    """The most common student matcher: a running best over the disparities, `better = c < best`.
    With c = -NCC it keeps the highest NCC (the hint to keep the HIGHEST is not said); with c = +NCC
    it keeps the lowest, and the hint stays. The SSD branch keeps the lowest cost either way."""
    from autograder.engine.hints import KEEPS_LOWEST
    from autograder.labs.lab12 import NCC_HINT

    code = read_code(textwrap.dedent(_RUNNING_BEST.format(sign=sign)))
    assert bool(NCC_HINT.contradicts(code, ["block_matching"])) == keeps_highest
    assert KEEPS_LOWEST.found(code.reachable(["block_matching"]))


def test_an_expression_in_a_helper_given_another_value_of_the_name_is_not_the_callers():
    # the blind set's DP: `_sad_volume(left, right, D - 1, ...)`: its `max_disparity + 1` is D, not the API's + 1
    rebound = """
        def f(left, right, max_disparity=64):
            D = int(max_disparity)
            return _volume(left, right, D - 1)
        def _volume(left, right, max_disparity):
            return np.zeros((max_disparity + 1,) + left.shape)
        """
    assert found(expr("max_disparity + 1"), rebound) == ""
    # the same value passed on, as itself or converted (directly, or through a name assigned so): found
    for call in ("_volume(left, right, max_disparity)", "_volume(left, right, int(max_disparity))",
                 "_volume(left, right, D)", "_volume(left, right, max_disparity=D)"):
        source = rebound.replace("_volume(left, right, D - 1)", call)
        assert found(expr("max_disparity + 1"), source) == "computes max_disparity + 1", call



def test_samples_drawn_in_a_batch_and_a_refit_on_a_mask_made_from_them_are_read_as_a_ransac_loop():
    """`np.argsort(rng.random((256, n)))[:, :4]` draws samples; `inliers = errors < threshold` is a mask
    (whatever it was measured from), so `homography_dlt(src[inliers], ...)` is a refit on the inliers: the
    RANSAC recipe is not told to code that follows it."""
    from autograder.engine.hints import read_code
    from autograder.labs import lab08

    code = read_code(textwrap.dedent("""
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            rng = np.random.default_rng(seed)
            best, best_inliers = -1, None
            for _ in range(10):
                samples = np.argsort(rng.random((256, len(src))), axis=1)[:, :4]
                errors = _errors(samples, src, dst)
                inliers = errors < threshold
                k = int(np.argmax(inliers.sum(axis=1)))
                if inliers[k].sum() > best:
                    best, best_inliers = inliers[k].sum(), inliers[k]
            inliers = best_inliers
            return homography_dlt(src[inliers], dst[inliers]), inliers
        """))
    assert lab08.OWN_RANSAC_LOOP.found(code.reachable(["homography_ransac"]))


@pytest.mark.parametrize("body, shifted", [
    ("return _compose([img1, img2], [np.eye(3), H])", True),
    ("images, homographies = [img1, img2], [np.eye(3), H]\n    return _compose(images, homographies)", True),
    ("images, homographies = [img1, img2], [H, np.eye(3)]\n    return _compose(images, homographies)", False),
    ("return cv2.warpPerspective(img1, H, size)", False),
])
def test_img1_paired_with_the_identity_is_read_as_only_shifted(body, shifted):
    from autograder.labs.lab08 import _img1_only_shifted
    function = ast.parse(f"def stitch(img1, img2):\n    {body}\n").body[0]
    assert _img1_only_shifted(function) is shifted


MASKED_DEPTH = """
    def depth_from_disparity(disparity, f, baseline):
        d = np.array(disparity, dtype=np.float64)
        valid = np.isfinite(d) & ({condition})
        depth = np.zeros(d.shape)
        depth[valid] = float(f) * float(baseline) / d[valid]
        {returned}
    """


@pytest.mark.parametrize("condition, returned, says, not_said", [
    # holes filled from the left after the masked division: the division is done, the array returned is not it
    ("d > 0", "return np.take_along_axis(depth, np.maximum.accumulate(np.where(valid, np.arange(d.shape[-1]), 0), "
              "axis=-1), axis=-1)", "the array returned", "check that"),
    ("d != 0", "return depth", "check that its condition is d > 0", "out starts as zeros"),
])
def test_a_masked_division_is_not_told_to_divide_with_where(tmp_path, no_repairs, condition, returned, says, not_said):
    source = MASKED_DEPTH.format(condition=condition, returned=returned)
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ex2"], pictures="none")
    hints = [c.hint for c in check_results(result, "lab12.ex2") if not c.passed and "divides only where" in c.hint]
    assert hints and all(says in h and not_said not in h and "np.divide(f * baseline" not in h for h in hints)


BLENDED_POINTS = """
    def draw_points(image, pts, radius=3, color=(0, 0, 255)):
        overlay = image.copy()
        for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
            if {skip}:
                continue
            cv2.circle(overlay, (int(round(x)), int(round(y))), int(radius), tuple(int(c) for c in color), -1)
        return cv2.addWeighted(overlay, {weight}, image, {rest}, 0)
    """


@pytest.mark.parametrize("skip, weight, says", [
    # skipping the non-finite rows already, blending the circles: not a NaN matter
    ("np.isnan(x) or np.isnan(y) or np.isinf(x) or np.isinf(y)", 0.6, "fails without the NaN and infinite rows too"),
    # drawing solidly, but skipping only NaN: the infinite row raises, and the advice is the tip's
    ("np.isnan(x) or np.isnan(y)", 1.0, "skip the rows that are not finite"),
])
def test_the_nan_tip_speaks_of_nan_only_where_the_finite_points_are_drawn(tmp_path, no_repairs, skip, weight, says):
    source = BLENDED_POINTS.format(skip=skip, weight=weight, rest=round(1 - weight, 1))
    result = grade(mutant(tmp_path, "lab09_camera", source), ["lab09.ex5"], pictures="none")
    [tip] = [c for c in check_results(result, "lab09.ex5") if c.name == "draw_points skips NaN points"]
    assert says in tip.message
    assert "if np.isfinite(x)" not in tip.hint    # the code tests every row already


@pytest.mark.parametrize("loop, greedy", [
    # each column chosen given the one before it, from the left: a greedy pass
    ("for x in range(1, width):\n        jump = ramp[np.abs(d - disparity[x - 1][:, None])]\n"
     "        disparity[x] = np.argmin(energy[x] + jump, axis=1)", True),
    # the lab sheet's walk back from the last column
    ("for x in range(width - 2, -1, -1):\n        jump = ramp[np.abs(d - disparity[x + 1][:, None])]\n"
     "        disparity[x] = np.argmin(energy[x] + jump, axis=1)", False),
    # each column's own argmin (no backtracking at all: another reading names it)
    ("for x in range(1, width):\n        disparity[x] = np.argmin(energy[x], axis=1)", False),
])
def test_a_dp_choosing_each_column_from_the_left_is_read_as_a_greedy_pass(loop, greedy):
    from autograder.labs.lab12 import _chosen_from_the_left
    function = ast.parse(f"def dp_stereo(left, right):\n    {loop}\n    return disparity\n").body[0]
    assert (_chosen_from_the_left([function]) is not None) is greedy


def test_a_step_under_a_condition_is_found_only_where_it_is_never_made_unconditionally():
    """hints.step_under_a_condition (the rank step of essential_8point under a 5% test, blind set 2026-12-06e):
    the test and both lines where the step is only ever made under an if; nothing where it is also made
    outside every if (then the test is not what left it undone)."""
    import ast as _ast
    from autograder.engine.hints import step_under_a_condition
    is_diag = lambda node: isinstance(node, _ast.Call) and _ast.unparse(node.func) == "np.diag"  # noqa: E731
    conditional = _ast.parse(textwrap.dedent("""
        def f(E, s):
            U, _, Vt = np.linalg.svd(E)
            if s[1] < 0.95 * s[0]:
                E = U @ np.diag([1.0, 1.0, 0.0]) @ Vt
            return E
        """)).body[0]
    assert step_under_a_condition([conditional], is_diag) == ("s[1] < 0.95 * s[0]", 4, 5)
    always = _ast.parse(textwrap.dedent("""
        def f(E, s):
            U, _, Vt = np.linalg.svd(E)
            if s[2] > 1:
                E = U @ np.diag([1.0, 1.0, 0.0]) @ Vt
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """)).body[0]
    assert step_under_a_condition([always], is_diag) is None


def test_points_normalised_by_their_spread_are_not_told_to_normalise(tmp_path):
    """An 8-point algorithm centring the points and scaling each axis by 1 / np.std, then fixing F[2, 2] = 1 and
    solving by least squares, was told "check ... that the points are normalised first (Hartley)" (third-party
    round of 2026-12-07): a normalisation by the spread is one; the checklist leaves it out."""
    result = grade(mutant(tmp_path, "lab11_two_view", """
        def _spread_normalised(points):
            points = np.asarray(points, dtype=np.float64)
            centre = np.mean(points, axis=0)
            scale = 1.0 / np.std(points - centre, axis=0)
            T = np.array([[scale[0], 0, -scale[0] * centre[0]], [0, scale[1], -scale[1] * centre[1]], [0, 0, 1]])
            return (points - centre) * scale, T

        def fundamental_8point(pts1, pts2):
            p1, T1 = _spread_normalised(pts1)
            p2, T2 = _spread_normalised(pts2)
            x1, y1, x2, y2 = p1[:, 0], p1[:, 1], p2[:, 0], p2[:, 1]
            A = np.column_stack([x2 * x1, x2 * y1, x2, y2 * x1, y2 * y1, y2, x1, y1])
            f = np.linalg.lstsq(A, -np.ones(len(p1)), rcond=None)[0]
            F = np.append(f, 1.0).reshape(3, 3)
            U, s, Vt = np.linalg.svd(F)
            F = U @ np.diag([s[0], s[1], 0.0]) @ Vt
            F = T2.T @ F @ T1
            return F / np.linalg.norm(F)
        """), ["lab11.ex4"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab11.ex4") if c.score < c.max_score]
    assert failed
    assert not any("normalised first" in c.hint + c.message for c in failed), [c.hint for c in failed]


def test_a_centre_computed_through_an_inverse_is_not_told_to_be_minus_r_transpose_t(tmp_path, monkeypatch):
    """`C2 = -np.linalg.inv(K2 @ R) @ (K2 @ T)`, the textbook's centre of a camera K [R | t], is -R^T T: a rectify
    computing it so, its axes stacked as columns, was told "check that camera 2's centre is -R^T T, not T"
    (third-party round of 2026-12-07). (The fixed hint itself: a change found of the code would take its place.)"""
    from autograder.engine import runner

    monkeypatch.setattr(runner, "_named_by_repair", lambda verdict, *args, **kwargs: verdict)
    monkeypatch.setattr(runner, "_named_by_error_model", lambda verdict, *args, **kwargs: verdict)
    result = grade(edited_reference(tmp_path, "lab12_stereo", ("C2 = -R.T @ T", "C2 = -np.linalg.inv(K2 @ R) @ (K2 @ T)"),
                                    ("R_rect = np.vstack([e1, e2, e3])", "R_rect = np.column_stack([e1, e2, e3])")),
                   ["lab12.ex3"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab12.ex3") if c.score < c.max_score]
    assert failed
    assert not any("-R^T T, not T" in c.hint + c.message for c in failed), [c.hint for c in failed]
    assert any("your code computes camera 2's centre -R^T T" in c.hint for c in failed), [c.hint for c in failed]
