"""The API's conventions on forms (autograder/engine/conventions.py): every lab says, for each of its
functions with images or points, which check judges the convention or why none does; the judges
pass a right answer whatever its form of computing, and fail a form that changes with how the same
input is given, in words."""

import re

import numpy as np

import pytest

from autograder.engine import conventions
from autograder.engine.registry import discover
from conftest import mutant
from autograder.engine.runner import grade

BUILT_IN = re.compile(r"lab(0[7-9]|1[0-2])")
IMAGES = {"image", "img1", "img2", "reference", "moving", "img_l", "img_r", "left", "right", "images", "frames"}
POINTS = {"points", "pts", "pts1", "pts2", "xl", "xr", "points3d", "points2d", "src", "dst"}


def _parameters(signature: str) -> set[str]:
    inside = signature[signature.index("(") + 1:signature.rindex(")")]
    return {part.split("=")[0].strip() for part in inside.split(",")}


def _functions():
    for lab in discover().values():
        if BUILT_IN.fullmatch(lab.key):
            for exercise in lab.exercises.values():
                yield from exercise.signatures.items()


@pytest.mark.parametrize("convention, names", [("channels", IMAGES), ("rows", POINTS), ("integers", POINTS)])
def test_every_function_with_images_or_points_is_judged_or_says_why_not(convention, names):
    unsaid = sorted(function for function, signature in _functions() if _parameters(signature) & names
                    and function not in conventions.DECLARED[convention]
                    and (convention, function) not in conventions.DECLARED["not judged"])
    assert unsaid == []


def test_what_is_declared_exists_and_is_declared_once():
    functions = {function for function, _ in _functions()}
    declared = {**conventions.DECLARED["channels"], **conventions.DECLARED["rows"], **conventions.DECLARED["integers"]}
    reasons = conventions.DECLARED["not judged"]
    assert set(declared) <= functions
    assert {function for _, function in reasons} <= functions
    assert all(function not in conventions.DECLARED[convention] for convention, function in reasons)
    assert all(why.strip() for why in reasons.values())


def _failed(result, exercise_id):
    return {c.name: c for e in result.exercises if e.id == exercise_id for c in e.checks if c.score < c.max_score}


def test_a_squeezed_answer_fails_only_the_one_row_check_in_words(tmp_path):
    submission = mutant(tmp_path, "lab10_camera2", """
        _reference = perspective_project
        def perspective_project(points, f):
            return np.squeeze(_reference(points, f))
        """)
    failed = _failed(grade(submission, ["lab10.ex1"]), "lab10.ex1")
    assert list(failed) == ["perspective_project answers a one-row array as the same point among many"]
    message = next(iter(failed.values())).message
    assert "one-row array of shape (1, 3)" in message and "shape (2,); expected (1, 2)" in message


def test_an_answer_for_one_point_that_differs_from_the_same_point_among_many_is_told(tmp_path):
    # (1, 3) read as the single point's coordinates in another order: one row only
    submission = mutant(tmp_path, "lab09_camera", """
        _reference = project_with_intrinsics
        def project_with_intrinsics(K, points):
            X = np.asarray(points, dtype=np.float64)
            if X.shape == (1, 3):
                X = X[:, [1, 0, 2]]
            return _reference(K, X)
        """)
    failed = _failed(grade(submission, ["lab09.ex2"]), "lab09.ex2")
    assert list(failed) == ["project_with_intrinsics answers a one-row array as the same point among many"]
    check = next(iter(failed.values()))
    assert "but the same point among 6 gives" in check.message
    assert not check.mistake or check.mistake.startswith("repair:")   # measured: only a repair of the code names it


def test_other_right_recipes_pass(tmp_path):
    # a float32 warp and points returned as float32: the form of the answer, not its precision, is judged
    submission = mutant(tmp_path, "lab09_camera", """
        _reference = project_onto_image
        def project_onto_image(image, P, points):
            drawn, pts = _reference(image, P, points)
            return drawn, pts.astype(np.float32)
        """)
    result = grade(submission, ["lab09.ex5"])
    names = [c.name for e in result.exercises for c in e.checks]
    assert "project_onto_image answers grey images in grey (the API: an image's channels are kept)" in names
    assert not any("grey images in grey" in name for name in _failed(result, "lab09.ex5"))


