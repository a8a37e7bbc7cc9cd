"""A beginner's mistakes get a sentence before the library's trace (issue 27).

OpenCV's own errors are raised here by calling it wrongly, as students do, and the
sentence :mod:`autograder.sandbox.beginner` gives for each is checked for what it must
name: the function, the argument, what it got, and the fix. End to end, graded
submissions with the issue's integer matrix, ``image[x, y]``, a rotation matrix
built as integers and an RGB result get that sentence first; what a student's
code does with OpenCV (results, caught errors, forbidden functions) is unchanged.
"""

from __future__ import annotations

import textwrap

import cv2
import numpy as np
import pytest

from autograder.sandbox import beginner
from autograder.engine.checks import Fail, Trial
from autograder.engine.registry import select
from autograder.engine.runner import grade
from conftest import mutant

IMAGE = np.zeros((40, 60, 3), np.uint8)
GREY = np.zeros((40, 60), np.uint8)


def sentence(function_name: str, *args, **kwargs) -> str:
    """The sentence for calling ``cv2.<function_name>`` so, as the worker's watched OpenCV gives it."""
    watched = beginner._watched(getattr(cv2, function_name), f"cv2.{function_name}")  # noqa: SLF001
    with pytest.raises(cv2.error) as raised:
        watched(*args, **kwargs)
    return beginner.sentence_of(raised.value)


