"""Lab 10: the reference passes, the skeleton scores 0, usual mistakes are named."""

import numpy as np
import pytest

from autograder.engine.runner import grade
from autograder.labs.mistakes.lab10 import ADVICE, MISTAKES
from conftest import assert_advice_case, assert_advised, assert_all_not_implemented, assert_full_marks, assert_mistake_named, check_results, mutant

MODULE = "lab10_camera2"


@pytest.mark.parametrize("name", sorted(ADVICE))
@pytest.mark.xdist_group("lab10")
def test_convention_is_advice_not_points(name):
    assert_advice_case(MODULE, *ADVICE[name])


def test_reference_scores_full_marks(reference_result):
    assert_full_marks(reference_result, "lab10")


def test_skeleton_scores_zero_with_not_implemented(skeleton_result):
    assert_all_not_implemented(skeleton_result, "lab10")


@pytest.mark.parametrize("name", sorted(MISTAKES))
@pytest.mark.xdist_group("lab10")
def test_mistake_is_diagnosed(name):
    assert_mistake_named(MODULE, *MISTAKES[name])


def test_projection_by_the_formula_alone_gets_full_marks_and_a_tip(tmp_path):
    """Finite pixels behind the camera (the lab sheet's formula, cv2.projectPoints) lose no
    points: NaN there is advice."""
    result = grade(mutant(tmp_path, MODULE, """
        def perspective_project(points, f):
            X, single = _points(points)
            x = f * X[:, :2] / X[:, 2:3]
            return x[0] if single else x
        """), ["lab10.ex1"])
    [exercise] = result.exercises
    assert exercise.score == exercise.max_score
    assert_advised(result, "lab10.ex1", "behind the camera", "nan")


def test_infinite_values_on_the_camera_plane_get_the_same_tip(tmp_path):
    """NaN only for Z < 0 (`Z < 0` where `Z <= 0` is meant): the point at Z = 0 comes out infinite;
    full marks, and the tip names the row on the camera plane."""
    result = grade(mutant(tmp_path, MODULE, """
        def perspective_project(points, f):
            X, single = _points(points)
            with np.errstate(divide="ignore", invalid="ignore"):
                x = f * X[:, :2] / X[:, 2:3]
            x[X[:, 2] < 0] = np.nan
            return x[0] if single else x
        """), ["lab10.ex1"])
    [exercise] = result.exercises
    assert exercise.score == exercise.max_score
    assert_advised(result, "lab10.ex1", "infinite values", "camera plane", "nan")


def test_a_dolly_that_projects_points_moved_behind_the_camera_gets_a_tip(tmp_path):
    """The formula written inline in dolly_zoom (no NaN where the move puts a point behind the camera: the
    advice table's case): full marks, and the dolly's own tip names the frame and the row."""
    _, source, _ = ADVICE["dolly_zoom projecting points moved behind the camera"]
    result = grade(mutant(tmp_path, MODULE, source), ["lab10.ext2"])
    [exercise] = result.exercises
    assert exercise.score == exercise.max_score
    assert_advised(result, "lab10.ext2", "frame at d = 2", "rows [1]", "nan")


def test_decomposition_remedy_fits_the_input(tmp_path):
    """With det(P[:, :3]) > 0 a negative diagonal of K is fixed by flipping signs, and the
    message says so (not 'negate P', which would be wrong for that input)."""
    from autograder.engine.checks import Fail
    from autograder.labs import lab10

    class Probe:
        def __init__(self, answer):
            self.answer = answer

        def call(self, *args):
            return self.answer

        def fail(self, message, hint="", mistake=""):
            raise Fail(message, hint)

        def expect_array(self, value, what, **kwargs):
            return np.asarray(value, dtype=float)

    from fixtures import lab10 as truth
    for seed in range(20):
        P, K, R, tv, s = truth.random_camera_matrix(seed)
        if s > 0:
            break
    flip = np.diag([-1.0, 1.0, 1.0])
    with pytest.raises(Fail) as failure:
        lab10.judge_decomposition(Probe((K @ flip, flip @ R, tv)), P, K, R, tv)
    assert "negative diagonal" in failure.value.message
    assert "multiply p by -1" not in failure.value.message.lower()
    assert "flip" in failure.value.message.lower() or "multiply the offending" in failure.value.message


