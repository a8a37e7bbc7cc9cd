"""The grader's side of the sandbox: one worker process per submission.

:class:`Sandbox` starts ``worker.py`` in a scratch directory with a scrubbed
environment and resource limits (at the namespaced levels forked from a warm template,
:mod:`autograder.sandbox.template`), sends it one call at a time, and turns whatever
happens -- a value, an exception, a hang, a crash, garbage on the pipe -- into a
:class:`CallOutcome`. It never raises because of what the student's code did.
A worker that hangs or dies is killed with its whole process group and started
again for the next call.

Nothing the worker sends is trusted: every reply must carry the id of the
request it answers (a stray frame fails the call that produced it), call
durations are measured here, and a worker that reports a suspect state after a
call (threads or children alive, descriptors exhausted) is replaced before the
next one. Time is billed against a budget per exercise (:meth:`Sandbox.start_exercise`),
within the submission's wall-clock deadline (:meth:`Sandbox.set_deadline`); restarts
are billed and capped per exercise.

Why a request failed is decided from what the grader measures, never from what the
worker says (:meth:`Sandbox._fault`, :mod:`autograder.sandbox.evidence`): the cgroup's
out-of-memory kills and limit hits, the memory and processes of the worker's tree
(watched while a request runs where no cgroup enforces them), whether the worker
still holds the grader's pipe, how it ended. What a request leaves running is gone
before the next one.
"""

from __future__ import annotations

import fcntl
import json
import logging
import os
import re
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

from . import confine, evidence, template
from .template import TemplateError
from .files import copy_regular_files

LENGTH = struct.Struct(">Q")
_WORKER_FILES = ("worker.py", "transport.py", "beginner.py")
STACK_NAME = "stack.txt"   # worker.STACK_FILE, beside the output file
STACK_MARGIN = 0.25        # s before the deadline the worker writes where a call still running is
STACK_BYTES = 16_384       # read of it at most
# What one call may send back grows with what it is given: ANSWER_RATIO times the bytes of its arrays, and
# ANSWER_FLOOR whatever it is given (a pattern of n_bits x width from two numbers), within Limits.max_result_bytes.
# The grader holds what comes back while it judges it: a reply of 120 MiB to a 3 x 3 question, kept for each of
# a property's calls, would make the grader swell to gigabytes (hostile round of 2026-12-07).
ANSWER_RATIO = 64
ANSWER_FLOOR = 16 * 2**20
_FRAME = re.compile(r'^\s*File "([^"\n]{1,400})", line (\d{1,7}) in ([A-Za-z_][A-Za-z0-9_<>]{0,80})\s*$')


def where_stopped(text: str, module_files: set[str]) -> str:
    """Where a call stopped for its time was, in words, from a faulthandler dump (most recent call first):
    the innermost frame of a file of the submission (``module_files``, names in its folder) and, when the call
    was further in, the library function it was in. "" when no frame of the submission is found."""
    for block in text.split("\n\n")[:8]:
        frames = [m.groups() for m in map(_FRAME.match, block.splitlines()[:120]) if m]
        own = next((k for k, (path, _, _) in enumerate(frames)
                    if os.path.basename(path) in module_files and os.path.basename(os.path.dirname(path)) == "submission"),
                   None)
        if own is None:
            continue
        path, line, function = frames[own]
        said = f": when it was stopped, it was at line {line} of your `{function}` ({os.path.basename(path)})"
        if own == 0:
            return said
        inner_path, _, inner = frames[0]
        parts = inner_path.replace("\\", "/").split("/")
        library = next((name for key, name in (("numpy", "NumPy's"), ("cv2", "OpenCV's"), ("scipy", "SciPy's"),
                                                ("skimage", "scikit-image's")) if key in parts), "")
        said += f", inside {library + ' ' if library else ''}`{inner}`"
        if library == "NumPy's" and "linalg" in parts:
            said += (" (NumPy's linear algebra can run for ever on a matrix holding inf or NaN: is something divided "
                     "by 0 before it?)")
        return said
    return ""

def array_bytes(value, depth: int = 0) -> int:
    """The bytes of the arrays in ``value`` (arguments or answers: arrays, numbers, and lists, tuples and dicts of
    them). Numbers outside arrays are few (the transport bounds them): a long list whose first item is a number is not
    walked, so a list of a million numbers costs nothing to measure."""
    if depth < 4 and isinstance(value, dict):
        value = list(value.values())
    if depth < 4 and isinstance(value, (list, tuple)):
        numbers = len(value) > 16 and isinstance(value[0], (int, float, complex, str, bool))
        return 0 if numbers else sum(array_bytes(item, depth + 1) for item in value)
    size = getattr(value, "nbytes", 0)   # (an array: NumPy is not imported here to start a worker)
    return size if type(size) is int else 0


