"""OpenCV 4 or 5: the two pin files, the course's choice, the versions every result records,
and feedback that states no false cause when code depends on what only one major does.

Runs under either major (bash .ci/opencv4 runs the suite under OpenCV 4): what differs
between them is asserted for the installed one.
"""

import ast
import json
import zipfile

import cv2
import numpy as np
import pytest

from autograder.engine import version_differences, versions
from autograder.engine.results import GradingResult
from autograder.engine.runner import grade
from autograder.instructor import verify
from autograder.instructor.course import CourseConfig, CourseConfigError
from conftest import REFERENCE, ROOT

MAJOR = cv2.__version__.split(".")[0]
OTHER = "4" if MAJOR == "5" else "5"


def pins(name: str) -> dict[str, str]:
    lines = (ROOT / name).read_text().splitlines()
    return dict(line.split("==", 1) for line in lines if line and not line.startswith("#"))


# ------------------------------------------------------------------ the two pin files
def test_the_two_constraints_files_differ_in_the_opencv_pin_only():
    """.ci/lock writes constraints-opencv4.txt from constraints.txt: the same NumPy, SciPy,
    scikit-image, Hypothesis... so the two majors are the only difference between two courses."""
    five, four = pins("constraints.txt"), pins("constraints-opencv4.txt")
    assert five.keys() == four.keys()
    differ = {name for name in five if five[name] != four[name]}
    assert differ == {"opencv-python-headless"}
    assert five["opencv-python-headless"].startswith("5.") and four["opencv-python-headless"].startswith("4.")
    lock = (ROOT / ".ci" / "lock").read_text()
    assert "constraints-opencv4.txt" in lock and "OPENCV4" in lock


def test_the_installed_opencv_is_one_the_grader_is_tested_with():
    installed = pins(versions.CONSTRAINTS[MAJOR])["opencv-python-headless"]
    assert cv2.__version__ == ".".join(installed.split(".")[:3])


# ------------------------------------------------------------------ the known differences
@pytest.mark.parametrize("difference", version_differences.KNOWN, ids=lambda d: d.name)
def test_each_known_difference_is_what_the_installed_opencv_does(difference):
    """The table states what each major does; this OpenCV does what it says of it, and the
    other major something else (else it would be no difference)."""
    got = difference.demonstrate()
    got = list(got) if isinstance(got, tuple) else got
    expected = {major: list(v) if isinstance(v, tuple) else v for major, v in difference.under.items()}
    assert got == expected[MAJOR]
    assert expected[OTHER] != expected[MAJOR]


def reads_location(source: str) -> bool:
    [function] = ast.parse(source).body
    return bool(version_differences.differences_in([function])) and \
        version_differences.differences_in([function])[0] is version_differences.KNOWN[0]


@pytest.mark.parametrize("body, reads", [
    ("return cv2.minMaxLoc(costs)[2][1]", True),
    ("_, _, loc, _ = cv2.minMaxLoc(costs)\n    return loc[1]", True),
    ("r = cv2.minMaxLoc(costs)\n    return r[3]", True),
    ("return cv2.minMaxLoc(costs)[0]", False),                 # the value: the same under both
    ("low, _, _, _ = cv2.minMaxLoc(costs)\n    return low", False),
    ("_, _, (x, y), _ = cv2.minMaxLoc(cv2.matchTemplate(a, b, 0))\n    return x", False),   # surely 2-D
    ("return np.argmin(costs)", False),
])
def test_reading_minmaxloc_location_is_told_from_the_code(body, reads):
    assert reads_location(f"def f(costs, a=None, b=None):\n    {body}\n") is reads


def test_undistortion_criteria_are_told_from_the_code():
    def named(body):
        [function] = ast.parse(f"def f(p, K, d, c):\n    {body}\n").body
        return [d.name for d in version_differences.differences_in([function])]

    assert named("return cv2.undistortPoints(p, K, d, P=K, criteria=c)") == ["cv2.undistortPoints' termination criteria"]
    assert named("return cv2.undistortPointsIter(p, K, d, None, K, c)") == ["cv2.undistortPoints' termination criteria"]
    assert named("return cv2.undistortPoints(p, K, d, P=K)") == []


