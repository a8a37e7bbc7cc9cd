"""Lab 12: the reference passes, the skeleton scores 0, usual mistakes are named."""

import json
import textwrap

import numpy as np
import pytest

from autograder.engine.runner import grade
from autograder.labs.mistakes.lab12 import ADVICE, MISTAKES
from conftest import (THREE_ROW_TRIANGULATION, assert_advice_case, assert_advised, assert_all_not_implemented, assert_full_marks, assert_mistake_named, check_results,
                      edited_reference, failing_messages, mutant)

MODULE = "lab12_stereo"


def test_reference_scores_full_marks(reference_result):
    assert_full_marks(reference_result, "lab12")


def test_skeleton_scores_zero_with_not_implemented(skeleton_result):
    assert_all_not_implemented(skeleton_result, "lab12")


def test_every_exercise_of_the_api_is_registered(reference_result):
    ids = {e.id for e in reference_result.exercises if e.id.startswith("lab12.")}
    assert ids == {f"lab12.ex{i}" for i in range(1, 7)} | {"lab12.ext1"}
    assert any(c.hidden for e in reference_result.exercises if e.id.startswith("lab12.")
               for c in e.checks)


# How far the reference's figures move between OpenCV majors (the scenes are drawn with OpenCV's
# warps and filters): at most 0.0013 measured (4.14 vs 5.0), against the checks' MARGIN of 0.05.
OTHER_MAJOR_DRIFT = 0.002


def test_stored_reference_figures_are_current():
    """fixtures/data/lab12_figures.json is what make_lab12_figures.py computes now, under the
    pinned OpenCV (constraints.txt's, which makes it); under the other major each figure within
    OTHER_MAJOR_DRIFT of it."""
    import cv2

    from autograder.engine.versions import DEFAULT_OPENCV
    from fixtures import lab12
    from fixtures.make_lab12_figures import compute

    stored, now = json.loads(lab12.FIGURES_FILE.read_text()), json.loads(json.dumps(compute()))
    if cv2.__version__.split(".")[0] == DEFAULT_OPENCV:
        assert stored == now
        return

    def leaves(tree, path=()):
        if isinstance(tree, dict):
            return {k: v for key, sub in tree.items() for k, v in leaves(sub, path + (key,)).items()}
        return {path: tree}

    stored, now = leaves(stored), leaves(now)
    assert stored.keys() == now.keys()
    moved = {path: (stored[path], now[path]) for path in stored if stored[path] != now[path]}
    assert all(isinstance(a, float) and abs(a - b) <= OTHER_MAJOR_DRIFT for a, b in moved.values()), moved


def test_hidden_reference_figures_are_current():
    """The bad-pixel rates written in the hidden checks bound the reference's on scenes drawn
    as the checks draw them (the worst over many draws; block matching's hardly vary)."""
    from autograder.labs.hidden import lab12 as hidden
    from fixtures import lab12
    from fixtures.make_lab12_figures import block_matching_figures, load_reference

    reference = load_reference()
    for draw in range(2):
        rng = np.random.default_rng(draw)
        measured = block_matching_figures(hidden.block_matching_scene(rng), hidden.BLOCK_MATCHING["block_size"])
        for key in ("reference", "legitimate", "far_legitimate"):
            assert abs(measured[key] - hidden.BLOCK_MATCHING[key]) < 0.005, (key, measured[key])
        cases = {"ncc": (hidden.ncc_scene(*hidden.darker(rng)), "block_matching", dict(block_size=9, cost="ncc")),
                 "dp_stereo": (hidden.dp_scene(rng), "dp_stereo", {})}
        for key, (scene, function, kwargs) in cases.items():
            got = getattr(reference, function)(scene.left, scene.right, max_disparity=scene.max_disparity, **kwargs)
            rate = lab12.bad_pixel_rate(got, scene.judged, scene.threshold)
            assert rate <= hidden.REFERENCE_BAD[key] + 0.005, (key, rate)
            assert key == "dp_stereo" or hidden.REFERENCE_BAD[key] - rate < 0.005, (key, rate)


