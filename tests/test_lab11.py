"""Lab 11: the reference passes, the skeleton scores 0, usual mistakes are named."""

import numpy as np
import pytest

from autograder.engine.runner import grade
from autograder.labs.mistakes.lab11 import MISTAKES
from conftest import (THREE_ROW_TRIANGULATION, assert_all_not_implemented, assert_full_marks,
                      assert_mistake_named, check_results, graded_case, mutant)
from fixtures import lab11 as truth

MODULE = "lab11_two_view"


def test_reference_scores_full_marks(reference_result):
    assert_full_marks(reference_result, "lab11")


def test_skeleton_scores_zero_with_not_implemented(skeleton_result):
    assert_all_not_implemented(skeleton_result, "lab11")


@pytest.mark.parametrize("case", sorted(MISTAKES))
@pytest.mark.xdist_group("lab11")
def test_mistake_is_caught_and_named(case):
    assert_mistake_named(MODULE, *MISTAKES[case])


# Correct variants the lab sheet or the API allows: full marks (and, where stated, a tip).
VARIANTS = {
    "triangulation with all three rows of x × (P X) = 0, rows not scaled": ("lab11.ex1", THREE_ROW_TRIANGULATION),
    "triangulation with two rows per view, each scaled to unit norm": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            pts1 = np.atleast_2d(np.asarray(pts1, float)); pts2 = np.atleast_2d(np.asarray(pts2, float))
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[1]], axis=1)
            A /= np.linalg.norm(A, axis=2, keepdims=True)
            h = np.linalg.svd(A)[2][:, -1]
            return h[:, :3] / h[:, 3:]
        """),
    "draw_epipolar_lines with anti-aliased grey lines (level 200) on a grey input": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = np.array(image, np.uint8, copy=True)
            h, w = canvas.shape[:2]
            colour = 200 if canvas.ndim == 2 else (0, 200, 0)
            for a, b, c in np.asarray(lines, float):
                if abs(b) >= abs(a):
                    p, q = (0, int(round(-c / b))), (w - 1, int(round(-(c + a * (w - 1)) / b)))
                else:
                    p, q = (int(round(-c / a)), 0), (int(round(-(c + b * (h - 1)) / a)), h - 1)
                cv2.line(canvas, p, q, colour, 1, cv2.LINE_AA)
            return canvas
        """),
    "draw_epipolar_lines on image.copy(), far end points clipped by cv2.clipLine": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            out = image.copy()
            h, w = out.shape[:2]
            for a, b, c in np.asarray(lines, float):
                point = -c * np.array([a, b]) / (a * a + b * b)         # the line's point nearest the origin
                far = 4 * (w + h) * np.array([-b, a]) / np.hypot(a, b)  # along the line, beyond the image
                p, q = (tuple(int(round(v)) for v in point + s * far) for s in (-1, 1))
                inside, p, q = cv2.clipLine((0, 0, w, h), p, q)
                if inside:
                    cv2.line(out, p, q, 255 if out.ndim == 2 else (0, 255, 255), 1)
            return out
        """),
    "draw_epipolar_lines branching on |b| >= |a|, no clipping (cv2.line clips)": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            out = np.array(image, np.uint8, copy=True)
            h, w = out.shape[:2]
            for a, b, c in np.asarray(lines, float):
                if abs(b) >= abs(a):
                    p, q = (0, int(round(-c / b))), (w - 1, int(round(-(c + a * (w - 1)) / b)))
                else:
                    p, q = (int(round(-c / a)), 0), (int(round(-(c + b * (h - 1)) / a)), h - 1)
                cv2.line(out, p, q, 255 if out.ndim == 2 else (0, 0, 255), 1)
            return out
        """),
    "epipoles by scipy.linalg.null_space": ("lab11.ex5", """
        import scipy.linalg
        def epipoles(F):
            F = np.asarray(F, float)
            return scipy.linalg.null_space(F)[:, 0], scipy.linalg.null_space(F.T)[:, 0]
        """),
    "epipoles as eigenvectors of F^T F and F F^T (smallest eigenvalue)": ("lab11.ex5", """
        def epipoles(F):
            F = np.asarray(F, float)
            return np.linalg.eigh(F.T @ F)[1][:, 0], np.linalg.eigh(F @ F.T)[1][:, 0]
        """),
    "epipoles as the longest cross product of two rows (columns) of F": ("lab11.ex5", """
        def _null_by_cross(M):
            pairs = [np.cross(M[i], M[j]) for i, j in ((0, 1), (0, 2), (1, 2))]
            e = max(pairs, key=np.linalg.norm)
            return e / np.linalg.norm(e)
        def epipoles(F):
            F = np.asarray(F, float)
            return _null_by_cross(F), _null_by_cross(F.T)
        """),
    "the lab sheet's 8-point on raw pixel coordinates (no normalisation asked)": ("lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            F = _eight_point_core(_homogeneous(pts1), _homogeneous(pts2))
            U, s, Vt = np.linalg.svd(F)
            return U @ np.diag([s[0], s[1], 0.0]) @ Vt
        """),
    "normalised 8-point with rank 2 enforced after denormalising": ("lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            T1, T2 = _hartley_normalisation(pts1), _hartley_normalisation(pts2)
            Fn = _eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T)
            U, s, Vt = np.linalg.svd(T2.T @ Fn @ T1)
            return U @ np.diag([s[0], s[1], 0.0]) @ Vt
        """),
    "fundamental_8point scaled so that its largest entry is 1": ("lab11.ex4", """
        _fundamental = fundamental_8point
        def fundamental_8point(pts1, pts2):
            F = _fundamental(pts1, pts2)
            return F / np.abs(F).max()
        """),
}


