"""Lab 7 - 2D transformations: the public checks.

Each exercise is judged against ground truth from :mod:`fixtures.lab07`: true
matrices by definition, true images by warping a photo with the true matrix.
Wrong answers are compared with what the usual mistakes would give, so the
feedback can name the mistake.
"""

from __future__ import annotations

import ast
import re

import numpy as np

from fixtures import lab07 as truth
from fixtures.images import photo, warp

from ..engine import conventions
from ..engine import strategies as st
from ..engine.checks import Fail, StudentFailure, Trial, Verdict, passed
from ..engine.claims import calls_any, from_code, guard, guessed, measured
from ..engine.compare import format_arrays_apart
from ..engine.judges import (Probe, call_probe, digits_apart, entries_misplaced, judge_matrix, judge_parameter_used, judge_warp, reads,
                      name_mistake, warp_probe)
from ..engine.hints import Predicate, _path, call_in_a_loop, calls, code_of, expr, mentions, uses_attr
from ..engine.registry import Lab
from ..sandbox.beginner import RGB_FOR_BGR, channels_reversed
from ..loading.parsing import walk

lab = Lab("lab07", module="lab07_transformations", title="2D transformations")

# Names that ask for code, held to the student's code (autograder.engine.claims): a rotation
# whose angle reaches cos and sin in degrees, from code that converts it (into another name, or
# back), is not told to convert it.
DEGREES_TO_RADIANS = (calls_any("np.deg2rad", "np.radians", "math.radians") | expr("_ * np.pi / 180")
                      | expr("np.pi * _ / 180") | expr("_ / 180 * np.pi") | expr("_ * (np.pi / 180)")
                      | expr("_ * math.pi / 180") | expr("math.pi * _ / 180")).saying("converts degrees to radians")
guard(truth.ANGLE_AS_RADIANS, asks=DEGREES_TO_RADIANS,
      instead="the angle is used as radians: your code {found}, but cos and sin are given the angle "
              "before the conversion (or converted back)")
# The column of ones of an affine system written: np.ones, a 1 set into an array's entries
# (`M[0::2, 2] = 1`), or a literal row of a point's coordinates and a 1 (`[x, y, 1, 0, 0, 0]`; a
# shape such as `(-1, 2, 1)` holds a 1 and at most one value, and is no row). A fit with no
# translation from code that has one is another slip (how the system is solved, or read back).
def _sets_ones(function) -> bool:
    def one(node) -> bool:
        return isinstance(node, ast.Constant) and type(node.value) in (int, float) and node.value == 1

    def row(node) -> bool:
        values = [e for e in node.elts if not isinstance(e, (ast.Constant, ast.UnaryOp))]
        return len(node.elts) >= 3 and any(one(e) for e in node.elts) and len(values) >= 2

    return any((isinstance(node, ast.Assign) and one(node.value)
                and any(isinstance(target, ast.Subscript) for target in node.targets))
               or (isinstance(node, (ast.List, ast.Tuple)) and row(node)) for node in walk(function))


ONES_COLUMN = (calls_any("np.ones", "np.ones_like", "cv2.convertPointsToHomogeneous")
               | Predicate("sets entries of the system to 1", _sets_ones)).saying("builds the column of ones")
# (what A came out as, measured; the two causes it names are the two ways code makes it -- the second, rows of six
# entries paired with the unknowns in another order, only of code that writes such rows: a (3, 2) solution of
# [x, y, 1] rows read back row by row is the first alone)
measured(truth.TRANSPOSED_READ_BY_ROWS)


def _six_wide_rows(function) -> bool:
    return any(isinstance(node, (ast.List, ast.Tuple)) and len(node.elts) == 6
               and sum(isinstance(e, ast.Constant) and e.value == 0 for e in node.elts) >= 3 for node in walk(function))


SIX_WIDE_ROWS = Predicate("writes rows of six entries ([x, y, 1, 0, 0, 0])", _six_wide_rows)
guard(truth.TRANSPOSED_READ_BY_ROWS, asks=~SIX_WIDE_ROWS,
      instead=truth.TRANSPOSED_READ_BY_ROWS.split(", or the rows", 1)[0])
guard(truth.NO_ONES_COLUMN, asks=ONES_COLUMN,
      instead="the fit has no translation (its last column is 0), yet your code {found}: look at how the system "
              "is solved and how its solution is read back into the matrix")
guard(truth.RADIANS_TO_OPENCV, asks=~calls_any("cv2.getRotationMatrix2D"),
      instead="the rotation is by angle_deg * pi / 180 degrees: the angle is converted to radians twice")
guard(truth.INVERSE_MAP, asks=~(calls_any("np.linalg.inv", "np.linalg.pinv", "cv2.invertAffineTransform")
                                | mentions("cv2.WARP_INVERSE_MAP")),
      instead="the inverse map is applied (A maps source pixels to output pixels); your code neither inverts "
              "A nor passes cv2.WARP_INVERSE_MAP: look at how each output pixel is looked up (reading the "
              "source at A x applies the inverse of A)")

# skimage.transform.warp's transform is the inverse map (each output pixel's source), where OpenCV's
# warps take the forward one: a forward transform passed to it moves the image the other way. So does
# cv2.WARP_INVERSE_MAP with the lab's forward matrix never inverted -- in a shared warp helper too, where
# the matrix itself is right. Every name of an image moved the other way is told so to such code: the fact
# measured (the part of the name before its colon) and the step read, never the name's cause in the matrix
# (the lecture's R(theta), a shear's sign), which the matrix's own checks judge.
SKIMAGE_FORWARD = (calls("skimage.transform.warp") & ~uses_attr(".inverse")
                   & ~calls_any("np.linalg.inv", "np.linalg.pinv", "cv2.invertAffineTransform")).saying(
    "warps with skimage.transform.warp, whose transform maps each output pixel to the input pixel it samples (the "
    "inverse map), where the lab's matrix maps input to output: pass tform.inverse (or the inverse matrix)")
def _flags_invert(function) -> bool:
    """A warp given cv2.WARP_INVERSE_MAP as its flags (`flags=...`, or its fifth argument: the fourth is `dst`)."""
    for node in walk(function):
        if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in ("warpAffine", "warpPerspective"):
            given = [k.value for k in node.keywords if k.arg == "flags"] + node.args[4:5]
            if any(_path(n) == "cv2.WARP_INVERSE_MAP" for flag in given for n in walk(flag)):
                return True
    return False


