"""The student's evening: every kind of broken submission gets a clear message naming the
file, and everything else is still graded -- locally, through the CLI, and on Gradescope."""

import io
import json
import shutil
import subprocess
import sys
import zipfile

import pytest
from rich.console import Console

from autograder import cli
from autograder.instructor import gradescope
from autograder.instructor.course import CourseConfig
from autograder.reports import html, terminal
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


def test_a_report_path_ending_in_a_slash_is_a_folder_made_when_missing(tmp_path, monkeypatch):
    """`--json out/` writes out/results.json, as --figures and --report take a folder (audit of 2026-12-07: it wrote
    a file named out)."""
    monkeypatch.chdir(tmp_path)
    assert cli.main(["grade", str(REFERENCE), "lab07.ex1", "--json", "out/", "--html", "pages/"]) == 0
    assert json.loads((tmp_path / "out" / "results.json").read_text())["exercises"][0]["id"] == "lab07.ex1"
    assert (tmp_path / "pages" / "feedback.html").is_file()


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


def test_warnings_alone_are_not_called_debugging_prints(tmp_path):
    """NumPy's "divide by zero encountered" is written by Python's warnings module, not printed by the student
    (third-party audit of 2026-12-07): the line says warnings, and asks to remove no print."""
    folder = submission_from_source(tmp_path, LAB07, (REFERENCE / f"{LAB07}.py").read_text() + """
_reference = translation_matrix
def translation_matrix(tx, ty):
    np.float64(1.0) / np.float64(0.0)
    return _reference(tx, ty)
""")
    text = " ".join(terminal_text(grade(folder, ["lab07.ex1"], pictures="none"), page="feedback.html").split())
    assert "Your code raised warnings in" in text and "feedback.html" in text, text
    assert "printed output" not in text and "remove" not in text


def test_gradescope_output_keeps_matrices_in_a_preformatted_block(tmp_path):
    folder = submission_from_source(tmp_path, LAB07, (REFERENCE / f"{LAB07}.py").read_text() + """
def translation_matrix(tx, ty):
    return np.array([[1.0, 0.5, tx], [0, 1, ty], [0, 0, 1]])
""")
    data = gradescope.run(folder, tmp_path / "r.json", CourseConfig(select=["lab07.ex1"]))
    failed = [t for t in data["tests"] if t["status"] == "failed"]
    assert failed and all(t["output_format"] == "html" for t in data["tests"])
    assert any("<pre>It returned\n[[" in t["output"] for t in failed)


# ------------------------------------------------------------------ issue 36: what a student reads
def lab07_notebook(*cells: str) -> str:
    return json.dumps({"cells": [{"cell_type": "code", "metadata": {}, "execution_count": None, "outputs": [],
                                  "source": cell} for cell in cells],
                       "metadata": {}, "nbformat": 4, "nbformat_minor": 5})


REFERENCE_07 = (REFERENCE / f"{LAB07}.py").read_text()
EX1_AND_EX2 = REFERENCE_07[:REFERENCE_07.index("def scaling_matrix")]


def test_an_exercise_not_started_in_a_notebook_is_one_line(tmp_path):
    """A notebook that does not define an exercise's functions yet gets one line for it, as a
    skeleton's stubs do, not a "not found: def ..." line per check (and the page says it once)."""
    folder = folder_with(tmp_path, {f"{LAB07}.ipynb": lab07_notebook(EX1_AND_EX2)})
    result = grade(folder, ["lab07.ex1", "lab07.ex3", "lab07.ex4"]).for_students()
    text = terminal_text(result)
    assert "· lab07.ex3: not started: scaling_matrix() and scale() are not defined yet" in text
    assert "· lab07.ex4: not started: shear_matrix() and shear() are not defined yet" in text
    assert "not found: def" not in text and "hidden check" not in text
    assert len([line for line in text.splitlines() if "lab07.ex3" in line]) == 2   # the table's row and this line
    for page in (html.render(result), html.render_selfcheck(result, "the kernel's code")):   # and check()'s
        assert page.count("not started: scaling_matrix() and scale() are not defined yet") == 1
        assert "not found: def scaling_matrix" not in page
    assert full(result, "lab07.ex1")


def test_the_left_out_note_is_whole_on_request_without_duplicates_as_written(tmp_path):
    demo = "plt.imshow(translate(img))\nplt.show()"
    cells = [EX1_AND_EX2, "%matplotlib inline\nimport matplotlib.pyplot as plt\nimg = plt.imread('photo.png')",
             demo, demo] + [f"out{i} = translate(img, {i}, 0)" for i in range(8)]
    folder = folder_with(tmp_path, {f"{LAB07}.ipynb": lab07_notebook(*cells)})
    result = grade(folder, ["lab07.ex1"])
    [note] = [n for n in result.notes if "left out at grading" in n]
    first, *listed = note.splitlines()
    assert "and 8 more (validate lists them all)" in first
    assert len(listed) == 13 and len(set(listed)) == len(listed)
    assert "cells 3, 4 `plt.show()` (plotting)" in listed, "the same statement in two cells is one line"
    assert "cell 2 `%matplotlib inline` (IPython syntax: commented out)" in listed   # as written
    assert all("get_ipython" not in line for line in listed)
    text = " ".join(terminal_text(result).split())   # the lines as one, whatever the wrapping
    assert " ".join(f"note: {first}".split()) in text and listed[-1] not in text   # the first line only
    for page in (html.render(result), html.render_selfcheck(result, "the kernel's code")):
        assert "<details><summary>all 13 listed</summary>" in page and "out7 = translate(img, 7, 0)" in page
    # check() in a kernel reads the cells as written: %matplotlib inline, not IPython's translation
    from autograder.student import selfcheck

    class Shell:
        user_ns = {"In": ["", "get_ipython().run_line_magic('matplotlib', 'inline')"]}
        history_manager = type("History", (), {"input_hist_raw": ["", "%matplotlib inline"]})()

    import IPython
    original = IPython.get_ipython
    IPython.get_ipython = lambda: Shell()
    try:
        assert selfcheck._kernel_history() == ["%matplotlib inline"]
    finally:
        IPython.get_ipython = original


