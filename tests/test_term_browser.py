"""An instructor's term in a real browser, by keyboard only (headless Chromium, DevTools protocol).

A class of 30 (Canvas layout) is batch-graded; most students share one of three submissions
(the reference, a translation that moves the wrong way, the skeleton), so each distinct
submission is graded once and its grading copied to the students who handed in the same
files (:func:`grading_each_distinct_submission_once`; the regrade's new file is the
reference, whose grading is reused): the batch's own code does everything else (reading the
download, the gradebook, final grades, changes, pages, the overview).

Then, with keys only (Tab, Shift+Tab, Enter, Space, the app's shortcuts; never a click):
the review queue is walked and filtered (not reviewed, no report); a student is opened,
a rubric item scored, a comment saved for reuse under a key and applied to the next student
by its key, the review saved; the next student and back: everything kept; an item's points
changed on the rubric page. A regrade after
one student handed in a new file lists, in the class overview, exactly the grades that
moved (old -> new and why); an extension and an excused student show theirs. Every page
visited is walked with Tab: every control is reached, shows a focus indicator, and Tab
leaves none of them trapped.

Screenshots at 1280x900 are written to ``$TERM_SCREENSHOTS`` when it is set (for a person).
A PDF report's review is not part of this journey (see the PDF report path's own tests).
"""

from __future__ import annotations

import base64
import json
import re
import os
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

from browser import find_chromium

pytest.importorskip("flask")
pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(find_chromium() is None,
                                 reason="Chromium is not installed (apt-get install chromium, or set CHROMIUM)")]

from test_batch import MODULE, WRONG_WAY, reference, skeleton, write   # noqa: E402
from test_review_browser import Server, Tab, browser   # noqa: E402,F401 (browser: the fixture)

WIDTH, HEIGHT = 1280, 900
# The class: Canvas names (surname + first name), each a user id; three distinct submissions.
NAMES = ["lovelaceada", "turingalan", "hopperg", "knuthdon", "liskovbarbara", "dijkstraedsger", "hamiltonmargaret",
         "ritchiedennis", "allenfran", "backusjohn", "kaysalan", "perlmanradia", "goldbergadele", "wingjeannette",
         "goldwassershafi", "micalisilvio", "thompsonken", "lamportleslie", "milnerrobin", "hoaretony",
         "cerfvint", "kahnbob", "berners-leetim", "engelbartdoug", "sutherlandivan", "shawmary", "joneskaren",
         "clarkewes", "stonebrakermike", "codded"]
REFERENCE, WRONG, SKELETON = "reference", "wrong way", "skeleton"
EXPLAINED = ("## Exercise 1: Translation\n\nThe image moves right by tx and down by ty; the corners it leaves "
             "behind are black because nothing maps there.\n")
RUBRIC = {"lab07.ex1": [{"id": "corners", "text": "explains the black corners", "points": 3},
                        {"id": "axes", "text": "says which way each axis moves", "points": 1},
                        {"id": "no-figure", "text": "no figure", "points": -1}]}
DUE = "2026-03-01T23:59:00+00:00"
LATE = (3, 4, 6)   # handed in a day late (Canvas's _LATE_)


def kind_of(i: int) -> str:
    return (REFERENCE, WRONG, SKELETON)[i % 3]


def student_id(i: int) -> str:
    return f"{NAMES[i]}-{1000 + i}"


# ------------------------------------------------------------------ the class, graded once per distinct submission
def grading_each_distinct_submission_once(grade_locally, graded: dict):
    """``run._grade_locally`` grading one submission of each distinct set of files (under the same
    grading arguments), its outcome given to every student who handed in the same files, their own
    id in it. ``graded`` keeps the outcomes from one batch to the next: files graded once, in any
    run, are not graded again."""
    def grade(todo, arguments, finished, workers, rules=None, running=None):
        groups: dict[tuple, list] = {}
        for entry in todo:
            groups.setdefault((repr(arguments), tuple(sorted(entry.files.items()))), []).append(entry)
        new = {group[0].student_id: files for files, group in groups.items() if files not in graded}
        grade_locally([group[0] for files, group in groups.items() if files not in graded], arguments,
                      lambda entry, outcome: graded.__setitem__(new[entry.student_id], (entry.student_id, outcome)),
                      workers, rules, running)
        for files, group in groups.items():
            first, outcome = graded[files]
            for entry in group:
                finished(entry, _as_of(outcome, first, entry.student_id))
    return grade


