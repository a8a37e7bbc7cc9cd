"""A failure inherited from another of the student's functions, told as such (issue 35).

Students' modules call their own API functions from other API functions: lab 12's
``simulate_structured_light`` calls the student's ``gray_code_patterns``, lab 11's pipeline the
student's ``essential_from_fundamental`` and ``triangulate``, lab 8's ``stitch`` the student's
``homography_ransac``. When the callee ``g`` is wrong and the caller ``f`` is right, ``f``'s checks
fail too; telling the student ``f``'s recipe ("pixel (u, v) at depth Z sees projector column
round(u - f*baseline/Z) ...") then describes what their ``f`` already does.

When a check of ``f`` fails (its own value judged, the check calling no other API function):

1. **Which API functions the student's** ``f`` **calls** is read from its code
   (:func:`api_callees`: :func:`autograder.engine.hints.read_code`, which follows aliases,
   ``module.f``, nested functions and the module's private helpers), and likewise the reference's;
   the *substitutes* are the callees both call.
2. **Is** ``f`` **right given the student's** ``g``? The reference ``f`` runs in the error model's
   helper process (:mod:`autograder.engine.mutants.helper`: trusted code, outside the student's
   sandbox, never in it) with each substitute ``g`` replaced by a stand-in answering what the
   *student's* ``g`` answers on the arguments the reference ``f`` passes it. Those answers are asked
   of the student's sandbox through its usual calls (plain data both ways, never pickle): a first
   run records the arguments (it is the reference's own answer, ``R``), the student's ``g`` is
   asked on them, and the reference runs again on the student's answers (a few rounds when a later
   call's arguments depend on an earlier answer). Its answer ``M`` is what a right ``f`` gives on
   the student's ``g``. For the first and the last call of ``f`` in the trial (the check's own
   input; a property's failing example), the student's answer ``S``:

   - ``S`` agrees with ``R``: the call is right (not judged);
   - the student's ``g`` agrees with the reference's on every argument asked, or ``S`` does not
     agree with ``M``: ``f``'s own failure (its diagnosis is kept);
   - else (``S`` agrees with ``M``, some ``g`` answered otherwise than the reference's ``g``):
     the failure is **inherited**.

   "Agrees" is :func:`same_answer`: the same structure, integer arrays (images) equal but for a
   grey level at 0.1% of their entries, floats within float32's precision of their magnitude
   (:func:`~autograder.engine.compare.at_precision` of a millionth) -- stricter than most checks, so
   that a caller with a mistake of its own is never said to be right.
3. An inherited failure's message says so in the student's terms ("Your
   ``simulate_structured_light`` itself is right here: on what your ``gray_code_patterns`` returned
   for gray_code_patterns(160, 6), a correct ``simulate_structured_light`` gives exactly your
   answer ..."); ``f``'s recipe hint and named mistake are withheld, and the error model and the
   code reading, which would name a mistake of ``f``, are not run. **The points are still lost**:
   the contract judges ``f``'s output, and a self-contained ``f`` giving the same output loses
   them too (giving them back would make a score depend on how the module is split into
   functions). The message only tells where the fault is.
4. **Static fallback**, when the dynamic test cannot decide (no reference in this copy of the
   grader, the reference raising on the student's answers, arguments that cannot cross, the time
   spent) or finds ``f`` wrong too: when a callee of the student's ``f`` failed its own checks in
   this grading, the message adds "Your ``f`` calls your ``g``, which fails its own checks in this
   grading: fix ``g`` first, then see what this check says"; the hints stay, each held to the
   student's code by :mod:`autograder.engine.claims` (a recipe the code already follows is not said).

Time is bounded: :data:`CHECK_SECONDS` per failed check, :data:`GRADING_SECONDS` per grading (kept on
the sandbox), and half of what the exercise's budget and the submission's deadline leave; each
helper run within what is left; the student's calls are billed to the check as
any other call (the exercise's budget). A decision is kept for the grading, by the call's input and
answer: lab 11's three pipeline checks on the same photos decide once.
"""

from __future__ import annotations

