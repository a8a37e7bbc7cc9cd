"""The labs' lists of things to check, each item held to the student's code (issue 35; the mechanism:
tests/test_checklists.py).

For each list converted to :func:`autograder.engine.claims.checklist`: code doing an item is not told
it, and the realistic mistake is still told the item it gets wrong. The code is read, never run: the
trial's code is the source given here (``code_of`` and ``functions_read`` stand in for a sandbox's).
"""

from __future__ import annotations

import textwrap

import pytest

from autograder.engine import claims, hints
from autograder.engine.hints import Hint, read_code


@pytest.fixture
def speak(monkeypatch):
    """``speak(hint_or_text, source, function)``: what a failed check says for that code, as
    :func:`autograder.engine.runner.run_check` has it said (a Hint's own reading, then every registered
    sentence in the result replaced)."""
    def said(hint, source: str, function: str) -> str:
        code = read_code(textwrap.dedent(source))
        assert code.functions, "the source given does not parse"
        for module in (hints, claims):
            monkeypatch.setattr(module, "code_of", lambda t: code)
            monkeypatch.setattr(module, "functions_read", lambda t: (function,))
        trial = object()
        text = hint.said(trial) if isinstance(hint, Hint) else hint
        return claims.said(trial, text)
    return said


# ------------------------------------------------------------------ lab 8
from autograder.labs import lab08  # noqa: E402

DLT_EACH = """
    def homography_dlt(src, dst):
        Ts, Td = hartley(src), hartley(dst)
        Hn = solve(Ts, Td, src, dst)
        return np.linalg.inv(Td) @ Hn @ Ts

    def hartley(pts):
        c = pts.mean(axis=0)
        s = np.sqrt(2) / np.linalg.norm(pts - c, axis=1).mean()
        return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])
    """


def test_lab08_dlt_normalisation_each_set_and_undone(speak):
    said = speak(lab08.DLT_NORMALISE_HINT, DLT_EACH, "homography_dlt")
    assert said == "your code already normalises the points (a mean and sqrt(2)); the error is elsewhere."
    uncentred = DLT_EACH.replace("np.linalg.norm(pts - c, axis=1)", "np.linalg.norm(pts, axis=1)").replace(
        "-s * c[0]", "0").replace("-s * c[1]", "0")
    assert speak(lab08.DLT_NORMALISE_HINT, uncentred, "homography_dlt").endswith(
        "the error is elsewhere: look at the transforms themselves (a centroid subtracted, a scale making the mean "
        "distance sqrt(2)).")
    one_transform = DLT_EACH.replace("Ts, Td = hartley(src), hartley(dst)", "Ts = Td = hartley(src)")
    said = speak(lab08.DLT_NORMALISE_HINT, one_transform, "homography_dlt")
    assert "check that each set has its own transform." in said and "undone" not in said
    in_a_loop = DLT_EACH.replace("Ts, Td = hartley(src), hartley(dst)", "Ts, Td = [hartley(p) for p in (src, dst)]")
    assert "check that" not in speak(lab08.DLT_NORMALISE_HINT, in_a_loop, "homography_dlt")


RATIO_KEPT = """
    def match_features(img1, img2, ratio=0.75, method="sift"):
        kp1, kp2, knn = detect(img1, img2)
        good = [m for m, n in knn if m.distance < ratio * n.distance]
        pts1 = np.float32([kp1[m.queryIdx].pt for m in good])
        pts2 = np.float32([kp2[m.trainIdx].pt for m in good])
        return pts1, pts2
    """


def test_lab08_ratio_ignored(speak):
    overwritten = RATIO_KEPT.replace("kp1, kp2, knn", "ratio = 0.75\n        kp1, kp2, knn")
    said = speak(lab08.RATIO_IGNORED_HINT, overwritten, "match_features")
    assert said.endswith("check that ratio is not overwritten.")
    left_aside = RATIO_KEPT.replace("for m in good", "for m, _ in knn")
    said = speak(lab08.RATIO_IGNORED_HINT, left_aside, "match_features")
    assert said.endswith("check that the matches returned are the ones that pass it.")
    appended = RATIO_KEPT.replace("good = [m for m, n in knn if m.distance < ratio * n.distance]",
                                  "good = []\n        for m, n in knn:\n            if m.distance < ratio * n.distance:\n"
                                  "                good.append(m)")
    assert "check that" not in speak(lab08.RATIO_IGNORED_HINT, appended, "match_features")


def test_lab08_ratio_test_applied_which_points(speak):
    said = speak(lab08.RATIO_HINT, RATIO_KEPT, "match_features")
    assert "check that" not in said and said.endswith("look at which points are returned, and in which order")
    second = RATIO_KEPT.replace("good = [m for m, n", "good = [n for m, n")
    said = speak(lab08.RATIO_HINT, second, "match_features")
    assert said.endswith("check that the match kept is the closer of the two neighbours (m of each m, n pair)")
    swapped = RATIO_KEPT.replace("kp1[m.queryIdx]", "kp1[m.trainIdx]")
    assert speak(lab08.RATIO_HINT, swapped, "match_features").endswith(
        "check that pts1 come from img1's keypoints by queryIdx")


RANSAC_ROOT = """
    def homography_ransac(src, dst, threshold=3.0, seed=0):
        err = np.sqrt(((transfer(H, src) - dst) ** 2).sum(axis=1))
        return H, err < threshold
    """


def test_lab08_squared_threshold(speak):
    said = speak(lab08.SQUARED_HINT, RANSAC_ROOT.replace("err < threshold", "err < threshold ** 2"),
                 "homography_ransac")
    assert said.endswith("check that the threshold itself is not squared")
    said = speak(lab08.SQUARED_HINT, RANSAC_ROOT.replace("err < threshold", "err ** 2 < threshold"),
                 "homography_ransac")
    assert said.endswith("check that the root's value is not squared again before the comparison")
    assert "check that" not in speak(lab08.SQUARED_HINT, RANSAC_ROOT, "homography_ransac")


BLEND = """
    def blend_multiband(img1, img2, mask, levels=4):
        m = mask.astype(np.float32)
        masks = [m]
        for _ in range(levels - 1):
            masks.append(cv2.pyrDown(masks[-1]))
        bands1, bands2 = laplacian(img1, levels), laplacian(img2, levels)
        out = [w * a + (1 - w) * b for w, a, b in zip(masks, bands1, bands2)]
        return collapse(out)
    """


def test_lab08_mask_pyramid(speak):
    assert "check that" not in speak(lab08.MASK_PYRAMID_HINT, BLEND, "blend_multiband")
    one_blur = BLEND.replace("m = mask.astype(np.float32)",
                             "m = cv2.GaussianBlur(mask.astype(np.float32), (5, 5), 1)").replace(
        "cv2.pyrDown(masks[-1])", "masks[-1][::2, ::2]")
    said = speak(lab08.MASK_PYRAMID_HINT, one_blur, "blend_multiband")
    assert "check that every level of the mask is blurred before it is halved" in said
    assert "float" not in said and "each band is weighted" not in said


