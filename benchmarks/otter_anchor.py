"""The anchor budget: our whole reference submission against Otter-Grader on a trivial notebook.

Issue 16's budget: the complete reference submission (all six labs, public and
hidden) is graded in less wall time than Otter-Grader takes to grade a trivial
notebook. This script measures both side by side, in one run:

1. builds Otter-Grader (pinned: ``OTTER_VERSION`` below) in its own virtual
   environment under ``~/.cache/autograder-bench/`` (outside the repository,
   reused by later runs);
2. writes a trivial master notebook in Otter Assign's format: 6 questions,
   each a one-line function (``square``, ``is_even``, ``mean``, ``reverse``,
   ``factorial``, ``count_vowels``) with one public and one hidden test cell of
   one ``assert`` each, 12 asserts in all, 2 points a question;
3. ``otter assign`` builds the autograder zip from it (tests run against the
   solutions there), and the student copy it writes is filled in correctly;
4. times, alternating in fresh processes so both see the same load,
   ``otter run -a autograder.zip student.ipynb`` (Otter's own non-containerised
   runner: no Docker, no sandbox) and ``python grade.py --submission
   reference_solutions`` of this repository (all labs, JSON and the HTML page,
   as a student runs it);
5. prints the medians of wall time (the budget: a ratio below 1) and of the
   CPU time of each process tree (far less sensitive to other jobs on a shared
   machine), and their ratios, and writes them with ``--json``.

    python benchmarks/otter_anchor.py                  # medians of 3 alternating runs
    python benchmarks/otter_anchor.py --runs 5 --json anchor.json

If Otter cannot be built (no registry, no network), it says why in one line and
exits with status 2. A benchmark, not a test: it prints figures and asserts nothing.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OTTER_VERSION = "7.0.0"
IPYKERNEL_VERSION = "7.4.0"  # Otter runs notebooks on a Jupyter kernel it does not install itself
CACHE = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "autograder-bench"

# The trivial assignment: name -> (prompt, solution, public assert, hidden assert).
QUESTIONS = {
    "square": ("Return `x` squared.",
               "def square(x):\n    return x * x",
               "assert square(3) == 9", "assert square(-4) == 16"),
    "is_even": ("Return whether `n` is even.",
                "def is_even(n):\n    return n % 2 == 0",
                "assert is_even(4)", "assert not is_even(7)"),
    "mean": ("Return the mean of a non-empty list of numbers.",
             "def mean(values):\n    return sum(values) / len(values)",
             "assert mean([1, 2, 3]) == 2", "assert mean([2.5]) == 2.5"),
    "reverse": ("Return the string `s` reversed.",
                "def reverse(s):\n    return s[::-1]",
                "assert reverse('abc') == 'cba'", "assert reverse('') == ''"),
    "factorial": ("Return `n!` for `n >= 0`.",
                  "def factorial(n):\n    return 1 if n == 0 else n * factorial(n - 1)",
                  "assert factorial(5) == 120", "assert factorial(0) == 1"),
    "count_vowels": ("Return how many vowels (a, e, i, o, u) `s` contains.",
                     "def count_vowels(s):\n    return sum(c in 'aeiou' for c in s.lower())",
                     "assert count_vowels('Otter') == 2", "assert count_vowels('xyz') == 0"),
}
ASSIGNMENT_CONFIG = """# ASSIGNMENT CONFIG
name: trivial
check_all_cell: false
export_cell: false
solutions_pdf: false
generate: true"""


class OtterUnavailable(Exception):
    """Otter-Grader could not be built or could not build the anchor's autograder."""


def last_error(stderr: str, otherwise: str) -> str:
    """The line of a tool's error output that says why (its last ERROR line, or its last line)."""
    lines = [line.strip() for line in stderr.splitlines() if line.strip()]
    errors = [line for line in lines if line.startswith("ERROR")]
    return (errors or lines or [otherwise])[-1]


