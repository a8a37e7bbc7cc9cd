"""The lab report, student side (issue 30): ``--report DIR`` writes a scaffold with the
figures of the student's own code; ``autograder.loading.report`` reads the explanations
back, safely, from Markdown and from notebooks."""

import json
import shutil

import cv2
import pytest
from hypothesis import given, settings, strategies as st

from autograder import cli
from autograder.engine.registry import select
from autograder.engine.results import CheckResult, ExerciseResult, GradingResult
from autograder.figures import SHEET_PICTURES, producers_for
from autograder.loading.report import (MAX_EXPLANATION_CHARS, MAX_EXPLANATIONS, MAX_PROBLEMS, MAX_REPORT_BYTES,
                                       PLACEHOLDER, explanations_in_markdown, explanations_in_notebook,
                                       read_report)
from autograder.student.report import Section, report_name, scaffold, write_report
from conftest import REFERENCE, mutant

START, END = "<!-- explanation {} -->", "<!-- end explanation -->"


@pytest.fixture(scope="module")
def reference_report(tmp_path_factory):
    """The scaffold of every lab for the reference solutions, figures and all, made once."""
    folder = tmp_path_factory.mktemp("report")
    return folder, write_report(REFERENCE, [], folder)


def report_text(folder, lab: str) -> str:
    return (folder / report_name(lab)).read_text(encoding="utf-8")


def section_ids(text: str) -> list[str]:
    return [line[len("<!-- explanation "):-len(" -->")] for line in text.splitlines()
            if line.startswith("<!-- explanation ")]


def written_everywhere(text: str) -> tuple[str, dict[str, str]]:
    """``text`` with each placeholder replaced by an answer naming its section."""
    answers = {}
    for section in section_ids(text):
        answers[section] = f"In **{section}** the corners go black: no source pixel lands there (x' = H x). é✓"
        text = text.replace(f"{START.format(section)}\n{PLACEHOLDER}\n",
                            f"{START.format(section)}\n{answers[section]}\n", 1)
    return text, answers


# ------------------------------------------------------------------ the scaffold
def test_every_picture_the_sheet_asks_for_is_in_the_reference_scaffold(reference_report):
    folder, report = reference_report
    assert [o.figure_id for o in report.figures if o.path is None] == []
    for figure_id in SHEET_PICTURES:
        text = report_text(folder, figure_id[:5])
        assert f"![{figure_id}](figures/{figure_id}.png)" in text, figure_id
        picture = cv2.imread(str(folder / "figures" / f"{figure_id}.png"))
        assert picture is not None and picture.shape[1] >= 400, figure_id


def test_every_exercise_and_experiment_has_a_section_and_an_empty_place_to_explain(reference_report):
    folder, report = reference_report
    assert sorted(path.name for path in report.files) == sorted(
        report_name(lab) for lab in {ex.lab.key for ex in select()})
    for exercise in select():
        text = report_text(folder, exercise.lab.key)
        expected = [exercise.id] + [p.figure_id for p in producers_for(exercise.id) if p.figure_id != exercise.id]
        for section in expected:
            assert f"\n## {section}: " in text
            assert f"{START.format(section)}\n{PLACEHOLDER}\n{END}" in text
            assert "Automatic verdict: not graded in this run" in text
    for path in report.files:
        untouched = read_report({path.name: path.read_bytes()})
        assert untouched.explanations == {} and untouched.problems == ()


def test_what_a_student_writes_in_the_scaffold_is_read_back_per_exercise(reference_report):
    folder, _ = reference_report
    for lab in sorted({ex.lab.key for ex in select()}):
        text, answers = written_everywhere(report_text(folder, lab))
        report = read_report({report_name(lab): text.encode()})
        assert {k: e.text for k, e in report.explanations.items()} == answers
        assert {e.source for e in report.explanations.values()} == {report_name(lab)}
        assert report.problems == ()


