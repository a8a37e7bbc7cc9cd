"""Each LMS in its own terms (issue 28): the exports, from gradebook rows, without grading.

Canvas fills an existing assignment from an import only when the grade column is
named ``"<assignment> (<id>)"`` as in Canvas's own gradebook export; Moodle's
worksheet identifies each row by ``Participant <id>``; every cell is safe to open
in a spreadsheet; overrides find a student by any identity the README promises
and refuse a row that names two.
"""

from __future__ import annotations

import csv
import io

import pytest

from autograder.instructor.batch import exports
from autograder.instructor.course import CourseConfig, CourseConfigError

RAW = [("lab07.ex1", 12.0)]

# Canvas's "Export" of the gradebook, as an instructor downloads it.
CANVAS_EXPORT = (
    "Student,ID,SIS User ID,SIS Login ID,Section,Lab 7 (12345),Lab 8 (12346),Current Score,Final Score\n"
    "    Points Possible,,,,,12,20,(read only),(read only)\n"
    '"Kim, Bo",1001,S1,bkim,A,,,,\n'
    '"Lee, Ann",1002,S2,alee,A,,,,\n'
    '"Nobody, Ned",1003,S3,nned,B,,,,\n')


def student(student_id, name, total=12.0, source="canvas", **lms):
    return {"student_id": student_id, "display_name": name, "source": source, "origin": student_id,
            "lms": lms, "members": [], "submitted_at": None, "late": None, "status": "graded", "reason": "",
            "result": {"total": total, "max_total": 12.0,
                       "exercises": [{"id": "lab07.ex1", "score": total, "max_score": 12.0}]},
            "feedback": f"{student_id}/feedback.html"}


CLASS = [student("kimbo-1001", "kimbo", canvas_user_id="1001"),
         student("leeann-1002", "leeann", 4.0, canvas_user_id="1002"),
         student("=evil-1004", "=HYPERLINK(\"http://x\",\"click\")", 1.0, canvas_user_id="1004")]


def roster(tmp_path, text=CANVAS_EXPORT):
    path = tmp_path / "roster.csv"
    path.write_text(text)
    return exports.read_roster(path)


def written(tmp_path, course, students=CLASS, rows=None, overrides=()):
    rows = rows if rows is not None else exports.Roster()
    grades, warnings = exports.compute_grades(students, RAW, course, overrides, rows)
    exports.write_csvs(tmp_path, grades, RAW, course, roster_given=bool(rows),
                       roster_columns=getattr(rows, "columns", ()))
    tables = {p.name: list(csv.reader(p.open(newline="", encoding="utf-8"))) for p in tmp_path.glob("*.csv")
              if p.name != "roster.csv"}
    return tables, warnings


def test_the_canvas_import_fills_the_assignment_of_the_canvas_export_it_came_from(tmp_path):
    tables, warnings = written(tmp_path, CourseConfig(assignment="Lab 7"), rows=roster(tmp_path))
    assert not [w for w in warnings if "Canvas" in w]
    header, points, *body = tables["canvas_import.csv"]
    assert header == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "Lab 7 (12345)"]
    assert points[0] == "Points Possible" and points[-1] == "12"
    by_id = {row[1]: row for row in body}
    # the round trip: the roster's identities come back as Canvas wrote them
    assert by_id["1001"][:5] == ["Kim, Bo", "1001", "S1", "bkim", "A"] and by_id["1001"][-1] == "12"
    assert by_id["1002"][-1] == "4"
    # grades.csv names students as the roster does
    names = {row[0]: row[1] for row in tables["grades.csv"][1:]}
    assert names["kimbo-1001"] == "Kim, Bo" and names["leeann-1002"] == "Lee, Ann"


