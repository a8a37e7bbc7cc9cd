"""Where a local batch's gradings run, and how nothing of them outlives the batch.

- :func:`grading_processes`: the processes are forked from a server that has
  imported the grader (started early, while the class is read), or spawned where
  no server can run or its start-up environment is no longer the caller's.
- :class:`GradingPool`: a process per worker, each running one grading at a
  time and saying which before it starts, so a process that dies is charged to
  that submission alone; it is replaced and the others go on.
- Nothing outlives the batch: each grading process gets a signal when its parent
  dies (Linux's parent-death signal), stops its sandbox's worker and removes its
  files; the batch stops on SIGTERM as on Ctrl-C (:func:`stopped_like_ctrl_c`).
- Temporary files (the class extracted from a zip, each grading's files and
  sandbox) live in one folder per batch process, ``autograder-batch-<pid>-*`` in
  the system's temporary folder (:func:`batch_folder`), each grading process's in
  a folder of its own there, removed by the pool once the process is dead; a batch
  removes the folders of batches that died without removing their own (a lock
  held for the owner's life says which).
"""

from __future__ import annotations

import ctypes
import fcntl
import functools
import os
import shutil
import signal
import sys
import tempfile
import threading
import time
from collections import deque
from contextlib import contextmanager
from dataclasses import dataclass
from multiprocessing import connection as connections
from multiprocessing import forkserver, get_context, util
from pathlib import Path
from typing import Callable, Iterator

FOLDER_PREFIX = "autograder-batch-"
_OWNER = "owner.lock"        # locked by the batch process for its whole life
_ORPHAN_SECONDS = 60         # a folder without its lock this old was left by a process killed at birth
_STOP_SECONDS = 10           # a grading process stopped (SIGTERM) has this long to clean up
_PR_SET_PDEATHSIG = 1
# Read when a process starts or imports the grader (the interpreter, BLAS, OpenCV): a process
# forked from the server keeps the values the server started with. Every other variable is
# handed to each grading process as the batch has it (importing OpenCV alone adds one).
_STARTUP_PREFIXES = ("PYTHON", "OPENBLAS_", "OMP_", "MKL_", "OPENCV_", "LD_PRELOAD")

_server_environment: dict | None = None   # the environment the fork server started with
_no_server = False                        # it could not start here: each process is spawned
_folder: Path | None = None               # this process's batch folder (see batch_folder)


# ------------------------------------------------------------------ the processes' origin
def grading_processes():
    """Where local gradings run (a multiprocessing context): processes forked from a server
    that has imported the grader (and nothing else: no copy of the gradebook's connection,
    nothing of the batch's process), started at the first call. Each grading process takes
    the caller's environment when it starts (:class:`GradingPool`); only if a variable read
    at start-up (``PYTHON*``, BLAS's and OpenCV's) has changed since the server started are
    the gradings spawned afresh. ``AUTOGRADER_FORKSERVER=off`` spawns them always."""
    global _server_environment, _no_server
    if os.environ.get("AUTOGRADER_FORKSERVER") == "off":
        return get_context("spawn")
    if _server_environment is None and not _no_server:
        environment = dict(os.environ)
        # A process that forks must have no other threads: NumPy's OpenBLAS would start them.
        os.environ["OPENBLAS_NUM_THREADS"] = "1"
        try:
            get_context("forkserver").set_forkserver_preload(
                ["autograder.instructor.batch.task", "autograder.engine.runner", "autograder.reports.html"])
            with _temporary_files_in(batch_folder()):   # the server's socket among the batch's files
                forkserver.ensure_running()
            _server_environment = environment
        except (OSError, ValueError):  # no server here (no socket, no fork)
            _no_server = True
        finally:  # the caller's environment as it was
            os.environ.pop("OPENBLAS_NUM_THREADS")
            if "OPENBLAS_NUM_THREADS" in environment:
                os.environ["OPENBLAS_NUM_THREADS"] = environment["OPENBLAS_NUM_THREADS"]
    forked = not _no_server and _read_at_startup(os.environ) == _read_at_startup(_server_environment)
    return get_context("forkserver" if forked else "spawn")


def _read_at_startup(environment) -> dict:
    return {name: value for name, value in environment.items() if name.startswith(_STARTUP_PREFIXES)}


# ------------------------------------------------------------------ the pool
@dataclass(frozen=True)
class ProcessDeath:
    """The outcome of a task whose process died while running it: ``how`` it died; ``overdue``:
    it was stopped, the task still running long after the grading's own deadline (a fault of
    the grader's, which running it again would meet again)."""

    how: str
    overdue: bool = False


class GradingProcessesFailed(RuntimeError):
    """The grading processes die before they run anything (a broken installation)."""


