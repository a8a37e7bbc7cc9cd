"""Hostile submissions, third generation: a fault is charged to its cause, named for what it is.

The first two generations check that an attack is contained. These check that it
is *charged* right: to the function that caused it, never to another lab's lane,
the module's import or the grader ("grader error"), and in words that say what
happened -- "used more than N MB of memory", "did not finish within N s",
"closed the grader's pipe", "time budget exhausted" -- decided from what the
grader measured (the cgroup's counters, the worker's descriptors and exit
status, the memory its processes hold), never from what the worker said.

Attacks on processes and memory run under every confinement level this machine
offers, with its cgroup and without one (``AUTOGRADER_CGROUP=off``: the grader
then measures memory and processes itself). Every attack bounds itself (sizes,
loops, lifetimes); limits are small so the file stays fast.
"""

import json
import math
import struct
import re
import tempfile
import textwrap

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from autograder.sandbox import confine, transport
from autograder.engine.registry import select
from autograder.engine.results import ERROR, write_json
from autograder.engine.runner import grade, run_check
from autograder.sandbox.supervisor import CallOutcome, Limits, Sandbox
from conftest import NAME_PROCESS, REFERENCE, assert_only_exercise_lost, marker, mutant, processes_named

LAB07, LAB09 = "lab07_transformations", "lab09_camera"
FAST = Limits(call_timeout=3.0, import_timeout=6.0, exercise_budget=30.0, submission_budget=90.0,
              memory=1 << 30, scratch_bytes=32 << 20, max_restarts=8)
NAMESPACED = confine.detect().level != "process-group"
LEVELS = [level for level in confine.LEVELS if level == "process-group"
          or (NAMESPACED and confine._candidate(level) is not None)]
CGROUP = confine.Cgroup.create(1 << 20, 8)
if CGROUP is not None:
    CGROUP.remove()
WITH_CGROUP = ["cgroup", "no cgroup"] if CGROUP is not None else ["no cgroup"]


@pytest.fixture(params=LEVELS)
def level(request, monkeypatch):
    """Every confinement level this machine offers."""
    monkeypatch.setenv("AUTOGRADER_CONFINEMENT", request.param)
    return request.param


@pytest.fixture(params=WITH_CGROUP)
def cgroup(request, monkeypatch):
    """With the cgroup the kernel enforces limits in (where the grader may make one), and without."""
    if request.param == "no cgroup":
        monkeypatch.setenv("AUTOGRADER_CGROUP", "off")
    return request.param


@pytest.fixture
def own_temporary_folder(tmp_path, monkeypatch):
    """The grader's temporary folders (sandboxes' scratch) go here, to see that none is left."""
    folder = tmp_path / "grader-tmp"
    folder.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(folder))
    return folder


# The attack runs once per grading, in shear_matrix(0.5), the first check's call; the rest
# of lab07.ex4 says "not implemented" (cheap), so no attack is repeated.
ONE_SHOT = """
        def shear_matrix(s):
            if s == 0.5:
                return _attack()
            raise NotImplementedError

        def shear(image, s=0.5):
            raise NotImplementedError
        """


def attacked(tmp_path, body, *, also=(), select_=("lab07.ex4", "lab07.ex5"), limits=FAST, lanes=1):
    """A correct submission (lab07 and the modules ``also``) whose ``_attack()`` runs in lab07.ex4."""
    submission = mutant(tmp_path, LAB07, textwrap.dedent(body) + textwrap.dedent(ONE_SHOT))
    for module in also:
        (submission / f"{module}.py").write_text((REFERENCE / f"{module}.py").read_text())
    return grade(submission, list(select_), limits=limits, pictures="none", lanes=lanes)


def messages(result, exercise_id) -> str:
    [exercise] = [e for e in result.exercises if e.id == exercise_id]
    return " ".join([exercise.message] + [c.message for c in exercise.checks])


def assert_no_grader_error(result):
    errors = [(e.id, c.name, c.message) for e in result.exercises for c in e.checks if c.status == ERROR]
    assert errors == []


