"""The lab sheet's "Expected Output" pictures, made by the student's own functions.

``python grade.py --figures DIR`` writes one PNG per exercise (``DIR/lab07.ex1.png``
...), ready for the report the lab sheet asks for: the translated image, the
matches drawn, the panorama, projections for several focal lengths, epipolar
lines, disparity maps ... made by calling the student's functions, in the
sandbox, on the lab's inputs (the same photos and scenes the checks use). A
figure is made whether the exercise passes or not: it shows what the code does.

The engine knows no lab: a producer per exercise, registered with
:func:`figure` in ``autograder/figures/labNN.py``, receives a ``call``
(``call("translate", image)`` runs the student's function and returns its
value, or stops the figure with the reason) and returns :class:`Panel` s.
"""

from __future__ import annotations

import importlib
import pkgutil
from dataclasses import dataclass, field
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


class FigureUnavailable(Exception):
    """The student's function failed, so the figure cannot be made (the reason says why)."""


@dataclass
class Producer:
    exercise_id: str
    title: str
    make: Callable[[Callable], list[Panel]]


PRODUCERS: dict[str, Producer] = {}


def figure(exercise_id: str, title: str):
    """Register ``make(call) -> list[Panel]`` as the figure of ``exercise_id``."""
    def register(make):
        PRODUCERS[exercise_id] = Producer(exercise_id, title, make)
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
    reason: str = ""


def make_figures(submission, selectors=(), out_dir=".", limits=None) -> list[FigureOutcome]:
    """Write ``out_dir/<exercise>.png`` for every selected exercise that has a figure."""
    from ..engine.registry import select
    from ..sandbox.supervisor import Sandbox
    from ..loading.submission import load_submission

    producers = _discover()
    exercises = [ex for ex in select(selectors) if ex.id in producers]
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    outcomes = []
    with load_submission(submission, sorted({ex.lab.module for ex in exercises})) as loaded:
        with Sandbox(loaded.path, limits) as sandbox:
            for exercise in exercises:
                producer = producers[exercise.id]
                call = _caller(sandbox, exercise.lab.module, loaded.problems.get(exercise.lab.module))
                try:
                    panels = producer.make(call)
                except FigureUnavailable as exc:
                    outcomes.append(FigureOutcome(exercise.id, reason=str(exc)))
                    continue
                path = out_dir / f"{exercise.id}.png"
                path.write_bytes(render_png(f"{exercise.id} · {producer.title}", panels))
                outcomes.append(FigureOutcome(exercise.id, path))
    return outcomes


def _caller(sandbox, module: str, problem: str | None):
    def call(function: str, *args, **kwargs):
        if problem:
            raise FigureUnavailable(problem)
        outcome = sandbox.call(module, function, args, kwargs)
        if not outcome.ok:
            raise FigureUnavailable(f"{function}(): {outcome.message.splitlines()[0]}")
        return outcome.value
    return call


def render_png(title: str, panels: list[Panel], dpi: int = 110) -> bytes:
    """The panels side by side (wrapping after three) as one PNG, each with its title."""
    import io

    from matplotlib.figure import Figure

    columns = min(3, len(panels))
    rows = [panels[i:i + columns] for i in range(0, len(panels), columns)]
    # Each panel as wide as its picture's aspect asks (a side-by-side pair is wide), plots square-ish.
    ratios = [[_aspect(panel) for panel in row] + [0.0] * (columns - len(row)) for row in rows]
    width = 3.4 * max(sum(r) for r in ratios)
    fig = Figure(figsize=(min(width, 14.0), 3.4 * len(rows) + 0.5), dpi=dpi, layout="constrained")
    fig.suptitle(title)
    for row, (row_panels, row_ratios) in enumerate(zip(rows, ratios)):
        grid = fig.add_gridspec(len(rows), len(row_ratios), width_ratios=[r or 1e-3 for r in row_ratios])
        for column, panel in enumerate(row_panels):
            ax = fig.add_subplot(grid[row, column])
            ax.set_title(panel.title, fontsize=9)
            if panel.image is not None:
                _show_image(ax, panel.image)
            else:
                _plot_points(ax, panel)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()


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
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        ax.scatter(points[:, 0], points[:, 1], s=10, label=label)
    if len(panel.points) > 1:
        ax.legend(fontsize=7)
    ax.set_aspect("equal", adjustable="datalim")
    if panel.flip_y:
        ax.invert_yaxis()
    ax.tick_params(labelsize=7)
