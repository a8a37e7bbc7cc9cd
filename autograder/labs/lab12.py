"""Lab 12 - stereo: the public checks.

Ground truth comes from :mod:`fixtures.lab12`: rectified pairs rendered from
textured planes with their exact disparity maps, the Middlebury motorcycle pair
shipped with scikit-image with its measured disparities, unrectified pairs with
exact correspondences, and the structured-light patterns and simulation exactly
as the API defines them. Disparity maps are judged by their bad-pixel rate
(error above a threshold, invalid pixels counted bad, measured where the truth
is known) against figures precomputed on the same scene by
``fixtures/make_lab12_figures.py``: for SSD block matching, the worst of the
legitimate matchers (the reference, a Gaussian prefilter, SAD, and the lab
sheet's ``cv2.StereoBM``; ``benchmarks/spread_block_matching.py`` prints the
spread), right of the band where no matcher can search every disparity; for
DP and NCC, the reference's.
"""

from __future__ import annotations

import ast
from dataclasses import replace
from typing import Callable

import cv2
import numpy as np

from fixtures import lab12 as truth
from fixtures.images import coverage, tinted

from ..engine import inplace
from ..engine import conventions
from ..engine import strategies as st
from ..engine.checks import Fail, StudentFailure, Trial, partial, passed
from ..engine.compare import (HALF_PIXEL_OFFSETS, at_precision, blurred_difference, describe_difference,
                       fill_fraction, format_apart, format_arrays_apart, magnitude, max_abs_error, nearest_variants)
from ..engine.claims import (calls_any, checklist, divides_by, from_code, guard, guessed, look_at, measured,
                             passes_parameters, takes_last_row_of_vt, where_to_look, wherever_written)
from ..engine.forms import shape_form
from ..engine.ignored import never_read
from ..engine.hints import (KEEPS_HIGHEST, KEEPS_LOWEST, TO_FLOAT, TO_UINT8, Hint, Predicate, _path, calls, code_of, expr,
                            keyword, mentions,
                            size_given_as_shape)
from ..engine.judges import (BLACK_FILL_HINT, FILL_TOLERANCE, Probe, call_probe, fail_if_front_points_not_given,
                            fail_if_points_left_out, fingerprint,
                      judge_default_is_the_apis,
                      judge_parameter_changes_result, judge_parameter_used, name_mistake, over_variants,
                      repeating_border, same_informative_result)
from ..engine.mutants.repair import found_on_earlier_checks
from ..engine.pictures import disparity_error_picture, disparity_picture, side_by_side
from ..engine.registry import Lab
from .code_signs import (DIVIDES_BY_16, STEREO_MATCHER, constant_factor, factor_words, name_batched_vt_row,
                         zero_taken_for_missing)
from ..loading.parsing import walk

# OpenCV's matcher called, its answer never divided by 16 (a sign, said with a measurement).
STEREO_MATCHER_UNDIVIDED = (STEREO_MATCHER & ~DIVIDES_BY_16).saying(
    "calls OpenCV's block matcher and never divides by 16")

lab = Lab("lab12", module="lab12_stereo", title="Stereo")

# Names and sentences that ask for code, held to the student's code (autograder.engine.claims).
# A block's deviation (or the square root of a product of variances) as a divisor.
STD_PRODUCT = divides_by("np.sqrt(_ * _)", "np.sqrt(_) * np.sqrt(_)", "_.std() * _.std()", "np.std(_) * np.std(_)",
                         "(_ * _) ** 0.5", "np.sqrt(_ * _) + _", "np.sqrt(_ * _ + _)", "_.std() * _.std() + _",
                         "_ * _.std() * _.std()", "_ * np.std(_) * np.std(_)",
                         says="divides by a product of the blocks' deviations")
guard(truth.NCC_BY_VARIANCE, asks=STD_PRODUCT,
      instead="the NCC is divided by the right block's variance (std_R^2, or var_L var_R): your code {found}, so "
              "look at which blocks' deviations are multiplied (std_L std_R, each a square root)")
FOURTH_COORDINATE = divides_by("_[:, 3]", "_[:, 3:]", "_[:, 3:4]", "_[:, 3, None]", "_[:, -1]", "_[:, -1:]",
                               "_[:, -1, None]", "_[3]", "_[-1]", "_[3, :]", "_[-1, :]", "_[..., 3:]", "_[..., -1:]",
                               "_[..., 3]", "_[..., -1]", says="divides by the fourth coordinate")
guard(truth.THIRD_NOT_FOURTH, asks=FOURTH_COORDINATE,
      instead="X comes out divided by its third coordinate: your code {found}, so look at the layout of the array "
              "it indexes ((N, 4) rows or (4, N) columns?) and at the X returned")


def _xor(function) -> bool:
    """``a ^ b`` or ``a ^= b`` written in ``function``."""
    return any(isinstance(node, (ast.BinOp, ast.AugAssign)) and isinstance(node.op, ast.BitXor)
               for node in walk(function))


XORS = (Predicate("computes an XOR", _xor) | calls("np.bitwise_xor") | calls("np.logical_xor")).saying(
    "computes an XOR")
# (read in the decoder and its helpers only: an XOR in gray_code_patterns, which a check calls to make its
# images, is no decoding step -- 06j 12/06)
guard(truth.PLAIN_BINARY_DECODE, asks=XORS,
      instead="the patterns are decoded as plain binary: your code {found}, so check both steps: the Gray code turned "
              "into binary (b_0 = g_0, b_i = b_(i-1) XOR g_i), and the stripe index read from those binary bits b, "
              "not from the Gray bits g", functions=("depth_from_structured_light",))

MARGIN = 0.05   # bad-pixel rate accepted above the reference's on the same scene (DP, NCC)
SLACK = 0.03    # block matching (SSD): accepted above the worst legitimate matcher's rate
FAR_SLACK = 0.1  # pixels at infinity given d >= 1, accepted above the worst legitimate matcher's
TOP_SLACK = 0.1  # pixels at d = max_disparity given it: accepted below the worst legitimate matcher's
FADE = 0.15     # partial credit fades out over this much more
STEREO_TIMEOUT = 30.0


# ================================================================== shared judges
def figures(scene_key: str, method: str) -> dict:
    return truth.reference_figures()[scene_key][method]


def show_disparity(t: Trial, title: str, scene, got, bad=None, judged=None):
    judged = scene.judged if judged is None else judged
    caption = (f"bad-pixel rate {bad:.1%} (error > {scene.threshold:g} px or invalid, where the "
               f"truth is known, ignoring the outer {truth.JUDGE_BORDER} pixels). Errors: green = good, "
               "yellow to red = wrong, blue = invalid, grey = not judged") if bad is not None else ""
    picture = None
    if isinstance(got, np.ndarray) and got.shape == scene.disparity.shape and got.dtype.kind in "iuf":
        picture = got
    t.images(title, caption, left_image=scene.left,
             true_disparity=disparity_picture(scene.disparity, scene.max_disparity),
             yours=None if picture is None else disparity_picture(picture, scene.max_disparity),
             errors=None if picture is None else disparity_error_picture(judged, picture, scene.threshold))


def expect_disparity(t: Trial, what: str, got, scene) -> np.ndarray:
    """The returned map as an (H, W) number array, or a failure naming the shape mistake."""
    shape = scene.disparity.shape
    if isinstance(got, np.ndarray) and got.shape != shape:
        if got.shape == shape[::-1]:
            t.fail(f"{what} returned shape {got.shape}; expected {shape}: rows and columns are swapped",
                   mistake="the result is transposed")
        if got.ndim == 2 and got.shape[0] == shape[0] and got.shape[1] < shape[1]:
            t.fail(f"{what} returned shape {got.shape}; expected {shape}: {shape[1] - got.shape[1]} columns are "
                   "missing (the map has the left image's size, pixels without a match marked invalid (0))")
    return t.expect_array(got, what, shape=shape, kind="iuf")


def _disparity_name(node) -> bool:
    return isinstance(node, ast.Name) and node.id.lower().startswith("d")


def _stores_by_disparity(function) -> bool:
    """A cost stored at an index read from the disparity (``costs[d] = ...``, ``volume[:, :, d] = ...``), or costs
    collected in order (``.append``, ``np.stack``): read leniently."""
    for n in walk(function):
        if isinstance(n, (ast.Assign, ast.AugAssign)):
            targets = n.targets if isinstance(n, ast.Assign) else [n.target]
            if any(isinstance(t, ast.Subscript) and any(_disparity_name(m) for m in walk(t.slice)) for t in targets):
                return True
        if isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] in ("append", "stack", "dstack", "array"):
            return True
    return False


def _marks_left_border(function) -> bool:
    """The columns x < d given a cost of their own (``np.inf``, a slice up to d, a test against d): read leniently;
    a slice from d on alone (``costs[d][:, d:] = ...``) leaves the columns before d as they were."""
    for n in walk(function):
        if isinstance(n, (ast.Name, ast.Attribute)) and _path(n).rsplit(".", 1)[-1] in ("inf", "nan", "Inf", "NaN"):
            return True
        if isinstance(n, ast.Constant) and isinstance(n.value, (int, float)) and abs(n.value) >= 1e6:
            return True
        if isinstance(n, ast.Slice) and _disparity_name(n.upper) and n.lower is None:   # costs[d, :, :d] = ...
            return True
        # (a test of d against a column -- `x < d`, `x - d >= 0` --, not against a number: `if d == 0:` starts a
        # running minimum; third-party audit of 2026-12-07)
        operands = [n.left, *n.comparators] if isinstance(n, ast.Compare) else []
        if any(_disparity_name(m) for m in operands) and \
                not all(_disparity_name(m) or isinstance(m, ast.Constant) for m in operands):
            return True
    return False


LOWEST_COST_HINT = Hint(
    "for left pixel (x, y) compare its block with the block around (x - d, y) in the right image, "
    "d = 0..max_disparity, and keep the d with the lowest cost",
    asks=KEEPS_LOWEST,
    # (code that keeps the lowest cost has its search written: restating the search would tell it
    # what it does; what is left is how each block's cost is computed and which blocks are compared)
    instead="your code already {found}: " + checklist(
        "", ("a block's cost is the sum or mean of the squared differences over the block, computed in floats",
             Predicate("converts the images", lambda f: _converts_an_image(f))),
        ("the blocks compared are left (x, y) and right (x - d, y), d = 0..max_disparity",
         Predicate("shifts by the disparity", lambda f: _shifts_by_disparity(f))),
        none_left=look_at(("where each cost is stored (the cost of disparity d at index d)",
                           Predicate("stores each cost at its disparity", _stores_by_disparity)),
                          ("the columns near the left border (no block at x - d there)",
                           Predicate("marks the columns without a block at x - d", _marks_left_border)))))




def _shifts_by_disparity(function) -> bool:
    """A subtraction of a disparity (``x - d``, ``right[:, :-d]``, ``np.roll(right, d)``): the right block taken at
    x - d, read leniently (any name starting with d or disp, any roll)."""
    return calls("np.roll").holds([function]) or any(
        isinstance(n, ast.BinOp) and isinstance(n.op, ast.Sub) and isinstance(n.right, ast.Name)
        and n.right.id.lower().startswith("d") for n in walk(function)) or any(
        isinstance(n, ast.Slice) and any(isinstance(b, ast.UnaryOp) and isinstance(b.operand, ast.Name)
                                         and b.operand.id.lower().startswith("d") for b in (n.lower, n.upper))
        for n in walk(function))


def _parameters_read(function) -> tuple:
    """``(read, of)``: name -> the positions of the function's parameters its value is computed from (through
    assignments, tuples unpacked element by element: ``grey_l, grey_r = f(left), f(right)``), and ``of(node)``,
    the positions an expression reads."""
    parameters = [a.arg for a in function.args.posonlyargs + function.args.args]
    read = {name: {i} for i, name in enumerate(parameters)}

    def of(node) -> set:
        return set().union(*[read.get(n.id, set()) for n in walk(node) if isinstance(n, ast.Name)])
    pairs = []
    for n in walk(function):
        if isinstance(n, ast.Assign):
            for target in n.targets:
                if isinstance(target, ast.Tuple) and isinstance(n.value, ast.Tuple) \
                        and len(target.elts) == len(n.value.elts):
                    pairs += [(t, v) for t, v in zip(target.elts, n.value.elts) if isinstance(t, ast.Name)]
                elif isinstance(target, ast.Name):
                    pairs.append((target, n.value))
    for _ in range(3):   # names from names, a few steps
        for target, value in pairs:
            if target.id not in parameters:
                read[target.id] = read.get(target.id, set()) | of(value)
    return read, of


def _computes_left_first(function) -> bool | None:
    """``matcher.compute(left, right)``: the first image read from the first parameter (left); False only where the
    first is read from the right image alone and the second from the left alone."""
    computes = [n for n in walk(function) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)
                and n.func.attr == "compute" and len(n.args) >= 2]
    if not computes:
        return None
    _, of = _parameters_read(function)
    return not any(of(n.args[0]) == {1} and of(n.args[1]) == {0} for n in computes)


def _sixteens(function) -> bool:
    """A 16 written (numDisparities rounded to a multiple of 16); read leniently."""
    return any(isinstance(n, ast.Constant) and not isinstance(n.value, bool) and n.value in (16, 16.0)
               for n in walk(function))


# Code that calls OpenCV's matcher has its block search done: what is left to tell is what it is given and what
# is done with its answer, each item held to the code.
OPENCV_MATCHER_HINT = Hint(
    LOWEST_COST_HINT.text, asks=STEREO_MATCHER,
    instead="your code {found}, which compares the blocks and keeps the lowest cost itself: " + checklist(
        "", ("it is given the left image first (matcher.compute(left, right))",
             wherever_written("gives compute the left image first", _computes_left_first)),
        ("its int16 answer is divided by 16 (disparities in 1/16 px)", DIVIDES_BY_16),
        ("numDisparities is a multiple of 16 above max_disparity", Predicate("writes a 16", _sixteens)),
        ("it is given grey uint8 images", TO_UINT8 | calls("cv2.cvtColor") | mentions("np.uint8")),
        none_left=look_at(("the pixels where no match is found (-16 in its answer)",
                           expr("_ <= 0") | expr("_ < 0") | expr("_ > 0") | expr("_ >= 0") | expr("_ == -16")
                           | expr("_ < 1") | expr("_ > _")))))


DP_STEPS = ("the difference can come from any step of the lab sheet's: the matching cost, the accumulation along "
            "the row with its smoothness penalty, and the backtracking from the last column")


# a name compared, not called: kept out of the functions' own constants, where stubs.functions_called
# would count it as a call (and every matcher check would then wait on the DP too)
DP_FUNCTION = "dp_stereo"


def judged_function(what: str) -> str:
    """The student function whose answer ``what`` describes ("dp_stereo(left, right)" -> "dp_stereo")."""
    return what.split("(", 1)[0].strip()


def matching_hint(t: Trial, what: str) -> str:
    """For a wrong map of ``what``: the block-search recipe, or, for code calling OpenCV's matcher, what
    is left to check; for the DP, where the difference can come from (its own steps, not block matching's)."""
    function = judged_function(what)
    if function == DP_FUNCTION:
        return dp_hint(t)
    if OPENCV_MATCHER_HINT.contradicts(code_of(t), [function]):
        return OPENCV_MATCHER_HINT.said(t, [function])
    return LOWEST_COST_HINT.said(t, [function])


FIXED_POINT_HINT = Hint(
    "(it looks like OpenCV's fixed point: StereoBM and StereoSGBM return 16 times the disparity; divide by 16).",
    asks=DIVIDES_BY_16,
    instead="(it looks like OpenCV's fixed point: StereoBM and StereoSGBM return 16 times the disparity; your code "
            "{found}, but not the map returned).")


def judge_disparity(t: Trial, what: str, got, scene, reference_bad: float, *, again=None,
                    show: bool = True, threshold_name: str = "reference solution:",
                    judged=None, allowed=None, accepted_by: str = "", probe=None, mistakes=None, naming=None):
    """Judge a disparity map by its bad-pixel rate against the reference's, naming mistakes.

    ``again(left, right)`` calls the student's function on another pair (used to
    recognise a search in the wrong direction, on the swapped views). ``probe()``
    looks, for a failing map only, for the mistakes only another call can show (a
    parameter ignored); it fails naming one, or returns. ``judged``
    replaces the scene's judged truth, ``allowed`` the accepted rate (default: the
    reference's plus :data:`MARGIN`), explained by ``accepted_by``. ``mistakes()`` gives,
    for a failing map only, the maps the usual mistakes give (name -> map). ``naming()``, for a
    failing map no check names, offers the error model a small input (:func:`naming_crop`).
    """
    got = expect_disparity(t, what, got, scene)
    judged = scene.judged if judged is None else judged
    fail_if_an_edge_row_left_out(t, what, got, scene.disparity)
    bad = truth.bad_pixel_rate(got, judged, scene.threshold)
    if show:
        show_disparity(t, f"{what} on {scene.name}", scene, got, bad, judged)
    allowed = reference_bad + MARGIN if allowed is None else allowed
    if bad <= allowed:
        return passed(f"bad-pixel rate {bad:.1%} ({threshold_name} {reference_bad:.1%}{accepted_by})")
    summary = (f"bad-pixel rate {format_apart(bad, allowed, 2, percent=True)} ({threshold_name} "
               f"{reference_bad:.1%}{accepted_by})")
    fraction = (allowed + FADE - bad) / FADE  # partial credit near the accepted rate
    try:
        diagnose_disparity(t, what, got, scene, allowed, again, judged, mistakes)
        if what.startswith("block_matching"):
            name_left_image_shifted(t, what, got, scene.max_disparity)
        if NCC_CALL in what:
            name_ncc_normalisation(t, what)
        if probe is not None:
            probe()
    except Fail as named:
        if fraction <= 0:
            raise
        # A named mistake says why the map falls short; it does not take the credit the map earns.
        return partial(fraction, f"{named.message} {summary}; up to {allowed:.1%} gets full marks.",
                       hint=named.hint, mistake=named.mistake)
    if naming is not None:
        naming()
    where = where_disparities_wrong(got, judged, scene.threshold)
    if fraction > 0:
        return partial(fraction, f"{what}: {where}. {summary}; up to "
                       f"{allowed:.1%} gets full marks (see the error map).")
    t.fail(f"{what}: most of the map is wrong: {where}. {summary} (see the error map).",
           hint=NCC_HINT.said(t) if NCC_CALL in what else matching_hint(t, what))


def where_disparities_wrong(got, judged, threshold) -> str:
    """What the wrong pixels of a disparity map have in common, measured, in words.

    No cause is guessed: the sentence says whether the wrong pixels are mostly
    invalid, mostly too small or too large, or gathered in one part of the image.
    """
    got, judged = np.asarray(got, np.float64), np.asarray(judged, np.float64)
    known = judged > 0
    with np.errstate(invalid="ignore"):
        valid = np.isfinite(got) & (got > 0)
        bad = known & ~(valid & (np.abs(got - judged) <= threshold))
    if not bad.any():
        return "no pixel is wrong"
    invalid = float(np.mean(~valid[bad]))
    if invalid >= 0.6:
        return f"{invalid:.0%} of the wrong pixels have no disparity (0, negative or NaN)"
    height, width = got.shape
    columns, rows = np.mgrid[0:height, 0:width][::-1]
    for name, region in (("leftmost quarter", columns < width / 4), ("rightmost quarter", columns >= 3 * width / 4),
                         ("top quarter", rows < height / 4), ("bottom quarter", rows >= 3 * height / 4)):
        in_region = float(np.mean(region[bad]))
        if in_region >= 0.5 and np.mean(region[known]) <= 0.3:
            return f"{in_region:.0%} of the wrong pixels are in the {name} of the image"
    error = (got - judged)[bad & valid]
    too_small = float(np.mean(error < 0))
    if too_small >= 0.8 or too_small <= 0.2:
        side = "too small" if too_small >= 0.8 else "too large"
        share = too_small if too_small >= 0.8 else 1 - too_small
        return (f"{share:.0%} of the wrong disparities are {side} (median error "
                f"{np.median(error):+.3g} px; your largest disparity is {np.max(got[valid]):.3g}, "
                f"the true ones reach {judged[known].max():.3g})")
    return (f"the wrong pixels are spread over the map ({invalid:.0%} of them invalid, the others "
            f"off by {np.median(np.abs(error)):.3g} px in the median)")


NAMING_ROWS = 16   # rows of a scene the error model names a matcher's mistake on (its mutants run there)
NAMING_COLUMNS = 64   # and, for the DP (a loop over the columns), its rightmost columns


