"""The class upload is untrusted input (issue 24): Hypothesis builds hostile classes.

Each example is a class in one of the four layouts (one entry per student,
Canvas, Moodle, Gradescope), as a folder or as a zip, holding well-formed
students -- with hostile names: control characters, undecodable bytes, formulas,
case twins, names too long for a file system -- beside hostile items: links to a
folder of secrets outside the upload, pipes, stray files, a file and a folder of
one name, members outside the archive, names that impersonate another student's
LMS prefix, metadata keys that are paths. Reading it must:

- complete, whatever the class holds;
- give every well-formed student exactly one entry, with exactly their own files;
- never read a byte from outside the upload;
- account for every hostile item (listed as ignored, or an entry's error);
- give ids unique whatever the case, and texts safe to store and to show.

A few classes also go through the whole batch: each well-formed student's
total equals the same work graded alone, every CSV cell is safe to open in a
spreadsheet, and nothing outside RESULTS changes.
"""

from __future__ import annotations

import csv
import hashlib
import io
import os
import re
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from autograder.instructor.batch.exports import spreadsheet_safe
from autograder.instructor.batch.ingest import read_upload
from autograder.loading.text import shown

MODULE = "lab07_transformations"
SECRET = "SECRET-OUTSIDE-THE-UPLOAD"
LAYOUTS = ("entry", "canvas", "moodle", "gradescope")
ID = re.compile(r"^[a-z0-9](?:[a-z0-9-]{0,78}[a-z0-9])?$")
CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e]")

# Names students could give themselves (or their folders): formulas, controls, bidi
# overrides, accents, case twins of one another, LMS-looking fragments.
NAME_PARTS = ["alice", "Alice", "alice-2", "ALICE", "Élodie", "=HYPERLINK(\"x\")", "+1", "-2", "@SUM(A1)",
              "\t", "\x1b[2J", "\u202e", "ƒ", "李", " ", "bob", "_12_", "__", "o'neil", "x" * 120]
names = st.lists(st.sampled_from(NAME_PARTS), min_size=1, max_size=4).map("".join)


@dataclass
class Student:
    name: str
    mark: str
    entry_name: str = ""          # the item (folder, file) holding the student at the top
    lms_id: str = ""


@dataclass
class Upload:
    layout: str
    zipped: bool
    students: list[Student]
    hostile: list[str] = field(default_factory=list)    # top-level names that must be accounted for
    items: dict[str, bytes] = field(default_factory=dict)   # member path -> bytes (zip) / file path (folder)
    links: dict[str, str] = field(default_factory=dict)     # folder only: path -> link target
    fifos: list[str] = field(default_factory=list)          # folder only


def module_source(mark: str) -> bytes:
    return f"MARK = {mark!r}\n".encode()


def safe_fs_name(name: str, zipped: bool) -> str:
    """A name the container can hold: no '/' or NUL, not hidden; short enough for a file system."""
    name = name.replace("/", "_").replace("\x00", "_").replace("\\", "_").lstrip(".") or "x"
    if not zipped:
        while len(name.encode()) > 200:
            name = name[:-1]
    return name


@st.composite
def uploads(draw) -> Upload:
    layout = draw(st.sampled_from(LAYOUTS))
    zipped = draw(st.booleans())
    count = draw(st.integers(1, 4))
    students = [Student(draw(names), f"student-{i}") for i in range(count)]
    upload = Upload(layout, zipped, students)
    hostile = draw(st.lists(st.sampled_from(HOSTILE[layout]), max_size=4, unique=True))
    builders[layout](upload, draw)
    for kind in hostile:
        if kind in FOLDER_ONLY and zipped or kind in ZIP_ONLY and not zipped:
            continue
        add_hostile(upload, kind)
    return upload


def build_entry(upload: Upload, draw) -> None:
    seen = set()
    for s in upload.students:
        base = safe_fs_name(s.name, upload.zipped)
        if base in seen or base in ("__MACOSX", "__pycache__"):
            base = f"{base}-{s.mark}"
        seen.add(base)
        s.entry_name = base
        if draw(st.booleans()):
            upload.items[f"{base}/{MODULE}.py"] = module_source(s.mark)
        else:   # a lone file, named after no module: the lone-file rule applies
            s.entry_name = f"{base}.py"
            upload.items[s.entry_name] = module_source(s.mark)


