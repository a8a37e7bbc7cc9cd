"""What the hidden checks draw from ``t.rng`` (the submission's own generator), beyond plain
uniforms: a seed for a fixture's scene, a crop of a photo at a drawn place, chessboard views
moved from written ones while every board stays whole in the image.

Crops rather than drawn photo sizes: every size is decoded and kept once per process
(``fixtures.images``), so drawing sizes would grow that cache with every submission.
"""

from __future__ import annotations

import numpy as np

from fixtures import lab09
from fixtures.images import photo


def seed(rng: np.random.Generator) -> int:
    """A seed for a fixture's own generator (its scenes, points, noise)."""
    return int(rng.integers(0, 2**31 - 1))


def crop(rng: np.random.Generator, name: str, size, margin: int = 40, grey: bool = False) -> np.ndarray:
    """A ``size = (width, height)`` window of the photo ``name`` resized to ``margin`` pixels
    more each way, at a drawn place: a new image, its content shifted by up to ``margin``."""
    width, height = int(size[0]), int(size[1])
    whole = photo(name, (width + margin, height + margin), grey=grey)
    x, y = (int(v) for v in rng.integers(0, margin + 1, size=2))
    return whole[y:y + height, x:x + width].copy()


def uniform(rng: np.random.Generator, low: float, high: float, digits: int = 2) -> float:
    """A value in [low, high], rounded to ``digits`` decimals (short in a message, and a
    plain Python float in a call)."""
    return round(float(rng.uniform(low, high)), digits)


def uncached(function):
    """``function`` without the caches its fixture wraps it in (``lru_cache``, the persistent
    store): a scene drawn for one submission is never asked for again, so keeping it would
    only grow the grader's memory and store with every submission."""
    return getattr(function, "__wrapped__", function)


# How far a hidden board view moves from the one written in its check: tilt (rvec, radians),
# spin (degrees), distance and offset (world units, the square being 0.25).
VIEW_JITTER = {"tilt": 0.05, "spin": 4.0, "distance": 0.15, "offset": 0.05}
BOARD_MARGIN = 2.0   # px between the whole board (its outer squares) and the image border


def board_views(rng: np.random.Generator, views, K, pattern, square, size, jitter=VIEW_JITTER) -> tuple:
    """``views`` (tilt rvec, spin in degrees, distance, (x, y) offset: ``fixtures.lab09.board_pose``)
    each moved by a drawn amount within ``jitter``, drawn again until every whole board lies in
    the ``size = (width, height)`` image of camera ``K`` (a corner detector needs the squares
    around every inner corner). A nested tuple, as the fixtures' caches want."""
    def moved(values, by):
        return tuple(round(float(v + rng.uniform(-by, by)), 3) for v in values)

    for _ in range(200):
        drawn = tuple((moved(tilt, jitter["tilt"]), moved([spin], jitter["spin"])[0],
                       moved([distance], jitter["distance"])[0], moved(offset, jitter["offset"]))
                      for tilt, spin, distance, offset in views)
        if all(board_margin(K, view, pattern, square, size) >= BOARD_MARGIN for view in drawn):
            return drawn
    raise RuntimeError("no board views inside the image after 200 draws: the jitter is too large")


def board_margin(K, view, pattern, square, size) -> float:
    """Pixels between the outline of the whole board of ``view`` and the image border
    (negative: the board leaves the image)."""
    tilt, spin, distance, offset = view
    R, tvec = lab09.board_pose(np.array(tilt), spin, distance, pattern, square, offset)
    cols, rows = pattern
    outline = np.array([[-1, -1, 0], [cols, -1, 0], [cols, rows, 0], [-1, rows, 0]]) * square
    x = lab09.homogeneous_project(lab09.camera(K, R, tvec), outline)
    return float(min(x.min(), size[0] - 1 - x[:, 0].max(), size[1] - 1 - x[:, 1].max()))


def vetted(rng: np.random.Generator, key: str) -> np.random.Generator:
    """A generator for the scene of the hidden check ``key``, seeded with one of the scenes on which the
    reference solution and the lab sheet's recipe were measured to get full marks (``_vetted.py``, made by
    ``python -m autograder.labs.hidden.make_vetted``): drawn scenes where a correct pipeline is itself at
    the edge of a judge's bounds (a panorama's far corners a few pixels off along a chain of homographies)
    are left out, instead of taking points from correct code on one submission in seventy. ``rng`` itself
    for a key with no measured scenes."""
    from ._vetted import VETTED

    scenes = VETTED.get(key)
    return np.random.default_rng(int(rng.choice(scenes))) if scenes else rng