def naming_crop(t: Trial, function: str, scene, columns: int | None = None, **kwargs):
    """``naming()`` for :func:`judge_disparity`: the student's ``function`` on the :data:`NAMING_ROWS`
    central rows of ``scene``'s pair (and its ``columns`` rightmost columns, all by default), offered
    to the error model in place of the check's calls (:meth:`~autograder.engine.checks.Trial.naming_input`).
    Measured with a block_matching mistake the model names: 7.4 s on the check's calls, 2.1 s on the
    band (its 3 s a check); dp_stereo's 178 mutants: 42 s, 13 s on the band, 4 s on 64 columns."""
    def offer():
        top = max(0, scene.left.shape[0] // 2 - NAMING_ROWS // 2)
        rows = slice(top, top + NAMING_ROWS)
        cols = slice(-columns if columns else None, None)
        t.naming_input(function, np.array(scene.left[rows, cols]), np.array(scene.right[rows, cols]),
                       max_disparity=scene.max_disparity, **kwargs)
    return offer


class MatchingMistakes:
    """The maps the usual winner-take-all mistakes give on ``scene`` (called), and the
    confirmation probe that tells them apart on another scene (:meth:`probe`)."""

    PROBE_SCENE = dict(seed=12_012, n_boxes=2, noise=1.0)

    def __init__(self, scene, block_size: int, cost: str = "ssd"):
        self.scene, self.block_size, self.cost = scene, block_size, cost

    def __call__(self) -> dict:
        return truth.matching_mistakes(self.scene, self.block_size, self.cost)

    def matched(self) -> np.ndarray:
        """A right winner-take-all matcher's map of the scene (its blocks centred on their pixels)."""
        return truth.winner_take_all(self.scene, self.block_size, self.cost)

    def probe(self, t: Trial) -> Probe:
        scene = truth.random_dot_scene(**self.PROBE_SCENE)
        columns = np.arange(scene.judged.shape[1])[None, :] >= scene.max_disparity
        mask = (scene.judged > 0) & columns
        return call_probe(t, "block_matching", (np.array(scene.left), np.array(scene.right)),
                          dict(max_disparity=scene.max_disparity, block_size=self.block_size, cost=self.cost),
                          candidates=lambda: truth.matching_mistakes(scene, self.block_size, self.cost),
                          truth=scene.judged, shape=scene.judged.shape, distance=truth.map_disagreement(mask),
                          tolerance=0.2)


def name_matching_mistake(t: Trial, what, got, scene, judged, mistakes):
    """Fail naming the mistake whose map ``got`` is, where every disparity can be searched, here
    and on ``mistakes``' probe scene."""
    candidates = mistakes()
    columns = np.arange(got.shape[1])[None, :] >= scene.max_disparity
    mask = (judged > 0) & columns
    probe = mistakes.probe(t) if hasattr(mistakes, "probe") else None
    mistake = name_mistake(t, got, candidates, truth.map_disagreement(mask), 0.2, truth=judged, probe=probe)
    if mistake:
        t.fail(f"{what}: it looks like {mistake}.", mistake=mistake)


FIXED_POINT = "OpenCV's 16x fixed-point disparities, not divided by 16"
# The code's half of that name: OpenCV's matcher called, its answer never divided by 16.
FIXED_POINT_KEPT = from_code("your code calls OpenCV's block matcher and never divides its answer by 16: "
                             "StereoBM and StereoSGBM return int16 disparities in 1/16 px (16 times the "
                             "disparity, -16 where no match is found); divide by 16 in floating point "
                             "(compute(left, right).astype(np.float32) / 16)")
# Factors a map in pixels is commonly off by, in words ("16 times the expected").
FACTORS = {16.0: "16 times", 1 / 16: "1/16 of", 2.0: "twice", 0.5: "half", 4.0: "4 times", 0.25: "a quarter of"}
EXPLAINED = 0.8      # share of the valid, unclipped pixels a single factor must explain
AT_TOP = 0.5         # share of the valid pixels at the map's largest value: a map clipped there


def disparity_scale(got, judged, threshold, max_disparity) -> tuple[float | None, float]:
    """``(c, clipped)``: the factor ``c`` with ``got ~ c * truth`` on the valid pixels whose value is not
    the map's largest (a map clipped at ``max_disparity`` or its own top keeps the others' scale),
    when it explains :data:`EXPLAINED` of them within ``threshold`` (None: no single factor does);
    ``clipped`` the share of the valid pixels at ``max_disparity`` or above (the truth's is small)."""
    got, judged = np.asarray(got, np.float64), np.asarray(judged, np.float64)
    valid = (judged >= 1) & np.isfinite(got) & (got > 0)   # (a wall at infinity has no scale to tell)
    if valid.sum() <= 10:
        return None, 0.0
    top = float(got[valid].max())
    at_top = valid & (got >= top - 1e-9)
    clipped = float(np.mean(got[valid] >= max_disparity - 1e-9))
    unclipped = valid & ~at_top if at_top.sum() >= 0.1 * valid.sum() else valid
    if unclipped.sum() <= 10:
        return None, clipped
    ratio = float(np.median(got[unclipped] / judged[unclipped]))

    def explained(factor) -> float:
        return float(np.mean(np.abs(got[unclipped] / factor - judged[unclipped]) <= threshold))
    # A round factor near the median ratio that explains about as many pixels is the one said.
    share = explained(ratio)
    for factor in FACTORS:
        if abs(ratio / factor - 1) <= 0.2 and explained(factor) >= share - 0.05:
            ratio, share = factor, explained(factor)
            break
    return (ratio if share >= EXPLAINED else None), clipped


def name_disparity_scale(t: Trial, what: str, got, judged, threshold, max_disparity):
    """Fail telling the factor a failing map is off by (16 times, half, ...), measured on the pixels
    it has not clipped, and, where the code calls OpenCV's matcher without dividing by 16, naming
    the fixed point (also when the map is clipped at ``max_disparity`` almost everywhere)."""
    ratio, clipped = disparity_scale(got, judged, threshold, max_disparity)
    judged_code = code_of(t).reachable([judged_function(what)])   # a DP check also names block_matching
    kept = STEREO_MATCHER_UNDIVIDED.holds(judged_code)
    truth_at_top = float(np.mean(judged[judged > 0] >= max_disparity - 0.5)) if np.any(judged > 0) else 0.0
    if ratio is not None and abs(ratio - 1) > 0.3:
        # OpenCV's fixed point is said only to code that calls OpenCV's matcher (a DP may not).
        fixed_point = abs(ratio - 16) <= 0.1 * 16 and STEREO_MATCHER.holds(judged_code)
        factor = next((words for value, words in FACTORS.items() if abs(ratio / value - 1) <= 0.1), None)
        said = f"{factor} the expected" if factor else f"{ratio:.3g} times the expected"
        cause = (FIXED_POINT_KEPT + "." if kept else FIXED_POINT_HINT.said(t, [judged_function(what)])) if fixed_point else \
            measured("they are expected in pixels.")
        t.fail(f"{what}: the disparities are {said} (on the pixels not clipped)"
               + (f": it looks like {FIXED_POINT}: " if fixed_point and kept else ": ") + cause,
               mistake=FIXED_POINT if fixed_point else "the disparities are rescaled")
    if not kept:
        return
    if clipped >= AT_TOP and truth_at_top <= 0.1:
        t.fail(f"{what}: {clipped:.0%} of your valid disparities are max_disparity ({max_disparity}) or more, "
               f"where {truth_at_top:.0%} of the true ones are: it looks like {FIXED_POINT}: "
               + FIXED_POINT_KEPT + ", before comparing with max_disparity.", mistake=FIXED_POINT)
    known = judged > 0
    with np.errstate(invalid="ignore"):
        found = float(np.mean(np.isfinite(got[known]) & (got[known] > 0))) if known.any() else 1.0
    if found < 1 - AT_TOP:
        t.fail(f"{what}: only {found:.0%} of the pixels get a disparity (0 elsewhere): it looks like {FIXED_POINT} "
               "(16 times the disparity is above max_disparity nearly everywhere): "
               + FIXED_POINT_KEPT + ", before comparing with max_disparity.", mistake=FIXED_POINT)


MAP_MOVED = "the disparity map is moved by whole pixels (the block is not centred on its pixel)"
MOVES = 8          # pixels a map is tried moved by, each way (a 17 x 17 block's half)
MOVED_AGREES = 0.5   # a moved map disagrees with a block matcher's at most this share of what it does unmoved
MOVED_AT_MOST = 0.25   # and at most this share of the pixels (another recipe's map, moved, is still near it)


def map_moved(got, matched, searched) -> tuple[int, int, float, float] | None:
    """``(dx, dy, apart, as_is)`` when ``got`` moved by ``dx`` px right and ``dy`` down (up to :data:`MOVES`)
    is ``matched`` -- a winner-take-all block matcher's map of the same pair -- on the ``searched`` pixels
    both cover: ``apart`` the share of them more than a pixel off, at most :data:`MOVED_AGREES` times
    ``as_is``, the share unmoved; None otherwise. Measured against a matcher's map, not the truth: a
    matcher's errors at depth edges spread as far as a moved block does."""
    height, width = matched.shape

    def apart(dx, dy) -> float:
        rows, columns = slice(max(0, dy), height + min(0, dy)), slice(max(0, dx), width + min(0, dx))
        part = got[max(0, -dy):height + min(0, -dy), max(0, -dx):width + min(0, -dx)]
        inside = searched[rows, columns]
        with np.errstate(invalid="ignore"):
            return float(np.mean(~(np.abs(part - matched[rows, columns]) <= 1.0)[inside])) if inside.any() else 1.0

    as_is = apart(0, 0)
    best = min(((apart(dx, dy), abs(dx) + abs(dy), dx, dy) for dy in range(-MOVES, MOVES + 1)
                for dx in range(-MOVES, MOVES + 1) if (dx, dy) != (0, 0)))
    return (best[2], best[3], best[0], as_is) if best[0] <= min(MOVED_AGREES * as_is, MOVED_AT_MOST) else None


def _moved_words(dx: int, dy: int, how: str = "") -> str:
    """`3 px right and 3 px down`; with ``how`` "away": where the value comes from (`3 px to the left and
    3 px up`)."""
    parts = [f"{abs(dx)} px " + ("to the " if how else "") + ("right" if dx > 0 else "left") if dx else "",
             f"{abs(dy)} px " + ("down" if dy > 0 else "up") if dy else ""]
    return " and ".join(part for part in parts if part)


MIRRORED_ROWS = "each row of the map is stored mirrored, left to right"


def name_mirrored_rows(t: Trial, what: str, got, gt, threshold, allowed: float, better: float = 0.5):
    """Fail naming :data:`MIRRORED_ROWS` where the map read right to left is right (within ``allowed``) and
    far better than as it is (``better`` times its bad-pixel rate at most): a path collected from the last
    column backwards, stored without reversing."""
    finite = np.nan_to_num(np.asarray(got, np.float64), nan=0.0, posinf=0.0, neginf=0.0)
    mirrored = truth.bad_pixel_rate(finite[:, ::-1], gt, threshold)
    if mirrored <= allowed and mirrored < better * truth.bad_pixel_rate(finite, gt, threshold):
        t.fail(measured(f"{what}: every row is mirrored: read right to left, your map has a bad-pixel rate of "
                        f"{mirrored:.1%}, so column x holds the disparity of column W - 1 - x (a path collected "
                        "from the last column back to the first is in reverse order: reverse it, [::-1], before "
                        "storing it as the row)"), mistake=MIRRORED_ROWS)


def diagnose_disparity(t: Trial, what, got, scene, allowed, again=None, judged=None, mistakes=None):
    gt, thr = (scene.judged if judged is None else judged), scene.threshold
    finite = np.nan_to_num(got.astype(np.float64), nan=0.0, posinf=0.0, neginf=0.0)
    name_mirrored_rows(t, what, finite, gt, thr, allowed)
    if truth.bad_pixel_rate(-finite, gt, thr) <= allowed:
        t.fail(f"{what}: the disparities are negative. d = x_l - x_r is positive: the match "
               "of left pixel x lies at x - d in the right image.", mistake="the disparities are negative")
    for shift in (1, -1):
        if truth.bad_pixel_rate(finite + shift, gt, 0.5) <= allowed:
            # (the range of d and the right image's column x - d both shift every disparity by one: audit of 2026-12-06)
            t.fail(measured(f"{what}: every disparity is off by {'-' if shift > 0 else '+'}1 - "
                            "it looks like an off-by-one error in the disparity index: look at the disparities searched "
                            "(d runs from 0) and at the right image's column matched with left column x (x - d)."),
                   mistake="the disparity index is off by one")
    name_disparity_scale(t, what, finite, gt, thr, scene.max_disparity)
    matched = getattr(mistakes, "matched", None)
    # (a map of the right image's pixels -- the left image shifted where the right one belongs -- is moved by the
    # disparity, the same on a plane: its own check tells it from the code)
    rolled_back = any(map(_left_image_rolled_back, code_of(t).reachable([judged_function(what)])))
    moved = map_moved(finite, matched(), (gt > 0) & (np.arange(gt.shape[1])[None, :] >= scene.max_disparity)) \
        if matched is not None and not rolled_back else None
    if moved is not None:
        dx, dy, apart, as_is = moved
        t.fail(f"{what}: the map is moved: " + measured(
            f"taken {_moved_words(dx, dy)}, it is a block matcher's map of the pair ({apart:.0%} of the pixels "
            f"more than a pixel off, {as_is:.0%} as it is): each pixel holds the disparity found for the pixel "
            f"{_moved_words(-dx, -dy, 'away')} -- the block compared for pixel (x, y) is not centred on (x, y) "
            "(a block from its corner, a padding on one side only), or the map is written at an offset."),
            mistake=MAP_MOVED)
    values = finite[gt > 0]
    if values.size and np.ptp(values) < 1e-9:
        t.fail(f"{what}: every pixel got the same disparity ({values[0]:g}).")
    if mistakes is not None:
        name_matching_mistake(t, what, got, scene, gt, mistakes)
    if again is not None and scene.judged_right is not None:
        try:
            flipped = again(scene.right, scene.left)
        except StudentFailure:
            flipped = None
        if isinstance(flipped, np.ndarray) and flipped.shape == gt.shape and flipped.dtype.kind in "iuf":
            if truth.bad_pixel_rate(flipped, scene.judged_right, thr) <= allowed:
                t.fail(f"{what}: you search in the wrong direction. The match of left pixel x is "
                       "at x - d in the right image (objects appear further left in the right view); "
                       "your matcher finds the right image's disparities when given the views swapped.",
                       mistake="the search runs in the wrong direction (x + d)")


finite_floats = lambda lo, hi: st.floats(lo, hi, allow_nan=False, allow_infinity=False)  # noqa: E731


# ================================================================== ex1 triangulation
ex1 = lab.exercise("ex1", "Triangulation revisited", functions=["triangulate(P1, P2, pts1, pts2)"])
lab.forbid("triangulate", "cv2.triangulatePoints")
VARIANT_SLACK = 1.1   # noisy data: up to 10% above the least accurate textbook variant


def judge_triangulation(t: Trial, what: str, got, P1, P2, pts1, pts2, X_true, exact=True):
    n = len(pts1)
    if isinstance(got, np.ndarray) and got.shape == (n, 4):
        t.fail(f"{what} returned homogeneous (N, 4) points; (N, 3) points are expected, divided by the fourth "
               "coordinate.")
    if isinstance(got, np.ndarray) and got.shape == (3, n) and n != 3:
        t.fail(f"{what} returned shape {got.shape}; expected ({n}, 3): one row per point (this is its transpose).")
    name_batched_vt_row(t, what, got, n)
    linear = truth.linear_triangulation(P1, P2, pts1, pts2)
    fail_if_points_left_out(t, what, got, linear, P1)
    fail_if_front_points_not_given(t, what, got, linear, P1, P2, pts1, pts2)
    got = t.expect_array(got, what, shape=(n, 3), kind="iuf", finite=True)
    scale = max(1.0, float(np.abs(X_true).max()))
    error = np.linalg.norm(got - (X_true if exact else linear), axis=1)
    if exact and error.max() <= at_precision(1e-6 * scale, scale):
        return passed(f"largest 3D error {error.max():.2g}")
    if not exact:
        err_true = np.linalg.norm(got - X_true, axis=1).mean()
        spread = [np.linalg.norm(X - X_true, axis=1).mean()
                  for X in truth.triangulation_variants(P1, P2, pts1, pts2).values()]
        if err_true <= VARIANT_SLACK * max(spread) + 1e-9 * scale:
            return passed(f"mean 3D error {err_true:.3g} (linear triangulation with two or three rows "
                          f"per view, rows scaled or not: {min(spread):.3g} to {max(spread):.3g})")
    depth = np.maximum(np.linalg.norm(X_true, axis=1), 1e-9 * scale)
    distance = truth.triangulation_distance(depth)
    mistakes = nearest_variants(got, truth.triangulation_mistakes(P1, P2, pts1, pts2), distance)
    mistake = name_mistake(t, got, mistakes, distance, 1e-3, truth=X_true, probe=triangulation_probe(t))
    if mistake:
        t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    norms = np.linalg.norm(got, axis=1) * np.linalg.norm(X_true, axis=1)
    cosine = np.abs(np.sum(got * X_true, axis=1)) / np.where(norms > 0, norms, 1.0)
    if np.all(cosine > 1 - 1e-6) and np.ptp(np.linalg.norm(got, axis=1) / np.linalg.norm(X_true, axis=1)) > 1e-3:
        t.fail(f"{what}: each point is right up to its own scale - divide the SVD's homogeneous "
               "solution by its fourth coordinate.")
    factor = constant_factor(got, X_true) if exact else None
    if factor is not None:
        t.fail(f"{what}: every point is {factor_words(factor)} the true one (X, Y and Z alike).", mistake=SCALED_POINTS)
    reprojection = np.linalg.norm(truth.project(P1, got) - pts1, axis=1).mean()
    t.fail(f"{what}: 3D points are off by up to {error.max():.3g} (mean reprojection error in "
           f"image 1: {reprojection:.3g} px).",
           hint=TRIANGULATION_ROWS_HINT.said(t))


# x p3 - p1 written with a point's coordinate times P's third row, minus its first (or OpenCV's own)
ROWS_OF_P = (expr("_ * _[2] - _[0]") | expr("_ * _[2, :] - _[0, :]") | expr("_ * _[2, :] - _[0]")
             | expr("_ * _[2] - _[0, :]") | expr("_[2] * _ - _[0]") | expr("_[2, :] * _ - _[0, :]")
             | calls("cv2.triangulatePoints")).saying("builds the rows x p3 - p1")
# the last row of Vt, one system's (takes_last_row_of_vt) or a stack's (Vt[:, -1], Vt[..., -1, :])
LAST_SINGULAR_VECTOR = (takes_last_row_of_vt() | expr("_[:, -1]") | expr("_[:, -1, :]") | expr("_[..., -1, :]")
                        | calls("cv2.triangulatePoints")).saying("keeps the last row of Vt")
TRIANGULATION_ROWS_HINT = Hint(
    "each view gives two rows, x p3 - p1 and y p3 - p2 (p_i the rows of P); X is the last right singular vector of "
    "the 4x4 matrix", asks=calls("np.linalg.svd") | calls("cv2.triangulatePoints"),
    instead="each view gives two rows, x p3 - p1 and y p3 - p2 (p_i the rows of P); your code already {found}: "
            + checklist("", ("each view's rows are made of its own P's rows and its own point's x and y", ROWS_OF_P),
                        ("the solution is divided by its fourth coordinate",
                         FOURTH_COORDINATE | calls("cv2.convertPointsFromHomogeneous")),
                        # (which point each system is given is no step a reading can find wrong: not pointed at)
                        none_left=look_at(("which singular vector is kept (the last row of Vt of each point's own "
                                           "4x4 system)", LAST_SINGULAR_VECTOR))))


def triangulation_probe(t: Trial) -> Probe:
    """triangulate on another pair of general cameras (10 exact matches)."""
    P1, P2, X, pts1, pts2 = truth.general_points(seed=12_013, n=10)
    distance = truth.triangulation_distance(np.maximum(np.linalg.norm(X, axis=1), 1e-9))
    return call_probe(t, "triangulate", (P1, P2, pts1, pts2),
                      candidates=lambda: truth.triangulation_mistakes(P1, P2, pts1, pts2), truth=X,
                      shape=(len(pts1), 3), distance=over_variants(distance, 2), tolerance=1e-3)


@ex1.check("triangulate on a rectified rig recovers the points (Z = f b / d)", points=3)
def triangulate_rig(t):
    # (the first match on the top row, y = 0, the second on the left column, x = 0: pixels like any other)
    P1, P2, X, pts1, pts2 = truth.stereo_points(seed=3, n=12, on_the_edges=True)
    got = t.call("triangulate", P1, P2, pts1, pts2)
    verdict = judge_triangulation(t, "triangulate(P1, P2, pts1, pts2), match 0 on row y = 0, match 1 at x = 0", got,
                                  P1, P2, pts1, pts2, X)
    return verdict


@ex1.check("triangulate: any two cameras, exact matches", points=3)
def triangulate_property(t):
    # N = 1 too: one match is (1, 2) arrays in, a (1, 3) array out (a squeezed (3,) is not (N, 3))
    def holds(case):
        seed, n = case
        P1, P2, X, pts1, pts2 = truth.general_points(seed, n=n)
        judge_triangulation(t, f"triangulate(P1, P2, pts1, pts2) with N={n}",
                            t.call("triangulate", P1, P2, pts1, pts2), P1, P2, pts1, pts2, X)

    t.for_all(st.tuples(st.integers(0, 2**32 - 1), st.sampled_from((15, 1))), holds, max_examples=12,
              describe=lambda c: f"fixtures.lab12.general_points(seed={c[0]}, n={c[1]})")
    # (a camera matrix is defined up to a non-zero scale, sign included: -P1 is the same camera -- a test of
    # "in front" read off P's third row without the sign of det(P[:, :3]) takes every point for behind it)
    P1, P2, X, pts1, pts2 = truth.general_points(7, n=15)
    judge_triangulation(t, "triangulate(-P1, -0.5 * P2, pts1, pts2) (the same cameras at a negative scale)",
                        t.call("triangulate", -P1, -0.5 * P2, pts1, pts2), -P1, -0.5 * P2, pts1, pts2, X)


@ex1.check("triangulate is as accurate as linear triangulation on noisy matches", points=2)
def triangulate_noisy(t):
    P1, P2, X, pts1, pts2 = truth.general_points(seed=41, n=40)
    rng = np.random.default_rng(42)
    noisy1 = pts1 + rng.normal(0, 0.7, pts1.shape)
    noisy2 = pts2 + rng.normal(0, 0.7, pts2.shape)
    got = t.call("triangulate", P1, P2, noisy1, noisy2)
    return judge_triangulation(t, "triangulate(P1, P2, noisy pts1, noisy pts2)", got,
                               P1, P2, noisy1, noisy2, X, exact=False)


# ================================================================== ex2 disparity and depth
ex2 = lab.exercise("ex2", "Disparity and depth", functions=[
    "disparity_from_matches(xl, xr)", "depth_from_disparity(disparity, f, baseline)"])
# The sheet's exercise 2 outputs the disparity map and the depth map computed from it: the map is
# shown after depth_from_disparity, so writing into it (np.asarray of a float map is no copy) shows.
inplace.shown_after(lab, "depth_from_disparity", "disparity",
                    "exercise 2's expected output is the disparity map and the depth map computed from it")


def judge_disparities(t: Trial, what: str, got, xl, xr, n):
    got = t.expect_array(got, what, shape=(n,), kind="iuf", finite=True)
    expected = xl - xr
    # float32 rounds d = x_l - x_r at the coordinates' magnitude, not the disparity's
    tolerance = at_precision(1e-9 * max(1.0, np.abs(expected).max()), magnitude(xl, xr))
    if max_abs_error(got, expected) <= tolerance:
        return
    if max_abs_error(got, -expected) <= tolerance:
        t.fail(f"{what} has the wrong sign: d = x_l - x_r (positive for a point in front of the rig).",
               mistake="the disparity's sign is reversed (x_r - x_l)")
    negative = expected < 0
    if negative.any() and max_abs_error(got, np.abs(expected)) <= tolerance:
        i = int(np.argmax(negative))
        t.fail(f"{what}: where x_r > x_l (x_l = {xl[i]:g}, x_r = {xr[i]:g}) it returned {got[i]:g}, not "
               f"{expected[i]:g}: " + measured("every disparity came back positive. d = x_l - x_r keeps its sign: "
                                               "a negative one marks a match no point in front of the rig gives "
                                               "(depth_from_disparity makes it invalid)."),
               mistake=ABSOLUTE_DISPARITY)
    shown, wanted = format_arrays_apart(got[:5], expected[:5])
    t.fail(f"{what} returned {shown}...; expected {wanted}... ({describe_difference(got, expected, 'px', tolerance)})")


ABSOLUTE_DISPARITY = "the disparity's sign is dropped (|x_l - x_r|)"


@ex2.check("disparity_from_matches on x coordinates", points=1)
def disparities_from_x(t):
    # the last match is a mismatch, its right point right of the left one: d = x_l - x_r < 0
    xl = np.array([120.5, 80.0, 33.25, 150.0, 12.0])
    xr = np.array([100.5, 72.0, 30.0, 110.0, 19.5])
    judge_disparities(t, "disparity_from_matches(xl, xr)", t.call("disparity_from_matches", xl, xr), xl, xr, 5)
    # Two matches too: two x coordinates have a last axis of length 2, as one (x, y) point has; the contract's
    # (N,) arrays are told from (N, 2) points by their number of dimensions.
    what = "disparity_from_matches(xl[:2], xr[:2])"
    got = t.call("disparity_from_matches", xl[:2], xr[:2])
    if isinstance(got, (np.ndarray, float, np.floating, int, np.integer)) and np.ndim(got) == 0:
        taken = measured(", as if the two x coordinates were one (x, y) point (x_l - x_r of the first match)") \
            if np.isclose(float(got), xl[0] - xr[0]) else ""
        t.fail(f"{what} returned the single number {float(got):g}, not 2 disparities{taken}: 1-D inputs are x "
               "coordinates whatever their length, (N, 2) arrays are points.")
    judge_disparities(t, what, got, xl[:2], xr[:2], 2)


@ex2.check("disparity_from_matches on (N, 2) matched points of a rectified pair", points=2)
def disparities_from_points(t):
    P1, P2, X, pts1, pts2 = truth.stereo_points(seed=8, n=10)
    what = "disparity_from_matches(pts_left, pts_right)"
    got = t.call("disparity_from_matches", pts1, pts2)
    if isinstance(got, np.ndarray) and got.shape == (10, 2):
        t.fail(f"{what} returned shape (10, 2): for (N, 2) points subtract the x coordinates "
               "(column 0) only and return (N,).")
    got = t.expect_array(got, what, shape=(10,), kind="iuf", finite=True)
    tolerance = at_precision(1e-9, magnitude(pts1, pts2))
    if max_abs_error(got, pts1[:, 1] - pts2[:, 1]) <= tolerance < max_abs_error(got, pts1[:, 0] - pts2[:, 0]):
        t.fail(f"{what} subtracts the y coordinates; x (column 0) is what differs in a rectified pair.")
    judge_disparities(t, what, got, pts1[:, 0], pts2[:, 0], 10)
    # (matched points of a real pair are a fraction of a pixel off each other's row: each is still a match)
    off_row = pts2 + np.column_stack([np.zeros(10), np.random.default_rng(9).uniform(-1.5, 1.5, 10)])
    what = "disparity_from_matches(pts_left, pts_right) with the right points up to 1.5 px off the left ones' rows"
    got = t.call("disparity_from_matches", pts1, off_row)
    if np.shape(got) != (10,):
        t.fail(measured(f"{what} returned shape {np.shape(got)} for 10 matches: every match gets its disparity "
                        "d = x_l - x_r, whatever its rows (the API keeps the N matches; none is dropped)"),
               mistake=MATCHES_DROPPED)
    judge_disparities(t, what, t.expect_array(got, what, shape=(10,), kind="iuf", finite=True),
                      pts1[:, 0], off_row[:, 0], 10)


MATCHES_DROPPED = "matches off each other's row are dropped"


def _invalid_depths(got, disparity) -> list[str]:
    """What ``got`` holds where the disparity is invalid, per kind (0, negative, NaN), in words: a depth other than 0
    where d <= 0 (the API's ex2), other than an invalid depth -- 0, below 0 or NaN, the API's conventions -- where d is
    NaN (no match: the API asks nothing more of it)."""
    kinds = (("0", disparity == 0), ("negative", disparity < 0), ("NaN", np.isnan(disparity)))
    found = []
    for kind, where in kinds:
        values = got[where]
        wrong = values[~((values <= 0) | np.isnan(values))] if kind == "NaN" else values[values != 0]
        if wrong.size == 0:
            continue
        value = wrong[0]
        described = ("inf" if value > 0 else "-inf") if np.isinf(value) else "NaN" if np.isnan(value) \
            else f"{value:.3g}"
        found.append(f"where the disparity is {kind}, your depth is {described}")
    return found


def depth_probe(t: Trial) -> Probe:
    """depth_from_disparity of fractional disparities, f and b neither 1 nor alike."""
    d, f, b = np.array([[3.5, 17.25, 61.0], [8.75, 0.6, 29.0]]), 712.5, 0.085
    expected = f * b / d
    return call_probe(t, "depth_from_disparity", (d, f, b), candidates=lambda: truth.depth_mistakes(d, f, b),
                      truth=expected, shape=d.shape, tolerance=1e-6 * float(expected.max()))


def judge_depth(t: Trial, what: str, got, disparity, f, baseline):
    disparity = np.asarray(disparity, dtype=np.float64)
    valid = np.isfinite(disparity) & (disparity > 0)
    expected = np.divide(f * baseline, disparity, out=np.zeros_like(disparity), where=valid)
    got = t.expect_array(got, what, shape=disparity.shape, kind="iuf")
    with np.errstate(invalid="ignore"):
        wrong = _invalid_depths(np.asarray(got, dtype=np.float64), disparity)
    if wrong:
        nan_only = all(w.startswith("where the disparity is NaN") for w in wrong)
        t.fail(f"{what}: " + "; ".join(wrong) + (
               ". A NaN disparity (no match) has no depth: it is invalid there too, 0 (or NaN)." if nan_only else
               ". The depth there must be 0 (invalid): no point of the scene has d <= 0."),
               hint=GUARDED_DIVISION_HINT.said(t))
    if np.isnan(disparity).any() and np.asarray(got).dtype.kind == "f":
        got = np.where(np.isnan(disparity), 0, got).astype(np.asarray(got).dtype)   # (judged above: 0 or NaN there)
    if not np.all(np.isfinite(got)):
        t.fail(f"{what} returned NaN or infinite depths for valid disparities")
    scale = magnitude(expected)
    tolerance = at_precision(1e-9 * scale, scale)
    if max_abs_error(got, expected) <= tolerance:
        return
    fractions = valid & (np.abs(expected - np.round(expected)) > 1e-6 * max(scale, 1.0))
    if got.dtype.kind in "iub" and fractions.any():
        # (an integer array: every depth cut to a whole number -- np.vectorize takes its type from the first
        # value, an int 0 for an invalid pixel, say -- whatever factor the few values tried happen to show)
        t.fail(f"{what} returned an array of {got.dtype} where the depths have fractions (Z = f b / d): "
               + measured("every depth is cut to a whole number; the depths are floats"), mistake=INTEGER_DEPTHS)
    mistake = name_mistake(t, got, truth.depth_mistakes(disparity, f, baseline), max_abs_error,
                           1e-6 * scale, truth=expected, probe=depth_probe(t))
    if mistake:
        t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    factor = constant_factor(got, expected) if int(valid.sum()) >= 3 else None   # (two values: any factor fits)
    if factor is not None:
        t.fail(f"{what}: the depths are {factor_words(factor)} the expected at every pixel (Z = f b / d, in "
               "the baseline's unit).", mistake=SCALED_DEPTHS)
    t.fail(f"{what}: the depths are off by {describe_difference(got, expected, tolerance=tolerance)} "
           "(Z = f b / d).")


SCALED_DEPTHS = "the depths are off by a constant factor"
INTEGER_DEPTHS = "the depths are an integer array (every depth cut to a whole number)"
SCALED_POINTS = "the points are off by a constant factor"


@ex2.check("depth_from_disparity: Z = f b / d on a worked example", points=2)
def depth_example(t):
    d = np.array([10.0, 20.0, 40.0, 2.5])
    judge_depth(t, "depth_from_disparity([10, 20, 40, 2.5], f=500, baseline=0.1)",
                t.call("depth_from_disparity", d, 500.0, 0.1), d, 500.0, 0.1)


@ex2.check("depth_from_disparity gives 0 for invalid disparities (<= 0 or NaN)", points=2)
def depth_invalid(t):
    d = np.array([[8.0, 0.0, -3.0], [np.nan, 16.0, 0.5]])
    judge_depth(t, "depth_from_disparity(map with 0, negative and NaN disparities, f=400, baseline=0.2)",
                t.call("depth_from_disparity", d, 400.0, 0.2), d, 400.0, 0.2)


@ex2.check("depth_from_disparity works for arrays of any shape", points=2)
def depth_any_shape(t):
    def holds(case):
        shape, seed = case
        rng = np.random.default_rng(seed)
        d = rng.uniform(-5, 60, size=shape)
        f, b = rng.uniform(100, 2000), rng.uniform(0.05, 1.0)
        judge_depth(t, f"depth_from_disparity(array of shape {shape}, f={f:.4g}, baseline={b:.4g})",
                    t.call("depth_from_disparity", d, f, b), d, f, b)

    shapes = st.lists(st.integers(1, 6), min_size=1, max_size=3).map(tuple)
    t.for_all(st.tuples(shapes, st.integers(0, 2**32 - 1)), holds, max_examples=10,
              describe=lambda c: f"shape {c[0]}, seed {c[1]}")
    # (and no axis at all: one pixel's disparity as a 0-d array gives a 0-d depth, or a plain number)
    what = measured("depth_from_disparity(np.array(8.0), f=400, baseline=0.1), a 0-d array")
    got = t.call("depth_from_disparity", np.array(8.0), 400.0, 0.1)
    if np.shape(got) != ():   # (every other shape kept: half the points)
        added = ADDS_AN_AXIS.found(code_of(t).reachable(["depth_from_disparity"]))
        return partial(0.5, measured(f"{what} returned shape {np.shape(got)}; the depth of a 0-d disparity is 0-d "
                                     "too (or a plain number): the shape is kept, whatever it is")
                       + (from_code(f"; your code {added}, which gives a 0-d array an axis") if added else "."),
                       mistake=AXIS_ADDED)
    judge_depth(t, what, np.asarray(got), np.array(8.0), 400.0, 0.1)
    return passed("the depths keep the disparities' shape, a 0-d one too")


AXIS_ADDED = "a 0-d disparity gets an axis"
ADDS_AN_AXIS = calls_any("np.atleast_1d", "np.atleast_2d", ".ravel", ".flatten", "np.ravel") | expr("_.reshape(-1)")


@ex2.check("depth_from_disparity on a rendered scene's disparity map", points=1)
def depth_scene(t):
    scene = truth.scene("slanted")
    got = t.call("depth_from_disparity", np.array(scene.disparity), scene.f, scene.baseline)
    judge_depth(t, "depth_from_disparity(disparity map, f, baseline)", got, scene.disparity,
                scene.f, scene.baseline)
    t.images("depth from the true disparity", left_image=scene.left,
             true_depth=disparity_picture(scene.depth), yours=disparity_picture(got))


# A matcher's map is integer (cv2.StereoBM's int16, an argmin's int64), and the API takes arrays of
# any shape, not only float ones: a depth array made like the disparity (np.zeros_like(d) filled by
# np.divide(..., out=depth)) is integer then, so the division raises (float cannot be cast into an
# integer out=) or the depths are truncated to whole numbers.
INTEGER_DEPTH = measured("the depth array takes the disparity's integer dtype, and depths must be float "
                         "(f b / d is fractional)")
LIKE_THE_DISPARITY = calls_any("np.zeros_like", "np.empty_like", "np.full_like", "np.ones_like") \
    | keyword("np.divide", "out")
INTEGER_DEPTH_CAUSE = from_code("your code makes the depth array like the disparity (np.zeros_like / "
                                "np.empty_like, or np.divide's out=): give it a float dtype (np.zeros(d.shape), "
                                "or convert first: d = np.asarray(disparity, dtype=float))")
INTEGER_MAPS = ((np.array([[12, 0, -16], [35, 7, 64]], dtype=np.int16), 700.0, 0.12),
                (np.array([[3, 9, 0, 41], [-1, 18, 27, 5]], dtype=np.int64), 512.0, 0.3))


def _integer_depth(t: Trial, what: str, outcome: str):
    """Fail naming :data:`INTEGER_DEPTH` (measured: the call raised a casting error into, or
    returned, the disparity's integer dtype), with its cause where the code shows it."""
    kept = LIKE_THE_DISPARITY.found(code_of(t).reachable(["depth_from_disparity"]))
    t.fail(f"{what}: {outcome} -- {INTEGER_DEPTH}" + (f"; {INTEGER_DEPTH_CAUSE}" if kept else "") + ".",
           mistake="the depth array takes the disparity's integer dtype")


@ex2.check("depth_from_disparity on an integer disparity map (int16, int64: a matcher's)", points=1)
def depth_integer_map(t):
    for d, f, b in INTEGER_MAPS:
        what = f"depth_from_disparity({d.dtype} disparity map, f={f:g}, baseline={b:g})"
        try:
            got = t.call("depth_from_disparity", d.copy(), f, b)
        except StudentFailure as failure:
            said = failure.message.splitlines()[0] if failure.message else ""
            if failure.outcome.kind == "exception" and "cast" in said.lower() and str(d.dtype) in said:
                _integer_depth(t, what, said)
            raise
        if isinstance(got, np.ndarray) and got.shape == d.shape and got.dtype == d.dtype:
            _integer_depth(t, what, f"it returned depths of dtype {got.dtype}")
        judge_depth(t, what, got, d, f, b)
    return passed("float depths f b / d from int16 and int64 maps, 0 where d <= 0")


# ================================================================== ex3 rectification
ex3 = lab.exercise("ex3", "Rectification", functions=["rectify(img_l, img_r, K1, K2, R, T)"])
ROW_TOLERANCE = 0.5      # pixels: corresponding points on the same rectified row
EXACT_ROWS = 1e-3        # pixels: rows agree to rounding error (a mistake undone exactly)
IN_VIEW = 0.5            # fraction of each image kept in view / of each frame covered


INVERSE_WARP = "the images are warped by the inverse of the homographies"


def call_rectify(t: Trial, pair):
    what = "rectify(img_l, img_r, K1, K2, R, T)"
    result = t.call("rectify", pair.img_l, pair.img_r, pair.K1, pair.K2, pair.R, pair.T)
    rect_l, rect_r, H1, H2 = t.expect_results(result, what, ("rect_l", "rect_r", "H1", "H2"))
    H1 = t.expect_array(H1, f"{what}: H1", shape=(3, 3), kind="iuf", finite=True)
    H2 = t.expect_array(H2, f"{what}: H2", shape=(3, 3), kind="iuf", finite=True)
    shape = pair.img_l.shape
    rect_l = t.expect_array(rect_l, f"{what}: rect_l", dtype=np.uint8)
    rect_r = t.expect_array(rect_r, f"{what}: rect_r", dtype=np.uint8)
    for name, image in (("rect_l", rect_l), ("rect_r", rect_r)):
        if image.shape != shape:
            form = shape_form(image.shape, shape)   # the channels not kept: grey for BGR, BGR for grey
            converted = _grey_conversion(t) if image.ndim == 2 and len(shape) == 3 else ""
            t.fail(f"{what}: {name} has shape {image.shape}; expected {shape} (the input size)"
                   + (f": {form.sentence}" if form else "")
                   + (from_code(f"; your code converts the colour images to grey ({converted}) before warping "
                                "them: warp them as they are") if converted else ""),
                   mistake=form.mistake if form else "")
    return rect_l, rect_r, H1.astype(np.float64), H2.astype(np.float64)


# Measured: H1 and H2 orthonormal with determinant 1. A pixel map K_new R K^-1 never is (K's focal length and
# principal point are in pixels), so both so are rotations returned where the pixel maps belong.
ROTATIONS_RETURNED = "the rectifying rotations are returned as H1 and H2, where the pixel maps K_new R_rect K^-1 belong"
IDENTITY_RETURNED = "a pair taken for rectified already: H1 and H2 the identity"


def identity(H) -> bool:
    """Whether ``H`` is the identity up to its scale."""
    H = np.asarray(H, np.float64)
    return H.shape == (3, 3) and bool(H[2, 2] != 0) and bool(np.allclose(H / H[2, 2], np.eye(3), atol=1e-9))


def name_identity(t: Trial, pair, H1, H2, what="rectify"):
    """Fail naming :data:`IDENTITY_RETURNED` when both maps are the identity for a pair whose cameras' K differ
    (the rows were found not to agree): the images left as they are, as if rectified already."""
    if identity(H1) and identity(H2) and not np.allclose(pair.K1, pair.K2):
        t.fail(measured(f"{what}: H1 and H2 are both the identity: the images are left as they are, yet the "
                        "matches are not on the same rows -- a pair is rectified only when both views share one "
                        "camera matrix and one orientation, and these two cameras' K differ"), mistake=IDENTITY_RETURNED)


def name_rotations(t: Trial, H1, H2, what="rectify"):
    """Fail naming :data:`ROTATIONS_RETURNED` when both maps returned are rotation matrices."""
    def rotation(H) -> bool:
        return bool(np.allclose(H @ H.T, np.eye(3), atol=1e-6) and abs(np.linalg.det(H) - 1) <= 1e-6)
    if identity(H1) and identity(H2):
        return   # (the identity is a rotation too, but says nothing of rotations returned: see name_identity)
    if rotation(H1) and rotation(H2):
        t.fail(f"{what}: H1 and H2 are rotation matrices (orthonormal, determinant 1), not pixel-to-pixel maps: "
               f"it looks like {ROTATIONS_RETURNED} (a rotation moves rays, and the pixels are "
               "first turned into rays by K^-1).", mistake=ROTATIONS_RETURNED)


def row_errors(H1, H2, pair):
    a = truth.apply_homography(H1, pair.pts1)
    b = truth.apply_homography(H2, pair.pts2)
    return np.abs(a[:, 1] - b[:, 1]), a[:, 0] - b[:, 0]


def rectified_picture(rect_l, rect_r, H1, H2, pair, count=10):
    """The rectified pair side by side (enlarged 2x) with the true matches and their rows."""
    scale = 2
    tiles = []
    a = truth.apply_homography(H1, pair.pts1[:count])
    b = truth.apply_homography(H2, pair.pts2[:count])
    for image, pts in ((rect_l, a), (rect_r, b)):
        big = cv2.resize(image, None, fx=scale, fy=scale, interpolation=cv2.INTER_NEAREST)
        big = cv2.cvtColor(big, cv2.COLOR_GRAY2BGR) if big.ndim == 2 else big.copy()
        tiles.append((big, pts))
    colours = [(0, 0, 255), (0, 200, 0), (255, 0, 0), (0, 200, 255), (255, 0, 255), (255, 255, 0)]
    for i in range(min(count, len(a))):
        colour = colours[i % len(colours)]
        y_row = a[i, 1]
        for big, pts in tiles:
            if np.all(np.isfinite(pts[i])) and np.isfinite(y_row) and abs(y_row) < 1e4:
                y = int(round((y_row + 0.5) * scale - 0.5))
                cv2.line(big, (0, y), (big.shape[1] - 1, y), colour, 1)
                centre = tuple(int(round((v + 0.5) * scale - 0.5)) for v in pts[i])
                if all(abs(c) < 1e4 for c in centre):
                    cv2.circle(big, centre, 4, colour, 1)
    return side_by_side(tiles[0][0], tiles[1][0])


POSE_FIXES = {   # a mistake inside rectify -> the arguments that undo it (R, T and K1, K2 as given)
    "R is transposed inside your function (X2 = R X1 + T: R takes camera-1 coordinates to camera 2's)":
        lambda K1, K2, R, T: (K1, K2, R.T, T),
    "the pose is read backwards: X2 = R X1 + T takes camera-1 coordinates to camera 2's, so camera 2's "
    "centre is -R^T T": lambda K1, K2, R, T: (K1, K2, R.T, -R.T @ T),
    "K1 and K2 are swapped inside your function (K1 belongs to the left image)":
        lambda K1, K2, R, T: (K2, K1, R, T),
    "T itself is taken as camera 2's centre: X2 = R X1 + T takes camera-1 coordinates to camera 2's, so "
    "camera 2's centre is -R^T T": lambda K1, K2, R, T: (K1, K2, R, -R.T @ T),
}


def name_pose_mistake(t: Trial, pair, what):
    """Fail naming the mistake inside ``rectify`` that changing its arguments undoes, when
    exactly one does: the output alone cannot tell a transposed R from other errors."""
    undone = []
    for mistake, fix in POSE_FIXES.items():
        K1, K2, R, T = fix(np.asarray(pair.K1, float), np.asarray(pair.K2, float),
                           np.asarray(pair.R, float), np.asarray(pair.T, float).reshape(3))
        try:
            result = t.call("rectify", pair.img_l, pair.img_r, K1, K2, R, T)
        except StudentFailure:
            return
        if not isinstance(result, (tuple, list)) or len(result) != 4:
            return
        H1, H2 = (np.asarray(H, dtype=float) if isinstance(H, np.ndarray) and H.shape == (3, 3) else None
                  for H in result[2:])
        if H1 is None or H2 is None or not (np.all(np.isfinite(H1)) and np.all(np.isfinite(H2))):
            continue
        dy, _ = row_errors(H1, H2, pair)
        if np.all(np.isfinite(dy)) and dy.max() <= ROW_TOLERANCE:
            undone.append(mistake)
    if len(undone) == 1:
        t.fail(f"{what}: it looks like {undone[0]}: called with that undone, your function rectifies "
               "the pair.", mistake=undone[0])


def orientation(H, shape) -> tuple[bool, bool, bool]:
    """Whether ``H`` reverses the image's x axis, its y axis (measured along the image's centre
    lines), and maps the image centre to a negative third coordinate (the new camera looks away)."""
    h, w = shape[:2]
    ends = np.array([[0.0, (h - 1) / 2, 1], [w - 1.0, (h - 1) / 2, 1], [(w - 1) / 2, 0.0, 1],
                     [(w - 1) / 2, h - 1.0, 1], [(w - 1) / 2, (h - 1) / 2, 1]])
    mapped = ends @ np.asarray(H, float).T
    behind = bool(mapped[4, 2] < 0)
    mapped = mapped[:, :2] / mapped[:, 2:3]
    return bool(mapped[1, 0] < mapped[0, 0]), bool(mapped[3, 1] < mapped[2, 1]), behind


def _crosses_in_order(function) -> bool | None:
    """e2 = z x e1 and e3 = e1 x e2, in this order: a name assigned ``np.cross(z, e1)`` crossed after e1
    (``np.cross(e1, e2)``); code without a cross product of its own (cv2.stereoRectify) counts as doing it."""
    crosses = [n for n in walk(function) if isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] == "cross"
               and len(n.args) == 2]
    if not crosses:
        return None
    values = _assigned_values(function)

    def second_axis(name, e1) -> bool:   # name holds np.cross(_, e1), perhaps divided by its norm afterwards
        return any(isinstance(m, ast.Call) and m in crosses and isinstance(m.args[1], ast.Name) and m.args[1].id == e1
                   for v in values.get(name, []) for m in walk(v))
    return any(isinstance(n.args[0], ast.Name) and isinstance(n.args[1], ast.Name)
               and second_axis(n.args[1].id, n.args[0].id) for n in crosses)


