"""Naming a failure with the error model: the reference's mutants, confirmed on the student's inputs.

When a check fails, :func:`name_failure` takes the calls the check made
(:attr:`~autograder.engine.checks.Trial.calls`: function, arguments, the student's answer),
runs the reference and each mutant of the function (:mod:`.operators`) on the same inputs
in the helper process (:mod:`.helper`), and keeps the *candidates*: mutants that reproduce
the student's answers on every call of that function in the trial -- much closer to the
student's answer than the reference is, and within a small tolerance. Then it derives
*confirmation inputs* from the failing ones (the same shapes and types, other values),
keeps those on which the candidates (and the reference) disagree, asks the student's
function for its answers there (through the sandbox; what it prints is labelled as the
grader's confirmation call) and keeps the candidates that reproduce those too. A mistake
is named only when the candidates left agree with each other everywhere (equivalent
mutants: the simplest operator's sentence); otherwise nothing is said. When no single
mutant reproduces, pairs of the mutants that each come closer to the student than the
reference are tried (a few).

Time is bounded: a few seconds per failed check, a total per grading (kept on the
sandbox), a timeout per mutant (the helper is killed and restarted). Without the
reference module (a copy of the grader without ``reference_solutions/``) nothing is named.
"""

from __future__ import annotations

import ast
import atexit
import functools
import itertools
import os
import re
import threading
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ...loading.parsing import compile_source, copy_tree, parse, walk
from ...sandbox import evidence
from ..inplace import MISTAKE as IN_PLACE
from .helper import ERROR, Helper, HelperFailed
from .operators import Mutant, _dotted, _parents, mutants_of, mutated_defs

CHECK_SECONDS = 3.0        # the error model's time for one failed check
GRADING_SECONDS = 10.0     # and for one grading (all its failed checks): bounds what failing everything costs
SPENT = "error model seconds"   # the key of the grading's counter of it (runner: one per grading, every worker)
CALLS_PER_FUNCTION = 6     # the trial's last calls of a function that are compared
PAIR_MUTANTS = 6           # the closest single mutants combined in pairs
VARIANTS_PER_CALL = 5      # confirmation inputs derived from each failing call
CONFIRMATIONS = 3          # of which the student's function is asked at most this many
PROJECT_ROOT = Path(__file__).resolve().parents[3]


@dataclass(frozen=True)
class Naming:
    """A confirmed mistake: the mutant, and the evidence (calls compared, confirmation calls)."""

    mutant: Mutant
    calls: int
    confirmations: int

    @property
    def sentence(self) -> str:
        return self.mutant.sentence

    @property
    def mistake(self) -> str:
        return f"mutant:{self.mutant.operator}"


# ------------------------------------------------------------------ the lab's error model
@dataclass(frozen=True)
class ErrorModel:
    """A lab's reference module and its mutants per graded function."""

    module: str
    source: str
    mutants: dict
    defaults: dict   # function -> [(parameter, position, default)] for its numeric defaults
    optional: dict = field(default_factory=dict)   # function -> [(parameter, position, None)]
    modes: dict = field(default_factory=dict)      # function -> [(parameter, position, default, values)]
    twins: dict = field(default_factory=dict)      # function -> [(position, position)] of twin parameters
    resolved: dict = field(default_factory=dict)   # function -> [(parameter, position, number)]: None stands for it


def _numeric_defaults(source: str) -> dict:
    """function -> [(parameter, position, default)] for the parameters with a number as default
    (confirmation inputs vary them too: a mistake may hide behind a default)."""
    return _defaults(source, lambda value: isinstance(value, (int, float)) and not isinstance(value, bool))


def _none_defaults(source: str) -> dict:
    """function -> [(parameter, position, None)] for the parameters that default to None (an
    exception raised on a value given there is confirmed on the call without it)."""
    return _defaults(source, lambda value: value is None)


def _resolved_defaults(source: str) -> dict:
    """function -> [(parameter, position, number)] for the parameters defaulting to None that the def
    resolves to a fixed number (`s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)`,
    `if p is None: p = 6.0`; a module constant or a literal). Confirmation gives them a value too: a
    change right only with the default's own number (`s` -> `block_size`, 5 beside a default of 6) is
    wrong where the caller chooses it."""
    tree = parse(source, max_chars=None, max_statements=None)   # the reference, under the lock
    constants = {}
    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            value = _number(node.value, {})
            if value is not None:
                constants[node.targets[0].id] = value

    def tested(test, name) -> bool:   # `name is None`
        return isinstance(test, ast.Compare) and isinstance(test.left, ast.Name) and test.left.id == name \
            and len(test.ops) == 1 and isinstance(test.ops[0], ast.Is) \
            and isinstance(test.comparators[0], ast.Constant) and test.comparators[0].value is None

    out = {}
    for def_ in (n for n in tree.body if isinstance(n, ast.FunctionDef)):
        for name, position, _ in _none_defaults_of(def_):
            for node in walk(def_):
                value = None
                if isinstance(node, ast.IfExp) and tested(node.test, name):
                    value = _number(node.body, constants)
                elif isinstance(node, ast.If) and tested(node.test, name) and len(node.body) == 1 \
                        and isinstance(node.body[0], ast.Assign):
                    value = _number(node.body[0].value, constants)
                if value is not None:
                    out.setdefault(def_.name, []).append((name, position, value))
                    break
    return out


def _number(node, constants):
    """The number ``node`` writes (a literal, or a name in ``constants``); None otherwise."""
    if isinstance(node, ast.Name):
        return constants.get(node.id)
    try:
        value = ast.literal_eval(node)
    except ValueError:
        return None
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def _none_defaults_of(def_: ast.FunctionDef) -> list:
    """[(parameter, position, None)] for the def's parameters defaulting to None."""
    params = def_.args.args
    first = len(params) - len(def_.args.defaults)
    return [(params[first + offset].arg, first + offset, None) for offset, default in enumerate(def_.args.defaults)
            if isinstance(default, ast.Constant) and default.value is None]


def _defaults(source: str, keep) -> dict:
    import ast

    out = {}
    for node in parse(source, max_chars=None, max_statements=None).body:  # the reference, under the lock
        if isinstance(node, ast.FunctionDef):
            params = node.args.args
            found = []
            for offset, default in enumerate(node.args.defaults):
                position = len(params) - len(node.args.defaults) + offset
                try:
                    value = ast.literal_eval(default)
                except ValueError:
                    continue
                if keep(value):
                    found.append((params[position].arg, position, value))
            out[node.name] = found
    return out


def _modes(source: str) -> dict:
    """function -> [(parameter, position, default, values)] for the parameters that choose a mode by
    name: a string default, compared in the function with string constants (``cost="ssd"``; "ncc").
    A change made where every mode reads it is confirmed on the other modes too."""
    import ast

    tree = parse(source, max_chars=None, max_statements=None)   # the reference, under the lock
    named = {}   # a name -> the strings it is compared with anywhere (a helper given the parameter)
    for compare in (n for n in walk(tree) if isinstance(n, ast.Compare) and isinstance(n.left, ast.Name)):
        for right in compare.comparators:
            values = [right] if isinstance(right, ast.Constant) else \
                list(right.elts) if isinstance(right, (ast.Tuple, ast.List, ast.Set)) else []
            named.setdefault(compare.left.id, set()).update(
                v.value for v in values if isinstance(v, ast.Constant) and isinstance(v.value, str))
    out = {}
    for node in tree.body:
        if not isinstance(node, ast.FunctionDef):
            continue
        found = []
        for parameter, position, default in _defaults(source, lambda value: isinstance(value, str)).get(node.name, ()):
            if len(named.get(parameter, ())) > 1 and default in named[parameter]:
                found.append((parameter, position, default, tuple(sorted(named[parameter]))))
        out[node.name] = found
    return out


def _twin_parameters(source: str) -> dict:
    """function -> [(position, position), ...]: its parameters that come in twin pairs (`img1`/`img2`,
    `pts1`/`pts2`, `img_l`/`img_r`, `src`/`dst`): exchanging every pair at once gives another input of
    the same kind, the roles of the two views turned round."""
    import ast

    from .operators import twin_names

    out = {}
    for node in parse(source, max_chars=None, max_statements=None).body:
        if isinstance(node, ast.FunctionDef):
            names = [a.arg for a in node.args.args]
            pairs, used = [], set()
            for i, a in enumerate(names):
                for j in range(i + 1, len(names)):
                    if i not in used and j not in used and twin_names(a, names[j]):
                        pairs.append((i, j, a, names[j]))
                        used |= {i, j}
            out[node.name] = pairs
    return out


def twins_exchanged(call, pairs) -> list:
    """``call`` with every twin pair of its arguments exchanged, given by position or by keyword
    (`scale(image, sx=2.0, sy=0.8)` -> `sy=2.0, sx=0.8`); [] when it gives neither of any pair both."""
    function, args, kwargs = call
    turned, named, exchanged = list(args), dict(kwargs), False
    for i, j, first, second in pairs:
        values = [turned[i] if i < len(turned) else named.get(first, _ABSENT),
                  turned[j] if j < len(turned) else named.get(second, _ABSENT)]
        if any(value is _ABSENT for value in values):   # (`is`: arrays compare entry by entry)
            continue
        for position, name, value in ((i, first, values[1]), (j, second, values[0])):
            if position < len(turned):
                turned[position] = value
            else:
                named[name] = value
        exchanged = True
    return [(function, tuple(turned), named)] if exchanged else []


_ABSENT = object()


