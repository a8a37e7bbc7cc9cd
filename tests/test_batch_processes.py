"""Issue 24, the batch's processes: a grading process that dies is charged to its own
submission alone; nothing of a batch outlives it, whatever signal ends it, and a later
batch removes what a killed one left; the grading processes are forked from the server.

The class grades the cheap ``lab07.ex1``, as in ``test_batch.py``. No submission can kill
its grading process (student code runs in the sandbox's worker), so the grading
processes are made to die here: the pool runs :func:`grade_or_die` in place of
``grade_files``, picked up by reference in each grading process.
"""

from __future__ import annotations

import functools
import inspect
import os
import signal
import subprocess
import sys
import shutil
import tempfile
import textwrap
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from autograder.instructor.batch import processes, run
from autograder.instructor.batch.gradebook import Gradebook
from autograder.instructor.batch.run import POOL_ATTEMPTS, run_batch
from autograder.instructor.batch.task import grade_files
from conftest import ROOT
from test_batch import (COURSE, MODULE, WRONG_WAY, _first_difference, _gradings, assert_same_gradebook,
                        class_course, comparable, reference, skeleton, write)

pytestmark = pytest.mark.slow


# ------------------------------------------------------------------ the class
def make_class(root: Path, hanging: bool = True) -> Path:
    for i in range(6):
        write(root / f"correct-{i}" / f"{MODULE}.py", reference())
    write(root / "partly-wrong" / f"{MODULE}.py", reference() + WRONG_WAY)
    write(root / "skeleton" / f"{MODULE}.py", skeleton())
    write(root / "broken-import" / f"{MODULE}.py", "import numpy_but_misspelt\n" + reference())
    write(root / "lone-file.py", reference())
    if hanging:   # its import never ends: only a grader alive stops its worker
        write(root / "hangs" / f"{MODULE}.py", "while True:\n    pass\n")
    return root


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    """The class (without the hanging student) graded once, uninterrupted."""
    root = tmp_path_factory.mktemp("processes")
    submissions = make_class(root / "class", hanging=False)
    out = root / "uninterrupted"
    run_batch(submissions, out, course=COURSE, workers=2)
    return submissions, out


# ------------------------------------------------------------------ processes, seen from /proc
def _stat(pid: int) -> tuple[int, str, int] | None:
    """(parent pid, state, start time) of ``pid``, None if it is gone."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return None
    return int(fields[1]), fields[0], int(fields[19])


def _cmdline(pid: int) -> list[str]:
    """``pid``'s command line; a process forked from the workers' template (whose command line it keeps) has
    its name after it ("comm=ag-worker", see autograder/sandbox/zygote.py)."""
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            command = [part.decode(errors="replace") for part in f.read().split(b"\0") if part]
        if any(part.endswith("zygote.py") for part in command[:6]):
            with open(f"/proc/{pid}/comm") as f:
                command.append(f"comm={f.read().strip()}")
        return command
    except OSError:
        return []


def descendants(root: int) -> dict[tuple[int, int], list[str]]:
    """The processes under ``root`` now: ``{(pid, start time): command line}``."""
    parents = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit() and (stat := _stat(int(entry))) is not None:
            parents[int(entry)] = stat
    found, frontier = {}, [root]
    while frontier:
        parent = frontier.pop()
        for pid, (ppid, _, started) in parents.items():
            if ppid == parent and (pid, started) not in found:
                found[(pid, started)] = _cmdline(pid)
                frontier.append(pid)
    return found


def still_running(processes_seen) -> list[tuple[int, int]]:
    """Those of ``processes_seen`` ((pid, start time)) alive now (a zombie is not)."""
    alive = []
    for pid, started in processes_seen:
        stat = _stat(pid)
        if stat is not None and stat[2] == started and stat[1] not in ("Z", "X"):
            alive.append((pid, started))
    return alive


def wait_until_gone(processes_seen, seconds: float = 30) -> list[str]:
    """Wait (up to ``seconds``) for every process of ``processes_seen`` to end; the command
    lines of those still running then."""
    deadline = time.monotonic() + seconds
    while still_running(processes_seen) and time.monotonic() < deadline:
        time.sleep(0.1)
    return [" ".join(_cmdline(pid))[:200] for pid, _ in still_running(processes_seen)]


def is_sandbox_worker(command: list[str]) -> bool:
    """A worker started (``python -I -B worker.py``) or forked from the template (named ag-worker)."""
    return (len(command) > 3 and command[1:3] == ["-I", "-B"] and command[3].endswith("worker.py")) \
        or command[-1:] == ["comm=ag-worker"]


# ------------------------------------------------------------------ grading processes that die
def grade_or_die(*arguments, ways: dict[str, str], notes: str):
    """``grade_files(*arguments)``, but the grading process dies as ``ways[student]`` says:
    ``kill`` (SIGKILL), ``exit`` (``os._exit(3)``), ``segfault`` (SIGSEGV) before grading;
    ``once`` killed the first time only; ``beside-its-worker`` killed while its sandbox's
    worker runs the student's code (whose pids are noted in ``notes`` first)."""
    name = inspect.signature(grade_files).bind(*arguments).arguments["name"]
    way = ways.get(name)
    if way == "once":
        first = not (Path(notes) / name).exists()
        (Path(notes) / name).touch()
        way = "kill" if first else None
    if way == "kill":
        os.kill(os.getpid(), signal.SIGKILL)
    elif way == "exit":
        os._exit(3)
    elif way == "segfault":
        os.kill(os.getpid(), signal.SIGSEGV)
    elif way == "beside-its-worker":
        threading.Thread(target=_die_once_the_worker_runs, args=(Path(notes) / f"{name}.pids",),
                         daemon=True).start()
    return grade_files(*arguments)


