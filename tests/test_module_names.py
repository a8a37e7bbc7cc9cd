"""No module of the grader binds a top-level name twice: a second ``HINT = ...`` far down a lab
suite silently replaces the first for every check that reads it at call time (lab 12's rectify
checks once gave the NCC's block-means hint this way)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MODULES = sorted(p for top in ("autograder", "fixtures") for p in (ROOT / top).rglob("*.py"))


def _bound_twice(tree: ast.Module) -> list[str]:
    """Top-level names assigned (or defined) more than once, except in ``if``/``try`` fallbacks."""
    seen, twice = set(), []
    for node in tree.body:
        names = []
        if isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            names = [t.id for t in targets if isinstance(t, ast.Name)]
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names = [node.name]
        for name in names:
            if name in seen and name != "__all__":
                twice.append(f"{name} (line {node.lineno})")
            seen.add(name)
    return twice


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_no_top_level_name_is_bound_twice(path):
    assert _bound_twice(ast.parse(path.read_text(encoding="utf-8"))) == []


def test_the_check_finds_a_name_bound_twice():
    assert _bound_twice(ast.parse("A = 1\ndef f(): pass\nA = 2\ndef f(): pass\n")) == ["A (line 3)", "f (line 4)"]
