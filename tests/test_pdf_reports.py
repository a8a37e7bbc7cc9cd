"""Issue 37: PDF reports read per exercise, only in a sandbox worker, and the report's figures
matched against the figures the student's code makes.

The PDFs are written in code (tests/pdf_making.py); one :class:`ReportReader` (one worker,
a fresh one after a failure) serves the module's tests, as one serves a class.
"""

from __future__ import annotations

import io
import resource
import zlib

import cv2
import numpy as np
import pytest

from autograder.engine.registry import discover
from autograder.instructor.review import provenance
from autograder.loading import pdf_report
from autograder.loading.headings import ExerciseNames
from autograder.loading.pdf_report import ReportReader
from autograder.loading.report import read_report
from autograder.sandbox import report_reader
from pdf_making import assemble, pdf

NAMES = ExerciseNames.of_labs(discover().values())
UNREADABLE = "the PDF's text could not be read: "


@pytest.fixture(scope="module")
def reader():
    with ReportReader() as reader:
        yield reader


def texture(seed: int, shape=(200, 300)) -> np.ndarray:
    """A grey picture with structure at every scale (smoothed noise), ``uint8``."""
    noise = np.random.default_rng(seed).random(shape).astype(np.float32)
    smooth = cv2.GaussianBlur(noise, (0, 0), 6) * 0.7 + cv2.GaussianBlur(noise, (0, 0), 1.5) * 0.3
    return cv2.normalize(smooth, None, 0, 255, cv2.NORM_MINMAX).astype(np.uint8)


def test_a_pdf_with_the_students_own_headings_is_split_per_exercise(reader):
    data = pdf([["Lab 7 report - Ada", "Exercise 1: Translation", "Moving by (tx, ty) shifts every pixel.", "1"],
                ["Lab 7 report - Ada", "2. Rotation", "Turning about the centre keeps it in view.",
                 "Scaling doubles the size of everything.", "2"],
                ["Scaling", "The picture grows from the origin."]])
    report = read_report({"lab07_report.pdf": data}, NAMES, reader)
    assert report.problems == ()
    found = {e: (x.text, x.source) for e, x in report.explanations.items()}
    # a section runs to the next exercise's heading, page numbers and running headers included
    assert found["lab07.ex1"] == ("Moving by (tx, ty) shifts every pixel.\n1\n\nLab 7 report - Ada",
                                  "lab07_report.pdf, page 1")
    # the running header atop page 2 ends no section of its own; a sentence starting with a title is no heading
    assert found["lab07.ex2"][0].startswith("Turning about the centre keeps it in view.\nScaling doubles the size")
    assert found["lab07.ex2"][1] == "lab07_report.pdf, page 2"
    assert found["lab07.ex3"] == ("The picture grows from the origin.", "lab07_report.pdf, page 3")
    assert set(found) == {"lab07.ex1", "lab07.ex2", "lab07.ex3"}
    # without a reader (or the exercises' names) a PDF is only listed, as before
    assert read_report({"lab07_report.pdf": data}, NAMES).explanations == {}
    assert read_report({"lab07_report.pdf": data}, None, reader).attachments == ("lab07_report.pdf",)


def test_the_scaffolds_markers_keep_precedence_over_a_pdfs_headings(reader):
    markdown = b"## lab07.ex1: Translation\n<!-- explanation lab07.ex1 -->\nFrom the scaffold.\n<!-- end explanation -->\n"
    data = pdf([["Exercise 1", "From the PDF."], ["Exercise 2", "Only in the PDF."]])
    report = read_report({"lab07_report.md": markdown, "lab07_report.pdf": data}, NAMES, reader)
    assert report.explanations["lab07.ex1"].text == "From the scaffold."
    assert report.explanations["lab07.ex2"].text == "Only in the PDF."


def encrypted() -> bytes:
    import pypdf

    writer = pypdf.PdfWriter(clone_from=io.BytesIO(pdf([["Exercise 1", "secret words"]])))
    writer.encrypt(user_password="a password", algorithm="RC4-128")
    out = io.BytesIO()
    writer.write(out)
    return out.getvalue()