import logging
import threading
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from .claims import measured
from .compare import at_precision, magnitude
from .hints import Code, code_of, read_code

CHECK_SECONDS = 6.0       # for one failed check (the helper runs the reference a few times)
GRADING_SECONDS = 15.0    # for one grading's failed checks together
ROUNDS = 3                # reference runs per call (each adds the student's answers it needed)
ASKED = 16                # the student's callee answers asked per call, at most
PIXEL_SHARE = 0.001       # integer entries (pixels) that may differ by more than one level
FLOAT_RELATIVE = 1e-6     # float entries: this much of their magnitude (float32's precision at least)

INHERITED = "inherited"   # a decision: the failure comes from the callees
OWN = "own"               # the function itself is wrong (or its callees are right)
SHARED_FAILING = "inherited: functions failing their own checks"
SHARED_RIGHT_ITSELF = "inherited: functions told right but for a function they call"
SHARED_SECONDS = "inherited: seconds"


# ------------------------------------------------------------------ reading the calls
def api_callees(code: Code, function: str, api) -> frozenset[str]:
    """The API functions (``api``) other than ``function`` that ``code``'s ``function`` calls:
    directly, or through the module's functions that are not API functions (private helpers,
    nested functions, aliases and ``module.f``: :func:`~autograder.engine.hints.read_code`); an API
    function's own callees are its own business (not followed)."""
    api = frozenset(api)
    found, seen, todo = set(), {function}, [function]
    while todo:
        for callee in sorted(code.calls.get(todo.pop(), ())):
            if callee in seen:
                continue
            seen.add(callee)
            if callee in api:
                found.add(callee)
            else:
                todo.append(callee)
    return frozenset(found)


def private_helpers(code: Code, function: str, api) -> frozenset[str]:
    """The module's functions other than API functions (``api``) that ``code``'s ``function`` goes
    through: called by it or by such helpers (an API function's own helpers are not followed)."""
    api = frozenset(api)
    found, todo = set(), [function]
    while todo:
        for callee in sorted(code.calls.get(todo.pop(), ())):
            if callee not in found and callee not in api and callee != function and callee in code.functions:
                found.add(callee)
                todo.append(callee)
    return frozenset(found)


def _api(lab) -> frozenset[str]:
    return frozenset(name for exercise in lab.exercises.values() for name in exercise.signatures)


_REFERENCES: dict = {}
_REFERENCES_LOCK = threading.Lock()


def reference_of(lab) -> tuple[str, Code] | None:
    """The lab's reference module (text and code read), as the error model finds it
    (:func:`autograder.engine.mutants.naming.reference_module`); None without one."""
    from .mutants.naming import reference_module

    path = reference_module(lab)
    if path is None:
        return None
    try:
        key = (str(path), Path(path).stat().st_mtime_ns)
    except OSError:
        return None
    with _REFERENCES_LOCK:
        if key not in _REFERENCES:
            text = Path(path).read_text(encoding="utf-8")
            _REFERENCES[key] = (text, read_code(text))
        return _REFERENCES[key]


def calls_judged(trial) -> list:
    """The calls whose answers the trial's check judged: those it made and those behind the values
    another check's ``t.shared`` served it (:attr:`~autograder.engine.checks.Trial.served`)."""
    return list(getattr(trial, "served", ())) + list(trial.calls)


def exercised(trial) -> frozenset[str]:
    """The student functions whose answers the trial's check judged (:func:`calls_judged`); when none
    answered (the first call raised), those its code names
    (:func:`~autograder.engine.stubs.functions_called`)."""
    from .stubs import functions_called

    called = {call[0] for call in calls_judged(trial)}
    raised = getattr(trial, "raised", None)
    if raised:
        called.add(raised[0])
    check = getattr(trial, "check", None)
    return frozenset(called or (functions_called(check) if check is not None else ()))


