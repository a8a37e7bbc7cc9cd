"""The grader's side of the sandbox: one worker process per submission.

:class:`Sandbox` starts ``worker.py`` in a scratch directory with a scrubbed
environment and resource limits, sends it one call at a time, and turns whatever
happens -- a value, an exception, a hang, a crash, garbage on the pipe -- into a
:class:`CallOutcome`. It never raises because of what the student's code did.
A worker that hangs or dies is killed with its whole process group and started
again for the next call.

Nothing the worker sends is trusted: every reply must carry the id of the
request it answers (a stray frame fails the call that produced it), call
durations are measured here, and a worker that reports a suspect state after a
call (threads or children alive, descriptors exhausted) is replaced before the
next one. Time is billed against budgets per exercise and per submission
(:meth:`Sandbox.start_exercise`); restarts are billed and capped per exercise.
"""

from __future__ import annotations

import fcntl
import json
import logging
import os
import secrets
import select
import shutil
import signal
import stat
import struct
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path
from typing import Any, Callable

from . import confine
from .submission import copy_regular_files

LENGTH = struct.Struct(">Q")
_WORKER_FILES = ("worker.py", "transport.py")

FAILURE_KINDS = {
    "timeout", "crashed", "exception", "not_implemented", "missing_function",
    "missing_module", "import_error", "memory", "recursion", "result_type",
    "forbidden_call", "output_too_large", "protocol", "grader_error", "budget",
}
# What a worker may say about its own call; the rest only the grader decides.
WORKER_KINDS = FAILURE_KINDS - {"timeout", "crashed", "grader_error", "budget"}


@dataclass(frozen=True)
class Limits:
    """Per-submission limits of the worker process."""

    call_timeout: float = 10.0           # wall seconds per call, unless a check says otherwise
    import_timeout: float = 20.0         # wall seconds to import one student module
    address_space: int = 6 * 2**30       # bytes of virtual memory, per process
    memory: int = 6 * 2**30              # bytes for the worker and all its children (cgroup, where available)
    scratch_bytes: int = 256 * 2**20     # writable scratch, and again /tmp (tmpfs, namespaced levels)
    file_size: int = 64 * 2**20          # bytes in any file written, printed output included
    cpu_total: int = 1800                # CPU seconds over the worker's life
    extra_processes: int = 64            # processes/threads beyond those the user already has
    max_result_bytes: int = 256 * 2**20  # largest result frame accepted
    max_output_chars: int = 4000         # captured stdout/stderr kept per call
    startup_timeout: float = 60.0        # for the worker to import NumPy/OpenCV (not billed)
    timeouts_per_function: int = 2       # after this many timeouts a function is not called again
    exercise_budget: float = 60.0        # student seconds per exercise (calls, timeouts, restarts)
    submission_budget: float = 480.0     # student seconds per submission (under a Gradescope timeout of 10 min)
    max_restarts: int = 12               # worker restarts per exercise (each billed its start-up)
    threads: int | None = None           # OpenCV's threads in the worker (None: OpenCV's own, one per core)

    def shared_by(self, lanes: int) -> "Limits":
        """These limits for each of ``lanes`` workers grading one submission side by side
        (:func:`autograder.runner.grade`): the memory of all its processes together, and the
        replies the grader may be holding at once, stay within :attr:`memory` and
        :attr:`max_result_bytes`; the workers share the cores out."""
        if lanes <= 1:
            return self
        return replace(self, memory=self.memory // lanes, max_result_bytes=self.max_result_bytes // lanes,
                       threads=cores_each(lanes))

    def worker_json(self, processes: int | None) -> str:
        return json.dumps({
            "address_space": self.address_space,
            "file_size": self.file_size,
            "cpu_total": self.cpu_total,
            "processes": processes,
            "threads": self.threads,
        })