def other_channels(call) -> list:
    """``call`` with its images in the other numbers of channels: BGR images (uint8, (H, W, 3)) made
    grey, grey ones (uint8, (H, W)) made BGR; with two images, every other mix of the two (grey and
    grey, BGR and BGR, each turned alone: a test of the first image's channels made where the second's
    belongs mends a BGR-and-grey call and breaks the grey-and-grey one); with more, all turned, all
    grey and all BGR ([] when it has no image). All are images a caller may give."""
    import cv2

    function, args, kwargs = call
    image = lambda v: isinstance(v, np.ndarray) and v.dtype == np.uint8 and min(v.shape[:2], default=0) >= 8 \
        and (v.ndim == 2 or (v.ndim == 3 and v.shape[2] == 3))  # noqa: E731
    as_grey = lambda v: cv2.cvtColor(v, cv2.COLOR_BGR2GRAY) if v.ndim == 3 else v  # noqa: E731
    as_bgr = lambda v: cv2.cvtColor(v, cv2.COLOR_GRAY2BGR) if v.ndim == 2 else v  # noqa: E731
    places = [("a", i) for i, a in enumerate(args) if image(a)] + [("k", k) for k, v in kwargs.items() if image(v)]
    if not places:
        return []
    grey_now = tuple((args[i] if kind == "a" else kwargs[i]).ndim == 2 for kind, i in places)
    if len(places) == 2:
        mixes = [mix for mix in itertools.product((True, False), repeat=2) if mix != grey_now]
        mixes.sort(key=lambda mix: mix != tuple(not g for g in grey_now))   # (all turned first, as before)
    else:
        mixes = list(dict.fromkeys([tuple(not g for g in grey_now), (True,) * len(places), (False,) * len(places)]))
        mixes = [mix for mix in mixes if mix != grey_now]
    made = []
    for mix in mixes:
        new_args, new_kwargs = list(args), dict(kwargs)
        for (kind, i), grey in zip(places, mix):
            value = args[i] if kind == "a" else kwargs[i]
            value = as_grey(value) if grey else as_bgr(value)
            if kind == "a":
                new_args[i] = value
            else:
                new_kwargs[i] = value
        made.append((function, tuple(new_args), new_kwargs))
    return made


def mode_calls(call, modes) -> list:
    """Copies of ``call`` (function, args, kwargs) in each other mode its function has (``modes``:
    see :func:`_modes`)."""
    function, args, kwargs = call
    made = []
    for parameter, position, default, values in modes:
        given = args[position] if position < len(args) else kwargs.get(parameter, default)
        for value in values:
            if value == given:
                continue
            if position < len(args):
                made.append((function, args[:position] + (value,) + args[position + 1:], dict(kwargs)))
            else:
                made.append((function, tuple(args), {**kwargs, parameter: value}))
    return made


_MODELS: dict = {}
_MODELS_LOCK = threading.Lock()


def reference_module(lab) -> Path | None:
    """The lab's reference solution module (a course lab's ``reference/``), None when absent."""
    from ..labfolders import REFERENCE, lab_folder

    loaded = lab_folder(lab)
    installed = os.environ.get("AUTOGRADER_REFERENCE_SOLUTIONS")   # the Gradescope container's copy
    folder = loaded.folder / REFERENCE if loaded is not None else \
        Path(installed) if installed else PROJECT_ROOT / "reference_solutions"
    path = folder / f"{lab.module}.py"
    return path if path.is_file() else None


def model_for(lab) -> ErrorModel | None:
    """The lab's error model (made once per process); None without a reference."""
    path = reference_module(lab)
    if path is None:
        return None
    with _MODELS_LOCK:
        key = (lab.key, str(path), path.stat().st_mtime_ns)
        if key not in _MODELS:
            source = path.read_text(encoding="utf-8")
            api = {name for exercise in lab.exercises.values() for name in exercise.signatures}
            try:
                mutants = mutants_of(source, api)
            except SyntaxError:
                return None
            for function in mutants:  # simplest first: the time may end before the last
                mutants[function].sort(key=lambda m: m.rank)
            _MODELS[key] = ErrorModel(lab.module, source, mutants, _numeric_defaults(source), _none_defaults(source),
                                      _modes(source), _twin_parameters(source), _resolved_defaults(source))
        return _MODELS[key]


_IDLE: list[Helper] = []          # helper processes not naming right now (kept between gradings)
_ALL_HELPERS: list[Helper] = []
_POOL_LOCK = threading.Lock()
_USING = threading.local()


def helper() -> Helper:
    """The helper this thread is naming with (taken from the idle ones, else a new one): as many
    helpers as lanes name at once, each started at its first use and kept for the next grading."""
    current = getattr(_USING, "helper", None)
    if current is None:
        with _POOL_LOCK:
            current = _IDLE.pop() if _IDLE else None
            if current is None:
                current = Helper()
                _ALL_HELPERS.append(current)
        _USING.helper = current
    return current


def release_helper() -> None:
    """Let this thread's reference helper go (another naming may take it)."""
    current = getattr(_USING, "helper", None)
    if current is not None:
        _USING.helper = None
        with _POOL_LOCK:
            _IDLE.append(current)


@atexit.register
def close_helpers() -> None:
    for each in _ALL_HELPERS:
        each.close()


# ------------------------------------------------------------------ comparing answers
def _leaves(value, out: list) -> bool:
    """Flatten an answer into arrays and other leaves; False for an error."""
    if isinstance(value, dict) and ERROR in value:
        return False
    if isinstance(value, (tuple, list)) and not (value and all(isinstance(v, (int, float)) for v in value)):
        out.append(("seq", len(value)))
        return all(_leaves(v, out) for v in value)
    if isinstance(value, dict):
        out.append(("dict", tuple(sorted(map(str, value)))))
        return all(_leaves(value[k], out) for k in sorted(value, key=str))
    if isinstance(value, (np.ndarray, int, float, tuple, list)) and not isinstance(value, bool):
        try:
            out.append(np.asarray(value))
        except (ValueError, TypeError):
            out.append(("other", repr(value)))
        return True
    out.append(("other", repr(value)))
    return True


def numeric_pairs(a, b) -> list | None:
    """The two answers' numeric arrays side by side; None when their forms differ (different
    structures, shapes, non-numeric leaves that are not equal): infinitely far apart then."""
    left, right = [], []
    if not (_leaves(a, left) and _leaves(b, right)) or len(left) != len(right):
        return None
    pairs = []
    for x, y in zip(left, right):
        if isinstance(x, tuple) or isinstance(y, tuple):
            if not (isinstance(x, tuple) and isinstance(y, tuple) and x == y):
                return None
            continue
        if x.shape != y.shape or x.dtype.kind not in "biufc" or y.dtype.kind not in "biufc":
            return None
        pairs.append((x, y))
    return pairs


def distance(a, b, lenient: bool = False, projective: bool = False) -> float:
    """How far answer ``a`` is from ``b``: the largest mean absolute difference of their arrays
    (small matrices also compared up to scale and sign, as the checks do); infinite when
    their structure, shapes or NaN places differ, or one is an error.

    ``lenient``: ``a`` (a mutant's answer) may have NaN where ``b`` has numbers, in fewer than
    half the places (the reference marks points behind the camera NaN; a student who does not
    still makes the mutant's mistake everywhere else). ``projective``: small matrices (up to 16
    entries) are compared up to scale and sign, as checks of homographies and fundamental
    matrices do."""
    pairs = numeric_pairs(a, b)
    if pairs is None:
        return float("inf")
    worst = 0.0
    for x, y in pairs:
        if x.dtype.kind in "biu" and y.dtype.kind in "biu":  # images: no NaN, no float copies
            worst = max(worst, float(np.mean(np.abs(x.astype(np.int64) - y))) if x.size else 0.0)
            continue
        kind = np.complex128 if "c" in x.dtype.kind + y.dtype.kind else np.float64
        x, y = x.astype(kind, copy=False), y.astype(kind, copy=False)
        nan_x, nan_y = ~np.isfinite(x), ~np.isfinite(y)
        if not np.array_equal(nan_x, nan_y):
            if not (lenient and not (nan_y & ~nan_x).any() and nan_x.mean() < 0.5):
                return float("inf")
            x, y = x[~nan_x], y[~nan_x]
            nan_x = nan_y = np.zeros(x.shape, bool)
        if x.size == 0 or nan_x.all():
            continue
        raw = float(np.mean(np.abs(x[~nan_x] - y[~nan_y])))
        if projective and (x.ndim == 2 and x.size <= 16 or x.ndim == 1 and x.size in (3, 4)) and not nan_x.any():
            # (a small matrix, or a homogeneous vector: an epipole, a line, a point of P^3)
            raw = min(raw, _up_to_scale(x, y))
        worst = max(worst, raw)
    return worst


def _up_to_scale(x, y) -> float:
    nx, ny = np.linalg.norm(x), np.linalg.norm(y)
    if nx == 0 or ny == 0:
        return float("inf")
    xs, ys = x / nx, y / ny
    if np.real(np.vdot(xs, ys)) < 0:
        xs = -xs
    return float(np.mean(np.abs(xs - ys))) * ny / np.sqrt(x.size)


def _scale(value) -> float:
    leaves = []
    _leaves(value, leaves)
    sizes = [np.abs(v[np.isfinite(v)]).mean() for v in leaves
             if isinstance(v, np.ndarray) and v.dtype.kind in "iuf" and np.isfinite(v).any()]
    return float(max(sizes, default=1.0))


_MEASURED: dict = {}   # id(answer) -> (answer, tolerance), for one naming (answers are compared often)


def forget_measures() -> None:
    """End one naming's measures of answers (kept by identity: the answers go with the naming)."""
    _MEASURED.clear()


def _measures(value) -> tuple[float, float]:
    """(tolerance, scale) of an answer, measured once per naming."""
    kept = _MEASURED.get(id(value))
    if kept is not None and kept[0] is value:
        return kept[1]
    measured = (_measured_tolerance(value), _scale(value))
    _MEASURED[id(value)] = (value, measured)
    return measured


def _tolerance(value) -> float:
    """A difference too small to tell two answers apart (images: half a grey level)."""
    return _measures(value)[0]


def _measured_tolerance(value) -> float:
    leaves = []
    _leaves(value, leaves)
    if any(isinstance(v, np.ndarray) and v.dtype.kind in "iu" and v.size > 64 for v in leaves):
        return 0.5
    return 1e-5 * _scale(value) + 1e-9