def test_the_verdict_line_is_the_gradings_and_an_exercise_without_a_picture_says_so():
    checks = [CheckResult("a", 3.0, 4.0, "partial"), CheckResult("b", 0.0, 6.0, "failed")]
    result = GradingResult("s", "h", "v", [ExerciseResult("lab10.ex4", "Camera matrix by the DLT", [], checks)])
    [exercise] = select(["lab10.ex4"])
    from autograder.student.report import _sections
    [section] = _sections(exercise, {}, {e.id: e for e in result.exercises}, REFERENCE / "nowhere")
    assert section.verdict == "Automatic verdict: 3 / 10 (partly passed)"
    assert section.figures[0].startswith("_No figure: the lab sheet asks for numbers")


# ------------------------------------------------------------------ writing again
def test_running_again_keeps_every_explanation_and_refreshes_figures_and_verdicts(reference_report, tmp_path):
    folder, _ = reference_report
    shutil.copytree(folder, tmp_path, dirs_exist_ok=True)
    path = tmp_path / report_name("lab07")
    text, answers = written_everywhere(path.read_text())
    text = text.replace("Automatic verdict: not graded in this run", "Automatic verdict: 1 / 10 (partly passed)")
    # markers of ex3 deleted: its text under the heading still counts (and gets its markers back)
    text = text.replace(START.format("lab07.ex3") + "\n", "").replace(answers["lab07.ex3"] + f"\n{END}",
                                                                     answers["lab07.ex3"])
    text += f"\n{START.format('lab07.ex9')}\nAn exercise that does not exist.\n{END}\n"
    path.write_text(text)
    before = read_report({path.name: text.encode()}).explanations
    assert set(before) == set(answers) | {"lab07.ex9"}

    checks = [CheckResult("a", 10.0, 10.0, "passed")]
    graded = GradingResult("s", "h", "v", [ExerciseResult("lab07.ex1", "Translation", [], checks)])
    rerun = write_report(REFERENCE, ["lab07.ex1"], tmp_path, graded)
    again = path.read_text()
    after = read_report({path.name: again.encode()})
    assert {k: e.text for k, e in after.explanations.items()} == {k: e.text for k, e in before.items()}
    assert after.problems == ()
    assert rerun.kept[path.name] == len(before)
    assert f"{START.format('lab07.ex3')}\n{answers['lab07.ex3']}\n{END}" in again
    ex1, ex2 = again.split("## lab07.ex2")[0].split("## lab07.ex1")[1], again.split("## lab07.ex2")[1]
    assert "Automatic verdict: 10 / 10 (passed)" in ex1          # graded now: refreshed
    assert "Automatic verdict: 1 / 10 (partly passed)" in ex2.split("## ")[0]  # not graded now: kept
    assert (tmp_path / "lab07_report.previous.md").read_text() == text
    # and once more, unchanged: the file is stable
    write_report(REFERENCE, ["lab07.ex1"], tmp_path, graded)
    assert path.read_text() == again


def test_a_figure_that_cannot_be_made_says_why_and_an_old_picture_of_it_is_removed(tmp_path):
    submission = mutant(tmp_path, "lab07_transformations", """
        def rotate(image, angle_deg=45):
            raise ValueError("boom at the corners")
        """)
    out = tmp_path / "out"
    (out / "figures").mkdir(parents=True)
    (out / "figures" / "lab07.ex2.png").write_bytes(b"an old picture")
    write_report(submission, ["lab07.ex2"], out)
    text = (out / report_name("lab07")).read_text()
    section = text.split("## lab07.ex2")[1].split("## ")[0]
    assert "_No figure: rotate() raised ValueError: boom at the corners_" in section  # the function named once
    assert not (out / "figures" / "lab07.ex2.png").exists()
    assert "No figure yet: run `python grade.py --report DIR lab07.ex1`" in text


