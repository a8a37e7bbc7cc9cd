"""A lab handed in more than once: which file is graded, and why the others are not.

A student may hand a lab in twice without meaning to: a notebook beside the skeleton
``.py`` (``assignments/lab07_transformations.ipynb`` and ``.py``), two notebooks, the
module in two folders, or a copy (``lab07_transformations (1).py``). Exactly one file
is graded as the lab's module; nothing is ignored silently: every file left aside is a
:class:`NotGraded`, which the submission keeps (:attr:`Submission.not_graded
<autograder.loading.submission.Submission.not_graded>`) and every report names.

The file graded is the one that implements the lab (:func:`choose`): the most top-level
functions that are defined and not a skeleton stub, then the fewest stubs, then the
newest (modification time), then the shallowest path (``.py`` before ``.ipynb``). Code is
read, never run. What counts as a stub is :func:`stub_names` (also the engine's, see
:mod:`autograder.engine.stubs`): a function whose body is only ``raise NotImplementedError``.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

from .parsing import parse, walk

# Code that can rebind a module's names at run time: a function "stub" might not stay one.
DYNAMIC = ("globals(", "setattr(", "__dict__", "sys.modules", "exec(", "eval(", "importlib")


# ------------------------------------------------------------------ reading a module for stubs
def stub_names(tree: ast.Module, text: str) -> frozenset[str]:
    """Top-level functions of the module ``tree`` (parsed from ``text``) that can only raise
    ``NotImplementedError``: undecorated, the body an optional docstring then ``raise
    NotImplementedError`` (constant arguments, if any), and nothing else in the module binds
    the name or ``NotImplementedError``. Empty when the module may rebind names at run time."""
    if "NotImplementedError" not in text or any(token in text for token in DYNAMIC):
        return frozenset()
    bindings: dict[str, int] = {}
    for node in walk(tree):
        for name in _bound_names(node):
            bindings[name] = bindings.get(name, 0) + 1
    if bindings.get("NotImplementedError"):
        return frozenset()
    return frozenset(node.name for node in tree.body
                     if isinstance(node, ast.FunctionDef) and _is_stub(node)
                     and bindings.get(node.name) == 1)


def _bound_names(node: ast.AST):
    """Names a node binds (defs, assignments, imports, ``global``, deletions...)."""
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        yield node.name
    elif isinstance(node, ast.Name) and not isinstance(node.ctx, ast.Load):
        yield node.id
    elif isinstance(node, (ast.Import, ast.ImportFrom)):
        for alias in node.names:
            yield alias.asname or alias.name.split(".")[0]
    elif isinstance(node, (ast.Global, ast.Nonlocal)):
        yield from node.names
    elif isinstance(node, ast.arg):
        yield node.arg


def _is_stub(function: ast.FunctionDef) -> bool:
    if function.decorator_list:
        return False
    body = function.body
    if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
            and isinstance(body[0].value.value, str):
        body = body[1:]
    if len(body) != 1 or not isinstance(body[0], ast.Raise) or body[0].cause is not None:
        return False
    raised = body[0].exc
    if isinstance(raised, ast.Name):
        return raised.id == "NotImplementedError"
    return (isinstance(raised, ast.Call) and isinstance(raised.func, ast.Name)
            and raised.func.id == "NotImplementedError" and not raised.keywords
            and all(isinstance(arg, ast.Constant) for arg in raised.args))


@dataclass(frozen=True)
class Progress:
    """How much of a lab one file implements, read from its source (never run)."""

    implemented: int      # top-level functions defined and not stubs
    stubs: int            # top-level functions that only raise NotImplementedError
    unreadable: str = ""  # why the file could not be read ("is not UTF-8 text"), "" when it could
    implemented_names: frozenset = frozenset()   # the names of both (where the file parses)
    stub_names: frozenset = frozenset()

    def words(self) -> str:
        """What the file implements, as a predicate: ``"implements 6 functions"``, ``"implements
        none of its 6 functions yet (each only raises NotImplementedError)"``, ``"cannot be read: ..."``."""
        if self.unreadable:
            return self.unreadable
        plural = "s" * (self.implemented != 1)
        if not self.stubs:
            return f"implements {self.implemented} function{plural}" if self.implemented else "defines no function"
        if not self.implemented:
            return (f"implements none of its {self.stubs} function{'s' * (self.stubs != 1)} yet "
                    f"({'each' if self.stubs != 1 else 'it'} only raises NotImplementedError)")
        return (f"implements {self.implemented} function{plural} ({self.stubs} more only "
                f"raise{'s' * (self.stubs == 1)} NotImplementedError)")


