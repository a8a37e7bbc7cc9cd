"""The lab sheet's "Expected Output" pictures, made by the student's own functions.

``python grade.py --figures DIR`` writes one PNG per exercise (``DIR/lab07.ex1.png``
...), ready for the report the lab sheet asks for: the translated image, the
matches drawn, the panorama, projections for several focal lengths, epipolar
lines, disparity maps ... made by calling the student's functions, in the
sandbox, on the lab's inputs (the same photos and scenes the checks use). A
figure is made whether the exercise passes or not: it shows what the code does.

The engine knows no lab: a producer per figure, registered with
:func:`figure` in ``autograder/figures/labNN.py``, receives a ``call``
(``call("translate", image)`` runs the student's function and returns its
value, or stops the figure with the reason) and returns :class:`Panel` s.

Figure ids. A figure of a graded exercise (extensions with functions of their
own included, e.g. ``lab08.ext2``) has that exercise's id. An experiment the lab
sheet lists as an extension without a function of its own (the effects of R and
t; block sizes in stereo matching) is a figure of the exercise whose functions it
runs, with ``-extension`` after that id: ``lab09.ex3-extension``. The id is also
the file name (``lab09.ex3-extension.png``) and the report section's name.
:data:`SHEET_PICTURES` lists, apart from the producers, every figure the lab sheet
asks for (an "Expected Output" that is an image, plot or visualisation, and the
two experiments), so a test notices a producer that goes missing.

Bounds. Making figures is part of grading a submission and is held to the same
limits (:func:`make_figures`): its calls run in the same :class:`Sandbox` machinery
with the graded calls' limits (their memory share, processes, call timeout), within
what is left of the submission's deadline (``Limits.submission_budget`` from the
start of its grading: grading and its figures share it; a figure left when it is
spent is skipped with one sentence saying so). What a call returns to a figure is
capped before the grader reads it (:data:`FIGURE_REPLY_BYTES` on the reply's length,
:data:`FIGURE_REPLY_ELEMENTS` numbers on its header: the figure is skipped, naming
the sizes), and what is drawn after that is thinned (images to
``engine.pictures.MAX_SIDE`` a side, point sets to :data:`MAX_POINTS_DRAWN`, the
figure's note saying so).
"""

from __future__ import annotations

import importlib
import pkgutil
import re
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable

import numpy as np


@dataclass
class Panel:
    """One picture of a figure: an image (BGR or grey), or 2-D point sets to plot."""

    title: str
    image: np.ndarray | None = None
    points: dict[str, np.ndarray] = field(default_factory=dict)
    flip_y: bool = True  # image coordinates: y down
    frame: tuple[float, float] | None = None  # (width, height): draw the image's border, fix the axes to it
    axes: tuple[str, str] = ("x", "y")  # the plot's axis labels
    extent: tuple[float, float, float, float] | None = None  # (x0, x1, y0, y1), e.g. common_extent(...)


class FigureUnavailable(Exception):
    """The student's function failed, so the figure cannot be made (the reason says why)."""


@dataclass
class Producer:
    figure_id: str       # "lab07.ex1", "lab09.ex3-extension"
    title: str
    make: Callable[[Callable], list[Panel]]

    @property
    def exercise_id(self) -> str:
        """The exercise whose functions the figure runs (its selector): ``lab09.ex3``."""
        return self.figure_id.split("-", 1)[0]


# What a figure's call may return, checked before the grader reads the reply (on its length,
# then on its header): the largest the reference solutions return is 460,800 numbers (two photos
# side by side with their matches drawn); a figure draws no more than a thousand pixels a side.
FIGURE_REPLY_BYTES = 32 * 2**20
FIGURE_REPLY_ELEMENTS = 4_000_000
MAX_POINTS_DRAWN = 20_000  # per point set of a panel: Matplotlib's cost grows with each point

PRODUCERS: dict[str, Producer] = {}
_FIGURE_ID = re.compile(r"lab\d\d\.ext?\d+(-extension)?")

