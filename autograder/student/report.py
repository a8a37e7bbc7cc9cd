"""``python grade.py --report DIR``: the lab report's scaffold, made from the student's own code.

One Markdown file per selected lab, ``DIR/labNN_report.md``, its figures in
``DIR/figures/<figure id>.png``. Per exercise (and per experiment extension, see
:mod:`autograder.figures`): a heading, the figures the student's functions make (or
why one could not be made), the automatic verdict in one line, and the place for
the explanation between two markers, holding :data:`~autograder.loading.report.PLACEHOLDER`
until the student writes there. The format is the one
:func:`autograder.loading.report.read_report` reads back.

Writing again refreshes the figures and verdict lines and keeps every explanation
already written (read with the same reader, so a section whose markers were deleted
keeps its text too). An explanation of a section the scaffold no longer has is kept
at the end, and the previous file is kept as ``labNN_report.previous.md``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..engine.registry import Exercise, select
from ..engine.results import GradingResult, write_atomically
from ..figures import SHEET_PICTURES, FigureOutcome, make_figures, producers_for
from ..loading.report import (BACKUP_SUFFIX, PLACEHOLDER, VERDICT_PREFIX, VERDICT_LINE, exercise_id,
                              explanations_in_markdown)
from ..loading.text import one_line

FIGURES_FOLDER = "figures"
KEPT_HEADING = "## Explanations kept from an earlier version of this report"


def report_name(lab_key: str) -> str:
    return f"{lab_key}_report.md"


@dataclass
class Section:
    """One part of a report: an exercise, or an experiment extension beside its exercise."""

    id: str                    # "lab07.ex1", "lab09.ex3-extension"
    title: str
    figures: list[str] = field(default_factory=list)   # Markdown lines: pictures, or why there is none
    verdict: str = ""          # the whole "Automatic verdict: ..." line


@dataclass
class ReportWritten:
    files: list[Path]                      # the labNN_report.md files written
    figures: list[FigureOutcome]           # this run's figures (made or not, with the reason)
    kept: dict[str, int]                   # report file name -> explanations carried over


def write_report(submission, selectors=(), out_dir=".", result: GradingResult | None = None,
                 limits=None, deadline: float | None = None) -> ReportWritten:
    """Write (or refresh) ``out_dir/labNN_report.md`` and its figures for the selected labs.

    ``result``: this run's grading (the verdict lines); exercises it does not hold keep the
    verdict line the earlier report had. ``limits`` and ``deadline``: the grading's, which
    its figures are held to (see :func:`autograder.figures.make_figures`). Raises ``OSError``
    when ``out_dir`` cannot be written.
    """
    out_dir = Path(out_dir)
    figure_dir = out_dir / FIGURES_FOLDER
    selected = select(selectors)
    outcomes = make_figures(submission, [ex.id for ex in selected], figure_dir, limits, deadline)
    for outcome in outcomes:  # a picture from an earlier run would show code that is gone
        if outcome.path is None:
            (figure_dir / f"{outcome.figure_id}.png").unlink(missing_ok=True)
    made = {o.figure_id: o for o in outcomes}
    graded = {e.id: e for e in result.exercises} if result is not None else {}
    files, kept = [], {}
    labs = {ex.lab.key: ex.lab for ex in selected}  # in the order selected
    for lab in labs.values():
        path = out_dir / report_name(lab.key)
        earlier = path.read_text(encoding="utf-8", errors="replace") if path.is_file() else None
        sections = [section for ex in select([lab.key])
                    for section in _sections(ex, made, graded, figure_dir)]
        text, carried = scaffold(f"{lab.key} report: {lab.title}", sections, earlier, path.name)
        if earlier is not None and earlier != text:
            write_atomically(path.with_name(f"{lab.key}_report{BACKUP_SUFFIX}"), earlier)
        write_atomically(path, text)
        files.append(path)
        kept[path.name] = carried
    return ReportWritten(files, outcomes, kept)


def _sections(exercise: Exercise, made: dict[str, FigureOutcome], graded: dict, figure_dir: Path) -> list[Section]:
    """The exercise's section, then one per experiment extension run with its functions."""
    own = Section(exercise.id, exercise.title, verdict=_verdict(graded.get(exercise.id)))
    sections = [own]
    for producer in producers_for(exercise.id):
        if producer.figure_id == exercise.id:
            target = own
        else:
            title = SHEET_PICTURES.get(producer.figure_id, producer.title)
            target = Section(producer.figure_id, f"Extension: {title}",
                             verdict=f"{VERDICT_PREFIX} none (an experiment to explain; "
                                     f"{exercise.id} grades the functions it runs)")
            sections.append(target)
        target.figures.append(_figure_line(producer.figure_id, made.get(producer.figure_id), figure_dir))
    if not own.figures:
        own.figures.append("_No figure: the lab sheet asks for numbers here (a matrix, coordinates); "
                           "quote the ones your code gives in your explanation._")
    return sections


