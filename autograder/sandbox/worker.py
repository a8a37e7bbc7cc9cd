"""The sandboxed worker: imports student modules and calls one function per request.

This file runs in its own process, as a copy placed in the submission's scratch
directory next to copies of ``transport.py`` and ``beginner.py`` (the sentences for
a beginner's mistakes); it imports nothing else from the grader, so the worker
never sees checks, fixtures or reference solutions.

Protocol: the parent writes length-prefixed transport frames to the request pipe
and reads one length-prefixed frame per request from the response pipe. A
request is a dict ``{"op": "import" | "call" | "variant", ...}``; the response is
``{"ok": True, "value": ..., "seconds": float}`` or
``{"ok": False, "kind": str, "message": str, "traceback": str, "seconds": float}``.
The student's stdout and stderr go to a file the parent reads after each call.

Every response carries the request's ``"id"``, so the parent can tell a reply
from a stray frame, and a ``"suspect"`` reason when the call left the worker in a
state the next call should not inherit (threads or child processes still
alive, file descriptors exhausted): the parent then starts a fresh worker.

Usage (by the parent only)::

    python -I -B worker.py REQUEST_FD RESPONSE_FD SUBMISSION_DIR OUTPUT_FILE LIMITS_JSON
"""

import builtins
import copy
import errno
import faulthandler
import hashlib
import importlib
import importlib.util
import itertools
import json
import os
import resource
import struct
import sys
import threading
import time
import traceback

_HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, _HERE)
import beginner  # noqa: E402  (the copy beside this file)
import transport  # noqa: E402  (the copy beside this file)

sys.path.remove(_HERE)
LENGTH = struct.Struct(">Q")
# Kept before any student code runs: the submission may replace the modules' own.
_active_threads, _listdir = threading.active_count, os.listdir
_open, _read, _close = os.open, os.read, os.close
_exec, _compile, _FunctionType, _ModuleType = exec, compile, type(lambda: None), type(sys)
_settrace = sys.settrace
_TRACED_LINES = 20_000   # the lines of the student's file a traced call reports, at most


def _file_bytes(path: str, limit: int = 8 * 2**20) -> bytes:
    """A file's bytes, at most ``limit``, read with the functions kept at start (a student's
    module may replace ``open``)."""
    fd = _open(path, os.O_RDONLY)
    try:
        chunks, size = [], 0
        while size <= limit:
            chunk = _read(fd, 1 << 20)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        return b"".join(chunks)[:limit]
    finally:
        _close(fd)


def _same_draws() -> None:
    """OpenCV's own random generator (cv2.drawMatches' colours, cv2.randu) set to one state before
    every call: a call's answer does not depend on the calls before it, so a variant of the student's
    code and the student's own code draw alike (a drawing of 12 matches has the first 10 colours of one
    of 10), and a grading run again says the same."""
    cv2 = sys.modules.get("cv2")
    setter = getattr(cv2, "setRNGSeed", None)
    if callable(setter):
        try:
            setter(0)
        except Exception:  # noqa: BLE001 - a student's stand-in module named cv2
            pass


def _limit_cpu(budget):
    """Let this request use ``budget`` more seconds of CPU (RLIMIT_CPU), if given."""
    if not budget:
        return
    used = resource.getrusage(resource.RUSAGE_SELF).ru_utime
    soft, hard = resource.getrlimit(resource.RLIMIT_CPU)
    new_soft = int(used + budget) + 1
    if hard != resource.RLIM_INFINITY:
        new_soft = min(new_soft, hard)
    try:
        resource.setrlimit(resource.RLIMIT_CPU, (new_soft, hard))
    except (ValueError, OSError):
        pass  # the wall-clock timeout still applies


class ForbiddenCall(BaseException):
    """Raised by a tripwire; a BaseException so `except Exception` cannot swallow it."""


class Tripwire:
    """Stands in for a forbidden function or class: calling it, or reaching into it
    (``cv2.StereoBM.create``), records the use and raises :class:`ForbiddenCall`."""

    def __init__(self, name, record):
        object.__setattr__(self, "_name", name)
        object.__setattr__(self, "_record", record)

    def _refuse(self):
        self._record.append(self._name)
        raise ForbiddenCall(self._name)

    def __call__(self, *args, **kwargs):
        self._refuse()

    def __getattr__(self, attribute):
        self._refuse()