def _as_of(outcome: dict, first: str, student: str) -> dict:
    if "result" not in outcome or student == first:
        return outcome
    as_json = json.loads(outcome["json"])
    as_json["submission"] = student
    return {**outcome, "result": {**outcome["result"], "submission": student}, "json": json.dumps(as_json),
            "page": outcome["page"].replace(first, student)}


def download_of(folder: Path, kinds: dict[int, str]) -> None:
    """The Canvas download: student ``i`` hands in ``kinds[i]``; every other one a report that
    explains lab07.ex1 (the odd ones none, the first at length); students 3, 4 and 6 late
    (``_LATE_``: one day)."""
    code = {REFERENCE: reference(), WRONG: reference() + WRONG_WAY, SKELETON: skeleton()}
    for i, kind in kinds.items():
        late = "_LATE" if i in LATE else ""
        prefix = f"{NAMES[i]}{late}_{1000 + i}_{5000 + i}"
        write(folder / f"{prefix}_{MODULE}.py", code[kind])
        if i % 2 == 0:   # the first's is long: the review screen scrolls it in its pane
            write(folder / f"{prefix}_lab07_report.md", EXPLAINED + "\n\nMore on the borders." * 60 * (i == 0))


def term_course():
    from autograder.instructor.course import CourseConfig

    # Three are late by a day: 3 has an extension of two days, 4 is excused, 6 pays the penalty.
    return CourseConfig(select=["lab07.ex1"], assignment="Lab 7", rubric=RUBRIC, hidden_points_visible=True,
                        late_penalty={"due": DUE, "per_day": 25},
                        extensions={student_id(3): {"days": 2}, student_id(4): {"excused": True}})


@dataclass
class Term:
    download: Path
    out: Path
    seconds: float
    graded: dict


@pytest.fixture(scope="session")
def term(tmp_path_factory):
    """The graded class: its download, RESULTS, the batch's wall time and its gradings (by files)."""
    from autograder.instructor.batch import run

    root = tmp_path_factory.mktemp("term")
    download, out = root / "download", root / "out"
    download_of(download, {i: kind_of(i) for i in range(30)})
    started, graded = time.monotonic(), {}
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(run, "_grade_locally", grading_each_distinct_submission_once(run._grade_locally, graded))
        summary = run.run_batch(download, out, course=term_course(), workers=2)
    assert summary.students == 30 and summary.graded == 30 and not summary.failed, summary
    assert len(graded) == 3, "each distinct submission graded once"
    return Term(download, out, time.monotonic() - started, graded)


# ------------------------------------------------------------------ the keyboard
# DevTools key events as a keyboard sends them: the key, its code and virtual key code, and the
# text it types (Enter and Space activate what has the focus; Tab moves it).
KEYS = {"Tab": ("Tab", 9, ""), "Enter": ("Enter", 13, "\r"), " ": ("Space", 32, " "), "Escape": ("Escape", 27, ""),
        "ArrowDown": ("ArrowDown", 40, ""), "ArrowUp": ("ArrowUp", 38, ""), "PageDown": ("PageDown", 34, ""),
        "End": ("End", 35, ""), "Home": ("Home", 36, "")}
SHIFT = 8

# An element in words: its tag, id and label (its aria-label, its <label>, its text, value or address).
DESCRIBE_FUNCTION = r"""(el => el.tagName.toLowerCase() + (el.id ? '#' + el.id : '') + ' '
  + (el.getAttribute('aria-label') || (el.labels && el.labels[0] && el.labels[0].innerText) || el.innerText
     || el.value || el.getAttribute('href') || '').trim().replace(/\s+/g, ' ').slice(0, 50))"""

