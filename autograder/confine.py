"""How the worker process is confined, chosen by what the platform allows.

Three levels, strongest first; :func:`detect` probes them once per process and
keeps the first that really starts Python:

``namespaces+user``
    The grader runs as root (a course container). The worker starts in new PID,
    network and mount namespaces (``unshare``), with the grader's sources
    (``autograder/``, ``fixtures/``, ``reference_solutions/``, results folders)
    covered by empty read-only mounts, then drops to the unprivileged user
    ``agworker`` (created if missing; ``nobody`` otherwise) with no capabilities.
    It sees no grader process, has no network, cannot read the answers, and the
    whole namespace (daemons included) dies with it.
``namespaces``
    The same namespaces and hidden folders, without changing user: as root when
    the interpreter is not readable by another user (Python under ``/root``), or
    through an unprivileged user namespace on a student's Linux laptop. Every
    capability is dropped, so the hiding mounts cannot be undone.
``process-group``
    Best effort (macOS, or Linux without namespaces): the worker gets its own
    session, the grader becomes a child subreaper so double-forked daemons are
    re-parented to it and killed, and the resource limits still apply. No
    network isolation, and the worker can read what the user can.

``AUTOGRADER_CONFINEMENT=process-group`` (or another level) forces a level.
"""

from __future__ import annotations

import ctypes
import os
import pwd
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

LEVELS = ("namespaces+user", "namespaces", "process-group")
WORKER_USER = "agworker"
_PR_SET_CHILD_SUBREAPER = 36


@dataclass(frozen=True)
class Confinement:
    """A confinement level and, for ``namespaces+user``, the worker's uid/gid."""

    level: str
    uid: int | None = None
    gid: int | None = None
    reexpose: tuple[Path, ...] = ()   # interpreter folders under a folder the worker's user cannot enter

    def wrap(self, argv: list[str], hide=(), writable=(), hold=None) -> list[str]:
        """The command that starts ``argv`` confined.

        In the namespaced levels the folders ``hide`` are covered by empty
        read-only mounts, and every file system is remounted read-only except
        the folders ``writable`` (the worker's scratch) and a private ``/dev/shm``.
        For ``namespaces+user``, ``hold`` is an empty folder of the grader's used
        to re-expose :attr:`reexpose` (e.g. ``/root/.pyenv`` under ``/root``).
        """
        if self.level == "process-group":
            return list(argv)
        unshare = ["unshare", "--pid", "--fork", "--kill-child", "--mount-proc", "--net", "--mount"]
        if os.geteuid() != 0:
            unshare[1:1] = ["--user", "--map-root-user"]
        keep = [shlex.quote(str(p)) for p in writable]
        steps = self._reexpose_steps(hold) if self.level == "namespaces+user" else []
        steps += [f"mount --bind {p} {p}" for p in keep]
        steps += [f"mount -t tmpfs -o ro,size=4k,mode=000 none {shlex.quote(str(p))}"
                  for p in hide if Path(p).is_dir()]
        skip = "|".join(["/proc|/proc/*|/sys|/sys/*|/dev|/dev/*", *keep])
        steps.append("while read -r _ mnt _; do case \"$mnt\" in " + skip + ") ;; "
                     "*) mount -o remount,bind,ro \"$mnt\" 2>/dev/null || true ;; esac; "
                     "done < /proc/self/mounts")
        steps.append("{ mount -t tmpfs -o size=64m,mode=1777 none /dev/shm 2>/dev/null || true; }")
        steps.append('cd -- "$PWD"')  # re-enter the working folder through the writable mount
        drop = ["setpriv", "--no-new-privs", "--bounding-set=-all", "--inh-caps=-all"]
        if self.level == "namespaces+user":
            drop[1:1] = [f"--reuid={self.uid}", f"--regid={self.gid}", "--clear-groups"]
        script = " && ".join(steps + [f'exec {" ".join(drop)} -- "$@"'])
        return unshare + ["--", "/bin/sh", "-c", script, "sh", *argv]

    def _reexpose_steps(self, hold) -> list[str]:
        """Shell steps making :attr:`reexpose` reachable for the worker's user.

        Each folder is held at ``hold/i``, its closed parent (``/root``) covered
        by an empty, traversable tmpfs, and the folder bound back in place: the
        worker reaches the interpreter and nothing else of that parent.
        """
        if not self.reexpose or hold is None:
            return []
        steps, covered = [], set()
        for i, folder in enumerate(self.reexpose):
            held = shlex.quote(str(Path(hold) / str(i)))
            steps += [f"mkdir -p {held}", f"mount --bind {shlex.quote(str(folder))} {held}"]
        for folder in self.reexpose:
            parent = shlex.quote(str(folder.parent))
            if parent not in covered:
                covered.add(parent)
                steps.append(f"mount -t tmpfs -o mode=755,size=64k none {parent}")
        for i, folder in enumerate(self.reexpose):
            target = shlex.quote(str(folder))
            steps += [f"mkdir -p {target}", f"mount --bind {shlex.quote(str(Path(hold) / str(i)))} {target}"]
        return steps

    @property
    def isolates_network(self) -> bool:
        return self.level != "process-group"

    @property
    def hides_files(self) -> bool:
        return self.level != "process-group"

    def prepare_scratch(self, scratch: Path, private=("worker",)) -> None:
        """Give the worker's user its scratch folder (all but ``private`` entries)."""
        if self.uid is None:
            return
        os.chown(scratch, self.uid, self.gid)
        for entry in scratch.iterdir():
            if entry.name not in private:
                for path in [entry, *entry.rglob("*")]:
                    os.chown(path, self.uid, self.gid, follow_symlinks=False)