# ------------------------------------------------------------------ set-up
def apply_limits(limits):
    """Resource limits of the worker process, set before any student code runs.

    Each limit is best effort: a platform that does not support one (macOS and
    RLIMIT_AS) keeps the others, and the wall-clock timeout always applies.
    """
    def cap(name, soft, hard=None):
        which = getattr(resource, name, None)
        if which is None or soft is None:
            return
        hard = soft if hard is None else hard
        _, current_hard = resource.getrlimit(which)
        if current_hard != resource.RLIM_INFINITY:
            soft, hard = min(soft, current_hard), min(hard, current_hard)
        try:
            resource.setrlimit(which, (int(soft), int(hard)))
        except (ValueError, OSError):
            pass

    cap("RLIMIT_AS", limits.get("address_space"))
    cap("RLIMIT_FSIZE", limits.get("file_size"))
    cap("RLIMIT_CORE", 0)
    cpu_total = limits.get("cpu_total")
    if cpu_total is not None:
        cap("RLIMIT_CPU", cpu_total, cpu_total + 5)
    cap("RLIMIT_NPROC", limits.get("processes"))  # counted by the parent: RLIMIT_NPROC is per user


# ------------------------------------------------------------------ I/O
def read_exact(fd, n):
    chunks = []
    while n:
        chunk = os.read(fd, min(n, 1 << 20))
        if not chunk:
            raise EOFError
        chunks.append(chunk)
        n -= len(chunk)
    return b"".join(chunks)


def send(fd, message, max_bytes=transport.DEFAULT_MAX_BYTES, max_elements=None):
    """Write one reply. A value that cannot cross is that call's failure, told in one sentence
    (what the function returned, and why it cannot be sent back), and the worker goes on: no
    value, whatever it is or does, ends it here. The frame is written in its parts, an
    array's bytes straight from the array (see ``transport.frame_parts``)."""
    try:
        parts = transport.frame_parts(message, max_bytes, max_elements)
    except BaseException as exc:  # noqa: BLE001 - encoding runs none of the value's code; whatever happened
        parts = [transport.encode(_failure(message, _unsendable(message.get("value"), exc)))]
    try:
        transport.write_frame(fd, LENGTH.pack(sum(len(part) for part in parts)) + parts[0])
        for part in parts[1:]:
            for piece in transport.pieces(part):
                transport.write_frame(fd, piece)
    except OSError:
        hold_still()


def _unsendable(value, exc):
    """The sentence for a reply whose ``value`` could not be encoded (``exc``)."""
    try:
        if isinstance(exc, transport.Unsendable):
            return exc.about(value, "value")
        if isinstance(exc, transport.TransportError):
            return str(exc)
        why = ("copying it out for the grader ran out of memory (MemoryError)" if isinstance(exc, MemoryError)
               else f"encoding it raised {type(exc).__name__}")
        return f"returned {transport.describe(value)}, which cannot be sent back: {why}"
    except BaseException:  # noqa: BLE001
        return "returned a value that cannot be sent back"


def _failure(message, text):
    reply = {"ok": False, "kind": "result_type", "message": text, "traceback": "",
             "seconds": message.get("seconds", 0.0), "id": message.get("id")}
    if "suspect" in message:
        reply["suspect"] = message["suspect"]
    return reply


def hold_still():
    """The grader's pipe is gone from this process (the submission closed it, or put another
    file at its descriptor). Say nothing and wait to be stopped: the grader sees the pipe
    missing from this process's descriptors, which is its evidence, and the call that did it
    is charged (a worker that ended instead could not be told from one that called exit)."""
    end = time.monotonic() + 600  # bounded: if the grader is gone too, do not stay forever
    while time.monotonic() < end:
        time.sleep(1)
    os._exit(70)


STACK_FILE = "stack.txt"   # where the call's Python stack is written, shortly before the grader stops a call


class StackAtDeadline:
    """The Python stack of a call still running shortly before the grader's deadline, written to a file
    (faulthandler's watchdog thread: it writes even while the call is inside C code, a LAPACK routine that
    never returns). The grader reads it only to say where the call was; nothing it decides rests on it."""

    def __init__(self, path):
        try:
            self.fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
        except OSError:
            self.fd = None

    def armed(self, seconds):
        return _Armed(self, seconds if type(seconds) in (int, float) and seconds > 0 else None)


