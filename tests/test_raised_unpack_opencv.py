"""Relayed exceptions and wrong results explained from the student's line (issue 35: "say which input
and why"; blind set 2026-11-29d found only the relayed error for three of them).

- an unpacking error (``height, width = image.shape`` given a colour image) names where the count
  comes from: the parameter's shape as given (:func:`autograder.engine.raised.unpacked`);
- an OpenCV method's error (FLANN's ``buildIndex_`` with ``type=0``) is tied to what the code
  builds (:mod:`autograder.engine.cv_raised`);
- an OpenCV call's outputs unpacked under each other's names (``rms, dist, K, ... =
  cv2.calibrateCamera(...)``) are named where the result made from them fails
  (:mod:`autograder.engine.outputs`).

Each is named only when it is true of the code and the inputs: look-alikes -- the value changed
before the line, a count the message contradicts, names that say nothing -- are not.
"""

from __future__ import annotations

import textwrap
from types import SimpleNamespace

import cv2
import numpy as np
import pytest

from autograder.engine import outputs, raised
from autograder.engine.checks import Fail, Trial, Verdict
from autograder.engine.cv_raised import (CROSS_CHECK_KNN, DETECT_FLOAT, DISPARITIES_NOT_16, FLANN_KDTREE_BINARY,
                                         FLANN_LSH_FLOAT, HAMMING_FLOAT, PASSED_AS_GIVEN, REMAP_TYPES)
from autograder.engine.hints import read_code
from autograder.engine.runner import _named_by_exception, _named_by_misread_output, grade
from conftest import check_results, mutant

COLOUR, GREY = np.zeros((12, 16, 3), np.uint8), np.zeros((12, 16), np.uint8)
TOO_MANY = "ValueError: too many values to unpack (expected 2)"
NOT_ENOUGH = "ValueError: not enough values to unpack (expected 3, got 2)"


def traceback_of(frames, message: str) -> str:
    """The worker's "Traceback (your code):" text for ``frames`` [(function, line)], outermost first."""
    lines = [f'  File "lab.py", line {line}, in {function}\n    ...' for function, line in frames]
    return "Traceback (your code):\n" + "\n".join(lines) + "\n" + message


def explain(source: str, frames, message: str, args=(), kwargs=None, called: str = ""):
    function = called or frames[0][0]
    return raised.explained(read_code(textwrap.dedent(source)), traceback_of(frames, message),
                            f"{function}() raised {message}", function, args, kwargs or {})


