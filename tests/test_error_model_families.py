"""The error model's operators for mistakes nobody listed (issue 35): an inverse written as a
transpose, a copy-pasted index, an index on the wrong axis, stacked pieces in another order, a
loop over positions where the values belong, a normalisation undone the wrong way round or never, a bit shift the wrong way, a sign in a drawing, a name left from the line above, an element-wise product for a matrix product, a bit mask dropped,
``x or DEFAULT`` swallowing a 0, and a single point a 1-D array that raises. Each realistic
student module (a small edit of the reference's text) gets that name; the reference and a
legitimate alternative get none."""

from __future__ import annotations

import types
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from autograder.engine.mutants import naming
from autograder.engine.registry import discover
from autograder.sandbox.supervisor import CallOutcome

ROOT = Path(__file__).resolve().parents[1]
LABS = discover()


class _InProcess:
    """A stand-in for the student's sandbox: the test's own (trusted) student module, called here;
    an exception is answered as the sandbox does ("f() raised Type: text")."""

    def __init__(self, module):
        self.module, self.shared, self.asked = module, {}, []

    def call(self, module, function, args, kwargs, timeout=None, forbid=()):
        self.asked.append((function, args, kwargs))
        try:
            value = getattr(self.module, function)(*args, **kwargs)
        except Exception as exc:  # noqa: BLE001 - the student's exception, as the sandbox reports it
            return CallOutcome(ok=False, kind="exception", message=f"{function}() raised {type(exc).__name__}: {exc}")
        return CallOutcome(ok=True, value=value)


def _student(key: str, edit: tuple[str, str] | None):
    """The reference module of ``key`` with one text edit (old, new) made, executed."""
    source = (ROOT / "reference_solutions" / f"{LABS[key].module}.py").read_text()
    if edit is not None:
        assert source.count(edit[0]) == 1, edit[0]
        source = source.replace(edit[0], edit[1])
    module = types.ModuleType("student")
    exec(source, module.__dict__)  # noqa: S102 - the test's own code
    return module


def _trial(key: str, edit, calls):
    """A trial of ``calls`` [(function, args, kwargs)] on the edited module: the calls that return
    are recorded, the last one that raises is :attr:`Trial.raised`."""
    module = _student(key, edit)
    recorded, raised = [], None
    for f, a, k in calls:
        try:
            recorded.append((f, a, k, getattr(module, f)(*a, **k)))
        except Exception as exc:  # noqa: BLE001 - the student's exception, as the sandbox reports it
            raised = (f, a, k, f"{f}() raised {type(exc).__name__}: {exc}")
    return SimpleNamespace(lab=LABS[key], calls=recorded, raised=raised, sandbox=_InProcess(module),
                           check=SimpleNamespace(timeout=20), forbid={}, student_seconds=0.0, outputs=[])


def _named(trial):
    return naming.name_raised(trial, seconds=120) if trial.raised else naming.name_failure(trial, seconds=120)


RNG = np.random.default_rng(7)
K1 = np.array([[800.0, 2.0, 320.0], [0.0, 760.0, 240.0], [0.0, 0.0, 1.0]])
K2 = np.array([[700.0, 0.0, 300.0], [0.0, 720.0, 250.0], [0.0, 0.0, 1.0]])
PTS1, PTS2 = RNG.uniform(0, 600, (12, 2)), RNG.uniform(0, 600, (12, 2))
P1 = np.hstack([K1, np.zeros((3, 1))])
P2 = K2 @ np.hstack([np.eye(3), np.array([[-1.0], [0.1], [0.2]])])


def _projected(P, X):
    x = np.column_stack([X, np.ones(len(X))]) @ P.T
    return x[:, :2] / x[:, 2:]


X3 = RNG.uniform(-1, 1, (6, 3)) + [0, 0, 6]
SRC = RNG.uniform(0, 500, (6, 2))


def _mapped(points):
    h = np.column_stack([points, np.ones(len(points))]) @ np.array([[1.1, 0.1, 20], [0.05, 0.9, -10],
                                                                   [1e-4, 2e-4, 1]]).T
    return h[:, :2] / h[:, 2:]
ESSENTIAL = ("essential_8point", (PTS1, PTS2, K1, K2), {})
LINES = ("draw_epipolar_lines", (np.zeros((120, 160, 3), np.uint8),
                                 np.array([[0.02, 1.0, -60.0], [-0.05, 1.0, -30.0], [1.0, 0.1, -80.0]])), {})
