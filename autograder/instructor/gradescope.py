"""Gradescope: ``results.json`` from a grading, and the ``autograder.zip`` that produces it.

``run_autograder`` (in the zip) calls :func:`run`, which always writes one
``results.json``, atomically and once, also when the submission or the grader
fails. The format follows Gradescope's published autograder specification: per
test ``name``, ``number``, ``score``, ``max_score``, ``status``, ``output``,
``output_format`` and ``visibility``; at the top ``score``, ``execution_time``,
``output`` and ``stdout_visibility``.

A check's output is HTML (``output_format: "html"``): the diagnosis, the details in
``<pre>``, and for a public check that lost points small copies of its pictures as
``data:`` PNG/JPEG images, within :data:`PICTURES_BUDGET` for the whole file. Every
word in it is escaped; it uses only tags Gradescope's sanitiser keeps (see
:data:`HTML_TAGS`). Students cannot download files from Gradescope, so the
full-size feedback page stays the one ``python grade.py`` writes on their own copy.
"""

from __future__ import annotations

import dataclasses
import html
import json
import logging
import math
import os
import secrets
import shutil
import time
import zipfile
from pathlib import Path

from ..engine.results import GradingResult, write_atomically
from ..engine.versions import constraints_file, describe
from ..loading.submission import SubmissionError
from ..loading.text import printable
from ..sandbox.confine import WeakerConfinement
from .course import CourseConfig

log = logging.getLogger("autograder")
PROJECT_ROOT = Path(__file__).resolve().parents[2]
# The Python versions the grader is tested on (pyproject's requires-python);
# setup.sh installs the second (the one CI runs) where the image has none of them.
TESTED_PYTHONS = ("3.10", "3.11", "3.12", "3.13")


# ------------------------------------------------------------------ results.json
def results_json(result: GradingResult, config: CourseConfig) -> dict:
    """The Gradescope results for a grading: what students may see of it (hidden checks
    as verdicts, :meth:`~autograder.engine.results.GradingResult.for_students`). The hidden tests
    keep their points (the grade needs them; Gradescope keeps them from students until
    their ``visibility`` allows); the text at the top counts them only where the course
    shows hidden checks' points (``hidden_points_visible``)."""
    # In the course's points (``points``), as every other grade of the course is.
    result = result.in_points(config.point_factors([(e.id, e.max_score) for e in result.exercises]))
    shown = result.for_students(points_visible=True)  # hidden checks: a verdict, no pictures
    figures, left_out = pictures_within_budget(shown)
    tests, position = [], {}
    for exercise in shown.exercises:
        lab = exercise.id.split(".")[0]
        position[lab] = position.get(lab, 0) + 1  # ex1..exN then the extensions, as registered
        for index, check in enumerate(exercise.checks, 1):
            tests.append({
                "name": f"{exercise.id} {exercise.title}: {check.name}",
                "number": f"{int(lab[3:])}.{position[lab]}.{index}",
                "score": check.score,
                "max_score": check.max_score,
                "status": "passed" if check.passed or check.max_score == 0 else "failed",  # advice never fails
                "output": check_html(check, figures.get((exercise.id, index - 1), []),
                                     exercise.id if (exercise.id, index - 1) in left_out else ""),
                "output_format": "html",
                "visibility": config.hidden_visibility if check.hidden else config.public_visibility,
            })
    return {"score": result.total, "output": _summary(result.for_students(config.hidden_points_visible)),
            "output_format": "text",
            "stdout_visibility": config.stdout_visibility, "tests": tests}


def _summary(result: GradingResult) -> str:
    """The top of the results page: notes on how the files were read, the total, each
    exercise's score, a module-wide problem said once per lab, and where the full
    feedback page is."""
    lines = [f"Note: {note}" for note in result.notes]
    # (while hidden points are withheld this total is not results.json's score, which Gradescope keeps from students
    # until the tests are published: said on the line itself, for whoever reads the file)
    lines.append(f"Total: {result.total:g} / {result.max_total:g}"
                 + (" (public checks only; the grade counts the hidden checks too)" if result.hidden_points_withheld
                    else ""))
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
    if any(c.lost_points and not c.hidden for e in result.exercises for c in e.checks):
        lines.append(FULL_PAGE)
    if describe(result.versions):
        lines.append(f"Judged with {describe(result.versions)}.")
    return "\n".join(lines)


