"""Hints that never contradict the student's code.

A fixed hint tells the student to do something ("keep the disparity with the HIGHEST
score", "warp img2 with T @ H", "choose the pose with cv2.recoverPose"). When the code
already does it, the hint is wrong about the student and sends them the wrong way. So a
hint declares, next to its text, the code it asks for -- a small predicate over the
student's function read with :mod:`ast` (parsed, never executed)::

    NCC_HINT = Hint("... it is a similarity: keep the disparity with the HIGHEST score",
                    asks=calls("np.argmax") | calls(".argmax"),
                    instead="... your code keeps the highest score (argmax); the error is elsewhere")

and a check gives ``NCC_HINT.said(t)`` (a ``str``) where it used the text. The predicate
is evaluated on the functions the check calls (:func:`~autograder.engine.stubs.functions_called`,
or those the hint names) and on the module's functions they call; when it holds, the
hint says ``instead`` (a neutral sentence, or nothing) rather than its text.

Predicates (combine with ``|``, ``&`` and ``~``):

- :func:`calls` -- a call of ``np.argmax`` (numpy's, however it is imported: ``numpy.argmax``,
  ``xp.argmax``, ``argmax`` imported from numpy, or a method ``a.argmax``; never a function the
  student's module defines) or, written ``".argmax"``, an attribute call only;
- :func:`mentions` -- a name or attribute (``"cv2.BORDER_CONSTANT"``, ``".T"``);
  :func:`uses_attr` is its spelling for attributes;
- :func:`matmul_of` -- a matrix product of two operands (``T @ H``, ``np.dot(T, H)``,
  ``T.dot(H)``, ``np.matmul(T, H)``), each a name or ``None`` for any operand;
- :func:`expr` -- a sub-expression with the pattern's structure (``"max_disparity + 1"``,
  ``_`` matching anything);
- :func:`keyword` -- a call passing ``name=value`` (``keyword("svd", "full_matrices", False)``);
- :func:`passes_product` -- a call given a matrix product as one argument (``cv2.warpPerspective(img,
  T @ H, size)``, or through a name holding the product).

A predicate reads only what is written: ``calls("np.argmax")`` holds for a function that
calls ``np.argmax`` somewhere, whatever it does with the result. That is the point: a hint
asking for code the student wrote is wrong about them whatever else is wrong, and the
neutral sentence says only that ("your code calls np.argmax; the error is elsewhere").
Without a submission to read (a check run on a stand-in sandbox) every hint keeps its text.
"""

from __future__ import annotations

import ast
import inspect
import itertools
import re
from collections import Counter
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path
from typing import Callable, Iterable

from ..loading.parsing import parse, walk
from ..loading.reading import MAX_NODES, MAX_SOURCE_BYTES, overwritten_running_bests


# ------------------------------------------------------------------ predicates
@dataclass(frozen=True)
class Predicate:
    """A test of the student's code: ``test(node) -> bool`` on one ``FunctionDef`` (a leaf), or
    ``a | b``, ``a & b``, ``~a`` of predicates over the functions read together (``a & b``
    holds when each holds in one of them: a helper may do one part). ``says`` what it found,
    in words that fit "your code already ...": "calls np.argmax"."""

    says: str
    test: Callable[[ast.AST], bool] | None = field(default=None, compare=False)
    kind: str = "leaf"   # "leaf", "all" (a test of every function read), "or", "and", "not"
    parts: tuple = ()
    told: bool = False   # ``says`` was given with :meth:`saying` (an "or" then says it, not its part)

    def found(self, functions: Iterable[ast.AST]) -> str:
        """What holds in ``functions`` in words (for ``a | b``, the alternative found); "" when
        nothing does (never raises)."""
        functions = list(functions)
        if self.kind == "or":
            said = next(filter(None, (part.found(functions) for part in self.parts)), "")   # each part once
            return (self.says if self.told else said) if said else ""
        if self.kind == "and":
            return self.says if all(part.found(functions) for part in self.parts) else ""
        if self.kind == "not":
            return "" if self.parts[0].found(functions) else self.says
        if self.kind == "all":   # a test of the functions read together (a value followed across them)
            try:
                return self.says if self.test(functions) else ""
            except (RecursionError, ValueError, TypeError, AttributeError):
                return ""
        for function in functions:
            try:
                if self.test(function):
                    return self.says
            except (RecursionError, ValueError, TypeError, AttributeError):
                continue
        return ""

    def holds(self, functions: Iterable[ast.AST]) -> bool:
        return bool(self.found(functions))

    def saying(self, says: str) -> "Predicate":
        """This predicate, saying ``says`` when it holds ("computes T @ H" for ``matmul_of(None, "H")``)."""
        return replace(self, says=says, told=True)

    def __or__(self, other: "Predicate") -> "Predicate":
        return Predicate(f"{self.says} or {other.says}", kind="or", parts=(self, other))

    def __and__(self, other: "Predicate") -> "Predicate":
        return Predicate(f"{self.says} and {other.says}", kind="and", parts=(self, other))

    def __invert__(self) -> "Predicate":
        return Predicate(f"does not: {self.says}", kind="not", parts=(self,))


def call_in_a_loop(functions, names) -> tuple[str, int] | None:
    """(the call as written, its line) of the first call of one of ``names`` (the last part of its dotted
    name: "calibrateCamera") made in a loop's body or a comprehension of ``functions``: a step the sheet makes
    once, made for each item (each view calibrated alone); None when there is none."""
    for function in functions:
        for loop in walk(function):
            body = loop.body if isinstance(loop, (ast.For, ast.While)) else [loop.elt] \
                if isinstance(loop, (ast.ListComp, ast.GeneratorExp, ast.SetComp)) else []
            for node in (n for part in body for n in walk(part)):
                if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in names:
                    return _path(node.func), node.lineno
    return None


def step_under_a_condition(functions, matches) -> tuple[str, int, int] | None:
    """(the test as written, its line, the step's line) of the first node ``matches`` accepts that runs only
    under an ``if`` of ``functions`` (in its body or its else): a step the sheet makes always, made on some
    inputs only; None when there is none, or when one of them runs outside every ``if`` (the step is made
    always there, whatever the test elsewhere). One pass over each function."""
    found = None
    for function in functions:
        todo = [(function, None)]   # (node, the innermost if whose body or else holds it)
        while todo:
            node, branch = todo.pop()
            if node is not function and matches(node):
                if branch is None:
                    return None
                here = (" ".join(ast.unparse(branch.test).split()), branch.lineno, node.lineno)
                found = min(found, here, key=lambda f: f[2]) if found else here   # (the first in the file)
            if isinstance(node, ast.If):
                todo.append((node.test, branch))
                todo.extend((part, node) for part in node.body + node.orelse)
            else:
                todo.extend((child, branch) for child in ast.iter_child_nodes(node))
    return found


