"""Lab 8's extensions and two realistic mistakes (issue 35: none uncaught).

- ext3: a mask pyramid made by subsampling (slicing, cv2.resize) loses the points of the check
  "coarse levels are weighted by the mask's local mean" and is named only where the code shows it
  (the mistakes table, tests/test_lab08.py); every legitimate pyramid keeps full marks here.
- ext1: ORB's descriptors matched with a float norm cannot be told by the outputs
  (benchmarks/spread_lab08_extensions.py): a 0-point tip read from the code (the advice table),
  withheld from every legitimate matcher here.

The predicates that read the code are tested on snippets; the gradings on whole submissions.
"""

from __future__ import annotations

import textwrap

import pytest

from autograder.engine.hints import read_code
from autograder.labs import lab08
from autograder.labs.mistakes.lab08 import MISTAKES
from autograder.engine.runner import grade
from conftest import advice_given, check_results, graded_case, mutant

MODULE = "lab08_homographies"
GRAIN_CHECK = "coarse levels are weighted by the mask's local mean: a fine-grained mask (levels=5)"
ORB_TIP = "ORB's binary descriptors are matched with the Hamming distance"


def reading(source: str, predicate, function: str = "blend_multiband") -> str:
    return predicate.found(read_code(textwrap.dedent(source)).reachable([function]))


# ------------------------------------------------------------------ reading the mask's pyramid
SLICED = """
    def blend_multiband(img1, img2, mask, levels=4):
        weights = [mask]
        for _ in range(levels - 1):
            weights.append(weights[-1][::2, ::2])
        return combine(img1, img2, weights)
"""
THROUGH_A_HELPER = """
    def halve(x):
        return cv2.resize(x, (x.shape[1] // 2, x.shape[0] // 2), interpolation=cv2.INTER_NEAREST)
    def blend_multiband(img1, img2, m, levels=4):
        gm = [np.float32(m)]
        for i in range(levels - 1):
            gm.append(halve(gm[i]))
        return combine(img1, img2, gm)
"""
PYRDOWN = """
    def pyramid(x, levels):
        out = [x]
        for _ in range(levels - 1):
            out.append(cv2.pyrDown(out[-1]))
        return out
    def blend_multiband(img1, img2, mask, levels=4):
        return combine(pyramid(img1, levels), pyramid(img2, levels), pyramid(mask, levels))
"""
BLUR_THEN_SLICE = """
    def blend_multiband(img1, img2, mask, levels=4):
        w = [mask]
        for _ in range(levels - 1):
            w.append(cv2.GaussianBlur(w[-1], (5, 5), 0)[::2, ::2])
        return combine(img1, img2, w)
"""
IMAGES_SLICED_ONLY = """
    def blend_multiband(img1, img2, mask, levels=4):
        small = img1[::2, ::2]
        return combine(small, img2, cv2.pyrDown(mask))
"""


@pytest.mark.parametrize("source, unsmoothed", [
    (SLICED, True), (THROUGH_A_HELPER, True), (PYRDOWN, False), (BLUR_THEN_SLICE, False),
    (IMAGES_SLICED_ONLY, False),
    ("""
    def blend_multiband(img1, img2, mask, levels=4):
        return [skimage.transform.resize(mask, s) for s in shapes(img1, levels)]
    """, False),   # skimage's resize anti-aliases when it shrinks
    ("""
    from skimage.transform import resize
    def blend_multiband(img1, img2, mask, levels=4):
        return [resize(mask, s, anti_aliasing=False) for s in shapes(img1, levels)]
    """, True),
    ("""
    def blend_multiband(img1, img2, mask, levels=4):
        return [cv2.resize(mask, s, interpolation=cv2.INTER_AREA) for s in shapes(img1, levels)]
    """, False),   # an area mean
    ("""
    def blend_multiband(img1, img2, mask, levels=4):
        m = mask[..., None]
        return m * img1 + (1 - m) * img2
    """, False)])  # no pyramid at all: nothing subsampled (other checks name an alpha blend)
def test_the_mask_read_as_subsampled_without_smoothing_only_where_the_code_does(source, unsmoothed):
    assert bool(reading(source, lab08.UNSMOOTHED_MASK)) == unsmoothed


