"""Lab 7's figures: each transformation applied to a photo, as the lab sheet shows them."""

import numpy as np

from . import Panel, figure


def _photo():
    from fixtures.images import photo

    return photo("astronaut", (320, 240))


@figure("lab07.ex1", "translate(image), tx=100, ty=50")
def translation(call):
    image = _photo()
    return [Panel("input", image), Panel("translate(image)", call("translate", image))]


@figure("lab07.ex2", "rotate(image) by 45 degrees about the centre")
def rotation(call):
    image = _photo()
    return [Panel("input", image), Panel("rotate(image)", call("rotate", image)),
            Panel("rotate(image, angle_deg=-30)", call("rotate", image, -30.0))]


@figure("lab07.ex3", "scale(image), 1.5x about the top-left corner")
def scaling(call):
    image = _photo()
    return [Panel("input", image), Panel("scale(image)", call("scale", image)),
            Panel("scale(image, sx=0.5, sy=0.75)", call("scale", image, 0.5, 0.75))]


@figure("lab07.ex4", "shear(image), s=0.5")
def shearing(call):
    image = _photo()
    return [Panel("input", image), Panel("shear(image)", call("shear", image))]


@figure("lab07.ex5", "warp_affine(image, affine_from_points(src, dst))")
def affine(call):
    image = _photo()
    src = np.array([[50.0, 50.0], [250.0, 60.0], [60.0, 200.0]])
    dst = np.array([[70.0, 40.0], [260.0, 90.0], [40.0, 190.0]])
    A = call("affine_from_points", src, dst)
    return [Panel("input", image), Panel("warp_affine(image, A)", call("warp_affine", image, A))]


@figure("lab07.ex6", "warp_affine(image, affine_lstsq(src, dst)) from 10 noisy points")
def least_squares(call):
    image = _photo()
    rng = np.random.default_rng(0)
    src = rng.uniform(20, 300, (10, 2))
    true = np.array([[0.9, -0.2, 30.0], [0.15, 0.95, 10.0]])
    dst = src @ true[:, :2].T + true[:, 2] + rng.normal(0, 1.0, (10, 2))
    A = call("affine_lstsq", src, dst)
    return [Panel("input", image), Panel("warp_affine(image, A)", call("warp_affine", image, A))]
