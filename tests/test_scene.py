"""The ground-truth scene generator (fixtures/scene.py), tested on its own."""

import cv2
import numpy as np
import pytest

from fixtures.scene import (TexturedPlane, chessboard_object_points, chessboard_plane,
                            chessboard_texture, intrinsics, look_at, photo_plane, random_camera,
                            random_points_in_view, render, rotation_from_rvec)


def test_intrinsics_principal_point_is_image_centre():
    K = intrinsics(300.0, 320, 240, fy=310.0, skew=0.5)
    assert np.allclose(K, [[300, 0.5, 159.5], [0, 310, 119.5], [0, 0, 1]])


@pytest.mark.parametrize("seed", range(5))
def test_projection_consistent_with_P(seed):
    rng = np.random.default_rng(seed)
    cam = random_camera(rng)
    assert np.isclose(np.linalg.det(cam.R), 1.0) and np.allclose(cam.R @ cam.R.T, np.eye(3))
    X = rng.normal(size=(20, 3))
    x = np.column_stack([X, np.ones(20)]) @ cam.P.T
    assert np.allclose(cam.project(X), x[:, :2] / x[:, 2:], atol=1e-9)
    assert np.allclose(cam.depth(X), (X @ cam.R.T + cam.t)[:, 2])
    assert np.allclose(cam.P @ np.append(cam.center, 1.0), 0.0, atol=1e-9)
    # single points in, single points out
    assert cam.project(X[0]).shape == (2,) and np.allclose(cam.project(X[0]), cam.project(X)[0])
    assert np.ndim(cam.depth(X[0])) == 0
    # the target (origin) is on the optical axis
    assert np.allclose(cam.project(np.zeros(3)), [159.5, 119.5], atol=1e-9)


def test_random_camera_is_deterministic():
    a, b = random_camera(np.random.default_rng(7)), random_camera(np.random.default_rng(7))
    assert np.array_equal(a.P, b.P)
    assert not np.allclose(a.P, random_camera(np.random.default_rng(8)).P)


def test_look_at_orientation():
    K = intrinsics(200.0, 64, 48)
    cam = look_at((3.0, -1.0, -4.0), (0.5, 0.2, 1.0), K, 64, 48)
    assert np.allclose(cam.center, [3.0, -1.0, -4.0])
    assert np.allclose(cam.project(np.array([0.5, 0.2, 1.0])), [31.5, 23.5])
    assert cam.depth(np.array([0.5, 0.2, 1.0])) > 0
    # world -y (the default "up") appears above the target in the image
    above = cam.project(np.array([0.5, 0.2 - 0.5, 1.0]))
    assert above[1] < 23.5
    # degenerate up (looking straight down the y axis) still gives a rotation
    cam = look_at((0.0, -5.0, 0.0), (0.0, 0.0, 0.0), K, 64, 48)
    assert np.isclose(np.linalg.det(cam.R), 1.0)


@pytest.mark.parametrize("seed", range(3))
def test_random_points_in_view(seed):
    rng = np.random.default_rng(seed)
    cam = random_camera(rng)
    X = random_points_in_view(rng, cam, 200, depth_range=(4.0, 6.0), margin=15)
    x, z = cam.project(X), cam.depth(X)
    assert X.shape == (200, 3)
    assert (x >= 15 - 1e-9).all() and (x[:, 0] <= 320 - 1 - 15 + 1e-9).all() and (x[:, 1] <= 240 - 1 - 15 + 1e-9).all()
    assert (z >= 4.0).all() and (z <= 6.0).all()


def test_homography_matches_projection_of_texture_points():
    rng = np.random.default_rng(3)
    cam = random_camera(rng)
    plane = photo_plane(np.zeros((30, 40), np.uint8), 3.0, R=rotation_from_rvec([0.2, -0.3, 0.1]))
    tex = rng.uniform(0, 40, size=(25, 2))
    x = np.column_stack([tex, np.ones(25)]) @ plane.homography_to(cam).T
    assert np.allclose(x[:, :2] / x[:, 2:], cam.project(plane.world_points(tex)), atol=1e-9)


def test_chessboard_texture_layout():
    tex = chessboard_texture((4, 3), square_px=5, border_px=3)
    assert tex.shape == (3 * 5 + 6, 4 * 5 + 6) and tex.dtype == np.uint8
    assert (tex[:3] == 255).all() and (tex[:, -3:] == 255).all()
    assert tex[3, 3] == 0 and tex[3, 8] == 255 and tex[8, 3] == 255 and tex[8, 8] == 0


def test_chessboard_plane_corners_sit_on_square_corners():
    R = rotation_from_rvec([0.1, 0.4, -0.2])
    t = np.array([0.3, -0.2, 1.0])
    plane, corners = chessboard_plane((5, 3), 0.5, R=R, t=t, square_px=10)
    assert np.allclose(corners, chessboard_object_points((5, 3), 0.5) @ R.T + t)
    # inner corner (i, j) is at texture coordinate border - 0.5 + (i + 1) * square_px
    tex = np.array([[10 - 0.5 + 10 * (i + 1), 10 - 0.5 + 10 * (j + 1)] for j in range(3) for i in range(5)])
    assert np.allclose(plane.world_points(tex), corners)
    assert np.allclose(plane.normal, R[:, 2])


def _scene_camera():
    return look_at((0.4, -0.3, -6.0), (0.0, 0.0, 0.0), intrinsics(300.0, 160, 120), 160, 120)