def test_lab08_stitch_many_reference_frame(speak):
    chained = """
        def stitch_many(images):
            Hs = [np.eye(3)]
            for a, b in zip(images, images[1:]):
                Hs.append(Hs[-1] @ pairwise(a, b))
            return [cv2.warpPerspective(img, H, size) for img, H in zip(images, Hs)]
        """
    said = speak(lab08.REFERENCE_FRAME_CHECKLIST, chained, "stitch_many")
    assert said == "look at the shift applied to every image"   # homographies composed: their direction is chosen
    shifted = chained.replace("return [", "T = np.array([[1, 0, 40], [0, 1, 20], [0, 0, 1]])\n            return [")
    assert speak(lab08.REFERENCE_FRAME_CHECKLIST, shifted, "stitch_many") == (
        "your code gives one image no warp and warps the others")
    as_given = shifted.replace("Hs.append(Hs[-1] @ pairwise(a, b))", "Hs.append(pairwise(a, b))")
    assert speak(lab08.REFERENCE_FRAME_CHECKLIST, as_given, "stitch_many") == (
        "look at the direction of each homography used (from image k to the reference frame, not the reverse)")
    unreferenced = chained.replace("[np.eye(3)]", "[pairwise(images[0], images[1])]")
    assert speak(lab08.REFERENCE_FRAME_CHECKLIST, unreferenced, "stitch_many") == (
        "check that one image is the reference frame (only shifted: its homography is the identity)")


# ------------------------------------------------------------------ lab 9
from autograder.labs import lab09  # noqa: E402

APERTURE = """
    def simulate_aperture(X, f, aperture, n_rays, seed=0):
        rng = np.random.default_rng(seed)
        offsets = rng.uniform(-aperture, aperture, size=(n_rays, 2))
        return trace(X, f, offsets)
    """


def test_lab09_seed(speak):
    said = speak(lab09.SEED_HINT, APERTURE, "simulate_aperture")
    assert said == "your code calls np.random.default_rng."
    fixed = APERTURE.replace("default_rng(seed)", "default_rng(0)")
    assert speak(lab09.SEED_HINT, fixed, "simulate_aperture").endswith("check that it is given seed.")
    global_draws = APERTURE.replace("rng.uniform(", "np.random.uniform(")
    assert speak(lab09.SEED_HINT, global_draws, "simulate_aperture").endswith(
        "check that every random number is drawn from that generator (none from np.random's own functions).")


CALIBRATE = """
    def calibrate(images, pattern_size, square_size):
        cols, rows = pattern_size
        objp = np.zeros((cols * rows, 3), np.float32)
        objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
        obj_points, img_points = [], []
        for image in images:
            found, corners = cv2.findChessboardCorners(image, pattern_size)
            if found:
                obj_points.append(objp)
                img_points.append(corners)
        return cv2.calibrateCamera(obj_points, img_points, size, None, None)
    """


def test_lab09_object_points(speak):
    said = speak(lab09.OBJECT_POINTS_HINT, CALIBRATE, "calibrate")
    assert "check that" not in said and "look at" not in said and said.endswith(".T.reshape(-1, 2).")
    unscaled = CALIBRATE.replace(".reshape(-1, 2) * square_size", ".reshape(-1, 2)")
    assert speak(lab09.OBJECT_POINTS_HINT, unscaled, "calibrate").endswith(": look at the square size.")
    unfound = CALIBRATE.replace("            if found:\n", "            if True:\n")
    assert speak(lab09.OBJECT_POINTS_HINT, unfound, "calibrate").endswith(
        ": look at the views kept (those whose corners were found).")
    rows_first = CALIBRATE.replace("cols, rows = pattern_size", "rows, cols = pattern_size")
    assert speak(lab09.OBJECT_POINTS_HINT, rows_first, "calibrate").endswith(
        "check that pattern_size is read as (cols, rows).")
    every_view = CALIBRATE.replace("                obj_points.append(objp)\n", "").replace(
        "            if found:", "            obj_points.append(objp)\n            if found:")
    assert speak(lab09.OBJECT_POINTS_HINT, every_view, "calibrate").endswith(
        "check that each view's object points go with that view's corners.")


DISC = """
    def simulate_aperture(X, f, aperture, n_rays, seed=0):
        rng = np.random.default_rng(seed)
        r = aperture * np.sqrt(rng.random(n_rays))
        a = 2 * np.pi * rng.random(n_rays)
        return trace(X, f, np.stack([r * np.cos(a), r * np.sin(a)], axis=1))
    """


def test_lab09_uniform_disc(speak):
    assert "check that" not in speak(lab09.UNIFORM_DISC_HINT, DISC, "simulate_aperture")
    half_turn = DISC.replace("2 * np.pi * rng.random", "np.pi * rng.random")
    assert speak(lab09.UNIFORM_DISC_HINT, half_turn, "simulate_aperture").endswith(
        "check that the angle is uniform in [0, 2 pi)")
    root_outside = DISC.replace("aperture * np.sqrt(rng.random(n_rays))", "np.sqrt(aperture * rng.random(n_rays))")
    said = speak(lab09.UNIFORM_DISC_HINT, root_outside, "simulate_aperture")
    assert said.endswith("check that the radius is aperture * sqrt(u)") and "angle" not in said


DRAW = """
    def draw_points(image, pts, radius=3, color=(0, 0, 255)):
        out = image.copy()
        for x, y in pts:
            cv2.circle(out, (int(round(x)), int(round(y))), radius, color, -1)
        return out
    """


def test_lab09_copy(speak):
    assert "check that" not in speak(lab09.COPY_HINT, DRAW, "draw_points")
    on_image = DRAW.replace("cv2.circle(out,", "cv2.circle(image,")
    assert speak(lab09.COPY_HINT, on_image, "draw_points").endswith(
        "check that each point is drawn on the copy, not on `image`")
    rebound = on_image.replace("out = image.copy()", "image = image.copy()").replace("return out", "return image")
    said = speak(lab09.COPY_HINT, rebound, "draw_points")
    assert "check that" not in said
    not_returned = DRAW.replace("return out", "return image")
    assert speak(lab09.COPY_HINT, not_returned, "draw_points").endswith("check that the copy is returned")


# ------------------------------------------------------------------ lab 10
from autograder.labs import lab10  # noqa: E402

DECOMPOSE = """
    def decompose_camera_matrix(P):
        if np.linalg.det(P[:, :3]) < 0:
            P = -P
        K, R = scipy.linalg.rq(P[:, :3])
        D = np.diag(np.sign(np.diag(K)))
        K = K @ D
        R = D @ R
        t = np.linalg.solve(K, P[:, 3])
        return K / K[2, 2], R, t
    """