def _path(node) -> str:
    """``np.linalg.svd`` for that expression, ``.argmax`` for ``x.argmax`` on anything else."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    head = node.id if isinstance(node, ast.Name) else ""
    return ".".join([head, *reversed(parts)])


# Module names as students import them, when the module read has no import saying otherwise.
_CONVENTIONAL = {"np": "numpy", "numpy": "numpy", "cv2": "cv2", "cv": "cv2", "scipy": "scipy", "math": "math"}
_FAMILY = {"scipy": "numpy"}   # scipy.linalg.svd is an SVD as numpy.linalg.svd is


@dataclass(frozen=True)
class Scope:
    """What the names of one module refer to (read from its ``import`` statements and ``def``s,
    wherever they are): ``modules`` local name -> module (``cv`` -> ``cv2``, ``la`` -> ``numpy.linalg``),
    ``imported`` local name -> module attribute (``rp`` -> ``cv2.recoverPose``), ``defined`` the
    module's own functions and classes, ``star`` the modules imported with ``*``."""

    modules: dict
    imported: dict
    defined: frozenset
    star: tuple


def scope_of(tree: ast.AST) -> Scope:
    """The :class:`Scope` of a parsed module (or of one function read alone)."""
    modules, imported, defined, star = {}, {}, set(), []
    for node in walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.asname:
                    modules[alias.asname] = alias.name
                else:   # import numpy.linalg binds numpy
                    head = alias.name.split(".")[0]
                    modules[head] = head
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            for alias in node.names:
                if alias.name == "*":
                    star.append(node.module)
                else:
                    imported[alias.asname or alias.name] = f"{node.module}.{alias.name}"
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            defined.add(node.name)
    return Scope(modules, imported, frozenset(defined), tuple(star))


def _scope(function) -> Scope:
    """The scope :func:`read_code` gave ``function`` (its module's), else the function's own."""
    found = getattr(function, "_hint_scope", None)
    if found is None:
        found = scope_of(function)
        function._hint_scope = found
    return found


def _resolved(node, scope: Scope) -> tuple[str, str]:
    """``(kind, path)`` of the name or attribute chain ``node``: ``("module", "cv2.recoverPose")``
    for a module's attribute under any alias or imported from it, ``("own", "recoverPose")`` for a
    function or class of the student's module, ``("method", ".argmax")``/``("method", "a.argmax")``
    for an attribute of a value, ``("bare", "argmax")`` for any other name (a builtin, a local)."""
    path = _path(node)
    head, _, rest = path.partition(".")
    tail = f".{rest}" if rest else ""
    if head in scope.modules:
        return "module", scope.modules[head] + tail
    if head in scope.imported:
        return "module", scope.imported[head] + tail
    if head in scope.defined:
        return "own", path
    if head in _CONVENTIONAL and rest:
        return "module", _CONVENTIONAL[head] + tail
    return ("method" if rest or not head else "bare"), path


def _root(module_path: str) -> str:
    head = module_path.split(".")[0]
    head = _CONVENTIONAL.get(head, head)
    return _FAMILY.get(head, head)


def _name_matches(node, wanted: str, scope: Scope) -> bool:
    """Whether the name or attribute chain ``node`` refers to ``wanted``.

    ``"np.argmax"``: that module's function (the same last name, the module under any alias or
    imported from, numpy's submodules and scipy counting as numpy), or a method of that name of a
    value (``x.argmax``); never a function the student's module defines, nor another module's.
    ``".argmax"``: an attribute of anything (``x.argmax``, ``np.argmax``), not a bare name nor the
    student's own function. ``"argmax"``: the last name only (the student's own functions too:
    ``calls("transform_points")``)."""
    kind, path = _resolved(node, scope)
    last = wanted.rsplit(".", 1)[-1]
    if path.rsplit(".", 1)[-1] != last:
        return False
    if "." not in wanted:
        return True
    if wanted.startswith("."):
        return kind in ("module", "method")
    if kind == "module":
        return _root(path) == _root(wanted)
    if kind == "bare":   # a module's function only under a star import of it
        return any(_root(module) == _root(wanted) for module in scope.star)
    return kind == "method"


def calls(name: str, at_least: int = 1) -> Predicate:
    """A call of ``name`` (see :func:`_name_matches` for how prefixes match); with ``at_least``, in at
    least that many places of the functions read together (a helper may make one of them: the 8-point
    solve's SVD in a helper, the rank-2 one in the function)."""
    shown = name.lstrip(".")

    def count(function) -> int:
        return sum(1 for node in walk(function)
                   if isinstance(node, ast.Call) and _name_matches(node.func, name, _scope(function)))
    if at_least <= 1:
        return Predicate(f"calls {shown}", lambda function: count(function) >= 1)
    return Predicate(f"calls {shown} in {at_least} places", lambda functions: sum(map(count, functions)) >= at_least,
                     kind="all")


RANDOM_DRAWS = frozenset({"choice", "sample", "permutation", "shuffle", "integers", "randint", "random_sample", "random",
                          "rand"})   # (`np.argsort(rng.random((k, n)))[:, :4]`: samples drawn in a batch)


def _drawn_names(function) -> set[str]:
    """The names holding a random draw, or made from one (`idx = rng.permutation(n)`, `sample = idx[:4]`,
    `for idx in samples` over drawn samples), never a mask a comparison makes."""
    bindings = [(node.targets, node.value) for node in walk(function) if isinstance(node, ast.Assign)] + \
        [([node.target], node.iter) for node in walk(function) if isinstance(node, (ast.For, ast.comprehension))]
    # (a name a comparison binds is a mask, whatever it was measured from: `inliers = errors < threshold`
    # with the errors of drawn samples picks the pairs a model keeps, not a random sample -- nor is a copy of it
    # kept as the best so far, `best_inliers = inliers`, then refined, `mask = best_inliers`)
    masks = {n.id for targets, value in bindings if isinstance(value, ast.Compare)
             for t in targets for n in walk(t) if isinstance(n, ast.Name)}
    drawn: set[str] = set()
    grown = True
    while grown:
        grown = False
        for targets, value in bindings:
            reads = {n.id for n in walk(value) if isinstance(n, ast.Name)}
            draws = any(isinstance(c, ast.Call) and isinstance(c.func, (ast.Attribute, ast.Name))
                        and (c.func.attr if isinstance(c.func, ast.Attribute) else c.func.id) in RANDOM_DRAWS
                        for c in walk(value))
            if draws or reads & drawn:
                made = {n.id for t in targets for n in walk(t) if isinstance(n, ast.Name)} - drawn - masks
                if made:
                    drawn |= made
                    grown = True
    return drawn


def picked_point_fits(function, name: str) -> list[ast.Call]:
    """The calls of ``name`` in ``function`` given points some chosen subset picks (`homography_dlt(
    src[inliers], dst[inliers])`): refits on the inliers, not the fit of a random sample (`src[sample]`,
    a name holding a draw) nor of every point (`homography_dlt(src, dst)`)."""
    drawn = _drawn_names(function)
    return [node for node in walk(function)
            if isinstance(node, ast.Call) and _name_matches(node.func, name, _scope(function))
            and any(isinstance(argument, ast.Subscript) and not isinstance(argument.slice, ast.Slice)
                    and not {n.id for n in walk(argument.slice) if isinstance(n, ast.Name)} & drawn
                    and any(isinstance(n, ast.Name) for n in walk(argument.slice)) for argument in node.args)]


