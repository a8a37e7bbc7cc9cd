"""Lab 9 - hidden checks (instructor's copy and container only).

Every input is drawn from ``t.rng``, the submission's own generator: the cameras, poses
and points, the focal lengths, and the intrinsics and board views of the calibration.
"""

from __future__ import annotations

import numpy as np

from fixtures import lab09 as truth

import ast

from ...engine.checks import Fail, StudentFailure
from ...engine.claims import from_code, measured
from ...engine.hints import Predicate, code_of
from ..lab09 import (ex3, ex4, ext1, judge_in_front, judge_calibration, judge_matrix, judge_points,
                     points_probe, project_mistakes)
from ._draws import board_views, seed, uncached, uniform
from ...loading.parsing import walk


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
                     uncached(truth.camera_mistakes)(K, R, tvec), shape=(3, 4), up_to_scale=True)   # (P: any scale)
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


def calibration_camera(rng) -> tuple:
    """A 320 x 240 camera's K (nested tuples, as the fixtures' caches want): focal lengths 10 px apart
    or so, the principal point off the image centre."""
    fx = uniform(rng, 330.0, 390.0, 1)
    return ((fx, 0.0, uniform(rng, 150.0, 170.0, 1)),
            (0.0, round(fx + uniform(rng, -10.0, 10.0), 1), uniform(rng, 112.0, 128.0, 1)), (0.0, 0.0, 1.0))


@ext1.check("hidden: calibrate on views of another camera", points=2, hidden=True)
def hidden_calibration(t):
    K = calibration_camera(t.rng)
    views = board_views(t.rng, HIDDEN_VIEWS, np.array(K), truth.CALIBRATION_PATTERN, truth.CALIBRATION_SQUARE,
                        truth.CALIBRATION_SIZE)
    images, _ = uncached(truth.render_calibration_views)(K, views)
    return judge_calibration(t, images, np.array(K), truth.CALIBRATION_PATTERN)


def out_of_frame(K, view, pattern, square, size) -> tuple:
    """``view`` moved sideways until two columns of its board's inner corners lie outside the image: a
    photo in which no corner detector can find the whole board (a calibration set taken by hand has some)."""
    tilt, spin, distance, (x, y) = view
    cols, rows = pattern
    for step in range(1, 60):
        moved = (tilt, spin, distance, (round(x + 0.05 * step, 3), y))
        R, tvec = truth.board_pose(np.array(tilt), spin, distance, pattern, square, moved[3])
        corners = truth.homogeneous_project(truth.camera(K, R, tvec), truth.board_points(pattern, square))
        outside = (corners[:, 0] < 0) | (corners[:, 0] > size[0] - 1) | (corners[:, 1] < 0) | (corners[:, 1] > size[1] - 1)
        if outside.sum() >= 2 * rows:
            return moved
    raise RuntimeError("the board never left the image")


def _breaks_a_loop(function) -> bool:
    return any(isinstance(n, ast.Break) for n in walk(function))


@ext1.check("hidden: calibrate when one of the views does not show the whole board", points=1, hidden=True)
def hidden_calibration_board_missing(t):
    K = calibration_camera(t.rng)
    pattern, square, size = truth.CALIBRATION_PATTERN, truth.CALIBRATION_SQUARE, truth.CALIBRATION_SIZE
    views = board_views(t.rng, HIDDEN_VIEWS, np.array(K), pattern, square, size)
    missing = out_of_frame(np.array(K), views[1], pattern, square, size)
    images, _ = uncached(truth.render_calibration_views)(K, (views[0], missing) + views[1:])
    t.images("the second view: the board leaves the image", view_2=images[1])
    # (measured: the view was made so, and no corner detector finds a board whose corners leave the image)
    told = measured(f"The second of these {len(images)} views does not show the whole board (two columns of its "
                    "corners are outside the image), as happens in a set of photos taken by hand: "
                    "cv2.findChessboardCorners finds no board there, and such a view is left out (the other views "
                    "calibrate the camera).")
    try:
        return judge_calibration(t, images, np.array(K), pattern)
    except StudentFailure as failure:
        if failure.outcome.kind != "exception":
            raise
        raise failure.said(f"{failure.message}\n" + told) from None
    except Fail as failure:
        # Judged again with that view last: right there, the views after it were never used.
        try:
            judge_calibration(t, images[:1] + images[2:] + images[1:2], np.array(K), pattern)
        except (Fail, StudentFailure):
            raise failure from None
        stops = Predicate("leaves its loop with break", _breaks_a_loop).found(code_of(t).reachable(["calibrate"]))
        cause = from_code(" (your code leaves its loop with `break`: `continue` goes on to the next view)") if stops else ""
        mistake = "the views after one without a board are not used"
        t.fail(f"{failure.message}\n{told}\n" + measured(
            "With that view given last, your calibration is right: the views after a view without a board are "
            "not used") + f"{cause}.", mistake=mistake)