def _die_once_the_worker_runs(notes: Path) -> None:
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline and not any(map(is_sandbox_worker, descendants(os.getpid()).values())):
        time.sleep(0.05)
    time.sleep(1.5)   # it has imported NumPy and OpenCV, and spins in the student's module
    with notes.open("a") as f:
        for (pid, started), command in descendants(os.getpid()).items():
            f.write(f"{pid} {started} {int(is_sandbox_worker(command))}\n")
    os.kill(os.getpid(), signal.SIGKILL)


def test_a_dying_grading_process_is_charged_to_its_own_submission_alone(uninterrupted, tmp_path, monkeypatch):
    """Three students whose gradings kill their process (three ways) are failed with how it
    died; one whose grading kills it once is graded; everyone else is graded as in an
    uninterrupted run; the sandbox worker of a process killed mid-grading dies with it."""
    submissions, reference_out = uninterrupted
    make_class(submissions.parent / "with-hanging")
    ways = {"correct-1": "segfault", "skeleton": "exit", "hangs": "beside-its-worker", "partly-wrong": "once",
            "broken-import": "once"}
    notes = tmp_path / "notes"
    notes.mkdir()
    monkeypatch.setattr(run, "grade_files", functools.partial(grade_or_die, ways=ways, notes=str(notes)))
    summary = run_batch(submissions.parent / "with-hanging", tmp_path / "out", course=COURSE, workers=2)

    doomed = {"correct-1": "killed by SIGSEGV", "skeleton": "exit status 3", "hangs": "killed by SIGKILL"}
    assert sorted(line.split(":")[0] for line in summary.failed) == sorted(doomed)
    students = {s["student_id"]: s for s in comparable(tmp_path / "out")}
    for student_id, how in doomed.items():
        assert students[student_id]["status"] == "failed"
        assert students[student_id]["reason"] == (f"the grading process died while grading this submission, "
                                                  f"{POOL_ATTEMPTS} times: {how}")
    expected = {s["student_id"]: s for s in comparable(reference_out)}
    assert sorted(students) == sorted([*expected, "hangs"])
    for student_id, student in expected.items():
        if student_id not in doomed:
            assert students[student_id] == student, _first_difference(students[student_id], student)
    with Gradebook(tmp_path / "out") as book:
        assert set(book.grading_counts().values()) == {1}

    # The processes under each killed grading process (its worker, busy at the student's
    # import, and the worker's namespace) ended with it.
    noted = [tuple(map(int, line.split())) for line in (notes / "hangs.pids").read_text().splitlines()]
    # (two workers each: the public checks' and the hidden checks' fresh one, booting meanwhile)
    assert sum(worker for *_, worker in noted) >= POOL_ATTEMPTS, "a worker ran under each killed process"
    assert wait_until_gone({(pid, started) for pid, started, _ in noted}) == []
    # and the files of the killed processes (their gradings' and sandboxes') are gone: those of
    # the processes that ended normally go as they end.
    deadline = time.monotonic() + 30
    while list(processes.batch_folder().glob("grading-*")) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert list(processes.batch_folder().glob("grading-*")) == []


# ------------------------------------------------------------------ signals
def _batch_folders(temporary: Path, pid: int) -> list[Path]:
    return list(temporary.glob(f"{processes.FOLDER_PREFIX}{pid}-*"))


@pytest.fixture
def private_temporary_folder() -> Iterator[dict]:
    """An environment whose temporary folder is this test's alone: any batch started meanwhile
    by a parallel test removes the folders of dead batches in *its* temporary folder, which
    would otherwise include the one this test kills and then looks for."""
    # Short (under the system's): the fork server's socket lives there, and a socket's path
    # is limited to 107 bytes (beyond, the batch spawns its gradings instead).
    temporary = Path(tempfile.mkdtemp(prefix="ag-"))
    yield {**os.environ, "TMPDIR": str(temporary)}
    shutil.rmtree(temporary, ignore_errors=True)


