"""The grader's one walk and one copy of syntax trees (autograder/loading/parsing.py) behave as
ast.walk and copy.deepcopy do, on every module the grader reads and on trees changed while walked.

Every reader, mutant operator and repair goes through them: a walk that read a node's children
after handing the node out walked into the wrapper a caller had just put around it, and wrapped
it again without end (a grading's process grew past 19 GB in tests/test_repair.py).
"""

from __future__ import annotations

import ast
import copy
from pathlib import Path

import pytest

from autograder.loading.parsing import copy_tree, walk

ROOT = Path(__file__).resolve().parents[1]
MODULES = sorted([*(ROOT / "reference_solutions").glob("lab*.py"), *(ROOT / "assignments").glob("lab*.py"),
                  ROOT / "autograder" / "engine" / "mutants" / "repair.py"])


def _kinds(nodes) -> list[str]:
    return [type(node).__name__ for node in nodes]


@pytest.mark.parametrize("path", MODULES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_walk_gives_ast_walks_nodes_in_its_order(path):
    tree = ast.parse(path.read_text())
    assert [id(n) for n in walk(tree)] == [id(n) for n in ast.walk(tree)]


def _wrapping_each_name(walker, tree) -> list[str]:
    """Walk ``tree`` wrapping each Name read in a call ``f(name)`` in its parent's place, as mutant
    operators do; the names seen, in order (a walk that follows the change never ends: bounded here)."""
    seen = []
    for node in walker(tree):
        for name, value in ast.iter_fields(node):
            if isinstance(value, ast.Name) and isinstance(value.ctx, ast.Load):
                setattr(node, name, ast.Call(ast.Name("f", ast.Load()), [value], []))
        seen.append(type(node).__name__)
        if len(seen) > 10_000:
            break
    return seen


def test_a_tree_changed_while_walked_is_walked_as_it_was_as_ast_walk_does():
    source = "def g(a, b):\n    c = a * b + a\n    return h(c, b)\n"
    ours, theirs = ast.parse(source), ast.parse(source)
    walked = _wrapping_each_name(walk, ours)
    assert len(walked) < 10_000 and walked == _wrapping_each_name(ast.walk, theirs)
    assert ast.dump(ours) == ast.dump(theirs)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_copy_tree_copies_as_deepcopy_does(path):
    tree = ast.parse(path.read_text())
    copied = copy_tree(tree)
    assert ast.dump(copied, include_attributes=True) == ast.dump(copy.deepcopy(tree), include_attributes=True)
    # every node with fields or a position is new: a change of the copy never reaches the original
    originals = {id(node) for node in ast.walk(tree) if node._fields or node.__dict__}
    assert not [node for node in ast.walk(copied) if id(node) in originals]
    function = next(node for node in ast.walk(copied) if isinstance(node, ast.FunctionDef))
    function.body.clear()
    assert all(node.body for node in ast.walk(tree) if isinstance(node, ast.FunctionDef))


def test_copy_tree_copies_lists_of_nodes_and_other_values_deeply():
    nodes = ast.parse("x = [1, 2]\ny = x").body
    copied = copy_tree(nodes)
    assert isinstance(copied, list) and [ast.dump(n) for n in copied] == [ast.dump(n) for n in nodes]
    assert all(a is not b for a, b in zip(copied, nodes))
    value = {"a": [1, 2]}
    assert copy_tree(value) == value and copy_tree(value)["a"] is not value["a"]


def test_the_caches_a_reader_keeps_on_a_node_are_copied_with_the_copys_nodes():
    """Readers keep caches on a def (reading._nodes' ``_walked``, the operators' ``_uses_of``...), holding nodes of
    its tree: a copy shared with the original would read the original's nodes, unchanged by the copy's mutation.
    As deepcopy does, the copy's cache holds the copy's own nodes."""
    from autograder.loading.reading import _nodes

    fn = ast.parse("def f(a):\n    b = a + 1\n    return b\n").body[0]
    _nodes(fn)
    fn._scope = {"names": ["a", "b"]}
    copied = copy_tree(fn)
    assert [id(n) for n in copied._walked] == [id(n) for n in ast.walk(copied)]
    assert copied._scope == fn._scope and copied._scope is not fn._scope
    assert [id(n) for n in copy_tree([fn])[0]._walked] != [id(n) for n in fn._walked]