def reproduces(mutant, student, reference) -> bool:
    """Whether the mutant's answer is the student's.

    Numbers (matrices, points): every entry within 1e-4 of the answer's size (another order
    of floating-point operations, not another value; a mutant that is merely close, as the
    identity is to a rotation by half a degree, is not the student's). Images: the mean absolute
    difference within half a grey level and the same pixels changed both ways (a drawing's thin
    lines move the mean little wherever they are), or else (another interpolation of the same warp)
    :data:`IMAGE_CLOSER` times smaller than the reference's, under 5% of the mean brightness,
    and the student's pixels where the mutant changes the reference's are the mutant's
    (:func:`_explains_changed_pixels`): a mutant sharing only part of a mistake (uint8
    arithmetic wrapped around, with two images exchanged besides) is ten times closer on
    average than the reference but disagrees with the student on a third of the pixels."""
    tolerance, scale = _measures(student)
    if not has_image(student):
        size = max(largest_entry(student), 1e-12)
        if not _non_finite_as_reference(mutant, student, reference):
            return False
        if _largest_difference(mutant, student) <= 1e-4 * size:
            return True
        return _largest_difference(mutant, student, projective=True) <= 1e-4 * size \
            and _largest_difference(reference, student, projective=True) > 1e-3 * size
    apart = distance(mutant, student, lenient=True)
    if apart <= tolerance:   # close on average; a drawing's few pixels must be the same ones too
        return _explains_changed_pixels(mutant, student, reference) and _explains_changed_pixels(student, mutant,
                                                                                                 reference)
    off = distance(reference, student)
    if not wrong(student, reference):   # the student is right here: the mutant must be as near
        return apart <= 2 * off
    return apart <= min(off / IMAGE_CLOSER, 0.05 * scale) and _explains_changed_pixels(mutant, student, reference)


def _non_finite_as_reference(mutant, student, reference) -> bool:
    """Whether the mutant's NaN and infinities, where the student's answer has numbers, are where the
    reference's are too: the leniency of :func:`distance` is for the reference's own marking (points
    behind the camera), not for a mutant dividing by zero where the student's code, like the
    reference, gives a number (a validity test made always true gives inf at d = 0, where the student
    tests d != 0 and gives 0). True when the forms differ (judged elsewhere)."""
    with_student, with_reference = numeric_pairs(mutant, student), numeric_pairs(mutant, reference)
    if with_student is None or with_reference is None:
        return True
    for (mine, theirs), (_, right) in zip(with_student, with_reference):
        if (~np.isfinite(mine) & np.isfinite(theirs) & np.isfinite(right)).any():
            return False
    return True


IMAGE_CLOSER = 30        # how many times closer than the reference a mutant's image must be to the student's
PIXEL_LEVELS = 3         # grey levels within which a pixel is "the same" (interpolations differ by one or two)
PIXELS_EXPLAINED = 0.9   # share of the pixels the mutant changes where the student's are the mutant's


def _explains_changed_pixels(mutant, student, reference) -> bool:
    """Whether, at the pixels of every image where the mutant differs from the reference by more
    than :data:`PIXEL_LEVELS`, the student's image is within :data:`PIXEL_LEVELS` of the mutant's
    at :data:`PIXELS_EXPLAINED` of them or more (the mistake is judged where it shows, not on
    average over pixels nobody changed). Answers of other forms: False."""
    mine, theirs, right = [], [], []
    if not (_leaves(mutant, mine) and _leaves(student, theirs) and _leaves(reference, right)) \
            or not len(mine) == len(theirs) == len(right):
        return False
    for m, s, r in zip(mine, theirs, right):
        if not (isinstance(m, np.ndarray) and isinstance(s, np.ndarray) and isinstance(r, np.ndarray)
                and s.dtype.kind in "iub" and s.ndim >= 2 and s.size > 64):
            continue   # numbers beside the image are judged by the distance
        if not m.shape == s.shape == r.shape or m.dtype.kind not in "biuf":
            return False
        m, s, r = (np.asarray(v, np.float64) for v in (m, s, r))
        per_pixel = (lambda d: d.max(axis=2) if d.ndim == 3 else d)   # colour: the worst channel
        changed = per_pixel(np.abs(m - r)) > PIXEL_LEVELS
        if changed.any() and (per_pixel(np.abs(m - s))[changed] <= PIXEL_LEVELS).mean() < PIXELS_EXPLAINED:
            return False
    return True


def has_image(value) -> bool:
    """Whether an answer holds an image: an integer or boolean array of two or more dimensions."""
    leaves = []
    _leaves(value, leaves)
    return any(isinstance(v, np.ndarray) and v.dtype.kind in "iub" and v.ndim >= 2 and v.size > 64 for v in leaves)


def largest_entry(value) -> float:
    """The largest finite magnitude among an answer's numbers (0 when it has none)."""
    leaves = []
    _leaves(value, leaves)
    sizes = [float(np.abs(v[np.isfinite(v)]).max()) for v in leaves
             if isinstance(v, np.ndarray) and v.dtype.kind in "iufc" and np.isfinite(v).any()]
    return max(sizes, default=0.0)


def _largest_difference(a, b, projective: bool = False) -> float:
    """The largest entry-wise difference of two answers (``a`` a mutant's, NaN-lenient as
    :func:`distance`); infinite when their forms differ."""
    pairs = numeric_pairs(a, b)
    if pairs is None:
        return float("inf")
    worst = 0.0
    for x, y in pairs:
        x, y = x.astype(np.complex128 if "c" in x.dtype.kind + y.dtype.kind else np.float64), y.astype(
            np.complex128 if "c" in x.dtype.kind + y.dtype.kind else np.float64)
        bad_x, bad_y = ~np.isfinite(x), ~np.isfinite(y)
        if (bad_y & ~bad_x).any() or (bad_x.any() and (bad_x & ~bad_y).mean() >= 0.5):
            return float("inf")
        keep = ~bad_x & ~bad_y
        if projective and x.ndim == 2 and x.size <= 16 and keep.all():
            nx, ny = np.linalg.norm(x), np.linalg.norm(y)
            if nx == 0 or ny == 0:
                return float("inf")
            x = x / nx * ny
            if np.real(np.vdot(x, y)) < 0:
                x = -x
        if keep.any():
            worst = max(worst, float(np.max(np.abs(x[keep] - y[keep]))))
    return worst


def _constant(value) -> bool:
    """Whether every array of an answer holds one value only (then it tells no cause apart): an 8-bit
    image within BLANK grey levels of one value too (lit pixels of level 1 where 255 belongs are as
    black as an image a wrong column sends off the projector)."""
    leaves = []
    if not _leaves(value, leaves):
        return True
    arrays = [v for v in leaves if isinstance(v, np.ndarray) and v.size > 1]
    return bool(arrays) and all(int(v.max()) - int(v.min()) <= BLANK if v.dtype == np.uint8 else np.all(v == v.flat[0])
                                for v in arrays)


BLANK = 2   # grey levels an 8-bit answer may span and still be blank


def _tells_nothing(value) -> bool:
    """Whether an answer can tell no mistake apart, before any mutant runs: constant (every array
    one value), nothing but NaN and infinities, or not made of numbers (a string, an integer beyond
    64 bits, an object array, only empty sequences), which no mutant of numeric reference code gives."""
    leaves = []
    if not _leaves(value, leaves) or _constant(value):
        return True
    arrays = [v for v in leaves if isinstance(v, np.ndarray)]
    other = any(isinstance(v, tuple) and v[0] == "other" for v in leaves)
    if other or not arrays or any(v.dtype.kind not in "biufc" for v in arrays):
        return True
    return not any(np.isfinite(v).any() for v in arrays if v.size)   # only NaN and infinities


def _same_kind(student, reference) -> bool:
    """Whether a mutant could give the student's answer's form: the same containers (sequence
    lengths, dict keys) around arrays of the same number of dimensions (a mutant may transpose
    or drop a row, not turn a matrix into a scalar or a dict)."""
    left, right = [], []
    if not (_leaves(student, left) and _leaves(reference, right)) or len(left) != len(right):
        return False
    return all((x == y) if isinstance(x, tuple) and isinstance(y, tuple)
               else (isinstance(x, np.ndarray) and isinstance(y, np.ndarray) and x.ndim == y.ndim)
               for x, y in zip(left, right))


def wrong(student, reference) -> bool:
    """Whether an answer differs from the reference's beyond a rounding: for an image, also one
    whose pixels differ in a few places only, strongly (a drawing: thin lines in other places
    change the mean little)."""
    return distance(reference, student) > 10 * _tolerance(student) or drawn_elsewhere(student, reference)


def drawn_elsewhere(student, reference) -> bool:
    """An integer image of the reference's shape with more than 1% of its pixels over 16 grey levels off."""
    if not (isinstance(student, np.ndarray) and isinstance(reference, np.ndarray)) or student.shape != reference.shape \
            or student.dtype.kind not in "iu" or reference.dtype.kind not in "iu" or student.ndim < 2 or student.size < 64:
        return False
    apart = np.abs(student.astype(np.int64) - reference) > 16
    return bool((apart.reshape(student.shape[0], student.shape[1], -1).any(axis=2)).mean() > 0.01)


# ------------------------------------------------------------------ confirmation inputs
_SMALL_MATRIX = 4   # matrices up to 4 x 4 (K, R, H, P, F, an affine A) keep their structure


def _rotation(value: np.ndarray) -> bool:
    """Whether ``value`` is a 2 x 2 or 3 x 3 rotation (or reflection): R^T R = I."""
    return value.ndim == 2 and value.shape[0] == value.shape[1] in (2, 3) and bool(np.all(np.isfinite(value))) \
        and np.allclose(value.T @ value, np.eye(value.shape[0]), atol=1e-6)


def _small_rotation(size: int, rng) -> np.ndarray:
    """A random rotation of about 0.2 radians, ``size`` x ``size`` (2 or 3)."""
    if size == 2:
        angle = rng.normal(0, 0.2)
        return np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis) or 1.0
    skew = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    angle = rng.normal(0, 0.2)
    return np.eye(3) + np.sin(angle) * skew + (1 - np.cos(angle)) * skew @ skew   # Rodrigues


def _structure(value: np.ndarray) -> np.ndarray:
    """The entries that make an array's form and stay as they are when it is perturbed: a small
    matrix's exact 0s and 1s (K's zeros and its 1, an affine's last row [0, 0, 1]) and a column of
    ones in a table of points (homogeneous coordinates). Perturbing them gives inputs no caller
    gives (a K with entries below the diagonal), where right code may answer otherwise."""
    kept = np.zeros(value.shape, dtype=bool)
    if value.ndim == 2 and max(value.shape) <= _SMALL_MATRIX:
        kept |= (value == 0) | (value == 1)
    elif value.ndim == 2 and value.shape[1] <= _SMALL_MATRIX:
        kept[:, np.all(value == 1, axis=0)] = True
    return kept