def test_lab10_sign_fix(speak):
    said = speak(lab10.SIGN_FIX, DECOMPOSE, "decompose_camera_matrix")
    assert said.endswith("your code already negates a matrix when a determinant is negative.")
    k_only = DECOMPOSE.replace("        R = D @ R\n", "")
    assert speak(lab10.SIGN_FIX, k_only, "decompose_camera_matrix").endswith(
        "check that flipping K's columns flips the same rows of R")


def test_lab10_signs_returned(speak):
    said = speak(lab10.SIGNS_HINT, DECOMPOSE, "decompose_camera_matrix")
    assert "check that" not in said
    unreturned = DECOMPOSE.replace("K = K @ D\n        R = D @ R", "K2 = K @ D\n        R2 = D @ R").replace(
        "return K / K[2, 2], R, t", "return K, R, t")
    assert speak(lab10.SIGNS_HINT, unreturned, "decompose_camera_matrix").endswith(
        "check that the fixed K and R are the ones returned")
    columns = DECOMPOSE.replace("R = D @ R", "R = R @ D")
    assert speak(lab10.SIGNS_HINT, columns, "decompose_camera_matrix").endswith(
        "check that it flips the same columns of K and rows of R (K D and D R with one D)")


DLT10 = """
    def camera_matrix_dlt(points3d, points2d):
        rows = []
        for (X, Y, Z), (u, v) in zip(points3d, points2d):
            rows.append([X, Y, Z, 1, 0, 0, 0, 0, -u * X, -u * Y, -u * Z, -u])
            rows.append([0, 0, 0, 0, X, Y, Z, 1, -v * X, -v * Y, -v * Z, -v])
        return np.linalg.svd(np.array(rows))[2][-1].reshape(3, 4)
    """


def test_lab10_fixed_p23(speak):
    assert "check that" not in speak(lab10.FIXED_P23_HINT, DLT10, "camera_matrix_dlt")
    eleven = DLT10.replace(", -u])", "])").replace(", -v])", "])")
    assert speak(lab10.FIXED_P23_HINT, eleven, "camera_matrix_dlt").endswith(
        "check that A has 12 columns (P[2, 3] is an unknown too).")
    column = DLT10.replace("[2][-1]", "[2][:, -1]")
    assert speak(lab10.FIXED_P23_HINT, column, "camera_matrix_dlt").endswith("check that p is the last row of Vt.")


POSE = """
    def estimate_pose(image, pattern_size, square_size, K, dist=None):
        found, corners = cv2.findChessboardCorners(image, pattern_size)
        ok, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)
        projected, _ = cv2.projectPoints(objp, rvec, tvec, K, dist)
        return rvec.ravel(), tvec.ravel(), projected.reshape(-1, 2)
    """


def test_lab10_project_points(speak):
    said = speak(lab10.PROJECT_POINTS_HINT, POSE, "estimate_pose")
    assert said == "your code calls cv2.projectPoints."
    swapped = POSE.replace("(objp, rvec, tvec, K, dist)", "(objp, tvec, rvec, K, dist)")
    assert speak(lab10.PROJECT_POINTS_HINT, swapped, "estimate_pose").endswith(
        "check that it is given the object points, rvec, tvec, K and dist of this pose, in that order.")
    corners = POSE.replace("projected.reshape(-1, 2)", "corners.reshape(-1, 2)")
    assert speak(lab10.PROJECT_POINTS_HINT, corners, "estimate_pose").endswith(
        "check that its output is what is returned.")


def test_lab10_rq(speak):
    said = speak(lab10.RQ_HINT, DECOMPOSE, "decompose_camera_matrix")
    assert said == " (your code decomposes P[:, :3])"
    undivided = DECOMPOSE.replace("return K / K[2, 2], R, t", "return K, R, t")
    assert speak(lab10.RQ_HINT, undivided, "decompose_camera_matrix") == (
        " (your code decomposes P[:, :3]: look at K divided by K[2, 2])")
    unsigned = DECOMPOSE.replace("np.diag(np.sign(np.diag(K)))", "np.eye(3)")
    assert speak(lab10.RQ_HINT, unsigned, "decompose_camera_matrix") == (
        " (your code decomposes P[:, :3]: look at the signs fixed after it)")
    reversed_names = DECOMPOSE.replace("K, R = scipy.linalg.rq", "R, K = scipy.linalg.rq")
    said = speak(lab10.RQ_HINT, reversed_names, "decompose_camera_matrix")
    assert said.endswith("check that the upper-triangular factor becomes K (P[:, :3] = K R))")
    plain_qr = DECOMPOSE.replace("scipy.linalg.rq(P[:, :3])", "np.linalg.qr(P[:, :3])")
    assert speak(lab10.RQ_HINT, plain_qr, "decompose_camera_matrix").endswith(
        "check that the rows and columns are reversed to turn a QR into an RQ)")


# ------------------------------------------------------------------ lab 11
from autograder.labs import lab11  # noqa: E402

LINES11 = """
    def epipolar_lines(F, pts1):
        lines = np.column_stack([pts1, np.ones(len(pts1))]) @ F.T
        return lines / np.linalg.norm(lines[:, :2], axis=1, keepdims=True)
    """


def test_lab11_line_scale(speak):
    said = speak(lab11.LINE_SCALE_HINT, LINES11, "epipolar_lines")
    assert said == " (your code computes a norm)."
    l1 = LINES11.replace("np.linalg.norm(lines[:, :2], axis=1, keepdims=True)",
                         "np.sqrt(np.abs(lines[:, 0]) + np.abs(lines[:, 1]))[:, None]")
    said = speak(lab11.LINE_SCALE_HINT, l1, "epipolar_lines")
    assert said.endswith("check that each line is divided by sqrt(a^2 + b^2) of its own first two entries).")
    kept = LINES11.replace("return lines / np.linalg.norm(lines[:, :2], axis=1, keepdims=True)",
                           "unit = lines / np.hypot(lines[:, 0], lines[:, 1])[:, None]\n        return lines")
    assert speak(lab11.LINE_SCALE_HINT, kept, "epipolar_lines").endswith(
        "check that the divided lines are returned).")
    by_hand = LINES11.replace("np.linalg.norm(lines[:, :2], axis=1, keepdims=True)",
                              "np.sqrt(a * a + b * b)")
    assert "check that" not in speak(lab11.LINE_SCALE_HINT, by_hand, "epipolar_lines")


