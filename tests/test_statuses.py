"""Statuses that say what happened: graded, nothing implemented, does not import (why), could
not be read (why), missing, and late -- shown even at 0 points; and exports warn while
reports wait for their review (their points count 0 until then)."""

from __future__ import annotations

import csv

import pytest

from autograder.instructor.batch.run import run_batch
from autograder.instructor.course import CourseConfig
from test_batch import COURSE, MODULE, reference, skeleton, write

pytestmark = pytest.mark.slow


def test_each_status_says_what_happened(tmp_path):
    download, out = tmp_path / "download", tmp_path / "out"
    write(download / f"annlee_1001_1_{MODULE}.py", reference())
    write(download / f"bochen_LATE_1002_2_{MODULE}.py", skeleton())                    # untouched, and late
    write(download / f"cydee_1003_3_{MODULE}.py", reference() + "\ndef broken(:\n")  # a syntax error
    write(download / f"dieu_1004_4_{MODULE}.py", b"\xff\xfe not text")                 # cannot be read as text
    course = CourseConfig(select=COURSE.select, assignment="Lab 7", late_penalty={"per_day": 10})
    summary = run_batch(download, out, course=course, workers=2)
    status = {row["Student ID"]: row["Status"] for row in csv.DictReader((out / "grades.csv").open())}
    assert status["annlee-1001"] == "graded"
    assert status["bochen-1002"] == "nothing implemented; late (1 day)"   # late even at 0 points
    assert status["cydee-1003"].startswith("does not import (") and "line" in status["cydee-1003"]
    assert status["dieu-1004"].startswith(("could not be read", "does not import"))
    assert not [w for w in summary.warnings if "not reviewed" in w]     # no rubric, nothing to review


def test_exports_warn_while_reports_wait_for_their_review(tmp_path):
    download, out = tmp_path / "download", tmp_path / "out"
    write(download / "ann" / f"{MODULE}.py", reference())
    course = CourseConfig(select=COURSE.select, assignment="Lab 7",
                          rubric={"lab07.ex1": [{"id": "explains", "text": "explains the matrix", "points": 3}]})
    summary = run_batch(download, out, course=course, workers=1)
    [warning] = [w for w in summary.warnings if "not reviewed" in w]
    assert warning.startswith("lab07.ex1: 1 of 1 reports not reviewed yet") and "count 0" in warning
