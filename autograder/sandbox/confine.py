"""How the worker process is confined, chosen by what the platform allows.

Three levels, strongest first; :func:`detect` probes them once per process and
keeps the first that really starts Python:

``namespaces+user``
    The grader runs as root (a course container). The worker starts in new PID,
    network, IPC, UTS and mount namespaces (``unshare``) and its file system is
    *built*, not hidden (:meth:`Confinement.wrap`): a fresh root holding only the
    system folders (``/usr``, ``/bin``, ``/lib*``: programs and shared libraries),
    a few files of ``/etc`` the dynamic loader needs, the interpreter's own
    folders, the site-packages entries of the libraries a student may use
    (:data:`ALLOWED_LIBRARIES` and what they require), ``/dev/null`` and friends,
    a fresh ``/proc``, a private size-limited ``/tmp``, and the worker's scratch
    folder (its copy of the submission and of the worker code read-only, a
    size-limited writable area, its output file). Everything else -- the grader's
    sources, any installed copy of the grader (hidden checks included), home
    folders, other submissions -- does not exist there. It then drops to the
    unprivileged user ``agworker`` (created if missing; ``nobody`` otherwise)
    with no capabilities. PID 1 of the namespace is a small shell that waits for
    the worker: when the worker ends, or the grader kills it, every process left
    in the namespace ends too, however it regrouped (``setsid``).
``namespaces``
    The same namespaces and the same built file system, without changing user:
    as root when no unprivileged user exists, or through an unprivileged user
    namespace on a student's Linux laptop. Every capability is dropped, so the
    mounts cannot be undone.
``process-group``
    Best effort (macOS, or Linux without namespaces): the worker gets its own
    session, the grader becomes a child subreaper so double-forked daemons are
    re-parented to it and killed, and the resource limits still apply. No
    network isolation, and the worker can read what the user can.

In every level a :class:`Cgroup` (cgroup v2, or the v1 ``memory`` and ``pids``
controllers) bounds the memory and processes of the worker and all its children
together, where the grader may create one; otherwise the per-process limits
(``RLIMIT_AS``, ``RLIMIT_NPROC``) are all there is.

``AUTOGRADER_CONFINEMENT=process-group`` (or another level) forces a level.
"""

from __future__ import annotations

import csv
import ctypes
import json
import logging
import os
import pwd
import re
import secrets
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

LEVELS = ("namespaces+user", "namespaces", "process-group")
WORKER_USER = "agworker"
_PR_SET_CHILD_SUBREAPER = 36

# Distributions a submission may import (with everything they require): the lab
# sheet's NumPy, OpenCV and Matplotlib, and SciPy and scikit-image as courtesy; pypdf for the
# workers that read PDF reports (autograder.sandbox.report_reader: never in the grader's process).
ALLOWED_LIBRARIES = ("numpy", "opencv-python", "opencv-python-headless", "opencv-contrib-python",
                     "opencv-contrib-python-headless", "matplotlib", "scipy", "scikit-image", "pypdf")
# The same, as a student imports them (told where graded code imports another library).
OFFERED = "Python's standard library, NumPy, OpenCV (cv2), SciPy, scikit-image and Matplotlib"
# System folders bound read-only (programs and shared libraries), and the few
# files of /etc the dynamic loader and the C library read.
SYSTEM_FOLDERS = ("/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32")
ETC_ENTRIES = ("/etc/ld.so.cache", "/etc/ld.so.conf", "/etc/ld.so.conf.d", "/etc/alternatives",
               "/etc/localtime", "/etc/passwd", "/etc/group", "/etc/nsswitch.conf", "/etc/fonts")
DEVICES = ("null", "zero", "full", "random", "urandom")


def _absolute(executable: str) -> str:
    """``executable`` as an absolute path, against the folder this process started in.

    Python started through a relative ``PATH`` entry (``PATH=.venv/bin:$PATH python
    grade.py``) has a relative ``sys.executable``, which names nothing once a worker
    starts in its scratch folder or in its own root: every namespaced level would
    fail its probe and the grading fall to ``process-group``.
    """
    return os.path.abspath(executable) if executable and not os.path.isabs(executable) else executable


# Resolved at import, before anything could change the working folder.
INTERPRETER = _absolute(sys.executable)


