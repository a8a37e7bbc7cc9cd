"""Students' notebooks as gradable modules.

A notebook is written to be run from the top, with demo, plotting and
``plt.show()`` cells between the definitions. Grading imports the module, so by
default it takes what running the notebook from the top *defines*: imports,
functions, classes, and values computed from them and from constants
(``K = np.array([[800, 0, 320], ...])``, ``H = K @ R``, ``to_h = lambda p: ...``),
each statement exactly when everything it needs is taken too; demo code
(loading images, plotting, printing, calling your functions on examples) and
whatever depends on it is left out, and so is an import only demo code uses
(see :mod:`autograder.loading.definitions` for the rules). One line per notebook names
the statements left out and why. Two cell tags give control where that guess is
wrong (in Jupyter: View > Cell toolbar > Tags, or the property inspector):

- ``skip-grading``: the whole cell is left out;
- ``grade``: the whole cell is taken as written, statements and all.

Only these two tags count; every other tag, and every other piece of metadata, is
passed over. A notebook is data: nothing in it (metadata, tags, names) ever becomes a
format string, a template or a path, and what a message quotes of it is bounded.

IPython syntax is commented out: magics (``%matplotlib inline``), shell commands
(``!pip install ...``, ``files = !ls``), help (``np.array?``), and the whole of a
cell whose ``%%`` magic makes it other than Python (``%%bash``, ``%%writefile``).
Left-out lines stay in the module as comments, so every line keeps its place:
a converted module's line numbers map back to the notebook's cell and line
(:meth:`ConvertedNotebook.where`, :func:`point_into_notebook`). Cells are
numbered from 1 at the top of the notebook, Markdown cells included.
"""

from __future__ import annotations

import bisect
import re
from dataclasses import dataclass, field
from typing import Callable

from .definitions import GUARD, CellCode, Omission, analyse, taken_whole
from .parsing import MAX_PARSE_CHARS, MAX_PARSE_STATEMENTS, parse
from .text import one_line

SKIP_TAG = "skip-grading"
GRADE_TAG = "grade"
HEADER = "# --- notebook cell "   # + the cell's number
LEFT_OUT = "# (not graded) "
# How messages name a cell: "cell 7" (its place in the notebook), or "In [7]" for a kernel's
# input history (see selfcheck), asked for by the notebook's metadata ``autograder.cell_label``.
CELL_LABELS = ("cell", "input")
# Cell magics whose body is Python, run as it is (the magic only times or captures it).
_PYTHON_CELL_MAGICS = {"time", "timeit", "capture", "prun", "debug", "memit"}
NOTE_STATEMENTS = 5   # statements a notebook's note names (the rest are counted)


class NotebookError(ValueError):
    """A file that should be a notebook but cannot be read as one."""


