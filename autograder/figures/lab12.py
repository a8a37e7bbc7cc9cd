"""Lab 12's figures: disparity and depth maps, block matching, structured light."""

import numpy as np

from . import Panel, figure


def _scene(name="slanted"):
    from fixtures.lab12 import scene

    return scene(name)


@figure("lab12.ex2", "depth_from_disparity(true disparity, f, baseline)")
def depth(call):
    from ..engine.pictures import disparity_picture

    scene = _scene()
    depth_map = np.asarray(call("depth_from_disparity", scene.disparity, scene.f, scene.baseline), float)
    return [Panel("left image", scene.left), Panel("disparity", disparity_picture(scene.disparity)),
            Panel("your depth map", disparity_picture(depth_map))]


@figure("lab12.ex4", "block_matching(left, right)")
def block(call):
    from ..engine.pictures import disparity_picture

    scene = _scene("random_dots")
    got = call("block_matching", scene.left, scene.right, scene.max_disparity)
    return [Panel("left image", scene.left),
            Panel("true disparity", disparity_picture(scene.disparity, scene.max_disparity)),
            Panel("your disparity", disparity_picture(got, scene.max_disparity))]


@figure("lab12.ex5", "dp_stereo(left, right)")
def smooth(call):
    from ..engine.pictures import disparity_picture

    scene = _scene("random_dots")
    got = call("dp_stereo", scene.left, scene.right, scene.max_disparity)
    return [Panel("left image", scene.left),
            Panel("true disparity", disparity_picture(scene.disparity, scene.max_disparity)),
            Panel("your disparity", disparity_picture(got, scene.max_disparity))]