# Measured (the message): both new cameras look away. The order of the cross products is told only to code
# that does not visibly write them in this order.
CROSS_ORDER_HINT = Hint("e2 = z x e1 (the mean optical axis crossed with e1, in this order) and e3 = e1 x e2 keep the "
                        "new z axis towards the scene",
                        asks=wherever_written("crosses z with e1, then e1 with e2", _crosses_in_order), instead="")


THIRD_AXIS_HINT = Hint("e3 = e1 x e2 (e1 crossed with e2, in this order) keeps the new z axis towards the scene",
                       asks=wherever_written("crosses e1 with e2", _crosses_in_order), instead="")


INVERT_HINT = Hint(" (invert them)", asks=calls_any("np.linalg.inv", "np.linalg.pinv", "cv2.invert",
                                                  says="inverts a matrix"),
                   instead=" (your code {found}: look at which way each matrix it inverts maps)")


PRINCIPAL_POINTS_DIFFER = "the rectified cameras' principal points differ (every disparity shifted)"
ZERO_DISPARITY_LEFT_OUT = from_code("cv2.stereoRectify without cv2.CALIB_ZERO_DISPARITY: the principal points differ")
SHIFT_TREND = 0.9   # correlation of the disparities with 1/Z above which they still grow with nearness


def judge_rows(t: Trial, pair, H1, H2, what="rectify"):
    dy, dx = row_errors(H1, H2, pair)
    worst = float(np.nanmax(dy)) if np.all(np.isfinite(dy)) else float("inf")
    if worst <= ROW_TOLERANCE:
        if np.median(dx) <= 0:
            # Negative disparities: how the two maps turn the images tells the cause apart -- the images, not H's sign:
            # H and -H are one homography (the API's "up to scale, sign included"), and e3 alone reversed is -1 times e1
            # and e2 reversed (a half turn), e2 and e3 reversed -1 times e1 alone (a mirror): each pair is told together
            # (audit of 2026-12-06: a student's H / H[2, 2] turned one name into the other).
            shape = np.asarray(pair.img_l).shape
            (x1, y1, _), (x2, y2, _) = orientation(H1, shape), orientation(H2, shape)   # (flips: the same for -H)
            negative = (f"{what}: matches are on the same rows, but the disparities x_l - x_r are "
                        f"negative (median {np.median(dx):.3g} px)")
            if x1 and x2 and y1 and y2:
                t.fail(f"{negative}: both rectified images are turned half round (mirrored in x and in y): the "
                       "rectifying rotation's third axis alone points the opposite way (e3 = e2 x e1), or its first "
                       "two axes do (the baseline taken the other way round) -- the same maps, a homography's sign "
                       "aside.", mistake="the rectified images are turned half round (e3 alone, or e1 and e2, reversed)",
                       hint=THIRD_AXIS_HINT.said(t) or TOWARDS_CENTRE_HINT.said(t))
            if x1 and x2 and not (y1 or y2):
                t.fail(f"{negative}: both rectified images are mirrored left to right with the new cameras "
                       "facing the scene: the new x axis points from camera 2 to camera 1, or the rectifying "
                       "rotation's second and third axes point the opposite way -- the same maps, a homography's "
                       "sign aside.", mistake="the rectified images are mirrored left to right (e1 alone, or e2 and "
                       "e3, reversed)", hint=TOWARDS_CENTRE_HINT.said(t) or CROSS_ORDER_HINT.said(t))
            if not (x1 or x2 or y1 or y2):
                # (the disparities' trend tells a swap from a shift: swapped roles negate them, so they fall as
                # the points come nearer; principal points that differ add one constant, so they still grow)
                nearness = 1.0 / np.asarray(pair.X, float)[:, 2]
                trend = float(np.corrcoef(dx, nearness)[0, 1]) if np.std(dx) > 0 else 0.0
                if trend >= SHIFT_TREND:
                    _, at_infinity = np.polyfit(nearness, dx, 1)
                    read = code_of(t).reachable(["rectify"])
                    unflagged = calls("cv2.stereoRectify").found(read) \
                        and not mentions("cv2.CALIB_ZERO_DISPARITY").found(read)
                    t.fail(measured(f"{negative}, though they grow as the points come nearer, as they should "
                                    f"(correlation {trend:.2f} with 1/Z): they are all shifted, by about "
                                    f"{at_infinity:.3g} px at infinity, where a disparity is 0: the two rectified "
                                    "cameras' principal points differ")
                           + (from_code("; your code calls cv2.stereoRectify without cv2.CALIB_ZERO_DISPARITY, "
                                        "which gives them the same principal point.") if unflagged else "."),
                           mistake=ZERO_DISPARITY_LEFT_OUT if unflagged else PRINCIPAL_POINTS_DIFFER)
                t.fail(f"{negative}, and neither image is turned or mirrored: the left and right roles are "
                       "swapped.", mistake="the left and right roles are swapped in the rectification")
            t.fail(f"{negative}: the two maps turn the images differently (left image: "
                   f"{'mirrored' if x1 else 'not mirrored'}, {'upside down' if y1 else 'upright'}; right: "
                   f"{'mirrored' if x2 else 'not mirrored'}, {'upside down' if y2 else 'upright'}).")
        return worst, float(np.median(dx))
    name_identity(t, pair, H1, H2, what)
    name_rotations(t, H1, H2, what)
    name_pose_mistake(t, pair, what)
    # Undoing a mistake of the construction must rectify exactly (the rows agree to rounding
    # error): nearly rectified pairs leave room for other wrong maps to come close by chance.
    # H = K_new R_rect K, with K where K^-1 belongs, times K^-2 is a rectifying homography.
    undo1 = np.linalg.matrix_power(np.linalg.inv(np.asarray(pair.K1, float)), 2)
    undo2 = np.linalg.matrix_power(np.linalg.inv(np.asarray(pair.K2, float)), 2)
    if np.nanmax(row_errors(H1 @ undo1, H2 @ undo2, pair)[0]) <= EXACT_ROWS:
        t.fail(f"{what}: it looks like K is used where K^-1 belongs: H = K_new R_rect K^-1 (a pixel is "
               "turned into a ray by K^-1 before the rotation).", mistake="K is used where K^-1 belongs")
    inv1, inv2 = np.linalg.pinv(H1), np.linalg.pinv(H2)
    if np.nanmax(row_errors(inv1, inv2, pair)[0]) <= EXACT_ROWS:
        t.fail(f"{what}: H1 and H2 map rectified pixels back to the originals; the API wants "
               "them from original to rectified coordinates" + INVERT_HINT.said(t) + ".",
               mistake="H1 and H2 are inverted (rectified to original)")
    if np.nanmax(row_errors(H2, H1, pair)[0]) <= EXACT_ROWS:
        t.fail(f"{what}: H1 and H2 are swapped (H1 rectifies the left image).",
               mistake="H1 and H2 are swapped")
    t.fail(f"{what}: true correspondences end up {np.nanmedian(dy):.3g} px apart vertically "
           f"(up to {worst:.3g} px); after rectification they must share a row.",
           hint=GIVEN_AS_IS_HINT.said(t) if RECTIFY_HINT.contradicts(code_of(t), ["rectify"]) else CENTRE_HINT.said(t))


# Code that already gives both cameras one new rotation and one K is told the other half of the
# recipe: the baseline's direction comes from the camera centres (C2 = -R^T T), not T itself.
def _shared_by_products(function) -> bool:
    """A name in two separate matrix products (``K_new @ R_rect @ inv(K1)`` and ``K_new @ R_rect @ R @ inv(K2)``):
    one new rotation (and K) given to both cameras."""
    inner = {id(n.left) for n in walk(function) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.MatMult)}
    chains = [n for n in walk(function) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.MatMult)
              and id(n) not in inner]
    names = [{m.id for m in walk(chain) if isinstance(m, ast.Name)} for chain in chains]
    return any(sum(name in held for held in names) >= 2 for held in names for name in held)


# Code that computes the centre -R^T T is not told it (the rest of the recipe is a checklist).
# (or through an inverse: c = -(K R)^-1 (K t), the textbook's centre of a camera K [R | t], is -R^T t)
CENTRE = (expr("-R.T @ T") | expr("-_.T @ _") | expr("-(_.T @ _)") | expr("-np.dot(_.T, _)")
          | expr("-_.T.dot(_)") | expr("_.T @ -_") | expr("-np.linalg.inv(_) @ _") | expr("-(np.linalg.inv(_) @ _)")
          | expr("np.linalg.inv(_) @ -_") | expr("-np.linalg.solve(_, _)")).saying("computes camera 2's centre -R^T T")
BASELINE_AXIS = (expr("_ / np.linalg.norm(_)") | calls("np.linalg.norm")).saying("divides the baseline by its length")
AXES_AS_COLUMNS = (calls("np.column_stack") | keyword("np.stack", "axis", 1) | keyword("np.stack", "axis", -1)
                   | expr("np.array([_, _, _]).T") | expr("np.vstack([_, _, _]).T") | expr("np.stack([_, _, _]).T")
                   ).saying("stacks the new axes as columns")
ONE_ROTATION = Predicate("gives both cameras one new rotation and one new K", _shared_by_products)
TOWARDS_CENTRE_HINT = Hint("camera 2's centre in camera-1 coordinates is -R^T T: the new x axis points towards it",
                           asks=CENTRE, instead="")   # the message's measured cause alone


def rectification_recipe(lead: str, *first: tuple) -> str:
    """The rectification recipe's checklist after ``lead``: ``first`` items, then the new axes and the maps."""
    return checklist(
        lead, *first, ("the new x axis follows the baseline between the two centres", BASELINE_AXIS),
        ("the new axes are the rows of the rectifying rotation (np.vstack([e1, e2, e3]), not its columns)",
         ~AXES_AS_COLUMNS),
        ("both cameras get that one new rotation and one new K", ONE_ROTATION),
        none_left=look_at(("the order of the products in each map (H1 = K_new R_rect K1^-1, H2 = K_new R_rect R K2^-1)",
                           INVERSE_RIGHTMOST), otherwise="each of its steps is written in your code, so the "
                                                         "difference is inside one of them"))


def _inverse_rightmost(function) -> bool:
    """A matrix product whose rightmost factor is an inverse (``K_new @ R_rect @ np.linalg.inv(K1)``, or a name
    assigned one): each map written with K^-1 applied first; read leniently (any inverse)."""
    inverses = {t.id for n in walk(function) if isinstance(n, ast.Assign) and _is_inverse(n.value)
                for t in n.targets if isinstance(t, ast.Name)}
    return any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.MatMult)
               and (_is_inverse(n.right) or isinstance(n.right, ast.Name) and (n.right.id in inverses
                                                                               or "inv" in n.right.id.lower()))
               for n in walk(function))


def _is_inverse(node) -> bool:
    return isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in ("inv", "pinv", "invert")


INVERSE_RIGHTMOST = Predicate("applies K^-1 first in each map", _inverse_rightmost)


RECTIFY_HINT = Hint(
    rectification_recipe("compare your steps with the recipe: ",
                         ("camera 2's centre is -R^T T, not T (X2 = R X1 + T takes camera-1 coordinates to camera "
                          "2's)", CENTRE)),
    asks=calls("cv2.stereoRectify"),
    instead="your code {found}; then check what it is given: R and T take camera-1 coordinates to camera "
            "2's (X2 = R X1 + T), so the second camera's centre is -R^T T, not T")
# Code that gives cv2.stereoRectify K1, K2, R and T as they came is not told to check what it gives
# it: the rest of that recipe, as a checklist (which output belongs to which image).
class _Alone:
    """One function read as a module's code (for the readings written over a Code's functions)."""

    def __init__(self, function):
        self.function = function

    def reachable(self, names):
        return [self.function]


def _outputs_out_of_order(function) -> bool:
    """``R1, P1, R2, P2, ... = cv2.stereoRectify(...)`` (its outputs are R1, R2, P1, P2, in that order)."""
    from ..engine.outputs import out_of_order

    return out_of_order(function, "stereoRectify")


def _warps(function) -> list:
    """The ``cv2.warpPerspective`` calls of ``function``: (image, map) argument nodes."""
    found = []
    for n in walk(function):
        if isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] == "warpPerspective":
            given = dict(enumerate(n.args[:2]))
            given.update({{"src": 0, "M": 1}[k.arg]: k.value for k in n.keywords if k.arg in ("src", "M")})
            if len(given) == 2:
                found.append((given[0], given[1]))
    return found


def _names_in(node) -> set:
    return {n.id for n in walk(node) if isinstance(n, ast.Name)}


def _warps_each_by_its_own(function) -> bool | None:
    """img_l (the first parameter) and img_r (the second) each warped by a different map; code that warps in a
    helper or with cv2.remap cannot be read and counts as doing it."""
    parameters = [a.arg for a in function.args.posonlyargs + function.args.args]
    warps = _warps(function)
    if len(parameters) < 2 or not warps:
        return None
    left = [_names_in(m) for image, m in warps if parameters[0] in _names_in(image)]
    right = [_names_in(m) for image, m in warps if parameters[1] in _names_in(image)]
    return any(a != b for a in left for b in right)


def _returns_its_warps(function) -> bool | None:
    """The last two values returned (H1, H2) are names the images were warped with (``return rect_l, rect_r, H1,
    H2`` after ``cv2.warpPerspective(img_l, H1, ...)``); code that cannot be read that way counts as doing it."""
    warped_with = {m.id for _, m in _warps(function) if isinstance(m, ast.Name)}
    returns = [n.value for n in walk(function) if isinstance(n, ast.Return) and isinstance(n.value, ast.Tuple)
               and len(n.value.elts) == 4]
    if not warped_with or not returns:
        return None
    return all(all(not isinstance(e, ast.Name) or e.id in warped_with for e in r.elts[2:]) for r in returns)


GIVEN_AS_IS_HINT = Hint(RECTIFY_HINT.neutral("calls cv2.stereoRectify"),
                        asks=passes_parameters("cv2.stereoRectify", {0: "K1", 2: "K2", 5: "R", 6: "T"},
                                               says="gives cv2.stereoRectify K1, K2, R and T as they came"),
                        instead="your code {found}, as it takes them; " + checklist(
                            "", ("the image size it is given is (width, height)", ~Predicate(
                                "gives the size rows first", lambda f: bool(size_given_as_shape(_Alone(f), ())))),
                            ("R1 and P1 go to the left image, R2 and P2 to the right (it returns R1, R2, P1, P2 in "
                             "that order)", ~Predicate("reads its outputs out of order", _outputs_out_of_order)),
                            ("each image's map is H = P[:, :3] R K^-1", expr("_[:, :3] @ _") | expr("_[:3, :3] @ _")),
                            # (the output size is the first item's predicate: every OpenCV size is read)
                            none_left=look_at(("which image each map is applied to (img_l by H1, img_r by H2)",
                                               wherever_written("warps each image by its own map",
                                                                _warps_each_by_its_own)),
                                              ("which matrices are returned as H1 and H2 (the maps the images are "
                                               "warped with)", wherever_written("returns the maps it warps with",
                                                                                _returns_its_warps)))))
CENTRE_HINT = Hint(RECTIFY_HINT.text, asks=CENTRE,
                   instead="your code {found}; " + rectification_recipe("compare the rest with the recipe: "))


@ex3.check("rectify: true correspondences end up on the same row", points=4)
def rectify_rows(t):
    pair = truth.unrectified_pair(seed=4)
    rect_l, rect_r, H1, H2 = call_rectify(t, pair)
    t.images("rectified pair with true matches and their rows", "every circle should sit on its line",
             rectified=rectified_picture(rect_l, rect_r, H1, H2, pair))
    worst, median_dx = judge_rows(t, pair, H1, H2)
    return passed(f"rows agree within {worst:.2g} px; median disparity {median_dx:.3g} px")


@ex3.check("rectify: rows agree for other camera pairs", points=2)
def rectify_property(t):
    def holds(seed):
        pair = truth.unrectified_pair(seed)
        _, _, H1, H2 = call_rectify(t, pair)
        judge_rows(t, pair, H1, H2)

    t.for_all(st.integers(0, 2**32 - 1), holds, max_examples=4,
              describe=lambda s: f"fixtures.lab12.unrectified_pair(seed={s})")
    # (a rig not turned, camera 2 straight to the right, is not rectified while the two cameras' K differ)
    pair = truth.unrectified_pair(seed=5, parallel=True)
    _, _, H1, H2 = call_rectify(t, pair)
    judge_rows(t, pair, H1, H2, what="a rig not turned (R = I, T along x) whose two cameras' K differ")


def warped_error(image, H, got) -> float:
    """Mean blurred difference between ``got`` and ``image`` warped by ``H`` (best half-pixel offset), on
    the pixels with a source well inside the image (on the whole frame where there are almost none)."""
    height, width = image.shape[:2]
    ys, xs = np.mgrid[0:height, 0:width].astype(np.float64)
    errors = []
    for dx, dy in HALF_PIXEL_OFFSETS:
        shifted = np.array([[1, 0, dx], [0, 1, dy], [0, 0, 1.0]]) @ H
        expected = cv2.warpPerspective(image, shifted, (width, height), flags=cv2.INTER_LINEAR)
        source = truth.apply_homography(np.linalg.inv(shifted), np.column_stack([xs.ravel(), ys.ravel()]))
        inside = ((source[:, 0] >= 2) & (source[:, 0] <= width - 3) & (source[:, 1] >= 2)
                  & (source[:, 1] <= height - 3)).reshape(height, width)
        if inside.mean() < 0.05:   # (H sends the image almost all out of the frame: then the frame
            inside = np.ones_like(inside)   # itself, mostly black, is what the warp shows)
        errors.append(blurred_difference(got, expected, inside))
    return min(errors)


@ex3.check("rectify: the rectified images are the inputs warped by H1 and H2", points=2)
def rectify_images(t):
    pair = truth.unrectified_pair(seed=4)
    rect_l, rect_r, H1, H2 = call_rectify(t, pair)
    for name, image, H, got in (("rect_l", pair.img_l, H1, rect_l), ("rect_r", pair.img_r, H2, rect_r)):
        try:
            error = warped_error(image, H, got)
        except np.linalg.LinAlgError:
            t.fail(f"rectify: {'H1' if name == 'rect_l' else 'H2'} is singular")
        if error > 8.0:
            other_image, other_H = (pair.img_r, H2) if name == "rect_l" else (pair.img_l, H1)
            # The images agree with the other homography: the returned H1 and H2 are swapped
            # when they rectify the pair that way round, else the images were warped wrongly.
            h_swapped = np.nanmax(row_errors(H2, H1, pair)[0]) <= EXACT_ROWS
            alternatives = {
                "rect_l and rect_r are swapped": (other_image, other_H),
                "H1 and H2 are swapped" if h_swapped else _warped_with_the_other(t, name, pair, rect_l, rect_r, H1, H2):
                    (image, other_H),
            }
            for mistake, (source, homography) in alternatives.items():
                try:
                    if warped_error(source, homography, got) <= 8.0:
                        t.fail(f"rectify: it looks like {mistake}: {name} is "
                               f"{'img_r' if source is pair.img_r else 'img_l'} warped by "
                               f"{'H2' if homography is H2 else 'H1'}.", mistake=mistake)
                except np.linalg.LinAlgError:
                    continue
            try:   # right homographies, applied the other way round: the image warped by H's inverse
                inverted = warped_error(image, np.linalg.inv(H), got) <= 8.0 \
                    and np.nanmax(row_errors(H1, H2, pair)[0]) <= EXACT_ROWS
            except np.linalg.LinAlgError:
                inverted = False
            if inverted:
                t.fail(f"rectify: {name} is the input warped by the inverse of your {'H1' if name == 'rect_l' else 'H2'}: "
                       + measured("the homography is applied the other way round (a warp with cv2.WARP_INVERSE_MAP "
                                  "takes the map from the result back to the input, or H was inverted before the warp)"),
                       mistake=INVERSE_WARP)
            name_rotations(t, H1, H2)
            height, width = image.shape[:2]
            expected = cv2.warpPerspective(image, H, (width, height))
            t.compare_images(f"{name} against the input warped by your homography", image, expected, got)
            t.fail(f"rectify: {name} differs from the input warped by your "
                   f"{'H1' if name == 'rect_l' else 'H2'} by {error:.0f} grey levels on average "
                   "(do the images and the homographies describe the same warp?)")
    return passed("both images match their homographies")


def _warped_with_the_other(t, name, pair, rect_l, rect_r, H1, H2) -> str:
    """The mistake of ``name`` (rect_l or rect_r) warped with the other image's homography: both
    images so, or that one alone (a line copied from the other image's), as the other image shows."""
    other, image, H = ("rect_r", pair.img_r, H1) if name == "rect_l" else ("rect_l", pair.img_l, H2)
    got = rect_r if name == "rect_l" else rect_l
    try:
        both = warped_error(image, H, got) <= 8.0
    except np.linalg.LinAlgError:
        both = False
    if both:
        return "each image is warped with the other one's homography"
    own, wrong = ("H1", "H2") if name == "rect_l" else ("H2", "H1")
    return f"{name} alone is warped with {wrong}, the other image's homography, where {own} belongs"


def _in_front(H, shape) -> np.ndarray:
    """(H, W) bool: the output pixels whose pre-image under ``H`` is in front of the camera (its third
    homogeneous coordinate of the sign most of the frame has: H is defined up to its sign)."""
    height, width = shape[:2]
    ys, xs = np.mgrid[0:height, 0:width].astype(np.float64)
    inverse = np.linalg.inv(np.asarray(H, np.float64))
    q = inverse[2, 0] * xs + inverse[2, 1] * ys + inverse[2, 2]
    return q * np.sign(np.median(q) or 1.0) > 0


@ex3.check("rectify leaves black the pixels whose source lies outside the image", points=1)
def rectify_black_fill(t):
    """The API's black fill: the rectifying rotation brings in pixels from beyond each input (here about
    10% of the left frame and 2% of the right), which are 0, as cv2.warpPerspective and cv2.remap leave
    them by default. Judged with the student's own H1 and H2 (their images are the other checks')."""
    pair = truth.unrectified_pair(seed=4)
    rect_l, rect_r, H1, H2 = call_rectify(t, pair)
    for name, image, H, got in (("rect_l", pair.img_l, H1, rect_l), ("rect_r", pair.img_r, H2, rect_r)):
        try:
            if warped_error(image, H, got) > 8.0:
                return passed(measured(f"{name} is not the input warped by its homography: the images check "
                                       "judges it"))
            _, outside = coverage(H, image.shape, margin=1.5)
        except np.linalg.LinAlgError:
            return passed(measured("a homography is singular: the other checks judge it"))
        if outside.mean() > 0.5:   # (a map sending most of the frame beyond the input -- or behind, where
            # cv2.warpPerspective samples the input all the same -- is the other checks' to judge)
            return passed(measured(f"{name}'s homography sends most of the frame outside the input: the other "
                                   "checks judge it"))
        # (pixels whose pre-image is behind the camera: cv2.warpPerspective samples the input there all the same,
        # whatever its border rule -- the map's doing, which the rows and view checks judge, not the fill)
        outside &= _in_front(H, image.shape)
        if not outside.any():
            continue
        nonblack = fill_fraction(got, outside)
        if nonblack > FILL_TOLERANCE:
            t.images(f"rectify(...): {name}", "the pixels with no source pixel: black fill", input=image, yours=got)
            rule = repeating_border(code_of(t).reachable(["rectify"]))
            t.fail(measured(f"rectify: {nonblack:.0%} of the {int(outside.sum())} pixels of {name} whose source "
                            "lies outside the input image are not black (the API's black fill: a pixel with no "
                            "source pixel is 0)")
                   + (from_code(f"; your code uses cv2.{rule}, which fills them from the image's edge.") if rule
                      else "."),
                   hint=BLACK_FILL_HINT.said(t), mistake="the fill is not black")
    return passed(measured("the pixels with no source pixel are black in both images"))


@ex3.check("rectify keeps a colour pair in colour (BGR in, BGR out)", points=1)
def rectify_colour(t):
    """The skeleton: (H, W) or (H, W, 3) images in, rectified images of the same shape out; every
    other check gives a grey pair. One question, the colour: each rectified image is its colour
    input warped by the homography returned with it. Whether the images match their homographies
    at all is the grey check's: where the grey pair's do not either, this check passes."""
    pair = truth.unrectified_pair(seed=4)
    colour = replace(pair, img_l=tinted(pair.img_l), img_r=tinted(pair.img_r))
    rect_l, rect_r, H1, H2 = call_rectify(t, colour)
    errors = {name: _warped_or_inf(image, H, got) for name, image, H, got in
              (("rect_l", colour.img_l, H1, rect_l), ("rect_r", colour.img_r, H2, rect_r))}
    wrong = [name for name, error in errors.items() if error > 8.0]
    if not wrong:
        return passed("both colour images match their homographies")
    grey_l, grey_r, G1, G2 = call_rectify(t, pair)
    if max(_warped_or_inf(pair.img_l, G1, grey_l), _warped_or_inf(pair.img_r, G2, grey_r)) > 8.0:
        return passed("the grey pair's images do not match their homographies either: judged by the grey check")
    t.fail(f"rectify of a colour pair: {wrong[0]} differs from the colour input warped by your "
           f"{'H1' if wrong[0] == 'rect_l' else 'H2'} by {errors[wrong[0]]:.0f} levels on average, while "
           "a grey pair's images match their homographies" + (f": {told}" if (told := COLOUR_HINT.said(t)) else "."))


