"""No message names a cause the student's code or outputs contradict (issue 35), labs 8 and 12.

Each fixed message is tested twice: a variant whose code already does what the old words told
it to do is not told so (its outputs, or its code read with ``ast``, say otherwise), and the
realistic mistake behind it gets the right name. The predicates of the code are tested on source
alone; the diagnoses by grading mutants of the reference (the reference and the sensible
alternatives pass: tests/test_lab08.py, tests/test_lab12.py).
"""

import textwrap

import numpy as np
import pytest

from autograder.engine.hints import KEEPS_HIGHEST, KEEPS_LOWEST, read_code
from autograder.engine.runner import grade
from autograder.labs import lab08, lab12
from conftest import check_results, edited_reference, mutant
from fixtures import lab08 as truth08


def found(predicate, source: str, function: str) -> str:
    return predicate.found(read_code(textwrap.dedent(source)).reachable([function]))


# ------------------------------------------------------------------ what the code keeps
NCC_HELPER = """
    def _ssd(left, right, d):
        return (left - np.roll(right, d, axis=1)) ** 2
    def _ncc_costs(left, right, n):
        costs = np.full((n, 4, 4), np.inf)
        for d in range(n):
            ncc = _correlate(left, np.roll(right, -d, axis=1))
            costs[d] = {negate}ncc
        return costs
    def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
        volume = (_ssd if cost == "ssd" else _ncc_costs)(left, right, max_disparity + 1)
        return np.{pick}(volume, axis=0)
    """


@pytest.mark.parametrize("negate, pick, highest", [
    ("-", "argmin", True),     # a cost -NCC stored by a helper, its argmin (the blind set's NCC)
    ("1 - ", "argmin", True),  # 1 - NCC
    ("", "argmax", True),
    ("", "argmin", False),     # the lowest NCC: the hint to keep the highest is what it needs
    ("-", "argmax", False),
])
def test_the_highest_score_is_seen_through_a_negation_in_a_helper(negate, pick, highest):
    """A negated shift (``np.roll(right, -d)``) in the same code is no negated score."""
    source = NCC_HELPER.format(negate=negate, pick=pick)
    assert bool(found(KEEPS_HIGHEST, source, "block_matching")) == highest


@pytest.mark.parametrize("source, highest", [
    ("def f(scores):\n    return np.argsort(scores, axis=0)[-1]\n", True),
    ("def f(scores):\n    return max(range(len(scores)), key=lambda d: scores[d])\n", True),
    ("def f(l, r):\n    best = -2\n    for d in range(9):\n        score = ncc(l, r, d)\n"
     "        if score > best:\n            best, keep = score, d\n    return keep\n", True),
    ("def f(scores):\n    s = -scores\n    return np.argmin(-s, axis=0)\n", False),   # negated twice
    ("def f(scores):\n    return np.argsort(scores, axis=0)[0]\n", False),
    # (an NCC negated in its numerator, stored in a volume and its argmin taken: blind set 08d lab12/04)
    ("def f(volume, L, R, d, denom):\n    cov = cv2.blur(L * R, (5, 5))\n    c = -cov / (denom + 1e-6)\n"
     "    volume[d] = c\n    return np.argmin(volume, axis=0)\n", True),
    ("def f(volume, L, R, d, denom):\n    cov = cv2.blur(L * R, (5, 5))\n    c = cov / (denom + 1e-6)\n"
     "    volume[d] = c\n    return np.argmin(volume, axis=0)\n", False),
])
def test_other_ways_of_keeping_the_highest_score(source, highest):
    assert bool(found(KEEPS_HIGHEST, source, "f")) == highest


