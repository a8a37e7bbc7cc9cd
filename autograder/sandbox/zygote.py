"""A warm template for workers: each worker forked from it, confined as a started one is.

Starting a worker costs a quarter of a second, most of it the interpreter importing NumPy and OpenCV;
a grading starts two to five. This process, started once per grading process by the grader
(:class:`autograder.sandbox.supervisor.Template`), imports them once -- and the worker's own code, from a
private copy beside this file -- then serves requests to start a worker. It runs no student code, is
given no input, holds no answer: a request is read by the forked child alone, never by this process,
so what one worker's start carried (its folders, its view) is in no later worker's memory.

Each worker is built as :meth:`autograder.sandbox.confine.Confinement.wrap` builds one with ``unshare``,
``namespace_init.py`` and ``setpriv``, in the same order, by the same code where it can be:

1. the child (the process the grader holds, its own session) asks to die with this process, joins
   the worker's cgroup, enters an unprivileged user namespace where the grader is not root (mapped
   to the grader's ids, as ``unshare --map-root-user``), then new mount, PID, network, IPC and UTS
   namespaces, forks PID 1 of them, tells the grader its pid, and waits for PID 1 (its exit status
   is the worker's: ``128 + n`` for a signal ``n``; written to the grader's status pipe);
2. PID 1 builds the worker's file system (:func:`namespace_init.build`), forks the worker and reaps
   every process of the namespace until the worker ends;
3. the worker drops every capability and the bounding set, takes the worker's user where the level
   has one, sets no-new-privileges, puts back the interpreter's start as ``python -I -B worker.py``
   has it inside its view (the environment, ``sys.path`` made by ``site`` from the view's own
   site-packages, fresh random states), and runs :func:`worker.main`.

Usage (by the grader only)::

    python -I -B -S zygote.py CONTROL_FD
"""

import ctypes
import fcntl
import json
import os
import platform
import signal
import socket
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
_BASE_PATH = list(sys.path)        # (-S: the standard library only; site's folders come inside each view)
_BASE_META_PATH, _BASE_PATH_HOOKS = list(sys.meta_path), list(sys.path_hooks)

import site  # noqa: E402

site.main()   # the grader's site-packages, for the imports below (a view's own are read again in each worker)
import numpy  # noqa: E402,F401  (warm: what every worker would import first)

try:
    import cv2  # noqa: F401
except ImportError:
    pass
sys.path.insert(0, _HERE)
import namespace_init  # noqa: E402  (the copies beside this file)
import worker  # noqa: E402

_libc = ctypes.CDLL(None, use_errno=True)
CLONE_NEWNS, CLONE_NEWUTS, CLONE_NEWIPC = 0x00020000, 0x04000000, 0x08000000
CLONE_NEWUSER, CLONE_NEWPID, CLONE_NEWNET = 0x10000000, 0x20000000, 0x40000000
PR_SET_PDEATHSIG, PR_SET_NAME, PR_CAPBSET_DROP, PR_SET_NO_NEW_PRIVS = 1, 15, 24, 38
SYS_CAPSET = {"x86_64": 126, "aarch64": 91, "arm64": 91, "ppc64le": 184, "s390x": 185}
CAP_VERSION_3 = 0x20080522
MAX_REQUEST = 1 << 20


def _check(result, what):
    if result != 0:
        errno = ctypes.get_errno()
        raise OSError(errno, f"{what}: {os.strerror(errno)}")


def _die_with_parent(parent: int | None) -> None:
    """SIGKILL when the parent ends (``parent``: its pid, to see it has not already; None where this process
    cannot see it, as PID 1 of a namespace)."""
    _check(_libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0), "prctl(PR_SET_PDEATHSIG)")
    if parent is not None and os.getppid() != parent:   # (it ended before the signal was asked for)
        os._exit(137)


def _named(name: str) -> None:
    """The process's name (``ps``, /proc/PID/comm): its command line is the template's."""
    _libc.prctl(PR_SET_NAME, name.encode(), 0, 0, 0)


def _last_capability() -> int:
    with open("/proc/sys/kernel/cap_last_cap") as last:
        return int(last.read())