# Textbook variants of the estimators: full marks.
VARIANTS = {
    "undistortion by initUndistortRectifyMap and remap (fixed-point CV_16SC2 maps)": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K, dist = np.asarray(K, float), np.asarray(dist, float)
            h, w = image.shape[:2]
            map1, map2 = cv2.initUndistortRectifyMap(K, dist, None, K, (w, h), cv2.CV_16SC2)
            return cv2.remap(image, map1, map2, cv2.INTER_LINEAR)
        """),
    "undistortion by cv.undistort given K as the new camera matrix": ("lab10.ext1", """
        import cv2 as cv
        def undistort_image(image, K, dist):
            K = np.asarray(K, float)
            return cv.undistort(image, K, np.asarray(dist, float), None, newCameraMatrix=K)
        """),
    "undistortion with float32 K and dist, nearest-neighbour remap": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K, dist = np.float32(K), np.float32(dist)
            h, w = image.shape[:2]
            map1, map2 = cv2.initUndistortRectifyMap(K, dist, None, K, (w, h), cv2.CV_32FC1)
            return cv2.remap(image, map1, map2, cv2.INTER_NEAREST)
        """),
    "undistortion by an own map of the full model (k1, k2, p1, p2, k3)": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K = np.asarray(K, np.float64)
            k1, k2, p1, p2, k3 = np.ravel(dist)[:5]
            h, w = image.shape[:2]
            ys, xs = np.mgrid[0:h, 0:w].astype(np.float64)
            x, y = (xs - K[0, 2]) / K[0, 0], (ys - K[1, 2]) / K[1, 1]
            r2 = x * x + y * y
            radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
            xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
            yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
            return cv2.remap(image, (xd * K[0, 0] + K[0, 2]).astype(np.float32),
                             (yd * K[1, 1] + K[1, 2]).astype(np.float32), cv2.INTER_CUBIC)
        """),
    "tracking by undistorting each frame first, then the pose without dist": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            K = np.asarray(K, np.float64)
            rows = []
            for frame in frames:
                if dist is not None:
                    frame = cv2.undistort(frame, K, np.asarray(dist, np.float64))
                rows.append(np.concatenate(estimate_pose(frame, pattern_size, square_size, K)[:2]))
            return np.array(rows, dtype=np.float64).reshape(-1, 6)
        """),
    "DLT on raw coordinates (the lab sheet does not ask for normalisation)": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            rows = []
            for Xi, (u, v) in zip(np.column_stack([points3d, np.ones(len(points3d))]), points2d):
                rows.append(np.concatenate([Xi, np.zeros(4), -u * Xi]))
                rows.append(np.concatenate([np.zeros(4), Xi, -v * Xi]))
            return np.linalg.svd(np.array(rows))[2][-1].reshape(3, 4)
        """),
    "decomposition with cv2.decomposeProjectionMatrix": ("lab10.ex5", """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            if np.linalg.det(P[:, :3]) < 0:
                P = -P
            K, R, C = cv2.decomposeProjectionMatrix(P)[:3]
            C = C[:3, 0] / C[3, 0]
            return K / K[2, 2], R, -R @ C
        """),
    "decomposition by QR of M^-1 (the lab sheet's recipe)": ("lab10.ex5", """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            if np.linalg.det(P[:, :3]) < 0:
                P = -P
            M = P[:, :3]
            Q, U = np.linalg.qr(np.linalg.inv(M))
            K, R = np.linalg.inv(U), Q.T
            D = np.diag(np.sign(np.diag(K)))
            K, R = K @ D, D @ R
            return K / K[2, 2], R, -R @ (-np.linalg.inv(M) @ P[:, 3])
        """),
    "pose without sub-pixel corner refinement": ("lab10.ex6", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
            found, corners = cv2.findChessboardCorners(grey, tuple(pattern_size))
            if not found:
                return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))
            objp = _object_points(pattern_size, square_size)
            _, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)
            reprojected, _ = cv2.projectPoints(objp, rvec, tvec, K, dist)
            return rvec.ravel(), tvec.ravel(), reprojected.reshape(-1, 2)
        """),
}


