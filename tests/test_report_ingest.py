"""Issue 30: the batch reads each student's lab report beside the code, deny by default.

Reports (``.md``, bounded by the report's cap) and PDFs (kept as files, never parsed,
bounded) are read in every layout (folder, zip, Canvas, Moodle, Gradescope), never
graded and never part of the submission's key; explanations come from them and from
the notebooks' tagged cells; whatever is refused is a sentence of the report's
problems, never the entry's error; and the gradebook keeps them with the student.
"""

from __future__ import annotations

import io
import json
import os
import zipfile

import pytest

from autograder.instructor.batch.gradebook import Gradebook
from autograder.instructor.batch.ingest import read_upload
from autograder.instructor.batch.tree import MAX_ATTACHMENT_BYTES, MAX_REPORT_FILES
from autograder.loading.report import MAX_REPORT_BYTES
from test_batch import write, zipped

MODULE = "lab07_transformations"
CODE = b"def translate(image, tx, ty):\n    return image\n"
PDF = b"%PDF-1.4\n% a report\n"


def section(exercise: str, text: str) -> str:
    return (f"## {exercise}: Title\n\n![{exercise}](figures/{exercise}.png)\n\nAutomatic verdict: 1 / 1 (passed)\n\n"
            f"<!-- explanation {exercise} -->\n{text}\n<!-- end explanation -->\n")


def notebook(text: str) -> bytes:
    cells = [{"cell_type": "code", "metadata": {}, "source": CODE.decode(), "outputs": [], "execution_count": None},
             {"cell_type": "markdown", "metadata": {"tags": ["report:lab07.ex1"]}, "source": text}]
    return json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}).encode()




def read(root):
    return {e.student_id: e for e in read_upload(root, [MODULE], [MODULE]).entries}


def test_reports_are_read_beside_the_code_in_a_folder_a_zip_and_a_notebook(tmp_path):
    root = tmp_path / "class"
    write(root / "ada" / f"{MODULE}.py", CODE)
    write(root / "ada" / "lab07_report.md", section("lab07.ex1", "The **warp** leaves black corners.").encode())
    write(root / "ada" / "figures" / "lab07.ex1.png", b"\x89PNG not read")
    write(root / "ada" / "extra.pdf", PDF)
    write(root / "bo.zip", zipped({f"bo/{MODULE}.py": CODE, "bo/report/lab07_report.md":
                                   section("lab07.ex2", "Bilinear is smoother.").encode(), "bo/scan.pdf": PDF}))
    write(root / "cy" / f"{MODULE}.ipynb", notebook("Because the inverse map samples outside."))
    entries = read(root)
    ada, bo, cy = entries["ada"], entries["bo"], entries["cy"]
    assert not (ada.error or bo.error or cy.error)
    assert set(ada.files) == {f"{MODULE}.py"}, "the report is never graded"
    assert set(ada.report_files) == {"lab07_report.md", "extra.pdf"}, "pictures are not taken"
    assert ada.report.explanations["lab07.ex1"].text.strip() == "The **warp** leaves black corners."
    assert ada.report.attachments == ("extra.pdf",) and ada.report.problems == ()
    assert set(bo.report_files) == {"bo/bo/report/lab07_report.md", "bo/bo/scan.pdf"}
    assert bo.report.explanations["lab07.ex2"].text.strip() == "Bilinear is smoother."
    assert "Because the inverse map" in cy.report.explanations["lab07.ex1"].text
    assert cy.report_files == {} and "notebook" not in cy.report.problems


def test_the_copy_report_keeps_of_the_report_it_replaced_is_never_read(tmp_path):
    """``--report`` keeps the report it replaced as labNN_report.previous.md beside it: handed in
    with the folder, it would repeat every explanation (older texts among them)."""
    from autograder.loading.report import read_report

    current, older = section("lab07.ex1", "Final text.").encode(), section("lab07.ex1", "An older draft.").encode()
    root = tmp_path / "class"
    write(root / "ada" / f"{MODULE}.py", CODE)
    write(root / "ada" / "report" / "lab07_report.md", current)
    write(root / "ada" / "report" / "lab07_report.previous.md", older)
    write(root / "bo.zip", zipped({f"{MODULE}.py": CODE, "lab07_report.md": current,
                                   "lab07_report.previous.md": older}))
    for entry in read(root).values():
        assert [e.text for e in entry.report.explanations.values()] == ["Final text."], entry.student_id
        assert entry.report.problems == () and not any("previous" in f for f in entry.report_files)
    report = read_report({"lab07_report.md": current, "x/LAB07_REPORT.PREVIOUS.MD": older})
    assert report.explanations["lab07.ex1"].text == "Final text." and report.problems == ()


