"""Every performance figure of the grader, measured side by side in one run.

    python benchmarks/bench_all.py                     # medians of 3 runs
    python benchmarks/bench_all.py --runs 5 --json figures.json

Prints, for ``python grade.py --submission ...`` run as a student would (a fresh
process each time, reference and skeleton alternating so both see the same load):

- wall time of the complete reference submission (all labs, public and hidden),
  and of each lab alone;
- time inside the student's functions, and the grader's overhead as a share;
- wall time of the untouched skeleton, and its ratio to the reference;
- the worker round trip of a 1-megapixel image (out and back), beyond the
  function's own time;
- peak memory (RSS) of the grader process and of its largest child (the worker);
- the size of the JSON results and of ``feedback.html`` for the reference.

A benchmark, not a test: it prints figures (and writes them with ``--json``)
and asserts nothing.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
LABS = ("lab07", "lab08", "lab09", "lab10", "lab11", "lab12")

# Runs grade.py in this process and reports the peak RSS of the grader (self) and of
# its largest finished descendant (the worker, through its sandbox wrapper).
_MEASURED = """
import json, os, resource, runpy, sys
sys.argv = sys.argv[1:]
try:
    runpy.run_path(sys.argv[0], run_name="__main__")
except SystemExit:
    pass
with open(os.environ["BENCH_RUSAGE"], "w") as out:
    json.dump({"grader_kb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss,
               "worker_kb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss}, out)
"""


# A student's Python caches the grader's bytecode after the first run; an inherited
# PYTHONDONTWRITEBYTECODE would make every measured run compile it all again.
_AS_A_STUDENT = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def grade_once(submission: str, selectors=(), html: bool = False) -> dict:
    """One ``grade.py`` process: wall time, the result's own timings, peak memory, sizes."""
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        results, page, usage = tmp / "result.json", tmp / "feedback.html", tmp / "rusage.json"
        command = [sys.executable, "-c", _MEASURED, str(ROOT / "grade.py"), "--submission",
                   str(ROOT / submission), *selectors, "--json", str(results), "--quiet"]
        command += ["--html", str(page)] if html else ["--no-html"]
        started = time.perf_counter()
        subprocess.run(command, check=True, cwd=tmp, stdout=subprocess.DEVNULL,
                       env={**_AS_A_STUDENT, "BENCH_RUSAGE": str(usage)})
        wall = time.perf_counter() - started
        result = json.loads(results.read_text())
        memory = json.loads(usage.read_text())
        return {"wall": wall, "grading": result["seconds"], "student": result["student_seconds"],
                "score": result["total"], "max": result["max_total"],
                "grader_mb": memory["grader_kb"] / 1024, "worker_mb": memory["worker_kb"] / 1024,
                "json_bytes": results.stat().st_size,
                "html_bytes": page.stat().st_size if html else None}


def median(runs: list[dict], key: str) -> float:
    return statistics.median(r[key] for r in runs)


def round_trip(repeats: int = 20) -> dict:
    """Send a 1000 x 1000 x 3 uint8 image to the worker and get it back (``translate``
    by zero pixels): median wall time per call, and the part outside the function."""
    from autograder.sandbox import Sandbox

    image = np.random.default_rng(0).integers(0, 256, (1000, 1000, 3), dtype=np.uint8)
    walls, inside = [], []
    with Sandbox(ROOT / "reference_solutions") as sandbox:
        sandbox.import_module("lab07_transformations")
        for _ in range(repeats):
            started = time.perf_counter()
            outcome = sandbox.call("lab07_transformations", "translate", (image,), {"tx": 0, "ty": 0})
            walls.append(time.perf_counter() - started)
            inside.append(outcome.seconds)
            assert outcome.ok, outcome.message
    wall, own = statistics.median(walls), statistics.median(inside)
    return {"call_ms": wall * 1e3, "function_ms": own * 1e3, "round_trip_ms": (wall - own) * 1e3}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="runs per figure (medians)")
    parser.add_argument("--json", metavar="FILE", help="write the figures as JSON")
    args = parser.parse_args()

    reference, skeleton = [], []
    for _ in range(args.runs):  # alternating, so both see the same load
        reference.append(grade_once("reference_solutions"))
        skeleton.append(grade_once("assignments"))
    labs = {lab: [grade_once("reference_solutions", [lab]) for _ in range(args.runs)] for lab in LABS}
    page = grade_once("reference_solutions", html=True)
    trip = round_trip()

    wall, student = median(reference, "wall"), median(reference, "student")
    figures = {
        "runs": args.runs,
        "reference": {"wall_s": wall, "grading_s": median(reference, "grading"), "student_s": student,
                      "overhead_share": 1 - student / wall,
                      "score": f"{reference[0]['score']:g}/{reference[0]['max']:g}",
                      "grader_peak_mb": max(r["grader_mb"] for r in reference),
                      "worker_peak_mb": max(r["worker_mb"] for r in reference)},
        "labs": {lab: {"wall_s": median(runs, "wall"), "student_s": median(runs, "student"),
                       "overhead_share": 1 - median(runs, "student") / median(runs, "wall")}
                 for lab, runs in labs.items()},
        "skeleton": {"wall_s": median(skeleton, "wall"), "ratio": median(skeleton, "wall") / wall,
                     "score": f"{skeleton[0]['score']:g}/{skeleton[0]['max']:g}"},
        "worker_round_trip_1mpx": trip,
        "outputs": {"json_bytes": page["json_bytes"], "html_bytes": page["html_bytes"]},
    }
    report(figures)
    if args.json:
        Path(args.json).write_text(json.dumps(figures, indent=2) + "\n")


def report(f: dict):
    ref, skel = f["reference"], f["skeleton"]
    print(f"grade.py as a student runs it, fresh processes, medians of {f['runs']} runs")
    print(f"  reference, all labs ({ref['score']})  {ref['wall_s']:6.2f} s wall, "
          f"{ref['student_s']:.2f} s in student functions, overhead {ref['overhead_share']:.0%}")
    for lab, figures in f["labs"].items():
        print(f"    {lab}                         {figures['wall_s']:6.2f} s wall, "
              f"{figures['student_s']:.2f} s in student functions, overhead {figures['overhead_share']:.0%}")
    print(f"  skeleton ({skel['score']})                {skel['wall_s']:6.2f} s wall, "
          f"{skel['ratio']:.2f}x the reference")
    trip = f["worker_round_trip_1mpx"]
    print(f"  worker call with a 1-megapixel image  {trip['call_ms']:.1f} ms "
          f"({trip['function_ms']:.1f} ms in the function, round trip {trip['round_trip_ms']:.1f} ms)")
    print(f"  peak RSS                              grader {ref['grader_peak_mb']:.0f} MB, "
          f"worker {ref['worker_peak_mb']:.0f} MB")
    out = f["outputs"]
    print(f"  reference outputs                     JSON {out['json_bytes'] / 1e6:.2f} MB, "
          f"feedback.html {out['html_bytes'] / 1e6:.2f} MB")


if __name__ == "__main__":
    main()
