"""A course's own labs, outside the package: loaded, listed, verified, graded everywhere.

The example course is tests/data/course/: course.json names one lab folder, labs/imstats/
(lab 13, image statistics: a histogram and a contrast stretch, with a hidden check and a
mistakes table), written for these tests and written like a built-in lab.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from autograder.cli import main
from autograder.engine.labfolders import LabFolderError, forget_lab_folders, use_lab_folders
from autograder.engine.registry import discover, hide_checks, select
from autograder.engine.runner import grade
from autograder.instructor import gradescope
from autograder.instructor.bundle import write_student_bundle
from autograder.instructor.course import CourseConfig, CourseConfigError
from autograder.instructor.verify import verify_lab
from conftest import ROOT, mutant
from test_gradescope import run_container

COURSE = Path(__file__).parent / "data" / "course"
LAB = COURSE / "labs" / "imstats"
MODULE = "lab13_image_stats"
REFERENCE, SKELETON = LAB / "reference", LAB / "skeleton"
TRUNCATED = """
    def stretch(image):
        image = np.asarray(image, float)
        low, high = image.min(), image.max()
        return ((image - low) * 255.0 / (high - low)).astype(np.uint8)
    """

pytestmark = pytest.mark.xdist_group("course_labs")


@pytest.fixture(autouse=True)
def course_labs_forgotten():
    """Each test starts and ends with the built-in labs only (and nothing hidden by a course)."""
    forget_lab_folders()
    yield
    forget_lab_folders()
    hide_checks([])


def course_copy(tmp_path: Path) -> Path:
    """A copy of the example course, to change or to move."""
    target = tmp_path / "course"
    shutil.copytree(COURSE, target, ignore=shutil.ignore_patterns("__pycache__"))
    return target


# ------------------------------------------------------------------ loading
def test_the_course_config_registers_its_labs_relative_to_itself(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)   # not where the configuration is
    course = CourseConfig.load(COURSE / "course.json")
    assert course.labs == [str(LAB.resolve())]
    lab = discover()["lab13"]
    assert lab.folder == LAB.resolve() and lab.module == MODULE
    checks = {c.name: c.hidden for e in lab.exercises.values() for c in e.checks}
    assert checks["stretch of a bright narrow band"] is True          # hidden.py was loaded
    assert [e.id for e in select(["lab13"])] == ["lab13.ex1", "lab13.ex2"]
    CourseConfig.load(COURSE / "course.json")                        # loading again changes nothing
    assert discover()["lab13"] is lab
    forget_lab_folders()
    assert "lab13" not in discover()


def test_lab_folders_may_start_at_home_and_be_named_twice(tmp_path, monkeypatch):
    course = course_copy(tmp_path)
    monkeypatch.setenv("HOME", str(course))
    path = tmp_path / "elsewhere" / "course.json"
    path.parent.mkdir()
    path.write_text(json.dumps({"labs": ["~/labs/imstats", str(course / "labs" / "imstats"),
                                         "../course/labs/./imstats/"]}))
    folder = str((course / "labs" / "imstats").resolve())
    assert CourseConfig.load(path).labs == [folder]            # one folder, however it is named
    assert discover()["lab13"].folder == Path(folder)


def test_another_course_forgets_the_first_ones_labs(tmp_path):
    CourseConfig.load(COURSE / "course.json")
    other = tmp_path / "other.json"
    other.write_text("{}")
    CourseConfig.load(other)
    assert "lab13" not in discover() and "lab07" in discover()


def test_list_shows_the_course_labs(capsys):
    assert main(["list", "--course", str(COURSE / "course.json"), "--ids"]) == 0
    out = capsys.readouterr().out
    assert f"lab13  {MODULE}.py  Image statistics  (course lab: {LAB.resolve()})" in out
    assert "[lab13.ex2::stretch_bright]" in out and "stretch of a bright narrow band (hidden)" in out
    # As the course grades: its own labs only, as it selects none (a built-in lab: name it in select).
    assert "lab07" not in out


def test_list_shows_what_the_course_grades_at_its_points(tmp_path, capsys):
    """The course's selection, its points (the suite's beside them) and its hidden checks."""
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"labs": [str(LAB)], "select": ["lab13", "lab07.ex1"],
                                  "points": {"lab07.ex1": 24}, "hide": ["lab07.ex1::translate_grey"]}))
    assert main(["list", "--course", str(course)]) == 0
    out = capsys.readouterr().out
    assert "lab07.ex1       24 pts  Translation (suite: 12)" in out
    assert "translate keeps a grey image grey (hidden)" in out and "      4  translation_matrix(100, 50)" in out
    assert "lab13  " in out and "lab07.ex2" not in out and "lab08" not in out


def edit(name: str, old: str, new: str):
    """A change to a lab folder: in its file ``name``, ``old`` becomes ``new``."""
    def change(folder: Path):
        path = folder / name
        path.write_text(path.read_text().replace(old, new) if old else new)
    return change


@pytest.mark.parametrize("change, words", [
    (lambda folder: (folder / "suite.py").unlink(), ["has no suite.py", "new-lab"]),
    (shutil.rmtree, ["does not exist"]),
    (edit("suite.py", 'Lab("lab13"', 'Lab("lab07"'),
     ["suite.py, line 11", "lab07 is taken by a built-in lab", "another key"]),
    (edit("suite.py", "from . import truth", "from . import truth\nimport no_such_module"),
     ["suite.py, line 10", "ModuleNotFoundError", "no_such_module"]),
    (edit("suite.py", "from . import truth", "from . import truth\nraise ValueError('figure lab07 is registered twice')"),
     ["suite.py, line 10", "ValueError: figure lab07 is registered twice"]),   # no lab key: said as it is
    (edit("suite.py", "from . import truth", "from . import truth\nimport sys\nsys.exit(3)"),
     ["suite.py, line 11", "SystemExit: 3"]),                               # said, not a silent exit
    (edit("hidden.py", "", "def broken(:\n"), ["hidden.py, line 1", "SyntaxError"]),
    (edit("truth.py", '"""Ground truth', '1 / 0\n"""Ground truth'), ["truth.py, line 1", "ZeroDivisionError"]),
    (edit("suite.py", "", "x = 1\n"), ["registers 0 labs"]),
])
def test_a_bad_lab_folder_is_refused_saying_where_and_why(tmp_path, change, words):
    folder = course_copy(tmp_path) / "labs" / "imstats"
    change(folder)
    with pytest.raises(CourseConfigError) as raised:
        CourseConfig.load(folder.parents[1] / "course.json")
    for word in words:
        assert word in str(raised.value), str(raised.value)
    assert "lab13" not in discover() and not any(m.startswith("autograder_course_lab_") for m in sys.modules)
    assert "lab07" in discover() and discover()["lab07"].folder is None   # the built-in lab untouched


def test_two_folders_may_not_share_a_key(tmp_path):
    first = course_copy(tmp_path)
    second = tmp_path / "second"
    shutil.copytree(LAB, second)
    use_lab_folders([first / "labs" / "imstats"])
    with pytest.raises(LabFolderError, match="taken by the course lab in"):
        use_lab_folders([first / "labs" / "imstats", second])


def test_hide_makes_checks_of_a_built_in_lab_hidden_without_code(tmp_path):
    path = tmp_path / "course.json"
    lab = discover()["lab07"]
    built_in_hidden = {c.id for e in lab.exercises.values() for c in e.checks if c.hidden}
    path.write_text(json.dumps({"hide": ["lab07.ex1::translate_grey", "lab07.ex2"]}))
    CourseConfig.load(path)
    hidden = {c.id for e in lab.exercises.values() for c in e.checks if c.hidden}
    assert {"lab07.ex1::translate_grey"} | {c.id for c in lab.exercises["ex2"].checks} <= hidden
    result = grade(ROOT / "reference_solutions", ["lab07.ex1"], pictures="none")
    [at] = [i for i, c in enumerate(result.exercises[0].checks) if c.name == "translate keeps a grey image grey"]
    grey = result.for_students().exercises[0].checks[at]
    assert grey.hidden and grey.redacted and grey.passed and "grey" not in grey.name   # a verdict only
    path.write_text("{}")
    CourseConfig.load(path)      # the next course hides nothing: the checks are public again
    assert {c.id for e in lab.exercises.values() for c in e.checks if c.hidden} == built_in_hidden
    path.write_text(json.dumps({"hide": ["lab07.ex1::no_such_check"]}))
    with pytest.raises(CourseConfigError, match="no_such_check"):
        CourseConfig.load(path)


# ------------------------------------------------------------------ verify
def test_the_example_lab_is_sound_and_verify_says_so(capsys):
    assert main(["verify", "--course", str(COURSE / "course.json")]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "lab13 is sound" in out and "mistake: stretch truncated" in out
    assert "lab07" not in out      # with --course and no LAB: the course's own labs


def broken_course(tmp_path: Path) -> Path:
    """The example course with five flaws verify must find: a check no mistake fails, a
    case named as another mistake, a check whose verdict changes when graded again, one
    whose inputs do (the reference passes both), and one that crashes on a wrong answer."""
    course = course_copy(tmp_path)
    folder = course / "labs" / "imstats"
    suite = folder / "suite.py"
    suite.write_text(suite.read_text() + '''

@ex2.check("stretch returns an array", points=1)
def stretch_returns_an_array(t):
    t.expect_array(t.call("stretch", truth.dim()), "stretch(dim image)")


_GRADINGS = iter(range(10**6))


@ex1.check("histogram of a flaky grader", points=1)
def flaky(t):
    t.call("histogram", truth.scene())
    if next(_GRADINGS) % 2:
        t.fail("a different verdict on every other grading")


@ex1.check("histogram of an image drawn at random", points=1)
def unseeded(t):
    image = np.random.default_rng().integers(0, 256, (8, 8), dtype=np.uint8)
    if not np.array_equal(np.asarray(t.call("histogram", image)), truth.histogram(image)):
        t.fail("the histogram of a random image is wrong")


@ex2.check("stretch of a dim image, judged by a fragile grader", points=1)
def fragile(t):
    if np.asarray(t.call("stretch", truth.dim())).max() <= 1:
        raise KeyError("a judge that crashes on an answer it did not foresee")
''')
    mistakes = folder / "mistakes.py"
    mistakes.write_text(mistakes.read_text().replace('""", ["truncated"]),', '""", ["minimum is not subtracted"]),'))
    return course


def test_verify_finds_each_flaw_of_a_broken_lab(tmp_path, capsys, monkeypatch):
    course = broken_course(tmp_path)
    reports = []

    def verify_and_keep(*args, **kwargs):
        reports.append(verify_lab(*args, **kwargs))
        return reports[-1]

    monkeypatch.setattr("autograder.instructor.verify.verify_lab", verify_and_keep)
    assert main(["verify", "lab13", "--course", str(course / "course.json")]) == 1
    out = " ".join(capsys.readouterr().out.split())
    assert "lab13 is not sound (8 problems)" in out and "no case" in out
    [report] = reports
    problems = "\n".join(report.problems)
    assert "lab13.ex2 'stretch returns an array': no case of the mistakes table fails it" in problems
    again = "a different verdict, message or input when the reference is graded again"
    assert f"lab13.ex1 'histogram of a flaky grader': {again}" in problems
    assert f"lab13.ex1 'histogram of an image drawn at random': {again}" in problems   # passed both times
    assert "stretch truncated: not named in its own words ['minimum is not subtracted']" in problems
    assert "stretch truncated: named as another mistake" in problems and "truncated, not rounded" in problems
    # A crash on a wrong answer is no failure of it: a problem, and the check is failed by no case.
    assert ("stretch to 0..1: grader error in lab13.ex2 'stretch of a dim image, judged by a fragile grader': "
            "grader error in this check (KeyError") in problems
    assert "'stretch of a dim image, judged by a fragile grader': no case of the mistakes table fails it" in problems
    assert len(report.problems) == 8, problems   # the misnamed case: by both checks that name it


def test_a_lab_without_hidden_checks_is_not_sound():
    """Its public checks' answers, tabled, would earn every point."""
    from autograder.instructor.verify import CheckReport, LabReport

    def report(*hidden):
        checks = [CheckReport("lab13.ex1", f"check {i}", 1, h, False, 0.0, 1, True) for i, h in enumerate(hidden)]
        return LabReport("lab13", "Image statistics", (2, 2), [], (0, 2), [], [], checks)

    assert report(False, True).ok
    assert report(False, False).problems == [
        "lab13 has no hidden checks: a table of the public checks' answers would earn every point "
        "(add some to hidden.py, or hide some checks)"]


