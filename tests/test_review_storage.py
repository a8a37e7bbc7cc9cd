"""Issue 30, instructor side: the rubric in the course, its review in the gradebook, and the
review's points in the one final grade (grades.csv, the Canvas import, the student's page).

No grading here: the gradebook is filled with results as the batch records them.
"""

from __future__ import annotations

import csv
import sqlite3

import pytest

from autograder.instructor.batch import exports
from autograder.instructor.batch.gradebook import SCHEMA_VERSION, Gradebook
from autograder.instructor.batch.ingest import Entry
from autograder.instructor.batch.run import class_grades, write_exports, _course_record
from autograder.instructor.course import CourseConfig, CourseConfigError

RUBRIC = {"lab07.ex1": [{"id": "corners", "text": "explains the black corners", "points": 2},
                        {"id": "axes", "text": "names the axes", "points": 1},
                        {"id": "no-figure", "text": "discusses no figure", "points": -1}]}
COURSE = CourseConfig(select=["lab07.ex1"], assignment="Lab 7", rubric=RUBRIC, canvas_assignment_id="77")


# ------------------------------------------------------------------ the course's rubric
@pytest.mark.parametrize("rubric, says", [
    ([], "must be an object of exercises"),
    ({"lab07": [{"id": "a", "text": "t", "points": 1}]}, "not an exercise id"),
    ({"lab07.ex99": [{"id": "a", "text": "t", "points": 1}]}, "lab07.ex99 is no exercise of the labs (lab07 has"),
    ({"lab07.ex1": []}, "non-empty list of items"),
    ({"lab07.ex1": ["corners"]}, "item 1 must be an object"),
    ({"lab07.ex1": [{"id": "a", "text": "t"}]}, "missing ['points']"),
    ({"lab07.ex1": [{"id": "a", "text": "t", "points": 1, "weight": 2}]}, "unknown keys ['weight']"),
    ({"lab07.ex1": [{"id": "a b", "text": "t", "points": 1}]}, "id must be 1 to 40 letters"),
    ({"lab07.ex1": [{"id": "a", "text": " ", "points": 1}]}, "text must be one line"),
    ({"lab07.ex1": [{"id": "a", "text": "two\nlines", "points": 1}]}, "text must be one line"),
    ({"lab07.ex1": [{"id": "a", "text": "t", "points": "2"}]}, "points must be a number"),
    ({"lab07.ex1": [{"id": "a", "text": "t", "points": True}]}, "points must be a number"),
    ({"lab07.ex1": [{"id": "a", "text": "t", "points": float("nan")}]}, "points must be a number"),
    ({"lab07.ex1": [{"id": "a", "text": "t", "points": 1e9}]}, "points must be a number from -1000"),
    ({"lab07.ex1": [{"id": "a", "text": "t", "points": 1}, {"id": "a", "text": "u", "points": 2}]}, "used twice"),
])
def test_a_malformed_rubric_is_refused_saying_which_item_and_why(rubric, says):
    with pytest.raises(CourseConfigError) as raised:
        CourseConfig(rubric=rubric)
    assert says in str(raised.value)


def test_a_rubric_for_an_exercise_the_assignment_does_not_grade_is_refused():
    with pytest.raises(CourseConfigError, match="not in select"):
        CourseConfig(select=["lab08"], rubric=RUBRIC)
    assert CourseConfig(select=["lab07"], rubric=RUBRIC).rubric == RUBRIC   # a lab's selection holds it
    assert CourseConfig(rubric={"lab07.ex1": [{"id": "x", "text": "t", "points": -2.5}]}).rubric


def test_the_rubric_loads_from_the_course_file_and_is_applied_by_the_batch(tmp_path):
    path = tmp_path / "course.json"
    path.write_text(CourseConfig(rubric=RUBRIC).to_json())
    course = CourseConfig.load(path)
    assert course.rubric == RUBRIC and "rubric" not in course.ignored_by("batch")
    assert "rubric" in course.ignored_by("grade")


