"""Class throughput of ``autograder batch``: 1 and 2 local workers, and a local Dask cluster.

Generates a class (copies of the reference solutions, skeletons and one wrong
exercise, in equal thirds), grades it from scratch with ``autograder batch`` as an
instructor would (a fresh process each time), and prints submissions per
minute, the 2-vs-1 worker ratio (budget: at least 1.8x on 2 cores), and the
batch's cost per submission against a single ``grade.py`` run of one submission.
A benchmark, not a test: it prints figures, it asserts nothing.

    python benchmarks/bench_batch.py                     # 24 students, lab07
    python benchmarks/bench_batch.py --students 60 --select lab07 lab08
    python benchmarks/bench_batch.py --no-dask
"""

from __future__ import annotations

import argparse
import json
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


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=24)
    parser.add_argument("--select", nargs="*", default=["lab07"], help="lab07 ... (default: lab07)")
    parser.add_argument("--no-dask", action="store_true", help="skip the local Dask cluster")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="bench-batch-") as tmp:
        tmp = Path(tmp)
        make_class(tmp / "class", args.students)
        course = tmp / "course.json"
        course.write_text(json.dumps({"select": args.select}))
        print(f"class of {args.students} students, grading {' '.join(args.select)}")

        single = single_grade(tmp / "class" / "student-000", args.select, tmp)
        print(f"  one grade.py run (fresh process, page and JSON) {single:7.2f} s")

        walls = {}
        for workers in (1, 2):
            walls[workers] = batch(tmp / "class", tmp / f"out-{workers}", course, "--workers", str(workers))
        rerun = batch(tmp / "class", tmp / "out-2", course, "--workers", "2")

        if not args.no_dask:
            try:
                from distributed import LocalCluster
            except ImportError:
                print("  (Dask: distributed is not installed; pip install '.[dask]')")
            else:
                with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster:
                    walls["dask"] = batch(tmp / "class", tmp / "out-dask", course,
                                          "--dask-scheduler", cluster.scheduler_address)

        for label, wall in walls.items():
            name = f"{label} local worker{'s' if label != 1 else ''}" if label != "dask" else "Dask LocalCluster (2x1)"
            print(f"  {name:<28} {wall:7.2f} s   {60 * args.students / wall:6.1f} submissions/min")
        print(f"  2 workers vs 1: {walls[1] / walls[2]:.2f}x   (budget: at least 1.8x on 2 cores)")
        per_submission = walls[1] / args.students
        print(f"  batch cost per submission, 1 worker: {per_submission:.2f} s "
              f"= {per_submission / single:.2f}x a single grade.py run")
        print(f"  re-run with nothing changed: {rerun:.2f} s (the gradebook resumes, grades nothing)")
        size = sum(f.stat().st_size for f in (tmp / "out-1").rglob("*") if f.is_file())
        print(f"  RESULTS with --pictures failing: {size / 2**20:.1f} MB, {size / args.students / 2**10:.0f} KB "
              f"per student (x300 students: {300 * size / args.students / 2**30:.2f} GB)")


if __name__ == "__main__":
    main()
