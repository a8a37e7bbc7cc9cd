"""How long the class pages take for a class of N students (default 300).

The overview is rendered from N generated results (every lab's exercises, a
third of the students with a named mistake). For the similarity report, N
disguised copies of each reference module are fingerprinted and every pair
scored by shared fingerprints; aligning a pair with copydetect (done only for
close pairs) is timed separately. A benchmark, not a test: it prints figures.

    python benchmarks/bench_classreport.py            # 300 students
    python benchmarks/bench_classreport.py --students 100
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from classreport_disguise import disguise  # noqa: E402

from autograder.instructor.classreport.analysis import StudentRecord  # noqa: E402
from autograder.instructor.classreport.overview import render_overview  # noqa: E402
from autograder.engine.registry import discover  # noqa: E402
from autograder.engine.results import FAILED, PASSED, CheckResult, ExerciseResult, GradingResult  # noqa: E402


def generated_class(n: int) -> list[StudentRecord]:
    exercises = [e for lab in sorted(discover().values(), key=lambda lab: lab.key) for e in lab.exercises.values()]
    students = []
    for i in range(n):
        result = GradingResult(f"s{i}", "h", "v")
        for e in exercises:
            checks = []
            for j, c in enumerate(e.checks):
                if (i + j) % 3 == 0:
                    checks.append(CheckResult(c.name, 0.0, c.points, FAILED, f"{c.name} is wrong: it looks like "
                                              f"mistake {j % 4}.", mistake=f"mistake {j % 4}"))
                else:
                    checks.append(CheckResult(c.name, c.points, c.points, PASSED))
            result.exercises.append(ExerciseResult(e.id, e.title, [], checks))
        students.append(StudentRecord(f"s{i:03d}", f"Student {i}", result=result.to_dict(),
                                      feedback_href=f"s{i:03d}/feedback.html"))
    return students


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=300)
    args = parser.parse_args()
    n = args.students
    with tempfile.TemporaryDirectory() as tmp:
        students = generated_class(n)
        start = time.perf_counter()
        render_overview(students, Path(tmp) / "index.html")
        size = (Path(tmp) / "index.html").stat().st_size
        print(f"overview: {n} students in {time.perf_counter() - start:.2f} s, {size / 1024:.0f} KiB")

        similarity(n)


def similarity(n: int):
    """Where the similarity report's time goes, per lab module, and the whole class's estimate."""
    import copydetect

    from autograder.instructor.classreport.similarity import compare_module, lab_modules, skeleton_sources

    labs = lab_modules()
    skeletons = skeleton_sources(labs)
    total, aligns = 0.0, []
    for module in sorted(labs):
        reference = (ROOT / "reference_solutions" / f"{module}.py").read_text()
        sources = {f"s{i:03d}": disguise(reference, seed=i) for i in range(n)}
        start = time.perf_counter()
        result = compare_module(module, sources, skeletons[module], align_above=2.0, aligned_at_least=0)
        estimated = time.perf_counter() - start
        prints = [copydetect.CodeFingerprint(f"{module}.py", 25, 6, fp=__import__("io").StringIO(sources[s]))
                  for s in ("s000", "s001")]
        start = time.perf_counter()
        for _ in range(10):
            copydetect.compare_files(*prints)
        align = (time.perf_counter() - start) / 10
        total += estimated
        aligns.append(align)
        print(f"similarity {labs[module]}: {n} files fingerprinted and {len(result.pairs)} pairs scored in "
              f"{estimated:.1f} s; aligning one pair of copies {1000 * align:.0f} ms")
    print(f"similarity, all labs: {total:.0f} s for {n} students, plus {1000 * max(aligns):.0f} ms at most "
          f"per pair aligned (the close pairs, and the 10 best per lab)")


if __name__ == "__main__":
    main()
