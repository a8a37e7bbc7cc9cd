"""The batch on a Dask distributed cluster (``pip install "cv-autograder[dask]"``).

Every Dask worker needs this package installed (the same version: the gradebook
key holds it). Each task is :func:`.task.grade_files`: the student's files go
out as bytes, the grading runs in the same sandbox as on one machine, and the
results model comes back as plain data to land in the local gradebook. A task
whose worker is lost is run again on another one by the scheduler; ``retries``
covers a task that fails for other reasons (it never does for a student's code), and a
task whose result the client could not get (a connection dropped, the client's state upset
by a lost worker) is sent once more.

A grading still running long after its own deadline (the grader's fault: a loop in C code
that the grading's own backstop cannot interrupt) is stopped as on one machine: each task
says on the cluster's event log when it starts, and one running past the batch's overdue
bound is cancelled and its worker restarted (the other tasks it held are run again by the
scheduler); the submission is told it was stopped, and is not sent again.
"""

from __future__ import annotations

import asyncio
import threading
import time

from .task import grade_files

RETRIES = 2
STARTED = "autograder-grading-started"   # the event-log topic a task's start is said on
POLL_SECONDS = 5.0                       # how often running tasks are looked at for the overdue bound


class DaskUnavailable(RuntimeError):
    """``distributed`` is not installed."""


def grading_on_a_worker(files, *arguments) -> dict:
    """The task: :func:`.task.grade_files`, its start said first on the event log (key, worker),
    so the client counts its overdue bound from when it runs, not from when it was queued."""
    try:
        from distributed import get_worker
    except ImportError:  # pragma: no cover - a Dask worker has it
        raise DaskUnavailable('a Dask worker needs Dask: pip install "cv-autograder[dask]"') from None
    try:
        worker = get_worker()
    except ValueError:   # (not on a worker: nothing to say it to)
        worker = None
    if worker is not None:
        worker.log_event(STARTED, {"key": worker.get_current_task(), "worker": worker.address})
    return grade_files(files, *arguments)


def grade_on_dask(address: str, todo, arguments, finished, client=None, rules: dict | None = None,
                  overdue: float | None = None) -> None:
    """Grade ``todo`` (entries) on the cluster at ``address``; ``finished(entry, outcome)`` per result.
    ``overdue``: the seconds a task may run (default: the batch's bound, :func:`.run.overdue_after`)."""
    try:
        from distributed import Client, wait
    except ImportError:  # pragma: no cover - depends on the extra
        raise DaskUnavailable('--dask-scheduler needs Dask: pip install "cv-autograder[dask]"') from None
    if overdue is None:
        from .run import overdue_after

        overdue = overdue_after(rules)

    own = client is None
    client = client or Client(address)
    started: dict[str, tuple[str, float]] = {}   # task key -> (worker, when it said it started)
    lock = threading.Lock()

    def said_started(event) -> None:
        _, message = event
        if isinstance(message, dict) and isinstance(message.get("key"), str):
            with lock:
                started[message["key"]] = (str(message.get("worker")), time.monotonic())

    def submit(entry, again: bool = False):
        return client.submit(grading_on_a_worker, entry.files, *arguments, entry.student_id, None, rules,
                             key=f"grade-{entry.student_id}-{entry.content_hash[:16]}{'-again' if again else ''}",
                             pure=False, retries=RETRIES)

    client.subscribe_topic(STARTED, said_started)
    try:
        pending = {submit(entry): entry for entry in todo}
        sent_again = set()
        while pending:
            try:
                wait(list(pending), timeout=min(POLL_SECONDS, overdue), return_when="FIRST_COMPLETED")
            except (TimeoutError, asyncio.TimeoutError):
                pass
            for future in [f for f in pending if f.done()]:
                entry = pending.pop(future)
                try:
                    outcome = future.result()
                except Exception as exc:  # noqa: BLE001 - KilledWorker, a lost connection ...
                    if type(exc).__name__ != "KilledWorker" and entry.student_id not in sent_again:
                        # The cluster's own fault, not the task's (grade_files never raises for a student's code):
                        # a connection dropped, distributed's state upset by a lost worker. Sent once more; a task
                        # that killed worker after worker (KilledWorker) is not.
                        sent_again.add(entry.student_id)
                        pending[submit(entry, again=True)] = entry
                        future.release()
                        continue
                    outcome = {"error": f"the cluster could not grade it: {type(exc).__name__}: {exc}"}
                finished(entry, outcome)
                future.release()
            now = time.monotonic()
            for future, entry in list(pending.items()):
                with lock:
                    begun = started.get(future.key)
                if begun is None or now - begun[1] <= overdue or future.done():
                    continue
                # (run again, it would hang again: stopped and told, as a local batch's overdue process is)
                pending.pop(future)
                client.cancel([future])
                try:
                    client.restart_workers([begun[0]], raise_for_error=False)
                except Exception:  # noqa: BLE001 - a worker no nanny restarts (threads): its task is let be
                    pass
                finished(entry, {"error": f"the grading was stopped after {overdue:g} s on the cluster, long past its "
                                          "own deadline: the grader never finished it (a fault of the grader's, not "
                                          "of this submission's code)"})
    finally:
        try:
            client.unsubscribe_topic(STARTED)
        except Exception:  # noqa: BLE001 - a closed client
            pass
        if own:
            client.close()
