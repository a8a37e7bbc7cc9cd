"""An image returned (W, H) where (H, W) is asked is told which OpenCV call the code gives a size
rows first (issue 35: "transposed" or "width and height are swapped" described the output, not
the argument that did it)."""

from __future__ import annotations

import textwrap

import pytest

from autograder.engine.hints import read_code, size_given_as_shape
from autograder.engine.runner import grade
from conftest import check_results, mutant

ROWS_FIRST = {
    "shape[:2] to resize": "def f(img, other):\n    return cv2.resize(img, other.shape[:2])\n",
    "unpacked (h, w) to warpAffine": "def f(img, M):\n    h, w = img.shape[:2]\n    return cv2.warpAffine(img, M, (h, w))\n",
    "keyword size": "def f(K, d, img):\n    return cv2.initUndistortRectifyMap(K, d, None, K, size=img.shape[0:2], m1type=5)\n",
    "indexed tuple": "def f(img, H):\n    return cv2.warpPerspective(img, H, (img.shape[0], img.shape[1]))\n",
    "a name given the shape": "def f(img, M):\n    size = img.shape[:2]\n    return cv2.warpAffine(img, M, size)\n",
    "in a helper": "def f(img, H):\n    return _warp(img, H)\ndef _warp(img, H):\n"
                   "    rows, cols = img.shape[:2]\n    return cv2.warpPerspective(img, H, dsize=(rows, cols))\n",
}
RIGHT = {
    "shape reversed": "def f(img, other):\n    return cv2.resize(img, other.shape[1::-1])\n",
    "(w, h)": "def f(img, M):\n    h, w = img.shape[:2]\n    return cv2.warpAffine(img, M, (w, h))\n",
    "columns first indexed": "def f(img, H):\n    return cv2.warpPerspective(img, H, (img.shape[1], img.shape[0]))\n",
    "a size not from a shape": "def f(img, M, size):\n    return cv2.warpAffine(img, M, size)\n",
    "a name given the shape reversed": "def f(img, M):\n    size = img.shape[1::-1]\n    return cv2.warpAffine(img, M, size)\n",
    "a name given twice": "def f(img, M, w, h):\n    size = img.shape[:2]\n    size = (w, h)\n"
                        "    return cv2.warpAffine(img, M, size)\n",
}


@pytest.mark.parametrize("name", sorted(ROWS_FIRST))
def test_a_size_given_rows_first_is_read(name):
    said = size_given_as_shape(read_code(ROWS_FIRST[name]), ["f"])
    assert "(rows, columns) to cv2." in said and "(width, height)" in said


@pytest.mark.parametrize("name", sorted(RIGHT))
def test_a_size_given_as_width_height_is_told_nothing(name):
    assert size_given_as_shape(read_code(RIGHT[name]), ["f"]) == ""


def test_a_warp_sized_rows_first_is_told_in_grading(tmp_path):
    source = textwrap.dedent("""
        def warp_affine(image, A, dsize=None):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, np.asarray(A, np.float64), dsize or (h, w))
        """)
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex5"], pictures="none")
    messages = [c.message for c in check_results(result, "lab07.ex5") if not c.passed]
    assert any("width and height are swapped" in m and "passes `(h, w)` (rows, columns) to cv2.warpAffine" in m
               for m in messages), messages


def test_a_size_read_rows_first_leaves_no_guess_from_the_lengths(tmp_path):
    # (06i: a check comparing shapes guessed "stacked along another axis, or transposed?" beside the call
    # read in the code; the call is the cause, told alone)
    source = textwrap.dedent("""
        def translate(image, tx=100, ty=50):
            h, w = image.shape[:2]
            M = np.float32([[1, 0, tx], [0, 1, ty]])
            return cv2.warpAffine(image, M, (h, w))
        """)
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex1"], pictures="none")
    failing = [c for c in check_results(result, "lab07.ex1") if not c.passed]
    assert len(failing) >= 3
    for check in failing:
        assert check.mistake == "width and height are swapped", (check.name, check.mistake)
        assert "passes `(h, w)` (rows, columns) to cv2.warpAffine" in check.message, check.message
        assert "transposed?" not in check.message and "another axis" not in check.message, check.message
