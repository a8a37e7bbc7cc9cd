"""Running mutants: a helper process of the grader's, apart from the student's sandbox.

The reference and its mutants are trusted code, but a mutant may loop or allocate without
end (a loop bound moved, a statement that shrank a step dropped): they run in a helper
process of their own (never the grader's process, never the student's worker), started
lazily, with a memory limit; a request that overruns its timeout kills it, and the next
request starts another. Values cross as the sandbox's frames
(:mod:`autograder.sandbox.transport`), never as pickle.

Requests (one frame each, a length before it):

- ``{"op": "module", "source": str, "name": str}``: the reference module's text;
- ``{"op": "calls", "calls": [[function, args, kwargs], ...]}``: inputs kept for later runs;
- ``{"op": "run", "edits": [...], "function": str, "calls": [index, ...]}``: the mutant made by
  ``edits`` (:func:`.operators.apply_edits`; none: the reference) called on the kept inputs;
  the reply's ``values`` hold each call's result or ``{"__error__": "..."}``; with
  ``"changed": true`` also ``changed``, per call the argument arrays it wrote into, as
  ``[[position or keyword, index in a list or None, array], ...]`` (the sandbox's form, see
  :attr:`autograder.sandbox.supervisor.CallOutcome.changed`).

``python -m autograder.engine.mutants.helper`` serves them on stdin/stdout.
"""

from __future__ import annotations

import hashlib
import os
import resource
import select
import signal
import struct
import subprocess
import sys
import threading
import time
from collections import OrderedDict

from ...sandbox import evidence, transport

LENGTH = struct.Struct(">Q")
MEMORY_BYTES = 3 * 2**30       # address space of the helper (NumPy, OpenCV and the mutants' arrays)
MAX_FRAME = 256 * 2**20
ERROR = "__error__"
CACHE_BYTES = 256 * 2**20      # the mutants' answers kept in the grader's process (all helpers)


class HelperFailed(RuntimeError):
    """The helper did not answer in time (it was killed) or died."""


