"""The terminal report: a table of per-exercise scores, then what to fix, then tips.

Every string that may hold a submission's words goes through
:func:`~autograder.loading.text.printable` first, so nothing it prints can move the
cursor, clear the screen or redraw the table.
"""

from __future__ import annotations

import re

from rich.console import Console
from rich.table import Table
from rich.text import Text

from ..engine.results import ERROR, NOT_IMPLEMENTED, NOT_STARTED, GradingResult
from ..engine.versions import describe
from ..loading.text import printable


def _score_style(score: float, maximum: float) -> str:
    if maximum and score >= maximum:
        return "bold green"
    return "yellow" if score > 0 else "red"


def render(result: GradingResult, console: Console | None = None, html_path=None,
           details: bool = True, page=None, printed_where: str = "") -> None:
    """Print the score table and, under it, one line per check that lost points.
    ``printed_where``: how to read what the student's code printed, in the terms of where
    this runs, when there is no page (default: the command line's)."""
    console = console or Console()
    caption = "\n".join(filter(None, [   # a line each: rich wraps each to the table's width
        f"student code confined at the {result.confinement} level" if result.confinement else "",
        f"judged with {describe(result.versions)}" if describe(result.versions) else ""]))
    table = Table(title=f"Grading {printable(result.submission)}", title_justify="left", expand=False,
                  caption=caption or None, caption_justify="left")
    table.add_column("exercise", style="bold")
    table.add_column("title")
    table.add_column("score", justify="right")
    table.add_column("checks passed", justify="right")
    for exercise in result.exercises:
        table.add_row(exercise.id, exercise.title,
                      Text(f"{exercise.score:g} / {exercise.max_score:g}",
                           style=_score_style(exercise.score, exercise.max_score)),
                      _checks_passed(exercise, result.hidden_points_withheld))
    table.add_section()
    table.add_row("total", "", Text(f"{result.total:g} / {result.max_total:g}",
                                    style=_score_style(result.total, result.max_total)), "")
    for note in result.notes:  # its first line: the lines after it list what it counts, for the page
        console.print(Text("note: ", style="yellow") + Text(printable((note.splitlines() or [""])[0])))
    if result.confinement_warning:  # never quietly weaker than the machine allows
        console.print(Text("warning: ", style="bold red") + Text(result.confinement_warning, style="bold"))
    console.print(table)

    for exercise in result.exercises:
        for rule in exercise.rules:
            console.print(Text(f"rule {exercise.id}: ", style="bold yellow") + Text(rule))
    if details:
        _print_problems(result, console)
        _print_advice(result, console)
    printed = printed_output_line(result, page or html_path, printed_where)
    if printed:
        console.print(Text(printed, style="magenta"))
    if not result.hidden_included:
        from ..engine.registry import hidden_checks_installed

        # (the instructor's copy, with --public-only: the hidden checks are there, and were left out)
        console.print("[dim]Hidden checks were not run (--public-only).[/dim]" if hidden_checks_installed() else
                      "[dim]Hidden checks are not part of this copy; your instructor runs them.[/dim]")
    if result.hidden_points_withheld:
        console.print("[dim]Hidden checks show only whether they passed; their points are not in these "
                      "scores until your instructor releases them.[/dim]")
    if html_path:
        render_written(console, [("details and pictures", html_path)])


def _checks_passed(exercise, hidden_apart: bool) -> str:
    """The table's "checks passed" cell: passed / graded (advice is not a check to pass); where the score leaves the
    hidden checks' points out (a students' view before release), the hidden checks counted apart, as the score is."""
    graded = [c for c in exercise.checks if _graded(c)]
    hidden = [c for c in graded if hidden_apart and c.hidden]
    shown = [c for c in graded if not (hidden_apart and c.hidden)]
    cell = f"{sum(c.passed for c in shown)} / {len(shown)}"
    return cell + (f" (hidden: {sum(c.passed for c in hidden)} / {len(hidden)})" if hidden else "")


def printed_output_line(result: GradingResult, page=None, elsewhere: str = "") -> str:
    """One line saying that the student's code printed, how much, and where to read it: on
    ``page``, else ``elsewhere`` (how, where this runs), else the command line's way."""
    checks = [(e, c) for e in result.exercises for c in e.checks if c.output]
    if not checks:
        return ""
    size = sum(len(c.output) for _, c in checks)
    amount = f"{size / 1024:.1f} KB" if size >= 1024 else f"{size} characters"
    exercises = list(dict.fromkeys(e.id for e, _ in checks))
    where = (f"read it in {page} under \"what your code printed\"" if page
             else elsewhere or "write the feedback page (drop --no-html) to read it")
    listed = f"{', '.join(exercises[:6])}{' ...' if len(exercises) > 6 else ''}"
    if all(_warnings_only(c.output) for _, c in checks):
        # (NumPy's "divide by zero encountered", written by Python's warnings, is no print of the student's)
        return (f"Your code raised warnings in {len(checks)} check{'s' * (len(checks) != 1)} ({amount} kept) of "
                f"{listed}; {where.replace('read it', 'read them')}. "
                "A warning costs no points, but it often shows where a value went wrong (a division by zero, "
                "an overflow).")
    return (f"Your code printed output in {len(checks)} check{'s' * (len(checks) != 1)} ({amount} kept, at most 4 KB "
            "per call) of"
            f" {listed}; {where}. Printing slows grading: remove the prints you no longer need.")