@dataclass
class ConvertedNotebook:
    """A notebook turned into a module's source.

    Attributes
    ----------
    source : str
        The module text: one block per code cell, left-out lines commented.
    guarded_source : str
        What grading imports: ``source`` with each line of kept values guarded, so that
        one raising is skipped rather than failing the import (see :mod:`autograder.loading.definitions`).
    cells : list of (module_line, cell_number, line_count)
        Where each code cell sits in the module (first line, 1-based).
    omissions : list of Omission
        The statements left out, in notebook order, with why
        (:class:`autograder.loading.definitions.Omission`).
    left_out : list of str
        Per cell with lines left out: ``"cell 7: plt.show() (+2 lines)"``.
    whole : str
        Why no statement was read and every cell was taken whole (its code is beyond what
        the grader parses, see :mod:`autograder.loading.parsing`), or ``""``.
    """

    source: str
    cells: list[tuple[int, int, int]] = field(default_factory=list)
    omissions: list[Omission] = field(default_factory=list)
    left_out: list[str] = field(default_factory=list)
    guarded_source: str = ""
    cell_label: str = "cell"  # one of CELL_LABELS
    whole: str = ""           # why every cell was taken whole, unread (too much code to read), or ""

    def label(self, number: int) -> str:
        """``"cell 7"`` or ``"In [7]"``: the words are the grader's, never the notebook's."""
        return f"In [{int(number)}]" if self.cell_label == "input" else f"cell {int(number)}"

    def labels(self, numbers: list[int]) -> str:
        """``"cell 7"``, ``"cells 6, 7"``, ``"In [6], In [9]"``."""
        if self.cell_label == "input" or len(numbers) == 1:
            return ", ".join(self.label(n) for n in numbers)
        return "cells " + ", ".join(str(int(n)) for n in numbers)

    def left_out_lines(self) -> list[str]:
        """Every statement left out at grading that would have done something, once each (the
        same statement in several cells, or a cell run twice in a kernel, is one line naming
        every cell), as written: ``"cells 6, 7 `plt.show()` (plotting)"``. Statements whose
        names a kept function reads come first: that function fails when called."""
        grouped: dict[tuple, list[int]] = {}
        for omission in sorted((o for o in self.omissions if o.listed), key=lambda o: not o.users):
            why = omission.reason
            if omission.users:
                why += "; " + ", ".join(f"{f}() uses {n}" for f, n in omission.users[:2])
            cells = grouped.setdefault((one_line(omission.text, 50), one_line(why, 120)), [])
            if omission.cell not in cells:
                cells.append(omission.cell)
        return [f"{self.labels(cells)} `{text}` ({why})" for (text, why), cells in grouped.items()]

    def left_out_note(self, name: str) -> str:
        """A note naming the statements left out and why (those that would have done
        something: a value shown at a cell's end is not named), or ``""``: its first line
        names the first :data:`NOTE_STATEMENTS` (see :meth:`left_out_lines`) and how many
        more; when there are more, each following line is one of them all, for a page to
        fold (the terminal shows the first line)."""
        if self.whole:
            return f"{one_line(name, 80)}: {self.whole}"
        lines = self.left_out_lines()
        if not lines:
            return ""
        more = len(lines) - NOTE_STATEMENTS
        first = (f"{one_line(name, 80)}: left out at grading: {', '.join(lines[:NOTE_STATEMENTS])}"
                 + (f", and {more} more (validate lists them all)" if more > 0 else "")
                 + f". Tag a cell '{GRADE_TAG}' to grade it whole, '{SKIP_TAG}' to leave it out.")
        return "\n".join([first] + (lines if more > 0 else []))

    def where(self, line: int) -> tuple[int, int] | None:
        """``(cell_number, line_in_cell)`` of a converted module's ``line``; None for a header.
        ``cells`` is in module order, so the cell is found by bisection."""
        index = bisect.bisect_right(self.cells, (line, float("inf"))) - 1
        if index >= 0:
            start, cell, count = self.cells[index]
            if start <= line < start + count:
                return cell, line - start + 1
        return None


def read_notebook(text: str, name: str = "notebook") -> dict:
    """Parse a notebook's JSON: a dict whose ``cells`` is a list (nbformat 4, or a bare
    ``{"cells": [...]}`` written by a tool).

    Only the JSON parser reads it: nothing is validated against nbformat's schema,
    converted or copied, and :func:`convert` picks out what grading uses (each code
    cell's source and the two known tags) defensively. So metadata of any shape or
    size costs its parsing (bounded by the loader's cap on a notebook's size) and
    nothing more, and a cell may hold anything besides its code.

    Raises
    ------
    NotebookError
        Naming ``name`` and saying what is wrong and how to mend it.
    """
    import json

    try:
        data = json.loads(text)
    except RecursionError:  # nested deeper than the parser goes
        raise _unreadable(name, "nested too deeply") from None
    except ValueError:
        raise _unreadable(name, "not valid JSON") from None
    if not isinstance(data, dict) or not isinstance(data.get("cells"), list):
        raise _unreadable(name, "no list of cells")
    for number, cell in enumerate(data["cells"], 1):
        if isinstance(cell, dict) and cell.get("cell_type") == "code" and not _is_text(cell.get("source", "")):
            raise _unreadable(name, f"the code of cell {number} is not text")
    return data


def _unreadable(name: str, reason: str) -> NotebookError:
    return NotebookError(f"{name} is not a readable notebook ({reason}); open it in Jupyter and save it "
                         "again, or hand in the code as a .py file")