@dataclass(frozen=True)
class View:
    """The worker's own part of its file system: the scratch folder.

    Inside the namespace ``scratch`` is a tmpfs of ``size`` bytes holding the
    ``writable`` folders (owned by the worker), with the grader's ``read_only``
    folders and ``files`` bound at the same paths (read-only, resp. writable:
    the output file the grader reads). ``/tmp`` is another tmpfs of ``size``
    bytes; ``/dev/shm`` is a folder of the scratch.
    """

    scratch: Path
    read_only: tuple[Path, ...] = ()
    files: tuple[Path, ...] = ()
    writable: tuple[str, ...] = ("home", "tmp", "work")
    size: int = 256 * 2**20


@dataclass(frozen=True)
class Confinement:
    """A confinement level and, for ``namespaces+user``, the worker's uid/gid."""

    level: str
    uid: int | None = None
    gid: int | None = None

    def wrap(self, argv: list[str], view: View | None = None, hold=None) -> list[str]:
        """The command that starts ``argv`` confined.

        In the namespaced levels the worker's file system is built in ``hold``
        (an empty folder of the grader's) from the allowlist described in this
        module's documentation plus ``view``, then made the root, by
        ``namespace_init.py``, which stays as PID 1 and waits for the worker.
        """
        if self.level == "process-group":
            return list(argv)
        if hold is None:
            raise ValueError("the namespaced levels need a folder to build the worker's root in")
        unshare = ["unshare", "--pid", "--fork", "--kill-child", "--net", "--mount", "--ipc", "--uts"]
        if os.geteuid() != 0:
            unshare[1:1] = ["--user", "--map-root-user"]
        drop = [shutil.which("setpriv") or "setpriv", "--no-new-privs", "--bounding-set=-all",
                "--inh-caps=-all"]
        if self.level == "namespaces+user":
            drop[1:1] = [f"--reuid={self.uid}", f"--regid={self.gid}", "--clear-groups"]
        spec = json.dumps(self._root_ops(str(Path(hold) / "root"), view))
        init = str(Path(__file__).with_name("namespace_init.py"))
        return unshare + ["--", INTERPRETER, "-I", "-S", init, spec, "--", *drop, "--", *argv]

    def forked(self, view: View, hold) -> dict:
        """What a worker forked from the warm template (``zygote.py``) needs to be confined as :meth:`wrap`
        confines a started one: the operations building its root in ``hold``, the user it drops to (None:
        it stays root of its namespaces, every capability dropped), and whether the grader, not being root,
        maps itself to root of a user namespace first. Namespaced levels only."""
        if self.level == "process-group":
            raise ValueError("only the namespaced levels fork workers from the template")
        own_user = self.level == "namespaces+user"
        return {"ops": self._root_ops(str(Path(hold) / "root"), view), "map_root": os.geteuid() != 0,
                "uid": self.uid if own_user else None, "gid": self.gid if own_user else None}

    def _root_ops(self, root: str, view: View | None) -> list:
        """The operations building the worker's root in ``root``, ending with the switch to it."""
        at = lambda p: f"{root}{p}"  # noqa: E731  (``p`` inside the new root)
        size = view.size if view is not None else 16 * 2**20
        # /tmp first: an interpreter or scratch folder under /tmp is bound on top of it.
        ops: list = [("tmpfs", root, "mode=755,size=8m"), ("tmpfs", at("/tmp"), f"mode=1777,size={size}")]

        def bind(source, read_only=True):
            ops.append(("bind", str(source), at(source), read_only))

        for top in SYSTEM_FOLDERS:
            if os.path.islink(top):
                ops.append(("symlink", os.readlink(top), at(top)))
            elif os.path.isdir(top):
                bind(top)
        for entry in ETC_ENTRIES:
            if os.path.exists(entry):
                bind(entry)
        interpreter, sites = interpreter_layout()
        for kind, *args in interpreter:
            if kind == "symlink":
                ops.append(("symlink", args[0], at(args[1])))
            else:
                bind(args[0])
        for site, entries in sites:
            ops.append(("tmpfs", at(site), "mode=755,size=1m"))
            for entry in entries:
                path = os.path.join(site, entry)
                if os.path.islink(path):
                    ops.append(("symlink", os.readlink(path), at(path)))
                else:
                    bind(path)
            ops.append(("remount_ro", at(site)))
        ops.append(("tmpfs", at("/dev"), "mode=755,size=64k"))
        for device in DEVICES:
            bind(f"/dev/{device}", read_only=False)
        for name, target in (("fd", "/proc/self/fd"), ("stdin", "/proc/self/fd/0"),
                             ("stdout", "/proc/self/fd/1"), ("stderr", "/proc/self/fd/2")):
            ops.append(("symlink", target, at("/dev/" + name)))
        ops.append(("proc", at("/proc")))
        if view is not None:
            ops += self._scratch_ops(view, at)
        ops += [("remount_ro", at("/dev")), ("pivot", root, at("/.old")), ("rmdir", "/.old"),
                ("remount_ro", "/")]
        return ops

    def _scratch_ops(self, view: View, at) -> list:
        owner = f",uid={self.uid},gid={self.gid}" if self.uid is not None else ""
        scratch = str(view.scratch)
        ops: list = [("tmpfs", at(scratch), f"mode=755,size={view.size}{owner}")]
        for name in (*view.writable, "shm"):
            ops.append(("mkdir", at(f"{scratch}/{name}")))
            if self.uid is not None:
                ops.append(("chown", at(f"{scratch}/{name}"), self.uid, self.gid))
        ops.append(("chmod", at(f"{scratch}/shm"), 0o1777))
        ops += [("bind", str(folder), at(folder), True) for folder in view.read_only]
        ops += [("bind", str(file), at(file), False) for file in view.files]
        ops.append(("bind", at(f"{scratch}/shm"), at("/dev/shm"), False))
        return ops

    @property
    def isolates_network(self) -> bool:
        return self.level != "process-group"

    @property
    def hides_files(self) -> bool:
        return self.level != "process-group"

    def exit_signal(self, code: int | None) -> int | None:
        """The worker's exit status as :attr:`subprocess.Popen.returncode` would be unconfined.

        In the namespaced levels PID 1 is a shell, which reports a worker killed by
        signal ``n`` as exit status ``128 + n``.
        """
        if code is not None and self.level != "process-group" and 128 < code < 128 + 65:
            return -(code - 128)
        return code

    def with_own_user(self) -> "Confinement":
        """This level, its worker running as a user id of its own (``namespaces+user`` only).

        Where no cgroup bounds a worker's processes, ``RLIMIT_NPROC`` does, and it counts
        every process of the worker's user: workers graded side by side as one user (a
        submission's lanes, a batch's gradings) would share one budget, and one fork bomb
        would keep the others from starting threads. A user id nothing else runs as --
        from a range no account uses, with no name, owning nothing but the worker's
        scratch -- gives each worker a budget of its own (and no way to signal another).
        """
        if self.level != "namespaces+user":
            return self
        for _ in range(32):
            uid = OWN_USERS + secrets.randbelow(OWN_USERS_COUNT)
            if _unused_id(uid):
                return Confinement(self.level, uid, uid)
        return self

    def prepare_scratch(self, scratch: Path, private=("worker",)) -> None:
        """Give the worker's user its scratch folder (all but ``private`` entries)."""
        if self.uid is None:
            return
        os.chown(scratch, self.uid, self.gid)
        for entry in scratch.iterdir():
            if entry.name not in private:
                for path in [entry, *entry.rglob("*")]:
                    os.chown(path, self.uid, self.gid, follow_symlinks=False)