# (the skeleton gives T as (3,); cv2.stereoCalibrate returns it as a (3, 1) column -- the blind set 1205d's 12/04)
def _rectify_arguments() -> tuple:
    pair = truth.unrectified_pair(seed=4)
    return pair.img_l, pair.img_r, pair.K1, pair.K2, pair.R, pair.T


conventions.column_vector(ex3, "rectify", _rectify_arguments, 5, "T")


def _converts_colour(function) -> bool:
    """A colour image turned into something else before the warp: cv2.cvtColor, a channel taken (``img[..., 0]``,
    ``img[:, :, 1]``) or averaged (``.mean(axis=2)``)."""
    return calls("cv2.cvtColor").holds([function]) or any(
        isinstance(n, ast.Subscript) and isinstance(n.slice, ast.Tuple) and n.slice.elts
        and isinstance(n.slice.elts[-1], ast.Constant) and n.slice.elts[-1].value in (0, 1, 2)
        and (len(n.slice.elts) == 3 or isinstance(n.slice.elts[0], ast.Constant) and n.slice.elts[0].value is Ellipsis)
        for n in walk(function)) or keyword("np.mean", "axis", 2).holds([function]) \
        or keyword(".mean", "axis", 2).holds([function])


def _grey_conversion(t: Trial) -> str:
    """The first conversion to grey in rectify's code (`cv2.cvtColor(img_l, cv2.COLOR_BGR2GRAY)`), quoted with its
    line; "" where there is none."""
    for function in code_of(t).reachable(["rectify"]):
        for node in walk(function):
            if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == "cvtColor" \
                    and any(_path(a).endswith("2GRAY") for a in [*node.args[1:2], *(k.value for k in node.keywords)]):
                said = ast.unparse(node)   # (a call written long is quoted by its name: the line says where)
                return f"`{said if len(said) <= 80 else _path(node.func) + '(...)'}`, line {node.lineno}"
    return ""


# Told only to code that converts the images somewhere (code warping them as they come does what it says).
COLOUR_HINT = Hint("warp the colour images as they are (cv2.warpPerspective takes BGR images).",
                   asks=~Predicate("converts a colour image", _converts_colour), instead="")


def _warped_or_inf(image, H, got) -> float:
    try:
        return warped_error(image, H, got)
    except np.linalg.LinAlgError:   # a singular H: no warp to compare with
        return float("inf")


# A short baseline too (0.12 units: a stereo camera's few centimetres): a rectification's maps do not depend
# on the baseline's length, where an unnormalised axis (e1 = C2) scales the images by it.
SHORT_BASELINE = 0.12


@ex3.check("rectify: most of each image stays in view", points=2)   # (a short baseline too)
def rectify_in_view(t):
    for pair, said in ((truth.unrectified_pair(seed=4), ""),
                       (truth.unrectified_pair(seed=4, baseline=SHORT_BASELINE), f" (baseline {SHORT_BASELINE:g})")):
        judge_in_view(t, pair, said, short=bool(said))
    return passed(measured("both images stay mostly in view and fill their frames"))


def judge_in_view(t: Trial, pair, said: str, short: bool = False):
    """Both of rectify's maps keep most of their image in view and fill their frames, on ``pair`` (``short``:
    its baseline is the short one, and the same cameras at the usual baseline passed)."""
    _, _, H1, H2 = call_rectify(t, pair)
    height, width = pair.img_l.shape[:2]
    # The new camera's K is the cause only of maps that rectify: other maps fail the rows check for their own cause.
    dy, dx = row_errors(H1, H2, pair)
    rectifies = bool(np.all(np.isfinite(dy)) and dy.max() <= ROW_TOLERANCE and np.median(dx) > 0)
    for name, H in (("left", H1), ("right", H2)):
        kept = truth.fraction_in_view(H, width, height)
        covered = truth.frame_coverage(H, width, height)
        if min(kept, covered) < IN_VIEW:
            name_rotations(t, H1, H2)
        if kept < IN_VIEW:
            t.fail(f"rectify{said}: only {format_apart(kept, IN_VIEW, 2, percent=True)} of the {name} image stays "
                   f"inside the rectified frame (at least {IN_VIEW:.0%} should)"
                   + (": H1 and H2 rectify the pair, but " + measured(
                       "the same cameras at the usual baseline (about 0.6 units) stay in view: your maps change with "
                       "the baseline's length, where a rectification depends only on its direction.")
                       if rectifies and short else
                      ": H1 and H2 rectify the pair, but the new principal point (and focal length) do not keep "
                      "the rectified images in view." if rectifies else
                      "; H1 and H2 do not rectify the pair either (see the rows check)."))
        if covered < IN_VIEW:
            t.fail(f"rectify{said}: the {name} image covers only {format_apart(covered, IN_VIEW, 2, percent=True)} of "
                   "its rectified frame "
                   f"(at least {IN_VIEW:.0%} should): " + (
                       measured("the same cameras at the usual baseline (about 0.6 units) fill their frames: your "
                                "maps change with the baseline's length, where a rectification depends only on its "
                                "direction.")
                       if short else "the result is shrunk or pushed aside."))


# ================================================================== ex4 block matching (SSD)
ex4 = lab.exercise("ex4", "Block matching", functions=[
    "block_matching(left, right, max_disparity=64, block_size=9, cost=\"ssd\")"])
# No forbidden call: the lab sheet's recipe is cv2.StereoBM (SSD). Every matcher is judged
# right of the search band, where StereoBM too searches the whole range, and accepted up to
# the worst legitimate matcher's rate on the same scene (benchmarks/spread_block_matching.py).


def block_matcher(t: Trial, scene, **kwargs):
    def again(left, right):
        return t.call("block_matching", np.array(left), np.array(right),
                      max_disparity=scene.max_disparity, **kwargs)
    return again


BLOCK_SIZES = (5, 15)  # two block sizes any matcher (cv2.StereoBM included) accepts


def matcher_on(t: Trial, scene, **kwargs):
    """``block_matching`` on ``scene``'s pair, the keyword arguments left open."""
    return lambda **more: t.call("block_matching", np.array(scene.left), np.array(scene.right),
                                 max_disparity=scene.max_disparity, **kwargs, **more)


def block_size_probe(t: Trial, what: str, scene, **kwargs):
    """A probe (see :func:`judge_disparity`): does ``block_size`` change the map at all?"""
    return lambda: judge_parameter_used(t, what, matcher_on(t, scene, **kwargs), "block_size", BLOCK_SIZES,
                                        "disparity map")


def _zero_missed(got, scene, far) -> str:
    """": the search must include d = 0 ...", where the map's disparities are of the search range and the wall at
    infinity has none of 0 (measured: a map of costs, or of values past max_disparity, has another cause; a wall
    with zeros here and there was searched at 0)."""
    got = np.asarray(got, float)
    finite = got[np.isfinite(got)]
    wall = got[far]
    # (and a map of more than one value: one disparity everywhere -- every cost NaN, argmin's first -- is no
    # search short of 0)
    if finite.size and finite.min() >= 0 and finite.max() <= scene.max_disparity + 0.5 and np.ptp(finite) > 0 \
            and not np.any(np.abs(wall[np.isfinite(wall)]) < 0.5):
        return measured(": none of the wall's disparities is 0") + where_to_look(
            " -- the search must include d = 0 (d = 0..max_disparity)")
    return ""


def judge_block_matching(t: Trial, what: str, got, scene, figures: dict, *, again=None, show=True):
    """Judge an SSD disparity map against the legitimate matchers' rates on ``scene``.

    ``figures`` are :func:`fixtures.make_lab12_figures.block_matching_figures` of the
    scene. The ends of the search range are judged apart: pixels at infinity (true d
    rounds to 0: the search must include d = 0) and pixels at d = max_disparity (the
    search must include it; :func:`judge_top_of_range`). A failing map is probed for an
    ignored ``block_size``.
    """
    got = expect_disparity(t, what, got, scene)
    far, near = truth.far_and_near(truth.band(scene.judged, scene.max_disparity, figures["block_size"]))
    top = truth.top_of_range(near, scene.max_disparity)
    mistakes = MatchingMistakes(scene, figures["block_size"], "ssd")
    if far.any():
        wrong = truth.far_wrong_rate(got, far)
        if wrong > figures["far_legitimate"] + FAR_SLACK:
            if show:
                show_disparity(t, f"{what} on {scene.name}", scene, got)
            name_matching_mistake(t, what, got, scene, scene.judged, mistakes)
            t.fail(f"{what}: the wall at infinity (true disparity {scene.judged[far].max():.2g} px, "
                   f"i.e. d = 0) gets a disparity of 1 or more at {wrong:.0%} of its pixels "
                   f"(legitimate matchers: at most {figures['far_legitimate']:.0%})" + _zero_missed(got, scene, far) + ".")
    # The pixels at the top of the range are judged apart (cv2.StereoBM's recipe leaves half
    # of them invalid), once the rest of the map is right: a wrong map gets its own diagnosis.
    verdict = judge_disparity(t, what, got, scene, figures["reference"], again=again, show=show,
                              judged=np.where(top, 0.0, near),
                              mistakes=mistakes,
                              allowed=figures["legitimate"] + SLACK,
                              accepted_by=measured(f"; the legitimate SSD matchers, cv2.StereoBM included, up to "
                                                   f"{figures['legitimate']:.1%}"),
                              probe=block_size_probe(t, what, scene, cost="ssd"),
                              naming=naming_crop(t, "block_matching", scene, block_size=figures["block_size"]))
    if verdict.fraction == 1:
        # (figures of a scene with no pixel at the top of the range may leave it out)
        judge_top_of_range(t, what, got, scene, top, figures.get("top_legitimate", 1.0),
                           measured("legitimate SSD matchers, cv2.StereoBM included"), mistakes=mistakes, show=False)
    return verdict


TOP_MISSED = "the search stops at max_disparity - 1"
TOP_RANGE_HINT = Hint("the search must include d = max_disparity: range(max_disparity + 1)",
                      asks=expr("max_disparity + 1"),
                      instead="your code's search reaches max_disparity ({found}): what the square gets comes "
                              "from elsewhere (its matching costs, or the choice among them)")


def judge_top_of_range(t: Trial, what: str, got, scene, top, legitimate: float, legitimate_name: str,
                       mistakes=None, show=True):
    """Fail when the pixels whose true disparity is ``max_disparity`` itself (mask ``top``)
    do not get it, at fewer than ``legitimate`` (the worst legitimate method's fraction, by
    ``legitimate_name``) minus :data:`TOP_SLACK`. A search that stops at ``max_disparity - 1``
    gives that there, within the bad-pixel threshold: only this judgement tells it."""
    if not np.any(top):
        return
    found = truth.top_found_rate(got, top, scene.max_disparity)
    allowed = legitimate - TOP_SLACK
    if found >= allowed:
        return
    if show:
        show_disparity(t, f"{what} on {scene.name}", scene, got)
    top_d = scene.max_disparity
    with np.errstate(invalid="ignore"):
        one_below = float(np.mean(np.abs(np.asarray(got, np.float64)[top] - (top_d - 1)) <= truth.TOP_THRESHOLD))
    hint = Hint("d = 0..max_disparity includes max_disparity itself: range(max_disparity + 1)",
                asks=expr("max_disparity + 1"),
                instead="d = 0..max_disparity includes max_disparity itself; your code already {found}: check "
                        "that the block shifted by max_disparity is compared too (not cut off at the image "
                        "edge or by a slice one short)").said(t)
    if one_below >= 0.5:
        t.fail(f"{what}: it looks like {TOP_MISSED}: the square at the top of the search range (true "
               f"disparity {top_d} = max_disparity) gets {top_d - 1} at {one_below:.0%} of its pixels.",
               hint=hint, mistake=TOP_MISSED)
    if mistakes is not None:
        name_matching_mistake(t, what, got, scene, scene.judged, mistakes)
    # (not one below it: the range is one cause among others -- its costs, the choice among them)
    t.fail(f"{what}: the square at the top of the search range (true disparity {top_d} = max_disparity) "
           f"gets it at only {format_apart(found, allowed, 2, percent=True)} of its pixels ({legitimate_name}: "
           f"at least {legitimate:.0%}).", hint=TOP_RANGE_HINT.said(t))


def judge_range_ends(t: Trial, what: str, got, scene, reference: dict, show=True):
    """The ends of the search range on ``scene`` (``zero_disparity``: a wall at infinity, d = 0,
    and a square at d = max_disparity), against ``reference``, the reference's figures of the
    same method there (``far_wrong``, ``top_found``): fail saying which end the search misses."""
    far, _ = truth.far_and_near(scene.judged)
    wrong = truth.far_wrong_rate(got, far)
    if wrong > reference["far_wrong"] + FAR_SLACK:
        if show:
            show_disparity(t, f"{what} on {scene.name}", scene, got)
        t.fail(f"{what}: the wall at infinity (true disparity {scene.judged[far].max():.2g} px, i.e. d = 0) "
               f"gets a disparity of 1 or more at {format_apart(wrong, reference['far_wrong'] + FAR_SLACK, 2, True)} "
               f"of its pixels (the reference: {reference['far_wrong']:.0%})" + _zero_missed(got, scene, far) + ".")
    judge_top_of_range(t, what, got, scene, truth.top_of_range(scene.judged, scene.max_disparity),
                       reference["top_found"], "the reference", show=show)


def bm_figures(key: str) -> dict:
    return truth.reference_figures()["block_matching"][key]


@ex4.check("block_matching returns an (H, W) float disparity map in 0..max_disparity", points=1,
           timeout=STEREO_TIMEOUT)
def block_matching_form(t):
    scene = truth.scene("random_dots")
    # A multiple of 16, so the lab sheet's cv2.StereoBM (numDisparities % 16 == 0) meets the
    # range as it is; the scene's disparities stay below it.
    max_disparity = FORM_DISPARITY
    what = f"block_matching(left, right, max_disparity={max_disparity})"
    got = expect_disparity(t, what, random_dots_map(t), scene)
    got = t.expect_array(got, what, kind="f")
    with np.errstate(invalid="ignore"):
        if np.any(got > max_disparity + 1e-9):
            if np.nanmax(got) > 2 * max_disparity and \
                    STEREO_MATCHER_UNDIVIDED.holds(code_of(t).reachable(["block_matching"])):
                t.fail(f"{what} returned disparities up to {np.nanmax(got):g}, far above the search range "
                       f"0..{max_disparity}: it looks like {FIXED_POINT}: " + FIXED_POINT_KEPT + ".",
                       mistake=FIXED_POINT)
            opencv = STEREO_MATCHER.holds(code_of(t).reachable(["block_matching"]))
            t.fail(f"{what} returned disparities up to {np.nanmax(got):g}; the search range is "
                   f"0..{max_disparity}",
                   hint=measured("the disparities searched are 0..max_disparity, no more") if not opencv else Hint("cv2.StereoBM rounds numDisparities up to a multiple of 16: set what it finds "
                             "above max_disparity to 0 (invalid)",
                             asks=expr("_ > max_disparity") | expr("max_disparity < _"),
                             instead="your code already compares disparities with max_disparity: check that "
                                     "the comparison is made on the map returned (after StereoBM's division "
                                     "by 16)").said(t))
    # (and a pair narrower than the search range, as the API allows: a map of its size, no error)
    left, right = (np.ascontiguousarray(np.array(image)[:, :12]) for image in (scene.left, scene.right))
    narrow = f"block_matching(left, right, max_disparity={max_disparity}) on a pair 12 pixels wide"
    t.expect_array(t.call("block_matching", left, right, max_disparity=max_disparity), narrow, shape=left.shape[:2],
                   kind="f")
    return passed(measured("a float map in 0..max_disparity; a pair narrower than the search range answered in "
                           "its size"))


FORM_DISPARITY = 16   # the form check's search range: a multiple of 16, as cv2.StereoBM needs


def random_dots_map(t: Trial):
    """block_matching on the random-dot planes with max_disparity=16: one call, judged by the form check
    and read by the left strip's tip."""
    scene = truth.scene("random_dots")
    return t.shared(("block_matching", "random_dots", FORM_DISPARITY), lambda: t.call(
        "block_matching", np.array(scene.left), np.array(scene.right), max_disparity=FORM_DISPARITY))


@ex4.advice("block_matching gives no disparity past the left edge of the right image (x - d < 0)")
def left_strip_advice(t):
    scene = truth.scene("random_dots")
    strip_tip_where_right_elsewhere(t, f"block_matching(left, right, max_disparity={FORM_DISPARITY})",
                                    random_dots_map(t), scene, truth.band(scene.judged, FORM_DISPARITY, 9),
                                    bm_figures("random_dots")["legitimate"] + SLACK + FADE, FORM_DISPARITY)


def strip_tip_where_right_elsewhere(t: Trial, what: str, got, scene, judged, allowed: float, max_disparity: int,
                                    function: str = "block_matching"):
    """:func:`left_strip_tip` for a map of ``scene`` whose bad-pixel rate on ``judged`` is within ``allowed`` (the
    credit its graded check gives): a map wrong all over is told why by the graded checks."""
    try:
        got = np.asarray(got)
    except (ValueError, TypeError):   # (a ragged answer: its graded check says what is wrong with it)
        return
    if got.shape == np.asarray(scene.left).shape[:2] and got.dtype.kind in "fiu" \
            and truth.bad_pixel_rate(got, judged, scene.threshold) <= allowed:
        left_strip_tip(t, what, got, max_disparity, function)


# A left pixel x has its match at x - d in the right image, whose first column is 0: d <= x (+ half a
# pixel, the pixel-centre convention). The API leaves that band open (the skeleton: the band where x - d
# leaves the right image is not judged), so a map past it there gets a tip, no point lost (the blind set
# 1206m's legitimate NCC and DP, the right image's first column repeated, lost 1.5 and 2 points). Measured on the
# public scenes (benchmarks/left_strip_block_matching.py): the reference (SSD, NCC), SAD, a Gaussian
# prefilter, cv2.StereoBM (clipped or not) and a loop over the columns x >= d put no pixel past its
# column; searches against a right image padded or wrapped round (np.roll, np.pad with zeros, edge or
# reflection, the x < d cost left finite) 4% to 21% of the strip on the form check's scene, 18% to 29%
# with NCC on the motorcycle.
PAST_THE_EDGE = 0.5     # px beyond x: still the right image's first pixel
LEFT_STRIP_ALLOWED = 0.01   # share of the strip's pixels (legitimate matchers: none)
PAST_THE_EDGE_MISTAKE = "disparities point left of the right image (x - d < 0) along the left border"


def past_the_edge(disparity) -> np.ndarray:
    """The pixels of a disparity map (H, W) -- or of its left columns -- whose disparity is above their column
    x (+ :data:`PAST_THE_EDGE`): a match x - d left of the right image's first column."""
    disparity = np.asarray(disparity, np.float64)
    with np.errstate(invalid="ignore"):
        return np.isfinite(disparity) & (disparity > 0) & \
            (disparity > np.arange(disparity.shape[1])[None, :] + PAST_THE_EDGE)


ROLLED = calls("np.roll")


def _overwrites_rolled_columns(function) -> bool:
    """A rolled image's first d columns written over (``shifted = np.roll(right, d, axis=1)`` then
    ``shifted[:, :d] = ...``): the columns np.roll brought round are no longer there."""
    rolled = {t.id for n in walk(function) if isinstance(n, ast.Assign) and isinstance(n.value, ast.Call)
              and _path(n.value.func).rsplit(".", 1)[-1] == "roll" for t in n.targets if isinstance(t, ast.Name)}
    return any(isinstance(n, ast.Assign) and any(
        isinstance(t, ast.Subscript) and isinstance(t.value, ast.Name) and t.value.id in rolled
        and any(isinstance(part, ast.Slice) and part.lower is None and _disparity_name(part.upper)
                for part in (t.slice.elts if isinstance(t.slice, ast.Tuple) else [t.slice]))
        for t in n.targets) for n in walk(function))


WRAPPED_ROUND = ROLLED & ~Predicate("writes over the columns np.roll brings round", _overwrites_rolled_columns)


def _derived_from(function) -> dict:
    """Local name -> the parameters its value is computed from (`L = _grey(left)`: {"left"}), followed
    through assignments."""
    params = {a.arg for a in function.args.posonlyargs + function.args.args + function.args.kwonlyargs}
    made: dict = {name: {name} for name in params}
    bindings = []
    for node in walk(function):
        if isinstance(node, ast.Assign):
            for target in node.targets:   # (`L, R = f(left), f(right)`: item by item)
                paired = isinstance(target, (ast.Tuple, ast.List)) and isinstance(node.value, (ast.Tuple, ast.List)) \
                    and len(target.elts) == len(node.value.elts)
                bindings += list(zip(target.elts, node.value.elts)) if paired else [(target, node.value)]
    # (in the order of the lines, twice: a loop's later line feeding an earlier one is followed too --
    # linear in the function, where a search to a fixed point is not)
    bindings.sort(key=lambda pair: getattr(pair[1], "lineno", 0))
    for _ in range(2):
        for target, value in bindings:
            reads = set().union(*(made.get(n.id, set()) for n in walk(value) if isinstance(n, ast.Name)))
            for name in (n.id for n in walk(target) if isinstance(n, ast.Name)):
                made.setdefault(name, set()).update(reads)
    return made


def _left_image_rolled_back(function) -> str:
    """`np.roll(L, -d, axis=1)` with L made from ``left`` alone: the left image shifted left, its pixel
    x + d compared with the right image's x -- a map of the right image's pixels (the right image
    shifted by +d, `np.roll(right, d, axis=1)`, compares left x with right x - d). The call, as
    written; "" when the code does not."""
    made = _derived_from(function)
    rolls = [node for node in walk(function)
             if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == "roll"]
    if len(rolls) != 1:   # (a cost rolled back by +d afterwards is indexed by the left image's pixels again)
        return ""
    for node in rolls:
        if len(node.args) >= 2:
            image, shift = node.args[:2]
            origin = set().union(*(made.get(n.id, set()) for n in walk(image) if isinstance(n, ast.Name)))
            if origin == {"left"} and isinstance(shift, ast.UnaryOp) and isinstance(shift.op, ast.USub):
                return ast.unparse(node)
    return ""


def _shifted_left_words(backwards: str) -> str:
    """What the code does where it shifts the left image back (``backwards``: the call, as written)."""
    return from_code(f"Your code shifts the left image (`{backwards}`): it compares the left image's pixel x + d with "
                     "the right image's pixel x, a map of the right image's pixels. The left pixel x matches the "
                     "right pixel x - d: shift the right image by +d instead, and compare it with the left image as "
                     "it is.")


LEFT_IMAGE_SHIFTED = "the left image shifted where the right one belongs (a map of the right image's pixels)"


def name_left_image_shifted(t: Trial, what: str, got, max_disparity: int):
    """Fail naming the left image shifted back (`np.roll(L, -d)`, read from the code) for a failing map whose left
    strip gets disparities above their column x (measured): the left pixel x + d compared with the right pixel
    x, a map of the right image's pixels."""
    got = np.asarray(got, np.float64)
    if got.ndim != 2:
        return
    backwards = next(filter(None, map(_left_image_rolled_back, code_of(t).reachable(["block_matching"]))), "")
    past = past_the_edge(got[:, :min(int(max_disparity), got.shape[1])])
    if backwards and past.size and past.mean() > LEFT_STRIP_ALLOWED:
        t.fail(f"{what}: {past.mean():.0%} of the left strip x < {max_disparity} gets a disparity larger than its "
               "column x. " + _shifted_left_words(backwards), mistake=LEFT_IMAGE_SHIFTED)


EDGE_ROW_LEFT_OUT = "the first or last row of the map never computed"
EDGE_ROW_EMPTY = "the first or last row of the map has no disparity"


_ROW_NAMES = frozenset({"y", "row", "r", "v", "yy", "iy", "i_row", "row_index"})
_HEIGHT_NAMES = frozenset({"h", "height", "rows", "n_rows", "nrows", "H", "img_h", "image_height"})


def _loops_over_rows(function) -> bool:
    """Whether a def runs a `for` loop over the rows: over a `range` whose variable is a row's name (`for y in
    range(1, h)`) or whose bound is the height (`range(height - 1)`, `range(left.shape[0])`) -- one that may start
    late or stop short. (A loop over the disparities of a (D, H, W) volume, `costs[d] = ...`, is not.)"""
    for loop in walk(function):
        if isinstance(loop, ast.For) and isinstance(loop.target, ast.Name) and isinstance(loop.iter, ast.Call) \
                and _path(loop.iter.func) == "range":
            bounds = [n for argument in loop.iter.args for n in walk(argument)]
            if loop.target.id in _ROW_NAMES or any(isinstance(n, ast.Name) and n.id in _HEIGHT_NAMES for n in bounds) \
                    or any(isinstance(n, ast.Subscript) and isinstance(n.value, ast.Attribute) and n.value.attr == "shape"
                           and isinstance(n.slice, ast.Constant) and n.slice.value == 0 for n in bounds):
                return True
    return False


def fail_if_an_edge_row_left_out(t: Trial, what: str, got, true_disparity):
    """Fail when the map's first or last row has no disparity at all while the row beside it and the opposite
    edge row have one at most pixels, and the truth at most of it: a loop over the rows one short
    (`range(height - 1)`), said so where the code loops over the rows (where it does not -- a slice blanking
    rows where it meant columns -- the row is told empty, no cause guessed). A border a block leaves invalid is
    left alike at the top and the bottom (StereoBM leaves block_size // 2 rows at each), and is not this."""
    got = np.asarray(got, np.float64)
    if got.ndim != 2 or got.shape[0] < 3:
        return
    with np.errstate(invalid="ignore"):
        computed = (np.isfinite(got) & (got > 0)).mean(axis=1)
        known = (np.isfinite(true_disparity) & (np.asarray(true_disparity, np.float64) > 0)).mean(axis=1)
    last = got.shape[0] - 1
    for edge, beside, opposite, which in ((last, last - 1, 0, "last"), (0, 1, last, "first")):
        if computed[edge] == 0 and computed[beside] >= 0.5 and computed[opposite] >= 0.5 and known[edge] >= 0.5:
            said = (f"{what}: row {edge}, the {which} row of the map, has no disparity at all (every pixel "
                    f"invalid), where the row beside it has one at {computed[beside]:.0%} of its pixels, the "
                    f"{'first' if which == 'last' else 'last'} row at {computed[opposite]:.0%}, and the truth "
                    f"at {known[edge]:.0%} of this row")
            if not any(map(_loops_over_rows, code_of(t).reachable([what.split("(")[0]]))):
                t.fail(measured(said), mistake=EDGE_ROW_EMPTY)
            t.fail(measured(f"{said}: the {which} row is never computed (a loop over the rows that "
                            f"{'stops one short' if which == 'last' else 'starts one late'}?)"),
                   mistake=EDGE_ROW_LEFT_OUT)


def left_strip_tip(t: Trial, what: str, got, max_disparity: int, function: str = "block_matching"):
    """A tip (advice checks) when more than :data:`LEFT_STRIP_ALLOWED` of the left strip ``x < max_disparity``
    of the map ``got`` (H, W) get a disparity above their column ``x`` (+ :data:`PAST_THE_EDGE`): a match
    left of the right image, which has no pixel there. Said of the map; np.roll only when the code calls it;
    the left image shifted the wrong way, where the code does that."""
    got = np.asarray(got, np.float64)
    if got.ndim != 2:
        return
    strip = got[:, :min(int(max_disparity), got.shape[1])]
    past = past_the_edge(strip)
    if not past.size or past.mean() <= LEFT_STRIP_ALLOWED:
        return
    y, x = (int(v[0]) for v in np.nonzero(past))
    read = code_of(t).reachable([function])
    found = (f"{what}: {past.sum()} pixels of the left strip x < {max_disparity} ({past.mean():.0%} of it) get a "
             f"disparity larger than their column x (e.g. d = {strip[y, x]:g} at x = {x}, row {y})")
    # (block matching's band is left out of every bad-pixel rate, as its skeleton says; a DP's scenes may judge it)
    unjudged = " The band where x - d leaves the right image is not judged: no points depend on this tip." \
        if function == "block_matching" else \
        " No points depend on this tip (a check that judges the band counts its wrong pixels like any others)."
    backwards = next(filter(None, map(_left_image_rolled_back, read)), "")
    if backwards:
        t.advise(f"{found}. " + _shifted_left_words(backwards) + unjudged)
        return
    rolled = WRAPPED_ROUND.found(read)
    t.advise(f"{found}: their match x - d would lie left of the right image's first column, where it has no pixel. "
             + measured("A left pixel x can only match d = 0..min(x, max_disparity); a pixel with no match there "
                        "is best left invalid (0).")
             + (from_code(" Your code calls np.roll, which brings the right image's last columns round to its "
                          "left edge: blocks there are compared with the far side of the image.") if rolled else "")
             + unjudged,
             hint=NO_PARTNER_HINT.said(t, [function]))


def fail_if_mostly_past_the_edge(t: Trial, what: str, got, truth_disparity, threshold: float, function: str):
    """Fail naming matches left of the right image when at least half of a failing map's wrong pixels (on a scene
    that judges the left band, as the deep step does) get a disparity above their column x: pixels whose match
    x - d has no pixel in the right image."""
    got = np.asarray(got, np.float64)
    known = np.asarray(truth_disparity, np.float64)
    if got.shape != known.shape or got.ndim != 2:
        return
    with np.errstate(invalid="ignore"):
        wrong = (known > 0) & ~(np.isfinite(got) & (got > 0) & (np.abs(got - known) <= threshold))
    past = past_the_edge(got)
    if not wrong.any() or (wrong & past).sum() < 0.5 * wrong.sum():
        return
    y, x = (int(v[0]) for v in np.nonzero(wrong & past))
    t.fail(measured(f"{what}: {(wrong & past).sum() / wrong.sum():.0%} of its wrong pixels get a disparity larger "
                    f"than their column x (e.g. d = {got[y, x]:g} at x = {x}, row {y}): their match x - d would lie "
                    "left of the right image's first column, where it has no pixel. A left pixel x can only match "
                    "d = 0..min(x, max_disparity): impossible matches win along the left border."),
           mistake=PAST_THE_EDGE_MISTAKE, hint=NO_PARTNER_HINT.said(t, [function]))