def test_the_fixtures_undistortion_is_the_same_under_both_majors():
    """fixtures.lab10 undistorts with criteria through the call each major has: the points are
    those of the plain call refined further (the plain call's 5 iterations: within 0.1 px here)."""
    from fixtures.lab10 import undistort_points_iterated

    K = np.array([[300.0, 0, 160], [0, 300, 120], [0, 0, 1]])
    dist = np.array([-0.28, 0.08, 0.001, -0.0015, 0.0])
    pix = np.float64([[[0.0, 0.0]], [[319.0, 239.0]], [[100.0, 50.0]]])
    iterated = undistort_points_iterated(pix, K, dist, K, (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 40, 1e-6))
    np.testing.assert_allclose(iterated.ravel(), [-25.24998092, -19.37899141, 344.86722351, 257.92283543,
                                                  98.38142942, 48.02709588], atol=1e-6)   # measured on 4.14 and 5.0
    assert np.abs(iterated - cv2.undistortPoints(pix, K, dist, P=K)).max() < 0.1


# ------------------------------------------------------------------ the versions that judged
def test_results_record_the_versions_and_old_results_read_without_them():
    result = GradingResult("s", "h", "1", versions=versions.judged_with())
    data = json.loads(json.dumps(result.to_dict()))
    assert data["versions"] == {"python": data["versions"]["python"], "numpy": np.__version__,
                                "opencv": cv2.__version__}
    assert GradingResult.from_dict(data).versions == result.versions
    assert result.for_students().versions == result.versions
    old = {k: v for k, v in data.items() if k != "versions"}
    assert GradingResult.from_dict(old).versions == {}
    assert versions.describe({}) == ""
    assert versions.describe(result.versions) == f"NumPy {np.__version__}, OpenCV {cv2.__version__}"


def test_every_report_says_which_numpy_and_opencv_judged():
    from rich.console import Console

    from autograder.instructor.gradescope import _summary
    from autograder.reports import html, terminal

    result = GradingResult("alice", "h", "1", versions=versions.judged_with())
    said = f"NumPy {np.__version__}, OpenCV {cv2.__version__}"
    console = Console(record=True, width=200)
    terminal.render(result, console=console, details=False)
    assert said in console.export_text()
    assert said in html.render(result)
    assert said in _summary(result)
    old = GradingResult("alice", "h", "1")   # stored before versions were recorded: nothing claimed
    assert "judged with" not in html.render(old) and "Judged with" not in _summary(old)


def test_the_class_overview_says_which_versions_judged_the_class():
    from autograder.instructor.classreport.analysis import StudentRecord
    from autograder.instructor.classreport.overview import overview_html

    graded = GradingResult("alice", "h", "1", versions=versions.judged_with()).to_dict()
    old = GradingResult("bob", "h", "1").to_dict()   # kept from before versions were recorded
    page = overview_html([StudentRecord("alice", result=graded), StudentRecord("bob", result=old),
                          StudentRecord("carol", status="unreadable", reason="empty")])
    assert f"judged with NumPy {np.__version__}, OpenCV {cv2.__version__}</div>" in page


# ------------------------------------------------------------------ the course's choice
def test_a_course_chooses_its_opencv_major():
    assert CourseConfig().opencv == "5"
    assert CourseConfig(opencv=4).opencv == "4"
    with pytest.raises(CourseConfigError, match='opencv must be "4" or "5"'):
        CourseConfig(opencv="4.10")
    assert "opencv" in CourseConfig(opencv="4").ignored_by("grade")   # told, never silently ignored
    assert "opencv" not in CourseConfig(opencv="4").ignored_by("batch")