# ------------------------------------------------------------------ the allowlist
@lru_cache(maxsize=1)
def interpreter_layout() -> tuple[tuple, tuple[tuple[str, tuple[str, ...]], ...]]:
    """What the worker's interpreter needs, asked of the interpreter itself (started ``-I``).

    Returns the operations exposing the interpreter outside the system folders
    -- its installation (``base_prefix``: standard library, shared library)
    bound whole; of a virtual environment only ``pyvenv.cfg`` and the
    ``bin/python*`` entries, never its scripts -- and for each site-packages
    folder the entries of :data:`ALLOWED_LIBRARIES` and their requirements in it.
    """
    probe = ("import json, sys; print(json.dumps([sys.prefix, sys.base_prefix, sys.exec_prefix, "
             "sys.base_exec_prefix, sys.executable, sys.path]))")
    with subprocess.Popen([INTERPRETER, "-I", "-c", probe], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                          stdin=subprocess.DEVNULL, text=True) as asked:
        try:
            # Meanwhile, the entries of the site folders this interpreter has (almost always the probe's).
            guessed = {site: allowed_entries(Path(site)) for site in _site_folders(sys.path)}
            out, _ = asked.communicate(timeout=60)
        except BaseException:
            asked.kill()  # never left behind (a timeout included)
            raise
    if asked.returncode:
        raise subprocess.CalledProcessError(asked.returncode, asked.args)
    prefix, base_prefix, exec_prefix, base_exec_prefix, executable, path = json.loads(out)
    sites = _site_folders(path)
    covered = lambda p: any(p == s or p.startswith(s + "/") for s in SYSTEM_FOLDERS)  # noqa: E731
    folders: list[str] = []
    wanted = [base_prefix, base_exec_prefix, str(Path(executable).resolve().parent)]
    wanted += [p for p in path if p not in sites and os.path.exists(p) and not p.startswith(prefix + "/")
               and not _holds_grader(p)]
    for folder in sorted({os.path.realpath(p) for p in wanted}, key=len):
        if not covered(folder) and not any(folder == f or folder.startswith(f + "/") for f in folders):
            folders.append(folder)
    ops: list = [("bind", folder) for folder in folders]
    for venv in dict.fromkeys([prefix, exec_prefix]):
        if venv in (base_prefix, base_exec_prefix) or covered(venv):
            continue
        if os.path.exists(f"{venv}/pyvenv.cfg"):
            ops.append(("bind", f"{venv}/pyvenv.cfg"))
        for entry in sorted(Path(venv, "bin").glob("python*")):
            # A link is laid again pointing at its final target (inside the bound installation):
            # a venv made from another venv links to that venv's python, which is not in the view.
            ops.append(("symlink", os.path.realpath(entry), str(entry)) if entry.is_symlink()
                       else ("bind", str(entry)))
    allowed = tuple((site, tuple(sorted(guessed[site] if site in guessed else allowed_entries(Path(site)))))
                    for site in sites)
    return tuple(ops), allowed