# ------------------------------------------------------------------ comparing answers
def _leaves(value, out: list, depth: int = 0) -> None:
    """Flatten an answer: arrays (numbers as 0-d arrays), and markers of its structure."""
    if isinstance(value, (list, tuple)) and depth < 16:
        if value and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            out.append(np.asarray(value, dtype=np.float64))
            return
        out.append(("seq", len(value)))
        for item in value:
            _leaves(item, out, depth + 1)
    elif isinstance(value, dict) and depth < 16:
        out.append(("dict", tuple(sorted(map(str, value)))))
        for key in sorted(value, key=str):
            _leaves(value[key], out, depth + 1)
    elif isinstance(value, np.ndarray) and value.dtype.kind in "biufc":
        out.append(value)
    elif isinstance(value, (int, float, complex)) and not isinstance(value, bool):
        out.append(np.asarray(value))
    else:
        out.append(("other", repr(value)[:200]))


def same_answer(a, b) -> bool:
    """Whether answers ``a`` and ``b`` are the same answer: the same structure and shapes; integer
    arrays (images, indices) equal but for :data:`PIXEL_SHARE` of their entries off by more than one
    level; float entries within :func:`~autograder.engine.compare.at_precision` of
    :data:`FLOAT_RELATIVE` of ``b``'s magnitude, NaN and infinities in the same places."""
    left, right = [], []
    _leaves(a, left)
    _leaves(b, right)
    if len(left) != len(right):
        return False
    for x, y in zip(left, right):
        if isinstance(x, tuple) or isinstance(y, tuple):
            # (an array beside another kind of value is another answer: no comparison that broadcasts)
            if not (isinstance(x, tuple) and isinstance(y, tuple)) or x != y:
                return False
            continue
        if x.shape != y.shape:
            return False
        if x.size == 0:
            continue
        if x.dtype.kind in "biu" and y.dtype.kind in "biu":
            apart = np.abs(x.astype(np.int64) - y.astype(np.int64)) > 1
            if apart.mean() > PIXEL_SHARE:
                return False
            continue
        if "c" in x.dtype.kind + y.dtype.kind:
            x, y = x.astype(np.complex128), y.astype(np.complex128)
        else:
            x, y = x.astype(np.float64), y.astype(np.float64)
        finite = np.isfinite(x)
        if not np.array_equal(finite, np.isfinite(y)) or not np.array_equal(x[~finite], y[~finite],
                                                                              equal_nan=True):
            return False
        if finite.any():
            scale = magnitude(np.abs(y[finite]))
            if np.max(np.abs(x[finite] - y[finite])) > at_precision(FLOAT_RELATIVE * scale, scale):
                return False
    return True


# ------------------------------------------------------------------ the helper's side
# Appended to the reference's text in the helper process (never the student's sandbox): see
# autograder/engine/stand_ins.py.
APPENDIX = "\n\n" + (Path(__file__).parent / "stand_ins.py").read_text(encoding="utf-8")
ENTRY = "_autograder_given_answers"   # the stand-in runner APPENDIX defines


# ------------------------------------------------------------------ deciding
@dataclass(frozen=True)
class Decision:
    """How one failing call of ``function`` is explained: :data:`INHERITED` (``callees`` answered
    otherwise than they should, ``shown`` the first such call, and ``function`` gives exactly
    what a right one gives on their answers) or :data:`OWN`."""

    kind: str
    function: str
    callees: tuple = ()
    shown: str = ""


def _shown_value(value) -> str | None:
    """A scalar or a tiny array as written; None for anything larger (named by its parameter)."""
    if isinstance(value, np.ndarray):
        return np.array2string(value, separator=", ") if value.size <= 4 else None
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, (list, tuple)) and 0 < len(value) <= 4 and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
        return f"({', '.join(_shown_value(v) for v in value)})"
    text = repr(value)
    return text if len(text) <= 24 and not isinstance(value, (list, tuple, dict)) else None


