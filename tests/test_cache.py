"""The store of ground truth and property examples kept between gradings (autograder.sandbox.cache,
autograder.engine.examples): it gives back exactly what would be computed, never what it cannot trust,
and a replayed property reaches Hypothesis's own verdict and message."""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path

import numpy as np
import pytest

from autograder.sandbox import cache
from autograder.engine import examples
from autograder.engine.checks import Fail, Trial
from autograder.engine.registry import select
from autograder.sandbox.supervisor import CallOutcome

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def store(tmp_path, monkeypatch):
    monkeypatch.setenv("AUTOGRADER_CACHE_DIR", str(tmp_path / "store"))
    return tmp_path / "store"


calls = []


@cache.persistent
def _rendered(size: int, shift: float):
    calls.append((size, shift))
    image = (np.arange(size * size, dtype=np.float64).reshape(size, size) * shift).astype(np.uint8)
    return image, np.full((size, size), shift), {"size": size, "mask": image > 3}


def _same(a, b):
    assert examples.same(list(a), list(b))


def test_outside_a_grading_results_are_computed(store):
    calls.clear()
    _rendered(4, 1.5), _rendered(4, 1.5)
    assert calls == [(4, 1.5), (4, 1.5)] and not store.exists()


def test_stored_results_come_back_exactly(store):
    calls.clear()
    with cache.enabled():
        first, second, other = _rendered(5, 0.5), _rendered(5, 0.5), _rendered(5, 0.25)
    assert calls == [(5, 0.5), (5, 0.25)]
    _same(first, second)
    assert second[0].flags.writeable and second[0].flags.owndata and second[0].dtype == np.uint8
    assert not examples.same(list(first), list(other))


def test_a_corrupt_or_foreign_entry_is_computed_again(store):
    calls.clear()
    with cache.enabled():
        expected = _rendered(6, 2.0)
        [entry] = [p for p in store.rglob("*") if p.is_file() and p.name != "key"]
        entry.write_bytes(entry.read_bytes()[:-3] + b"xyz")    # corrupt: its checksum fails
        _same(_rendered(6, 2.0), expected)
        entry.write_bytes(b"garbage")                          # truncated
        _same(_rendered(6, 2.0), expected)
    assert calls == [(6, 2.0)] * 3


def test_a_folder_others_may_write_is_not_used(store):
    calls.clear()
    store.mkdir(mode=0o777)
    os.chmod(store, 0o777)
    with cache.enabled():
        _rendered(3, 1.0), _rendered(3, 1.0)
    assert calls == [(3, 1.0)] * 2 and not any(store.iterdir())


def test_switched_off(monkeypatch):
    monkeypatch.setenv("AUTOGRADER_CACHE_DIR", "off")
    calls.clear()
    with cache.enabled():
        _rendered(3, 1.0), _rendered(3, 1.0)
    assert len(calls) == 2


# ------------------------------------------------------------------ replayed properties
def _reference(module):
    spec = importlib.util.spec_from_file_location(module, ROOT / "reference_solutions" / f"{module}.py")
    loaded = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(loaded)
    return loaded


class InProcess:
    """Stands in for the sandbox: calls a module's functions here (tests only)."""

    def __init__(self, module, wrong_from=None):
        self.module, self.calls, self.wrong_from, self.shared = module, 0, wrong_from, {}

    def call(self, module, function, args=(), kwargs=None, **_):
        self.calls += 1
        value = getattr(self.module, function)(*args, **(kwargs or {}))
        if self.wrong_from is not None and self.calls >= self.wrong_from:
            value = value.T  # a realistic mistake: the matrix transposed
        return CallOutcome(ok=True, value=value)


def _run(check, sandbox):
    trial = Trial(sandbox, check)
    try:
        check.func(trial)
    except Fail as failure:
        return failure.message
    return "passed"


@pytest.fixture
def translation_property():
    [exercise] = select(["lab07.ex1"])
    return next(c for c in exercise.checks if c.func.__name__ == "translation_matrix_property")


def test_a_replayed_property_needs_no_hypothesis(store, translation_property, monkeypatch):
    module = _reference("lab07_transformations")
    with cache.enabled():
        assert _run(translation_property, first := InProcess(module)) == "passed"
        import hypothesis

        monkeypatch.setattr(hypothesis, "given", None)  # the engine cannot run now
        assert _run(translation_property, again := InProcess(module)) == "passed"
    assert again.calls == first.calls > 5


@pytest.mark.parametrize("wrong_from", [1, 4, 9])
def test_a_failure_found_in_the_replay_is_reported_as_hypothesis_reports_it(store, translation_property,
                                                                             wrong_from):
    module = _reference("lab07_transformations")
    without_store = _run(translation_property, InProcess(module, wrong_from))
    assert without_store != "passed" and "Smallest failing input found" in without_store
    with cache.enabled():
        assert _run(translation_property, InProcess(module)) == "passed"  # records the examples
        assert _run(translation_property, InProcess(module, wrong_from)) == without_store
