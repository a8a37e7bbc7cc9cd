"""A string the student's code compares a parameter with, where the API spells that value otherwise
(read, never run).

``if method == "ORB":`` where the API's value is ``"orb"``: ``method="orb"`` never takes the branch,
and what runs instead fails far from the comparison (SIFT's float descriptors given a Hamming
matcher: an OpenCV assertion). The API's values are the strings the reference compares the same
parameter with; a student's string that is one of them written in other letters' case, or with spaces
around it, is named -- unless the function changes the parameter before comparing (``method.upper()``).
"""

from __future__ import annotations

import ast
import functools

from ..loading.parsing import parse, walk
from .claims import from_code

MISTAKE = "a parameter compared with a string the API spells otherwise"


def _compared(functions) -> list[tuple[str, str, int, str]]:
    """``(parameter, string, line, function)`` of every comparison of a parameter (as it came: never
    bound again in that function) with string constants (``==``, ``!=``, ``in (...)``)."""
    found = []
    for function in (f for f in functions if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))):
        parameters = {a.arg for a in function.args.posonlyargs + function.args.args + function.args.kwonlyargs}
        rebound = {t.id for n in walk(function) if isinstance(n, (ast.Assign, ast.AugAssign, ast.AnnAssign))
                   for target in (n.targets if isinstance(n, ast.Assign) else [n.target])
                   for t in walk(target) if isinstance(t, ast.Name)}
        for node in walk(function):
            if not isinstance(node, ast.Compare):
                continue
            sides = [node.left, *node.comparators]
            names = [s.id for s in sides if isinstance(s, ast.Name) and s.id in parameters - rebound]
            strings = [c.value for s in sides for c in ([s] if isinstance(s, ast.Constant) else
                                                        s.elts if isinstance(s, (ast.Tuple, ast.List, ast.Set)) else [])
                       if isinstance(c, ast.Constant) and isinstance(c.value, str)]
            found += [(name, string, node.lineno, function.name) for name in names for string in strings]
    return found


@functools.lru_cache(maxsize=16)
def _api_strings(source: str) -> dict:
    """parameter -> the strings the reference module compares it with (the API's values)."""
    tree = parse(source, max_chars=None, max_statements=None)   # (the reference's text: trusted)
    values: dict = {}
    for parameter, string, _, _ in _compared([n for n in tree.body if isinstance(n, ast.FunctionDef)]):
        values.setdefault(parameter, set()).add(string)
    return values


def misspelt(functions, reference_source: str) -> tuple[str, str, int, str, str] | None:
    """``(function, parameter, their string, line, the API's string)`` of the first comparison in
    ``functions`` (the student's, read together) with a string the API spells otherwise; None."""
    api = _api_strings(reference_source)
    for parameter, string, line, function in _compared(functions):
        wanted = api.get(parameter, set())
        if string in wanted:
            continue
        same = [value for value in sorted(wanted) if value.strip().lower() == string.strip().lower()]
        if same:
            return function, parameter, string, line, same[0]
    return None


def sentence(function: str, parameter: str, theirs: str, line: int, api: str) -> str:
    return from_code(f"your `{function}` compares `{parameter}` with {theirs!r} (line {line}), where the API's value "
                     f"is {api!r}: strings compare letter for letter, so {parameter}={api!r} never matches it")
