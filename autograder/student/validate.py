"""``autograder validate PATH [LAB...]``: what would lose points for reasons other than the algorithm.

Like nbgrader's validate, before hand-in: the submission is read as grading reads
it, each module imported in a clean sandboxed worker, and the public checks of the
selected exercises run (property checks left out: their inputs add nothing here).
What it says is about the form of the work, never about whether an answer is right:

- files: modules missing or misnamed (with the rename to make), files refused;
- notebooks: statements left out at grading and why, functions reading a name
  that is left out (they fail when called), a kept value that raises when run
  (grading skips it);
- modules: imports that fail, demo code a ``.py`` runs when imported;
- functions: missing or misnamed (the nearest name suggested), parameters that
  differ from the lab's declared signature (names the grader passes by keyword,
  defaults it relies on, parameters it never passes);
- calls: a function that raises, hangs, crashes or calls what it may not; a value
  of the wrong type, shape or dtype (an integer matrix where the skeleton
  documents a float array), with the sentence for a beginner's OpenCV mistake.

Exit status (``autograder validate``): 0 when nothing was found, 1 when problems
were, 2 for a usage error.
"""

from __future__ import annotations

import ast
import difflib
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..engine.registry import Exercise, discover, select
from ..loading.definitions import CellCode, analyse
from ..loading.notebooks import point_into_notebook
from ..loading.parsing import parse, walk
from ..loading.submission import load_submission, plain_name
from ..loading.text import one_line
from ..sandbox.supervisor import Limits

PROBLEM, NOTE, GOOD = "problem", "note", "ok"
SKELETONS = Path(__file__).resolve().parents[2] / "assignments"
_PLAIN_PREFIX = "_validate_plain_"   # the notebook as written (unguarded), imported to find what raises


@dataclass
class Finding:
    level: str      # PROBLEM (costs points), NOTE (worth knowing), GOOD (checked and fine)
    subject: str    # "lab07_transformations.py", "translate()"
    text: str


@dataclass
class Validation:
    """What :func:`validate` found, in the order it looked. Displays itself (text, or HTML in a notebook)."""

    submission: str
    selected: list[str]
    findings: list[Finding] = field(default_factory=list)

    @property
    def problems(self) -> list[Finding]:
        return [f for f in self.findings if f.level == PROBLEM]

    @property
    def ok(self) -> bool:
        return not self.problems

    def add(self, level: str, subject: str, text: str) -> None:
        finding = Finding(level, subject, one_line(text, 600))
        # (the same exception met again in another check, told with the input it was raised on, adds nothing)
        if not any(f.level == level and f.subject == subject and finding.text.startswith(f.text)
                   for f in self.findings):
            self.findings.append(finding)

    def __str__(self) -> str:
        marks = {PROBLEM: "✗", NOTE: "·", GOOD: "✓"}
        lines = [f"Validating {one_line(self.submission, 80)} for {', '.join(self.selected)}, as grading reads it"]
        lines += [f"  {marks[f.level]} {f.subject}: {f.text}" for f in self.findings]
        count = len(self.problems)
        lines.append("No problems found: what is graded now is your algorithm." if not count else
                     f"{count} problem{'s' * (count != 1)} found: each would cost points for a reason other "
                     "than your algorithm.")
        return "\n".join(lines)

    __repr__ = __str__

    def _repr_html_(self) -> str:
        from html import escape

        colours = {PROBLEM: "#b00020", NOTE: "#555", GOOD: "#1b7f3b"}
        rows = "".join(f'<li style="color:{colours[f.level]}"><b>{escape(f.subject)}</b>: {escape(f.text)}</li>'
                       for f in self.findings)
        head, *_, last = str(self).splitlines()
        return f"<div><p>{escape(head)}</p><ul>{rows}</ul><p><b>{escape(last)}</b></p></div>"


