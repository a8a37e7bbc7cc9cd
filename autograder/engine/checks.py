"""What a check sees: the trial object ``t``, verdicts, and failures.

A check is a function of one argument, ``t`` (a :class:`Trial`). It calls the
student's functions with ``t.call``, judges the results in the grader's process,
and ends in one of three ways:

- returns ``None`` (full points) or ``passed("what was verified")``;
- returns ``partial(fraction, message, hint)`` for partial credit;
- raises :class:`Fail` (through ``t.fail`` / ``t.expect_array``), for no points.

If the student's code raises, hangs or crashes, ``t.call`` raises
:class:`StudentFailure` and the check scores 0 with the student's own message.
Anything else escaping a check is a grader error, reported as such.

An advice check (registered with ``@exercise.advice(name)``, 0 points) calls
``t.advise(message)`` when it has a tip and returns normally otherwise; a
failure inside it is silent (the graded checks report it).
"""

from __future__ import annotations

import re
import functools
import hashlib
import threading
from dataclasses import dataclass

import numpy as np

from ..sandbox.beginner import uint8_wraps
from ..sandbox.supervisor import CallOutcome, Sandbox, array_bytes
from . import pictures
from .claims import measured
from .forms import shape_form
from .inputs import NO_SUBMISSION
from .registry import Check
from .results import Artifact

# Failure kinds after which calling the same function again in this check is pointless.
_FATAL_KINDS = {"timeout", "crashed", "memory", "output_too_large", "import_error",
                "missing_module", "missing_function", "not_implemented", "forbidden_call",
                "budget", "protocol"}


@dataclass
class Verdict:
    fraction: float
    message: str = ""
    hint: str = ""
    mistake: str = ""  # the named mistake, when the check recognised one (class reports count them)


def passed(message: str = "") -> Verdict:
    return Verdict(1.0, message)


def partial(fraction: float, message: str, hint: str = "", mistake: str = "") -> Verdict:
    """Partial credit: ``fraction`` of the check's points (clipped to [0, 1])."""
    return Verdict(float(min(max(fraction, 0.0), 1.0)), message, hint, mistake)


class Fail(Exception):
    """The student's answer is wrong: no points for this check.

    ``mistake`` names the recognised mistake in a few words ("the rotation goes
    the opposite way ..."), the same for every student who makes it.
    """

    def __init__(self, message: str, hint: str = "", mistake: str = ""):
        super().__init__(message)
        self.message, self.hint, self.mistake = message, hint, mistake


class ChangedInPlace(Fail):
    """The student's function changed its caller's array, and a second call on it answers
    differently (see :mod:`autograder.engine.inplace`)."""


class StudentFailure(Exception):
    """The student's function did not return normally (raised, hung, crashed, missing...)."""

    def __init__(self, outcome: CallOutcome, message: str):
        super().__init__(message)
        self.outcome, self.message = outcome, message

    def said(self, message: str) -> "StudentFailure":
        """The same failure told with ``message`` (the input it was raised on added): what was noted on
        it on the way (whose function failed, for a validation's report) stays."""
        told = StudentFailure(self.outcome, message)
        told.__dict__.update({k: v for k, v in vars(self).items() if k not in ("outcome", "message")})
        return told


_KIND_NAMES = {"f": "float", "i": "integer", "u": "unsigned integer", "b": "bool", "c": "complex"}


def _kind_too(value: np.ndarray, dtype, kind) -> str:
    """What a result of the wrong shape gets wrong besides, in its type ("" when nothing): told with the
    shape, so that mending the shape alone is not a second failed submission (OpenCV's (N, 1) uint8 mask
    where a flat boolean one is asked)."""
    if dtype is not None and value.dtype != np.dtype(dtype):
        wanted = str(np.dtype(dtype))
    elif kind is not None and value.dtype.kind not in kind:
        wanted = " or ".join(_KIND_NAMES[k] for k in kind)
    else:
        return ""
    from .claims import measured   # (claims reads checks: imported when a result is told)

    # (read only where small: a mask's length, never a student's huge answer sorted)
    zeros_ones = kind == "b" and value.dtype.kind in "iu" and 0 < value.size <= 1_000_000 \
        and bool(((value == 0) | (value == 1)).all())
    return measured(f"; its values are also {value.dtype} where {wanted} is asked" + (
        " (0/1 integers used as an index pick rows 0 and 1, not the rows marked 1: astype(bool))"
        if zeros_ones else ""))


def fingerprint(*values) -> str:
    """A short key for values given to a student's function (arrays by their bytes, other
    values by repr): a probe's input, and every input a check gives (:attr:`Trial.given`)."""
    digest = hashlib.sha1()
    for value in values:
        if isinstance(value, np.ndarray):
            digest.update(f"{value.dtype}{value.shape}".encode())
            digest.update(np.ascontiguousarray(value).tobytes())
        elif isinstance(value, (tuple, list)):
            digest.update(fingerprint(*value).encode())
        elif isinstance(value, dict):
            digest.update(fingerprint(*sorted(value.items(), key=lambda item: str(item[0]))).encode())
        else:
            digest.update(repr(value).encode())
    return digest.hexdigest()[:16]