TRIANGULATE = ("triangulate", (P1, P2, _projected(P1, X3), _projected(P2, X3)), {})

CASES = {
    # family 1: the inverse of K written as its transpose
    "inverse as transpose": ("lab11", ("x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T",
                                       "x1 = _homogeneous(pts1) @ K1"), [ESSENTIAL],
                             "the transpose of `K1` is used where its inverse belongs"),
    # family 2: the y row of the triangulation built from the x coordinate (copy-paste)
    "copied index": ("lab11", ("pts1[:, 1:2] * P1[2] - P1[1]", "pts1[:, 0:1] * P1[2] - P1[1]"), [TRIANGULATE],
                     "the x coordinates (column 0) of `pts1` are used where the y coordinates (column 1) belong"),
    # family 2, in a private helper: one row of the design matrix built with the other coordinate
    "copied name in a helper": ("lab08", ("rows_v = np.stack([zeros, zeros, zeros, x, y, ones, -v * x, -v * y, -v]",
                                          "rows_v = np.stack([zeros, zeros, zeros, x, y, ones, -u * x, -v * y, -v]"),
                                [("homography_dlt", (SRC, _mapped(SRC)), {})],
                                "the x coordinates (column 0) of the destination points are used where the y "
                                "coordinates (column 1) of the destination points belong"),
    # family 3: the batched SVD's null vectors taken as columns
    "index on the wrong axis": ("lab11", ("X = np.linalg.svd(A)[2][:, -1, :]", "X = np.linalg.svd(A)[2][:, :, -1]"),
                                [TRIANGULATE], "the last column of each matrix of"),
    # family 6: [t | R] for [R | t]
    "stacked in another order": ("lab09", ("Rt = np.column_stack([np.asarray(R, dtype=np.float64), np.asarray(t, "
                                           "dtype=np.float64).reshape(3)])",
                                           "Rt = np.hstack([np.asarray(t, dtype=np.float64).reshape(3, 1), "
                                           "np.asarray(R, dtype=np.float64)])"),
                                 [("camera_matrix", (K1, np.eye(3)[[1, 0, 2]], np.array([0.5, -0.2, 4.0])), {})],
                                 "`R` and `t` are stacked in the other order"),
    # a loop over positions where the values belong (the focal lengths 0, 1, 2 ...)
    "positions for values": ("lab09", ("pinhole_project(X, f) for f in np.asarray(focal_lengths, dtype=np.float64).ravel()",
                                       "pinhole_project(X, f) for f in range(len(focal_lengths))"),
                             [("project_focal_lengths", (X3, np.array([100.0, 400.0, 900.0])), {})],
                             "the loop takes the positions 0, 1, 2, ... of `focal_lengths` where its values belong"),
    # a normalisation undone with the inverse on the other transform
    "undone the wrong way round": ("lab10", ("P = np.linalg.inv(T) @ p.reshape(3, 4) @ U",
                                             "P = T @ p.reshape(3, 4) @ np.linalg.inv(U)"),
                                   [("camera_matrix_dlt", (X3 * [3, 3, 1], _projected(P2, X3 * [3, 3, 1])), {})],
                                   "the normalisation is undone the wrong way round"),
    # ... or never undone
    "never undone": ("lab08", ("H = np.linalg.inv(T2) @ Vt[-1].reshape(3, 3) @ T1", "H = Vt[-1].reshape(3, 3)"),
                     [("homography_dlt", (SRC, _mapped(SRC)), {})], "the normalisation is never undone"),
    # two entries of a design matrix's row exchanged, past the sixth (positions told by number)
    "row entries exchanged": ("lab08", ("rows_v = np.stack([zeros, zeros, zeros, x, y, ones, -v * x, -v * y, -v]",
                                        "rows_v = np.stack([zeros, zeros, zeros, x, y, ones, -v * y, -v * x, -v]"),
                              [("homography_dlt", (SRC, _mapped(SRC)), {})],
                              "the seventh and eighth pieces stacked by `np.stack` are exchanged"),
    # a drawing: its lines in other places change few pixels, named by the pixels, both ways
    "sign in a drawing": ("lab11", ("p, q = (0.0, -c / b), (width - 1.0, -(c + a * (width - 1)) / b)",
                                    "p, q = (0.0, c / b), (width - 1.0, -(c + a * (width - 1)) / b)"), [LINES],
                          "the third entry of each item of `lines` has the wrong sign"),
    # a line copied from its sibling's, one name left unchanged throughout (T1 for T2)
    "a name left from the line above": ("lab08", ("    dst_n = dst @ T2[:2, :2].T + T2[:2, 2]\n    A = _dlt_rows",
                                                  "    dst_n = dst @ T1[:2, :2].T + T1[:2, 2]\n    A = _dlt_rows"),
                                        [("homography_dlt", (SRC, _mapped(SRC)), {})],
                                        'on `src` is used where the result of the step "hartley\'s similarity" on `dst` '
                                        "belongs, everywhere in one line"),
    # arithmetic operators replaced: an element-wise product for a matrix product, a bit mask dropped
    "element-wise for matrix product": ("lab11", ("np.asarray(F, np.float64) @ np.asarray(K1, np.float64)",
                                                  "np.asarray(F, np.float64) * np.asarray(K1, np.float64)"),
                                        [("essential_from_fundamental", (P2[:, :3] @ K1.T, K1, K2), {})],
                                        "are multiplied element by element (*) where their matrix product (@) belongs"),
    "bit mask dropped": ("lab12", ("(((gray[None, :] >> shifts) & 1) * 255)", "((gray[None, :] >> shifts) * 255)"),
                         [("gray_code_patterns", (97, 5), {})], "the mask & 1 that keeps the lowest bits is missing"),
    # a bit shift the wrong way: k ^ (k << 1) for the Gray code
    "shift the wrong way": ("lab12", ("gray = k ^ (k >> 1)", "gray = k ^ (k << 1)"),
                            [("gray_code_patterns", (97, 5), {})], "(<< where >> belongs)"),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_the_mistake_is_named_by_its_operator(case):
    key, edit, calls, words = CASES[case]
    named = _named(_trial(key, edit, calls))
    assert named is not None and words in named.sentence, (case, named)


@pytest.mark.parametrize("case", sorted(CASES))
def test_the_reference_is_not_named(case):
    key, _, calls, _ = CASES[case]
    assert _named(_trial(key, None, calls)) is None


ALTERNATIVES = {   # legitimate code that differs from the reference's text
    "inverse as transpose": ("x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T",
                             "x1 = np.linalg.solve(K1, _homogeneous(pts1).T).T"),
    "copied index": ("pts1[:, 1:2] * P1[2] - P1[1]", "pts1[:, [1]] * P1[2] - P1[1]"),
    "copied name in a helper": ("rows_v = np.stack([zeros, zeros, zeros, x, y, ones, -v * x, -v * y, -v]",
                                "rows_v = np.stack([zeros, zeros, zeros, x, y, ones, -(v * x), -(v * y), -v]"),
    "index on the wrong axis": ("X = np.linalg.svd(A)[2][:, -1, :]", "X = np.linalg.svd(A)[2][..., -1, :]"),
    "stacked in another order": ("Rt = np.column_stack([np.asarray(R, dtype=np.float64), np.asarray(t, "
                                 "dtype=np.float64).reshape(3)])",
                                 "Rt = np.hstack([np.asarray(R, dtype=np.float64), "
                                 "np.asarray(t, dtype=np.float64).reshape(3, 1)])"),
    "positions for values": ("pinhole_project(X, f) for f in np.asarray(focal_lengths, dtype=np.float64).ravel()",
                             "pinhole_project(X, focal_lengths[i]) for i in range(len(focal_lengths))"),
    "undone the wrong way round": ("P = np.linalg.inv(T) @ p.reshape(3, 4) @ U",
                                   "P = np.linalg.solve(T, p.reshape(3, 4) @ U)"),
    "never undone": ("H = np.linalg.inv(T2) @ Vt[-1].reshape(3, 3) @ T1",
                     "H = np.linalg.solve(T2, Vt[-1].reshape(3, 3)) @ T1"),
    "shift the wrong way": ("gray = k ^ (k >> 1)", "gray = np.bitwise_xor(k, k // 2)"),
    "a name left from the line above": ("    dst_n = dst @ T2[:2, :2].T + T2[:2, 2]\n    A = _dlt_rows",
                                        "    dst_n = (T2[:2, :2] @ dst.T).T + T2[:2, 2]\n    A = _dlt_rows"),
    "element-wise for matrix product": ("np.asarray(F, np.float64) @ np.asarray(K1, np.float64)",
                                        "np.asarray(F, np.float64).dot(np.asarray(K1, np.float64))"),
    "bit mask dropped": ("(((gray[None, :] >> shifts) & 1) * 255)", "(((gray[None, :] >> shifts) % 2) * 255)"),
    "sign in a drawing": ("p, q = (0.0, -c / b), (width - 1.0, -(c + a * (width - 1)) / b)",
                          "p, q = (0.0, -(c / b)), (width - 1.0, -(c + a * (width - 1)) / b)"),
    "row entries exchanged": ("rows_v = np.stack([zeros, zeros, zeros, x, y, ones, -v * x, -v * y, -v]",
                              "rows_v = np.stack([zeros, zeros, zeros, x, y, ones, -(v * x), -(v * y), -v]"),
}


@pytest.mark.parametrize("case", sorted(ALTERNATIVES))
def test_a_legitimate_alternative_is_not_named(case):
    key, _, calls, _ = CASES[case]
    assert _named(_trial(key, ALTERNATIVES[case], calls)) is None


# ------------------------------------------------------------------ family 5: a 0 swallowed by `or`
def _stereo_pair():
    rng = np.random.default_rng(3)
    right = rng.integers(0, 255, (14, 30)).astype(np.uint8)
    left = np.roll(right, 3, axis=1)
    return left, right


@pytest.mark.parametrize("edit, named", [
    (("s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)",
      "s = float(smoothness or DEFAULT_SMOOTHNESS)"), True),
    (("s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)",
      "s = DEFAULT_SMOOTHNESS if smoothness is None else smoothness * 1.0"), False),
])
def test_a_zero_taken_as_not_given_is_named(edit, named):
    left, right = _stereo_pair()
    trial = _trial("lab12", edit, [("dp_stereo", (left, right), {"max_disparity": 5, "block_size": 3,
                                                                  "smoothness": 0.0})])
    found = _named(trial)
    if named:
        assert found is not None and found.mutant.operator == "default", found
        assert "a `smoothness` of 0 (or any value that is false) is taken as not given" in found.sentence
    else:
        assert found is None


# ------------------------------------------------------------------ family 7: the student's exception
ROWS = np.array([[0.1, 0.2], [-0.3, 0.05], [0.2, -0.1]])
DIST = np.array([0.1, -0.05, 0.01, 0.002, 0.0])
SINGLE = ("    pts = np.atleast_2d(pts)\n", "")


def test_a_single_point_that_raises_is_named_by_a_mutant_raising_the_same():
    """distort_points without np.atleast_2d: rows work, a single (2,) point raises IndexError; the
    mutant dropping it raises the same there and returns the student's answers on the rows."""
    trial = _trial("lab09", SINGLE, [("distort_points", (ROWS, DIST), {}),
                                     ("distort_points", (np.array([0.1, 0.2]), DIST), {})])
    assert trial.raised is not None and "IndexError" in trial.raised[3]
    found = naming.name_raised(trial, seconds=120)
    assert found is not None and found.mutant.operator == "single_point", found
    assert "a single point (a 1-D array) is not handled" in found.sentence


def test_a_single_point_raising_alone_is_confirmed_on_a_batch():
    """Only the single point was asked: the batch of two rows derived from it is the evidence that
    the rest of the student's code is the mutant's."""
    trial = _trial("lab09", SINGLE, [("distort_points", (np.array([0.1, 0.2]), DIST), {})])
    assert not trial.calls
    found = naming.name_raised(trial, seconds=120)
    assert found is not None and found.mutant.operator == "single_point", found
    assert any(np.ndim(call[1][0]) == 2 for call in trial.sandbox.asked)


@pytest.mark.parametrize("source_edit", [
    ("x, y = pts[:, 0], pts[:, 1]", "x, y = pts[:, 0], pts[:, 1]\n    raise ValueError('mine')"),   # another type
    ("pts = np.atleast_2d(pts)\n", "pts = np.atleast_2d(pts)\n    assert len(pts) > 1\n"),   # raises, no mutant does
])
def test_an_exception_no_mutant_raises_like_that_is_not_named(source_edit):
    trial = _trial("lab09", source_edit, [("distort_points", (ROWS, DIST), {}),
                                          ("distort_points", (np.array([0.1, 0.2]), DIST), {})])
    assert trial.raised is not None
    assert naming.name_raised(trial, seconds=120) is None


def test_an_exception_no_mutant_can_raise_is_decided_without_running_them(monkeypatch):
    """A NameError (a name of the student's own) is no mutant's: the helper is never asked."""
    monkeypatch.setattr(naming, "helper", lambda: pytest.fail("the helper was asked"))
    trial = _trial("lab09", ("x, y = pts[:, 0], pts[:, 1]", "x, y = pts[:, 0], ptss[:, 1]"),
                   [("distort_points", (ROWS, DIST), {})])
    assert "NameError" in trial.raised[3]
    assert naming.name_raised(trial, seconds=60) is None and not trial.sandbox.asked


def test_an_input_the_reference_raises_on_is_not_named():
    trial = _trial("lab08", None, [("homography_ransac", (ROWS, ROWS), {})])   # 3 pairs: ValueError for all
    assert trial.raised is not None
    assert naming.name_raised(trial, seconds=120) is None


def test_the_error_class_tells_two_value_errors_apart():
    broadcast = {naming.ERROR: "ValueError: operands could not be broadcast together with shapes (3,) (4,)"}
    reshape = {naming.ERROR: "ValueError: cannot reshape array of size 6 into shape (4,)"}
    assert naming._same_outcome(broadcast, dict(broadcast), None)
    assert not naming._same_outcome(broadcast, reshape, None)
    assert not naming._same_outcome(np.eye(3), broadcast, np.eye(3))
    assert naming.raised_answer("Your points are (3,).\nf() raised IndexError: too many indices") == \
        {naming.ERROR: "IndexError: too many indices"}


def test_in_a_grading_a_check_ended_by_the_students_exception_is_named(tmp_path):
    """The runner passes a check that ended by the student's exception to the error model
    (:attr:`Trial.raised`): `_points` without np.atleast_2d raises on the lab sheet's single point."""
    from autograder.engine.runner import grade

    source = (ROOT / "reference_solutions" / "lab09_camera.py").read_text()
    old = "    return np.atleast_2d(points), points.ndim == 1\n"
    assert source.count(old) == 1
    (tmp_path / "lab09_camera.py").write_text(source.replace(old, "    return points, points.ndim == 1\n"))
    result = grade(tmp_path, ["lab09.ex1"], pictures="none")
    failed = [c for e in result.exercises for c in e.checks if c.score < c.max_score]
    assert failed and all(c.failure == "exception" for c in failed)
    # (or the line made the reference's again: a repair takes a mutant's place)
    assert any((c.mistake == "mutant:single_point" and "IndexError" in c.message
                and "a single point (a 1-D array) is not handled" in c.message)
               or (c.mistake == "repair:aligned" and "np.atleast_2d(points)" in c.message) for c in failed), \
        [c.message for c in failed]


def test_an_array_tested_for_truth_is_named_on_the_call_without_it(monkeypatch):
    """`if not dist` on lab 10's estimate_pose: a given distortion array raises ValueError (its truth
    value is ambiguous). Only that call was made; the same call with dist left as None returns the
    reference's pose, the evidence that the rest of the code is the `default` mutant's. Named with a
    long budget (a grading's 3 s do not run this pipeline's 114 mutants once; the answer cache does
    over a class)."""
    from fixtures import lab10 as truth

    # each helper run finds the board in six images: the per-run second is the grader's, not this test's
    monkeypatch.setattr(naming, "_timeout", lambda clock: max(0.05, min(20.0, clock.left())))
    image = truth.pose_views()[0][0]
    call = ("estimate_pose", (image, truth.POSE_PATTERN, truth.POSE_SQUARE, truth.POSE_K,
                              np.array([0.05, -0.02, 0.0, 0.0, 0.0])), {})
    edit = ("    dist = None if dist is None else np.asarray(dist, dtype=np.float64)\n",
            "    dist = None if not dist else np.asarray(dist, dtype=np.float64)\n")
    trial = _trial("lab10", edit, [call])
    assert trial.raised is not None and "truth value of an array" in trial.raised[3]
    found = naming.name_raised(trial, seconds=300)
    assert found is not None and found.mutant.operator == "default", found
    assert any(asked[1][4] is None for asked in trial.sandbox.asked)   # the call without dist
    assert naming.name_raised(_trial("lab10", None, [call]), seconds=60) is None   # the reference raises nothing
