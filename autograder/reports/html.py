"""The feedback page: one self-contained HTML file (pictures embedded, no JavaScript)."""

from __future__ import annotations

import functools
import json
import re

from jinja2 import Environment, PackageLoader, select_autoescape
from markupsafe import Markup, escape

from ..engine import pictures
from ..engine.results import ADVICE, ERROR, NOT_IMPLEMENTED, PARTIAL, PASSED, GradingResult, write_atomically
from ..engine.versions import describe

_UNSAFE_SVG = re.compile(r"<\s*(script|foreignObject|iframe)|\bon\w+\s*=|javascript:", re.IGNORECASE)


def _safe_svg(svg: str) -> Markup:
    """Inline SVG made by the grader; anything that could run script is shown as text."""
    if svg.lstrip().startswith("<svg") and not _UNSAFE_SVG.search(svg):
        return Markup(svg)
    return escape(svg)


def _grade_class(exercise) -> str:
    if exercise.max_score and exercise.score >= exercise.max_score:
        return "full"
    return "some" if exercise.score > 0 else "none"


_STATUS = {PASSED: ("passed", "✓"), PARTIAL: ("partial", "◐"), NOT_IMPLEMENTED: ("notimpl", "·"),
           ERROR: ("error", "!"), ADVICE: ("advice", "tip")}


@functools.lru_cache(maxsize=1)
def _environment() -> Environment:
    """The templates' environment, made once per process: it keeps its compiled templates
    (compiling them costs a tenth of a second; a batch renders a page per student)."""
    env = Environment(loader=PackageLoader("autograder.reports", "templates"),
                      autoescape=select_autoescape(["html", "j2"]), trim_blocks=True, lstrip_blocks=True)
    env.filters["num"] = lambda x: f"{x:g}"
    env.filters["grade_class"] = _grade_class
    env.filters["status_class"] = lambda c: _STATUS.get(c.status, ("failed", "✗"))[0]
    env.filters["status_icon"] = lambda c: _STATUS.get(c.status, ("failed", "✗"))[1]
    env.filters["safe_svg"] = _safe_svg
    env.filters["check_name"] = lambda c: c.name.removesuffix(" (hidden)").rstrip()
    return env


def prepare() -> None:
    """Compile the page's templates now (a tenth of a second), e.g. while a worker boots."""
    for name in ("feedback.html.j2", "_checks.html.j2"):
        _environment().get_template(name)


def what_was_graded(result: GradingResult) -> str:
    """``lab07 ex1, ex2 · lab11 ex3``: the exercises on this page, per lab."""
    labs: dict[str, list[str]] = {}
    for exercise in result.exercises:
        lab, key = exercise.id.split(".", 1)
        labs.setdefault(lab, []).append(key)
    return " · ".join(f"{lab} {', '.join(keys)}" for lab, keys in labs.items())


def _graded_at(result: GradingResult) -> str:
    return result.graded_at.replace("T", " ").replace("+00:00", " UTC") if result.graded_at else ""