# ------------------------------------------------------------------ reading the ORB matcher
@pytest.mark.parametrize("source, said", [
    ("""
    def match_features(img1, img2, ratio=0.75, method="sift"):
        \"\"\"ORB's descriptors are compared with the Hamming distance.\"\"\"   # a docstring is no code
        d = cv2.ORB_create() if method == "orb" else cv2.SIFT_create()
        return cv2.BFMatcher(cv2.NORM_L2).knnMatch(d1, d2, k=2)
    """, "cv2.NORM_L2"),
    ("""
    def match_features(img1, img2, ratio=0.75, method="sift"):
        d = cv2.ORB_create() if method == "orb" else cv2.SIFT_create()
        return cv2.BFMatcher().knnMatch(d1, d2, k=2)
    """, "cv2.BFMatcher() without a norm (NORM_L2 by default)"),
    ("""
    def match_features(img1, img2, ratio=0.75, method="sift"):
        d = cv2.ORB_create()
        flann = cv2.FlannBasedMatcher(dict(algorithm=1, trees=5), dict(checks=50))
        return flann.knnMatch(np.float32(d1), np.float32(d2), k=2)
    """, "FLANN's KD-tree index (the L2 norm on float32 copies)"),
    ("""
    def match_features(img1, img2, ratio=0.75, method="sift"):
        d = cv2.ORB_create() if method == "orb" else cv2.SIFT_create()
        norm = cv2.NORM_HAMMING if method == "orb" else cv2.NORM_L2
        return cv2.BFMatcher(norm).knnMatch(d1, d2, k=2)
    """, ""),
    ("""
    def match_features(img1, img2, ratio=0.75, method="sift"):
        d = cv2.ORB_create()
        return cv2.DescriptorMatcher_create("BruteForce-Hamming").knnMatch(d1, d2, k=2)
    """, ""),
    ("""
    def match_features(img1, img2, ratio=0.75, method="sift"):
        d = cv2.ORB_create()
        index = dict(algorithm=6, table_number=6, key_size=12, multi_probe_level=1)
        return cv2.FlannBasedMatcher(index, dict(checks=50)).knnMatch(d1, d2, k=2)
    """, ""),
    ("""
    def match_features(img1, img2, ratio=0.75, method="sift"):
        d = cv2.ORB_create() if method == "orb" else cv2.SIFT_create()
        matcher = cv2.BFMatcher(6) if method == "orb" else cv2.BFMatcher(cv2.NORM_L2)   # 6: NORM_HAMMING
        return matcher.knnMatch(d1, d2, k=2)
    """, ""),
    ("""
    def match_features(img1, img2, ratio=0.75, method="sift"):
        d = cv2.SIFT_create()
        return cv2.BFMatcher(cv2.NORM_L2).knnMatch(d1, d2, k=2)
    """, "")])   # no ORB at all (the method check says so)
def test_the_orb_tip_only_where_the_code_matches_orb_with_a_float_norm(source, said):
    functions = read_code(textwrap.dedent(source)).reachable(["match_features"])
    told = lab08.ORB_CREATED.holds(functions) and not lab08.HAMMING.holds(functions)
    assert (lab08.FLOAT_NORM.found(functions) if told else "") == said


