"""Issue 37: a review screen for 300 reports (Flask's test client; the layout itself is
checked in a real browser by tests/test_review_browser.py).

Reusable comments per exercise (saved once, inserted by key, edited centrally; a comment
already saved on a student stays as written), the queue saying who handed in a report and
filtering, each diagnosis shown once, and no inline script on any page.
"""

from __future__ import annotations

import html
import re

import pytest

pytest.importorskip("flask")

from autograder.instructor.batch.gradebook import Gradebook  # noqa: E402
from autograder.instructor.review.app import ReviewSession, create_app  # noqa: E402
from test_review_app import CSRF, TOKEN, base, get, post, results  # noqa: E402,F401  (the fixture)
from test_review_storage import result  # noqa: E402


def client_for(folder):
    session = ReviewSession(folder, reviewer="prof")
    return session, create_app(session, token=TOKEN, csrf=CSRF).test_client()


def saved_buttons(page: str) -> list[tuple[str, str]]:
    """The review screen's saved comments: (key, the text an insertion puts in)."""
    return [(html.unescape(key).strip(), html.unescape(text)) for text, key in
            re.findall(r'<button type="button" class="saved" data-text="([^"]*)"[^>]*>(?:<kbd>v</kbd><kbd>\d</kbd> )?([^<]*)</button>',
                       page)]


def test_reusable_comments_are_saved_once_inserted_by_key_and_edited_centrally(results):
    session, client = client_for(results)
    bank = f"/{TOKEN}/bank/lab07.ex1"
    try:
        assert saved_buttons(get(client, f"/{TOKEN}/review/0").get_data(as_text=True)) == []
        assert post(client, bank, {"key": "corners", "text": "Why black?"}).status_code == 403, "CSRF needed"
        answer = post(client, bank, {"csrf": CSRF, "key": "corners", "text": "Why are the corners black?", "back": "1"})
        # back to the screen it was saved from, the focus on its new button (see review.js)
        assert answer.status_code == 303 and answer.headers["Location"].endswith(f"/{TOKEN}/review/1#saved-corners")
        post(client, bank, {"csrf": CSRF, "key": "axes", "text": "Label the <b>axes</b>."})
        for position in (0, 1, 2):   # every student's screen of that exercise offers them
            page = get(client, f"/{TOKEN}/review/{position}").get_data(as_text=True)
            assert saved_buttons(page) == [("axes", "Label the <b>axes</b>."), ("corners", "Why are the corners black?")]
            assert "<b>axes</b>" not in page, "a saved comment is text, never markup"
        # The screen inserts the text into bo's comment, which is saved as written ...
        post(client, base(client, 1) + "/note", {"csrf": CSRF, "comment": "Why are the corners black?"})
        # ... and editing the saved comment changes later insertions, not bo's comment.
        post(client, bank, {"csrf": CSRF, "key": "corners", "text": "Explain the black corners."})
        page = get(client, f"/{TOKEN}/review/1").get_data(as_text=True)
        assert ("corners", "Explain the black corners.") in saved_buttons(page)
        with Gradebook(results, readonly=True) as other:
            assert other.reviews()[("bo", "lab07.ex1")]["comment"] == "Why are the corners black?"
            assert {c["key"]: c["changed_by"] for c in other.comment_bank()["lab07.ex1"]} == {"axes": "prof", "corners": "prof"}
        rubric = get(client, f"/{TOKEN}/rubric").get_data(as_text=True)
        assert 'id="bank-lab07.ex1"' in rubric and "Explain the black corners." in rubric
        # refused: a malformed key (the error is the refusal's own), an exercise with no rubric
        bad = post(client, bank, {"csrf": CSRF, "key": "no spaces", "text": "x"})
        assert bad.status_code == 400 and "a comment&#39;s key is" in bad.get_data(as_text=True)
        assert post(client, f"/{TOKEN}/bank/lab99.ex1", {"csrf": CSRF, "key": "a", "text": "t"}).status_code == 404
        post(client, bank, {"csrf": CSRF, "key": "axes", "text": "  "})   # an empty text deletes it
        assert [key for key, _ in saved_buttons(get(client, f"/{TOKEN}/review/0").get_data(as_text=True))] == ["corners"]
    finally:
        session.close()


def queue_names(page: str) -> list[str]:
    return re.findall(r'<td class="name"><a href="[^"]+">([^<]+)</a>', page)


def test_the_queue_says_who_handed_in_a_report_and_filters(results):
    """ada explained lab07.ex1 (fixture); bo and cy handed in nothing."""
    session, client = client_for(results)
    try:
        queue = get(client, f"/{TOKEN}/").get_data(as_text=True)
        assert queue_names(queue) == ["Ada", "Bo", "Cy"]
        rows = {name: row for name, row in zip(queue_names(queue), queue.split("<tr data-position")[1:])}
        assert "handed in" in rows["Ada"] and "no report" in rows["Bo"] and "no report" in rows["Cy"]
        assert queue_names(get(client, f"/{TOKEN}/?show=noreport").get_data(as_text=True)) == ["Bo", "Cy"]
        post(client, base(client, 1) + "/note", {"csrf": CSRF, "done": "1"})
        todo = get(client, f"/{TOKEN}/?show=todo").get_data(as_text=True)
        assert queue_names(todo) == ["Ada", "Cy"] and "1 of 3 reviewed" in todo
        assert re.search(r'<a href="/[^"]+/\?show=noreport" data-key="r">', todo), "each filter has its key"
        assert queue_names(get(client, f"/{TOKEN}/?show=nonsense").get_data(as_text=True)) == ["Ada", "Bo", "Cy"]
        # a position stays the queue's own: Cy is still review/2 in the filtered list
        assert f'href="/{TOKEN}/review/2">Cy<' in todo
    finally:
        session.close()


def test_each_diagnosis_is_shown_once(tmp_path):
    from test_review_storage import graded_book

    with graded_book(tmp_path, ("ada",), (0.0,)) as book:
        named = result(0.0)
        named["exercises"][0]["checks"][0].update(
            message="translate() is wrong: it looks like tx and ty swapped.", mistake="tx and ty swapped")
        book.record("key-ada", "ada", "hash", "lab07.ex1", named, lock="l")
    session, client = client_for(tmp_path)
    try:
        page = get(client, f"/{TOKEN}/review/0").get_data(as_text=True)
        assert page.count("tx and ty swapped") == 1
    finally:
        session.close()


def test_no_page_has_an_inline_script_and_the_scripts_are_served_under_the_token(results):
    session, client = client_for(results)
    try:
        for path in ("/", "/review/0", "/rubric", "/?show=todo"):
            answer = get(client, f"/{TOKEN}{path}")
            page = answer.get_data(as_text=True)
            assert "script-src 'self'" in answer.headers["Content-Security-Policy"]
            assert "unsafe-inline" not in answer.headers["Content-Security-Policy"].split("script-src")[1].split(";")[0]
            scripts = re.findall(r"<script([^>]*)>(.*?)</script>", page, re.DOTALL)
            assert all(re.fullmatch(rf' src="/{TOKEN}/static/\w+\.js"', attrs) and not body.strip()
                       for attrs, body in scripts), scripts
        script = get(client, f"/{TOKEN}/static/review.js")
        assert script.status_code == 200 and "data" in script.get_data(as_text=True)
        assert get(client, "/static/review.js").status_code == 403, "the scripts need the token too"
    finally:
        session.close()
