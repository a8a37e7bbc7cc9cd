"""Reading the submitted code where the outputs cannot tell (issue 26, autograder/loading/reading.py).

The reading finds, without running anything, the places in a function that cause a known
mistake; the runner uses a finding only to name the cause of a failure a check measured
in that function (or a helper it calls), never to take points.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from autograder.loading.reading import MAX_SOURCE_BYTES, NOTHING, findings_for, read_file, read_source
from autograder.engine.registry import discover
from conftest import check_results, graded_case, named_mistakes

ROOT = Path(__file__).resolve().parents[1]
MODULE8 = "lab08_homographies"


def mistakes_in(source: str, api=frozenset()) -> dict[str, set[str]]:
    reading = read_source(textwrap.dedent(source), frozenset(api))
    return {name: {f.mistake for f in found} for name, found in reading.findings.items() if found}


def one(source: str, api=frozenset()) -> set[str]:
    found = mistakes_in(source, api)
    return set().union(*found.values()) if found else set()


# ------------------------------------------------------------------ graded
DLT_BY_EIG = """
    def homography_dlt(src, dst):
        A = []
        for (x, y), (u, v) in zip(np.asarray(src, float), np.asarray(dst, float)):
            A.append([-x, -y, -1, 0, 0, 0, u * x, u * y, u])
            A.append([0, 0, 0, -x, -y, -1, v * x, v * y, v])
        A = np.array(A)
        w, V = np.linalg.eig(A.T @ A)
        H = V[:, -1].reshape(3, 3)
        return H / H[2, 2]
    """


@pytest.mark.xdist_group("lab08")
def test_the_eig_dlt_is_named_by_the_reading():
    result = graded_case(MODULE8, "lab08.ex2", DLT_BY_EIG)
    named = named_mistakes(result, "lab08.ex2")
    assert named, "the eig DLT must be named"
    for label, message in named:
        assert label == "np.linalg.eig's eigenvalues are not sorted", (label, message)
        assert "calls np.linalg.eig, whose eigenvalues are not sorted" in message
        assert "line" in message   # it says where


@pytest.mark.xdist_group("lab08")
@pytest.mark.parametrize("solver", [
    "w, V = np.linalg.eigh(A.T @ A); h = V[:, 0]",                              # eigh sorts: the first
    "w, V = np.linalg.eig(A.T @ A); h = np.real(V[:, np.argmin(np.real(w))])",  # eig, chosen by w
])
def test_a_correct_eigen_solver_is_never_mentioned(solver):
    result = graded_case(MODULE8, "lab08.ex2", f"""
        def homography_dlt(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            T1, T2 = _normalisation(src), _normalisation(dst)
            A = _dlt_rows(src @ T1[:2, :2].T + T1[:2, 2], dst @ T2[:2, :2].T + T2[:2, 2])
            {solver}
            H = np.linalg.inv(T2) @ h.reshape(3, 3) @ T1
            return H / H[2, 2]
        """)
    checks = check_results(result, "lab08.ex2")
    assert all(c.passed or c.max_score == 0 for c in checks), [c.message for c in checks if not c.passed]
    assert not any("eig" in c.message for c in checks)


@pytest.mark.xdist_group("lab08")
def test_eigh_with_another_mistake_is_not_named_as_eig():
    """A failing DLT that uses eigh: the failure is measured, the reading has nothing to say."""
    result = graded_case(MODULE8, "lab08.ex2", """
        def homography_dlt(src, dst):
            A = []
            for (x, y), (u, v) in zip(np.asarray(src, float), np.asarray(dst, float)):
                A.append([-x, -y, -1, 0, 0, 0, u * x, u * y, u])
                A.append([0, 0, 0, -x, -y, -1, v * x, v * y, -v])     # a sign slip
            w, V = np.linalg.eigh(np.array(A).T @ np.array(A))
            H = V[:, 0].reshape(3, 3)
            return H / H[2, 2]
        """)
    checks = check_results(result, "lab08.ex2")
    assert any(not c.passed for c in checks)
    assert not any("eig" in c.message.lower() and "eigh" not in c.message for c in checks if not c.passed)
    assert not any("np.linalg.eig" in c.message for c in checks)


@pytest.mark.xdist_group("lab08")
def test_a_finding_takes_no_points():
    """Code the reading flags, in a function that is right: full marks, nothing said."""
    result = graded_case(MODULE8, "lab08.ex1", """
        _right = transform_points
        def transform_points(H, pts):
            half = len(pts) // 2              # floor division the values never show
            w, V = np.linalg.eig(np.eye(3))   # an eigen-solver whose vectors choose nothing
            return _right(H, pts)
        """)
    checks = check_results(result, "lab08.ex1")
    assert all(c.passed or c.max_score == 0 for c in checks), [c.message for c in checks if not c.passed]
    assert not any("your code" in c.message.lower() for c in checks)


@pytest.mark.xdist_group("lab09")
def test_floor_division_is_named_only_when_the_values_show_whole_numbers():
    named = graded_case("lab09_camera", "lab09.ex1", """
        def pinhole_project(points, f):
            X = np.atleast_2d(np.asarray(points, dtype=float))
            xy = f * X[:, :2] // X[:, 2:3]
            return xy[0] if np.ndim(points) == 1 else xy
        """)
    assert any("floor division" in m for _, m in named_mistakes(named, "lab09.ex1"))
    # A // that only halves an index, in a function wrong for another reason: not named.
    other = graded_case("lab09_camera", "lab09.ex1", """
        def pinhole_project(points, f):
            X = np.atleast_2d(np.asarray(points, dtype=float))
            middle = len(X) // 2
            xy = -f * X[:, :2] / X[:, 2:3]
            return xy[0] if np.ndim(points) == 1 else xy
        """)
    failed = [c.message for c in check_results(other, "lab09.ex1") if not c.passed]
    assert failed and not any("floor division" in m for m in failed)


@pytest.mark.xdist_group("lab12")
def test_an_integer_array_is_not_blamed_for_values_that_are_whole_anyway():
    """Gray-code patterns built in a dtype=int array hold the right 0/255 values as int64: the
    dtype is wrong, no fraction was cut off, so the truncation reading is not told."""
    named = graded_case("lab12_stereo", "lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            patterns = np.zeros((n_bits, width), dtype=int)
            columns = np.arange(width)
            gray = columns ^ (columns >> 1)
            for bit in range(n_bits):
                patterns[bit] = ((gray >> (n_bits - 1 - bit)) & 1) * 255
            return patterns
        """)
    failed = [c.message for c in check_results(named, "lab12.ex6") if not c.passed]
    assert failed and not any("cut off" in m for m in failed), failed
    assert not any("0/1 values" in m for m in failed), failed


