"""Extensions, excused work and pooled late days, applied by the one final-grade computation.

A student's extension (extra days or a due date of their own) is found by any identity
the download or roster knows, as an override is; excused work counts for nothing and
shows as Canvas's "EX"; pooled late days are spent before any penalty, across the
term's assignments in the order of their due dates, whichever assignment is graded first.
"""

from __future__ import annotations

import csv

import pytest

from autograder.instructor.batch.exports import (compute_grades, read_ledger, record_late_days, write_csvs,
                                                 _status)
from autograder.instructor.course import CourseConfig, CourseConfigError

EXERCISES = [("lab07.ex1", 10.0)]
DUE = "2026-03-01T23:59:00+00:00"


def student(student_id: str, submitted_at: str | None, email: str = "", name: str = "") -> dict:
    return {"student_id": student_id, "display_name": name or student_id, "origin": f"{student_id}/",
            "lms": {"email": email} if email else {}, "members": [], "status": "graded", "reason": "",
            "submitted_at": submitted_at, "late": None, "feedback": None,
            "result": {"total": 10.0, "max_total": 10.0,
                       "exercises": [{"id": "lab07.ex1", "score": 10.0, "max_score": 10.0, "checks": []}]}}


def course(**options) -> CourseConfig:
    return CourseConfig(assignment=options.pop("assignment", "Lab 7"),
                        late_penalty=options.pop("late_penalty", {"due": DUE, "per_day": 10}), **options)


def grades_of(students, config, ledger=None):
    grades, warnings = compute_grades(students, EXERCISES, config, ledger=ledger)
    return {g.student["student_id"]: g for g in grades}, warnings


TWO_DAYS_LATE = "2026-03-03T20:00:00+00:00"


@pytest.mark.parametrize("extension, penalty", [
    ({"days": 2}, 0.0), ({"days": 1}, 1.0), ({"days": 0}, 2.0),
    ({"due": "2026-03-04T00:00:00+00:00"}, 0.0), ({"due": "2026-03-02T23:59:00+00:00"}, 1.0)])
@pytest.mark.parametrize("named_by", ["ann", "ann@uni.edu", "Ann Lee", "lee ann"])
def test_an_extension_moves_the_due_date_of_the_student_it_names(extension, penalty, named_by):
    config = course(extensions={named_by: extension})
    grades, warnings = grades_of([student("ann", TWO_DAYS_LATE, "ann@uni.edu", "Ann Lee"),
                                  student("bo", TWO_DAYS_LATE)], config)
    assert warnings == []
    assert grades["ann"].late_penalty == penalty and grades["ann"].total == 10 - penalty
    assert grades["bo"].late_penalty == 2.0            # nobody else's due date moves
    assert [a.what for a in grades["ann"].adjustments][0] == "extension"


def test_excused_work_counts_for_nothing_and_is_told_so(tmp_path):
    config = course(extensions={"ann": {"excused": True}})
    grades, _ = grades_of([student("ann", TWO_DAYS_LATE), student("bo", None)], config)
    assert grades["ann"].total is None and grades["ann"].late_penalty == 0 and _status(grades["ann"]) == "excused"
    write_csvs(tmp_path, list(grades.values()), EXERCISES, config, roster_given=False)
    canvas = list(csv.reader((tmp_path / "canvas_import.csv").open()))
    assert [row[-1] for row in canvas[2:]] == ["EX", "10"]


@pytest.mark.parametrize("named_by", ["s005", "zoe@uni.edu", "Zoe Ng"])
def test_a_roster_student_with_nothing_handed_in_can_be_excused(tmp_path, named_by):
    """A roster's student who handed nothing in, excused by id, e-mail or name: "names no student; ignored" and an
    empty Canvas cell until the first-time user's audit of 2026-12-07; Canvas's EX now, and no warning."""
    config = course(extensions={named_by: {"excused": True}})
    roster = [{"student_id": "s005", "name": "Zoe Ng", "email": "zoe@uni.edu", "canvas_user_id": "1005"}]
    grades, warnings = compute_grades([student("bo", "2026-03-01T20:00:00+00:00")], EXERCISES, config, roster=roster)
    assert warnings == [], warnings
    [zoe] = [g for g in grades if g.student["student_id"] == "s005"]
    assert zoe.excused and _status(zoe) == "excused"
    write_csvs(tmp_path, grades, EXERCISES, config, roster_given=True)
    canvas = {row[0]: row[-1] for row in csv.reader((tmp_path / "canvas_import.csv").open())}
    assert canvas["Zoe Ng"] == "EX" and canvas["bo"] == "10"


