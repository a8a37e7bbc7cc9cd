"""Command line: ``autograder grade``, ``autograder batch``, ``autograder list`` (and ``python grade.py``).

Exit status is 0 whenever grading completed, whatever the score; 2 for usage
errors (an unknown selector, a submission path that does not exist, a bad
option value, a report that cannot be written). ``batch`` and ``report`` exit
with 1 when the results folder cannot be read or written (a full disk, a
read-only folder, a damaged gradebook, the folder deleted mid-run): one line
naming the file and what to do; finished gradings are kept. Errors go to stderr.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import shlex
import shutil
import sys
import time
from dataclasses import replace
from pathlib import Path

# The grader's matrices are small: one BLAS thread is as fast, NumPy starts a tenth of a
# second sooner without starting the others, and the cores stay free for the workers and
# the lanes. Set before anything imports NumPy; a value the user set is kept. (Only the
# command line does this: importing the package in a notebook changes nothing.)
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from . import __version__  # noqa: E402
from .loading.submission import SubmissionError  # noqa: E402
from .loading.text import printable  # noqa: E402
from .sandbox import confine  # noqa: E402
from .sandbox.supervisor import Limits, usable_cores  # noqa: E402

USAGE_ERROR = 2
STORAGE_ERROR = 1   # batch/report: RESULTS cannot be read or written (see StorageError)


# Imported when first used: grade.py starts its worker before the grader's heavier imports.
def escape(text: str) -> str:
    """Rich markup in ``text`` shown as written."""
    from rich.markup import escape as rich_escape

    return rich_escape(text)


def discover():
    from .engine.registry import discover as load_suites

    return load_suites()


class CommandParser(argparse.ArgumentParser):
    """A command's parser: options and arguments in any order (``autograder grade SUB
    --no-html lab07.ex2``, as ``grade.py lab07 --no-html lab08``), and the command's own
    usage on every error, an unknown option's too (argparse leaves those to the top-level
    parser, whose usage names no option of the command)."""

    _intermixing = False   # inside parse_known_intermixed_args, which calls parse_known_args twice

    def parse_known_args(self, args=None, namespace=None):
        if self._intermixing:
            return super().parse_known_args(args, namespace)
        # A command with subcommands (gradescope build|run) cannot be intermixed; each of them is.
        mixable = not any(action.nargs in (argparse.PARSER, argparse.REMAINDER)
                          for action in self._get_positional_actions())
        self._intermixing = True
        try:
            parsed, extras = (self.parse_known_intermixed_args if mixable else super().parse_known_args)(
                args, namespace)
        finally:
            self._intermixing = False
        if extras:
            self.error(f"unrecognized arguments: {' '.join(extras)}")
        return parsed, []


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="autograder", description="Grade computer-vision lab submissions: autograder grade, "
                                       "autograder list (students: python grade.py).")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, parser_class=CommandParser)

    grade = commands.add_parser("grade", help="grade one submission")
    grade.add_argument("submission", nargs="?", help="folder, .py, .zip or .ipynb")
    add_grading_options(grade)
    grade.add_argument("--show-hidden", action="store_true",
                       help="report hidden checks in full: their inputs, messages and pictures (for "
                            "instructors; by default they show as students see them, a verdict only)")

    listing = commands.add_parser("list", help="list the labs, exercises and checks")
    listing.add_argument("--course", metavar="COURSE", help="course configuration (JSON): its own labs too")
    listing.add_argument("--ids", action="store_true",
                         help="show each check's id (lab07.ex1::translate_grey), as the course's 'hide' names it")

    validate = commands.add_parser(
        "validate", help="before hand-in: what would lose points for reasons other than the algorithm",
        description="Read the submission as grading does, import it in a clean sandboxed worker and run the "
                    "public checks, then name what would cost points for reasons other than the algorithm: "
                    "files and names, imports, notebook cells left out, signatures, dtypes of returned values. "
                    "Exit status: 0 when nothing was found, 1 when problems were, 2 for a usage error.")
    validate.add_argument("submission", help="folder, .py, .zip or .ipynb")
    validate.add_argument("select", nargs="*", metavar="SELECT",
                          help="what to validate: lab07, lab07.ex2 ... (default: everything)")
    validate.add_argument("--config", metavar="COURSE", help="course configuration (JSON): its own labs too")

    batch = commands.add_parser("batch", help="grade a class: a gradebook, every student's page, LMS CSVs")
    batch.add_argument("submissions", metavar="SUBMISSIONS",
                       help="folder or .zip: one entry per student, or a Gradescope/Canvas/Moodle download")
    batch.add_argument("--out", metavar="RESULTS", required=True, help="results folder (created; reused to resume)")
    batch.add_argument("--workers", type=_positive, metavar="N", help="parallel gradings (default: the number of cores)")
    batch.add_argument("--pictures", choices=("none", "failing", "all"), default="failing",
                       help="pictures on the feedback pages (default: %(default)s)")
    batch.add_argument("--regrade", action="store_true", help="grade everything again, even if unchanged")
    batch.add_argument("--compare", action="store_true",
                       help="regrade into a scratch copy of the gradebook and list whose final grade would "
                            "change, and why; nothing in OUT changes (the same command without --compare applies)")
    batch.add_argument("--course", metavar="COURSE", help="course configuration (JSON): labs, points, late rule")
    batch.add_argument("--roster", metavar="CSV", help="roster mapping students to LMS identities")
    batch.add_argument("--overrides", metavar="CSV", help="instructor overrides: student,exercise,points,penalty,comment")
    batch.add_argument("--dask-scheduler", metavar="ADDRESS", help="grade on this Dask cluster (tcp://host:8786)")
    batch.add_argument("--allow-unconfined", action="store_true",
                       help="grade even where student code cannot be confined (each submission could read the "
                            "others), or only less than this machine allows")
    batch.add_argument("--similarity", action="store_true",
                       help="also write RESULTS/similarity.html: the most similar submissions, lab by lab")

    gradescope = commands.add_parser("gradescope", help="Gradescope autograder: build the zip, or run inside it")
    actions = gradescope.add_subparsers(dest="action", required=True)
    build = actions.add_parser("build", help="write autograder.zip (setup.sh, run_autograder, sources)")
    build.add_argument("--out", default="autograder.zip", help="zip to write (default: %(default)s)")
    build.add_argument("--config", metavar="COURSE", help="course configuration (JSON)")
    run = actions.add_parser("run", help="grade a submission and write results.json (used by run_autograder)")
    run.add_argument("--submission", default="/autograder/submission")
    run.add_argument("--results", default="/autograder/results/results.json")
    run.add_argument("--config", metavar="COURSE", help="course configuration (JSON)")

    bundle = commands.add_parser("bundle", help="write the repository students receive")
    bundle.add_argument("--student", metavar="OUT", required=True, help="folder to create")
    bundle.add_argument("--course", metavar="COURSE",
                        help="course configuration (JSON): its labs' skeletons and public checks ship too")
    bundle.add_argument("--wheels", action="store_true",
                        help="also download every package the grader needs into OUT/wheels (for this Python "
                             "and platform, at constraints.txt's versions), so the bundle installs offline")
    add_class_commands(commands)
    add_author_commands(commands)
    return parser


def _positive(text: str) -> int:
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a positive whole number, got {text!r}")
    return int(text)


def add_grading_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("select", nargs="*", metavar="SELECT",
                        help="what to grade: lab07, lab07.ex2 ... (default: everything)")
    parser.add_argument("--json", metavar="FILE", help="write the results as JSON (a folder: FOLDER/results.json)")
    parser.add_argument("--json-pictures", action="store_true",
                        help="keep the pictures (base64 PNG/JPEG) in the JSON file too")
    parser.add_argument("--html", metavar="FILE", default="feedback.html",
                        help="write the feedback page (default: %(default)s; a folder: FOLDER/feedback.html)")
    parser.add_argument("--no-html", action="store_true", help="do not write the feedback page")
    parser.add_argument("--public-only", action="store_true", help="skip hidden checks")
    parser.add_argument("--timeout", type=_positive_seconds, metavar="SECONDS",
                        help=f"default time limit per call (default {Limits.call_timeout:g})")
    parser.add_argument("--quiet", action="store_true", help="print only the table")
    parser.add_argument("--config", metavar="COURSE",
                        help="course configuration (JSON); its 'forbid' and 'hidden_points_visible' apply")
    parser.add_argument("--figures", metavar="DIR",
                        help="also write the lab sheet's output pictures, made by your functions, "
                             "as DIR/<exercise>.png (and show them on the feedback page)")
    parser.add_argument("--report", metavar="DIR",
                        help="write (or refresh) your lab report: DIR/labNN_report.md per lab, with the figures "
                             "your functions make, the verdicts and a place for each explanation (kept when run again)")


def _positive_seconds(text: str) -> float:
    """``--timeout``: a positive, finite number of seconds."""
    try:
        seconds = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not (0 < seconds < float("inf")):
        raise argparse.ArgumentTypeError(f"must be a positive number of seconds, got {text}")
    return seconds


def _report_path(path, default_name: str) -> Path:
    """An output path; an existing folder, or a path ending in a slash (a folder, made when written), means
    ``folder/default_name``."""
    folder = str(path).endswith(("/", os.sep))
    path = Path(path)
    return path / default_name if folder or path.is_dir() else path


NO_SUBMISSION = ("autograder grade needs the submission to grade: a folder, .py, .zip or .ipynb.\n"
                 "  autograder grade path/to/submission            everything\n"
                 "  autograder grade path/to/submission lab07.ex2  one exercise\n"
                 "Students grade their own work with: python grade.py")


def run_grade(args) -> int:
    from .engine.labfolders import bundled_selection
    from .instructor.course import CourseConfig, CourseConfigError

    try:  # read first: its time limits are the worker's, and the worker starts next
        course = CourseConfig.load(args.config) if args.config else CourseConfig()
    except CourseConfigError as exc:
        print(f"error: {printable(str(exc))}", file=sys.stderr)
        return USAGE_ERROR
    limits = course.limits() if args.config else Limits()
    if args.timeout:
        limits = replace(limits, call_timeout=args.timeout)
    # (what to grade: the selection named, else the course's, else a course bundle's own -- course_labs/selection.json)
    chosen = args.select or course.select or bundled_selection()
    lanes = lanes_for(args.select)
    # First: the worker boots meanwhile.
    early = _early_sandbox(limits.shared_by(lanes)) if args.submission is not None else None

    from rich.console import Console

    from .engine.registry import SelectionError
    from .engine.results import write_json
    from .engine.runner import grade
    from .figures import grading_budget
    from .reports import terminal

    console, errors = Console(stderr=False), Console(stderr=True)
    if args.submission is None:
        errors.print(NO_SUBMISSION, markup=False, highlight=False)
        return USAGE_ERROR
    with contextlib.ExitStack() as closing:
        if early is not None:
            closing.enter_context(early)
        several = _several_students(args.submission)
        if several:
            console.print(f"[red]error:[/red] {escape(several)}")
            return USAGE_ERROR
        if not args.no_html:
            _prepare_page()  # while the worker boots
        try:
            with _progress(errors) as advance:
                # Pictures cost time to encode: make them only for a page (or a JSON file asking for them).
                pictures = "all" if (args.json_pictures or not args.no_html) else "none"
                note = ignored_keys_note(course, "grade")
                if note:
                    errors.print(f"[yellow]note:[/yellow] {escape(note)}", highlight=False)
                begun = time.monotonic()  # the submission's deadline counts from here: its figures share it
                result = grade(args.submission, chosen, limits=limits, pictures=pictures,
                               rerun=_rerun(args),
                               include_hidden=not args.public_only, on_check=advance, forbid=course.forbid,
                               lanes=lanes, sandboxes=[early] if early else [],
                               inputs_secret=course.inputs_secret or None)
        except (SelectionError, SubmissionError, CourseConfigError) as exc:
            errors.print(f"[red]error:[/red] {escape(str(exc))}", highlight=False, soft_wrap=True)
            return USAGE_ERROR
    if not getattr(args, "show_hidden", False):  # every report below is one a student may read
        result = result.for_students(course.hidden_points_visible)
    html_path = None if args.no_html else _report_path(args.html, "feedback.html")
    replaced_full_page = bool(args.select) and html_path is not None and html_path.is_file()
    terminal.render(result, console, details=not args.quiet, page=html_path)  # scores first
    moved = _since_previous_run(result, args, html_path, console)
    written, status = [], 0
    # Figures are part of the grading: its calls' limits (a lane's memory share), what is left of its deadline.
    graded, deadline = limits.shared_by(lanes), begun + grading_budget(limits, chosen)
    figures = {}
    if getattr(args, "figures", None):
        figures = _write_figures(args, graded, deadline, console, errors, written)
    if getattr(args, "report", None):
        status = _write_report(args, result, graded, deadline, console, errors, written) or status
    for path, write, what in ((html_path, lambda r, p: _write_page(r, p, figures, moved), "details and pictures"),
                              (args.json and _report_path(args.json, "results.json"),
                               lambda r, p: write_json(r, p, pictures=args.json_pictures), "results")):
        if not path:
            continue
        try:
            write(result, path)
            written.append((what, path))
        except OSError as exc:
            errors.print(f"[red]error:[/red] cannot write {escape(str(path))}: "
                         f"{escape(exc.strerror or str(exc))}", highlight=False, soft_wrap=True)
            status = USAGE_ERROR
    terminal.render_written(console, written)
    if replaced_full_page and any(path == html_path for _, path in written):
        errors.print(f"[yellow]note:[/yellow] {escape(str(html_path))} now shows only "
                     f"{escape(' '.join(args.select))}; run without a selection for the whole page "
                     "(or keep a partial page apart with --html other.html)", highlight=False, soft_wrap=True)
    return status


def _rerun(args) -> tuple[str, str]:
    """How to grade these files again, around an exercise's id (the words property failures give)."""
    if getattr(args, "rerun", None):
        return args.rerun
    return f"autograder grade {shlex.quote(str(args.submission))} ", ""


