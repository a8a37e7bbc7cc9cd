"""Gradescope: ``results.json`` from a grading, and the ``autograder.zip`` that produces it.

``run_autograder`` (in the zip) calls :func:`run`, which always writes one
``results.json``, atomically and once, also when the submission or the grader
fails. The format follows Gradescope's published autograder specification: per
test ``name``, ``number``, ``score``, ``max_score``, ``status``, ``output``,
``output_format`` and ``visibility``; at the top ``score``, ``execution_time``,
``output`` and ``stdout_visibility``.
"""

from __future__ import annotations

import dataclasses
import json
import logging
import math
import re
import secrets
import time
import zipfile
from pathlib import Path

from .confine import WeakerConfinement
from .course import CourseConfig
from .results import GradingResult, write_atomically
from .submission import SubmissionError

log = logging.getLogger("autograder")
PROJECT_ROOT = Path(__file__).resolve().parents[1]
# The Python versions the grader is tested on (pyproject's requires-python);
# setup.sh installs the second (the one CI runs) where the image has none of them.
TESTED_PYTHONS = ("3.10", "3.11", "3.12", "3.13")


# ------------------------------------------------------------------ results.json
def results_json(result: GradingResult, config: CourseConfig) -> dict:
    """The Gradescope results for a grading: what students may see of it (hidden checks
    as verdicts, :meth:`~autograder.results.GradingResult.for_students`). The hidden tests
    keep their points (the grade needs them; Gradescope keeps them from students until
    their ``visibility`` allows); the text at the top counts them only where the course
    shows hidden checks' points (``hidden_points_visible``)."""
    # In the course's points (``points``), as every other grade of the course is.
    result = result.in_points(config.point_factors([(e.id, e.max_score) for e in result.exercises]))
    tests, position = [], {}
    for exercise in result.for_students(points_visible=True).exercises:
        lab = exercise.id.split(".")[0]
        position[lab] = position.get(lab, 0) + 1  # ex1..exN then the extensions, as registered
        for index, check in enumerate(exercise.checks, 1):
            tests.append({
                "name": f"{exercise.id} {exercise.title}: {check.name}",
                "number": f"{int(lab[3:])}.{position[lab]}.{index}",
                "score": check.score,
                "max_score": check.max_score,
                "status": "passed" if check.passed or check.max_score == 0 else "failed",  # advice never fails
                "output": _check_markdown(check),
                "output_format": "md",
                "visibility": config.hidden_visibility if check.hidden else config.public_visibility,
            })
    return {"score": result.total, "output": _summary(result.for_students(config.hidden_points_visible)),
            "output_format": "text",
            "stdout_visibility": config.stdout_visibility, "tests": tests}


def _summary(result: GradingResult) -> str:
    """The top of the results page: notes on how the files were read, the total, each
    exercise's score, and a module-wide problem said once per lab."""
    lines = [f"Note: {note}" for note in result.notes]
    lines.append(f"Total: {result.total:g} / {result.max_total:g}")
    said = set()
    for e in result.exercises:
        line = f"{e.id} {e.title}: {e.score:g} / {e.max_score:g}"
        if e.message and e.message not in said:
            said.add(e.message)
            line += f" - {e.message.splitlines()[0]}"
        elif e.message:
            line += " - as above"
        lines.append(line)
    lines += [f"Rule for {e.id}: {rule}" for e in result.exercises for rule in e.rules]
    if result.hidden_points_withheld:
        lines.append("Hidden checks are not counted above: their points appear here once your "
                     "instructor releases them.")
    return "\n".join(lines)


def hidden_checks_log(result: GradingResult) -> str:
    """The hidden checks that lost points, in full (names, messages, hints, tracebacks), for the
    autograder's log: Gradescope shows it to instructors only, while ``stdout_visibility`` is
    ``hidden``; results.json shows students a verdict only."""
    lines = []
    for exercise in result.exercises:
        for check in exercise.checks:
            if check.hidden and check.score < check.max_score:
                lines.append(f"hidden {exercise.id} {check.name} ({check.score:g}/{check.max_score:g}): "
                             f"{check.message}" + (f"\n  hint: {check.hint}" if check.hint else ""))
                if check.traceback:
                    lines.append(check.traceback.rstrip())
    return "\n".join(lines)