def test_an_extension_naming_nobody_or_several_is_refused_with_a_warning():
    config = course(extensions={"zed": {"days": 1}, "Ann Lee": {"days": 1}})
    grades, warnings = grades_of([student("ann", TWO_DAYS_LATE, name="Ann Lee"),
                                  student("ann-2", TWO_DAYS_LATE, name="Ann Lee")], config)
    assert any("'zed' names no student" in w for w in warnings)
    assert any("'Ann Lee' is ambiguous" in w for w in warnings)
    assert grades["ann"].late_penalty == grades["ann-2"].late_penalty == 2.0


def test_pooled_late_days_are_spent_in_the_order_of_the_due_dates(tmp_path):
    ledger = tmp_path / "late_days.json"
    first = course(assignment="Lab 7", late_days={"tokens": 3, "ledger": str(ledger)})
    second = course(assignment="Lab 8", late_days={"tokens": 3, "ledger": str(ledger)},
                    late_penalty={"due": "2026-03-15T23:59:00+00:00", "per_day": 10})
    late_for_second = "2026-03-17T20:00:00+00:00"

    # Lab 8 graded before Lab 7: it may spend what Lab 7 will need...
    eight, _ = grades_of([student("ann", late_for_second)], second, read_ledger(second))
    assert eight["ann"].late_days_used == 2 and eight["ann"].late_penalty == 0
    record_late_days(second, list(eight.values()))
    # ...but Lab 7 is due first: it spends first, whatever ran first.
    seven, _ = grades_of([student("ann", TWO_DAYS_LATE)], first, read_ledger(first))
    assert seven["ann"].late_days_used == 2 and seven["ann"].late_penalty == 0
    record_late_days(first, list(seven.values()))
    eight, _ = grades_of([student("ann", late_for_second)], second, read_ledger(second))
    assert eight["ann"].late_days_used == 1 and eight["ann"].late_penalty == 1.0
    assert any(a.what == "late days" and "0 of 3 left" in a.comment for a in eight["ann"].adjustments)


def test_without_a_ledger_the_tokens_are_this_assignments():
    grades, _ = grades_of([student("ann", TWO_DAYS_LATE)], course(late_days={"tokens": 1}))
    assert grades["ann"].late_days_used == 1 and grades["ann"].late_penalty == 1.0


@pytest.mark.parametrize("extensions", [{"ann": {"days": -1}}, {"ann": {"weeks": 1}}, {"ann": {"excused": "yes"}},
                                        {"ann": {"due": "tomorrow"}}, {"ann": {"days": 1, "due": DUE}}, ["ann"]])
def test_a_malformed_extension_is_refused_saying_which(extensions):
    with pytest.raises(CourseConfigError, match="extensions"):
        course(extensions=extensions)


@pytest.mark.slow
def test_autograder_report_tells_the_batchs_final_grades(tmp_path):
    """`autograder report` (and the review app) compute grades from the course the batch kept:
    extensions and pooled late days included, or the grade they write would differ from the batch's."""
    from autograder.instructor.batch.run import run_batch, write_exports
    from test_batch import COURSE, MODULE, reference, write

    download, out = tmp_path / "download", tmp_path / "out"
    write(download / f"annlee_LATE_1001_1_{MODULE}.py", reference())      # Canvas's late flag: one day
    write(download / f"bochen_LATE_1002_2_{MODULE}.py", reference())
    config = CourseConfig(select=COURSE.select, assignment="Lab 7", late_penalty={"per_day": 50},
                          extensions={"annlee-1001": {"days": 1}}, late_days={"tokens": 0})
    run_batch(download, out, course=config, workers=1)
    batch = (out / "grades.csv").read_text()
    totals = {row["Student ID"]: row["Total"] for row in csv.DictReader(batch.splitlines())}
    assert totals == {"annlee-1001": "12", "bochen-1002": "6"}
    write_exports(out)            # no course given: the batch's own
    assert (out / "grades.csv").read_text() == batch


