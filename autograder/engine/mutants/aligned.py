"""Changes that make a student's statement the reference's counterpart of it again.

Many students write a function the way the reference does, statement for statement, and slip at one
place: `np.diag([sx, sy], 1)` for a 3x3 scaling matrix, a canvas sized by the larger image, a step left
out. No operator foresees every such slip, but the statement itself shows it: beside its counterpart
(the reference's statement of the same kind in the def of the same name: the same names assigned, the
same function called), it differs at one or two small places. Each such difference made the
counterpart's is a change the repairs try (:mod:`.repair`) like any operator's -- run on the failing
inputs and confirmation inputs, told only when the answers come right, and shown as the student's own
line changed. A statement of the reference's the student's def lacks, where the statements around it
are written alike, is a step to add; a statement with no counterpart that only rebinds a name is a
step to take out.

Names of the student's own are followed (:func:`_names_map`: `m = h @ K` stands for `mapped =
homogeneous @ K.T`), and a counterpart is written in them. What it cannot reach: code of the student's
own structure (a loop where the reference is vectorised, other steps: no counterpart, or one that
differs everywhere), and differences larger than a short expression (:data:`SHOWN`): those would show
the reference's code, not a slip of the student's.

Read only, never run here: both defs are parsed trees (the student's under the grader's parse bounds).
"""

from __future__ import annotations

import ast
import builtins
import contextlib
import difflib
from collections import Counter

from ...loading.parsing import copy_tree, parse, walk
from .anchors import _key, _names
from .operators import Mutant, _defs, _dotted, runs

SHOWN = 48          # the longest counterpart expression a change writes
DIFFERENCES = 2     # the most places one statement may differ at and still be the counterpart's slip
ADDED = 60          # the longest statement a change adds
_ENABLED = [True]   # off within left_out() (see there)
MAX_STATEMENTS = 300  # a def with more statements (the labs' longest has about 40) is not aligned
SHORT = 12          # code this short (a name, a number, `width - 1`) may stand for any other as short
LONGEST_SLIP = 4 * SHOWN   # the student's code at a place longer than this is no slip (and is not compared)
LIKENESS = 0.6      # longer code must share this much of its characters with the counterpart's (difflib's ratio)
_HEADER_FIELDS = {ast.For: ("target", "iter"), ast.While: ("test",), ast.If: ("test",)}
_SIMPLE = (ast.Assign, ast.AugAssign, ast.AnnAssign, ast.Return, ast.Expr)
_BUILTINS = frozenset(dir(builtins))
_WHOLE = object()   # a node that differs as a whole (its kind, a name, a number, an operator, a count)


@contextlib.contextmanager
def left_out():
    """No counterparts within the block: `autograder verify --error-model` measures the operators on mutants
    of the reference, each one edit of it, which its counterpart statement would repair every time."""
    before, _ENABLED[0] = _ENABLED[0], False
    try:
        yield
    finally:
        _ENABLED[0] = before


def _statements(fn: ast.FunctionDef) -> list[ast.stmt]:
    """The def's statements in line order (compound ones too, each before its body)."""
    return sorted((node for node in walk(fn) if isinstance(node, ast.stmt) and node is not fn),
                  key=lambda node: (node.lineno, node.col_offset))


def _signature(statement: ast.stmt):
    """What a statement and its counterpart share: its kind and the names it assigns, or the function
    it calls; None for a statement no counterpart is looked for."""
    if isinstance(statement, ast.Assign):
        return ("=", tuple(ast.dump(t) for t in statement.targets))
    if isinstance(statement, (ast.AugAssign, ast.AnnAssign)):
        return ("+=", ast.dump(statement.target))
    if isinstance(statement, ast.Return):
        return ("return",)
    if isinstance(statement, ast.Expr) and isinstance(statement.value, ast.Call):
        return ("call", _dotted(statement.value.func))
    if isinstance(statement, ast.For):
        return ("for", ast.dump(statement.target))
    if isinstance(statement, (ast.If, ast.While)):
        return (type(statement).__name__,)
    return None


