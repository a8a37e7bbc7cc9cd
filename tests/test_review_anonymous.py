"""Issue 34: ``autograder review --anonymous`` shows no name, id, e-mail, file name or path of a student.

- a property (Hypothesis, the derandomised profile): students with generated identities --
  names with accents and letters no ASCII has, ids, e-mails, LMS ids -- hand in report files
  named after themselves in many forms (case, separators, decomposed Unicode, run
  together), some refused (a link, a pipe), with explanations and check messages naming
  them; every route of the application is walked with Flask's test client (each one, as
  ``url_map`` lists them), and no form of any of it is in any body or header;
- every sentence the grader writes about a report (driven from the real readers) is
  rewritten from a template, never shown as "a problem was found";
- a student's links that resolve against the application (its rubric page showed their
  words in its error panel) are inert on the review screen.
"""

from __future__ import annotations

import html
import json
import os
import re
import unicodedata
import warnings
from urllib.parse import quote, quote_plus

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

pytest.importorskip("flask")

from autograder.instructor.batch.gradebook import Gradebook  # noqa: E402
from autograder.instructor.batch.ingest import Entry  # noqa: E402
from autograder.instructor.batch.run import _course_record  # noqa: E402
from autograder.instructor.batch.tree import ReportFiles  # noqa: E402
from autograder.instructor.review.anonymity import UNKNOWN_PROBLEM, Anonymiser  # noqa: E402
from autograder.instructor.review.app import ReviewSession, create_app  # noqa: E402
from autograder.loading.report import Explanation, Report, read_report  # noqa: E402
from test_review_app import CSRF, TOKEN, get, post  # noqa: E402
from test_review_storage import COURSE, result  # noqa: E402

MODULE = "lab07_transformations"
# Letters outside a-f (a pseudonym and the addresses are hexadecimal), some no ASCII has.
LETTERS = "ghijklmnopqrstuvwxyzøñłüßçåšžéí"


def plain(text: str) -> str:
    return "".join(c for c in unicodedata.normalize("NFKD", text) if not unicodedata.combining(c))


def slug(text: str) -> str:
    return "".join(c for c in plain(text).casefold() if c.isascii() and c.isalnum())


@st.composite
def identities(draw) -> dict:
    part = st.text(LETTERS, min_size=4, max_size=9).map(str.capitalize)
    first, last = draw(part), draw(part)
    matric = f"s{draw(st.integers(1_000_000, 9_999_999))}"
    canvas = str(draw(st.integers(10**6, 10**9)))
    name = f"{first} {last}"
    email = f"{slug(first) or 'x'}.{slug(last) or 'y'}@uni.example"
    mate_first, mate_last = draw(part), draw(part)   # a group partner (Gradescope's submitters)
    partner = {"first": mate_first, "last": mate_last, "name": f"{mate_first} {mate_last}",
               "sid": f"s{draw(st.integers(1_000_000, 9_999_999))}", "email": f"{slug(mate_last) or 'p'}@uni.example"}
    return {"first": first, "last": last, "name": name, "matric": matric, "canvas": canvas, "email": email,
            "id": f"{slug(last) or 'z'}-{matric}", "origin": f"{slug(last)}{slug(first)}_{canvas}_55_{MODULE}.py",
            "partner": partner}


def forms_of(who: dict) -> list[str]:
    """The texts that would tell who the student is (each checked in several spellings)."""
    slugs = [s for s in (slug(who["first"]), slug(who["last"])) if len(s) >= 4]
    mate = who["partner"]
    return [who["first"], who["last"], who["name"], who["matric"], who["canvas"], who["email"], who["id"],
            who["origin"], f"{who['first']}{who['last']}", *slugs, *who["files"],
            mate["first"], mate["last"], mate["name"], mate["sid"], mate["email"]]


def spellings(text: str) -> set[str]:
    forms = {text, unicodedata.normalize("NFD", text), unicodedata.normalize("NFC", text), plain(text)}
    escaped = {f for t in forms for f in (json.dumps(t)[1:-1], quote(t), quote_plus(t), html.escape(t))}
    return {f.casefold() for f in forms | escaped}