def otter_environment(version: str = OTTER_VERSION) -> Path:
    """The ``otter`` command of a virtual environment holding Otter-Grader ``version``,
    built once under the cache folder (about a minute) and reused."""
    home = CACHE / f"otter-{version}"
    otter, built = home / "bin" / "otter", home / "built"  # the marker of a finished install
    if built.exists():
        return otter
    print(f"building Otter-Grader {version} in {home} (once) ...", flush=True)
    venv.EnvBuilder(with_pip=True, clear=True).create(home)
    install = subprocess.run([str(home / "bin" / "python"), "-m", "pip", "install", "-q",
                              f"otter-grader=={version}", f"ipykernel=={IPYKERNEL_VERSION}"],
                             capture_output=True, text=True)
    if install.returncode != 0 or not otter.exists():
        reason = last_error(install.stderr, "pip failed")
        raise OtterUnavailable(f"pip could not install otter-grader=={version}: {reason}")
    built.write_text(f"otter-grader=={version}\nipykernel=={IPYKERNEL_VERSION}\n")
    return otter


def master_notebook() -> dict:
    """The trivial assignment in Otter Assign's format (nbformat 4, built as plain JSON)."""
    def cell(kind, source):
        extra = {"outputs": [], "execution_count": None} if kind == "code" else {}
        return {"cell_type": kind, "metadata": {}, "source": source, **extra}

    cells = [cell("raw", ASSIGNMENT_CONFIG), cell("markdown", "# A trivial assignment")]
    for number, (name, (prompt, solution, public, hidden)) in enumerate(QUESTIONS.items(), 1):
        cells += [
            cell("raw", f"# BEGIN QUESTION\nname: q{number}\npoints: 2"),
            cell("markdown", f"**Question {number}.** {prompt}"),
            cell("raw", "# BEGIN SOLUTION"),
            cell("code", f"# BEGIN SOLUTION NO PROMPT\n{solution}\n# END SOLUTION"),
            cell("raw", "# END SOLUTION"),
            cell("raw", "# BEGIN TESTS"),
            cell("code", public),
            cell("code", f"# HIDDEN\n{hidden}"),
            cell("raw", "# END TESTS"),
            cell("raw", "# END QUESTION"),
        ]
    return {"cells": cells, "nbformat": 4, "nbformat_minor": 5,
            "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3",
                                        "language": "python"},
                         "language_info": {"name": "python"}}}


def fill_in(student: dict) -> dict:
    """The student copy with every question answered correctly: the emptied solution cell
    that follows each question's prompt gets the solution."""
    answers = iter(solution for _, solution, _, _ in QUESTIONS.values())
    expecting = False
    for cell in student["cells"]:
        source = "".join(cell["source"])
        if cell["cell_type"] == "markdown" and source.startswith("**Question"):
            expecting = True
        elif expecting and cell["cell_type"] == "code":
            cell["source"] = next(answers)
            expecting = False
    leftover = next(answers, None)
    if leftover is not None:
        raise OtterUnavailable("otter assign wrote a student notebook of an unexpected shape")
    return student


def build_anchor(otter: Path, folder: Path) -> tuple[Path, Path]:
    """``otter assign`` the master notebook; returns (autograder zip, correct student notebook)."""
    master = folder / "trivial.ipynb"
    master.write_text(json.dumps(master_notebook(), indent=1))
    assign = subprocess.run([str(otter), "assign", str(master), str(folder / "dist")],
                            cwd=folder, capture_output=True, text=True)
    zips = sorted((folder / "dist" / "autograder").glob("*.zip"))
    if assign.returncode != 0 or not zips:
        reason = last_error(assign.stderr, "no autograder zip written")
        raise OtterUnavailable(f"otter assign failed: {reason}")
    student = json.loads((folder / "dist" / "student" / "trivial.ipynb").read_text())
    submission = folder / "submission" / "trivial.ipynb"
    submission.parent.mkdir()
    submission.write_text(json.dumps(fill_in(student), indent=1))
    return zips[0], submission


