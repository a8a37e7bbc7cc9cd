"""The grader's side of the sandbox: one worker process per submission.

:class:`Sandbox` starts ``worker.py`` in a scratch directory with a scrubbed
environment and resource limits, sends it one call at a time, and turns whatever
happens -- a value, an exception, a hang, a crash, garbage on the pipe -- into a
:class:`CallOutcome`. It never raises because of what the student's code did.
A worker that hangs or dies is killed with its whole process group and started
again for the next call.
"""

from __future__ import annotations

import json
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
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from . import confine, transport

LENGTH = struct.Struct(">Q")
_WORKER_FILES = ("worker.py", "transport.py")

FAILURE_KINDS = {
    "timeout", "crashed", "exception", "not_implemented", "missing_function",
    "missing_module", "import_error", "memory", "recursion", "result_type",
    "forbidden_call", "output_too_large", "protocol", "grader_error",
}


@dataclass(frozen=True)
class Limits:
    """Per-submission limits of the worker process."""

    call_timeout: float = 10.0           # wall seconds per call, unless a check says otherwise
    import_timeout: float = 20.0         # wall seconds to import one student module
    address_space: int = 6 * 2**30       # bytes of virtual memory
    file_size: int = 64 * 2**20          # bytes in any file written, printed output included
    cpu_total: int = 1800                # CPU seconds over the worker's life
    extra_processes: int = 64            # processes/threads beyond those the user already has
    max_result_bytes: int = 256 * 2**20  # largest result frame accepted
    max_output_chars: int = 4000         # captured stdout/stderr kept per call
    startup_timeout: float = 60.0        # for the worker to import NumPy/OpenCV (not billed)
    timeouts_per_function: int = 2       # after this many timeouts a function is not called again

    def worker_json(self, processes: int | None) -> str:
        return json.dumps({
            "address_space": self.address_space,
            "file_size": self.file_size,
            "cpu_total": self.cpu_total,
            "processes": processes,
        })


# Workers alive in this process, so reaping escaped daemons never touches a worker.
_LIVE_WORKERS: set[int] = set()