@pytest.mark.parametrize("major", ["4", "5"])
def test_the_bundle_and_gradescope_install_the_courses_pins(tmp_path, major):
    from autograder.instructor import gradescope
    from autograder.instructor.bundle import write_student_bundle

    course = CourseConfig(opencv=major, select=["lab07"])
    wanted = (ROOT / versions.CONSTRAINTS[major]).read_text()
    write_student_bundle(tmp_path / "bundle", course=course)
    assert (tmp_path / "bundle" / "constraints.txt").read_text() == wanted
    with zipfile.ZipFile(gradescope.build(tmp_path / "autograder.zip", course)) as zf:
        assert zf.read("constraints.txt").decode() == wanted
        setup = zf.read("setup.sh").decode()
        assert json.loads(zf.read("course.json"))["opencv"] == major
    assert "-c /autograder/source/constraints.txt" in setup
    assert f"== '{major}' else 'setup.sh: the course grades with OpenCV {major}" in setup


def test_a_batch_under_the_other_major_stops_saying_what_to_install(tmp_path):
    from autograder.instructor.batch.run import run_batch

    with pytest.raises(CourseConfigError) as refused:
        run_batch(tmp_path / "nowhere", tmp_path / "out", course=CourseConfig(opencv=OTHER))
    said = str(refused.value)
    assert f"grades with OpenCV {OTHER}" in said and f"OpenCV {cv2.__version__} is installed" in said
    assert f"-c {versions.CONSTRAINTS[OTHER]}" in said
    assert not (tmp_path / "out").exists()   # refused before anything was read or written


def test_the_gradebook_lock_is_the_installed_majors_pins():
    import hashlib

    from autograder.instructor.batch.gradebook import lock_hash

    text = (ROOT / versions.CONSTRAINTS[MAJOR]).read_text()
    assert lock_hash() == hashlib.sha256(text.encode()).hexdigest()[:16]


# ------------------------------------------------------------------ third-party OpenCV-4 code
def test_opencv4_block_matcher_full_marks_under_4_and_no_false_cause_under_5(tmp_path):
    """A block matcher written for OpenCV 4 (cv2.minMaxLoc's location on the 1-D vector of costs
    of a pixel): right under OpenCV 4, a map of zeros under 5. Under 5 it loses the points, but no
    check names a false cause in its code ("the cost argument is ignored" was said) -- a change
    confirmed to mend it under 5 may be shown (a repair); each failure says what differs and which
    OpenCV graded."""
    folder = tmp_path / "submission"
    folder.mkdir()
    source = (ROOT / "tests" / "data" / "opencv4" / "block_matcher.py").read_text()
    (folder / "lab12_stereo.py").write_text(
        verify.with_mutation((REFERENCE / "lab12_stereo.py").read_text(), source))
    result = grade(folder, ["lab12.ex4", "lab12.ext1"], pictures="none")
    assert result.versions["opencv"] == cv2.__version__
    checks = [c for e in result.exercises for c in e.checks]
    if MAJOR == "4":
        assert result.total == result.max_total, [(c.name, c.message) for c in checks if not c.passed]
        return
    failed = [c for c in checks if not c.passed]
    assert result.total < result.max_total / 2 and failed
    for check in failed:
        assert (not check.mistake or check.mistake.startswith("repair:")) and "ignored" not in check.message, \
            (check.name, check.message)
        assert "cv2.minMaxLoc's location" in check.message
        assert f"this course grades with OpenCV {cv2.__version__}" in check.message


@pytest.mark.parametrize("body, noted", [
    ("t = np.linalg.solve(K, p)", False),                  # another library's solve: no note
    ("t = scipy.linalg.solve(K, p)", False),
    ("ok, t = cv2.solve(K, p)", True),
    ("ok, t = cv.solve(K, p)", True),
    ("r = cv2.gemm(a, b, 1, None, 0)", True),
    ("order = np.argsort(x)", False),
    ("order = cv2.sortIdx(x, cv2.SORT_EVERY_COLUMN)", True),
])
def test_a_note_on_opencv_versions_needs_opencvs_own_call(body, noted):
    """A note about OpenCV 4 and 5 is true of the code only when the code calls OpenCV's function
    (the blind set's decomposition, which calls np.linalg.solve, was told it calls cv2.solve)."""
    import ast

    from autograder.engine.version_differences import KNOWN

    function = ast.parse(f"def f(K, p, a, b, x):\n    {body}\n").body[0]
    assert any(bool(d.reads.found([function])) for d in KNOWN[1:]) == noted