# What the focused element is, how its focus shows, and whether it is in view; each element
# keeps one number for the page's life (a WeakMap), so a walk can tell where it has been.
FOCUSED = r"""
(() => {
  const el = document.activeElement;
  if (!el || el === document.body || el === document.documentElement) return null;
  window.__ids = window.__ids || new WeakMap();
  if (!window.__ids.has(el)) window.__ids.set(el, window.__n = (window.__n || 0) + 1);
  const s = getComputedStyle(el), r = el.getBoundingClientRect();
  const outline = s.outlineStyle !== 'none' && parseFloat(s.outlineWidth) > 0 && s.outlineColor !== 'rgba(0, 0, 0, 0)';
  return {id: window.__ids.get(el), what: (DESCRIBE)(el),
          visible: el.matches(':focus-visible'),
          indicator: outline ? `outline ${s.outlineStyle} ${s.outlineWidth} ${s.outlineColor}`
                     : (s.boxShadow !== 'none' ? 'box-shadow ' + s.boxShadow : ''),
          inView: r.width > 0 && r.height > 0 && r.bottom > 0 && r.top < innerHeight
                  && r.right > 0 && r.left < innerWidth};
})()
""".replace("DESCRIBE", DESCRIBE_FUNCTION)

# Every control a keyboard user must reach: links, buttons, fields, summaries, focusable
# elements, rendered (not inside a closed <details> but its summary, not display: none).
CONTROLS = r"""
(() => {
  const all = [...document.querySelectorAll('a[href], button, input:not([type=hidden]), textarea, select, summary, '
                                            + '[tabindex]:not([tabindex="-1"])')];
  const missed = all.filter(el => !el.disabled && el.getClientRects().length > 0
                                  && !(el.closest('details:not([open])') && el.tagName !== 'SUMMARY')
                                  && !(window.__ids && window.__ids.has(el)));
  return missed.map(DESCRIBE);
})()
""".replace("DESCRIBE", DESCRIBE_FUNCTION)

# Every region that scrolls (its content larger than it) that a keyboard cannot scroll: neither it
# nor anything in it took the focus (arrow keys and Page Down scroll the focus's scrolling region).
UNSCROLLABLE = r"""
(() => [...document.querySelectorAll('body *')].filter(el => {
    const s = getComputedStyle(el);
    return el.getClientRects().length > 0
      && ((/auto|scroll/.test(s.overflowY) && el.scrollHeight > el.clientHeight + 1)
          || (/auto|scroll/.test(s.overflowX) && el.scrollWidth > el.clientWidth + 1))
      && !(window.__ids && (window.__ids.has(el) || [...el.querySelectorAll('*')].some(d => window.__ids.has(d))));
  }).map(DESCRIBE))()
""".replace("DESCRIBE", DESCRIBE_FUNCTION)