# ------------------------------------------------------------------ unpacking
UNPACKING = """
    import cv2
    import numpy as np

    def shear(image, s=0.5):
        height, width = image.shape
        return image

    def _size(img):
        h, w, c = img.shape
        return w, h

    def resize_half(image):
        w, h = _size(np.asarray(image, np.float32))
        return image

    def split(pts):
        x, y = pts
        return x

    def rows(pts):
        return [a for a, b in pts]

    def loop(pts, other):
        for i, (x, y) in enumerate(pts):
            pass
        return other

    def outlines(mask):
        _, contours, _ = cv2.findContours(mask, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)
        return contours

    def _three(x):
        if x is None:
            return 0, 0, 0
        return x, x, x

    def two_of_three(x):
        a, b = _three(x)
        return a

    def grey_first(image):
        image = image[..., None]
        height, width = image.shape
        return image

    def made_here(a, b):
        h, w = np.dstack([a, b]).shape
        return h

    def computed_for_helper(image):
        w, h = _size(image * 2)
        return image

    def converted(image):
        img = np.float32(image)
        h, w = img.shape
        return img

    def converted_twice(image, grey):
        img = np.float32(image)
        if grey:
            img = img[..., 0]
        h, w = img.shape
        return img

    def _some(x):
        if x:
            return 1, 2
        return 1, 2, 3

    def varied(x):
        a, b = _some(x)
        return a
"""
UNPACK_NAMED = {
    "a colour image's shape in two names": (
        [("shear", 6)], TOO_MANY, (COLOUR,), raised.COLOUR_SHAPE, "`image.shape` is (12, 16, 3)"),
    "a grey image's shape in three, in a helper given it as it came": (
        [("resize_half", 14), ("_size", 10)], NOT_ENOUGH, (GREY,), raised.GREY_SHAPE, "`img.shape` is (12, 16)"),
    "an (N, 2) array's rows": (
        [("split", 18)], TOO_MANY, (np.ones((10, 2)),), raised.ROWS_UNPACKED, "takes its 10 rows"),
    "rows of three in a comprehension": (
        [("rows", 22), ("<listcomp>", 22)], TOO_MANY, (np.ones((10, 3)),), raised.UNPACK_MISTAKE,
        "each row of `pts`, given with shape (10, 3) here, holds 3 values"),
    "rows of three under enumerate": (
        [("loop", 25)], TOO_MANY, (np.ones((10, 3)), 0), raised.UNPACK_MISTAKE, "holds 3 values"),
    "cv2.findContours's outputs counted as OpenCV 3's": (
        [("outlines", 30)], NOT_ENOUGH, (GREY,), raised.OUTPUTS_COUNTED, "cv2.findContours returns 2 values"),
    "a converted copy of a colour image": (
        [("converted", 57)], TOO_MANY, (COLOUR,), raised.COLOUR_SHAPE, "`img.shape` is (12, 16, 3)"),
    "a helper of the module returning three": (
        [("two_of_three", 39)], TOO_MANY, (1,), raised.UNPACK_MISTAKE, "your `_three` returns 3 values"),
}
UNPACK_NOT_NAMED = {
    "the image changed before the line": ([("grey_first", 44)], TOO_MANY, (GREY,)),
    "the count in the message is not the given shape's": ([("shear", 6)], TOO_MANY, (GREY,)),
    "an array made on the line": ([("made_here", 48)], TOO_MANY, (GREY, GREY)),
    "a helper given a computed value": ([("computed_for_helper", 52), ("_size", 10)], NOT_ENOUGH, (GREY,)),
    "a helper whose returns differ in length": ([("varied", 72)], TOO_MANY, (0,)),
    "a converted copy bound twice": ([("converted_twice", 64)], TOO_MANY, (COLOUR, False)),
    "the outermost frame is not the function called": ([("_size", 10)], NOT_ENOUGH, (GREY,), "resize_half"),
}


@pytest.mark.parametrize("name", sorted(UNPACK_NAMED))
def test_an_unpacking_error_names_where_its_count_comes_from(name):
    frames, message, args, mistake, words = UNPACK_NAMED[name]
    form = explain(UNPACKING, frames, message, args)
    assert form is not None and form.mistake == mistake, form
    assert words in form.sentence and f"line {frames[-1][1]}" in form.sentence


@pytest.mark.parametrize("name", sorted(UNPACK_NOT_NAMED))
def test_an_unpacking_error_the_code_does_not_explain_is_left_as_it_is(name):
    frames, message, args, *called = UNPACK_NOT_NAMED[name]
    assert explain(UNPACKING, frames, message, args, called="".join(called)) is None


def test_a_colour_image_unpacked_in_two_is_told_in_grading(tmp_path):
    source = """
        def shear(image, s=0.5):
            height, width = image.shape
            ys, xs = np.indices((height, width), dtype=np.float32)
            return cv2.remap(image, xs - np.float32(s) * ys, ys, cv2.INTER_LINEAR,
                             borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex4"], pictures="none")
    failed = [c for c in check_results(result, "lab07.ex4") if not c.passed]
    assert failed and any(c.mistake == raised.COLOUR_SHAPE and "take `image.shape[:2]`" in c.message
                          for c in failed), [c.message for c in failed]


SINGLE = """
    def rotate(image, angle, center=None):
        cx, cy = center
        return image

    def scale(image, s):
        sx, sy = s
        return image

    def recentred(image, center=None):
        if center is None:
            center = image.shape[1] / 2
        cx, cy = center
        return image
