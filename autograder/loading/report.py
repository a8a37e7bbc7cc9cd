"""Reading the lab report a student hands in: an explanation per exercise.

``python grade.py --report DIR`` writes a scaffold (:mod:`autograder.student.report`):
per exercise a ``## lab07.ex1: title`` heading, the figures made by the student's
code, the automatic verdict, and a marked place for the explanation::

    <!-- explanation lab07.ex1 -->
    _Explain what you see here._
    <!-- end explanation -->

This module reads what the student wrote there, from Markdown files and from the
Markdown cells of notebooks, into :class:`Explanation` s. It never renders
anything (the instructor side does, safely) and never raises on what a student
sends: every fault (a file too large, a notebook that is no JSON, one exercise
explained twice ...) is a sentence in :attr:`Report.problems`. Sizes are bounded:
a file over :data:`MAX_REPORT_BYTES` is not read, an explanation over
:data:`MAX_EXPLANATION_CHARS` is cut (``truncated=True``), at most
:data:`MAX_EXPLANATIONS` exercises and :data:`MAX_PROBLEMS` sentences are kept; an
exercise is read from at most :data:`MAX_PLACES` places, a file's first
:data:`MAX_SECTIONS` markers and headings and a notebook's first :data:`MAX_REPORT_CELLS`
Markdown cells are read (a problem says what was not). Reading is linear in what is
handed in: no regular expression here backtracks beyond a line, and an explanation
gathered from many places is joined once, at the end.

Where the explanation is, in a Markdown file:

1. between ``<!-- explanation ID -->`` and the next ``<!-- end explanation -->``;
   a missing end marker ends it at the next start marker or ``#``/``##`` heading;
2. without markers for an exercise, under its heading ``## ID...`` up to the next
   ``#`` or ``##`` heading (outside code blocks), the scaffold's lines removed: the
   figures, the verdict, the "No figure" sentences.

In a notebook: a Markdown cell tagged ``report:ID``, or holding the start marker of
one exercise, is that exercise's explanation (its text, markers and placeholder
removed); a cell holding markers of several exercises is read as a Markdown file.

In the student's own structure (when the reader is given the
:class:`~.headings.ExerciseNames` of the labs graded): the text under any heading that
names an exercise -- "## Exercise 2: Rotation", "Ex. 2", "2. Rotation", "Rotation",
"Lab 7 Exercise 2", "Extension 1", setext and bold-line headings too (see
:mod:`.headings`) -- in a Markdown file, and in a notebook's Markdown cells read one
after the other (a heading's text runs on into the cells after it). The scaffold's
markers, tags and ``## ID`` headings keep precedence: a heading of the student's own is
read only for an exercise that none of those explains anywhere in the hand-in.

PDF reports (when the reader is given a :class:`~.pdf_report.ReportReader` and the
exercise names): the text is extracted in a sandbox worker, never here, and split per
exercise as the student's own headings are (:func:`~.pdf_report.pdf_sections`: strictly,
a heading being a short line that names an exercise); a PDF whose text cannot be read is
one problem, "report.pdf: the PDF's text could not be read: it is encrypted ...".

Figures (:class:`ReportFigure`, with the same reader): the pictures of a PDF, the image
outputs of a notebook's code cells, and the pictures a Markdown report links to among the
hand-in's PNG and JPEG files (``![](figures/lab07.ex1.png)``, relative to the report),
thumbnailed in the worker, each with the exercise whose section holds it (a PDF's page, a
notebook's cell after the exercise's heading or tagged cell, the link's place in the file); the review screen compares them with the figures the student's code makes
(:mod:`autograder.instructor.review.provenance`).

IDs are exercise ids (``lab07.ex1``, ``lab08.ext2``) or the figure ids of the
experiment extensions (``lab09.ex3-extension``). :data:`PLACEHOLDER` alone, or
nothing, means "not written": such a section gives no explanation.
"""

from __future__ import annotations

import bisect
import json
import posixpath
import re
from dataclasses import dataclass, field
from itertools import islice
from pathlib import PurePosixPath
from urllib.parse import unquote

import numpy as np