def _mapping(value) -> dict:
    """``value`` if it is a dict, else an empty one (a hand-edited notebook may hold anything)."""
    return value if isinstance(value, dict) else {}


def _text(source) -> str:
    """A code cell's source (text, see :func:`read_notebook`) as one string."""
    return source if isinstance(source, str) else "".join(source)


def _known_tags(tags) -> set[str]:
    """The tags grading knows of (:data:`SKIP_TAG`, :data:`GRADE_TAG`) among a cell's ``tags``,
    which count only as a list of strings."""
    if not isinstance(tags, list):
        return set()
    return {tag for tag in tags if isinstance(tag, str) and tag in (SKIP_TAG, GRADE_TAG)}


def _is_text(source) -> bool:
    """A cell's source as nbformat writes it: a string, or a list of lines."""
    return isinstance(source, str) or (isinstance(source, list) and all(isinstance(s, str) for s in source))


MAX_CODE_LINES = 100_000   # a lab's notebook holds a few thousand
MAX_CODE_CELLS = 10_000    # and a few hundred cells


def convert(text: str, name: str = "notebook", definitions_only: bool = True,
            importable: Callable[[str], bool] | None = None) -> ConvertedNotebook:
    """The code cells of a notebook as one module (see the module docstring for the rules).

    Linear in the notebook: the code is parsed (one cell at a time) only within the
    grader's bounds on parsing (:data:`autograder.loading.parsing.MAX_PARSE_CHARS`,
    :data:`~autograder.loading.parsing.MAX_PARSE_STATEMENTS`, counted over all cells);
    beyond them every cell but those tagged skip-grading is taken whole, unread, and
    :attr:`ConvertedNotebook.whole` (and the note) says so.

    Parameters
    ----------
    text : str
        The notebook file's content (JSON).
    name : str
        The file name, for error messages.
    definitions_only : bool
        Take only what running the notebook defines from untagged cells (the
        default); False takes every code cell whole.
    importable : callable, optional
        ``importable("seaborn")``: whether an import can succeed where grading runs
        (default :func:`autograder.loading.definitions.available_at_grading`).

    Raises
    ------
    NotebookError
        Not a notebook (:func:`read_notebook`), or more than :data:`MAX_CODE_LINES` lines
        or :data:`MAX_CODE_CELLS` code cells of code.
    """
    notebook = read_notebook(text, name)
    lines: list[str] = []
    converted = ConvertedNotebook("")
    settings = _mapping(_mapping(notebook.get("metadata")).get("autograder"))
    if settings.get("cell_label") == "input":  # compared, never used: the words are ours
        converted.cell_label = "input"
    raw: list[tuple[int, list[str], str]] = []   # (number, lines as written, mode)
    for number, cell in enumerate(notebook["cells"], 1):
        if not isinstance(cell, dict) or cell.get("cell_type") != "code":
            continue
        if len(raw) >= MAX_CODE_CELLS:
            raise NotebookError(f"{name} holds more than {MAX_CODE_CELLS:,} code cells, more than grading "
                                "reads of a notebook: hand in the lab module as a .py file")
        source = _text(cell.get("source", ""))
        tags = _known_tags(_mapping(cell.get("metadata")).get("tags"))
        mode = "skip" if SKIP_TAG in tags else "keep" if GRADE_TAG in tags or not definitions_only else "analyse"
        raw.append((number, source.splitlines(), mode))
    if sum(len(cell_lines) for _, cell_lines, _ in raw) > MAX_CODE_LINES:  # the analysis is linear, ~40 us a line
        raise NotebookError(f"{name} holds more than {MAX_CODE_LINES:,} lines of code, more than grading "
                            "reads of a notebook: hand in the lab module as a .py file")
    too_large = _beyond_parsing(raw)
    if too_large:  # read nothing: each cell whole (tagged skip-grading: left out), the import reports errors
        converted.whole = (f"holds {too_large}, more code than grading reads statement by statement: every "
                           f"cell was graded whole, demo code included; tag a cell '{SKIP_TAG}' to leave it out")
    code = [CellCode(number, _without_magics(cell_lines, read_blocks=not too_large),
                     "keep" if too_large and mode == "analyse" else mode) for number, cell_lines, mode in raw]
    selection = taken_whole(code) if too_large else analyse(code, importable)
    guarded: list[str] = []  # the module's lines again, lines of kept values guarded
    for cell in code:
        cell_lines, keep = selection.lines[cell.number], selection.kept[cell.number]
        lines.append(f"{HEADER}{cell.number}")
        converted.cells.append((len(lines) + 1, cell.number, len(cell_lines)))
        guarded.append(lines[-1])
        for index, (text_line, kept) in enumerate(zip(cell_lines, keep)):
            lines.append(text_line if kept or not text_line.strip() else LEFT_OUT + text_line)
            guarded.append(GUARD + text_line if index in selection.guarded[cell.number] else lines[-1])
        dropped = [index for index, (line, kept) in enumerate(zip(cell_lines, keep)) if not kept and line.strip()
                   and not line.lstrip().startswith("#")]
        if dropped:
            converted.left_out.append(f"{converted.label(cell.number)}: {cell_lines[dropped[0]].strip()[:60]}"
                                      + (f" (+{len(dropped) - 1} lines)" if len(dropped) > 1 else ""))
        lines.append("")
        guarded.append("")
    converted.omissions = selection.omissions + _magics_left_out(raw)
    converted.source = "\n".join(lines) + "\n"
    converted.guarded_source = "\n".join(guarded) + "\n"
    return converted


