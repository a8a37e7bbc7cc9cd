"""A function that answers the same whatever it is given earns no points.

Some checks compare a function's answers with each other: the same point alone and among many,
whole numbers given as integers and as floats, a grey image answered in grey, a parameter's
default against the API's value. A function that returns one constant computes nothing, yet it
passes all of them. In the hostile round of 2026-12-07, ``return np.full(1, 0.5)`` in every
function earned 43 of the 464 public points.

While an exercise is graded, :func:`remember` keeps, for each function, its first answer, the distinct
inputs answered alike and the checks that called it. A function is constant when at least
two distinct inputs got answers alike (within :data:`ALIKE` of the largest entry), and the reference's
answers to those inputs differ (by more than :data:`DIFFERENT`). The reference is compared up to scale and sign, because the labs ask for every matrix and
homogeneous vector only up to those. :func:`zero_constant` then sets to 0 the points of the
exercise's checks that called such a function.

Nothing is decided without the reference (a copy of the grader without ``reference_solutions/``).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .checks import fingerprint
from .compare import projective_distance
from .results import FAILED, CheckResult

# Alike: within ALIKE of the answer's largest entry, where the right answers are DIFFERENT apart (up to scale and
# sign): the answer carries nothing of its input, whatever tag drawn from the input it carries (hostile round of
# 2026-12-07: 1e-13, then 1e-9 times the length of the arguments' text, each within the checks' own 1e-7 where
# those checks compared). A right answer is that near another only where the right answers are too.
ALIKE = 1e-4
DIFFERENT = 1e-2
KEY = "answers seen"
KEPT = 4               # distinct inputs (their arguments) kept per function for the reference's confirmation
SECONDS = 10.0         # for the reference's answers to them
MISTAKE = "the answer does not depend on the input"


def remember(trial) -> None:
    """Keep, for each function the trial called, its first answer and up to :data:`KEPT` distinct inputs answered
    alike, and the checks that called it, until an answer not alike (:data:`ALIKE`, :func:`.inplace.same_answer`)
    shows that it does depend on its input. Alike, not equal bit for bit: a tag drawn from each input changes
    nothing the answer says of it."""
    from .inplace import same_answer

    shared = getattr(getattr(trial, "sandbox", None), "shared", None)
    if shared is None:
        return
    for function, args, kwargs, value in trial.calls:
        seen = shared.setdefault((KEY, trial.lab.module, function), {"inputs": {}, "first": None, "varies": False,
                                                                     "checks": set()})
        seen["checks"].add((trial.check.exercise.id, trial.check.name))
        if seen["varies"]:
            continue   # (its answers vary: nothing more to keep)
        given = fingerprint(args, kwargs)
        if given in seen["inputs"] or len(seen["inputs"]) >= KEPT:
            continue
        if not seen["inputs"]:
            seen["first"] = _sampled(value)
        elif not same_answer(_sampled(value), seen["first"], ALIKE):
            seen.update(inputs={}, first=None, varies=True)
            continue
        seen["inputs"][given] = (args, kwargs)


SAMPLE = 1 << 16   # entries of a large array kept for comparing (every k-th: a photograph's map, a stack of patterns)


def _sampled(value, depth: int = 0):
    """``value`` with every array of more than :data:`SAMPLE` entries cut to every k-th of them (its shape kept beside):
    an answer alike to another is alike in those too, and the grader holds a few hundred kilobytes a function at most,
    whatever the answers are."""
    if depth >= 4:
        return fingerprint(value)   # (deeper than any answer the API asks for: stands for itself)
    if isinstance(value, (list, tuple)):   # (a long sequence: its length and its first items)
        kept = type(value)(_sampled(item, depth + 1) for item in value[:16])
        return kept if len(value) <= 16 else (len(value), kept)
    if isinstance(value, dict):
        return {key: _sampled(item, depth + 1) for key, item in list(value.items())[:16]}
    if isinstance(value, np.ndarray) and value.size > SAMPLE:
        return (value.shape, np.ascontiguousarray(value.reshape(-1)[::-(-value.size // SAMPLE)]))
    return value


def zero_constant(sandbox, exercise, results: list[CheckResult]) -> None:
    """Set to 0 the points of ``results`` (the exercise's checks) that called a function of the exercise
    answering one same answer to inputs whose right answers differ (told once, in each such check)."""
    shared = getattr(sandbox, "shared", {})
    for function in exercise.signatures:
        seen = shared.get((KEY, exercise.lab.module, function))
        if not seen or seen["varies"] or len(seen["inputs"]) < 2:
            continue
        if not _right_answers_differ(exercise.lab, function, list(seen["inputs"].values())):
            continue
        said = (f"{function}() gave one same answer to each of the {len(seen['inputs'])} different inputs it was "
                "given, whose right answers differ: its answer does not depend on what it is given, so no check of "
                "its answers can pass")
        for k, result in enumerate(results):
            if result.max_score > 0 and result.score > 0 and (exercise.id, result.name) in seen["checks"]:
                results[k] = replace(result, score=0.0, status=FAILED, message=said, hint="", mistake=MISTAKE)


def _right_answers_differ(lab, function: str, inputs: list) -> bool:
    """Whether the reference answers ``inputs`` [(args, kwargs)] of ``function`` otherwise than all alike
    (beyond a scale and a sign); False without a reference or its answers."""
    from .mutants import naming
    from .mutants.helper import HelperFailed

    model = naming.model_for(lab)
    if model is None:
        return False
    calls = [(function, tuple(args), dict(kwargs)) for args, kwargs in inputs]
    try:
        runner = naming.helper()
        runner.prepare(model.source, model.module, calls, SECONDS)
        answers = runner.run((), range(len(calls)), SECONDS)
    except HelperFailed:
        return False
    finally:
        naming.release_helper()
    answers = [a for a in answers if naming.error_kind(a) is None]
    return any(_differ(answers[0], other) for other in answers[1:])


def _differ(a, b) -> bool:
    """Whether two answers differ in structure, in shape, or in their numbers beyond a scale and a sign."""
    if isinstance(a, (list, tuple)) or isinstance(b, (list, tuple)):
        return not (isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)) and len(a) == len(b)) \
            or any(_differ(x, y) for x, y in zip(a, b))
    if isinstance(a, dict) or isinstance(b, dict):
        return not (isinstance(a, dict) and isinstance(b, dict) and a.keys() == b.keys()) \
            or any(_differ(a[key], b[key]) for key in a)
    try:
        x, y = np.asarray(a, np.float64), np.asarray(b, np.float64)
    except (TypeError, ValueError):
        return a != b
    if x.shape != y.shape or not np.array_equal(np.isfinite(x), np.isfinite(y)):
        return True
    x, y = np.where(np.isfinite(x), x, 0.0), np.where(np.isfinite(y), y, 0.0)   # (NaN where NaN is: alike)
    if not x.any() or not y.any():
        return bool(x.any() or y.any())
    return not projective_distance(x, y) <= DIFFERENT
