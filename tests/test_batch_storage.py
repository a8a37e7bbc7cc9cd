"""The batch's storage faults (issue 24): a full disk, a read-only or deleted results
folder, a damaged gradebook, an export that cannot be written.

Each fault stops the batch with one :class:`StorageError` naming the file and saying
what to do (the command line: one line on stderr, exit status 1, no traceback);
once the fault is fixed, the same command gives exactly the grades of a run that
never met it, with nothing graded twice. Faults are injected at the write boundary
(``tempfile.mkstemp``, which every file the batch writes goes through) and, where this
process may mount a small file system of its own (root), met for real on a tmpfs that
is full or read-only. A small class graded on ``lab07.ex1`` keeps each run to seconds.
"""

from __future__ import annotations

import contextlib
import csv
import errno
import json
import os
import shutil
import sqlite3
import subprocess
import tempfile
from pathlib import Path

import pytest

from autograder.instructor import gradescope
from autograder.instructor.batch.gradebook import SCHEMA_VERSION, Gradebook, StorageError
from autograder.instructor.batch.run import run_batch
from autograder.cli import STORAGE_ERROR, main
from autograder.instructor.course import CourseConfig
from autograder.engine.results import without_timings
from test_batch import COURSE, MODULE, WRONG_WAY, assert_same_gradebook, comparable, reference, skeleton, write

pytestmark = pytest.mark.slow

CLASS = {"ada": reference(), "bo": reference() + WRONG_WAY, "cy": skeleton(),
         "di": "import numpy_but_misspelt\n" + reference()}
GRADED = sorted(CLASS)


# ------------------------------------------------------------------ the class and its uninterrupted run
def make_class(root: Path, names=GRADED) -> Path:
    for name in names:
        write(root / name / f"{MODULE}.py", CLASS[name])
    return root


@pytest.fixture(scope="module")
def submissions(tmp_path_factory) -> Path:
    return make_class(tmp_path_factory.mktemp("storage") / "class")


