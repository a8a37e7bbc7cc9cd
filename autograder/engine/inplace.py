"""Inputs changed in place, where the effect shows: a second call on the same array.

A function that writes into its caller's array (``points /= scale``) answers its first
call rightly and every later one wrongly: the caller's array is no longer what it was.
The worker sends back each argument array a call changed, as the caller now holds it
(:attr:`autograder.sandbox.supervisor.CallOutcome.changed`). :func:`effect_of_change` then
calls the function twice more: on the same inputs again (a function whose answers vary
for the same input shows the change only where the answer moves far more than that), and on the
inputs as the caller now holds them.
When that second answer differs from the first, the change has an effect a caller meets,
and :meth:`autograder.engine.checks.Trial.call` fails the check naming it; a change without
effect (an idempotent write) keeps only the engine's 0-point advice.

Unless the lab sheet's own workflow shows or uses that argument after the call: a lab declares
such an argument with :func:`shown_after` (lab 12's ``depth_from_disparity(disparity, ...)``: its
exercise outputs the disparity map beside the depth map computed from it). There a change of its
values is itself the effect a caller meets, with no second call needed (29c's lab12/07 wrote inf
into the caller's invalid disparities: the depths right, the map shown afterwards not).

Each function loses points in one check per grading at most (the first public check where
the effect shows), not in every check that calls it.

The hint is held to the code (issue 35): "work on a copy" is measured (the caller's array did
change, so it was not copied before the write); "write x = x / s rather than x /= s" is said only
to code that writes an augmented assignment (``x /= s``, ``x[:, 0] -= c``), the usual way in.
"""

from __future__ import annotations

import re

import ast

import numpy as np

from .claims import guard, measured
from .compare import answer_scale, same_to_precision
from .hints import Predicate
from ..loading.parsing import walk

MISTAKE = "the caller's array is changed in place"


def with_changed(args: tuple, kwargs: dict, changed) -> tuple[tuple, dict] | None:
    """``(args, kwargs)`` with each changed array (``(position or keyword, index in a list or None,
    array)``) in its place; None when one has no place among them."""
    args, kwargs = list(args), dict(kwargs)
    for key, index, array in changed:
        if isinstance(key, int) and 0 <= key < len(args):
            holder, slot = args, key
        elif isinstance(key, str) and key in kwargs:
            holder, slot = kwargs, key
        else:
            return None
        if index is None:
            holder[slot] = array
        elif isinstance(holder[slot], (list, tuple)) and 0 <= index < len(holder[slot]):
            items = list(holder[slot])
            items[index] = array
            holder[slot] = type(holder[slot])(items) if isinstance(holder[slot], tuple) else items
        else:
            return None
    return tuple(args), kwargs


def argument_name(signature: str, key, index) -> str:
    """``points`` (or ``images[2]``) for the changed argument at ``key`` of ``signature``
    (``"normalise_points(points)"``)."""
    if isinstance(key, int):
        inside = signature.partition("(")[2].rpartition(")")[0]
        names = [re.split(r"[=:]", part)[0].strip().lstrip("*") for part in inside.split(",") if part.strip()]
        key = names[key] if key < len(names) else f"argument {key + 1}"
    return key if index is None else f"{key}[{index}]"


def how_changed(before, after) -> str:
    """What the call did to the array, in a verb the values show: "divides" (by one factor),
    "multiplies", "shifts" (the same offset for every row), else "writes into"."""
    try:
        b, a = np.asarray(before, np.float64), np.asarray(after, np.float64)
    except (TypeError, ValueError):
        return "writes into"
    if b.shape != a.shape or not (np.all(np.isfinite(b)) and np.all(np.isfinite(a))):
        return "writes into"
    with np.errstate(all="ignore"):
        if np.any(a) and np.all((a == 0) == (b == 0)):
            ratio = b[a != 0] / a[a != 0]
            if np.allclose(ratio, ratio[0], rtol=1e-9, atol=0) and abs(ratio[0]) != 1:
                return f"divides (by {ratio[0]:.4g})" if abs(ratio[0]) > 1 else f"multiplies (by {1 / ratio[0]:.4g})"
        offset = b - a
        rows = offset.reshape(len(offset), -1) if offset.ndim > 1 else offset[:, None]
        if offset.ndim and np.allclose(rows, rows[:1], rtol=0, atol=1e-12 * max(1.0, float(np.abs(b).max()))):
            added = -rows[0]
            if added.size <= 4:   # (the offset itself, as the call added it: `pts2[:, 0] += w1` is "adds [400, 0]")
                shown = ", ".join(f"{value + 0.0:.4g}" for value in added)   # (+ 0.0: no "-0")
                return f"shifts (adds {shown} to every entry of)" if offset.ndim == 1 else \
                    f"shifts (adds [{shown}] to every row of)"
            return "shifts (adds the same offset to every row of)"
    return "writes into"