def shown_call(signature: str, args, kwargs) -> str:
    """A call as the student would read it: ``gray_code_patterns(160, 6)``; larger values by their
    parameter's name in ``signature`` (``"triangulate(P1, P2, pts1, pts2)"``), arrays' shapes after:
    ``triangulate(P1, P2, pts1, pts2) with arrays of shapes (3, 4), (3, 4), (243, 2), (243, 2)``."""
    function, _, rest = signature.partition("(")
    params = [p.split("=")[0].strip() for p in rest.rstrip(")").split(",") if p.strip()]
    parts, shapes = [], []
    for index, value in enumerate(args):
        shown = _shown_value(value)
        name = params[index] if index < len(params) else f"argument {index + 1}"
        parts.append(shown if shown is not None else name)
        if shown is None and isinstance(value, np.ndarray):
            shapes.append(str(value.shape))
    for key, value in kwargs.items():
        shown = _shown_value(value)
        parts.append(f"{key}={shown if shown is not None else key}")
        if shown is None and isinstance(value, np.ndarray):
            shapes.append(str(value.shape))
    text = f"{function}({', '.join(parts)})"
    if shapes:
        text += f" with {'an array' if len(shapes) == 1 else 'arrays'} of shape{'s' * (len(shapes) > 1)} " \
            + ", ".join(shapes)
    return text


_FAILED = object()


def _student_answer(trial, function: str, args, kwargs, asked_for: str):
    """The student's ``function`` on these arguments, through the sandbox (billed to the check; what
    it prints labelled as the grader's call); :data:`_FAILED` when it did not answer."""
    lab = trial.lab
    outcome = trial.sandbox.call(lab.module, function, tuple(args), dict(kwargs), timeout=trial.check.timeout,
                                 forbid=lab.forbidden.get(function, ()) + tuple(trial.forbid.get(function, ())))
    trial.student_seconds += outcome.seconds
    if outcome.output.strip():
        trial.outputs.append(f"(printed during the grader's call to {function}(), asked to tell whether "
                             f"{asked_for}()'s failure comes from it)\n{outcome.output}")
    return outcome.value if outcome.ok else _FAILED


def _decide_call(trial, runner, source: str, module: str, function: str, substitutes, args, kwargs, answer,
                 clock) -> Decision | None:
    """The :class:`Decision` for one call of ``function`` whose student answer is ``answer``; None when
    the call is right or nothing can be decided (see the module docstring)."""
    from .mutants.helper import ERROR

    answers: dict = {g: [] for g in substitutes}   # g -> [[args, kwargs, the student's answer], ...]
    differ: list = []                              # (g, the call shown) the student's g answers otherwise
    reference, asked = None, 0
    for _ in range(ROUNDS):
        if clock.left() <= 0:
            return None
        call = (ENTRY, (function, answers, tuple(args), dict(kwargs)), {})
        runner.prepare(source, module, [call], max(1.0, clock.wall_left()))
        [reply] = runner.run((), [0], max(0.2, clock.wall_left()))
        if not isinstance(reply, dict) or ERROR in reply:
            return None   # the reference raised on the student's answers, or they cannot cross
        if reference is None:
            reference = reply["value"]   # no answer given: the reference's own
            if same_answer(answer, reference):
                return None   # this call is right
        needed = reply["needed"]
        if not needed:
            model = reply["value"]
            break
        for g, g_args, g_kwargs, right in needed:
            asked += 1
            if asked > ASKED or clock.left() <= 0:
                return None
            theirs = _student_answer(trial, g, g_args, g_kwargs, function)
            if theirs is _FAILED:
                return None
            answers[g].append([g_args, g_kwargs, theirs])
            if not same_answer(theirs, right):
                differ.append((g, shown_call(trial.lab.signature(g), g_args, g_kwargs)))
    else:
        return None
    callees = tuple(dict.fromkeys(g for g, _ in differ))
    if callees and same_answer(answer, model):
        return Decision(INHERITED, function, callees, differ[0][1])
    return Decision(OWN, function)


def _judged_calls(trial, function: str) -> list:
    """The calls of ``function`` decided on: the trial's first (the check's own input; probes come
    after it) and its last (a property's failing example), once each."""
    from .checks import fingerprint

    calls, seen = [c for c in calls_judged(trial) if c[0] == function], set()
    judged = []
    for call in calls[:1] + calls[-1:]:
        key = fingerprint(call[1], call[2])
        if key not in seen:
            seen.add(key)
            judged.append(call)
    return judged