EIGHT = """
    def fundamental_8point(pts1, pts2):
        T1, T2 = hartley(pts1), hartley(pts2)
        x1, x2 = apply(T1, pts1), apply(T2, pts2)
        A = np.column_stack([x2[:, 0] * x1[:, 0], x2[:, 0] * x1[:, 1], x2[:, 0], x2[:, 1] * x1[:, 0],
                             x2[:, 1] * x1[:, 1], x2[:, 1], x1[:, 0], x1[:, 1], np.ones(len(x1))])
        Fn = np.linalg.svd(A)[2][-1].reshape(3, 3)
        U, s, Vt = np.linalg.svd(Fn)
        s[2] = 0
        Fn = U @ np.diag(s) @ Vt
        return T2.T @ Fn @ T1

    def hartley(pts):
        c = pts.mean(axis=0)
        s = np.sqrt(2) / np.linalg.norm(pts - c, axis=1).mean()
        return np.array([[s, 0, s * c[0]], [0, s, s * c[1]], [0, 0, 1]])
    """


def test_lab11_fundamental_steps(speak):
    said = speak(lab11.FUNDAMENTAL_STEPS_HINT, EIGHT, "fundamental_8point")
    assert said == "your code already calls np.linalg.svd in 2 places (A f = 0 and rank 2?)."
    one_transform = EIGHT.replace("T1, T2 = hartley(pts1), hartley(pts2)", "T1 = T2 = hartley(pts1)").replace(
        "x1, x2 = apply(T1, pts1), apply(T2, pts2)", "x1, x2 = T1 @ pts1, T2 @ pts2")
    assert speak(lab11.FUNDAMENTAL_STEPS_HINT, one_transform, "fundamental_8point").endswith(
        "(A f = 0 and rank 2?): look at which points each transform is built from")
    uncentred = EIGHT.replace("np.linalg.norm(pts - c, axis=1)", "np.linalg.norm(pts, axis=1)").replace(
        "s * c[0]", "0").replace("s * c[1]", "0")
    assert speak(lab11.FUNDAMENTAL_STEPS_HINT, uncentred, "fundamental_8point").endswith(
        "(A f = 0 and rank 2?): look at the normalising transforms (T = [[s, 0, -s cx], [0, s, -s cy], [0, 0, 1]]: "
        "the centroid subtracted, then scaled so the mean distance is sqrt(2))")
    not_undone = EIGHT.replace("return T2.T @ Fn @ T1", "return Fn")
    assert speak(lab11.FUNDAMENTAL_STEPS_HINT, not_undone, "fundamental_8point").endswith(
        "check that the normalisation is undone: F = T2^T Fn T1")
    raw = not_undone.replace("T1, T2 = hartley(pts1), hartley(pts2)", "T1 = T2 = np.eye(3)").replace(
        "np.sqrt(2)", "1.0")
    assert "check that" not in speak(lab11.FUNDAMENTAL_STEPS_HINT, raw, "fundamental_8point")


def test_lab11_nine_unknowns(speak):
    assert "check that" not in speak(lab11.FIXED_F22_HINT, EIGHT, "fundamental_8point")
    eight_columns = EIGHT.replace(", np.ones(len(x1))])", "])")
    assert speak(lab11.FIXED_F22_HINT, eight_columns, "fundamental_8point").endswith(
        "check that A has 9 columns (F[2, 2] is an unknown too).")


def test_lab11_rank2_rebuilt_and_returned(speak):
    said = speak(lab11.RANK2_HINT, EIGHT, "fundamental_8point")
    assert said == "Your code sets a singular value to 0."
    first = EIGHT.replace("s[2] = 0", "s[0] = 0")
    assert speak(lab11.RANK2_HINT, first, "fundamental_8point") == (
        "Your code sets a singular value to 0: look at which singular value is set to 0 (the smallest, the last of "
        "np.linalg.svd's).")
    unreturned = EIGHT.replace("Fn = U @ np.diag(s) @ Vt\n        return T2.T @ Fn @ T1",
                               "F2 = U @ np.diag(s) @ Vt\n        return T2.T @ Fn @ T1")
    assert speak(lab11.RANK2_HINT, unreturned, "fundamental_8point").endswith(
        "check that this F is the one returned.")


RECONSTRUCTION = """
    def two_view_reconstruction(img1, img2, K):
        pts1, pts2 = match(img1, img2)
        F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, 1.0, 0.999)
        E = K.T @ F @ K
        _, R, t, _ = cv2.recoverPose(E, pts1, pts2, K)
        P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
        P2 = K @ np.hstack([R, t])
        X = cv2.triangulatePoints(P1, P2, pts1.T, pts2.T)
        return F, pts1, pts2, (X[:3] / X[3]).T

    def match(img1, img2):
        kp1, kp2, knn = detect(img1, img2)
        good = [m for m, n in knn if m.distance < 0.75 * n.distance]
        return points(kp1, kp2, good)
    """


def test_lab11_robust_f(speak):
    said = speak(lab11.ROBUST_F_HINT, RECONSTRUCTION, "two_view_reconstruction")
    assert said == "your code already estimates F robustly."   # the points come from a helper not read
    query_twice = RECONSTRUCTION.replace("return points(kp1, kp2, good)",
                                         "return (np.float32([kp1[m.queryIdx].pt for m in good]), "
                                         "np.float32([kp2[m.queryIdx].pt for m in good]))")
    assert speak(lab11.ROBUST_F_HINT, query_twice, "two_view_reconstruction").endswith(
        "look at the points it is given: pts1 from image 1 (queryIdx), pts2 from image 2 (trainIdx)")
    both = query_twice.replace("kp2[m.queryIdx]", "kp2[m.trainIdx]")
    assert speak(lab11.ROBUST_F_HINT, both, "two_view_reconstruction") == said
    loose = RECONSTRUCTION.replace("cv2.FM_RANSAC, 1.0", "cv2.FM_RANSAC, 10.0")
    assert speak(lab11.ROBUST_F_HINT, loose, "two_view_reconstruction").endswith(
        "check that its threshold is about 1 px")
    unfiltered = RECONSTRUCTION.replace("if m.distance < 0.75 * n.distance", "")
    assert speak(lab11.ROBUST_F_HINT, unfiltered, "two_view_reconstruction").endswith(
        "check that the matches it is given pass Lowe's ratio test")


def test_lab11_in_front(speak):
    said = speak(lab11.IN_FRONT_HINT, RECONSTRUCTION, "two_view_reconstruction")
    assert "check that" not in said and "look at which points are triangulated" in said
    no_k = RECONSTRUCTION.replace("P1 = K @ np.hstack", "P1 = np.hstack").replace("P2 = K @ np.hstack", "P2 = np.hstack")
    said = speak(lab11.IN_FRONT_HINT, no_k, "two_view_reconstruction")
    assert said.endswith("check that the cameras the points are triangulated with match the coordinates given to them "
                         "(P = K [R | t] on pixels, [R | t] on normalised coordinates)")
    undivided = RECONSTRUCTION.replace("(X[:3] / X[3]).T", "X[:3].T")
    assert speak(lab11.IN_FRONT_HINT, undivided, "two_view_reconstruction").endswith(
        "check that the points are divided by w")


# ------------------------------------------------------------------ lab 12
from autograder.labs import lab12  # noqa: E402