# ------------------------------------------------------------------ the gradebook
def result(score: float, exercise="lab07.ex1", maximum=12.0) -> dict:
    return {"submission": "s", "total": score, "max_total": maximum, "grader_version": "v", "seconds": 1.0,
            "exercises": [{"id": exercise, "title": "Translate", "score": score, "max_score": maximum,
                           "message": "", "checks": [{"name": "c", "score": score, "max_score": maximum,
                                                       "status": "passed" if score == maximum else "failed",
                                                       "message": "m", "hint": "", "hidden": False,
                                                       "artifacts": []}]}]}


def graded_book(folder, students=("ada", "bo", "cy"), scores=(12.0, 6.0, 0.0), course=COURSE) -> Gradebook:
    book = Gradebook(folder)
    entries = [Entry(s, s.title(), "canvas", f"{s}.py", files={"lab07_transformations.py": b"x"},
                     lms={"canvas_user_id": str(100 + i)}) for i, s in enumerate(students)]
    keys = {e.student_id: f"key-{e.student_id}" for e in entries}
    book.sync_students(entries, keys)
    book.set_meta("course", _course_record(course))
    book.sync_rubric(course.rubric)
    for e, score in zip(entries, scores):
        book.record(keys[e.student_id], e.student_id, e.content_hash, "lab07.ex1", result(score), lock="l")
    return book


def test_marks_and_notes_are_stored_with_who_and_when_and_items_edited_centrally(tmp_path):
    with graded_book(tmp_path) as book:
        assert [i["id"] for i in book.rubric()["lab07.ex1"]] == ["corners", "axes", "no-figure"]
        book.set_mark("ada", "lab07.ex1", "corners", True, "prof")
        book.set_mark("ada", "lab07.ex1", "axes", True, "ta")
        book.set_mark("ada", "lab07.ex1", "axes", True, "ta")          # twice: applied once
        book.set_mark("bo", "lab07.ex1", "corners", True, "prof")
        book.set_mark("bo", "lab07.ex1", "no-figure", True, "prof")
        book.set_review_note("bo", "lab07.ex1", "prof", comment="Good\x1b[31m\u202e\x9b\r\nwork", done=True)
        with pytest.raises(KeyError, match="no rubric item 'nope'"):
            book.set_mark("ada", "lab07.ex1", "nope", True, "prof")
        reviews = book.reviews()
        assert reviews[("ada", "lab07.ex1")]["items"] == ["corners", "axes"]
        assert reviews[("ada", "lab07.ex1")]["points"] == 3
        assert reviews[("ada", "lab07.ex1")]["changed_by"] in ("prof", "ta") and not reviews[("ada", "lab07.ex1")]["done"]
        assert reviews[("bo", "lab07.ex1")] | {"changed_at": ""} == {
            "items": ["corners", "no-figure"], "points": 1, "comment": "Good[31m\nwork", "done": True,
            "changed_by": "prof", "changed_at": ""}
        # One edit of an item's points reaches every student who has it.
        book.set_rubric_item("lab07.ex1", "corners", "explains the black corners of the warp", 4, "prof")
        assert book.reviews()[("ada", "lab07.ex1")]["points"] == 5 and book.reviews()[("bo", "lab07.ex1")]["points"] == 3
        book.set_rubric_item("lab07.ex1", "extra", "tries two sizes", 0.5, "prof")    # added in the review
        assert book.rubric()["lab07.ex1"][-1] | {"changed_at": ""} == {
            "id": "extra", "text": "tries two sizes", "points": 0.5, "changed_by": "prof", "changed_at": ""}
        with pytest.raises(CourseConfigError, match="points must be a number"):
            book.set_rubric_item("lab07.ex1", "corners", "t", float("inf"), "prof")
        book.set_mark("ada", "lab07.ex1", "axes", False, "prof")
        assert book.reviews()[("ada", "lab07.ex1")]["items"] == ["corners"]