def test_a_grey_image_answered_in_bgr_is_told_and_an_exception_on_grey_names_its_input(tmp_path):
    submission = mutant(tmp_path, "lab08_homographies", """
        def warp_to_reference(reference, moving, H):
            grey = cv2.cvtColor(moving, cv2.COLOR_BGR2GRAY)   # raises for a grey image
            h, w = reference.shape[:2]
            return cv2.warpPerspective(moving, np.asarray(H, dtype=np.float64), (w, h))
        """)
    failed = _failed(grade(submission, ["lab08.ex2"]), "lab08.ex2")
    assert list(failed) == ["warp_to_reference answers grey images in grey (the API: an image's channels are kept)"]
    message = next(iter(failed.values())).message
    assert message.startswith("warp_to_reference(reference, moving, H) on grey images (the BGR inputs converted")


def test_an_image_of_floats_kept_grey_is_not_told_its_channels_are_lost(tmp_path):
    """A warp returned in float32 (the dtype is another check's to judge) keeps a grey image grey: the
    channels check passes, where it once read the BGR float answer as a matrix and told the grey one
    "a grey (H, W) image where a BGR (H, W, 3) one is asked" (30l's lab08/04)."""
    submission = mutant(tmp_path, "lab08_homographies", """
        def warp_to_reference(reference, moving, H):
            h, w = reference.shape[:2]
            return cv2.warpPerspective(moving.astype(np.float32), np.asarray(H, dtype=np.float64), (w, h))
        """)
    failed = _failed(grade(submission, ["lab08.ex2"]), "lab08.ex2")
    assert failed and not any("channels are kept" in name for name in failed), list(failed)
    assert any("float32" in c.message for c in failed.values()), [c.message for c in failed.values()]


def test_a_float32_answer_is_judged_at_float32s_precision():
    """One row and many rows of a float32 product may round differently (BLAS sums them in another
    order): a float32 rounding apart is the same answer; a float64 answer that far apart is not."""
    from autograder.engine.conventions import _close

    many = np.array([[123.456, 78.9]], dtype=np.float32)
    alone = many * np.float32(1 + 2 ** -22)   # a couple of float32 roundings apart
    assert _close(alone, many)
    assert not _close(many.astype(np.float64) * (1 + 1e-5), many.astype(np.float64))


def test_points_given_as_integers_answered_in_integers_are_told_with_the_line_that_makes_the_array(tmp_path):
    submission = mutant(tmp_path, "lab10_camera2", """
        _reference = weak_perspective_project
        def weak_perspective_project(points, f, z_avg=None):
            pts = np.asarray(points)
            projected = np.zeros_like(pts[..., :2])
            projected[...] = _reference(points, f, z_avg)
            return projected
        """)
    failed = _failed(grade(submission, ["lab10.ex2"]), "lab10.ex2")
    assert list(failed) == ["weak_perspective_project answers whole numbers given as integers as it answers them as floats"]
    message = next(iter(failed.values())).message
    assert "(dtype int64)" in message and "your answer is an integer array" in message
    assert "`projected = np.zeros_like(pts[..., :2])` (line" in message and "then writes into it" in message


def test_an_integer_answer_from_code_that_makes_no_array_of_the_inputs_dtype_names_no_line(tmp_path):
    # the answer converted to the input's dtype on its way out: no array is written into, no line is named
    submission = mutant(tmp_path, "lab11_two_view", """
        _reference = triangulate
        def triangulate(P1, P2, pts1, pts2):
            return _reference(P1, P2, pts1, pts2).astype(np.asarray(pts1).dtype)
        """)
    failed = _failed(grade(submission, ["lab11.ex1"]), "lab11.ex1")
    check = failed["triangulate answers whole numbers given as integers as it answers them as floats"]
    assert "your answer is an integer array" in check.message and "of the input's dtype" not in check.message