_CALLS_KEPT = 32   # a property's hundreds of calls: its last ones hold the failing example
_CALLS_BYTES = 64 * 2**20   # and at most this much of their answers, the last one whatever its size: the grader
                            # holds what a check keeps while it runs (hostile round of 2026-12-07)
_EXAMPLES_KEPT = 3   # a property's passing examples kept for running its check again

# Hypothesis's engine runs one property at a time, whatever the lanes (runner.grade): the
# examples it draws never depend on another lane's property.
_ONE_ENGINE = threading.Lock()


def _within_bytes(calls: list, largest: int) -> None:
    """Drop the oldest of ``calls`` [(function, args, kwargs, answer)] until their answers' arrays hold at most
    ``largest`` bytes (the last call is kept whatever its size)."""
    sizes = [array_bytes(call[3]) for call in calls]
    while len(calls) > 1 and sum(sizes) > largest:
        del calls[0], sizes[0]


class Trial:
    """The handle a check uses to call student code and attach pictures.

    Parameters
    ----------
    sandbox : Sandbox
        The submission's worker.
    check : Check
        The check being run (for its exercise, lab, timeout and forbidden calls).
    forbid : dict, optional
        The instructor's extra forbidden calls, per student function.
    inputs : Inputs, optional
        Where the submission's properties draw their inputs (see
        :mod:`autograder.engine.inputs`); by default those of no submission.

    A check that draws its own inputs (every hidden check: angles, scales, seeds of
    scenes, noise) draws them from :attr:`rng`, never from fixed values nor the clock.
    """

    def __init__(self, sandbox: Sandbox, check: Check, forbid: dict | None = None, inputs=None):
        self.sandbox, self.check = sandbox, check
        self.inputs = inputs if inputs is not None else NO_SUBMISSION
        self.lab = check.exercise.lab
        self._thread = threading.get_ident()  # the sandbox's one caller
        self.forbid = forbid or {}
        self.forbidden_allowed = False   # (a second look at what a forbidden call's answer was worth)
        self._pictures: list = []  # made into Artifacts only if the grading keeps them
        self.outputs: list[str] = []
        self.student_seconds = 0.0
        self._fatal: dict[str, StudentFailure] = {}
        self.tips: list[tuple[str, str]] = []  # (message, hint) from t.advise
        # (function, argument) pairs the student's function modified in place.
        self.modified_inputs: list[tuple[str, str]] = []
        self._properties = 0  # t.for_all calls so far (each has its recorded examples)
        # Per t.for_all call, the examples that decided it: the failing one, or a few that passed (a
        # check run again on them -- autograder.engine.mutants.repair -- needs no Hypothesis engine).
        self.property_examples: list[list] = []
        self._probed: dict = {}  # confirmation probes' answers, asked once per trial (see probe)
        # The calls behind the values this trial was served from another check's t.shared, as in
        # calls: what it judged although it called nothing (autograder.engine.inherited).
        self.served: list[tuple[str, tuple, dict, object]] = []
        self._in_place: dict = {}  # (function, input) -> how its change of the caller's array shows ("": not)
        self._last_changed: tuple = ()  # the arrays the last call changed in place (see held)
        # Student functions that, in this trial, were given fractional numbers and returned only
        # whole ones (the values' side of autograder.loading.reading's findings about truncation).
        self.whole_numbers: set[str] = set()
        # Every call's function and arguments, in order: two gradings of the same files must give
        # the same (autograder verify), else the check draws inputs from the clock or an unseeded RNG.
        self._given = hashlib.sha1()
        # The calls that returned, as (function, args, kwargs, answer), the last few: what the
        # error model (autograder.engine.mutants) reproduces when the check fails.
        self.calls: list[tuple[str, tuple, dict, object]] = []
        # The last call that raised, as (function, args, kwargs, message): the error model names the
        # cause of a check that ended by the student's exception from it.
        self.raised: tuple | None = None
        self.raised_lines: tuple = ()   # the lines of the student's module in its traceback, outermost first

    @functools.cached_property
    def rng(self) -> np.random.Generator:
        """This submission's generator for this check (:meth:`Inputs.generator` of the
        check's id): the same files and course secret draw the same values on every run and
        machine, other files or another secret other values. Draw in a fixed order."""
        return self.inputs.generator(self.check.id)

    @property
    def given(self) -> str:
        """A digest of every call this trial made so far (function and arguments, in order)."""
        return self._given.hexdigest()[:16]

    # ------------------------------------------------------------ calling
    def call(self, function: str, *args, **kwargs):
        """Call the student's ``function`` and return its (plain-data) result.

        Raises
        ------
        StudentFailure
            If it raised, timed out, crashed, is missing or returned a forbidden type.
        """
        if threading.get_ident() != self._thread:
            raise RuntimeError("student code is called from the check itself, never while a picture is "
                               "drawn (pictures are drawn on other threads)")
        self._given.update(fingerprint(function, args, kwargs).encode())
        failure = self._fatal.get(function)
        if failure is None:
            outcome = self.sandbox.call(self.lab.module, function, args, kwargs,
                                        timeout=self.check.timeout, forbid=self.forbidden(function))
            self.student_seconds += outcome.seconds
            if outcome.output.strip():
                self.outputs.append(outcome.output)
            for argument in outcome.modified:
                if (function, argument) not in self.modified_inputs:
                    self.modified_inputs.append((function, argument))
            if outcome.ok:
                self.calls.append((function, args, kwargs, outcome.value))
                del self.calls[:-_CALLS_KEPT]
                _within_bytes(self.calls, _CALLS_BYTES)
                if function not in self.whole_numbers and _whole_numbers(outcome.value) \
                        and _fractional((args, kwargs)):
                    self.whole_numbers.add(function)
                self._last_changed = outcome.changed
                if outcome.changed:
                    self._changed_in_place(function, args, kwargs, outcome)
                if outcome.shared:
                    self._one_array_handed_out(function, outcome)
                return outcome.value
            failure = StudentFailure(outcome, self._describe(function, outcome))
            if outcome.kind == "exception":
                self.raised = (function, args, kwargs, outcome.message)
                self.raised_lines = _lines_of(outcome.traceback, self.lab.module)
            if outcome.kind in _FATAL_KINDS:
                self._fatal[function] = failure
        # One raise site, and a fresh exception each time: Hypothesis tells failures
        # apart by where they are raised, and re-raising one object grows its traceback.
        raise StudentFailure(failure.outcome, failure.message)

    def forbidden(self, function: str) -> tuple[str, ...]:
        """The library functions ``function`` may not call in this trial: the lab's and the instructor's
        (none in a trial that judges the answer a forbidden call gave: :func:`.runner.besides_forbidden`)."""
        if self.forbidden_allowed:
            return ()
        return self.lab.forbidden.get(function, ()) + self.forbid.get(function, ())

    def _changed_in_place(self, function: str, args: tuple, kwargs: dict, outcome: CallOutcome):
        """Fail the check when ``function`` changed its caller's arrays and a second call on them,
        as the caller now holds them, answers differently (:mod:`autograder.engine.inplace`): in the
        first public check of the grading where that shows, and again in it for the same input."""
        from . import inplace

        owners = getattr(self.sandbox, "shared", None)
        if owners is None or self.check.hidden:
            return   # hidden checks run in a sandbox of their own: the public check says it, once
        owner = owners.get(("changed in place", self.lab.module, function))
        if owner not in (None, self.check.id):
            return
        given = (function, fingerprint(args, kwargs))
        if given not in self._in_place:
            def again(call_args, call_kwargs):
                more = self.sandbox.call(self.lab.module, function, call_args, call_kwargs,
                                         timeout=self.check.timeout, forbid=self.forbidden(function))
                self.student_seconds += more.seconds
                return more.value if more.ok else None

            self._in_place[given] = inplace.effect_of_change(again, function, self.lab.signature(function), args,
                                                             kwargs, outcome, fingerprint, module=self.lab.module)
        if self._in_place[given]:
            owners[("changed in place", self.lab.module, function)] = self.check.id
            raise ChangedInPlace(self._in_place[given], inplace.HINT, inplace.MISTAKE)

    def held(self, *args, **kwargs) -> tuple[tuple, dict]:
        """``(args, kwargs)``, the arguments of the last call, as its caller now holds them: the
        arrays the call changed in place replaced by what they became (unchanged when it changed
        none). For a check that calls a function twice on the same arrays, as a caller does."""
        from .inplace import with_changed

        return (with_changed(args, kwargs, self._last_changed) if self._last_changed else None) or (args, kwargs)

    def naming_input(self, function: str, *args, **kwargs):
        """The student's ``function`` on a small input offered to the error model
        (:mod:`autograder.engine.mutants`) in place of the trial's other calls of it: a function
        whose ~100 mutants cannot run on the check's own inputs within the model's time (lab 12's
        matchers) is named on this one, when it fails there too. Asked once per trial, what it
        prints set apart (:meth:`probe`); returns the answer, None when the call failed."""
        def answer():
            value = self.call(function, *args, **kwargs)
            kept = self.calls[-1]   # (the call returned: it is the last recorded)
            self.calls[:] = [call for call in self.calls if call[0] != function] + [kept]
            return value
        return self.probe(f"naming input/{function}/{fingerprint(function, args, kwargs)}", answer)

    def probe(self, key: str, answer):
        """The student's answer on a confirmation probe's input, ``answer()``, asked once per
        trial (a property shrinking a failing example names it again at every step): None
        when the call failed or its answer was not of the documented form.

        A probe is a second input chosen to tell candidate mistakes apart; see
        :class:`autograder.engine.judges.Probe`.
        """
        if key not in self._probed:
            printed = len(self.outputs)
            try:
                self._probed[key] = answer()
            except ChangedInPlace:
                raise   # the check's own verdict, wherever it shows
            except (StudentFailure, Fail):
                self._probed[key] = None
            finally:
                self._set_apart(printed, len(self.outputs), "the grader's own extra calls, on other inputs")
        return self._probed[key]

    def _set_apart(self, start: int, end: int, during: str) -> None:
        """Label what the student's code printed in ``outputs[start:end]`` as printed during
        ``during``, one entry, its lines indented under the label: a student reading it under
        a check must not take it for the output of the call the check is about (``rotating by
        37.0`` under the default 45); what is not indented is that call's."""
        printed = "\n".join(self.outputs[start:end]).strip("\n")
        if printed:
            indented = "\n".join("    " + line for line in printed.splitlines())
            self.outputs[start:end] = [f"(printed during {during}:)\n{indented}"]

    def not_implemented(self) -> str:
        """The message of a call in this trial that met a function not implemented yet, or ``""``
        (also when the check caught the failure itself, as advice does)."""
        return next((f.message for f in self._fatal.values() if f.outcome.kind == "not_implemented"), "")

    def _describe(self, function: str, outcome: CallOutcome) -> str:
        if outcome.kind == "missing_function":
            return f"not found: def {self.lab.signature(function)}"
        return outcome.message

    # ------------------------------------------------------------ judging
    def fail(self, message: str, hint: str = "", mistake: str = ""):
        raise Fail(message, hint, mistake)

    def advise(self, message: str, hint: str = ""):
        """Give a tip (advice checks only): shown with its reason, worth no points."""
        if not self.check.advice:
            raise TypeError(f"t.advise() in graded check {self.check.name!r}; "
                            "register advice with @exercise.advice(name)")
        self.tips.append((message, hint))

    def _why_none(self, value) -> str:
        """Where the function just called returns None, read from its code (": your `f` returns
        None where `not found`"), when ``value`` is None and is that call's whole answer or a
        part of the tuple it returned (": your `f` returns `(None, None)` where `not found`")."""
        if value is not None or not self.calls:
            return ""
        answer = self.calls[-1][3]
        in_tuple = isinstance(answer, (tuple, list)) and any(part is None for part in answer)
        if answer is not None and not in_tuple:
            return ""
        from .hints import code_of, none_returned

        function = self.calls[-1][0]
        found = none_returned(code_of(self), function, in_tuple=in_tuple)
        return f": your `{function}` {found}" if found else ""

    def _why_misread(self, value) -> tuple[str, str] | None:
        """(sentence, mistake) when ``value`` -- a call's answer, or one of the results it returned,
        in this check or served to it from another's (:meth:`shared`) -- is made from an OpenCV
        output the student's unpack names as another (:mod:`autograder.engine.outputs`:
        ``rms, dist, K, ... = cv2.calibrateCamera(...)``)."""
        for function, _, _, answer in reversed(self.calls + getattr(self, "served", [])):
            if answer is value:
                index, count = None, None
                break
            if isinstance(answer, (tuple, list)) and any(part is value for part in answer):
                index, count = next(i for i, part in enumerate(answer) if part is value), len(answer)
                break
        else:
            return None
        from . import outputs
        from .hints import code_of

        return outputs.told(code_of(self), function, index, count)

    def _fail_complex(self, what: str, value: np.ndarray, wanted: str) -> None:
        """A complex array where real numbers are asked: whether its imaginary parts are 0 (the
        values may be real ones in a complex type), and the calls of the student's code that make
        complex arrays (``np.linalg.eig`` of a matrix that is not symmetric)."""
        hints = _hints()
        with np.errstate(all="ignore"):
            real = bool(np.all(np.abs(value.imag) <= 1e-12 * max(1.0, float(np.max(np.abs(value.real), initial=0)))))
        said = f"{what} returned dtype {value.dtype} (complex numbers); expected {wanted}"
        said += ": its imaginary parts are all 0" if real else ": some imaginary parts are not 0"
        makers = hints.complex_makers(hints.code_of(self), hints.functions_read(self))
        if not makers:
            self.fail(said)
        from .claims import measured   # (the answer measured complex; the calls read in the code)

        made = (f"{said}. Your code calls {' and '.join(makers)}, which {'return' if len(makers) > 1 else 'returns'} "
                "a complex array as soon as one eigenvalue (or root) is complex, a Fourier transform always")
        if not real:   # (the real part would not be the answer: the vector taken is a complex one itself)
            self.fail(measured(f"{made}: the values returned are complex themselves, not real values in a "
                               "complex type"))
        self.fail(measured(f"{made}: keep the real part (`.real`) of what you return"),
                  mistake="complex values returned: the real part is not kept")

    def _why_swapped(self, got, expected) -> str:
        """For an image returned (W, H) where (H, W) is asked, the OpenCV call the student's code
        gives a size rows first (": your code passes `image.shape[:2]` ... to cv2.resize ...")."""
        if not _image_sides_swapped(got, expected, smallest=0):
            return ""
        from .hints import code_of, functions_read, size_given_as_shape

        found = size_given_as_shape(code_of(self), functions_read(self))
        return f"; your code {found}" if found else ""

    def _one_array_handed_out(self, function: str, outcome) -> None:
        """Fail when ``function`` returned the module-level array ``outcome.shared``, the same object an earlier
        call returned (the worker tells), with other values than its previous call in this check: the array a
        caller kept from that call has become this one's (each answer crosses as its own copy: only the values
        tell)."""
        from .claims import measured   # (claims reads checks: imported when a result is told)

        earlier = next((value for called, _, _, value in reversed(self.calls[:-1]) if called == function), None)
        if earlier is None or _same_values(earlier, outcome.value):
            return
        self.fail(measured(f"{function}() returns the module-level array `{outcome.shared}` itself, not a new one: "
                           "called again, it returned that same array holding other values, so the result a caller "
                           "kept from the earlier call changed too. Return a new array (made inside the function, or "
                           f"`{outcome.shared}.copy()`)."), mistake="a module-level array is returned itself")

    def expect_results(self, value, what: str, names: tuple[str, ...]) -> tuple:
        """Check that a function documented to return several results returned them as a tuple (or list) of
        ``len(names)`` items, and return it; fail saying what came instead (an array of the results stacked
        together, a tuple of another length, None).

        Parameters
        ----------
        value : object
            What the student returned.
        what : str
            How to name the call in messages, e.g. ``"epipoles(F)"``.
        names : tuple of str
            The results' names in their order, e.g. ``("e1", "e2")``.
        """
        n, listed = len(names), ", ".join(names)
        if isinstance(value, (tuple, list)) and len(value) == n:
            return tuple(value)
        expected = f"expected the {n} results as a tuple ({listed}): `return {listed}`"
        if isinstance(value, (tuple, list)):
            self.fail(f"{what} returned a {type(value).__name__} of {len(value)} items; {expected}")
        if isinstance(value, np.ndarray):
            stacked = [axis for axis, size in enumerate(value.shape) if size == n]
            how = ""
            if value.ndim == 2 and stacked:
                how = f": it looks like the {n} results were stacked as its {'rows' if stacked[0] == 0 else 'columns'}"
            self.fail(f"{what} returned an array of shape {value.shape}{how}; {expected}")
        self.fail(f"{what} returned {type(value).__name__}; {expected}")

    def expect_array(self, value, what: str, *, shape=None, dtype=None, kind=None,
                     finite: bool = False) -> np.ndarray:
        """Check that a returned value is an array of the documented form.

        Parameters
        ----------
        value : object
            What the student returned.
        what : str
            How to name it in messages, e.g. ``"translate()"``.
        shape : tuple, optional
            Expected shape; ``None`` entries match any length.
        dtype : dtype, optional
            Exact dtype required (e.g. ``np.uint8`` for images).
        kind : str, optional
            Required dtype kinds, e.g. ``"f"`` or ``"iuf"`` (numbers) or ``"b"``.
        finite : bool
            Require every value to be finite.

        Returns
        -------
        ndarray
            ``value`` (lists of numbers are accepted and converted when only
            ``kind`` is constrained).
        """
        held = _arrays_held(value, shape) if isinstance(value, (list, tuple)) else ""
        if isinstance(value, (list, tuple)) and dtype is None:
            try:
                value = np.asarray(value, dtype=float)
            except (TypeError, ValueError):
                pass
        if not isinstance(value, np.ndarray):
            self.fail(f"{what} returned {_type_name(value)}; expected a numpy array"
                      + (f" of shape {_shape_text(shape)}" if shape is not None else "") + self._why_none(value))
        if shape is not None:
            if value.ndim != len(shape) or any(s is not None and s != v for s, v in zip(shape, value.shape)):
                if held:   # (a tuple of arrays made one array: what it held says what went wrong)
                    self.fail(f"{what} returned {held}", mistake=ARRAYS_HELD)
                misread = self._why_misread(value)
                if misread is not None:   # the code's own names say which output it is
                    self.fail(f"{what} returned an array of shape {value.shape}; expected {_shape_text(shape)}: "
                              f"{misread[0]}", mistake=misread[1])
                form = shape_form(value.shape, tuple(shape))
                also = _kind_too(value, dtype, kind)
                swapped = self._why_swapped(value.shape, shape).removeprefix("; ")
                image = dtype is not None and np.dtype(dtype) == np.uint8   # (an image asked: not an (F, N, 2) stack)
                if swapped or (image and _image_sides_swapped(value.shape, shape)):
                    # (an image's height and width exchanged: the call read in the code is the cause where it is
                    # found, and no guess from the lengths -- "stacked along another axis?" -- beside it)
                    self.fail(f"{what} returned an array of shape {value.shape}; expected {_shape_text(shape)}: "
                              f"width and height are swapped (shapes are (rows, columns), OpenCV's sizes are "
                              f"(width, height)){': ' + swapped if swapped else ''}{also}", mistake=SIZE_SWAPPED)
                if form is not None:
                    self.fail(f"{what} returned an array of shape {value.shape}; expected {_shape_text(shape)}: "
                              f"{form.sentence}{also}", mistake=form.mistake)
                self.fail(f"{what} returned an array of shape {value.shape}; expected {_shape_text(shape)}{also}")
        if dtype is not None and value.dtype != np.dtype(dtype):
            canvas = _hints().float_canvas(self) if np.dtype(dtype) == np.uint8 and value.dtype.kind == "f" else ""
            if canvas:   # (the array returned was made float by NumPy's default dtype: read, the cause)
                self.fail(f"{what} returned dtype {value.dtype}; expected {np.dtype(dtype)}: " + canvas,
                          mistake="an image made with NumPy's default dtype (float64)")
            unit = np.dtype(dtype) == np.uint8 and _unit_range(value)
            if unit:   # (the image is in [0, 1]: converted as it is, every pixel becomes 0 or 1 -- black)
                divided = _hints().divides_by_255(self)
                self.fail(f"{what} returned dtype {value.dtype}; expected {np.dtype(dtype)}: " + measured(
                          f"its values lie in [0, 1] (at most {unit:.3g}), a float image's range; a uint8 image holds "
                          "0..255, so it needs scaling by 255 before the conversion (converted as it is, it would "
                          "be black)") + (f". {divided}" if divided else ""),
                          mistake="a float image in [0, 1] where a uint8 image in 0..255 is asked")
            self.fail(f"{what} returned dtype {value.dtype}; expected {np.dtype(dtype)}",
                      hint=_hints().UINT8_HINT.said(self) if np.dtype(dtype) == np.uint8 else "")
        if kind is not None and value.dtype.kind not in kind:
            wanted = " or ".join(_KIND_NAMES[k] for k in kind)
            hint = ""
            if "f" in kind and value.dtype.kind in "iub":  # a beginner's integer (or uint8) array
                hint = uint8_wraps(value) or _hints().FLOAT_HINT.said(self)
            if "f" in kind and value.dtype.kind == "c":
                self._fail_complex(what, value, wanted)
            self.fail(f"{what} returned dtype {value.dtype}; expected {wanted}", hint=hint)
        if finite and value.dtype.kind in "fc" and not np.all(np.isfinite(value)):
            self.fail(f"{what} returned NaN or infinite values")
        return value

    # ------------------------------------------------------------ properties
    def for_all(self, strategy, body, *, max_examples: int | None = None, describe=repr):
        """Run ``body(example)`` on examples drawn by Hypothesis (grading profile).

        On failure the smallest failing example (after shrinking) is added to the
        message. The examples are drawn for this submission (:attr:`inputs`): the
        same files meet the same ones on every run and machine, other files other
        ones. Examples of a property that passed are replayed without Hypothesis's
        engine the next time (:mod:`autograder.engine.examples`); Hypothesis takes over at
        the first one that fails.
        """
        from . import examples

        seed = self.inputs.seed(self.check.id, self._properties)
        where = examples.key(self.check, self._properties, strategy, max_examples, seed)
        self._properties += 1
        begin = current = len(self.outputs)  # what the examples print; the last one's stays unlabelled

        def run(example):
            nonlocal current
            current = len(self.outputs)
            body(example)

        try:
            self._for_all(strategy, run, max_examples, describe, where, seed)
            current = len(self.outputs)  # it held: no example failed, every one is "other"
        finally:
            self._set_apart(begin, current, "the other examples this property tried")

    def _for_all(self, strategy, body, max_examples, describe, where, seed):
        """:meth:`for_all` once its recorded examples are known (``where``) and its ``seed``."""
        from . import examples

        recorded = examples.recorded(where)
        passed = self._replay(recorded, body)
        if passed is None:
            self.property_examples.append(list(recorded or ())[:_EXAMPLES_KEPT])
            return
        # Only now, with examples to draw, is Hypothesis needed (see autograder.engine.strategies).
        from hypothesis import errors, given, seed as seeded, settings

        from .properties import grading_settings
        from .strategies import build

        strategy = build(strategy)
        last, seen = [], []

        @seeded(seed)
        @settings(grading_settings(max_examples))
        @given(strategy)
        def property_holds(example):
            last[:] = [example]
            seen.append(example)
            if len(seen) <= len(passed) and examples.same(example, passed[len(seen) - 1]):
                return  # it passed a moment ago, in the replay: Hypothesis draws the same examples
            passed.clear()  # from here on, every example is really run
            body(example)

        for attempt in (1, 2):
            try:
                with _ONE_ENGINE:
                    property_holds()
                break
            except StudentFailure as exc:
                if exc.outcome.kind not in _FATAL_KINDS and last:  # fatal ones fail for every input
                    exc.message += self._counterexample(describe(last[0]))
                self.property_examples.append(list(last))
                raise
            except Fail as exc:
                if last:
                    exc.message += self._counterexample(describe(last[0]))
                self.property_examples.append(list(last))
                raise
            except errors.Flaky as exc:
                # A call the grader could not make (its worker did not start in time on a loaded
                # machine) fails once and passes when Hypothesis replays it: that is the grader's
                # failure, reported as one, never the student's randomness.
                grader = _grader_failure(exc)
                if grader is not None:
                    raise StudentFailure(grader.outcome, grader.message) from None
                if attempt == 1:  # once more from the start: a hiccup does not repeat, randomness does
                    last.clear(), seen.clear(), passed.clear()
                    continue
                self._unreproduced(exc, describe(last[0]) if last else "")
        examples.record(where, seen)
        self.property_examples.append(list(seen[:_EXAMPLES_KEPT]))

    def _unreproduced(self, flaky: BaseException, example: str):
        """Fail a property whose failure Hypothesis could not reproduce (twice): with what the
        calls showed, never a cause they do not show."""
        first = _first_failure(flaky)
        answers = {}
        for function, args, kwargs, value in self.calls:
            given, answered = fingerprint(function, args, kwargs), fingerprint(value)
            if answers.setdefault(given, answered) != answered:
                self.fail("your function gave different answers for the same input "
                          "(does it depend on randomness or on earlier calls?)"
                          + self._counterexample(example))
        said = first.message if first is not None else "an input failed"
        hint = getattr(first, "hint", "")
        self.fail(f"{said}{self._counterexample(example) if example else ''}\n(the same input did not "
                  "fail when it was tried again: does your function depend on randomness or on "
                  "earlier calls?)", hint=hint)

    def _replay(self, recorded: list | None, body) -> list | None:
        """Run ``body`` on recorded examples: None if every one passed, else those
        that passed before the first that did not (Hypothesis then takes over)."""
        for index, example in enumerate(recorded or ()):
            before = (len(self.outputs), len(self.modified_inputs), len(self.tips),
                      len(self._pictures), set(self._fatal))
            try:
                body(example)
            except Exception:  # noqa: BLE001 - Hypothesis runs it again and reports it its own way
                # It runs this example again: what the call printed or changed is recorded
                # then (unless the function may not be called again: then it is not).
                if set(self._fatal) == before[4]:
                    del self.outputs[before[0]:], self.modified_inputs[before[1]:]
                    del self.tips[before[2]:], self._pictures[before[3]:]
                return list(recorded[:index])
        return None if recorded else []

    def _counterexample(self, example: str) -> str:
        if self.inputs.secret:  # the course's inputs: a student's own run draws others
            return (f"\nSmallest failing input found: {example}"
                    "\n(inputs drawn for this submission: try this one directly, "
                    "your own runs draw others)")
        before, after = self.inputs.rerun
        return (f"\nSmallest failing input found: {example}"
                f"\n(the same inputs every run of these files: re-run with {before}{self.check.exercise.id}{after})")

    # ------------------------------------------------------------ pictures
    def images(self, title: str, caption: str = "", **labelled: np.ndarray):
        """Attach images side by side, e.g. ``t.images("rotate", input=a, yours=b)``.

        Pictures are encoded only if the grading keeps them (see
        :func:`~autograder.engine.runner.grade`'s ``pictures``), on another thread while
        grading goes on; an image may also be given as a function that draws it
        (``matches=lambda: matches_picture(...)``), then drawn only in that case. So
        the arrays must not change after the check, and a drawing function must not
        call student code.
        """
        def artifact():
            items = []
            for label, image in labelled.items():
                if callable(image):  # drawn only now that it is kept
                    image = image()
                if image is None:
                    continue
                try:  # what the student returned may not be drawable (a 0-d array): leave it out
                    items.append(pictures.picture_item(label.replace("_", " "), image))
                except ValueError:
                    pass
            return Artifact("images", title, items, caption)

        self._pictures.append(artifact)

    def compare_images(self, title: str, source, expected, got, valid=None, caption: str = ""):
        """Attach input, expected, the student's output and a difference heat map."""
        heat = None
        # the whole shape: a grey answer for a BGR truth (or BGR for grey) has no difference map,
        # and the check goes on to judge it (a channel count the API does not allow)
        if isinstance(got, np.ndarray) and got.shape == np.shape(expected):
            heat = pictures.deferred_heatmap(expected, got, valid)  # drawn only if pictures are kept
        self.images(title, caption, input=source, expected=expected, yours=got, difference=heat)

    def svg(self, title: str, svg: str, caption: str = ""):
        """Attach an inline SVG plot."""
        self._pictures.append(lambda: Artifact("svg", title, [{"label": "", "svg": svg}], caption))

    def artifacts(self) -> list[Artifact]:
        """The attached pictures, encoded now."""
        return [make() for make in self._pictures]

    # ------------------------------------------------------------ sharing
    def shared(self, key, compute):
        """``compute()`` once per grading, shared by every check that asks for ``key``.

        For an expensive student call several checks judge (a panorama, a
        calibration): the value, or the student's failure, is remembered on the
        sandbox, so each check sees the same outcome.
        """
        cache = self.sandbox.shared
        if key not in cache:
            before = len(self.calls)
            try:
                cache[key] = (True, compute())
            except StudentFailure as failure:
                cache[key] = (False, failure)
            cache[("calls behind", key)] = self.calls[before:]
        else:
            self.served += cache.get(("calls behind", key), [])
        ok, value = cache[key]
        if ok:
            return value
        raise StudentFailure(value.outcome, value.message)