def test_thousands_of_report_files_are_a_few_sentences_not_thousands(tmp_path):
    from autograder.loading.report import MAX_PROBLEMS

    write(tmp_path / "class" / "ada" / f"{MODULE}.py", CODE)
    for number in range(MAX_REPORT_FILES + 300):
        write(tmp_path / "class" / "ada" / f"notes{number:04d}.md", b"x")
        write(tmp_path / "class" / "ada" / f"scan{number:04d}.pdf", b"not a pdf")
    ada = read(tmp_path / "class")["ada"]
    assert not ada.error and len(ada.report_files) == MAX_REPORT_FILES
    assert len(ada.report.problems) <= 2 * MAX_PROBLEMS + 2
    assert ada.report.problems[MAX_PROBLEMS].startswith("and ") and "more files were not read" in ada.report.problems[MAX_PROBLEMS]


def test_a_report_changes_no_submission_key(tmp_path):
    write(tmp_path / "a" / "ada" / f"{MODULE}.py", CODE)
    write(tmp_path / "b" / "ada" / f"{MODULE}.py", CODE)
    write(tmp_path / "b" / "ada" / "lab07_report.md", section("lab07.ex1", "text").encode())
    assert read(tmp_path / "a")["ada"].content_hash == read(tmp_path / "b")["ada"].content_hash


def test_lms_downloads_carry_reports_too(tmp_path):
    canvas = tmp_path / "canvas"
    write(canvas / f"adalovelace_1234_55_{MODULE}.py", CODE)
    write(canvas / "adalovelace_1234_55_lab07_report.md", section("lab07.ex1", "old").encode())
    write(canvas / "adalovelace_1234_56_lab07_report-1.md", section("lab07.ex1", "resubmitted").encode())
    [ada] = read(canvas).values()
    assert set(ada.report_files) == {"lab07_report.md"}
    assert ada.report.explanations["lab07.ex1"].text.strip() == "resubmitted", "Canvas's renaming undone"
    moodle = tmp_path / "moodle"
    write(moodle / "Bo Li_77_assignsubmission_file_" / f"{MODULE}.py", CODE)
    write(moodle / "Bo Li_77_assignsubmission_file_" / "report.pdf", PDF)
    [bo] = read(moodle).values()
    assert bo.report.attachments == ("report.pdf",)


def test_hostile_report_files_are_refused_with_their_reason_and_the_code_is_still_graded(tmp_path):
    root = tmp_path / "class"
    student = root / "eve"
    write(student / f"{MODULE}.py", CODE)
    write(student / "huge.md", b"x" * (MAX_REPORT_BYTES + 1))
    write(student / "huge.pdf", b"%PDF-" + b"0" * MAX_ATTACHMENT_BYTES)
    write(student / "not-a.pdf", b"MZ\x90\x00 an executable")
    write(student / "bad\x1bname.md", b"# escape")
    (student / "linked.md").symlink_to("/etc/passwd")
    os.mkfifo(student / "pipe.md")
    for i in range(MAX_REPORT_FILES + 3):
        write(student / "many" / f"n{i:02d}.md", b"x")
    eve = read(root)["eve"]
    assert not eve.error and set(eve.files) == {f"{MODULE}.py"}
    problems = "\n".join(eve.report.problems)
    assert "huge.md was not read: it is larger than 1 MiB" in problems
    assert "huge.pdf was not read: it is larger than 20 MiB" in problems
    assert "not-a.pdf was not read: it is not a PDF" in problems
    assert "control characters" in problems
    assert f"more than {MAX_REPORT_FILES} report files" in problems
    assert "linked.md" not in eve.report_files and "pipe.md" not in eve.report_files
    assert len(eve.report_files) == MAX_REPORT_FILES
    assert all(not name.startswith("huge") and "\x1b" not in name for name in eve.report_files)


