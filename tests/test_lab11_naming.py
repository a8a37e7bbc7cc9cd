"""Lab 11 names what the student's code shows (issue 35): the code-reading signs of
autograder/labs/code_signs.py on source alone, and the legitimate variants next to the mistakes
they name keeping full marks with no name. The mistakes themselves are graded in tests/test_lab11.py
(the mistakes table: lines from the left and right borders only, cameras without K, x for y in a
DLT row, Vt[-1] of a batched SVD)."""

from __future__ import annotations

import textwrap

import pytest

from autograder.engine.hints import read_code
from autograder.engine.runner import grade
from autograder.labs import code_signs
from conftest import REFERENCE, check_results, mutant

MODULE = "lab11_two_view"


def found(predicate, source: str, function: str) -> str:
    code = read_code(textwrap.dedent(source))
    assert function in code.functions, "the test's source does not parse"
    return predicate.found(code.reachable([function]))


def function_source(head: str, body: str, tail: str) -> str:
    """``head`` (a ``def`` and its first lines, 4-space indented), ``body`` (lines at 4 spaces), ``tail``."""
    return head + textwrap.indent(body, "    ") + "\n" + tail


@pytest.mark.parametrize("body, sides_only", [
    ("y0 = -c / b\n        y1 = -(c + a * (w - 1)) / b", True),
    ("y0 = -line[2] / line[1]\n        y1 = -(line[2] + line[0] * (w - 1)) / line[1]", True),
    ("if abs(b) >= abs(a):\n            y0 = -c / b\n        else:\n            x0 = -c / a", False),
    ("p = (-c / a, 0.0) if abs(a) > abs(b) else (0.0, -c / b)", False),
    ("d = np.array([b, -a]) * 1e4\n        p0 = np.array([-a * c, -b * c])", False),   # a far segment, no division
])
def test_lines_from_the_side_borders_only_are_read(body, sides_only):
    source = function_source("def draw_epipolar_lines(image, lines):\n    h, w = image.shape[:2]\n"
                             "    for line in lines:\n        a, b, c = line\n",
                             textwrap.indent(body.replace("\n        ", "\n"), "    "), "    return image\n")
    assert bool(found(code_signs.LINES_FROM_SIDES_ONLY, source, "draw_epipolar_lines")) == sides_only




@pytest.mark.parametrize("cameras, without_k", [
    ("P1 = np.hstack([np.eye(3), np.zeros((3, 1))])\n        P2 = np.hstack([R, t])", True),
    ("P1 = np.eye(3, 4)\n        P2 = np.column_stack((R, t))", True),
    ("P1 = np.concatenate([np.eye(3), np.zeros((3, 1))], axis=1)\n        P2 = np.c_[R, t]", True),
    ("P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])\n        P2 = K @ np.hstack([R, t])", False),
    # a translation computed from R, without K: still built without K
    ("P1 = np.eye(3, 4)\n        P2 = np.hstack([R, -R @ C])", True),
    # K given to R's columns only, [K R | t] (blind set 08a lab11/08): not built without K
    ("P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])\n        P2 = np.hstack([K @ R, t])", False),
    ("P1 = np.eye(3, 4)\n        P2 = np.hstack([R, t])\n        P1, P2 = K @ P1, np.dot(K, P2)", False),
    # normalised coordinates: [R | t] is right for them
    ("P1 = np.eye(3, 4)\n        P2 = np.hstack([R, t])\n        pts1 = cv2.undistortPoints(pts1, K, None)", False),
    ("P1 = np.eye(3, 4)\n        P2 = np.hstack([R, t])\n        Kinv = np.linalg.inv(K)", False),
])
def test_cameras_built_without_k_are_read(cameras, without_k):
    source = function_source("def two_view_reconstruction(img1, img2, K):\n"
                             "    _, R, t, _ = cv2.recoverPose(E, pts1, pts2, K)\n",
                             cameras.replace("\n        ", "\n"), "    return triangulate(P1, P2, pts1, pts2)\n")
    assert bool(found(code_signs.CAMERA_WITHOUT_K, source, "two_view_reconstruction")) == without_k


