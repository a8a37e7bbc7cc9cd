"""Lab 9: the reference passes, the skeleton scores 0, usual mistakes are named."""

import pytest

from autograder.labs.mistakes.lab09 import ADVICE, MISTAKES
from conftest import (assert_advice_case, assert_all_not_implemented, assert_full_marks, assert_mistake_named,
                      check_results, graded_case)

MODULE = "lab09_camera"


def test_reference_scores_full_marks(reference_result):
    assert_full_marks(reference_result, "lab09")


def test_skeleton_scores_zero_with_not_implemented(skeleton_result):
    assert_all_not_implemented(skeleton_result, "lab09")


@pytest.mark.parametrize("name", sorted(MISTAKES))
@pytest.mark.xdist_group("lab09")
def test_mistake_is_diagnosed(name):
    assert_mistake_named(MODULE, *MISTAKES[name])


@pytest.mark.parametrize("name", sorted(ADVICE))
@pytest.mark.xdist_group("lab09")
def test_convention_is_advice_not_points(name):
    assert_advice_case(MODULE, *ADVICE[name])


def test_the_pattern_given_to_find_the_corners_is_read_from_the_call():
    """`cv2.findChessboardCorners(grey, (rows, cols))` turns the board found by 90 degrees against object
    points laid out for (cols, rows): the calibration's checklist asks for it only where the call has it."""
    import ast as _ast
    from autograder.labs.lab09 import _corners_asked_cols_first

    def reads(call: str) -> bool:
        return _corners_asked_cols_first(_ast.parse(f"def calibrate(images, pattern_size, s):\n    {call}").body[0])

    assert not reads("found, c = cv2.findChessboardCorners(grey, (rows, cols))")
    assert not reads("found, c = cv2.findChessboardCorners(grey, (pattern_size[1], pattern_size[0]))")
    assert reads("found, c = cv2.findChessboardCorners(grey, pattern_size)")
    assert reads("found, c = cv2.findChessboardCorners(grey, (cols, rows), None)")
    assert reads("found, c = cv2.findChessboardCornersSB(grey, patternSize=(nx, ny))")


def test_outlined_markers_drawn_without_cv2_circle_are_not_told_to_pass_thickness_minus_1(tmp_path):
    """cv2.drawMarker's squares are outlines too, and refuse thickness=-1: the code is told it does not
    call cv2.circle, which fills; cv2.circle drawn with thickness 1 is told thickness=-1."""
    from autograder.engine.runner import grade
    from conftest import mutant

    source = """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.drawMarker(out, (int(round(x)), int(round(y))), tuple(int(c) for c in color),
                                   cv2.MARKER_SQUARE, 2 * int(radius) + 1, 1)
            return out
        """
    result = grade(mutant(tmp_path, "lab09_camera", source), ["lab09.ex5"], pictures="none", include_hidden=False)
    messages = [c.message for e in result.exercises for c in e.checks if not c.passed]
    assert any("does not call cv2.circle" in m for m in messages), messages
    assert not any("should be filled (thickness=-1)" in m for m in messages), messages


def test_lens_distortion_through_cv2_project_points_scores_full_marks(tmp_path):
    """The sheet asks to simulate lens distortion, not to write the model by hand: cv2.projectPoints
    of (x, y, 1) with a zero pose and K = I is the same model, and loses nothing."""
    from autograder.engine.runner import grade
    from conftest import mutant

    source = """
        def distort_points(points, dist):
            pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
            rays = np.hstack([pts, np.ones((len(pts), 1))])
            image, _ = cv2.projectPoints(rays, np.zeros(3), np.zeros(3), np.eye(3),
                                         np.asarray(dist, dtype=np.float64))
            return image.reshape(-1, 2)
        """
    result = grade(mutant(tmp_path, "lab09_camera", source), ["lab09.ext2"], pictures="none")
    failed = [(c.name, c.message) for e in result.exercises for c in e.checks if not c.passed]
    assert not failed, failed
    assert result.total == result.max_total > 0


def test_rays_crowding_a_blur_disc_of_another_size_are_not_told_to_take_the_root_they_take():
    """The radius drawn as aperture * sqrt(u), scaled by a blur radius from the distance |X|: the share of the
    rays within half the expected radius is off, and the advice says so without the recipe the code follows."""
    exercise, source, _ = MISTAKES["simulate_aperture scaling the blur by the points' distance, not their depth"]
    result = graded_case(MODULE, exercise, source)
    [advice] = [c for c in check_results(result, exercise) if c.name.startswith("simulate_aperture fills the pinhole")]
    assert "of the rays land within half the blur radius" in advice.message, advice.message
    assert "sqrt(u)" not in advice.message and "do not all reach its blur radius" in advice.message, advice.message