@pytest.mark.parametrize("source, highest, lowest", [
    # (OpenCV's template matching: the location of the best score read from cv2.minMaxLoc -- third-party audit
    # of 2026-12-07, course code told to "keep the HIGHEST score" where it reads the maximum's location)
    ("def f(strip, patch):\n    s = cv2.matchTemplate(strip, patch, cv2.TM_CCOEFF_NORMED)\n"
     "    _, _, _, max_loc = cv2.minMaxLoc(s)\n    return max_loc[0]\n", True, False),
    ("def f(strip, patch):\n    s = cv2.matchTemplate(strip, patch, cv2.TM_SQDIFF)\n"
     "    _, _, min_loc, _ = cv2.minMaxLoc(s)\n    return min_loc[0]\n", False, True),
    ("def f(s):\n    return cv2.minMaxLoc(s)[3][0]\n", True, False),
    ("def f(s):\n    return cv2.minMaxLoc(s)[-2][0]\n", False, True),
    # (a location unpacked and never read keeps nothing)
    ("def f(s):\n    lo, hi, min_loc, max_loc = cv2.minMaxLoc(s)\n    return hi\n", False, False),
])
def test_the_location_read_from_min_max_loc_says_which_extreme_is_kept(source, highest, lowest):
    assert bool(found(KEEPS_HIGHEST, source, "f")) == highest
    assert bool(found(KEEPS_LOWEST, source, "f")) == lowest


def test_the_lowest_cost_is_seen_through_a_negation_too():
    assert found(KEEPS_LOWEST, "def f(cost):\n    return np.argmax(-cost, axis=0)\n", "f")
    assert found(KEEPS_LOWEST, "def f(cost):\n    return cost.argmin(axis=0)\n", "f")
    assert not found(KEEPS_LOWEST, "def f(cost):\n    return np.argmax(cost, axis=0)\n", "f")


@pytest.mark.parametrize("source, computes", [
    ("def rectify(a, b, K1, K2, R, T):\n    C2 = -R.T @ T\n    return C2\n", True),
    ("def rectify(a, b, K1, K2, R, T):\n    c = -np.dot(R.T, T)\n    return c\n", True),
    ("def rectify(a, b, K1, K2, R, T):\n    C2 = T\n    return C2\n", False),
])
def test_the_rectification_hint_reads_the_centre_from_the_code(source, computes):
    assert bool(found(lab12.CENTRE, source, "rectify")) == computes


# ------------------------------------------------------------------ what the outputs show
def test_an_image_only_shifted_and_partly_drawn_over_is_told_apart_from_a_warped_one():
    rng = np.random.default_rng(3)
    image = rng.integers(0, 256, (120, 160, 3)).astype(np.uint8)
    image = np.ascontiguousarray(np.repeat(np.repeat(image[::4, ::4], 4, 0), 4, 1))   # blocks, not noise
    panorama = np.zeros((160, 240, 3), np.uint8)
    panorama[20:140, 30:190] = image
    panorama[20:140, 30:100] = rng.integers(30, 256, (120, 70, 3))                       # something drawn over
    covered, said = lab08.placed_as_is(panorama, image, (30, 20), "img1")
    assert covered and "in place, only shifted, over" in said and "drawn over" in said
    warped = cv2_warp(image, truth08.corner_homography(np.random.default_rng(1), (160, 120), 0.08))
    panorama[20:140, 30:190] = warped
    covered, said = lab08.placed_as_is(panorama, image, (30, 20), "img1")
    assert not covered and said.startswith("only")


def cv2_warp(image, H):
    import cv2

    return cv2.warpPerspective(image, H, (image.shape[1], image.shape[0]))


def test_a_mask_of_another_hypothesis_is_told_apart_from_a_mask_of_none():
    src, dst, H, true_inliers = truth08.ransac_problem(10, 100, 0.3, 1.0)
    assert lab08.another_hypothesis(true_inliers, src, dst)
    sample = np.zeros(len(src), bool)
    sample[np.flatnonzero(~true_inliers)[:4]] = True      # four outliers: the inliers of their own H
    assert lab08.another_hypothesis(sample, src, dst)
    scattered = np.random.default_rng(0).random(len(src)) < 0.5
    assert not lab08.another_hypothesis(scattered, src, dst)


# ------------------------------------------------------------------ graded: lab 8
def failing(result, exercise: str):
    return [c for c in check_results(result, exercise) if not c.passed]