# What the lab sheet shows for each exercise whose expected output is a picture, in our
# words; an experiment extension under its figure id. Producers must cover every entry.
SHEET_PICTURES: dict[str, str] = {
    "lab07.ex1": "the image translated, uncovered pixels black",
    "lab07.ex2": "the image rotated about its centre",
    "lab07.ex3": "the image scaled up",
    "lab07.ex4": "the image sheared along x",
    "lab07.ex5": "the image warped by the affine map of three point pairs",
    "lab07.ex6": "the image warped by the least-squares affine map",
    "lab08.ex1": "the image warped by a homography",
    "lab08.ex2": "the second image warped into the first's view (DLT)",
    "lab08.ex3": "the matched features drawn",
    "lab08.ex4": "the second image warped into the first's view (RANSAC), inliers shown",
    "lab08.ex5": "the panorama",
    "lab09.ex1": "projections of a pinhole camera",
    "lab09.ex2": "projections with the intrinsic matrix",
    "lab09.ex3": "projections with the full camera matrix",
    "lab09.ex3-extension": "projections for several rotations and translations",
    "lab09.ex4": "projections for several focal lengths, and pinhole blur",
    "lab09.ex5": "projected points marked on a photo",
    "lab10.ex1": "projections for three focal lengths",
    "lab10.ex2": "perspective and weak perspective side by side",
    "lab10.ex3": "orthographic and perspective projections",
    "lab10.ex6": "the reprojected chessboard corners",
    "lab11.ex2": "epipolar lines on the second image",
    "lab11.ex6": "matches, epipolar lines of the estimated F, triangulated points",
    "lab12.ex2": "disparity and depth maps",
    "lab12.ex3": "the rectified pair",
    "lab12.ex4": "the disparity map of block matching",
    "lab12.ex4-extension": "disparity maps for several block sizes",
    "lab12.ex5": "the disparity map of the smoothness-enforcing matcher",
    "lab12.ex6": "the depth map recovered from structured light",
}


def figure(figure_id: str, title: str):
    """Register ``make(call) -> list[Panel]`` as the figure ``figure_id`` (see the module doc)."""
    if not _FIGURE_ID.fullmatch(figure_id):
        raise ValueError(f"a figure id looks like lab07.ex1, lab08.ext2 or lab09.ex3-extension, "
                         f"not {figure_id!r}")

    def register(make):
        known = PRODUCERS.get(figure_id)
        if known and (known.make.__module__, known.make.__qualname__) != (make.__module__, make.__qualname__):
            raise ValueError(f"figure {figure_id} is registered twice")
        PRODUCERS[figure_id] = Producer(figure_id, title, make)
        return make
    return register


def _discover() -> dict[str, Producer]:
    for info in pkgutil.iter_modules(__path__):
        if not info.name.startswith("_"):
            importlib.import_module(f"{__name__}.{info.name}")
    return PRODUCERS


@dataclass
class FigureOutcome:
    exercise_id: str
    path: Path | None = None
    reason: str = ""     # why there is no figure (path None)
    figure_id: str = ""  # the file's stem; the exercise id unless an experiment's figure
    note: str = ""       # what the figure leaves out (points thinned), for the student

    def __post_init__(self):
        self.figure_id = self.figure_id or self.exercise_id


def producers_for(exercise_id: str) -> list[Producer]:
    """The figures of one exercise, its own first, in the order they were registered."""
    return [p for p in _discover().values() if p.exercise_id == exercise_id]


def figure_limits(limits) -> "Limits":
    """``limits`` (those the submission's graded calls had: their memory share, processes,
    timeouts) with a figure's caps on what a call returns."""
    return replace(limits, max_result_bytes=min(limits.max_result_bytes, FIGURE_REPLY_BYTES),
                   max_result_elements=min(limits.max_result_elements or FIGURE_REPLY_ELEMENTS,
                                           FIGURE_REPLY_ELEMENTS))


def grading_budget(limits, selectors=()) -> float:
    """The seconds a grading of ``selectors`` has from its start to its deadline, as the runner
    sets it: ``Limits.budget_for`` the exercises selected, where the limits have it (a lab's
    share each), else ``Limits.submission_budget``. Figures made after that grading share it."""
    from ..engine.registry import select

    budget_for = getattr(limits, "budget_for", None)
    return budget_for(select(selectors)) if budget_for is not None else limits.submission_budget