class _Armed:
    def __init__(self, stack, seconds):
        self.stack, self.seconds = stack, seconds

    def __enter__(self):
        if self.stack.fd is None or self.seconds is None:
            return
        try:
            os.ftruncate(self.stack.fd, 0)
            os.lseek(self.stack.fd, 0, os.SEEK_SET)
            faulthandler.dump_traceback_later(self.seconds, repeat=False, file=self.stack.fd)
        except (OSError, ValueError, RuntimeError):
            pass

    def __exit__(self, *exc):
        if self.stack.fd is not None and self.seconds is not None:
            faulthandler.cancel_dump_traceback_later()


class CapturedOutput:
    """Point fds 1 and 2 at a fresh output file for the duration of one request."""

    def __init__(self, path):
        self.path = path

    def __enter__(self):
        for stream in (sys.stdout, sys.stderr):
            _flush(stream)
        fd = os.open(self.path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
        os.dup2(fd, 1)
        os.dup2(fd, 2)
        os.close(fd)

    def __exit__(self, *exc):
        for stream in (sys.stdout, sys.stderr):
            _flush(stream)


def _flush(stream):
    try:
        stream.flush()
    except Exception:
        pass


# ------------------------------------------------------------------ reporting
def student_traceback(exc, submission_dir):
    """The traceback restricted to frames from the student's files, paths relative."""
    frames = [f for f in traceback.extract_tb(exc.__traceback__)
              if os.path.abspath(f.filename).startswith(submission_dir + os.sep)]
    lines = []
    for f in frames:
        rel = os.path.relpath(f.filename, submission_dir)
        lines.append(f'  File "{rel}", line {f.lineno}, in {f.name}')
        if f.line:
            lines.append(f"    {f.line.strip()}")
    head = "Traceback (your code):\n" if lines else ""
    return head + "\n".join(lines + [_exception_line(exc)])


def _exception_line(exc):
    try:  # the exception is the student's: its __str__ may raise, exit or recurse
        text = str(exc)
    except BaseException:  # noqa: BLE001
        text = "(its message could not be read: str() of it raised)"
    if type(text) is not str:
        text = ""
    if len(text) > 2000:  # a reply's text stays small (the grader keeps 2000 characters)
        text = text[:2000] + f"... ({len(text) - 2000} more characters)"
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def explained(exc, arguments=()):
    """The beginner's sentence for ``exc`` and a newline (an OpenCV error explained from the
    arguments given, ``image[x, y]`` for ``image[y, x]``...), or ``""``; never raises."""
    try:
        sentence = beginner.sentence_of(exc)
        if not sentence and isinstance(exc, IndexError):
            sentence = beginner.explain_index_error(str(exc), list(arguments))
    except BaseException:  # noqa: BLE001 - the student's code may have broken anything
        return ""
    return sentence + "\n" if sentence else ""


def failure(kind, message, tb="", seconds=0.0):
    return {"ok": False, "kind": kind, "message": message, "traceback": tb, "seconds": seconds}


# ------------------------------------------------------------------ around each call
def snapshot_arrays(args, kwargs):
    """``(position or keyword, index in a list or None, array, copy)`` for each argument array
    (and each array in a list argument, e.g. ``images``), to compare after the call."""
    import numpy
    snapshot = []
    for key, value in list(enumerate(args)) + list(kwargs.items()):
        items = enumerate(value) if isinstance(value, (list, tuple)) else [(None, value)]
        snapshot += [(key, index, item, item.copy()) for index, item in items
                     if isinstance(item, numpy.ndarray)]
    return snapshot


def modified_arguments(function, snapshot):
    """Names of the argument arrays the call changed in place (callers do not expect that)."""
    try:  # the student's code may have broken anything; this is advice, never a failure
        changed = [(key, index) for key, index, value, before in snapshot
                   if value.shape != before.shape or value.tobytes() != before.tobytes()]
        if not changed:
            return []
        import inspect
        try:
            parameters = [p.name for p in inspect.signature(function).parameters.values()
                          if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
        except (TypeError, ValueError):
            parameters = []
        names = [(key if isinstance(key, str) else
                  parameters[key] if key < len(parameters) else f"argument {key + 1}", index)
                 for key, index in changed]
        return [name if index is None else f"{name}[{index}]" for name, index in names]
    except BaseException:  # noqa: BLE001
        return []


def module_array_returned(module, value, most: int = 2000) -> tuple:
    """(name, array) of a module-level array the returned value is, or views (``M = _IDENTITY; M[0, 2] = tx;
    return M``), else ("", None): the first ``most`` names of the module looked at; never raises."""
    np = sys.modules.get("numpy")   # (an array returned means NumPy is loaded; nothing is imported for this)
    if np is None:
        return "", None
    try:
        results = value if type(value) is tuple else (value,)
        arrays = [r for r in results[:8] if type(r) is np.ndarray]
        if not arrays:
            return "", None
        # (the namespace read in place, its first `most` names only: a student's thread changing it makes the
        # iteration raise, which reports nothing)
        for key, held in itertools.islice(iter(vars(module).items()), most):
            if type(key) is str and type(held) is np.ndarray and held.size \
                    and any(np.may_share_memory(a, held) for a in arrays):
                return key[:80], held
    except Exception:  # noqa: BLE001 - a module's namespace is the student's: nothing in it stops the reply
        return "", None
    return "", None


CHANGED_BYTES = 8 * 2**20   # the most bytes of changed argument arrays sent back with a reply


def changed_arrays(snapshot, max_bytes=CHANGED_BYTES):
    """``[[position or keyword, index in a list or None, array], ...]``: each argument array the
    call changed in place, as its caller holds it now (numbers only, ``max_bytes`` in all) -- what
    a second call on the same array would be given (the grader makes that call, see
    :meth:`autograder.engine.checks.Trial.call`)."""
    try:  # the student's code may have broken anything; never a failure of the call
        import numpy
        out, total = [], 0
        for key, index, value, before in snapshot:
            if value.shape == before.shape and value.tobytes() == before.tobytes():
                continue
            if value.dtype.kind not in "biuf" or total + value.nbytes > max_bytes:
                continue
            total += value.nbytes
            out.append([key, index, numpy.array(value, subok=False)])
        return out
    except BaseException:  # noqa: BLE001
        return []


def close_figures():
    """Close every Matplotlib figure the call opened: the sheet asks for plots, the grader
    shows none (the backend is Agg, so ``plt.show()`` opens no window), and open figures
    would only accumulate memory over hundreds of calls."""
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None:
        try:
            pyplot.close("all")
        except BaseException:  # noqa: BLE001 - a student's broken pyplot is not the grader's error
            pass


def headless_matplotlib():
    """Agg backend whatever the environment or the student says, ``plt.show()`` silent.

    There is no display here: ``matplotlib.use("TkAgg")`` in a student's module
    would make pyplot raise, so once Matplotlib is imported (lazily: importing it
    costs most of a second) ``matplotlib.use`` keeps Agg.
    """
    import warnings
    os.environ["MPLBACKEND"] = "Agg"
    warnings.filterwarnings("ignore", message=r".*(non-GUI backend|non-interactive)")
    sys.meta_path.insert(0, _KeepAgg())


class _KeepAgg:
    """Import hook: the imported ``matplotlib`` gets a ``use`` that changes nothing."""

    def find_spec(self, name, path=None, target=None):
        if name != "matplotlib":
            return None
        sys.meta_path.remove(self)  # once, and no recursion through the lookup below
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.loader is not None:
            execute = spec.loader.exec_module

            def exec_module(module):
                execute(module)
                module.use = lambda backend, *args, **kwargs: None

            spec.loader.exec_module = exec_module
        return spec


# ------------------------------------------------------------------ the worker
class Worker:
    def __init__(self, submission_dir, file_size_mb=None, max_result_bytes=transport.DEFAULT_MAX_BYTES,
                 max_result_elements=None):
        self.submission_dir = os.path.abspath(submission_dir)
        self.file_size_mb = file_size_mb
        self.max_result_bytes = max_result_bytes
        self.max_result_elements = max_result_elements  # the grader checks it too: this only saves a restart
        self.modules = {}
        self.forbidden_called = []
        self.memo = _Memo()   # the variants' calls of the student's unchanged helpers (see handle_variant)
        self.handed_out = {}  # module-level array name -> the array a call last returned (see _handed_out_again)

    # -- import
    def load(self, name):
        if name in self.modules:
            return self.modules[name]
        path_py = os.path.join(self.submission_dir, name + ".py")
        path_pkg = os.path.join(self.submission_dir, name, "__init__.py")
        if not (os.path.isfile(path_py) or os.path.isfile(path_pkg)):
            raise LookupError(name)
        importlib.invalidate_caches()  # the files may have arrived after this worker started
        module = importlib.import_module(name)
        self.modules[name] = module
        return module

    def handle_import(self, name):
        start = time.perf_counter()
        try:
            self.load(name)
        except LookupError:
            return failure("missing_module", f"module {name}.py not found")
        except SyntaxError as exc:
            return failure("import_error", self._syntax_message(exc, name),
                           seconds=time.perf_counter() - start)
        except SystemExit as exc:
            return failure("import_error",
                           f"{name}.py called sys.exit({exc.code!r}) while being imported; "
                           "remove top-level code that exits",
                           seconds=time.perf_counter() - start)
        except MemoryError as exc:
            return failure("memory", f"{name}.py ran out of memory while being imported",
                           student_traceback(exc, self.submission_dir),
                           time.perf_counter() - start)
        except BaseException as exc:  # noqa: BLE001 - anything the student's import raises
            return failure("import_error",
                           f"{explained(exc)}{name}.py failed to import: {_exception_line(exc)}",
                           student_traceback(exc, self.submission_dir),
                           time.perf_counter() - start)
        return {"ok": True, "value": None, "seconds": time.perf_counter() - start}

    def _syntax_message(self, exc, name):
        filename = os.path.relpath(exc.filename, self.submission_dir) if exc.filename else name + ".py"
        where = f"{filename}, line {exc.lineno}"
        text = (exc.text or "").rstrip("\n")
        pointer = ""
        if text and exc.offset:
            stripped = text.lstrip()
            pointer = "\n    " + stripped + "\n    " + " " * max(exc.offset - 1 - (len(text) - len(stripped)), 0) + "^"
        return f"{type(exc).__name__} in {where}: {exc.msg}{pointer}"

    # -- call
    def handle_call(self, request):
        module_name, name = request["module"], request["function"]
        try:
            module = self.load(module_name)
        except BaseException:  # the parent imports first; this is a fallback
            return self.handle_import(module_name)
        function = getattr(module, name, None)
        if not callable(function):
            return failure("missing_function", f"function {name} not found in {module_name}.py")
        _limit_cpu(request.get("cpu_seconds"))
        self.forbidden_called = []
        args, kwargs = request.get("args", ()), request.get("kwargs", {})
        inputs = snapshot_arrays(args, kwargs)
        restore = self.install_tripwires(request.get("forbid") or [])
        start = time.perf_counter()
        try:
            _same_draws()
            value = function(*args, **kwargs)
        except ForbiddenCall as exc:
            return failure("forbidden_call", self._forbidden_message(str(exc), name),
                           seconds=time.perf_counter() - start)
        except NotImplementedError:
            return failure("not_implemented", f"{name}() is not implemented yet",
                           seconds=time.perf_counter() - start)
        except OSError as exc:
            if exc.errno == errno.EFBIG:  # RLIMIT_FSIZE: printed or wrote too much
                return failure("output_too_large",
                               f"{name}() printed or wrote more than {self.file_size_mb} MB",
                               seconds=time.perf_counter() - start)
            return failure("exception", f"{name}() raised {_exception_line(exc)}",
                           student_traceback(exc, self.submission_dir), time.perf_counter() - start)
        except MemoryError as exc:
            return failure("memory", f"{name}() ran out of memory",
                           student_traceback(exc, self.submission_dir), time.perf_counter() - start)
        except RecursionError as exc:
            return failure("recursion", f"{name}() recursed too deeply (infinite recursion?)",
                           student_traceback(exc, self.submission_dir), time.perf_counter() - start)
        except SystemExit as exc:
            return failure("exception", f"{name}() called sys.exit({exc.code!r})",
                           student_traceback(exc, self.submission_dir), time.perf_counter() - start)
        except BaseException as exc:  # noqa: BLE001
            sentence = explained(exc, list(args) + list(kwargs.values()))
            return failure("exception", f"{sentence}{name}() raised {_exception_line(exc)}",
                           student_traceback(exc, self.submission_dir), time.perf_counter() - start)
        finally:
            seconds = time.perf_counter() - start
            restore()
        if self.forbidden_called:  # the student swallowed the tripwire's exception
            return failure("forbidden_call", self._forbidden_message(self.forbidden_called[0], name),
                           seconds=seconds)
        return {"ok": True, "value": value, "seconds": seconds,
                "modified": modified_arguments(function, inputs), "changed": changed_arrays(inputs),
                "shared": self._handed_out_again(module, value)}

    def _handed_out_again(self, module, value) -> str:
        """The name of a module-level array the value is or views, when an earlier call returned that same
        array object too (one array handed to every caller; a global rebound to a new array each call is
        not); "" otherwise."""
        name, held = module_array_returned(module, value)
        if not name:
            return ""
        again = self.handed_out.get(name) is held
        self.handed_out[name] = held
        return name if again else ""

    # -- a variant: the student's functions with some of their defs rewritten by the grader
    def handle_variant(self, request):
        """Call ``function`` of a *variant* of the student's module on each of ``calls``.

        The variant is the imported module with the defs in ``source`` (the grader's rewrite of
        the student's own functions: one small change, to see whether it repairs the answers)
        executed over a copy of its namespace; every function of the copy sees the copy, so a
        changed helper is the one the unchanged functions call. With ``"fresh": true`` it is the
        module's own file executed anew, in a namespace of its own (the module as a first call finds
        it: no cache or list an earlier call filled). The module itself is left as it was. The value
        is one entry per call: its result, or ``{"__error__": "Type: text"}``.
        """
        try:
            base = self.load(request["module"])
        except BaseException:  # the parent imports first; this is a fallback
            return self.handle_import(request["module"])
        start = time.perf_counter()
        fresh = bool(request.get("fresh"))
        try:   # (what the import left under the module's name may be any object of the student's)
            variant = _ModuleType(str(getattr(base, "__name__", request["module"])))
            own = vars(base)
            space = vars(variant)
            if fresh:   # the module's whole file run anew: nothing an earlier call left in it is there
                space.update({key: own[key] for key in ("__file__", "__package__", "__spec__", "__loader__")
                              if key in own})
                _exec(_compile(_file_bytes(own["__file__"]), own["__file__"], "exec"), space)
            else:
                space.update(own)
                _exec(_compile(request["source"], getattr(base, "__file__", None) or "<variant>", "exec"), space)
        except BaseException as exc:  # noqa: BLE001 - a rewrite that cannot run is no variant
            return failure("exception", f"the variant did not run: {_exception_line(exc)}")
        # A helper the rewrite leaves as it was, calling nothing it changed, answers the same arguments
        # as it did for the variant before: its answer is kept and given again (a panorama's feature
        # matching, run once for the many changes of its compositing, instead of once for each).
        unchanged = _unchanged(own, space) if request["source"] and not fresh else set()
        forbid = tuple(request.get("forbid") or ())
        for key, value in list(space.items()):   # the copy's functions read the copy's globals
            if isinstance(value, _FunctionType) and value.__globals__ is own:
                rebound = _FunctionType(value.__code__, space, value.__name__, value.__defaults__, value.__closure__)
                rebound.__kwdefaults__ = value.__kwdefaults__
                space[key] = rebound if key not in unchanged or key == request["function"] \
                    else self.memo.wrapped(rebound, key, forbid)
        function = space.get(request["function"])
        if not callable(function):
            return failure("missing_function", f"function {request['function']} not found in the variant")
        _limit_cpu(request.get("cpu_seconds"))
        key = f"{base.__name__} (variant)"
        self.modules[key] = variant   # so that the tripwires reach names it imported itself
        restore = self.install_tripwires(request.get("forbid") or [])
        values, modified = [], []
        traced = _LineTrace(getattr(base, "__file__", None)) \
            if request.get("trace") and not request["source"] and not fresh else None
        try:
            for number, (args, kwargs) in enumerate(request.get("calls", ())):
                self.forbidden_called = []
                inputs = snapshot_arrays(args, kwargs)
                try:
                    if traced is not None:
                        _settrace(traced.enter)
                    _same_draws()
                    value = function(*args, **kwargs)
                    # (a variant that writes into its caller's arrays mends nothing a caller can use)
                    modified += [f"{number}:{name}" for name in modified_arguments(function, inputs)]
                except BaseException as exc:  # noqa: BLE001 - the variant's exception is its answer
                    value = {"__error__": _exception_line(exc)[:300]}
                finally:
                    if traced is not None:
                        _settrace(None)
                if self.forbidden_called:
                    value = {"__error__": f"ForbiddenCall: {self.forbidden_called[0]}"}
                values.append(value)
        finally:
            restore()
            del self.modules[key]
        if traced is not None:   # (the lines its own code ran: the grader skips changes of others)
            values = {"values": values, "lines": sorted(traced.lines)}
        return {"ok": True, "value": values, "seconds": time.perf_counter() - start, "modified": modified}

    @staticmethod
    def _forbidden_message(qualified, function_name):
        return (f"{function_name}() called {qualified}, which this exercise asks you "
                "to implement yourself")

    def install_tripwires(self, forbidden):
        """Replace each forbidden library function or class by a :class:`Tripwire`.

        Names the student imported directly (``from cv2 import findHomography``)
        are replaced in the student's modules too. Returns an undo function.
        """
        undo = []
        for qualified in forbidden:
            module_name, _, attr = qualified.rpartition(".")
            try:
                library = importlib.import_module(module_name)
                original = getattr(library, attr)
            except (ImportError, AttributeError):
                continue

            tripwire = Tripwire(qualified, self.forbidden_called)
            setattr(library, attr, tripwire)
            undo.append((library, attr, original))
            for module in self.modules.values():
                for key, val in list(vars(module).items()):
                    if val is original:
                        setattr(module, key, tripwire)
                        undo.append((module, key, original))

        def restore():
            for owner, attr, original in reversed(undo):
                setattr(owner, attr, original)

        return restore

    def serve(self, request_fd, response_fd, output_path):
        # The worker's own code must keep working whatever the submission does to
        # builtins (isinstance, len...): restore them after every request.
        namespace = builtins.__dict__
        pristine_builtins = dict(namespace)
        stack = StackAtDeadline(os.path.join(os.path.dirname(output_path), STACK_FILE))
        while True:
            try:
                length, = LENGTH.unpack(read_exact(request_fd, LENGTH.size))
                request = transport.decode(read_exact(request_fd, length))
            except EOFError:
                return
            except OSError:  # the request pipe was closed under the worker
                hold_still()
            with CapturedOutput(output_path), stack.armed(request.get("stack_after")):
                if request.get("op") == "import":
                    response = self.handle_import(request["module"])
                elif request.get("op") == "call":
                    response = self.handle_call(request)
                elif request.get("op") == "variant":
                    response = self.handle_variant(request)
                else:
                    response = failure("protocol", f"unknown op {request.get('op')!r}")
                close_figures()
            namespace.clear()
            namespace.update(pristine_builtins)
            response["id"] = request.get("id")
            reason = suspect_state()
            if reason:
                response["suspect"] = reason
            # (a reply as large as the grader takes for this call: what it was given decides -- see
            # supervisor.answer_cap; the grader holds to it whatever this process does)
            asked = request.get("max_bytes")
            largest = min(self.max_result_bytes, asked) if type(asked) is int and asked > 0 else self.max_result_bytes
            send(response_fd, response, largest, self.max_result_elements)
            # Nothing of this call is held while the worker waits: the grader weighs what the
            # worker holds now (memory a call keeps would be the next call's missing).
            request = response = None


def _names_used(code) -> set:
    """The global names a function's code (and the code nested in it) reads."""
    names = set(code.co_names)
    for constant in code.co_consts:
        if isinstance(constant, type(code)):
            names |= _names_used(constant)
    return names


def _unchanged(own, space) -> set:
    """The student's functions that a variant's rewrite (``space``: ``own`` with its defs executed over
    it) leaves as they were, and that call none of those it changed, however indirectly."""
    functions = {key: value for key, value in space.items() if isinstance(value, _FunctionType)}
    dirty = {key for key, value in functions.items() if value is not own.get(key)}
    used = {key: _names_used(value.__code__) for key, value in functions.items() if key not in dirty}
    grown = True
    while grown:
        grown = False
        for key, names in used.items():
            if key not in dirty and names & dirty:
                dirty.add(key)
                grown = True
    return {key for key, value in functions.items() if key not in dirty and value.__globals__ is own}


class _Memo:
    """The answers of the student's unchanged helpers in a companion's variants, by their arguments
    (arrays by their bytes), given again as copies. Kept only for calls that left their arguments as
    they were and raised nothing, at most :data:`ENTRIES` answers of :data:`BYTES` in all; it lives
    in the companion worker of one sandbox (one phase of one grading) and dies with it."""

    ENTRIES, BYTES = 256, 32 * 2**20

    def __init__(self):
        self.answers, self.size = {}, 0

    def wrapped(self, function, name, forbid):
        memo = self

        def remembered(*args, **kwargs):
            key = _memo_key((name, forbid, args, kwargs))
            if key is not None and key in memo.answers:
                return _copied(memo.answers[key])
            snapshot = snapshot_arrays(args, kwargs) if key is not None else None
            value = function(*args, **kwargs)
            if key is not None and len(memo.answers) < memo.ENTRIES and not modified_arguments(function, snapshot):
                size = _bytes_of(value)   # (measured before any copy: an answer too large is never copied)
                kept = _copied(value) if size is not None and memo.size + size <= memo.BYTES else _UNCOPIED
                if kept is not _UNCOPIED:
                    memo.answers[key], memo.size = kept, memo.size + size
            return value
        return remembered


_UNCOPIED = object()


def _copied(value):
    try:
        return copy.deepcopy(value)
    except Exception:  # noqa: BLE001 - an answer that cannot be copied is not kept
        return _UNCOPIED


def _bytes_of(value, depth=0):
    """The bytes of the arrays in an answer (and a little for the rest); None for an object of the
    student's own kind (its size unknown)."""
    import numpy
    if depth > 6:
        return None
    if isinstance(value, numpy.ndarray):
        return value.nbytes if value.dtype.kind != "O" else None
    if value is None or isinstance(value, (bool, int, float, complex, str, bytes, numpy.generic)):
        return 64 + (len(value) if isinstance(value, (str, bytes)) else 0)
    if isinstance(value, (tuple, list)):
        sizes = [_bytes_of(item, depth + 1) for item in value]
        return None if None in sizes else 64 + sum(sizes)
    if isinstance(value, dict):
        sizes = [_bytes_of(item, depth + 1) for pair in value.items() for item in pair]
        return None if None in sizes else 64 + sum(sizes)
    return None


def _memo_key(value, depth=0):
    """A key standing for an argument (an array by its dtype, shape and bytes), or None."""
    import numpy
    if depth > 6:
        return None
    if value is None or isinstance(value, (bool, int, float, complex, str, bytes)):
        return (type(value).__name__, value)
    if isinstance(value, numpy.generic):
        return (type(value).__name__, value.item())
    if isinstance(value, numpy.ndarray):
        if value.dtype.kind not in "biufc":
            return None
        digest = hashlib.blake2b(numpy.ascontiguousarray(value).tobytes(), digest_size=16).hexdigest()
        return ("ndarray", value.dtype.str, value.shape, digest)
    if isinstance(value, (tuple, list)):
        items = tuple(_memo_key(item, depth + 1) for item in value)
        return None if any(item is None for item in items) else (type(value).__name__, items)
    if isinstance(value, dict):
        items = tuple(sorted(((repr(k), _memo_key(v, depth + 1)) for k, v in value.items()), key=lambda item: item[0]))
        return None if any(item[1] is None for item in items) else ("dict", items)
    return None


class _LineTrace:
    """The lines of one file (the student's module) that a call runs, for ``sys.settrace``. The
    student's code may stop the trace: it only loses the grader's shortcut."""

    def __init__(self, filename):
        self.filename, self.lines = filename, set()

    def enter(self, frame, event, arg):
        return self.line if frame.f_code.co_filename == self.filename else None

    def line(self, frame, event, arg):
        if event == "line" and len(self.lines) < _TRACED_LINES:
            self.lines.add(frame.f_lineno)
        return self.line


def suspect_state():
    """Why the next call should not run in this process, or ``""``."""
    if _active_threads() > 1:
        return "threads still running after the call"
    try:
        for task in _listdir("/proc/self/task"):
            fd = _open(f"/proc/self/task/{task}/children", os.O_RDONLY)
            try:
                if _read(fd, 64).strip():
                    return "child processes still running after the call"
            finally:
                _close(fd)
    except OSError:
        pass  # no /proc (macOS): threads and descriptors are still checked
    try:
        _close(_open(os.devnull, os.O_RDONLY))
    except OSError:
        return "file descriptors exhausted"
    return ""


def main(argv):
    request_fd, response_fd = int(argv[1]), int(argv[2])
    submission_dir, output_path = argv[3], argv[4]
    limits = json.loads(argv[5])
    apply_limits(limits)
    headless_matplotlib()
    # The worker's own imports come first, while the submission is not on sys.path:
    # a cv2.py or numpy.py handed in cannot run before the worker is ready.
    import numpy  # noqa: F401  (warm: the first student call should not pay for it)
    try:
        import cv2
    except ImportError:
        pass
    else:
        if limits.get("threads"):
            cv2.setNumThreads(limits["threads"])  # the cores are shared with other workers
        beginner.watch(cv2)  # an error inside an OpenCV function then says what was wrong with its arguments
    sys.path.insert(0, os.path.abspath(submission_dir))
    send(response_fd, {"ok": True, "value": "ready", "seconds": 0.0})  # start-up done
    file_size_mb = (limits.get("file_size") or 0) // 2**20 or None
    max_result_bytes = limits.get("max_result_bytes") or transport.DEFAULT_MAX_BYTES
    Worker(submission_dir, file_size_mb, max_result_bytes,
           limits.get("max_result_elements")).serve(request_fd, response_fd, output_path)


if __name__ == "__main__":
    main(sys.argv)
