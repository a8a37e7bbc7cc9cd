"""What a hostile student's figures cost the grader (issue 34): wall time, the grader's CPU time
and its peak memory (RSS of the grading process, not its worker), one attack per fresh process.

    python benchmarks/bench_figures_budget.py                 # this checkout
    python benchmarks/bench_figures_budget.py --tree OTHER    # another checkout (e.g. before the caps)

Attacks (each on the reference solutions, one function replaced):

- ``points``: ``pinhole_project`` returns 8 million random points (128 MB), figure lab09.ex1;
- ``image``: ``translate`` returns a 3000 x 3000 colour image (27 MB of uint8), lab07.ex1;
- ``sleep``: every lab 7 function sleeps 100 s, the six lab 7 figures, default call timeout
  (10 s), the figures given 20 s of the submission's deadline (the grading took the rest);
- ``reference``: the reference's lab 7 and lab 9 figures, for scale.

Measured 2026-11-28 on the shared 2-core machine (busy), before (cc90517) -> after the caps:
points 75.9 s wall, 14.5 s CPU, 634 MB peak -> 6.7 s, 0.7 s, 61 MB (refused: "returned ... 122 MiB
..., more than the 32 MiB"); image 13.6 s, 2.1 s, 125 MB -> 5.4 s, 0.7 s, 64 MB (refused: 27,000,000
numbers); sleep 77.3 s (six 10 s timeouts, more calls left) -> 20.6 s (the 20 s left of the deadline);
reference 42.1 s, 9.4 s, 119 MB -> 39.9 s, 8.9 s, 120 MB (13 of 13 made either way). Most of an
attack's wall time after the caps is the worker's start on a busy machine.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ATTACKS = {
    "points": ("lab09_camera", ["lab09.ex1"], """
        def pinhole_project(points, f):
            import numpy as np
            return np.random.default_rng(0).normal(size=(8_000_000, 2))
        """),
    "image": ("lab07_transformations", ["lab07.ex1"], """
        def translate(image, tx=100, ty=50):
            import numpy as np
            return np.zeros((3000, 3000, 3), np.uint8)
        """),
    "sleep": ("lab07_transformations", [f"lab07.ex{k}" for k in range(1, 7)], """
        import time as _time
        for _name, _function in list(globals().items()):
            if callable(_function) and not _name.startswith("_") and getattr(_function, "__module__", "") == __name__:
                globals()[_name] = lambda *args, **kwargs: _time.sleep(100)
        """),
    "reference": (None, ["lab07", "lab09"], ""),
}

CHILD = """
import inspect, json, resource, sys, time
sys.path.insert(0, {tree!r})
from autograder.figures import make_figures
kwargs = {{"deadline": time.monotonic() + 20}} if {attack!r} == "sleep" and \\
    "deadline" in inspect.signature(make_figures).parameters else {{}}
started, cpu = time.monotonic(), time.process_time()
outcomes = make_figures({folder!r}, {selected!r}, {out!r}, **kwargs)
print(json.dumps({{"wall": time.monotonic() - started, "cpu": time.process_time() - cpu,
                  "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                  "made": sum(o.path is not None for o in outcomes), "of": len(outcomes),
                  "reasons": sorted({{o.reason[:150] for o in outcomes if o.reason}}),
                  "notes": [getattr(o, "note", "")[:150] for o in outcomes if getattr(o, "note", "")]}}))
"""


def run(tree: Path, attack: str) -> dict:
    module, selected, source = ATTACKS[attack]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "submission"
        folder.mkdir()
        for path in (tree / "reference_solutions").glob("*.py"):
            text = path.read_text()
            if path.stem == module:
                text += "\n\n" + textwrap.dedent(source)
            (folder / path.name).write_text(text)
        child = CHILD.format(tree=str(tree), folder=str(folder), selected=selected, out=str(Path(tmp) / "out"),
                             attack=attack)
        done = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True, cwd=tree)
        if done.returncode != 0:
            return {"error": done.stderr[-2000:]}
        return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tree", type=Path, default=Path(__file__).resolve().parents[1])
    parser.add_argument("--only", nargs="*", choices=list(ATTACKS), default=list(ATTACKS))
    args = parser.parse_args()
    for attack in args.only:
        print(attack, json.dumps(run(args.tree.resolve(), attack)), flush=True)


if __name__ == "__main__":
    main()
