"""Gradescope: ``results.json`` from a grading, and the ``autograder.zip`` that produces it.

``run_autograder`` (in the zip) calls :func:`run`, which always writes one
``results.json``, atomically and once, also when the submission or the grader
fails. The format follows Gradescope's published autograder specification: per
test ``name``, ``number``, ``score``, ``max_score``, ``status``, ``output``,
``output_format`` and ``visibility``; at the top ``score``, ``execution_time``,
``output`` and ``stdout_visibility``.
"""

from __future__ import annotations

import json
import logging
import time
import zipfile
from pathlib import Path

from .course import CourseConfig
from .results import GradingResult, write_atomically
from .sandbox import Limits

log = logging.getLogger("autograder")
PROJECT_ROOT = Path(__file__).resolve().parents[1]


# ------------------------------------------------------------------ results.json
def results_json(result: GradingResult, config: CourseConfig) -> dict:
    """The Gradescope results for a grading."""
    tests, position = [], {}
    for exercise in result.exercises:
        lab = exercise.id.split(".")[0]
        position[lab] = position.get(lab, 0) + 1  # ex1..exN then the extensions, as registered
        for index, check in enumerate(exercise.checks, 1):
            tests.append({
                "name": f"{exercise.id} {exercise.title}: {check.name}",
                "number": f"{int(lab[3:])}.{position[lab]}.{index}",
                "score": check.score,
                "max_score": check.max_score,
                "status": "passed" if check.passed or check.max_score == 0 else "failed",  # advice never fails
                "output": _check_output(check),
                "output_format": "text",
                "visibility": config.hidden_visibility if check.hidden else config.public_visibility,
            })
    lines = [f"Total: {result.total:g} / {result.max_total:g}"]
    lines += [f"{e.id} {e.title}: {e.score:g} / {e.max_score:g}" + (f" - {e.message.splitlines()[0]}" if e.message else "")
              for e in result.exercises]
    lines += [f"Rule for {e.id}: {rule}" for e in result.exercises for rule in e.rules]
    return {"score": result.total, "output": "\n".join(lines), "output_format": "text",
            "stdout_visibility": config.stdout_visibility, "tests": tests}


def _check_output(check) -> str:
    if check.advice:
        parts = [f"Tip (no points): {check.message}"]
    elif check.max_score == 0:
        parts = [check.message or "Advice: nothing to suggest."]
    else:
        parts = [check.message or ("Passed." if check.passed else check.status)]
    if check.hint:
        parts.append(f"Hint: {check.hint}")
    if check.traceback:
        parts.append(check.traceback)
    if check.output:
        parts.append("What your code printed:\n" + check.output)
    return "\n\n".join(parts)


def failure_json(message: str, config: CourseConfig) -> dict:
    """Results when nothing could be graded: score 0 and a clear message."""
    return {"score": 0.0, "output": message, "output_format": "text",
            "stdout_visibility": config.stdout_visibility, "tests": []}


def run(submission, results_path, config: CourseConfig | None = None) -> dict:
    """Grade ``submission`` and write ``results_path``; never raises for a bad submission."""
    from .runner import grade

    config = config or CourseConfig()
    started = time.monotonic()
    try:
        result = grade(submission, config.select, limits=Limits(call_timeout=config.call_timeout),
                       pictures="none", forbid=config.forbid)  # results.json carries text only
        data = results_json(result, config)
    except Exception as exc:  # noqa: BLE001 - results.json must be written whatever happens
        log.exception("grading failed")
        data = failure_json(f"The autograder could not grade this submission: {exc}. "
                            "Your instructor has been notified through the autograder log; "
                            "check that you uploaded the lab modules (e.g. lab07_transformations.py).",
                            config)
    data["execution_time"] = round(time.monotonic() - started, 3)
    write_atomically(results_path, json.dumps(data, indent=1, allow_nan=False) + "\n")
    return data


