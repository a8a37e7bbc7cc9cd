"""Workers forked from the warm template (autograder/sandbox/zygote.py, template.py) are confined as
started ones are: no capability, no new privileges, the worker's user, a process and a /tmp of their own,
nothing of the template's socket or of the grader's install, random states of their own -- and the
template itself never holds what a worker's start carried."""

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from autograder.sandbox import confine, template
from autograder.sandbox.supervisor import Sandbox

NAMESPACED = confine.detect().level != "process-group"
pytestmark = pytest.mark.skipif(not NAMESPACED, reason="workers are forked from the template at the namespaced levels")

PROBE = '''
import os, sys
import numpy as np

GRADER = {grader!r}

def state():
    status = dict(line.split(":", 1) for line in open("/proc/self/status") if ":" in line)
    links = []
    for fd in os.listdir("/proc/self/fd"):
        try:
            links.append(os.readlink(f"/proc/self/fd/{fd}"))
        except OSError:
            pass
    return {
        "caps": {k: int(status[k].strip(), 16) for k in ("CapEff", "CapPrm", "CapInh", "CapBnd", "CapAmb")},
        "no_new_privs": status["NoNewPrivs"].strip(),
        "uid": os.getuid(), "pid": os.getpid(),
        "sockets": [link for link in links if link.startswith("socket:")],
        "grader": sorted(name for name in sys.modules if name.startswith(("autograder", "__editable__"))),
        "path": [p for p in sys.path if "autograder-template-" in p or p == GRADER or p.startswith(GRADER + "/autograder")
                 or "__editable__" in p] + [repr(hook) for hook in sys.path_hooks if "editable" in repr(hook).lower()],
        "draw": float(np.random.random()),
        "tmp": sorted(os.listdir("/tmp")),
        "argv": sys.argv,
        "main": sys.modules["__main__"].__file__,
    }

def leave(name):
    open(f"/tmp/{name}", "w").write("left")
'''


@pytest.fixture(autouse=True)
def own_template(monkeypatch):
    """A template of the test's own: what another test in this process did to the shared one (a refusal it
    provoked) is not this test's."""
    monkeypatch.setattr(template, "_SHARED", {})
    monkeypatch.setattr(template, "_PROCESSES", set())
    yield
    if template._SHARED.get("template") is not None:
        template._SHARED["template"].close()


@pytest.fixture
def probe(tmp_path) -> Path:
    folder = tmp_path / "submission"
    folder.mkdir()
    (folder / "probe.py").write_text(PROBE.replace("{grader!r}", repr(str(Path(__file__).resolve().parents[1]))))
    return folder


def _state(folder):
    with Sandbox(folder) as box:
        outcome = box.call("probe", "state")
        assert outcome.ok, outcome.message
        assert isinstance(box.proc, template.Forked)
        return outcome.value


def test_a_forked_worker_holds_no_privilege_and_nothing_of_the_template_or_the_grader(probe):
    state = _state(probe)
    assert state["caps"] == dict.fromkeys(("CapEff", "CapPrm", "CapInh", "CapBnd", "CapAmb"), 0)
    assert state["no_new_privs"] == "1"
    confinement = confine.detect()
    if confinement.level == "namespaces+user":
        assert state["uid"] == confinement.uid
    assert state["pid"] == 2             # (PID 1 of its own namespace is its init)
    assert state["sockets"] == []        # the template's control socket above all
    assert state["grader"] == [] and state["path"] == []
    # (its arguments as a started worker's: the pipes' numbers, the submission, the output, the limits)
    assert state["argv"][0].endswith("/worker/worker.py") and len(state["argv"]) == 6
    assert all(argument.isdigit() for argument in state["argv"][1:3])
    assert state["main"].endswith("worker.py")   # (the worker's code is __main__, as the script started)


def test_each_forked_worker_draws_its_own_random_numbers_and_has_its_own_tmp(probe):
    with Sandbox(probe) as box:
        assert box.call("probe", "leave", ("left-by-the-first",)).ok
        first = box.call("probe", "state").value
    second = _state(probe)
    assert "left-by-the-first" in first["tmp"] and "left-by-the-first" not in second["tmp"]
    assert first["draw"] != second["draw"]


def test_the_template_never_holds_what_a_worker_s_start_carried(probe):
    """The request (the worker's folders, its view) is read by the forked child alone: the scratch folder's
    random name, which keeps one submission's worker from finding another's, is not in the template's memory."""
    with Sandbox(probe) as box:
        assert box.call("probe", "state").ok
        name = box.scratch.name.encode()
        pid = template.shared(confine.INTERPRETER, {}).pid
        try:
            memory = _memory_of(pid)
        except PermissionError:
            pytest.skip("the template's memory cannot be read here")
    assert memory and name not in memory


