"""The terminal report: a table of per-exercise scores, then what to fix, then tips."""

from __future__ import annotations

from rich.console import Console
from rich.table import Table
from rich.text import Text

from ..results import ERROR, NOT_IMPLEMENTED, GradingResult


def _score_style(score: float, maximum: float) -> str:
    if maximum and score >= maximum:
        return "bold green"
    return "yellow" if score > 0 else "red"


def render(result: GradingResult, console: Console | None = None, html_path=None,
           details: bool = True) -> None:
    """Print the score table and, under it, one line per check that lost points."""
    console = console or Console()
    table = Table(title=f"Grading {result.submission}", title_justify="left", expand=False)
    table.add_column("exercise", style="bold")
    table.add_column("title")
    table.add_column("score", justify="right")
    table.add_column("checks passed", justify="right")
    for exercise in result.exercises:
        graded = [c for c in exercise.checks if c.max_score > 0]  # advice is not a check to pass
        table.add_row(exercise.id, exercise.title,
                      Text(f"{exercise.score:g} / {exercise.max_score:g}",
                           style=_score_style(exercise.score, exercise.max_score)),
                      f"{sum(c.passed for c in graded)} / {len(graded)}")
    table.add_section()
    table.add_row("total", "", Text(f"{result.total:g} / {result.max_total:g}",
                                    style=_score_style(result.total, result.max_total)), "")
    console.print(table)

    for exercise in result.exercises:
        for rule in exercise.rules:
            console.print(Text(f"rule {exercise.id}: ", style="bold yellow") + Text(rule))
    if details:
        _print_problems(result, console)
        _print_advice(result, console)
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
            lines = exercise.message.splitlines()
            console.print(Text(f"✗ {exercise.id}: ", style="bold") + Text(lines[0]))
            if len(lines) > 1:
                console.print(Text("    " + "\n    ".join(lines[1:]), style="dim"))
            continue
        for check in exercise.checks:
            if check.passed or check.max_score == 0:  # advice is printed apart, as tips
                continue
            icon = {NOT_IMPLEMENTED: "·", ERROR: "!"}.get(check.status, "✗")
            first, *rest = (check.message or check.status).splitlines() or [""]
            line = Text(f"{icon} {exercise.id} ", style="bold") + Text(check.name, style="italic")
            line += Text(f" ({check.score:g}/{check.max_score:g}): {first}")
            console.print(line)
            for extra in rest[:6]:
                console.print(Text(f"    {extra}", style="dim"))
            if check.hint:
                console.print(Text(f"    hint: {check.hint}", style="cyan"))
            if check.traceback and check.traceback in shown_tracebacks:
                console.print(Text("    (same traceback as above)", style="dim"))
            elif check.traceback:
                shown_tracebacks.add(check.traceback)
                console.print(Text("    " + check.traceback.replace("\n", "\n    "), style="dim"))


def _print_advice(result: GradingResult, console: Console) -> None:
    """Tips (0 points, never failures), for every exercise whatever its score."""
    for exercise in result.exercises:
        for check in exercise.checks:
            if not check.advice:
                continue
            first, *rest = check.message.splitlines() or [""]
            line = Text(f"tip {exercise.id} ", style="bold blue") + Text(check.name, style="italic")
            console.print(line + Text(f" (no points): {first}"))
            for extra in rest[:6]:
                console.print(Text(f"    {extra}", style="dim"))
            if check.hint:
                console.print(Text(f"    hint: {check.hint}", style="cyan"))