# ------------------------------------------------------------------ gradings
# Each legitimate submission: one ORB matcher and one multi-band blend (graded together).
LEGITIMATE = {
    "crossCheck Hamming; skimage pyramids": """
        def _match(features1, features2, ratio, method="sift"):
            (p1, d1), (p2, d2) = features1, features2
            if d1 is None or d2 is None or len(p2) < 2:
                return np.zeros((0, 2)), np.zeros((0, 2))
            if method == "orb":   # mutual best matches, no ratio test
                found = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(d1, d2)
            else:
                pairs = cv2.BFMatcher().knnMatch(d1, d2, k=2)
                found = [m for m, n in (p for p in pairs if len(p) == 2) if m.distance < ratio * n.distance]
            return (p1[[m.queryIdx for m in found]].reshape(-1, 2), p2[[m.trainIdx for m in found]].reshape(-1, 2))

        def blend_multiband(img1, img2, mask, levels=4):
            from skimage.transform import pyramid_gaussian, resize
            axis = -1 if img1.ndim == 3 else None
            def gaussian(x, channel_axis):
                return list(pyramid_gaussian(x, max_layer=levels - 1, channel_axis=channel_axis, preserve_range=True))
            def laplacian(x):
                g = gaussian(x, axis)
                return [f - resize(c, f.shape, order=1, preserve_range=True) for f, c in zip(g[:-1], g[1:])] + [g[-1]]
            weights = gaussian(np.clip(mask.astype(float), 0, 1), None)
            bands = []
            for a, b, w in zip(laplacian(img1.astype(float)), laplacian(img2.astype(float)), weights):
                w = w[..., None] if a.ndim == 3 else w
                bands.append(w * a + (1 - w) * b)
            out = bands[-1]
            for band in reversed(bands[:-1]):
                out = resize(out, band.shape, order=1, preserve_range=True) + band
            return np.clip(np.round(out), 0, 255).astype(np.uint8)
        """,
    "FLANN LSH, nfeatures=500; GaussianBlur + [::2, ::2] mask, float64": """
        def _detect(image, method="sift"):
            detector = cv2.ORB_create(nfeatures=500) if method == "orb" else cv2.SIFT_create()
            keypoints, descriptors = detector.detectAndCompute(_grey(image), None)
            return np.array([k.pt for k in keypoints], dtype=np.float64).reshape(-1, 2), descriptors

        def _match(features1, features2, ratio, method="sift"):
            (p1, d1), (p2, d2) = features1, features2
            if d1 is None or d2 is None or len(p2) < 2:
                return np.zeros((0, 2)), np.zeros((0, 2))
            if method == "orb":
                index = dict(algorithm=6, table_number=6, key_size=12, multi_probe_level=1)
            else:
                index = dict(algorithm=1, trees=5)
            pairs = cv2.FlannBasedMatcher(index, dict(checks=50)).knnMatch(d1, d2, k=2)
            good = [p[0] for p in pairs if len(p) == 2 and p[0].distance < ratio * p[1].distance]
            return (p1[[m.queryIdx for m in good]].reshape(-1, 2), p2[[m.trainIdx for m in good]].reshape(-1, 2))

        def blend_multiband(img1, img2, mask, levels=4):
            weights = [np.clip(np.float64(mask), 0, 1)]
            for _ in range(levels - 1):
                weights.append(cv2.GaussianBlur(weights[-1], (5, 5), 0)[::2, ::2])
            bands = []
            for a, b, w in zip(_laplacian_pyramid(np.float64(img1), levels),
                               _laplacian_pyramid(np.float64(img2), levels), weights):
                w = w[..., None] if a.ndim == 3 else w
                bands.append(w * a + (1 - w) * b)
            out = bands[-1]
            for band in reversed(bands[:-1]):
                out = cv2.pyrUp(out, dstsize=(band.shape[1], band.shape[0])) + band
            return np.clip(np.round(out), 0, 255).astype(np.uint8)
        """,
    "own Hamming distance (NORM_L2 for SIFT); INTER_AREA mask levels, uint8 truncation": """
        def _match(features1, features2, ratio, method="sift"):
            (p1, d1), (p2, d2) = features1, features2
            if d1 is None or d2 is None or len(p2) < 2:
                return np.zeros((0, 2)), np.zeros((0, 2))
            if method == "orb":   # differing bits, counted by hand
                distance = np.unpackbits(d1[:, None, :] ^ d2[None, :, :], axis=2).sum(axis=2).astype(float)
            else:
                distance = np.linalg.norm(d1[:, None, :].astype(float) - d2[None, :, :], axis=2)
            order = np.argsort(distance, axis=1)[:, :2]
            rows = np.arange(len(d1))
            best, second = distance[rows, order[:, 0]], distance[rows, order[:, 1]]
            keep = best < ratio * second
            return p1[keep].reshape(-1, 2), p2[order[keep, 0]].reshape(-1, 2)

        def blend_multiband(img1, img2, mask, levels=4):
            la = _laplacian_pyramid(np.float32(img1), levels)
            lb = _laplacian_pyramid(np.float32(img2), levels)
            m = np.float32(mask)
            bands = []
            for a, b in zip(la, lb):
                w = cv2.resize(m, (a.shape[1], a.shape[0]), interpolation=cv2.INTER_AREA)
                w = w[..., None] if a.ndim == 3 else w
                bands.append(w * a + (1 - w) * b)
            out = bands[-1]
            for band in reversed(bands[:-1]):
                out = cv2.pyrUp(out, dstsize=(band.shape[1], band.shape[0])) + band
            return np.clip(out, 0, 255).astype(np.uint8)
        """,
}


@pytest.mark.parametrize("name", sorted(LEGITIMATE))
def test_legitimate_extensions_keep_full_marks_and_get_no_orb_tip(name, tmp_path):
    result = grade(mutant(tmp_path, MODULE, LEGITIMATE[name]), ["lab08.ext1", "lab08.ext3"], pictures="none")
    for exercise in ("lab08.ext1", "lab08.ext3"):
        for check in check_results(result, exercise):
            assert check.passed or check.advice, f"{name}: {exercise} {check.name}: {check.message}"
    assert not advice_given(result, "lab08.ext1"), name


def test_the_grain_check_is_the_one_that_fails_the_unsmoothed_mask_pyramid():
    result = graded_case(MODULE, *MISTAKES["mask pyramid by slicing (mask[::2, ::2], no smoothing)"][:2])
    failed = [c for c in check_results(result, "lab08.ext3") if not c.passed]
    assert [c.name for c in failed] == [GRAIN_CHECK]
    assert failed[0].mistake == lab08.MASK_NOT_SMOOTHED