def answer_cap(largest: int, *given) -> int:
    """The most bytes a reply to a call given ``given`` (its arguments) may hold: :data:`ANSWER_RATIO` times their
    arrays' bytes, at least :data:`ANSWER_FLOOR`, at most ``largest``."""
    return int(min(largest, max(ANSWER_FLOOR, ANSWER_RATIO * sum(array_bytes(g) for g in given))))


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
    memory: int = 6 * 2**30              # bytes for the worker and all its children (see Sandbox.memory)
    scratch_bytes: int = 256 * 2**20     # writable scratch, and again /tmp (tmpfs, namespaced levels)
    file_size: int = 64 * 2**20          # bytes in any file written, printed output included
    cpu_total: int = 1800                # CPU seconds over the worker's life
    extra_processes: int = 64            # processes/threads beyond those the user already has
    max_result_bytes: int = 256 * 2**20  # largest result frame accepted
    max_result_elements: int | None = None  # most numbers a result's arrays may hold (None: any)
    max_output_chars: int = 4000         # captured stdout/stderr kept per call
    startup_timeout: float = 60.0        # for the worker to import NumPy/OpenCV (not billed)
    timeouts_per_function: int = 2       # after this many timeouts (or memory stops) a function is not called again
    exercise_budget: float = 60.0        # student seconds per exercise (calls, timeouts, restarts)
    submission_budget: float = 240.0     # wall seconds for grading the whole submission, whatever runs
    lab_budget: float | None = None      # wall seconds per lab selected (None: a third of submission_budget)
    max_restarts: int = 12               # worker restarts per exercise (each billed its start-up)
    threads: int | None = None           # OpenCV's threads in the worker (None: OpenCV's own, one per core)

    def budget_for(self, exercises) -> float:
        """Wall seconds for grading ``exercises`` (those selected; each has a ``lab`` with a
        ``key``): :attr:`lab_budget` for each lab they come from, at most
        :attr:`submission_budget`, never less than one exercise's :attr:`exercise_budget`.

        A grading of one lab ends within that lab's time, not the whole submission's: a
        submission whose every call sleeps just under its timeout costs a lab-7 grading 80 s
        by default, not 240. A third of the submission's time per lab is what a lab has on
        average when a whole submission (six labs) is graded in two lanes."""
        per_lab = self.submission_budget / 3 if self.lab_budget is None else self.lab_budget
        labs = {exercise.lab.key for exercise in exercises}
        return min(self.submission_budget, max(self.exercise_budget, per_lab * max(1, len(labs))))

    def shared_by(self, lanes: int) -> "Limits":
        """These limits for each of ``lanes`` workers grading one submission side by side
        (:func:`autograder.engine.runner.grade`): each worker has a fixed share of :attr:`memory` (and
        of the machine's, :func:`memory_for_workers`) that no other can borrow, so one lane's
        memory bomb leaves the others theirs; the replies the grader may be holding at once
        stay within :attr:`max_result_bytes`; the workers share the cores out."""
        if lanes <= 1:
            return self
        memory = min(self.memory, memory_for_workers() or self.memory)
        return replace(self, memory=memory // lanes, max_result_bytes=self.max_result_bytes // lanes,
                       threads=cores_each(lanes))

    def worker_json(self, processes: int | None) -> str:
        return json.dumps({
            "address_space": self.address_space,
            "file_size": self.file_size,
            "cpu_total": self.cpu_total,
            "processes": processes,
            "threads": self.threads,
            "max_result_bytes": self.max_result_bytes,
            "max_result_elements": self.max_result_elements,
        })


@lru_cache(maxsize=1)
def memory_for_workers() -> int | None:
    """Bytes the workers of this process may hold together: three quarters of what this
    process's cgroup (each of its ancestors), or else the machine, has -- the rest is the
    grader's, and the page cache's that keeps the libraries' code in memory. None where
    unknown (no ``/proc``).

    A worker's :attr:`Limits.memory` larger than this would not be a limit: the machine
    would run out first, and its OOM killer, or thrashing, would hit any process, another
    lane's worker or the grader included."""
    meminfo = evidence._read("/proc/meminfo") or ""
    total = next((int(line.split()[1]) * 1024 for line in meminfo.splitlines()
                  if line.startswith("MemTotal:")), None)
    for limit in _cgroup_memory_limits():
        total = limit if total is None else min(total, limit)
    return None if total is None else total * 3 // 4


def _cgroup_memory_limits() -> list[int]:
    """The memory limits of this process's cgroup and its ancestors (v2 ``memory.max``,
    v1 ``memory.limit_in_bytes``), those that are set."""
    limits = []
    for line in (evidence._read("/proc/self/cgroup") or "").splitlines():
        _, controllers, path = line.split(":", 2)
        if controllers == "":
            root, name = Path("/sys/fs/cgroup"), "memory.max"
        elif "memory" in controllers.split(","):
            root, name = Path("/sys/fs/cgroup/memory"), "memory.limit_in_bytes"
        else:
            continue
        folder = root / path.lstrip("/")
        while True:
            value = (evidence._read(str(folder / name)) or "").strip()
            if value.isdigit() and int(value) < 2**60:  # "max", or v1's "unlimited" (a huge number)
                limits.append(int(value))
            if folder == root or root not in folder.parents:
                break
            folder = folder.parent
    return limits


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
    (:func:`autograder.sandbox.cache.revoke`) before the worker runs student code and after it
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
    names the argument arrays the call changed in place, and ``changed`` holds them as the
    caller would after the call: ``(position or keyword, index in a list or None, array)``.
    """

    ok: bool
    value: Any = None
    kind: str = ""
    message: str = ""
    traceback: str = ""
    output: str = ""
    seconds: float = 0.0
    modified: tuple[str, ...] = ()
    changed: tuple = ()
    shared: str = ""   # the module-level array the value is (worker.module_array_returned), if any


def _changed_arrays(changed) -> tuple:
    """The worker's ``changed`` (see ``worker.changed_arrays``), kept only where well formed."""
    if type(changed) is not list or not changed:
        return ()
    import numpy as np   # only when an argument was changed: most replies never need it here

    return tuple((key, index, array) for key, index, array in
                 (item for item in changed[:20] if type(item) is list and len(item) == 3)
                 if type(key) in (int, str) and (index is None or type(index) is int)
                 and isinstance(array, np.ndarray) and array.dtype.kind in "biuf")


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