def _memory_of(pid: int) -> bytes:
    chunks = []
    with open(f"/proc/{pid}/maps") as maps, open(f"/proc/{pid}/mem", "rb", 0) as mem:
        for line in maps:
            span, permissions = line.split()[:2]
            if not permissions.startswith("rw"):
                continue
            start, end = (int(x, 16) for x in span.split("-"))
            try:
                mem.seek(start)
                chunks.append(mem.read(end - start))
            except (OSError, ValueError, OverflowError):
                continue
    return b"".join(chunks)


def test_a_killed_worker_is_told_as_a_started_one_is(probe):
    with Sandbox(probe) as box:
        assert box.call("probe", "state").ok
        worker = box.proc
        os.killpg(worker.pid, signal.SIGKILL)
        assert worker.wait(timeout=10) in (-signal.SIGKILL, 128 + signal.SIGKILL)
        killed = box.call("probe", "state")
        assert not killed.ok and "was killed (SIGKILL), not by the grader" in killed.message
        assert box.call("probe", "state").ok and box.proc is not worker   # (a new worker for the next call)


def test_a_process_group_sandbox_s_sweep_of_escaped_daemons_leaves_the_template_and_its_workers(probe):
    """At the process-group level, closing a sandbox kills the grader's children in other sessions (daemons
    its worker left); the template and its workers live in sessions of their own and are not such."""
    with Sandbox(probe) as box:
        assert box.call("probe", "state").ok and isinstance(box.proc, template.Forked)
        with Sandbox(probe, confinement=confine.Confinement("process-group")) as other:
            assert other.call("probe", "state").ok
        assert box.call("probe", "state").ok          # its forked worker lives on
    with Sandbox(probe) as box:                       # and so does the template
        assert box.call("probe", "state").ok and isinstance(box.proc, template.Forked)


def test_where_the_template_cannot_fork_workers_are_started_and_the_log_says_why(probe, monkeypatch, caplog):
    def cannot(self, request, fds):
        raise template.TemplateError("refused for the test")

    monkeypatch.setattr(template.Template, "fork", cannot)
    with Sandbox(probe) as box:
        outcome = box.call("probe", "state")
        assert outcome.ok and not isinstance(box.proc, template.Forked)
    assert "not forked from the warm template: a fork failed (refused for the test)" in caplog.text
    with Sandbox(probe) as box:   # (never tried again in this process)
        assert box.call("probe", "state").ok and not isinstance(box.proc, template.Forked)


def test_a_forked_worker_ending_before_it_is_ready_gives_way_to_a_started_one(probe, monkeypatch, caplog):
    """A failure after the fork (in PID 1's view, the worker's privilege drop) ends the worker before it says
    it is ready: the template is not used again, and this worker is started instead."""
    dummies = []

    def ends_at_once(self, request, fds):
        dummies.append(subprocess.Popen(["sleep", "30"], start_new_session=True))
        status_r, status_w = os.pipe()
        os.close(status_w)        # (it wrote no status: as if killed)
        return template.Forked(dummies[-1].pid, status_r)

    monkeypatch.setattr(template.Template, "fork", ends_at_once)
    with Sandbox(probe) as box:
        outcome = box.call("probe", "state")
        assert outcome.ok and not isinstance(box.proc, template.Forked)
        assert box.restarts == 0
    assert "a forked worker ended before it was ready (EOFError)" in caplog.text
    assert len(dummies) == 1 and dummies[0].wait(timeout=10) is not None


def test_exec_in_the_environment_starts_every_worker(probe, monkeypatch):
    monkeypatch.setenv("AUTOGRADER_WORKER_START", "exec")
    with Sandbox(probe) as box:
        assert box.call("probe", "state").ok and not isinstance(box.proc, template.Forked)


def test_the_template_and_its_workers_end_with_the_grading_process(probe):
    script = textwrap.dedent(f'''
        import sys, time
        from autograder.sandbox import confine, template
        from autograder.sandbox.supervisor import Sandbox
        box = Sandbox({str(probe)!r})
        assert box.call("probe", "state").ok
        print(template.shared(confine.INTERPRETER, {{}}).pid, box._worker_pid, flush=True)
        time.sleep(600)
        ''')
    grader = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True,
                              cwd=Path(__file__).resolve().parents[1])
    try:
        pids = [int(pid) for pid in grader.stdout.readline().split()]
    finally:
        grader.kill()
        grader.wait()
    assert len(pids) == 2
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline and any(_alive(pid) for pid in pids):
        time.sleep(0.1)
    assert not any(_alive(pid) for pid in pids)


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False