def detect() -> Confinement:
    """The strongest confinement that works here (probed once per process)."""
    forced = os.environ.get("AUTOGRADER_CONFINEMENT")
    if forced:
        if forced not in LEVELS:
            raise ValueError(f"AUTOGRADER_CONFINEMENT must be one of {LEVELS}, got {forced!r}")
        return _candidate(forced) or Confinement("process-group")
    return _detect()


@lru_cache(maxsize=1)
def _detect() -> Confinement:
    for level in LEVELS[:-1]:
        candidate = _candidate(level)
        if candidate is not None and _works(candidate):
            return candidate
    return Confinement("process-group")


def _candidate(level: str) -> Confinement | None:
    if level == "process-group":
        return Confinement(level)
    if sys.platform != "linux" or not (shutil.which("unshare") and shutil.which("setpriv")):
        return None
    if level == "namespaces+user":
        if os.geteuid() != 0:
            return None
        uid, gid = worker_user()
        return Confinement(level, uid, gid, reexpose=tuple(closed_interpreter_folders()))
    return Confinement(level)


def _works(confinement: Confinement) -> bool:
    hold = tempfile.mkdtemp(prefix="autograder-probe-")
    probe = confinement.wrap([sys.executable, "-c", "import numpy"], hold=hold)
    try:
        return subprocess.run(probe, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, timeout=30, cwd="/").returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False
    finally:
        shutil.rmtree(hold, ignore_errors=True)


def closed_interpreter_folders() -> list[Path]:
    """Folders holding the interpreter and its packages whose parent others cannot enter.

    For Python installed under ``/root`` (pyenv: ``/root/.pyenv``), that is
    ``/root/.pyenv``: the worker's user needs it, and nothing else of ``/root``.
    """
    needed = {Path(sys.executable).resolve().parent, Path(sys.prefix), Path(sys.base_prefix)}
    needed |= {Path(p) for p in sys.path if p and Path(p).is_dir()}
    found = []
    for path in sorted(needed):
        parts = path.resolve().parts
        for depth in range(1, len(parts) - 1):
            ancestor = Path(*parts[:depth])
            try:
                closed = not os.stat(ancestor).st_mode & 0o001
            except OSError:
                break
            if closed:
                child = Path(*parts[:depth + 1])
                if child not in found:
                    found.append(child)
                break
    return found


def worker_user() -> tuple[int, int]:
    """uid and gid of ``agworker``, created if missing (root only); ``nobody`` as a fallback."""
    for attempt in range(2):
        try:
            entry = pwd.getpwnam(WORKER_USER)
            return entry.pw_uid, entry.pw_gid
        except KeyError:
            if attempt == 0 and shutil.which("useradd"):
                subprocess.run(["useradd", "--system", "--no-create-home", "--home-dir", "/nonexistent",
                                "--shell", "/usr/sbin/nologin", "--user-group", WORKER_USER],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    nobody = pwd.getpwnam("nobody")
    return nobody.pw_uid, nobody.pw_gid


# ------------------------------------------------------------------ reaping
@lru_cache(maxsize=1)
def become_subreaper() -> bool:
    """Make this process adopt orphaned descendants (Linux), so escaped daemons can be killed."""
    if sys.platform != "linux":
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(_PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def kill_adopted_orphans(keep: set[int]) -> int:
    """SIGKILL the children of this process that escaped a worker (re-parented daemons).

    A child counts as escaped when it is not in ``keep`` (the live workers) and
    runs in another session than the grader's: workers and ``setsid`` daemons
    do, while the grader's own helper processes stay in its session. Repeats
    until none is left, since a killed daemon's children are re-parented to us
    in turn. Returns how many were killed.
    """
    killed, own_session = 0, os.getsid(0)
    for _ in range(50):
        orphans = [pid for pid, session in _children_of(os.getpid())
                   if pid not in keep and session != own_session]
        if not orphans:
            break
        for pid in orphans:
            try:
                os.kill(pid, signal.SIGKILL)
                killed += 1
            except ProcessLookupError:
                pass
        for pid in orphans:
            try:
                os.waitpid(pid, 0)
            except ChildProcessError:
                pass
    return killed


def _children_of(parent: int) -> list[tuple[int, int]]:
    """(pid, session id) of the children of ``parent``."""
    if not os.path.isdir("/proc"):
        return []
    children = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            if int(fields[1]) == parent:
                children.append((int(entry), int(fields[3])))
        except (OSError, IndexError, ValueError):
            pass
    return children


def count_tasks(uid: int) -> int | None:
    """Processes and threads of ``uid`` (what RLIMIT_NPROC counts), from /proc; None without /proc."""
    count = 0
    if not os.path.isdir("/proc"):
        return None
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/status") as status:
                fields = dict(line.split(":", 1) for line in status if ":" in line)
            if int(fields["Uid"].split()[0]) == uid:
                count += int(fields["Threads"])
        except (OSError, KeyError, ValueError):
            pass
    return count