@pytest.mark.xdist_group("lab12")
def test_a_uint8_ssd_loses_points_and_is_named():
    result = graded_case("lab12_stereo", "lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            h, w = left.shape
            costs = np.full((max_disparity + 1, h, w), np.inf)
            for d in range(max_disparity + 1):
                shifted = np.zeros_like(right)
                shifted[:, d:] = right[:, :w - d]
                costs[d] = cv2.boxFilter(((left - shifted) ** 2).astype(np.float64), -1, (block_size, block_size))
                costs[d, :, :d] = np.inf
            return np.argmin(costs, axis=0).astype(np.float64)
        """)
    [exercise] = [e for e in result.exercises if e.id == "lab12.ex4"]
    assert exercise.score < exercise.max_score
    assert any(label == "uint8 arithmetic wraps around" for label, _ in named_mistakes(result, "lab12.ex4"))


# ------------------------------------------------------------------ the findings, one by one
FINDINGS = {
    "np.linalg.eig's eigenvalues are not sorted": ("""
        def f(A):
            w, V = np.linalg.eig(A.T @ A)
            return V[:, -1]
        """, """
        def f(A):
            w, V = np.linalg.eig(A.T @ A)
            return V[:, np.argmin(w)]
        """),
    "an integer array: the values written into it are truncated": ("""
        def f(tx, ty):
            M = np.eye(3, dtype=int)
            M[0, 2] = tx
            return M
        """, """
        def f(image, tx):
            canvas = np.zeros((10, 10, 3), dtype=np.uint8)
            canvas[:5] = image
            index = np.zeros(4, dtype=int)
            index[0] = np.argmin(tx)
            return canvas, index
        """),
    "// floors the results to whole numbers": ("""
        def f(X, f):
            return f * X[:, :2] // X[:, 2:3]
        """, """
        def f(X):
            return X[: 10 // 2]
        """),
    "uint8 arithmetic wraps around": ("""
        def block_matching(left, right):
            shifted = np.zeros_like(right)
            shifted[:, 3:] = right[:, :-3]
            return (left - shifted) ** 2
        """, """
        def block_matching(left, right):
            left, right = left.astype(np.float32), right.astype(np.float32)
            return (left - right) ** 2
        """),
    "the homogeneous coordinate is 0 instead of 1": ("""
        def f(H, pts):
            p = np.hstack([pts, np.zeros((len(pts), 1))])
            return p @ H.T
        """, """
        def f(K, R, pts):
            P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
            p = np.hstack([pts, np.ones((len(pts), 1))])
            return p @ P1.T
        """),
    "queryIdx and trainIdx are exchanged": ("""
        def f(g1, g2):
            kp1, des1 = sift.detectAndCompute(g1, None)
            kp2, des2 = sift.detectAndCompute(g2, None)
            return [kp1[m.trainIdx].pt for m in matcher.match(des1, des2)]
        """, """
        def f(g1, g2):
            kp1, des1 = sift.detectAndCompute(g1, None)
            kp2, des2 = sift.detectAndCompute(g2, None)
            return [(kp1[m.queryIdx].pt, kp2[m.trainIdx].pt) for m in matcher.match(des1, des2)]
        """),
    "OpenCV's 0/1 mask is used as indices": ("""
        def f(p1, p2):
            F, mask = cv2.findFundamentalMat(p1, p2, cv2.FM_RANSAC)
            return p1[mask.ravel()]
        """, """
        def f(p1, p2):
            F, mask = cv2.findFundamentalMat(p1, p2, cv2.FM_RANSAC)
            inliers = mask.ravel().astype(bool)
            return p1[inliers], p2[mask.ravel() == 1]
        """),
    "cv2.recoverPose without the camera matrix": ("""
        def f(E, pts1, pts2, K):
            _, R, t, mask = cv2.recoverPose(E, pts1, pts2)
            return R, t
        """, """
        def f(E, pts1, pts2, K):
            _, R, t, mask = cv2.recoverPose(E, pts1, pts2, cameraMatrix=K)
            n1 = cv2.undistortPoints(pts1.reshape(-1, 1, 2), K, None)
            _, R2, t2, _ = cv2.recoverPose(E, n1, n1)   # normalised first: no camera needed
            return R, t
        """),
    "np.where's tuple counted as the entries found": ("""
        def f(errors, t):
            inliers = np.where(errors < t)
            return len(inliers) >= 4, len(np.nonzero(errors)), inliers
        """, """
        def f(errors, t):
            inliers = np.where(errors < t)[0]
            rows, cols = np.nonzero(errors)
            chosen = np.where(errors < t, errors, 0)
            return len(inliers), len(rows), len(chosen), len(np.argwhere(errors < t))
        """),
    "one row repeated: the list's rows are the same list": ("""
        def f(sx, sy):
            M = [[0.0] * 3] * 3
            M[0][0], M[1][1], M[2][2] = sx, sy, 1.0
            return np.array(M)
        """, """
        def f(sx, sy):
            M = [[0.0] * 3 for _ in range(3)]
            M[0][0], M[1][1], M[2][2] = sx, sy, 1.0
            rows = [[1, 2]] * 3
            return np.array(M), rows
        """),
    "** -1 taken for a matrix's inverse": ("""
        def f(T1, T2, M):
            return T2 ** -1 @ M @ T1
        """, """
        def f(T1, T2, M, w):
            return np.linalg.inv(T2) @ M @ T1, w ** -1
        """),
    "the null vector picked by the argmin of the singular values": ("""
        def f(A, E):
            _, S, Vt = np.linalg.svd(A)
            U, _, Vt = np.linalg.svd(E)
            return Vt[np.argmin(S)], U
        """, """
        def f(A):
            U, S, Vt = np.linalg.svd(A)
            return Vt[-1], U[:, np.argmin(S)]
        """),
    "the lens model centred on the points' centroid": ("""
        def f(pts, k1):
            cx, cy = pts.mean(axis=0)
            x = pts[:, 0] - cx
            y = pts[:, 1] - cy
            r2 = x ** 2 + y ** 2
            return 1 + k1 * r2
        """, """
        def f(pts, k1, K):
            cx, cy = K[0, 2], K[1, 2]
            x = (pts[:, 0] - cx) / K[0, 0]
            y = (pts[:, 1] - cy) / K[1, 1]
            r2 = x ** 2 + y ** 2
            return 1 + k1 * r2, pts.mean(axis=0)
        """),
    "an iterator read twice: the second reading finds it empty": ("""
        def f(pts1, pts2):
            pairs = zip(pts1, pts2)
            colours = [c for c in pairs]
            return [(p, c) for p, c in zip(pairs, colours)]
        """, """
        def f(pts1, pts2):
            pairs = list(zip(pts1, pts2))
            colours = [c for c in pairs]
            once = zip(pts1, pts2)
            header = iter(pts1)
            for row in header:
                break
            return [(p, c) for p, c in zip(pairs, colours)], [a for a in once], [r for r in header]
        """),
    "the distortion coefficients are read in the wrong order": ("""
        def f(points, dist):
            k1, k2, k3, p1, p2 = dist
            return points
        """, """
        def f(points, dist):
            k1, k2, p1, p2, k3 = np.asarray(dist).ravel()[:5]
            return points
        """),
}


@pytest.mark.parametrize("mistake", sorted(FINDINGS))
def test_each_finding_is_found_and_the_right_code_is_not_flagged(mistake):
    wrong, right = FINDINGS[mistake]
    api = {"block_matching"}
    assert mistake in one(wrong, api), mistakes_in(wrong, api)
    assert mistake not in one(right, api), mistakes_in(right, api)


# The points of each descriptor set, however a student pairs them, and indices kept in names.
QUERY_TRAIN_FORMS = {
    "siblings of an unpacked tuple, indices in names": ("""
        def f(a, b):
            (pts_a, desc_a), (pts_b, desc_b) = features(a), features(b)
            good = [m for m, n in matcher.knnMatch(desc_a, desc_b, k=2) if m.distance < 0.7 * n.distance]
            q = np.array([m.queryIdx for m in good])
            t = np.array([m.trainIdx for m in good])
            return pts_a[{first}], pts_b[{second}]
        """, ("t", "q"), ("q", "t")),
    "names ending alike": ("""
        def f(g1, g2):
            keypoints1 = detect(g1)
            keypoints2 = detect(g2)
            descriptors1, descriptors2 = describe(g1), describe(g2)
            return [(keypoints1[m.{first}].pt, keypoints2[m.{second}].pt)
                    for m in matcher.match(descriptors1, descriptors2)]
        """, ("trainIdx", "queryIdx"), ("queryIdx", "trainIdx")),
}


@pytest.mark.parametrize("form", sorted(QUERY_TRAIN_FORMS))
def test_query_and_train_exchanged_are_read_in_other_forms(form):
    source, wrong, right = QUERY_TRAIN_FORMS[form]
    mistake = "queryIdx and trainIdx are exchanged"
    assert mistake in one(source.format(first=wrong[0], second=wrong[1]))
    assert mistake not in one(source.format(first=right[0], second=right[1]))


def test_image_parameters_are_uint8_only_in_the_api_functions():
    helper = """
        def _ssd(left, right):          # a helper: its parameters may hold floats
            return (left - right) ** 2
        """
    assert "uint8 arithmetic wraps around" not in one(helper, api={"block_matching"})


def test_the_reference_solutions_hold_no_finding_a_failure_could_use():
    for key, lab in discover().items():
        api = frozenset(f for e in lab.exercises.values() for f in e.signatures)
        reading = read_file(ROOT / "reference_solutions" / f"{lab.module}.py", api)
        unconditional = [(name, f.mistake) for name, found in reading.findings.items() for f in found if not f.needs]
        assert unconditional == [], (key, unconditional)


def test_findings_reach_the_helpers_a_function_calls():
    reading = read_source(textwrap.dedent("""
        def _solve(A):
            w, V = np.linalg.eig(A.T @ A)
            return V[:, -1]
        def homography_dlt(src, dst):
            return _solve(build(src, dst)).reshape(3, 3)
        """))
    assert [f.function for f in findings_for(reading, {"homography_dlt"}, False)] == ["_solve"]
    assert findings_for(reading, {"transform_points"}, False) == []


# ------------------------------------------------------------------ never crashes
@settings(max_examples=40, deadline=None)
@given(st.text(max_size=400))
def test_any_text_is_read_without_raising(text):
    assert read_source(text) is not None


@pytest.mark.parametrize("text", [
    "x = " + "(" * 3000 + "1" + ")" * 3000,                    # nested beyond the parser
    "x = " + "-" * 100_000 + "1",                               # a long unary chain
    "def f(a):\n    return " + " + ".join(["a"] * 20_000),     # a huge expression
    "\x00\xff def",                                             # not Python
    "def f(" + ", ".join(f"a{i}" for i in range(3000)) + "):\n    return a0 // a1",
])
def test_hostile_sources_are_read_or_left_alone(text):
    reading = read_source(text)
    assert reading is NOTHING or isinstance(reading.findings, dict)


def test_too_large_a_source_is_not_read(tmp_path):
    path = tmp_path / "big.py"
    path.write_text("x = 1\n" * (MAX_SOURCE_BYTES // 6 + 10) + "def f(A):\n    return np.linalg.eig(A)[1][:, -1]\n")
    too_large = read_file(path)
    assert too_large.findings == {} and "not read" in too_large.note and "characters" in too_large.note
    path.write_bytes(b"\xff\xfe\x00garbage")
    assert read_file(path).findings == {}
    assert read_file(tmp_path / "missing.py") is NOTHING


def test_in_a_notebook_the_finding_points_at_the_cell(tmp_path):
    """The reading's line is the converted module's: the message names the notebook's cell."""
    import nbformat
    from nbformat.v4 import new_code_cell, new_notebook

    from autograder.engine.runner import grade

    reference = (ROOT / "reference_solutions" / f"{MODULE8}.py").read_text()
    folder = tmp_path / "submission"
    folder.mkdir()
    nbformat.write(new_notebook(cells=[new_code_cell(reference), new_code_cell(textwrap.dedent(DLT_BY_EIG))]),
                   folder / f"{MODULE8}.ipynb")
    result = grade(folder, ["lab08.ex2"], pictures="none")
    named = [m for _, m in named_mistakes(result, "lab08.ex2")]
    assert named and all(f"{MODULE8}.ipynb, cell 2, line" in m for m in named), named
    assert not any(f"{MODULE8}.py" in m for m in named)


@pytest.mark.xdist_group("lab12")
def test_a_float_binary_image_is_not_blamed_on_a_floor_division_elsewhere():
    """Structured-light frames allocated as float64 (np.zeros without a dtype) hold 0.0 and 255.0: the
    dtype is wrong, no fraction was cut off, so gray_code_patterns' // (floor by the API) is not told."""
    named = graded_case("lab12_stereo", "lab12.ex6", """
        def simulate_structured_light(depth, f, baseline, n_bits):
            depth = np.asarray(depth, dtype=np.float64)
            h, w = depth.shape
            patterns = gray_code_patterns(w, n_bits)
            valid = np.isfinite(depth) & (depth > 0)
            cols = np.floor(np.arange(w)[None, :] - f * baseline / np.where(valid, depth, 1.0) + 0.5).astype(int)
            lit = valid & (cols >= 0) & (cols < w)
            frames = []
            for i in range(int(n_bits)):
                frame = np.zeros((h, w))
                frame[lit] = patterns[i][cols[lit]]
                frames.append(frame)
            return np.stack(frames)
        """)
    failed = [c.message for c in check_results(named, "lab12.ex6") if not c.passed]
    assert failed and any("float64" in m for m in failed), failed
    assert not any("floor division" in m or "//" in m for m in failed), failed


# ------------------------------------------------------------------ blind set 2026-12-01b's classes
VIEW_OVERWRITTEN = """
    def distort_points(points, dist):
        pts = np.asarray(points, float)
        x, y = pts[:, 0], pts[:, 1]
        r2 = x * x + y * y
        pts[:, 0] = x * (1 + dist[0] * r2) + 2 * dist[2] * x * y
        pts[:, 1] = y * (1 + dist[0] * r2) + 2 * dist[3] * x * y
        return pts
    """


def test_a_view_read_after_its_array_was_written_is_found():
    found = read_source(textwrap.dedent(VIEW_OVERWRITTEN)).findings["distort_points"]
    assert [f.mistake for f in found] == ["a view of an array read after the array was written"]
    assert "reads `x` (line 7), a view of `pts[:, 0]` (line 4) that line 6 has written over" in found[0].sentence


@pytest.mark.parametrize("source", [
    VIEW_OVERWRITTEN.replace("x, y = pts[:, 0], pts[:, 1]", "x, y = pts[:, 0].copy(), pts[:, 1].copy()"),
    VIEW_OVERWRITTEN.replace("x, y = pts[:, 0], pts[:, 1]", "x, y = pts[[0], 0], pts[:, 1]"),   # (a copy)
    # (the new values written last: nothing reads x after)
    VIEW_OVERWRITTEN.replace("2 * dist[3] * x * y", "2 * dist[3]").replace("pts[:, 1] = y *", "pts[:, 1] = y *"),
])
def test_a_copy_or_nothing_read_after_the_write_is_not_found(source):
    assert "a view of an array read after the array was written" not in one(source)


def test_a_generator_seeded_at_every_turn_is_found_and_one_made_before_the_loop_is_not():
    loop = """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            out = []
            for i in range(n_rays):
                rng = np.random.default_rng(seed)
                out.append(rng.random(2))
            return out
        """
    assert one(loop) == {"the random generator is seeded again at every turn of a loop"}
    assert not one(loop.replace("            for i in range(n_rays):\n                rng = np.random.default_rng(seed)",
                                "            rng = np.random.default_rng(seed)\n            for i in range(n_rays):"))
    assert not one(loop.replace("default_rng(seed)", "default_rng(i)"))   # (a seed of each turn's own)


def test_a_mean_of_points_already_centred_is_found():
    source = """
        def affine_from_points(src, dst):
            src = np.asarray(src, float)
            src = src - src.mean(axis=0)
            L = np.linalg.lstsq(src, dst - dst.mean(axis=0), rcond=None)[0].T
            t = dst.mean(axis=0) - L @ src.mean(axis=0)
            return np.column_stack([L, t])
        """
    assert one(source) == {"a mean taken of an array already centred"}
    kept = source.replace("src = src - src.mean(axis=0)", "c = src.mean(axis=0); src = src - c") \
        .replace("L @ src.mean(axis=0)", "L @ c")
    assert not one(kept)


@pytest.mark.parametrize("line, named", [
    ("X = cv2.triangulatePoints(P1, P2, x1.T, x2.T)[:3].T", True),
    ("Xh = cv2.triangulatePoints(P1, P2, x1.T, x2.T); X = Xh[:3].T", True),
    ("Xh = cv2.triangulatePoints(P1, P2, x1.T, x2.T); X = (Xh[:3] / Xh[3]).T", False),
    ("X = cv2.convertPointsFromHomogeneous(cv2.triangulatePoints(P1, P2, x1.T, x2.T).T)[:, 0]", False),
])
def test_triangulated_points_kept_without_w_are_found(line, named):
    source = f"""
        def triangulate(P1, P2, x1, x2):
            {line}
            return X
        """
    assert ("the homogeneous result of cv2.triangulatePoints is not divided by w" in one(source)) == named


def test_numpy_calls_filling_more_than_one_entry_are_found():
    assert one("""
        def scaling_matrix(sx, sy):
            M = np.eye(3)
            np.fill_diagonal(M, [sx, sy])
            return M
        """) == {"np.fill_diagonal repeats a list shorter than the diagonal"}
    assert not one("""
        def scaling_matrix(sx, sy):
            M = np.eye(3)
            np.fill_diagonal(M, [sx, sy, 1])
            return M
        """)
    assert one("""
        def shear_matrix(s):
            return np.eye(3) + s * np.eye(3, k=1)
        """) == {"np.eye(n, k) fills its whole off-diagonal"}


def test_the_references_hold_none_of_these_findings():
    new = {"a view of an array read after the array was written", "the random generator is seeded again at every "
           "turn of a loop", "a mean taken of an array already centred",
           "the homogeneous result of cv2.triangulatePoints is not divided by w",
           "np.fill_diagonal repeats a list shorter than the diagonal", "np.eye(n, k) fills its whole off-diagonal",
           "the last turn's value is used after the loop, not the best one kept",
           "an alias of an array is changed in place", "a row of the eigenvector matrix taken as an eigenvector",
           "a sine or cosine from the other by a square root: its sign is lost",
           "a dimension tested after the array was made two-dimensional", "the RANSAC mask's outliers kept",
           "a root written as a power of 1/n (** binds tighter than /)", "a grid's rows taken for its x",
           "the result rounded to a few decimals", "a value kept in a loop is the array the loop rewrites",
           "one array given two names by a chained assignment", "a lambda made in a loop reads the loop's variable when called",
           "rows of np.empty left unwritten where a loop continues", "infinity written into an array before it is filtered",
           "every view given to the calibration as one view", "a whole row's norm where the block's row's belongs"}
    for path in sorted((ROOT / "reference_solutions").glob("lab*.py")):
        assert not one(path.read_text()) & new, path.name


def test_an_opencv_constant_given_another_parameters_place_is_named():
    assert one("""
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in pts:
                cv2.circle(out, (int(x), int(y)), radius, color, cv2.LINE_AA)
            return out
        """) == {"cv2.LINE_AA is passed as cv2.circle's thickness"}
    assert one("""
        def shrink(image):
            return cv2.resize(image, (10, 10), cv2.INTER_NEAREST)
        """) == {"cv2.INTER_NEAREST is passed as cv2.resize's dst"}
    assert one("""
        def smooth(image):
            return cv2.GaussianBlur(image, (5, 5), cv2.BORDER_DEFAULT)
        """) == {"cv2.BORDER_DEFAULT is passed as cv2.GaussianBlur's sigmaX"}
    # each in its place, by name, after a starred argument (places unknown), or in another signature's place
    for right in ("cv2.circle(out, c, 3, color, -1, cv2.LINE_AA)", "cv2.circle(out, c, 3, color, lineType=cv2.LINE_AA)",
                  "cv2.line(out, *ends, color, 1, cv2.LINE_AA)", "cv2.findHomography(a, b, cv2.RANSAC, 5.0)",
                  "cv2.findEssentialMat(a, b, K, cv2.RANSAC, 0.999, 1.0)", "cv2.remap(img, mx, my, cv2.INTER_LINEAR)",
                  "cv2.warpAffine(img, M, size, flags=cv2.INTER_LINEAR)", "cv2.normalize(img, None, 0, 255, cv2.NORM_MINMAX)",
                  "cv2.circle(out, c, 3, color, cv2.FILLED)", "cv2.BFMatcher(cv2.NORM_HAMMING, True)"):
        assert not one(f"def f(out, c, color, a, b, K, img, mx, my, M, size, ends):\n    return {right}\n"), right


def test_a_name_a_later_loop_assigns_before_reading_it_is_not_the_last_turns_value():
    """Course code normalising two point sets with two loops over one name (third-party audit of 2026-12-07):
    the second loop assigns `norm` before it reads it, so no read there is of the first loop's last turn."""
    two_loops = """
        def normalise(x1, x2):
            max1 = 0
            for p in x1:
                norm = np.linalg.norm(p)
                if norm > max1:
                    max1 = norm
            max2 = 0
            for p in x2:
                {second}
                if norm > max2:
                    max2 = norm
            return max1, max2
        """
    assert not one(two_loops.format(second="norm = np.linalg.norm(p)"))
    # (a later loop that reads it before assigning it does read the first loop's last turn)
    assert one(two_loops.format(second="scale = norm; norm = np.linalg.norm(p)")) == {
        "the last turn's value is used after the loop, not the best one kept"}


def test_the_last_turns_value_read_after_a_loop_that_kept_the_best_is_named():
    ransac = """
        def homography_ransac(src, dst, threshold=3.0, n_iters=500, seed=None):
            best_count, best_inliers = -1, None
            for _ in range(n_iters):
                H = fit(src, dst)
                inliers = errors(H, src, dst) < threshold
                if inliers.sum() > best_count:
                    best_count, best_inliers = inliers.sum(), inliers
            return fit(src[{kept}], dst[{kept}]), {kept}
        """
    assert one(ransac.format(kept="inliers")) == {"the last turn's value is used after the loop, not the best one kept"}
    assert not one(ransac.format(kept="best_inliers"))
    # assigned again after the loop, before it is read; a name the loop never assigns
    assert not one("""
        def f(xs):
            best = None
            for x in xs:
                y = x * 2
                if y > 0:
                    best = y
            y = best
            return y
        """)
    assert not one("""
        def f(xs, own):
            for x in xs:
                if x > 0:
                    target = own
            return own
        """)


def test_a_step_applied_to_one_of_two_twin_coordinates_is_named():
    rotate = """
        def rotate(image, angle_deg=45.0):
            h, w = image.shape[:2]
            cx, cy = (w - 1) / 2.0, (h - 1) / 2.0
            c, s = np.cos(np.radians(angle_deg)), np.sin(np.radians(angle_deg))
            xs, ys = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
            dx, dy = xs - cx, ys - cy
            map_x = (cx + c * dx - s * dy).astype(np.float32)
            map_y = ({centre}s * dx + c * dy).astype(np.float32)
            return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR)
        """
    assert one(rotate.format(centre="")) == {"`map_y` lacks the `cy` its twin `map_x` has"}
    assert not one(rotate.format(centre="cy + "))
    # a term only one coordinate has by its formula (K's skew, beside the other coordinate's own name)
    assert not one("""
        def to_pixels(K, xd, yd):
            map_x = K[0, 0] * xd + K[0, 1] * yd + K[0, 2]
            map_y = K[1, 1] * yd + K[1, 2]
            return map_x, map_y
        """)


def test_an_alias_changed_in_place_is_named():
    scaled = """
        def project_focal_lengths(points, focal_lengths):
            base = pinhole_project(points, 1.0)
            results = []
            for f in focal_lengths:
                xy = {copy}
                xy *= f
                results.append(xy)
            return np.stack(results)
        """
    assert one(scaled.format(copy="base")) == {"an alias of an array is changed in place"}
    assert not one(scaled.format(copy="base.copy()"))
    assert not one(scaled.format(copy="base * 1"))
    # a list row made another name for, then written in parts (the y row of a least-squares system)
    rows = """
        def affine_lstsq(src, dst):
            rows = []
            for (x, y) in src:
                row_x = [x, y, 1.0, 0.0, 0.0, 0.0]
                row_y = {copy}
                row_y[:3], row_y[3:] = [0.0, 0.0, 0.0], [x, y, 1.0]
                rows += [row_x, row_y]
            return rows
        """
    assert one(rows.format(copy="row_x")) == {"an alias of an array is changed in place"}
    assert not one(rows.format(copy="list(row_x)"))
    assert not one(rows.format(copy="row_x.copy()"))
    # a counter binds anew; a loop's own variable is no array
    assert not one("""
        def f(items):
            for i in range(len(items)):
                j = i
                j += 2
            return j
        """)


def test_the_strip_np_roll_brings_round_blanked_for_one_sign_only_is_named():
    rolled = """
        def translate(image, tx=100, ty=50):
            dx, dy = int(tx), int(ty)
            shifted = np.roll(image, (dy, dx), axis=(0, 1))
            {blank}
            return shifted
        """
    assert one(rolled.format(blank="shifted[:dy] = 0")) == {"the strip np.roll brings round is blanked for one sign only"}
    # the sign handled, or a disparity of a range (never below 0)
    assert not one(rolled.format(blank="shifted[:max(dy, 0)] = 0"))
    assert not one(rolled.format(blank="if dy > 0: shifted[:dy] = 0"))
    assert not one("""
        def costs(left, right):
            for d in range(16):
                shifted = np.roll(right, d, axis=1)
                shifted[:, :d] = 0
            return shifted
        """)


def test_a_parameter_compared_with_a_string_the_api_spells_otherwise_is_named():
    import ast
    from autograder.engine import strings_compared

    reference = (ROOT / "reference_solutions" / f"{MODULE8}.py").read_text()
    tree = ast.parse(textwrap.dedent("""
        def _detect(image, method):
            if method == "ORB":
                return 1
            return 2
        """))
    found = strings_compared.misspelt(tree.body, reference)
    assert found == ("_detect", "method", "ORB", 3, "orb")
    assert "compares `method` with 'ORB' (line 3), where the API's value is 'orb'" in strings_compared.sentence(*found)
    upper = ast.parse(textwrap.dedent("""
        def _detect(image, method):
            method = method.upper()
            return 1 if method == "ORB" else 2
        """))
    assert strings_compared.misspelt(upper.body, reference) is None   # (changed before it is compared)
    assert strings_compared.misspelt(ast.parse(reference).body, reference) is None


def test_an_array_scaled_in_place_at_every_turn_is_named():
    scaled = """
        def project_focal_lengths(points, focal_lengths):
            xy = {made}
            result = np.empty((len(focal_lengths), len(points), 2))
            for i, f in enumerate(focal_lengths):
                {scale}
                result[i] = xy
            return result
        """
    assert one(scaled.format(made="pinhole_project(points, 1.0)", scale="xy *= f")) \
        == {"an array scaled in place at every turn of a loop"}
    # a new array each turn; a running product started at a constant on purpose
    assert not one(scaled.format(made="pinhole_project(points, 1.0)", scale="xy = xy * 1.0; result[i] = xy * f"))
    assert not one(scaled.format(made="np.ones((len(points), 2))", scale="xy *= f"))


def test_a_write_through_an_index_that_copies_is_named():
    written = """
        def scaling_matrix(sx, sy):
            M = np.eye(3)
            {index}
            M{target} = np.diag([sx, sy])
            return M
        """
    for index, target in (("d = [0, 1]", "[d][:, d]"), ("d = np.arange(2)", "[d][:, d]"),
                          ("pass", "[[0, 1]][:, [0, 1]]")):
        assert one(written.format(index=index, target=target)) == {"a write into a copy made by an index"}, target
    # whole numbers and slices index views: the write lands in M
    assert not one(written.format(index="d = 1", target="[:2][:, :2]"))
    assert not one(written.format(index="pass", target="[0:2, 0:2]"))
    assert not one(written.format(index="d = 0", target="[d][:2]"))


def test_a_pose_kept_from_the_decomposition_without_testing_its_candidates_is_named():
    pose = """
        def two_view_reconstruction(img1, img2, K):
            E = K.T @ F @ K
            {decompose}
            points = triangulate(K, K @ np.hstack([R, t]), pts1, pts2)
            return points[points[:, 2] > 0]
        """
    wanted = {"a pose taken from cv2.decomposeEssentialMat without the test of its candidates"}
    assert one(pose.format(decompose="R, _, t = cv2.decomposeEssentialMat(E)")) == wanted
    assert one(pose.format(decompose="R = cv2.decomposeEssentialMat(E)[0]; t = np.ones((3, 1))")) == wanted
    # both rotations read (the four candidates tested), or recoverPose doing the test
    assert not one(pose.format(decompose="R1, R2, t = cv2.decomposeEssentialMat(E); R = best(R1, R2, t)"))
    assert not one(pose.format(decompose="_, R, t, _ = cv2.recoverPose(E, pts1, pts2, K); cv2.decomposeEssentialMat(E)"))


def test_a_lens_model_evaluated_on_pixel_offsets_is_named():
    lens = """
        def undistort_image(image, K, dist):
            k1, k2, p1, p2, k3 = dist
            u, v = np.meshgrid(np.arange(640.0), np.arange(480.0))
            x = (u - K[0, 2]){fx}
            y = (v - K[1, 2]){fy}
            r2 = x * x + y * y
            radial = 1 + k1 * r2 + k2 * r2 ** 2
            return x * radial, y * radial
        """
    assert one(lens.format(fx="", fy="")) == {"the lens model evaluated on pixel offsets, not normalised coordinates"}
    assert not one(lens.format(fx=" / K[0, 0]", fy=" / K[1, 1]"))


def test_a_loop_variable_named_as_a_value_read_after_the_loop_is_named():
    loop = """
        def project(P, world):
            out = []
            for {target} in np.atleast_2d(world):
                out.append(P @ np.append(point, 1.0))
            out = np.array(out)
            {after}
            return out[0] if world.ndim == 1 else out
        """
    wanted = {"a loop variable named as a value read after the loop"}
    assert one(loop.format(target="world", after="")) == wanted
    assert one(loop.format(target="point", after="")) == set()   # a name of its own
    # bound again after the loop before it is read: what it holds then is the new value
    assert one(loop.format(target="world", after="world = np.asarray(world)")) == set()


def test_a_homogeneous_system_solved_by_least_squares_is_named():
    centre = """
        def camera_center(P):
            C = np.linalg.{solver}(P, {rhs}, rcond=None)[0]
            return C[:3] / C[3]
        """
    wanted = {"a homogeneous system solved by least squares"}
    assert one(centre.format(solver="lstsq", rhs="np.zeros(3)")) == wanted
    assert one(centre.format(solver="lstsq", rhs="np.zeros_like(P[:, 0])")) == wanted
    assert one(centre.format(solver="lstsq", rhs="-P[:, 3]")) == set()   # an inhomogeneous system: right


def test_a_fundamental_matrix_given_where_the_essential_one_belongs_is_named():
    pose = """
        def two_view_reconstruction(pts1, pts2, K):
            F = {make}
            {between}
            _, R, t, _ = cv2.recoverPose({given}, pts1, pts2, K)
            return R, t
        """
    wanted = {"a fundamental matrix given where the essential matrix belongs"}
    assert one(pose.format(make="fundamental_8point(pts1, pts2)", between="", given="F")) == wanted
    assert one(pose.format(make="cv2.findFundamentalMat(pts1, pts2, cv2.FM_8POINT)[0]", between="", given="F")) \
        == wanted
    # E made from it first, and given instead (or under the same name)
    assert one(pose.format(make="fundamental_8point(pts1, pts2)", between="E = K.T @ F @ K", given="E")) == set()
    assert one(pose.format(make="fundamental_8point(pts1, pts2)", between="F = K.T @ F @ K", given="F")) == set()


def test_a_row_of_the_eigenvector_matrix_taken_as_an_eigenvector_is_named():
    centre = """
        def camera_center(P):
            {bind}
            {between}
            C = {taken}
            return C[:3] / C[3]
        """
    wanted = {"a row of the eigenvector matrix taken as an eigenvector"}
    pair = "vals, vecs = np.linalg.eig(P.T @ P)"
    assert one(centre.format(bind=pair, between="", taken="vecs[np.argmin(np.abs(vals))]")) == wanted
    assert one(centre.format(bind="vecs = np.linalg.eigh(P.T @ P)[1]", between="", taken="vecs[0]")) == wanted
    assert one(centre.format(bind=pair, between="i = np.argmin(np.abs(vals))", taken="vecs[i, :]")) == wanted
    # the columns, or rows of the transposed matrix, or the eigenvalues: right
    assert one(centre.format(bind=pair, between="i = np.argmin(np.abs(vals))", taken="vecs[:, i]")) == set()
    assert one(centre.format(bind=pair, between="vecs = vecs.T", taken="vecs[np.argmin(np.abs(vals))]")) == set()
    assert one(centre.format(bind=pair, between="", taken="vecs.T[np.argmin(np.abs(vals))]")) == set()
    assert one(centre.format(bind="vals = np.linalg.eigh(P.T @ P)[0]", between="", taken="vals[0] * P[0]")) == set()


def test_a_sine_from_its_cosine_by_a_square_root_is_named():
    rotation = """
        def rotation_matrix(theta):
            c = np.cos(np.deg2rad(theta))
            s = {sine}
            return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        """
    wanted = {"a sine or cosine from the other by a square root: its sign is lost"}
    assert one(rotation.format(sine="np.sqrt(1 - c ** 2)")) == wanted
    assert one(rotation.format(sine="math.sqrt(1.0 - c * c)")) == wanted
    assert one(rotation.format(sine="(1 - c**2) ** 0.5")) == wanted
    assert one(rotation.format(sine="np.sin(np.deg2rad(theta))")) == set()
    assert one(rotation.format(sine="np.sqrt(c ** 2 + 1)")) == set()   # (a square root of another kind)


def test_a_dimension_tested_after_the_array_was_made_two_dimensional_is_named():
    project = """
        def pinhole_project(points, f):
            {first}
            {second}
            xy = f * P[:, :2] / P[:, 2:3]
            return xy[0] if single else xy
        """
    wanted = {"a dimension tested after the array was made two-dimensional"}
    assert one(project.format(first="P = np.atleast_2d(points)", second="single = P.ndim == 1")) == wanted
    assert one(project.format(first="P = np.asarray(points, float).reshape(-1, 3)",
                              second="single = len(P.shape) == 1")) == wanted
    # tested before reshaping, or on the input as given: right
    assert one(project.format(first="single = np.ndim(points) == 1", second="P = np.atleast_2d(points)")) == set()
    assert one(project.format(first="P = np.atleast_2d(points)", second="single = np.asarray(points).ndim == 1")) \
        == set()
    assert one(project.format(first="P = np.asarray(points, float)", second="single = P.ndim == 1; "
                              "P = np.atleast_2d(P)")) == set()
    # one row of the 2-D array taken at once: the name is 1-D again
    assert one(project.format(first="P = np.atleast_2d(points)[0]", second="single = P.ndim == 1")) == set()


def test_the_ransac_masks_outliers_kept_are_named():
    pipeline = """
        def two_view_reconstruction(img1, img2, K):
            F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, 1.0, 0.999)
            inliers = {selection}
            return F, pts1[inliers], pts2[inliers]
        """
    wanted = {"the RANSAC mask's outliers kept"}
    assert one(pipeline.format(selection="mask.ravel() == 0")) == wanted
    assert one(pipeline.format(selection="mask.ravel() != 1")) == wanted
    assert one(pipeline.format(selection="~mask.ravel().astype(bool)")) == wanted
    assert one(pipeline.format(selection="mask.ravel() == 1")) == set()
    assert one(pipeline.format(selection="mask.ravel().astype(bool)")) == set()


def test_a_root_written_as_a_power_of_one_over_n_is_named():
    lines = """
        def epipolar_lines(F, pts):
            lines = pts @ F.T
            s = {scale}
            return lines / s
        """
    wanted = {"a root written as a power of 1/n (** binds tighter than /)"}
    assert one(lines.format(scale="(lines[:, 0] ** 2 + lines[:, 1] ** 2) ** 1/2")) == wanted
    assert one("def f(lines):\n    return lines / (lines[:, :1] ** 2 + lines[:, 1:2] ** 2) ** 1/2\n") == wanted
    assert one(lines.format(scale="(lines[:, 0] ** 2 + lines[:, 1] ** 2) ** (1 / 2)")) == set()
    assert one(lines.format(scale="(lines[:, 0] ** 2 + lines[:, 1] ** 2) ** 0.5")) == set()


def test_a_grid_unpacked_as_x_then_y_is_named():
    warp = """
        def apply_homography(image, H, dsize=None):
            h, w = image.shape[:2]
            {grid}
            return xs + ys
        """
    wanted = {"a grid's rows taken for its x"}
    assert one(warp.format(grid="xs, ys = np.mgrid[0:h, 0:w]")) == wanted
    assert one(warp.format(grid="xs, ys = np.indices((image.shape[0], w))")) == wanted
    assert one(warp.format(grid="xs, ys = np.mgrid[0:h, 0:w].astype(np.float64)")) == wanted
    assert one(warp.format(grid="ys, xs = np.mgrid[0:h, 0:w]")) == set()
    assert one(warp.format(grid="xs, ys = np.meshgrid(np.arange(w), np.arange(h))")) == set()   # (x first: right)


def test_a_result_rounded_to_a_few_decimals_is_named():
    essential = """
        def essential_from_fundamental(F, K1, K2):
            E = K2.T @ F @ K1
            {end}
        """
    wanted = {"the result rounded to a few decimals"}
    assert one(essential.format(end="return np.round(E, 4)")) == wanted
    assert one(essential.format(end="E = E.round(6)\n            return E")) == wanted
    assert one(essential.format(end="return E")) == set()
    assert one(essential.format(end="return np.round(E)")) == set()   # (whole numbers: an image's pixels)


def test_a_list_outside_the_function_grown_at_every_call_is_named():
    kept = """
        {head}
        def project_focal_lengths(points, focal_lengths):
            {made}
            for f in focal_lengths:
                results.append(points * f)
            return np.array(results)
        """
    wanted = {"a container outside the function keeps what earlier calls put in"}
    assert one(kept.format(head="results = []", made="pass")) == wanted
    assert one(kept.format(head="", made="results = []")) == set()          # made anew at each call
    assert one(kept.format(head="results = []", made="results = list()")) == set()
    cache = """
        _CACHE = {}
        def f(x):
            _CACHE.update({x: x})                                            # (a dict cache: no mistake)
            return _CACHE[x]
        """
    assert one(cache) == set()
    assert one("""
        import numpy as np
        def f(x):
            return np.append(x, 1.0)                                         # (numpy's function: nothing grown)
        """) == set()
    assert one("""
        results = []
        def f(x):
            global results
            results = []                                                     # (made anew at each call)
            results.append(x)
            return results
        """) == set()


def test_a_view_read_after_its_whole_array_changed_in_place_is_named():
    source = """
        def affine_from_points(src, dst):
            src, dst = np.array(src, float), np.array(dst, float)
            p0, q0 = src[0], dst[0]
            src {op} p0
            return q0 - p0
        """
    wanted = {"a view of an array read after the array was written"}
    assert one(source.format(op="-=")) == wanted        # (p0 is src[0]: it is 0 after the subtraction)
    assert one(source.format(op="= src -")) == set()   # (src bound anew: p0 keeps the old row)


def test_a_camera_matrix_augmented_with_a_zero_column_is_no_homogeneous_point():
    """`np.hstack([K, np.zeros((3, 1))])` is K [I | 0] (1202e lab09/04 was told "homogeneous with 0"); points given
    a constant zero column still are."""
    camera = """
        def project(K, X):
            P = np.hstack([{first}, np.zeros((3, 1))])
            x = np.hstack([X, np.ones((len(X), 1))]) @ P.T
            return x[:, :2] / x[:, 2:]
        """
    assert one(camera.format(first="K")) == set()
    assert one(camera.format(first="K1")) == set()
    assert one(camera.format(first="np.asarray(K, dtype=np.float64)")) == set()
    assert one("""
        def f(H, pts):
            p = np.hstack([pts, np.zeros((3, 1))])
            return p @ H.T
        """) == {"the homogeneous coordinate is 0 instead of 1"}


@pytest.mark.parametrize("product", ["np.dot(K2.T, F, K1)", "K2.T.dot(F, K1)", "np.asarray(K2).T.dot(F, K1)"])
def test_a_third_factor_given_where_dot_takes_its_output_is_read(product):
    """np.dot(a, b, c) and a.dot(b, c): the last argument is `out` (written into, not multiplied)."""
    source = f"""
        import numpy as np

        def essential_from_fundamental(F, K1, K2):
            return {product}
        """
    assert one(source) in ({"np.dot's third argument is its output, not an operand"},
                           {"ndarray.dot's second argument is its output, not an operand"}), one(source)


@pytest.mark.parametrize("product", ["K2.T.dot(F).dot(K1)", "np.dot(np.dot(K2.T, F), K1)", "K2.T.dot(F, out=None)",
                                     "K2.T @ F @ K1"])
def test_a_product_of_three_written_rightly_is_not_read_as_an_output(product):
    source = f"""
        import numpy as np

        def essential_from_fundamental(F, K1, K2):
            return {product}
        """
    assert not one(source), one(source)


def test_one_array_overwritten_and_appended_at_every_turn_is_read():
    source = """
        import numpy as np

        def project_focal_lengths(points, focal_lengths):
            xy = np.empty((len(points), 2))
            results = []
            for f in focal_lengths:
                xy[:] = f * points[:, :2] / points[:, 2:]
                results.append(xy)
            return np.array(results)
        """
    assert one(source) == {"one array is appended at every turn"}, one(source)


@pytest.mark.parametrize("turn", ["xy = f * points[:, :2]\\n                results.append(xy)",
                                  "xy[:] = f * points[:, :2]\\n                results.append(xy.copy())",
                                  "xy[:] = f * points[:, :2]\\n                results.append(np.array(xy))"])
def test_an_array_made_anew_or_copied_at_every_turn_is_not_read_as_one(turn):
    source = f"""
        import numpy as np

        def project_focal_lengths(points, focal_lengths):
            xy = np.empty((len(points), 2))
            results = []
            for f in focal_lengths:
                {turn}
            return np.array(results)
        """
    assert "one array is appended at every turn" not in one(source), one(source)


def test_a_running_product_stored_per_item_and_updated_in_place_is_read_with_each_loop():
    """`to_ref[k] = chain` after `chain @= step[k - 1]`, walking to each side of a reference image (the blind
    set 1205d's 08/02): every stored item is the one array; told once, with the second loop's line, and the
    update written anew; the product rebound (`chain = chain @ ...`) or stored as a copy is not read."""
    source = """
        import numpy as np

        def graded(step, r, n):
            to_ref = [None] * n
            chain = np.eye(3)
            for k in range(r + 1, n):
                chain @= step[k - 1]
                to_ref[k] = chain
            chain = np.eye(3)
            for k in range(r - 1, -1, -1):
                chain @= np.linalg.inv(step[k])
                to_ref[k] = chain
            return to_ref
        """
    findings = read_source(textwrap.dedent(source)).findings["graded"]
    assert [f.mistake for f in findings] == ["one array is appended at every turn"], findings
    assert "`chain = chain @ step[k - 1]`" in findings[0].sentence and "line 13 does the same" in findings[0].sentence, \
        findings[0].sentence
    rebound = source.replace("chain @= step[k - 1]", "chain = chain @ step[k - 1]").replace(
        "chain @= np.linalg.inv(step[k])", "chain = chain @ np.linalg.inv(step[k])")
    assert not one(rebound), one(rebound)
    assert not one(source.replace("to_ref[k] = chain", "to_ref[k] = chain.copy()")), one(source)
    # (an array's item is written with the values, a copy: `to_ref = np.empty((n, 3, 3))` keeps each product)
    assert not one(source.replace("to_ref = [None] * n", "to_ref = np.empty((n, 3, 3))")), one(source)


def test_the_unbound_method_with_its_array_first_is_not_read_as_an_output():
    """`np.ndarray.dot(a, b)` is `a.dot(b)`: two operands, no output."""
    source = """
        import numpy as np

        def essential_from_fundamental(F, K1, K2):
            return np.ndarray.dot(np.ndarray.dot(K2.T, F), K1)
        """
    assert not one(source), one(source)


def test_an_array_appended_in_nested_loops_is_read_once():
    """The buffer overwritten and appended inside an inner loop is found from the outermost loop (each node is
    read once: nested loops cost no more than their size)."""
    source = """
        import numpy as np

        def graded(blocks):
            buf = np.zeros(3)
            out = []
            for block in blocks:
                for row in block:
                    buf[:] = row
                    out.append(buf)
            return out
        """
    assert one(source) == {"one array is appended at every turn"}, one(source)


# ------------------------------------------------------------------ loops over values
RUNNING_HALVES = "a running average of pairs where the mean belongs"


@pytest.mark.parametrize("update", ["z = (z + d) / 2", "z = 0.5 * (d + z)", "z = (z + d) * 0.5"])
def test_a_running_average_of_pairs_is_read(update):
    assert RUNNING_HALVES in one(f"""
        def depth(values):
            z = values[0]
            for d in values[1:]:
                {update}
            return z
        """)


@pytest.mark.parametrize("loop", [
    # a bisection halves its bracket under a test
    """for _ in range(40):
                mid = (lo + hi) / 2
                if f(mid) > 0:
                    hi = (lo + hi) / 2
                else:
                    lo = mid""",
    # the midpoint of two values of the turn, not a running value
    """for a, b in pairs:
                m = (a + b) / 2""",
    # the mean itself
    """for d in values:
                total = total + d""",
])
def test_other_halvings_are_not_read_as_a_running_average(loop):
    assert RUNNING_HALVES not in one(f"""
        def solve(f, lo, hi, pairs, values, total):
            {loop}
            return lo
        """)


EARLIER_LOOP = "a loop reads the value an earlier loop left"


def test_a_value_an_earlier_loop_kept_per_turn_is_read_in_a_later_loop():
    assert EARLIER_LOOP in one("""
        def frames(points, f0, z0, distances):
            lengths, views = [], []
            for d in distances:
                f = f0 * d / z0
                lengths.append(f)
            for d in distances:
                views.append(project(points, f))
            return lengths, views
        """)


@pytest.mark.parametrize("second", [
    "for d, f in zip(distances, lengths):",      # the kept values, paired again
    "for d in distances:\n                f = f0 * d / z0",   # computed again in the loop
])
def test_a_later_loop_that_computes_or_pairs_the_value_is_not_read(second):
    assert EARLIER_LOOP not in one(f"""
        def frames(points, f0, z0, distances):
            lengths, views = [], []
            for d in distances:
                f = f0 * d / z0
                lengths.append(f)
            {second}
                views.append(project(points, f))
            return lengths, views
        """)


NORM_AT_ONCE = "a norm of every pair at once, where one per pair belongs"


@pytest.mark.parametrize("use", ["return errors < threshold", "mask = errors < threshold\n    return src[mask]",
                                 "inliers = errors < threshold\n    return int(np.sum(inliers))"])
def test_a_norm_without_axis_used_as_a_mask_of_the_pairs_is_read(use):
    assert NORM_AT_ONCE in one(f"""
def inliers(H, src, dst, threshold):
    errors = np.linalg.norm(project(H, src) - dst)
    {use}
""")


@pytest.mark.parametrize("source", [
    # one distance per pair
    """
def inliers(H, src, dst, threshold):
    errors = np.linalg.norm(project(H, src) - dst, axis=1)
    return errors < threshold
""",
    # two single points compared with a tolerance
    """
def same_centre(c1, c2):
    gap = np.linalg.norm(c1 - c2)
    if gap < 1e-9:
        return True
    return False
""",
])
def test_a_norm_with_its_axis_or_of_one_point_is_not_read(source):
    assert NORM_AT_ONCE not in one(source)


ROWS_TRANSPOSED = "points transposed into a function that reads them as rows"
OWN_TRIANGULATE = """
def triangulate(P1, P2, pts1, pts2):
    pts1 = np.asarray(pts1, np.float64).reshape(-1, 2)
    return solve(P1, P2, pts1, pts2)

def pipeline(P1, P2, pts1, pts2):
    return triangulate(P1, P2, {given})
"""


def test_points_transposed_into_a_function_that_reads_rows_are_read():
    found = mistakes_in(OWN_TRIANGULATE.format(given="pts1.T, pts2.T"))
    assert ROWS_TRANSPOSED in found.get("pipeline", set()), found


@pytest.mark.parametrize("given", ["pts1, pts2", "pts1, pts2.T"])   # (pts2 is not read as rows there)
def test_points_given_as_rows_or_to_a_parameter_read_otherwise_are_not(given):
    assert ROWS_TRANSPOSED not in one(OWN_TRIANGULATE.format(given=given))


SVD_FACTOR = "a factor of an SVD left out of the rebuild"


def test_an_svd_rebuilt_without_one_factor_is_read():
    assert SVD_FACTOR in one("""
def essential(E):
    U, S, Vt = np.linalg.svd(E)
    return np.diag([1.0, 1.0, 0.0]) @ Vt
""")


@pytest.mark.parametrize("source", [
    "def null(A):\n    U, S, Vt = np.linalg.svd(A)\n    return Vt[-1]",                                 # a null vector
    "def rank2(F):\n    U, S, Vt = np.linalg.svd(F)\n    return U @ np.diag([S[0], S[1], 0.0]) @ Vt",   # both used
])
def test_an_svd_whose_factors_are_used_as_needed_is_not_read(source):
    assert SVD_FACTOR not in one(source)


def test_a_value_assigned_to_the_loop_variable_and_dropped_is_named():
    """`for x, K in ((x1, K1), (x2, K2)): x = x @ inv(K).T` changes neither x1 nor x2; read later in the turn,
    or kept by an append, the value is used."""
    loop = """
        def essential_8point(x1, x2, K1, K2):
            kept = []
            for x, K in ((x1, K1), (x2, K2)):
                x = x @ np.linalg.inv(K).T
                {after}
            return x1, x2, kept
        """
    wanted = "a value assigned to the loop variable and dropped"
    assert one(loop.format(after="")) == {wanted}
    assert "`x1`, `x2` stay as they were" in next(f.sentence for f in read_source(textwrap.dedent(loop.format(after="")))
                                                 .findings["essential_8point"] if f.mistake == wanted)
    assert wanted not in one(loop.format(after="kept.append(x)"))
    assert wanted not in one(loop.format(after="x[0] = 1"))   # (read: x[0] = ... writes into the array x holds)


def test_the_fisheye_lens_model_is_named_where_the_calibrations_belongs():
    code = """
        def undistort_image(image, K, dist):
            return cv2.{call}(image, K, np.asarray(dist, np.float64).ravel()[:4]{more})
        """
    wanted = "the fisheye lens model used for the calibration's distortion"
    assert wanted in one(code.format(call="fisheye.undistortImage", more=", Knew=K"))
    assert wanted not in one(code.format(call="undistort", more=""))


def test_a_loop_variable_assigned_and_read_after_the_loop_is_not_dropped():
    """The last turn's value read after the loop (`for x in xs: x = f(x)` then `return x`) is used."""
    assert "a value assigned to the loop variable and dropped" not in one("""
        def f(xs):
            for x in xs:
                x = x * 2
            return x
        """)


def test_a_value_compared_with_a_literal_by_identity_is_named_and_none_by_identity_is_not():
    """The blind set 1204c's 08/04: `method is "orb"` fails for the caller's equal string (another object);
    `is None`, `is True` are right, and `==` is what the finding asks for."""
    code = """
        def match_features(img1, img2, method="sift"):
            if {test}:
                return 1
            return 2
        """
    wanted = "a value compared with a literal by identity (is)"
    for test in ('method is "orb"', "'sift' is not method", "ratio is 0.75"):
        assert wanted in one(code.format(test=test)), test
    for test in ("method is None", "method is True", 'method == "orb"', "method is other"):
        assert wanted not in one(code.format(test=test)), test


def test_a_rotation_matrix_given_back_to_itself_through_rodrigues_is_named():
    """The blind set 1204c's 09/03: `R, _ = cv2.Rodrigues(R)` "accepts a rotation vector too" by turning every 3x3
    R into its vector. Guarded by R's shape, or a vector made under another name (for cv2.projectPoints), it
    is right."""
    wanted = "a rotation matrix turned into a rotation vector by cv2.Rodrigues"
    code = """
        def camera_matrix(K, R, t):
            {body}
            return K @ np.hstack([R, np.reshape(t, (3, 1))])
        """
    assert wanted in one(code.format(body="R, _ = cv2.Rodrigues(R)"))
    assert wanted in one(code.format(body="R = cv2.Rodrigues(R)[0]"))
    assert wanted not in one(code.format(body="R = cv2.Rodrigues(R)[0] if np.size(R) == 3 else R"))
    assert wanted not in one(code.format(body="rvec, _ = cv2.Rodrigues(R)"))


def test_a_matrix_from_a_literal_of_whole_numbers_truncates_a_fractional_scale_without_a_measure():
    """`T = np.array([[1, 0, 0], ...])` then `T[0, 0] = s` with `s` a ratio of roots: every value written is cut,
    whatever the outputs show (the finding needs no whole numbers, and is said beside a check's own name); a
    count written into it needs the measure, and a float literal or a dtype is no finding."""
    source = """
        def conditioning(pts):
            centre = pts.mean(axis=0)
            s = np.sqrt(2.0) / np.mean(np.linalg.norm(pts - centre, axis=1))
            T = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1]]{dtype})
            T[0, 0] = {value}
            return T
        """
    found = read_source(textwrap.dedent(source.format(dtype="", value="s")), frozenset()).findings["conditioning"]
    assert [(f.mistake, f.needs, f.certain) for f in found] == [
        ("an integer array: the values written into it are truncated", "", True)]
    counted = read_source(textwrap.dedent(source.format(dtype="", value="n + k")), frozenset()).findings
    assert [(f.needs, f.certain) for f in counted.get("conditioning", [])] == [("whole numbers", False)]
    assert "an integer array: the values written into it are truncated" not in one(source.format(dtype=", dtype=float", value="s"))
    assert "an integer array: the values written into it are truncated" not in one(
        source.format(dtype="", value="s").replace("[[1, 0, 0]", "[[1.0, 0, 0]"))


READ_TWICE = "an iterator read twice: the second reading finds it empty"


@pytest.mark.parametrize("source, found", [
    # a generator read by the loop, then by np.fromiter: the second finds it empty
    ("def f(ds, f0):\n    fs = (f0 * d for d in ds)\n    out = [g for g in fs]\n    return np.fromiter(fs, float), out", True),
    ("def f(ds, f0):\n    fs = (f0 * d for d in ds)\n    return list(fs), sum(fs)", True),
    # read once, through a wrapper in the loop's own header: one reading
    ("def f(ds, f0):\n    fs = (f0 * d for d in ds)\n    return [(i, g) for i, g in enumerate(fs)]", False),
    ("def f(ds, f0):\n    fs = (f0 * d for d in ds)\n    return [g for g in sorted(fs)]", False),
    ("def f(ds, f0):\n    fs = [f0 * d for d in ds]\n    return np.fromiter(fs, float), [g for g in fs]", False),
])
def test_a_generator_read_by_a_loop_and_a_call_is_read_twice(source, found):
    assert (READ_TWICE in one(source)) is found


def test_rows_repeated_are_told_to_be_made_anew_with_the_student_s_own_count_and_row():
    """`[[0.0] * 3] * n` (n points of 3 coordinates): the advice keeps their row and their count, `n` -- a 3 of
    the grader's would mend only three points (the blind set 05c's 12/01, its evaluator's strict note)."""
    reading = read_source(textwrap.dedent("""
        def f(pts):
            n = len(pts)
            points = [[0.0] * 3] * n
            for i in range(n):
                points[i][0] = pts[i][0]
            return points
        """), frozenset())
    sentences = [finding.sentence for found in reading.findings.values() for finding in found]
    assert any("`[[0.0] * 3 for _ in range(n)]`, or np.zeros((n, 3))" in s for s in sentences), sentences


@pytest.mark.parametrize("source, said", [
    ("def f(p, q):\n    return p[:, 2] > 0 & q[:, 2] > 0",
     "write `(p[:, 2] > 0) & (q[:, 2] > 0)`"),
    ("def f(d, lo, hi):\n    return d >= lo | d <= hi", "write `(d >= lo) | (d <= hi)`"),
    ("def f(d):\n    return (d > 0) & (d < 5)", None),
    ("def f(d, m):\n    return 0 < d & m < 5", "write `(0 < d) & (m < 5)`"),
    ("def f(d):\n    return 0 < d < 5", None),
])
def test_two_comparisons_joined_by_a_bitwise_operator_without_parentheses_are_read(source, said):
    """`&` binds before `>`: `a > 0 & b > 0` is `a > (0 & b) > 0` (the 05d blind set's 11/06, a TypeError told
    only as relayed before)."""
    sentences = [f.sentence for found in read_source(source, frozenset()).findings.values() for f in found]
    assert (any(said in s for s in sentences) if said else not any("binds before" in s for s in sentences)), sentences


def test_a_reciprocal_transposed_in_a_product_is_read_as_taken_for_the_inverse():
    """`x @ (K1 ** -1).T` (the 05d blind set's 11/04, a failed SVD told only as relayed before)."""
    source = "def f(x, K1):\n    return x @ (K1 ** -1).T\n"
    sentences = [f.sentence for found in read_source(source, frozenset()).findings.values() for f in found]
    assert any("np.linalg.inv(K1)" in s for s in sentences), sentences


def test_vectors_divided_by_the_whole_arrays_norm_are_read():
    """`d = rng.standard_normal((n, k, 2))` then `d / np.linalg.norm(d)` (the blind set 1205e's 09/02): one
    number for every vector; with an axis, or of a single vector, nothing is read."""
    source = """
        import numpy as np

        def graded(n, k, seed):
            rng = np.random.default_rng(seed)
            d = rng.standard_normal((n, k, 2))
            d = d / np.linalg.norm(d)
            return d
        """
    assert one(source) == {"every vector divided by the norm of the whole array"}, one(source)
    assert not one(source.replace("np.linalg.norm(d)", "np.linalg.norm(d, axis=-1, keepdims=True)"))
    assert not one(source.replace("rng.standard_normal((n, k, 2))", "rng.standard_normal(3)"))


def test_a_homogeneous_one_scaled_with_the_coordinates_is_read_beside_its_transform():
    """`np.hstack([pts - c, ones]) * s` where T = [[s, 0, -s c0], ...] undoes the normalisation (the blind set
    1205e's 11/04): the 1 becomes s; scaled before the 1 is appended, or with no transform made of s, nothing."""
    source = """
        import numpy as np

        def graded(pts):
            c = pts.mean(axis=0)
            s = np.sqrt(2) / np.mean(np.linalg.norm(pts - c, axis=1))
            ones = np.ones((len(pts), 1))
            q = np.hstack([pts - c, ones]) * s
            T = np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])
            return q, T
        """
    assert one(source) == {"the homogeneous 1 is scaled with the coordinates"}, one(source)
    assert not one(source.replace("np.hstack([pts - c, ones]) * s", "np.hstack([(pts - c) * s, ones])"))
    assert not one(source.replace("T = np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])", "T = None"))


def test_a_determinant_compared_with_an_exact_value_is_read():
    """`if np.linalg.det(R) == -1:` (the blind set 1205f's 10/02): a float determinant is -1 only to rounding;
    a test of its sign is not read."""
    source = """
        import numpy as np

        def graded(R, t):
            if np.linalg.det(R) == -1:
                R, t = -R, -t
            return R, t
        """
    assert one(source) == {"a determinant compared with an exact value"}, one(source)
    assert not one(source.replace("np.linalg.det(R) == -1", "np.linalg.det(R) < 0"))


def test_opencv_flags_joined_with_or_are_read():
    """`flags=cv2.INTER_LINEAR or cv2.WARP_INVERSE_MAP` (the blind set 1205e's 08/01): `or` keeps one flag;
    joined with `|`, nothing is read."""
    source = """
        import cv2

        def graded(image, H, size):
            return cv2.warpPerspective(image, H, size, flags=cv2.INTER_LINEAR or cv2.WARP_INVERSE_MAP)
        """
    assert one(source) == {"OpenCV flags joined with `or` or `and`"}, one(source)
    assert not one(source.replace(" or ", " | "))


def test_a_best_kept_as_another_name_for_the_array_the_loop_rewrites_is_read():
    """`best_inliers = mask` where the loop writes `mask` in place at every turn (the blind set 1205g's 08/04,
    `np.less(err, t, out=mask)`): the best kept is the last turn's. A copy, or a mask made anew each turn, is
    not read; nor a name never read after the loop."""
    source = """
        import numpy as np

        def ransac(err_of, n, trials):
            best_count, best = 0, None
            mask = np.zeros(n, dtype=bool)
            for _ in range(trials):
                {write}
                if mask.sum() > best_count:
                    best_count, best = mask.sum(), {kept}
            return best
        """
    read = {"a value kept in a loop is the array the loop rewrites"}
    for write in ("np.less(err_of(), 3.0, out=mask)", "mask[:] = err_of() < 3.0", "np.copyto(mask, err_of() < 3.0)"):
        assert one(source.format(write=write, kept="mask")) == read, write
        assert not one(source.format(write=write, kept="mask.copy()")), write
    assert not one(source.format(write="mask = err_of() < 3.0", kept="mask"))
    assert not one(source.format(write="np.less(err_of(), 3.0, out=mask)", kept="mask").replace("return best", "return best_count"))


def test_one_array_given_two_names_by_a_chained_assignment_is_read():
    """`xs = ys = np.full(n, np.nan)` then each written into (the blind set 1205g's 09/01): one array. Two
    arrays, or a chained number, are not read."""
    source = """
        import numpy as np

        def project(points, f):
            n = len(points)
            {made}
            for i, (X, Y, Z) in enumerate(points):
                xs[i] = f * X / Z
                ys[i] = f * Y / Z
            return np.stack([xs, ys], axis=1)
        """
    assert one(source.format(made="xs = ys = np.full(n, np.nan)")) == {"one array given two names by a chained assignment"}
    assert not one(source.format(made="xs, ys = np.full(n, np.nan), np.full(n, np.nan)"))
    assert not one(source.format(made="xs = ys = 0").replace("xs[i] = ", "xs = ").replace("ys[i] = ", "ys = "))


def test_a_lambda_made_in_a_loop_reading_its_variable_is_read():
    """`[lambda p: project(p, f) for f in fs]` (the blind sets 1205g's 09/02 and 1204g's 10/05): every lambda
    uses the last f. Bound as a default, or called in the loop's own turn, nothing is read."""
    made = """
        def project_all(points, fs):
            cameras = {cameras}
            return [camera(points) for camera in cameras]
        """
    read = {"a lambda made in a loop reads the loop's variable when called"}
    assert one(made.format(cameras="[lambda p: project(p, f) for f in fs]")) == read
    assert not one(made.format(cameras="[lambda p, f=f: project(p, f) for f in fs]"))
    assert one("""
        def project_all(points, fs):
            cameras = []
            for f in fs:
                cameras.append(lambda p: project(p, f))
            return [camera(points) for camera in cameras]
        """) == read
    assert not one("""
        def project_all(points, fs):
            return [(lambda p: project(p, f))(points) for f in fs]
        """.replace("(lambda p: project(p, f))(points)", "project(points, f)"))


def test_rows_of_np_empty_a_loop_continues_past_are_read():
    """`poses = np.empty((F, 6))` and a `continue` before the row is written (the blind set 1205g's 10/06): those
    rows are garbage. Made with np.full, or the row written before continuing, nothing is read."""
    source = """
        import numpy as np

        def track(frames):
            poses = {made}
            for i, frame in enumerate(frames):
                found, pose = detect(frame)
                if not found:
                    {skipped}
                    continue
                poses[i] = pose
            return poses
        """
    read = {"rows of np.empty left unwritten where a loop continues"}
    assert one(source.format(made="np.empty((len(frames), 6))", skipped="pass")) == read
    assert not one(source.format(made="np.full((len(frames), 6), np.nan)", skipped="pass"))
    assert not one(source.format(made="np.empty((len(frames), 6))", skipped="poses[i] = np.nan"))


def test_infinity_written_before_a_filter_is_read():
    """`squared[:, :d] = np.inf` and then a box filter (cv2.blur, or a helper of the module filtering its first
    parameter; the blind set 1205g's 12/02): inf - inf is NaN in the filter's sums. Set after the filter,
    nothing is read."""
    source = """
        import cv2
        import numpy as np

        def _box_mean(image, k):
            return cv2.blur(image, (k, k))

        def volume(left, right, d, k):
            squared = (left - right) ** 2
            {before}
            cost = {filtered}
            {after}
            return cost
        """
    read = {"infinity written into an array before it is filtered"}
    for filtered in ("cv2.blur(squared, (k, k))", "_box_mean(squared, k)"):
        assert one(source.format(before="squared[:, :d] = np.inf", filtered=filtered, after="pass")) == read, filtered
        assert not one(source.format(before="pass", filtered=filtered, after="cost[:, :d] = np.inf")), filtered


def test_every_view_given_to_the_calibration_as_one_is_read():
    """`[np.concatenate(object_points)]` given to cv2.calibrateCamera (the blind set 1205g's 09/04): one view of
    every view's points. The per-view lists as they are, nothing is read."""
    source = """
        import cv2
        import numpy as np

        def calibrate(object_points, image_points, size):
            {merge}
            rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points, size, None, None)
            return K, dist, rms
        """
    assert one(source.format(merge="object_points = [np.concatenate(object_points)]")) \
        == {"every view given to the calibration as one view"}
    assert not one(source.format(merge="object_points = [np.asarray(p, np.float32) for p in object_points]"))


def test_a_whole_rows_norm_where_its_blocks_belongs_is_read():
    """`P / np.linalg.norm(P[2])` where the code decomposes the block `P[:, :3]` (the blind set 1205g's 10/04):
    the row's last column counts too. The block's row, or a matrix with no block taken, is not read."""
    source = """
        import numpy as np

        def decompose(P):
            P = P / np.linalg.norm({row})
            M = P[:, :3]
            return np.linalg.qr(np.linalg.inv(M))
        """
    assert one(source.format(row="P[2]")) == {"a whole row's norm where the block's row's belongs"}
    assert not one(source.format(row="P[2, :3]"))
    assert not one(source.format(row="P[2]").replace("P[:, :3]", "P"))


def test_a_reader_that_fails_costs_no_other_findings(monkeypatch):
    """One reader raising on code nobody foresaw leaves the others' findings."""
    from autograder.loading import reading

    def broken(name, function):
        raise AttributeError("a reader's own slip")

    monkeypatch.setattr(reading, "_eig_unsorted", broken)
    assert one("""
        def shear_matrix(s):
            return np.eye(3) + s * np.eye(3, k=1)
        """) == {"np.eye(n, k) fills its whole off-diagonal"}


def test_rows_of_np_empty_filled_outside_the_loop_and_a_scale_fixed_after_are_not_read():
    """Review: np.empty whose skipped rows are set after the loop (or filled before it) holds no garbage; P scaled by
    its whole row's norm and K divided by K[2, 2] afterwards may be right (t solved before K is divided)."""
    rows = """
        import numpy as np

        def track(frames):
            poses = np.empty((len(frames), 6))
            {before}
            found_any = np.zeros(len(frames), bool)
            for i, frame in enumerate(frames):
                found, pose = detect(frame)
                if not found:
                    continue
                poses[i] = pose
                found_any[i] = True
            {after}
            return poses
        """
    read = {"rows of np.empty left unwritten where a loop continues"}
    assert one(rows.format(before="pass", after="pass")) == read
    assert not one(rows.format(before="poses.fill(np.nan)", after="pass"))
    assert not one(rows.format(before="pass", after="poses[~found_any] = np.nan"))
    scaled = """
        import numpy as np

        def decompose(P):
            P = P / np.linalg.norm(P[2])
            K, R = rq(P[:, :3])
            t = np.linalg.solve(K, P[:, 3])
            {fixed}
            return K, R, t
        """
    assert one(scaled.format(fixed="pass")) == {"a whole row's norm where the block's row's belongs"}
    assert not one(scaled.format(fixed="K = K / K[2, 2]"))
    assert not one(scaled.format(fixed="K /= K[-1, -1]"))


def test_a_binary_search_of_the_gray_codes_in_stripe_order_is_read():
    """`np.searchsorted(codes, g)` with `codes = k ^ (k >> 1)` (the blind set 1205h's 12/03): the table is not
    sorted. A sorted table, or a search given its sorter, is not read."""
    source = """
        import numpy as np

        def decode(g, n_bits):
            stripes = np.arange(2 ** n_bits)
            codes = {table}
            return np.searchsorted(codes, g{sorter})
        """
    assert one(source.format(table="stripes ^ (stripes >> 1)", sorter="")) == {
        "a binary search (np.searchsorted) of a table that is not sorted"}
    assert not one(source.format(table="np.sort(stripes ^ (stripes >> 1))", sorter=""))
    assert not one(source.format(table="stripes ^ (stripes >> 1)", sorter=", sorter=np.argsort(codes)"))
    assert not one(source.format(table="stripes * 2", sorter=""))


def test_a_list_repeated_by_star_and_an_item_changed_in_place_is_read():
    """`[np.eye(3)] * n` with `Hs[k] @= step` (the blind set 1206a's 08/03) and `[[0.0] * 3] * 3` with
    `M[0][0] = sx` hold one object n times: an item changed in place changes every item. A list of numbers
    (`counts[k] += 1` rebinds the item) and an item given a new array are not read as one."""
    repeated = "one object repeated by * and changed in place"
    assert repeated in one("""
        def f(steps):
            Hs = [np.eye(3)] * len(steps)
            for k, step in enumerate(steps):
                Hs[k] @= step
            return Hs
        """)
    assert repeated in one("""
        def f(sx, sy):
            M = [[0.0] * 3] * 3
            M[0][0] = sx
            M[1][1] = sy
            return np.array(M)
        """)
    assert repeated not in one("""
        def f(n):
            counts = [0] * n
            counts[1] += 1
            Hs = [np.eye(3)] * n
            Hs[1] = Hs[1] @ np.eye(3)
            return counts, Hs
        """)


def test_a_loop_value_never_used_is_not_told_as_items_left_unchanged():
    """`for la, lb, w in zip(lap_a, lap_b, masks): w = w[..., None]` with nothing reading `w` or `masks` after (the
    blind set 1206a's 08/06: the mask ignored): the value is told unused, not the items unchanged; where the items
    looped over are read after the loop, the dropped value is the cause."""
    unused = one("""
        def f(lap_a, lap_b, masks):
            out = []
            for la, lb, w in zip(lap_a, lap_b, masks):
                w = w[..., None]
                out.append(la + lb)
            return out
        """)
    assert "a value made in a loop and never used" in unused and "a value assigned to the loop variable and dropped" not in unused
    dropped = one("""
        def f(images):
            for image in images:
                image = image / 255.0
            return images
        """)
    assert "a value assigned to the loop variable and dropped" in dropped


def test_a_comparison_written_as_a_statement_is_read():
    """`M[0, 1] == s` on a line of its own (the blind set 1206b's 07/06): nothing keeps the comparison, the entry
    keeps its value; a comparison that is kept (assigned, returned, tested) is not read as one."""
    assert "a comparison written where an assignment belongs" in one("""
        def f(s):
            M = np.eye(3)
            M[0, 1] == s
            return M
        """)
    assert "a comparison written where an assignment belongs" not in one("""
        def f(s):
            same = s == 0
            if s == 1:
                return same
            return s == 2
        """)


def test_an_alias_reversed_or_sorted_in_place_changes_the_list_it_names():
    """`mirrored = codes; mirrored.reverse()` (the blind set 1206b's 12/04): a method that changes a list in place
    changes the list both names hold; a copy taken first is not read as one."""
    source = """
        def f(n):
            codes = ["0", "1"]
            for _ in range(n - 1):
                mirrored = codes
                mirrored.reverse()
                codes = ["0" + c for c in codes] + ["1" + c for c in mirrored]
            return codes
        """
    assert "an alias of an array is changed in place" in one(source)
    assert "an alias of an array is changed in place" not in one(source.replace("mirrored = codes", "mirrored = codes[:]"))


def test_a_comparison_of_a_whole_value_and_a_list_grown_through_another_name_are_not_read():
    """`result.shape == (3,)` or `x == 5` left from debugging writes nothing whatever was meant, and `rows = out;
    rows.append(x)` grows the list both names hold, as is often meant: neither is read as a slip."""
    found = one("""
        def f(x, out):
            result = np.zeros(3)
            result.shape == (3,)
            x == 5
            rows = out
            for v in range(3):
                rows.append(v)
            return result, out
        """)
    assert "a comparison written where an assignment belongs" not in found
    assert "an alias of an array is changed in place" not in found


def test_a_value_whose_name_a_loop_takes_before_it_is_read_is_read():
    """`r, c = out.shape[:2]` then `for a, b, c in lines:` reading `c` as the width (the blind set 1206c's 11/02):
    the loop's items are what the loop reads, the width is never read. A constant set first (`i = 0`), a value
    read before the loop, or a loop that does not read the name is not read as one."""
    source = """
        def f(out, lines):
            r, c = out.shape[:2]
            for a, b, c in lines:
                out[0, int(c) - 1] = a + b
            return out, r
        """
    assert "a value assigned above a loop whose variable takes its name" in one(source)
    assert "a value assigned above a loop whose variable takes its name" not in one(
        source.replace("r, c = out.shape[:2]", "r, c = out.shape[:2]\n            print(c)"))
    assert "a value assigned above a loop whose variable takes its name" not in one("""
        def f(items):
            i = 0
            for i, item in enumerate(items):
                item.append(i)
            return items
        """)
    assert "a value assigned above a loop whose variable takes its name" not in one("""
        def f(out, lines):
            r, c = out.shape[:2]
            for a, b, c in lines:
                out[0, 0] = a + b
            return out, r
        """)


def test_opencv_flags_joined_with_or_passed_into_another_parameter_are_read():
    """`cv2.warpAffine(image, M, size, cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)` (the blind set 1206c's 07/02): the
    fourth place is `dst`, which gets the flags' number; by name (`flags=...`) it is not read."""
    source = """
        def f(image, M, size):
            return cv2.warpAffine(image, M, size, cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
        """
    found = one(source)
    assert "cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP is passed as cv2.warpAffine's dst" in found
    assert not any("is passed as" in mistake for mistake in one(source.replace("size, cv2.INTER", "size, flags=cv2.INTER")))


def test_one_samples_pairs_drawn_by_two_random_draws_are_read():
    """`src[rng.choice(n, 4)]` beside `dst[rng.choice(n, 4)]` (the blind set 1206b's 08/04): the rows of one array
    are not the partners of the other's. One draw indexing both, or two draws each indexing both arrays (a sample
    and a check set), is not read as one."""
    source = """
        def f(src, dst, rng, n):
            for _ in range(10):
                a = src[rng.choice(n, 4, replace=False)]
                b = dst[rng.choice(n, 4, replace=False)]
            keep = src[src[:, 0] > 0]
            return a, b, keep
        """
    assert "one sample's pairs drawn apart, by two random draws" in one(source)
    assert "one sample's pairs drawn apart, by two random draws" not in one("""
        def f(src, dst, rng, n):
            pick = rng.choice(n, 4, replace=False)
            check = rng.permutation(n)[:10]
            return src[pick], dst[pick], src[check], dst[check]
        """)


@pytest.mark.parametrize("reordered", [
    "return np.unique(pts1, axis=0), np.unique(pts2, axis=0)",
    "pts1 = np.unique(pts1, axis=0)\n            pts2 = np.unique(pts2, axis=0)\n            return pts1, pts2",
    "src = src[np.argsort(src[:, 0])]\n            dst = dst[np.argsort(dst[:, 0])]\n            return src, dst",
])
def test_the_two_arrays_of_one_set_of_pairs_reordered_apart_are_read(reordered):
    """`np.unique(pts1, axis=0), np.unique(pts2, axis=0)` (the blind set 1206d's 08/05): each array sorted and
    thinned by its own values, so row k of one no longer pairs with row k of the other. Both reordered by one
    index, or one array made unique on its own (its partner not reordered), is not read."""
    mistake = "the two arrays of one set of pairs reordered apart"
    assert mistake in one(f"""
        def f(pts1, pts2, src, dst):
            {reordered}
        """)
    assert mistake not in one("""
        def f(pts1, pts2):
            _, keep = np.unique(pts1, axis=0, return_index=True)
            return pts1[keep], pts2[keep]
        """)
    assert mistake not in one("""
        def f(pts1, pts2):
            order = np.argsort(pts1[:, 0])
            return pts1[order], pts2[order], np.unique(pts1, axis=0)
        """)


@pytest.mark.parametrize("made", ["p = _homogeneous(points)", "p = np.hstack([points, np.ones((len(points), 1))])"])
@pytest.mark.parametrize("centred", ["c = p.mean(axis=0)\n            q = p - c", "q = p - np.mean(p, axis=0)"])
def test_homogeneous_rows_centred_with_their_ones_are_read(made, centred):
    """`p - p.mean(axis=0)` of rows (x, y, 1) (the blind set 1206e's 11/05): the 1s become 0. Centring x and y
    only, or points that are not homogeneous, is not read."""
    mistake = "the homogeneous 1s centred with the points"
    assert mistake in one(f"""
        def f(points):
            {made}
            {centred}
            return q
        """)
    assert mistake not in one(f"""
        def f(points):
            {made}
            c = p[:, :2].mean(axis=0)
            return p[:, :2] - c
        """)
    assert mistake not in one("""
        def f(points):
            p = np.asarray(points, float)
            return p - p.mean(axis=0)
        """)


def test_keypoints_sorted_apart_from_their_descriptors_are_read():
    """`kp, des = sift.detectAndCompute(...)` then `kp = sorted(kp, key=...)` (the blind sets 1201i's 08/05 and
    1206e's 11/06): descriptor i no longer belongs to keypoint i. Sorted together, or the descriptors given an
    order too, is not read."""
    mistake = "keypoints reordered apart from their descriptors"
    source = """
        def f(image, sift):
            kp, des = sift.detectAndCompute(image, None)
            kp = sorted(kp, key=lambda k: -k.response)
            return kp, des
        """
    assert mistake in one(source)
    assert mistake not in one(source.replace("return kp, des", "des = des[np.argsort([-k.response for k in kp])]\n"
                                                                "            return kp, des"))
    assert mistake not in one("""
        def f(image, sift):
            kp, des = sift.detectAndCompute(image, None)
            order = np.argsort([-k.response for k in kp])
            return [kp[i] for i in order], des[order]
        """)


def test_a_mutable_default_written_into_is_read():
    """`def _condition(pts, T=np.eye(3)):` filling T in place (the blind set 1206d's 11/04): every call leaving T
    out shares one array. A default None, or a copy made first, is not read as one."""
    source = """
        def _condition(pts, T=np.eye(3)):
            T[0, 0] = 1.0 / pts.std()
            return pts * T[0, 0], T
        """
    assert "a default made once and written into by every call" in one(source)
    assert "a default made once and written into by every call" not in one(
        source.replace("T[0, 0] = 1.0", "T = T.copy()\n            T[0, 0] = 1.0"))
    assert "a default made once and written into by every call" not in one(
        source.replace("T=np.eye(3)", "T=None").replace("T[0, 0] = 1.0", "T = np.eye(3)\n            T[0, 0] = 1.0"))


def test_a_conditional_taken_into_a_tuple_is_read():
    """`size = dsize if dsize is not None else width, height` (the blind set 1206d's 07/04): the comma binds
    looser than the conditional; bracketed either way it is not read."""
    source = """
        def f(image, dsize=None):
            height, width = image.shape[:2]
            size = dsize if dsize is not None else width, height
            return size
        """
    assert "a conditional expression taken into a tuple (the comma binds looser)" in one(source)
    for meant in ("dsize if dsize is not None else (width, height)", "(dsize if dsize is not None else width), height"):
        assert "a conditional expression taken into a tuple (the comma binds looser)" not in one(
            source.replace("dsize if dsize is not None else width, height", meant))


def test_a_pair_returned_or_unpacked_beside_a_conditional_is_meant():
    """`return H if ok else None, mask` and `H, mask = ...`: a pair is meant, not read as a conditional taken in."""
    for line in ("return H if ok else None, mask", "H, m = H if ok else None, mask\n            return H, m"):
        assert "a conditional expression taken into a tuple (the comma binds looser)" not in one(f"""
        def f(H, ok, mask):
            {line}
        """)


def test_a_pyramid_of_uint8_images_is_read_as_uint8_where_its_levels_are_subtracted():
    """`g = [img1]`, `g.append(cv2.pyrDown(g[i]))`, then `g[i] - cv2.pyrUp(g[i + 1])`: the levels of a list of uint8
    images wrap around as the images do; a list given a float level, or lists added (concatenated), are not."""
    wraps = """
        def blend_multiband(img1, img2, mask, levels=4):
            g = [img1]
            for i in range(levels - 1):
                g.append(cv2.pyrDown(g[i]))
            return [g[i] - cv2.pyrUp(g[i + 1]) for i in range(levels - 1)]
        """
    assert "uint8 arithmetic wraps around" in one(wraps, api={"blend_multiband"})
    floats = wraps.replace("g = [img1]", "g = [img1.astype(np.float32)]")
    assert "uint8 arithmetic wraps around" not in one(floats, api={"blend_multiband"})
    appended_float = wraps.replace("g.append(cv2.pyrDown(g[i]))", "g.append(cv2.pyrDown(g[i]) / 1.0)")
    assert "uint8 arithmetic wraps around" not in one(appended_float, api={"blend_multiband"})
    concatenated = """
        def blend_multiband(img1, img2, mask, levels=4):
            both = [img1] + [img2]
            return both
        """
    assert "uint8 arithmetic wraps around" not in one(concatenated, api={"blend_multiband"})


def test_opencv_arithmetic_on_uint8_images_is_read_as_saturating():
    """`cv2.subtract(level, up)` on uint8 levels saturates (the negative half of a band is lost); NumPy's wraps;
    either given a dtype, or on converted images, is not read."""
    source = """
        def blend_multiband(img1, img2, mask, levels=4):
            g = [img1.copy()]
            for i in range(levels - 1):
                g.append(cv2.pyrDown(g[-1]))
            return [{sub}(g[i], cv2.pyrUp(g[i + 1]){extra}) for i in range(levels - 1)]
        """
    assert "uint8 arithmetic saturates" in one(source.format(sub="cv2.subtract", extra=""), api={"blend_multiband"})
    assert "uint8 arithmetic wraps around" in one(source.format(sub="np.subtract", extra=""), api={"blend_multiband"})
    typed = source.format(sub="cv2.subtract", extra=", dtype=cv2.CV_32F")
    assert not {"uint8 arithmetic saturates", "uint8 arithmetic wraps around"} & one(typed, api={"blend_multiband"})
    floats = source.format(sub="cv2.subtract", extra="").replace("img1.copy()", "img1.astype(np.float32)")
    assert "uint8 arithmetic saturates" not in one(floats, api={"blend_multiband"})


def test_a_helper_giving_back_its_images_dtype_keeps_a_uint8_image_uint8():
    """`left - _shift_right(right, d)` where the module's `_shift_right` fills `np.empty_like(image)` from its image:
    the difference is of two uint8 images; a helper converting its image first gives floats."""
    source = """
        def _shift_right(image, d):
            if d == 0:
                return image
            out = np.empty_like(image)
            out[:, d:] = image[:, :-d]
            return out

        def block_matching(left, right, max_disparity=64, block_size=9):
            for d in range(max_disparity + 1):
                diff = left - _shift_right(right, d)
            return diff
        """
    assert "uint8 arithmetic wraps around" in one(source, api={"block_matching"})
    converting = source.replace("out = np.empty_like(image)", "out = np.empty_like(image, dtype=np.float32)")
    assert "uint8 arithmetic wraps around" not in one(converting, api={"block_matching"})


def test_a_fundamental_matrix_given_to_recover_pose_beside_the_essential_one_made_is_told_to_give_that():
    """`E = essential_from_fundamental(F, K, K)` made, then `cv2.recoverPose(F, ...)`: the sentence points at the E
    the code made, not at making one; code that makes none is told to make it."""
    source = """
        def two_view_reconstruction(img1, img2, K):
            F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, 1.0, 0.999)
            E = essential_from_fundamental(F, K, K)
            _, R, t, m = cv2.recoverPose(F, pts1, pts2, K)
            return R, t
        """
    [finding] = [f for f in read_source(textwrap.dedent(source), {"two_view_reconstruction"}).findings[
        "two_view_reconstruction"] if f.mistake == "a fundamental matrix given where the essential matrix belongs"]
    assert "makes the essential matrix `E` at line 4: give cv2.recoverPose `E` instead of `F`" in finding.sentence
    without = source.replace("            E = essential_from_fundamental(F, K, K)\n", "")
    [finding] = [f for f in read_source(textwrap.dedent(without), {"two_view_reconstruction"}).findings[
        "two_view_reconstruction"] if f.mistake == "a fundamental matrix given where the essential matrix belongs"]
    assert "make E = K2^T F K1 first" in finding.sentence


def test_the_last_turns_value_read_after_a_loop_is_told_to_read_the_name_the_best_was_refined_into():
    """The best mask kept in `best_inliers`, taken on after the loop as `mask` and refined by refits, and the loop's
    last `inliers` returned (07e lab08/06): "use `best_inliers`" would return the unrefined mask beside a refit H."""
    source = textwrap.dedent("""
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            best_count, best_inliers = 0, None
            for _ in range(200):
                H = fit(src, dst)
                inliers = errors(H, src, dst) < threshold
                if inliers.sum() > best_count:
                    best_count = inliers.sum()
                    best_inliers = inliers
            mask = best_inliers
            H = fit(src[mask], dst[mask])
            for _ in range(5):
                mask = errors(H, src, dst) < threshold
                H = fit(src[mask], dst[mask])
            return H, inliers
        """)
    reading = read_source(source, frozenset())
    [finding] = [f for found in reading.findings.values() for f in found]
    assert "use `mask`, which your code makes from it after the loop, there" in finding.sentence, finding.sentence


def test_whole_numbers_read_from_another_integer_array_are_not_truncated():
    """A DP's backtrack writes into an integer map what it reads from an integer table (`disp[:, x - 1] =
    back[x][rows, disp[:, x]]`, blind set 08a lab12/05): nothing is cut, no finding; a ratio written is one."""
    source = """
        def backtrack(M, W, H, D):
            back = np.zeros((W, H, D), dtype=np.int64)
            rows = np.arange(H)
            disp = np.zeros((H, W), dtype=np.int64)
            disp[:, W - 1] = np.argmin(M[W - 1], axis=1)
            for x in range(W - 1, 0, -1):
                disp[:, x - 1] = {value}
            return disp
        """
    truncated = "an integer array: the values written into it are truncated"
    assert truncated not in one(source.format(value="back[x][rows, disp[:, x]]"))
    assert truncated not in one(source.format(value="back[x][rows, disp[:, x]] + 1"))
    assert truncated in one(source.format(value="M[x][rows, disp[:, x]]"))
    assert truncated in one(source.format(value="back[x][rows, disp[:, x]] * s"))
