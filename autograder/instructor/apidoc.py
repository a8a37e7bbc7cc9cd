"""The assignment API of every lab, generated so that it cannot drift from the code.

Two sources are read, neither is run: the skeletons (``assignments/labNN_*.py``:
each module's docstring, each function's signature and docstring, read with
``ast``) and the registry (:func:`autograder.engine.registry.discover`: labs, exercises,
the functions each grades, public checks and their points, forbidden calls).
Hidden checks are left out of everything written here: their names, number and
points are the instructor's.

Two kinds of page come out, under the documentation folder ``DOCS``:

- ``DOCS/api/labNN.md``, written whole: the lab's conventions, its exercises,
  and every function with its signature and docstring.
- blocks inside hand-written pages (``DOCS/contract/*.md``), between
  ``<!-- apidoc:begin KEY -->`` and ``<!-- apidoc:end -->``: ``KEY`` is an
  exercise (``lab07.ex1``: its functions, points, checks and rules) or ``labs``
  (the table of labs). Every exercise of a lab with a page ``contract/labNN.md``
  must have its block there, so a new exercise cannot go undescribed.

``python -m autograder.instructor.apidoc [DOCS]`` writes them (default: ``docs`` beside the
package); ``--check`` writes nothing and exits 1 naming the pages that differ
from what the code says (the test suite runs the same comparison).
"""

from __future__ import annotations

import argparse
import ast
import re
import sys
import unicodedata
from dataclasses import dataclass
from pathlib import Path

from ..loading.parsing import parse

PROJECT_ROOT = Path(__file__).resolve().parents[2]
GENERATOR = "python -m autograder.instructor.apidoc docs"

_BLOCK = re.compile(r"(<!-- apidoc:begin (?P<key>[\w.]+) -->\n)(?P<body>.*?)(<!-- apidoc:end -->)", re.S)


def _parse(text: str, filename: str = "<unknown>", mode: str = "exec"):
    """The project's own text parsed under the grader's parse lock (no size bounds)."""
    return parse(text, filename, mode, max_chars=None, max_statements=None)


class ApidocError(ValueError):
    """The skeletons, the registry and the hand-written pages disagree."""


# ---------------------------------------------------------------------------------- reading
@dataclass(frozen=True)
class Function:
    """One function of a skeleton, as written there."""

    name: str
    parameters: str  # "image, tx=100, ty=50"
    docstring: str

    @property
    def signature(self) -> str:
        return f"{self.name}({self.parameters})"


@dataclass(frozen=True)
class Skeleton:
    """A lab's skeleton module: its docstring and its public functions, in file order."""

    module: str
    path: Path
    docstring: str
    functions: dict[str, Function]


def read_skeleton(path: Path) -> Skeleton:
    """Read ``path`` with ``ast`` (never imported: a skeleton may import anything)."""
    tree = _parse(path.read_text(encoding="utf-8"), filename=str(path))
    functions = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
            functions[node.name] = Function(node.name, ast.unparse(node.args), ast.get_docstring(node) or "")
    return Skeleton(path.stem, path, ast.get_docstring(tree) or "", functions)


@dataclass(frozen=True)
class Entry:
    """One public check as the contract states it."""

    name: str
    points: float
    advice: bool


@dataclass(frozen=True)
class ExerciseFacts:
    key: str
    id: str
    title: str
    signatures: dict[str, str]  # function -> the signature the registry declares (as called)
    checks: tuple[Entry, ...]

    @property
    def points(self) -> float:
        return sum(entry.points for entry in self.checks)


@dataclass(frozen=True)
class LabFacts:
    key: str
    module: str
    title: str
    exercises: tuple[ExerciseFacts, ...]
    forbidden: dict[str, tuple[str, ...]]
    skeleton: Skeleton

    @property
    def points(self) -> float:
        return sum(exercise.points for exercise in self.exercises)

    @property
    def number(self) -> int:
        return int(self.key[3:])

    def first_exercise_of(self, function: str) -> ExerciseFacts:
        return next(exercise for exercise in self.exercises if function in exercise.signatures)