class Keyboard(Tab):
    """A browser tab driven by keys only: :meth:`press` a key (Tab, Enter, Space...), :meth:`type` text."""

    def __init__(self, browser):
        super().__init__(browser)
        browser.send("Emulation.setDeviceMetricsOverride", {"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1,
                                                            "mobile": False}, session=self.session)

    def press(self, key: str, shift: bool = False):
        code, number, text = KEYS[key] if key in KEYS else (f"Key{key.upper()}", ord(key.upper()), key)
        event = {"key": key, "code": code, "windowsVirtualKeyCode": number, "modifiers": SHIFT if shift else 0}
        self.browser.send("Input.dispatchKeyEvent", {"type": "keyDown" if text else "rawKeyDown", "text": text, **event}
                          if text else {"type": "rawKeyDown", **event}, session=self.session)
        self.browser.send("Input.dispatchKeyEvent", {"type": "keyUp", **event}, session=self.session)

    def type(self, text: str):
        self.browser.send("Input.insertText", {"text": text}, session=self.session)

    def focused(self) -> dict | None:
        return self.eval(FOCUSED)

    def tab_to(self, expression: str, limit: int = 120, shift: bool = False) -> dict:
        """Tab (or Shift+Tab) until ``expression`` (on ``document.activeElement``, as ``el``) holds."""
        for _ in range(limit):
            self.press("Tab", shift)
            if self.eval(f"(el => !!el && !!({expression}))(document.activeElement)"):
                return self.focused()
        raise AssertionError(f"Tab never reached {expression}; focus is on {self.focused()}")

    def walk(self, limit: int = 300) -> list[dict]:
        """Tab from the top of the page through every stop until the first comes round again."""
        self.eval("document.activeElement && document.activeElement.blur(); window.scrollTo(0, 0); "
                  "window.__ids = new WeakMap()")   # each walk numbers its own stops
        stops, outside = [], 0
        for _ in range(limit):
            self.press("Tab")
            stop = self.focused()
            if stop is None:     # out of the page, between the last stop and the first
                outside += 1
                if outside > 2 and not stops:
                    raise AssertionError("Tab reaches nothing on the page")
                continue
            if stops and stop["id"] == stops[0]["id"]:
                return stops
            stops.append(stop)
        raise AssertionError(f"Tab did not come round to the first stop in {limit} presses (a trap?): "
                             f"{[s['what'] for s in stops[-5:]]}")

    def presses_until(self, key: str, expression: str, limit: int = 20) -> bool:
        """Press ``key`` until ``expression`` holds (a key pressed while a smooth scroll ends is lost)."""
        for _ in range(limit):
            self.press(key)
            try:
                return self.wait(expression, timeout=0.5)
            except AssertionError:
                continue
        return False

    def leaves(self, *keys: str, shift: bool = False):
        """Press ``keys``, the last of which loads another page; return when it has loaded."""
        self.eval("window.__leaving = true")
        for key in keys:
            self.press(key, shift)
        self.wait("!window.__leaving && document.readyState === 'complete'")

    def screenshot(self, name: str):
        folder = os.environ.get("TERM_SCREENSHOTS")
        if folder:
            shot = self.browser.send("Page.captureScreenshot", {"format": "png"}, session=self.session)
            Path(folder).mkdir(parents=True, exist_ok=True)
            (Path(folder) / f"{name}.png").write_bytes(base64.b64decode(shot["data"]))


def assert_keyboard_reaches_everything(tab: Keyboard, page: str) -> list[dict]:
    """Tab through ``page``: every control is a stop, and every region that scrolls is one or holds
    one; each stop shows its focus (an outline or a shadow on :focus-visible) in view, and Tab
    comes round to the first (no trap); Shift+Tab goes back."""
    stops = tab.walk()
    missed = tab.eval(CONTROLS)   # the controls the walk's stops did not number
    assert not missed, f"{page}: not reachable by Tab: {missed}"
    stuck = tab.eval(UNSCROLLABLE)
    assert not stuck, f"{page}: scrolls, but not by keyboard (nothing in it takes the focus): {stuck}"
    unseen = [s["what"] for s in stops if not (s["visible"] and s["indicator"] and s["inView"])]
    assert not unseen, f"{page}: focus not shown (no outline or shadow on :focus-visible, or out of view): " \
                       f"{[s for s in stops if s['what'] in unseen][:5]}"
    if len(stops) > 1:   # the first stop has the focus again: Shift+Tab leaves for the page's last
        tab.press("Tab", shift=True)
        back = tab.focused()
        assert back is None or back["id"] == stops[-1]["id"], f"{page}: Shift+Tab went to {back}"
    return stops


def assert_plain_focus(stops: list[dict]):
    """The review application's own focus style on every stop: a 2-pixel solid outline (the
    browser's ring is a thin one)."""
    thin = [s for s in stops if not s["indicator"].startswith("outline solid 2px")]
    assert not thin, f"the focus is shown thinly on {thin[:3]}"


