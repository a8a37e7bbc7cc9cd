"""Lab 10's figures: focal lengths, perspective vs weak perspective vs orthographic."""

from . import FigureUnavailable, Panel, common_extent, figure, thinned


def _scene():
    from fixtures.lab10 import scene_points

    return scene_points(101, n=40, depth=8.0, relief=4.0)


@figure("lab10.ex1", "perspective_project(points, f) for f = 100, 500, 1000")
def focal_lengths(call):
    X = _scene()
    projections = {f: call("perspective_project", X, f) for f in (100.0, 500.0, 1000.0)}
    extent = common_extent(*projections.values())  # one scale for all three: the picture grows with f
    return [Panel(f"f = {f:g}", points={"perspective": p}, extent=extent) for f, p in projections.items()]


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
    corners, count = thinned(reprojected)  # drawn one by one: at most MAX_POINTS_DRAWN
    marked = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image.copy()
    for x, y in np.clip(corners[np.all(np.isfinite(corners), axis=1)], -1e5, 1e5):
        cv2.circle(marked, (int(round(x)), int(round(y))), 3, (0, 0, 255), -1)
    drawn = "" if count == len(corners) else f", {len(corners):,} of {count:,} drawn"
    return [Panel("input", image), Panel(f"reprojected corners (red{drawn})", marked)]


@figure("lab10.ext1", "undistort_image(distorted chessboard view, K, dist)")
def undistortion(call):
    from fixtures.lab10 import DIST, POSE_K, distorted_view

    distorted, clean, *_ = distorted_view()
    return [Panel("what the lens records", distorted),
            Panel("undistort_image(image, K, dist)", call("undistort_image", distorted, POSE_K, DIST)),
            Panel("the view without distortion", clean)]


@figure("lab10.ext2", "dolly_zoom(points, f0=300, z0=4, distances=[2, 4, 8])")
def dolly(call):
    import numpy as np

    side = np.linspace(-0.5, 0.5, 9)
    edge, depth = np.full_like(side, 0.5), np.full_like(side, 4.0)  # a square of side 1 at z0 = 4
    subject = np.vstack([np.column_stack([side, s * edge, depth]) for s in (-1, 1)]
                        + [np.column_stack([s * edge, side, depth]) for s in (-1, 1)])
    xs, ys = np.meshgrid(np.linspace(-4, 4, 9), np.linspace(-3, 3, 7))
    background = np.column_stack([xs.ravel(), ys.ravel(), np.full(xs.size, 12.0)])
    distances = np.array([2.0, 4.0, 8.0])
    focal_lengths, projections = call("dolly_zoom", np.vstack([subject, background]), 300.0, 4.0, distances)
    projections = np.asarray(projections, float)
    if projections.shape != (3, len(subject) + len(background), 2):
        raise FigureUnavailable(f"dolly_zoom() returned projections of shape {projections.shape}")
    centre = np.array([160.0, 120.0])  # drawn on a 320 x 240 image, the optical axis at its centre
    return [Panel(f"subject at {d:g}, f = {float(f):.4g}",
                  points={"subject": projections[k, :len(subject)] + centre,
                          "background": projections[k, len(subject):] + centre},
                  frame=(320.0, 240.0), axes=("column x", "row y"))
            for k, (d, f) in enumerate(zip(distances, np.asarray(focal_lengths, float).reshape(-1)))]


@figure("lab10.ext3", "track_pose(frames): the board's position in each frame")
def tracking(call):
    import numpy as np
    from fixtures.lab10 import POSE_K, POSE_PATTERN, POSE_SQUARE, track_sequence

    frames, _ = track_sequence()
    poses = np.asarray(call("track_pose", list(frames), POSE_PATTERN, POSE_SQUARE, POSE_K), float)
    if poses.ndim != 2 or poses.shape[1] != 6:
        raise FigureUnavailable(f"track_pose() returned shape {poses.shape}; expected (frames, 6)")
    found = np.all(np.isfinite(poses), axis=1)
    return [Panel(f"frame {k + 1}" + ("" if k < len(found) and found[k] else ": no board found"), frame)
            for k, frame in enumerate(frames)] + [
        Panel(f"tvec seen from above ({found.sum()} of {len(frames)} frames)",
              points={"board origin": poses[found][:, [3, 5]]}, flip_y=False, axes=("X", "Z (depth)"))]