INVERSE_FLAG = (Predicate("passes cv2.WARP_INVERSE_MAP", _flags_invert)
                & ~calls_any("np.linalg.inv", "np.linalg.pinv", "cv2.invertAffineTransform")).saying(
    "passes cv2.WARP_INVERSE_MAP, with which cv2.warpAffine reads the matrix as the map from each output pixel to "
    "the input pixel it samples (the inverse map), where the lab's matrix maps input to output: take the flag out")
OTHER_WAY = sorted({name for mistakes in (truth.translation_mistakes(3.0, 4.0), truth.rotation_mistakes(30.0, (5.0, 7.0)),
                                           truth.scaling_mistakes(2.0, 3.0), truth.shear_mistakes(0.3))
                     for name in mistakes if "opposite way" in name or "inverted" in name or "inverse map" in name})
for _other_way in OTHER_WAY:
    _measured = re.split(r": | \(", _other_way)[0].replace("has the wrong sign", "goes the opposite way")
    guard(_other_way, asks=SKIMAGE_FORWARD | INVERSE_FLAG, instead=f"{_measured}: your code {{found}}")


# scipy.ndimage indexes arrays (row, col) = (y, x): a map written in (x, y) there acts on the other axis, which is
# the cause of an x/y exchange in code that warps with it (its matrix and offset in the lab's (x, y) order)
NDIMAGE_WARP = (calls("scipy.ndimage.affine_transform") | calls("scipy.ndimage.shift") | calls("scipy.ndimage.zoom")
                ).saying("warps with scipy.ndimage")
AXES_EXCHANGED = sorted({name for mistakes in (truth.translation_mistakes(3.0, 4.0), truth.scaling_mistakes(2.0, 3.0),
                                               truth.shear_mistakes(0.3))
                         for name in mistakes if "swapped" in name or "along y" in name})
for _exchanged in AXES_EXCHANGED:
    guard(_exchanged, asks=NDIMAGE_WARP, instead=f"{_exchanged}: " + from_code(
        "your code {found}, which indexes arrays (row, col) = (y, x): a matrix (or offset) written in the lab's (x, y) "
        "order acts there on the other axis -- exchange its rows and columns (and the offset's two entries) for "
        "ndimage, or warp with cv2.warpAffine, which takes (x, y)"))


# The confirmation probes' inputs (see autograder.engine.judges.Probe): values no usual mistake leaves
# unchanged -- fractional, of both signs, x apart from y, an angle far from 0 and 90 degrees, a
# centre off the origin -- so that the mistakes answer them differently.
PROBE_ARGS = {
    "translation_matrix": ((37.25, -12.5), {}, truth.translation, truth.translation_mistakes),
    "rotation_matrix": ((37.0,), {"center": (13.5, -7.25)}, truth.rotation, truth.rotation_mistakes),
    "scaling_matrix": ((1.75, 0.6), {}, truth.scaling, truth.scaling_mistakes),
    "shear_matrix": ((0.35,), {}, truth.shear, truth.shear_mistakes),
}


def matrix_probe(t: Trial, function: str) -> Probe:
    """``function`` on its probe input: what it returns there, and what each mistake gives."""
    args, kwargs, true_matrix, mistakes = PROBE_ARGS[function]
    values = args + tuple(kwargs.values())
    return call_probe(t, function, args, kwargs, candidates=lambda: mistakes(*values), truth=true_matrix(*values),
                      shape=(3, 3))


def image_probe(t: Trial, function: str) -> Probe:
    """The image function on its probe input: another photo (neither square nor the checks' size)
    moved by the probe's matrix."""
    source = photo("rocket", (190, 130))
    if function == "warp_affine":
        A = np.array([[0.9, -0.25, 20.0], [0.15, 1.05, -8.0]])
        return warp_probe(t, function, source, A, truth.warp_mistakes(A), args=(source, A))
    if function == "rotate":
        centre = truth.image_centre(source.shape)
        return warp_probe(t, function, source, truth.rotation(37.0, centre), truth.rotation_mistakes(37.0, centre),
                          kwargs={"angle_deg": 37.0})
    kwargs, M, mistakes = {
        "translate": ({"tx": 23.5, "ty": -17.25}, truth.translation(23.5, -17.25),
                      truth.translation_mistakes(23.5, -17.25)),
        "scale": ({"sx": 1.3, "sy": 0.7}, truth.scaling(1.3, 0.7), truth.scaling_mistakes(1.3, 0.7, source.shape)),
        "shear": ({"s": 0.35}, truth.shear(0.35), truth.shear_mistakes(0.35, source.shape)),
    }[function]
    return warp_probe(t, function, source, M, mistakes, kwargs=kwargs)


def judge_matrix_call(t: Trial, function: str, args: tuple, true_matrix, mistakes):
    """Call ``function(*args)`` and judge it against ``true_matrix(*args)`` and ``mistakes(*args)``."""
    what = f"{function}({', '.join(repr(a) for a in args)})"
    judge_matrix(t, what, t.call(function, *args), true_matrix(*args), mistakes(*args),
                 probe=matrix_probe(t, function))


finite_floats = lambda lo, hi: st.floats(lo, hi, allow_nan=False, allow_infinity=False)  # noqa: E731


def call_on(t: Trial, what: str, function: str, *args, **kwargs):
    """``t.call``; an exception it relays is said with ``what``, the input it raised on ("scale() raised
    ValueError: ... (raised on scale(grey image, sx=2.0, sy=0.8))", at the end of its first line),
    where the check's name does not say it."""
    try:
        return t.call(function, *args, **kwargs)
    except StudentFailure as failure:
        if failure.outcome.kind != "exception":
            raise
        first, newline, rest = failure.message.partition("\n")
        raise failure.said(f"{first} (raised on {what}){newline}{rest}") from None


# ================================================================== ex1 translation
ex1 = lab.exercise("ex1", "Translation", functions=[
    "translation_matrix(tx, ty)", "translate(image, tx=100, ty=50)"])


@ex1.check("translation_matrix(100, 50)", points=2)
def translation_matrix_example(t):
    judge_matrix_call(t, "translation_matrix", (100, 50), truth.translation, truth.translation_mistakes)


