"""How large the feedback page is, and what its pictures cost.

Grades the reference solutions (or ``--submission PATH``) once, as ``python grade.py
--html`` would, then prints the page's size, its pictures by encoding, and the time
to render it. A benchmark, not a test: it prints figures.

    python benchmarks/bench_page.py            # everything
    python benchmarks/bench_page.py lab11
"""

from __future__ import annotations

import argparse
import re
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from autograder.reports import html  # noqa: E402
from autograder.engine.runner import grade  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("select", nargs="*")
    parser.add_argument("--submission", default=str(ROOT / "reference_solutions"))
    args = parser.parse_args()
    result = grade(args.submission, args.select)
    raw = sum(len(item.get("data", "")) for e in result.exercises for c in e.checks
              for a in c.artifacts for item in a.items)
    start = time.perf_counter()
    page = html.render(result)
    seconds = time.perf_counter() - start
    print(f"score                 {result.total:g} / {result.max_total:g}")
    print(f"pictures as graded    {raw / 2**20:6.2f} MB of base64 PNG/JPEG (each picture of each check)")
    for mime in ("image/jpeg", "image/png"):
        data = re.findall(rf"data:{mime};base64,([^\"]+)", page)
        print(f"  on the page, {mime[6:]:<5}  {len(data):4d} pictures, {sum(map(len, data)) / 2**20:6.2f} MB")
    print(f"page                  {len(page.encode()) / 2**20:6.2f} MB, rendered in {seconds:.2f} s")


if __name__ == "__main__":
    main()