def test_scenes_show_what_the_checks_rely_on():
    """The premises: DP beats block matching on weak texture, SSD fails under a gain change."""
    from fixtures import lab12

    figures = lab12.reference_figures()
    weak = figures["weak_texture"]
    assert weak["dp_5"]["bad"] < weak["bm_ssd_5"]["bad"] - 0.15
    assert weak["dp_5"]["jumps"] < 0.2 * weak["bm_ssd_5"]["jumps"]
    gain = figures["motorcycle_gain"]
    assert gain["bm_ssd_9"]["bad"] > gain["bm_ncc_9"]["bad"] + 0.15


def test_structured_light_fixture_round_trip():
    from fixtures import lab12

    depth, f, baseline = lab12.structured_light_scene("boxes")
    images = lab12.simulate_structured_light(depth, f, baseline, 7)
    decoded = lab12.depth_from_structured_light(images, f, baseline)
    both = (decoded > 0) & (depth > 0)
    assert both.mean() > 0.5
    stripe = depth.shape[1] / 2**7
    disparity_error = np.abs(f * baseline / decoded[both] - f * baseline / depth[both])
    # half a stripe, the -0.5 px centre convention, and the simulation's rounding
    assert disparity_error.max() <= stripe / 2 + 1.0 + 1e-9


@pytest.mark.parametrize("case", sorted(MISTAKES))
@pytest.mark.xdist_group("lab12")
def test_mistake_is_caught_and_named(case):
    assert_mistake_named(MODULE, *MISTAKES[case])


@pytest.mark.parametrize("case", sorted(ADVICE))
@pytest.mark.xdist_group("lab12")
def test_convention_is_advice_not_points(case):
    assert_advice_case(MODULE, *ADVICE[case])


# Realistic correct variants that must keep full marks.
STEREO_RECTIFY = """
        def rectify(img_l, img_r, K1, K2, R, T):
            h, w = img_l.shape[:2]
            R1, R2, P1, P2, *_ = cv2.stereoRectify(np.float64(K1), None, np.float64(K2), None, (w, h),
                                                   np.float64(R), np.float64(T).reshape(3, 1),
                                                   flags=cv2.CALIB_ZERO_DISPARITY, alpha=ALPHA)
            H1 = P1[:, :3] @ R1 @ np.linalg.inv(K1)
            H2 = P2[:, :3] @ R2 @ np.linalg.inv(K2)
            return (cv2.warpPerspective(img_l, H1, (w, h)), cv2.warpPerspective(img_r, H2, (w, h)), H1, H2)
        """