def _write_page(result, path, figures, since=()) -> None:
    from .reports import html  # Jinja2 is imported only when a page is written

    html.write(result, path, figures=figures, since=since)


def _since_previous_run(result, args, html_path, console) -> list[str]:
    """What moved since the previous run, read from the results it left (the ``--json`` file,
    else the page) before this run overwrites them; told on the terminal, returned for the page."""
    from .student.progress import previous_scores, since

    moved = since(previous_scores(args.json and _report_path(args.json, "results.json"), html_path), result)
    if moved:
        console.print("since your previous run: " + "; ".join(moved), highlight=False, markup=False)
    return moved


def _prepare_page() -> None:
    """Jinja2 imported and the page's templates compiled (a tenth of a second)."""
    from .reports import html

    html.prepare()


def _write_figures(args, limits, deadline, console, errors, written) -> dict[str, bytes]:
    """``--figures DIR``: the lab sheet's pictures made by the student's functions; returns
    the PNG bytes by exercise for the page, and notes each file (or why there is none)."""
    from .figures import make_figures

    try:
        outcomes = make_figures(args.submission, args.select, args.figures, limits, deadline)
    except OSError as exc:
        errors.print(f"[red]error:[/red] cannot write figures to {escape(str(args.figures))}: "
                     f"{escape(exc.strerror or str(exc))}", highlight=False, soft_wrap=True)
        return {}
    _say_what_figures_lack(console, outcomes)
    written += [(f"figure {o.figure_id}", o.path) for o in outcomes if o.path is not None]
    return {o.figure_id: o.path.read_bytes() for o in outcomes if o.path is not None}


