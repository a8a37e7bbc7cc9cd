"""Lab 11's figures: epipolar lines drawn on the second image; the two-view pipeline."""

import numpy as np

from . import FigureUnavailable, Panel, figure


@figure("lab11.ex2", "draw_epipolar_lines(image 2, epipolar_lines(F, points of image 1))")
def epipolar(call):
    import cv2
    from fixtures import lab11 as truth
    from fixtures.images import photo

    views = truth.two_views(seed=6, n=40)
    inside = truth.inside(views.pts2, views.cam2, margin=3)
    pts1, pts2 = views.pts1[inside][:8], views.pts2[inside][:8]
    image = photo("coffee", (views.cam2.width, views.cam2.height))
    drawn = call("draw_epipolar_lines", image, call("epipolar_lines", views.F, pts1))
    if getattr(drawn, "ndim", 0) == 3:
        drawn = drawn.copy()
        for x, y in pts2:
            cv2.circle(drawn, (int(round(x)), int(round(y))), 4, (255, 255, 255), 1)
    return [Panel("image 2", image), Panel("your lines; white circles: the matches", drawn)]


def _line_ends(line, width, height):
    """Two far-apart points of the line ``a x + b y + c = 0`` across a ``width`` x ``height`` image."""
    a, b, c = line
    if abs(b) >= abs(a):
        xs = np.array([-width, 2.0 * width])
        ys = -(c + a * xs) / b
    else:
        ys = np.array([-height, 2.0 * height])
        xs = -(c + b * ys) / a
    return [(int(x), int(y)) for x, y in np.clip(np.column_stack([xs, ys]), -1e5, 1e5)]


@figure("lab11.ex6", "two_view_reconstruction(img1, img2, K): matches, epipolar lines, 3D points")
def reconstruction(call):
    import cv2
    from fixtures import lab11 as truth

    pair = truth.rendered_pair(0)
    got = call("two_view_reconstruction", pair.img1, pair.img2, pair.K)
    if not isinstance(got, (tuple, list)) or len(got) != 4:
        raise FigureUnavailable("two_view_reconstruction() did not return (F, pts1, pts2, points3d)")
    F, pts1, pts2, points3d = (np.asarray(a, dtype=float) for a in got)
    if F.shape != (3, 3) or pts1.ndim != 2 or pts1.shape[1:] != (2,) or pts2.shape != pts1.shape \
            or points3d.shape != (len(pts1), 3) or len(pts1) == 0:
        raise FigureUnavailable(f"two_view_reconstruction() returned shapes {F.shape}, {pts1.shape}, "
                                f"{pts2.shape}, {points3d.shape}; expected (3, 3), (M, 2), (M, 2), (M, 3)")
    height, width = pair.img2.shape[:2]
    shown = np.unique(np.linspace(0, len(pts1) - 1, 12).astype(int))
    img1, img2 = (cv2.cvtColor(i, cv2.COLOR_GRAY2BGR) if i.ndim == 2 else i.copy() for i in (pair.img1, pair.img2))
    lines = np.column_stack([pts1[shown], np.ones(len(shown))]) @ F.T  # l' = F x for each shown match
    for k, i in enumerate(shown):
        colour = tuple(int(v) for v in _PALETTE[k % len(_PALETTE)])
        cv2.circle(img1, _pixel(pts1[i]), 4, colour, 2)
        cv2.circle(img2, _pixel(pts2[i]), 4, colour, 2)
        if np.all(np.isfinite(lines[k])) and np.any(lines[k][:2]):
            cv2.line(img2, *_line_ends(lines[k], width, height), colour, 1, cv2.LINE_AA)
    finite = np.all(np.isfinite(points3d), axis=1)
    return [Panel(f"image 1: {len(shown)} of your {len(pts1)} matches", img1),
            Panel("image 2: the matches on their epipolar lines (your F)", img2),
            Panel(f"your {finite.sum()} 3D points seen from above", points={"points3d": points3d[finite][:, [0, 2]]},
                  flip_y=False, axes=("X", "Z (depth, up to scale)"))]


_PALETTE = [(255, 80, 80), (80, 200, 80), (60, 60, 255), (0, 200, 255), (255, 0, 255), (255, 255, 0),
            (0, 128, 255), (128, 0, 255), (255, 128, 0), (0, 255, 128), (200, 200, 200), (128, 128, 255)]


def _pixel(point):
    x, y = np.clip(np.nan_to_num(np.asarray(point, float), nan=-1e5), -1e5, 1e5)
    return int(round(x)), int(round(y))