def test_rows_of_another_width_are_not_told_as_points_taken_for_one(tmp_path):
    """r^2 kept as an (N, 1) column beside 1-D x and y (the blind set 1206a's 09/03): the answer is (N, 2N) for any
    N, so two points give two rows of another width -- not two points taken for one (no length test in the code),
    and a one-row array's (1, 2) is not told to be (1, 12)."""
    from autograder.engine.conventions import SQUARE_TAKEN
    from autograder.engine.runner import grade
    from conftest import check_results, edited_reference

    folder = edited_reference(tmp_path, "lab09_camera", *_KEEPDIMS)
    result = grade(folder, ["lab09.ext2"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab09.ext2") if not c.passed]
    assert failed and not any(c.mistake == SQUARE_TAKEN for c in failed), [(c.name, c.mistake) for c in failed]
    assert not any("expected (1, " in c.message for c in failed), [c.message for c in failed]


def test_a_seeded_call_is_said_to_keep_rays_in_only_where_it_does(tmp_path):
    """x and y offsets mixed across rays by a reshape (the blind set 1206a's 09/02): seeded or not, rays fall
    outside the blur disc, so the unseeded call's failure does not say a seeded one keeps them in."""
    from autograder.engine.runner import grade
    from conftest import check_results, mutant

    source = """
        def simulate_aperture(points, f, aperture, n_rays=50, seed=None):
            X = np.asarray(points, dtype=np.float64).reshape(-1, 3)
            rng = np.random.default_rng(seed)
            radius = aperture * np.sqrt(rng.uniform(0.0, 1.0, (len(X), n_rays)))
            angle = rng.uniform(0.0, 2.0 * np.pi, (len(X), n_rays))
            ax, ay = radius * np.cos(angle), radius * np.sin(angle)
            offsets = np.stack([ax, ay]).reshape(len(X), n_rays, 2)
            ideal = f * X[:, :2] / X[:, 2:3]
            return ideal[:, None, :] + offsets * (1.0 + f / X[:, 2])[:, None, None]
        """
    result = grade(mutant(tmp_path, "lab09_camera", source), ["lab09.ex4"], pictures="none", include_hidden=False)
    [seeded] = [c for c in check_results(result, "lab09.ex4") if c.name.startswith("simulate_aperture is reproducible")]
    assert not seeded.passed and "keeps them in" not in seeded.message, seeded.message


_KEEPDIMS = (("    r2 = x * x + y * y\n", "    r2 = np.sum(pts ** 2, axis=1, keepdims=True)\n"),)


@pytest.mark.parametrize("body, told", [
    # (raises for the points behind only: the note on Z <= 0 is the cause)
    ("    if np.any(X[:, 2] <= 0):\n        raise ValueError('point behind the camera')\n"
     "    return f * X[:, :2] / X[:, 2:3]", True),
    # (raises for every call of three points or more -- 06k 10/01's broadcast: the points behind are not its cause)
    ("    return f * X[:, :2] / X[:, 2]", False),
])
def test_the_points_behind_are_told_as_the_cause_of_a_raise_only_where_they_are(tmp_path, body, told):
    source = "def pinhole_project(points, f):\n    X = np.atleast_2d(np.asarray(points, dtype=np.float64))\n" + body + "\n"
    from autograder.engine.runner import grade
    from conftest import mutant

    result = grade(mutant(tmp_path, "lab09_camera", source), ["lab09.ex1"], pictures="none", include_hidden=False)
    behind = [c for c in check_results(result, "lab09.ex1") if "behind" in c.name and c.score < c.max_score]
    assert behind, [c.name for c in check_results(result, "lab09.ex1")]
    assert ("the projection must not raise for them" in behind[0].message) is told, behind[0].message


def test_an_order_of_the_object_points_is_told_only_where_it_gives_the_student_s_rms(tmp_path, no_naming):
    """With nothing to overrule it (no repair runs: a grading whose naming time is spent), the calibration's
    error is told as the object points' order only where points laid out in that order give the student's rms
    on the views: a grid built for (rows, cols) is; a row coordinate left unscaled (2.6 px where the orders give
    42) is not told an order."""
    import textwrap

    from autograder.labs.lab09 import OBJECT_POINTS_ORDER
    from autograder.labs.mistakes.lab09 import MISTAKES

    def calibration_checks(name):
        exercise, source, _ = MISTAKES[name]
        # (a source of its own: the table's own grading, with naming, is kept per process)
        result = graded_case(MODULE, exercise, textwrap.dedent(source) + "\n# (naming off)\n")
        return [c for c in check_results(result, exercise) if c.lost_points and "reprojection error" in c.message]

    unscaled = calibration_checks("calibrate scaling one coordinate of the object points only")
    assert unscaled and not any(c.mistake == OBJECT_POINTS_ORDER or "wrong order" in c.message for c in unscaled)
    rows_first = calibration_checks("calibration grid built as (rows, cols)")
    assert rows_first and all(c.mistake == OBJECT_POINTS_ORDER for c in rows_first)
    assert "for the pattern read as (rows, cols)" in rows_first[0].message


def test_circles_drawn_at_y_x_are_told_so_by_the_check_of_points_just_off_the_image():
    """Its point in view lies on the diagonal, where (y, x) is (x, y): circles drawn at (y, x) miss only the
    points just off the image, which were told "not drawn", as if left out (06l 09/04)."""
    from autograder.labs.lab09 import XY_SWAPPED
    from autograder.labs.mistakes.lab09 import MISTAKES

    exercise, source, _ = MISTAKES["circles at (y, x)"]
    [off] = [c for c in check_results(graded_case(MODULE, exercise, source), exercise)
             if c.name.startswith("draw_points draws the part in view of a circle centred just off the image")]
    assert off.lost_points and off.mistake == XY_SWAPPED and "drawn at (y, x)" in off.message, off.message
    assert "is not drawn" not in off.message


def test_a_camera_matrix_at_another_scale_and_sign_keeps_full_marks():
    """P is a projective quantity: the API accepts any non-zero scale of it, sign included (the blind legitimate
    set 1206n's v3 returned K [R | t] scaled to unit norm and negated, and lost 3 points)."""
    result = graded_case(MODULE, "lab09.ex3", """
        _camera_matrix = camera_matrix
        def camera_matrix(K, R, t):
            P = _camera_matrix(K, R, t)
            return -P / np.linalg.norm(P)
        """)
    [exercise] = [e for e in result.exercises if e.id == "lab09.ex3"]
    assert exercise.score == exercise.max_score, [c.message for c in exercise.checks if c.score < c.max_score]