def bomb() -> bytes:
    """A page whose content stream inflates from ~200 KB to 200 MB (pypdf stops at 75 MB)."""
    inflated = zlib.compress(b" " * (200 * 2**20), 9)
    return pdf([["Exercise 1", "text"]], raw_objects=[b"<< /Length %d /Filter /FlateDecode >>\nstream\n" % len(inflated)
                                                       + inflated + b"\nendstream"]).replace(
        b"/Contents 4 0 R", b"/Contents 6 0 R")


def nested() -> bytes:
    """A page tree 100,000 arrays deep."""
    depth = 100_000
    return assemble([b"<< /Type /Catalog /Pages 2 0 R >>",
                     b"<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
                     b"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 612 792] /Resources " + b"[" * depth
                     + b"]" * depth + b" /Contents 4 0 R >>",
                     b"<< /Length 0 >>\nstream\n\nendstream"])


def cycle() -> bytes:
    """A page tree whose only kid is itself."""
    return assemble([b"<< /Type /Catalog /Pages 2 0 R >>", b"<< /Type /Pages /Kids [2 0 R] /Count 1 >>"])


HOSTILE = {
    "not a PDF": (lambda: b"PK\x03\x04 a zip renamed .pdf" * 100, "it is not a PDF"),
    "cut short": (lambda: pdf([["Exercise 1", "text"]])[:300], "it is not a readable PDF"),
    "encrypted": (encrypted, "it is encrypted (protected by a password)"),
    "a decompression bomb": (bomb, "the text of its pages cannot be read (LimitReachedError"),
    "nested 100,000 deep": (nested, "its pages cannot be found"),
    "a page tree that is its own kid": (cycle, "its pages cannot be found"),
    "pictures only": (lambda: pdf([[]], {0: [texture(1)]}), "it holds no text"),
}


@pytest.mark.parametrize("kind", sorted(HOSTILE))
def test_a_hostile_pdf_is_one_clear_sentence_and_the_grader_neither_fails_nor_swells(reader, kind):
    make, words = HOSTILE[kind]
    data = make()
    assert len(data) < 1_000_000
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    report = read_report({"lab07_report.pdf": data, "lab07_report.md": b"## Exercise 4\nShearing slants it."},
                         NAMES, reader)
    grown = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) * 1024   # KiB on Linux
    assert grown < 50 * 2**20, f"the grader's peak memory grew by {grown / 2**20:.0f} MiB"
    pdf_problems = [p for p in report.problems if p.startswith("lab07_report.pdf")]
    assert len(pdf_problems) == 1 and pdf_problems[0].startswith(f"lab07_report.pdf: {UNREADABLE}"), report.problems
    assert words in pdf_problems[0]
    assert report.explanations["lab07.ex4"].text == "Shearing slants it."   # the rest of the report is read


def test_time_is_bounded_by_the_worker_and_the_next_pdf_gets_a_fresh_one(monkeypatch):
    many = pdf([[f"Exercise {1 + n % 6}", "words " * 200] for n in range(150)])
    with ReportReader() as reader:
        monkeypatch.setattr(pdf_report, "PDF_SECONDS", 0.05)
        slow = reader.pdf(many)
        assert slow.error == "reading it took longer than 0.05 seconds"
        monkeypatch.setattr(pdf_report, "PDF_SECONDS", 20.0)
        assert reader.pdf(pdf([["Exercise 1", "fine"]])).pages == ("Exercise 1\nfine\n",)


def test_a_pdf_larger_than_read_is_not_sent_to_a_worker(monkeypatch):
    monkeypatch.setattr(pdf_report, "MAX_PDF_BYTES", 1000)
    with ReportReader() as reader:
        answer = reader.pdf(b"%PDF-1.4\n" + b"0" * 2000)
        assert answer.error.startswith("it is 0.0 MiB, more than") and reader._box is None


def test_the_worker_answers_plain_data_only():
    """What crosses back is strings, numbers and uint8 arrays (the transport refuses the rest);
    the grader checks each field again (pdf_report._pdf_text)."""
    answer = {"pages": ["a", 3, None], "images": [{"page": 1, "number": 1, "width": 10, "height": 10,
                                                    "thumb": np.zeros((2, 2), np.uint8)}, "x"],
              "notes": [7], "error": 5}
    checked = pdf_report._pdf_text(answer)
    assert checked == pdf_report.PdfText(pages=("a",))
    assert pdf_report._pdf_text(["not", "a", "dict"]).error


