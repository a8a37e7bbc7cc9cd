"""Every performance figure of the grader, measured side by side in one run.

    python benchmarks/bench_all.py                       # every section, medians of 3 runs
    python benchmarks/bench_all.py --otter               # ... and the Otter-Grader anchor
    python benchmarks/bench_all.py --runs 5 --json figures.json
    python benchmarks/bench_all.py --only grade trip     # some sections only

Sections (all by default; ``--only`` picks some):

- ``grade``: ``python grade.py --submission ...`` run as a student runs it (a
  fresh process, JSON and the HTML page written; wall time, and the CPU time of
  the process tree, which depends far less on other jobs), the complete reference
  submission (all labs, public and hidden) and the untouched skeleton
  ALTERNATING, so both see the same load; with ``--otter`` Otter-Grader's
  ``otter run`` on a trivial notebook takes its turn in the same rotation
  (``otter_anchor.py``: built once in its own venv). Wall time, the wall time
  during which student functions ran (in any lane: grade.py grades labs side by
  side, a worker per core) and the grader's overhead, the rest, as a share; the skeleton's
  ratio to the reference, peak memory (RSS) of the grader process and of its
  largest child (the worker), the size of the JSON results and of
  ``feedback.html`` and whether the JSON holds pictures;
- ``labs``: each lab alone (JSON only, no page), wall time and overhead;
- ``trip``: the worker round trip of a 1-megapixel image (out and back),
  beyond the function's own time;
- ``batch``: ``autograder batch`` on a generated class with 1 and 2 local
  workers taking turns (``--runs`` rounds, medians), submissions per minute and
  the 2-vs-1 ratio (``bench_batch.py``);
- ``stereo``: the lab 12 quality/time table, reference matchers against
  OpenCV's on the Middlebury motorcycle pair (``bench_stereo.py``).

Every figure is printed, next to its budget from issue 16 where it has one,
and written with ``--json`` (with the time and the load average) so runs can
be compared. A benchmark, not a test: it asserts nothing.
"""

from __future__ import annotations

import argparse
import datetime
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
sys.path.insert(0, str(ROOT / "benchmarks"))

import bench_batch  # noqa: E402  (benchmarks/ is not a package)
import bench_stereo  # noqa: E402
import otter_anchor  # noqa: E402

LABS = ("lab07", "lab08", "lab09", "lab10", "lab11", "lab12")
SECTIONS = ("grade", "labs", "trip", "batch", "stereo")
BUDGETS = {  # issue 16, on the 2-core machine
    "anchor": "below 1x Otter's time on the trivial notebook",
    "overhead": "at most 50% of the wall time",
    "skeleton": "at most 0.2x the reference",
    "html": "at most 2 MB",
    "json": "no pictures by default",
}

