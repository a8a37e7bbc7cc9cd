"""The review application: Flask over the batch's gradebook, one reviewer's local server.

Security
--------
- Bound to ``127.0.0.1`` only; every address lives under a per-run random token
  (``http://127.0.0.1:PORT/<token>/``, printed at start): any request without it,
  or with a ``Host`` other than 127.0.0.1/localhost (DNS rebinding), is answered 403.
- Every POST carries a second per-run secret in its form (``csrf``) and, when the
  browser sends an ``Origin``, it must be this server's; else 403.
- Pages forbid scripts but their own files (``static/``: no inline script runs), frames, remote
  images and any referrer leaving the application (``Content-Security-Policy``,
  ``Referrer-Policy: same-origin``), so a student's report can neither run code nor leak the
  token. Within it the browser sends its real ``Origin`` (under ``no-referrer`` a form's POST
  says ``Origin: null``, refused above: no form of the application could be sent).
- The student's text is rendered by :func:`autograder.reports.markdown.render_markdown`
  (a link into this application is inert text); no page shows text taken from its
  address (the rubric's error is the refused change's own); a PDF is offered as a
  download, never shown or parsed here (its text was read in a sandbox worker by the
  batch); figures are only the PNGs the batch made from the student's code
  (``RESULTS/<student>/figures/``); the report's own pictures are only compared with them
  as the worker's thumbnails (:mod:`.provenance`), never decoded here.
- Anonymous mode shows nothing of a student but their pseudonym (:mod:`.anonymity`).

Storage
-------
Every change (an item applied or taken back, a comment, "reviewed", an item's text
or points) is one transaction of the gradebook (WAL, ``synchronous=FULL``, a busy
timeout), at once: two tabs see each other's changes on reload, a batch may grade
meanwhile, and a server killed at any moment loses nothing that was answered.
"""

from __future__ import annotations

import hashlib
import hmac
import logging
import random
import re
import secrets
import threading
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import urlsplit

from ...reports.markdown import render_markdown
from ..batch.exports import report_maxima
from ..batch.gradebook import Gradebook
from ..batch.run import batch_course, class_grades
from ..classreport.pages import rules_applied
from ..course import CourseConfigError
from .anonymity import Anonymiser
from .provenance import for_exercise

FIGURE_ID = re.compile(r"lab\d\d\.[A-Za-z0-9_.-]{1,60}")
LOCAL_HOSTS = ("127.0.0.1", "localhost")
# The queue's filters (``?show=``): every pair, those not reviewed yet, those with no report text;
# each with its key on the queue.
QUEUE_FILTERS = {"all": ("all", "a"), "todo": ("not reviewed", "t"), "noreport": ("no report", "r")}


@dataclass(frozen=True)
class Pair:
    """One (student, exercise) to review, as the queue orders them."""

    position: int
    student_id: str
    exercise: str
    shown_name: str   # the student's name, or their pseudonym in anonymous mode
    ref: str          # the student in addresses: stable, and no name (see ReviewSession.ref)


