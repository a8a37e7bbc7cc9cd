"""``autograder verify``: proof that a lab's checks are sound.

A lab's checks are sound when

- the reference solution gets full marks on every check, public and hidden;
- the skeleton scores zero, every check saying "not implemented yet";
- every case of the lab's mistakes table loses points in its own exercise, named in its
  own words (a failing check's message holds every fragment of the case), and no check
  names it as another mistake; every advice case gets its tip and loses nothing;
- every check is failed by some case of the table (a check nothing fails proves nothing);
- every check gives the same verdict and message, from the same inputs, when the reference
  is graded twice;
- no check is a grader error on any of these gradings, and the lab has hidden checks;
- every exercise has at least ``min_mistakes`` cases in the table (default 5, the course's
  ``min_mistakes``), or a reason in its ``FEWER_MISTAKES``: the same bar for every lab.

:func:`verify_lab` grades all of it (through a :class:`Gradings`, which the project's tests
replace by one that shares gradings between tests) and returns a :class:`LabReport`; the
judging functions (:func:`reference_problems`, :func:`skeleton_problems`,
:func:`case_problems`, :func:`unfailed_checks`, :func:`differing_verdicts`) each take
gradings and return the problems found, in words. :func:`render` prints the tables.

Where the parts are: for a built-in lab, ``reference_solutions/``, ``assignments/`` and
:mod:`autograder.labs.mistakes`; for a course lab, its folder's ``reference/``,
``skeleton/`` and ``mistakes.py`` (:mod:`autograder.engine.labfolders`).
"""

from __future__ import annotations

import importlib
import shutil
import tempfile
import textwrap
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable

from ..engine.constant import MISTAKE as CONSTANT_ANSWER
from ..engine.ignored import MISTAKE as UNUSED_PARAMETER, UNUSED_VALUE
from ..engine.labfolders import MISTAKES, REFERENCE, SKELETON, LabFolderError, lab_folder
from ..engine.registry import Lab
from ..engine.results import ERROR, GradingResult
from ..loading.parsing import compile_source

PROJECT_ROOT = Path(__file__).resolve().parents[2]
NOT_IMPLEMENTED = "not implemented yet"
MIN_MISTAKES = 5   # cases of the mistakes table per exercise, at least (a course's min_mistakes)


class VerifyError(ValueError):
    """A lab cannot be verified: a part is missing, or its mistakes table is malformed."""


@dataclass(frozen=True)
class Case:
    """One case of a mistakes table: ``source`` appended to the reference must lose points in
    ``exercise`` with every one of ``fragments`` in a failing check's message (an advice
    case: a tip holding them, and no point lost)."""

    name: str
    exercise: str
    source: str
    fragments: tuple[str, ...]
    advice: bool = False


@dataclass(frozen=True)
class LabParts:
    """What verifying ``lab`` needs: the folders holding its reference and skeleton module,
    and its mistakes table."""

    lab: Lab
    reference: Path
    skeleton: Path
    cases: tuple[Case, ...]
    fewer: dict = field(default_factory=dict)   # exercise id -> why it has fewer cases than the minimum
    table: str = ""                             # where the table is, for messages


