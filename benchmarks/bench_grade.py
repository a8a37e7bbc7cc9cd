"""How long grading takes, and how much of it is the student's code.

Runs ``python grade.py --submission reference_solutions SELECT...`` as a user
would (a fresh process each time) and prints wall time, time inside student
functions, and grader overhead. A benchmark, not a test: it prints figures.

    python benchmarks/bench_grade.py            # lab07, 3 runs
    python benchmarks/bench_grade.py lab08 --runs 5
    python benchmarks/bench_grade.py all
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def one_run(selectors: list[str]) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "result.json"
        start = time.perf_counter()
        subprocess.run([sys.executable, str(ROOT / "grade.py"), "--submission",
                        str(ROOT / "reference_solutions"), *selectors, "--json", str(out),
                        "--no-html", "--quiet"], check=True, cwd=tmp, stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - start
        result = json.loads(out.read_text())
    return {"wall": wall, "grading": result["seconds"], "student": result["student_seconds"],
            "score": f'{result["total"]:g}/{result["max_total"]:g}'}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("select", nargs="*", default=["lab07"], help="lab07 ... or 'all'")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    selectors = [] if args.select == ["all"] else args.select
    runs = [one_run(selectors) for _ in range(args.runs)]
    median = {k: statistics.median(r[k] for r in runs) for k in ("wall", "grading", "student")}
    overhead = median["grading"] - median["student"]
    print(f"grading reference_solutions {' '.join(selectors) or '(all labs)'}: "
          f"score {runs[0]['score']}, median of {args.runs} runs")
    print(f"  process wall time        {median['wall']:7.2f} s   (start-up and imports included)")
    print(f"  grading time             {median['grading']:7.2f} s")
    print(f"  inside student functions {median['student']:7.2f} s")
    print(f"  grader overhead          {overhead:7.2f} s   ({overhead / median['grading']:.0%} of grading)")


if __name__ == "__main__":
    main()