def _fenced(text: str) -> str:
    """``text`` in a Markdown code block that no backtick run inside it can close."""
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    fence = "`" * max(3, longest + 1)
    return f"{fence}\n{text}\n{fence}"


def _check_markdown(check) -> str:
    """A check's output for Gradescope's ``md`` format: the message's first line (the
    diagnosis) as text, the lines after it in a code block that keeps their column
    layout (matrices); what the student's code printed is quoted
    verbatim, never rendered."""
    if check.advice:
        message = f"Tip (no points): {check.message}"
    elif check.max_score == 0:
        message = check.message or "Advice: nothing to suggest."
    else:
        message = check.message or ("Passed." if check.passed else check.status)
    # The diagnosis (the first line) reads as text; what follows keeps its layout.
    first, _, details = message.partition("\n")
    parts = [_escape_markdown(first)] + ([_fenced(details)] if details.strip() else [])
    if check.hint:
        parts.append("**Hint:** " + _escape_markdown(check.hint))
    if check.traceback:
        parts.append("Traceback (your code):\n\n" + _fenced(check.traceback))
    if check.output:
        parts.append("What your code printed:\n\n" + _fenced(check.output))
    return "\n\n".join(parts)


def _escape_markdown(text: str) -> str:
    """Plain text in Markdown: no emphasis, links, code or HTML (intraword _ is safe)."""
    return re.sub(r"([\\`*\[\]<>])", r"\\\1", text)


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
        result = grade(submission, config.select, limits=config.limits(), pictures="none",  # text only
                       forbid=config.forbid, inputs_secret=config.inputs_secret or None,
                       refuse_weaker=not config.allow_weaker_confinement)
        data = results_json(result, config)
        instructors_only = hidden_checks_log(result) if config.stdout_visibility == "hidden" else ""
        if instructors_only:  # the autograder's output, which students never see
            print(instructors_only, flush=True)
    except WeakerConfinement as exc:  # before any student code ran
        log.error("not graded: %s; set allow_weaker_confinement in the course configuration to accept it", exc)
        data = failure_json("The autograder did not run this submission: it could not confine student code "
                            "as strongly as this machine allows. Please tell your instructor; the details "
                            "are in the autograder's log.", config)
    except SubmissionError as exc:  # nothing in the upload can be read as a submission
        data = failure_json(f"The autograder could not grade this submission: {exc}. "
                            "Upload the lab modules themselves (e.g. lab07_transformations.py, "
                            "or lab07_transformations.ipynb).", config)
    except Exception as exc:  # noqa: BLE001 - results.json must be written whatever happens
        log.exception("grading failed")
        data = failure_json(f"The autograder could not grade this submission because of an error in "
                            f"the autograder itself ({type(exc).__name__}), not in your files. "
                            "Please tell your instructor; the details are in the autograder's log.",
                            config)
    data["execution_time"] = round(time.monotonic() - started, 3)
    return write_results(results_path, data, config)


def write_results(path, data: dict, config: CourseConfig) -> dict:
    """Write ``data`` as ``results.json``, atomically: the whole file or none, never a partial or
    empty one. If the whole cannot be written (a full disk), a small valid file still keeps
    the score and says why the rest is missing. Returns what was written (None-free)."""
    try:
        write_atomically(path, json.dumps(data, indent=1, allow_nan=False) + "\n")
        return data
    except (OSError, ValueError) as exc:  # ValueError: a score that is not a number
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        log.error("cannot write %s: %s; writing the score alone", path, reason)
    score = data.get("score")
    score = float(score) if isinstance(score, (int, float)) and math.isfinite(score) else 0.0
    tests = data.get("tests", [])
    # The score travels in one test as hidden as the hidden checks were, so it shows no sooner.
    hidden = any(t.get("visibility") == config.hidden_visibility for t in tests)
    minimal = {"score": score, "execution_time": data.get("execution_time", 0.0), "output_format": "text",
               "output": f"The autograder graded this submission but could not write its full results "
                         f"({reason}): only the score is here. Please tell your instructor.",
               "stdout_visibility": config.stdout_visibility, "tests": []}
    if tests:
        possible = sum(t["max_score"] for t in tests if isinstance(t.get("max_score"), (int, float)))
        minimal["tests"] = [{"name": "Total (the full results could not be written)", "score": score,
                             "max_score": possible if math.isfinite(possible) else score, "output": "",
                             "visibility": config.hidden_visibility if hidden else config.public_visibility}]
    try:
        write_atomically(path, json.dumps(minimal, indent=1) + "\n")
    except OSError as exc:  # no results.json at all rather than a broken one; run_autograder tries too
        log.error("cannot write %s at all: %s", path, exc.strerror or exc)
    return minimal