def _write_report(args, result, limits, deadline, console, errors, written) -> int:
    """``--report DIR``: the lab report's scaffold (autograder.student.report); notes each file."""
    from .student.report import write_report

    try:
        report = write_report(args.submission, args.select, args.report, result, limits, deadline)
    except OSError as exc:
        errors.print(f"[red]error:[/red] cannot write the report to {escape(str(args.report))}: "
                     f"{escape(exc.strerror or str(exc))}", highlight=False, soft_wrap=True)
        return USAGE_ERROR
    _say_what_figures_lack(console, report.figures)
    written += [(f"report ({report.kept[path.name]} explanations kept)" if report.kept[path.name] else "report",
                 path) for path in report.files]
    return 0


def _say_what_figures_lack(console, outcomes) -> None:
    """Why each figure missing is (figures missing for one reason, e.g. the deadline, in one
    line), and what a figure made leaves out."""
    missing: dict[str, list[str]] = {}
    for outcome in outcomes:
        if outcome.path is None:
            missing.setdefault(outcome.reason, []).append(outcome.figure_id)
        elif outcome.note:
            console.print(f"[yellow]note on figure {outcome.figure_id}:[/yellow] {escape(outcome.note)}",
                          highlight=False)
    for reason, figure_ids in missing.items():
        console.print(f"[yellow]no figure for {', '.join(figure_ids)}:[/yellow] {escape(reason)}", highlight=False)


def _early_sandbox(limits):
    """A sandbox without a submission yet, its worker spawned (it imports NumPy and OpenCV
    while the grader loads) at the strongest confinement level the platform offers, or
    None if it could not be made: grading then makes its own and reports why. Grading
    checks that the level works (the worker gets ready) before relying on it."""
    from .sandbox.supervisor import Sandbox

    try:
        sandbox = Sandbox(None, limits, confinement=confine.strongest_candidate())
    except Exception:  # noqa: BLE001
        return None
    try:
        sandbox.start()
    except Exception:  # noqa: BLE001
        sandbox.close()
        return None
    return sandbox


def lanes_for(selectors) -> int:
    """How many lanes ``grade.py`` grades with: a lab per core this process may use at once,
    up to 4 (a worker each), and no more than the labs selected (``lab07``, ``lab07.ex2``;
    none: all, and grading gives up lanes it has no lab with work for)."""
    lanes = min(usable_cores(), 4)
    if selectors:
        lanes = min(lanes, len({selector.split(".", 1)[0] for selector in selectors}))
    return max(1, lanes)


