"""The student's evening: every kind of broken submission gets a clear message naming the
file, and everything else is still graded -- locally, through the CLI, and on Gradescope."""

import io
import json
import shutil
import zipfile

import pytest
from rich.console import Console

from autograder import cli
from autograder.instructor import gradescope
from autograder.instructor.course import CourseConfig
from autograder.reports import terminal
from autograder.engine.runner import grade
from conftest import REFERENCE, ROOT, submission_from_source

LAB07, LAB11 = "lab07_transformations", "lab11_two_view"
ONE_EACH = ["lab07.ex1", "lab11.ex1"]


def exercise(result, exercise_id):
    [found] = [e for e in result.exercises if e.id == exercise_id]
    return found


def full(result, exercise_id):
    e = exercise(result, exercise_id)
    return e.score == e.max_score > 0


def folder_with(tmp_path, files: dict) -> str:
    """A submission folder: name -> text, or name -> a reference module to copy."""
    folder = tmp_path / "handin"
    folder.mkdir()
    for name, content in files.items():
        if content in (LAB07, LAB11):
            shutil.copy(REFERENCE / f"{content}.py", folder / name)
        else:
            (folder / name).write_text(content)
    return folder


def terminal_text(result, **kwargs) -> str:
    buffer = io.StringIO()
    terminal.render(result, Console(file=buffer, width=200), **kwargs)
    return buffer.getvalue()


# ------------------------------------------------------------------ unreadable files
def test_an_unreadable_notebook_is_named_and_the_rest_is_graded(tmp_path):
    folder = folder_with(tmp_path, {f"{LAB07}.ipynb": "{not json", f"{LAB11}.py": LAB11})
    result = grade(folder, ONE_EACH)
    assert full(result, "lab11.ex1")
    lab07 = exercise(result, "lab07.ex1")
    assert lab07.score == 0
    assert f"{LAB07}.ipynb is not a readable notebook" in lab07.message
    assert "save it again" in lab07.message


def test_an_unreadable_notebook_on_gradescope_still_grades_the_rest(tmp_path):
    folder = folder_with(tmp_path, {f"{LAB07}.ipynb": "{not json", f"{LAB11}.py": LAB11})
    data = gradescope.run(folder, tmp_path / "results.json", CourseConfig(select=ONE_EACH))
    assert data["tests"], "the whole submission was thrown away"
    lab11 = [t for t in data["tests"] if t["name"].startswith("lab11.ex1")]
    assert lab11 and all(t["status"] == "passed" for t in lab11)
    assert data["score"] == sum(t["max_score"] for t in lab11)
    lab07 = [t for t in data["tests"] if t["name"].startswith("lab07.ex1")]
    assert all(f"{LAB07}.ipynb is not a readable notebook" in t["output"] for t in lab07)
    assert "notified" not in data["output"]
    assert json.loads((tmp_path / "results.json").read_text())["score"] == data["score"]


def test_a_notebook_that_is_not_utf8_is_named(tmp_path):
    folder = tmp_path / "handin"
    folder.mkdir()
    (folder / f"{LAB07}.ipynb").write_bytes(b"\xff\xfe{\x00")
    result = grade(folder, ["lab07.ex1"])
    assert f"{LAB07}.ipynb is not a readable notebook" in exercise(result, "lab07.ex1").message


def test_a_zip_inside_the_folder_is_graded_and_a_broken_one_is_named(tmp_path):
    folder = tmp_path / "handin"
    folder.mkdir()
    with zipfile.ZipFile(folder / "lab07.zip", "w") as zf:
        zf.write(REFERENCE / f"{LAB07}.py", f"work/{LAB07}.py")
    (folder / "lab11.zip").write_bytes(b"PK\x03\x04 this is not a zip")
    result = grade(folder, ONE_EACH)
    assert full(result, "lab07.ex1")
    message = exercise(result, "lab11.ex1").message
    assert "lab11.zip is not a valid zip archive" in message and f"{LAB11}.py not found" in message


