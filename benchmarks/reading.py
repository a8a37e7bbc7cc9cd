"""How long the grader takes to read adversarial hand-ins, per reader, shape and size.

Each reader of what a student hands in (issue 34) is given inputs of one hostile
shape at sizes n, 2n, 4n; a linear reader takes about twice as long per doubling
(the ``x`` column), a quadratic one four times. Prints one line per reader, shape
and size: the best of ``--repeat`` runs (wall clock and CPU), and the CPU ratio to the
size before.

    python benchmarks/reading.py [--scale 1] [--repeat 3] [--only notebook]

Runs against whatever ``autograder`` is importable (``PYTHONPATH=/path/to/old/checkout``
times an earlier version); a shape whose previous size took over ``--give-up`` seconds
is not timed at the next. Shapes (all within the size caps of a hand-in):

- ``report.markdown``: repeated sections under one heading, marked sections, a line of spaces;
- ``report.notebook``: thousands of tagged Markdown cells, one cell with thousands of tags;
- ``notebooks.convert``: a code cell that is one line of spaces (the IPython-syntax check),
  one line of many statements, many small cells, many blocks after many names;
- ``reading.read_source``: one line of many statements, a long ``//`` chain, a long
  ``*`` chain, a chain of helpers.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

try:  # PYTHONPATH's autograder first (an older checkout, to compare), else this one's
    import autograder  # noqa: F401
except ImportError:
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def _notebook(cells) -> str:
    return json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5})


def _code(source: str) -> dict:
    return {"cell_type": "code", "metadata": {}, "source": source, "outputs": [], "execution_count": None}


def shapes():
    """``(reader, shape, make(n) -> input, run(input))``; ``n`` is roughly the input's size in KiB."""
    from autograder.loading import notebooks, reading, report

    folder = "submissions/" + "a-student-s-long-folder-name/" * 5   # a name shown in full: ~160 characters
    markdown = lambda text: report.read_report({folder + "lab07_report.md": text.encode()})  # noqa: E731
    notebook_report = lambda data: report.read_report({folder + "a.ipynb": data, folder + "b.ipynb": data})  # noqa: E731
    convert = lambda text: notebooks.convert(text, "lab07_transformations.ipynb")  # noqa: E731
    tagged = lambda n: _notebook([{"cell_type": "markdown", "metadata": {"tags": ["report:lab07.ex1"]},  # noqa: E731
                                   "source": f"text {i}"} for i in range(n * 1024 // 80)]).encode()
    return [
        ("report.markdown", "repeated sections", lambda n: "## lab07.ex1\nsome text\n" * (n * 1024 // 22), markdown),
        ("report.markdown", "marked sections", lambda n: "<!-- explanation lab07.ex1 -->\nx\n" * (n * 1024 // 34),
         markdown),
        ("report.markdown", "a line of spaces", lambda n: "## lab07.ex1\n<!--" + " " * (n * 1024) + "x\n", markdown),
        ("report.notebook", "tagged cells (two notebooks)", tagged, notebook_report),
        ("report.notebook", "one cell, many tags", lambda n: _notebook([{
            "cell_type": "markdown", "metadata": {"tags": [f"report:lab07.ex{i}" for i in range(n * 1024 // 20)]},
            "source": "text"}]).encode(), notebook_report),
        ("notebooks.convert", "a line of spaces", lambda n: _notebook([_code(" " * (n * 1024) + "\n")]), convert),
        ("notebooks.convert", "one line of statements", lambda n: _notebook([_code("x=1;" * (n * 1024 // 4))]),
         convert),
        ("notebooks.convert", "many cells", lambda n: _notebook([_code(f"a{i} = {i}") for i in range(n * 1024 // 80)]),
         convert),
        ("notebooks.convert", "blocks after names", lambda n: _notebook([_code(
            "".join(f"v{i} = {i}\n" for i in range(n * 1024 // 40))
            + "".join(f"if v{i}:\n    w{i} = v{i}\n" for i in range(n * 1024 // 40)))]), convert),
        ("reading.read_source", "one line of statements", lambda n: "a;" * (n * 1024 // 2), reading.read_source),
        ("reading.read_source", "a // chain", lambda n: "def f(x):\n    return " + "//".join(
            ["1"] * min(n * 1024 // 2, 2900)) + "\n", reading.read_source),
        ("reading.read_source", "a * chain", lambda n: "def f(x):\n    return " + "*".join(
            ["x"] * min(n * 1024 // 2, 2900)) + "\n", reading.read_source),
        ("reading.read_source", "a chain of helpers", lambda n: "".join(
            f"def f{i}(x):\n    return f{i + 1}(x)\n" for i in range(n * 1024 // 36)), reading.read_source),
    ]


def best_of(run, value, repeat: int) -> tuple[float, float]:
    """The least wall-clock and the least CPU seconds of ``repeat`` runs (on a shared
    machine the CPU time is the steadier figure)."""
    wall = cpu = float("inf")
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        run(value)
        wall, cpu = min(wall, time.perf_counter() - start), min(cpu, time.process_time() - start_cpu)
    return wall, cpu


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scale", type=float, default=1.0, help="sizes are 64, 128, 256 KiB times this")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--give-up", type=float, default=20.0, help="seconds: a slower size ends its shape")
    parser.add_argument("--only", default="", help="readers whose name holds this")
    args = parser.parse_args(argv)
    sizes = [max(1, int(base * args.scale)) for base in (64, 128, 256)]
    print(f"{'reader':22} {'shape':32} {'KiB':>6} {'seconds':>9} {'CPU s':>9} {'x CPU':>6}")
    for reader, shape, make, run in shapes():
        if args.only not in reader:
            continue
        before = None
        for size in sizes:
            value = make(size)
            try:
                seconds, cpu = best_of(run, value, args.repeat if (before or 0) < args.give_up / 4 else 1)
            except Exception as exc:  # noqa: BLE001 - an older version may raise: say so, go on
                print(f"{reader:22} {shape:32} {len(value) // 1024:6} raised {type(exc).__name__}: {exc}"[:160])
                break
            ratio = f"{cpu / max(before, 1e-6):6.2f}" if before is not None else ""
            print(f"{reader:22} {shape:32} {len(value) // 1024:6} {seconds:9.3f} {cpu:9.3f} {ratio:>6}", flush=True)
            before = cpu
            if seconds > args.give_up:
                print(f"{reader:22} {shape:32} (larger sizes not timed: over {args.give_up:g} s)")
                break


if __name__ == "__main__":
    main()