def _several_students(path) -> str | None:
    from .instructor.batch.ingest import several_students

    modules = sorted({lab.module for lab in discover().values()})
    if not (str(path).lower().endswith(".zip") and Path(path).is_file()):
        return several_students(path, modules)
    # (a class comes as a zip as often as a folder: an LMS's bulk download is one -- read as the grading would
    # unpack it, its own refusals left to the grading)
    import tempfile

    from .loading.submission import SubmissionError, unzip_regular_files

    with tempfile.TemporaryDirectory(prefix="autograder-class-zip-") as unpacked:
        try:
            unzip_regular_files(Path(path), Path(unpacked))
        except SubmissionError:
            return None
        said = several_students(unpacked, modules)
    return None if said is None else said.replace(unpacked, str(path))


class _progress:
    """A transient progress line on stderr when it is a terminal (nothing when redirected):
    the exercise being graded, checks done, and time so far."""

    def __init__(self, console):
        self.console = console
        self.bar = None

    def __enter__(self):
        if not self.console.is_terminal:
            return None
        from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

        self.bar = Progress(TextColumn("[bold]grading[/bold] {task.description}"), BarColumn(),
                            TextColumn("{task.completed} checks"), TimeElapsedColumn(),
                            console=self.console, transient=True)
        self.bar.start()
        self.task = self.bar.add_task("", total=None)
        return lambda exercise, check: self.bar.update(self.task, advance=1, description=exercise.id)

    def __exit__(self, *exc):
        if self.bar:
            self.bar.stop()


BATCH_LINES = 20   # lines of each kind the batch prints (a stray-filled upload lists thousands)


def _out_among_submissions(submissions, out) -> str:
    """Why ``out`` cannot hold a batch's results (``""``: it can): it is the submissions folder or inside it, where
    the pages and sources written would be read back as the students' work by the next run."""
    try:
        given, results = Path(submissions).resolve(), Path(out).resolve()
    except (OSError, RuntimeError):
        return ""
    if not given.is_dir() or (results != given and given not in results.parents):
        return ""
    return (f"--out {out} is {'the' if results == given else 'inside the'} folder of submissions {submissions}: the "
            "results written there (pages, sources, the gradebook) would be read as students' work by the next run; "
            f"give a folder outside it, e.g. --out {given.parent / (given.name + '-results')}")


def run_batch(args) -> int:
    from .instructor.batch.task import grading_processes

    # What takes a process of its own starts before the rest of the batch is imported.
    if args.dask_scheduler is None:
        grading_processes()
        if not args.allow_unconfined:
            confine.detect_in_background()
    from rich.console import Console
    from rich.text import Text

    from .instructor.batch.cluster import DaskUnavailable
    from .instructor.batch.exports import ExportError
    from .instructor.batch.gradebook import StorageError
    from .instructor.batch.ingest import IngestError
    from .instructor.batch.processes import GradingProcessesFailed
    from .instructor.batch.run import run_batch as batch
    from .instructor.course import CourseConfig, CourseConfigError
    from .engine.registry import SelectionError

    console = Console()
    out = args.out
    inside = _out_among_submissions(args.submissions, args.out)
    if inside:
        console.print(f"[red]error:[/red] {escape(inside)}", highlight=False)
        return USAGE_ERROR
    try:
        course = CourseConfig.load(args.course) if args.course else CourseConfig()
        note = ignored_keys_note(course, "batch")
        if note:
            console.print(f"[yellow]note:[/yellow] {escape(note)}", highlight=False)
        if args.compare:
            out = _scratch_copy(args.out)
            course = _preview_course(course, out)
        with _batch_progress(console) as progress:
            summary = batch(args.submissions, out, course=course, workers=args.workers,
                            pictures=args.pictures, regrade=args.regrade, roster=args.roster,
                            overrides=args.overrides, dask_scheduler=args.dask_scheduler, progress=progress,
                            allow_unconfined=args.allow_unconfined)
    except (CourseConfigError, IngestError, ExportError, SelectionError, DaskUnavailable) as exc:
        console.print(f"[red]error:[/red] {escape(str(exc))}")
        return USAGE_ERROR
    except GradingProcessesFailed as exc:   # this machine's fault: every finished grading is kept
        print(f"error: {exc}; every finished grading is in the gradebook: run the same command again",
              file=sys.stderr)
        return STORAGE_ERROR
    except StorageError as exc:
        return _storage_failed(exc)
    except KeyboardInterrupt:
        console.print("interrupted: every finished grading is in the gradebook; "
                      "run the same command again to resume")
        return 130
    finally:
        if out != args.out:   # the preview's scratch copy
            shutil.rmtree(out, ignore_errors=True)
    console.print(f"{summary.students} students: {summary.graded} graded now, {summary.reused} unchanged "
                  f"(kept from the gradebook), {len(summary.failed)} failed, {len(summary.unreadable)} unreadable",
                  highlight=False)
    moved = len(summary.changes)
    if summary.first_run and not args.compare:   # (nothing graded before to compare with: no "0 changed")
        console.print("the first run of this gradebook: the next runs say whose final grade changed (changes.csv)",
                      highlight=False, markup=False)
    else:
        console.print(f"{moved} final grade{'s' if moved != 1 else ''} "
                      + ("would change (a preview: nothing in " f"{args.out} changed; run the same command without "
                         "--compare to apply)" if args.compare else "changed since the last run (changes.csv)"),
                      highlight=False, markup=False)
    for title, lines in (("changed", [change.sentence() for change in summary.changes]),
                         ("unreadable", summary.unreadable), ("failed", summary.failed),
                         ("ignored", summary.ignored),
                         ("no longer in SUBMISSIONS", [f"{i} (kept, with their last grading)" for i in summary.missing]),
                         ("roster", summary.unmatched),
                         ("file not graded", summary.files_not_graded),
                         ("warning", summary.warnings)):
        for line in lines[:BATCH_LINES]:
            console.print(Text.assemble("  ", (f"{title}:", "yellow"), f" {printable(line)}"), highlight=False)
        if len(lines) > BATCH_LINES:
            more = {"ignored": " (all in ignored.csv)", "changed": " (all in changes.csv)",
                    "file not graded": " (all in grades.csv)"}.get(title, "")
            console.print(f"  ... and {len(lines) - BATCH_LINES} more {title}{more}", highlight=False, markup=False)
    if args.compare:
        return 0
    if args.similarity:
        try:
            summary.files.append(_batch_similarity(args, course, console))
            if summary.files[-1]:   # the class overview links it
                from .instructor.classreport.pages import write_overview

                write_overview(args.out)
        except StorageError as exc:
            return _storage_failed(exc)
    results = Path(args.out).resolve()
    inside = [p for p in summary.files if p and results in Path(p).resolve().parents]
    elsewhere = [p for p in summary.files if p and p not in inside]   # (the course's pooled late-days ledger)
    console.print(f"wrote {args.out}/ : " + ", ".join(p.name for p in inside)
                  + ", <student>/feedback.html, <student>/results.json, gradebook.sqlite"
                  + "".join(f"; and {p}" for p in elsewhere), highlight=False, markup=False)
    return 0