def test_verify_refuses_what_it_cannot_verify(tmp_path, capsys):
    course = course_copy(tmp_path)
    (course / "labs" / "imstats" / "mistakes.py").unlink()
    assert main(["verify", "--course", str(course / "course.json")]) == 2
    assert "has no mistakes.py" in capsys.readouterr().err
    assert main(["verify", "lab42"]) == 2
    assert "no lab lab42" in capsys.readouterr().err


@pytest.mark.parametrize("change, words", [
    (edit("mistakes.py", '"""Lab 13\'s', 'import no_such_module\n"""Lab 13\'s'),
     ["mistakes.py, line 1", "cannot be imported", "no_such_module"]),
    (edit("mistakes.py", "MISTAKES = {", "MISTAKES = {{"), ["mistakes.py, line", "SyntaxError in the mistakes table"]),
    (edit("mistakes.py", '["truncated"]', '[""]'), ["MISTAKES['stretch truncated']", "an empty fragment"]),
    (edit("mistakes.py", "            if high == low:\n", "            if high == low\n"),
     ["MISTAKES['stretch in uint8']'s source, line 4: SyntaxError"]),
    (edit("mistakes.py", '("lab13.ex1", """\n        def histogram(image, bins=256):\n            return np.histogram',
          '(["lab13.ex1"], """\n        def histogram(image, bins=256):\n            return np.histogram'),
     ['MISTAKES["np.histogram over the image\'s own range"] must be (exercise id']),
    (edit("mistakes.py", "MISTAKES = {", 'FEWER_MISTAKES = {"lab13.ex2"}\nMISTAKES = {'),
     ["mistakes.py: FEWER_MISTAKES must be a dict"]),
    (edit("mistakes.py", "MISTAKES = {", 'FEWER_MISTAKES = {"lab13.ex9": "no such exercise"}\nMISTAKES = {'),
     ["FEWER_MISTAKES names 'lab13.ex9', not an exercise of lab13"]),
])
def test_a_mistakes_table_verify_cannot_use_is_a_usage_error_saying_where(tmp_path, capsys, change, words):
    """Exit 2 before any grading, with the file and line: never a traceback, nor a case that
    "loses points" to its own SyntaxError, nor a fragment every message holds."""
    course = course_copy(tmp_path)
    change(course / "labs" / "imstats")
    assert main(["verify", "--course", str(course / "course.json")]) == 2
    err = " ".join(capsys.readouterr().err.split())
    for word in words:
        assert word in err, err