def test_the_reference_pipeline_builds_its_cameras_with_k():
    source = (REFERENCE / f"{MODULE}.py").read_text()
    assert not found(code_signs.CAMERA_WITHOUT_K, source, "two_view_reconstruction")
    assert not found(code_signs.LINES_FROM_SIDES_ONLY, source, "draw_epipolar_lines")


# ------------------------------------------------------------------ legitimate variants: full marks, no name
VARIANTS = {
    "the pipeline triangulating normalised coordinates with [I | 0] and [R | t]": ("lab11.ex6", """
        _reconstruction = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, _ = _reconstruction(img1, img2, K)
            K = np.asarray(K, np.float64)
            E = K.T @ F @ K
            _, R, t, _ = cv2.recoverPose(E, pts1, pts2, K)
            n1 = cv2.undistortPoints(pts1.reshape(-1, 1, 2), K, None).reshape(-1, 2)
            n2 = cv2.undistortPoints(pts2.reshape(-1, 1, 2), K, None).reshape(-1, 2)
            P1 = np.hstack([np.eye(3), np.zeros((3, 1))])
            P2 = np.hstack([R, t])
            points3d = triangulate(P1, P2, n1, n2)
            return F, pts1, pts2, points3d
        """),
    "lines drawn between two far points along the line, cut by cv2.clipLine": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = np.array(image, dtype=np.uint8, copy=True)
            height, width = canvas.shape[:2]
            for i, (a, b, c) in enumerate(np.asarray(lines, np.float64).reshape(-1, 3)):
                norm = np.hypot(a, b)
                foot = np.array([-a * c, -b * c]) / norm ** 2
                along = np.array([b, -a]) / norm * 4 * (width + height)
                p, q = np.round(foot - along).astype(int), np.round(foot + along).astype(int)
                inside, p, q = cv2.clipLine((0, 0, width, height), tuple(map(int, p)), tuple(map(int, q)))
                if inside:
                    cv2.line(canvas, p, q, _PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 255, 1)
            return canvas
        """),
}


@pytest.mark.parametrize("case", sorted(VARIANTS))
def test_legitimate_variants_keep_full_marks_and_no_name(tmp_path, case):
    exercise, source = VARIANTS[case]
    result = grade(mutant(tmp_path, MODULE, source), [exercise], pictures="none")
    for check in check_results(result, exercise):
        assert check.passed and not check.mistake, f"{check.name}: {check.message}"


def test_points_left_at_zero_are_not_told_as_undivided(tmp_path):
    """A loop one point short leaves the last row of np.zeros: (0, 0, 0) is parallel to every point and
    0 times it, but no w was left undivided -- the points never computed are told as such."""
    folder = mutant(tmp_path, "lab11_two_view", """
        _triangulate_all = triangulate
        def triangulate(P1, P2, pts1, pts2):
            pts1 = np.asarray(pts1, float).reshape(-1, 2)
            pts2 = np.asarray(pts2, float).reshape(-1, 2)
            X = np.zeros((len(pts1), 3))
            for i in range(len(pts1) - 1):
                X[i] = _triangulate_all(P1, P2, pts1[i:i + 1], pts2[i:i + 1])
            return X
        """)
    result = grade(folder, ["lab11.ex1"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab11.ex1") if c.score < c.max_score]
    assert failed and not any("not divided by w" in c.message for c in failed)
    assert any("(0, 0, 0), as if never computed" in c.message for c in failed), [c.message for c in failed]


def test_of_mistakes_giving_the_same_f_transposed_the_one_seen_in_the_code_is_said_alone(tmp_path):
    # order='F' gives F^T, as do kron(x1, x2) rows and pts1/pts2 swapped: the code shows which one it is
    from conftest import edited_reference

    folder = edited_reference(tmp_path, "lab11_two_view", ("return np.linalg.svd(A)[2][-1].reshape(3, 3)",
                                                           "return np.linalg.svd(A)[2][-1].reshape(3, 3, order='F')"))
    failed = [c for c in check_results(grade(str(folder), ["lab11.ex4"]), "lab11.ex4") if c.score < c.max_score]
    named = [c for c in failed if "reshaped column by column" in c.message]
    assert named and all("kron(x1, x2)" not in c.message and "the same answer here" not in c.message for c in named)


ESSENTIAL_TRANSPOSED = """
    def essential_8point(pts1, pts2, K1, K2):
        x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
        x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
        A = ({rows}[:, :, None] * {columns}[:, None, :]).reshape(len(x1), 9)
        E = np.linalg.svd(A)[2][-1].reshape(3, 3{order})
        U, _, Vt = np.linalg.svd(E)
        return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
    """


@pytest.mark.parametrize("rows, columns, order, column_order_said", [
    ("x2", "x1", ", order='F'", True),    # the null vector reshaped column by column: said alone
    ("x1", "x2", "", False),              # rows kron(x1, x2), reshaped row by row: never told it reshapes by columns
])
def test_e_transposed_is_a_column_major_reshape_only_where_the_code_shows_one(tmp_path, rows, columns, order,
                                                                               column_order_said):
    folder = mutant(tmp_path, MODULE, ESSENTIAL_TRANSPOSED.format(rows=rows, columns=columns, order=order))
    result = grade(folder, ["lab11.ex3"], pictures="none", include_hidden=False)
    exact = next(c for c in check_results(result, "lab11.ex3") if c.name.startswith("essential_8point recovers E"))
    assert exact.score < exact.max_score
    assert ("reshaped column by column" in exact.message) == column_order_said, exact.message
    if column_order_said:
        assert "swapped" not in exact.message and "kron(x1, x2)" not in exact.message, exact.message


def test_a_repeated_entry_is_read_in_a_row_of_a_not_in_a_matrix_written_flat():
    """The sheet's misprinted row (y2 twice among products of the two points) is read; a 3 x 3 matrix written as
    9 entries (diag(s, s, 0), a skew matrix) repeats entries and is no row of A."""
    from autograder.labs.lab11 import repeated_column

    def read(row: str) -> str:
        return repeated_column(read_code(f"def f(x1, y1, x2, y2, s, t):\n    return np.array({row})\n")
                               .reachable(["f"]))

    assert "`y2` twice" in read("[x1 * x2, x1 * y2, x1, y1 * x2, y1, x2, y2, y2, 1]")
    assert read("[x2 * x1, x2 * y1, x2, y2 * x1, y2 * y1, y2, x1, y1, 1]") == ""
    assert read("[s, 0, 0, 0, s, 0, 0, 0, 0]") == ""
    assert read("[0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0]") == ""


def test_an_svd_per_pair_in_a_loop_is_no_batched_svd():
    """Vt[-1] of each pair's own 4 x 4 system, taken in a loop, is that system's solution: a result short of rows
    (4 for 5 points, a row lost elsewhere) is not told as the last row of a batched SVD."""
    per_pair = read_code(textwrap.dedent("""
        def triangulate(P1, P2, pts1, pts2):
            out = []
            for (x, y), (u, v) in zip(pts1[1:], pts2[1:]):
                A = np.array([x * P1[2] - P1[0], y * P1[2] - P1[1], u * P2[2] - P2[0], v * P2[2] - P2[1]])
                Vt = np.linalg.svd(A)[2]
                out.append(Vt[-1][:3] / Vt[-1][3])
            return np.array(out)
        """))
    batched = read_code(textwrap.dedent("""
        def triangulate(A):
            Vt = np.linalg.svd(A)[2]
            return Vt[-1][:, :3] / Vt[-1][:, 3:]
        """))
    assert code_signs._svd_in_a_loop(per_pair.reachable(["triangulate"]))
    assert not code_signs._svd_in_a_loop(batched.reachable(["triangulate"]))


def test_lines_drawn_black_on_a_grey_image_kept_grey_are_not_told_to_keep_it_grey(tmp_path):
    """A palette colour on a grey image draws its first value (07d lab11/03): told, with a grey level to draw; the
    image the code already keeps grey is not asked to be kept grey (a hint the code contradicts)."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, "lab11_two_view", ("if canvas.ndim == 3 else 255", ""))
    messages = [c.message + c.hint for c in check_results(grade(str(folder), ["lab11.ex2"]), "lab11.ex2")
                if c.score < c.max_score]
    black = [m for m in messages if "draws them in black" in m or "draws it in black" in m]
    assert black and not any("keep the image grey" in m for m in black), messages