def validate(path, selectors=(), limits: Limits | None = None) -> Validation:
    """Validate the submission at ``path`` for ``selectors`` (``lab07``, ``lab07.ex2``; all when none).

    Raises
    ------
    SelectionError, SubmissionError
        For a selector that names nothing, or a path that is not a submission.
    """
    exercises = select(selectors, include_hidden=False)
    labs = sorted({e.lab.key for e in exercises})
    modules = sorted({e.lab.module for e in exercises})
    every_module = {lab.module for lab in discover().values()}
    with load_submission(path, modules, every_module=every_module) as submission:
        report = Validation(submission.name, list(selectors) or labs)
        for name, reason in submission.refused.items():
            report.add(PROBLEM, name, f"not read: {reason}")
        readable = []
        for module in modules:
            subject = handed_in(submission, module)
            for file in submission.not_graded.get(module, []):
                report.add(NOTE, file.file, f"not graded: {file.sentence()}")
            if module in submission.problems:
                report.add(PROBLEM, subject, submission.problems[module])
                continue
            if module in submission.renamed:
                renamed = submission.renamed[module]
                suffix = Path(renamed).suffix
                if plain_name(Path(renamed).stem) == module:   # (graded whatever else is selected: a note)
                    report.add(NOTE, subject, f"{renamed} is graded as {module}.py, the name the grader looks for; "
                                              f"rename it {module}{suffix} to be sure")
                else:   # (a lone file of any name: graded only while this lab alone is selected)
                    report.add(PROBLEM, subject, f"{renamed} is graded as {module}.py only while it is the only file "
                                                 f"and this lab the only one graded; rename it {module}{suffix}")
            readable.append(module)
            if module in submission.notebooks:
                source = submission.notebooks[module][1].source  # as written: no guards
                _notebook_findings(report, *submission.notebooks[module])
            else:
                source = (submission.path / f"{module}.py").read_text(encoding="utf-8", errors="replace")
                _demo_code_findings(report, subject, source)
            for exercise in (e for e in exercises if e.lab.module == module):
                _signature_findings(report, exercise, source)
        if readable:
            _run_findings(report, submission, [e for e in exercises if e.lab.module in readable], limits)
    return report


# ------------------------------------------------------------------ notebooks and modules, read
def _notebook_findings(report: Validation, name: str, converted) -> None:
    for omission in converted.omissions:
        for function, needed in omission.users:
            report.add(PROBLEM, f"{function}()", f"reads {needed}, which grading leaves out "
                                                 f"({converted.label(omission.cell)} `{one_line(omission.text, 60)}`: "
                                                 f"{omission.reason}): pass it in as an argument, or compute it "
                                                 "inside the function from constants")
    for line in converted.left_out_lines():  # every one, each once: a grading's note names the first few
        report.add(NOTE, name, f"left out at grading: {line}")


def _demo_code_findings(report: Validation, subject: str, source: str) -> None:
    """A .py runs all its top-level code when grading imports it: demo code there runs too."""
    selection = analyse([CellCode(1, source.splitlines())])
    demo = [o for o in selection.omissions if o.listed and not o.reason.startswith(("needs", "used only"))
            and "not available" not in o.reason]
    if demo:
        shown = ", ".join(f"line {o.line} `{one_line(o.text, 40)}` ({o.reason})" for o in demo[:4])
        report.add(NOTE, subject, f"runs when grading imports it: {shown}; keep demo code under "
                                  "if __name__ == '__main__': so that only definitions run at import")


def _signature_findings(report: Validation, exercise: Exercise, source: str) -> None:
    """The functions of ``exercise`` against the lab's declared signatures, read, not run."""
    try:
        tree = parse(source, max_chars=None, max_statements=None)  # the student's own file, on their machine
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return  # the import reports it, with its line
    bound: dict[str, ast.AST] = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            bound[node.name] = node
        elif isinstance(node, ast.Assign):
            for target in node.targets:
                if isinstance(target, ast.Name):
                    bound[target.id] = node.value
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            bound.update({(a.asname or a.name): node for a in node.names})
        elif isinstance(node, (ast.If, ast.Try, ast.With)):
            bound.update({n.name: n for n in walk(node) if isinstance(n, ast.FunctionDef)})
    for function, declared in exercise.signatures.items():
        subject = f"{function}()"
        if function not in bound:
            names = {n.lower(): n for n in bound if _may_be_callable(bound[n])}  # never a constant (SCALE_INV)
            near = difflib.get_close_matches(function.lower(), names, n=1, cutoff=0.7)
            hint = f" (is {names[near[0]]} meant to be it? the grader looks for this exact name)" if near else ""
            report.add(PROBLEM, subject, f"not defined: def {declared}{hint}")
            continue
        node = bound[function]
        arguments = node.args if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)) else None
        if arguments is None:
            continue  # made by a call or imported: its parameters are known only when it runs
        for problem in _parameter_problems(declared, arguments):
            report.add(PROBLEM, subject, problem)