FULL_PAGE = ("Each check below shows small copies of its pictures (some are left out to keep these "
             "results small). The full feedback page, every picture at full size: run python grade.py "
             "in your copy of the labs (it writes feedback.html; the public checks are the same).")


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


# ------------------------------------------------------------------ a check's HTML
# Gradescope renders a test's "html" output after sanitising it and documents neither the
# tags it keeps nor a size limit for results.json. The output uses only tags of Rails'
# default safe list (Gradescope is a Rails application), with no style attributes, and
# pictures as data: URIs of PNG or JPEG, the image types every version of Rails' sanitiser
# (Loofah) lets through; SVG, inline or as a data: URI, is not relied on.
HTML_TAGS = frozenset({"p", "pre", "strong", "em", "br", "div", "img"})
THUMBNAIL = (480, 180)      # largest copy of an image (width, height): a row of four fits a page
PLOT = (360, 300)           # largest copy of a point plot: its own size, so its labels stay legible
PICTURES_BUDGET = 750_000   # characters of base64 pictures in one results.json, all checks together
_SMALLEST_PICTURE = 2_000   # below this much budget left, no further check's pictures can fit


@dataclasses.dataclass
class Figure:
    """One artifact of a check, in small copies: ``pictures`` are ``(label, mime, base64
    data, width, height)``."""

    title: str
    caption: str
    pictures: list[tuple[str, str, str, int, int]]

    @property
    def size(self) -> int:
        return sum(len(data) for _, _, data, _, _ in self.pictures)


def figures_of(check) -> list[Figure]:
    """Small copies of ``check``'s pictures: images at most :data:`THUMBNAIL`, point plots
    drawn as PNG (at most :data:`PLOT`); a picture that cannot be drawn is left out."""
    import cv2

    from ..engine import pictures

    figures = []
    for artifact in check.artifacts:
        drawn = []
        for item in artifact.items:
            try:
                if artifact.kind == "svg":
                    mime, data, width, height = pictures.compact(pictures.rasterise_svg(item["svg"]), *PLOT)
                else:
                    mime, data, width, height = pictures.compact_encoding(item.get("data") or item["png"],
                                                                          *THUMBNAIL)
            except (KeyError, ValueError, cv2.error):
                continue
            if mime in ("image/png", "image/jpeg"):
                drawn.append((item.get("label", ""), mime, data, width, height))
        if drawn:
            figures.append(Figure(artifact.title, artifact.caption, drawn))
    return figures


def pictures_within_budget(result: GradingResult, budget: int | None = None
                           ) -> tuple[dict[tuple[str, int], list[Figure]], set[tuple[str, int]]]:
    """Which checks of ``result`` show their pictures: ``(shown, left_out)``, keyed by
    ``(exercise id, index of the check)``. Only public checks that lost points have
    pictures shown, each check's whole or none, within ``budget`` characters of base64
    (default :data:`PICTURES_BUDGET`); ``left_out`` are those that did not fit.

    The budget goes round the exercises: each exercise's first such check first, then
    each one's second, and so on; so a submission wrong everywhere shows pictures in as
    many exercises as fit rather than all of the first lab's."""
    queues = [[((e.id, index), check) for index, check in enumerate(e.checks)
               if check.artifacts and check.lost_points and not check.advice
               and not check.hidden and not check.redacted] for e in result.exercises]
    budget = PICTURES_BUDGET if budget is None else budget
    shown: dict[tuple[str, int], list[Figure]] = {}
    left_out: set[tuple[str, int]] = set()
    for rank in range(max((len(q) for q in queues), default=0)):
        for key, check in (queue[rank] for queue in queues if rank < len(queue)):
            if budget < _SMALLEST_PICTURE:
                left_out.add(key)
                continue
            figures = figures_of(check)
            cost = sum(f.size for f in figures)
            if figures and cost <= budget:
                shown[key] = figures
                budget -= cost
            elif figures:
                left_out.add(key)
    return shown, left_out


# What a picture's label alone does not say (the feedback page draws a colour scale).
_LABELS = {"difference": "difference (dark where equal, bright where 64 or more grey levels apart)"}