def usable_cores() -> int:
    """The cores this process may run on (its CPU affinity where the platform says)."""
    try:
        return len(os.sched_getaffinity(0)) or 1
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def cores_each(workers: int) -> int:
    """Threads each of ``workers`` processes running side by side may use: more than
    one per core would only make them take turns (and evict each other's caches)."""
    return max(1, usable_cores() // max(1, workers))


PIPE_BYTES = 1 << 20  # pipe capacity asked for: an image crosses in a few writes, not hundreds


def _distrust_store() -> None:
    """A worker that runs as the grader's user (``process-group``) can read the store of
    ground truth and recorded examples, key included, and write it: its key is revoked
    (:func:`autograder.cache.revoke`) before the worker runs student code and after it
    stopped, so nothing it saw or wrote is trusted by a later grading."""
    from . import cache  # with NumPy: imported only here, once the worker is on its way

    cache.revoke()


def _ends_with_this_thread(command: list[str]) -> list[str]:
    """``command`` started so that the kernel kills it (SIGKILL) when the thread starting it
    ends: a grader killed with no chance to stop its worker (``kill -9``, the OOM killer, a
    batch's grading process) leaves no worker running student code. Linux's parent-death
    signal, set by ``setpriv``, is kept across the wrappers' ``exec``; ``unshare
    --kill-child`` passes it on to the namespace, whose end ends every process in it. The
    thread is the grader's main one, or a lane's, which outlives its worker's use."""
    setpriv = _pdeathsig_setpriv()
    return [setpriv, "--pdeathsig", "KILL", "--", *command] if setpriv else command


@lru_cache(maxsize=1)
def _pdeathsig_setpriv() -> str | None:
    """``setpriv`` where it sets the parent-death signal (Linux, util-linux 2.33 or later)."""
    setpriv = shutil.which("setpriv") if sys.platform.startswith("linux") else None
    if setpriv is None:
        return None
    try:
        usage = subprocess.run([setpriv, "--help"], capture_output=True, text=True, timeout=10).stdout
    except (OSError, subprocess.SubprocessError):
        return None
    return setpriv if "--pdeathsig" in usage else None


def _widen_pipe(fd: int) -> None:
    """Enlarge a pipe's buffer (Linux; best effort: the default 64 KiB still works).

    With 64 KiB, a megapixel image needs some fifty wake-ups of each process, and
    on a busy machine every one waits for a time slice."""
    setsize = getattr(fcntl, "F_SETPIPE_SZ", 1031) if sys.platform.startswith("linux") else None
    if setsize is None:
        return
    for size in (PIPE_BYTES, PIPE_BYTES // 4):
        try:
            fcntl.fcntl(fd, setsize, size)
            return
        except OSError:
            continue


# Workers alive in this process, so reaping escaped daemons never touches a worker.
_LIVE_WORKERS: set[int] = set()


class WorkerStartError(RuntimeError):
    """The worker process could not be started: a problem of the grader's installation."""


@dataclass
class CallOutcome:
    """What one call into the student's code produced.

    ``ok`` with ``value``, or not ``ok`` with a failure ``kind`` (one of
    :data:`FAILURE_KINDS`), a ``message`` for the student, and the student-only
    ``traceback``. ``output`` is what the call printed (truncated); ``modified``
    names the argument arrays the call changed in place.
    """

    ok: bool
    value: Any = None
    kind: str = ""
    message: str = ""
    traceback: str = ""
    output: str = ""
    seconds: float = 0.0
    modified: tuple[str, ...] = ()


def _scrubbed_environment(scratch: Path) -> dict[str, str]:
    one_thread = {k: "1" for k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS",
                                   "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS")}
    return {
        "PATH": "/usr/local/bin:/usr/bin:/bin",
        "HOME": str(scratch / "home"),
        "TMPDIR": str(scratch / "tmp"),
        "LANG": "C.UTF-8",
        "LC_ALL": "C.UTF-8",
        "PYTHONHASHSEED": "0",
        "PYTHONDONTWRITEBYTECODE": "1",
        "PYTHONIOENCODING": "utf-8",
        "MPLBACKEND": "Agg",
        **one_thread,
    }


class Sandbox:
    """Run functions of a submission in a separate, limited worker process.

    Parameters
    ----------
    submission_dir : path or None
        Folder holding the student's modules (``lab07_transformations.py`` ...).
        It is copied into the scratch directory; the original is never touched.
        None: the submission comes later (:meth:`admit`), so that the worker can be
        started (:meth:`start`) while the grader is still loading.
    limits : Limits

    Examples
    --------
    >>> with Sandbox("reference_solutions") as box:            # doctest: +SKIP
    ...     box.call("lab07_transformations", "translation_matrix", (1, 2)).value
    """

    def __init__(self, submission_dir, limits: Limits | None = None,
                 confinement: confine.Confinement | None = None):
        self.limits = limits or Limits()
        self.confinement = confinement or confine.detect()
        if self.confinement.level == "process-group":
            confine.become_subreaper()
        # One memory and task budget for the worker and everything it starts (its own
        # wrappers, and a thread per core for OpenCV's pool, come on top of the student's share).
        self.cgroup = confine.Cgroup.create(self.limits.memory,
                                            self.limits.extra_processes + 16 + (os.cpu_count() or 1))
        self._oom_kills = 0
        self._own_processes = 0
        # A private base (listable by the grader only) around a randomly named
        # scratch folder, so workers of other submissions cannot find this one.
        self._base = Path(tempfile.mkdtemp(prefix="autograder-"))
        self._base.chmod(0o711)
        self.scratch = self._base / secrets.token_hex(8)
        self.scratch.mkdir()
        self._source = None if submission_dir is None else Path(submission_dir)
        self.submission_dir = self.scratch / "submission"
        self.output_path = self.scratch / "out" / "output.txt"
        self._lay_out_scratch()
        self.proc: subprocess.Popen | None = None
        self._ready = False     # the worker said it is ready
        self._closed = False
        self._interrupted = False  # see interrupt(): no worker is started again
        self._request_fd = self._response_fd = -1
        self._imported: set[str] = set()
        self._import_failures: dict[str, CallOutcome] = {}
        self.student_seconds = 0.0
        self.billed_spans: list[tuple[float, float]] = []  # (start, end) of each billed time, perf_counter
        self.restarts = 0       # in the current exercise
        self._started = False   # the first start is not a restart
        self._restart_refused = False
        self._budget: float | None = None
        self._shared_budget: tuple[Callable[[], float], float] | None = None
        self._request_id = secrets.randbits(48)
        self.shared: dict = {}  # values checks share within one grading (see Trial.shared)
        self._timeouts: dict[tuple[str, str], int] = {}

    # The worker may write only in these folders of its scratch (when namespaces
    # allow): its copy of the submission and of the worker code stay intact.
    WRITABLE = ("home", "tmp", "work", "out")

    def _lay_out_scratch(self):
        """(Re)create the scratch folder: fresh copies of the submission and the worker code."""
        self.scratch.mkdir(parents=True, exist_ok=True)
        for name in ("submission", "worker", *self.WRITABLE):
            shutil.rmtree(self.scratch / name, ignore_errors=True)
        self.submission_dir.mkdir()
        self._copy_submission()
        (self.scratch / "worker").mkdir()
        here = Path(__file__).parent
        for name in _WORKER_FILES:
            shutil.copy(here / name, self.scratch / "worker" / name)
        for name in self.WRITABLE:
            (self.scratch / name).mkdir()
        self.output_path.touch()  # bound into the worker's view: it must exist
        self.confinement.prepare_scratch(self.scratch, private=("worker",))

    def _copy_submission(self):
        if self._source is None:
            return
        refused = copy_regular_files(self._source, self.submission_dir, suffixes=(".py",))
        if refused:
            logging.getLogger("autograder").warning("not copied into the sandbox: %s", refused)

    def admit(self, submission_dir) -> None:
        """Copy in the submission of a sandbox made without one, before its first request.

        The worker, if already started, has run nothing of the submission: its
        folder, empty until now, is part of the worker's view from the start."""
        if self._source is not None or self._started:
            raise RuntimeError("a sandbox admits one submission, before its first request")
        self._source = Path(submission_dir)
        self._copy_submission()
        self.confinement.prepare_scratch(self.scratch, private=("worker",))

    # ------------------------------------------------------------ lifecycle
    def __enter__(self):
        return self

    def start(self) -> None:
        """Start the worker and return at once: it imports NumPy and OpenCV while the
        grader goes on; the first request waits until it is ready (never billed).

        Raises
        ------
        WorkerStartError
            If the process cannot be started at all.
        """
        if self.proc is None and not (self._closed or self._interrupted):
            self._spawn_worker()

    def interrupt(self) -> None:
        """Abandon this sandbox from another thread: its worker's processes are killed and
        no worker is started again. The thread using it sees its call fail and releases
        what it holds itself (its pipes are never closed under it), then :meth:`close`."""
        self._interrupted = True
        proc = self.proc
        if proc is not None:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        if self.cgroup is not None:
            self.cgroup.kill()

    def ready(self) -> bool:
        """Start the worker if it is not running and wait until it is ready (it has
        imported NumPy and OpenCV at this confinement level); False if it could not
        start (it is stopped then, and the reason logged)."""
        if self._closed or self._interrupted:
            return False
        if self.proc is not None and self._ready:
            return True
        try:
            self._start_worker()
        except WorkerStartError:
            return False
        return True

    def __exit__(self, *exc):
        self.close()

    def close(self):
        """Stop the worker and everything it started, then delete the scratch directory."""
        if self._closed:
            return
        self._closed = True
        self._stop_worker(restarting=False)
        if self.cgroup is not None:
            self.cgroup.remove()
        shutil.rmtree(self._base, ignore_errors=True)

    def _start_worker(self):
        if self.proc is None:
            self._spawn_worker()
        self._await_ready()

    def _spawn_worker(self):
        try:
            log = open(self._base / "worker.log", "ab")
        except OSError as exc:
            raise WorkerStartError(f"cannot write the worker log: {exc}") from None
        request_r, request_w = os.pipe()
        response_r, response_w = os.pipe()
        for fd in (request_w, response_r):
            _widen_pipe(fd)
        # The worker's own process budget: its cgroup's where there is one and the worker cannot
        # see the cgroup file system (the namespaced levels). RLIMIT_NPROC, the fallback, counts
        # every process of the user: workers side by side (a batch's gradings, lanes) share it,
        # and one submission's fork bomb could starve the other. At the process-group level the
        # worker is the grader's user and could leave a cgroup the grader made: it keeps both.
        processes = None
        if self.cgroup is None or not self.confinement.hides_files:
            uid = self.confinement.uid if self.confinement.uid is not None else os.getuid()
            tasks = confine.count_tasks(uid)  # None where they cannot be counted (macOS): no limit
            processes = None if tasks is None else tasks + self.limits.extra_processes
        view = confine.View(scratch=self.scratch, read_only=(self.submission_dir, self.scratch / "worker"),
                            files=(self.output_path,), size=self.limits.scratch_bytes)
        command = self.confinement.wrap(
            [confine.INTERPRETER, "-I", "-B", str(self.scratch / "worker" / "worker.py"),
             str(request_r), str(response_w), str(self.submission_dir),
             str(self.output_path), self.limits.worker_json(processes)],
            view=view, hold=self._base / "hold")
        if self.cgroup is not None:
            command = self.cgroup.wrap(command)
        command = _ends_with_this_thread(command)
        try:
            self.proc = subprocess.Popen(
                command, pass_fds=(request_r, response_w), stdin=subprocess.DEVNULL,
                stdout=log, stderr=log, cwd=self.scratch / "work",
                env=_scrubbed_environment(self.scratch), start_new_session=True,
            )
        except OSError as exc:
            os.close(request_w)
            os.close(response_r)
            raise WorkerStartError(f"cannot start the worker: {exc}") from None
        finally:
            log.close()
            os.close(request_r)
            os.close(response_w)
        _LIVE_WORKERS.add(self.proc.pid)
        self._request_fd, self._response_fd = request_w, response_r
        if not self.confinement.hides_files:
            _distrust_store()  # before its first request: no student code has run yet
        self._imported = set()
        self._ready = False

    def _await_ready(self):
        # Wait for the worker's "ready" (it imports NumPy and OpenCV first), so that
        # start-up time is never billed to the student's first call.
        from . import transport  # with NumPy: not needed to start a worker, only to talk to it
        try:
            length, = LENGTH.unpack(self._read(LENGTH.size, time.monotonic() + self.limits.startup_timeout))
            ready = transport.decode(self._read(length, time.monotonic() + 5))
        except (TimeoutError, EOFError, transport.TransportError) as exc:
            # The log goes to the instructor's log, never into a message: it is no grader's word.
            log = (self._base / "worker.log").read_text(errors="replace")[-2000:]
            logging.getLogger("autograder").error("the grading worker did not start:\n%s", log)
            self._stop_worker()
            raise WorkerStartError(f"the grading worker did not start ({type(exc).__name__}); "
                                   "see the autograder's log") from None
        if ready != {"ok": True, "value": "ready", "seconds": 0.0}:
            self._stop_worker()
            raise WorkerStartError("the grading worker sent an unexpected greeting")
        self._ready = True
        # What the sandbox's own processes are (wrappers, PID 1, the worker): more after a call
        # means the submission left one running, whatever the worker says.
        self._own_processes = len(self.cgroup.processes()) if self.cgroup is not None else 0

    def _stop_worker(self, restarting: bool = True):
        if self.proc is None:
            return
        for fd in (self._request_fd, self._response_fd):
            try:
                os.close(fd)
            except OSError:
                pass
        if restarting:
            try:
                self.proc.wait(timeout=0.5)   # a healthy worker exits on EOF
            except subprocess.TimeoutExpired:
                pass
        # When closing, nothing the worker could still do matters: it is not left to
        # tear its interpreter down (a tenth of a second), it is killed with the rest.
        self._kill_process_group()
        if self.cgroup is not None:
            self.cgroup.kill()  # whatever left the process group (setsid) is still in the cgroup
        _LIVE_WORKERS.discard(self.proc.pid)
        if self.confinement.level == "process-group":
            confine.kill_adopted_orphans(keep=_LIVE_WORKERS)
            _distrust_store()  # now that nothing of it runs: what it wrote there is never read
            if restarting:
                self._lay_out_scratch()  # nothing stopped this worker from damaging it
        self.proc = None
        self._ready = False
        self._request_fd = self._response_fd = -1

    def _kill_process_group(self):
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        try:
            self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            pass

    # ------------------------------------------------------------ budgets
    def start_exercise(self, until: float | None) -> None:
        """A new exercise: stop calling once :attr:`student_seconds` reaches ``until``
        (None: no budget), and count its worker restarts afresh."""
        self._budget = until
        self.restarts = 0

    def _bill(self, seconds: float) -> None:
        """Bill ``seconds`` that just ended to the student."""
        self.student_seconds += seconds
        end = time.perf_counter()
        self.billed_spans.append((end - seconds, end))

    def share_budget(self, spent: Callable[[], float], limit: float) -> None:
        """Also stop calling once ``spent()`` (the seconds billed in this sandbox and the
        others it shares a submission's budget with) reaches ``limit``."""
        self._shared_budget = (spent, limit)

    def remaining(self) -> float:
        left = float("inf") if self._budget is None else self._budget - self.student_seconds
        if self._shared_budget is not None:
            spent, limit = self._shared_budget
            left = min(left, limit - spent())
        return left

    def _over_budget(self, what: str) -> CallOutcome:
        return CallOutcome(ok=False, kind="budget",
                           message=f"{what} was not run: time budget exhausted")

    # ------------------------------------------------------------ public API
    def import_module(self, module: str, timeout: float | None = None) -> CallOutcome:
        """Import a student module in the worker (once); failures are remembered."""
        if module in self._import_failures:
            return self._import_failures[module]
        if module in self._imported and self.proc is not None:
            return CallOutcome(ok=True)
        what = f"importing {module}.py"
        timeout = timeout or self.limits.import_timeout
        if self.remaining() <= 0:
            return self._over_budget(what)
        outcome = self._billed({"op": "import", "module": module}, timeout, what)
        if outcome.ok:
            self._imported.add(module)
        elif outcome.kind not in ("budget", "grader_error") and not self._restart_refused:
            self._import_failures[module] = outcome  # the module's own failure, not the sandbox's
        return outcome

    def _billed(self, request: dict, timeout: float, what: str) -> CallOutcome:
        """:meth:`_request` within the budget; its time (a timeout's in full) is billed."""
        clipped = timeout > self.remaining()
        outcome = self._request(request, min(timeout, self.remaining()), what)
        self._bill(outcome.seconds)
        if clipped and outcome.kind == "timeout":
            outcome.kind, outcome.message = "budget", f"{what} was stopped: time budget exhausted"
        return outcome

    def call(self, module: str, function: str, args=(), kwargs=None, *,
             timeout: float | None = None, forbid=()) -> CallOutcome:
        """Call ``module.function(*args, **kwargs)`` in the worker.

        ``forbid`` lists library functions (``"cv2.findHomography"``) that the
        call must not use; using one makes the outcome a ``forbidden_call``.
        """
        imported = self.import_module(module)
        if not imported.ok:
            return imported
        # A function that hung repeatedly would only cost every later check its full timeout.
        if self._timeouts.get((module, function), 0) >= self.limits.timeouts_per_function:
            return CallOutcome(ok=False, kind="timeout",
                               message=f"{function}() timed out {self.limits.timeouts_per_function} "
                                       "times already; not called again")
        timeout = timeout or self.limits.call_timeout
        if self.remaining() <= 0:
            return self._over_budget(f"{function}()")
        request = {"op": "call", "module": module, "function": function,
                   "args": list(args), "kwargs": dict(kwargs or {}),
                   "forbid": list(forbid), "cpu_seconds": timeout + 1.0}
        outcome = self._billed(request, timeout, what=f"{function}()")
        if outcome.kind == "timeout":
            self._timeouts[(module, function)] = self._timeouts.get((module, function), 0) + 1
        return outcome

    # ------------------------------------------------------------ plumbing
    def _restart(self) -> CallOutcome | None:
        """Start the worker; a restart is billed its start-up time and capped."""
        if self._closed or self._interrupted:
            return CallOutcome(ok=False, kind="grader_error", message="grading was stopped")
        restart = self._started
        self._restart_refused = restart and self.restarts >= self.limits.max_restarts
        if self._restart_refused:
            return CallOutcome(ok=False, kind="crashed",
                               message=f"the worker was restarted {self.limits.max_restarts} times in this "
                                       "exercise after crashes, hangs or suspect states; not started again")
        started = time.perf_counter()
        try:
            self._start_worker()
        except WorkerStartError as exc:
            return CallOutcome(ok=False, kind="grader_error", message=str(exc))
        self._started = True
        if restart:
            self.restarts += 1
            self._bill(time.perf_counter() - started)
        return None

    def _request(self, request: dict, timeout: float, what: str) -> CallOutcome:
        from . import transport  # with NumPy: not needed to start a worker, only to talk to it
        if self.proc is None or not self._ready:
            failed = self._restart()
            if failed is not None:
                return failed
            if request["op"] == "call":
                imported = self.import_module(request["module"])
                if not imported.ok:
                    return imported
                timeout = min(timeout, self.remaining())
                if timeout <= 0:
                    return self._over_budget(what)
        self._started = True  # (a worker made ready before this request is started too)
        self._request_id += 1
        request = {**request, "id": self._request_id}
        frame = transport.encode(request)
        start = time.perf_counter()
        deadline = time.monotonic() + timeout
        try:
            self._write(LENGTH.pack(len(frame)) + frame, deadline)
            length, = LENGTH.unpack(self._read(LENGTH.size, deadline))
            if length > self.limits.max_result_bytes:
                return self._abandon(CallOutcome(
                    ok=False, kind="result_type", seconds=time.perf_counter() - start,
                    message=f"{what} returned more than {self.limits.max_result_bytes // 2**20} MiB"))
            head = self._read(min(length, transport.PREFIX.size), deadline)
            if len(head) == transport.PREFIX.size:  # refuse an oversized header before reading it
                _, header_length = transport.PREFIX.unpack(head)
                if header_length > transport.MAX_HEADER_BYTES:
                    raise transport.TransportError(f"frame header larger than {transport.MAX_HEADER_BYTES} bytes")
            frame = head + self._read(length - len(head), deadline)
            reply = transport.decode(frame, max_bytes=self.limits.max_result_bytes)
            seconds = time.perf_counter() - start  # measured here: the worker's word is not taken
            if self._pending_reply():
                raise transport.TransportError("more than one reply to one call")
        except TimeoutError:
            return self._abandon(CallOutcome(
                ok=False, kind="timeout", seconds=time.perf_counter() - start,
                message=f"{what} did not finish within {timeout:g} s (an infinite loop, or far too slow?)"))
        except (EOFError, BrokenPipeError, ConnectionError):
            return self._abandon(self._crash_outcome(what, time.perf_counter() - start))
        except transport.TransportError as exc:
            return self._abandon(CallOutcome(
                ok=False, kind="protocol", seconds=time.perf_counter() - start,
                message=f"{what}: the worker sent back something that is not a valid result ({exc})"))
        outcome = self._outcome_from_reply(reply, what, request["id"], seconds)
        if self.proc is not None:
            outcome.output = self._read_output()
            if type(reply.get("suspect")) is str or self._processes_left():
                self._stop_worker()  # the next call gets a clean worker
        return outcome

    def _processes_left(self) -> bool:
        return self.cgroup is not None and len(self.cgroup.processes()) > self._own_processes

    def _pending_reply(self) -> bool:
        readable, _, _ = select.select([self._response_fd], [], [], 0)
        return bool(readable)

    def _outcome_from_reply(self, reply, what, request_id, seconds) -> CallOutcome:
        if type(reply) is not dict or type(reply.get("ok")) is not bool:
            return self._abandon(CallOutcome(ok=False, kind="protocol", seconds=seconds,
                                             message=f"{what}: malformed reply from the worker"))
        if reply.get("id") != request_id:
            return self._abandon(CallOutcome(
                ok=False, kind="protocol", seconds=seconds,
                message=f"{what}: the worker's reply does not answer this call (a stray reply "
                        "written by a thread or process the submission left behind?)"))
        modified = reply.get("modified")
        modified = tuple(name[:100] for name in modified[:20] if type(name) is str) \
            if type(modified) is list else ()
        if reply["ok"]:
            return CallOutcome(ok=True, value=reply.get("value"), seconds=seconds, modified=modified)
        kind = reply.get("kind") if reply.get("kind") in WORKER_KINDS else "exception"
        message = reply.get("message") if type(reply.get("message")) is str else ""
        tb = reply.get("traceback") if type(reply.get("traceback")) is str else ""
        if kind == "result_type" and message.startswith("returned"):
            message = f"{what} {message}"
        return CallOutcome(ok=False, kind=kind, message=message[:2000], traceback=tb[-4000:],
                           seconds=seconds)

    def _abandon(self, outcome: CallOutcome) -> CallOutcome:
        """After a hang, crash or garbage: kill the worker; the next call starts a new one."""
        outcome.output = self._read_output()
        self._stop_worker()
        return outcome

    def _crash_outcome(self, what, seconds) -> CallOutcome:
        try:
            code = self.confinement.exit_signal(self.proc.wait(timeout=2))
        except subprocess.TimeoutExpired:
            code = None
        oom_kills = self.cgroup.oom_kills() if self.cgroup is not None else 0
        if oom_kills > self._oom_kills:
            self._oom_kills = oom_kills
            return CallOutcome(ok=False, kind="memory", seconds=seconds,
                               message=f"{what} ran out of memory (the submission's processes together "
                                       f"may use {self.limits.memory / 2**30:g} GiB)")
        if code is not None and code < 0:
            signame = signal.Signals(-code).name if -code in signal.valid_signals() else str(-code)
            reasons = {
                "SIGXCPU": "used up its CPU time limit",
                "SIGXFSZ": f"wrote more than {self.limits.file_size // 2**20} MB (printed output counts)",
                "SIGSEGV": "crashed with a segmentation fault",
                "SIGKILL": "was killed (out of memory?)",
                "SIGABRT": "aborted",
            }
            kind = "output_too_large" if signame == "SIGXFSZ" else "crashed"
            message = f"{what} {reasons.get(signame, f'was stopped by {signame}')}"
        else:
            kind = "crashed"
            message = (f"{what} ended the worker process (exit code {code}); "
                       "do not call os._exit() or kill processes")
        return CallOutcome(ok=False, kind=kind, message=message, seconds=seconds)

    def _write(self, data: bytes, deadline: float):
        view = memoryview(data)
        while view:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError
            _, writable, _ = select.select([], [self._request_fd], [], remaining)
            if writable:
                view = view[os.write(self._request_fd, view[:PIPE_BYTES]):]

    def _read(self, n: int, deadline: float) -> bytes:
        chunks = []
        while n:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError
            readable, _, _ = select.select([self._response_fd], [], [], remaining)
            if not readable:
                continue
            chunk = os.read(self._response_fd, min(n, 1 << 20))
            if not chunk:
                raise EOFError
            chunks.append(chunk)
            n -= len(chunk)
        return b"".join(chunks)

    def _read_output(self) -> str:
        limit = self.limits.max_output_chars
        try:  # never follow a link the student put there (the grader may be root)
            fd = os.open(self.output_path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
        except OSError:
            return ""
        with os.fdopen(fd, "rb") as f:
            info = os.fstat(f.fileno())
            if not stat.S_ISREG(info.st_mode):
                return ""
            size = info.st_size
            head = f.read(limit)
        text = head.decode("utf-8", errors="replace")
        if size > limit:
            text += f"\n... ({size - limit} more bytes of output not shown)"
        return text
