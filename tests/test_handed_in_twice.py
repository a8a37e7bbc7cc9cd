"""A lab handed in twice is graded from the file that implements it, and every output says so (issue 36).

Before, a notebook beside the skeleton (``assignments/lab07_transformations.ipynb`` next to
``lab07_transformations.py``, as the notebooks page told students) scored 0 in silence: the
``.py`` won. Now the file with the most functions implemented is graded (fewest stubs next,
then the newer), and the terminal, the feedback page, ``results.json``, ``validate``, the
class's ``grades.csv`` and its overview name the file graded, the one not graded and why.

Classes of cases: a ``.py`` beside a notebook (either one the skeleton), two notebooks (two
folders, or a copy), a module in two folders; the same work twice with the notebook newer,
older, or of the same date (a tie); a zip's member dates. The choice is tested on loading
alone (no student code runs); each output once on a real grading.
"""

from __future__ import annotations

import csv
import io
import json
import os
import time
import zipfile
from pathlib import Path

import pytest
from hypothesis import given, strategies as st
from rich.console import Console

from autograder.engine.results import GradingResult
from autograder.engine.runner import grade
from autograder.cli import main
from autograder.loading.handed_in import Candidate, NotGraded, Progress, choose, progress
from autograder.loading.submission import load_submission
from autograder.reports import html, terminal
from conftest import REFERENCE, SKELETON

MODULE = "lab07_transformations"
PY, NB = f"{MODULE}.py", f"{MODULE}.ipynb"
SELECT = ["lab07.ex1"]
REF = (REFERENCE / PY).read_text()
SKEL = (SKELETON / PY).read_text()
PART = REF[:REF.index("def scaling_matrix")]   # ex1 and ex2 written, the rest not yet
HOUR = 3600.0


def notebook(source: str) -> str:
    """A notebook as Jupyter writes it: a Markdown cell, then the code under a magic."""
    cells = [{"cell_type": "markdown", "metadata": {}, "source": ["# Lab 7\n"]},
             {"cell_type": "code", "metadata": {}, "execution_count": 1, "outputs": [],
              "source": ["%matplotlib inline\n", source]}]
    return json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5})


def hand_in(folder: Path, files: dict[str, str], older: dict[str, float] | None = None) -> Path:
    """Write ``files`` (relative path -> text) into ``folder``, all dated one moment, each of
    ``older`` that many seconds before it."""
    now = time.time() - 10 * HOUR
    for relative, text in files.items():
        path = folder / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        stamp = now - (older or {}).get(relative, 0.0)
        os.utime(path, (stamp, stamp))
    return folder


# name -> (files, seconds older per file, the file graded, the file not graded, why in words)
CASES = {
    "notebook beside the skeleton": (
        {PY: SKEL, NB: notebook(REF)}, {NB: HOUR}, NB, PY, "implements none of its"),
    # (the reference's helper counted apart: "none of its 11 functions" beside "12 functions" read as a miscount,
    # audit of 2026-12-07)
    "notebook with a helper beside the skeleton": (
        {PY: SKEL, NB: notebook(REF)}, {NB: HOUR}, NB, PY,
        f"{PY} implements none of its 11 functions yet (each only raises NotImplementedError) and {NB} implements "
        "11 of them (and 1 function of its own)"),
    "the .py written, a skeleton notebook beside it": (
        {PY: REF, NB: notebook(SKEL)}, {PY: HOUR}, PY, NB, "implements none of its"),
    "two notebooks in two folders": (
        {f"old/{NB}": notebook(PART), f"new/{NB}": notebook(REF)}, {f"new/{NB}": HOUR}, f"new/{NB}", f"old/{NB}",
        f"old/{NB} implements 5 functions and new/{NB} implements 12"),
    "a notebook and its copy": (
        {NB: notebook(REF), f"{MODULE} (1).ipynb": notebook(SKEL)}, {}, NB, f"{MODULE} (1).ipynb",
        "implements none of its"),
    "a module in two folders": (
        {f"lab7/{PY}": REF, PY: PART}, {}, f"lab7/{PY}", PY, f"{PY} implements 5 functions"),
    "the same work, the notebook newer": (
        {PY: REF, NB: notebook(REF)}, {PY: HOUR}, NB, PY, f"both implement 12 functions and {NB} is newer"),
    "the same work, the notebook older": (
        {PY: REF, NB: notebook(REF)}, {NB: HOUR}, PY, NB, f"both implement 12 functions and {PY} is newer"),
    # a full tie: the file nearest the top of the submission, then a .py before a notebook
    "the same work of the same date, in two folders": (
        {f"a/{PY}": REF, f"b/{PY}": REF, NB: notebook(REF)}, {}, NB, f"a/{PY}", "have the same date"),
    "the same work of the same date, side by side": (
        {PY: REF, NB: notebook(REF)}, {}, PY, NB, "have the same date: the grader takes the file nearest the top"),
}