def _scratch_copy(out) -> Path:
    """A scratch folder holding a consistent copy of OUT's gradebook (none yet: an empty folder),
    for ``batch --compare``: gradings kept there are reused, and nothing in OUT is touched."""
    import sqlite3
    import tempfile

    from .instructor.batch.gradebook import GRADEBOOK

    scratch = Path(tempfile.mkdtemp(prefix="autograder-compare-"))
    source = Path(out) / GRADEBOOK
    if source.is_file():
        original, copy = sqlite3.connect(f"{source.resolve().as_uri()}?mode=ro", uri=True), \
            sqlite3.connect(scratch / GRADEBOOK)
        try:
            original.backup(copy)
        finally:
            original.close()
            copy.close()
    return scratch


def _preview_course(course, scratch: Path):
    """``course`` for a ``--compare`` preview: its late-day ledger (shared by the term's
    assignments, outside RESULTS) copied into the scratch folder, so the preview writes nothing
    anywhere else."""
    ledger = (course.late_days or {}).get("ledger")
    if not ledger:
        return course
    copy = scratch / "late_days.json"
    if Path(ledger).is_file():
        shutil.copyfile(ledger, copy)
    return replace(course, late_days={**course.late_days, "ledger": str(copy)})


def _batch_similarity(args, course, console) -> Path | None:
    from .instructor.batch.gradebook import StorageError
    from .instructor.classreport.pages import SIMILARITY, write_similarity
    from .instructor.classreport.similarity import SimilarityUnavailable

    page = str(Path(args.out) / SIMILARITY)
    try:
        return write_similarity(args.submissions, args.out, course.similarity_threshold, course.assignment)
    except SimilarityUnavailable as exc:
        console.print(f"[yellow]similarity report skipped:[/yellow] {escape(str(exc))}")
        return None
    except OSError as exc:   # the page (or a submission gone since it was graded)
        named = exc.filename or page
        raise StorageError.from_exception(exc, named, "write" if str(named) == page else "read") from exc


def _storage_failed(exc) -> int:
    """A StorageError: its one line (the file, what to do) on stderr."""
    print(f"error: {exc}", file=sys.stderr)
    return STORAGE_ERROR


def _running_column():
    from rich.progress import ProgressColumn
    from rich.text import Text

    class RunningColumn(ProgressColumn):
        """The students being graded, the longest first, with how long each has run: a slow
        one is named while the ETA waits for it."""

        def __init__(self, since: dict):
            super().__init__()
            self.since = since

        def render(self, task):
            import time

            now = time.monotonic()
            longest = sorted(self.since.items(), key=lambda item: item[1])[:3]
            shown = ", ".join(f"{key} {int(now - start) // 60}:{int(now - start) % 60:02d}" for key, start in longest)
            more = f" +{len(self.since) - 3}" if len(self.since) > 3 else ""
            return Text(f"running: {shown}{more}" if shown else "", style="dim")

    return RunningColumn


class _batch_progress:
    """A progress bar with ETA and finished/failed counts on a terminal; nothing when redirected."""

    def __init__(self, console):
        self.console = console
        self.bar = None

    def __enter__(self):
        if not self.console.is_terminal:
            return None
        from rich.progress import (BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn,
                                   TimeRemainingColumn)

        self.since: dict[str, float] = {}   # student id -> when the batch saw them running
        self.bar = Progress(TextColumn("[bold]grading[/bold]"), BarColumn(), MofNCompleteColumn(),
                            TextColumn("{task.fields[counts]}"), TimeElapsedColumn(), TextColumn("ETA"),
                            TimeRemainingColumn(), _running_column()(self.since), console=self.console)
        self.bar.start()
        self.task = None
        return self.update

    def update(self, event, entry, summary):
        import time

        if event == "start":
            self.task = self.bar.add_task("", total=summary.students, counts="")
            return
        now = time.monotonic()
        # (in place: the bar's running column holds this dict, not the name)
        running = {key: self.since.get(key, now) for key in summary.running}
        self.since.clear()
        self.since.update(running)
        self.bar.update(self.task, advance=1, counts=f"{summary.graded} finished, {len(summary.failed)} failed")

    def __exit__(self, *exc):
        if self.bar:
            self.bar.stop()


VALIDATE_PROBLEMS = 1   # validate: problems found


def run_validate(args) -> int:
    """``autograder validate PATH [SELECT...]``: 0 clean, 1 problems found, 2 usage."""
    from .engine.registry import SelectionError
    from .instructor.course import CourseConfig, CourseConfigError
    from .student.validate import validate

    try:
        if getattr(args, "config", None):
            CourseConfig.load(args.config)   # registers the course's labs
        report = validate(args.submission, args.select)
    except (SelectionError, SubmissionError, CourseConfigError) as exc:
        print(f"error: {printable(str(exc))}", file=sys.stderr)
        return USAGE_ERROR
    print(printable(str(report)))
    return 0 if report.ok else VALIDATE_PROBLEMS


