"""Instructor batch grading (issue 12): a generated class graded end to end.

Most of the class grades one cheap exercise (``lab07.ex1``, 12 points) so the
whole file stays within a couple of minutes on two cores. The class holds the
kinds of work an instructor meets: correct copies of the reference solutions,
partly wrong and skeleton work, broken imports, hostile modules, notebooks,
zips, and each of the three LMS bulk-download layouts.
"""

from __future__ import annotations

import csv
import io
import json
import os
import shutil
import signal
import sqlite3
import subprocess
import sys
import textwrap
import time
import zipfile
from pathlib import Path

import pytest

from autograder.instructor.batch import exports
from autograder.instructor.batch.gradebook import Gradebook, lock_hash, submission_key
from autograder.instructor.batch.ingest import IngestError, read_class, several_students
from autograder.instructor.batch.run import run_batch
from autograder.cli import main
from autograder.instructor.course import CourseConfig
from autograder.engine.results import without_timings
from conftest import REFERENCE, ROOT, SKELETON

pytestmark = pytest.mark.slow

MODULE = "lab07_transformations"
SELECT = ["lab07.ex1"]
FULL = 12.0
COURSE = CourseConfig(select=SELECT, assignment="Lab 7")

# translate() moves the wrong way; translation_matrix itself is right (4 of 12 points).
WRONG_WAY = '''
def translate(image, tx=100, ty=50):
    return _warp(image, translation_matrix(-tx, -ty))
'''


# ------------------------------------------------------------------ the generated class
def reference() -> str:
    return (REFERENCE / f"{MODULE}.py").read_text()


def skeleton() -> str:
    return (SKELETON / f"{MODULE}.py").read_text()


def notebook(source: str) -> str:
    cells = [{"cell_type": "markdown", "metadata": {}, "source": ["# Lab 7\n"]},
             {"cell_type": "code", "metadata": {}, "execution_count": 1, "outputs": [],
              "source": ["%matplotlib inline\n", source]}]
    return json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5})


def zipped(files: dict[str, str]) -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as zf:
        for name, text in files.items():
            zf.writestr(name, text)
    return buffer.getvalue()


def write(path: Path, content) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)


def make_class(root: Path, copies: int = 8) -> dict[str, tuple[str, float | None]]:
    """A class of one entry per student; returns ``{student id: (status, lab07.ex1 points)}``."""
    expected = {}

    def student(name, files, status="graded", points=FULL):
        for relative, content in files.items():
            write(root / relative, content)
        expected[name] = (status, points)

    for i in range(copies):
        student(f"correct-{i:02d}", {f"correct-{i:02d}/{MODULE}.py": reference()})
    student("nested", {f"nested/work/labs/{MODULE}.py": reference(), "nested/work/helpers.py": "X = 1\n"})
    # (translation_matrix's two checks, and a shift past the image's size: black whichever way it goes)
    student("partly-wrong", {f"partly-wrong/{MODULE}.py": reference() + WRONG_WAY}, points=5.0)
    student("skeleton", {f"skeleton/{MODULE}.py": skeleton()}, points=0.0)
    student("broken-import", {f"broken-import/{MODULE}.py": "import numpy_but_misspelt\n" + reference()}, points=0.0)
    student("exits-at-import", {f"exits-at-import/{MODULE}.py": "import os\nos._exit(3)\n"}, points=0.0)
    student("eats-memory", {f"eats-memory/{MODULE}.py": reference()
                            + "\ndef translation_matrix(tx, ty):\n    return bytearray(2**40)\n"}, points=None)
    student("nothing-of-lab07", {"nothing-of-lab07/lab08_homographies.py": "X = 1\n"}, points=0.0)
    student("notebook-in-folder", {f"notebook-in-folder/{MODULE}.ipynb": notebook(reference())})
    student("lone-notebook", {"lone-notebook.ipynb": notebook(reference())})
    student("lone-file", {"lone-file.py": reference()})
    student("zipped", {"zipped.zip": zipped({f"zipped/{MODULE}.py": reference()})})
    student("zip-in-folder", {"zip-in-folder/upload.zip": zipped({f"{MODULE}.py": reference()})})
    student("bad-zip", {"bad-zip.zip": b"PK\x03\x04 this is not a zip"}, status="unreadable", points=None)
    student("empty-folder", {"empty-folder/README.txt": "I forgot"}, status="unreadable", points=None)
    write(root / "notes.pdf", b"%PDF-1.4")  # a stray file is listed (ignored.csv), no student
    write(root / ".DS_Store", b"\0")  # hidden files are no students
    return expected


def class_course(tmp: Path) -> Path:
    path = tmp / "course.json"
    path.write_text(json.dumps({"select": SELECT, "assignment": "Lab 7"}))
    return path


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    root = tmp_path_factory.mktemp("class")
    expected = make_class(root / "submissions")
    return root / "submissions", expected


