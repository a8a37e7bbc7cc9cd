"""Lab 10 - hidden checks (instructor's copy and container only).

Every input is drawn from ``t.rng``, the submission's own generator: the objects, focal
lengths and depths, the DLT problems, the cameras to decompose and the board's poses.
"""

from __future__ import annotations


from fixtures import lab10 as truth

from ..lab10 import (ex2, ex4, ex5, ex6, _call_pose, judge_center, judge_decomposition, judge_dlt,
                     judge_pose, judge_points, projection_probe, weak_mistakes)
from ._draws import board_views, seed, uniform


@ex2.check("hidden: weak perspective on other objects", points=1, hidden=True)
def hidden_weak(t):
    # A short focal length with the mean depth, a long one with a given z_avg 4 to 8 units
    # beyond the object's depth (so a z_avg ignored, or the mean used, shows).
    depth = uniform(t.rng, 20.0, 30.0, 1)
    cases = ((uniform(t.rng, 150.0, 400.0, 1), None),
             (uniform(t.rng, 600.0, 1000.0, 1), round(depth + uniform(t.rng, 4.0, 8.0), 1)))
    relief = uniform(t.rng, 3.0, 6.0, 1)
    for f, z_avg in cases:
        X = truth.scene_points(seed(t.rng), n=15, depth=depth, relief=relief)
        judge_points(t, f"weak_perspective_project(points, f={f:g}, z_avg={z_avg})",
                     t.call("weak_perspective_project", X, f, z_avg=z_avg),
                     truth.weak_perspective(X, f, z_avg), weak_mistakes(X, f, z_avg),
                     probe=projection_probe(t, "weak_perspective_project", z_avg=None if z_avg is None else 7.25))


@ex4.check("hidden: DLT on other cameras, exact and noisy", points=2, hidden=True)
def hidden_dlt(t):
    judge_dlt(t, seed(t.rng), int(t.rng.integers(8, 13)), 0.0)
    judge_dlt(t, seed(t.rng), int(t.rng.integers(50, 71)), uniform(t.rng, 0.8, 1.2))
    return judge_dlt(t, seed(t.rng), int(t.rng.integers(25, 36)), uniform(t.rng, 0.2, 0.4))


@ex5.check("hidden: decomposition and centre of other cameras", points=2, hidden=True)
def hidden_decompose(t):
    for k in range(4):
        P, K, R, tv, s = truth.random_camera_matrix(seed(t.rng))
        if k == 0 and s > 0:   # the first P is -1 times a K [R | t]: the sign fix must negate it
            P = -P
        judge_decomposition(t, P, K, R, tv)
        judge_center(t, P, R, tv)


# A tilted board off the axis and one turned by 90 degrees in its plane, each moved by a
# drawn amount (_draws.board_views).
HIDDEN_POSES = (((-0.45, -0.1, 0.1), -30.0, 3.8, (0.25, -0.1)), ((0.05, 0.05, 0.0), 90.0, 4.5, (0.0, 0.0)))


@ex6.check("hidden: pose of a board in other positions", points=2, hidden=True)
def hidden_pose(t):
    views = board_views(t.rng, HIDDEN_POSES, truth.POSE_K, truth.POSE_PATTERN, truth.POSE_SQUARE, truth.POSE_SIZE)
    for view in views:
        image, R, tv, corners = truth.render_pose_view(*view)
        what, got = _call_pose(t, image, truth.POSE_PATTERN, truth.POSE_SQUARE, truth.POSE_K)
        verdict = judge_pose(t, what, got, image, R, tv, corners, truth.POSE_PATTERN, truth.POSE_SQUARE,
                             truth.POSE_K, show=False)
        if verdict.fraction < 1:
            return verdict
    return verdict