TRIANGULATE = """
    def triangulate(P1, P2, pts1, pts2):
        out = []
        for (x1, y1), (x2, y2) in zip(pts1, pts2):
            A = np.array([x1 * P1[2] - P1[0], y1 * P1[2] - P1[1], x2 * P2[2] - P2[0], y2 * P2[2] - P2[1]])
            X = np.linalg.svd(A)[2][-1]
            out.append(X[:3] / X[3])
        return np.array(out)
    """


def test_lab12_triangulation_rows(speak):
    said = speak(lab12.TRIANGULATION_ROWS_HINT, TRIANGULATE, "triangulate")
    assert "check that" not in said and "look at" not in said and said.endswith("your code already calls np.linalg.svd.")
    first_vector = TRIANGULATE.replace("np.linalg.svd(A)[2][-1]", "np.linalg.svd(A)[2][0]")
    assert speak(lab12.TRIANGULATION_ROWS_HINT, first_vector, "triangulate").endswith(
        "look at which singular vector is kept (the last row of Vt of each point's own 4x4 system)")
    undivided = TRIANGULATE.replace("X[:3] / X[3]", "X[:3]")
    assert speak(lab12.TRIANGULATION_ROWS_HINT, undivided, "triangulate").endswith(
        "check that the solution is divided by its fourth coordinate")
    columns = TRIANGULATE.replace("x1 * P1[2] - P1[0], y1 * P1[2] - P1[1], x2 * P2[2] - P2[0], y2 * P2[2] - P2[1]",
                                  "x1 * P1[:, 2] - P1[:, 0], y1 * P1[:, 2] - P1[:, 1], x2 * P2[:, 2] - P2[:, 0], "
                                  "y2 * P2[:, 2] - P2[:, 1]")
    assert speak(lab12.TRIANGULATION_ROWS_HINT, columns, "triangulate").endswith(
        "check that each view's rows are made of its own P's rows and its own point's x and y")


RECTIFY = """
    def rectify(img_l, img_r, K1, K2, R, T):
        C2 = -R.T @ T.ravel()
        e1 = C2 / np.linalg.norm(C2)
        e2 = np.cross([0, 0, 1], e1)
        e2 /= np.linalg.norm(e2)
        e3 = np.cross(e1, e2)
        R_rect = np.vstack([e1, e2, e3])
        K_new = (K1 + K2) / 2
        H1 = K_new @ R_rect @ np.linalg.inv(K1)
        H2 = K_new @ R_rect @ R.T @ np.linalg.inv(K2)
        return warp(img_l, H1), warp(img_r, H2), H1, H2
    """


def test_lab12_rectify_recipe(speak):
    said = speak(lab12.CENTRE_HINT, RECTIFY, "rectify")
    assert "check that" not in said and "look at" not in said and said.endswith("the difference is inside one of them")
    inverse_first = RECTIFY.replace("K_new @ R_rect @ np.linalg.inv(K1)", "np.linalg.inv(K1) @ R_rect @ K_new").replace(
        "K_new @ R_rect @ R.T @ np.linalg.inv(K2)", "np.linalg.inv(K2) @ R.T @ R_rect @ K_new")
    assert speak(lab12.CENTRE_HINT, inverse_first, "rectify").endswith("look at the order of the products in each map "
                                                                      "(H1 = K_new R_rect K1^-1, H2 = K_new R_rect R K2^-1)")
    columns = RECTIFY.replace("np.vstack([e1, e2, e3])", "np.column_stack([e1, e2, e3])")
    assert speak(lab12.CENTRE_HINT, columns, "rectify").endswith(
        "check that the new axes are the rows of the rectifying rotation (np.vstack([e1, e2, e3]), not its columns)")
    from_t = RECTIFY.replace("C2 = -R.T @ T.ravel()", "C2 = T.ravel()")
    said = speak(lab12.CENTRE_HINT, from_t, "rectify")
    assert said.startswith("compare your steps with the recipe: check that camera 2's centre is -R^T T, not T")
    assert "and that" not in said


STEREO_RECTIFY = """
    def rectify(img_l, img_r, K1, K2, R, T):
        h, w = img_l.shape[:2]
        R1, R2, P1, P2 = cv2.stereoRectify(K1, None, K2, None, (w, h), R, T)[:4]
        H1 = P1[:, :3] @ R1 @ np.linalg.inv(K1)
        H2 = P2[:, :3] @ R2 @ np.linalg.inv(K2)
        return warp(img_l, H1), warp(img_r, H2), H1, H2
    """


def test_lab12_stereo_rectify_given_as_is(speak):
    said = speak(lab12.GIVEN_AS_IS_HINT, STEREO_RECTIFY, "rectify")
    assert said == "your code gives cv2.stereoRectify K1, K2, R and T as they came, as it takes them."
    warped = STEREO_RECTIFY.replace("return warp(img_l, H1), warp(img_r, H2), H1, H2",
                                    "rect_l = cv2.warpPerspective(img_l, H1, (w, h))\n"
                                    "        rect_r = cv2.warpPerspective(img_r, H2, (w, h))\n"
                                    "        return rect_l, rect_r, H1, H2")
    assert speak(lab12.GIVEN_AS_IS_HINT, warped, "rectify") == said   # each image its own map, those maps returned
    # the blind set's 29d 12/03: the images warped right, the rotations returned
    rotations = warped.replace("return rect_l, rect_r, H1, H2", "return rect_l, rect_r, R1, R2")
    assert speak(lab12.GIVEN_AS_IS_HINT, rotations, "rectify").endswith(
        "as it takes them; look at which matrices are returned as H1 and H2 (the maps the images are warped with)")
    one_map = warped.replace("cv2.warpPerspective(img_r, H2, (w, h))", "cv2.warpPerspective(img_r, H1, (w, h))")
    assert "as it takes them; look at which image each map is applied to (img_l by H1, img_r by H2)" in speak(
        lab12.GIVEN_AS_IS_HINT, one_map, "rectify")
    rows_first = STEREO_RECTIFY.replace("(w, h)", "img_l.shape[:2]")
    assert speak(lab12.GIVEN_AS_IS_HINT, rows_first, "rectify").endswith(
        "check that the image size it is given is (width, height)")
    out_of_order = STEREO_RECTIFY.replace("R1, R2, P1, P2 =", "R1, P1, R2, P2 =")
    assert speak(lab12.GIVEN_AS_IS_HINT, out_of_order, "rectify").endswith(
        "check that R1 and P1 go to the left image, R2 and P2 to the right (it returns R1, R2, P1, P2 in that order)")


DP = """
    def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
        L, R = left.astype(np.float64), right.astype(np.float64)
        cost = block_costs(L, R, max_disparity, block_size)
        return scanlines(cost, 0.01 if smoothness is None else smoothness)
    """