def default_hidden_paths() -> list[Path]:
    """Folders the worker must not read: the grader, its fixtures, the answers, the tests.

    ``AUTOGRADER_HIDE`` adds more (``os.pathsep``-separated), e.g. a container's
    results folder.
    """
    import fixtures

    package = Path(__file__).resolve().parent
    root = package.parent
    paths = [package, Path(fixtures.__file__).resolve().parent,
             root / "reference_solutions", root / "tests", root / ".git"]
    extra = os.environ.get("AUTOGRADER_HIDE", "")
    paths += [Path(p) for p in extra.split(os.pathsep) if p]
    return [p for p in dict.fromkeys(paths) if p.is_dir()]


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
    submission_dir : path
        Folder holding the student's modules (``lab07_transformations.py`` ...).
        It is copied into the scratch directory; the original is never touched.
    limits : Limits

    Examples
    --------
    >>> with Sandbox("reference_solutions") as box:            # doctest: +SKIP
    ...     box.call("lab07_transformations", "translation_matrix", (1, 2)).value
    """

    def __init__(self, submission_dir, limits: Limits | None = None,
                 confinement: confine.Confinement | None = None, hide=None):
        self.limits = limits or Limits()
        self.confinement = confinement or confine.detect()
        self.hide = default_hidden_paths() if hide is None else list(hide)
        if self.confinement.level == "process-group":
            confine.become_subreaper()
        # A private base (listable by the grader only) around a randomly named
        # scratch folder, so workers of other submissions cannot find this one.
        self._base = Path(tempfile.mkdtemp(prefix="autograder-"))
        self._base.chmod(0o711)
        self.scratch = self._base / secrets.token_hex(8)
        self.scratch.mkdir()
        self._source = Path(submission_dir)
        self.submission_dir = self.scratch / "submission"
        self.output_path = self.scratch / "out" / "output.txt"
        self._lay_out_scratch()
        self.proc: subprocess.Popen | None = None
        self._request_fd = self._response_fd = -1
        self._imported: set[str] = set()
        self._import_failures: dict[str, CallOutcome] = {}
        self.student_seconds = 0.0
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
        shutil.copytree(self._source, self.submission_dir,
                        ignore=shutil.ignore_patterns("__pycache__", "*.pyc", ".*"))
        (self.scratch / "worker").mkdir()
        here = Path(__file__).parent
        for name in _WORKER_FILES:
            shutil.copy(here / name, self.scratch / "worker" / name)
        for name in self.WRITABLE:
            (self.scratch / name).mkdir()
        self.confinement.prepare_scratch(self.scratch, private=("worker",))

    # ------------------------------------------------------------ lifecycle
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        """Stop the worker and everything it started, then delete the scratch directory."""
        self._stop_worker(restarting=False)
        shutil.rmtree(self._base, ignore_errors=True)

    def _start_worker(self):
        try:
            log = open(self._base / "worker.log", "ab")
        except OSError as exc:
            raise WorkerStartError(f"cannot write the worker log: {exc}") from None
        request_r, request_w = os.pipe()
        response_r, response_w = os.pipe()
        uid = self.confinement.uid if self.confinement.uid is not None else os.getuid()
        tasks = confine.count_tasks(uid)  # None where they cannot be counted (macOS): no limit
        processes = None if tasks is None else tasks + self.limits.extra_processes
        command = self.confinement.wrap(
            [sys.executable, "-B", str(self.scratch / "worker" / "worker.py"),
             str(request_r), str(response_w), str(self.submission_dir),
             str(self.output_path), self.limits.worker_json(processes)],
            hide=self.hide, writable=[self.scratch / name for name in self.WRITABLE],
            hold=self._base / "hold")
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
        self._imported = set()
        # Wait for the worker's "ready" (it imports NumPy and OpenCV first), so that
        # start-up time is never billed to the student's first call.
        try:
            length, = LENGTH.unpack(self._read(LENGTH.size, time.monotonic() + self.limits.startup_timeout))
            ready = transport.decode(self._read(length, time.monotonic() + 5))
        except (TimeoutError, EOFError, transport.TransportError) as exc:
            log = (self._base / "worker.log").read_text(errors="replace")[-2000:]
            self._stop_worker()
            raise WorkerStartError(f"the grading worker did not start ({type(exc).__name__}): {log}") from None
        if ready != {"ok": True, "value": "ready", "seconds": 0.0}:
            self._stop_worker()
            raise WorkerStartError("the grading worker sent an unexpected greeting")

    def _stop_worker(self, restarting: bool = True):
        if self.proc is None:
            return
        for fd in (self._request_fd, self._response_fd):
            try:
                os.close(fd)
            except OSError:
                pass
        try:
            self.proc.wait(timeout=0.5)   # a healthy worker exits on EOF
        except subprocess.TimeoutExpired:
            pass
        self._kill_process_group()
        _LIVE_WORKERS.discard(self.proc.pid)
        if self.confinement.level == "process-group":
            confine.kill_adopted_orphans(keep=_LIVE_WORKERS)
            if restarting:
                self._lay_out_scratch()  # nothing stopped this worker from damaging it
        self.proc = None
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

    # ------------------------------------------------------------ public API
    def import_module(self, module: str, timeout: float | None = None) -> CallOutcome:
        """Import a student module in the worker (once); failures are remembered."""
        if module in self._import_failures:
            return self._import_failures[module]
        if module in self._imported and self.proc is not None:
            return CallOutcome(ok=True)
        outcome = self._request({"op": "import", "module": module},
                                timeout or self.limits.import_timeout,
                                what=f"importing {module}.py")
        if outcome.ok:
            self._imported.add(module)
        else:
            self._import_failures[module] = outcome
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
        request = {"op": "call", "module": module, "function": function,
                   "args": list(args), "kwargs": dict(kwargs or {}),
                   "forbid": list(forbid), "cpu_seconds": timeout + 1.0}
        outcome = self._request(request, timeout, what=f"{function}()")
        if outcome.kind == "timeout":
            self._timeouts[(module, function)] = self._timeouts.get((module, function), 0) + 1
            self.student_seconds += timeout
        else:
            self.student_seconds += outcome.seconds
        return outcome

    # ------------------------------------------------------------ plumbing
    def _request(self, request: dict, timeout: float, what: str) -> CallOutcome:
        if self.proc is None:
            try:
                self._start_worker()
            except WorkerStartError as exc:
                return CallOutcome(ok=False, kind="grader_error", message=str(exc))
            if request["op"] == "call":
                imported = self.import_module(request["module"])
                if not imported.ok:
                    return imported
        frame = transport.encode(request)
        start = time.perf_counter()
        deadline = time.monotonic() + timeout
        try:
            self._write(LENGTH.pack(len(frame)) + frame, deadline)
            length, = LENGTH.unpack(self._read(LENGTH.size, deadline))
            if length > self.limits.max_result_bytes:
                return self._abandon(CallOutcome(
                    ok=False, kind="result_type",
                    message=f"{what} returned more than {self.limits.max_result_bytes // 2**20} MiB"))
            reply = transport.decode(self._read(length, deadline), max_bytes=self.limits.max_result_bytes)
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
        outcome = self._outcome_from_reply(reply, what)
        outcome.output = self._read_output()
        return outcome

    def _outcome_from_reply(self, reply, what) -> CallOutcome:
        if type(reply) is not dict or type(reply.get("ok")) is not bool:
            return self._abandon(CallOutcome(ok=False, kind="protocol",
                                             message=f"{what}: malformed reply from the worker"))
        seconds = reply.get("seconds")
        seconds = float(seconds) if type(seconds) in (int, float) and seconds >= 0 else 0.0
        modified = reply.get("modified")
        modified = tuple(name[:100] for name in modified[:20] if type(name) is str) \
            if type(modified) is list else ()
        if reply["ok"]:
            return CallOutcome(ok=True, value=reply.get("value"), seconds=seconds, modified=modified)
        kind = reply.get("kind") if reply.get("kind") in FAILURE_KINDS else "exception"
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
            code = self.proc.wait(timeout=2)
        except subprocess.TimeoutExpired:
            code = None
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
                view = view[os.write(self._request_fd, view[: 1 << 16]):]

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