def fits_on_picked_points(name: str) -> Predicate:
    """A refit of ``name`` on the points a mask picks (:func:`picked_point_fits`)."""
    shown = name.lstrip(".")
    return Predicate(f"fits {shown} again on the points a mask picks",
                     lambda function: bool(picked_point_fits(function, name)))


def mentions(name: str) -> Predicate:
    """A name or attribute ``name`` read anywhere (``"cv2.BORDER_CONSTANT"``, ``".T"``, ``"np.nan"``)."""
    shown = name.lstrip(".")

    def test(function) -> bool:
        for node in walk(function):
            if isinstance(node, (ast.Attribute, ast.Name)) and _name_matches(node, name, _scope(function)):
                return True
        return False
    return Predicate(f"uses {shown}", test)


def uses_attr(attribute: str) -> Predicate:
    """The attribute ``attribute`` (``".T"``) of anything."""
    return mentions(attribute if attribute.startswith(".") else "." + attribute)


def _holds_name(node, name: str | None) -> bool:
    return name is None or any(isinstance(n, ast.Name) and n.id == name for n in walk(node))


def matmul_of(left: str | None, right: str | None) -> Predicate:
    """A matrix product ``left @ right`` (or ``np.dot``/``np.matmul``/``left.dot(right)``), each
    operand an expression holding that name (``None``: any operand)."""
    shown = f"{left or 'M'} @ {right or 'M'}"

    def operands(node):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult):
            return node.left, node.right
        if isinstance(node, ast.Call):
            path = _path(node.func)
            if path.rsplit(".", 1)[-1] in ("dot", "matmul"):
                if len(node.args) == 2:
                    return node.args[0], node.args[1]
                if len(node.args) == 1 and isinstance(node.func, ast.Attribute) \
                        and not (isinstance(node.func.value, ast.Name) and node.func.value.id in ("np", "numpy")):
                    return node.func.value, node.args[0]
        return None

    def test(function) -> bool:
        for node in walk(function):
            pair = operands(node)
            if pair and _holds_name(pair[0], left) and _holds_name(pair[1], right):
                return True
        return False
    return Predicate(f"computes {shown}", test)


def _product(node) -> bool:
    """Whether ``node`` is a matrix product (``a @ b``, ``np.dot(a, b)``, ``np.matmul(a, b)``, ``a.dot(b)``)."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult):
        return True
    return isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in ("dot", "matmul") \
        and len(node.args) + isinstance(node.func, ast.Attribute) >= 2


def passes_product(function: str, position: int) -> Predicate:
    """A call of ``function`` whose argument at ``position`` is a matrix product, written there or
    held by a name the function assigns a product to (``M = T @ H; cv2.warpPerspective(img, M, ...)``)."""
    def test(tree) -> bool:
        products = {target.id for node in walk(tree) if isinstance(node, ast.Assign) and _product(node.value)
                    for target in node.targets if isinstance(target, ast.Name)}
        for node in walk(tree):
            if isinstance(node, ast.Call) and _name_matches(node.func, function, _scope(tree)) \
                    and len(node.args) > position:
                given = node.args[position]
                if _product(given) or (isinstance(given, ast.Name) and given.id in products):
                    return True
        return False
    return Predicate(f"passes a matrix product to {function.lstrip('.')}", test)


def _same(node, pattern) -> bool:
    """Whether ``node`` has ``pattern``'s structure (the name ``_`` in it matches anything)."""
    if isinstance(pattern, ast.Name) and pattern.id == "_":
        return True
    if type(node) is not type(pattern):
        return False
    for name, value in ast.iter_fields(pattern):
        if name == "ctx":
            continue
        other = getattr(node, name, None)
        if isinstance(value, list):
            if not isinstance(other, list) or len(other) != len(value) or \
                    not all(_same(a, b) if isinstance(b, ast.AST) else a == b for a, b in zip(other, value)):
                return False
        elif isinstance(value, ast.AST):
            if not isinstance(other, ast.AST) or not _same(other, value):
                return False
        elif value != other:
            return False
    return True


def expr(pattern: str) -> Predicate:
    """A sub-expression shaped like ``pattern`` (``"max_disparity + 1"``; ``_`` matches anything)."""
    wanted = parse(pattern, mode="eval", max_chars=None, max_statements=None).body

    named = {node.id for node in walk(wanted) if isinstance(node, ast.Name)}

    def test(function) -> bool:
        if named & getattr(function, "_rebound", set()):
            return False   # (a helper's parameter of that name holds another value: not the caller's expression)
        return any(_same(node, wanted) for node in walk(function))
    return Predicate("computes " + re.sub(r"\b_\b", "...", pattern), test)


ANY = object()   # keyword(..., value=ANY): any value


def keyword(function: str, name: str, value=ANY) -> Predicate:
    """A call of ``function`` passing ``name=value`` (a constant, or a dotted name such as
    ``"cv2.BORDER_CONSTANT"`` given as :class:`str` and matched like :func:`mentions`; by
    default any value)."""
    def matches(node, scope) -> bool:
        if value is ANY:
            return True
        if isinstance(node, ast.Constant):
            return node.value == value and type(node.value) is type(value)
        return isinstance(value, str) and isinstance(node, (ast.Attribute, ast.Name)) \
            and _name_matches(node, value, scope)

    def test(tree) -> bool:
        scope = _scope(tree)
        return any(isinstance(node, ast.Call) and _name_matches(node.func, function, scope)
                   and any(k.arg == name and matches(k.value, scope) for k in node.keywords)
                   for node in walk(tree))
    shown = f"{name}=" if value is ANY else f"{name}={value}"
    return Predicate(f"passes {shown} to {function.lstrip('.')}", test)


# ------------------------------------------------------------------ picking the best score
# A disparity (or any index) kept for the highest score is kept, equally, by the argmin of the
# score negated (a cost ``-ncc``, ``1 - ncc``, stored by a helper), by the last entry of an
# ascending argsort, by ``max(..., key=...)`` and by a loop keeping ``score > best``. Whether
# the value an argmin/argmax picks from is negated is followed through the code: names assigned
# in the function (``costs[d] = -ncc`` counts for ``costs``), the module's functions it calls
# (their returned value), each negation flipping the sign; a score is recognised by its name
# (``score``, ``ncc``, ``corr``, ...), so a negated shift (``-d``) is no negated score.
SCORE_NAMES = ("score", "ncc", "corr", "sim", "zncc", "nxc", "cov")
COST_NAMES = ("cost", "ssd", "sad", "energy", "err", "dist", "diff")
_FOLLOW = 8   # steps followed back from the picked value