"""


@pytest.mark.parametrize("function, line, args, kwargs, kind, words", [
    ("rotate", 3, (COLOUR, 30), {}, "NoneType", "does not give `center`, so it holds its default, None"),
    ("scale", 7, (COLOUR, 1.5), {}, "float", "`s` is given a single value here (1.5)"),
])
def test_a_single_value_unpacked_names_the_parameter(function, line, args, kwargs, kind, words):
    message = f"TypeError: cannot unpack non-iterable {kind} object"
    form = explain(SINGLE, [(function, line)], message, args, kwargs)
    assert form is not None and form.mistake == raised.NOT_ITERABLE and words in form.sentence


@pytest.mark.parametrize("function, line, args, kwargs, kind", [
    ("rotate", 3, (COLOUR, 30), {"center": 4}, "NoneType"),      # given: not the default the message names
    ("scale", 7, (COLOUR, 2), {}, "float"),                       # an int given, the message says float
    ("recentred", 13, (COLOUR,), {}, "float"),                    # changed before the line
])
def test_a_single_value_the_inputs_do_not_show_is_not_named(function, line, args, kwargs, kind):
    message = f"TypeError: cannot unpack non-iterable {kind} object"
    assert explain(SINGLE, [(function, line)], message, args, kwargs) is None


# ------------------------------------------------------------------ OpenCV's errors of methods
def opencv_error(operation) -> str:
    """The message this OpenCV raises for ``operation``, as the worker relays it."""
    with pytest.raises(cv2.error) as caught:
        operation()
    return f"error: {caught.value}"


UINT8 = np.random.default_rng(0).integers(0, 255, (40, 32), dtype=np.uint8)
FLOAT32 = UINT8.astype(np.float32)
KD_ON_BINARY = opencv_error(lambda: cv2.FlannBasedMatcher(dict(algorithm=1, trees=5), {}).knnMatch(UINT8, UINT8, k=2))
LSH_ON_FLOAT = opencv_error(lambda: cv2.FlannBasedMatcher(
    dict(algorithm=6, table_number=6, key_size=12, multi_probe_level=1), {}).knnMatch(FLOAT32, FLOAT32, k=2))
HAMMING_ON_FLOAT = opencv_error(lambda: cv2.BFMatcher(cv2.NORM_HAMMING).match(FLOAT32, FLOAT32))
ys, xs = np.indices((8, 8))
REMAP_FLOAT64 = opencv_error(lambda: cv2.remap(COLOUR, xs - 0.5 * ys, ys.astype(float), cv2.INTER_LINEAR))
ONE_NEIGHBOUR = opencv_error(lambda: cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).knnMatch(UINT8, UINT8, k=2))
DETECT_ON_FLOAT = opencv_error(lambda: cv2.SIFT_create().detectAndCompute(np.zeros((40, 40), np.float32), None))
NUM_DISPARITIES = opencv_error(lambda: cv2.StereoBM_create(numDisparities=21, blockSize=9).compute(UINT8, UINT8))

MATCHING = """
    import cv2
    import numpy as np
    FLANN_INDEX_KDTREE = 1

    def orb_flann(a, b):
        orb = cv2.ORB_create()
        k1, d1 = orb.detectAndCompute(a, None)
        k2, d2 = orb.detectAndCompute(b, None)
        index = dict(algorithm=FLANN_INDEX_KDTREE, trees=5)
        matcher = cv2.FlannBasedMatcher(index, dict(checks=50))
        return matcher.knnMatch(d1, d2, k=2)

    def sift_lsh(a, b):
        sift = cv2.SIFT_create()
        k1, d1 = sift.detectAndCompute(a, None)
        k2, d2 = sift.detectAndCompute(b, None)
        matcher = cv2.FlannBasedMatcher({"algorithm": 6, "table_number": 6, "key_size": 12}, {})
        return matcher.knnMatch(d1, d2, k=2)

    def sift_hamming(a, b):
        sift = cv2.SIFT_create()
        k1, d1 = sift.detectAndCompute(a, None)
        k2, d2 = sift.detectAndCompute(b, None)
        return cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(d1, d2)

    def shear(image, s):
        h, w = image.shape[:2]
        ys, xs = np.indices((h, w))
        return cv2.remap(image, xs - s * ys, ys, cv2.INTER_LINEAR)

    def detect(image, other=None):
        grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) / 255.0
        return cv2.SIFT_create().detectAndCompute(grey, None)

    def l2_match(a, b):
        return cv2.BFMatcher(cv2.NORM_L2).match(a, b)

    def one_map(image, maps):
        return cv2.remap(image, maps, None, cv2.INTER_LINEAR)

    def detect_given(image, other=None):
        return cv2.SIFT_create().detectAndCompute(image, None)

    def ratio_cross_checked(a, b):
        matcher = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True)
        return [m for m, n in matcher.knnMatch(a, b, k=2) if m.distance < 0.75 * n.distance]

    def cross_checked_once(a, b):
        matcher = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True)
        return matcher.knnMatch(a, b, k=1, mask=a)

    def kd_tree(a, b):
        matcher = cv2.FlannBasedMatcher(dict(algorithm=1, trees=5), {})
        return matcher.knnMatch(a, b, k=2)

    def stereo_bm(left, right, max_disparity=20):
        matcher = cv2.StereoBM_create(numDisparities=max_disparity + 1, blockSize=9)
        return matcher.compute(left, right)

    def stereo_bm_rounded(left, right, max_disparity=20):
        matcher = cv2.StereoBM_create(numDisparities=16 * ((max_disparity + 15) // 16), blockSize=9)
        return matcher.compute(left, right)

    def detect_mean(image, other=None):
        grey = image.mean(axis=2) if image.ndim == 3 else image
        keypoints, descriptors = cv2.SIFT_create().detectAndCompute(grey, None)
        return keypoints, descriptors

    def detect_weighted(image, other=None):
        grey = image @ [0.114, 0.587, 0.299]
        return cv2.SIFT_create().detectAndCompute(grey, None)

    def detect_mean_converted(image, other=None):
        grey = image.mean(axis=2).astype(np.uint8)
        return cv2.SIFT_create().detectAndCompute(grey, None)
"""
OPENCV_NAMED = {
    "a KD-tree index for ORB's descriptors": (
        [("orb_flann", 12)], KD_ON_BINARY, FLANN_KDTREE_BINARY, ("KD-tree index", "line 11", "cv2.ORB_create's",
                                                                 "algorithm=6", "NORM_HAMMING")),
    "an LSH index for SIFT's descriptors": (
        [("sift_lsh", 19)], LSH_ON_FLOAT, FLANN_LSH_FLOAT, ("LSH index", "cv2.SIFT_create's", "algorithm=1")),
    "NORM_HAMMING for SIFT's descriptors": (
        [("sift_hamming", 25)], HAMMING_ON_FLOAT, HAMMING_FLOAT, ("NORM_HAMMING (line 25)", "cv2.NORM_L2")),
    "remap's maps of NumPy's arithmetic": (
        [("shear", 30)], REMAP_FLOAT64, REMAP_TYPES, ("`xs - s * ys` and `ys`", ".astype(np.float32)")),
    "a detector given an image the code divided": (
        [("detect", 34)], DETECT_ON_FLOAT, DETECT_FLOAT, ("a float array", "line 33")),
    "a detector given the mean of the colour channels": (
        [("detect_mean", 67)], DETECT_ON_FLOAT, DETECT_FLOAT, ("`image.mean(axis=2)`, line 66",)),
    "a detector given a grey image weighted by float numbers": (
        [("detect_weighted", 72)], DETECT_ON_FLOAT, DETECT_FLOAT, ("`image @ [0.114, 0.587, 0.299]`, line 71",)),
    "a KD-tree index and uint8 descriptors, no detector in sight": (
        [("kd_tree", 53)], KD_ON_BINARY, FLANN_KDTREE_BINARY, ("binary descriptors. Match",)),
    "StereoBM given max_disparity + 1 disparities": (
        [("stereo_bm", 59)], NUM_DISPARITIES, DISPARITIES_NOT_16, ("numDisparities=max_disparity + 1 (line 58)",
                                                                   "multiple of 16")),
    "two neighbours of a cross-checking matcher": (
        [("ratio_cross_checked", 47)], ONE_NEIGHBOUR, CROSS_CHECK_KNN, ("crossCheck=True (line 46)",
                                                                        "crossCheck=False")),
}
OPENCV_NOT_NAMED = {
    "the Hamming assertion where the code asks for L2": ([("l2_match", 37)], HAMMING_ON_FLOAT),
    "remap given one map": ([("one_map", 40)], REMAP_FLOAT64),
    "StereoBM's error where the code rounds to a multiple of 16": ([("stereo_bm_rounded", 63)], NUM_DISPARITIES),
    "a detector given the caller's image": ([("detect_given", 43)], DETECT_ON_FLOAT),
    "a detector given a mean converted to uint8": ([("detect_mean_converted", 76)], DETECT_ON_FLOAT),
    "FLANN's float32 error where the code builds a KD-tree": ([("kd_tree", 53)], LSH_ON_FLOAT),
    "the one-neighbour assertion where the code builds no cross-check": ([("kd_tree", 53)], ONE_NEIGHBOUR),
    "the one-neighbour assertion where one neighbour is asked (with a mask)": (
        [("cross_checked_once", 51)], ONE_NEIGHBOUR),
    "FLANN's uint8 error where the code builds an LSH index": ([("sift_lsh", 19)], KD_ON_BINARY),
}


@pytest.mark.parametrize("name", sorted(OPENCV_NAMED))
def test_an_opencv_error_is_tied_to_what_the_code_builds(name):
    frames, message, mistake, words = OPENCV_NAMED[name]
    form = explain(MATCHING, frames, message, (UINT8, UINT8))
    assert form is not None and form.mistake == mistake, form
    for word in words:
        assert word in form.sentence, (word, form.sentence)
    if "no detector" in name:
        assert "ORB" not in form.sentence.partition("Match")[0]   # no detector is named where none is used


@pytest.mark.parametrize("name", sorted(OPENCV_NOT_NAMED))
def test_an_opencv_error_the_code_does_not_explain_is_left_as_it_is(name):
    frames, message = OPENCV_NOT_NAMED[name]
    assert explain(MATCHING, frames, message, (UINT8, UINT8)) is None


def test_an_error_the_worker_explained_already_is_left_to_its_sentence():
    code = read_code(textwrap.dedent(MATCHING))
    message = f"cv2.remap needs ... (the worker's sentence)\nshear() raised {REMAP_FLOAT64}"
    assert raised.explained(code, traceback_of([("shear", 30)], REMAP_FLOAT64), message, "shear", (COLOUR, 0.5),
                            {}) is None


def test_the_blind_sets_flann_kdtree_for_orb_is_named():
    source = open("benchmarks/blind_mistakes/2026-11-29d/lab08_homographies/"
                  "04_match_features_flann_kdtree_for_orb.py").read()
    line = next(n for n, text in enumerate(source.splitlines(), 1) if "matcher.knnMatch" in text)
    form = raised.explained(read_code(source), traceback_of([("match_features", line)], KD_ON_BINARY),
                            f"match_features() raised {KD_ON_BINARY}", "match_features", (COLOUR, COLOUR),
                            {"method": "orb"})
    assert form is not None and form.mistake == FLANN_KDTREE_BINARY and "cv2.ORB_create's" in form.sentence


# ------------------------------------------------------------------ OpenCV's outputs out of order
ORDERS = """
    import cv2
    import numpy as np

    def calibrate(objects, images, size):
        rms, dist, K, rvecs, tvecs = cv2.calibrateCamera(objects, images, size, None, None)
        return K, dist.ravel()[:5], float(rms)

    def calibrate_right(objects, images, size):
        ret, mtx, dist, rvecs, tvecs = cv2.calibrateCamera(objects, images, size, None, None)
        return mtx, dist.ravel()[:5], float(ret)

    def calibrate_unnamed(objects, images, size):
        a, b, c, d, e = cv2.calibrateCamera(objects, images, size, None, None)
        return b, c.ravel(), d

    def rectify(K1, d1, K2, d2, size, R, T):
        R1, P1, R2, P2, *_ = cv2.stereoRectify(K1, d1, K2, d2, size, R, T)
        H1 = P1[:, :3] @ R1 @ np.linalg.inv(K1)
        return H1

    def pose(E, a, b, K):
        _, t, R, _ = cv2.recoverPose(E, a, b, K)
        return R, t

    def homography(a, b):
        mask, H = cv2.findHomography(a, b, cv2.RANSAC)
        return H

    def unused(a, b):
        mask, H = cv2.findHomography(a, b, cv2.RANSAC)
        return np.eye(3)

    def _pose(E, a, b, K):
        n, t, R, mask = cv2.recoverPose(E, a, b, K)
        return R

    def pose_through_helper(E, a, b, K):
        R = _pose(E, a, b, K)
        return R / np.linalg.det(R)

    def ambiguous(E, a, b, K):
        n, inliers, R, t = cv2.recoverPose(E, a, b, K)
        return inliers

    def rotation(rvec):
        _, R = cv2.Rodrigues(rvec)
        return R

    def calibrate_rotated(objects, images, size):
        K, dist, rvecs, tvecs, rms = cv2.calibrateCamera(objects, images, size, None, None)
        return K
"""
ORDER_NAMED = {   # function, result index and count (None: any), the misread variable
    "calibrateCamera's K at the distortion's place": ("calibrate", 0, 3, "`K` takes its 3rd output"),
    "calibrateCamera's dist at K's place": ("calibrate", 1, 3, "`dist` takes its 2nd output"),
    "stereoRectify's P1 at R2's place, returned through a product": ("rectify", None, None, "`P1` takes its 2nd"),
    "recoverPose's R and t exchanged": ("pose", None, None, "recoverPose returns (retval, R, t, mask)"),
    "findHomography's mask first": ("homography", None, None, "`H` takes its 2nd output, the inlier mask"),
    "in a helper whose return the result is made of": ("pose_through_helper", None, None, "your `_pose` unpacks"),
    "the place of the output named thrown away": ("rotation", None, None, "`R` takes its 2nd output, the Jacobian"),
    "every name one place early": ("calibrate_rotated", None, None, "`K` takes its 1st output, the RMS"),
}
ORDER_NOT_NAMED = {
    "the documented order": ("calibrate_right", None, None),
    "names that read as no output, or one that no other name shows misplaced (d)": ("calibrate_unnamed", None, None),
    "a result made of the right output only": ("calibrate", 2, 3),
    "a misread output the result is not made of": ("unused", None, None),
    "a name that reads as two outputs (inliers: a count or a mask)": ("ambiguous", None, None),
}


@pytest.mark.parametrize("name", sorted(ORDER_NAMED))
def test_outputs_unpacked_out_of_order_are_named(name):
    function, index, count, words = ORDER_NAMED[name]
    found = outputs.told(read_code(textwrap.dedent(ORDERS)), function, index, count)
    assert found is not None and found[1] == outputs.MISTAKE and words in found[0], found


@pytest.mark.parametrize("name", sorted(ORDER_NOT_NAMED))
def test_outputs_whose_names_show_no_mismatch_are_not_named(name):
    function, index, count = ORDER_NOT_NAMED[name]
    assert outputs.told(read_code(textwrap.dedent(ORDERS)), function, index, count) is None


class _StandIn:
    """What Trial.expect_array and the runner read of a trial: its calls and the module's code."""

    def __init__(self, tmp_path, source: str, calls, served=()):
        (tmp_path / "lab.py").write_text(textwrap.dedent(source))
        self.sandbox = SimpleNamespace(submission_dir=str(tmp_path))
        self.lab = SimpleNamespace(module="lab")
        self.calls = calls
        self.served = list(served)

    fail = Trial.fail
    _why_misread = Trial._why_misread
    _why_swapped = Trial._why_swapped
    _why_none = Trial._why_none
    expect_array = Trial.expect_array


def test_a_wrong_shaped_result_made_from_a_misread_output_is_named(tmp_path):
    dist, K = np.zeros((1, 5)), np.eye(3)
    answer = (dist, K.ravel()[:5], 0.3)   # what calibrate returns, its K being the distortion
    trial = _StandIn(tmp_path, ORDERS, [("calibrate", (), {}, answer)])
    with pytest.raises(Fail) as failed:
        trial.expect_array(answer[0], "calibrate(...)[0] (K)", shape=(3, 3))
    assert failed.value.mistake == outputs.MISTAKE
    assert "returned an array of shape (1, 5); expected (3, 3): cv2.calibrateCamera returns (rms, K, dist" \
        in failed.value.message
    served = _StandIn(tmp_path, ORDERS, [], served=[("calibrate", (), {}, answer)])   # from another check's call
    with pytest.raises(Fail) as failed:
        served.expect_array(answer[0], "calibrate(...)[0] (K)", shape=(3, 3))
    assert failed.value.mistake == outputs.MISTAKE
    good = (np.zeros((1, 5)), np.zeros(5), 0.3)
    trial.calls = [("calibrate_right", (), {}, good)]
    with pytest.raises(Fail) as failed:
        trial.expect_array(good[0], "calibrate(...)[0] (K)", shape=(3, 3))
    assert failed.value.mistake != outputs.MISTAKE   # shaped wrong for another reason: not said


def test_a_failed_value_check_is_told_the_misread_output(tmp_path):
    trial = _StandIn(tmp_path, ORDERS, [("pose", (), {}, (np.eye(3), np.zeros(3)))])
    told = _named_by_misread_output(Verdict(0.0, "pose() returned a rotation 90 degrees off"), trial)
    assert told.mistake == outputs.MISTAKE and told.message.startswith("pose() returned a rotation 90 degrees off. "
                                                                       "Reading your code: cv2.recoverPose returns")
    trial.calls = [("calibrate_right", (), {}, None)]
    assert _named_by_misread_output(Verdict(0.0, "K is off"), trial).mistake == ""


def test_lab12_reads_stereo_rectify_out_of_order_with_the_shared_table():
    from autograder.labs.lab12 import _outputs_out_of_order

    code = read_code(textwrap.dedent(ORDERS))
    assert _outputs_out_of_order(code.functions["rectify"])
    assert not _outputs_out_of_order(code.functions["pose"])   # another call's order: not stereoRectify's
    right = read_code("import cv2\ndef f(a):\n    R1, R2, P1, P2, Q, r1, r2 = cv2.stereoRectify(*a)\n    return P1\n")
    assert not _outputs_out_of_order(right.functions["f"])


def test_a_slice_of_the_outputs_is_read_from_where_it_starts():
    sliced = read_code("import cv2\ndef f(a):\n    R1, P1, R2, P2 = cv2.stereoRectify(*a)[:4]\n    return P1\n"
                       "def g(a):\n    K, dist = cv2.calibrateCamera(*a)[1:3]\n    return K\n"
                       "def h(a):\n    dist, K = cv2.calibrateCamera(*a)[1:3]\n    return K\n")
    assert outputs.told(sliced, "f") is not None and outputs.told(sliced, "g") is None
    assert "your `K` takes its 2nd output" not in outputs.told(sliced, "h")[0]
    assert "your `K` takes its 3rd output" in outputs.told(sliced, "h")[0]


# ------------------------------------------------------------------ which input reached OpenCV as it came
QUAD = """
    import cv2
    import numpy as np

    def warp_quad(image, corners, target):
        M = cv2.getPerspectiveTransform(corners, target)
        return cv2.warpPerspective(image, M, (100, 100))

    def warp_quad_converted(image, corners, target):
        corners = np.asarray(corners, np.float64)
        M = cv2.getPerspectiveTransform(corners, target)
        return cv2.warpPerspective(image, M, (100, 100))

    def warp_quad_helper(image, corners, target):
        return _quad(np.asarray(corners, np.float64), target)

    def _quad(corners, target):
        return cv2.getPerspectiveTransform(corners, target)
"""
CORNERS = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], np.float64)