CASES = [
    # (function, args, kwargs, what the sentence must say)
    ("warpAffine", (IMAGE, np.array([[1, 0, 5], [0, 1, 3]]), (60, 40)), {},
     ["cv2.warpAffine needs M as a float32 or float64 matrix", "yours is int64", "dtype=float"]),
    ("warpAffine", (IMAGE, np.eye(3), (60, 40)), {},
     ["cv2.warpAffine needs M of shape (2, 3); yours is (3, 3)", "M[:2]"]),
    ("warpPerspective", (IMAGE, np.eye(3)[:2], (60, 40)), {},
     ["cv2.warpPerspective needs M of shape (3, 3); yours is (2, 3)", "[0, 0, 1]"]),
    ("warpPerspective", (IMAGE, np.eye(3, dtype=int), (60, 40)), {}, ["float32 or float64", "int64"]),
    ("warpAffine", (IMAGE.astype(np.int64), np.eye(3)[:2], (60, 40)), {},
     ["cannot work on src, a int64 image", "astype(np.uint8)"]),
    ("warpAffine", (IMAGE, np.eye(3)[:2], (60.0, 40)), {}, ["dsize as whole numbers", "(width, height)", "60.0"]),
    ("warpAffine", (None, np.eye(3)[:2], (60, 40)), {}, ["got None for src", "cv2.imread"]),
    ("warpAffine", ([[1, 2], [3, 4]], np.eye(3)[:2], (60, 40)), {}, ["needs a numpy array for src; yours is a list, [[1, 2], [3, 4]]", "np.asarray"]),
    ("circle", (IMAGE, (12.5, 20.0), 3, (0, 0, 255)), {},
     ["cv2.circle needs center as whole numbers, pixel coordinates", "(12.5, 20.0)", "int(round(x))"]),
    ("circle", (IMAGE, (12, 20), 2.5, (0, 0, 255)), {}, ["whole number for radius", "2.5"]),
    ("line", (IMAGE, (np.float64(1.5), 2), (3, 4), (255, 0, 0)), {}, ["pt1 as whole numbers", "1.5"]),
    ("line", (IMAGE, (0, 10 ** 15), (3, 4), (255, 0, 0)), {},
     ["pt1 as whole numbers within OpenCV's int range", "1000000000000000", "cv2.clipLine"]),
    ("circle", (IMAGE, (1, 2, 3), 2, (255, 0, 0)), {}, ["center as 2 numbers; yours has 3"]),
    ("cvtColor", (GREY, cv2.COLOR_BGR2GRAY), {}, ["cannot convert src with 1 channel", "already grey"]),
    ("cvtColor", (IMAGE.astype(np.int64), cv2.COLOR_BGR2GRAY), {}, ["int64 image", "astype"]),
    ("getPerspectiveTransform", (np.zeros((4, 2)), np.zeros((4, 2))), {},
     ["exactly 4 points of 2 float32 coordinates", "float64", "np.float32(src)"]),
    ("perspectiveTransform", (np.zeros((4, 2)), np.eye(3)), {}, ["(N, 1, 2)", "reshape(-1, 1, 2)"]),
    ("findHomography", (np.zeros((3, 2)), np.zeros((3, 2))), {}, ["at least 4 point pairs; yours has 3"]),
    ("Rodrigues", (np.zeros((3, 3), int),), {}, ["float", "int64"]),
    ("imshow", ("result", IMAGE), {}, ["cv2.imshow opens a window", "without a screen", "plt.imshow"]),
    ("GaussianBlur", (GREY, (4, 4), 0), {}, ["odd, positive kernel size; yours is (4, 4)"]),
    ("triangulatePoints", (np.eye(3, 4), np.eye(3, 4), np.zeros((2, 5), int), np.zeros((2, 5), int)), {},
     ["as float32 or float64; yours are int64"]),
    # sizes one argument must have from another, and point arrays OpenCV cannot read as points
    ("pyrUp", (np.zeros((30, 40), np.float32),), {"dstsize": (60, 80)},
     ["doubles its image", "within a pixel of (80, 60)", "(60, 80)", "the other order"]),
    ("pyrDown", (np.zeros((30, 40), np.float32),), {"dstsize": (40, 30)},
     ["halves its image", "(20, 15)", "the size of src itself"]),
    ("add", (np.zeros((40, 60), np.float32), np.zeros((40, 61), np.float32)), {},
     ["the same shape", "(40, 60)", "(40, 61)"]),
    ("subtract", (IMAGE, GREY), {}, ["the same shape (size and channels)", "(40, 60, 3)", "(40, 60)"]),
    ("projectPoints", (np.zeros((5, 2)), np.zeros(3), np.zeros(3), np.eye(3), np.zeros(5)), {},
     ["objectPoints as N points of 3 coordinates", "(5, 2)"]),
    ("solvePnP", (np.random.default_rng(0).random((3, 3)), np.random.default_rng(1).random((3, 2)), np.eye(3), None),
     {}, ["at least 4 object points", "(3, 3)", "(3, 2)"]),
    ("calibrateCamera", (np.zeros((10, 3), np.float32), np.zeros((10, 2), np.float32), (80, 60), None, None), {},
     ["a list of views", "[objectPoints]"]),
    ("triangulatePoints", (np.eye(3), np.eye(3), np.zeros((2, 5)), np.zeros((2, 5))), {},
     ["projMatr1 of shape (3, 4); yours is (3, 3)"]),
    ("findEssentialMat", (np.random.default_rng(0).random((10, 2)), np.random.default_rng(1).random((10, 2)),
                          np.eye(2)), {}, ["cameraMatrix of shape (3, 3)", "(2, 2)"]),
    ("copyMakeBorder", (GREY, -1, 2, 2, 2, cv2.BORDER_CONSTANT), {}, ["borders of 0 pixels or more", "top=-1"]),
    ("boxFilter", (GREY, -1, (0, 5)), {}, ["kernel size of at least 1", "(0, 5)"]),
    # a pair given inside a size (`dsize if dsize else w, h`): no number to round
    ("warpAffine", (IMAGE, np.eye(3)[:2], ((60, 40), 40)), {}, ["dsize as 2 numbers", "((60, 40), 40)",
                                                               "a sequence inside the sequence"]),
    # a grey float mask: only its dtype is converted (no colour conversion of a one-channel array)
    ("distanceTransform", (np.zeros((40, 60)), cv2.DIST_L2, 3), {}, ["grey uint8 image", "np.clip(x, 0, 255)"]),
    # a weight per pixel given where one number weighs the whole image (a mask level as addWeighted's alpha)
    ("addWeighted", (IMAGE.astype(np.float32), np.full((40, 60, 1), 0.5, np.float32), IMAGE.astype(np.float32), 0.5,
                     0), {}, ["needs one number for alpha", "(40, 60, 1)", "multiply the arrays by it"]),
]