VARIANTS = {
    # An integer disparity map (issue 35): float depths however the division is written, no name.
    "depth into a float np.zeros(d.shape), the map kept integer": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity)
            valid = d > 0
            depth = np.zeros(d.shape)
            np.divide(f * baseline, d, out=depth, where=valid)
            return depth
        """),
    "depth into np.zeros_like(disparity, dtype=float)": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            depth = np.zeros_like(disparity, dtype=float)
            np.divide(f * baseline, disparity, out=depth, where=disparity > 0)
            return depth
        """),
    "depth by np.where on the integer map": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity)
            valid = d > 0
            return np.where(valid, f * baseline / np.where(valid, d, 1), 0.0)
        """),
    "rectify with cv2.stereoRectify, alpha=-1": ("lab12.ex3", "ALPHA = -1\n" + textwrap.dedent(STEREO_RECTIFY)),
    "rectify with cv2.stereoRectify, alpha=0": ("lab12.ex3", "ALPHA = 0\n" + textwrap.dedent(STEREO_RECTIFY)),
    "rectify with cv2.stereoRectify, alpha=1": ("lab12.ex3", "ALPHA = 1\n" + textwrap.dedent(STEREO_RECTIFY)),
    "block matching with summed SSD and sub-pixel refinement": ("lab12.ex4", """
        _ssd = _ssd_volume
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            volume = _ssd(_grey_float(left), _grey_float(right), max_disparity, block_size) * block_size**2
            d = np.argmin(volume, axis=0)
            inner = (d > 0) & (d < max_disparity)
            rows, cols = np.nonzero(inner)
            c0 = volume[d[inner] - 1, rows, cols]; c1 = volume[d[inner], rows, cols]
            c2 = volume[d[inner] + 1, rows, cols]
            denom = c0 - 2 * c1 + c2
            ok = np.isfinite(denom) & (denom > 0)
            out = d.astype(float)
            out[rows[ok], cols[ok]] += 0.5 * (c0[ok] - c2[ok]) / denom[ok]
            return out
        """),
    "block matching with the lab sheet's cv2.StereoBM, as the skeleton says": ("lab12.ex4", """
        _block_matching_own = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost != "ssd":
                return _block_matching_own(left, right, max_disparity, block_size, cost)
            n = 16 * -(-(max_disparity + 1) // 16)
            d = cv2.StereoBM_create(numDisparities=n, blockSize=block_size).compute(left, right) / 16.0
            d[(d <= 0) | (d > max_disparity)] = 0
            return d
        """),
    "block matching with cv2.StereoBM, numDisparities rounded up to 16, nothing clipped": ("lab12.ex4", """
        _block_matching_own = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost != "ssd":
                return _block_matching_own(left, right, max_disparity, block_size, cost)
            n = 16 * int(np.ceil(max_disparity / 16))
            return cv2.StereoBM_create(numDisparities=n, blockSize=block_size).compute(left, right) / 16.0
        """),
    "block matching after a Gaussian prefilter": ("lab12.ex4", """
        _block_matching_own = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            blur = lambda image: cv2.GaussianBlur(image, (5, 5), 0)
            return _block_matching_own(blur(left), blur(right), max_disparity, block_size, cost)
        """),
    "block matching with SAD": ("lab12.ex4", """
        def _ssd_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(max_disparity + 1):
                costs[d] = cv2.boxFilter(np.abs(left - _shift_right(right, d)), -1, (block_size, block_size),
                                         normalize=False)
                costs[d, :, :d] = np.inf
            return costs
        """),
    "triangulation with all three rows of x × (P X) = 0, rows not scaled": ("lab12.ex1", THREE_ROW_TRIANGULATION),
    "DP with a squared-difference cost and its own default": ("lab12.ex5", """
        def _sad_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.empty((max_disparity + 1, height, width))
            for d in range(max_disparity + 1):
                costs[d] = _box_mean((left - _shift_right(right, d)) ** 2, block_size) * block_size**2
                costs[d, :, :d] = 1e6
            return np.ascontiguousarray(costs.transpose(2, 1, 0))
        DEFAULT_SMOOTHNESS = 2000.0
        """),
    "DP written the student way: a loop over rows and columns": ("lab12.ex5", """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            L = np.asarray(left, float); R = np.asarray(right, float)
            H, W = L.shape
            D = max_disparity + 1
            lam = 40.0 if smoothness is None else smoothness
            C = np.full((H, W, D), 1e9)
            for d in range(D):
                diff = np.zeros_like(L)
                diff[:, d:] = (L[:, d:] - R[:, :W - d]) ** 2
                C[:, :, d] = cv2.boxFilter(diff, -1, (block_size, block_size))
                C[:, :d, d] = 1e9
            jumps = np.abs(np.arange(D)[:, None] - np.arange(D)[None, :])
            out = np.zeros((H, W))
            for y in range(H):
                M = np.zeros((W, D)); back = np.zeros((W, D), int)
                M[0] = C[y, 0]
                for x in range(1, W):
                    total = M[x - 1][None, :] + lam * jumps
                    back[x] = np.argmin(total, axis=1)
                    M[x] = C[y, x] + total[np.arange(D), back[x]]
                d = int(np.argmin(M[-1]))
                for x in range(W - 1, -1, -1):
                    out[y, x] = d
                    d = back[x, d]
            return out
        """),
}


@pytest.mark.parametrize("case", sorted(VARIANTS))
def test_correct_variants_keep_full_marks(tmp_path, case):
    exercise, source = VARIANTS[case]
    result = grade(mutant(tmp_path, MODULE, source), [exercise])
    for check in check_results(result, exercise):
        assert check.passed, f"{check.name}: {check.message}"


@pytest.mark.parametrize("at_nan, passes", [("np.nan", True), ("-1.0", True), ("0.0", True), ("np.inf", False),
                                             ("1.0", False)])
def test_a_nan_disparity_may_have_any_invalid_depth(tmp_path, at_nan, passes):
    """The API's ex2 asks 0 where d <= 0 and nothing of a NaN disparity (no match), and its conventions call a depth
    <= 0 or NaN invalid: NaN kept as NaN lost 2 points (third-party round of 2026-12-07, a probe of 0 where d <= 0).
    A positive or infinite depth there is still a depth where there is none."""
    result = grade(mutant(tmp_path, MODULE, f"""
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=float)
            with np.errstate(divide="ignore", invalid="ignore"):
                z = np.where(d > 0, f * baseline / d, 0.0)
            return np.where(np.isnan(d), {at_nan}, z)
        """), ["lab12.ex2"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab12.ex2") if c.score < c.max_score]
    if passes:
        assert not failed, [c.message for c in failed]
    else:
        assert [c.name for c in failed] == ["depth_from_disparity gives 0 for invalid disparities (<= 0 or NaN)"]
        assert "A NaN disparity (no match) has no depth" in failed[0].message, failed[0].message


def test_a_disparity_map_written_into_loses_one_check_though_a_second_call_agrees(tmp_path):
    """The sheet shows the disparity map beside the depth computed from it (inplace.shown_after):
    inf written into the caller's invalid entries (f b / inf = 0, the depths right, a second call on
    the changed map the same) loses the first check where it shows, named, and no other."""
    result = grade(mutant(tmp_path, MODULE, """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=np.float64)   # no copy for a float array
            d[~(d > 0)] = np.inf                          # f b / inf = 0: invalid
            return f * baseline / d
        """), ["lab12.ex2"], pictures="none")
    failed = [c for c in check_results(result, "lab12.ex2") if not c.passed and not c.advice]
    assert [c.name for c in failed] == ["depth_from_disparity gives 0 for invalid disparities (<= 0 or NaN)"]
    assert "writes into the caller's `disparity` in place (3 of its 6 values: 0 became inf, -3 became inf, " \
           "nan became inf)" in failed[0].message, failed[0].message
    assert_advised(result, "lab12.ex2", "depth_from_disparity", "disparity", "in place")



def test_a_depth_map_written_into_by_the_simulation_loses_one_check_though_a_second_call_agrees(tmp_path):
    """Exercise 6 compares the depth it triangulates with the depth map it simulated from
    (inplace.shown_after): inf written into the caller's invalid depths (never lit, the patterns
    right, a second call on the changed map the same) loses the first check where it shows, named."""
    result = grade(mutant(tmp_path, MODULE, """
        def simulate_structured_light(depth, f, baseline, n_bits):
            Z = np.asarray(depth, dtype=np.float64)   # no copy for a float map
            Z[~(Z > 0)] = np.inf                      # f b / inf = 0 ... and then off by the valid test
            height, width = Z.shape
            patterns = gray_code_patterns(width, n_bits)
            valid = np.isfinite(Z) & (Z > 0)
            u = np.broadcast_to(np.arange(width, dtype=np.float64), Z.shape)
            disparity = np.divide(float(f) * float(baseline), Z, out=np.zeros_like(Z), where=valid)
            column = np.floor(u - disparity + 0.5).astype(np.int64)
            lit = valid & (column >= 0) & (column < width)
            images = np.zeros((int(n_bits), height, width), dtype=np.uint8)
            images[:, lit] = patterns[:, column[lit]]
            return images
        """), ["lab12.ex6"], pictures="none")
    failed = [c for c in check_results(result, "lab12.ex6") if not c.passed and not c.advice]
    assert len(failed) == 1, [c.name for c in failed]
    assert "writes into the caller's `depth` in place" in failed[0].message, failed[0].message
    assert "became inf" in failed[0].message and "compares the depth map it triangulates" in failed[0].message


def test_a_pattern_hint_tells_the_stripe_index_from_the_code_by_what_the_columns_carry():
    """One code per stripe: the stripe index is right, the Gray code is not (its formula is the
    hint); several codes within a stripe: k itself is wrong (the floor formula is the hint)."""
    from autograder.labs.lab12 import one_code_per_stripe
    from fixtures import lab12 as truth

    width, n_bits = 97, 5
    stripes = truth._stripe(width, n_bits)
    assert one_code_per_stripe(truth.gray_code_patterns(width, n_bits), stripes)
    assert one_code_per_stripe(truth.binary_code_patterns(width, n_bits), stripes)   # another code, right k
    assert not one_code_per_stripe(truth.rounded_stripe_patterns(width, n_bits), stripes)   # k rounded


@pytest.mark.parametrize("edit, words", [
    (("rect_r = cv2.warpPerspective(np.asarray(img_r), H2,", "rect_r = cv2.warpPerspective(np.asarray(img_r), H1,"),
     "rect_r alone is warped with H1, the other image's homography, where H2 belongs"),
    (("rect_l = cv2.warpPerspective(np.asarray(img_l), H1,", "rect_l = cv2.warpPerspective(np.asarray(img_l), H2,"),
     "rect_l alone is warped with H2, the other image's homography, where H1 belongs"),
])
def test_one_image_warped_with_the_other_homography_is_told_alone(tmp_path, edit, words):
    """A warp line copied from the other image's is not "each image is warped with the other's"."""
    from conftest import edited_reference

    result = grade(edited_reference(tmp_path, "lab12_stereo", edit), ["lab12.ex3"], pictures="none")
    [check] = [c for c in check_results(result, "lab12.ex3") if c.name.startswith("rectify: the rectified images")]
    assert not check.passed and words in check.message and "each image" not in check.message, check.message