def worker_message(function: str) -> str:
    """The message the worker relays for getPerspectiveTransform given float64 corners: its sentence first."""
    from autograder.sandbox import beginner

    error = opencv_error(lambda: cv2.getPerspectiveTransform(CORNERS, CORNERS + 1))
    sentence = beginner.explain_opencv("cv2.getPerspectiveTransform", error, [("src", CORNERS), ("dst", CORNERS + 1)])
    assert sentence.startswith("cv2.getPerspectiveTransform needs src")
    return f"{sentence}\n{function}() raised {error}"


def test_the_callers_input_reaching_opencv_as_it_came_is_named():
    form = raised.explained(read_code(textwrap.dedent(QUAD)), traceback_of([("warp_quad", 6)], "error: ..."),
                            worker_message("warp_quad"), "warp_quad", (COLOUR, CORNERS, CORNERS + 1), {})
    assert form is not None and form.mistake == PASSED_AS_GIVEN
    assert "that src is `corners` (line 6) as your `warp_quad` was given it (shape (4, 2), float64)" in form.sentence


@pytest.mark.parametrize("frames, function", [
    ([("warp_quad_converted", 12)], "warp_quad_converted"),            # a converted copy reached it
    ([("warp_quad_helper", 16), ("_quad", 19)], "warp_quad_helper"),   # a helper's parameter: maybe converted
])
def test_a_converted_input_reaching_opencv_is_not_said_to_be_the_callers(frames, function):
    form = raised.explained(read_code(textwrap.dedent(QUAD)), traceback_of(frames, "error: ..."),
                            worker_message(function), function, (COLOUR, CORNERS, CORNERS + 1), {})
    assert form is None