@ex1.check("translation_matrix for any tx, ty", points=2)
def translation_matrix_property(t):
    t.for_all(st.tuples(finite_floats(-1000, 1000), finite_floats(-1000, 1000)), lambda shift: judge_matrix_call(
        t, "translation_matrix", shift, truth.translation, truth.translation_mistakes))


@ex1.check("translate(image) with the defaults tx=100, ty=50", points=3)
def translate_defaults(t):
    source = photo("astronaut", (240, 180))
    return judge_warp(t, "translate(image)", t.call("translate", source), source,
                      truth.translation(100, 50), truth.translation_mistakes(100, 50),
        probe=image_probe(t, "translate"))


# Shifts of either sign, and a pure horizontal one: ty = 0 is an offset like any other (an image
# shifted by slicing, image[:-ty], is empty there); and shifts whole in one direction only (code taking a
# shortcut for whole pixels must test both).
GREY_SHIFTS = ((-30, 20), (45, 0), (12, 7.8), (-6.8, 10))


@ex1.check("translate keeps a grey image grey", points=2)
def translate_grey(t):
    source = photo("camera", (160, 120), grey=True)
    for tx, ty in GREY_SHIFTS:
        what = f"translate(grey image, tx={tx}, ty={ty})"
        verdict = judge_warp(t, what, call_on(t, what, "translate", source, tx=tx, ty=ty), source,
                             truth.translation(tx, ty), truth.translation_mistakes(tx, ty),
                             probe=image_probe(t, "translate"))
        if verdict.fraction < 1:
            return verdict
    return verdict


# Shifts past the image's own size, either way: the content leaves the frame and the image is black (a shift
# by slicing must stop at the border: a window of negative size is an error or an empty copy).
BEYOND_SHIFTS = ((200, 30), (-20, -150))
# And shifts to the frame's edge, one pixel short of the size: one column (row) of the image is left in it
# (a shortcut that blanks the image from `width - 1` on loses it).
EDGE_SHIFTS = ((159, 0), (0, -119))


@ex1.check("translate to the frame's edge (one column or row left) and past it (the content leaves the frame)",
           points=1)
def translate_beyond(t):
    source = photo("coffee", (160, 120))
    # (a translate wrong for an ordinary shift too -- the wrong way, the wrong axis, its channels reversed -- is
    # the other checks' to judge: one mistake told once, as the -H check of lab 8 does; the edge is judged of a
    # translate right there)
    what = "translate(160x120 image, tx=30, ty=20)"
    try:
        right_there = judge_warp(t, what, call_on(t, what, "translate", source, tx=30, ty=20), source,
                                 truth.translation(30, 20), show=False).fraction == 1
    except Fail:
        right_there = False
    except StudentFailure as failure:   # (raised there too: the defaults' check says so)
        if failure.outcome.kind != "exception":
            raise
        right_there = False
    wrong = []   # (both shifts called first: a change that mends one edge and not the other is no repair)
    for tx, ty in (EDGE_SHIFTS if right_there else ()):
        what = f"translate(160x120 image, tx={tx}, ty={ty})"
        got = t.expect_array(call_on(t, what, "translate", source, tx=tx, ty=ty), what, shape=source.shape,
                             dtype=np.uint8)
        # (a whole-pixel shift: every recipe copies the line exactly, and the rest is black fill)
        expected = np.zeros_like(source)
        if tx:
            expected[:, -1], line, place = source[:, 0], got[:, -1], f"column {source.shape[1] - 1}"
        else:
            expected[0], line, place = source[-1], got[0], "row 0"
        kept = expected[:, -1] if tx else expected[0]
        if float(np.abs(line.astype(np.int16) - kept).mean()) > 1 \
                or float(np.abs(got.astype(np.int16) - expected).mean()) > 0.5:
            wrong.append((what, got, expected, "the first column" if tx else "the last row", place,
                          "width" if tx else "height", not np.any(line)))
    if wrong:
        what, got, expected, which, place, size, black = wrong[0]
        t.images(what, yours=got, expected=expected)
        t.fail(measured(f"{what}: {which} of the image should be left at the frame's edge ({place}), the rest "
                        f"black fill; {'it is black there' if black else 'it is not'} (a shift one pixel short of "
                        f"the {size} leaves one line)."))
    for tx, ty in BEYOND_SHIFTS:
        what = f"translate(160x120 image, tx={tx}, ty={ty})"
        got = t.expect_array(call_on(t, what, "translate", source, tx=tx, ty=ty), what, shape=source.shape,
                             dtype=np.uint8)
        lit = float(np.any(got > 0, axis=-1).mean())
        if lit > 0.001:
            t.images(what, yours=got)
            t.fail(measured(f"{what}: {lit:.0%} of the pixels are not black, but every pixel's source lies outside the "
                            "image (the shift is larger than the image): the result is all black fill."))
    return passed("all black for shifts past the image's width and height")


# ================================================================== ex2 rotation
ex2 = lab.exercise("ex2", "Rotation", functions=[
    "rotation_matrix(angle_deg, center=(0.0, 0.0))", "rotate(image, angle_deg=45)"])


@ex2.check("rotation_matrix(30) about the origin", points=2)
def rotation_matrix_example(t):
    judge_matrix(t, "rotation_matrix(30)", t.call("rotation_matrix", 30),
                 truth.rotation(30), truth.rotation_mistakes(30, (0.0, 0.0)), probe=matrix_probe(t, "rotation_matrix"))


@ex2.check("rotation_matrix equals cv2.getRotationMatrix2D for any angle and centre", points=3)
def rotation_matrix_property(t):
    def holds(case):
        angle, center = case
        what = f"rotation_matrix({angle!r}, center={center!r})"
        judge_matrix(t, what, t.call("rotation_matrix", angle, center=center),
                     truth.rotation(angle, center), truth.rotation_mistakes(angle, center),
                     probe=matrix_probe(t, "rotation_matrix"))

    # (first a centre of whole numbers, as a caller writes one -- `(10, 20)` --: code computing in the centre's
    # own dtype, `c = np.array(center); c -= R @ c`, cannot hold the rotated part)
    holds((30, (10, 20)))
    centres = st.tuples(finite_floats(-300, 300), finite_floats(-300, 300))
    t.for_all(st.tuples(finite_floats(-360, 360), centres), holds)