class ReviewSession:
    """The gradebook and what a run of the review application fixes: the reviewer's name, the
    queue's order, the names shown. One connection, used by one thread at a time."""

    def __init__(self, results, reviewer: str = "reviewer", anonymous: bool = False,
                 shuffle: int | None = None):
        self.results = Path(results)
        self.reviewer, self.anonymous, self.shuffle = reviewer, anonymous, shuffle
        self.lock = threading.Lock()
        self.book = Gradebook(self.results, threads=True)   # migrates an older gradebook
        with self.lock:
            self.course = batch_course(self.book)
            self.book.sync_rubric(self.course.rubric)
            secret = self.book.get_meta("review_pseudonym_key")
            if secret is None:   # stable pseudonyms across runs, unguessable from the ids
                secret = secrets.token_hex(16)
                self.book.set_meta("review_pseudonym_key", secret)
        self._pseudonym_key = secret.encode()

    def close(self) -> None:
        self.book.close()

    def pseudonym(self, student_id: str) -> str:
        return "Student " + self.ref(student_id)[:6].upper()

    def ref(self, student_id: str) -> str:
        """The student in the application's addresses. A queue's positions move when a batch
        grades a student meanwhile, so whatever changes or shows one student's review (a mark,
        a note, a figure, a PDF) names the student by this, never by a position."""
        return hmac.new(self._pseudonym_key, student_id.encode(), hashlib.sha256).hexdigest()[:20]

    def queue(self) -> list[Pair]:
        """Every graded student's exercise that has a rubric: by student and exercise, or
        shuffled by the seed (the same seed, the same order); in anonymous mode, unshuffled, by
        pseudonym (the students' order would tell their names)."""
        with self.lock:
            rubric = self.book.rubric()
            students = [s for s in self.book.class_results() if s["status"] == "graded"]
        exercises = [e for e in sorted(rubric) if e in _selected(self.course)]
        if self.anonymous:
            students.sort(key=lambda s: self.ref(s["student_id"]))
        pairs = [(s["student_id"], e, self.pseudonym(s["student_id"]) if self.anonymous else s["display_name"],
                  self.ref(s["student_id"])) for s in students for e in exercises]
        if self.shuffle is not None:
            random.Random(self.shuffle).shuffle(pairs)
        return [Pair(i, *p) for i, p in enumerate(pairs)]


def _selected(course) -> set[str]:
    from ...engine.registry import select

    return {e.id for e in select(course.select)}