def test_new_lab_scaffolds_a_lab_that_verify_proves_sound(tmp_path, capsys):
    folder = tmp_path / "labs" / "flow"
    assert main(["new-lab", "lab14_optical_flow", "--into", str(folder)]) == 0
    assert {p.relative_to(folder).as_posix() for p in folder.rglob("*.py")} == {
        "suite.py", "hidden.py", "truth.py", "mistakes.py", "reference/lab14_optical_flow.py",
        "skeleton/lab14_optical_flow.py"}
    (tmp_path / "course.json").write_text(json.dumps({"labs": ["labs/flow"]}))
    assert main(["verify", "--course", str(tmp_path / "course.json")]) == 0
    assert "lab14 is sound" in capsys.readouterr().out
    assert discover()["lab14"].title == "Optical flow"
    assert main(["new-lab", "lab14_optical_flow", "--into", str(folder)]) == 2         # not empty
    assert main(["new-lab", "optical_flow", "--into", str(tmp_path / "other")]) == 2  # not a lab's name
    assert "lab<two digits>_<words>" in capsys.readouterr().err


def test_new_lab_refuses_a_built_in_key_and_takes_any_title(tmp_path, capsys):
    assert main(["new-lab", "lab07_flow", "--into", str(tmp_path / "a")]) == 2
    assert "lab07 is a built-in lab's key" in capsys.readouterr().err and not (tmp_path / "a").exists()
    assert main(["new-lab", "lab13_flow", "--into", str(tmp_path / "b"), "--title", "Two\nlines"]) == 2
    title = 'Lucas-Kanade\'s "flow" \\ C:\\x'
    assert main(["new-lab", "lab13_flow", "--into", str(tmp_path / "c"), "--title", title]) == 0
    [lab] = use_lab_folders([tmp_path / "c"])
    assert lab.title == title


