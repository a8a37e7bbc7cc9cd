"""Lab 8's figures: a warped photo, matches drawn, a warp onto the reference, a panorama."""

import numpy as np

from . import FigureUnavailable, Panel, figure


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


def _side_by_side(left, right):
    """Two images next to each other as one BGR picture (the shorter padded with black)."""
    import cv2

    pictures = [cv2.cvtColor(i, cv2.COLOR_GRAY2BGR) if i.ndim == 2 else np.asarray(i) for i in (left, right)]
    height = max(p.shape[0] for p in pictures)
    padded = [np.pad(p, ((0, height - p.shape[0]), (0, 0), (0, 0))) for p in pictures]
    return np.ascontiguousarray(np.hstack(padded))


@figure("lab08.ex4", "homography_ransac(src, dst) on matches with 30% outliers")
def ransac(call):
    import cv2
    from fixtures.lab08 import apply_h, matching_pair

    reference, moving, H = matching_pair("coffee", (320, 240), strength=0.12)
    rng = np.random.default_rng(8)
    in_reference = rng.uniform([15, 15], [305, 225], (60, 2))
    in_moving = apply_h(H, in_reference) + rng.normal(0, 0.5, (60, 2))
    outliers = rng.choice(60, 18, replace=False)
    in_moving[outliers] = rng.uniform([15, 15], [305, 225], (18, 2))  # wrong matches
    H_moving_to_reference, inliers = call("homography_ransac", in_moving, in_reference)
    inliers = np.asarray(inliers, dtype=bool).reshape(-1)
    if inliers.shape != (60,):
        raise FigureUnavailable(f"homography_ransac() returned {inliers.size} inlier flags for 60 matches")
    drawn = _side_by_side(reference, moving)
    for (x1, y1), (x2, y2), kept in zip(in_reference, in_moving, inliers):
        colour = (0, 200, 0) if kept else (0, 0, 255)
        cv2.line(drawn, (int(x1), int(y1)), (int(x2) + 320, int(y2)), colour, 1, cv2.LINE_AA)
    warped = call("warp_to_reference", reference, moving, H_moving_to_reference)
    return [Panel(f"your inliers (green, {inliers.sum()}) and outliers (red, {(~inliers).sum()}); "
                  "18 matches were made wrong", drawn),
            Panel("moving warped onto reference with your H", warped)]


@figure("lab08.ext1", 'match_features(..., method="orb") beside SIFT')
def orb(call):
    from fixtures.lab08 import matching_pair

    img1, img2, _ = matching_pair("astronaut", (320, 240))
    panels = []
    for method in ("sift", "orb"):
        pts1, pts2 = call("match_features", img1, img2, 0.75, method)
        panels.append(Panel(f"{method.upper()}: {len(pts1)} matches", call("draw_matches", img1, img2, pts1, pts2)))
    return panels


@figure("lab08.ext2", "stitch_many(three views)")
def many(call):
    from fixtures.lab08 import panorama_scene

    scene = panorama_scene("astronaut", (480, 250), ((10, 30), (115, 10), (225, 45)), (240, 180), 0.03, 34, False)
    return [Panel(f"view {k + 1}", view) for k, view in enumerate(scene.views)] + [
        Panel("stitch_many(views)", call("stitch_many", list(scene.views)))]


@figure("lab08.ext3", "blend_multiband(dark, bright, mask) against a plain cut")
def multiband(call):
    from fixtures.lab08 import exposure_pair, step_mask

    dark, bright = exposure_pair("coffee", (256, 192))
    mask = step_mask((256, 192), 128)
    cut = np.where(mask[..., None] > 0.5, dark, bright).astype(np.uint8)
    return [Panel("img1 (weighted left of the seam)", dark), Panel("img2", bright),
            Panel("plain cut at the seam", cut),
            Panel("blend_multiband(img1, img2, mask)", call("blend_multiband", dark, bright, mask))]