def test_a_name_missing_because_its_cell_raised_names_that_cell(tmp_path):
    folder = folder_with(tmp_path, {f"{LAB07}.ipynb": lab07_notebook(
        "import numpy as np", "S = np.zeros((3, 3))\nS_INV = np.linalg.inv(S)",
        "def translation_matrix(tx, ty):\n    return S_INV @ np.array([[1.0, 0, tx], [0, 1, ty], [0, 0, 1]])")})
    result = grade(folder, ["lab07.ex1"], pictures="none")
    [check, *_] = exercise(result, "lab07.ex1").checks
    assert check.message.splitlines()[0].endswith(
        "NameError: name 'S_INV' is not defined (`S_INV` is not defined because cell 2 raised when run: "
        "`S_INV = np.linalg.inv(S)`; grading skips a statement that raises, as Jupyter goes on after a "
        "failing cell: run that cell to see its error)")


def test_validate_names_the_notebook_and_suggests_only_functions(tmp_path):
    from autograder.student.validate import validate

    folder = folder_with(tmp_path, {f"{LAB07}.ipynb": lab07_notebook(
        EX1_AND_EX2.replace("def rotate(", "def rotat("), "SCALING_MATRX = 2.0")})
    text = str(validate(folder, ["lab07.ex2", "lab07.ex3"]))
    assert f"✓ {LAB07}.ipynb: imports cleanly" in text and f"{LAB07}.py" not in text
    assert "(is rotat meant to be it?" in text
    assert "SCALING_MATRX" not in text, "a constant is never suggested as a misspelt function"


def test_check_prints_its_report_in_a_script_and_advises_in_its_own_terms(tmp_path):
    (tmp_path / f"{LAB07}.py").write_text(REFERENCE_07 + "\n_t = translation_matrix\n"
                                          "def translation_matrix(tx, ty):\n    print('debug')\n    return _t(tx, ty)\n")
    script = "from autograder import check\nreport = check('lab07.ex1')\n"
    run = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert "lab07.ex1" in run.stdout and "Translation" in run.stdout, "a script's check() prints the report"
    assert "print(report.printed())" in run.stdout and "--no-html" not in run.stdout
    # an interactive shell shows the value itself: nothing printed twice
    shell = subprocess.run([sys.executable, "-i", "-c", ""], input=script, cwd=tmp_path, capture_output=True,
                           text=True, timeout=300)
    assert "Traceback" not in shell.stderr and "Translation" not in shell.stdout + shell.stderr


def test_output_printed_during_the_graders_own_calls_is_labelled(tmp_path):
    folder = submission_from_source(tmp_path, LAB07, REFERENCE_07 + """
def rotate(image, angle_deg=45):
    print("rotating by", float(angle_deg))
    height, width = image.shape[:2]
    return _warp(image, rotation_matrix(-angle_deg, ((width - 1) / 2.0, (height - 1) / 2.0)))
""")
    result = grade(folder, ["lab07.ex2"], pictures="none")
    [check] = [c for c in exercise(result, "lab07.ex2").checks if c.name.startswith("rotate(image) by the default")]
    own, _, extra = check.output.partition("(printed during the grader's own extra calls, on other inputs:)")
    assert "rotating by 45.0" in own and "rotating by 37.0" not in own
    assert "rotating by 37.0" in extra


def test_output_of_a_propertys_other_examples_is_labelled_and_the_failing_ones_is_not(tmp_path):
    folder = submission_from_source(tmp_path, LAB07, REFERENCE_07 + """
_right = translation_matrix
def translation_matrix(tx, ty):
    print("called with", tx)
    return _right(-tx if tx > 500 else tx, ty)
""")
    result = grade(folder, ["lab07.ex1"], pictures="none")
    [check] = [c for c in exercise(result, "lab07.ex1").checks if c.name == "translation_matrix for any tx, ty"]
    assert check.score == 0
    lines = check.output.splitlines()
    assert lines[0] == "(printed during the other examples this property tried:)"
    own = [line for line in lines if line.startswith("called with")]   # not indented: the failing example's
    assert len(own) == 1 and float(own[0].split()[-1]) > 500
    assert sum(line.startswith("    called with") for line in lines) > 1


def test_public_only_on_the_instructors_copy_says_the_hidden_checks_were_left_out(monkeypatch):
    """The instructor's copy holds the hidden checks: --public-only leaves them out, it does not lack them (audit of
    2026-12-07: it told the instructor "your instructor runs them"); a student's copy has none to run."""
    from autograder.engine import registry

    result = grade(REFERENCE, ["lab07.ex1"], pictures="none", include_hidden=False)
    assert "Hidden checks were not run (--public-only)." in " ".join(terminal_text(result).split())
    monkeypatch.setattr(registry, "hidden_checks_installed", lambda: False)
    assert "Hidden checks are not part of this copy" in " ".join(terminal_text(result).split())