# ------------------------------------------------------------------ graded everywhere
def test_grade_with_the_course_config(tmp_path, capsys):
    submission = mutant(tmp_path, MODULE, TRUNCATED, base=REFERENCE)
    status = main(["grade", str(submission), "lab13", "--no-html", "--config", str(COURSE / "course.json"),
                   "--json", str(tmp_path / "results.json")])
    assert status == 0
    result = json.loads((tmp_path / "results.json").read_text())
    assert [e["id"] for e in result["exercises"]] == ["lab13.ex1", "lab13.ex2"]
    stretch = result["exercises"][1]
    assert result["exercises"][0]["score"] == 5 and stretch["score"] < stretch["max_score"]
    assert any("truncated" in c["message"] for c in stretch["checks"])


def test_grade_with_the_course_config_grades_what_it_selects(tmp_path):
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"labs": [str(LAB)], "select": ["lab13.ex2"]}))
    assert main(["grade", str(REFERENCE), "--no-html", "--config", str(course),
                 "--json", str(tmp_path / "results.json")]) == 0
    result = json.loads((tmp_path / "results.json").read_text())
    assert [e["id"] for e in result["exercises"]] == ["lab13.ex2"]


def test_validate_with_the_course_config(capsys):
    assert main(["validate", str(REFERENCE), "lab13", "--config", str(COURSE / "course.json")]) == 0
    assert "lab13" in capsys.readouterr().out


