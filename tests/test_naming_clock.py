"""The naming's clock counts the CPU time of the processes doing the work, not the wall clock.

A submission should get the same names on a busy machine as on a quiet one (a regrade, a batch
beside other work): the error model's and the repairs' budgets are CPU seconds of this thread, the
reference's helper and the student's sandboxes, within WALL_SLACK times the budget of wall-clock time.
Those seconds are the budgets' machine's: a slower machine's count as fewer (its measured pace), so it
tells the same names, taking longer.
"""

from __future__ import annotations

import subprocess
import sys
import time

import pytest

from autograder.engine.mutants import naming
from autograder.sandbox import evidence

SPIN = "import time\nwhile time.process_time() < {cpu} + 0.1: pass\ntime.sleep(60)"   # (/proc counts in ticks)


@pytest.fixture(autouse=True)
def budgets_machine(request, monkeypatch):
    """The counting tests run as on the machine the budgets were set on (pace 1)."""
    if "pace" not in request.node.name:
        monkeypatch.setattr(naming, "machine_pace", lambda: 1.0)


def _spinning(cpu: float) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", SPIN.format(cpu=cpu)])


def _settled(pid: int) -> float:
    """``pid``'s CPU seconds once it has stopped spinning (two reads 0.2 s apart agree): its start's
    imports count too, so a read taken at the spin's target may still be short of the end on a busy machine."""
    last = -1.0
    while True:
        now = evidence.cpu_seconds(pid) or 0.0
        if now == last:
            return now
        last = now
        time.sleep(0.2)


def test_waiting_on_an_idle_process_uses_little_of_the_budget():
    idle = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        clock = naming.Clock(3.0, lambda: [(idle.pid, 0.0)])
        time.sleep(0.6)   # the machine busy elsewhere: wall time passes, no work is done
        assert clock.used() < 0.4   # at most a third of the wall time (WALL_SLACK), not all of it
        assert clock.left() > 2.6
    finally:
        idle.kill()
        idle.wait()


def test_a_worker_started_during_the_naming_counts_all_its_cpu_time():
    workers = []   # (none yet when the naming starts)
    clock = naming.Clock(10.0, lambda: workers)
    busy = _spinning(0.5)
    workers.append((busy.pid, time.monotonic()))
    try:
        while (evidence.cpu_seconds(busy.pid) or 0.0) < 0.5:
            time.sleep(0.05)
        assert clock.used() >= 0.45
    finally:
        busy.kill()
        busy.wait()


def test_a_helper_started_during_the_naming_does_not_count_its_start():
    """The reference's helper, started by a cold grading's first naming: the CPU seconds it took to start
    and import (its ``startup_cpu``) are not naming work; what it does after counts."""
    helpers = []
    busy = _spinning(0.6)
    try:
        started = _settled(busy.pid)
        clock = naming.Clock(10.0, lambda: helpers)   # (after the settling: its wall time is no naming's)
        helpers.append((busy.pid, time.monotonic(), started - 0.2))   # the last 0.2 s after its start
        assert 0.1 <= clock.used() < 0.45
    finally:
        busy.kill()
        busy.wait()


def test_a_worker_running_before_counts_from_the_start_only():
    busy = _spinning(0.4)
    try:
        while (evidence.cpu_seconds(busy.pid) or 0.0) < 0.4:
            time.sleep(0.05)
        clock = naming.Clock(10.0, lambda: [(busy.pid, 0.0)])   # its 0.4 s are an earlier grading's
        assert clock.used() < 0.2
    finally:
        busy.kill()
        busy.wait()


def test_the_wall_clock_bounds_a_naming_on_a_very_busy_machine():
    clock = naming.Clock(0.1, lambda: [])
    time.sleep(0.1 * naming.WALL_SLACK + 0.05)
    assert clock.left() <= 0


def test_without_a_readable_process_the_clock_is_the_wall_clock():
    clock = naming.Clock(1.0, lambda: [(2**22 + 12345, 0.0)])   # no such process
    time.sleep(0.3)
    assert clock.used() >= 0.3
    assert naming.Clock(1.0).left() > 0.9   # (no processes given: wall clock)


def test_a_call_may_take_the_cpu_seconds_left_times_the_slack_in_wall_time():
    """A timeout for work measured in CPU seconds: on a busy machine it takes up to WALL_SLACK times as long
    in wall time, within the naming's own wall bound; a wall clock gives its seconds left as they are."""
    clock = naming.Clock(2.0, lambda: [])
    assert 2.0 * naming.WALL_SLACK - 0.5 < clock.wall_left() <= 2.0 * naming.WALL_SLACK
    wall = naming.Clock(2.0)
    assert 1.5 < wall.wall_left() <= 2.0