@ex2.check("rotation_matrix about a centre given as a NumPy array (a 2D point), twice", points=1)
def rotation_matrix_array_centre(t):
    """A centre held as an array (the API's 2D points are float arrays) is the caller's: a function that
    writes into it (``c = np.asarray(center); c -= R @ c``) answers its first call rightly and the caller's
    next one about another centre (:mod:`autograder.engine.inplace` names it from the second call)."""
    center = np.array([40.25, -25.5])
    what = "rotation_matrix(30, center=np.array([40.25, -25.5]))"
    try:
        got = t.call("rotation_matrix", 30, center=center)
    except StudentFailure as failure:
        if failure.outcome.kind != "exception":
            raise
        # (the API's centre is a pair: code taking only tuples is not wrong, and this check asks no more)
        return passed(measured("a centre given as an array raises here; the API asks for a pair, which the other "
                               "checks give"))
    judge_matrix(t, what, got, truth.rotation(30, (40.25, -25.5)), truth.rotation_mistakes(30, (40.25, -25.5)),
                 probe=matrix_probe(t, "rotation_matrix"))


@ex2.check("rotate(image) by the default 45 degrees about the centre", points=3)
def rotate_default(t):
    source = photo("astronaut", (200, 150))
    centre = truth.image_centre(source.shape)
    return judge_warp(t, "rotate(image)", t.call("rotate", source), source,
                      truth.rotation(45, centre), truth.rotation_mistakes(45, centre),
        probe=image_probe(t, "rotate"))


@ex2.check("rotate keeps a grey image grey and its size, a quarter turn too", points=2)
def rotate_grey(t):
    source = photo("camera", (160, 120), grey=True)
    centre = truth.image_centre(source.shape)
    # A quarter turn of a non-square image stays in the input's frame (warps keep the input's size):
    # np.rot90 would give a (W, H) image with nothing cut off.
    quarter = t.call("rotate", source, angle_deg=90)
    if isinstance(quarter, np.ndarray) and quarter.shape[:2] == source.shape[1::-1]:
        t.fail(f"rotate(grey 160x120 image, angle_deg=90) returned shape {quarter.shape}; expected {source.shape}: "
               "a rotation keeps the input's size, its corners cut off and the rest filled black, also for "
               "multiples of 90 degrees (a quarter turn of the whole array, as np.rot90 makes, turns the frame "
               "with the image)")
    verdict = judge_warp(t, "rotate(grey image, angle_deg=90)", quarter, source, truth.rotation(90, centre),
                         truth.rotation_mistakes(90, centre), show=False)
    if verdict.fraction < 1.0:
        return verdict
    return judge_warp(t, "rotate(grey image, angle_deg=-30)",
                      t.call("rotate", source, angle_deg=-30), source,
                      truth.rotation(-30, centre), truth.rotation_mistakes(-30, centre),
        probe=image_probe(t, "rotate"))


@ex2.check("rotate a square image by quarter, half and whole turns (90, -90, 180, 270, 0 and 360 degrees)", points=1)
def rotate_square_quarter_turns(t):
    """A square image turned a quarter turn fills its frame exactly, so a shortcut through np.rot90 or
    cv2.rotate is right there -- in the direction a positive angle means (counter-clockwise on screen)
    only; the other checks' quarter turn is of a non-square image, where no such shortcut applies. No
    turn and a whole turn give the image back (a shortcut for half turns testing `angle % 180 == 0`
    flips them). A half turn is a flip of both axes: judged for its channels only (a shortcut through
    `np.flip(image)` flips them too), since OpenCV's tutorial centre (w / 2, h / 2) -- legitimate -- turns
    it a whole pixel off the frame's centre."""
    source = photo("astronaut", (128, 128))
    verdict = judge_rotations(t, "square image", source, (90, -90, 270, 0, 360))
    if verdict.fraction < 1:
        return verdict
    what = "rotate(square image, angle_deg=180)"
    got = t.expect_array(call_on(t, what, "rotate", source, angle_deg=180), what, shape=source.shape, dtype=np.uint8)
    turned = [warp(source, truth.rotation(180, centre)) for centre in (truth.image_centre(source.shape), (64.0, 64.0))]
    if any(channels_reversed(got, expected) for expected in turned):
        t.images(what, yours=got, expected=turned[0])
        t.fail(f"{what} is wrong: {RGB_FOR_BGR}.", mistake="the colour channels are reversed (RGB for BGR)")
    return verdict


def judge_rotations(t: Trial, described: str, source, angles) -> Verdict:
    """rotate(source, angle_deg=a) judged for each of ``angles`` in turn, about the image's centre: the
    first that fails is the verdict."""
    centre = truth.image_centre(source.shape)
    for angle in angles:
        verdict = judge_warp(t, f"rotate({described}, angle_deg={angle})", t.call("rotate", source, angle_deg=angle),
                             source, truth.rotation(angle, centre), truth.rotation_mistakes(angle, centre),
                             probe=image_probe(t, "rotate"))
        if verdict.fraction < 1.0:
            return verdict
    return verdict


@ex2.check("rotate by a fractional angle (30.5 degrees)", points=1)
def rotate_fractional(t):
    """Every other check's angle is whole, where an angle cut to an integer (`int(angle_deg)`) is exact;
    half a degree moves the image's corners by about a pixel, which the image comparison may forgive, so
    the answer is also held to being another image than the whole angle's."""
    source = photo("astronaut", (200, 150))
    centre = truth.image_centre(source.shape)
    half = t.call("rotate", source, angle_deg=30.5)
    verdict = judge_warp(t, "rotate(image, angle_deg=30.5)", half, source, truth.rotation(30.5, centre),
                         truth.rotation_mistakes(30.5, centre), probe=image_probe(t, "rotate"))
    whole = t.call("rotate", source, angle_deg=30)
    if isinstance(whole, np.ndarray) and isinstance(half, np.ndarray) and np.array_equal(whole, half):
        t.fail("rotate(image, angle_deg=30.5) is exactly rotate(image, angle_deg=30): "
               + measured("the angle's fractional part is lost (is it made an integer, int() or //, on its way?)"),
               mistake="the angle is cut to a whole number of degrees")
    return verdict


# ================================================================== ex3 scaling
ex3 = lab.exercise("ex3", "Scaling", functions=[
    "scaling_matrix(sx, sy)", "scale(image, sx=1.5, sy=1.5)"])