def sandbox_for(tmp_path, source: str, limits: Limits, **modules: str) -> Sandbox:
    """A sandbox of its own around a module ``m`` (and ``modules``, name -> source): cheaper than a
    grading, for attacks on the worker."""
    folder = tmp_path / "module"
    folder.mkdir()
    for name, text in {"m": source, **modules}.items():
        (folder / f"{name}.py").write_text(textwrap.dedent(text))
    return Sandbox(folder, limits)


# ================================================================ memory
def test_a_memory_bomb_leaves_the_other_lanes_memory_alone(tmp_path, cgroup):
    """Lanes have fixed shares of the submission's memory: lab 7's bomb is stopped at its own,
    lab 9 beside it keeps all of its share and every mark."""
    result = attacked(tmp_path, """
        def _attack():
            import numpy as np
            held = []
            for _ in range(40):                          # 40 x 64 MiB, touched: far over a lane's share
                held.append(np.ones(64 * 2**20, np.uint8))
            return None
        """, also=[LAB09], select_=("lab07.ex4", "lab07.ex5", "lab09"), lanes=2,
        limits=Limits(**{**FAST.__dict__, "memory": 512 << 20, "call_timeout": 10.0}))
    assert_only_exercise_lost(result, "lab07.ex4", "shear_matrix() used more than 256 MB of memory")
    assert_no_grader_error(result)


def test_lanes_shares_fit_in_the_machine(monkeypatch):
    """A share no lane can borrow from another is one that exists: the shares together are no more
    than the workers may hold on this machine (else its OOM killer would pick any process)."""
    monkeypatch.setattr("autograder.sandbox.supervisor.memory_for_workers", lambda: 2 << 30)
    assert Limits(memory=6 << 30).shared_by(2).memory == 1 << 30
    assert Limits(memory=1 << 30).shared_by(2).memory == 512 << 20
    assert Limits(memory=6 << 30).shared_by(1) == Limits(memory=6 << 30)  # one worker: capped by its sandbox


HOG = """
    import time
    import numpy as np

    def page_by_page():
        held = []
        for _ in range(1500):                            # 1 MiB every 2 ms, each page touched
            block = bytearray(2**20)
            block[::4096] = b"x" * 256
            held.append(block)
            time.sleep(0.002)
        return len(held)

    def in_four_children():
        import os
        children = []
        for _ in range(4):                               # 4 x 150 MiB, together over the limit
            pid = os.fork()
            if pid == 0:
                block = bytearray(150 * 2**20)
                block[::4096] = b"x" * len(block[::4096])
                time.sleep(3)
                os._exit(0)
            children.append(pid)
        for pid in children:
            os.waitpid(pid, 0)
        time.sleep(8)                                    # (over the call's timeout)
        return 0

    def too_large_at_once():
        return float(np.zeros((10**6, 10**6)).sum())    # refused by the address-space limit

    def fine():
        return 1
    """


def test_memory_hogs_are_told_they_used_too_much_memory(tmp_path, cgroup, level):
    limits = Limits(call_timeout=6.0, memory=320 << 20, address_space=4 << 30)
    with sandbox_for(tmp_path, HOG, limits) as box:
        for function in ("page_by_page", "in_four_children"):
            outcome = box.call("m", function)
            assert outcome.kind == "memory", outcome.message
            assert outcome.message.startswith(f"{function}() used more than 320 MB of memory"), outcome.message
            assert box.call("m", "fine").value == 1  # the next call has a worker with all its memory
        outcome = box.call("m", "too_large_at_once")
        assert (outcome.kind, outcome.message) == \
            ("memory", "too_large_at_once() asked for more than 4096 MB of memory (MemoryError)")


def test_a_zero_stride_view_is_refused_for_its_size_before_it_is_copied(tmp_path, level):
    """2.3 GB that are eight bytes of memory: what crosses is counted before it is made."""
    with sandbox_for(tmp_path, """
        import numpy as np

        def broadcast():
            return np.broadcast_to(np.zeros(1), (2300, 2**17))

        def strided():
            return np.lib.stride_tricks.as_strided(np.zeros(1), shape=(2300, 2**17), strides=(0, 0))

        def fine():
            return 1
        """, Limits(call_timeout=5.0)) as box:
        for function in ("broadcast", "strided"):
            outcome = box.call("m", function)
            assert (outcome.kind, outcome.message) == ("result_type", f"{function}() returned a float64 array of "
                                                       "shape (2300, 131072) (2.25 GiB), which cannot be sent back: "
                                                       "it is more than the 16 MiB a result may be")
            assert box.call("m", "fine").value == 1