# ------------------------------------------------------------------ autograder.zip
SETUP_SH = """#!/usr/bin/env bash
# Installs the autograder on Gradescope's Ubuntu image, with its system Python.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends python3 python3-venv python3-pip util-linux
python3 -m venv /autograder/venv
/autograder/venv/bin/python -m pip install --upgrade pip
/autograder/venv/bin/python -m pip install /autograder/source
chmod -R a+rX /autograder/venv
# Student code runs as this unprivileged user when grading as root.
id agworker >/dev/null 2>&1 || useradd --system --no-create-home --home-dir /nonexistent \\
    --shell /usr/sbin/nologin --user-group agworker
"""

RUN_AUTOGRADER = """#!/usr/bin/env bash
# Grades $ROOT/submission and writes $ROOT/results/results.json (always).
# AUTOGRADER_ROOT and AUTOGRADER_PYTHON exist for tests; Gradescope sets neither.
set -uo pipefail
ROOT="${AUTOGRADER_ROOT:-/autograder}"
PYTHON="${AUTOGRADER_PYTHON:-$ROOT/venv/bin/python}"
RESULTS="$ROOT/results/results.json"
mkdir -p "$ROOT/results"
# The worker never sees the grader's sources or the results folder.
export AUTOGRADER_HIDE="$ROOT/source:$ROOT/results"
cd "$ROOT/source"
status=0
"$PYTHON" -m autograder gradescope run --submission "$ROOT/submission" \\
    --results "$RESULTS" --config "$ROOT/source/course.json" || status=$?
if [ ! -s "$RESULTS" ]; then
    # Only if the grader itself could not start: still give Gradescope valid results.
    printf '{"score": 0, "execution_time": 0, "output": "The autograder failed to start (exit status %s). Please tell your instructor.", "stdout_visibility": "hidden", "tests": []}\\n' "$status" > "$RESULTS.tmp"
    mv "$RESULTS.tmp" "$RESULTS"
fi
exit 0
"""

# What the container needs: the engine (hidden checks included) and the fixtures,
# never the reference solutions or the grader's own tests.
_SHIPPED = ("autograder", "fixtures")
_SHIPPED_FILES = ("pyproject.toml", "README.md", "grade.py")


def _shipped_files(root: Path):
    for top in _SHIPPED:
        for path in sorted((root / top).rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts and path.suffix != ".pyc" \
                    and not path.name.startswith("make_"):
                yield path
    for name in _SHIPPED_FILES:
        yield root / name


def build(out, config: CourseConfig | None = None, root: Path = PROJECT_ROOT) -> Path:
    """Write ``autograder.zip``: ``setup.sh`` and ``run_autograder`` at its root, plus sources."""
    from .registry import select

    out = Path(out)
    config = config or CourseConfig()
    select(config.select)  # a course that names a missing lab fails now, not at the deadline
    _check_forbidden_functions(config)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_name(out.name + ".tmp")
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as zf:
        _add(zf, "setup.sh", SETUP_SH, executable=True)
        _add(zf, "run_autograder", RUN_AUTOGRADER, executable=True)
        _add(zf, "course.json", config.to_json())
        for path in _shipped_files(root):
            _add(zf, path.relative_to(root).as_posix(), path.read_bytes())
    tmp.replace(out)
    return out


def _check_forbidden_functions(config: CourseConfig) -> None:
    """Every ``forbid`` key names a student function some exercise grades."""
    from .course import CourseConfigError
    from .registry import discover

    labs = discover()
    for key in config.forbid:
        lab, function = key.split(".", 1)
        if lab not in labs or not any(function in e.signatures for e in labs[lab].exercises.values()):
            raise CourseConfigError(f"forbid: {key} is not a function any exercise grades")


def _add(zf: zipfile.ZipFile, name: str, data, executable: bool = False):
    info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))  # reproducible archives
    info.compress_type = zipfile.ZIP_DEFLATED
    info.external_attr = ((0o755 if executable else 0o644) | 0o100000) << 16
    zf.writestr(info, data.encode() if isinstance(data, str) else data)