@pytest.mark.parametrize("case", sorted(VARIANTS))
def test_correct_variants_keep_full_marks(tmp_path, case):
    exercise, source = VARIANTS[case]
    result = grade(mutant(tmp_path, MODULE, source), [exercise])
    for check in check_results(result, exercise):
        assert check.passed or check.advice, f"{check.name}: {check.message}"


def test_bgr_for_a_grey_input_loses_half_the_grey_check_only(tmp_path):
    """OpenCV's tutorial draws on cv2.cvtColor(grey, COLOR_GRAY2BGR): the lines are right, the
    channel count is not the API's (grey in, grey out). Half of the grey-input check, named; every
    other check (BGR inputs, the photo, the vertical line) keeps its points."""
    exercise, source, _ = MISTAKES["draw_epipolar_lines returning BGR for a grey input (the tutorial's way)"]
    checks = {c.name: c for c in check_results(grade(mutant(tmp_path, MODULE, source), [exercise]), exercise)}
    grey = checks["draw_epipolar_lines draws across the whole image of a grey input"]
    assert grey.score == pytest.approx(grey.max_score / 2) and grey.mistake == "the channels are not kept"
    assert "grey in, grey out" in grey.message and "draws the lines rightly" in grey.message
    assert all(c.passed for name, c in checks.items() if name != grey.name and c.max_score > 0)


def test_drawing_on_the_callers_image_loses_the_twice_check_only(tmp_path):
    """Drawing on np.asarray(image) returns the right picture on a fresh image (every other check);
    drawn twice on the same image, the second picture shows both sets of lines: that check's
    point, named, with the copy hint held to the code (it copies nothing)."""
    exercise, source, _ = MISTAKES["draw_epipolar_lines drawing on the caller's image"]
    checks = {c.name: c for c in check_results(grade(mutant(tmp_path, MODULE, source), [exercise]), exercise)}
    twice = checks["draw_epipolar_lines twice on the same image: each drawing shows its own lines only"]
    assert not twice.passed and twice.mistake == "draw_epipolar_lines draws on the caller's image"
    assert "the second drawing shows the first one's lines too" in twice.message
    assert "out = image.copy()" in twice.hint
    assert all(c.passed for name, c in checks.items() if name != twice.name and c.max_score > 0)


