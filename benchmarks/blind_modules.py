"""Grade a blind set of whole-module submissions and keep what the grader told each one.

The sets under ``benchmarks/blind_mistakes/<date>/`` are whole modules, each with one bug,
written from the lab sheet, the API and the reference alone, and a ``MANIFEST.json`` saying
(for each file) the function with the bug and the bug in a teacher's words. Each file is
graded on the exercises that call that function, hidden checks included; the failing
checks' messages and named mistakes are written out beside the truth, for a reader who
classifies each case as named (the feedback names the true cause), described (points
lost, no cause named), wrong (a cause named that is not the bug) or not caught.

    python benchmarks/blind_modules.py benchmarks/blind_mistakes/2026-11-28 --json after.json
    python benchmarks/blind_modules.py SET --code /tmp/old --json before.json   # another copy of the grader
    python benchmarks/blind_modules.py SET --cold --json after.json   # each file in a process of its own

By default the files are graded one after another in one process, so the error model's answers
on a check's fixed inputs (kept per process) are warm for every file after a lab's first; a
student's own grading, or a Gradescope container's, starts cold: ``--cold`` grades each file in
a fresh process, as they do.
"""

from __future__ import annotations

import argparse
import atexit
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
MESSAGE_LINES = 24      # of each message kept for the evaluator (a matrix printed after "expected" included)
MESSAGE_CHARS = 3000


def _kept(message: str) -> str:
    return "\n".join(message.splitlines()[:MESSAGE_LINES])[:MESSAGE_CHARS]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("set", type=Path, help="the set's folder (holding MANIFEST.json)")
    parser.add_argument("--code", type=Path, default=HERE.parent, help="the grader's copy to measure")
    parser.add_argument("--json", type=Path, required=True, help="where to write every case's feedback")
    parser.add_argument("--only", help="only files whose path contains this")
    parser.add_argument("--cold", action="store_true", help="grade each file in a fresh process")
    args = parser.parse_args(argv)
    if args.cold:
        return _cold(args)

    sys.path.insert(0, str(args.code.resolve()))
    if "AUTOGRADER_CACHE_DIR" not in os.environ:  # a store of this run's own, removed when it ends
        os.environ["AUTOGRADER_CACHE_DIR"] = tempfile.mkdtemp(prefix="blind-store-")
        atexit.register(shutil.rmtree, os.environ["AUTOGRADER_CACHE_DIR"], ignore_errors=True)
    from autograder.engine.registry import select  # noqa: E402  (the copy chosen above)
    from autograder.engine.runner import grade  # noqa: E402
    from autograder.engine.results import ADVICE  # noqa: E402

    manifest = json.loads((args.set / "MANIFEST.json").read_text())
    cases = []
    for entry in manifest["submissions"]:
        if args.only and args.only not in entry["file"]:
            continue
        lab = "lab" + entry["lab"][3:5]
        exercises = _exercises_running(select([lab]), entry["function"], (args.set / entry["file"]).read_text())
        folder = Path(tempfile.mkdtemp(prefix="blind-module-"))
        try:
            (folder / f"{entry['lab']}.py").write_text((args.set / entry["file"]).read_text())
            started = time.perf_counter()
            result = grade(folder, exercises, pictures="none")
            seconds = time.perf_counter() - started
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        checks = [c for e in result.exercises for c in e.checks if c.max_score > 0]
        failed = [c for c in checks if c.score < c.max_score]
        cases.append({**entry, "exercises": exercises, "seconds": round(seconds, 1),
                      "score": round(sum(c.score for c in checks), 2), "max": round(sum(c.max_score for c in checks), 2),
                      "caught": bool(failed),
                      "failed": [{"check": c.name, "hidden": c.hidden, "mistake": c.mistake,
                                  "message": _kept(c.message), "hint": c.hint[:400]}
                                 for c in failed],
                      # (tips, 0 points: what the student reads besides the checks that cost points)
                      "tips": [{"check": c.name, "message": _kept(c.message),
                                "hint": c.hint[:400]}
                               for e in result.exercises for c in e.checks if c.status == ADVICE and c.message]})
        print(f"{entry['file']:<60} {'caught' if failed else 'NOT CAUGHT':<10} "
              f"{cases[-1]['score']}/{cases[-1]['max']}  {seconds:.0f}s", flush=True)
        args.json.write_text(json.dumps(cases, indent=1))
    caught = sum(c["caught"] for c in cases)
    print(f"caught {caught} of {len(cases)}")
    return 0


def _exercises_running(exercises, function: str, source: str) -> list[str]:
    """The exercises grading ``function``; for a private helper, those whose functions run it in
    the file (its whole lab when none does): never every lab, whose other modules are missing."""
    import ast

    from autograder.engine.mutants.operators import _defs, runs

    graded = [e.id for e in exercises if function in e.signatures]
    if graded:
        return graded
    defs = _defs(ast.parse(source))
    running = [e.id for e in exercises if any(function in runs(defs, name) for name in e.signatures if name in defs)]
    return running or [e.id for e in exercises]


def _cold(args) -> int:
    """Each file of the set graded by this script in a process of its own (``--only`` that file)."""
    import subprocess

    manifest = json.loads((args.set / "MANIFEST.json").read_text())
    cases = []
    for entry in manifest["submissions"]:
        if args.only and args.only not in entry["file"]:
            continue
        with tempfile.TemporaryDirectory(prefix="blind-cold-") as folder:
            out = Path(folder) / "case.json"
            subprocess.run([sys.executable, str(Path(__file__).resolve()), str(args.set), "--code", str(args.code),
                            "--json", str(out), "--only", entry["file"]], check=True)
            cases += [case for case in json.loads(out.read_text()) if case["file"] == entry["file"]]
        args.json.write_text(json.dumps(cases, indent=1))
    print(f"caught {sum(c['caught'] for c in cases)} of {len(cases)} (each file in a fresh process)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