def _magics_left_out(cells: list[tuple[int, list[str], str]]) -> list[Omission]:
    """The IPython syntax commented out of the cells read (not those tagged skip-grading), as the student wrote it:
    a line magic or shell command each (``!pip install seaborn`` installs nothing where grading runs), a cell magic
    that makes its cell other than Python once, by its first line."""
    left_out = []
    for number, cell_lines, mode in cells:
        if mode == "skip":
            continue
        first = next(((k, line.strip()) for k, line in enumerate(cell_lines) if line.strip()), None)
        if first and first[1].startswith("%%") and (first[1][2:].split() or [""])[0] not in _PYTHON_CELL_MAGICS:
            left_out.append(Omission(number, first[0] + 1, first[1], "IPython syntax: the whole cell is commented out"))
            continue
        left_out += [Omission(number, k + 1, line.strip(), "IPython syntax: commented out")
                     for k, line in enumerate(cell_lines) if is_ipython_line(line)][:20]
    return left_out


def _beyond_parsing(cells: list[tuple[int, list[str], str]]) -> str:
    """What of the cells to be read is beyond the grader's bounds on parsing, in words
    (``"more than 200,000 characters of code"``), or ``""``. Counted over every cell read
    (cells tagged skip-grading are not), in one pass over the lines."""
    chars = statements = 0
    for _, cell_lines, mode in cells:
        if mode == "skip":
            continue
        statements += len(cell_lines) + 1 + sum(line.count(";") for line in cell_lines)
        chars += len(cell_lines) + sum(len(line) for line in cell_lines)
    if chars > MAX_PARSE_CHARS:
        return f"more than {MAX_PARSE_CHARS:,} characters of code"
    if statements > MAX_PARSE_STATEMENTS:
        return f"more than {MAX_PARSE_STATEMENTS:,} statements (lines and ';')"
    return ""


def is_ipython_line(line: str) -> bool:
    """Whether ``line`` is IPython syntax, not Python: ``%magic``, ``!shell``, ``?help`` (after
    any indentation), ``x = !ls`` / ``x, y = %magic`` (names, dots, commas and spaces, then
    ``=``), or help asked at the line's end (``obj?``, ``np.array??``: a name, ``)`` or ``]``
    just before one or two ``?``, no ``#`` or quote before it).

    Scanned with ``str`` methods in one pass (no regular expression, which backtracked on
    long lines of spaces: seconds for a 300 KB line).
    """
    code = line.lstrip()
    if code[:1] in ("%", "!", "?"):
        return True
    equals = line.find("=")   # names cannot hold one: the first is the assignment's
    if equals > 0 and line[equals + 1:].lstrip()[:1] in ("%", "!"):
        names = equals   # the names before it: a run of word characters, dots, commas and spaces...
        while names > 0 and (line[names - 1].isalnum() or line[names - 1] in "_., "):
            names -= 1
        if names < equals and not line[:names].strip():   # ... after nothing but indentation
            return True
    end = line.rstrip()
    marks = len(end) - len(end.rstrip("?"))
    if marks not in (1, 2) or len(end) == marks:
        return False
    before = end[-marks - 1]
    if not (before.isalnum() or before in "_)]"):
        return False
    head = end[:-marks - 1]
    return "#" not in head and "'" not in head and '"' not in head