def _text(text) -> str:
    """Student or grader text as HTML: control characters removed, everything escaped."""
    return html.escape(printable(text), quote=True)


def check_html(check, figures: list[Figure] = (), left_out: str = "") -> str:
    """A check's output for Gradescope's ``html`` format: the message's first line (the
    diagnosis) as a paragraph, the lines after it in ``<pre>`` (matrices keep their
    columns), the hint, the traceback and what the student's code printed (verbatim,
    escaped, never rendered), then ``figures``. ``left_out``: the exercise id of a check
    whose pictures did not fit in the budget; the output says how to see them."""
    if check.advice:
        message = f"Tip (no points): {check.message}"
    elif check.max_score == 0:
        message = check.message or "Advice: nothing to suggest."
    else:
        message = check.message or ("Passed." if check.passed else check.status)
    first, _, details = message.partition("\n")
    parts = [f"<p>{_text(first)}</p>"] + ([f"<pre>{_text(details)}</pre>"] if details.strip() else [])
    if check.hint:
        parts.append(f"<p><strong>Hint:</strong> {_text(check.hint)}</p>")
    if check.traceback:
        parts.append(f"<p>Traceback (your code):</p><pre>{_text(check.traceback)}</pre>")
    if check.output:
        parts.append(f"<p>What your code printed:</p><pre>{_text(check.output)}</pre>")
    for figure in figures:
        title = figure.title + (f" - {figure.caption}" if figure.caption else "")
        images = " ".join(f'<img src="data:{mime};base64,{data}" alt="{_text(label)}" title="{_text(label)}" '
                          f'width="{width}" height="{height}">'
                          for label, mime, data, width, height in figure.pictures)
        labels = ", ".join(_text(_LABELS.get(label, label)) for label, *_ in figure.pictures if label)
        parts.append(f"<p><strong>{_text(title)}</strong></p><div>{images}</div>"
                     + (f"<p><em>Left to right: {labels}.</em></p>" if len(figure.pictures) > 1 and labels else ""))
    if left_out:
        parts.append(f"<p><em>Pictures left out here to keep these results small: python grade.py "
                     f"{_text(left_out)} on your own copy shows them on your feedback page.</em></p>")
    return "\n".join(parts)


def failure_json(message: str, config: CourseConfig) -> dict:
    """Results when nothing could be graded: score 0 and a clear message."""
    return {"score": 0.0, "output": message, "output_format": "text",
            "stdout_visibility": config.stdout_visibility, "tests": []}


