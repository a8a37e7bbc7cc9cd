"""The mutants' answers are kept: the same mutant on the same input runs once per process."""

from __future__ import annotations

import numpy as np
import pytest

from autograder.engine.mutants import helper as helpers
from autograder.engine.mutants.helper import Helper

SOURCE = "def double(x):\n    return x * 2\n"


@pytest.fixture
def counted(monkeypatch):
    """A fresh helper whose run requests are counted (calls asked of the process)."""
    asked = []
    original = Helper._request

    def request(self, message, timeout):
        if message["op"] == "run":
            asked.append(list(message["calls"]))
        return original(self, message, timeout)

    monkeypatch.setattr(Helper, "_request", request)
    monkeypatch.setattr(helpers, "ANSWERS", helpers._Answers(helpers.CACHE_BYTES))
    runner = Helper()
    yield runner, asked
    runner.close()


def test_the_same_mutant_on_the_same_input_runs_once(counted):
    runner, asked = counted
    runner.prepare(SOURCE, "twice", [("double", (np.arange(3.0),), {}), ("double", (np.ones(2),), {})], 5)
    first = runner.run((), [0, 1], 5)
    again = runner.run((), [1, 0], 5)
    assert asked == [[0, 1]]                                  # the second run asked nothing
    assert np.array_equal(again[1], first[0]) and np.array_equal(again[0], [2.0, 2.0])
    with pytest.raises(ValueError):
        first[0][0] = 7.0                                     # kept answers cannot be changed by a reader
    # Equal inputs prepared anew (another grading of the class) are found by content; another
    # input, another mutant or another module is asked.
    runner.prepare(SOURCE, "twice", [("double", (np.arange(3.0),), {}), ("double", (np.zeros(2),), {})], 5)
    runner.run((), [0, 1], 5)
    assert asked[-1] == [1]
    runner.run([["x", 1, "dummy"]], [0], 5)
    assert len(asked) == 3
    runner.prepare(SOURCE.replace("2", "3"), "twice", [("double", (np.arange(3.0),), {})], 5)
    assert np.array_equal(runner.run((), [0], 5)[0], [0.0, 3.0, 6.0])


def test_the_kept_answers_stay_within_their_budget():
    kept = helpers._Answers(budget=8 * 10_000)
    for index in range(40):
        kept.put(index, np.zeros(1000))                       # 8 kB each
    assert kept.size <= kept.budget and kept.get(0) is None and kept.get(39) is not None
    kept.put("huge", np.zeros(100_000))                       # over an eighth of the budget: not kept
    assert kept.get("huge") is None