def _figure_line(figure_id: str, outcome: FigureOutcome | None, figure_dir: Path) -> str:
    picture = f"![{figure_id}]({FIGURES_FOLDER}/{figure_id}.png)"
    if outcome is None:  # not selected in this run: the picture of an earlier run, if there is one
        if (figure_dir / f"{figure_id}.png").is_file():
            return picture
        return f"_No figure yet: run `python grade.py --report DIR {figure_id.split('-')[0]}` to make it._"
    if outcome.path is None:
        return f"_No figure: {one_line(outcome.reason, 300)}_"
    return picture


def _verdict(exercise_result) -> str:
    if exercise_result is None:
        return ""  # the earlier report's line, or "not graded" (see scaffold)
    score, top = exercise_result.score, exercise_result.max_score
    state = "passed" if top and score >= top else ("not passed" if score <= 0 else "partly passed")
    return f"{VERDICT_PREFIX} {score:g} / {top:g} ({state})"


def scaffold(title: str, sections: list[Section], earlier: str | None = None,
             source: str = "report") -> tuple[str, int]:
    """The report's Markdown, with the explanations of ``earlier`` (a previous version of the
    file) in their places; returns it and how many explanations were carried over."""
    written = explanations_in_markdown(earlier, source) if earlier else {}
    old_verdicts = _verdict_lines(earlier) if earlier else {}
    lines = [f"# {one_line(title, 160)}", "",
             "<!-- Write each explanation between its two markers, in Markdown; the figures were made",
             "     by your own functions. Running `python grade.py --report DIR` again refreshes the",
             "     figures and verdict lines and keeps what you wrote. Hand this file in with your code",
             "     and the figures folder. -->", ""]
    carried = 0
    for section in sections:
        verdict = section.verdict or old_verdicts.get(section.id) or f"{VERDICT_PREFIX} not graded in this run"
        explanation = written.pop(section.id, None)
        carried += explanation is not None
        lines += [f"## {section.id}: {one_line(section.title, 120)}", ""]
        for figure in section.figures:
            lines += [figure, ""]
        lines += [verdict, "", *_explanation_block(section.id, explanation.text if explanation else None), ""]
    if written:  # sections this scaffold has no more: nothing a student wrote is dropped
        lines += [KEPT_HEADING, ""]
        for exercise, explanation in written.items():
            lines += [f"### {exercise}", "", *_explanation_block(exercise, explanation.text), ""]
            carried += 1
    return "\n".join(lines).rstrip("\n") + "\n", carried


def _explanation_block(section_id: str, text: str | None) -> list[str]:
    return [f"<!-- explanation {section_id} -->", text if text else PLACEHOLDER, "<!-- end explanation -->"]


def _verdict_lines(text: str) -> dict[str, str]:
    """Each section's verdict line in an earlier report (kept for exercises not graded now)."""
    import re

    verdicts, current = {}, None
    for line in text.splitlines():
        heading = re.match(r"##[ \t]+([^\s:]+)", line)
        if heading:
            current = exercise_id(heading.group(1))
        elif current and VERDICT_LINE.fullmatch(line) and current not in verdicts:
            verdicts[current] = one_line(line, 200)
    return verdicts