# (module, function) -> {argument: where the lab sheet shows or uses it after the call}
SHOWN_AFTER: dict[tuple[str, str], dict[str, str]] = {}


def shown_after(lab, function: str, argument: str, where: str) -> None:
    """Declare that ``lab``'s sheet shows or uses ``function``'s ``argument`` after the call
    (``where``: the sheet's words, "ex2's output is the disparity map beside the depth map"): a
    change of its values in place is then an effect the caller meets, named and losing points
    like one a second call shows (see :func:`effect_of_change`)."""
    SHOWN_AFTER.setdefault((lab.module, function), {})[argument] = where


def values_changed(before, after) -> str:
    """How many values of the array changed, and the first few changes ("2 of its 6 values: 0
    became inf, -3 became inf"); ``""`` when none did (NaN equal to NaN, -0.0 to 0.0)."""
    b, a = np.asarray(before), np.asarray(after)
    if b.shape != a.shape:
        return f"its shape {b.shape} became {a.shape}"
    with np.errstate(invalid="ignore"):
        same = (b == a) | (np.isnan(b) & np.isnan(a) if b.dtype.kind == a.dtype.kind == "f" else False)
    where = np.flatnonzero(~np.asarray(same).ravel())
    if not where.size:
        return ""
    pairs = list(dict.fromkeys(f"{float(b.ravel()[i]):g} became {float(a.ravel()[i]):g}" for i in where[:12]))[:3]
    return f"{where.size} of its {b.size} values: " + ", ".join(pairs) + (", ..." if where.size > len(pairs) else "")


def _shown_change(function: str, signature: str, args: tuple, kwargs: dict, changed, module: str) -> str:
    """The sentence for a change of an argument declared :func:`shown_after`, or ``""``."""
    shown = SHOWN_AFTER.get((module, function), {})
    for key, index, after in changed:
        name = argument_name(signature, key, index)
        where = shown.get(name.partition("[")[0])
        if where is None:
            continue
        try:
            holder = args[key] if isinstance(key, int) else kwargs[key]
            before = holder[index] if index is not None else holder
        except (IndexError, KeyError, TypeError):   # no place among the arguments (see with_changed)
            continue
        changes = values_changed(before, after)
        if changes:
            return (f"{function}() {how_changed(before, after)} the caller's `{name}` in place ({changes}). "
                    f"The lab sheet shows or uses `{name}` after the call ({where}): what is shown then is no "
                    "longer what was passed.")
    return ""


def effect_of_change(call, function: str, signature: str, args: tuple, kwargs: dict, outcome,
                     fingerprint, module: str = "") -> str:
    """The sentence saying how ``function``'s change of its caller's array shows, or ``""``.

    ``call(args, kwargs)`` calls the student's function once more and returns its answer (None
    when that call failed: nothing is told then); ``outcome`` is the first call's, with the
    changed arrays; ``fingerprint`` tells answers apart. An argument of ``module``'s function
    declared :func:`shown_after` needs no second call: its change is the effect.
    """
    shown = _shown_change(function, signature, args, kwargs, outcome.changed, module)
    if shown:
        return shown
    again = with_changed(args, kwargs, outcome.changed)
    if again is None:
        return ""
    repeated = call(args, kwargs)
    if repeated is None:
        return ""
    second = call(*again)
    if second is not None and _same(second, outcome.value, fingerprint):
        return ""
    if _same(repeated, outcome.value, fingerprint) and second is not None \
            and _apart(second, outcome.value) <= VARYING_EFFECT:
        # (a small difference: the array's, or a draw's whose repeat happened to fall near the first? one more call
        # of the same inputs tells -- two draws as near as that by chance are rare, three are rarer still)
        once_more = call(args, kwargs)
        if once_more is not None and not _same(once_more, outcome.value, fingerprint):
            repeated = once_more
    if not _same(repeated, outcome.value, fingerprint):
        # Its answers vary for the same input (a random draw, or noise added to each answer: hostile round of
        # 2026-12-07, 1e-5 of jitter): the changed array shows only where its answer is far farther from the first
        # than the same inputs' answer is (a draw's own spread says nothing of the array).
        spread, apart = _apart(repeated, outcome.value), _apart(second, outcome.value) if second is not None else np.inf
        if not apart > max(SPREAD_FACTOR * spread, VARYING_EFFECT):
            return ""
    key, index, after = outcome.changed[0]
    name = argument_name(signature, key, index)
    holder = args[key] if isinstance(key, int) else kwargs[key]
    before = holder[index] if index is not None else holder
    result = "failed" if second is None else "returned a different result"
    return (f"{function}() {how_changed(before, after)} the caller's `{name}` in place: called a second time "
            f"on that same array, as the caller holds it after the first call, it {result}. A caller that "
            "calls it twice, or uses its array afterwards, gets wrong values.")