@ex3.check("scaling_matrix(1.5, 0.5)", points=2)
def scaling_matrix_example(t):
    judge_matrix_call(t, "scaling_matrix", (1.5, 0.5), truth.scaling, truth.scaling_mistakes)


# Any factor but 0: a negative one mirrors the image (diag(-1, 1, 1) flips x), and is a scaling too.
SCALE_FACTORS = st.one_of(finite_floats(0.1, 10), finite_floats(-10, -0.1))


@ex3.check("scaling_matrix for any sx, sy (negative ones mirror)", points=1)
def scaling_matrix_property(t):
    t.for_all(st.tuples(SCALE_FACTORS, SCALE_FACTORS), lambda factors: judge_matrix_call(
        t, "scaling_matrix", factors, truth.scaling, truth.scaling_mistakes))


@ex3.check("scale(image) with the defaults: 1.5x about the top-left corner, same size", points=4)
def scale_default(t):
    source = photo("coffee", (200, 150))
    return judge_warp(t, "scale(image)", t.call("scale", source), source,
                      truth.scaling(1.5, 1.5), truth.scaling_mistakes(1.5, 1.5, source.shape),
        probe=image_probe(t, "scale"))


@ex3.check("scale with whole-number factors (sx=2, sy=1)", points=1)
def scale_whole_factors(t):
    """The factors are numbers, and a caller's 2 is one: a matrix made from them must still be of floats
    for cv2.warpAffine (`np.array([[sx, 0, 0], [0, sy, 0]])` of two ints is an integer matrix). And a frame
    wider than 256 pixels, as photos are: pixel coordinates counted in the image's uint8 wrap round there."""
    source = photo("coffee", (320, 240))
    return judge_warp(t, "scale(image, sx=2, sy=1)", t.call("scale", source, sx=2, sy=1), source,
                      truth.scaling(2.0, 1.0), truth.scaling_mistakes(2.0, 1.0, source.shape),
                      probe=image_probe(t, "scale"))


def judge_warp_using(t: Trial, function: str, parameter: str, values, judge):
    """``judge()``; when it fails, say so if ``parameter`` changes nothing (it is ignored)."""
    try:
        return judge()
    except Fail as failure:
        if not failure.mistake:  # unexplained by the image alone: probe the parameter
            source = photo("chelsea", (200, 150))
            judge_parameter_used(t, f"{function}(image)", lambda **kw: t.call(function, source, **kw),
                                 parameter, values, "image")
        raise


@ex3.check("scale with different sx and sy", points=3)
def scale_anisotropic(t):
    # grey, as the API allows: the other scale checks give colour images
    source = photo("chelsea", (200, 150), grey=True)
    return judge_warp_using(t, "scale", "sy", (0.8, 1.6), lambda: judge_warp(
        t, "scale(grey image, sx=2.0, sy=0.8)", call_on(t, "scale(grey image, sx=2.0, sy=0.8)", "scale", source,
                                                        sx=2.0, sy=0.8),
        source, truth.scaling(2.0, 0.8), truth.scaling_mistakes(2.0, 0.8, source.shape)))


# ================================================================== ex4 shearing
ex4 = lab.exercise("ex4", "Shearing", functions=["shear_matrix(s)", "shear(image, s=0.5)"])


@ex4.check("shear_matrix(0.5)", points=2)
def shear_matrix_example(t):
    judge_matrix_call(t, "shear_matrix", (0.5,), truth.shear, truth.shear_mistakes)


@ex4.check("shear_matrix for any s", points=1)
def shear_matrix_property(t):
    t.for_all(finite_floats(-5, 5).filter(lambda s: abs(s) > 1e-3), lambda s: judge_matrix_call(
        t, "shear_matrix", (s,), truth.shear, truth.shear_mistakes))


@ex4.check("shear(image) with the default s=0.5, and a steep one (s=1.5)", points=4)
def shear_default(t):
    source = photo("astronaut", (200, 150))
    verdict = judge_warp(t, "shear(image)", t.call("shear", source), source,
                         truth.shear(0.5), truth.shear_mistakes(0.5, source.shape),
                         probe=image_probe(t, "shear"))
    if verdict.fraction < 1:
        return verdict
    # (any factor is a shear: one beyond 1, a slope past 45 degrees, is no less one -- blind set 1204e's 07/05 clipped it)
    steep = judge_warp(t, "shear(image, s=1.5)", t.call("shear", source, s=1.5), source,
                       truth.shear(1.5), truth.shear_mistakes(1.5, source.shape))
    return verdict if steep.fraction >= 1 else steep


@ex4.check("shear keeps a grey image grey", points=3)
def shear_grey(t):
    source = photo("camera", (160, 120), grey=True)
    return judge_warp_using(t, "shear", "s", (0.3, -0.4), lambda: judge_warp(
        t, "shear(grey image, s=0.3)", t.call("shear", source, s=0.3), source,
        truth.shear(0.3), truth.shear_mistakes(0.3, source.shape)))


# ================================================================== ex5 affine from 3 points
ex5 = lab.exercise("ex5", "Affine transformation from three points", functions=[
    "affine_from_points(src, dst)", "warp_affine(image, A, dsize=None)"])


# Affine fits are judged in pixels, where the points are: the largest distance
# between where the student's map and the true map send the data (the points and
# the corners of their bounding box). The tolerance grows with the coordinates'
# magnitude, as float32 rounding does. Measured (benchmarks/fairness_lab07.py):
# cv2.getAffineTransform with float32 points -- the lab sheet's recipe -- is at
# most 6e-5 px off for coordinates up to 300 and 1.3e-3 px up to 6000; a float32
# least-squares system 3.6e-4 px up to 4000; float64 variants (solve, inv,
# lstsq, pinv, normal equations, centred points) 1e-10 px. The smallest named
# mistake is 1 px away (ex6) or 66 px (ex5). Tolerance: 1e-5 px per pixel of the
# data's extent, at least 0.01 px -- 30 times the worst legitimate figure.
POINT_TOLERANCE_PER_PX = 1e-5


def point_tolerance(*point_sets) -> float:
    """Pixels of disagreement a float32 recipe may cause at the data's scale."""
    extent = max(float(np.abs(np.asarray(p, float)).max()) for p in point_sets)
    return POINT_TOLERANCE_PER_PX * max(1000.0, extent)