def _first_failure(exc: BaseException) -> Fail | StudentFailure | None:
    """The first check failure or failed call among those a Hypothesis ``Flaky`` saw."""
    if isinstance(exc, (Fail, StudentFailure)):
        return exc
    for inner in getattr(exc, "exceptions", ()):
        found = _first_failure(inner)
        if found is not None:
            return found
    return None


def _grader_failure(exc: BaseException) -> StudentFailure | None:
    """The first failure of the grader's own (kind ``grader_error``) among those a Hypothesis
    ``Flaky`` saw (a ``FlakyFailure`` groups them), else None."""
    if isinstance(exc, StudentFailure):
        return exc if exc.outcome.kind == "grader_error" else None
    for inner in getattr(exc, "exceptions", ()):
        found = _grader_failure(inner)
        if found is not None:
            return found
    return None


def _unit_range(value) -> float:
    """The largest value of a float image whose finite values all lie in [0, 1] (and are not all 0), else 0."""
    if value.dtype.kind != "f" or value.ndim not in (2, 3) or min(value.shape[:2]) < 8:
        return 0.0
    finite = value[np.isfinite(value)]
    if finite.size == 0 or finite.min() < 0 or finite.max() > 1.0 or finite.max() == 0:
        return 0.0
    return float(finite.max())


