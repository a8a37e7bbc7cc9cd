"""One final grade on every page and export (issue 28).

A small Canvas class graded with course points, a late rule, an override and
Canvas's own gradebook export as the roster: the student's page headline, the
class overview, grades.csv and the Canvas import all tell the same final grade,
with the checks' own points beside it, labelled, where they differ -- except that
a page never shows a final grade holding hidden checks' points the course withholds.
"""

from __future__ import annotations

import csv
import re

import pytest

from autograder.instructor.batch.run import run_batch
from autograder.instructor.course import CourseConfig
from test_batch import MODULE, SELECT, WRONG_WAY, reference, write

pytestmark = pytest.mark.slow

ROSTER = ("Student,ID,SIS User ID,SIS Login ID,Section,Lab 7 (4242)\n"
          "    Points Possible,,,,,20\n"
          '"Smith, John",1234,S1,jsmith,A,\n'
          '"Doe, Jane",2345,S2,jdoe,A,\n'
          '"Lee, Ann",3456,S3,alee,B,\n'
          '"Nobody, Ned",4567,S4,nned,B,\n')


def canvas_class(root):
    write(root / f"smithjohn_1234_5678_{MODULE}.py", reference())                  # 12 / 12
    write(root / f"doejane_LATE_2345_6789_{MODULE}.py", reference())               # late: -25%
    write(root / f"leeann_3456_7890_{MODULE}.py", reference() + WRONG_WAY)          # 5 / 12, +2 by override


def run(tmp_path, hidden_points_visible):
    download = tmp_path / "download"
    canvas_class(download)
    (tmp_path / "roster.csv").write_text(ROSTER)
    (tmp_path / "overrides.csv").write_text("student,exercise,points,penalty,comment\n"
                                            "Ann Lee,total,2,,explained it in the lab\n")
    course = CourseConfig(select=SELECT, assignment="Lab 7", points={"lab07": 20}, late_penalty={"per_day": 25},
                          hidden_points_visible=hidden_points_visible)
    out = tmp_path / "out"
    summary = run_batch(download, out, course=course, workers=2, roster=tmp_path / "roster.csv",
                        overrides=tmp_path / "overrides.csv")
    assert not [w for w in summary.warnings if "override" in w or "Canvas" in w], summary.warnings
    grades = {r["Student ID"]: r for r in csv.DictReader((out / "grades.csv").open())}
    canvas = {r["ID"]: r for r in csv.DictReader((out / "canvas_import.csv").open())}
    return out, grades, canvas


def headline(out, student_id):
    page = (out / student_id / "feedback.html").read_text()
    return re.sub(r"<[^>]+>", "", re.search(r"<h1>(.*?)</h1>", page, re.S)[1]).strip()


def test_every_page_and_export_tells_the_same_final_grade(tmp_path):
    out, grades, canvas = run(tmp_path, hidden_points_visible=True)
    expected = {"smithjohn-1234": ("20", "1234"), "doejane-2345": ("15", "2345"), "leeann-3456": ("10.33", "3456")}
    overview = (out / "index.html").read_text()
    for student_id, (total, canvas_id) in expected.items():
        assert grades[student_id]["Total"] == total
        assert canvas[canvas_id]["Lab 7 (4242)"] == total            # the Canvas column carries its id
        assert headline(out, student_id).startswith(f"final grade {total} / 20"), headline(out, student_id)
        assert f"{total} / 20" in overview
    assert "(checks: 12 / 12 points)" in headline(out, "doejane-2345")   # the raw score, labelled
    page = (out / "doejane-2345" / "feedback.html").read_text()          # the title and bar agree
    assert "<title>Feedback: final grade 15 / 20 — " in page and 'aria-label="75 percent"' in page
    # named as the roster names them; the roster student with no submission is listed too
    assert grades["smithjohn-1234"]["Name"] == "Smith, John"
    assert "Smith, John" in overview and "Nobody, Ned" in overview and "no submission" in overview
    # the overview links every report the batch wrote
    for report in ("grades.csv", "canvas_import.csv", "roster_unmatched.csv"):
        assert f'href="{report}"' in overview
    assert 'href="moodle_import.csv"' not in overview and not (out / "moodle_import.csv").exists()


def test_a_page_never_shows_a_final_grade_holding_withheld_hidden_points(tmp_path):
    out, grades, _ = run(tmp_path, hidden_points_visible=False)
    page = (out / "leeann-3456" / "feedback.html").read_text()
    assert "final grade: shown when the hidden checks are released" in page
    assert grades["leeann-3456"]["Total"] not in headline(out, "leeann-3456").split(" / ")[0]
    assert "final grade" not in headline(out, "smithjohn-1234")
    # the headline beside adjustments that change the grade says what it counts (audit of 2026-12-07: "65 / 65
    # points" beside "lab07.ex2 set to 1")
    assert "(the public checks; your final grade, with the adjustments below, is shown when the hidden checks are " \
           "released)" in headline(out, "leeann-3456")
    assert "the public checks" not in headline(out, "smithjohn-1234")   # nothing adjusted: the plain total
    from autograder.instructor.batch.run import write_exports   # every later run brings the page up to date
    write_exports(out)
    assert (out / "leeann-3456" / "feedback.html").read_text().count("the public checks;") == 1