def _site_folders(path: list[str]) -> list[str]:
    return [p for p in path if Path(p).name in ("site-packages", "dist-packages") and Path(p).is_dir()]


def _holds_grader(folder: str) -> bool:
    """Whether ``folder`` is, or holds, the grader's own sources (an editable install's path)."""
    package = Path(__file__).resolve().parents[1]
    folder_path = Path(folder).resolve()
    return (folder_path / "autograder").is_dir() or package.is_relative_to(folder_path)


def _plain_path_file(path: Path) -> bool:
    """A ``.pth`` file that only adds folders (no ``import`` line: nothing runs)."""
    try:
        lines = path.read_text(errors="replace").splitlines()
    except OSError:
        return False
    return all(not line.startswith(("import ", "import\t")) for line in lines)


def allowed_entries(site: Path) -> set[str]:
    """Top-level entries of ``site`` belonging to :data:`ALLOWED_LIBRARIES` or their requirements.

    Read from the distributions' metadata folders directly (their names, then the
    ``Requires-Dist`` headers and ``RECORD`` of the wanted ones only): a site with a
    hundred distributions costs milliseconds, not the third of a second that parsing
    every distribution's metadata with :mod:`importlib.metadata` takes, on the path
    to the worker's start.
    """
    folders: dict[str, Path] = {}
    for folder in sorted(site.glob("*.dist-info")) + sorted(site.glob("*.egg-info")):
        folders.setdefault(_normalized(folder.name.split("-", 1)[0]), folder)
    wanted, todo = set(), [_normalized(n) for n in ALLOWED_LIBRARIES]
    while todo:
        name = todo.pop()
        if name in wanted or name not in folders:
            continue
        wanted.add(name)
        todo += [_normalized(r) for r in _requirements(folders[name])]
    entries = set()
    for name in wanted:
        entries |= _top_level_entries(folders[name])
    entries = {e for e in entries if "/" not in e and e not in (".", "", "..", "__pycache__")}
    found = {p.name for p in site.glob("*.pth") if _plain_path_file(p)}
    for entry in entries:
        for candidate in (entry, entry + ".py"):
            if (site / candidate).exists() or (site / candidate).is_symlink():
                found.add(candidate)
    return found


def _normalized(name: str) -> str:
    """A distribution's name as PEP 503 compares names (``Scikit_Image`` -> ``scikit-image``)."""
    return re.sub(r"[-_.]+", "-", name).lower()