def _may_be_callable(node: ast.AST) -> bool:
    """Whether what binds a name can make a function: a ``def``, an import, a lambda, a
    call's result (``functools.partial(f)``), a name; not a literal or arithmetic."""
    return isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Import, ast.ImportFrom, ast.Lambda,
                             ast.Call, ast.Name, ast.Attribute))


def _parameter_problems(declared: str, arguments: ast.arguments) -> list[str]:
    """How parameters ``arguments`` differ from the declared signature (``translate(image, tx=100, ty=50)``)."""
    wanted = parse(f"def {declared}: pass", max_chars=None, max_statements=None).body[0].args
    names = [a.arg for a in wanted.posonlyargs + wanted.args]
    wanted_defaults = dict(zip(names[len(names) - len(wanted.defaults):], wanted.defaults))
    theirs = [a.arg for a in arguments.posonlyargs + arguments.args]
    their_defaults = dict(zip(theirs[len(theirs) - len(arguments.defaults):], arguments.defaults))
    keywords_too = {a.arg for a in arguments.kwonlyargs} | set(theirs)
    problems = []
    if len(theirs) < len(names) and arguments.vararg is None:
        problems.append(f"takes {len(theirs)} argument{'s' * (len(theirs) != 1)} ({', '.join(theirs) or 'none'}); "
                        f"the grader calls it as {declared}")
    # Parameters with a default are the ones passed by name (rotation_matrix(30, center=c)).
    renamed = [n for n in wanted_defaults if n not in keywords_too] if arguments.kwarg is None else []
    if renamed and len(theirs) >= len(names):
        problems.append(f"the grader passes {', '.join(n + '=' for n in renamed)} by name: name the parameters "
                        f"as the lab does, {declared} (yours: {', '.join(theirs)})")
    for name, default in wanted_defaults.items():
        if name in theirs and name not in their_defaults:
            problems.append(f"{name} has no default; the lab says {name}={ast.unparse(default)} "
                            "(the grader calls it without it)")
        elif name in their_defaults and ast.unparse(their_defaults[name]) != ast.unparse(default):
            problems.append(f"{name} defaults to {ast.unparse(their_defaults[name])}; the lab says "
                            f"{name}={ast.unparse(default)} (the grader calls it without it)")
    extra = [n for n in theirs[len(names):] if n not in their_defaults]
    extra += [a.arg for a, d in zip(arguments.kwonlyargs, arguments.kw_defaults) if d is None]
    if extra:
        problems.append(f"needs {', '.join(extra)}, which the grader never passes: give "
                        f"{'it a default' if len(extra) == 1 else 'them defaults'}")
    return problems


# ------------------------------------------------------------------ run
class _Skipped(Exception):
    """A property check, left out of validation."""


def handed_in(submission, module: str) -> str:
    """The file the student handed in as ``module``, as they named it: the notebook
    (``lab07_transformations.ipynb``), the file taken under another name, else ``module.py``."""
    if module in submission.notebooks:
        return submission.notebooks[module][0]
    return submission.renamed.get(module) or f"{module}.py"


def _run_findings(report: Validation, submission, exercises: list[Exercise], limits: Limits | None) -> None:
    from ..engine.checks import Fail, StudentFailure, Trial
    from ..engine.runner import _first_sandbox, _import  # the sandbox grading would use; an import as grading reports it

    limits = limits or Limits()
    documented = _documented_dtypes(exercises)
    plain = _write_plain_notebooks(submission)
    with _first_sandbox(submission.path, limits) as sandbox:
        imported = set()
        for module in sorted({e.lab.module for e in exercises}):
            outcome = _import(sandbox, module, submission)
            subject = handed_in(submission, module)
            if outcome.ok:
                imported.add(module)
                report.add(GOOD, subject, "imports cleanly in a fresh sandboxed worker")
                if module in plain:
                    _raising_value(report, sandbox, submission, module, plain[module])
            else:
                message = outcome.message  # with its file and line
                if module in submission.notebooks:
                    name, converted = submission.notebooks[module]
                    message = point_into_notebook(message, module, name, converted)
                report.add(PROBLEM, subject, f"does not import: {message.strip()}")

        class Recording(Trial):
            """A trial noting each function's first outcome and the form of what it returns."""

            def call(self, function, *args, **kwargs):
                try:
                    value = super().call(function, *args, **kwargs)
                except StudentFailure as failure:
                    failure.function = function  # whose failure it is, for the report
                    raise
                expected = documented.get(function)
                kind = getattr(getattr(value, "dtype", None), "kind", None)
                if expected == "float" and kind in ("i", "u", "b"):
                    report.add(PROBLEM, f"{function}()", f"returned an {value.dtype} array; the lab documents a "
                                                          "float array (OpenCV's warps and most maths need floats): "
                                                          "build it with dtype=float")
                return value

            def for_all(self, *args, **kwargs):
                raise _Skipped

        for exercise in exercises:
            if exercise.lab.module not in imported:
                continue
            sandbox.start_exercise(sandbox.student_seconds + limits.exercise_budget)
            for check in (c for c in exercise.checks if not c.hidden and not c.advice):
                trial = Recording(sandbox, check)
                try:
                    check.func(trial)
                except StudentFailure as failure:
                    _student_failure(report, exercise, failure, submission)
                except Fail as failure:
                    if _about_form(failure.message):
                        report.add(PROBLEM, check.name, failure.message + (f" ({failure.hint})" if failure.hint
                                                                           else ""))
                except Exception:  # noqa: BLE001 - properties skipped, and the grader's own trouble is not the student's
                    continue


