"""``autograder validate`` and ``check(..., validate=True)``: before hand-in, what would lose
points for reasons other than the algorithm (issue 27); and a lone file with any name graded
when one lab is selected."""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

from autograder.student import selfcheck
from autograder.student.validate import NOTE, PROBLEM, validate
from conftest import REFERENCE, ROOT, SKELETON, mutant, submission_from_source
from test_beginner_errors import INTEGER_MATRIX

MODULE = "lab07_transformations"
REFERENCE_SOURCE = (REFERENCE / f"{MODULE}.py").read_text()


def autograder(*args, cwd=ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "autograder", *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=300)


def problems(report) -> dict[str, list[str]]:
    found: dict[str, list[str]] = {}
    for finding in report.problems:
        found.setdefault(finding.subject, []).append(finding.text)
    return found


def write_notebook(folder, cells, name=MODULE):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{name}.ipynb").write_text(json.dumps({
        "cells": [{"cell_type": "code", "metadata": {}, "source": c, "outputs": [], "execution_count": None}
                  for c in cells], "metadata": {}, "nbformat": 4, "nbformat_minor": 5}))
    return folder


def test_clean_work_validates_with_status_0_and_says_so():
    run = autograder("validate", REFERENCE, "lab07.ex1", "lab07.ex2")
    assert run.returncode == 0, run.stdout + run.stderr
    assert f"✓ {MODULE}.py: imports cleanly" in run.stdout and "No problems found" in run.stdout


def test_the_skeleton_is_not_implemented_yet_which_is_no_form_problem():
    report = validate(SKELETON, ["lab07.ex1"])
    assert report.ok
    assert {(f.subject, f.text) for f in report.findings if f.level == NOTE} == {
        ("translation_matrix()", "not implemented yet"), ("translate()", "not implemented yet")}


def test_a_notebook_with_every_kind_of_form_problem_is_named_point_by_point(tmp_path):
    cells = re.split(r"\n(?=def |class )", REFERENCE_SOURCE)
    cells = [c.replace("def translate(image, tx=100, ty=50):", "def translate(img, dx=100, dy=50):\n"
                                                               "    image, tx, ty = img, dx, dy")
             .replace("def rotate(image, angle_deg=45):", "def Rotate(image, angle_deg=45):") for c in cells]
    cells += ["import skimage\nimg = skimage.data.astronaut()\nSIZE = img.shape[:2]",
              "def centre():\n    return SIZE[1] / 2, SIZE[0] / 2", "ratio = 1 / 0",
              "import matplotlib.pyplot as plt\nplt.imshow(img)\nplt.show()"]
    folder = write_notebook(tmp_path / "handin", cells)
    run = autograder("validate", folder, "lab07.ex1", "lab07.ex2")
    assert run.returncode == 1, run.stdout + run.stderr
    report = validate(folder, ["lab07.ex1", "lab07.ex2"])
    found = problems(report)
    assert found["centre()"] == [f"reads SIZE, which grading leaves out (cell {len(cells) - 3} "
                                 "`SIZE = img.shape[:2]`: needs img): pass it in as an argument, or compute it "
                                 "inside the function from constants"]
    assert any("name the parameters as the lab does, translate(image, tx=100, ty=50) (yours: img, dx, dy)" in t
               for t in found["translate()"])
    assert any("got an unexpected keyword argument 'tx'" in t for t in found["translate()"])
    assert found["rotate()"] == ["not defined: def rotate(image, angle_deg=45) (is Rotate meant to be it? "
                                 "the grader looks for this exact name)"]
    assert found[f"{MODULE}.ipynb"] == [f"cell {len(cells) - 1}, line 1 raises ZeroDivisionError: division by zero "
                                        "when run: grading skips that statement, and whatever needs what it "
                                        "defines fails"]
    left_out = [f.text for f in report.findings if f.level == NOTE and f.subject == f"{MODULE}.ipynb"]
    # every statement left out, one line each, each once (a grading's note names the first five)
    assert f"left out at grading: cell {len(cells) - 3} `img = skimage.data.astronaut()` (a call: demo code)" \
        in left_out and any("(plotting)" in t for t in left_out)
    assert len(left_out) == len(set(left_out)) >= 4


def test_signatures_are_held_to_the_labs_declarations(tmp_path):
    source = '''
def translation_matrix(tx):
    return np.eye(3)


def translate(image, tx, ty=10):
    return image


def rotation_matrix(angle_deg, center=(0.0, 0.0), *, scale):
    return np.eye(3)
'''
    found = problems(validate(mutant(tmp_path, MODULE, source), ["lab07.ex1", "lab07.ex2"]))
    assert "takes 1 argument (tx); the grader calls it as translation_matrix(tx, ty)" in found["translation_matrix()"]
    assert "tx has no default; the lab says tx=100 (the grader calls it without it)" in found["translate()"]
    assert "ty defaults to 10; the lab says ty=50 (the grader calls it without it)" in found["translate()"]
    assert "needs scale, which the grader never passes: give it a default" in found["rotation_matrix()"]


