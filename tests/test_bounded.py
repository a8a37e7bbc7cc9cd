"""The backstop on the grader's own work about a check (autograder/engine/bounded.py): a loop that no
search's clock sees -- in a reader, an operator or a judge -- is stopped in its thread past its CPU time or
memory, the check keeps its verdict, and the grading goes on."""

import logging
import threading
import time

import pytest

from autograder.engine import runner
from autograder.engine.bounded import Runaway, bounded
from autograder.engine.results import ERROR
from autograder.engine.runner import grade
from autograder.sandbox.supervisor import Sandbox
from conftest import REFERENCE, check_results, mutant


def _spin(seconds: float) -> None:
    end = time.thread_time() + seconds
    while time.thread_time() < end:
        pass


def test_a_loop_past_its_cpu_bound_is_stopped_in_its_thread():
    started = time.monotonic()
    with pytest.raises(Runaway, match="CPU time"):
        with bounded(cpu_seconds=0.3):
            while True:
                pass
    assert time.monotonic() - started < 10


def test_a_runaway_swallowed_on_the_way_is_raised_again_while_the_work_goes_on():
    swallowed = []
    with pytest.raises(Runaway, match="CPU time"):
        with bounded(cpu_seconds=0.2):
            try:
                while True:
                    pass
            except Runaway:       # (a handler of the grader's own, or a bound within this one)
                swallowed.append(True)
            while True:
                pass
    assert swallowed == [True]


def test_waiting_costs_none_of_the_bound_and_nothing_is_raised_after_the_body():
    with bounded(cpu_seconds=0.2):
        time.sleep(0.6)         # (a worker's call: the grader's thread waits)
        _spin(0.05)
    _spin(0.4)                  # past the bound, after the body: nothing lands here


def test_memory_held_past_its_bound_is_stopped():
    held = []
    with pytest.raises(Runaway, match="GB, past its bound"):
        with bounded(cpu_seconds=60, memory_growth=200 * 2**20):
            while True:
                held.append(bytearray(8 * 2**20))
                held[-1][::4096] = b"x" * len(held[-1][::4096])   # (touched: resident, not only reserved)
    held.clear()


def test_a_bound_stops_only_its_own_thread():
    stopped = []

    def runaway():
        try:
            with bounded(cpu_seconds=0.2):
                while True:
                    pass
        except Runaway:
            stopped.append(True)

    thread = threading.Thread(target=runaway)
    thread.start()
    with bounded(cpu_seconds=30):
        _spin(0.5)              # busy beside it, within its own bound
    thread.join(10)
    assert stopped == [True]


def test_a_request_interrupted_by_the_grader_leaves_a_new_worker_unbilled(monkeypatch):
    """A Runaway (or Ctrl-C) raised while a reply is half read: what is left on the pipe is unknown, so the
    worker goes; the next call gets a new one, not counted as the student's restart nor billed to them."""
    real = Sandbox._read
    reads = []

    def interrupted(self, n, deadline):
        reads.append(n)
        if len(reads) == 2:     # (the first reads the reply's length; the rest of it is left on the pipe)
            raise Runaway("stopped")
        return real(self, n, deadline)

    with Sandbox(REFERENCE) as box:
        box.import_module("lab07_transformations")
        monkeypatch.setattr(Sandbox, "_read", interrupted)
        with pytest.raises(Runaway):
            box.call("lab07_transformations", "translation_matrix", (1, 2))
        monkeypatch.setattr(Sandbox, "_read", real)
        billed = box.student_seconds
        outcome = box.call("lab07_transformations", "translation_matrix", (1, 2))
        assert outcome.ok and outcome.value.tolist() == [[1, 0, 1], [0, 1, 2], [0, 0, 1]]
        assert box.restarts == 0
        assert box.student_seconds - billed < 0.1   # (the call only: the new worker's start is not billed)


def test_a_naming_that_runs_away_leaves_the_check_its_verdict_and_the_grading_goes_on(
        tmp_path, monkeypatch, caplog):
    from autograder.engine.mutants import naming

    def for_ever(verdict, trial, raised=False):
        while True:
            pass

    monkeypatch.setattr(naming, "named_by_error_model", for_ever)
    monkeypatch.setattr(runner, "own_work_bound", lambda: 0.5)
    folder = mutant(tmp_path, "lab07_transformations", """
        def translation_matrix(tx, ty):
            return np.array([[1.0, 0.0, ty], [0.0, 1.0, tx], [0.0, 0.0, 1.0]])
        """)
    started = time.monotonic()
    with caplog.at_level(logging.ERROR, logger="autograder"):
        result = grade(folder, ["lab07.ex1", "lab07.ex2"], pictures="none")
    assert time.monotonic() - started < 120
    failed = [c for c in check_results(result, "lab07.ex1") if c.score < c.max_score]
    assert failed and all(c.status == "failed" and c.message for c in failed)
    assert all(c.score == c.max_score for c in check_results(result, "lab07.ex2"))
    assert "naming its failure was stopped" in caplog.text and "a fault of the grader's" in caplog.text


def test_a_judge_that_runs_away_is_a_grader_error_of_that_check_alone(tmp_path, monkeypatch):
    from autograder.engine import checks

    real = checks.Trial.call
    looping = []

    def call(self, *args, **kwargs):
        if self.check.id.startswith("lab07.ex1") and not looping:
            looping.append(self.check.id)
            while True:
                pass
        return real(self, *args, **kwargs)

    monkeypatch.setattr(checks.Trial, "call", call)
    monkeypatch.setattr(runner, "own_work_bound", lambda: 0.5)
    result = grade(REFERENCE, ["lab07.ex1"], pictures="none")
    [stopped] = [c for c in check_results(result, "lab07.ex1") if c.status == ERROR]
    assert "ran far past its time or memory" in stopped.message and stopped.score == 0
    assert all(c.score == c.max_score for c in check_results(result, "lab07.ex1") if c is not stopped)
