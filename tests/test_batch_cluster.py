"""The batch on a Dask cluster: a result the client could not get is asked for once more."""

import time
from dataclasses import dataclass

import pytest

from autograder.instructor.batch import cluster

distributed = pytest.importorskip("distributed", reason="the dask extra (distributed) is not installed")


@dataclass
class Entry:
    student_id: str
    content_hash: str = "0" * 16
    files: dict = None


FAILURES: dict = {}   # student id -> how many more times its task raises


def flaky_grading(files, *arguments):
    student = arguments[-3]   # (grade_files' arguments: ..., student id, None, rules)
    if FAILURES.get(student, 0) > 0:
        FAILURES[student] -= 1
        raise RuntimeError("the cluster's own fault")
    return {"graded": student}


class KilledWorker(Exception):
    """What the client gets for a task whose workers all died running it (distributed's name)."""


KILLS = []


def killing_grading(files, *arguments):
    KILLS.append(arguments[-3])
    raise KilledWorker("grade-eve")


def _graded(monkeypatch, grading, students):
    monkeypatch.setattr(cluster, "grade_files", grading)
    got = {}
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0") as local, \
            distributed.Client(local) as client:
        cluster.grade_on_dask(local.scheduler_address, [Entry(s) for s in students], (),
                              lambda entry, outcome: got.setdefault(entry.student_id, outcome), client=client)
    return got


def test_a_task_failing_past_the_schedulers_retries_is_sent_once_more(monkeypatch):
    # (the scheduler runs a task 1 + RETRIES times; one failure more reaches the client, which sends it again)
    FAILURES.update({"ada": cluster.RETRIES + 1, "bob": 0, "cy": 2 * (cluster.RETRIES + 1)})
    got = _graded(monkeypatch, flaky_grading, ["ada", "bob", "cy"])
    assert got["ada"] == {"graded": "ada"} and got["bob"] == {"graded": "bob"}
    assert "the cluster could not grade it: RuntimeError" in got["cy"]["error"]   # (once more only)
    assert FAILURES["cy"] == 0


def test_a_task_that_killed_its_workers_is_not_sent_again(monkeypatch):
    got = _graded(monkeypatch, killing_grading, ["eve"])
    assert "the cluster could not grade it: KilledWorker" in got["eve"]["error"]
    assert KILLS == ["eve"] * (1 + cluster.RETRIES)   # (the scheduler's runs only)


ORDER = []


def hanging_grading(files, *arguments):
    student = arguments[-3]
    ORDER.append(student)
    if student == "slow":
        time.sleep(3.0)   # (a grading that never ends, as far as a 1 s bound is concerned)
    return {"graded": student}


def test_a_grading_running_past_the_overdue_bound_is_stopped_and_the_others_graded(monkeypatch):
    """One worker thread: "slow" runs past the bound and is told it was stopped (not sent again); "queued" waits
    behind it on the same thread, and its bound counts from when it starts, so it is graded, not stopped."""
    monkeypatch.setattr(cluster, "grade_files", hanging_grading)
    monkeypatch.setattr(cluster, "POLL_SECONDS", 0.2)
    got = {}
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0") as local, \
            distributed.Client(local) as client:
        cluster.grade_on_dask(local.scheduler_address, [Entry(s) for s in ("slow", "queued")], (),
                              lambda entry, outcome: got.setdefault(entry.student_id, outcome), client=client,
                              overdue=1.0)
    assert "the grading was stopped after 1 s on the cluster" in got["slow"]["error"], got
    assert got["queued"] == {"graded": "queued"}
    assert ORDER == ["slow", "queued"]   # (queued behind the slow one: more than 1 s after it was handed out)
