"""Lab 7 - hidden checks: the same properties on inputs the students never saw.

Every input is drawn from ``t.rng``, the submission's own generator: a photo crop, the
offsets, angles, scales and point sets, within ranges that keep each check's question.
"""

import numpy as np

from autograder.engine.judges import judge_warp
from autograder.labs.lab07 import ex1, ex2, ex3, ex4, ex5, ex6, image_probe, judge_affine_fit, judge_lstsq, judge_rotations
from fixtures import lab07 as truth

from ._draws import crop, seed, uniform


def fractional(rng, low, high) -> float:
    """A value in [low, high) with a quarter, half or three-quarter fraction."""
    return float(rng.integers(low, high)) + float(rng.choice([0.25, 0.5, 0.75]))


@ex1.check("translate by negative and fractional offsets", points=2, hidden=True)
def translate_fractional(t):
    source = crop(t.rng, "rocket", (200, 150))
    tx, ty = -fractional(t.rng, 10, 60), fractional(t.rng, 5, 40)
    return judge_warp(t, f"translate(image, tx={tx}, ty={ty})", t.call("translate", source, tx=tx, ty=ty), source,
                      truth.translation(tx, ty), truth.translation_mistakes(tx, ty), probe=image_probe(t, "translate"))


@ex2.check("rotate by large angles, beyond 180 and negative", points=2, hidden=True)
def rotate_large_angles(t):
    source = crop(t.rng, "chelsea", (180, 120))
    # Well away from 180 degrees, where a rotation the opposite way is the same rotation.
    angles = (uniform(t.rng, 195.0, 255.0, 1), uniform(t.rng, -160.0, -60.0, 1))
    return judge_rotations(t, "image", source, angles)


@ex3.check("shrinking: scale(image, sx, sy) with both below 1", points=2, hidden=True)
def scale_shrink(t):
    source = crop(t.rng, "brick", (160, 120))
    # sx and sy at least 0.15 apart: "sy is ignored" and "swapped" stay visible.
    sx = uniform(t.rng, 0.4, 0.6)
    sy = uniform(t.rng, sx + 0.15, 0.9)
    return judge_warp(t, f"scale(image, sx={sx}, sy={sy})", t.call("scale", source, sx=sx, sy=sy),
                      source, truth.scaling(sx, sy), truth.scaling_mistakes(sx, sy, source.shape),
                      probe=image_probe(t, "scale"))


@ex4.check("negative shear", points=2, hidden=True)
def shear_negative(t):
    source = crop(t.rng, "coffee", (200, 150))
    s = uniform(t.rng, -0.6, -0.25)
    return judge_warp(t, f"shear(image, s={s})", t.call("shear", source, s=s), source,
                      truth.shear(s), truth.shear_mistakes(s, source.shape), probe=image_probe(t, "shear"))


@ex5.check("affine_from_points with coordinates in the thousands", points=2, hidden=True)
def affine_large_coordinates(t):
    A = truth.random_affine(t.rng)
    src = truth.triangle(t.rng, extent=uniform(t.rng, 3000.0, 6000.0)) + uniform(t.rng, 800.0, 2000.0)
    dst = truth.apply_affine(A, src)
    judge_affine_fit(t, "affine_from_points(src, dst)", t.call("affine_from_points", src, dst), A, src, dst)


@ex6.check("affine_lstsq on hundreds of noisy points far from the origin", points=3, hidden=True)
def lstsq_many_points(t):
    src, dst, _, least_squares = truth.noisy_correspondences(
        seed=seed(t.rng), n=int(t.rng.integers(300, 601)), noise=uniform(t.rng, 2.0, 4.0),
        extent=uniform(t.rng, 3000.0, 5000.0))
    judge_lstsq(t, src + 0.0, dst, least_squares)