def run_list(args) -> int:
    """The labs, exercises and checks; with ``--course``, as that course grades them: its labs,
    its selection, its points (the suite's beside them where they differ) and its hidden checks."""
    from .engine.registry import SelectionError, select
    from .instructor.course import CourseConfig, CourseConfigError

    try:
        course = CourseConfig.load(args.course) if getattr(args, "course", None) else CourseConfig()
        exercises = select(course.select)   # every exercise when the course selects none
    except (CourseConfigError, SelectionError) as exc:
        print(f"error: {printable(str(exc))}", file=sys.stderr)
        return USAGE_ERROR
    factors = course.point_factors([(e.id, e.max_score()) for e in exercises])
    shown_lab = None
    for exercise in exercises:
        lab = exercise.lab
        if lab is not shown_lab:
            where = f"  (course lab: {lab.folder})" if lab.folder else ""
            print(f"{lab.key}  {lab.module}.py  {lab.title}{where}")
            shown_lab = lab
        factor = factors.get(exercise.id, 1.0)
        raw = f" (suite: {exercise.max_score():g})" if factor != 1.0 else ""
        print(f"  {exercise.id:<12} {exercise.max_score() * factor:>5.4g} pts  {exercise.title}{raw}")
        for check in exercise.checks:
            points = "tip" if check.advice else f"{check.points * factor:.3g}"  # advice: 0 points
            print(f"      {points:>4}  {check_label(check.name, check.hidden)}"
                  + (f"  [{check.id}]" if getattr(args, "ids", False) else ""))
    return 0


def check_label(name: str, hidden: bool) -> str:
    """A check's name with "(hidden)" once when it is hidden (some names already say so)."""
    name = name.removesuffix(" (hidden)").rstrip()
    return f"{name} (hidden)" if hidden else name


_NOT_APPLIED = {
    "grade": "a single grading applies only what judges the code (select, labs, hide, the time limits, forbid, "
             "inputs_secret, hidden_points_visible)",
    "batch": "Gradescope's visibility settings apply only on Gradescope",
    "gradescope": "Gradescope applies its own late policy and exports (set them in the assignment's settings)",
}


def ignored_keys_note(course, mode: str) -> str:
    """One sentence naming the course keys ``mode`` does not apply ('' when it applies them all)."""
    keys = course.ignored_by(mode)
    if not keys:
        return ""
    return f"the course sets {', '.join(keys)}, which {_COMMAND[mode]} does not apply: {_NOT_APPLIED[mode]}"


_COMMAND = {"grade": "grading one submission", "batch": "autograder batch", "gradescope": "Gradescope"}


def run_gradescope(args) -> int:
    from .instructor import gradescope
    from .instructor.course import CourseConfig, CourseConfigError
    from .engine.registry import SelectionError

    try:
        config = CourseConfig.load(args.config) if args.config else CourseConfig()
    except CourseConfigError as exc:
        if args.action == "build":
            print(f"error: {exc}", file=sys.stderr)
            return USAGE_ERROR
        config = CourseConfig()  # inside the container results.json is written regardless
        gradescope.log.error("%s; using the defaults", exc)
    if args.action == "build":
        note = ignored_keys_note(config, "gradescope")
        if note:
            print(f"warning: {note}", file=sys.stderr)
        try:
            out = gradescope.build(args.out, config)
        except SelectionError as exc:
            print(f"error: {exc}", file=sys.stderr)
            return USAGE_ERROR
        print(f"wrote {out}: upload it as the Gradescope autograder")
        return 0
    data = gradescope.run(args.submission, args.results, config)
    print(data["output"])
    return 0