def _named(node, names) -> bool:
    """Whether an identifier in ``node`` (a name, an attribute or a called function's) holds one of ``names``."""
    for n in walk(node):
        ident = n.id if isinstance(n, ast.Name) else n.attr if isinstance(n, ast.Attribute) else None
        if ident and any(word in ident.lower() for word in names):
            return True
    return False


def _plain_negation(node):
    """The operand of ``-x`` or ``c - x`` (``c`` a constant), else None."""
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and not isinstance(node.operand, ast.Constant):
        return node.operand
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Sub) and isinstance(node.left, ast.Constant):
        return node.right
    return None


def _negation(node):
    """The operand of ``-x`` or ``c - x`` (``c`` a constant), or of a product or quotient one factor of which is
    negated so (`-cov / (denom + 1e-6)` is the NCC negated), else None. One level only: a chain of divisions is
    read in constant time, whatever its length."""
    plain = _plain_negation(node)
    if plain is not None or not (isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Div, ast.Mult))):
        return plain
    left, right = _plain_negation(node.left), _plain_negation(node.right)
    if left is not None and right is None:
        return ast.BinOp(left, node.op, node.right)
    if right is not None and left is None and isinstance(node.op, ast.Mult):
        return ast.BinOp(node.left, node.op, right)
    return None


def _target_name(target) -> str | None:
    while isinstance(target, ast.Subscript):
        target = target.value
    return target.id if isinstance(target, ast.Name) else None


class _Signs:
    """Follows a value back through one module's functions: ``(negated, named)`` -- whether it is
    negated an odd number of times on its way, and whether a value named by ``names`` is met."""

    def __init__(self, functions, names):
        self.functions = {f.name: f for f in functions if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))}
        self.names = names

    def of(self, node, function, steps: int = _FOLLOW) -> tuple[bool, bool]:
        if steps <= 0 or node is None:
            return False, False
        operand = _negation(node)
        if operand is not None:
            negated, named = self.of(operand, function, steps - 1)
            return not negated, named or _named(operand, self.names)
        if isinstance(node, ast.Name):
            values = self._assigned(node.id, function)
            if not values:
                return False, _named(node, self.names)
            negated, named = self.of(values[-1], function, steps - 1)
            return negated, named or _named(node, self.names)
        if isinstance(node, ast.Call):
            called = self._called(node.func)
            if called is not None:
                returned = [n.value for n in walk(called) if isinstance(n, ast.Return) and n.value is not None]
                if returned:
                    negated, named = self.of(returned[-1], called, steps - 1)
                    return negated, named or _named(node.func, self.names)
            first = node.args[0] if node.args else None   # np.asarray(x), x.astype(...): follow x
            if isinstance(node.func, ast.Attribute) and not (isinstance(node.func.value, ast.Name)
                                                               and node.func.value.id in ("np", "numpy")):
                first = node.func.value
            negated, named = self.of(first, function, steps - 1)
            return negated, named or _named(node, self.names)
        return False, _named(node, self.names)

    def _assigned(self, name: str, function) -> list:
        """The values stored in ``name`` (or its elements) in ``function`` that carry something
        (not a constant or an array filled with one)."""
        values = []
        for n in walk(function):
            if isinstance(n, ast.Assign):
                targets, value = n.targets, n.value
            elif isinstance(n, (ast.AugAssign, ast.AnnAssign)) and n.value is not None:
                targets, value = [n.target], n.value
            else:
                continue
            if any(_target_name(t) == name for t in targets) and not self._filler(value):
                values.append(value)
        return values

    @staticmethod
    def _filler(value) -> bool:
        if isinstance(value, ast.Constant) or (isinstance(value, ast.Attribute) and value.attr in ("inf", "nan")):
            return True
        return isinstance(value, ast.Call) and _path(value.func).rsplit(".", 1)[-1] in (
            "full", "zeros", "ones", "empty", "full_like", "zeros_like", "ones_like", "empty_like")

    def _called(self, func):
        """The module function ``func`` calls (of an ``a if c else b`` of two, the one named by ``names``)."""
        if isinstance(func, ast.IfExp):
            branches = [b for b in (func.body, func.orelse) if _named(b, self.names)]
            func = branches[0] if branches else func.body
        return self.functions.get(func.id) if isinstance(func, ast.Name) else None


def _picks(highest: bool, names) -> Callable[[list], bool]:
    """Whether an argmax (``highest``) or argmin, in effect, is taken of a value named by ``names``."""
    def test(functions) -> bool:
        signs = _Signs(functions, names)
        for function in functions:
            for node in walk(function):
                if not isinstance(node, ast.Call):
                    continue
                last = _path(node.func).rsplit(".", 1)[-1]
                if last not in ("argmax", "argmin", "nanargmax", "nanargmin"):
                    continue
                method = isinstance(node.func, ast.Attribute) and not (
                    isinstance(node.func.value, ast.Name) and node.func.value.id in ("np", "numpy"))
                if not (method or node.args):
                    continue
                picked = node.func.value if method else node.args[0]
                negated, named = signs.of(picked, function)
                if (last.endswith("argmax") != negated) == highest and (named or not negated):
                    return True
        return False
    return test


def _argsort_end(last: bool) -> Callable[[ast.AST], bool]:
    """An ``argsort(...)`` indexed at its last entry (``[-1]``, ``[..., -1]``, ``[::-1]``) or, ``last=False``,
    at its first (``[0]``)."""
    def end(index) -> bool:
        if isinstance(index, ast.Tuple):
            return any(end(e) for e in index.elts)
        if isinstance(index, ast.Slice):
            step = index.step
            return last and isinstance(step, ast.UnaryOp) and isinstance(step.op, ast.USub)
        if last:
            return isinstance(index, ast.UnaryOp) and isinstance(index.op, ast.USub) \
                and isinstance(index.operand, ast.Constant) and index.operand.value == 1
        return isinstance(index, ast.Constant) and index.value == 0

    def test(function) -> bool:
        return any(isinstance(node, ast.Subscript) and isinstance(node.value, ast.Call)
                   and _path(node.value.func).rsplit(".", 1)[-1] == "argsort" and _negation(node.value.args[0]
                                                                                           if node.value.args else None) is None
                   and end(node.slice) for node in walk(function))
    return test


def _loop_keeps(op, names) -> Callable[[ast.AST], bool]:
    """An ``if`` comparing a value named by ``names`` with a kept best (``score > best``)."""
    def test(function) -> bool:
        for node in walk(function):
            if isinstance(node, ast.If) and isinstance(node.test, ast.Compare) and len(node.test.ops) == 1:
                left, right = node.test.left, node.test.comparators[0]
                if isinstance(node.test.ops[0], op) and _named(left, names) and _named(right, ("best", "max", "min")):
                    return True
        return False
    return test