def _requirements(folder: Path) -> list[str]:
    """The names a distribution requires unconditionally (not only for an extra)."""
    metadata = folder / ("METADATA" if folder.suffix == ".dist-info" else "PKG-INFO")
    try:
        headers = metadata.read_text(errors="replace").split("\n\n", 1)[0]
    except OSError:
        headers = ""
    names = []
    for line in headers.splitlines():
        if line.lower().startswith("requires-dist:") and "extra ==" not in line:
            match = re.match(r"\s*([A-Za-z0-9][A-Za-z0-9._-]*)", line.split(":", 1)[1])
            if match:
                names.append(match.group(1))
    if folder.suffix == ".egg-info":  # setuptools' older format: requires.txt, in [sections]
        try:
            lines = (folder / "requires.txt").read_text(errors="replace").splitlines()
        except OSError:
            lines = []
        for_an_extra = False
        for line in lines:
            if line.startswith("["):  # "[extra]", "[extra:marker]": an extra's; "[:marker]": everyone's
                for_an_extra = not line.startswith("[:")
                continue
            match = re.match(r"\s*([A-Za-z0-9][A-Za-z0-9._-]*)", line)
            if match and not for_an_extra:
                names.append(match.group(1))
    return names


def _top_level_entries(folder: Path) -> set[str]:
    """The first path component of every file a distribution installed (its ``RECORD``),
    else the names in ``top_level.txt``."""
    try:
        record = (folder / "RECORD").read_text(errors="replace")
    except OSError:
        record = None
    if record is not None:
        return {row[0].split("/", 1)[0] for row in csv.reader(record.splitlines()) if row}
    try:
        return {line.strip() for line in (folder / "top_level.txt").read_text().splitlines() if line.strip()}
    except OSError:
        return set()


def detect() -> Confinement:
    """The strongest confinement that works here (probed once per process)."""
    forced = os.environ.get("AUTOGRADER_CONFINEMENT")
    if forced:
        if forced not in LEVELS:
            raise ValueError(f"AUTOGRADER_CONFINEMENT must be one of {LEVELS}, got {forced!r}")
        return _candidate(forced) or Confinement("process-group")
    with _probing:  # one probe, however many threads ask at once
        return _detect()


def detect_in_background() -> None:
    """Start :func:`detect` now on a thread of its own (its probe is a process: the caller
    goes on meanwhile); a later :func:`detect` returns the answer once it is there."""
    def probe():
        try:
            detect()
        except Exception:  # noqa: BLE001 - the caller's own detect() raises it again
            pass

    threading.Thread(target=probe, name="confinement-probe").start()


_probing = threading.Lock()


def strongest_candidate() -> Confinement:
    """The level :func:`detect` tries first, known without starting anything (so a
    worker can start at it while the probe runs; only :func:`detect` says it works)."""
    forced = os.environ.get("AUTOGRADER_CONFINEMENT")
    if forced:
        return detect()
    for level in LEVELS[:-1]:
        candidate = _candidate(level)
        if candidate is not None:
            return candidate
    return Confinement("process-group")


class WeakerConfinement(RuntimeError):
    """Student code would run less confined than this machine allows (see :func:`shortfall`)."""


def shortfall(confinement: Confinement) -> str:
    """Why student code confined at ``confinement`` is less confined than this machine
    allows, or ``""`` when it is not.

    Weaker than the level :func:`detect`'s probe finds working (forced by
    ``AUTOGRADER_CONFINEMENT`` or asked for by a caller); or, as root (a course
    container, an instructor's batch), weaker than a namespaced level whose tools are
    here but whose worker could not start Python, which there means something is
    broken. A student's laptop without user namespaces is not short of anything.
    Probes (one process, once per process) only when the level is not the strongest
    one the machine has the tools for.
    """
    rank = LEVELS.index(confinement.level)
    present = next((level for level in LEVELS if _candidate(level) is not None), LEVELS[-1])
    if rank <= LEVELS.index(present):
        return ""
    with _probing:
        works = _detect().level
    if rank > LEVELS.index(works):
        forced = os.environ.get("AUTOGRADER_CONFINEMENT")
        why = f"AUTOGRADER_CONFINEMENT={forced} forces it" if forced == confinement.level else "it was asked for"
        return f"student code ran at the {confinement.level} level though {works} works here ({why})"
    if os.geteuid() == 0:
        return (f"student code ran at the {confinement.level} level: {present} is available here but its "
                "worker could not start Python (see the log)")
    return ""