def test_ransac_with_src_and_dst_swapped_in_opencv_is_named_not_told_it_does_not_refit(tmp_path):
    """H and mask from one cv2.findHomography(dst, src): they agree, read dst -> src."""
    source = """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            H, mask = cv2.findHomography(np.float64(dst), np.float64(src), cv2.RANSAC, threshold)
            return H, mask.ravel().astype(bool)
        """
    result = grade(mutant(tmp_path, "lab08_homographies", source), ["lab08.ex4"], pictures="none")
    failed = {c.name: c for c in failing(result, "lab08.ex4")}
    for name in ("homography_ransac: the inlier mask it returns is the inliers of the H it returns",
                 "homography_ransac refits H on all its inliers"):
        assert failed[name].mistake == lab08.SWAPPED_ENDS, failed[name].message
        assert "H maps dst onto src" in failed[name].message or "mapping dst onto src" in failed[name].message
    text = " ".join(c.message + " " + c.hint for c in failed.values())
    assert "not the fit to its own inliers" not in text and "different hypotheses" not in text
    assert "refit H on all the inliers" not in text and "draw enough samples" not in text


def test_ransac_through_opencv_the_right_way_round_passes_the_consistency_checks(tmp_path):
    source = """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            H, mask = cv2.findHomography(np.float64(src), np.float64(dst), cv2.RANSAC, threshold)
            return H, mask.ravel().astype(bool)
        """
    result = grade(mutant(tmp_path, "lab08_homographies", source), ["lab08.ex4"], pictures="none")
    assert not failing(result, "lab08.ex4"), [c.message for c in failing(result, "lab08.ex4")]


def test_a_panorama_warped_the_wrong_way_is_named_and_not_told_to_copy_img1(tmp_path):
    """img2 warped with the H of img1 -> img2 (img1 itself only shifted): the second warp is
    named wherever img1's part is drawn over, and img1 is never told to be copied unchanged."""
    source = """
        def stitch(img1, img2):
            return _compose([img1, img2], [np.eye(3), _pairwise_homography(img1, img2)])
        """
    result = grade(mutant(tmp_path, "lab08_homographies", source), ["lab08.ex5"], pictures="none")
    failed = failing(result, "lab08.ex5")
    assert failed
    for check in failed:
        assert "copy img1 unchanged" not in check.message and "must only be shifted" not in check.message \
            and "not in the panorama unchanged" not in check.message
    named = [c for c in failed if c.mistake == "img2 was warped with the inverse homography"]
    assert any(c.name == "stitch: img1 appears unwarped, only shifted" for c in named), \
        [(c.name, c.message) for c in failed]


UINT8_PYRAMIDS = """
    def blend_multiband(img1, img2, mask, levels=4):
        def lap(image):   # uint8 throughout
            g = [image]
            for _ in range(levels - 1):
                g.append(cv2.pyrDown(g[-1]))
            return [{sub}(f, cv2.pyrUp(c, dstsize=(f.shape[1], f.shape[0]))) for f, c in zip(g[:-1], g[1:])] + [g[-1]]
        weights = _gaussian_pyramid(np.asarray(mask, np.float32), levels)
        bands = []
        for a, b, w in zip(lap(img1), lap(img2), weights):
            w = w[..., None] if a.ndim == 3 else w
            bands.append((w * a + (1 - w) * b).astype(np.uint8))
        out = bands[-1]
        for band in reversed(bands[:-1]):
            out = {add}(cv2.pyrUp(out, dstsize=(band.shape[1], band.shape[0])), band)
        return out
    """


@pytest.mark.parametrize("sub, add, damaged", [
    ("cv2.subtract", "cv2.add", True),                                # saturated: an image blended with itself changes
    ("np.subtract", "np.add", False),                                 # wrapped: it comes back, the seam does not
])
def test_a_multiband_blend_in_uint8_is_not_told_of_feathers(tmp_path, sub, add, damaged):
    """The pyramid in uint8 is a pyramid: no message says feather, nor tells it the finest level's
    recipe it follows; what blending an image with itself shows is said when it shows."""
    result = grade(mutant(tmp_path, "lab08_homographies", UINT8_PYRAMIDS.format(sub=sub, add=add)), ["lab08.ext3"],
                   pictures="none")
    failed = failing(result, "lab08.ext3")
    assert failed
    messages = [c.message for c in failed]
    assert not any("feather" in m or "finest level uses the sharp mask" in m for m in messages), messages
    assert any("uint8 arithmetic" in m for m in messages) == damaged, messages
    assert any("Blending an image with itself already changes" in m for m in messages) == damaged, messages


