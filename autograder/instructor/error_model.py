"""``autograder verify --error-model``: how well a lab's error model names its own mutants.

The error model (:mod:`autograder.engine.mutants`) names a failed check's mistake when a
mutant of the reference reproduces the student's answers. This measures it on the mutants
themselves: each sampled mutant is written as a student's file (the reference module with
the mutant's edits) and its exercise is graded. A mutant is

- **equivalent** when every check passes: no check tells it from the reference (a mutant
  whose change does not matter, or one the checks miss -- the author decides which);
- **caught** when some check loses points, and then
- **named** when a failing check names that very mutant (its sentence), **repaired** when
  a failing check shows a change of the file that mends its answers
  (:mod:`autograder.engine.mutants.repair`: the mutant's edit undone, or an equivalent change),
  **named as another** when the error model names another mutant (an equivalent one, or a wrong
  name: read them), **named by hand** when only a hand-written diagnosis names it.

The counterparts (:mod:`autograder.engine.mutants.aligned`: a line made the reference's again) are left
out while measuring: a mutant is the reference but for one edit, which they would repair every time.

Grading every mutant of a lab takes long (hundreds of gradings): a sample is graded,
spread over the operators (``--mutants N``, the same sample every run).
"""

from __future__ import annotations

import shutil
import tempfile
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from ..engine.mutants import aligned
from ..engine.mutants.naming import model_for, reference_module
from ..engine.mutants.operators import Mutant, apply_edits
from ..engine.registry import Lab

OUTCOMES = ("named", "repaired", "named as another", "named by hand", "described", "equivalent")


@dataclass
class MutantOutcome:
    mutant: Mutant
    exercise: str
    outcome: str          # one of OUTCOMES
    said: str = ""        # the error model's sentence (named as another) or the first failing message


@dataclass
class ErrorModelReport:
    key: str
    generated: int                     # mutants the lab's graded functions have
    outcomes: list[MutantOutcome] = field(default_factory=list)
    seconds: float = 0.0

    def counts(self) -> Counter:
        return Counter(o.outcome for o in self.outcomes)

    @property
    def naming_rate(self) -> float:
        """Named (this mutant, or the change of the student's code that undoes it) among the caught ones."""
        counts = self.counts()
        caught = sum(counts[o] for o in OUTCOMES if o != "equivalent")
        return (counts["named"] + counts["repaired"]) / caught if caught else 0.0


def sample(mutants: list[Mutant], count: int) -> list[Mutant]:
    """``count`` mutants spread over the operators (round robin over them, each operator's in
    its order): the same sample every run."""
    by_operator: dict[str, list[Mutant]] = {}
    for mutant in mutants:
        by_operator.setdefault(mutant.operator, []).append(mutant)
    queues = [list(reversed(spread(group))) for _, group in sorted(by_operator.items())]
    chosen = []
    while len(chosen) < count and any(queues):
        for queue in queues:
            if queue and len(chosen) < count:
                chosen.append(queue.pop())
    return chosen


def spread(group: list) -> list:
    """The group reordered so that its first items are far apart (every k-th first)."""
    step = max(1, len(group) // 7)
    return [group[i] for start in range(step) for i in range(start, len(group), step)]


def measure_error_model(lab: Lab, count: int = 30,
                        progress: Callable[[str], None] | None = None) -> ErrorModelReport:
    """Grade a sample of ``count`` of ``lab``'s mutants (see the module docstring).

    Raises
    ------
    ValueError
        When the lab has no reference module (this copy of the grader has none).
    """
    from ..engine.runner import grade

    model = model_for(lab)
    path = reference_module(lab)
    if model is None or path is None:
        raise ValueError(f"{lab.key}: no reference module, no error model to measure")
    exercise_of = {name: exercise.id for exercise in lab.exercises.values() for name in exercise.signatures}
    unique = {}
    for function in sorted(model.mutants):
        for mutant in model.mutants[function]:
            unique.setdefault(mutant.key, mutant)   # a helper's mutant: measured once, through one function
    report = ErrorModelReport(lab.key, len(unique))
    started = time.perf_counter()
    tell = progress or (lambda what: None)
    for mutant in sample(list(unique.values()), count):
        exercise = exercise_of[mutant.function]
        tell(f"{lab.key} {mutant.operator} in {mutant.where}")
        folder = Path(tempfile.mkdtemp(prefix="verify-mutant-"))
        try:
            (folder / f"{lab.module}.py").write_text(apply_edits(model.source, mutant.edits), encoding="utf-8")
            with aligned.left_out():   # (each mutant is one edit of the reference: see aligned.left_out)
                result = grade(folder, [exercise], pictures="none")
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        checks = [c for e in result.exercises if e.id == exercise for c in e.checks if c.max_score > 0]
        report.outcomes.append(classify(mutant, exercise, checks))
    report.seconds = round(time.perf_counter() - started, 3)
    return report


def classify(mutant: Mutant, exercise: str, checks) -> MutantOutcome:
    """The outcome of one graded mutant (see the module docstring)."""
    failed = [c for c in checks if c.score < c.max_score]
    if not failed:
        return MutantOutcome(mutant, exercise, "equivalent")
    modelled = [c for c in failed if c.mistake.startswith("mutant:")]
    if any(mutant.sentence in c.message for c in failed):   # (an in-place change keeps the engine's label)
        return MutantOutcome(mutant, exercise, "named")
    repaired = [c for c in failed if c.mistake.startswith("repair:")]
    if repaired:   # a change of the "student's" code, confirmed to mend its answers, is shown
        said = repaired[0].message.split("Trying small changes to your code: ", 1)[-1].split("\n")[0]
        return MutantOutcome(mutant, exercise, "repaired", said)
    if modelled:
        said = modelled[0].message.split("The error model: it looks like ", 1)[-1].split("\n")[0]
        return MutantOutcome(mutant, exercise, "named as another", said)
    if any(c.mistake for c in failed):
        return MutantOutcome(mutant, exercise, "named by hand", failed[0].mistake)
    return MutantOutcome(mutant, exercise, "described", failed[0].message.split("\n")[0])


def render_error_model(report: ErrorModelReport, console) -> None:
    """The sample's outcomes per operator, then the mutants named as another (to read)."""
    from rich.markup import escape
    from rich.table import Table

    table = Table(title=f"{report.key}: error model ({len(report.outcomes)} of {report.generated} mutants graded)",
                  title_justify="left")
    table.add_column("operator")
    for outcome in OUTCOMES:
        table.add_column(outcome, justify="right")
    by_operator: dict[str, Counter] = {}
    for outcome in report.outcomes:
        by_operator.setdefault(outcome.mutant.operator, Counter())[outcome.outcome] += 1
    for operator, counts in sorted(by_operator.items()):
        table.add_row(operator, *(str(counts[o]) for o in OUTCOMES))
    total = report.counts()
    table.add_row("all", *(str(total[o]) for o in OUTCOMES))
    console.print(table)
    for outcome in report.outcomes:
        if outcome.outcome == "named as another":
            console.print(f"  {escape(outcome.mutant.sentence)}\n    named as: {escape(outcome.said)}")
    console.print(f"{report.key}: the error model names {report.naming_rate:.0%} of the caught mutants "
                  f"({report.seconds:.0f} s)")
