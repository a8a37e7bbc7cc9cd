"""A broken or hostile submission costs only its own exercise, with a clear message."""

import importlib.util
import json

import pytest

from autograder.engine.results import without_timings
from autograder.engine.runner import grade
from autograder.sandbox.supervisor import Limits
from autograder.sandbox import confine
from conftest import REFERENCE, ROOT, assert_only_exercise_lost, check_results, mutant, submission_from_source

MODULE = "lab07_transformations"
FAST = Limits(call_timeout=2.0, import_timeout=4.0)


def scores(result):
    return {e.id: (e.score, e.max_score) for e in result.exercises}


def test_infinite_loop_costs_only_its_exercise(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        def shear_matrix(s):
            while True:
                pass
        """), ["lab07"], limits=FAST)
    assert_only_exercise_lost(result, "lab07.ex4", "did not finish within 2 s",
                              "timed out 2 times already; not called again")


def test_exception_costs_only_its_exercise_and_shows_student_frames_only(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        def scaling_matrix(sx, sy):
            return helper(sx)

        def helper(sx):
            raise ValueError("bad scale")
        """), ["lab07"], limits=FAST)
    assert_only_exercise_lost(result, "lab07.ex3", "ValueError: bad scale")
    tb = check_results(result, "lab07.ex3")[0].traceback
    assert "in helper" in tb and "in scaling_matrix" in tb
    assert "autograder" not in tb and "worker.py" not in tb