# ------------------------------------------------------------------ graded: lab 12
def test_an_ncc_without_the_means_subtracted_is_named_and_not_told_to_keep_the_highest(tmp_path):
    """The helper returns -NCC and block_matching takes the argmin: it keeps the highest score."""
    source = """
        def _ncc_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            mean_l = _box_mean(left, block_size)
            std_l = np.sqrt(np.maximum(_box_mean(left * left, block_size) - mean_l ** 2, 0.0))
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(min(max_disparity, width - 1) + 1):
                shifted = _shift_right(right, d)
                mean_r = _box_mean(shifted, block_size)
                std_r = np.sqrt(np.maximum(_box_mean(shifted * shifted, block_size) - mean_r ** 2, 0.0))
                product = _box_mean(left * shifted, block_size)             # the means never subtracted
                ncc = np.divide(product, std_l * std_r, out=np.zeros_like(product), where=std_l * std_r > 1e-6)
                costs[d] = -ncc
                costs[d, :, :d] = np.inf
            return costs
        """
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ext1"], pictures="none")
    failed = failing(result, "lab12.ext1")
    assert failed and all(c.mistake == lab12.NOT_CENTRED for c in failed), [(c.name, c.message) for c in failed]
    assert not any("HIGHEST" in c.hint or "HIGHEST" in c.message for c in failed)


def test_a_dp_reading_the_forward_pass_is_named_and_keeps_the_credit_its_map_earns(tmp_path):
    source = """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)
            left, right = _grey_float(left), _grey_float(right)
            D = int(max_disparity) + 1
            costs = _sad_volume(left, right, D - 1, int(block_size))
            ramp = (s * np.arange(D)).astype(np.float32)
            energy = np.empty_like(costs)
            energy[0] = costs[0]
            for x in range(1, costs.shape[0]):
                previous = energy[x - 1]
                below = np.minimum.accumulate(previous - ramp, axis=1) + ramp
                above = np.minimum.accumulate((previous + ramp)[:, ::-1], axis=1)[:, ::-1] - ramp
                best = np.minimum(below, above)
                energy[x] = costs[x] + best - best.min(axis=1, keepdims=True)
            return np.argmin(energy, axis=2).T.astype(np.float64)   # no backtracking
        """
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ex5"], pictures="none")
    failed = failing(result, "lab12.ex5")
    assert failed and any(c.mistake == lab12.NOT_BACKTRACKED for c in failed), [(c.name, c.message) for c in failed]
    weak = [c for c in failed if c.name == "dp_stereo beats block matching where the texture is weak"]
    assert all(c.score > 0 for c in weak)   # better than block matching: half the points, named


def test_the_reference_dp_is_not_a_forward_pass_map():
    """At smoothness 1e7 the reference keeps one disparity a row: no forward-pass map to match."""
    scene = lab12.truth.scene("weak_texture")
    maps = lab12.forward_pass_maps(scene)
    assert set(maps) == {"SAD", "SSD"} and all(m.shape == scene.disparity.shape for m in maps.values())
    constant = np.repeat(maps["SAD"][:, -1:], scene.disparity.shape[1], axis=1)    # a backtracked DP's rows
    assert np.mean(np.abs(constant - maps["SAD"]) <= 1) < lab12.FORWARD_AGREEMENT


def test_a_rectification_taking_t_as_the_centre_is_named(tmp_path):
    """Called with -R^T T in place of T, the function rectifies: T was taken as the centre."""
    source = """
        _rectify_right = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            R = np.asarray(R, float)
            return _rectify_right(img_l, img_r, K1, K2, R, -R @ np.asarray(T, float).reshape(3))
        """
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ex3"], pictures="none")
    failed = failing(result, "lab12.ex3")
    assert failed and any(c.mistake.startswith("T itself is taken as camera 2's centre") for c in failed), \
        [(c.name, c.message) for c in failed]