def test_refusing_integer_points_is_allowed_and_opencv_recipes_pass(tmp_path):
    # the API gives floats: raising on integers is no mistake; cv2.projectPoints on float32 answers alike
    submission = mutant(tmp_path, "lab08_homographies", """
        def transform_points(H, pts):
            if np.asarray(pts).dtype.kind != "f":
                raise TypeError("pts must be a float array")
            moved = cv2.perspectiveTransform(np.asarray(pts, np.float64).reshape(-1, 1, 2), np.asarray(H, np.float64))
            return moved.reshape(-1, 2)
        """)
    checks = {c.name: c for e in grade(submission, ["lab08.ex1"]).exercises for c in e.checks}
    refused = checks["transform_points answers whole numbers given as integers as it answers them as floats"]
    assert refused.score == refused.max_score and "refusing integers is allowed" in refused.message
    submission = mutant(tmp_path / "projected", "lab09_camera", """
        def project(P, points):
            K, R, t = cv2.decomposeProjectionMatrix(np.asarray(P, np.float64))[:3]
            C = t[:3, 0] / t[3, 0]
            X = np.asarray(points, np.float32).reshape(-1, 3)
            rvec = cv2.Rodrigues(R)[0]
            uv, _ = cv2.projectPoints(X, rvec, -R @ C, K / K[2, 2], None)
            uv = uv.reshape(-1, 2).astype(np.float64)
            return uv[0] if np.ndim(points) == 1 else uv
        """)
    checks = {c.name: c for e in grade(submission, ["lab09.ex3"]).exercises for c in e.checks}
    assert checks["project answers whole numbers given as integers as it answers them as floats"].score == 1


def test_the_code_reading_follows_names_read_from_an_input_and_wants_a_write():
    import ast

    from autograder.engine.conventions import _made_like

    def lines(source):
        function = ast.parse(source).body[0]
        return [text for _, text in _made_like([function], {a.arg for a in function.args.args})]

    assert lines("def f(pts1):\n    pts = np.asarray(pts1).reshape(-1, 2)\n"
                 "    out = np.zeros((len(pts), 3), dtype=pts.dtype)\n    out[0] = 1.5\n    return out") \
        == ["out = np.zeros((len(pts), 3), dtype=pts.dtype)"]
    assert lines("def f(points):\n    X = points.copy()\n    X /= X[:, 2:]\n    return X") == ["X = points.copy()"]
    # made like the input but never written into, or made as floats: nothing to name
    assert lines("def f(points):\n    X = np.asarray(points)\n    return X[:, :2] / X[:, 2:]") == []
    assert lines("def f(points):\n    out = np.zeros_like(points, dtype=float)\n    out[0] = 1.5\n    return out") == []
    assert lines("def f(points):\n    out = np.array(points, float)\n    out[0] = 1.5\n    return out") == []
    assert lines("def f(points):\n    out = np.copy(points)\n    out[0] = 1.5\n    return out") == ["out = np.copy(points)"]


SQUARE = "answers as many points as a point has coordinates as the same points among many"


def test_three_points_taken_for_one_point_fail_the_square_check_naming_the_length_test(tmp_path):
    # the blind sets' single point told by its length: a (3, 3) array is three points
    submission = mutant(tmp_path, "lab09_camera", """
        _reference = pinhole_project
        def pinhole_project(points, f):
            pts = np.asarray(points, dtype=np.float64)
            one_point = len(pts) == 3
            answer = _reference(pts.reshape(-1, 3), f)
            return answer[0] if one_point else answer
        """)
    failed = _failed(grade(submission, ["lab09.ex1"]), "lab09.ex1")
    assert list(failed) == [f"pinhole_project {SQUARE}"]
    message = failed[f"pinhole_project {SQUARE}"].message
    assert "with 3 points, an array of shape (3, 3) returned shape (2,)" in message
    assert "`len(pts) == 3` (line" in message and "np.ndim(points) == 1" in message


