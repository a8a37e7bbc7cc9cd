"""How the grader names mistakes nobody tabulated: the blind set, graded and classified.

Every case of ``benchmarks/blind_mistakes`` (single-bug submissions written apart from
the project's mistake tables, each with its truth written beside it) is graded on its
exercise, hidden checks included, and classified:

- **named**: a failing check names the mistake (its ``mistake`` field, or an "it looks
  like ..." sentence) and every name given fits the truth (one of the case's
  ``accept`` fragments);
- **wrong**: some failing check names a mistake that does not fit the truth;
- **described**: points are lost, nothing is named (the message says what is measurably
  wrong);
- **not caught**: full marks.

    python benchmarks/blind_naming.py                  # this checkout
    python benchmarks/blind_naming.py --code /tmp/old  # another copy of the grader, same cases
    python benchmarks/blind_naming.py --lab lab08 --json out.json
    python benchmarks/blind_naming.py --set b           # the second set (blind_mistakes/later.py; --later)
    python benchmarks/blind_naming.py --set c           # the third set (blind_mistakes/set_c.py)
    python benchmarks/blind_naming.py --set d           # the fourth set (blind_mistakes/set_d.py)

The cases are never tuned on: they were written and committed before the naming
mechanism was changed, and the truth of each was written with it.
"""

from __future__ import annotations

import argparse
import atexit
import json
import os
import re
import shutil
import sys
import tempfile
import textwrap
from pathlib import Path

HERE = Path(__file__).resolve().parent
OUTCOMES = ("named", "described", "wrong", "not caught")
# set -> module of (module, Case) pairs; a is per lab
SETS = {"a": None, "b": "later", "c": "set_c", "d": "set_d"}
_LOOKS_LIKE = re.compile(r"(?:it )?looks like (.+?)(?:\.(?:\s|$)|\n|$)", re.S | re.I)


def names_given(checks) -> list[str]:
    """What each failing check names, lower-cased: its mistake label and its "looks like" clause."""
    names = []
    for check in checks:
        if check.score >= check.max_score:
            continue
        clause = _LOOKS_LIKE.search(check.message or "")
        if check.mistake or clause:
            names.append(" | ".join(part for part in (check.mistake, clause.group(1) if clause else "")
                                    if part).lower())
    return names


def classify(checks, accept) -> tuple[str, list[str]]:
    """(outcome, names) of one graded case."""
    if sum(c.score for c in checks) >= sum(c.max_score for c in checks):
        return "not caught", []
    names = names_given(checks)
    if not names:
        return "described", []
    fits = [any(fragment in name for fragment in accept) for name in names]
    return ("named" if all(fits) else "wrong"), names


def grade_case(grade, reference: Path, module: str, case):
    folder = Path(tempfile.mkdtemp(prefix="blind-case-"))
    try:
        submission = folder / "submission"
        submission.mkdir()
        original = (reference / f"{module}.py").read_text()
        (submission / f"{module}.py").write_text(original + "\n\n# --- the student's version\n"
                                                 + textwrap.dedent(case.source))
        result = grade(submission, [case.exercise], pictures="none")
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    [exercise] = [e for e in result.exercises if e.id == case.exercise]
    return [c for c in exercise.checks if c.max_score > 0]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--code", type=Path, default=HERE.parent,
                        help="the grader's copy to measure (its autograder/, fixtures/, reference_solutions/)")
    parser.add_argument("--lab", action="append", help="only these labs (lab08 ...)")
    parser.add_argument("--json", type=Path, help="write every case's outcome, names and first message here")
    parser.add_argument("--set", dest="blind_set", choices=SETS, default="a",
                        help="which blind set: a (blind_mistakes/labNN.py, the default), b (later.py, written "
                             "after the mechanism), c (set_c.py) or d (set_d.py), both written without "
                             "reading the grader)")
    parser.add_argument("--later", dest="blind_set", action="store_const", const="b",
                        help="the same as --set b")
    args = parser.parse_args(argv)

    sys.path.insert(0, str(args.code.resolve()))
    sys.path.insert(0, str(HERE))
    if "AUTOGRADER_CACHE_DIR" not in os.environ:  # a store of this run's own, removed when it ends
        os.environ["AUTOGRADER_CACHE_DIR"] = tempfile.mkdtemp(prefix="blind-store-")
        atexit.register(shutil.rmtree, os.environ["AUTOGRADER_CACHE_DIR"], ignore_errors=True)
    from autograder.engine.runner import grade  # noqa: E402  (the copy chosen above)
    from blind_mistakes import all_cases  # noqa: E402

    reference = args.code.resolve() / "reference_solutions"
    counts, details = {}, []
    if args.blind_set != "a":
        listed = __import__(f"blind_mistakes.{SETS[args.blind_set]}", fromlist=["CASES"]).CASES
        chosen = {}
        for module, case in listed:
            chosen.setdefault(case.exercise.split(".")[0], (module, []))[1].append(case)
    else:
        chosen = {lab: (__import__(f"blind_mistakes.{lab}", fromlist=["MODULE"]).MODULE, cases)
                  for lab, cases in all_cases().items()}
    for lab, (module, cases) in chosen.items():
        if args.lab and lab not in args.lab:
            continue
        counts[lab] = dict.fromkeys(OUTCOMES, 0)
        missed_movers = 0
        for case in cases:
            checks = grade_case(grade, reference, module, case)
            outcome, names = classify(checks, case.accept)
            counts[lab][outcome] += 1
            missed_movers += outcome == "not caught" and case.moves
            failed = [c for c in checks if c.score < c.max_score]
            first = failed[0].message.split("\n")[0] if failed else ""
            details.append({"lab": lab, "case": case.name, "exercise": case.exercise, "outcome": outcome,
                            "truth": case.truth, "moves": case.moves, "names": names, "first_message": first})
            print(f"{lab} {outcome:<11} {case.name}" + (f"  -> {'; '.join(names)}" if names else "")
                  + ("" if names or not first else f"  [{first[:150]}]"), flush=True)
        counts[lab]["missed movers"] = missed_movers

    print()
    print(f"{'lab':<8}" + "".join(f"{o:>12}" for o in OUTCOMES) + f"{'cases':>8}{'named %':>9}")
    total = dict.fromkeys(OUTCOMES, 0)
    for lab, row in counts.items():
        n = sum(row[o] for o in OUTCOMES)
        for o in OUTCOMES:
            total[o] += row[o]
        print(f"{lab:<8}" + "".join(f"{row[o]:>12}" for o in OUTCOMES) + f"{n:>8}{row['named'] / n:>9.0%}")
    n = sum(total.values())
    print(f"{'all':<8}" + "".join(f"{total[o]:>12}" for o in OUTCOMES) + f"{n:>8}{total['named'] / n:>9.0%}")
    missed = sum(row["missed movers"] for row in counts.values())
    print(f"not caught although the bug moves results beyond the legitimate spread: {missed}")
    if args.json:
        args.json.write_text(json.dumps({"counts": counts, "cases": details}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