def _run_until_graded(command, out: Path, at_least: int, env: dict) -> tuple[subprocess.Popen, dict]:
    """Start ``command`` (a batch), noting every process under it, until the gradebook holds
    ``at_least`` gradings; returns the batch's process and what was seen under it."""
    batch = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             start_new_session=True, cwd=ROOT, env=env)
    seen: dict = {}
    deadline = time.monotonic() + 120
    try:
        while _gradings(out) < at_least:
            assert batch.poll() is None, batch.stderr.read().decode()
            assert time.monotonic() < deadline, "the batch graded too little in two minutes"
            seen.update(descendants(batch.pid))
            time.sleep(0.05)
        seen.update(descendants(batch.pid))
    except BaseException:
        os.killpg(batch.pid, signal.SIGKILL)
        batch.wait()
        raise
    return batch, seen


def test_sigterm_and_sigkill_leave_no_process_and_a_rerun_removes_what_was_left(uninterrupted, tmp_path,
                                                                              private_temporary_folder):
    """SIGTERM (the batch stops as on Ctrl-C, its files removed) then SIGKILL (nothing of the
    batch can run after it): within seconds no process of the batch is left -- grading
    processes, fork server, resource tracker, sandbox workers -- and a rerun removes the
    killed batch's folder and gives the uninterrupted run's gradebook, nothing graded twice."""
    submissions, reference_out = uninterrupted
    out = tmp_path / "out"
    command = [sys.executable, "-m", "autograder", "batch", str(submissions), "--out", str(out),
               "--workers", "2", "--course", str(class_course(tmp_path))]
    env = private_temporary_folder
    temporary = Path(env["TMPDIR"])
    terminated, seen = _run_until_graded(command, out, at_least=2, env=env)
    try:
        folder, = _batch_folders(temporary, terminated.pid)
        terminated.send_signal(signal.SIGTERM)
        assert terminated.wait(timeout=60) == 130, terminated.stderr.read().decode()   # as after Ctrl-C
        assert wait_until_gone(seen) == []
    finally:
        os.killpg(terminated.pid, signal.SIGKILL)   # whatever is left of it, once the assertions are made
    commands = [" ".join(c) for c in seen.values()]
    assert any("forkserver" in c for c in commands) and any("resource_tracker" in c for c in commands)
    assert any(is_sandbox_worker(c) for c in seen.values()), commands
    assert not any("spawn_main" in c for c in commands), "the grading processes are forked, not spawned"
    assert not folder.exists(), "a batch stopped by SIGTERM removes its temporary files"

    graded_before = _gradings(out)
    killed, seen = _run_until_graded(command, out, at_least=graded_before + 1, env=env)
    folder, = _batch_folders(temporary, killed.pid)
    os.kill(killed.pid, signal.SIGKILL)
    killed.wait()
    try:
        assert wait_until_gone(seen) == []
    finally:
        os.killpg(killed.pid, signal.SIGKILL)
    assert folder.exists(), "nothing of a batch killed with SIGKILL removes its files"
    assert _gradings(out) < len(comparable(reference_out)), "killed before the end"

    rerun = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=ROOT,
                           env=env, timeout=300)
    assert rerun.returncode == 0, rerun.stderr.decode()
    assert not folder.exists(), "the next batch removes a dead batch's temporary files"
    assert_same_gradebook(out, reference_out)
    with Gradebook(out) as book:
        assert set(book.grading_counts().values()) == {1}, "nothing graded twice"


# ------------------------------------------------------------------ the fork server
def test_the_grading_processes_are_forked_from_the_server_after_opencv_is_imported():
    """The command line starts the server before importing the grader; importing OpenCV
    then adds LD_LIBRARY_PATH to the environment: the gradings are still forked from it."""
    probe = textwrap.dedent("""
        import os, time
        from autograder.instructor.batch.task import grading_processes
        grading_processes()
        import cv2, autograder.instructor.batch.run
        from multiprocessing import forkserver
        context = grading_processes()
        server = getattr(forkserver._forkserver, "_forkserver_pid", None)  # private: the only way to find it
        if server is None:
            raise SystemExit("no server pid")
        process = context.Process(target=time.sleep, args=(0.5,))
        process.start()
        with open(f"/proc/{process.pid}/stat") as f:
            parent = int(f.read().rsplit(")", 1)[1].split()[1])
        process.join()
        print(context.get_start_method(), parent == server)
        """)
    result = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=60,
                            cwd=ROOT)
    if "no server pid" in result.stderr:
        pytest.skip("this Python's multiprocessing does not say which process is the fork server")
    assert result.stdout.split() == ["forkserver", "True"], result.stderr