def test_a_chain_of_homographies_in_the_reverse_order_is_named(tmp_path):
    """Four images, the reference the third: the first is two steps away, multiplied the wrong way round."""
    source = """
        def stitch_many(images):
            images = list(images)
            features = [_detect(image) for image in images]
            step = [_pairwise_homography(features[k + 1], features[k]) for k in range(len(images) - 1)]
            r = len(images) // 2
            homographies = []
            for k in range(len(images)):
                H = np.eye(3)
                for j in range(k - 1, r - 1, -1):
                    H = H @ step[j]                          # reversed: step[j] @ H is right
                for j in range(k, r):
                    H = H @ np.linalg.inv(step[j])
                homographies.append(H / H[2, 2])
            return _compose(images, homographies)
        """
    result = grade(mutant(tmp_path, "lab08_homographies", source), ["lab08.ext2"], pictures="none")
    failed = failing(result, "lab08.ext2")
    assert failed and any(c.mistake == lab08.REVERSED_CHAIN for c in failed), [(c.name, c.message) for c in failed]


def test_the_new_principal_point_is_the_in_view_cause_only_of_maps_that_rectify(tmp_path):
    """Maps that rectify but push the images aside are told of the new K; maps that do not rectify (K where K^-1
    belongs) are not: their cause is the rows check's."""
    from autograder.labs.mistakes.lab12 import MISTAKES

    def in_view(source):
        result = grade(mutant(tmp_path / str(len(source)), "lab12_stereo", source), ["lab12.ex3"], pictures="none")
        [check] = [c for c in check_results(result, "lab12.ex3") if c.name == "rectify: most of each image stays in view"]
        return check.message
    pushed = in_view(MISTAKES["rectify pushes the images out of view"][1])
    assert "H1 and H2 rectify the pair, but the new principal point" in pushed
    k_for_inverse = in_view(MISTAKES["rectify with K where K^-1 belongs"][1])
    assert "principal point" not in k_for_inverse and "do not rectify the pair either" in k_for_inverse


@pytest.mark.parametrize("overwrite, wraps", [
    ("", True),                                  # the columns np.roll brings round are compared
    ("shifted[:, :d] = right[:, :1]\n", False),  # written over with the first column: no wrap-round
    ("shifted[..., :d] = 0\n", False),
])
def test_np_roll_is_said_to_wrap_round_only_where_its_columns_stay(overwrite, wraps):
    source = ("def block_matching(left, right, max_disparity=64, block_size=9, cost='ssd'):\n"
              "    for d in range(max_disparity + 1):\n"
              "        shifted = np.roll(right, d, axis=1)\n"
              + (f"        {overwrite}" if overwrite else "") +
              "        cost = (left - shifted) ** 2\n"
              "    return cost\n")
    assert bool(found(lab12.WRAPPED_ROUND, source, "block_matching")) == wraps


def test_a_dp_that_walks_back_with_a_unit_penalty_is_not_told_it_never_backtracks(tmp_path):
    """The walk back from the last column weighs a jump by |d - d'| where the forward pass added
    smoothness * |d - d'|: its maps are the forward pass's at a huge smoothness, as a DP without
    backtracking gives, but the code does walk back -- told as the jump's cost, never as no backtracking."""
    folder = edited_reference(tmp_path, "lab12_stereo", ("jump = ramp[np.abs(candidates[None, :] - disparity[x][:, None])]",
                                                         "jump = np.abs(candidates[None, :] - disparity[x][:, None])"))
    result = grade(folder, ["lab12.ex5"], pictures="none", include_hidden=False)
    failed = failing(result, "lab12.ex5")
    assert failed and any(c.mistake == lab12.JUMP_COST_DIFFERS for c in failed), [(c.name, c.message) for c in failed]
    assert not any(c.mistake == lab12.NOT_BACKTRACKED or "not backtracked" in c.message for c in failed)