@pytest.fixture(scope="module")
def graded(generated, tmp_path_factory):
    """The class graded once, uninterrupted, with two local workers."""
    submissions, expected = generated
    out = tmp_path_factory.mktemp("results")
    summary = run_batch(submissions, out, course=COURSE, workers=2)
    return out, summary


def comparable(out: Path) -> list[dict]:
    with Gradebook(out, readonly=True) as book:
        return without_timings(book.class_results())


def assert_same_gradebook(out: Path, reference_out: Path):
    """Both gradebooks hold the same students with the same results (timings aside)."""
    ours, theirs = comparable(out), comparable(reference_out)
    assert [s["student_id"] for s in ours] == [s["student_id"] for s in theirs]
    for a, b in zip(ours, theirs):
        assert a == b, f"{a['student_id']}: first difference at {_first_difference(a, b)}"


def _first_difference(a, b, path=""):
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if a.get(key) != b.get(key):
                return _first_difference(a.get(key), b.get(key), f"{path}.{key}")
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            if x != y:
                return _first_difference(x, y, f"{path}[{i}]")
    return f"{path}: {str(a)[:300]!r} != {str(b)[:300]!r}"


def assert_matches_expectations(students: list[dict], expected: dict):
    by_id = {s["student_id"]: s for s in students}
    assert sorted(by_id) == sorted(expected), "every entry is a student, none skipped"
    for student_id, (status, points) in expected.items():
        student = by_id[student_id]
        assert student["status"] == status, (student_id, student["reason"])
        if status == "unreadable":
            assert student["reason"], student_id
            continue
        total = student["result"]["total"]
        if points is None:
            assert total < FULL, student_id
        else:
            assert total == points, (student_id, student["result"]["exercises"])


# ------------------------------------------------------------------ the class end to end
def test_generated_class_grades_to_the_expected_gradebook(generated, graded):
    _, expected = generated
    out, summary = graded
    students = comparable(out)
    assert_matches_expectations(students, expected)
    readable = [s for s, (status, _) in expected.items() if status == "graded"]
    assert summary.graded == len(readable) and not summary.failed
    assert len(summary.unreadable) == 2
    assert [line.split(":")[0] for line in summary.ignored] == ["notes.pdf"]
    assert list(csv.reader((out / "ignored.csv").open()))[1][0] == "notes.pdf"
    by_id = {s["student_id"]: s for s in students}
    assert "no .py or .ipynb" in by_id["empty-folder"]["reason"]
    assert "zip" in by_id["bad-zip"]["reason"]
    messages = " ".join(c["message"] for e in by_id["broken-import"]["result"]["exercises"] for c in e["checks"])
    assert "numpy_but_misspelt" in messages
    for student_id in readable:
        page = (out / student_id / "feedback.html").read_text()
        assert "<html" in page
        data = json.loads((out / student_id / "results.json").read_text())
        assert data["exercises"][0]["id"] == "lab07.ex1"
        assert all(c["artifacts"] == [] for e in data["exercises"] for c in e["checks"]), "no base64 pictures"
    # the failing student's page has its pictures, the gradebook none
    assert "data:image/png;base64" in (out / "partly-wrong" / "feedback.html").read_text()
    assert b"base64" not in (out / "gradebook.sqlite").read_bytes()


def test_rerun_grades_nothing_and_regrade_grades_everything(generated, graded, tmp_path):
    submissions, expected = generated
    out, _ = graded
    before = comparable(out)
    again = run_batch(submissions, out, course=COURSE, workers=2)
    assert again.graded == 0 and again.reused == len([1 for s, _ in expected.values() if s == "graded"])
    assert comparable(out) == before
    with Gradebook(out) as book:
        assert set(book.grading_counts().values()) == {1}


def test_a_changed_submission_alone_is_graded_again(generated, tmp_path):
    submissions, _ = generated
    small = tmp_path / "small"
    for name in ("correct-00", "skeleton"):
        write(small / name / f"{MODULE}.py", (submissions / name / f"{MODULE}.py").read_text())
    out = tmp_path / "out"
    run_batch(small, out, course=COURSE, workers=1)
    write(small / "skeleton" / f"{MODULE}.py", reference())
    summary = run_batch(small, out, course=COURSE, workers=1)
    assert (summary.graded, summary.reused) == (1, 1)
    regraded = run_batch(small, out, course=COURSE, workers=1, regrade=True)
    assert regraded.graded == 2
    by_id = {s["student_id"]: s for s in comparable(out)}
    assert by_id["skeleton"]["result"]["total"] == FULL