def decide(trial, function: str, substitutes, seconds: float = CHECK_SECONDS) -> Decision | None:
    """Whether the failure of ``trial``'s calls of ``function`` is inherited from the student's
    ``substitutes`` (see the module docstring): None when it cannot be decided."""
    from .checks import fingerprint
    from .mutants import naming

    found = reference_of(trial.lab)
    if found is None or not substitutes:
        return None
    source = found[0] + APPENDIX
    shared = trial.sandbox.shared
    spent = shared.setdefault(SHARED_SECONDS, [0.0])
    remaining = getattr(trial.sandbox, "remaining", lambda: float("inf"))()
    # at most half what the exercise's budget and the submission's deadline leave (this machine's seconds,
    # a naming's are the budgets' machine's): the checks after come first
    clock = naming.work_clock(trial, min(seconds, GRADING_SECONDS - spent[0], remaining / 2 / naming.machine_pace()))
    decisions = []
    try:
        for _, args, kwargs, answer in _judged_calls(trial, function):
            if clock.left() <= 0:
                break
            key = ("inherited", function, tuple(sorted(substitutes)), fingerprint(args, kwargs), fingerprint(answer))
            if key not in shared:
                try:
                    shared[key] = _decide_call(trial, naming.helper(), source, trial.lab.module, function,
                                               substitutes, args, kwargs, answer, clock)
                except naming.HelperFailed:
                    return None   # cut short (not kept: another check may have the time)
            if shared[key] is not None:
                decisions.append(shared[key])
    finally:
        spent[0] += clock.used()
        naming.release_helper()
    if not decisions:
        return None
    own = next((d for d in decisions if d.kind == OWN), None)
    return own or decisions[0]


# ------------------------------------------------------------------ telling
def _names(callees) -> str:
    named = [f"`{g}`" for g in callees]
    return named[0] if len(named) == 1 else ", ".join(named[:-1]) + f" and your {named[-1]}"


def inherited_sentence(decision: Decision, failing) -> str:
    """What an inherited failure's message says first (``failing``: the functions known to fail their
    own checks in this grading; a hidden check's fresh worker knows none)."""
    f, callees, one = decision.function, decision.callees, len(decision.callees) == 1
    known = set(callees) <= set(failing)
    whose = (" (see its own checks)" if one else " (see their own checks)") if known else ""
    # measured: the reference, given the student's callee's answers, gave the student's answer
    return measured(f"Your `{f}` itself is right here: given what your {_names(callees)} "
                    f"{'returns' if one else 'return'} ({decision.shown}), it gives exactly what a correct "
                    f"`{f}` gives. Its answer is wrong because your {_names(callees)} {'is' if one else 'are'} "
                    f"wrong there{whose}: fix {'it' if one else 'them'} first.")


def dependency_sentence(function: str, callees) -> str:
    """The static fallback's sentence: ``function`` calls callees that fail their own checks."""
    which = "fails its own checks" if len(callees) == 1 else "fail their own checks"
    # measured: the callees' own checks failed in this grading, and the function's code calls them
    return measured(f"Your `{function}` calls your {_names(callees)}, which {which} in this grading: fix "
                    f"{'it' if len(callees) == 1 else 'them'} first, then see what this check says.")


def shared_helper_sentence(function: str, helpers, others) -> str:
    """The static fallback's sentence where ``function`` goes through private ``helpers`` that the API
    functions ``others``, failing their own checks, go through too."""
    def joined(word: str) -> str:
        return ", ".join(f"`{h}`" for h in helpers[:-1]) + (f" {word} " if len(helpers) > 1 else "") + f"`{helpers[-1]}`"
    named, one = joined("and"), len(others) == 1
    # measured: the others' own checks failed in this grading; the code reads that both go through the helpers
    return measured(f"Your `{function}` goes through your {named}, which your {_names(others)} "
                    f"{'uses' if one else 'use'} too, and {'it fails its' if one else 'they fail their'} own checks "
                    f"in this grading: a mistake in {joined('or')} would fail this check as well.")