def test_the_review_adds_no_more_items_to_an_exercise_than_the_course_file_may_have(tmp_path):
    from autograder.instructor.course import RUBRIC_MAX_ITEMS

    with graded_book(tmp_path) as book:
        have = len(book.rubric()["lab07.ex1"])
        for number in range(RUBRIC_MAX_ITEMS - have):
            book.set_rubric_item("lab07.ex1", f"extra{number}", "another item", 1, "prof")
        with pytest.raises(CourseConfigError, match=f"at most {RUBRIC_MAX_ITEMS}"):
            book.set_rubric_item("lab07.ex1", "one-too-many", "another item", 1, "prof")
        book.set_rubric_item("lab07.ex1", "extra0", "an item edited", 2, "prof")   # editing one still works
        assert len(book.rubric()["lab07.ex1"]) == RUBRIC_MAX_ITEMS


def test_the_course_file_seeds_the_rubric_and_a_later_edit_of_it_wins_once(tmp_path):
    with graded_book(tmp_path) as book:
        book.set_rubric_item("lab07.ex1", "axes", "names both axes", 1.5, "prof")
        book.sync_rubric(RUBRIC)   # the course as before: the review's edit stays
        assert book.rubric()["lab07.ex1"][1]["points"] == 1.5
        edited = {"lab07.ex1": [dict(RUBRIC["lab07.ex1"][1], points=3)]}
        book.sync_rubric(edited)   # the course file changed: its change wins
        assert [(i["id"], i["points"]) for i in book.rubric()["lab07.ex1"]] == [
            ("corners", 2), ("axes", 3), ("no-figure", -1)], "items the course dropped are kept"


def schema_2(path) -> None:
    """The gradebook as schema 2 made it: no report tables, no students.report_problems."""
    db = sqlite3.connect(path)
    for table in ("report_files", "explanations", "rubric_items", "review_marks", "review_notes"):
        db.execute(f"DROP TABLE {table}")
    db.execute("ALTER TABLE students DROP COLUMN report_problems")
    db.execute("UPDATE meta SET value='2' WHERE name='schema_version'")
    db.commit()
    db.close()


def test_a_schema_2_gradebook_is_read_as_it_is_and_migrated_when_opened_for_writing(tmp_path):
    graded_book(tmp_path).close()
    schema_2(tmp_path / "gradebook.sqlite")
    with Gradebook(tmp_path, readonly=True) as book:   # read-only: nothing created, nothing to review yet
        assert book.rubric() == {} and book.reviews() == {} and book.report("ada")["explanations"] == {}
        assert [g.total for g in class_grades(book).grades] == [12, 6, 0]
    with Gradebook(tmp_path) as book:
        assert book.get_meta("schema_version") == str(SCHEMA_VERSION) == "3"
        assert len(book.class_results()) == 3, "the class kept"
        book.sync_rubric(RUBRIC)
        book.set_mark("cy", "lab07.ex1", "corners", True, "prof")
        assert book.reviews()[("cy", "lab07.ex1")]["points"] == 2