def test_a_black_warp_from_code_that_makes_no_unit_range_image_is_not_told_a_cast(tmp_path):
    """An affine made 3x3 with a [0, 0, 0] row sends every pixel to infinity: the warp comes back black (all
    0, as a [0, 1] image cast to uint8 would), but nothing in the code makes values in [0, 1] -- no division
    by 255, no scikit-image transform -- so the cast is not named."""
    source = """
        def warp_affine(image, A, dsize=None):
            M = np.vstack([np.asarray(A, dtype=np.float64), [0.0, 0.0, 0.0]])
            height, width = image.shape[:2]
            return cv2.warpPerspective(image, M, dsize or (width, height))
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex5"], pictures="none")
    failed = failing(result, "lab07.ex5")
    assert failed
    assert not any("values in [0, 1]" in c.message or "[0, 1]" in c.mistake for c in failed), \
        [(c.name, c.message) for c in failed]


def test_where_a_matrix_is_wrong_counts_each_row_at_its_own_size():
    # (a camera matrix: rows of hundreds above a third row of entries near 1; R shrunk by sqrt(3) leaves the
    # translation column right and every row wrong -- the third too, by as much as the others relative to itself)
    from autograder.engine.judges import where_matrices_differ

    K = np.array([[400.0, 0.0, 160.0], [0.0, 400.0, 120.0], [0.0, 0.0, 1.0]])
    Rt = np.hstack([np.eye(3), [[0.5], [0.2], [5.0]]])
    shrunk = np.hstack([np.eye(3) / np.sqrt(3), [[0.5], [0.2], [5.0]]])
    assert where_matrices_differ(K @ shrunk, K @ Rt) == "in its first, second and third columns"
    third = K @ Rt
    third[2, :3] += [0.3, -0.2, 0.5]   # (a tilted third row: small entries, wrong by as much as they are)
    assert where_matrices_differ(third, K @ Rt) == "in its third row"
    noisy = K @ Rt + 1e-13   # (rounding everywhere is no error of a row)
    noisy[0, 0] += 5.0
    assert where_matrices_differ(noisy, K @ Rt) == "in entry [0, 0] only"


def test_a_place_is_named_only_where_every_entry_outside_it_is_right():
    """A homography from a DLT taking a column of Vt: its translation entries carry most of the error, and its
    small entries are wrong too, by less than a tenth of it -- not "wrong in entries [0, 2], [1, 1], [2, 0]"
    (06l 08/02) nor "wrong in its second and third columns" (06o 08/02), every entry printed apart."""
    from autograder.engine.judges import where_matrices_differ

    got = [[-0.1149, 0.0041, -0.0261], [0.4562, -10.0535, -42.4938], [-35.7291, -0.8632, 1.0]]
    expected = [[0.6678, -0.0313, 35.0622], [-0.0595, 0.8957, -44.201], [-0.0002, -0.0006, 1.0]]
    assert where_matrices_differ(got, expected, up_to_scale=True) == "in every row and every column"
    got = [[0.6835, -1.1626, 369.7213], [-0.0142, 0.2405, 158.7888], [-0.0001, -0.0002, 1.0]]
    expected = [[0.6483, -0.1408, 53.9746], [-0.0877, 0.7759, 15.242], [-0.0005, -0.0002, 1.0]]
    assert where_matrices_differ(got, expected, up_to_scale=True) == "in every row and every column"
    two = np.eye(3)
    two[:, 2] = [5.0, -3.0, 1.0]   # (the third column alone wrong, the rest exact)
    assert where_matrices_differ(two, np.eye(3)) == "in its third column"
    one = np.eye(3)
    one[0, 2] = 5.0
    assert where_matrices_differ(one, np.eye(3)) == "in entry [0, 2] only"
    one[1, 0], one[2, 1] = 3.0, 2.0
    assert where_matrices_differ(one, np.eye(3)) == "in entries [0, 2], [1, 0], [2, 1]"


def test_a_statement_moved_so_that_a_step_goes_unread_is_no_fix():
    import ast

    from autograder.engine.mutants import repair

    source = textwrap.dedent("""
        import numpy as np

        def graded(K, R, t):
            R = np.asarray(R, dtype=np.float64)
            R = R / np.linalg.norm(R)
            extrinsic = np.hstack([R, t])
            return K @ extrinsic
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    moves = [m for m in student.mutants("graded") if m.edits[0][2] == "move" and student.fix(m) is not None
             and "extrinsic" in str(student.fix(m).changes)]
    assert moves and all(student.leaves_a_step_unused(m) for m in moves)
    assert not any(student.leaves_a_step_unused(m) for m in student.mutants("graded") if m.edits[0][2] != "move")


