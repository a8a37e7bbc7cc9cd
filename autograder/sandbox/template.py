"""The grader's side of the warm template workers are forked from (``zygote.py``).

A worker started with ``unshare``, ``namespace_init.py`` and ``setpriv`` imports NumPy and OpenCV anew:
about a quarter of a second of CPU each time, and a grading starts two to five workers (the public and
the hidden phase, their companions, restarts). The template imports them once per grading process;
each worker is forked from it and confined as a started one is (the namespaces, the view built by the
same operations, the cgroup, the user, no capability, no new privileges), in a few milliseconds.

:func:`shared` starts the template at the first worker of a process (namespaced levels only) and hands
out :class:`Template`; :meth:`Template.fork` returns a :class:`Forked`, which the sandbox holds as it
holds a :class:`subprocess.Popen`. Where the template cannot start or fork, the workers are started as
before, and the instructor's log says why once. ``AUTOGRADER_WORKER_START=exec`` always starts them.
"""

from __future__ import annotations

import atexit
import json
import logging
import os
import select
import shutil
import signal
import socket
import subprocess
import tempfile
import threading
from pathlib import Path

FILES = ("zygote.py", "namespace_init.py", "worker.py", "transport.py", "beginner.py")
REPLY_SECONDS = 60.0   # for the template's answer to a fork (its own start included, on a loaded machine)


class TemplateError(Exception):
    """The template could not fork this worker (the grader then starts it)."""


class Forked:
    """A worker forked from the template, as the grader holds it: its outer process's ``pid`` (its own
    session: ``os.killpg(pid, ...)`` ends the worker's namespace with it), and :meth:`poll` and :meth:`wait`
    as :class:`subprocess.Popen` has them, read from the pipe that process writes its exit status to as it
    ends (nothing written: it was killed, -SIGKILL)."""

    def __init__(self, pid: int, status_fd: int):
        self.pid = pid
        self.returncode: int | None = None
        self._status_fd = status_fd

    def poll(self) -> int | None:
        if self.returncode is None and select.select([self._status_fd], [], [], 0)[0]:
            self._read_status()
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        if self.returncode is None:
            if not select.select([self._status_fd], [], [], timeout)[0]:
                raise subprocess.TimeoutExpired(f"worker {self.pid}", timeout)
            self._read_status()
        return self.returncode

    def _read_status(self) -> None:
        try:
            status = os.read(self._status_fd, 4)
        except OSError:
            status = b""
        self.returncode = int.from_bytes(status, "big", signed=True) if len(status) == 4 else -signal.SIGKILL
        self.close()

    def close(self) -> None:
        if self._status_fd >= 0:
            os.close(self._status_fd)
            self._status_fd = -1

    def __del__(self):
        self.close()


class Template:
    """The template process of this grading process, and the socket it is asked to fork on."""

    def __init__(self, interpreter: str, environment: dict[str, str]):
        self._lock = threading.Lock()
        self._folder = Path(tempfile.mkdtemp(prefix="autograder-template-"))
        self._folder.chmod(0o700)
        here = Path(__file__).parent
        for name in FILES:
            shutil.copy(here / name, self._folder / name)
        self._control, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            with open(self._folder / "template.log", "ab") as log:
                self._process = subprocess.Popen(
                    [interpreter, "-I", "-B", "-S", str(self._folder / "zygote.py"), str(theirs.fileno())],
                    pass_fds=(theirs.fileno(),), stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                    cwd=self._folder, env={**environment, "HOME": str(self._folder), "TMPDIR": str(self._folder)},
                    start_new_session=True)   # (a Ctrl-C to the grader's terminal is the grader's to handle)
        finally:
            theirs.close()

    @property
    def pid(self) -> int:
        return self._process.pid

    def fork(self, request: dict, fds) -> Forked:
        """Fork a worker confined as ``request`` says (:meth:`autograder.sandbox.confine.Confinement.forked`,
        with its script, arguments, environment and working folder) on ``fds`` (its request and response
        pipes and its log); raises :class:`TemplateError` when the template cannot."""
        status_r, status_w = os.pipe()
        try:
            with self._lock:
                try:
                    socket.send_fds(self._control, [json.dumps(request).encode()], [*fds, status_w])
                    if not select.select([self._control], [], [], REPLY_SECONDS)[0]:
                        raise TemplateError(f"no answer in {REPLY_SECONDS:.0f} s")
                    reply = self._control.recv(4096)
                except OSError as exc:
                    raise TemplateError(f"{type(exc).__name__}: {exc}") from None
            if not reply:
                raise TemplateError(f"the template ended{self._log_tail()}")
            answer = json.loads(reply)
            if "pid" not in answer:
                raise TemplateError(str(answer.get("error", answer))[:500])
        except BaseException:
            os.close(status_r)
            raise
        finally:
            os.close(status_w)
        return Forked(int(answer["pid"]), status_r)

    def _log_tail(self) -> str:
        try:
            tail = (self._folder / "template.log").read_text(errors="replace")[-1500:].strip()
        except OSError:
            return ""
        return f":\n{tail}" if tail else ""

    def close(self) -> None:
        """End the template (its workers end with it) and remove its folder."""
        if self._control.fileno() < 0:
            return
        self._control.close()   # (it ends on the socket's end)
        try:
            self._process.wait(timeout=2)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait()
        shutil.rmtree(self._folder, ignore_errors=True)


_LOCK = threading.Lock()
_SHARED: dict = {}   # {"pid": the process it belongs to, "template": the Template, none once refused}
_PROCESSES: set[int] = set()   # every template this process started, used or retired: its workers may run


def processes() -> set[int]:
    """The template processes this process started (in sessions of their own, as workers are: a sweep of
    escaped daemons keeps them, see :func:`autograder.sandbox.confine.kill_adopted_orphans`)."""
    return set(_PROCESSES)


def shared(interpreter: str, environment: dict[str, str]) -> Template | None:
    """This process's template, started at its first use; None where workers are started instead
    (``AUTOGRADER_WORKER_START=exec``, or the template failed: logged once, then never tried again)."""
    if os.environ.get("AUTOGRADER_WORKER_START", "").strip().lower() == "exec" or not hasattr(socket, "send_fds"):
        return None
    with _LOCK:
        if _SHARED.get("pid") != os.getpid():   # (a process forked from one with a template has none yet)
            _SHARED.clear()
            _PROCESSES.clear()
            _SHARED["pid"] = os.getpid()
            try:
                _SHARED["template"] = Template(interpreter, environment)
            except OSError as exc:
                _refuse(f"it could not start ({exc})")
            else:
                _PROCESSES.add(_SHARED["template"].pid)
                atexit.register(_SHARED["template"].close)
        return _SHARED.get("template")


def refuse(why: str) -> None:
    """Start this process's workers without the template from now on (``why``: logged)."""
    with _LOCK:
        _refuse(why)


def _refuse(why: str) -> None:
    # (not ended now: workers forked from it may be running, and end with it -- it ends with this process)
    _SHARED.pop("template", None)
    logging.getLogger("autograder").warning(
        "workers are started one by one, not forked from the warm template: %s", why)
