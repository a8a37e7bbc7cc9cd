"""What reading a class's PDF reports costs (autograder.loading.pdf_report), the store off.

    python benchmarks/bench_pdf_reports.py [STUDENTS] [READERS]

Each student's PDF: 6 pages, an exercise heading and 150 words a page, two 400 x 300 pictures a
page (~1 MB). Prints the wall time read one by one in one worker and side by side (prefetch, as
ingest does), and the grader's peak memory.
"""

from __future__ import annotations

import os
import resource
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
os.environ["AUTOGRADER_CACHE_DIR"] = "off"

from autograder.loading.pdf_report import ReportReader  # noqa: E402
from pdf_making import pdf  # noqa: E402


def main(students: int = 12, readers: int = 2) -> None:
    rng = np.random.default_rng(0)
    files = [pdf([[f"Exercise {page + 1}", f"Student {n} " + "word " * 150] for page in range(6)],
                 {page: [rng.integers(0, 256, (300, 400), dtype=np.uint8) for _ in range(2)] for page in range(6)})
             for n in range(students)]
    print(f"{students} PDFs of {np.mean([len(f) for f in files]) / 2**20:.2f} MiB, 6 pages, 12 pictures each")
    start = time.perf_counter()
    with ReportReader() as reader:
        reader.pdf(b"%PDF-1.4")   # the worker's start, apart
        started = time.perf_counter()
        for data in files:
            reader.pdf(data)
    one = time.perf_counter() - started
    print(f"one worker: start {started - start:.1f} s, then {one:.1f} s ({one / students:.2f} s a PDF)")
    start = time.perf_counter()
    with ReportReader() as reader:
        reader.prefetch(files, readers)
        for data in files:
            reader.pdf(data)
    print(f"{readers} readers side by side (their starts included): {time.perf_counter() - start:.1f} s")
    print(f"grader's peak memory: {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MiB")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
