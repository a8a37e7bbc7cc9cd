"""Mutation operators over a reference module's functions (Python's ``ast``; trusted code).

A *mutant* is the reference module with one small, realistic change (or two) in a
function a graded function runs: a sign flipped, two arguments swapped, a ``.T`` added
or missing, degrees used as radians, another axis, another OpenCV flag... Each carries
the edits that make it (so that another process rebuilds it from the source alone) and a
sentence for the student built from the operator and its place in the code, in the
student's terms: API parameter names, the NumPy/OpenCV call involved, "the sine of
`angle_deg`" -- never the reference's code, its private helpers' or local variables' names.

An edit is ``(def name, ordinal, operator, payload)``: the ``ordinal``-th node of
``ast.walk`` over that ``def`` (in the unmutated source), replaced by what the operator
makes of it with ``payload`` (JSON-able). :func:`apply_edits` rebuilds a module's source
from edits; :func:`mutants_of` lists a module's mutants per API function.
"""

from __future__ import annotations

import ast
import bisect
import functools
import itertools
import math
import os
import re
from collections import Counter, deque
from dataclasses import dataclass

from ...loading.parsing import copy_tree, parse, walk


def _parse(source: str):
    """The reference's text (trusted, no size bounds) parsed under the grader's parse lock."""
    return parse(source, max_chars=None, max_statements=None)

# Operators, simplest first (equivalent mutants are named by the simplest), with the words
# their sentences use (a hand-written name sharing none of them is another diagnosis).
OPERATORS = {
    "sign": ("sign", "minus", "negat", "opposite"),
    "add_sub": ("sign", "added", "subtracted", "minus", "plus"),
    "swap_operands": ("order", "swap", "revers", "other way"),
    "swap_args": ("order", "swap", "revers"),
    "transpose": ("transpos",),
    "inverse": ("invers", "transpos"),                 # inv(X) <-> X.T, an inversion dropped
    "degrees": ("degree", "radian"),
    "axis": ("axis", "x and y", "column", "row", "width", "height", "swap"),
    "minmax": ("min", "max", "small", "larg", "high", "low"),
    "flag": ("cv2.", "flag", "interpolat", "border", "method"),
    "bound": ("off by one", "one element", "bound", "- 1", "+ 1"),
    "int_division": ("integer", "truncat", "round"),
    "drop_conversion": ("float", "uint8", "integer", "convert", "conversion", "wrap", "dtype", "clip"),
    "drop_division": ("normalis", "normaliz", "homogeneous", "divid", "division", "scale"),
    "drop_factor": ("denormalis", "normalis", "product", "missing", "undone"),
    "drop_centring": ("mean", "centr", "center", "subtract", "average"),
    "other_name": ("instead of", "in place of", "where"),
    "swap_names": ("exchang", "swap", "order", "other way", "revers"),   # two other_name, crossed
    "reshape_order": ("order", "column by column", "row by row", "reshape", "transpos", "flatten"),
    "single_point": ("single", "1-d", "2-d", "one point", "atleast"),   # np.atleast_2d(x) -> x
    "drop_statement": ("missing", "skipped", "not "),
    "in_place": ("in place", "copy", "caller", "writes into", "written into"),   # named where the change shows
    "stack_order": ("order", "stack", "exchang", "swap", "piece"),   # np.hstack([a, b]) -> np.hstack([b, a])
    "default": ("default", "none", "0", "zero"),      # `x is None` -> `not x`: a legitimate 0 swallowed
    "loop_index": ("position", "index", "loop"),      # for f in fs -> for f in range(len(fs))
    "shift": ("shift", "<<", ">>"),                    # k >> 1 -> k << 1
    "arithmetic": ("divid", "multipl", "element", "*", "@"),   # x * r -> x / r, A @ B -> A * B
    "other_name_line": ("instead of", "in place of", "where"),   # every T2 of a line copied with T1
    "stack_kind": ("stack", "concatenat", "axis"),     # np.stack(pieces) -> np.concatenate(pieces)
    "drop_mask": ("mask", "& 1", "bit"),               # (g >> s) & 1 -> g >> s
    "reshape_transpose": ("reshape", "transpos"),      # X.T -> X.reshape(X.shape[::-1])
    "int_base": ("base", "binary", "decimal", "int("),
    "loop_counter": ("index", "loop", "first", "every"),
    "shape_reversed": ("shape", "width", "height", "channel"),
    "flat_column": ("column", "axis", "shape", "broadcast"),   # (student only) P[:, 3:] -> P[:, 3]
    "count_rows": ("count", "size", "number", "len"),           # (student only) pts.size -> len(pts)
    "unpack_pair": ("unpack", "pair", "tuple"),                 # (student only) X = f(p) -> X, _ = f(p)
    "source_names": ("source", "scaled", "distorted", "before"),
    "tile_repeat": ("tile", "repeat", "order", "pair"),
    "row_kron": ("kron", "row", "pair", "every"),          # (student only) np.kron(a, b) of two point arrays -> one row per pair
    "flip_axis": ("flip", "mirror", "axis", "rows"),          # (student only) np.fliplr(x) <-> np.flipud(x), cv2.flip(x, 0) <-> 1
    "clip_range": ("clip", "range", "stretch", "normali"),    # (student only) cv2.normalize(x, None, 0, 255, NORM_MINMAX) -> np.clip(x, 0, 255)
    "cross_multiply": ("ratio", "divid", "zero", "product"),   # (student only) a / b < r -> a < r * b
    "stack_window": ("window", "axis", "volume", "stack"),      # (student only) uniform_filter(v, size=k) -> size=(1, k, k)
    "per_image": ("image", "stack", "each", "slice"),           # (student only) cv2.blur(v, k) -> each image of v
    "flip_reduction": ("all", "any", "negat", "every", "some"),   # (student only) ~np.all(x) -> np.any(x)
    "square_window": ("window", "block", "square", "strip"),     # (student only) (k, 1) -> (k, k) in a call           # (student only) np.tile(a, n) <-> np.repeat(a, n)
    "math_numpy": ("math", "numpy", "array", "number"),           # (student only) math.pow(x, 2) -> np.power(x, 2)   # (student only) f(xr, yr) -> f(x, y), xr = x * k   # (student only) img.shape[::-1] -> img.shape[1::-1]   # (student only) pts1[0, 1] -> pts1[i, 1] in a loop over i   # (student only) int("".join(bits)) -> int(..., 2)
    # Changes of the student's own code only (:mod:`.repair`: each undoes a slip a student makes).
    "unwrap": ("call", "function"),                    # np.tan(s) -> s: a function applied that does not belong
    "own_values": ("each", "own", "per", "whole"),     # total / weights.max() -> total / weights[..., None]
    "estimator": ("n - 1", "sample", "population", "ddof", "bias", "divid"),   # np.cov(x) -> np.cov(x, bias=True)
    "stack_last": ("axis", "last", "stack", "channel", "first"),   # np.array(planes) -> np.stack(planes, axis=-1)
    "swap_axes": ("transpos", "axes", "channel", "rows", "columns"),   # img.T -> np.swapaxes(img, 0, 1)
    "scale_xy": ("x and y", "depth", "z", "scale", "every coordinate"),   # X * f -> X * np.array([f, f, 1.0])
    "neutral": ("scale", "normalis", "own step", "1", "0"),   # s = r.max() -> s = 1.0 (a scale applied and undone)
    "unused_name": ("never used", "unused", "computes"),   # n = len(src) never read: `1` -> `n` where it belongs
    "twin_test": ("both", "twin", "and", "only one"),   # if whole(tx): -> if whole(tx) and whole(ty):
    "drop_epsilon": ("epsilon", "small", "added", "1e-"),   # X[:, 2:3] + 1e-6 -> X[:, 2:3]
    "scale_inverse": ("invers", "divid", "multipl", "undo", "the other way"),   # H[:2, 2] /= k -> H[:2, 2] *= k
    "twin_values": ("twin", "as", "other axis", "like"),   # y_min, y_max = 0, h - 1 -> as x_min, x_max are made
    "chosen_value": ("chosen", "given", "instead of", "where"),   # z = c[2] if z_avg is None else z_avg; c[2] -> z
    "add_stacked": ("stack", "added", "sum", "rows"),   # A = rows_u + rows_v -> np.vstack([rows_u, rows_v])
    "float_kept": ("integer", "int", "truncat", "float"),   # np.int32(pts) -> pts: fractions cut
    "derived_name": ("instead of", "where"),           # `K[0, 1] * Y` -> `K[0, 1] * yn` beside `K[0, 0] * xn`
    "function": ("function", "call"),                  # np.sin -> np.cos, np.floor -> np.ceil
    "identity": ("identity", "eye", "diagonal", "zero"),   # np.ones((3, 3)) -> np.eye(3): a matrix started filled
    "first_term": ("first", "initial", "start", "cost"),   # energy[0] = 0.0 -> costs[0] (the recurrence's own term)
    "measure_first": ("absolute", "square", "mean", "filter", "difference"),   # |box(l) - box(r)| -> box(|l - r|)
    "dehomogenise": ("homogeneous", "divid", "last coordinate"),   # x[:, :2] -> x[:, :2] / x[:, 2:3]
    "swap_items": ("order", "swap", "exchang"),       # (rows, cols) -> (cols, rows), [0, ty, 1] -> [0, 1, ty]
    "sibling_step": ("missing", "also", "both"),      # xl = xl[:, 0] -> xl, xr = xl[:, 0], xr[:, 0]
    "sibling_argument": ("missing", "other call"),    # warp(w, H) beside warp(img, shift @ H): -> warp(w, shift @ H)
    "dtype": ("dtype", "uint8", "float", "integer"),  # np.zeros(shape) -> np.zeros(shape, dtype=np.uint8)
    "compare": ("compar", "strict", "equal"),         # x > 0 -> x >= 0, x < t -> x > t
    "regroup": ("bracket", "parenthes", "order"),     # a - b + c -> a - (b + c), a / b * c -> a / (b * c)
    "twin_step": ("missing", "also", "both", "only"),  # (x / w, y) -> (x / w, y / w): a step done to one twin only
    "sibling_line": ("as the", "like", "sibling", "others"),   # gM.append(cv2.resize(gM[-1], ...)) -> (cv2.pyrDown(gM[-1]))
    "twin_argument": ("missing", "also", "both", "only"),  # f(A1 @ T1.T, A2) -> f(A1 @ T1.T, A2 @ T2.T)
    "measure": ("square", "absolute", "abs", "**"),   # np.abs(d) <-> d ** 2: the other measure of a difference
    "power_inside": ("square", "mean", "sum", "**"),  # np.mean(d) ** 2 <-> np.mean(d ** 2)
    "slice": ("slice", "column", "entries", "first", "last"),   # l[:, 1:] -> l[:, :2], A[r, 3:7] -> A[r, 4:8]
    "drop_slice": ("first", "only", "all"),          # pts[:8] -> pts: every point, not the first few
    "slice_item": ("slice", "entry", "entries"),       # M[0, 1:] = s -> M[0, 1] = s: one entry written, not a run
    "cross_items": ("exchang", "swap", "end", "other point"),   # (x0, y1), (x1, y0) -> (x0, y0), (x1, y1)
    "row_column": ("row", "column", "[:, "),           # X[2] += dz -> X[:, 2] += dz: a row indexed where a column belongs
    "canvas": ("size", "height", "width", "max", "both"),   # np.zeros((h1, w1 + w2)) -> max(h1, h2) rows
    "loop_all": ("only", "first", "all", "every"),    # for i in range(8) -> range(len(p1)): every point
    "power_spread": ("square", "sum", "**"),          # (x + y) ** 2 -> x ** 2 + y ** 2
    "keep_result": ("result", "returned", "discard", "assign"),   # draw(img, p) -> img = draw(img, p)
    "add_axis": ("axis",),                             # np.delete(X, 2) -> np.delete(X, 2, axis=1)
    "flip_keyword": ("true", "false", "keyword"),     # full_matrices=False -> True
    "float32": ("float32", "dtype", "float"),         # cv2.remap(img, mx, my) -> cv2.remap(img, np.float32(mx), ...)
    "python_numbers": ("int", "numeric", "tuple", "type"),
    "size_given": ("size", "frame", "crop", "default"),
    "middle_axis": ("shape", "axis", "(n, 1"),
    "widen": ("uint8", "overflow", "wrap", "float"),
    "bracket": ("bracket", "parenthes", "factor", "term"),
    "x_difference": ("x", "distance", "difference", "disparit"),
    "colour_axis": ("channel", "grey", "gray", "axis"),
    "drop_w": ("homogeneous", "(n, 3)", "(n, 2)", "column"),
    "power_xor": ("power", "square", "xor", "^"),   # r ^ 2 (a bitwise XOR in Python) -> r ** 2
    "einsum": ("einsum", "index", "summed", "axes", "transpos"),   # 'ni,nj->ij' -> 'ni,nj->nij'
    "like_input": ("like", "shape", "channel", "dtype"),   # np.zeros((h, w)) -> np.zeros_like(image)
    "append_extend": ("append", "extend", "list"),     # rhs.append([x, y]) -> rhs.extend([x, y])
    "last_row": ("row", "0, 0, 1", "homogeneous"),    # np.vstack([A, np.ones(3)]) -> np.vstack([A, [0.0, 0.0, 1.0]])
    "store_name": ("stored", "instead of", "bound", "loop"),   # n = ... -> needed = ... (the loop's bound)
    "map_whole": ("map", "each", "whole", "pair"),    # map(f, X, fs) -> map(lambda each_: f(X, each_), fs)
    "index_step": ("index", "one place", "off by one", "column", "row"),   # out[y, x] = d -> out[y, x - 1] = d
    "unflip": ("flip", "upside", "mirror", "far end", "- 1 -"),   # (x, h - 1 - y) -> (x, y)
    "identity": ("identity", "eye", "diagonal", "1 -"),   # (1 - R) @ c -> (np.eye(len(R)) - R) @ c
    "half_pixel": ("half", "0.5", "pixel", "offset", "centre"),   # (x + 0.5) -> x: a half-pixel convention   # f(x1, x2), x1 homogeneous -> f(x1[:, :2], x2)   # f(img, channel_axis=-1) -> channel_axis=-1 if img.ndim == 3 else None   # np.linalg.norm(l - r, axis=1) -> (l - r)[:, 0]
    "perspective_warp": ("warp", "perspective", "affine", "homograph"),   # cv2.warpAffine(i, H[:2], s) -> cv2.warpPerspective(i, H, s)   # p2 * r2 + 2 * x * x -> p2 * (r2 + 2 * x * x)   # diff ** 2 -> diff.astype(np.float64) ** 2 (uint8 wraps)   # cv2.convertPointsToHomogeneous(p) -> ...(p)[:, 0]: (N, 1, 3) -> (N, 3)   # warp(moving, H) -> warp(moving, H, dsize=(w, h))   # tuple(rng.integers(0, 256, 3)) -> tuple(map(int, ...))
    "accumulate": ("accumulat", "+=", "sum", "add"),   # total = x -> total += x in a loop, and back
    "magnitude": ("abs", "magnitude", "absolute"),   # np.argmin(values) -> np.argmin(np.abs(values))
    "fill_inf": ("inf", "zero", "start", "unfilled"),
    "jump_size": ("jump", "abs", "difference", "penalty"),   # s * (a != b) -> s * np.abs(a - b): a jump's size
    "len_axis": ("len", "axis", "column", "shape"),   # len(patterns) -> patterns.shape[1]: len counts the rows   # costs = np.zeros(s) -> np.full(s, np.inf) before an argmin
    "carry": ("each", "again", "running", "restart"),   # out = draw(image.copy(), l) -> out = draw(out, l) in a loop
    "summary": ("mean", "centroid", "average", "one point"),   # dst[0] -> dst_mean: one item where the mean belongs
    "reduced": ("mean", "average", "one value", "every point"),   # z = X[:, 2] -> X[:, 2].mean(): a column, its mean meant
    "per_item": ("first", "each", "every", "once", "loop"),   # a scale made once from the first item, used for each
    "grid_axis": ("row", "column", "axis", "width", "height"),   # np.arange(h)[:, None] -> np.arange(w)[None, :]
    "mirror": ("copied", "copy", "instead of", "other image"),   # grey2 = f(img1) -> f(img2): its twin line's
    "chain_order": ("order", "product", "exchang", "swap"),   # K2.T @ K1 @ F -> K2.T @ F @ K1
    "initial": ("initial", "start", "inf", "infinity", "zero"),   # best = np.zeros(s) -> np.full(s, np.inf)
    "reshape_back": ("reshape", "transpos", "order"),   # x.reshape(2, -1).T -> x.reshape(-1, 2)
    "astype_float": ("float", "uint8", "integer", "dtype"),   # d.astype(np.uint8) -> d.astype(np.float64)
    "divide_last": ("floor", "//", "order", "first"),    # c // w * 2 ** n -> c * 2 ** n // w
    "unused": ("parameter", "unused", "ignored", "instead of"),   # X[:, 2].mean() -> z0, z0 never read
    "drop_colour": ("colour", "color", "rgb", "bgr", "conversion"),   # cv2.cvtColor(img, COLOR_BGR2RGB) -> img
    "zero_based": ("1", "one", "start", "index", "off by one"),   # np.arange(1, w + 1) -> np.arange(w)
    "zero_entry": ("entry", "0", "zero", "translation", "term"),   # [1, s, -s * h / 2] -> [1, s, 0]
    "midrange": ("mean", "average", "midrange", "middle"),   # (Z.min() + Z.max()) / 2 -> np.mean(Z)
    "exchange": ("exchang", "swap", "other way", "revers"),   # n.d < 0.75 * m.d -> m.d < 0.75 * n.d
    "drop_argument": ("argument", "default", "given", "remov"),   # _warp(img, M, size) -> _warp(img, M)
    "convert_if": ("grey", "gray", "channel", "already", "ndim"),   # cvtColor(f, BGR2GRAY) -> ... if f.ndim == 3 else f
    "negate": ("not", "condition", "invert", "opposite"),   # if x > t: -> if not x > t:, not m -> m
    "logic": ("and", "or", "&", "|"),
    "from_end": ("end", "last", "-1"),                # Vt[len(A) - 1] -> Vt[-1]
    "frame_cross": ("cross", "orthogonal", "axis"),   # e3 = mean / |mean| -> np.cross(e1, e2)
    "colour_scale": ("255", "white", "colour", "color", "scale"),   # cv2.line(grey, p, q, 1.0) -> 255: a [0, 1] colour   # rows = [white] then rows.append(...) -> rows = []
    "whole_vector": ("homogeneous", "divid", "third"),   # np.append(e[:2], 1.0) -> e / e[2]
    "quadrant": ("arctan2", "quadrant", "atan2"),   # np.arctan(b / a) -> np.arctan2(b, a)
    "swap_both": ("swap", "exchang", "both", "also"),   # P1, P2 = P2, P1 -> the points exchanged with them
    "drop_flag": ("flag", "cv2.", "remov", "|"),          # INTER_LINEAR | WARP_INVERSE_MAP -> INTER_LINEAR                 # m1 & m2 -> m1 | m2, a and b -> a or b
    "literal": ("argument", "value", "flag"),         # cv2.computeCorrespondEpilines(p, 2, F) -> (p, 1, F)
    "boolean_mask": ("mask", "boolean", "index"),   # pts[mask.ravel()] -> pts[mask.ravel().astype(bool)]
    "negative_index": ("negative", "index", "abs", "wrap"),   # ramp[i - j] -> ramp[np.abs(i - j)]
    "part": ("column", "part", "whole", "component"),   # np.linalg.norm(X, axis=1) -> X[:, 2] (seen elsewhere)
    "translation": ("translation", "homogeneous", "column", "1"),   # pts @ M[:, :3].T -> ... + M[:, 3]
    "true_division": ("division", "floor", "//", "integer"),   # f * b // Z -> f * b / Z
    "factor_two": ("half", "twice", "factor", "2"),       # a * pi / 360 -> a * pi / 180
    "by_last": ("homogeneous", "third", "last", "norm"),   # h / np.linalg.norm(h, ...) -> h / h[..., -1:]
    "ufunc_out": ("out", "where", "uninitialised"),       # np.divide(a, b, where=m) -> (..., out=np.zeros(...))
    "empty_slice": ("slice", "empty", "0"),                # right[:, :-d] -> right[:, :right.shape[1] - d]
    "divided_by_w": ("homogeneous", "divid", "third", "w"),   # (H @ grid)[0] -> (H @ grid)[0] / (H @ grid)[2]
    "drop_keyword": ("argument", "keyword", "remov"),     # cv2.undistortPoints(p, K, None, P=K) -> (p, K, None)
    "method_given": ("method", "flag", "default", "cv2."),   # cv2.findFundamentalMat(p1, p2) -> (..., method=cv2.FM_8POINT)
    "reverse_back": ("revers", "back", "turn", "far end"),   # acc(x[:, ::-1], axis=1) -> acc(...)[:, ::-1]
    "drop_reversal": ("revers", "order", "[::-1]"),    # tuple(pattern_size)[::-1] -> tuple(pattern_size)
    "loop_order": ("revers", "order", "last", "first"),  # for b in bands[:-1] -> for b in reversed(bands[:-1])
    "matrix_applied": ("matrix", "applied", "@", "map"),   # t = dst[0] - src[0] -> dst[0] - L @ src[0]
    "series_powers": ("power", "square", "r^2", "**"),   # k1 * r + k2 * r ** 2 -> k1 * r ** 2 + k2 * r ** 4
    "counted": ("count", "len", "fixed", "number"),   # for k in range(3) -> range(len(images))
    "default_written": ("default", "fixed", "parameter", "ignored"),   # _pyramid(a, 4) -> _pyramid(a, levels)
    "crossed": ("exchang", "swap", "other way", "x and y"),   # beta * cy + a * cx -> beta * cx + a * cy
    "fraction": ("ratio", "fraction", "share", "count"),
    "loop_item": ("loop", "index", "each", "last", "first"),
    "conversion_inverted": ("degree", "radian", "180", "pi"),   # a * 180 / np.pi -> a * np.pi / 180   # d[-1] in a loop over x beside d[x - 1] -> d[x]   # w = best.sum() -> best.mean(): a count where a share belongs
    "homogeneous_one": ("homogeneous", "1", "third", "depth"),
    "moved_term": ("x", "y", "offset", "other coordinate", "twin"),   # (q[0], q[1] + w1) -> (q[0] + w1, q[1])   # np.column_stack([x, y, Z]) -> [x, y, np.ones_like(Z)]
    "neutral_argument": ("scale", "1", "argument", "zoom"),   # cv2.getRotationMatrix2D(c, a, zoom) -> (c, a, 1.0)
    "factor_transposed": ("transpos", "product", "factor"),   # (K2 @ F).T -> K2.T @ F
    "twin_factor": ("missing", "also", "both", "factor"),   # P1 = K @ A; P2 = B -> P2 = K @ B
    "select_mask": ("mask", "inlier", "selected", "kept", "all"),   # fit(src, dst) -> fit(src[best], dst[best]): every point where the kept ones belong
    "factor_pair": ("missing", "also", "both", "sign", "factor"),   # K = K @ D -> K, R = K @ D, D @ R: a factor's fix made to one of the pair
    "stride": ("row", "2 *", "twice", "index"),           # A[i] = ...; A[i + 1] = ... -> A[2 * i], A[2 * i + 1]
    "keep_axis": ("column", "axis", "broadcast"),         # pts[:, :2] / pts[:, 2] -> pts[:, 2:3]
    "column_order": ("row", "column", "x", "y", "order"),
    "rounding": ("round", "truncat", "clip", "wrap", "uint8"),
    "grey": ("grey", "gray", "channel", "colour", "color"),
    "rank": ("singular", "rank", "constraint", "diag"),
    "guard": ("invalid", "zero", "where", "nan", "inf", "divid"),
    "squared_bound": ("square", "radius", "**", "root"),   # dx ** 2 + dy ** 2 <= r -> <= r ** 2 (and back)
    "exact_constant": ("pi", "constant", "round", "digits"),   # 3.14 -> np.pi, 57.3 -> 180 / np.pi
    "translation_scaled": ("scale", "translation", "order", "centr"),   # [[s, 0, -c]] <-> [[s, 0, -s * c]]
    "lower_bound": ("bound", "negative", ">= 0", "below 0", "left"),   # cols < w -> (cols >= 0) & (cols < w)
    "whole_shape": ("shape", "length", "len", "dimension"),   # np.zeros(len(d)) -> np.zeros(np.shape(d))
    "move_factor": ("square root", "sqrt", "factor", "inside", "outside"),   # np.sqrt(a * u) -> a * np.sqrt(u)
    "convert_first": ("convert", "uint8", "wrap", "before"),   # (a - b).astype(float) -> a.astype(float) - b
    "precedence": ("bracket", "parenthes", "precedence", "&", "|"),   # d > 0 & m -> (d > 0) & m
    "drop_term": ("term", "added", "subtracted", "extra"),   # Z + f -> Z: a term that does not belong
    "one_of_two": ("larger", "smaller", "max", "min", "both", "either"),   # max(h1, h2) -> h1: one value, not the larger
    "size_written": ("size", "fixed", "640", "input's", "shape"),   # (640, 480) -> (image.shape[1], image.shape[0])
    "type_widened": ("type", "isinstance", "int", "float", "numpy"),   # isinstance(z, float) -> (int, float, np.number)
    "to_degrees": ("degree", "radian"),   # np.arctan2(b, a) compared with 45 -> np.degrees(np.arctan2(b, a))
    "perpendicular": ("perpendicular", "normal", "direction", "90", "quarter turn"),   # (a, b) -> (-b, a)
    "key_order": ("order", "insert", "key", "sorted"),   # d.values() -> [d[k] for k in sorted(d)]
    "focal_left_out": ("focal", "principal point", "normalis", "k^-1", "inv(k"),   # x - K[0, 2] -> (x - K[0, 2]) / K[0, 0]
    "other_result": ("result", "return", "mask", "index"),   # cv2.findHomography(...)[1] -> [0]   # f * b / d -> only where d > 0   # U @ np.diag(S) @ Vt -> np.diag([S[0], S[1], 0])
    "denormalise": ("normalis", "undo", "undone", "transform"),   # return F -> return T2.T @ F @ T1   # cv2.cornerSubPix(image, ...) -> its grey view   # int(x) -> int(round(x)), astype(np.uint8) -> clip   # np.argwhere(mask) -> np.argwhere(mask)[:, ::-1]
    "simultaneous": ("together", "old value", "updated", "before"),   # x = f(x, y); y = g(x, y) -> x, y = ...
    "move": ("before", "after", "order", "too early", "too late"),   # K = K / K[2, 2] moved after t = ... K ...
    "indent": ("inside", "loop", "if", "indent"),        # best = inliers moved into `if count > best_count:`
    "dedent": ("after", "loop", "outside", "indent"),    # a return inside a loop moved after it
    "hoist": ("before", "loop", "once", "each turn", "anew"),   # for i: out = np.zeros(n); out[i] = ... -> out first
    "keep_parameter": ("overwrit", "each turn", "previous turn", "parameter"),   # f0 = f0 * d / z0 in a loop
    "undecomposed": ("decompos", "rebuilt", "singular", "svd"),   # return U @ diag(s') @ Vt -> return E
    "slice_order": ("revers", "order", "slice", "last"),   # shape[::-1][:2] -> shape[:2][::-1]
    "map_term": ("mapped", "linear part", "centroid", "transform"),   # dst_mean - src_mean -> dst_mean - L @ src_mean
    "centre_translation": ("centre", "center", "translation", "-R"),   # tvec = C -> tvec = -R @ C
    "aligned": (),            # (the student's code only) a statement made its counterpart's: see aligned.py
    "add_step": ("missing", "step", "add"),   # (the student's code only) a counterpart's step added
    "extra_step": ("extra", "step", "remov"),   # (the student's code only) a rebinding no counterpart has, taken out
}
_MOVES = {"simultaneous", "move", "indent", "dedent", "hoist"}   # changes of where statements are
RANK = {name: index for index, name in enumerate(OPERATORS)}

_NON_COMMUTATIVE = {ast.Sub: "subtraction", ast.Div: "division", ast.MatMult: "matrix product",
                    ast.FloorDiv: "division"}
_ANGLE_CONVERSIONS = {"np.deg2rad": "radians", "np.radians": "radians", "math.radians": "radians",
                      "np.rad2deg": "degrees", "np.degrees": "degrees", "math.degrees": "degrees"}
_OPPOSITES = {"argmin": "argmax", "argmax": "argmin", "min": "max", "max": "min", "amin": "amax",
              "amax": "amin", "minimum": "maximum", "maximum": "minimum", "nanargmin": "nanargmax",
              "nanargmax": "nanargmin", "nanmin": "nanmax", "nanmax": "nanmin", "all": "any", "any": "all"}
# the array methods among them (`mask.any(axis=0)`, `d.argmax(axis=2)`), told on a name's array
_ARRAY_METHODS = {"all", "any", "min", "max", "argmin", "argmax"}
# OpenCV constants that stand for one another (a student picks another member of the family).
_FLAG_FAMILIES = [
    ("INTER_NEAREST", "INTER_LINEAR", "INTER_CUBIC", "INTER_AREA"),
    ("BORDER_CONSTANT", "BORDER_REPLICATE", "BORDER_REFLECT", "BORDER_REFLECT_101"),
    ("RANSAC", "LMEDS", "RHO"),
    ("FM_7POINT", "FM_8POINT", "FM_RANSAC", "FM_LMEDS"),
    ("NORM_L1", "NORM_L2", "NORM_HAMMING", "NORM_INF", "NORM_L2SQR"),
    ("TM_SQDIFF", "TM_SQDIFF_NORMED", "TM_CCORR", "TM_CCORR_NORMED", "TM_CCOEFF", "TM_CCOEFF_NORMED"),
    ("COLOR_BGR2GRAY", "COLOR_RGB2GRAY"),
    ("COLOR_BGR2RGB", "COLOR_RGB2BGR", "COLOR_BGR2HSV"),
    ("CV_32F", "CV_64F", "CV_8U"),
    ("THRESH_BINARY", "THRESH_BINARY_INV"),
    ("SOLVEPNP_ITERATIVE", "SOLVEPNP_EPNP", "SOLVEPNP_SQPNP"),
    # (calibrateCamera's CALIB_ options are independent restrictions, not alternatives of one choice: one given
    # where none belongs is taken out -- drop_keyword --, never swapped for another that mends by the scene's luck)
    ("DECOMP_LU", "DECOMP_SVD", "DECOMP_NORMAL", "DECOMP_QR", "DECOMP_CHOLESKY", "DECOMP_EIG"),
    ("STEREO_SGBM_MODE_SGBM", "STEREO_SGBM_MODE_HH", "STEREO_SGBM_MODE_SGBM_3WAY"),
    ("CALIB_ZERO_DISPARITY", "CALIB_USE_INTRINSIC_GUESS", "CALIB_FIX_INTRINSIC"),
    ("COLOR_BGR2LAB", "COLOR_BGR2YCrCb"),
]
_ORDERED = {"reshape": "reshaped", "ravel": "flattened", "flatten": "flattened"}   # order="C" unless told
_FLAG_FAMILY = {name: family for family in _FLAG_FAMILIES for name in family}
_OTHER_NAMES_PER_SITE = 4
_NEAREST_LOCALS = 16   # the student's code: the locals last assigned before a use that may replace it
_MAX_PHRASE = 110


@dataclass(frozen=True)
class Mutant:
    """One mutant of the reference module, seen from the graded function ``function``.

    operator : the operator id (a key of :data:`OPERATORS`).
    function : the API function whose mistake it models.
    where : the ``def`` the edit changes (``function`` itself or a function it calls).
    line : the edit's line in the reference (for authors; never shown to students).
    edits : ``((def name, ordinal, operator, payload), ...)``, see :func:`apply_edits`.
    sentence : what it says to the student, e.g. "in `rotation_matrix`, the sine of
        `angle_deg` has the wrong sign".
    """

    operator: str
    function: str
    where: str
    line: int
    edits: tuple
    sentence: str
    place: str = ""   # the sentence's start that says where ("in `rotate` (in `rotation_matrix`, ...), ")

    @property
    def key(self) -> str:
        """A stable id: the edits."""
        return ";".join(f"{d}:{o}:{op}:{p}" for d, o, op, p in self.edits)

    @property
    def rank(self) -> tuple:
        return (len(self.edits), max(RANK[e[2]] for e in self.edits), len(self.sentence))

    def combined(self, other: "Mutant") -> "Mutant":
        """This mutant and ``other`` at once (two mistakes); two names used in each other's place
        are told as exchanged."""
        crossed = [re.fullmatch(r"(.+?) is used where (.+) belongs", m.sentence[len(m.place):]) for m in (self, other)]
        if self.operator == other.operator == "other_name" and all(crossed) and self.place == other.place \
                and crossed[0].groups() == crossed[1].groups()[::-1]:
            first, second = crossed[0].groups()
            return Mutant("swap_names", self.function, self.where, self.line, self.edits + other.edits,
                          f"{self.place}{second} and {first} are exchanged (each is used where the other belongs)",
                          self.place)
        said = other.sentence[len(other.place):] if other.place and other.place == self.place else other.sentence
        alike = [re.fullmatch(r"(`[^`]+`) (is not converted .+)", m.sentence[len(m.place):]) for m in (self, other)]
        if self.operator == other.operator == "drop_conversion" and all(alike) and self.place == other.place \
                and alike[0].group(2) == alike[1].group(2):   # one slip made twice: told once
            said = alike[0].group(2).replace("is not", "are not", 1)
            return Mutant(self.operator, self.function, self.where, self.line, self.edits + other.edits,
                          f"{self.place}{alike[0].group(1)} and {alike[1].group(1)} {said}", self.place)
        return Mutant(f"{self.operator}+{other.operator}", self.function, self.where, self.line,
                      self.edits + other.edits, f"{self.sentence}; and {said}", self.place)


# ------------------------------------------------------------------ rebuilding a mutant
def _defs(tree: ast.Module) -> dict[str, ast.FunctionDef]:
    return {node.name: node for node in tree.body if isinstance(node, ast.FunctionDef)}


def _parents(root: ast.AST) -> dict[int, tuple[ast.AST, str, int | None]]:
    """id(child) -> (parent, field, index in the field's list or None)."""
    parents = {}
    for parent in walk(root):
        for field, value in ast.iter_fields(parent):
            if isinstance(value, list):
                for index, item in enumerate(value):
                    if isinstance(item, ast.AST):
                        parents[id(item)] = (parent, field, index)
            elif isinstance(value, ast.AST):
                parents[id(value)] = (parent, field, None)
    return parents


def apply_edits(source: str, edits) -> str:
    """The module ``source`` with ``edits`` made (all located in the unmutated tree first).

    Raises
    ------
    ValueError
        When an edit does not apply (a stale ordinal, overlapping edits).
    """
    tree = _parse(source)
    defs = _defs(tree)
    located = []
    for def_name, ordinal, operator, payload in edits:
        if def_name not in defs:
            raise ValueError(f"no def {def_name}")
        nodes = list(walk(defs[def_name]))
        if not 0 <= ordinal < len(nodes):
            raise ValueError(f"no node {ordinal} in {def_name}")
        located.append((nodes[ordinal], operator, payload))
    targets = [id(node) for node, _, _ in located]
    for node, _, _ in located:  # an edit inside another's node would be lost
        inner = {id(n) for n in walk(node)} - {id(node)}
        if inner & set(targets):
            raise ValueError("overlapping edits")
    parents = _parents(tree)
    for node, operator, payload in located:
        _replace(parents, node, _MAKE[operator](node, payload))
    return ast.unparse(ast.fix_missing_locations(tree))


def mutated_defs(tree: ast.Module, edits, source: str | None = None) -> ast.Module:
    """Only the ``def``s ``edits`` change, mutated, as a module (``tree``, the reference's, is left
    as it is): executed over a copy of the reference module's namespace, they make the mutant.
    With the module's ``source``, each def is parsed again from its own lines (the same nodes in
    the same order, ten times faster than copying the tree).

    Raises ValueError as :func:`apply_edits` does."""
    defs = _defs(tree)
    lines = source.splitlines(keepends=True) if source is not None else None
    changed, wanted = {}, {}
    for def_name, ordinal, _, _ in edits:
        if def_name not in defs:
            raise ValueError(f"no def {def_name}")
        if def_name not in changed:
            fn = defs[def_name]
            if lines is not None:
                first = min([fn.lineno] + [d.lineno for d in fn.decorator_list])
                changed[def_name] = _parse("".join(lines[first - 1:fn.end_lineno])).body[0]
            else:
                changed[def_name] = copy_tree(fn)
        wanted.setdefault(def_name, set()).add(ordinal)
    # (each def walked once, only as far as its last edit: the located nodes, their places and the
    # locations a new node there inherits -- a mutant is built thousands of times in a grading)
    found = {name: _located(changed[name], ordinals) for name, ordinals in wanted.items()}
    located = []
    for def_name, ordinal, operator, payload in edits:
        if ordinal not in found[def_name]:
            raise ValueError(f"no node {ordinal} in {def_name}")
        located.append((found[def_name][ordinal], operator, payload))
    if len(located) > 1:
        targets = {id(place[0]) for place, _, _ in located}
        for (node, *_), _, _ in located:
            if ({id(n) for n in walk(node)} - {id(node)}) & targets:
                raise ValueError("overlapping edits")
    for (node, parent, field, index, inherited), operator, payload in located:
        if parent is None:   # (the def itself is no place of a change)
            continue
        new = _MAKE[operator](node, payload)
        _replace({id(node): (parent, field, index)}, node, new)
        _fix_locations(new, inherited)
    return ast.Module(list(changed.values()), [])


_LOCATION = ("lineno", "col_offset", "end_lineno", "end_col_offset")


def _located(root: ast.AST, ordinals: set) -> dict:
    """ordinal -> (node, parent, field, index, inherited) for the nodes at ``ordinals`` in
    ``walk(root)``'s order (breadth first, fields in order): where each is held, and the
    location :func:`ast.fix_missing_locations` would give a new node put there (the nearest
    enclosing node's, attribute by attribute). The walk stops at the last ordinal asked."""
    last = max(ordinals)
    todo = deque([(root, None, None, None)])   # (node, its parent's entry, field, index)
    found, count = {}, 0
    while todo and count <= last:
        entry = todo.popleft()
        node = entry[0]
        if count in ordinals:
            found[count] = entry
        count += 1
        for name, value in ast.iter_fields(node):
            if isinstance(value, ast.AST):
                todo.append((value, entry, name, None))
            elif isinstance(value, list):
                todo.extend((item, entry, name, position) for position, item in enumerate(value)
                            if isinstance(item, ast.AST))
    return {ordinal: (node, None if above is None else above[0], field, index, _inherited(above))
            for ordinal, (node, above, field, index) in found.items()}


def _inherited(entry) -> tuple:
    """The location :func:`ast.fix_missing_locations` hands down from ``entry`` (a node's entry in
    :func:`_located`'s walk, its ancestors' chained) to a child missing one."""
    chain = []
    while entry is not None:
        chain.append(entry[0])
        entry = entry[1]
    location = (1, 0, 1, 0)
    for node in reversed(chain):
        location = _own_location(node, location)
    return location


def _own_location(node: ast.AST, inherited: tuple) -> tuple:
    """The location ``node`` passes on to children missing one (as :func:`ast.fix_missing_locations`)."""
    if not node._attributes:
        return inherited
    return tuple(inherited[k] if name not in node._attributes or getattr(node, name, None) is None
                 else getattr(node, name) for k, name in enumerate(_LOCATION))


def _fix_locations(node: ast.AST, inherited: tuple) -> None:
    """:func:`ast.fix_missing_locations` for a subtree put where ``inherited`` is the location around it."""
    todo = [(node, inherited)]
    while todo:
        node, inherited = todo.pop()
        for k, name in enumerate(_LOCATION):
            if name in node._attributes and getattr(node, name, None) is None:
                setattr(node, name, inherited[k])
        own = _own_location(node, inherited)
        todo.extend((child, own) for child in ast.iter_child_nodes(node))


def _replace(parents, node, new) -> None:
    parent, field, index = parents[id(node)]
    if index is None:
        setattr(parent, field, new)
    else:
        getattr(parent, field)[index] = new


def _dotted(node) -> str:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        inner = _dotted(node.value)
        return f"{inner}.{node.attr}" if inner else ""
    return ""


def _name(dotted: str) -> ast.expr:
    parts = dotted.split(".")
    node: ast.expr = ast.Name(parts[0], ast.Load())
    for part in parts[1:]:
        node = ast.Attribute(node, part, ast.Load())
    return node


def _call(dotted: str, *args) -> ast.Call:
    return ast.Call(_name(dotted), list(args), [])


# How each operator changes its node (payload from the generator).
def _make_sign(node, payload):
    if payload == "all":   # [-u, -v] -> [u, v]: one sign slip written into every item
        return type(node)([copy_tree(item.operand) for item in node.elts], node.ctx)
    if payload == "remove":
        return copy_tree(node.operand)
    return ast.UnaryOp(ast.USub(), copy_tree(node))


def _make_add_sub(node, payload):
    new = copy_tree(node)
    new.op = ast.Sub() if isinstance(node.op, ast.Add) else ast.Add()
    return new


def _make_swap_operands(node, payload):
    return ast.BinOp(copy_tree(node.right), node.op, copy_tree(node.left))


def _make_swap_args(node, payload):
    new = copy_tree(node)
    i, j = payload
    new.args[i], new.args[j] = new.args[j], new.args[i]
    return new


def _make_transpose(node, payload):
    if payload == "for_reshape":   # x.reshape(w, h) -> x.T
        return ast.Attribute(copy_tree(node.func.value), "T", ast.Load())
    if payload == "before_reshape":   # x.reshape(-1, 2) -> x.T.reshape(-1, 2)
        new = copy_tree(node)
        new.func.value = ast.Attribute(new.func.value, "T", ast.Load())
        return new
    if payload == "cv_points":   # cv2.f(a, b, pts1, pts2) -> cv2.f(a, b, pts1.T, pts2.T)
        new = copy_tree(node)
        for p in _CV_POINT_SETS[_dotted(node.func).rsplit(".", 1)[-1]]:
            new.args[p] = ast.Attribute(new.args[p], "T", ast.Load())
        return new
    if payload == "remove":
        return copy_tree(node.value if isinstance(node, ast.Attribute) else node.args[0])
    if payload == "literal":
        new = copy_tree(node)
        rows = [row.elts for row in new.args[0].elts]
        new.args[0].elts = [ast.List([row[j] for row in rows], ast.Load()) for j in range(len(rows[0]))]
        return new
    return ast.Attribute(copy_tree(node), "T", ast.Load())


def _make_degrees(node, payload):
    if payload == "remove":
        return copy_tree(node.args[0])
    return _call(payload, copy_tree(node))


def _make_axis(node, payload):
    if payload == "swap_index":  # x[:, k] <-> x[k, :]: a row for a column
        new = copy_tree(node)
        new.slice.elts.reverse()
        return new
    if isinstance(payload, list):   # another index: [":", -1] for x[-1]; ["0:1"] a slice for x[:, 1:2]
        new = copy_tree(node)
        parts = [_index_part(p) for p in payload]
        new.slice = parts[0] if len(parts) == 1 else ast.Tuple(parts, ast.Load())
        return new
    return _signed(payload) if isinstance(payload, int) and not isinstance(payload, bool) else ast.Constant(payload)


def _index_part(spec):
    """":" -> a whole slice, "a:b" -> a constant slice, an int -> that index."""
    if spec == ":":
        return ast.Slice()
    if isinstance(spec, str):
        lower, upper = (ast.Constant(int(b)) if b else None for b in spec.split(":"))
        return ast.Slice(lower, upper)
    return ast.Constant(spec) if spec >= 0 else ast.UnaryOp(ast.USub(), ast.Constant(-spec))


def _make_inverse(node, payload):
    if payload in ("swap_sides", "undone_never"):   # inv(A) @ M @ B -> A @ M @ inv(B), or -> M
        first, middle, last = _chain_of_three(node)
        if payload == "undone_never":
            return copy_tree(middle)
        toggled = [copy_tree(f.args[0]) if _is_inverse(f) else _call("np.linalg.inv", copy_tree(f))
                   for f in (first, last)]
        return ast.BinOp(ast.BinOp(toggled[0], ast.MatMult(), copy_tree(middle)), ast.MatMult(), toggled[1])
    if payload == "entrywise":  # X ** -1, 1 / X -> np.linalg.inv(X)
        return _call("np.linalg.inv", copy_tree(_reciprocal_of(node)))
    if payload == "wrap":       # X -> np.linalg.inv(X) (the student's code: an inversion missing)
        return _call("np.linalg.inv", copy_tree(node))
    if payload == "insert":     # X.T -> np.linalg.inv(X)
        return _call("np.linalg.inv", copy_tree(node.value))
    if payload == "transpose":  # np.linalg.inv(X) -> X.T
        return ast.Attribute(copy_tree(node.args[0]), "T", ast.Load())
    return copy_tree(node.args[0])   # np.linalg.inv(X) -> X


def _reciprocal_of(node):
    """``M`` of ``M ** -1`` or ``1 / M`` (``1.0 / M``) where M is a name, an item or a call; else None."""
    if not (isinstance(node, ast.BinOp) and isinstance(node.right if isinstance(node.op, ast.Pow) else node.left,
                                                       (ast.Constant, ast.UnaryOp))):
        return None
    if isinstance(node.op, ast.Pow):
        exponent, matrix = node.right, node.left
        minus_one = isinstance(exponent, ast.UnaryOp) and isinstance(exponent.op, ast.USub) \
            and isinstance(exponent.operand, ast.Constant) and exponent.operand.value == 1
    elif isinstance(node.op, ast.Div):
        matrix = node.right
        minus_one = isinstance(node.left, ast.Constant) and node.left.value == 1
    else:
        return None
    return matrix if minus_one and isinstance(matrix, (ast.Name, ast.Subscript, ast.Call)) else None


def _make_stack_order(node, payload):
    new = copy_tree(node)   # np.hstack([a, b, c]) -> np.hstack([b, a, c]); (0, 2): cv2.merge([c, b, a])
    i, j = payload if isinstance(payload, tuple) else (payload, payload + 1)
    items = new.args[0].elts
    items[i], items[j] = items[j], items[i]
    return new


def _make_default(node, payload):
    if payload == "is_not_none":   # if dist: -> if dist is not None: (an array's truth is ambiguous)
        return ast.Compare(copy_tree(node), [ast.IsNot()], [ast.Constant(None)])
    if payload == "is_none":       # if not dist: -> if dist is None:
        return ast.Compare(copy_tree(node.operand), [ast.Is()], [ast.Constant(None)])
    return ast.UnaryOp(ast.Not(), copy_tree(node.left))   # x is None -> not x


def _none_defaults(fn) -> set:
    """The parameters of ``fn`` whose default is None."""
    args = fn.args
    positional = args.posonlyargs + args.args
    given = list(zip(positional[len(positional) - len(args.defaults):], args.defaults)) \
        + [(a, d) for a, d in zip(args.kwonlyargs, args.kw_defaults) if d is not None]
    return {a.arg for a, d in given if isinstance(d, ast.Constant) and d.value is None}


def _make_single_point(node, payload):
    return copy_tree(node.args[0])   # np.atleast_2d(x) -> x


def _make_minmax(node, payload):
    """The call with its opposite function (`np.argmin(d, axis=2)` -> `np.argmax(d, axis=2)`), its
    arguments kept."""
    if isinstance(node, ast.Call):
        return ast.Call(_name(payload), copy_tree(node.args), copy_tree(node.keywords))
    return _name(payload)


def _make_flag(node, payload):
    return ast.Attribute(copy_tree(node.value), payload, ast.Load())


def _make_bound(node, payload):
    if payload == "drop":  # x - 1 -> x
        return copy_tree(node.left)
    if isinstance(payload, str):  # "+1" / "-1" around an expression
        return ast.BinOp(copy_tree(node), ast.Add() if payload[0] == "+" else ast.Sub(), ast.Constant(1))
    return ast.Constant(payload)  # a constant bound moved


def _make_int_division(node, payload):
    if payload == "floor":
        return ast.BinOp(copy_tree(node.left), ast.FloorDiv(), copy_tree(node.right))
    if payload == "astype":  # np.asarray(x).astype(int)
        return ast.Call(ast.Attribute(_call("np.asarray", copy_tree(node)), "astype", ast.Load()),
                        [ast.Name("int", ast.Load())], [])
    return _call("int", copy_tree(node))


def _make_drop_division(node, payload):
    return copy_tree(node.left)


def _make_drop_factor(node, payload):
    return copy_tree(node.right if payload == "left" else node.left)


def _make_drop_conversion(node, payload):
    converted = _float_conversion(node)
    if isinstance(node.func, ast.Attribute) and node.func.attr == "astype":
        return copy_tree(converted)
    return _call("np.asarray", copy_tree(converted))


def _make_in_place(node, payload):
    if payload == "augment":   # x = x / s -> x /= s
        return ast.AugAssign(copy_tree(node.targets[0]), node.value.op, copy_tree(node.value.right))
    if payload == "rebind":    # x @= s -> x = x @ s: a new array, the one kept before left as it was
        target = copy_tree(node.target)
        return ast.Assign([target], ast.BinOp(ast.Name(target.id, ast.Load()), node.op, copy_tree(node.value)))
    if payload == "array":     # np.array(x, ...) copies, np.asarray(x, ...) does not
        new = copy_tree(node)
        new.func = _name("np.asarray")
        new.keywords = [k for k in new.keywords if k.arg != "copy"]
        return new
    return copy_tree(node.func.value if isinstance(node.func, ast.Attribute) and node.func.attr == "copy"
                         else node.args[0])   # x.copy() / np.copy(x) -> x


def _make_drop_centring(node, payload):
    return copy_tree(node.left)   # x - mean -> x


def _index_of_the_loop(node: ast.Subscript, parents):
    """A fixed index where the loop's own belongs: `pts1[0, 1]` in a loop over `i` whose other reads of
    `pts1` index that axis with `i` (`pts1[i, 0]`) -- a typo that makes every turn read the first item."""
    loop = parents.get(id(node), (None,))[0]
    while loop is not None and not isinstance(loop, ast.For):
        loop = parents.get(id(loop), (None,))[0]
    if loop is None or not isinstance(loop.target, ast.Name):
        return
    counter = loop.target.id
    # (the (array, position) pairs the loop indexes with its own counter, read once per loop)
    indexed = getattr(loop, "_indexed_by_counter", None)
    if indexed is None:
        indexed = loop._indexed_by_counter = {
            (other.value.id, position) for other in walk(loop)
            if isinstance(other, ast.Subscript) and isinstance(other.value, ast.Name)
            for position in range(len(other.slice.elts) if isinstance(other.slice, ast.Tuple) else 1)
            if _index_at(other, position) == counter}
    items = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
    for position, item in enumerate(items):
        # (a fixed index where the same array is read at that position with the loop's index elsewhere)
        if isinstance(item, ast.Constant) and type(item.value) is int and (node.value.id, position) in indexed:
            yield "loop_counter", (position, counter), ""


def _index_at(node: ast.Subscript, position: int) -> str:
    items = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
    return items[position].id if position < len(items) and isinstance(items[position], ast.Name) else ""


def _make_loop_counter(node, payload):
    position, counter = payload   # pts1[0, 1] -> pts1[i, 1]
    new = copy_tree(node)
    if isinstance(new.slice, ast.Tuple):
        new.slice.elts[position] = ast.Name(counter, ast.Load())
    else:
        new.slice = ast.Name(counter, ast.Load())
    return new


def _make_shape_reversed(node, payload):
    new = copy_tree(node)   # img.shape[::-1] -> img.shape[1::-1]
    new.slice = ast.Slice(ast.Constant(1), None, ast.UnaryOp(ast.USub(), ast.Constant(1)))
    return new


_UNPACKED: dict = {}   # id(module_defs) -> (module_defs, {helper: the widths its answers are unpacked into})


def _unpacked_width(helper: str, module_defs: dict) -> int:
    """How many names the module's functions unpack ``helper``'s answer into (`X, single = _points(p)`: 2),
    where they all agree; 0 where none does. The module is read once (every assignment asks)."""
    kept = _UNPACKED.get(id(module_defs))
    if kept is None or kept[0] is not module_defs:
        widths: dict = {}
        for fn in (module_defs or {}).values():
            for node in walk(fn):
                if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Tuple) \
                        and isinstance(node.value, ast.Call) and isinstance(node.value.func, ast.Name):
                    widths.setdefault(node.value.func.id, set()).add(len(node.targets[0].elts))
        if len(_UNPACKED) > 8:   # (the modules read lately: one per grading at a time)
            _UNPACKED.clear()
        kept = _UNPACKED[id(module_defs)] = (module_defs, widths)
    found = kept[1].get(helper, set())
    return next(iter(found)) if len(found) == 1 else 0


def _make_flat_column(node, payload):
    new = copy_tree(node)   # P[:, 3:] -> P[:, 3]
    new.slice.elts[1] = copy_tree(node.slice.elts[1].lower)
    return new


def _make_count_rows(node, payload):
    return ast.Call(ast.Name("len", ast.Load()), [copy_tree(node.value)], [])   # pts.size -> len(pts)


def _make_unpack_pair(node, payload):
    target = node.targets[0].id   # X = _points(p) -> X, _ = _points(p)
    names = [ast.Name(target, ast.Store())] + [ast.Name("_", ast.Store()) for _ in range(payload - 1)]
    return ast.Assign([ast.Tuple(names, ast.Store())], copy_tree(node.value))


def _scaled_copies(fn) -> dict:
    """{name: its source} of the names ``fn`` assigns once as another name scaled (`xr = x * radial`,
    `yn = y / s`): a value and the one it was made from, either of which a formula may read."""
    cached = getattr(fn, "_scaled_copies", None)
    if cached is None:
        counts: dict = {}
        for node in walk(fn):
            if isinstance(node, (ast.Assign, ast.AugAssign)):
                for target in (node.targets if isinstance(node, ast.Assign) else [node.target]):
                    for t in walk(target):
                        if isinstance(t, ast.Name):
                            counts[t.id] = counts.get(t.id, 0) + 1
        cached = {}
        for node in walk(fn):
            if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                    and counts.get(node.targets[0].id) == 1 and isinstance(node.value, ast.BinOp) \
                    and isinstance(node.value.op, (ast.Mult, ast.Div)):
                # (two simple factors, a name among them: `x * radial`, `radial * x`, `y / s`; a parameter is
                # the source where both are names)
                sides = [node.value.left] + ([node.value.right] if isinstance(node.value.op, ast.Mult) else [])
                simple = all(isinstance(side, (ast.Name, ast.Constant, ast.Attribute))
                             for side in (node.value.left, node.value.right))
                names = [side.id for side in sides if isinstance(side, ast.Name)]
                params = {a.arg for a in fn.args.args}
                names = sorted(names, key=lambda name: name not in params)
                if simple and names and names[0] != node.targets[0].id:
                    cached[node.targets[0].id] = names[0]
        fn._scaled_copies = cached
    return cached


def _make_source_names(node, payload):
    made = copy_tree(node)   # dx = 2 * p1 * xr * yr -> dx = 2 * p1 * x * y
    sources = dict(payload)
    for name in walk(made.value):
        if isinstance(name, ast.Name) and name.id in sources and isinstance(name.ctx, ast.Load):
            name.id = sources[name.id]
    return made


def _make_tile_repeat(node, payload):
    new = copy_tree(node)   # np.tile(fs, n) <-> np.repeat(fs, n)
    name = _dotted(node.func)
    new.func = _name(name.replace("tile", "repeat") if "tile" in name else name.replace("repeat", "tile"))
    return new


# math's functions of one number and NumPy's of the same meaning, entry by entry
_MATH_TO_NUMPY = {name: name for name in ("sqrt", "exp", "log", "log10", "log2", "sin", "cos", "tan", "floor", "ceil",
                                          "hypot", "degrees", "radians", "isnan", "isinf", "isfinite", "trunc")}
_MATH_TO_NUMPY.update(pow="power", atan2="arctan2", atan="arctan", asin="arcsin", acos="arccos", fabs="abs")


def _make_math_numpy(node, payload):
    new = copy_tree(node)   # math.pow(r2, 2) -> np.power(r2, 2)
    new.func = _name("np." + _MATH_TO_NUMPY[_dotted(node.func)[5:]])
    return new


def _negated_reduction(node):
    """The all()/any() call a ``~``/``not`` negates (`~np.all(x, axis=0)`, `not x.any()`), or None."""
    if not (isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.Invert, ast.Not))
            and isinstance(node.operand, ast.Call)):
        return None
    called = _dotted(node.operand.func).rsplit(".", 1)[-1]
    return node.operand if called in ("all", "any") else None


def _make_flip_reduction(node, payload):
    """~np.all(x, ...) -> np.any(x, ...), ~x.any() -> x.all(): the negation dropped and the reduction turned."""
    call = copy_tree(_negated_reduction(node))
    func = call.func
    if isinstance(func, ast.Attribute):
        func.attr = "any" if func.attr == "all" else "all"
    else:
        call.func = ast.Name("any" if func.id == "all" else "all", ast.Load())
    return call


def _enclosing_def(node, parents):
    """The def holding ``node`` (through the parents' map), or None."""
    while id(node) in parents and not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
        node = parents[id(node)][0]
    return node if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) else None


def _parameters_for_identity(node, parents) -> list[str]:
    """The def's parameters an identity given to an OpenCV call (`np.eye(3)`, `np.identity(3)`) may stand for."""
    if not (isinstance(node, ast.Call) and _dotted(node.func) in ("np.eye", "numpy.eye", "np.identity", "numpy.identity")
            and id(node) in parents):
        return []
    call = parents[id(node)][0]
    if not (isinstance(call, ast.Call) and _dotted(call.func).startswith(("cv2.", "cv."))):
        return []
    scope = _enclosing_def(call, parents)
    if scope is None:
        return []
    given = {n.id for n in walk(call) if isinstance(n, ast.Name)}
    return [a.arg for a in (*scope.args.posonlyargs, *scope.args.args) if a.arg in given][:3]


_IMAGE_FILTERS = frozenset({"blur", "boxFilter", "sqrBoxFilter", "GaussianBlur", "medianBlur", "filter2D",
                            "bilateralFilter"})


def _filters_a_made_stack(node, parents) -> bool:
    """An OpenCV filter, or a helper of the module, called on a name the def binds to a stack of images
    (`np.zeros((D, h, w))`, `np.stack(...)`): the whole stack given where each image belongs."""
    if not (isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Name)):
        return False
    called = _dotted(node.func)
    if not (called.startswith(("cv2.", "cv.")) and called.rsplit(".", 1)[-1] in _IMAGE_FILTERS) \
            and not (isinstance(node.func, ast.Name) and node.func.id.startswith("_")):
        return False
    scope = _enclosing_def(node, parents)
    if scope is None:
        return False
    name = node.args[0].id
    for statement in walk(scope):
        if isinstance(statement, ast.Assign) and any(isinstance(t, ast.Name) and t.id == name for t in statement.targets) \
                and isinstance(statement.value, ast.Call):
            made = _dotted(statement.value.func).rsplit(".", 1)[-1]
            shape = statement.value.args[0] if statement.value.args else None
            if made in ("stack", "dstack") or (made in ("zeros", "empty", "full", "ones") and isinstance(shape, ast.Tuple)
                                               and len(shape.elts) == 3):
                return True
    return False


def _make_per_image(node, payload):
    """f(stack, *rest) -> np.stack([f(image, *rest) for image in stack])."""
    each = copy_tree(node)
    each.args[0] = ast.Name("_image", ast.Load())
    listed = ast.ListComp(each, [ast.comprehension(ast.Name("_image", ast.Store()), copy_tree(node.args[0]), [], 0)])
    return _call("np.stack", listed)


def _make_stack_window(node, payload):
    new = copy_tree(node)   # size=k -> size=(1, k, k): a window over each image of a stack, not across them
    keyword = next(k for k in new.keywords if k.arg in _WINDOW_KEYWORDS)
    kept = ast.Constant(0 if keyword.arg == "sigma" else 1)
    sides = [copy_tree(keyword.value), copy_tree(keyword.value)]
    keyword.value = ast.Tuple([kept, *sides] if payload == "first" else [*sides, kept], ast.Load())
    return new


_WINDOW_FILTERS = frozenset({"uniform_filter", "gaussian_filter", "median_filter", "maximum_filter",
                             "minimum_filter", "percentile_filter", "rank_filter"})
_WINDOW_KEYWORDS = ("size", "sigma")


def _make_square_window(node, payload):
    side = next(e for e in node.elts if not (isinstance(e, ast.Constant) and e.value == 1))
    return ast.Tuple([copy_tree(side), copy_tree(side)], ast.Load())   # (k, 1) -> (k, k)


def _makes_text(node) -> bool:
    """Whether ``node`` makes a string: `"".join(...)`, an f-string, `str(...)`, a sum of strings."""
    if isinstance(node, ast.JoinedStr) or (isinstance(node, ast.Constant) and isinstance(node.value, str)):
        return True
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "join" \
            and isinstance(node.func.value, ast.Constant) and isinstance(node.func.value.value, str):
        return True
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "str":
        return True
    return isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add) and (_makes_text(node.left) or _makes_text(node.right))


def _make_int_base(node, payload):
    new = copy_tree(node)   # int("".join(bits)) -> int("".join(bits), 2)
    new.args = [*new.args, ast.Constant(payload)]
    return new


def _make_reshape_order(node, payload):
    if payload == "transpose":   # x.reshape(3, -1) -> x.reshape(-1, 3).T (the student's code: the transposed shape
        #                            for a transpose; still 2-D for a single point)
        new = copy_tree(node)
        new.args = [ast.Tuple(list(reversed(new.args[0].elts)), ast.Load())] if len(new.args) == 1 \
            else list(reversed(new.args))
        return ast.Attribute(new, "T", ast.Load())
    if payload == "swap_first":   # x.reshape(n, 4, 4) -> x.reshape(4, n, 4).transpose(1, 0, 2)
        new = copy_tree(node)
        sizes = list(new.args[0].elts) if len(new.args) == 1 else list(new.args)
        sizes[0], sizes[1] = sizes[1], sizes[0]
        new.args = [ast.Tuple(sizes, ast.Load())] if len(node.args) == 1 else sizes
        return ast.Call(ast.Attribute(new, "transpose", ast.Load()), [ast.Constant(1), ast.Constant(0), ast.Constant(2)], [])
    new = copy_tree(node)   # x.reshape(3, 4) -> x.reshape(3, 4, order="F")
    new.keywords = [k for k in new.keywords if k.arg != "order"] + [ast.keyword("order", ast.Constant(payload))]
    return new


def _make_other_name(node, payload):
    return ast.Name(payload, ast.Load())


def _make_drop_statement(node, payload):
    return ast.Pass()


_ARITHMETIC = {"mul_div": ast.Div, "div_mul": ast.Mult, "matmul_mult": ast.Mult, "mult_matmul": ast.MatMult,
               "xor_pow": ast.Pow}


def _make_other_name_line(node, payload):
    old, new = payload
    made = copy_tree(node)
    for name in walk(made.value):
        if isinstance(name, ast.Name) and name.id == old and isinstance(name.ctx, ast.Load):
            name.id = new
    return made


def _make_arithmetic(node, payload):
    if payload in _CHAINED:   # every product of the chain `a * b * c` made the other kind (its left spine)
        made = copy_tree(node)
        link, was = made, _CHAINED[payload][0]
        while isinstance(link, ast.BinOp) and isinstance(link.op, was):
            link.op = _CHAINED[payload][1]()
            link = link.left
        return made
    return ast.BinOp(copy_tree(node.left), _ARITHMETIC[payload](), copy_tree(node.right))


# a chain of products written element by element where matrix products belong (`K2.T * F * K1`), and back
_CHAINED = {"chain_matmul": (ast.Mult, ast.MatMult), "chain_mult": (ast.MatMult, ast.Mult)}


def _make_stack_kind(node, payload):
    new = copy_tree(node)
    new.func = _name(f"np.{payload}")
    return new


def _make_drop_mask(node, payload):
    return copy_tree(node.left)


def _make_reshape_transpose(node, payload):
    inner = copy_tree(node.value)
    shape = ast.Subscript(ast.Attribute(copy_tree(node.value), "shape", ast.Load()),
                          ast.Slice(None, None, ast.UnaryOp(ast.USub(), ast.Constant(1))), ast.Load())
    return ast.Call(ast.Attribute(inner, "reshape", ast.Load()), [shape], [])


def _make_shift(node, payload):
    return ast.BinOp(copy_tree(node.left), ast.LShift() if isinstance(node.op, ast.RShift) else ast.RShift(),
                     copy_tree(node.right))


def _make_loop_index(node, payload):
    return _call("range", _call("len", copy_tree(node)))   # the positions of what was looped over


def _make_dehomogenise(node, payload):
    if isinstance(payload, tuple):   # x[:, :2] / d -> x[:, :2] / x[:, 2:3]: the divisor made the last coordinate
        return _make_dehomogenise(node.left, payload[1])
    # x[:, :2] -> x[:, :2] / x[:, 2:3]: the points divided by their last coordinate
    last = copy_tree(node)
    bound = ast.Slice(ast.Constant(payload), ast.Constant(payload + 1))
    if isinstance(last.slice, ast.Tuple):
        last.slice.elts[-1] = bound
    else:
        last.slice = bound
    return ast.BinOp(copy_tree(node), ast.Div(), last)


def _make_translation(node, payload):
    # pts @ M[:, :3].T -> pts @ M[:, :3].T + M[:, 3]: the last column (the homogeneous 1's) added back
    block, column = _sliced_block(node.right if payload[0] == "right" else node.left)
    bound = column if payload[1] == "row" else ast.Slice(column, ast.Constant(column.value + 1))
    last = ast.Subscript(copy_tree(block.value), ast.Tuple([ast.Slice(), bound], ast.Load()), ast.Load())
    return ast.BinOp(copy_tree(node), ast.Add(), last)


def _sliced_block(node):
    """``(M[:, :k], Constant(k))`` when ``node`` is ``M[:, :k]`` or its transpose (a matrix's first
    columns, its last left out), else ``(None, None)``."""
    if isinstance(node, ast.Attribute) and node.attr == "T":
        node = node.value
    if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2:
        rows, columns = node.slice.elts
        if isinstance(rows, ast.Slice) and rows.lower is None and rows.upper is None and rows.step is None \
                and isinstance(columns, ast.Slice) and columns.lower is None and columns.step is None \
                and isinstance(columns.upper, ast.Constant) and columns.upper.value in (2, 3):
            return node, ast.Constant(columns.upper.value)
    return None, None


def _bare(node):
    """``node`` without a unary minus (a negative bound is a constant too)."""
    return node.operand if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) else node


_GATHERS = frozenset({"take_along_axis", "take", "choose"})   # NumPy calls that pick a result's values anew


def _summed_up(fn) -> set[str]:
    """The names ``fn`` adds to in place (`weights += weight`): sums built up item by item (read once per def)."""
    if not hasattr(fn, "_summed_up"):
        fn._summed_up = {node.target.id for node in walk(fn) if isinstance(node, ast.AugAssign)
                         and isinstance(node.op, ast.Add) and isinstance(node.target, ast.Name)}
    return fn._summed_up


def _make_scale_inverse(node, payload):
    """A scaling done in place the other way: `x /= k` -> `x *= k`, `x *= k` -> `x /= k`."""
    return ast.AugAssign(copy_tree(node.target), ast.Mult() if isinstance(node.op, ast.Div) else ast.Div(),
                         copy_tree(node.value))


def _make_own_values(node, payload):
    """One value of a whole array made each item's own, given to an operand with one more axis:
    `total / weights.max()` -> `total / weights[..., None]`."""
    whole = node.func.value if isinstance(node.func, ast.Attribute) and not node.args else node.args[0]
    return ast.Subscript(copy_tree(whole), ast.Tuple([ast.Constant(...), ast.Constant(None)], ast.Load()),
                         ast.Load())


def _make_unwrap(node, payload):
    if payload == "method":   # depth.mean() -> depth
        return copy_tree(node.func.value)
    if payload == "ratio":   # np.arctan2(y, x) -> y / x
        return ast.BinOp(copy_tree(node.args[0]), ast.Div(), copy_tree(node.args[1]))
    if payload == "third":   # cv2.addWeighted(a, 0.6, b, 0.4, 0) -> b
        return copy_tree(node.args[2])
    if payload == "clamped":   # np.maximum(d, 1.0) -> d
        return copy_tree(next(a for a in node.args if not isinstance(_bare(a), ast.Constant)))
    inner = node.args[0]
    while payload == "chain" and _unary_call(inner):   # np.tan(np.deg2rad(s)) -> s: both calls at once
        inner = inner.args[0]
    return copy_tree(inner)


_INTEGER_NAMES = {"int", "int8", "int16", "int32", "int64", "intp", "int_", "int0", "uint16", "uint32", "uint64"}


def _integer_type(node) -> bool:
    """Whether ``node`` names an integer dtype (`int`, `np.int32`, `"int32"`)."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value in _INTEGER_NAMES
    dotted = _dotted(node) if isinstance(node, (ast.Name, ast.Attribute)) else ""
    return dotted.rsplit(".", 1)[-1] in _INTEGER_NAMES and dotted[: -len(dotted.rsplit(".", 1)[-1])] in ("", "np.", "numpy.")


def _integer_cast(node) -> str:
    """How ``node`` makes an array of integers: "call" (`np.int32(x)`), "dtype" (`np.asarray(x, np.int32)`,
    `np.array(x, dtype=int)`); "" for none (`x.astype(int)` is the astype_float operator's)."""
    if not isinstance(node, ast.Call):
        return ""
    dotted = _dotted(node.func)
    if len(node.args) == 1 and not node.keywords and _integer_type(node.func) and dotted != "int":
        return "call"
    if dotted in ("np.asarray", "np.array", "numpy.asarray", "numpy.array") and node.args and (
            (len(node.args) >= 2 and _integer_type(node.args[1]))
            or any(k.arg == "dtype" and _integer_type(k.value) for k in node.keywords)):
        return "dtype"
    return ""


def _make_float_kept(node, payload):
    """An array made of integers, kept as floats: `np.int32(x)` -> `x`, `np.asarray(x, np.int32)` ->
    `np.asarray(x, np.float64)`."""
    if payload == "call":
        return copy_tree(node.args[0])
    new = copy_tree(node)
    if len(new.args) >= 2 and _integer_type(new.args[1]):
        new.args[1] = _name("np.float64")
    else:
        new.keywords = [ast.keyword("dtype", _name("np.float64")) if k.arg == "dtype" else k for k in new.keywords]
    return new


def _unary_call(node) -> bool:
    """Whether ``node`` is a one-argument call of a numeric function (`np.tan(s)`, `int(z)`)."""
    if not isinstance(node, ast.Call) or len(node.args) != 1 or node.keywords or isinstance(node.args[0], ast.Starred):
        return False
    dotted = _dotted(node.func)
    short = dotted.rsplit(".", 1)[-1]
    return short in _UNARY and dotted[: -len(short)] in ("np.", "numpy.", "math.", "")


_ROUNDING = ("np.round", "numpy.round", "np.around", "numpy.around", "round")


def _rounded_to_decimals(node, dotted: str) -> bool:
    """`np.round(x, 2)`, `round(x, 3)`, `np.around(x, decimals=2)`: a number rounded to some decimals."""
    return dotted in _ROUNDING and len(node.args) in (1, 2) and not isinstance(node.args[0], ast.Starred) \
        and (len(node.args) == 2 or any(k.arg in ("decimals", "ndigits") for k in node.keywords))


def _make_swap_items(node, payload):
    new = copy_tree(node)   # (h, w) -> (w, h): the same for a tuple assigned to, `w, h = image.shape[:2]`
    if payload[0] == "moved":   # (a, b, c) -> (b, c, a): the items in the order given
        new.elts = [new.elts[k] for k in payload[1]]
        return new
    i, j = payload
    new.elts[i], new.elts[j] = new.elts[j], new.elts[i]
    return new


def _make_cross_items(node, payload):
    new = copy_tree(node)   # ((x0, y0), (x1, y1)) -> ((x0, y1), (x1, y0)): the k-th items of two points exchanged
    i, j, k = payload
    new.elts[i].elts[k], new.elts[j].elts[k] = new.elts[j].elts[k], new.elts[i].elts[k]
    return new


def _make_compare(node, payload):
    new = copy_tree(node)
    operator, threshold = payload if isinstance(payload, tuple) else (payload, None)
    new.ops = [getattr(ast, operator)()]
    if threshold is not None:   # `d >= 1` -> `d > 0`: the test and its threshold
        new.comparators = [ast.Constant(threshold)]
    return new


def _make_row_kron(node, payload):
    first, second = node.args   # np.kron(a, b) -> (a[:, :, None] * b[:, None, :]).reshape(len(a), -1): row i's kron only
    outer = ast.BinOp(ast.Subscript(copy_tree(first), parse("x[:, :, None]", mode="eval").body.slice, ast.Load()),
                      ast.Mult(),
                      ast.Subscript(copy_tree(second), parse("x[:, None, :]", mode="eval").body.slice, ast.Load()))
    return ast.Call(ast.Attribute(outer, "reshape", ast.Load()),
                    [ast.Call(ast.Name("len", ast.Load()), [copy_tree(first)], []), ast.Constant(-1)], [])


_FLIPS = {"fliplr": "flipud", "flipud": "fliplr"}


def _make_flip_axis(node, payload):
    new = copy_tree(node)   # np.fliplr(x) -> np.flipud(x); cv2.flip(x, 0) -> cv2.flip(x, 1): the other axis reversed
    if payload == "code":
        new.args[1] = ast.Constant(1 - new.args[1].value)
    else:
        new.func.attr = _FLIPS[new.func.attr]
    return new


def _flips(node):
    """A flip of one axis where the other's belongs: np.fliplr/np.flipud, cv2.flip with code 0 or 1."""
    if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
        return
    if node.func.attr in _FLIPS and _dotted(node.func.value) in ("np", "numpy"):
        yield "flip_axis", "name", ""
    if node.func.attr == "flip" and _dotted(node.func.value) == "cv2" and len(node.args) >= 2 \
            and isinstance(node.args[1], ast.Constant) and node.args[1].value in (0, 1):
        yield "flip_axis", "code", ""


def _make_clip_range(node, payload):
    low, high = payload   # cv2.normalize(x, None, 0, 255, cv2.NORM_MINMAX) -> np.clip(x, 0, 255): kept in range, not stretched
    return ast.Call(_name("np.clip"), [copy_tree(node.args[0]), copy_tree(low), copy_tree(high)], [])


def _stretched_range(node):
    """The range (low, high) a min-max normalisation stretches to (`cv2.normalize(x, None, 0, 255, cv2.NORM_MINMAX)`,
    its keywords alpha/beta/norm_type too), or None."""
    if not (isinstance(node, ast.Call) and _dotted(node.func).endswith("normalize") and node.args):
        return None
    given = dict(enumerate(node.args)) | {{"alpha": 2, "beta": 3, "norm_type": 4}.get(k.arg, k.arg): k.value
                                           for k in node.keywords}
    kind = given.get(4)
    if not (isinstance(kind, ast.Attribute) and kind.attr == "NORM_MINMAX") or 2 not in given or 3 not in given:
        return None
    return given[2], given[3]


def _make_cross_multiply(node, payload):
    new = copy_tree(node)   # a / b < r -> a < r * b: no division, and a b of 0 compares instead of raising
    ratio = new.left
    new.left, new.comparators = ratio.left, [ast.BinOp(new.comparators[0], ast.Mult(), ratio.right)]
    return new


def _make_regroup(node, payload):
    if payload == "first":   # a - b / c -> (a - b) / c
        inner = node.right
        return ast.BinOp(ast.BinOp(copy_tree(node.left), node.op, copy_tree(inner.left)), inner.op,
                         copy_tree(inner.right))
    if payload == "last":    # a * b + c -> a * (b + c)
        inner = node.left
        return ast.BinOp(copy_tree(inner.left), inner.op,
                         ast.BinOp(copy_tree(inner.right), node.op, copy_tree(node.right)))
    if payload == "floor_last":   # (a // c) * b -> a * b // c
        inner = node.left
        return ast.BinOp(ast.BinOp(copy_tree(inner.left), node.op, copy_tree(node.right)), inner.op,
                         copy_tree(inner.right))
    if payload == "divisor_rounded":   # a // (b // c) -> a * c // b
        inner = node.right
        return ast.BinOp(ast.BinOp(copy_tree(node.left), ast.Mult(), copy_tree(inner.right)), ast.FloorDiv(),
                         copy_tree(inner.left))
    if payload in ("factor_last", "factor_first"):   # (a - b) * c -> a - b * c, or a * c - b
        inner = node.left
        if payload == "factor_last":
            return ast.BinOp(copy_tree(inner.left), inner.op,
                             ast.BinOp(copy_tree(inner.right), node.op, copy_tree(node.right)))
        return ast.BinOp(ast.BinOp(copy_tree(inner.left), node.op, copy_tree(node.right)), inner.op,
                         copy_tree(inner.right))
    if payload == "flat":   # a - (b + c) -> a - b + c
        inner = node.right
        return ast.BinOp(ast.BinOp(copy_tree(node.left), node.op, copy_tree(inner.left)), inner.op,
                         copy_tree(inner.right))
    inner = node.left       # a / b * c -> a / (b * c)
    return ast.BinOp(copy_tree(inner.left), inner.op,
                     ast.BinOp(copy_tree(inner.right), node.op, copy_tree(node.right)))


def _make_dtype(node, payload):
    new = copy_tree(node)   # np.zeros(shape) -> np.zeros(shape, dtype=np.uint8); dtype=int -> np.float64
    new.keywords = [k for k in new.keywords if k.arg != "dtype"] + [ast.keyword("dtype", _name(payload))]
    return new


def _make_sibling_step(node, payload):
    name = node.targets[0].id   # a = f(a) -> a, b = f(a), f(b)
    twin = _renamed(node, name, payload)
    return ast.fix_missing_locations(ast.copy_location(ast.Assign(
        [ast.Tuple([ast.Name(name, ast.Store()), ast.Name(payload, ast.Store())], ast.Store())],
        ast.Tuple([copy_tree(node.value), twin.value], ast.Load())), node))


def _make_factor_pair(node, payload):
    other, text = payload   # K = K @ D -> K, R = K @ D, D @ R
    return ast.fix_missing_locations(ast.copy_location(ast.Assign(
        [ast.Tuple([copy_tree(node.targets[0]), ast.Name(other, ast.Store())], ast.Store())],
        ast.Tuple([copy_tree(node.value), _parse(text).body[0].value], ast.Load())), node))


def _make_select_mask(node, payload):
    arrays, mask = payload   # f(src, dst) -> f(src[best], dst[best])
    new = copy_tree(node)
    new.args = [ast.Subscript(a, ast.Name(mask, ast.Load()), ast.Load()) if isinstance(a, ast.Name) and a.id in arrays
                else a for a in new.args]
    return new


def _make_sibling_argument(node, payload):
    new = copy_tree(node)
    position, text = payload
    new.args[position] = _parse(text).body[0].value   # (the other call's argument, as it was written)
    return new


def _make_twin_step(node, payload):
    new = copy_tree(node)   # (x / w, y) -> (x / w, y / w); `v = y` -> `v = y / w`
    position, text = payload
    step = _parse(text).body[0].value   # (the twin's step, as the student wrote it)
    if position is None:
        new.value = step
    else:
        new.elts[position] = step
    return new


def _make_twin_argument(node, payload):
    new = copy_tree(node)   # f(A1 @ T1.T, A2) -> f(A1 @ T1.T, A2 @ T2.T)
    position, text = payload
    new.args[position] = _parse(text).body[0].value
    return new


def _make_measure(node, payload):
    if payload == "sqrt":   # np.sum(d ** 2, axis=1) -> np.sqrt(np.sum(d ** 2, axis=1))
        return ast.Call(_name("np.sqrt"), [copy_tree(node)], [])
    if payload == "abs_inside":   # np.sum(l - r) -> np.sum(np.abs(l - r))
        new = copy_tree(node)
        new.args[0] = ast.Call(_name("np.abs"), [new.args[0]], [])
        return new
    if payload == "square":   # np.abs(d) -> d ** 2
        return ast.BinOp(copy_tree(node.args[0]), ast.Pow(), ast.Constant(2))
    inner = node.left if isinstance(node, ast.BinOp) else node.args[0]   # d ** 2, np.square(d) -> np.abs(d)
    return ast.Call(_name("np.abs"), [copy_tree(inner)], [])


def _make_power_inside(node, payload):
    if payload == "ratio":   # np.mean(f / z) -> f / np.mean(z): the ratio of the mean, not the mean of ratios
        call = copy_tree(node)
        ratio = call.args[0]
        call.args[0] = ratio.right
        return ast.BinOp(ratio.left, ast.Div(), call)
    if payload == "inside":   # np.mean(d) ** 2 -> np.mean(d ** 2)
        call = copy_tree(node.left)
        call.args[0] = ast.BinOp(call.args[0], ast.Pow(), copy_tree(node.right))
        return call
    new = copy_tree(node)   # np.mean(d ** 2) -> np.mean(d) ** 2
    power = new.args[0]
    new.args[0] = power.left
    return ast.BinOp(new, ast.Pow(), power.right)


def _make_slice(node, payload):
    if payload == "other_end":   # costs[:, d:] -> costs[:, :d]: the part before the bound, not after it
        return ast.Slice(copy_tree(node.upper), copy_tree(node.lower), None)
    if payload == "drop_last":   # x[:, d:] -> x[:, :-d or None]: the last d entries off, not the first (none for 0)
        return ast.Slice(None, ast.BoolOp(ast.Or(), [ast.UnaryOp(ast.USub(), copy_tree(node.lower)),
                                                     ast.Constant(None)]), None)
    lower, upper = payload   # l[:, 1:] -> l[:, :2]; A[r, 3:7] -> A[r, 4:8]
    return ast.Slice(None if lower is None else _signed(lower), None if upper is None else _signed(upper), None)


def _make_row_column(node, payload):
    made = copy_tree(node)
    if payload == "column":   # X[k] -> X[:, k]
        made.slice = ast.Tuple([ast.Slice(None, None, None), copy_tree(node.slice)], ast.Load())
    elif payload == "next_axis":   # costs[d, :d] -> costs[d, :, :d]: the run of rows made a run of columns
        items = list(node.slice.elts) if isinstance(node.slice, ast.Tuple) else [node.slice]
        made.slice = ast.Tuple([*map(copy_tree, items[:-1]), ast.Slice(None, None, None), copy_tree(items[-1])],
                               ast.Load())
    else:                     # X[:, k] -> X[k]
        made.slice = copy_tree(node.slice.elts[1])
    return made


def _make_slice_item(node, payload):
    position, start = payload
    made = copy_tree(node)
    if position is None:   # the block's diagonal: `K[:2, :2]` -> `K[[0, 1], [0, 1]]`
        diagonal = ast.List([ast.Constant(k) for k in range(*start)], ast.Load())
        made.slice = ast.Tuple([diagonal, copy_tree(diagonal)], ast.Load())
    elif isinstance(made.slice, ast.Tuple):
        made.slice.elts[position] = ast.Constant(start)
    else:
        made.slice = ast.Constant(start)
    return made


def _signed(value: int):
    return ast.UnaryOp(ast.USub(), ast.Constant(-value)) if value < 0 else ast.Constant(value)


def _make_canvas(node, payload):
    return _parse(payload).body[0].value   # h1 -> max(h1, h2), w1 -> w1 + w2


def _make_chain_order(node, payload):
    first, middle, last = (copy_tree(f) for f in _chain_of_three(node))
    factors = {"first": [middle, first, last], "last": [first, last, middle],
               "outer": [last, middle, first]}[payload]   # (a conjugation turned round: T(-c) R T(c) for T(c) R T(-c))
    return ast.BinOp(ast.BinOp(factors[0], ast.MatMult(), factors[1]), ast.MatMult(), factors[2])


def _make_loop_all(node, payload):
    return _parse(payload).body[0].value   # range(8) -> range(len(p1))


def _make_drop_slice(node, payload):
    return copy_tree(node.value)   # pts[:8] -> pts


def _make_power_spread(node, payload):
    terms = node.left   # (x + y) ** 2 -> x ** 2 + y ** 2
    return ast.BinOp(ast.BinOp(copy_tree(terms.left), ast.Pow(), copy_tree(node.right)), terms.op,
                     ast.BinOp(copy_tree(terms.right), ast.Pow(), copy_tree(node.right)))


def _make_keep_result(node, payload):
    return ast.Assign([ast.Name(payload, ast.Store())], copy_tree(node.value))   # f(x) -> x = f(x)


def _make_add_axis(node, payload):
    new = copy_tree(node)   # np.delete(X, 2) -> np.delete(X, 2, axis=1)
    axis, kept = payload if isinstance(payload, tuple) else (payload, False)
    new.keywords = [*new.keywords, ast.keyword("axis", _signed(axis))]
    if kept:   # np.linalg.norm(l[:, :2]) -> (..., axis=1, keepdims=True): each row's, divided row by row
        new.keywords.append(ast.keyword("keepdims", ast.Constant(True)))
    return new


def _make_flip_keyword(node, payload):
    new = copy_tree(node)   # np.linalg.svd(A, full_matrices=False) -> full_matrices=True
    if isinstance(payload, tuple):   # (a keyword left at its default given: np.linspace(0, n, w) -> endpoint=False)
        new.keywords = [*new.keywords, ast.keyword(payload[0], ast.Constant(payload[1]))]
        return new
    new.keywords = [ast.keyword(k.arg, ast.Constant(not k.value.value)) if k.arg == payload else k
                    for k in new.keywords]
    return new


def _make_simultaneous(node, payload):
    _, target, value = payload   # x = f(x, y) (then y = g(x, y)) -> x, y = f(x, y), g(x, y)
    return ast.copy_location(ast.Assign(
        [ast.Tuple([copy_tree(node.targets[0]), parse(target, mode="eval").body], ast.Store())],
        ast.Tuple([copy_tree(node.value), parse(value, mode="eval").body], ast.Load())), node)


def _make_move(node, payload):
    _, moved, _, side = payload   # a statement made again beside the edited one (an `if True:` holds both)
    made = parse(moved).body[0]
    pair = [copy_tree(node), made] if side == "after" else [made, copy_tree(node)]
    return ast.copy_location(ast.If(ast.Constant(True), pair, []), node)


def _make_indent(node, payload):
    new = copy_tree(node)   # for ...: body; s -> for ...: body; s
    moved = parse(payload[1]).body[0]
    new.body = [moved, *new.body] if payload[3] == "first" else [*new.body, moved]   # (s; for ...: -> for ...: s)
    return new


@dataclass(frozen=True)
class _Assigned:
    """One assignment of a def, read once (:func:`_assignments`)."""
    line: int
    names: tuple          # every name it assigns, in order (`U, s, Vt = ...`)
    single: str | None    # the name, when it assigns one name alone
    reads: frozenset      # the names its value reads
    calls: frozenset      # the dotted names its value calls (`np.linalg.lstsq`, `cv2.Rodrigues`)
    value: ast.expr


def _assignments(words) -> tuple:
    """The def's assignments, read once per def (kept on ``words``, as :func:`_read_siblings` keeps its own):
    the operators asking what was assigned above a place look them up here, so that a def of many such
    places is read in linear time."""
    if not hasattr(words, "assignments"):
        words.assignments = _assignments_of(words.fn)
    return words.assignments


def _assignments_of(fn) -> tuple:
    found = []
    for statement in walk(fn):
        if isinstance(statement, ast.Assign):
            names = tuple(n.id for t in statement.targets for n in walk(t) if isinstance(n, ast.Name))
            single = statement.targets[0].id if len(statement.targets) == 1 \
                and isinstance(statement.targets[0], ast.Name) else None
            calls = frozenset(_dotted(c.func) for c in walk(statement.value) if isinstance(c, ast.Call))
            found.append(_Assigned(statement.lineno, names, single, frozenset(_read(statement.value)), calls,
                                   statement.value))
    return tuple(found)


def _made_from(name: str, words, line: int) -> list[str]:
    """The names assigned above ``line`` in the def from a library call's answer that reads ``name`` (a matrix
    fitted on values ``name`` moved: `L = np.linalg.lstsq(src - src_mean, ...)[0].T`), at most two, nearest
    first."""
    made = [(a.line, a.single) for a in _assignments(words)
            if a.single not in (None, name) and a.line < line and name in a.reads
            and any(call.split(".")[0] in ("np", "numpy", "cv2", "scipy") for call in a.calls)]
    return [target for _, target in sorted(made, reverse=True)[:2]]


def _centre_and_translation(node, parent, words):
    """(R, inverse) for a name given where the other of a camera's centre and translation belongs: assigned to
    a translation's name (`tvec = C`, `t = C`) or given as cv2.projectPoints' tvec -- tried as ``-R @ C`` --, or
    assigned to a centre's name (`C = t`) -- tried as ``-R.T @ t`` --, with R a 3x3 rotation the def made
    above (a name R, or one unpacked from cv2.Rodrigues or cv2.decomposeProjectionMatrix)."""
    target = parent.targets[0].id if isinstance(parent, ast.Assign) and parent.value is node \
        and len(parent.targets) == 1 and isinstance(parent.targets[0], ast.Name) else None
    given_as_tvec = isinstance(parent, ast.Call) and _dotted(parent.func).endswith("projectPoints") \
        and len(parent.args) > 2 and parent.args[2] is node
    to_translation = given_as_tvec or (target is not None and target.lower() in ("t", "tvec", "trans", "translation"))
    to_centre = target is not None and target.lower() in ("c", "centre", "center", "camera_centre", "camera_center")
    if not (to_translation or to_centre) or node.id.lower() in ("r", "rvec"):
        return []
    rotations = [n for a in _assignments(words) if a.line < node.lineno for n in a.names
                 if n == "R" or (n.lower().startswith("r") and n != "rvec"
                                 and {c.rsplit(".", 1)[-1] for c in a.calls} & {"decomposeProjectionMatrix", "Rodrigues"})]
    return [(rotation, to_centre) for rotation in dict.fromkeys(rotations) if rotation != node.id][:1]


def _make_centre_translation(node, payload):
    rotation, inverse = payload   # C -> -R @ C (a translation), t -> -R.T @ t (a centre)
    matrix = ast.Attribute(ast.Name(rotation, ast.Load()), "T", ast.Load()) if inverse else ast.Name(rotation, ast.Load())
    return ast.UnaryOp(ast.USub(), ast.BinOp(matrix, ast.MatMult(), copy_tree(node)))


def _make_map_term(node, payload):
    new = copy_tree(node)   # a - b -> a - M @ b
    new.right = ast.BinOp(ast.Name(payload, ast.Load()), ast.MatMult(), new.right)
    return new


def _make_slice_order(node, payload):
    inner = copy_tree(node.value.value)   # x[a][b] -> x[b][a]
    return ast.Subscript(ast.Subscript(inner, copy_tree(node.slice), ast.Load()), copy_tree(node.value.slice),
                         ast.Load())


def _make_undecomposed(node, payload):
    return parse(payload, mode="eval").body   # U @ np.diag([s[0], s[1], 0.0]) @ Vt -> E


def _make_keep_parameter(node, payload):
    # for d in ...: f0 = f0 * d / z0; ... f0 ... -> for d in ...: f = f0 * d / z0; ... f ...
    k, name, fresh = payload
    new = copy_tree(node)
    statement = new.body[k]
    value = statement.value if isinstance(statement, ast.Assign) else \
        ast.BinOp(ast.Name(name, ast.Load()), statement.op, statement.value)
    new.body[k] = ast.copy_location(ast.Assign([ast.Name(fresh, ast.Store())], value), statement)
    for later in new.body[k + 1:]:
        for n in walk(later):
            if isinstance(n, ast.Name) and n.id == name:
                n.id = fresh
    return new


def _make_dedent(node, payload):
    new = copy_tree(node)   # for ...: body; s -> for ...: body / s
    last = new.body.pop()
    return ast.copy_location(ast.If(ast.Constant(True), [new, last], []), node)


def _make_hoist(node, payload):
    new = copy_tree(node)   # for ...: s; body -> s / for ...: body
    first = new.body.pop(0)
    return ast.copy_location(ast.If(ast.Constant(True), [first, new], []), node)


def _make_guard(node, payload):
    # l / d -> np.where(d > 0, l / np.where(d > 0, d, 1), 0.0): divided only where the divisor is valid
    left, right = ast.unparse(node.left), ast.unparse(node.right)
    return parse(f"np.where({right} > 0, ({left}) / np.where({right} > 0, {right}, 1), {payload})", mode="eval").body


def _make_lower_bound(node, payload):
    # cols < width -> (cols >= 0) & (cols < width): an index below 0 counts from the end in NumPy
    return ast.BinOp(ast.Compare(copy_tree(node.left), [ast.GtE()], [ast.Constant(0)]), ast.BitAnd(),
                     copy_tree(node))


def _make_drop_keyword(node, payload):
    new = copy_tree(node)   # cv2.undistortPoints(p, K, None, P=K) -> cv2.undistortPoints(p, K, None)
    if isinstance(payload, int):   # cv2.resize(image, size, fx=s) -> cv2.resize(image, None, fx=s)
        new.args[payload] = ast.Constant(None)
    new.keywords = [k for k in new.keywords if k.arg != payload]
    return new


def _make_neutral_argument(node, payload):
    new = copy_tree(node)   # cv2.getRotationMatrix2D(centre, angle, zoom) -> (centre, angle, 1.0)
    if isinstance(payload, int):
        new.args[payload] = ast.Constant(1.0)
    else:
        new.keywords = [ast.keyword(k.arg, ast.Constant(1.0)) if k.arg == payload else k for k in new.keywords]
    return new


def _make_method_given(node, payload):
    keyword, member = payload   # cv2.findFundamentalMat(p1, p2) -> cv2.findFundamentalMat(p1, p2, method=cv2.FM_8POINT)
    module = _dotted(node.func).split(".", 1)[0]
    value = _parse(" | ".join(f"{module}.{name.strip()}" for name in member.split("|"))).body[0].value
    new = copy_tree(node)
    new.keywords = list(new.keywords) + [ast.keyword(arg=keyword, value=value)]
    return new


def _make_drop_argument(node, payload):
    new = copy_tree(node)   # _warp(image, M, size) -> _warp(image, M): the helper's default used
    if isinstance(payload, int):
        del new.args[payload]
    new.keywords = [k for k in new.keywords if k.arg != payload]
    return new


def _make_drop_flag(node, payload):
    return copy_tree(node.right if payload == "left" else node.left)   # a | b -> b (or a)


def _make_grey(node, payload):
    new = copy_tree(node)   # cv2.cornerSubPix(image, ...) -> the image in grey where it has 3 channels
    image = ast.unparse(new.args[payload])
    new.args[payload] = parse(f"(cv2.cvtColor({image}, cv2.COLOR_BGR2GRAY) if {image}.ndim == 3 else {image})",
                              mode="eval").body
    return new


def _make_stride(node, payload):
    # A[i] -> A[2 * i], A[i + 1] -> A[2 * i + 1]: two rows (entries) per item where one was written
    new = copy_tree(node)
    index = new.slice.elts[0] if isinstance(new.slice, ast.Tuple) else new.slice
    counter = index.left if isinstance(index, ast.BinOp) else index
    doubled = ast.BinOp(ast.Constant(2), ast.Mult(), counter)
    if isinstance(index, ast.BinOp):
        index.left = doubled
    elif isinstance(new.slice, ast.Tuple):
        new.slice.elts[0] = doubled
    else:
        new.slice = doubled
    return new


def _make_float32(node, payload):
    new = copy_tree(node)   # cv2.remap(img, mx, my, ...) -> np.float32(mx), np.float32(my)
    new.args = [_call("np.float32", arg) if position in payload else arg for position, arg in enumerate(new.args)]
    return new


def _make_python_numbers(node, payload):
    return ast.Call(_name("tuple"), [ast.Call(_name("map"), [_name("int"), copy_tree(node.args[0])], [])], [])


def _make_size_given(node, payload):
    parameter, size = payload   # apply_homography(moving, H) -> apply_homography(moving, H, dsize=(w, h))
    new = copy_tree(node)
    new.keywords.append(ast.keyword(parameter, parse(size, mode="eval").body))
    return new


def _make_len_axis(node, payload):
    # len(x) -> x.shape[1]: the length along the second axis
    return ast.Subscript(ast.Attribute(copy_tree(node.args[0]), "shape", ast.Load()), ast.Constant(1), ast.Load())


def _make_jump_size(node, payload):
    # (a != b) -> np.abs(a - b): a jump of k paid k times, not once
    return ast.Call(_name("np.abs"), [ast.BinOp(copy_tree(node.left), ast.Sub(), copy_tree(node.comparators[0]))], [])


def _nan_fill_minimised(node, parents, words) -> bool:
    """Whether ``node`` is NaN (`np.nan`) assigned into a table (`costs = np.full(s, np.nan)`, `costs[d, :, :d] = np.nan`)
    whose smallest entries the def takes, or which it returns to a def of the module that takes an argmin: a NaN
    is what np.argmin picks first, where an entry without a value must lose."""
    if _dotted(node) not in ("np.nan", "numpy.nan", "np.NaN", "math.nan"):
        return False
    statement = node
    while id(statement) in parents and not isinstance(statement, ast.stmt):
        statement = parents[id(statement)][0]
    if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1):
        return False
    target = statement.targets[0]
    root = target.value if isinstance(target, ast.Subscript) else target
    if not isinstance(root, ast.Name):
        return False
    fn = _def_of(statement, parents)
    if root.id in _minimised_names(fn):
        return True
    returned = any(isinstance(r, ast.Return) and isinstance(r.value, ast.Name) and r.value.id == root.id for r in walk(fn))
    return returned and isinstance(fn, ast.FunctionDef) and fn.name in _minimising_callees(words)


def _minimising_callees(words) -> set:
    """The names of the module's defs that the module's other defs name (call, or choose to call) beside an argmin:
    read once per def's words (every NaN asks)."""
    if not hasattr(words, "minimising_callees"):
        named = set()
        for other in words.module_defs.values():
            if any(isinstance(c, ast.Call) and _dotted(c.func).rsplit(".", 1)[-1] in ("argmin", "nanargmin", "amin")
                   for c in walk(other)):
                named |= {n.id for n in walk(other) if isinstance(n, ast.Name) and n.id != other.name}
        words.minimising_callees = named
    return words.minimising_callees


def _make_fill_inf(node, payload):
    if payload == "nan":   # np.nan -> np.inf
        return _name("np.inf")
    # np.zeros(s) -> np.full(s, np.inf); np.zeros_like(x) -> np.full_like(x, np.inf, dtype=np.float64)
    if _dotted(node.func).endswith("zeros_like"):
        return ast.Call(_name("np.full_like"), [copy_tree(node.args[0]), _name("np.inf")],
                        [ast.keyword("dtype", _name("np.float64"))])
    return ast.Call(_name("np.full"), [copy_tree(node.args[0]), _name("np.inf")], [])


def _minimised(assign, parents) -> bool:
    """Whether ``assign`` (`costs = np.zeros(...)`) binds a name whose smallest entries the def later takes
    (`np.argmin(costs, ...)`, `costs.argmin()`, `np.min(costs)`)."""
    if not (len(assign.targets) == 1 and isinstance(assign.targets[0], ast.Name)):
        return False
    return assign.targets[0].id in _minimised_names(_def_of(assign, parents))


def _minimised_names(fn) -> set:
    """The names whose smallest entries ``fn`` takes (read once per def, kept on it: every table asks)."""
    if not hasattr(fn, "_minimised"):
        minimised = set()
        for n in walk(fn):
            if isinstance(n, ast.Call) and n.args and _dotted(n.func).rsplit(".", 1)[-1] in ("argmin", "nanargmin", "min", "amin") \
                    and isinstance(n.args[0], ast.Name):
                minimised.add(n.args[0].id)
            if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute) and n.func.attr in ("argmin", "min") \
                    and isinstance(n.func.value, ast.Name):
                minimised.add(n.func.value.id)
        fn._minimised = minimised
    return fn._minimised


def _make_accumulate(node, payload):
    if payload == "assign":   # total += x -> total = x
        return ast.Assign([copy_tree(node.target)], copy_tree(node.value))
    if payload == "MatMultLeft":   # H = step[j] -> H = step[j] @ H (a chain multiplied on the left)
        running = copy_tree(node.targets[0])
        running.ctx = ast.Load()
        return ast.Assign([copy_tree(node.targets[0])], ast.BinOp(copy_tree(node.value), ast.MatMult(), running))
    target = copy_tree(node.targets[0])   # total = x -> total += x
    target.ctx = ast.Store()
    return ast.AugAssign(target, getattr(ast, payload)(), copy_tree(node.value))


def _make_magnitude(node, payload):
    if payload == "wrap":   # a[i - j] -> a[np.abs(i - j)]
        return ast.Call(_name("np.abs"), [copy_tree(node)], [])
    new = copy_tree(node)   # np.argmin(v) -> np.argmin(np.abs(v))
    part = new.args[0].value if payload == "complex" else new.args[0]   # (v.real -> v: its modulus)
    new.args[0] = ast.Call(_name("np.abs"), [part], [])
    return new


def _make_summary(node, payload):
    return ast.Name(payload, ast.Load())   # the array's mean (a local) where one of its items was taken


def _make_carry(node, payload):
    return ast.Name(payload, ast.Load())   # the running result where the loop restarted from the input


def _make_negate(node, payload):
    if payload == "drop":   # not m -> m
        return copy_tree(node.operand)
    return ast.UnaryOp(ast.Not(), copy_tree(node))   # x > t -> not x > t


def _make_frame_cross(node, payload):
    new = copy_tree(node)   # e3 = mean / |mean| -> e3 = np.cross(e1, e2): a frame's axis from the other two
    first, second = payload
    new.value = ast.Call(_name("np.cross"), [ast.Name(first, ast.Load()), ast.Name(second, ast.Load())], [])
    return new


def _make_whole_vector(node, payload):
    # np.append(e[:2], 1.0) -> e, or e / e[2]: a homogeneous vector kept whole (or divided), not its third entry replaced
    return _parse(payload).body[0].value


def _make_quadrant(node, payload):
    # np.arctan(b / a) -> np.arctan2(b, a): the angle's quadrant from the signs of both
    ratio = node.args[0]
    return ast.Call(_name(payload), [copy_tree(ratio.left), copy_tree(ratio.right)], [])


def _make_swap_both(node, payload):
    # P1, P2 = P2, P1 -> P1, P2, pts1, pts2 = P2, P1, pts2, pts1: a pair exchanged with its twin pair
    first, second = payload
    new = copy_tree(node)
    new.targets[0].elts += [ast.Name(first, ast.Store()), ast.Name(second, ast.Store())]
    new.value.elts += [ast.Name(second, ast.Load()), ast.Name(first, ast.Load())]
    return new


DRAWING_COLOUR_AT = {"line": 3, "arrowedLine": 3, "rectangle": 3, "circle": 3, "drawMarker": 2, "ellipse": 6,
                     "polylines": 3, "fillPoly": 2, "fillConvexPoly": 2, "putText": 5}   # OpenCV's colour argument


def _drawn_colour(node, parents, fn) -> bool:
    """Whether ``node`` is (part of) the colour an OpenCV drawing call is given: inside its colour argument, or in
    the value of a name that argument is (`colour = ... if canvas.ndim == 3 else 1.0`, then `cv2.line(..., colour)`)."""
    holder = node
    while id(holder) in parents and not isinstance(holder, ast.stmt):
        parent, field, index = parents[id(holder)]
        if isinstance(parent, ast.Call) and field == "args" and _dotted(parent.func).startswith(("cv2.", "cv.")) \
                and DRAWING_COLOUR_AT.get(_dotted(parent.func).rsplit(".", 1)[-1]) == index:
            return True
        holder = parent
    if not (isinstance(holder, ast.Assign) and len(holder.targets) == 1 and isinstance(holder.targets[0], ast.Name)) \
            or fn is None:
        return False
    if not hasattr(fn, "_colour_names"):   # (read once per def: every constant 1 asks)
        fn._colour_names = {call.args[at].id for call in walk(fn)
                            if isinstance(call, ast.Call) and _dotted(call.func).startswith(("cv2.", "cv."))
                            and isinstance(at := DRAWING_COLOUR_AT.get(_dotted(call.func).rsplit(".", 1)[-1]), int)
                            and len(call.args) > at and isinstance(call.args[at], ast.Name)}
    return holder.targets[0].id in fn._colour_names


def _make_from_end(node, payload):
    return ast.UnaryOp(ast.USub(), copy_tree(node.right))   # len(A) - 1 -> -1: counted from the end


def _make_logic(node, payload):
    new = copy_tree(node)   # m1 & m2 <-> m1 | m2, a and b <-> a or b
    new.op = getattr(ast, payload)()
    return new


def _make_function(node, payload):
    new = copy_tree(node)
    if isinstance(node.func, ast.Name) and node.func.id == "int" and payload.endswith(".floor"):
        new.args = [ast.Call(_name(payload), new.args, [])]   # int(t) -> int(np.floor(t)): a whole number still
        return new
    new.func = _name(payload)
    return new


def _make_boolean_mask(node, payload):
    return ast.Call(ast.Attribute(copy_tree(node), "astype", ast.Load()), [ast.Name("bool", ast.Load())], [])


def _make_part(node, payload):
    return parse(payload, mode="eval").body   # a part of the array, as the function writes it elsewhere


_CUMULATIVE = {"cumsum", "cumprod", "nancumsum", "nancumprod"}
_RUNNING = {"cumsum": "running sum", "cumprod": "running product", "nancumsum": "running sum",
            "nancumprod": "running product", "np.minimum": "running minimum", "np.maximum": "running maximum",
            "numpy.minimum": "running minimum", "numpy.maximum": "running maximum"}


def _cumulative(call: ast.Call) -> bool:
    """A running result along an axis: ``np.cumsum``, ``np.minimum.accumulate`` (order matters)."""
    dotted = _dotted(call.func)
    return dotted.endswith(".accumulate") or dotted.rsplit(".", 1)[-1] in _CUMULATIVE


def _running(call: ast.Call) -> str:
    """"running minimum" for ``np.minimum.accumulate``, "running sum" for ``np.cumsum``."""
    dotted = _dotted(call.func)
    return _RUNNING.get(dotted.rsplit(".", 1)[0] if dotted.endswith(".accumulate") else dotted.rsplit(".", 1)[-1],
                        "running result")


def _slice_text(index) -> str:
    """``:, ::-1`` for the index of ``x[:, ::-1]`` (unparsed alone, a tuple gets brackets)."""
    return ", ".join(ast.unparse(part) for part in index.elts) if isinstance(index, ast.Tuple) else ast.unparse(index)


def _reversal(node):
    """The slice of ``node`` (a subscript) that reverses an axis (``x[:, ::-1]``, ``x[::-1]``), or None."""
    if not isinstance(node, ast.Subscript):
        return None
    parts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
    reversing = [p for p in parts if isinstance(p, ast.Slice) and p.lower is None and p.upper is None
                 and isinstance(p.step, ast.UnaryOp) and isinstance(p.step.op, ast.USub)
                 and isinstance(p.step.operand, ast.Constant) and p.step.operand.value == 1]
    whole = all(isinstance(p, ast.Slice) and p.lower is None and p.upper is None for p in parts)
    return node.slice if reversing and whole else None


def _make_written(node, payload):
    return parse(payload, mode="eval").body   # the new expression, written out by the operator


def _make_index_step(node, payload):
    new = copy_tree(node)   # out[y, x] = d -> out[y, x - 1] = d
    position, delta = payload
    stepped = ast.BinOp(new.slice.elts[position] if isinstance(new.slice, ast.Tuple) else new.slice,
                        ast.Sub() if delta < 0 else ast.Add(), ast.Constant(abs(delta)))
    if isinstance(new.slice, ast.Tuple):
        new.slice.elts[position] = stepped
    else:
        new.slice = stepped
    return new


def _make_store_name(node, payload):
    new = copy_tree(node)   # n = f(w) -> needed = f(w): the value stored under another name
    new.targets = [ast.Name(payload, ast.Store())]
    return new


def _make_constant(node, payload):
    return ast.Constant(payload)   # a condition made constant: the guard it is removed (see repair)


_MAKE = {**{name: _make_written for name in ("einsum", "sibling_line", "map_whole", "unflip", "like_input", "append_extend", "last_row", "per_item", "estimator", "stack_last", "swap_axes", "scale_xy", "neutral",
                                              "unused_name", "twin_test", "drop_epsilon", "twin_values",
                                              "chosen_value", "add_stacked", "middle_axis", "widen", "bracket", "perspective_warp",
                                              "x_difference", "colour_axis", "drop_w", "power_xor", "identity", "half_pixel", "grid_axis", "initial", "reshape_back", "astype_float",
                                              "divide_last", "unused", "drop_colour", "zero_based", "convert_if", "exchange", "zero_entry",
                                              "true_division", "factor_two", "by_last", "ufunc_out", "empty_slice", "divided_by_w",
                                              "keep_axis", "column_order", "rounding", "rank", "denormalise",
                                              "other_result", "whole_shape", "move_factor", "convert_first", "precedence",
                                              "drop_term", "one_of_two", "focal_left_out", "perpendicular", "key_order", "to_degrees", "type_widened", "size_written", "midrange", "reverse_back", "drop_reversal", "loop_order",
                                              "matrix_applied", "series_powers", "counted", "default_written", "fraction", "crossed", "loop_item", "conversion_inverted", "factor_transposed",
                                              "twin_factor", "homogeneous_one", "moved_term", "reduced", "squared_bound",
                                              "translation_scaled", "exact_constant", "colour_scale", "aligned")},
         "drop_keyword": _make_drop_keyword, "method_given": _make_method_given, "neutral_argument": _make_neutral_argument, "drop_argument": _make_drop_argument, "drop_flag": _make_drop_flag, "stride": _make_stride, "simultaneous": _make_simultaneous,
         "move": _make_move, "add_step": _make_move, "indent": _make_indent, "keep_parameter": _make_keep_parameter, "undecomposed": _make_undecomposed, "slice_order": _make_slice_order, "map_term": _make_map_term, "centre_translation": _make_centre_translation, "dedent": _make_dedent, "hoist": _make_hoist, "grey": _make_grey, "guard": _make_guard, "lower_bound": _make_lower_bound,
         "translation": _make_translation, "constant": _make_constant, "literal": _make_constant, "boolean_mask": _make_boolean_mask, "negative_index": _make_magnitude, "part": _make_part, "identity": _make_part, "first_term": _make_part, "measure_first": _make_part, "summary": _make_summary, "mirror": _make_twin_step, "chain_order": _make_chain_order, "magnitude": _make_magnitude, "carry": _make_carry, "accumulate": _make_accumulate, "fill_inf": _make_fill_inf, "jump_size": _make_jump_size, "len_axis": _make_len_axis, "negate": _make_negate, "logic": _make_logic, "from_end": _make_from_end, "frame_cross": _make_frame_cross,
         "whole_vector": _make_whole_vector, "quadrant": _make_quadrant, "swap_both": _make_swap_both,
         "power_spread": _make_power_spread, "keep_result": _make_keep_result, "add_axis": _make_add_axis,
         "flip_keyword": _make_flip_keyword, "float32": _make_float32, "python_numbers": _make_python_numbers, "size_given": _make_size_given, "twin_step": _make_twin_step, "twin_argument": _make_twin_argument, "measure": _make_measure, "power_inside": _make_power_inside,
         "slice": _make_slice, "slice_item": _make_slice_item, "row_column": _make_row_column, "drop_slice": _make_drop_slice, "canvas": _make_canvas, "loop_all": _make_loop_all, "compare": _make_compare, "regroup": _make_regroup, "dtype": _make_dtype, "sibling_step": _make_sibling_step, "factor_pair": _make_factor_pair, "select_mask": _make_select_mask, "sibling_argument": _make_sibling_argument, "swap_items": _make_swap_items, "cross_items": _make_cross_items, "dehomogenise": _make_dehomogenise, "unwrap": _make_unwrap, "own_values": _make_own_values, "scale_inverse": _make_scale_inverse, "function": _make_function, "other_name_line": _make_other_name_line, "arithmetic": _make_arithmetic, "stack_kind": _make_stack_kind, "drop_mask": _make_drop_mask,
         "reshape_transpose": _make_reshape_transpose, "int_base": _make_int_base, "loop_counter": _make_loop_counter, "shape_reversed": _make_shape_reversed, "flat_column": _make_flat_column, "count_rows": _make_count_rows, "unpack_pair": _make_unpack_pair, "source_names": _make_source_names, "tile_repeat": _make_tile_repeat, "square_window": _make_square_window, "stack_window": _make_stack_window, "per_image": _make_per_image, "flip_reduction": _make_flip_reduction, "cross_multiply": _make_cross_multiply, "clip_range": _make_clip_range, "flip_axis": _make_flip_axis, "row_kron": _make_row_kron, "math_numpy": _make_math_numpy, "shift": _make_shift, "loop_index": _make_loop_index, "sign": _make_sign, "add_sub": _make_add_sub, "swap_operands": _make_swap_operands,
         "swap_args": _make_swap_args, "transpose": _make_transpose, "degrees": _make_degrees,
         "axis": _make_axis, "minmax": _make_minmax, "flag": _make_flag, "bound": _make_bound,
         "int_division": _make_int_division, "drop_division": _make_drop_division,
         "drop_factor": _make_drop_factor, "drop_centring": _make_drop_centring,
         "drop_conversion": _make_drop_conversion, "float_kept": _make_float_kept, "other_name": _make_other_name, "derived_name": _make_other_name, "in_place": _make_in_place,
         "drop_statement": _make_drop_statement, "store_name": _make_store_name, "index_step": _make_index_step, "extra_step": _make_drop_statement, "reshape_order": _make_reshape_order,
         "inverse": _make_inverse, "stack_order": _make_stack_order, "default": _make_default,
         "single_point": _make_single_point}


# ------------------------------------------------------------------ describing, in the student's terms
_PARAMETER_WORDS = {"src": "the source points", "dst": "the destination points",
                    "src_n": "the normalised source points", "dst_n": "the normalised destination points",
                    "pts": "the points", "points": "the points", "x1": "the points of image 1",
                    "x2": "the points of image 2", "left": "the left image", "right": "the right image"}


class _Words:
    """Phrases for expressions of one ``def``: API parameters by name, locals by what they hold."""

    def __init__(self, fn: ast.FunctionDef, api_params: set[str], module_defs: dict, api: set[str],
                 student: bool = False):
        self.fn, self.api_params, self.module_defs, self.api = fn, api_params, module_defs, api
        # The student's own code is shown, not told: any expression is its own phrase (its text),
        # and every call's arguments may be swapped (a helper of theirs, too).
        self.student = student
        # A private helper's parameters told by what they hold, where the name says it plainly
        # (`src` in a helper building the design matrix: "the source points"); else nothing.
        self.helper_params = {} if fn.name in api else {
            a.arg: _PARAMETER_WORDS[a.arg] for a in fn.args.args if a.arg in _PARAMETER_WORDS}
        self.definitions: dict[str, list[tuple[int, ast.AST, int | None]]] = {}
        self.zipped: dict[str, set] = {}   # name -> its siblings: looped over beside it (zip), or one item's parts
        for node in walk(fn):
            if isinstance(node, ast.Assign):
                for target in node.targets:
                    self._define(target, node.value, node.lineno)
            elif isinstance(node, (ast.AugAssign, ast.AnnAssign)) and node.value is not None:
                self._define(node.target, node.value if isinstance(node, ast.AnnAssign) else node, node.lineno)
            elif isinstance(node, (ast.For, ast.comprehension)):
                self._define_loop(node.target, node.iter, getattr(node, "lineno", getattr(node.iter, "lineno", 0)))
        for names in unpacked_items(fn):   # (`m, n = pair` in a loop over knnMatch's pairs: siblings too)
            for name in names:
                self.zipped.setdefault(name, set()).update(names - {name})
        # A loop's own variable that nothing reads (`[f(X, f) for fl in f]`): the name that was to be used
        # in it, line of the loop -> names (a comprehension's, in scope on its own line too)
        read = {n.id for n in walk(fn) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
        self.unread_loop_names: dict[int, set] = {}
        for node in walk(fn):
            if isinstance(node, (ast.For, ast.comprehension)):
                for target in walk(node.target):
                    if isinstance(target, ast.Name) and target.id not in read and target.id != "_":
                        self.unread_loop_names.setdefault(target.lineno, set()).add(target.id)

    def _define_loop(self, target, iterable, line):
        """A loop's targets: through ``enumerate`` (its item) and ``zip`` (each its own sequence),
        a name takes each item of what is looped over, a tuple's names each an entry of it."""
        if isinstance(iterable, ast.Call) and _dotted(iterable.func) == "enumerate" and iterable.args \
                and isinstance(target, ast.Tuple) and len(target.elts) == 2:
            self._define_loop(target.elts[1], iterable.args[0], line)   # (the position has no words)
        elif isinstance(iterable, ast.Call) and _dotted(iterable.func) == "zip" and isinstance(target, ast.Tuple) \
                and len(target.elts) == len(iterable.args):
            for part, sequence in zip(target.elts, iterable.args):
                self._define_loop(part, sequence, line)
            # (the items of sequences zipped together: `p, q` of `zip(pts1, pts2)`, each the other's sibling)
            names = {part.id for part in target.elts if isinstance(part, ast.Name)}
            for name in names:
                self.zipped.setdefault(name, set()).update(names - {name})
        else:
            self._define(target, ast.Call(ast.Name("__loop__", ast.Load()), [iterable], []), line)
            if isinstance(target, ast.Tuple):   # (the parts of one item, `m, n` of a knnMatch pair: siblings)
                names = {part.id for part in target.elts if isinstance(part, ast.Name)}
                for name in names:
                    self.zipped.setdefault(name, set()).update(names - {name})

    def _define(self, target, value, line):
        if isinstance(target, ast.Name):
            self.definitions.setdefault(target.id, []).append((line, value, None))
        elif isinstance(target, (ast.Tuple, ast.List)):
            for index, element in enumerate(target.elts):
                if isinstance(element, ast.Name):
                    self.definitions.setdefault(element.id, []).append((line, value, index))

    def loops_up_to(self, line: int, nearest: int = 2) -> list[int]:
        """The lines of the ``nearest`` loops with an unread variable at or above ``line`` (a bisection: each
        use looks at a bounded number of loops, whatever the def's length)."""
        if not hasattr(self, "_unread_lines"):
            self._unread_lines = sorted(self.unread_loop_names)
        return self._unread_lines[max(0, bisect.bisect_right(self._unread_lines, line) - nearest):
                                  bisect.bisect_right(self._unread_lines, line)]

    def locals_before(self, line: int, nearest: int | None = None) -> list[str]:
        """The def's parameters and the locals assigned before ``line`` (``nearest``: only that many
        of the locals, the last assigned before it -- the student's code: each use compared with a
        bounded number of names, so reading a long function stays linear in its length)."""
        names = [a.arg for a in self.fn.args.args + self.fn.args.kwonlyargs]
        if nearest is None:
            names += [name for name, defs in self.definitions.items() if any(at < line for at, _, _ in defs)]
            return list(dict.fromkeys(names))
        if not hasattr(self, "_first_lines"):   # (the line a name is first assigned, the name), by line
            self._first_lines = sorted((min(at for at, _, _ in defs), name) for name, defs in self.definitions.items())
        before = self._first_lines[:bisect.bisect_left(self._first_lines, (line, ""))]
        names += [name for _, name in before[-nearest:]]
        return list(dict.fromkeys(names))

    def related(self, line: int) -> frozenset:
        """The names read where the names read on ``line`` are assigned (`lit = ... (proj >= 0) ...` for a
        line reading `cols[lit]`): what the line's values were made from, kept per line."""
        if not hasattr(self, "_related"):
            self._related, self._read_on = {}, {}
            for node in walk(self.fn):
                if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
                    self._read_on.setdefault(node.lineno, set()).add(node.id)
        if line not in self._related:
            made_from = set()
            for name in self._read_on.get(line, ()):
                for at, value, _ in self.definitions.get(name, ())[-2:]:
                    if at < line:
                        made_from |= {n.id for n in walk(value) if isinstance(n, ast.Name)}
            self._related[line] = frozenset(made_from)
        return self._related[line]

    def what(self, node, depth: int = 0, line: int | None = None) -> str:
        """A short phrase for ``node`` (never a local or private name); "" when none fits. (The
        student's code: its text.)"""
        if self.student:
            text = ast.unparse(node)
            return f"`{text}`" if len(text) <= _MAX_PHRASE else ""
        line = line if line is not None else getattr(node, "lineno", 10**9)
        for start in (depth, depth + 2, depth + 4):  # deeper starts say less: a shorter phrase
            phrase = self._what(node, start, line)
            if len(phrase) <= _MAX_PHRASE:
                return phrase
        return ""

    def _what(self, node, depth, line) -> str:
        if depth > 6:
            return ""
        if isinstance(node, ast.Name):
            if node.id in self.api_params:
                return f"`{node.id}`"
            before = [d for d in self.definitions.get(node.id, ()) if d[0] < line]
            if not before and node.id in self.helper_params:
                return self.helper_params[node.id]
            defs = before or self.definitions.get(node.id, [])
            if not defs:
                return ""
            at, value, index = defs[-1]
            if isinstance(value, ast.AugAssign):
                return self._what(value.target, depth, at)
            if index is not None:
                shape_of = _shape_source(value)
                if shape_of is not None and index < 3:
                    inner = self._what(shape_of, depth + 1, at)
                    which = ("height", "width", "number of channels")[index]
                    return f"the {which} of {inner}" if inner else ""
                if isinstance(value, (ast.Tuple, ast.List)) and index < len(value.elts):
                    return self._what(value.elts[index], depth + 1, at)
                if isinstance(value, ast.Call) and _dotted(value.func) == "__loop__" and index < len(_ORDINALS):
                    looped = self._what(value.args[0], depth + 1, at)
                    return f"the {_ORDINALS[index]} entry of each item of {looped}" if looped else ""
                if index == 0 and isinstance(value, ast.Call) and _dotted(value.func) in self.module_defs \
                        and _dotted(value.func) not in self.api and value.args:
                    return self._what(value.args[0], depth + 1, at)  # a helper that prepares its input
                whole = self._what(value, depth + 1, at)
                return f"result {index + 1} of {whole}" if whole else ""
            return self._what(value, depth + 1, at)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return repr(node.value)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            inner = self._what(node.operand, depth + 1, line)
            return f"minus {inner}" if inner else ""
        if isinstance(node, ast.Attribute):
            if node.attr == "T":
                inner = self._what(node.value, depth + 1, line)
                return f"the transpose of {inner}" if inner else ""
            if node.attr == "shape":
                inner = self._what(node.value, depth + 1, line)
                return f"the shape of {inner}" if inner else ""
            dotted = _dotted(node)
            return f"`{dotted}`" if dotted.startswith(("cv2.", "np.")) else ""
        if isinstance(node, ast.Subscript):
            return self._subscript(node, depth, line)
        if isinstance(node, ast.Call):
            return self._call(node, depth, line)
        if isinstance(node, ast.BinOp) and depth < 2:
            left, right = self._what(node.left, depth + 1, line), self._what(node.right, depth + 1, line)
            if not (left and right):
                return ""
            word = {ast.Add: "plus", ast.Sub: "minus", ast.Mult: "times", ast.Div: "divided by",
                    ast.FloorDiv: "divided by"}.get(type(node.op))
            if isinstance(node.op, ast.MatMult):
                return f"the product of {left} and {right}"
            return f"{left} {word} {right}" if word else ""
        if isinstance(node, (ast.Tuple, ast.List)) and 0 < len(node.elts) <= 3:
            parts = [self._what(e, depth + 1, line) for e in node.elts]
            return f"({', '.join(parts)})" if all(parts) else ""
        return ""

    def _subscript(self, node, depth, line) -> str:
        if isinstance(node.value, ast.Attribute) and node.value.attr == "shape" \
                and isinstance(node.slice, ast.Constant):
            inner = self._what(node.value.value, depth + 1, line)
            which = {0: "height (number of rows)", 1: "width (number of columns)", 2: "number of channels",
                     -1: "last dimension"}.get(node.slice.value, f"dimension {node.slice.value}")
            return f"the {which} of {inner}" if inner else ""
        index = node.slice
        if isinstance(node.value, ast.Call) and _dotted(node.value.func).endswith("linalg.svd") \
                and isinstance(index, ast.Constant) and index.value in (0, 1, 2) and node.value.args:
            of = self._what(node.value.args[0], depth + 1, line)
            part = ("U (the left singular vectors)", "the singular values",
                    "Vt (the right singular vectors, as rows)")[index.value]
            return f"{part} of the SVD of {of}" if of else f"{part} of an SVD"
        inner = self._what(node.value, depth + 1, line)
        if not inner:
            return ""
        if isinstance(index, ast.Constant) and isinstance(index.value, int):
            return f"{'the last' if index.value == -1 else f'element {index.value}'} of {inner}"
        if isinstance(index, ast.Tuple) and len(index.elts) == 2:
            first, second = index.elts
            if all(isinstance(e, ast.Constant) and isinstance(e.value, int) for e in index.elts):
                return f"entry [{first.value}, {second.value}] of {inner}"
            if _whole_slice(first) and isinstance(second, ast.Constant) and isinstance(second.value, int):
                name = {0: "the x coordinates (column 0)", 1: "the y coordinates (column 1)"}.get(
                    second.value, f"column {second.value}")
                return f"{name} of {inner}"
            if isinstance(first, ast.Constant) and isinstance(first.value, int) and _whole_slice(second):
                return f"{'the last row' if first.value == -1 else f'row {first.value}'} of {inner}"
        block = _block_text(index)
        return f"{block} of {inner}" if block else f"part of {inner}"

    def _call(self, node, depth, line) -> str:
        dotted = _dotted(node.func)
        first = node.args[0] if node.args else None
        arg = self._what(first, depth + 1, line) if first is not None else ""
        short = dotted.rsplit(".", 1)[-1]
        if dotted == "__loop__":
            return f"each item of {arg}" if arg else ""
        if short in ("sin", "cos", "tan") and arg:
            return f"the {dict(sin='sine', cos='cosine', tan='tangent')[short]} of {arg}"
        if dotted in _ANGLE_CONVERSIONS and arg:
            return f"{arg} in {_ANGLE_CONVERSIONS[dotted]}"
        if short in ("asarray", "array", "float64", "float", "atleast_2d", "ascontiguousarray", "copy",
                     "astype") and isinstance(first, (ast.Name, ast.Subscript, ast.Attribute)):
            return arg
        if isinstance(node.func, ast.Attribute) and node.func.attr in ("astype", "copy", "reshape", "ravel"):
            return self._what(node.func.value, depth + 1, line)
        if short in ("array", "asarray") and isinstance(first, ast.List):
            parts = [self._what(e, depth + 2, line) for row in first.elts
                     for e in (row.elts if isinstance(row, ast.List) else [row])]
            parts = list(dict.fromkeys(p for p in parts if p and not p[0].isdigit()))[:2]
            built = f"the matrix built from {' and '.join(parts)}"
            return built if parts and len(built) <= _MAX_PHRASE // 2 else "the matrix built there"
        if dotted in ("np.eye", "np.identity"):
            return "the matrix started from the identity"
        named = {"inv": "the inverse of", "svd": "the SVD of", "norm": "the norm of", "pinv": "the pseudo-inverse of",
                 "det": "the determinant of", "eig": "the eigendecomposition of", "qr": "the QR decomposition of",
                 "sqrt": "the square root of", "hstack": "the columns stacked from", "vstack": "the rows stacked from",
                 "column_stack": "the columns stacked from"}.get(short)
        if named and dotted.startswith(("np.", "numpy.")):
            return f"{named} {arg}" if arg else f"the result of `{dotted}`"
        if dotted in self.api:
            return f"what `{dotted}` returns"
        if dotted in self.module_defs:   # on its argument, when it has words: T1 and T2 of src and dst
            step = step_phrase(self.module_defs[dotted])
            return (f"the result of {step}" + (f" on {arg}" if arg else "")) if step else arg
        if dotted.startswith(("cv2.", "np.")):
            return f"the result of `{dotted}`"
        return ""


def _shape_source(value):
    """``x`` when ``value`` is ``x.shape`` or ``x.shape[:k]`` (unpacked into height, width...)."""
    if isinstance(value, ast.Subscript) and isinstance(value.slice, ast.Slice) and value.slice.lower is None:
        value = value.value
    if isinstance(value, ast.Attribute) and value.attr == "shape":
        return value.value
    return None


def _block_text(index) -> str:
    """"rows 0-1, column 2" for ``[:2, 2]``; "" when the index is not constants and constant slices."""
    elements = index.elts if isinstance(index, ast.Tuple) else [index]
    words = []
    for axis, element in zip(("row", "column"), elements):
        if isinstance(element, ast.Constant) and isinstance(element.value, int):
            words.append(f"{'the last ' + axis if element.value == -1 else f'{axis} {element.value}'}")
        elif isinstance(element, ast.Slice) and element.step is None and all(
                b is None or (isinstance(b, ast.Constant) and isinstance(b.value, int) and b.value >= 0)
                for b in (element.lower, element.upper)):
            lower = element.lower.value if element.lower is not None else 0
            if element.upper is None:
                words.append(f"{axis}s {lower} onwards" if lower else f"all {axis}s")
            elif element.upper.value == lower + 1:
                words.append(f"{axis} {lower}")
            else:
                words.append(f"{axis}s {lower}-{element.upper.value - 1}")
        else:
            return ""
    return ", ".join(words) if len(elements) <= 2 else ""


def _whole_slice(node) -> bool:
    return isinstance(node, ast.Slice) and node.lower is None and node.upper is None and node.step is None


def step_phrase(fn: ast.FunctionDef) -> str:
    """A private helper told as the step it does, from its docstring's first sentence: "the
    step that normalises the points"; "" without a docstring."""
    doc = ast.get_docstring(fn) or ""
    first = re.split(r"(?<=[a-z\)])[.:;](\s|$)", doc.strip().split("\n\n")[0].replace("\n", " "))[0]
    first = re.sub(r"``([^`]*)``", r"\1", first).strip()
    if not first or len(first) > 90 or re.search(r"[=_\[\]`]|\w\.\w", first):  # code, not words
        return ""
    return f"the step \"{first[0].lower() + first[1:]}\""


# ------------------------------------------------------------------ generating
@functools.lru_cache(maxsize=16)
def _module_defs(source: str) -> dict:
    """The module's defs by name, parsed once per text (read only: every change is made on a copy)."""
    return _defs(_parse(source))


@functools.lru_cache(maxsize=512)
def _def_sites(source: str, api: frozenset, phrased: bool, name: str) -> list:
    """[(operator, ordinal, payload, line, phrase)], the sites of the def ``name`` (``phrased``: only
    those the operators can tell in words), read only when a function that runs it is asked for: a
    student's whole module is many defs, and a failed check needs one function's."""
    defs = _module_defs(source)
    fn = defs[name]
    params = {a.arg for a in fn.args.args + fn.args.kwonlyargs} if name in api else set()
    return list(_sites(fn, _Words(fn, params, defs, set(api), student=not phrased), phrased))


def runs(defs: dict, function: str) -> list[str]:
    """The module functions ``function`` runs (directly or not), itself first."""
    reached, queue = [], [function]
    while queue:
        name = queue.pop(0)
        if name not in reached and name in defs:
            reached.append(name)
            queue += _calls_of(defs[name], defs)
    return reached


def _calls_of(fn: ast.FunctionDef, defs: dict) -> list[str]:
    """The module functions ``fn`` names (a function named anywhere counts as called: a cost picked
    by ``(_ssd_volume if cost == "ssd" else _ncc_volume)(...)``, a helper passed as a callback)."""
    return list(dict.fromkeys(n.id for n in walk(fn) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)
                              and n.id in defs and n.id != fn.name))


def mutants_of(source: str, api, phrased: bool = True, functions=None) -> dict[str, list[Mutant]]:
    """API function -> its mutants: edits in its own ``def`` and in every module function it
    calls (directly or not), each once (the first of the edits giving the same code).

    ``source`` is the reference module's text; ``api`` the graded function names; ``functions``
    those of them whose mutants are made (default: all). ``phrased`` False keeps the changes no
    sentence tells too (their sentence is the place alone): a change of the student's own code is
    told by showing it (:mod:`.repair`).
    """
    api = frozenset(api)
    defs = _module_defs(source)
    out = {}
    for function in sorted(api & set(defs) & (set(functions) if functions is not None else set(api))):
        mutants = []
        for where in runs(defs, function):
            context = _context(function, where, defs, api)
            for operator, ordinal, payload, line, phrase in _def_sites(source, api, phrased, where):
                place = f"in `{function}`{context}, "
                edits = ((where, ordinal, operator, payload),)
                if operator in _MOVES and payload[0] is not None:   # (the statement made at the edited node
                    edits += ((where, payload[0], "drop_statement", None),)   # is removed where it was)
                if operator == "counted_sized":   # (the count and the sizes it gives, changed together)
                    parameter, sizes = payload
                    operator = "counted"
                    edits = ((where, ordinal, operator, f"range(len({parameter}))"),) + tuple(
                        (where, at, operator, f"{factor} * len({parameter})" if factor > 1 else f"len({parameter})")
                        for at, factor in sizes)
                mutants.append(Mutant(operator, function, where, line, edits, place + phrase, place))
        out[function] = mutants
    return out


def _context(function: str, where: str, defs: dict, api) -> str:
    if where == function:
        return ""
    if where in api:
        return f" (in `{where}`, which it calls)"
    step = step_phrase(defs[where])
    return f", in {step}" if step else ", in a step it runs"


def _sites(fn: ast.FunctionDef, words: _Words, phrased: bool = True):
    """(operator, ordinal, payload, line, phrase) for every change the operators make in ``fn``
    (``phrased``: only those with a phrase)."""
    nodes = list(walk(fn))
    parents = _parents(fn)
    seen = set()
    for ordinal, node in enumerate(nodes):
        if ordinal == 0 or _in_docstring(node, fn):
            continue
        line = getattr(node, "lineno", None) or getattr(parents.get(id(node), (fn,))[0], "lineno", fn.lineno)
        for operator, payload, phrase in _changes(node, parents, words, line):
            if not phrase and phrased:
                continue
            try:
                before = ast.unparse(node)
                after = ast.unparse(ast.fix_missing_locations(_MAKE[operator](node, payload)))
            except Exception:  # noqa: BLE001 - an edit that cannot be written is not a mutant
                continue
            if before == after or (ordinal, after) in seen:
                continue
            seen.add((ordinal, after))
            yield operator, ordinal, payload, line, phrase
    if words.student:
        ordinals = {id(node): ordinal for ordinal, node in enumerate(nodes)}
        for returned, undone in _denormalisations(fn):
            yield "denormalise", ordinals[id(returned)], undone, returned.lineno, ""
        for first, second in _sequential_updates(fn):
            yield "simultaneous", ordinals[id(first)], (ordinals[id(second)], ast.unparse(second.targets[0]),
                                                         ast.unparse(second.value)), first.lineno, ""
        # A statement in the wrong place: the payload's first item is the statement the change removes
        # from where it was (made again at the edited node), None when the edited node holds it.
        for start, text in _recurrence_starts(fn):
            yield "first_term", ordinals[id(start)], text, start.lineno, ""
        for loop, k, name, fresh in _overwritten_in_loop(fn):
            yield "keep_parameter", ordinals[id(loop)], (k, name, fresh), loop.body[k].lineno, ""
        for operator, edited, moved, side in _statement_moves(fn):
            removed = ordinals[id(moved)] if operator not in ("dedent", "hoist") else None
            yield operator, ordinals[id(edited)], (removed, ast.unparse(moved), moved.lineno, side), moved.lineno, ""
        # A loop counted by a number written in the code beside an array sized by it: the count and the
        # sizes changed together (`np.zeros((12, 12))` and `for i in range(6)`: only six points used)
        params = [a.arg for a in fn.args.args]
        for loop, sizes in _counted_with_sizes(fn):
            for parameter in params:
                yield "counted_sized", ordinals[id(loop)], (parameter, tuple(
                    (ordinals[id(size)], factor) for size, factor in sizes)), loop.lineno, ""


_ALLOCATIONS = {"zeros", "empty", "ones", "full"}


def _counted_with_sizes(fn):
    """(range(C) call, [(constant k * C in an allocation's shape, k)]) for each loop counted by a number
    C >= 2 written in the code whose array, made in the same def, is sized by C, 2 C or 3 C (its rows)."""
    allocated = {}   # rows -> the constants writing them (looked up per loop: linear in the def)
    for node in walk(fn):
        if isinstance(node, ast.Call) and _dotted(node.func).rsplit(".", 1)[-1] in _ALLOCATIONS and node.args \
                and isinstance(node.args[0], ast.Tuple) and node.args[0].elts:
            first = node.args[0].elts[0]
            if isinstance(first, ast.Constant) and type(first.value) is int:
                allocated.setdefault(first.value, []).append(first)
    for node in walk(fn):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "range" \
                and len(node.args) == 1 and isinstance(node.args[0], ast.Constant) \
                and type(node.args[0].value) is int and node.args[0].value >= 2:
            count = node.args[0].value
            sizes = [(size, factor) for factor in (1, 2, 3) for size in allocated.get(factor * count, ())]
            if sizes:
                yield node, sizes


_SIMPLE = (ast.Assign, ast.AugAssign, ast.Expr, ast.Return)
_MOVE_REACH = 3   # statements a statement is moved past, at most
_LEAVES = (ast.Continue, ast.Break, ast.Return, ast.Raise)


def _assigned(statement) -> set:
    targets = statement.targets if isinstance(statement, ast.Assign) else \
        [statement.target] if isinstance(statement, ast.AugAssign) else []
    return {n.id for t in targets for n in walk(t) if isinstance(n, ast.Name)}


def _read(node) -> set:
    return {n.id for n in walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}


def _reader_moves(statements, k):
    """A value read from a name before the update of that name it was to see, or after the one it
    was to come before: `scale = K[2, 2]` above the sign fix `K = K @ signs` moved after it (and
    back), when no statement it is moved past reads or sets what it makes."""
    statement = statements[k]
    made, reads = _assigned(statement), _read(statement)

    def passable(passed) -> bool:
        return not any((_read(s) | _assigned(s)) & made for s in passed)
    later = statements[k + 1:k + 1 + _MOVE_REACH]
    # (an update made only when a test holds counts: `if dsize is not None: w, h = dsize` below
    # `size = (w, h)`, the size read before it is decided)
    update = next((s for s in later if (isinstance(s, _SIMPLE) and _assigned(s) & reads)
                   or (isinstance(s, ast.If) and _updates_in_branch(s) & reads)), None)
    if update is not None and not isinstance(update, _LEAVES) and passable(later[:later.index(update) + 1]):
        yield "move", update, statement, "after"
    earlier = statements[max(0, k - _MOVE_REACH):k]
    update = next((s for s in reversed(earlier) if isinstance(s, _SIMPLE) and _assigned(s) & _read(s) & reads), None)
    if update is not None and passable(earlier[earlier.index(update):]):
        yield "move", update, statement, "before"


def _rebinding_moves(statements, k):
    """A value read from a name after a fresh value -- not an update of its own -- replaced the one it
    had before, where the old was meant: `x, y = src[i]` ... `x, y = dst[i]` ... `M[r] = [0, 0, 0, x, y, 1]`
    moved before the second binding (a student reusing names for the next point too early)."""
    statement = statements[k]
    reads = _read(statement)
    earlier = statements[max(0, k - _MOVE_REACH):k]
    rebinding = next((s for s in reversed(earlier) if isinstance(s, ast.Assign) and (_assigned(s) & reads) - _read(s)
                      and _bound_in((_assigned(s) & reads) - _read(s), statements[:statements.index(s)])), None)
    if rebinding is not None:
        container = _containers_set(statement)
        passed = earlier[earlier.index(rebinding):]
        if not any((_read(s) | _assigned(s)) & container for s in passed) \
                and not any(_containers_set(s) & reads for s in passed[1:]):
            yield "move", rebinding, statement, "before"


def _bound_in(names: set, statements) -> bool:
    """Whether any of ``names`` is given a value by one of ``statements`` (simple ones, at their level)."""
    return any(isinstance(s, (ast.Assign, ast.AugAssign)) and _assigned(s) & names for s in statements)


def _containers_set(statement) -> set:
    """The names an assignment gives a value to or writes into (`M` of `M[2 * i] = ...`; not its index)."""
    targets = statement.targets if isinstance(statement, ast.Assign) else \
        [statement.target] if isinstance(statement, ast.AugAssign) else []
    made = set()
    for target in targets:
        while isinstance(target, (ast.Subscript, ast.Attribute)):
            target = target.value
        made |= {n.id for n in walk(target) if isinstance(n, ast.Name)}
    return made


def _recurrence_starts(fn):
    """(the number, the text replacing it): a recurrence's first item set to a number (`energy[0] = 0.0`)
    above a loop filling the next items as a term of their own plus the rest (`energy[x] = costs[x] +
    best`): the first item is that term at its own index (`costs[0]`), the sum of nothing before it."""
    for block in walk(fn):
        statements = getattr(block, "body", None)
        if not isinstance(statements, list):
            continue
        for k, statement in enumerate(statements):
            if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1
                    and isinstance(statement.targets[0], ast.Subscript) and isinstance(statement.targets[0].value, ast.Name)
                    and isinstance(statement.targets[0].slice, ast.Constant) and isinstance(statement.value, ast.Constant)
                    and isinstance(statement.value.value, (int, float))):
                continue
            array, first = statement.targets[0].value.id, statement.targets[0].slice.value
            for loop in statements[k + 1:k + 3]:
                if not (isinstance(loop, ast.For) and isinstance(loop.target, ast.Name)):
                    continue
                step = loop.target.id
                for inner in walk(loop):
                    if isinstance(inner, ast.Assign) and len(inner.targets) == 1 \
                            and isinstance(inner.targets[0], ast.Subscript) and isinstance(inner.targets[0].value, ast.Name) \
                            and inner.targets[0].value.id == array and isinstance(inner.targets[0].slice, ast.Name) \
                            and inner.targets[0].slice.id == step:
                        terms = _summed_terms(inner.value) or []
                        for sign, term in terms[:1]:
                            if sign == "+" and isinstance(term, ast.Subscript) and isinstance(term.value, ast.Name) \
                                    and term.value.id != array and isinstance(term.slice, ast.Name) and term.slice.id == step:
                                yield statement.value, f"{term.value.id}[{first!r}]"


def _updates_in_branch(test: ast.If) -> set:
    """The names an ``if`` (without loops in it) assigns in its branches' simple statements."""
    if any(isinstance(n, (ast.For, ast.While)) for n in walk(test)):
        return set()
    return {name for s in test.body + test.orelse if isinstance(s, (ast.Assign, ast.AugAssign)) for name in _assigned(s)}


def _overwritten_in_loop(fn):
    """(loop, k, name, fresh): a parameter given a new value from its own in a loop's body, its k-th
    statement (`f0 = f0 * d / z0`, `scale *= s`), and nowhere else: each turn after the first starts from
    the turn before's value where the parameter's own was meant. ``fresh``: a name for each turn's value."""
    params = {a.arg for a in (*fn.args.posonlyargs, *fn.args.args, *fn.args.kwonlyargs)}
    used = params | {n.id for n in walk(fn) if isinstance(n, ast.Name)}
    stores = Counter(n.id for n in walk(fn) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store))
    for loop in (n for n in walk(fn) if isinstance(n, ast.For)):
        for k, statement in enumerate(loop.body):
            target = statement.targets[0] if isinstance(statement, ast.Assign) and len(statement.targets) == 1 \
                else statement.target if isinstance(statement, ast.AugAssign) else None
            if not (isinstance(target, ast.Name) and target.id in params and stores[target.id] == 1):
                continue
            if isinstance(statement, ast.Assign) and target.id not in _read(statement.value):
                continue
            base = target.id.rstrip("0123456789_")
            fresh = next(name for name in (base, f"{base}_now", f"{target.id}_now") if name and name not in used)
            yield loop, k, target.id, fresh


def _statement_moves(fn):
    """(operator, edited, moved, side): statements a student puts in the wrong place. An update of a
    name (`K = K / K[2, 2]`, `x += d`) made before a statement reading the old value, or after one that
    needs the new (moved past it: "move", side "after" or "before" the edited statement); a statement
    just after a loop or an ``if`` that belongs as its body's last ("indent": `best = inliers` left out
    of `if count > best_count:`); a loop's or an ``if``'s last statement that belongs after it
    ("dedent": a `return` inside the loop)."""
    for block in walk(fn):
        for field in ("body", "orelse"):
            statements = getattr(block, field, None)
            if not isinstance(statements, list) or not statements or not isinstance(statements[0], ast.stmt):
                continue
            for k, statement in enumerate(statements):
                updated = _assigned(statement) & _read(statement) if isinstance(statement, (ast.Assign, ast.AugAssign)) \
                    else set()
                if isinstance(statement, ast.AugAssign):
                    updated |= _assigned(statement)
                if updated:
                    later = statements[k + 1:k + 1 + _MOVE_REACH]
                    reader = next((s for s in later if isinstance(s, _SIMPLE) and _read(s) & updated), None)
                    # (never past a `return`: after it the statement is dead, a removal, and is told as one)
                    # (nor, in the def's own body, past the last statement reading it: there too it is dead)
                    if reader is not None and not isinstance(reader, _LEAVES) \
                            and not any(_assigned(s) & updated for s in later[:later.index(reader)]) \
                            and (not isinstance(block, (ast.FunctionDef, ast.AsyncFunctionDef))
                                 or any(_read(s) & updated for s in statements[statements.index(reader) + 1:])):
                        yield "move", reader, statement, "after"
                    earlier = statements[max(0, k - _MOVE_REACH):k]
                    reader = next((s for s in reversed(earlier) if isinstance(s, _SIMPLE) and _read(s) & updated), None)
                    if reader is not None and not any(_assigned(s) & updated for s in earlier[earlier.index(reader):]):
                        yield "move", reader, statement, "before"
                elif isinstance(statement, ast.Assign):
                    yield from _reader_moves(statements, k)
                if isinstance(statement, ast.Assign):
                    yield from _rebinding_moves(statements, k)
                if isinstance(statement, (ast.For, ast.While, ast.If)) and k + 1 < len(statements) \
                        and not isinstance(statement.body[-1], _LEAVES):   # (moved after a `continue`: never run)
                    following = statements[k + 1]
                    # (after a loop: a statement reading what the loop sets, its own variable too; after an
                    # `if`: any update, which the condition was to guard)
                    inside = {n for s in statement.body for n in _assigned_anywhere(s)} | (
                        {n.id for n in walk(statement.target) if isinstance(n, ast.Name)}
                        if isinstance(statement, ast.For) else set())
                    if isinstance(following, _SIMPLE) and not isinstance(following, ast.Return) \
                            and (_read(following) & inside or (isinstance(statement, ast.If) and _assigned(following))):
                        yield "indent", statement, following, "into"
                if isinstance(statement, (ast.For, ast.While, ast.If)) and len(statement.body) >= 2 \
                        and isinstance(statement.body[-1], _SIMPLE) and not statement.orelse:
                    yield "dedent", statement, statement.body[-1], "out"
                if isinstance(statement, (ast.For, ast.While)) and len(statement.body) >= 2 \
                        and _allocates(statement.body[0]) \
                        and _stored_into(statement, next(iter(_assigned(statement.body[0])))):
                    # (the array the loop fills, item by item, made anew at each turn: only the last turn's item
                    # is left in it -- made once, before the loop)
                    yield "hoist", statement, statement.body[0], "before"
                if isinstance(statement, ast.For) and k > 0 and _allocates(statements[k - 1]) \
                        and _kept_each_time(statement, next(iter(_assigned(statements[k - 1])))):
                    # one array made before the loop and kept (appended, stored) at every turn: every item is
                    # that same array, the last turn's (`frame = np.zeros(...)` above `frames.append(frame)`)
                    yield "indent", statement, statements[k - 1], "first"
                if isinstance(statement, ast.For):
                    for made in _reset_each_turn(statements[max(0, k - _MOVE_REACH):k], statement):
                        yield "indent", statement, made, "first"
                    # (and a loop nested in it, whose turns each need their own sum: `total = 0.0` above
                    # `for i`, grown in `for k` and stored as E[i, j] in `for j`, where it belongs first)
                    for inner in (n for n in walk(statement) if isinstance(n, ast.For) and n is not statement):
                        for made in _reset_each_turn(statements[max(0, k - _MOVE_REACH):k], inner):
                            yield "indent", inner, made, "first"


def _reset_each_turn(earlier, loop):
    """Statements among ``earlier`` (just above ``loop``) starting a collection or a sum, or making a copy,
    that the loop grows or changes in place and also reads at each turn, beside the change: a per-turn
    value made once, so each turn sees the turns before it too (`rows = []` above a loop appending four
    rows and solving `np.array(rows)` in it: the first point's rows in every later system; `moved =
    X.copy()` above a loop shifting `moved[:, 2] += d - z0` and projecting it: the shifts add up)."""
    for k, statement in enumerate(earlier):
        if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1
                and isinstance(statement.targets[0], ast.Name)
                and (_starts_empty(statement.value) or _fresh_copy(statement.value))):
            continue
        name = statement.targets[0].id
        if any(name in _read(s) | _assigned(s) for s in earlier[k + 1:]):
            continue
        grown = read = False
        for s in (n for n in walk(loop) if isinstance(n, ast.stmt) and not isinstance(n, ast.For)):
            if _grows(s, name):
                grown = True
            elif not isinstance(s, (ast.If, ast.While, ast.With, ast.Try)) and name in _read(s):
                read = True   # (a compound statement's own reading is its parts', walked on their own)
        if grown and read:
            yield statement


def _fresh_copy(value) -> bool:
    """A new copy of an array: `x.copy()`, `np.copy(x)`, `np.array(x, ...)`, `x.astype(...)`."""
    if not isinstance(value, ast.Call):
        return False
    called = _dotted(value.func)
    if isinstance(value.func, ast.Attribute) and value.func.attr in ("copy", "astype") and not called.startswith(("np.", "numpy.")):
        return True
    return called in ("np.copy", "numpy.copy", "np.array", "numpy.array") and len(value.args) >= 1


def _starts_empty(value) -> bool:
    """An empty list or dict, a zero, or a new array of zeros (what a collection or a sum starts from)."""
    if isinstance(value, (ast.List, ast.Dict)) and not (value.keys if isinstance(value, ast.Dict) else value.elts):
        return True
    if isinstance(value, ast.Constant) and type(value.value) in (int, float) and value.value == 0:
        return True
    if not isinstance(value, ast.Call):
        return False
    called = _dotted(value.func)
    return (called == "list" and not value.args) or (called.rsplit(".", 1)[-1] in {"zeros", "zeros_like"} and bool(value.args))


def _grows(statement, name: str) -> bool:
    """Whether ``statement`` adds to ``name``: `name.append(...)`, `name.extend(...)`, `name += ...`,
    `name[...] += ...`."""
    if isinstance(statement, ast.AugAssign):
        target = statement.target.value if isinstance(statement.target, ast.Subscript) else statement.target
        return isinstance(target, ast.Name) and target.id == name
    call = statement.value if isinstance(statement, ast.Expr) else None
    return isinstance(call, ast.Call) and isinstance(call.func, ast.Attribute) \
        and call.func.attr in ("append", "extend", "insert") \
        and isinstance(call.func.value, ast.Name) and call.func.value.id == name


def _stored_into(loop, name: str) -> bool:
    """Whether ``loop`` writes items of ``name`` (`points[i] = ...`)."""
    return any(isinstance(n, (ast.Assign, ast.AugAssign)) and any(
        isinstance(t, ast.Subscript) and isinstance(t.value, ast.Name) and t.value.id == name
        for t in (n.targets if isinstance(n, ast.Assign) else [n.target])) for n in walk(loop))


def _allocates(statement) -> bool:
    """Whether ``statement`` makes one new array for one name (`frame = np.zeros((h, w))`)."""
    return isinstance(statement, ast.Assign) and len(statement.targets) == 1 \
        and isinstance(statement.targets[0], ast.Name) and isinstance(statement.value, ast.Call) \
        and _dotted(statement.value.func).rsplit(".", 1)[-1] in _ALLOCATED | {"zeros_like", "empty_like", "full_like",
                                                                               "ones_like", "copy"}


def _kept_each_time(loop, name: str) -> bool:
    """Whether the loop keeps ``name`` itself at every turn: appended, or stored whole as an item."""
    for node in walk(loop):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in ("append", "insert") \
                and any(isinstance(a, ast.Name) and a.id == name for a in node.args):
            return True
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.Name) and node.value.id == name \
                and all(isinstance(t, ast.Subscript) for t in node.targets):
            return True
    return False


def _assigned_anywhere(statement) -> set:
    return {n for s in walk(statement) if isinstance(s, (ast.Assign, ast.AugAssign)) for n in _assigned(s)}


def _sequential_updates(fn):
    """(first, second): an assignment updating a name from its own value (`x = x * r + ...`) followed
    by one reading the updated name (`y = y * r + ... x ...`), where both belong computed from the old
    values at once (`x, y = ..., ...`: a point's coordinates updated one after the other)."""
    for block in walk(fn):
        for field in ("body", "orelse"):
            statements = getattr(block, field, None)
            if not isinstance(statements, list):
                continue
            for k, (first, second) in enumerate(zip(statements, statements[1:])):
                if not all(isinstance(s, ast.Assign) and len(s.targets) == 1 and isinstance(s.targets[0], ast.Name)
                           for s in (first, second)):
                    continue
                a, b = first.targets[0].id, second.targets[0].id
                reads = lambda value, name: any(isinstance(n, ast.Name) and n.id == name  # noqa: E731
                                                and isinstance(n.ctx, ast.Load) for n in walk(value))
                # (the updated name read again after the pair, or in a loop's next turn: else the update is dead
                # once the pair is made at once -- a removal of it, told as one)
                again = isinstance(block, (ast.For, ast.While)) or any(reads(s, a) for s in statements[k + 2:])
                if a != b and reads(first.value, a) and reads(second.value, a) and again:
                    yield first, second


def _in_docstring(node, fn) -> bool:
    body = fn.body
    return bool(body) and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
        and node is body[0].value


_SIZE_NAMES = frozenset({"width", "height", "w", "h", "cols", "rows", "n_cols", "n_rows", "ncols", "nrows"})


def _image_size(node) -> bool:
    """An image's size: a name for one (`width`, `h`, `cols`) or an entry of a `.shape`."""
    if isinstance(node, ast.Name):
        return node.id in _SIZE_NAMES
    return isinstance(node, ast.Subscript) and isinstance(node.value, ast.Attribute) and node.value.attr == "shape"


def _changes(node, parents, words: _Words, line):
    """The operators' changes of one node: (operator, payload, phrase)."""
    what = lambda n: words.what(n, line=line)  # noqa: E731
    parent = parents.get(id(node), (None, None, None))[0]
    place = functools.partial(_place, node, parents, words, line)   # where, when nothing names the term
    if not words.student and isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) \
            and isinstance(node.value, ast.Call) and _cumulative(node.value) and _reversal(node) is not None \
            and node.value.args and _reversal(node.value.args[0]) is not None:
        yield "reverse_back", ast.unparse(node.value), \
            f"the {_running(node.value)} taken from the far end (over a reversed axis) is not reversed back"
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and not isinstance(node.operand, ast.Constant):
        yield "sign", "remove", _subject(what(node.operand), "has the wrong sign (its minus is missing)", node, parents,
                                         words) or _placed("a minus sign is missing", place())
    if isinstance(node, ast.expr) and _entry_of_literal(node, parents) and not (
            isinstance(node, ast.Constant) and node.value in (0, 0.0, 1, 1.0)) \
            and not isinstance(node, ast.UnaryOp) and not isinstance(parent, ast.UnaryOp):
        yield "sign", "insert", _subject(what(node), "has the wrong sign", node, parents, words)
    if _trig_argument(node, parent):
        yield "sign", "insert", f"{what(node)} has the wrong sign (inside the sine/cosine)" if what(node) else ""
    if isinstance(node, ast.Name) and node.id in words.api_params and _angle_name(node.id) \
            and isinstance(parent, ast.Call) and node in parent.args \
            and _dotted(parent.func) not in _ANGLE_CONVERSIONS and not _trig_argument(node, parent):
        yield "degrees", "np.deg2rad", f"`{node.id}` is converted to radians where degrees are needed"
    if isinstance(node, ast.Constant) and isinstance(node.value, int) and not isinstance(node.value, bool):
        yield from _constant_changes(node, parents, words, what)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and isinstance(node.operand, ast.Constant) \
            and node.operand.value == 1:
        holder = parent if not isinstance(parent, ast.Tuple) else parents.get(id(parent), (None,))[0]
        if isinstance(holder, ast.Subscript) and not isinstance(parent, ast.Slice):
            inner = what(holder.value)
            first = "row" if (isinstance(parent, ast.Tuple) and parent.elts[0] is node) or inner.startswith("Vt") \
                else "element"
            yield "axis", 0, f"the first {first} of {inner} is used where the last belongs" if inner else ""
    if isinstance(parent, ast.Call) and _dotted(parent.func) == "range" and parent.args \
            and node is parent.args[min(1, len(parent.args) - 1)] and not isinstance(node, ast.Constant):
        for delta in ("-1", "+1"):
            yield "bound", delta, f"a loop over {what(node)} runs one step {'short' if delta == '-1' else 'too far'} " \
                                  "(off by one)" if what(node) else ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)):
        left, right = what(node.left), what(node.right)
        verb = "added instead of subtracted" if isinstance(node.op, ast.Sub) else "subtracted instead of added"
        if right:
            yield "add_sub", None, f"{right} is {verb}" + (f" ({left} {'minus' if isinstance(node.op, ast.Sub) else 'plus'} it)" if left else "")
        else:
            yield "add_sub", None, _placed(f"a term is {verb}", place())
    if words.student and isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) \
            and not isinstance(node.left, ast.Constant) and isinstance(node.right, ast.Constant) \
            and node.right.value == 2 and type(node.right.value) is int:
        # (a power of two written as a square: `n_bits ** 2` stripes where `2 ** n_bits` belong -- equal at 2 and 4;
        # the student's code only: the reference's squares are sums of squares, never powers of two)
        yield "swap_operands", None, _placed("the base and the exponent of a power are swapped (a square where a "
                                             "power of 2 belongs)", place())
    if isinstance(node, ast.BinOp) and type(node.op) in _NON_COMMUTATIVE:
        left, right = what(node.left), what(node.right)
        kind = _NON_COMMUTATIVE[type(node.op)]
        if left and right:
            if isinstance(node.op, ast.MatMult):
                yield "swap_operands", None, f"the matrix product of {left} and {right} is taken in the reverse order"
            else:
                yield "swap_operands", None, f"the {kind} has its two operands swapped ({left} and {right})"
        else:
            yield "swap_operands", None, _placed(f"the two operands of a {kind} are swapped", place())
        if isinstance(node.op, ast.MatMult):
            if right and left:
                yield "drop_factor", "left", f"the product with {left} is missing (only {right} is used)"
                yield "drop_factor", "right", f"the product with {right} is missing (only {left} is used)"
            else:
                yield "drop_factor", "left", _placed("the left factor of a matrix product is missing", place())
                yield "drop_factor", "right", _placed("the right factor of a matrix product is missing", place())
        if isinstance(node.op, ast.Sub) and (_is_mean(node.right, words) or words.student and _is_image_centre(node.right, words)):
            yield "drop_centring", None, _centring_phrase(node, what)
        if isinstance(node.op, ast.Div):
            yield "drop_division", None, _division_phrase(node, what) or _placed(
                "a division (a normalisation) is missing", place())
            yield "int_division", "floor", f"{left or 'a value'} divided by {right or 'another'} is an integer " \
                                           "division (// truncates)"
            if left and right:
                yield "int_division", "int", f"{left} divided by {right} is truncated to an integer (int())"
    if isinstance(parent, ast.Return) and isinstance(node, (ast.Name, ast.Call, ast.BinOp, ast.Subscript)):
        yield "int_division", "astype", _placed("the result is truncated to integers (astype(int))", "in the returned value")
    if isinstance(node, ast.Call):
        yield from _call_changes(node, words, what, parents)
        converted = _float_conversion(node)
        if converted is not None and what(converted) and not _dotted(getattr(converted, "func", None)) \
                .rsplit(".", 1)[-1].startswith("arg"):   # (an index array is integer by design)
            yield "drop_conversion", None, f"{what(converted)} is not converted to float before the arithmetic " \
                                           "(integer values, such as uint8 pixels, wrap around or are truncated)"
    if isinstance(node, ast.Attribute) and node.attr == "T" and isinstance(node.ctx, ast.Load):
        inner = what(node.value)
        yield "transpose", "remove", f"{inner} is used untransposed (its transpose belongs there)" if inner else \
            _placed("a transpose is missing", place())
    if isinstance(node, ast.expr) and (_transposable(node, parent) or (words.student and (
            _cv_points(node, parent) or _matrix_renamed(node, parent)))):
        inner = what(node)
        yield "transpose", "insert", f"{inner} is used transposed" if inner else \
            _placed("a matrix is used transposed", place())
    if isinstance(node, ast.Attribute) and _dotted(node).startswith("cv2.") and node.attr in _FLAG_FAMILY:
        for other in _FLAG_FAMILY[node.attr]:
            if other != node.attr:
                yield "flag", other, f"`cv2.{other}` is used where `cv2.{node.attr}` belongs"
    if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2:
        first, second = node.slice.elts
        inner = what(node.value)
        for whole, index, was, now in ((first, second, "column", "row"), (second, first, "row", "column")):
            if _whole_slice(whole) and isinstance(index, ast.Constant) and isinstance(index.value, int) and inner:
                yield "axis", "swap_index", f"{now} {index.value} of {inner} is used where {was} {index.value} " \
                                            f"belongs (a {now} instead of a {was})"
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)) and isinstance(node.right, ast.Constant) \
            and node.right.value == 1:
        inner = what(node.left)
        sign = "- 1" if isinstance(node.op, ast.Sub) else "+ 1"
        yield "bound", "drop", f"the {sign} after {inner} is missing (off by one)" if inner else ""
    if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) \
            and (_replaceable(node, parent, words.student) or _sibling_item_read(node, parent, words)
                 or (words.student and isinstance(parent, ast.Attribute) and parent.attr in _RESHAPING_METHODS)) \
            and not (words.student and isinstance(parent, ast.Subscript) and isinstance(parent.ctx, ast.Store)):
        # (and in the student's code an array reshaped by a method of its own: `src.reshape(-1)` where the
        # right-hand side is `dst`'s)
        # (the student's code: another array written into, `F[:, 2] = 1.0` for `lines[:, 2] = 1.0`,
        # "mends" a statement by writing into the caller's array instead -- that is no fix)
        yield from _name_changes(node, words, what, line)
    if isinstance(node, (ast.Assign, ast.AugAssign)) and parent is not None:
        yield "drop_statement", None, _statement_phrase(node, words, line)
    if words.student and isinstance(node, (ast.Continue, ast.Break)):
        yield "drop_statement", None, ""   # a frame skipped, a loop left, where it must go on
    if words.student and isinstance(node, ast.If) and not node.orelse and isinstance(node.body[-1], ast.Return) \
            and isinstance(parent, (ast.FunctionDef, ast.For, ast.While, ast.If, ast.With)):
        yield "drop_statement", None, ""   # a shortcut for a special value that answers otherwise than the general way
    if words.student and isinstance(node, ast.If) and not node.orelse and len(node.body) == 1 \
            and isinstance(node.body[0], ast.Raise) and node.body[0].exc is not None:
        yield "drop_statement", None, ""   # a test of its own that refuses valid input (`matrix_rank(F) != 2`)
    if words.student and isinstance(node, ast.If) and not node.orelse and len(node.body) >= 2 \
            and all(isinstance(s, ast.Assign) and all(isinstance(x, ast.Name) for x in s.targets) for s in node.body) \
            and isinstance(parent, (ast.FunctionDef, ast.For, ast.While, ast.With)):
        # a special case of its own that replaces values the general way made (`canvas = cv2.resize(...)` and
        # `marks = pts * scale` for a wide image: the answer no longer the size it was given)
        made = {s.targets[0].id for s in node.body if len(s.targets) == 1}
        before = {n.id for s in getattr(parent, "body", ()) if getattr(s, "lineno", node.lineno) < node.lineno
                  for n in walk(s) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
        if made & before:
            yield "drop_statement", None, ""
    if isinstance(node, ast.Assign) and len(node.targets) == 1:
        yield from _line_name_changes(node, words, line)
    yield from _in_place_changes(node, words)
    yield from _inverse_changes(node, what, place)
    yield from _undoing_changes(node)
    if isinstance(node, ast.Subscript):
        yield from _index_changes(node, what)
    if isinstance(node, ast.Call):
        yield from _stack_changes(node, what)
    if isinstance(node, ast.Constant) and isinstance(parent, ast.Call) and parent.args and parent.args[0] is node \
            and _dotted(parent.func) in ("np.einsum", "numpy.einsum"):
        yield from _einsum_changes(node.value)
    if words.student and isinstance(parent, (ast.IfExp, ast.If, ast.While)) and parent.test is node:
        # a parameter whose default is None tested for truth (`... if dist else None`): an array given
        # has no truth value (ValueError), a list of zeros is taken as not given
        tested = node.operand if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not) else node
        if isinstance(tested, ast.Name) and tested.id in _none_defaults(words.fn):
            yield "default", "is_none" if tested is not node else "is_not_none", ""
    if isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], ast.Is) \
            and isinstance(node.comparators[0], ast.Constant) and node.comparators[0].value is None \
            and isinstance(node.left, ast.Name) and node.left.id in words.api_params \
            and isinstance(parent, (ast.IfExp, ast.If)) and parent.test is node:
        yield "default", None, f"a `{node.left.id}` of 0 (or any value that is false) is taken as not given: " \
                               "the default is used in its place (only None means not given)"
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div, ast.MatMult)):
        yield from _arithmetic_changes(node, what, place)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitAnd) and isinstance(node.right, ast.Constant):
        yield "drop_mask", None, f"the mask & {node.right.value} that keeps the lowest bits is missing" \
            if isinstance(node.right.value, int) and not isinstance(node.right.value, bool) else ""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.stack", "numpy.stack", "np.concatenate",
                                                            "numpy.concatenate") and node.args:
        other = "concatenate" if _dotted(node.func).endswith("stack") else "stack"
        yield "stack_kind", other, (f"the pieces are joined with `np.{other}` where `{_dotted(node.func)}` belongs "
                                    + ("(along an existing axis instead of a new one)" if other == "concatenate"
                                       else "(along a new axis instead of an existing one)"))
    if isinstance(node, ast.Attribute) and node.attr == "T" and isinstance(node.ctx, ast.Load) \
            and _named_matrix(node.value) and what(node.value):
        yield "reshape_transpose", None, f"{what(node.value)} is reshaped to the transposed shape where it is " \
                                         "transposed (reshape keeps the order of the entries; .T moves them)"
    if words.student and isinstance(parent, ast.Call) and _dotted(parent.func) == "range" and parent.args == [node] \
            and isinstance(node, ast.Constant) and isinstance(node.value, int) and node.value >= 3:
        loop = parents.get(id(parent), (None,))[0]
        if isinstance(loop, ast.For) and loop.iter is parent and isinstance(loop.target, ast.Name):
            yield from _counted_loop_changes(loop)
    if words.student and isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name):
        yield from _index_of_the_loop(node, parents)
    if words.student and isinstance(node, ast.Call) and _dotted(node.func) in ("np.kron", "numpy.kron") \
            and len(node.args) == 2 and all(isinstance(a, ast.Name) for a in node.args) and not node.keywords:
        # (the student's code only: the Kronecker product of two whole arrays of points is one row for every pair
        # of points, N^2 rows, where one row per correspondence, each point's with its match's, belongs)
        yield "row_kron", None, ""
    if words.student:
        yield from _flips(node)   # (the student's code only: rows reversed where columns belong, or the other way)
    if words.student and _stretched_range(node) is not None:
        # (the student's code only: a result stretched to the range where it belongs clipped into it -- a blend's
        # overshoot min-max normalised changes every pixel, where clipping changes only those out of range)
        yield "clip_range", _stretched_range(node), ""
    if words.student and isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], (ast.Lt, ast.LtE)) \
            and isinstance(node.left, ast.BinOp) and isinstance(node.left.op, ast.Div):
        # (the student's code only: a ratio compared where its cross-multiplied form belongs -- Lowe's test as
        # `m.distance / n.distance < ratio` divides by a second distance of 0, where `m < ratio * n` compares)
        yield "cross_multiply", None, ""
    if words.student and isinstance(node, ast.Call) and _dotted(node.func).rsplit(".", 1)[-1] in _WINDOW_FILTERS \
            and any(k.arg in _WINDOW_KEYWORDS and not isinstance(k.value, (ast.Tuple, ast.List)) for k in node.keywords):
        # (the student's code only: scipy's filters take a number as the window along EVERY axis -- a cost volume
        # (D, H, W) averaged across its disparities too; one window per image of the stack, either end)
        yield "stack_window", "first", ""
        yield "stack_window", "last", ""
    if words.student and isinstance(node, ast.Tuple) and len(node.elts) == 2 and isinstance(parent, ast.Call) \
            and sum(isinstance(e, ast.Constant) and e.value == 1 for e in node.elts) == 1 \
            and not all(isinstance(e, ast.Constant) for e in node.elts):
        # (the student's code only: a window one pixel high or wide where a square one belongs --
        # `cv2.blur(cost, (block_size, 1))` averages a strip, not the block)
        yield "square_window", None, ""
    if words.student and isinstance(node, ast.Assign) and len(node.targets) == 1:
        # (the student's code only: a formula written with values already scaled where their sources belong --
        # the tangential terms of a distortion given the radially distorted x and y, `xr = x * radial`)
        derived = _scaled_copies(words.fn)
        read = sorted({n.id for n in walk(node.value) if isinstance(n, ast.Name) and n.id in derived})
        if read and not any(isinstance(t, ast.Name) and t.id in derived for t in walk(node.targets[0])):
            yield "source_names", tuple((name, derived[name]) for name in read), ""
    if words.student and isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) \
            and isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2 and _whole_slice(node.slice.elts[0]) \
            and isinstance(node.slice.elts[1], ast.Slice) and node.slice.elts[1].upper is None \
            and node.slice.elts[1].step is None and isinstance(node.slice.elts[1].lower, ast.Constant) \
            and type(node.slice.elts[1].lower.value) is int and node.slice.elts[1].lower.value >= 1:
        # (the student's code only: a last column kept 2-D, (3, 1), where the flat column belongs -- `P[:, 3:]`
        # added to (N, 3) rows broadcasts -- `P[:, 3]`)
        yield "flat_column", None, ""
    if words.student and isinstance(node, ast.Attribute) and node.attr == "size" and isinstance(node.ctx, ast.Load) \
            and isinstance(node.value, ast.Name) and isinstance(parent, ast.BinOp):
        # (the student's code only: every entry counted, 3N, where the points' count belongs -- `sum / pts.size`)
        yield "count_rows", None, ""
    if words.student and isinstance(node, ast.Assign) and len(node.targets) == 1 \
            and isinstance(node.targets[0], ast.Name) and isinstance(node.value, ast.Call) \
            and isinstance(node.value.func, ast.Name):
        # (the student's code only: a helper's pair kept whole where it is unpacked elsewhere -- `X = _points(p)`
        # beside `X, single = _points(p)`)
        width = _unpacked_width(node.value.func.id, words.module_defs)
        if width:
            yield "unpack_pair", width, ""
    if words.student and isinstance(node, ast.Subscript) and isinstance(node.value, ast.Attribute) \
            and node.value.attr == "shape" and isinstance(node.slice, ast.Slice) and node.slice.lower is None \
            and node.slice.upper is None and isinstance(node.slice.step, ast.UnaryOp) \
            and isinstance(node.slice.step.op, ast.USub) and isinstance(node.slice.step.operand, ast.Constant) \
            and node.slice.step.operand.value == 1:
        # (the student's code only: an image's whole shape reversed for OpenCV's (width, height) -- (3, W, H) for a
        # colour image -- where its first two belong, `shape[1::-1]`)
        yield "shape_reversed", None, ""
    if words.student:
        yield from _student_changes(node, parent, parents, words)
        yield from _sibling_changes(node, words)
        yield from _helper_changes(node, words)
        yield from _defaulted_argument_changes(node, words)
        yield from _homogeneous_arguments(node, words)
        yield from _exchanged_sides(node, words)
        yield from _exchanged_in_product(node, parent)
        yield from _logic_changes(node, parent, parents)
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.LShift, ast.RShift)):
        wrong, right = ("<<", ">>") if isinstance(node.op, ast.RShift) else (">>", "<<")
        shifted = what(node.left)
        # (a function has few shifts: where nothing names the shifted term, the direction says enough)
        yield "shift", None, f"{shifted} is shifted the wrong way ({wrong} where {right} belongs)" if shifted \
            else _placed(f"a bit shift goes the wrong way ({wrong} where {right} belongs)", place()) \
            or f"a bit shift goes the wrong way ({wrong} where {right} belongs)"
    if isinstance(parent, (ast.comprehension, ast.For)) and parent.iter is node and isinstance(parent.target, ast.Name) \
            and not (isinstance(node, ast.Call) and _dotted(node.func) in _LOOPED_POSITIONS):
        looped = what(node)
        yield "loop_index", None, f"the loop takes the positions 0, 1, 2, ... of {looped} where its values belong" \
            if looped else _placed("a loop takes positions 0, 1, 2, ... where the values belong", place())
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.atleast_2d", "numpy.atleast_2d") \
            and len(node.args) == 1:   # (in a helper, the array may have no name of the student's)
        subject = what(node.args[0])
        yield "single_point", None, f"{subject} is not made 2-D: a single point (a 1-D array) is not handled " \
                                    "(`np.atleast_2d` is missing)" if subject else \
            "a single point (a 1-D array) is not handled: it is not made 2-D (`np.atleast_2d` is missing)"


_INDEX_WORDS = {-1: "last", 0: "first", 1: "second", 2: "third"}
_LOOPED_POSITIONS = {"range", "enumerate", "zip"}   # loops whose targets are positions or tuples already


# Functions a student applies where they do not belong, and those mistaken for each other.
# OpenCV functions taken for their sibling (the same arguments, another model or direction).
_CV_MISTAKEN = {"estimateAffinePartial2D": "estimateAffine2D", "estimateAffine2D": "estimateAffinePartial2D",
                "pyrDown": "pyrUp", "pyrUp": "pyrDown", "add": "subtract", "subtract": "add"}
_UNARY = {"sin", "cos", "tan", "arcsin", "arccos", "arctan", "abs", "absolute", "fabs", "sqrt", "square", "exp",
          "log", "round", "rint", "floor", "ceil", "deg2rad", "rad2deg", "radians", "degrees", "int",
          "unique", "sort"}   # (and an order imposed that does not belong: np.unique sorts and drops repeats)
_ROUNDED = {"floor", "ceil", "round", "rint", "trunc", "fix", "around"}   # a value already whole: int() of it cuts nothing
_WHOLE_METHODS = {"mean", "sum", "max", "min", "median"}
_WHOLE_REDUCTIONS = {"np.mean", "np.median", "np.sum", "np.max", "np.min", "np.amax", "np.amin"}
_MISTAKEN = {"sin": "cos", "cos": "sin", "arcsin": "arccos", "arccos": "arcsin", "tan": "arctan", "arctan": "tan",
             "floor": "ceil", "ceil": "floor", "round": "floor", "mean": "median", "median": "mean", "sum": "mean",
             "log": "log10", "log10": "log",
             "column_stack": "vstack", "vstack": "column_stack", "hstack": "vstack",
             "zeros": "ones", "ones": "zeros", "zeros_like": "ones_like", "ones_like": "zeros_like"}


_LOGS = {"log", "log10", "log2", "log1p"}


def _log_of_a_ratio(node, short: str, parent) -> bool:
    """Whether ``node`` is a logarithm divided by another or dividing one (`np.log(1 - p) / np.log(1 - w ** 4)`):
    the base cancels in the ratio, so one log's base changed only scales the result -- never the slip (a RANSAC's
    count of samples made 2.3 times larger passes by running longer)."""
    if short not in _LOGS or not (isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.Div)):
        return False
    other = parent.right if parent.left is node else parent.left
    return any(isinstance(n, ast.Call) and _dotted(n.func).rsplit(".", 1)[-1] in _LOGS for n in walk(other))


def _root(node, parents):
    """The outermost node ``parents`` knows above ``node`` (the def it was made for)."""
    while id(node) in parents:
        node = parents[id(node)][0]
    return node


def _written_into(fn, name: str, after: int) -> bool:
    """Whether ``fn`` writes into the array ``name`` holds below line ``after`` (`name[...] = `, `name[...] += `,
    `name += ` on an array is not told apart from a rebinding and does not count)."""
    return any(isinstance(node, (ast.Assign, ast.AugAssign)) and node.lineno > after
               and any(isinstance(t, ast.Subscript) and isinstance(t.value, ast.Name) and t.value.id == name
                       for t in (node.targets if isinstance(node, ast.Assign) else [node.target]))
               for node in walk(fn))


def _extreme_of(node) -> tuple[str, str] | None:
    """``("min" or "max", what it is of, with its other arguments)`` of `X.min(...)`, `np.max(X, ...)`
    (`np.amin`, `np.amax` too); None otherwise."""
    if not isinstance(node, ast.Call) or node.keywords and any(k.arg is None for k in node.keywords):
        return None
    name = _dotted(node.func)
    short = node.func.attr if isinstance(node.func, ast.Attribute) else name.rsplit(".", 1)[-1]
    kind = {"min": "min", "amin": "min", "max": "max", "amax": "max"}.get(short)
    if kind is None:
        return None
    if name in (f"np.{short}", f"numpy.{short}") and node.args:
        of = [ast.unparse(a) for a in node.args] + [ast.unparse(k) for k in node.keywords]
    elif isinstance(node.func, ast.Attribute) and short in ("min", "max") and name.split(".", 1)[0] not in ("np", "numpy"):
        of = [ast.unparse(node.func.value)] + [ast.unparse(a) for a in node.args] + [ast.unparse(k) for k in node.keywords]
    else:
        return None
    return kind, ", ".join(of)


def _midrange(node) -> str | None:
    """`np.mean(X, ...)` for the middle of X's range, `(X.min() + X.max()) / 2` or `0.5 * (...)`; None
    for anything else."""
    if not isinstance(node, ast.BinOp):
        return None
    if isinstance(node.op, ast.Div) and isinstance(node.right, ast.Constant) and node.right.value == 2:
        total = node.left
    elif isinstance(node.op, ast.Mult) and isinstance(node.left, ast.Constant) and node.left.value == 0.5:
        total = node.right
    else:
        return None
    if not (isinstance(total, ast.BinOp) and isinstance(total.op, ast.Add)):
        return None
    ends = [_extreme_of(total.left), _extreme_of(total.right)]
    if None in ends or {e[0] for e in ends} != {"min", "max"} or ends[0][1] != ends[1][1]:
        return None
    return f"np.mean({ends[0][1]})"


def _measured_after_filtering(node) -> str | None:
    """`np.abs(f(a, k) - f(b, k))` (or `(f(a, k) - f(b, k)) ** 2`, `np.square(...)`), one function given the
    same other arguments on both sides: the measure taken inside it, `f(np.abs(a - b), k)` -- a block's sum
    of absolute differences, not the difference of its means (the text, or None)."""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.abs", "np.absolute", "abs", "np.fabs", "np.square") \
            and len(node.args) == 1 and not node.keywords:
        difference, wrap = node.args[0], lambda inner: ast.Call(copy_tree(node.func), [inner], [])
    elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) and isinstance(node.right, ast.Constant) \
            and node.right.value == 2:
        difference, wrap = node.left, lambda inner: ast.BinOp(inner, ast.Pow(), ast.Constant(2))
    else:
        return None
    if not (isinstance(difference, ast.BinOp) and isinstance(difference.op, ast.Sub)):
        return None
    left, right = difference.left, difference.right
    if not (isinstance(left, ast.Call) and isinstance(right, ast.Call) and left.args and right.args
            and _dotted(left.func) == _dotted(right.func) and len(left.args) == len(right.args)
            and [ast.dump(a) for a in left.args[1:]] == [ast.dump(a) for a in right.args[1:]]
            and [ast.dump(k) for k in left.keywords] == [ast.dump(k) for k in right.keywords]):
        return None
    if _dotted(left.func).rsplit(".", 1)[-1] in _UNARY | {"asarray", "array", "float32", "float64"}:
        return None   # (a conversion or a pointwise function: nothing summed over a block)
    inner = wrap(ast.BinOp(copy_tree(left.args[0]), ast.Sub(), copy_tree(right.args[0])))
    return ast.unparse(ast.Call(copy_tree(left.func), [inner, *copy_tree(left.args[1:])],
                                copy_tree(left.keywords)))


def _mask_names(fn) -> frozenset:
    """The names ``fn`` binds only to masks (read once per def): a comparison (`inliers = errors < t`),
    another mask or a row of one (`best = inliers[k]`, `inliers = best`), or None before the first."""
    known = getattr(fn, "_grader_mask_names", None)
    if known is None:
        bound: dict = {}

        def bind(target, value):
            if isinstance(target, ast.Name):
                bound.setdefault(target.id, []).append(value)
            elif isinstance(target, (ast.Tuple, ast.List)):
                pairs = value.elts if isinstance(value, (ast.Tuple, ast.List)) and len(value.elts) == len(target.elts) \
                    else [None] * len(target.elts)
                for part, part_value in zip(target.elts, pairs):
                    bind(part, part_value)
        for statement in walk(fn):
            if isinstance(statement, ast.Assign):
                for target in statement.targets:
                    bind(target, statement.value)
            elif isinstance(statement, (ast.AugAssign, ast.AnnAssign, ast.For, ast.comprehension, ast.NamedExpr)):
                bind(statement.target, None)
        def a_mask(value, masks) -> bool:
            return _masks(value) or (isinstance(value, ast.Constant) and value.value is None) \
                or (isinstance(value, ast.Name) and value.id in masks) \
                or (isinstance(value, ast.Subscript) and isinstance(value.value, ast.Name) and value.value.id in masks)
        # (the largest set of names bound only to masks, their rows, each other or None; then those of them
        # that something compared made)
        # (each round is linear in the def; a mask is followed through a few names at most, so the rounds are
        # bounded and a long chain of names in a hostile def costs no more than _MASK_ROUNDS readings of it)
        masks = {name for name, values in bound.items() if all(v is not None for v in values)}
        for _ in range(_MASK_ROUNDS):
            kept = {name for name in masks if all(a_mask(v, masks) for v in bound[name])}
            if kept == masks:
                break
            masks = kept
        made = {name for name in masks if any(_masks(v) for v in bound[name])}
        for _ in range(_MASK_ROUNDS):
            grown = made | {name for name in masks if any(isinstance(v, (ast.Name, ast.Subscript)) and (
                v.id if isinstance(v, ast.Name) else v.value.id) in made for v in bound[name])}
            if grown == made:
                break
            made = grown
        masks = made
        known = frozenset(masks)
        fn._grader_mask_names = known
    return known


_MASK_ROUNDS = 6   # names a mask is followed through (`inliers` -> `best` -> `inliers[k]` ...), at most


def _masks(value) -> bool:
    return isinstance(value, ast.Compare) or (isinstance(value, ast.BinOp) and isinstance(value.op, (ast.BitAnd, ast.BitOr))
                                              and any(isinstance(side, ast.Compare) for side in (value.left, value.right)))


def _operand(node) -> str:
    """``node``'s code, ready to take an attribute or an index: bracketed unless it is a name, an
    attribute, an index or a call (`(k + 0.5) * w`.astype(...), not `... - 0.5.astype(...)`)."""
    text = ast.unparse(node)
    return text if isinstance(node, (ast.Name, ast.Attribute, ast.Subscript, ast.Call)) else f"({text})"


def _conversion_inverted(node, parent):
    """An angle converted with the factor upside down, written out: `a * 180 / np.pi` where `a * np.pi /
    180` belongs (or the other way round): the 180 and the pi of one product exchanged. The outermost
    product holding both only."""
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div))) \
            or (isinstance(parent, ast.BinOp) and isinstance(parent.op, (ast.Mult, ast.Div))):
        return
    hundred = [n for n in walk(node) if isinstance(n, ast.Constant) and type(n.value) in (int, float) and n.value == 180]
    pi = [n for n in walk(node) if isinstance(n, ast.Attribute) and n.attr == "pi"
          and _dotted(n) in ("np.pi", "numpy.pi", "math.pi")]
    if len(hundred) != 1 or len(pi) != 1:
        return
    swapped = copy_tree(node)
    for n in walk(swapped):
        for field, child in ast.iter_fields(n):
            if isinstance(child, ast.Constant) and type(child.value) in (int, float) and child.value == 180:
                setattr(n, field, _name(_dotted(pi[0])))
            elif isinstance(child, ast.Attribute) and child.attr == "pi" and _dotted(child) == _dotted(pi[0]):
                setattr(n, field, ast.Constant(hundred[0].value))
    yield "conversion_inverted", ast.unparse(swapped), ""


def _fixed_index(node) -> bool:
    """`-1`, `0`: an index written as a number."""
    return (isinstance(node, ast.Constant) and type(node.value) is int) or (
        isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and isinstance(node.operand, ast.Constant)
        and type(node.operand.value) is int)


def _loop_item_changes(node, words):
    """A fixed item read in a loop where the loop's own item belongs: `disparity[-1]` inside `for x in ...`
    whose body writes `disparity[x - 1]` (the last column's value each time round, where the column just
    chosen belongs). Offered: the array at the loop variable, and at each index the loop gives it elsewhere.
    Each loop's indices are read once (a long loop with many fixed items stays linear)."""
    if not (isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(node.value, ast.Name)
            and _fixed_index(node.slice)):
        return
    loop = _parent_of(node, words)
    while loop is not None and not isinstance(loop, (ast.For, ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
        loop = _parent_of(loop, words)
    if not (isinstance(loop, ast.For) and isinstance(loop.target, ast.Name)):
        return
    if not hasattr(words, "loop_indices"):
        words.loop_indices = {}
    if id(loop) not in words.loop_indices:   # array name -> the indices the loop's variable gives it
        variable, indexed = loop.target.id, {}
        for statement in loop.body:
            for n in walk(statement):
                if isinstance(n, ast.Subscript) and isinstance(n.value, ast.Name) \
                        and any(isinstance(m, ast.Name) and m.id == variable for m in walk(n.slice)):
                    indexed.setdefault(n.value.id, set()).add(ast.unparse(n.slice))
        words.loop_indices[id(loop)] = indexed
    indices = words.loop_indices[id(loop)].get(node.value.id)
    if indices:
        for index in sorted(indices | {loop.target.id}):
            yield "loop_item", f"{node.value.id}[{index}]", ""


def _fraction_changes(node):
    """A count where a share belongs: `w = inliers.sum()` for `inliers.mean()` (RANSAC's inlier ratio),
    `np.sum(m)` for `np.mean(m)`, `np.count_nonzero(m)` for it divided by `m.size`. Whole sums only
    (no axis): a count of one array."""
    if not (isinstance(node, ast.Call) and not node.keywords):
        return
    dotted = _dotted(node.func)
    if isinstance(node.func, ast.Attribute) and node.func.attr == "sum" and not node.args \
            and not dotted.startswith(("np.", "numpy.")):
        yield "fraction", f"{_operand(node.func.value)}.mean()", ""
    elif dotted in ("np.sum", "numpy.sum") and len(node.args) == 1:
        yield "fraction", f"np.mean({ast.unparse(node.args[0])})", ""
    elif dotted in ("np.count_nonzero", "numpy.count_nonzero") and len(node.args) == 1:
        argument = ast.unparse(node.args[0])
        yield "fraction", f"np.count_nonzero({argument}) / np.size({argument})", ""


_IMAGE_WORDS = ("im", "img", "image", "images", "frame", "canvas", "panorama", "photo", "picture", "view", "left",
                "right", "plane", "planes", "warped", "shifted", "out", "result", "src", "dst")


def _image_name(name: str) -> bool:
    """Whether a name reads as an image's (`img`, `left_image`, `shifted`), by its words."""
    return any(part in _IMAGE_WORDS for part in name.lower().split("_"))


class _SwapAxes(ast.NodeTransformer):
    """Every `.T` of an image's name made `np.swapaxes(x, 0, 1)`."""

    def visit_Attribute(self, node):
        self.generic_visit(node)
        if node.attr == "T" and isinstance(node.value, ast.Name) and _image_name(node.value.id):
            return ast.Call(_name("np.swapaxes"), [node.value, ast.Constant(0), ast.Constant(1)], [])
        return node


_POINT_WORDS = ("x", "xyz", "pts", "points", "world", "pw", "cam", "camera", "p", "q", "scene")


def _point_name(name: str) -> bool:
    """Whether a name reads as 3D points' (`X`, `points`, `pts_cam`), by its words."""
    return any(part in _POINT_WORDS for part in name.lower().split("_"))


def _in_an_index(node, parents) -> bool:
    """Whether ``node`` is part of an index (`dst[:, 0]`, `x[1:]`): a position, not a value."""
    child = node
    while id(child) in parents:
        above = parents[id(child)][0]
        if isinstance(above, ast.Subscript) and child is above.slice:
            return True
        if isinstance(above, ast.stmt):
            return False
        child = above
    return False


class _OtherAxis(ast.NodeTransformer):
    """The twin's expression: names renamed (``renames``) and a last index 0 made 1 (`corners[:, 0]` ->
    `corners[:, 1]`), for a value made per axis."""

    def __init__(self, renames: dict):
        self.renames = renames

    def visit_Name(self, node):
        return ast.Name(self.renames.get(node.id, node.id), node.ctx)

    def visit_Subscript(self, node):
        self.generic_visit(node)
        index = node.slice.elts[-1] if isinstance(node.slice, ast.Tuple) and node.slice.elts else node.slice
        if isinstance(index, ast.Constant) and index.value in (0, 1) and type(index.value) is int:
            index.value = 1 - index.value
        return node


def _choices(fn) -> dict:
    """text of a branch -> (name, line) of the assignments choosing between two values (`z = c[2] if z_avg is None
    else float(z_avg)`), read once per def."""
    if not hasattr(fn, "_choices"):
        fn._choices = {}
        for n in walk(fn):
            if isinstance(n, ast.Assign) and len(n.targets) == 1 and isinstance(n.targets[0], ast.Name) \
                    and isinstance(n.value, ast.IfExp):
                for branch in (n.value.body, n.value.orelse):
                    if not isinstance(branch, (ast.Constant, ast.Name)):
                        fn._choices.setdefault(ast.unparse(branch), (n.targets[0].id, n.lineno))
    return fn._choices


def _chosen_value(node, parents):
    """One branch of a choice read where the choice belongs: `centroid[2]` after `z = centroid[2] if z_avg is None
    else z_avg` -> `z` (the value given, when it is, left unused there)."""
    if not isinstance(node, (ast.Subscript, ast.Call, ast.Attribute, ast.BinOp)) or getattr(node, "lineno", None) is None:
        return
    if isinstance(getattr(node, "ctx", ast.Load()), ast.Store):
        return
    chosen = _choices(_def_of(node, parents)).get(ast.unparse(node))
    if chosen is not None and chosen[1] < node.lineno:
        yield "chosen_value", chosen[0], ""


def _twin_values(node, parent, parents):
    """Names assigned together (`y_min, y_max = 0.0, h - 1.0`) whose twins are each assigned a value of their own
    (`x_min = np.floor(corners[:, 0].min())`): given the twins' values for the other axis (`np.floor(corners[:,
    1].min())`) -- one axis worked out, the other written from a guess."""
    if not (isinstance(parent, ast.Assign) and parent.value is node and len(parent.targets) == 1
            and isinstance(parent.targets[0], ast.Tuple) and isinstance(node, ast.Tuple)
            and all(isinstance(t, ast.Name) for t in parent.targets[0].elts)
            and len(node.elts) == len(parent.targets[0].elts) >= 2):
        return
    fn = _def_of(node, parents)
    single = {name: made[0][1] for name, made in _values_of(fn).items() if made[0][0] < parent.lineno}
    names = [t.id for t in parent.targets[0].elts]
    twins = [next((other for other in single if twin_names(name, other)), None) for name in names]
    if None in twins:
        return
    renames = dict(zip(twins, names))
    values = [_OtherAxis(renames).visit(copy_tree(single[twin])) for twin in twins]
    text = ", ".join(ast.unparse(v) for v in values)
    if text != ast.unparse(node).strip("()"):
        yield "twin_values", f"({text})", ""


class _Renamed(ast.NodeTransformer):
    def __init__(self, old: str, new: str):
        self.old, self.new = old, new

    def visit_Name(self, node):
        return ast.Name(self.new, node.ctx) if node.id == self.old else node


def _twin_test(node, parent, parents):
    """A condition testing one of two twins where the branch treats both (`if float(tx).is_integer():` before a
    whole-pixel shift by tx and ty): the twin's test added, `... and float(ty).is_integer()`."""
    if not (isinstance(parent, (ast.If, ast.IfExp, ast.While)) and parent.test is node) \
            or isinstance(node, ast.BoolOp):
        return
    read = {n.id for n in walk(node) if isinstance(n, ast.Name)}
    fn = _def_of(node, parents)
    known = {a.arg for a in walk(fn.args) if isinstance(a, ast.arg)} if hasattr(fn, "args") else set()
    for name in sorted(read):
        twins = [other for other in known if other not in read and twin_names(name, other)]
        if len(twins) == 1:
            twin = ast.unparse(_Renamed(name, twins[0]).visit(copy_tree(node)))
            yield "twin_test", f"{ast.unparse(node)} and {twin}", ""


def _stacked_rows(name: str, fn) -> bool:
    """Whether ``fn`` makes ``name`` only by stacking (`np.hstack([...])`, `np.column_stack`, `np.array([...])`)."""
    values = [value for _, value in _values_of(fn).get(name, [])]
    return bool(values) and all(isinstance(v, ast.Call) and _dotted(v.func).rsplit(".", 1)[-1] in (
        "hstack", "vstack", "column_stack", "stack", "concatenate", "array") for v in values)


def _never_read(fn) -> list[tuple[str, int]]:
    """(name, line) of the locals ``fn`` assigns once and never reads (read once per def)."""
    if not hasattr(fn, "_never_read"):
        assigned: dict = {}
        read = set()
        for n in walk(fn):
            if isinstance(n, ast.Name):
                if isinstance(n.ctx, ast.Load):
                    read.add(n.id)
                elif isinstance(n.ctx, ast.Store):
                    assigned.setdefault(n.id, []).append(n.lineno)
        fn._never_read = [(name, lines[0]) for name, lines in assigned.items()
                          if name not in read and len(lines) == 1 and not name.startswith("_")][:3]
    return fn._never_read


def _neutral_value(node, parent, parents):
    """A value of the student's own that only scales (every read of it multiplies or divides), made neutral:
    `scale = r.max()` -> `scale = 1.0` where the points are divided by it, treated, and multiplied back (a model
    that holds at the coordinates as they are, not rescaled)."""
    if not (isinstance(parent, ast.Assign) and parent.value is node and len(parent.targets) == 1
            and isinstance(parent.targets[0], ast.Name)):
        return
    name, fn = parent.targets[0].id, _def_of(node, parents)
    uses = _uses_of(fn).get(name, [])
    if len(uses) < 2 or sum(isinstance(target, ast.Name) and target.id == name
                            for n in walk(fn) if isinstance(n, ast.Assign) for target in n.targets) != 1:
        return   # (a value read once, or assigned again, is a step of another kind)
    if isinstance(node, ast.Constant):
        # (a number of the student's own only added or subtracted wherever it is read: a margin, a gap between two
        # pictures -- `gap = 4` -> `gap = 0`, the step the API does not take)
        if type(node.value) in (int, float) and node.value != 0 and all(isinstance(op, (ast.Add, ast.Sub)) for op in uses):
            yield "neutral", "0", ""
        return
    if all(isinstance(op, (ast.Mult, ast.Div)) for op in uses):
        yield "neutral", "1.0", ""
    # (a value only added or subtracted is a centring: drop_centring takes it out, told where it is undone)


def _uses_of(fn) -> dict:
    """name -> the operator of each BinOp it is read as an operand of (None for any other read), once per def."""
    if not hasattr(fn, "_uses_of"):
        operators = {}
        for n in walk(fn):
            if isinstance(n, ast.BinOp):
                for side in (n.left, n.right):
                    if isinstance(side, ast.Name):
                        operators[id(side)] = n.op
        uses: dict = {}
        for n in walk(fn):
            if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load):
                uses.setdefault(n.id, []).append(operators.get(id(n)))
        fn._uses_of = uses
    return fn._uses_of


def _stacked_last(node, parents):
    """Items a loop or a comprehension made, stacked along a new first axis where the last belongs: `np.array(planes)`
    -> `np.stack(planes, axis=-1)` (a colour image's warped planes put back channel-first)."""
    if not (isinstance(node, ast.Call) and _dotted(node.func) in ("np.array", "np.asarray", "np.stack", "numpy.array",
                                                                  "numpy.asarray", "numpy.stack")
            and len(node.args) == 1 and not node.keywords and isinstance(node.args[0], ast.Name)):
        return
    if node.args[0].id in _lists_made(_def_of(node, parents)):
        yield "stack_last", f"np.stack({node.args[0].id}, axis=-1)", ""


def _lists_made(fn) -> set[str]:
    """The names ``fn`` makes lists of items in (a comprehension, or `[]` appended to), read once per def."""
    if not hasattr(fn, "_lists_made"):
        made = {t.id for node in walk(fn) if isinstance(node, ast.Assign) and isinstance(node.value, ast.ListComp)
                for t in node.targets if isinstance(t, ast.Name)}
        started = {t.id for node in walk(fn) if isinstance(node, ast.Assign) and isinstance(node.value, ast.List)
                   and not node.value.elts for t in node.targets if isinstance(t, ast.Name)}
        appended = {node.func.value.id for node in walk(fn) if isinstance(node, ast.Call)
                    and isinstance(node.func, ast.Attribute) and node.func.attr == "append"
                    and isinstance(node.func.value, ast.Name)}
        fn._lists_made = made | (started & appended)
    return fn._lists_made


_SPREADS = {"cov": "bias", "std": "ddof", "var": "ddof"}   # estimators written with n or with n - 1


def _estimator_changes(node, parents):
    """A spread's other normalisation (the sample's n - 1 where the population's n belongs, or back):
    `np.cov(S, rowvar=False)` -> `np.cov(S, rowvar=False, bias=True)`, `x.std()` -> `x.std(ddof=1)`; and a sum
    divided by a count where the other is written (`D.T @ S / n` -> `/ (n - 1)`, `n` a length)."""
    if isinstance(node, ast.Call):
        dotted = _dotted(node.func)
        short = dotted.rsplit(".", 1)[-1]
        method = isinstance(node.func, ast.Attribute) and not dotted.startswith(("np.", "numpy."))
        if short not in _SPREADS or not (method or dotted in (f"np.{short}", f"numpy.{short}")) \
                or (method and short == "cov"):
            return
        keyword = _SPREADS[short]
        given = next((k.value for k in node.keywords if k.arg == keyword), None)
        if given is not None and not isinstance(given, ast.Constant):
            return
        flipped = copy_tree(node)
        flipped.keywords = [k for k in flipped.keywords if k.arg != keyword]
        on = bool(given.value) if given is not None else False
        if not on:
            flipped.keywords.append(ast.keyword(keyword, ast.Constant(True if keyword == "bias" else 1)))
        yield "estimator", ast.unparse(flipped), ""
        return
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div) and _calls_a_spread(_def_of(node, parents))):
        return   # (a count divided by where a spread is also taken: the two normalisations side by side)
    if isinstance(node.right, ast.Name) and _is_a_count(node.right.id, _def_of(node, parents)):
        yield "estimator", f"{_operand(node.left)} / ({node.right.id} - 1)", ""
    elif isinstance(node.right, ast.BinOp) and isinstance(node.right.op, ast.Sub) and isinstance(node.right.left, ast.Name) \
            and isinstance(node.right.right, ast.Constant) and node.right.right.value == 1 \
            and _is_a_count(node.right.left.id, _def_of(node, parents)):
        yield "estimator", f"{_operand(node.left)} / {node.right.left.id}", ""


def _calls_a_spread(fn) -> bool:
    """Whether ``fn`` takes a covariance, a standard deviation or a variance (read once per def)."""
    if not hasattr(fn, "_calls_a_spread"):
        fn._calls_a_spread = any(isinstance(node, ast.Call) and _dotted(node.func).rsplit(".", 1)[-1] in _SPREADS
                                 for node in walk(fn))
    return fn._calls_a_spread


def _values_of(fn) -> dict:
    """name -> the values ``fn`` assigns it alone (`n = len(src)`), with their lines, read once per def."""
    if not hasattr(fn, "_values_of"):
        fn._values_of = {}
        for node in walk(fn):
            if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
                fn._values_of.setdefault(node.targets[0].id, []).append((node.lineno, node.value))
    return fn._values_of


def _is_a_count(name: str, fn) -> bool:
    """Whether ``fn`` assigns ``name`` only a length (`n = len(src)`, `n = S.shape[0]`)."""
    values = [value for _, value in _values_of(fn).get(name, [])]
    return bool(values) and all(
        (isinstance(v, ast.Call) and _dotted(v.func) == "len")
        or (isinstance(v, ast.Subscript) and isinstance(v.value, ast.Attribute) and v.value.attr == "shape")
        for v in values)


def _shapes_read(fn) -> list[str]:
    """The parameters of ``fn`` whose ``.shape`` it reads (the inputs an array may be made like; read once per def)."""
    if not hasattr(fn, "_shapes_read"):
        params = {a.arg for a in fn.args.posonlyargs + fn.args.args + fn.args.kwonlyargs}
        fn._shapes_read = sorted({n.value.id for n in walk(fn) if isinstance(n, ast.Attribute)
                                  and n.attr == "shape" and isinstance(n.value, ast.Name) and n.value.id in params})
    return fn._shapes_read


def _loop_bounds(loop, fn) -> list[str]:
    """The names a while loop's test reads that the def sets before the loop and the loop never sets (the
    bounds it is meant to update: RANSAC's adaptive count), read once per loop."""
    if not hasattr(loop, "_bounds"):
        set_in_loop = {n.id for n in walk(loop) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
        params = {a.arg for a in fn.args.args + fn.args.kwonlyargs}
        set_before = {n.id for s in fn.body if s.lineno < loop.lineno
                      for n in walk(s) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
        loop._bounds = sorted({n.id for n in walk(loop.test) if isinstance(n, ast.Name)
                               and n.id not in set_in_loop and n.id in set_before and n.id not in params})
    return loop._bounds


def _enclosing_while(node, parents):
    while id(node) in parents:
        node = parents[id(node)][0]
        if isinstance(node, ast.While):
            return node
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            return None
    return None


def _loop_names(node, parents) -> set[str]:
    """The names the innermost ``for`` loop around ``node`` (in its def) takes."""
    while id(node) in parents:
        node = parents[id(node)][0]
        if isinstance(node, ast.For):
            return {n.id for n in walk(node.target) if isinstance(n, ast.Name)}
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            break
    return set()


def _container_slips(node, parent, parents):
    """Slips in making an array or a list: an array of the input's kind made by hand with a shape that
    drops its channels or dtype (``np.zeros((h, w))`` -> ``np.zeros_like(image)``); a list grown by one item
    where its items belong one by one (``append([x, y])`` <-> ``extend``); a homogeneous matrix's last row
    stacked as ones (``np.ones(3)`` -> ``[0.0, 0.0, 1.0]``); a value stored in another name than the bound
    its while loop tests (``n = ...`` where ``needed`` is tested, and never set in the loop); a value written
    one place off along its innermost loop (``out[y, x]`` -> ``out[y, x - 1]``); a coordinate counted from the
    far end (``h - 1 - y`` -> ``y``); ``map`` zipping two iterables where one is meant whole."""
    dotted = _dotted(node.func) if isinstance(node, ast.Call) else ""
    short = dotted.rsplit(".", 1)[-1]
    if dotted.startswith(("np.", "numpy.")) and short in ("zeros", "ones", "empty") and node.args:
        fn = _def_of(node, parents)
        for name in (_shapes_read(fn) if fn is not None else [])[:3]:
            yield "like_input", f"{dotted}_like({name})", ""
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in ("append", "extend") \
            and len(node.args) == 1 and not node.keywords and isinstance(parent, ast.Expr) \
            and (node.func.attr == "extend" or isinstance(node.args[0], (ast.List, ast.Tuple))):
        other = "extend" if node.func.attr == "append" else "append"
        yield "append_extend", f"{ast.unparse(node.func.value)}.{other}({ast.unparse(node.args[0])})", ""
    if dotted in ("np.ones", "numpy.ones") and len(node.args) == 1 and not node.keywords \
            and isinstance(parent, (ast.List, ast.Tuple)):
        holder = parents.get(id(parent), (None,))[0]
        size = node.args[0]
        row = isinstance(size, ast.Constant) and size.value in (3, 4)
        block = isinstance(size, ast.Tuple) and len(size.elts) == 2 and isinstance(size.elts[0], ast.Constant) \
            and size.elts[0].value == 1 and isinstance(size.elts[1], ast.Constant) and size.elts[1].value in (3, 4)
        if isinstance(holder, ast.Call) and _dotted(holder.func).rsplit(".", 1)[-1] in ("vstack", "row_stack",
                                                                                       "concatenate") and (row or block):
            n = (size.value if row else size.elts[1].value)
            entries = ", ".join(["0.0"] * (n - 1) + ["1.0"])
            yield "last_row", f"[{entries}]" if row else f"[[{entries}]]", ""
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Store):
        # (a value written one place off along the loop: a backtrack storing column x - 1's choice in column x)
        looped = _loop_names(node, parents)
        parts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
        for position, part in enumerate(parts):
            if isinstance(part, ast.Name) and part.id in looped:
                yield "index_step", (position, -1), ""
                yield "index_step", (position, +1), ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Sub) and isinstance(node.left, ast.BinOp) \
            and isinstance(node.left.op, ast.Sub) and isinstance(node.left.right, ast.Constant) \
            and node.left.right.value == 1 and isinstance(node.left.left, (ast.Name, ast.Attribute, ast.Subscript)):
        # (a coordinate counted from the far end, `h - 1 - y`: an image's y counted upwards, where rows count down)
        yield "unflip", ast.unparse(node.right), ""
    if dotted == "map" and len(node.args) == 3 and not node.keywords \
            and isinstance(node.args[0], (ast.Name, ast.Attribute)):
        # (map zips its iterables -- call i gets item i of each -- where one was meant whole with each item of
        # the other: `map(pinhole_project, X, fs)` for one projection of all of X per focal length)
        f, first, second = (ast.unparse(a) for a in node.args)
        yield "map_whole", f"map(lambda each_: {f}({first}, each_), {second})", ""
        yield "map_whole", f"map(lambda each_: {f}(each_, {second}), {first})", ""
    if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
        loop, fn = _enclosing_while(node, parents), _def_of(node, parents)
        for name in (_loop_bounds(loop, fn) if loop is not None and fn is not None else []):
            if name != node.targets[0].id:
                yield "store_name", name, ""


def _student_changes(node, parent, parents, words):
    """Changes made to a student's code only (:mod:`.repair`), told by showing them: a function applied
    that does not belong (``np.tan(s)`` for ``s``), one mistaken for its sibling (``np.sin`` for
    ``np.cos``), a reshape where a transpose belongs, an inversion missing in a matrix product, points
    not divided by their last coordinate (``x[:, :2]``)."""
    if isinstance(node, ast.Call) and _cumulative(node) and node.args and _reversal(node.args[0]) is not None \
            and not (isinstance(parent, ast.Subscript) and parent.value is node and _reversal(parent) is not None):
        # a running minimum (sum, ...) taken from the far end, never turned back
        yield "reverse_back", f"{_operand(node)}[{_slice_text(_reversal(node.args[0]))}]", ""
    yield from _series_powers(node, parent)
    yield from _fraction_changes(node)
    yield from _container_slips(node, parent, parents)
    for parameter in _parameters_for_identity(node, parents):
        # an identity written where a matrix the function is given belongs (cv2.initUndistortRectifyMap's
        # new camera matrix np.eye(3), where K keeps the image's pixels)
        yield "other_name", parameter, ""
    if _negated_reduction(node) is not None:
        # a negated all() where any() belongs (De Morgan's rule half applied: `~np.all(bits, axis=0)` is "not every
        # image lit", where "some image lit" was meant), and the other way round
        yield "flip_reduction", None, ""
    if _filters_a_made_stack(node, parents):
        # an image filter given a whole stack the def made (D, H, W) at once: OpenCV reads its last axis as
        # channels and filters across the first two -- each image of the stack on its own is meant
        yield "per_image", None, ""
    yield from _estimator_changes(node, parents)
    yield from _stacked_last(node, parents)
    yield from _neutral_value(node, parent, parents)
    yield from _twin_test(node, parent, parents)
    yield from _twin_values(node, parent, parents)
    yield from _chosen_value(node, parents)
    if isinstance(node, ast.AugAssign) and isinstance(node.op, (ast.Mult, ast.Div)):
        # (a scaling undone the wrong way round: the entries a normalisation divided, multiplied back, and those
        # it multiplied, divided -- made at two places, it is one slip)
        yield "scale_inverse", None, ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)):
        for tiny, other in ((node.right, node.left), (node.left, node.right)):
            if isinstance(tiny, ast.Constant) and type(tiny.value) is float and 0 < abs(tiny.value) <= 1e-3:
                # (a small number added to keep a division finite: it changes every value it is added to)
                negated = tiny is node.left and isinstance(node.op, ast.Sub)   # (`eps - d` is `-d` without it)
                yield "drop_epsilon", f"-{_operand(other)}" if negated else ast.unparse(other), ""
    if isinstance(node, ast.Constant) and type(node.value) in (int, float) and not isinstance(parent, ast.keyword) \
            and not _in_an_index(node, parents):
        for name, line in _never_read(_def_of(node, parents)):
            if line < node.lineno:
                # (a value the code makes and never reads: meant for a place where a number is written instead)
                yield "unused_name", name, ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) and isinstance(node.left, ast.Name) \
            and isinstance(node.right, ast.Name) and _point_name(node.left.id) and not _point_name(node.right.id):
        # (3D points scaled whole where only x and y are: a magnification by f that scales the depth too, and
        # cancels in the division by it)
        yield "scale_xy", f"{node.left.id} * np.array([{node.right.id}, {node.right.id}, 1.0])", ""
    if isinstance(node, ast.Attribute) and node.attr == "T" and isinstance(node.ctx, ast.Load) \
            and isinstance(node.value, (ast.Name, ast.Call)) \
            and any(isinstance(n, ast.Name) and _image_name(n.id) for n in walk(node.value)):
        # (an image's rows and columns exchanged with .T, which reverses every axis: a colour image's channels
        # come first)
        # (a .T inside it is the same slip: `_down(image.T, tx).T` -> both swapped, the one change nested in the other)
        yield "swap_axes", f"np.swapaxes({ast.unparse(_SwapAxes().visit(copy_tree(node.value)))}, 0, 1)", ""
    yield from _conversion_inverted(node, parent)
    if isinstance(node, ast.Call) and _dotted(node.func) in ("cv2.warpAffine", "cv.warpAffine") and len(node.args) >= 2 \
            and isinstance(node.args[1], ast.Subscript) and isinstance(node.args[1].slice, ast.Slice) \
            and node.args[1].slice.lower is None and isinstance(node.args[1].slice.upper, ast.Constant) \
            and node.args[1].slice.upper.value == 2:
        # a homography's first two rows given to an affine warp: `cv2.warpAffine(img, H[:2], size)`
        new = copy_tree(node)
        new.func = _name(_dotted(node.func).replace("warpAffine", "warpPerspective"))
        new.args[1] = copy_tree(node.args[1].value)
        yield "perspective_warp", ast.unparse(new), ""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.linalg.norm", "numpy.linalg.norm") and node.args \
            and isinstance(node.args[0], ast.BinOp) and isinstance(node.args[0].op, ast.Sub) \
            and any(k.arg == "axis" and isinstance(k.value, (ast.Constant, ast.UnaryOp)) for k in node.keywords):
        # the distance between two points where the difference of their x belongs (a disparity x_l - x_r)
        yield "x_difference", f"({ast.unparse(node.args[0])})[:, 0]", ""
    given = next((k for k in getattr(node, "keywords", ()) if k.arg == "channel_axis"), None) \
        if isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Name) else None
    if given is not None and not (isinstance(given.value, ast.Constant) and given.value.value is None) \
            and not isinstance(given.value, ast.IfExp):
        # scikit-image told the last axis holds colours on a grey image too (its columns taken for channels)
        new = copy_tree(node)
        image = node.args[0].id
        new.keywords = [ast.keyword("channel_axis", parse(f"{ast.unparse(given.value)} if {image}.ndim == 3 else None",
                                                          mode="eval").body) if k.arg == "channel_axis" else k
                        for k in new.keywords]
        yield "colour_axis", ast.unparse(new), ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Sub, ast.Add)) and isinstance(node.left, ast.Constant) \
            and node.left.value in (1, 1.0) and type(node.left.value) in (int, float) \
            and isinstance(node.right, (ast.Name, ast.Attribute, ast.Subscript, ast.Call)) \
            and isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.MatMult):
        # the number 1 where the identity matrix belongs (`(1 - R) @ c` for `(I - R) c`): NumPy takes every
        # entry from 1, not the diagonal's alone
        sign = "-" if isinstance(node.op, ast.Sub) else "+"
        yield "identity", f"np.eye(len({_operand(node.right)})) {sign} {_operand(node.right)}", ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitXor) \
            and not (isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.BitXor)) \
            and re.search(r"\^ [23]\b", ast.unparse(node)):
        # `x ^ 2 + y ^ 2` for a sum of squares: Python's ^ is a bitwise XOR, binding looser than + (it
        # parses as x ^ (2 + y) ^ 2), so the text is read again with ** in its place
        yield "power_xor", ast.unparse(parse(ast.unparse(node).replace("^", "**"), mode="eval").body), ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)) and isinstance(node.right, ast.Constant) \
            and node.right.value == 0.5:
        # a half-pixel offset the convention does not have (pixel centres at integers)
        yield "half_pixel", ast.unparse(node.left) if not isinstance(node.left, ast.BinOp) \
            else f"({ast.unparse(node.left)})", ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add) and isinstance(node.left, ast.Name) \
            and isinstance(node.right, ast.Name) and twin_names(node.left.id, node.right.id) \
            and all(_stacked_rows(name, _def_of(node, parents)) for name in (node.left.id, node.right.id)):
        # two twins' blocks of rows added where they stack (`A = rows_u + rows_v`: each point's two equations
        # summed into one)
        yield "add_stacked", f"np.vstack([{node.left.id}, {node.right.id}])", ""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.arctan2", "numpy.arctan2", "math.atan2") \
            and len(node.args) == 2 and not node.keywords:
        # an angle where the ratio belongs (`f * np.arctan2(X, Z)` for the pinhole's `f * X / Z`)
        yield "unwrap", "ratio", ""
    if isinstance(node, ast.Call) and _dotted(node.func).startswith(("np.", "numpy.")) and len(node.args) == 2 \
            and not node.keywords and isinstance(node.args[0], (ast.List, ast.Tuple)) and node.args[0].elts \
            and isinstance(node.args[1], (ast.Constant, ast.Name)) and not isinstance(getattr(node.args[1], "value", 0), str):
        # a list closed one item early: `np.diag([sx, sy], 1)` (1 taken for the diagonal's offset) where
        # `np.diag([sx, sy, 1])` belongs
        items = ", ".join(ast.unparse(e) for e in [*node.args[0].elts, node.args[1]])
        yield "bracket", f"{ast.unparse(node.func)}([{items}])", ""
    bracketed = _brackets_left_out(node)
    if bracketed is not None:
        # a factor's brackets left out: `p2 * r2 + 2 * x * x` where `p2 * (r2 + 2 * x * x)` belongs
        yield "bracket", bracketed, ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) and isinstance(node.right, ast.Constant) \
            and node.right.value == 2 and isinstance(node.left, (ast.Name, ast.Subscript)) \
            and _holds_bytes(_root(node, parents)):
        # a square taken in the image's own 8 bits (`cv2.absdiff(L, R) ** 2` wraps round from 16 on)
        yield "widen", f"{_operand(node.left)}.astype(np.float64) ** 2", ""
    if isinstance(node, ast.Call) and _dotted(node.func).startswith(("cv2.", "cv.")) \
            and _dotted(node.func).rsplit(".", 1)[-1] in _NESTED_POINTS \
            and not isinstance(parent, ast.Subscript) \
            and not (isinstance(parent, ast.Attribute) and parent.attr in ("reshape", "squeeze")):
        # OpenCV's points one per (1, k) row -- (N, 1, 3) from cv2.convertPointsToHomogeneous -- used as
        # (N, k): every product and index on them broadcasts otherwise
        yield "middle_axis", f"{_operand(node)}[:, 0]", ""
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(node.value, ast.Name) \
            and isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2 \
            and all(isinstance(e, ast.Constant) and type(e.value) is int for e in node.slice.elts) \
            and node.slice.elts[0].value == node.slice.elts[1].value in (0, 1):
        # the other entry of a diagonal: `K[0, 0]` (fx) where `K[1, 1]` (fy) belongs
        other = 1 - node.slice.elts[0].value
        yield "axis", [other, other], ""
    if isinstance(node, ast.Attribute) and node.attr == "T" and isinstance(node.ctx, ast.Load) \
            and isinstance(node.value, ast.BinOp) and isinstance(node.value.op, ast.MatMult):
        # a transpose of a whole product where one factor's belongs: `(K2 @ F).T` for `K2.T @ F`
        left, right = node.value.left, node.value.right
        yield "factor_transposed", f"{_operand(left)}.T @ {ast.unparse(right)}" if isinstance(left, (ast.Name, ast.Subscript,
                                                                                                  ast.Attribute)) \
            else f"({ast.unparse(left)}).T @ {ast.unparse(right)}", ""
        yield "factor_transposed", f"{ast.unparse(left)} @ {_operand(right)}.T" if isinstance(right, (ast.Name, ast.Subscript,
                                                                                                   ast.Attribute)) \
            else f"{ast.unparse(left)} @ ({ast.unparse(right)}).T", ""
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and _column_taken(node) \
            and (isinstance(parent, ast.Assign) or (isinstance(parent, ast.IfExp) and parent.test is not node)):
        # a whole column named where its mean belongs: `z = X[:, 2]` for the mean depth
        yield "reduced", f"{_operand(node)}.mean()", ""
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and _reversal(node) is not None:
        # an order reversed that does not belong: `tuple(pattern_size)[::-1]`, NumPy's (rows, columns)
        # habit where OpenCV takes (columns, rows)
        yield "drop_reversal", ast.unparse(node.value), ""
    if isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.MatMult) \
            and isinstance(node, (ast.Name, ast.Subscript, ast.Call)) and not _is_inverse(node):
        yield "inverse", "wrap", ""
    if _reciprocal_of(node) is not None:
        # each entry's reciprocal where the matrix inverse belongs: `M ** -1`, `1 / M` (the sheet's M^-1)
        yield "inverse", "entrywise", ""
    if _chain_of_three(node) is not None and not (isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.MatMult)):
        yield "chain_order", "first", ""   # `A @ B @ C` -> `B @ A @ C`
        yield "chain_order", "last", ""    # `A @ B @ C` -> `A @ C @ B` (K2.T @ K1 @ F for K2.T @ F @ K1)
        yield "chain_order", "outer", ""   # `A @ B @ C` -> `C @ B @ A` (T(-c) @ R @ T(c) for T(c) @ R @ T(-c))
    if _cv_point_pair(node):
        yield "transpose", "cv_points", ""   # both point sets given as rows where columns belong (2 x N)
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.RShift, ast.LShift)) \
            and isinstance(node.right, ast.BinOp) and isinstance(node.right.op, (ast.Add, ast.Sub)) \
            and not any(isinstance(part, ast.Constant) for part in (node.right.left, node.right.right)):
        # a bit read one place off: `(g >> (n - i)) & 1` where `n - 1 - i` belongs (no constant to move)
        for step in (ast.Sub(), ast.Add()):
            moved = copy_tree(node)
            moved.right = ast.BinOp(moved.right, step, ast.Constant(1))
            yield "zero_based", ast.unparse(moved), ""
    if isinstance(parent, ast.Assign) and parent.value is node and isinstance(node, (ast.List, ast.Tuple)) \
            and 2 <= len(node.elts) <= 4 and not any(isinstance(e, (ast.List, ast.Tuple, ast.Starred)) for e in node.elts) \
            and any(isinstance(t, ast.Subscript) and isinstance(t.slice, ast.Tuple) and len(t.slice.elts) == 2
                    and all(isinstance(part, ast.Slice) for part in t.slice.elts) for t in parent.targets):
        # a row of values given to a square block (`M[:2, :2] = [sx, sy]`: every row gets both): its diagonal
        yield "zero_entry", f"np.diag({ast.unparse(node) if isinstance(node, ast.List) else '[' + ast.unparse(node)[1:-1] + ']'})", ""
    if isinstance(parent, ast.Assign) and parent.value is node and isinstance(node, ast.Name) \
            and len(parent.targets) == 1 and isinstance(parent.targets[0], ast.Name) \
            and _written_into(_root(parent, parents), parent.targets[0].id, parent.lineno):
        # a second name for the same array, then written into (`moved = pts` then `moved[:, 2] += s`: pts
        # changes too, and each pass of a loop starts from the last one's): a copy
        yield "zero_entry", f"{node.id}.copy()", ""
    middle = _midrange(node)
    if middle is not None:
        yield "midrange", middle, ""   # the middle of the range where the mean belongs: (Z.min() + Z.max()) / 2
    scaled = _scaled_identity(node)
    if scaled is not None:
        yield "zero_entry", f"np.diag([{scaled}, {scaled}, 1.0])", ""   # f * np.eye(3): K's last entry is 1
    yield from _grid_axis_changes(node)
    yield from _layout_and_type_changes(node)
    if isinstance(parent, ast.Return) and parent.value is node:
        rebuilt = _rebuilt_from(node, words)
        if rebuilt is not None:
            # `U @ np.diag([s[0], s[1], 0]) @ Vt` returned where the matrix decomposed belongs: a step the
            # function was not to take (E = K2^T F K1 made rank 2 on the way out)
            yield "undecomposed", rebuilt, ""
    if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Subscript) \
            and (_reversal(node.value) is not None) != (_reversal(node) is not None) \
            and isinstance(node.slice, ast.Slice) and isinstance(node.value.slice, ast.Slice):
        # `image.shape[::-1][:2]` (the last two sizes, reversed: (3, W) of a colour image) for
        # `image.shape[:2][::-1]` (W, H): a reversal and a slice taken in the other order
        yield "slice_order", None, ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Sub, ast.Add)) and isinstance(node.right, ast.Name):
        for matrix in _made_from(node.right.id, words, node.lineno):
            # `t = dst_mean - src_mean` where L was fitted on points moved by src_mean: `dst_mean - L @ src_mean`
            yield "map_term", matrix, ""
    if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
        for rotation, inverse in _centre_and_translation(node, parent, words):
            # t = -R C: the camera centre given where the translation belongs (`tvec = C`), or the other way
            yield "centre_translation", (rotation, inverse), ""
    if _antisymmetric_literal(node):
        # a rotation written out transposed (`[[c, 0, -s], [0, 1, 0], [s, 0, c]]` for the y rotation's
        # `[[c, 0, s], ..., [-s, 0, c]]`): the sine terms have each other's signs, one slip in two places
        yield "transpose", "literal", "the matrix written out has its sine terms' signs exchanged (it is transposed)"
    if isinstance(parent, ast.Call) and len(parent.args) >= 2 and node is parent.args[1] \
            and _dotted(parent.func).rsplit(".", 1)[-1] in ("lstsq", "solve") \
            and not (isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub)):
        yield "sign", "insert", ""   # a term moved to the right-hand side of A x = b without its minus
    if isinstance(parent, ast.Assign) and parent.value is node and isinstance(node, ast.BinOp) \
            and isinstance(node.op, ast.MatMult):
        yield "sign", "insert", ""   # a product's minus dropped: `C = R.T @ t` for a camera centre's `-R.T @ t`
    if isinstance(parent, ast.List) and isinstance(parents.get(id(parent), (None,))[0], ast.List) \
            and isinstance(node, (ast.BinOp, ast.UnaryOp, ast.Call)):
        yield "zero_entry", "0", ""   # a matrix literal's entry that does not belong: `[1, s, -s * (h - 1) / 2]`
    if isinstance(node, (ast.List, ast.Tuple)) and len(node.elts) >= 2 and isinstance(node.ctx, ast.Load) \
            and all(isinstance(item, ast.UnaryOp) and isinstance(item.op, ast.USub) for item in node.elts):
        yield "sign", "all", ""   # `rhs.extend([-u, -v])`: every item's minus, one slip
    if isinstance(parent, ast.Call) and node in parent.args and len(parent.args) == 1 \
            and _dotted(parent.func).rsplit(".", 1)[-1] in ("sin", "cos", "tan") \
            and not (isinstance(node, ast.Call) and _dotted(node.func) in _ANGLE_CONVERSIONS) \
            and not _in_radians(node, parents):
        yield "degrees", "np.deg2rad", ""   # an angle in degrees given to the sine
    if isinstance(parent, ast.BinOp) and isinstance(parent.op, (ast.Add, ast.Sub, ast.Mult)) \
            and isinstance(node, (ast.Name, ast.Subscript)) and node is parent.right \
            and not (isinstance(parent.op, ast.Mult) and _image_size(parent.left)):
        # a term's sign: `x + s * y` for `x - s * y` (never a factor of an image's size, `width * -sx`: a
        # size is never negative, and OpenCV reads one as "the input's", right by that alone)
        yield "sign", "insert", ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitXor) and isinstance(node.left, ast.Constant):
        yield "arithmetic", "xor_pow", ""   # `2 ^ n` (bitwise exclusive or, in Python) where `2 ** n` belongs
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult):
        for dropped, factor in (("left", node.left), ("right", node.right)):
            if not (isinstance(factor, ast.UnaryOp) or (isinstance(factor, ast.Constant) and factor.value in (1, -1))):
                yield "drop_factor", dropped, ""   # a factor that does not belong: `f * Z` for `Z`
    # OpenCV's 0/1 masks (findFundamentalMat's, findHomography's) used as indices pick items 0 and 1: a
    # mask, known by its name, indexing (`pts[mask.ravel()]`) or made for it (`inliers = mask.ravel()`)
    if isinstance(parent, ast.Subscript) and parent.slice is node and isinstance(parent.ctx, ast.Load) \
            and isinstance(node, (ast.Name, ast.Call, ast.Attribute)) and not _is_astype(node) and _a_mask(node):
        yield "boolean_mask", None, ""
    if isinstance(parent, ast.Assign) and parent.value is node and isinstance(node, (ast.Call, ast.Attribute)) \
            and not _is_astype(node) and any(_a_mask(part) for part in (*parent.targets, node)):
        yield "boolean_mask", None, ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Sub) and _indexes(node, parent, parents) \
            and not isinstance(node.left, ast.Constant) and not isinstance(node.right, ast.Constant):
        yield "negative_index", "wrap", ""   # `ramp[i - j]`: a negative index wraps round where |i - j| belongs
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load):
        last = node.slice.elts[-1] if isinstance(node.slice, ast.Tuple) and node.slice.elts else node.slice
        if isinstance(last, ast.Slice) and last.lower is None and last.step is None \
                and isinstance(last.upper, ast.Constant) and last.upper.value in (2, 3):
            yield "dehomogenise", last.upper.value, ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div) and isinstance(node.left, ast.Subscript):
        # `x[:, :2] / depth` -> `x[:, :2] / x[:, 2:3]`: points divided by another value than their own last
        # coordinate (the Z of the points before K was applied, where K's w belongs)
        last = node.left.slice.elts[-1] if isinstance(node.left.slice, ast.Tuple) and node.left.slice.elts \
            else node.left.slice
        if isinstance(last, ast.Slice) and last.lower is None and last.step is None \
                and isinstance(last.upper, ast.Constant) and last.upper.value in (2, 3) \
                and not (isinstance(node.right, ast.Subscript) and ast.dump(node.right.value) == ast.dump(node.left.value)):
            # (a divisor read from the points themselves, `x[:, 2]`, is theirs already: its axis is another slip)
            yield "dehomogenise", ("divisor", last.upper.value), ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult):
        # `pts @ M[:, :3].T` (or `M[:, :3] @ X`) where the homogeneous 1 belongs: M's last column missing,
        # added as a row (points in rows, or a single point) or as a column (points in columns)
        for side, factor in (("right", node.right), ("left", node.left)):
            if _sliced_block(factor)[0] is not None:
                for shape in ("row", "column"):
                    yield "translation", (side, shape), ""
    yield from _numpy_slips(node, parent, parents)
    yield from _column_order(node, parent)
    yield from _singular_value_changes(node, parent)
    if isinstance(node, ast.Constant) and type(node.value) in (int, float) and node.value in (0, 1) \
            and isinstance(parent, (ast.List, ast.Tuple)) and 3 <= len(parent.elts) <= 4 and parent.elts[-1] is node \
            and not all(isinstance(e, ast.Constant) for e in parent.elts):
        # a point's homogeneous coordinate written 0 where 1 belongs (`[X, Y, Z, 0.0]`: w = 0), or 1 for 0 (a
        # direction)
        yield "literal", type(node.value)(1 - node.value), ""
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(node.value, ast.Call) \
            and _dotted(node.value.func).startswith(("cv2.", "cv.", "np.linalg.", "numpy.linalg.")) \
            and isinstance(node.slice, ast.Constant) and type(node.slice.value) is int and 0 <= node.slice.value <= 4:
        # another of the results a library call returns (`cv2.findHomography(...)[1]`: the mask, not H)
        for other in range(5):
            if other != node.slice.value:
                yield "other_result", f"{_operand(node.value)}[{other}]", ""
    if isinstance(node, ast.Call) and _dotted(node.func).startswith(("cv2.", "cv.", "np.linalg.", "numpy.linalg.")) \
            and (isinstance(parent, ast.Return) or isinstance(parent, ast.Assign) and len(parent.targets) == 1
                 and isinstance(parent.targets[0], ast.Name)):
        # the whole tuple a library call returns kept where one of its results belongs
        # (`A = cv2.estimateAffine2D(src, dst)`: the matrix and the inlier mask)
        for item in range(2):
            yield "other_result", f"{_operand(node)}[{item}]", ""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.where", "numpy.where", "np.nonzero", "numpy.nonzero") \
            and len(node.args) == 1 and not (isinstance(parent, ast.Subscript) and parent.value is node) \
            and not isinstance(parent, ast.Starred):
        # the tuple of index arrays np.where(mask) returns kept where its first array belongs (`len(np.where(m))` is 1)
        yield "other_result", f"{_operand(node)}[0]", ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div) \
            and isinstance(node.right, (ast.Name, ast.Subscript)) and not isinstance(node.left, ast.Constant):
        for invalid in ("0.0", "np.nan"):   # a division with no guard where the divisor may be 0 or below
            yield "guard", invalid, ""
    if isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], (ast.Lt, ast.LtE)) \
            and isinstance(node.left, ast.Name) and not isinstance(node.comparators[0], ast.Constant):
        yield "lower_bound", None, ""   # an index tested against its upper end only: `cols < width`
    if isinstance(node, ast.Compare) and len(node.ops) == 1 \
            and isinstance(node.ops[0], (ast.Lt, ast.LtE, ast.Gt, ast.GtE)):
        yield from _squared_bounds(node, words)
    if isinstance(node, (ast.List, ast.Tuple)) and len(node.elts) == 3:
        yield from _translation_scaled(node)
    if isinstance(node, ast.Constant) and type(node.value) is float:
        exact = _exact_constant(node.value)
        if exact:
            yield "exact_constant", exact, ""   # a constant typed with a few digits: `3.14` where np.pi belongs
    yield from _conversion_slips(node, parent)
    if isinstance(node, (ast.Tuple, ast.List)):
        yield from _item_swaps(node, parent)
    yield from _measure_changes(node)
    if isinstance(parent, ast.Assign) and parent.value is node and _sum_of_squares(node):
        yield "measure", "sqrt", ""   # `r = x ** 2 + y ** 2` where the radius, its root, belongs
    if isinstance(node, ast.Slice):
        # (in a write, one entry where a slice runs on is the slice item's change, `M[0, 1] = s`: not told twice)
        subscript = parent if isinstance(parent, ast.Subscript) else parents.get(id(parent), (None,))[0]
        written = isinstance(subscript, ast.Subscript) and isinstance(subscript.ctx, ast.Store)
        yield from (change for change in _slice_changes(node)
                    if not (written and isinstance(change[1], tuple) and change[1][0] is not None
                            and change[1][1] == change[1][0] + 1 and node.upper is None))
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Store):
        yield from _slice_item_changes(node)
    if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name):
        yield from _row_column_changes(node)

    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(node.slice, ast.Slice) \
            and node.slice.lower is None and node.slice.step is None \
            and isinstance(node.slice.upper, ast.Constant) and isinstance(node.slice.upper.value, int) \
            and node.slice.upper.value >= 4:
        yield "drop_slice", None, ""   # `pts[:8]`: only the first few used where all belong
    measured = _measured_after_filtering(node)
    if measured is not None:
        yield "measure_first", measured, ""   # |box(l) - box(r)|: the difference of means where the mean of the differences belongs
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(node.value, ast.Name) \
            and isinstance(node.slice, ast.Name) and node.slice.id in _mask_names(_root(node, parents)):
        yield "drop_slice", None, ""   # `src[inliers]`: the points a mask kept, where every point belongs
    chain = _chain_of_three(node)
    if chain is not None and not any(_is_inverse(f) for f in (chain[0], chain[2])):
        yield "inverse", "undone_never", ""   # `K2.T @ F @ K1` -> `F`: a transform applied twice, or too early
    if isinstance(node, ast.Call):
        yield from _dtype_changes(node, _calls_opencv(_root(node, parents)))
        if _calls_opencv(_root(node, parents)):
            yield from _python_numbers(node)
        yield from _shape_changes(node)
        yield from _factor_moves(node)
        yield from _converted_late(node)
        yield from _call_slips(node)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult):
        yield from _factor_moves(node)
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)) \
            and not isinstance(node.right, ast.Constant) and not isinstance(parent, ast.Subscript):
        yield "drop_term", ast.unparse(node.left), ""   # `X[:, 2] + f` where `X[:, 2]` belongs (an extra term)
    yield from _focal_left_out(node, parent)
    yield from _perpendicular(node, parent)
    yield from _key_order(node)
    yield from _to_degrees(node, parent)
    yield from _type_widened(node)
    yield from _size_written(node, parents)
    if isinstance(node, ast.Call) and _dotted(node.func) in _BOUNDS_OF_TWO and len(node.args) == 2 and not node.keywords \
            and not any(isinstance(a, ast.Starred) for a in node.args):
        # (`max(reference.shape[0], moving.shape[0])` where the reference's own size belongs: a bound taken
        # over a value that has no part in it)
        for argument in node.args:
            yield "one_of_two", ast.unparse(argument), ""
    if isinstance(node, ast.Expr):
        yield from _discarded_result(node)
    if isinstance(node, ast.AugAssign) and isinstance(node.op, (ast.Add, ast.Sub)):
        yield "add_sub", None, ""   # `total -= d` for `total += d`
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) and isinstance(node.left, ast.BinOp) \
            and isinstance(node.left.op, (ast.Add, ast.Sub)) and isinstance(node.right, ast.Constant):
        yield "power_spread", None, ""   # `(x + y) ** 2` where `x ** 2 + y ** 2` belongs
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)) \
            and isinstance(node.right, ast.BinOp) and isinstance(node.right.op, _BINDS_TIGHTER):
        yield "regroup", "first", ""     # `w - 1 / 2` for `(w - 1) / 2`
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)) \
            and isinstance(node.left, ast.BinOp) and isinstance(node.left.op, _BINDS_TIGHTER):
        yield "regroup", "last", ""      # `a * b + c` for `a * (b + c)`
    if isinstance(node, ast.BinOp) and isinstance(node.op, _BITWISE) \
            and isinstance(node.right, ast.BinOp) and isinstance(node.right.op, _BINDS_BEFORE_BITS):
        yield "regroup", "first", ""     # `k << 1 + bit` is `k << (1 + bit)`: `(k << 1) + bit` was meant
    if isinstance(node, ast.BinOp) and isinstance(node.op, _BITWISE) \
            and isinstance(node.left, ast.BinOp) and isinstance(node.left.op, _BINDS_BEFORE_BITS):
        yield "regroup", "last", ""      # `a + b << 2` is `(a + b) << 2`: `a + (b << 2)` was meant
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.FloorDiv) \
            and isinstance(node.right, ast.BinOp) and isinstance(node.right.op, ast.FloorDiv):
        yield "regroup", "divisor_rounded", ""   # `u // (w // 2 ** n)`: a stripe's width rounded before it divides
    # (and `u * (2 ** n / w)`: the factor rounded first, so an exact integer u * 2 ** n / w comes out a hair
    # below it and its floor one less)
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.arctan", "numpy.arctan", "math.atan") \
            and len(node.args) == 1 and isinstance(node.args[0], ast.BinOp) and isinstance(node.args[0].op, ast.Div):
        yield "quadrant", "math.atan2" if _dotted(node.func) == "math.atan" else "np.arctan2", \
            "the angle is taken with arctan of a ratio, which loses its quadrant (arctan2 keeps it)"
    if words.student and isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
        for local in _resolved_from(node.id, words, node.lineno):
            yield "other_name", local, ""   # `DEFAULT_SMOOTHNESS` read again where `s`, made from it and the parameter, belongs
    if words.student:
        for pair in _twin_pairs_beside_a_swap(node, words.fn):
            yield "swap_both", pair, ""   # the cameras exchanged, their points left (`P1, P2 = P2, P1`)
    if words.student:
        vector = _third_entry_replaced(node)
        if vector:
            yield "whole_vector", f"{vector} / {vector}[2]", ""   # its third entry divided out
            yield "whole_vector", vector, ""                        # or kept, homogeneous
    if words.student and isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
        for first, second in _frame_partners(node.targets[0].id, node, words):
            yield "frame_cross", (first, second), ""   # a rotation's row not made orthogonal to the other two
    if words.student and _nan_fill_minimised(node, parents, words):
        yield "fill_inf", "nan", ""   # a cost NaN where the argmin must lose it: NumPy's argmin picks the first NaN
    if words.student and isinstance(node, ast.Constant) and type(node.value) in (int, float) and node.value == 1 \
            and _drawn_colour(node, parents, words.fn):
        yield "colour_scale", "255", ""   # a colour of 1 (a [0, 1] image's white) drawn on a uint8 image
    if words.student and isinstance(node, ast.BinOp) and isinstance(node.op, ast.Sub) \
            and isinstance(node.right, ast.Constant) and type(node.right.value) is int and node.right.value > 0 \
            and _size_of_something(node.left) and _indexes_with(node, parent):
        yield "from_end", None, ""   # `Vt[len(A) - 1]` for `Vt[-1]`: the end counted with another array's size
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) and isinstance(node.right, ast.BinOp) \
            and isinstance(node.right.op, (ast.FloorDiv, ast.Div)):
        yield "regroup", "first", ""     # `u * (2 ** n // w)` for `u * 2 ** n // w`: the floor taken first
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) and isinstance(node.left, ast.BinOp) \
            and isinstance(node.left.op, (ast.FloorDiv, ast.Div)):
        yield "regroup", "floor_last", ""   # `(2 ** n // w) * u` for `2 ** n * u // w`
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div, ast.MatMult)) \
            and isinstance(node.left, ast.BinOp) and isinstance(node.left.op, (ast.Add, ast.Sub)):
        yield "regroup", "factor_last", ""    # `(ideal - A) * s` for `ideal - A * s`: the factor of one term
        yield "regroup", "factor_first", ""   # `(x - c) * s` for `x * s - c`; `(X + p4) @ M.T` for `X @ M.T + p4`
    if isinstance(parent, ast.For) and parent.iter is node:
        yield from _loop_order_changes(node)
    if isinstance(node, ast.Compare) and len(node.ops) == 1:
        yield from _precedence_slips(node)
    if words.student and isinstance(node, ast.IfExp) and isinstance(node.body, ast.BinOp):
        # `f * X / z if z is not None else mean` for `f * X / (z if z is not None else mean)`: the conditional
        # binds loosest, so its else-branch is the whole answer, not the last operand
        body = node.body
        yield "precedence", (f"{ast.unparse(body.left) if not isinstance(body.left, ast.IfExp) else _grouped(body.left)} "
                             f"{ast.unparse(ast.BinOp(ast.Name('a'), body.op, ast.Name('b'))).split()[1]} "
                             f"({ast.unparse(body.right)} if {ast.unparse(node.test)} else {ast.unparse(node.orelse)})"), ""
    if isinstance(node, ast.Compare) and len(node.ops) == 1 and type(node.ops[0]) in _COMPARED:
        for other in _COMPARED[type(node.ops[0])]:
            yield "compare", other, ""   # `x > 0` for `x >= 0`, or the other way
        yield from _threshold_changes(node)
    if words.student and isinstance(node, ast.Compare) and len(node.ops) == 1 and type(node.ops[0]) in _BOUNDED \
            and isinstance(node.comparators[0], ast.Constant) and type(node.comparators[0].value) in (int, float) \
            and not isinstance(node.left, ast.Constant):
        for other in _BOUNDED[type(node.ops[0])]:
            yield "compare", other, ""   # `rank != 8` for `rank < 8`: one value tested where a bound belongs
    if isinstance(parent, ast.List) and len(parent.elts) >= 3 and not _entry_of_literal(node, parents) \
            and isinstance(node, (ast.Name, ast.Subscript, ast.Attribute, ast.BinOp, ast.Call)) \
            and any(_negated(item) for item in parent.elts):
        # an entry of a row of signed terms built from a formula (`[..., -v * Z, v]` for `-v`)
        yield "sign", "insert", ""
    if isinstance(node, ast.BinOp) and type(node.op) in (ast.Sub, ast.Div) \
            and type(node.right) is ast.BinOp and type(node.right.op) in _REGROUPED[type(node.op)]:
        yield "regroup", "flat", ""      # `a - (b + c)` for `a - b + c`
    if isinstance(node, ast.BinOp) and type(node.left) is ast.BinOp and type(node.left.op) in (ast.Sub, ast.Div) \
            and type(node.op) in _REGROUPED[type(node.left.op)]:
        yield "regroup", "nested", ""    # `a / b * c` for `a / (b * c)`
    if isinstance(parent, ast.Compare) and parent.left is node and len(parent.ops) == 1 \
            and isinstance(parent.ops[0], (ast.Lt, ast.LtE)) and isinstance(parent.comparators[0], ast.Constant) \
            and isinstance(parent.comparators[0].value, (int, float)) and 0 <= parent.comparators[0].value < 1 \
            and not (isinstance(node, ast.Call) and _dotted(node.func).rsplit(".", 1)[-1] in ("abs", "fabs", "absolute")):
        holder = parents.get(id(parent), (None,))[0]
        if isinstance(holder, ast.If) and holder.test is parent \
                and any(isinstance(n, (ast.Raise, ast.Return)) for n in holder.body):
            # a signed value tested where its size belongs: `if area <= 0: raise` (a degenerate triangle
            # has area 0; one listed clockwise has a negative area and is none)
            yield "magnitude", "wrap", ""
    if not isinstance(node, ast.Call):
        return
    dotted = _dotted(node.func)
    short = dotted.rsplit(".", 1)[-1]
    prefix = dotted[: -len(short)]
    if _integer_cast(node):
        yield "float_kept", _integer_cast(node), ""   # floats cut to integers: `np.int32(pts1)`
    if _unary_call(node) or (len(node.args) == 1 and not node.keywords and dotted in _WHOLE_REDUCTIONS):
        yield "unwrap", None, ""
        if _unary_call(node.args[0]):
            yield "unwrap", "chain", ""   # two functions applied that do not belong (an angle's tan of its radians)
    if (isinstance(node.func, ast.Name) and node.func.id.startswith("_") and len(node.args) == 1
            and not node.keywords or short == "cvtColor" and len(node.args) == 2) \
            and isinstance(node.args[0], ast.Name) and isinstance(parent, ast.Call) and node in parent.args:
        # an input converted on its way into a call where the input itself belongs: `warp(_grey(moving), H)`
        # (the grey copy made for a comparison, passed on where the colour image is warped)
        yield "unwrap", None, ""
    whole_method = isinstance(node.func, ast.Attribute) and node.func.attr in _WHOLE_METHODS and not node.args \
        and not node.keywords
    if whole_method:
        yield "unwrap", "method", ""   # one value of the whole array where each item's own belongs (a mean depth)
    reduced = node.func.value if whole_method else node.args[0] if len(node.args) == 1 and not node.keywords \
        and dotted in _WHOLE_REDUCTIONS else None
    if isinstance(reduced, ast.Name) and isinstance(parent, ast.BinOp) and parent.right is node \
            and isinstance(parent.op, (ast.Div, ast.Mult)) \
            and reduced.id in _summed_up(_def_of(node, parents)):
        # (each pixel's own sum, given to an operand with one more axis: a colour image divided by the
        # per-pixel sum of weights the code adds up, where one number for the whole canvas was taken)
        yield "own_values", None, ""
    if short == "addWeighted" and prefix in ("cv2.", "cv.") and len(node.args) >= 3:
        yield "unwrap", None, ""      # a drawing blended with the image it was drawn on a copy of: the drawing itself
        yield "unwrap", "third", ""   # (or the image, where the blend was to leave it as it was)
    if short in _GATHERS and prefix in ("np.", "numpy.") and node.args and isinstance(node.args[0], ast.Name) \
            and isinstance(parent, ast.Return):
        yield "unwrap", None, ""   # a result gathered anew before it is returned: `np.take_along_axis(depth, source)`
    if _rounded_to_decimals(node, dotted):
        yield "unwrap", None, ""   # a value rounded to a few decimals where the exact one belongs: `np.round(c, 2)`
    if words.student and dotted in ("np.unique", "numpy.unique", "sorted", "set") and node.args \
            and isinstance(parent, (ast.For, ast.comprehension)) and parent.iter is node:
        yield "unwrap", None, ""   # a loop over the items sorted and made unique where each given one belongs, in order
    if dotted in ("np.clip", "numpy.clip") and node.args and not (isinstance(parent, ast.Attribute) and parent.attr == "astype"):
        yield "unwrap", None, ""   # a clip of an intermediate value that may be signed or beyond 255: a band-pass level
    if dotted in ("np.maximum", "numpy.maximum", "np.minimum", "numpy.minimum", "max", "min") and len(node.args) == 2 \
            and not node.keywords and sum(isinstance(_bare(a), ast.Constant) for a in node.args) == 1:
        yield "unwrap", "clamped", ""   # a value clamped to a bound where it belongs whole: `f * b / np.maximum(d, 1.0)`
    if isinstance(node.func, ast.Attribute) and node.func.attr == "squeeze" and not node.args and not node.keywords:
        # every length-1 axis dropped, those the API keeps too (one distance, one point): the array as made
        yield "unwrap", "method", ""
    if isinstance(node.func, ast.Attribute) and node.func.attr == "round" and dotted not in _ROUNDING \
            and dotted.split(".")[0] not in ("np", "numpy", "math") and (node.args or node.keywords):
        yield "unwrap", "method", ""   # `np.cos(t).round(2)` -> `np.cos(t)`
    if short in _MISTAKEN and prefix in ("np.", "numpy.", "math.") and not _log_of_a_ratio(node, short, parent):
        yield "function", prefix + _MISTAKEN[short], ""
    if short in ("ones", "zeros", "empty") and prefix in ("np.", "numpy.") and len(node.args) == 1 \
            and isinstance(node.args[0], ast.Tuple) and len(node.args[0].elts) == 2 \
            and ast.dump(node.args[0].elts[0]) == ast.dump(node.args[0].elts[1]):
        # a square matrix started filled where the identity belongs (the entries never set keep the fill)
        yield "identity", f"{prefix}eye({ast.unparse(node.args[0].elts[0])})", ""
    if short in _CV_MISTAKEN and prefix in ("cv2.", "cv."):
        yield "function", prefix + _CV_MISTAKEN[short], ""
    if dotted == "int" and len(node.args) == 1 and not node.keywords and not (
            isinstance(node.args[0], ast.Call) and _dotted(node.args[0].func).rsplit(".", 1)[-1] in _ROUNDED):
        # (truncation taken for the floor: int(-20.4) is -20, the whole pixels below it -21 -- a shift split into
        # whole pixels and a remainder that do not add up for negative ones)
        yield "function", "np.floor", ""
    if isinstance(node.func, ast.Attribute) and node.func.attr == "reshape":
        yield "transpose", "for_reshape", ""
        inner = node.func.value
        grid = (isinstance(inner, ast.Subscript) and _dotted(inner.value) in ("np.mgrid", "numpy.mgrid")) or (
            isinstance(inner, ast.Call) and _dotted(inner.func).rsplit(".", 1)[-1] in ("indices", "meshgrid", "stack"))
        if grid:
            # (a grid read in memory order: `np.mgrid[0:c, 0:r].reshape(-1, 2)`, its x's and y's in runs, where
            # each point's (x, y) -- `.T.reshape(-1, 2)` -- belongs)
            yield "transpose", "before_reshape", ""


def _negated(node) -> bool:
    """Whether a term is written with a minus in front (`-v`, `-v * Z`)."""
    while isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div, ast.MatMult)):
        node = node.left
    return isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub)


_WHERE_UFUNCS = {"divide", "true_divide", "sqrt", "log", "log10", "reciprocal", "power", "multiply", "arctan2"}


def _numpy_slips(node, parent, parents):
    """Python's and NumPy's traps, each written out whole: a floor division where a true one belongs
    (`f * b // Z`); a constant twice or half what it should be (`pi / 360` for `pi / 180`, a radius for
    a diameter); points scaled to unit length where they are divided by their last coordinate
    (`h / np.linalg.norm(h, ...)`); a ufunc told `where=` without `out=` (NumPy leaves the other
    entries as the memory it got: garbage); `x[:, :-d]`, empty for d = 0."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.FloorDiv):
        yield "true_division", ast.unparse(ast.BinOp(node.left, ast.Div(), node.right)), ""
    if isinstance(node, ast.Constant) and type(node.value) in (int, float) and abs(node.value) >= 2 \
            and isinstance(parent, ast.BinOp) and isinstance(parent.op, (ast.Mult, ast.Div)):
        for other in (node.value * 2, node.value / 2):
            yield "factor_two", repr(int(other) if type(node.value) is int and float(other).is_integer()
                                     else float(other)), ""
    if isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.Div) and parent.right is node:
        norm = node.value if isinstance(node, ast.Subscript) else node
        if isinstance(norm, ast.Call) and _dotted(norm.func).rsplit(".", 1)[-1] == "norm" and norm.args:
            points = ast.unparse(norm.args[0])
            for last in ("[..., -1:]", "[-1]"):
                yield "by_last", f"({points}){last}", ""
    if isinstance(node, ast.Call) and _dotted(node.func).rsplit(".", 1)[-1] in _WHERE_UFUNCS \
            and _dotted(node.func).startswith(("np.", "numpy.")):
        where = next((k.value for k in node.keywords if k.arg == "where"), None)
        if where is not None and not any(k.arg == "out" for k in node.keywords):
            out = ast.keyword("out", parse(f"np.zeros(np.shape({ast.unparse(where)}))", mode="eval").body)
            yield "ufunc_out", ast.unparse(ast.Call(node.func, node.args, [*node.keywords, out])), ""
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(node.value, ast.Name) \
            and isinstance(node.slice, ast.Constant) and node.slice.value in (0, 1) \
            and not isinstance(parent, ast.BinOp) and _made_by_product(node.value.id, parents):
        # a homogeneous product's first rows used as coordinates, never divided by the third
        yield "divided_by_w", f"{node.value.id}[{node.slice.value}] / {node.value.id}[2]", ""
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(parent, ast.BinOp) \
            and isinstance(parent.op, (ast.Add, ast.Sub, ast.Mult, ast.Div)) and isinstance(node.slice, ast.Tuple) \
            and len(node.slice.elts) >= 2 and all(_whole_slice(e) for e in node.slice.elts[:-1]) \
            and isinstance(node.slice.elts[-1], ast.Constant) and type(node.slice.elts[-1].value) is int:
        # one column of an (N, k) array in arithmetic with an (N, m) one: broadcast against the rows
        # (or raising) where the column, kept 2-D, belongs (`pts[:, :2] / pts[:, 2]`)
        k = node.slice.elts[-1].value
        kept = [ast.unparse(e) for e in node.slice.elts[:-1]] + [f"{k}:{k + 1}" if k != -1 else "-1:"]
        yield "keep_axis", f"{_operand(node.value)}[{', '.join(kept)}]", ""
    row = _constant_index(node.slice) if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) \
        and isinstance(node.value, ast.Name) else None
    if row is not None and isinstance(parent, ast.BinOp) and isinstance(parent.op, (ast.Add, ast.Sub, ast.Mult, ast.Div)) \
            and any(isinstance(side, ast.Name) and side.id == node.value.id for side in (parent.left, parent.right)):
        # one ROW of an array of points-as-rows in arithmetic with the array itself (`x / x[-1]`, the
        # column-vector habit): its column, kept 2-D, belongs (`x[:, -1:]`, each point's own w)
        yield "keep_axis", f"{node.value.id}[:, {f'{row}:{row + 1}' if row != -1 else '-1:'}]", ""
    if isinstance(node, ast.Call) and isinstance(parent, ast.BinOp) \
            and isinstance(parent.op, (ast.Add, ast.Sub, ast.Mult, ast.Div)) \
            and _dotted(node.func).rsplit(".", 1)[-1] in _PER_ROW_REDUCTIONS \
            and any(k.arg == "axis" for k in node.keywords) and not any(k.arg == "keepdims" for k in node.keywords):
        # a value per row reduced flat, (N,), in arithmetic with the (N, k) array: kept as a column
        # (`lines / np.linalg.norm(lines[:, :2], axis=1)`)
        kept = ast.Call(node.func, node.args, [*node.keywords, ast.keyword("keepdims", ast.Constant(True))])
        yield "keep_axis", ast.unparse(kept), ""
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Store) and _looped_index(node, parents) is not None:
        yield "stride", None, ""   # rows written at `i` and `i + 1` where `2 * i` and `2 * i + 1` belong
    if isinstance(node, ast.Subscript) and isinstance(node.value, (ast.Name, ast.Attribute)):
        items = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
        for axis, item in enumerate(items):
            if isinstance(item, ast.Slice) and isinstance(item.upper, ast.UnaryOp) \
                    and isinstance(item.upper.op, ast.USub) and not isinstance(item.upper.operand, ast.Constant):
                array, count = ast.unparse(node.value), ast.unparse(item.upper.operand)
                bounds = [ast.unparse(i) if i is not item else
                          f"{ast.unparse(item.lower) if item.lower else ''}:{array}.shape[{axis}] - ({count})"
                          for i in items]
                yield "empty_slice", f"{array}[{', '.join(bounds)}]", ""


def _looped_index(node: ast.Subscript, parents):
    """The first index of ``node`` (`A[i]`, `A[i + 1, :]`) when it is a ``for`` loop's counter (``for i
    in range(...)`` around it), alone or plus a constant; else None. (A stride's place: two rows per
    point written at `i` and `i + 1`.)"""
    index = node.slice.elts[0] if isinstance(node.slice, ast.Tuple) and node.slice.elts else node.slice
    counter = index.left if isinstance(index, ast.BinOp) and isinstance(index.op, ast.Add) \
        and isinstance(index.right, ast.Constant) and type(index.right.value) is int else index
    if not isinstance(counter, ast.Name) or not isinstance(node.value, ast.Name):
        return None
    up = node
    while id(up) in parents:
        up = parents[id(up)][0]
        if isinstance(up, ast.For) and isinstance(up.target, ast.Name) and up.target.id == counter.id \
                and isinstance(up.iter, ast.Call) and _dotted(up.iter.func) == "range":
            return index
    return None


_PRODUCTS: dict = {}   # id of a function's parents map -> (the map, kept alive; the names it assigns a product)


def _in_radians(node, parents) -> bool:
    """Whether an angle is visibly in radians already: written with pi (`2 * np.pi * u`), or a name the
    function assigns only such values (a conversion to radians of it is no slip of the student's)."""
    def with_pi(value) -> bool:
        return any(isinstance(n, (ast.Name, ast.Attribute)) and _dotted(n).rsplit(".", 1)[-1] == "pi"
                   or isinstance(n, ast.Call) and _dotted(n.func) in _ANGLE_CONVERSIONS for n in walk(value))
    if with_pi(node):
        return True
    if not isinstance(node, ast.Name):
        return False
    values = [statement.value for statement, _, _ in parents.values() if isinstance(statement, ast.Assign)
              and any(isinstance(t, ast.Name) and t.id == node.id for t in statement.targets)]
    return bool(values) and all(with_pi(value) for value in values)


def _made_by_product(name: str, parents) -> bool:
    """Whether the function (of ``parents``, :func:`_parents`) assigns ``name`` a matrix product
    (`source = H_inv @ grid`); read once per function."""
    entry = _PRODUCTS.get(id(parents))
    if entry is None or entry[0] is not parents:   # (another thread may clear it, an id be reused)
        if len(_PRODUCTS) > 64:
            _PRODUCTS.clear()
        names = {target.id for node, _, _ in parents.values() if isinstance(node, ast.Assign)
                 and isinstance(node.value, ast.BinOp) and isinstance(node.value.op, ast.MatMult)
                 for target in node.targets if isinstance(target, ast.Name)}
        entry = _PRODUCTS[id(parents)] = (parents, names)
    return name in entry[1]


def _frame_reading(words):
    """The def's stored names, its one-name assignments reading a parameter (line, name, names read), and its
    three names stacked into rows (line, names): read once per def (kept on ``words``), so that each node's
    question costs no walk of the def (a long student def would make that the square of its size)."""
    if not hasattr(words, "frame_reading"):
        fn = words.fn
        params = {a.arg for a in fn.args.args + fn.args.kwonlyargs}
        stored, resolved, stacks = set(), [], []
        for node in walk(fn):
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
                stored.add(node.id)
            elif isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
                read = {n.id for n in walk(node.value) if isinstance(n, ast.Name)}
                if read & params:
                    resolved.append((node.lineno, node.targets[0].id, read))
            elif isinstance(node, ast.Call) and _dotted(node.func).rsplit(".", 1)[-1] in _ROWS_STACKED and node.args \
                    and isinstance(node.args[0], (ast.List, ast.Tuple)) and len(node.args[0].elts) == 3 \
                    and all(isinstance(e, ast.Name) for e in node.args[0].elts):
                stacks.append((node.lineno, [e.id for e in node.args[0].elts]))
        words.frame_reading = (stored | params, sorted(resolved, key=lambda r: r[0]), stacks)
    return words.frame_reading


def _resolved_from(name: str, words, line: int) -> list[str]:
    """The locals assigned (above ``line``) from the module-level ``name`` and a parameter together (`s =
    DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)`): the value resolved for this call, where
    ``name`` read again would ignore the parameter. Empty when ``name`` is the def's own or a parameter."""
    own, resolved, _ = _frame_reading(words)
    if name in own:
        return []
    return list(dict.fromkeys(target for at, target, read in resolved if at < line and name in read))[:2]


def _twin_pairs_beside_a_swap(node, fn) -> list[tuple[str, str]]:
    """For `a, b = b, a` of twin names, the def's other twin pairs of parameters (c, d): exchanged with them."""
    if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Tuple)
            and isinstance(node.value, ast.Tuple) and len(node.targets[0].elts) == 2 == len(node.value.elts)):
        return []
    names = [getattr(e, "id", None) for e in node.targets[0].elts]
    values = [getattr(e, "id", None) for e in node.value.elts]
    if None in names or values != names[::-1] or not twin_names(*names):
        return []
    params = [a.arg for a in fn.args.args if a.arg not in names]
    return [(c, d) for i, c in enumerate(params) for d in params[i + 1:] if twin_names(c, d)][:2]


def _third_entry_replaced(node) -> str:
    """The name ``v`` of `np.append(v[:2], 1.0)`, `np.hstack([v[:2], 1])`, `np.array([v[0], v[1], 1.0])`: a 3-vector's
    first two entries with a constant for its third (a homogeneous vector's scale thrown away); "" otherwise."""
    if not isinstance(node, ast.Call):
        return ""
    name = _dotted(node.func).rsplit(".", 1)[-1]
    parts = node.args
    if name == "append" and len(parts) == 2:
        pieces = list(parts)
    elif name in ("hstack", "concatenate", "array") and len(parts) == 1 and isinstance(parts[0], (ast.List, ast.Tuple)):
        pieces = list(parts[0].elts)
    else:
        return ""
    if not pieces or not isinstance(pieces[-1], ast.Constant) or not isinstance(pieces[-1].value, (int, float)):
        return ""
    head = pieces[:-1]
    if len(head) == 1 and isinstance(head[0], ast.Subscript) and isinstance(head[0].value, ast.Name) \
            and isinstance(head[0].slice, ast.Slice) and head[0].slice.lower is None \
            and isinstance(head[0].slice.upper, ast.Constant) and head[0].slice.upper.value == 2:
        return head[0].value.id
    if len(head) == 2 and all(isinstance(h, ast.Subscript) and isinstance(h.value, ast.Name) for h in head) \
            and head[0].value.id == head[1].value.id \
            and [getattr(h.slice, "value", None) for h in head] == [0, 1]:
        return head[0].value.id
    return ""


_ROWS_STACKED = {"vstack", "array", "stack", "row_stack", "column_stack"}


def _frame_partners(name: str, assignment, words) -> list[tuple[str, str]]:
    """For a name stacked with two others into a 3 x 3 matrix (`np.vstack([e1, e2, e3])`) whose value here is
    not a cross product: the two others in the cyclic order that makes it their cross product (e3 = e1 x e2,
    e1 = e2 x e3, e2 = e3 x e1)."""
    if isinstance(assignment.value, ast.Call) and _dotted(assignment.value.func).rsplit(".", 1)[-1] == "cross":
        return []
    for at, names in _frame_reading(words)[2]:
        if at > assignment.lineno and name in names and len(set(names)) == 3:
            k = names.index(name)
            return [(names[(k + 1) % 3], names[(k + 2) % 3])]
    return []


def _size_of_something(node) -> bool:
    """`len(A)`, `A.shape[0]`, `A.size`: a size read from an array."""
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "len":
        return True
    if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Attribute) and node.value.attr == "shape":
        return True
    return isinstance(node, ast.Attribute) and node.attr == "size"


def _indexes_with(node, parent) -> bool:
    """Whether ``node`` is an index of a subscript (alone, or one of a tuple's)."""
    return isinstance(parent, ast.Subscript) and parent.slice is node or (
        isinstance(parent, ast.Tuple) and node in parent.elts)


def _threshold_changes(node: ast.Compare):
    """A validity test with the wrong threshold or strictness (`d >= 1` where `d > 0` belongs: a
    sub-pixel disparity is valid): the same direction, the threshold one either side or 0."""
    threshold = node.comparators[0]
    if _reduction_of(threshold, node.left):
        # (`d > np.nanmin(d)`: a threshold the data sets -- its own smallest value -- where a fixed one belongs)
        yield "compare", (type(node.ops[0]).__name__, 0), ""
        return
    if isinstance(threshold, ast.Name) and isinstance(node.ops[0], (ast.Gt, ast.GtE)):
        # (`Z > f`: a test against a value of the problem's where 0 belongs -- in front of the camera is Z > 0)
        yield "compare", (type(node.ops[0]).__name__, 0), ""
        return
    if not (isinstance(threshold, ast.Constant) and type(threshold.value) in (int, float)):
        return
    value = threshold.value
    strict, loose = ("Gt", "GtE") if isinstance(node.ops[0], (ast.Gt, ast.GtE)) else ("Lt", "LtE")
    for other in dict.fromkeys((value - 1, value + 1, 0)):
        if other != value and (other >= 0 or value < 0):
            for operator in (strict, loose):
                yield "compare", (operator, type(value)(other)), ""


_TO_ONE_VALUE = {"min", "amin", "nanmin", "max", "amax", "nanmax", "mean", "nanmean", "median", "nanmedian"}


def _reduction_of(node, array) -> bool:
    """`np.nanmin(d)`, `d.min()`, `np.median(d)`: a reduction of ``array`` (the same code) to one value."""
    if not isinstance(node, ast.Call) or _dotted(node.func).rsplit(".", 1)[-1] not in _TO_ONE_VALUE:
        return False
    reduced = node.args[0] if node.args and not (isinstance(node.func, ast.Attribute)
                                                 and ast.dump(node.func.value) == ast.dump(array)) else \
        node.func.value if isinstance(node.func, ast.Attribute) else None
    return reduced is not None and ast.dump(reduced) == ast.dump(array)


_FILLED = {"zeros", "ones", "empty", "full", "zeros_like", "ones_like", "empty_like", "full_like"}
_MADE = _FILLED | {"array", "asarray", "arange"}
_INTEGER_TYPES = {"int", "np.int32", "np.int64", "np.uint8", "np.int16", "np.uint16", "np.intp", "numpy.int64"}
_NARROW_INTEGERS = {"np.uint8", "np.int8", "np.int16", "np.uint16"}


# A comparison a student writes strictly where it is not (or the wrong way round), and the operators
# a subtraction or division is regrouped with (`a - b + c` is not `a - (b + c)`).
_COMPARED = {ast.Lt: ("LtE", "Gt"), ast.LtE: ("Lt", "GtE"), ast.Gt: ("GtE", "Lt"), ast.GtE: ("Gt", "LtE")}
_BOUNDED = {ast.NotEq: ("Lt", "Gt"), ast.Eq: ("LtE", "GtE")}
_REGROUPED = {ast.Sub: (ast.Add, ast.Sub), ast.Div: (ast.Mult, ast.Div)}


def _helper_changes(node, words):
    """Another of the student's own functions called where a sibling belongs (`_laplacian_pyramid(mask)`
    where `_gaussian_pyramid(mask)` does): defs of the module whose names share a word with the one
    called and that take the call's arguments."""
    if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in words.module_defs
            and not node.keywords and not any(isinstance(a, ast.Starred) for a in node.args)):
        return
    called = node.func.id
    mine = _name_words(called)
    offered = 0
    for name, fn in words.module_defs.items():
        if name in (called, words.fn.name) or not mine & _name_words(name):
            continue
        positional = fn.args.posonlyargs + fn.args.args
        if len(positional) - len(fn.args.defaults) <= len(node.args) <= len(positional) and offered < 3:
            offered += 1
            yield "function", name, ""


def _exchanged_sides(node, words):
    """A comparison of two siblings' values written the other way round (`n.distance < 0.75 * m.distance`
    where `m, n` come from one pair: the ratio test inverted): the two names exchanged throughout it."""
    if not (isinstance(node, ast.Compare) and len(node.comparators) == 1):
        return
    left = {n.id for n in walk(node.left) if isinstance(n, ast.Name)}
    right = {n.id for n in walk(node.comparators[0]) if isinstance(n, ast.Name)}
    for a in sorted(left - right):
        for b in sorted((right - left) & words.zipped.get(a, set())):
            yield "exchange", _names_exchanged(node, a, b), ""


def _exchanged_in_product(node, parent):
    """A matrix product whose twin names are in each other's places (`inv(T1) @ Hn @ T2` where `inv(T2) @ Hn
    @ T1` belongs: a normalisation undone with the two images' transforms exchanged): the two exchanged
    throughout the whole product, one slip (exchanging one at a time makes a product of the same transform
    twice, no nearer). So is a matrix written out as rows (`[[0, -1, x], [1, 0, -y], [-x, y, 0]]`, a
    cross-product matrix of (x, y, 1) with x and y in each other's places)."""
    product = isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult) \
        and not (isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.MatMult))
    rows = isinstance(node, ast.List) and not isinstance(parent, (ast.List, ast.Tuple)) \
        and len(node.elts) >= 2 and all(isinstance(row, (ast.List, ast.Tuple)) for row in node.elts)
    if not (product or rows):
        return
    names = sorted({n.id for n in walk(node) if isinstance(n, ast.Name)})
    for a, b in itertools.combinations(names, 2):
        if twin_names(a, b):
            exchanged = copy_tree(node)
            for name in walk(exchanged):
                if isinstance(name, ast.Name) and name.id in (a, b):
                    name.id = b if name.id == a else a
            yield "exchange", ast.unparse(exchanged), ""


def _defaulted_argument_changes(node, words):
    """An argument given to one of the student's own functions where its default belongs
    (`_warp(image, M, (w + tx, h + ty))`: the helper's own size, the input's, was due): the last
    positional argument a default covers, and each keyword one, left out."""
    if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in words.module_defs
            and not any(isinstance(a, ast.Starred) for a in node.args)):
        return
    fn = words.module_defs[node.func.id]
    positional = fn.args.posonlyargs + fn.args.args
    required = len(positional) - len(fn.args.defaults)
    if required < len(node.args) <= len(positional):
        yield "drop_argument", len(node.args) - 1, ""
    defaulted = {a.arg for a in positional[required:]} | {a.arg for a, d in zip(fn.args.kwonlyargs, fn.args.kw_defaults)
                                                          if d is not None}
    for keyword in node.keywords:
        if keyword.arg in defaulted:
            yield "drop_argument", keyword.arg, ""
    # and the converse: an output size left to its default (the input's own) where the caller holds the
    # size it was due -- `apply_homography(moving, H)` made into `reference`'s frame from `h, w = reference.shape[:2]`
    given = {a.arg for a in positional[:len(node.args)]} | {k.arg for k in node.keywords}
    for parameter in (a.arg for a in positional[required:] if a.arg not in given):
        if parameter in _SIZE_PARAMETERS:
            for height, width in _sizes_unpacked(words.fn, node.lineno):
                order = (width, height) if _SIZE_PARAMETERS[parameter] == "xy" else (height, width)
                yield "size_given", (parameter, f"({order[0]}, {order[1]})"), ""


def _homogeneous_arguments(node, words):
    """Homogeneous (N, 3) points given to one of the module's functions that takes (N, 2) pixels
    (`fundamental_8point(x1, x2)` with `x1 = _homogeneous(pts1) @ K1_inv.T`): each such argument's first
    two columns, all at once (one slip made for both images), and each alone."""
    if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in words.module_defs):
        return
    homogeneous = [position for position, argument in enumerate(node.args) if isinstance(argument, ast.Name) and any(
        index is None and value is not None and re.search(r"homogeneous|\bones(_like)?\(", ast.unparse(value))
        for _, value, index in words.definitions.get(argument.id, ()))]
    for positions in ([homogeneous] if len(homogeneous) > 1 else []) + [[p] for p in homogeneous]:
        new = copy_tree(node)
        for position in positions:
            new.args[position] = parse(f"{node.args[position].id}[:, :2]", mode="eval").body
        yield "drop_w", ast.unparse(new), ""


# the parameters of a student's helper (or of an API function) that take an output size, and their order
_SIZE_PARAMETERS = {"dsize": "xy", "size": "xy", "out_size": "xy", "output_shape": "yx", "out_shape": "yx"}


def _sizes_unpacked(fn, before: int) -> list:
    """The (height, width) names ``fn`` unpacks from an image's shape above line ``before`` (`h, w = X.shape[:2]`)."""
    return [pair for line, pair in _shape_unpackings(fn) if line < before]


@functools.lru_cache(maxsize=64)
def _shape_unpackings(fn) -> tuple:
    """``((line, (height, width)), ...)``: every `h, w = X.shape[:2]` of the def ``fn``, read once (each call of a
    helper asks for those above it)."""
    pairs = []
    for node in walk(fn):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 \
                and isinstance(node.targets[0], ast.Tuple) and len(node.targets[0].elts) == 2 \
                and all(isinstance(e, ast.Name) for e in node.targets[0].elts) \
                and isinstance(node.value, ast.Subscript) and isinstance(node.value.value, ast.Attribute) \
                and node.value.value.attr == "shape":
            pairs.append((node.lineno, tuple(e.id for e in node.targets[0].elts)))
    return tuple(pairs)



@functools.lru_cache(maxsize=4096)
def _name_words(name: str) -> frozenset:
    """The words of a def's name (`_laplacian_pyramid`: laplacian, pyramid), three letters or more."""
    return frozenset(word for word in name.lower().split("_") if len(word) >= 3)


def _a_mask(node) -> bool:
    return any(word in ast.unparse(node).lower() for word in ("mask", "inlier"))


def _is_astype(node) -> bool:
    return isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "astype"


def _indexes(node, parent, parents) -> bool:
    """Whether ``node`` is an index (not a slice bound) of a subscript: ``a[node]``, ``a[node, j]``."""
    if isinstance(parent, ast.Tuple):
        holder = parents.get(id(parent), (None,))[0]
        return isinstance(holder, ast.Subscript) and holder.slice is parent
    return isinstance(parent, ast.Subscript) and parent.slice is node


# Python's arithmetic binds tighter than its shifts and bit operators (a slip where a shift or a bit
# was meant to come first)
_BITWISE = (ast.LShift, ast.RShift, ast.BitAnd, ast.BitOr, ast.BitXor)
_BINDS_BEFORE_BITS = (ast.Add, ast.Sub, ast.Mult, ast.FloorDiv, ast.Mod)


def _precedence_slips(node: ast.Compare):
    """A comparison written beside ``&`` or ``|`` without brackets, which bind tighter than it:
    ``d > 0 & seen`` is ``d > (0 & seen)``; ``(d > 0) & seen`` was meant (and ``m & d > 0`` likewise)."""
    bitwise = (ast.BitAnd, ast.BitOr)
    op = ast.unparse(ast.Compare(ast.Name("a"), node.ops, [ast.Name("b")])).split()[1]
    right, left = node.comparators[0], node.left
    if isinstance(right, ast.BinOp) and isinstance(right.op, bitwise):
        joined = "&" if isinstance(right.op, ast.BitAnd) else "|"
        yield "precedence", f"({_grouped(left)} {op} {_grouped(right.left)}) {joined} {_grouped(right.right)}", ""
    if isinstance(left, ast.BinOp) and isinstance(left.op, bitwise):
        joined = "&" if isinstance(left.op, ast.BitAnd) else "|"
        yield "precedence", f"{_grouped(left.left)} {joined} ({_grouped(left.right)} {op} {_grouped(right)})", ""


def _converted_late(node: ast.Call):
    """A difference (sum, product) converted after it is taken: ``(L - R).astype(np.float64)`` of two
    uint8 images has wrapped round already; converting the first operand before it is the fix."""
    if isinstance(node.func, ast.Attribute) and node.func.attr == "astype" and len(node.args) == 1 \
            and isinstance(node.func.value, ast.BinOp) and isinstance(node.func.value.op, (ast.Sub, ast.Add, ast.Mult)):
        inner, kind = node.func.value, ast.unparse(node.args[0])
        operator = {ast.Sub: "-", ast.Add: "+", ast.Mult: "*"}[type(inner.op)]
        yield "convert_first", f"{_grouped(inner.left)}.astype({kind}) {operator} {_grouped(inner.right)}", ""


def _grouped(node) -> str:
    """``node``'s code, in brackets where an attribute after it would bind to its last part."""
    text = ast.unparse(node)
    return text if isinstance(node, (ast.Name, ast.Attribute, ast.Subscript, ast.Call, ast.Constant)) else f"({text})"


_ROOTS = {"np.sqrt", "numpy.sqrt", "math.sqrt"}


def _factor_moves(node):
    """A factor taken inside a square root where it belongs outside, or the other way round
    (``np.sqrt(aperture * u)`` for ``aperture * np.sqrt(u)``: a radius scaled by the root of the scale)."""
    if isinstance(node, ast.Call) and _dotted(node.func) in _ROOTS and len(node.args) == 1 and not node.keywords \
            and isinstance(node.args[0], ast.BinOp) and isinstance(node.args[0].op, ast.Mult):
        product, root = node.args[0], _dotted(node.func)
        yield "move_factor", f"{ast.unparse(product.left)} * {root}({ast.unparse(product.right)})", ""
        yield "move_factor", f"{root}({ast.unparse(product.left)}) * {ast.unparse(product.right)}", ""
    elif isinstance(node, ast.BinOp):
        for factor, other in ((node.left, node.right), (node.right, node.left)):
            if isinstance(other, ast.Call) and _dotted(other.func) in _ROOTS and len(other.args) == 1 \
                    and not other.keywords:
                yield "move_factor", f"{_dotted(other.func)}({ast.unparse(factor)} * {ast.unparse(other.args[0])})", ""


def _shape_changes(node: ast.Call):
    """An array allocated with an input's length where its whole shape belongs (``np.zeros(len(d))``,
    ``np.full(d.shape[0], np.nan)``): right for a 1-D input only, an IndexError for an image."""
    dotted = _dotted(node.func)
    if not dotted.startswith(("np.", "numpy.")) or dotted.rsplit(".", 1)[-1] not in ("zeros", "ones", "empty", "full") \
            or not node.args:
        return
    size = node.args[0]
    if isinstance(size, ast.Call) and _dotted(size.func) == "len" and len(size.args) == 1:
        array = size.args[0]
    elif isinstance(size, ast.Subscript) and isinstance(size.value, ast.Attribute) and size.value.attr == "shape" \
            and isinstance(size.slice, ast.Constant) and size.slice.value == 0:
        array = size.value.value
    else:
        return
    new = copy_tree(node)
    new.args[0] = ast.Call(_name("np.shape"), [copy_tree(array)], [])
    yield "whole_shape", ast.unparse(new), ""


def _brackets_left_out(node) -> str | None:
    """``... + c * u + v`` (or ``- v``) with the factor ``c`` over ``u + v`` too (`p2 * (r2 + 2 * x * x)`), as
    text; None where ``node`` is no such sum. Only where ``v`` is a product or a name (a constant added
    after a product is rarely a bracket's)."""
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub))
            and isinstance(node.right, (ast.BinOp, ast.Name)) and not isinstance(node.right, ast.Constant)):
        return None
    before, product = (node.left.left, node.left.right) if isinstance(node.left, ast.BinOp) \
        and isinstance(node.left.op, (ast.Add, ast.Sub)) else (None, node.left)
    if not (isinstance(product, ast.BinOp) and isinstance(product.op, ast.Mult)):
        return None
    inner = ast.BinOp(copy_tree(product.right), node.op, copy_tree(node.right))
    grouped = ast.BinOp(copy_tree(product.left), ast.Mult(), inner)
    whole = grouped if before is None else ast.BinOp(copy_tree(before), node.left.op, grouped)
    return ast.unparse(whole)


@functools.lru_cache(maxsize=64)
def _holds_bytes(fn) -> bool:
    """Whether the def ``fn`` makes 8-bit values (uint8 named, or an OpenCV difference of images)."""
    return any((isinstance(n, ast.Attribute) and n.attr == "uint8") or (isinstance(n, ast.Constant) and n.value == "uint8")
               or (isinstance(n, ast.Call) and _dotted(n.func) in ("cv2.absdiff", "cv2.subtract"))
               for n in walk(fn))


@functools.lru_cache(maxsize=64)
def _calls_opencv(fn) -> bool:
    """Whether the def ``fn`` calls OpenCV (whose functions take float32 points and Python numbers only)."""
    return any(isinstance(n, ast.Call) and _dotted(n.func).startswith(("cv2.", "cv.")) for n in walk(fn))


def _python_numbers(node: ast.Call):
    """NumPy numbers given where OpenCV takes Python ones: `tuple(rng.integers(0, 256, 3))` as a colour
    (cv2.line: "Scalar value for argument 'color' is not numeric")."""
    if _dotted(node.func) == "tuple" and len(node.args) == 1 and not node.keywords \
            and isinstance(node.args[0], (ast.Call, ast.Name, ast.Subscript)) \
            and not (isinstance(node.args[0], ast.Call) and _dotted(node.args[0].func) in ("map", "range", "zip")):
        yield "python_numbers", None, ""


def _dtype_changes(node: ast.Call, opencv: bool = False):
    """An array made of the wrong type: a canvas allocated without its dtype (np.zeros is float64: an
    image built on it is not uint8; np.zeros_like(image) is uint8: sums on it wrap round), values
    cast to integers where they are not (`np.asarray(f, dtype=int)`), and (``opencv``: the student's
    function calls OpenCV) points made float64 where OpenCV takes float32 (cv2.calibrateCamera's
    object points)."""
    dotted = _dotted(node.func)
    if not dotted.startswith(("np.", "numpy.")) or dotted.rsplit(".", 1)[-1] not in _MADE:
        return
    given = next((k for k in node.keywords if k.arg == "dtype"), None)
    if given is not None and isinstance(given.value, ast.Attribute) and given.value.attr == "dtype" \
            and not dotted.endswith("_like"):
        yield "dtype", "np.float64", ""   # (a matrix made in an image's dtype, `dtype=image.dtype`: uint8)
        if dotted.endswith("arange"):
            yield "dtype", "np.int64", ""   # (pixel coordinates counted in an image's uint8: 255 + 1 is 0)
    elif given is not None and _dotted(given.value) in _INTEGER_TYPES:
        yield "dtype", "np.float64", ""
        if _dotted(given.value) != "np.uint8":
            yield "dtype", "np.uint8", ""   # (an image built in an int array: right values, not uint8)
        if _dotted(given.value) in _NARROW_INTEGERS:
            yield "dtype", "np.int64", ""   # (counts or codes that outgrow 8 or 16 bits: they wrap round)
    elif given is None and dotted.rsplit(".", 1)[-1] in _FILLED \
            and len(node.args) < (3 if dotted.endswith("full") or dotted.endswith("full_like") else 2):
        yield "dtype", "np.uint8", ""
        if dotted.endswith("_like"):
            yield "dtype", "np.float64", ""
        elif opencv:
            yield "dtype", "np.float32", ""


_BINDS_TIGHTER = (ast.Mult, ast.Div, ast.FloorDiv, ast.MatMult, ast.Mod)
# NumPy functions that take an axis, and the position it has among their arguments: left out, the
# array is flattened (np.delete, np.append, np.sum) or a default axis used where another belongs.
_KEEPS_DIMS = {"sum", "mean", "max", "min", "amax", "amin", "median", "std", "var", "norm", "average", "nanmean",
               "nansum", "nanmax", "nanmin", "any", "all"}   # reductions that take keepdims
_AXIS_POSITIONS = {"delete": 2, "insert": 3, "append": 2, "sum": 1, "mean": 1, "max": 1, "min": 1, "amax": 1,
                   "amin": 1, "argmax": 1, "argmin": 1, "median": 1, "std": 1, "var": 1, "any": 1, "all": 1,
                   "cumsum": 1, "flip": 1, "concatenate": 1, "stack": 1, "norm": 2, "average": 1, "nanmean": 1,
                   "nansum": 1, "nanmax": 1, "nanmin": 1, "diff": 2, "sort": 1, "argsort": 1, "unique": 99}
# OpenCV functions that take float32 arrays only (float64 fails their assertions): maps, point sets.
_FLOAT32_ONLY = {"remap", "getAffineTransform", "getPerspectiveTransform", "cornerSubPix", "calcOpticalFlowPyrLK",
                 "convertMaps", "minAreaRect", "fitLine", "kmeans", "calcBackProject"}
_REDUCTIONS = {"sum", "mean", "max", "min", "argmax", "argmin", "std", "var", "any", "all", "cumsum"}
# Methods of an array that return a new one: a call of them whose result is not kept changes nothing.
_RETURNS_NEW = {"astype", "copy", "reshape", "round", "clip", "transpose", "flatten", "ravel", "squeeze"}
_SIDE_EFFECTS = {"print", "append", "extend", "insert", "update", "setdefault", "write", "imshow", "imwrite",
                 "waitKey", "destroyAllWindows", "fill", "sort", "shuffle", "seed", "put", "setflags", "plot",
                 "show", "savefig", "remove", "pop", "clear", "add", "discard", "close", "assert_allclose"}


def _call_slips(node: ast.Call):
    """Slips in how a library function is called: an axis left out (`np.delete(X, 2)` flattens X; the
    sum of every entry for each row's), a flag keyword given the wrong truth value (`full_matrices=False`
    where the full V is needed), and float64 arrays given to an OpenCV function that takes float32
    (`cv2.remap`'s maps, `cv2.getAffineTransform`'s points): the arguments after the image cast."""
    dotted = _dotted(node.func)
    short = dotted.rsplit(".", 1)[-1]
    function = dotted.startswith(("np.", "numpy.")) and short in _AXIS_POSITIONS
    method = isinstance(node.func, ast.Attribute) and not dotted.startswith(("np.", "numpy.", "cv2.")) \
        and short in _REDUCTIONS   # `x.sum()`: the array is not among the arguments
    if (function or method) and not any(k.arg == "axis" for k in node.keywords) \
            and not any(isinstance(a, ast.Starred) for a in node.args) \
            and len(node.args) + method <= _AXIS_POSITIONS[short]:
        for axis in (0, 1, -1):
            yield "add_axis", axis, ""
        if short in _KEEPS_DIMS and not any(k.arg == "keepdims" for k in node.keywords):
            for axis in (1, -1):   # (a whole array's norm dividing it, where each row's belongs)
                yield "add_axis", (axis, True), ""
    for keyword in node.keywords:
        if keyword.arg and isinstance(keyword.value, ast.Constant) and isinstance(keyword.value.value, bool):
            yield "flip_keyword", keyword.arg, ""
    if dotted in ("np.linspace", "numpy.linspace") and len(node.args) == 3 \
            and not any(k.arg == "endpoint" for k in node.keywords):
        yield "flip_keyword", ("endpoint", False), ""   # w samples of [0, n) where [0, n] was written
    if dotted.startswith(("cv2.", "cv.", "np.", "numpy.", "scipy.")):
        # an optional argument that does not belong (`P=K` makes cv2.undistortPoints map the normalised
        # points back to pixels): a library's keyword left out, its default used
        for keyword in node.keywords:   # (a flag's truth value is turned instead: `crossCheck=False`)
            if keyword.arg and keyword.arg not in _KEPT_KEYWORDS \
                    and not (isinstance(keyword.value, ast.Constant) and isinstance(keyword.value.value, bool)):
                yield "drop_keyword", keyword.arg, ""
    if dotted.startswith(("cv2.", "cv.")):
        # (OpenCV's optional arguments given by position: `cv2.resize(image, size, fx=s, fy=s)` resizes
        # to `size` whatever the factors; None there lets them count)
        for position, argument in enumerate(node.args[1:], start=1):
            if isinstance(argument, (ast.Name, ast.Tuple, ast.Subscript)) and not isinstance(argument, ast.Starred):
                yield "drop_keyword", position, ""
    if dotted.startswith(("cv2.", "cv.")) and short in _NEUTRAL_ONE:
        # (a scale that does not belong, given where its neutral 1 does: a rotation that also zooms)
        keyword, position = _NEUTRAL_ONE[short]
        given = node.args[position] if len(node.args) > position else \
            next((k.value for k in node.keywords if k.arg == keyword), None)
        if given is not None and not (isinstance(given, ast.Constant) and given.value == 1):
            yield "neutral_argument", position if len(node.args) > position else keyword, ""
    if dotted.startswith(("cv2.", "cv.")) and short in _METHOD_ARGUMENTS \
            and not any(isinstance(a, ast.Starred) for a in node.args) and not any(k.arg is None for k in node.keywords):
        # (a method or flags argument left out, the library's default used: cv2.findFundamentalMat's is
        # RANSAC, not the 8-point algorithm; cv2.findHomography's a least-squares fit of every point)
        keyword, position, members = _METHOD_ARGUMENTS[short]
        if len(node.args) <= position and not any(k.arg == keyword for k in node.keywords):
            for member in members:
                yield "method_given", (keyword, member), ""
    if dotted.startswith(("cv2.", "cv.")) and short in _GREY_ONLY and node.args \
            and isinstance(node.args[0], (ast.Name, ast.Subscript)):
        yield "grey", 0, ""   # a colour image given to a function that takes one channel
    if isinstance(node.func, ast.Attribute) and node.func.attr == "compute" and len(node.args) == 2 \
            and all(isinstance(a, (ast.Name, ast.Subscript)) for a in node.args):
        for position in (0, 1):
            yield "grey", position, ""   # a stereo matcher's images in colour (StereoBM takes 8-bit grey)
    if short in ("hstack", "concatenate") and dotted.startswith(("np.", "numpy.")) and node.args \
            and isinstance(node.args[0], (ast.List, ast.Tuple)):
        for item in node.args[0].elts:
            if isinstance(item, ast.Call) and _dotted(item.func) in ("np.ones", "np.zeros", "numpy.ones", "numpy.zeros") \
                    and len(item.args) == 1 and not isinstance(item.args[0], ast.Tuple):
                # `np.hstack([pts, np.ones(n)])`: a column of ones made 1-D
                yield "keep_axis", ast.unparse(ast.Call(node.func, [ast.List(
                    [parse(f"{_dotted(e.func)}(({ast.unparse(e.args[0])}, 1))", mode="eval").body if e is item else e
                     for e in node.args[0].elts], ast.Load())] + node.args[1:], node.keywords)), ""
    if short in _STACKS and dotted.startswith(("np.", "numpy.")) and node.args \
            and isinstance(node.args[0], (ast.List, ast.Tuple)) and len(node.args[0].elts) in (3, 4) \
            and isinstance(node.args[0].elts[-1], (ast.Name, ast.Subscript, ast.Attribute)):
        # a homogeneous point's last value left as it was -- its depth Z -- where 1 belongs: `[x, y, Z]`
        # for `[x, y, 1]` after the division by Z (the division's removal would compensate elsewhere)
        *first, last = node.args[0].elts
        ones = parse(f"np.ones_like({ast.unparse(last)})", mode="eval").body
        yield "homogeneous_one", ast.unparse(ast.Call(node.func, [type(node.args[0])([*first, ones], ast.Load())]
                                                      + node.args[1:], node.keywords)), ""
    if dotted.startswith(("cv2.", "cv.")) and short in _FLOAT32_ONLY and len(node.args) >= 2:
        arrays = [i for i, a in enumerate(node.args) if isinstance(a, (ast.Name, ast.Subscript))]
        if any(i >= 1 for i in arrays):
            yield "float32", [i for i in arrays if i >= 1], ""
        if len(arrays) >= 2 and 0 in arrays:
            yield "float32", arrays, ""


_KEPT_KEYWORDS = {"dtype", "axis", "out", "where"}
_STACKS = {"column_stack", "stack", "vstack", "dstack", "array"}   # NumPy calls that put a point's values together
# OpenCV arguments whose neutral value is 1 (a scale): the keyword and the position
_NEUTRAL_ONE = {"getRotationMatrix2D": ("scale", 2), "convertScaleAbs": ("alpha", 2)}
# OpenCV calls whose method (or interpolation) argument a student may leave at its default: its keyword,
# its position, and the values given it (each an expression of the cv2 module's constants)
_INTERPOLATIONS = ("INTER_NEAREST", "INTER_CUBIC", "INTER_AREA")
_METHOD_ARGUMENTS = {
    "findFundamentalMat": ("method", 2, ("FM_8POINT", "FM_LMEDS", "FM_7POINT")),
    "findHomography": ("method", 2, ("RANSAC", "LMEDS", "RHO")),
    "findEssentialMat": ("method", 3, ("LMEDS",)),
    # (DECOMP_LU, the default, solves square systems only: a least-squares system needs SVD or QR)
    "solve": ("flags", 3, ("DECOMP_SVD", "DECOMP_QR")),
    "resize": ("interpolation", 5, _INTERPOLATIONS),
    "warpAffine": ("flags", 4, _INTERPOLATIONS + ("INTER_LINEAR | WARP_INVERSE_MAP",)),
    "warpPerspective": ("flags", 4, _INTERPOLATIONS + ("INTER_LINEAR | WARP_INVERSE_MAP",)),
}
# NumPy functions whose first argument is the data and the others its bounds, fill or shape
_DATA_FIRST = {"clip", "where", "full", "full_like", "pad", "reshape", "repeat", "tile", "round", "around",
               "percentile", "quantile", "linspace", "arange"}
_GREY_ONLY = {"cornerSubPix", "equalizeHist", "goodFeaturesToTrack", "cornerHarris", "threshold", "adaptiveThreshold"}   # (changed by their own operators, or never a slip left in)
_ACCUMULATED = {ast.Add: "Add", ast.Sub: "Sub", ast.Mult: "Mult", ast.MatMult: "MatMult"}


def _chained_product(assign, parents) -> bool:
    """``assign`` (`H = step[j]` in a loop) sets a matrix that the function started before the loop
    as the identity (`H = np.eye(3)`): a product along a chain, whose factors each turn were to multiply
    it, not replace it."""
    if not isinstance(assign.targets[0], ast.Name):
        return False
    name = assign.targets[0].id
    fn = _def_of(assign, parents)
    if not hasattr(fn, "_identities"):   # (read once per def: every assignment in a loop asks)
        fn._identities = [(n.targets[0].id, n.lineno) for n in walk(fn)
                          if isinstance(n, ast.Assign) and len(n.targets) == 1 and isinstance(n.targets[0], ast.Name)
                          and isinstance(n.value, ast.Call) and _dotted(n.value.func).rsplit(".", 1)[-1] in ("eye", "identity")]
    return any(started == name and line < assign.lineno for started, line in fn._identities)


def _def_of(node, parents):
    """The def holding ``node`` (the outermost node reached, where none does)."""
    while id(node) in parents and not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
        node = parents[id(node)][0]
    return node


def _in_loop(node, parents) -> bool:
    while id(node) in parents:
        node = parents[id(node)][0]
        if isinstance(node, (ast.For, ast.While, ast.comprehension)):
            return True
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            return False
    return False


def _mode_test(test) -> bool:
    """A test of which case a call is in, not of the data: a mode named by a string (`cost == "ncc"`),
    None for "not given" (`x is None`), a type (`isinstance(x, list)`). Turned round, it runs the code
    of another case -- which may pass a check by chance (NCC's search where SSD's is wrong) and is no
    slip a student makes."""
    for node in walk(test):
        if isinstance(node, ast.Constant) and (isinstance(node.value, str) or node.value is None):
            return True
        if isinstance(node, ast.Compare) and any(isinstance(op, (ast.Is, ast.IsNot)) for op in node.ops):
            return True
        if isinstance(node, ast.Call) and _dotted(node.func) in ("isinstance", "hasattr", "callable"):
            return True
    return False


def _opencv_flags(node) -> bool:
    """Whether ``node`` combines OpenCV constants (``cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP``)."""
    parts = [node.left, node.right]
    while parts:
        part = parts.pop()
        if isinstance(part, ast.BinOp) and isinstance(part.op, ast.BitOr):
            parts += [part.left, part.right]
        elif not (isinstance(part, ast.Attribute) and _dotted(part).startswith("cv2.") and part.attr.isupper()):
            return False
    return True


def _logic_changes(node, parent, parents):
    """Slips of logic and accumulation: a condition the wrong way round (`if x > t:` where `if not x >
    t:` belongs, a `not` too many), masks combined with & where | belongs (or `and`/`or`), and a sum
    in a loop assigned where it is added to (`total = x` for `total += x`) or the other way round."""
    if isinstance(parent, (ast.If, ast.IfExp, ast.While)) and parent.test is node \
            and not (isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not)) and not _mode_test(node):
        yield "negate", "insert", ""
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not) and not _mode_test(node.operand):
        yield "negate", "drop", ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitOr) and _opencv_flags(node):
        # OpenCV's flags are combined with |, never &: a flag too many is the slip (WARP_INVERSE_MAP
        # beside a forward map); `&` of two flags is 0, another flag altogether (INTER_NEAREST)
        yield "drop_flag", "left", ""
        yield "drop_flag", "right", ""
    elif isinstance(node, ast.BinOp) and isinstance(node.op, (ast.BitAnd, ast.BitOr)) \
            and not isinstance(node.right, ast.Constant) and not isinstance(node.left, ast.Constant):
        yield "logic", "BitOr" if isinstance(node.op, ast.BitAnd) else "BitAnd", ""
    if isinstance(node, ast.BoolOp):
        yield "logic", "Or" if isinstance(node.op, ast.And) else "And", ""
    if isinstance(node, ast.AugAssign) and type(node.op) in _ACCUMULATED:
        yield "accumulate", "assign", ""
    if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], (ast.Name, ast.Subscript)) \
            and _in_loop(node, parents):
        yield "accumulate", "Add", ""
        if _chained_product(node, parents):   # H = step[j] -> H = step[j] @ H: a chain's product kept
            yield "accumulate", "MatMultLeft", ""
            yield "accumulate", "MatMult", ""
    if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Subscript) \
            and any(isinstance(part, ast.Slice) for part in walk(node.targets[0].slice)) \
            and isinstance(node.value, (ast.Name, ast.Constant)):
        yield "accumulate", "Mult", ""   # a block set to a scale where it was to be scaled: T[:2, :2] = s
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.zeros", "np.zeros_like", "numpy.zeros", "numpy.zeros_like") \
            and node.args and isinstance(parents.get(id(node), (None,))[0], ast.Assign) \
            and _minimised(parents[id(node)][0], parents):
        yield "fill_inf", None, ""   # a table whose unfilled entries must lose an argmin started at 0, where they win
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "len" and len(node.args) == 1 \
            and isinstance(node.args[0], ast.Name) and isinstance(parent, ast.Compare):
        yield "len_axis", None, ""   # a bound counted along the first axis (rows) where the second (columns) is
    if isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], ast.NotEq) \
            and isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.Mult):
        yield "jump_size", None, ""   # a penalty for any change (Potts) where one for its size belongs
    running = _restarted(node, parents)
    if running:
        yield "carry", running, ""
    for mean in _summaries(node, parents):
        yield "summary", mean, ""
    parts = list(_parts(node, parents))
    for part in parts:
        yield "part", part, ""
    if not parts and isinstance(node, ast.Call) and _dotted(node.func).endswith("linalg.norm") and len(node.args) == 1 \
            and isinstance(node.args[0], ast.Name) \
            and any(k.arg == "axis" and isinstance(k.value, ast.Constant) and k.value.value in (1, -1) for k in node.keywords):
        yield "part", f"{node.args[0].id}[:, 2]", ""   # each point's distance where its depth Z belongs: `1 + f / norm(X)`
    if isinstance(node, ast.Call) and node.args and _dotted(node.func).rsplit(".", 1)[-1] in _EXTREMES \
            and not (isinstance(node.args[0], ast.Call) and _dotted(node.args[0].func).rsplit(".", 1)[-1] in _MAGNITUDES):
        yield "magnitude", None, ""   # the smallest value where the smallest magnitude belongs (an eigenvalue)
        if isinstance(node.args[0], ast.Attribute) and node.args[0].attr in ("real", "imag"):
            yield "magnitude", "complex", ""   # np.argmin(v.real) -> np.argmin(np.abs(v)): a complex value's modulus


_REDUCED = {"mean", "median", "average", "nanmean"}


def _index(fn, parents) -> tuple[dict, dict]:
    """A def read once for the slips below (each of its nodes asks: a walk per node would make reading
    a long function quadratic): (name -> [(line, names read)] of its assignments outside loops, array ->
    [(line, name)] of the locals holding its mean)."""
    if not hasattr(fn, "_slip_index"):
        made, means = {}, {}
        for assign in (n for n in walk(fn) if isinstance(n, ast.Assign) and len(n.targets) == 1):
            target, value = assign.targets[0], assign.value
            if isinstance(target, ast.Name) and not _in_loop(assign, parents):
                made.setdefault(target.id, []).append(
                    (assign.lineno, frozenset(m.id for m in walk(value) if isinstance(m, ast.Name))))
            pairs = zip(target.elts, value.elts) if isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) \
                and len(target.elts) == len(value.elts) else [(target, value)]   # (`c1, c2 = a.mean(0), b.mean(0)`)
            for name, call in pairs:
                if not (isinstance(name, ast.Name) and isinstance(call, ast.Call)
                        and _dotted(call.func).rsplit(".", 1)[-1] in _REDUCED):
                    continue
                if isinstance(call.func, ast.Attribute) and isinstance(call.func.value, ast.Name):
                    means.setdefault(call.func.value.id, []).append((assign.lineno, name.id))
                elif call.args and isinstance(call.args[0], ast.Name) and _dotted(call.func).startswith("np."):
                    means.setdefault(call.args[0].id, []).append((assign.lineno, name.id))
        fn._slip_index = (made, means)
    return fn._slip_index


def _parts(node, parents) -> list:
    """The parts of an array the function takes elsewhere (`X[:, 2]`), in place of a statistic of the whole
    of it (`np.linalg.norm(X, axis=1)`: the distance where the depth belongs); the first three written."""
    if not (isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Name)
            and _dotted(node.func).rsplit(".", 1)[-1] in _WHOLE):
        return []
    fn = _def_of(node, parents)
    if not hasattr(fn, "_parts_index"):
        parts = {}
        for sub in walk(fn):
            if isinstance(sub, ast.Subscript) and isinstance(sub.ctx, ast.Load) and isinstance(sub.value, ast.Name) \
                    and not any(isinstance(n, ast.Call) for n in walk(sub.slice)):
                parts.setdefault(sub.value.id, {})[ast.unparse(sub)] = None   # (a dict: ordered, no repeats)
                # (and the component after a leading slice: `X[:, 2]` beside `X[:, :2]`, a point's depth
                # beside its first two coordinates)
                last = sub.slice.elts[-1] if isinstance(sub.slice, ast.Tuple) else sub.slice
                if isinstance(last, ast.Slice) and last.lower is None and last.step is None \
                        and isinstance(last.upper, ast.Constant) and type(last.upper.value) is int and last.upper.value > 0:
                    after = copy_tree(sub)
                    if isinstance(after.slice, ast.Tuple):
                        after.slice.elts[-1] = ast.Constant(last.upper.value)
                    else:
                        after.slice = ast.Constant(last.upper.value)
                    parts[sub.value.id][ast.unparse(after)] = None
        # (one component -- `X[:, 2]`, an index, not a slice -- is what a statistic of the whole replaces)
        fn._parts_index = {name: sorted(texts, key=lambda text: ":" in text.split(",")[-1])
                           for name, texts in parts.items()}
    return fn._parts_index.get(node.args[0].id, [])[:4]


_WHOLE = {"norm", "sum", "mean", "max", "min", "amax", "amin", "sqrt", "hypot", "prod"}


def _summaries(node, parents) -> list:
    """The locals holding a mean of the array one item of which ``node`` takes (`dst[0]` where `dst_mean
    = dst.mean(axis=0)` was made: a translation from the first pair where the centroids belong)."""
    if not (isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(node.value, ast.Name)
            and _constant_index(node.slice) is not None):
        return []
    fn = _def_of(node, parents)
    before = [name for line, name in _index(fn, parents)[1].get(node.value.id, ()) if line < node.lineno]
    return before[-2:]   # (the latest: a long function's every mean would make many changes per item)


_EXTREMES = {"argmin", "argmax", "argsort", "nanargmin", "nanargmax"}
_MAGNITUDES = {"abs", "absolute", "fabs", "norm", "square"}


def _restarted(node, parents) -> str | None:
    """The running result a loop's step starts from the input again instead of (`out = cv2.line(image.copy(),
    ...)` each time round, where `out` was made before the loop and belongs there): its name, or None.
    ``node``: a name read (`image`), a copy of one (`image.copy()`, `np.copy(image)`) or a fixed item of
    one (`images[0]`)."""
    copied = isinstance(node, ast.Call) and not node.keywords and (
        (isinstance(node.func, ast.Attribute) and node.func.attr == "copy" and not node.args
         and isinstance(node.func.value, ast.Name))
        or (_dotted(node.func) in ("np.copy", "numpy.copy") and len(node.args) == 1 and isinstance(node.args[0], ast.Name)))
    # (or an item of one: `stitch(images[0], image)` after `panorama = images[0]`)
    item = isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and isinstance(node.ctx, ast.Load) \
        and isinstance(node.slice, ast.Constant)
    if not (copied or item or (isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)
                               and not isinstance(parents.get(id(node), (None,))[0], ast.Attribute))):
        return None
    source = node if isinstance(node, ast.Name) else node.value if item else \
        node.func.value if isinstance(node.func, ast.Attribute) else node.args[0]
    statement, fn = node, None
    while id(statement) in parents and not isinstance(statement, ast.stmt):
        statement = parents[id(statement)][0]
    if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1 and isinstance(statement.targets[0], ast.Name)
            and _in_loop(statement, parents)):
        return None
    running = statement.targets[0].id
    if running == source.id or any(isinstance(n, ast.Name) and n.id == running for n in walk(statement.value)):
        return None
    fn = _def_of(statement, parents)
    # (made before the loop from the same input: `out = image.copy()`, `out = np.array(image)`)
    made = any(line < statement.lineno and source.id in read for line, read in _index(fn, parents)[0].get(running, ()))
    return running if made else None


def _discarded_result(statement: ast.Expr):
    """A call whose result is dropped (`draw_points(image, pts)`, `np.clip(x, 0, 255)`, `x.astype(int)` on
    a line of their own): the result kept in the array it was made from."""
    call = statement.value
    if not isinstance(call, ast.Call) or _dotted(call.func).rsplit(".", 1)[-1] in _SIDE_EFFECTS:
        return
    if isinstance(call.func, ast.Attribute) and call.func.attr in _RETURNS_NEW and isinstance(call.func.value, ast.Name):
        yield "keep_result", call.func.value.id, ""   # x.astype(int) -> x = x.astype(int)
    elif call.args and isinstance(call.args[0], ast.Name) and (
            isinstance(call.func, ast.Name) or _dotted(call.func).startswith(("np.", "numpy.", "cv2."))):
        yield "keep_result", call.args[0].id, ""      # f(x, ...) -> x = f(x, ...)


_SQUARED = {"abs", "absolute", "fabs"}


def _squares(node) -> bool:
    return any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.Pow) and isinstance(n.right, ast.Constant)
               and n.right.value == 2 or isinstance(n, ast.Call) and _dotted(n.func) in ("np.square", "numpy.square")
               for n in walk(node))


_ROOT_CALLS = ("np.sqrt", "numpy.sqrt", "math.sqrt", "np.hypot", "numpy.hypot", "math.hypot", "np.linalg.norm",
               "numpy.linalg.norm", "cv2.norm")


def _squared_bounds(node, words=None):
    """A squared distance compared with a bound that is not squared (`dx ** 2 + dy ** 2 <= r`, a disc of
    radius sqrt(r)), or a distance compared with a squared bound (`np.hypot(dx, dy) <= r ** 2`). The squared
    distance may be a name made from squares on the line of its own above (`sq_err = np.sum(d ** 2, axis=1)`,
    then `sq_err < threshold`)."""
    def squared(side) -> bool:
        if _squares(side):
            return True
        if words is None or not isinstance(side, ast.Name):
            return False
        made = [(at, value) for at, value, index in words.definitions.get(side.id, ())
                if at < node.lineno and index is None]
        return bool(made) and _squares(max(made, key=lambda pair: pair[0])[1]) and not any(
            isinstance(n, ast.Call) and _dotted(n.func) in _ROOT_CALLS for n in walk(max(made, key=lambda p: p[0])[1]))
    for side, other in ((node.left, node.comparators[0]), (node.comparators[0], node.left)):
        bare = isinstance(other, (ast.Name, ast.Attribute, ast.Subscript, ast.Constant)) \
            or isinstance(other, ast.Call) and _dotted(other.func) in ("float", "int")
        rooted = any(isinstance(n, ast.Call) and _dotted(n.func) in _ROOT_CALLS for n in walk(side))
        if bare and squared(side) and not rooted:
            written = ast.unparse(ast.Compare(side, node.ops, [ast.BinOp(other, ast.Pow(), ast.Constant(2))])
                                  if side is node.left else
                                  ast.Compare(ast.BinOp(other, ast.Pow(), ast.Constant(2)), node.ops, [side]))
            yield "squared_bound", written, ""
        if rooted and isinstance(other, ast.BinOp) and isinstance(other.op, ast.Pow) \
                and isinstance(other.right, ast.Constant) and other.right.value == 2:
            written = ast.unparse(ast.Compare(side, node.ops, [other.left]) if side is node.left else
                                  ast.Compare(other.left, node.ops, [side]))
            yield "squared_bound", written, ""


# Constants a student types with a few digits: each with the expression that is exact.
_EXACT_CONSTANTS = ((math.pi, "np.pi"), (2 * math.pi, "2 * np.pi"), (math.pi / 2, "np.pi / 2"),
                    (math.pi / 180, "np.pi / 180"), (180 / math.pi, "180 / np.pi"), (math.sqrt(2), "np.sqrt(2)"),
                    (math.sqrt(3), "np.sqrt(3)"), (1 / math.sqrt(2), "1 / np.sqrt(2)"), (math.e, "np.e"))


def _exact_constant(value: float) -> str:
    """The exact expression of a known constant ``value`` approximates to a few digits (within 0.2%, not
    exactly: `3.14`, `57.3`, `1.414`), or ""."""
    for exact, text in _EXACT_CONSTANTS:
        if value != exact and abs(value - exact) <= 2e-3 * exact and abs(value - exact) > 1e-12 * exact:
            return text
    return ""


def _translation_scaled(node):
    """A similarity written [[s, 0, t_x], [0, s, t_y], [0, 0, 1]] with its translation scaled or not by s:
    the scale and the translation composed in the other order (`-c` where S T(-c) has `-s * c`, and back)."""
    rows = node.elts
    if not all(isinstance(row, (ast.List, ast.Tuple)) and len(row.elts) == 3 for row in rows):
        return
    scale = ast.unparse(rows[0].elts[0])
    if isinstance(rows[0].elts[0], ast.Constant) or ast.unparse(rows[1].elts[1]) != scale:
        return
    shifts = [rows[0].elts[2], rows[1].elts[2]]
    if any(isinstance(shift, ast.Constant) for shift in shifts):
        return

    def unscaled(shift):   # `-s * c[0]`, `s * -c[0]`, `-(s * c[0])` -> `-c[0]`; None where s is no factor
        negated = isinstance(shift, ast.UnaryOp) and isinstance(shift.op, ast.USub)
        inner = shift.operand if negated else shift
        if isinstance(inner, ast.BinOp) and isinstance(inner.op, ast.Mult):
            for factor, other in ((inner.left, inner.right), (inner.right, inner.left)):
                plain = factor.operand if isinstance(factor, ast.UnaryOp) and isinstance(factor.op, ast.USub) else factor
                if ast.unparse(plain) == scale:
                    sign = negated != (plain is not factor)
                    return f"-{ast.unparse(other)}" if sign else ast.unparse(other)
        return None

    texts = [ast.unparse(shift) for shift in shifts]
    plain = [unscaled(shift) for shift in shifts]
    if all(text is not None for text in plain):
        changed = plain
    elif not any(scale in {n.id for n in walk(shift) if isinstance(n, ast.Name)} for shift in shifts) \
            and scale.isidentifier():
        changed = [f"{scale} * {text}" if not text.startswith("-") else f"-{scale} * {text[1:]}" for text in texts]
    else:
        return
    made = copy_tree(node)
    for row, text in zip(made.elts[:2], changed):
        row.elts[2] = parse(text, mode="eval").body
    yield "translation_scaled", ast.unparse(made), ""


# Calls a power may be taken inside or outside of: reductions and box/blur filters (a mean of squares
# is not the square of a mean).
_AVERAGING = {"mean", "sum", "average", "nanmean", "nansum", "blur", "boxFilter", "filter2D", "GaussianBlur",
              "sqrBoxFilter", "uniform_filter", "convolve", "correlate", "sepFilter2D"}


def _measure_changes(node):
    """A difference measured the other way: squared where its absolute value belongs or the other
    way round (`np.abs(d)` / `d ** 2` / `np.square(d)`), and a power taken outside an average where it
    belongs inside (`np.mean(d) ** 2` for `np.mean(d ** 2)`) or the other way round."""
    if isinstance(node, ast.Call) and len(node.args) == 1 and not node.keywords \
            and _dotted(node.func).rsplit(".", 1)[-1] in _SQUARED and _dotted(node.func) in (
                "abs", "np.abs", "numpy.abs", "np.absolute", "numpy.absolute", "np.fabs", "math.fabs"):
        yield "measure", "square", ""
    squared = isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) \
        and isinstance(node.right, ast.Constant) and node.right.value == 2
    if squared or (isinstance(node, ast.Call) and _dotted(node.func) in ("np.square", "numpy.square")
                   and len(node.args) == 1):
        yield "measure", "abs", ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) and isinstance(node.left, ast.Call) \
            and node.left.args and not isinstance(node.left.args[0], ast.Starred) \
            and _averages(_dotted(node.left.func)):
        yield "power_inside", "inside", ""
    if isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.BinOp) \
            and isinstance(node.args[0].op, ast.Pow) and _averages(_dotted(node.func)):
        yield "power_inside", "outside", ""
    if isinstance(node, ast.Call) and len(node.args) == 1 and isinstance(node.args[0], ast.BinOp) \
            and isinstance(node.args[0].op, ast.Div) and _dotted(node.func).rsplit(".", 1)[-1] in _REDUCED:
        yield "power_inside", "ratio", ""   # a mean of ratios where the ratio to the mean belongs
    yield from _missing_measure(node)


def _column_order(node, parent):
    """`np.argwhere(mask)` gives (row, column) pairs: used as (x, y) points they are the other way round."""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.argwhere", "numpy.argwhere") \
            and not (isinstance(parent, ast.Subscript) and parent.value is node):
        yield "column_order", f"{_operand(node)}[:, ::-1]", ""


def _conversion_slips(node, parent):
    """A conversion that truncates where it should round (`int(x)`, `x.astype(int)`: 2.9 becomes 2), one
    to uint8 that wraps round where it should saturate (`x.astype(np.uint8)`: 256 becomes 0, -1 255),
    and an integer constant of an arithmetic step one off (`2 ** n - 1` for `2 ** n`, `% 8` for `% 9`)."""
    if isinstance(node, ast.Call) and _dotted(node.func) == "int" and len(node.args) == 1 and not node.keywords \
            and not (isinstance(node.args[0], ast.Call) and _dotted(node.args[0].func) in ("round", "np.round")):
        yield "rounding", f"int(round({ast.unparse(node.args[0])}))", ""
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "astype" \
            and len(node.args) == 1 and (_dotted(node.args[0]) in _INTEGER_TYPES | {"int"}
                                         or (isinstance(node.args[0], ast.Constant) and node.args[0].value in ("uint8", "int"))):
        array, kind = ast.unparse(node.func.value), ast.unparse(node.args[0])
        if not (isinstance(node.func.value, ast.Call) and _dotted(node.func.value.func) in ("np.round", "np.rint", "np.clip")):
            yield "rounding", f"np.round({array}).astype({kind})", ""
            if "uint8" in kind:
                yield "rounding", f"np.clip(np.round({array}), 0, 255).astype({kind})", ""
    if isinstance(node, ast.Constant) and type(node.value) is int and isinstance(parent, ast.BinOp) \
            and isinstance(parent.op, (ast.Add, ast.Sub, ast.Mod, ast.FloorDiv)) and 0 <= node.value <= 16:
        for other in (node.value - 1, node.value + 1):   # (`x - 0`: the term dropped, a change made already)
            if other >= (1 if isinstance(parent.op, (ast.Add, ast.Sub)) else 0):
                yield "bound", other, ""


def _singular_value_changes(node, parent):
    """A matrix recomposed from its SVD without its constraint (`U @ np.diag(S) @ Vt`: the rank-2 F's
    smallest singular value left, an E's (s, s, 0) not imposed), or with the wrong one."""
    if not (isinstance(node, ast.Call) and _dotted(node.func) in ("np.diag", "numpy.diag") and len(node.args) == 1
            and isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.MatMult)):
        return
    listed = node.args[0]
    if isinstance(listed, (ast.List, ast.Tuple)) and len(listed.elts) == 3 \
            and not (isinstance(listed.elts[2], ast.Constant) and listed.elts[2].value == 0):
        # the values written out with the smallest one kept (`np.diag([s, s, S[2]])`)
        kept = ", ".join(ast.unparse(item) for item in listed.elts[:2])
        yield "rank", f"np.diag([{kept}, 0])", ""
        return
    if not isinstance(listed, ast.Name):
        return
    values = node.args[0].id
    for kept in (f"[{values}[0], {values}[1], 0]", "[1, 1, 0]", f"[({values}[0] + {values}[1]) / 2] * 2 + [0]"):
        yield "rank", f"np.diag({kept})", ""


def _denormalisations(fn):
    """(node, payload): an estimate made in normalised coordinates and returned without the normalising
    transforms undone (`return F` where `T2.T @ F @ T1` belongs, `return H` for `inv(T2) @ H @ T1`, or
    on one side only where the other is undone: `inv(T) @ P` for a camera whose world side is): the
    transforms are what one of the student's helpers returns for each image (`T1, T2 = _norm(p1),
    _norm(p2)`; `n1, T1 = _norm(p1)` and `n2, T2 = _norm(p2)`), the estimate the first name the return reads."""
    made = {}
    for node in walk(fn):
        if not (isinstance(node, ast.Assign) and len(node.targets) == 1):
            continue
        target, value = node.targets[0], node.value
        pairs = list(zip(target.elts, value.elts)) if isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) \
            and len(target.elts) == len(value.elts) else [(target, value)]
        for name, call in pairs:
            if not isinstance(call, ast.Call) or not isinstance(call.func, ast.Name):
                continue   # (a helper of the student's module, called by its name)
            if isinstance(name, ast.Tuple) and len(name.elts) == 2 and isinstance(name.elts[1], ast.Name):
                made.setdefault(_dotted(call.func), []).append(name.elts[1].id)
            elif isinstance(name, ast.Name):
                made.setdefault(_dotted(call.func), []).append(name.id)
    transforms = next((names[:2] for names in made.values() if len(names) >= 2), None)
    if transforms is None:
        return
    first, second = transforms
    for node in walk(fn):
        if isinstance(node, ast.Return) and node.value is not None:
            estimate = next((n for n in walk(node.value) if isinstance(n, ast.Name) and n.id not in transforms
                             and isinstance(n.ctx, ast.Load) and n.id not in ("np", "numpy", "cv2")), None)
            if estimate is None:
                continue
            for a, b in ((second, first), (first, second)):
                for undone in (f"({a}.T @ {estimate.id} @ {b})", f"(np.linalg.inv({a}) @ {estimate.id} @ {b})"):
                    yield estimate, undone
            # (one side only, where the other is in more matrix products than it -- undone already: `P =
            # p.reshape(3, 4) @ U` returned without `inv(T)`, U also normalising the points as T does)
            products = {name: sum(isinstance(n, ast.BinOp) and isinstance(n.op, ast.MatMult) and any(
                isinstance(m, ast.Name) and m.id == name for side in (n.left, n.right) for m in walk(side))
                for n in walk(fn)) for name in transforms}
            for a, b in ((first, second), (second, first)):
                if products[b] > products[a]:
                    for undone in (f"(np.linalg.inv({a}) @ {estimate.id})", f"({a}.T @ {estimate.id})",
                                   f"({estimate.id} @ {a})"):
                        yield estimate, undone


def _sum_of_squares(node) -> bool:
    """``a ** 2 + b ** 2`` (or ``a * a + b * b``, of two or more terms): the square of a length."""
    def square(term) -> bool:
        return (isinstance(term, ast.BinOp) and isinstance(term.op, ast.Pow) and isinstance(term.right, ast.Constant)
                and term.right.value == 2) or (isinstance(term, ast.BinOp) and isinstance(term.op, ast.Mult)
                                               and ast.dump(term.left) == ast.dump(term.right))
    return isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add) and square(node.right) \
        and (square(node.left) or _sum_of_squares(node.left))


def _missing_measure(node):
    """A step of a measure left out: a sum of squares where its square root -- the distance -- belongs
    (`np.sum(d ** 2, axis=1) < t` for a threshold in pixels), and a sum of differences where the sum
    of their absolute values belongs (`np.sum(l - r)` for the SAD)."""
    if not isinstance(node, ast.Call) or not node.args or isinstance(node.args[0], ast.Starred):
        return
    short = _dotted(node.func).rsplit(".", 1)[-1]
    if short not in ("sum", "mean") or not _dotted(node.func).startswith(("np.", "numpy.")):
        return
    argument = node.args[0]
    squares = any((isinstance(n, ast.BinOp) and isinstance(n.op, ast.Pow) and isinstance(n.right, ast.Constant)
                   and n.right.value == 2) or (isinstance(n, ast.Call) and _dotted(n.func) in ("np.square", "numpy.square"))
                  for n in walk(argument))
    if squares:
        yield "measure", "sqrt", ""
    if isinstance(argument, ast.BinOp) and isinstance(argument.op, ast.Sub):
        yield "measure", "abs_inside", ""


def _averages(dotted: str) -> bool:
    """Whether a called function averages: NumPy's and OpenCV's, or one of the student's own whose name
    says so (`_box_mean`, `local_average`, `blur3`)."""
    name = dotted.rsplit(".", 1)[-1]
    return name in _AVERAGING or (not dotted.startswith(("np.", "numpy.", "cv2.", "math."))
                                  and any(word in name.lower() for word in ("mean", "blur", "box", "average", "smooth")))


def _loop_order_changes(iterable):
    """A loop over a list's items in the wrong order: a pyramid collapsed from its finest level up
    (`for band in bands[:-1]` where `reversed(bands[:-1])` belongs), or the other way round."""
    if isinstance(iterable, ast.Call) and isinstance(iterable.func, ast.Name) and iterable.func.id == "reversed" \
            and len(iterable.args) == 1:
        yield "loop_order", ast.unparse(iterable.args[0]), ""
    elif isinstance(iterable, (ast.Name, ast.Subscript, ast.Attribute)):
        yield "loop_order", f"reversed({ast.unparse(iterable)})", ""


def _row_column_changes(node: ast.Subscript):
    """A coordinate's row taken where its column belongs, or back: `X[2] += dz` moves the third point,
    `X[:, 2] += dz` every point's depth (points are rows). Only a constant index 0..3 of a name."""
    item = node.slice
    # (a run of entries cut along one axis where the next belongs: `costs[d, :d] = np.inf` blanks the first d rows
    # of the d-th slice, `costs[d, :, :d]` its first d columns)
    last = item.elts[-1] if isinstance(item, ast.Tuple) and item.elts else item
    if isinstance(last, ast.Slice) and (last.lower is not None or last.upper is not None) and last.step is None \
            and not (isinstance(item, ast.Tuple) and any(isinstance(e, ast.Slice) for e in item.elts[:-1])):
        yield "row_column", "next_axis", ""
    if _constant_index(item) in (0, 1, 2, 3):
        yield "row_column", "column", ""
    elif isinstance(item, ast.Tuple) and len(item.elts) == 2 and isinstance(item.elts[0], ast.Slice) \
            and item.elts[0].lower is None and item.elts[0].upper is None and item.elts[0].step is None \
            and _constant_index(item.elts[1]) in (0, 1, 2, 3):
        yield "row_column", "row", ""


def _slice_item_changes(node: ast.Subscript):
    """A slice written to where one entry belongs: `M[0, 1:] = s` fills the rest of row 0 too (the
    translation `M[0, 2]` overwritten with the shear), `K[:2, 2] = p` where `K[0, 2] = p` was meant: the
    slice's first entry alone; a square block where its diagonal belongs (`K[:2, :2] = f`). Only slices
    of constant bounds and no step, in a write."""
    items = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
    for k, item in enumerate(items):
        if isinstance(item, ast.Slice) and item.step is None and (item.lower is not None or item.upper is not None):
            start = 0 if item.lower is None else _constant_index(item.lower)
            if start is not None and start >= 0:
                yield "slice_item", (k, start), ""
    # (a square block written where its diagonal belongs: `K[:2, :2] = f` sets the skew entries to f too)
    if len(items) == 2 and all(isinstance(item, ast.Slice) and item.step is None for item in items) \
            and ast.dump(items[0]) == ast.dump(items[1]) and items[0].upper is not None:
        start = 0 if items[0].lower is None else _constant_index(items[0].lower)
        stop = _constant_index(items[0].upper)
        if start is not None and stop is not None and 0 <= start and start + 2 <= stop <= start + 4:
            yield "slice_item", (None, (start, stop)), ""


def _slice_changes(node: ast.Slice):
    """A slice of constant bounds one place off: the window moved by one (`3:7` for `4:8`), or the
    last entries taken where the first belong (`1:` for `:2` of a 3-vector, and back)."""
    if node.step is not None:
        return
    if (node.lower is None) != (node.upper is None) and _constant_index(node.lower or node.upper) is None:
        yield "slice", "other_end", ""   # `x[d:]` <-> `x[:d]` for a bound the code computes
        if node.lower is not None:
            # (d entries dropped from the start where the last d belong off: a shift padded on the left and then
            # cut back where it began, `np.pad(R, ((0, 0), (d, 0)))[:, d:]`, undoes itself)
            yield "slice", "drop_last", ""
        return
    lower, upper = (None if b is None else _constant_index(b) for b in (node.lower, node.upper))
    if (node.lower is not None and lower is None) or (node.upper is not None and upper is None):
        return
    if lower is not None and upper is not None:
        for delta in (-1, 1):
            if lower + delta >= 0 and (upper + delta != 0 or upper < 0):
                yield "slice", (lower + delta, upper + delta), ""
        # (and the block beside it, of the same width: a row of a design matrix written `A[k, 0:4] = X`
        # where its second block `4:8` belongs -- the line copied from the row above, its columns left)
        width = upper - lower
        if 0 <= lower < upper and width >= 2:
            for delta in (-width, width):
                if lower + delta >= 0:
                    yield "slice", (lower + delta, upper + delta), ""
    elif lower == 1 and upper is None:
        yield "slice", (None, 2), ""
        yield "slice", (None, -1), ""
    if lower is not None and lower >= 1 and upper is None:
        # (every column from k on, where column k alone belongs: `xn[:, 1:]` of points left homogeneous is
        # (y, 1), where y, kept 2-D, was meant -- `xn[:, 1:2]`)
        yield "slice", (lower, lower + 1), ""
    elif lower is None and upper in (2, -1):
        yield "slice", (1, None), ""


def _counted_loop_changes(loop: ast.For):
    """A loop over a fixed count where every item belongs (`for i in range(8)` over `p1[i]`: the
    eight-point algorithm given 40 points uses eight): the count becomes `len` of what it indexes."""
    indexed = []
    for inner in walk(loop):
        if isinstance(inner, ast.Subscript) and isinstance(inner.value, ast.Name) and inner.value.id not in indexed:
            first = inner.slice.elts[0] if isinstance(inner.slice, ast.Tuple) and inner.slice.elts else inner.slice
            if isinstance(first, ast.Name) and first.id == loop.target.id:
                indexed.append(inner.value.id)
    for name in indexed[:2]:
        yield "loop_all", f"len({name})", ""


def _twins(a, b) -> bool:
    """Two like terms, one letter or one index apart (`x` and `y`, `q[:, 0]` and `q[:, 1]`,
    `pts1[i]` and `pts2[i]`): what a student writes twice, once per coordinate or image."""
    if type(a) is not type(b) or not isinstance(a, _TERMS):
        return False
    first, second = list(walk(a)), list(walk(b))
    if len(first) != len(second) or len(first) > 12:
        return False
    apart = 0
    for x, y in zip(first, second):
        if type(x) is not type(y):
            return False
        words = (x.id, y.id) if isinstance(x, ast.Name) else (x.attr, y.attr) if isinstance(x, ast.Attribute) \
            else None
        if words and words[0] != words[1]:
            if len(words[0]) != len(words[1]) or sum(p != q for p, q in zip(*words)) != 1:
                return False
            apart += 1
        if isinstance(x, ast.Constant) and x.value != y.value:
            if not (isinstance(x.value, int) and isinstance(y.value, int)):
                return False
            apart += 1
    return apart == 1


def _index_twins(a, b) -> bool:
    """Two parts of one array taken at one index apart in kind: an item and a slice (`line[2]` and
    `line[:2]`, `out[i, 2]` and `out[i, :2]`): the last entry written apart from the first ones."""
    if not (isinstance(a, ast.Subscript) and isinstance(b, ast.Subscript)) or ast.dump(a.value) != ast.dump(b.value):
        return False
    first, second = a.slice, b.slice
    if isinstance(first, ast.Tuple) and isinstance(second, ast.Tuple) and len(first.elts) == len(second.elts):
        differ = [(x, y) for x, y in zip(first.elts, second.elts) if ast.dump(x) != ast.dump(y)]
        if len(differ) != 1:
            return False
        first, second = differ[0]
    kinds = {type(first), type(second)}
    return kinds == {ast.Constant, ast.Slice}


def _twin_steps(items):
    """For each bare term among ``items`` (a tuple's entries, the values of twin assignments), its
    twin's step done to it too: `(x / w, y)` -> `y / w`, `(int(u), v)` -> `int(v)`. (position, text)."""
    for j, bare in enumerate(items):
        if not isinstance(bare, _TERMS):
            continue
        made = set()
        for i, stepped in enumerate(items):
            if i == j or isinstance(stepped, (*_TERMS, ast.Constant)):
                continue
            for inner in itertools.islice((n for n in walk(stepped) if n is not stepped
                                           and (_twins(n, bare) or _index_twins(n, bare))), 3):
                twin = copy_tree(stepped)
                for old, new in zip(walk(stepped), walk(twin)):
                    if old is inner:
                        replaced = _swap_in(twin, new, copy_tree(bare))
                        break
                text = ast.unparse(replaced)
                if text not in made and len(text) <= 80:
                    made.add(text)
                    yield j, text


def _moved_terms(node):
    """The tuple with a term added to one item moved to its twin: `(q[0], q[1] + w1)` -> `(q[0] + w1, q[1])`,
    an offset put on y where x takes it -- the two items alike but for the term and the index (written out
    whole, at most 3 texts)."""
    made = []
    for i, j in itertools.permutations(range(len(node.elts)), 2):
        pair = _one_difference(node.elts[i], node.elts[j])
        if pair is None:
            continue
        bare, offset = pair
        if not (isinstance(offset, ast.BinOp) and isinstance(offset.op, (ast.Add, ast.Sub))
                and not isinstance(offset.right, ast.Constant) and (_twins(offset.left, bare) or _index_twins(offset.left, bare))):
            continue
        moved = copy_tree(node)
        for old, new in zip(walk(node), walk(moved)):
            if old is bare:
                _swap_in(moved, new, ast.BinOp(copy_tree(bare), offset.op, copy_tree(offset.right)))
            elif old is offset:
                _swap_in(moved, new, copy_tree(offset.left))
        text = ast.unparse(moved)
        if text not in made and len(text) <= 120:
            made.append(text)
    return made[:3]


def _one_difference(a, b):
    """``(a's part, b's part)`` where two expressions differ at one place only and are the same around
    it (`v.astype(t)` and `(u / w).astype(t)`: `v` and `u / w`); None when they are alike or differ
    at more places."""
    if ast.dump(a) == ast.dump(b):
        return None
    if type(a) is not type(b) or isinstance(a, (ast.Name, ast.Constant)):
        return a, b
    found = None
    for (field, x), (_, y) in zip(ast.iter_fields(a), ast.iter_fields(b)):
        xs, ys = (x, y) if isinstance(x, list) else ([x], [y])
        if not isinstance(ys, list) or len(xs) != len(ys):
            return None
        for p, q in zip(xs, ys):
            if isinstance(p, ast.AST) and isinstance(q, ast.AST):
                if ast.dump(p) == ast.dump(q):
                    continue
                if found is not None:
                    return None
                found = _one_difference(p, q)
                if found is None:
                    return None
            elif p != q:
                return None
    return found


def _swap_in(root, old, new):
    """``root`` with the node ``old`` (inside it) replaced by ``new``."""
    for parent in walk(root):
        for field, value in ast.iter_fields(parent):
            if value is old:
                setattr(parent, field, new)
                return root
            if isinstance(value, list) and any(item is old for item in value):
                value[next(k for k, item in enumerate(value) if item is old)] = new
                return root
    return root


def _twin_mapping(inner: ast.AST, bare: ast.AST) -> dict | None:
    """The names of ``inner`` to rename (each to its twin) to write ``bare``; None when no such renaming
    does (or none is needed: the two are alike)."""
    first, second = list(walk(inner)), list(walk(bare))
    if len(first) != len(second) or len(first) > 16:
        return None
    names = {}
    for x, y in zip(first, second):
        if type(x) is not type(y):
            return None
        if isinstance(x, ast.Name):
            if x.id != y.id and not (twin_names(x.id, y.id) and names.get(x.id, y.id) == y.id):
                return None
            if x.id != y.id:
                names[x.id] = y.id
        elif ast.dump(x) != ast.dump(y) and not list(ast.iter_child_nodes(x)):
            return None   # (a leaf other than a name differs: a constant, an attribute's word)
        elif isinstance(x, ast.Attribute) and x.attr != y.attr:
            return None
    return names or None


def _twin_argument_changes(node, words):
    """One argument of a call given bare where its twin argument has a step: `core(h(pts1) @ T1.T,
    h(pts2))` -> `h(pts2) @ T2.T` (the second view's normalisation left out), the step's other names
    renamed as the twins are (T1 -> T2) when the function has those names, and also kept as written."""
    if not isinstance(node, ast.Call) or not 2 <= len(node.args) <= 4 or any(isinstance(a, ast.Starred) for a in node.args):
        return
    known = {n.id for n in walk(words.fn) if isinstance(n, ast.Name)}
    for j, bare in enumerate(node.args):
        if isinstance(bare, ast.Constant):
            continue
        made = set()
        for i, stepped in enumerate(node.args):
            if i == j:
                continue
            for inner in walk(stepped):
                if inner is stepped or not isinstance(inner, (*_TERMS, ast.Call)):
                    continue
                names = _twin_mapping(inner, bare)
                if names is None:
                    continue
                # the step's other names renamed as the twins differ (`T1` -> `T2` beside `pts1` -> `pts2`)
                differences = {_difference(a, b) for a, b in names.items()}
                more = dict(names)
                for other in {n.id for n in walk(stepped) if isinstance(n, ast.Name)} - set(names):
                    more.update((other, twin) for twin in sorted(known)
                                if twin != other and twin_names(other, twin) and _difference(other, twin) in differences)
                for mapping in (more, names):
                    step = copy_tree(stepped)
                    for old_node, new_node in zip(walk(stepped), walk(step)):
                        if old_node is inner:
                            step = _swap_in(step, new_node, copy_tree(bare))
                            break
                    for name in set(mapping) - set(names):   # (names the twins' renaming leaves: the step's own)
                        step = _renamed(step, name, mapping[name])
                    text = ast.unparse(step)
                    if text not in made and len(text) <= 80:
                        made.add(text)
                        yield "twin_argument", (j, text), ""
                break


def _difference(a: str, b: str) -> tuple:
    """Where two twin names differ: `("1", "2")` for `pts1`/`pts2` and `T1`/`T2` alike."""
    if len(a) != len(b):
        return (a, b)
    return tuple((x, y) for x, y in zip(a, b) if x != y)


def _series_powers(node, parent):
    """A series in the powers of one name written in the powers of its square root, or of its square:
    `1 + k1 * r + k2 * r ** 2 + k3 * r ** 3` (r the radius) where `r ** 2, r ** 4, r ** 6` belong -- every
    power doubled -- or every even power halved (the powers of r written on r2 = r ** 2)."""
    def additive(n):
        return isinstance(n, ast.BinOp) and isinstance(n.op, (ast.Add, ast.Sub))
    if not additive(node) or additive(parent):
        return
    bases = {}   # name -> the powers it is raised to in the sum
    bare = set()
    for n in walk(node):
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Pow) and isinstance(n.left, ast.Name) \
                and isinstance(n.right, ast.Constant) and type(n.right.value) is int and 1 <= n.right.value <= 8:
            bases.setdefault(n.left.id, set()).add(n.right.value)
            bare.add(id(n.left))
    for n in walk(node):
        if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load) and id(n) not in bare and n.id in bases:
            bases[n.id].add(1)
    for name, powers in sorted(bases.items()):
        if len(powers) < 2:
            continue
        for factor in (2, 0.5):
            if factor == 0.5 and any(p % 2 for p in powers):
                continue
            changed = copy_tree(node)
            for n in list(walk(changed)):
                for field, child in ast.iter_fields(n):
                    if isinstance(child, ast.Name) and child.id == name and isinstance(child.ctx, ast.Load) \
                            and not (isinstance(n, ast.BinOp) and isinstance(n.op, ast.Pow) and field == "left"):
                        setattr(n, field, ast.BinOp(ast.Name(name, ast.Load()), ast.Pow(), ast.Constant(2))
                                if factor == 2 else child)
                    elif isinstance(child, ast.BinOp) and isinstance(child.op, ast.Pow) and isinstance(child.left, ast.Name) \
                            and child.left.id == name and isinstance(child.right, ast.Constant):
                        power = int(child.right.value * factor)
                        setattr(n, field, ast.Name(name, ast.Load()) if power == 1 else
                                ast.BinOp(ast.Name(name, ast.Load()), ast.Pow(), ast.Constant(power)))
            yield "series_powers", ast.unparse(changed), ""


def _twin_factor(node, words):
    """A matrix factor one of two twin names is given and the other is not: `P1 = K @ np.hstack([I, 0])`
    beside `P2 = np.hstack([R, t])` (camera 2 built without K): the twin's factor given to it too."""
    parent = _parent_of(node, words)
    if not (isinstance(parent, ast.Assign) and parent.value is node and len(parent.targets) == 1
            and isinstance(parent.targets[0], ast.Name)) or isinstance(node, ast.Constant):
        return
    name = parent.targets[0].id
    for twin, defs in words.definitions.items():
        if twin == name or not twin_names(name, twin):
            continue
        for _, value, index in defs:
            if index is None and isinstance(value, ast.BinOp) and isinstance(value.op, ast.MatMult) \
                    and isinstance(value.left, ast.Name) and not (
                        isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult)
                        and isinstance(node.left, ast.Name) and node.left.id == value.left.id):
                yield "twin_factor", f"{value.left.id} @ {ast.unparse(node)}", ""
                return


def _factor_pair(node, words):
    """A fix made to one factor of a product and not undone in the other: `K, R = rq(M)` then `K = K @ D`
    (K's columns given the signs that make its diagonal positive) with R's rows left as they were, so
    K @ R is no longer M: the pair changed together, `K, R = K @ D, D @ R` (a sign matrix is its own
    inverse; any other matrix's inverse is tried too). The factors are two names unpacked together, or
    made each from one of two names unpacked together (`Q, U = np.linalg.qr(...)`, `K = inv(U)`, `R = Q.T`);
    the other factor is not given a value again after the fix."""
    if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)
            and isinstance(node.value, ast.BinOp) and isinstance(node.value.op, ast.MatMult)):
        return
    name, product = node.targets[0].id, node.value
    for on_the_right, (mine, fix) in enumerate(((product.right, product.left), (product.left, product.right))):
        # (`K @ D`: on_the_right 1, the fix applied on K's right; `D @ R`: 0, on its left)
        if not (isinstance(mine, ast.Name) and mine.id == name) or name in _read(fix):
            continue
        for other in _factor_partners(name, node.lineno, words):
            text = ast.unparse(fix)
            if other in _read(fix) or any(at > node.lineno for at, _, _ in words.definitions[other]) \
                    or _given_already(other, text, node.lineno, words):
                continue
            fix_text = text if isinstance(fix, (ast.Name, ast.Attribute, ast.Subscript, ast.Call)) else f"({text})"
            for undone in (fix_text, f"np.linalg.inv({text})"):
                yield "factor_pair", (other, f"{undone} @ {other}" if on_the_right else f"{other} @ {undone}"), ""
        return


def _given_already(name: str, fix: str, line: int, words) -> bool:
    """Whether ``name`` was last given, above ``line``, a product with ``fix`` as a factor (`K = K @ D` above
    `R = D @ R`: the pair is fixed)."""
    defs = [d for d in words.definitions.get(name, ()) if d[0] < line]
    value = max(defs, key=lambda d: d[0])[1] if defs else None
    return isinstance(value, ast.BinOp) and isinstance(value.op, ast.MatMult) \
        and fix in (ast.unparse(value.left), ast.unparse(value.right))


def _factor_partners(name: str, line: int, words) -> list:
    """The names made with ``name`` as two factors of one decomposition, as they stand above ``line``: unpacked
    together from one call (`K, R = rq(M)`), or each made from one of two names so unpacked (`K = inv(U)`,
    `R = Q.T` of `Q, U = qr(...)`)."""
    def last(of):
        defs = [d for d in words.definitions.get(of, ()) if d[0] < line]
        return max(defs, key=lambda d: d[0]) if defs else None

    def unpacked_with(of):
        made = last(of)
        if made is None or made[2] is None or not isinstance(made[1], ast.Call):
            return []
        at, value, index = made
        return [o for o, defs in words.definitions.items() if o != of and any(
            a == at and v is value and i is not None and i != index for a, v, i in defs)]

    def made_from(of):
        made = last(of)
        if made is None or made[2] is not None or isinstance(made[1], ast.AugAssign):
            return None
        sources = [n for n in _read(made[1]) if n in words.definitions and n != of]
        return sources[0] if len(sources) == 1 else None
    partners = unpacked_with(name)
    if partners:
        return partners
    source = made_from(name)
    if source is None:
        return []
    twins = unpacked_with(source)
    # (the local made from the source's twin alone: `R = Q.T` beside `K = inv(U)`; among the locals last given
    # above the line, a bounded number of them: a long def is read in linear time)
    return [o for o in words.locals_before(line, nearest=_NEAREST_LOCALS) if o != name and made_from(o) in twins][:2] \
        if twins else []


def _boolean_made(value) -> bool:
    """A comparison, or a new boolean array (`np.zeros(n, dtype=bool)`)."""
    return _masks(value) or (isinstance(value, ast.Call) and _dotted(value.func).rsplit(".", 1)[-1] in _ALLOCATIONS
                             and any(k.arg == "dtype" and ast.unparse(k.value) in ("bool", "np.bool_", "numpy.bool_")
                                     for k in value.keywords))


def _masks_held(fn) -> frozenset:
    """The names ``fn`` gives a mask at some point -- a comparison, a new boolean array, another such name
    (`best = np.zeros(n, dtype=bool)`, later `best = inliers`) -- looser than :func:`_mask_names` (a name
    also given other values counts), for changes that only offer a mask where one may belong. Read once per def."""
    known = getattr(fn, "_grader_masks_held", None)
    if known is None:
        held = set()
        assigned = [(t.id, n.value) for n in walk(fn) if isinstance(n, ast.Assign) for t in n.targets
                    if isinstance(t, ast.Name)]
        for _ in range(_MASK_ROUNDS):   # (each round linear in the def: a mask followed through a few names)
            grown = held | {name for name, value in assigned if _boolean_made(value)
                            or (isinstance(value, ast.Name) and value.id in held)}
            if grown == held:
                break
            held = grown
        known = fn._grader_masks_held = frozenset(held)
    return known


def _masked_arrays(fn) -> dict:
    """name -> the mask names ``fn`` indexes it with somewhere (`src[inliers]`), kept per def."""
    known = getattr(fn, "_grader_masked_arrays", None)
    if known is None:
        masks, known = _masks_held(fn), {}
        for n in walk(fn):
            if isinstance(n, ast.Subscript) and isinstance(n.ctx, ast.Load) and isinstance(n.value, ast.Name) \
                    and isinstance(n.slice, ast.Name) and n.slice.id in masks:
                known.setdefault(n.value.id, set()).add(n.slice.id)
        fn._grader_masked_arrays = known
    return known


_MASKS_TRIED = 3   # masks a call's arrays are selected by, at most (the last bound above it first)


def _selected_by_mask(node, words):
    """Every point given where the points a mask keeps belong: `homography_dlt(src, dst)` after a RANSAC
    loop that keeps its consensus as `best_inliers`, in code that selects `src[inliers]` elsewhere -- the
    arrays the code indexes by a mask somewhere, given whole to a call, selected by each mask bound above
    it (the last bound first)."""
    if not (isinstance(node, ast.Call) and len(node.args) >= 2 and not any(isinstance(a, ast.Starred) for a in node.args)):
        return
    masked = _masked_arrays(words.fn)
    arrays = [a.id for a in node.args if isinstance(a, ast.Name) and a.id in masked]
    if len(arrays) < 2:
        return
    line = node.lineno
    # (any mask bound above the call: the one the code selects with elsewhere may be the loop's, not the best)
    bound = sorted(((max(at for at, _, _ in words.definitions.get(m, ()) if at < line), m)
                    for m in _masks_held(words.fn)
                    if any(at < line for at, _, _ in words.definitions.get(m, ()))), reverse=True)
    for _, mask in bound[:_MASKS_TRIED]:
        yield "select_mask", (tuple(arrays), mask), ""


def _counted_by_length(node, words):
    """A loop counted by a number written in the code where the length of a list the function is given
    belongs: `for k in range(3)` for `range(len(images))` (three images in the student's own tests)."""
    if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "range"
            and len(node.args) == 1 and isinstance(node.args[0], ast.Constant)
            and type(node.args[0].value) is int and node.args[0].value >= 2):
        return
    for parameter in words.fn.args.args:
        yield "counted", f"range(len({parameter.arg}))", ""


_CROSSED_PAIRS = 3


def _crossed_twins(node, words):
    """Two twin names exchanged throughout one entry of a matrix written out, or one assigned value:
    `beta * cy + (1 - alpha) * cx` for `beta * cx + (1 - alpha) * cy` (each name alone is wrong,
    so no single change of one name mends the entry)."""
    parent = _parent_of(node, words)
    if not ((isinstance(parent, (ast.List, ast.Tuple)) and isinstance(parent.ctx, ast.Load))
            or (isinstance(parent, ast.Assign) and parent.value is node)) \
            or not isinstance(node, (ast.BinOp, ast.Call, ast.UnaryOp)):
        return
    read = list(dict.fromkeys(n.id for n in walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)))
    # (each pair of twins on its own: `y * radial + p2 * (r2 + 2 * y ** 2) + 2 * p1 * x * y` holds x and y
    # as well as p1 and p2; a few pairs at most, a longer formula's every pair is no one slip)
    pairs = [(a, b) for i, a in enumerate(read) for b in read[i + 1:] if twin_names(a, b)]
    if len(pairs) > _CROSSED_PAIRS:
        return
    # (names in an index or a tuple -- `np.mgrid[0:rows, 0:cols]`, `(h, w)` -- are swap_items' to exchange,
    # shown as the smaller change)
    # (a name deeper in an item -- `x1[:, 0:1] * x2` in a list of columns -- is the formula's: exchanged here)
    inside = {id(n) for part in walk(node) if isinstance(part, ast.Slice) for n in walk(part)} \
        | {id(item) for part in walk(node) if isinstance(part, (ast.Tuple, ast.List)) for item in part.elts}
    for a, b in pairs:
        if not any(isinstance(n, ast.Name) and n.id in (a, b) and id(n) in inside for n in walk(node)):
            yield "crossed", _names_exchanged(node, a, b), ""


def _names_exchanged(node, a: str, b: str) -> str:
    """``node``'s code with every name ``a`` read as ``b`` and the other way round."""
    exchanged = copy_tree(node)
    for name in walk(exchanged):
        if isinstance(name, ast.Name) and name.id in (a, b):
            name.id = b if name.id == a else a
    return ast.unparse(exchanged)


def _default_written_out(node, words):
    """A parameter's default value written where the parameter belongs: `_pyramid(a, 4)` beside
    `levels=4` (right for the default, wrong for every other value given). Numbers other than 0 and
    1, which are everywhere for reasons of their own."""
    if not (isinstance(node, ast.Constant) and type(node.value) in (int, float) and node.value not in (0, 1)):
        return
    if not hasattr(words, "numeric_defaults"):
        args = words.fn.args
        positional = args.posonlyargs + args.args
        given = list(zip(positional[len(positional) - len(args.defaults):], args.defaults)) \
            + [(a, d) for a, d in zip(args.kwonlyargs, args.kw_defaults) if d is not None]
        words.numeric_defaults = [(a.arg, d.value) for a, d in given if isinstance(d, ast.Constant)
                                  and type(d.value) in (int, float) and d.value not in (0, 1)]
    for parameter, value in words.numeric_defaults:
        if value == node.value:
            yield "default_written", parameter, ""


def _matrix_applied(node, words):
    """A point subtracted as it is where its image under a matrix the function made belongs: `t = dst[0] -
    src[0]` for `dst[0] - L @ src[0]` (a translation that leaves out the linear part's move of the point).
    The matrices are the locals made above by a matrix product or a ``np.linalg`` call."""
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Sub)
            and isinstance(node.right, (ast.Name, ast.Subscript)) and isinstance(node.right.ctx, ast.Load)):
        return
    line = node.lineno
    for name, defs in words.definitions.items():
        made = [value for at, value, index in defs if at < line and index is None]
        if not made or not _matrix_made(made[-1]) or any(isinstance(n, ast.Name) and n.id == name
                                                         for n in walk(node)):
            continue
        yield "matrix_applied", f"{ast.unparse(node.left)} - {name} @ {ast.unparse(node.right)}", ""


def _matrix_made(value) -> bool:
    """Whether ``value`` makes a matrix: a matrix product, or a call of ``np.linalg`` (inv, solve, lstsq's
    first result)."""
    return (isinstance(value, ast.BinOp) and isinstance(value.op, ast.MatMult)) or (
        isinstance(value, ast.Call) and _dotted(value.func).startswith(("np.linalg.inv", "numpy.linalg.inv",
                                                                        "np.linalg.solve", "numpy.linalg.solve")))


def _sibling_changes(node, words):
    """Changes that copy what the student's code does for one of two like things to the other: a step
    done to one input only (`xl = xl[:, 0]` and no `xr = xr[:, 0]`: the two done together, `xl, xr =
    xl[:, 0], xr[:, 0]`), and an argument of a call that another call of the same function is given
    (`warp(weight, H, size)` beside `warp(image, shift @ H, size)`: the shift left out of one)."""
    done, calls, _ = _read_siblings(words)
    yield from _matrix_applied(node, words)
    yield from _counted_by_length(node, words)
    yield from _default_written_out(node, words)
    yield from _crossed_twins(node, words)
    yield from _twin_factor(node, words)
    yield from _factor_pair(node, words)
    yield from _selected_by_mask(node, words)
    yield from _twin_argument_changes(node, words)
    yield from _canvas_changes(node, words)
    yield from _per_item_changes(node, words)
    yield from _initial_changes(node, words)
    yield from _out_buffer_changes(node, words)
    yield from _started_with_an_item(node, words)
    yield from _loop_item_changes(node, words)
    yield from _unused_parameter_changes(node, _parent_of(node, words), words)
    if isinstance(node, (ast.Tuple, ast.List)) and isinstance(node.ctx, ast.Load) and 2 <= len(node.elts) <= 4:
        for position, text in _twin_steps(node.elts):
            yield "twin_step", (position, text), ""
        for text in _moved_terms(node):
            yield "moved_term", text, ""
    if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.value, _TERMS) \
            and isinstance(node.targets[0], _TERMS):
        for twin in _twin_assignments(node, words):   # `u = x / w` beside `v = y`; `out[i, 1] = v` too
            for position, text in _twin_steps([node.value, twin.value]):
                if position == 0:
                    yield "twin_step", (None, text), ""
    elif isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], _TERMS):
        # the same inside a wrapper both lines share: `map_y = v.astype(np.float32)` beside
        # `map_x = (u / w).astype(np.float32)` (the division done for x only)
        for twin in _twin_assignments(node, words):
            pair = _one_difference(node.value, twin.value)
            if pair is None or not isinstance(pair[0], _TERMS):
                continue
            for position, text in _twin_steps(list(pair)):
                if position == 0:
                    whole = copy_tree(node.value)
                    for old, new in zip(walk(node.value), walk(whole)):
                        if old is pair[0]:
                            whole = _swap_in(whole, new, _parse(text).body[0].value)
                            break
                    yield "twin_step", (None, ast.unparse(whole)), ""
    if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], _TERMS):
        yield from _mirror_changes(node, words)
    yield from _twin_unit_changes(node, words)
    yield from _row_like_its_siblings(node, words)
    yield from _term_its_siblings_have(node, words)
    yield from _as_its_twin_line(node, words)
    yield from _like_its_siblings(node, words)
    yield from _raw_beside_derived(node, words)
    if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], _TERMS) \
            and isinstance(node.value, ast.BinOp) and isinstance(node.value.op, (ast.Add, ast.Sub)):
        # the first term of a sum left bare where its twin's has a step: `y_d = y + ...` beside
        # `x_d = x * radial + ...` (the radial factor applied to x only)
        leading = _leading_term(node.value)
        if isinstance(leading, _TERMS):
            for twin in _twin_assignments(node, words):
                other = _leading_term(twin.value) if isinstance(twin.value, ast.BinOp) else None
                if other is None or isinstance(other, (*_TERMS, ast.Constant)):
                    continue
                for _, text in _twin_steps([leading, other]):
                    whole = copy_tree(node.value)
                    holder = whole
                    while isinstance(holder.left, ast.BinOp) and isinstance(holder.left.op, (ast.Add, ast.Sub)):
                        holder = holder.left
                    holder.left = _parse(text).body[0].value
                    yield "twin_step", (None, ast.unparse(whole)), ""
                    break
    if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
        name = node.targets[0].id
        if any(isinstance(n, ast.Name) and n.id == name for n in walk(node.value)):
            # (its twin first, a parameter or a local -- `pts2` beside `pts1 = pts1[inliers]` -- then the
            # def's other parameters)
            twins = [other for other in words.definitions if twin_names(name, other)]
            for other in dict.fromkeys([*twins, *(a.arg for a in words.fn.args.args)]):
                if other != name and ast.dump(_renamed(node, name, other)) not in done:
                    yield "sibling_step", other, ""
    if isinstance(node, ast.Call) and not any(isinstance(a, ast.Starred) for a in node.args):
        given = set()
        for other in calls.get((_dotted(node.func), len(node.args)), ()):
            for position, (mine, theirs) in enumerate(zip(node.args, other.args)):
                text = ast.unparse(theirs)
                if other is not node and position and ast.dump(mine) != ast.dump(theirs) and len(text) <= 40 \
                        and not isinstance(theirs, ast.Starred) and (position, text) not in given:
                    given.add((position, text))
                    yield "sibling_argument", (position, text), ""


_SIBLING_CALLS = 6   # the calls of one function (and arity) a call is compared with: the first few


_TERMS = (ast.Name, ast.Subscript, ast.Attribute)
_ALLOCATED = {"zeros", "ones", "empty", "full"}


def _per_item_changes(node, words):
    """A value made once before a loop from its first item, used for every item in it: `norm` of
    `first = F @ [pts[0, 0], pts[0, 1], 1]` dividing each `line = F @ [x, y, 1]` -> the norm made of
    `line` itself (the loop's twin of the first item's value, written alike)."""
    if not (isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)):
        return
    if not hasattr(words, "loop_reads"):   # (read once per def: names read in loops, the loops' assignments)
        words.loop_reads = {}
        for loop in walk(words.fn):
            if isinstance(loop, ast.For):
                made = [n for statement in loop.body for n in walk(statement)
                        if isinstance(n, ast.Assign) and len(n.targets) == 1 and isinstance(n.targets[0], ast.Name)]
                for n in walk(loop):
                    if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load) and n.lineno > loop.lineno:
                        words.loop_reads[id(n)] = (loop, made[:8])
    if id(node) not in words.loop_reads:
        return
    loop, made = words.loop_reads[id(node)]
    defs = words.definitions.get(node.id, ())
    if len(defs) != 1 or defs[0][0] >= loop.lineno or defs[0][2] is not None:
        return
    value = defs[0][1]
    for once in {n.id for n in walk(value) if isinstance(n, ast.Name)}:
        first = words.definitions.get(once, ())
        if len(first) != 1 or first[0][0] >= loop.lineno or first[0][2] is not None:
            continue
        for assigned in made:   # the loop's own value written alike (`line = F @ np.array([x, y, 1.0])`)
            if assigned.lineno < node.lineno and assigned.targets[0].id != once \
                    and not isinstance(first[0][1], _TERMS) and _masked(first[0][1]) == _masked(assigned.value):
                text = ast.unparse(_renamed(copy_tree(value), once, assigned.targets[0].id))
                if len(text) <= 80:
                    yield "per_item", f"({text})", ""
                break


_GRID_AXES = {"height": "width", "width": "height", "h": "w", "w": "h", "rows": "cols", "cols": "rows",
              "H": "W", "W": "H", "n_rows": "n_cols", "n_cols": "n_rows"}


def _grid_axis_changes(node):
    """A coordinate grid made along the other axis: `np.arange(height)[:, None]` (each row's index)
    where `np.arange(width)[None, :]` (each column's) belongs, or the other way round."""
    if not (isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2):
        return
    first, second = node.slice.elts
    none = lambda item: isinstance(item, ast.Constant) and item.value is None  # noqa: E731
    whole = lambda item: isinstance(item, ast.Slice) and item.lower is item.upper is item.step is None  # noqa: E731
    if not ((whole(first) and none(second)) or (none(first) and whole(second))):
        return
    sizes = [n for n in walk(node.value) if isinstance(n, ast.Name) and n.id in _GRID_AXES]
    if len(sizes) != 1:
        return
    other = _renamed(node.value, sizes[0].id, _GRID_AXES[sizes[0].id])
    flipped = ast.Subscript(other, ast.Tuple([copy_tree(second), copy_tree(first)], ast.Load()), ast.Load())
    yield "grid_axis", ast.unparse(flipped), ""


def _mirror_changes(node, words):
    """A line copied from its twin's with one name left as it was: `grey2 = cvtColor(img1) if img2.ndim
    == 3 else img2` under `grey1 = cvtColor(img1) if img1.ndim == 3 else img1`. The twin's line with
    its names turned the other way (each name with a `1` read as its `2`, as the targets differ) is
    written at every place of this one but one: that place, as the twin's line has it."""
    mine, theirs = ast.unparse(node.targets[0]), None
    if not hasattr(words, "names_anywhere"):   # (read once per def)
        words.names_anywhere = {n.id for n in walk(words.fn) if isinstance(n, ast.Name)}
    names = words.names_anywhere
    for twin in _twin_assignments(node, words):
        other = ast.unparse(twin.targets[0])
        if len(other) != len(mine):
            continue
        apart = [(a, b) for a, b in zip(other, mine) if a != b]
        if len(apart) != 1:
            continue
        old, new = apart[0]
        turned = copy_tree(twin.value)
        for inner in walk(turned):   # (a name with the twin's letter that has a partner in the def)
            if isinstance(inner, ast.Name) and old in inner.id and inner.id.replace(old, new) in names:
                inner.id = inner.id.replace(old, new)
        pair = _one_difference(node.value, turned)
        if pair is None or pair[0] is node.value or ast.dump(turned) == ast.dump(twin.value):
            continue   # (alike, or alike nowhere: no line copied from the other)
        whole = copy_tree(node.value)
        for before, after in zip(walk(node.value), walk(whole)):
            if before is pair[0]:
                whole = _swap_in(whole, after, copy_tree(pair[1]))
                break
        theirs = ast.unparse(whole)
        if len(theirs) <= 200:
            yield "mirror", (None, theirs), ""


def _summed_terms(node) -> list | None:
    """The terms of a sum ``a + b - c`` as ``[("+", a), ("+", b), ("-", c)]``; None when ``node`` is none."""
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub))):
        return None
    terms = []
    def walk(part, sign):
        if isinstance(part, ast.BinOp) and isinstance(part.op, (ast.Add, ast.Sub)):
            walk(part.left, sign)
            walk(part.right, sign if isinstance(part.op, ast.Add) else ("-" if sign == "+" else "+"))
        else:
            terms.append((sign, part))
    walk(node, "+")
    return terms


def _rows_read(terms) -> set:
    """The (matrix, row) of every constant-row subscript the terms read (`P[1, 3]`: ("P", 1))."""
    return {_row_index(n) for _, term in terms for n in walk(term) if _row_index(n)}


def _term_its_siblings_have(node, words):
    """A term the sibling rows' sums all have, missing from this one: `v = P[1, 0] * X + P[1, 1] * Y + P[1, 2] *
    Z` beside `u = ... + P[0, 3]` and `w = ... + P[2, 3]` (the translation's entry of v's row left out):
    the sum with the siblings' extra term, read in this row."""
    if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)):
        return
    divided = isinstance(node.value, ast.BinOp) and isinstance(node.value.op, ast.Div)
    summed = node.value.left if divided else node.value   # (`(K[1, 1] * Y + K[1, 2]) / Z`: the sum divided)
    mine = _summed_terms(summed)
    rows = _rows_read(mine) if mine else set()
    if not mine or len(rows) != 1:
        return
    (matrix, row), = rows
    texts = [(sign, ast.unparse(term)) for sign, term in mine]
    constants = [term for _, term in mine if isinstance(term, ast.Constant)]
    extras, in_place, factored = set(), set(), set()
    for sibling in _read_siblings(words)[2]:
        value = sibling.value.left if isinstance(sibling.value, ast.BinOp) and isinstance(sibling.value.op, ast.Div) \
            else sibling.value   # (`(H[0, 0] * x + ... + H[0, 2]) / w`: the sum divided)
        theirs = _summed_terms(value) if sibling is not node else None
        their_rows = _rows_read(theirs) if theirs else set()
        if not theirs or len(theirs) not in (len(mine), len(mine) + 1) or len(their_rows) != 1 \
                or next(iter(their_rows))[0] != matrix:
            continue
        other = next(iter(their_rows))[1]
        moved = []
        for sign, term in theirs:
            term = copy_tree(term)
            for n in walk(term):
                if _row_index(n) == (matrix, other):
                    first = n.slice.elts[0] if isinstance(n.slice, ast.Tuple) else None
                    if first is not None:
                        first.value = row
                    else:
                        n.slice = ast.Constant(row)
            moved.append((sign, ast.unparse(term)))
        missing = [item for item in moved if item not in texts]
        if len(theirs) == len(mine) + 1 and len(missing) == 1 and all(item in moved for item in texts):
            extras.add(missing[0])
        elif len(theirs) == len(mine) and len(missing) == 1 and len(constants) == 1 \
                and [item for item in texts if item not in moved] == [(s, ast.unparse(constants[0])) for s, t in mine
                                                                      if t is constants[0]]:
            in_place.add(missing[0])   # (a number written where the siblings read their row's entry: `+ 1.0`)
        # (a term the sibling's sum has times a factor, bare in this one: `+ K[1, 2]` beside `+ K[0, 2] * Z`)
        unmatched = [(sign, term) for sign, term in mine if (sign, ast.unparse(term)) not in moved]
        if len(unmatched) == 1:
            sign, term = unmatched[0]
            times = [text for their_sign, text in moved if their_sign == sign and _times_a_factor(text, term)]
            if len(times) == 1:
                factored.add((ast.unparse(term), times[0]))
    if len(extras) == 1:
        sign, term = extras.pop()
        grown = f"{ast.unparse(summed)} {sign} {term}"
        yield "mirror", (None, f"({grown}) / {ast.unparse(node.value.right)}" if divided else grown), ""
    if len(factored) == 1:
        bare, times = factored.pop()
        value = copy_tree(node.value)
        for n in walk(value):   # (the bare term, found again in the copy)
            for field in ("left", "right"):
                part = getattr(n, field, None)
                if isinstance(part, ast.AST) and ast.unparse(part) == bare:
                    setattr(n, field, parse(times, mode="eval").body)
        yield "mirror", (None, ast.unparse(value)), ""
    if len(in_place) == 1:
        sign, term = in_place.pop()
        value = copy_tree(node.value)
        for n in walk(value):   # (the one constant term of the sum, found again in the copy)
            for field in ("left", "right"):
                part = getattr(n, field, None)
                if isinstance(part, ast.Constant) and ast.unparse(part) == ast.unparse(constants[0]):
                    setattr(n, field, parse(term, mode="eval").body)
                    if sign == "-" and isinstance(n, ast.BinOp) and field == "right" and isinstance(n.op, ast.Add):
                        n.op = ast.Sub()
        yield "mirror", (None, ast.unparse(value)), ""


def _times_a_factor(text: str, term) -> bool:
    """Whether ``text`` is ``term`` times something (either side of one product)."""
    product = parse(text, mode="eval").body
    bare = ast.dump(term)
    return isinstance(product, ast.BinOp) and isinstance(product.op, ast.Mult) \
        and bare in (ast.dump(product.left), ast.dump(product.right))


def _row_index(node):
    """(matrix name, row) of a subscript `M[k]` or `M[k, ...]` with a constant row k; None otherwise."""
    if not (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name)):
        return None
    first = node.slice.elts[0] if isinstance(node.slice, ast.Tuple) and node.slice.elts else node.slice
    if isinstance(first, ast.Constant) and type(first.value) is int:
        return node.value.id, first.value
    return None


def _row_products(words) -> dict:
    """Matrix name -> (the other factor's code, whether it is on the left) of the def's assignments whose
    value is a whole row of it times something (`u = Xh @ P[0]`), read once per def."""
    if not hasattr(words, "row_products"):
        found = {}
        for statement in walk(words.fn):
            value = statement.value if isinstance(statement, ast.Assign) and len(statement.targets) == 1 else None
            if isinstance(value, ast.BinOp) and isinstance(value.op, ast.MatMult):
                for row, other, left in ((value.right, value.left, True), (value.left, value.right, False)):
                    if isinstance(row, ast.Subscript) and not isinstance(row.slice, ast.Tuple) and _row_index(row):
                        found.setdefault(_row_index(row)[0], (ast.unparse(other), left))
        words.row_products = found
    return words.row_products


def _row_like_its_siblings(node, words):
    """A row of a matrix used otherwise than its sibling rows are: `w = pts @ P[2, :3]` under `u = Xh @ P[0]`
    and `v = Xh @ P[1]` (the depth without P's last column): the line written as they are, `Xh @ P[2]`."""
    if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)):
        return
    products = _row_products(words)
    if not products:
        return
    value = node.value
    rows = [_row_index(n) for n in walk(value) if _row_index(n)]
    if not rows or len({matrix for matrix, _ in rows}) != 1 or rows[0][0] not in products:
        return
    matrix, row = rows[0]
    other, left = products[matrix]
    written = f"{other} @ {matrix}[{row}]" if left else f"{matrix}[{row}] @ {other}"
    if ast.unparse(value) != written and ast.dump(_parse(written).body[0].value) != ast.dump(value):
        yield "mirror", (None, written), ""


def _derived_values(words) -> dict:
    """Name -> [(derived name, its value's code with the name read as "{}")] for the def's assignments
    `b = <arithmetic reading a>` (`yn = Y / Z`), read once per def."""
    if not hasattr(words, "derived_values"):
        derived = {}
        for statement in walk(words.fn):
            if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1
                    and isinstance(statement.targets[0], ast.Name) and isinstance(statement.value, ast.BinOp)):
                continue
            target = statement.targets[0].id
            read = {n.id for n in walk(statement.value) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
            for name in read - {target}:
                form = copy_tree(statement.value)
                for inner in walk(form):
                    if isinstance(inner, ast.Name) and inner.id == name:
                        inner.id = "_raw_"
                derived.setdefault(name, []).append((target, ast.dump(form), statement.lineno))
        words.derived_values = derived
    return words.derived_values


def _raw_beside_derived(node, words):
    """A raw value read where its derived form belongs, beside a sibling read in that form: `K[0, 1] * Y`
    in `u = K[0, 0] * xn + K[0, 1] * Y + K[0, 2]` with `xn = X / Z` and `yn = Y / Z` above (the skew term
    of the unnormalised y): `Y` -> `yn`."""
    if not (isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)):
        return
    derived = _derived_values(words)
    mine = [(name, form) for name, form, line in derived.get(node.id, ()) if line < getattr(node, "lineno", 0)]
    if not mine:
        return
    statement = node
    while _parent_of(statement, words) is not None and not isinstance(statement, ast.stmt):
        statement = _parent_of(statement, words)
    beside = {n.id for n in walk(statement) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
    forms_beside = {form for raw, made in derived.items() if raw != node.id
                    for name, form, _ in made if name in beside}
    for name, form in mine:
        if form in forms_beside and name != node.id:
            yield "derived_name", name, ""
            return


def _started_with_an_item(node, words):
    """A list started with an item where a loop then appends to it (`views = [project(X, fs[0])]`, then `for f in fs:
    views.append(project(X, f))`: the first item twice; `rows = [white]` then a row per bit: a row too many). Offered:
    the list started empty."""
    if not (isinstance(node, ast.List) and node.elts):
        return
    parent = _parent_of(node, words)
    if not (isinstance(parent, ast.Assign) and parent.value is node and len(parent.targets) == 1
            and isinstance(parent.targets[0], ast.Name)):
        return
    if not hasattr(words, "appended_in_loops"):   # (read once per def: (loop's line, list appended to))
        words.appended_in_loops = {(loop.lineno, c.func.value.id)
                                   for loop in walk(words.fn) if isinstance(loop, (ast.For, ast.While))
                                   for statement in loop.body for c in walk(statement)
                                   if isinstance(c, ast.Call) and isinstance(c.func, ast.Attribute)
                                   and c.func.attr in ("append", "extend") and isinstance(c.func.value, ast.Name) and c.args}
    name = parent.targets[0].id
    if any(line > parent.lineno and name == appended for line, appended in words.appended_in_loops):
        yield "initial", "[]", ""


def _out_buffer_changes(node, words):
    """A ufunc's output buffer made as a copy of its data (`depth = d.copy()` for `np.divide(fb, d,
    out=depth, where=ok)`): where the mask is false the buffer keeps the data, where 0 belongs."""
    copied = isinstance(node, ast.Call) and (
        (isinstance(node.func, ast.Attribute) and node.func.attr in ("copy", "astype"))
        or _dotted(node.func) in ("np.copy", "np.array", "np.asarray", "numpy.copy", "numpy.array"))
    if not copied:
        return
    if not hasattr(words, "masked_outputs"):   # (read once per def: the names given as out= beside a where=)
        words.masked_outputs = {k.value.id for c in walk(words.fn) if isinstance(c, ast.Call)
                                and any(k.arg == "where" for k in c.keywords)
                                for k in c.keywords if k.arg == "out" and isinstance(k.value, ast.Name)}
        words.allocated_into = getattr(words, "allocated_into", None) or {
            id(a.value): a.targets[0].id for a in walk(words.fn) if isinstance(a, ast.Assign)
            and len(a.targets) == 1 and isinstance(a.targets[0], ast.Name)}
    if words.allocated_into.get(id(node)) in words.masked_outputs:
        data = node.func.value if isinstance(node.func, ast.Attribute) else node.args[0] if node.args else None
        if data is not None:
            yield "initial", f"np.zeros_like({ast.unparse(data)}, dtype=np.float64)", ""


def _initial_changes(node, words):
    """A running best started at 0 where nothing may beat it (`best = np.zeros(shape)` kept only where
    `cost < best`: no cost is below 0): started at +inf (or -inf, for a running largest)."""
    if not (isinstance(node, ast.Call) and node.args and _dotted(node.func) in ("np.zeros", "np.zeros_like")):
        return
    if not hasattr(words, "compared_names"):   # (read once per def: the names a comparison reads)
        words.compared_names = {n.id for c in walk(words.fn) if isinstance(c, ast.Compare)
                                and any(isinstance(op, (ast.Lt, ast.LtE, ast.Gt, ast.GtE)) for op in c.ops)
                                for side in [c.left, *c.comparators] for n in walk(side) if isinstance(n, ast.Name)}
        words.allocated_into = {id(a.value): a.targets[0].id for a in walk(words.fn) if isinstance(a, ast.Assign)
                                and len(a.targets) == 1 and isinstance(a.targets[0], ast.Name)}
    if words.allocated_into.get(id(node)) not in words.compared_names:
        return
    full = "np.full" if _dotted(node.func) == "np.zeros" else "np.full_like"
    first = ast.unparse(node.args[0])
    for start in ("np.inf", "-np.inf"):
        yield "initial", f"{full}({first}, {start})", ""


def _layout_and_type_changes(node):
    """Slips of layout, type and order: an array reshaped to (k, -1) and transposed where (-1, k) belongs
    (`lines.reshape(3, -1).T`: the entries read across the points), an integer type where the API's
    values are floats (`argmin(...).astype(np.uint8)`, `np.reciprocal` of integers: 1 // d), a floor
    division done before the product it should follow (`c // w * 2 ** n`: 0 for every c < w), positions
    counted from 1 (`np.arange(1, w + 1)`, `np.mgrid[1:n + 1]`), a conversion between colour orders that
    does not belong (`cv2.cvtColor(img, cv2.COLOR_BGR2RGB)` on a BGR image), and a grey conversion made
    whatever the image is (`cv2.COLOR_BGR2GRAY` of a grey frame the API allows)."""
    if isinstance(node, ast.Attribute) and node.attr == "T" and isinstance(node.value, ast.Call) \
            and isinstance(node.value.func, ast.Attribute) and node.value.func.attr == "reshape" \
            and len(node.value.args) == 2 and not node.value.keywords:
        first, second = node.value.args
        if isinstance(second, ast.UnaryOp) and isinstance(second.op, ast.USub) \
                and isinstance(second.operand, ast.Constant) and second.operand.value == 1:
            array = ast.unparse(node.value.func.value)
            yield "reshape_back", f"{array}.reshape(-1, {ast.unparse(first)})", ""
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "astype" \
            and len(node.args) == 1 and (_dotted(node.args[0]) in _INTEGER_TYPES | {"int", "np.int_"}):
        yield "astype_float", f"{_operand(node.func.value)}.astype(np.float64)", ""
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div)) and isinstance(node.left, ast.BinOp) \
            and isinstance(node.left.op, ast.FloorDiv):
        a, b, c = (ast.unparse(x) for x in (node.left.left, node.left.right, node.right))
        op = "*" if isinstance(node.op, ast.Mult) else "/"
        yield "divide_last", f"({a}) {op} ({c}) // ({b})", ""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.arange", "range", "numpy.arange") and len(node.args) == 2 \
            and isinstance(node.args[0], ast.Constant) and node.args[0].value == 1 and isinstance(node.args[1], ast.BinOp) \
            and isinstance(node.args[1].op, ast.Add) and isinstance(node.args[1].right, ast.Constant) \
            and node.args[1].right.value == 1:
        # positions counted from 1 (`np.arange(1, width + 1)`) where they are indices, from 0
        counted = ast.Call(copy_tree(node.func), [copy_tree(node.args[1].left)], copy_tree(node.keywords))
        yield "zero_based", ast.unparse(counted), ""
    if isinstance(node, ast.Call) and _dotted(node.func) == "enumerate" and node.args \
            and (len(node.args) == 2 or any(k.arg == "start" for k in node.keywords)):
        # items numbered from another start (`enumerate(frames, start=1)`) where their index belongs, from 0
        counted = ast.Call(copy_tree(node.func), [copy_tree(node.args[0])],
                           [copy_tree(k) for k in node.keywords if k.arg != "start"])
        yield "zero_based", ast.unparse(counted), ""
    if isinstance(node, ast.Subscript) and _dotted(node.value) in ("np.mgrid", "np.ogrid", "numpy.mgrid", "numpy.ogrid"):
        counted = copy_tree(node)   # np.mgrid[1:cols + 1, 1:rows + 1] -> np.mgrid[0:cols, 0:rows]
        changed = False
        for part in walk(counted.slice):
            if isinstance(part, ast.Slice) and isinstance(part.lower, ast.Constant) and part.lower.value == 1 \
                    and isinstance(part.upper, ast.BinOp) and isinstance(part.upper.op, ast.Add) \
                    and isinstance(part.upper.right, ast.Constant) and part.upper.right.value == 1:
                part.lower, part.upper, changed = ast.Constant(0), part.upper.left, True
        if changed:
            yield "zero_based", ast.unparse(counted), ""
    if isinstance(node, ast.Call) and len(node.args) == 1 and _dotted(node.func) in ("np.reciprocal", "numpy.reciprocal"):
        # (integers given: np.reciprocal of an int array is integer division, 1 // d)
        yield "astype_float", f"{_dotted(node.func)}(np.asarray({ast.unparse(node.args[0])}, dtype=np.float64))", ""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("cv2.cvtColor", "cv.cvtColor") and len(node.args) >= 2:
        flag = _dotted(node.args[1]).rsplit(".", 1)[-1]
        image = ast.unparse(node.args[0])
        if flag in ("COLOR_BGR2RGB", "COLOR_RGB2BGR"):
            yield "drop_colour", image, ""
        # a conversion made whatever the image is: a grey image the API allows given to BGR2GRAY raises
        for kind, channels in (("2GRAY", 3), ("GRAY2", 2)):
            if kind in flag and isinstance(node.args[0], (ast.Name, ast.Subscript, ast.Attribute)):
                yield "convert_if", f"({ast.unparse(node)} if {image}.ndim == {channels} else {image})", ""


def _parent_of(node, words):
    """``node``'s parent in the def ``words`` reads (kept per def)."""
    if not hasattr(words, "parents"):
        words.parents = {id(child): parent for parent in walk(words.fn) for child in ast.iter_child_nodes(parent)}
    return words.parents.get(id(node))


def _unused_parameter_changes(node, parent, words):
    """A parameter the def never reads, where an operand of a sum, difference or product is computed
    otherwise: that operand is likely where it belongs (`d - X[:, 2].mean()` with `z0` unread)."""
    if not hasattr(words, "unread"):
        read = {n.id for n in walk(words.fn) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
        args = words.fn.args
        words.unread = [a.arg for a in args.args + args.kwonlyargs if a.arg not in read and a.arg not in ("self", "_")]
    if not words.unread or not (isinstance(parent, ast.BinOp) and isinstance(parent.op, (ast.Add, ast.Sub, ast.Mult, ast.Div))):
        return
    if not isinstance(node, (ast.Name, ast.Subscript, ast.Call, ast.Attribute)) or isinstance(node, ast.Constant):
        return
    for name in words.unread[:2]:
        yield "unused", name, ""


def _masked(node) -> str:
    """``node``'s code with every name, item and attribute read masked: how it is written, not what
    it reads (`F @ np.array([pts[0, 0], pts[0, 1], 1.0])` and `F @ np.array([x, y, 1.0])` alike)."""
    class Mask(ast.NodeTransformer):
        def visit_Call(self, call):   # (the function called stays: np.array is not np.zeros)
            call.args = [self.visit(a) for a in call.args]
            call.keywords = [self.visit(k) for k in call.keywords]
            return call

        def generic_visit(self, inner):
            if isinstance(inner, _TERMS):
                return ast.Name("_", ast.Load())
            return super().generic_visit(inner)

    return ast.dump(Mask().visit(copy_tree(node)))


def _canvas_changes(node, words):
    """A canvas sized by one image where both belong: `np.zeros((h1, w1 + w2, 3))` with `max(h1, h2)`
    rows, or `w1` columns where `w1 + w2` belong (the names' twins: `h1`/`h2`, `w_a`/`w_b`)."""
    if not hasattr(words, "canvas_sizes"):   # (read once per def: the sizes of allocated shapes)
        words.canvas_sizes = {id(size) for call in walk(words.fn) if isinstance(call, ast.Call) and call.args
                              and isinstance(call.args[0], ast.Tuple)
                              and _dotted(call.func).rsplit(".", 1)[-1] in _ALLOCATED
                              for size in call.args[0].elts}
        words.names_read = sorted({n.id for n in walk(words.fn) if isinstance(n, ast.Name)})
    if id(node) not in words.canvas_sizes:
        return
    if not isinstance(node, ast.Name):
        # a size made from both images' in another way (`2 * max(w1, w2)` where `w1 + w2` belongs)
        called = {id(n.func) for n in walk(node) if isinstance(n, ast.Call)}
        read = list(dict.fromkeys(n.id for n in walk(node) if isinstance(n, ast.Name) and id(n) not in called))
        if len(read) == 2 and _twins(ast.Name(read[0]), ast.Name(read[1])):
            for text in (f"{read[0]} + {read[1]}", f"max({read[0]}, {read[1]})"):
                if ast.dump(_parse(text).body[0].value) != ast.dump(node):
                    yield "canvas", text, ""
        return
    for twin in words.names_read:   # (the same quantity of the other image: h1/h2, not h1/w1)
        if twin[:1] == node.id[:1] and _twins(ast.Name(twin), ast.Name(node.id)):
            yield "canvas", f"max({node.id}, {twin})", ""
            yield "canvas", f"{node.id} + {twin}", ""


def _leading_term(value):
    """The first term of a sum or difference (``a`` of ``a + b - c``)."""
    while isinstance(value, ast.BinOp) and isinstance(value.op, (ast.Add, ast.Sub)):
        value = value.left
    return value


def _norm_call(node) -> str:
    """The dotted name of a norm taken (`np.linalg.norm`), or ""."""
    if isinstance(node, ast.Call) and _dotted(node.func).rsplit(".", 1)[-1] == "norm":
        return _dotted(node.func)
    return ""


def _unit_vectors(words) -> dict:
    """Names the def divides by their own norm (`e1 = c / np.linalg.norm(c)`, `n /= norm(n)`) -> that
    norm's function, read once per def."""
    if not hasattr(words, "unit_vectors"):
        units = {}
        for statement in walk(words.fn):
            if isinstance(statement, ast.Assign) and len(statement.targets) == 1 \
                    and isinstance(statement.targets[0], ast.Name) and isinstance(statement.value, ast.BinOp) \
                    and isinstance(statement.value.op, ast.Div) and _norm_call(statement.value.right):
                units[statement.targets[0].id] = _norm_call(statement.value.right)
            elif isinstance(statement, ast.AugAssign) and isinstance(statement.op, ast.Div) \
                    and isinstance(statement.target, ast.Name) and _norm_call(statement.value):
                units[statement.target.id] = _norm_call(statement.value)
        words.unit_vectors = units
    return words.unit_vectors


def _twin_unit_changes(node, words):
    """A vector left at its length where its twin is made a unit vector: `e2 = np.cross(axis, e1)` beside
    `e1 = c / np.linalg.norm(c)` (a cross product of unit vectors not at right angles is shorter than 1,
    and a rotation built of the two is none): the twin's division by its norm done to it too."""
    if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)):
        return
    name, units = node.targets[0].id, _unit_vectors(words)
    if name in units or any(_norm_call(n) for n in walk(node.value)):
        return
    norms = [units[other] for other in units if twin_names(name, other)]
    if not norms:
        return
    value = ast.unparse(node.value)
    value = f"({value})" if isinstance(node.value, (ast.BinOp, ast.BoolOp, ast.IfExp, ast.Compare)) else value
    text = f"{value} / {norms[0]}({value})"
    if len(text) <= 100:
        yield "twin_step", (None, text), ""


def _as_its_twin_line(node, words):
    """A twin's line written alike but for its names and one part: `std_r = sqrt(mean(s * s) - mean_r)`
    beside `std_l = sqrt(mean(l * l) - mean_l ** 2)` -- the part written as the twin writes it, in this
    line's names (`mean_r ** 2`): a formula misremembered in one of two lines copied from each other."""
    if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)):
        return
    for twin in _twin_assignments(node, words):
        if not isinstance(twin.targets[0], ast.Name):
            continue
        renames: dict = {}
        pair = _one_difference_but_names(node.value, twin.value, renames)
        if not isinstance(pair, tuple) or any(len(set(mine)) > 1 for mine in _inverted(renames).values()):
            continue
        mine, theirs = pair
        if mine is node.value or isinstance(theirs, (*_TERMS, ast.Constant)):
            continue   # (a whole value, or a step taken out: the twin's step tried on a bare term is twin_step's)
        # (the twin's names read in this line's terms: those aligned elsewhere in the two lines, else the
        # twin's name with this line's target's difference -- `mean_l` -> `mean_r` beside `std_l`, `std_r`)
        here, there = node.targets[0].id, twin.targets[0].id
        part = copy_tree(theirs)
        for name in walk(part):
            if isinstance(name, ast.Name):
                if name.id in renames:
                    name.id = renames[name.id]
                else:
                    renamed = _renamed_as(name.id, there, here)
                    if renamed is not None and renamed in words.definitions:
                        name.id = renamed
        whole = copy_tree(node.value)
        for old, new in zip(walk(node.value), walk(whole)):
            if old is mine:
                whole = _swap_in(whole, new, part) if new is not whole else part
                break
        text = ast.unparse(whole)
        if text != ast.unparse(node.value) and len(text) <= 160:
            yield "twin_step", (None, text), ""


def _own_name(statement) -> str | None:
    """The name a statement works on: `gM` of `gM.append(f(gM[-1]))`, `x` of `x = f(x, ...)`."""
    if isinstance(statement, ast.Expr) and isinstance(statement.value, ast.Call) \
            and isinstance(statement.value.func, ast.Attribute) and isinstance(statement.value.func.value, ast.Name):
        name = statement.value.func.value.id
        reads = [n for a in statement.value.args for n in walk(a)]
    elif isinstance(statement, ast.Assign) and len(statement.targets) == 1 and isinstance(statement.targets[0], ast.Name):
        name, reads = statement.targets[0].id, list(walk(statement.value))
    else:
        return None
    return name if any(isinstance(n, ast.Name) and n.id == name for n in reads) else None


def _like_its_siblings(node, words):
    """A statement unlike its siblings in a block where they are alike but for their own names: the mask's pyramid
    `gM.append(cv2.resize(gM[-1], size, interpolation=cv2.INTER_NEAREST))` beside `gA.append(cv2.pyrDown(gA[-1]))`
    and `gB.append(cv2.pyrDown(gB[-1]))` -- the statement written as the two others are, in its own name."""
    statement = _parent_of(node, words)
    if not (isinstance(statement, (ast.Expr, ast.Assign)) and statement.value is node):
        return
    own = _own_name(statement)
    block = _parent_of(statement, words)
    siblings = next((getattr(block, field) for field in ("body", "orelse")
                     if any(s is statement for s in getattr(block, field, []))), [])
    if own is None or len(siblings) > _SIBLINGS_READ:
        return
    alike, example = Counter(), {}
    for sibling in siblings:
        name = _own_name(sibling) if sibling is not statement else None
        if name is not None and name != own and type(sibling) is type(statement):
            form = ast.dump(_renamed(sibling, name, own))
            alike[form] += 1
            example[form] = sibling, name
    mine = ast.dump(statement)
    for form, count in alike.items():
        if count >= 2 and form != mine:
            sibling, name = example[form]
            yield "sibling_line", ast.unparse(_renamed(sibling.value, name, own)), ""


_SIBLINGS_READ = 12   # statements of a block compared with each other (a longer block's lines are no siblings)


def _inverted(mapping: dict) -> dict:
    out: dict = {}
    for key, value in mapping.items():
        out.setdefault(value, []).append(key)
    return out


def _renamed_as(name: str, there: str, here: str) -> str | None:
    """``name`` with the part in which ``there`` differs from ``here`` changed as it is (`mean_l` for `std_l`
    -> `std_r`: `mean_r`); None where ``name`` does not end or start alike."""
    head = len(os.path.commonprefix([there, here]))
    tail = len(os.path.commonprefix([there[head:][::-1], here[head:][::-1]]))
    old, new = there[head:len(there) - tail], here[head:len(here) - tail]
    if not old:
        return None
    suffix = there[len(there) - tail:] if tail else ""
    if name.endswith(old + suffix) and there.endswith(old + suffix):
        return name[:len(name) - len(old + suffix)] + new + suffix
    prefix = there[:head]
    if name.startswith(old) and not prefix:
        return new + name[len(old):]
    return None


def _one_difference_but_names(a, b, renames: dict):
    """``(a's part, b's part)`` where two expressions differ at one place besides names read in each
    other's place (gathered in ``renames``, b's name -> a's); "same" when only names differ; None when
    they differ at more places or a name stands for two."""
    if ast.dump(a) == ast.dump(b):
        return "same"
    if isinstance(a, ast.Name) and isinstance(b, ast.Name):
        if renames.setdefault(b.id, a.id) != a.id:
            return None
        return "same"
    if type(a) is not type(b) or isinstance(a, (ast.Name, ast.Constant)):
        return a, b
    found = "same"
    for (field, x), (_, y) in zip(ast.iter_fields(a), ast.iter_fields(b)):
        xs, ys = (x, y) if isinstance(x, list) else ([x], [y])
        if not isinstance(ys, list) or len(xs) != len(ys):
            return (a, b) if found == "same" else None
        for p, q in zip(xs, ys):
            if isinstance(p, ast.AST) and isinstance(q, ast.AST):
                inner = _one_difference_but_names(p, q, renames)
                if inner is None:
                    return None
                if inner != "same":
                    if found != "same":
                        return None
                    found = inner
            elif p != q:
                if found != "same":
                    return None
                found = (a, b)
    return found


def _twin_assignments(node, words):
    """The def's assignments to ``node``'s target's twin (`u = ...` for `v = ...`, `out[i, 0] = ...`
    for `out[i, 1] = ...`)."""
    return [other for other in _read_siblings(words)[2]
            if other is not node and (_twins(other.targets[0], node.targets[0])
                                      or _index_twins(other.targets[0], node.targets[0]))][:2]


def _read_siblings(words):
    """The def's assignments (dumped) and its calls by (function, arity), read once per def (kept
    on ``words``): comparing every node with every other would grow with the square of the code."""
    if not hasattr(words, "siblings"):
        done, calls, named = set(), {}, []
        for statement in walk(words.fn):
            if isinstance(statement, ast.Assign):
                done.add(ast.dump(statement))
                if len(statement.targets) == 1 and isinstance(statement.targets[0], _TERMS) and len(named) < 64:
                    named.append(statement)
            elif isinstance(statement, ast.Call):
                kept = calls.setdefault((_dotted(statement.func), len(statement.args)), [])
                if len(kept) < _SIBLING_CALLS:
                    kept.append(statement)
        words.siblings = (done, calls, named)
    return words.siblings


def _renamed(node, old: str, new: str):
    """A copy of ``node`` with every name ``old`` read or written as ``new``."""
    copied = copy_tree(node)
    for inner in walk(copied):
        if isinstance(inner, ast.Name) and inner.id == old:
            inner.id = new
    return copied


def _item_swaps(node, parent):
    """Two entries of a tuple or list written in each other's place: a size given as (rows, cols), a
    matrix row's entries, the images paired with their homographies, a pixel indexed [x, y], the
    names assigned `w, h = image.shape[:2]`. Every pair of a short sequence, neighbours of a longer
    one (up to nine entries); never a stacking call's pieces (``stack_order`` exchanges those)."""
    items = node.elts
    if not 2 <= len(items) <= 9 or any(isinstance(item, ast.Starred) for item in items) \
            or (isinstance(parent, ast.Call) and node in parent.args
                and (_dotted(parent.func).rsplit(".", 1)[-1] in _STACKING
                     or _dotted(parent.func) == "cv2.merge" and len(items) == 3)):
        return
    pairs = itertools.combinations(range(len(items)), 2) if len(items) <= 4 else \
        ((i, i + 1) for i in range(len(items) - 1))
    for i, j in pairs:
        if ast.dump(items[i]) != ast.dump(items[j]):
            yield "swap_items", (i, j), ""
    # (and the results a function returns in another order than they are asked in, one moved past
    # others: `return rms, K, dist` -- cv2.calibrateCamera's order -- where `K, dist, rms` is asked)
    if isinstance(parent, ast.Return) and 3 <= len(items) <= 4:
        for i, j in itertools.permutations(range(len(items)), 2):
            if abs(i - j) > 1:
                order = list(range(len(items)))
                order.insert(j, order.pop(i))
                yield "swap_items", ("moved", tuple(order)), ""
    # (and one coordinate of two points exchanged between them: a line's end points each given the other's
    # row, `(x_top, h - 1), (x_bottom, 0)` for `(x_top, 0), (x_bottom, h - 1)`)
    points = [item for item in items if isinstance(item, (ast.Tuple, ast.List))]
    if len(points) == len(items) <= 4 and len({len(p.elts) for p in points}) == 1 and 2 <= len(points[0].elts) <= 3:
        for i, j in itertools.combinations(range(len(items)), 2):
            for k in range(len(points[0].elts)):
                a, b = points[i].elts[k], points[j].elts[k]
                if ast.dump(a) != ast.dump(b) and ast.dump(points[i]) != ast.dump(points[j]) \
                        and not (isinstance(_bare(a), ast.Constant) and isinstance(_bare(b), ast.Constant)):
                    # (two numbers written out exchanged between rows is a matrix's own structure, which the
                    # items' own exchanges reach; the values a student computes are what get crossed)
                    yield "cross_items", (i, j, k), ""


def _column_taken(node) -> bool:
    """``X[:, k]``: one column of an array, every row of it."""
    index = node.slice
    return isinstance(index, ast.Tuple) and len(index.elts) == 2 and isinstance(index.elts[0], ast.Slice) \
        and index.elts[0].lower is None and index.elts[0].upper is None and index.elts[0].step is None \
        and _constant_index(index.elts[1]) is not None


def _constant_index(node):
    """The int an index node holds (``-1`` written ``-1``), else None."""
    if isinstance(node, ast.Constant) and isinstance(node.value, int) and not isinstance(node.value, bool):
        return node.value
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and isinstance(node.operand, ast.Constant) \
            and isinstance(node.operand.value, int) and not isinstance(node.operand.value, bool):
        return -node.operand.value
    return None


def _axis_name(position: int, count: int) -> str:
    """A position of an index told as what it picks: a row or a column of a matrix (of each
    matrix of a stack, for three indices)."""
    if count <= 2:
        return ("row", "column")[position]
    return {1: "row", 2: "column"}.get(position, f"axis-{position} slice")


def _index_changes(node: ast.Subscript, what):
    """An index on another axis (``Vt[-1]`` for ``Vt[:, -1]``, a batched SVD's ``Vt[:, :, -1]`` for
    ``Vt[:, -1]``, ``a[:, 0]`` for ``a[0]``) and a copy-paste slice (``p[:, 0:1]`` where ``p[:, 1:2]``
    belongs: the x coordinates for the y)."""
    elements = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
    if len(elements) > 3 or isinstance(node.ctx, ast.Store):
        return
    inner = what(node.value)
    if not inner:
        return
    # The axis moves only on an array the code names or an SVD's factor (a tuple's item, a list's, a
    # 1-D result of np.lexsort indexed on another axis raises everywhere: no one's slip).
    named = isinstance(node.value, ast.Name) or (
        isinstance(node.value, ast.Subscript) and isinstance(node.value.value, ast.Call)
        and _dotted(node.value.value.func).endswith("linalg.svd"))
    constants = [(i, _constant_index(e)) for i, e in enumerate(elements) if _constant_index(e) is not None] \
        if named else []
    wholes = [i for i, e in enumerate(elements) if _whole_slice(e)]
    if len(constants) == 1 and len(constants) + len(wholes) == len(elements) and constants[0][1] in _INDEX_WORDS:
        (position, value), count = constants[0], len(elements)
        targets = [q for q in range(count) if q != position and (count < 3 or q > 0)]
        if count == 2 and position == 1 and ("SVD" in inner or "singular" in inner):
            targets.append(2)   # a batched SVD's stack of matrices: the column of each where its row belongs
        if count == 1:
            targets = [1]
        word = _INDEX_WORDS[value]
        for target in targets:
            size = max(count, target + 1)
            spec = [":"] * size
            spec[target] = value
            was = _axis_name(position, count) if count > 1 else "row"
            now = _axis_name(target, size)
            if count == 1:
                said = f"the {word} column of {inner} is used where its {word} row belongs"
            elif size == 3 and target > 0 and position > 0:   # a stack of matrices, indexed in each
                said = f"the {word} {now} of each matrix of {inner} is used where its {word} " \
                       f"{_axis_name(position, 3) if count == 3 else 'row'} belongs"
            else:
                said = f"the {word} {now} of {inner} is used where the {word} {was} belongs"
            yield "axis", spec, said + " (an index on the wrong axis)"
    if len(elements) == 2 and _whole_slice(elements[0]) and isinstance(elements[1], ast.Slice) \
            and elements[1].step is None:
        lower = _constant_index(elements[1].lower) if elements[1].lower is not None else 0
        upper = _constant_index(elements[1].upper) if elements[1].upper is not None else None
        if lower not in (0, 1, 2) or (upper is not None and upper != lower + 1) or (upper is None and lower != 1):
            return
        names = {0: "x coordinates (column 0)", 1: "y coordinates (column 1)", 2: "values in column 2"}
        for other in (0, 1):   # x for y, y for x, either for z (no z where only x and y are)
            if other != lower:
                yield "axis", [":", f"{other}:{other + 1}"], f"the {names[other]} of {inner} are used where the " \
                                                              f"{names[lower]} belong (a copied index)"


def _inverse_changes(node, what, place):
    """``np.linalg.inv(X)`` as ``X.T`` or as ``X``, and ``X.T`` as ``np.linalg.inv(X)``."""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.linalg.inv", "numpy.linalg.inv") \
            and len(node.args) == 1 and not node.keywords and not isinstance(node.args[0], ast.Starred):
        inner = what(node.args[0])
        yield "inverse", "transpose", f"the transpose of {inner} is used where its inverse belongs" if inner \
            else _placed("a transpose is used where an inverse belongs", place())
        yield "inverse", "drop", f"{inner} is used where its inverse belongs (the inversion is missing)" if inner \
            else _placed("an inversion is missing", place())
    if isinstance(node, ast.Attribute) and node.attr == "T" and isinstance(node.ctx, ast.Load) and _named_matrix(node.value):
        inner = what(node.value)
        yield "inverse", "insert", f"the inverse of {inner} is used where its transpose belongs" if inner \
            else _placed("an inverse is used where a transpose belongs", place())


def _arithmetic_changes(node, what, place):
    """``*`` and ``/`` exchanged, and ``@`` taken element by element (``*``) or the reverse; a side
    without words of its own is "a term" when the other side has them."""
    left, right = what(node.left), what(node.right)
    told = bool(left or right)
    left, right = left or "a term", right or "a term"
    if isinstance(node.left, ast.BinOp) and type(node.left.op) is type(node.op) \
            and isinstance(node.op, (ast.Mult, ast.MatMult)):
        # (the same slip at every product of a chain: one change each would cross the other's place)
        if isinstance(node.op, ast.Mult):
            yield "arithmetic", "chain_matmul", _placed(
                "matrix products (@) stand where every product of the chain is element by element", place())
        else:
            yield "arithmetic", "chain_mult", _placed(
                "the matrices are multiplied element by element (*) where their matrix products (@) belong", place())
    if isinstance(node.op, ast.Mult):
        yield "arithmetic", "mul_div", (f"{left} is divided by {right} where it is multiplied by it" if told
                                        else _placed("a division stands where a multiplication belongs", place()))
        yield "arithmetic", "mult_matmul", (
            f"the matrix product of {left} and {right} is taken where they are multiplied element by element"
            if told else _placed("a matrix product stands where an element-wise product belongs", place()))
    elif isinstance(node.op, ast.Div):
        yield "arithmetic", "div_mul", (f"{left} is multiplied by {right} where it is divided by it" if told
                                        else _placed("a multiplication stands where a division belongs", place()))
    else:
        yield "arithmetic", "matmul_mult", (
            f"{left} and {right} are multiplied element by element (*) where their matrix product (@) belongs"
            if told else _placed("an element-wise product (*) stands where a matrix product (@) belongs", place()))


def _is_inverse(node) -> bool:
    return isinstance(node, ast.Call) and _dotted(node.func) in ("np.linalg.inv", "numpy.linalg.inv") \
        and len(node.args) == 1 and not node.keywords


def _chain_of_three(node):
    """``(A, M, B)`` of ``A @ M @ B`` (left to right), else None."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult) and isinstance(node.left, ast.BinOp) \
            and isinstance(node.left.op, ast.MatMult):
        return node.left.left, node.left.right, node.right
    return None


def _undoing_changes(node):
    """A normalisation undone as ``inv(T) @ M @ U``: undone with the inverses on the other sides
    (``T @ M @ inv(U)``), or never undone (``M``). Told without the transforms' names: a student's
    locals have names of their own, and the step is the same whatever they are."""
    chain = _chain_of_three(node)
    if chain is None or not any(_is_inverse(f) for f in (chain[0], chain[2])):
        return
    yield "inverse", "swap_sides", "the normalisation is undone the wrong way round: each of the two normalising " \
                                   "transforms is inverted where the other is (undoing it takes the inverse of the " \
                                   "output side's transform, on the left, and the other as it is, on the right)"
    yield "inverse", "undone_never", "the normalisation is never undone: the solution of the normalised system is " \
                                     "returned without its two transforms"


def _named_matrix(node) -> bool:
    """Whether ``node`` is a matrix a student names (``R``, ``np.asarray(K, ...)``): where a transpose
    may be written for an inverse. A grid, a stack, a product or an inverse (inv(X).T as inv(inv(X))
    is X: the operators above say it) is not: inverting those raises everywhere, no slip of anyone's."""
    if isinstance(node, ast.Call) and _dotted(node.func) in ("np.asarray", "np.array", "numpy.asarray", "numpy.array"):
        node = node.args[0] if node.args else None
    # (or one item of a list of them: `step[j].T` for a homography's inverse, a rotation's habit)
    if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) \
            and isinstance(node.slice, (ast.Name, ast.Constant)) and not isinstance(getattr(node.slice, "value", 0), str):
        return True
    return isinstance(node, ast.Name)


_STACKING = ("hstack", "vstack", "concatenate", "column_stack", "stack", "dstack")


def _stack_changes(node: ast.Call, what):
    """Two neighbouring pieces of ``np.hstack([...])`` (``vstack``, ``concatenate``, ...) exchanged, and
    the outer two of three channels given to ``cv2.merge`` or ``np.dstack`` (the B, G, R order reversed)."""
    dotted = _dotted(node.func)
    stacking = dotted.startswith(("np.", "numpy.")) and dotted.rsplit(".", 1)[-1] in _STACKING
    if not (stacking or dotted == "cv2.merge") or not node.args \
            or not isinstance(node.args[0], (ast.List, ast.Tuple)) or len(node.args[0].elts) < 2:
        return
    items = node.args[0].elts
    if len(items) == 3 and dotted.endswith(("merge", "dstack")) and not any(isinstance(e, ast.Starred) for e in items):
        a, b = what(items[0]), what(items[2])
        if a and b and len(a + b) <= 90:
            yield "stack_order", (0, 2), f"the channels {a} and {b} are given in the other order (B, G, R reversed)"
    for i in range(min(len(items), 9) - 1):
        if any(isinstance(e, ast.Starred) for e in items[i:i + 2]):
            continue
        a, b = what(items[i]), what(items[i + 1])
        if a and b and len(a + b) <= 90:
            yield "stack_order", i, f"{a} and {b} are stacked in the other order (each where the other belongs)"
        else:   # (a design matrix's row: its entries by position, the way the lab sheet writes them)
            yield "stack_order", i, f"the {_ORDINALS[i]} and {_ORDINALS[i + 1]} pieces stacked by `{dotted}` " \
                                    "are exchanged"


def _einsum_changes(spec):
    """Subscripts of ``np.einsum`` a student gets wrong: an index summed over that the answer keeps
    (``'ni,nj->ij'`` for the rows ``'ni,nj->nij'``), the answer's axes in another order, one operand's
    two indices reversed (the operand transposed). Explicit subscripts only (``->``, no ``...``)."""
    if not isinstance(spec, str) or "->" not in spec or "." in spec or not spec.replace(" ", ""):
        return
    spec = spec.replace(" ", "")
    inputs, out = spec.split("->")
    terms = inputs.split(",")
    if not all(t.isalpha() for t in terms) or (out and not out.isalpha()) or len(set(out)) != len(out):
        return
    summed = sorted({c for t in terms for c in t} - set(out), key=inputs.index)
    changes = []
    for c in summed:
        changes += [(f"{c}{out}", f"the index {c} is summed over, where the answer keeps it as its first axis"),
                    (f"{out}{c}", f"the index {c} is summed over, where the answer keeps it as its last axis")]
    for i, j in itertools.combinations(range(len(out)), 2):
        swapped = list(out)
        swapped[i], swapped[j] = swapped[j], swapped[i]
        changes.append(("".join(swapped), f"the answer's axes {out[i]} and {out[j]} are in the other order"))
    for k, term in enumerate(terms):
        if len(term) == 2 and term[0] != term[1]:
            others = terms[:k] + [term[::-1]] + terms[k + 1:]
            changes.append((None, f"the {_ORDINALS[k]} operand's indices are reversed (it is used transposed)",
                            ",".join(others)))
    for change in changes:
        new_inputs = change[2] if len(change) == 3 else inputs
        new_out = change[0] if change[0] is not None else out
        yield "einsum", repr(f"{new_inputs}->{new_out}"), \
            f"in `np.einsum`, {change[1]} ('{new_inputs}->{new_out}' for '{spec}')"


def _in_place_changes(node, words: _Words):
    """A copy of an input dropped (``out = image.copy()`` -> ``out = image``, ``np.array`` -> ``np.asarray``)
    or an input's update written in place (``x = x / s`` -> ``x /= s``): the caller's array changes.
    Only on the graded function's own parameters (what a caller hands in)."""
    if isinstance(node, ast.Call) and node.args[:1] and isinstance(node.args[0], ast.Name) \
            and node.args[0].id in words.api_params and _dotted(node.func) in ("np.array", "numpy.array") \
            and not any(k.arg == "copy" and isinstance(k.value, ast.Constant) and not k.value.value
                        for k in node.keywords):
        yield "in_place", "array", f"`{node.args[0].id}` is written into in place (the copy of it is missing: " \
                                   "the caller's array changes)"
    copied = node.func.value if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
        and node.func.attr == "copy" and not node.args else \
        (node.args[0] if isinstance(node, ast.Call) and _dotted(node.func) in ("np.copy", "numpy.copy")
         and len(node.args) == 1 else None)
    if isinstance(copied, ast.Name) and copied.id in words.api_params:
        yield "in_place", "copy", f"`{copied.id}` is written into in place (the copy of it is missing: " \
                                  "the caller's array changes)"
    if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
            and isinstance(node.value, ast.BinOp) and isinstance(node.value.left, ast.Name) \
            and node.value.left.id == node.targets[0].id and node.targets[0].id in words.api_params \
            and type(node.value.op) in (ast.Add, ast.Sub, ast.Mult, ast.Div):
        verb = {ast.Add: "increased", ast.Sub: "decreased", ast.Mult: "multiplied", ast.Div: "divided"}[
            type(node.value.op)]
        yield "in_place", "augment", f"`{node.targets[0].id}` is {verb} in place (the caller's array changes)"
    if words.student and isinstance(node, ast.AugAssign) and isinstance(node.target, ast.Name) \
            and node.target.id in _stored_names(words.fn):
        # (the student's code only: an array kept in a list, then updated in place -- `to_ref[k] = chain` and
        # `chain @= step` on the next turn of the loop -- changes the one already kept: each item the same array)
        yield "in_place", "rebind", ""


def _stored_names(fn) -> set:
    """Names whose value the function keeps in a container (`items[k] = x`, `items.append(x)`, `{k: x}`
    as a value): the same object, not a copy."""
    cached = getattr(fn, "_stored_names", None)
    if cached is None:
        cached = set()
        for node in walk(fn):
            if isinstance(node, ast.Assign) and isinstance(node.value, ast.Name) \
                    and any(isinstance(target, ast.Subscript) for target in node.targets):
                cached.add(node.value.id)
            elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                    and node.func.attr in ("append", "insert") and node.args and isinstance(node.args[-1], ast.Name):
                cached.add(node.args[-1].id)
        fn._stored_names = cached
    return cached


def _placed(sentence: str, place: str) -> str:
    return f"{sentence} {place}" if place else ""


def _place(node, parents, words: _Words, line) -> str:
    """Where an unnamed term is, in the student's terms: "in the arguments of `np.hstack`", "in
    the returned value", "in computing rows 0-1, column 2 of ..."; "" when nothing says it."""
    up, child, item = parents.get(id(node)), node, None
    while up is not None:
        holder = up[0]
        if isinstance(holder, (ast.List, ast.Tuple)):
            item = next((i for i, e in enumerate(holder.elts) if e is child), None)
        if isinstance(holder, ast.Call):
            dotted = _dotted(holder.func)
            if dotted.startswith(("np.", "cv2.")) or dotted in words.api:
                which = next((i for i, a in enumerate(holder.args) if a is child), None)
                argument = f"the {_ORDINALS[which]} argument" if which is not None and which < 6 else "the arguments"
                if which is not None and isinstance(child, (ast.List, ast.Tuple)) and item is not None and item < 6:
                    argument = f"the {_ORDINALS[item]} item of {argument}"
                same = [n for n in walk(words.fn) if isinstance(n, ast.Call) and _dotted(n.func) == dotted]
                call = f"the {_ORDINALS[same.index(holder)]} `{dotted}`" if 1 < len(same) <= 6 else f"`{dotted}`"
                return f"in {argument} of {call}"
        if isinstance(holder, ast.Return):
            return "in the returned value"
        if isinstance(holder, (ast.Assign, ast.AugAssign)):
            target = holder.targets[0] if isinstance(holder, ast.Assign) else holder.target
            named = words.what(target, line=line + 1) if not isinstance(target, ast.Tuple) else ""
            return f"in computing {named}" if named else ""
        if isinstance(holder, ast.stmt):
            return ""
        up, child = parents.get(id(holder)), holder
    return ""


_ORDINALS = ("first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth")


def _subject(phrase: str, predicate: str, node, parents, words) -> str:
    """"<phrase> <predicate>", placed in its matrix literal when it is an entry of one."""
    place = _entry_of_literal(node, parents)
    if place:
        where = f"entry [{place[0]}, {place[1]}] of the matrix built there"
        return f"{phrase} at {where} {predicate}" if phrase else f"{where} {predicate}"
    return f"{phrase} {predicate}" if phrase else ""


def _rebuilt_from(node, words) -> str | None:
    """The matrix (its code) that ``node`` rebuilds from its factors, when every name ``node`` reads (but
    modules) comes from one unpacking of one decomposition of it in the def (`U, s, Vt = np.linalg.svd(E)`)."""
    read = _read(node) - {"np", "numpy", "cv2", "scipy"}
    for a in _assignments(words):
        if len(a.names) > 1 and a.single is None and isinstance(a.value, ast.Call) and len(a.value.args) == 1 \
                and _dotted(a.value.func).rsplit(".", 1)[-1] in ("svd", "eig", "eigh", "qr", "rq", "SVDecomp") \
                and read and read <= set(a.names):
            return ast.unparse(a.value.args[0])
    return None


def _antisymmetric_literal(node) -> bool:
    """Whether ``node`` is ``np.array([[...], ...])`` of a square matrix written out with an entry and its
    minus in mirrored places (row i, column j and row j, column i): a rotation's sines."""
    if not (isinstance(node, ast.Call) and _dotted(node.func) in ("np.array", "numpy.array", "np.asarray")
            and node.args and isinstance(node.args[0], ast.List)):
        return False
    rows = node.args[0].elts
    if len(rows) < 2 or not all(isinstance(r, ast.List) and len(r.elts) == len(rows) for r in rows):
        return False

    def negated(a, b) -> bool:
        return isinstance(a, ast.UnaryOp) and isinstance(a.op, ast.USub) and not isinstance(a.operand, ast.Constant) \
            and ast.dump(a.operand) == ast.dump(b)

    return any(negated(rows[i].elts[j], rows[j].elts[i]) or negated(rows[j].elts[i], rows[i].elts[j])
               for i in range(len(rows)) for j in range(i + 1, len(rows)))


def _entry_of_literal(node, parents):
    """(row, column) when ``node`` (or its minus) is an entry of a nested list literal."""
    if not isinstance(node, ast.expr):
        return None
    up = parents.get(id(node))
    if up and isinstance(up[0], ast.UnaryOp):
        node, up = up[0], parents.get(id(up[0]))
    if not up or not isinstance(up[0], ast.List) or up[2] is None:
        return None
    above = parents.get(id(up[0]))
    if not above or not isinstance(above[0], ast.List) or above[2] is None:
        return None
    if not all(isinstance(r, ast.List) for r in above[0].elts):
        return None
    return above[2], up[2]


def _division_phrase(node, what) -> str:
    right = node.right
    left = what(node.left)
    if isinstance(right, ast.Subscript):
        index = right.slice
        last = (isinstance(index, ast.Constant) and index.value in (2, -1)) or (
            isinstance(index, ast.Tuple) and len(index.elts) == 2 and (
                (isinstance(index.elts[1], ast.Constant) and index.elts[1].value in (2, -1))
                or (isinstance(index.elts[1], ast.Slice) and isinstance(index.elts[1].lower, ast.Constant)
                    and index.elts[1].lower.value in (2, -1))
                or (isinstance(index.elts[0], ast.Constant) and index.elts[0].value in (2, -1))))
        if last:
            return (f"{left} is not divided by its last (homogeneous) coordinate (no de-homogenisation)"
                    if left else "the division by the last (homogeneous) coordinate is missing (no de-homogenisation)")
    divisor = what(right)
    if isinstance(right, ast.Call) and _dotted(right.func).endswith("norm"):
        return f"the normalisation by {divisor} is missing" if divisor else "a normalisation (by a norm) is missing"
    if divisor and left:
        return f"{left} is not divided by {divisor} (a normalisation is missing)"
    return ""


def _call_changes(node: ast.Call, words, what, parents):
    dotted = _dotted(node.func)
    short = dotted.rsplit(".", 1)[-1]
    shown = f"`{dotted}`" if dotted.startswith(("cv2.", "np.", "numpy.")) else (
        f"`{dotted}`" if dotted in words.api or words.student else "")
    positional = [a for a in node.args if not isinstance(a, ast.Starred)]
    if len(positional) == len(node.args) and len(node.args) >= 2 and shown:
        for i in range(len(node.args)):
            for j in range(i + 1, min(len(node.args), i + 3)):
                if i == 0 and short in _DATA_FIRST and dotted.startswith(("np.", "numpy.")):
                    continue   # (`np.clip(limit, 0, v)`: the data exchanged with a bound is no one's slip)
                a, b = what(node.args[i]), what(node.args[j])
                ordinal = ("first", "second", "third", "fourth", "fifth", "sixth")
                if i < 6 and j < 6:
                    detail = f" ({a} and {b})" if a and b else ""
                    yield "swap_args", (i, j), f"{shown} gets its {ordinal[i]} and {ordinal[j]} arguments in " \
                                               f"the wrong order{detail}"
    if dotted in _ANGLE_CONVERSIONS:
        arg = what(node.args[0]) if node.args else ""
        unit = _ANGLE_CONVERSIONS[dotted]
        other = "degrees" if unit == "radians" else "radians"
        yield "degrees", "remove", f"{arg or 'the angle'} is used in {other} where {unit} are needed " \
                                   f"(the conversion `{dotted}` is missing)"
    if words.student and dotted.endswith("ndimage.rotate") and not any(k.arg == "reshape" for k in node.keywords):
        # (the student's code only: scipy's rotate enlarges its output to hold the whole turned image unless told
        # reshape=False -- the API's warps keep the input's size)
        yield "flip_keyword", ("reshape", False), ""
    if words.student and dotted in ("np.tile", "numpy.tile", "np.repeat", "numpy.repeat") and len(node.args) == 2 \
            and not node.keywords:
        # (the student's code only: each item repeated where the whole array is tiled, or the other way --
        # `np.tile(fs, n)` pairs f_0, f_1, ... with the points where `np.repeat(fs, n)` pairs f_0 with n of them)
        yield "tile_repeat", None, ""
    if words.student and dotted.startswith("math.") and dotted[5:] in _MATH_TO_NUMPY and node.args:
        # (the student's code only: a function of one number given an array -- `math.pow(r2, 2)` -- where
        # NumPy's of the same name works entry by entry)
        yield "math_numpy", None, ""
    if words.student and dotted == "int" and len(node.args) == 1 and not node.keywords and _makes_text(node.args[0]):
        # (the student's code only: a string of bits read as a decimal number -- `int("".join(bits))` where
        # `int(..., 2)` belongs: "1010" is ten hundred and ten)
        yield "int_base", 2, ""
    method = node.func.attr if isinstance(node.func, ast.Attribute) else ""   # x.reshape, np.reshape(x, ...)
    if words.student and method == "reshape" and not dotted.startswith(("np.", "numpy.")) \
            and (len(node.args) == 2 or (len(node.args) == 1 and isinstance(node.args[0], ast.Tuple)
                                         and len(node.args[0].elts) == 2)) and not node.keywords:
        # (the student's code only: a 2-D array reshaped to the transposed shape where it is transposed --
        # `pts.reshape(3, -1)` for the points as columns mixes their coordinates; .T moves them)
        yield "reshape_order", "transpose", ""
    if words.student and method == "reshape" and not dotted.startswith(("np.", "numpy.")) and not node.keywords \
            and (len(node.args) == 3 or (len(node.args) == 1 and isinstance(node.args[0], ast.Tuple)
                                         and len(node.args[0].elts) == 3)):
        # (a stack regrouped by reshape where its first two axes trade places: `rows.reshape(n, 4, 4)` of a
        # (4, n, 4) stack mixes the points' equations; .transpose(1, 0, 2) moves them)
        yield "reshape_order", "swap_first", ""
    if method in _ORDERED and not any(k.arg == "order" for k in node.keywords):
        array = what(node.args[0]) if dotted.startswith(("np.", "numpy.")) and node.args else what(node.func.value)
        yield "reshape_order", "F", f"{array or 'an array'} is {_ORDERED[method]} column by column " \
                                    "(Fortran order) instead of row by row"
    method_of_array = short in _ARRAY_METHODS and "." in dotted and not dotted.startswith(("cv2.", "cv.", "math."))
    if short in _OPPOSITES and (dotted.startswith(("np.", "numpy.")) or dotted in ("min", "max")):
        other = dotted[: -len(short)] + _OPPOSITES[short]
        on = what(node.args[0]) if node.args else ""
        yield "minmax", other, f"`{other}` is used where `{dotted}` belongs" + (f" (on {on})" if on else "")
    elif short in _OPPOSITES and method_of_array:   # (an array's own method: told without the array's local name)
        other = dotted[: -len(short)] + _OPPOSITES[short]
        on = what(node.func.value)
        yield "minmax", other, f"{_OPPOSITES[short]}() is taken where {short}() belongs" + (f" (of {on})" if on else "")


_INVERSE_TRIG = {"np.arctan2", "np.arctan", "np.arcsin", "np.arccos", "numpy.arctan2", "numpy.arctan", "numpy.arcsin",
                 "numpy.arccos", "math.atan2", "math.atan", "math.asin", "math.acos"}
_TO_DEGREES = {"np.degrees", "np.rad2deg", "numpy.degrees", "numpy.rad2deg", "math.degrees"}


_NUMBER_TYPES = {"float": "(int, float, np.number)", "int": "(int, np.integer)", "np.floating": "(int, float, np.number)",
                 "np.float64": "(int, float, np.number)"}


_IMAGE_NAMES = re.compile(r"^(image|img|frame|picture|photo|left|right|source|src_img)\w*$")


def _size_written(node, parents):
    """An image size written as numbers where the input's own belongs: `size = (640, 480)` for the maps of
    whatever image is given -> `(image.shape[1], image.shape[0])`, for each image parameter of the function (one
    whose shape it reads, or named as an image is), in OpenCV's (width, height) order."""
    if not (isinstance(node, ast.Tuple) and isinstance(node.ctx, ast.Load) and len(node.elts) == 2
            and all(isinstance(e, ast.Constant) and type(e.value) is int and e.value >= 16 for e in node.elts)):
        return
    fn = _def_of(node, parents)
    if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
        return
    for name in _image_parameters(fn)[:2]:
        yield "size_written", f"({name}.shape[1], {name}.shape[0])", ""


def _image_parameters(fn) -> list[str]:
    """The parameters of ``fn`` that are images: one whose shape it reads, or named as an image is (once per
    def: each of its size tuples asks, and a walk per tuple would be quadratic in the def)."""
    if not hasattr(fn, "_image_parameters"):
        shaped = {n.value.id for n in walk(fn) if isinstance(n, ast.Attribute) and n.attr == "shape"
                  and isinstance(n.value, ast.Name)}
        fn._image_parameters = [a.arg for a in fn.args.args if a.arg in shaped or _IMAGE_NAMES.match(a.arg)]
    return fn._image_parameters


def _type_widened(node):
    """A type test narrower than the values the API allows: `isinstance(z_avg, float)` takes an int or a NumPy
    float32 for no value -> `isinstance(z_avg, (int, float, np.number))`."""
    if isinstance(node, ast.Call) and _dotted(node.func) == "isinstance" and len(node.args) == 2 \
            and _dotted(node.args[1]) in _NUMBER_TYPES:
        yield "type_widened", f"isinstance({ast.unparse(node.args[0])}, {_NUMBER_TYPES[_dotted(node.args[1])]})", ""


def _to_degrees(node, parent):
    """An angle an inverse trigonometric function gives in radians, used where degrees belong: `np.arctan2(b, a)`
    compared with 45 and 135 -> `np.degrees(np.arctan2(b, a))` (the conversion left out)."""
    if isinstance(node, ast.Call) and _dotted(node.func) in _INVERSE_TRIG \
            and not (isinstance(parent, ast.Call) and _dotted(parent.func) in _TO_DEGREES):
        yield "to_degrees", f"np.degrees({ast.unparse(node)})", ""


def _key_order(node):
    """A dict's entries taken in the order they were put in, where the order of their keys belongs: values
    filled from the middle image outwards, listed as image 0, 1, 2... -- `d.values()` -> `[d[k] for k in
    sorted(d)]`, `d.keys()` -> `sorted(d)`, `d.items()` -> `sorted(d.items())`."""
    if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and not node.args and not node.keywords
            and node.func.attr in ("values", "keys", "items") and isinstance(node.func.value, (ast.Name, ast.Attribute))):
        return
    d = ast.unparse(node.func.value)
    yield "key_order", {"values": f"[{d}[k] for k in sorted({d})]", "keys": f"sorted({d})",
                        "items": f"sorted({d}.items())"}[node.func.attr], ""


_VECTOR_MAKERS = {"np.array", "np.asarray", "np.float64", "np.float32", "numpy.array", "numpy.asarray"}


def _perpendicular(node, parent):
    """A 2D vector written where the one perpendicular to it belongs: a line's normal (a, b) walked along as
    its direction -- `np.array([a, b])` -> `np.array([-b, a])` or `[b, -a]` (a quarter turn either way).
    Only a pair of plain values (names, entries, their negatives) made a vector -- given to np.array, or a
    list bound to one name: a size or a point's coordinates computed in place are no vector of the kind, and
    two values exchanged (`P1, P2 = P2, P1`, matrices) none at all."""
    if not (isinstance(node, (ast.List, ast.Tuple)) and isinstance(node.ctx, ast.Load) and len(node.elts) == 2):
        return
    made = (isinstance(parent, ast.Call) and _dotted(parent.func) in _VECTOR_MAKERS and parent.args[:1] == [node]) \
        or (isinstance(node, ast.List) and isinstance(parent, ast.Assign) and parent.value is node
            and len(parent.targets) == 1 and isinstance(parent.targets[0], ast.Name))
    if not made:
        return
    plain = lambda item: isinstance(item, (ast.Name, ast.Subscript)) or (   # noqa: E731
        isinstance(item, ast.UnaryOp) and isinstance(item.op, ast.USub) and isinstance(item.operand, (ast.Name, ast.Subscript)))
    if not all(plain(item) for item in node.elts):
        return
    negated = lambda item: ast.unparse(item.operand) if isinstance(item, ast.UnaryOp) else f"-{ast.unparse(item)}"  # noqa: E731
    first, second = (ast.unparse(item) for item in node.elts)
    opening, closing = ("[", "]") if isinstance(node, ast.List) else ("(", ")")
    for turned in (f"{negated(node.elts[1])}, {first}", f"{second}, {negated(node.elts[0])}"):
        yield "perpendicular", f"{opening}{turned}{closing}", ""


def _focal_left_out(node, parent):
    """A pixel centred on a camera matrix's principal point and left in pixels, where normalised coordinates
    (K^-1 applied) belong: `pts - K[:2, 2]` -> `(pts - K[:2, 2]) @ np.linalg.inv(K[:2, :2]).T`, `u - K[0, 2]`
    -> `(u - K[0, 2]) / K[0, 0]` (half of K^-1: the shift without the division by the focal length)."""
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Sub) and isinstance(node.right, ast.Subscript)
            and isinstance(node.right.value, (ast.Name, ast.Attribute))):
        return
    if isinstance(parent, ast.BinOp) and isinstance(parent.op, (ast.Div, ast.MatMult)) and parent.left is node:
        return   # (divided or mapped already: `(u - K[0, 2]) / K[0, 0]`)
    matrix, index = ast.unparse(node.right.value), ast.unparse(node.right.slice).strip("()")
    if index in (":2, 2", "0:2, 2"):
        yield "focal_left_out", f"({ast.unparse(node)}) @ np.linalg.inv({matrix}[:2, :2]).T", ""
    elif index in ("0, 2", "1, 2"):
        yield "focal_left_out", f"({ast.unparse(node)}) / {matrix}[{index[0]}, {index[0]}]", ""


_BOUNDS_OF_TWO = {"max", "min", "np.maximum", "np.minimum", "np.fmax", "np.fmin", "numpy.maximum", "numpy.minimum"}
_FLOAT_TYPES = {"float", "np.float32", "np.float64", "np.double", "numpy.float32", "numpy.float64"}


def _float_conversion(node: ast.Call):
    """``x`` when ``node`` converts ``x`` to a float array: ``np.asarray(x, dtype=np.float32)``,
    ``np.array(x, float)``, ``np.float64(x)``, ``x.astype(np.float32)``; else None."""
    dotted = _dotted(node.func)
    is_float = (lambda n: _dotted(n) in _FLOAT_TYPES
                or (isinstance(n, ast.Constant) and n.value in ("float", "float32", "float64")))
    if dotted in ("np.asarray", "np.array", "numpy.asarray", "numpy.array") and len(node.args) >= 1:
        dtype = node.args[1] if len(node.args) > 1 else next((k.value for k in node.keywords if k.arg == "dtype"), None)
        return node.args[0] if dtype is not None and is_float(dtype) else None
    if dotted in _FLOAT_TYPES - {"float"} and len(node.args) == 1 and not node.keywords:
        return node.args[0]
    if isinstance(node.func, ast.Attribute) and node.func.attr == "astype" and node.args and is_float(node.args[0]):
        return node.func.value
    return None


_MEAN_WORDS = ("mean", "average", "centroid", "centre", "center")


def _centring_phrase(node: ast.BinOp, what) -> str:
    """What is missing when ``x - mean`` becomes ``x``: a covariance's product of means, a variance's
    squared mean, or a centring."""
    right = node.right
    if isinstance(right, ast.BinOp) and isinstance(right.op, ast.Mult):
        return "the product of the two means is not subtracted (a covariance is the mean of the products " \
               "minus the product of the means: without it the score is not centred)"
    if isinstance(right, ast.BinOp) and isinstance(right.op, ast.Pow):
        return "the squared mean is not subtracted (a variance is the mean of the squares minus the squared mean)"
    mean, of = what(right), what(node.left)
    said = f"{mean} is not subtracted from {of}" if mean and of else f"{mean} is not subtracted" if mean \
        else "a mean is not subtracted"
    return f"{said} (the values are not centred on their mean)"


def _is_mean(node, words: _Words, depth: int = 0) -> bool:
    """Whether ``node`` is (or is a product or a function of) a mean: ``np.mean(x)``, ``x.mean(axis=0)``,
    ``np.average``, a call of a module function whose docstring or name says it averages, or a name
    holding one (``mean_l * mean_r``, ``centroid``): what centring subtracts."""
    if depth > 3:
        return False
    if isinstance(node, ast.Call):
        dotted = _dotted(node.func)
        short = dotted.rsplit(".", 1)[-1].lower()
        if short in ("mean", "nanmean", "average", "median", "blur", "boxfilter") or any(w in short for w in _MEAN_WORDS):
            return True
        helper = words.module_defs.get(dotted)
        if helper is not None:
            said = (ast.get_docstring(helper) or "").split("\n\n")[0].lower()
            return any(w in said.split(".")[0] for w in ("mean", "average"))
        return False
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Pow)):
        return _is_mean(node.left, words, depth + 1)
    if isinstance(node, ast.Name):
        if any(w in node.id.lower() for w in _MEAN_WORDS):
            return True
        defined = words.definitions.get(node.id, ())
        return len(defined) == 1 and defined[0][2] is None and _is_mean(defined[0][1], words, depth + 1)
    if isinstance(node, ast.Subscript):
        return _is_mean(node.value, words, depth + 1)
    return False


_CENTRE_NAMES = frozenset({"cx", "cy", "u0", "v0", "c_x", "c_y", "ox", "oy"})


def _is_image_centre(node, words: _Words) -> bool:
    """Whether ``node`` is a principal point's or an image centre's coordinate the student's code subtracts: `cx`,
    or a name bound once to half a size (`(width - 1) / 2`): coordinates made relative to it, to be made absolute
    again where they become pixel indices."""
    if not isinstance(node, ast.Name):
        return False
    if node.id.lower() in _CENTRE_NAMES:
        return True
    defined = words.definitions.get(node.id, ())
    value = defined[0][1] if len(defined) == 1 and defined[0][2] is None else None
    return isinstance(value, ast.BinOp) and isinstance(value.op, ast.Div) and isinstance(value.right, ast.Constant) \
        and value.right.value == 2


def _trig_argument(node, parent) -> bool:
    return isinstance(parent, ast.Call) and bool(parent.args) and node is parent.args[0] \
        and _dotted(parent.func).rsplit(".", 1)[-1] in ("sin", "cos", "tan") \
        and not isinstance(node, (ast.UnaryOp, ast.Constant))


def _angle_name(name: str) -> bool:
    return any(word in name.lower() for word in ("angle", "deg", "theta"))


def _constant_changes(node: ast.Constant, parents, words, what):
    """An integer constant as an axis, an index or a slice bound: another axis or index, a bound
    moved by one."""
    parent, field, _ = parents.get(id(node), (None, None, None))
    value = node.value
    if isinstance(parent, ast.keyword) and parent.arg == "axis":
        # (a student's 3-D stacks: axis 2 too; and the last, whatever the input's dimensions --
        # `np.stack([x, y], axis=1)` where one point's (3,) gives 0-D coordinates and axis=-1 belongs)
        for other in (0, 1, 2, -1) if words.student else (0, 1):
            if other != value:
                yield "axis", other, f"the sum/statistic runs over axis {other} where axis {value} belongs"
        return
    call = parents.get(id(parent), (None,))[0] if isinstance(parent, ast.keyword) else parent
    if words.student and isinstance(call, ast.Call) and _dotted(call.func).startswith(("cv2.", "cv.")) \
            and (node in call.args[1:] or isinstance(parent, ast.keyword)) and value in _LITERALS:
        # an OpenCV argument given as a number (`whichImage=2` for 1, a flip code): the nearest first
        for other in sorted(_LITERALS, key=lambda other: (abs(other - value), -other)):
            if other != value:
                yield "literal", other, ""
        return
    if words.student and isinstance(parent, ast.Call) and _dotted(parent.func) == "range" and node in parent.args:
        for delta in (-1, 1):   # a loop that starts or stops one early or late: `range(1, n)` for `range(n)`
            if value + delta >= 0:
                yield "bound", value + delta, ""
        return
    if isinstance(parent, ast.Slice):
        subscript = parents.get(id(parent), (None,))[0]
        subscript = parents.get(id(subscript), (None,))[0] if isinstance(subscript, ast.Tuple) else subscript
        inner = what(subscript.value) if isinstance(subscript, ast.Subscript) else ""
        if value >= 0 and inner and field == "step":
            for delta in (-1, 1):   # (a stride: `M[0::2]`, the even rows, read as every row, or every third)
                if value + delta >= 1:
                    yield "bound", value + delta, f"a slice of {inner} takes {_every(value + delta)} where " \
                                                  f"{_every(value)} belongs"
        elif value >= 0 and inner:
            for delta in (-1, 1):
                if value + delta >= 0:
                    yield "bound", value + delta, f"a slice of {inner} {'starts' if field == 'lower' else 'stops'} " \
                                                  f"one element {'early' if delta < 0 else 'late'} (off by one)"
        return
    subscript, elements = parent, [node]
    if isinstance(parent, ast.Tuple):
        subscript, elements = parents.get(id(parent), (None,))[0], parent.elts
    if not (isinstance(subscript, ast.Subscript) and subscript.slice is (parent if elements != [node] else node)):
        return
    if not 0 <= value <= (3 if words.student else 2):
        return
    position = next(i for i, e in enumerate(elements) if e is node)
    if isinstance(subscript.value, ast.Attribute) and subscript.value.attr == "shape" and value in (0, 1):
        target = what(subscript.value.value)
        if target:
            yield "axis", 1 - value, f"the width and height of {target} are swapped"
        if words.student:   # (a stack's (n, H, W) shape read an axis early: `shape[1]`, the height, for the width)
            for other in (value + 1, -1):
                if other != 1 - value:
                    yield "axis", other, ""
        return
    inner = what(subscript.value)
    if words.student:   # (shown, not told: another of the first four, `P[:, 2]` for `P[:, 3]`, or the last)
        for other in (0, 1, 2, 3, -1):
            if other != value:
                yield "axis", other, ""
        return
    for other in (0, 1, 2):
        if other != value and (other < 2 or value == 1):
            phrase = _index_phrase(inner, elements, position, value, other)
            if phrase:
                yield "axis", other, phrase


_LITERALS = (-1, 0, 1, 2)


def _transposable(node, parent) -> bool:
    """Where a ``.T`` is a plausible slip: a matrix product's operand, a linear-algebra call's
    argument, a returned matrix."""
    if isinstance(node, (ast.Constant, ast.Starred)) or (isinstance(node, ast.Attribute) and node.attr == "T"):
        return False
    if isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.MatMult):
        return True
    if isinstance(parent, ast.Call) and node in parent.args and _dotted(parent.func).startswith("np.linalg."):
        return True
    return isinstance(parent, ast.Return) and isinstance(node, (ast.Name, ast.Call, ast.BinOp))


def _matrix_renamed(node, parent) -> bool:
    """A student's matrix given its name from another one or from a linear-algebra call
    (``L = X``, ``W = np.linalg.lstsq(A, B)[0]``): where the result is the transpose of what the
    name stands for (``lstsq`` solves ``A @ X = B``: one column per output), the ``.T`` belongs there,
    and no single later use of the name mends every one."""
    if not (isinstance(parent, ast.Assign) and parent.value is node and len(parent.targets) == 1
            and isinstance(parent.targets[0], ast.Name)):
        return False
    inner = node.value if isinstance(node, ast.Subscript) else node
    return (isinstance(node, ast.Name) and node.id != parent.targets[0].id) or (
        isinstance(inner, ast.Call) and _dotted(inner.func).startswith(("np.linalg.", "numpy.linalg.")))


# OpenCV functions' point-set arguments (by position), one point per row ((N, 2), (N, 3), (N, 4)); a
# (k, N) stack of columns is read as k points of N coordinates (triangulatePoints' 2 x N and its 4 x N
# result the other way round). Their matrices (K, F, P) are not point sets.
_CV_POINT_SETS = {"convertPointsFromHomogeneous": (0,), "convertPointsToHomogeneous": (0,),
                  "perspectiveTransform": (0,), "undistortPoints": (0,), "computeCorrespondEpilines": (0,),
                  "projectPoints": (0,), "findHomography": (0, 1), "findFundamentalMat": (0, 1),
                  "findEssentialMat": (0, 1), "solvePnP": (0, 1), "solvePnPRansac": (0, 1),
                  "estimateAffine2D": (0, 1), "estimateAffinePartial2D": (0, 1), "getAffineTransform": (0, 1),
                  "getPerspectiveTransform": (0, 1), "triangulatePoints": (2, 3), "recoverPose": (1, 2)}


def _cv_points(node, parent) -> bool:
    """A name (or part of one) given to an OpenCV function as a point set: given as columns where rows belong."""
    if not (isinstance(parent, ast.Call) and isinstance(node, (ast.Name, ast.Subscript))
            and _dotted(parent.func).startswith(("cv2.", "cv."))):
        return False
    positions = _CV_POINT_SETS.get(_dotted(parent.func).rsplit(".", 1)[-1], ())
    return any(p < len(parent.args) and parent.args[p] is node for p in positions)


# OpenCV functions that return their points as an (N, 1, k) array
_NESTED_POINTS = {"convertPointsToHomogeneous", "convertPointsFromHomogeneous", "perspectiveTransform",
                  "undistortPoints", "undistortPointsIter", "computeCorrespondEpilines"}
_PER_ROW_REDUCTIONS = {"norm", "sum", "mean", "max", "min", "std", "var", "amax", "amin", "median", "nansum",
                       "nanmean"}   # (reductions whose value per row may be kept as a column: keepdims)


def _scaled_identity(node) -> str | None:
    """The factor of a 3 x 3 identity scaled whole (`f * np.eye(3)`, `np.eye(3) * f`): an intrinsic matrix
    whose last entry must stay 1; None otherwise."""
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult)):
        return None
    for eye, factor in ((node.left, node.right), (node.right, node.left)):
        if isinstance(eye, ast.Call) and _dotted(eye.func).rsplit(".", 1)[-1] in ("eye", "identity") \
                and len(eye.args) == 1 and isinstance(eye.args[0], ast.Constant) and eye.args[0].value == 3 \
                and isinstance(factor, (ast.Name, ast.Attribute, ast.Subscript)):
            return ast.unparse(factor)
    return None


def _cv_point_pair(node) -> bool:
    """An OpenCV call given two point sets (``cv2.triangulatePoints(P1, P2, pts1, pts2)``), each a name
    or a part of one: one slip made for both (rows where OpenCV reads columns) is one change."""
    if not (isinstance(node, ast.Call) and _dotted(node.func).startswith(("cv2.", "cv."))):
        return False
    positions = _CV_POINT_SETS.get(_dotted(node.func).rsplit(".", 1)[-1], ())
    return len(positions) == 2 and all(p < len(node.args) and isinstance(node.args[p], (ast.Name, ast.Subscript))
                                       for p in positions)


def _index_phrase(inner, elements, position, value, other) -> str:
    if not inner:
        return ""
    if len(elements) == 2 and position == 1 and _whole_slice(elements[0]):
        names = {0: "x coordinates (column 0)", 1: "y coordinates (column 1)", 2: "values in column 2"}
        return f"the {names[other]} of {inner} are used where the {names[value]} belong"
    if len(elements) == 1:
        return f"element {other} of {inner} is used where element {value} belongs"
    if len(elements) == 2 and position == 0 and _whole_slice(elements[1]):
        return f"row {other} of {inner} is used where row {value} belongs"
    return f"another index ({other} for {value}) is used in {inner}"


def unpacked_items(fn) -> list[set]:
    """The sets of names a loop's item is unpacked into by an assignment in the loop (`for pair in
    matches:` then `m, n = pair`): the parts of one item, as a loop's own tuple target makes them."""
    items = set()
    for loop in walk(fn):
        if isinstance(loop, (ast.For, ast.comprehension)):
            items |= {n.id for n in walk(loop.target) if isinstance(n, ast.Name)}
    found = []
    for node in walk(fn):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Tuple) \
                and isinstance(node.value, ast.Name) and node.value.id in items:
            names = {n.id for n in node.targets[0].elts if isinstance(n, ast.Name)}
            if len(names) >= 2:
                found.append(names)
    return found


def _sibling_item_read(node: ast.Name, parent, words) -> bool:
    """In the student's code, an attribute read of a loop item with siblings (`m.distance` where `m, n`
    come from one pair): `n.distance < 0.75 * m.distance` has the two exchanged."""
    return words.student and isinstance(parent, ast.Attribute) and parent.value is node \
        and bool(words.zipped.get(node.id))


def _replaceable(node: ast.Name, parent, student: bool = False) -> bool:
    if isinstance(parent, ast.Call) and parent.func is node:
        return False
    if isinstance(parent, ast.Compare) and _mode_test(parent):
        return False   # (`cost == "ssd"` -> `block_size == "ssd"` runs another mode's code: no slip)
    if isinstance(parent, ast.Attribute):
        return False
    if student and isinstance(parent, ast.Assign) and parent.value is node:
        return True   # (a value copied as it is: `poses[i, 3:] = rvec` where `tvec` belongs)
    # (a slice's bound too: `canvas[:h2, w2:]` where img2 goes right of img1, at `w1:`)
    return isinstance(parent, (ast.Call, ast.BinOp, ast.Subscript, ast.Return, ast.keyword, ast.Tuple,
                               ast.List, ast.UnaryOp, ast.Compare, ast.Slice))


_RESHAPING_METHODS = {"reshape", "ravel", "flatten", "T", "astype"}   # (not copy: `image.copy()` in a loop is the carry operator's)
_TWIN_WORDS = {frozenset(pair) for pair in (("left", "right"), ("src", "dst"), ("l", "r"), ("x", "y"), ("u", "v"),
                                            ("rows", "cols"), ("h", "w"), ("height", "width"), ("first", "second"))}


_TWIN_LETTERS = {frozenset("xy"), frozenset("uv")}


def twin_names(a: str, b: str) -> bool:
    """Whether two names are twins: one digit apart (`R1`/`R2`, `x1`/`x2`) or a pair's other half
    (`left`/`right`, `src`/`dst`, `l`/`r` in `img_l`/`img_r`); names only, not numbers."""
    if not (a.isidentifier() and b.isidentifier()):
        return False
    differing = [frozenset((x, y)) for x, y in zip(a, b) if x != y] if len(a) == len(b) else []
    if len(differing) == 1 and (any(x.isdigit() for x in differing[0]) or differing[0] in _TWIN_LETTERS):
        return True   # (`x1`/`x2`; `sx`/`sy`, `tx`/`ty`: the two axes' halves of a pair)
    parts_a, parts_b = a.split("_"), b.split("_")
    return len(parts_a) == len(parts_b) and sum(x != y for x, y in zip(parts_a, parts_b)) == 1 and any(
        frozenset((x, y)) in _TWIN_WORDS for x, y in zip(parts_a, parts_b) if x != y)


def _copies_of(name: str, words, line: int) -> set:
    """The locals defined above ``line`` as a copy of ``name`` (`out = canvas.copy()`, `np.copy(canvas)`), and the
    one ``name`` is a copy of."""
    def copied(value):
        if isinstance(value, ast.Call) and isinstance(value.func, ast.Attribute) and value.func.attr == "copy" \
                and not value.args and isinstance(value.func.value, ast.Name):
            return value.func.value.id
        if isinstance(value, ast.Call) and _dotted(value.func) in ("np.copy", "numpy.copy", "copy.copy", "copy.deepcopy") \
                and value.args and isinstance(value.args[0], ast.Name):
            return value.args[0].id
        return None
    found = set()
    for other, defs in words.definitions.items():
        for at, value, index in defs:
            if at >= line or index is not None:
                continue
            source = copied(value)
            if source == name and other != name:
                found.add(other)
            if other == name and source and source != name:
                found.add(source)
    return found


def _made_from_since(words: _Words, other: str, name: str, line: int) -> bool:
    """Whether ``other``'s last value before ``line`` was made from ``name`` -- reading it, or a value made from it
    in turn (`Xh = np.hstack([pts, 1])`, then `x = P @ Xh`: both made from `pts`) -- after ``name``'s own last value."""
    given = [at for at, _, _ in words.definitions.get(name, ()) if at < line]
    if not given:
        return False
    return other in _made_since(words, name, given[-1], line)


_MADE_SINCE_REACH = 64   # assignments after a name's value followed for the values made from it, at most


def _made_since(words: _Words, name: str, since: int, line: int) -> frozenset:
    """The locals whose last value before ``line``, given after line ``since``, is made from ``name`` directly or
    through one another (one pass over the def's assignments, read once per def; kept per name and lines)."""
    if not hasattr(words, "_assignments_read"):
        words._assignments_read = sorted(
            (at, other, frozenset(n.id for n in walk(value) if isinstance(n, ast.Name)))
            for other, defs in words.definitions.items() for at, value, _ in defs)
        words._made_since = {}
    key = (name, since, line)
    if key not in words._made_since:
        made, sources = set(), {name}
        first = bisect.bisect_right(words._assignments_read, (since, "\uffff"))
        # (in the order they were made, each may read the ones before; the few dozen after the name's value only:
        # every use of a name asks, and a long def is read in linear time)
        for at, other, reads in words._assignments_read[first:first + _MADE_SINCE_REACH]:
            if at >= line:
                break
            if at <= since or other == name:
                continue
            if reads & sources:
                made.add(other)
                sources.add(other)
            else:   # (given a value of another making since: its last value is not made from the name)
                made.discard(other)
                sources.discard(other)
        words._made_since[key] = frozenset(made)
    return words._made_since[key]


def _name_changes(node: ast.Name, words: _Words, what, line):
    if node.id in ("np", "cv2", "math", "None", "True", "False"):
        return
    own = what(node)
    if not own:
        return
    params = {a.arg for a in words.fn.args.args + words.fn.args.kwonlyargs}
    others = []
    for other in words.locals_before(line, nearest=_NEAREST_LOCALS if words.student else None):
        if other == node.id or other in words.module_defs or other == "_":   # (`_` is thrown away)
            continue
        phrase = words.what(ast.Name(other, ast.Load()), line=line)
        if phrase and phrase != own:
            others.append((other, phrase))
    unread = set()
    if words.student:   # (the parts of one item, made on this very line: `n.distance < 0.75 * m.distance`)
        listed = {other for other, _ in others}
        others += [(other, f"`{other}`") for other in sorted(words.zipped.get(node.id, ())) if other not in listed]
        # (a loop variable nothing reads, of a loop on this line or above it: tried first)
        unread = {name for at in words.loops_up_to(line) for name in words.unread_loop_names[at]} - {node.id}
        # (and a local assigned above and never read anywhere: `n1, T1 = normalise(p1)` with the rows built
        # from p1 -- the value made for this use, left out of it)
        if not hasattr(words, "unread_locals"):
            loaded = {n.id for n in walk(words.fn) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
            words.unread_locals = {name for name in words.definitions if name not in loaded and not name.startswith("_")}
        unread |= {name for name in words.unread_locals if name != node.id
                   and any(at < line for at, _, _ in words.definitions[name])}
        listed = {other for other, _ in others}
        others += [(other, f"`{other}`") for other in sorted(unread) if other not in listed]
        # (and a copy of the name made above, or the name it copies: `cv2.line(canvas, ...)` where the copy `out =
        # canvas.copy()` the circles are drawn on, and returned, belongs -- told alike, so not among the others)
        copies = _copies_of(node.id, words, line)
        unread |= copies   # (tried first, with the loop variables nothing reads)
        listed = {other for other, _ in others}
        others += [(other, f"`{other}`") for other in sorted(copies) if other not in listed]
    # Two names told alike (`img2`, and its float copy told as `img2` too): only the one of the
    # replaced name's kind (a parameter for a parameter, a local for a local) is that mistake; the
    # other one also drops the copy's conversion, which its sentence would not say.
    kind = node.id in params
    alike = {phrase for other, phrase in others if (other in params) == kind}
    # A copy-paste slip takes a name's sibling: one unpacked with it (`u, v = ...`), or the same
    # array's other part ("column 0 of `dst`" for "column 1 of `dst`"); those are tried first.
    together = {other for line_at, value, _ in words.definitions.get(node.id, ())
                for other, defs in words.definitions.items() if any(d[0] == line_at and d[1] is value for d in defs)}
    together |= words.zipped.get(node.id, set()) if words.student else set()
    tail = own.rsplit(" of ", 1)[-1]
    # (then the name's twin: `x1` for `x2`, a line copied from image 2's with its names half changed)
    # (and a processed version of the name, or the raw one it came from: `x_norm` for `x`, `pts` for
    # `pts_h` -- the raw points used where their normalised copy belongs, or the other way round)
    # (then, in the student's code, a name of the same kind -- a local for a local -- that the line's
    # other values were made from: `patterns[i][cols[lit]]` with `lit` made from `proj`, the projector's
    # columns where the camera's were read)
    # (first of all, a name written in the other case: `Z`, a point's own depth, where `z`, the common one,
    # belongs)
    related = words.related(line) if words.student else frozenset()
    # (and, in the student's code, a value made from this name since it was last given -- `b = prev ^ g` for `g`,
    # the Gray bit converted to binary: the conversion made for this use, the raw value read instead; tried first)
    # (not one `derived_name` offers, beside a sibling read in that form: told as that)
    converted = {other for other, _ in others if words.student and _made_from_since(words, other, node.id, line)}
    converted -= {name for _, name, _ in _raw_beside_derived(node, words)} if converted else set()
    # (of the values made from it, the last made first: the one nearest the use, `x = P @ Xh` before `Xh`)
    made_at = {other: max(d[0] for d in words.definitions[other] if d[0] < line) for other in converted}
    others.sort(key=lambda pair: (pair[0] not in unread, pair[0] not in converted, -made_at.get(pair[0], 0),
                                  pair[0].lower() != node.id.lower(), pair[0] not in together,
                                  not twin_names(node.id, pair[0]),
                                  not _derived_names(node.id, pair[0]) and not _one_stem(node.id, pair[0]),
                                  not (pair[0] in related and (pair[0] in params) == kind),
                                  pair[1].rsplit(" of ", 1)[-1] != tail or " of " not in own))
    count, twin_given = 0, False
    for other, phrase in others:
        if (other in params) != kind and phrase in alike and not _derived_names(node.id, other):
            continue   # (a processed copy and its raw name -- `new_K` and `K` -- are tried whatever their kinds)
        if words.helper_params and other not in together and not twin_names(node.id, other) and (
                " of " not in phrase or " of " not in own or phrase.rsplit(" of ", 1)[-1] != tail):
            continue   # in a private helper, only a sibling's or a twin's copy-paste slip (the count stays small)
        twin = twin_names(node.id, other)
        if count >= _OTHER_NAMES_PER_SITE and (twin_given or not twin):
            continue   # (the name's twin is tried whatever comes before it: `w` for `h` in an else-branch, below the
            #            four values the if-branch made from `w`)
        yield "other_name", other, f"{phrase} {_plural(phrase, 'is', 'are')} used where {own} " \
                                   f"{_plural(own, 'belongs', 'belong')}"
        count += 1
        twin_given |= twin


def _every(step: int) -> str:
    """'every element', 'every second element', ... for a slice's step."""
    return "every element" if step == 1 else f"every {_INDEX_WORDS.get(step - 1, f'{step}th')} element"


def _derived_names(a: str, b: str) -> bool:
    """Whether one name is the other with a suffix (`x` / `x_norm`, `pts` / `pts_h`, `K` / `Kn`), or with a
    prefix of its own word (`K` / `new_K`, `pts` / `raw_pts`)."""
    short, long = sorted((a, b), key=len)
    return short != long and (long.startswith(short) and (long[len(short)] == "_" or len(long) - len(short) <= 2)
                              or long.endswith("_" + short))


def _one_stem(a: str, b: str) -> bool:
    """Whether two names are one word's two variants (`z_mean` / `z_avg`, `pts_norm` / `pts_raw`): the same
    stem before their first underscore, told apart after it."""
    stem_a, _, rest_a = a.partition("_")
    stem_b, _, rest_b = b.partition("_")
    return bool(stem_a) and stem_a == stem_b and bool(rest_a) and bool(rest_b) and a != b


def _line_name_changes(node: ast.Assign, words: _Words, line):
    """A line copied from its sibling's with one name left unchanged everywhere in it (``dst_n = dst
    @ T1[:2, :2].T + T1[:2, 2]`` under ``src_n = src @ T1...``): each local read twice or more in
    the value, replaced throughout by a name unpacked with it (``T1, T2 = ...``)."""
    counts = {}
    for name in walk(node.value):
        if isinstance(name, ast.Name) and isinstance(name.ctx, ast.Load):
            counts[name.id] = counts.get(name.id, 0) + 1
    for name, count in sorted(counts.items()):
        if count < 2 or name not in words.definitions:
            continue
        own = words.what(ast.Name(name, ast.Load()), line=line)
        siblings = {other for line_at, value, _ in words.definitions[name] for other, defs in words.definitions.items()
                    if other != name and any(d[0] == line_at and d[1] is value for d in defs)}
        for other in sorted(siblings):
            phrase = words.what(ast.Name(other, ast.Load()), line=line)
            if own and phrase and phrase != own:
                yield "other_name_line", (name, other), f"{phrase} {_plural(phrase, 'is', 'are')} used where {own} " \
                                                        f"{_plural(own, 'belongs', 'belong')}, everywhere in one line"


def _plural(phrase: str, one: str, many: str) -> str:
    """``many`` for a phrase naming several things ("the x coordinates (column 0) of ...", "the
    source points"), else ``one``."""
    head = re.sub(r" \(.*?\)", "", phrase).split(" of ", 1)[0]
    return many if head.endswith(("coordinates", "points", "values", "vectors")) else one


def _statement_phrase(node, words: _Words, line) -> str:
    target = node.target if isinstance(node, ast.AugAssign) else (node.targets[0] if len(node.targets) == 1 else None)
    if isinstance(target, ast.Subscript):
        inner = words.what(target, line=line + 1)
        return f"{inner} is never set (that step is missing)" if inner else ""
    if isinstance(target, ast.Name):
        earlier = [d for d in words.definitions.get(target.id, ()) if d[0] < node.lineno]
        is_param = target.id in {a.arg for a in words.fn.args.args}
        if isinstance(node, ast.AugAssign) or earlier or is_param:
            before = words.what(ast.Name(target.id, ast.Load()), line=node.lineno)
            change = words.what(node.value if isinstance(node, ast.Assign) else node, line=node.lineno + 1)
            if isinstance(node, ast.AugAssign):
                verb = {ast.Div: "divided by", ast.Mult: "multiplied by", ast.Add: "increased by",
                        ast.Sub: "decreased by"}.get(type(node.op))
                amount = words.what(node.value, line=node.lineno)
                if before and verb and amount:
                    return f"{before} is never {verb} {amount} (that step is missing)"
            if before and change and change != before:
                return f"{before} is used as it was, without the update to {change}"
    return ""