def student_files(who: dict) -> dict[str, bytes]:
    """Report files named after the student, as students name them."""
    first, last, matric = who["first"], who["last"], who["matric"]
    marker = (f"## lab07.ex1: Translate\n\n<!-- explanation lab07.ex1 -->\nI am {who['name']} ({matric}).\n"
              "<!-- end explanation -->\n")
    return {
        f"{last.lower()}_{matric}_lab07_report.md": marker.encode(),
        f"{first.upper()}-{last.upper()}/scan.pdf": b"%PDF-1.4 one",
        unicodedata.normalize("NFD", f"{who['name']} report.pdf"): b"%PDF-1.4 two",
        f"{who['email']}/notes.md": f"<!-- explanation {who['id']} -->\nx\n<!-- end explanation -->\n".encode(),
    }


def refused_files(who: dict) -> list[str]:
    reports = ReportFiles()
    reports.refuse(f"{who['last']}{who['first']}.md", "it is a symbolic link")
    reports.refuse(f"{who['matric']}/{who['first'].lower()}.pdf", "it is not a regular file (a named pipe)")
    reports.refuse(f"{who['name']}.zip/{who['id']}.md", f"the archive holds {who['id']}.md twice")
    return reports.problems()


def explanation(who: dict) -> str:
    first, last = who["first"], who["last"]
    return (f"Written by {who['name']} / {who['name'].upper()} / {unicodedata.normalize('NFD', who['name'])} / "
            f"{plain(who['name'])} / {first}{last} / {last}_{first} / {last.lower()}-{first.lower()} / "
            f"{who['email']} / {who['matric']}lab07 / id {who['id']} / canvas {who['canvas']} / "
            f"see {who['origin']} and [my rubric](../rubric?error=by-{quote(who['name'])}) and "
            "[the rubric](../rubric?error=hello) and [the sheet](https://example.org/lab) and "
            f"[my page](https://example.org/{slug(first)}{slug(last)}) and <{who['email']}>. With "
            f"{who['partner']['name']} ({who['partner']['sid']}, {who['partner']['email']}).")


def build_class(folder, who: dict) -> None:
    """A graded class of the student and a neighbour, their report as the batch keeps it."""
    files = student_files(who)
    report = read_report(files)
    source = next(iter(report.explanations.values())).source if report.explanations else ""
    report = Report({"lab07.ex1": Explanation("lab07.ex1", explanation(who),
                                              f"{source}; {who['last']}_{MODULE}.ipynb, cell 3")},
        report.attachments, tuple(refused_files(who)) + report.problems)
    who["files"] = sorted({*files, f"{who['last']}{who['first']}.md", f"{who['last']}_{MODULE}.ipynb",
                           f"{who['matric']}/{who['first'].lower()}.pdf", f"{who['name']}.zip/{who['id']}.md"})
    student = Entry(who["id"], who["name"], "canvas", who["origin"], files={f"{MODULE}.py": b"x"},
                    lms={"canvas_user_id": who["canvas"], "email": who["email"], "sid": who["matric"]},
                    members=[{"name": who["name"], "sid": who["matric"], "email": who["email"]},
                             {k: who["partner"][k] for k in ("name", "sid", "email")}],
                    report_files=files, report=report)
    other = Entry("zz-other", "Other Person", "canvas", "other.py", files={f"{MODULE}.py": b"y"})
    graded = result(6.0)
    graded["exercises"][0]["checks"][0].update(status="failed", message=(
        f"File \"/submissions/{who['origin']}/{MODULE}.py\", line 3: raised ValueError('{who['name']} "
        f"{who['matric']}') for {who['email']}"))
    with Gradebook(folder) as book:
        book.sync_students([student, other], {who["id"]: "k1", "zz-other": "k2"})
        book.set_meta("course", _course_record(COURSE))
        book.sync_rubric(COURSE.rubric)
        book.record("k1", who["id"], student.content_hash, "lab07.ex1", graded, lock="l")
        book.record("k2", "zz-other", other.content_hash, "lab07.ex1", result(12.0), lock="l")
    figures = folder / who["id"] / "figures"
    figures.mkdir(parents=True)
    (figures / "lab07.ex1.png").write_bytes(b"\x89PNG figure")


