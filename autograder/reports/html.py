"""The feedback page: one self-contained HTML file (pictures embedded, no JavaScript)."""

from __future__ import annotations

import re

from jinja2 import Environment, PackageLoader, select_autoescape
from markupsafe import Markup, escape

from ..results import ADVICE, ERROR, NOT_IMPLEMENTED, PARTIAL, PASSED, GradingResult, write_atomically

_UNSAFE_SVG = re.compile(r"<\s*(script|foreignObject|iframe)|\bon\w+\s*=|javascript:", re.IGNORECASE)


def _safe_svg(svg: str) -> Markup:
    """Inline SVG made by the grader; anything that could run script is shown as text."""
    if svg.lstrip().startswith("<svg") and not _UNSAFE_SVG.search(svg):
        return Markup(svg)
    return escape(svg)


def _grade_class(exercise) -> str:
    if exercise.max_score and exercise.score >= exercise.max_score:
        return "full"
    return "some" if exercise.score > 0 else "none"


_STATUS = {PASSED: ("passed", "✓"), PARTIAL: ("partial", "◐"), NOT_IMPLEMENTED: ("notimpl", "·"),
           ERROR: ("error", "!"), ADVICE: ("advice", "tip")}


def _environment() -> Environment:
    env = Environment(loader=PackageLoader("autograder.reports", "templates"),
                      autoescape=select_autoescape(["html", "j2"]), trim_blocks=True, lstrip_blocks=True)
    env.filters["num"] = lambda x: f"{x:g}"
    env.filters["grade_class"] = _grade_class
    env.filters["status_class"] = lambda c: _STATUS.get(c.status, ("failed", "✗"))[0]
    env.filters["status_icon"] = lambda c: _STATUS.get(c.status, ("failed", "✗"))[1]
    env.filters["safe_svg"] = _safe_svg
    return env


def render(result: GradingResult) -> str:
    """The feedback page as a string."""
    percent = round(100 * result.total / result.max_total) if result.max_total else 0
    return _environment().get_template("feedback.html.j2").render(result=result, percent=percent)


def write(result: GradingResult, path) -> None:
    write_atomically(path, render(result))
