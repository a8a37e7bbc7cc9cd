"""Lab 8 - hidden checks: new inputs for the same judges (instructor copy and container only).

Every input is generated here from the seeds and parameters written below.
"""

from __future__ import annotations

import numpy as np

from fixtures import lab08 as truth
from fixtures.images import photo

from ...engine.checks import partial, passed
from ...engine.compare import blurred_difference
from ..lab08 import (RANSAC_H_TOLERANCE, blended, diagnose_ransac, ex1, ex2, ex3, ex4, ex5, ext1, ext2,
                     ext3, fitted_h, diagnose_h, judge_coverage, judge_many_content, judge_matches,
                     judge_homography_warp, judge_region, many_judge, many_names, matched_points, ransac_result,
                     ransac_success, stitch_judge)


@ex1.check("apply_homography: strong perspective, larger dsize (hidden)", points=2, hidden=True)
def hidden_apply(t):
    source = photo("rocket", (200, 150))
    H = truth.translation(30, 25) @ truth.corner_homography(np.random.default_rng(1234), (200, 150), 0.22)
    return judge_homography_warp(t, "apply_homography(image, H, dsize=(260, 200))",
                      t.call("apply_homography", source, H, dsize=(260, 200)), source, H,
                      dsize=(260, 200), show=False)


@ex2.check("homography_dlt: 8 noisy pairs on a 1280x960 image (hidden)", points=2, hidden=True)
def hidden_dlt(t):
    region = (0, 0, 1280, 960)
    errors, best = [], []
    for seed in (501, 502):
        src, dst, H = truth.dlt_problem(seed, 8, 1.0, region, 0.15)
        what = "homography_dlt(src, dst) with 8 noisy pairs"
        got = fitted_h(t, src, dst, what)
        errors.append(truth.transfer_rms(got, H, region))
        best.append(truth.transfer_rms(truth.dlt(src, dst), H, region))
        if errors[-1] > 1.5 * best[-1] + 0.2:
            diagnose_h(t, what, got, H, src, dst, tolerance=2e-2)
    error, reference = float(np.mean(errors)), float(np.mean(best))
    if error <= 1.5 * reference + 0.2:
        return passed(f"{error:.2f} px RMS (a normalised DLT: {reference:.2f} px)")
    t.fail(f"homography_dlt is {error:.2f} px (RMS) from the true H on average, where a normalised "
           f"DLT is {reference:.2f} px away.")


@ex3.check("match_features on a grey pair (hidden)", points=2, hidden=True)
def hidden_match(t):
    img1, img2, H = truth.matching_pair("camera", (240, 180), seed=77, strength=0.1, grey=True)
    return judge_matches(t, "match_features(grey img1, grey img2)", img1, img2, H,
                         t.call("match_features", img1, img2), min_matches=40, min_fraction=0.85)


@ex4.check("homography_ransac: 50% outliers, threshold=2, three seeds (hidden)", points=2, hidden=True)
def hidden_ransac(t):
    wins = 0
    for k in range(3):
        src, dst, H_true, true_inliers = truth.ransac_problem(900 + k, 160, 0.5, 0.5)
        what = f"homography_ransac(src, dst, threshold=2.0, seed={k + 10})"
        H, inliers = ransac_result(t, src, dst, what, threshold=2.0, seed=k + 10)
        error, recall, precision = ransac_success(H, inliers, H_true, true_inliers)
        ok = error <= RANSAC_H_TOLERANCE and recall >= 0.9 and precision >= 0.9
        wins += ok
        if not ok and k == 0:
            diagnose_ransac(t, what, H, inliers, src, dst, H_true, true_inliers, threshold=2.0,
                            seed=k + 10)
    if wins >= 2:
        return passed(f"succeeded with {wins} of 3 seeds")
    if wins == 1:
        return partial(0.3, "homography_ransac succeeded with only 1 of 3 seeds")
    t.fail("homography_ransac failed with all 3 seeds (50% outliers, threshold=2.0)")


def left_scene():
    # img2 lies to the LEFT of img1 and reaches below it
    return truth.panorama_scene("astronaut", (400, 260), ((140, 30), (20, 60)), (240, 180), 0.04, 12)


@ex5.check("stitch when img2 lies to the left of img1 (hidden)", points=3, hidden=True)
def hidden_stitch(t):
    what = "stitch(img1, img2) with img2 on the left"
    judge = stitch_judge(t, "stitch-hidden", left_scene(), what)
    verdict = judge_coverage(t, judge, what, ["img1", "img2"])
    if verdict.fraction < 1:
        return verdict
    return judge_region(t, judge, what, np.any(judge.inside, axis=0), "the panorama")


@ext1.check('match_features(..., method="orb") on a grey pair (hidden)', points=1, hidden=True)
def hidden_orb(t):
    img1, img2, H = truth.matching_pair("camera", (240, 180), seed=78, strength=0.1, grey=True)
    result = t.call("match_features", img1, img2, method="orb")
    matched_points(t, 'match_features(img1, img2, method="orb")', result)
    return judge_matches(t, 'match_features(grey img1, grey img2, method="orb")', img1, img2, H,
                         result, min_matches=40, min_fraction=0.85)


def four_scene():
    return truth.panorama_scene("astronaut", (560, 250), ((10, 30), (105, 10), (205, 50), (310, 20)),
                                (240, 180), 0.02, 23, False)


@ext2.check("stitch_many with 4 images (hidden)", points=2, hidden=True)
def hidden_many(t):
    what = "stitch_many([img1, img2, img3, img4])"
    judge = many_judge(t, "many-hidden", four_scene(), what)
    verdict = judge_coverage(t, judge, what, many_names(4))
    if verdict.fraction < 1:
        return verdict
    return judge_many_content(t, judge, what)


@ext3.check("blend_multiband: disc mask, levels=5, grey odd size (hidden)", points=1, hidden=True)
def hidden_blend(t):
    size = (237, 181)
    img1, img2 = photo("brick", size, grey=True), photo("camera", size, grey=True)
    mask = truth.disc_mask(size, (118, 90), 60)
    what = "blend_multiband(grey img1, grey img2, disc mask, levels=5)"
    got = blended(t, what, img1, img2, mask, levels=5)
    inner = truth.disc_mask(size, (118, 90), 20) > 0
    outer = truth.disc_mask(size, (118, 90), 105) == 0
    e1, e2 = blurred_difference(got, img1, inner), blurred_difference(got, img2, outer)
    if e1 <= 3 and e2 <= 3:
        return passed(f"mean difference {e1:.1f} inside, {e2:.1f} outside")
    t.fail(f"{what}: far from the mask's edge the result differs from the selected image by "
           f"{e1:.0f} (inside the disc) and {e2:.0f} (outside) grey levels.")