def test_what_a_call_may_answer_grows_with_what_it_is_given(tmp_path, level):
    """A reply may hold 64 times the bytes of the call's arrays, 16 MiB whatever it is given, at most the limit:
    a 3 x 3 question answered with 120 MiB, for each of a property's calls, made the grader hold gigabytes
    (hostile round of 2026-12-07). The worker refuses such a reply itself and answers the next call."""
    from autograder.sandbox.supervisor import ANSWER_FLOOR, ANSWER_RATIO, answer_cap

    assert answer_cap(2**30, (3.0, 4.0), {}) == ANSWER_FLOOR
    assert answer_cap(2**30, (np.zeros((1000, 1000)),), {}) == ANSWER_RATIO * 8 * 10**6
    assert answer_cap(2**28, ([np.zeros((1000, 1000))] * 3,), {}) == 2**28
    with sandbox_for(tmp_path, """
        import numpy as np

        def as_large_as(image, mib):
            return np.zeros(int(mib * 2**20) // 8)
        """, Limits(call_timeout=10.0)) as box:
        small, image = np.zeros((4, 4)), np.zeros((256, 256))   # 128 bytes, 512 KiB: 16 MiB and 32 MiB allowed
        assert box.call("m", "as_large_as", (small, 15)).ok
        refused = box.call("m", "as_large_as", (small, 17))
        assert (refused.kind, refused.message) == ("result_type", "as_large_as() returned a float64 array of shape "
                                                   "(2228224,) (17 MiB), which cannot be sent back: it is more than "
                                                   "the 16 MiB a result may be")
        assert box.call("m", "as_large_as", (image, 31)).ok
        assert box.call("m", "as_large_as", (image, 33)).kind == "result_type"
        assert box.restarts == 0   # (refused by the worker, which stays)


def test_a_worker_sending_more_than_its_call_may_answer_is_stopped_before_it_is_read(tmp_path):
    """The cap is the grader's: a worker that sends a reply past it anyway (its code replaced by the
    submission's) is stopped at the length, before any of it is read."""
    with sandbox_for(tmp_path, """
        import numpy as np
        import sys

        def lies():
            worker = sys.modules["__main__"]
            original = worker.send
            worker.send = lambda fd, message, max_bytes, max_elements=None: original(fd, message, 2**30, max_elements)
            return np.zeros(3 * 2**20)   # 24 MiB past a 16 MiB cap

        def fine():
            return 1
        """, Limits(call_timeout=10.0)) as box:
        outcome = box.call("m", "lies")
        assert outcome.kind == "result_type" and "at most 16 MiB can" in outcome.message, outcome.message
        assert box.call("m", "fine").value == 1


# ================================================================ processes
def test_children_left_allocating_are_killed_before_the_next_import(tmp_path, level, cgroup):
    """A call that leaves four double-forked children holding memory: they are gone as soon as it
    has answered (whether the grader counts them in a cgroup, among the worker's descendants, or
    as orphans handed to it), so the next module's import has its time and memory."""
    name = marker()
    with sandbox_for(tmp_path, NAME_PROCESS + f"""
        def leave_children():
            import os, time
            for _ in range(4):
                middle = os.fork()
                if middle == 0:
                    os.setsid()
                    if os.fork() == 0:
                        _name_this_process("{name}")
                        block = bytearray(150 * 2**20)   # 4 x 150 MiB: most of the worker's memory
                        block[::4096] = b"x" * len(block[::4096])
                        time.sleep(8)                    # bounded lifetime
                    os._exit(0)
                os.waitpid(middle, 0)                    # no child of the worker's is left to see
            time.sleep(0.5)
            return 1
        """, Limits(call_timeout=5.0, import_timeout=5.0, memory=768 << 20),
            later="import numpy\n\ndef fine():\n    return 2\n") as box:
        assert box.call("m", "leave_children").value == 1
        assert processes_named(name) == []
        assert box.call("later", "fine").value == 2


