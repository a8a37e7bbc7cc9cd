"""Lab 9 - hidden checks (instructor's copy and container only).

Every input is drawn from ``t.rng``, the submission's own generator: the cameras, poses
and points, the focal lengths, and the intrinsics and board views of the calibration.
"""

from __future__ import annotations

import numpy as np

from fixtures import lab09 as truth

from ..lab09 import (ex3, ex4, ext1, judge_in_front, judge_calibration, judge_matrix, judge_points,
                     points_probe, project_mistakes)
from ._draws import board_views, seed, uncached, uniform


def hidden_intrinsics(rng) -> np.ndarray:
    """A 640 x 480 camera: focal lengths 20 px apart or so, a small skew, the principal
    point off the image centre."""
    fx = uniform(rng, 480.0, 560.0, 1)
    return np.array([[fx, uniform(rng, 0.5, 2.5), uniform(rng, 285.0, 315.0, 1)],
                     [0.0, round(fx - uniform(rng, 8.0, 30.0, 1), 1), uniform(rng, 200.0, 230.0, 1)],
                     [0.0, 0.0, 1.0]])


@ex3.check("hidden: camera_matrix and project for other cameras", points=2, hidden=True)
def hidden_project(t):
    K = hidden_intrinsics(t.rng)
    for _ in range(3):
        R, tvec = truth.random_pose(seed(t.rng), max_angle_deg=60.0, distance=9.0)
        P = truth.camera(K, R, tvec)
        judge_matrix(t, "camera_matrix(K, R, t)", t.call("camera_matrix", K, R, tvec), P,
                     uncached(truth.camera_mistakes)(K, R, tvec), shape=(3, 4))
        X = truth.world_points_for(K, R, tvec, seed=seed(t.rng), n=25, width=640, height=480)
        judge_points(t, "project(P, points)", t.call("project", P, X), truth.homogeneous_project(P, X),
                     project_mistakes(P, X), probe=points_probe(t, "project"))
    Xc, behind = truth.with_points_behind(truth.points_in_front(seed(t.rng), n=16), seed=seed(t.rng))
    X = (Xc - tvec) @ R
    judge_in_front(t, "project(P, points, some behind)", t.call("project", P, X),
                   truth.homogeneous_project(P, X), behind)


@ex4.check("hidden: project_focal_lengths for many focal lengths", points=1, hidden=True)
def hidden_focal_lengths(t):
    X = truth.points_in_front(seed(t.rng), n=20)
    fs = np.linspace(uniform(t.rng, 40.0, 80.0, 1), uniform(t.rng, 1200.0, 1800.0, 1), 7)
    got = t.expect_array(t.call("project_focal_lengths", X, fs), "project_focal_lengths(points, 7 focal lengths)",
                         shape=(7, 20, 2), kind="iuf")
    for i, f in enumerate(fs):
        judge_points(t, f"project_focal_lengths(...)[{i}] (f={f:g})", got[i], truth.pinhole(X, f),
                     truth.projection_mistakes(f, X), probe=points_probe(t, "project_focal_lengths"))


# Board views (tilt rvec, spin in degrees, distance, (x, y) offset), each moved by a drawn
# amount (_draws.board_views); the six views stay tilted about different axes, so the
# calibration stays well conditioned.
HIDDEN_VIEWS = (
    ((-0.45, 0.0, 0.0), 0.0, 3.7, (0.0, 0.0)),
    ((0.4, -0.25, 0.0), -10.0, 3.9, (0.2, 0.1)),
    ((0.0, -0.5, 0.0), 8.0, 3.6, (-0.2, 0.0)),
    ((-0.2, 0.45, -0.1), -5.0, 4.1, (0.1, -0.15)),
    ((0.3, 0.3, 0.0), -15.0, 3.8, (-0.1, 0.15)),
    ((-0.35, -0.35, 0.1), 12.0, 4.2, (0.0, -0.1)),
)


@ext1.check("hidden: calibrate on views of another camera", points=2, hidden=True)
def hidden_calibration(t):
    fx = uniform(t.rng, 330.0, 390.0, 1)
    K = ((fx, 0.0, uniform(t.rng, 150.0, 170.0, 1)),
         (0.0, round(fx + uniform(t.rng, -10.0, 10.0), 1), uniform(t.rng, 112.0, 128.0, 1)), (0.0, 0.0, 1.0))
    views = board_views(t.rng, HIDDEN_VIEWS, np.array(K), truth.CALIBRATION_PATTERN, truth.CALIBRATION_SQUARE,
                        truth.CALIBRATION_SIZE)
    images, _ = uncached(truth.render_calibration_views)(K, views)
    return judge_calibration(t, images, np.array(K), truth.CALIBRATION_PATTERN)
