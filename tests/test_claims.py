"""Hints and diagnoses held to the student's code (autograder/engine/claims.py, labs 7, 9, 10, 11).

For each guarded sentence: a student whose code already does what it asks (or never does what it
claims) is not told it; the realistic mistake it names still is. The code is read, never run.
Three graded cases check the path through the runner (a mistake's name from a fixtures table).
"""

from __future__ import annotations

import textwrap

import pytest

from autograder.engine import claims
from autograder.engine.claims import (THIRD_COORDINATE, divides_by, negates_on_negative_det, passes_argument,
                                      reshapes, zeroes_an_entry)
from autograder.engine.hints import read_code
from autograder.engine.runner import grade
from autograder.labs import lab07, lab09, lab10, lab11
from conftest import check_results, mutant
from fixtures import lab07 as truth07
from fixtures import lab09 as truth09
from fixtures import lab10 as truth10


def told(hint, source: str, function: str) -> bool:
    """Whether ``hint`` keeps its text for ``function`` of the module ``source``."""
    return not hint.contradicts(read_code(textwrap.dedent(source)), [function])


G = claims.GUARDED
# (hint, student function, code that already does what it asks, the realistic mistake)
CASES = {
    "lab07 angle as radians": (G[truth07.ANGLE_AS_RADIANS], "rotation_matrix", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            c, s = np.cos(angle_deg), np.sin(angle_deg)
            return np.array([[c, s, 0], [-s, c, 0], [0, 0, 1.0]])
        """, """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            c, s = np.cos(angle_deg), np.sin(angle_deg)
            return np.array([[c, s, 0], [-s, c, 0], [0, 0, 1.0]])
        """),
    "lab07 radians given to OpenCV": (G[truth07.RADIANS_TO_OPENCV], "rotation_matrix", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(np.radians(angle_deg))
            c, s = np.cos(theta), np.sin(theta)
            return np.array([[c, s, 0], [-s, c, 0], [0, 0, 1.0]])
        """, """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            return np.vstack([cv2.getRotationMatrix2D(center, np.deg2rad(angle_deg), 1.0), [0, 0, 1]])
        """),
    "lab07 inverse map": (G[truth07.INVERSE_MAP], "warp_affine", """
        def warp_affine(image, A, dsize=None):
            h, w = image.shape[:2]
            ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)
            return cv2.remap(image, A[0, 0] * xs + A[0, 1] * ys + A[0, 2], A[1, 0] * xs + A[1, 1] * ys + A[1, 2],
                             cv2.INTER_LINEAR)
        """, """
        def warp_affine(image, A, dsize=None):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, A, dsize or (w, h), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
        """),
    "lab09 division missing": (G[truth09.DIVISION_MISSING], "pinhole_project", """
        def pinhole_project(points, f):
            X = np.atleast_2d(points)
            Z = X[:, 2]
            out = f * X[:, :2]
            divided = out / Z[:, None]
            return out
        """, """
        def pinhole_project(points, f):
            return f * np.atleast_2d(points)[:, :2]
        """),
    "lab09 K transposed": (G[truth09.K_TRANSPOSED], "project_with_intrinsics", """
        def project_with_intrinsics(K, points):
            h = np.atleast_2d(points) @ K.T
            return (h[:, :2] / h[:, 2:]).T
        """, """
        def project_with_intrinsics(K, points):
            h = np.atleast_2d(points) @ K
            return h[:, :2] / h[:, 2:]
        """),
    "lab09 translation dropped": (G[lab09.TRANSLATION_DROPPED], "project", """
        def project(P, points):
            X = np.hstack([points, np.ones((len(points), 1))])
            h = X[:, :3] @ P[:, :3].T
            return h[:, :2] / h[:, 2:]
        """, """
        def project(P, points):
            h = points @ P[:, :3].T
            return h[:, :2] / h[:, 2:]
        """),
    "lab09 a single point": (lab09.SINGLE_POINT_HINT, "pinhole_project", """
        def pinhole_project(points, f):
            X = np.atleast_2d(np.asarray(points, float))
            return f * X[:, :2] / X[:, 2:]
        """, """
        def pinhole_project(points, f):
            X = np.asarray(points, float).reshape(-1, 3)
            return f * X[:, :2] / X[:, 2:]
        """),
    "lab09 the seed": (lab09.SEED_HINT, "simulate_aperture", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            rng = np.random.default_rng()
            u = np.random.uniform(size=n_rays)
            return u
        """, """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            u = np.random.uniform(size=n_rays)
            return u
        """),
    "lab09 drawing on a copy": (lab09.COPY_HINT, "draw_points", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in pts:
                cv2.circle(image, (int(x), int(y)), radius, color, -1)
            return out
        """, """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            for x, y in pts:
                cv2.circle(image, (int(x), int(y)), radius, color, -1)
            return image
        """),
    "lab09 object points": (lab09.OBJECT_POINTS_HINT, "calibrate", """
        def calibrate(images, pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float32)
            objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
            return objp
        """, """
        def calibrate(images, pattern_size, square_size):
            objp = np.zeros((pattern_size[0] * pattern_size[1], 3), np.float32)
            objp[:, :2] = np.mgrid[0:pattern_size[1], 0:pattern_size[0]].T.reshape(-1, 2) * square_size
            return objp
        """),
    "lab10 the 12-vector's order": (G[truth10.RESHAPED_WRONG], "camera_matrix_dlt", """
        def camera_matrix_dlt(points3d, points2d):
            return np.linalg.svd(_design(points3d, points2d))[2][-1].reshape(3, 4)
        """, """
        def camera_matrix_dlt(points3d, points2d):
            return np.linalg.svd(_design(points3d, points2d))[2][-1].reshape(4, 3).T
        """),
    "lab10 the largest singular vector": (G[truth10.LARGEST_TAKEN], "camera_matrix_dlt", """
        def camera_matrix_dlt(points3d, points2d):
            U, S, Vt = np.linalg.svd(_design(points3d, points2d).T)
            return Vt[-1, :].reshape(3, 4)
        """, """
        def camera_matrix_dlt(points3d, points2d):
            return np.linalg.svd(_design(points3d, points2d))[2][0].reshape(3, 4)
        """),
    "lab10 the last column of Vt": (G[truth10.LAST_COLUMN_TAKEN], "camera_matrix_dlt", """
        def camera_matrix_dlt(points3d, points2d):
            vt = np.linalg.svd(_design(points3d, points2d))[2]
            return vt[-1].reshape(4, 3).T
        """, """
        def camera_matrix_dlt(points3d, points2d):
            return np.linalg.svd(_design(points3d, points2d))[2][:, -1].reshape(3, 4)
        """),
    "lab11 the largest singular vector": (G[lab11.FUNDAMENTAL_MISTAKES["largest"]], "fundamental_8point", """
        def fundamental_8point(pts1, pts2):
            _, _, V = np.linalg.svd(_design(pts1, pts2).T @ _design(pts1, pts2))
            return _rank2(V[-1].reshape(3, 3))
        """, """
        def fundamental_8point(pts1, pts2):
            _, _, V = np.linalg.svd(_design(pts1, pts2))
            return _rank2(V[0].reshape(3, 3))
        """),
    "lab10 normalisation not undone": (G[truth10.NOT_UNDONE], "camera_matrix_dlt", """
        def camera_matrix_dlt(points3d, points2d):
            Pn = _solve(points3d, points2d)
            P = np.linalg.inv(T2) @ Pn @ T3
            return Pn
        """, """
        def camera_matrix_dlt(points3d, points2d):
            return _solve(points3d, points2d)
        """),
    "lab10 P negated first": (lab10.SIGN_FIX, "decompose_camera_matrix", """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            if np.linalg.det(P[:, :3]) > 0:
                P = -P
            K, R = scipy.linalg.rq(P[:, :3])
            return K / K[2, 2], R, np.linalg.solve(K, P[:, 3])
        """, """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            K, R = scipy.linalg.rq(P[:, :3])
            return K / K[2, 2], R, np.linalg.solve(K, P[:, 3])
        """),
    "lab10 RQ": (lab10.RQ_HINT, "decompose_camera_matrix", """
        def decompose_camera_matrix(P):
            R, K = scipy.linalg.rq(P[:, :3])
            return K, R, P[:, 3]
        """, """
        def decompose_camera_matrix(P):
            K = P[:, :3] / np.linalg.norm(P[2, :3])
            return K, np.eye(3), P[:, 3]
        """),
    "lab10 K normalised": (lab10.NORMALISE_K_HINT, "decompose_camera_matrix", """
        def decompose_camera_matrix(P):
            K, R = scipy.linalg.rq(P[:, :3])
            Kn = K / K[2, 2]
            return K, R, P[:, 3]
        """, """
        def decompose_camera_matrix(P):
            K, R = scipy.linalg.rq(P[:, :3])
            return K, R, P[:, 3]
        """),
    "lab10 signs of K and R": (lab10.SIGNS_HINT, "decompose_camera_matrix", """
        def decompose_camera_matrix(P):
            K, R = scipy.linalg.rq(P[:, :3])
            D = np.diag(np.sign(np.diag(K)))
            return K @ D, R, P[:, 3]
        """, """
        def decompose_camera_matrix(P):
            K, R = scipy.linalg.rq(P[:, :3])
            return K, R, P[:, 3]
        """),
    "lab10 fixed P[2, 3]": (lab10.FIXED_P23_HINT, "camera_matrix_dlt", """
        def camera_matrix_dlt(points3d, points2d):
            A = _design(points3d, points2d)[:, :11]
            return np.append(np.linalg.svd(A)[2][-1], 1.0).reshape(3, 4)
        """, """
        def camera_matrix_dlt(points3d, points2d):
            A, b = _system(points3d, points2d)
            p = np.linalg.lstsq(A, b, rcond=None)[0]
            return np.append(p, 1.0).reshape(3, 4)
        """),
    "lab10 dist to projectPoints": (G["the corners are projected without dist (pass dist to cv2.projectPoints too)"],
                                    "estimate_pose", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            ok, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)
            out, _ = cv2.projectPoints(objp, rvec, tvec, K, np.zeros(5))
            return rvec, tvec, out
        """, """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            ok, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)
            out, _ = cv2.projectPoints(objp, rvec, tvec, K, None)
            return rvec, tvec, out
        """),
    "lab10 dist to solvePnP": (lab10.DIST_TO_PNP_HINT, "estimate_pose", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            ok, rvec, tvec = cv2.solvePnP(objp, corners, K, distCoeffs=np.zeros(5))
            return rvec, tvec, corners
        """, """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            ok, rvec, tvec = cv2.solvePnP(objp, corners, K, None)
            return rvec, tvec, corners
        """),
    "lab10 dist to undistort": (lab10.DIST_TO_UNDISTORT_HINT, "undistort_image", """
        def undistort_image(image, K, dist):
            return cv2.undistort(image, K, np.zeros(5))
        """, """
        def undistort_image(image, K, dist):
            return cv2.undistort(image, K, None)
        """),
    "lab10 K transposed in undistort": (G["K is transposed (cv2.undistort wants K as given)"], "undistort_image", """
        def undistort_image(image, K, dist):
            mapx, mapy = _own_maps(image.shape, K.T, dist)
            return cv2.remap(image, mapx, mapy, cv2.INTER_LINEAR)
        """, """
        def undistort_image(image, K, dist):
            return cv2.undistort(image, K.T, dist)
        """),
    "lab10 object points for (rows, cols)": (
        G["the object points are built for (rows, cols): np.mgrid[0:rows, 0:cols]"], "estimate_pose", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            ys, xs = np.indices(pattern_size)
            return xs, ys, None
        """, """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            cols, rows = pattern_size
            grid = np.mgrid[0:rows, 0:cols].T.reshape(-1, 2)
            return grid, None, None
        """),
    "lab10 the first frame": (G[lab10.FIRST_FRAME], "track_pose", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            first = frames[-1]
            return np.array([_pose(first) for frame in frames])
        """, """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            return np.array([_pose(frames[0]) for frame in frames])
        """),
    "lab10 pattern axes": (lab10.PATTERN_AXES_HINT, "estimate_pose", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            objp = np.mgrid[0:pattern_size[0], 0:pattern_size[1]].T.reshape(-1, 2)
            found, corners = cv2.findChessboardCorners(image, pattern_size[::-1])
            return objp, corners, None
        """, """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            objp = np.mgrid[0:pattern_size[1], 0:pattern_size[0]].T.reshape(-1, 2)
            return objp, None, None
        """),
    "lab10 projectPoints": (lab10.PROJECT_POINTS_HINT, "estimate_pose", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            out, _ = cv2.projectPoints(objp, tvec, rvec, K, dist)
            return rvec, tvec, out
        """, """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            return rvec, tvec, corners
        """),
    "lab11 V not transposed": (G[lab11.ESSENTIAL_MISTAKES["v_not_transposed"]], "essential_8point", """
        def essential_8point(pts1, pts2, K1, K2):
            U, s, V = np.linalg.svd(_fundamental(pts1, pts2, K1, K2))
            return U @ np.diag([1, 1, 0]) @ V
        """, """
        def essential_8point(pts1, pts2, K1, K2):
            U, s, Vt = np.linalg.svd(_fundamental(pts1, pts2, K1, K2))
            return U @ np.diag([1, 1, 0]) @ Vt.T
        """),
    "lab11 reshaped column by column": (G[lab11.FUNDAMENTAL_MISTAKES["column_order"]], "fundamental_8point", """
        def fundamental_8point(pts1, pts2):
            A = _design_transposed(pts1, pts2)
            F = np.linalg.svd(A)[2][-1].reshape(3, 3)
            return _rank2(F)
        """, """
        def fundamental_8point(pts1, pts2):
            A = _design(pts1, pts2)
            F = np.linalg.svd(A)[2][-1].reshape(3, 3, order="F")
            return _rank2(F)
        """),
    "lab11 lines scaled": (lab11.LINE_SCALE_HINT, "epipolar_lines", """
        def epipolar_lines(F, pts1):
            lines = _homogeneous(pts1) @ F.T
            scaled = lines / np.hypot(lines[:, 0], lines[:, 1])[:, None]
            return lines
        """, """
        def epipolar_lines(F, pts1):
            return _homogeneous(pts1) @ F.T
        """),
    "lab11 essential values": (lab11.ESSENTIAL_VALUES_HINT, "essential_8point", """
        def essential_8point(pts1, pts2, K1, K2):
            U, s, Vt = np.linalg.svd(_fundamental(pts1, pts2, K1, K2))
            E = U @ np.diag([1, 1, 0]) @ Vt
            return U @ np.diag([s[0], s[1], 0]) @ Vt
        """, """
        def essential_8point(pts1, pts2, K1, K2):
            U, s, Vt = np.linalg.svd(_fundamental(pts1, pts2, K1, K2))
            return U @ np.diag([s[0], s[1], 0]) @ Vt
        """),
    "lab11 divided by F[2, 2]": (lab11.DIVIDED_BY_F22_HINT, "fundamental_8point", """
        def fundamental_8point(pts1, pts2):
            F = _eight_point(pts1, pts2)
            return F / F.ravel()[np.argmax(np.abs(F))] / 0.0
        """, """
        def fundamental_8point(pts1, pts2):
            F = _eight_point(pts1, pts2)
            return F / F[2, 2]
        """),
    "lab11 fixed F[2, 2]": (lab11.FIXED_F22_HINT, "fundamental_8point", """
        def fundamental_8point(pts1, pts2):
            A = _design(pts1, pts2)[:, :8]
            return np.append(np.linalg.svd(A)[2][-1], 1.0).reshape(3, 3)
        """, """
        def fundamental_8point(pts1, pts2):
            A = _design(pts1, pts2)
            f = np.linalg.lstsq(A[:, :8], -A[:, 8], rcond=None)[0]
            U, s, Vt = np.linalg.svd(np.append(f, 1.0).reshape(3, 3))
            return U @ np.diag([s[0], s[1], 0.0]) @ Vt
        """),
    "lab11 rank 2": (lab11.RANK2_HINT, "fundamental_8point", """
        def fundamental_8point(pts1, pts2):
            U, S, Vt = np.linalg.svd(_eight_point(pts1, pts2))
            S[2] = 0
            return _eight_point(pts1, pts2)
        """, """
        def fundamental_8point(pts1, pts2):
            return _eight_point(pts1, pts2)
        """),
    "lab11 epipole not finite": (lab11.EPIPOLE_NOT_FINITE_HINT, "epipoles", """
        def epipoles(F):
            e1 = np.linalg.svd(F)[2][-1]
            e2 = np.linalg.svd(F.T)[2][-1]
            return np.log(e1 - e1), e2
        """, """
        def epipoles(F):
            e1 = np.linalg.svd(F)[2][-1]
            e2 = np.linalg.svd(F.T)[2][-1]
            return e1 / e1[2], e2 / e2[-1]
        """),
    "lab11 epipole divided": (lab11.EPIPOLE_DIVIDED_HINT, "epipoles", """
        def epipoles(F):
            e1 = np.linalg.svd(F)[2][-1]
            return e1 * 1e12, e1
        """, """
        def epipoles(F):
            e1 = np.linalg.svd(F)[2][-1]
            w = e1[2]
            return e1 / w, e1
        """),
    "lab11 recoverPose's pose": (lab11.RECOVER_POSE_HINT, "two_view_reconstruction", """
        def two_view_reconstruction(img1, img2, K):
            R, t = _best_of_four(E, pts1, pts2)
            return F, pts1, pts2, triangulate(P1, P2, pts1, pts2)
        """, """
        def two_view_reconstruction(img1, img2, K):
            _, R, t, _ = cv2.recoverPose(E, pts1, pts2, K)
            return F, pts1, pts2, triangulate(P1, P2, pts1, -pts2)
        """),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_student_whose_code_does_it_is_not_told_the_realistic_mistake_is(name):
    hint, function, does_it, mistake = CASES[name]
    assert hint.asks is not None
    assert not told(hint, does_it, function), f"{name}: told to do what the code does"
    assert told(hint, mistake, function), f"{name}: the mistake is no longer told"