def run_timed(command: list[str], **options) -> tuple[subprocess.CompletedProcess, float, float]:
    """Run a process to its end: (the completed process, wall seconds, CPU seconds of it and
    every descendant it waited for). CPU time depends far less on other jobs than wall time."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    completed = subprocess.run(command, **options)
    wall = time.perf_counter() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return completed, wall, cpu


def time_otter(otter: Path, autograder: Path, submission: Path) -> dict:
    """One ``otter run`` process: wall and CPU time, and the score it gives."""
    with tempfile.TemporaryDirectory(prefix="otter-run-") as out:
        run, wall, cpu = run_timed([str(otter), "run", "-a", str(autograder), "-o", out, "--no-logo",
                                    str(submission)], capture_output=True, text=True)
        results = Path(out) / "results.json"
        if run.returncode != 0 or not results.exists():
            reason = last_error(run.stderr, "no results.json")
            raise OtterUnavailable(f"otter run failed: {reason}")
        tests = json.loads(results.read_text())["tests"]
    return {"wall": wall, "cpu": cpu, "score": sum(t.get("score", 0) for t in tests),
            "max": sum(t.get("max_score", 0) for t in tests)}


def time_grader(selectors=()) -> dict:
    """One ``grade.py`` process on the reference solutions, as a student runs it."""
    with tempfile.TemporaryDirectory(prefix="grade-") as tmp:
        tmp = Path(tmp)
        _, wall, cpu = run_timed([sys.executable, str(ROOT / "grade.py"), "--submission",
                                  str(ROOT / "reference_solutions"), *selectors, "--json", str(tmp / "result.json"),
                                  "--html", str(tmp / "feedback.html"), "--quiet"],
                                 check=True, cwd=tmp, stdout=subprocess.DEVNULL)
        result = json.loads((tmp / "result.json").read_text())
    return {"wall": wall, "cpu": cpu, "score": result["total"], "max": result["max_total"]}


def measure(runs: int = 3, selectors=()) -> dict:
    """Build the anchor, then alternate ``otter run`` and ``grade.py`` ``runs`` times each."""
    otter = otter_environment()
    with tempfile.TemporaryDirectory(prefix="otter-anchor-") as folder:
        autograder, submission = build_anchor(otter, Path(folder))
        otter_runs, grader_runs = [], []
        for _ in range(runs):
            otter_runs.append(time_otter(otter, autograder, submission))
            grader_runs.append(time_grader(selectors))
    figures = {"otter_version": OTTER_VERSION, "runs": runs,
               "notebook": f"{len(QUESTIONS)} questions, {2 * len(QUESTIONS)} asserts"}
    for name, measured in (("otter", otter_runs), ("grader", grader_runs)):
        figures[name] = {"wall_s": statistics.median(r["wall"] for r in measured),
                         "cpu_s": statistics.median(r["cpu"] for r in measured),
                         "walls_s": [r["wall"] for r in measured],
                         "score": f"{measured[0]['score']:g}/{measured[0]['max']:g}"}
    figures["grader"]["labs"] = " ".join(selectors) or "all"
    figures["ratio"] = figures["grader"]["wall_s"] / figures["otter"]["wall_s"]
    figures["cpu_ratio"] = figures["grader"]["cpu_s"] / figures["otter"]["cpu_s"]
    return figures


def report(f: dict) -> None:
    grader, otter = f["grader"], f["otter"]
    labs = "all labs" if grader["labs"] == "all" else grader["labs"]
    print(f"Otter-Grader {f['otter_version']} against grade.py, alternating in fresh processes, "
          f"medians of {f['runs']} runs")
    rows = [(f"otter run, trivial notebook: {f['notebook']} ({otter['score']})", otter),
            (f"grade.py, reference solutions, {labs} ({grader['score']})", grader)]
    for label, figures in rows:
        print(f"  {label:<62} {figures['wall_s']:6.2f} s wall, {figures['cpu_s']:6.2f} s CPU")
    verdict = "met" if f["ratio"] < 1 else "NOT met"
    print(f"  grade.py takes {f['ratio']:.2f}x Otter's wall time (budget: below 1x, {verdict}), "
          f"{f['cpu_ratio']:.2f}x its CPU time")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="alternating runs of each (medians)")
    parser.add_argument("--json", metavar="FILE", help="write the figures as JSON")
    parser.add_argument("select", nargs="*", help="grade only these labs (default: all)")
    args = parser.parse_args()
    try:
        figures = measure(args.runs, args.select)
    except OtterUnavailable as error:
        print(f"otter_anchor: {error}", file=sys.stderr)
        return 2
    report(figures)
    if args.json:
        Path(args.json).write_text(json.dumps(figures, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