def _parts(statement: ast.stmt) -> list:
    """The parts of a statement compared with its counterpart's (a compound one: its header)."""
    fields = _HEADER_FIELDS.get(type(statement))
    if fields is not None:
        return [getattr(statement, field) for field in fields]
    if isinstance(statement, ast.Return):
        return [statement.value]
    if isinstance(statement, ast.Expr):
        return [statement.value]
    if isinstance(statement, ast.AugAssign):
        return [statement.target, statement.op, statement.value]
    return [statement.value]


def _differences(mine, theirs):
    """The pairs (student's node, counterpart's node) of expressions at which two trees differ, or
    :data:`_WHOLE` when they differ in a part that is no expression of its own (then the nearest
    expression holding it differs whole)."""
    if type(mine) is not type(theirs):
        return _WHOLE
    if mine is None or isinstance(mine, (str, int, float, complex, bytes, bool)):
        return [] if mine == theirs else _WHOLE
    if isinstance(mine, (ast.expr_context, ast.operator, ast.unaryop, ast.cmpop, ast.boolop)):
        return []   # (equal types: the same operator)
    if isinstance(mine, list):
        if len(mine) != len(theirs):
            return _WHOLE
        found = []
        for a, b in zip(mine, theirs):
            inner = _differences(a, b)
            if inner is _WHOLE:
                if _placeable(a):
                    found.append((a, b))
                else:
                    return _WHOLE
            else:
                found += inner
        return found
    if isinstance(mine, ast.AST):
        found = []
        for field in mine._fields:
            a, b = getattr(mine, field, None), getattr(theirs, field, None)
            if (a is None) != (b is None):
                return _WHOLE   # (a part one side leaves out -- a slice's bound, a default --: this node whole)
            inner = _differences(a, b)
            if inner is _WHOLE:
                if _placeable(a):
                    found.append((a, b))
                else:
                    return _WHOLE   # (a name, a number, an operator, a keyword's name: this node whole)
            else:
                found += inner
        return found
    return [] if mine == theirs else _WHOLE


def _placeable(node) -> bool:
    """Whether an expression can be a place of its own: written out alone it reads back as itself (a slice,
    `1:-1`, or the index `:, 2` holding one, cannot: the subscript holding it is the place)."""
    return isinstance(node, ast.expr) and not isinstance(node, ast.Slice) \
        and not (isinstance(node, ast.Tuple) and any(isinstance(item, ast.Slice) for item in node.elts))


def _statement_differences(mine: ast.stmt, theirs: ast.stmt, stand_ins: frozenset = frozenset(),
                           inputs: frozenset = frozenset()):
    """The places a statement differs from a counterpart at, or None where it cannot be told by
    places (too many, too long, or the whole statement). ``stand_ins``: names the student's own steps
    bind; one of them where the counterpart writes a short expression of ``inputs`` alone (names
    computed as the reference computes them) is a place too -- `size` for `(width, height)`."""
    found = []
    for a, b in zip(_parts(mine), _parts(theirs)):
        inner = _differences(a, b)
        if inner is _WHOLE:
            if not isinstance(a, ast.expr):
                return None
            inner = [(a, b)]
        found += inner
    if not found or len(found) > DIFFERENCES:
        return None
    if len(found) == 1 and not any(found[0][0] is part for part in _parts(mine)) \
            and _stands_in(*found[0], stand_ins, inputs):
        return found   # (a part of the statement, not its whole value: `return out` is no place of `return f(...)`)
    if len(found) == 1 and _fixed_for_computed(*found[0], inputs):
        return found   # (`limit = 1000.0` where `limit = 4.0 * (width + height)`: a number fixed in advance)
    for a, b in found:
        if not _writable(b) or not _a_slip(a, b):
            return None
    return found


def _stands_in(mine: ast.expr, theirs: ast.expr, stand_ins: frozenset, inputs: frozenset) -> bool:
    """Whether the student's code at the one place a statement differs is a name of the student's own
    steps standing for the counterpart's expression of values the student computes as the reference
    does (the student's own step in between is where it went wrong, and the statement can do without it):
    values alone, no call -- the reference's own helper called in a student's name's place would stand in for
    the student's work, not for a slip."""
    return isinstance(mine, ast.Name) and mine.id in stand_ins and not isinstance(theirs, ast.Name) \
        and not any(isinstance(node, ast.Call) for node in walk(theirs)) \
        and _writable(theirs) and _names([theirs], ast.Load) <= inputs