def create_app(session: ReviewSession, token: str | None = None, csrf: str | None = None):
    """The Flask application over ``session``; ``token`` (the URL's secret) and ``csrf`` (the
    forms') are random unless given (tests)."""
    from flask import Flask, Response, abort, jsonify, redirect, render_template, request, url_for

    token, csrf = token or secrets.token_urlsafe(24), csrf or secrets.token_urlsafe(24)
    # The pages' scripts are files (no inline script may run); served under the token like everything else.
    app = Flask(__name__, template_folder=str(Path(__file__).parent / "templates"),
                static_folder=str(Path(__file__).parent / "static"), static_url_path=f"/{token}/static")
    app.config.update(TOKEN=token, CSRF=csrf, MAX_CONTENT_LENGTH=256 * 1024)

    @app.before_request
    def guard():
        host = (request.host or "").rsplit(":", 1)[0].strip("[]")
        parts = request.path.split("/", 2)
        if host not in LOCAL_HOSTS or len(parts) < 2 or not hmac.compare_digest(parts[1].encode(), token.encode()):
            abort(403)
        if request.method not in ("GET", "HEAD"):
            origin = request.headers.get("Origin")
            if origin and urlsplit(origin).netloc != request.host:
                abort(403)
            if not hmac.compare_digest(request.form.get("csrf", "").encode(), csrf.encode()):
                abort(403)

    @app.after_request
    def headers(response):
        response.headers["Content-Security-Policy"] = (
            "default-src 'none'; script-src 'self'; style-src 'unsafe-inline'; "
            "img-src 'self'; connect-src 'self'; form-action 'self'; base-uri 'none'; frame-ancestors 'none'")
        response.headers["Referrer-Policy"] = "same-origin"   # see the module docstring
        response.headers["X-Content-Type-Options"] = "nosniff"
        response.headers["Cache-Control"] = "no-store"
        return response

    def pair_at(position: int) -> tuple[Pair, list[Pair]]:
        queue = session.queue()
        if not 0 <= position < len(queue):
            abort(404)
        return queue[position], queue

    def pair_of(ref: str, exercise: str) -> tuple[Pair, list[Pair]]:
        """The pair a page was made for, wherever the queue has it now (404: no longer in it)."""
        queue = session.queue()
        pair = next((p for p in queue if p.ref == ref and p.exercise == exercise), None)
        if pair is None:
            abort(404)
        return pair, queue

    def state(pair: Pair) -> dict:
        """The review of ``pair`` now, and its points."""
        with session.lock:
            review = session.book.reviews().get((pair.student_id, pair.exercise), {})
            items = session.book.rubric().get(pair.exercise, [])
        return {"applied": review.get("items", []), "points": review.get("points", 0.0),
                "comment": review.get("comment", ""), "done": review.get("done", False),
                "changed_by": review.get("changed_by", ""), "changed_at": review.get("changed_at", ""),
                "maximum": report_maxima({pair.exercise: items}, [(pair.exercise, 0)]).get(pair.exercise, 0.0)}

    def page(template: str, **context):
        return render_template(template, token=token, csrf=csrf, reviewer=session.reviewer,
                               anonymous=session.anonymous, **context)

    @app.get(f"/{token}/")
    def queue_page():
        """The queue; ``?show=todo`` keeps the pairs not reviewed, ``?show=noreport`` those whose
        student explained nothing of that exercise (a position stays the queue's own)."""
        show = request.args.get("show", "all")
        show = show if show in QUEUE_FILTERS else "all"
        queue = session.queue()
        with session.lock:
            reviews = session.book.reviews()
            handed_in = session.book.reports_handed_in()
        rows = [(p, reviews.get((p.student_id, p.exercise), {}), _report_state(handed_in.get(p.student_id), p.exercise))
                for p in queue]
        done = sum(1 for _, r, _ in rows if r.get("done"))
        shown = [row for row in rows if show == "all" or (show == "todo" and not row[1].get("done"))
                 or (show == "noreport" and row[2] != "explained")]
        return page("queue.html", rows=shown, total=len(rows), done=done, show=show, filters=QUEUE_FILTERS)

    @app.get(f"/{token}/review/<int:position>")
    def review_page(position: int):
        pair, queue = pair_at(position)
        with session.lock:
            report = session.book.report(pair.student_id)
            rubric = session.book.rubric().get(pair.exercise, [])
            students = {s["student_id"]: s for s in session.book.class_results()}
            report_figures = session.book.report_figures(pair.student_id)
        explanation = report["explanations"].get(pair.exercise)
        figures = _figures(session.results, pair.student_id, pair.exercise)

        def figure_url(name: str):
            return url_for("figure", ref=pair.ref, exercise=pair.exercise, figure_id=name) if name in figures else None

        student = students.get(pair.student_id) or {}
        verdict = next((e for e in (student.get("result") or {}).get("exercises", []) if e["id"] == pair.exercise),
                       None)
        text, source = (explanation["text"], explanation["source"]) if explanation else ("", "")
        attachments = [(i, path, size) for i, (path, size) in enumerate(_pdfs(report["files"]))]
        problems = report["problems"]
        if session.anonymous:   # no file name a student chose, no name of theirs (see .anonymity)
            hide = Anonymiser(student, report["files"], pair.shown_name)
            problems = [hide.problem(p) for p in problems]   # first: the files refused get labels too
            source = hide.sources(source) if source else ""
            text = hide.text(text)
            attachments = [(i, hide.label(path), size) for i, path, size in attachments]
            report_figures = [{**f, "source": _labelled(hide, f["source"])} for f in report_figures]
            if verdict:
                verdict = {**verdict, "checks": [{**c, "message": hide.text(c.get("message") or "")}
                                                 for c in verdict.get("checks", [])]}
        rendered = render_markdown(text, figure_url) if explanation else None
        # The report's figures against every figure the student's code made (see .provenance).
        provenance = for_exercise(report_figures, _figures(session.results, pair.student_id), pair.exercise)
        with session.lock:
            bank = session.book.comment_bank().get(pair.exercise, [])
            rules = _rules_of(session, pair.student_id)
        return page("review.html", pair=pair, queue_length=len(queue), explanation=explanation, source=source,
                    rendered=rendered, figures=figures, verdict=verdict, rubric=rubric, review=state(pair),
                    attachments=attachments, problems=problems, bank=bank, provenance=provenance, rules=rules)

    @app.get(f"/{token}/pair/<ref>/<exercise>/step/<any('next','previous'):step>")
    def step(ref: str, exercise: str, step: str):
        """The next or previous review from where this pair is now (the queue may have moved)."""
        pair, queue = pair_of(ref, exercise)
        position = pair.position + (1 if step == "next" else -1)
        if 0 <= position < len(queue):
            return redirect(url_for("review_page", position=position), code=303)
        return redirect(url_for("queue_page"), code=303)

    @app.post(f"/{token}/pair/<ref>/<exercise>/mark")
    def mark(ref: str, exercise: str):
        pair, _ = pair_of(ref, exercise)
        item, applied = request.form.get("item", ""), request.form.get("applied") == "1"
        with session.lock:
            try:
                session.book.set_mark(pair.student_id, pair.exercise, item, applied, session.reviewer)
            except KeyError:
                abort(400)
        return answer(pair)

    @app.post(f"/{token}/pair/<ref>/<exercise>/note")
    def note(ref: str, exercise: str):
        pair, _ = pair_of(ref, exercise)
        comment = request.form.get("comment")
        done = {"1": True, "0": False}.get(request.form.get("done", ""))
        with session.lock:
            session.book.set_review_note(pair.student_id, pair.exercise, session.reviewer, comment=comment, done=done)
        return answer(pair)

    def answer(pair: Pair):
        if request.headers.get("Accept", "").startswith("application/json"):
            return jsonify(state(pair))
        return redirect(url_for("review_page", position=pair.position), code=303)

    @app.get(f"/{token}/rubric")
    def rubric_page(error: str = ""):
        """The rubric, and ``error`` from a change just refused: the error panel never shows text
        from the address (a student's relative link could put their words there)."""
        with session.lock:
            rubric = session.book.rubric()
            bank = session.book.comment_bank()
        return page("rubric.html", rubric=rubric, bank=bank, error=error), 400 if error else 200

    @app.post(f"/{token}/rubric/<exercise>")
    def rubric_item(exercise: str):
        with session.lock:
            known = session.book.rubric()
        if exercise not in known:
            abort(404)
        try:
            points = float(request.form.get("points", ""))
        except ValueError:
            points = None
        try:
            with session.lock:
                session.book.set_rubric_item(exercise, request.form.get("item", "").strip(),
                                             request.form.get("text", "").strip(), points, session.reviewer)
        except CourseConfigError as exc:
            return rubric_page(error=str(exc))
        back = request.form.get("back", "")
        if re.fullmatch(r"[0-9]{1,9}", back):
            return redirect(url_for("review_page", position=int(back)), code=303)
        # the rubric page, its focus on the item just saved (static/rubric.js)
        return redirect(url_for("rubric_page") + f"#item-{exercise}-{request.form['item'].strip()}", code=303)

    @app.post(f"/{token}/bank/<exercise>")
    def bank_comment(exercise: str):
        """Save, change (for every later insertion) or delete (empty text) a reusable comment."""
        with session.lock:
            known = session.book.rubric()
        if exercise not in known:
            abort(404)
        try:
            with session.lock:
                session.book.set_bank_comment(exercise, request.form.get("key", "").strip(),
                                              request.form.get("text", ""), session.reviewer)
        except ValueError as exc:
            return rubric_page(error=str(exc))
        back = request.form.get("back", "")
        if re.fullmatch(r"[0-9]{1,9}", back):   # the review screen, its focus on the comment just saved
            return redirect(url_for("review_page", position=int(back)) + f"#saved-{request.form['key'].strip()}",
                            code=303)
        return redirect(url_for("rubric_page") + f"#bank-{exercise}-{request.form['key'].strip()}", code=303)

    @app.get(f"/{token}/figure/<ref>/<exercise>/<figure_id>.png")
    def figure(ref: str, exercise: str, figure_id: str):
        pair, _ = pair_of(ref, exercise)
        path = _figures(session.results, pair.student_id, pair.exercise).get(figure_id)
        if path is None:
            abort(404)
        return Response(path.read_bytes(), mimetype="image/png")

    @app.get(f"/{token}/attachment/<ref>/<exercise>/<int:number>")
    def attachment(ref: str, exercise: str, number: int):
        pair, _ = pair_of(ref, exercise)
        with session.lock:
            paths = [path for path, _ in _pdfs(session.book.report(pair.student_id)["files"])]
            if not 0 <= number < len(paths):
                abort(404)
            data = session.book.report_file(pair.student_id, paths[number])
        name = f"{pair.shown_name if session.anonymous else pair.student_id}-{number + 1}.pdf"
        return Response(data, mimetype="application/pdf", headers={
            "Content-Disposition": f'attachment; filename="{re.sub(r"[^A-Za-z0-9._-]", "_", name)}"'})

    app.jinja_env.filters["num"] = lambda v: "" if v is None else f"{round(float(v), 4):g}"
    return app