def found(predicate, source: str, function: str = "f") -> str:
    return predicate.found(read_code(textwrap.dedent(source)).reachable([function]))


def test_divides_by_follows_a_name_holding_the_divisor():
    assert found(THIRD_COORDINATE, "def f(X):\n    w = X[:, 2:]\n    return X[:, :2] / w\n")
    assert found(THIRD_COORDINATE, "def f(X):\n    X /= X[-1]\n    return X\n")
    assert found(THIRD_COORDINATE, "def f(X):\n    return np.divide(X[:, :2], X[:, 2, None])\n")
    assert not found(THIRD_COORDINATE, "def f(X):\n    return X[:, :2] * X[:, 2:]\n")
    assert not found(divides_by("_[2, 2]"), "def f(K):\n    return K / K[1, 1]\n")


@pytest.mark.parametrize("source, negates", [
    ("def f(P):\n    if np.linalg.det(P[:, :3]) < 0:\n        P = -P\n    return P\n", True),
    ("def f(P):\n    if np.linalg.det(P[:, :3]) < 0:\n        P *= -1\n    return P\n", True),
    ("def f(P):\n    d = np.linalg.det(P[:, :3])\n    if d < 0:\n        P = -1 * P\n    return P\n", True),
    ("def f(P):\n    return P if np.linalg.det(P[:, :3]) > 0 else -P\n", True),
    ("def f(P):\n    return np.sign(np.linalg.det(P[:, :3])) * P\n", True),
    ("def f(P):\n    P = -P\n    return P\n", False),                                   # not on a determinant
    ("def f(P):\n    if np.linalg.det(P[:, :3]) < 0:\n        print(P)\n    return P\n", False),
])
def test_negates_on_a_negative_determinant(source, negates):
    assert bool(found(negates_on_negative_det(), source)) is negates


