"""``autograder review``: the Flask application over the gradebook (Flask's test client).

The token is required everywhere, POSTs need the form's CSRF secret (and a same-origin
``Origin``), the student's text is inert, anonymous mode shows no name, a seeded shuffle
is stable, and every change lands in the gradebook at once.
"""

from __future__ import annotations

import logging
import re
import socket
import threading
import urllib.request

import pytest

pytest.importorskip("flask")

from autograder.instructor.batch.gradebook import Gradebook  # noqa: E402
from autograder.instructor.batch.ingest import Entry  # noqa: E402
from autograder.instructor.review.app import ReviewSession, create_app, serve  # noqa: E402
from test_review_storage import graded_book  # noqa: E402

TOKEN, CSRF = "t0ken-for-tests", "csrf-for-tests"
STUDENTS = ("ada", "bo", "cy")


@pytest.fixture
def results(tmp_path):
    with graded_book(tmp_path, STUDENTS, (12.0, 6.0, 0.0)) as book:
        book.db.execute("INSERT INTO explanations VALUES ('ada', 'lab07.ex1', ?, 'lab07_report.md', 0)",
                        ("The warp leaves **black corners** <script>alert(1)</script> "
                         "[x](javascript:alert(1)) ![fig](figures/lab07.ex1.png) ![t](https://evil.example/t.png)",))
        book.db.execute("INSERT INTO report_files VALUES ('ada', 'ada lovelace.pdf', ?)", (b"%PDF-1.4 x",))
    (tmp_path / "ada" / "figures").mkdir(parents=True)
    (tmp_path / "ada" / "figures" / "lab07.ex1.png").write_bytes(b"\x89PNG figure")
    (tmp_path / "ada" / "figures" / "notes.png").write_bytes(b"\x89PNG not a figure id")
    return tmp_path


def client_for(results, **options):
    session = ReviewSession(results, reviewer="prof", **options)
    app = create_app(session, token=TOKEN, csrf=CSRF)
    return session, app.test_client()


def get(client, path, **kw):
    return client.get(path, base_url="http://127.0.0.1:5000", **kw)


def post(client, path, data, **kw):
    return client.post(path, data=data, base_url="http://127.0.0.1:5000", **kw)


def base(client, position: int) -> str:
    """Where the review screen at ``position`` sends its changes (its script's ``base``)."""
    page = get(client, f"/{TOKEN}/review/{position}").get_data(as_text=True)
    return re.search(r'data-base="([^"]+)"', page)[1]


def test_every_request_needs_the_token_and_a_local_host(results):
    session, client = client_for(results)
    try:
        assert get(client, f"/{TOKEN}/").status_code == 200
        for path in ("/", "/review/0", f"/{TOKEN}x/", f"/{TOKEN[:-1]}/", "/favicon.ico", f"/x/{TOKEN}/",
                     f"/{TOKEN.upper()}/review/0"):
            assert get(client, path).status_code == 403, path
        assert post(client, f"/x/review/0/mark", {"csrf": CSRF, "item": "corners", "applied": "1"}).status_code == 403
        rebinding = client.get(f"/{TOKEN}/", base_url="http://evil.example:5000")
        assert rebinding.status_code == 403, "a DNS-rebound host is refused"
        page = get(client, f"/{TOKEN}/")
        assert page.headers["Referrer-Policy"] == "same-origin"   # no referrer leaves; forms send their Origin
        assert "default-src 'none'" in page.headers["Content-Security-Policy"]
    finally:
        session.close()


def test_posts_need_the_csrf_secret_and_the_same_origin(results):
    session, client = client_for(results)
    try:
        form = {"item": "corners", "applied": "1"}
        mark = base(client, 0) + "/mark"
        assert post(client, mark, form).status_code == 403
        assert post(client, mark, {**form, "csrf": "wrong"}).status_code == 403
        for origin in ("https://evil.example", "null"):   # "null": a sandboxed or no-referrer page elsewhere
            assert post(client, mark, {**form, "csrf": CSRF}, headers={"Origin": origin}).status_code == 403
        assert Gradebook(results, readonly=True).reviews() == {}, "nothing written by a refused request"
        answer = post(client, mark, {**form, "csrf": CSRF},
                      headers={"Origin": "http://127.0.0.1:5000", "Accept": "application/json"})
        assert answer.status_code == 200 and answer.json["applied"] == ["corners"] and answer.json["points"] == 2
        assert post(client, mark, {"csrf": CSRF, "item": "nope", "applied": "1"}).status_code == 400
    finally:
        session.close()


