"""Students' notebooks as gradable modules.

A notebook is written to be run from the top, with demo, plotting and
``plt.show()`` cells between the definitions. Grading imports the module, so by
default only the *definitions* of a notebook are taken:

- ``import`` / ``from ... import`` statements (also inside ``try``),
- ``def`` and ``class`` statements (with their decorators),
- assignments of constants: literals, arithmetic on them, names and attributes
  (``ANGLE = np.pi / 4``), and a few pure NumPy constructors of literals
  (``K = np.array([[800, 0, 320], [0, 800, 240], [0, 0, 1]])``).

Everything else (loading images, calling functions, plotting, printing) is
left out of grading. Two cell tags give control where that guess is wrong
(in Jupyter: View > Cell toolbar > Tags, or the property inspector):

- ``skip-grading``: the whole cell is left out;
- ``grade``: the whole cell is taken as written, statements and all.

IPython magics (``%matplotlib inline``, ``!pip install ...``) are commented out.
Left-out lines stay in the module as comments, so every line keeps its place:
a converted module's line numbers map back to the notebook's cell and line
(:meth:`ConvertedNotebook.where`, :func:`point_into_notebook`). Cells are
numbered from 1 at the top of the notebook, Markdown cells included.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass, field

SKIP_TAG = "skip-grading"
GRADE_TAG = "grade"
HEADER = "# --- notebook cell {number}"
LEFT_OUT = "# (not graded) "

# Calls that only build constants, safe to run at import when their arguments are constants.
_CONSTANT_CALLS = {
    "array", "asarray", "float32", "float64", "int32", "int64", "uint8", "eye", "zeros", "ones",
    "diag", "deg2rad", "rad2deg", "radians", "degrees", "sqrt", "cos", "sin", "tan", "arctan2",
    "float", "int", "tuple", "list", "dict", "set", "frozenset", "range",
}


class NotebookError(ValueError):
    """A file that should be a notebook but cannot be read as one."""


@dataclass
class ConvertedNotebook:
    """A notebook turned into a module's source.

    Attributes
    ----------
    source : str
        The module text: one block per code cell, left-out lines commented.
    cells : list of (module_line, cell_number, line_count)
        Where each code cell sits in the module (first line, 1-based).
    left_out : list of str
        ``"cell 7: plt.show()"``-style notes of the statements not graded.
    """

    source: str
    cells: list[tuple[int, int, int]] = field(default_factory=list)
    left_out: list[str] = field(default_factory=list)
    cell_label: str = "cell {number}"  # "In [{number}]" for a kernel's history (see selfcheck)

    def label(self, number: int) -> str:
        return self.cell_label.format(number=number)

    def where(self, line: int) -> tuple[int, int] | None:
        """``(cell_number, line_in_cell)`` of a converted module's ``line``; None for a header."""
        for start, cell, count in self.cells:
            if start <= line < start + count:
                return cell, line - start + 1
        return None


def read_notebook(text: str, name: str = "notebook"):
    """Parse a notebook's JSON (any nbformat version, upgraded to v4).

    Raises
    ------
    NotebookError
        Naming ``name`` and saying what is wrong and how to mend it.
    """
    import json
    import warnings

    try:
        data = json.loads(text)
        if not isinstance(data, dict) or not isinstance(data.get("cells"), list):
            raise TypeError("no list of cells")
        if "nbformat" not in data:
            return data  # a bare {"cells": [...]} (hand-made or exported by a tool): usable as is
        import nbformat

        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # missing cell ids and the like: harmless here
                notebook = nbformat.reads(text, as_version=4)
        except Exception:  # noqa: BLE001 - strict schema; the code may still be plainly readable
            if not _plainly_readable(data["cells"]):
                raise
            return data  # cells without metadata/outputs (written by a tool): their code is all we need
        if not isinstance(notebook["cells"], list):
            raise TypeError("'cells' is not a list")
    except Exception as exc:  # noqa: BLE001 - nbformat raises many types for a damaged file
        reason = ("not valid JSON" if isinstance(exc, ValueError) and not str(exc).startswith("Notebook")
                  else (str(exc).splitlines() or [type(exc).__name__])[0])
        raise NotebookError(
            f"{name} is not a readable notebook ({reason[:200]}); open it in Jupyter and save it "
            "again, or hand in the code as a .py file") from None
    return notebook


def _mapping(value) -> dict:
    """``value`` if it is a dict, else an empty one (a hand-edited notebook may hold anything)."""
    return value if isinstance(value, dict) else {}


def _plainly_readable(cells) -> bool:
    """Every code cell's source is text or a list of lines (other entries are passed over)."""
    def text(source):
        return isinstance(source, str) or (isinstance(source, list) and all(isinstance(s, str) for s in source))
    return all(text(c.get("source", "")) for c in cells if isinstance(c, dict) and c.get("cell_type") == "code")