# ------------------------------------------------------------------ figure provenance
def code_figure_folder(tmp_path, pictures: dict[str, np.ndarray]) -> dict:
    folder = tmp_path / "figures"
    folder.mkdir()
    for figure_id, picture in pictures.items():
        cv2.imwrite(str(folder / f"{figure_id}.png"), picture)
    return {figure_id: folder / f"{figure_id}.png" for figure_id in pictures}


def test_a_report_figure_the_code_makes_matches_and_one_it_does_not_make_matches_none(reader, tmp_path):
    made, other = texture(7), texture(8)
    # In the PDF: the code's figure at half size, then another picture of the same shape.
    half = cv2.resize(made, (150, 100), interpolation=cv2.INTER_AREA)
    # (page 2's running header ends exercise 1's section there: too little of it for page 2's picture)
    data = pdf([["Exercise 1: Translation", "My result:"], ["Lab 7 report", "Exercise 2", "Another picture:"]],
               {0: [half], 1: [cv2.resize(other, (150, 100), interpolation=cv2.INTER_AREA)]})
    report = read_report({"lab07_report.pdf": data}, NAMES, reader)
    assert [(f.exercise, f.source, f.number, f.width, f.height) for f in report.figures] == [
        ("lab07.ex1", "lab07_report.pdf, page 1", 1, 150, 100), ("lab07.ex2", "lab07_report.pdf, page 2", 2, 150, 100)]
    stored = [{"exercise": f.exercise, "number": f.number, "source": f.source, "width": f.width,
               "height": f.height, "thumb": f.thumb.tobytes()} for f in report.figures]
    # The code made the first (in colour, as the batch draws) and a third picture.
    paths = code_figure_folder(tmp_path, {"lab07.ex1": cv2.cvtColor(made, cv2.COLOR_GRAY2BGR), "lab07.ex3": texture(9)})
    first, = provenance.for_exercise(stored, paths, "lab07.ex1")
    assert first.matched == "lab07.ex1" and not first.unmatched
    assert first.sentence == "report figure 1 (lab07_report.pdf, page 1) matches the figure lab07.ex1 the code makes"
    second, = provenance.for_exercise(stored, paths, "lab07.ex2")
    assert second.unmatched and second.sentence == \
        "report figure 2 (lab07_report.pdf, page 2) matches none of the figures your code makes"
    # Honest: with no figure of the code's, nothing is said to match none.
    alone, = provenance.for_exercise(stored, {}, "lab07.ex2")
    assert not alone.unmatched and "was not compared" in alone.sentence


def test_rescaling_and_jpeg_keep_a_match_and_a_changed_panel_breaks_it():
    made = cv2.cvtColor(np.hstack([texture(1), texture(2), texture(3)]), cv2.COLOR_GRAY2BGR)
    code = [provenance.CodeFigure("lab07.ex1", made.shape[1], made.shape[0], report_reader.thumbnail(made))]

    def verdict(picture) -> bool:
        thumb = report_reader.thumbnail(picture)
        finding, = provenance.findings([{"exercise": "lab07.ex1", "number": 1, "source": "r.pdf, page 1",
                                         "width": picture.shape[1], "height": picture.shape[0],
                                         "thumb": thumb.tobytes()}], code)
        return finding.matched == "lab07.ex1"

    for scale, quality in ((0.35, 40), (0.6, 75), (1.4, 90)):   # 70 to 280 pixels high
        small = cv2.resize(made, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA)
        assert verdict(cv2.imdecode(cv2.imencode(".jpg", small, [cv2.IMWRITE_JPEG_QUALITY, quality])[1],
                                    cv2.IMREAD_COLOR)), (scale, quality)
    shifted = made.copy()
    shifted[:, 600:] = np.roll(made[:, 600:], 12, axis=1)     # the third panel moved 12 px
    assert not verdict(shifted)
    replaced = made.copy()
    replaced[:, 600:] = made[:, 300:600]                       # the third panel is the second
    assert not verdict(replaced)
    assert not verdict(made[:, :600])                          # another shape: two panels of three
    tiny = cv2.resize(made, None, fx=0.2, fy=0.2, interpolation=cv2.INTER_AREA)   # 40 pixels high
    finding, = provenance.findings([{"exercise": "lab07.ex1", "number": 1, "source": "r.pdf, page 1", "width": 180,
                                     "height": 40, "thumb": report_reader.thumbnail(tiny).tobytes()}], code)
    assert not finding.unmatched and finding.sentence.endswith("is 180 x 40 pixels, too small to be compared")


