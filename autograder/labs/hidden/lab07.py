"""Lab 7 - hidden checks: the same properties on inputs the students never saw."""

import numpy as np

from autograder.engine.judges import judge_warp
from autograder.labs.lab07 import ex1, ex2, ex3, ex4, ex5, ex6, image_probe, judge_affine_fit, judge_lstsq
from fixtures import lab07 as truth
from fixtures.images import photo


@ex1.check("translate by negative and fractional offsets", points=2, hidden=True)
def translate_fractional(t):
    source = photo("rocket", (200, 150))
    return judge_warp(t, "translate(image, tx=-37.5, ty=12.25)",
                      t.call("translate", source, tx=-37.5, ty=12.25), source,
                      truth.translation(-37.5, 12.25), truth.translation_mistakes(-37.5, 12.25), probe=image_probe(t, "translate"))


@ex2.check("rotate by 200 and -110 degrees", points=2, hidden=True)
def rotate_large_angles(t):
    source = photo("chelsea", (180, 120))
    centre = truth.image_centre(source.shape)
    for angle in (200, -110):
        verdict = judge_warp(t, f"rotate(image, angle_deg={angle})", t.call("rotate", source, angle_deg=angle),
                             source, truth.rotation(angle, centre), truth.rotation_mistakes(angle, centre), probe=image_probe(t, "rotate"))
        if verdict.fraction < 1:
            return verdict
    return verdict


@ex3.check("shrinking: scale(image, sx=0.5, sy=0.75)", points=2, hidden=True)
def scale_shrink(t):
    source = photo("brick", (160, 120))
    return judge_warp(t, "scale(image, sx=0.5, sy=0.75)", t.call("scale", source, sx=0.5, sy=0.75),
                      source, truth.scaling(0.5, 0.75), truth.scaling_mistakes(0.5, 0.75, source.shape), probe=image_probe(t, "scale"))


@ex4.check("negative shear s=-0.4", points=2, hidden=True)
def shear_negative(t):
    source = photo("coffee", (200, 150))
    return judge_warp(t, "shear(image, s=-0.4)", t.call("shear", source, s=-0.4), source,
                      truth.shear(-0.4), truth.shear_mistakes(-0.4, source.shape), probe=image_probe(t, "shear"))


@ex5.check("affine_from_points with coordinates in the thousands", points=2, hidden=True)
def affine_large_coordinates(t):
    rng = np.random.default_rng(20240607)
    A = truth.random_affine(rng)
    src = truth.triangle(rng, extent=5000.0) + 1000.0
    dst = truth.apply_affine(A, src)
    judge_affine_fit(t, "affine_from_points(src, dst)", t.call("affine_from_points", src, dst), A, src, dst)


@ex6.check("affine_lstsq on 500 noisy points far from the origin", points=3, hidden=True)
def lstsq_many_points(t):
    src, dst, _, least_squares = truth.noisy_correspondences(seed=424242, n=500, noise=3.0, extent=4000.0)
    judge_lstsq(t, src + 0.0, dst, least_squares)