from .headings import ExerciseNames, student_sections
from .pdf_report import ReportReader, notebook_pictures, pdf_sections
from .text import printable, shown

REPORT_SUFFIXES = (".md", ".ipynb")      # .pdf files are listed; their text is read in a worker (pdf_report)
MAX_FIGURES = 100                        # report figures kept per hand-in
ATTACHMENT_SUFFIXES = (".pdf",)
MAX_REPORT_BYTES = 1 << 20               # a larger report file is refused with its reason
MAX_EXPLANATION_CHARS = 20_000           # longer: cut, with truncated=True
MAX_EXPLANATIONS = 300                   # exercises read from one hand-in (six labs have ~50)
MAX_PROBLEMS = 20                        # sentences kept; the rest are counted
MAX_PLACES = 20                          # places one exercise is explained in, read (more: noted)
MAX_SECTIONS = 1_000                     # markers, and headings, read per file or cell (more: noted)
MAX_REPORT_CELLS = 2_000                 # Markdown cells read per notebook (more: noted)

BACKUP_SUFFIX = ".previous.md"           # the scaffold's copy of the report it replaced: never read
PLACEHOLDER = "_Explain what you see here._"
REPORT_TAG_PREFIX = "report:"            # a notebook cell's tag: report:lab07.ex1
VERDICT_PREFIX = "Automatic verdict:"

_ID = re.compile(r"lab\d\d\.[a-z]+\d+(?:-[a-z]+)?")
_START = re.compile(r"<!--[ \t]*explanation[ \t]+([^\s>]{1,60})[ \t]*-->", re.IGNORECASE)
_END = re.compile(r"<!--[ \t]*end[ \t]+explanation[ \t]*-->", re.IGNORECASE)
_MARKER_LINE = re.compile(f"(?:{_START.pattern}|{_END.pattern})[ \t]*\n?", re.IGNORECASE)
_HEADING = re.compile(r"^#{1,2}[ \t]+(\S.*)$", re.MULTILINE)   # a level 1 or 2 heading
_FENCE = re.compile(r"^[ \t]{0,3}(```|~~~)", re.MULTILINE)     # a code block's fence (its "# comments" are no headings)
_SECTION = re.compile(r"(lab\d\d\.[a-z]+\d+(?:-[a-z]+)?)(?![\w-])", re.IGNORECASE)  # its id, first thing
_FIGURE_LINE = re.compile(r"^[ \t]*!\[[^\]\n]*\]\([^)\n]*\)[ \t]*$", re.MULTILINE)
VERDICT_LINE = re.compile(r"^[ \t]*" + re.escape(VERDICT_PREFIX) + r".*$", re.MULTILINE)
# A Markdown picture link: ![alt](target) or ![alt](<target> "title"); bounded on one line.
_PICTURE_LINK = re.compile(r'!\[[^\]\n]{0,300}\]\([ \t]*<?([^)\s>]{1,500})>?(?:[ \t]+"[^"\n]{0,300}")?[ \t]*\)')
_NO_FIGURE_LINE = re.compile(r"^[ \t]*_No figure[^\n]*_[ \t]*$", re.MULTILINE)  # the scaffold's, for a figure not made


def is_backup(name) -> bool:
    """Whether ``name`` is the copy ``--report`` keeps of the report it replaced
    (``lab07_report.previous.md``): handed in beside the report, it would repeat every
    explanation, older ones among them."""
    return str(name).lower().endswith(BACKUP_SUFFIX)


def exercise_id(text: str) -> str | None:
    """``text`` as a section id (``lab07.ex1``, ``lab09.ex3-extension``), lower case, or None."""
    text = text.strip().lower()
    return text if _ID.fullmatch(text) else None


@dataclass(frozen=True)
class Explanation:
    exercise: str          # "lab07.ex1"
    text: str              # Markdown, as written (never rendered here), control chars removed
    source: str            # "lab07_report.md" or "lab07_transformations.ipynb, cell 12"
    truncated: bool = False