def test_the_review_screen_shows_the_explanation_inert_the_figures_verdict_and_rubric(results):
    session, client = client_for(results)
    try:
        page = get(client, f"/{TOKEN}/review/0").get_data(as_text=True)
        assert "<strong>black corners</strong>" in page
        assert "<script>alert(1)" not in page and "&lt;script&gt;" in page
        assert 'href="javascript:' not in page and "evil.example" not in page.split('id="explanation"')[1][:2000] \
            .replace("[image not shown: t]", "")
        ada = session.ref("ada")
        assert f'src="/{TOKEN}/figure/{ada}/lab07.ex1/lab07.ex1.png"' in page
        assert "notes.png" not in page
        assert "12 / 12" in page and "explains the black corners" in page and "<kbd>1</kbd>" in page
        assert "Ada" in page and "ada lovelace.pdf" in page
        assert get(client, f"/{TOKEN}/figure/{ada}/lab07.ex1/lab07.ex1.png").data == b"\x89PNG figure"
        assert get(client, f"/{TOKEN}/figure/{ada}/lab07.ex1/notes.png").status_code == 404
        assert get(client, f"/{TOKEN}/figure/{ada}/lab07.ex1/..%2f..%2fgradebook.sqlite.png").status_code == 404
        pdf = get(client, f"/{TOKEN}/attachment/{ada}/lab07.ex1/0")
        assert pdf.data == b"%PDF-1.4 x" and pdf.headers["Content-Disposition"].startswith("attachment;")
        assert get(client, f"/{TOKEN}/attachment/{ada}/lab07.ex1/5").status_code == 404
        assert get(client, f"/{TOKEN}/review/99").status_code == 404
        nothing = get(client, f"/{TOKEN}/review/2").get_data(as_text=True)
        assert "No explanation written" in nothing and "No figure" in nothing
    finally:
        session.close()


def test_each_pdf_link_downloads_that_pdf_when_markdown_files_sort_before_it(tmp_path):
    with graded_book(tmp_path, ("ada",), (12.0,)) as book:
        for path, data in (("a_notes.md", b"# notes"), ("b_first.pdf", b"%PDF first"),
                           ("c_report.md", b"# report"), ("d_second.pdf", b"%PDF second")):
            book.db.execute("INSERT INTO report_files VALUES ('ada', ?, ?)", (path, data))
    session, client = client_for(tmp_path)
    try:
        page = get(client, f"/{TOKEN}/review/0").get_data(as_text=True)
        links = re.findall(rf'href="(/{TOKEN}/attachment/[^"]+)">([^<]+)</a>', page)
        assert [name for _, name in links] == ["b_first.pdf", "d_second.pdf"]
        assert [get(client, link).data for link, _ in links] == [b"%PDF first", b"%PDF second"]
    finally:
        session.close()


def test_changes_are_in_the_gradebook_at_once_and_items_are_edited_centrally(results):
    session, client = client_for(results)
    try:
        for position, item in ((0, "corners"), (1, "corners"), (1, "no-figure")):
            post(client, base(client, position) + "/mark", {"csrf": CSRF, "item": item, "applied": "1"})
        post(client, base(client, 1) + "/note", {"csrf": CSRF, "comment": "Where is <b>it</b>?", "done": "1"})
        with Gradebook(results, readonly=True) as other:   # another connection: committed already
            reviews = other.reviews()
        assert reviews[("ada", "lab07.ex1")]["points"] == 2 and reviews[("bo", "lab07.ex1")]["points"] == 1
        assert reviews[("bo", "lab07.ex1")]["done"] and reviews[("bo", "lab07.ex1")]["changed_by"] == "prof"
        answer = post(client, f"/{TOKEN}/rubric/lab07.ex1", {"csrf": CSRF, "item": "corners",
                                                            "text": "explains the corners", "points": "3"})
        assert answer.status_code == 303
        with Gradebook(results, readonly=True) as other:
            reviews = other.reviews()
        assert reviews[("ada", "lab07.ex1")]["points"] == 3 and reviews[("bo", "lab07.ex1")]["points"] == 2
        bad = post(client, f"/{TOKEN}/rubric/lab07.ex1", {"csrf": CSRF, "item": "corners", "text": "t", "points": "x"})
        assert bad.status_code == 400 and "points must be a number" in bad.get_data(as_text=True)
        reflected = get(client, f"/{TOKEN}/rubric?error=Ada+wrote+this").get_data(as_text=True)
        assert "Ada wrote this" not in reflected and 'class="panel error"' not in reflected, \
            "the error panel never shows text from the address"
        assert post(client, f"/{TOKEN}/rubric/lab99.ex1", {"csrf": CSRF, "item": "a", "text": "t",
                                                          "points": "1"}).status_code == 404
        queue = get(client, f"/{TOKEN}/").get_data(as_text=True)
        assert "1 of 3 reviewed" in queue
        page = get(client, f"/{TOKEN}/review/1").get_data(as_text=True)
        assert "Where is &lt;b&gt;it&lt;/b&gt;?" in page
    finally:
        session.close()