@lru_cache(maxsize=1)
def _detect() -> Confinement:
    for level in LEVELS[:-1]:
        candidate = _candidate(level)
        if candidate is not None:
            if _works(candidate):
                return candidate
            # Never silently weaker: the instructor's log says which level failed.
            logging.getLogger("autograder").warning(
                "confinement level %s is available here but could not start Python; trying a weaker one", level)
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
        return Confinement(level, uid, gid)
    return Confinement(level)


def _works(confinement: Confinement) -> bool:
    hold = tempfile.mkdtemp(prefix="autograder-probe-")
    probe = confinement.wrap([INTERPRETER, "-I", "-c", "import numpy"], hold=hold)
    try:
        return subprocess.run(probe, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, timeout=30, cwd="/").returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False
    finally:
        shutil.rmtree(hold, ignore_errors=True)


# Numeric user ids for workers of their own (Confinement.with_own_user): far above the
# accounts of any system (and below the 2**31 some tools take as negative).
OWN_USERS, OWN_USERS_COUNT = 1_900_000_000, 100_000_000


def _unused_id(uid: int) -> bool:
    """No account and no process has ``uid`` (nor a group ``uid``)."""
    import grp

    try:
        pwd.getpwuid(uid)
        return False
    except KeyError:
        pass
    try:
        grp.getgrgid(uid)
        return False
    except KeyError:
        pass
    return not count_tasks(uid)


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


# ------------------------------------------------------------------ one budget for all processes
def _pauses(seconds: float, first: float = 0.0005, longest: float = 0.01):
    """Pauses between polls of something the kernel finishes in a moment (killed processes
    leaving a cgroup): short at first, doubling up to ``longest``, ``seconds`` in all."""
    pause, waited = first, 0.0
    while waited < seconds:
        yield pause
        waited += pause
        pause = min(2 * pause, longest)


_CGROUP_NAME = re.compile(r"^autograder-(\d+)-[0-9a-f]{8}$")


def _remove_left_behind(parent: Path) -> None:
    """Remove the cgroups beside ours whose creating process is dead (it was killed before it
    could remove them: a batch's grading process killed outright), their processes first."""
    try:
        names = [p.name for p in parent.iterdir() if _CGROUP_NAME.match(p.name)]
    except OSError:
        return
    for name in names:
        pid = int(_CGROUP_NAME.match(name)[1])
        try:
            os.kill(pid, 0)
            continue   # its creator lives: its own to remove
        except ProcessLookupError:
            pass
        except PermissionError:
            continue   # another user's live process
        Cgroup([parent / name]).remove()