def with_bounding_box(pts) -> np.ndarray:
    """The points and the corners of their bounding box: the region the data covers."""
    pts = np.asarray(pts, float)
    (x0, y0), (x1, y1) = pts.min(0), pts.max(0)
    return np.vstack([pts, [[x0, y0], [x1, y0], [x0, y1], [x1, y1]]])


def point_error(A, B, pts) -> float:
    """Largest distance (px) between where the affine maps ``A`` and ``B`` send ``pts``."""
    return float(np.linalg.norm(truth.apply_affine(A, pts) - truth.apply_affine(B, pts), axis=1).max())


def fit_probe(t: Trial, function: str) -> Probe:
    """``function`` (affine_from_points or affine_lstsq) on a probe problem: points of another
    extent and origin, a map far from the identity."""
    rng = np.random.default_rng(707)
    A = np.array([[1.15, -0.35, 42.5], [0.25, 0.8, -31.0]])
    src = truth.triangle(rng, 250.0) + [60.0, 35.0] if function == "affine_from_points" \
        else rng.uniform(-150, 350, size=(9, 2))
    dst = truth.apply_affine(A, src)
    region = with_bounding_box(src)
    return call_probe(t, function, (src, dst), candidates=lambda: truth.affine_fit_mistakes(src, dst), truth=A,
                      shape=(2, 3), distance=lambda a, b: point_error(a, b, region), tolerance=1.0)


def _vector_laid_out(function) -> bool:
    """A matrix written out of a vector's entries (`[[p[0], p[1], p[2]], [p[3], p[4], p[5]]]`): three or more
    entries of one name indexed by numbers in one literal."""
    def entries(node) -> list:   # (the literal's own entries, its rows' too: not those inside a sum)
        found = []
        for item in node.elts:
            if isinstance(item, (ast.List, ast.Tuple)):
                found += entries(item)
            elif isinstance(item, ast.Subscript) and isinstance(item.value, ast.Name) \
                    and isinstance(item.slice, ast.Constant) and isinstance(item.slice.value, int):
                found.append((item.value.id, item.slice.value))
        return found

    for node in walk(function):
        if isinstance(node, (ast.List, ast.Tuple)) and isinstance(node.ctx, ast.Load):
            picked = set(entries(node))
            if any(sum(name == other for other, _ in picked) >= 3 for name, _ in picked):
                return True
    return False


# The solved unknowns are laid out by the code: reshaped, or written out entry by entry.
PLACES_UNKNOWNS = calls(".reshape") | calls("np.reshape") | Predicate("writes the matrix out of a vector's entries",
                                                                      _vector_laid_out)
# (a cause guessed from the entries' places: a change of the student's code confirmed to mend it says where)
ENTRIES_MISPLACED = guessed("the solved unknowns put into the matrix in another order than the equations use them")


def judge_affine_fit(t: Trial, what: str, got, expected, src, dst):
    """An affine fit from point pairs: right within :func:`point_tolerance` over the data."""
    got = t.expect_array(got, what, shape=(2, 3), kind="iuf", finite=True)
    region, tolerance = with_bounding_box(src), point_tolerance(src, dst)
    error = point_error(got, expected, region)
    if error <= tolerance:
        return
    mistake = name_mistake(t, got, truth.affine_fit_mistakes(src, dst), lambda a, b: point_error(a, b, region),
                           max(1.0, 100 * tolerance), truth=expected, probe=fit_probe(t, "affine_from_points"))
    if mistake:
        t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    shown, wanted = format_arrays_apart(got, expected, 6)
    misplaced = entries_misplaced(got, expected)
    # (a cause about how the unknowns are placed only where the code places them: a solve giving A.T whole
    # -- `np.linalg.solve(S, dst).T` -- has its entries misplaced by another step, its rows paired wrongly)
    places = PLACES_UNKNOWNS.holds(code_of(t).reachable([what.partition("(")[0]]))
    if misplaced and not places:
        t.fail(f"{what} holds the six right numbers, in other places: " + measured(f"{misplaced}.")
               + f"\nIt returned\n{shown}\nexpected\n{wanted}")
    if misplaced:
        # measured: each returned entry is one of the expected six, all of them once
        t.fail(f"{what} holds the six right numbers, in other places: " + measured(
            f"{misplaced}; it looks like {ENTRIES_MISPLACED} (is the solution vector reshaped in its own order, "
            "(a, b, c, d, tx, ty) say, where A is [[a, b, tx], [c, d, ty]]?)") + f"\nIt returned\n{shown}\nexpected\n{wanted}",
            mistake=ENTRIES_MISPLACED)
    t.fail(f"{what} sends the points up to {digits_apart(error, tolerance)} px away from where the "
           f"true map sends them (at most {tolerance:.3g} px expected).\nIt returned\n{shown}\n"
           f"expected\n{wanted}")


@ex5.check("affine_from_points on a worked example", points=2)
def affine_from_points_example(t):
    src = np.array([[0.0, 0.0], [100.0, 0.0], [0.0, 100.0]])
    A = np.array([[0.9, -0.2, 30.0], [0.3, 1.1, 20.0]])
    dst = truth.apply_affine(A, src)
    judge_affine_fit(t, "affine_from_points(src, dst)", t.call("affine_from_points", src, dst), A, src, dst)


@ex5.check("affine_from_points recovers any affine map exactly", points=3)
def affine_from_points_property(t):
    def holds(seed):
        rng = np.random.default_rng(seed)
        A, src = truth.random_affine(rng), truth.triangle(rng)
        dst = truth.apply_affine(A, src)
        judge_affine_fit(t, "affine_from_points(src, dst)", t.call("affine_from_points", src, dst),
                         A, src, dst)

    t.for_all(st.integers(0, 2**32 - 1), holds, max_examples=20,
              describe=lambda seed: f"fixtures.lab07 triangle/affine from seed {seed}")
    # and a triangle in normalised coordinates (area 0.35: no collinearity test in square pixels refuses it)
    A = np.array([[0.9, -0.2, 0.3], [0.3, 1.1, -0.1]])
    judge_affine_fit(t, "affine_from_points(src, dst) for a triangle of normalised coordinates",
                     t.call("affine_from_points", SMALL_TRIANGLE, truth.apply_affine(A, SMALL_TRIANGLE)),
                     A, SMALL_TRIANGLE, truth.apply_affine(A, SMALL_TRIANGLE))