# ------------------------------------------------------------------ the journey
def queue_names(tab: Keyboard) -> list[str]:
    return tab.eval("[...document.querySelectorAll('#queue td.name')].map(td => td.textContent.trim())")


def review_state(tab: Keyboard) -> dict:
    return tab.eval("({student: document.getElementById('student').textContent, "
                    "points: document.getElementById('points').textContent, "
                    "done: document.getElementById('done').textContent, "
                    "comment: document.getElementById('comment').value, "
                    "applied: [...document.querySelectorAll('#rubric input')].filter(b => b.checked)"
                    ".map(b => b.dataset.item)})")


def saved(tab: Keyboard):
    tab.wait("document.getElementById('status').textContent === 'saved'")


@pytest.mark.slow
def test_a_term_by_keyboard_review_regrade_and_extensions(term, browser):
    from autograder.instructor.batch import run
    from autograder.instructor.batch.gradebook import Gradebook

    download, out = term.download, term.out
    started = time.monotonic()
    order = sorted(NAMES)                       # the queue's order: by name
    first = NAMES[0]                            # lovelaceada: the reference, a long report
    second = order[order.index(first) + 1]      # micalisilvio: the reference, no report
    first_id, second_id = student_id(0), student_id(NAMES.index(second))
    server = Server(out)
    tab = Keyboard(browser)
    try:
        # The queue: every control by Tab; the filters by Tab and Enter, and by their letters.
        tab.open(server.url)
        assert "0 of 30 reviewed" in tab.text("h1")
        assert_plain_focus(assert_keyboard_reaches_everything(tab, "queue"))
        tab.screenshot("1-queue")
        tab.tab_to("el.textContent === 'not reviewed'")
        tab.leaves("Enter")
        assert tab.eval("location.search") == "?show=todo" and len(queue_names(tab)) == 30
        tab.leaves("r")
        assert tab.eval("location.search") == "?show=noreport"
        assert sorted(queue_names(tab)) == sorted(NAMES[i] for i in range(1, 30, 2)), "the odd ones handed in none"
        tab.leaves("a")
        # A student opened by Tab and Enter: the one focused, not the queue's first row.
        tab.tab_to(f"el.textContent === {json.dumps(first)}")
        tab.leaves("Enter")
        assert review_state(tab)["student"] == first

        # The review screen: every control by Tab, with its focus shown; the student's long report
        # scrolls by keys, also with the figures fitted to the pane (z), when they no longer scroll.
        assert_plain_focus(assert_keyboard_reaches_everything(tab, "review screen"))
        tab.press("z")
        assert_keyboard_reaches_everything(tab, "review screen, figures fitted")
        tab.tab_to("el.id === 'work'")
        tab.press("Home")
        tab.wait("document.getElementById('work').scrollTop === 0")
        assert tab.presses_until("PageDown", "document.getElementById('work').scrollTop > 300")

        # Score a rubric item (Space on its box), write a comment, save it for reuse under a key.
        tab.tab_to("el.dataset.item === 'corners'", shift=True)
        tab.press(" ")
        saved(tab)
        assert review_state(tab)["points"] == "3"
        tab.tab_to("el.id === 'comment'")
        text = "Why are the corners black? Nothing maps there."
        tab.type(text)
        tab.tab_to("el.name === 'key'")
        tab.type("corners")
        tab.leaves("Enter")
        assert tab.focused()["what"].endswith("corners"), f"focus after saving a comment: {tab.focused()}"
        assert review_state(tab) | {"done": ""} == {"student": first, "points": "3", "done": "", "comment": text,
                                                     "applied": ["corners"]}
        tab.screenshot("2-review")
        # Save and mark reviewed: the button by Tab and Enter; the focus stays on it.
        tab.tab_to("el.id === 'save'")
        tab.press("Enter")
        tab.wait("document.getElementById('done').textContent === 'reviewed'")
        assert tab.focused()["what"].startswith("button#save")

        # The next student: the saved comment applied by its key (its button, then v and its number), an item, s.
        tab.leaves("j")
        assert review_state(tab)["student"] == second and review_state(tab)["comment"] == ""
        tab.tab_to("el.id === 'saved-corners'")
        tab.press("Enter")
        saved(tab)
        assert review_state(tab)["comment"] == text
        tab.press("v")   # the focus on a button: the keys are the screen's
        tab.press("1")
        tab.wait(f"document.getElementById('comment').value === {json.dumps(text + chr(10) + text)}")
        tab.tab_to("el.dataset.item === 'axes'")
        tab.press(" ")
        saved(tab)
        tab.press("s")
        tab.wait("document.getElementById('done').textContent === 'reviewed'")

        # Back: everything kept, on both.
        tab.leaves("k")
        assert review_state(tab) == {"student": first, "points": "3", "done": "reviewed", "comment": text,
                                     "applied": ["corners"]}
        tab.leaves("j")
        assert review_state(tab) == {"student": second, "points": "1", "done": "reviewed",
                                     "comment": text + "\n" + text, "applied": ["axes"]}
        tab.leaves("q")
        assert "2 of 30 reviewed" in tab.text("h1")
        tab.leaves("t")
        assert first not in queue_names(tab) and second not in queue_names(tab) and len(queue_names(tab)) == 28

        # The screens of the students with an extension and excused say so.
        for i, told in ((3, "extension +2 days"), (4, "excused"), (6, "late 1 day, -3")):
            tab.open(server.url + f"review/{order.index(NAMES[i])}")
            assert review_state(tab)["student"] == NAMES[i] and tab.text("#rules") == told
        tab.open(server.url + f"review/{order.index(NAMES[5])}")
        assert tab.eval("document.getElementById('rules')") is None

        # The rubric page, by Tab too: an item's points changed (Tab selects the field's text), Enter saves
        # it, and the focus comes back to that item's save button.
        tab.leaves("e")
        assert tab.eval("location.pathname").endswith("/rubric")
        assert_plain_focus(assert_keyboard_reaches_everything(tab, "rubric page"))
        tab.tab_to("el.getAttribute('aria-label') === 'points of no-figure'")
        tab.type("-2")
        tab.leaves("Enter")
        assert tab.focused()["what"] == "button#item-lab07.ex1-no-figure save", tab.focused()
        assert tab.eval("document.querySelector('[aria-label=\"points of no-figure\"]').value") == "-2"
        tab.screenshot("3-rubric")
    finally:
        server.kill()
    with Gradebook(out, readonly=True) as book:
        reviews = book.reviews()
    assert reviews[(first_id, "lab07.ex1")]["points"] == 3 and reviews[(second_id, "lab07.ex1")]["points"] == 1
    with Gradebook(out, readonly=True) as book:
        assert [i["points"] for i in book.rubric()["lab07.ex1"]] == [3, 1, -2]

    # A regrade after student 2 (the skeleton) handed in the reference: the overview lists exactly
    # the grades that moved, and why.
    regraded = time.monotonic()
    download_of(download, {2: REFERENCE})
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(run, "_grade_locally", grading_each_distinct_submission_once(run._grade_locally, term.graded))
        summary = run.run_batch(download, out, course=term_course(), workers=2)
    regraded = time.monotonic() - regraded
    assert summary.graded == 1 and summary.reused == 29 and len(term.graded) == 3, "the reference's grading reused"
    moved = {c.student_id: c for c in summary.changes}
    assert set(moved) == {first_id, second_id, student_id(2)}, summary.changes
    assert (moved[student_id(2)].before, moved[student_id(2)].after, moved[student_id(2)].why) == (0, 12,
                                                                                                   "new submission")

    tab.open((out / "index.html").as_uri())
    changes = tab.eval("[...document.querySelectorAll('#changes tr')].slice(1).map(r => r.innerText.split('\\t'))")
    assert {row[0]: row[1:4] + [row[4].split(" (")[0]] for row in changes} == {
        first_id: ["12", "15", "report reviewed", "lab07.ex1 report not reviewed -> 3"],
        second_id: ["12", "13", "report reviewed", "lab07.ex1 report not reviewed -> 1"],
        student_id(2): ["0", "12", "new submission", "lab07.ex1: 0 -> 12"]}, changes
    every = {li.split("\n")[0]: li for li in tab.eval("[...document.querySelectorAll('#students li')]"
                                                      ".map(li => li.innerText)")}
    assert "extension +2 days" in every[NAMES[3]] and "excused" in every[NAMES[4]]
    assert "late" in every[NAMES[6]] and "extension" not in every[NAMES[5]] + every[NAMES[6]]
    stops = assert_keyboard_reaches_everything(tab, "class overview")
    tab.screenshot("4-overview")
    tab.browser.send("Emulation.setDeviceMetricsOverride", {"width": 390, "height": 844, "deviceScaleFactor": 1,
                                                             "mobile": True}, session=tab.session)
    assert tab.wait("innerWidth === 390") and tab.eval("document.documentElement.scrollWidth") <= 390, \
        "on a phone the overview (its changes too) does not scroll sideways"
    tab.screenshot("4-overview-phone")
    tab.browser.send("Emulation.setDeviceMetricsOverride", {"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1,
                                                             "mobile": False}, session=tab.session)
    # From the overview to the student's page, by keyboard.
    tab.tab_to(f"el.textContent === {json.dumps(NAMES[3])}")
    tab.leaves("Enter")
    assert "extension" in tab.text("#adjustments") and "+2 days" in tab.text("#adjustments")
    tab.open((out / student_id(2) / "feedback.html").as_uri())
    assert "Since your previous grading: 0 → 12" in tab.text("body")
    assert_keyboard_reaches_everything(tab, "a student's page")
    tab.screenshot("5-student")
    print(f"batch {term.seconds:.1f} s, browser journey {time.monotonic() - started:.1f} s "
          f"(of which the regrade {regraded:.1f} s), {len(stops)} stops on the overview")