def test_a_broken_zip_as_the_whole_submission_is_graded_zero_naming_it(tmp_path, capsys):
    archive = tmp_path / "handin.zip"
    archive.write_bytes(b"not a zip at all")
    report = tmp_path / "results.json"
    assert cli.grade_py_main(["--submission", str(archive), "lab07.ex1", "lab11.ex1", "--no-html",
                              "--json", str(report)], root=ROOT) == 0
    captured = capsys.readouterr()
    data = json.loads(report.read_text())
    assert data["total"] == 0 and data["max_total"] > 0
    for e in data["exercises"]:
        assert e["message"].startswith("handin.zip is not a valid zip archive, so ")
        assert all(c["score"] == 0 for c in e["checks"])
    assert "hand in lab07_transformations.py itself" in data["exercises"][0]["message"]
    assert "handin.zip is not a valid zip archive" in " ".join(captured.out.split())
    assert "Traceback" not in captured.out + captured.err
    # A path that is not there is still the caller's mistake.
    assert cli.main(["grade", str(tmp_path / "nowhere.zip"), "lab07.ex1", "--no-html"]) == cli.USAGE_ERROR
    assert "submission not found" in capsys.readouterr().err


def test_gradescope_grades_a_broken_zip_zero_and_says_what_to_upload_when_nothing_is_a_submission(tmp_path):
    archive = tmp_path / "handin.zip"
    archive.write_bytes(b"not a zip at all")
    data = gradescope.run(archive, tmp_path / "results.json", CourseConfig(select=["lab07.ex1"]))
    assert data["score"] == 0 and data["tests"]
    assert all("handin.zip is not a valid zip archive" in t["output"] for t in data["tests"] if not t["score"])
    assert "handin.zip is not a valid zip archive" in data["output"] and "notified" not in data["output"]
    notes = tmp_path / "handin.txt"
    notes.write_text("my answers")
    data = gradescope.run(notes, tmp_path / "results.json", CourseConfig(select=["lab07.ex1"]))
    assert data["score"] == 0 and data["tests"] == []
    assert "cannot grade handin.txt" in data["output"]
    assert "notified" not in data["output"] and "lab07_transformations.py" in data["output"]


# ------------------------------------------------------------------ misnamed files
@pytest.mark.parametrize("name", [f"{LAB07} (1).py", "Lab07_Transformations.py", f"{LAB07}-copy.py"])
def test_a_plainly_meant_name_is_accepted_with_a_note(tmp_path, name):
    result = grade(folder_with(tmp_path, {name: LAB07}), ["lab07.ex1"])
    assert full(result, "lab07.ex1")
    assert any(name in note and f"{LAB07}.py" in note for note in result.notes)
    assert f"note: graded {name}" in terminal_text(result)


def test_two_files_meant_as_one_module_are_both_named_and_one_graded(tmp_path):
    """Two copies of a lab: one is graded (issue 36: the one that implements it, the newer on a
    tie), and the note names both and says to keep one (see tests/test_handed_in_twice.py)."""
    result = grade(folder_with(tmp_path, {f"{LAB07} (1).py": LAB07, f"{LAB07} (2).py": LAB07}),
                   ["lab07.ex1"])
    assert full(result, "lab07.ex1")
    [note] = [n for n in result.notes if "more than once" in n]
    assert f"{LAB07} (1).py" in note and f"{LAB07} (2).py" in note and "keep one file per lab" in note


def test_a_missing_module_lists_what_was_found_and_suggests_the_rename(tmp_path):
    folder = folder_with(tmp_path, {"lab07_transformation.py": LAB07, "helpers.py": "X = 1\n"})
    result = grade(folder, ["lab07.ex1"])
    message = exercise(result, "lab07.ex1").message
    assert f"module {LAB07}.py not found" in message
    assert "found: helpers.py, lab07_transformation.py" in message
    assert f"rename it {LAB07}.py" in message


# ------------------------------------------------------------------ import errors
def test_a_runtime_import_error_names_file_and_line_once_per_module(tmp_path):
    folder = submission_from_source(tmp_path, LAB07, """
        import numpy as np

        SIZE = undefined_name + 1
        """)
    result = grade(folder, ["lab07.ex1", "lab07.ex2", "lab07.ex3"])
    message = exercise(result, "lab07.ex1").message
    assert "NameError" in message and f"{LAB07}.py, line 4: SIZE = undefined_name + 1" in message
    text = terminal_text(result)
    assert text.count("NameError") == 1
    assert "lab07 ex1, ex2, ex3:" in text


def test_missing_modules_are_one_line_per_lab(tmp_path):
    result = grade(folder_with(tmp_path, {f"{LAB11}.py": LAB11}), ["lab07", "lab11.ex1"])
    text = terminal_text(result)
    assert text.count(f"module {LAB07}.py not found") == 1
    assert "lab07 ex1, ex2, ex3, ex4, ex5, ex6:" in text