# Told only to code that marks no column as without a partner (an infinite cost, a slice up to d, a test against d).
NO_PARTNER_HINT = Hint(measured("where x - d < 0 the block has no partner in the right image: ")
                       + "give those disparities an infinite cost (or leave the pixel invalid)",
                       asks=Predicate("gives some costs a value of their own (an infinite cost, a slice up to d "
                                      "or a test of d against a column)", _marks_left_border),
                       # (read leniently: which entries the code marks is not read -- `costs[d, :d]` marks rows --,
                       # so the tip says where the marks belong, not that the code puts them there)
                       instead=measured("where x - d < 0 the block has no partner in the right image: ")
                       + "your code {found}: look at which entries it marks for each d (the columns x < d, in every "
                         "row), and at what becomes of them afterwards")


@ex4.check("block_matching (SSD, block_size=9) on random-dot planes", points=3, timeout=STEREO_TIMEOUT)
def block_matching_dots(t):
    scene = truth.scene("random_dots")
    got = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity)
    return judge_block_matching(t, "block_matching(left, right)", got, scene, bm_figures("random_dots"),
                                again=block_matcher(t, scene))


@ex4.check("block_matching (SSD, block_size=7) on a slanted textured plane", points=2,
           timeout=STEREO_TIMEOUT)
def block_matching_slanted(t):
    scene = truth.scene("slanted")
    got = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity, block_size=7, cost="ssd")
    return judge_block_matching(t, "block_matching(left, right, block_size=7)", got, scene,
                                bm_figures("slanted"), again=block_matcher(t, scene, block_size=7))


@ex4.check("block_size is used: block_size=5 and 15 give different maps", points=1, timeout=STEREO_TIMEOUT)
def block_matching_uses_block_size(t):
    # Quality checks cannot see an ignored block_size (a fixed 9 matches as well as 7).
    judge_parameter_changes_result(t, "block_matching(left, right)", matcher_on(t, truth.scene("random_dots")),
                                   "block_size", BLOCK_SIZES, "disparity map")
    # (and every other check gives max_disparity: its default is judged here, on a small pair)
    return judge_max_disparity_default(t, "block_matching")


@ex4.check("cost is used: cost=\"ssd\" and cost=\"ncc\" give different maps where the right image is darker",
           points=1, timeout=STEREO_TIMEOUT)
def block_matching_uses_cost(t):
    """The default cost is SSD; NCC (the extension) forgives a brightness gain SSD does not. Quality checks
    cannot see a default that runs NCC (it matches as well): on the slanted plane with its right image at 40% of
    its brightness (the two costs' maps differ at about half the pixels there, at 2% on random dots) the two
    maps must differ. Where cost="ncc" is not written yet, the extension's checks say so."""
    what = "block_matching(left, right at 40% brightness, cost=...)"
    _dimmed_map(t, "ssd")   # (the default cost's failure is this check's)
    try:
        _dimmed_map(t, "ncc")
    except StudentFailure:
        return passed("cost=\"ncc\" is not answered: the extension's checks judge it")
    near = _one_map_for_both_costs(t)
    if near is None:
        return passed("the maps' form is judged by the check of block_matching's answer")
    if near:
        if near["ncc"] >= 0.9 and near["ncc"] > near["ssd"] + 0.2:
            capitals = any(isinstance(node, ast.Constant) and node.value in ("SSD", "NCC")
                           for function in code_of(t).reachable(["block_matching"]) for node in walk(function))
            t.fail(measured(f"{what}: cost=\"ssd\" gives exactly the map cost=\"ncc\" gives, on a pair where the "
                            "two costs disagree (a change of brightness changes SSD, not NCC), and that map is NCC's "
                            f"({near['ncc']:.0%} of the pixels within 1 px of it, {near['ssd']:.0%} of SSD's): the "
                            "default cost is not SSD -- look at how cost is compared")
                   + (from_code(": your code compares it with a string in capitals, where the API's values are \"ssd\" and \"ncc\"")
                      if capitals else ""), mistake="cost is ignored")
        return passed("cost=\"ncc\" gives the same map as cost=\"ssd\", not NCC's: the extension's checks judge it")
    return passed("cost=\"ssd\" and cost=\"ncc\" give different maps")


def _dimmed_map(t: Trial, cost: str):
    """block_matching(cost=``cost``) on the slanted plane with its right image at 40% of its brightness, where the two
    costs' maps differ at about half the pixels: one call per grading, shared by the checks that compare them."""
    scene = truth.scene("slanted")
    brighter = _dimmed_pair_right(scene)
    return t.shared(("block_matching", "slanted at 40%", cost), lambda: t.call(
        "block_matching", np.array(scene.left), brighter, max_disparity=scene.max_disparity, cost=cost))


def _one_map_for_both_costs(t: Trial) -> dict | bool | None:
    """Whether cost="ssd" and cost="ncc" give one same informative map on the dimmed pair (:func:`_dimmed_map`): then
    how near that map is to each cost's winner-take-all (``{"ssd": share, "ncc": share}`` of pixels within 1 px),
    else False; None where a map is not of a disparity map's form. Raises the student's failure of either call."""
    scene = truth.scene("slanted")
    ssd, ncc = _dimmed_map(t, "ssd"), _dimmed_map(t, "ncc")
    shape = np.shape(scene.disparity)
    if not all(isinstance(m, np.ndarray) and m.shape == shape and m.dtype.kind in "biuf" for m in (ssd, ncc)):
        return None
    if not same_informative_result(ssd, ncc):
        return False
    # (which cost the one map is: SSD for both is NCC not written -- the extension's to judge --, NCC for both
    # is the default not what it names, ex4's; and clearly NCC's: a wrong SSD map ignoring cost is near neither)
    gained = replace(scene, right=_dimmed_pair_right(scene))
    return {cost: float(np.mean(np.abs(np.nan_to_num(np.asarray(ssd, np.float64)) - truth.winner_take_all(
        gained, 9, cost)) <= 1)) for cost in ("ssd", "ncc")}


def _dimmed_pair_right(scene):
    return np.clip(np.asarray(scene.right, np.float64) * 0.4, 0, 255).astype(np.uint8)


def ncc_not_written(t: Trial) -> None:
    """Fail an extension's check where cost="ncc" gives exactly cost="ssd"'s map on the dimmed pair, and that map is
    not NCC's: the extension is NCC, and a map the SSD matching made earns none of its points (a block matcher
    ignoring cost earned 4 of its 8 points where SSD's map is as good: third-party round of 2026-12-07)."""
    try:
        near = _one_map_for_both_costs(t)
    except StudentFailure:
        return   # (a call that failed: the check's own call says so)
    if near and not (near["ncc"] >= 0.9 and near["ncc"] > near["ssd"] + 0.2):
        said = measured("block_matching(left, right at 40% brightness, cost=\"ncc\") gives exactly the map cost=\"ssd\" "
                        "gives, on a pair where the two costs disagree at about half the pixels (a change of brightness "
                        "changes SSD, not NCC)")
        fn = code_of(t).functions.get("block_matching")
        if fn is not None and "cost" not in never_read(fn):   # (read, and both costs come out one map: see ncc_gain)
            t.fail(said + from_code(": your block_matching reads cost, yet NCC is not computed, and the extension is "
                                    "NCC -- look at what each cost's branch computes"), hint=NCC_HINT.said(t))
        t.fail(said + ": the cost argument is ignored, so NCC is not computed, and the extension is NCC.",
               hint=NCC_HINT.said(t), mistake="the cost argument is ignored")


def judge_max_disparity_default(t: Trial, function: str):
    """``function(left, right)`` with max_disparity left out gives what max_disparity=64, the API's
    default, gives: the checks give it, each for its scene."""
    left, right, _ = truth.square_on_background(7)
    return judge_default_is_the_apis(t, f"{function}(left, right) on a 120 x 160 pair",
                                     lambda **kw: t.call(function, np.array(left), np.array(right), **kw),
                                     "max_disparity", 64, "disparity map")


# The window is block_size x block_size: a 9 x 9 window centred on a 5 x 5 square in front of a
# background holds 25 of the square's pixels and 56 of the background's, so the background's disparity
# wins there; on a 7 x 7 square (49 against 32) the square's does (a map that loses it is wrong in other
# ways too -- costs in uint8 -- and is left to the other checks). Measured: the reference (SSD and
# NCC) and cv2.StereoBM (blockSize=9) give the background on the 5 x 5 square (median 4, 3.75) and the
# square on the 7 x 7 one (12, 11.9); a 4 x 4 window (block_size // 2) or a 9 x 1 strip keep the small
# square (12).
SQUARES = ((7, "square"), (5, "background"))   # (the larger first: a map that loses it is judged elsewhere)


@ex4.check("block_matching compares block_size x block_size windows: a square smaller than the window takes "
           "its background's disparity", points=1, timeout=STEREO_TIMEOUT)
def block_matching_window_size(t):
    found = []
    for side, wins in SQUARES:
        left, right, square = truth.square_on_background(side)
        what = f"block_matching(left, right, max_disparity=32, block_size=9) on a {side} x {side} square"
        got = t.call("block_matching", np.array(left), np.array(right), max_disparity=32, block_size=9)
        got = np.asarray(t.expect_array(got, what, shape=left.shape, kind="iuf"), np.float64)
        # (a map wrong on the background too -- another direction, another unit -- is the other checks' to judge)
        background = np.ones(left.shape, bool)
        background[:, :40] = False   # (left of the search band: no match there)
        background[square[0].start - 12:square[0].stop + 12, square[1].start - 12:square[1].stop + 12] = False
        if not abs(_valid_median(got[background]) - 4) <= 1:
            return passed("the background is not found at its 4 px: the other checks judge the map")
        if not (got[square] > 0).any():   # (a matcher may mark the square invalid: a left-right check's)
            found.append(f"the {side} x {side} square invalid")
            continue
        median = _valid_median(got[square])
        found.append(f"{median:g} px on the {side} x {side} square")
        kept = median >= 8.0   # (halfway between the background's 4 px and the square's 12 px)
        if wins == "background" and kept:
            kept_by = measured(f"{what} keeps the square at its own disparity ({median:g} px in the median): a "
                               f"9 x 9 window centred on it holds {side * side} of its pixels and "
                               f"{81 - side * side} of the background's, so the background's disparity (4 px) wins "
                               "there, as it does for cv2.StereoBM with blockSize=9.")
            window = _window_giving(got, left, right, square)
            if window:   # (the map is that window's map: confirmed, not inferred from the square alone)
                t.fail(measured(f"{kept_by} Your map is the one {window} gives (SSD), a window smaller than 9 x 9: "
                                "the cost is summed over block_size x block_size pixels."),
                       mistake="the matching window is smaller than block_size x block_size")
            t.fail(measured(f"{kept_by} Your map is not that of a smaller window either ("
                            + ", ".join(SMALLER_WINDOWS) + "): look at how your cost is computed from the 9 x 9 "
                            "window; SSD is the mean of the squared pixel differences (L - R)^2 over it."))
        if wins == "square" and not kept:   # (a costs computed wrongly loses it too: the other checks judge)
            window = _window_giving(got, left, right, square, windows=_larger_windows(9))
            if window:   # (confirmed with block_size=5: the same rule gives its own window there, a fixed
                # window -- block_size ignored -- does not)
                rule = next(name for name in LARGER_RULES if name in window)
                again = t.call("block_matching", np.array(left), np.array(right), max_disparity=32, block_size=5)
                again = np.asarray(t.expect_array(again, what.replace("block_size=9", "block_size=5"),
                                                  shape=left.shape, kind="iuf"), np.float64)
                fives = {name: size for name, size in _larger_windows(5).items() if rule in name}
                if not _window_giving(again, left, right, square, windows=fives):
                    window = ""
            if window:   # (the map is that larger window's map: confirmed, not inferred from the square alone)
                t.fail(measured(f"{what} gives the {side} x {side} square its background's disparity ({median:g} px "
                                f"in the median), where {side * side} of the 81 pixels of a 9 x 9 window centred on "
                                f"it are the square's, so it keeps its own 12 px: your map is the one {window} gives "
                                "(SSD), a window larger than block_size x block_size."),
                       mistake="the matching window is larger than block_size x block_size")
            return passed(measured(f"the {side} x {side} square is not found ({median:g} px): the other checks "
                                   "judge the map"))
    return passed("; ".join(found))


# The windows smaller than block_size x block_size a matcher may use instead (half the side, or one row).
SMALLER_WINDOWS = {"a 5 x 5 window": (5, 5), "a 4 x 4 window (block_size // 2)": (4, 4), "a 3 x 3 window": (3, 3),
                   "a 9 x 1 strip (one row)": (9, 1)}
# and the larger ones: block_size taken as the half-width (2 block_size + 1), or doubled.
LARGER_RULES = {"2 block_size + 1: block_size taken as the half-width": lambda b: 2 * b + 1,
                "2 block_size": lambda b: 2 * b}


def _larger_windows(block_size: int) -> dict:
    """{name: (side, side)} of the windows :data:`LARGER_RULES` make of ``block_size``."""
    return {f"a {rule(block_size)} x {rule(block_size)} window ({name})": (rule(block_size), rule(block_size))
            for name, rule in LARGER_RULES.items()}


WINDOW_AGREEMENT = 0.9   # of the judged pixels within 1 px of that window's map


def _square_neighbourhood(square, shape) -> np.ndarray:
    """The pixels within 6 px of the ``square`` (rows, columns) slices."""
    around = np.zeros(shape, bool)
    rows, columns = square
    around[rows.start - 6:rows.stop + 6, columns.start - 6:columns.stop + 6] = True
    return around


def _window_giving(got, left, right, square, max_disparity: int = 32, windows=None) -> str:
    """Which of ``windows`` (by default :data:`SMALLER_WINDOWS`) gives ``got`` (winner-take-all SSD) on the
    ``square`` and around it (the pixels where windows of other sizes part); "" when none does."""
    L, R = np.asarray(left, np.float64), np.asarray(right, np.float64)
    on_square = np.zeros(L.shape, bool)
    on_square[square] = True
    around = _square_neighbourhood(square, L.shape) & ~on_square
    for name, window in (windows or SMALLER_WINDOWS).items():
        costs = np.full((max_disparity + 1,) + L.shape, np.inf)
        for d in range(max_disparity + 1):
            shifted = np.empty_like(R)
            shifted[:, d:], shifted[:, :d] = R[:, :R.shape[1] - d], R[:, :1]
            costs[d] = cv2.blur((L - shifted) ** 2, window, borderType=cv2.BORDER_REFLECT)
        agrees = np.abs(np.argmin(costs, axis=0) - got) <= 1
        if min(agrees[on_square].mean(), agrees[around].mean()) >= WINDOW_AGREEMENT:
            return name
    return ""


def _valid_median(disparities) -> float:
    """The median of the valid disparities (> 0; NaN marks none), 0 when none is valid."""
    valid = disparities[disparities > 0]
    return float(np.median(valid)) if valid.size else 0.0


@ex4.check("block_matching (SSD, block_size=9) on the Middlebury motorcycle", points=2,
           timeout=STEREO_TIMEOUT)
def block_matching_motorcycle(t):
    scene = truth.scene("motorcycle")
    got = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity, block_size=9)
    return judge_block_matching(t, "block_matching(left, right, block_size=9)", got, scene,
                                bm_figures("motorcycle"))


@ex4.check("block_matching searches the whole range: d = 0 on a wall at infinity, d = max_disparity on "
           "the nearest square", points=1, timeout=STEREO_TIMEOUT)
def block_matching_zero_disparity(t):
    scene = truth.scene("zero_disparity")
    got = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity, block_size=9)
    return judge_block_matching(t, "block_matching(left, right, block_size=9)", got, scene,
                                bm_figures("zero_disparity"), again=block_matcher(t, scene, block_size=9))


# ================================================================== ext1 NCC
NCC_FORMULA = "NCC = sum((L - mean L)(R - mean R)) / (N std L std R) over the block"
NCC_HINT = Hint(f"{NCC_FORMULA}; it is a similarity: keep the disparity with the HIGHEST score",
                asks=KEEPS_HIGHEST,
                instead=f"{NCC_FORMULA}; your code already {{found}}: the error is elsewhere")
NCC_CALL = 'cost="ncc"'
NOT_CENTRED = "the block means are not subtracted"
# The views of the invariance probe: a random-dot pair whose right view is dimmed (x 0.4, so that
# + 150 stays within 0..255) and then lifted by 150 grey levels. A normalised cross-correlation
# gives the same map for the three (measured, the reference: at most 0.01% of the pixels apart);
# without the means subtracted the lifted view moves the map (the blind set's matcher, numerator
# mean(L R): 24% of the pixels, its dimmed view 0.6%). (A gain of the right view moves no argmax of
# a covariance, divided by the deviations or not: it cannot tell that step.)
INVARIANCE_SCENE = dict(seed=12_016, n_boxes=2)
GAIN, OFFSET = 0.4, 150
INVARIANT = 0.03     # share of the pixels apart: the same map
MOVED = 0.1          # share of the pixels apart: the map moved


def ncc_invariance(t: Trial) -> tuple[float, float] | None:
    """(share of pixels apart under a gain of GAIN, under an offset of OFFSET grey levels) of the student's
    NCC maps on the invariance probe; None when a call fails or gives no map."""
    scene = truth.random_dot_scene(**INVARIANCE_SCENE)
    right = np.asarray(scene.right, np.float64)
    dimmed = np.round(GAIN * right).astype(np.uint8)
    views = {"plain": np.array(scene.right), "dimmed": dimmed, "lifted": (dimmed + OFFSET).astype(np.uint8)}

    def answer(view):
        got = t.call("block_matching", np.array(scene.left), views[view], max_disparity=scene.max_disparity,
                     block_size=9, cost="ncc")
        ok = isinstance(got, np.ndarray) and got.shape == scene.judged.shape and got.dtype.kind in "iuf"
        return got if ok else None

    maps = {view: t.probe(f"block_matching/ncc invariance/{view}", lambda view=view: answer(view)) for view in views}
    if any(m is None for m in maps.values()) or not same_informative_result(maps["plain"], maps["plain"]):
        return None
    columns = np.arange(scene.judged.shape[1])[None, :] >= scene.max_disparity
    apart = truth.map_disagreement((scene.judged > 0) & columns)
    return apart(maps["plain"], maps["dimmed"]), apart(maps["dimmed"], maps["lifted"])


SUBTRACTS_MEANS = calls_any("np.mean", ".mean", "cv2.boxFilter", "cv2.blur", "scipy.ndimage.uniform_filter",
                            says="computes block means")
BLOCK_MEANS_HINT = Hint("Subtract each block's mean before multiplying.", asks=SUBTRACTS_MEANS,
                   instead="Your code {found}: check that each block's own mean is subtracted from it, in both "
                           "views, before the product.")
NORMALISE_NCC_HINT = Hint(
    "Subtract each block's mean and divide by the product of the blocks' standard deviations.",
    asks=SUBTRACTS_MEANS & STD_PRODUCT,
    # what it asks for is read (means, a product of deviations); which pixels they are taken over is not
    instead="Your code {found}: look at the pixels each mean and each deviation is taken over (the two blocks of "
            "the product, each its own, over the same window).")


def name_ncc_normalisation(t: Trial, what: str):
    """Fail naming the means not subtracted when the NCC maps show it: moved by an offset of one view,
    not by a gain (a cost that is no correlation at all, SSD, is moved by both)."""
    measured = ncc_invariance(t)
    if measured is None:
        return
    gain, offset = measured
    if gain <= INVARIANT and offset >= MOVED:
        t.fail(f"{what}: it looks like {NOT_CENTRED}: adding {OFFSET} grey levels to the right view moves {offset:.0%} "
               f"of your disparities (on random dots), while scaling it by {GAIN:g} moves {gain:.0%}; a normalised "
               "cross-correlation is unchanged by both. " + BLOCK_MEANS_HINT.said(t),
               hint=NCC_FORMULA, mistake=NOT_CENTRED)


ext1 = lab.exercise("ext1", "Normalised cross-correlation", functions=[
    "block_matching(left, right, max_disparity=64, block_size=9, cost=\"ncc\")"])


@ext1.check("block_matching(cost=\"ncc\") on the Middlebury motorcycle, and at the ends of the search range",
            points=3, timeout=STEREO_TIMEOUT)
def ncc_motorcycle(t):
    scene = truth.scene("motorcycle")
    got = ncc_motorcycle_map(t)
    ncc_not_written(t)
    what = "block_matching(left, right, cost=\"ncc\")"
    verdict = judge_disparity(t, what, got, scene, figures("motorcycle", "bm_ncc_9")["bad"],
                              probe=block_size_probe(t, what, scene, cost="ncc"),
                              mistakes=MatchingMistakes(scene, 9, "ncc"),
                              naming=naming_crop(t, "block_matching", scene, block_size=9, cost="ncc"))
    if verdict.fraction < 1:
        verdict.hint = NCC_HINT.said(t)
        return verdict
    # The motorcycle has no pixel at either end of the range: d = 0 and d = max_disparity are
    # judged on the range-ends scene; a map right but for one end takes half the points.
    ends = truth.scene("zero_disparity")
    got = expect_disparity(t, what, t.call("block_matching", np.array(ends.left), np.array(ends.right),
                                           max_disparity=ends.max_disparity, block_size=9, cost="ncc"), ends)
    try:
        judge_range_ends(t, what, got, ends, figures("zero_disparity", "bm_ncc_9"))
    except Fail as missed:
        return partial(0.5, f"{missed.message} On the motorcycle: {verdict.message}.", hint=missed.hint,
                       mistake=missed.mistake)
    return verdict


def ncc_motorcycle_map(t: Trial):
    """block_matching(cost="ncc") on the motorcycle: one call, judged by its check and read by the left strip's tip."""
    scene = truth.scene("motorcycle")
    return t.shared(("block_matching", "motorcycle", "ncc"), lambda: t.call(
        "block_matching", np.array(scene.left), np.array(scene.right), max_disparity=scene.max_disparity,
        block_size=9, cost="ncc"))


@ext1.advice("block_matching(cost=\"ncc\") gives no disparity past the left edge of the right image (x - d < 0)")
def ncc_left_strip_advice(t):
    scene = truth.scene("motorcycle")
    strip_tip_where_right_elsewhere(t, "block_matching(left, right, cost=\"ncc\")", ncc_motorcycle_map(t), scene,
                                    scene.judged, figures("motorcycle", "bm_ncc_9")["bad"] + MARGIN, scene.max_disparity)


COSTS_SWAPPED = "the two costs are swapped: cost=\"ncc\" runs the SSD matching and cost=\"ssd\" the NCC"


def _nearer(got, scene, cost: str) -> bool:
    """Whether ``got`` (a map of the student's of ``scene``) is nearer the ``cost`` matching's map than the other
    cost's (winner-take-all, 9 x 9 blocks)."""
    if not isinstance(got, np.ndarray) or got.shape != np.asarray(scene.left).shape[:2]:
        return False
    apart = {c: truth.bad_pixel_rate(got, truth.winner_take_all(scene, 9, c), 1.0) for c in ("ssd", "ncc")}
    return apart[cost] < apart["ncc" if cost == "ssd" else "ssd"]


@ext1.check("NCC is robust to a brightness and contrast change between the views", points=4,
            timeout=STEREO_TIMEOUT)
def ncc_gain(t):
    gain, offset = truth.reference_figures()["gain"]
    scene = truth.with_gain(truth.scene("motorcycle"), gain, offset)
    what = f"block_matching(left, {gain:g} * right {offset:+g}, cost=\"ncc\")"
    got = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity, block_size=9, cost="ncc")
    got = expect_disparity(t, what, got, scene)
    bad = truth.bad_pixel_rate(got, scene.judged, scene.threshold)
    show_disparity(t, what, scene, got, bad)
    reference = figures("motorcycle_gain", "bm_ncc_9")["bad"]
    summary = (f"bad-pixel rate {bad:.1%} (reference NCC {reference:.1%}; "
               f"SSD would give {figures('motorcycle_gain', 'bm_ssd_9')['bad']:.1%})")
    if bad <= reference + MARGIN:
        return passed(summary)
    plain = truth.scene("motorcycle")
    unchanged = t.call("block_matching", np.array(plain.left), np.array(plain.right),
                       max_disparity=plain.max_disparity, block_size=9, cost="ncc")
    ssd = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity, block_size=9, cost="ssd")
    # Two equal maps show an ignored cost only when they are informative: a map of zeros under
    # both costs (OpenCV-4 code reading cv2.minMaxLoc's location under OpenCV 5) says nothing of it.
    if isinstance(ssd, np.ndarray) and ssd.shape == got.shape and same_informative_result(ssd, got):
        fn = code_of(t).functions.get("block_matching")
        if fn is not None and "cost" not in never_read(fn):
            # (code that reads cost -- a branch for each -- is not ignoring it: whatever each cost computes, the
            # disparities come out one map; a location read alike from both costs' scores, under the OpenCV major
            # the code was not written for, is one way -- audit of 2026-12-07)
            t.fail(from_code(f"{what} gives exactly the map cost=\"ssd\" gives on this pair, although your "
                             "block_matching reads cost: whatever each cost computes, the disparities come out the "
                             "same -- look at how a disparity is taken from each cost's scores."))
        t.fail(f"{what} gives exactly the SSD result: the cost argument is ignored.",
               mistake="the cost argument is ignored")
    # cost="ssd" robust where cost="ncc" is not: each cost runs the other's matching (SSD cannot be robust
    # to a gain -- the reference's SSD fails here -- so its map being right says it is normalised)
    if isinstance(ssd, np.ndarray) and ssd.shape == got.shape \
            and truth.bad_pixel_rate(ssd, scene.judged, scene.threshold) <= reference + MARGIN:
        robust = (f"{what}: bad-pixel rate {bad:.1%} (reference {reference:.1%}), while cost=\"ssd\" on the same "
                  f"pair gives {truth.bad_pixel_rate(ssd, scene.judged, scene.threshold):.1%}, as only a "
                  "normalised cost can (the sum of squared differences changes with the gain)")
        # (the swap is told where, on the plain pair, cost="ncc" is the SSD matching's map and cost="ssd" the NCC's: an SSD of images
        # normalised as a whole is robust too, beside an NCC of its own gone wrong -- audit of 2026-12-06)
        # (a confirmation only: its call failing -- raising, out of time -- confirms nothing and costs the verdict
        # nothing; made only where cost="ncc" already looks like the SSD matching)
        plain_ssd = None
        if _nearer(unchanged, plain, "ssd"):
            try:
                plain_ssd = t.call("block_matching", np.array(plain.left), np.array(plain.right),
                                   max_disparity=plain.max_disparity, block_size=9, cost="ssd")
            except StudentFailure:
                plain_ssd = None
        if _nearer(plain_ssd, plain, "ncc"):
            t.fail(measured(f"{robust}: it looks like {COSTS_SWAPPED}."), mistake=COSTS_SWAPPED)
        t.fail(measured(f"{robust}: cost=\"ssd\" copes with the gain where cost=\"ncc\" does not."),
               mistake="cost=\"ncc\" is not robust to a gain where cost=\"ssd\" is")
    if (isinstance(unchanged, np.ndarray) and unchanged.shape == plain.disparity.shape
            and truth.bad_pixel_rate(unchanged, plain.judged, plain.threshold)
            <= figures("motorcycle", "bm_ncc_9")["bad"] + MARGIN):
        name_ncc_normalisation(t, what)
        t.fail(f"{what}: bad-pixel rate {bad:.1%} (reference {reference:.1%}), although it works "
               "when the views have the same brightness: your NCC is not fully normalised. "
               + NORMALISE_NCC_HINT.said(t),
               mistake="the NCC is not fully normalised")
    diagnose_disparity(t, what, got, scene, reference + MARGIN,
                       mistakes=MatchingMistakes(scene, 9, "ncc"))
    name_ncc_normalisation(t, what)
    block_size_probe(t, what, scene, cost="ncc")()
    if bad < reference + MARGIN + FADE:
        return partial((reference + MARGIN + FADE - bad) / FADE, f"{what}: {summary}.", hint=NCC_HINT.said(t))
    t.fail(f"{what}: {summary}; it fails even when both views have the same brightness.",
           hint=NCC_HINT.said(t))


# A flat area (a rectified pair's black border) has no texture: a block inside it has standard
# deviation 0 and its NCC is 0/0. Where a flat block falls in a textured pixel's search range, the
# match must not change: the reference scores flat blocks 0 (so do an epsilon in the denominator and
# cv2.matchTemplate's TM_CCOEFF_NORMED). Measured on the motorcycle with a 24-px black strip down both
# views' left side, max_disparity=32: the reference's map changes on 0.0% of the textured pixels whose
# range reaches the strip, NaN left in the costs (np.argmin takes it as the lowest) on 47%.
FLAT_STRIP = 24
FLAT_CHANGED = 0.10   # of the textured pixels whose search range reaches the strip
FLAT_NAN = measured("a flat block (standard deviation 0) gets the NCC 0/0 = NaN, and np.argmin takes NaN as the lowest "
            "cost: a textured pixel is matched to the first flat block in its range")


@ext1.check("block_matching(cost=\"ncc\") with a flat black border: textured pixels keep their matches",
            points=1, timeout=STEREO_TIMEOUT)