@dataclass(frozen=True)
class ReportFigure:
    """A picture embedded in the report, thumbnailed in a worker (never decoded here)."""

    exercise: str          # the exercise whose section holds it; "" when none does
    source: str            # "report.pdf, page 3" or "lab07_transformations.ipynb, cell 12"
    number: int            # its place among the hand-in's report figures, from 1
    width: int             # its own size, pixels
    height: int
    thumb: np.ndarray      # THUMB x THUMB grey uint8 (autograder.sandbox.report_reader.thumbnail)


@dataclass(frozen=True)
class Report:
    explanations: dict[str, Explanation] = field(default_factory=dict)  # written ones only
    attachments: tuple[str, ...] = ()    # relative paths of PDFs handed in (offered as files)
    problems: tuple[str, ...] = ()       # sentences: a file refused, two explanations of one exercise...
    figures: tuple[ReportFigure, ...] = ()   # pictures in the report (with a reader only)


# ------------------------------------------------------------------ public functions
def explanations_in_markdown(text: str, source: str) -> dict[str, Explanation]:
    """The written explanations of a Markdown report, by exercise id (see the module doc)."""
    reading = _Reading()
    reading.markdown(text, source)
    return reading.explanations()


def explanations_in_notebook(data: bytes, source: str) -> dict[str, Explanation]:
    """The written explanations in a notebook's Markdown cells, by exercise id."""
    reading = _Reading()
    reading.notebook(data, source)
    return reading.explanations()


def read_report(files: dict[str, bytes], names: ExerciseNames | None = None,
                reader: ReportReader | None = None, pictures: dict[str, bytes] | None = None) -> Report:
    """Every explanation in the Markdown files and notebooks of a hand-in, the PDFs beside
    them, and what could not be read.

    ``files``: relative path -> bytes (as ``sandbox.files.read_regular_files`` gives them).
    ``names``: the exercises the student's own headings may name (none read without it).
    ``reader``: reads the PDFs' text and the report's pictures in sandbox workers (with
    ``names``; without, PDFs are only listed and no figure is read). ``pictures``: the
    hand-in's PNG and JPEG files (relative path -> bytes) a Markdown report may link to.
    Files are read in path order; an exercise explained in two places keeps both texts,
    one after the other, and the problems say so.
    """
    reading = _Reading(names, reader if names is not None else None)
    attachments = []
    for path in sorted(files, key=str):
        name = shown(path)
        parts = PurePosixPath(str(path).replace("\\", "/")).parts
        if any(part.startswith(".") or part == "__MACOSX" for part in parts) or is_backup(path):
            continue  # editor backups, macOS resource forks, the scaffold's own backup
        suffix = PurePosixPath(parts[-1] if parts else "").suffix.lower()
        if suffix in ATTACHMENT_SUFFIXES:
            attachments.append(name)
            if reading.reader is not None and isinstance(files[path], (bytes, bytearray, memoryview)):
                reading.pdf(bytes(files[path]), name)
            continue
        if suffix not in REPORT_SUFFIXES:
            continue
        data = files[path]
        if not isinstance(data, (bytes, bytearray, memoryview)):
            reading.problem(f"{name} could not be read")
            continue
        if len(data) > MAX_REPORT_BYTES:
            reading.problem(f"{name} is {len(data) / (1 << 20):.1f} MiB, larger than the "
                            f"{MAX_REPORT_BYTES >> 20} MiB a report may be; it was not read "
                            "(keep the pictures as separate files, not inside the text)")
            continue
        if suffix == ".md":
            text = _decoded(bytes(data))
            reading.markdown(text, name)
            if reading.reader is not None and pictures:
                reading.markdown_pictures(printable(text)[: 4 * MAX_REPORT_BYTES], name, str(path), pictures)
        else:
            reading.notebook(bytes(data), name)
    return Report(reading.explanations(), tuple(attachments), reading.problem_list(), tuple(reading.figures))


# ------------------------------------------------------------------ reading
@dataclass
class _Gathered:
    """One exercise's explanation as read so far: its texts and where they came from."""

    texts: list[str] = field(default_factory=list)   # at most MAX_PLACES, MAX_EXPLANATION_CHARS in all
    sources: list[str] = field(default_factory=list)
    length: int = 0
    truncated: bool = False
    more_places: int = 0                              # places beyond MAX_PLACES, not read

    def explanation(self, exercise: str) -> Explanation:
        text = "\n\n".join(self.texts)
        truncated = self.truncated or len(text) > MAX_EXPLANATION_CHARS
        source = "; ".join(self.sources) + (f"; and {self.more_places} more places" if self.more_places else "")
        return Explanation(exercise, text[:MAX_EXPLANATION_CHARS], source, truncated)


