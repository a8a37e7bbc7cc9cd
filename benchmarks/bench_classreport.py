"""How long the class pages take for a class of N students (default 300).

The overview is rendered from N generated results (every lab's exercises, a
third of the students with a named mistake); the similarity report compares N
versions of every lab module (disguised copies of the reference and of an
independent lab 7, so every pair has real code to compare). A benchmark, not a
test: it prints figures.

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

from autograder.classreport.analysis import StudentRecord  # noqa: E402
from autograder.classreport.overview import render_overview  # noqa: E402
from autograder.registry import discover  # noqa: E402
from autograder.results import FAILED, PASSED, CheckResult, ExerciseResult, GradingResult  # noqa: E402


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

        from autograder.classreport.similarity import (compare_class, lab_modules, similarity_html,
                                                       skeleton_sources)

        labs = lab_modules()
        references = {m: (ROOT / "reference_solutions" / f"{m}.py").read_text() for m in labs}
        independent = (ROOT / "tests" / "classreport_data" / "lab07_transformations.py").read_text()
        sources = {}
        for i in range(n):
            sources[f"s{i:03d}"] = {m: disguise(independent if (m.startswith("lab07") and i % 2) else code, seed=i)
                                    for m, code in references.items()}
        start = time.perf_counter()
        results = compare_class(sources, skeleton_sources(labs), labs, threshold=0.5)
        compared = time.perf_counter() - start
        html = similarity_html(results, 0.5)
        pairs = sum(len(r.pairs) for r in results)
        print(f"similarity: {n} students x {len(labs)} labs = {pairs} pairs in {compared:.1f} s "
              f"({1e6 * compared / max(pairs, 1):.0f} us per pair), page {len(html) / 1024:.0f} KiB")


if __name__ == "__main__":
    main()
