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