@pytest.mark.parametrize("function, args, kwargs, words", CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_an_opencv_error_gets_a_sentence_naming_the_argument_and_the_fix(function, args, kwargs, words):
    said = sentence(function, *args, **kwargs)
    assert said.startswith(f"cv2.{function}"), said
    for word in words:
        assert word in said, (word, said)
    assert "\n" not in said and "Assertion" not in said


def test_an_error_of_an_opencv_method_is_explained_from_its_message():
    stereo = cv2.StereoBM_create(16, 5)
    with pytest.raises(cv2.error) as raised:
        stereo.compute(GREY.astype(np.float64), GREY.astype(np.float64))
    said = beginner.sentence_of(raised.value)
    assert said.startswith("OpenCV's compute needs grey uint8 images"), said
    for stereo, left, right, words in [(cv2.StereoBM_create(16, 14), GREY, GREY, "blockSize odd, within 5..255"),
                                       (cv2.StereoBM_create(16, 15), GREY, GREY[:, 1:], "images of the same size")]:
        with pytest.raises(cv2.error) as raised:
            stereo.compute(left, right)
        assert words in beginner.sentence_of(raised.value), beginner.sentence_of(raised.value)
    matcher = cv2.BFMatcher(cv2.NORM_L2)
    with pytest.raises(cv2.error) as raised:
        matcher.match(np.zeros((5, 32), np.float32), np.zeros((5, 64), np.float32))
    assert "descriptors of one type and length" in beginner.sentence_of(raised.value)


def test_watching_opencv_changes_nothing_the_students_code_sees():
    class Library:  # a stand-in for the cv2 module, with two of its functions
        warpAffine, add, error = cv2.warpAffine, cv2.add, cv2.error

    beginner.watch(Library)
    moved = Library.warpAffine(IMAGE + 7, np.float64([[1, 0, 2], [0, 1, 1]]), (60, 40))
    assert np.array_equal(moved, cv2.warpAffine(IMAGE + 7, np.float64([[1, 0, 2], [0, 1, 1]]), (60, 40)))
    assert Library.warpAffine.__wrapped__ is cv2.warpAffine and Library.warpAffine.__name__ == "warpAffine"
    try:  # a student catching OpenCV's error still catches it
        Library.add(IMAGE, GREY)
    except cv2.error as caught:
        assert "Sizes" in str(caught) or "size" in str(caught).lower()
    else:
        pytest.fail("cv2.add of different sizes raised nothing")


def test_an_index_error_from_x_y_order_is_named():
    image = np.zeros((40, 60), np.uint8)
    try:
        image[50, 10]
    except IndexError as exc:
        said = beginner.explain_index_error(str(exc), [image])
    assert "[row, column], that is [y, x]" in said and "width (60)" in said and "height (40)" in said
    assert beginner.explain_index_error("index 80 is out of bounds for axis 0 with size 40", [image]) == ""


def test_integer_entries_and_reversed_channels_are_recognised():
    rotation = np.array([[0.866, 0.5, 0.0], [-0.5, 0.866, 0.0], [0.0, 0.0, 1.0]])
    assert "cut off" in beginner.integer_entries(rotation.astype(int), rotation)
    assert beginner.integer_entries(rotation, rotation) == ""
    assert beginner.integer_entries(np.eye(3, dtype=int), np.eye(3)) == ""  # whole numbers: nothing lost
    colour = np.random.default_rng(0).integers(0, 255, (30, 40, 3)).astype(np.uint8)
    assert beginner.channels_reversed(colour[..., ::-1], colour)
    assert not beginner.channels_reversed(colour, colour)
    grey_as_colour = np.repeat(colour[..., :1], 3, axis=2)
    assert not beginner.channels_reversed(grey_as_colour, grey_as_colour)


def test_an_integer_array_where_floats_are_expected_gets_the_fix_as_hint():
    check = select(["lab07.ex1"])[0].checks[0]
    trial = Trial(None, check)
    with pytest.raises(Fail) as failed:
        trial.expect_array(np.arange(4), "f()", kind="f")
    assert "dtype=float" in failed.value.hint
    with pytest.raises(Fail) as failed:
        trial.expect_array(np.arange(4, dtype=np.uint8), "f()", kind="f")
    assert "wraps around at 256" in failed.value.hint


def test_arrays_returned_in_a_tuple_are_told_as_the_tuple_they_are():
    """`return x, y` for (N, 2) points and `return E,` (a trailing comma): what the tuple holds is told, not only
    the shape NumPy makes of it; a tuple of numbers is converted as before."""
    check = select(["lab07.ex1"])[0].checks[0]
    trial = Trial(None, check)
    with pytest.raises(Fail) as failed:
        trial.expect_array((np.zeros(4), np.ones(4)), "f()", shape=(None, 2), kind="f")
    assert "a tuple of 2 arrays of shape (4,), one per column" in failed.value.message
    with pytest.raises(Fail) as failed:
        trial.expect_array((np.eye(3),), "f()", shape=(3, 3), kind="f")
    assert "a tuple holding one array of shape (3, 3)" in failed.value.message
    assert trial.expect_array((1.0, 2.0), "f()", shape=(2,), kind="f").shape == (2,)


# ------------------------------------------------------------------ graded end to end
INTEGER_MATRIX = '''
def translation_matrix(tx, ty):
    return np.array([[1, 0, tx], [0, 1, ty], [0, 0, 1]])


def translate(image, tx=100, ty=50):
    height, width = image.shape[:2]
    return cv2.warpAffine(image, translation_matrix(tx, ty)[:2], (width, height))
'''


def test_the_issues_integer_matrix_is_named_before_opencvs_assertion(tmp_path):
    result = grade(mutant(tmp_path, "lab07_transformations", INTEGER_MATRIX), ["lab07.ex1"], pictures="none")
    failed = [c for e in result.exercises for c in e.checks if c.score < c.max_score]
    warps = [c for c in failed if c.name.startswith("translate")]
    assert warps and all(c.message.startswith("cv2.warpAffine needs M as a float32 or float64 matrix; "
                                              "yours is int64") for c in warps), [c.message for c in failed]
    assert "Assertion failed" in warps[0].message  # OpenCV's words follow, for whoever wants them
    # (and the matrix itself, right in value, is told as the integer array it is: matrices are float arrays)
    matrices = [c for c in failed if c.name.startswith("translation_matrix")]
    assert matrices and all("returned an integer matrix (dtype int64)" in c.message for c in matrices)


X_Y_ORDER = '''
def translate(image, tx=100, ty=50):
    height, width = image.shape[:2]
    out = np.zeros_like(image)
    for x in range(width):
        for y in range(height):
            if 0 <= x - tx < width and 0 <= y - ty < height:
                out[x, y] = image[x - tx, y - ty]
    return out
'''


def test_indexing_an_image_x_first_is_named(tmp_path):
    result = grade(mutant(tmp_path, "lab07_transformations", X_Y_ORDER), ["lab07.ex1"], pictures="none")
    messages = [c.message for e in result.exercises for c in e.checks if c.score < c.max_score]
    assert messages and messages[0].startswith("an image is indexed [row, column], that is [y, x]"), messages


INTEGER_ROTATION = '''
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    theta = np.deg2rad(angle_deg)
    c, s = np.cos(theta), np.sin(theta)
    M = np.eye(3, dtype=int)
    M[:2, :2] = [[c, s], [-s, c]]
    M[:2, 2] = np.asarray(center) - M[:2, :2] @ np.asarray(center)
    return M
'''

RGB_RESULT = '''
def translate(image, tx=100, ty=50):
    height, width = image.shape[:2]
    moved = cv2.warpAffine(image, translation_matrix(tx, ty)[:2], (width, height))
    return cv2.cvtColor(moved, cv2.COLOR_BGR2RGB) if moved.ndim == 3 else moved
'''


def test_values_built_as_integers_or_as_rgb_are_named_where_they_are_judged(tmp_path):
    result = grade(mutant(tmp_path, "lab07_transformations", INTEGER_ROTATION), ["lab07.ex2"], pictures="none")
    messages = [c.message for e in result.exercises for c in e.checks if c.score < c.max_score]
    assert messages and "holds integers (int64)" in messages[0] and "dtype=float" in messages[0], messages
    result = grade(mutant(tmp_path / "rgb", "lab07_transformations", RGB_RESULT), ["lab07.ex1"], pictures="none")
    failed = [c for e in result.exercises for c in e.checks if c.score < c.max_score]
    assert failed and all("the colour channels are reversed (RGB for BGR)" in c.message for c in failed)
    assert "translate keeps a grey image grey" not in [c.name for c in failed]  # grey: nothing to reverse


FORBIDDEN_IMPORTED = '''
from cv2 import estimateAffine2D


def affine_lstsq(src, dst):
    M, _ = estimateAffine2D(np.float32(src), np.float32(dst))
    return M
'''


def test_a_forbidden_function_imported_by_name_is_still_caught(tmp_path):
    result = grade(mutant(tmp_path, "lab07_transformations", FORBIDDEN_IMPORTED), ["lab07.ex6"], pictures="none")
    failures = {c.failure for e in result.exercises for c in e.checks if c.max_score}
    assert failures == {"forbidden_call"}


@pytest.mark.parametrize("ending, told", [
    ("", "With the forbidden call allowed, the answer is wrong: triangulate(P1, P2, pts1, pts2), pts1[0] at x = 0 and "
         "pts2[1] at y = 0 returned shape (3, 5); expected (5, 3)"),
    (".T", "The answer it gave passes this check otherwise"),
])
def test_a_forbidden_call_is_told_with_what_its_answer_was_worth(tmp_path, ending, told):
    """cv2.triangulatePoints in the exercise that asks for triangulation by hand: the points are lost
    for the call; what its answer is worth is told (the call's result left as columns is a second mistake
    the rule alone would hide: told first, the rule after it), and the points stay lost either way."""
    from autograder.engine.runner import FORBIDDEN_LOOKS

    source = f"""
        def triangulate(P1, P2, pts1, pts2):
            a = np.asarray(pts1, dtype=np.float64).reshape(-1, 2).T
            b = np.asarray(pts2, dtype=np.float64).reshape(-1, 2).T
            X = cv2.triangulatePoints(np.asarray(P1, dtype=np.float64), np.asarray(P2, dtype=np.float64), a, b)
            return (X[:3] / X[3]){ending}
        """
    result = grade(mutant(tmp_path, "lab11_two_view", source), ["lab11.ex1"], pictures="none",
                   include_hidden=False)
    checks = [c for e in result.exercises for c in e.checks if c.max_score]
    assert all(c.failure == "forbidden_call" and c.score == 0 for c in checks)
    first = next(c for c in checks if "worked example" in c.name)
    assert told in first.message and "triangulate() called cv2.triangulatePoints" in first.message, first.message
    assert first.message.startswith("triangulate() called" if ending else "With the forbidden call allowed"), \
        first.message
    looked = [c for c in checks if "the answer is wrong" in c.message or "passes this check otherwise" in c.message]
    assert looked[0] is first and len(looked) == (1 if ending == "" else min(FORBIDDEN_LOOKS, len(checks))), \
        [c.message for c in checks]
    # (the look is made until it finds the answer wrong, in FORBIDDEN_LOOKS checks at most; the
    # exercise's other checks lost for the call point to what it found -- "called cv2.triangulatePoints"
    # alone would hide it)
    pointing = [c for c in checks if f"the answer in the check '{first.name}' was wrong" in c.message
                and "Besides that mistake, triangulate() called cv2.triangulatePoints" in c.message]
    assert pointing == ([c for c in checks if c is not first] if ending == "" else []), \
        [c.message for c in checks]


def test_a_forbidden_call_whose_code_raises_is_told_with_the_change_that_mends_it(tmp_path):
    """cv2.triangulatePoints' 4 x N result given to cv2.convertPointsFromHomogeneous (which reads points
    as rows): with the call allowed the code raises; the second look says so, and names the transpose."""
    source = """
        def triangulate(P1, P2, pts1, pts2):
            a = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
            b = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
            X = cv2.triangulatePoints(np.asarray(P1, dtype=np.float64), np.asarray(P2, dtype=np.float64), a.T, b.T)
            return cv2.convertPointsFromHomogeneous(X).reshape(-1, 3)
        """
    result = grade(mutant(tmp_path, "lab11_two_view", source), ["lab11.ex1"], pictures="none",
                   include_hidden=False)
    first = next(c for e in result.exercises for c in e.checks if "worked example" in c.name)
    assert first.failure == "forbidden_call" and first.score == 0, first
    assert first.message.startswith("With the forbidden call allowed, your code fails"), first.message
    assert "`cv2.convertPointsFromHomogeneous(X.T)`" in first.message, first.message


def test_a_forbidden_calls_wrong_answer_is_named_in_the_students_code(tmp_path):
    """The library's 2 x N point arrays made by reshape where a transpose belongs, beside a forbidden
    cv2.triangulatePoints: the second look names the reshapes (both lines: one slip made twice), and
    the library's own least squares -- not the reference's -- is judged by the check."""
    source = """
        def triangulate(P1, P2, pts1, pts2):
            pts1 = np.asarray(pts1, dtype=np.float64)
            a = pts1.reshape(2, -1)
            b = np.asarray(pts2, dtype=np.float64).reshape(2, -1)
            X = cv2.triangulatePoints(np.asarray(P1, dtype=np.float64), np.asarray(P2, dtype=np.float64), a, b)
            return (X[:3] / X[3]).T
        """
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ex1"], pictures="none", include_hidden=False)
    besides = [c for e in result.exercises for c in e.checks if "the answer is wrong" in c.message]
    # (the transpose, or the reshape to the other shape then transposed: both the slip's own mend)
    assert besides and ("to `pts1.T`" in besides[0].message or "to `pts1.reshape(-1, 2).T`" in besides[0].message) \
        and besides[0].score == 0, \
        [c.message for e in result.exercises for c in e.checks]


def test_point_sets_given_to_opencv_as_rows_are_named_as_one_slip(tmp_path):
    """Both point sets given to cv2.triangulatePoints as (N, 2) where it reads 2 x N (one slip made for
    both; each transposed alone makes OpenCV raise): the second look names the two transposes as one
    change, and leads with it, the rule after."""
    source = """
        def triangulate(P1, P2, pts1, pts2):
            a = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
            b = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
            X = cv2.triangulatePoints(np.asarray(P1, dtype=np.float64), np.asarray(P2, dtype=np.float64), a, b)
            return (X[:3] / X[3]).T
        """
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ex1"], pictures="none", include_hidden=False)
    looked = [c for e in result.exercises for c in e.checks if "the answer is wrong" in c.message]
    assert looked and looked[0].message.startswith("With the forbidden call allowed"), \
        [c.message for e in result.exercises for c in e.checks]
    assert ", a.T, b.T)`" in looked[0].message and looked[0].score == 0, looked[0].message


def test_what_a_forbidden_calls_second_look_computes_is_never_shared_with_the_other_checks():
    """The check run again with the forbidden call allowed shares nothing it computes with the grading's
    other checks (a panorama one check computes is served to the next): they judge under the rules."""
    from types import SimpleNamespace

    from autograder.engine.checks import Fail, Verdict
    from autograder.engine.runner import besides_forbidden

    runs = []

    def check_func(t):
        runs.append(t)
        t.shared("the student's panorama", lambda: "computed with the call allowed")
        raise Fail("the panorama is wrong")

    sandbox = SimpleNamespace(shared={"earlier": 1})
    lab = SimpleNamespace(forbidden={}, module="m")
    check = SimpleNamespace(func=check_func, hidden=False, exercise=SimpleNamespace(lab=lab, id="lab98.ex1"),
                            timeout=1, name="the panorama")
    verdict = besides_forbidden(Verdict(0.0, "f() called cv2.f"), sandbox, check, None, None)
    assert verdict.message == ("With the forbidden call allowed, the answer is wrong: the panorama is wrong.\n"
                               "Besides that mistake, f() called cv2.f: that alone loses this check."), verdict.message
    assert "the student's panorama" not in sandbox.shared and sandbox.shared["earlier"] == 1
    # once per exercise: its time comes out of the exercise's budget (another check points to it)
    again = besides_forbidden(Verdict(0.0, "f() called cv2.f"), sandbox, check, None, None).message
    assert len(runs) == 1 and again == ("With the forbidden call allowed, the answer in the check 'the panorama' "
                                        "was wrong: see there. Besides that mistake, f() called cv2.f: that alone "
                                        "loses this check."), again


def test_a_forbidden_call_left_at_its_default_method_is_named_where_a_later_check_shows_it(tmp_path):
    """cv2.findFundamentalMat called without a method in the exercise that asks for the 8-point algorithm:
    its default (RANSAC) gives the exact correspondences' F, so the first checks' looks pass; the look is
    made again in the next check lost for the call, where on noisy matches the answer is partly wrong, and
    the change giving the 8-point method is named there (the rule still loses every check)."""
    source = """
        def fundamental_8point(pts1, pts2):
            F, _ = cv2.findFundamentalMat(np.float64(pts1), np.float64(pts2))
            return F / np.linalg.norm(F)
        """
    result = grade(mutant(tmp_path, "lab11_two_view", source), ["lab11.ex4"], pictures="none", include_hidden=False)
    checks = [c for e in result.exercises for c in e.checks if c.max_score]
    assert all(c.failure == "forbidden_call" and c.score == 0 for c in checks), [c.message for c in checks]
    named = [c for c in checks if "method=cv2.FM_8POINT" in c.message]
    assert named and named[0].message.startswith("With the forbidden call allowed, the answer is partly wrong"), \
        [c.message for c in checks]


def test_a_depth_opencv_does_not_take_is_told_with_the_ones_it_does():
    """cv2.cvtColor of a float64 mask (the blind set 1205e's 08/06): OpenCV's own list of depths in the
    message (8U, 16U, 32F) is said, with the conversion."""
    from autograder.sandbox import beginner

    message = ("OpenCV(5.0.0) color.simd_helpers.hpp:94: error: (-2:Unspecified error) in function 'cv::impl::"
               "CvtHelper<VScn, VDcn, VDepth, sizePolicy>::CvtHelper(...) [with VScn = Set<1>; VDcn = Set<3, 4>; "
               "VDepth = cv::impl::{anonymous}::Set<0, 2, 5>; SizePolicy sizePolicy = NONE]'\n> Unsupported depth "
               "of input image:\n>     'VDepth::contains(depth)'\n> where\n>     'depth' is 6 (CV_64F)")
    mask = np.zeros((20, 30), dtype=np.float64)
    said = beginner._wrong_image("cv2.cvtColor", message, [("src", mask)], {})
    assert said == "cv2.cvtColor takes src as uint8, uint16 or float32; yours is float64: convert it with " \
                   "x.astype(np.float32)", said


def test_a_grey_array_is_not_told_to_be_converted_from_colour():
    said = sentence("distanceTransform", np.zeros((40, 60)), cv2.DIST_L2, 3)
    assert "cvtColor" not in said and "astype(np.uint8)" in said, said


def test_an_image_indexed_one_index_after_the_other_reads_as_y_x():
    """`canvas[i][j]` over `range(image.shape[0])` and `range(image.shape[1])` indexes rows first, as `canvas[i, j]`
    does: an IndexError from a loop over another image's rows was told "index it as image[y, x]" (third-party round
    of 2026-12-07). Indexed [x][y], or [x, y], it is not read so."""
    import ast

    from autograder.engine.forms import INDEXES_Y_X

    def reads(source):
        return INDEXES_Y_X.holds([ast.parse(textwrap.dedent(source)).body[0]])

    assert reads("""
        def blend(canvas, image):
            for i in range(image.shape[0]):
                for j in range(image.shape[1]):
                    canvas[i][j] = image[i][j]
        """)
    assert not reads("""
        def blend(canvas, image):
            for x in range(image.shape[1]):
                for y in range(image.shape[0]):
                    canvas[x][y] = image[y, x]
        """)
    assert not reads("def f(a, i, j):\n    return a[i:j][0]\n")