def test_a_fork_bomb_in_one_lane_leaves_the_other_lane_alone(tmp_path, level, cgroup):
    """Lab 9's import forks until it cannot: charged to that import, in its words; lab 7 in the
    other lane is graded in full, and no check reads "grader error"."""
    name = marker()
    submission = mutant(tmp_path, LAB09, NAME_PROCESS + f"""
        import os as _os, time as _time
        for _ in range(300):                             # bounded
            try:
                _pid = _os.fork()
            except OSError:
                break
            if _pid == 0:
                _name_this_process("{name}")
                _time.sleep(4)                           # each child ends by itself
                _os._exit(0)
        """)
    (submission / f"{LAB07}.py").write_text((REFERENCE / f"{LAB07}.py").read_text())
    result = grade(submission, ["lab07", "lab09.ex1", "lab09.ex2"], limits=FAST, pictures="none", lanes=2)
    assert_no_grader_error(result)
    for exercise in result.exercises:
        if exercise.id.startswith("lab07"):
            assert exercise.score == exercise.max_score, (exercise.id, messages(result, exercise.id))
        else:
            assert exercise.score == 0
            assert ("importing lab09_camera.py left processes running" in exercise.message
                    or "importing lab09_camera.py started more than 64 processes" in exercise.message), \
                exercise.message
    assert processes_named(name) == []


def test_a_fork_bomb_does_not_starve_a_worker_beside_it(tmp_path, level, cgroup):
    """Two workers at once (lanes, a batch's gradings): each has a process budget of its own --
    its cgroup's, else (as root) a user id of its own for RLIMIT_NPROC, or the grader's count --
    so one's fork bomb never keeps the other from starting threads."""
    import threading
    import time

    bomb_source = """
        import os, time

        def explode(seconds):
            children = []
            for _ in range(500):                         # bounded
                try:
                    pid = os.fork()
                except OSError:
                    break
                if pid == 0:
                    time.sleep(seconds)
                    os._exit(0)
                children.append(pid)
            for pid in children:
                os.waitpid(pid, 0)
            return len(children)
        """
    calm_source = """
        import threading, time

        def threads(n):
            started = [threading.Thread(target=time.sleep, args=(0.2,)) for _ in range(n)]
            for thread in started:
                thread.start()
            for thread in started:
                thread.join()
            return len(started)
        """
    (tmp_path / "bomb").mkdir()
    (tmp_path / "calm").mkdir()
    with sandbox_for(tmp_path / "bomb", bomb_source, Limits(call_timeout=20.0)) as bomb, \
            sandbox_for(tmp_path / "calm", calm_source, Limits(call_timeout=20.0)) as calm:
        assert bomb.ready() and calm.ready()
        exploded = {}
        explosion = threading.Thread(target=lambda: exploded.update(outcome=bomb.call("m", "explode", (3.0,))))
        explosion.start()
        time.sleep(1.0)                                  # the bomb has taken all it may by now
        outcome = calm.call("m", "threads", (40,))
        explosion.join()
    assert (outcome.ok, outcome.value) == (True, 40), outcome.message
    bombed = exploded["outcome"]
    assert (bombed.ok and 0 < bombed.value < 500) or bombed.message == \
        "explode() started more than 64 processes (a fork bomb?)", bombed.message


def test_an_import_that_leaves_a_thread_running_fails_once_without_a_grader_error(tmp_path, level):
    """Each new worker would import the module, and the thread, again: the import is charged."""
    result = attacked(tmp_path, """
        import threading as _threading, time as _time
        _threading.Thread(target=_time.sleep, args=(2,), daemon=True).start()

        def _attack():
            return None
        """)
    assert_no_grader_error(result)
    for exercise in result.exercises:
        assert exercise.score == 0
        assert exercise.message.startswith("importing lab07_transformations.py left threads running")


