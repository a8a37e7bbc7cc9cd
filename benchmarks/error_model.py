"""What naming costs: grading a submission that fails everything against one that passes.

For each lab, and for the whole submission (every lab at once, in as many lanes as ``grade.py``
uses here): the reference (passes every check: nothing is named), and a submission whose every
graded function carries a mutant of its own (the first of its mutants, simplest operator first,
that changes its own ``def``) so that most checks fail with wrong values -- naming's worst case.
The failing one is graded twice (the first grading of a process also starts the helper
process, which later gradings reuse) after one warm-up grading of the reference (ground truth
cached), and once more with no time to name. The issue's target: failing at most 2x the passing
grading. What the student's own code takes is the student's (a mutant may loop longer than the
reference): the wall-clock seconds of the student's calls are shown beside. Naming's time is
bounded per failed check and per grading (``naming.GRADING_SECONDS`` for the error model and the
repairs, ``traced.GRADING_SECONDS`` for the recordings, ``inherited.GRADING_SECONDS``); the authors'
guide (docs/authors/judges.md, "Cost") says why those bounds are not cut to meet the ratio.

    python benchmarks/error_model.py                 # lab07, lab10 and the whole submission
    python benchmarks/error_model.py --lab lab08 --lab lab12
    python benchmarks/error_model.py --lab all       # every lab, then the whole submission
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
os.environ.setdefault("AUTOGRADER_CACHE_DIR", tempfile.mkdtemp(prefix="error-model-bench-"))

from autograder.cli import lanes_for  # noqa: E402
from autograder.engine import inherited, traced  # noqa: E402
from autograder.engine.mutants import naming  # noqa: E402
from autograder.engine.mutants.operators import apply_edits  # noqa: E402
from autograder.engine.registry import discover  # noqa: E402
from autograder.engine.runner import grade  # noqa: E402


def failing_everything(lab) -> str:
    """The reference module with one mutant in every graded function's own def."""
    model = naming.model_for(lab)
    edits = []
    for function, mutants in sorted(model.mutants.items()):
        own = [m for m in mutants if m.where == function and m.operator not in ("drop_statement", "other_name")]
        if own:
            edits += own[0].edits
    return apply_edits(model.source, edits)


def timed(folder: Path, keys: list[str], lanes: int = 1):
    """(seconds, the student's seconds, checks failed, checks graded, checks named) of one grading."""
    started = time.perf_counter()
    result = grade(folder, keys, pictures="none", lanes=lanes)
    seconds = time.perf_counter() - started
    checks = [c for e in result.exercises for c in e.checks if c.max_score > 0]
    return seconds, result.student_wall_seconds, sum(c.score < c.max_score for c in checks), len(checks), \
        sum(bool(c.mistake) for c in checks)


def unnamed(folder: Path, keys: list[str], lanes: int):
    """:func:`timed` with no time for naming: every namer's time for the grading 0 (each stops at once)."""
    kept = naming.GRADING_SECONDS, traced.GRADING_SECONDS, inherited.GRADING_SECONDS
    naming.GRADING_SECONDS = traced.GRADING_SECONDS = inherited.GRADING_SECONDS = 0.0
    try:
        return timed(folder, keys, lanes)
    finally:
        naming.GRADING_SECONDS, traced.GRADING_SECONDS, inherited.GRADING_SECONDS = kept


def measured(name: str, labs: list, lanes: int = 1) -> None:
    """One row: ``labs`` graded passing, failing everything, and failing everything with no time to name."""
    reference = ROOT / "reference_solutions"
    folder = Path(tempfile.mkdtemp(prefix="error-model-bench-"))
    keys = [lab.key for lab in labs]
    try:
        for lab in labs:
            (folder / f"{lab.module}.py").write_text(failing_everything(lab))
        timed(reference, keys, lanes)                      # warm-up: ground truth cached
        passing, passing_own, _, _, _ = timed(reference, keys, lanes)
        first = timed(folder, keys, lanes)[0]             # starts the helper process (once per process)
        failing, failing_own, failed, total, named = timed(folder, keys, lanes)
        plain = unnamed(folder, keys, lanes)[0]
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print(f"{name:<8}{passing:>9.1f}{first:>8.1f}{failing:>9.1f}{plain:>9.1f}{failing / passing:>8.2f}"
          f"{failing / plain:>8.2f}{passing_own:>10.1f}{failing_own:>6.1f}{f'{failed}/{total}':>9}{named:>7}", flush=True)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--lab", action="append", help="labs to measure (default lab07, lab10); all: every lab")
    parser.add_argument("--whole", action=argparse.BooleanOptionalAction, default=True,
                        help="also the whole submission, every lab at once (default: yes)")
    args = parser.parse_args(argv)
    labs = discover()
    chosen = args.lab or ["lab07", "lab10"]
    chosen = sorted(labs) if chosen == ["all"] else chosen
    print(f"{'':<8}{'passing':>9}{'failing everything':>26}{'failing / passing':>18}{'student s':>16}")
    print(f"{'graded':<8}{'s':>9}{'first s':>8}{'s':>9}{'unnamed':>9}{'ratio':>8}{'/unnamed':>8}"
          f"{'passing':>10}{'fail':>6}{'failed':>9}{'named':>7}")
    for key in chosen:
        measured(key, [labs[key]])
    if args.whole:
        measured("all six", [labs[key] for key in sorted(labs)], lanes_for([]))
    print("first: the process's first failing grading (it starts the helper); unnamed: failing with no time to name;"
          " student s: the student's own calls' wall-clock seconds, passing and failing")
    return 0


if __name__ == "__main__":
    sys.exit(main())