@pytest.mark.parametrize("source, by_svd", [
    # an SVD solve, denormalised with inverses of the normalising transforms
    ("def f(A, T1, T2):\n    _, _, Vt = np.linalg.svd(A)\n    F = Vt[-1].reshape(3, 3)\n"
     "    return np.linalg.inv(T2).T @ F @ np.linalg.inv(T1)\n", True),
    # 8 unknowns by the normal equations, the SVD only for rank 2 (third-party course code, audit of 2026-12-07)
    ("def f(A, b):\n    f = np.linalg.inv(A.T @ A + 1e-9) @ (A.T @ b)\n    U, S, Vt = np.linalg.svd(f.reshape(3, 3))\n"
     "    return U @ np.diag([S[0], S[1], 0]) @ Vt\n", False),
    ("def f(A, b):\n    f = np.linalg.inv(np.dot(A.T, A)).dot(A.T).dot(b)\n    return np.linalg.svd(f)\n", False),
    ("def f(A, b):\n    f = np.linalg.lstsq(A, b, rcond=None)[0]\n    return np.linalg.svd(f)\n", False),
])
def test_an_svd_beside_the_normal_equations_is_not_called_the_solve(source, by_svd):
    """"Your code solves by np.linalg.svd" (lab 10's and lab 11's hints on an entry fixed to 1) is said only of
    code whose least squares is not solved otherwise."""
    from autograder.labs.code_signs import SOLVES_BY_SVD

    assert bool(found(SOLVES_BY_SVD, source, "f")) == by_svd


@pytest.mark.parametrize("test, marks", [
    ("if d == 0:\n            best = cost", False),   # a running minimum started at d = 0 (course code)
    ("if x < d:\n            cost = 1e9", True),
    ("if d > x:\n            continue", True),
])
def test_a_test_of_d_against_a_number_is_no_mark_of_the_columns_without_a_partner(test, marks):
    """Lab 12's tip for matches left of the right image says "your code marks the columns without a partner" only
    of code that tests d against a column (third-party audit of 2026-12-07: `if d == 0:` was read as one)."""
    from autograder.labs.lab12 import _marks_left_border

    source = f"def f(left, right, n):\n    best = None\n    for d in range(n):\n        cost = left - right\n        {test}\n    return best\n"
    assert _marks_left_border(read_code(source).functions["f"]) == marks


def test_a_floor_division_is_named_as_such_not_by_a_change_that_keeps_it(tmp_path):
    """`s = (S[0] + S[1]) // 2` (E all zeros, blind set 07c lab11/04): `// 1` and `2 // (...)` give E's own scale
    exactly, by the floor of a sum near 1.41 being 1; the floor is the slip, `/ 2` the change told."""
    source = """
        def essential_8point(pts1, pts2, K1, K2):
            x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
            x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
            U, S, Vt = np.linalg.svd(_eight_point_core(x1, x2))
            s = (S[0] + S[1]) // 2
            return U @ np.diag([s, s, 0]) @ Vt
        """
    result = grade(mutant(tmp_path, "lab11_two_view", source), ["lab11.ex3"], pictures="none")
    failed = failing(result, "lab11.ex3")
    assert failed and all("to `(S[0] + S[1]) / 2`" in c.message for c in failed), [c.message for c in failed]


def test_a_tip_on_normalising_code_neither_blames_raw_coordinates_nor_lists_what_the_code_does(tmp_path):
    """A DLT whose v rows read -u * y (blind set 08b lab08/02), fitted on normalised points: the normalisation tip
    fires (its H is a little off on a far patch) and must say neither "with raw pixel coordinates ..." nor "check
    that each set has its own transform, and that it is undone" (tips are said for the code as failures are)."""
    folder = edited_reference(tmp_path, "lab08_homographies", ("-v * x, -v * y, -v]", "-v * x, -u * y, -v]"))
    result = grade(str(folder), ["lab08.ex2"], pictures="none")
    [tip] = [c for c in check_results(result, "lab08.ex2") if c.name == "homography_dlt normalises its points"]
    assert tip.status == "advice", (tip.status, tip.message)
    assert "raw pixel coordinates" not in tip.message and "check that" not in tip.hint, (tip.message, tip.hint)
    assert tip.hint.startswith("your code already normalises the points"), tip.hint


