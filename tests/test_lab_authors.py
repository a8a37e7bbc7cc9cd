"""What lab authors meet (issue 36): new-lab prints the line for course.json, verify holds
every lab to one minimum of mistakes per exercise (a course's ``min_mistakes``, default 5)
and fits an 80-column terminal, and a course of its own labs grades those only."""

from __future__ import annotations

import io
import json
import re
from pathlib import Path

import pytest
from rich.console import Console

from autograder.cli import main
from autograder.engine.labfolders import forget_lab_folders
from autograder.engine.registry import discover
from autograder.instructor.course import CourseConfig, CourseConfigError
from autograder.instructor.newlab import course_entry
from autograder.instructor.verify import (MIN_MISTAKES, Case, CaseReport, CheckReport, LabReport, parts_of,
                                          render, too_few_mistakes)

from test_course_labs import REFERENCE, course_labs_forgotten  # noqa: F401 - autouse: built-in labs only
from test_course_labs import course_copy as copy_of_the_example_course

pytestmark = pytest.mark.xdist_group("course_labs")


def course_copy(tmp_path: Path, **keys) -> Path:
    """The example course (lab13) copied, its course.json given ``keys`` too; returns the file."""
    course = copy_of_the_example_course(tmp_path) / "course.json"
    course.write_text(json.dumps({**json.loads(course.read_text()), **keys}))
    return course


def keep_two_histogram_mistakes(course: Path) -> None:
    """lab13.ex1's table cut to its first two cases (the others' sources removed with them)."""
    table = course.parent / "labs" / "imstats" / "mistakes.py"
    text = table.read_text()
    start, end = text.index('    "cumulative histogram"'), text.index('    "stretch in uint8"')
    table.write_text(text[:start] + text[end:])


# ------------------------------------------------------------------ new-lab
def test_new_lab_prints_the_line_for_the_course_file_relative_to_it(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "course").mkdir()
    (tmp_path / "course" / "course.json").write_text(json.dumps({"labs": ["labs/imstats"], "assignment": "A"}))
    assert main(["new-lab", "lab14_flow", "--into", "labs/flow",
                 "--course", "course/course.json"]) == 0
    out = capsys.readouterr().out
    assert '  "labs": ["labs/imstats", "../labs/flow"]' in out.splitlines()
    assert str(tmp_path) not in out   # nothing absolute to edit by hand (the folder was given relative)
    assert "autograder verify --course course/course.json" in out