def _perturbed(value, rng, depth=0, zeros=None):
    """Another input of the same form: other values of the same shape, dtype and range, and the
    same structure (a rotation stays a rotation, :func:`_structure`). A number 0 stays 0 (``zeros``
    False), moves off it (True), or either, at random (None): a mistake may show only at 0 (`x or
    DEFAULT`), another only off it (a centre truncated by int(), which 0 hides)."""
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return value
    if isinstance(value, float):
        factor, shift = rng.uniform(0.6, 1.4), (rng.uniform(-1, 1) if value == 0 else 0.0)
        if value == 0 and zeros is not None:
            shift = abs(shift) + 0.1 if zeros else 0.0
        return value * factor + (shift if shift > 0 else 0.0)
    if isinstance(value, int):
        return value + 2 * int(rng.integers(-2, 3)) if abs(value) > 4 else value
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "f" and value.size:
            if _rotation(value):
                return (value @ _small_rotation(value.shape[0], rng)).astype(value.dtype)
            finite = value[np.isfinite(value)]
            spread = float(finite.std()) if finite.size > 1 else float(abs(finite).mean() if finite.size else 1.0)
            noise = rng.normal(0, 0.15 * (spread or 1.0), value.shape)
            return _same_rank(value, value + np.where(_structure(value), 0.0, noise).astype(value.dtype))
        if value.dtype == np.uint8 and value.ndim >= 2:  # an image: the same picture, moved and relit
            moved = np.roll(value, (int(rng.integers(-9, 10)), int(rng.integers(-9, 10))), axis=(0, 1))
            return np.clip(moved.astype(np.int16) + int(rng.integers(-20, 21)), 0, 255).astype(np.uint8)
        return value.copy()
    if isinstance(value, (tuple, list)) and depth < 3:
        made = [_perturbed(v, rng, depth + 1, zeros) for v in value]
        return tuple(made) if isinstance(value, tuple) else made
    if isinstance(value, dict) and depth < 3:
        return {k: _perturbed(v, rng, depth + 1, zeros) for k, v in value.items()}
    return value


def _same_rank(value, moved):
    """``moved`` brought back to ``value``'s rank where ``value`` is a small square matrix short of full
    rank (a fundamental matrix, of rank 2: its null vectors are what an epipole is; a perturbed F of rank
    3 has none, and every method of finding them answers differently)."""
    if value.ndim != 2 or value.shape[0] != value.shape[1] or not 2 <= value.shape[0] <= 4 \
            or not np.isfinite(value).all() or not np.isfinite(moved).all():
        return moved
    singular = np.linalg.svd(value, compute_uv=False)
    rank = int((singular > 1e-9 * singular[0]).sum()) if singular[0] > 0 else 0
    if rank in (0, value.shape[0]):
        return moved
    U, S, Vt = np.linalg.svd(moved.astype(np.float64))
    S[rank:] = 0.0
    return ((U * S) @ Vt).astype(value.dtype)


def derived_calls(call, count, seed, defaults=()):
    """``count`` perturbed copies of a call; every other one also gives the numeric defaults it
    left out, perturbed."""
    function, args, kwargs = call
    rng = np.random.default_rng(seed)
    made = []
    for index in range(count):
        extra = {name: default for name, position, default in defaults
                 if position >= len(args) and name not in kwargs} if index % 2 else {}
        # (the second of each pair moves every 0 off it, the first keeps them: both kinds are tried)
        zeros = None if count < 2 else bool(index % 2)
        made.append((function, _perturbed(tuple(args), rng, zeros=zeros),
                     _perturbed({**kwargs, **extra}, rng, zeros=zeros)))
    return made


# ------------------------------------------------------------------ naming
WALL_SLACK = 3.0   # a naming's wall-clock time is at most this many times its budget (a busy machine)
PACE_SECONDS = 0.015   # CPU seconds of :func:`_pace_work` on the machine the budgets were set on
PACE_BOUNDS = (0.5, 4.0)   # a machine's pace is taken within these (a measure gone wrong stays harmless)
PACE_FRESH = 2.0   # seconds a measure of the pace stands for


def _pace_work() -> None:
    """A few milliseconds of the error model's kinds of work: parsing and compiling source, running
    Python, small array arithmetic and an OpenCV call (a mutant made, run, its answer compared)."""
    import cv2
    source = "\n".join(f"def f{i}(x, y):\n    z = x * {i} + y\n    return [v for v in range(3) if v != z]\n"
                       for i in range(40))
    namespace: dict = {}
    exec(compile_source(parse(source, "<pace>", max_chars=None, max_statements=None), "<pace>"), namespace)
    sum(len(namespace[f"f{i}"](i, 1)) for i in range(40) for _ in range(60))
    a = np.linspace(0.0, 1.0, 64 * 64).reshape(64, 64)
    for _ in range(180):
        b = a @ a.T / (1.0 + np.abs(a).sum(axis=0))
        np.allclose(a, b, rtol=1e-6)
    cv2.warpAffine(a.astype(np.float32), np.float32([[1, 0.1, 2], [0.1, 1, 3]]), (64, 64))


_PACE: list = []   # [(time.monotonic() when measured, the pace)]: the last measure


def last_pace() -> float:
    """The pace :func:`machine_pace` measured last, without measuring it again (1.0 before any measure)."""
    return _PACE[0][1] if _PACE else 1.0


def machine_pace() -> float:
    """How many times longer this machine takes over the error model's work now than the one its budgets
    (:data:`CHECK_SECONDS`, :data:`GRADING_SECONDS`) were set on: a naming's clock counts its seconds
    divided by it, so a slower machine (a grading container, CI) or one whose cores other work shares
    (a batch, a virtual machine's neighbours: CPU seconds then stretch too) tries as many changes and tells
    the same names, taking longer. The median CPU time of three runs of :func:`_pace_work`, measured again
    when the last measure is older than :data:`PACE_FRESH` seconds (a machine's pace drifts)."""
    now = time.monotonic()
    if _PACE and now - _PACE[0][0] < PACE_FRESH:
        return _PACE[0][1]
    if not _PACE:
        _pace_work()   # (imports, caches: the first run is no measure)
    spent = []
    for _ in range(3):
        started = time.thread_time()
        _pace_work()
        spent.append(time.thread_time() - started)
    low, high = PACE_BOUNDS
    pace = float(min(high, max(low, float(np.median(spent)) / PACE_SECONDS)))
    _PACE[:] = [(time.monotonic(), pace)]
    return pace


class Clock:
    """The time a naming has left (:meth:`left`, seconds), from a budget given at its start.

    Counted in CPU seconds of the processes doing the work -- this thread (the grader's comparisons)
    and ``processes()`` (the reference's helper, the student's sandboxes) -- so that a submission gets
    the same names on a busy machine as on a quiet one (a regrade, a batch beside other work, a class
    graded on shared cores), within :data:`WALL_SLACK` times the budget in wall-clock time. Without
    ``processes``, or where a process's CPU time cannot be read (no ``/proc``), wall-clock seconds.
    Seconds of the budget are those of the machine it was set on: this machine's are divided by its
    :func:`machine_pace` (:attr:`pace`), so that a slower one tells the same names, taking longer."""

    def __init__(self, seconds: float, processes=None):
        self.pace = machine_pace()   # (measured before the clock starts: its measure is no naming's work)
        self.seconds, self.started = seconds, time.monotonic()
        self.spare = 0.0   # seconds of the grading's budget this clock may draw on (:meth:`draw_on_spare`)
        self._processes = processes
        self._thread = time.thread_time()
        self._cpu: dict[int, list[float]] = {}         # pid -> [CPU seconds when first seen, last seen]
        if processes is not None and not self._look():
            self._processes = None   # no /proc to read: wall-clock seconds

    def _look(self) -> bool:
        """Read the CPU time of the processes working now; False when one cannot be read. A process
        that ended since (a worker restarted after a timeout) keeps the time last read of it."""
        readable = True
        for pid, started, *startup in self._processes():
            cpu = evidence.cpu_seconds(pid)
            if cpu is None:
                readable = False
                continue
            # A process started since (a helper or worker restarted) counts all its time but its start
            # (``startup``: CPU seconds it took to start, where known); one that ran before (the student's
            # worker, a helper kept from an earlier grading) from now on.
            seen = self._cpu.setdefault(pid, [0.0 if started >= self.started else cpu, cpu])
            seen[0], seen[1] = max(seen[0], *startup, 0.0), cpu
        return readable

    def used(self) -> float:
        """Seconds of the budget used so far: CPU seconds, and never less than a WALL_SLACK-th of the
        wall-clock time (a very busy machine)."""
        wall = time.monotonic() - self.started
        if self._processes is None:
            return wall / self.pace
        self._look()
        cpu = time.thread_time() - self._thread + sum(last - first for first, last in self._cpu.values())
        return max(cpu, wall / WALL_SLACK) / self.pace

    def left(self) -> float:
        return self.seconds - self.used()

    def draw_on_spare(self, needed: float) -> None:
        """Have ``needed`` seconds left, as far as :attr:`spare` allows: a change found late in a slow
        function's search is confirmed with the grading's time left, not lost for want of its check's."""
        drawn = min(self.spare, max(0.0, needed - self.left()))
        self.seconds += drawn
        self.spare -= drawn

    def wall_left(self) -> float:
        """Wall-clock seconds a call started now may take: the CPU seconds left take up to WALL_SLACK times
        as long on a busy machine (a timeout of CPU seconds would cut the reference's confirmation answers
        short there, and the names they decide would be lost or differ), within the naming's wall bound."""
        if self._processes is None:
            return self.left() * self.pace
        return min(self.left() * WALL_SLACK * self.pace,
                   self.seconds * WALL_SLACK * self.pace - (time.monotonic() - self.started))


def work_clock(trial, seconds: float) -> Clock:
    """A :class:`Clock` of ``seconds`` counting the CPU time of this thread, its reference helper and
    the trial's sandboxes (the student's worker and its companion)."""
    working = getattr(getattr(trial, "sandbox", None), "working_pids", None)

    def processes() -> list[tuple[int, float]]:
        current = getattr(_USING, "helper", None)   # (this thread's, once it has one)
        running = current.running if current is not None else None
        return list(working()) + ([(*running, current.startup_cpu)] if running is not None else [])

    return Clock(seconds, processes if working is not None else None)