@pytest.mark.parametrize("source, negates", [
    ("def f(P):\n    P = np.asarray(P, float)\n    if np.linalg.det(P[:, :3]) < 0:\n        P = -P\n    return P\n", True),
    ("def f(P):\n    M = P.copy()\n    if np.linalg.det(M[:, :3]) < 0:\n        M *= -1\n    return M\n", True),
    ("def f(P):\n    P = -P if np.linalg.det(P[:, :3]) < 0 else P\n    return P\n", True),
    ("def f(P):\n    P = np.sign(np.linalg.det(P[:, :3])) * P\n    return P\n", True),
    ("def f(P):\n    K, R = rq(P[:, :3])\n    if np.linalg.det(P[:, :3]) < 0:\n        K = -K\n    return K\n", False),
    ("def f(P):\n    K = rq(P)\n    K = -K if np.linalg.det(P[:, :3]) < 0 else K\n    return K\n", False),
    ("def f(P):\n    P = -P\n    return P\n", False),
])
def test_negates_the_argument_on_a_negative_determinant(source, negates):
    # the sign fix's place: P itself (or a converted copy of it), not K or R
    assert bool(found(negates_on_negative_det(0), source)) is negates


def test_reshapes_reads_the_shape_and_the_order():
    assert found(reshapes(3, 3), "def f(v):\n    return v.reshape(3, 3)\n")
    assert found(reshapes(3, 3), "def f(v):\n    return np.reshape(v, (3, 3))\n")
    assert found(reshapes(3, 3, order="F"), "def f(v):\n    return v.reshape((3, 3), order='F')\n")
    assert found(reshapes(3, 3, order="F"), "def f(v):\n    return np.reshape(v, (3, 3), 'F')\n")
    assert not found(reshapes(3, 3), "def f(v):\n    return v.reshape(3, 3, order='F')\n")
    assert not found(reshapes(3, 3), "def f(v):\n    return v.reshape(3, 4)\n")