SAME = 1e-7   # relative to the answer's largest entry: the same answer, but for noise a caller would never see
SPREAD_FACTOR = 10.0   # how much farther than the same inputs' answer the changed array's must be (answers that vary),
VARYING_EFFECT = 1e-3   # and at least (relative to the largest entry): one draw's spread measured is itself a draw


def same_answer(a, b, relative: float = SAME) -> bool:
    """Whether answers ``a`` and ``b`` are one answer, to ``relative`` of their largest entry (:func:`_same`)."""
    from .checks import fingerprint

    return _same(a, b, fingerprint, relative)


def _apart(a, b) -> float:
    """How far answer ``a`` is from ``b``: the largest difference of their numbers relative to ``b``'s largest finite
    entry (at least 1); infinite where their structures, shapes or kinds differ or NaN is not where NaN is."""
    if isinstance(a, (tuple, list)) or isinstance(b, (tuple, list)):
        if not (isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)) and len(a) == len(b)):
            return np.inf
        return max([_apart(x, y) for x, y in zip(a, b)], default=0.0)
    try:
        x, y = np.asarray(a), np.asarray(b)
    except Exception:  # noqa: BLE001 - an answer NumPy cannot read: apart unless equal
        return 0.0 if a == b else np.inf
    if x.shape != y.shape or x.dtype.kind not in "biuf" or y.dtype.kind not in "biuf":
        return 0.0 if x.shape == y.shape and np.array_equal(x, y) else np.inf
    x, y = x.astype(np.float64), y.astype(np.float64)
    if not np.array_equal(np.isnan(x), np.isnan(y)):
        return np.inf
    with np.errstate(invalid="ignore"):
        difference = np.where((x == y) | (np.isnan(x) & np.isnan(y)), 0.0, np.abs(x - y))
    return float(difference.max()) / answer_scale(y) if difference.size else 0.0


def _same(a, b, fingerprint, relative: float = SAME) -> bool:
    """Whether answers ``a`` and ``b`` are one answer: equal, or of the same structure with their numbers the same
    to the precision computed in (:func:`.compare.same_to_precision`, :data:`SAME`). A last digit's noise added to
    every answer (hostile round of 2026-12-07) does not make a repeated call's answer another one."""
    if fingerprint(a) == fingerprint(b):
        return True
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)):
        return len(a) == len(b) and all(_same(x, y, fingerprint, relative) for x, y in zip(a, b))
    try:
        x, y = np.asarray(a), np.asarray(b)
    except Exception:  # noqa: BLE001 - an answer NumPy cannot read is compared by its fingerprint alone
        return False
    return x.size > 0 and x.dtype.kind in "biuf" and y.dtype.kind in "biuf" and same_to_precision(x, y, relative)


AUGMENTS = Predicate("writes an augmented assignment (x /= s)",
                     lambda function: any(isinstance(node, ast.AugAssign) for node in walk(function)))
# (x.astype(float) copies too, whatever x's dtype; np.asarray(x, dtype=float) of a float array does not)
HINT = (measured("work on a copy: x = np.array(x, dtype=float) copies (np.asarray(x, dtype=float) of a float "
                 "array does not)")
        + guard(", and write x = x / s rather than x /= s", ~AUGMENTS, instead=""))


# ---------------------------------------------------------------- where the code writes into its input
# What the code holds of an argument without copying it: the name itself, np.asarray of it (a float array given is
# returned as it is), a reshape, a view, a plain slice, its transpose.
_VIEWS = frozenset({"asarray", "asanyarray", "reshape", "view", "ravel", "squeeze", "atleast_1d", "atleast_2d"})
_VERB_OPS = {"divides": (ast.Div, ast.FloorDiv, ast.Mult), "multiplies": (ast.Mult, ast.Div),
             "shifts": (ast.Add, ast.Sub)}


def _held(value, aliases) -> str | None:
    """The name of ``aliases`` that ``value`` holds without a copy (`x`, `x[:]`, `x.T`, `x.reshape(-1, 2)`,
    `np.asarray(x, dtype=float)`), or None."""
    if isinstance(value, ast.Name):
        return value.id if value.id in aliases else None
    if isinstance(value, ast.Subscript) and isinstance(value.slice, ast.Slice):
        return _held(value.value, aliases)
    if isinstance(value, ast.Attribute) and value.attr == "T":
        return _held(value.value, aliases)
    if not isinstance(value, ast.Call) or not isinstance(value.func, ast.Attribute) \
            or any(k.arg == "copy" for k in value.keywords):
        return None
    function, name = value.func, value.func.attr
    if isinstance(function.value, ast.Name) and function.value.id in ("np", "numpy"):
        return _held(value.args[0], aliases) if name in _VIEWS and value.args else None
    return _held(function.value, aliases) if name in _VIEWS else None