def _drop_bounding_set(last: int) -> None:
    """Empty the capability bounding set (as ``setpriv --bounding-set=-all``)."""
    for capability in range(last + 1):
        _check(_libc.prctl(PR_CAPBSET_DROP, capability, 0, 0, 0), f"prctl(PR_CAPBSET_DROP, {capability})")


def _capset_nothing() -> None:
    """Hold no capability, effective, permitted or inheritable (``--inh-caps=-all``; a root worker's exec with
    an empty bounding set would have lost the others)."""
    number = SYS_CAPSET.get(platform.machine())
    if number is None:
        raise OSError(f"capset: unknown system call number on {platform.machine()}")
    header = (ctypes.c_uint32 * 2)(CAP_VERSION_3, 0)
    data = (ctypes.c_uint32 * 6)()   # two of {effective, permitted, inheritable}: all empty
    _check(_libc.syscall(number, header, data), "capset")


def _status_of(path: str) -> dict:
    with open(path) as status:
        return dict(line.split(":", 1) for line in status if ":" in line)


def _write(path: str, text: str) -> None:
    with open(path, "w") as out:
        out.write(text)


def _keep_only(fds) -> None:
    """Close every descriptor but ``fds`` and the standard ones (the control socket above all)."""
    low = 3
    for fd in sorted(fd for fd in set(fds) if fd >= 3):
        if low < fd:   # (never os.closerange(n, n): Python asks close_range(n, n - 1), which wraps to every descriptor)
            os.closerange(low, fd)
        low = fd + 1
    os.closerange(low, max(low + 1, os.sysconf("SC_OPEN_MAX")))


def _start(control: socket.socket, consumed: int, template: int, last_capability: int) -> None:
    """The forked child: read one request, build the worker's namespaces, tell the grader, wait."""
    signal.signal(signal.SIGCHLD, signal.SIG_DFL)
    _named("ag-sandbox")
    message, fds, _, _ = socket.recv_fds(control, MAX_REQUEST, 8)
    os.write(consumed, b"x")     # (the template may read its socket again: this request is taken)
    os.close(consumed)
    try:
        request = json.loads(message)
        request_fd, response_fd, log_fd, status_fd = fds
        os.setsid()
        _die_with_parent(template)
        for procs in request["cgroup_procs"]:
            _write(procs, str(os.getpid()))
        if request["map_root"]:   # (an unprivileged grader: root of a user namespace of its own, as --map-root-user)
            uid, gid = os.getuid(), os.getgid()
            _check(_libc.unshare(CLONE_NEWUSER), "unshare(user)")
            _write("/proc/self/setgroups", "deny")
            _write("/proc/self/uid_map", f"0 {uid} 1")
            _write("/proc/self/gid_map", f"0 {gid} 1")
        _check(_libc.unshare(CLONE_NEWNS | CLONE_NEWPID | CLONE_NEWNET | CLONE_NEWIPC | CLONE_NEWUTS), "unshare")
        outer = os.getpid()
        init = os.fork()
    except BaseException as exc:   # noqa: BLE001 - told to the grader, which starts this worker the other way
        control.send(json.dumps({"error": f"{type(exc).__name__}: {exc}"}).encode())
        os._exit(127)
    if init == 0:
        _pid_one(request, (request_fd, response_fd, log_fd), last_capability)
    control.send(json.dumps({"pid": outer}).encode())
    control.close()
    _keep_only((status_fd,))
    _, status = os.waitpid(init, 0)
    code = os.waitstatus_to_exitcode(status)
    code = 128 - code if code < 0 else code
    try:
        os.write(status_fd, code.to_bytes(4, "big", signed=True))
    finally:
        os._exit(code)


def _pid_one(request: dict, fds, last_capability: int) -> None:
    """PID 1 of the worker's namespaces: its file system, then the worker, reaped with every orphan."""
    try:
        _named("ag-init")
        _die_with_parent(None)
        _keep_only(fds)
        os.chdir(request["cwd"])
        namespace_init.build(request["ops"])
        child = os.fork()
    except BaseException:   # noqa: BLE001 - the grader sees the worker never say it is ready, and the log
        _traceback_to(fds[2])
        os._exit(127)
    if child == 0:
        _worker(request, fds, last_capability)
    for fd in fds:   # (the worker's alone: its end is the pipes' end)
        os.close(fd)
    os._exit(namespace_init.reap(child))


