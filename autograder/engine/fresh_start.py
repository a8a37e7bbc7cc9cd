"""A failure that comes from what earlier calls left behind: the same call, made first in a module
imported anew, answers right.

A function that keeps something between calls -- a cache keyed by less than the answer depends on,
a module-level list that grows, an array of the module changed in place, a mutable default argument
-- answers its first call right and a later one wrong. Whatever the check measured then (a wrong
angle, a shifted image) describes the stale answer, not the code, and a change that makes the
answers right (a repair) would only work around the state. So, before anything else names a failed
check, the failing call is made again in the student's companion sandbox, in their module's file
executed anew (:meth:`autograder.sandbox.supervisor.Sandbox.call_variant` with ``fresh``), twice:
when both fresh answers agree (no random draw) and are the reference's, while the grading's answer
was wrong, the cause is named as state kept between calls, with the module-level holders the
function reads (a reading of the code, never run) as where to look.

Tried only where the student's code has such a holder: a name bound at the top of the module to a
container or an array, a ``global`` statement, a mutable default, an attribute set on a function or
class -- and never costs the verdict.
"""

from __future__ import annotations

import ast
from dataclasses import replace

from ..loading.parsing import TooLarge, parse, walk
from .conventions import STATE_BETWEEN_CALLS

# Calls whose value is a new container: a name bound to one at the top of a module can hold state.
_CONTAINERS = frozenset({"dict", "list", "set", "defaultdict", "OrderedDict", "deque", "Counter",
                         "array", "zeros", "ones", "eye", "identity", "full", "empty", "asarray", "copy"})
TIMEOUT_FACTOR = 4.0      # a fresh call may take this many times the grading's own calls (an import too)
MIN_TIMEOUT = 2.0


def _is_container(node) -> bool:
    if isinstance(node, (ast.Dict, ast.List, ast.Set, ast.DictComp, ast.ListComp, ast.SetComp)):
        return True
    if isinstance(node, ast.Call):
        func = node.func
        name = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
        return name in _CONTAINERS
    return False


def _defs(tree: ast.Module) -> dict[str, ast.FunctionDef]:
    """The module's top-level functions and the methods of its top-level classes, by name."""
    found = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            found[node.name] = node
        elif isinstance(node, ast.ClassDef):
            found.update({f"{node.name}.{item.name}": item for item in node.body
                          if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef))})
    return found


def _reached(tree: ast.Module, function: str) -> list[ast.AST]:
    """``function``'s def and those of the module it calls, however indirectly (by name)."""
    defs = _defs(tree)
    classes = {node.name for node in tree.body if isinstance(node, ast.ClassDef)}
    todo, seen = [function], set()
    while todo:
        name = todo.pop()
        if name in seen or name not in defs:
            continue
        seen.add(name)
        for node in walk(defs[name]):
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
                todo.append(node.id)
                if node.id in classes:
                    todo += [key for key in defs if key.startswith(node.id + ".")]
    return [defs[name] for name in sorted(seen)]


def holders(source: str, function: str) -> list[tuple[str, int]]:
    """(name, line) of what ``function`` (or a def of the module it calls) could keep between calls:
    module-level names bound to a container or an array that it reads, names it declares ``global``,
    its parameters with a mutable default, attributes it sets on a module-level def or class. Empty
    when there is none, or the source does not parse."""
    try:
        tree = parse(source)   # (the student's text: within the bounds, under the parse lock)
    except (SyntaxError, ValueError, RecursionError, MemoryError, TooLarge):
        return []
    top: dict[str, int] = {}
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else \
            [node.target] if isinstance(node, ast.AnnAssign) and node.value is not None else []
        value = getattr(node, "value", None)
        for target in targets:
            if isinstance(target, ast.Name) and _is_container(value):
                top.setdefault(target.id, node.lineno)
    named = {node.name for node in tree.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    read: dict[str, int] = {}      # what the code reads (a constant table too)
    changed: dict[str, int] = {}   # of which what it changes or rebinds: where state is kept
    for fn in _reached(tree, function):
        for default in [*fn.args.defaults, *(d for d in fn.args.kw_defaults if d is not None)]:
            if _is_container(default):
                changed.setdefault(f"a mutable default of {fn.name}", default.lineno)
        for node in walk(fn):
            if isinstance(node, (ast.Global, ast.Nonlocal)):
                for name in node.names:
                    changed.setdefault(name, top.get(name, node.lineno))
            elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id in top:
                read.setdefault(node.id, top[node.id])
            elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store) \
                    and isinstance(node.value, ast.Name) and node.value.id in named:
                changed.setdefault(f"{node.value.id}.{node.attr}", node.lineno)
            held = _changed_in_place(node)
            if held in top:
                changed.setdefault(held, top[held])
    return sorted((changed or read).items(), key=lambda item: item[1])