def test_grade_py_report_writes_the_scaffold_beside_the_grading(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status = cli.main(["grade", str(REFERENCE), "lab08.ex4", "--report", "report", "--no-html", "--quiet"])
    assert status == 0
    text = (tmp_path / "report" / "lab08_report.md").read_text()
    section = text.split("## lab08.ex4")[1].split("## ")[0]
    assert "![lab08.ex4](figures/lab08.ex4.png)" in section
    assert "Automatic verdict: " in section and "(passed)" in section
    assert "report/lab08_report.md" in capsys.readouterr().out.replace("\n", "")


# ------------------------------------------------------------------ hostile reports
def test_a_report_too_large_is_refused_with_its_reason_and_the_others_are_read():
    small = f"{START.format('lab07.ex1')}\nfine\n{END}".encode()
    huge = (f"{START.format('lab07.ex2')}\n" + "x" * MAX_REPORT_BYTES).encode()
    report = read_report({"a/lab07_report.md": small, "b/lab08_report.md": huge})
    assert list(report.explanations) == ["lab07.ex1"]
    assert len(report.problems) == 1 and "b/lab08_report.md" in report.problems[0] and "MiB" in report.problems[0]


def test_a_long_explanation_is_cut_and_marked():
    text = f"{START.format('lab07.ex1')}\n{'word ' * MAX_EXPLANATION_CHARS}\n{END}"
    [explanation] = explanations_in_markdown(text, "r.md").values()
    assert explanation.truncated and len(explanation.text) == MAX_EXPLANATION_CHARS


def test_control_characters_go_and_html_stays_text_as_written():
    written = "Look\x1b[2J\x00 at \u202eit\x07 <script>alert(1)</script> <img src=http://x/y.png>"
    text = f"## lab07.ex1: T\n{START.format('lab07.ex1')}\n{written}\n{END}\n"
    [explanation] = read_report({"r.md": text.encode()}).explanations.values()
    assert explanation.text == "Look[2J at it <script>alert(1)</script> <img src=http://x/y.png>"


def test_an_exercise_explained_twice_keeps_both_texts_and_says_so():
    text = (f"{START.format('lab07.ex1')}\nfirst\n{END}\n{START.format('LAB07.EX1')}\nsecond\n{END}\n")
    report = read_report({"lab07_transformations.ipynb": notebook(("report:lab07.ex1", "third")),
                          "lab07_report.md": text.encode()})  # read in path order
    assert report.explanations["lab07.ex1"].text == "first\n\nsecond\n\nthird"
    assert len(report.problems) == 2 and all("twice" in p for p in report.problems)


def test_a_missing_end_marker_ends_the_explanation_at_the_next_section():
    text = (f"## lab07.ex1: A\n{START.format('lab07.ex1')}\nfirst\n\n## lab07.ex2: B\n"
            f"{START.format('lab07.ex2')}\nsecond\n{END}\n")
    report = read_report({"r.md": text.encode()})
    assert {k: e.text for k, e in report.explanations.items()} == {"lab07.ex1": "first", "lab07.ex2": "second"}
    assert len(report.problems) == 1 and "lab07.ex1" in report.problems[0]


def test_without_markers_the_text_under_the_heading_counts_but_not_the_scaffolds_lines():
    text = ("# lab07 report\n\n## lab07.ex1: Translation\n\n![lab07.ex1](figures/lab07.ex1.png)\n\n"
            "Automatic verdict: 10 / 10 (passed)\n\nIt moved.\n\n```python\n# a comment, no heading\nx = 1\n```\n\n"
            "## lab07.ex2: Rotation\n\n_No figure: rotate(): boom_\n\nAutomatic verdict: 0 / 10\n\n"
            f"{PLACEHOLDER}\n\n## Notes\nnot an exercise\n")
    found = explanations_in_markdown(text, "r.md")
    assert {k: e.text for k, e in found.items()} == {
        "lab07.ex1": "It moved.\n\n```python\n# a comment, no heading\nx = 1\n```"}


def test_a_flood_of_markers_is_bounded():
    text = "".join(f"{START.format(f'lab07.ex{n}')}\nsome text\n{END}\n" for n in range(1, 2000))
    text += "".join(f"<!-- explanation not-an-id-{n} -->\n" for n in range(200))
    report = read_report({"r.md": text.encode()})
    assert len(report.explanations) == MAX_EXPLANATIONS
    assert len(report.problems) == MAX_PROBLEMS + 1 and report.problems[-1].startswith("and ")


def notebook(*cells, raw: bool = False) -> bytes:
    """A notebook of Markdown cells: ``(tag or None, text)`` pairs."""
    return json.dumps({"cells": [{"cell_type": "markdown", "metadata": {"tags": [tag] if tag else []},
                                  "source": text} for tag, text in cells], "nbformat": 4}).encode()


def test_notebook_cells_tagged_or_marked_are_explanations():
    data = notebook(("report:lab07.ex1", [f"{START.format('lab07.ex1')}\n", "Tagged **cell**.\n"]),
                    (None, f"Before the marker counts too.\n{START.format('lab07.ex2')}\n"
                           f"{PLACEHOLDER}\nMarked.\n{END}"),
                    (None, "# A heading cell with nothing to do with the report"),
                    ("report:lab07.ex3", PLACEHOLDER),
                    (None, f"{START.format('lab07.ex4')}\nfour\n{END}\n{START.format('lab07.ex5')}\nfive\n{END}"))
    found = explanations_in_notebook(data, "lab07_transformations.ipynb")
    assert {k: (e.text, e.source) for k, e in found.items()} == {
        "lab07.ex1": ("Tagged **cell**.", "lab07_transformations.ipynb, cell 1"),
        "lab07.ex2": ("Before the marker counts too.\n\nMarked.", "lab07_transformations.ipynb, cell 2"),
        "lab07.ex4": ("four", "lab07_transformations.ipynb, cell 5"),
        "lab07.ex5": ("five", "lab07_transformations.ipynb, cell 5")}


@pytest.mark.parametrize("data", [b"not json", b"[" * 200_000, b'{"cells": 3}', b'{"cells": [3, {"cell_type": '
                                  b'"markdown", "source": [1, 2]}, {"cell_type": "markdown", "metadata": '
                                  b'{"tags": "report:lab07.ex1"}, "source": "x"}]}', bytes(range(256)) * 10])
def test_a_broken_notebook_is_a_problem_never_an_error(data):
    report = read_report({"lab07.ipynb": data, "report.pdf": b"%PDF-1.4", ".hidden.md": b"## lab07.ex1\nno"})
    assert report.explanations == {} and report.attachments == ("report.pdf",)
    assert len(report.problems) <= 2


@settings(max_examples=60)
@given(st.lists(st.one_of(st.sampled_from([START.format("lab07.ex1"), START.format("lab07.ex2"), END,
                                           "## lab07.ex1: x", "## lab07.ex2", "```", PLACEHOLDER,
                                           "Automatic verdict: 1", "![a](b.png)", "\n", "<!--", "-->"]),
                          st.text(max_size=20)), max_size=40))
def test_any_markdown_is_read_without_error_within_bounds(pieces):
    report = read_report({"r.md": "\n".join(pieces).encode("utf-8", errors="surrogatepass")})
    for explanation in report.explanations.values():
        assert explanation.text and explanation.text == explanation.text.strip()
        assert PLACEHOLDER not in explanation.text and "<!-- end explanation -->" not in explanation.text
        assert not any(ord(c) < 9 or 13 < ord(c) < 32 or c == "\x1b" for c in explanation.text)
        assert len(explanation.text) <= MAX_EXPLANATION_CHARS


def test_scaffold_is_pure_and_keeps_an_explanation_of_a_section_it_no_longer_has():
    sections = [Section("lab07.ex1", "T", ["![lab07.ex1](figures/lab07.ex1.png)"], "Automatic verdict: 1 / 1 (passed)")]
    earlier = f"## lab07.ex2: gone\n{START.format('lab07.ex2')}\nkept\n{END}\n"
    text, carried = scaffold("lab07 report: T", sections, earlier)
    assert carried == 1
    assert {k: e.text for k, e in explanations_in_markdown(text, "r").items()} == {"lab07.ex2": "kept"}
    assert scaffold("lab07 report: T", sections, text) == (text, 1)