def _without_magics(lines: list[str], read_blocks: bool = True) -> list[str]:
    """A cell's IPython syntax commented out (see the module docstring); an indented line
    of it becomes ``pass`` (and the comment), so its block stays a block (when
    ``read_blocks``: it takes parsing the cell)."""
    first = next((line.strip() for line in lines if line.strip()), "")
    if first.startswith("%%") and (first[2:].split() or [""])[0] not in _PYTHON_CELL_MAGICS:
        return [("# " + line) if line.strip() else line for line in lines]  # %%bash, %%writefile...
    commented, passed = [], []
    for line in lines:
        code = line.lstrip()
        magic = is_ipython_line(line)
        commented.append("# " + line if magic else line)
        passed.append(f"{line[:len(line) - len(code)]}pass  # {code}" if magic and code != line else commented[-1])
    if passed == commented or not read_blocks:
        return commented
    try:  # `pass` where a magic was the body of a block; else (an indented cell) a comment
        parse("\n".join(passed))
    except (SyntaxError, ValueError, RecursionError, MemoryError):  # TooLarge is a ValueError
        return commented
    return passed


def point_into_notebook(text: str, module: str, notebook_name: str, converted: ConvertedNotebook) -> str:
    """Rewrite ``module.py, line N`` and tracebacks' ``File "module.py", line N`` in ``text``
    as ``notebook.ipynb, cell C, line L``; other mentions of ``module.py`` name the notebook."""
    if not text:
        return text
    filename = re.escape(module + ".py")

    def spot(line: str) -> str:
        found = converted.where(int(line))
        return f"{converted.label(found[0])}, line {found[1]}" if found else f"line {line}"

    # A line number has at most 9 digits (longer runs are text the student wrote, left as it is).
    text = re.sub(rf'File "{filename}", line (\d{{1,9}})(?!\d)',
                  lambda m: f'File "{notebook_name}", {spot(m.group(1))}', text)
    text = re.sub(rf"(?<![\w/.]){filename}, line (\d{{1,9}})(?!\d)",
                  lambda m: f"{notebook_name}, {spot(m.group(1))}", text)
    text = re.sub(rf"(?<![\w/.\"]){filename}", lambda m: notebook_name, text)  # a name, never a template
    first, newline, rest = text.partition("\n")
    return _why_not_defined(first, converted) + newline + rest


_NOT_DEFINED = re.compile(r"name '([A-Za-z_]\w*)' is not defined")
_ASSIGNED = re.compile(r"\s*([A-Za-z_]\w*(?:\s*,\s*[A-Za-z_]\w*)*)\s*(?::[^=]*)?=(?!=)")


def _why_not_defined(line: str, converted: ConvertedNotebook) -> str:
    """``line`` (a message's first line) with, after its first "name 'H' is not defined",
    the cell that would have defined ``H`` when that is a kept statement grading skipped
    because it raised (it is guarded, see :data:`GUARD`): the NameError is its consequence."""
    found = _NOT_DEFINED.search(line)
    if not found:
        return line
    name = found.group(1)
    for index, (plain, guarded) in enumerate(zip(converted.source.splitlines(),
                                                 converted.guarded_source.splitlines())):
        assigned = _ASSIGNED.match(plain) if guarded.startswith(GUARD) else None
        if assigned and name in re.split(r"\s*,\s*", assigned.group(1)):
            where = converted.where(index + 1)
            cell = converted.label(where[0]) if where else "a cell"
            why = (f" (`{name}` is not defined because {cell} raised when run: `{one_line(plain.strip(), 60)}`; "
                   "grading skips a statement that raises, as Jupyter goes on after a failing cell: run that "
                   "cell to see its error)")
            return line[:found.end()] + why + line[found.end():]
    return line
