"""What anonymous review (``autograder review --anonymous``) shows of one student.

Three kinds of text about a student reach the review screen, and each is made
anonymous its own way:

- **the files they handed in** (``jdoe_s2231234_lab07_report.pdf``): never shown;
  each is a neutral label, ``report 1 (PDF)``, numbered in the order of the
  student's kept files (so a PDF's download link and its mention in a problem agree),
  then in the order the problems name more;
- **the problems found reading their report**: sentences the grader wrote around
  file names the student chose. They are not redacted but *rewritten*: each is
  matched, whole, against the grader's sentence templates (:data:`_PROBLEMS`) and
  written again from a fixed vocabulary, with labels for the files, and only
  exercise ids and numbers taken from it. A sentence that matches no template is
  shown as :data:`UNKNOWN_PROBLEM`: what anonymous mode shows is safe by
  construction, whatever a file is named;
- **free text** (the explanation they wrote, a check's message): their known file
  names become labels, and every form of their identities (:func:`identities`: id,
  names, e-mails, LMS ids, group members', the upload item's name) becomes their
  pseudonym, in any case, composed or decomposed Unicode, with or without accents,
  the parts of a name in any order joined by nothing, ``_``, ``-``, ``.`` or a space.
  A word is a whole word when it is not continued by another letter (for a word
  ending in a letter) or digit (ending in a digit): ``s2231234lab07`` and
  ``jane_doe`` hold names, ``remark`` does not hold "Mark". A text naming the
  student in a way nobody knows (a nickname) cannot be caught.
"""

from __future__ import annotations

import functools
import itertools
import re
import unicodedata
from pathlib import PurePosixPath
from urllib.parse import quote

UNKNOWN_PROBLEM = ("a problem was found reading the report (its sentence names files: "
                   "run without --anonymous to read it)")
_KINDS = {".pdf": "PDF", ".md": "Markdown", ".ipynb": "notebook", ".zip": "zip", ".py": "Python"}
_EXERCISE = r"lab\d\d\.[a-z]+\d+(?:-[a-z]+)?"
_NUMBER = r"\d[\d,.]{0,12}"
_CELL = re.compile(r"^(.*?)(, cell \d{1,9})?$", re.DOTALL)
_SEPARATORS = ("", "_", "-", ".", " ")

