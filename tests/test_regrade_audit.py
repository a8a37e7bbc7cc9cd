"""Every regrade is an audit: whose final grade moved since the last run, old -> new, and why.

A small class graded once; then one student's file is replaced, then the course's late
rule changes: each run lists exactly the students whose final grade moved, with the
exercise and checks (or the late penalty) that moved it, on the terminal, in
``changes.csv``, in the overview and on the student's own page. ``batch --compare``
shows the same list before anything in RESULTS changes.
"""

from __future__ import annotations

import csv
import json
import subprocess
import sys

import pytest

from autograder.instructor.batch.run import run_batch
from autograder.instructor.course import CourseConfig
from test_batch import COURSE, MODULE, WRONG_WAY, reference, skeleton, write

pytestmark = pytest.mark.slow


def changes_csv(out):
    return {row["Student ID"]: row for row in csv.DictReader((out / "changes.csv").open())}


def test_each_run_lists_the_grades_it_moved_and_why(tmp_path):
    download, out = tmp_path / "download", tmp_path / "out"
    write(download / "ann" / f"{MODULE}.py", reference())
    write(download / "bo" / f"{MODULE}.py", skeleton())
    write(download / "cy" / f"{MODULE}.py", reference() + WRONG_WAY)
    first = run_batch(download, out, course=COURSE, workers=2)
    assert first.changes == [] and changes_csv(out) == {}          # nothing to compare with yet

    again = run_batch(download, out, course=COURSE, workers=2)
    assert again.graded == 0 and again.changes == []                 # nothing moved, nothing listed

    write(download / "bo" / f"{MODULE}.py", reference())             # bo hands in a working file
    moved = run_batch(download, out, course=COURSE, workers=2)
    [change] = moved.changes
    assert (change.student_id, change.before, change.after, change.why) == ("bo", 0.0, 12.0, "new submission")
    assert change.parts and change.parts[0].startswith("lab07.ex1: 0 -> 12 (checks' own points: ")
    row = changes_csv(out)["bo"]
    assert (row["Before"], row["After"], row["Why regraded"]) == ("0", "12", "new submission")
    assert "lab07.ex1: 0 -> 12" in row["What moved it"]
    overview = (out / "index.html").read_text()
    assert 'id="changes"' in overview and "new submission" in overview and 'href="changes.csv"' in overview
    page = (out / "bo" / "feedback.html").read_text()
    # lab07.ex1 has hidden checks, whose points this course withholds: every number could tell them
    assert "Graded again since your previous grading</strong> (new submission)" in page and "0 → 12" not in page
    assert "previous grading" not in (out / "ann" / "feedback.html").read_text()
    shown = run_batch(download, out, course=CourseConfig(select=COURSE.select, assignment="Lab 7",
                                                         hidden_points_visible=True), workers=2)
    assert shown.changes == []   # the same grades, shown otherwise: nothing moved
    page = (out / "bo" / "feedback.html").read_text()
    assert "Since your previous grading: 0 → 12" in page and "lab07.ex1: 0 -&gt; 12" in page

    # A course change (a late rule nobody here falls under) and an override: only the override's
    # student is listed, with the override as the cause.
    late_course = CourseConfig(select=COURSE.select, assignment="Lab 7", late_penalty={"per_day": 25})
    (tmp_path / "overrides.csv").write_text("student,exercise,points,penalty,comment\nann,total,2,,presented\n")
    rule = run_batch(download, out, course=late_course, workers=2, overrides=tmp_path / "overrides.csv")
    moved_ids = {c.student_id: c for c in rule.changes}
    assert set(moved_ids) == {"ann"}
    assert moved_ids["ann"].parts == ["override total +2 (presented)"]


def test_compare_previews_the_changes_and_leaves_the_gradebook_alone(tmp_path):
    download, out = tmp_path / "download", tmp_path / "out"
    write(download / "ann" / f"{MODULE}.py", skeleton())
    write(download / "bo" / f"{MODULE}.py", reference())
    first = run_batch(download, out, course=COURSE, workers=2)
    assert first.first_run and first.changes == []   # (the CLI says so, not "0 final grades changed")
    before = {p.name: p.read_bytes() for p in out.rglob("*") if p.is_file() and p.suffix in (".csv", ".sqlite")}

    write(download / "ann" / f"{MODULE}.py", reference())
    (tmp_path / "course.json").write_text(json.dumps({"select": COURSE.select, "assignment": "Lab 7",
                                                      "late_days": {"tokens": 3, "ledger": "late_days.json"}}))
    ledger_before = (tmp_path / "late_days.json").read_bytes() if (tmp_path / "late_days.json").exists() else None
    command = [sys.executable, "-m", "autograder", "batch", str(download), "--out", str(out),
               "--course", str(tmp_path / "course.json"), "--workers", "1", "--compare"]
    preview = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert preview.returncode == 0, preview.stderr
    assert "1 final grade would change" in preview.stdout and "without --compare to apply" in preview.stdout
    assert "ann: 0 -> 12 (new submission; lab07.ex1: 0 -> 12" in preview.stdout
    after = {p.name: p.read_bytes() for p in out.rglob("*") if p.is_file() and p.suffix in (".csv", ".sqlite")}
    assert after == before                                             # a preview changes nothing
    assert not (tmp_path / "late_days.json").exists() and ledger_before is None   # not even the term's ledger

    applied = subprocess.run(command[:-1], capture_output=True, text=True, timeout=600)
    assert applied.returncode == 0, applied.stderr
    assert "1 final grade changed since the last run" in applied.stdout and "the first run" not in applied.stdout
    assert changes_csv(out)["ann"]["After"] == "12"