_CHANGES = frozenset({"append", "extend", "insert", "update", "setdefault", "pop", "popitem", "clear", "add",
                      "remove", "discard", "fill", "sort", "appendleft", "resize", "put", "itemset"})


def _changed_in_place(node) -> str:
    """The name a statement changes in place (`_CACHE[key] = M`, `seen.append(x)`, `M[0, 2] += tx`), or ""."""
    if isinstance(node, (ast.Assign, ast.AugAssign)):
        for target in node.targets if isinstance(node, ast.Assign) else [node.target]:
            while isinstance(target, (ast.Subscript, ast.Attribute)) and not isinstance(target.value, ast.Name):
                target = target.value
            if isinstance(target, (ast.Subscript, ast.Attribute)) and isinstance(target.value, ast.Name):
                return target.value.id
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in _CHANGES \
            and isinstance(node.func.value, ast.Name):
        return node.func.value.id
    return ""


def _where(kept: list[tuple[str, int]]) -> str:
    names = [f"`{name}` (line {line})" if not name.startswith("a mutable default") else f"{name} (line {line})"
             for name, line in kept[:3]]
    if not names:
        return ""
    return " -- look at " + (names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]) \
        + ", kept from one call to the next"


def named(verdict, trial):
    """The failed ``verdict`` named as state kept between calls when it is (see the module docstring);
    else unchanged. The check's own first line (what it measured) stays; its hint goes."""
    from .mutants import naming
    from .mutants.repair import _student_code

    if verdict.mistake == STATE_BETWEEN_CALLS or getattr(trial, "sandbox", None) is None:
        return verdict   # (told already, by a check calling twice)
    student = _student_code(trial)
    if student is None:
        return verdict

    def work(trial, model, clock):
        for function, calls in _recorded_calls(trial):
            kept = holders(student.text, function)
            if function in model.mutants and kept and _right_when_fresh(trial, model, clock, function, calls):
                return _told(verdict, function, kept)
        return None

    return naming._within_budget(trial, naming.GRADING_SECONDS, work) or verdict


def _recorded_calls(trial):
    from .mutants import naming
    from .mutants.repair import _recorded

    return [(function, calls[-naming.CALLS_PER_FUNCTION:]) for function, calls in _recorded(trial).items()]


def _right_when_fresh(trial, model, clock, function, calls) -> bool:
    """Whether the first of ``calls`` the reference answers otherwise, made twice in the student's module
    imported anew, answers the same both times and right."""
    from .mutants import naming
    from .mutants.repair import _wrong, right

    inputs = [call[:3] for call in calls]
    runner = naming.helper()
    runner.prepare(model.source, model.module, inputs, max(1.0, clock.wall_left()))
    references = runner.run((), range(len(inputs)), max(0.5, clock.wall_left()))
    failing = [i for i, (call, reference) in enumerate(zip(calls, references))
               if naming.error_kind(reference) is None and _wrong(call[3], reference)]
    if not failing:
        return False
    index = failing[0]
    per_call = trial.student_seconds / max(1, len(trial.calls))
    timeout = max(MIN_TIMEOUT, TIMEOUT_FACTOR * per_call)
    fresh = []
    for _ in range(2):   # two fresh modules: the same answer twice, no random draw behind it
        if clock.left() <= 0:
            return False
        outcome = trial.sandbox.companion().call_variant(
            trial.lab.module, "", function, [inputs[index][1:]], fresh=True,
            timeout=max(0.05, min(timeout, clock.wall_left())))
        value = outcome.value if outcome.ok else None
        if not (isinstance(value, list) and len(value) == 1) or naming.error_kind(value[0]) is not None:
            return False
        fresh.append(value[0])
    return naming.distance(fresh[0], fresh[1]) == 0 and right(fresh[0], references[index]) \
        and _wrong(calls[index][3], references[index])


def _told(verdict, function: str, kept):
    first, newline, rest = str(verdict.message).partition("\n")
    lead = first.rstrip()
    lead += "" if not lead or lead[-1] in ".:;!?" else "."
    said = (f"Made again as the first call of your module, imported anew, the same call of `{function}` gives "
            f"the expected answer: your `{function}` keeps something between calls{_where(kept)} -- so an earlier "
            "call's leftovers (a cache keyed by less than the answer depends on, a list that grows, an array "
            "changed in place) decide this answer. A function's answer may depend on its arguments only.")
    return replace(verdict, message=f"{lead} {said}{newline}{rest}", hint="", mistake=STATE_BETWEEN_CALLS)
