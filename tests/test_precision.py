"""Checks judge meaning, not representation.

The API pins no float dtype, memory order or writeability: the reference solutions
wrapped to return float32 (what many OpenCV recipes give), or Fortran-ordered read-only
arrays, get full marks in every lab. float16 is not wrapped: it is not a legitimate
precision for geometry (a 1000 px coordinate is off by up to 0.25 px in it) and no
tolerance grows for it (``autograder.engine.compare.precision_floor``); a float16 answer loses
points. Messages that put a figure beside what it was compared with print the digits that
tell them apart.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, strategies as st

from autograder.engine.compare import (FLOAT32_EPS, at_precision, describe_difference, format_apart,
                                format_arrays_apart, precision_floor)
from autograder.engine.runner import grade
from conftest import REFERENCE, assert_full_marks, check_results, mutant

LABS = ("lab07", "lab08", "lab09", "lab10", "lab11", "lab12")

# A module in place of the reference module: the reference is imported under a private name
# (a helper module beside the lab module, which the grader copies along) and every public
# function it defines is wrapped, so that the functions calling each other inside it still
# compute as the reference does: only what the grader receives changes.
WRAPPER = '''\
"""The reference solution, every result {what}."""
import functools as _functools

import numpy as _np

import {private} as _reference


def _convert(value):
    if isinstance(value, tuple):
        return tuple(_convert(item) for item in value)
    if isinstance(value, list):
        return [_convert(item) for item in value]
    if not isinstance(value, _np.ndarray):
        return value
{convert}


def _wrap(function):
    @_functools.wraps(function)
    def wrapper(*args, **kwargs):
        return _convert(function(*args, **kwargs))
    return wrapper


for _name, _value in list(vars(_reference).items()):
    if (not _name.startswith("_") and callable(_value)
            and getattr(_value, "__module__", None) == _reference.__name__):
        globals()[_name] = _wrap(_value)
'''

CONVERSIONS = {   # name -> (what, body of _convert for an ndarray ``value``)
    "float32": ("as float32 where it is float64 (integer and other results as they are)",
                "    return value.astype(_np.float32) if value.dtype == _np.float64 else value"),
    "fortran_readonly": ("Fortran-ordered and read-only",
                         # (np.asfortranarray gives a 0-d array an axis: a 0-d result is only made read-only)
                         "    value = _np.asfortranarray(value) if value.ndim else value.copy()\n"
                         "    value.flags.writeable = False\n"
                         "    return value"),
}


def wrapped_reference(folder: Path, conversion: str) -> Path:
    """A submission folder: each reference module replaced by a wrapper converting its results."""
    what, body = CONVERSIONS[conversion]
    folder.mkdir(parents=True, exist_ok=True)
    for source in sorted(REFERENCE.glob("lab*.py")):
        private = f"_reference_{source.stem}"
        shutil.copyfile(source, folder / f"{private}.py")
        (folder / source.name).write_text(WRAPPER.format(what=what, private=private, convert=body))
    return folder


@pytest.mark.slow
@pytest.mark.parametrize("conversion", sorted(CONVERSIONS))
def test_the_reference_in_another_representation_gets_full_marks(tmp_path, conversion):
    result = grade(wrapped_reference(tmp_path / "submission", conversion), lanes=2, pictures="none")
    for lab in LABS:
        assert_full_marks(result, lab)
    assert sum(e.score for e in result.exercises) == sum(e.max_score for e in result.exercises) > 0


def test_the_wrapper_really_converts(tmp_path):
    """The wrapped module returns float32 and leaves integers alone (else the test above proves nothing)."""
    import importlib
    import sys

    folder = wrapped_reference(tmp_path / "submission", "float32")
    sys.path.insert(0, str(folder))
    try:
        module = importlib.import_module("lab12_stereo")
        depth = module.depth_from_disparity(np.array([10.0, 0.0]), 500.0, 0.1)
        patterns = module.gray_code_patterns(16, 4)
        _, _, H1, H2 = module.rectify(np.zeros((20, 30), np.uint8), np.zeros((20, 30), np.uint8),
                                      np.eye(3), np.eye(3), np.eye(3), np.array([-1.0, 0.0, 0.0]))
    finally:
        sys.path.remove(str(folder))
        for name in ("lab12_stereo", "_reference_lab12_stereo"):
            sys.modules.pop(name, None)
    assert depth.dtype == np.float32 and H1.dtype == np.float32 and H2.dtype == np.float32
    assert patterns.dtype == np.uint8


FLOAT32_DEPTH = """
    def depth_from_disparity(disparity, f, baseline):
        # a third party's: float32 throughout
        d = np.asarray(disparity, dtype=np.float32)
        depth = np.zeros(d.shape, dtype=np.float32)
        valid = d > 0
        depth[valid] = np.float32(f) * np.float32(baseline) / d[valid]
        return depth
    """


@pytest.mark.slow
def test_a_float32_depth_from_disparity_gets_full_marks(tmp_path):
    result = grade(mutant(tmp_path, "lab12_stereo", FLOAT32_DEPTH), ["lab12.ex2"], pictures="none")
    checks = check_results(result, "lab12.ex2")
    assert all(c.passed for c in checks), [(c.name, c.message) for c in checks if not c.passed]


@pytest.mark.slow
def test_float16_is_not_a_precision_for_geometry(tmp_path):
    source = """
        _disparity_from_matches = disparity_from_matches
        def disparity_from_matches(xl, xr):
            return _disparity_from_matches(xl, xr).astype(np.float16)
        """
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ex2"], pictures="none")
    failed = [c for c in check_results(result, "lab12.ex2") if not c.passed]
    assert failed, "a float16 disparity (0.06 px off at x = 500) got full marks"


@pytest.mark.slow
def test_a_difference_beyond_float32_is_reported_with_its_digits(tmp_path):
    """Off by 1e-3 px: the arrays in the message differ, and the difference is stated."""
    source = """
        _disparity_from_matches = disparity_from_matches
        def disparity_from_matches(xl, xr):
            return _disparity_from_matches(xl, xr) + 1e-3
        """
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ex2"], pictures="none")
    failed = [c for c in check_results(result, "lab12.ex2") if not c.passed]
    assert failed
    for check in failed:
        returned, expected = check.message.split("returned ", 1)[1].split("; expected ", 1)
        assert returned.split("...")[0] != expected.split("...")[0], check.message
        assert "up to 0.001 px" in check.message, check.message


# ------------------------------------------------------------------ the helpers themselves
finite = st.floats(-1e12, 1e12, allow_nan=False, allow_infinity=False)


@given(finite, finite)
def test_two_different_numbers_never_print_alike(value, other):
    if value != other:
        assert format_apart(value, other) != format_apart(other, value)
        assert format_apart(value, other, percent=True) != format_apart(other, value, percent=True)


@given(st.floats(1e-300, 1e12))
def test_a_nonzero_difference_never_prints_as_zero(difference):
    assert float(format_apart(difference, 0.0)) != 0.0
    assert "up to 0 " not in describe_difference([difference], [0.0], "px")


@given(st.lists(finite, min_size=1, max_size=6), st.data())
def test_different_arrays_never_print_alike(values, data):
    got = np.array(values)
    index = data.draw(st.integers(0, len(values) - 1))
    expected = got.copy()
    expected[index] = np.nextafter(expected[index], np.inf)   # the smallest possible difference
    shown, wanted = format_arrays_apart(got, expected)
    assert shown != wanted


def test_the_precision_floor_is_float32s():
    assert precision_floor(1.0) == pytest.approx(16 * FLOAT32_EPS)
    # float32 rounding of any value of magnitude <= scale passes: half an ulp, with room to spare
    for scale in (1.0, 640.0, 1e4):
        value = np.float64(scale) * (1 - 1e-9)
        assert abs(float(np.float32(value)) - value) <= at_precision(1e-12, scale)
    # a tolerance looser than the floor is kept as it is
    assert at_precision(0.5, 100.0) == 0.5
    np.testing.assert_array_equal(at_precision(np.array([1e-9, 1.0]), np.array([100.0, 100.0])),
                                  [precision_floor(100.0), 1.0])
