"""Lab 12's figures: disparity and depth maps, block matching, structured light."""

import numpy as np

from . import FigureUnavailable, Panel, figure


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


def _colour(image):
    import cv2

    image = np.asarray(image)
    return cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image.copy()


def _rows_drawn(left, right, pts_l, pts_r):
    """A pair side by side with a light line every 20 rows and matched points in matching colours:
    after rectification each pair of points sits on one row."""
    import cv2

    left, right = _colour(left), _colour(right)
    height = max(left.shape[0], right.shape[0])
    pair = np.hstack([np.pad(i, ((0, height - i.shape[0]), (0, 0), (0, 0))) for i in (left, right)])
    for y in range(10, height, 20):
        cv2.line(pair, (0, y), (pair.shape[1] - 1, y), (120, 220, 120), 1)
    shift = np.array([left.shape[1], 0.0])
    for k, (p, q) in enumerate(zip(pts_l, pts_r)):
        colour = _PALETTE[k % len(_PALETTE)]
        for point in (p, q + shift):
            if np.all(np.isfinite(point)):
                x, y = np.clip(point, -1e5, 1e5)
                cv2.circle(pair, (int(round(x)), int(round(y))), 3, colour, -1)
    return pair


_PALETTE = [(255, 80, 80), (60, 60, 255), (0, 200, 255), (255, 0, 255), (255, 255, 0), (0, 128, 255)]


@figure("lab12.ex3", "rectify(img_l, img_r, K1, K2, R, T)")
def rectification(call):
    from fixtures.lab12 import apply_homography, unrectified_pair

    pair = unrectified_pair(seed=4)
    got = call("rectify", pair.img_l, pair.img_r, pair.K1, pair.K2, pair.R, pair.T)
    if not isinstance(got, (tuple, list)) or len(got) != 4:
        raise FigureUnavailable("rectify() did not return (rect_l, rect_r, H1, H2)")
    rect_l, rect_r, H1, H2 = got
    pts_l, pts_r = pair.pts1[::10], pair.pts2[::10]
    return [Panel("before: the same points lie on different rows", _rows_drawn(pair.img_l, pair.img_r, pts_l, pts_r)),
            Panel("your rectified pair, the points moved by your H1 and H2",
                  _rows_drawn(rect_l, rect_r, apply_homography(np.asarray(H1, float), pts_l),
                              apply_homography(np.asarray(H2, float), pts_r)))]


@figure("lab12.ex4-extension", "block_matching(left, right, block_size=...) for four block sizes")
def block_sizes(call):
    from ..engine.pictures import disparity_picture

    scene = _scene("motorcycle")
    panels = [Panel("left image", scene.left),
              Panel("true disparity", disparity_picture(scene.disparity, scene.max_disparity))]
    for block_size in (3, 7, 15, 25):
        got = call("block_matching", scene.left, scene.right, scene.max_disparity, block_size)
        panels.append(Panel(f"block_size = {block_size}", disparity_picture(got, scene.max_disparity)))
    return panels


@figure("lab12.ext1", 'block_matching(..., cost="ncc") against SSD, the right view in another exposure')
def ncc(call):
    from fixtures.lab12 import reference_figures, with_gain

    from ..engine.pictures import disparity_picture

    gain, offset = reference_figures()["gain"]
    scene = with_gain(_scene("motorcycle"), gain, offset)
    picture = {cost: disparity_picture(call("block_matching", scene.left, scene.right, scene.max_disparity, 9, cost),
                                       scene.max_disparity) for cost in ("ssd", "ncc")}
    return [Panel("left image", scene.left), Panel(f"right image x {gain:g} {offset:+g}", scene.right),
            Panel("true disparity", disparity_picture(scene.disparity, scene.max_disparity)),
            Panel('cost="ssd"', picture["ssd"]), Panel('cost="ncc"', picture["ncc"])]


@figure("lab12.ex6", "structured light: simulate_structured_light, then depth_from_structured_light")
def structured_light(call):
    from fixtures.lab12 import simulate_structured_light, structured_light_scene

    from ..engine.pictures import disparity_picture

    depth, f, baseline = structured_light_scene("boxes")
    yours = np.asarray(call("simulate_structured_light", np.array(depth), f, baseline, 6))
    if yours.ndim != 3 or yours.shape[1:] != depth.shape:
        raise FigureUnavailable(f"simulate_structured_light() returned shape {yours.shape}; "
                                f"expected (6, {depth.shape[0]}, {depth.shape[1]})")
    images = simulate_structured_light(depth, f, baseline, 6)  # the decoder gets the right input
    got = call("depth_from_structured_light", images, f, baseline)
    top = float(depth.max())
    return [Panel("your simulation: the coarsest stripes", yours[0]),
            Panel(f"your simulation: stripes of bit {len(yours)}", yours[-1]),
            Panel("true depth", disparity_picture(depth, top)),
            Panel("depth_from_structured_light", disparity_picture(got, top))]
