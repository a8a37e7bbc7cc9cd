"""Hints and diagnoses of labs 8 and 12 held to the student's code (issue 35; see tests/test_claims.py).

For each guarded sentence: a student whose code already does what it asks (or never does what it
claims) is not told it; the realistic mistake it names still is. The code is read, never run.
"""

from __future__ import annotations

import textwrap

import pytest

from autograder.engine import claims
from autograder.engine.hints import read_code
from autograder.labs import lab08
from fixtures import lab08 as truth08


def told(hint, source: str, function: str) -> bool:
    """Whether ``hint`` keeps its text for ``function`` of the module ``source``."""
    return not hint.contradicts(read_code(textwrap.dedent(source)), [function])


G = claims.GUARDED
# (hint, student function, code that already does what it asks, the realistic mistake)
CASES = {
    "lab08 division missing": (G[truth08.DIVISION_MISSING], "transform_points", """
        def transform_points(H, pts):
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ H.T
            w = q[:, 2:]
            out = q[:, :2] / w
            return q[:, :2]
        """, """
        def transform_points(H, pts):
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ H.T
            return q[:, :2]
        """),
    "lab08 H transposed": (G[truth08.H_TRANSPOSED], "transform_points", """
        def transform_points(H, pts):
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ H.T
            return q[:, :2] / q[:, 2:]
        """, """
        def transform_points(H, pts):
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ H
            return q[:, :2] / q[:, 2:]
        """),
    "lab08 divided by x": (G[truth08.DIVIDED_BY_X], "transform_points", """
        def transform_points(H, pts):
            q = H @ np.vstack([pts.T, np.ones(len(pts))])
            return (q[:2] / q[-1]).T
        """, """
        def transform_points(H, pts):
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ H.T
            return q[:, :2] / q[:, :1]
        """),
    "lab08 first point's w": (G[truth08.FIRST_W], "transform_points", """
        def transform_points(H, pts):
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ H.T
            return q[:, :2] / q[:, 2:3]
        """, """
        def transform_points(H, pts):
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ H.T
            return q[:, :2] / q[0, 2]
        """),
    "lab08 warp inverted": (G[truth08.WARP_INVERTED], "apply_homography", """
        def apply_homography(image, H, dsize=None):
            return cv2.warpPerspective(image, H.T, dsize or image.shape[1::-1])
        """, """
        def apply_homography(image, H, dsize=None):
            return cv2.warpPerspective(image, H, dsize or image.shape[1::-1], flags=cv2.WARP_INVERSE_MAP)
        """),
    "lab08 warpAffine": (G[truth08.WARP_AFFINE], "apply_homography", """
        def apply_homography(image, H, dsize=None):
            return cv2.warpPerspective(image, H, dsize or image.shape[1::-1])
        """, """
        def apply_homography(image, H, dsize=None):
            return cv2.warpAffine(image, H[:2], dsize or image.shape[1::-1])
        """),
    "lab08 zero matrix": (lab08.NULL_VECTOR_HINT, "homography_dlt", """
        def homography_dlt(src, dst):
            A = build(src, dst)
            h = np.linalg.svd(A)[2][-1]
            return np.zeros((3, 3))
        """, """
        def homography_dlt(src, dst):
            A = build(src, dst)
            return np.linalg.lstsq(A, np.zeros(len(A)), rcond=None)[0].reshape(3, 3)
        """),
    "lab08 reduced SVD": (G[lab08.REDUCED_SVD], "homography_dlt", """
        def homography_dlt(src, dst):
            _, _, Vt = np.linalg.svd(build(src, dst))
            return Vt[-2].reshape(3, 3)
        """, """
        def homography_dlt(src, dst):
            _, _, Vt = np.linalg.svd(build(src, dst), full_matrices=False)
            return Vt[-1].reshape(3, 3)
        """),
    "lab08 normalisation not undone": (G[lab08.NOT_UNDONE], "homography_dlt", """
        def homography_dlt(src, dst):
            Ts, Td = hartley(src), hartley(dst)
            Hn = solve(Ts, Td, src, dst)
            return np.linalg.inv(Ts) @ Hn @ Td
        """, """
        def homography_dlt(src, dst):
            Ts, Td = hartley(src), hartley(dst)
            return solve(Ts, Td, src, dst)
        """),
    "lab08 x and y swapped": (lab08.XY_HINT, "match_features", """
        def match_features(img1, img2):
            kp1, kp2, matches = detect_and_match(img1, img2)
            pts1 = np.float32([kp1[m.queryIdx].pt[::-1] for m in matches])
            pts2 = np.float32([kp2[m.trainIdx].pt[::-1] for m in matches])
            return pts1, pts2
        """, """
        def match_features(img1, img2):
            kp1, kp2, matches = detect_and_match(img1, img2)
            pts1 = np.float32([(kp1[m.queryIdx].y, kp1[m.queryIdx].x) for m in matches])
            pts2 = np.float32([(kp2[m.trainIdx].y, kp2[m.trainIdx].x) for m in matches])
            return pts1, pts2
        """),
    "lab08 ratio ignored": (lab08.RATIO_IGNORED_HINT, "match_features", """
        def match_features(img1, img2, ratio=0.75):
            good = [m for m, n in knn(img1, img2) if m.distance < ratio * n.distance]
            return points(knn(img1, img2))
        """, """
        def match_features(img1, img2, ratio=0.75):
            good = [m for m, n in knn(img1, img2) if m.distance < 0.75 * n.distance]
            return points(good)
        """),
    "lab08 ratio reversed": (lab08.RATIO_REVERSED_HINT, "match_features", """
        def match_features(img1, img2, ratio=0.75):
            good = [n for m, n in knn(img1, img2) if m.distance < ratio * n.distance]
            return points(good)
        """, """
        def match_features(img1, img2, ratio=0.75):
            good = [m for m, n in knn(img1, img2) if m.distance > ratio * n.distance]
            return points(good)
        """),
    "lab08 squared error": (lab08.SQUARED_HINT, "homography_ransac", """
        def homography_ransac(src, dst, threshold=3.0, seed=0):
            err = np.linalg.norm(transfer(H, src) - dst, axis=1)
            return H, err < threshold ** 2
        """, """
        def homography_ransac(src, dst, threshold=3.0, seed=0):
            err = ((transfer(H, src) - dst) ** 2).sum(axis=1)
            return H, err < threshold
        """),
    "lab08 img2 warped with the inverse": (G[lab08.INVERSE_SECOND_WARP], "stitch", """
        def stitch(img1, img2):
            H = np.linalg.inv(pairwise(img2, img1))
            return compose(img1, img2, H)
        """, """
        def stitch(img1, img2):
            H = pairwise(img1, img2)
            return compose(img1, img2, H)
        """),
    "lab08 shift on the wrong side": (G[lab08.SHIFT_ON_THE_RIGHT], "stitch", """
        def stitch(img1, img2):
            H, T = pairwise(img2, img1), shift(img1, img2)
            return cv2.warpPerspective(img2, T @ H, size)
        """, """
        def stitch(img1, img2):
            H, T = pairwise(img2, img1), shift(img1, img2)
            return cv2.warpPerspective(img2, H @ T, size)
        """),
    "lab08 shift not applied": (G[lab08.SHIFT_NOT_APPLIED], "stitch", """
        def stitch(img1, img2):
            H, T = pairwise(img2, img1), shift(img1, img2)
            return cv2.warpPerspective(img2, T @ H, size)
        """, """
        def stitch(img1, img2):
            H, T = pairwise(img2, img1), shift(img1, img2)
            return cv2.warpPerspective(img2, H, size)
        """),
    "lab08 bands not added": (lab08.ADD_BANDS_HINT, "blend_multiband", """
        def blend_multiband(img1, img2, mask, levels=4):
            out = bands[-1]
            for band in bands[-2::-1]:
                up = cv2.pyrUp(out, dstsize=band.shape[1::-1]) + band
            return out
        """, """
        def blend_multiband(img1, img2, mask, levels=4):
            out = bands[-1]
            for band in bands[-2::-1]:
                out = cv2.pyrUp(out, dstsize=band.shape[1::-1])
            return out
        """),
    "lab08 exact collapse": (lab08.EXACT_COLLAPSE_HINT, "blend_multiband", """
        def blend_multiband(img1, img2, mask, levels=4):
            down = cv2.pyrDown(img1)
            return cv2.pyrUp(down)
        """, """
        def blend_multiband(img1, img2, mask, levels=4):
            return cv2.resize(cv2.resize(img1, None, fx=0.5, fy=0.5), img1.shape[1::-1])
        """),
    "lab08 mask weights img2": (lab08.MASK_SIDE_HINT, "blend_multiband", """
        def blend_multiband(img1, img2, mask, levels=4):
            img1, img2 = img2, img1
            return mask * img1 + (1 - mask) * img2
        """, """
        def blend_multiband(img1, img2, mask, levels=4):
            return mask * img2 + (1 - mask) * img1
        """),
    # (30f lab08/03: a generator made again in the loop draws one sample over and over, and was told its
    # inlier test -- exactly |H src - dst| < threshold -- counts otherwise)
    "lab08 RANSAC miscounted": (G[lab08.MISCOUNTED], "homography_ransac", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            for _ in range(500):
                rng = np.random.default_rng(seed)
                H = homography_dlt(src[rng.choice(len(src), 4)], dst[rng.choice(len(src), 4)])
                inliers = np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold
            return H, inliers
        """, """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            rng = np.random.default_rng(seed)
            for _ in range(500):
                H = homography_dlt(src[rng.choice(len(src), 4)], dst[rng.choice(len(src), 4)])
                inliers = np.abs(transform_points(H, src) - dst).sum(axis=1) < threshold
            return H, inliers
        """),
    "lab08 pyrUp without dstsize": (G[lab08.ODD_SIZES_LOST], "blend_multiband", """
        def blend_multiband(img1, img2, mask, levels=4):
            return cv2.pyrUp(cv2.pyrDown(img1), dstsize=img1.shape[1::-1])
        """, """
        def blend_multiband(img1, img2, mask, levels=4):
            return cv2.pyrUp(cv2.pyrDown(img1))
        """),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_student_whose_code_does_it_is_not_told_the_realistic_mistake_is(name):
    hint, function, does_it, mistake = CASES[name]
    assert hint.asks is not None
    assert not told(hint, does_it, function), f"{name}: told to do what the code does"
    assert told(hint, mistake, function), f"{name}: the mistake is no longer told"


@pytest.mark.parametrize("loop, written, told_it", [
    ("range(len(images) - 1)", "for i in range(len(images) - 1):\n        warp(images[i])", True),
    ("range(len(images) - 1)", "for i in range(len(images)):\n        warp(images[i])", False),
    ("range(1, len(images))", "for i in range(1, len(imgs)):\n        warp(imgs[i])", True),
])
def test_the_off_by_one_loop_is_named_only_to_a_loop_written_that_way(loop, written, told_it):
    from autograder.engine.hints import Hint, expr
    # the Hint lab08.fail_if_left_out builds for the image left out
    every = Hint(f"loop over every image, not {loop}", asks=~expr(loop.replace("images", "_")), instead="")
    assert told(every, f"def stitch_many(images):\n    {written}\n", "stitch_many") is told_it


# ------------------------------------------------------------------ lab 12
from autograder.labs import lab12  # noqa: E402
from fixtures import lab12 as truth12  # noqa: E402

CASES12 = {
    "lab12 NCC divided by a variance": (G[truth12.NCC_BY_VARIANCE], "block_matching", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            Lc, Rc = L - L.mean(), R - R.mean()
            return (Lc * Rc).sum() / np.sqrt((Lc ** 2).sum() * (Rc ** 2).sum())
        """, """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            Lc, Rc = L - L.mean(), R - R.mean()
            return (Lc * Rc).mean() / (Rc.std() ** 2)
        """),
    "lab12 third coordinate for the fourth": (G[truth12.THIRD_NOT_FOURTH], "triangulate", """
        def triangulate(P1, P2, pts1, pts2):
            X = np.linalg.svd(rows(P1, P2, pts1, pts2))[2][:, -1]
            return X[:, :3] / X[:, 3:]
        """, """
        def triangulate(P1, P2, pts1, pts2):
            X = np.linalg.svd(rows(P1, P2, pts1, pts2))[2][:, -1]
            return X[:, :3] / X[:, 2:3]
        """),
    "lab12 Gray code decoded as binary": (G[truth12.PLAIN_BINARY_DECODE], "depth_from_structured_light", """
        def depth_from_structured_light(images, f, baseline):
            bits = np.array(images) > 127
            for i in range(1, len(bits)):
                bits[i] ^= bits[i - 1]
            return depth(bits, f, baseline)
        """, """
        def depth_from_structured_light(images, f, baseline):
            bits = np.array(images) > 127
            return depth(bits, f, baseline)
        """),
    "lab12 OpenCV's fixed point": (lab12.FIXED_POINT_HINT, "block_matching", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            raw = cv2.StereoBM_create(max_disparity, block_size).compute(left, right)
            disparity = raw / 16.0
            return raw.astype(np.float64)
        """, """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return cv2.StereoBM_create(max_disparity, block_size).compute(left, right).astype(np.float64)
        """),
    "lab12 H1 and H2 inverted": (lab12.INVERT_HINT, "rectify", """
        def rectify(img_l, img_r, K1, K2, R, T):
            H1 = np.linalg.inv(K_new @ R1 @ np.linalg.inv(K1))
            return warp(img_l, img_r, H1, H2)
        """, """
        def rectify(img_l, img_r, K1, K2, R, T):
            H1 = K1 @ R1.T @ K_new_inverse   # the map back, rectified -> original
            return warp(img_l, img_r, H1, H2)
        """),
    "lab12 NCC means not subtracted": (lab12.BLOCK_MEANS_HINT, "block_matching", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            Lc = L - cv2.boxFilter(L, -1, (block_size, block_size))
            return ncc(Lc, R)
        """, """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return (L * R).sum() / np.sqrt((L ** 2).sum() * (R ** 2).sum())
        """),
    "lab12 NCC not fully normalised": (lab12.NORMALISE_NCC_HINT, "block_matching", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            Lc, Rc = L - L.mean(), R - R.mean()
            return (Lc * Rc).mean() / (Lc.std() * Rc.std() + 1e-9)
        """, """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            Lc, Rc = L - L.mean(), R - R.mean()
            return (Lc * Rc).sum()
        """),
    "lab12 what cv2.stereoRectify is given": (lab12.GIVEN_AS_IS_HINT, "rectify", """
        def rectify(img_l, img_r, K1, K2, R, T):
            K1 = np.asarray(K1, dtype=np.float64)
            h, w = img_l.shape[:2]
            R1, R2, P1, P2 = cv2.stereoRectify(K1, np.zeros(5), K2, np.zeros(5), (w, h),
                                               np.asarray(R, np.float64), np.asarray(T).reshape(3, 1))[:4]
            return warp(img_l, img_r, P1[:, :3] @ R1 @ np.linalg.inv(K1), P2[:, :3] @ R1 @ np.linalg.inv(K2))
        """, """
        def rectify(img_l, img_r, K1, K2, R, T):
            h, w = img_l.shape[:2]
            R1, R2, P1, P2 = cv2.stereoRectify(K1, np.zeros(5), K2, np.zeros(5), (w, h), R.T, T)[:4]
            return warp(img_l, img_r, P1[:, :3] @ R1 @ np.linalg.inv(K1), P2[:, :3] @ R2 @ np.linalg.inv(K2))
        """),
}


@pytest.mark.parametrize("name", sorted(CASES12))
def test_lab12_a_student_whose_code_does_it_is_not_told_the_realistic_mistake_is(name):
    hint, function, does_it, mistake = CASES12[name]
    assert hint.asks is not None
    assert not told(hint, does_it, function), f"{name}: told to do what the code does"
    assert told(hint, mistake, function), f"{name}: the mistake is no longer told"


def test_the_gray_decoding_is_read_in_the_decoder_not_in_the_pattern_maker():
    # (06j 12/06: a check calling gray_code_patterns to make its images read the XOR written there as the decoder's)
    hint = G[truth12.PLAIN_BINARY_DECODE]
    source = textwrap.dedent("""
        def gray_code_patterns(width, n_bits):
            k = np.arange(width) * 2 ** n_bits // width
            return (((k ^ (k >> 1))[None] >> np.arange(n_bits)[::-1, None]) & 1).astype(np.uint8) * 255
        def depth_from_structured_light(images, f, baseline):
            bits = np.array(images) > 127
            return depth(bits, f, baseline)
        """)
    assert hint.functions == ("depth_from_structured_light",)
    assert not hint.contradicts(read_code(source), hint.functions)