def test_the_canvas_id_from_the_course_and_a_warning_when_the_export_has_no_such_assignment(tmp_path):
    tables, _ = written(tmp_path / "a", CourseConfig(assignment="Lab 7", canvas_assignment_id="777"))
    assert tables["canvas_import.csv"][0][-1] == "Lab 7 (777)"
    _, warnings = written(tmp_path / "b", CourseConfig(assignment="Lab 9"), rows=roster(tmp_path))
    assert any("no column for the assignment 'Lab 9'" in w and "Lab 7 (12345)" in w for w in warnings)
    with pytest.raises(CourseConfigError, match="canvas_assignment_id"):
        CourseConfig(canvas_assignment_id="Lab 7")


@pytest.fixture(autouse=True)
def _folders(tmp_path):
    for name in ("a", "b", "c", "d"):
        (tmp_path / name).mkdir()


def test_moodle_worksheet_only_where_moodle_applies(tmp_path):
    tables, _ = written(tmp_path / "a", CourseConfig(assignment="Lab 7"))
    assert "moodle_import.csv" not in tables and "canvas_import.csv" in tables
    moodle_class = [student("ann-lee-501", "Ann Lee", source="moodle", moodle_participant_id="501")]
    tables, _ = written(tmp_path / "b", CourseConfig(assignment="Lab 7"), students=moodle_class)
    assert tables["moodle_import.csv"][1] == ["Participant 501", "Ann Lee", "", "12"]
    tables, _ = written(tmp_path / "c", CourseConfig(assignment="Lab 7", lms_exports=["moodle"]))
    assert "moodle_import.csv" in tables and "canvas_import.csv" not in tables
    moodle_roster = roster(tmp_path / "d", "Identifier,Full name,Email address\nParticipant 7,Kim Bo,bo@x\n")
    tables, _ = written(tmp_path / "d", CourseConfig(assignment="Lab 7"), rows=moodle_roster)
    assert "moodle_import.csv" in tables


def test_every_cell_of_every_export_is_safe_to_open_in_a_spreadsheet(tmp_path):
    tables, _ = written(tmp_path, CourseConfig(assignment="Lab 7", lms_exports=["canvas", "moodle"]))
    cells = [cell for rows in tables.values() for row in rows for cell in row]
    assert "'=HYPERLINK(\"http://x\",\"click\")" in cells and "'=evil-1004" in cells
    assert not [c for c in cells if c[:1] in ("=", "+", "@", "\t", "\r")]
    assert not [c for c in cells if c.startswith("-") and not c[1:].replace(".", "").isdigit()]


@pytest.mark.parametrize("who", ["kimbo-1001", "Kim, Bo", "Bo Kim", "bo kim", "bkim", "S1", "1001"])
def test_an_override_finds_the_student_by_every_identity(tmp_path, who):
    override = exports.Override(who, "total", 1.0, None, "presented in class")
    grades, warnings = exports.compute_grades(CLASS, RAW, CourseConfig(), [override], roster(tmp_path))
    assert not [w for w in warnings if "override" in w]
    [kim] = [g for g in grades if g.student["student_id"] == "kimbo-1001"]
    assert kim.total == 13.0


def test_an_ambiguous_override_is_refused_naming_the_candidates(tmp_path):
    twins = [student("ann-lee-1", "Ann Lee"), student("ann-lee-2", "Lee Ann")]
    override = exports.Override("Ann Lee", "total", 1.0, None, "")
    grades, warnings = exports.compute_grades(twins, RAW, CourseConfig(), [override])
    assert [w for w in warnings if "ambiguous" in w and "ann-lee-1" in w and "ann-lee-2" in w]
    assert [g.total for g in grades] == [12.0, 12.0]
    # the derived id is never ambiguous
    grades, warnings = exports.compute_grades(twins, RAW, CourseConfig(), [exports.Override("ann-lee-2", "total",
                                                                                            1.0, None, "")])
    assert [g.total for g in grades] == [12.0, 13.0] and not warnings