@pytest.mark.parametrize("case", list(CASES))
def test_the_file_that_implements_the_lab_is_graded_and_the_other_named(tmp_path, case):
    files, older, graded, other, why = CASES[case]
    with load_submission(hand_in(tmp_path / "handin", files, older), [MODULE]) as submission:
        not_graded = submission.not_graded[MODULE]
        materialised = (submission.path / PY).read_text()
    assert other in [f.file for f in not_graded]
    assert all(f.graded == graded and f.module == MODULE for f in not_graded)
    assert len(not_graded) == len(files) - 1, "every other file is named"
    [mine] = [f for f in not_graded if f.file == other]
    assert why in mine.why, mine.why
    # what is graded is the chosen file's code: a skeleton only when the skeleton won
    source = files[graded]
    assert ("NotImplementedError(" in materialised) == ("NotImplementedError(" in source)
    assert ("def scaling_matrix" in materialised) == ("def scaling_matrix" in source)


def test_a_zip_keeps_its_members_dates(tmp_path):
    """In a zip, "the newer" is the member's own date, not the moment it was unpacked."""
    archive = tmp_path / "handin.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        zf.writestr(zipfile.ZipInfo(PY, date_time=(2026, 11, 20, 9, 0, 0)), REF)
        zf.writestr(zipfile.ZipInfo(NB, date_time=(2026, 11, 21, 9, 0, 0)), notebook(REF))
    with load_submission(archive, [MODULE]) as submission:
        [not_graded] = submission.not_graded[MODULE]
    assert (not_graded.graded, not_graded.file) == (NB, PY)
    assert "2026-11-21" in not_graded.why and "2026-11-20" in not_graded.why


def test_one_file_per_lab_is_read_as_before(tmp_path):
    with load_submission(hand_in(tmp_path / "handin", {NB: notebook(REF)}), [MODULE]) as submission:
        assert submission.not_graded == {} and MODULE in submission.notebooks


def test_progress_counts_functions_written_and_stubs():
    assert progress(REF).implemented == 12 and progress(REF).stubs == 0
    assert progress(SKEL).implemented == 0 and progress(SKEL).stubs == 11
    broken = progress("def translate(image):\n    return image[\n")   # work in progress: a SyntaxError
    assert broken.implemented == 1 and broken.stubs == 0


# ------------------------------------------------------------------ every output, on a real grading
def terminal_text(result) -> str:
    buffer = io.StringIO()
    terminal.render(result, Console(file=buffer, width=400))
    return buffer.getvalue()


@pytest.mark.parametrize("case", ["notebook beside the skeleton", "two notebooks in two folders",
                                  "a module in two folders"])
def test_every_output_names_the_file_graded_and_the_file_not(tmp_path, case):
    files, older, graded, other, why = CASES[case]
    result = grade(hand_in(tmp_path / "handin", files, older), SELECT).for_students()
    [exercise] = result.exercises
    assert exercise.score == exercise.max_score > 0, "the file that implements the lab is graded"
    sentence = f"was handed in more than once: graded {graded}, not {other}, because"
    # terminal
    assert f"note: {MODULE} {sentence}" in terminal_text(result)
    # feedback page
    assert sentence in html.render(result)
    # results.json: a structured field and the note, kept through a write and read
    data = json.loads(json.dumps(result.to_dict()))
    assert [f["file"] for f in data["files_not_graded"]] == [other]
    assert data["files_not_graded"][0]["graded"] == graded and why in data["files_not_graded"][0]["why"]
    assert any(sentence in note for note in data["notes"])
    assert GradingResult.from_dict(data).files_not_graded == data["files_not_graded"]
    assert NotGraded.from_dict(data["files_not_graded"][0]).sentence() in data["notes"]