def _hints():
    from . import hints   # hints reads the student's code: only a failing form needs it

    return hints


def _arrays(value, kind: str, depth: int = 0):
    """The arrays of dtype ``kind`` ("f": floats too, "i": signed integers -- not images, uint8, nor
    booleans) in a value, its tuples, lists and dicts (a few levels, 64 items each)."""
    if isinstance(value, np.ndarray) and value.dtype.kind == kind:
        yield value
    elif isinstance(value, float) and kind == "f":
        yield np.array(value)
    elif isinstance(value, (tuple, list)) and depth < 3:
        for item in value[:64]:
            yield from _arrays(item, kind, depth + 1)
    elif isinstance(value, dict) and depth < 3:
        for item in list(value.values())[:64]:
            yield from _arrays(item, kind, depth + 1)


def _float_arrays(value):
    return _arrays(value, "f")


def _lines_of(traceback: str, module: str) -> tuple:
    """The line numbers of ``module``'s file in a relayed traceback ("File "m.py", line 6, in f")."""
    return tuple(int(n) for n in re.findall(r'File "(?:[^"]*/)?' + re.escape(module) + r'\.py", line (\d+)',
                                             str(traceback)[-4000:]))[-8:]


def _whole_numbers(value) -> bool:
    """Whether a returned value holds an array of whole numbers only, not all zero: a float array
    without fractions, or a signed integer one (an array made with dtype=int keeps no fraction)."""
    if any(np.any(array) for array in _arrays(value, "i")):
        return True
    for array in _float_arrays(value):
        if _has_fraction(array.ravel()[:_GLANCE]):   # most float results tell at once
            continue
        finite = array[np.isfinite(array)]
        if finite.size and np.any(finite != 0) and not _has_fraction(finite) \
                and not (array.ndim >= 2 and np.isin(finite, (0.0, 1.0, 255.0)).all()):
            return True   # (a binary image or mask, 0 and 255 or 0 and 1, is whole by nature: no fraction lost)
    return False