def test_an_argument_given_and_an_entry_zeroed():
    given = passes_argument("cv2.projectPoints", 4, "distCoeffs")
    assert found(given, "def f(o, r, t, K, d):\n    return cv2.projectPoints(o, r, t, K, d)\n")
    assert found(given, "def f(o, r, t, K, d):\n    return cv2.projectPoints(o, r, t, K, distCoeffs=d)\n")
    assert not found(given, "def f(o, r, t, K, d):\n    return cv2.projectPoints(o, r, t, K, None)\n")
    assert not found(given, "def f(o, r, t, K, d):\n    return cv2.projectPoints(o, r, t, K)\n")
    assert found(zeroes_an_entry(), "def f(s):\n    s[-1] = 0.0\n    return s\n")
    assert found(zeroes_an_entry(), "def f(s):\n    return np.diag([s[0], s[1], 0])\n")
    assert not found(zeroes_an_entry(), "def f(s):\n    s = 0\n    return np.diag(s)\n")
    assert found(zeroes_an_entry(), "def f(s):\n    S = np.diag(s)\n    S[2, 2] = 0\n    return S\n")
    # a row of F set to 0 has rank 2, and is not the nearest rank-2 matrix: no singular value is zeroed
    assert not found(zeroes_an_entry(), "def f(Fn):\n    Fn[2, :] = 0.0\n    return Fn\n")