# Runs grade.py in this process and reports, as it exits (grade.py leaves with os._exit
# once its exit handlers have run), the peak RSS of the grader (self) and of its largest
# finished descendant (the worker, through its sandbox wrapper).
_MEASURED = """
import atexit, json, os, resource, runpy, sys

def dump():
    with open(os.environ["BENCH_RUSAGE"], "w") as out:
        json.dump({"grader_kb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss,
                   "worker_kb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss}, out)

atexit.register(dump)
sys.argv = sys.argv[1:]
runpy.run_path(sys.argv[0], run_name="__main__")
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
        _, wall, cpu = otter_anchor.run_timed(command, check=True, cwd=tmp, stdout=subprocess.DEVNULL,
                                              env={**_AS_A_STUDENT, "BENCH_RUSAGE": str(usage)})
        result = json.loads(results.read_text())
        memory = json.loads(usage.read_text())
        # Overhead is the wall time during which no student code ran in any lane (the labs are
        # graded side by side, a lane per core): the summed student time would hide it.
        return {"wall": wall, "cpu": cpu, "grading": result["seconds"],
                "student": result.get("student_wall_seconds", result["student_seconds"]),
                "student_sum": result["student_seconds"],
                "score": result["total"], "max": result["max_total"],
                "grader_mb": memory["grader_kb"] / 1024, "worker_mb": memory["worker_kb"] / 1024,
                "json_bytes": results.stat().st_size,
                "json_pictures": sum(len(check["artifacts"]) for exercise in result["exercises"]
                                     for check in exercise["checks"]),
                "html_bytes": page.stat().st_size if html else None}


def median(runs: list[dict], key: str) -> float:
    return statistics.median(r[key] for r in runs)


def measure_grade(runs: int, anchor: tuple | None) -> dict:
    """Reference, skeleton (and ``otter run`` on the anchor, if given) alternating."""
    reference, skeleton, otter_runs = [], [], []
    for _ in range(runs):
        reference.append(grade_once("reference_solutions", html=True))
        skeleton.append(grade_once("assignments", html=True))
        if anchor:
            otter_runs.append(otter_anchor.time_otter(*anchor))
    wall, student = median(reference, "wall"), median(reference, "student")
    figures = {
        "reference": {"wall_s": wall, "cpu_s": median(reference, "cpu"), "grading_s": median(reference, "grading"),
                      "student_s": student, "student_summed_over_lanes_s": median(reference, "student_sum"),
                      "overhead_share": 1 - student / wall,
                      "score": f"{reference[0]['score']:g}/{reference[0]['max']:g}",
                      "grader_peak_mb": max(r["grader_mb"] for r in reference),
                      "worker_peak_mb": max(r["worker_mb"] for r in reference)},
        "skeleton": {"wall_s": median(skeleton, "wall"), "cpu_s": median(skeleton, "cpu"),
                     "ratio": median(skeleton, "wall") / wall,
                     "score": f"{skeleton[0]['score']:g}/{skeleton[0]['max']:g}"},
        "outputs": {"json_bytes": reference[0]["json_bytes"], "json_pictures": reference[0]["json_pictures"],
                    "html_bytes": reference[0]["html_bytes"]},
    }
    if anchor:
        otter_wall = median(otter_runs, "wall")
        figures["otter_anchor"] = {
            "otter_version": otter_anchor.OTTER_VERSION,
            "notebook": f"{len(otter_anchor.QUESTIONS)} questions, {2 * len(otter_anchor.QUESTIONS)} asserts",
            "otter_wall_s": otter_wall, "otter_cpu_s": median(otter_runs, "cpu"),
            "cpu_ratio": median(reference, "cpu") / median(otter_runs, "cpu"),
            "otter_score": f"{otter_runs[0]['score']:g}/{otter_runs[0]['max']:g}",
            "ratio": wall / otter_wall}
    return figures


def measure_labs(runs: int) -> dict:
    labs = {lab: [grade_once("reference_solutions", [lab]) for _ in range(runs)] for lab in LABS}
    return {lab: {"wall_s": median(r, "wall"), "student_s": median(r, "student"),
                  "overhead_share": 1 - median(r, "student") / median(r, "wall")}
            for lab, r in labs.items()}


def round_trip(repeats: int = 20) -> dict:
    """Send a 1000 x 1000 x 3 uint8 image to the worker and get it back (``translate``
    by zero pixels): median wall time per call, and the part outside the function."""
    from autograder.sandbox.supervisor import Sandbox

    image = np.random.default_rng(0).integers(0, 256, (1000, 1000, 3), dtype=np.uint8)
    walls, inside = [], []
    with Sandbox(ROOT / "reference_solutions") as sandbox:
        sandbox.import_module("lab07_transformations")
        for _ in range(repeats):
            started = time.perf_counter()
            outcome = sandbox.call("lab07_transformations", "translate", (image,), {"tx": 0, "ty": 0})
            walls.append(time.perf_counter() - started)
            inside.append(outcome.seconds)
            if not outcome.ok:
                raise RuntimeError(f"the reference translate failed in the worker: {outcome.message}")
    wall, own = statistics.median(walls), statistics.median(inside)
    return {"call_ms": wall * 1e3, "function_ms": own * 1e3, "round_trip_ms": (wall - own) * 1e3}


def machine_state() -> dict:
    return {"utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M"),
            "load_average": [round(load, 2) for load in os.getloadavg()], "cores": os.cpu_count()}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="sections: " + ", ".join(SECTIONS))
    parser.add_argument("--runs", type=int, default=3,
                        help="runs per grade.py figure, rounds of the batch section (medians)")
    parser.add_argument("--only", nargs="+", choices=SECTIONS, metavar="SECTION",
                        help="measure only these sections (default: all)")
    parser.add_argument("--otter", action="store_true",
                        help="also time Otter-Grader on a trivial notebook in the grade rotation "
                             "(builds it once in ~/.cache/autograder-bench)")
    parser.add_argument("--students", type=int, default=300,
                        help="class size for the batch section (default: 300, a class as the grader is "
                             "built for; on a small class the batch's fixed start-up, about 0.4 s, "
                             "weighs more)")
    parser.add_argument("--batch-labs", nargs="+", default=["lab07"], metavar="LAB",
                        help="labs graded in the batch section (default: lab07)")
    parser.add_argument("--dask", action="store_true", help="batch section: also a local Dask cluster")
    parser.add_argument("--json", metavar="FILE", help="write the figures as JSON")
    parser.add_argument("--markdown", action="store_true",
                        help="also print the figures as the README's Markdown tables")
    args = parser.parse_args()
    sections = args.only or SECTIONS
    if args.otter and "grade" not in sections:
        parser.error("--otter runs in the grade section's rotation: add 'grade' to --only")

    figures = {"runs": args.runs}
    with tempfile.TemporaryDirectory(prefix="otter-anchor-") as folder:
        anchor = None  # (otter command, autograder zip, correct student notebook)
        if args.otter:
            try:
                otter = otter_anchor.otter_environment()
                anchor = (otter, *otter_anchor.build_anchor(otter, Path(folder)))
            except otter_anchor.OtterUnavailable as error:
                print(f"bench_all: {error}", file=sys.stderr)
                return 2
        figures["started"] = machine_state()
        if "grade" in sections:
            figures.update(measure_grade(args.runs, anchor))
    if "labs" in sections:
        figures["labs"] = measure_labs(args.runs)
    if "trip" in sections:
        figures["worker_round_trip_1mpx"] = round_trip()
    if "batch" in sections:
        figures["batch"] = bench_batch.measure(args.students, args.batch_labs, dask=args.dask, rounds=args.runs)
    if "stereo" in sections:
        figures["stereo"] = bench_stereo.measure()
    figures["finished"] = machine_state()

    report(figures)
    if args.markdown:
        print("\n" + markdown(figures))
    if args.json:
        Path(args.json).write_text(json.dumps(figures, indent=2) + "\n")
    return 0


def load(f: dict) -> str:
    """The machine's load while measuring: at the start, at the end, over the last 5 minutes."""
    start, end = f["started"]["load_average"], f["finished"]["load_average"]
    return (f"load average {start[0]:.1f} at the start, {end[0]:.1f} at the end "
            f"({end[1]:.1f} over the last 5 minutes)")