def confirming_extra(trial) -> float:
    """Time a grading may add, beyond :data:`GRADING_SECONDS`, to confirm a change already found: as much as the
    student's own calls have taken so far in it, up to :data:`GRADING_SECONDS` again. A submission whose own loops
    are slow (a scanline DP in Python) takes that long to pass, and a change of it as long to confirm; a search
    that finds nothing stops within the grading's time, as before."""
    own = getattr(getattr(trial, "sandbox", None), "student_seconds", 0.0) or 0.0
    return min(GRADING_SECONDS, own / machine_pace())


def name_failure(trial, seconds: float = CHECK_SECONDS) -> Naming | None:
    """The confirmed mutant that explains the failing trial's answers, or None.

    ``trial`` is the failed check's :class:`~autograder.engine.checks.Trial` (its
    ``calls``); the student's function is asked for a few confirmation answers through
    its sandbox. Never raises for the student's sake: any failure of the helper is "no name".
    """
    return _within_budget(trial, seconds, _name)


def _within_budget(trial, seconds: float, work, evidence=None) -> Naming | None:
    """``work(trial, model, clock)`` within this check's and this grading's time left (None without
    a model, without ``evidence`` -- by default the calls that returned --, out of time or when the
    helper fails)."""
    model = model_for(trial.lab)
    if model is None or not (trial.calls if evidence is None else evidence):
        return None
    spent = trial.sandbox.shared.setdefault(SPENT, [0.0])
    seconds = min(seconds, GRADING_SECONDS - spent[0])
    if seconds <= 0.2:
        return None
    clock = work_clock(trial, seconds)
    try:
        return work(trial, model, clock)
    except HelperFailed:
        return None
    finally:
        spent[0] += clock.used()
        _MEASURED.clear()
        release_helper()


def name_in_place(trial, seconds: float = CHECK_SECONDS) -> Naming | None:
    """Where a function changes its caller's array, when the check failed for it
    (:class:`~autograder.engine.checks.ChangedInPlace`: the trial's last call changed arrays in place,
    :attr:`~autograder.engine.checks.Trial.calls`' last entry): the ``in_place`` mutant of that function
    that, on that call, gives the student's answer and changes the same arguments to the same values;
    None when none or several different ones do."""
    return _within_budget(trial, seconds, _name_in_place)


def _name_in_place(trial, model: ErrorModel, clock: Clock) -> Naming | None:
    changed = getattr(trial, "_last_changed", ()) or ()
    function, args, kwargs, answer = trial.calls[-1]
    mutants = [m for m in model.mutants.get(function, ()) if m.operator == "in_place"]
    if not changed or not mutants:
        return None
    theirs = {(key, index): array for key, index, array in changed}
    runner = helper()
    runner.prepare(model.source, model.module, [(function, tuple(args), dict(kwargs))], max(1.0, clock.wall_left()))
    [reference] = runner.run((), [0], _timeout(clock))
    found = []
    for mutant in mutants:
        if clock.left() <= 0:
            return None
        [(value, mine)] = runner.run_changed(mutant.edits, [0], _timeout(clock))
        mine = {(key, index): array for key, index, array in mine}
        if set(mine) == set(theirs) and reproduces(value, answer, reference) \
                and all(distance(mine[k], theirs[k]) <= _tolerance(theirs[k]) for k in theirs):
            found.append(mutant)
    if not found or len({m.sentence.split(", ", 1)[-1] for m in found}) > 1:
        return None   # (one copy dropped, told from the graded function and from a helper it runs)
    return Naming(min(found, key=lambda m: m.rank), 1, 0)


def _name(trial, model: ErrorModel, clock: Clock) -> Naming | None:
    recorded = {}
    for function, args, kwargs, value in trial.calls:
        if function in model.mutants:
            recorded.setdefault(function, []).append((function, tuple(args), dict(kwargs), value))
    runner = helper()
    for function, calls in recorded.items():
        calls = calls[-CALLS_PER_FUNCTION:]
        inputs = [call[:3] for call in calls]
        answers = [call[3] for call in calls]
        if all(_tells_nothing(answer) for answer in answers):
            continue   # decided from the answers alone: the helper is not asked
        runner.prepare(model.source, model.module, inputs, max(1.0, clock.wall_left()))
        references = runner.run((), range(len(inputs)), max(0.5, clock.wall_left()))
        failing = [i for i, (s, r) in enumerate(zip(answers, references)) if wrong(s, r)]
        if not failing or all(_constant(answers[i]) or not _same_kind(answers[i], references[i]) for i in failing):
            continue   # a constant answer (all zeros, a black image) is what many mistakes give;
            # an answer of another kind (a dict, a scalar for a matrix) is none of the mutants'
        naming = _name_function(trial, model, function, inputs, answers, references, failing, clock)
        if naming is not None:
            return naming
    return None


def _timeout(clock: Clock) -> float:
    return max(0.05, min(1.0, clock.wall_left()))


def _name_function(trial, model, function, inputs, answers, references, failing, clock) -> Naming | None:
    runner = helper()
    others = [i for i in range(len(inputs)) if i not in failing]
    # A mistake confirmed in an earlier check of this grading, that reproduces these answers too,
    # is named again without asking the student's function once more.
    named = trial.sandbox.shared.setdefault("error model named", [])
    for mutant in named:
        if mutant.function != function:
            continue
        outcome = _reproduces(runner, mutant.edits, failing, others, answers, references, clock)
        if outcome is True:
            return Naming(mutant, len(inputs), 0)
        if outcome is not None:   # (the same code answering otherwise here: the name is taken back there)
            trial.sandbox.shared.setdefault(REFUTED, []).append(
                (mutant.sentence, bool(getattr(getattr(trial, "check", None), "hidden", False))))
    # The student's function is the same code in every check of a grading: a mutant that did not
    # reproduce its answers in an earlier check is not its mistake, and is not run again.
    ruled_out = trial.sandbox.shared.setdefault("error model ruled out", {}).setdefault(function, set())
    candidates, near = [], []
    off = sum(distance(references[i], answers[i]) for i in failing)
    for mutant in model.mutants[function]:
        if mutant.key in ruled_out:
            continue
        if clock.left() <= 0:
            return None  # a mutant not tried might reproduce the answers too: no name is sure
        outcome = _reproduces(runner, mutant.edits, failing, others, answers, references, clock)
        if outcome is True:
            candidates.append(mutant)
            continue
        if clock.left() > 0:   # (a mutant cut short by the clock is not ruled out)
            ruled_out.add(mutant.key)
        if outcome is not None and outcome < 0.9 * off:
            near.append((outcome, mutant))
    kept_near = trial.sandbox.shared.setdefault("error model near", {}).setdefault(function, [])
    if not candidates:   # the closest singles of earlier checks (ruled out as singles) are scored here too
        scored = {m.key for _, m in near}
        for mutant in kept_near:
            if mutant.key not in scored and clock.left() > 0:
                outcome = _reproduces(runner, mutant.edits, failing, others, answers, references, clock)
                if outcome is not None and outcome is not True and outcome < 0.9 * off:
                    near.append((outcome, mutant))
    if not candidates and near:
        near.sort(key=lambda pair: (pair[0], pair[1].rank))
        closest = [m for _, m in near[:PAIR_MUTANTS]]
        kept_near[:] = closest
        for first, second in itertools.combinations(closest, 2):
            if clock.left() <= 0:
                break
            if (first.where, first.edits[0][1]) == (second.where, second.edits[0][1]):
                continue
            pair = first.combined(second) if first.rank <= second.rank else second.combined(first)
            if _reproduces(runner, pair.edits, failing, others, answers, references, clock) is True:
                candidates.append(pair)
    if not candidates or clock.left() <= 0:
        return None
    naming = _confirmed(trial, model, function, inputs, failing, candidates, clock)
    if naming is not None:
        named.append(naming.mutant)
    return naming


def _reproduces(runner, edits, failing, others, answers, references, clock):
    """True when the mutant reproduces every answer; else its summed distance on the failing
    calls (None: it failed there)."""
    try:
        values = runner.run(edits, failing, _timeout(clock))
    except HelperFailed:
        return None
    if not all(reproduces(v, answers[i], references[i]) for v, i in zip(values, failing)):
        total = sum(distance(v, answers[i]) for v, i in zip(values, failing))
        return total if np.isfinite(total) else None
    if others:
        try:
            values = runner.run(edits, others, _timeout(clock))
        except HelperFailed:
            return None
        if not all(reproduces(v, answers[i], references[i]) for v, i in zip(values, others)):
            return None
    return True


def _confirmed(trial, model, function, inputs, failing, candidates, clock) -> Naming | None:
    """The candidate left after the student's answers on inputs that tell them apart, or None."""
    from ..checks import fingerprint

    variants = []
    for i in failing[:2]:
        variants += derived_calls(inputs[i], VARIANTS_PER_CALL, int(fingerprint(function, i, inputs[i][1])[:8], 16),
                              model.defaults.get(function, ()))
    every, indices, reference, outputs, candidates, usable = _on_variants(model, inputs, variants, candidates, clock)
    chosen = _separating(usable, reference, [outputs[c.key] for c in candidates])
    if not chosen:
        return None
    answers = []
    for k in chosen:
        answer = _student_answer(trial, every[indices[k]])
        if answer is _FAILED or _constant(answer):
            return None
        answers.append(answer)
    survivors = [c for c in candidates
                 if all(reproduces(outputs[c.key][k], answer, reference[k]) for k, answer in zip(chosen, answers))
                 and any(wrong(answer, reference[k]) for k, answer in zip(chosen, answers))]
    if not survivors:
        return None
    first = survivors[0]
    for other in survivors[1:]:  # they must be one mistake (equivalent on every input seen)
        if any(distance(outputs[other.key][k], outputs[first.key][k]) > _tolerance(outputs[first.key][k])
               for k in chosen):
            return None
    ordered = sorted(survivors, key=lambda m: m.rank)
    best = ordered[0]
    # An equivalent mutant of another operator says the same mistake another way (c @ R is R^T c):
    # both are told, the simplest first.
    other = next((m for m in ordered[1:] if m.operator != best.operator), None)
    if other is not None:
        said = other.sentence[len(other.place):] if other.place and other.place == best.place else other.sentence
        best = replace(best, sentence=f"{best.sentence} (equivalently, {said})")
    return Naming(best, len(inputs), len(chosen))