def build_canvas(upload: Upload, draw) -> None:
    for i, s in enumerate(upload.students):
        login = re.sub(r"[^a-z0-9]", "", s.name.lower()) or "student"
        s.lms_id = str(1000 + i)
        s.entry_name = f"{login}_{s.lms_id}_{5000 + i}_{MODULE}.py"
        upload.items[s.entry_name] = module_source(s.mark)


def build_moodle(upload: Upload, draw) -> None:
    for i, s in enumerate(upload.students):
        full = safe_fs_name(s.name, upload.zipped).replace("assignsubmission", "x")
        s.lms_id = str(300 + i)
        if draw(st.booleans()):
            s.entry_name = f"{full}_{s.lms_id}_assignsubmission_file_"
            upload.items[f"{s.entry_name}/{MODULE}.py"] = module_source(s.mark)
        else:
            s.entry_name = f"{full}_{s.lms_id}_assignsubmission_file_{MODULE}.py"
            upload.items[s.entry_name] = module_source(s.mark)


def build_gradescope(upload: Upload, draw) -> None:
    metadata = {}
    for i, s in enumerate(upload.students):
        s.entry_name = f"submission_{700 + i}"
        metadata[s.entry_name] = {":submitters": [{":name": s.name, ":sid": f"S{i}",
                                                   ":email": f"{s.mark}@uni.edu"}]}
        upload.items[f"{s.entry_name}/{MODULE}.py"] = module_source(s.mark)
    upload.items["submission_metadata.yml"] = yaml.safe_dump(metadata, allow_unicode=True).encode()


builders = {"entry": build_entry, "canvas": build_canvas, "moodle": build_moodle, "gradescope": build_gradescope}

# ------------------------------------------------------------------ hostile items
COMMON = ["stray-file", "link-to-secrets", "link-to-secret-file", "fifo", "file-and-folder", "outside-member",
          "absolute-member", "long-member"]
HOSTILE = {
    "entry": COMMON + ["undecodable-folder", "link-inside-student"],
    "canvas": COMMON + ["canvas-impersonation"],
    "moodle": COMMON + ["moodle-impersonation", "moodle-name-trick"],
    "gradescope": COMMON + ["gradescope-path-keys", "unlisted-folder"],
}
FOLDER_ONLY = {"link-to-secrets", "link-to-secret-file", "fifo", "undecodable-folder", "link-inside-student"}
ZIP_ONLY = {"file-and-folder", "outside-member", "absolute-member", "long-member"}