def test_an_interrupted_regrade_resumes_where_it_stopped(tmp_path, monkeypatch):
    """Ctrl-C half way through a --regrade: the same command again grades only what the regrade had left, and so
    does a plain run (audit of 2026-12-07: the same command started the regrade over, a plain run regraded none)."""
    from autograder.instructor.batch import run as batch_run

    small = tmp_path / "small"
    for name in ("ann", "bo", "cy"):
        write(small / name / f"{MODULE}.py", reference())
    out = tmp_path / "out"
    run_batch(small, out, course=COURSE, workers=1)
    grade_locally = batch_run._grade_locally

    def stopped_after_one(todo, arguments, finished, workers, rules, running=None):
        grade_locally(todo[:1], arguments, finished, workers, rules, running=running)
        raise KeyboardInterrupt

    monkeypatch.setattr(batch_run, "_grade_locally", stopped_after_one)
    with pytest.raises(KeyboardInterrupt):
        run_batch(small, out, course=COURSE, workers=1, regrade=True)
    monkeypatch.setattr(batch_run, "_grade_locally", grade_locally)
    resumed = run_batch(small, out, course=COURSE, workers=1, regrade=True)
    assert (resumed.graded, resumed.reused) == (2, 1)
    assert any("an interrupted regrade resumed: 2" in w for w in resumed.warnings)
    with Gradebook(out) as book:
        assert sorted(book.grading_counts().values()) == [2, 2, 2]
    assert run_batch(small, out, course=COURSE, workers=1).graded == 0   # (done: nothing left)
    assert run_batch(small, out, course=COURSE, workers=1, regrade=True).graded == 3   # (a new regrade: all)


def test_sigkill_half_way_then_restart_equals_an_uninterrupted_run(generated, graded, tmp_path):
    submissions, expected = generated
    reference_out, _ = graded
    out = tmp_path / "killed"
    command = [sys.executable, "-m", "autograder", "batch", str(submissions), "--out", str(out),
               "--workers", "2", "--course", str(class_course(tmp_path))]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True,
                               cwd=ROOT)
    deadline = time.monotonic() + 120
    try:
        while _gradings(out) < 6:
            assert process.poll() is None, process.stderr.read().decode()
            assert time.monotonic() < deadline, "the batch graded too little in two minutes"
            time.sleep(0.1)
    finally:
        os.killpg(process.pid, signal.SIGKILL)   # the coordinator and its pool, mid-grading
        process.wait()
    done_before = _gradings(out)
    readable = [s for s, (status, _) in expected.items() if status == "graded"]
    assert done_before < len(readable), "killed before the end"
    run_batch(submissions, out, course=COURSE, workers=2)
    assert_same_gradebook(out, reference_out)
    with Gradebook(out) as book:
        counts = book.grading_counts()
    assert set(counts.values()) == {1}, "no submission graded twice"
    assert len(counts) == len(readable)


def test_dask_cluster_losing_a_worker_gives_the_same_gradebook_as_local(generated, graded, tmp_path):
    distributed = pytest.importorskip("distributed", reason="the dask extra (distributed) is not installed")
    submissions, expected = generated
    reference_out, _ = graded
    # A part of the class (the cluster's start-up is the slow part), compared student by student.
    part = ["correct-00", "correct-01", "partly-wrong", "skeleton", "broken-import", "exits-at-import",
            "eats-memory", "lone-notebook", "zipped", "bad-zip"]
    subset = tmp_path / "part"
    subset.mkdir()
    for item in submissions.iterdir():
        if item.name.split(".")[0] in part:
            (shutil.copytree if item.is_dir() else shutil.copy)(item, subset / item.name)
    out = tmp_path / "dask"
    killed = []
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, distributed.Client(cluster) as client:
        pids = client.run(os.getpid)

        def kill_a_busy_worker(event, entry, summary):
            # After the first result, SIGKILL a worker in the middle of a grading: the
            # scheduler must hand its submissions to another worker.
            if event == "done" and not killed:
                busy = [w for w, tasks in client.processing().items() if tasks] or list(pids)
                killed.append(busy[0])
                os.kill(pids[busy[0]], signal.SIGKILL)

        summary = run_batch(subset, out, course=COURSE, dask_scheduler=cluster.scheduler_address,
                            progress=kill_a_busy_worker)
    assert killed
    assert not summary.failed
    assert summary.graded == len(part) - 1
    local = {s["student_id"]: s for s in comparable(reference_out)}
    on_dask = comparable(out)
    assert [s["student_id"] for s in on_dask] == sorted(part)
    for student in on_dask:
        assert student == local[student["student_id"]], _first_difference(student, local[student["student_id"]])
    with Gradebook(out) as book:
        assert set(book.grading_counts().values()) == {1}


def _gradings(out: Path) -> int:
    try:
        with sqlite3.connect(out / "gradebook.sqlite", timeout=5) as db:
            return db.execute("SELECT COUNT(*) FROM gradings").fetchone()[0]
    except sqlite3.Error:
        return 0