def _on_variants(model, inputs, variants, candidates, clock):
    """The confirmation inputs run: ``(every, indices, reference, outputs, candidates, usable)`` --
    the inputs then the variants, the variants' indices in it, the reference's outputs there, the
    candidates' (the first 12, by key; those the helper could not run are left out) and the
    variants where the reference answers (positions in ``indices``)."""
    runner = helper()
    every = inputs + variants
    runner.prepare(model.source, model.module, every, max(1.0, clock.wall_left()))
    indices = list(range(len(inputs), len(every)))
    reference = runner.run((), indices, _timeout(clock))
    outputs = {}
    for candidate in candidates[:12]:
        try:
            outputs[candidate.key] = runner.run(candidate.edits, indices, _timeout(clock))
        except HelperFailed:
            continue
    candidates = [c for c in candidates if c.key in outputs]
    usable = [k for k, r in enumerate(reference) if error_kind(r) is None]
    return every, indices, reference, outputs, candidates, usable


def _separating(usable, reference, candidate_outputs) -> list[int]:
    """Up to :data:`CONFIRMATIONS` variant indices that, greedily, tell apart most pairs of
    (the reference, each candidate); empty when none tells any candidate from the reference."""
    rows = [reference] + candidate_outputs
    pairs = [(a, b) for a in range(len(rows)) for b in range(a + 1, len(rows))]

    def apart(k, a, b):
        kinds = error_kind(rows[a][k]), error_kind(rows[b][k])
        if kinds != (None, None):
            return kinds[0] != kinds[1]
        return wrong(rows[a][k], rows[b][k])   # (a drawing's lines apart change its mean little)

    split = {k: {p for p in pairs if apart(k, *p)} for k in usable}
    chosen, covered = [], set()
    while len(chosen) < CONFIRMATIONS:
        k = max(usable, key=lambda k: (len(split[k] - covered), -k), default=None)
        if k is None or not split[k] - covered:
            break
        chosen.append(k)
        covered |= split[k]
    if not any(a == 0 for a, _ in covered):
        return []
    return sorted(chosen)


_FAILED = object()


# ------------------------------------------------------------------ naming an exception
# Phrases that class an exception's message (the first found): two errors of one type but of
# different classes (a broadcast and a matmul mismatch, both ValueError) are different mistakes.
_ERROR_CLASSES = ("could not be broadcast", "too many indices", "out of bounds", "cannot reshape",
                  "mismatch in its core dimension", "not aligned", "input array dimensions",
                  "same number of dimensions", "singular matrix", "assertion failed", "truth value of an array",
                  "unsupported operand", "not subscriptable", "invalid index", "must be square",
                  "only integer scalar arrays", "last 2 dimensions")
_RAISED = re.compile(r"raised ([A-Za-z_][\w.]*)(?::\s*(.*))?")


def error_kind(value) -> tuple | None:
    """(exception type, message class) of an error answer (the helper's ``{ERROR: "Type: text"}``),
    None for an answer."""
    if not (isinstance(value, dict) and ERROR in value):
        return None
    kind, _, text = str(value[ERROR]).partition(":")
    return kind.strip().rsplit(".", 1)[-1], _error_class(text)


def _error_class(text: str) -> str:
    lowered = text.lower()
    return next((phrase for phrase in _ERROR_CLASSES if phrase in lowered), "")


def raised_answer(message: str) -> dict | None:
    """The student's exception as an error answer, from the sandbox's "f() raised Type: text"."""
    for line in str(message).splitlines():
        found = _RAISED.search(line)
        if found:
            return {ERROR: f"{found.group(1)}: {found.group(2) or ''}"}
    return None


def _same_outcome(value, student, reference) -> bool:
    """A mutant's outcome is the student's: the same exception (:func:`_same_exception`), or an
    answer that :func:`reproduces` theirs."""
    if (error_kind(value), error_kind(student)) != (None, None):
        return _same_exception(value, student)
    return reproduces(value, student, reference)


def _same_exception(value, student) -> bool:
    """The very exception the student's code raised: type and text (its shapes, indices and sizes:
    "could not be broadcast together with shapes (24,30) (23,30)"), as far as both were kept. The
    type and the kind of message alone let a mutant failing elsewhere in the code pass for theirs."""
    if error_kind(value) is None or error_kind(value) != error_kind(student):
        return False
    texts = [" ".join(str(answer[ERROR]).split()) for answer in (value, student)]
    kept = min(len(texts[0]), len(texts[1]), 120)
    return texts[0][:kept] == texts[1][:kept]


def name_raised(trial, seconds: float = CHECK_SECONDS) -> Naming | None:
    """The confirmed mutant that raises the student's exception (:attr:`Trial.raised`: the same type
    and message class) on the input where the student's function raised, while it returns the
    student's answers on the trial's calls of that function that returned, and agrees with the
    student on confirmation inputs derived from both (at least one of them an answer, not an
    exception: a mutant that raises everywhere names nothing); None otherwise."""
    return _within_budget(trial, seconds, _name_raised, evidence=getattr(trial, "raised", None) or ())


# Exceptions no mutant of the reference raises (a name of the student's own, an import, their own
# assert): decided without running any, so a submission that fails everything this way costs nothing.
NO_MUTANT_RAISES = {"NameError", "ImportError", "ModuleNotFoundError", "AssertionError", "SyntaxError",
                    "IndentationError", "NotImplementedError"}


def _name_raised(trial, model: ErrorModel, clock: Clock) -> Naming | None:
    function, args, kwargs, message = trial.raised
    theirs = raised_answer(message)
    if function not in model.mutants or theirs is None or error_kind(theirs)[0] in NO_MUTANT_RAISES:
        return None
    returned = [call for call in trial.calls if call[0] == function][-(CALLS_PER_FUNCTION - 1):]
    inputs = [(function, tuple(args), dict(kwargs))] + [(f, tuple(a), dict(k)) for f, a, k, _ in returned]
    answers = [theirs] + [call[3] for call in returned]
    runner = helper()
    runner.prepare(model.source, model.module, inputs, max(1.0, clock.wall_left()))
    references = runner.run((), range(len(inputs)), max(0.5, clock.wall_left()))
    if error_kind(references[0]) is not None:
        return None   # the reference raises there too: the input, not the code, is the cause
    ruled_out = trial.sandbox.shared.setdefault("error model ruled out raising", {}).setdefault(function, set())
    candidates = []
    for mutant in model.mutants[function]:
        if mutant.key in ruled_out:
            continue
        if clock.left() <= 0:
            return None   # a mutant not tried might raise the same: no name is sure
        try:
            values = runner.run(mutant.edits, range(len(inputs)), _timeout(clock))
        except HelperFailed:
            continue
        if all(_same_outcome(v, a, r) for v, a, r in zip(values, answers, references)):
            candidates.append(mutant)
        elif clock.left() > 0:
            ruled_out.add(mutant.key)
    if not candidates:
        return None
    return _confirmed_raised(trial, model, function, inputs, answers, candidates, clock)


def _confirmed_raised(trial, model, function, inputs, answers, candidates, clock) -> Naming | None:
    """As :func:`_confirmed`, outcomes compared as exceptions or answers; at least one answer (a
    returned call or a confirmation that returned) must be among the evidence."""
    from ..checks import fingerprint

    variants = []
    for i in range(min(len(inputs), 3)):
        seed = int(fingerprint(function, "raised", i, inputs[i][1])[:8], 16)
        variants += derived_calls(inputs[i], VARIANTS_PER_CALL if i == 0 else 2, seed, model.defaults.get(function, ()))
    # The rest of the code, where only the raising call was made: the same point as a batch, the
    # call without an optional argument (`if not dist:` raises on an array, not on None).
    corroborating = _batched(inputs[0], int(fingerprint(function, "batched", inputs[0][1])[:8], 16)) \
        + left_out(inputs[0], model.optional.get(function, ()))
    variants += corroborating
    every, indices, reference, outputs, candidates, usable = _on_variants(model, inputs, variants, candidates, clock)
    chosen = _separating(usable, reference, [outputs[c.key] for c in candidates])
    if not chosen:
        return None
    if len(inputs) == 1:
        extra = range(len(indices) - len(corroborating), len(indices))
        chosen = sorted(set(chosen) | {k for k in extra if k in usable})
    theirs = []
    for k in chosen:
        answer = _student_outcome(trial, every[indices[k]])
        if answer is _FAILED or (error_kind(answer) is None and _constant(answer)):
            return None
        theirs.append(answer)
    if len(inputs) == 1 and all(error_kind(answer) is not None for answer in theirs):
        return None   # raising everywhere: nothing says the rest of the mutant is the student's
    survivors = [c for c in candidates
                 if all(_same_outcome(outputs[c.key][k], answer, reference[k]) for k, answer in zip(chosen, theirs))]
    if not survivors:
        return None
    first = survivors[0]
    for other in survivors[1:]:   # one mistake: the same outcome on every input seen
        if any(not _same_outcome(outputs[other.key][k], outputs[first.key][k], reference[k]) for k in chosen):
            return None
    best = min(survivors, key=lambda m: m.rank)
    return Naming(best, len(inputs), len(chosen))


def _batched(call, seed) -> list:
    """The raising call with its 1-D float arrays given as a batch of two rows (the array and a
    perturbed copy): where a single point raised, a batch tells whether the rest of the code is a
    mutant's; [] without a 1-D float array."""
    function, args, kwargs = call
    rng = np.random.default_rng(seed)

    def batch(value):
        if isinstance(value, np.ndarray) and value.ndim == 1 and value.dtype.kind == "f" and 1 < value.size <= 4:
            return np.stack([value, _perturbed(value, rng)])
        return value

    made = (function, tuple(batch(a) for a in args), {k: batch(v) for k, v in kwargs.items()})
    return [made] if _changed_call(call, made) else []


