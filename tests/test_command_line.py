"""The command line is consistent (issue 36): every command takes its options and its
arguments in any order, says its own usage on an error, and lists what it wrote."""

from __future__ import annotations

import itertools
import json
import re
import shutil

import pytest

from autograder.cli import build_parser, main
from conftest import REFERENCE

LAB07 = "lab07_transformations"

# autograder grade SUB [SELECT...] with options: each order parses to the same request.
GRADE_PARTS = [["SUB"], ["--show-hidden"], ["--no-html"], ["--json", "out.json"]]
SELECTORS = ["lab07.ex2", "lab08"]


def grade_orders():
    """Every order of the parts, the selectors after the submission (before, after or between
    the options), as written on a command line."""
    for order in itertools.permutations(GRADE_PARTS):
        words = [word for part in order for word in part]
        at = words.index("SUB") + 1
        for gap in sorted({at, len(words)} | {i for i in range(at, len(words) + 1)
                                                if i == len(words) or words[i].startswith("--")}):
            yield ["grade", *words[:gap], *SELECTORS, *words[gap:]]


@pytest.mark.parametrize("argv", list(grade_orders()), ids=" ".join)
def test_grade_takes_options_and_selectors_in_any_order(argv):
    args = build_parser().parse_args(argv)
    assert (args.submission, args.select, args.show_hidden, args.no_html, args.json) == (
        "SUB", SELECTORS, True, True, "out.json")


@pytest.mark.parametrize("argv, expected", [
    (["validate", "--config", "c.json", "SUB", "lab07"], {"submission": "SUB", "select": ["lab07"], "config": "c.json"}),
    (["validate", "SUB", "--config", "c.json", "lab07", "lab08"],
     {"submission": "SUB", "select": ["lab07", "lab08"], "config": "c.json"}),
    (["verify", "lab07", "--course", "c.json", "lab13"], {"labs": ["lab07", "lab13"], "course": "c.json"}),
    (["batch", "--out", "R", "SUBS", "--workers", "2"], {"submissions": "SUBS", "out": "R", "workers": 2}),
])
def test_every_command_taking_arguments_takes_them_between_options(argv, expected):
    args = vars(build_parser().parse_args(argv))
    assert {key: args[key] for key in expected} == expected


def test_grade_grades_selectors_written_after_its_options(tmp_path, capsys):
    """The issue's command, graded: the selector after the options is the one graded."""
    out = tmp_path / "r.json"
    assert main(["grade", str(REFERENCE), "--show-hidden", "--no-html", "lab07.ex1", "--json", str(out)]) == 0
    assert [e["id"] for e in json.loads(out.read_text())["exercises"]] == ["lab07.ex1"]


@pytest.mark.parametrize("argv, usage", [
    (["grade", "SUB", "--no-such-flag"], "usage: autograder grade "),
    (["grade", "SUB", "lab07", "--timeout", "soon"], "usage: autograder grade "),
    (["list", "--ids", "extra"], "usage: autograder list "),
    (["report", "R", "--no-such-flag"], "usage: autograder report "),
    (["gradescope", "build", "--no-such-flag"], "usage: autograder gradescope build "),
])
def test_an_error_shows_the_commands_own_usage(argv, usage, capsys):
    with pytest.raises(SystemExit) as exit_:
        build_parser().parse_args(argv)
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith(usage), err
    assert "{grade,list" not in err       # not the top-level usage
    bad = argv[-1] if argv[-1].startswith("--no-such") or argv[-1] == "extra" else None
    if bad:
        assert f"unrecognized arguments: {bad}" in err


def test_grade_py_takes_selectors_around_options(tmp_path):
    from autograder.cli import CommandParser, add_grading_options

    parser = CommandParser(prog="grade.py")
    add_grading_options(parser)
    args = parser.parse_args(["lab07", "--no-html", "lab08.ex1", "--quiet"])
    assert args.select == ["lab07", "lab08.ex1"] and args.no_html and args.quiet


# ------------------------------------------------------------------ report lists what it wrote
@pytest.mark.slow
def test_report_lists_the_exports_and_the_student_pages_it_wrote(tmp_path, capsys):
    submissions = tmp_path / "class"
    for student in ("ada", "bo"):
        (submissions / student).mkdir(parents=True)
        shutil.copy(REFERENCE / f"{LAB07}.py", submissions / student)
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"select": ["lab07.ex1"]}))
    results = tmp_path / "results"
    assert main(["batch", str(submissions), "--out", str(results), "--workers", "1", "--pictures", "none",
                 "--course", str(course)]) == 0
    capsys.readouterr()
    assert main(["report", str(results)]) == 0
    [line] = [line for line in capsys.readouterr().out.splitlines() if line.startswith("wrote ")]
    match = re.fullmatch(rf"wrote {re.escape(results.as_posix())}/ : (.+); (\d+) student pages up to date "
                         r"\(<student>/feedback\.html\)", line)
    assert match, line
    named = match.group(1).split(", ")
    assert {"grades.csv", "changes.csv", "index.html"} <= set(named), named
    assert all((results / name).is_file() for name in named), named
    assert int(match.group(2)) == 2