def walk(folder, anonymous: bool = True) -> tuple[list[tuple[str, str]], set[str]]:
    """Every route of the application, in anonymous mode: (what was asked, body and headers)
    for each response, and the endpoints not reached (of those ``url_map`` lists)."""
    session = ReviewSession(folder, reviewer="prof", anonymous=anonymous)
    app = create_app(session, token=TOKEN, csrf=CSRF)
    routes = {rule.endpoint for rule in app.url_map.iter_rules()}
    client = app.test_client()
    seen: list[tuple[str, str]] = []
    reached: set[str] = set()

    def keep(what: str, response) -> None:
        headers = "\n".join(f"{k}: {v}" for k, v in response.headers.items())
        seen.append((what, headers + "\n" + response.get_data().decode("utf-8", "replace")))

    def ask(method, path, data=None, **kw):
        response = get(client, path, **kw) if method == "GET" else post(client, path, data, **kw)
        with app.test_request_context(path.split("?")[0], method=method, base_url="http://127.0.0.1:5000"):
            from flask import request
            reached.add(request.url_rule.endpoint if request.url_rule else "")
        keep(f"{method} {path}", response)
        return response

    try:
        ask("GET", f"/{TOKEN}/")
        for pair in session.queue():
            ask("GET", f"/{TOKEN}/review/{pair.position}")
            where = f"/{TOKEN}/pair/{pair.ref}/{pair.exercise}"
            for step in ("next", "previous"):
                ask("GET", f"{where}/step/{step}")
            ask("POST", f"{where}/mark", {"csrf": CSRF, "item": "corners", "applied": "1"},
                headers={"Accept": "application/json"})
            ask("POST", f"{where}/mark", {"csrf": CSRF, "item": "nope", "applied": "1"})
            ask("POST", f"{where}/note", {"csrf": CSRF, "comment": "seen", "done": "1"},
                headers={"Accept": "application/json"})
            ask("POST", f"{where}/note", {"csrf": CSRF, "comment": "seen"})
            ask("GET", f"/{TOKEN}/figure/{pair.ref}/{pair.exercise}/{pair.exercise}.png")
            ask("GET", f"/{TOKEN}/figure/{pair.ref}/{pair.exercise}/lab07.ex9.png")
            for number in range(4):
                ask("GET", f"/{TOKEN}/attachment/{pair.ref}/{pair.exercise}/{number}")
        ask("GET", f"/{TOKEN}/rubric")
        ask("GET", f"/{TOKEN}/rubric?error=x")
        ask("POST", f"/{TOKEN}/rubric/lab07.ex1", {"csrf": CSRF, "item": "corners", "text": "t", "points": "x"})
        ask("POST", f"/{TOKEN}/rubric/lab07.ex1", {"csrf": CSRF, "item": "corners", "text": "t", "points": "2",
                                                   "back": "0"})
        ask("POST", f"/{TOKEN}/bank/lab07.ex1", {"csrf": CSRF, "key": "corners", "text": "Why black?", "back": "0"})
        ask("POST", f"/{TOKEN}/bank/lab07.ex1", {"csrf": CSRF, "key": "not a key", "text": "t"})
        ask("GET", f"/{TOKEN}/review/0")       # with a saved comment
        for show in ("todo", "noreport"):
            ask("GET", f"/{TOKEN}/?show={show}")
        ask("GET", f"/{TOKEN}/static/review.js")
        ask("GET", f"/{TOKEN}/review/99")
        ask("GET", "/not-the-token/")
    finally:
        session.close()
    return seen, routes - reached


@pytest.fixture(scope="module")
def baseline(tmp_path_factory) -> str:
    """Everything the application shows of a class whose student is named with ASCII only: a
    generated name part that is one of its words (a CSS property, "rubric") tells nothing."""
    folder = tmp_path_factory.mktemp("baseline")
    build_class(folder, {"first": "Aaaa", "last": "Bbbb", "name": "Aaaa Bbbb", "matric": "s0000000",
                         "canvas": "0", "email": "a.b@uni.example", "id": "bbbb-s0000000", "origin": "x.py",
                         "partner": {"first": "Cccc", "last": "Dddd", "name": "Cccc Dddd", "sid": "s0000001",
                                     "email": "d@uni.example"}})
    return _Corpus("\n".join(text for _, text in walk(folder)[0]).casefold())