def test_a_zip_bomb_of_a_report_is_refused_before_it_is_inflated(tmp_path):
    bomb = io.BytesIO()
    with zipfile.ZipFile(bomb, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("ada/" + f"{MODULE}.py", CODE)
        archive.writestr("ada/report.md", b"\0" * (64 * MAX_REPORT_BYTES))
        archive.writestr("../outside.md", b"escape")
    write(tmp_path / "class" / "ada.zip", bomb.getvalue())
    ada = read(tmp_path / "class")["ada"]
    assert not ada.error and ada.report_files == {}
    assert any("report.md was not read" in p and "MiB" in p for p in ada.report.problems)


def test_the_gradebook_keeps_the_report_with_the_student(tmp_path):
    root = tmp_path / "class"
    write(root / "ada" / f"{MODULE}.py", CODE)
    write(root / "ada" / "lab07_report.md", section("lab07.ex1", "Corners are black.").encode())
    write(root / "ada" / "scan.pdf", PDF)
    write(root / "ada" / "not.pdf", b"nope")
    entries = list(read(root).values())
    with Gradebook(tmp_path / "out") as book:
        book.sync_students(entries, {"ada": "k"})
        report = book.report("ada")
        assert report["explanations"]["lab07.ex1"]["text"].strip() == "Corners are black."
        assert report["explanations"]["lab07.ex1"]["source"] == "lab07_report.md"
        assert report["files"] == {"lab07_report.md": len(section("lab07.ex1", "Corners are black.")),
                                   "scan.pdf": len(PDF)}
        assert any("not.pdf" in p for p in report["problems"])
        assert book.report_file("ada", "scan.pdf") == PDF and book.report_file("ada", "../etc/passwd") is None
        # A later download without the report: the report as read now (nothing left over).
        (root / "ada" / "lab07_report.md").unlink()
        book.sync_students(list(read(root).values()), {"ada": "k"})
        assert book.report("ada")["explanations"] == {}


# Issue 34: a report file that is not a regular file was skipped silently; it is named, with what it is.
FOLDER_KINDS = {"link": "it is a symbolic link", "fifo": "it is not a regular file (a named pipe)",
                "socket": "it is not a regular file (a socket)",
                "chardev": "it is not a regular file (a character device)",
                "blockdev": "it is not a regular file (a block device)"}


def make_special(path, kind: str) -> None:
    import socket
    import stat
    import tempfile

    if kind in ("chardev", "blockdev") and os.geteuid() != 0:
        pytest.skip("making a device needs root")
    if kind == "link":
        path.symlink_to("/etc/passwd")
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "socket":
        short = tempfile.mkdtemp()   # a socket's path must be short: bound there, then moved
        with socket.socket(socket.AF_UNIX) as sock:
            sock.bind(f"{short}/s")
        os.rename(f"{short}/s", path)
        os.rmdir(short)
    else:
        os.mknod(path, (stat.S_IFCHR if kind == "chardev" else stat.S_IFBLK) | 0o600, os.makedev(1, 3))


@pytest.mark.parametrize("kind", FOLDER_KINDS)
@pytest.mark.parametrize("name", ["lab07_report.md", "notes/scan.pdf"])
def test_a_report_file_that_is_a_link_pipe_socket_or_device_is_named_with_what_it_is(tmp_path, kind, name):
    student = tmp_path / "class" / "eve"
    write(student / f"{MODULE}.py", CODE)
    (student / name).parent.mkdir(parents=True, exist_ok=True)
    make_special(student / name, kind)
    eve = read(tmp_path / "class")["eve"]
    assert not eve.error and set(eve.files) == {f"{MODULE}.py"} and eve.report_files == {}
    assert eve.report.problems == (f"{name} was not read: {FOLDER_KINDS[kind]}",)


@pytest.mark.parametrize("mode, reason", [
    (0o120777, "it is a symbolic link"), (0o010644, "it is not a regular file (a named pipe)"),
    (0o140644, "it is not a regular file (a socket)"), (0o020644, "it is not a regular file (a character device)"),
    (0o060644, "it is not a regular file (a block device)")])
def test_a_zipped_report_member_that_is_no_regular_file_is_named_with_what_it_is(tmp_path, mode, reason):
    archive = io.BytesIO()
    with zipfile.ZipFile(archive, "w") as zf:
        zf.writestr(f"{MODULE}.py", CODE)
        member = zipfile.ZipInfo("lab07_report.md")
        member.external_attr = mode << 16
        zf.writestr(member, b"/etc/passwd")
    write(tmp_path / "class" / "eve.zip", archive.getvalue())
    eve = read(tmp_path / "class")["eve"]
    assert not eve.error and eve.report_files == {}
    assert eve.report.problems == (f"eve/lab07_report.md was not read: {reason}",)


@pytest.mark.parametrize("kind", ["link", "fifo"])
def test_an_lms_downloads_report_link_or_pipe_is_named_on_its_students_report(tmp_path, kind):
    """A Canvas or Moodle download is flat: a link or a pipe at its top named like a student's report
    file is listed as ignored (never followed) and named in that student's report's problems."""
    canvas = tmp_path / "canvas"
    write(canvas / f"adalovelace_1234_55_{MODULE}.py", CODE)
    make_special(canvas / "adalovelace_1234_56_lab07_report-1.md", kind)
    moodle = tmp_path / "moodle"
    write(moodle / f"Bo Li_77_assignsubmission_file_{MODULE}.py", CODE)
    make_special(moodle / "Bo Li_77_assignsubmission_file_scan.pdf", kind)
    for root, file in ((canvas, "lab07_report.md"), (moodle, "scan.pdf")):
        upload = read_upload(root, [MODULE], [MODULE])
        [entry] = upload.entries
        assert not entry.error and entry.report_files == {}
        assert entry.report.problems == (f"{file} was not read: {FOLDER_KINDS[kind]}",)
        assert len(upload.ignored) == 1, "still listed with the upload's ignored items"
