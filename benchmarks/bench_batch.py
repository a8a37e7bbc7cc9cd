"""Class throughput of ``autograder batch``: 1 and 2 local workers, and a local Dask cluster.

Generates a class of the size the grader is built for (300 submissions: copies
of the reference solutions, skeletons and one wrong exercise, in equal thirds),
grades it from scratch with ``autograder batch`` as an instructor would (a fresh
process each time; 1 and 2 workers take turns, so both see the same load,
medians over the rounds), and prints submissions per minute, the 2-vs-1 worker
ratio (budget: at least 1.8x on 2 cores), and the batch's cost per submission
against a single ``grade.py`` run of one submission.
A benchmark, not a test: it prints figures, it asserts nothing.

    python benchmarks/bench_batch.py                     # 300 students, lab07, 3 rounds
    python benchmarks/bench_batch.py --students 48       # a small class: start-up weighs more
    python benchmarks/bench_batch.py --students 60 --select lab07 lab08 --rounds 5
    python benchmarks/bench_batch.py --no-dask
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
WRONG_WAY = '''
def translate(image, tx=100, ty=50):
    return _warp(image, translation_matrix(-tx, -ty))
'''


def make_class(folder: Path, students: int) -> None:
    for i in range(students):
        student = folder / f"student-{i:03d}"
        student.mkdir(parents=True)
        for module in (ROOT / "reference_solutions").glob("lab*.py"):
            kind = i % 3
            source = (ROOT / ("assignments" if kind == 1 else "reference_solutions") / module.name).read_text()
            if kind == 2 and module.stem == "lab07_transformations":
                source += WRONG_WAY
            (student / module.name).write_text(source)


def batch(submissions: Path, out: Path, course: Path, *extra: str) -> float:
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "autograder", "batch", str(submissions), "--out", str(out),
                    "--course", str(course), *extra], check=True, cwd=ROOT, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def single_grade(submission: Path, selectors: list[str], tmp: Path) -> float:
    start = time.perf_counter()
    subprocess.run([sys.executable, str(ROOT / "grade.py"), "--submission", str(submission), *selectors,
                    "--json", str(tmp / "single.json"), "--html", str(tmp / "single.html"), "--quiet"],
                   check=True, cwd=tmp, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def measure(students: int = 300, select=("lab07",), dask: bool = True, rounds: int = 3) -> dict:
    """Grade a generated class with 1 and 2 local workers, taking turns for ``rounds``
    rounds (and once on a local Dask cluster): median wall times, the 2-vs-1 ratio,
    the cost per submission and the results' size."""
    select = list(select)
    with tempfile.TemporaryDirectory(prefix="bench-batch-") as tmp:
        tmp = Path(tmp)
        make_class(tmp / "class", students)
        course = tmp / "course.json"
        course.write_text(json.dumps({"select": select}))

        single = single_grade(tmp / "class" / "student-000", select, tmp)
        runs = {"1": [], "2": []}
        for round_ in range(rounds):
            for workers in runs:
                out = tmp / f"out-{workers}-{round_}"
                runs[workers].append(batch(tmp / "class", out, course, "--workers", workers))
        walls = {workers: statistics.median(times) for workers, times in runs.items()}
        rerun = batch(tmp / "class", tmp / "out-2-0", course, "--workers", "2")

        dask_note = None
        if dask:
            try:
                from distributed import LocalCluster
            except ImportError:
                dask_note = "distributed is not installed; pip install '.[dask]'"
            else:
                with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster:
                    walls["dask"] = batch(tmp / "class", tmp / "out-dask", course,
                                          "--dask-scheduler", cluster.scheduler_address)
        size = sum(f.stat().st_size for f in (tmp / "out-1-0").rglob("*") if f.is_file())
    return {"students": students, "select": select, "single_grade_s": single, "rounds": rounds,
            "runs_s": runs, "wall_s": walls,
            "per_minute": {label: 60 * students / wall for label, wall in walls.items()},
            "ratio_2_vs_1": walls["1"] / walls["2"],
            "per_submission_s": walls["1"] / students,
            "per_submission_vs_single": walls["1"] / students / single,
            "rerun_s": rerun, "results_bytes": size, "dask_note": dask_note}


def report(f: dict) -> None:
    print(f"class of {f['students']} students, grading {' '.join(f['select'])}; "
          f"1 and 2 workers taking turns, medians of {f['rounds']} rounds")
    print(f"  one grade.py run (fresh process, page and JSON) {f['single_grade_s']:7.2f} s")
    for label, wall in f["wall_s"].items():
        name = ("Dask LocalCluster (2x1)" if label == "dask"
                else f"{label} local worker{'s' if label != '1' else ''}")
        print(f"  {name:<28} {wall:7.2f} s   {f['per_minute'][label]:6.1f} submissions/min")
    if f["dask_note"]:
        print(f"  (Dask: {f['dask_note']})")
    verdict = "met" if f["ratio_2_vs_1"] >= 1.8 else "NOT met"
    print(f"  2 workers vs 1: {f['ratio_2_vs_1']:.2f}x   (budget: at least 1.8x on 2 cores, {verdict})")
    print(f"  batch cost per submission, 1 worker: {f['per_submission_s']:.2f} s "
          f"= {f['per_submission_vs_single']:.2f}x a single grade.py run")
    print(f"  re-run with nothing changed: {f['rerun_s']:.2f} s (the gradebook resumes, grades nothing)")
    size, students = f["results_bytes"], f["students"]
    print(f"  RESULTS with --pictures failing: {size / 2**20:.1f} MB, {size / students / 2**10:.0f} KB "
          f"per student (x300 students: {300 * size / students / 2**30:.2f} GB)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=300)
    parser.add_argument("--select", nargs="*", default=["lab07"], help="lab07 ... (default: lab07)")
    parser.add_argument("--rounds", type=int, default=3, help="rounds of 1 then 2 workers (medians)")
    parser.add_argument("--no-dask", action="store_true", help="skip the local Dask cluster")
    args = parser.parse_args()
    report(measure(args.students, args.select, dask=not args.no_dask, rounds=args.rounds))


if __name__ == "__main__":
    main()
