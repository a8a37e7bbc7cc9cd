"""The terminal report: a table of per-exercise scores, then what to fix.

Every string that may hold a submission's words goes through
:func:`~autograder.text.printable` first, so nothing it prints can move the
cursor, clear the screen or redraw the table.
"""

from __future__ import annotations

from rich.console import Console
from rich.table import Table
from rich.text import Text

from ..results import ERROR, NOT_IMPLEMENTED, GradingResult
from ..text import printable


def _score_style(score: float, maximum: float) -> str:
    if maximum and score >= maximum:
        return "bold green"
    return "yellow" if score > 0 else "red"


def render(result: GradingResult, console: Console | None = None, html_path=None,
           details: bool = True) -> None:
    """Print the score table and, under it, one line per check that lost points."""
    console = console or Console()
    table = Table(title=f"Grading {printable(result.submission)}", title_justify="left", expand=False)
    table.add_column("exercise", style="bold")
    table.add_column("title")
    table.add_column("score", justify="right")
    table.add_column("checks passed", justify="right")
    for exercise in result.exercises:
        passed = sum(c.passed for c in exercise.checks)
        table.add_row(exercise.id, exercise.title,
                      Text(f"{exercise.score:g} / {exercise.max_score:g}",
                           style=_score_style(exercise.score, exercise.max_score)),
                      f"{passed} / {len(exercise.checks)}")
    table.add_section()
    table.add_row("total", "", Text(f"{result.total:g} / {result.max_total:g}",
                                    style=_score_style(result.total, result.max_total)), "")
    console.print(table)

    if details:
        _print_problems(result, console)
    if not result.hidden_included:
        console.print("[dim]Hidden checks are not part of this copy; your instructor runs them.[/dim]")
    if html_path:
        console.print(f"Details and pictures: [bold]{html_path}[/bold]")


NOT_STARTED = "not implemented yet"


def _print_problems(result: GradingResult, console: Console) -> None:
    shown_tracebacks = set()
    not_started: dict[str, list[str]] = {}  # lab -> exercises still stubs, said once per lab
    for exercise in result.exercises:
        if exercise.message == NOT_STARTED:
            lab, key = exercise.id.split(".")
            not_started.setdefault(lab, []).append(key)
    for lab, keys in not_started.items():
        console.print(Text(f"· {lab} {', '.join(keys)}: ", style="bold") + Text(NOT_STARTED))
    for exercise in result.exercises:
        if exercise.score >= exercise.max_score or exercise.message == NOT_STARTED:
            continue
        if exercise.message:  # one message says it for every check (missing module, syntax error...)
            lines = printable(exercise.message).splitlines()
            console.print(Text(f"✗ {exercise.id}: ", style="bold") + Text(lines[0]))
            if len(lines) > 1:
                console.print(Text("    " + "\n    ".join(lines[1:]), style="dim"))
            continue
        for check in exercise.checks:
            if check.passed:
                continue
            icon = {NOT_IMPLEMENTED: "·", ERROR: "!"}.get(check.status, "✗")
            first, *rest = printable(check.message or check.status).splitlines() or [""]
            line = Text(f"{icon} {exercise.id} ", style="bold") + Text(printable(check.name), style="italic")
            line += Text(f" ({check.score:g}/{check.max_score:g}): {first}")
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