# ================================================================ the pipe, and how a worker ends
PIPES = """
    import os, signal, sys

    def close_reply():
        os.close(int(sys.argv[2]))
        return 1

    def close_request():
        os.close(int(sys.argv[1]))
        return 1

    def replace_reply():
        os.dup2(os.open(os.devnull, os.O_WRONLY), int(sys.argv[2]))
        return 1

    def close_everything():
        os.closerange(3, 1024)
        return 1

    def kill_itself():
        os.kill(os.getpid(), signal.SIGKILL)

    def exit_at_once():
        os._exit(3)

    def loop():
        while True:
            pass

    def fine():
        return 1
    """


def test_each_way_of_ending_gets_its_own_words(tmp_path, level):
    """A broken pipe, a kill, an exit and a timeout: charged to the call, in their own words."""
    with sandbox_for(tmp_path, PIPES, Limits(call_timeout=2.0)) as box:
        for function in ("close_reply", "close_request", "replace_reply", "close_everything"):
            outcome = box.call("m", function)
            assert (outcome.kind, outcome.message) == (
                "crashed", f"{function}() closed the grader's pipe to the worker; do not close or "
                           "replace file descriptors your code did not open")
            assert box.call("m", "fine").value == 1
        expected = {
            "kill_itself": ("crashed", "kill_itself() was killed (SIGKILL), not by the grader; do not kill processes"),
            "exit_at_once": ("crashed", "exit_at_once() ended the worker process (exit code 3); "
                                        "do not call os._exit() or kill processes"),
            "loop": ("timeout", "loop() did not finish within 2 s (an infinite loop, or far too slow?): when it was "
                                "stopped, it was at line {line} of your `loop` (m.py)"),
        }
        for function, verdict in expected.items():
            outcome = box.call("m", function)
            line = re.search(r"line (\d+) of", outcome.message)   # (the loop's own lines: `while True:` or `pass`)
            assert (outcome.kind, outcome.message) == (verdict[0], verdict[1].format(line=line and line.group(1)))
            assert line is None or textwrap.dedent(PIPES).splitlines()[int(line.group(1)) - 1].strip() in ("while True:", "pass")
            assert box.call("m", "fine").value == 1


# ================================================================ time
SLOW_LORIS = {
    "sleeps": """
        import time as _time
        def _slowly(function):
            def slow(*args, **kwargs):
                _time.sleep(0.9)                         # just under the call's timeout
                return function(*args, **kwargs)
            return slow
        """,
    "dribbles": """
        import time as _time
        def _slowly(function):
            def slow(*args, **kwargs):
                for _ in range(18):                      # a character every 50 ms, 0.9 s in all
                    print(".", end="", flush=True)
                    _time.sleep(0.05)
                return function(*args, **kwargs)
            return slow
        """,
}


@pytest.mark.parametrize("how", SLOW_LORIS)
def test_a_slow_loris_ends_at_the_deadline_with_results_and_nothing_left(tmp_path, own_temporary_folder, how):
    name = marker()
    source = textwrap.dedent(SLOW_LORIS[how]) + textwrap.dedent(NAME_PROCESS) + textwrap.dedent(f"""
        _name_this_process("{name}")
        for _name, _function in list(globals().items()):
            if callable(_function) and not _name.startswith("_") and getattr(_function, "__module__", "") == __name__:
                globals()[_name] = _slowly(_function)
        """)
    submission = mutant(tmp_path, LAB07, source)
    with open(submission / f"{LAB09}.py", "w") as module:
        module.write((REFERENCE / f"{LAB09}.py").read_text() + "\n" + source)
    limits = Limits(call_timeout=1.0, import_timeout=4.0, exercise_budget=3.0, submission_budget=6.0,
                    lab_budget=3.0)  # (two labs: the whole 6 s)
    result = grade(submission, ["lab07", "lab09"], limits=limits, pictures="none", lanes=2)
    # The deadline is the grader's: whatever the calls did, grading ended at it (with what a
    # call running then and a busy machine add), every check has its verdict.
    assert result.seconds < limits.submission_budget + 2 * limits.call_timeout + 10
    text = json.dumps(result.to_dict())
    assert "time budget exhausted (the submission's 6 s)" in text
    assert_no_grader_error(result)
    write_json(result, tmp_path / "results.json")
    assert json.loads((tmp_path / "results.json").read_text())["exercises"]
    assert processes_named(name) == []
    assert list(own_temporary_folder.iterdir()) == []