def parts_of(lab: Lab) -> LabParts:
    """The reference, skeleton and mistakes table of ``lab`` (built-in or a course's)."""
    loaded = lab_folder(lab)
    if loaded is not None:
        try:
            reference, skeleton = loaded.part(REFERENCE), loaded.part(SKELETON)
            loaded.part(MISTAKES)
        except LabFolderError as exc:
            raise VerifyError(str(exc)) from None
        table_name = f"{loaded.package}.{Path(MISTAKES).stem}"
        where = str(loaded.folder / MISTAKES)
    else:
        reference, skeleton = PROJECT_ROOT / "reference_solutions", PROJECT_ROOT / "assignments"
        table_name, where = f"autograder.labs.mistakes.{lab.key}", f"autograder/labs/mistakes/{lab.key}.py"
        for folder in (reference, skeleton):
            if not (folder / f"{lab.module}.py").is_file():
                raise VerifyError(f"{lab.key}: {folder / (lab.module + '.py')} is missing "
                                  "(this copy of the grader has no reference solutions: verify runs "
                                  "in the instructor's repository)")
    try:
        table = importlib.import_module(table_name)
    except ModuleNotFoundError as exc:
        if exc.name != table_name:
            raise VerifyError(f"{_where(exc, where)}: the mistakes table cannot be imported: {exc}") from None
        raise VerifyError(f"{lab.key} has no mistakes table ({where})") from None
    except SyntaxError as exc:
        raise VerifyError(f"{exc.filename or where}, line {exc.lineno}: SyntaxError in the mistakes table: "
                          f"{exc.msg}") from None
    except (Exception, SystemExit) as exc:  # noqa: BLE001 - the author's table: any error, said where (sys.exit too)
        raise VerifyError(f"{_where(exc, where)}: the mistakes table cannot be imported: "
                          f"{type(exc).__name__}: {exc}") from None
    cases = _cases(lab, table, "MISTAKES", where) + _cases(lab, table, "ADVICE", where, advice=True)
    return LabParts(lab, reference, skeleton, tuple(cases), _fewer(lab, table, where), where)


def _fewer(lab: Lab, table, where: str) -> dict:
    """The table's ``FEWER_MISTAKES`` (exercise id -> why), refused unless it is that."""
    fewer = getattr(table, "FEWER_MISTAKES", {})
    exercises = {e.id for e in lab.exercises.values()}
    if not (isinstance(fewer, dict) and all(isinstance(k, str) and isinstance(v, str) and v.strip()
                                            for k, v in fewer.items())):
        raise VerifyError(f"{where}: FEWER_MISTAKES must be a dict: exercise id -> why its algorithm has "
                          "fewer realistic mistakes than verify's minimum (the course's min_mistakes, default 5)")
    stale = sorted(set(fewer) - exercises)
    if stale:
        raise VerifyError(f"{where}: FEWER_MISTAKES names {', '.join(map(repr, stale))}, not an exercise of "
                          f"{lab.key} ({', '.join(sorted(exercises))})")
    return dict(fewer)


def _where(exc: BaseException, where: str) -> str:
    """``file, line N`` of the innermost frame of ``exc`` in the table ``where`` (else ``where``)."""
    import traceback

    frames = [f for f in traceback.extract_tb(exc.__traceback__) if f.filename.endswith(where)]
    return f"{frames[-1].filename}, line {frames[-1].lineno}" if frames else where


def _cases(lab: Lab, table, name: str, where: str, advice: bool = False) -> list[Case]:
    entries = getattr(table, name, None if name == "MISTAKES" else {})
    if not isinstance(entries, dict):
        raise VerifyError(f"{where}: {name} must be a dict: case name -> (exercise id, source, fragments)")
    exercises = {e.id for e in lab.exercises.values()}
    cases = []
    for case_name, entry in entries.items():
        if not (isinstance(entry, tuple) and len(entry) == 3 and isinstance(entry[0], str)
                and isinstance(entry[1], str)
                and isinstance(entry[2], (list, tuple)) and entry[2]
                and all(isinstance(f, str) and f.strip() for f in entry[2])):
            raise VerifyError(f"{where}: {name}[{case_name!r}] must be (exercise id, source, [fragments...]) "
                              "with at least one fragment, a word or words the diagnosis must contain "
                              "(an empty fragment is in every message)")
        if entry[0] not in exercises:
            raise VerifyError(f"{where}: {name}[{case_name!r}] names {entry[0]!r}, not an exercise of "
                              f"{lab.key} ({', '.join(sorted(exercises))})")
        try:   # a case that cannot even be imported would lose points to its own SyntaxError
            compile_source(textwrap.dedent(entry[1]), f"{name}[{case_name!r}]", "exec")
        except SyntaxError as exc:
            raise VerifyError(f"{where}: {name}[{case_name!r}]'s source, line {exc.lineno}: "
                              f"SyntaxError: {exc.msg}") from None
        cases.append(Case(case_name, entry[0], entry[1], tuple(entry[2]), advice))
    return cases


def with_mutation(reference: str, source: str) -> str:
    """The reference module's text with ``source`` appended: its ``def``s win, and the
    module's other functions call the new ones, as in a student's file."""
    return reference + "\n\n# --- mutation\n" + textwrap.dedent(source)