# The grader's sentences about a report (loading/report.py, batch/tree.py, batch/ingest.py), matched
# whole: "file" and "source(s)" become labels; "ex" (an exercise id), "n" (a number) and "why" (the
# reasons below) are all that is taken from the sentence.
_PROBLEMS = [(re.compile(pattern, re.DOTALL), text) for pattern, text in (
    (r"(?P<file>.+) was not read: (?P<why>.*)", "{file} was not read: {why}"),
    (rf"(?P<file>.+) is {_NUMBER} MiB, larger than the (?P<n>{_NUMBER}) MiB a report may be; it was not read.*",
     "{file} is larger than the {n} MiB a report may be; it was not read"),
    (rf"(?P<file>.+) is larger than (?P<n>{_NUMBER}) MiB; its explanations were not read",
     "{file} is larger than {n} MiB; its explanations were not read"),
    (r"(?P<file>.+) is not a readable notebook \(not valid JSON\); its explanations were not read",
     "{file} is not a readable notebook (not valid JSON); its explanations were not read"),
    (r"(?P<file>.+) has no list of cells; its explanations were not read",
     "{file} has no list of cells; its explanations were not read"),
    (r"(?P<file>.+) could not be read", "{file} could not be read"),
    (rf"(?P<file>.+): more than (?P<n>{_NUMBER}) exercises explained; (?P<ex>{_EXERCISE}) and those after it "
     "were not read", "{file}: more than {n} exercises explained; {ex} and those after it were not read"),
    (r"(?P<file>.+): a marker names .*, which is no exercise \(they look like lab07\.ex1\)",
     "{file}: a marker names something that is no exercise (they look like lab07.ex1)"),
    (rf"(?P<file>.+): the explanation of (?P<ex>{_EXERCISE}) has no '<!-- end explanation -->'; it was read up "
     "to the next section", "{file}: the explanation of {ex} has no '<!-- end explanation -->'; "
                            "it was read up to the next section"),
    (r"(?P<file>.+): its text is not text; it was not read", "{file}: its text is not text; it was not read"),
    (rf"(?P<file>.+) is tagged for (?P<n>{_NUMBER}) exercises \(.*\); it counts for (?P<ex>{_EXERCISE})",
     "{file} is tagged for {n} exercises; it counts for {ex}"),
    (rf"(?P<ex>{_EXERCISE}) is explained twice \((?P<sources>.+)\); both texts are kept, one after the other",
     "{ex} is explained twice ({sources}); both texts are kept, one after the other"),
    (rf"the explanation of (?P<ex>{_EXERCISE}) \((?P<sources>.+)\) is longer than (?P<n>{_NUMBER}) characters; "
     "the rest was cut", "the explanation of {ex} ({sources}) is longer than {n} characters; the rest was cut"),
    (rf"(?P<ex>{_EXERCISE}) is explained in more than (?P<n>{_NUMBER}) places; the text at (?P<sources>.+) and "
     "after it was not read", "{ex} is explained in more than {n} places; the text at {sources} and after it "
                              "was not read"),
    (rf"(?P<file>.+) holds more than (?P<n>{_NUMBER}) explanation markers or headings; what follows the first "
     rf"(?P<m>{_NUMBER}) was not read", "{file} holds more than {n} explanation markers or headings; what follows "
                                        "the first {m} was not read"),
    (rf"(?P<file>.+) holds more than (?P<n>{_NUMBER}) Markdown cells; cell (?P<m>\d+) and those after it were not "
     "read", "{file} holds more than {n} Markdown cells; cell {m} and those after it were not read"),
    (rf"and (?P<n>{_NUMBER}) more problems like these", "and {n} more problems like these"),
    (rf"and (?P<n>{_NUMBER}) more files were not read", "and {n} more files were not read"),
    (r"the report could not be read \(\w+\)", "the report could not be read"),
    (r"(?P<file>.+): the heading .* names an exercise by number but not its lab; name the lab in the file's name "
     r"\(lab07_report\.md\) or a heading \(# Lab 7\)", "{file}: a heading names an exercise by number but not its "
                                                        "lab; name the lab in the file's name (lab07_report.md) or a "
                                                        "heading (# Lab 7)"),
    (r"(?P<file>.+): the PDF's text could not be read: (?P<pdf_why>.*)",
     "{file}: the PDF's text could not be read: {pdf_why}"),
)]
# Why a PDF's text could not be read (sandbox/report_reader.py, loading/pdf_report.py): a parser's own
# words (which may quote the file) are never taken.
_PDF_REASONS = [(re.compile(pattern, re.DOTALL), text) for pattern, text in (
    (r"it is encrypted.*", "it is encrypted (protected by a password)"),
    (r"it is not a PDF\b.*", "it is not a PDF"),
    (r"it is not a readable PDF.*", "it is not a readable PDF"),
    (r"it holds no text.*", "it holds no text (scanned pages or pictures only?)"),
    (r"(?:its pages cannot be found|it has no pages|the text of its pages cannot be read).*", "its pages cannot be read"),
    (r"its objects are nested too deeply.*|its page tree is nested too deeply.*", "its objects are nested too deeply"),
    (rf"reading it took longer than (?P<n>{_NUMBER}) seconds", "reading it took longer than {n} seconds"),
    (rf"reading it needed more than (?P<n>{_NUMBER}) MiB of memory", "reading it needed more than {n} MiB of memory"),
    (rf"it is {_NUMBER} MiB, more than the (?P<n>{_NUMBER}) MiB read", "it is larger than the {n} MiB read"),
)]
# Why a file was refused (batch/tree.py, sandbox/files.py): a reason naming another of the student's
# files ("the archive holds X twice") is said without it.
_REASONS = [(re.compile(pattern, re.DOTALL), text) for pattern, text in (
    (r"it is a symbolic link.*", "it is a symbolic link"),
    (r"it is not a regular file \((?P<kind>a named pipe|a socket|a character device|a block device)\)",
     "it is not a regular file ({kind})"),
    (r"it is not a regular file.*", "it is not a regular file"),
    (rf"it is larger than (?P<n>{_NUMBER}) MiB", "it is larger than {n} MiB"),
    (rf"it unpacks to more than (?P<n>{_NUMBER}) MiB", "it unpacks to more than {n} MiB"),
    (r"it unpacks to more than it declares", "it unpacks to more than it declares"),
    (r"it is not a PDF \(it does not begin with %PDF-\)", "it is not a PDF (it does not begin with %PDF-)"),
    (r"it is encrypted.*", "it is encrypted; zip it without a password"),
    (r"its name (?P<what>is not valid UTF-8|holds control characters|points outside the submission)"
     r"(?:; rename it)?", "its name {what}"),
    (rf"a name in its path is longer than (?P<n>{_NUMBER}) bytes; shorten it",
     "a name in its path is longer than {n} bytes; shorten it"),
    (rf"it is more than (?P<n>{_NUMBER}) folders deep", "it is more than {n} folders deep"),
    (rf"more than (?P<n>{_NUMBER}) report files; the rest was not read", "more than {n} report files; "
                                                                          "the rest was not read"),
    (r"more report files than are kept; not read", "more report files than are kept; not read"),
    (r"the upload holds it twice", "the upload holds it twice"),
    (r"the archive holds a file and a folder both named .*", "the archive holds a file and a folder of one name"),
    (r"the archive holds .* twice", "the archive holds it twice"),
    (r".* holds a file of the same name", "a zip beside it holds a file of the same name"),
    (r"it cannot be (?P<how>read|unpacked|listed)\b.*", "it cannot be {how}"),
    (r"its name cannot be opened", "its name cannot be opened"),
)]