def convert(text: str, name: str = "notebook", definitions_only: bool = True) -> ConvertedNotebook:
    """The code cells of a notebook as one module (see the module docstring for the rules).

    Parameters
    ----------
    text : str
        The notebook file's content (JSON).
    name : str
        The file name, for error messages.
    definitions_only : bool
        Take only definitions from untagged cells (the default); False takes
        every code cell whole, as running the notebook top to bottom would.
    """
    notebook = read_notebook(text, name)
    lines: list[str] = []
    converted = ConvertedNotebook("")
    settings = _mapping(_mapping(notebook.get("metadata")).get("autograder"))
    if isinstance(settings.get("cell_label"), str) and "{number}" in settings["cell_label"]:
        converted.cell_label = settings["cell_label"]
    for number, cell in enumerate(notebook["cells"], 1):
        if not isinstance(cell, dict) or cell.get("cell_type") != "code":
            continue
        source = cell.get("source", "")
        source = "".join(map(str, source)) if isinstance(source, list) else str(source)
        tags = _mapping(cell.get("metadata")).get("tags")
        tags = {t for t in tags if isinstance(t, str)} if isinstance(tags, list) else set()
        cell_lines = _without_magics(source.splitlines())
        if SKIP_TAG in tags:
            keep = [False] * len(cell_lines)
        elif GRADE_TAG in tags or not definitions_only:
            keep = [True] * len(cell_lines)
        else:
            keep = _definition_lines(cell_lines)
        lines.append(HEADER.format(number=number))
        converted.cells.append((len(lines) + 1, number, len(cell_lines)))
        for text_line, kept in zip(cell_lines, keep):
            lines.append(text_line if kept or not text_line.strip() else LEFT_OUT + text_line)
        dropped = [line.strip() for line, kept in zip(cell_lines, keep) if not kept and line.strip()
                   and not line.lstrip().startswith("#")]
        if dropped:
            converted.left_out.append(f"{converted.label(number)}: {dropped[0][:60]}"
                                      + (f" (+{len(dropped) - 1} lines)" if len(dropped) > 1 else ""))
        lines.append("")
    converted.source = "\n".join(lines) + "\n"
    return converted


def _without_magics(lines: list[str]) -> list[str]:
    """IPython's ``%magic``, ``%%cell magic`` and ``!shell`` lines, commented out."""
    return [("# " + line) if line.lstrip().startswith(("%", "!")) else line for line in lines]


def _definition_lines(lines: list[str]) -> list[bool]:
    """Which lines of a cell belong to definitions. A cell that does not parse is kept
    whole, so that its syntax error is reported (with its cell and line) at grading."""
    try:
        tree = ast.parse("\n".join(lines))
    except (SyntaxError, ValueError, RecursionError, MemoryError):  # ValueError: NUL bytes (Python 3.10)
        return [True] * len(lines)
    keep = [False] * len(lines)
    for statement in tree.body:
        if _is_definition(statement):
            first = min([statement.lineno] + [d.lineno for d in getattr(statement, "decorator_list", [])])
            for i in range(first - 1, statement.end_lineno):
                keep[i] = True
    return keep


def _is_definition(node: ast.stmt) -> bool:
    if isinstance(node, (ast.Import, ast.ImportFrom)):
        # `from autograder import check` is for the notebook, not for the graded module.
        names = [node.module or ""] if isinstance(node, ast.ImportFrom) else [a.name for a in node.names]
        return not any(name.split(".")[0] == "autograder" for name in names)
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return True
    if isinstance(node, ast.Try):  # try: import cv2 / except ImportError: ...
        body = node.body + node.orelse + node.finalbody + [s for h in node.handlers for s in h.body]
        return all(_is_definition(s) or isinstance(s, ast.Pass) for s in body)
    if isinstance(node, ast.Assign):
        return all(isinstance(t, (ast.Name, ast.Tuple)) for t in node.targets) and _is_constant(node.value)
    if isinstance(node, ast.AnnAssign):
        return isinstance(node.target, ast.Name) and (node.value is None or _is_constant(node.value))
    if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant):
        return True  # a docstring
    return False


def _is_constant(node: ast.expr) -> bool:
    """An expression that only combines constants: cheap, silent and safe to evaluate at import."""
    if isinstance(node, ast.Constant):
        return True
    if isinstance(node, ast.Name):
        return True
    if isinstance(node, ast.Attribute):
        return _is_constant(node.value)
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return all(_is_constant(e) for e in node.elts)
    if isinstance(node, ast.Dict):
        return all(k is None or _is_constant(k) for k in node.keys) and all(_is_constant(v) for v in node.values)
    if isinstance(node, ast.UnaryOp):
        return _is_constant(node.operand)
    if isinstance(node, ast.BinOp):
        return _is_constant(node.left) and _is_constant(node.right)
    if isinstance(node, ast.Call):
        func = node.func
        called = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", None)
        return (called in _CONSTANT_CALLS and all(_is_constant(a) for a in node.args)
                and all(_is_constant(k.value) for k in node.keywords))
    return False


def point_into_notebook(text: str, module: str, notebook_name: str, converted: ConvertedNotebook) -> str:
    """Rewrite ``module.py, line N`` and tracebacks' ``File "module.py", line N`` in ``text``
    as ``notebook.ipynb, cell C, line L``; other mentions of ``module.py`` name the notebook."""
    if not text:
        return text
    filename = re.escape(module + ".py")

    def spot(line: str) -> str:
        found = converted.where(int(line))
        return f"{converted.label(found[0])}, line {found[1]}" if found else f"line {line}"

    text = re.sub(rf'File "{filename}", line (\d+)',
                  lambda m: f'File "{notebook_name}", {spot(m.group(1))}', text)
    text = re.sub(rf"(?<![\w/.]){filename}, line (\d+)",
                  lambda m: f"{notebook_name}, {spot(m.group(1))}", text)
    return re.sub(rf"(?<![\w/.\"]){filename}", notebook_name, text)