def lab_facts(skeletons: Path | None = None) -> list[LabFacts]:
    """Every registered lab that has a skeleton in ``skeletons``, public checks only, by key.

    Raises :class:`ApidocError` where the registry names a function the skeleton
    lacks, or a parameter its definition does not have.
    """
    from ..engine.registry import discover

    folder = Path(skeletons) if skeletons is not None else PROJECT_ROOT / "assignments"
    labs = []
    for lab in sorted(discover().values(), key=lambda lab: lab.key):
        path = folder / f"{lab.module}.py"
        if not path.is_file():
            continue  # a plug-in lab documents itself
        skeleton = read_skeleton(path)
        exercises = []
        for exercise in lab.exercises.values():
            checks = tuple(Entry(check.name, check.points, check.advice)
                           for check in exercise.checks if not check.hidden)
            if not checks:
                continue
            for function, signature in exercise.signatures.items():
                _agrees(lab.key, exercise.key, signature, skeleton, function)
            exercises.append(ExerciseFacts(exercise.key, exercise.id, exercise.title,
                                           dict(exercise.signatures), checks))
        labs.append(LabFacts(lab.key, lab.module, lab.title, tuple(exercises), dict(lab.forbidden), skeleton))
    return labs


def _agrees(lab: str, exercise: str, signature: str, skeleton: Skeleton, function: str) -> None:
    """The registry's ``signature`` names a function of the skeleton, with parameters it has."""
    if function not in skeleton.functions:
        raise ApidocError(f"{lab}.{exercise} grades {function}(), which {skeleton.path.name} does not define")
    try:
        call = _parse(signature, mode="eval").body
    except SyntaxError:
        raise ApidocError(f"{lab}.{exercise}: cannot read the signature {signature!r}") from None
    defined = _parse(f"def {skeleton.functions[function].signature}: pass").body[0].args
    names = [a.arg for a in defined.posonlyargs + defined.args + defined.kwonlyargs]
    used = [a.id for a in getattr(call, "args", []) if isinstance(a, ast.Name)]
    used += [k.arg for k in getattr(call, "keywords", []) if k.arg]
    unknown = [name for name in used if name not in names]
    if unknown:
        raise ApidocError(f"{lab}.{exercise} declares {signature}, but {skeleton.path.name} defines "
                          f"{skeleton.functions[function].signature}: no parameter {', '.join(unknown)}")


# ---------------------------------------------------------------------------------- Markdown
def slug(heading: str) -> str:
    """The anchor Python-Markdown's table of contents (and GitHub) give a heading."""
    text = unicodedata.normalize("NFKD", heading).encode("ascii", "ignore").decode()
    text = re.sub(r"[^\w\s-]", "", text).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


_ROLE = re.compile(r":[a-z]+:`~?([^`]+)`")                  # :func:`name` -> `name`
_LITERAL = re.compile(r"``(.+?)``|`([^`]+)`", re.S)         # ``code`` / `code`
_EMPHASIS = re.compile(r"(?<![\w*])(\*\*?)(?=\S)(.+?)(?<=\S)\1(?![\w*])", re.S)


def inline(text: str) -> str:
    """One line of reStructuredText, as Markdown that shows the same words.

    Literals become code spans; ``*emphasis*`` and ``**strong**`` stay; every
    other character Markdown would read as markup (``*``, ``_`` at a word's edge,
    ``#``, a ``]`` that would open a link, ``<``, ``&``, a backslash) is escaped, so
    ``w**4`` or ``<mistake>`` print as written.
    """
    text = _ROLE.sub(r"``\1``", text)
    out, last = [], 0
    for match in _LITERAL.finditer(text):
        out.append(_plain(text[last:match.start()]))
        code = match.group(1) if match.group(1) is not None else match.group(2)
        fence = "``" if "`" in code else "`"
        pad = " " if code.startswith("`") or code.endswith("`") else ""
        out.append(f"{fence}{pad}{code}{pad}{fence}")
        last = match.end()
    out.append(_plain(text[last:]))
    return "".join(out)


def _plain(text: str) -> str:
    out, last = [], 0
    for match in _EMPHASIS.finditer(text):
        out.append(_escape(text[last:match.start()]))
        out.append(f"{match.group(1)}{_escape(match.group(2))}{match.group(1)}")
        last = match.end()
    out.append(_escape(text[last:]))
    return "".join(out)


def _escape(text: str) -> str:
    text = text.replace("\\", "\\\\")
    text = re.sub(r"&(?=#|\w+;)", "&amp;", text)          # what would read as an entity
    text = re.sub(r"<(?=[A-Za-z/!?])", "&lt;", text)      # what would read as a tag
    text = re.sub(r"([*`#])", r"\\\1", text)
    text = re.sub(r"\](?=\s*[(\[])", r"\\]", text)  # "[R | t] (...)" must not read as a link
    return re.sub(r"(?<!\w)_|_(?!\w)", r"\\_", text)  # inside a word, _ is no markup


_SECTION_RULE = re.compile(r"-{3,}\s*$")
_ITEM = re.compile(r"(?:[-*]|\d+\.)\s")
_FIELD_SECTIONS = {"Parameters", "Returns", "Yields", "Raises", "Other Parameters", "Attributes"}