def test_the_workers_sentence_leads_and_the_input_follows_it(tmp_path):
    trial = _StandIn(tmp_path, QUAD, [])
    message = worker_message("warp_quad")
    trial.raised = ("warp_quad", (COLOUR, CORNERS, CORNERS + 1), {}, message)
    told = _named_by_exception(Verdict(0.0, message), trial, traceback_of([("warp_quad", 6)], "error: ..."))
    first = told.message.splitlines()[0]
    assert told.mistake == PASSED_AS_GIVEN and first.startswith("cv2.getPerspectiveTransform needs src")
    assert first.endswith("np.float32(src). That src is `corners` (line 6) as your `warp_quad` was given it (shape "
                          "(4, 2), float64): inputs may come in that form, so convert `corners` in your function "
                          "before it reaches cv2.getPerspectiveTransform.")
    assert told.message.splitlines()[1].startswith("warp_quad() raised error: OpenCV")


def test_a_methods_outputs_are_read_and_written_as_a_method():
    code = read_code("import cv2\ndef f(a):\n    des, kp = cv2.SIFT_create().detectAndCompute(a, None)\n    return kp\n")
    sentence, _ = outputs.told(code, "f")
    assert sentence.startswith(".detectAndCompute returns (keypoints, descriptors)") and "cv2.detect" not in sentence