def ncc_flat_border(t):
    scene = truth.scene("motorcycle")
    left, right = np.array(scene.left), np.array(scene.right)
    flat_left, flat_right = left.copy(), right.copy()
    flat_left[:, :FLAT_STRIP] = 0
    flat_right[:, :FLAT_STRIP] = 0
    max_disparity, block = 32, 9
    called = f"block_matching(left, right, max_disparity={max_disparity}, cost=\"ncc\")"
    what = f"{called} with the {FLAT_STRIP} left columns of both views black"
    plain = expect_disparity(t, called, t.call("block_matching", left, right, max_disparity=max_disparity,
                                               block_size=block, cost="ncc"), scene)
    got = expect_disparity(t, what, t.call("block_matching", flat_left, flat_right, max_disparity=max_disparity,
                                           block_size=block, cost="ncc"), scene)
    ncc_not_written(t)
    # the left pixels whose own block and true match are textured (the scene's disparities are at most
    # its own search range) and whose search range reaches a block inside the strip
    first = FLAT_STRIP + block // 2 + scene.max_disparity
    reach = np.zeros(got.shape, bool)
    reach[:, first:FLAT_STRIP + block // 2 + max_disparity] = True
    changed = np.abs(np.asarray(got, np.float64) - plain) > 0.5
    share = float(changed[reach].mean())
    if share <= FLAT_CHANGED:
        return passed(f"{share:.1%} of the textured pixels near the border change their match")
    t.images(what, left_image=flat_left, without_the_border=disparity_picture(plain, max_disparity),
             yours=disparity_picture(got, max_disparity))
    # np.argmin over NaN costs: the first disparity whose right block lies wholly in the strip
    columns = np.broadcast_to(np.arange(got.shape[1]), got.shape)
    first_flat = columns + block // 2 - FLAT_STRIP + 1
    at_first_flat = float((np.abs(np.asarray(got, np.float64) - first_flat) < 0.5)[changed & reach].mean())
    message = (f"{what}: {share:.0%} of the textured pixels whose search range reaches the black border get "
               "another disparity than without the border (their own blocks and true matches are "
               f"unchanged; at most {FLAT_CHANGED:.0%} allowed)")
    if at_first_flat > 0.5:
        t.fail(measured(f"{message}. A flat block has no texture: its NCC is 0/0, and {at_first_flat:.0%} of those "
                        "pixels take the first disparity whose right block lies wholly in the border: it looks like "
                        f"{FLAT_NAN}. Give flat blocks a score of 0 (np.divide(cov, std_l * std_r, "
                        "out=np.zeros_like(cov), where=std_l * std_r > 1e-6), or a small epsilon in the "
                        "denominator)."), mistake=FLAT_NAN)
    # (an NCC not normalised scores the blocks half in the border highest: that is its own mistake)
    name_ncc_normalisation(t, what)
    # The border's blocks win over the real matches only where the map without the border found them: where it
    # is wrong there too (the views swapped, the search turned round), the other checks say why, not this one.
    truth_there = np.where(reach, np.asarray(scene.disparity, np.float64), 0.0)
    if truth.bad_pixel_rate(plain, truth_there, scene.threshold) > 0.5:
        t.fail(f"{message}; without the border your map is wrong there too (see the other checks of "
               "block_matching).")
    t.fail(measured(f"{message}: the blocks in and at the border, with little or no texture, win over the real "
                    "matches."))


# ================================================================== ex5 dynamic programming
ex5 = lab.exercise("ex5", "Smoothness: scanline dynamic programming", functions=[
    "dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None)"])
lab.forbid("dp_stereo", "cv2.StereoBM_create", "cv2.StereoSGBM_create", "cv2.StereoBM", "cv2.StereoSGBM")
JUMPS_VS_BM = 0.4   # "far fewer jumps": at most this fraction of block matching's


def call_dp(t: Trial, scene, **kwargs):
    return t.call("dp_stereo", np.array(scene.left), np.array(scene.right),
                  max_disparity=scene.max_disparity, **kwargs)


def smoothness_probe(t: Trial, scene):
    """Fail naming ``smoothness`` as ignored when 0 and a huge penalty give the same map, or a penalty
    of 1 and a huge one do (its value read only to tell 0 from the rest: the winner-take-all branch)."""
    for values in ((0, 1e7), (1, 1e7)):
        judge_parameter_used(t, "dp_stereo(left, right)", lambda **kw: call_dp(t, scene, **kw),
                             "smoothness", values, "disparity map")


SMOOTHNESS_IGNORED = "the smoothness term is ignored"
PENALTY_REWARDS = "the smoothness penalty rewards jumps instead of costing them"


WEAK_DEFAULT = guessed("the default smoothness penalty is too weak for the cost's scale")
# a conversion that stops uint8 differences wrapping round (a float, or a signed integer type)
FLOATS = ("float", "float32", "float64", "double", "img_as_float", "int", "int16", "int32", "int64")


def _converts_an_image(function) -> bool:
    """A float conversion of one of the function's first two parameters (the images), written on it
    (``left.astype(np.float64)``, ``np.float32(right)``, ``np.asarray(left, dtype=float)``)."""
    arguments = function.args.posonlyargs + function.args.args
    images = {a.arg for a in arguments[:2]}
    for node in walk(function):
        if not isinstance(node, ast.Call):
            continue
        last = _path(node.func).rsplit(".", 1)[-1]
        given = [node.func.value] if last == "astype" and isinstance(node.func, ast.Attribute) else node.args[:1]
        kinds = [*node.args[1:], *(k.value for k in node.keywords if k.arg == "dtype")] if last != "astype" \
            else node.args
        floating = last in FLOATS or any(_path(k).rsplit(".", 1)[-1] in FLOATS for k in kinds
                                         if isinstance(k, (ast.Name, ast.Attribute)))
        if floating and any(isinstance(n, ast.Name) and n.id in images for g in given for n in walk(g)):
            return True
    return False


COST_SCALE_HINT = Hint("compute the data cost in float (differences of uint8 images wrap round: 10 - 12 = 254), "
                       "and choose the default penalty for that cost's scale", asks=TO_FLOAT,
                       # the penalty's scale is the measurement itself (WEAK_DEFAULT); the conversion is read
                       instead="your code {found}: " + checklist(
                           "", ("the data cost is computed on the converted images",
                                Predicate("converts the images to float", _converts_an_image)),
                           none_left="the cost is computed in float; the default penalty is what is too weak for "
                                     "that cost's scale"))


# half to a thousand times the reference's default (6 grey levels a step), past an SSD cost's scale
STRONGER_PENALTIES = (3.0, 10.0, 30.0, 100.0, 1000.0, 10000.0)
_SCENE_KEYS = ("weak_texture", "motorcycle", "random_dots", "slanted", "zero_disparity")


def stronger_penalty_rates(t: Trial, scene) -> list:
    """The bad-pixel rates of the student's dp_stereo on ``scene`` with :data:`STRONGER_PENALTIES` (1.0 where a
    call fails or answers in another form), up to the first as good as the reference's DP; asked once per trial."""
    key = next((k for k in _SCENE_KEYS if truth.scene(k).name == scene.name), None)
    good = figures(key, "dp_5")["bad"] + MARGIN if key is not None else 0.0

    def rates():
        out = []
        for smoothness in STRONGER_PENALTIES:
            if out and out[-1] <= good:
                break
            try:
                got = call_dp(t, scene, smoothness=smoothness)
            except StudentFailure:
                got = None
            usable = isinstance(got, np.ndarray) and got.shape == scene.disparity.shape and got.dtype.kind in "iuf"
            out.append(truth.bad_pixel_rate(np.nan_to_num(got.astype(np.float64)), scene.judged, scene.threshold)
                       if usable else 1.0)
        return out
    return t.probe(f"dp_stereo/stronger penalties/{scene.name}", rates) or []


def stronger_penalty_mends(t: Trial, scene) -> bool | None:
    """Whether a penalty stronger than the student's default makes their map as good as the reference's DP
    (the guess that the default is too weak for the cost's scale, tried); None where it cannot be told."""
    key = next((k for k in _SCENE_KEYS if truth.scene(k).name == scene.name), None)
    rates = stronger_penalty_rates(t, scene) if key is not None else []
    if not rates:
        return None
    return min(rates) <= figures(key, "dp_5")["bad"] + MARGIN


def fail_winner_take_all(t: Trial, what, jumps, wta_jumps, scene, compared_with="winner-take-all block matching",
                         zero_jumps=None):
    """The map is as jumpy as winner-take-all matching. Named "ignored" only when the student's own
    smoothness=0 map is as jumpy (``zero_jumps``, else asked on ``scene``): where 0 gives clearly more
    jumps, the penalty acts, too weakly for the cost's scale (a data cost far larger than it should
    be -- uint8 differences wrapping round, say -- or a default chosen too small)."""
    if zero_jumps is None:
        zero = t.probe(f"dp_stereo/smoothness 0/{scene.name}", lambda: call_dp(t, scene, smoothness=0))
        usable = isinstance(zero, np.ndarray) and zero.shape == scene.disparity.shape and zero.dtype.kind in "iuf"
        zero_jumps = truth.jump_rate(np.nan_to_num(zero.astype(np.float64)), scene.judged) if usable else None
    if zero_jumps is not None and jumps < 0.85 * zero_jumps:
        beside = "" if zero_jumps == wta_jumps else f" ({compared_with}: {wta_jumps:.1%})"
        said = f"{what}: {jumps:.1%} of neighbouring pixels jump by more than 1 px{beside}, and {zero_jumps:.1%} " \
               "with your smoothness=0: the penalty acts"
        if stronger_penalty_mends(t, scene) is False:
            # (the guess tried: no penalty up to a thousand times the default makes the map right, so the
            # default's scale is not the cause -- a path traced back from the wrong neighbour is)
            t.fail(measured(f"{said}, but no other penalty makes the map right (smoothness "
                            f"{', '.join(f'{p:g}' for p in STRONGER_PENALTIES)} tried: bad-pixel rates "
                            f"{', '.join(f'{r:.0%}' for r in stronger_penalty_rates(t, scene))})."))
        t.fail(f"{said}, but it looks like {WEAK_DEFAULT}.", hint=COST_SCALE_HINT.said(t), mistake=WEAK_DEFAULT)
    if zero_jumps is not None and jumps > 1.5 * zero_jumps and jumps > zero_jumps + 0.05:
        # Jumpier than with no penalty at all: the penalty acts, and favours jumps.
        # (measured: the student's own maps with and without the penalty; where to look, not what to write)
        t.fail(measured(f"{what}: {jumps:.1%} of neighbouring pixels jump by more than 1 px, against {zero_jumps:.1%} "
                        f"with your smoothness=0: the penalty makes the map jumpier, so it looks like {PENALTY_REWARDS}: "
                        "look at how a jump's cost enters the forward pass and the choice made where the path is "
                        "traced back."), mistake=PENALTY_REWARDS)
    t.fail(f"{what}: it looks like {SMOOTHNESS_IGNORED} (winner-take-all): {jumps:.1%} of "
           f"neighbouring pixels jump by more than 1 px, as many as {compared_with} ({wta_jumps:.1%}).",
           hint=from_code("your code sets smoothness to 0 when it is None, which switches the smoothness term off: "
                          "the default is a positive penalty suited to your cost's scale")
           if ZERO_DEFAULT.holds(code_of(t).reachable([DP_FUNCTION])) else
           "with smoothness=None, use a default penalty suited to your cost's scale",
           mistake=SMOOTHNESS_IGNORED)


def _zero_default(function) -> bool:
    """The smoothness parameter given 0 where it is None: ``smoothness = 0.0`` (under ``if smoothness is None``),
    ``smoothness = 0 if smoothness is None else smoothness``, ``smoothness = smoothness or 0``."""
    def zero(node) -> bool:
        return isinstance(node, ast.Constant) and not isinstance(node.value, bool) and node.value == 0

    for n in walk(function):
        if isinstance(n, ast.Assign) and any(isinstance(t, ast.Name) and "smooth" in t.id.lower() for t in n.targets):
            value = n.value
            if zero(value) or isinstance(value, ast.IfExp) and zero(value.body) \
                    or isinstance(value, ast.BoolOp) and isinstance(value.op, ast.Or) and zero(value.values[-1]):
                return True
    return False


ZERO_DEFAULT = Predicate("sets smoothness to 0 when it is None", _zero_default)


# Said of the map, not of the code: a last column wrong alone shows where the backtracking starts,
# not why (a start that is right meets wrong energies when the forward pass is wrong).
BACKTRACKING = "the last column, where the backtracking starts, is wrong, far more than the rest of the map"
OVERSMOOTHED = guessed("the default smoothness is far too large for your cost's scale")


def name_oversmoothing(t: Trial, what: str, got, scene, allowed: float):
    """Fail naming a default penalty so large that the rows come out flat, for a failing map."""
    got = np.nan_to_num(np.asarray(got, np.float64))
    if got.shape != scene.disparity.shape or truth.bad_pixel_rate(got, scene.judged, scene.threshold) <= allowed:
        return
    def flat_rows(disparity) -> float:
        inner = np.nan_to_num(np.asarray(disparity, np.float64))[
            truth.JUDGE_BORDER:-truth.JUDGE_BORDER, truth.JUDGE_BORDER:-truth.JUDGE_BORDER]
        return float(np.mean(np.all(np.diff(inner, axis=1) == 0, axis=1)))

    flat = flat_rows(got)
    if flat >= 0.9:
        # With no smoothness at all the rows must vary: if they come out flat still, the penalty is not
        # the cause (a minimum over the wrong axis flattens them whatever it is).
        # (asked as a probe: a call that raises or runs out of time there names nothing, and is no verdict)
        unsmoothed = t.probe(f"dp unsmoothed/{scene.name}", lambda: call_dp(t, scene, smoothness=0))
        if unsmoothed is None or np.shape(unsmoothed) != got.shape or flat_rows(unsmoothed) >= 0.9:
            return
        t.fail(f"{what}: it looks like {OVERSMOOTHED}: {flat:.0%} of the rows have a single disparity "
               "(with smoothness=None, use a penalty of the order of your data cost's differences).",
               mistake=OVERSMOOTHED)


NOT_BACKTRACKED = ("the disparities are not backtracked: each column takes the lowest accumulated energy of the "
                   "forward pass instead of following the choices back from the last column")


FORWARD_AGREEMENT = 0.9   # share of pixels within 1 px of a forward-pass map
JUMP_COST_DIFFERS = ("the backtracking weighs a jump between disparities otherwise than the forward pass (each "
                     "step back must add the same smoothness * |d - d'| the forward pass added)")


def _walks_back(function) -> bool:
    """A loop that runs backwards: `range(..., ..., -1)`, `reversed(...)`, or over `x[::-1]`."""
    for loop in walk(function):
        if not isinstance(loop, ast.For):
            continue
        iterated = loop.iter
        if isinstance(iterated, ast.Call) and isinstance(iterated.func, ast.Name):
            if iterated.func.id == "reversed":
                return True
            step = iterated.args[2] if iterated.func.id == "range" and len(iterated.args) == 3 else None
            if isinstance(step, ast.UnaryOp) and isinstance(step.op, ast.USub) \
                    or (isinstance(step, ast.Constant) and isinstance(step.value, int) and step.value < 0):
                return True
        if isinstance(iterated, ast.Subscript) and isinstance(iterated.slice, ast.Slice) \
                and isinstance(iterated.slice.step, ast.UnaryOp) and isinstance(iterated.slice.step.op, ast.USub):
            return True
    return False


WALKS_BACK = Predicate("loops backwards over the columns", _walks_back)


def _chosen_from_the_left(functions) -> int | None:
    """The line where a loop running forward (`for x in range(1, width)`) picks each column's disparity by an
    argmin that reads the disparity it picked at the column before (`d[x] = np.argmin(E[x] + jump(d[x - 1]))`):
    a greedy pass from column 0, where the backtracking starts at the last column and walks left. None when no
    loop does (or the code also loops backwards: a walk back is there)."""
    for function in functions:
        if _walks_back(function):
            return None
        for loop in walk(function):
            if not (isinstance(loop, ast.For) and isinstance(loop.target, ast.Name) and isinstance(loop.iter, ast.Call)
                    and isinstance(loop.iter.func, ast.Name) and loop.iter.func.id == "range"):
                continue
            x = loop.target.id
            for node in walk(loop):
                if not (isinstance(node, ast.Assign) and len(node.targets) == 1
                        and isinstance(node.targets[0], ast.Subscript) and isinstance(node.targets[0].value, ast.Name)):
                    continue
                chosen, at = node.targets[0].value.id, ast.unparse(node.targets[0].slice)
                if at != x or not any(isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] == "argmin"
                                      for n in walk(node.value)):
                    continue
                # (directly, or through a name the loop makes from it: `jump = ramp[|d - d_prev[x - 1]|]`)
                made = {t.id: m.value for m in walk(loop) if isinstance(m, ast.Assign)
                        for t in m.targets if isinstance(t, ast.Name)}
                read = [node.value] + [made[n.id] for n in walk(node.value)
                                       if isinstance(n, ast.Name) and n.id in made]
                if any(isinstance(n, ast.Subscript) and isinstance(n.value, ast.Name) and n.value.id == chosen
                       and ast.unparse(n.slice).replace(" ", "") == f"{x}-1" for value in read for n in walk(value)):
                    return node.lineno
    return None


def dp_hint(t: Trial) -> str:
    """Where a DP's difference can come from: its steps, or, for code choosing each column from the one before it
    left to right, that the backtracking runs the other way."""
    line = _chosen_from_the_left(code_of(t).reachable([DP_FUNCTION]))
    if line is None:
        return DP_STEPS
    return from_code(f"your code picks each column's disparity given the one picked at the column before it, from "
                     f"the left (line {line}): a greedy pass, which can never revise an early choice. The lab sheet's "
                     "backtracking starts at the last column, at the lowest accumulated energy there, and walks left, "
                     "each column's disparity the one that led to its right neighbour's")


def forward_pass_maps(scene, block_size: int = 5) -> dict[str, np.ndarray]:
    """The maps a DP gives at a huge smoothness when it reads each column's lowest accumulated
    energy instead of backtracking, for the two usual data costs (block SAD, block SSD; the cost
    255 or 255^2 where x - d < 0): with a penalty far above any cost, the accumulated energy at
    column x is the sum of the cost up to x at one disparity, so its argmin per column is that of
    the cumulative sum along the row."""
    left, right = (np.asarray(image, np.float64) for image in (scene.left, scene.right))
    if left.ndim == 3:
        left, right = (cv2.cvtColor(image.astype(np.float32), cv2.COLOR_BGR2GRAY).astype(np.float64)
                       for image in (left, right))
    height, width = left.shape
    depth = scene.max_disparity + 1
    maps = {}
    for name, cost, fill in (("SAD", np.abs, 255.0), ("SSD", np.square, 255.0 ** 2)):
        volume = np.full((depth, height, width), fill)
        for d in range(min(depth, width)):
            shifted = np.empty_like(right)
            shifted[:, d:] = right[:, :width - d]
            shifted[:, :d] = right[:, :1]
            volume[d, :, d:] = cv2.blur(cost(left - shifted), (block_size, block_size),
                                        borderType=cv2.BORDER_REFLECT)[:, d:]
        maps[name] = np.argmin(np.cumsum(volume, axis=2), axis=0).astype(np.float64)
    return maps


def name_no_backtracking(t: Trial, what: str):
    """Fail naming disparities read from the forward pass when, on the weak-texture scene at a
    huge smoothness, the rows are not constant (a backtracked DP keeps one disparity a row) and
    the map is a forward-pass map (:func:`forward_pass_maps`). Measured there: the blind set's DP
    without backtracking (SAD) 99% of the pixels within 1 px of the SAD map; the reference (constant
    rows) 49% and 1%."""
    scene = truth.scene("weak_texture")
    flat = t.probe("dp_stereo/huge smoothness", lambda: call_dp(t, scene, smoothness=1e7))
    if not isinstance(flat, np.ndarray) or flat.shape != scene.disparity.shape or flat.dtype.kind not in "iuf":
        return
    flat = np.nan_to_num(flat.astype(np.float64), nan=-1.0)
    changing = float(np.mean(np.any(np.diff(flat, axis=1) != 0, axis=1)))
    if changing < 0.5:
        return
    agreement = {name: float(np.mean(np.abs(flat - m) <= 1)) for name, m in forward_pass_maps(scene).items()}
    cost, share = max(agreement.items(), key=lambda item: item[1])
    walking = WALKS_BACK.found(code_of(t).reachable(["dp_stereo"])) if share >= FORWARD_AGREEMENT else ""
    if walking:
        # (their code does walk back: then a jump costs less there than in the forward pass -- a unit
        # penalty, |d - d'|, where smoothness * |d - d'| belongs -- and the forward pass's choice wins)
        t.fail(f"{what}: it looks like {JUMP_COST_DIFFERS}. " + from_code(
               f"Your code walks back from the last column (it {walking}), yet with smoothness=1e7, where a "
               f"backtracked DP keeps one disparity per row, {changing:.0%} of your rows change, and {share:.0%} "
               f"of your pixels are, within 1 px, the disparity with the lowest {cost} summed along the row up to "
               "that column: the walk back weighs a jump by less than smoothness * |d - d'|."),
               mistake=JUMP_COST_DIFFERS)
    if share >= FORWARD_AGREEMENT:
        t.fail(f"{what}: it looks like {NOT_BACKTRACKED}. With smoothness=1e7 a backtracked DP keeps one "
               f"disparity per row; {changing:.0%} of your rows change, and {share:.0%} of your pixels are, "
               f"within 1 px, the disparity with the lowest {cost} summed along the row up to that column "
               "(what the forward pass holds at each column under so large a penalty).", mistake=NOT_BACKTRACKED)


LAST_COLUMN_TOLERANCE = 0.2   # bad fraction of the last column (the references: 0 on synthetic scenes)


def judge_last_column(t: Trial, what: str, got, scene):
    """The DP is judged up to the last column, where its backtracking starts.

    The judged border leaves out a few columns, which hides a last column that
    is never filled in; on a synthetic scene the last column is as easy as any.
    """
    got = np.asarray(got, dtype=np.float64)
    truth_column = scene.disparity[truth.JUDGE_BORDER:-truth.JUDGE_BORDER, -1]
    column = got[truth.JUDGE_BORDER:-truth.JUDGE_BORDER, -1]
    known = truth_column > 0
    with np.errstate(invalid="ignore"):
        good = np.isfinite(column) & (column > 0) & (np.abs(column - truth_column) <= scene.threshold)
    bad = 1.0 - float(good[known].mean())
    # the backtracking's start is the cause only where the last column stands out: a map wrong
    # all over (a broken data cost) is wrong at its last column too, and is judged as a whole
    whole = truth.bad_pixel_rate(got, scene.judged, scene.threshold)
    stands_out = whole <= 0.5 * bad
    if bad > LAST_COLUMN_TOLERANCE and stands_out:
        # (a row stored right to left is wrong at its last column first, on a scene of one disparity per row:
        # there, read right to left, the last column is right and the map no worse)
        flipped = got[truth.JUDGE_BORDER:-truth.JUDGE_BORDER, 0]
        with np.errstate(invalid="ignore"):
            flipped_good = np.isfinite(flipped) & (flipped > 0) & (np.abs(flipped - truth_column) <= scene.threshold)
        if 1.0 - float(flipped_good[known].mean()) <= LAST_COLUMN_TOLERANCE:
            name_mirrored_rows(t, what, got, scene.judged, scene.threshold,
                               truth.bad_pixel_rate(np.nan_to_num(got), scene.judged, scene.threshold), better=1.0 + 1e-9)
        values = np.unique(np.round(column[known], 2))
        shown = ", ".join(f"{v:g}" for v in values[:3]) + (", ..." if len(values) > 3 else "")
        # measured: the map's last column, where every backtracking starts, whatever the code does there
        # (the map's own share right is told, measured on this input: "mostly right" was said of a map 45% wrong)
        t.fail(measured(f"{what}: the last column (x = {got.shape[1] - 1}), where the backtracking starts, is wrong "
                        f"in {bad:.0%} of the rows (your values there: {shown}; true disparities "
                        f"{truth_column[known].min():.1f} to {truth_column[known].max():.1f}), while the map as a "
                        f"whole is right in {1.0 - whole:.0%} of the pixels judged."), mistake=BACKTRACKING)   # (where in the code: not known)


@ex5.check("dp_stereo beats block matching where the texture is weak", points=4, timeout=STEREO_TIMEOUT)
def dp_weak_texture(t):
    scene = truth.scene("weak_texture")
    what = "dp_stereo(left, right)"
    got = expect_disparity(t, what, weak_texture_dp_map(t), scene)
    bad = truth.bad_pixel_rate(got, scene.judged, scene.threshold)
    show_disparity(t, f"{what} on {scene.name}", scene, got, bad)
    judge_last_column(t, what, got, scene)
    fail_if_an_edge_row_left_out(t, what, got, scene.disparity)
    reference, bm = figures("weak_texture", "dp_5"), figures("weak_texture", "bm_ssd_5")
    summary = (f"bad-pixel rate {bad:.1%} (reference {reference['bad']:.1%}; block matching "
               f"with the same block size {bm['bad']:.1%})")
    if bad <= reference["bad"] + MARGIN:
        # the square is at the top of the search range: within 1 px, d = max_disparity - 1 would pass;
        # the map is otherwise right, so a miss there takes half the points
        try:
            judge_top_of_range(t, what, got, scene, truth.top_of_range(scene.judged, scene.max_disparity),
                               reference["top_found"], "the reference", show=False)
        except Fail as missed:
            return partial(0.5, f"{missed.message} {summary}.", hint=missed.hint, mistake=missed.mistake)
        return passed(summary)
    jumps = truth.jump_rate(got, scene.judged)
    if jumps >= 0.6 * bm["jumps"]:
        smoothness_probe(t, scene)
        fail_winner_take_all(t, what, jumps, bm["jumps"], scene)
    name_oversmoothing(t, what, got, scene, reference["bad"] + MARGIN)
    diagnose_disparity(t, what, got, scene, reference["bad"] + MARGIN)
    if bad < bm["bad"] - MARGIN:
        better = f"{summary}: better than block matching, but not yet as good as the reference."
        try:
            name_no_backtracking(t, what)
        except Fail as named:   # a named mistake does not take the credit the map earns
            return partial(0.5, f"{named.message} {better}", mistake=named.mistake)
        # No cause is known here: the hint says where the difference can come from, not what to change.
        naming_crop(t, "dp_stereo", scene, columns=NAMING_COLUMNS)()
        return partial(0.5, f"{what}: {better}", hint=dp_hint(t))
    name_no_backtracking(t, what)
    naming_crop(t, "dp_stereo", scene, columns=NAMING_COLUMNS)()
    t.fail(f"{what}: {summary}: no better than block matching.")


def weak_texture_dp_map(t: Trial):
    """dp_stereo on the weak-texture scene with its defaults: one call, judged by its check and read by the left
    strip's tip."""
    scene = truth.scene("weak_texture")
    return t.shared(("dp_stereo", "weak_texture"), lambda: call_dp(t, scene))


@ex5.advice("dp_stereo gives no disparity past the left edge of the right image (x - d < 0)")
def dp_left_strip_advice(t):
    # (a left pixel x matches d <= x only, as in block matching: an impossible match given the best cost -- the
    # columns x < d of the cost volume filled with 0 -- takes the left strip; told of a map right elsewhere)
    scene = truth.scene("weak_texture")
    strip_tip_where_right_elsewhere(t, "dp_stereo(left, right)", weak_texture_dp_map(t), scene, scene.judged,
                                    figures("weak_texture", "dp_5")["bad"] + MARGIN, scene.max_disparity, DP_FUNCTION)


@ex5.check("dp_stereo is smooth: far fewer disparity jumps along scanlines than block matching",
           points=2, timeout=STEREO_TIMEOUT)
def dp_smooth(t):
    for key in ("weak_texture", "motorcycle"):
        scene = truth.scene(key)
        what = f"dp_stereo(left, right) on {scene.name}"
        got = expect_disparity(t, what, call_dp(t, scene), scene)
        jumps = truth.jump_rate(got, scene.judged)
        bm = figures(key, "bm_ssd_5")["jumps"]
        if jumps > JUMPS_VS_BM * bm:
            smoothness_probe(t, scene)
            if jumps >= 0.6 * bm:
                fail_winner_take_all(t, what, jumps, bm, scene)
            t.fail(f"{what}: {format_apart(jumps, JUMPS_VS_BM * bm, 2, percent=True)} of neighbouring pixels "
                   f"jump by more than 1 px; block matching gives {bm:.1%} and at most "
                   f"{JUMPS_VS_BM * bm:.1%} is expected.")
    return passed("far fewer jumps than block matching on both scenes")


@ex5.check("block_size is used: block_size=3 and 9 give different maps", points=1, timeout=STEREO_TIMEOUT)
def dp_uses_block_size(t):
    # The DP checks call the default block_size=5 only: a block fixed at 5 (or a cost per pixel) passes them.
    scene = truth.scene("weak_texture")
    judge_parameter_changes_result(t, "dp_stereo(left, right)", lambda **kw: call_dp(t, scene, **kw),
                                   "block_size", (3, 9), "disparity map")
    return judge_max_disparity_default(t, "dp_stereo")


@ex5.check("dp_stereo on the Middlebury motorcycle", points=3, timeout=STEREO_TIMEOUT)
def dp_motorcycle(t):
    scene = truth.scene("motorcycle")
    got = expect_disparity(t, "dp_stereo(left, right)", call_dp(t, scene), scene)
    reference = figures("motorcycle", "dp_5")["bad"]
    name_oversmoothing(t, "dp_stereo(left, right)", got, scene, reference + MARGIN)
    return judge_disparity(t, "dp_stereo(left, right)", got, scene, reference,
                           naming=naming_crop(t, "dp_stereo", scene, columns=NAMING_COLUMNS),
                           probe=lambda: (name_no_backtracking(t, "dp_stereo(left, right)"), judge_parameter_used(
                               t, "dp_stereo(left, right)", lambda **kw: call_dp(t, scene, **kw),
                               "block_size", (3, 9), "disparity map")))


JUMPS_LIMITED = ("a jump between neighbouring disparities is limited in size: the minimum over the previous "
                 "column's disparities d' (in the forward pass or the walk back) leaves the far ones out, where "
                 "every d' in 0..max_disparity belongs, each at smoothness * |d - d'|")
ALMOST_NO_PENALTY = 1e-4   # a smoothness at which any DP free to jump crosses the edge as winner-take-all does


@ex5.check("dp_stereo crosses a deep depth edge (22 px) in one step", points=1, timeout=STEREO_TIMEOUT)
def dp_depth_edge(t):
    # The other scenes' edges are at most 10 px deep: a DP that only steps by a pixel or two follows
    # them closely enough; under the API's linear penalty a jump of 22 costs no more than 22 steps of 1.
    scene = truth.scene("deep_step")
    what = f"dp_stereo(left, right) on {scene.name}"
    got = expect_disparity(t, what, call_dp(t, scene), scene)
    bad = truth.bad_pixel_rate(got, scene.judged, scene.threshold)
    reference = figures("deep_step", "dp_5")["bad"]
    summary = f"bad-pixel rate {bad:.1%} (reference {reference:.1%})"
    if bad <= reference + MARGIN:
        return passed(summary)
    show_disparity(t, what, scene, got, bad)
    fail_if_mostly_past_the_edge(t, what, got, scene.judged, scene.threshold, DP_FUNCTION)
    name_oversmoothing(t, what, got, scene, reference + MARGIN)

    def rate(smoothness):   # the student's own map at another penalty, None where it cannot be told
        got = t.probe(f"dp_stereo/smoothness {smoothness:g}/{scene.name}", lambda: call_dp(t, scene,
                                                                                          smoothness=smoothness))
        usable = isinstance(got, np.ndarray) and got.shape == scene.disparity.shape and got.dtype.kind in "iuf"
        return truth.bad_pixel_rate(np.nan_to_num(got.astype(np.float64)), scene.judged, scene.threshold) \
            if usable else None
    unsmoothed, almost = rate(0), rate(ALMOST_NO_PENALTY)
    # (a change of the code confirmed on an earlier check -- `np.maximum` of the two halves made `np.minimum` --
    # limits the jumps too: its account comes first, the rule's guess at the cause is not told beside it)
    if unsmoothed is not None and almost is not None and not found_on_earlier_checks(t, DP_FUNCTION) and \
            unsmoothed <= figures("deep_step", "dp_5_s0")["bad"] + MARGIN and almost > unsmoothed + MARGIN:
        # (measured: with no penalty the edge is found, with almost none it is not -- so it is not the
        # penalty's size that stops the map, but which jumps the minimum may take)
        t.fail(measured(f"{what}: {summary}; it looks like {JUMPS_LIMITED}. With smoothness=0 your map finds "
                        f"the edge ({unsmoothed:.1%} bad pixels), yet with smoothness={ALMOST_NO_PENALTY:g}, a "
                        f"penalty that weighs almost nothing, it does not ({almost:.1%}): the jump of 22 px is not "
                        "taken at any penalty."), mistake=JUMPS_LIMITED)
    t.fail(measured(f"{what}: {summary}: the map does not follow the square's edge, a jump from 25 to 3.3 px."))