def add_hostile(upload: Upload, kind: str) -> None:
    victim = upload.students[0]
    evil = module_source(SECRET)
    if kind == "stray-file":
        upload.items["notes.pdf"] = b"%PDF-1.4 " + SECRET.encode()
        upload.hostile.append("notes.pdf")
    elif kind == "link-to-secrets":
        upload.links["solutions"] = "SECRETS"
        upload.hostile.append("solutions")
    elif kind == "link-to-secret-file":
        upload.links[f"zz_{MODULE}.py"] = f"SECRETS/{MODULE}.py"
        upload.hostile.append(f"zz_{MODULE}.py")
    elif kind == "fifo":
        upload.fifos.append("pipe")
        upload.hostile.append("pipe")
    elif kind == "link-inside-student" and victim.entry_name and not victim.entry_name.endswith(".py"):
        upload.links[f"{victim.entry_name}/helpers.py"] = f"SECRETS/{MODULE}.py"
    elif kind == "undecodable-folder":
        upload.items[f"bad\udcffname/{MODULE}.py"] = module_source("undecodable")
        upload.students.append(Student("bad\udcffname", "undecodable", "bad\udcffname"))
    elif kind == "file-and-folder":
        upload.items["twin"] = b"a file"
        upload.items[f"twin/{MODULE}.py"] = evil
        upload.hostile.append("twin")
    elif kind == "outside-member":
        upload.items[f"../outside/{MODULE}.py"] = evil
        upload.hostile.append(f"../outside/{MODULE}.py")
    elif kind == "absolute-member":
        upload.items[f"/abs/{MODULE}.py"] = evil
        upload.hostile.append(f"/abs/{MODULE}.py")
    elif kind == "long-member":
        name = "l" * 300
        upload.items[f"{name}/{MODULE}.py"] = module_source("long")
        if upload.layout == "entry":
            upload.students.append(Student(name, "long", name))
        else:
            upload.hostile.append(name)
    elif kind == "canvas-impersonation":
        name = f"mallory_999_9999_victim_{victim.lms_id}_1_{MODULE}.py"
        upload.items[name] = evil
        upload.students.append(Student("mallory", SECRET, name, "999"))   # Mallory's own, not the victim's
    elif kind == "moodle-impersonation":
        name = f"Mallory_999_assignsubmission_file_x_{victim.lms_id}_assignsubmission_file_{MODULE}.py"
        upload.items[name] = evil
        upload.hostile.append(name)
    elif kind == "moodle-name-trick":
        name = f"Victim_{victim.lms_id}_assignsubmission_file__999_assignsubmission_file_"
        upload.items[f"{name}/{MODULE}.py"] = evil
        upload.hostile.append(name)
    elif kind == "gradescope-path-keys":
        metadata = yaml.safe_load(upload.items["submission_metadata.yml"])
        for key in ("../SECRETS", "/etc", "submission_700/../..", "SECRETS"):
            metadata[key] = {":submitters": [{":name": "Evil"}]}
            upload.hostile.append(key)
        upload.items["submission_metadata.yml"] = yaml.safe_dump(metadata).encode()
    elif kind == "unlisted-folder":
        upload.items[f"submission_999/{MODULE}.py"] = evil
        upload.hostile.append("submission_999")