# ------------------------------------------------------------------ grading
class Gradings:
    """How verify grades: each grading afresh, without pictures, only the lab or exercise
    concerned. ``run`` numbers the reference's gradings (0, then 1 to compare)."""

    def reference(self, parts: LabParts, run: int = 0) -> GradingResult:
        return _grade(parts.reference, [parts.lab.key])

    def skeleton(self, parts: LabParts) -> GradingResult:
        return _grade(parts.skeleton, [parts.lab.key])

    def case(self, parts: LabParts, case: Case) -> GradingResult:
        folder = Path(tempfile.mkdtemp(prefix="verify-case-"))
        try:
            module = f"{parts.lab.module}.py"
            original = (parts.reference / module).read_text(encoding="utf-8")
            (folder / module).write_text(with_mutation(original, case.source), encoding="utf-8")
            return _grade(folder, [case.exercise])
        finally:
            shutil.rmtree(folder, ignore_errors=True)


def _grade(folder: Path, selectors) -> GradingResult:
    from ..engine.runner import grade

    return grade(folder, selectors, pictures="none")


# ------------------------------------------------------------------ judging
def _exercises(result: GradingResult, prefix: str):
    return [e for e in result.exercises if e.id == prefix or e.id.startswith(prefix + ".")]


def _scores(result: GradingResult, prefix: str) -> tuple[float, float]:
    exercises = _exercises(result, prefix)
    return sum(e.score for e in exercises), sum(e.max_score for e in exercises)


def reference_problems(result: GradingResult, lab_key: str) -> list[str]:
    """Every check of every exercise of the lab passed (advice may speak: it is no failure, but
    not crash)."""
    exercises = _exercises(result, lab_key)
    if not exercises:
        return [f"no exercise of {lab_key} was graded"]
    return [f"the reference fails {e.id} {c.name!r}: {c.message.splitlines()[0] if c.message else c.status}"
            for e in exercises for c in e.checks if (not c.passed and c.max_score > 0) or c.status == ERROR]


def skeleton_problems(result: GradingResult, lab_key: str) -> list[str]:
    """Every exercise scores 0 with "not implemented yet", every check too, no traceback."""
    exercises = _exercises(result, lab_key)
    if not exercises:
        return [f"no exercise of {lab_key} was graded"]
    problems = []
    for e in exercises:
        if e.score != 0:
            problems.append(f"the skeleton scores {e.score:g} in {e.id}")
        if e.message != NOT_IMPLEMENTED:
            problems.append(f"{e.id} of the skeleton says {e.message!r}, not {NOT_IMPLEMENTED!r}")
        problems += [f"the skeleton's {e.id} {c.name!r} says {c.message.splitlines()[0] if c.message else ''!r}"
                     + (" with a traceback" if c.traceback else "")
                     for c in e.checks if NOT_IMPLEMENTED not in c.message or c.traceback]
    return problems


def named_mistakes(result: GradingResult, exercise_id: str) -> list[tuple[str, str]]:
    """(label, message) of each failing graded check of the exercise that names a mistake."""
    return [(c.mistake, c.message) for e in _exercises(result, exercise_id) for c in e.checks
            if not c.passed and c.max_score > 0 and (c.mistake or "looks like" in c.message.lower())]


def grader_errors(result: GradingResult, prefix: str) -> list[str]:
    """The checks of the exercises under ``prefix`` (a lab or an exercise) that were grader
    errors: a check that crashes on some answer scores it 0 without judging it."""
    return [f"grader error in {e.id} {c.name!r}: {c.message.splitlines()[0] if c.message else ''}"
            for e in _exercises(result, prefix) for c in e.checks if c.status == ERROR]



