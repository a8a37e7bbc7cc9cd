"""PID 1 of the worker's namespaces: builds its file system, then waits for it.

Run by :meth:`autograder.sandbox.confine.Confinement.wrap` as root inside fresh mount,
PID, network and IPC namespaces, with the standard library only (``python -I -S``)::

    python -I -S namespace_init.py SPEC_JSON -- setpriv ... worker.py ...

``SPEC_JSON`` lists the operations that build the new root (tmpfs mounts,
read-only binds, symbolic links, folders...), ending with ``pivot_root``
into it and the old root detached. Then the command after ``--`` runs as a
child, and this process waits for it: when it exits (or is killed with the
namespace's parent), the kernel ends every process left in the namespace,
however they regrouped. A worker killed by signal ``n`` is reported as exit
status ``128 + n``. One process doing system calls, not a shell starting
hundreds of ``mount`` commands: starting a worker stays cheap.
"""

import ctypes
import json
import os
import platform
import sys

MS_RDONLY, MS_NOSUID, MS_NODEV, MS_NOEXEC = 1, 2, 4, 8
MS_REMOUNT, MS_BIND, MS_REC, MS_PRIVATE = 32, 4096, 16384, 1 << 18
MS_NOATIME, MS_NODIRATIME, MS_RELATIME = 1024, 2048, 1 << 21
MNT_DETACH = 2
SYS_PIVOT_ROOT = {"x86_64": 155, "aarch64": 41, "arm64": 41, "ppc64le": 203, "s390x": 217}
_libc = ctypes.CDLL(None, use_errno=True)


def _check(result, what):
    if result != 0:
        errno = ctypes.get_errno()
        raise OSError(errno, f"{what}: {os.strerror(errno)}")


def mount(source, target, fstype, flags, data=None):
    _check(_libc.mount(source and source.encode(), target.encode(), fstype and fstype.encode(),
                       ctypes.c_ulong(flags), data and data.encode()),
           f"mount {source} {target}")


def locked_flags(path):
    """The flags of the mount holding ``path`` that a remount in a user namespace must keep."""
    flag = os.statvfs(path).f_flag
    kept = flag & (MS_NOSUID | MS_NODEV | MS_NOEXEC)  # these ST_* values equal the MS_* ones
    for st, ms in ((os.ST_NOATIME, MS_NOATIME), (os.ST_NODIRATIME, MS_NODIRATIME),
                   (os.ST_RELATIME, MS_RELATIME)):
        if flag & st:
            kept |= ms
    return kept


def run(op):
    kind, *args = op
    if kind == "mkdir":
        os.makedirs(args[0], mode=0o755, exist_ok=True)
    elif kind == "touch":
        os.makedirs(os.path.dirname(args[0]), mode=0o755, exist_ok=True)
        os.close(os.open(args[0], os.O_WRONLY | os.O_CREAT, 0o644))
    elif kind == "symlink":
        os.makedirs(os.path.dirname(args[1]), mode=0o755, exist_ok=True)
        os.symlink(args[0], args[1])
    elif kind == "tmpfs":
        os.makedirs(args[0], mode=0o755, exist_ok=True)
        mount("none", args[0], "tmpfs", MS_NOSUID | MS_NODEV, args[1])
    elif kind == "bind":  # source, target, read_only
        source, target, read_only = args
        if os.path.isdir(source):
            os.makedirs(target, mode=0o755, exist_ok=True)
        else:
            run(("touch", target))
        mount(source, target, None, MS_BIND)
        if read_only:
            mount(None, target, None, MS_REMOUNT | MS_BIND | MS_RDONLY | MS_NOSUID | MS_NODEV
                  | locked_flags(source))
    elif kind == "remount_ro":
        mount(None, args[0], None, MS_REMOUNT | MS_RDONLY | MS_NOSUID | MS_NODEV | locked_flags(args[0]))
    elif kind == "proc":
        os.makedirs(args[0], mode=0o755, exist_ok=True)
        mount("proc", args[0], "proc", MS_NOSUID | MS_NODEV | MS_NOEXEC)
    elif kind == "rmdir":
        os.rmdir(args[0])
    elif kind == "chown":
        os.chown(args[0], args[1], args[2])
    elif kind == "chmod":
        os.chmod(args[0], args[1])
    elif kind == "pivot":  # new root, where the old one goes (inside the new root)
        new_root, put_old = args
        os.makedirs(put_old, exist_ok=True)
        number = SYS_PIVOT_ROOT.get(platform.machine())
        if number is None:
            raise OSError(f"pivot_root: unknown system call number on {platform.machine()}")
        _check(_libc.syscall(number, new_root.encode(), put_old.encode()), "pivot_root")
        os.chdir("/")
        old = "/" + os.path.relpath(put_old, new_root)
        _check(_libc.umount2(old.encode(), MNT_DETACH), "umount old root")
    else:
        raise ValueError(f"unknown operation {kind!r}")


def build(spec) -> None:
    """Build the worker's file system from ``spec`` (mount namespace of its own, as root in it) and switch
    to it, staying in the folder this process was in."""
    cwd = os.getcwd()
    mount(None, "/", None, MS_REC | MS_PRIVATE)  # nothing propagates back to the grader's mounts
    for op in spec:
        run(op)
    os.chdir(cwd)


def reap(child) -> int:
    """As PID 1, reap every orphan until ``child`` itself ends; its exit status (``128 + n`` when
    killed by signal ``n``)."""
    while True:
        pid, status = os.wait()
        if pid == child:
            break
    code = os.waitstatus_to_exitcode(status)
    return 128 - code if code < 0 else code


def main(argv):
    spec = json.loads(argv[1])
    command = argv[argv.index("--") + 1:]
    build(spec)
    child = os.fork()
    if child == 0:
        try:
            os.execvp(command[0], command)
        finally:
            os._exit(127)
    sys.exit(reap(child))


if __name__ == "__main__":
    main(sys.argv)
