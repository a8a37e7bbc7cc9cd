"""Labs 10-12 written the way the lab sheet says score full marks.

``tests/submissions/lab_sheet/`` holds one module per lab written line by line
from the lab sheet: the OpenCV recipes it names (cv2.findChessboardCorners,
cv2.solvePnP and cv2.projectPoints; SIFT, cv2.findFundamentalMat and
cv2.triangulatePoints; cv2.stereoRectify with cv2.warpPerspective, cv2.StereoBM),
NumPy and SVD where it says so (without the normalisations it does not ask
for), and Matplotlib windows to look at the results. Conventions the API leaves
open (NaN behind the camera) may give tips, never lose points.
"""

from pathlib import Path

import pytest

from autograder.runner import grade
from conftest import assert_full_marks

LAB_SHEET = Path(__file__).parent / "submissions" / "lab_sheet"
LABS = ["lab10", "lab11", "lab12"]


@pytest.fixture(scope="module")
def lab_sheet_result():
    return grade(LAB_SHEET, LABS, pictures="none")


@pytest.mark.parametrize("lab", LABS)
def test_the_lab_sheets_recipes_score_full_marks(lab_sheet_result, lab):
    assert_full_marks(lab_sheet_result, lab)
    exercises = [e for e in lab_sheet_result.exercises if e.id.startswith(lab + ".")]
    assert sum(e.score for e in exercises) == sum(e.max_score for e in exercises) > 0