def _rules_of(session: ReviewSession, student_id: str) -> list[str]:
    """What the course's rules did to the student's grade (excused, an extension, days late), as the
    class overview says it: from the one final-grade computation, over the whole class (an extension
    names a student by any identity, which only the class makes unambiguous)."""
    try:
        grades = class_grades(session.book, session.course).grades
    except ValueError as exc:   # a damaged late-day ledger: said on the screen, not a failed page
        return [str(exc)]
    return next((rules_applied(g) for g in grades if g.student.get("student_id") == student_id), [])


def _report_state(handed_in: dict | None, exercise: str) -> str:
    """``"explained"``, ``"not this exercise"`` (a report without its text) or ``"none"``."""
    if not handed_in:
        return "none"
    return "explained" if exercise in handed_in["explained"] else "not this exercise"


def _pdfs(files: dict[str, int]) -> list[tuple[str, int]]:
    """The PDFs of a report's files (path -> size), in order: an attachment's number on the
    review screen and in its download address is its place in this list."""
    return [(path, size) for path, size in files.items() if path.lower().endswith(".pdf")]


def _labelled(hide: Anonymiser, source: str) -> str:
    """A report figure's source (``report.pdf, page 3``; ``report.md, figures/a.png``) with the
    file's label, and the rest as free text (a picture's own name may hold the student's)."""
    name, comma, where = source.partition(", ")
    return hide.label(name) + comma + hide.text(where)