def case_problems(result: GradingResult, case: Case) -> list[str]:
    """What is wrong with how the checks answer ``case`` (nothing: an empty list)."""
    errors = grader_errors(result, case.exercise)
    if case.advice:
        return errors + _advice_problems(result, case)
    exercises = _exercises(result, case.exercise)
    if not exercises:
        return [f"{case.exercise} was not graded"]
    failed = [c for e in exercises for c in e.checks if not c.passed and c.max_score > 0 and c.status != ERROR]
    if not failed:
        return errors + [f"loses no points in {case.exercise}: every check passed"
                         + (" or crashed" if errors else "") + ", but the implementation is wrong"]
    problems = errors
    words = [f.lower() for f in case.fragments]
    if not any(all(w in c.message.lower() for w in words) for c in failed):
        problems.append(f"not named in its own words {list(case.fragments)}; the messages were: "
                        + " | ".join(c.message.splitlines()[0] for c in failed if c.message))
    # The error model's names (``mutant:...``), its repairs of the student's code (``repair:...``), an
    # unused parameter's or value's (engine/ignored.py: read in the code, true of it) and an answer that does
    # not depend on the input (engine/constant.py: measured) are told in their own generic words: they count as
    # another mistake only when no check names the case in its own words (autograder verify --error-model
    # measures the model's apart).
    named_in_own_words = any(all(w in c.message.lower() for w in words) for c in failed)
    problems += [f"named as another mistake: {message.splitlines()[0]!r}"
                 for label, message in named_mistakes(result, case.exercise)
                 if not all(w in message.lower() for w in words)
                 and not (named_in_own_words and (label.startswith(("mutant:", "repair:"))
                                                   or label in (UNUSED_PARAMETER, UNUSED_VALUE, CONSTANT_ANSWER)))]
    if sum(e.score for e in exercises) >= sum(e.max_score for e in exercises):
        problems.append(f"loses no points in {case.exercise}")
    return problems


def _advice_problems(result: GradingResult, case: Case) -> list[str]:
    exercises = _exercises(result, case.exercise)
    tips = [c.message.lower() for e in exercises for c in e.checks if c.advice]
    words = [f.lower() for f in case.fragments]
    problems = [] if any(all(w in tip for w in words) for tip in tips) else [
        f"no tip holds {list(case.fragments)}; the tips were: " + (" | ".join(tips) or "none")]
    lost = [f"{c.name!r}: {c.message.splitlines()[0] if c.message else c.status}"
            for e in exercises for c in e.checks if not c.passed and c.max_score > 0]
    return problems + [f"a convention loses points: {line}" for line in lost]


def failures(results: Iterable[GradingResult]) -> dict[tuple[str, str], int]:
    """How many gradings of ``results`` fail each check, by (exercise id, check name) (an advice
    check counts as failed when it gave its tip; a grader error is no failure)."""
    counted: dict[tuple[str, str], int] = {}
    for result in results:
        for e in result.exercises:
            for c in e.checks:
                if not c.passed and c.status != ERROR:
                    counted[(e.id, c.name)] = counted.get((e.id, c.name), 0) + 1
    return counted


def unfailed_checks(lab: Lab, results: Iterable[GradingResult]) -> list[tuple[str, str]]:
    """(exercise id, check name) of the checks of ``lab`` that no grading of ``results`` failed
    (:func:`failures`)."""
    failed = failures(results)
    return [(e.id, c.name) for e in lab.exercises.values() for c in e.checks if (e.id, c.name) not in failed]


def differing_verdicts(first: GradingResult, second: GradingResult, lab_key: str) -> list[tuple[str, str]]:
    """(exercise id, check name) of the checks of the lab whose score or message differs
    between two gradings of the same files, or which gave the student's functions other
    inputs (a check drawing from the clock or an unseeded random generator, even if the
    reference passes both)."""
    def verdicts(result):
        return {(e.id, c.name): (c.score, c.message, c.inputs_digest)
                for e in _exercises(result, lab_key) for c in e.checks}

    one, two = verdicts(first), verdicts(second)
    return [key for key in one if one[key] != two.get(key)] + [key for key in two if key not in one]


def too_few_mistakes(parts: LabParts, minimum: int = MIN_MISTAKES) -> list[str]:
    """A sentence for each exercise of the lab whose mistakes table has fewer than ``minimum``
    cases (advice not counted) and no reason for it in ``FEWER_MISTAKES``."""
    counts = {e.id: 0 for e in parts.lab.exercises.values()}
    for case in parts.cases:
        counts[case.exercise] += not case.advice
    return [f"{exercise} has {count} mistake{'s' if count != 1 else ''} in its table ({parts.table}); every "
            f"exercise of every lab needs at least {minimum} (the course's min_mistakes), or the reason "
            "its algorithm has fewer in FEWER_MISTAKES"
            for exercise, count in counts.items() if count < minimum and not parts.fewer.get(exercise)]