@pytest.mark.slow
def test_a_batch_grades_the_course_lab(tmp_path, capsys):
    submissions = tmp_path / "class"
    for student, folder in (("ada", REFERENCE), ("bob", mutant(tmp_path / "bob", MODULE, TRUNCATED, base=REFERENCE)),
                            ("cy", SKELETON)):
        (submissions / student).mkdir(parents=True)
        shutil.copy(folder / f"{MODULE}.py", submissions / student)
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"labs": [str(LAB)], "select": ["lab13"]}))
    forget_lab_folders()   # the batch's own processes must load the lab from the course
    out = tmp_path / "out"
    assert main(["batch", str(submissions), "--out", str(out), "--course", str(course), "--workers", "2",
                 "--pictures", "none"]) == 0
    assert "3 students: 3 graded now" in " ".join(capsys.readouterr().out.split())
    totals = {s: json.loads((out / s / "results.json").read_text()) for s in ("ada", "bob", "cy")}
    assert totals["ada"]["total"] == totals["ada"]["max_total"] > 0
    assert 0 < totals["bob"]["total"] < totals["bob"]["max_total"]
    assert totals["cy"]["total"] == 0
    assert "truncated" in (out / "bob" / "feedback.html").read_text()
    assert main(["report", str(out)]) == 0      # the overview, from the gradebook's course