@pytest.mark.parametrize("old, new, why, part", [
    ({"reports": {}}, {"reports": {"lab07.ex1": 3.0}}, "report reviewed", "lab07.ex1 report not reviewed -> 3"),
    ({"adjustments": []}, {"adjustments": ["override +5"]}, "override changed", "override override +5"),
    ({"late": 0.0}, {"late": -7.3}, "late rules changed (extension, late days, penalty)", "late penalty 0 -> -7.3"),
])
def test_a_change_without_a_regrade_says_what_moved_it(old, new, why, part):
    """A grade moved by a review, an override or the late rules (the same grading) says so in
    its 'why' column, never a blank or a dash for a report not reviewed before."""
    from autograder.instructor.batch.changes import compare

    base = {"content": "c", "lock": "l", "status": "graded"}
    [change] = compare({"ada": {**base, **old, "total": 10.0}}, {"ada": {**base, **new, "total": 13.0}})
    assert (change.why, change.parts) == (why, [part])


def test_a_roster_student_with_nothing_handed_in_is_no_changed_grade():
    """A roster row with no submission has no grade before or after: not "eve: - -> - (first grading)" (audit of
    2026-12-07); a first grading that gives one is a change."""
    from autograder.instructor.batch.changes import compare

    assert compare({}, {"eve": {"name": "Eve", "total": None}}) == []
    [change] = compare({}, {"ada": {"name": "Ada", "total": 10.0, "exercises": {"lab07.ex1": 10.0},
                                    "checks": {"lab07.ex1: translate": 4, "lab07.ex1: hidden check 1": 2}}})
    # a newcomer's line says so, not every exercise and check "moved" from nothing (audit: 20 wrapped lines)
    assert change.why == "first grading" and change.parts == []
    assert change.sentence() == "ada: - -> 10 (first grading)"


def test_a_grade_moved_without_grading_again_is_not_told_graded_again():
    """While hidden points are withheld a student's page tells only that the grade changed and why: an override, a
    reviewed report or an extension changes it without grading the code again (audit of 2026-12-07: "Graded again
    since your previous grading (override changed)" after a run that graded nothing)."""
    from autograder.instructor.batch.changes import Change
    from autograder.instructor.batch.exports import changed_html

    override = changed_html(Change("ada", "Ada", 10.0, 12.0, "override changed", ["override lab07.ex2 set to 1"]),
                            show_final=False)
    assert "Your grade changed since your previous grading</strong> (override changed)" in override
    assert "Graded again" not in override and "12" not in override
    resubmitted = changed_html(Change("ada", "Ada", 10.0, 12.0, "new submission", []), show_final=False)
    assert "Graded again since your previous grading</strong> (new submission)" in resubmitted


def test_a_run_asking_for_other_pictures_or_figures_says_which_pages_keep_theirs(tmp_path):
    """Pictures and the rubric's figures change no score: a run asking for others grades nothing again, and says so
    with what to do (audit of 2026-12-07: a rubric added, or --pictures all, to a graded class made no figures and no
    pictures, silently: "0 graded now"). A --regrade makes them, and the note is gone."""
    download, out = tmp_path / "download", tmp_path / "out"
    write(download / "ann" / f"{MODULE}.py", reference())
    write(download / "bo" / f"{MODULE}.py", reference() + WRONG_WAY)
    first = run_batch(download, out, course=COURSE, workers=2)
    assert first.graded == 2 and not [w for w in first.warnings if "graded before" in w]
    rubric = {"lab07.ex1": [{"id": "why", "text": "explains the warp", "points": 1}]}
    asked = CourseConfig(select=COURSE.select, assignment=COURSE.assignment, rubric=rubric)
    again = run_batch(download, out, course=asked, pictures="all", workers=2)
    [note] = [w for w in again.warnings if "graded before" in w]
    assert again.graded == 0 and note.startswith("2 submissions graded before keep the pages made with "
                                                 "pictures: failing; figures: none, not this run's pictures: all; "
                                                 "figures: lab07.ex1"), note
    assert "--regrade" in note
    regraded = run_batch(download, out, course=asked, pictures="all", regrade=True, workers=2)
    assert regraded.graded == 2 and not [w for w in regraded.warnings if "graded before" in w]
    assert not [w for w in run_batch(download, out, course=asked, pictures="all", workers=2).warnings
                if "graded before" in w]