class _Reading:
    """Explanations and problems gathered over the files of one hand-in."""

    def __init__(self, names: ExerciseNames | None = None, reader: ReportReader | None = None):
        self.gathered: dict[str, _Gathered] = {}
        self.problems: list[str] = []
        self.more_problems = 0
        self.names = names
        self.reader = reader
        self.figures: list[ReportFigure] = []
        self.own: list[tuple[str, str, str]] = []   # (exercise, text, source) under the student's own headings

    def explanations(self) -> dict[str, Explanation]:
        """Every exercise's explanation, its texts joined once (not at each new place: an
        exercise explained in thousands of cells made that quadratic). The student's own
        headings count for the exercises nothing of the scaffold's explains."""
        explained = set(self.gathered)
        for exercise, text, source in self.own:
            if exercise not in explained:
                self.add(exercise, text, source)
        self.own = []
        return {exercise: gathered.explanation(exercise) for exercise, gathered in self.gathered.items()}

    def own_headings(self, text: str, source: str, where=None, sections=None) -> list:
        """Keep the sections under the student's own headings in ``text`` (of the file
        ``source``) for the end, and return them. ``where(position)``: the source of the text
        at ``position`` (a notebook's cell). ``sections``: given (a PDF's), else found here."""
        if self.names is None:
            return []
        unsure: list[str] = []
        if sections is None:
            sections = student_sections(text, self.names, self.names.lab_of_path(source), MAX_SECTIONS, unsure)
        for section in sections:
            self.own.append((section.exercise, _section_text(section.body),
                             where(section.start) if where else source))
        if unsure:
            self.problem(f"{source}: the heading {unsure[0]!r} names an exercise by number but not its lab; "
                         "name the lab in the file's name (lab07_report.md) or a heading (# Lab 7)")
        return sections

    # -------------------------------------------------------------- PDFs and pictures (in a worker)
    def pdf(self, data: bytes, source: str) -> None:
        """The PDF's text per exercise (as the student's own headings), and its pictures."""
        pdf = self.reader.pdf(data)
        if pdf.error:
            self.problem(f"{source}: the PDF's text could not be read: {pdf.error}")
            return
        for note in pdf.notes:
            self.problem(f"{source}: {note}")
        text, unsure = pdf.text, []
        sections = pdf_sections(pdf, self.names, source, MAX_SECTIONS, unsure)
        if unsure:
            self.problem(f"{source}: the heading {unsure[0]!r} names an exercise by number but not its lab; "
                         "name the lab in the file's name (lab07_report.pdf) or a heading (Lab 7)")
        self.own_headings(text, source, lambda at: f"{source}, page {pdf.page_at(at)}", sections)
        for picture in pdf.pictures:
            page = int(picture.where.split()[-1])
            self.figure(_exercises_on_page(pdf, sections, page), f"{source}, {picture.where}", picture)

    def markdown_pictures(self, text: str, source: str, path: str, pictures: dict[str, bytes]) -> None:
        """The pictures the Markdown ``text`` (of the file at ``path``) links to among
        ``pictures``, each with the exercise of the last marker or heading before its link."""
        folder, found = PurePosixPath(path.replace("\\", "/")).parent, {}
        for link in islice(_PICTURE_LINK.finditer(text), MAX_FIGURES):
            target = unquote(link.group(1))
            if "://" in target or target.startswith(("/", "data:")):
                continue
            resolved = posixpath.normpath((folder / target).as_posix())
            if resolved in pictures and resolved not in found:   # a picture linked twice is one figure
                found[resolved] = link.start()
        if not found:
            return
        marks = [(m.start(), exercise) for m in islice(_START.finditer(text), MAX_SECTIONS)
                 if (exercise := exercise_id(m.group(1)))]
        marks += [(h.start(), m.group(1).lower()) for h in _headings(text, MAX_SECTIONS)
                  if (m := _SECTION.match(h.group(1).strip()))]
        if self.names is not None:
            marks += [(section.start, section.exercise) for section in
                      student_sections(text, self.names, self.names.lab_of_path(source), MAX_SECTIONS)]
        marks.sort()
        where = {f"{source}, {shown(target)}": at for target, at in found.items()}
        read, problems = self.reader.pictures([(label, pictures[target]) for label, target
                                               in zip(where, found)])
        for sentence in problems:
            self.problem(sentence)
        for picture in read:
            before = bisect.bisect_right(marks, (where[picture.where], "\uffff"))
            self.figure([marks[before - 1][1]] if before else [], picture.where, picture)

    def notebook_figures(self, notebook: dict, source: str, marks: list[tuple[int, str]]) -> None:
        """The image outputs of the notebook's code cells, each with the exercise of the last
        mark (cell number, exercise: a tagged cell, a heading of the student's) before it."""
        found = notebook_pictures(notebook)
        if not found or self.reader is None:
            return
        pictures, problems = self.reader.pictures([(f"{source}, cell {cell}", blob) for cell, blob in found])
        for sentence in problems:
            self.problem(sentence)
        marks = sorted(marks)
        for picture in pictures:
            cell = int(picture.where.rsplit(" ", 1)[-1])
            before = bisect.bisect_right(marks, (cell, "\uffff"))
            self.figure([marks[before - 1][1]] if before else [], picture.where, picture)

    def figure(self, exercises: list[str], source: str, picture) -> None:
        number = len({(f.source, f.number) for f in self.figures}) + 1
        if number > MAX_FIGURES:
            return
        for exercise in dict.fromkeys(exercises or [""]):   # an exercise in two sections of a page: once
            self.figures.append(ReportFigure(exercise, source, number, picture.width, picture.height, picture.thumb))

    def problem(self, sentence: str) -> None:
        if len(self.problems) < MAX_PROBLEMS:
            self.problems.append(sentence)
        else:
            self.more_problems += 1

    def problem_list(self) -> tuple[str, ...]:
        more = [f"and {self.more_problems} more problems like these"] if self.more_problems else []
        return tuple(self.problems + more)

    def add(self, exercise: str, text: str, source: str) -> None:
        """Keep ``text`` as ``exercise``'s explanation if it is written; a second one is added
        after the first (nothing a student wrote is dropped unless beyond the bounds, and
        then the problems say so). Constant work beyond cleaning ``text``."""
        text = _cleaned(text)
        if not text:
            return
        known = self.gathered.get(exercise)
        if known is None:
            if len(self.gathered) >= MAX_EXPLANATIONS:
                self.problem(f"{source}: more than {MAX_EXPLANATIONS} exercises explained; "
                             f"{exercise} and those after it were not read")
                return
            known = self.gathered[exercise] = _Gathered()
        elif len(known.sources) >= MAX_PLACES:
            known.more_places += 1
            if known.more_places == 1:
                self.problem(f"{exercise} is explained in more than {MAX_PLACES} places; the text at "
                             f"{source} and after it was not read")
            return
        else:
            self.problem(f"{exercise} is explained twice ({known.sources[0]}; {source}); "
                         "both texts are kept, one after the other")
        known.sources.append(source)
        if known.truncated:
            return
        room = MAX_EXPLANATION_CHARS - known.length - 2 * len(known.texts)   # "\n\n" between texts
        if len(text) > room:
            text, known.truncated = text[:max(room, 0)], True
            self.problem(f"the explanation of {exercise} ({source}) is longer than "
                         f"{MAX_EXPLANATION_CHARS:,} characters; the rest was cut")
        if text:
            known.texts.append(text)
            known.length += len(text)

    # -------------------------------------------------------------- Markdown
    def markdown(self, text: str, source: str, notebook_cell: bool = False) -> None:
        text = printable(text)[: 4 * MAX_REPORT_BYTES]  # at most 4 characters a byte came in as
        starts = list(islice(_START.finditer(text), MAX_SECTIONS + 1))
        heading_matches = _headings(text, MAX_SECTIONS + 1)
        cut = min((found[MAX_SECTIONS].start() for found in (starts, heading_matches) if len(found) > MAX_SECTIONS),
                  default=None)
        if cut is not None:  # read up to the first marker or heading beyond the bound
            self.problem(f"{source} holds more than {MAX_SECTIONS:,} explanation markers or headings; "
                         f"what follows the first {MAX_SECTIONS:,} was not read")
            text = text[:cut]
            starts = [m for m in starts if m.start() < cut]
            heading_matches = [m for m in heading_matches if m.start() < cut]
        ends = [m.start() for m in _END.finditer(text)]
        headings = [m.start() for m in heading_matches]
        marked: set[str] = set()
        for number, start in enumerate(starts):
            exercise = exercise_id(start.group(1))
            if exercise is None:
                self.problem(f"{source}: a marker names {shown(start.group(1), 40)!r}, which is no "
                             "exercise (they look like lab07.ex1)")
                continue
            marked.add(exercise)
            next_start = starts[number + 1].start() if number + 1 < len(starts) else len(text)
            end = _first_after(ends, start.end(), len(text))
            if end > next_start:  # the end marker was deleted: stop before the next section
                end = min(next_start, _first_after(headings, start.end(), len(text)))
                self.problem(f"{source}: the explanation of {exercise} has no "
                             "'<!-- end explanation -->'; it was read up to the next section")
            self.add(exercise, text[start.end():end], source)
        self._under_headings(text, source, marked, heading_matches)
        if not notebook_cell:
            self.own_headings(text, source)

    def _under_headings(self, text, source, marked, heading_matches) -> None:
        """The fallback: the text under ``## ID...`` for each exercise with no markers."""
        headings = [m.start() for m in heading_matches]
        for number, heading in enumerate(heading_matches):
            title = heading.group(1)
            match = _SECTION.match(title.strip())
            if match is None:
                continue
            exercise = match.group(1).lower()
            if exercise in marked:
                continue
            end = headings[number + 1] if number + 1 < len(headings) else len(text)
            self.add(exercise, _section_text(text[heading.end():end]), source)

    # -------------------------------------------------------------- notebooks
    def notebook(self, data: bytes, source: str) -> None:
        if len(data) > MAX_REPORT_BYTES:
            self.problem(f"{source} is larger than {MAX_REPORT_BYTES >> 20} MiB; its explanations were not read")
            return
        try:
            notebook = json.loads(_decoded(data))
        except (ValueError, RecursionError):
            self.problem(f"{source} is not a readable notebook (not valid JSON); its explanations were not read")
            return
        cells = notebook.get("cells") if isinstance(notebook, dict) else None
        if not isinstance(cells, list):
            self.problem(f"{source} has no list of cells; its explanations were not read")
            return
        read = 0
        plain: list[str] = []      # the Markdown cells with no tag or marker, for the student's own headings
        starts: list[int] = []     # where each of them starts in "\n\n".join(plain)
        numbers: list[int] = []
        marks: list[tuple[int, str]] = []   # (cell number, exercise) where an exercise's text begins
        for number, cell in enumerate(cells, 1):
            if isinstance(cell, dict) and cell.get("cell_type") == "markdown":
                if read == MAX_REPORT_CELLS:
                    self.problem(f"{source} holds more than {MAX_REPORT_CELLS:,} Markdown cells; cell {number} "
                                 "and those after it were not read")
                    break
                read += 1
                text, exercise = self._markdown_cell(cell, f"{source}, cell {number}")
                if exercise:
                    marks.append((number, exercise))
                if text is not None:
                    starts.append(starts[-1] + len(plain[-1]) + 2 if plain else 0)
                    plain.append(text)
                    numbers.append(number)
        cell_at = lambda at: numbers[bisect.bisect_right(starts, at) - 1]  # noqa: E731
        if plain and self.names is not None:
            sections = self.own_headings("\n\n".join(plain), source, lambda at: f"{source}, cell {cell_at(at)}")
            marks += [(cell_at(section.start), section.exercise) for section in sections]
        if self.reader is not None:
            self.notebook_figures(notebook, source, marks)

    def _markdown_cell(self, cell: dict, where: str) -> tuple[str | None, str | None]:
        """Read one Markdown cell: (its text when it holds no tag or marker, else None; the
        exercise it is tagged or marked for, the first one, or None)."""
        text = _cell_text(cell.get("source"))
        if text is None:
            self.problem(f"{where}: its text is not text; it was not read")
            return None, None
        text = printable(text)
        metadata = cell.get("metadata")
        tags = metadata.get("tags") if isinstance(metadata, dict) else None
        tagged: dict[str, None] = {}   # in order, each once (a dict: a list's `in` was quadratic in the tags)
        for tag in tags if isinstance(tags, list) else ():
            if isinstance(tag, str) and tag.lower().startswith(REPORT_TAG_PREFIX):
                exercise = exercise_id(tag[len(REPORT_TAG_PREFIX):])
                if exercise:
                    tagged.setdefault(exercise)
        tagged = list(tagged)
        marked = list(dict.fromkeys(filter(None, (exercise_id(m.group(1)) for m in _START.finditer(text)))))
        if len(tagged) > 1:
            self.problem(f"{where} is tagged for {len(tagged)} exercises ({', '.join(tagged[:4])}); "
                         f"it counts for {tagged[0]}")
        if tagged:
            self.add(tagged[0], _without_markers(text), where)
        elif len(marked) == 1:
            self.add(marked[0], _without_markers(text), where)
        elif len(marked) > 1:
            self.markdown(text, where, notebook_cell=True)
        else:
            return text, None
        return None, (tagged or marked)[0]


