"""What the error model costs: grading a submission that fails everything against one that passes.

For each lab: the reference (passes every check: the error model never runs), and a
submission whose every graded function carries a mutant of its own (the first of its
mutants, simplest operator first, that changes its own ``def``) so that most checks fail
with wrong values -- the error model's worst case. The failing one is graded with the error
model and its repairs of the student's code (twice: the first grading of a process also starts
the helper process, which later gradings reuse) and without them (naming by mutants and by
repairs replaced by nothing), after one warm-up grading
of the reference (ground truth cached). The issue's target: failing with the error model at
most 2x the passing grading.

    python benchmarks/error_model.py                 # lab07 and lab10
    python benchmarks/error_model.py --lab lab08 --lab lab12
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

from autograder.engine.mutants import naming, repair  # noqa: E402
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


def timed(folder: Path, key: str):
    started = time.perf_counter()
    result = grade(folder, [key], pictures="none")
    checks = [c for e in result.exercises for c in e.checks if c.max_score > 0]
    return time.perf_counter() - started, sum(c.score < c.max_score for c in checks), len(checks), \
        sum(c.mistake.startswith(("mutant:", repair.MISTAKE)) for c in checks)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--lab", action="append", help="labs to measure (default lab07, lab10)")
    args = parser.parse_args(argv)
    labs = discover()
    print(f"{'lab':<7}{'passing s':>11}{'first failing s':>17}{'failing s':>11}{'ratio':>7}{'without EM s':>14}"
          f"{'failed':>9}{'named':>7}")
    for key in args.lab or ["lab07", "lab10"]:
        lab = labs[key]
        reference = ROOT / "reference_solutions"
        folder = Path(tempfile.mkdtemp(prefix="error-model-bench-"))
        try:
            (folder / f"{lab.module}.py").write_text(failing_everything(lab))
            timed(reference, key)                      # warm-up: ground truth cached
            passing, _, _, _ = timed(reference, key)
            first, _, _, _ = timed(folder, key)           # starts the helper process (once per process)
            failing, failed, total, named = timed(folder, key)
            keep = naming.name_failure, repair.name_by_repair
            naming.name_failure = repair.name_by_repair = lambda trial, *args, **kwargs: None
            try:
                without, _, _, _ = timed(folder, key)
            finally:
                naming.name_failure, repair.name_by_repair = keep
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        print(f"{key:<7}{passing:>11.1f}{first:>17.1f}{failing:>11.1f}{failing / passing:>7.2f}{without:>14.1f}"
              f"{f'{failed}/{total}':>9}{named:>7}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