class _Member:
    """One process of the pool and the task it holds (None: idle)."""

    def __init__(self, process, connection):
        self.process, self.connection = process, connection
        self.key: str | None = None
        self.arguments: tuple = ()
        self.started = False   # it said it started the task: its death is the task's
        self.handed = 0.0      # when it was handed the task (time.monotonic())
        self.overdue = False   # stopped for running past the pool's task_seconds


class GradingPool:
    """Up to ``processes`` processes (from :func:`grading_processes`) running
    ``task(*arguments)`` one task at a time each; ``task`` returns plain data (a
    :func:`.task.grade_files` outcome) and is pickled by reference.

    Each process says which task it starts before running it: a process that dies
    is charged to that task alone (its outcome is a :class:`ProcessDeath`), and
    replaced; the other tasks go on. Leaving the ``with`` block normally lets the
    processes end on their own (while the caller goes on); on an exception (Ctrl-C,
    SIGTERM) they are stopped, their sandboxes and files removed, before it returns.

    Examples
    --------
    >>> with GradingPool(2, grade_files) as pool:                  # doctest: +SKIP
    ...     pool.submit("alice", (files, selectors, ..., "alice", threads))
    ...     for key, outcome in pool.outcomes():
    ...         ...
    """

    def __init__(self, processes: int, task: Callable, context=None, task_seconds: float | None = None):
        if processes < 1:
            raise ValueError(f"a pool needs at least one process, not {processes}")
        self._size = processes
        # A backstop, not a budget: a grading ends at its own deadline, and the grader's code
        # after it (judging, pictures, the page) is bounded too; a task still running this long
        # after it was handed out is stuck in the grader (a loop that never ends, a lock never
        # released) and would hold the batch forever. None: no bound.
        self._task_seconds = task_seconds
        self._context = context or grading_processes()
        self._folder = batch_folder()
        self._start_arguments = (task, dict(os.environ), str(self._folder), os.getpid())
        self._queue: deque[tuple[str, tuple]] = deque()
        self._members: list[_Member] = []
        self._unstarted_deaths = 0

    def __enter__(self):
        return self

    def __exit__(self, kind, *exc):
        if kind is None:
            self.close()
        else:
            self.stop()

    @property
    def running(self) -> list[str]:
        """The keys of the tasks handed out and not ended yet (one per busy process)."""
        return [m.key for m in self._members if m.key is not None]

    def submit(self, key: str, arguments: tuple) -> None:
        """Run ``task(*arguments)``; its outcome comes out of :meth:`outcomes` with ``key``."""
        self._queue.append((key, arguments))

    def outcomes(self) -> Iterator[tuple[str, object]]:
        """``(key, outcome)`` as each task ends, until none is left (tasks submitted
        meanwhile included): the task's value, or a :class:`ProcessDeath`."""
        while self._queue or any(m.key is not None for m in self._members):
            self._hand_out()
            busy = [m for m in self._members if m.key is not None]
            ready = set(connections.wait([m.connection for m in busy] + [m.process.sentinel for m in busy],
                                         self._wait_seconds(busy)))
            for member in busy:
                if member.connection in ready or member.process.sentinel in ready:
                    yield from self._receive(member)
                elif self._task_seconds is not None and time.monotonic() - member.handed > self._task_seconds:
                    member.overdue = True
                    self._stop_member(member)
                    yield from self._bury(member)

    def _wait_seconds(self, busy: list) -> float | None:
        """How long the pool may wait for a message before a busy process is overdue (None: no bound)."""
        if self._task_seconds is None or not busy:
            return None
        return max(0.0, min(m.handed for m in busy) + self._task_seconds - time.monotonic())

    @staticmethod
    def _stop_member(member: "_Member") -> None:
        """SIGTERM (it stops its sandbox's worker and removes its files), SIGKILL if still there after
        :data:`_STOP_SECONDS`."""
        member.process.terminate()
        member.process.join(_STOP_SECONDS)
        if member.process.exitcode is None:
            member.process.kill()

    def close(self) -> None:
        """Let the processes end (each when it sees the pool closed); do not wait for them."""
        for member in self._members:
            try:
                member.connection.send(None)
            except OSError:
                pass
            member.connection.close()
        self._members = []

    def stop(self) -> None:
        """Stop every process now: SIGTERM (each stops its sandbox's worker and removes its
        files), SIGKILL for any still there after :data:`_STOP_SECONDS`."""
        for member in self._members:
            if member.process.exitcode is None:
                member.process.terminate()
        deadline = time.monotonic() + _STOP_SECONDS
        for member in self._members:
            member.process.join(max(0.0, deadline - time.monotonic()))
            if member.process.exitcode is None:
                member.process.kill()
                member.process.join()
            member.connection.close()
            shutil.rmtree(_own_folder(self._folder, member.process.pid), ignore_errors=True)
        self._members = []

    def _hand_out(self) -> None:
        while self._queue:
            idle = next((m for m in self._members if m.key is None), None)
            if idle is None:
                if len(self._members) >= self._size:
                    return
                idle = self._start()
            idle.key, idle.arguments = self._queue.popleft()
            idle.started, idle.handed = False, time.monotonic()
            try:
                idle.connection.send((idle.key, idle.arguments))
            except OSError:
                pass   # it died: its sentinel says so, and the task is handed out again

    def _start(self) -> _Member:
        ours, theirs = self._context.Pipe()
        process = self._context.Process(target=_serve, args=(theirs, *self._start_arguments),
                                        name="autograder-grading")
        process.start()
        theirs.close()
        member = _Member(process, ours)
        self._members.append(member)
        return member

    def _receive(self, member: _Member) -> Iterator[tuple[str, object]]:
        """What ``member`` sent (up to its outcome), or, if it died, its burial."""
        try:
            while member.connection.poll():
                message = member.connection.recv()
                if message[0] == "started":
                    member.started = True
                    self._unstarted_deaths = 0
                else:
                    key, member.key = member.key, None
                    yield key, message[1]
                    return
            if member.process.is_alive():
                return
        except (EOFError, OSError):
            pass   # its end of the pipe closed: it died
        yield from self._bury(member)

    def _bury(self, member: _Member) -> Iterator[tuple[str, object]]:
        member.process.join(_STOP_SECONDS)
        if member.process.exitcode is None:   # it closed its pipe, yet lives on: never trusted again
            member.process.kill()
            member.process.join()
        member.connection.close()
        shutil.rmtree(_own_folder(self._folder, member.process.pid), ignore_errors=True)
        self._members.remove(member)
        how = _how_it_ended(member.process.exitcode)
        if member.key is None:
            return
        if member.overdue:
            yield member.key, ProcessDeath(f"stopped after {self._task_seconds:g} s, long past the grading's own "
                                           "deadline: the grader never finished it (a fault of the grader's, not of "
                                           "this submission's code)", overdue=True)
            return
        if member.started:
            yield member.key, ProcessDeath(how)
            return
        # It died before it took its task (nothing of the submission ran): handed out again.
        self._queue.appendleft((member.key, member.arguments))
        self._unstarted_deaths += 1
        if self._unstarted_deaths > 3 * self._size:
            raise GradingProcessesFailed(f"the grading processes die before they grade anything ({how})")