def test_a_new_camera_matrix_loses_half_the_undistortion_check_and_nothing_else(tmp_path):
    """OpenCV's tutorial recipe undoes the lens rightly into cv2.getOptimalNewCameraMatrix's
    matrix: half of the undistortion check, named; the colour check (its own question) passes."""
    exercise, source, _ = MISTAKES["undistort into the tutorial's new camera matrix (alpha=1)"]
    checks = {c.name: c for c in check_results(grade(mutant(tmp_path, MODULE, source), [exercise]), exercise)}
    main = checks["undistort_image straightens views through two distorting lenses (the second with large "
                  "tangential terms p1, p2)"]
    assert main.score == pytest.approx(main.max_score / 2)
    assert main.mistake == "undistorted into a new camera matrix (cv2.getOptimalNewCameraMatrix), not K"
    assert checks["undistort_image keeps a colour image in colour (BGR in, BGR out)"].passed
    assert checks[OFF_CENTRE].passed, checks[OFF_CENTRE].message


OFF_CENTRE = "undistort_image keeps K's principal point off the image centre (and fx != fy)"
MAIN_UNDISTORTION = ("undistort_image straightens views through two distorting lenses (the second with large "
                     "tangential terms p1, p2)")


@pytest.mark.parametrize("new_matrix, told", [
    ("None", True),                                                 # OpenCV then centres the principal point
    ("cv2.getDefaultNewCameraMatrix(K, (w, h), True)", False),     # a new matrix is given: not told to give one
])
def test_a_recentred_principal_point_loses_the_off_centre_check(tmp_path, new_matrix, told):
    """The blind set's initUndistortRectifyMap without a new camera matrix: right where K's principal
    point is at the image centre (the first check's K), shifted elsewhere: named, confirmed on a
    second camera; the hint to pass K only to code that passes no new camera matrix."""
    source = f"""
        def undistort_image(image, K, dist):
            K = np.asarray(K, np.float64)
            h, w = image.shape[:2]
            maps = cv2.initUndistortRectifyMap(K, np.asarray(dist, np.float64), None, {new_matrix}, (w, h),
                                               cv2.CV_32FC1)
            return cv2.remap(image, *maps, cv2.INTER_LINEAR)
        """
    checks = {c.name: c for c in check_results(grade(mutant(tmp_path, MODULE, source), ["lab10.ext1"]), "lab10.ext1")}
    assert checks[MAIN_UNDISTORTION].passed
    off = checks[OFF_CENTRE]
    assert not off.passed and off.mistake.startswith("the principal point is moved to the image centre"), off.message
    assert "shifted by (-15.5, +9.5) px (on a second camera too)" in off.message
    assert ("pass K as newCameraMatrix" in off.message + off.hint) == told, off.message
    assert ("look at where your code puts the principal point" in off.message + off.hint) != told, off.message


@pytest.mark.parametrize("case", sorted(VARIANTS))
def test_correct_variants_keep_full_marks(tmp_path, case):
    exercise, source = VARIANTS[case]
    result = grade(mutant(tmp_path, MODULE, source), [exercise])
    [graded] = result.exercises
    assert graded.score == graded.max_score, [(c.name, c.message) for c in graded.checks if not c.passed]


def test_points_written_into_by_a_projection_lose_one_check_though_a_second_call_agrees(tmp_path):
    """Exercises 2 and 3 compare each projection of the points with the perspective one
    (inplace.shown_after): a weak perspective that sets the caller's depths to their mean (its own
    answer right, a second call the same) changes what the perspective projection gives; named."""
    result = grade(mutant(tmp_path, MODULE, """
        def weak_perspective_project(points, f, z_avg=None):
            X = np.asarray(points, dtype=np.float64)   # no copy for float points
            single = X.ndim == 1
            X = np.atleast_2d(X)
            X[:, 2] = X[:, 2].mean() if z_avg is None else float(z_avg)   # every point at one depth
            x = f / X[:, 2:3] * X[:, :2]
            return x[0] if single else x
        """), ["lab10.ex2"], pictures="none")
    failed = [c for c in check_results(result, "lab10.ex2") if not c.passed and not c.advice]
    assert len(failed) == 1, [c.name for c in failed]
    assert "writes into the caller's `points` in place" in failed[0].message, failed[0].message