def left_out(call, optional) -> list:
    """The call with each optional argument it gives (a parameter defaulting to None, given a value)
    given as None instead, one call per argument."""
    function, args, kwargs = call
    made = []
    for name, position, _ in optional:
        if name in kwargs and kwargs[name] is not None:
            made.append((function, tuple(args), {**kwargs, name: None}))
        elif position < len(args) and args[position] is not None:
            made.append((function, tuple(None if i == position else a for i, a in enumerate(args)), dict(kwargs)))
    return made


def _changed_call(call, made) -> bool:
    return any(a is not b for a, b in zip(call[1], made[1])) or any(call[2][k] is not made[2][k] for k in call[2])


def _student_outcome(trial, call):
    """The student's answer on a confirmation input, or their exception as an error answer."""
    function, args, kwargs = call
    lab = trial.lab
    outcome = trial.sandbox.call(lab.module, function, args, kwargs, timeout=trial.check.timeout,
                                 forbid=lab.forbidden.get(function, ()) + tuple(trial.forbid.get(function, ())))
    trial.student_seconds += outcome.seconds
    if outcome.output.strip():
        trial.outputs.append(f"(printed during the grader's confirmation call to {function}())\n{outcome.output}")
    if outcome.ok:
        return outcome.value
    raised = raised_answer(outcome.message) if outcome.kind == "exception" else None
    return raised if raised is not None else _FAILED


def _student_answer(trial, call):
    """The student's answer on a confirmation input (the grader's own call, labelled so)."""
    answer = _student_outcome(trial, call)
    return _FAILED if error_kind(answer) is not None else answer


def named_by_error_model(verdict, trial, raised: bool = False):
    """A failed check's verdict with the error model's name added (see the module docstring),
    appended to the message's first line, when the verdict names nothing; unchanged otherwise.
    ``raised``: the check ended by the student's exception (:attr:`Trial.raised`), named by a
    mutant raising the same (:func:`name_raised`)."""
    from ..stubs import functions_called

    # The functions the check calls (by its source, and by the calls it made: a value shared
    # between checks is called only once, in the first check that asks for it).
    called = {call[0] for call in trial.calls} | set(functions_called(trial.check)) if hasattr(trial, "check") \
        else {call[0] for call in trial.calls}
    hand_named = trial.sandbox.shared.setdefault("error model: named by hand", set())
    if verdict.mistake == IN_PLACE:   # the engine names the change; the code read, or the model, says where it is made
        hand_named.update(called)
        place = _place_of_change(verdict, trial, called)
        if place:
            first, newline, rest = str(verdict.message).partition("\n")
            return replace(verdict, message=f"{first} {place}{newline}{rest}")
        naming = name_in_place(trial)
        return verdict if naming is None else replace(verdict, message=_appended(str(verdict.message), naming))
    if verdict.mistake or "looks like" in str(verdict.message).lower():
        # A hand-written name keeps precedence (here and in the grading's later checks of these
        # functions). Replacing one a mutant "contradicts" was tried with a test on the operator's
        # words: too crude, it replaced right names ("c + R c instead of c - R c") with clumsier ones.
        hand_named.update(called)
        return verdict
    if called and called <= hand_named:
        return verdict
    naming = name_raised(trial) if raised else name_failure(trial)
    if naming is None or not _code_can(naming, trial, called) or _vouched_for(naming, trial):
        return verdict
    return replace(verdict, message=_appended(str(verdict.message), naming), mistake=naming.mistake)


def _place_of_change(verdict, trial, called) -> str:
    """Where the student's code that ``called`` functions run writes into its caller's array, read from it
    (:func:`..inplace.place_of_change`: one statement, of the arithmetic the change measured shows); ""."""
    from ..hints import code_of
    from ..inplace import place_of_change

    code = code_of(trial)
    if not code.functions:
        return ""
    verb = re.search(r"\(\) (\w+)", str(verdict.message))
    changed = re.search(r"the caller's `(\w+)`", str(verdict.message))
    # (the functions the changing call ran: the last call's, where the check named the change)
    function = trial.calls[-1][0] if getattr(trial, "calls", None) else None
    if function is None or changed is None:
        return ""
    return place_of_change(code.reachable([function]), verb.group(1) if verb else "", function, changed.group(1))


# An operation a mutant's words say the code does, and what the code must hold to do it: a name saying the
# student's values are truncated to integers is not said of code that never makes an integer (a translation
# left unscaled gave the same numbers on the check's inputs as a truncation: 30b's lab11/05).
_INTEGER_MAKERS = re.compile(r"//|\bint\s*\(|astype\(\s*(?:int|np\.u?int|numpy\.u?int|['\"]u?int)|np\.(?:floor|trunc|fix|"
                             r"rint|round|around)\b|\bround\s*\(|dtype\s*=\s*(?:int|np\.u?int|['\"]u?int)|np\.u?int\d*\(")


_QUOTED_CALL = re.compile(r"`((?:np|numpy|cv2|cv|math)\.(\w+))`")


def _code_can(naming: Naming, trial, called) -> bool:
    """Whether the student's code that ``called`` functions run can do what the mutant's words say it does:
    it makes integers where the words say values are truncated; it calls each library function the words
    quote (`the result of `np.floor``); and a name the words say is used in another's place is read
    somewhere else than inside the very call that makes the other (`f` only inside `np.floor(u - f * b / Z)`
    is never used where the floor's result belongs)."""
    from ..hints import code_of

    code = code_of(trial)
    if not code.functions:
        return True
    functions = code.reachable(sorted(called))
    if naming.mutant.operator == "int_division":
        return bool(_INTEGER_MAKERS.search("\n".join(ast.unparse(fn) for fn in functions)))
    called_names = {_short(n) for fn in functions for n in walk(fn) if isinstance(n, ast.Call)}
    quoted = _QUOTED_CALL.findall(naming.sentence)
    # (a call the mutant's own code makes: one it takes out -- "`np.atleast_2d` is missing" -- the student's
    # code lacks by that very mistake)
    if any(short not in called_names for _, short in quoted if short in _mutant_calls(trial, naming.mutant)):
        return False
    if naming.mutant.operator == "drop_conversion" and any(_converts_result_of(fn, short) for fn in functions
                                                           for _, short in quoted):
        return False   # (`the result of cv2.cvtColor is not converted` said of code that converts it: 06h 12/05)
    if naming.mutant.operator == "other_name" and len(naming.mutant.edits) == 1:
        used = naming.mutant.edits[0][3]
        makers = {short for _, short in quoted}
        if not any(_read_outside(fn, used, makers) for fn in functions):
            return False
    return _written_alike(naming.mutant, trial, functions)


# The expressions that carry an edit's meaning: a change is judged with its operands around it
# (`abs(a) >= abs(a)`, not the lone `a`).
_CARRIERS = (ast.Compare, ast.BinOp, ast.BoolOp, ast.Call, ast.Subscript, ast.UnaryOp)
_LIBRARIES = frozenset({"np", "numpy", "math", "cv2", "cv"})