def docstring_markdown(text: str, heading: str = "####") -> str:
    """A NumPy-style docstring as Markdown.

    Sections (a title underlined with dashes) become ``heading`` titles; the
    entries of Parameters/Returns/Raises (``name : type`` then an indented
    description) become a list; ``::`` blocks and ``>>>`` examples become code
    blocks; paragraphs and lists keep their words and line breaks.
    """
    lines = text.expandtabs().splitlines()
    out: list[str] = []
    section = ""
    i = 0
    while i < len(lines):
        line = lines[i]
        if _section_title(lines, i):
            section = line.strip()
            out += ["", f"{heading} {_plain(section)}", ""]
            i += 2
            continue
        if section in _FIELD_SECTIONS and _at_margin(line):
            j = i + 1
            while j < len(lines) and (not lines[j].strip() or lines[j].startswith(" ")):
                j += 1
            description = _dedent(lines[i + 1:j])
            out += ["", f"- {_field(line)}"]
            if description:
                out += [""] + ["    " + row if row else "" for row in _blocks(description)]
            i = j
            continue
        j = i + 1  # free text, up to the next section (or, in a field section, the next entry)
        while j < len(lines) and not _section_title(lines, j) \
                and not (section in _FIELD_SECTIONS and _at_margin(lines[j])):
            j += 1
        out += _blocks(lines[i:j])
        i = j
    return _tidy(out)


def _at_margin(line: str) -> bool:
    return bool(line.strip()) and not line.startswith(" ")


def _section_title(lines: list[str], i: int) -> bool:
    """Whether ``lines[i]`` is a section's title: at the margin, underlined with dashes."""
    return i + 1 < len(lines) and _at_margin(lines[i]) and bool(_SECTION_RULE.fullmatch(lines[i + 1].strip()))


def _field(line: str) -> str:
    """``name : type`` (or a bare type) as a list item's first line."""
    name, colon, kind = line.partition(" : ")
    if not colon:
        return inline(line.strip())
    names = ", ".join(f"`{n.strip()}`" for n in name.split(","))
    return f"{names}: {inline(kind.strip())}"


def _dedent(lines: list[str]) -> list[str]:
    widths = [len(line) - len(line.lstrip()) for line in lines if line.strip()]
    cut = min(widths, default=0)
    return [line[cut:] for line in lines]


def _blocks(lines: list[str]) -> list[str]:
    """Paragraphs, lists, ``::`` literal blocks and ``>>>`` examples of one stretch of text."""
    out: list[str] = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if not line.strip():
            out.append("")
            i += 1
        elif line.lstrip().startswith(">>>"):
            j = i
            while j < len(lines) and lines[j].strip():
                j += 1
            out += ["", "```pycon", *_dedent(lines[i:j]), "```", ""]
            i = j
        else:
            j = i
            while j < len(lines) and lines[j].strip() and not lines[j].lstrip().startswith(">>>"):
                j += 1
            paragraph = lines[i:j]
            literal = paragraph[-1].rstrip().endswith("::")
            if literal:
                last = paragraph[-1].rstrip()[:-2].rstrip()
                paragraph = paragraph[:-1] + ([last + ":"] if last else [])
            units = _units(paragraph)
            if units and units[0][0] and out and out[-1] != "":
                out.append("")  # a list needs a blank line before it
            for k, (marker, rows) in enumerate(units):
                if k and marker and not units[k - 1][0]:
                    out.append("")
                if not marker and k and units[k - 1][0]:
                    out.append("")  # text after a list is a paragraph of its own
                text = inline("\n".join(rows)).split("\n")
                if marker:
                    pad = " " * (len(marker) + 1)
                    out += [f"{marker} {text[0]}"] + [pad + row for row in text[1:]]
                else:
                    out += text
            i = j
            if literal:
                while i < len(lines) and not lines[i].strip():
                    i += 1
                k = i
                while k < len(lines) and (not lines[k].strip() or lines[k].startswith(" ")):
                    k += 1
                block = _dedent(lines[i:k])
                while block and not block[-1].strip():
                    block.pop()
                out += ["", "```text", *block, "```", ""]
                i = k
    return out


def _units(paragraph: list[str]) -> list[tuple[str, list[str]]]:
    """A paragraph's lines as (list marker or "", stripped lines): one unit per list item,
    with its continuation lines, so that markup spanning lines is read whole."""
    units: list[tuple[str, list[str]]] = []
    for row in paragraph:
        item = _ITEM.match(row)  # a list item starts at the margin; indented lines continue
        if item:
            units.append((item.group(0).strip(), [row[item.end():].strip()]))
        elif units:
            units[-1][1].append(row.strip())
        else:
            units.append(("", [row.strip()]))
    return units