# ------------------------------------------------------------------ the walk can fail
KEYBOARD_FAULTS = {
    "no focus style": ("<button>ok</button><style>button:focus-visible { outline: none }</style>", "focus not shown"),
    "out of the Tab order": ('<button>ok</button><button tabindex="-1">save</button>',
                             "not reachable by Tab: ['button save']"),
    "a trap": ('<input id="a" aria-label="a"><input id="b" aria-label="b"><button>after</button><script>'
               "b.addEventListener('keydown', e => { if (e.key === 'Tab') { e.preventDefault(); a.focus(); } })"
               "</script>", "not reachable by Tab: ['button after']"),
    "a region no key scrolls": ('<div id="long" tabindex="-1" style="height: 100px; overflow: auto">'
                                '<p style="height: 900px">text</p></div><button>ok</button>',
                                "scrolls, but not by keyboard (nothing in it takes the focus): ['div#long"),
}


@pytest.mark.parametrize("fault", KEYBOARD_FAULTS)
def test_the_keyboard_walk_catches_what_it_should(browser, tmp_path, fault):
    page, told = KEYBOARD_FAULTS[fault]
    tab = Keyboard(browser)
    (tmp_path / "page.html").write_text(f"<!doctype html><html><body>{page}</body></html>")
    tab.open((tmp_path / "page.html").as_uri())
    with pytest.raises(AssertionError, match=re.escape(told)):
        assert_keyboard_reaches_everything(tab, fault)
    # and a page without the fault passes: a shadow is a focus style too
    (tmp_path / "good.html").write_text('<!doctype html><html><body><a href="#x">x</a><input aria-label="i">'
                                        "<button>ok</button><style>button:focus-visible { outline: none; "
                                        "box-shadow: 0 0 0 3px #0969da }</style></body></html>")
    tab.open((tmp_path / "good.html").as_uri())
    assert [s["what"] for s in assert_keyboard_reaches_everything(tab, "good")] == ["a x", "input i", "button ok"]