# ------------------------------------------------------------------ autograder.zip
SETUP_SH = """#!/usr/bin/env bash
# Installs the autograder on Gradescope's Ubuntu image with the pinned versions
# of constraints.txt (the versions the grader is tested with), on a Python the
# grader is tested on: the image's own python3 if it is one of them, otherwise
# a tested Python installed by uv.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends python3 python3-venv python3-pip util-linux
TESTED="{tested}"
version="$(python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
if [[ " $TESTED " == *" $version "* ]]; then
    python3 -m venv /autograder/venv
else
    echo "setup.sh: the image's Python $version is not one the grader is tested on ($TESTED); installing {preferred}"
    python3 -m pip install --quiet uv || python3 -m pip install --quiet --break-system-packages uv
    UV_PYTHON_INSTALL_DIR=/opt/python python3 -m uv venv --seed --python {preferred} /autograder/venv
fi
/autograder/venv/bin/python -m pip install --upgrade pip
/autograder/venv/bin/python -m pip install -c /autograder/source/constraints.txt /autograder/source
chmod -R a+rX /autograder/venv
if [ -d /opt/python ]; then chmod -R a+rX /opt/python; fi
# Student code runs as this unprivileged user when grading as root.
id agworker >/dev/null 2>&1 || useradd --system --no-create-home --home-dir /nonexistent \\
    --shell /usr/sbin/nologin --user-group agworker
""".format(tested=" ".join(TESTED_PYTHONS), preferred=TESTED_PYTHONS[1])

RUN_AUTOGRADER = """#!/usr/bin/env bash
# Grades $ROOT/submission and writes $ROOT/results/results.json (always).
# AUTOGRADER_ROOT and AUTOGRADER_PYTHON exist for tests; Gradescope sets neither.
set -uo pipefail
ROOT="${AUTOGRADER_ROOT:-/autograder}"
PYTHON="${AUTOGRADER_PYTHON:-$ROOT/venv/bin/python}"
RESULTS="$ROOT/results/results.json"
mkdir -p "$ROOT/results"
cd "$ROOT/source"
status=0
"$PYTHON" -m autograder gradescope run --submission "$ROOT/submission" \\
    --results "$RESULTS" --config "$ROOT/source/course.json" || status=$?
if [ ! -s "$RESULTS" ]; then
    # Only if the grader itself could not start: still give Gradescope valid results.
    # Written whole and renamed, or not at all: never an empty or partial results.json.
    if printf '{"score": 0, "execution_time": 0, "output": "The autograder failed to start (exit status %s). Please tell your instructor.", "stdout_visibility": "hidden", "tests": []}\\n' "$status" > "$RESULTS.tmp" \\
            && sync "$RESULTS.tmp"; then
        mv "$RESULTS.tmp" "$RESULTS"
    else
        rm -f "$RESULTS.tmp"
    fi
fi
exit 0
"""

# What the container needs: the engine (hidden checks included) and the fixtures,
# never the reference solutions or the grader's own tests.
_SHIPPED = ("autograder", "fixtures")
_SHIPPED_FILES = ("pyproject.toml", "README.md", "grade.py", "constraints.txt")


def _shipped_files(root: Path):
    for top in _SHIPPED:
        for path in sorted((root / top).rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts and path.suffix != ".pyc" \
                    and not path.name.startswith("make_"):
                yield path
    for name in _SHIPPED_FILES:
        yield root / name


def build(out, config: CourseConfig | None = None, root: Path = PROJECT_ROOT) -> Path:
    """Write ``autograder.zip``: ``setup.sh`` and ``run_autograder`` at its root, plus sources.

    Its ``course.json`` is ``config``, with a new ``inputs_secret`` where ``config`` has
    none (set one in the course configuration to keep the same inputs across builds)."""
    from .registry import select

    out = Path(out)
    config = config or CourseConfig()
    if not config.inputs_secret:  # the official grading's inputs: known to no one who lacks the zip
        config = dataclasses.replace(config, inputs_secret=secrets.token_hex(16))
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