# A warning as Python's warnings module writes it: "file.py:12: RuntimeWarning: ..." and the line of code after.
_WARNING = re.compile(r"^.{0,400}?:\d+: \w*Warning: .{0,2000}$")


def _warnings_only(output: str) -> bool:
    """Whether ``output`` is only warnings written by Python's warnings module (each with its line of code)."""
    lines = [line for line in output.splitlines() if line.strip()]
    if not lines:
        return False
    expected_code = False
    for line in lines:
        if _WARNING.match(line):
            expected_code = True
        elif expected_code and line.startswith(" "):
            expected_code = False
        else:
            return False
    return True


def render_written(console: Console, written) -> None:
    """One line per report file written: ``(what, path)`` pairs."""
    for what, path in written:
        console.print(Text(f"{what[0].upper()}{what[1:]}: ") + Text(str(path), style="bold"),
                      soft_wrap=True)  # a path stays whole, to copy and paste


def _graded(check) -> bool:
    """A check to pass (not advice): one with points, or a hidden one whose points are withheld."""
    return check.max_score > 0 or check.redacted


def _module_messages(result: GradingResult, console: Console) -> None:
    """A message that holds for every check of a module (not found, does not import) is
    printed once per lab, naming the exercises it costs."""
    grouped: dict[tuple[str, str], list[str]] = {}
    for exercise in result.exercises:
        if exercise.message and exercise.message != NOT_STARTED and exercise.score < exercise.max_score:
            lab, key = exercise.id.split(".")
            grouped.setdefault((lab, exercise.message), []).append(key)
    for (lab, message), keys in grouped.items():
        first, *rest = message.splitlines()
        console.print(Text(f"✗ {lab} {', '.join(keys)}: ", style="bold") + Text(first))
        if rest:
            console.print(Text("    " + "\n    ".join(rest), style="dim"))


def _print_problems(result: GradingResult, console: Console) -> None:
    shown_tracebacks = set()
    not_started: dict[str, list[str]] = {}  # lab -> exercises still stubs, said once per lab
    for exercise in result.exercises:
        if exercise.message == NOT_STARTED:
            lab, key = exercise.id.split(".")
            not_started.setdefault(lab, []).append(key)
    for lab, keys in not_started.items():
        console.print(Text(f"· {lab} {', '.join(keys)}: ", style="bold") + Text(NOT_STARTED))
    for exercise in result.exercises:  # functions not written at all (a notebook): one line each
        if exercise.not_started and exercise.message != NOT_STARTED:
            console.print(Text(f"· {exercise.id}: ", style="bold") + Text(exercise.not_started))
    _module_messages(result, console)
    for exercise in result.exercises:
        if exercise.message or exercise.not_started:  # said once per module or exercise, above
            continue
        for check in exercise.checks:
            if check.passed or not _graded(check):  # advice is printed apart, as tips
                continue
            icon = {NOT_IMPLEMENTED: "·", ERROR: "!"}.get(check.status, "✗")
            first, *rest = printable(check.message or check.status).splitlines() or [""]
            line = Text(f"{icon} {exercise.id} ", style="bold") + Text(printable(check.name), style="italic")
            points = f" ({check.score:g}/{check.max_score:g})" if check.max_score else ""
            line += Text(f"{points}: {first}")
            console.print(line)
            for extra in rest[:6]:
                console.print(Text(f"    {extra}", style="dim"))
            if check.hint:
                console.print(Text(f"    hint: {printable(check.hint)}", style="cyan"))
            if check.traceback and check.traceback in shown_tracebacks:
                console.print(Text("    (same traceback as above)", style="dim"))
            elif check.traceback:
                shown_tracebacks.add(check.traceback)
                console.print(Text("    " + printable(check.traceback).replace("\n", "\n    "), style="dim"))


def _print_advice(result: GradingResult, console: Console) -> None:
    """Tips (0 points, never failures), for every exercise whatever its score."""
    for exercise in result.exercises:
        for check in exercise.checks:
            if not check.advice:
                continue
            first, *rest = printable(check.message).splitlines() or [""]
            line = Text(f"tip {exercise.id} ", style="bold blue") + Text(printable(check.name), style="italic")
            console.print(line + Text(f" (no points): {first}"))
            for extra in rest[:6]:
                console.print(Text(f"    {extra}", style="dim"))
            if check.hint:
                console.print(Text(f"    hint: {printable(check.hint)}", style="cyan"))