def met(ok: bool) -> str:
    return "met" if ok else "NOT met"


def report(f: dict) -> None:
    start, end = f["started"], f["finished"]
    print(f"{start['utc']} to {end['utc']} UTC, {start['cores']} cores, {load(f)}")
    if "reference" in f:
        ref, skel, out = f["reference"], f["skeleton"], f["outputs"]
        print(f"\ngrade.py as a student runs it (fresh processes, JSON and page), alternating, "
              f"medians of {f['runs']} runs")
        print(f"  reference, all labs ({ref['score']})  {ref['wall_s']:6.2f} s wall ({ref['cpu_s']:.2f} s CPU), "
              f"{ref['student_s']:.2f} s with student functions running "
              f"({ref['student_summed_over_lanes_s']:.2f} s summed over the lanes), overhead {ref['overhead_share']:.0%}"
              f"   [{BUDGETS['overhead']}: {met(ref['overhead_share'] <= 0.5)}]")
        print(f"  skeleton ({skel['score']})                {skel['wall_s']:6.2f} s wall ({skel['cpu_s']:.2f} s CPU), "
              f"{skel['ratio']:.2f}x the reference   [{BUDGETS['skeleton']}: {met(skel['ratio'] <= 0.2)}]")
        if "otter_anchor" in f:
            anchor = f["otter_anchor"]
            print(f"  Otter-Grader {anchor['otter_version']}, trivial notebook ({anchor['otter_score']}) "
                  f"{anchor['otter_wall_s']:6.2f} s wall ({anchor['otter_cpu_s']:.2f} s CPU; `otter run`, "
                  f"{anchor['notebook']})")
            print(f"    the reference takes {anchor['ratio']:.2f}x Otter's wall time   "
                  f"[{BUDGETS['anchor']}: {met(anchor['ratio'] < 1)}], {anchor['cpu_ratio']:.2f}x its CPU time")
        print(f"  peak RSS                              grader {ref['grader_peak_mb']:.0f} MB, "
              f"worker {ref['worker_peak_mb']:.0f} MB")
        print(f"  reference outputs                     JSON {out['json_bytes'] / 1e6:.2f} MB "
              f"({out['json_pictures']} pictures) [{BUDGETS['json']}: {met(out['json_pictures'] == 0)}], "
              f"feedback.html {out['html_bytes'] / 1e6:.2f} MB [{BUDGETS['html']}: "
              f"{met(out['html_bytes'] <= 2e6)}]")
    if "labs" in f:
        print(f"\neach lab alone (reference, JSON only), medians of {f['runs']} runs")
        for lab, figures in f["labs"].items():
            print(f"  {lab}  {figures['wall_s']:6.2f} s wall, {figures['student_s']:.2f} s in student "
                  f"functions, overhead {figures['overhead_share']:.0%}")
    if "worker_round_trip_1mpx" in f:
        trip = f["worker_round_trip_1mpx"]
        print(f"\nworker call with a 1-megapixel image  {trip['call_ms']:.1f} ms "
              f"({trip['function_ms']:.1f} ms in the function, round trip {trip['round_trip_ms']:.1f} ms)")
    if "batch" in f:
        print("\nautograder batch")
        bench_batch.report(f["batch"])
    if "stereo" in f:
        print("\nstereo, lab 12")
        bench_stereo.report(f["stereo"])