def test_a_plain_picture_is_not_said_to_match_none():
    code = [provenance.CodeFigure("lab07.ex1", 300, 200, report_reader.thumbnail(texture(1)))]
    flat = np.full((200, 300), 128, np.uint8)
    finding, = provenance.findings([{"exercise": "lab07.ex1", "number": 1, "source": "r.pdf, page 1",
                                     "width": 300, "height": 200,
                                     "thumb": report_reader.thumbnail(flat).tobytes()}], code)
    assert not finding.unmatched and "almost uniform" in finding.sentence


def test_a_notebooks_image_outputs_are_figures_of_the_exercise_above_them(reader):
    import base64
    import json

    png = base64.b64encode(cv2.imencode(".png", texture(4))[1].tobytes()).decode()
    cells = [{"cell_type": "markdown", "metadata": {}, "source": "## Exercise 2: Rotation\nIt turns."},
             {"cell_type": "code", "metadata": {}, "source": "show()", "execution_count": 1,
              "outputs": [{"output_type": "display_data", "metadata": {}, "data": {"image/png": png}}]},
             {"cell_type": "code", "metadata": {}, "source": "icon()", "execution_count": 2,
              "outputs": [{"output_type": "display_data", "metadata": {},
                           "data": {"image/png": base64.b64encode(cv2.imencode(".png", texture(5, (20, 20)))[1]
                                                                  .tobytes()).decode()}}]}]
    notebook = json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}).encode()
    report = read_report({"lab07_transformations.ipynb": notebook}, NAMES, reader)
    assert report.explanations["lab07.ex2"].text == "It turns."
    assert [(f.exercise, f.source, f.width) for f in report.figures] == [
        ("lab07.ex2", "lab07_transformations.ipynb, cell 2", 300)]   # the 20 px icon is no figure
    assert report.problems == ()


def test_the_review_screen_shows_the_pdfs_text_and_the_report_figures_the_code_does_not_make(reader, tmp_path):
    pytest.importorskip("flask")
    from autograder.instructor.review.app import ReviewSession, create_app
    from test_review_app import CSRF, TOKEN, get
    from test_review_storage import graded_book

    made, other = texture(11), texture(12)
    data = pdf([["Lab 7", "Exercise 1: Translation", "The corners turn <b>black</b>."]],
               {0: [cv2.resize(made, (150, 100), interpolation=cv2.INTER_AREA),
                    cv2.resize(other, (150, 100), interpolation=cv2.INTER_AREA)]})
    with graded_book(tmp_path, ("ada",), (12.0,)) as book:
        entry = next(iter(book_entries(book)))
        entry.report_files = {"ada lovelace lab07.pdf": data}
        entry.report = read_report(entry.report_files, NAMES, reader)
        book.sync_students([entry], {"ada": "key-ada"})
    (tmp_path / "ada" / "figures").mkdir(parents=True)
    cv2.imwrite(str(tmp_path / "ada" / "figures" / "lab07.ex1.png"), cv2.cvtColor(made, cv2.COLOR_GRAY2BGR))
    for anonymous in (False, True):
        session = ReviewSession(tmp_path, reviewer="prof", anonymous=anonymous)
        try:
            page = get(create_app(session, token=TOKEN, csrf=CSRF).test_client(), f"/{TOKEN}/review/0").get_data(as_text=True)
        finally:
            session.close()
        explanation = page.split('id="explanation"')[1].split('id="figures"')[0]
        assert "The corners turn &lt;b&gt;black&lt;/b&gt;." in explanation   # the PDF's text, inert
        figures = page.split('id="provenance"')[1]
        name = "report 1 (PDF)" if anonymous else "ada lovelace lab07.pdf"   # a label of the anonymous mode
        assert f"report figure 1 ({name}, page 1) matches the figure lab07.ex1 the code makes" in figures
        assert f'<li class="bad">report figure 2 ({name}, page 1) matches none of the figures your code makes</li>' \
            in figures
        assert ("ada lovelace" in page) is not anonymous