def _running_best(highest: bool) -> Callable[[ast.AST], bool]:
    """A running best kept over a loop, vectorised or not: ``better = c < best`` (or ``c > best``,
    ``best > c``...) where ``c`` is assigned, somewhere in the function, a negated value (``c = -ncc``:
    the lowest of the negation is the highest) or a plain one. ``highest``: keeping the highest of
    the plain value (a larger plain value, or a smaller negated one); else the lowest."""
    def test(function) -> bool:
        negated, plain = set(), set()
        for node in walk(function):
            if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
                (negated if _negation(node.value) is not None else plain).add(node.targets[0].id)
        overwritten = {id(compare) for compare, *_ in overwritten_running_bests(function)}
        for node in walk(function):
            if not (isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], (ast.Lt, ast.Gt))) \
                    or id(node) in overwritten:   # (a best set to every turn's value is not kept)
                continue
            left, right, smaller = node.left, node.comparators[0], isinstance(node.ops[0], ast.Lt)
            if _named(left, ("best",)) and isinstance(right, ast.Name):
                left, right, smaller = right, left, not smaller   # best > c: c < best
            if not (isinstance(left, ast.Name) and _named(right, ("best",))):
                continue
            kinds = ({True} if left.id in negated else set()) | ({False} if left.id in plain else set())
            # a smaller negated value, or a larger plain one, is a higher one
            if any((smaller == is_negated) == highest for is_negated in kinds):
                return True
        return False
    return test


def _location_of_extreme(highest: bool) -> Callable[[ast.AST], bool]:
    """OpenCV's location of the largest (``highest``) or smallest value read and used: ``_, _, _, loc =
    cv2.minMaxLoc(scores)`` with ``loc`` read later, or ``cv2.minMaxLoc(scores)[3]`` (the minimum's: [2])."""
    index = 3 if highest else 2

    def test(function) -> bool:
        loaded = {n.id for n in walk(function) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
        for node in walk(function):
            call = node.value if isinstance(node, (ast.Assign, ast.Subscript)) else None
            if not (isinstance(call, ast.Call) and _path(call.func).rsplit(".", 1)[-1] == "minMaxLoc"):
                continue
            if isinstance(node, ast.Subscript):
                try:
                    if ast.literal_eval(node.slice) in (index, index - 4):
                        return True
                except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
                    pass
                continue
            for target in node.targets:
                if isinstance(target, (ast.Tuple, ast.List)) and len(target.elts) == 4 \
                        and isinstance(target.elts[index], ast.Name) and target.elts[index].id in loaded:
                    return True
        return False
    return test


KEEPS_HIGHEST = (Predicate("picks the highest score", _picks(True, SCORE_NAMES), kind="all")
                 | Predicate("sorts", _argsort_end(last=True)) | keyword("max", "key")
                 | Predicate("keeps a larger score", _loop_keeps(ast.Gt, SCORE_NAMES))
                 | Predicate("keeps a running best", _running_best(highest=True))
                 | Predicate("reads the maximum's location", _location_of_extreme(highest=True))
                 ).saying("keeps the highest score (argmax, or argmin of the score negated)")
KEEPS_LOWEST = (Predicate("picks the lowest cost", _picks(False, COST_NAMES), kind="all")
                | Predicate("sorts", _argsort_end(last=False)) | keyword("min", "key")
                | Predicate("keeps a smaller cost", _loop_keeps(ast.Lt, COST_NAMES))
                | Predicate("keeps a running best", _running_best(highest=False))
                | Predicate("reads the minimum's location", _location_of_extreme(highest=False))
                ).saying("keeps the lowest cost (argmin, or argmax of the cost negated)")


# Predicates several labs' hints share.
RATIO_TEST = (expr("_.distance < _ * _.distance") | expr("_.distance < _.distance * _")
              | expr("_ * _.distance > _.distance") | expr("_.distance / _.distance < _")).saying(
    # (the comparison's form only: the factor may be a number of the code's own, not the `ratio` asked for)
    "applies a ratio test (best.distance < r * second.distance)")
TO_UINT8 = (expr("_.astype(np.uint8)") | expr("_.astype('uint8')") | expr("np.uint8(_)")
            | keyword("np.clip", "dtype") | expr("_.astype(dtype=np.uint8)")).saying("converts to uint8")
NAN_WHERE = (calls("np.where") & mentions("np.nan")).saying("uses np.where with np.nan")
def _any_of(predicates) -> Predicate:
    """``a | b | ...`` of an iterable of predicates."""
    predicates = list(predicates)
    combined = predicates[0]
    for predicate in predicates[1:]:
        combined = combined | predicate
    return combined


TO_FLOAT = (expr("_.astype(float)") | expr("_.astype(np.float64)") | expr("_.astype(np.float32)")
            # dtype=int or np.uint8 is no float: only the float types count
            | _any_of(keyword(call, "dtype", kind) for call in ("np.array", "np.asarray", "np.zeros")
                      for kind in ("float", "np.float64", "np.float32"))
            | expr("np.float64(_)") | expr("np.float32(_)")).saying("converts to float")


def nan_behind(text: str) -> "Hint":
    """The advice to give points behind the camera NaN (``text``: how), in labs 9 and 10."""
    return Hint(text, asks=NAN_WHERE, instead="your code already {found}: check its condition (a point is "
                "behind the camera when Z <= 0) and that the array returned is the one it makes")


# ------------------------------------------------------------------ the student's code
@dataclass(frozen=True)
class Code:
    """A module's top-level functions (the last ``def`` of a name wins, as it does when the
    module runs) and the module's functions each one calls by name."""

    functions: dict
    calls: dict

    def reachable(self, names: Iterable[str]) -> list[ast.AST]:
        """The functions ``names`` and those of the module they call, directly or not."""
        seen, todo = [], sorted(names)
        while todo:
            name = todo.pop()
            if name in seen or name not in self.functions:
                continue
            seen.append(name)
            todo.extend(sorted(self.calls[name]))
        return [self.functions[name] for name in seen]


NO_CODE = Code({}, {})


def parameter_flows(code: Code, function: str, parameter: str, depth: int = 4) -> bool:
    """Whether the parameter ``parameter`` of the student's ``function`` reaches a use (read, never
    run): read anywhere but as an argument of one of the module's own functions, or passed to one
    whose own parameter there flows. False when the function never reads it, when it is assigned
    (overwritten: its value may never be used), or when it goes only to helpers that ignore it."""
    node = code.functions.get(function)
    if node is None or depth < 0:
        return False
    if parameter not in {a.arg for a in (*node.args.posonlyargs, *node.args.args, *node.args.kwonlyargs)}:
        return False
    names = [n for n in walk(node) if isinstance(n, ast.Name) and n.id == parameter]
    if any(not isinstance(n.ctx, ast.Load) for n in names):
        return False   # (assigned somewhere: what is used may be another value)
    parents = {id(child): parent for parent in walk(node) for child in ast.iter_child_nodes(parent)}
    for name in names:
        parent = parents.get(id(name))
        while isinstance(parent, ast.Call) and len(parent.args) == 1 and parent.args[0] is name \
                and ast.unparse(parent.func) in _SAME_VALUE:   # (converted on the way: `int(block_size)`)
            name, parent = parent, parents.get(id(parent))
        call = parents.get(id(parent)) if isinstance(parent, ast.keyword) else parent
        own = isinstance(call, ast.Call) and isinstance(call.func, ast.Name) and call.func.id in code.functions
        if not own:
            return True
        callee = code.functions[call.func.id]
        if isinstance(parent, ast.keyword):
            target = parent.arg
        elif name in call.args and not any(isinstance(a, ast.Starred) for a in call.args):
            positional = [a.arg for a in (*callee.args.posonlyargs, *callee.args.args)]
            index = call.args.index(name)
            target = positional[index] if index < len(positional) else None
        else:
            return True
        if target is None or parameter_flows(code, call.func.id, target, depth - 1):
            return True
    return False


def read_code(text: str) -> Code:
    """The functions of the module ``text`` (nothing when it cannot be parsed, or is too large)."""
    try:
        if len(text) > MAX_SOURCE_BYTES:
            return NO_CODE
        tree = parse(text)   # under the parse lock, within its bounds (TooLarge is a ValueError)
        if sum(1 for _ in walk(tree)) > MAX_NODES:
            return NO_CODE
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return NO_CODE
    functions = {node.name: node for node in tree.body if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))}
    scope = scope_of(tree)   # what the names refer to: cv2's recoverPose, or the student's own
    for node in functions.values():
        node._hint_scope = scope
    # a function named anywhere in another counts as called by it: ``(_ssd if c else _ncc)(...)``,
    # a helper passed as a callback, under another name, or as an attribute of the module itself
    aliases = _aliases(tree, functions, scope)
    calls = {name: _own_references(node, name, functions, aliases, scope) for name, node in functions.items()}
    for name, rebound in _rebound(functions).items():
        functions[name]._rebound = rebound
    return Code(functions, calls)


