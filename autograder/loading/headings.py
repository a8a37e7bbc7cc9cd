"""Reports in the student's own structure: which exercise a heading names.

Students write their own headings, not the scaffold's markers::

    ## Exercise 2: Rotation        ### Ex. 2          Ex2          2. Rotation
    Task 2 / Q2 / Part 2 / Problem 2      Rotation      Lab 7 Exercise 2      7.2
    Extension 1 / ext1              **Exercise 2**    Rotation (setext)
                                                      --------

:func:`student_sections` finds such headings in a Markdown text (ATX headings of any
level, setext headings, a line that is wholly bold) and returns the text under each one
that names an exercise of :class:`ExerciseNames`. What the heading names:

- a number, after an optional kind word (exercise, ex, task, question, q, problem,
  part; extension or ext for the labs' extensions ``labNN.extK``) and an optional lab
  prefix (``Lab 7``, ``lab07``, ``7.2``); a bare number only followed by ``.``, ``)``,
  ``:``, ``-``, nothing, or the exercise's title (``## 3 observations`` is no exercise);
- an exercise's title alone or at the heading's start, case and punctuation ignored
  (``The pinhole camera``, ``pinhole camera``; an extension's ``Extension:`` prefix is
  optional).

The lab is the heading's own (``Lab 7 ...``, ``7.2``), else the one the latest lab
heading named (``# Lab 7`` or the lab's title), else the one the file's path names
(``lab07_report.md``, ``lab07_transformations.ipynb``), else the only lab there is. A
number with no lab to go by names nothing, and a problem says so.

An exercise's section runs from its heading to the next heading of the same or a higher
level, or the next heading naming another exercise (a deeper heading naming the same
exercise, "2.1 The matrix" under "Exercise 2", stays in it). A ``---`` setext underline
or a bold line counts as a heading only when it names an exercise or lab (students draw
``---`` as a rule under a paragraph). Code blocks hold no headings.

Linear in the text: lines are scanned once, a heading's text is cut to
:data:`MAX_HEADING_CHARS` before any regular expression looks at it, and sections are
closed in one forward pass.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import cached_property
from typing import Iterable, Iterator, Mapping

MAX_HEADING_CHARS = 200          # a heading's text looked at; longer headings are cut
BOLD_LEVEL = 7                   # a wholly bold line: below every ATX level
MAX_PLAIN_HEADING_CHARS = 80     # a line of a PDF's text that may be a heading

_EXERCISE_ID = re.compile(r"(lab\d\d)\.(ex|ext)(\d+)")
# On a heading already lower case, whitespace collapsed to single spaces, and cut: the
# optional parts are separated by literals or " ?", so matching is bounded by the cut.
_NUMBERED = re.compile(
    r"(?:lab ?0*(?P<lab>\d{1,2})(?!\d) ?[-:.,/)]* ?)?"
    r"(?:(?P<kind>extensions?|ext|exercises?|exercices?|exo|ex|tasks?|questions?|q|problems?|prob|parts?)"
    r" ?[.:#-]? ?(?:no\. ?)?)?"
    r"0*(?P<n>\d{1,3})(?!\d)"
    r"(?: ?\. ?0*(?P<m>\d{1,3})(?!\d))?")
_LAB = re.compile(r"lab ?0*(?P<lab>\d{1,2})(?!\d)")
_LAB_IN_PATH = re.compile(r"lab[ _-]?0*(\d{1,2})(?!\d)")
_WORD = re.compile(r"[a-z0-9]+")
_ATX = re.compile(r" {0,3}(#{1,6})(?:[ \t]|$)")
_FENCE = re.compile(r" {0,3}(?:```|~~~)")
_BOLD = re.compile(r"[ \t]*(\*\*|__)(.+)\1[ \t]*[.:]?[ \t]*")
_EMPHASIS = str.maketrans({c: " " for c in "*_`~"})
_LEADING_WORDS = ("extension ", "the ", "a ", "an ")
_BARE_NUMBER_ENDS = ".):-"


def words(text: str) -> str:
    """``text`` as lower-case words joined by single spaces (a title's comparable form),
    leading "extension"/articles dropped: ``"Extension: The lens-distortion"`` -> ``"lens distortion"``."""
    joined = " ".join(_WORD.findall(text[:MAX_HEADING_CHARS].lower()))
    for prefix in _LEADING_WORDS:
        joined = joined.removeprefix(prefix)
    return joined


@dataclass(frozen=True)
class ExerciseNames:
    """The exercises a report's headings may name.

    ``exercises``: exercise id (``lab07.ex2``, ``lab08.ext1``) -> its title;
    ``labs``: lab key (``lab07``) -> the lab's title. Other id forms are ignored.
    """

    exercises: Mapping[str, str]
    labs: Mapping[str, str] = field(default_factory=dict)

    @classmethod
    def of_labs(cls, labs: Iterable) -> "ExerciseNames":
        """From registry labs (:class:`autograder.engine.registry.Lab`: ``key``, ``title``,
        ``exercises`` with ``id`` and ``title``)."""
        labs = list(labs)
        return cls({e.id: e.title for lab in labs for e in lab.exercises.values()},
                   {lab.key: lab.title for lab in labs})

    @cached_property
    def _numbers(self) -> dict[tuple[str, str, int], str]:
        """(lab key, "ex"/"ext", number) -> exercise id."""
        out = {}
        for exercise in self.exercises:
            match = _EXERCISE_ID.fullmatch(exercise)
            if match:
                out[match.group(1), match.group(2), int(match.group(3))] = exercise
        return out

    @cached_property
    def lab_keys(self) -> dict[int, str]:
        """Lab number -> lab key, for the labs that have exercises here."""
        return {int(lab[3:]): lab for lab, _, _ in self._numbers}

    @cached_property
    def _titles(self) -> dict[str, list[tuple[str, str]]]:
        """Lab key -> [(title's words, exercise id)], the longest titles first."""
        out: dict[str, list] = {}
        for exercise, title in self.exercises.items():
            lab, _, _ = exercise.partition(".")
            if words(title):
                out.setdefault(lab, []).append((words(title), exercise))
        return {lab: sorted(found, key=lambda pair: -len(pair[0])) for lab, found in out.items()}

    @cached_property
    def _lab_titles(self) -> dict[str, str]:
        return {words(title): lab for lab, title in self.labs.items() if words(title) and lab in self._titles}

    def lab_of_path(self, path: str) -> str | None:
        """The lab a file's path names (``lab07_report.md``), if it is one of these."""
        match = _LAB_IN_PATH.search(path.lower())
        return self.lab_keys.get(int(match.group(1))) if match else None

    def named(self, heading: str, lab: str | None, strict: bool = False) -> "Named":
        """What ``heading`` (its text, without ``#``) names, ``lab`` being the lab in force.
        ``strict``: a bare number names an exercise only with its title after it ("2. Rotation",
        not "2": in text extracted from a PDF a line "2" is a page number)."""
        text = " ".join(heading[:MAX_HEADING_CHARS].translate(_EMPHASIS).lower().split())
        title_words = words(text)
        numbered = _NUMBERED.match(text)
        if numbered:
            exercise, unsure = self._by_number(numbered, text, lab, strict)
            if exercise or unsure:
                return Named(exercise=exercise, unsure=unsure and not exercise)
        found = self._by_title(title_words, lab, exact=strict)
        if found:
            return Named(exercise=found)
        if title_words in self._lab_titles:
            return Named(lab=self._lab_titles[title_words])
        only_lab = _LAB.search(text)    # "# Lab 7", "# My lab 7 report"
        if only_lab and self.lab_keys.get(int(only_lab.group("lab"))):
            return Named(lab=self.lab_keys[int(only_lab.group("lab"))])
        return Named()

    def _by_number(self, match: re.Match, text: str, lab: str | None, strict: bool = False) -> tuple[str | None, bool]:
        """(exercise id or None, whether it looked like a number with no lab to go by)."""
        kind = "ext" if (match.group("kind") or "").startswith("ext") else "ex"
        n, m = int(match.group("n")), match.group("m")
        if match.group("lab"):
            lab = self.lab_keys.get(int(match.group("lab")))
            if lab is None:
                return None, False
        elif m is not None and n in self.lab_keys and (self.lab_keys[n], kind, int(m)) in self._numbers:
            lab, n = self.lab_keys[n], int(m)          # "7.2": lab 7, exercise 2
        rest = text[match.end():]
        if not match.group("kind"):   # a bare number: "2.", "Lab 7 - 2)", "2 Rotation"; not "Lab 7: 2D ..."
            if (strict and not match.group("lab") or m is None and rest[:1] not in ("", *_BARE_NUMBER_ENDS)) \
                    and not self._title_follows(rest.lstrip(_BARE_NUMBER_ENDS), lab, n):
                return None, False
        if lab is None:
            lab = next(iter(self._titles)) if len(self._titles) == 1 else None
        if lab is None:
            return None, True
        return self._numbers.get((lab, kind, n)), False

    def _title_follows(self, rest: str, lab: str | None, n: int) -> bool:
        return any(self._numbers.get((lab_key, "ex", n)) == exercise and _starts_with(words(rest), title)
                   for lab_key in ([lab] if lab else self._titles)
                   for title, exercise in self._titles.get(lab_key, ()))

    def _by_title(self, heading_words: str, lab: str | None, exact: bool = False) -> str | None:
        """The exercise whose title the heading is, or starts with unless ``exact`` (the lab in
        force's; else the only lab's whose title it is)."""
        if not heading_words:
            return None
        found = set()
        for lab_key in [lab] if lab else self._titles:
            # the longest title the heading starts with: "triangulation revisited" before "triangulation"
            found.update(next(([e] for title, e in self._titles.get(lab_key, ()) if heading_words == title or not exact and _starts_with(heading_words, title)), []))
        return found.pop() if len(found) == 1 else None


def _starts_with(heading_words: str, title: str) -> bool:
    return heading_words == title or heading_words.startswith(title + " ")


@dataclass(frozen=True)
class Named:
    exercise: str | None = None   # the exercise id the heading names
    lab: str | None = None        # a lab heading: the lab it names
    unsure: bool = False          # an exercise number with no lab to go by


@dataclass(frozen=True)
class Heading:
    start: int          # where the heading's first line starts
    end: int            # where the text under it starts
    level: int          # 1-6, setext 1-2, a bold line BOLD_LEVEL
    text: str
    strong: bool        # a heading whatever it names (ATX, "===" setext)


@dataclass(frozen=True)
class Section:
    exercise: str
    start: int          # the heading's start
    body: str           # the text under the heading, up to the section's end


def headings(text: str, most: int) -> Iterator[Heading]:
    """The heading candidates of ``text`` outside fenced code blocks, the first ``most``."""
    position, fenced, previous, found = 0, False, None, 0
    for line in text.split("\n"):
        start, position = position, position + len(line) + 1
        if _FENCE.match(line):
            fenced, previous = not fenced, None
            continue
        if fenced:
            continue
        candidate = _heading_at(line, start, min(position, len(text)), previous)
        if candidate is not None:
            found += 1
            yield candidate
            if found >= most:
                return
        previous = None if candidate or not line.strip() else (start, line)


def _heading_at(line: str, start: int, end: int, previous) -> Heading | None:
    atx = _ATX.match(line)
    if atx:
        return Heading(start, end, len(atx.group(1)), line[atx.end():].strip().rstrip("#").strip(), True)
    stripped = line.strip()
    if previous is not None and stripped and len(line) - len(line.lstrip(" ")) < 4 and set(stripped) in ({"="}, {"-"}):
        return Heading(previous[0], end, 1 if stripped[0] == "=" else 2, previous[1].strip(), stripped[0] == "=")
    if stripped.startswith(("**", "__")) and len(stripped) <= MAX_HEADING_CHARS:
        bold = _BOLD.fullmatch(line)
        if bold:
            return Heading(start, end, BOLD_LEVEL, bold.group(2), False)
    return None


@dataclass
class _Open:
    exercise: str
    level: int
    start: int
    body: int


def student_sections(text: str, names: ExerciseNames, path_lab: str | None, most: int,
                     unsure: list | None = None) -> list[Section]:
    """The sections of ``text`` under headings naming an exercise of ``names``, in order.

    ``path_lab``: the lab the file's path names (or None); ``most``: heading candidates
    read (the rest of the text is read as part of the last section). A heading that names
    an exercise by number with no lab to go by is appended to ``unsure`` (its text).
    """
    return _sections(text, names, path_lab, headings(text, most), unsure)


def plain_text_sections(text: str, names: ExerciseNames, path_lab: str | None, most: int,
                        unsure: list | None = None) -> list[Section]:
    """As :func:`student_sections`, for plain text (a PDF's, extracted): a line of at most
    :data:`MAX_PLAIN_HEADING_CHARS` characters that names an exercise or a lab is a heading,
    strictly (a bare number needs the title after it, a title is the whole line: "Scaling
    doubles the size" is a sentence); a section runs to the next one, running headers
    ("Lab 7 - report" atop each page) and all."""
    return _sections(text, names, path_lab, _short_lines(text, most), unsure, strict=True)


def _short_lines(text: str, most: int) -> Iterator[Heading]:
    position = 0
    for number, line in enumerate(text.split("\n")):
        start, position = position, position + len(line) + 1
        if number >= most:
            return
        if 0 < len(line.strip()) <= MAX_PLAIN_HEADING_CHARS:
            yield Heading(start, min(position, len(text)), 2, line.strip(), False)


def _sections(text, names, path_lab, candidates, unsure, strict=False) -> list[Section]:
    sections: list[Section] = []
    lab, current = path_lab, None

    def close(at: int) -> None:
        sections.append(Section(current.exercise, current.start, text[current.body:at]))

    # One forward pass: a section closes at the next heading of its level or above, or naming another exercise.
    for heading in candidates:
        named = names.named(heading.text, lab, strict)
        if named.unsure and unsure is not None:
            unsure.append(heading.text[:80])
        if not (heading.strong or named.exercise or named.lab):
            continue
        if strict and not named.exercise:   # a PDF's running header ("Lab 7 - report") on every page
            lab = named.lab or lab
            continue
        if current and (heading.level <= current.level or (named.exercise or current.exercise) != current.exercise):
            close(heading.start)
            current = None
        if named.lab:
            lab = named.lab
        if named.exercise and current is None:
            current = _Open(named.exercise, heading.level, heading.start, heading.end)
    if current:
        close(len(text))
    return sections
