"""simulate_aperture's rays told by the shape they fill (issue 35: "some rays land outside the
blur disc" located the mistake without its cause): a square, a normal distribution, the rim, half
the disc, one line. Every way of drawing uniformly over the disc, and a radius drawn uniformly
(random points of the disc, which the API accepts), is named nothing."""

from __future__ import annotations

import numpy as np
import pytest

from autograder.engine.runner import grade
from autograder.labs.lab09 import aperture_sampling
from conftest import check_results, mutant

N, RAYS = 6, 4000


def polar(radius_of, angle_high=2 * np.pi, seed=0):
    rng = np.random.default_rng(seed)
    r = radius_of(rng.uniform(0, 1, (N, RAYS)))
    a = rng.uniform(0, angle_high, (N, RAYS))
    return np.stack([r * np.cos(a), r * np.sin(a)], axis=-1)


def whole_radians(seed=5):
    """Radius sqrt(u), angle drawn with rng.integers(0, 2 pi): seven directions (blind set 1204e's 09/05)."""
    rng = np.random.default_rng(seed)
    r, a = np.sqrt(rng.uniform(0, 1, (N, RAYS))), rng.integers(0, 7, (N, RAYS))
    return np.stack([r * np.cos(a), r * np.sin(a)], axis=-1)


def rejection(seed=1):
    rng = np.random.default_rng(seed)
    points = rng.uniform(-1, 1, (N * RAYS * 2, 2))
    return points[np.hypot(*points.T) <= 1][: N * RAYS].reshape(N, RAYS, 2)


RIGHT = {
    "polar, radius sqrt(u)": polar(np.sqrt),
    "rejection from the square": rejection(),
    "radius drawn uniformly (accepted)": polar(lambda u: u),
}
WRONG = {
    "square": (np.random.default_rng(2).uniform(-1, 1, (N, RAYS, 2)), "fill the square"),
    "normal": (np.random.default_rng(3).normal(0, 0.5, (N, RAYS, 2)), "normal distribution"),
    "rim": (polar(lambda u: np.ones_like(u)), "rim of the blur disc"),
    "half a turn": (polar(np.sqrt, angle_high=np.pi), "only half of the blur disc"),
    "angles of whole radians": (whole_radians(), "along a few directions only"),
    "one random number": (np.repeat(np.random.default_rng(4).uniform(-0.7, 0.7, (N, RAYS, 1)), 2, axis=2),
                          "made from the same random numbers"),
    "cos used for both coordinates": (polar(np.sqrt)[..., [0, 0]], "made from the same random numbers"),
    # (one angle drawn for every ray, a radius per ray: one direction, not x = y)
    "an angle drawn once": (np.sqrt(np.random.default_rng(6).uniform(0, 1, (N, RAYS, 1)))
                            * [np.cos(1.1), np.sin(1.1)], "one angle for all the rays"),
}


@pytest.mark.parametrize("name", sorted(RIGHT))
def test_a_disc_drawn_any_right_way_is_named_nothing(name):
    assert aperture_sampling(RIGHT[name]) == ""


@pytest.mark.parametrize("name", sorted(WRONG))
def test_a_wrong_shape_is_told(name):
    offsets, words = WRONG[name]
    assert words in aperture_sampling(offsets)


def test_off_centre_rays_are_not_called_half_a_disc():
    assert aperture_sampling(polar(np.sqrt) + [1.5, 0.0]) == ""


def test_a_square_aperture_is_named_in_grading(tmp_path):
    source = """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X = np.asarray(points, dtype=np.float64).reshape(-1, 3)
            rng = np.random.default_rng(seed)
            A = rng.uniform(-aperture, aperture, size=(len(X), n_rays, 2))
            ideal = pinhole_project(X, f)
            return ideal[:, None, :] - A * (1.0 + f / X[:, 2])[:, None, None]
        """
    result = grade(mutant(tmp_path, "lab09_camera", source), ["lab09.ex4"], pictures="none")
    failed = [c for c in check_results(result, "lab09.ex4") if not c.passed]
    assert any("fill the square [-aperture, aperture]^2, not the disc" in c.message for c in failed), \
        [c.message for c in failed]
    assert not any("outside the blur disc" in c.message for c in failed)