def _fixed_for_computed(mine: ast.expr, theirs: ast.expr, inputs: frozenset) -> bool:
    """Whether the student's code at the one place a statement differs is a number written in advance where the
    counterpart computes the value from the function's inputs (values alone, no call): `1000.0` for a clamp the
    reference sizes by the image, `4.0 * (width + height)`."""
    read = _names([theirs], ast.Load)
    return isinstance(mine, ast.Constant) and type(mine.value) in (int, float) \
        and not any(isinstance(node, ast.Call) for node in walk(theirs)) \
        and bool(read) and read <= inputs and _writable(theirs)


def _writable(node: ast.expr) -> bool:
    """Whether an expression written out alone reads back as itself (a subscript's `:, -1` does not)."""
    written = ast.unparse(node)
    if len(written) > SHOWN or "\n" in written:
        return False
    try:
        return ast.dump(parse(written, mode="eval").body) == ast.dump(node)
    except (SyntaxError, ValueError, RecursionError):
        return False


def _a_slip(mine: ast.expr, theirs: ast.expr) -> bool:
    """Whether the student's code at a place is a slip of the counterpart's there, not other code: a
    name or number for another (both short), one holding the other whole (a step wrapped round it or
    left out: `cv2.flip(frame, 1)` for `frame`, `img1` for `_bgr(img1)`), or most of its characters
    the counterpart's."""
    mine_text, theirs_text = ast.unparse(mine), ast.unparse(theirs)
    if len(mine_text) > LONGEST_SLIP:
        return False   # (the student's side is theirs, of any length: longer code than a slip is other code)
    if max(len(mine_text), len(theirs_text)) <= SHORT or _holds(mine, theirs) or _holds(theirs, mine):
        return True
    return difflib.SequenceMatcher(None, mine_text, theirs_text, autojunk=False).ratio() >= LIKENESS


def _holds(outer: ast.expr, inner: ast.expr) -> bool:
    """Whether ``inner`` is written whole inside ``outer``."""
    wanted = ast.dump(inner)
    return any(ast.dump(node) == wanted for node in walk(outer) if type(node) is type(inner))


def _counterparts(statement: ast.stmt, reference: list[ast.stmt], known: set[str],
                  stand_ins: frozenset = frozenset(), inputs: frozenset = frozenset()):
    """The reference statements of the same signature, each with the places they differ at, nearest first
    (only those whose new code reads names ``known`` to the student's code at that statement)."""
    signature = _signature(statement)
    if signature is None:
        return []
    found = []
    for model in reference:
        if _signature(model) != signature:
            continue
        places = _statement_differences(statement, model, stand_ins, inputs)
        if places and all(_names([b], ast.Load) <= known for _, b in places):
            found.append((sum(len(ast.unparse(b)) + len(ast.unparse(a)) for a, b in places), model, places))
    return [(model, places) for _, model, places in sorted(found, key=lambda item: item[0])]


def _ordinals(fn: ast.FunctionDef) -> dict[int, int]:
    return {id(node): ordinal for ordinal, node in enumerate(walk(fn))}


def _rebinds(statement: ast.stmt, earlier: set[str]) -> bool:
    """Whether a statement only binds again names bound above it (`frame = cv2.flip(frame, 1)`), so
    the code still runs without it."""
    if isinstance(statement, ast.AugAssign):
        return True
    if isinstance(statement, ast.Assign):
        names = [t.id for t in statement.targets if isinstance(t, ast.Name)]
        return len(names) == len(statement.targets) and all(name in earlier for name in names)
    return False