ZERO_SMOOTHNESS = "smoothness=0 is taken for the default (0 is false, as None is)"
ZERO_TAKEN = zero_taken_for_missing("smoothness")


def name_zero_smoothness(t: Trial, scene, wta, default):
    """Fail naming 0 taken for "not given" (``smoothness or DEFAULT``, ``if not smoothness``) when the
    smoothness=0 map is the default's (measured) and the code tests smoothness for truth (read)."""
    wta, default = (np.nan_to_num(np.asarray(m, np.float64), nan=-1.0) for m in (wta, default))
    if not np.array_equal(wta, default):
        return
    measured_part = ("dp_stereo(left, right, smoothness=0) gives exactly the map of smoothness=None (the "
                     "default), where 0 means no smoothness at all (winner-take-all)")
    found = ZERO_TAKEN.found(code_of(t).reachable(["dp_stereo"]))
    if found:
        t.fail(f"{measured_part}: it looks like {ZERO_SMOOTHNESS}. Your code {found}; "
               + from_code("test `smoothness is None` for the default instead (0 is a value given)."),
               mistake=ZERO_SMOOTHNESS)
    t.fail(measured_part + ".")


@ex5.check("smoothness=0 is winner-take-all; a huge smoothness makes every row constant", points=2,
           timeout=STEREO_TIMEOUT)
def dp_smoothness_parameter(t):
    scene = truth.scene("weak_texture")
    wta = expect_disparity(t, "dp_stereo(left, right, smoothness=0)", call_dp(t, scene, smoothness=0), scene)
    default = expect_disparity(t, "dp_stereo(left, right)", call_dp(t, scene), scene)
    wta_jumps = truth.jump_rate(wta, scene.judged)
    default_jumps = truth.jump_rate(default, scene.judged)
    reference = figures("weak_texture", "dp_5_s0")["jumps"]
    if wta_jumps < 0.5 * reference or default_jumps * 3 > wta_jumps:
        smoothness_probe(t, scene)
    if wta_jumps < 0.5 * reference:
        name_zero_smoothness(t, scene, wta, default)
        t.fail(f"dp_stereo(left, right, smoothness=0): only {wta_jumps:.1%} of neighbouring pixels "
               f"jump by more than 1 px (winner-take-all gives about {reference:.1%}): with "
               "smoothness 0 every pixel must take its best data cost.")
    if default_jumps * 3 > wta_jumps:
        fail_winner_take_all(t, "dp_stereo(left, right)", default_jumps, wta_jumps, scene, "your smoothness=0 result",
                             zero_jumps=wta_jumps)
    flat = expect_disparity(t, "dp_stereo(left, right, smoothness=1e7)",
                            call_dp(t, scene, smoothness=1e7), scene)
    rows_with_jumps = float(np.mean(np.any(np.diff(np.nan_to_num(flat), axis=1) != 0, axis=1)))
    if rows_with_jumps > 0.1:
        smoothness_probe(t, scene)
        name_no_backtracking(t, "dp_stereo(left, right, smoothness=1e7)")
        t.fail(f"dp_stereo(left, right, smoothness=1e7): {rows_with_jumps:.0%} of the rows still "
               "change disparity; with a huge penalty each row should be constant.")
    return passed(f"smoothness=0: {wta_jumps:.1%} jumps; smoothness=1e7: constant rows")


# The API's smoothness is a weight of any size (smoothness * |d_p - d_q|): a weight truncated to a whole
# number shows as plateaus -- 0.5 the map of 0 and 1.5 that of 1 -- where whole steps (0, 1, 2) each
# change the map. Measured on the weak-texture scene: the reference changes 5295 pixels from 0 to 0.5
# and 886 from 1 to 1.5; a truncating DP changes none (and 6016 from 0 to 1).
FRACTIONAL_STEPS = ((0.0, 0.5), (1.0, 1.5))
TRUNCATED = "smoothness is truncated to a whole number"
TRUNCATES_SMOOTHNESS = (expr("int(smoothness)") | expr("round(smoothness)") | expr("np.floor(smoothness)")
                        | expr("math.floor(smoothness)") | expr("smoothness // _") | expr("np.int32(smoothness)")
                        | expr("np.int64(smoothness)")).saying("converts smoothness to an integer")


@ex5.check("a fractional smoothness acts as given: 0.5 is not 0, 1.5 is not 1", points=1, timeout=STEREO_TIMEOUT)
def dp_fractional_smoothness(t):
    scene = truth.scene("weak_texture")
    maps = {s: expect_disparity(t, f"dp_stereo(left, right, smoothness={s:g})", call_dp(t, scene, smoothness=s),
                                scene) for s in (0.0, 0.5, 1.0, 1.5, 2.0)}
    whole_steps = not same_informative_result(maps[0.0], maps[1.0]) and not same_informative_result(maps[1.0],
                                                                                                     maps[2.0])
    plateaus = all(same_informative_result(maps[low], maps[high]) for low, high in FRACTIONAL_STEPS)
    if not (whole_steps and plateaus):
        return passed("the map changes with fractional weights as with whole ones" if whole_steps else
                      measured("whole steps of smoothness do not each change the map: the other checks judge it"))
    read = TRUNCATES_SMOOTHNESS.found(code_of(t).reachable(["dp_stereo"]))
    t.fail(measured("dp_stereo(left, right, smoothness=0.5) gives exactly the map of smoothness=0, and 1.5 that "
                    "of 1, while 0, 1 and 2 each give another: the weight is rounded down to a whole number (a "
                    "penalty of 0.5 per pixel of jump is none at all)")
           + (from_code(f"; your code {read}: keep it a float.") if read else "."),
           mistake=TRUNCATED)


# Per scanline, data cost + s |d_p - d_q| with a huge s is least for one disparity over the whole row: the one
# most of its columns support, whatever the data cost's form. Rows at disparity 6 whose last 16 columns are at 12
# tell a DP that minimises the row's energy (6: the reference, every legitimate variant) from one decided by its
# last columns alone (12: the forward pass carrying the previous column's data cost C(x - 1, d') where its
# accumulated energy M(x - 1, d') belongs, or the backtracking started from the last column's least data cost).
WHOLE_ROW = (6, 12, 16, 16)   # the row's disparity, the strip's, the strip's width, max_disparity
LAST_COLUMNS_DECIDE = "each row's disparity is decided by its last columns alone, not by the energy of the whole row"
FORWARD_PASS_DATA_COST = from_code("the forward pass carries the previous column's data cost, not its accumulated "
                                   "energy")


def _one_before(index, variable: str) -> bool:
    """Whether a subscript's index holds ``variable - 1`` (``x - 1``, ``[:, x - 1]``)."""
    return any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.Sub) and isinstance(n.left, ast.Name)
               and n.left.id == variable and isinstance(n.right, ast.Constant) and n.right.value == 1
               for n in walk(index))


def recurrence_without_itself(functions) -> str:
    """A loop filling ``built[x]`` from ``other[x - 1]`` that never reads ``built[x - 1]`` (a recurrence that does
    not recur: `energy[x] = costs[x] + min(costs[x - 1] + ...)`), said as "`energy[x]` (line 12) is computed from
    `costs[x - 1]` and never from `energy[x - 1]`"; "" where no loop does so."""
    for function in functions:
        for loop in (n for n in walk(function) if isinstance(n, ast.For) and isinstance(n.target, ast.Name)):
            variable = loop.target.id
            body = [n for statement in loop.body for n in walk(statement)]
            before = {}   # name -> its first subscript one before (`costs[x - 1]`)
            for n in body:
                if isinstance(n, ast.Subscript) and isinstance(n.ctx, ast.Load) and isinstance(n.value, ast.Name) \
                        and _one_before(n.slice, variable):
                    before.setdefault(n.value.id, ast.unparse(n))
            for assign in (n for n in body if isinstance(n, ast.Assign)):
                for target in assign.targets:
                    index = target.slice.elts if isinstance(getattr(target, "slice", None), ast.Tuple) else \
                        [getattr(target, "slice", None)]
                    # (filled at x itself -- `energy[x]`, `M[:, x]` -- not at x - 1: a backtracking's `d[x - 1]`)
                    if isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name) \
                            and any(isinstance(i, ast.Name) and i.id == variable for i in index) \
                            and before and target.value.id not in before:
                        other = before[sorted(before)[0]]
                        return from_code(f"`{ast.unparse(target)}` (line {assign.lineno}) is computed from `{other}` "
                                         f"and never from `{target.value.id}` at {variable} - 1")
    return ""


@ex5.check("with a huge smoothness each row takes the disparity its whole length supports (not its last columns')",
           points=1, timeout=STEREO_TIMEOUT)
def dp_whole_row(t):
    d_row, d_strip, strip, max_disparity = WHOLE_ROW
    left, right = truth.strip_at_the_end(d_row, d_strip, strip, max_disparity)
    what = (f"dp_stereo(left, right, max_disparity={max_disparity}, smoothness=1e7) on rows at disparity {d_row} "
            f"whose last {strip} columns are at {d_strip}")
    got = t.expect_array(t.call("dp_stereo", left.copy(), right.copy(), max_disparity=max_disparity,
                                smoothness=1e7), what, shape=left.shape, kind="iuf")
    judged = np.asarray(got, np.float64)[:, max_disparity:]   # (the first columns can see no disparity above x)
    modes = np.array([np.median(row[np.isfinite(row)]) if np.isfinite(row).any() else np.nan for row in judged])
    at_strip = float(np.mean(np.abs(modes - d_strip) <= 0.5))
    if at_strip < 0.5:   # (rows not constant, or at another disparity: the other checks judge the DP)
        return passed(f"{float(np.mean(np.abs(modes - d_row) <= 0.5)):.0%} of the rows at disparity {d_row}")
    columns = judged.shape[1]
    read = recurrence_without_itself(code_of(t).reachable(["dp_stereo"]))
    if read:
        t.fail(f"{what}: {at_strip:.0%} of the rows take disparity {d_strip}, that of their last {strip} columns, where "
               f"the other {columns - strip} columns judged are at {d_row}: {LAST_COLUMNS_DECIDE}. Reading your code: "
               + from_code(f"{read}: the forward pass does not accumulate the energy along the row. Each column "
                           "carries the previous column's accumulated energy, M(x, d) = C(x, d) + min_d' "
                           f"[M(x - 1, d') + s |d - d'|], not its data cost."),
               mistake=FORWARD_PASS_DATA_COST)
    t.fail(measured(f"{what}: {at_strip:.0%} of the rows take disparity {d_strip}, that of their last {strip} "
                    f"columns, where the other {columns - strip} columns judged are at {d_row}: {LAST_COLUMNS_DECIDE}. "
                    "With a huge penalty a row keeps one disparity, the one whose data cost summed over the whole "
                    "row is least. The energy carried from column to column is the accumulated one, "
                    "M(x, d) = C(x, d) + min_d' [M(x - 1, d') + s |d - d'|], and the backtracking starts from the "
                    "least M of the last column."), mistake=LAST_COLUMNS_DECIDE)


# ================================================================== ex6 structured light
ex6 = lab.exercise("ex6", "Structured light", functions=[
    "gray_code_patterns(width, n_bits)", "simulate_structured_light(depth, f, baseline, n_bits)",
    "depth_from_structured_light(images, f, baseline)"])
# The sheet's exercise 6 simulates the patterns a depth map lights and triangulates a depth map back from
# them: the depth map it started from is what the result is compared with.
inplace.shown_after(lab, "simulate_structured_light", "depth", "exercise 6 compares the depth map it triangulates "
                                                                "with the one the patterns were simulated from")


ZERO_ONE = "the values are 0 and 1, not 0 and 255"


def pattern_mistakes(width, n_bits) -> dict:
    expected = truth.gray_code_patterns(width, n_bits)
    return {
        "plain binary code of k instead of its Gray code (g = k XOR (k >> 1))":
            truth.binary_code_patterns(width, n_bits),
        "the bits are in the wrong order: row 0 carries the least significant bit, where the most significant "
        "belongs (bit i of the code, most significant first, in row i)": expected[::-1],
        "black and white are swapped (bit 1 is 255)": 255 - expected,
        ZERO_ONE: expected // 255,
        "the stripe index is rounded; it is floor(u * 2**n_bits / width), (u * 2**n_bits) // width":
            truth.rounded_stripe_patterns(width, n_bits),
        "the columns are numbered from 1 (u = 1 .. width, column u shows column u + 1's code); u runs from 0: "
        "k = (u * 2**n_bits) // width for u = 0 .. width - 1":
            _patterns_of(((np.arange(width) + 1) * (1 << n_bits)) // width, n_bits),
        STRIPE_ONE_TOO_LARGE: _patterns_of((np.arange(width) * (1 << n_bits)) // width + 1, n_bits),
    }


# (on a width that is a multiple of 2**n_bits, the same patterns as the columns numbered from 1: the probe tells)
STRIPE_ONE_TOO_LARGE = measured("the stripe index is one too large: column u shows the code of stripe k + 1, k = "
                                "floor(u * 2**n_bits / width) (np.digitize, for one, numbers its bins from 1)")


PATTERN_PROBE = (97, 5)   # a size on which every mistake of pattern_mistakes shows in many columns


def name_pattern_mistake(t: Trial, what, got, width, n_bits):
    """Fail naming the mistake whose patterns ``got`` are, on evidence: on a few columns
    different mistakes give the same patterns, so a small example is checked again at
    :data:`PATTERN_PROBE` with the student's function."""
    expected = truth.gray_code_patterns(width, n_bits)
    candidates = pattern_mistakes(width, n_bits)
    matching = [mistake for mistake, wrong in candidates.items() if np.array_equal(got, wrong)]
    if not matching:
        return
    # (a mistake shown in a few columns only, or two that give these very patterns: the probe tells)
    if len(matching) > 1 or int(np.sum(np.any(candidates[matching[0]] != expected, axis=0))) < 3:
        try:
            again = t.call("gray_code_patterns", *PATTERN_PROBE)
        except StudentFailure:
            return
        probed = pattern_mistakes(*PATTERN_PROBE)
        matching = [mistake for mistake in matching if isinstance(again, np.ndarray)
                    and again.shape == PATTERN_PROBE[::-1] and np.array_equal(again, probed[mistake])]
        if len(matching) != 1:
            return
    t.fail(f"{what} is wrong: it looks like {matching[0]}.", mistake=matching[0])


def judge_patterns(t: Trial, width, n_bits):
    what = f"gray_code_patterns({width}, {n_bits})"
    got = t.call("gray_code_patterns", width, n_bits)
    expected = truth.gray_code_patterns(width, n_bits)
    if isinstance(got, np.ndarray) and got.shape == (width, n_bits) and width != n_bits:
        t.fail(f"{what} returned shape {got.shape}; expected ({n_bits}, {width}): one row per bit")
    got = t.expect_array(got, what, shape=(n_bits, width))
    if got.dtype != np.uint8:
        if got.any() and np.array_equal(got, expected // 255):   # (all black tells nothing of 0/1)
            t.fail(f"{what} returned 0/1 values as {got.dtype}; the patterns are uint8 images of 0 and 255",
                   mistake=ZERO_ONE)
        t.expect_array(got, what, dtype=np.uint8)
    if np.array_equal(got, expected):
        return
    name_bits_not_isolated(t, what, got, width, n_bits)
    name_pattern_mistake(t, what, got, width, n_bits)
    name_wrapped_stripes(t, what, got, width, n_bits)
    stripes = truth._stripe(width, n_bits)
    column = int(np.argmax(np.any(got != expected, axis=0)))
    if one_code_per_stripe(got, stripes):
        hint = GRAY_CODE_HINT.said(t)
    elif codes_differ_within_stripes(got, stripes):
        hint = STRIPE_HINT + STRIPE_FORMULA_HINT.said(t)
    else:
        hint = SHARED_CODES
    t.fail(f"{what}: column {column} (stripe k = {stripes[column]}) is {got[:, column].tolist()}; "
           f"expected {expected[:, column].tolist()}", hint=hint)


def _patterns_of(k, n_bits) -> np.ndarray:
    """The (n_bits, len(k)) Gray-code patterns of stripe indices ``k``."""
    k = np.asarray(k, dtype=np.int64)
    return truth._bit_rows(k ^ (k >> 1), n_bits)


# measured: the patterns are exactly those of k mod 256, here and on a 1024-column 10-bit projector
WRAPPED_STRIPES = "the stripe index k is kept in 8 bits (uint8): from k = 256 on it wraps round to k - 256"


def name_wrapped_stripes(t: Trial, what, got, width, n_bits):
    """Fail naming :data:`WRAPPED_STRIPES` for patterns that are those of k mod 256 (more than 8 bits), on this
    input and on a projector where most stripes are past 255."""
    stripes = truth._stripe(width, n_bits)
    if stripes.max() < 256 or not np.array_equal(got, _patterns_of(stripes % 256, n_bits)):
        return
    try:
        again = t.call("gray_code_patterns", 1024, 10)
    except StudentFailure:
        return
    if isinstance(again, np.ndarray) and np.array_equal(again, _patterns_of(np.arange(1024) % 256, 10)):
        t.fail(f"{what} is wrong: it looks like {WRAPPED_STRIPES} (gray_code_patterns(1024, 10) too gives "
               "each stripe k from 256 on the code of k mod 256).", mistake=WRAPPED_STRIPES)


def name_bits_not_isolated(t: Trial, what: str, got, width: int, n_bits: int):
    """Fail naming rows that hold more than a bit: values other than 0 and 255, each row (g >> s) & 255
    or g >> s itself (the Gray code shifted, its bit never isolated: `(g >> s) & 1 * 255` is
    `(g >> s) & (1 * 255)`, Python's * binding tighter than &)."""
    values = np.unique(got)
    if np.isin(values, (0, 255)).all():
        return
    stripes = truth._stripe(width, n_bits)
    g = (stripes ^ (stripes >> 1)).astype(np.int64)
    shifts = np.arange(n_bits - 1, -1, -1)[:, None]
    shifted = g[None, :] >> shifts
    shown = ", ".join(str(int(v)) for v in values[:6]) + (", ..." if len(values) > 6 else "")
    # (only where the higher bits show: with one bit, or a few stripes, g >> s is the bit itself -- the bit
    # isolated and left unscaled answers alike)
    if (shifted & 255 != shifted & 1).any() and (np.array_equal(got.astype(np.int64), shifted & 255)
                                                 or np.array_equal(got.astype(np.int64), shifted % 256)):
        t.fail(measured(f"{what}: the patterns hold the values {shown}, not only 0 and 255: row i is (g >> s) & 255, "
                        "the Gray code g shifted with its higher bits kept, where it must be the single bit "
                        "((g >> s) & 1) * 255. Mind that * binds tighter than &: `x & 1 * 255` is `x & 255`."),
               mistake="the bit is not isolated before it is scaled to 255")
    t.fail(measured(f"{what}: the patterns hold the values {shown}, not only 0 and 255: each row is one bit of the "
                    "Gray code, 0 or 255."))


def codes_differ_within_stripes(patterns, stripes) -> bool:
    """Whether two columns of one stripe carry different bits (patterns (n_bits, width), read at mid-grey)."""
    codes = np.packbits(patterns > 127, axis=0).T.copy().view(f"V{(patterns.shape[0] + 7) // 8}").ravel()
    return len(set(zip(stripes.tolist(), codes.tolist()))) > len(set(stripes.tolist()))


# measured: every column of a stripe carries the same code (the stripe index is right), not its Gray code
GRAY_CODE_FORMULA = expr("_ ^ (_ >> 1)") | calls("np.bitwise_xor")
GRAY_CODE_HINT = Hint(measured("each stripe k gets one code, but not the binary-reflected Gray code of k: ")
                      + "g = k XOR (k >> 1), bit i of g (most significant first) in row i",
                      asks=GRAY_CODE_FORMULA.saying("computes k XOR (k >> 1)"),
                      instead=measured("each stripe k gets one code, but not the binary-reflected Gray code of k: ")
                      + "your code {found}: look at which k it is taken of and which bit of g each row shows")
# measured: columns of one stripe carry different codes, so k itself differs
STRIPE_HINT = measured("the columns of one stripe carry different codes")
STRIPE_FORMULA_HINT = Hint(": k = floor(u * 2**n_bits / width), with integer arithmetic (u * 2**n_bits) // width",
                           asks=(expr("_ * _ // _") | expr("(_ << _) // _") | calls("np.floor_divide")
                                 ).saying("computes k with an integer division"),
                           instead=" (your code {found}: look at the values of k it gives the columns of the failing "
                                   "stripe)")
# measured: no stripe's columns differ, but different stripes share a code
SHARED_CODES = measured("different stripes carry the same code: each stripe's Gray code is its own")


def one_code_per_stripe(patterns, stripes) -> bool:
    """Whether all the columns of each stripe carry the same bits (patterns (n_bits, width), bits
    read at mid-grey), and different stripes different bits: the stripe index is right."""
    codes = np.packbits(patterns > 127, axis=0).T.copy().view(f"V{(patterns.shape[0] + 7) // 8}").ravel()
    pairs = len(set(zip(stripes.tolist(), codes.tolist())))
    return pairs == len(set(stripes.tolist())) == len(set(codes.tolist()))


@ex6.check("gray_code_patterns(16, 4) bit for bit", points=2)
def patterns_example(t):
    judge_patterns(t, 16, 4)


@ex6.check("gray_code_patterns for any width and number of bits", points=2)
def patterns_property(t):
    t.for_all(st.tuples(st.integers(1, 700), st.integers(1, 9)), lambda c: judge_patterns(t, *c),
              max_examples=20, describe=lambda c: f"width={c[0]}, n_bits={c[1]}")
    # and every width up to SWEPT_WIDTHS: a stripe index computed in floating point is off by one at
    # the stripe borders of a few widths only (`int(u * (2**n / width))` first at width 98)
    for width in range(1, SWEPT_WIDTHS + 1):
        judge_patterns(t, width, 6)


SWEPT_WIDTHS = 256


# measured: the images are those of each column's own Gray code (its low n_bits bits), here and on another scene
COLUMN_CODED = ("each pixel shows the Gray code of its projector column itself, not of the column's stripe "
                "k = (column * 2**n_bits) // width")


def simulation_explained(got, depth, f, baseline, n_bits) -> list[str]:
    """The simulation mistakes whose images are ``got`` (pixels of tied columns aside)."""
    width = depth.shape[1]
    ties = truth.simulation_ties(depth, f, baseline)
    mistakes = {
        "the projector column is u + f b / Z; the projector is to the right, so it is u - f b / Z":
            dict(sign=1.0),
        "the columns are truncated (int/floor) instead of rounded": dict(rounding=np.floor),
        "plain binary patterns are projected instead of Gray code":
            dict(patterns=truth.binary_code_patterns(width, n_bits)),
        "columns off the projector are clipped to its edge; those pixels must stay black (0)":
            dict(clip=True),
        "the images are in the wrong order: image 0 is lit by the most significant pattern (row 0)":
            dict(reverse=True),
        COLUMN_CODED: dict(patterns=_patterns_of(np.arange(width), n_bits)),
        "the lit pixels are 1, not 255 (each bit is written as 0 or 1)": dict(bits=True),
    }
    found = []
    for mistake, kwargs in mistakes.items():
        reverse, bits = kwargs.pop("reverse", False), kwargs.pop("bits", False)
        candidate = truth.simulate_structured_light(depth, f, baseline, n_bits, **kwargs)
        candidate = candidate[::-1] if reverse else candidate
        candidate = candidate // 255 if bits else candidate
        if not (np.any(got != candidate, axis=0) & ~ties).any():
            found.append(mistake)
    return found


def simulation_on_probe(t: Trial) -> list[str]:
    """The simulation mistakes that explain the student's images of the other scene, with 5 bits."""
    depth, f, baseline = truth.structured_light_scene("slope")

    def answer():
        got = t.call("simulate_structured_light", np.array(depth), f, 1.3 * baseline, 5)
        ok = isinstance(got, np.ndarray) and got.shape == (5,) + depth.shape and got.dtype == np.uint8
        return got if ok else None

    got = t.probe("simulate_structured_light/probe", answer)
    return [] if got is None else simulation_explained(got, depth, f, 1.3 * baseline, 5)


@ex6.check("simulate_structured_light matches the projector model", points=3)
def simulate_boxes(t):
    depth, f, baseline = truth.structured_light_scene("boxes")
    n_bits = 6
    what = f"simulate_structured_light(depth, f={f:g}, baseline={baseline:g}, n_bits={n_bits})"
    got = t.call("simulate_structured_light", np.array(depth), f, baseline, n_bits)
    expected = truth.simulate_structured_light(depth, f, baseline, n_bits)
    height, width = depth.shape
    if isinstance(got, np.ndarray) and got.shape == (height, width, n_bits):
        t.fail(f"{what} returned shape {got.shape}; expected {expected.shape}: the image index comes first")
    got = t.expect_array(got, what, shape=expected.shape, dtype=np.uint8)
    t.images(what, "most significant pattern, then the least significant", expected_first=expected[0],
             yours_first=got[0], expected_last=expected[-1], yours_last=got[-1])
    ties = truth.simulation_ties(depth, f, baseline)
    wrong = np.any(got != expected, axis=0) & ~ties
    if not wrong.any():
        return passed("every lit pixel sees the right projector column")
    for mistake in simulation_explained(got, depth, f, baseline, n_bits):
        if mistake in simulation_on_probe(t):
            t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    lit_expected = np.any(expected > 0, axis=0)
    t.fail(f"{what}: {format_apart(wrong.mean(), 0.0, 2, percent=True)} of the pixels differ from the projector model "
           f"({np.mean(wrong & ~lit_expected):.1%} should be black).",
           hint=PROJECTOR_MODEL)


@ex6.check("simulate_structured_light with a baseline other than 1 (0.6): disparities f b / Z", points=1)
def simulate_other_baseline(t):
    """The public scenes' baseline is 1, where f b / Z, f / (b Z) and f / Z are one number. The baseline enters
    only through the disparity f b / Z, so a scene at baseline b is the same scene with every depth divided by b
    at baseline 1: the student's own two answers are compared (the rest of their model, right or not, is the
    same on both sides), ties of the rounding left out."""
    depth, f, _ = truth.structured_light_scene("boxes")
    baseline, n_bits = 0.6, 6
    what = f"simulate_structured_light(depth, f={f:g}, baseline={baseline:g}, n_bits={n_bits})"
    shape = (n_bits, *depth.shape)
    got = t.expect_array(t.call("simulate_structured_light", np.array(depth), f, baseline, n_bits), what,
                         shape=shape, dtype=np.uint8)
    closer = t.expect_array(t.call("simulate_structured_light", np.array(depth) / baseline, f, 1.0, n_bits),
                            f"simulate_structured_light(depth / {baseline:g}, f={f:g}, baseline=1, n_bits={n_bits})",
                            shape=shape, dtype=np.uint8)
    ties = truth.simulation_ties(depth, f, baseline)
    wrong = np.any(got != closer, axis=0) & ~ties
    if not wrong.any():
        return passed("the baseline enters as f b / Z: the scene at baseline 0.6 is the scene with its depths divided "
                      "by 0.6 at baseline 1")
    lead = (f"{what}: {wrong.mean():.1%} of the pixels differ from what your function gives for the same scene with "
            f"every depth divided by {baseline:g} at baseline 1, where the disparity f b / Z is the same number")
    inverse = truth.simulate_structured_light(depth, f, 1.0 / baseline, n_bits)
    if not (np.any(got != inverse, axis=0) & ~truth.simulation_ties(depth, f, 1.0 / baseline)).any():
        t.fail(measured(f"{lead}; yours are exactly the images of a baseline of {1 / baseline:g}: a disparity f / (b Z) "
                        "where f b / Z belongs (at 1, the public scenes' baseline, both are one)."),
               mistake="the disparity is f / (b Z) instead of f b / Z")
    t.fail(measured(lead + ": look at how the baseline enters the disparity."))


@ex6.check("simulate_structured_light leaves pixels with no depth in front black (Z = 0 and Z < 0), and a "
           "surface too near for the projector", points=1)
def simulate_not_in_front(t):
    """The scene of the first check with a band of rows at Z = 0 and one behind the camera (Z = -3): a
    negative depth gives a negative disparity, whose column u - f b / Z is often on the projector. And a band
    so near that its column u - f b / Z lies more than the projector's width to its left: black too (code that
    reads the patterns at every pixel's column before leaving the unlit ones out reads past the patterns)."""
    depth, f, baseline = truth.structured_light_scene("boxes")
    depth = np.array(depth)
    near = f * baseline / (3.0 * depth.shape[1])   # (a disparity of three widths: every column below -width)
    depth[20:30], depth[60:75], depth[40:45] = 0.0, -3.0, near
    n_bits = 6
    what = f"simulate_structured_light(depth, f={f:g}, baseline={baseline:g}, n_bits={n_bits}), rows 20-29 at Z = 0, " \
           f"rows 60-74 at Z = -3 and rows 40-44 at Z = {near:.3g} (a disparity of three image widths)"
    got = t.expect_array(t.call("simulate_structured_light", depth.copy(), f, baseline, n_bits), what,
                         shape=(n_bits,) + depth.shape, dtype=np.uint8)
    near_lit = np.any(got[:, 40:45] > 0)
    if near_lit:
        wrapped = truth.simulate_structured_light(depth, f, baseline, n_bits, column_dtype=np.uint8)
        if not (np.any(got != wrapped, axis=0) & ~truth.simulation_ties(depth, f, baseline)).any():
            # (a column kept in 8 bits wraps round there: -480 is 32)
            t.fail(f"{what}: rows 40-44 are lit, " + measured(f"exactly as if {COLUMN_IN_8_BITS}") + ".",
                   mistake=COLUMN_IN_8_BITS)
        t.fail(f"{what}: rows 40-44 are lit, but their projector column u - f b / Z is off the projector (three "
               "widths to its left): no column lights them, they are black (0) in every image.",
               mistake="pixels off the projector are lit")
    lit = np.any(got > 0, axis=0) & (depth <= 0)
    if not lit.any():
        return passed("every pixel with Z <= 0, and every pixel too near for the projector, is black in every image")
    rows = sorted({int(r) for r in np.nonzero(lit)[0]})
    where = "Z = -3" if all(depth[r, 0] < 0 for r in rows) else "Z = 0" if all(depth[r, 0] == 0 for r in rows) \
        else "Z = 0 or Z = -3"
    t.images(what, "the first (most significant) image", yours_first=got[0],
             expected_first=truth.simulate_structured_light(depth, f, baseline, n_bits)[0])
    t.fail(f"{what}: {lit.mean():.1%} of the pixels, all at {where}, are lit: a point at Z <= 0 is not in "
           "front of the camera, so no projector column lights it: it is black (0) in every image.",
           mistake="pixels with Z <= 0 are lit", hint=measured(
               "a pixel whose depth is not > 0 must be left out of the pixels the patterns are written to (black "
               "in every image), whatever column its disparity gives (a disparity set to 0 there gives column u, "
               "inside the projector)"))


@ex6.advice("simulate_structured_light leaves NaN depths black, as it does Z <= 0")
def simulate_nan_depth(t):
    """The skeleton marks "nothing there" with Z <= 0; a depth map from a sensor or a triangulation marks it
    with NaN too (NaN <= 0 is False). Worth no points: a tip where NaN pixels raise or are lit."""
    depth, f, baseline = truth.structured_light_scene("boxes")
    depth = np.array(depth, dtype=np.float64)
    depth[20:30] = np.nan
    n_bits = 6
    what = f"simulate_structured_light(depth, f={f:g}, baseline={baseline:g}, n_bits={n_bits}) with rows 20-29 NaN"
    try:
        got = t.call("simulate_structured_light", depth.copy(), f, baseline, n_bits)
    except StudentFailure as failure:
        t.advise(measured(f"{what} raised ({failure.message.splitlines()[0]}): NaN says no depth, as Z <= 0 does, "
                          "and NaN <= 0 is False; test `not (Z > 0)` (or np.isfinite) to leave those pixels black"))
        return
    if isinstance(got, np.ndarray) and got.shape == (n_bits,) + depth.shape and np.any(got[:, 20:30] > 0):
        t.advise(measured(f"{what} lights some of the NaN rows: NaN says no depth, as Z <= 0 does, and NaN <= 0 is "
                          "False; test `not (Z > 0)` (or np.isfinite) to leave those pixels black"))


# A projector as wide as a 320-pixel image has columns above 255: a column kept in 8 bits (uint8)
# wraps round there (256 -> 0), and a negative one (off the projector, black) to 256 + column.
WIDE_DEPTH = np.hstack([np.full((24, 40), 6.0), np.full((24, 280), 3.0)])   # disparities 10 and 20 px
COLUMN_IN_8_BITS = "the projector column is kept in 8 bits (uint8): it wraps round above 255 and below 0"


@ex6.check("simulate_structured_light on a projector 320 pixels wide (columns above 255)", points=1)
def simulate_wide(t):
    f, baseline, n_bits = 300.0, 0.2, 8
    what = f"simulate_structured_light(depth of a 320 x 24 image, f={f:g}, baseline={baseline:g}, n_bits={n_bits})"
    got = t.expect_array(t.call("simulate_structured_light", WIDE_DEPTH.copy(), f, baseline, n_bits), what,
                         shape=(n_bits,) + WIDE_DEPTH.shape, dtype=np.uint8)
    column, _, ties = truth.projector_columns(WIDE_DEPTH, f, baseline)
    wrong = np.any(got != truth.simulate_structured_light(WIDE_DEPTH, f, baseline, n_bits), axis=0) & ~ties
    if not wrong.any():
        return passed("every pixel sees the right projector column, columns above 255 too")
    if wrong[(column >= 0) & (column < 256)].any():   # (wrong below 256 too: the other checks judge that)
        return passed(measured("the pixels of projector columns 0 to 255 are wrong too: the other checks judge "
                               "the simulation"))
    wrapped = truth.simulate_structured_light(WIDE_DEPTH, f, baseline, n_bits, column_dtype=np.uint8)
    if not (np.any(got != wrapped, axis=0) & ~ties).any():
        t.fail(measured(f"{what}: {wrong.mean():.0%} of the pixels light the wrong stripes, exactly as if "
                        f"{COLUMN_IN_8_BITS} (column 300 read as 44, column -5 as 251): keep it in a wide integer "
                        "type (np.int64, or np.rint(...).astype(int))."), mistake=COLUMN_IN_8_BITS)
    t.fail(f"{what}: {format_apart(wrong.mean(), 0.0, 2, percent=True)} of the pixels differ from the projector "
           "model; the other checks' 160-pixel images have no column above 255.", hint=PROJECTOR_MODEL)


# A far wall (disparity f b / Z = 0.16 px) is the only place a camera pixel sees the projector's last
# column, width - 1 (u - f b / Z <= width - 1 - f b / Z): a test `column < width - 1` leaves it black.
FAR_WALL = np.hstack([np.full((16, 80), 2.0), np.full((16, 80), 1000.0)])
LAST_COLUMN_DARK = "the projector's last column (width - 1) lights nothing: it is taken as off the projector"


@ex6.check("simulate_structured_light on a far wall: the projector's last column lights it too", points=1)
def simulate_far_wall(t):
    depth, (f, baseline, n_bits) = FAR_WALL, (truth.FOCAL, 1.0, 5)
    width = depth.shape[1]
    what = (f"simulate_structured_light(depth: Z = 2 on the left half, a far wall at Z = 1000 on the right, "
            f"f={f:g}, baseline={baseline:g}, n_bits={n_bits})")
    got = t.expect_array(t.call("simulate_structured_light", depth.copy(), f, baseline, n_bits), what,
                         shape=(n_bits,) + depth.shape, dtype=np.uint8)
    expected = truth.simulate_structured_light(depth, f, baseline, n_bits)
    column, _, ties = truth.projector_columns(depth, f, baseline)
    wrong = np.any(got != expected, axis=0) & ~ties
    if not wrong.any():
        return passed("every lit pixel sees the right projector column, the last one too")
    last = column == width - 1
    if wrong[~last].any():   # (wrong elsewhere too: the other checks judge the simulation)
        return passed(measured("pixels of other projector columns are wrong too: the other checks judge the "
                               "simulation"))
    if not np.any(got[:, wrong] > 0):
        t.fail(measured(f"{what}: the {int(wrong.sum())} pixels that see projector column {width - 1} (the far "
                        f"wall's right edge) are black in every image: {LAST_COLUMN_DARK}. The projector's "
                        f"columns are 0 .. width - 1 ({width - 1} here): a column is off it below 0 or at width "
                        "and past."), mistake=LAST_COLUMN_DARK, hint=PROJECTOR_MODEL)
    t.fail(f"{what}: the {int(wrong.sum())} pixels that see projector column {width - 1} (the far wall's right "
           "edge) are lit with another stripe's code.", hint=PROJECTOR_MODEL)


def _both_bounds(function) -> bool:
    """A column tested against both ends of the projector: ``>= 0`` (or ``> -1``) and ``< width`` (or ``<= w - 1``);
    a test of the depth (the first parameter: ``depth > 0``) is no test of the column."""
    arguments = function.args.posonlyargs + function.args.args
    depth = arguments[0].arg if arguments else ""
    low = high = False
    for n in walk(function):
        if isinstance(n, ast.Compare) and len(n.ops) == 1 and not any(
                isinstance(m, ast.Name) and m.id == depth for m in walk(n)):
            right = n.comparators[0]
            constant = right.value if isinstance(right, ast.Constant) and isinstance(right.value, (int, float)) else None
            if isinstance(n.ops[0], (ast.GtE, ast.Gt)) and constant in (0, -1):
                low = True
            elif isinstance(n.ops[0], (ast.Lt, ast.LtE)) and constant is None:
                high = True
            elif isinstance(n.ops[0], (ast.Lt, ast.LtE)) and isinstance(n.left, ast.Constant) and n.left.value in (0, -1):
                low = True   # 0 <= column
    return low and high


def _assigned_values(function) -> dict:
    """name -> the values the function assigns it."""
    values: dict = {}
    for n in walk(function):
        if isinstance(n, ast.Assign):
            for target in n.targets:
                if isinstance(target, ast.Name):
                    values.setdefault(target.id, []).append(n.value)
    return values


def _stripe_like(node, values, depth=0) -> bool:
    """A value computed through the stripe's scaling (an integer division, a power of two, a shift left), directly
    or through the names it reads."""
    if depth > 4:
        return False
    for n in walk(node):
        if isinstance(n, ast.BinOp) and isinstance(n.op, (ast.FloorDiv, ast.LShift, ast.Pow)):
            return True
        if isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] in ("floor_divide", "left_shift", "power"):
            return True
        if isinstance(n, ast.Name) and n is not node and any(_stripe_like(v, values, depth + 1)
                                                            for v in values.get(n.id, [])):
            return True
    if isinstance(node, ast.Name):
        return any(_stripe_like(v, values, depth + 1) for v in values.get(node.id, []))
    return False


def _codes_the_stripe(function) -> bool | None:
    """Every Gray code written out (``a ^ (a >> 1)``) is taken of a value scaled as a stripe index is
    (``(column * 2**n) // width``); code that computes no Gray code itself (a helper in another function, the
    patterns indexed by column) counts as doing it."""
    values = _assigned_values(function)
    codes = [n for n in walk(function) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.BitXor)
             and isinstance(n.right, ast.BinOp) and isinstance(n.right.op, ast.RShift)]
    return all(_stripe_like(n.left, values) for n in codes) if codes else None


def _bits_in_order(function) -> bool | None:
    """Bits read most significant first, or bits read in a way this reading does not follow (counted as done):
    only a shift by the image's own index (``code >> i`` for ``i`` of ``range(n)``, the least significant first)
    counts as not done."""
    loops = {n.target.id for n in walk(function) if isinstance(n, (ast.For, ast.comprehension))
             and isinstance(n.target, ast.Name) and isinstance(n.iter, ast.Call)
             and _path(n.iter.func) == "range" and len(n.iter.args) == 1}
    shifts = [n for n in walk(function) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.RShift)
              and not (isinstance(n.right, ast.Constant) and n.right.value == 1)]
    return not all(isinstance(n.right, ast.Name) and n.right.id in loops for n in shifts) if shifts else None


