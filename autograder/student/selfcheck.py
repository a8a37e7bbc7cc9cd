"""``check("lab07.ex2")``: grade your current code from inside a notebook or a Python shell.

In a Jupyter notebook (classic, Lab, VS Code, Colab: any IPython kernel)::

    from autograder import check
    check("lab07.ex2")

grades the code *as the kernel has it now*: the cells you have run, in the order
you ran them (IPython's input history), taken as a notebook is at grading
(definitions only; see :mod:`autograder.loading.notebooks`), so an unsaved notebook is
checked as it stands and a demo cell never runs twice. Cells that did not parse
are skipped (they defined nothing). The result shows inline: score, and every
check that lost points with its message, hint and pictures.

Elsewhere (a plain Python shell or a script) it grades the lab's module file: in
the current folder, or in ``assignments/`` below it; and shows the result as
text: a script's ``check()`` prints it, a shell shows what ``check()`` returns (as for
any value), so it is never shown twice. Advice in the report is given in the terms of
where it runs (``report.printed()``, not a command-line flag). Either way, ``check(..., notebook="lab07_transformations.ipynb")`` or
``check(..., submission="path/to/folder")`` names exactly what to grade.

The code runs in the same sandbox as ``python grade.py``, with the same checks,
so the score is the one ``grade.py`` gives for the same code.
"""

from __future__ import annotations

import io
import shutil
import tempfile
from pathlib import Path

import nbformat
import nbformat.v4

from ..engine.registry import select
from ..engine.results import GradingResult


class CheckReport:
    """What :func:`check` returns: shown as HTML in a notebook, as text in a shell."""

    def __init__(self, result: GradingResult, source: str):
        self.result = result
        self.source = source  # what was graded, in words

    @property
    def score(self) -> float:
        return self.result.total

    @property
    def max_score(self) -> float:
        return self.result.max_total

    def _repr_html_(self) -> str:
        from ..reports.html import render_selfcheck

        return render_selfcheck(self.result, self.source)

    def printed(self) -> str:
        """What the student's code printed, check by check (``""`` when it printed nothing):
        what ``grade.py`` shows on the feedback page under "what your code printed"."""
        return "\n\n".join(f"{exercise.id} {check.name}:\n{check.output.rstrip()}"
                             for exercise in self.result.exercises for check in exercise.checks if check.output)

    def __str__(self) -> str:
        from rich.console import Console

        from ..reports import terminal

        buffer = io.StringIO()
        console = Console(file=buffer, width=100, color_system=None, force_terminal=False, force_jupyter=False)
        terminal.render(self.result, console, printed_where="print(report.printed()) shows it, where "
                                                            "report is what check() returned")
        return buffer.getvalue().rstrip()

    __repr__ = __str__


def check(*selectors: str, notebook=None, submission=None, public_only: bool = False,
          validate: bool = False):
    """Grade ``selectors`` (``"lab07.ex2"``, ``"lab07"``; everything when none) now.

    Parameters
    ----------
    notebook : path, optional
        Grade this saved notebook (definitions only, as at grading).
    submission : path, optional
        Grade this folder, ``.py``, ``.zip`` or notebook, as ``grade.py --submission`` does.
    public_only : bool
        Skip hidden checks (a student's copy has none anyway).
    validate : bool
        Instead of grading, say what would lose points for reasons other than the
        algorithm (names, imports, cells left out, signatures, dtypes): returns a
        :class:`~autograder.student.validate.Validation` (see ``autograder validate``).

    Returns
    -------
    CheckReport
        ``.score``, ``.max_score``, ``.result`` (the results as students see them: hidden
        checks as verdicts only, see :meth:`GradingResult.for_students`); displays itself.
    """
    from ..engine.runner import grade

    exercises = select(selectors)
    modules = sorted({ex.lab.module for ex in exercises})
    path, source, temporary = _what_to_grade(modules, notebook, submission)
    if validate:
        from .validate import validate as validated

        try:
            report = validated(path, list(selectors))
        finally:
            if temporary:
                shutil.rmtree(temporary, ignore_errors=True)
        report.submission = source
        return _shown(report)
    try:
        # A failing property says how to meet its input again: this same call.
        named = "" if notebook is None and submission is None else \
            f", {'notebook' if notebook is not None else 'submission'}={str(path)!r}"
        result = grade(path, list(selectors), pictures="failed", include_hidden=not public_only,
                       rerun=('check("', f'"{named})'))
    finally:
        if temporary:
            shutil.rmtree(temporary, ignore_errors=True)
    result = result.for_students()
    result.submission = source
    return _shown(CheckReport(result, source))


def _shown(report):
    """``report``, printed first as text when nothing else would show it: in a script. A
    notebook or an IPython shell displays the value a cell ends with, and Python's
    interactive shell the value of an expression (``sys.ps1`` is set there)."""
    import sys

    if _kernel_history() is None and not hasattr(sys, "ps1"):
        print(report, flush=True)
    return report


def _what_to_grade(modules: list[str], notebook, submission):
    """``(path, description, temporary folder or None)`` of the code to grade."""
    if notebook is not None or submission is not None:
        path = Path(notebook if notebook is not None else submission).expanduser()
        return path, path.name, None
    history = _kernel_history()
    if history is not None:
        folder = Path(tempfile.mkdtemp(prefix="selfcheck-"))
        for module in modules:
            nbformat.write(_history_notebook(history), folder / f"{module}.ipynb")
        return folder, "the code this notebook's kernel has run", folder
    for folder in (Path.cwd(), Path.cwd() / "assignments"):
        if any((folder / f"{module}{suffix}").exists() for module in modules for suffix in (".py", ".ipynb")):
            return folder, str(folder), None
    raise FileNotFoundError(
        f"no {' or '.join(m + '.py' for m in modules)} in {Path.cwd()} or its assignments/ folder; "
        "name what to grade: check(..., submission='path/to/folder') or check(..., notebook='lab.ipynb')")


def _history_notebook(history: list[str]):
    """The kernel's inputs as a notebook whose cell N is ``In [N]`` (messages say so). An
    input that did not parse defined nothing in the kernel, so it is left out (an empty
    cell keeps the numbering): the student has usually run the mended cell since."""
    from ..loading.parsing import parse

    cells = []
    for source in history:
        try:
            parse("\n".join(("# " + line) if line.lstrip().startswith(("%", "!")) else line
                               for line in source.splitlines()), max_chars=None, max_statements=None)
        except SyntaxError:
            source = ""
        cells.append(nbformat.v4.new_code_cell(source))
    return nbformat.v4.new_notebook(cells=cells, metadata={"autograder": {"cell_label": "input"}})


def _kernel_history() -> list[str] | None:
    """The cells an IPython kernel has run, in order, as the student wrote them (``%matplotlib
    inline``, not IPython's ``get_ipython().run_line_magic(...)`` that ``In`` holds); None
    outside IPython."""
    try:
        from IPython import get_ipython
    except ImportError:
        return None
    shell = get_ipython()
    if shell is None:
        return None
    history = shell.user_ns.get("In")
    if not isinstance(history, list):
        return None
    raw = getattr(getattr(shell, "history_manager", None), "input_hist_raw", None)
    if isinstance(raw, list) and len(raw) == len(history):  # the same cells, untransformed
        history = raw
    return [cell for cell in history[1:] if isinstance(cell, str)]