def test_the_helper_knows_what_its_start_cost():
    from pathlib import Path

    from autograder.engine.mutants.helper import Helper

    helper = Helper()
    try:
        source = (Path(__file__).resolve().parents[1] / "reference_solutions" / "lab07_transformations.py").read_text()
        helper.prepare(source, "lab07_transformations", [], 20.0)
        pid, _ = helper.running
        assert 0.0 < helper.startup_cpu <= (evidence.cpu_seconds(pid) or 0.0)
    finally:
        helper.close()


def _spin_here(cpu: float) -> None:
    started = time.thread_time()
    while time.thread_time() - started < cpu:
        pass


def _measured_afresh(monkeypatch) -> float:
    monkeypatch.setattr(naming, "_PACE", [])
    return naming.machine_pace()


def test_a_machine_s_pace_is_its_time_for_the_work_the_budgets_were_set_with(monkeypatch):
    """Work that takes this machine twice the budgets' machine's time: a pace of 2, within its bounds."""
    monkeypatch.setattr(naming, "_pace_work", lambda: _spin_here(0.02))
    monkeypatch.setattr(naming, "PACE_SECONDS", 0.01)
    assert 1.8 <= _measured_afresh(monkeypatch) <= 2.3
    monkeypatch.setattr(naming, "PACE_SECONDS", 0.001)   # twenty times slower: taken as the bound
    assert _measured_afresh(monkeypatch) == naming.PACE_BOUNDS[1]


def test_the_pace_is_measured_again_once_its_measure_is_old(monkeypatch):
    """A machine's pace drifts (other work comes and goes): a measure stands for PACE_FRESH seconds."""
    monkeypatch.setattr(naming, "_pace_work", lambda: _spin_here(0.01))
    monkeypatch.setattr(naming, "PACE_SECONDS", 0.01)
    monkeypatch.setattr(naming, "PACE_FRESH", 0.3)
    first = _measured_afresh(monkeypatch)
    assert naming.PACE_BOUNDS[0] <= first <= naming.PACE_BOUNDS[1]
    monkeypatch.setattr(naming, "_pace_work", lambda: _spin_here(0.03))   # the machine three times slower
    assert naming.machine_pace() == first   # (the measure still stands)
    time.sleep(0.35)
    assert naming.machine_pace() >= 2.5 * first


def test_a_slower_machine_s_seconds_count_as_fewer_of_the_budget_s(monkeypatch):
    """At pace 2 a naming's 1 s budget lasts 2 s of this machine's time: as many changes are tried."""
    monkeypatch.setattr(naming, "machine_pace", lambda: 2.0)
    wall = naming.Clock(1.0)
    time.sleep(0.4)
    assert 0.18 <= wall.used() < 0.3
    assert 1.0 < wall.wall_left() <= 1.6
    cpu = naming.Clock(1.0, lambda: [])
    _spin_here(0.4)
    assert 0.18 <= cpu.used() < 0.3
    # (the budget's 0.8 s left, WALL_SLACK times as long in wall time on a busy machine, at this pace)
    assert 0.7 * naming.WALL_SLACK * 2 < cpu.wall_left() <= 0.82 * naming.WALL_SLACK * 2


def test_a_slow_submission_s_found_change_may_take_as_long_again_as_its_calls_to_confirm():
    """A submission whose own loops are slow takes that long to pass: confirming a change found in it may take as
    much more, up to the grading's naming time again; a search finding nothing is not given it."""
    from types import SimpleNamespace

    def trial(own: float):
        return SimpleNamespace(sandbox=SimpleNamespace(student_seconds=own))

    assert naming.confirming_extra(trial(0.0)) == 0.0
    assert naming.confirming_extra(trial(4.0)) == 4.0
    assert naming.confirming_extra(trial(1000.0)) == naming.GRADING_SECONDS
    assert naming.confirming_extra(SimpleNamespace()) == 0.0   # (no sandbox: nothing more)


def test_a_clock_draws_on_its_spare_time_only_as_far_as_needed_and_given():
    clock = naming.Clock(1.0)
    clock.spare = 2.0
    clock.draw_on_spare(0.5)           # (enough left already: nothing drawn)
    assert clock.seconds == 1.0 and clock.spare == 2.0
    clock.draw_on_spare(2.5)
    assert 2.4 < clock.left() <= 2.5 and clock.spare < 0.6
    clock.draw_on_spare(10.0)          # (no more than the spare)
    assert clock.spare == 0.0 and clock.seconds == 3.0
