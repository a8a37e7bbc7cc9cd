"""Lab 9 - hidden checks (instructor's copy and container only).

Inputs come only from seeds and parameters written here.
"""

from __future__ import annotations

import numpy as np

from fixtures import lab09 as truth

from ..lab09 import (ex3, ex4, ext1, judge_in_front, judge_calibration, judge_matrix, judge_points,
                     points_probe, project_mistakes)


@ex3.check("hidden: camera_matrix and project for other cameras", points=2, hidden=True)
def hidden_project(t):
    for seed in (9001, 9002, 9003):
        K = np.array([[520.0, 1.5, 300.0], [0.0, 505.0, 215.0], [0.0, 0.0, 1.0]])
        R, tvec = truth.random_pose(seed, max_angle_deg=60.0, distance=9.0)
        P = truth.camera(K, R, tvec)
        judge_matrix(t, "camera_matrix(K, R, t)", t.call("camera_matrix", K, R, tvec), P,
                     truth.camera_mistakes(K, R, tvec), shape=(3, 4))
        X = truth.world_points_for(K, R, tvec, seed=seed + 7, n=25, width=640, height=480)
        judge_points(t, "project(P, points)", t.call("project", P, X), truth.homogeneous_project(P, X),
                     project_mistakes(P, X), probe=points_probe(t, "project"))
    Xc, behind = truth.with_points_behind(truth.points_in_front(9004, n=16), seed=9005)
    X = (Xc - tvec) @ R
    judge_in_front(t, "project(P, points, some behind)", t.call("project", P, X),
                 truth.homogeneous_project(P, X), behind)


@ex4.check("hidden: project_focal_lengths for many focal lengths", points=1, hidden=True)
def hidden_focal_lengths(t):
    X = truth.points_in_front(9010, n=20)
    fs = np.linspace(50.0, 1500.0, 7)
    got = t.expect_array(t.call("project_focal_lengths", X, fs), "project_focal_lengths(points, 7 focal lengths)",
                         shape=(7, 20, 2), kind="iuf")
    for i, f in enumerate(fs):
        judge_points(t, f"project_focal_lengths(...)[{i}]", got[i], truth.pinhole(X, f),
                     truth.projection_mistakes(f, X), probe=points_probe(t, "project_focal_lengths"))


HIDDEN_K = ((360.0, 0.0, 155.0), (0.0, 355.0, 124.0), (0.0, 0.0, 1.0))
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
    images, _ = truth.render_calibration_views(HIDDEN_K, HIDDEN_VIEWS)
    return judge_calibration(t, images, np.array(HIDDEN_K), truth.CALIBRATION_PATTERN)