def book_entries(book):
    """The gradebook's students as ingest Entries (the fields sync_students stores)."""
    from autograder.instructor.batch.ingest import Entry

    return [Entry(s["student_id"], s["display_name"], "canvas", f"{s['student_id']}.py",
                  files={"lab07_transformations.py": b"x"}, lms={"canvas_user_id": "100"})
            for s in book.class_results()]


def test_anonymous_review_rewrites_an_unreadable_pdfs_sentence_from_fixed_words():
    from autograder.instructor.review.anonymity import Anonymiser

    hide = Anonymiser({"student_id": "ada", "display_name": "Ada Lovelace", "lms": {}, "members": [], "origin": "ada"},
                      {"ada lovelace lab07.pdf": 10}, "Student X")
    said = [hide.problem(f"ada lovelace lab07.pdf: {UNREADABLE}{why}") for why in
            ("it is encrypted (protected by a password); hand in a PDF without one",
             "it is not a readable PDF (PdfReadError: Ada Lovelace wrote this object)",
             "reading it took longer than 20 seconds")]
    assert said == [f"report 1 (PDF): {UNREADABLE}it is encrypted (protected by a password)",
                    f"report 1 (PDF): {UNREADABLE}it is not a readable PDF",     # the parser's words are dropped
                    f"report 1 (PDF): {UNREADABLE}reading it took longer than 20 seconds"]


def test_a_markdown_reports_linked_pictures_are_figures_of_the_section_linking_them(tmp_path):
    """Read as the batch reads a class: the pictures beside the report are kept in memory for
    their thumbnails only (never stored), and each link counts under the heading above it."""
    from autograder.instructor.batch.ingest import read_upload

    made, other = texture(21), texture(22)
    student = tmp_path / "class" / "ada"
    (student / "figures").mkdir(parents=True)
    (student / "lab07_transformations.py").write_text("def translate(image, tx, ty):\n    return image\n")
    cv2.imwrite(str(student / "figures" / "mine.jpg"), cv2.resize(made, (240, 160)), [cv2.IMWRITE_JPEG_QUALITY, 70])
    cv2.imwrite(str(student / "figures" / "other one.png"), other)
    (student / "figures" / "fake.png").write_bytes(b"not a picture at all")
    (student / "lab07_report.md").write_text(
        "# Lab 7\n\n## Exercise 1: Translation\n\n![my result](figures/mine.jpg)\n\nIt moves.\n\n"
        "## Exercise 2\n\n![](<figures/other%20one.png> \"title\")\n![again](./figures/mine.jpg)\n"
        "![gone](figures/fake.png) ![web](https://example.org/x.png) ![up](../secret.png)\n")
    entry, = read_upload(tmp_path / "class", ["lab07_transformations"], ["lab07_transformations"], names=NAMES).entries
    assert "figures/mine.jpg" not in entry.report_files and entry.report.explanations["lab07.ex1"].text == "It moves."
    figures = [(f.exercise, f.source, f.number, f.width) for f in entry.report.figures]
    assert figures == [("lab07.ex1", "lab07_report.md, figures/mine.jpg", 1, 240),
                       ("lab07.ex2", "lab07_report.md, figures/other one.png", 2, 300)]
    stored = [{"exercise": f.exercise, "number": f.number, "source": f.source, "width": f.width,
               "height": f.height, "thumb": f.thumb.tobytes()} for f in entry.report.figures]
    from autograder.instructor.review.anonymity import Anonymiser
    from autograder.instructor.review.app import _labelled

    hide = Anonymiser({"student_id": "ada", "display_name": "Ada Lovelace", "lms": {}, "members": [],
                       "origin": "ada"}, {"lab07_report.md": 1}, "Student X")
    assert _labelled(hide, "lab07_report.md, figures/ada_lovelace.png") == "report 1 (Markdown), figures/Student X.png"
    paths = code_figure_folder(tmp_path, {"lab07.ex1": made})
    assert provenance.for_exercise(stored, paths, "lab07.ex1")[0].matched == "lab07.ex1"
    assert provenance.for_exercise(stored, paths, "lab07.ex2")[0].unmatched


