"""The ends of every range are in the scenes: an off-by-one loop loses points.

For each parameter with a range -- the disparities ``0..max_disparity`` of block matching
(SSD and NCC) and of the scanline DP, the images of a sequence (``track_pose``'s frames,
``stitch_many``'s images), the pixels ``0..W-1`` of an image (``draw_points``) -- the
scenes put content at both ends, and a realistic off-by-one implementation (the reference
with one function redefined) loses points with a diagnosis that says which end; the
reference keeps full marks.

Ranges with no end to cover, and why: RANSAC's iterations (the API gives no count: a
loop one short draws other samples, not a wrong answer), ``calibrate``'s views (leaving one
out still calibrates), ``simulate_structured_light``'s projector column 0 (stripe 0, black in
every pattern: its last column, which only a pixel with a disparity below 0.5 px reaches, is
judged on a far wall);
the ends of the other ranges were covered already (``affine_lstsq`` and the DLT with their
minimum number of points, ``triangulate`` with one point, ``fundamental_8point`` with
exactly 8, the ``gray_code_patterns`` property from width 1 and one bit, the epipoles at
infinity).
"""

from __future__ import annotations

import pytest

from autograder.engine.runner import grade
from conftest import REFERENCE, assert_diagnosed, check_results, edited_reference, mutant

SSD_VOLUME = """
    def _ssd_volume(left, right, max_disparity, block_size):
        height, width = left.shape
        costs = np.full((max_disparity + 1, height, width), np.inf)
        for d in {search}:
            squared = (left - _shift_right(right, d)) ** 2
            costs[d] = _box_mean(squared, block_size)
            costs[d, :, :d] = np.inf
        return costs
    """

NCC_VOLUME = """
    def _ncc_volume(left, right, max_disparity, block_size):
        height, width = left.shape
        mean_l = _box_mean(left, block_size)
        std_l = np.sqrt(np.maximum(_box_mean(left * left, block_size) - mean_l ** 2, 0.0))
        costs = np.full((max_disparity + 1, height, width), np.inf)
        for d in {search}:
            shifted = _shift_right(right, d)
            mean_r = _box_mean(shifted, block_size)
            std_r = np.sqrt(np.maximum(_box_mean(shifted * shifted, block_size) - mean_r ** 2, 0.0))
            covariance = _box_mean(left * shifted, block_size) - mean_l * mean_r
            denominator = std_l * std_r
            ncc = np.divide(covariance, denominator, out=np.zeros_like(covariance),
                            where=denominator > 1e-6)
            costs[d] = -ncc
            costs[d, :, :d] = np.inf
        return costs
    """

STOPS_SHORT = "range(0, max_disparity)"          # never tries d = max_disparity
STARTS_AT_ONE = "range(1, max_disparity + 1)"    # never tries d = 0