def _how_it_ended(exitcode: int | None) -> str:
    if exitcode is not None and exitcode < 0:
        try:
            return f"killed by {signal.Signals(-exitcode).name}"
        except ValueError:
            return f"killed by signal {-exitcode}"
    return f"exit status {exitcode}"


# ------------------------------------------------------------------ one grading process
def _serve(connection, task: Callable, environment: dict, folder: str, batch: int) -> None:
    """The life of a grading process: take a task, say so, run it, send its outcome back."""
    _die_with_parent(batch)
    signal.signal(signal.SIGINT, signal.SIG_IGN)   # Ctrl-C stops the batch, which stops us
    signal.signal(signal.SIGTERM, _stop_cleanly)
    signal.signal(signal.SIGHUP, _stop_cleanly)
    os.environ.clear()
    os.environ.update(environment)
    own = _own_folder(folder, os.getpid())
    own.mkdir(mode=0o711, exist_ok=True)
    tempfile.tempdir = str(own)
    try:
        while True:
            try:
                message = connection.recv()
            except EOFError:
                return
            if message is None:
                return
            key, arguments = message
            try:
                connection.send(("started", key))
                try:
                    outcome = task(*arguments)
                except Exception as exc:  # noqa: BLE001 - the task's own failure is its outcome
                    outcome = {"error": f"the grader could not finish: {type(exc).__name__}: {exc}"}
                connection.send(("done", outcome))
            except BrokenPipeError:   # the batch is gone
                return
    finally:
        shutil.rmtree(own, ignore_errors=True)


def _own_folder(folder, pid: int) -> Path:
    """A grading process's temporary files (its gradings' files and sandboxes): removed by
    the process as it ends, or by the pool once it is dead (however it died)."""
    return Path(folder) / f"grading-{pid}"


def _die_with_parent(batch: int) -> None:
    """Get SIGTERM when the parent (the fork server, or the batch) dies, however it dies:
    the fork server ends with the batch, and the stop below removes this process's sandbox
    and files. Where the batch is already gone, stop at once."""
    if sys.platform.startswith("linux"):
        try:
            ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)
        except (OSError, AttributeError):
            pass
    if not _alive(batch):
        raise SystemExit(0)