def _traceback_to(fd: int) -> None:
    import traceback
    try:
        os.write(fd, traceback.format_exc().encode(errors="replace")[-4000:])
    except OSError:
        pass


def _worker(request: dict, fds, last_capability: int) -> None:
    """The worker itself: no privilege left, the interpreter as a fresh start would have it, then its loop."""
    try:
        _named("ag-worker")
        # The pipes at the numbers the grader gave them (it looks for them there, see Sandbox._pipe_taken), the
        # log as standard output and error: each moved out of the way first, so no number is taken twice.
        request_fd, response_fd = request["fds"]
        clear = max(*fds, request_fd, response_fd) + 1
        moved = [fcntl.fcntl(fd, fcntl.F_DUPFD, clear) for fd in fds]
        for fd in fds:
            os.close(fd)
        for fd, target in zip(moved, (request_fd, response_fd, 1)):
            os.dup2(fd, target)
        os.dup2(moved[2], 2)
        for fd in moved:
            os.close(fd)
        null = os.open(os.devnull, os.O_RDONLY)
        os.dup2(null, 0)
        os.close(null)
        _drop_bounding_set(last_capability)
        if request["uid"] is not None:
            os.setgroups([])
            os.setresgid(request["gid"], request["gid"], request["gid"])
            os.setresuid(request["uid"], request["uid"], request["uid"])
        _check(_libc.prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0), "prctl(PR_SET_NO_NEW_PRIVS)")
        _capset_nothing()
        status = _status_of("/proc/self/status")
        held = [name for name in ("CapEff", "CapPrm", "CapInh", "CapBnd", "CapAmb")
                if int(status.get(name, "0").strip() or "0", 16)]
        if held or status.get("NoNewPrivs", "").strip() != "1":
            raise OSError(f"privileges left: {held or 'no NoNewPrivs'}")
        _as_started(request)
    except BaseException:   # noqa: BLE001 - never run the worker with what could not be dropped
        _traceback_to(2)
        os._exit(127)
    code = 0
    try:
        worker.main(list(sys.argv))
    except SystemExit as stop:
        code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
    except BaseException:   # noqa: BLE001 - as an interpreter would: the traceback on stderr, status 1
        _traceback_to(2)
        code = 1
    finally:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except Exception:   # noqa: BLE001
                pass
        os._exit(code)


def _as_started(request: dict) -> None:
    """What ``python -I -B worker.py`` would have at its start inside this view: its environment, its
    arguments, ``sys.path`` as ``site`` makes it from the view's own site-packages (the grader's own
    ``.pth`` files are not there), random states of its own, and the worker's code as ``__main__``."""
    import importlib
    import random

    os.environ.clear()
    os.environ.update(request["environment"])
    sys.argv = [request["script"], *map(str, request["fds"]), *request["arguments"]]
    sys.path[:] = [os.path.dirname(request["script"]), *_BASE_PATH[1:]]
    sys.meta_path[:], sys.path_hooks[:] = _BASE_META_PATH, _BASE_PATH_HOOKS   # (an editable install's finder is the grader's)
    sys.path_importer_cache.clear()
    for name in [name for name in sys.modules if name.startswith("__editable__")]:
        del sys.modules[name]
    site.main()
    importlib.invalidate_caches()
    random.seed()
    numpy.random.seed()
    worker.__name__ = "__main__"      # (the script a started worker runs is its __main__)
    sys.modules["__main__"] = worker


def serve(control: socket.socket) -> None:
    """Fork a child for each request; the child reads it. Ends when the grader closes its end."""
    template = os.getpid()
    last_capability = _last_capability()
    _named("ag-template")

    def reap(*_):
        while True:
            try:
                pid, _ = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                return
            if pid == 0:
                return

    signal.signal(signal.SIGCHLD, reap)
    while True:
        try:
            waiting = control.recv(1, socket.MSG_PEEK)
        except InterruptedError:
            continue
        if not waiting:
            return
        consumed_r, consumed_w = os.pipe()
        child = os.fork()
        if child == 0:
            os.close(consumed_r)
            try:
                _start(control, consumed_w, template, last_capability)
            finally:
                os._exit(127)
        os.close(consumed_w)
        os.read(consumed_r, 1)
        os.close(consumed_r)


if __name__ == "__main__":
    serve(socket.socket(fileno=int(sys.argv[1])))