def test_lab12_dp_cost_scale(speak):
    said = speak(lab12.COST_SCALE_HINT, DP, "dp_stereo")
    assert "check that" not in said and "the default penalty is what is too weak" in said
    unconverted = DP.replace("L, R = left.astype(np.float64), right.astype(np.float64)",
                             "L, R = left, right\n        scale = np.zeros(3, dtype=float)")
    assert speak(lab12.COST_SCALE_HINT, unconverted, "dp_stereo").endswith(
        "check that the data cost is computed on the converted images")


STRUCTURED = """
    def depth_from_structured_light(images, f, baseline):
        bits = np.asarray(images) > 127
        binary = bits.copy()
        for i in range(1, len(bits)):
            binary[i] = binary[i - 1] ^ bits[i]
        k = sum(b.astype(int) << (len(bits) - 1 - i) for i, b in enumerate(binary))
        width = images.shape[2]
        column = (k + 0.5) * width / 2 ** len(bits) - 0.5
        u = np.arange(width)[None, :]
        return f * baseline / (u - column)
    """


def test_lab12_structured_light_recipe(speak):
    said = speak(lab12.STRUCTURED_LIGHT_RECIPE, STRUCTURED, "depth_from_structured_light")
    # bits read most significant first and each XOR with the previous binary bit: only the undecoded pixels
    assert said == "look at the pixels left undecoded (black in every image: depth 0)"
    marked = STRUCTURED.replace("return f * baseline / (u - column)",
                                "return np.where(bits.any(axis=0), f * baseline / (u - column), 0)")
    assert speak(lab12.STRUCTURED_LIGHT_RECIPE, marked, "depth_from_structured_light") == ""
    gray_bits = marked.replace("binary[i] = binary[i - 1] ^ bits[i]", "binary[i] = bits[i - 1] ^ bits[i]")
    assert speak(lab12.STRUCTURED_LIGHT_RECIPE, gray_bits, "depth_from_structured_light") == (
        "look at what each XOR is taken with (the previous binary bit, not the previous Gray bit)")
    reversed_bits = marked.replace("<< (len(bits) - 1 - i) for i, b in enumerate(binary)",
                                   "<< i for i in range(len(binary)) for b in [binary[i]]")
    assert speak(lab12.STRUCTURED_LIGHT_RECIPE, reversed_bits, "depth_from_structured_light") == (
        "look at the order the bits are read in (the first image is the most significant bit)")
    plain = STRUCTURED.replace("binary[i] = binary[i - 1] ^ bits[i]", "pass")
    assert speak(lab12.STRUCTURED_LIGHT_RECIPE, plain, "depth_from_structured_light") == (
        "check that the Gray code is converted to binary (most significant bit first: b0 = g0, b_i = b_(i-1) XOR g_i)")
    # the triangulation done by their own depth_from_disparity is done: not asked of the code
    delegated = marked.replace("f * baseline / (u - column)", "depth_from_disparity(u - column, f, baseline)") \
        .replace("(k + 0.5) * width / 2 ** len(bits) - 0.5", "(k + 0.5) * width * 2.0 ** -len(bits) - 0.5")
    assert "Z = f b" not in speak(lab12.STRUCTURED_LIGHT_RECIPE, delegated, "depth_from_structured_light")
    stripe_edge = STRUCTURED.replace("(k + 0.5) * width / 2 ** len(bits) - 0.5", "k * width / 2 ** len(bits)")
    assert speak(lab12.STRUCTURED_LIGHT_RECIPE, stripe_edge, "depth_from_structured_light") == (
        "check that the projector column is (k + 0.5) * width / 2**n_bits - 0.5")


SSD = """
    def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
        L, R = left.astype(np.float64), right.astype(np.float64)
        costs = np.full((max_disparity + 1,) + L.shape, np.inf)
        for d in range(max_disparity + 1):
            diff = (L[:, d:] - R[:, :L.shape[1] - d]) ** 2
            costs[d][:, d:] = box(diff, block_size)
        return np.argmin(costs, axis=0).astype(np.float64)
    """


def test_lab12_lowest_cost(speak):
    said = speak(lab12.LOWEST_COST_HINT, SSD, "block_matching")
    assert said == "your code already keeps the lowest cost (argmin, or argmax of the cost negated)."
    zero_border = SSD.replace("np.full((max_disparity + 1,) + L.shape, np.inf)", "np.zeros((max_disparity + 1,) + L.shape)")
    assert speak(lab12.LOWEST_COST_HINT, zero_border, "block_matching").endswith(
        "look at the columns near the left border (no block at x - d there)")
    in_uint8 = SSD.replace("left.astype(np.float64), right.astype(np.float64)", "left, right")
    assert speak(lab12.LOWEST_COST_HINT, in_uint8, "block_matching").endswith(
        "check that a block's cost is the sum or mean of the squared differences over the block, computed in floats")


DEPTH = """
    def depth_from_disparity(disparity, f, baseline):
        d = np.asarray(disparity, dtype=np.float64)
        return np.divide(f * baseline, d, out=np.zeros_like(d), where=d > 0)
    """


def test_lab12_guarded_division(speak):
    said = speak(lab12.GUARDED_DIVISION_HINT, DEPTH, "depth_from_disparity")
    assert said == "your code already passes where= to np.divide."
    unreturned = DEPTH.replace("return np.divide(f * baseline, d, out=np.zeros_like(d), where=d > 0)",
                               "np.divide(f * baseline, d, out=np.zeros_like(d), where=d > 0)\n        return d")
    assert speak(lab12.GUARDED_DIVISION_HINT, unreturned, "depth_from_disparity").endswith("look at the array returned")
    by_baseline = DEPTH.replace("np.divide(f * baseline, d,", "np.divide(f * d, baseline,")
    assert speak(lab12.GUARDED_DIVISION_HINT, by_baseline, "depth_from_disparity").endswith(
        "look at the value divided by (the disparity given, d = x_l - x_r)")
    nonzero = DEPTH.replace("where=d > 0", "where=d != 0")
    assert speak(lab12.GUARDED_DIVISION_HINT, nonzero, "depth_from_disparity").endswith(
        "check that its condition is d > 0 (NaN > 0 is False)")
    empty = DEPTH.replace("out=np.zeros_like(d)", "out=np.empty_like(d)")
    assert speak(lab12.GUARDED_DIVISION_HINT, empty, "depth_from_disparity").endswith(
        "check that out starts as zeros")


SIMULATE = """
    def simulate_structured_light(depth, f, baseline, n_bits):
        h, w = depth.shape
        u = np.arange(w)[None, :]
        with np.errstate(divide="ignore"):
            column = np.round(u - f * baseline / depth)
        lit = (depth > 0) & (column >= 0) & (column < w)
        return patterns(column, lit, n_bits)
    """


