"""The batch grades by the course's rules, as a single grading does, and says who is still running.

- ``forbid``, the time budgets and the inputs' secret reach every grading of the batch;
  changing one of them grades the class again (the gradebook key holds them, hashed);
- a full temporary folder while grading stops the batch with the storage error
  (it is the machine's fault, not the submission's);
- the progress line names the students still being graded, the longest first.
"""

from __future__ import annotations

import pytest

from autograder.instructor.batch import run
from autograder.instructor.batch.gradebook import Gradebook, StorageError
from autograder.instructor.batch.run import run_batch
from autograder.instructor.course import CourseConfig
from test_batch import MODULE, reference, write

pytestmark = pytest.mark.slow


@pytest.fixture
def one_student(tmp_path):
    write(tmp_path / "class" / "ada" / f"{MODULE}.py", reference())
    return tmp_path / "class"


def total(out):
    with Gradebook(out, readonly=True) as book:
        [row] = book.class_results()
    return row["result"]["total"], row["result"]


def test_the_course_forbid_applies_in_a_batch_as_in_a_single_grading(one_student, tmp_path):
    plain = CourseConfig(select=["lab07.ex1"])
    run_batch(one_student, tmp_path / "a", course=plain, workers=1)
    assert total(tmp_path / "a")[0] == 12
    strict = CourseConfig(select=["lab07.ex1"], forbid={"lab07.translate": ["cv2.warpAffine"]})
    summary = run_batch(one_student, tmp_path / "a", course=strict, workers=1)
    assert summary.graded == 1, "a changed rule grades the class again"
    score, result = total(tmp_path / "a")
    assert score < 12
    messages = " ".join(c["message"] for e in result["exercises"] for c in e["checks"])
    assert "cv2.warpAffine" in messages and "implement yourself" in messages


def test_a_changed_inputs_secret_grades_again_and_an_unchanged_course_does_not(one_student, tmp_path):
    course = CourseConfig(select=["lab07.ex1"], inputs_secret="one")
    run_batch(one_student, tmp_path / "a", course=course, workers=1)
    assert run_batch(one_student, tmp_path / "a", course=course, workers=1).graded == 0
    again = CourseConfig(select=["lab07.ex1"], inputs_secret="two")
    assert run_batch(one_student, tmp_path / "a", course=again, workers=1).graded == 1
    with Gradebook(tmp_path / "a", readonly=True) as book:
        assert "one" not in str(book.db.execute("SELECT lock_hash FROM submissions").fetchall())


def full_disk(*arguments):
    """What grade_files says when the grading process cannot write the submission's files."""
    return {"storage": "No space left on device", "path": "/tmp/batch-x/ada", "errno": 28}


def test_a_full_temporary_folder_stops_the_batch_as_a_storage_fault(one_student, tmp_path, monkeypatch):
    monkeypatch.setattr(run, "grade_files", full_disk)
    with pytest.raises(StorageError, match="No space left on device") as raised:
        run_batch(one_student, tmp_path / "a", course=CourseConfig(select=["lab07.ex1"]), workers=1)
    assert raised.value.kind == "full"
    with Gradebook(tmp_path / "a", readonly=True) as book:
        assert book.class_results()[0]["status"] == "pending"   # not failed: graded on the next run


def test_the_progress_line_names_the_students_still_running():
    import time

    from rich.console import Console
    from rich.progress import Progress

    from autograder.cli import _running_column

    now = time.monotonic()
    column = _running_column()({"bo": now - 95, "ada": now - 3, "cy": now - 1, "di": now})
    progress = Progress(console=Console(file=open("/dev/null", "w")))
    task_id = progress.add_task("x")
    text = column.render(progress._tasks[task_id]).plain
    assert text.startswith("running: bo 1:35, ada 0:03, cy 0:01") and text.endswith("+1")


def test_the_batch_bar_shows_the_students_the_batch_reports_running():
    """The bar's column reads the students the batch's last event said were running (a first-time user saw
    "running" never appear: the column kept the empty dict it was made with -- audit of 2026-12-07)."""
    import io
    from types import SimpleNamespace

    from rich.console import Console

    from autograder.cli import _batch_progress

    console = Console(file=io.StringIO(), force_terminal=True, width=200)
    progress = _batch_progress(console)
    update = progress.__enter__()
    try:
        update("start", None, SimpleNamespace(students=3))
        update("graded", None, SimpleNamespace(running=["alice", "bo"], graded=1, failed=[]))
        column = progress.bar.columns[-1]
        text = column.render(progress.bar._tasks[progress.task]).plain
    finally:
        progress.__exit__(None, None, None)
    assert text.startswith("running: alice 0:00, bo 0:00"), text


def test_results_are_never_written_among_the_submissions(tmp_path, capsys):
    """`--out` the class folder or inside it is refused before anything is graded: the pages and sources written
    there would be read back as students' work by the next run (audit of 2026-12-07: a report's error message led a
    first-time user to do just that)."""
    from autograder import cli

    (tmp_path / "class" / "alice").mkdir(parents=True)
    for out in (tmp_path / "class", tmp_path / "class" / "results"):
        assert cli.main(["batch", str(tmp_path / "class"), "--out", str(out)]) == 2
        said = " ".join(capsys.readouterr().out.split())
        assert "folder of submissions" in said and "class-results" in said, said
    assert not (tmp_path / "class" / "results").exists()
