"""A warp a whole pixel off is told, where a pixel convention (half a pixel at most) is forgiven.

The blind set 1204c's 07/01 and 07/07: a shift split into `floor(tx)` and `tx - int(tx)` moves a
negative fractional shift a pixel too far; an image padded with a one-pixel border before the warp, and
the border never taken back, comes out moved by A's (1, 1). Both passed the warp checks' blurred
tolerance, which forgives the interpolation and the pixel convention. The rule compares the best fit
within half a pixel with the best fit moved by a whole one (measured in benchmarks/whole_pixel_shift.py).
"""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from autograder.engine.compare import whole_pixel_shift
from autograder.engine.mutants.operators import apply_edits, mutants_of
from autograder.labs.lab07 import photo
from fixtures.images import as_homography

A = np.array([[0.9, -0.2, 20.0], [0.15, 1.05, -5.0]])


def _moved(dx, dy):
    return np.array([[1.0, 0, dx], [0, 1, dy], [0, 0, 1]])


def _warped(source, H, flags=cv2.INTER_LINEAR):
    h, w = source.shape[:2]
    return cv2.warpPerspective(source, H, (w, h), flags=flags, borderMode=cv2.BORDER_CONSTANT, borderValue=0)


@pytest.mark.parametrize("legitimate", ["bilinear", "nearest", "cubic", "centre", "corner"])
def test_a_legitimate_warp_is_no_whole_pixel_off(legitimate):
    source = photo("chelsea", (160, 120), grey=True)
    H = as_homography(A)
    got = {"bilinear": lambda: _warped(source, H), "nearest": lambda: _warped(source, H, cv2.INTER_NEAREST),
           "cubic": lambda: _warped(source, H, cv2.INTER_CUBIC),
           "centre": lambda: _warped(source, _moved(.5, .5) @ H @ _moved(-.5, -.5)),
           "corner": lambda: _warped(source, _moved(-.5, -.5) @ H @ _moved(.5, .5))}[legitimate]()
    assert whole_pixel_shift(got, source, A) is None


@pytest.mark.parametrize("move, expected", [((1, 0), (1, 0)), ((0, -1), (0, -1)), ((1, 1), (1, 1))])
def test_a_warp_moved_by_a_whole_pixel_is_told_with_its_direction(move, expected):
    source = photo("chelsea", (160, 120), grey=True)
    found = whole_pixel_shift(_warped(source, _moved(*move) @ as_homography(A)), source, A)
    assert found is not None and found[:2] == expected, found


def test_a_border_added_and_not_taken_back_is_a_whole_pixel_off():
    source = photo("rocket", (200, 150))
    padded = cv2.copyMakeBorder(source, 1, 1, 1, 1, cv2.BORDER_CONSTANT, value=0)
    found = whole_pixel_shift(_warped(padded, as_homography(A))[:150, :200], source, A)
    assert found is not None and found[:2] == (1, 1), found


SPLIT = """
import numpy as np

def translate(image, tx=100, ty=50):
    ix, iy = int(np.floor(tx)), int(np.floor(ty))
    return ix, iy, tx - int(tx), ty - int(ty)
"""


def test_truncation_is_tried_as_the_floor_and_a_floor_is_not_floored_again():
    """`tx - int(tx)` -> `tx - int(np.floor(tx))` (the remainder of the whole pixels below); `int(np.floor(tx))`
    has nothing to mend."""
    made = {apply_edits(SPLIT, m.edits).split("return ")[1].strip() for m in mutants_of(SPLIT, ["translate"], phrased=False)["translate"]
            if m.operator == "function"}
    assert "(ix, iy, tx - int(np.floor(tx)), ty - int(ty))" in made, made
    changed = {apply_edits(SPLIT, m.edits).splitlines()[4].strip() for m in mutants_of(SPLIT, ["translate"], phrased=False)["translate"]
               if m.operator == "function"}
    assert not any("np.floor(np.floor" in line for line in changed), changed


def test_the_usual_places_to_look_give_way_to_a_confirmed_change_of_the_code(tmp_path):
    """A pixel grid counted from 1 (`np.arange(1, w + 1)`): the check measures a whole pixel off and lists the
    usual places (a border, a split shift, a grid from 1); the change confirmed at the student's own lines
    takes their place -- none of them is read in the code, and beside the change they would send the student
    elsewhere. Without a change, the list stays."""
    import textwrap

    from autograder.engine.claims import LOOK_FOR, without_where_to_look
    from autograder.engine.runner import grade
    from conftest import check_results, edited_reference

    own = textwrap.indent(textwrap.dedent('''
        height, width = image.shape[:2]
        out_w, out_h = dsize if dsize is not None else (width, height)
        inverse = cv2.invertAffineTransform(np.asarray(A, np.float64))
        xs, ys = np.meshgrid(np.arange(1, out_w + 1, dtype=np.float64), np.arange(1, out_h + 1, dtype=np.float64))
        map_x = (inverse[0, 0] * xs + inverse[0, 1] * ys + inverse[0, 2]).astype(np.float32)
        map_y = (inverse[1, 0] * xs + inverse[1, 1] * ys + inverse[1, 2]).astype(np.float32)
        return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT)''').strip("\n"), "    ")
    folder = edited_reference(tmp_path, "lab07_transformations", ("    return _warp(image, A, dsize)\n", own + "\n"))
    result = grade(folder, ["lab07.ex5"], pictures="none", include_hidden=False)
    told = [c for c in check_results(result, "lab07.ex5") if c.mistake == "the image is a whole pixel off"]
    assert told, [c.message for c in check_results(result, "lab07.ex5")]
    assert any("`np.arange(out_w, dtype=np.float64)`" in c.message for c in told), [c.message for c in told]
    for check in told:
        if "Trying small changes" in check.message:
            assert not any(text in check.message for text in LOOK_FOR), check.message
    advice = next(iter(LOOK_FOR))
    assert without_where_to_look(f"measured. {advice} Trying small changes") == "measured. Trying small changes"