def test_gradescope_summary_says_a_module_problem_once(tmp_path):
    folder = folder_with(tmp_path, {f"{LAB11}.py": LAB11})
    data = gradescope.run(folder, tmp_path / "r.json", CourseConfig(select=["lab07.ex1", "lab07.ex2"]))
    assert data["output"].count(f"{LAB07}.py not found") == 1
    assert "as above" in data["output"]


# ------------------------------------------------------------------ options and output paths
def test_report_paths_that_are_folders_get_the_default_names(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "reports"
    out.mkdir()
    status = cli.main(["grade", str(REFERENCE), "lab07.ex1", "--json", str(out), "--html", str(out)])
    assert status == 0
    assert json.loads((out / "results.json").read_text())["exercises"][0]["id"] == "lab07.ex1"
    assert (out / "feedback.html").read_text().startswith("<!doctype html>")
    printed = capsys.readouterr().out
    assert str(out / "results.json") in printed and str(out / "feedback.html") in printed


def test_a_report_that_cannot_be_written_is_an_error_after_the_scores(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("")
    status = cli.main(["grade", str(REFERENCE), "lab07.ex1", "--no-html",
                       "--json", str(blocker / "results.json")])
    captured = capsys.readouterr()
    assert status == cli.USAGE_ERROR
    assert "total" in captured.out, "the score table must print before the files are written"
    assert f"cannot write {blocker / 'results.json'}" in captured.err
    assert "Traceback" not in captured.err


@pytest.mark.parametrize("value", ["-1", "0", "nan", "inf", "soon"])
def test_bad_timeouts_are_refused(value, capsys):
    with pytest.raises(SystemExit) as exit_:
        cli.main(["grade", str(REFERENCE), "--timeout", value])
    assert exit_.value.code == cli.USAGE_ERROR
    assert "--timeout" in capsys.readouterr().err


def test_grade_without_a_submission_explains(capsys):
    assert cli.main(["grade"]) == cli.USAGE_ERROR
    err = capsys.readouterr().err
    assert "needs the submission to grade" in err and "python grade.py" in err
    assert "SELECT" not in err


def test_help_has_no_raw_markup(capsys):
    for argv in (["--help"], ["grade", "--help"]):
        with pytest.raises(SystemExit):
            cli.main(argv)
        assert "``" not in capsys.readouterr().out
    with pytest.raises(SystemExit):
        cli.grade_py_main(["--help"], root=ROOT)
    assert "``" not in capsys.readouterr().out


def test_hidden_checks_are_labelled_once(capsys):
    cli.main(["list"])
    listing = capsys.readouterr().out
    assert "(hidden) (hidden)" not in listing
    assert "(hidden)" in listing


def test_a_partial_run_warns_that_it_replaced_the_page(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "feedback.html").write_text("the whole page")
    assert cli.main(["grade", str(REFERENCE), "lab07.ex1"]) == 0
    assert "now shows only lab07.ex1" in capsys.readouterr().err


def test_printed_output_is_mentioned_with_where_to_read_it(tmp_path):
    folder = submission_from_source(tmp_path, LAB07, (REFERENCE / f"{LAB07}.py").read_text() + """
_reference = translation_matrix
def translation_matrix(tx, ty):
    for i in range(2000):
        print("debug", i)
    return _reference(tx, ty)
""")
    result = grade(folder, ["lab07.ex1"], pictures="none")
    text = terminal_text(result, page="feedback.html")
    assert "Your code printed output in" in text and "feedback.html" in text
    assert "printed" not in terminal_text(grade(REFERENCE, ["lab07.ex1"], pictures="none"))


def test_gradescope_output_keeps_matrices_in_a_preformatted_block(tmp_path):
    folder = submission_from_source(tmp_path, LAB07, (REFERENCE / f"{LAB07}.py").read_text() + """
def translation_matrix(tx, ty):
    return np.array([[1.0, 0.5, tx], [0, 1, ty], [0, 0, 1]])
""")
    data = gradescope.run(folder, tmp_path / "r.json", CourseConfig(select=["lab07.ex1"]))
    failed = [t for t in data["tests"] if t["status"] == "failed"]
    assert failed and all(t["output_format"] == "html" for t in data["tests"])
    assert any("<pre>It returned\n[[" in t["output"] for t in failed)