def run(submission, results_path, config: CourseConfig | None = None) -> dict:
    """Grade ``submission`` and write ``results_path``; never raises for a bad submission."""
    from ..engine.runner import grade

    config = config or CourseConfig()
    started = time.monotonic()
    withhold_readable_reference()
    try:
        result = grade(submission, config.select, limits=config.limits(), pictures="failed",
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


def withhold_readable_reference(hides_files: bool | None = None) -> bool:
    """Delete the container's copy of the reference solutions (the error model's) when student
    code would run where it can read the grader's files (a weaker level the course allowed):
    the error model then names nothing, and no student can print the reference. True if deleted."""
    from ..sandbox import confine

    folder = os.environ.get("AUTOGRADER_REFERENCE_SOLUTIONS")
    if not folder or not Path(folder).is_dir():
        return False
    if hides_files is None:
        hides_files = confine.detect().hides_files
    if hides_files:
        return False
    log.warning("student code can read this machine's files: the reference solutions are removed, "
                "the error model names nothing")
    shutil.rmtree(folder, ignore_errors=True)
    return True


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

# Appended to SETUP_SH: a wrong OpenCV fails the build, where the instructor sees it, not a grading.
OPENCV_CHECK = """# The course grades with OpenCV {major} ("opencv" in course.json; constraints.txt holds its pins).
/autograder/venv/bin/python -c "import cv2, sys; sys.exit(0 if cv2.__version__.split('.')[0] == '{major}' else 'setup.sh: the course grades with OpenCV {major}, but ' + cv2.__version__ + ' was installed')"
"""

RUN_AUTOGRADER = """#!/usr/bin/env bash
# Grades $ROOT/submission and writes $ROOT/results/results.json (always).
# AUTOGRADER_ROOT and AUTOGRADER_PYTHON exist for tests; Gradescope sets neither.
set -uo pipefail
ROOT="${AUTOGRADER_ROOT:-/autograder}"
PYTHON="${AUTOGRADER_PYTHON:-$ROOT/venv/bin/python}"
RESULTS="$ROOT/results/results.json"
mkdir -p "$ROOT/results"
cd "$ROOT/source"
# The error model's reference (when the course ships it): read by the grader, never by the worker.
export AUTOGRADER_REFERENCE_SOLUTIONS="$ROOT/source/reference_solutions"
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

# What the container needs: the engine (hidden checks included) and the fixtures, and the
# reference solutions for the error model (unless the course says no: ``error_model``), never
# the mistakes tables or the grader's own tests. Student code sees none of them: the worker's
# file system is built without /autograder/source and the installed grader.
_SHIPPED = ("autograder", "fixtures")
_REFERENCE = "reference_solutions"
_NOT_SHIPPED = ("autograder/labs/mistakes/",)
_SHIPPED_FILES = ("pyproject.toml", "README.md", "grade.py", "constraints.txt")


def _shipped_files(root: Path, error_model: bool = True):
    for top in _SHIPPED + ((_REFERENCE,) if error_model else ()):
        for path in sorted((root / top).rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts and path.suffix != ".pyc" \
                    and not path.name.startswith("make_") \
                    and not path.relative_to(root).as_posix().startswith(_NOT_SHIPPED):
                yield path
    for name in _SHIPPED_FILES:
        yield root / name


def build(out, config: CourseConfig | None = None, root: Path = PROJECT_ROOT) -> Path:
    """Write ``autograder.zip``: ``setup.sh`` and ``run_autograder`` at its root, plus sources.

    Its ``course.json`` is ``config``, with a new ``inputs_secret`` where ``config`` has
    none (set one in the course configuration to keep the same inputs across builds).
    The course's own labs ship as ``course_labs/<lab key>/`` (suite, hidden checks,
    helpers; not their reference, skeleton or mistakes table), named so in it."""
    from ..engine.labfolders import MISTAKES, REFERENCE, SKELETON
    from ..engine.registry import select
    from .bundle import COURSE_LABS, course_lab_folders, shipped_lab_files

    out = Path(out)
    config = config or CourseConfig()
    if not config.inputs_secret:  # the official grading's inputs: known to no one who lacks the zip
        config = dataclasses.replace(config, inputs_secret=secrets.token_hex(16))
    lab_folders = course_lab_folders(config)
    config.use_labs()
    select(config.select)  # a course that names a missing lab fails now, not at the deadline
    config.check_forbidden_names()
    left_out = (SKELETON, MISTAKES) if config.error_model else (REFERENCE, SKELETON, MISTAKES)
    shipped_labs = {f"{COURSE_LABS}/{f.lab.key}": shipped_lab_files(f.folder, left_out) for f in lab_folders}
    config = dataclasses.replace(config, labs=list(shipped_labs))   # where they are in the zip
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_name(out.name + ".tmp")
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as zf:
        _add(zf, "setup.sh", SETUP_SH + OPENCV_CHECK.format(major=config.opencv), executable=True)
        _add(zf, "run_autograder", RUN_AUTOGRADER, executable=True)
        _add(zf, "course.json", config.to_json())
        for path in _shipped_files(root, config.error_model):
            if path.name == "constraints.txt":   # the pins of the course's OpenCV major
                path = constraints_file(config.opencv, root)
                _add(zf, "constraints.txt", path.read_bytes())
                continue
            _add(zf, path.relative_to(root).as_posix(), path.read_bytes())
        for (shipped, files), lab_folder in zip(shipped_labs.items(), lab_folders):
            for path in files:
                _add(zf, f"{shipped}/{path.relative_to(lab_folder.folder).as_posix()}", path.read_bytes())
    tmp.replace(out)
    return out


def _add(zf: zipfile.ZipFile, name: str, data, executable: bool = False):
    info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))  # reproducible archives
    info.compress_type = zipfile.ZIP_DEFLATED
    info.external_attr = ((0o755 if executable else 0o644) | 0o100000) << 16
    zf.writestr(info, data.encode() if isinstance(data, str) else data)
