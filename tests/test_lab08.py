"""Lab 8: the reference passes, the skeleton scores 0, usual mistakes are named."""

import numpy as np
import pytest

from autograder.engine.runner import grade
from autograder.labs.mistakes.lab08 import ADVICE, MISTAKES
from conftest import assert_advice_case, assert_all_not_implemented, assert_full_marks, assert_mistake_named, check_results, edited_reference, mutant

MODULE = "lab08_homographies"


def test_reference_scores_full_marks(reference_result):
    assert_full_marks(reference_result, "lab08")


def test_skeleton_scores_zero_with_not_implemented(skeleton_result):
    assert_all_not_implemented(skeleton_result, "lab08")


@pytest.mark.parametrize("case", sorted(MISTAKES))
@pytest.mark.xdist_group("lab08")
def test_mistake_is_caught_and_named(case):
    assert_mistake_named(MODULE, *MISTAKES[case])


def test_other_exercises_unaffected_by_a_mistake(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        def draw_matches(img1, img2, pts1, pts2):
            raise ValueError("oops")
        """), ["lab08.ex3", "lab08.ex1"])
    for exercise in result.exercises:
        assert (exercise.score == exercise.max_score) == (exercise.id != "lab08.ex3"), exercise.id
    failing = [c for c in check_results(result, "lab08.ex3") if not c.passed]
    assert len(failing) == 3   # the three draw_matches checks
    assert all("ValueError: oops" in c.message for c in failing)


SENSIBLE_ALTERNATIVES = """
    def transform_points(H, pts):   # float32 through OpenCV
        return cv2.perspectiveTransform(np.float32(pts).reshape(-1, 1, 2), np.float32(H)).reshape(-1, 2)

    def homography_dlt(src, dst):   # normalised per axis instead of Hartley's isotropic scaling
        src = np.asarray(src, float); dst = np.asarray(dst, float)
        def T(p):
            c, s = p.mean(0), p.std(0)
            return np.array([[1 / s[0], 0, -c[0] / s[0]], [0, 1 / s[1], -c[1] / s[1]], [0, 0, 1]])
        T1, T2 = T(src), T(dst)
        _, _, Vt = np.linalg.svd(_dlt_rows(transform_points(T1, src), transform_points(T2, dst)))
        H = np.linalg.inv(T2) @ Vt[-1].reshape(3, 3) @ T1
        return H / H[2, 2]

    def draw_matches(img1, img2, pts1, pts2):   # OpenCV's drawing, random colours
        k1 = [cv2.KeyPoint(float(x), float(y), 1) for x, y in pts1]
        k2 = [cv2.KeyPoint(float(x), float(y), 1) for x, y in pts2]
        matches = [cv2.DMatch(i, i, 0) for i in range(len(k1))]
        return cv2.drawMatches(_bgr(img1), k1, _bgr(img2), k2, matches, None)

    def homography_ransac(src, dst, threshold=3.0, seed=None):   # loop, symmetric error
        src = np.asarray(src, float); dst = np.asarray(dst, float)
        rng = np.random.default_rng(seed)
        def error(H):
            forward = np.linalg.norm(transform_points(H, src) - dst, axis=1)
            backward = np.linalg.norm(transform_points(np.linalg.inv(H), dst) - src, axis=1)
            return np.maximum(forward, backward)
        best = None
        for _ in range(300):
            sample = rng.choice(len(src), 4, replace=False)
            try:
                inliers = error(homography_dlt(src[sample], dst[sample])) < threshold
            except np.linalg.LinAlgError:
                continue
            if best is None or inliers.sum() > best.sum():
                best = inliers
        H = homography_dlt(src[best], dst[best])
        return H, error(H) < threshold

    def stitch(img1, img2):   # plain average in the overlap, fractional canvas shift
        H = _pairwise_homography(img2, img1)
        corners = np.vstack([_corners(img1), transform_points(H, _corners(img2))])
        x0, y0 = corners.min(0)
        x1, y1 = corners.max(0)
        T = _translation(-x0, -y0)
        size = (int(np.ceil(x1 - x0)) + 1, int(np.ceil(y1 - y0)) + 1)
        a = apply_homography(img1, T, size).astype(float)
        b = apply_homography(img2, T @ H, size).astype(float)
        ma = apply_homography(np.full(img1.shape[:2], 255, np.uint8), T, size) > 127
        mb = apply_homography(np.full(img2.shape[:2], 255, np.uint8), T @ H, size) > 127
        count = np.maximum(ma.astype(float) + mb, 1)[..., None]
        return ((a * ma[..., None] + b * mb[..., None]) / count).astype(np.uint8)
"""


def test_sensible_alternatives_score_full_marks(tmp_path):
    """Other reasonable implementations (OpenCV helpers, other conventions) are not penalised."""
    exercises = [f"lab08.ex{k}" for k in range(1, 6)]
    result = grade(mutant(tmp_path, MODULE, SENSIBLE_ALTERNATIVES), exercises)
    for exercise in result.exercises:
        for check in exercise.checks:
            assert check.passed, f"{exercise.id} {check.name}: {check.message}"


def test_lines_shifted_by_w2_are_named_on_images_of_unequal_widths(tmp_path):
    """Lines shifted by img2's width instead of img1's: the canvas is right (the shape check
    passes); on img1 120 px and img2 280 px wide the lines end 160 px off, named."""
    exercise, source, _ = MISTAKES["lines shifted by W2 instead of W1"]
    checks = {c.name: c for c in check_results(grade(mutant(tmp_path, MODULE, source), [exercise]), exercise)}
    unequal = checks["draw_matches of a narrow, short img1 and a wide, tall img2: the lines end at x2 + W1"]
    assert not unequal.passed and unequal.mistake == "the lines are shifted by W2 instead of W1"
    assert "shifted by img2's width (280 px)" in unequal.message and "x = W1 = 120" in unequal.message
    assert checks["draw_matches: side by side, width W1+W2, height max(H1,H2), 3 channels"].passed


@pytest.mark.parametrize("name", sorted(ADVICE))
@pytest.mark.xdist_group("lab08")
def test_convention_is_advice_not_points(name):
    assert_advice_case(MODULE, *ADVICE[name])


@pytest.mark.parametrize("edit, sizing_told", [
    (("shift = _translation(-x_min, -y_min)  # integer shift", "shift = np.eye(3)  # integer shift"), False),
])
def test_a_canvas_of_the_right_size_never_shifted_is_told_the_shift_only(tmp_path, edit, sizing_told):
    """The canvas sized from all the warped corners but never translated: told to shift, not to
    size the canvas, which it already does (the table's 'no shift' case sizes it wrongly too)."""
    from conftest import edited_reference

    result = grade(edited_reference(tmp_path, "lab08_homographies", edit), ["lab08.ex5"], pictures="none")
    told = [c for c in check_results(result, "lab08.ex5") if c.mistake == "the canvas is not shifted for negative coordinates"]
    assert told, [c.message for c in check_results(result, "lab08.ex5") if not c.passed]
    assert all(("size the canvas" in c.message) == sizing_told for c in told), [c.message for c in told]


def test_a_canvas_sized_to_the_maximum_only_is_told_to_size_it_too(tmp_path):
    exercise, source, _ = MISTAKES["no shift for negative coordinates"]
    result = grade(mutant(tmp_path, "lab08_homographies", source), [exercise], pictures="none")
    told = [c for c in check_results(result, exercise) if c.mistake == "the canvas is not shifted for negative coordinates"]
    assert told and any("size the canvas to the bounding box" in c.message for c in told), [c.message for c in told]


def test_a_pyramid_collapsed_with_resize_is_told_the_two_enlargements(tmp_path):
    """Bands made with cv2.pyrUp, collapsed with cv2.resize: not told to compare with pyrUp, which it
    already calls, but that the two enlargements differ."""
    from conftest import edited_reference

    edit = ("result = cv2.pyrUp(result, dstsize=(band.shape[1], band.shape[0])) + band",
            "result = cv2.resize(result, (band.shape[1], band.shape[0])) + band")
    result = grade(edited_reference(tmp_path, "lab08_homographies", edit), ["lab08.ext3"], pictures="none")
    [check] = [c for c in check_results(result, "lab08.ext3") if c.name == "blending an image with itself leaves it unchanged"]
    assert not check.passed and "both with cv2.pyrUp and with cv2.resize" in check.message, check.message
    assert "compare each band" not in check.message + check.hint


def test_a_band_with_its_sign_flipped_in_float_is_not_told_uint8_arithmetic(tmp_path):
    """The pyramid built in float with each band's sign flipped (up(coarser) - finer): blending an image
    with itself changes it by over 100 grey levels, as uint8 arithmetic would; the code computes in
    float, so neither uint8 nor a band "still computed from uint8" is said, but what must hold."""
    from conftest import edited_reference

    edit = ("bands.append(fine - cv2.pyrUp(coarse, dstsize=size))", "bands.append(cv2.pyrUp(coarse, dstsize=size) - fine)")
    result = grade(edited_reference(tmp_path, "lab08_homographies", edit), ["lab08.ext3"], pictures="none")
    [check] = [c for c in check_results(result, "lab08.ext3") if c.name == "blending an image with itself leaves it unchanged"]
    assert not check.passed
    said = check.message + check.hint
    # (what must hold, or the change of the build or the collapse that mends it)
    repaired = "Trying small changes" in said and "cv2.pyrUp" in said.split("Trying small changes")[-1]
    assert "uint8" not in said and ("must undo the one taken out" in said or repaired), said


def test_a_ransac_measuring_its_error_backwards_is_not_told_an_inverted_mask_or_an_ignored_threshold(tmp_path):
    """|H dst - src| for |H src - dst|: every pair ends up an inlier and H a fit to all of them. The
    outputs look like a fit to all the points and, against the truth, like an inverted mask; neither
    the mask's inversion nor an ignored threshold is true of such code."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, "lab08_homographies",
                              ("homogeneous = np.hstack([src, np.ones((len(src), 1))])",
                               "homogeneous = np.hstack([dst, np.ones((len(dst), 1))])"),
                              ("errors = np.linalg.norm(xy - dst, axis=2)", "errors = np.linalg.norm(xy - src, axis=2)"))
    result = grade(folder, ["lab08.ex4"], pictures="none")
    failed = [c for c in check_results(result, "lab08.ex4") if not c.passed]
    assert failed
    text = " ".join(c.message + c.hint + c.mistake for c in failed)
    assert "inverted" not in text and "threshold is ignored" not in text and "another sample" not in text, text
    [mask] = [c for c in failed if c.name == "homography_ransac: the inlier mask it returns is the inliers of the H it returns"]
    assert "the mask marks every pair" in mask.message, mask.message


DRAWING_CHECKS = ("draw_matches shows both images and a line per match",
                  "draw_matches of a narrow, short img1 and a wide, tall img2: the lines end at x2 + W1")


def drawing_checks(tmp_path, source):
    result = grade(mutant(tmp_path, MODULE, source), ["lab08.ex3"], pictures="none")
    checks = {c.name: c for c in check_results(result, "lab08.ex3")}
    return [checks[name] for name in DRAWING_CHECKS]


# Legitimate drawings (benchmarks/spread_draw_matches.py measures many more): OpenCV's with the
# random colour that left a line hardest to see under the old rule, rich keypoints and a fixed
# colour; a student's own cv2.line drawing in black (LINE_8), numbered, with a divider and a frame.
OWN_DRAWING = """
    def draw_matches(img1, img2, pts1, pts2):
        h1, w1 = img1.shape[:2]
        h2, w2 = img2.shape[:2]
        canvas = np.zeros((max(h1, h2), w1 + w2, 3), np.uint8)
        canvas[:h1, :w1] = _bgr(img1)
        canvas[:h2, w1:] = _bgr(img2)
        for i, ((x1, y1), (x2, y2)) in enumerate(zip(pts1, pts2)):
            cv2.line(canvas, (int(x1), int(y1)), (int(x2) + w1, int(y2)), (0, 0, 0), 1, cv2.LINE_8)
            cv2.putText(canvas, str(i), (int(x1) + 4, int(y1) - 4), cv2.FONT_HERSHEY_SIMPLEX, 0.4, (0, 255, 255), 1)
        cv2.line(canvas, (w1, 0), (w1, canvas.shape[0] - 1), (255, 255, 255), 1)
        cv2.rectangle(canvas, (0, 0), (canvas.shape[1] - 1, canvas.shape[0] - 1), (0, 255, 255), 1)
        return canvas
    """


def opencv_drawing(matches="[cv2.DMatch(i, i, 0) for i in range(len(k1))]", seed=126, **options):
    keywords = "".join(f", {k}={v}" for k, v in options.items())
    return f"""
    def draw_matches(img1, img2, pts1, pts2):
        cv2.setRNGSeed({seed})
        k1 = [cv2.KeyPoint(float(x), float(y), 20) for x, y in pts1]
        k2 = [cv2.KeyPoint(float(x), float(y), 20) for x, y in pts2]
        return cv2.drawMatches(_bgr(img1), k1, _bgr(img2), k2, {matches}, None{keywords})
    """


@pytest.mark.parametrize("source", [
    opencv_drawing(), opencv_drawing(seed=241),
    opencv_drawing(flags="cv2.DrawMatchesFlags_DRAW_RICH_KEYPOINTS", matchColor=(0, 255, 0)), OWN_DRAWING],
    ids=["drawMatches seed 126", "drawMatches seed 241", "drawMatches rich keypoints, green", "own black lines"])
def test_legitimate_match_drawings_keep_full_marks(tmp_path, source):
    for check in drawing_checks(tmp_path, source):
        assert check.passed, f"{check.name}: {check.message}"


def test_a_drawing_leaving_out_the_last_match_loses_points_naming_it(tmp_path):
    """The blind set's cv2.drawMatches given range(len(pts1) - 1): 11 of 12 lines were enough."""
    for check in drawing_checks(tmp_path, opencv_drawing("[cv2.DMatch(i, i, 0) for i in range(len(k1) - 1)]")):
        assert not check.passed and check.mistake == "the last match has no line", check.message
        assert "has no line: the last one (from pts1[" in check.message, check.message
        assert "shifted" not in check.message


def test_a_drawing_leaving_out_the_first_match_names_it(tmp_path):
    content, _ = drawing_checks(tmp_path, opencv_drawing("[cv2.DMatch(i, i, 0) for i in range(1, len(k1))]"))
    assert not content.passed and content.mistake == "the first match has no line", content.message
    assert "1 of the 12 matches has no line: the first one (from pts1[0] = (" in content.message


def test_matches_paired_off_by_one_lose_points(tmp_path):
    _, unequal = drawing_checks(tmp_path, opencv_drawing("[cv2.DMatch(i, (i + 1) % len(k1), 0) for i in range(len(k1))]"))
    assert not unequal.passed and "matches have no line" in unequal.message, unequal.message


def test_a_line_joining_no_match_loses_points(tmp_path):
    extra = OWN_DRAWING.replace("        cv2.line(canvas, (w1, 0)",
                                "        cv2.line(canvas, (0, 0), (int(pts2[-1][0]) + w1, int(pts2[-1][1])), (0, 255, 0), 1)\n"
                                "        cv2.line(canvas, (w1, 0)")
    for check in drawing_checks(tmp_path, extra):
        assert not check.passed and check.mistake == "a line that joins no match is drawn", check.message
        assert "every match has its line, but a line from about (" in check.message


def test_a_pyramid_counting_levels_as_downsamplings_keeps_full_marks(tmp_path):
    """levels + 1 pyramid levels (downsampled `levels` times), as OpenCV's stitching module counts
    them (detail::createLaplacePyr(img, num_levels) builds num_levels + 1): neither the lab sheet nor
    the API says which count `levels` is, and one more level only smooths the seam further, so it is
    a legitimate variant (the blind set's 2026-11-29d lab08 08), not a mistake."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, MODULE, ("    for _ in range(levels - 1):", "    for _ in range(levels):"))
    [graded] = grade(folder, ["lab08.ext3"], pictures="none").exercises
    assert graded.score == graded.max_score, [(c.name, c.message) for c in graded.checks if not c.passed]


def test_a_ransac_measuring_its_error_before_the_division_is_not_told_src_and_dst_swapped(tmp_path):
    """An own RANSAC loop comparing (u, v) with dst where (u / w, v / w) belongs: a wrong H with a
    mask of its own making, which by chance also agrees with H read backwards. H does not map dst
    onto src, so the swap is not said."""
    folder = mutant(tmp_path, "lab08_homographies", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float).reshape(-1, 2)
            dst = np.asarray(dst, float).reshape(-1, 2)
            rng = np.random.default_rng(seed)
            src_h = np.hstack([src, np.ones((len(src), 1))])

            def inliers_of(H):
                mapped = src_h @ H.T
                return np.linalg.norm(mapped[:, :2] - dst, axis=1) < threshold

            best = np.zeros(len(src), dtype=bool)
            for _ in range(1000):
                sample = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[sample], dst[sample])
                if np.all(np.isfinite(H)) and inliers_of(H).sum() > best.sum():
                    best = inliers_of(H)
            if best.sum() < 4:
                return homography_dlt(src, dst), np.ones(len(src), dtype=bool)
            H = homography_dlt(src[best], dst[best])
            inliers = inliers_of(H)
            if inliers.sum() >= 4:
                H = homography_dlt(src[inliers], dst[inliers])
            return H, inliers
        """)
    result = grade(folder, ["lab08.ex4"], pictures="none")
    failed = [c for c in check_results(result, "lab08.ex4") if not c.passed]
    assert failed
    text = " ".join(c.message + c.hint + c.mistake for c in failed)
    assert "swapped" not in text and "maps dst onto src" not in text, text


def test_a_blend_whose_weights_are_overwritten_is_told_by_its_white_panorama(tmp_path):
    """The reference's `_compose` with `weights = weight` where `weights += weight` belongs: where only
    img1 is, the weighted sum is divided by weights that are 0 and clipped to white. The message says so
    (measured), not that img1 must only be shifted -- the code places it by the identity already."""
    folder = edited_reference(tmp_path, "lab08_homographies", ("weights += weight", "weights = weight"))
    result = grade(str(folder), ["lab08.ex5"])
    failed = [c for c in check_results(result, "lab08.ex5") if c.score < c.max_score]
    assert any("of your panorama is pure white (255)" in c.message for c in failed), [c.message for c in failed]
    assert not any("must only be shifted" in c.message for c in failed)


def test_a_mask_at_the_squared_error_of_the_h_before_a_last_refit_is_named():
    """RANSAC's mask drawn at the squared error (|e|^2 < 3: within 1.73 px) by the H before a final
    refit: the returned H is a little off that one, so the mask agrees with the squared rule a little
    less than exactly -- as well as any one threshold does -- and is named; a mask of another model
    (agreeing with no threshold) is not."""
    from autograder.engine.checks import Fail
    from autograder.labs.lab08 import name_squared_threshold

    class Told:   # a stand-in trial: fail raises, as a check's does; no code to read
        sandbox = None

        def fail(self, message, hint="", mistake=""):
            raise Fail(message, hint, mistake)

    rng = np.random.default_rng(3)
    src = rng.uniform(0, 300, (200, 2))
    dst = src + rng.normal(0, 1.2, (200, 2))          # H = I, errors of about 1.5 px
    errors = np.linalg.norm(dst - src, axis=1)
    previous = errors + rng.normal(0, 0.1, 200)       # the H before the refit: errors a little apart
    with pytest.raises(Fail) as told:
        name_squared_threshold(Told(), "ransac", np.eye(3), previous ** 2 < 3.0, src, dst, 3.0)
    assert told.value.mistake == "the squared error is compared with the threshold"
    other = rng.random(200) < 0.5                     # no function of the distances
    name_squared_threshold(Told(), "ransac", np.eye(3), other, src, dst, 3.0)   # (nothing named: no raise)


@pytest.mark.parametrize("edit", [
    ("return bands + [gaussian[-1]]", "return bands"),                      # the top never kept
    ("result = bands[-1]", "result = np.zeros_like(bands[-1])"),            # the collapse not started from it
])
def test_a_pyramid_without_its_low_pass_top_is_named(tmp_path, edit):
    """Band-pass levels alone collapse to the image less its coarsest level upsampled: named from that
    measurement, whichever way the top is lost, not told to add back bands the code adds back."""
    from conftest import edited_reference

    result = grade(edited_reference(tmp_path, "lab08_homographies", edit), ["lab08.ext3"], pictures="none")
    [check] = [c for c in check_results(result, "lab08.ext3") if c.name == "blending an image with itself leaves it unchanged"]
    assert not check.passed and check.mistake.startswith("the pyramid's low-pass top"), (check.mistake, check.message)
    assert "must undo the one taken out" not in check.message + check.hint


@pytest.mark.parametrize("iterable, part", [
    ("images", False), ("zip(images, homographies)", False), ("range(len(images))", False),
    ("range(0, len(images))", False), ("images[0:]", False),
    ("images[1:]", True), ("zip(images[1:], homographies[1:])", True), ("range(1, len(images))", True),
    ("range(len(images) - 1)", True), ("enumerate(images[:-1])", True),
])
def test_a_loop_over_part_of_the_images_is_not_every_image(iterable, part):
    """The canvas sentence "your code sizes it from every image's warped corners" is said only of a loop
    over every image: `images[1:]` leaves the reference frame's corners out."""
    import ast as python_ast

    from autograder.labs import lab08

    assert lab08._over_a_part(python_ast.parse(iterable, mode="eval").body) == part


def test_a_ransac_without_refit_is_not_told_to_draw_more_samples_or_keep_the_best(tmp_path):
    """A RANSAC that draws 500 samples and keeps the best model's inliers, but fits H on the first 8 of them, was told
    "draw enough samples ..., keep the H with the most inliers, then refit on them" by the 50%-outlier check
    (third-party round of 2026-12-07: 1000 samples drawn, the best sample's H returned): where its mask is right on
    every seed that failed and a DLT on the pairs it marks is right, the check says so and asks for the refit alone."""
    _, unrefitted, _ = MISTAKES["RANSAC without the final refit"]
    last = "            return best, np.linalg.norm(transform_points(best, src) - dst, axis=1) < threshold\n"
    assert last in unrefitted
    first_eight = unrefitted.replace(last, "            inliers = np.linalg.norm(transform_points(best, src) - dst, axis=1) < threshold\n"
                                           "            return homography_dlt(src[inliers][:8], dst[inliers][:8]), inliers\n")
    result = grade(mutant(tmp_path, MODULE, first_eight), ["lab08.ex4"], pictures="none", include_hidden=False)
    [seeds] = [c for c in check_results(result, "lab08.ex4") if c.name.startswith("homography_ransac with 50% outliers")]
    assert not seeds.passed
    assert "the H returned is not the one its inliers give" in seeds.message, seeds.message
    assert "draw enough samples" not in seeds.hint + seeds.message and "refit" in seeds.hint, seeds.hint


RANSAC_REFIT_ON = """
def homography_ransac(src, dst, threshold=3.0, seed=None):
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    rng = np.random.default_rng(seed)
    best_inliers, best_count = np.zeros(len(src), dtype=bool), 0
    for _ in range(500):
        idx = rng.choice(len(src), 4, replace=False)
        H = homography_dlt(src[idx], dst[idx])
        inliers = np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold
        if inliers.sum() > best_count:
            best_count, best_inliers = inliers.sum(), inliers
    if best_count < 4:
        return homography_dlt(src, dst), np.ones(len(src), dtype=bool)
    {refit}
    return H, best_inliers
"""


@pytest.mark.parametrize("refit, told", [
    ("H = homography_dlt(src, dst)", "`H = homography_dlt(src, dst)`"),
    ("H = homography_dlt(src[best_inliers], dst[best_inliers])", None),
    ("src, dst = src[best_inliers], dst[best_inliers]\n    H = homography_dlt(src, dst)", None),
])
def test_a_refit_after_the_loop_on_every_pair_is_read_where_it_is(tmp_path, refit, told):
    """The RANSAC reading of a refit given the whole arrays the loop samples, after the loop (the fallback branch
    of too few inliers is no refit); arrays selected first, or selected in the call, are not every pair."""
    from types import SimpleNamespace

    from autograder.labs.lab08 import _refit_on_every_pair
    folder = mutant(tmp_path, "lab08_homographies", RANSAC_REFIT_ON.replace("{refit}", refit))
    trial = SimpleNamespace(sandbox=SimpleNamespace(submission_dir=folder), lab=SimpleNamespace(module="lab08_homographies"))
    found = _refit_on_every_pair(trial)
    assert (found is None) if told is None else (found is not None and found.startswith(told + ", line ")), found


def test_a_fallback_marking_every_pair_is_read_where_it_is(tmp_path):
    """The branch returning every pair as inliers (`np.ones(n, dtype=bool)` in an `if`), read with its line: a mask
    marking every pair beside a wrong H is told as that fallback, not as a mask of its own making; code returning
    its mask alone has no such branch."""
    from types import SimpleNamespace

    from autograder.labs.lab08 import _every_pair_fallback
    folder = mutant(tmp_path, "lab08_homographies", RANSAC_REFIT_ON.replace("{refit}", "H = homography_dlt(src, dst)"))
    trial = SimpleNamespace(sandbox=SimpleNamespace(submission_dir=folder), lab=SimpleNamespace(module="lab08_homographies"))
    found = _every_pair_fallback(trial)
    assert found is not None and found.startswith("`return (homography_dlt(src, dst), np.ones(len(src), dtype=bool))`"), found
    without = RANSAC_REFIT_ON.replace("{refit}", "H = homography_dlt(src, dst)").replace(
        "        return homography_dlt(src, dst), np.ones(len(src), dtype=bool)\n", "        raise ValueError('too few')\n")
    folder = mutant(tmp_path / "without", "lab08_homographies", without)
    trial = SimpleNamespace(sandbox=SimpleNamespace(submission_dir=folder), lab=SimpleNamespace(module="lab08_homographies"))
    assert _every_pair_fallback(trial) is None


def test_a_canvas_sized_from_the_images_sizes_without_a_dtype_is_read_as_the_cause_of_a_float_image(tmp_path):
    """`np.zeros((max(h1, h2), w1 + w2, 3))` returned as made (07e lab08/05): its size is no `.shape`, yet it is the
    array returned, float64 by NumPy's default -- read and told, with its line."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, "lab08_homographies", (
        "canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)", "canvas = np.zeros((max(h1, h2), w1 + w2, 3))"))
    failed = [c for c in check_results(grade(str(folder), ["lab08.ex3"]), "lab08.ex3") if c.score < c.max_score]
    assert failed and all("your code makes `np.zeros((max(h1, h2), w1 + w2, 3))`" in c.message for c in failed), \
        [c.message for c in failed]


def test_an_empty_region_of_a_wrong_panorama_is_read_without_numpy_warnings():
    """A panorama that leaves no part to img2 alone (a DLT gone wrong, blind set 08a lab08/02) gives the hint's
    reading an empty region: nothing to correlate, no "Mean of empty slice" printed by the grader."""
    import warnings
    from types import SimpleNamespace

    from autograder.labs.lab08 import _in_step

    judge = SimpleNamespace(panorama=np.zeros((4, 5, 3)), expected=np.ones((4, 5, 3)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _in_step(judge, np.zeros((4, 5), bool)) is True
