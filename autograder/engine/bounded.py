"""A backstop on the grader's own work about one check: its CPU time and the memory it makes the grader hold.

Judging a check and naming its failure run in the grader's process, over the student's answers and code: the
searches keep their own clocks (:mod:`autograder.engine.mutants.naming`), and the student's calls their
deadlines, but a loop in a reader, an operator or a judge that some shape of code nobody foresaw sends round
and round checks no clock (the first syntax-tree walk did: it wrapped the node it was reading again and again
and grew past 19 GB). :func:`bounded` stops such work in the thread doing it: a watchdog thread measures that
thread's own CPU time (waiting for a worker costs none, so a slow student call is never the grader's) and the
process's resident memory, and past either bound raises :class:`Runaway` in it (again each second while the work
goes on: a handler on the way, or a bound within this one, may have swallowed it). What was being worked out is
left out -- a name, a hint, or the check's verdict, which is then a grader error -- and the grading goes on.

The bounds are far beyond any legitimate work (a backstop, not a budget): a bound that fires is a fault of the
grader's, logged as such. A batch has a second one for whatever this cannot stop, a loop inside C code
(:class:`autograder.instructor.batch.processes.GradingPool` stops a grading process long overdue).

    >>> with bounded(cpu_seconds=60):      # doctest: +SKIP
    ...     named = name_the_failure()
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import threading
import time
from dataclasses import dataclass

MEMORY_GROWTH = 2 * 2**30   # bytes the grader may come to hold beyond what it held when the work began
POLL_SECONDS = 0.1          # how often the watchdog looks
AGAIN_SECONDS = 1.0         # a Runaway something swallowed is raised again after this long


class Runaway(BaseException):
    """Raised in a thread whose bounded work went past its bound. A BaseException, as KeyboardInterrupt is:
    a reader's own ``except Exception`` does not swallow it; whoever bounded the work catches it."""


@dataclass(eq=False)
class _Guard:
    thread: int                      # threading.get_ident() of the bounded thread
    clock: int | None                # its CPU-time clock; None where there is none (then wall-clock time)
    cpu_seconds: float
    memory: int | None               # resident bytes past which it is stopped; None where unmeasured
    started: float = 0.0
    fired: str = ""                  # why it was stopped, once it was
    again: float = 0.0               # time.monotonic() from which it is raised again (the work went on)

    def used(self) -> float:
        now = time.clock_gettime(self.clock) if self.clock is not None else time.monotonic()
        return now - self.started


def _thread_clock() -> int | None:
    try:
        return time.pthread_getcpuclockid(threading.get_ident())
    except (AttributeError, OSError):   # (macOS has no per-thread clock: wall-clock time, bounded more loosely)
        return None


def resident_bytes() -> int | None:
    """The grader process's resident memory now (Linux), or None."""
    try:
        with open("/proc/self/statm", "rb") as statm:
            return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return None


def _raise_in(thread: int, exception) -> None:
    """Raise ``exception`` in ``thread`` at its next Python instruction (None: cancel one not raised yet)."""
    ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(thread),
                                               None if exception is None else ctypes.py_object(exception))


class _Watchdog:
    """One daemon thread for every bound of the process; it sleeps while nothing is bounded."""

    def __init__(self):
        self._lock = threading.Condition()
        self._guards: set[_Guard] = set()
        self._thread: threading.Thread | None = None

    def add(self, guard: _Guard) -> None:
        with self._lock:
            self._guards.add(guard)
            if self._thread is None or not self._thread.is_alive():
                self._thread = threading.Thread(target=self._watch, name="grader-watchdog", daemon=True)
                self._thread.start()
            self._lock.notify()

    def remove(self, guard: _Guard) -> bool:
        """Take ``guard`` off (it cannot fire afterwards); whether it fired."""
        with self._lock:
            self._guards.discard(guard)
            return bool(guard.fired)

    def _watch(self) -> None:
        while True:
            with self._lock:
                while not self._guards:
                    self._lock.wait()
                resident = resident_bytes() if any(g.memory is not None for g in self._guards) else None
                now = time.monotonic()
                for guard in self._guards:
                    if guard.fired and now < guard.again:
                        continue
                    used, why = guard.used(), ""
                    if used > guard.cpu_seconds:
                        why = (f"{used:.3g} s of the grader's own CPU time, past its bound of "
                               f"{guard.cpu_seconds:.3g} s" if guard.clock is not None else
                               f"{used:.3g} s, past its bound of {guard.cpu_seconds:.3g} s")
                    elif guard.memory is not None and resident is not None and resident > guard.memory:
                        why = f"the grader came to hold {resident / 2**30:.1f} GB, past its bound"
                    if why:   # (again, while the work goes on: a handler on the way may have swallowed it)
                        guard.fired, guard.again = guard.fired or why, now + AGAIN_SECONDS
                        _raise_in(guard.thread, Runaway)
                self._lock.wait(POLL_SECONDS)


_WATCHDOG = _Watchdog()


@contextlib.contextmanager
def bounded(cpu_seconds: float, memory_growth: int | None = MEMORY_GROWTH):
    """Run the body with at most ``cpu_seconds`` of this thread's CPU time (wall-clock time, three times as
    much, where the platform has no per-thread clock) and the process's resident memory at most
    ``memory_growth`` bytes above what it is now; past either, :class:`Runaway` is raised in the body, its
    message saying which bound. Nothing is raised after the body has ended."""
    clock = _thread_clock()
    resident = resident_bytes() if memory_growth is not None else None
    guard = _Guard(thread=threading.get_ident(), clock=clock,
                   cpu_seconds=cpu_seconds if clock is not None else 3 * cpu_seconds,
                   memory=None if resident is None else resident + memory_growth)
    guard.started = time.clock_gettime(clock) if clock is not None else time.monotonic()
    _WATCHDOG.add(guard)
    try:
        yield guard
    except Runaway:
        raise Runaway(guard.fired or "stopped") from None
    finally:
        if _WATCHDOG.remove(guard):
            _raise_in(guard.thread, None)   # (fired as the body was ending: it is not raised after it)