def test_validate_names_the_file_not_graded_and_the_notebook_handed_in(tmp_path):
    from autograder.student.validate import validate

    files, older, *_ = CASES["notebook beside the skeleton"]
    report = validate(hand_in(tmp_path / "handin", files, older), SELECT)
    text = str(report)
    assert f"· {PY}: not graded: {MODULE} was handed in more than once: graded {NB}, not {PY}" in text
    assert f"✓ {NB}: imports cleanly" in text and f"{PY}: imports" not in text


@pytest.mark.slow
def test_the_class_files_name_the_file_not_graded(tmp_path, capsys):
    submissions = tmp_path / "submissions"
    files, older, *_ = CASES["notebook beside the skeleton"]
    hand_in(submissions / "twice", files, older)
    hand_in(submissions / "once", {PY: REF})
    out, course = tmp_path / "results", tmp_path / "course.json"
    course.write_text(json.dumps({"select": SELECT, "assignment": "Lab 7"}))
    assert main(["batch", str(submissions), "--out", str(out), "--course", str(course), "--workers", "1",
                 "--pictures", "none"]) == 0
    printed = " ".join(capsys.readouterr().out.split())   # the batch's terminal
    assert f"file not graded: twice: graded {NB}, not {PY}, because {PY} implements none" in printed
    rows = list(csv.DictReader((out / "grades.csv").open(newline="")))
    header = next(csv.reader((out / "grades.csv").open(newline="")))
    assert header[:4] == ["Student ID", "Name", "Status", "Files not graded"]
    by_id = {row["Student ID"]: row for row in rows}
    assert by_id["twice"]["Files not graded"].startswith(f"graded {NB}, not {PY}, because {PY} implements none")
    assert by_id["once"]["Files not graded"] == ""
    assert by_id["twice"]["Total"] == by_id["once"]["Total"] != "0"   # the notebook was graded
    overview = (out / "index.html").read_text()
    assert "Files handed in but not graded" in overview and f"graded {NB}, not {PY}" in overview
    assert "1 handed a lab in twice" in overview
    page = (out / "twice" / "feedback.html").read_text()
    assert f"graded {NB}, not {PY}, because" in page
    assert json.loads((out / "twice" / "results.json").read_text())["files_not_graded"][0]["file"] == PY


# ------------------------------------------------------------------ the rule, for any files
candidates = st.lists(st.tuples(st.sampled_from(["a/", "b/", ""]), st.sampled_from([".py", ".ipynb"]),
                                st.integers(0, 3), st.integers(0, 3), st.sampled_from([0.0, 1.0, 2.0])),
                      min_size=2, max_size=5, unique_by=lambda c: (c[0], c[1]))


@given(candidates)
def test_the_file_graded_implements_the_most_and_every_other_is_named_once(drawn):
    files = [Candidate(Path(f"{folder}{MODULE}{suffix}"), f"{folder}{MODULE}{suffix}", Progress(done, stubs), when)
             for folder, suffix, done, stubs, when in drawn]
    best, others = choose(MODULE, files)
    assert sorted(f.file for f in others) == sorted(c.shown for c in files if c is not best)
    assert all(f.graded == best.shown and f.why for f in others)
    for other in files:   # nothing beats it: more implemented, or as much with fewer stubs, or as much and newer
        mine, theirs = (other.progress.implemented, -other.progress.stubs, other.modified), \
            (best.progress.implemented, -best.progress.stubs, best.modified)
        assert mine <= theirs


@pytest.mark.parametrize("progress_, words", [
    (Progress(0, 1), "implements none of its 1 function yet (it only raises NotImplementedError)"),
    (Progress(0, 11), "implements none of its 11 functions yet (each only raises NotImplementedError)"),
    (Progress(2, 1), "implements 2 functions (1 more only raises NotImplementedError)"),
    (Progress(1, 0), "implements 1 function"), (Progress(0, 0), "defines no function"),
    (Progress(0, 0, "is not UTF-8 text"), "is not UTF-8 text")])
def test_progress_in_words(progress_, words):
    assert progress_.words() == words