def test_stored_figures_are_current():
    """fixtures/data/lab11_figures.json matches the algorithms."""
    import importlib.util

    import numpy as np

    from autograder.engine.compare import projective_distance
    from conftest import ROOT
    from fixtures import lab11

    spec = importlib.util.spec_from_file_location("make_lab11_figures", ROOT / "fixtures" / "make_lab11_figures.py")
    make = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make)
    fresh, stored = make.compute(), lab11.figures()

    def compare(a, b, where):
        if isinstance(a, dict):
            assert set(a) == set(b), where
            for key in a:
                compare(a[key], b[key], f"{where}.{key}")
        elif np.shape(a) == (3, 3) and ".sideways." in where and "_zeroed" in where:
            # Sideways motion gives an F whose two non-zero singular values are equal, so
            # zeroing "the largest" or "the middle" one leaves any rank-1 matrix of that plane:
            # which one depends on the LAPACK build and CPU. Only its rank is defined.
            for m in (a, b):
                values = np.linalg.svd(np.asarray(m, float), compute_uv=False)
                assert values[1] < 1e-9 * values[0], where
        elif np.shape(a) == (3, 3) and ".sheet_row" in where:
            # The lab sheet's row as printed has y' twice: A has two equal columns, so its null space is a
            # plane and the SVD returns any vector of it (which one depends on the LAPACK build and CPU): no
            # value to compare, only a finite answer (the grader reads that row in the student's code instead).
            for m in (a, b):
                assert np.all(np.isfinite(np.asarray(m, float))), where
        elif np.shape(a) == (3, 3):
            # E and F are projective: an SVD may return either sign (LAPACK builds differ),
            # so they are compared as the grader compares them, up to scale and sign.
            assert projective_distance(a, b) < 1e-6, where
        else:
            assert np.allclose(np.asarray(a, float), np.asarray(b, float), rtol=1e-6, atol=1e-9), where

    compare(fresh, stored, "figures")


@pytest.mark.xdist_group("lab11")
def test_lines_scaled_by_another_norm_are_not_told_the_unit_length_mistake():
    """Lines divided by the norm of (b, c) differ from lines of unit length over (a, b, c) by about
    a^2 / c^2 only: that mistake's name is not said to this code (it is not what it does)."""
    result = graded_case(MODULE, "lab11.ex2", """
        def epipolar_lines(F, pts1):
            lines = _homogeneous(pts1) @ np.asarray(F, float).T
            return lines / np.linalg.norm(lines[:, 1:], axis=1, keepdims=True)
        """)
    failed = [c.message for c in check_results(result, "lab11.ex2") if not c.passed]
    assert failed and not any("all three entries" in m for m in failed), failed


def test_a_line_drawn_in_a_random_colour_is_the_same_line_with_the_other_sign(tmp_path):
    """OpenCV's tutorial draws each line in a colour drawn at random: on the sign check's black grey image a
    line may come out dark, and each call draws other colours; the relation judges where, not how bright."""
    submission = mutant(tmp_path, "lab11_two_view", """
        def draw_epipolar_lines(image, lines):
            out = image.copy()
            w = out.shape[1]
            for a, b, c in np.asarray(lines, float):
                colour = tuple(np.random.randint(0, 255, 3).tolist())
                if abs(b) < 1e-9:   # (the tutorial divides by b: a vertical line drawn across the rows)
                    x = int(round(-c / a))
                    cv2.line(out, (x, 0), (x, out.shape[0] - 1), colour, 1)
                    continue
                x0, y0 = map(int, [0, -c / b])
                x1, y1 = map(int, [w, -(c + a * w) / b])
                cv2.line(out, (x0, y0), (x1, y1), colour, 1)
            return out
        """)
    checks = {c.name: c for e in grade(submission, ["lab11.ex2"]).exercises for c in e.checks}
    sign = checks["draw_epipolar_lines draws a line given with the other sign, (-a, -b, -c), as the same line"]
    assert sign.score == sign.max_score, sign.message