class _Stopped(Exception):
    """The grader stopped a request on evidence it measured (``reason``: "memory", "processes"
    or "pipe"), see :meth:`Sandbox._check_in`."""

    def __init__(self, reason: str):
        super().__init__(reason)
        self.reason = reason


@dataclass
class _Measures:
    """What the grader measured of the worker during one request: its cgroup's counters when
    the request began, and the most memory it saw the worker's processes hold."""

    oom_kills: int = 0
    limit_hits: int = 0
    peak: int = 0

    @classmethod
    def now(cls, cgroup) -> "_Measures":
        if cgroup is None:
            return cls()
        return cls(cgroup.oom_kills(), cgroup.memory_limit_hits())

    def oom_killed(self, cgroup) -> bool:
        """The kernel killed a process of the cgroup for its memory since the request began."""
        return cgroup is not None and cgroup.oom_kills() > self.oom_kills

    def pressed(self, cgroup, memory: int) -> bool:
        """The worker's processes reached their memory limit since the request began."""
        if cgroup is not None:
            return cgroup.memory_limit_hits() > self.limit_hits
        return self.peak >= memory * 9 // 10


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
        # The memory the worker and everything it starts may hold: enforced by the kernel in
        # its cgroup, else measured by the grader while a request runs (Sandbox._check_in).
        self.memory = min(self.limits.memory, memory_for_workers() or self.limits.memory)
        self.cgroup = self._new_cgroup()
        if self.cgroup is None:  # RLIMIT_NPROC bounds its processes: a budget no other worker shares
            self.confinement = self.confinement.with_own_user()
        self._own_processes = 0
        self._own_pids: set[int] = set()      # the sandbox's own processes (wrappers, PID 1, the worker)
        self._worker_pid: int | None = None   # the worker's process (host PID), once it is ready
        self._pidfd = -1
        self._spawned = 0                     # workers started so far
        self._worker_alive: Callable[[], bool] = lambda: False
        self._worker_pipes: tuple[tuple[int, int], ...] = ()  # (descriptor in the worker, pipe inode)
        self._watching = False  # a request runs: look at the worker while waiting (see _check_in)
        self._measured = _Measures()
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
        if self.confinement.level != "process-group":   # (it imports NumPy and OpenCV while the grader goes on)
            template.shared(confine.INTERPRETER, _scrubbed_environment(self.scratch))
        self.proc: subprocess.Popen | template.Forked | None = None
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
        self._stopped_by_grader = False   # nor one after the grader interrupted a request (see _request)
        self._restart_refused = False
        self._budget: float | None = None
        self._deadline: float | None = None  # time.monotonic() at which the submission's time is up
        self._request_id = secrets.randbits(48)
        self.shared: dict = {}  # values checks share within one grading (see Trial.shared)
        self._companion: Sandbox | None = None   # see companion()
        self._strikes: dict[tuple[str, str, str], int] = {}  # (module, function, "timeout" or "memory")
        self._memory_floor = 0   # what the worker holds once ready and its modules imported (bytes)
        self._held_before = 0    # what it held when the current request began (bytes; see _weigh)

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
        (self.output_path.parent / STACK_NAME).touch()   # (and where the worker writes a late call's stack)
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
        if self._companion is not None:
            self._companion.close()
        self._stop_worker(restarting=False)
        if self.cgroup is not None:
            self.cgroup.remove()
        shutil.rmtree(self._base, ignore_errors=True)

    def _start_worker(self):
        if self.proc is None:
            self._spawn_worker()
        self._await_ready()

    def _new_cgroup(self) -> confine.Cgroup | None:
        # One memory and task budget for the worker and everything it starts (its own
        # wrappers, and a thread per core for OpenCV's pool, come on top of the student's share).
        return confine.Cgroup.create(self.memory, self.limits.extra_processes + 16 + (os.cpu_count() or 1))

    def _spawn_worker(self):
        if self.cgroup is not None and self._spawned:
            # A fresh account for each worker: what an earlier one left charged (files in a
            # tmpfs, shared memory) never counts against the next call, and the counters of
            # out-of-memory kills start from nothing.
            self.cgroup.remove()
            self.cgroup = self._new_cgroup()
        self._spawned += 1
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
                            files=(self.output_path, self.output_path.parent / STACK_NAME),
                            size=self.limits.scratch_bytes)
        script = str(self.scratch / "worker" / "worker.py")
        arguments = [str(self.submission_dir), str(self.output_path), self.limits.worker_json(processes)]
        try:
            self.proc = self._forked(script, arguments, view, (request_r, response_w, log.fileno()))
            if self.proc is None:
                command = self.confinement.wrap(
                    [confine.INTERPRETER, "-I", "-B", script, str(request_r), str(response_w), *arguments],
                    view=view, hold=self._base / "hold")
                if self.cgroup is not None:
                    command = self.cgroup.wrap(command)
                command = _ends_with_this_thread(command)
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
        self._worker_started = time.monotonic()
        self._request_fd, self._response_fd = request_w, response_r
        self._worker_pipes = ((request_r, os.fstat(request_w).st_ino), (response_w, os.fstat(response_r).st_ino))
        if not self.confinement.hides_files:
            _distrust_store()  # before its first request: no student code has run yet
        self._imported = set()
        self._ready = False

    def _forked(self, script: str, arguments: list[str], view: confine.View, fds) -> template.Forked | None:
        """The worker forked from this process's warm template (:mod:`autograder.sandbox.template`), or None
        where it is started instead: the process-group level, or no template here."""
        if self.confinement.level == "process-group":
            return None
        environment = _scrubbed_environment(self.scratch)
        warm = template.shared(confine.INTERPRETER, environment)
        if warm is None:
            return None
        request = {**self.confinement.forked(view, self._base / "hold"), "script": script, "arguments": arguments,
                   "environment": environment, "cwd": str(self.scratch / "work"),
                   "fds": list(fds[:2]),
                   "cgroup_procs": [str(folder / "cgroup.procs") for folder in self.cgroup.folders]
                   if self.cgroup is not None else []}
        try:
            return warm.fork(request, fds)
        except TemplateError as exc:
            template.refuse(f"a fork failed ({exc})")
            return None

    def _await_ready(self, timeout: float | None = None):
        # Wait for the worker's "ready" (it imports NumPy and OpenCV first), so that
        # start-up time is never billed to the student's first call.
        from . import transport  # with NumPy: not needed to start a worker, only to talk to it
        timeout = self.limits.startup_timeout if timeout is None else min(timeout, self.limits.startup_timeout)
        try:
            length, = LENGTH.unpack(self._read(LENGTH.size, time.monotonic() + timeout))
            ready = transport.decode(self._read(length, time.monotonic() + 5))
        except (TimeoutError, EOFError, transport.TransportError) as exc:
            # The log goes to the instructor's log, never into a message: it is no grader's word.
            log = (self._base / "worker.log").read_text(errors="replace")[-2000:]
            forked = isinstance(self.proc, template.Forked) and not isinstance(exc, TimeoutError)
            self._stop_worker()
            if forked:   # (it ended before it was ready: the template's way fails here, a started worker may not)
                template.refuse(f"a forked worker ended before it was ready ({type(exc).__name__}):\n{log}")
                self._spawn_worker()
                return self._await_ready(timeout)
            logging.getLogger("autograder").error("the grading worker did not start:\n%s", log)
            raise WorkerStartError(f"the grading worker did not start ({type(exc).__name__}); "
                                   "see the autograder's log") from None
        if ready != {"ok": True, "value": "ready", "seconds": 0.0}:
            self._stop_worker()
            raise WorkerStartError("the grading worker sent an unexpected greeting")
        self._ready = True
        # What the sandbox's own processes are (wrappers, PID 1, the worker): more after a call
        # means the submission left one running, whatever the worker says.
        self._own_processes = len(self.cgroup.processes()) if self.cgroup is not None else 0
        self._own_pids = {self.proc.pid, *evidence.descendants(self.proc.pid)}
        self._find_worker()
        self._memory_floor = self._held_before = evidence.resident(self._worker_pid) or 0

    def _find_worker(self) -> None:
        """Find the worker's own process among the sandbox's (the last of the wrappers' line, as
        the host numbers it), to look at its descriptors later; held by a pidfd where Linux has
        them, so a number reused after it ended is never mistaken for it."""
        script = str(self.scratch / "worker" / "worker.py")
        if isinstance(self.proc, template.Forked):   # (its outer process, PID 1, the worker: all the template's line)
            found = [pid for pid in evidence.children(self.proc.pid) for pid in evidence.children(pid)][:1]
        else:
            found = [pid for pid in [self.proc.pid, *evidence.descendants(self.proc.pid)]
                     if evidence.command_line(pid)[1:4] == ["-I", "-B", script]]
        self._worker_pid = found[-1] if found else None
        self._worker_alive = lambda: self.proc is not None and self.proc.poll() is None
        if self._worker_pid is not None and hasattr(os, "pidfd_open"):
            try:
                pidfd = os.pidfd_open(self._worker_pid)
            except OSError:
                return
            self._pidfd = pidfd
            self._worker_alive = lambda: not select.select([pidfd], [], [], 0)[0]

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
        self._forget_worker()
        if self.confinement.level == "process-group":
            confine.kill_adopted_orphans(keep=_LIVE_WORKERS | template.processes())
            _distrust_store()  # now that nothing of it runs: what it wrote there is never read
            if restarting:
                self._lay_out_scratch()  # nothing stopped this worker from damaging it
        self.proc = None
        self._ready = False
        self._request_fd = self._response_fd = -1

    def _forget_worker(self) -> None:
        if self._pidfd >= 0:
            os.close(self._pidfd)
        self._pidfd = -1
        self._worker_pid, self._worker_alive, self._worker_pipes = None, (lambda: False), ()

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

    def set_deadline(self, at: float | None) -> None:
        """Also stop calling once ``time.monotonic()`` reaches ``at``: the submission's wall-clock
        deadline, which holds whatever runs meanwhile (calls, restarts, other lanes, the grader's
        own judging). A request running then is stopped at it."""
        self._deadline = at
        if self._companion is not None:
            self._companion.set_deadline(at)

    def remaining(self) -> float:
        left = float("inf") if self._budget is None else self._budget - self.student_seconds
        if self._deadline is not None:
            left = min(left, self._deadline - time.monotonic())
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
        # A function that hung, or was stopped for its memory, repeatedly would only cost every
        # later check its full timeout, or the time to fill its memory and a restart.
        struck = self._struck(module, function)
        if struck is not None:
            return struck
        timeout = timeout or self.limits.call_timeout
        if self.remaining() <= 0:
            return self._over_budget(f"{function}()")
        request = {"op": "call", "module": module, "function": function,
                   "args": list(args), "kwargs": dict(kwargs or {}),
                   "forbid": list(forbid), "cpu_seconds": timeout + 1.0,
                   "max_bytes": answer_cap(self.limits.max_result_bytes, args, kwargs)}
        outcome = self._billed(request, timeout, what=f"{function}()")
        if outcome.kind in ("timeout", "memory"):
            key = (module, function, outcome.kind)
            self._strikes[key] = self._strikes.get(key, 0) + 1
        return outcome

    def call_variant(self, module: str, source: str, function: str, calls, *, timeout: float,
                     forbid=(), trace: bool = False, fresh: bool = False, max_bytes: int | None = None) -> CallOutcome:
        """Call ``function`` of a variant of the student's ``module`` -- its defs in ``source`` (the
        grader's rewrite of the student's own code) executed over a copy of the module -- on each
        ``(args, kwargs)`` of ``calls``. The value is a list: each call's result or ``{"__error__":
        "Type: text"}``. Not billed to the student: the caller bounds the time (``timeout``, and the
        submission's deadline); meant for a :meth:`companion`, whose faults cost the student's own
        worker nothing. ``trace`` with ``source`` "" (the student's code as it is): the value is
        ``{"values": [...], "lines": [...]}``, with the lines of the module's file the calls ran.
        ``fresh`` (``source`` ""): the student's module file executed anew for these calls alone, as a
        first call finds it (what earlier calls left in the module is not there). ``max_bytes``: the most its
        answers may hold together, where the caller knows what a right answer holds (within what the calls'
        arguments allow, :func:`answer_cap`)."""
        imported = self.import_module(module)
        if not imported.ok:
            return imported
        timeout = min(timeout, self.remaining())
        if timeout <= 0:
            return self._over_budget(f"{function}() (a variant)")
        calls = [[list(args), dict(kwargs)] for args, kwargs in calls]
        request = {"op": "variant", "module": module, "source": source, "function": function, "calls": calls,
                   "forbid": list(forbid), "cpu_seconds": timeout + 1.0, "trace": bool(trace), "fresh": bool(fresh),
                   "max_bytes": min(self.limits.max_result_bytes, max_bytes or self.limits.max_result_bytes,
                                    sum(answer_cap(self.limits.max_result_bytes, call) for call in calls) or ANSWER_FLOOR)}
        return self._request(request, timeout, f"{function}() (a variant)")

    def working_pids(self) -> list[tuple[int, float]]:
        """(pid, when it started: ``time.monotonic()``) of the processes running the student's code for
        this sandbox now: its worker, and its companion's when one runs (the CPU time a naming spends,
        :class:`~autograder.engine.mutants.naming.Clock`)."""
        pids = [(self._worker_pid, self._worker_started)] \
            if self._worker_pid is not None and self.proc is not None else []
        if self._companion is not None and not self._companion._closed:
            pids += self._companion.working_pids()
        return pids

    def companion(self) -> "Sandbox":
        """Another sandbox of the same submission, the same confinement and deadline, half the memory,
        started at its first use and closed with this one: the grader's own experiments with the
        student's code (:mod:`autograder.engine.mutants.repair`) run there, so a variant that hangs or
        crashes costs this worker no restart, its budget nothing, and the two never share memory."""
        if self._companion is None or self._companion._closed:
            # Half this worker's memory and reply size: the two together never hold more than one
            # and a half shares (the student's worker waits, idle, while its companion runs).
            halved = replace(self.limits, memory=self.limits.memory // 2,
                             max_result_bytes=self.limits.max_result_bytes // 2)
            self._companion = Sandbox(self._source, halved, confinement=self.confinement)
            self._companion.set_deadline(self._deadline)
        return self._companion

    def remember_strikes(self, other: "Sandbox") -> None:
        """Give up here too on the functions ``other`` (a worker of the same submission) gave up
        on: the hidden checks' fresh workers do not call again what the public phase stopped."""
        for key, count in other._strikes.items():
            self._strikes[key] = max(self._strikes.get(key, 0), count)

    def _struck(self, module: str, function: str) -> CallOutcome | None:
        """The outcome of a function not called again (it timed out, or was stopped for its
        memory, :attr:`Limits.timeouts_per_function` times), else None."""
        times = self.limits.timeouts_per_function
        if self._strikes.get((module, function, "timeout"), 0) >= times:
            return CallOutcome(ok=False, kind="timeout",
                               message=f"{function}() timed out {times} times already; not called again")
        if self._strikes.get((module, function, "memory"), 0) >= times:
            return CallOutcome(ok=False, kind="memory",
                               message=f"{function}() ran out of memory {times} times already; not called again")
        return None

    # ------------------------------------------------------------ plumbing
    def _restart(self, what: str) -> CallOutcome | None:
        """Start the worker; a restart is billed its start-up time and capped."""
        if self._closed or self._interrupted:
            return CallOutcome(ok=False, kind="grader_error", message="grading was stopped")
        restart = self._started and not self._stopped_by_grader
        self._stopped_by_grader = False
        self._restart_refused = restart and self.restarts >= self.limits.max_restarts
        if self._restart_refused:
            return CallOutcome(ok=False, kind="crashed",
                               message=f"the worker was restarted {self.limits.max_restarts} times in this "
                                       "exercise after crashes, hangs or suspect states; not started again")
        started = time.perf_counter()
        try:
            if self.proc is None:
                self._spawn_worker()
            self._await_ready(self.remaining() if restart else None)  # a restart is billed
        except WorkerStartError as exc:
            if restart:  # what is left of the budget was too short for the start-up: that is spent too
                self._bill(time.perf_counter() - started)
            if self.remaining() <= 0:
                return self._over_budget(what)
            return CallOutcome(ok=False, kind="grader_error", message=str(exc))
        self._started = True
        if restart:
            self.restarts += 1
            self._bill(time.perf_counter() - started)
        return None

    def _request(self, request: dict, timeout: float, what: str) -> CallOutcome:
        from . import transport  # with NumPy: not needed to start a worker, only to talk to it
        if self.proc is None or not self._ready:
            failed = self._restart(what)
            if failed is not None:
                return failed
            if request["op"] in ("call", "variant"):
                imported = self.import_module(request["module"])
                if not imported.ok:
                    return imported
                if self.proc is None:  # (an import that leaves the worker unusable fails)
                    return CallOutcome(ok=False, kind="crashed", message=f"{what}: the worker stopped")
                timeout = min(timeout, self.remaining())
                if timeout <= 0:
                    return self._over_budget(what)
        self._started = True  # (a worker made ready before this request is started too)
        self._request_id += 1
        request = {**request, "id": self._request_id}
        if request["op"] == "call":   # (where the call is, written shortly before it would be stopped)
            request["stack_after"] = max(0.05, timeout - STACK_MARGIN)
        frame = transport.encode(request)
        self._measured = _Measures.now(self.cgroup)
        start = time.perf_counter()
        deadline = time.monotonic() + timeout
        self._watching = True
        replying = None  # the reply's length, once the worker has begun sending it
        try:
            self._write(LENGTH.pack(len(frame)) + frame, deadline)
            length, = LENGTH.unpack(self._read(LENGTH.size, deadline))
            replying = length
            cap = request.get("max_bytes", self.limits.max_result_bytes)
            if length > cap:  # (the worker refuses it first: this one lied)
                return self._abandon(CallOutcome(
                    ok=False, kind="result_type", seconds=time.perf_counter() - start,
                    message=f"{what} returned {transport.size_words(length)}, which cannot be sent back: "
                            f"at most {transport.size_words(cap)} can"))
            head = self._read(min(length, transport.PREFIX.size), deadline)
            if len(head) == transport.PREFIX.size:  # refuse an oversized header before reading it
                _, header_length = transport.PREFIX.unpack(head)
                if header_length > transport.MAX_HEADER_BYTES:
                    raise transport.TransportError(f"frame header larger than {transport.MAX_HEADER_BYTES} bytes")
                if self.limits.max_result_elements is not None:  # counted on the header: no array read
                    head += self._read(min(header_length, length - len(head)), deadline)
                    transport.check_elements(head[transport.PREFIX.size:], self.limits.max_result_elements)
            frame = head + self._read(length - len(head), deadline)
            reply = transport.decode(frame, max_bytes=cap)
            seconds = time.perf_counter() - start  # measured here: the worker's word is not taken
            if self._pending_reply():
                raise transport.TransportError("more than one reply to one call")
        except TimeoutError:
            return self._abandon(self._fault(what, time.perf_counter() - start, timeout=timeout,
                                             replying=replying, where=self._where_it_was()))
        except _Stopped as stopped:
            return self._abandon(self._fault(what, time.perf_counter() - start, stopped=stopped.reason,
                                             replying=replying))
        except (EOFError, OSError):  # the pipe ended, or broke (EPIPE; a descriptor gone)
            return self._abandon(self._fault(what, time.perf_counter() - start, replying=replying))
        except transport.TooManyElements as exc:  # the arrays were never read: the worker goes
            return self._abandon(CallOutcome(ok=False, kind="result_type", message=f"{what} {exc}",
                                             seconds=time.perf_counter() - start))
        except transport.TransportError as exc:
            return self._abandon(CallOutcome(
                ok=False, kind="protocol", seconds=time.perf_counter() - start,
                message=f"{what}: the worker sent back something that is not a valid result ({exc})"))
        except BaseException:
            # Interrupted by the grader (Ctrl-C; its own work about a check stopped as a runaway, see
            # autograder.engine.bounded): what is left on the pipe is unknown, so the next request gets a new
            # worker, neither billed nor counted as a restart -- the student's code did nothing to earn it.
            self._stop_worker()
            self._stopped_by_grader = True
            raise
        finally:
            self._watching = False
        outcome = self._outcome_from_reply(reply, what, request["id"], seconds)
        if self.proc is not None:
            outcome.output = self._read_output()
            if self._pipe_taken():  # it answered, then the next request could not reach it
                return self._abandon(self._fault(what, seconds, stopped="pipe"))
            left = self._left_running(reply)
            if left:
                self._stop_worker()  # the next call gets a clean worker, nothing of this one's running
                if request["op"] == "import" and outcome.ok:  # each new worker would import it again
                    return CallOutcome(ok=False, kind="import_error", seconds=seconds, output=outcome.output,
                                       message=f"{what} left {left} running; the module's top-level code "
                                               "must finish its work (start threads and processes inside "
                                               "your functions, and wait for them there)")
            else:
                self._weigh(request["op"])
        return outcome

    def _weigh(self, op: str) -> None:
        """After a request: what the worker holds now. An import's is the floor of what it holds
        from then on (the module's own data). A call that left more than a quarter of the
        worker's memory held (in a global, a cache that grows) would leave the next call, of
        another function perhaps, only the rest: the worker is replaced before the next call
        (a restart, billed), and a memory bomb costs only the function that kept the memory."""
        held = evidence.resident(self._worker_pid)
        if held is None:
            return
        self._held_before = held  # (nothing runs in the worker until the next request)
        if op == "import":
            self._memory_floor = max(self._memory_floor, held)
        elif held - self._memory_floor > self.memory // 4:
            self._stop_worker()

    def _left_running(self, reply) -> str:
        """What the request left running besides the worker (``""``: nothing). Child processes as
        the grader counts them (in the cgroup, else among the worker's descendants); threads, which
        only the worker sees, as it says (its word can only make the grader stricter)."""
        if self.cgroup is not None:
            if len(self.cgroup.processes()) > self._own_processes:
                return "processes"
        elif set(evidence.descendants(self.proc.pid)) - self._own_pids:
            return "processes"
        if self.cgroup is None and self.confinement.level == "process-group":
            confine.kill_adopted_orphans(keep=_LIVE_WORKERS | template.processes())  # re-parented to the grader: no one's now
        suspect = reply.get("suspect") if type(reply) is dict else None
        if type(suspect) is not str:
            return ""
        return "threads" if suspect.startswith("threads") else \
            "processes" if suspect.startswith("child") else "the worker without file descriptors"

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
        shared = reply.get("shared")
        shared = shared if type(shared) is str and len(shared) <= 80 and shared.isidentifier() else ""
        if reply["ok"]:
            return CallOutcome(ok=True, value=reply.get("value"), seconds=seconds, modified=modified,
                               changed=_changed_arrays(reply.get("changed")), shared=shared)
        kind = reply.get("kind") if reply.get("kind") in WORKER_KINDS else "exception"
        message = reply.get("message") if type(reply.get("message")) is str else ""
        tb = reply.get("traceback") if type(reply.get("traceback")) is str else ""
        if kind == "result_type" and message.startswith("returned"):
            message = f"{what} {message}"
        if kind == "memory":  # a MemoryError: an allocation refused by RLIMIT_AS, in the worker's process
            message = (f"{what} asked for more than {self.limits.address_space // 2**20} MB of memory "
                       "(MemoryError)")
        return CallOutcome(ok=False, kind=kind, message=message[:2000], traceback=tb[-4000:],
                           seconds=seconds)

    def _abandon(self, outcome: CallOutcome) -> CallOutcome:
        """After a hang, crash or garbage: kill the worker; the next call starts a new one."""
        outcome.output = self._read_output()
        self._stop_worker()
        return outcome

    def _where_it_was(self) -> str:
        """Where the call was when it ran out of time, in words (": it was at line 42 of your `triangulate`,
        inside NumPy's `svd`"), from the stack the worker wrote shortly before (see worker.StackAtDeadline);
        "" when there is none. Read bounded, never following a link; only frames of the submission's own
        files are named (the text is the worker's: it says where to look, and decides nothing)."""
        try:
            fd = os.open(self.output_path.parent / STACK_NAME, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
        except OSError:
            return ""
        with os.fdopen(fd, "rb") as f:
            if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
                return ""
            text = f.read(STACK_BYTES).decode("utf-8", errors="replace")
        return where_stopped(text, {p.name for p in self.submission_dir.glob("*.py")})

    def _fault(self, what, seconds, timeout: float | None = None, stopped: str = "",
               replying: int | None = None, where: str = "") -> CallOutcome:
        """Why the worker stopped answering a request, decided from what the grader measured
        (before the worker is stopped): its own reason to stop it (``stopped``, see
        :meth:`_check_in`), the cgroup's counters, whether the worker still holds the grader's
        pipe, how it ended, and whether it had begun sending its reply (``replying``: the
        reply's length, read from the pipe). Never from what the worker said."""
        from . import transport  # with NumPy: imported once a request was made

        def fault(kind, message):
            return CallOutcome(ok=False, kind=kind, message=message, seconds=seconds)

        # The call had returned, and its result was on its way: the call's own code had ended.
        sending = "" if replying is None else f"{what} returned {transport.size_words(replying)}, and "
        memory = (f"{sending}the worker was stopped for using more than {self.memory // 2**20} MB of memory "
                  "while sending it back") if sending else self._memory_words(what) + self._held_words()
        if self._interrupted:
            return fault("grader_error", "grading was stopped")
        if stopped == "processes":
            return fault("crashed", f"{what} started more than {self.limits.extra_processes} processes "
                                    "(a fork bomb?)")
        if stopped == "memory" or self._measured.oom_killed(self.cgroup):
            return fault("memory", memory)
        if stopped == "pipe" or self._pipe_taken():
            return fault("crashed", f"{what} closed the grader's pipe to the worker; do not close or "
                                    "replace file descriptors your code did not open")
        if timeout is not None:
            if sending:
                return fault("timeout", f"{sending}it was not all sent back within {timeout:g} s")
            if self._measured.pressed(self.cgroup, self.memory):  # it thrashed at its limit meanwhile
                return fault("memory", f"{self._memory_words(what)} (and was stopped after {timeout:g} s)")
            held = max(self._measured.peak, evidence.memory_in_use(
                [self.proc.pid, *evidence.descendants(self.proc.pid)]) or 0)
            if held >= self.memory // 2:  # not an infinite loop: an allocation that was not done yet
                return fault("timeout", f"{what} did not finish within {timeout:g} s, holding "
                                        f"{held // 2**20} MB of memory by then (it may use "
                                        f"{self.memory // 2**20} MB)")
            return fault("timeout", f"{what} did not finish within {timeout:g} s "
                                    f"(an infinite loop, or far too slow?){where}")
        try:
            code = self.confinement.exit_signal(self.proc.wait(timeout=2))
        except subprocess.TimeoutExpired:  # alive, but the pipe ended: it closed the grader's
            return fault("crashed", f"{what} closed the grader's pipe to the worker; do not close or "
                                    "replace file descriptors your code did not open")
        if self._measured.oom_killed(self.cgroup):
            return fault("memory", memory)
        signame = None if code is None or code >= 0 else \
            signal.Signals(-code).name if -code in signal.valid_signals() else str(-code)
        if sending:
            return fault("crashed", f"{sending}the worker ended ({signame or f'exit code {code}'}) while sending "
                                    "it back; a thread or process your code left running can end it")
        if signame is not None:
            if signame == "SIGKILL" and self.cgroup is None and self._measured.peak >= self.memory // 2:
                # No cgroup to count out-of-memory kills: the system's OOM killer picks the process
                # holding the most memory, and this one held half its limit or more.
                return fault("memory", f"{what} was killed by the system while holding "
                                       f"{self._measured.peak // 2**20} MB of memory (out of memory)")
            reasons = {
                "SIGXCPU": "used up its CPU time limit",
                "SIGXFSZ": f"wrote more than {self.limits.file_size // 2**20} MB (printed output counts)",
                "SIGSEGV": "crashed with a segmentation fault",
                "SIGKILL": "was killed (SIGKILL), not by the grader; do not kill processes",
                "SIGABRT": "aborted",
            }
            kind = "output_too_large" if signame == "SIGXFSZ" else "crashed"
            return fault(kind, f"{what} {reasons.get(signame, f'was stopped by {signame}')}")
        return fault("crashed", f"{what} ended the worker process (exit code {code}); "
                                "do not call os._exit() or kill processes")

    def _memory_words(self, what: str) -> str:
        return f"{what} used more than {self.memory // 2**20} MB of memory"

    def _held_words(self) -> str:
        """What the worker held when the request began beyond its floor (its modules), when that
        was much of its memory: kept by earlier calls (``""`` otherwise)."""
        kept = self._held_before - self._memory_floor
        if kept <= self.memory // 8:
            return ""
        return f" ({kept // 2**20} MB of it already held when it was called, kept by earlier calls)"

    def _pipe_taken(self) -> bool:
        """Whether the worker, alive, no longer holds the grader's pipe at its descriptor (the
        submission closed it, or put another file there), as ``/proc`` shows the grader."""
        pid = self._worker_pid
        if pid is None or not self._worker_pipes:
            return False
        if not any(evidence.holds_pipe(pid, fd, inode) is False for fd, inode in self._worker_pipes):
            return False
        # A process that is ending closes its descriptors a moment before it is gone: one
        # that has not ended a little later has let the pipe go itself.
        for pause in confine._pauses(seconds=0.2, longest=0.02):
            if not self._worker_alive():
                return False
            time.sleep(pause)
        return self._worker_alive()

    TICK = 0.05  # seconds between looks at the worker while a request runs

    def _check_in(self) -> None:
        """While a request runs, every :attr:`TICK`: raise :class:`_Stopped` as soon as the grader
        sees the worker without its pipe, ended (its children may hold the pipe open), or -- where
        no cgroup makes the kernel enforce them -- over its memory or its processes."""
        if not self._watching or self.proc is None:
            return
        if self._pipe_taken():
            raise _Stopped("pipe")
        if self._worker_pid is not None and not self._worker_alive():
            raise EOFError
        if self.cgroup is None:
            budget = len(self._own_pids) + self.limits.extra_processes
            pids = [self.proc.pid, *evidence.descendants(self.proc.pid, limit=budget + 1)]
            if len(set(pids) - self._own_pids) > self.limits.extra_processes:
                raise _Stopped("processes")
            used = evidence.memory_in_use(pids)
            if used is not None:
                self._measured.peak = max(self._measured.peak, used)
                if used > self.memory:
                    raise _Stopped("memory")

    def _wait(self, fd: int, write: bool, deadline: float) -> None:
        """Wait until ``fd`` is ready, looking at the worker meanwhile; TimeoutError at ``deadline``."""
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError
            ready = select.select([] if write else [fd], [fd] if write else [], [], min(remaining, self.TICK))
            if ready[0] or ready[1]:
                return
            try:
                self._check_in()
            except (EOFError, _Stopped) as ended:
                # (a worker that ended wrote nothing more after the select: what it wrote before -- a reply
                # on its way, its length -- is read first, so that how it ended is told with it)
                if write or getattr(ended, "reason", "pipe") != "pipe" or not select.select([fd], [], [], 0)[0]:
                    raise
                return

    def _write(self, data: bytes, deadline: float):
        view = memoryview(data)
        while view:
            self._wait(self._request_fd, True, deadline)
            view = view[os.write(self._request_fd, view[:PIPE_BYTES]):]

    def _read(self, n: int, deadline: float) -> bytes:
        chunks = []
        while n:
            self._wait(self._response_fd, False, deadline)
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