def test_a_call_running_at_the_deadline_is_stopped_at_it(tmp_path):
    """The deadline is the grader's clock, not the seconds billed: a call, and the restart of a
    worker, end at it whatever the call's own timeout and the exercise's budget allow."""
    import time

    with sandbox_for(tmp_path, """
        import time

        def sleep(seconds):
            time.sleep(seconds)
            return seconds
        """, Limits(call_timeout=30.0)) as box:
        assert box.call("m", "sleep", (0.0,)).value == 0.0
        box.start_exercise(until=None)                      # no budget of billed seconds at all
        box.set_deadline(time.monotonic() + 1.5)
        stopped = box.call("m", "sleep", (20.0,))
        assert (stopped.kind, stopped.message) == ("budget", "sleep() was stopped: time budget exhausted")
        assert box.call("m", "sleep", (0.0,)).kind == "budget"  # nothing starts after it, not even a worker
    # Gradescope's timeout is 10 minutes, the measured harness's 300 s: by default a submission's
    # whole grading ends with a minute to spare for the process's start and the reports.
    assert Limits().submission_budget + 60 <= 300


# ================================================================ replies, however exotic
# Frames in the transport's grammar (tests/test_transport.py has random bytes and corrupted
# frames): valid nodes mostly, so that decoding goes deep, and every kind of nonsense in them.
DTYPES = st.sampled_from(["<f8", ">f8", "<f4", ">f4", "<c16", ">c8", "|b1", "|u1", "<i2", ">i8", "<u8", ">u4",
                          "<f2", "<f16", "<c32", "|O", "|V8", "<M8[s]", "<U3", "|S2", "f8", "<f8\0", "xx", ""])
SHAPES = st.one_of(st.lists(st.integers(0, 4), max_size=3), st.lists(st.integers(0, 4), max_size=3),
                   st.lists(st.integers(-2, 2**70), max_size=3), st.integers(), st.none(), st.text(max_size=3))
ARRAYS = st.fixed_dictionaries({"a": st.sampled_from([0, 0, 1, 2, -1, True]), "dtype": DTYPES, "shape": SHAPES})
VALID_LEAVES = st.one_of(
    st.none(), st.booleans(), st.integers(-2**63, 2**63 - 1), st.floats(), st.text(max_size=5),
    st.sampled_from(["\ud800", "\udfff\x00", 5e-324, 1e308, -0.0]),
    st.fixed_dictionaries({"f": st.sampled_from(["nan", "inf", "-inf"])}),
    st.fixed_dictionaries({"c": st.tuples(st.floats(), st.integers(-9, 9)).map(list)}), ARRAYS)
ODD_LEAVES = st.one_of(
    st.sampled_from([2**63, -2**63 - 1, 10**400, [], {}]),
    st.fixed_dictionaries({"f": st.sampled_from(["NaN", "1e999", ""])}),
    st.fixed_dictionaries({"big": st.one_of(st.text(max_size=5), st.just("9" * 500))}),
    st.fixed_dictionaries({"c": st.lists(st.one_of(st.floats(), st.text(max_size=2)), max_size=3)}))
LEAVES = st.one_of(VALID_LEAVES, VALID_LEAVES, VALID_LEAVES, VALID_LEAVES, ODD_LEAVES)
TREES = st.recursive(LEAVES, lambda inner: st.one_of(
    st.fixed_dictionaries({"l": st.lists(inner, max_size=4)}),
    st.fixed_dictionaries({"t": st.lists(inner, max_size=4)}),
    st.fixed_dictionaries({"d": st.lists(st.tuples(st.text(max_size=3), inner).map(list), max_size=3)}),
    st.fixed_dictionaries({"l": st.lists(inner, max_size=4)}),
    st.fixed_dictionaries({"d": st.lists(st.tuples(st.one_of(st.integers(), st.none()), inner).map(list),
                                         max_size=2)}),
    st.lists(inner, max_size=2), st.dictionaries(st.text(max_size=2), inner, max_size=2)), max_leaves=10)