def _tidy(lines: list[str]) -> str:
    """Join lines, with single blank lines between blocks and none at either end."""
    text = "\n".join(line.rstrip() for line in lines)
    text = re.sub(r"\n{3,}", "\n\n", text)
    return text.strip("\n") + "\n"


def _points(value: float) -> str:
    return f"{value:g}"


def _code(text: str) -> str:
    fence = "``" if "`" in text else "`"
    return f"{fence}{text}{fence}"


# ---------------------------------------------------------------------------------- pages
def api_page(lab: LabFacts) -> str:
    """``api/labNN.md``: conventions, exercises, and every function of the skeleton."""
    skeleton = lab.skeleton
    title, _, rest = skeleton.docstring.partition("\n")
    out = [f"# Lab {lab.number} API: `{lab.module}.py`", "",
           f"<!-- Generated by `{GENERATOR}` from assignments/{lab.module}.py and the registry. "
           "Do not edit: edit the skeleton's docstrings or the lab suite, then run it again. -->", "",
           f"{_plain(lab.title)}. Your work goes in `{lab.module}.py` (or the notebook "
           f"`{lab.module}.ipynb`); what each exercise asks, in words, is in "
           f"[Lab {lab.number}: what it asks](../contract/{lab.key}.md).", "",
           "## About the module", "",
           docstring_markdown(rest.strip("\n"), heading="###").rstrip(), "",
           "## Exercises", "",
           "| exercise | functions | public points | checks |", "|---|---|---|---|"]
    for exercise in lab.exercises:
        functions = ", ".join(f"[`{name}`](#{slug(name)})" for name in exercise.signatures)
        graded = sum(1 for entry in exercise.checks if not entry.advice)
        tips = len(exercise.checks) - graded
        checks = f"{graded}" + (f" + {tips} tip{'s' * (tips > 1)}" if tips else "")
        out.append(f"| [{exercise.key}: {_plain(exercise.title)}](#{slug(_exercise_heading(exercise))}) "
                   f"| {functions} | {_points(exercise.points)} | {checks} |")
    out += ["", f"Public points in all: {_points(lab.points)}. Your instructor may also run hidden "
            "checks, on the same functions and the same contract.", ""]
    documented: set[str] = set()
    for exercise in lab.exercises:
        out += [f"## {_exercise_heading(exercise)}", ""]
        out += _exercise_facts(lab, exercise, link_functions=False)
        for name in exercise.signatures:
            if name in documented:
                continue
            documented.add(name)
            function = skeleton.functions[name]
            out += [f"### {name}", "", "```python", f"def {function.signature}: ...", "```", ""]
            out += [docstring_markdown(function.docstring, heading="####").rstrip(), ""]
    others = [f for f in skeleton.functions if f not in documented]
    if others:
        out += ["## Other functions of the skeleton", "",
                "Not graded on their own; the graded functions may use them.", ""]
        for name in others:
            function = skeleton.functions[name]
            out += [f"### {name}", "", "```python", f"def {function.signature}: ...", "```", "",
                    docstring_markdown(function.docstring, heading="####").rstrip(), ""]
    return _tidy(out)


def _exercise_heading(exercise: ExerciseFacts) -> str:
    return f"{exercise.key}: {exercise.title}"


def _exercise_facts(lab: LabFacts, exercise: ExerciseFacts, link_functions: bool) -> list[str]:
    """Functions (as the exercise calls them), forbidden calls, and the public checks with points."""
    out = []
    for name, signature in exercise.signatures.items():
        first = lab.first_exercise_of(name)
        where = f"../api/{lab.key}.md#{slug(name)}" if link_functions else f"#{slug(name)}"
        defined = lab.skeleton.functions[name].signature
        shown = f"`{signature}`" if _same(signature, defined) else f"`{signature}` (defined as `{defined}`)"
        note = "" if first is exercise or link_functions else f", documented under {first.key}"
        out.append(f"- graded function: [{shown}]({where}){note}")
    for name in exercise.signatures:
        calls = lab.forbidden.get(name, ())
        if calls and lab.first_exercise_of(name) is exercise:
            listed = ", ".join(_code(call) for call in calls)
            out.append(f"- not allowed inside `{name}`: {listed} (the exercise asks for your own "
                       "implementation; calling one of them fails the check)")
    out += ["", f"Public checks ({_points(exercise.points)} points):", ""]
    for entry in exercise.checks:
        worth = "tip, no points" if entry.advice else f"{_points(entry.points)} point{'s' * (entry.points != 1)}"
        out.append(f"- {_plain(entry.name)} ({worth})")
    out.append("")
    return out