def test_a_guard_replaces_its_sentence_only_where_the_code_does_it():
    text = claims.guard("claims test: divide by w", asks=THIRD_COORDINATE, instead="claims test: it divides")
    try:
        hint = claims.GUARDED[text]
        assert hint.neutral() == "claims test: it divides"
        with pytest.raises(ValueError):
            claims.guard(text, asks=negates_on_negative_det())
    finally:
        del claims.GUARDED[text]


# ------------------------------------------------------------------ graded: through the runner
def test_a_decomposition_negating_on_a_negative_determinant_is_not_told_to_negate(tmp_path):
    # the sign fix applied to K instead of P: K comes out with a negative diagonal
    source = """
        _reference = decompose_camera_matrix
        def decompose_camera_matrix(P):
            K, R, t = _reference(P)
            if np.linalg.det(np.asarray(P, float)[:, :3]) < 0:
                K = -K
            return K, R, t
        """
    result = grade(mutant(tmp_path, "lab10_camera2", source), ["lab10.ex5"], pictures="none")
    messages = [c.message for c in check_results(result, "lab10.ex5") if not c.passed]
    assert any("det(P[:, :3]) < 0" in m for m in messages)
    assert not any("multiply P by -1 first" in m for m in messages)
    assert any("your code already negates a matrix when a determinant is negative" in m for m in messages)
    labels = [c.mistake or "" for c in check_results(result, "lab10.ex5") if not c.passed]
    assert not any("negated" in label and "det" in label for label in labels), labels


