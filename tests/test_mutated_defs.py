"""A mutant's defs are built by walking each def once, as far as its last edit, and fixing the
locations of the new nodes alone: the trees (and every node's location, which the lines told to
students come from) are those of the slow way -- the def copied whole, every node's parent
mapped, the whole module's missing locations fixed."""

from __future__ import annotations

import ast
import copy

import pytest

from autograder.engine.mutants import naming
from autograder.engine.mutants.operators import _MAKE, _defs, _parents, _replace, mutated_defs
from autograder.engine.registry import discover
from autograder.loading.parsing import parse


def slowly_mutated(tree: ast.Module, edits, source: str | None = None) -> ast.Module:
    """The defs ``edits`` change, built the plain way (the oracle; ValueError for overlapping edits).
    With ``source``, each def is parsed from its own lines, as mutated_defs does (its lines counted
    from the def's)."""
    defs = _defs(tree)
    lines = source.splitlines(keepends=True) if source is not None else None
    changed = {}
    for where, _, _, _ in edits:
        if where not in changed:
            fn = defs[where]
            changed[where] = copy.deepcopy(fn) if lines is None else \
                ast.parse("".join(lines[min([fn.lineno] + [d.lineno for d in fn.decorator_list]) - 1:fn.end_lineno])).body[0]
    located = [(list(ast.walk(changed[where]))[ordinal], operator, payload)
               for where, ordinal, operator, payload in edits]
    for node, _, _ in located:
        if any(other is not node and any(inner is other for inner in ast.walk(node)) for other, _, _ in located):
            raise ValueError("overlapping edits")
    for fn in changed.values():
        parents = _parents(fn)
        for node, operator, payload in located:
            if id(node) in parents:
                _replace(parents, node, _MAKE[operator](node, payload))
    return ast.fix_missing_locations(ast.Module(list(changed.values()), []))


@pytest.mark.parametrize("lab, every", [("lab07", 1), ("lab12", 3)])
def test_mutants_are_the_trees_the_slow_way_builds(lab, every):
    model = naming.model_for(discover()[lab])
    tree = parse(model.source, max_chars=None, max_statements=None)
    mutants = [m.edits for ms in model.mutants.values() for m in ms][::every]
    assert len(mutants) > 300
    # (and pairs, as the error model combines them: two edits of one def, or of two defs)
    paired = [first + second for first, second in zip(mutants[::7], mutants[3::7])]
    tried = 0
    for k, edits in enumerate(mutants + paired):
        for source in (model.source, None) if k % 6 == 0 else (model.source,):   # (copying the def: slower)
            try:
                expected = ast.dump(slowly_mutated(tree, edits, source), include_attributes=True)
            except ValueError:
                with pytest.raises(ValueError):
                    mutated_defs(tree, edits, source)
                continue
            tried += len(edits) > 1
            assert ast.dump(mutated_defs(tree, edits, source), include_attributes=True) == expected, edits
    assert tried > 30


def test_an_edit_past_the_def_or_overlapping_another_is_refused():
    source = "def f(x):\n    return (x + 1) * 2\n"
    tree = ast.parse(source)
    count = len(list(ast.walk(tree.body[0])))
    with pytest.raises(ValueError, match="no node"):
        mutated_defs(tree, [("f", count, "sign", None)], source)
    nodes = list(ast.walk(tree.body[0]))
    outer = next(i for i, n in enumerate(nodes) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Mult))
    inner = next(i for i, n in enumerate(nodes) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Add))
    with pytest.raises(ValueError, match="overlapping"):
        mutated_defs(tree, [("f", outer, "sign", None), ("f", inner, "add_sub", None)], source)
    changed = mutated_defs(tree, [("f", inner, "add_sub", None)], source)
    assert ast.unparse(changed) == "def f(x):\n    return (x - 1) * 2"
