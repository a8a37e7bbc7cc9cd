"""A named mistake is a confirmed one (issue 26).

A check names a mistake only when the mistake's answer reproduces the student's on the
failing input and on a second input chosen to tell the candidates apart (a probe,
``autograder.engine.judges.Probe``); otherwise the message says what is measurably wrong.

- The wrong names a blind set measured are gone: each bug is graded here as a mutant and
  must not be named as the mistake it was mistaken for.
- The mechanism: a candidate that matches on the failing input but not on the probe is not
  named; a probe answering as the mistake does confirms it; mistakes that answered alike are
  told apart by the probe.
- Messages that name a cause agree with the numbers they measure (the direction of a
  ratio, the sign of an offset, a count of levels): the named cause, written as code, gives
  that message.
- Every "it looks like" of the lab suites is either confirmed by a probe or rests on a
  measurement that is itself the claim (listed, with why, in :data:`DIRECT_EVIDENCE`).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import numpy as np
import pytest

from autograder.engine.checks import Trial
from autograder.engine.compare import SAME_ANSWER, max_abs_error
from autograder.engine.judges import Probe, confirm, name_mistake
from autograder.engine.runner import grade
from conftest import assert_diagnosed, check_results, graded_case, named_mistakes

ROOT = Path(__file__).resolve().parents[1]


# ------------------------------------------------------------------ the measured wrong names
RANSAC_WITHOUT_W = """
    def homography_ransac(src, dst, threshold=3.0, seed=None):
        src = np.asarray(src, dtype=float)
        dst = np.asarray(dst, dtype=float)
        rng = np.random.default_rng(seed)
        n = len(src)
        sh = np.hstack([src, np.ones((n, 1))])
        best, best_count = None, -1
        for _ in range(500):
            idx = rng.choice(n, 4, replace=False)
            H = homography_dlt(src[idx], dst[idx])
            err = np.linalg.norm((sh @ H.T)[:, :2] - dst, axis=1)   # not divided by w
            inliers = err < threshold
            if inliers.sum() > best_count:
                best, best_count = inliers, inliers.sum()
        H = homography_dlt(src[best], dst[best])
        return H, np.linalg.norm((sh @ H.T)[:, :2] - dst, axis=1) < threshold
    """

STITCH_RESTARTING = """
    def stitch_many(images):
        panorama = images[0]
        for k in range(1, len(images)):
            panorama = stitch(images[0], images[k])   # restarts from the first image every time
        return panorama
    """

COLLAPSE_FROM_IMG2 = """
    def blend_multiband(img1, img2, mask, levels=4):
        a = np.asarray(img1, dtype=np.float32)
        b = np.asarray(img2, dtype=np.float32)
        weights = _gaussian_pyramid(np.clip(np.asarray(mask, dtype=np.float32), 0, 1), levels)
        la, lb = _laplacian_pyramid(a, levels), _laplacian_pyramid(b, levels)
        bands = [(w[..., None] if x.ndim == 3 else w) * x + (1 - (w[..., None] if x.ndim == 3 else w)) * y
                 for x, y, w in zip(la, lb, weights)]
        result = lb[-1]                                 # img2's coarsest level, not the blended one
        for band in reversed(bands[:-1]):
            result = cv2.pyrUp(result, dstsize=(band.shape[1], band.shape[0])) + band
        return np.clip(np.round(result), 0, 255).astype(np.uint8)
    """

DLT_BY_EIG = """
    def homography_dlt(src, dst):
        src = np.asarray(src, dtype=float)
        dst = np.asarray(dst, dtype=float)
        A = []
        for (x, y), (u, v) in zip(src, dst):
            A.append([-x, -y, -1, 0, 0, 0, u * x, u * y, u])
            A.append([0, 0, 0, -x, -y, -1, v * x, v * y, v])
        A = np.array(A)
        w, V = np.linalg.eig(A.T @ A)
        H = V[:, -1].reshape(3, 3)      # eig does not sort: not the smallest eigenvalue's vector
        return H / H[2, 2]
    """

MODULE8 = "lab08_homographies"


def messages(result, exercise) -> str:
    return "\n".join(c.message.lower() for c in check_results(result, exercise) if c.score < c.max_score)


@pytest.mark.xdist_group("lab08")
def test_ransac_error_without_w_is_not_named_as_keeping_the_last_model():
    result = graded_case(MODULE8, "lab08.ex4", RANSAC_WITHOUT_W)
    text = messages(result, "lab08.ex4")
    assert "last model drawn" not in text and "does not keep the model" not in text
    # Four affine problems (w = 1 everywhere) tell the cause: right there, wrong where w varies.
    assert_diagnosed(result, "lab08.ex4", "without the perspective division")


@pytest.mark.xdist_group("lab08")
def test_a_ransac_that_keeps_its_best_model_is_not_told_it_keeps_the_last(tmp_path):
    """Transfer errors measured in the normalised coordinates, compared with a threshold in pixels:
    the loop keeps the model with the most inliers (its code says so), so what is wrong is what it
    counts, never "it returns the last model drawn"."""
    from conftest import mutant

    folder = mutant(tmp_path, MODULE8, """
        def homography_ransac(src, dst, threshold=3.0, seed=None, confidence=0.999, max_iterations=5000):
            src = np.asarray(src, float).reshape(-1, 2)
            dst = np.asarray(dst, float).reshape(-1, 2)
            rng = np.random.default_rng(seed)
            scale = np.abs(dst).max()
            best, best_count = None, -1
            for _ in range(500):
                sample = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[sample], dst[sample])
                mapped = np.c_[src, np.ones(len(src))] @ H.T
                errors = np.linalg.norm(mapped[:, :2] / mapped[:, 2:] - dst, axis=1) * scale
                count = int((errors < threshold).sum())
                if count > best_count:
                    best, best_count = errors < threshold, count
            return homography_dlt(src[best], dst[best]), best
        """)
    result = grade(folder, ["lab08.ex4"], pictures="none", include_hidden=False)
    text = messages(result, "lab08.ex4")
    assert "last model drawn" not in text and "keeps the model with the most inliers" in text, text


@pytest.mark.xdist_group("lab08")
def test_stitching_that_restarts_is_not_named_as_an_unshifted_canvas():
    result = graded_case(MODULE8, "lab08.ext2", STITCH_RESTARTING)
    text = messages(result, "lab08.ext2")
    assert text, "the restarting stitch must lose points"
    assert "not shifted" not in text
    assert "chain the pairwise homographies" not in text   # image 2, next to the reference, is wrong too
    for label, message in named_mistakes(result, "lab08.ext2"):
        assert "left out" in (label + message).lower(), (label, message)   # the one name that is true


@pytest.mark.xdist_group("lab08")
def test_collapse_from_the_wrong_image_is_not_told_to_pass_dstsize():
    result = graded_case(MODULE8, "lab08.ext3", COLLAPSE_FROM_IMG2)
    text = messages(result, "lab08.ext3")
    assert text and "dstsize" not in text
    # (named only where the code shows it: the coarsest level taken from img2's pyramid, not the blended one)
    # (found as the reference's name at that place, or as the value made from `lb` since -- the same change)
    assert all(label in ("repair:aligned", "repair:other_name") and "`result = lb[-1]` to `result = bands[-1]`" in message
               for label, message in named_mistakes(result, "lab08.ext3"))


@pytest.mark.xdist_group("lab08")
def test_dlt_by_eig_is_not_named_as_a_reduced_svd():
    result = graded_case(MODULE8, "lab08.ex2", DLT_BY_EIG)
    text = messages(result, "lab08.ex2")
    assert text and "reduced" not in text and "full svd" not in text
    for label, message in named_mistakes(result, "lab08.ex2"):
        assert "eig" in label.lower(), (label, message)   # only the reading's name (test_static_reading)


@pytest.mark.xdist_group("lab08")
def test_a_true_reduced_svd_is_still_named():
    """The probe (12 pairs, where a reduced SVD answers rightly) confirms the real mistake."""
    assert_diagnosed(graded_case(MODULE8, "lab08.ex2", """
        _reference_dlt = homography_dlt
        def homography_dlt(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            if len(src) > 4:
                return _reference_dlt(src, dst)
            A = _dlt_rows(src, dst)
            H = np.linalg.svd(A, full_matrices=False)[2][-1].reshape(3, 3)
            return H / H[2, 2]
        """), "lab08.ex2", "reduced")


# ------------------------------------------------------------------ the mechanism
class _Answers:
    """A stand-in for a trial: ``probe`` answers with a given value (or None: the call failed)."""

    def __init__(self, answer):
        self.answer, self.asked = answer, 0

    def probe(self, key, answer):
        self.asked += 1
        return self.answer


def _probe(candidates, truth=None):
    return Probe("probe", lambda: None, lambda: candidates, truth, distance=max_abs_error, tolerance=1e-6)


def test_a_name_the_probe_does_not_confirm_is_dropped():
    candidates = {"A": np.array([1.0, 2.0]), "B": np.array([5.0, 6.0])}
    trial = _Answers(np.array([9.0, 9.0]))   # on the probe the student answers like neither
    assert confirm(trial, "A", _probe(candidates, truth=np.array([0.0, 0.0]))) is None


def test_a_name_the_probe_confirms_stands():
    candidates = {"A": np.array([1.0, 2.0]), "B": np.array([5.0, 6.0])}
    assert confirm(_Answers(np.array([1.0, 2.0])), "A", _probe(candidates, np.array([0.0, 0.0]))) == "A"


def test_without_a_probe_or_an_answer_nothing_is_named():
    candidates = {"A": np.array([1.0, 2.0])}
    assert confirm(_Answers(np.array([1.0, 2.0])), "A", None) is None
    assert confirm(_Answers(None), "A", _probe(candidates)) is None   # the probe call failed


def test_mistakes_alike_on_the_failing_input_are_told_apart_by_the_probe():
    candidates = {"A": np.array([1.0, 2.0]), "B": np.array([5.0, 6.0])}
    assert confirm(_Answers(np.array([5.0, 6.0])), f"A{SAME_ANSWER}B", _probe(candidates)) == "B"


def test_a_mistake_invisible_on_the_probe_is_confirmed_by_a_right_answer_there():
    """A reduced SVD answers N >= 5 pairs rightly: a right answer there confirms it, a wrong
    one (a solver wrong everywhere) refutes it."""
    truth = np.array([0.0, 0.0])
    candidates = {"reduced": truth.copy(), "other": np.array([3.0, 3.0])}
    assert confirm(_Answers(truth.copy()), "reduced", _probe(candidates, truth)) == "reduced"
    assert confirm(_Answers(np.array([7.0, 1.0])), "reduced", _probe(candidates, truth)) is None


def test_a_probe_answer_as_close_to_a_rival_is_no_confirmation():
    candidates = {"A": np.array([1.0]), "B": np.array([1.0 + 2e-7])}
    probe = Probe("p", lambda: None, lambda: candidates, None, distance=max_abs_error, tolerance=1e-6)
    assert confirm(_Answers(np.array([1.0 + 1e-7])), "A", probe) is None


def test_name_mistake_asks_the_probe_only_for_a_candidate_that_matched():
    trial = _Answers(np.array([1.0]))
    candidates = {"A": np.array([1.0])}
    assert name_mistake(trial, np.array([50.0]), candidates, max_abs_error, 1e-6, truth=np.array([0.0]),
                        probe=_probe(candidates)) is None
    assert trial.asked == 0   # nothing matched: the student is not called again


def test_trial_asks_each_probe_once():
    calls = []

    class FakeTrial(Trial):
        def __init__(self):
            self._probed, self.outputs = {}, []

    trial = FakeTrial()
    for _ in range(3):
        trial.probe("k", lambda: calls.append(1) or np.array([1.0]))
    assert len(calls) == 1


# ------------------------------------------------------------------ causes agree with the numbers
# Each named cause, written as code, must give its own message, and the number the message
# measures must point the way the cause says (twice the disc for a doubled aperture...).
MODULE9, MODULE12 = "lab09_camera", "lab12_stereo"
CONSISTENT_CLAIMS = {
    "aperture doubled (2 * aperture: a diameter used as the radius)": (MODULE9, "lab09.ex4", """
        _right = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return _right(points, f, 2 * aperture, n_rays, seed)
        """, ["twice the expected disc", "doubled"], r"up to ([\d.]+) radii", lambda r: 1.8 < r < 2.2),
    "aperture halved (taken as a diameter)": (MODULE9, "lab09.ex4", """
        _right = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return _right(points, f, aperture / 2, n_rays, seed)
        """, ["inner half", "halved"], r"at most ([\d.]+)\s+radii", lambda r: 0.45 < r < 0.55),
    "aperture squared": (MODULE9, "lab09.ex4", """
        _right = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return _right(points, f, aperture ** 2, n_rays, seed)
        """, ["inner half", "squared"], r"at most ([\d.]+)\s+radii", lambda r: 0.45 < r < 0.55),
    "pyramid two levels short": (MODULE8, "lab08.ext3", """
        _right = blend_multiband
        def blend_multiband(img1, img2, mask, levels=4):
            return _right(img1, img2, mask, levels - 2)
        """, ["has 3 levels where levels=5", "off by 2"], None, None),
    "disparities one too small": (MODULE12, "lab12.ex4", """
        _right = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return _right(left, right, max_disparity, block_size, cost) - 1
        """, ["off by -1"], None, None),
    "disparities one too large": (MODULE12, "lab12.ex4", """
        _right = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return np.minimum(_right(left, right, max_disparity, block_size, cost) + 1, max_disparity)
        """, ["off by +1"], None, None),
    "search stops one short": (MODULE12, "lab12.ex4", """
        _right = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return _right(left, right, max_disparity - 1, block_size, cost)
        """, ["max_disparity - 1"], r"gets (\d+) at", None),
}


@pytest.mark.parametrize("claim", sorted(CONSISTENT_CLAIMS))
def test_a_named_cause_agrees_with_the_measured_numbers(claim):
    module, exercise, source, fragments, pattern, direction = CONSISTENT_CLAIMS[claim]
    result = graded_case(module, exercise, source)
    failed = [c.message for c in check_results(result, exercise) if c.score < c.max_score]
    matching = [m for m in failed if all(f.lower() in m.lower() for f in fragments)]
    assert matching, f"{claim}: no message says {fragments}:\n" + "\n".join(failed)
    if pattern is not None:
        measured = float(re.search(pattern, matching[0]).group(1))
        if direction is not None:
            assert direction(measured), (claim, measured, matching[0])
        if claim == "search stops one short":
            top = int(re.search(r"true disparity (\d+) = max_disparity", matching[0]).group(1))
            assert measured == top - 1, matching[0]


def test_the_aperture_message_no_longer_names_the_opposite_cause():
    """'Twice the disc' was told 'the aperture is used as the diameter', which would halve it."""
    source = (ROOT / "autograder" / "labs" / "lab09.py").read_text()
    twice = source[source.index("spread over twice the expected disc") - 600:][:1400]
    assert "used as the diameter" not in twice and "doubled" in twice


# ------------------------------------------------------------------ every "it looks like"
# The functions whose "it looks like" rests on a measurement that is itself the claim (no
# candidate answer is compared), and why that is evidence enough.
DIRECT_EVIDENCE = {
    "shape_form": "the result's shape is the named form's (2x3 for 3x3, (N, 1, 2), one coordinate more...)",
    "exception_form": "the shapes in NumPy's own error are the named form's",
    "scale_form": "the answer is the truth times one factor, measured, and the factor is -1 or 1 / an entry",
    "unit_range_cast": "a uint8 image holding only 0 and 1 where the expected one spans many grey levels",
    "_homogeneous_product": "the product's inner sizes differ by the homogeneous coordinate",
    "_channels_form": "the image's size is the asked one and only its channel axis differs (measured)",
    "judge_matrix": "an integer matrix: the entries are whole numbers where the truth's are not",
    "judge_warp": "the shape is the expected one with width and height exchanged",
    "expect_array": "the shape is the expected one transposed",
    "fit_triangulation_scale": "every point is the true one times its own factor",
    "_diagnose_triangulation": "each point is the truth times a factor (w not divided out); the points "
                               "project exactly onto one view; called again with the cameras exchanged "
                               "the function answers rightly (a probe of its own)",
    "judge_exact_fundamental": "F has NaN entries exactly where it was divided by F[2, 2] = 0",
    "essential_8point_singular_values": "the singular values themselves, printed: (s1, s2, 0) or not (1, 1, 0)",
    "judge_epipoles": "the epipole at infinity has w = 1 and huge x, y: divided by w = 0",
    "judge_structure": "every point lies on its ray at its own factor (not divided by w), or every point "
                       "is mirrored through camera 1's centre (the sign of the global scale)",
    "diagnose_disparity": "the map plus or minus 1 is right at half a pixel: an off-by-one",
    "judge_top_of_range": "the square at max_disparity gets max_disparity - 1 at half its pixels or more",
    "name_oversmoothing": "90% of the rows hold one disparity",
    "fail_winner_take_all": "as many jumps as winner-take-all matching, smoothness 0 and 1e7 compared",
    "judge_last_column": "the last column alone is wrong",
    "judge_rows": "undoing the named step (K^-2, the inverses, the swap) rectifies exactly",
    "rectify_images": "each returned image is the other image (or warped by the other homography), "
                      "to 8 grey levels",
    "name_pose_mistake": "called again with R transposed, the pose reversed or K1/K2 exchanged, "
                         "rectify rectifies exactly (probes of its own)",
    "judge_pipeline_F": "F transposed, or K^-T F K^-1, is right over thousands of true correspondences",
    "judge_track": "row by row over the sequence's frames, the rows are the poses of the frame before "
                   "or after, or inverted, or one frame's everywhere, or relative to the first frame's (each frame an "
                   "input of its own)",
    "name_pattern_mistake": "the patterns equal the mistake's bit for bit, and again at PATTERN_PROBE "
                            "when few columns tell them apart",
    "judge_dlt": "with t_z = 0, P[2, 3] is not 0, and the DLT is right on a camera with t_z != 0 (probe)",
    "judge_decomposition": "R K gives back P[:, :3]: a QR decomposition",
    "blend_identity": "the image blended with itself is its coarsest level upsampled, here and on "
                      "another photo (probe); or, to 1.5 grey levels on average, the image less that level "
                      "(what band-pass levels alone collapse to)",
    "name_rotations": "both maps returned are rotation matrices (orthonormal, determinant 1), measured: "
                      "the claim itself",
    "name_wrapped_stripes": "the patterns are those of k mod 256 bit for bit, here and on a 1024-column "
                            "projector with 10 bits (probe)",
    "blend_sharp": "one weight per pixel explains the image near the seam (a feather, not bands)",
    "name_image_left_out": "the panorama is exactly the bounding box of the other images, and the "
                           "image's own part is missing",
    "judge_many_content": "the image sits where the inverse homography puts it, here and on the probe "
                          "scene",
    "aperture_statistics": "the rays reach twice (or half) the blur disc, and at aperture 0.8 again "
                           "(probe); the spread ignores depth, and again with f = 2 (probe)",
    "name_ransac_h": "the consensus, and four affine problems (probes) tell the cause",
    "aperture_zero": "confirmed by the probe through judges.name_mistake",
    "ransac_refit": "H is the least-squares refit of its own inliers mapping dst onto src (measured on 7 "
                    "problems), and not of src onto dst",
    "name_ncc_normalisation": "an offset of one view moves the disparities while a gain does not (two "
                              "probes on random dots); a normalised correlation is moved by neither",
    "name_steep_lines_missed": "every line the drawing misses leaves the image through its top or bottom "
                               "border, and none other is missed (measured); the cause is said only where "
                               "the code divides by b and never by a (read)",
    "few_matches": "the few matches returned are right (within 2 px of the true correspondences), and the 3D "
                   "points are those of cameras without K at the pipeline's own pose (measured) or the code "
                   "builds P from R and t without K (read)",
    "name_disparity_scale": "the map is the truth times one factor on the pixels not clipped, or clipped at "
                            "max_disparity, or 0 almost everywhere after a range filter (measured); OpenCV's "
                            "fixed point only where the code calls StereoBM/SGBM and never divides by 16 (read)",
    "block_matching_form": "disparities far above the search range, from code calling StereoBM/SGBM that "
                           "never divides by 16 (read)",
    "blank_canvas": "away from what is drawn, every pixel of the drawing has one value where the input image varies, "
                    "and few of them are the input's (measured)",
    "name_zero_smoothness": "the smoothness=0 map is the default's (measured), and the code tests "
                            "smoothness for truth, 'smoothness or X' / 'if not smoothness' (read)",
    "aperture_short_focal": "each point's farthest ray lands (f / Z) / (1 + f / Z) radii out, for each of six "
                            "points' own depths (measured: no other slip gives that ratio at every depth)",
    "fail_if_calibrated_at_another_scale": "K is the true one times one factor in all four of fx, fy, cx and cy "
                                           "(the principal point as a resized pixel centre), within the "
                                           "calibration's own tolerances (measured)",
    "colours_lost": "the result's three channels are equal at every pixel where an input's differ (measured)",
    "judge_calibration": "a reprojection error above 1 px on clean rendered views (measured); the points' order is "
                         "a guess (claims.guessed: a change of the code confirmed to mend it takes its place), not "
                         "said where the code builds them row by row (read)",
    "ncc_flat_border": "more than half the pixels changed by the border take exactly the first disparity whose "
                       "right block lies wholly in it, where np.argmin over NaN costs lands (measured: a guard, an "
                       "epsilon or a cost not normalised lands elsewhere)",
}
CONFIRMING = {"name_mistake", "confirm", "judge_matrix", "judge_warp", "judge_points", "judge_projective",
              "name_second_warp_mistake", "name_matching_mistake", "probe", "_disc_ratio_on_probe"}
SUITES = ["engine/judges.py", "engine/forms.py", "labs/lab07.py", "labs/lab08.py", "labs/lab09.py", "labs/lab10.py", "labs/lab11.py",
          "labs/lab12.py"]


def _looks_like_functions(path: Path):
    """(function name, names it refers to) of each function whose own code says "looks like"."""
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef):
            own = [n for n in ast.walk(node) if isinstance(n, ast.Constant) and isinstance(n.value, str)
                   and "looks like" in n.value.lower()]
            if own:
                names = {n.id for n in ast.walk(node) if isinstance(n, ast.Name)} | \
                    {n.attr for n in ast.walk(node) if isinstance(n, ast.Attribute)}
                yield node.name, names


@pytest.mark.parametrize("suite", SUITES)
def test_every_it_looks_like_is_confirmed_or_direct_evidence(suite):
    unaccounted = []
    for function, names in _looks_like_functions(ROOT / "autograder" / suite):
        confirmed = bool(names & CONFIRMING) or any("probe" in name.lower() for name in names)
        if not confirmed and function not in DIRECT_EVIDENCE:
            unaccounted.append(function)
    assert not unaccounted, f"{suite}: 'it looks like' without a probe or a direct measurement: {unaccounted}"