def test_flat_rows_are_not_blamed_on_the_smoothness_when_they_stay_flat_without_it(tmp_path):
    """A DP whose rows come out flat whatever the penalty (a minimum taken over the wrong axis, here a
    constant map): the default smoothness is not the cause, and is not named."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab12_stereo", """
        def dp_stereo(left, right, max_disparity=64, smoothness=None, block_size=5):
            return np.full(np.shape(left)[:2], 4.0)
        """)
    result = grade(folder, ["lab12.ex5"], pictures="none", include_hidden=False)
    checks = check_results(result, "lab12.ex5")
    assert any(c.score < c.max_score for c in checks)
    assert not any("far too large" in c.message for c in checks), [c.message for c in checks]


def test_an_xor_carried_through_a_name_is_read_as_the_running_xor():
    import ast

    from autograder.labs.lab12 import _xor_accumulates

    carried = ast.parse(textwrap.dedent("""
        def f(lit, n):
            previous = lit[0] * 0
            for i in range(n):
                b = np.logical_xor(previous, lit[i])
                previous = b
    """)).body[0]
    gray_to_gray = ast.parse(textwrap.dedent("""
        def f(lit, n):
            for i in range(1, n):
                b = np.logical_xor(lit[i - 1], lit[i])
    """)).body[0]
    assert _xor_accumulates(carried) and not _xor_accumulates(gray_to_gray)


def test_images_warped_by_homographies_that_send_them_out_of_the_frame_agree_with_them(tmp_path):
    """A rectification whose H2 sends img_r almost all out of the frame, with rect_r that very warp: the
    images and the homographies agree (the rows and the coverage are the other checks' to judge), so
    the check of their agreement passes rather than telling an infinite difference."""
    folder = mutant(tmp_path, "lab12_stereo", """
        _reference_rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            rect_l, _, H1, H2 = _reference_rectify(img_l, img_r, K1, K2, R, T)
            h, w = img_r.shape[:2]
            H2 = np.array([[1.0, 0.0, 0.97 * w], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]) @ H2
            return rect_l, cv2.warpPerspective(img_r, H2, (w, h)), H1, H2
        """)
    result = grade(folder, ["lab12.ex3"], pictures="none", include_hidden=False)
    checks = {c.name: c for e in result.exercises for c in e.checks}
    assert checks["rectify: the rectified images are the inputs warped by H1 and H2"].score == 2
    assert checks["rectify: most of each image stays in view"].score == 0


def test_a_rectify_whose_maps_bring_pixels_from_behind_the_camera_is_not_told_its_fill(tmp_path):
    """`K1.T` for the inverse of K1 (the blind set 2026-12-06e's 12/06): the homographies send part of the
    frame behind the camera, where cv2.warpPerspective samples the input whatever its border rule. That
    is the maps' doing (the rows check fails); the black-fill check, which told the student to use the
    BORDER_CONSTANT its code already used, judges only pixels with a source in front."""
    folder = edited_reference(tmp_path, "lab12_stereo",
                              ("rot1 = R_rect @ np.linalg.inv(K1)", "rot1 = R_rect @ K1.T"),
                              ("rot2 = R_rect @ R.T @ np.linalg.inv(K2)", "rot2 = R_rect @ R.T @ K2.T"))
    messages = failing_messages(folder, "lab12.ex3")
    assert any("must share a row" in m for m in messages), messages
    assert not any("are not black" in m for m in messages), messages


def test_an_ssd_of_normalised_images_beside_an_uncentred_ncc_is_not_told_the_costs_are_swapped(tmp_path):
    # (audit of 2026-12-06: the gain check's swap was inferred from cost="ssd" coping with the gain alone; an SSD of
    # images normalised as a whole copes too, and the NCC's own slip is its block means not subtracted)
    folder = edited_reference(
        tmp_path, "lab12_stereo",
        ("    height, width = left.shape\n    costs = np.full((max_disparity + 1, height, width), np.inf)\n"
         "    for d in range(min(max_disparity, width - 1) + 1):\n        squared",
         "    height, width = left.shape\n    left = (left - left.mean()) / left.std()\n"
         "    right = (right - right.mean()) / right.std()\n"
         "    costs = np.full((max_disparity + 1, height, width), np.inf)\n"
         "    for d in range(min(max_disparity, width - 1) + 1):\n        squared"),
        ("covariance = _box_mean(left * shifted, block_size) - mean_l * mean_r",
         "covariance = _box_mean(left * shifted, block_size)"))
    result = grade(folder, ["lab12.ext1"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab12.ext1") if c.score < c.max_score]
    assert failed and not any("costs are swapped" in c.message for c in failed), [c.message for c in failed]


def test_a_block_matcher_ignoring_cost_earns_none_of_the_ncc_extension(tmp_path):
    """cost="ncc" answered by the SSD matching earned 4 of the extension's 8 points where SSD's map is as good as NCC's
    (the motorcycle, a flat border: third-party round of 2026-12-07). On a pair where the two costs disagree it gives
    exactly SSD's map: every check of the extension fails, saying so; the base exercise keeps its points."""
    result = grade(edited_reference(tmp_path, MODULE, ('(_ssd_volume if cost == "ssd" else _ncc_volume)(', '_ssd_volume(')),
                   ["lab12.ex4", "lab12.ext1"], pictures="none", include_hidden=False)
    scores = {e.id: (e.score, e.max_score) for e in result.exercises}
    assert scores["lab12.ex4"][0] == scores["lab12.ex4"][1] and scores["lab12.ext1"][0] == 0, scores
    # (the code reads cost -- it refuses an unknown one --: told so, not "ignored")
    assert any("your block_matching reads cost, yet NCC is not computed" in c.message
               for c in check_results(result, "lab12.ext1"))