def test_lab12_projector_model(speak):
    said = speak(lab12.PROJECTOR_MODEL, SIMULATE, "simulate_structured_light")
    assert said == ""   # every item done, and no bit read in an order this reading follows
    coded = SIMULATE.replace("return patterns(column, lit, n_bits)",
                             "k = (column * 2 ** n_bits) // w\n        g = k ^ (k >> 1)\n"
                             "        return np.stack([((g >> (n_bits - 1 - i)) & 1) * 255 * lit for i in range(n_bits)])")
    assert speak(lab12.PROJECTOR_MODEL, coded, "simulate_structured_light") == ""
    # the blind set's 29d 12/07: the column's own Gray code
    of_column = coded.replace("g = k ^ (k >> 1)", "g = column ^ (column >> 1)")
    assert speak(lab12.PROJECTOR_MODEL, of_column, "simulate_structured_light") == (
        "check that the Gray code shown is that of the column's stripe k = (column * 2**n_bits) // width, not of the "
        "column itself")
    lowest_first = coded.replace("(g >> (n_bits - 1 - i))", "(g >> i)")
    assert speak(lab12.PROJECTOR_MODEL, lowest_first, "simulate_structured_light") == (
        "look at which bit of the Gray code each image shows (the most significant first)")
    one_end = SIMULATE.replace(" & (column >= 0)", "")
    assert speak(lab12.PROJECTOR_MODEL, one_end, "simulate_structured_light") == (
        "check that a pixel whose column is off the projector (below 0, or at its width and past) is black")


GREY_VIEWS = """
    def calibrate(images, pattern_size, square_size):
        obj_points, img_points = [], []
        for image in images:
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
            found, corners = cv2.findChessboardCorners(grey, pattern_size)
            if found:
                corners = cv2.cornerSubPix(grey, corners, (11, 11), (-1, -1), criteria)
                obj_points.append(board(pattern_size, square_size))
                img_points.append(corners)
        return cv2.calibrateCamera(obj_points, img_points, grey.shape[::-1], None, None)
    """


def test_lab09_grey_for_opencv(speak):
    said = speak(lab09.GREY_FOR_OPENCV, GREY_VIEWS, "calibrate")
    assert said == "Your code calls cv2.cvtColor."   # both items done: no pointer restating them
    raw = GREY_VIEWS.replace("cv2.cornerSubPix(grey,", "cv2.cornerSubPix(image,")
    assert speak(lab09.GREY_FOR_OPENCV, raw, "calibrate").endswith(
        "check that every call that needs one channel gets the converted view")
    shape = GREY_VIEWS.replace("grey.shape[::-1]", "image.shape[::-1]")
    assert speak(lab09.GREY_FOR_OPENCV, shape, "calibrate").endswith(
        "check that the image size passed is (width, height), not the shape of a 3-channel array")


def test_lab11_inliers_kept(speak):
    masked = RECONSTRUCTION.replace("E = K.T @ F @ K", "pts1, pts2 = pts1[mask.ravel() == 1], pts2[mask.ravel() == 1]\n"
                                    "        E = K.T @ F @ K")
    said = speak(lab11.INLIERS_HINT, masked, "two_view_reconstruction")
    assert said == "your code already keeps the inliers of a RANSAC estimator."
    reversed_points = masked.replace("cv2.findFundamentalMat(pts1, pts2,", "cv2.findFundamentalMat(pts2, pts1,")
    assert speak(lab11.INLIERS_HINT, reversed_points, "two_view_reconstruction").endswith(
        "look at the order of the points given and returned (pts1 in image 1, pts2 in image 2)")
    # (calling the estimator is not keeping its inliers: code that never indexes its points by the mask,
    # or indexes them by the 0/1 uint8 mask itself -- points 0 and 1 over and over -- is told to keep them)
    assert speak(lab11.INLIERS_HINT, RECONSTRUCTION, "two_view_reconstruction") == lab11.INLIERS_HINT.text
    fancy = RECONSTRUCTION.replace("E = K.T @ F @ K", "pts1, pts2 = pts1[mask.ravel()], pts2[mask.ravel()]\n"
                                   "        E = K.T @ F @ K")
    assert speak(lab11.INLIERS_HINT, fancy, "two_view_reconstruction") == lab11.INLIERS_HINT.text


# ------------------------------------------------------------------ lab 12: fixed hints held to the code
def test_lab12_cross_order(speak):
    said = speak(lab12.CROSS_ORDER_HINT, RECTIFY.replace("np.cross([0, 0, 1], e1)", "np.cross(z, e1)"), "rectify")
    assert said == ""   # e2 = z x e1 and e3 = e1 x e2 written: the measured message alone
    reversed_order = RECTIFY.replace("np.cross([0, 0, 1], e1)", "np.cross(e1, z)")
    assert speak(lab12.CROSS_ORDER_HINT, reversed_order, "rectify") == lab12.CROSS_ORDER_HINT.text
    assert speak(lab12.CROSS_ORDER_HINT, STEREO_RECTIFY, "rectify") == ""   # no cross product of its own


def test_lab12_third_axis_order(speak):
    """The third axis alone reversed (a reflection): the hint tells e3 = e1 x e2 only, never the e2 the
    code already writes, and nothing where e3 is crossed in order."""
    said = speak(lab12.THIRD_AXIS_HINT, RECTIFY.replace("np.cross(e1, e2)", "np.cross(e2, e1)"), "rectify")
    assert said == lab12.THIRD_AXIS_HINT.text and "e2 =" not in said
    assert speak(lab12.THIRD_AXIS_HINT, RECTIFY, "rectify") == ""


def test_lab12_towards_camera_2(speak):
    assert speak(lab12.TOWARDS_CENTRE_HINT, RECTIFY, "rectify") == ""   # -R^T T written: the measured message alone
    from_t = RECTIFY.replace("C2 = -R.T @ T.ravel()", "C2 = T.ravel()")
    assert speak(lab12.TOWARDS_CENTRE_HINT, from_t, "rectify") == lab12.TOWARDS_CENTRE_HINT.text


def test_lab12_colour_warped_as_it_is(speak):
    warped = STEREO_RECTIFY.replace("return warp(img_l, H1), warp(img_r, H2), H1, H2",
                                    "return cv2.warpPerspective(img_l, H1, (w, h)), "
                                    "cv2.warpPerspective(img_r, H2, (w, h)), H1, H2")
    assert speak(lab12.COLOUR_HINT, warped, "rectify") == ""
    grey = warped.replace("cv2.warpPerspective(img_l,", "cv2.warpPerspective(cv2.cvtColor(img_l, cv2.COLOR_BGR2GRAY),")
    assert speak(lab12.COLOUR_HINT, grey, "rectify") == lab12.COLOUR_HINT.text
    channel = warped.replace("cv2.warpPerspective(img_l,", "cv2.warpPerspective(img_l[..., 0],")
    assert speak(lab12.COLOUR_HINT, channel, "rectify") == lab12.COLOUR_HINT.text