class PictureSheet:
    """Every distinct picture of a page once, compactly encoded, drawn wherever it is
    used by reference (``<use href="#id">``): pages show the same input in many checks.

    :meth:`figure` lays out one artifact: its pictures drawn at their relative sizes
    (the tallest at :data:`DRAWN_HEIGHT` CSS pixels, small ones enlarged at most
    :data:`MAX_ENLARGEMENT` times), each labelled with its size in pixels.
    """

    DRAWN_HEIGHT = 170   # four 4:3 pictures to a row on a laptop, two on a phone
    WIDE_FIGURE = 1.8    # a single picture this much wider than tall is a composite (a pair
    FIGURE_WIDTH = 900   # side by side): drawn as wide as the page allows, so it can be read
    MAX_ENLARGEMENT = 3.0
    # The page's pictures together (base64 characters): past it, the pictures only passed checks show -- folded
    # away under "pictures" -- are encoded at half their size, largest first, so a complete submission's page stays
    # within 2 MB (DESIGN's budget) however many checks draw; a failed check's pictures keep their size.
    PICTURES_BUDGET = 1_500_000

    def __init__(self, prefix: str = "pic"):
        self.prefix = prefix
        self.entries: dict[str, dict] = {}
        self._needed: set[str] = set()   # the entries a check that did not pass shows

    def _entry(self, item: dict) -> dict:
        key = item.get("data") or item["png"]
        if key not in self.entries:
            if "data" in item:  # encoded when the check drew it (pictures.picture_item)
                mime, data, (width, height) = item["mime"], item["data"], item["encoded_size"]
            else:  # results written before pictures were encoded once: a base64 PNG
                mime, data, width, height = pictures.compact_encoding(item["png"])
            self.entries[key] = {"id": f"{self.prefix}{len(self.entries)}", "mime": mime, "data": data,
                                 "width": width, "height": height}
        return self.entries[key]

    def figure(self, artifact, passed: bool = False) -> dict:
        """One artifact laid out (``passed``: of a check that passed, whose pictures may be made smaller)."""
        items = [dict(item, entry=self._entry(item)) for item in artifact.items
                 if item.get("data") or item.get("png")]
        if not passed:
            self._needed.update(item["entry"]["id"] for item in items)
        for item in items:  # results written before sizes were recorded: the picture's own
            item.setdefault("width", item["entry"]["width"])
            item.setdefault("height", item["entry"]["height"])
        tallest = max([item["height"] for item in items] + [1])
        scale = min(self.MAX_ENLARGEMENT, self.DRAWN_HEIGHT / tallest)
        if len(items) == 1 and items[0]["width"] > self.WIDE_FIGURE * items[0]["height"]:
            scale = min(self.MAX_ENLARGEMENT, self.FIGURE_WIDTH / items[0]["width"], 2.4 * scale)
        drawn = [{"label": item["label"], "id": item["entry"]["id"], "view": (item["entry"]["width"],
                                                                            item["entry"]["height"]),
                  "width": max(24, round(item["width"] * scale)),
                  "size": f"{item['width']} × {item['height']}",
                  "heat": item["label"] == "difference"} for item in items]
        return {"pictures": drawn, "caption": _figure_caption(artifact, items)}


    def encoded(self) -> list[dict]:
        """Every entry as the page embeds it, within :data:`PICTURES_BUDGET` where the passed checks' pictures
        allow (each keeps its drawn size: a smaller bitmap fills the same box)."""
        entries = list(self.entries.values())
        total = sum(len(e["data"]) for e in entries)
        for entry in sorted((e for e in entries if e["id"] not in self._needed), key=lambda e: -len(e["data"])):
            if total <= self.PICTURES_BUDGET:
                break
            mime, data, _, _ = pictures.compact_encoding(entry["data"], max(1, entry["width"] // 2),
                                                         max(1, entry["height"] // 2))
            if len(data) < len(entry["data"]):
                total -= len(entry["data"]) - len(data)
                entry["mime"], entry["data"] = mime, data
        return entries


def _figure_caption(artifact, items) -> str:
    """The artifact's caption, plus why a comparison has no difference map when it has none:
    one sentence (a caption about the difference map gives way to it)."""
    by_label = {item["label"]: item for item in items}
    caption = artifact.caption
    expected, yours = by_label.get("expected"), by_label.get("yours")
    if expected and yours and "difference" not in by_label:
        sizes = [(i["width"], i["height"]) for i in (yours, expected)]
        if sizes[0] != sizes[1]:
            note = (f"no difference map: your image is {sizes[0][0]} × {sizes[0][1]} pixels and the "
                    f"expected one {sizes[1][0]} × {sizes[1][1]} (width × height), so they cannot be "
                    "compared pixel by pixel")
            caption = note if not caption or "difference map" in caption else f"{caption.rstrip('. ')}; {note}"
    return caption


SCORES_ID = "autograder-scores"


def scores_script(result: GradingResult) -> Markup:
    """The page's scores as data for the next run's comparison (:mod:`autograder.student.progress`):
    a JSON block, never executed; every ``<`` escaped, so no text in it can end the script early."""
    scores = {"total": result.total, "max_total": result.max_total, "submission": result.submission,
              "exercises": {e.id: [e.score, e.max_score] for e in result.exercises}}
    text = json.dumps(scores, sort_keys=True).replace("<", "\\u003c")   # no "</script>", no "<!--"
    return Markup(f'<script type="application/json" id="{SCORES_ID}">{text}</script>')


def render(result: GradingResult, figures: dict[str, bytes] | None = None, since: list[str] = ()) -> str:
    """The feedback page as a string; ``figures`` (figure id -> PNG bytes, from
    :mod:`autograder.figures`) are shown at the top of their exercise (``lab09.ex3`` and
    ``lab09.ex3-extension`` at the top of lab09.ex3); ``since``, what changed since the
    student's previous run (:func:`autograder.student.progress.since`), at the top."""
    import base64

    percent = round(100 * result.total / result.max_total) if result.max_total else 0
    encoded = {}
    for figure_id, png in (figures or {}).items():
        mime, data, width, height = pictures.compact_encoding(base64.b64encode(png).decode("ascii"),
                                                              max_width=1400, max_height=900)
        encoded.setdefault(figure_id.split("-", 1)[0], []).append(
            {"mime": mime, "data": data, "width": width, "height": height})
    return _environment().get_template("feedback.html.j2").render(
        result=result, percent=percent, graded=what_was_graded(result), graded_at=_graded_at(result),
        judged_with=describe(result.versions), sheet=PictureSheet(), heat_scale=", ".join(pictures.heat_scale_stops()), figures=encoded,
        since=list(since), scores=scores_script(result))


def write(result: GradingResult, path, figures: dict[str, bytes] | None = None, since: list[str] = ()) -> None:
    write_atomically(path, render(result, figures, since))


def render_selfcheck(result: GradingResult, source: str) -> str:
    """The result of ``check(...)`` as an HTML fragment for a notebook's output area
    (picture ids unique to it: a notebook shows many such fragments)."""
    import secrets

    return _environment().get_template("selfcheck.html.j2").render(
        result=result, source=source, sheet=PictureSheet(f"ag{secrets.token_hex(4)}-"),
        heat_scale=", ".join(pictures.heat_scale_stops()))