def aligned_changes(student: ast.FunctionDef, reference: ast.FunctionDef, outside: frozenset = frozenset()) -> list[tuple]:
    """``(operator, ((ordinal, payload), ...))`` for each change that makes one statement of ``student``
    its counterpart in ``reference``: "aligned" (expressions written as the counterpart's, payload the
    new code), "add_step" (a statement added after the one at the ordinal: (None, text, line, "after")),
    "extra_step" (a rebinding with no counterpart taken out). ``outside``: the names the student's module
    binds at its top level (and the builtins), which a counterpart's code may read too."""
    if sum(1 for node in walk(student) if isinstance(node, ast.stmt)) > MAX_STATEMENTS:
        return []   # (each statement is compared with the reference's: a def far longer than any lab's is not read)
    mine, theirs = _statements(student), _statements(_renamed(reference, _names_map(student, reference)))
    written = {_key(s) for s in theirs}
    # (a reference statement the student wrote word for word is that statement's: it is no counterpart of
    # another -- `P = P / P[2, 3]` beside the reference's `P = -P`, written too, is a step of its own)
    copied = Counter(_key(s) for s in mine if _key(s) in written)
    free = []
    for model in theirs:
        if copied[_key(model)] > 0:
            copied[_key(model)] -= 1
        else:
            free.append(model)
    ordinals = _ordinals(student)
    changes, seen = [], set()
    parameters = {a.arg for a in walk(student.args) if isinstance(a, ast.arg)}
    bound: set[str] = set(parameters)
    as_reference: set[str] = set(parameters)   # (names bound as the reference binds them; the others: own steps')
    alike: dict[tuple, list] = {}   # the same one-place change in several statements: one change too
    for statement in mine:
        own = _key(statement) not in written
        if own:
            known = bound | outside | _names([statement], ast.Store)   # (a loop's own target, a comprehension's names)
            counterparts = _counterparts(statement, free, known, frozenset(bound - as_reference),
                                         frozenset(as_reference | outside))
            for model, places in counterparts[:2]:
                edits = tuple((ordinals[id(a)], ast.unparse(b)) for a, b in places)
                if edits not in seen:
                    seen.add(edits)
                    changes.append(("aligned", edits))
                    if len(places) == 1:
                        alike.setdefault((ast.dump(places[0][0]), edits[0][1]), []).append(edits[0])
            if not counterparts and isinstance(statement, _SIMPLE) and _rebinds(statement, bound) \
                    and _signature(statement) not in {_signature(s) for s in free}:
                changes.append(("extra_step", ((ordinals[id(statement)], None),)))
        header = [statement.target] if isinstance(statement, ast.For) else [statement] if isinstance(statement, _SIMPLE) else []
        bound |= _names(header, ast.Store)
        if not own:
            as_reference |= _names(header, ast.Store)
    changes += [("aligned", tuple(edits)) for edits in alike.values() if len({o for o, _ in edits}) > 1]
    if not _alike(mine, written):
        # (steps added or taken out only where the def is the reference's for the most part: in code of the
        # student's own, a statement the reference lacks is no extra step)
        return [change for change in changes if change[0] == "aligned"]
    return changes + _missing_steps(student, reference, mine, theirs, ordinals)


def _alike(mine: list[ast.stmt], written: set[str]) -> bool:
    """Whether at least half the student's statements are written as the reference writes them."""
    return bool(mine) and 2 * sum(_key(s) in written for s in mine) >= len(mine)


def _target_names(statement: ast.stmt) -> list[str] | None:
    """The names an assignment or a loop binds, in order (None where it binds anything else too)."""
    targets = [statement.target] if isinstance(statement, ast.For) else statement.targets
    names = []
    for target in targets:
        for node in (target.elts if isinstance(target, ast.Tuple) else [target]):
            if not isinstance(node, ast.Name):
                return None
            names.append(node.id)
    return names


