"""What the hidden checks draw from ``t.rng`` (the submission's own generator), beyond plain
uniforms: a seed for a fixture's scene, a crop of a photo at a drawn place.

Crops rather than drawn photo sizes: every size is decoded and kept once per process
(``fixtures.images``), so drawing sizes would grow that cache with every submission.
"""

from __future__ import annotations

import numpy as np

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