def test_new_lab_without_a_course_file_prints_the_whole_file(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["new-lab", "lab14_flow", "--into", "labs/flow"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert "write course.json (it does not exist yet):" in out and '  {"labs": ["labs/flow"]}' in out
    # Pasted as printed, the course finds the lab.
    (tmp_path / "course.json").write_text(out[out.index('  {"labs": ["labs/flow"]}')].strip())
    assert CourseConfig.load(tmp_path / "course.json").select == ["lab14"]


def test_the_printed_folder_is_the_one_the_course_reads(tmp_path):
    course = tmp_path / "a" / "course.json"
    course.parent.mkdir()
    line = course_entry(tmp_path / "b" / "lab", course)
    assert json.loads(line) == {"labs": ["../b/lab"]}
    assert (course.parent / "../b/lab").resolve() == (tmp_path / "b" / "lab").resolve()


# ------------------------------------------------------------------ verify: a minimum of mistakes
def test_a_course_lab_with_two_mistakes_in_an_exercise_is_refused(tmp_path, capsys):
    course = course_copy(tmp_path)
    keep_two_histogram_mistakes(course)
    assert main(["verify", "--course", str(course)]) == 1
    out = "".join(capsys.readouterr().out.split())   # the terminal's width folds the long path anywhere
    assert "lab13isnotsound" in out
    assert "".join((f"lab13.ex1 has 2 mistakes in its table ({course.parent / 'labs' / 'imstats' / 'mistakes.py'}); "
                    "every exercise of every lab needs at least 5 (the course's min_mistakes), or the reason its "
                    "algorithm has fewer in FEWER_MISTAKES").split()) in out


def test_the_minimum_is_the_courses_and_a_reason_excuses_an_exercise(tmp_path):
    course = course_copy(tmp_path, min_mistakes=2)
    keep_two_histogram_mistakes(course)
    config = CourseConfig.load(course)
    assert config.min_mistakes == 2
    parts = parts_of(discover()["lab13"])
    assert too_few_mistakes(parts, config.min_mistakes) == []
    assert [p.split(" ")[0] for p in too_few_mistakes(parts, 3)] == ["lab13.ex1"]
    assert [p.split(" ")[0] for p in too_few_mistakes(parts, MIN_MISTAKES)] == ["lab13.ex1"]   # ex2 has 6
    table = course.parent / "labs" / "imstats" / "mistakes.py"
    table.write_text('FEWER_MISTAKES = {"lab13.ex1": "a histogram has few ways to go wrong"}\n' + table.read_text())
    forget_lab_folders()
    CourseConfig.load(course)
    assert too_few_mistakes(parts_of(discover()["lab13"]), MIN_MISTAKES) == []


def test_the_built_in_labs_meet_the_same_minimum():
    for key in sorted(k for k, lab in discover().items() if lab.folder is None):
        assert too_few_mistakes(parts_of(discover()[key]), MIN_MISTAKES) == [], key


@pytest.mark.parametrize("value", [-1, 2.5, True, "5"])
def test_min_mistakes_must_be_a_whole_number(value):
    with pytest.raises(CourseConfigError, match="min_mistakes must be a whole number"):
        CourseConfig(min_mistakes=value)


def test_min_mistakes_is_no_key_a_grading_warns_about():
    assert CourseConfig(min_mistakes=3).ignored_by("batch") == []


# ------------------------------------------------------------------ verify: 80 columns
def long_report(lab_key: str = "lab08") -> LabReport:
    """A report on a built-in lab's real checks (long titles), with long case names and problems."""
    lab = discover()[lab_key]
    checks = [CheckReport(e.id, c.name, c.points, c.hidden, c.advice, 12.345, i % 3, i % 4 != 1)
              for e in lab.exercises.values() for i, c in enumerate(e.checks)]
    first = next(iter(lab.exercises.values())).id
    cases = [CaseReport(Case("a mistake whose name alone is longer than a column could ever be", first, "",
                             ("x",)), 3, 10, [], 0.3),
             CaseReport(Case("short", first, "", ("x",)), 10, 10,
                        ["loses no points in " + first + ": every check passed, but the implementation is wrong",
                         "not named in its own words"], 0.3)]
    return LabReport(lab_key, lab.title, (60, 60), [], (0, 60), ["the skeleton scores 3 in " + first], cases,
                     checks, 12.0)


@pytest.mark.parametrize("width", [80, 100])
def test_verify_tables_fit_the_terminal_one_line_a_row(width):
    report = long_report()
    console = Console(file=io.StringIO(), width=width, color_system=None)
    render(report, console)
    lines = console.file.getvalue().splitlines()
    assert max(len(line) for line in lines) <= width
    # One line per check: each starts with its exercise and the beginning of its title.
    rows = [line for line in lines if re.match(r"(ex|ext)\d+ ", line)]
    assert len(rows) == len(report.checks)
    for check, row in zip(report.checks, rows):
        assert row.startswith(check.exercise.split(".")[1] + " ") and check.name[:20] in row, (check.name, row)
    assert len([line for line in lines if line.startswith("mistake: ")]) == len(report.cases)
    # Every problem is listed whole after the tables, however the table cut it.
    listed = " ".join(" ".join(lines[lines.index(next(l for l in lines if "is not sound" in l)):]).split())
    for problem in report.problems:
        assert " ".join(problem.split()) in listed


# ------------------------------------------------------------------ a course of its own labs
def test_a_course_without_select_grades_its_own_labs_only(tmp_path, capsys):
    course = course_copy(tmp_path)
    assert CourseConfig.load(course).select == ["lab13"]
    out = tmp_path / "results.json"
    assert main(["grade", str(REFERENCE), "--no-html", "--config", str(course), "--json", str(out)]) == 0
    assert {e["id"].split(".")[0] for e in json.loads(out.read_text())["exercises"]} == {"lab13"}
    printed = capsys.readouterr()
    assert "not found" not in printed.out + printed.err


def test_a_course_that_selects_keeps_its_selection(tmp_path):
    course = course_copy(tmp_path, select=["lab07", "lab13.ex2"])
    assert CourseConfig.load(course).select == ["lab07", "lab13.ex2"]
    assert CourseConfig.load(course_copy(tmp_path / "2", labs=[])).select == []   # no labs: every built-in lab