# name -> (module, exercise, the wrong code, fragments the diagnosis must contain)
RANGE_ENDS = {
    "block matching (SSD) that stops at max_disparity - 1": (
        "lab12_stereo", "lab12.ex4", SSD_VOLUME.format(search=STOPS_SHORT),
        ["the search stops at max_disparity - 1"]),
    "block matching (SSD) that starts at d = 1": (
        "lab12_stereo", "lab12.ex4", SSD_VOLUME.format(search=STARTS_AT_ONE),
        ["wall at infinity", "must include d = 0"]),
    "block matching (NCC) that stops at max_disparity - 1": (
        "lab12_stereo", "lab12.ext1", NCC_VOLUME.format(search=STOPS_SHORT),
        ["the search stops at max_disparity - 1"]),
    "block matching (NCC) that starts at d = 1": (
        "lab12_stereo", "lab12.ext1", NCC_VOLUME.format(search=STARTS_AT_ONE),
        ["wall at infinity", "must include d = 0"]),
    "dp_stereo with disparities 0..max_disparity - 1": ("lab12_stereo", "lab12.ex5", """
        _dp_stereo = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            return _dp_stereo(left, right, max_disparity - 1, block_size, smoothness)
        """, ["the search stops at max_disparity - 1"]),
    "track_pose that skips the first frame": ("lab10_camera2", "lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = [np.full(6, np.nan)]
            for i in range(1, len(frames)):
                rvec, tvec, _ = estimate_pose(frames[i], pattern_size, square_size, K, dist)
                rows.append(np.concatenate([rvec, tvec]))
            return np.array(rows, dtype=np.float64).reshape(-1, 6)
        """, ["frame 0 shows the whole board", "nan"]),
    "track_pose that never estimates the last frame": ("lab10_camera2", "lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = []
            for i in range(len(frames) - 1):
                rvec, tvec, _ = estimate_pose(frames[i], pattern_size, square_size, K, dist)
                rows.append(np.concatenate([rvec, tvec]))
            rows.append(np.full(6, np.nan))
            return np.array(rows, dtype=np.float64).reshape(-1, 6)
        """, ["frame 4 shows the whole board", "nan"]),
    "stitch_many that leaves out the last image": ("lab08_homographies", "lab08.ext2", """
        _stitch_many = stitch_many
        def stitch_many(images):
            return _stitch_many(list(images)[:-1])
        """, ["the last one, is left out"]),
    "stitch_many that leaves out the first image": ("lab08_homographies", "lab08.ext2", """
        _stitch_many = stitch_many
        def stitch_many(images):
            return _stitch_many(list(images)[1:])
        """, ["the first one, is left out"]),
    "draw_points that leaves out the image's border": ("lab09_camera", "lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            h, w = image.shape[:2]
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if 0 < x < w - 1 and 0 < y < h - 1:
                    cv2.circle(out, (int(round(x)), int(round(y))), int(radius),
                               tuple(int(c) for c in color), thickness=-1)
            return out
        """, ["on the image's border"]),
    "simulate_structured_light that takes the last projector column as off the projector": (
        "lab12_stereo", "lab12.ex6", """
        _simulate = simulate_structured_light
        def simulate_structured_light(depth, f, baseline, n_bits):
            images = _simulate(depth, f, baseline, n_bits)
            depth = np.asarray(depth, dtype=np.float64)
            u = np.arange(depth.shape[1])[None, :]
            with np.errstate(divide="ignore", invalid="ignore"):
                column = np.floor(u - f * baseline / depth + 0.5)
            images[:, column == depth.shape[1] - 1] = 0
            return images
        """, ["projector's last column (width - 1) lights nothing"]),
}


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(RANGE_ENDS))
def test_an_off_by_one_loses_points_at_the_end_it_misses(tmp_path, name):
    module, exercise, source, fragments = RANGE_ENDS[name]
    result = grade(mutant(tmp_path, module, source), [exercise], pictures="none")
    assert_diagnosed(result, exercise, *fragments)


@pytest.mark.slow
def test_the_reference_keeps_full_marks_where_the_ends_are_judged():
    exercises = sorted({exercise for _, exercise, _, _ in RANGE_ENDS.values()})
    result = grade(REFERENCE, exercises, pictures="none")
    for exercise in exercises:
        checks = check_results(result, exercise)
        assert all(c.passed or c.max_score == 0 for c in checks), \
            [(c.name, c.message) for c in checks if not c.passed]


def test_the_range_ends_scene_reaches_both_ends():
    """The premise: pixels at d = 0 and at d = max_disparity, right of the search band."""
    from fixtures import lab12

    for key, block_size in (("zero_disparity", 9), ("weak_texture", 5)):
        scene = lab12.scene(key)
        far, near = lab12.far_and_near(lab12.band(scene.judged, scene.max_disparity, block_size))
        assert lab12.top_of_range(near, scene.max_disparity).sum() > 1000, key
        if key == "zero_disparity":
            assert far.sum() > 1000


@pytest.mark.slow
def test_a_loop_over_a_count_written_in_the_code_is_told_so(tmp_path):
    """stitch_many's loop `for k in range(3)` given four images: the last is left out, told as a count
    written in the code (read), with range(len(images)) the change -- never range(4), wrong for five."""
    folder = edited_reference(tmp_path, "lab08_homographies", ("for k in range(len(images)):", "for k in range(3):"))
    result = grade(folder, ["lab08.ext2"], pictures="none")
    assert_diagnosed(result, "lab08.ext2", "the last one, is left out: the loop over the images runs a fixed number of "
                     "times", "your code loops over `range(3)`", "`range(3)` to `range(len(images))`")


@pytest.mark.parametrize("body, told", [
    # the reference's loop over the images, counted by a number: it grows the list of maps
    ("for k in range(3):\n    H = np.eye(3)\n    if k > r:\n        H = step[k - 1] @ H\n    homographies.append(H)", True),
    ("for k in range(3):\n    warped.append(cv2.warpPerspective(images[k], Hs[k], size))", True),
    # a colour loop of three turns in a four-image stitch: not the loop over the images
    ("planes = cv2.split(panorama)\nfor c in range(3):\n    planes[c] = np.clip(planes[c] * gain, 0, 255)", False),
    ("for c in range(3):\n    out[:, :, c] = blend(a[:, :, c], b[:, :, c])", False),
    ("for k in range(3):\n    total = total + k", False),
])
def test_a_loop_counted_by_a_number_is_told_only_when_it_reaches_the_images(body, told):
    import ast
    import textwrap

    from autograder.labs.lab08 import _loop_counted

    source = ("def stitch_many(images):\n    homographies, warped, Hs = [], [], []\n"
              + textwrap.indent(body, "    ") + "\n    return images\n")
    function = ast.parse(source).body[0]
    assert bool(_loop_counted(3).found([function])) is told