def make_figures(submission, selectors=(), out_dir=".", limits=None,
                 deadline: float | None = None) -> list[FigureOutcome]:
    """Write ``out_dir/<figure id>.png`` for every figure of the selected exercises.

    ``limits``: those of the submission's graded calls (``Limits.shared_by(lanes)`` when it was
    graded in lanes), with the figure's reply caps added (:func:`figure_limits`). ``deadline``:
    the grading's, ``time.monotonic()`` at which its time is spent (:func:`grading_budget` after
    it began); None: that budget from now, for figures made on their own.
    A call running at the deadline is stopped, and every figure left is skipped with the reason.
    """
    from ..engine.registry import select
    from ..sandbox.supervisor import Limits, Sandbox
    from ..loading.submission import load_submission

    limits = figure_limits(limits or Limits())
    if deadline is None:
        deadline = time.monotonic() + grading_budget(limits, selectors)
    chosen = [(ex, producer) for ex in select(selectors) for producer in producers_for(ex.id)]
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    outcomes = []
    with load_submission(submission, sorted({ex.lab.module for ex, _ in chosen})) as loaded:
        with Sandbox(loaded.path, limits) as sandbox:  # its worker starts at the first call, if any
            sandbox.set_deadline(deadline)
            for exercise, producer in chosen:
                outcome = FigureOutcome(exercise.id, figure_id=producer.figure_id)
                outcomes.append(outcome)
                if sandbox.remaining() <= 0:
                    outcome.reason = _out_of_time()
                    continue
                sandbox.start_exercise(None)  # worker restarts are counted per figure, as per exercise
                call = _caller(sandbox, exercise.lab.module, loaded.problems.get(exercise.lab.module))
                try:
                    panels = producer.make(call)
                    outcome.note = " ".join(_thin(panels))
                    png = render_png(f"{producer.figure_id} · {producer.title}", panels)
                except FigureUnavailable as exc:
                    outcome.reason = str(exc)
                    continue
                except Exception as exc:  # noqa: BLE001 - what a student returned cannot stop the others
                    reason = f"what your functions returned cannot be drawn ({type(exc).__name__}: {exc})"
                    outcome.reason = reason[:300]
                    continue
                outcome.path = out_dir / f"{producer.figure_id}.png"
                outcome.path.write_bytes(png)
    return outcomes


def _out_of_time(function: str = "") -> str:
    """Why a figure was not made: the submission's deadline (grading and figures share it)."""
    what = f"{function}() was stopped" if function else "skipped"
    return f"{what}: the submission's time budget (grading and its figures together) is spent"


def _caller(sandbox, module: str, problem: str | None):
    def call(function: str, *args, **kwargs):
        if problem:
            raise FigureUnavailable(problem)
        outcome = sandbox.call(module, function, args, kwargs)
        if outcome.kind == "budget":
            raise FigureUnavailable(_out_of_time(function if outcome.seconds else ""))  # it ran: stopped
        if not outcome.ok:
            message = outcome.message.splitlines()[0] if outcome.message else outcome.kind
            raise FigureUnavailable(message if message.startswith(f"{function}()") else f"{function}(): {message}")
        return outcome.value
    return call