_SAME_VALUE = {"int", "float", "round", "abs", "np.int32", "np.int64", "np.float32", "np.float64"}


def _rebound(functions: dict) -> dict:
    """Per function, its parameters that one of the module's calls of it gives another value than the
    caller's own of that name (``_sad_volume(left, right, D - 1, ...)`` from ``dp_stereo(...,
    max_disparity)``): ``max_disparity + 1`` there is not the API's ``max_disparity + 1``. A name
    given as itself, converted (``int(max_disparity)``) or through a name assigned so (``D =
    int(max_disparity)``) is the same value."""
    rebound = {name: set() for name in functions}

    def origin(node, assigned) -> str:
        for _ in range(4):
            if isinstance(node, ast.Call) and len(node.args) == 1 and not node.keywords \
                    and ast.unparse(node.func) in _SAME_VALUE:
                node = node.args[0]
            elif isinstance(node, ast.Name) and node.id in assigned:
                node = assigned[node.id]
            else:
                break
        return node.id if isinstance(node, ast.Name) else ""

    for caller in functions.values():
        stores = [n for n in walk(caller) if isinstance(n, ast.Assign) and len(n.targets) == 1
                  and isinstance(n.targets[0], ast.Name)]
        counts = Counter(n.targets[0].id for n in stores)
        assigned = {n.targets[0].id: n.value for n in stores if counts[n.targets[0].id] == 1}
        for call in walk(caller):
            if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name) and call.func.id in functions):
                continue
            callee = functions[call.func.id]
            positional = [a.arg for a in (*callee.args.posonlyargs, *callee.args.args)]
            given = [(param, arg) for param, arg in zip(positional, itertools.takewhile(
                lambda a: not isinstance(a, ast.Starred), call.args))]
            given += [(k.arg, k.value) for k in call.keywords if k.arg]
            rebound[call.func.id] |= {param for param, arg in given if origin(arg, assigned) != param}
    return rebound


# Libraries a student imports: ``x.f`` of one of them, or an ``f`` imported from one, is never the
# student's own ``f`` (a module of the student's own functions is any other import).
_LIBRARIES = frozenset({"numpy", "cv2", "scipy", "math", "matplotlib", "skimage", "PIL", "random", "itertools",
                        "functools", "os", "sys", "time", "collections", "typing", "dataclasses"})


def _own_module(module: str) -> bool:
    return bool(module) and module.split(".")[0] not in _LIBRARIES


def _aliases(tree: ast.Module, functions: dict, scope: Scope) -> dict[str, str]:
    """Other names of the module's own functions: a module-level ``patterns = gray_code_patterns``,
    or one imported from the module itself (``from lab12_stereo import gray_code_patterns as gcp``)."""
    found = {local: target.rpartition(".")[2] for local, target in scope.imported.items()
             if target.rpartition(".")[2] in functions and _own_module(target.rpartition(".")[0])
             and local not in functions}
    for node in tree.body:
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.Name) and node.value.id in functions:
            found.update({target.id: node.value.id for target in node.targets
                          if isinstance(target, ast.Name) and target.id not in functions})
    return found


def _own_references(node, name: str, functions: dict, aliases: dict, scope: Scope) -> set[str]:
    """The module's functions other than ``name`` that ``node`` (a function, its nested ones
    included) refers to: by name, by an alias, or as ``module.f`` of an import of its own module."""
    found = set()
    for n in walk(node):
        if isinstance(n, ast.Name):
            target = n.id if n.id in functions else aliases.get(n.id)
        elif isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name) and n.attr in functions \
                and _own_module(scope.modules.get(n.value.id, "")):
            target = n.attr
        else:
            continue
        if target and target != name:
            found.add(target)
    return found


@lru_cache(maxsize=32)
def _code_at(path: str, mtime_ns: int, size: int) -> Code:
    if size > MAX_SOURCE_BYTES:
        return NO_CODE
    try:
        return read_code(Path(path).read_bytes().decode("utf-8", errors="replace"))
    except OSError:
        return NO_CODE


def code_of(t) -> Code:
    """The code of the module a trial's check grades, as the sandbox holds it (the file the
    worker imported; a notebook already converted); :data:`NO_CODE` without one."""
    folder = getattr(getattr(t, "sandbox", None), "submission_dir", None)   # a stand-in trial has none
    return NO_CODE if folder is None else module_code(folder, t.lab.module)


def module_code(folder, module: str) -> Code:
    """The code of ``module`` in the submission folder ``folder`` (read once per version of the file);
    :data:`NO_CODE` where there is none."""
    try:
        path = Path(folder) / f"{module}.py"
        stat = path.stat()
    except (OSError, TypeError, ValueError):
        return NO_CODE
    return _code_at(str(path), stat.st_mtime_ns, stat.st_size)