BITS_IN_ORDER = wherever_written("reads the bits most significant first", _bits_in_order)


# A column rounded, written any way (np.round, np.rint, round, np.floor(x + 0.5), int(x + 0.5)), from a division
# written any way (`f * b / Z`, `np.divide(f * b, Z, where=valid)`): predicates lean towards "the code does it".
ROUNDS = calls_any("np.round", "np.rint", "round", "np.around", "np.floor", "math.floor") | expr("_ + 0.5")
DIVIDES = expr("_ / _") | calls_any("np.divide", "np.true_divide")
PROJECTOR_MODEL = checklist(
    "", ("pixel (u, v) at depth Z sees projector column round(u - f*baseline/Z)", ROUNDS & DIVIDES),
    ("a pixel with Z <= 0 is black", expr("_ > 0") | expr("_ <= 0") | expr("0 < _")),
    ("a pixel whose column is off the projector (below 0, or at its width and past) is black",
     Predicate("tests the column against both ends", _both_bounds)),
    ("the Gray code shown is that of the column's stripe k = (column * 2**n_bits) // width, not of the column itself",
     wherever_written("codes the stripe", _codes_the_stripe)),
    none_left=look_at(("which bit of the Gray code each image shows (the most significant first)", BITS_IN_ORDER)))


def _divide_keyword(name: str, holds: Callable) -> Callable:
    """A test: an ``np.divide`` call given ``name=`` whose value ``holds`` (a name, computed elsewhere, holds)."""
    def test(function) -> bool:
        return any(isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] == "divide"
                   and any(k.arg == name and (isinstance(k.value, ast.Name) or holds(k.value)) for k in n.keywords)
                   for n in walk(function))
    return test


def _positive_test(node) -> bool:
    return isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], ast.Gt) \
        and isinstance(node.comparators[0], ast.Constant) and node.comparators[0].value == 0


def _zeros(node) -> bool:
    return isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in ("zeros_like", "zeros")


def _divisions(function) -> list:
    return [n for n in walk(function) if isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] == "divide"]


def _masked_divisions(function) -> list[tuple[ast.Subscript, ast.BinOp]]:
    """(target, division) of each division written into an array only where a mask holds, the divisor read
    under the same mask: ``depth[valid] = f * b / d[valid]`` (np.divide's ``where=`` written by hand)."""
    found = []
    for n in walk(function):
        if isinstance(n, ast.Assign) and len(n.targets) == 1 and isinstance(n.targets[0], ast.Subscript) \
                and isinstance(n.targets[0].value, ast.Name):
            mask = ast.dump(n.targets[0].slice)
            for m in walk(n.value):
                if isinstance(m, ast.BinOp) and isinstance(m.op, ast.Div) and any(
                        isinstance(k, ast.Subscript) and ast.dump(k.slice) == mask for k in walk(m.right)):
                    found.append((n.targets[0], m))
    return found


def _masked_division(function) -> bool:
    return bool(_masked_divisions(function))


def _masked_where_positive(function) -> bool:
    """A masked division (:func:`_masked_divisions`) whose mask tests ``> 0``, written in the slice or in the
    name it reads (``valid = np.isfinite(d) & (d > 0)``)."""
    values = _assigned_values(function)
    for target, _ in _masked_divisions(function):
        read = [target.slice] + [v for n in walk(target.slice) if isinstance(n, ast.Name)
                                 for v in values.get(n.id, [])]
        if any(_positive_test(n) for node in read for n in walk(node)):
            return True
    return False


def _masked_into_zeros(function) -> bool:
    """A masked division written into an array made by np.zeros / np.zeros_like."""
    values = _assigned_values(function)
    return any(any(_zeros(v) for v in values.get(target.value.id, [])) for target, _ in _masked_divisions(function))


def _divides_by_the_parameter(function) -> bool:
    """np.divide's divisor reads the first parameter (the disparity), directly or through names assigned from it
    (``d = np.asarray(disparity, float)``); read leniently."""
    parameters = [a.arg for a in function.args.posonlyargs + function.args.args]
    if not parameters:
        return False
    values = _assigned_values(function)

    def reads(node, depth=0) -> bool:
        return depth <= 4 and any(isinstance(n, ast.Name) and (n.id == parameters[0] or any(
            reads(v, depth + 1) for v in values.get(n.id, []))) for n in walk(node))
    return any(len(n.args) >= 2 and reads(n.args[1]) for n in _divisions(function)) \
        or any(reads(division.right) for _, division in _masked_divisions(function))


def _returns_the_division(function) -> bool:
    """A return of np.divide's result or of the array given as its ``out=`` (read leniently: a return of
    anything computed from either), or of the array a masked division fills (read strictly: the array
    itself, or a cast or copy of it -- `np.take_along_axis(depth, ...)` returns other values of it)."""
    filled = {target.value.id for target, _ in _masked_divisions(function)}
    if filled and any(isinstance(n, ast.Return) and _the_array_itself(n.value, filled) for n in walk(function)):
        return True
    held = set()
    for n in _divisions(function):
        held |= {k.value.id for k in n.keywords if k.arg == "out" and isinstance(k.value, ast.Name)}
    for n in walk(function):
        if isinstance(n, ast.Assign) and any(isinstance(m, ast.Call) and m in _divisions(function)
                                             for m in walk(n.value)):
            held |= {t.id for t in n.targets if isinstance(t, ast.Name)}
    return any(isinstance(n, ast.Return) and n.value is not None and any(
        (isinstance(m, ast.Name) and m.id in held) or (isinstance(m, ast.Call) and _path(m.func).endswith("divide"))
        for m in walk(n.value)) for n in walk(function))


def _the_array_itself(node, names) -> bool:
    """``node`` is one of ``names``, or a cast or copy of it (`depth.astype(np.float32)`, `np.asarray(depth)`)."""
    while isinstance(node, ast.Call):
        if isinstance(node.func, ast.Attribute) and node.func.attr in ("astype", "copy", "reshape") \
                and not _path(node.func).startswith(("np.", "numpy.")):
            node = node.func.value
        elif _path(node.func) in ("np.asarray", "np.array", "np.copy", "np.float64", "numpy.asarray") and node.args:
            node = node.args[0]
        else:
            break
    return isinstance(node, ast.Name) and node.id in names


GUARDED_DIVISION_HINT = Hint(
    "np.divide(f * baseline, d, out=np.zeros_like(d), where=d > 0) (NaN > 0 is False)",
    asks=keyword("np.divide", "where") | Predicate("divides only where a mask holds, the divisor read under it",
                                                    _masked_division),
    instead="your code already {found}: " + checklist(
        "", ("its condition is d > 0 (NaN > 0 is False)", Predicate("divides where d > 0",
                                                                    _divide_keyword("where", _positive_test))
             | Predicate("divides where d > 0", _masked_where_positive)),
        ("out starts as zeros", Predicate("gives np.divide zeros as out", _divide_keyword("out", _zeros))
         | Predicate("divides into zeros", _masked_into_zeros)),
        none_left=look_at(("the value divided by (the disparity given, d = x_l - x_r)",
                           Predicate("divides by the disparity given", _divides_by_the_parameter)),
                          ("the array returned", Predicate("returns what np.divide fills", _returns_the_division)))))


measured(truth.SL_PACKED_IN_A_BYTE)   # (named only where the decoded depth is that decoding's, on two scenes)


def sl_decoding_explained(got, images, f, baseline) -> list[str]:
    """The decoding mistakes whose depth map is ``got`` (at 99.5% of the pixels)."""
    got = np.asarray(got, dtype=np.float64)
    with np.errstate(invalid="ignore"):
        got_valid = np.isfinite(got) & (got > 0)
    truth_valid = truth.depth_from_structured_light(images, f, baseline) > 0
    found, few_lit = [], []
    for mistake, wrong in truth.structured_light_mistakes(images, f, baseline).items():
        wrong_valid = wrong > 0
        with np.errstate(invalid="ignore"):
            lit_alike = got_valid & wrong_valid & (np.abs(got - wrong) <= at_precision(
                1e-6 * np.maximum(wrong, 1.0), np.maximum(wrong, 1.0)))
        if (lit_alike | (~got_valid & ~wrong_valid)).mean() < 0.995:
            continue
        # agreeing on pixels both leave undecoded is no evidence: a candidate that decodes too
        # little of what the truth decodes names nothing (a decoder lighting almost no pixel
        # agrees with every mistake whose disparities come out negative) -- unless it is the one
        # candidate agreeing, on a twentieth of the truth's pixels at least, each to its depth
        if (got_valid | wrong_valid).mean() >= 0.5 * truth_valid.mean():
            found.append(mistake)
        elif lit_alike.sum() >= 0.05 * truth_valid.sum():
            few_lit.append(mistake)
    return found or (few_lit if len(few_lit) == 1 else [])


def sl_decoding_on_probe(t: Trial) -> list[str]:
    """The decoding mistakes that explain the student's depth on the other scene, with 5 bits."""
    depth, f, baseline = truth.structured_light_scene("slope")
    images = truth.simulate_structured_light(depth, f, 1.3 * baseline, 5)

    def answer():
        got = t.call("depth_from_structured_light", images, f, 1.3 * baseline)
        return got if isinstance(got, np.ndarray) and got.shape == depth.shape and got.dtype.kind in "iuf" else None

    got = t.probe(f"depth_from_structured_light/{fingerprint(images)}", answer)
    return [] if got is None else sl_decoding_explained(got, images, f, 1.3 * baseline)


def judge_sl_depth(t: Trial, what, got, images, f, baseline, true_depth):
    expected = truth.depth_from_structured_light(images, f, baseline)
    got = t.expect_array(got, what, shape=expected.shape, kind="iuf")
    t.images(what, "depth maps (black = invalid)", true_depth=disparity_picture(true_depth),
             expected=disparity_picture(expected), yours=disparity_picture(got))
    with np.errstate(invalid="ignore"):
        got_valid = np.isfinite(got) & (got > 0)
    exp_valid = expected > 0
    close = got_valid & exp_valid & (np.abs(got - expected) <= at_precision(1e-6 * np.maximum(expected, 1.0),
                                                                               np.maximum(expected, 1.0)))
    agree = np.mean(close | (~got_valid & ~exp_valid))
    if agree >= 0.995:
        judged = exp_valid & (true_depth > 0)
        relative = np.median(np.abs(got[judged] - true_depth[judged]) / true_depth[judged])
        return passed(f"decoded exactly; median depth error {relative:.1%} of the true depth")
    for mistake in sl_decoding_explained(got, images, f, baseline):
        if mistake in sl_decoding_on_probe(t):
            t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    if np.mean(got_valid & ~exp_valid) > 0.005 and np.all(got[~np.any(images > 127, axis=0)] != 0):
        t.fail(f"{what}: pixels that are black in every image are undecodable: their depth must be 0.")
    t.fail(f"{what}: only {format_apart(agree, 0.995, 3, percent=True)} of the pixels agree with the decoded "
           "depth (at least 99.5% needed).",
           hint=STRUCTURED_LIGHT_RECIPE)


def _mid_grey(function) -> bool:
    """A comparison with a constant near mid-grey (100..160 on 0..255, 0.4..0.6 on 0..1)."""
    return any(isinstance(n, ast.Compare) and any(isinstance(c, ast.Constant) and isinstance(c.value, (int, float))
                                                  and (100 <= c.value <= 160 or 0.4 <= c.value <= 0.6)
                                                  for c in [n.left, *n.comparators])
               for n in walk(function))


def _gray_encoding(node) -> bool:
    """``k ^ (k >> 1)``: a Gray code made from binary (a table of the stripes' codes), no decoding of one."""
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitXor)):
        return False
    for one, other in ((node.left, node.right), (node.right, node.left)):
        if isinstance(other, ast.BinOp) and isinstance(other.op, ast.RShift) and ast.dump(other.left) == ast.dump(one):
            return True
    return False


XOR = Predicate("XORs bits", lambda function: any(
    (isinstance(n, (ast.BinOp, ast.AugAssign)) and isinstance(n.op, ast.BitXor) and not _gray_encoding(n))
    # (np.logical_xor called, or its ufunc methods: np.logical_xor.accumulate(bits, axis=0))
    or (isinstance(n, ast.Attribute) and n.attr in ("bitwise_xor", "logical_xor"))
    or (isinstance(n, ast.Name) and n.id in ("bitwise_xor", "logical_xor"))
    for n in walk(function)))
STRIPE_CENTRE = (expr("_ + 0.5") & (expr("2 ** _") | expr("1 << _") | calls("np.power") | calls("np.left_shift"))
                 ).saying("takes the stripe's centre")
def _xor_accumulates(function) -> bool:
    """An XOR whose result feeds the next one (``b = b ^ g[i]``, ``b ^= g``, ``binary[i] = binary[i - 1] ^ bits[i]``,
    ``np.bitwise_xor.accumulate``): each bit XORed with the previous binary bit; read leniently (a name or array
    XORed into itself)."""
    for n in walk(function):
        if isinstance(n, ast.AugAssign) and isinstance(n.op, ast.BitXor):
            return True
        if isinstance(n, ast.Attribute) and n.attr == "accumulate":
            return True
        if isinstance(n, ast.Assign) and isinstance(n.value, ast.BinOp) and isinstance(n.value.op, ast.BitXor):
            written = {_root_name(t) for t in n.targets}
            read = {_root_name(side) for side in (n.value.left, n.value.right)}
            if written & read - {None}:
                return True
        if isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] in ("bitwise_xor", "logical_xor") \
                and any(k.arg == "out" for k in n.keywords):
            return True
    # carried through a name: `b = np.logical_xor(previous, lit[i])` then `previous = b`
    xors = [n for n in walk(function) if isinstance(n, ast.Assign) and (
        (isinstance(n.value, ast.BinOp) and isinstance(n.value.op, ast.BitXor))
        or (isinstance(n.value, ast.Call) and _path(n.value.func).rsplit(".", 1)[-1] in ("bitwise_xor", "logical_xor")))]
    made = {_root_name(t) for n in xors for t in n.targets} - {None}
    carried = made | {_root_name(t) for n in walk(function) if isinstance(n, ast.Assign)
                      and isinstance(n.value, ast.Name) and n.value.id in made for t in n.targets}
    return any(isinstance(r, ast.Name) and r.id in carried for n in xors for r in walk(n.value))


def _root_name(node):
    while isinstance(node, (ast.Subscript, ast.Attribute)):
        node = node.value
    return node.id if isinstance(node, ast.Name) else None


def _bits_assembled_in_order(function) -> bool | None:
    """Bits assembled most significant first, or in a way this reading does not follow (counted as done): only a
    shift left by the image's own index (``bit << i`` for ``i`` of ``range(n)``) counts as not done."""
    loops = {n.target.id for n in walk(function) if isinstance(n, (ast.For, ast.comprehension))
             and isinstance(n.target, ast.Name) and isinstance(n.iter, ast.Call)
             and _path(n.iter.func) == "range" and len(n.iter.args) == 1}
    shifts = [n for n in walk(function) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.LShift)]
    return not all(isinstance(n.right, ast.Name) and n.right.id in loops for n in shifts) if shifts else None


STRUCTURED_LIGHT_RECIPE = checklist(
    "", ("each image is thresholded at mid-grey", Predicate("thresholds at mid-grey", _mid_grey)),
    ("the Gray code is converted to binary (most significant bit first: b0 = g0, b_i = b_(i-1) XOR g_i)", XOR),
    ("the projector column is (k + 0.5) * width / 2**n_bits - 0.5", STRIPE_CENTRE),
    # (or done by their own depth_from_disparity, called on the disparity u - column)
    ("Z = f b / (u - column)", expr("_ * _ / (_ - _)") | expr("_ * _ / _") | expr("_ / (_ - _)")
     | calls("depth_from_disparity")),
    none_left=look_at(
        ("the order the bits are read in (the first image is the most significant bit)",
         wherever_written("reads the first image as the most significant bit", _bits_assembled_in_order)),
        ("what each XOR is taken with (the previous binary bit, not the previous Gray bit)",
         Predicate("XORs with the previous binary bit", _xor_accumulates)),
        ("the pixels left undecoded (black in every image: depth 0)",
         calls("np.any") | calls(".any") | calls("np.all") | calls(".all") | calls("np.max") | calls(".max")
         | calls("np.where") | calls("np.count_nonzero") | calls("np.sum") | calls(".sum")),
        otherwise=""))




# 10 bits too, as a 1024-column projector is coded: stripe indices past 255 (a uint8 accumulator of
# the decoded bits wraps from 9 bits on; 6 to 8 bits do not show it).
SL_BITS = (6, 10)


@ex6.check("depth_from_structured_light decodes the patterns and triangulates", points=3)
def sl_depth(t):
    depth, f, baseline = truth.structured_light_scene("boxes")
    for n_bits in SL_BITS:
        images = truth.simulate_structured_light(depth, f, baseline, n_bits)
        got = t.call("depth_from_structured_light", images, f, baseline)
        try:
            verdict = judge_sl_depth(t, f"depth_from_structured_light({n_bits} images, f={f:g}, "
                                        f"baseline={baseline:g})", got, images, f, baseline, depth)
        except Fail as wrong:
            if n_bits == SL_BITS[0]:
                raise
            t.fail(wrong.message + measured(f" With {SL_BITS[0]} images it decodes exactly; with {n_bits} the stripe "
                                            f"indices k reach {2 ** n_bits - 1}."), wrong.hint, wrong.mistake)
    return verdict


@ex6.check("depth_from_structured_light copes with a dim projector and sensor noise", points=1)
def sl_depth_noisy(t):
    depth, f, baseline = truth.structured_light_scene("boxes")
    images = truth.simulate_structured_light(depth, f, baseline, 7)
    rng = np.random.default_rng(9)
    dim = np.where(images > 0, 205.0, 25.0) * (np.any(images > 0, axis=0)) + rng.normal(0, 12, images.shape)
    dim = np.clip(np.rint(dim), 0, 255).astype(np.uint8)
    got = t.call("depth_from_structured_light", dim, f, baseline)
    return judge_sl_depth(t, "depth_from_structured_light(dim, noisy images)", got, dim, f, baseline, depth)


# On FAR_WALL the decoded disparity u - (stripe centre) is about the stripe's half width either side of the
# true 0.16 px: where it is not positive there is no depth in front, 0 (the docstring's; depth_from_disparity's
# convention), where f b / d is negative or infinite.
NOT_IN_FRONT = ("a pixel whose decoded disparity is not positive is given f b / d (negative or infinite) "
                "where its depth is 0")


@ex6.check("depth_from_structured_light on a far wall: 0 where the decoded disparity is not positive", points=1)
def sl_depth_far_wall(t):
    depth, (f, baseline, n_bits) = FAR_WALL, (truth.FOCAL, 1.0, 5)
    images = truth.simulate_structured_light(depth, f, baseline, n_bits)
    what = (f"depth_from_structured_light({n_bits} images of a scene with a far wall (Z = 1000, disparity "
            f"{f * baseline / 1000:.2f} px), f={f:g}, baseline={baseline:g})")
    got = t.expect_array(t.call("depth_from_structured_light", images, f, baseline), what, shape=depth.shape,
                         kind="iuf")
    expected = truth.depth_from_structured_light(images, f, baseline)
    with np.errstate(invalid="ignore"):
        behind = (expected == 0) & np.any(images > 127, axis=0) & ((got < 0) | np.isinf(got))
    if behind.any():
        row, column = np.argwhere(behind)[0]
        t.fail(f"{what}: {int(behind.sum())} decoded pixels have a depth of {got[row, column]:.4g} or the like "
               f"(pixel ({column}, {row}) among them); their decoded disparity u - (stripe centre) is not positive, "
               "so no point in front is seen there: their depth is 0.", mistake=NOT_IN_FRONT)
    judge_sl_depth(t, what, got, images, f, baseline, depth)
    return passed("decoded exactly, 0 wherever the decoded disparity is not positive")


# ================================================================== the API's conventions
conventions.point_by_point(ex2, "disparity_from_matches", lambda: truth.stereo_points(seed=18, n=6)[3:],
                           rows=(0, 1), described="pts_left, pts_right")
_GREY_ONLY = "the API asks for grey images only"
conventions.not_judged(
    "channels", rectify="judged on grey pairs against the truth, and on a colour pair", block_matching=_GREY_ONLY,
    dp_stereo=_GREY_ONLY,
    depth_from_structured_light="its images are the API's stack of grey patterns, (n_bits, H, W)")
def _rows_triangulation():
    """(P1, P2, pts1, pts2) of the rectified rig, six points."""
    P1, P2, _, pts1, pts2 = truth.stereo_points(seed=172, n=6)
    return P1, P2, pts1, pts2


# (triangulate's one-row form, N = 1, is judged against the truth by the checks above)
conventions.point_by_point(ex1, "triangulate", _rows_triangulation, rows=(2, 3), described="P1, P2, pts1, pts2",
                           one_row=False)
# Whole numbers given as integers (the sheet's own sample point is (1, 1, 2)) answered as the same
# numbers given as floats: an array made like an integer input holds integers only.
def _whole_triangulation():
    """(P1, P2, pts1, pts2) of the rectified rig, the pixel coordinates rounded to whole numbers."""
    P1, P2, _, pts1, pts2 = truth.stereo_points(seed=171, n=6)
    return P1, P2, np.round(pts1), np.round(pts2)


conventions.whole_numbers(ex1, "triangulate", _whole_triangulation, described="P1, P2, pts1, pts2")
conventions.not_judged("integers", disparity_from_matches="d = xl - xr of whole numbers is whole: integers cut nothing",
                       depth_from_disparity="judged on an int16 disparity map (StereoBM's kind) by a check of its own")