def test_huge_allocation_costs_only_its_exercise(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        def shear_matrix(s):
            return np.ones(10 * 2**30 // 8)  # 10 GB
        """), ["lab07"], limits=FAST)
    assert_only_exercise_lost(result, "lab07.ex4", "shear_matrix() asked for more than 6144 MB of memory (MemoryError)")


def test_always_equal_ndarray_subclass_is_refused(tmp_path, no_naming):
    """(Naming off: the refusal is the transport's, named by nothing else; 7 s -> 2 s.)"""
    result = grade(mutant(tmp_path, MODULE, """
        class Liar(np.ndarray):
            def __eq__(self, other):
                return True
            __ne__ = lambda self, other: False

        def translation_matrix(tx, ty):
            return np.zeros((3, 3)).view(Liar)
        """), ["lab07.ex1", "lab07.ex2"], limits=FAST)
    checks = check_results(result, "lab07.ex1")
    assert checks[0].score == 0 and "ndarray subclass" in checks[0].message
    score, maximum = scores(result)["lab07.ex2"]
    assert score == maximum > 0


def test_crash_restarts_the_worker_for_the_next_exercise(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        def scaling_matrix(sx, sy):
            import os
            os._exit(0)
        """), ["lab07"], limits=FAST)
    assert_only_exercise_lost(result, "lab07.ex3", "ended the worker process")


@pytest.mark.parametrize("source, message", [
    ("import sys\nsys.exit(0)\n", "lab07_transformations.py called sys.exit(0) while being imported"),
    ("import os\nos._exit(0)\n", "importing lab07_transformations.py ended the worker process"),
])
def test_exit_at_import_costs_the_module_with_a_clear_message(tmp_path, source, message):
    result = grade(submission_from_source(tmp_path, MODULE, source), ["lab07"], limits=FAST)
    for exercise in result.exercises:
        assert exercise.score == 0
        assert message in exercise.message


def test_a_file_importing_another_labs_module_handed_in_alone_is_told_to_hand_in_both(tmp_path):
    """A lab 8 file reusing lab 7's functions imports lab07_transformations: beside it, it grades; alone,
    the import error says which lab's file is missing and what to do; a module nobody hands in is left
    as Python says it."""
    reused = (REFERENCE / "lab08_homographies.py").read_text()
    (tmp_path / "lab08_homographies.py").write_text("from lab07_transformations import rotation_matrix\n" + reused)
    alone = grade(tmp_path, ["lab08.ex1"], limits=FAST)
    message = alone.exercises[0].message
    assert alone.exercises[0].score == 0 and "No module named 'lab07_transformations'" in message
    assert "lab07_transformations.py is the file of lab07, which lab08_homographies.py imports: hand it in " \
           "beside lab08_homographies.py" in message
    (tmp_path / "lab07_transformations.py").write_text((REFERENCE / "lab07_transformations.py").read_text())
    both = grade(tmp_path, ["lab08.ex1"], limits=FAST)
    assert both.exercises[0].score == both.exercises[0].max_score > 0
    (tmp_path / "lab08_homographies.py").write_text("import lab99_nowhere\n" + reused)
    unknown = grade(tmp_path, ["lab08.ex1"], limits=FAST).exercises[0].message
    assert "No module named 'lab99_nowhere'" in unknown and "hand it in" not in unknown


@pytest.mark.skipif(not confine.detect().hides_files, reason="the process-group level sees every installed library")
def test_a_library_the_sandbox_does_not_offer_is_told_with_what_it_offers(tmp_path):
    """`from tqdm import tqdm` (installed beside the grader, pinned in constraints.txt) made a whole lab 0 with only
    "No module named 'tqdm'" (third-party round of 2026-12-07): the message says what graded code may import, and
    that the library being installed where the grader runs changes nothing; a library nowhere, alike."""
    reference = (REFERENCE / f"{MODULE}.py").read_text()
    for name in ("tqdm", "surely_not_a_library"):
        installed = importlib.util.find_spec(name) is not None
        (tmp_path / f"{MODULE}.py").write_text(f"import {name}\n" + reference)
        message = grade(tmp_path, ["lab07.ex1"], limits=FAST).exercises[0].message
        assert f"No module named '{name}'" in message and "graded code may import Python's standard library, NumPy, " \
            "OpenCV (cv2), SciPy, scikit-image and Matplotlib" in message, message
        assert ("is installed where the grader runs" in message) == installed, message
        # (a name found nowhere may be a file of the student's own not handed in)
        assert (f"if {name}.py is a file of yours, add it to what you hand in" in message) == (not installed), message


def test_infinite_loop_at_import(tmp_path):
    result = grade(submission_from_source(tmp_path, MODULE, """
        while True:
            pass
        """), ["lab07"], limits=FAST)
    assert all(e.score == 0 for e in result.exercises)
    assert "importing lab07_transformations.py did not finish" in result.exercises[0].message
    assert result.seconds < 30  # the import is attempted once, not once per check


def test_syntax_error_points_at_file_and_line(tmp_path):
    result = grade(submission_from_source(tmp_path, MODULE, """
        import numpy as np

        def translation_matrix(tx, ty)
            return np.eye(3)
        """), ["lab07.ex1"], limits=FAST)
    message = result.exercises[0].message
    assert "SyntaxError in lab07_transformations.py, line 4" in message


def test_missing_module_and_missing_function(tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    result = grade(empty, ["lab07.ex1"], limits=FAST)
    assert result.exercises[0].message == "module lab07_transformations.py not found"
    partial_source = (REFERENCE / f"{MODULE}.py").read_text().replace("def rotate(", "def rotate_image(")
    folder = tmp_path / "partial"
    folder.mkdir()
    (folder / f"{MODULE}.py").write_text(partial_source)
    result = grade(folder, ["lab07.ex2"], limits=FAST)
    messages = [c.message for c in result.exercises[0].checks]
    assert "not found: def rotate(image, angle_deg=45)" in messages


def test_printed_output_is_captured_and_truncated(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        _original_translation_matrix = translation_matrix

        def translation_matrix(tx, ty):
            print("debug: tx =", tx)
            print("x" * 100000)
            return _original_translation_matrix(tx, ty)
        """), ["lab07.ex1"], limits=FAST)
    check = check_results(result, "lab07.ex1")[0]
    assert check.passed
    assert "debug: tx = 100" in check.output
    assert len(check.output) < 10000 and "more bytes of output not shown" in check.output


def test_grading_twice_gives_identical_json_apart_from_timings():
    first = grade(REFERENCE, ["lab07"]).to_dict()
    second = grade(REFERENCE, ["lab07"]).to_dict()
    assert json.dumps(without_timings(first)) == json.dumps(without_timings(second))


def test_monkeypatching_numpy_in_the_submission_changes_nothing_judged(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        np.allclose = lambda *a, **k: True
        np.testing.assert_allclose = lambda *a, **k: None

        def translation_matrix(tx, ty):
            return np.zeros((3, 3))
        """), ["lab07.ex1"], limits=FAST)
    assert check_results(result, "lab07.ex1")[0].score == 0


def test_the_original_submission_folder_is_left_untouched(tmp_path):
    folder = mutant(tmp_path, MODULE, """
        import os
        for name in os.listdir("."):
            os.remove(name)
        with open("results.json", "w") as f:
            f.write("{}")
        """)
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    grade(folder, ["lab07.ex1"], limits=FAST)
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before


def test_worker_limits_are_best_effort_where_the_platform_refuses_one():
    """macOS refuses RLIMIT_AS: the worker must still start, with the other limits set."""
    import subprocess
    import sys

    script = f"""
import resource, sys
sys.path.insert(0, {str(ROOT / "autograder" / "sandbox")!r})
import worker
real = resource.setrlimit
def refuse_address_space(which, limits):
    if which == resource.RLIMIT_AS:
        raise ValueError("not supported on this platform")
    return real(which, limits)
resource.setrlimit = refuse_address_space
worker.apply_limits({{"address_space": 2**33, "file_size": 2**26, "cpu_total": 100, "processes": None}})
print(resource.getrlimit(resource.RLIMIT_FSIZE)[0], resource.getrlimit(resource.RLIMIT_CPU)[0])
"""
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == [str(2**26), "100"]


def test_an_exception_while_judging_is_that_checks_grader_error_only():
    import dataclasses

    import numpy as np

    from autograder.engine.registry import select
    from autograder.engine.runner import run_check
    from autograder.sandbox.supervisor import Sandbox

    [exercise] = select(["lab07.ex4"])
    check = exercise.checks[0]

    def broken(t):
        t.images("undrawable", yours=np.zeros(()))   # a 0-d array: left out of the page
        raise KeyError("a bug in the check")

    with Sandbox(REFERENCE, FAST) as sandbox:
        failed = run_check(sandbox, dataclasses.replace(check, func=broken))
        after = run_check(sandbox, check)
    assert failed.status == "grader error" and "KeyError" in failed.message
    assert failed.artifacts == [] or all(a.items == [] for a in failed.artifacts)
    assert after.passed


def test_course_budgets_reach_the_sandbox():
    from autograder.instructor.course import CourseConfig, CourseConfigError

    limits = CourseConfig(call_timeout=3, exercise_budget=30, submission_budget=200).limits()
    assert (limits.call_timeout, limits.exercise_budget, limits.submission_budget) == (3, 30, 200)
    for key in ("exercise_budget", "submission_budget"):
        with pytest.raises(CourseConfigError, match=key):
            CourseConfig(**{key: 0})