def test_a_batch_moving_the_queue_never_turns_a_page_onto_another_student(results):
    """bo's screen is open when a batch grades 'ai', who sorts before bo: the page's marks, comment,
    figures and PDFs stay bo's, and 'next' goes on from where bo is now."""
    from test_review_storage import result

    for student in ("bo", "ai"):
        (results / student / "figures").mkdir(parents=True)
        (results / student / "figures" / "lab07.ex1.png").write_bytes(b"\x89PNG " + student.encode())
    session, client = client_for(results, shuffle=3)
    try:
        position = next(p.position for p in session.queue() if p.student_id == "bo")
        page = get(client, f"/{TOKEN}/review/{position}").get_data(as_text=True)
        changes = re.search(r'data-base="([^"]+)"', page)[1]
        figure = re.search(r'<img src="([^"]+)"', page.split('id="figures"')[1])[1]
        with Gradebook(results) as batch:   # another process grades a new student meanwhile
            entries = [Entry(s, s.title(), "canvas", f"{s}.py", files={"lab07_transformations.py": b"x"})
                       for s in ("ada", "ai", "bo", "cy")]
            batch.sync_students(entries, {e.student_id: f"key-{e.student_id}" for e in entries})
            batch.record("key-ai", "ai", entries[1].content_hash, "lab07.ex1", result(3.0), lock="l")
        assert next(p.position for p in session.queue() if p.student_id == "bo") != position, "the queue moved"
        post(client, changes + "/mark", {"csrf": CSRF, "item": "corners", "applied": "1"})
        post(client, changes + "/note", {"csrf": CSRF, "comment": "for bo", "done": "1"})
        reviews = Gradebook(results, readonly=True).reviews()
        assert set(reviews) == {("bo", "lab07.ex1")} and reviews[("bo", "lab07.ex1")]["comment"] == "for bo"
        assert get(client, figure).data == b"\x89PNG bo", "bo's figure, not the new student's"
        queue = session.queue()
        now = next(p.position for p in queue if p.student_id == "bo")
        step = get(client, f"{changes}/step/next")
        assert step.status_code == 303
        assert step.headers["Location"].endswith(f"/review/{now + 1}" if now + 1 < len(queue) else f"/{TOKEN}/")
    finally:
        session.close()


def test_anonymous_mode_hides_names_with_stable_pseudonyms_and_the_shuffle_is_seeded(results):
    session, client = client_for(results, anonymous=True, shuffle=7)
    try:
        queue = get(client, f"/{TOKEN}/").get_data(as_text=True)
        page = get(client, f"/{TOKEN}/review/0").get_data(as_text=True)
        for name in ("Ada", "Bo", "Cy", "ada lovelace", "lab07_report.md"):
            assert name not in queue and name not in page, name
        names = re.findall(r"Student [0-9A-F]{6}", queue)
        order = [p.student_id for p in session.queue()]
    finally:
        session.close()
    assert len(set(names)) == 3
    again = ReviewSession(results, anonymous=True, shuffle=7)
    try:
        assert [p.student_id for p in again.queue()] == order, "the same seed, the same order"
        assert [p.shown_name for p in again.queue()] == [again.pseudonym(s) for s in order]
        assert {p.shown_name for p in again.queue()} == set(names), "pseudonyms stable across runs"
    finally:
        again.close()
    orders = set()
    for seed in range(6):
        shuffled = ReviewSession(results, shuffle=seed)
        orders.add(tuple(p.student_id for p in shuffled.queue()))
        shuffled.close()
    assert len(orders) > 1, "the seed changes the order"


