"""What changed since the student's previous run of ``grade.py``.

Each feedback page carries its scores, as data (``<script type="application/json"
id="autograder-scores">``, never executed: :func:`autograder.reports.html.scores_script`);
a ``--json`` results file carries them too.
Before a run overwrites either, the grader reads the scores the previous run left there
and tells what moved: ``lab07.ex2: 0 -> 12`` on the terminal and at the top of the new
page. Only exercises graded both times are compared, so ``python grade.py lab07.ex2``
after a whole run speaks of lab07.ex2 alone; and only runs of the same submission (by its name):
``autograder grade class/alice`` after ``class/carla`` in one folder compares nothing.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

from ..engine.results import GradingResult
from ..reports.html import SCORES_ID

_SCORES = re.compile(f'<script type="application/json" id="{SCORES_ID}">(.*?)</script>', re.S)
_READ_AT_MOST = 64 << 20   # a results file with its pictures; anything larger is not ours
_PAGE_TAIL = 1 << 20       # what is read of a page: its end, where the scores are


def previous_scores(*paths) -> dict | None:
    """The scores a previous run left in the first of ``paths`` (a feedback page or a results
    JSON file) that holds some; None when none does (a first run, or a page of another tool)."""
    for path in paths:
        if not path:
            continue
        path = Path(path)
        page = path.suffix.lower() in (".html", ".htm")
        try:
            if not path.is_file() or (not page and path.stat().st_size > _READ_AT_MOST):
                continue
            with path.open("rb") as file:
                if page:   # the block closes the page, after its pictures: its tail is enough
                    file.seek(max(0, path.stat().st_size - _PAGE_TAIL))
                text = file.read(_READ_AT_MOST).decode("utf-8", errors="replace")
        except OSError:
            continue
        scores = _from_page(text) if page else _from_results(text)
        if scores is not None:
            return scores
    return None


def _from_page(text: str) -> dict | None:
    found = _SCORES.search(text)
    if not found:
        return None
    try:
        return _valid(json.loads(found[1]))   # JSON, not HTML: its escapes are JSON's own
    except ValueError:
        return None


def _from_results(text: str) -> dict | None:
    try:
        data = json.loads(text)
        return _valid({"total": data["total"], "max_total": data["max_total"], "submission": data.get("submission"),
                       "exercises": {e["id"]: [e["score"], e["max_score"]] for e in data["exercises"]}})
    except (ValueError, KeyError, TypeError):
        return None


def _valid(scores) -> dict | None:
    exercises = scores.get("exercises") if isinstance(scores, dict) else None
    if not isinstance(exercises, dict):
        return None
    kept = {key: value for key, value in exercises.items() if isinstance(key, str) and isinstance(value, list)
            and len(value) == 2 and all(isinstance(v, (int, float)) for v in value)}
    submission = scores.get("submission")
    return {"exercises": kept, "submission": submission if isinstance(submission, str) else None}


def since(previous: dict | None, result: GradingResult) -> list[str]:
    """``["lab07.ex2: 0 -> 12", ...]``: the exercises graded both times whose score moved
    (one whose points are now counted otherwise, e.g. a hidden check released, is told with its maximum)."""
    if not previous:
        return []
    if previous.get("submission") not in (None, result.submission):
        return []   # (another submission's page in this folder: an instructor grading student after student)
    moved = []
    for exercise in result.exercises:
        before = previous["exercises"].get(exercise.id)
        if before is None:
            continue
        (score, maximum), now = before, (exercise.score, exercise.max_score)
        if abs(score - now[0]) > 1e-6 or abs(maximum - now[1]) > 1e-6:
            out_of = f" (out of {_n(maximum)} then, {_n(now[1])} now)" if abs(maximum - now[1]) > 1e-6 else ""
            moved.append(f"{exercise.id}: {_n(score)} -> {_n(now[0])}{out_of}")
    return moved


def _n(value: float) -> str:
    return f"{round(value, 2):g}"
