"""Planted copies for the similarity tests: the same code, disguised as a copier would."""

from __future__ import annotations

import ast
import builtins
import random


class _Rename(ast.NodeTransformer):
    def __init__(self, names):
        self.names = names

    def visit_Name(self, node):
        node.id = self.names.get(node.id, node.id)
        return node

    def visit_arg(self, node):
        node.arg = self.names.get(node.arg, node.arg)
        return node

    def visit_FunctionDef(self, node):
        node.name = self.names.get(node.name, node.name)
        if (node.body and isinstance(node.body[0], ast.Expr)
                and isinstance(node.body[0].value, ast.Constant) and isinstance(node.body[0].value.value, str)):
            node.body[0].value.value = "Implementation for this part of the lab."
        self.generic_visit(node)
        return node


def disguise(source: str, seed: int) -> str:
    """``source`` with its local variables and private helpers renamed, its functions
    reordered, its comments and docstrings rewritten (and reformatted by ``ast.unparse``)."""
    rng = random.Random(seed)
    tree = ast.parse(source)
    public_params = {a.arg for f in tree.body if isinstance(f, ast.FunctionDef) and not f.name.startswith("_")
                     for a in f.args.args + f.args.kwonlyargs}
    bound = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            bound.add(node.id)
        elif isinstance(node, ast.FunctionDef) and node.name.startswith("_"):
            bound.add(node.name)
        elif isinstance(node, ast.arg) and node.arg not in public_params:
            bound.add(node.arg)
    bound -= set(dir(builtins)) | {"np", "cv2", "math"}
    names = {name: f"{'_' if name.startswith('_') else ''}v{rng.randrange(10**6)}_{i}"
             for i, name in enumerate(sorted(bound))}
    tree = _Rename(names).visit(tree)
    imports = [n for n in tree.body if isinstance(n, (ast.Import, ast.ImportFrom))]
    rest = [n for n in tree.body if not isinstance(n, (ast.Import, ast.ImportFrom, ast.Expr))]
    rng.shuffle(rest)
    tree.body = imports + rest
    lines = []
    for line in ast.unparse(tree).splitlines():
        if line.strip().startswith("return "):
            lines.append(line[: len(line) - len(line.lstrip())] + "# here is the answer")
        lines.append(line)
    return '"""My lab 7."""\n' + "\n".join(lines) + "\n"