def identities(student: dict) -> list[str]:
    """What names a student (``Gradebook.class_results``'s dict): their id, names, e-mails, LMS
    ids, their group members', and each word of them (of an e-mail, the words before the ``@``:
    the domain is everybody's; not a lab's name, ``lab07``, which a folder's name may hold); the
    item they came in as, whole. Numbers shorter than 5 digits are no identity (a message's
    "expected 3 corners")."""
    members = student.get("members") or []
    origin = str(student.get("origin") or "")
    values = [student.get("student_id"), student.get("display_name"), *(student.get("lms") or {}).values(),
              *(v for m in members if isinstance(m, dict) for v in m.values())]
    values = [str(v).strip() for v in values if isinstance(v, (str, int)) and str(v).strip()]
    words = values + [w for w in (origin, PurePosixPath(origin).stem) if w.strip()]
    for value in values:
        parts = [p for p in re.split(r"[\s&,._+'-]+", value.split("@")[0])
                 if len(p) >= 2 and not re.fullmatch(r"(?i)lab\d\d\w*", p)]
        words += parts
        if 1 < len(parts) <= 3:   # the parts of a name run together, in any order: JaneDoe, doe_jane
            words += [sep.join(order) for order in itertools.permutations(parts) for sep in _SEPARATORS]
    return [w for w in dict.fromkeys(words) if not (w.isdigit() and len(w) < 5)]


def _forms(word: str) -> set[str]:
    """``word`` as a file system, a keyboard or a case change may have written it."""
    forms = {unicodedata.normalize(f, word) for f in ("NFC", "NFD", "NFKC")} | {word.casefold(), word.upper()}
    plain = "".join(c for c in unicodedata.normalize("NFKD", word) if not unicodedata.combining(c))
    forms |= {plain, plain.casefold()}
    return forms | {quote(form, safe="") for form in forms}   # in a link the student wrote


def _whole(word: str) -> str:
    """A pattern of ``word`` not continued by a letter (where it begins or ends with one) or a digit."""
    def edge(char: str) -> str:
        return r"[^\W\d_]" if char.isalpha() else r"\d" if char.isdigit() else r"(?!)"
    return f"(?<!{edge(word[0])}){re.escape(word)}(?!{edge(word[-1])})"


class Anonymiser:
    """Anonymous mode's view of one student (see the module doc).

    ``student``: their ``Gradebook.class_results`` dict; ``files``: the paths of the report
    files kept for them (labelled first, sorted); ``pseudonym``: what their names become.
    """

    def __init__(self, student: dict, files, pseudonym: str):
        self.pseudonym = pseudonym
        self.labels: dict[str, str] = {}
        for name in sorted(files):
            self.label(name)
        forms = {form for word in identities(student) for form in _forms(word) if form.strip()}
        self._forms = sorted(((form, form.casefold()) for form in forms), key=lambda f: -len(f[0]))

    def label(self, name: str) -> str:
        """``name`` (a file's path) as ``report N (KIND)``: the same name, the same label."""
        if name not in self.labels:
            kind = _KINDS.get(PurePosixPath(name.strip()).suffix.lower(), "file")
            self.labels[name] = f"report {len(self.labels) + 1} ({kind})"
        return self.labels[name]

    def sources(self, text: str) -> str:
        """An explanation's source (``a.md; b.ipynb, cell 3``) with labels for the files."""
        parts = []
        for piece in text.split("; "):
            name, cell = _CELL.match(piece).groups()
            parts.append(self.label(name) + (cell or ""))
        return "; ".join(parts)

    def text(self, text: str) -> str:
        """Free text about the student: their known files as labels, their identities as the pseudonym."""
        for name in sorted(self.labels, key=len, reverse=True):
            if len(name) >= 3:
                text = text.replace(name, self.labels[name])
        # One alternation of every form (hundreds) costs seconds on a long explanation: only the
        # forms that occur at all, case aside, are looked for where they are whole.
        folded = text.casefold()
        present = tuple(form for form, fold in self._forms if fold in folded)
        return _pattern(present).sub(self.pseudonym, text) if present else text

    def problem(self, sentence: str) -> str:
        """A problem of the report, rewritten from the templates (see the module doc)."""
        for pattern, template in _PROBLEMS:
            match = pattern.fullmatch(sentence)
            if match:
                fields = match.groupdict()
                if "file" in fields:
                    fields["file"] = self.sources(fields["file"])
                if "sources" in fields:
                    fields["sources"] = self.sources(fields["sources"])
                if "why" in fields:
                    fields["why"] = _reason(fields["why"])
                if "pdf_why" in fields:
                    fields["pdf_why"] = _reason(fields["pdf_why"], _PDF_REASONS)
                return template.format(**fields)
        return UNKNOWN_PROBLEM


@functools.lru_cache(maxsize=256)
def _pattern(forms: tuple[str, ...]) -> re.Pattern:
    """``forms`` (longest first) as one pattern, each whole (see :func:`_whole`), case aside."""
    return re.compile("|".join(_whole(form) for form in forms), re.IGNORECASE)


def _reason(why: str, reasons=None) -> str:
    for pattern, template in reasons or _REASONS:
        match = pattern.fullmatch(why)
        if match:
            return template.format(**match.groupdict())
    return "it could not be read"