def _written_alike(mutant, trial, functions) -> bool:
    """Whether the student's ``functions`` write each expression the mutant's edits make, names aside
    (`abs(a) >= abs(a)` is written alike by `np.abs(v) >= np.abs(v)`; of a call, its function and the
    arguments up to the last edited one). A mutant's words tell the reference's code; they are said of
    the student's only where it writes the mutated expression: code of its own that answers alike has
    its mistake elsewhere (end points chosen by `b != 0` answered as `abs(a) >= abs(a)`, and "the
    first entry is used where the second belongs" was false of it). An edit that makes no expression
    (a statement moved or dropped, a name returned) is not read."""
    model = model_for(trial.lab) if hasattr(trial, "lab") else None
    if model is None:
        return True
    made = [m for m in (_expression_of_edit(model.source, edit) for edit in mutant.edits) if m is not None]
    if not made:
        return True
    sizes = _sizes(functions)   # (only carriers about the expression's size are written out: linear)
    carriers = [node for fn in functions for node in walk(fn) if isinstance(node, _CARRIERS)]
    theirs = {node.id for fn in functions for node in walk(fn) if isinstance(node, ast.Name)}
    for expression, call, kept, keywords, ours in made:
        shared = ours & theirs   # a name both codes use is the same name (`std_l` is not `denominator`)
        shape = _alike(expression, shared)
        size = sum(1 for _ in walk(expression))
        if not any(_alike(node if call is None else _cut(node, kept, keywords), shared) == shape
                   for node in carriers if (call is not None or size // 2 <= sizes[id(node)] <= 2 * size + 4)
                   and (call is None or isinstance(node, ast.Call) and _short(node) == call
                        and sum(1 for a in node.args[:kept] for _ in walk(a)) <= 2 * size + 4)):
            return False
    return True


def _sizes(functions) -> dict:
    """id(node) -> the number of nodes under it (itself included), for every node of ``functions``, in one
    pass (children before parents)."""
    sizes: dict = {}
    for fn in functions:
        order = list(walk(fn))
        for node in reversed(order):   # (breadth-first reversed: every child comes before its parent)
            sizes[id(node)] = 1 + sum(sizes.get(id(child), 0) for child in ast.iter_child_nodes(node))
    return sizes


def _expression_of_edit(source: str, edit) -> tuple | None:
    """:func:`_mutated_expression`, cached where the edit can be a key (a payload holding a list -- the names an
    operator moves -- is made each time)."""
    try:
        hash(edit)
    except TypeError:
        return _mutated_expression.__wrapped__(source, edit)
    return _mutated_expression(source, edit)


@functools.lru_cache(maxsize=1024)
def _mutated_expression(source: str, edit) -> tuple | None:
    """The expression around one edit of the reference, edited: the edited node or its nearest parent
    that carries an operation, within its statement -- of a call, cut after its last edited argument
    -- as (the expression, the call's function name or None, how many positional arguments and which
    keywords the cut keeps, the names the reference's def uses). None when the edit is a statement's,
    has no such parent or cannot be made. Read only (cached)."""
    where, ordinal = edit[0], edit[1]
    tree = parse(source, max_chars=None, max_statements=None)
    fn = next((n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == where), None)
    nodes = list(walk(fn)) if fn is not None else []
    if not 0 <= ordinal < len(nodes) or not isinstance(nodes[ordinal], ast.expr):
        return None
    parents = _parents(fn)
    steps, node = [], nodes[ordinal]
    while node is not fn:
        parent, field_name, index = parents[id(node)]
        steps.append((field_name, index))
        node = parent
    try:
        (changed_def,) = mutated_defs(ast.Module([fn], []), (edit,)).body
    except (ValueError, KeyError, TypeError, AttributeError, IndexError):
        return None
    carrier, changed = fn, changed_def
    for field_name, index in reversed(steps):
        carrier, changed = getattr(carrier, field_name), getattr(changed, field_name)
        if index is not None:
            carrier, changed = carrier[index], changed[index]
    # The nearest carrier around the edit, in the mutant (`x` made of `x.astype(float)` is judged
    # by the arithmetic it goes into) and in the reference at the same place.
    parents_after = _parents(changed_def)
    while not isinstance(changed, _CARRIERS):
        parent, carrier_parent = parents_after[id(changed)][0], parents[id(carrier)][0]
        if isinstance(parent, ast.keyword):   # (a keyword's value is judged with its call: `axis=1` of a norm)
            parent, carrier_parent = parents_after[id(parent)][0], parents[id(carrier_parent)][0]
        if not isinstance(parent, ast.expr):
            return None
        changed, carrier = parent, carrier_parent
    ours = frozenset(node.id for node in walk(fn) if isinstance(node, ast.Name))
    if not (isinstance(carrier, ast.Call) and isinstance(changed, ast.Call)):
        return changed, None, 0, frozenset(), ours
    # Of a call, only what the edit touches: `cv2.line(img, p, q, ...)` with its points swapped is
    # written alike whatever colour and thickness follow.
    edited = [k for k in range(max(len(carrier.args), len(changed.args)))
              if k >= min(len(carrier.args), len(changed.args)) or ast.dump(carrier.args[k]) != ast.dump(changed.args[k])]
    before = {k.arg: ast.dump(k.value) for k in carrier.keywords}
    after = {k.arg: ast.dump(k.value) for k in changed.keywords}
    keywords = frozenset(k for k in before.keys() | after.keys() if before.get(k) != after.get(k))
    kept = max(edited) + 1 if edited else 0
    return _cut(changed, kept, keywords), _short(changed), kept, keywords, ours


def _cut(call: ast.Call, kept: int, keywords) -> ast.Call:
    """``call`` with its first ``kept`` positional arguments and the ``keywords`` named."""
    return ast.Call(call.func, call.args[:kept], [k for k in call.keywords if k.arg in keywords])


def _alike(expression, kept=frozenset()) -> str:
    """``expression`` written with its names (but those ``kept``) by order of first appearance and
    library prefixes dropped (`np.abs(points[:, 0])` and `abs(p[:, 0])` are alike). Read only."""
    names: dict = {name: name for name in kept}

    class Renamed(ast.NodeTransformer):
        def visit_Attribute(self, node):
            if isinstance(node.value, ast.Name) and node.value.id in _LIBRARIES:
                return ast.Name(node.attr, ast.Load())
            return self.generic_visit(node)

        def visit_Call(self, node):
            function = node.func   # a called name is kept: it says what is done
            if isinstance(function, ast.Attribute) and isinstance(function.value, ast.Name) \
                    and function.value.id in _LIBRARIES:
                function = ast.Name(function.attr, ast.Load())
            elif not isinstance(function, ast.Name):
                function = self.visit(function)
            return ast.Call(function, [self.visit(a) for a in node.args],
                            [ast.keyword(k.arg, self.visit(k.value)) for k in node.keywords])

        def visit_Name(self, node):
            return ast.Name(names.setdefault(node.id, f"#{len(names)}"), ast.Load())

        def visit_Subscript(self, node):   # `a[2, :]`, `a[2, ...]` and `a[2]` index alike; `a[0:k]` is `a[:k]`
            value = self.visit(node.value)
            items = list(node.slice.elts) if isinstance(node.slice, ast.Tuple) else [node.slice]
            items = [ast.Slice(None, None, None) if _ellipsis(item) else item for item in items]
            while len(items) > 1 and _whole(items[-1]):
                items.pop()
            items = [ast.Slice(None if _zero(i.lower) else i.lower, i.upper, i.step) if isinstance(i, ast.Slice)
                     else i for i in items]
            index = items[0] if len(items) == 1 else ast.Tuple(items, ast.Load())
            return ast.Subscript(value, self.visit(index), ast.Load())

    return ast.dump(Renamed().visit(copy_tree(expression)), annotate_fields=False)


def _ellipsis(node) -> bool:
    return isinstance(node, ast.Constant) and node.value is Ellipsis


def _zero(node) -> bool:
    return isinstance(node, ast.Constant) and node.value == 0 and not isinstance(node.value, bool)


def _whole(node) -> bool:
    return isinstance(node, ast.Slice) and (node.lower is None or _zero(node.lower)) and node.upper is None \
        and node.step is None


def _mutant_calls(trial, mutant) -> set:
    """The names of the functions the mutant's changed defs call (empty when they cannot be made)."""
    model = model_for(trial.lab) if hasattr(trial, "lab") else None
    if model is None:
        return set()
    try:
        changed = mutated_defs(parse(model.source), mutant.edits, model.source)
    except (ValueError, SyntaxError):
        return set()
    return {_short(n) for n in walk(changed) if isinstance(n, ast.Call)}


_FLOAT_WORDS = re.compile(r"float|\bf[48]\b|\bdouble\b")


def _converts_result_of(function, short: str) -> bool:
    """Whether ``function`` converts to float what a call of ``short`` returns: the call itself, or a name given
    its result, inside `x.astype(float...)`, `np.float32(x)`, `np.asarray(x, float...)` or `np.array(x, ...)`."""
    given = {t.id for node in walk(function) if isinstance(node, ast.Assign) and isinstance(node.value, ast.Call)
             and _short(node.value) == short for t in node.targets if isinstance(t, ast.Name)}

    def made_by_it(node) -> bool:
        return (isinstance(node, ast.Call) and _short(node) == short) or (isinstance(node, ast.Name) and node.id in given)

    for node in walk(function):
        if not isinstance(node, ast.Call):
            continue
        name, text = _short(node), ast.unparse(node)
        if name == "astype" and isinstance(node.func, ast.Attribute) and made_by_it(node.func.value) \
                and _FLOAT_WORDS.search(ast.unparse(node.args[0]) if node.args else text):
            return True
        if node.args and made_by_it(node.args[0]) and (name.startswith("float")
                                                        or name in ("asarray", "array") and _FLOAT_WORDS.search(text)):
            return True
    return False


def _short(call) -> str:
    """The called function's own name (`floor` of `np.floor(...)`)."""
    return _dotted(call.func).rsplit(".", 1)[-1]


def _read_outside(function, name: str, makers: set) -> bool:
    """Whether ``function`` reads ``name`` somewhere outside every call of a function in ``makers``, and
    outside the statements that only rebind it (`dst = np.asarray(dst, float)` and never read again: the
    value is not used anywhere)."""
    inside = set()
    for node in walk(function):
        if isinstance(node, ast.Call) and _short(node) in makers:
            inside.update(id(n) for n in walk(node))
        if isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign)) and node.value is not None \
                and [_target_name(t) for t in getattr(node, "targets", [getattr(node, "target", None)])] == [name]:
            inside.update(id(n) for n in walk(node.value))
    return any(isinstance(n, ast.Name) and n.id == name and isinstance(n.ctx, ast.Load) and id(n) not in inside
               for n in walk(function))


def _target_name(target) -> str | None:
    return target.id if isinstance(target, ast.Name) else None


def _vouched_for(naming: Naming, trial) -> bool:
    """Whether the mutant's change sits in another graded function every check of which has passed in
    this grading: the student's own version of it is right there, so its answers come from elsewhere
    (a rotate composing T(-c) R T(c) answers as the reference's rotate whose rotation_matrix has the
    subtraction swapped -- the student's rotation_matrix passed)."""
    mutant = naming.mutant
    if mutant.where == mutant.function:
        return False
    from .repair import passing_functions

    return mutant.where in passing_functions(trial)


def _appended(message: str, naming: Naming) -> str:
    """``message`` with the error model's sentence at the end of its first line."""
    first, newline, rest = message.partition("\n")
    sentence = f"{APPENDED}{naming.sentence} ({naming.mutant.operator.replace('_', ' ')})."
    lead = first.rstrip()
    if lead and lead[-1] not in ".:;!?":   # "... is wrong" ends a sentence before the model's own
        lead += "."
    return f"{lead} {sentence}{newline}{rest}"


APPENDED = "The error model: it looks like "
REFUTED = "error model refuted"   # the shared key of (a name's sentence, whether a hidden check refuted it)


def take_back_refuted(results, refuted) -> None:
    """One account per function: the error model's names, in ``results`` (check results), that a later
    check of the same function refuted (``refuted``: (sentence, by a hidden check) pairs; its failing
    answers are not the named mutant's: the student's code is the same in every check) are taken back.
    A hidden check's refutation changes no public check's words. In place."""
    for result in results:
        if not (result.mistake.startswith("mutant:") and APPENDED in result.message):
            continue
        first, newline, rest = result.message.partition("\n")
        if any(sentence in first and (result.hidden or not by_hidden) for sentence, by_hidden in refuted):
            result.message = first.split(" " + APPENDED, 1)[0] + newline + rest
            result.mistake = ""


def defer_to_hand_written(graded, evidence=None) -> None:
    """Hand-written diagnoses keep precedence within an exercise: when a failed check of
    ``evidence`` (default ``graded``) names the mistake by hand, the error model's names appended
    to the checks of ``graded`` are taken back (one mistake, one name, whatever the checks' order:
    ``rotate`` and ``rotation_matrix`` share the mistake of the one it calls). Changed in place."""
    hand = any(((result.mistake and not result.mistake.startswith("mutant:"))
                or ("looks like" in result.message.lower() and APPENDED not in result.message))
               and result.score < result.max_score for result in (graded if evidence is None else evidence))
    for result in graded:
        if hand and result.mistake.startswith("mutant:") and APPENDED in result.message:
            first, newline, rest = result.message.partition("\n")
            result.message = first.split(" " + APPENDED, 1)[0] + newline + rest
            result.mistake = ""