def test_opencv_s_svd_unpacked_in_numpy_s_order_is_misread_and_its_downstream_repair_not_told(tmp_path):
    """cv2.SVDecomp answers (w, u, vt), np.linalg.svd (u, s, vt): `u, w, vt = cv2.SVDecomp(F)` names the
    singular values u. The code reading says so; a repair reading `w[:, -1]` for `u[:, -1]` mends the one
    use downstream and is not told beside it."""
    code = read_code(textwrap.dedent("""
        def epipoles(F):
            u, w, vt = cv2.SVDecomp(F)
            return vt[-1], u[:, -1]
        """))
    assert [m.name for m in outputs.misread(code.functions["epipoles"])] == ["u", "w"]
    folder = mutant(tmp_path, "lab11_two_view", '''
def epipoles(F):
    F = np.asarray(F, dtype=np.float64)
    u, w, vt = cv2.SVDecomp(F)
    e1 = vt[-1]
    e2 = u[:, -1]
    return e1, e2
''')
    messages = [c.message for c in check_results(grade(str(folder), ["lab11.ex5"]), "lab11.ex5") if c.score < c.max_score]
    assert messages and all("cv2.SVDecomp returns (w, u, vt)" in m for m in messages), messages
    assert not any("w[:, -1]" in m for m in messages)