class Helper:
    """The client: one helper process, started at the first request, restarted after a kill.

    Not thread-safe: each grading lane uses its own (:func:`for_this_thread`).
    """

    def __init__(self):
        self._process: subprocess.Popen | None = None
        self._module: tuple[str, str] | None = None   # what the running process holds
        self._calls: list | None = None
        self._keys: list[bytes] = []                  # each kept input's digest (with the module's)
        self.kills = 0

    def _start(self):
        env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
               "PYTHONHASHSEED": "0"}
        self._process = subprocess.Popen(
            [sys.executable, "-m", "autograder.engine.mutants.helper"], stdin=subprocess.PIPE,
            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=env, start_new_session=True,
            preexec_fn=_limit_memory, cwd=str(_project_root()))
        self._started = time.monotonic()
        self._module, self._calls = None, None
        self.startup_cpu = 0.0   # CPU seconds the process took to start and import (set once it has)

    @property
    def running(self) -> tuple[int, float] | None:
        """(pid, when it started: ``time.monotonic()``) of the helper process while it runs."""
        process = self._process
        return (process.pid, self._started) if process is not None and process.poll() is None else None

    def close(self):
        """Stop the helper (if running)."""
        process, self._process = self._process, None
        if process is not None:
            try:
                os.killpg(process.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
            process.wait()
            for pipe in (process.stdin, process.stdout):
                try:
                    pipe.close()
                except OSError:
                    pass

    def prepare(self, source: str, name: str, calls: list, timeout: float):
        """Make sure the helper holds this module and these inputs."""
        if self._process is None or self._process.poll() is not None:
            self.close()
            self._start()
        if self._module != (name, source):
            first = self._module is None
            self._request({"op": "module", "source": source, "name": name}, timeout + 5.0)  # imports cv2
            self._module = (name, source)
            if first:   # (starting the process is not naming work: a cold grading names as a warm one)
                self.startup_cpu = evidence.cpu_seconds(self._process.pid) or 0.0
        if self._calls is not calls:
            frames = [transport.encode(list(c)) for c in calls]
            module = hashlib.sha256(f"{name}\0{source}".encode()).digest()
            self._keys = [hashlib.sha256(module + frame).digest() for frame in frames]
            self._request({"op": "calls", "calls": [list(c) for c in calls]}, timeout)
            self._calls = calls

    def run(self, edits, calls: list[int], timeout: float) -> list:
        """The mutant's results on the kept inputs ``calls`` (each a value or an error dict).

        Results are kept (:data:`ANSWERS`): a mutant is deterministic code, so the same mutant on
        the same input (a public check's fixed inputs, met by every submission of a class) is
        run once per process. The values are read-only.

        Raises
        ------
        HelperFailed
            After ``timeout`` seconds (the helper is killed) or if it died.
        """
        calls = list(calls)
        mutant = repr([list(e) for e in edits])
        keys = [(self._keys[i], mutant) if i < len(self._keys) else None for i in calls]
        values = [ANSWERS.get(key) if key else None for key in keys]
        missing = [i for i, value in zip(calls, values) if value is None]
        if missing:
            reply = self._request({"op": "run", "edits": [list(e) for e in edits], "calls": missing}, timeout)
            fresh = iter(reply["values"])
            for place, (key, value) in enumerate(zip(keys, values)):
                if value is None:
                    values[place] = ANSWERS.put(key, next(fresh)) if key else next(fresh)
        return values

    def run_changed(self, edits, calls: list[int], timeout: float) -> list[tuple]:
        """``(value, changed)`` per call: as :meth:`run`, with the argument arrays the mutant
        changed in place (``[[position or keyword, index or None, array], ...]``)."""
        reply = self._request({"op": "run", "edits": [list(e) for e in edits], "calls": list(calls),
                               "changed": True}, timeout)
        return list(zip(reply["values"], reply["changed"]))

    def _request(self, request: dict, timeout: float):
        process = self._process
        if process is None:
            raise HelperFailed("no helper")
        deadline = time.monotonic() + timeout
        frame = transport.encode(request)
        try:
            _write(process.stdin.fileno(), LENGTH.pack(len(frame)) + frame, deadline)
            length, = LENGTH.unpack(_read(process.stdout.fileno(), LENGTH.size, deadline))
            if length > MAX_FRAME:
                raise HelperFailed("reply too large")
            return transport.decode(_read(process.stdout.fileno(), length, deadline))
        except (HelperFailed, OSError, transport.TransportError) as exc:
            self.kills += 1
            self.close()
            raise HelperFailed(str(exc)) from None


class _Answers:
    """The mutants' answers by (module and input digest, mutant), least recently used first out,
    at most :data:`CACHE_BYTES` of arrays in all; shared by the grading lanes' helpers."""

    def __init__(self, budget: int):
        self.budget, self.size = budget, 0
        self._kept: OrderedDict = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key):
        with self._lock:
            found = self._kept.get(key)
            if found is not None:
                self._kept.move_to_end(key)
                return found[0]
            return None

    def put(self, key, value):
        size = _frozen(value)
        if size <= self.budget // 8:
            with self._lock:
                if key not in self._kept:
                    self._kept[key] = (value, size)
                    self.size += size
                while self.size > self.budget:
                    _, (_, dropped) = self._kept.popitem(last=False)
                    self.size -= dropped
        return value

    def clear(self):
        with self._lock:
            self._kept.clear()
            self.size = 0


def _frozen(value, depth: int = 0) -> int:
    """The bytes a value holds (arrays and strings, roughly), its arrays made read-only."""
    import numpy as np

    if isinstance(value, np.ndarray):
        value.setflags(write=False)
        return value.nbytes + 100
    if isinstance(value, (list, tuple)) and depth < 32:
        return 64 + sum(_frozen(v, depth + 1) for v in value)
    if isinstance(value, dict) and depth < 32:
        return 64 + sum(_frozen(v, depth + 1) + len(str(k)) for k, v in value.items())
    return 64 + (len(value) if isinstance(value, (str, bytes)) else 0)


ANSWERS = _Answers(CACHE_BYTES)


def _project_root():
    from pathlib import Path
    return Path(__file__).resolve().parents[3]


def _limit_memory():
    try:
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_BYTES, MEMORY_BYTES))
    except (ValueError, OSError):
        pass


def _write(fd: int, data: bytes, deadline: float):
    view = memoryview(data)
    while view:
        left = deadline - time.monotonic()
        if left <= 0 or not select.select([], [fd], [], left)[1]:
            raise HelperFailed("timed out")
        view = view[os.write(fd, view[: 1 << 16]):]


def _read(fd: int, n: int, deadline: float) -> bytes:
    chunks = []
    while n:
        left = deadline - time.monotonic()
        if left <= 0 or not select.select([fd], [], [], None if left == float("inf") else left)[0]:
            raise HelperFailed("timed out")
        chunk = os.read(fd, min(n, 1 << 20))
        if not chunk:
            raise HelperFailed("the helper ended")
        chunks.append(chunk)
        n -= len(chunk)
    return b"".join(chunks)