@pytest.fixture(scope="module")
def uninterrupted(submissions, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("uninterrupted") / "results"
    summary = run_batch(submissions, out, course=COURSE, workers=2)
    assert summary.graded == len(GRADED) and not summary.failed
    return out


def assert_same_as_uninterrupted(out: Path, reference_out: Path) -> None:
    """The gradebook, every export and every student's files as an uninterrupted run left them,
    and no submission graded twice."""
    assert_same_gradebook(out, reference_out)
    exports = sorted(p.name for p in reference_out.glob("*.csv"))
    assert {"grades.csv", "canvas_import.csv"} <= set(exports)
    assert sorted(p.name for p in out.glob("*.csv")) == exports
    for name in exports:
        assert (out / name).read_text() == (reference_out / name).read_text(), name
    assert (out / "index.html").is_file()
    for student in GRADED:
        assert "<html" in (out / student / "feedback.html").read_text()
        ours, theirs = (json.loads((folder / student / "results.json").read_text()) for folder in (out, reference_out))
        assert without_timings(ours) == without_timings(theirs), student
    with Gradebook(out, readonly=True) as book:
        counts = book.grading_counts()
    assert sorted(counts.values()) == [1] * len(GRADED), "nothing graded twice"
    assert not list(out.rglob("*.tmp")), "no temporary file left behind"


def copy_results(reference_out: Path, to: Path) -> Path:
    shutil.copytree(reference_out, to)
    return to


# ------------------------------------------------------------------ faults at the write boundary
@contextlib.contextmanager
def failing_writes(monkeypatch, target: str, error: int = errno.ENOSPC, after: int = 0):
    """Every file whose name is ``target`` fails to be written (``error``) from its
    ``after``-th write on: what a disk filling up, or a folder turned read-only, does."""
    real, seen = tempfile.mkstemp, []

    def mkstemp(*args, **kwargs):
        if kwargs.get("prefix", "").startswith(f".{target}."):
            seen.append(kwargs["prefix"])
            if len(seen) > after:
                raise OSError(error, os.strerror(error), os.path.join(kwargs.get("dir", ""), "tmp"))
        return real(*args, **kwargs)

    with monkeypatch.context() as patch:
        patch.setattr(tempfile, "mkstemp", mkstemp)
        yield seen


@pytest.mark.parametrize("target, after, error", [
    ("feedback.html", 1, errno.ENOSPC),      # while grading: the second student's page
    ("results.json", 2, errno.EDQUOT),       # while grading: the third student's results
    ("grades.csv", 0, errno.ENOSPC),         # the exports, after every grading is committed
    ("canvas_import.csv", 0, errno.EROFS),   # an LMS import
    ("index.html", 0, errno.ENOSPC),         # the class overview
])
def test_a_write_failing_stops_the_batch_and_the_rerun_equals_an_uninterrupted_run(
        submissions, uninterrupted, tmp_path, monkeypatch, target, after, error):
    out = tmp_path / "results"
    with failing_writes(monkeypatch, target, error, after) as seen, pytest.raises(StorageError) as raised:
        run_batch(submissions, out, course=COURSE, workers=2)
    assert len(seen) > after, "the fault was met"
    message = str(raised.value)
    assert f"cannot write {out}" in message and target in message and os.strerror(error) in message
    assert "run the same command again" in message and "finished gradings are kept" in message
    run_batch(submissions, out, course=COURSE, workers=2)
    assert_same_as_uninterrupted(out, uninterrupted)


def test_the_command_line_says_it_in_one_line_and_exits_1(submissions, tmp_path, monkeypatch, capsys):
    out = tmp_path / "results"
    with failing_writes(monkeypatch, "canvas_import.csv"):
        status = main(["batch", str(submissions), "--out", str(out), "--course", str(course_file(tmp_path)),
                       "--workers", "2"])
    printed = capsys.readouterr()
    assert status == STORAGE_ERROR == 1
    assert printed.err.splitlines() == [
        f"error: cannot write {out / 'canvas_import.csv'}: No space left on device. Free space and run the "
        "same command again: finished gradings are kept."]
    assert "Traceback" not in printed.out + printed.err and "wrote" not in printed.out


def course_file(folder: Path) -> Path:
    path = folder / "course.json"
    path.write_text(json.dumps({"select": COURSE.select, "assignment": COURSE.assignment}))
    return path


def test_a_file_name_the_disk_refuses_fails_that_student_alone(tmp_path, monkeypatch):
    """Not every OSError is the disk's: a submission's own file this file system cannot hold
    (a name too long here) fails that student, recorded with the reason; the batch goes on."""
    students = make_class(tmp_path / "class", ["ada", "cy"])
    write(students / "ada" / "helper_with_a_long_name.py", "X = 1\n")
    real = Path.write_bytes

    def write_bytes(self, data):
        if self.name == "helper_with_a_long_name.py":
            raise OSError(errno.ENAMETOOLONG, os.strerror(errno.ENAMETOOLONG), str(self))
        return real(self, data)

    monkeypatch.setattr(Path, "write_bytes", write_bytes)
    summary = run_batch(students, tmp_path / "results", course=COURSE, workers=2)
    assert summary.graded == 1 and [f.split(":")[0] for f in summary.failed] == ["ada"]
    assert "File name too long" in summary.failed[0]


# ------------------------------------------------------------------ the results folder deleted mid-run
@pytest.mark.parametrize("deleted", ["folder", "gradebook"])
def test_results_deleted_mid_run_stop_the_batch_instead_of_losing_its_work(
        submissions, uninterrupted, tmp_path, deleted):
    """SQLite goes on writing to a deleted gradebook: without a check the batch ended "wrote
    gradebook.sqlite" with no gradebook, and the next run graded everyone again unawares."""
    out = tmp_path / "results"

    def delete_after_the_first_grading(event, entry, summary):
        if event == "done" and summary.graded == 1:
            if deleted == "folder":
                shutil.rmtree(out)
            else:
                for path in out.glob("gradebook.sqlite*"):
                    path.unlink()

    with pytest.raises(StorageError) as raised:
        run_batch(submissions, out, course=COURSE, workers=2, progress=delete_after_the_first_grading)
    assert raised.value.kind == "vanished"
    assert f"{out / 'gradebook.sqlite'} was deleted or moved" in str(raised.value)
    if deleted == "folder":
        assert not out.exists(), "a deleted results folder is not written again piecemeal"
    run_batch(submissions, out, course=COURSE, workers=2)
    assert_same_as_uninterrupted(out, uninterrupted)


# ------------------------------------------------------------------ a damaged gradebook
def damage_head(path: Path) -> None:
    with open(path, "r+b") as f:
        f.write(b"this is not SQLite" * 8)


@pytest.mark.parametrize("damage", ["garbage at the head", "truncated"])
def test_a_damaged_gradebook_is_named_kept_and_the_class_graded_anew_once_moved_aside(
        submissions, uninterrupted, tmp_path, capsys, damage):
    out = copy_results(uninterrupted, tmp_path / "results")
    gradebook = out / "gradebook.sqlite"
    if damage == "truncated":
        os.truncate(gradebook, gradebook.stat().st_size // 2)
    else:
        damage_head(gradebook)
    damaged = gradebook.read_bytes()
    status = main(["batch", str(submissions), "--out", str(out), "--course", str(course_file(tmp_path))])
    printed = capsys.readouterr()
    assert status == STORAGE_ERROR
    [line] = printed.err.splitlines()
    assert line.startswith(f"error: {gradebook} is not a gradebook or is damaged")
    assert f"mv {gradebook} {gradebook}.damaged" in line and "Traceback" not in printed.out + printed.err
    assert gradebook.read_bytes() == damaged, "the damaged gradebook is left as it was, for recovery"
    gradebook.rename(out / "gradebook.sqlite.damaged")
    run_batch(submissions, out, course=COURSE, workers=2)
    assert_same_as_uninterrupted(out, uninterrupted)


def test_every_truncation_of_a_gradebook_is_refused_when_opened(uninterrupted, tmp_path):
    """Cut at any page or half-way through one, the gradebook is refused before anything is
    graded (a quick check when opened), not half-read at the end of the run."""
    size = (uninterrupted / "gradebook.sqlite").stat().st_size
    page = 4096
    assert size > 4 * page, "a gradebook of several pages"
    for length in sorted({100, page, page + 1000, size // 2, size - page, size - 2000, size - 1}):
        folder = tmp_path / str(length)
        folder.mkdir()
        shutil.copy(uninterrupted / "gradebook.sqlite", folder)
        os.truncate(folder / "gradebook.sqlite", length)
        for readonly in (False, True):
            with pytest.raises(StorageError) as raised:
                Gradebook(folder, readonly=readonly).close()
            assert raised.value.kind == "corrupt", (length, str(raised.value))


# ------------------------------------------------------------------ a student missing from a re-download
def test_a_student_missing_from_a_new_download_is_kept_marked_and_reported(submissions, uninterrupted, tmp_path):
    out = copy_results(uninterrupted, tmp_path / "results")
    before = {s["student_id"]: s for s in comparable(out)}
    fewer = make_class(tmp_path / "download-2", ["ada", "cy", "di"])
    summary = run_batch(fewer, out, course=COURSE, workers=2)
    assert summary.missing == ["bo"] and summary.graded == 0 and summary.students == 3
    students = {s["student_id"]: s for s in comparable(out)}
    assert students["bo"]["missing_from_download"] is True
    assert {k: v for k, v in students["bo"].items() if k != "missing_from_download"} == \
        {k: v for k, v in before["bo"].items() if k != "missing_from_download"}, "kept with the last grading"
    assert not any(students[s]["missing_from_download"] for s in ("ada", "cy", "di"))
    with Gradebook(out, readonly=True) as book:
        graded_at = next(s["graded_at"] for s in book.class_results() if s["student_id"] == "bo")
    grades = {r["Student ID"]: r for r in csv.DictReader((out / "grades.csv").open())}
    assert grades["bo"]["Status"] == f"not in this download; last graded {graded_at[:10]}"
    assert grades["bo"]["Total"] == "5" and grades["ada"]["Status"] == "graded"
    assert len(list(csv.DictReader((out / "canvas_import.csv").open()))) == 1 + 4   # Points Possible + 4
    # back in the next download: nothing graded again, no longer marked
    summary = run_batch(submissions, out, course=COURSE, workers=2)
    assert summary.missing == [] and summary.graded == 0
    assert_same_as_uninterrupted(out, uninterrupted)


def test_the_command_line_lists_who_is_no_longer_in_submissions(submissions, uninterrupted, tmp_path, capsys):
    out = copy_results(uninterrupted, tmp_path / "results")
    fewer = make_class(tmp_path / "download-2", ["ada", "cy"])
    assert main(["batch", str(fewer), "--out", str(out), "--course", str(course_file(tmp_path))]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "no longer in SUBMISSIONS: bo (kept, with their last grading)" in printed
    assert "no longer in SUBMISSIONS: di" in printed


SCHEMA_1_STUDENTS = """CREATE TABLE students (
    student_id TEXT PRIMARY KEY, display_name TEXT NOT NULL, source TEXT NOT NULL, origin TEXT NOT NULL,
    lms TEXT NOT NULL, members TEXT NOT NULL, submitted_at TEXT, late INTEGER, content_hash TEXT NOT NULL,
    submission_key TEXT, unreadable TEXT NOT NULL DEFAULT '')"""


def schema_1(gradebook: Path) -> None:
    """The gradebook as the first schema made it: no students.present (nor the report's column), schema_version 1."""
    db = sqlite3.connect(gradebook)
    columns = ", ".join(row[1] for row in db.execute("PRAGMA table_info(students)")
                        if row[1] not in ("present", "report_problems"))
    db.executescript(f"""
        ALTER TABLE students RENAME TO new;
        {SCHEMA_1_STUDENTS};
        INSERT INTO students SELECT {columns} FROM new;
        DROP TABLE new;
        UPDATE meta SET value='1' WHERE name='schema_version';
        """)
    db.close()


def test_a_schema_1_gradebook_is_read_as_it_is_and_migrated_in_place(submissions, uninterrupted, tmp_path):
    out = copy_results(uninterrupted, tmp_path / "results")
    schema_1(out / "gradebook.sqlite")
    assert comparable(out) == comparable(uninterrupted), "read (read-only) before any migration"
    summary = run_batch(make_class(tmp_path / "download-2", ["ada", "bo", "cy"]), out, course=COURSE, workers=2)
    assert summary.graded == 0 and summary.missing == ["di"], "no regrading, the new column works at once"
    with Gradebook(out, readonly=True) as book:
        assert book.get_meta("schema_version") == str(SCHEMA_VERSION) == "3"
    run_batch(submissions, out, course=COURSE, workers=2)
    assert_same_as_uninterrupted(out, uninterrupted)


def test_a_gradebook_of_a_newer_autograder_is_refused(uninterrupted, tmp_path):
    out = copy_results(uninterrupted, tmp_path / "results")
    with sqlite3.connect(out / "gradebook.sqlite") as db:
        db.execute("UPDATE meta SET value='99' WHERE name='schema_version'")
        db.execute("DROP TABLE overrides")   # a schema 99 without it
    db.close()
    with pytest.raises(StorageError, match="newer autograder") as raised:
        Gradebook(out).close()
    assert raised.value.kind == "newer"
    with sqlite3.connect(out / "gradebook.sqlite") as db:
        tables = {row[0] for row in db.execute("SELECT name FROM sqlite_master WHERE type='table'")}
    db.close()
    assert "overrides" not in tables, "nothing of this schema created in a newer one"


# ------------------------------------------------------------------ restoring a student's files
def test_report_and_batch_restore_lost_pages_and_results(submissions, uninterrupted, tmp_path, capsys):
    out = copy_results(uninterrupted, tmp_path / "results")
    (out / "ada" / "feedback.html").unlink()
    (out / "bo" / "results.json").unlink()
    (out / "cy" / "feedback.html").unlink()
    (out / "cy" / "results.json").unlink()
    assert main(["report", str(out)]) == 0
    printed = capsys.readouterr().out
    for student, name in (("ada", "feedback.html"), ("bo", "results.json"), ("cy", "feedback.html"),
                          ("cy", "results.json")):
        assert f"restored {out / student / name}" in printed
    for student in ("bo", "cy"):   # the students' view of the stored grading: the file as the batch wrote it
        assert (out / student / "results.json").read_text() == (uninterrupted / student / "results.json").read_text()
    page = (out / "ada" / "feedback.html").read_text()
    assert "lab07.ex1" in page and "data:image/" not in page
    # the batch restores them too (it always wrote pages again; results.json as well now)
    (out / "bo" / "results.json").unlink()
    (out / "di" / "feedback.html").unlink()
    assert run_batch(submissions, out, course=COURSE, workers=2).graded == 0
    assert (out / "bo" / "results.json").read_text() == (uninterrupted / "bo" / "results.json").read_text()
    assert "lab07.ex1" in (out / "di" / "feedback.html").read_text()


def test_report_names_a_student_whose_files_it_cannot_restore(uninterrupted, tmp_path, capsys):
    out = copy_results(uninterrupted, tmp_path / "results")
    (out / "cy" / "feedback.html").unlink()
    with sqlite3.connect(out / "gradebook.sqlite") as db:
        # a stored grading this grader cannot read back (no "submission"): e.g. an older format
        db.execute("""UPDATE submissions SET result='{"total": 0, "max_total": 12, "exercises": []}'
                      WHERE student_id='cy'""")
    db.close()
    assert main(["report", str(out)]) == STORAGE_ERROR
    printed = capsys.readouterr()
    assert "error: cannot restore the files of cy:" in printed.err and "--regrade" in printed.err
    assert "Traceback" not in printed.err and (out / "index.html").is_file()


def test_report_on_a_damaged_gradebook_says_so_in_one_line(uninterrupted, tmp_path, capsys):
    out = copy_results(uninterrupted, tmp_path / "results")
    damage_head(out / "gradebook.sqlite")
    assert main(["report", str(out)]) == STORAGE_ERROR
    printed = capsys.readouterr()
    [line] = printed.err.splitlines()
    assert "is not a gradebook or is damaged" in line and "Traceback" not in line


# ------------------------------------------------------------------ Gradescope's results.json
GRADESCOPE_SCHEMA = json.loads((Path(__file__).parent / "gradescope_results.schema.json").read_text())


def gradescope_data(tests: int = 200) -> dict:
    return {"score": 7.5, "output": "Total: 7.5 / 10\n" + "x" * 2000, "output_format": "text",
            "stdout_visibility": "hidden", "execution_time": 1.0,
            "tests": [{"name": f"check {i}", "number": f"7.1.{i}", "score": 0.05, "max_score": 0.05,
                       "status": "passed", "output": "y" * 100, "output_format": "md",
                       "visibility": "after_published" if i % 2 else "visible"} for i in range(tests)]}


def test_gradescope_results_stay_valid_when_the_full_file_cannot_be_written(tmp_path, monkeypatch):
    import jsonschema

    path = tmp_path / "results" / "results.json"
    real = tempfile.mkstemp
    calls = []

    def mkstemp(*args, **kwargs):   # the first (whole) write meets a full disk, the small one fits
        calls.append(kwargs.get("prefix"))
        if len(calls) == 1:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return real(*args, **kwargs)

    monkeypatch.setattr(tempfile, "mkstemp", mkstemp)
    written = gradescope.write_results(path, gradescope_data(), CourseConfig())
    monkeypatch.undo()
    data = json.loads(path.read_text())
    jsonschema.validate(data, GRADESCOPE_SCHEMA)
    assert data == written and data["score"] == 7.5
    assert "could not write its full results (No space left on device)" in data["output"]
    assert [t["visibility"] for t in data["tests"]] == ["after_published"], "the score shows no sooner"
    assert sorted(p.name for p in path.parent.iterdir()) == ["results.json"]


# ------------------------------------------------------------------ real faults on a small file system
@contextlib.contextmanager
def small_disk(folder: Path, size: str = "8m"):
    """A tmpfs of ``size`` at ``folder`` (root only: skipped elsewhere), unmounted at the end."""
    folder.mkdir(parents=True)
    if os.geteuid() != 0:
        pytest.skip("a file system of its own (tmpfs) needs root; the write-boundary tests cover the rest")
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(folder)],
                             capture_output=True, text=True)
    if mounted.returncode:
        pytest.skip(f"cannot mount a tmpfs here: {mounted.stderr.strip()}")
    try:
        yield folder
    finally:
        subprocess.run(["umount", "-l", str(folder)], check=True)


def fill(folder: Path, leave: int = 0) -> Path:
    """Fill the file system of ``folder`` (then free ``leave`` bytes); returns the ballast file."""
    ballast = folder / "ballast"
    with open(ballast, "wb", buffering=0) as f:
        for chunk in (1 << 20, 1 << 12):
            with contextlib.suppress(OSError):
                while True:
                    f.write(b"\0" * chunk)
    if leave:
        os.truncate(ballast, ballast.stat().st_size - leave)
    return ballast


def remount(folder: Path, mode: str) -> None:
    subprocess.run(["mount", "-o", f"remount,{mode}", str(folder)], check=True)


@pytest.mark.parametrize("when", ["grading", "exports"])
def test_a_disk_filling_up_stops_the_batch_and_the_rerun_equals_an_uninterrupted_run(
        submissions, uninterrupted, tmp_path, when):
    with small_disk(tmp_path / "disk") as disk:
        out, ballast = disk / "results", []

        def fill_the_disk(event, entry, summary):
            last = summary.graded == len(GRADED)
            if event == "done" and not ballast and (last if when == "exports" else summary.graded == 1):
                ballast.append(fill(disk))

        with pytest.raises(StorageError) as raised:
            run_batch(submissions, out, course=COURSE, workers=2, progress=fill_the_disk)
        assert raised.value.kind == "full" and "Free space" in str(raised.value)
        if when == "exports":   # the run's audit (the gradebook), then the exports: the first write refused is named
            assert str(out / "gradebook.sqlite") in str(raised.value) or str(out / "grades.csv") in str(raised.value)
        ballast[0].unlink()
        run_batch(submissions, out, course=COURSE, workers=2)
        assert_same_as_uninterrupted(out, uninterrupted)


def test_a_full_disk_at_a_commit_keeps_the_gradebook_whole(tmp_path):
    with small_disk(tmp_path / "disk", "2m") as disk:
        book = Gradebook(disk / "results")
        result = {"total": 1.0, "max_total": 2.0, "exercises": []}
        book.record("k1", "ada", "h1", "lab07.ex1", result, lock="lock")
        ballast = fill(disk)
        with pytest.raises(StorageError) as raised:
            for i in range(200):   # the WAL has room for a few
                book.record(f"k{i + 2}", f"s{i}", "h", "lab07.ex1", {**result, "notes": ["z" * 20000]}, lock="lock")
        assert raised.value.kind == "full"
        assert str(raised.value).startswith(f"cannot write {disk / 'results' / 'gradebook.sqlite'}: database or disk is full")
        ballast.unlink()
        book.record("k-after", "bo", "h2", "lab07.ex1", result, lock="lock")
        book.close()
        with Gradebook(disk / "results", readonly=True) as book:
            counts = book.grading_counts()
        assert counts["k1"] == counts["k-after"] == 1


def test_a_read_only_results_folder_is_refused_before_anything_is_graded(submissions, uninterrupted, tmp_path, capsys):
    with small_disk(tmp_path / "disk") as disk:
        remount(disk, "ro")
        out = disk / "results"
        status = main(["batch", str(submissions), "--out", str(out), "--course", str(course_file(tmp_path))])
        printed = capsys.readouterr()
        assert status == STORAGE_ERROR
        assert printed.err.splitlines() == [
            f"error: cannot write {out}: Read-only file system. Make it writable (or write the results "
            "elsewhere) and run the same command again: finished gradings are kept."]
        remount(disk, "rw")
        run_batch(submissions, out, course=COURSE, workers=2)
        assert_same_as_uninterrupted(out, uninterrupted)


@pytest.mark.parametrize("room", [0, 4096])
def test_gradescope_on_a_full_disk_leaves_valid_results_or_none(tmp_path, room):
    """With a page of room the score is written alone; with none, no results.json rather than
    the empty one run_autograder used to leave (Gradescope takes that for a broken grader)."""
    import jsonschema

    with small_disk(tmp_path / "disk", "1m") as disk:
        results = disk / "results"
        results.mkdir()
        fill(disk, leave=room)
        gradescope.write_results(results / "results.json", gradescope_data(), CourseConfig())
        if room:
            jsonschema.validate(json.loads((results / "results.json").read_text()), GRADESCOPE_SCHEMA)
        else:
            assert not (results / "results.json").exists()
        assert [p.name for p in results.iterdir()] == (["results.json"] if room else [])
        # run_autograder's own fallback (the grader could not start) on the full disk
        (results / "results.json").unlink(missing_ok=True)
        root = tmp_path / "autograder"
        (root / "source").mkdir(parents=True)
        script = root / "source" / "run_autograder"
        script.write_text(gradescope.RUN_AUTOGRADER)
        script.chmod(0o755)
        os.symlink(results, root / "results")
        subprocess.run([str(script)], env={**os.environ, "AUTOGRADER_ROOT": str(root), "AUTOGRADER_PYTHON": "false"},
                       capture_output=True, check=True)
        if room:
            jsonschema.validate(json.loads((results / "results.json").read_text()), GRADESCOPE_SCHEMA)
        else:
            assert not (results / "results.json").exists(), "no empty results.json"
        assert [p.name for p in results.iterdir()] == (["results.json"] if room else [])