def test_a_squared_error_kept_in_a_name_is_told_with_the_bound_squared(tmp_path):
    """`sq_err = np.sum(d ** 2, axis=1)`, then `sq_err < threshold` (blind set 08c lab08/07, its function as written):
    the check names "the squared error is compared with the threshold"; beside it, a change of that kind
    (`threshold ** 2`, or the root taken) is told, not `np.sum` made `np.mean` (it halves the squares and passes the
    check by chance)."""
    source = """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            # RANSAC over 4-point samples, then a DLT refit on the inliers
            src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
            dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
            n = len(src)
            if n < 4:
                raise ValueError("need at least 4 correspondences")
            rng = np.random.default_rng(seed)
            best_mask, best_count = None, 0
            max_iters, it = 2000, 0
            while it < max_iters:
                it += 1
                idx = rng.choice(n, 4, replace=False)
                with np.errstate(all="ignore"):
                    H = homography_dlt(src[idx], dst[idx])
                    proj = transform_points(H, src)
                sq_err = np.sum((proj - dst) ** 2, axis=1)
                mask = sq_err < threshold
                count = int(mask.sum())
                if count > best_count:
                    best_mask, best_count = mask, count
                    w = count / n
                    needed = np.log(1 - 0.999) / np.log(max(1 - w ** 4, 1e-12))
                    max_iters = min(2000, int(np.ceil(needed)))
            if best_count < 4:
                return homography_dlt(src, dst), np.ones(n, dtype=bool)
            H = homography_dlt(src[best_mask], dst[best_mask])
            sq_err = np.sum((transform_points(H, src) - dst) ** 2, axis=1)
            inliers = sq_err < threshold
            if inliers.sum() >= 4:
                H = homography_dlt(src[inliers], dst[inliers])
            else:
                inliers = best_mask
            return H, inliers
        """
    result = grade(mutant(tmp_path, "lab08_homographies", source), ["lab08.ex4"], pictures="none")
    failed = failing(result, "lab08.ex4")
    assert any(c.mistake == "the squared error is compared with the threshold" for c in failed)
    # (a change told, where the search finds one in its time, is of those kinds: the bound squared, or the root of the
    # squares taken -- never the sum made a mean)
    told = [c.message for c in failed if "Trying small changes" in c.message]
    assert all("to `sq_err < threshold ** 2`" in m or "to `np.sqrt(np.sum(" in m for m in told), told


def test_a_panorama_at_half_brightness_is_told_its_levels_scaled_not_drawn_over(tmp_path):
    """A two-image sum divided by 2 everywhere (blind set 08d lab08/07): img1 is itself where img2 covers it too and
    half as bright where it alone does -- told as levels scaled (a blend's weights), not as "other content drawn over
    the rest"; and no change writing `/ 1.0` (a sum left undivided passes the geometry checks by chance)."""
    source = """
        _stitch_right = stitch
        def stitch(img1, img2):
            pts1, pts2 = match_features(img1, img2)
            H, _ = homography_ransac(pts2, pts1, threshold=3.0, seed=0)
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            c1 = np.array([[0, 0], [w1 - 1, 0], [w1 - 1, h1 - 1], [0, h1 - 1]], dtype=np.float64)
            c2 = transform_points(H, np.array([[0, 0], [w2 - 1, 0], [w2 - 1, h2 - 1], [0, h2 - 1]], dtype=np.float64))
            allc = np.vstack([c1, c2])
            x_min, y_min = np.floor(allc.min(axis=0)).astype(int)
            x_max, y_max = np.ceil(allc.max(axis=0)).astype(int)
            T = np.array([[1, 0, -x_min], [0, 1, -y_min], [0, 0, 1]], dtype=np.float64)
            size = (x_max - x_min + 1, y_max - y_min + 1)
            warped1 = apply_homography(img1, T, size).astype(np.float64)
            warped2 = apply_homography(img2, T @ H, size).astype(np.float64)
            m1 = apply_homography(np.ones((h1, w1), np.float32), T, size)
            m2 = apply_homography(np.ones((h2, w2), np.float32), T @ H, size)
            total = warped1 * m1[..., None] + warped2 * m2[..., None]
            count = m1 + m2
            pano = total / 2.0
            return np.clip(np.round(pano), 0, 255).astype(np.uint8)
        """
    result = grade(mutant(tmp_path, "lab08_homographies", source), ["lab08.ex5"], pictures="none")
    failed = failing(result, "lab08.ex5")
    assert failed and not any("other content is drawn over" in c.message for c in failed), [c.message for c in failed]
    assert any("its levels are scaled" in c.message for c in failed)
    assert not any("/ 1.0`" in c.message for c in failed), [c.message for c in failed]