# ------------------------------------------------------------------ the helper's side
def _copy(value):
    """A fresh copy of the arguments (a mutant may write into its inputs; the next must not see it)."""
    import numpy as np

    if isinstance(value, np.ndarray):
        return value.copy()
    if isinstance(value, list):
        return [_copy(v) for v in value]
    if isinstance(value, tuple):
        return tuple(_copy(v) for v in value)
    if isinstance(value, dict):
        return {k: _copy(v) for k, v in value.items()}
    return value


def _changed(given, kept) -> list:
    """The argument arrays of ``given`` (the arguments a call was handed) that differ from ``kept``
    (the same, untouched): ``[[position or keyword, index in a list or None, array], ...]``."""
    import numpy as np

    args, kwargs = given
    out = []
    for key, value in list(enumerate(args)) + list(kwargs.items()):
        before = kept[0][key] if isinstance(key, int) else kept[1][key]
        pairs = zip(range(len(value)), value, before) if isinstance(value, (list, tuple)) else [(None, value, before)]
        for index, now, was in pairs:
            if isinstance(now, np.ndarray) and isinstance(was, np.ndarray) and now.dtype.kind in "biuf" \
                    and (now.shape != was.shape or now.tobytes() != was.tobytes()):
                out.append([key, index, now])
    return out


def serve(request_fd: int, reply_fd: int) -> None:
    import types
    import warnings

    import numpy as np

    import ast

    from .operators import mutated_defs

    warnings.simplefilter("ignore")
    np.seterr(all="ignore")
    try:
        import cv2
        cv2.setNumThreads(1)
    except ImportError:  # a lab without OpenCV
        pass
    source, name, calls, built, reference, tree = "", "", [], {}, None, None

    def module(edits):
        """The mutant: the reference's namespace copied (its functions rebound to the copy) with the
        mutated defs executed over it."""
        key = repr(edits)
        if key not in built:
            if len(built) > 64:
                built.clear()
            made = types.ModuleType(name)
            made.__dict__.update(reference.__dict__)
            for attr, value in reference.__dict__.items():
                if isinstance(value, types.FunctionType) and value.__globals__ is reference.__dict__:
                    rebound = types.FunctionType(value.__code__, made.__dict__, value.__name__,
                                                 value.__defaults__, value.__closure__)
                    rebound.__kwdefaults__ = value.__kwdefaults__
                    setattr(made, attr, rebound)
            code = compile(mutated_defs(tree, [tuple(e) for e in edits], source), f"<mutant of {name}>", "exec")
            exec(code, made.__dict__)  # noqa: S102 - the trusted reference, changed
            built[key] = made
        return built[key]

    while True:
        try:
            head = _read(request_fd, LENGTH.size, float("inf"))
        except HelperFailed:
            return
        length, = LENGTH.unpack(head)
        request = transport.decode(_read(request_fd, length, float("inf")))
        reply: dict = {"ok": True}
        if request["op"] == "module":
            source, name, built = request["source"], request["name"], {}
            tree = ast.parse(source)
            reference = types.ModuleType(name)
            exec(compile(source, f"<reference {name}>", "exec"), reference.__dict__)  # noqa: S102 - trusted
        elif request["op"] == "calls":
            calls = request["calls"]
        elif request["op"] == "run":
            values, changes = [], []
            try:
                made = module(request["edits"]) if request["edits"] else reference
            except Exception as exc:  # noqa: BLE001 - a mutant that does not build is no candidate
                made, failure = None, f"{type(exc).__name__}: {exc}"
            for index in request["calls"]:
                function, args, kwargs = calls[index]
                changes.append([])
                if made is None:
                    values.append({ERROR: failure})
                    continue
                given = (_copy(args), _copy(kwargs))
                try:
                    value = getattr(made, function)(*given[0], **given[1])
                    transport.encode(value)  # what cannot cross is no answer
                    values.append(value)
                    if request.get("changed"):
                        changes[-1] = _changed(given, (args, kwargs))
                except Exception as exc:  # noqa: BLE001
                    values.append({ERROR: f"{type(exc).__name__}: {exc}"[:200]})
            reply["values"] = values
            if request.get("changed"):
                reply["changed"] = changes
        frame = transport.encode(reply)
        view = memoryview(LENGTH.pack(len(frame)) + frame)
        while view:
            view = view[os.write(reply_fd, view):]


def main() -> None:
    reply_fd = os.dup(1)  # the replies' pipe; what mutants print goes nowhere
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)
    serve(0, reply_fd)


if __name__ == "__main__":
    main()