def test_broken_pictures_leave_the_text_read_and_are_one_sentence(reader):
    picture = texture(31, (100, 100))
    packed = zlib.compress(picture.tobytes())
    data = pdf([["Exercise 1", "Text one."], ["Exercise 2", "Text two."]], {0: [picture, picture], 1: [picture]})
    data = data.replace(packed, b"x" * len(packed))   # every picture's stream is no zlib stream
    report = read_report({"lab07_report.pdf": data}, NAMES, reader)
    assert report.explanations["lab07.ex2"].text == "Text two." and report.figures == ()
    assert report.problems == ("lab07_report.pdf: a picture on pages 1, 2 could not be read; it was not compared",)


def test_a_classs_pdfs_are_read_side_by_side_with_the_same_answers(monkeypatch):
    monkeypatch.setenv("AUTOGRADER_CACHE_DIR", "off")   # every file read by a worker, none from the store
    files = [pdf([[f"Exercise {n % 6 + 1}", f"Student {n} writes."]]) for n in range(4)]
    files += [b"%PDF-1.4 cut", files[0]]                  # a broken one, and one handed in twice
    with ReportReader() as alone:
        one_by_one = [alone.pdf(data) for data in files]
    assert one_by_one[0].pages == ("Exercise 1\nStudent 0 writes.\n",) and one_by_one[4].error
    with ReportReader() as reader:
        reader.prefetch(files, 2)
        assert reader.files_read == 5 and reader._box is None   # read by two readers of its own
        assert [reader.pdf(data) for data in files] == one_by_one
        assert reader.files_read == 5 and reader._box is None   # nothing read again


def test_the_grader_never_parses_a_pdf_or_a_picture_itself(monkeypatch, reader):
    """With pypdf's reader and Pillow's decoder refusing in the grader's process, a PDF and a
    notebook's picture are still read: in the worker."""
    import base64
    import json

    import pypdf
    from PIL import Image

    def refuse(*args, **kwargs):
        raise AssertionError("parsed in the grader's process")

    monkeypatch.setenv("AUTOGRADER_CACHE_DIR", "off")   # read by the worker, not found in the store
    monkeypatch.setattr(pypdf, "PdfReader", refuse)
    monkeypatch.setattr(Image, "open", refuse)
    png = base64.b64encode(cv2.imencode(".png", texture(41))[1].tobytes()).decode()
    notebook = json.dumps({"nbformat": 4, "nbformat_minor": 5, "metadata": {}, "cells": [
        {"cell_type": "markdown", "metadata": {}, "source": "## Exercise 3\nScaled."},
        {"cell_type": "code", "metadata": {}, "source": "", "execution_count": 1, "outputs": [
            {"output_type": "display_data", "metadata": {}, "data": {"image/png": png}}]}]}).encode()
    report = read_report({"lab07_report.pdf": pdf([["Exercise 1", "Read elsewhere."]], {0: [texture(40)]}),
                          "lab07.ipynb": notebook}, NAMES, reader)
    assert report.problems == () and report.explanations["lab07.ex1"].text == "Read elsewhere."
    assert [(f.exercise, f.source) for f in report.figures] == [("lab07.ex3", "lab07.ipynb, cell 2"),
                                                                ("lab07.ex1", "lab07_report.pdf, page 1")]


def test_where_workers_cannot_be_confined_nothing_is_parsed_unless_allowed():
    from autograder.sandbox.confine import Confinement

    data = pdf([["Exercise 1", "Text."]])
    with ReportReader(Confinement("process-group")) as reader:
        assert reader.pdf(data).error == pdf_report.UNCONFINED and reader._box is None
        assert reader.pictures([("nb, cell 1", cv2.imencode(".png", texture(1))[1].tobytes())]) == (
            [], [f"the pictures were not compared: {pdf_report.UNCONFINED}"])
    with ReportReader(Confinement("process-group"), allow_unconfined=True) as reader:   # --allow-unconfined
        assert reader.pdf(data).pages == ("Exercise 1\nText.\n",)
