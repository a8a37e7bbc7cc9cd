"""Lab 8's figures: a warped photo, matches drawn, a warp onto the reference, a panorama."""

import numpy as np

from . import Panel, figure


@figure("lab08.ex1", "apply_homography(image, H)")
def apply_h(call):
    from fixtures.lab08 import matching_pair

    image, _, H = matching_pair("astronaut", (320, 240), strength=0.15)
    return [Panel("input", image), Panel("apply_homography(image, H)", call("apply_homography", image, H))]


@figure("lab08.ex2", "warp_to_reference(reference, moving, homography_dlt(src, dst))")
def dlt(call):
    from fixtures.lab08 import apply_h, matching_pair

    reference, moving, H = matching_pair("coffee", (320, 240), strength=0.12)
    corners = np.array([[20.0, 20.0], [300.0, 25.0], [290.0, 220.0], [30.0, 210.0], [160.0, 120.0]])
    H_moving_to_reference = call("homography_dlt", apply_h(H, corners), corners)
    warped = call("warp_to_reference", reference, moving, H_moving_to_reference)
    return [Panel("reference", reference), Panel("moving", moving), Panel("moving warped onto reference", warped)]


@figure("lab08.ex3", "match_features then draw_matches")
def matches(call):
    from fixtures.lab08 import matching_pair

    img1, img2, _ = matching_pair("astronaut", (320, 240))
    pts1, pts2 = call("match_features", img1, img2)
    return [Panel(f"draw_matches: {len(pts1)} matches", call("draw_matches", img1, img2, pts1, pts2))]


@figure("lab08.ex5", "stitch(img1, img2)")
def panorama(call):
    from fixtures.lab08 import panorama_scene

    scene = panorama_scene()
    img1, img2 = scene.views[0], scene.views[1]
    return [Panel("img1", img1), Panel("img2", img2), Panel("stitch(img1, img2)", call("stitch", img1, img2))]