def test_two_points_read_as_columns_fail_the_square_check_and_right_recipes_pass(tmp_path):
    # (2, N) accepted by transposing when the first axis is 2: two 2D points are transposed too
    wrong = mutant(tmp_path / "wrong", "lab08_homographies", """
        _reference = transform_points
        def transform_points(H, pts):
            pts = np.asarray(pts, dtype=np.float64)
            if pts.shape[0] == 2:
                pts = pts.T
            return _reference(H, pts)
        """)
    failed = _failed(grade(wrong, ["lab08.ex1"]), "lab08.ex1")
    assert list(failed) == [f"transform_points {SQUARE}"]
    assert "`pts.shape[0] == 2` (line" in failed[f"transform_points {SQUARE}"].message
    # OpenCV's recipe (cv2.perspectiveTransform on (N, 1, 2)) and a single point told by its dimensions pass
    right = mutant(tmp_path / "right", "lab08_homographies", """
        def transform_points(H, pts):
            pts = np.asarray(pts, dtype=np.float64)
            if pts.ndim == 1:
                return transform_points(H, pts[None])[0]
            return cv2.perspectiveTransform(pts.reshape(-1, 1, 2), np.asarray(H, np.float64)).reshape(-1, 2)
        """)
    assert not any(SQUARE in name for name in _failed(grade(right, ["lab08.ex1"]), "lab08.ex1"))


def test_the_length_test_reading_sees_len_shape_and_size_of_an_input_only():
    import ast

    from autograder.engine.conventions import _length_tests

    def tests(source, k=3):
        function = ast.parse(source).body[0]
        return [text for _, text in _length_tests([function], {a.arg for a in function.args.args}, k)]

    assert tests("def f(points):\n    X = np.asarray(points, float)\n    if X.shape[0] == 3:\n        X = X[None]") \
        == ["X.shape[0] == 3"]
    assert tests("def f(points):\n    single = len(points) in (2, 3)") == ["len(points) in (2, 3)"]
    assert tests("def f(pts):\n    if np.shape(pts)[0] != 2:\n        pass", k=2) == ["np.shape(pts)[0] != 2"]
    # the number of dimensions, another length than k, or a name not read from an input: nothing
    assert tests("def f(points):\n    if np.ndim(points) == 1:\n        pass") == []
    assert tests("def f(points):\n    if len(points) == 4:\n        pass") == []
    assert tests("def f(points):\n    corners = [1, 2, 3]\n    if len(corners) == 3:\n        pass") == []


def test_answers_of_the_right_form_that_depend_on_the_other_points_are_told_that_rule(tmp_path):
    # lines scaled by the norm over every line: two points give two rows, but not the rows they give among
    # six -- the rule said is the one the answer breaks, not "2 points are 2 rows"
    submission = mutant(tmp_path, "lab11_two_view", """
        def epipolar_lines(F, pts1):
            pts = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
            lines = np.hstack([pts, np.ones((len(pts), 1))]) @ np.asarray(F, np.float64).T
            return lines / np.linalg.norm(lines[:, :2])
        """)
    failed = _failed(grade(submission, ["lab11.ex2"], include_hidden=False), "lab11.ex2")
    message = failed[f"epipolar_lines {SQUARE}"].message
    assert "a point's answer must not depend on the other points given with it" in message, message
    assert "rows of the answer" not in message, message


def test_answers_that_change_from_call_to_call_are_told_so_not_blamed_on_the_inputs_form(tmp_path):
    # a counter of the module's, grown at every call: each call answers otherwise, whatever its input's form
    submission = mutant(tmp_path, "lab10_camera2", """
        _CALLS = []
        _reference = weak_perspective_project
        def weak_perspective_project(points, f, z_avg=None):
            _CALLS.append(1)
            return _reference(points, f, z_avg) * (1.0 + 0.01 * len(_CALLS))
        """)
    failed = _failed(grade(submission, ["lab10.ex2"]), "lab10.ex2")
    told = [c for name, c in failed.items() if "integers" in name or "one-row" in name]
    assert told, list(failed)
    for check in told:
        assert "called twice with the same arguments" in check.message, check.message
        assert check.mistake == conventions.STATE_BETWEEN_CALLS or "_CALLS" in check.message
        assert "answered in integers" not in check.mistake
