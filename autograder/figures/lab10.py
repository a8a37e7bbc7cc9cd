"""Lab 10's figures: focal lengths, perspective vs weak perspective vs orthographic."""

from . import Panel, figure


def _scene():
    from fixtures.lab10 import scene_points

    return scene_points(101, n=40, depth=8.0, relief=4.0)


@figure("lab10.ex1", "perspective_project(points, f) for f = 100, 500, 1000")
def focal_lengths(call):
    X = _scene()
    return [Panel(f"f = {f:g}", points={"perspective": call("perspective_project", X, f)})
            for f in (100.0, 500.0, 1000.0)]


@figure("lab10.ex2", "perspective and weak perspective, f = 500")
def weak(call):
    X = _scene()
    perspective = call("perspective_project", X, 500.0)
    weak_ = call("weak_perspective_project", X, 500.0)
    return [Panel("perspective", points={"perspective": perspective}),
            Panel("weak perspective", points={"weak perspective": weak_}),
            Panel("both", points={"perspective": perspective, "weak perspective": weak_})]


@figure("lab10.ex3", "orthographic and perspective projections")
def orthographic(call):
    X = _scene()
    return [Panel("orthographic", points={"orthographic": call("orthographic_project", X)}),
            Panel("perspective, f = 1", points={"perspective": call("perspective_project", X, 1.0)})]


@figure("lab10.ex6", "estimate_pose: reprojected chessboard corners")
def pose(call):
    import cv2
    import numpy as np
    from fixtures.lab10 import POSE_K, POSE_PATTERN, POSE_SQUARE, pose_views

    image = pose_views()[0][0]
    _, _, reprojected = call("estimate_pose", image, POSE_PATTERN, POSE_SQUARE, POSE_K)
    marked = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image.copy()
    for x, y in np.asarray(reprojected, float).reshape(-1, 2):
        if np.isfinite(x) and np.isfinite(y):
            cv2.circle(marked, (int(round(x)), int(round(y))), 3, (0, 0, 255), -1)
    return [Panel("input", image), Panel("reprojected corners (red)", marked)]