def test_lab12_no_partner_columns(speak):
    said = speak(lab12.NO_PARTNER_HINT, SSD, "block_matching")   # the costs start at np.inf
    assert "give those disparities an infinite cost" not in said and "look at which entries it marks for each d (the columns x < d, in every row)" in said
    zero_border = SSD.replace("np.full((max_disparity + 1,) + L.shape, np.inf)", "np.zeros((max_disparity + 1,) + L.shape)")
    assert speak(lab12.NO_PARTNER_HINT, zero_border, "block_matching").endswith(
        "give those disparities an infinite cost (or leave the pixel invalid)")


PATTERNS = """
    def gray_code_patterns(width, n_bits):
        k = (np.arange(width) * 2 ** n_bits) // width
        g = k ^ (k >> 1)
        return (((g[None, :] >> np.arange(n_bits - 1, -1, -1)[:, None]) & 1) * 255).astype(np.uint8)
    """


def test_lab12_stripe_formula(speak):
    said = speak(lab12.STRIPE_FORMULA_HINT, PATTERNS, "gray_code_patterns")
    assert "//" not in said and said.startswith(" (your code computes k with an integer division")
    in_floats = PATTERNS.replace("(np.arange(width) * 2 ** n_bits) // width",
                                 "np.floor(np.arange(width) * 2 ** n_bits / width).astype(int)")
    assert speak(lab12.STRIPE_FORMULA_HINT, in_floats, "gray_code_patterns") == lab12.STRIPE_FORMULA_HINT.text


def test_lab12_gray_code_formula(speak):
    said = speak(lab12.GRAY_CODE_HINT, PATTERNS, "gray_code_patterns")
    assert "k XOR (k >> 1), bit i" not in said and "your code computes k XOR (k >> 1)" in said
    binary = PATTERNS.replace("g = k ^ (k >> 1)", "g = k")
    assert speak(lab12.GRAY_CODE_HINT, binary, "gray_code_patterns") == lab12.GRAY_CODE_HINT.text


def test_lab12_zero_default_read():
    from autograder.engine.hints import read_code

    def reads(source):
        code = read_code(textwrap.dedent(source))
        return lab12.ZERO_DEFAULT.holds(code.reachable(["dp_stereo"]))
    base = """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            if smoothness is None:
                smoothness = 60.0
            return scanlines(left, right, smoothness)
        """
    assert not reads(base)
    assert reads(base.replace("60.0", "0.0"))   # the blind set 29d's 12/05
    assert reads(base.replace("if smoothness is None:\n                smoothness = 60.0",
                              "smoothness = 0 if smoothness is None else smoothness"))
    assert not reads(base.replace("if smoothness is None:\n                smoothness = 60.0",
                                  "smoothness = 40.0 if smoothness is None else smoothness"))


def test_lab10_colour_pose(speak):
    assert speak(lab10.COLOUR_POSE_HINT, POSE, "estimate_pose") == lab10.COLOUR_POSE_HINT.text
    grey = POSE.replace("cv2.findChessboardCorners(image,",
                        "cv2.findChessboardCorners(cv2.cvtColor(image, cv2.COLOR_BGR2GRAY),")
    said = speak(lab10.COLOUR_POSE_HINT, grey, "estimate_pose")
    assert "convert" not in said and said.startswith("estimate_pose takes either; your code calls cv2.cvtColor")


UNDISTORT = """
    def undistort_image(image, K, dist):
        return cv2.undistort(image, K, dist)
    """


def test_lab10_undistort_channels(speak):
    assert speak(lab10.UNDISTORT_CHANNELS_HINT, UNDISTORT, "undistort_image") == ""   # the BGR image as it is
    grey = UNDISTORT.replace("cv2.undistort(image,", "cv2.undistort(cv2.cvtColor(image, cv2.COLOR_BGR2GRAY),")
    assert speak(lab10.UNDISTORT_CHANNELS_HINT, grey, "undistort_image") == lab10.UNDISTORT_CHANNELS_HINT.text


STEREO_BM = """
    def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
        grey_l, grey_r = grey(left), grey(right)
        n = 16 * int(np.ceil((max_disparity + 1) / 16))
        matcher = cv2.StereoBM_create(numDisparities=n, blockSize=block_size)
        d = matcher.compute(grey_l.astype(np.uint8), grey_r.astype(np.uint8)).astype(np.float64) / 16.0
        d[d <= 0] = 0
        return d
    """


def test_lab12_opencv_matcher(speak):
    said = speak(lab12.OPENCV_MATCHER_HINT, STEREO_BM, "block_matching")
    assert said == "your code uses OpenCV's block matcher (cv2.StereoBM or StereoSGBM), which compares the blocks and " \
                   "keeps the lowest cost itself."
    # the blind set 29d's 12/04: compute(right, left)
    swapped = STEREO_BM.replace("matcher.compute(grey_l.astype(np.uint8), grey_r.astype(np.uint8))",
                                "matcher.compute(grey_r.astype(np.uint8), grey_l.astype(np.uint8))")
    assert speak(lab12.OPENCV_MATCHER_HINT, swapped, "block_matching").endswith(
        "itself: check that it is given the left image first (matcher.compute(left, right))")
    fixed_point = STEREO_BM.replace(" / 16.0", "")
    assert speak(lab12.OPENCV_MATCHER_HINT, fixed_point, "block_matching").endswith(
        "itself: check that its int16 answer is divided by 16 (disparities in 1/16 px)")
    unmarked = STEREO_BM.replace("        d[d <= 0] = 0\n", "")
    assert speak(lab12.OPENCV_MATCHER_HINT, unmarked, "block_matching").endswith(
        "itself: look at the pixels where no match is found (-16 in its answer)")


def test_lab11_fundamental_steps_of_code_that_solves_by_least_squares(speak):
    # (30f lab11/04: F[2, 2] = 1 solved by lstsq, rank 2 and Hartley done: told neither of those two)
    lstsq = EIGHT.replace("Fn = np.linalg.svd(A)[2][-1].reshape(3, 3)",
                          "f = np.linalg.lstsq(A[:, :8], -A[:, 8], rcond=None)[0]\n"
                          "        Fn = np.append(f, 1.0).reshape(3, 3)")
    said = speak(lab11.FUNDAMENTAL_STEPS_HINT, lstsq, "fundamental_8point")
    assert said == "check that f is the last row of Vt from np.linalg.svd(A), reshaped to 3 x 3 (A f = 0 for all 9 entries)"
    # code doing none of the steps is told all three
    bare = """
    def fundamental_8point(pts1, pts2):
        A = np.column_stack([pts2[:, :1] * pts1, pts2[:, :1], pts2[:, 1:] * pts1, pts2[:, 1:], pts1,
                             np.ones(len(pts1))])
        return np.linalg.lstsq(A[:, :8], -A[:, 8], rcond=None)[0]
    """
    said = speak(lab11.FUNDAMENTAL_STEPS_HINT, bare, "fundamental_8point")
    assert "rank 2 is enforced" in said and "normalised first (Hartley)" in said and "last row of Vt" in said
