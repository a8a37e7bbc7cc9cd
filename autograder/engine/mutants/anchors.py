"""Which of a student's statements are the reference's own, with everything they read.

A statement is *anchored* when the reference's function of the same name has a statement written
the same (names included) and every name it reads comes from the same place in both: the same
parameter, the same module-level name, or a statement anchored in turn (the last one before it
that assigns the name). Such a statement computes the reference's value at that point, so a
change there that mends the answers compensates for a slip elsewhere (`g = k ^ (k >> 1)` made
`k ^ (k << 1)` to undo a bit read one place off further on): a repair never tells it
(:meth:`.repair._Student.follows_reference`).

Read only, never run: both functions are parsed trees. Control flow is read in line order (the
last assignment above the statement), which is what a reader of a short lab function sees.
"""

from __future__ import annotations

import ast
from ...loading.parsing import walk

_HEADERS = (ast.For, ast.AsyncFor, ast.With, ast.AsyncWith)   # compound statements that assign names


def _key(statement: ast.stmt) -> str:
    """The statement's text for comparison (positions left out; a compound statement's header only)."""
    if isinstance(statement, (ast.For, ast.AsyncFor)):
        return ast.dump(ast.Tuple([statement.target, statement.iter], ast.Load()))
    if isinstance(statement, (ast.With, ast.AsyncWith)):
        return ast.dump(ast.Tuple([item.context_expr for item in statement.items], ast.Load()))
    return ast.dump(statement)


def _header_parts(statement: ast.stmt) -> list[ast.AST]:
    """The parts of a statement read before its body runs (all of a simple statement)."""
    if isinstance(statement, (ast.For, ast.AsyncFor)):
        return [statement.iter]
    if isinstance(statement, (ast.With, ast.AsyncWith)):
        return [item.context_expr for item in statement.items]
    if isinstance(statement, (ast.If, ast.While)):
        return [statement.test]
    if isinstance(statement, (ast.Try, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return []
    return [statement]


def _names(parts, context) -> set[str]:
    return {node.id for part in parts for node in walk(part)
            if isinstance(node, ast.Name) and isinstance(node.ctx, context)}


def _assigned(statement: ast.stmt) -> set[str]:
    if isinstance(statement, (ast.For, ast.AsyncFor)):
        return _names([statement.target], ast.Store)
    if isinstance(statement, (ast.With, ast.AsyncWith)):
        return _names([item.optional_vars for item in statement.items if item.optional_vars], ast.Store)
    return _names(_header_parts(statement), ast.Store)


def _read(statement: ast.stmt) -> set[str]:
    names = _names(_header_parts(statement), ast.Load)
    if isinstance(statement, ast.AugAssign) and isinstance(statement.target, ast.Name):
        names.add(statement.target.id)   # (`x += 1` reads x)
    return names


class _Function:
    """A def's statements in line order and, for each name a statement reads, where it comes from."""

    def __init__(self, fn: ast.FunctionDef):
        arguments = fn.args
        self.parameters = {a.arg for a in [*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs,
                                           *filter(None, [arguments.vararg, arguments.kwarg])]}
        self.statements = sorted((node for node in walk(fn) if isinstance(node, ast.stmt) and node is not fn),
                                 key=lambda node: (node.lineno, node.col_offset))
        self.local = set().union(*(_assigned(s) for s in self.statements)) if self.statements else set()
        self.by_key: dict[str, list[ast.stmt]] = {}
        self.sources: dict[int, dict] = {}    # id of a statement -> name it reads -> where it comes from
        last: dict[str, ast.stmt] = {}        # name -> the last statement so far that assigns it
        for statement in self.statements:     # (one pass: a long module is read in linear time)
            self.by_key.setdefault(_key(statement), []).append(statement)
            self.sources[id(statement)] = {name: last.get(name) or self._outside(name) for name in _read(statement)}
            last.update(dict.fromkeys(_assigned(statement), statement))

    def _outside(self, name: str):
        """Where a name no statement above assigns comes from: ("parameter", name) or ("module", name);
        None for a local one assigned only further on."""
        if name in self.parameters:
            return ("parameter", name)
        return None if name in self.local else ("module", name)


def _bindings(tree: ast.Module) -> tuple[dict[str, str], dict[str, set], set[str]]:
    """What each module-level name is bound to, for comparison (a def's or a class's whole code, an
    assignment's value, an import's module), the module-level names each binding reads, and the names
    bound more than once or otherwise (unknown)."""
    bound: dict[str, str] = {}
    reads: dict[str, set] = {}
    unknown: set[str] = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            named = [(node.name, ast.dump(node), node)]
        elif isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            named = [(node.targets[0].id, ast.dump(node.value), node.value)]
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            named = [(alias.asname or alias.name.split(".")[0], f"{getattr(node, 'module', '')}:{alias.name}", None)
                     for alias in node.names]
        else:
            named = [(n.id, "", None) for n in walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)]
            unknown.update(name for name, _, _ in named)
        for name, text, value in named:
            if name in bound:
                unknown.add(name)
            bound[name] = text
            reads[name] = set() if value is None else \
                {n.id for n in walk(value) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
    return bound, reads, unknown


def differing_names(student_module: ast.Module, reference_module: ast.Module) -> frozenset[str]:
    """The module-level names the two modules do not bind alike: bound to other code or values, bound
    in one only, bound twice, or bound alike but reading such a name (a helper of the same code calling
    a helper that differs)."""
    own, own_reads, own_unknown = _bindings(student_module)
    model, _, model_unknown = _bindings(reference_module)
    differ = {name for name in set(own) | set(model) if own.get(name) != model.get(name)}
    differ |= own_unknown | model_unknown
    grown = True
    while grown:   # (at most one pass per name: each pass adds one at least)
        grown = False
        for name, read in own_reads.items():
            if name not in differ and read & differ:
                differ.add(name)
                grown = True
    return frozenset(differ)


def anchored(student: ast.FunctionDef, reference: ast.FunctionDef, differ: frozenset = frozenset()) -> set[int]:
    """The ids of ``student``'s statements anchored in ``reference`` (see the module's docstring). A
    module-level name read is the same in both only where it is not in ``differ`` (:func:`differing_names`:
    `_eight_point_core` changed makes its callers' lines unanchored)."""
    mine, theirs = _Function(student), _Function(reference)
    known: dict[tuple[int, int], bool] = {}

    def same(statement: ast.stmt, model: ast.stmt) -> bool:
        # (each step goes to a statement above in the reference, a short trusted function: the depth
        # is bounded by its length, however long the student's)
        pair = (id(statement), id(model))
        if pair not in known:
            known[pair] = False
            read, model_read = mine.sources[id(statement)], theirs.sources[id(model)]
            known[pair] = _key(statement) == _key(model) and read.keys() == model_read.keys() and all(
                same_source(read[name], model_read[name]) for name in read)
        return known[pair]

    def same_source(source, model_source) -> bool:
        if source is None or model_source is None:
            return False
        if isinstance(source, tuple) or isinstance(model_source, tuple):
            return source == model_source and not (source[0] == "module" and source[1] in differ)
        return same(source, model_source)

    return {id(statement) for statement in mine.statements
            if any(same(statement, model) for model in theirs.by_key.get(_key(statement), ()))}
