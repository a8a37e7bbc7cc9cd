"""Lab 10 - hidden checks (instructor's copy and container only).

Inputs come only from seeds and parameters written here.
"""

from __future__ import annotations


from fixtures import lab10 as truth

from ..lab10 import (ex2, ex4, ex5, ex6, _call_pose, judge_center, judge_decomposition, judge_dlt,
                     judge_pose, judge_points, projection_probe, weak_mistakes)


@ex2.check("hidden: weak perspective on other objects", points=1, hidden=True)
def hidden_weak(t):
    for seed, f, z_avg in ((7001, 250.0, None), (7002, 800.0, 30.0)):
        X = truth.scene_points(seed, n=15, depth=25.0, relief=5.0)
        judge_points(t, f"weak_perspective_project(points, f={f:g}, z_avg={z_avg})",
                     t.call("weak_perspective_project", X, f, z_avg=z_avg),
                     truth.weak_perspective(X, f, z_avg), weak_mistakes(X, f, z_avg),
                     probe=projection_probe(t, "weak_perspective_project", z_avg=None if z_avg is None else 7.25))


@ex4.check("hidden: DLT on other cameras, exact and noisy", points=2, hidden=True)
def hidden_dlt(t):
    judge_dlt(t, 7010, 8, 0.0)
    judge_dlt(t, 7011, 60, 1.0)
    return judge_dlt(t, 7012, 30, 0.3)


@ex5.check("hidden: decomposition and centre of other cameras", points=2, hidden=True)
def hidden_decompose(t):
    for seed in (7020, 7021, 7022, 7023):
        P, K, R, tv, _ = truth.random_camera_matrix(seed)
        judge_decomposition(t, P, K, R, tv)
        judge_center(t, P, R, tv)


@ex6.check("hidden: pose of a board in other positions", points=2, hidden=True)
def hidden_pose(t):
    for view in (((-0.45, -0.1, 0.1), -30.0, 3.8, (0.25, -0.1)), ((0.05, 0.05, 0.0), 90.0, 4.5, (0.0, 0.0))):
        image, R, tv, corners = truth.render_pose_view(*view)
        what, got = _call_pose(t, image, truth.POSE_PATTERN, truth.POSE_SQUARE, truth.POSE_K)
        verdict = judge_pose(t, what, got, image, R, tv, corners, truth.POSE_PATTERN, truth.POSE_SQUARE,
                             truth.POSE_K, show=False)
        if verdict.fraction < 1:
            return verdict
    return verdict