# ------------------------------------------------------------------ hints
@dataclass(frozen=True)
class Hint:
    """A fixed hint and the code it asks for.

    Parameters
    ----------
    text : str
        What the hint says.
    asks : Predicate, optional
        The code the hint asks for; None: it asks for nothing specific (always said).
    instead : str, optional
        Said when the student's code already holds ``asks`` ("" says nothing; ``{found}`` in it
        becomes what the code does, "calls np.argmax"); by default "your code already
        {found}; the error is elsewhere".
    functions : tuple of str, optional
        The student functions whose code is read (default: those the check calls).
    """

    text: str
    asks: Predicate | None = None
    instead: str | None = None
    functions: tuple = ()

    def __str__(self) -> str:
        return self.text

    def neutral(self, found: str = "") -> str:
        """What is said instead of the text, ``found`` being what the code does ("calls np.argmax")."""
        if self.instead is not None:
            return self.instead.replace("{found}", found or self.asks.says)
        return f"your code already {found or self.asks.says}; the error is elsewhere"

    def said(self, t, functions: Iterable[str] = ()) -> str:
        """The hint's text, or :meth:`neutral` when the student's code (the functions the
        check ``t`` calls, or ``functions``) already does what it asks."""
        if self.asks is None:
            return self.text
        code = code_of(t)
        if not code.functions:   # nothing to read (a stand-in trial, code that cannot be parsed)
            return self.text
        found = self.contradicts(code, tuple(functions) or self.functions or functions_read(t))
        return self.neutral(found) if found else self.text

    def contradicts(self, code: Code, functions: Iterable[str]) -> str:
        """What ``code``'s ``functions`` (and their helpers) already do of what the hint asks, in
        words ("calls np.argmax"); "" when they do not."""
        return self.asks.found(code.reachable(functions)) if self.asks is not None else ""


def _own_nodes(function):
    """The nodes of ``function``'s body, not those of functions or lambdas defined in it."""
    todo = list(function.body)
    while todo:
        node = todo.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
            continue
        yield node
        todo.extend(ast.iter_child_nodes(node))


def _always_leaves(statements) -> bool:
    """Whether running ``statements`` always ends in a ``return`` or ``raise`` (an ``if`` whose
    branches both do, a ``with``/``try`` whose body does); a loop may finish, so it does not."""
    if not statements:
        return False
    last = statements[-1]
    if isinstance(last, (ast.Return, ast.Raise)):
        return True
    if isinstance(last, ast.If):
        return _always_leaves(last.body) and _always_leaves(last.orelse)
    if isinstance(last, (ast.With, ast.AsyncWith)):
        return _always_leaves(last.body)
    if isinstance(last, ast.Try):
        return (_always_leaves(last.body) or _always_leaves(last.orelse)) and all(
            _always_leaves(h.body) for h in last.handlers)
    if isinstance(last, ast.While) and isinstance(last.test, ast.Constant) and last.test.value is True:
        return not any(isinstance(n, ast.Break) for n in walk(last))
    return False


def none_returned(code: Code, function: str, *, in_tuple: bool = False) -> str:
    """Where the student's ``function`` returns None, in words for "your `f` ...": a ``return``
    without a value (and the condition it is under), no ``return`` of a value at all, or an end
    reached without one; "" when the code cannot say (a None from a call it returns).

    ``in_tuple``: where it returns a tuple holding None (``return None, None, None``) instead,
    the answer's part that was None."""
    fn = code.functions.get(function)
    if fn is None:
        return ""
    returns = [n for n in _own_nodes(fn) if isinstance(n, ast.Return)]
    conditions = {}
    for node in _own_nodes(fn):
        if isinstance(node, ast.If):
            for branch, negated in ((node.body, False), (node.orelse, True)):
                for inner in branch:
                    for leaf in walk(inner):
                        if isinstance(leaf, ast.Return) and id(leaf) not in conditions:
                            test = _unparsed(node.test)
                            conditions[id(leaf)] = f"not ({test})" if negated else test
    if in_tuple:
        holding = [n for n in returns if isinstance(n.value, (ast.Tuple, ast.List))
                   and any(_is_none(e) for e in n.value.elts)]
        where = [f"`{_unparsed(n.value)}` where `{conditions[id(n)]}`" for n in holding if id(n) in conditions]
        return f"returns {' and '.join(where[:2])}" if where else \
            (f"returns `{_unparsed(holding[0].value)}`" if holding else "")
    valued = [n for n in returns if n.value is not None and not _is_none(n.value)]
    if not valued:
        return "has no `return` of a value, and a Python function without one returns None"
    empty = [n for n in returns if n not in valued]
    if empty:
        where = [f"where `{conditions[id(n)]}`" for n in empty if id(n) in conditions][:2]
        return "returns None " + (" and ".join(where) if where else "with a bare `return`")
    if not _always_leaves(fn.body):
        return "can reach its end without a `return`, and then returns None"
    return ""


def _is_none(node) -> bool:
    return isinstance(node, ast.Constant) and node.value is None


def _unparsed(node, limit: int = 60) -> str:
    text = ast.unparse(node)
    return text if len(text) <= limit else text[:limit - 3] + "..."


# OpenCV functions that take an image size as (width, height): the argument's position and keywords
SIZE_ARGUMENTS = {"resize": (1, ("dsize",)), "warpAffine": (2, ("dsize",)), "warpPerspective": (2, ("dsize",)),
                  "initUndistortRectifyMap": (4, ("size",)), "getOptimalNewCameraMatrix": (2, ("imageSize",)),
                  "stereoRectify": (4, ("imageSize",)), "calibrateCamera": (2, ("imageSize",)),
                  "stereoCalibrate": (5, ("imageSize",)), "initInverseRectificationMap": (4, ("size",))}


def _rows_first(node, unpacked: dict):
    """The part of ``node`` that is an image size written rows first -- ``X.shape[:2]``,
    ``X.shape[0:2]``, ``(X.shape[0], X.shape[1])``, or ``(h, w)`` for names unpacked from
    ``X.shape[:2]`` in that order (``unpacked``: name -> its index in the shape); either side of
    ``dsize or (h, w)`` -- or None."""
    if isinstance(node, (ast.BoolOp, ast.IfExp)):
        parts = node.values if isinstance(node, ast.BoolOp) else [node.body, node.orelse]
        return next(filter(None, (_rows_first(part, unpacked) for part in parts)), None)
    if isinstance(node, ast.Subscript) and _path(node.value).endswith("shape") and isinstance(node.slice, ast.Slice):
        low, high = node.slice.lower, node.slice.upper
        if (low is None or _same(low, ast.Constant(0))) and isinstance(high, ast.Constant) and high.value == 2:
            return node
    if isinstance(node, (ast.Tuple, ast.List)) and len(node.elts) == 2:
        def index(e):
            if isinstance(e, ast.Name):
                return unpacked.get(e.id)
            if isinstance(e, ast.Subscript) and _path(e.value).endswith("shape") and isinstance(e.slice, ast.Constant):
                return e.slice.value
            return None
        if (index(node.elts[0]), index(node.elts[1])) == (0, 1):
            return node
    return None