def test_grades_csv_and_lms_imports_parse_with_the_documented_headers(generated, graded):
    out, _ = graded
    rows = list(csv.reader((out / "grades.csv").open(newline="")))
    assert rows[0] == ["Student ID", "Name", "Status", "lab07.ex1", "Late penalty", "Adjustments", "Total"]
    by_id = {r[0]: r for r in rows[1:]}
    assert by_id["correct-00"][-1] == "12" and by_id["partly-wrong"][-1] == "5"
    assert by_id["bad-zip"][2].startswith("could not be read: ")
    canvas = list(csv.reader((out / "canvas_import.csv").open(newline="")))
    assert canvas[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "Lab 7"]
    assert canvas[1] == ["Points Possible", "", "", "", "", "12"]
    assert not (out / "moodle_import.csv").exists()   # no Moodle download, no Moodle roster
    assert len(canvas) - 2 == len(rows) - 1 == len(generated[1])


def test_cli_batch_then_grade_refuses_the_class_folder(generated, tmp_path, capsys):
    submissions, _ = generated
    small = tmp_path / "class"
    for name in ("correct-00", "correct-01"):
        write(small / name / f"{MODULE}.py", reference())
    write(small / "dave" / "submission.zip", zipped({f"{MODULE}.py": reference()}))
    # hangs in translate(): stopped by its own time limit, the batch goes on
    write(small / "hangs" / f"{MODULE}.py",
          reference() + "\ndef translate(image, tx=100, ty=50):\n    while True:\n        pass\n")
    assert main(["grade", str(small), "lab07.ex1", "--no-html"]) == 2
    assert "autograder batch" in " ".join(capsys.readouterr().out.split())
    out = tmp_path / "out"
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"select": SELECT, "call_timeout": 1.5}))
    assert main(["batch", str(small), "--out", str(out), "--course", str(course),
                 "--workers", "2", "--pictures", "none"]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "4 students: 4 graded now" in printed and "0 failed" in printed
    assert "data:image/png" not in (out / "dave" / "feedback.html").read_text()
    hangs = json.loads((out / "hangs" / "results.json").read_text())
    assert hangs["total"] == 4.0
    with Gradebook(out, readonly=True) as book:   # the instructor's whole grading (hidden checks too)
        [row] = [s for s in book.class_results() if s["student_id"] == "hangs"]
    assert any("timed out" in c["message"] for c in row["result"]["exercises"][0]["checks"])


# ------------------------------------------------------------------ grade's guard
@pytest.mark.parametrize("layout, refused", [
    ({"a/lab07_transformations.py": "", "b/lab07_transformations.py": ""}, True),
    ({"a/lab07_transformations.py": "", "b/sub.zip": b"PK"}, True),
    ({"lab07_transformations.py": "", "lab07_transformations.ipynb": "{}"}, False),
    ({"lab07/lab07_transformations.py": "", "lab08/lab08_homographies.py": ""}, False),
    ({"lab07_transformations.py": "", "helpers.py": ""}, False),
    ({"smithjohn_12_34_lab07_transformations.py": "", "doejane_LATE_13_35_lab07_transformations.py": ""}, True),
    ({"submission_metadata.yml": "{}", "submission_1/lab07_transformations.py": ""}, True),
])
def test_grade_refuses_a_folder_of_several_students(tmp_path, layout, refused):
    for name, content in layout.items():
        write(tmp_path / "folder" / name, content)
    message = several_students(tmp_path / "folder", [MODULE, "lab08_homographies"])
    assert bool(message) == refused, message
    if refused:
        assert "autograder batch" in message


@pytest.mark.parametrize("layout, refused", [
    ({"a/lab07_transformations.py": "", "b/lab07_transformations.py": ""}, True),
    ({"smithjohn_12_34_lab07_transformations.py": "", "doejane_LATE_13_35_lab07_transformations.py": ""}, True),
    ({"lab07_transformations.py": "", "helpers.py": ""}, False),
])
def test_grade_refuses_a_class_handed_over_as_a_zip(tmp_path, layout, refused, capsys):
    """An LMS's bulk download is a zip as often as a folder: `autograder grade class.zip` refuses it as it refuses
    the folder (audit of 2026-12-07: it graded one student's file of the class)."""
    import zipfile

    archive = tmp_path / "class.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        for name, content in layout.items():
            zf.writestr(name, content or "def translation_matrix(tx, ty):\n    raise NotImplementedError\n")
    code = main(["grade", str(archive), "lab07.ex1", "--no-html"])
    said = " ".join(capsys.readouterr().out.split())
    assert (code == 2) == refused, said
    if refused:
        assert "class.zip" in said and "autograder batch" in said, said


def test_the_repository_folders_are_single_submissions():
    modules = [p.stem for p in REFERENCE.glob("lab*.py")]
    assert several_students(REFERENCE, modules) is None
    assert several_students(SKELETON, modules) is None


# ------------------------------------------------------------------ LMS layouts
GRADESCOPE_METADATA = """\
submission_101:
  :submitters:
  - :name: Ada Lovelace
    :sid: 'S001'
    :email: ada@uni.edu
  :created_at: 2026-03-01 22:00:00.123456000 +01:00
  :score: 0.0
submission_102:
  :submitters:
  - :name: Alan Turing
    :sid: 'S002'
    :email: alan@uni.edu
  - :name: Grace Hopper
    :sid: 'S003'
    :email: grace@uni.edu
  :created_at: 2026-03-03 09:30:00.000000000 +01:00
submission_103:
  :submitters:
  - :name: Emmy Noether
    :sid: 'S004'
  :created_at: 2026-03-01 10:00:00.000000000 +01:00
"""


def test_gradescope_export_with_a_group_and_a_late_submission(tmp_path):
    export = tmp_path / "assignment_1_export"
    write(export / "submission_metadata.yml", GRADESCOPE_METADATA)
    write(export / "submission_101" / f"{MODULE}.py", reference())
    write(export / "submission_102" / "lab7" / f"{MODULE}.py", reference() + WRONG_WAY)
    write(export / "submission_999" / f"{MODULE}.py", reference())   # not in the metadata
    archive = tmp_path / "export.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        for path in export.rglob("*"):
            zf.write(path, path.relative_to(tmp_path))
    course = CourseConfig(select=SELECT, assignment="Lab 7",
                          late_penalty={"due": "2026-03-01T23:59:00+01:00", "per_day": 10, "max": 50})
    overrides = tmp_path / "overrides.csv"
    overrides.write_text("student,exercise,points,penalty,comment\ngrace@uni.edu,total,1,,presented in class\n")
    out = tmp_path / "out"
    summary = run_batch(archive, out, course=course, workers=2, overrides=overrides)
    by_id = {s["student_id"]: s for s in comparable(out)}
    assert sorted(by_id) == ["ada-lovelace-s001", "alan-turing-s002", "emmy-noether-s004"]
    ada, group = by_id["ada-lovelace-s001"], by_id["alan-turing-s002"]
    assert ada["result"]["total"] == FULL and ada["lms"]["sid"] == "S001"
    assert [m["name"] for m in group["members"]] == ["Alan Turing", "Grace Hopper"]
    assert group["result"]["total"] == 5.0 and group["submitted_at"].startswith("2026-03-03T09:30")
    assert by_id["emmy-noether-s004"]["status"] == "unreadable"    # in the metadata, no folder
    assert summary.ignored == ["submission_999: not listed in submission_metadata.yml; not graded"]
    assert len(summary.unreadable) == 1
    grades = {r["Student ID"]: r for r in csv.DictReader((out / "grades.csv").open())}
    assert grades["alan-turing-s002"]["Late penalty"] == "1"       # 2 days late: 20% of 5 points
    assert grades["alan-turing-s002"]["Adjustments"] == "1"         # a member's override is the group's
    assert grades["alan-turing-s002"]["Total"] == "5"
    assert grades["ada-lovelace-s001"]["Total"] == "12"           # on time
    canvas = list(csv.DictReader((out / "canvas_import.csv").open()))
    assert [r["SIS User ID"] for r in canvas if r["Lab 7"] == "5"] == ["S002", "S003"]  # both group members
    assert "Instructor adjustments" in (out / "alan-turing-s002" / "feedback.html").read_text()


def test_canvas_download_groups_files_strips_prefixes_and_undoes_renaming(tmp_path):
    download = tmp_path / "submissions"
    write(download / f"smithjohn_1234_5678_{MODULE}.py", reference())
    write(download / "smithjohn_1234_5678_helpers.py", "X = 1\n")
    write(download / f"doejane_LATE_2345_6789_{MODULE}.py", skeleton())        # first upload
    write(download / f"doejane_LATE_2345_6789_{MODULE}-1.py", reference())     # re-upload: Canvas renamed it
    write(download / "leeann_3456_7890_Lab7.zip", zipped({f"Lab7/{MODULE}.py": reference() + WRONG_WAY}))
    write(download / "readme.txt", "instructions")   # no Canvas name: listed, never a student
    entries = {e.student_id: e for e in read_class(download, [MODULE])}
    assert sorted(entries) == ["doejane-2345", "leeann-3456", "smithjohn-1234"]
    assert sorted(entries["smithjohn-1234"].files) == ["helpers.py", f"{MODULE}.py"]
    assert entries["doejane-2345"].files == {f"{MODULE}.py": reference().encode()}
    assert entries["doejane-2345"].late is True and entries["smithjohn-1234"].late is False
    assert entries["smithjohn-1234"].lms == {"canvas_user_id": "1234", "canvas_submission_id": "5678"}

    roster = tmp_path / "roster.csv"
    roster.write_text("Student,ID,SIS User ID,SIS Login ID,Section,Lab 7\n"
                      "    Points Possible,,,,,12\n"
                      "\"Smith, John\",1234,S1,jsmith,A,\n"
                      "\"Doe, Jane\",2345,S2,jdoe,B,\n"
                      "\"Nobody, Ned\",4567,S4,nned,B,\n")
    overrides = tmp_path / "overrides.csv"
    overrides.write_text("student,exercise,points,penalty,comment\n"
                         "leeann-3456,lab07.ex1,10,,regraded by hand: the sign convention was explained\n"
                         "jdoe,late,0,,extension granted\n")
    course = CourseConfig(select=SELECT, assignment="Lab 7", points={"lab07": 20},
                          late_penalty={"per_day": 25})
    out = tmp_path / "out"
    summary = run_batch(download, out, course=course, workers=2, roster=roster, overrides=overrides)
    assert not summary.warnings
    grades = {r["Student ID"]: r for r in csv.DictReader((out / "grades.csv").open())}
    assert grades["smithjohn-1234"]["Total"] == "20"                  # 12 of 12 scaled to 20
    assert grades["doejane-2345"]["Late penalty"] == "0"              # _LATE_, waived by the override
    assert grades["leeann-3456"]["lab07.ex1"] == "10" and grades["leeann-3456"]["Total"] == "10"
    assert grades[""]["Status"] == "no submission"                    # Ned: on the roster only
    canvas = {r["ID"]: r for r in csv.DictReader((out / "canvas_import.csv").open())}
    assert canvas["1234"]["Student"] == "Smith, John" and canvas["1234"]["SIS Login ID"] == "jsmith"
    assert canvas["3456"]["Lab 7"] == "10"
    unmatched = list(csv.DictReader((out / "roster_unmatched.csv").open()))
    assert {r["Name"] for r in unmatched} == {"leeann", "Nobody, Ned"}
    assert summary.ignored == ["readme.txt: not named like a Canvas download (name_userid_submissionid_file); "
                               "not graded"]
    page = (out / "leeann-3456" / "feedback.html").read_text()
    assert "regraded by hand" in page
    # the overrides are kept in the gradebook: a later run without --overrides still applies them
    assert run_batch(download, out, course=course, workers=2, roster=roster).graded == 0
    grades = {r["Student ID"]: r for r in csv.DictReader((out / "grades.csv").open())}
    assert grades["leeann-3456"]["Total"] == "10"
    assert page.count("Instructor adjustments") == (out / "leeann-3456" / "feedback.html").read_text().count(
        "Instructor adjustments") == 1
    # a page lost since is written again from the gradebook, adjustments and all (its pictures are gone)
    assert "data:image/" in page
    (out / "leeann-3456" / "feedback.html").unlink()
    assert run_batch(download, out, course=course, workers=2, roster=roster).graded == 0
    page = (out / "leeann-3456" / "feedback.html").read_text()
    assert "regraded by hand" in page and "lab07.ex1" in page and "data:image/" not in page


def test_moodle_download_zipped_with_file_and_online_text_folders(tmp_path):
    download = tmp_path / "moodle"
    write(download / "Ann Lee_501_assignsubmission_file_" / f"{MODULE}.py", reference())
    write(download / "Bo Chen_502_assignsubmission_file_" / "lab7.zip", zipped({f"{MODULE}.py": skeleton()}))
    write(download / "Bo Chen_502_assignsubmission_onlinetext_" / "onlinetext.html", "<p>see the zip</p>")
    write(download / "Cy Dee_503_assignsubmission_onlinetext_" / "onlinetext.html", "<p>no file</p>")
    archive = tmp_path / "moodle.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        for path in download.rglob("*"):
            zf.write(path, path.relative_to(download))
    out = tmp_path / "out"
    run_batch(archive, out, course=COURSE, workers=2)
    by_id = {s["student_id"]: s for s in comparable(out)}
    assert sorted(by_id) == ["ann-lee-501", "bo-chen-502", "cy-dee-503"]
    assert by_id["ann-lee-501"]["result"]["total"] == FULL
    assert by_id["bo-chen-502"]["result"]["total"] == 0.0
    assert by_id["cy-dee-503"]["status"] == "unreadable"
    moodle = {r["Identifier"]: r for r in csv.DictReader((out / "moodle_import.csv").open())}
    assert moodle["Participant 501"]["Grade"] == "12" and moodle["Participant 501"]["Full name"] == "Ann Lee"
    assert moodle["Participant 503"]["Grade"] == "0"


# ------------------------------------------------------------------ keys
def test_the_gradebook_key_changes_with_student_content_grader_lock_and_selection():
    key = submission_key("alice", "abc", "lab07.ex1", "0.1.0", "lock")
    assert key == submission_key("alice", "abc", "lab07.ex1", "0.1.0", "lock")
    assert len({key, submission_key("bob", "abc", "lab07.ex1", "0.1.0", "lock"),
                submission_key("alice", "abd", "lab07.ex1", "0.1.0", "lock"),
                submission_key("alice", "abc", "lab07.ex1", "0.2.0", "lock"),
                submission_key("alice", "abc", "lab07.ex1", "0.1.0", "lock2"),
                submission_key("alice", "abc", "lab07", "0.1.0", "lock")}) == 6
    assert lock_hash() == lock_hash()


def test_overrides_file_errors_are_reported(tmp_path):
    path = tmp_path / "o.csv"
    path.write_text("student,exercise,points,penalty,comment\nalice,lab07.ex1,1,2,both\n")
    with pytest.raises(exports.ExportError, match="exactly one"):
        exports.read_overrides(path)
    path.write_text("student,exercise,points,penalty,comment\nalice,lab07.ex1,lots,,\n")
    with pytest.raises(exports.ExportError, match="not a number"):
        exports.read_overrides(path)


# ------------------------------------------------------------------ reading entries safely
def test_links_in_a_student_folder_are_not_followed(tmp_path):
    secret = tmp_path / "grader_secret.py"
    secret.write_text("ANSWER = 42\n")
    write(tmp_path / "class" / "alice" / f"{MODULE}.py", reference())
    (tmp_path / "class" / "alice" / "answers.py").symlink_to(secret)
    [alice] = read_class(tmp_path / "class", [MODULE])
    assert sorted(alice.files) == [f"{MODULE}.py"]


def test_results_inside_the_submissions_folder_are_refused(tmp_path):
    write(tmp_path / "class" / "alice" / f"{MODULE}.py", reference())
    with pytest.raises(IngestError, match="inside"):
        run_batch(tmp_path / "class", tmp_path / "class" / "results", course=COURSE, workers=1)


def test_ids_are_stable_slugs_and_unique(tmp_path):
    write(tmp_path / "class" / "Élodie Durand" / f"{MODULE}.py", reference())
    write(tmp_path / "class" / "elodie durand.py", reference())
    ids = [e.student_id for e in read_class(tmp_path / "class", [MODULE])]
    assert ids == ["elodie-durand", "elodie-durand-2"]
    assert ids == [e.student_id for e in read_class(tmp_path / "class", [MODULE])]


def test_one_batch_at_a_time_writes_a_results_folder(tmp_path):
    import fcntl

    write(tmp_path / "class" / "alice" / f"{MODULE}.py", reference())
    (tmp_path / "out").mkdir()
    with open(tmp_path / "out" / ".batch.lock", "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX)
        with pytest.raises(IngestError, match="another autograder batch"):
            run_batch(tmp_path / "class", tmp_path / "out", course=COURSE, workers=1)


def test_batch_refuses_a_class_where_student_code_cannot_be_confined(tmp_path, monkeypatch, capsys):
    """On a machine without namespaces one submission could read the others: refused
    unless the instructor says so, before anything is graded."""
    from autograder.sandbox import confine
    from autograder.instructor.batch.run import Unconfined

    class Unconfining:
        level = "process-group"

    monkeypatch.setattr(confine, "detect", lambda: Unconfining())
    monkeypatch.setattr(confine, "shortfall", lambda confinement: "")   # (no namespaces here: nothing stronger works)
    students = tmp_path / "class"
    (students / "alice").mkdir(parents=True)
    shutil.copy(SKELETON / "lab07_transformations.py", students / "alice")
    with pytest.raises(Unconfined, match="--allow-unconfined"):
        run_batch(students, tmp_path / "results", course=CourseConfig(select=["lab07.ex1"]), workers=1)
    assert not (tmp_path / "results" / "gradebook.sqlite").exists()
    # where no namespaced level is even available, refused before the class is read at all
    monkeypatch.setattr(confine, "strongest_candidate", lambda: Unconfining())
    with pytest.raises(Unconfined):
        run_batch(tmp_path / "not-read", tmp_path / "results", course=CourseConfig(select=["lab07.ex1"]))
    assert main(["batch", str(students), "--out", str(tmp_path / "results")]) == 2
    assert "cannot confine student code" in capsys.readouterr().out


def test_a_batch_forced_to_the_weakest_level_is_not_told_the_machine_cannot_confine(tmp_path, monkeypatch, capsys):
    """AUTOGRADER_CONFINEMENT=process-group where namespaces work: the refusal says what forced the level, as
    grade.py does, not that the machine cannot confine (audit of 2026-12-07)."""
    from autograder.sandbox import confine

    monkeypatch.delenv("AUTOGRADER_CONFINEMENT", raising=False)
    if confine.strongest_candidate().level == "process-group":
        pytest.skip("no namespaced level on this machine")
    monkeypatch.setenv("AUTOGRADER_CONFINEMENT", "process-group")
    students = tmp_path / "class"
    (students / "alice").mkdir(parents=True)
    shutil.copy(SKELETON / "lab07_transformations.py", students / "alice")
    assert main(["batch", str(students), "--out", str(tmp_path / "results")]) == 2
    said = " ".join(capsys.readouterr().out.split())
    assert "AUTOGRADER_CONFINEMENT=process-group forces it" in said and "cannot confine" not in said, said


def test_reports_and_pictures_beside_the_code_are_never_read_and_links_never_followed(tmp_path):
    """Students hand in reports with their code: a 60 MB PDF costs nothing and refuses
    nothing; a link to a file outside the student's folder is not read."""
    secret = tmp_path / "instructor-only.py"
    secret.write_text("ANSWERS = 42\n")
    ada = tmp_path / "class" / "ada"
    ada.mkdir(parents=True)
    shutil.copy(SKELETON / "lab07_transformations.py", ada)
    with open(ada / "report.pdf", "wb") as f:
        f.truncate(60 * 2**20)   # sparse: nothing is written, and nothing must be read
    (ada / "helper.py").symlink_to(secret)
    [entry] = read_class(tmp_path / "class", ["lab07_transformations"], ["lab07_transformations"])
    assert not entry.error
    assert set(entry.files) == {"lab07_transformations.py"}


def test_each_batch_of_a_program_grades_in_its_own_environment(tmp_path, monkeypatch):
    """A program running several batches: the gradings of each see the environment it runs
    in (here, the store of ground truth they fill), not the one the first batch ran in."""
    students = tmp_path / "class"
    write(students / "alice" / f"{MODULE}.py", reference())
    course = CourseConfig(select=["lab07.ex5"])   # ground truth: photos, kept in the store
    run_batch(students, tmp_path / "first", course=course, workers=1)
    monkeypatch.setenv("AUTOGRADER_CACHE_DIR", str(tmp_path / "store"))
    run_batch(students, tmp_path / "second", course=course, workers=1)
    assert any(path.is_file() for path in (tmp_path / "store").rglob("*"))


def test_the_grading_processes_fork_from_a_single_threaded_server():
    """Forking a process with other threads may copy a lock another thread holds: the server
    the gradings fork from starts no thread (NumPy's OpenBLAS would, unless told), even for
    a program that calls the batch without the command line's settings."""
    if not Path("/proc/self/task").is_dir():
        pytest.skip("no /proc here to count a process's threads")
    probe = textwrap.dedent("""
        import os, time
        from multiprocessing import forkserver
        from autograder.instructor.batch.task import grading_processes
        grading_processes()
        server = getattr(forkserver._forkserver, "_forkserver_pid", None)  # private: the only way to find it
        if server is None:
            raise SystemExit("no server pid")
        deadline = time.monotonic() + 20
        while "cv2" not in open(f"/proc/{server}/maps").read() and time.monotonic() < deadline:
            time.sleep(0.05)  # the server imports the grader (NumPy, OpenCV) first
        time.sleep(0.5)
        print(len(os.listdir(f"/proc/{server}/task")), "OPENBLAS_NUM_THREADS" in os.environ)
        """)
    environment = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    run = subprocess.run([sys.executable, "-c", probe], env=environment, capture_output=True, text=True,
                         timeout=60, cwd=ROOT)
    if "no server pid" in run.stderr:
        pytest.skip("this Python's multiprocessing does not say which process is the fork server")
    assert run.stdout.split() == ["1", "False"], run.stderr  # one thread; the caller's environment kept


@pytest.mark.parametrize("name, module, error", [
    ("lab07_transformations (1).py", "lab07_transformations (1).py", ""),   # plainly meant: graded with a note
    ("Lab08_Homographies.py", "Lab08_Homographies.py", ""),
    ("alice.py", "alice.py", "named after no lab module"),                 # several labs: which one is unknown
])
def test_a_lone_file_plainly_meant_as_a_module_is_graded_as_grade_would(tmp_path, name, module, error):
    """A batch grades each submission as `autograder grade` would: a single file whose name was plainly meant as a
    module is left for the grading to find, with its note (audit of 2026-12-07: the batch called it unreadable when
    several labs were graded)."""
    write(tmp_path / "class" / "xi" / name, "x = 1\n")
    [entry] = read_class(tmp_path / "class", [MODULE, "lab08_homographies"], [MODULE, "lab08_homographies"])
    assert (error in entry.error) if error else not entry.error, entry.error
    assert list(entry.files) == [module]


def test_a_lone_file_meant_for_another_lab_is_not_taken_for_the_one_graded(tmp_path):
    write(tmp_path / "class" / "xi" / "Lab08_Homographies.py", "x = 1\n")
    [entry] = read_class(tmp_path / "class", [MODULE], [MODULE, "lab08_homographies"])
    assert list(entry.files) == ["Lab08_Homographies.py"]
