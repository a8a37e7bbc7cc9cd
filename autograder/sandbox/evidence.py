"""What the grader measures of a worker, to say why a call failed without asking the worker.

A worker runs student code, so nothing it says about itself is believed: the
verdict on a call that failed -- out of memory, too many processes, a closed
pipe -- rests on what the kernel tells the grader. This module reads it from
``/proc`` (Linux; elsewhere every function answers "unknown"):

- :func:`descendants`: the processes a process started, and theirs, wherever
  they moved to in a process group or session;
- :func:`memory_in_use`: the memory a set of processes holds (proportional
  set size: pages shared by forked children are counted once in all);
- :func:`holds_pipe`: whether a process still has the grader's pipe at a
  descriptor (a submission may close it or put something else there).

The cgroup's own counters (:class:`autograder.sandbox.confine.Cgroup`) are the better
evidence where there is a cgroup; these work without one.
"""

from __future__ import annotations

import os

PAGE = os.sysconf("SC_PAGE_SIZE") if hasattr(os, "sysconf") else 4096
MAX_PROCESSES = 100_000  # a walk stops there, whatever a fork bomb made


def _read(path: str, limit: int = 1 << 16) -> str | None:
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return None
    try:
        return os.read(fd, limit).decode(errors="replace")
    except OSError:
        return None
    finally:
        os.close(fd)


def children(pid: int) -> list[int]:
    """The children of ``pid`` (of all its threads), from ``/proc/PID/task/*/children``."""
    try:
        tasks = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return []
    found = []
    for task in tasks:
        text = _read(f"/proc/{pid}/task/{task}/children", 1 << 20)
        if text:
            found += [int(child) for child in text.split()]
    return found


def descendants(pid: int, limit: int = MAX_PROCESSES) -> list[int]:
    """``pid``'s children, their children and so on (not ``pid``), parents before children;
    at most ``limit`` of them (a fork bomb's are not all walked to know there are too many).

    A process that left its process group or session (``setsid``) is still found
    while its parent lives; an orphan is re-parented away from the tree (to PID 1
    of a PID namespace, which is in the tree when the namespace is; else to a
    subreaper or init, and is lost here).
    """
    found, todo, seen = [], [pid], {pid}
    while todo and len(found) < limit:
        for child in children(todo.pop(0)):
            if child not in seen:
                seen.add(child)
                found.append(child)
                todo.append(child)
    return found


def command_line(pid: int) -> list[str]:
    text = _read(f"/proc/{pid}/cmdline")
    return text.split("\0")[:-1] if text else []


def memory_in_use(pids) -> int | None:
    """Bytes of memory the processes ``pids`` hold together, None where it cannot be read.

    Each process's proportional set size (``Pss`` of ``smaps_rollup``): a page shared
    by n of them counts 1/n in each, so a worker's forked children, which share most
    of its pages, are not counted many times over. The resident set size where the
    kernel has no ``smaps_rollup`` (before Linux 4.14).
    """
    total, known = 0, False
    for pid in pids:
        rollup = _read(f"/proc/{pid}/smaps_rollup")
        if rollup:
            for line in rollup.splitlines():
                if line.startswith("Pss:"):
                    total += int(line.split()[1]) * 1024
                    known = True
                    break
            continue
        statm = _read(f"/proc/{pid}/statm")
        if statm:
            total += int(statm.split()[1]) * PAGE
            known = True
    return total if known else None


def resident(pid: int | None) -> int | None:
    """Bytes of memory process ``pid`` holds (its resident set size, ``statm``): a tenth of a
    millisecond to read, cheap enough for every call. None where it cannot be read."""
    statm = _read(f"/proc/{pid}/statm") if pid is not None else None
    return int(statm.split()[1]) * PAGE if statm else None


TICKS = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


def cpu_seconds(pid: int | None) -> float | None:
    """CPU time (user and system, all threads) process ``pid`` has used, from ``/proc/PID/stat``;
    None where it cannot be read (the process ended, no ``/proc``)."""
    stat = _read(f"/proc/{pid}/stat") if pid is not None else None
    if not stat or ")" not in stat:
        return None
    fields = stat[stat.rindex(")") + 2:].split()   # (the command name may hold spaces and brackets)
    try:
        return (int(fields[11]) + int(fields[12])) / TICKS   # utime, stime: fields 14 and 15 of stat
    except (IndexError, ValueError):
        return None


def holds_pipe(pid: int, fd: int, pipe_inode: int) -> bool | None:
    """Whether process ``pid`` has the pipe ``pipe_inode`` at descriptor ``fd``: None when
    that cannot be told (no ``/proc``, not allowed, the process is gone)."""
    try:
        target = os.readlink(f"/proc/{pid}/fd/{fd}")
    except FileNotFoundError:
        return False if os.path.isdir(f"/proc/{pid}/fd") else None
    except OSError:
        return None
    return target == f"pipe:[{pipe_inode}]"