def test_a_damaged_ledger_is_refused_in_one_sentence(tmp_path):
    ledger = tmp_path / "late_days.json"
    ledger.write_text("[not a ledger")
    config = course(late_days={"tokens": 2, "ledger": str(ledger)})
    with pytest.raises(ValueError, match="late-day ledger .* cannot be read"):
        read_ledger(config)
    for damaged in ('{"assignments": 3}', '{"assignments": {"Lab 7": {"late": {"canvas:1": "two"}}}}',
                    '{"assignments": {"Lab 7": []}}'):
        ledger.write_text(damaged)
        with pytest.raises(ValueError, match="is not a ledger"):
            read_ledger(config)


def test_an_excused_students_page_says_excused_where_it_would_tell_the_final_grade():
    """The page of an excused student whose final grade may be shown (no hidden points withheld):
    the headline, the title and the adjustments say "excused" (the batch stopped on its total, None)."""
    from autograder.instructor.batch.exports import BAR, BAR_END, BEGIN, END, HEADLINE, HEADLINE_END, student_page

    config = course(extensions={"ann": {"excused": True}})
    grades, _ = grades_of([student("ann", TWO_DAYS_LATE)], config)
    page = f"<title>Feedback: 10 / 10 — ann</title>{HEADLINE}10 / 10{HEADLINE_END}{BAR}{BAR_END}{BEGIN}{END}"
    shown = student_page(page, grades["ann"], 10.0, config)
    assert "<title>Feedback: excused — ann</title>" in shown
    assert f"{HEADLINE}excused, not counted" in shown and "(checks: 10 / 10 points)" in shown
    assert "excused: not counted" in shown and "final grade" not in shown


def test_the_class_overview_tells_each_students_extension_excused_work_and_days_late():
    from autograder.instructor.classreport.overview import overview_html
    from autograder.instructor.classreport.pages import records_from_grades

    config = course(extensions={"ann": {"days": 2}, "bo": {"excused": True}}, late_days={"tokens": 1})
    grades, _ = grades_of([student("ann", TWO_DAYS_LATE) | {"late": True}, student("bo", TWO_DAYS_LATE),
                           student("dee", TWO_DAYS_LATE),
                           student("cy", None) | {"late": True}, student("eve", None)], config)
    records = {r.student_id: r for r in records_from_grades(list(grades.values()), 10.0)}
    # ann: late by the LMS's flag, within her extension; dee: two days late, one paid by a late day, one by
    # the penalty; cy: Canvas's late flag (a day), a late day
    assert {s: r.rules for s, r in records.items()} == {
        "ann": ["extension +2 days"], "bo": ["excused"], "dee": ["late days: 1 used", "late 2 days, -1"],
        "cy": ["late days: 1 used", "late 1 day"], "eve": []}
    page = overview_html(list(records.values()))
    assert '<span class="rules">extension +2 days</span>' in page and '<span class="rules">excused</span>' in page
    assert '<span class="rules">late days: 1 used · late 2 days, -1</span>' in page
    # (an excused student has no final grade: not the checks' points told as one, audit of 2026-12-07)
    bo = page[page.index("<li>bo "):page.index("</li>", page.index("<li>bo "))]
    assert "not counted (checks 10 / 10)" in bo and "/ 10" not in bo.split("(checks")[0], bo


def test_the_batch_says_where_it_wrote_the_pooled_ledger(tmp_path, capsys):
    """The term's late-days ledger lies beside the course file, not among the results: the batch's last line names it
    where it is (audit of 2026-12-07: it was listed as a file of the results folder)."""
    import json as _json
    import shutil as _shutil

    from autograder.cli import main
    from conftest import REFERENCE

    (tmp_path / "class" / "alice").mkdir(parents=True)
    _shutil.copy(REFERENCE / "lab07_transformations.py", tmp_path / "class" / "alice")
    (tmp_path / "course").mkdir()
    course = tmp_path / "course" / "c.json"
    course.write_text(_json.dumps({"select": ["lab07.ex1"], "late_penalty": {"per_day": 10, "due": "2026-12-01T00:00:00+00:00"},
                                   "late_days": {"tokens": 3, "ledger": "late_days.json"}}))
    assert main(["batch", str(tmp_path / "class"), "--out", str(tmp_path / "out"), "--course", str(course),
                 "--workers", "1", "--pictures", "none"]) == 0
    said = "".join(capsys.readouterr().out.split())   # (the terminal wraps a long path anywhere)
    assert f";and{tmp_path / 'course' / 'late_days.json'}" in said, said