@pytest.mark.slow
def test_the_gradescope_zip_ships_the_course_lab_and_grades_it(tmp_path):
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"labs": [os.path.relpath(LAB, tmp_path)], "select": ["lab13"]}))
    zip_path = gradescope.build(tmp_path / "autograder.zip", CourseConfig.load(course))
    with zipfile.ZipFile(zip_path) as zf:
        names = set(zf.namelist())
        shipped = json.loads(zf.read("course.json"))
    assert {"course_labs/lab13/suite.py", "course_labs/lab13/hidden.py", "course_labs/lab13/truth.py"} <= names
    assert any(n.startswith("course_labs/lab13/reference/") for n in names)   # the error model's
    assert not any(n.startswith(("course_labs/lab13/skeleton/",
                                 "course_labs/lab13/mistakes.py", "autograder/labs/mistakes/")) for n in names)
    assert shipped["labs"] == ["course_labs/lab13"] and shipped["inputs_secret"]
    forget_lab_folders()
    results = run_container(zip_path, tmp_path, mutant(tmp_path, MODULE, TRUNCATED, base=REFERENCE))
    tests = {t["name"]: t for t in results["tests"]}
    assert all(name.startswith("lab13.") for name in tests) and len(tests) == 7
    assert tests["lab13.ex1 Histogram: histogram of a ramp with every grey level"]["status"] == "passed"
    assert any(t["status"] == "failed" and "truncated" in t["output"] for t in tests.values())
    hidden = [t for t in results["tests"] if t["visibility"] == "after_published"]
    assert len(hidden) == 2 and 0 < results["score"] < sum(t["max_score"] for t in results["tests"])


def test_no_copy_of_an_answer_ships_with_a_course_lab(tmp_path):
    """An editor's copies of the parts students never get stay behind too."""
    from autograder.engine.labfolders import ANSWERS, SKELETON
    from autograder.instructor.bundle import shipped_lab_files

    folder = course_copy(tmp_path) / "labs" / "imstats"
    for name in ("hidden.py~", "mistakes.py.bak", ".hidden.py.swp", ".git/config", "reference.py.orig",
                 "data/.notes", "__pycache__/suite.cpython-311.pyc"):
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text("an answer")
    (folder / "data" / "pattern.txt").write_text("a fixture")
    shipped = {p.relative_to(folder).as_posix() for p in shipped_lab_files(folder, ANSWERS + (SKELETON,))}
    assert shipped == {"suite.py", "truth.py", "data/pattern.txt"}


@pytest.mark.slow
def test_the_student_bundle_ships_the_skeleton_and_public_checks_only(tmp_path):
    course = CourseConfig.load(COURSE / "course.json")
    out = tmp_path / "bundle"
    files = {p.as_posix() for p in write_student_bundle(out, course=course)}
    assert f"assignments/{MODULE}.py" in files
    assert {"course_labs/lab13/suite.py", "course_labs/lab13/truth.py"} <= files
    assert not any(f.startswith(("course_labs/lab13/reference", "course_labs/lab13/skeleton",
                                 "autograder/labs/mistakes", "autograder/labs/hidden"))
                   or f in ("course_labs/lab13/hidden.py", "course_labs/lab13/mistakes.py") for f in files)
    assert (out / "assignments" / f"{MODULE}.py").read_text() == (SKELETON / f"{MODULE}.py").read_text()
    # The bundle's own grader finds the lab unasked (course_labs/ beside its package), without its hidden checks.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    run = subprocess.run([sys.executable, "grade.py", "lab13", "--no-html", "--json", "results.json"],
                         cwd=out, env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    result = json.loads((out / "results.json").read_text())
    assert result["total"] == 0 and result["max_total"] == 9      # the public checks: 12 - 3 hidden points
    assert all("not implemented yet" in c["message"] for e in result["exercises"] for c in e["checks"])
    # A course of its own labs grades those alone, in its bundle too: `python grade.py` names none (audit of
    # 2026-12-07: the bundle graded the six built-in labs beside it).
    assert json.loads((out / "course_labs" / "selection.json").read_text()) == list(course.select) == ["lab13"]
    run = subprocess.run([sys.executable, "grade.py", "--no-html", "--json", "whole.json"],
                         cwd=out, env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert {e["id"].split(".")[0] for e in json.loads((out / "whole.json").read_text())["exercises"]} == {"lab13"}
