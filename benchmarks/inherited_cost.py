"""What telling inherited failures costs (issue 35, :mod:`autograder.engine.inherited`).

    python benchmarks/inherited_cost.py            # every chain of tests/test_inherited.py, 2 runs each
    python benchmarks/inherited_cost.py lab11 lab12 --runs 3

For each lab's chain (a wrong callee under the reference's caller, as in tests/test_inherited.py),
the exercise is graded with the test on and off, ALTERNATING (both see the same load), after one
warm-up grading (ground truth cached, helper started; the helper's answers, which the error model
and this test keep per process, are cleared before each grading): wall seconds of the grading, and the time
the test spent deciding (the sum of its decide() calls). Off, the error model names the failed
caller's checks instead (or tries to). A benchmark, not a test: it asserts nothing.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tests")]

from autograder.engine import inherited  # noqa: E402
from autograder.engine.mutants.helper import ANSWERS  # noqa: E402
from autograder.engine.runner import grade  # noqa: E402
from conftest import mutant  # noqa: E402
from test_inherited import CHAINS  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("labs", nargs="*", default=sorted(CHAINS))
    parser.add_argument("--runs", type=int, default=2)
    options = parser.parse_args()
    real_told, real_decide = inherited.told, inherited.decide
    deciding = [0.0]

    def timed(*args, **kwargs):
        started = time.perf_counter()
        try:
            return real_decide(*args, **kwargs)
        finally:
            deciding[0] += time.perf_counter() - started

    inherited.decide = timed
    print(f"{'lab':6} {'exercise':11} {'on (s)':>8} {'off (s)':>8} {'deciding (s)':>13}")
    for key in options.labs:
        module, exercise, _, source = CHAINS[key]
        folder = mutant(Path(tempfile.mkdtemp()), module, source)
        grade(folder, [exercise], pictures="none")   # warm-up
        times = {"on": [], "off": []}
        decided = []
        for _ in range(options.runs):
            for mode in ("on", "off"):
                inherited.told = real_told if mode == "on" else (lambda verdict, trial: (verdict, False))
                deciding[0] = 0.0
                ANSWERS.clear()   # the helper's answers kept per process: each grading as a first one
                started = time.perf_counter()
                grade(folder, [exercise], pictures="none")
                times[mode].append(time.perf_counter() - started)
                if mode == "on":
                    decided.append(deciding[0])
        inherited.told = real_told
        print(f"{key:6} {exercise:11} {statistics.median(times['on']):8.2f} {statistics.median(times['off']):8.2f} "
              f"{statistics.median(decided):13.2f}")


if __name__ == "__main__":
    main()
