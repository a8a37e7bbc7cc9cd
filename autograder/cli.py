"""Command line: ``autograder grade``, ``autograder list`` (and ``python grade.py``).

Exit status is 0 whenever grading completed, whatever the score; 2 for usage
errors (an unknown selector, a submission path that does not exist).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import __version__
from .registry import SelectionError, discover
from .sandbox import Limits
from .submission import SubmissionError

USAGE_ERROR = 2


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="autograder", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)

    grade = commands.add_parser("grade", help="grade one submission")
    grade.add_argument("submission", help="folder, .py, .zip or .ipynb")
    add_grading_options(grade)

    commands.add_parser("list", help="list the labs, exercises and checks")

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
    return parser


def add_grading_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("select", nargs="*", metavar="SELECT",
                        help="what to grade: lab07, lab07.ex2 ... (default: everything)")
    parser.add_argument("--json", metavar="FILE", help="write the results as JSON")
    parser.add_argument("--html", metavar="FILE", default="feedback.html",
                        help="write the feedback page (default: %(default)s)")
    parser.add_argument("--no-html", action="store_true", help="do not write the feedback page")
    parser.add_argument("--public-only", action="store_true", help="skip hidden checks")
    parser.add_argument("--timeout", type=float, metavar="SECONDS",
                        help=f"default time limit per call (default {Limits.call_timeout:g})")
    parser.add_argument("--quiet", action="store_true", help="print only the table")
    parser.add_argument("--config", metavar="COURSE",
                        help="course configuration (JSON); its 'forbid' rules apply")


def run_grade(args) -> int:
    from rich.console import Console

    from .course import CourseConfig, CourseConfigError
    from .reports import html, terminal
    from .results import write_json
    from .runner import grade

    console = Console(stderr=False)
    limits = Limits(call_timeout=args.timeout) if args.timeout else None
    try:
        with _progress(console) as advance:
            # Pictures cost time to encode: make them only for a page or a JSON file.
            pictures = "all" if (args.json or not args.no_html) else "none"
            forbid = CourseConfig.load(args.config).forbid if args.config else None
            result = grade(args.submission, args.select, limits=limits, pictures=pictures,
                           include_hidden=not args.public_only, on_check=advance, forbid=forbid)
    except (SelectionError, SubmissionError, CourseConfigError) as exc:
        console.print(f"[red]error:[/red] {exc}")
        return USAGE_ERROR
    html_path = None if args.no_html else args.html
    if html_path:
        html.write(result, html_path)
    if args.json:
        write_json(result, args.json)
    terminal.render(result, console, html_path=html_path, details=not args.quiet)
    return 0


class _progress:
    """A transient progress bar on a terminal; nothing when output is redirected."""

    def __init__(self, console):
        self.console = console
        self.bar = None

    def __enter__(self):
        if not self.console.is_terminal:
            return None
        from rich.progress import BarColumn, Progress, TextColumn

        self.bar = Progress(TextColumn("[bold]grading[/bold] {task.description}"), BarColumn(),
                            TextColumn("{task.completed} checks"), console=self.console, transient=True)
        self.bar.start()
        self.task = self.bar.add_task("", total=None)
        return lambda exercise, check: self.bar.update(self.task, advance=1, description=exercise.id)

    def __exit__(self, *exc):
        if self.bar:
            self.bar.stop()


def run_list(args) -> int:
    for lab in sorted(discover().values(), key=lambda lab: lab.key):
        print(f"{lab.key}  {lab.module}.py  {lab.title}")
        for exercise in lab.exercises.values():
            print(f"  {exercise.id:<12} {exercise.max_score():>5g} pts  {exercise.title}")
            for check in exercise.checks:
                flag = " (hidden)" if check.hidden else ""
                points = "tip" if check.advice else f"{check.points:g}"  # advice: 0 points
                print(f"      {points:>4}  {check.name}{flag}")
    return 0


def run_gradescope(args) -> int:
    from . import gradescope
    from .course import CourseConfig, CourseConfigError

    try:
        config = CourseConfig.load(args.config) if args.config else CourseConfig()
    except CourseConfigError as exc:
        if args.action == "build":
            print(f"error: {exc}", file=sys.stderr)
            return USAGE_ERROR
        config = CourseConfig()  # inside the container results.json is written regardless
        gradescope.log.error("%s; using the defaults", exc)
    if args.action == "build":
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
    from .bundle import write_student_bundle

    try:
        files = write_student_bundle(args.student)
    except FileExistsError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return USAGE_ERROR
    print(f"wrote {len(files)} files to {args.student}: the student repository "
          "(no reference solutions, no hidden checks)")
    return 0


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    commands = {"grade": run_grade, "list": run_list, "gradescope": run_gradescope, "bundle": run_bundle}
    return commands[args.command](args)


def grade_py_main(argv=None, root: Path | None = None) -> int:
    """``python grade.py [SELECT...] [--submission PATH]``: grade the student's own work."""
    root = root or Path.cwd()
    parser = argparse.ArgumentParser(
        prog="grade.py", description="Grade your labs: python grade.py [lab07 | lab07.ex2 ...]")
    parser.add_argument("--submission", default=str(root / "assignments"),
                        help="folder to grade (default: assignments/)")
    add_grading_options(parser)
    return run_grade(parser.parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