def markdown(f: dict) -> str:
    """The figures as the README quotes them: one table, each budget beside its figure."""
    def verdict(ok: bool) -> str:
        return "met" if ok else "**not met**"

    start, end = f["started"], f["finished"]
    lines = [f"Measured {start['utc']}-{end['utc'][-5:]} UTC on {start['cores']} cores, {load(f)}; "
             f"medians of {f['runs']} runs:", "",
             "| figure | measured | budget (issue 16) |", "|---|---|---|"]

    def row(*cells: str) -> None:
        lines.append("| " + " | ".join(cells) + " |")

    if "reference" in f:
        ref, skel, out = f["reference"], f["skeleton"], f["outputs"]
        row(f"complete reference submission ({ref['score']}, public and hidden), wall (CPU)",
            f"{ref['wall_s']:.2f} s ({ref['cpu_s']:.2f} s)", "")
        if "otter_anchor" in f:
            anchor = f["otter_anchor"]
            row(f"Otter-Grader {anchor['otter_version']} `otter run`, trivial notebook "
                f"({anchor['notebook']}), wall (CPU)",
                f"{anchor['otter_wall_s']:.2f} s ({anchor['otter_cpu_s']:.2f} s)", "")
            row("reference / Otter, wall (CPU)", f"{anchor['ratio']:.2f}x ({anchor['cpu_ratio']:.2f}x)",
                f"wall below 1x: {verdict(anchor['ratio'] < 1)}")
        row("wall time with student functions running in some lane (summed over the lanes) / "
            "grader overhead (the rest of the wall time)", f"{ref['student_s']:.2f} s "
            f"({ref['student_summed_over_lanes_s']:.2f} s) / {ref['overhead_share']:.0%}",
            f"overhead at most 50%: {verdict(ref['overhead_share'] <= 0.5)}")
        row(f"untouched skeleton ({skel['score']}), wall (CPU)", f"{skel['wall_s']:.2f} s ({skel['cpu_s']:.2f} s) "
            f"= {skel['ratio']:.2f}x the reference", f"at most 0.2x: {verdict(skel['ratio'] <= 0.2)}")
    if "labs" in f:
        labs = f["labs"]
        row(" / ".join(labs) + " alone, wall", " / ".join(f"{lab['wall_s']:.1f}" for lab in labs.values()) + " s",
            "")
    if "worker_round_trip_1mpx" in f:
        trip = f["worker_round_trip_1mpx"]
        row("worker call with a 1-megapixel image (1000 x 1000 x 3 uint8, out and back)",
            f"{trip['call_ms']:.0f} ms, of which {trip['round_trip_ms']:.1f} ms round trip", "")
    if "reference" in f:
        row("peak RSS, grader / worker", f"{ref['grader_peak_mb']:.0f} MB / {ref['worker_peak_mb']:.0f} MB", "")
        row("reference outputs: JSON / `feedback.html`",
            f"{out['json_bytes'] / 1e6:.2f} MB ({out['json_pictures']} pictures) / {out['html_bytes'] / 1e6:.2f} MB",
            f"JSON without pictures: {verdict(out['json_pictures'] == 0)}; page at most 2 MB: "
            f"{verdict(out['html_bytes'] <= 2e6)}")
    if "batch" in f:
        batch = f["batch"]
        row(f"`autograder batch`, {batch['students']} students, {' '.join(batch['select'])}: 1 / 2 workers "
            f"(taking turns, medians of {batch['rounds']})",
            f"{batch['wall_s']['1']:.1f} s / {batch['wall_s']['2']:.1f} s ({batch['per_minute']['1']:.0f} / "
            f"{batch['per_minute']['2']:.0f} submissions/min)", "")
        ratio = batch["ratio_2_vs_1"]
        row("2 workers vs 1", f"{ratio:.2f}x", f"at least 1.8x: {verdict(ratio >= 1.8)}")
    if "stereo" in f:
        stereo = f["stereo"]
        lines += ["", f"Stereo, Middlebury motorcycle {stereo['resolution']}, disparities 0-{stereo['max_disparity']} "
                  f"(bad pixel: error over {stereo['threshold_px']:g} px or invalid, over the "
                  f"{stereo['ground_truth_share']:.0%} of pixels with ground truth), in the same run:", "",
                  "| method | bad pixels | seconds |", "|---|---|---|"]
        for name, method in stereo["methods"].items():
            row(name, f"{method['bad_pixels']:.1%}", f"{method['seconds']:.2f}")
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