def assert_what_checks_compute_with(value):
    """Plain data of the kinds the checks are written for, or a TransportError: nothing else."""
    if isinstance(value, (list, tuple)):
        for item in value:
            assert_what_checks_compute_with(item)
    elif isinstance(value, dict):
        for key, item in value.items():
            key.encode("utf-8")
            assert_what_checks_compute_with(item)
    elif isinstance(value, np.ndarray):
        assert type(value) is np.ndarray and value.dtype.isnative and value.flags.writeable
        assert (value.dtype.kind, value.dtype.itemsize) in {("b", 1), ("f", 4), ("f", 8), ("c", 8), ("c", 16)} \
            or value.dtype.kind in "iu"
    elif isinstance(value, str):
        value.encode("utf-8")
    elif isinstance(value, int) and not isinstance(value, bool):
        assert -2**63 <= value < 2**63
    else:
        assert type(value) in (type(None), bool, float, complex)


def array_bytes(node) -> int | None:
    """How many bytes an array node's data takes, None when its dtype or shape make no sense."""
    try:
        count = 1
        for side in node["shape"]:
            count *= side
        return count * np.dtype(node["dtype"]).itemsize if 0 <= count < 2**16 else None
    except Exception:  # noqa: BLE001 - any nonsense the strategy drew
        return None


def array_nodes(tree):
    if isinstance(tree, dict) and "a" in tree:
        yield tree
    children = tree.values() if isinstance(tree, dict) else tree if isinstance(tree, list) else ()
    for child in children:
        yield from array_nodes(child)


@settings(max_examples=100)
@given(TREES, st.data())
def test_any_header_and_arrays_decode_to_plain_data_or_a_transport_error(tree, data):
    """Frames in the transport's own grammar, nonsense included: each array's bytes as long as its
    header says (mostly), then perhaps a few more or fewer."""
    header = json.dumps(tree, allow_nan=True).encode("utf-8", "surrogatepass")
    body = b"".join(data.draw(st.binary(min_size=n, max_size=n)) if n is not None else b""
                    for n in map(array_bytes, array_nodes(tree)))
    cut = data.draw(st.sampled_from([0, 0, 0, -1, 1]))
    body = body[:cut] if cut < 0 else body + b"\0" * cut
    frame = struct.pack(">4sQ", b"AGT1", len(header)) + header + body
    try:
        value = transport.decode(frame)
    except transport.TransportError:
        return
    assert_what_checks_compute_with(value)


@settings(max_examples=150)
@given(st.lists(st.tuples(DTYPES, st.lists(st.integers(0, 4), max_size=3)), min_size=1, max_size=3), st.data())
def test_arrays_of_any_dtype_decode_to_what_checks_compute_with_or_are_refused(arrays, data):
    """Well-formed array frames, every dtype: the allowed ones arrive with their values, in the
    machine's byte order; the rest are refused."""
    nodes = [{"a": index, "dtype": dtype, "shape": shape} for index, (dtype, shape) in enumerate(arrays)]
    chunks = [data.draw(st.binary(min_size=array_bytes(node) or 0, max_size=array_bytes(node) or 0))
              for node in nodes]
    header = json.dumps({"l": nodes}).encode()
    try:
        value = transport.decode(struct.pack(">4sQ", b"AGT1", len(header)) + header + b"".join(chunks))
    except transport.TransportError:
        return
    assert_what_checks_compute_with(value)
    for got, node, chunk in zip(value, nodes, chunks):
        sent = np.frombuffer(chunk, dtype=node["dtype"]).reshape(node["shape"])
        assert got.dtype == sent.dtype.newbyteorder("=")
        assert np.array_equal(got, sent, equal_nan=got.dtype.kind in "fc")