def test_depth_map_backprojects_onto_the_plane():
    cam = _scene_camera()
    R = rotation_from_rvec([0.5, -0.4, 0.2])
    plane = photo_plane(np.full((40, 50), 128, np.uint8), 2.5, R=R, t=[0.1, 0.0, 0.5])
    image, depth = render(cam, [plane])
    seen = depth > 0
    assert 1000 < seen.sum() < depth.size
    rows, cols = np.nonzero(seen)
    X = cam.backproject(np.column_stack([cols, rows]).astype(float), depth[seen])
    distance = (X - plane.origin) @ plane.normal
    assert np.abs(distance).max() < 1e-9
    # ... and lands inside the textured rectangle
    h, w = plane.texture.shape
    uv = np.linalg.lstsq(np.column_stack([plane.u, plane.v]), (X - plane.origin).T, rcond=None)[0]
    assert (uv[0] >= -0.5 - 1e-6).all() and (uv[0] <= w - 0.5 + 1e-6).all()
    assert (uv[1] >= -0.5 - 1e-6).all() and (uv[1] <= h - 0.5 + 1e-6).all()
    # the image shows the texture where the depth map sees the plane (away from the edges)
    inner = cv2.erode(seen.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
    assert (image[inner] == 128).all() and (image[~cv2.dilate(seen.astype(np.uint8), np.ones((3, 3))).astype(bool)] == 0).all()


@pytest.mark.parametrize("order", [(0, 1), (1, 0)])
def test_occlusion_nearest_plane_wins(order):
    cam = _scene_camera()
    near = photo_plane(np.full((20, 20), 200, np.uint8), 1.5, t=[-0.3, 0.0, -1.0])
    far = photo_plane(np.full((20, 30), 60, np.uint8), 3.0, t=[0.3, 0.2, 1.0])
    planes = [near, far]
    image, depth = render(cam, [planes[i] for i in order], supersample=1)

    def on_plane(plane, x, y):
        X = cam.backproject([[x, y]], depth[y, x])
        return abs((X - plane.origin) @ plane.normal)[0] < 1e-9

    # the centre of the near plane is in front of the far one
    cx, cy = np.rint(cam.project(np.array([-0.3, 0.0, -1.0]))).astype(int)
    assert image[cy, cx] == 200 and on_plane(near, cx, cy)
    # a point of the far plane outside the near one
    fx, fy = np.rint(cam.project(np.array([1.6, 0.2, 1.0]))).astype(int)
    assert image[fy, fx] == 60 and on_plane(far, fx, fy)
    assert set(np.unique(image)) <= {0, 60, 200}
    # everywhere, the drawn plane is the one the depth map says
    for value, plane in ((200, near), (60, far)):
        rows, cols = np.nonzero(image == value)
        X = cam.backproject(np.column_stack([cols, rows]).astype(float), depth[rows, cols])
        assert np.abs((X - plane.origin) @ plane.normal).max() < 1e-9


def test_planes_behind_the_camera_are_not_drawn():
    cam = _scene_camera()
    behind = photo_plane(np.full((20, 20), 255, np.uint8), 4.0, t=[0.0, 0.0, -9.0])
    image, depth = render(cam, [behind], background=17)
    assert (image == 17).all() and (depth == 0).all()
    # a plane through the camera centre's plane: only the part in front is drawn
    floor = TexturedPlane(np.full((100, 100), 255, np.uint8), np.array([-5.0, 1.0, -10.0]),
                          np.array([0.1, 0.0, 0.0]), np.array([0.0, 0.0, 0.2]))
    image, depth = render(cam, [floor])
    assert (depth >= 0).all()
    rows = np.nonzero((depth > 0).any(axis=1))[0]
    assert rows.size and rows.min() > cam.K[1, 2]      # the floor is below the horizon only
    assert (image[depth > 0] > 0).all() and (image[:int(cam.K[1, 2])] == 0).all()


def test_colour_follows_first_plane():
    cam = _scene_camera()
    colour = photo_plane(np.full((10, 10, 3), (10, 20, 30), np.uint8), 1.0)
    grey = photo_plane(np.full((10, 10), 99, np.uint8), 1.0, t=[1.5, 0.0, 0.0])
    image, _ = render(cam, [colour, grey], background=(1, 2, 3))
    assert image.shape == (120, 160, 3)
    assert (image[0, 0] == (1, 2, 3)).all()
    cx, cy = np.rint(cam.project(np.zeros(3))).astype(int)
    assert (image[cy, cx] == (10, 20, 30)).all()
    gx, gy = np.rint(cam.project(np.array([1.5, 0.0, 0.0]))).astype(int)
    assert (image[gy, gx] == 99).all()


@pytest.mark.parametrize("pattern_size,rvec,angle", [
    ((8, 5), [0.3, 0.2, 0.0], 0.0),
    ((8, 5), [-0.4, 0.3, 0.1], 30.0),
    ((7, 6), [0.2, -0.5, 0.0], 180.0),     # parity differs: order survives a half turn
    ((6, 4), [0.0, 0.0, 0.0], -20.0),
])
def test_found_chessboard_corners_match_projected_object_points(pattern_size, rvec, angle):
    K = intrinsics(300.0, 320, 240)
    cam = look_at((0.0, 0.0, -6.0), (0.0, 0.0, 0.0), K, 320, 240)
    a = np.deg2rad(angle)
    spin = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    R = rotation_from_rvec(rvec) @ spin
    centre = np.array([(pattern_size[0] - 1) * 0.15, (pattern_size[1] - 1) * 0.15, 0.0])
    plane, corners = chessboard_plane(pattern_size, 0.3, R=R, t=-R @ centre)
    image, _ = render(cam, [plane])
    found, detected = cv2.findChessboardCorners(image, pattern_size)
    assert found
    error = np.linalg.norm(detected.reshape(-1, 2) - cam.project(corners), axis=1)
    assert error.max() < 0.5, error.max()