def _names_map(student: ast.FunctionDef, reference: ast.FunctionDef) -> dict[str, str]:
    """The reference's local names and the student's names for the same values: an assignment (or a loop)
    of the reference whose value, in the student's names found so far, the student's def computes too --
    word for word, or but for one slip (:func:`_a_slip`) -- binds its names to the student's there, in
    order (`A = np.vstack(...)` and `M = np.vstack(...)`: A is M). Parameters keep theirs (the API's)."""
    mapping: dict[str, str] = {}
    images: set[str] = set()
    mine = [s for s in _statements(student) if isinstance(s, (ast.Assign, ast.For)) and _target_names(s)]
    used: set[int] = set()
    for model in _statements(reference):
        if not isinstance(model, (ast.Assign, ast.For)):
            continue
        names = _target_names(model)
        if not names or all(name in mapping for name in names):
            continue
        value = _renamed(model.iter if isinstance(model, ast.For) else model.value, mapping)
        near = None
        for index, statement in enumerate(mine):
            if index in used or type(statement) is not type(model) or len(_target_names(statement)) != len(names):
                continue
            theirs = statement.iter if isinstance(statement, ast.For) else statement.value
            places = _differences(theirs, value)
            if places == []:
                near = index
                break
            if near is None and places is not _WHOLE and len(places) == 1 \
                    and _a_slip(places[0][0], places[0][1]):
                near = index
        if near is None:
            continue
        used.add(near)
        for name, own in zip(names, _target_names(mine[near])):
            if name not in mapping and own not in images:
                mapping[name] = own
                images.add(own)
    return {name: own for name, own in mapping.items() if name != own}


def _renamed(node, mapping: dict[str, str]):
    """A copy of ``node`` with the names ``mapping`` holds written as their images."""
    node = copy_tree(node)
    if mapping:
        for inner in walk(node):
            if isinstance(inner, ast.Name) and inner.id in mapping:
                inner.id = mapping[inner.id]
    return node


def _missing_steps(student, reference, mine, theirs, ordinals) -> list[tuple]:
    """A simple statement of the reference the student's def writes nowhere (nor any of its kind), right
    after one the student writes word for word: the step added after the student's statement."""
    mine_by_key: dict[str, list[ast.stmt]] = {}
    for statement in mine:
        mine_by_key.setdefault(_key(statement), []).append(statement)
    written = {_key(s) for s in theirs}
    signatures = {_signature(s) for s in mine if _key(s) not in written}   # (of the student's own statements)
    found = []
    for block in _blocks(reference):
        for before, step in zip(block, block[1:]):
            if not isinstance(step, (ast.Assign, ast.AugAssign, ast.Expr)) or _key(step) in mine_by_key:
                continue
            if _signature(step) in signatures:
                continue   # (the student computes it otherwise: a counterpart to align, not a step to add)
            text = " ".join(ast.unparse(step).split())
            holders = mine_by_key.get(_key(before), [])
            if len(text) > ADDED or len(holders) != 1 or not isinstance(holders[0], _SIMPLE):
                continue
            found.append(("add_step", ((ordinals[id(holders[0])], (None, text, holders[0].lineno, "after")),)))
    return found


def _blocks(fn: ast.FunctionDef) -> list[list[ast.stmt]]:
    return [getattr(node, field) for node in walk(fn) for field in ("body", "orelse")
            if isinstance(getattr(node, field, None), list) and getattr(node, field)
            and isinstance(getattr(node, field)[0], ast.stmt)]


def aligned_mutants(student_tree: ast.Module, reference_tree: ast.Module, function: str) -> list[Mutant]:
    """The aligned changes (:func:`aligned_changes`) of every def ``function`` runs in the student's module
    that the reference defines too, as mutants of the student's code (repairs tell them by their code)."""
    if not _ENABLED[0]:
        return []
    student_defs, reference_defs = _defs(student_tree), _defs(reference_tree)
    outside = frozenset(_module_names(student_tree)) | _BUILTINS
    made = []
    for where in runs(student_defs, function):
        if where not in reference_defs:
            continue
        nodes = list(walk(student_defs[where]))
        for operator, edits in aligned_changes(student_defs[where], reference_defs[where], outside):
            full = tuple((where, ordinal, operator, payload) for ordinal, payload in edits)
            line = getattr(nodes[edits[0][0]], "lineno", student_defs[where].lineno)
            made.append(Mutant(operator, function, where, line, full, f"in `{function}`, ", f"in `{function}`, "))
    return made


def _module_names(tree: ast.Module) -> set[str]:
    """The names a module binds at its top level (imports, defs, classes, assignments)."""
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            names |= {alias.asname or alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        else:
            names |= {n.id for n in walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
    return names