class _Corpus(str):
    def __repr__(self):   # Hypothesis prints its arguments
        return "<the baseline pages>"


@settings(max_examples=20)
@given(who=identities())
def test_anonymous_mode_shows_no_identity_on_any_route(who, baseline, tmp_path_factory):
    mate = who["partner"]
    assume(all(not word or word.casefold() not in baseline for word in (
        who["first"], who["last"], who["matric"], who["canvas"], slug(who["last"]), slug(who["first"]),
        mate["first"], mate["last"], mate["sid"], slug(mate["last"]))))
    folder = tmp_path_factory.mktemp("class")
    build_class(folder, who)
    seen, missed = walk(folder)
    assert not missed, f"routes not walked: {missed}"
    for what, text in seen:
        found = text.casefold()
        for identity in forms_of(who):
            for spelling in spellings(identity):
                assert spelling not in found, (what, identity, spelling)
    review = next(text for what, text in seen if what.startswith("GET /") and "/review/" in what
                  and "Written by Student" in text)
    assert "the rubric [link not followed: ../rubric?error=hello]" in review, "a relative link is text"
    assert 'href="../' not in review and 'href="https://example.org/lab"' in review
    assert "was not read: it is a symbolic link" in review and "was not read: it is not a regular file (a named pipe)" \
        in review and "was not read: the archive holds it twice" in review
    assert len(re.findall(r">report \d \(PDF\)</a>", review)) == 2 and "(notebook), cell 3" in review


def test_the_same_class_not_anonymous_shows_the_names(tmp_path):
    """The property above is not vacuous: without --anonymous the pages do name the student."""
    who = {"first": "Jørgen", "last": "Łukasz", "name": "Jørgen Łukasz", "matric": "s2231234",
           "canvas": "7654321", "email": "jorgen.lukasz@uni.example", "id": "lukasz-s2231234",
           "origin": f"lukaszjorgen_7654321_55_{MODULE}.py",
           "partner": {"first": "Ngozi", "last": "Okoro", "name": "Ngozi Okoro", "sid": "s7777777",
                       "email": "okoro@uni.example"}}
    build_class(tmp_path, who)
    shown = "\n".join(text for _, text in walk(tmp_path, anonymous=False)[0])
    assert "Jørgen Łukasz" in shown and "Ngozi Okoro" in shown
    assert f"{who['last']}{who['first']}.md was not read: it is a symbolic link" in shown
    assert f'filename="{who["id"]}-1.pdf"' in shown


# ------------------------------------------------------------------ every sentence has a template
def grader_sentences(tmp_path) -> list[str]:
    """What the batch writes about hostile reports, from its own readers (no sentence typed here)."""
    import socket
    import stat
    import tempfile
    import zipfile

    from autograder.instructor.batch.ingest import read_upload
    from autograder.loading import report as reading

    from test_batch import write

    root = tmp_path / "class"
    eve = root / "eve"
    write(eve / f"{MODULE}.py", b"def translate(image, tx, ty):\n    return image\n")
    write(eve / "zqhuge.md", b"x" * (reading.MAX_REPORT_BYTES + 1))
    write(eve / "zqnot-a.pdf", b"MZ")
    write(eve / "zqbad\x1bname.md", b"# escape")
    (eve / "zqlinked.md").symlink_to("/etc/passwd")
    os.mkfifo(eve / "zqpipe.md")
    short = tempfile.mkdtemp()   # a socket's path must be short: bound there, then moved
    sock = socket.socket(socket.AF_UNIX)
    sock.bind(f"{short}/s")
    sock.close()
    os.rename(f"{short}/s", eve / "zqsocket.md")
    os.rmdir(short)
    if os.geteuid() == 0:
        os.mknod(eve / "zqdevice.md", stat.S_IFCHR | 0o600, os.makedev(1, 3))
    archive = eve / "zqinner.zip"
    with zipfile.ZipFile(archive, "w") as zf, warnings.catch_warnings():
        warnings.simplefilter("ignore")   # the duplicate is the point
        zf.writestr(f"{MODULE}.py", b"x = 1\n")
        zf.writestr("zqtwice.md", b"a")
        zf.writestr("zqtwice.md", b"b")
    sentences = list(read_upload(root, [MODULE], [MODULE]).entries[0].report.problems)
    marked = "<!-- explanation {} -->\n{}\n<!-- end explanation -->\n"
    files = {
        "zqa.md": ("<!-- explanation lab07.ex2 -->\nno end\n" + marked.format("lab07.ex1", "one") +
                 marked.format("zqnonsense", "x")).encode(),
        "zqb.md": marked.format("lab07.ex1", "y" * reading.MAX_EXPLANATION_CHARS).encode(),
        "zqc.ipynb": b"not json", "zqd.ipynb": b"{}", "zqe.md": 3,
        "zqf.ipynb": json.dumps({"cells": [{"cell_type": "markdown", "source": 7},
                                         {"cell_type": "markdown", "metadata": {"tags": [
                                             "report:lab07.ex3", "report:lab07.ex4"]}, "source": "t"}]}).encode(),
        "zqg.md": "".join(marked.format(f"lab{7 + i // 100:02d}.ex{i % 100 + 1}", "t")
                        for i in range(reading.MAX_EXPLANATIONS + 1)).encode(),
        "zqh.md": b"x" * (reading.MAX_REPORT_BYTES + 1),
    }
    sentences += read_report(files).problems
    from autograder.engine.registry import discover
    from autograder.loading.headings import ExerciseNames

    every = ExerciseNames.of_labs(discover().values())   # a number with no lab to go by
    sentences += read_report({"zqi.md": b"## Exercise 2: Eve's words\ntext\n"}, every).problems
    many = ReportFiles()
    for number in range(30):
        many.refuse(f"zqn{number}.md", "it is a symbolic link")
    sentences += many.problems()
    return sentences