def _figures(results: Path, student_id: str, exercise: str | None = None) -> dict[str, Path]:
    """The PNGs the batch made from the student's code for ``exercise`` (and its extension's;
    None: every exercise's): figure id -> file, only regular files named as the grader names them."""
    folder = results / student_id / "figures"
    if not folder.is_dir() or folder.is_symlink():
        return {}
    found = {}
    for path in sorted(folder.glob("*.png")):
        figure_id = path.name[:-4]
        if FIGURE_ID.fullmatch(figure_id) and path.is_file() and not path.is_symlink() and (
                exercise is None or figure_id == exercise or figure_id.startswith(exercise + "-")):
            found[figure_id] = path
    return found


class _WithoutToken(logging.Filter):
    """Werkzeug logs each request's path, which begins with the token: the log (a terminal, a
    file it is redirected to, a screen shared in a lecture) shows ``<token>`` instead."""

    def __init__(self, token: str):
        super().__init__()
        self.token = token

    def filter(self, record: logging.LogRecord) -> bool:
        if record.args:
            record.args = tuple(arg.replace(self.token, "<token>") if isinstance(arg, str) else arg
                                for arg in (record.args if isinstance(record.args, tuple) else (record.args,)))
        record.msg = str(record.msg).replace(self.token, "<token>")
        return True


def _hide_in_the_log(token: str) -> None:
    log = logging.getLogger("werkzeug")
    log.filters = [f for f in log.filters if not isinstance(f, _WithoutToken)]
    log.addFilter(_WithoutToken(token))


def serve(results, port: int = 0, reviewer: str = "reviewer", anonymous: bool = False,
          shuffle: int | None = None, announce=print) -> None:
    """Serve the review of ``results`` on 127.0.0.1:``port`` (0: a free one) until interrupted;
    ``announce(url)`` is told the address with its token."""
    from werkzeug.serving import make_server

    session = ReviewSession(results, reviewer, anonymous, shuffle)
    try:
        app = create_app(session)
        server = make_server("127.0.0.1", port, app, threaded=True)
        _hide_in_the_log(app.config["TOKEN"])
        announce(f"http://127.0.0.1:{server.server_port}/{app.config['TOKEN']}/")
        try:
            server.serve_forever()
        except KeyboardInterrupt:
            pass
        finally:
            server.server_close()
    finally:
        session.close()