def size_given_as_shape(code: Code, functions: Iterable[str]) -> str:
    """Where the student's ``functions`` (and their helpers) give OpenCV an image size rows first
    (``image.shape[:2]``, ``(h, w)``) where it reads (width, height), in words for ": your code
    ..."; "" when no such call is written."""
    for function in code.reachable(functions):
        unpacked = {}
        named: dict = {}   # a name given a size rows first once (`size = image.shape[:2]`) -> that value
        for node in walk(function):
            if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Tuple) and isinstance(
                    node.value, ast.Subscript) and _path(node.value.value).endswith("shape"):
                for position, target in enumerate(node.targets[0].elts):
                    if isinstance(target, ast.Name):
                        unpacked[target.id] = position
        for node in walk(function):
            if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
                name = node.targets[0].id
                named[name] = _rows_first(node.value, unpacked) if name not in named else None   # (once only)
        for node in walk(function):
            if not isinstance(node, ast.Call):
                continue
            name = _path(node.func).rsplit(".", 1)[-1]
            if name not in SIZE_ARGUMENTS:
                continue
            position, keywords = SIZE_ARGUMENTS[name]
            given = [node.args[position]] if len(node.args) > position else []
            given += [k.value for k in node.keywords if k.arg in keywords]
            for argument in given:
                part = _rows_first(argument, unpacked)
                if part is None and isinstance(argument, ast.Name) and named.get(argument.id) is not None:
                    part = named[argument.id]
                    return (f"passes `{argument.id}` = `{_unparsed(part)}` (rows, columns) to cv2.{name} as its "
                            "size, which OpenCV reads as (width, height)")
                if part is not None:
                    return (f"passes `{_unparsed(part)}` (rows, columns) to cv2.{name} as its size, which "
                            "OpenCV reads as (width, height)")
    return ""


# NumPy calls whose answers are complex arrays for real input (eigen-decompositions of a matrix that
# is not symmetric, Fourier transforms, polynomial roots).
COMPLEX_MAKERS = ("eig", "eigvals", "fft", "fft2", "fftn", "ifft", "ifft2", "ifftn", "roots")


def complex_makers(code: Code, functions: Iterable[str]) -> list[str]:
    """The calls in the student's ``functions`` (and their helpers) that make complex arrays from real
    ones, as ``np.linalg.eig`` (line N); [] when none is written."""
    found = []
    for function in code.reachable(functions):
        for node in walk(function):
            if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in COMPLEX_MAKERS:
                found.append((node.lineno, f"`{_path(node.func)}` (line {node.lineno})"))
    return [text for _, text in sorted(set(found))]


def functions_read(t) -> tuple[str, ...]:
    """The student functions whose code a check ``t``'s hints read: those the check calls."""
    from .stubs import functions_called

    return tuple(sorted(functions_called(t.check)))


# The engine's own form hints (autograder.engine.checks.Trial.expect_array).
UINT8_HINT = Hint("images stay uint8: convert with np.clip(x, 0, 255).astype(np.uint8)", asks=TO_UINT8,
                  instead="your code {found} somewhere, but not the array it returns")
FLOAT_HINT = Hint("build it with dtype=float (an array of whole numbers is an integer array) or convert it "
                  "with .astype(np.float64)", asks=TO_FLOAT,
                  instead="your code {found} somewhere, but not the array it returns")


_CANVAS_MAKERS = ("zeros", "ones", "empty", "full")


def divides_by_255(t) -> str:
    """"Reading your code: ..." where the functions the check calls divide something by 255 (an image scaled to
    [0, 1]), naming the line; "" otherwise."""
    from .claims import from_code

    for function in code_of(t).reachable(functions_read(t)):
        for node in walk(function):
            divisor = node.right if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div) else \
                node.value if isinstance(node, ast.AugAssign) and isinstance(node.op, ast.Div) else None
            if isinstance(divisor, ast.Constant) and type(divisor.value) in (int, float) and divisor.value == 255:
                return from_code(f"Your code divides by 255 (line {node.lineno}, in `{function.name}`): that scales "
                                 "the image to [0, 1]")
    return ""


def float_canvas(t) -> str:
    """A sentence naming ``np.zeros(image.shape)`` (``ones``, ``empty``, ``full``) written without a dtype
    in the functions ``t``'s calls reached -- an image made float64 by NumPy's default -- or ""."""
    from .claims import from_code

    code = code_of(t)
    called = list(dict.fromkeys(call[0] for call in getattr(t, "calls", ()) if call))
    for function in code.reachable(called) if called else ():
        returned = _returned_as_made(function)
        for node in walk(function):
            if isinstance(node, ast.Call) and _path(node.func) in {f"np.{m}" for m in _CANVAS_MAKERS} \
                    and node.args and (".shape" in ast.unparse(node.args[0]) or id(node) in returned) \
                    and not any(k.arg == "dtype" for k in node.keywords) \
                    and not (_path(node.func) == "np.full" and len(node.args) > 2):
                return from_code(f"your code makes `{ast.unparse(node)}` (line {node.lineno}), which NumPy makes "
                                 "float64 when no dtype is given; give it the image's: dtype=image.dtype "
                                 "(or np.uint8)")
    return ""


def values_bound(function) -> dict[str, list]:
    """name -> the values ``function`` binds it to (None for an augmented or annotated assignment), in walk order."""
    bound: dict[str, list] = {}
    for node in walk(function):
        if isinstance(node, ast.Assign):
            for target in node.targets:
                if isinstance(target, ast.Name):
                    bound.setdefault(target.id, []).append(node.value)
        elif isinstance(node, (ast.AugAssign, ast.AnnAssign)) and isinstance(node.target, ast.Name):
            bound.setdefault(node.target.id, []).append(None)
    return bound


def _returned_as_made(function) -> set[int]:
    """ids of the calls whose result ``function`` returns as made (`out = np.zeros((h, w1 + w2, 3))`, filled item by
    item, `return out`): its one binding of that name, and a return of the name alone."""
    bound = values_bound(function)
    names = {node.value.id for node in walk(function) if isinstance(node, ast.Return) and isinstance(node.value, ast.Name)}
    return {id(values[0]) for name, values in bound.items()
            if name in names and len(values) == 1 and isinstance(values[0], ast.Call)}


def signature_of_def(fn: ast.FunctionDef) -> inspect.Signature | None:
    """The student's own def as a signature (its names; defaults only marked), to bind a call's arguments."""
    arguments = fn.args
    kind = inspect.Parameter
    positional = [(a, kind.POSITIONAL_ONLY) for a in arguments.posonlyargs] + \
        [(a, kind.POSITIONAL_OR_KEYWORD) for a in arguments.args]
    first_default = len(positional) - len(arguments.defaults)
    parameters = [kind(a.arg, k, default=None if i >= first_default else kind.empty)
                  for i, (a, k) in enumerate(positional)]
    if arguments.vararg:
        parameters.append(kind(arguments.vararg.arg, kind.VAR_POSITIONAL))
    parameters += [kind(a.arg, kind.KEYWORD_ONLY, default=kind.empty if d is None else None)
                   for a, d in zip(arguments.kwonlyargs, arguments.kw_defaults)]
    if arguments.kwarg:
        parameters.append(kind(arguments.kwarg.arg, kind.VAR_KEYWORD))
    try:
        return inspect.Signature(parameters)
    except ValueError:   # two parameters of one name: not a def Python would run
        return None
