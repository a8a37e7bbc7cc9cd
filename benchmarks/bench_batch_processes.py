"""Where a batch's gradings run: grading processes forked from the server, or spawned.

Three figures, each with the processes forked (the default) and spawned
(``AUTOGRADER_FORKSERVER=off``), taking turns:

- start-up: from a :class:`GradingPool` of 2 processes made to both being ready
  to grade (the grader imported), the server having imported it already (as it
  does while a batch reads the class); medians of ``--rounds``;
- per grading: a lab07 grading of the reference solution in one process, its
  wall and CPU time (the first of each process left out: it warms the caches);
- whole batches: ``autograder batch`` on ``bench_batch.py``'s class (``--students``,
  2 workers), interleaved pairs, medians.

A benchmark, not a test: it prints figures, it asserts nothing.

    python benchmarks/bench_batch_processes.py                  # 24 students, 6 pairs
    python benchmarks/bench_batch_processes.py --pairs 0        # start-up only
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
import time
from multiprocessing import get_context
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")   # as the command line has it

import bench_batch  # noqa: E402


def ready() -> int:
    """What a grading process does before its first grading: import the grader."""
    import autograder.instructor.batch.task  # noqa: F401
    import autograder.reports.html  # noqa: F401
    import autograder.engine.runner  # noqa: F401

    return os.getpid()


def timed_grading(*arguments) -> dict:
    """``grade_files(*arguments)`` in a grading process: its wall and CPU time there."""
    from autograder.instructor.batch.task import grade_files

    wall, cpu = time.perf_counter(), time.process_time()
    outcome = grade_files(*arguments)
    if "result" not in outcome:
        raise RuntimeError(outcome.get("error"))
    return {"wall": time.perf_counter() - wall, "cpu": time.process_time() - cpu}


def per_grading(context, gradings: int = 4) -> list[dict]:
    import inspect

    from autograder.instructor.batch.processes import GradingPool
    from autograder.instructor.batch.task import grade_files

    reference = (bench_batch.ROOT / "reference_solutions" / "lab07_transformations.py").read_bytes()
    given = {"files": {"lab07_transformations.py": reference}, "selectors": ["lab07"], "call_timeout": 10.0,
             "pictures": "failed", "threads": 1}
    with GradingPool(1, timed_grading, context=context) as pool:
        for i in range(gradings):
            named = inspect.signature(grade_files).bind_partial(**given, name=f"student-{i}").arguments
            # the parameters this benchmark does not know take what a default course gives them
            parameters = inspect.signature(grade_files).parameters
            pool.submit(str(i), tuple(named[p] if p in named else _course_default(p) for p in parameters))
        return [outcome for _, outcome in sorted(pool.outcomes(), key=lambda kv: int(kv[0]))][1:]


def _course_default(parameter: str):
    from autograder.instructor.course import CourseConfig

    return getattr(CourseConfig(), parameter)


def start_up(context, processes: int = 2) -> float:
    from autograder.instructor.batch.processes import GradingPool

    start = time.perf_counter()
    with GradingPool(processes, ready, context=context) as pool:
        for i in range(processes):
            pool.submit(str(i), ())
        list(pool.outcomes())
    return time.perf_counter() - start


def measure(students: int = 24, pairs: int = 6, rounds: int = 10) -> dict:
    from autograder.instructor.batch.processes import grading_processes

    forked = grading_processes()
    if forked.get_start_method() != "forkserver":
        raise SystemExit("no fork server here: nothing to compare")
    ready()            # the server imports the grader meanwhile
    time.sleep(2)
    starts = {"forked": [], "spawned": []}
    for _ in range(rounds):
        starts["forked"].append(start_up(forked))
        starts["spawned"].append(start_up(get_context("spawn")))
    gradings = {"forked": [], "spawned": []}
    for k in range(max(2, rounds // 2)):
        for mode in (("forked", "spawned") if k % 2 == 0 else ("spawned", "forked")):
            gradings[mode] += per_grading(forked if mode == "forked" else get_context("spawn"))
    walls = {"forked": [], "spawned": []}
    with tempfile.TemporaryDirectory(prefix="bench-processes-") as tmp:
        tmp = Path(tmp)
        bench_batch.make_class(tmp / "class", students)
        course = tmp / "course.json"
        course.write_text(json.dumps({"select": ["lab07"]}))
        for k in range(pairs):
            for mode in (("forked", "spawned") if k % 2 == 0 else ("spawned", "forked")):
                if mode == "spawned":
                    os.environ["AUTOGRADER_FORKSERVER"] = "off"
                else:
                    os.environ.pop("AUTOGRADER_FORKSERVER", None)
                walls[mode].append(bench_batch.batch(tmp / "class", tmp / f"out-{mode}-{k}", course,
                                                     "--workers", "2"))
        os.environ.pop("AUTOGRADER_FORKSERVER", None)
    return {"students": students, "start_up_s": starts, "gradings": gradings, "batch_s": walls,
            "load": os.getloadavg()[0]}


def report(f: dict) -> None:
    print("a pool of 2 grading processes, from its start to both ready to grade (the grader imported):")
    for mode, times in f["start_up_s"].items():
        print(f"  {mode:<8} {statistics.median(times):6.2f} s   "
              f"(median of {len(times)}; min {min(times):.2f} s)")
    print("a lab07 grading of the reference, in the grading process (medians):")
    for mode, times in f["gradings"].items():
        print(f"  {mode:<8} {statistics.median(t['wall'] for t in times):6.3f} s wall, "
              f"{statistics.median(t['cpu'] for t in times):.3f} s CPU   ({len(times)} gradings)")
    if any(f["batch_s"].values()):
        print(f"autograder batch, {f['students']} students, lab07, 2 workers, interleaved pairs:")
        for mode, walls in f["batch_s"].items():
            print(f"  {mode:<8} {statistics.median(walls):6.2f} s   (median of {len(walls)}: "
                  + ", ".join(f"{w:.1f}" for w in walls) + ")")
    print(f"  (load average at the end: {f['load']:.1f})")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=24)
    parser.add_argument("--pairs", type=int, default=6, help="pairs of whole batches (0: start-up only)")
    parser.add_argument("--rounds", type=int, default=10, help="start-ups of each kind")
    args = parser.parse_args()
    report(measure(args.students, args.pairs, args.rounds))


if __name__ == "__main__":
    main()