def test_files_imports_and_dtypes_are_named(tmp_path):
    folder = submission_from_source(tmp_path / "a", "lab7_transform", "x = 1\n")
    (folder / "helpers.py").write_text("y = 2\n")
    missing = validate(folder, ["lab07.ex1"])
    assert problems(missing)[f"{MODULE}.py"] == [f"module {MODULE}.py not found (found: helpers.py, "
                                                 f"lab7_transform.py); if lab7_transform.py is this lab, rename it "
                                                 f"{MODULE}.py"]
    broken = validate(submission_from_source(tmp_path / "b", MODULE, "import numpy as np\nimport seaborn\n"),
                      ["lab07.ex1"])
    [text] = problems(broken)[f"{MODULE}.py"]
    assert text.startswith("does not import: ") and "No module named 'seaborn'" in text and "line 2" in text
    found = problems(validate(mutant(tmp_path / "c", MODULE, INTEGER_MATRIX), ["lab07.ex1"]))
    assert found["translation_matrix()"] == ["returned an int64 array; the lab documents a float array (OpenCV's "
                                             "warps and most maths need floats): build it with dtype=float"]
    assert found["translate()"][0].startswith("cv2.warpAffine needs M as a float32 or float64 matrix; yours is int64")


def test_demo_code_a_module_runs_when_imported_is_noted(tmp_path):
    source = REFERENCE_SOURCE + "\nimg = cv2.imread('lena.png')\nprint(translation_matrix(1, 2))\n"
    report = validate(submission_from_source(tmp_path, MODULE, source), ["lab07.ex1"])
    [note] = [f.text for f in report.findings if f.level == NOTE]
    assert "runs when grading imports it" in note and "`img = cv2.imread('lena.png')` (reads a file" in note
    assert "if __name__ == '__main__':" in note


def test_usage_errors_exit_2(tmp_path):
    assert autograder("validate", REFERENCE, "lab99").returncode == 2
    run = autograder("validate", tmp_path / "nowhere", "lab07")
    assert run.returncode == 2 and "not found" in run.stderr


def test_check_validate_in_a_notebook_displays_the_same_findings(tmp_path):
    folder = mutant(tmp_path, MODULE, "def translate(image, tx=100, ty=50):\n"
                                      "    raise ValueError('<b>no</b> & more')\n")
    report = selfcheck.check("lab07.ex1", submission=folder, validate=True)
    assert not report.ok and problems(report)["translate()"] == ["raised ValueError: <b>no</b> & more"]
    page = report._repr_html_()
    assert "&lt;b&gt;no&lt;/b&gt; &amp; more" in page and "<b>no</b>" not in page
    assert str(report).splitlines()[-1].startswith("1 problem found")


# ------------------------------------------------------------------ a lone file, any name
def test_a_lone_file_with_any_name_is_graded_as_the_one_lab_selected(tmp_path):
    lone = tmp_path / "lab7.py"
    lone.write_text(REFERENCE_SOURCE)
    run = subprocess.run([sys.executable, str(ROOT / "grade.py"), "--submission", str(lone), "lab07.ex1",
                          "--no-html"], capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert run.returncode == 0 and "10 / 10" in run.stdout, run.stdout + run.stderr
    assert f"graded lab7.py as {MODULE}.py" in " ".join(run.stdout.split())
    run = autograder("grade", lone, "lab07.ex1", "--no-html", cwd=tmp_path)
    assert "10 / 10" in run.stdout
    several = autograder("grade", lone, "--no-html", cwd=tmp_path)
    assert "a single file is graded as a lab's module when only that lab is selected" in " ".join(
        several.stdout.split())
    other_lab = tmp_path / "other"
    other_lab.mkdir()
    (other_lab / "lab08_homographies.py").write_text(REFERENCE_SOURCE)
    named_after_another = autograder("grade", other_lab / "lab08_homographies.py", "lab07.ex1", "--no-html",
                                     cwd=tmp_path)
    assert "0 / 10" in named_after_another.stdout  # never taken for another lab's module
    assert PROBLEM in [f.level for f in validate(lone, ["lab07.ex1"]).findings]  # validate asks for the rename


@pytest.mark.parametrize("name", ["Lab07_Transformations.py", "lab07_transformations (1).py"])
def test_a_name_plainly_meant_is_a_note_not_a_problem(tmp_path, name):
    """A file whose name was plainly meant as the module is graded whatever else is selected: validate notes the
    rename, it does not call the file a problem (audit of 2026-12-07: "graded only when found alone" of a file that
    was found alone and graded)."""
    (tmp_path / name).write_text(REFERENCE_SOURCE)
    findings = [f for f in validate(tmp_path, ["lab07.ex1"]).findings if "is graded as" in f.text]
    assert [f.level for f in findings] == [NOTE] and "to be sure" in findings[0].text