def test_a_decomposition_negating_p_but_leaving_rqs_signs_is_told_the_signs_not_the_negation(tmp_path):
    # P negated where det(P[:, :3]) < 0 as the sheet's recipe does, K's and R's signs never fixed:
    # the cause is RQ's sign ambiguity, not a missing negation (a fresh blind set's evaluator)
    source = """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            if np.linalg.det(P[:, :3]) < 0:
                P = -P
            flip = np.eye(3)[::-1]
            Q, U = np.linalg.qr((flip @ P[:, :3]).T)
            K, R = flip @ U.T @ flip, flip @ Q.T
            t = np.linalg.solve(K, P[:, 3])
            return K / K[2, 2], R, t
        """
    result = grade(mutant(tmp_path, "lab10_camera2", source), ["lab10.ex5"], pictures="none")
    failed = [c for c in check_results(result, "lab10.ex5") if not c.passed]
    messages = " ".join(c.message for c in failed)
    assert "RQ is unique only up to signs; multiply the offending columns of K and the same rows of R" in messages
    assert "multiply P by -1 first" not in messages
    assert "without the same rows of R" not in messages        # no column flip in this code
    labels = {c.mistake for c in failed if c.mistake}
    assert labels and all("negated" not in label for label in labels), labels
    assert "the signs of K's diagonal are not fixed" in labels