# ------------------------------------------------------------------ writing an upload
def write_upload(upload: Upload, where: Path) -> Path:
    """The upload as a folder or a zip in ``where`` (beside a folder of secrets it must never read)."""
    secrets = where / "SECRETS"
    secrets.mkdir(parents=True)
    (secrets / f"{MODULE}.py").write_bytes(module_source(SECRET))
    if upload.zipped:
        archive = where / "class.zip"
        with zipfile.ZipFile(archive, "w") as zf:
            for name, data in upload.items.items():
                info = zipfile.ZipInfo(name if name.startswith(("/", "..")) else f"export/{name}")
                zf.writestr(info, data)
        return archive
    root = where / "class"
    root.mkdir()
    for name, data in upload.items.items():
        path = os.fsencode(root) + b"/" + os.fsencode(name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as handle:
            handle.write(data)
    for name, target in upload.links.items():
        os.symlink(where / target, root / name)
    for name in upload.fifos:
        os.mkfifo(root / name)
    return root


def everything_read(entries) -> bytes:
    return b"".join(data for entry in entries for data in entry.files.values())


# ------------------------------------------------------------------ reading
@settings(max_examples=60, suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(upload=uploads())
def test_a_hostile_upload_is_read_entry_by_entry(upload, tmp_path_factory):
    assert_read_safely(upload, tmp_path_factory.mktemp("upload"))


@pytest.mark.parametrize("layout,kind,zipped", [
    (layout, kind, zipped) for layout in LAYOUTS for kind in HOSTILE[layout] for zipped in (False, True)
    if not (kind in FOLDER_ONLY and zipped or kind in ZIP_ONLY and not zipped)])
def test_every_hostile_item_in_every_layout(layout, kind, zipped, tmp_path):
    """Each hostile item alone, beside two students with case-twin names (the property
    above mixes them; this makes sure none is left untried)."""
    upload = Upload(layout, zipped, [Student("Alice", "student-0"), Student("alice", "student-1")])
    builders[layout](upload, lambda strategy: True)
    add_hostile(upload, kind)
    assert_read_safely(upload, tmp_path)


def assert_read_safely(upload: Upload, where: Path) -> None:
    path = write_upload(upload, where)
    result = read_upload(path, [MODULE], [MODULE])
    entries = result.entries

    # nothing from outside the upload, whatever pointed there
    assert SECRET.encode() not in everything_read(e for e in entries if e.student_id != "mallory-999"), \
        "a byte from outside the upload (or an impersonator's file) was read into someone's entry"

    # every well-formed student: one entry, exactly their own files
    for student in upload.students:
        mark = module_source(student.mark)
        holders = [e for e in entries if mark in e.files.values()]
        assert len(holders) == 1, (student, [(e.student_id, e.error) for e in entries])
        [entry] = holders
        assert not entry.error and entry.files == {f"{MODULE}.py": mark}, (student, entry)

    # every hostile item is accounted for: listed with a reason, or an entry that says why
    accounted = {item for item, reason in result.ignored if reason} | {e.origin for e in entries if e.error}
    for item in upload.hostile:
        assert shown(item) in accounted, (item, result.ignored)

    # ids unique whatever the case; every text fit to store and show
    ids = [e.student_id for e in entries]
    assert len({i.casefold() for i in ids}) == len(ids)
    for entry in entries:
        assert ID.match(entry.student_id), entry.student_id
        texts = [entry.display_name, entry.origin, entry.error, *entry.lms.values(),
                 *(v for m in entry.members for v in m.values())]
        for text in texts:
            text.encode("utf-8")   # SQLite and every file take it
            assert not CONTROL.search(text), repr(text)
        assert 0 < len(entry.display_name) <= 100 and len(entry.origin) <= 160
    for item, reason in result.ignored:
        (item + reason).encode("utf-8")
        assert not CONTROL.search(item + reason)


def test_a_yaml_alias_bomb_is_refused_and_names_are_plain_text(tmp_path):
    export = tmp_path / "export"
    (export / "submission_1").mkdir(parents=True)
    (export / "submission_1" / f"{MODULE}.py").write_bytes(module_source("one"))
    bomb = "".join(f"{a}: &{a} [{', '.join([f'*{p}' if p else 'lol'] * 9)}]\n"
                   for a, p in zip("abcdefghij", [""] + list("abcdefghi")))
    (export / "submission_metadata.yml").write_text(bomb + "submission_1:\n  :submitters:\n  - :name: *j\n")
    with pytest.raises(Exception, match="aliases|not readable"):
        read_upload(export, [MODULE], [MODULE])
    # a few aliases are fine, and a name that is a list is no name
    (export / "submission_metadata.yml").write_text(
        "submission_1:\n  :submitters:\n  - :name: &n [a, b]\n    :sid: &s S1\n  - :name: *n\n    :sid: *s\n")
    [entry] = read_upload(export, [MODULE], [MODULE]).entries
    assert entry.display_name == "submission_1" and entry.files


def test_a_class_zip_is_never_inflated_beyond_what_can_hold_code(tmp_path):
    """A huge picture costs nothing (never read); a source member that lies about its size is refused."""
    archive = tmp_path / "class.zip"
    with zipfile.ZipFile(archive, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        zf.writestr("ada/photo.png", b"\0" * (64 * 2**20))     # 64 MiB inflated, ~64 KiB stored
        zf.writestr(f"ada/{MODULE}.py", module_source("ada"))
        zf.writestr(f"bob/{MODULE}.py", b"#" * (3 * 2**20))    # over the 2 MiB cap of one .py
    upload = read_upload(archive, [MODULE], [MODULE])
    ada, bob = upload.entries
    assert ada.files == {f"{MODULE}.py": module_source("ada")}
    assert "larger than" in bob.error or "more than" in bob.error


# ------------------------------------------------------------------ the whole batch
@pytest.fixture(scope="module")
def lone_totals(tmp_path_factory):
    """The total each kind of work gets graded alone (lab07.ex1)."""
    from autograder.engine.runner import grade
    from test_batch import WRONG_WAY, reference, skeleton

    totals = {}
    for kind, source in (("right", reference()), ("wrong", reference() + WRONG_WAY), ("empty", skeleton())):
        folder = tmp_path_factory.mktemp(kind)
        (folder / f"{MODULE}.py").write_text(source)
        totals[kind] = (source, grade(folder, ["lab07.ex1"]).total)
    return totals


def fingerprint(folder: Path) -> dict[str, str]:
    out = {}
    for path in sorted(folder.rglob("*")):
        if path.is_symlink():
            out[str(path)] = "link:" + os.readlink(path)
        elif path.is_file():
            out[str(path)] = hashlib.sha256(path.read_bytes()).hexdigest()
    return out


@pytest.mark.slow
@settings(max_examples=3, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(upload=uploads(), kinds=st.lists(st.sampled_from(["right", "wrong", "empty"]), min_size=5, max_size=5))
def test_a_hostile_class_grades_each_student_as_alone(upload, kinds, lone_totals, tmp_path_factory):
    from autograder.instructor.batch.gradebook import Gradebook
    from autograder.instructor.batch.run import run_batch
    from autograder.instructor.course import CourseConfig

    for student, kind in zip(upload.students, kinds):   # real work in place of the markers
        for name, data in list(upload.items.items()):
            if data == module_source(student.mark):
                upload.items[name] = lone_totals[kind][0].encode()
        student.mark = kind
    where = tmp_path_factory.mktemp("batch")
    path = write_upload(upload, where)
    before = fingerprint(where)
    out = where / "RESULTS"
    summary = run_batch(path, out, course=CourseConfig(select=["lab07.ex1"], assignment="Lab 7"), workers=2)
    assert {k: v for k, v in fingerprint(where).items() if not k.startswith(str(out))} == before

    with Gradebook(out, readonly=True) as book:
        students = book.class_results()
    graded = {lone_totals[s.mark][0].encode(): s for s in upload.students}
    for row in students:
        if row["status"] == "graded":
            sources = {p.read_bytes() for p in (out / row["student_id"] / "sources").rglob("*.py")}
            [kind] = [s.mark for data, s in graded.items() if data in sources] or [None]
            if kind is not None:
                assert row["result"]["total"] == lone_totals[kind][1], (row["student_id"], kind)
    assert len([r for r in students if r["status"] == "graded"]) >= len(upload.students)
    for item in upload.hostile:
        assert any(line.startswith(shown(item)) for line in summary.ignored + summary.unreadable), item
    for table in out.glob("*.csv"):
        for row in csv.reader(table.open(newline="", encoding="utf-8")):
            assert all(spreadsheet_safe(cell) == cell for cell in row), (table, row)


def test_metadata_keys_that_are_no_folder_names_fail_alone(tmp_path):
    """A key of any YAML type (a 1000-digit number, a date, a list's worth of text) is one
    ignored item; the export's real submission is still read."""
    export = tmp_path / "export"
    (export / "submission_1").mkdir(parents=True)
    (export / "submission_1" / f"{MODULE}.py").write_bytes(module_source("one"))
    (export / "submission_metadata.yml").write_text(
        f"? {'9' * 1000}\n:\n  :submitters: []\n2026-01-01:\n  :submitters: []\ntrue:\n  :submitters: []\n"
        "submission_1:\n  :submitters:\n  - :name: Ada\n")
    upload = read_upload(export, [MODULE], [MODULE])
    [entry] = upload.entries
    assert entry.display_name == "Ada" and entry.files
    assert len(upload.ignored) == 3


def test_a_name_no_file_system_takes_is_refused_and_the_rest_of_the_entry_read(tmp_path):
    """Inside a class zip a name may be longer than any file system takes; the files are
    written to disk when graded, so such a file is refused with its reason, not the student."""
    archive = tmp_path / "class.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        zf.writestr(f"ada/{MODULE}.py", module_source("ada"))
        zf.writestr(f"ada/{'n' * 300}/helper.py", "X = 1\n")
        zf.writestr(f"bob/{'n' * 300}/{MODULE}.py", module_source("bob"))
    ada, bob = read_upload(archive, [MODULE], [MODULE]).entries
    assert ada.files == {f"{MODULE}.py": module_source("ada")} and not ada.error
    assert "longer than 255 bytes" in bob.error
