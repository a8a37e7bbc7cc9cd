"""Identities never move: a student graded once keeps their id in every later download.

Everything an instructor keys by a student's id -- overrides, review marks, comments,
their folder of results -- follows the id. So across downloads that add, remove and
rename students, in every layout: whoever was seen before keeps their id; an id once
given is never given to anybody else (a student gone since included); newcomers whose
names collide take the new suffixes.

A person is told by what the layout says of them: the LMS's user id (Canvas, Moodle),
else their folder's name, case and all. A folder renamed is a new person to the grader
(nothing says otherwise): they get a new id, and no id moves.
"""

from __future__ import annotations

import csv

import pytest
from hypothesis import given, strategies as st

from autograder.instructor.batch.ingest import Identities, read_upload
from autograder.instructor.batch.run import run_batch
from test_batch import COURSE, MODULE, reference, skeleton, write

MODULES = [MODULE]
SOURCE = "def translate(image, tx=100, ty=50):\n    return image\n"
# Names that collide once slugged: case, accents, separators.
NAMES = ["alice", "Alice", "ALICE", "alice-2", "Alíce", "bob", "Bob", "bob 2", "carol", "alice_2"]


def layout_writer(layout: str):
    """How one person (a number) with a display name is written into a download, per layout."""
    def folder(root, person, name, round_):
        write(root / name / f"{MODULE}.py", SOURCE + f"# {round_}\n")

    def canvas(root, person, name, round_):   # the user id is the person; the submission id changes
        plain = "".join(c for c in name.lower() if c.isalnum() and c.isascii())  # as Canvas writes names
        write(root / f"{plain}_{1000 + person}_{round_ * 100 + person}_{MODULE}.py", SOURCE)

    def moodle(root, person, name, round_):
        write(root / f"{name}_{500 + person}_assignsubmission_file_" / f"{MODULE}.py", SOURCE)

    return {"folder": folder, "canvas": canvas, "moodle": moodle}[layout]


def identity(layout: str, person: int, name: str):
    """What tells this person apart in ``layout`` (a renamed folder is a new person)."""
    return name if layout == "folder" else person


rounds = st.lists(  # each download: who is in it, under which of their names
    st.dictionaries(st.integers(0, 5), st.sampled_from(NAMES), min_size=1, max_size=6),
    min_size=2, max_size=4)


@pytest.mark.parametrize("layout", ["folder", "canvas", "moodle"])
@given(downloads=rounds)
def test_an_id_once_given_stays_with_its_student(tmp_path_factory, layout, downloads):
    write_person = layout_writer(layout)
    owner: dict[str, object] = {}     # id -> the identity it was given to
    given_to: dict[object, str] = {}  # identity -> its id
    stored: list[dict] = []           # the gradebook's students, present or gone
    for number, people in enumerate(downloads):
        root = tmp_path_factory.mktemp("download")
        if layout == "folder":  # one folder per name: two people under one name are one folder
            people = {person: name for name, person in {name: p for p, name in people.items()}.items()}
        for person, name in people.items():
            write_person(root, person, name, number)
        upload = read_upload(root, MODULES, MODULES, Identities.of(stored))
        ids = [entry.student_id for entry in upload.entries]
        assert len(ids) == len(set(ids)) == len(people)
        for entry in upload.entries:
            person = next(p for p, n in people.items()
                          if (layout != "folder" or entry.origin.strip("/") == n)
                          and (layout == "folder" or str(1000 + p) in entry.origin or str(500 + p) in entry.origin))
            who = identity(layout, person, people[person])
            if who in given_to:
                assert entry.student_id == given_to[who], "a student seen before lost their id"
            assert owner.setdefault(entry.student_id, who) == who, "an id moved to another student"
            given_to[who] = entry.student_id
        kept = {row["student_id"]: row for row in stored}
        kept.update({e.student_id: {"student_id": e.student_id, "origin": e.origin, "lms": e.lms}
                     for e in upload.entries})
        stored = list(kept.values())


@pytest.mark.slow
def test_an_override_stays_with_the_student_it_was_written_for(tmp_path):
    """The reported case: ``alice/`` graded (full marks), then a download that also holds
    ``Alice/`` (the skeleton). ``alice`` keeps her id and her grading (not regraded); the
    newcomer is ``alice-2``; the +5 written for ``alice`` stays hers."""
    download, out = tmp_path / "download", tmp_path / "out"
    write(download / "alice" / f"{MODULE}.py", reference())
    first = run_batch(download, out, course=COURSE, workers=1)
    assert first.graded == 1
    write(download / "Alice" / f"{MODULE}.py", skeleton())
    (tmp_path / "overrides.csv").write_text("student,exercise,points,penalty,comment\nalice,total,5,,bonus\n")
    second = run_batch(download, out, course=COURSE, workers=1, overrides=tmp_path / "overrides.csv")
    assert second.graded == 1 and second.reused == 1   # only the newcomer is graded
    grades = {row["Student ID"]: row for row in csv.DictReader((out / "grades.csv").open())}
    assert set(grades) == {"alice", "alice-2"}
    assert float(grades["alice"]["Total"]) == 12 + 5
    assert float(grades["alice-2"]["Total"]) == 0