def _failing(trial) -> set:
    return trial.sandbox.shared.setdefault((SHARED_FAILING, trial.lab.module), set())


def told(verdict, trial):
    """``(verdict, inherited)``: a failed check's verdict told as inherited when it is (its recipe
    hint and named mistake withheld, the points unchanged), or with the static fallback's
    sentence added; and whether it was inherited (the runner then names no mistake of the
    function). Records, for later checks, a function failing its own checks."""
    called = exercised(trial)
    code = code_of(trial)
    failing = _failing(trial)
    if len(called) != 1:
        # (a check judging a function and one it calls -- RANSAC and the DLT it fits with -- is judged of the caller:
        # where the callee fails its own checks, that is said (the static fallback), not decided by the dynamic test)
        api = _api(trial.lab)
        callers = [f for f in sorted(called) if code.functions and called - {f} <= api_callees(code, f, api)]
        depends = sorted(api_callees(code, callers[0], api) & failing) if len(callers) == 1 else []
        if depends:
            failing.add(callers[0])
            verdict = _waiting(verdict, dependency_sentence(callers[0], depends))
        return verdict, False
    [function] = called
    callees = api_callees(code, function, _api(trial.lab)) if code.functions else frozenset()
    reference = reference_of(trial.lab)
    substitutes = callees & api_callees(reference[1], function, _api(trial.lab)) if reference else frozenset()
    decision = None
    if substitutes:
        try:
            decision = decide(trial, function, substitutes)
        except Exception:  # noqa: BLE001 - the verdict stands without it (logged)
            logging.getLogger("autograder").exception("inherited failure test of %s", trial.check.id)
    if decision is not None and decision.kind == INHERITED:
        # the check's first line judges (or names a mistake of) the function: what follows it
        # (a property's failing input) stays
        rest = str(verdict.message).partition("\n")[2]
        message = inherited_sentence(decision, failing) + ("\n" + rest if rest else "")
        trial.sandbox.shared.setdefault((SHARED_RIGHT_ITSELF, trial.lab.module), set()).add(function)
        return replace(verdict, message=message, hint="", mistake=""), True
    failing.add(function)
    depends = sorted(callees & failing)
    # (a function found right itself where it failed -- its callee's answers wrong -- says nothing of the helpers it
    # shares: `rotate` right but for `rotation_matrix`'s sign was no evidence against `_apply`)
    suspects = failing - {function} - trial.sandbox.shared.get((SHARED_RIGHT_ITSELF, trial.lab.module), set())
    if depends:
        verdict = _waiting(verdict, dependency_sentence(function, depends))
    elif code.functions and suspects:
        verdict = _shared_with_failing(verdict, code, function, suspects, _api(trial.lab))
    return verdict, False


def _waiting(verdict, sentence: str):
    """``verdict`` told to wait for the callees failing their own checks (``sentence``). The check says what it can
    only once they are fixed: a recipe hint about the function's own steps -- "look at how many samples it draws"
    to a RANSAC fitting with a wrong DLT -- waits with it; a mistake the check named of the function keeps its hint."""
    return replace(verdict, message=f"{str(verdict.message).rstrip()}\n{sentence}",
                   hint=verdict.hint if verdict.mistake else "")


def _shared_with_failing(verdict, code: Code, function: str, failing, api):
    """``verdict`` with :func:`shared_helper_sentence` added where ``function`` goes through private helpers
    of failing API functions (``stitch`` and ``match_features`` both detecting with ``_detect``)."""
    mine = private_helpers(code, function, api)
    if not mine:
        return verdict
    others, helpers = [], set()
    for other in sorted(failing):
        shared = mine & private_helpers(code, other, api)
        if shared:
            others.append(other)
            helpers |= shared
    if not others:
        return verdict
    sentence = shared_helper_sentence(function, sorted(helpers), others)
    return replace(verdict, message=f"{str(verdict.message).rstrip()}\n{sentence}")