def _stop_cleanly(signum, frame):
    """Unwind the grading (its sandbox's worker killed, its files removed), once and in bounded
    time: a second signal is ignored, and SIGALRM ends the process if the cleanup hangs."""
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    signal.signal(signal.SIGHUP, signal.SIG_IGN)
    signal.alarm(_STOP_SECONDS)
    raise SystemExit(128 + signum)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] not in ("Z", "X")   # a zombie is dead
    except (OSError, IndexError):
        return True


# ------------------------------------------------------------------ the batch process
def batch_process(run: Callable) -> Callable:
    """``run`` (a batch) with its temporary files in this process's :func:`batch_folder`
    (the folders of batches that died removed first) and stopped by SIGTERM as by Ctrl-C."""
    @functools.wraps(run)
    def batch(*args, **kwargs):
        with temporary_files_in_batch_folder(), stopped_like_ctrl_c():
            return run(*args, **kwargs)

    return batch


@contextmanager
def stopped_like_ctrl_c() -> Iterator[None]:
    """While the block runs (in the main thread), SIGTERM and SIGHUP raise KeyboardInterrupt,
    as Ctrl-C does: the gradings are stopped and the batch ends as after Ctrl-C, with every
    finished grading kept. A handler the program installed itself is left alone."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {}
    for signum in (signal.SIGTERM, signal.SIGHUP):
        if signal.getsignal(signum) is signal.SIG_DFL:
            previous[signum] = signal.signal(signum, _interrupt)
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


def _interrupt(signum, frame):
    raise KeyboardInterrupt(f"stopped by {signal.Signals(signum).name}")


@contextmanager
def temporary_files_in_batch_folder() -> Iterator[Path]:
    """While the block runs, this process's temporary files go to its :func:`batch_folder`
    (after the folders of batches that died are removed)."""
    folder = batch_folder()
    remove_dead_batch_folders(folder.parent)
    with _temporary_files_in(folder):
        yield folder


@contextmanager
def _temporary_files_in(folder: Path) -> Iterator[Path]:
    previous = tempfile.tempdir
    tempfile.tempdir = str(folder)
    try:
        yield folder
    finally:
        if tempfile.tempdir == str(folder):
            tempfile.tempdir = previous


def batch_folder() -> Path:
    """This process's folder for a batch's temporary files (created at the first call,
    removed when the process exits): ``autograder-batch-<pid>-<random>`` in the system's
    temporary folder, holding ``owner.lock``, locked for the process's whole life."""
    global _folder
    if _folder is None:
        system = Path(tempfile.gettempdir())
        remove_dead_batch_folders(system)
        folder = Path(tempfile.mkdtemp(prefix=f"{FOLDER_PREFIX}{os.getpid()}-", dir=system))
        folder.chmod(0o711)   # as the system's: a worker may pass through to its scratch
        # Not inherited (the lock is this process's alone), nobody else's to open and lock,
        # and under its name only once locked: a batch sweeping meanwhile never takes it.
        locking = folder / f"{_OWNER}.new"
        owner = os.open(locking, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, 0o600)
        fcntl.flock(owner, fcntl.LOCK_EX)
        os.rename(locking, folder / _OWNER)
        _OWNER_FILES.append(owner)
        # After multiprocessing's own files (which may be in the folder) are removed at exit.
        util.Finalize(None, shutil.rmtree, args=(str(folder),), kwargs={"ignore_errors": True},
                      exitpriority=-200)
        _folder = folder
    return _folder


_OWNER_FILES: list[int] = []   # kept open (and locked) until the process ends


def remove_dead_batch_folders(system: Path) -> list[Path]:
    """Remove the batch folders, in ``system`` (the system's temporary folder), of batch
    processes that are gone (their owner lock is free); never a live batch's, nor another
    user's. Returns those removed."""
    removed = []
    for folder in system.glob(FOLDER_PREFIX + "*"):
        try:
            if (folder == _folder or folder.is_symlink() or not folder.is_dir()
                    or folder.stat().st_uid != os.getuid()):
                continue
            owner = os.open(folder / _OWNER, os.O_RDONLY | os.O_NOFOLLOW)
        except FileNotFoundError:   # its owner was killed before it locked it, or is locking it now
            try:
                if time.time() - folder.stat().st_mtime > _ORPHAN_SECONDS:
                    shutil.rmtree(folder, ignore_errors=True)
                    removed.append(folder)
            except OSError:
                pass
            continue
        except OSError:
            continue
        try:
            fcntl.flock(owner, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            continue   # its batch is alive
        else:
            shutil.rmtree(folder, ignore_errors=True)
            removed.append(folder)
        finally:
            os.close(owner)
    return removed