# ------------------------------------------------------------------ a lab's report
@dataclass
class CaseReport:
    case: Case
    score: float
    max_score: float
    problems: list[str]
    seconds: float


@dataclass
class CheckReport:
    exercise: str
    name: str
    points: float
    hidden: bool
    advice: bool
    seconds: float        # on the reference
    failed_by: int        # cases of the table that fail it
    same_twice: bool      # the same verdict and message on both gradings of the reference


@dataclass
class LabReport:
    key: str
    title: str
    reference: tuple[float, float]
    reference_problems: list[str]
    skeleton: tuple[float, float]
    skeleton_problems: list[str]
    cases: list[CaseReport]
    checks: list[CheckReport]
    seconds: float = 0.0
    table_problems: list[str] = field(default_factory=list)   # too_few_mistakes


    @property
    def problems(self) -> list[str]:
        """Every reason the lab is not sound, in words."""
        found = [f"reference: {p}" for p in self.reference_problems]
        found += [f"skeleton: {p}" for p in self.skeleton_problems]
        found += [f"{c.case.name}: {p}" for c in self.cases for p in c.problems]
        found += [f"mistakes table: {p}" for p in self.table_problems]
        found += [f"{c.exercise} {c.name!r}: no case of the mistakes table fails it" for c in self.checks
                  if not c.failed_by]
        found += [f"{c.exercise} {c.name!r}: a different verdict, message or input when the reference is graded "
                  "again (an unseeded random generator? the clock?)" for c in self.checks if not c.same_twice]
        if not any(c.hidden and not c.advice for c in self.checks):
            found.append(f"{self.key} has no hidden checks: a table of the public checks' answers would earn "
                         "every point (add some to hidden.py, or hide some checks)")
        return found

    @property
    def ok(self) -> bool:
        return not self.problems


def verify_lab(lab: Lab, gradings: Gradings | None = None,
               progress: Callable[[str], None] | None = None, min_mistakes: int = MIN_MISTAKES) -> LabReport:
    """Grade ``lab``'s reference (twice), skeleton and every case of its mistakes table, and
    judge them (each exercise needing ``min_mistakes`` cases, :func:`too_few_mistakes`);
    ``progress(what)`` is told each grading as it starts."""
    import time

    gradings = gradings or Gradings()
    parts = parts_of(lab)
    tell = progress or (lambda what: None)
    started = time.perf_counter()
    tell(f"{lab.key} reference")
    first = gradings.reference(parts, 0)
    tell(f"{lab.key} reference, again")
    second = gradings.reference(parts, 1)
    tell(f"{lab.key} skeleton")
    skeleton = gradings.skeleton(parts)
    cases, results = [], []
    for case in parts.cases:
        tell(f"{lab.key} {case.name}")
        result = gradings.case(parts, case)
        graded = _exercises(result, case.exercise)
        cases.append(CaseReport(case, sum(e.score for e in graded), sum(e.max_score for e in graded),
                                case_problems(result, case), result.seconds))
        results.append(result)
    failed_by = failures(results)
    differing = set(differing_verdicts(first, second, lab.key))
    timing = {(e.id, c.name): c.seconds for e in _exercises(first, lab.key) for c in e.checks}
    checks = [CheckReport(e.id, c.name, c.points, c.hidden, c.advice, timing.get((e.id, c.name), 0.0),
                          failed_by.get((e.id, c.name), 0), (e.id, c.name) not in differing)
              for e in lab.exercises.values() for c in e.checks]
    return LabReport(lab.key, lab.title, _scores(first, lab.key), reference_problems(first, lab.key),
                     _scores(skeleton, lab.key), skeleton_problems(skeleton, lab.key),
                     cases, checks, round(time.perf_counter() - started, 3), too_few_mistakes(parts, min_mistakes))