def writes_into_arguments(functions, verb: str = "") -> list[tuple]:
    """[(def, statement, the parameter written, the statement that made the alias or None)]: each statement of
    ``functions`` (the student's defs) that writes into an array one of its parameters was given -- an augmented
    assignment (`centred -= c`) or an item assignment (`pts[:, 0] = ...`) on the parameter or on a name holding it
    without a copy (`centred = points`, `x = np.asarray(x)`). ``verb``, :func:`how_changed`'s, keeps the
    arithmetic that changes an array so ("divides": `/=`, `*=`; "shifts": `+=`, `-=`). Read in the order of the
    lines, names rebound to anything else dropped; linear in the defs' length."""
    allowed = next((ops for word, ops in _VERB_OPS.items() if verb.startswith(word)), None)
    found = []
    for fn in functions:
        aliases = _alias_pass(fn)
        for node, written in aliases.writes:
            if allowed is None or (isinstance(node, ast.AugAssign) and isinstance(node.op, allowed)):
                found.append((fn, node) + written)
    return found


class _alias_pass:
    """One pass over ``fn``'s assignments in line order: ``held`` {name: (the parameter it holds without a copy, the
    statement that made it so or None)} as the def ends, ``ever`` every name that held a parameter (flow-insensitive),
    and ``writes`` [(statement, (parameter, alias statement))] of the writes into a held array."""

    def __init__(self, fn):
        parameters = [a.arg for a in fn.args.posonlyargs + fn.args.args + fn.args.kwonlyargs]
        held = {name: (name, None) for name in parameters}
        self.ever: dict[str, str] = {name: name for name in parameters}
        self.writes: list = []
        statements = sorted((node for node in walk(fn) if isinstance(node, (ast.Assign, ast.AugAssign))),
                            key=lambda node: (node.lineno, node.col_offset))
        for node in statements:
            if isinstance(node, ast.AugAssign):
                target = node.target.value if isinstance(node.target, ast.Subscript) else node.target
                if isinstance(target, ast.Name) and target.id in held:
                    self.writes.append((node, held[target.id]))
                continue
            for target in node.targets:
                if isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name) and target.value.id in held:
                    self.writes.append((node, held[target.value.id]))
                elif isinstance(target, ast.Name):
                    source = _held(node.value, held)
                    if source is not None:
                        root, made = held[source]
                        held[target.id] = (root, made or node)
                        self.ever[target.id] = root
                    else:
                        held.pop(target.id, None)
        self.held = held


def place_of_change(functions, verb: str = "", function: str = "", parameter: str = "") -> str:
    """The sentence saying where the student's code writes into its caller's array, when one statement of
    ``functions`` does (:func:`writes_into_arguments`); "" when none or several do (the place is then not
    certain). Given the graded ``function`` whose ``parameter`` was changed, only writes into that parameter count:
    in ``function`` itself, and in a helper it calls with that array (or a name holding it) as an argument."""
    found = writes_into_arguments(functions, verb)
    if function and parameter:
        targets = _written_through(functions, function, parameter)
        found = [entry for entry in found if entry[2] in targets.get(entry[0].name, ())]
    if len(found) != 1:
        return ""
    fn, statement, _, made = found[0]
    text = ast.unparse(statement)
    where = f"line {statement.lineno}, in `{fn.name}`"
    if made is None:
        return f"Your code writes into it at {where}: `{text}` changes the array given."
    return (f"Your code writes into it at {where}: `{text}` changes the array given, which `{ast.unparse(made)}` "
            f"(line {made.lineno}) does not copy.")


def _written_through(functions, function: str, parameter: str) -> dict[str, set]:
    """{def name: the parameters through which it may write into ``function``'s ``parameter``}: that parameter in
    ``function``, and each helper's parameter that ``function`` passes it to (one call deep)."""
    defs = {fn.name: fn for fn in functions}
    graded = defs.get(function)
    if graded is None:
        return {}
    names = {name for name, root in _alias_pass(graded).ever.items() if root == parameter}
    targets = {function: {parameter}}
    for node in walk(graded):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in defs \
                and node.func.id != function:
            helper = defs[node.func.id].args
            positional = [a.arg for a in helper.posonlyargs + helper.args]
            for name, value in list(zip(positional, node.args)) + [(k.arg, k.value) for k in node.keywords]:
                if name and any(isinstance(n, ast.Name) and n.id in names for n in walk(value)):
                    targets.setdefault(node.func.id, set()).add(name)
    return targets