def _same(signature: str, other: str) -> bool:
    """Whether two signatures say the same (``method="sift"`` is ``method='sift'``)."""
    try:
        return ast.unparse(_parse(signature, mode="eval")) == ast.unparse(_parse(other, mode="eval"))
    except SyntaxError:
        return signature == other


def labs_table(labs: list[LabFacts]) -> str:
    """The ``labs`` block: one row per lab."""
    out = ["| lab | module | exercises | public points | API | what it asks |", "|---|---|---|---|---|---|"]
    for lab in labs:
        keys = ", ".join(exercise.key for exercise in lab.exercises)
        out.append(f"| {lab.key}: {_plain(lab.title)} | `{lab.module}.py` | {keys} | {_points(lab.points)} "
                   f"| [API](../api/{lab.key}.md) | [Lab {lab.number}]({lab.key}.md) |")
    return "\n".join(out) + "\n"


def exercise_block(lab: LabFacts, exercise: ExerciseFacts) -> str:
    return _tidy(_exercise_facts(lab, exercise, link_functions=True))


def fill_blocks(page: str, text: str, labs: list[LabFacts]) -> str:
    """``text`` with every ``apidoc`` block written anew; raises on unknown keys or missing exercises."""
    exercises = {exercise.id: (lab, exercise) for lab in labs for exercise in lab.exercises}
    found = []

    def generated(match: re.Match) -> str:
        key = match.group("key")
        found.append(key)
        if key == "labs":
            body = labs_table(labs)
        elif key in exercises:
            body = exercise_block(*exercises[key])
        else:
            raise ApidocError(f"{page}: apidoc block {key!r} names no lab table and no exercise")
        return f"{match.group(1)}\n{body}\n{match.group(4)}"

    result = _BLOCK.sub(generated, text)
    unclosed = text.count("<!-- apidoc:begin ") - len(found)
    if unclosed:
        raise ApidocError(f"{page}: an apidoc:begin without its apidoc:end")
    lab = next((lab for lab in labs if Path(page).stem == lab.key), None)
    if lab is not None:
        missing = [exercise.id for exercise in lab.exercises if exercise.id not in found]
        if missing:
            raise ApidocError(f"{page} describes no {', '.join(missing)}: add a section with "
                              f"<!-- apidoc:begin {missing[0]} --><!-- apidoc:end -->")
    duplicated = sorted({key for key in found if found.count(key) > 1})
    if duplicated:
        raise ApidocError(f"{page}: apidoc blocks {duplicated} appear twice")
    return result


def generate(docs: Path, skeletons: Path | None = None) -> dict[Path, str]:
    """Every generated page (whole or with its blocks filled), by path: nothing is written."""
    docs = Path(docs)
    labs = lab_facts(skeletons)
    pages = {docs / "api" / f"{lab.key}.md": api_page(lab) for lab in labs}
    for path in sorted((docs / "contract").glob("*.md")):
        text = path.read_text(encoding="utf-8")
        if "<!-- apidoc:begin " in text:
            pages[path] = fill_blocks(path.name, text, labs)
    for lab in labs:
        if (docs / "contract" / f"{lab.key}.md") not in pages:
            raise ApidocError(f"{docs / 'contract' / lab.key}.md is missing: every lab has a page "
                              "saying what it asks, with an apidoc block per exercise")
    return pages


def stale(docs: Path, skeletons: Path | None = None) -> list[Path]:
    """The pages whose text differs from what :func:`generate` gives (missing ones included)."""
    return [path for path, text in generate(docs, skeletons).items()
            if not path.is_file() or path.read_text(encoding="utf-8") != text]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m autograder.instructor.apidoc", description=__doc__.split("\n\n")[0])
    parser.add_argument("docs", nargs="?", default=str(PROJECT_ROOT / "docs"), help="the documentation folder")
    parser.add_argument("--check", action="store_true", help="write nothing; exit 1 if a page is out of date")
    args = parser.parse_args(argv)
    try:
        if args.check:
            out_of_date = stale(Path(args.docs))
            for path in out_of_date:
                print(f"out of date: {path} (run {GENERATOR})", file=sys.stderr)
            return 1 if out_of_date else 0
        for path, text in generate(Path(args.docs)).items():
            if not path.is_file() or path.read_text(encoding="utf-8") != text:
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(text, encoding="utf-8")
                print(f"wrote {path}")
    except ApidocError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