def test_correspondences_left_out_are_told_only_when_all_the_others_fit_exactly():
    """The last of 6 correspondences missed by 40 px while the others fit to 1e-9 px: left out. Every point
    off a little (noise), or half of them missed, is no point left out."""
    from autograder.engine.checks import Fail
    from autograder.engine.judges import CORRESPONDENCES_LEFT_OUT, name_correspondences_left_out

    class Said:
        def fail(self, message, mistake=None):
            raise Fail(message, mistake=mistake)

    x = np.arange(12, dtype=float).reshape(6, 2)
    projected = x + 1e-10
    projected[5] += [40.0, 0.0]
    with pytest.raises(Fail) as told:
        name_correspondences_left_out(Said(), "dlt", np.linalg.norm(projected - x, axis=1), "P's 11 unknowns")
    assert told.value.mistake == CORRESPONDENCES_LEFT_OUT and "misses the last one (point 5" in told.value.message
    name_correspondences_left_out(Said(), "dlt", np.full(6, 0.3), "P")    # (noise everywhere: nothing said)
    name_correspondences_left_out(Said(), "dlt", np.array([5.0, 5.0, 5.0, 0, 0, 0]), "P")   # (half: nothing said)


def test_a_dolly_that_moves_the_wrong_points_is_not_told_of_nan_behind_the_camera(tmp_path):
    """The depth shift added to one point (a row) where every depth belongs: the points the tip would name
    are not the ones it projects -- and its projection already gives NaN behind the camera --, so the NaN tip,
    whose premise is a dolly right elsewhere, is not given; the graded checks name the row."""
    result = grade(mutant(tmp_path, MODULE, """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            focal_lengths = f0 * distances / z0
            frames = []
            for f, d in zip(focal_lengths, distances):
                moved = X.copy()
                moved[2] += d - z0
                frames.append(perspective_project(moved, f))
            return focal_lengths, np.stack(frames)
        """), ["lab10.ext2"])
    checks = check_results(result, "lab10.ext2")
    assert any(c.score < c.max_score for c in checks)
    assert not [c for c in checks if c.status == "advice" and "behind the camera" in c.message]


def test_corners_in_the_layout_cv2_project_points_returns_lose_a_quarter_named_and_a_right_pose_keeps_the_rest(tmp_path):
    """The API asks `reprojected` as (M, 2); cv2.projectPoints gives (M, 1, 2). A right pose with right corners in
    that layout keeps three quarters of each pose check, told the layout; the board-less case ((0, 2)) is unchanged."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, MODULE, ("return rvec.ravel(), tvec.ravel(), reprojected.reshape(-1, 2)",
                                                 "return rvec.ravel(), tvec.ravel(), reprojected"))
    results = check_results(grade(str(folder), ["lab10.ex6"]), "lab10.ex6")
    posed = [c for c in results if c.score < c.max_score]
    assert posed and all(c.score == pytest.approx(0.75 * c.max_score) for c in posed), [(c.name, c.score) for c in posed]
    assert all("(N, 1, 2) point layout" in c.message and "reshape it to (N, 2)" in c.message for c in posed)
    assert any("without a board" in c.name and c.passed for c in results)


def test_an_ignored_distortion_is_told_for_the_call_that_misses_it_only(tmp_path):
    """cv2.solvePnP given None where cv2.projectPoints already gets dist (07e lab10/06): "pass it to cv2.solvePnP
    (and to cv2.projectPoints)" asked for a call the code already makes rightly."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, MODULE, ("cv2.solvePnP(objp, corners, K, dist)", "cv2.solvePnP(objp, corners, K, None)"))
    failed = [c for c in check_results(grade(str(folder), ["lab10.ex6"]), "lab10.ex6") if c.score < c.max_score]
    ignored = [c for c in failed if "dist is ignored" in c.message]
    assert ignored and all("pass it to cv2.solvePnP too" in c.message and "cv2.projectPoints)" not in c.message
                           for c in ignored), [c.message for c in failed]
