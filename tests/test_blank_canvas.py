"""A drawing made on a new blank image (``np.zeros_like(image)``) instead of a copy of the input is
named where the input is gone (issue 35: the blind set's "79% of the changed pixels are away from
every line" described what the picture showed, not that the image itself was never drawn on)."""

from __future__ import annotations

import numpy as np

from autograder.engine.judges import BLANK_CANVAS, blank_canvas
from autograder.engine.runner import grade
from conftest import check_results, mutant

DRAW_POINTS_ON_ZEROS = '''
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    out = np.zeros_like(image)
    for x, y in np.asarray(pts, float).reshape(-1, 2):
        if np.isfinite(x) and np.isfinite(y):
            cv2.circle(out, (int(round(x)), int(round(y))), radius, color if out.ndim == 3 else color[0], -1)
    return out
'''

DRAW_LINES_ON_ZEROS = '''
def draw_epipolar_lines(image, lines):
    out = np.zeros_like(image) if image.ndim == 3 else np.zeros(image.shape + (3,), np.uint8)
    h, w = image.shape[:2]
    for a, b, c in np.asarray(lines, float).reshape(-1, 3):
        if abs(b) > abs(a):
            p, q = (0, -c / b), (w - 1, -(c + a * (w - 1)) / b)
        else:
            p, q = (-c / a, 0), (-(c + b * (h - 1)) / a, h - 1)
        cv2.line(out, tuple(int(round(v)) for v in p), tuple(int(round(v)) for v in q), (0, 255, 0), 1)
    return out
'''


def test_a_drawing_on_zeros_is_named_in_both_labs(tmp_path):
    for module, source, exercise in (("lab09_camera", DRAW_POINTS_ON_ZEROS, "lab09.ex5"),
                                     ("lab11_two_view", DRAW_LINES_ON_ZEROS, "lab11.ex2")):
        result = grade(str(mutant(tmp_path / module, module, source)), [exercise])
        failed = [c for c in check_results(result, exercise) if c.score < c.max_score and c.mistake]
        assert any(c.mistake == BLANK_CANVAS for c in failed), [(c.name, c.message) for c in failed]


def test_a_drawing_on_the_image_or_on_a_dark_image_is_not_called_blank():
    rng = np.random.default_rng(0)
    image = rng.integers(0, 255, (40, 50, 3), dtype=np.uint8)
    away = np.ones((40, 50), bool)
    away[18:22] = False
    drawn = image.copy()
    drawn[18:22] = (0, 255, 0)
    assert blank_canvas(drawn, image, away) == ""
    dark = np.zeros_like(image)   # (a black input drawn on: nothing to tell)
    assert blank_canvas(dark, dark, away) == ""
    assert BLANK_CANVAS in blank_canvas(np.zeros_like(image), image, away)