def _student_failure(report: Validation, exercise: Exercise, failure, submission) -> None:
    outcome = failure.outcome
    module = exercise.lab.module
    message = failure.message
    if module in submission.notebooks:
        name, converted = submission.notebooks[module]
        message = point_into_notebook(message, module, name, converted)
    called = getattr(failure, "function", None)
    subject = f"{called}()" if called else exercise.id
    message = message.removeprefix(f"{subject} ")  # "translate(): raised ...", not "translate(): translate() raised"
    if outcome.kind == "not_implemented":
        report.add(NOTE, subject, "not implemented yet")
    elif outcome.kind == "missing_function":
        if not any(f.subject == subject and f.text.startswith("not defined") for f in report.problems):
            report.add(PROBLEM, subject, message)
    else:  # the first line: the beginner's sentence when there is one, else the exception
        report.add(PROBLEM, subject, message.splitlines()[0] if message else outcome.kind)


def _about_form(message: str) -> bool:
    """A judged value's form, not its correctness: its type, shape or dtype, or channels."""
    return bool(re.search(r"returned (dtype|an array of shape|shape|None|a \w+;)|expected a numpy array"
                          r"|RGB for BGR|holds integers", message))


def _documented_dtypes(exercises: list[Exercise]) -> dict[str, str]:
    """``{"translation_matrix": "float"}``: what the skeletons' docstrings say each function returns
    ("Returns" and its first line: ``(3, 3) float array``)."""
    documented = {}
    for module in sorted({e.lab.module for e in exercises}):
        try:
            tree = parse((SKELETONS / f"{module}.py").read_text(encoding="utf-8"), max_chars=None, max_statements=None)
        except (OSError, SyntaxError):
            continue  # no skeletons here: nothing to compare with
        for node in tree.body:
            doc = ast.get_docstring(node) if isinstance(node, ast.FunctionDef) else None
            found = re.search(r"Returns\n\s*-+\n\s*(.+)", doc or "")
            if found and re.search(r"\bfloat\b", found.group(1)) and "int" not in found.group(1):
                documented[node.name] = "float"
    return documented


def _write_plain_notebooks(submission) -> dict[str, str]:
    """Each notebook's module as written, without the guards grading adds, beside the graded one."""
    plain = {}
    for module, (_, converted) in submission.notebooks.items():
        if converted.source != converted.guarded_source:
            (submission.path / f"{_PLAIN_PREFIX}{module}.py").write_text(converted.source, encoding="utf-8")
            plain[module] = f"{_PLAIN_PREFIX}{module}"
    return plain


def _raising_value(report: Validation, sandbox, submission, module: str, plain: str) -> None:
    """Name the first kept value of a notebook that raises when run (grading skips it)."""
    outcome = sandbox.import_module(plain)
    if outcome.ok:
        return
    name, converted = submission.notebooks[module]
    frames = re.findall(rf'File "{re.escape(plain)}\.py", line (\d+)', outcome.traceback or "")
    where = converted.where(int(frames[-1])) if frames else None
    spot = f"{converted.label(where[0])}, line {where[1]}" if where else "a cell"
    error = outcome.message.split("failed to import: ", 1)[-1].splitlines()[0]
    report.add(PROBLEM, name, f"{spot} raises {error} when run: grading skips that statement, and "
                              "whatever needs what it defines fails")
