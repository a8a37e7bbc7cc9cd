"""The batch on a Dask distributed cluster (``pip install "cv-autograder[dask]"``).

Every Dask worker needs this package installed (the same version: the gradebook
key holds it). Each task is :func:`.task.grade_files`: the student's files go
out as bytes, the grading runs in the same sandbox as on one machine, and the
results model comes back as plain data to land in the local gradebook. A task
whose worker is lost is run again on another one by the scheduler; ``retries``
covers a task that fails for other reasons (it never does for a student's code), and a
task whose result the client could not get (a connection dropped, the client's state upset
by a lost worker) is sent once more.
"""

from __future__ import annotations

from .task import grade_files

RETRIES = 2


class DaskUnavailable(RuntimeError):
    """``distributed`` is not installed."""


def grade_on_dask(address: str, todo, arguments, finished, client=None, rules: dict | None = None) -> None:
    """Grade ``todo`` (entries) on the cluster at ``address``; ``finished(entry, outcome)`` per result."""
    try:
        from distributed import Client, as_completed
    except ImportError:  # pragma: no cover - depends on the extra
        raise DaskUnavailable('--dask-scheduler needs Dask: pip install "cv-autograder[dask]"') from None

    own = client is None
    client = client or Client(address)

    def submit(entry, again: bool = False):
        return client.submit(grade_files, entry.files, *arguments, entry.student_id, None, rules,
                             key=f"grade-{entry.student_id}-{entry.content_hash[:16]}{'-again' if again else ''}",
                             pure=False, retries=RETRIES)

    try:
        futures = {submit(entry): entry for entry in todo}
        sent_again = set()
        done = as_completed(futures)
        for future in done:
            entry = futures[future]
            try:
                outcome = future.result()
            except Exception as exc:  # noqa: BLE001 - KilledWorker, a lost connection ...
                if type(exc).__name__ != "KilledWorker" and entry.student_id not in sent_again:
                    # The cluster's own fault, not the task's (grade_files never raises for a student's code):
                    # a connection dropped, distributed's state upset by a lost worker. Sent once more; a task
                    # that killed worker after worker (KilledWorker) is not.
                    sent_again.add(entry.student_id)
                    again = submit(entry, again=True)
                    futures[again] = entry
                    done.add(again)
                    future.release()
                    continue
                outcome = {"error": f"the cluster could not grade it: {type(exc).__name__}: {exc}"}
            finished(entry, outcome)
            future.release()
    finally:
        if own:
            client.close()