def test_a_transposed_design_matrix_reshaped_row_wise_is_not_told_it_reshaped_column_by_column(tmp_path):
    # issue 35's example: A built as kron(x1, x2), f reshaped row by row, gives the answer of
    # f reshaped column by column; the code shows the reshape is not the cause
    core = """
        def _eight_point_core(x1, x2):
            A = (x{a}[:, :, None] * x{b}[:, None, :]).reshape(len(x1), 9)
            return np.linalg.svd(A)[2][-1].reshape(3, 3{order})
        """
    result = grade(mutant(tmp_path, "lab11_two_view", core.format(a=1, b=2, order="")), ["lab11.ex4"],
                   pictures="none")
    messages = " ".join(c.message for c in check_results(result, "lab11.ex4") if not c.passed)
    # (the check's own reading of it, or -- where a change confirms where the values first go wrong -- the
    # helper's answer located as the transpose of the reference's: either way not the reshape)
    assert "the normalised F comes out transposed, as if f were reshaped column by column; your code reshapes f row by row" \
        in messages or "`_eight_point_core(" in messages and "gives the transpose of a value" in messages, messages
    assert "(order='F')" not in messages
    labels = [c.mistake or "" for c in check_results(result, "lab11.ex4") if not c.passed]
    assert not any("order='F'" in label for label in labels), labels   # instructors read labels too
    control = grade(mutant(tmp_path / "control", "lab11_two_view", core.format(a=2, b=1, order=', order="F"')),
                    ["lab11.ex4"], pictures="none")
    messages = " ".join(c.message for c in check_results(control, "lab11.ex4") if not c.passed)
    assert lab11.FUNDAMENTAL_MISTAKES["column_order"] in messages
    labels = [c.mistake or "" for c in check_results(control, "lab11.ex4") if not c.passed]
    assert any("order='F'" in label for label in labels), labels       # the true label is kept


