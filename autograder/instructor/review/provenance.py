"""Figure provenance: which pictures of a student's report their submitted code does not make.

The report's pictures (a PDF's, a notebook's image outputs, the files a Markdown report
links to) were thumbnailed in a sandbox
worker when the class was read (:class:`autograder.loading.report.ReportFigure`; never
decoded in the grader's process). The figures the student's code makes are the PNGs the
batch drew from it (``RESULTS/<student>/figures/<figure id>.png``, the grader's own
files: the pictures ``python grade.py --figures`` makes for the report), thumbnailed here
the same way (:func:`autograder.sandbox.report_reader.thumbnail`: grey, ``128 x 128`` by
area averaging).

Two pictures are the same figure (:func:`same_figure`) when

- their aspect ratios differ by less than :data:`MAX_ASPECT_CHANGE` (a figure rescaled
  keeps its shape);
- the whole: the zero-mean normalised correlation of their thumbnails at ``64 x 64`` is at
  least :data:`SAME_WHOLE` (a panel made darker or lighter falls below), and
- the details: the thumbnails' fine structure (the thumbnail less its Gaussian blur,
  sigma 2 px), correlated in each of 4 x 4 blocks, is at least :data:`SAME_DETAIL` in the
  worst block that has any (a panel shifted, turned or replaced falls below there, while
  the rest of the figure still matches).

Measured on the 14 figures of labs 7 and 8 (benchmarks/bench_provenance.py): the same
figure rescaled to 25-150 % and JPEG-compressed at quality 30-80 scores at least 0.990
whole and 0.74 in detail; two different figures of the same shape at most 0.966 whole and
0.34 in detail; one panel of three shifted by 12 px, turned by 5 degrees or replaced, at
most 0.97 whole and 0.32 in detail; made 30 % darker, at most 0.974 whole.

What the reviewer is told, per report figure (:func:`findings`): "matches lab07.ex2's figure",
or "matches none of the figures your code makes" -- said only when that is meaningful:
the code made figures to compare with, and the picture is not plain (a uniform or almost
uniform picture correlates with nothing). Otherwise it says why no comparison was made.

Limits (said on the review screen's help and in docs/instructors/review.md): a picture the
student drew themselves from their code's output (another layout, one panel cropped out,
other colours, their own matplotlib plot) matches none even when the code made it: "matches
none" is a reason to look, not a verdict. A Markdown report's pictures are read only where
it links to them inside the hand-in; a PDF's vector drawings (a plot exported as vector
graphics) are no pictures and are not compared.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from ...sandbox.report_reader import THUMB, thumbnail

SAME_WHOLE = 0.98            # correlation of two 64 x 64 thumbnails of one figure, at least
SAME_DETAIL = 0.5            # correlation of their fine structure, in the worst 4 x 4 block, at least
DETAIL_SIGMA = 2.0           # the blur taken off a thumbnail to keep its fine structure (pixels)
MAX_ASPECT_CHANGE = 1.25     # width/height ratios of one figure differ by less than this factor
MIN_CONTRAST = 4.0           # grey levels (standard deviation) a thumbnail needs to be compared
MIN_COMPARED_SIDE = 64       # pixels: a smaller report picture has too little left to tell figures apart
MAX_FIGURE_BYTES = 32 * 2**20   # a code figure's PNG larger than this is not decoded


@dataclass(frozen=True)
class CodeFigure:
    figure_id: str           # "lab07.ex2"
    width: int
    height: int
    thumb: np.ndarray        # THUMB x THUMB grey uint8


@dataclass(frozen=True)
class Finding:
    """What one report figure is, for the reviewer."""

    number: int              # the report figure's number
    source: str              # "report.pdf, page 3"
    matched: str | None      # the code figure it matches (its id), if any
    score: float | None      # the best match found, as a share of the thresholds (>= 1: the same; None: not compared)
    sentence: str

    @property
    def unmatched(self) -> bool:
        """The code makes no figure like it (said only where the comparison means something)."""
        return self.matched is None and self.score is not None


def code_figures(paths: dict[str, Path]) -> list[CodeFigure]:
    """Thumbnails of the code's figures (figure id -> PNG the batch wrote); a file that cannot
    be decoded is left out. Each file is decoded once while it is unchanged (a review screen
    is shown again and again)."""
    found = []
    for figure_id, path in sorted(paths.items()):
        try:
            stat = path.stat()
        except OSError:
            continue
        if stat.st_size <= MAX_FIGURE_BYTES:
            made = _code_thumbnail(str(path), stat.st_mtime_ns, stat.st_size)
            if made is not None:
                found.append(CodeFigure(figure_id, *made))
    return found


@lru_cache(maxsize=2048)
def _code_thumbnail(path: str, mtime_ns: int, size: int) -> tuple[int, int, np.ndarray] | None:
    """(width, height, thumbnail) of a PNG of the grader's, None if it cannot be read
    (``mtime_ns`` and ``size``: a file written again is read again)."""
    import cv2

    try:
        image = cv2.imdecode(np.fromfile(path, np.uint8), cv2.IMREAD_COLOR)
    except OSError:
        return None
    if image is None:
        return None
    thumb = thumbnail(image)
    thumb.flags.writeable = False   # shared by every caller of the cache
    return image.shape[1], image.shape[0], thumb


def similarity(a: np.ndarray, b: np.ndarray) -> float:
    """Zero-mean normalised correlation of two thumbnails (-1..1; 0 when either is uniform)."""
    x = a.astype(np.float64).ravel() - a.mean()
    y = b.astype(np.float64).ravel() - b.mean()
    norm = math.sqrt(float(x @ x) * float(y @ y))
    return float(x @ y) / norm if norm else 0.0


def _detail(thumb: np.ndarray) -> np.ndarray:
    import cv2

    image = thumb.astype(np.float32)
    return image - cv2.GaussianBlur(image, (0, 0), DETAIL_SIGMA)


def worst_block(a: np.ndarray, b: np.ndarray, blocks: int = 4, flat: float = 2.0) -> float:
    """The lowest :func:`similarity` of ``a`` and ``b`` over a ``blocks x blocks`` grid, among
    the blocks where either has structure (a standard deviation above ``flat``); 1.0 if none has."""
    side = a.shape[0] // blocks
    scores = [similarity(x, y) for i in range(blocks) for j in range(blocks)
              for x, y in [(a[i * side:(i + 1) * side, j * side:(j + 1) * side],
                            b[i * side:(i + 1) * side, j * side:(j + 1) * side])]
              if x.std() > flat or y.std() > flat]
    return min(scores, default=1.0)


def scores(a: np.ndarray, b: np.ndarray) -> tuple[float, float]:
    """(whole, detail) of two ``THUMB x THUMB`` thumbnails (see the module's doc)."""
    import cv2

    half = (THUMB // 2, THUMB // 2)
    whole = similarity(cv2.resize(a.astype(np.float32), half, interpolation=cv2.INTER_AREA),
                       cv2.resize(b.astype(np.float32), half, interpolation=cv2.INTER_AREA))
    return whole, worst_block(_detail(a), _detail(b))


def same_figure(a: np.ndarray, b: np.ndarray) -> bool:
    whole, detail = scores(a, b)
    return whole >= SAME_WHOLE and detail >= SAME_DETAIL


def same_shape(width: int, height: int, other_width: int, other_height: int) -> bool:
    ratio = (width / height) / (other_width / other_height)
    return 1 / MAX_ASPECT_CHANGE < ratio < MAX_ASPECT_CHANGE


def findings(report_figures: list[dict], code: list[CodeFigure]) -> list[Finding]:
    """Per report figure (dicts as :meth:`.gradebook.Gradebook.report_figures` gives them),
    the code figure it matches, or why it matches none."""
    out = []
    for figure in report_figures:
        number, source = figure["number"], figure["source"]
        label = f"report figure {number} ({source}{'' if figure.get('exercise') else ', under no exercise heading'})"
        thumb = np.frombuffer(figure["thumb"], np.uint8)
        if thumb.size != THUMB * THUMB:
            continue
        thumb = thumb.reshape(THUMB, THUMB)
        if not code:
            out.append(Finding(number, source, None, None,
                               f"{label} was not compared: the batch has no figure made by this student's code"))
            continue
        if min(figure["width"], figure["height"]) < MIN_COMPARED_SIDE:
            out.append(Finding(number, source, None, None, f"{label} is {figure['width']} x {figure['height']} "
                                                           "pixels, too small to be compared"))
            continue
        if thumb.std() < MIN_CONTRAST:
            out.append(Finding(number, source, None, None, f"{label} is almost uniform; it was not compared"))
            continue
        scored = [(min(whole / SAME_WHOLE, detail / SAME_DETAIL), c)   # >= 1: the same figure
                  for c in code if same_shape(figure["width"], figure["height"], c.width, c.height)
                  for whole, detail in [scores(thumb, c.thumb)]]
        best_score, best = max(scored, key=lambda pair: pair[0], default=(None, None))
        if best is not None and best_score >= 1.0:
            out.append(Finding(number, source, best.figure_id, best_score,
                               f"{label} matches the figure {best.figure_id} the code makes"))
        else:
            out.append(Finding(number, source, None, best_score if best_score is not None else -1.0,
                               f"{label} matches none of the figures your code makes"))
    return out


def for_exercise(report_figures: list[dict], code_paths: dict[str, Path], exercise: str) -> list[Finding]:
    """What the review screen of ``exercise`` says of the report's figures: every figure in
    that exercise's part of the report, and those under no exercise's heading that match
    none. ``code_paths``: every figure the student's code made (id -> PNG), any exercise's:
    a report may show a figure under another heading than the grader's."""
    here = [f for f in report_figures if f.get("exercise") == exercise]
    nowhere = [f for f in report_figures if not f.get("exercise")]
    if not (here or nowhere):
        return []
    code = code_figures(code_paths)
    return findings(here, code) + [f for f in findings(nowhere, code) if f.unmatched]
