"""grade.py and the reports: exit codes, selection, JSON keys, a self-contained page."""

import json
import re
import subprocess
import sys
import zipfile

import pytest

from autograder.reports import html
from autograder.engine.results import GradingResult
from autograder.engine.runner import grade
from autograder.loading.submission import notebook_to_source
from conftest import REFERENCE, ROOT, mutant

MODULE = "lab07_transformations"


def run_grade_py(*args, cwd):
    return subprocess.run([sys.executable, str(ROOT / "grade.py"), *args], cwd=cwd,
                          capture_output=True, text=True, timeout=300)


def test_grade_py_writes_json_and_html_and_exits_zero(tmp_path):
    run = run_grade_py("--submission", str(REFERENCE), "lab07.ex1", "--json", "r.json", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    data = json.loads((tmp_path / "r.json").read_text())
    assert data["total"] == data["max_total"] > 0
    [exercise] = data["exercises"]
    assert exercise["id"] == "lab07.ex1"
    assert {"id", "score", "max_score", "checks"} <= exercise.keys()
    for check in exercise["checks"]:
        assert {"name", "passed", "score", "max_score", "message"} <= check.keys()
    assert (tmp_path / "feedback.html").exists()
    assert "lab07.ex1" in run.stdout and "total" in run.stdout


def test_grade_py_defaults_to_assignments_and_a_zero_score_still_exits_zero(tmp_path):
    run = run_grade_py("lab07.ex2", "--no-html", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert "not implemented yet" in run.stdout
    assert "Traceback" not in run.stdout + run.stderr
    assert not (tmp_path / "feedback.html").exists()


@pytest.mark.parametrize("args, fragment", [
    (["lab99"], "nothing to grade matches 'lab99'"),
    (["--submission", "/no/such/folder"], "submission not found"),
])
def test_usage_errors_exit_non_zero_with_a_message(tmp_path, args, fragment):
    run = run_grade_py(*args, "--no-html", cwd=tmp_path)
    assert run.returncode == 2
    assert fragment in " ".join((run.stdout + run.stderr).split())


def test_feedback_page_is_self_contained_and_escapes_student_output(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        def translate(image, tx=100, ty=50):
            print("<script>alert(1)</script>")
            return image.astype(np.float64)
        """), ["lab07.ex1"])
    page = html.render(result)
    assert "<script>alert(1)</script>" not in page
    assert "&lt;script&gt;" in page
    # No script runs: the one script element is the scores' JSON data block (never executed)
    scripts = re.findall(r"<script[^>]*>", page, re.I)
    assert scripts == ['<script type="application/json" id="autograder-scores">']
    # Everything is embedded: no external stylesheets, scripts or images.
    assert not re.search(r'(src|href)="(?!data:|#)', page)
    assert "data:image/png;base64," in page
    assert "dtype float64" in page


def test_results_round_trip_through_json(tmp_path):
    result = grade(REFERENCE, ["lab07.ex6"])
    again = GradingResult.from_dict(json.loads(json.dumps(result.to_dict())))
    assert again.to_dict() == result.to_dict()


def test_zip_and_nested_folder_submissions(tmp_path):
    archive = tmp_path / "handin.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        zf.write(REFERENCE / f"{MODULE}.py", f"student123/{MODULE}.py")
        zf.writestr("__MACOSX/._junk.py", "garbage")
        zf.writestr("../evil.py", "print('outside')")
    result = grade(archive, ["lab07.ex1"])
    assert result.total == result.max_total


def test_notebook_submission(tmp_path):
    source = (REFERENCE / f"{MODULE}.py").read_text()
    notebook = {"cells": [
        {"cell_type": "markdown", "source": ["# Lab 7"]},
        {"cell_type": "code", "source": ["%matplotlib inline\n", "!pip install nothing\n"]},
        {"cell_type": "code", "source": source},
    ]}
    path = tmp_path / f"{MODULE}.ipynb"
    path.write_text(json.dumps(notebook))
    assert "# %matplotlib inline" in notebook_to_source(path.read_text())
    result = grade(path, ["lab07.ex1"])
    assert result.total == result.max_total


def test_json_leaves_pictures_out_unless_asked(tmp_path, no_naming):
    """A JSON file is for programs: no base64 pictures by default (megabytes each). (Naming off:
    it adds no picture.)"""
    from autograder.cli import main

    plain, with_pictures = tmp_path / "plain.json", tmp_path / "pictures.json"
    mutant_dir = tmp_path / "handin"
    mutant_dir.mkdir()
    (mutant_dir / "lab07_transformations.py").write_text(
        (REFERENCE / "lab07_transformations.py").read_text().replace("[0.0, 1.0, ty]", "[0.0, 1.0, -ty]"))
    for path, extra in ((plain, []), (with_pictures, ["--json-pictures"])):
        assert main(["grade", str(mutant_dir), "lab07.ex1", "--no-html", "--json", str(path), *extra]) == 0

    def artifacts(path):
        return [a for e in json.loads(path.read_text())["exercises"] for c in e["checks"] for a in c["artifacts"]]
    assert artifacts(plain) == [] and artifacts(with_pictures) != []


def test_grade_applies_the_course_time_limits_and_timeout_overrides_them(tmp_path):
    """``--config``'s call_timeout is the worker's limit (the note says grade applies it); an
    explicit --timeout wins over it."""
    from autograder.cli import main

    handin = tmp_path / "handin"
    handin.mkdir()
    (handin / "lab07_transformations.py").write_text(
        (REFERENCE / "lab07_transformations.py").read_text()
        + "\n\nimport time\n_own, _slept = translation_matrix, []\n\ndef translation_matrix(tx, ty):\n"
          "    if not _slept:  # the first call of each worker\n"
          "        _slept.append(time.sleep(2))\n    return _own(tx, ty)\n")
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"call_timeout": 1}))
    out = tmp_path / "r.json"

    def first_failure(*extra):
        assert main(["grade", str(handin), "lab07.ex1", "--no-html", "--config", str(course),
                     "--json", str(out), *extra]) == 0
        checks = [c for e in json.loads(out.read_text())["exercises"] for c in e["checks"]]
        return next((c for c in checks if c["status"] != "passed"), None)

    limited = first_failure()
    assert limited is not None and limited["failure"] == "timeout", limited
    assert first_failure("--timeout", "10") is None


def test_a_page_of_many_pictures_keeps_within_its_budget_by_shrinking_the_passed_checks_ones():
    """Pictures that only passed checks show (folded away) are encoded at half their size, largest first, once the
    page's pictures pass PictureSheet.PICTURES_BUDGET; a failed check's pictures keep theirs (the reference's page
    was 2.67 MB against DESIGN's 2 MB -- audit of 2026-12-07)."""
    from types import SimpleNamespace

    import numpy as np

    from autograder.engine import pictures

    rng = np.random.default_rng(0)
    noisy = lambda: rng.integers(0, 256, (360, 480, 3), dtype=np.uint8)   # noqa: E731 - JPEG of ~100 KB each
    artifact = lambda: SimpleNamespace(kind="images", caption="", items=[pictures.picture_item("yours", noisy())])  # noqa: E731
    sheet = html.PictureSheet()
    failing = artifact()
    sheet.figure(failing, passed=False)
    kept = failing.items[0]["data"]
    for _ in range(30):
        sheet.figure(artifact(), passed=True)
    before = sum(len(e["data"]) for e in sheet.entries.values())
    assert before > sheet.PICTURES_BUDGET
    entries = sheet.encoded()
    assert sum(len(e["data"]) for e in entries) <= sheet.PICTURES_BUDGET
    assert entries[0]["data"] == kept and all(e["width"] == 480 for e in entries)   # (drawn in the same box)