SMALL_TRIANGLE = np.array([[0.0, 0.0], [0.8, 0.1], [0.2, 0.9]])


@ex5.check("warp_affine(image, A) keeps the input size", points=3)
def warp_affine_default(t):
    source = photo("rocket", (200, 150))
    A = np.array([[0.8, 0.3, 10.0], [-0.2, 0.9, 40.0]])
    return judge_warp(t, "warp_affine(image, A)", t.call("warp_affine", source, A), source, A,
                      truth.warp_mistakes(A),
        probe=image_probe(t, "warp_affine"))


@ex5.check("warp_affine(grey image, A) keeps a grey image's size too, and vertical stripes shifted down", points=1)
def warp_affine_grey_default(t):
    """The default size read from a grey (H, W) image as from a colour one (`image.shape[1::-1]` is (W, H)
    for both; a slice counted from the end, `shape[-2::-1]`, is (H,) for a grey one)."""
    source = photo("chelsea", (160, 120), grey=True)
    A = np.array([[0.9, -0.2, 20.0], [0.15, 1.05, -5.0]])
    what = "warp_affine(grey image, A)"
    verdict = judge_warp(t, what, call_on(t, what, "warp_affine", source, A), source, A, truth.warp_mistakes(A),
                         probe=image_probe(t, "warp_affine"))
    if verdict.fraction < 1:
        return verdict
    # (a shift along y alone mixes rows only, whatever the interpolation -- nearest, bilinear, bicubic: vertical
    # stripes stay stripes; an interpolation that weighs with x's fraction where y's belongs mixes columns)
    # (compared as they are: the comparison of photos blurs, which would wash 2-px stripes out)
    stripes = np.tile(np.where(np.arange(160) // 2 % 2 == 0, 0, 255).astype(np.uint8), (120, 1))
    what = "warp_affine(grey vertical stripes 2 px wide, a shift of half a pixel down)"
    got = t.expect_array(call_on(t, what, "warp_affine", stripes, HALF_PIXEL_DOWN), what, shape=stripes.shape)
    apart = float(np.abs(got[2:-2].astype(np.float64) - stripes[2:-2]).mean())   # (the rows by the border left out)
    if apart > STRIPES_KEPT:
        t.images(what, given=stripes, yours=got)
        t.fail(measured(f"{what}: a shift along y alone mixes rows only, so each column keeps its one value whatever "
                        f"the interpolation (nearest, bilinear, bicubic); yours differs from the stripes by {apart:.0f} "
                        "grey levels on average: it mixes neighbouring columns too"))
    return verdict


HALF_PIXEL_DOWN = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.5]])
STRIPES_KEPT = 2.0   # grey levels: exact for every interpolation of a shift along y; mixing columns gives ~64


@ex5.check("warp_affine with dsize=(width, height)", points=2)
def warp_affine_dsize(t):
    # grey, as the API allows (the other warp_affine check gives a colour image); then a colour image, whose
    # output is made at dsize too (not like the input); then the identity, which at another size is a crop
    # (a shortcut for a matrix that moves nothing still owes dsize its size -- blind set 1205d's 07/05)
    source = photo("chelsea", (160, 120), grey=True)
    A = np.array([[1.2, 0.1, 5.0], [0.0, 1.1, -10.0]])
    colour = photo("chelsea", (160, 120))
    identity = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    cases = [("warp_affine(grey image, A, dsize=(220, 100))", source, A, (220, 100)),
             ("warp_affine(colour image, A, dsize=(220, 100))", colour, A, (220, 100)),
             ("warp_affine(colour image, the identity, dsize=(100, 90))", colour, identity, (100, 90))]
    try:
        for what, image, M, dsize in cases:
            verdict = judge_warp(t, what, call_on(t, what, "warp_affine", image, M, dsize=dsize), image, M,
                                 truth.warp_mistakes(M), dsize=dsize, probe=image_probe(t, "warp_affine"))
            if verdict.fraction < 1:
                return verdict
        return verdict
    except Fail as failure:
        # (unexplained by the image alone, and dsize read: does its value change anything? A dsize never read
        # is named as a parameter unused, from the code, by the grading itself)
        if not failure.mistake and reads("dsize").found(code_of(t).reachable(["warp_affine"])):
            judge_parameter_used(t, "warp_affine(grey image, A)", lambda **kw: t.call("warp_affine", source, A, **kw),
                                 "dsize", ((220, 100), (180, 140)), "image")
        raise


# ================================================================== ex6 least squares
ex6 = lab.exercise("ex6", "Least-squares affine transformation", functions=["affine_lstsq(src, dst)"])
lab.forbid("affine_lstsq", "cv2.estimateAffine2D", "cv2.estimateAffinePartial2D")


INVERSE_FITTED = "the inverse map (dst -> src) fitted by least squares, then inverted"


# Library fits of another family of maps, whose result is no least-squares affine fit (the call's last name ->
# what it fits)
OTHER_MODELS = {
    "findHomography": "a homography (a perspective map, 8 unknowns): its top two rows are no affine fit -- the "
                      "perspective row takes its share of the residuals -- and 3 pairs, enough for an affine map, "
                      "are too few for it",
    "getPerspectiveTransform": "a homography through exactly 4 pairs (a perspective map, 8 unknowns), no "
                               "least-squares affine fit of N pairs",
    "estimateAffinePartial2D": "a similarity (a rotation, one scale and a shift: 4 unknowns), not the general "
                               "affine map of 6",
}
OTHER_MODEL = "a library fit of another family of maps"


def _feeds_the_return(function, call: ast.Call) -> bool:
    """Whether ``call``'s value reaches a ``return`` of ``function``: returned as it is, or through the names
    assigned from it and from those, in the order the statements are written (one pass: linear in the def).
    A fit called only to compare with, or to check, is not what the function answers."""
    carried, statements = set(), sorted((n for n in walk(function) if isinstance(n, (ast.Assign, ast.Return))),
                                        key=lambda n: (n.lineno, n.col_offset))
    for statement in statements:
        parts = list(walk(statement.value)) if statement.value is not None else []
        reached = any(p is call for p in parts) or any(isinstance(p, ast.Name) and p.id in carried for p in parts)
        if reached and isinstance(statement, ast.Return):
            return True
        if reached:
            carried |= {n.id for target in statement.targets for n in walk(target) if isinstance(n, ast.Name)}
    return False