class Cgroup:
    """A cgroup bounding the memory and the number of processes of a worker and all its children.

    cgroup v2 where the grader may create a child of its own cgroup with the
    ``memory`` and ``pids`` controllers enabled, else the cgroup v1 ``memory``
    and ``pids`` hierarchies; :meth:`create` returns None where neither is
    writable (macOS, most unprivileged setups, containers with a read-only
    ``/sys/fs/cgroup``): the per-process limits then stand alone. Memory counts
    every process's pages and the worker's tmpfs; going over it kills the
    process the kernel picks (reported as killed, out of memory).
    """

    def __init__(self, folders: list[Path]):
        self.folders = folders

    @classmethod
    def create(cls, memory: int | None, processes: int | None) -> "Cgroup | None":
        if sys.platform != "linux" or os.environ.get("AUTOGRADER_CGROUP") == "off":
            return None
        name = f"autograder-{os.getpid()}-{secrets.token_hex(4)}"
        for attempt in (cls._v2, cls._v1):
            try:
                made = attempt(name, memory, processes)
            except (OSError, ValueError):  # not writable, not delegated, or not what we expect
                made = None
            if made is not None:
                return made
        return None

    @staticmethod
    def _own(controller: str) -> str | None:
        """This process's cgroup path in the hierarchy of ``controller`` ("" for v2)."""
        with open("/proc/self/cgroup") as f:
            for line in f:
                _, controllers, path = line.rstrip("\n").split(":", 2)
                if controllers.split(",") == [controller] or (controller == "" and controllers == ""):
                    return path
        return None

    @classmethod
    def _v2(cls, name, memory, processes):
        path = cls._own("")
        mounts = [Path("/sys/fs/cgroup"), Path("/sys/fs/cgroup/unified")]
        for mount in mounts:
            if path is None or not (mount / "cgroup.controllers").exists():
                continue
            parent = mount / path.lstrip("/")
            if not {"memory", "pids"} <= set((parent / "cgroup.subtree_control").read_text().split()):
                (parent / "cgroup.subtree_control").write_text("+memory +pids")
            _remove_left_behind(parent)
            folder = parent / name
            folder.mkdir()
            try:
                if memory:
                    (folder / "memory.max").write_text(str(memory))
                    (folder / "memory.swap.max").write_text("0") if (folder / "memory.swap.max").exists() else None
                if processes:
                    (folder / "pids.max").write_text(str(processes))
            except OSError:
                folder.rmdir()
                raise
            return cls([folder])
        return None

    @classmethod
    def _v1(cls, name, memory, processes):
        folders = []
        try:
            for controller, key, value in (("memory", "memory.limit_in_bytes", memory),
                                           ("pids", "pids.max", processes)):
                own = cls._own(controller)
                root = Path("/sys/fs/cgroup") / controller
                if own is None or not (root / "cgroup.procs").exists():
                    raise OSError(f"no cgroup v1 {controller} hierarchy")
                _remove_left_behind(root / own.lstrip("/"))
                folder = root / own.lstrip("/") / name
                folder.mkdir()
                folders.append(folder)
                if value:
                    (folder / key).write_text(str(value))
        except OSError:
            for folder in folders:
                folder.rmdir()
            raise
        return cls(folders)

    def wrap(self, argv: list[str]) -> list[str]:
        """``argv`` started inside the cgroup (it joins before it runs anything else)."""
        joins = " && ".join(f"echo $$ > {shlex.quote(str(f / 'cgroup.procs'))}" for f in self.folders)
        return ["/bin/sh", "-c", f'{joins} && exec "$@"', "sh", *argv]

    def processes(self) -> set[int]:
        """The processes in the cgroup now (host PIDs)."""
        pids = set()
        for folder in self.folders:
            try:
                pids |= {int(p) for p in (folder / "cgroup.procs").read_text().split()}
            except (OSError, ValueError):
                pass
        return pids

    def kill(self) -> None:
        """SIGKILL every process in the cgroup, until none is left."""
        for folder in self.folders:
            if (folder / "cgroup.kill").exists():
                try:
                    (folder / "cgroup.kill").write_text("1")
                except OSError:
                    pass
        for pause in _pauses(seconds=1.0):
            pids = self.processes()
            if not pids:
                return
            for pid in pids:
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            time.sleep(pause)

    def remove(self) -> None:
        self.kill()
        for folder in self.folders:
            for pause in _pauses(seconds=1.0):
                try:
                    folder.rmdir()
                    break
                except FileNotFoundError:
                    break
                except OSError:
                    time.sleep(pause)  # the last processes are still exiting

    def oom_kills(self) -> int:
        """How many processes of this cgroup the kernel killed for going over its memory."""
        count = 0
        for folder in self.folders:
            for name in ("memory.events", "memory.oom_control"):
                try:
                    for line in (folder / name).read_text().splitlines():
                        key, _, value = line.partition(" ")
                        if key == "oom_kill":
                            count += int(value)
                except (OSError, ValueError):
                    pass
        return count

    def memory_limit_hits(self) -> int:
        """How many times the memory of this cgroup reached its limit (each time the kernel
        had to reclaim pages to go on): a process pressing against its limit thrashes,
        slowly, before anything is killed."""
        count = 0
        for folder in self.folders:
            try:
                if (folder / "memory.events").exists():
                    for line in (folder / "memory.events").read_text().splitlines():
                        key, _, value = line.partition(" ")
                        if key == "max":
                            count += int(value)
                elif (folder / "memory.failcnt").exists():
                    count += int((folder / "memory.failcnt").read_text())
            except (OSError, ValueError):
                pass
        return count


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
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            # /proc/PID belongs to the process's effective uid: a cheap first sieve (the
            # worker user's processes have one uid); the status file says the real one.
            if entry.stat().st_uid != uid:
                continue
            with open(f"/proc/{entry.name}/status") as status:
                fields = dict(line.split(":", 1) for line in status if ":" in line)
            if int(fields["Uid"].split()[0]) == uid:
                count += int(fields["Threads"])
        except (OSError, KeyError, ValueError):
            pass
    return count
