"""A worker started before its submission is known (grade.py starts it while the lab suites load)."""

from pathlib import Path

import numpy as np
import pytest

from autograder.sandbox.supervisor import Sandbox

ROOT = Path(__file__).resolve().parents[1]


def test_the_submission_admitted_after_the_worker_started_is_graded():
    with Sandbox(None) as sandbox:
        sandbox.start()
        assert not sandbox._ready  # booting while the caller goes on
        sandbox.admit(ROOT / "reference_solutions")
        outcome = sandbox.call("lab07_transformations", "translation_matrix", (2.0, 3.0))
        assert outcome.ok, outcome.message
        np.testing.assert_array_equal(outcome.value, [[1, 0, 2], [0, 1, 3], [0, 0, 1]])
        assert sandbox.student_seconds < 5  # the start-up itself is not billed
        with pytest.raises(RuntimeError):
            sandbox.admit(ROOT / "assignments")  # one submission, before the first request


def test_a_module_missing_from_the_admitted_submission_is_reported(tmp_path):
    (tmp_path / "lab07_transformations.py").write_text("def translation_matrix(tx, ty):\n    return 1\n")
    with Sandbox(None) as sandbox:
        sandbox.start()
        sandbox.admit(tmp_path)
        assert sandbox.call("lab07_transformations", "translation_matrix", (1, 2)).value == 1
        outcome = sandbox.import_module("lab08_homographies")
        assert not outcome.ok and outcome.kind == "missing_module"


def test_a_worker_made_ready_first_grades_the_submission_and_its_restarts_count(tmp_path):
    (tmp_path / "lab07_transformations.py").write_text(
        "import os\ndef translation_matrix(tx, ty):\n    return tx + ty\n"
        "def rotation_matrix(angle, center=None):\n    os._exit(3)\n")
    with Sandbox(None) as sandbox:
        sandbox.start()
        assert sandbox.ready() and sandbox.ready()  # the level works: the worker imported NumPy there
        sandbox.admit(tmp_path)
        assert sandbox.call("lab07_transformations", "translation_matrix", (1, 2)).value == 3
        assert sandbox.call("lab07_transformations", "rotation_matrix", (1,)).kind == "crashed"
        assert sandbox.call("lab07_transformations", "translation_matrix", (2, 2)).value == 4
        assert sandbox.restarts == 1  # billed and capped like any restart
        with pytest.raises(RuntimeError):
            sandbox.admit(ROOT / "assignments")


def test_a_worker_uses_the_opencv_threads_it_is_given(tmp_path):
    """Workers side by side (lanes, a batch's gradings) share the cores: one thread each here."""
    from autograder.sandbox.supervisor import Limits

    (tmp_path / "threads_probe.py").write_text("import cv2\n\n\ndef threads():\n    return cv2.getNumThreads()\n")
    with Sandbox(tmp_path, Limits(threads=1)) as sandbox:
        outcome = sandbox.call("threads_probe", "threads")
        assert outcome.ok and outcome.value == 1, outcome.message