BLURRED_ONCE = """
    def blend_multiband(img1, img2, mask, levels=4):
        smooth = cv2.GaussianBlur(np.float32(mask), (0, 0), 1.0)     # blurred once, at full size
        weights = [smooth[::2 ** k, ::2 ** k] for k in range(levels)]
        bands = []
        for a, b, w in zip(_laplacian_pyramid(np.float32(img1), levels),
                           _laplacian_pyramid(np.float32(img2), levels), weights):
            w = w[..., None] if a.ndim == 3 else w
            bands.append(w * a + (1 - w) * b)
        out = bands[-1]
        for band in reversed(bands[:-1]):
            out = cv2.pyrUp(out, dstsize=(band.shape[1], band.shape[0])) + band
        return np.clip(np.round(out), 0, 255).astype(np.uint8)
"""


@pytest.mark.xdist_group("lab08")
def test_a_mask_the_code_smooths_is_not_called_unsmoothed():
    """The mask blurred once at full size, then sliced: the coarse levels still alias (the check
    fails, 6 % against 5 %), but the code smooths the mask, so no 'without smoothing' is said."""
    result = graded_case(MODULE, "lab08.ext3", BLURRED_ONCE)
    [check] = [c for c in check_results(result, "lab08.ext3") if c.name == GRAIN_CHECK]
    assert not check.passed and not check.mistake
    assert "without smoothing" not in check.message and "looks like" not in check.message
    assert check.hint.startswith("your code smooths the mask") and "one blur at full size" in check.hint


@pytest.mark.xdist_group("lab08")
def test_a_plain_alpha_blend_fails_the_grain_check_unnamed():
    """No pyramid at all: the check fails with the measurement and the hint to build the mask's
    pyramid; its own diagnosis names nothing (the seam check names the plain cut), the code reading
    only the parameter `levels` that such code never reads."""
    from autograder.engine.ignored import MISTAKE as UNUSED

    result = graded_case(MODULE, *MISTAKES["plain alpha blend"][:2])
    [check] = [c for c in check_results(result, "lab08.ext3") if c.name == GRAIN_CHECK]
    assert not check.passed and "without smoothing" not in check.message
    assert not check.mistake or (check.mistake == UNUSED and "never uses its parameter `levels`" in check.message)
    assert check.hint == lab08.MASK_PYRAMID_HINT.text


def test_the_orb_tip_is_worth_no_points():
    [tip] = [c for c in lab08.ext1.checks if c.name == ORB_TIP]
    assert tip.advice and tip.points == 0


PARTIAL_WEIGHT = "a mask's weights are used as given: 0.25 everywhere is a quarter of img1"


def test_a_mask_stretched_to_its_maximum_fails_the_partial_weight_check_named_from_the_code(tmp_path):
    # the blind set's `mask / mask.max()`: right for every mask reaching 1, wrong for weights below 1
    stretched = mutant(tmp_path / "stretched", MODULE, """
        _reference_blend = blend_multiband
        def blend_multiband(img1, img2, mask, levels=4):
            m = np.asarray(mask, dtype=np.float32)
            m = m / m.max()
            return _reference_blend(img1, img2, m, levels)
        """)
    failed = {c.name: c for c in check_results(grade(stretched, ["lab08.ext3"]), "lab08.ext3") if c.score < c.max_score}
    assert list(failed) == [PARTIAL_WEIGHT]
    assert "`m / m.max()` (line" in failed[PARTIAL_WEIGHT].message and failed[PARTIAL_WEIGHT].mistake
    # a mask clipped to [0, 1] (a weight kept as given) passes; one thresholded to 0 or 1 fails, unnamed
    clipped = mutant(tmp_path / "clipped", MODULE, """
        _reference_blend = blend_multiband
        def blend_multiband(img1, img2, mask, levels=4):
            return _reference_blend(img1, img2, np.clip(mask, 0.0, 1.0), levels)
        """)
    assert all(c.score == c.max_score for c in check_results(grade(clipped, ["lab08.ext3"]), "lab08.ext3")
               if c.name == PARTIAL_WEIGHT)
    thresholded = mutant(tmp_path / "thresholded", MODULE, """
        _reference_blend = blend_multiband
        def blend_multiband(img1, img2, mask, levels=4):
            return _reference_blend(img1, img2, (np.asarray(mask) > 0.5).astype(float), levels)
        """)
    [check] = [c for c in check_results(grade(thresholded, ["lab08.ext3"]), "lab08.ext3") if c.name == PARTIAL_WEIGHT]
    assert check.score < check.max_score and not check.mistake and "mask of 0 everywhere" in check.message