def test_anonymous_mode_shows_no_name_in_the_reports_problems_nor_in_the_queues_order(results):
    """File names a student chose (in the problems of their report, the sources of its explanations)
    and their names are not shown; unshuffled, the queue is in pseudonym order, not by name."""
    import json

    with Gradebook(results) as book:
        book.set_meta("review_pseudonym_key", "k1")   # orders the pseudonyms bo, cy, ada
        book.db.execute("UPDATE students SET display_name='Ada Lovelace' WHERE student_id='ada'")
        book.db.execute("UPDATE students SET report_problems=? WHERE student_id='ada'", (json.dumps([
            "Report_ADA_LOVELACE.pdf was not read: it is not a PDF (it does not begin with %PDF-)",
            "lovelace-notes/lab07_report.md: the explanation of lab07.ex1 has no '<!-- end explanation -->'; "
            "it was read up to the next section",
            "lab07.ex1 is explained twice (lovelace-notes/lab07_report.md; ada.ipynb, cell 3); both texts are kept, "
            "one after the other",
            "a sentence no template knows, naming ada-100.zip"]),))
        book.db.execute("UPDATE explanations SET source='lovelace-notes/lab07_report.md; ada.ipynb, cell 3' "
                        "WHERE student_id='ada'")
    session, client = client_for(results, anonymous=True)
    try:
        assert [p.student_id for p in session.queue()] == ["bo", "cy", "ada"]
        position = next(p.position for p in session.queue() if p.student_id == "ada")
        page = get(client, f"/{TOKEN}/review/{position}").get_data(as_text=True)
        shown = page.split('id="files"')[1]
        for name in ("ada", "Ada", "ADA", "Lovelace", "LOVELACE", "lovelace"):
            assert not re.search(rf"(?<![A-Za-z]){name}(?![A-Za-z])", page), name
        problems = re.findall(r'<p class="muted problem">Report: ([^<]*)</p>', shown)
        assert problems == [   # the files as neutral labels, numbered after the kept ones, the same name the same
            "report 2 (PDF) was not read: it is not a PDF (it does not begin with %PDF-)",
            "report 3 (Markdown): the explanation of lab07.ex1 has no &#39;&lt;!-- end explanation --&gt;&#39;; "
            "it was read up to the next section",
            "lab07.ex1 is explained twice (report 3 (Markdown); report 4 (notebook), cell 3); both texts are kept, "
            "one after the other",
            "a problem was found reading the report (its sentence names files: run without --anonymous to read it)"]
        assert ">report 1 (PDF)</a>" in shown and "from report 3 (Markdown); report 4 (notebook), cell 3" in page
        assert "100.zip" not in page
    finally:
        session.close()
    session, client = client_for(results)
    try:   # not anonymous: everything as it is
        page = get(client, f"/{TOKEN}/review/0").get_data(as_text=True)
        assert "Report_ADA_LOVELACE.pdf" in page and "lovelace-notes/lab07_report.md" in page
    finally:
        session.close()


def test_the_server_listens_on_127_0_0_1_only_and_prints_its_token(results):
    announced = []
    ready = threading.Event()

    def announce(url):
        announced.append(url)
        ready.set()

    thread = threading.Thread(target=serve, args=(results,), kwargs={"announce": announce}, daemon=True)
    thread.start()
    assert ready.wait(30)
    url = announced[0]
    match = re.fullmatch(r"http://127\.0\.0\.1:(\d+)/([A-Za-z0-9_-]{20,})/", url)
    assert match, url
    port = int(match[1])
    logged = []

    class Collect(logging.Handler):
        def emit(self, record):
            logged.append(record.getMessage())

    collect = Collect()
    logging.getLogger("werkzeug").addHandler(collect)
    try:
        assert urllib.request.urlopen(url, timeout=10).status == 200
    finally:
        logging.getLogger("werkzeug").removeHandler(collect)
    assert logged and not any(match[2] in line for line in logged), logged   # the log shows <token>
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=10)
    assert refused.value.code == 403
    addresses = {info[4][0] for info in socket.getaddrinfo(socket.gethostname(), None, socket.AF_INET)} - {"127.0.0.1"}
    for address in addresses:   # another interface of this machine: nothing listens there
        with pytest.raises(OSError):
            socket.create_connection((address, port), timeout=2).close()
    import psutil

    listening = [c.laddr for c in psutil.net_connections("tcp") if c.laddr and c.laddr.port == port
                 and c.status == psutil.CONN_LISTEN]
    assert listening and all(addr.ip == "127.0.0.1" for addr in listening)