def test_spreadsheet_safe_leaves_numbers_and_text_alone():
    assert [exports.spreadsheet_safe(c) for c in ["12", "-2", "+1.5", "1e-3", "Ann", "", None]] == \
        ["12", "-2", "+1.5", "1e-3", "Ann", "", ""]
    assert [exports.spreadsheet_safe(c) for c in ["=1+1", "-1+1", "@A1", "\tx", "\rx", "+cmd"]] == \
        ["'=1+1", "'-1+1", "'@A1", "'\tx", "'\rx", "'+cmd"]
    buffer = io.StringIO()
    csv.writer(buffer).writerow([exports.spreadsheet_safe("=1+1")])
    assert buffer.getvalue().startswith("'=1+1")


def test_a_class_of_folders_matches_canvas_s_own_export_by_login(tmp_path):
    """Folders named after the students' logins (alice/, bkim/) match Canvas's gradebook export as it is: its SIS
    Login ID, or SIS User ID, is the folder's name (audit of 2026-12-07: every student was "not on the roster")."""
    rows = roster(tmp_path)
    folders = [student("bkim", "bkim", source="folder"), student("s2", "s2", 4.0, source="folder")]
    matched, unmatched, absent = exports.match_roster(folders, list(rows))
    assert matched["bkim"]["name"] == "Kim, Bo" and matched["s2"]["name"] == "Lee, Ann"
    assert not unmatched and [row["name"] for row in absent] == ["Nobody, Ned"]


def test_a_late_rule_over_an_upload_without_times_says_it_applied_nothing():
    """A plain folder carries no submission times: the late rule cannot apply, and the batch says so (audit of
    2026-12-07: it applied nothing, silently)."""
    course = CourseConfig(late_penalty={"per_day": 10, "due": "2026-12-01T00:00:00+00:00"})
    folders = [student("ann", "ann", source="folder")]
    _, warnings = exports.compute_grades(folders, RAW, course)
    assert any("no submission times" in w for w in warnings), warnings
    timed = [dict(student("bo", "bo"), submitted_at="2026-12-03T10:00:00+00:00")]
    grades, warnings = exports.compute_grades(timed, RAW, course)
    assert not any("no submission times" in w for w in warnings) and grades[0].late_penalty > 0


def test_rows_an_lms_cannot_match_are_counted_in_a_warning(tmp_path):
    """Audit of 2026-12-07: a class of plain folders gave a Canvas import whose ID, SIS User ID and SIS Login ID were
    empty, and a Canvas download asked for Moodle's worksheet too gave empty identifiers -- rows the LMS cannot
    match, without a word. The batch says how many, and what would give them."""
    folders = [student("alice", "alice", source="folder"), student("bob", "bob", 4.0, source="folder")]
    grades, _ = exports.compute_grades(folders, RAW, CourseConfig(assignment="Lab 7"), (), exports.Roster())
    [canvas] = exports.lms_warnings(grades, CourseConfig(assignment="Lab 7"))
    assert canvas.startswith("canvas_import.csv: 2 of 2 graded rows have no Canvas ID") and "--roster" in canvas
    # the class's own Canvas export as the roster: matched by login, every row has its ids
    rows = roster(tmp_path, CANVAS_EXPORT.replace("bkim", "alice").replace("alee", "bob"))
    grades, _ = exports.compute_grades(folders, RAW, CourseConfig(assignment="Lab 7"), (), rows)
    assert exports.lms_warnings(grades, CourseConfig(assignment="Lab 7"), rows.columns) == []
    # a Canvas download (its user ids) asked for Moodle's worksheet too: no identifier for Moodle
    both = CourseConfig(assignment="Lab 7", lms_exports=["canvas", "moodle"])
    grades, _ = exports.compute_grades(CLASS, RAW, both, (), exports.Roster())
    [moodle] = exports.lms_warnings(grades, both)
    assert moodle.startswith("moodle_import.csv: 3 of 3 graded rows have no Identifier")