def thinned(points) -> tuple[np.ndarray, int]:
    """``points`` (anything of 2 N numbers) as an ``(M, 2)`` float array of at most
    :data:`MAX_POINTS_DRAWN` rows, every k-th kept, and ``N``. Raises ValueError for an
    odd count of numbers."""
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    step = max(1, -(-len(points) // MAX_POINTS_DRAWN))
    return points[::step], len(points)


def _thin(panels: list[Panel]) -> list[str]:
    """Thin the panels' point sets to :data:`MAX_POINTS_DRAWN` (their titles say so); one
    sentence per set thinned, for the student."""
    notes = []
    for panel in panels:
        drawn = []
        for label, points in panel.points.items():
            panel.points[label], count = thinned(points)
            if count > len(panel.points[label]):
                drawn.append(f"{len(panel.points[label]):,} of {count:,}")
                notes.append(f"your figure's panel “{panel.title}” has {count:,} points of “{label}”; "
                             f"at most {MAX_POINTS_DRAWN:,} are drawn.")
        if drawn:
            panel.title += f" ({', '.join(drawn)} points drawn)"
    return notes


def render_png(title: str, panels: list[Panel], dpi: int = 110) -> bytes:
    """The panels side by side (three to a row, four as two by two) as one PNG, each with its title."""
    import io

    from matplotlib.figure import Figure

    columns = 2 if len(panels) in (2, 4) else min(3, len(panels))
    rows = [panels[i:i + columns] for i in range(0, len(panels), columns)]
    # Each panel as wide as its picture's aspect asks (a side-by-side pair is wide), plots square-ish;
    # a short last row keeps the panel size of the rows above, left-aligned.
    ratios = [[_aspect(panel) for panel in row] for row in rows]
    usual = float(np.mean(ratios[0]))
    ratios = [r + [usual] * (columns - len(r)) for r in ratios]
    width = 3.4 * max(sum(r) for r in ratios)
    fig = Figure(figsize=(min(width, 14.0), 3.4 * len(rows) + 0.5), dpi=dpi, layout="constrained")
    fig.suptitle(title)
    row_figures = np.atleast_1d(fig.subfigures(len(rows), 1))  # rows laid out apart: no title overlaps
    for row_figure, row_panels, row_ratios in zip(row_figures, rows, ratios):
        grid = row_figure.add_gridspec(1, columns, width_ratios=row_ratios)
        for column, panel in enumerate(row_panels):
            ax = row_figure.add_subplot(grid[0, column])
            ax.set_title(panel.title, fontsize=9)
            if panel.image is not None:
                _show_image(ax, panel.image)
            else:
                _plot_points(ax, panel)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()


def common_extent(*point_sets, margin: float = 0.05) -> tuple[float, float, float, float]:
    """``(x0, x1, y0, y1)`` holding every finite point of ``point_sets``: panels that share it
    show sizes that can be compared (a longer focal length, a larger picture)."""
    points = np.vstack([np.asarray(p, dtype=float).reshape(-1, 2) for p in point_sets] or [np.zeros((0, 2))])
    points = points[np.all(np.isfinite(points), axis=1)]
    if len(points) == 0:
        return (-1.0, 1.0, -1.0, 1.0)
    low, high = points.min(axis=0), points.max(axis=0)
    pad = np.maximum((high - low) * margin, 1e-9)
    return (low[0] - pad[0], high[0] + pad[0], low[1] - pad[1], high[1] + pad[1])


def _aspect(panel: Panel) -> float:
    if panel.image is None:
        return 1.2
    shape = np.shape(panel.image)
    return float(np.clip(shape[1] / max(shape[0], 1), 0.5, 4.0)) if len(shape) >= 2 else 1.0


def _show_image(ax, image):
    from ..engine.pictures import as_displayable

    try:
        shown = as_displayable(np.asarray(image))
    except ValueError as exc:
        ax.text(0.5, 0.5, str(exc), ha="center", va="center", wrap=True, fontsize=8)
        ax.set_axis_off()
        return
    if shown.ndim == 3:
        shown = shown[:, :, 2::-1]  # BGR -> RGB
        ax.imshow(shown, interpolation="nearest")
    else:
        ax.imshow(shown, cmap="gray", vmin=0, vmax=255, interpolation="nearest")
    ax.set_xticks([]), ax.set_yticks([])
    height, width = np.shape(image)[:2]
    ax.set_xlabel(f"{width} × {height}", fontsize=8)


def _plot_points(ax, panel: Panel):
    for label, points in panel.points.items():
        points, _ = thinned(points)  # (make_figures has thinned them already, and said so)
        ax.scatter(points[:, 0], points[:, 1], s=10, label=label)
    if len(panel.points) > 1:
        ax.legend(fontsize=7)
    if panel.frame is not None:
        width, height = panel.frame
        ax.plot([0, width, width, 0, 0], [0, 0, height, height, 0], color="0.6", linewidth=1)
        ax.set_xlim(-0.05 * width, 1.05 * width)
        ax.set_ylim(-0.05 * height, 1.05 * height)
        ax.set_aspect("equal")
    elif panel.extent is not None:
        ax.set_xlim(*panel.extent[:2])
        ax.set_ylim(*panel.extent[2:])
        ax.set_aspect("equal")
    else:
        ax.set_aspect("equal", adjustable="datalim")
    if panel.flip_y:
        ax.invert_yaxis()
    ax.set_xlabel(panel.axes[0], fontsize=8)
    ax.set_ylabel(panel.axes[1], fontsize=8)
    ax.tick_params(labelsize=7)