def test_complex_values_that_are_not_real_are_not_told_to_keep_their_real_part(tmp_path):
    """An eigenvector of a complex eigenvalue returned (the smallest-magnitude one is not taken): the
    values are complex themselves, so `.real` is not offered as the fix."""
    result = grade(mutant(tmp_path, MODULE, """
        def epipoles(F):
            values1, vectors1 = np.linalg.eig(F)
            values2, vectors2 = np.linalg.eig(F.T)
            return vectors1[:, np.argmax(np.abs(values1.imag))], vectors2[:, np.argmax(np.abs(values2.imag))]
        """), ["lab11.ex5"], pictures="none")
    messages = [c.message for c in check_results(result, "lab11.ex5") if not c.passed]
    complex_told = [m for m in messages if "complex numbers" in m]
    assert complex_told and all("not 0" in m and "`.real`" not in m for m in complex_told), complex_told


def test_points_indexed_by_an_estimators_mask_are_its_inliers_only_when_the_mask_is_made_boolean():
    """cv2.findFundamentalMat's mask is 0/1 uint8: `pts1[mask.ravel()]` picks points 0 and 1 over and
    over. Only an index boolean by its code (a comparison, astype(bool), np.where, a name holding one)
    is told "keeps the inliers"."""
    import ast as _ast

    from autograder.labs import lab11

    def reads(body):
        source = "def f(pts1, pts2):\n    F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC)\n" + body
        return lab11._indexes_by_a_mask(_ast.parse(source).body[0])

    assert not reads("    return pts1[mask.ravel()]\n")
    assert not reads("    inliers = mask.ravel()\n    return pts1[inliers]\n")
    assert reads("    return pts1[mask.ravel() == 1]\n")
    assert reads("    inliers = mask.ravel().astype(bool)\n    return pts1[inliers]\n")
    assert reads("    keep = mask.ravel() > 0\n    inliers = keep\n    return pts1[inliers]\n")
    assert reads("    idx = np.flatnonzero(mask)\n    return pts1[idx], pts2[mask.ravel() != 0]\n")


def test_the_truth_behind_no_point_or_points_seen_by_one_camera_only_is_empty_not_an_error():
    """A pipeline that keeps no correct match (0 of its points land inside image 2) is judged, never a grader
    error: cv2.remap refuses an empty map, so the truth's bilinear sampling asks it for no point."""
    pair = truth.rendered_pair(seed=3)
    X, pts2, valid = truth.true_correspondences(pair, np.zeros((0, 2)))
    assert X.shape == (0, 3) and pts2.shape == (0, 2) and valid.shape == (0,)
    X, pts2, valid = truth.true_correspondences(pair, np.array([[-500.0, -500.0], [5000.0, 10.0]]))
    assert not valid.any()


def test_steep_lines_ending_at_the_width_fail_on_a_portrait_image(tmp_path):
    """Steep lines drawn from y = 0 to y = W - 1 (the sizes mixed up, blind set 08b lab11/03) are right on every
    image wider than tall, and stop short on a portrait one: the any-size check draws on one."""
    from autograder.engine.runner import grade
    from conftest import check_results, mutant

    source = """
        def draw_epipolar_lines(image, lines):
            out = image.copy()
            h, w = out.shape[:2]
            for i, (a, b, c) in enumerate(np.asarray(lines, dtype=float).reshape(-1, 3)):
                if abs(b) >= abs(a):
                    x0, x1 = 0.0, w - 1.0
                    y0, y1 = -(a * x0 + c) / b, -(a * x1 + c) / b
                else:
                    y0, y1 = 0.0, w - 1.0
                    x0, x1 = -(b * y0 + c) / a, -(b * y1 + c) / a
                colour = _PALETTE[i % len(_PALETTE)] if out.ndim == 3 else 255
                cv2.line(out, _to_int((x0, y0), w, h), _to_int((x1, y1), w, h), colour, 1)
            return out
        """
    result = grade(str(mutant(tmp_path, "lab11_two_view", source)), ["lab11.ex2"], pictures="none")
    failed = [c for c in check_results(result, "lab11.ex2") if c.score < c.max_score]
    assert [c.name for c in failed] == [
        "draw_epipolar_lines draws a line given at any scale ((a, b, c) times 2.5 is the same line), on an image of "
        "any size (a portrait one too)"], [c.name for c in failed]
    # (and named: `w`'s twin `h` is offered in the else-branch, below the values the if-branch made from `w`)
    assert "changing `0.0, w - 1.0` to `0.0, h - 1.0`" in failed[0].message, failed[0].message