# ------------------------------------------------------------------ the tables
def render(report: LabReport, console) -> None:
    """``report`` as two tables on a rich ``console``: the gradings (reference, skeleton, each
    case), then the checks (points, cases failing it, the same twice, time); then a verdict
    and every problem in full. A row is one line, whatever the console's width (80 columns
    and up): names too long are cut with an ellipsis, as a failing verdict is, which the
    list of problems after the tables gives whole."""
    from rich.markup import escape
    from rich.table import Table

    ok, bad = "[green]ok[/green]", "[red]FAIL[/red]"

    def said(problems):
        return ok if not problems else bad + " " + escape("; ".join(problems))

    def short(exercise_id: str) -> str:   # the table's title names the lab
        return exercise_id.removeprefix(f"{report.key}.")

    rows = [("reference", "all", f"{report.reference[0]:g} / {report.reference[1]:g}",
             said(report.reference_problems)),
            ("skeleton", "all", f"{report.skeleton[0]:g} / {report.skeleton[1]:g}", said(report.skeleton_problems))]
    rows += [(f"{'tip' if c.case.advice else 'mistake'}: {escape(c.case.name)}", short(c.case.exercise),
              f"{c.score:g} / {c.max_score:g}", said(c.problems)) for c in report.cases]
    console.print(_table(f"{report.key} {escape(report.title)}: gradings", console.width, rows,
                         ("grading", "left", True), ("ex.", "left", False), ("score", "right", False),
                         ("verdict", "left", True)))
    rows = [(short(c.exercise), escape(c.name.removesuffix(" (hidden)") + (" (hidden)" if c.hidden else "")),
             "tip" if c.advice else f"{c.points:g}", str(c.failed_by) if c.failed_by else "[red]0[/red]",
             "yes" if c.same_twice else "[red]no[/red]", f"{c.seconds:.2f}") for c in report.checks]
    console.print(_table(f"{report.key}: checks (failed by: cases failing it; same: verdict graded twice)",
                         console.width, rows,
                         ("ex.", "left", False), ("check", "left", True), ("pts", "right", False),
                         ("failed by", "right", False), ("same", "left", False), ("s", "right", False)))
    if report.ok:
        console.print(f"[green]{report.key} is sound[/green]: {len(report.cases)} cases, "
                      f"{len(report.checks)} checks, {report.seconds:.0f} s")
    else:
        console.print(f"[red]{report.key} is not sound[/red] ({len(report.problems)} problems):")
        listed = Table.grid(padding=(0, 1), pad_edge=True)   # a problem's lines indented under its dash
        listed.add_column(no_wrap=True)
        listed.add_column(overflow="fold")
        for problem in report.problems:
            listed.add_row("-", escape(problem))
        console.print(listed, highlight=False)


def _table(title: str, width: int, rows, *columns: tuple[str, str, bool]):
    """A table ``width`` columns wide at most, without vertical rules, each of ``rows`` (rich
    markup) on one line: ``columns`` are (header, justify, cut). A column not cut is as wide
    as its widest cell; the columns cut (names, verdicts) share what is left, a longer cell
    ending in an ellipsis."""
    from rich import box
    from rich.table import Table
    from rich.text import Text

    widest = [max([Text.from_markup(row[i]).cell_len for row in rows] + [len(header)])
              for i, (header, _, _) in enumerate(columns)]
    cut = [i for i, (_, _, shortened) in enumerate(columns) if shortened]
    # Two characters between columns (a space of padding, the rule's), none outside; what
    # the others leave, shared.
    left = width - 2 * (len(columns) - 1) - sum(w for i, w in enumerate(widest) if i not in cut)
    need = [widest[i] for i in cut]
    share = dict(zip(cut, need if sum(need) <= left else [max(8, left * n // sum(need)) for n in need]))
    table = Table(title=title, title_justify="left", box=box.SIMPLE_HEAD, show_edge=False, pad_edge=False,
                  collapse_padding=True)
    for i, (header, justify, shortened) in enumerate(columns):
        table.add_column(header, justify=justify, no_wrap=True, overflow="ellipsis",
                         min_width=None if shortened else widest[i], max_width=share.get(i))
    for row in rows:
        table.add_row(*row)
    return table