def progress(text: str) -> Progress:
    """:class:`Progress` of a module's source ``text``. A module that does not parse (work in
    progress, as a skeleton never is) counts its top-level ``def`` lines as implemented."""
    try:
        tree = parse(text)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return Progress(sum(line.startswith(("def ", "async def ")) for line in text.splitlines()), 0)
    stubs = stub_names(tree, text)
    defined = {node.name for node in tree.body if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))}
    return Progress(len(defined - stubs), len(stubs), "", frozenset(defined - stubs), frozenset(stubs))


# ------------------------------------------------------------------ choosing the file to grade
@dataclass(frozen=True)
class Candidate:
    """One file handed in as a lab's module."""

    path: Path            # where it was read (a copy inside the grader's folder)
    shown: str            # its path inside the submission, as the student knows it
    progress: Progress
    modified: float       # modification time (seconds since the epoch), as handed in

    def rank(self) -> tuple:
        """Greater is graded: readable, most implemented, fewest stubs, newest, then the
        shallowest path, ``.py`` before ``.ipynb`` (deterministic on a full tie)."""
        return (not self.progress.unreadable, self.progress.implemented, -self.progress.stubs, self.modified,
                -len(Path(self.shown).parts), self.path.suffix.lower() == ".py", self.shown)


@dataclass(frozen=True)
class NotGraded:
    """A file handed in for ``module`` that was not graded, because ``graded`` was; ``why``
    in words (``"it implements no function ...; lab07_transformations.ipynb implements 6"``)."""

    module: str
    file: str
    graded: str
    why: str

    def sentence(self) -> str:
        """The one line every report shows."""
        return (f"{self.module} was handed in more than once: graded {self.graded}, not {self.file}, "
                f"because {self.why}; keep one file per lab (move or delete the other)")

    def to_dict(self) -> dict:
        return {"module": self.module, "file": self.file, "graded": self.graded, "why": self.why}

    @classmethod
    def from_dict(cls, data: dict) -> "NotGraded":
        return cls(str(data.get("module", "")), str(data.get("file", "")), str(data.get("graded", "")),
                   str(data.get("why", "")))


def choose(module: str, candidates: list[Candidate]) -> tuple[Candidate, list[NotGraded]]:
    """The candidate to grade as ``module`` (see the module docstring), and why each other
    one is not. ``candidates`` holds at least one."""
    ranked = sorted(candidates, key=Candidate.rank, reverse=True)
    best, others = ranked[0], ranked[1:]
    return best, [NotGraded(module, other.shown, best.shown, _why(other, best)) for other in others]


def _why(other: Candidate, best: Candidate) -> str:
    """Why ``other`` is not graded, ``best`` is: a clause naming both files."""
    mine, theirs = other.progress, best.progress
    if mine.unreadable:
        return f"{other.shown} {mine.unreadable}"
    if (mine.implemented, mine.stubs) != (theirs.implemented, theirs.stubs):
        # (a skeleton beside the work: the work's count of the skeleton's own functions, its helpers apart --
        # "none of its 11 functions" beside "12 functions" reads as a miscount)
        skeleton = mine.stub_names and not mine.implemented and theirs.implemented_names & mine.stub_names
        helpers = len(theirs.implemented_names - mine.stub_names)
        if skeleton and helpers and not theirs.stubs:
            done = len(theirs.implemented_names & mine.stub_names)
            return (f"{other.shown} {mine.words()} and {best.shown} implements {done} of them "
                    f"(and {helpers} function{'s' * (helpers != 1)} of its own)")
        return f"{other.shown} {mine.words()} and {best.shown} {theirs.words()}"
    both = f"both {theirs.words().replace('implements', 'implement', 1).replace('defines', 'define', 1)}"
    if other.modified != best.modified:
        return f"{both} and {best.shown} is newer ({_when(best.modified)}, the other {_when(other.modified)})"
    return f"{both} and have the same date: the grader takes the file nearest the top, a .py before a notebook"


def _when(seconds: float) -> str:
    return datetime.fromtimestamp(seconds, timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