EXOTIC = {
    "an int too large for a float": [[10**400, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    "an int beyond 64 bits": 2**70,
    "NaN": math.nan,
    "a lone surrogate": "\ud800",
    "a dict": {"H": [[1.0]]},
    "a 0-d array": np.array(3.0),
    "big-endian floats": np.ones((3, 3), ">f8"),
    "nested empty lists": [[[[]]]],
}


class Replies:
    """Stands in for the sandbox: every call returns ``value`` as the transport delivers it."""

    def __init__(self, value):
        self.value = transport.decode(transport.encode(value))
        self.shared = {}

    def call(self, module, function, args=(), kwargs=None, **options):
        return CallOutcome(ok=True, value=self.value)


@pytest.mark.parametrize("value", list(EXOTIC.values()), ids=list(EXOTIC))
def test_no_reply_however_exotic_is_a_grader_error_in_any_check(value):
    """Every check of every lab (hidden ones where installed), judging an exotic reply to every call."""
    errors, sandboxes = [], {}
    for exercise in select([], include_hidden=True):
        sandbox = sandboxes.setdefault(exercise.lab.key, Replies(value))   # one per lab, as a grading's lane
        for check in exercise.checks:
            result = run_check(sandbox, check, pictures="none")
            if result.status == ERROR:
                errors.append((check.id, result.message))
    assert errors == []


@pytest.mark.parametrize("value, kind", [
    (np.ones(3, np.float16), "returned a float16 array of shape (3,) (6 bytes), which cannot be sent back: "
                             "arrays of dtype float16 cannot cross; use float32 or float64"),
    (np.ones(3, np.longdouble), "returned a float128 array of shape (3,) (48 bytes), which cannot be sent back: "
                                "arrays of dtype float128 cannot cross; use float32 or float64"),
    (np.array([object()]), "returned an object array of shape (1,) (8 bytes), which cannot be sent back: "
                           "arrays of dtype object cannot cross; use a numeric or bool dtype"),
    (np.broadcast_to(np.zeros(1), (2300, 2**17)), "returned a float64 array of shape (2300, 131072) (2.25 GiB), "
                                                  "which cannot be sent back: it is more than the 256 MiB a "
                                                  "result may be"),
    ("x" * (5 * 2**20), "returned a string of 5242880 characters, which cannot be sent back: it holds more than "
                        "4 MiB of numbers and text outside arrays; at most that can cross (return an array)"),
])
def test_what_cannot_cross_is_refused_where_it_is_made(value, kind):
    with pytest.raises(transport.TransportError) as refused:
        transport.encode(value)
    assert str(refused.value) == kind


def test_huge_and_odd_numbers_cross_as_the_numbers_checks_compute_with():
    value = transport.decode(transport.encode([10**400, -10**400, 2**70, 2**63 - 1, np.longdouble(0.5),
                                               np.ones(2, ">f4"), {"\ud800": "x\udfff"}]))
    assert value[:5] == [math.inf, -math.inf, float(2**70), 2**63 - 1, 0.5]
    assert value[5].dtype == np.float32 and value[5].dtype.isnative
    assert value[6] == {"?": "x?"}  # lone surrogates: valid JSON, not text a page or a file can hold


def test_a_checks_kept_calls_hold_a_bounded_share_of_answers():
    """A check keeps its last calls for naming: at most 64 MiB of their answers, the last call whatever its size."""
    from autograder.engine.checks import _CALLS_BYTES, _within_bytes
    from autograder.sandbox.supervisor import array_bytes as answer_bytes

    calls = [("f", (k,), {}, np.zeros(2**22)) for k in range(40)]   # 32 MiB each
    _within_bytes(calls, _CALLS_BYTES)
    assert [call[1] for call in calls] == [(38,), (39,)]
    huge = [("f", (), {}, [np.zeros(2**24), {"H": np.zeros(3)}])]   # 128 MiB, alone: kept
    _within_bytes(huge, _CALLS_BYTES)
    assert len(huge) == 1 and answer_bytes(huge[0][3]) == 2**27 + 24
    assert answer_bytes([(1.0, 2.0)] * 10**5) == 0   # numbers outside arrays: bounded by the transport
