"""Lab 9, issue 35: two conventions the API leaves open are told, never lost points. A radius
drawn uniformly (aperture * u) crowds simulate_aperture's rays near the centre; draw_points
truncating its centres with int() draws a pixel off. The mistakes themselves are ADVICE cases of
autograder/labs/mistakes/lab09.py (tests/test_lab09.py); here, the legitimate ways of doing it
right keep full marks and get no tip, and the code-read half of the draw_points tip is said only
where the code truncates with int()."""

from __future__ import annotations

import pytest

from autograder.engine.runner import grade
from conftest import advice_given, check_results, mutant

MODULE = "lab09_camera"

RIGHT = {
    "aperture by rejection sampling from the square": ("lab09.ex4", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X, _ = _points(points)
            rng = np.random.default_rng(seed)
            A = np.empty((len(X), n_rays, 2))
            for i in range(len(X)):
                kept = np.empty((0, 2))
                while len(kept) < n_rays:
                    p = rng.uniform(-1.0, 1.0, size=(2 * n_rays, 2))
                    kept = np.concatenate([kept, p[np.hypot(p[:, 0], p[:, 1]) <= 1.0]])
                A[i] = aperture * kept[:n_rays]
            return pinhole_project(X, f)[:, None, :] - A * (1.0 + f / X[:, 2])[:, None, None]
        """),
    "aperture with the radius aperture * u ** 0.5": ("lab09.ex4", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X, _ = _points(points)
            rng = np.random.default_rng(seed)
            radius = aperture * rng.random((len(X), n_rays)) ** 0.5
            angle = 2 * np.pi * rng.random((len(X), n_rays))
            A = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)
            return pinhole_project(X, f)[:, None, :] - A * (1.0 + f / X[:, 2])[:, None, None]
        """),
    "draw_points rounding with np.rint": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
            for x, y in np.rint(pts[np.isfinite(pts).all(axis=1)]).astype(int):
                cv2.circle(out, (int(x), int(y)), radius, color, -1)
            return out
        """),
    "draw_points rounding with np.round(...).astype(int)": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    centre = tuple(np.round([x, y]).astype(int).tolist())
                    cv2.circle(out, centre, radius, color, thickness=-1)
            return out
        """),
}


@pytest.mark.parametrize("case", sorted(RIGHT))
@pytest.mark.xdist_group("lab09")
def test_right_ways_keep_full_marks_and_get_no_tip(tmp_path, case):
    exercise, source = RIGHT[case]
    result = grade(mutant(tmp_path, MODULE, source), [exercise], pictures="none")
    for check in check_results(result, exercise):
        assert check.passed, f"{check.name}: {check.message}"
    tips = advice_given(result, exercise)
    assert not any("crowd the centre" in tip or "floor(x)" in tip for tip in tips), tips


@pytest.mark.xdist_group("lab09")
def test_truncation_by_astype_is_measured_but_not_blamed_on_int(tmp_path):
    """Centres truncated by .astype(int) (no int() on a coordinate): the measurement is said,
    the sentence about int() is not; no point is lost."""
    result = grade(mutant(tmp_path, MODULE, """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
            for x, y in pts[np.isfinite(pts).all(axis=1)].astype(int).tolist():
                cv2.circle(out, (x, y), int(radius), tuple(int(c) for c in color), -1)
            return out
        """), ["lab09.ex5"], pictures="none")
    for check in check_results(result, "lab09.ex5"):
        assert check.passed or check.advice, f"{check.name}: {check.message}"
    tips = advice_given(result, "lab09.ex5")
    assert any("centred at (floor(x), floor(y))" in tip for tip in tips), tips
    assert not any("int()" in tip for tip in tips), tips