# ------------------------------------------------------------------ the final grade
def test_review_points_are_in_the_final_grade_of_every_export_and_the_students_page(tmp_path):
    with graded_book(tmp_path) as book:
        book.set_mark("ada", "lab07.ex1", "corners", True, "prof")
        book.set_mark("ada", "lab07.ex1", "axes", True, "prof")
        book.set_mark("bo", "lab07.ex1", "no-figure", True, "prof")
        book.set_review_note("bo", "lab07.ex1", "prof", comment="<b>Where</b> is the figure?")
        standing = class_grades(book)
    assert standing.report_max == {"lab07.ex1": 3} and standing.possible == 15
    totals = {g.student["student_id"]: g.total for g in standing.grades}
    assert totals == {"ada": 15, "bo": 5, "cy": 0}   # cy: not reviewed, the checks' 0
    for student in ("ada", "bo", "cy"):   # pages as the batch writes them
        (tmp_path / student).mkdir()
        (tmp_path / student / "feedback.html").write_text(
            '<html><title>Feedback: 1 / 12 — x</title><main><header class="summary"><h1><!-- headline -->'
            '1 / 12<!-- /headline --></h1></header><section class="exercise" id="lab07.ex1"><header><h2>lab07.ex1'
            "</h2></header><pre>checks</pre></section></main></html>")
        (tmp_path / student / "results.json").write_text("{}")
    write_exports(tmp_path)
    grades = {r["Student ID"]: r for r in csv.DictReader((tmp_path / "grades.csv").open())}
    assert (grades["ada"]["lab07.ex1"], grades["ada"]["lab07.ex1 report"], grades["ada"]["Total"]) == ("12", "3", "15")
    assert (grades["bo"]["lab07.ex1 report"], grades["bo"]["Total"]) == ("-1", "5")
    assert grades["cy"]["lab07.ex1 report"] == "" and grades["cy"]["Total"] == "0"
    canvas = list(csv.reader((tmp_path / "canvas_import.csv").open()))
    assert canvas[0][-1] == "Lab 7 (77)" and canvas[1][-1] == "15", "points possible hold the report's"
    assert {row[1]: row[-1] for row in canvas[2:]} == {"100": "15", "101": "5", "102": "0"}
    page = (tmp_path / "bo" / "feedback.html").read_text()
    review = page[page.index("<!-- review lab07.ex1 -->"):page.index("<!-- /review lab07.ex1 -->")]
    assert "discusses no figure <b>-1</b>" in review and "-1 / 3 points" in review
    assert "&lt;b&gt;Where&lt;/b&gt; is the figure?" in review, "the comment is escaped"
    assert page.index("<h2>lab07.ex1") < page.index("<!-- review lab07.ex1 -->") < page.index("<pre>checks")
    assert "final grade 5 / 15" in page
    # A second refresh replaces the block (no duplicate); a review taken back removes it.
    with Gradebook(tmp_path) as book:
        book.set_mark("bo", "lab07.ex1", "no-figure", False, "prof")
        book.set_rubric_item("lab07.ex1", "corners", "explains the black corners", 5, "prof")
    write_exports(tmp_path)
    page = (tmp_path / "bo" / "feedback.html").read_text()
    assert page.count("<!-- review lab07.ex1 -->") == 1 and "no figure" not in page
    grades = {r["Student ID"]: r for r in csv.DictReader((tmp_path / "grades.csv").open())}
    assert grades["ada"]["Total"] == "18" and grades["bo"]["Total"] == "6", "the edited item counts for all"
    assert list(csv.reader((tmp_path / "canvas_import.csv").open()))[1][-1] == "18"


def test_the_late_penalty_applies_to_the_reports_points_too():
    students = [{"student_id": "ada", "display_name": "Ada", "status": "graded", "lms": {}, "late": True,
                 "result": result(10.0)}]
    rubric = {"lab07.ex1": [{"id": "a", "text": "t", "points": 10.0}]}
    reviews = {("ada", "lab07.ex1"): {"items": ["a"], "points": 10.0, "comment": ""}}
    course = CourseConfig(select=["lab07.ex1"], late_penalty={"per_day": 50})
    [grade], _ = exports.compute_grades(students, [("lab07.ex1", 12.0)], course, rubric=rubric, reviews=reviews)
    assert grade.late_penalty == 10 and grade.total == 10


@pytest.mark.parametrize("show_final, says", [(True, "final grade 14 / 15"),
                                              (False, "final grade: shown when the hidden checks are released")])
def test_the_reports_points_are_listed_with_the_adjustments_the_final_grade_holds(show_final, says):
    """While hidden points are withheld the headline shows the checks' total only: the block of
    what makes the final grade lists the reviewed reports too, so the page never hides them."""
    grade = exports.StudentGrade(student={"student_id": "ada", "status": "graded"}, exercises={"lab07.ex1": 12},
                                 reports={"lab07.ex1": 2}, reviews={"lab07.ex1": exports.Review([("axes", 2)], 2, 3, "")})
    block = exports.adjustments_html(grade, 15, show_final)
    assert "<td>lab07.ex1 report, reviewed</td><td>+2</td>" in block and says in block
    assert exports.adjustments_html(exports.StudentGrade(student={"student_id": "bo", "status": "graded"},
                                                         exercises={"lab07.ex1": 12}), 15) == \
        f"{exports.BEGIN}{exports.END}", "nothing to list: no block"