def _other_model(t: Trial) -> str:
    """The sentence naming a fit of another family the student's affine_lstsq calls and answers with (read in
    its code), or ''."""
    for function in code_of(t).reachable(["affine_lstsq"]):
        for node in walk(function):
            name = _path(node.func).rsplit(".", 1)[-1] if isinstance(node, ast.Call) else ""
            if name in OTHER_MODELS and _feeds_the_return(function, node):
                return from_code(f" Your code fits {OTHER_MODELS[name]} (`cv2.{name}`, line {node.lineno}); the "
                                 "least-squares affine map solves the sheet's 2N x 6 system of all the pairs "
                                 "(np.linalg.lstsq).")
    return ""


def judge_lstsq(t: Trial, src, dst, least_squares, show=False):
    what = f"affine_lstsq(src, dst) with N={len(src)}"
    try:
        answer = t.call("affine_lstsq", src, dst)
    except StudentFailure as failure:
        other = _other_model(t) if failure.outcome.kind == "exception" else ""
        if not other:
            raise
        t.fail(f"{failure.message.rstrip('.')} (raised on {what}).{other}", mistake=OTHER_MODEL)
    got = t.expect_array(answer, what, shape=(2, 3), kind="iuf", finite=True)
    if show:
        from ..engine.pictures import svg_points

        t.svg("where your fit sends the source points", svg_points({
            "target points (noisy)": dst,
            "least-squares fit": truth.apply_affine(least_squares, src),
            "your fit": truth.apply_affine(got, src)}))
    tolerance = point_tolerance(src, dst)
    error = point_error(got, least_squares, src)
    if error <= tolerance:
        return passed(f"within {error:.2g} px of the least-squares fit at every point")
    mistake = name_mistake(t, got, truth.affine_fit_mistakes(src, dst), lambda a, b: point_error(a, b, src),
                           max(0.5, 100 * tolerance), truth=least_squares, probe=fit_probe(t, "affine_lstsq"))
    if mistake:
        t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    if point_error(got, truth.inverse_fit_inverted(src, dst), src) <= 1e-3 * tolerance:
        # (to the digit: a least squares of its own kind, near the right one on mild noise)
        t.fail(f"{what} is not the least-squares fit: it sends a source point {digits_apart(error, tolerance)} px "
               "away from where the least-squares fit sends it; " + measured(
                   "it is, to the digit, the least-squares map from dst to src, inverted: that fit minimises the "
                   "residuals in the source image, where the least-squares map src -> dst minimises them in the "
                   "target image (the sheet's system: [x y 1] rows of src, x' y' of dst on the right)"),
               mistake=INVERSE_FITTED)
    residual = float(np.sqrt(np.mean(np.sum((truth.apply_affine(got, src) - dst) ** 2, axis=1))))
    best = float(np.sqrt(np.mean(np.sum((truth.apply_affine(least_squares, src) - dst) ** 2, axis=1))))
    # The residual grows only to second order in the error: quoted only when the digits show it.
    residuals = f"; RMS residual {residual:.4f} px where the least-squares fit has {best:.4f} px" \
        if f"{residual:.4f}" != f"{best:.4f}" else ""
    subsets = call_in_a_loop(code_of(t).reachable(["affine_lstsq"]), _EXACT_FITS)
    cause = from_code(f" Your code fits the map exactly to a few points at a time (`{subsets[0]}` in a loop, line "
                      f"{subsets[1]}) and combines the fits: an average of exact fits is not the least-squares fit "
                      "of all the points; solve the one system of all 2N equations (np.linalg.lstsq).") if subsets else ""
    other = "" if subsets else _other_model(t)
    t.fail(f"{what} is not the least-squares fit: it sends a source point "
           f"{digits_apart(error, tolerance)} px away from where the least-squares fit sends it "
           f"(at most {tolerance:.3g} px expected)"
           f"{residuals}.{cause or other}", mistake=from_code("exact fits of a few points combined") if subsets
           else OTHER_MODEL if other else "")


_EXACT_FITS = ("affine_from_points", "getAffineTransform")   # three-point fits


@ex6.check("affine_lstsq on exact correspondences (N=3 and N=12; in pixels and in small units)", points=3)
def lstsq_exact(t):
    rng = np.random.default_rng(7)
    A = truth.random_affine(rng)
    for n in (3, 12):
        src = rng.uniform(0, 400, size=(n, 2))
        judge_lstsq(t, src, truth.apply_affine(A, src), A)
    # (points in other units -- metres, a few centimetres apart -- are points like any others:
    # a test of collinearity against a fixed number, det(M^T M) < 1e-6, refuses them)
    small = A * [1.0, 1.0, 1e-3]
    src = rng.uniform(0, 0.05, size=(8, 2))
    judge_lstsq(t, src, truth.apply_affine(small, src), small)


@ex6.check("affine_lstsq is the least-squares fit to noisy points", points=4)
def lstsq_noisy(t):
    src, dst, _, least_squares = truth.noisy_correspondences(seed=11, n=40, noise=2.0)
    judge_lstsq(t, src, dst, least_squares, show=True)


@ex6.check("affine_lstsq property: any noisy affine problem", points=3)
def lstsq_property(t):
    def holds(case):
        seed, n = case
        src, dst, _, least_squares = truth.noisy_correspondences(seed, n, noise=1.5)
        judge_lstsq(t, src, dst, least_squares)

    t.for_all(st.tuples(st.integers(0, 2**32 - 1), st.integers(4, 60)), holds, max_examples=15,
              describe=lambda c: f"fixtures.lab07.noisy_correspondences(seed={c[0]}, n={c[1]})")


# ================================================================== the API's conventions judged elsewhere
_OWN_GREY = "judged on a grey image against the truth by a check of its own"
conventions.not_judged("channels", translate=_OWN_GREY, rotate=_OWN_GREY, scale=_OWN_GREY, shear=_OWN_GREY,
                       warp_affine=_OWN_GREY)
conventions.not_judged("rows", affine_from_points=conventions.FITTED, affine_lstsq=conventions.FITTED)


conventions.not_judged("integers", affine_from_points=conventions.MODEL, affine_lstsq=conventions.MODEL)