def test_every_sentence_the_grader_writes_about_a_report_is_rewritten_from_a_template(tmp_path):
    sentences = grader_sentences(tmp_path)
    hide = Anonymiser({"student_id": "eve"}, [], "Student ABC123")
    rewritten = {sentence: hide.problem(sentence) for sentence in sentences}
    unknown = [s for s, text in rewritten.items() if text == UNKNOWN_PROBLEM]
    assert not unknown, unknown
    kinds = " ".join(rewritten.values())
    for reason in ("it is a symbolic link", "it is not a regular file (a named pipe)",
                   "it is not a regular file (a socket)", "it is not a PDF", "its name holds control characters",
                   "the archive holds it twice", "(a character device)" if os.geteuid() == 0 else "",
                   "is longer than", "a marker names something", "is explained twice",
                   "has no '<!-- end explanation -->'", "is not a readable notebook", "has no list of cells",
                   "its text is not text", "is tagged for 2 exercises", "more than 300 exercises explained",
                   "and 10 more files were not read", "larger than", "names an exercise by number but not its lab"):
        assert reason in kinds, reason
    for sentence, text in rewritten.items():
        assert "zq" not in text, (sentence, text)   # every file handed in is named zq...
        assert "Eve's words" not in text, (sentence, text)   # nor a heading the student wrote


def test_a_sentence_no_template_knows_is_not_shown_and_a_crafted_name_tells_nothing():
    hide = Anonymiser({"student_id": "eve"}, [], "Student ABC123")
    assert hide.problem("Jane Doe's notes.md is odd") == UNKNOWN_PROBLEM
    crafted = "x was not read: it cannot be read (Jane Doe) was not read: it is a symbolic link"
    assert hide.problem(crafted) == "report 1 (file) was not read: it is a symbolic link"
    assert "Jane" not in hide.problem("the archive holds Jane.md twice was not read: the archive holds Jane.md twice")


def test_free_text_names_the_students_files_by_their_labels_refused_ones_too():
    hide = Anonymiser({"student_id": "eve", "display_name": "Eve Ng"}, ["notes/zqscan.pdf"], "Student ABC123")
    assert hide.problem("zqdraft.md was not read: it is a symbolic link") == \
        "report 2 (Markdown) was not read: it is a symbolic link"
    assert hide.text("see notes/zqscan.pdf and zqdraft.md, by Eve and NG") == \
        "see report 1 (PDF) and report 2 (Markdown), by Student ABC123 and Student ABC123"
    assert hide.text("a remark on Evelyn's eve-ning") == "a remark on Evelyn's Student ABC123-ning", \
        "a name inside a longer word is no name; joined by a hyphen it is"