def run_bundle(args) -> int:
    from .instructor.bundle import WheelhouseError, write_student_bundle, write_wheelhouse
    from .instructor.course import CourseConfig, CourseConfigError

    try:
        course = CourseConfig.load(args.course) if getattr(args, "course", None) else None
        files = write_student_bundle(args.student, course=course)
    except (FileExistsError, CourseConfigError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return USAGE_ERROR
    print(f"wrote {len(files)} files to {args.student}: the student repository "
          "(no reference solutions, no hidden checks)")
    if not getattr(args, "wheels", False):
        return 0
    try:
        wheels = write_wheelhouse(args.student)
    except WheelhouseError as exc:
        print(f"error: no wheels: {exc}. {args.student} is complete but installs with a network only "
              "(its README says how); run autograder bundle again where pip can download.", file=sys.stderr)
        return 1
    size = sum((Path(args.student) / wheel).stat().st_size for wheel in wheels)
    print(f"wrote {len(wheels)} wheels ({size / 2**20:.0f} MiB) to {Path(args.student) / 'wheels'}: "
          "the README says how to install from them offline")
    return 0


def add_class_commands(commands) -> None:
    """``autograder report`` and ``autograder similarity``: the class pages of a batch."""
    report = commands.add_parser("report", help="write RESULTS/index.html, the class overview, from the gradebook")
    report.add_argument("results", metavar="RESULTS", help="a batch's results folder")
    report.add_argument("--course", metavar="COURSE", help="course configuration (JSON)")
    report.add_argument("--title", default="", help="course title shown on the page")

    review = commands.add_parser(
        "review", help="grade the lab reports with the course's rubric in a local web application")
    review.add_argument("results", metavar="RESULTS", help="a batch's results folder")
    review.add_argument("--port", type=int, default=0, help="port on 127.0.0.1 (default: a free one)")
    review.add_argument("--anonymous", action="store_true", help="hide the students' names (stable pseudonyms)")
    review.add_argument("--shuffle", type=int, metavar="SEED", help="review in an order shuffled by SEED")
    review.add_argument("--reviewer", default="", help="your name, stored with each change (default: your login)")

    similarity = commands.add_parser(
        "similarity", help="write similarity.html: the most similar submissions, lab by lab (leads to read)")
    similarity.add_argument("submissions", metavar="SUBMISSIONS_OR_RESULTS",
                            help="the class's submissions (a batch's input), or a results folder keeping sources")
    similarity.add_argument("--out", metavar="HTML", help="page to write (default: RESULTS/similarity.html for "
                                                          "a results folder, else ./similarity.html)")
    similarity.add_argument("--course", metavar="COURSE", help="course configuration (JSON): similarity_threshold")
    similarity.add_argument("--threshold", type=float, help="show pairs scoring at least this (0-1), "
                                                            "instead of the course's similarity_threshold")
    similarity.add_argument("--title", default="", help="course title shown on the page")


def run_report(args) -> int:
    """``autograder report RESULTS``: the class overview again, and each student's page and
    results.json written again from the gradebook where they were lost (1 if some cannot be)."""
    from .instructor.batch.exports import ExportError
    from .instructor.batch.gradebook import StorageError
    from .instructor.batch.run import restore_student_files
    from .instructor.classreport.pages import NoGradebook, write_overview
    from .instructor.course import CourseConfig, CourseConfigError
    from .engine.registry import SelectionError

    from .instructor.batch.ingest import IngestError
    from .instructor.batch.run import write_exports

    try:
        course = CourseConfig.load(args.course) if args.course else None
        title = args.title or (course.assignment if course else None)
        written, warnings, pages = [write_overview(args.results, course_title=title)], [], False
        restored, problems = restore_student_files(args.results, course)
        try:   # the CSVs and every page again, with the reports' reviews
            written, warnings = write_exports(args.results, course, course_title=title)
            pages = True
        except IngestError as exc:   # a batch is writing RESULTS: it writes them when it ends
            print(f"note: {exc}; the CSVs and pages are written by that batch when it finishes", file=sys.stderr)
    except (CourseConfigError, NoGradebook, SelectionError, ExportError) as exc:   # ExportError: the late-day ledger
        print(f"error: {exc}", file=sys.stderr)
        return USAGE_ERROR
    except StorageError as exc:
        return _storage_failed(exc)
    for path in restored:
        print(f"restored {path} (from the gradebook)")
    for problem in problems:
        student, _, why = problem.partition(": ")
        print(f"error: cannot restore the files of {student}: {why}; "
              f"grade them again with autograder batch SUBMISSIONS --out {args.results} --regrade",
              file=sys.stderr)
    for line in warnings[:BATCH_LINES]:
        print(f"warning: {printable(line)}", file=sys.stderr)
    if len(warnings) > BATCH_LINES:
        print(f"warning: ... and {len(warnings) - BATCH_LINES} more", file=sys.stderr)
    print(_what_report_wrote(Path(args.results), written, pages))
    return STORAGE_ERROR if problems else 0


def _what_report_wrote(results: Path, written: list[Path], pages: bool) -> str:
    """One line: the files written, by name, and (``pages``: they were brought up to date with
    the gradebook) how many students' pages the folder holds."""
    names = ", ".join(path.relative_to(results).as_posix() if path.is_relative_to(results) else str(path)
                      for path in written if path)
    line = f"wrote {results.as_posix()}/ : {names}"
    if pages:
        count = sum(1 for _ in results.glob("*/feedback.html"))
        line += f"; {count} student page{'s' if count != 1 else ''} up to date (<student>/feedback.html)"
    return line


def run_review(args) -> int:
    """``autograder review RESULTS``: serve the report review on 127.0.0.1 until Ctrl-C."""
    import getpass

    from .instructor.batch.gradebook import GRADEBOOK, StorageError

    if not (Path(args.results) / GRADEBOOK).is_file():
        print(f"error: no gradebook in {args.results}: run autograder batch first", file=sys.stderr)
        return USAGE_ERROR
    try:
        from .instructor.review import serve
    except ImportError as exc:
        print(f"error: autograder review needs Flask, a dependency of the grader ({exc}): install the grader "
              "again as the README says (python -m pip install -c constraints.txt -e .)",
              file=sys.stderr)
        return USAGE_ERROR
    try:
        reviewer = args.reviewer or getpass.getuser()
    except (KeyError, OSError):
        reviewer = "reviewer"

    def announce(url: str) -> None:
        print(f"Reviewing {args.results} as {reviewer}: open\n  {url}\n(only this machine can reach it; "
              "every change is saved at once; Ctrl-C stops the server)", flush=True)

    try:
        serve(args.results, args.port, reviewer=reviewer, anonymous=args.anonymous, shuffle=args.shuffle,
              announce=announce)
    except StorageError as exc:
        return _storage_failed(exc)
    except OSError as exc:
        print(f"error: cannot serve on 127.0.0.1:{args.port}: {exc.strerror or exc}", file=sys.stderr)
        return USAGE_ERROR
    return 0


def _default_similarity_page(folder: Path) -> Path:
    from .instructor.classreport.pages import GRADEBOOK, SIMILARITY

    return folder / SIMILARITY if (folder / GRADEBOOK).is_file() else Path(SIMILARITY)


def run_similarity(args) -> int:
    from .instructor.classreport.similarity import SimilarityUnavailable, write_similarity_report
    from .instructor.course import CourseConfig, CourseConfigError

    try:
        course = CourseConfig.load(args.course) if args.course else CourseConfig()
        threshold = args.threshold if args.threshold is not None else course.similarity_threshold
        if not 0 < threshold <= 1:
            raise CourseConfigError("--threshold must be in (0, 1]")
        out = Path(args.out) if args.out else _default_similarity_page(Path(args.submissions))
        results = write_similarity_report(args.submissions, out, threshold=threshold,
                                          course_title=args.title or getattr(course, "assignment", ""))
    except (CourseConfigError, SubmissionError, SimilarityUnavailable) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return USAGE_ERROR
    for lab in results:
        print(f"{lab.lab}: {lab.students} students, {len(lab.leads(threshold))} pairs at or above {threshold:.0%}")
    print(f"wrote {out} (leads to read, not findings)")
    return 0


def add_author_commands(commands) -> None:
    """``autograder verify`` and ``autograder new-lab``: for those who write labs."""
    verify = commands.add_parser(
        "verify", help="prove labs' checks sound: reference, skeleton, mistakes table, determinism",
        description="Grade each lab's reference solution (twice), its skeleton and every case of its mistakes "
                    "table, and check that the reference gets full marks, the skeleton zero ('not implemented "
                    "yet'), every case loses points named in its own words and never as another mistake, every "
                    "check fails on some case and gives the same verdict twice. Exit status: 0 when every lab is "
                    "sound, 1 when some is not, 2 for a usage error.")
    verify.add_argument("labs", nargs="*", metavar="LAB",
                        help="labs to verify: lab07 lab13 ... (default: the course's own labs with --course, "
                             "else every built-in lab)")
    verify.add_argument("--course", metavar="COURSE", help="course configuration (JSON): its labs")
    verify.add_argument("--error-model", action="store_true",
                        help="also measure the error model: grade a sample of the reference's mutants and count "
                             "those caught, named and equivalent (slow: one grading per mutant)")
    verify.add_argument("--mutants", type=int, default=30, metavar="N",
                        help="how many mutants per lab --error-model grades (default 30)")
    new_lab = commands.add_parser("new-lab", help="write a lab folder to start from (it passes verify as it is)")
    new_lab.add_argument("name", metavar="NAME", help="the lab's module, lab<NN>_<words>: lab13_flow")
    new_lab.add_argument("--into", metavar="FOLDER", required=True, help="folder to create (empty or new)")
    new_lab.add_argument("--title", default="", help="the lab's title (default: from NAME)")
    new_lab.add_argument("--course", metavar="COURSE", default="course.json",
                         help="the course configuration that will name the lab (default: %(default)s): "
                              "the line to write there is printed, the folder relative to it")


VERIFY_FAILED = 1   # verify: some lab is not sound


def run_verify(args) -> int:
    """``autograder verify [LAB ...] [--course COURSE]``: 0 sound, 1 not, 2 usage."""
    from rich.console import Console

    from .instructor.course import CourseConfig, CourseConfigError
    from .instructor.verify import MIN_MISTAKES, VerifyError, render, verify_lab

    console, errors = Console(), Console(stderr=True)
    try:
        course = CourseConfig.load(args.course) if args.course else None
    except CourseConfigError as exc:
        errors.print(f"[red]error:[/red] {escape(str(exc))}", highlight=False, soft_wrap=True)
        return USAGE_ERROR
    labs = discover()
    if args.labs:
        keys = [key.strip().lower() for key in args.labs]
    elif course is not None and course.labs:
        keys = sorted(lab.key for lab in labs.values() if lab.folder)
    else:
        keys = sorted(key for key, lab in labs.items() if lab.folder is None)
    unknown = [key for key in keys if key not in labs]
    if unknown:
        errors.print(f"[red]error:[/red] no lab {escape(', '.join(unknown))} (labs: {', '.join(sorted(labs))}; "
                     "a course's own labs need --course)", highlight=False)
        return USAGE_ERROR
    sound = True
    for key in keys:
        try:
            with _progress(errors) as advance:
                report = verify_lab(labs[key], progress=(lambda what: advance(_Step(what), None)) if advance else None,
                                    min_mistakes=course.min_mistakes if course else MIN_MISTAKES)
        except VerifyError as exc:
            errors.print(f"[red]error:[/red] {escape(str(exc))}", highlight=False, soft_wrap=True)
            return USAGE_ERROR
        render(report, console)
        sound = sound and report.ok
        if args.error_model:
            from .instructor.error_model import measure_error_model, render_error_model

            try:
                with _progress(errors) as advance:
                    measured = measure_error_model(labs[key], max(1, args.mutants), progress=(
                        lambda what: advance(_Step(what), None)) if advance else None)
            except ValueError as exc:
                errors.print(f"[red]error:[/red] {escape(str(exc))}", highlight=False, soft_wrap=True)
                return USAGE_ERROR
            render_error_model(measured, console)
    return 0 if sound else VERIFY_FAILED


class _Step:
    """What the progress line shows while verify grades (it reads ``.id``)."""

    def __init__(self, what: str):
        self.id = what


def run_new_lab(args) -> int:
    from .instructor.newlab import NewLabError, course_entry, new_lab

    try:
        written = new_lab(args.name, args.into, args.title)
    except NewLabError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return USAGE_ERROR
    folder, course = Path(args.into), Path(args.course)
    print(f"wrote {len(written)} files to {folder}: " + ", ".join(p.relative_to(folder).as_posix() for p in written))
    entry = course_entry(folder, course)
    if course.is_file():
        print(f"in {course}, set (replacing its \"labs\" line if it has one):\n  {entry}")
    else:
        print(f"write {course} (it does not exist yet):\n  {entry}")
    print(f"then: autograder verify --course {shlex.quote(str(course))}")
    return 0


def _judged_not_warned() -> None:
    """The grader's own arithmetic on a student's answers (NaN, an empty region of a wrong panorama) is judged by
    the checks; NumPy's RuntimeWarnings about it ("Mean of empty slice") are nothing a student or an instructor
    can act on, and are not printed (the grader's own process only: student code runs in workers)."""
    import warnings

    warnings.filterwarnings("ignore", category=RuntimeWarning)


def main(argv=None) -> int:
    _judged_not_warned()
    args = build_parser().parse_args(argv)
    commands = {"grade": run_grade, "list": run_list, "validate": run_validate, "batch": run_batch,
                "gradescope": run_gradescope,
                "bundle": run_bundle, "report": run_report, "similarity": run_similarity, "review": run_review,
                "verify": run_verify, "new-lab": run_new_lab}
    return _until_the_reader_goes(commands[args.command], args)


def _until_the_reader_goes(command, args) -> int:
    """``command(args)``, and its status; a reader that stops early (``autograder list | head``)
    ends the output, not with a traceback: what is left to print goes nowhere."""
    status = 0
    try:
        status = command(args)
        sys.stdout.flush()
    except BrokenPipeError:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # also for the flush at exit
    return status


def grade_py_main(argv=None, root: Path | None = None) -> int:
    """``python grade.py [SELECT...] [--submission PATH]``: grade the student's own work."""
    _judged_not_warned()
    root = root or Path.cwd()
    parser = CommandParser(
        prog="grade.py", description="Grade your labs: python grade.py [lab07 | lab07.ex2 ...]",
        epilog="In a notebook, check one exercise as you work: "
               "from autograder import check; check(\"lab07.ex2\")")
    parser.add_argument("--submission", metavar="PATH", default=str(root / "assignments"),
                        help="folder to grade (default: assignments/)")
    add_grading_options(parser)
    args = parser.parse_args(argv)
    default = args.submission == str(root / "assignments")
    args.rerun = ("python grade.py " + ("" if default else f"--submission {shlex.quote(args.submission)} "), "")
    return _until_the_reader_goes(run_grade, args)


if __name__ == "__main__":
    sys.exit(main())