def test_an_angle_in_degrees_from_code_that_converts_it_is_not_told_to_convert(tmp_path):
    source = """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            return cv2_free_rotation(angle_deg, center)
        def cv2_free_rotation(a, center):
            c, s = np.cos(a), np.sin(a)
            cx, cy = center
            return np.array([[c, s, (1 - c) * cx - s * cy], [-s, c, s * cx + (1 - c) * cy], [0, 0, 1.0]])
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex2"], pictures="none")
    messages = " ".join(c.message for c in check_results(result, "lab07.ex2") if not c.passed)
    assert "your code converts degrees to radians, but cos and sin are given the angle" in messages
    assert "convert degrees with np.deg2rad" not in messages


@pytest.mark.parametrize("source, compares", [
    # the reference's shape: the root is taken in a helper the comparison's value comes from
    ("def f(H, src, dst, threshold):\n    errors = _errors(H, src, dst)\n    return errors < threshold\n"
     "def _errors(H, src, dst):\n    d = apply(H, src) - dst\n    return np.sqrt((d ** 2).sum(axis=1))\n", True),
    ("def f(H, src, dst, threshold=3.0):\n    e = np.linalg.norm(apply(H, src) - dst, axis=1)\n"
     "    inliers = e <= threshold\n    return inliers\n", True),
    ("def f(p, q, thresh):\n    return np.hypot(*(p - q).T) < thresh\n", True),
    ("def f(p, q, threshold):\n    return ((p - q) ** 2).sum(axis=1) ** 0.5 < threshold\n", True),
    # squared distances compared, though the code takes a square root elsewhere (a normalisation)
    ("def f(H, src, dst, threshold):\n    scale = np.sqrt(2) / np.std(src)\n    d = apply(H, src) - dst\n"
     "    err = (d ** 2).sum(axis=1)\n    return err < threshold\n", False),
    ("def f(H, src, dst, threshold):\n    s = np.sqrt(2)\n    return ((apply(H, src) - dst) ** 2).sum(1) < threshold\n", False),
    # squared errors from a helper given a homography fitted on normalised (square-rooted) points
    ("def f(src, dst, threshold):\n    T = _norm(src)\n    H = fit(src) @ T\n    errors = _errors(H, src, dst)\n"
     "    return errors < threshold\n"
     "def _norm(p):\n    return np.sqrt(2) / p.std()\n"
     "def _errors(H, src, dst):\n    e = ((apply(H, src) - dst) ** 2).sum(axis=1)\n    return np.where(e > 0, e, 0)\n", False),
    # the same through a def inside the function (read by its returns, as a helper is), and its root
    ("def f(src, dst, threshold):\n    H = fit(src) @ _norm(src)\n    def errors(H):\n"
     "        return ((apply(H, src) - dst) ** 2).sum(axis=1)\n    return errors(H) < threshold\n"
     "def _norm(p):\n    return np.sqrt(2) / p.std()\n", False),
    ("def f(src, dst, threshold):\n    H = fit(src)\n    def errors(H):\n"
     "        return np.sqrt(((apply(H, src) - dst) ** 2).sum(axis=1))\n    return errors(H) < threshold\n", True),
])
def test_compares_a_distance_with_the_threshold_follows_the_compared_value(source, compares):
    from autograder.engine.claims import compares_a_distance_with
    assert bool(found(compares_a_distance_with(), source)) is compares


def test_compares_a_distance_with_follows_any_chain_of_names_each_once():
    # a square root ten names away is found (each name expanded once, not to a fixed depth), and
    # names that each read many others are not re-expanded per use (a wide web stays linear)
    from autograder.engine.claims import compares_a_distance_with
    chain = "".join(f"    e{i + 1} = e{i} * 1.0\n" for i in range(10))
    source = f"def f(d, threshold):\n    e0 = np.sqrt((d ** 2).sum(1))\n{chain}    return e10 < threshold\n"
    assert found(compares_a_distance_with(), source)
    web = "".join(f"    w{i} = " + " + ".join(f"w{j}" for j in range(i)) + " + d\n" if i else "    w0 = d * d\n"
                  for i in range(200))
    source = f"def f(d, threshold):\n{web}    return w199 < threshold\n"
    assert not found(compares_a_distance_with(), source)


def test_p1_and_p2_swapped_is_told_from_x_and_y_swapped_by_the_code():
    """The two give the same answer; x's line with p1 beside x's square is the coefficients' slip, x's
    line with y's square the coordinates'."""
    import ast
    import textwrap

    from autograder.engine.claims import EVIDENCED
    from autograder.labs import lab09  # noqa: F401  (registers the evidence)
    from fixtures.lab09 import P1_P2_SWAPPED

    def written(x_line: str):
        return ast.parse(textwrap.dedent(f"""
            def distort_points(pts, dist):
                k1, k2, p1, p2, k3 = dist
                x, y = pts[:, 0], pts[:, 1]
                r2 = x ** 2 + y ** 2
                {x_line}
                return x_t
        """)).body[0]

    does = EVIDENCED[P1_P2_SWAPPED]
    assert does.found([written("x_t = 2 * p2 * x * y + p1 * (r2 + 2 * x ** 2)")])
    assert not does.found([written("x_t = 2 * p1 * x * y + p2 * (r2 + 2 * y ** 2)")])   # (x and y swapped)
    assert not does.found([written("x_t = 2 * p1 * x * y + p2 * (r2 + 2 * x ** 2)")])   # (right)