# ------------------------------------------------------------------ leftovers
def test_only_the_folders_of_dead_batches_are_removed(tmp_path):
    """A batch folder whose owner's lock is free goes; one locked by a live process stays, as
    does one without its lock yet (its batch is starting) unless it is old."""
    holder = textwrap.dedent("""
        import fcntl, os, sys, time
        fd = os.open(sys.argv[1], os.O_WRONLY | os.O_CREAT, 0o600)
        fcntl.flock(fd, fcntl.LOCK_EX)
        print("locked", flush=True)
        time.sleep(60)
        """)
    live, dead, starting, stale = (tmp_path / f"{processes.FOLDER_PREFIX}{name}" for name in
                                   ("1-live", "2-dead", "3-starting", "4-stale"))
    for folder in (live, dead, starting, stale):
        (folder / "autograder-x" / "batch-y").mkdir(parents=True)
    (dead / "owner.lock").touch()
    os.utime(stale, (time.time() - 3600, time.time() - 3600))
    (tmp_path / "unrelated").mkdir()
    with subprocess.Popen([sys.executable, "-c", holder, str(live / "owner.lock")], stdout=subprocess.PIPE,
                          text=True) as owner:
        try:
            assert owner.stdout.readline().strip() == "locked"
            removed = processes.remove_dead_batch_folders(tmp_path)
        finally:
            owner.kill()
    assert sorted(removed) == sorted([dead, stale])
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([live.name, starting.name, "unrelated"])


def test_cgroups_left_by_a_killed_grading_process_are_removed_by_the_next():
    """A grading process killed outright cannot remove its sandboxes' cgroups: the next cgroup
    made beside them removes those whose creator is dead (never a live process's)."""
    from autograder.sandbox.confine import Cgroup

    def made(name):
        for attempt in (Cgroup._v2, Cgroup._v1):   # as Cgroup.create tries them
            try:
                group = attempt(name, None, None)
            except (OSError, ValueError):
                group = None
            if group is not None:
                return group
        pytest.skip("no cgroup can be made here")

    dead = subprocess.Popen(["true"])
    dead.wait()
    left, alive = made(f"autograder-{dead.pid}-0badcafe"), made(f"autograder-{os.getpid()}-00c0ffee")
    try:
        Cgroup.create(memory=None, processes=None).remove()
        assert not any(folder.exists() for folder in left.folders), "a dead creator's cgroup was left"
        assert all(folder.exists() for folder in alive.folders), "a live process's cgroup was removed"
    finally:
        left.remove()
        alive.remove()


# ------------------------------------------------------------------ a grading that never ends
def grade_or_hang(*arguments, stuck: str, notes: str):
    """``grade_files(*arguments)``, but the grading of ``stuck`` never ends, in the grader's own code (as a
    reading that loops without end would), each attempt noted."""
    name = inspect.signature(grade_files).bind(*arguments).arguments["name"]
    if name == stuck:
        with open(Path(notes) / name, "a") as attempts:
            attempts.write("attempt\n")
        while True:
            sum(range(10_000))
    return grade_files(*arguments)


def test_a_grading_stuck_in_the_graders_own_code_is_stopped_and_the_class_goes_on(tmp_path, monkeypatch):
    """The sandbox bounds the student's code and each grading stops at its own deadline, but a fault of the
    grader's (2026-12-07: a walk of syntax trees that wrapped what it walked, without end) ran on in its grading
    process, and the batch waited for it forever. The pool stops a grading process still on one submission
    twice the submission budget and two minutes after it took it; that submission is failed, once (run again, it
    would hang again), told as the grader's fault; the others are graded."""
    class_folder = tmp_path / "class"
    for name in ("ann", "bo", "stuck"):
        write(class_folder / name / f"{MODULE}.py", reference())
    notes = tmp_path / "notes"
    notes.mkdir()
    monkeypatch.setattr(run, "grade_files", functools.partial(grade_or_hang, stuck="stuck", notes=str(notes)))
    assert run.overdue_after({"submission_budget": 240}) == 600.0   # the course's default budget: ten minutes
    monkeypatch.setattr(run, "overdue_after", lambda rules: 8.0)
    started = time.monotonic()
    summary = run_batch(class_folder, tmp_path / "out", course=COURSE, workers=2)
    assert time.monotonic() - started < 8.0 + processes._STOP_SECONDS + 60
    [failed] = summary.failed
    assert failed.startswith("stuck: the grading process was stopped after 8 s, long past the grading's own deadline")
    assert "a fault of the grader's, not of this submission's code" in failed
    assert summary.graded == 2 and (notes / "stuck").read_text().count("attempt") == 1