# ------------------------------------------------------------------ helpers
PAGE_TEXT_CHARS = 80     # a section's text on a page it does not start on, for its pictures to be its


def _exercises_on_page(pdf, sections: list, page: int) -> list[str]:
    """The exercises a picture on ``page`` of ``pdf`` belongs to: those whose section starts on
    that page or holds at least :data:`PAGE_TEXT_CHARS` of its text (a section's tail over the
    next page's running header is not enough); else every section over the page."""
    text, starts, at = pdf.text, [], 0
    for page_text in pdf.pages:
        starts.append(at)
        at += len(page_text) + 1
    if not 1 <= page <= len(starts):
        return []
    first, last = starts[page - 1], starts[page] if page < len(starts) else len(text)
    over, owning = [], []
    for section in sections:
        end = text.find(section.body, section.start) + len(section.body)
        share = text[max(section.start, first):min(end, last)].strip()
        if share:
            over.append(section.exercise)
            if first <= section.start < last or len(share) >= PAGE_TEXT_CHARS:
                owning.append(section.exercise)
    return owning or over


def _decoded(data: bytes) -> str:
    return data.decode("utf-8", errors="replace").removeprefix("\ufeff")


def _cell_text(source) -> str | None:
    if isinstance(source, str):
        return source
    if isinstance(source, list) and all(isinstance(line, str) for line in source):
        return "".join(source)
    return None


def _headings(text: str, most: int | None = None) -> list[re.Match]:
    """The level 1 and 2 headings of ``text`` outside fenced code blocks (the first ``most``)."""
    fences = [m.start() for m in _FENCE.finditer(text)]
    return list(islice((m for m in _HEADING.finditer(text) if _fences_before(fences, m.start()) % 2 == 0), most))


def _fences_before(fences: list[int], position: int) -> int:
    return bisect.bisect_left(fences, position)


def _first_after(positions: list[int], after: int, default: int) -> int:
    index = bisect.bisect_left(positions, after)
    return positions[index] if index < len(positions) else default


def _section_text(body: str) -> str:
    """The text under a heading without the scaffold's lines: figures, verdict, "No figure"."""
    body = _FIGURE_LINE.sub("", body)
    return _NO_FIGURE_LINE.sub("", VERDICT_LINE.sub("", body))


def _without_markers(text: str) -> str:
    """``text`` without explanation markers (each with the line break after it)."""
    return _MARKER_LINE.sub("", text)


def _cleaned(text: str) -> str:
    """An explanation's text: markers and the placeholder removed, blank edges trimmed."""
    return _without_markers(text).replace(PLACEHOLDER, "").strip()