def _fractional(arguments) -> bool:
    """Whether the arguments hold a float with a fractional part."""
    return any(_has_fraction(array.ravel()[:_GLANCE]) or _has_fraction(array) for array in _float_arrays(arguments))


_GLANCE = 256   # values looked at before a whole array is scanned (this runs after every call)


def _has_fraction(values: np.ndarray) -> bool:
    """Whether a finite value of ``values`` has a fractional part."""
    finite = values[np.isfinite(values)]
    return bool(finite.size) and not np.array_equal(finite, np.round(finite))


ARRAYS_HELD = "a tuple or list of arrays returned where one array is asked"
SIZE_SWAPPED = "width and height are swapped"   # an image (W, H) for (H, W): a size given rows first


def _image_sides_swapped(got, expected, smallest: int = 8) -> bool:
    """Whether ``got`` is the shape ``expected`` (its first two sides at least ``smallest``, unequal) with those
    two exchanged, the rest kept: an image's height and width."""
    expected = tuple(expected)
    return len(got) == len(expected) >= 2 and None not in expected[:2] and min(expected[:2]) >= smallest \
        and expected[0] != expected[1] and tuple(got[:2]) == (expected[1], expected[0]) \
        and tuple(got[2:]) == expected[2:]


def _arrays_held(value, shape) -> str:
    """What a tuple or list of arrays returned where one array of ``shape`` is asked holds, where it explains
    the shape it makes: one array in a tuple (`return E,`: a comma after the value), or one array per column
    (`return x, y` for an (N, 2) array); "" otherwise."""
    items = list(value)
    if not items or not all(isinstance(item, np.ndarray) for item in items) \
            or len({item.shape for item in items}) != 1 or shape is None:
        return ""
    kind, inner = type(value).__name__, items[0].shape
    if len(items) == 1 and len(inner) == len(shape):
        return measured(f"a {kind} holding one array of shape {inner}, not the array itself"
                        + (" (a comma after the returned value makes a tuple of one)" if kind == "tuple" else ""))
    if len(inner) == 1 and len(shape) == 2 and shape[1] == len(items):
        return measured(f"a {kind} of {len(items)} arrays of shape {inner}, one per column, where one array of "
                        f"shape {_shape_text(shape)} is asked: stack them as its columns (np.column_stack)")
    return ""


def _type_name(value) -> str:
    if value is None:
        return "None"
    return f"a {type(value).__name__}"


def _shape_text(shape) -> str:
    inner = ", ".join("N" if s is None else str(s) for s in shape)
    return f"({inner},)" if len(shape) == 1 else f"({inner})"


def _same_values(first, second) -> bool:
    """Whether two answers hold the same numbers (arrays, or tuples of them); False where unsure."""
    try:
        if isinstance(first, (tuple, list)) and isinstance(second, (tuple, list)):
            return len(first) == len(second) and all(_same_values(a, b) for a, b in zip(first, second))
        return bool(np.array_equal(np.asarray(first), np.asarray(second), equal_nan=True))
    except (TypeError, ValueError):
        return False
