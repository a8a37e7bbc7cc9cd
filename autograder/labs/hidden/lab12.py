"""Lab 12 - stereo: hidden checks (instructor's copy and container only).

Every input is drawn from ``t.rng``, the submission's own generator. The stereo scenes keep
their geometry (written here) and draw their sensor noise, or the right view's gain and
offset: disparity maps are judged against the reference solution's bad-pixel rates on these
scenes, the worst over many draws, measured and written here (the stored figures file only
covers the public scenes), with the same margin as the public checks.
"""

from __future__ import annotations

import numpy as np

from dataclasses import replace

from fixtures import lab12 as truth

from ...engine.checks import passed
from ..lab12 import (STEREO_TIMEOUT, MatchingMistakes, block_matcher, block_size_probe, call_rectify, ex1, ex2, ex3, ex4, ex5, ex6, ext1,
                     expect_disparity, judge_block_matching, judge_depth, judge_disparity, judge_last_column,
                     judge_patterns, judge_rows, judge_sl_depth, judge_triangulation, name_no_backtracking,
                     smoothness_probe)
from ._draws import seed, uniform


# The reference solution's bad-pixel rates on the scenes below, and for block matching the
# legitimate matchers' (fixtures.make_lab12_figures.block_matching_figures): the worst over
# 20 draws of each scene (block matching: reference 4.8 to 5.0%, legitimate 6.0 to 6.2%; NCC
# 4.3 to 4.4%; DP 17 to 25%: on the nearly flat square the noise decides much);
# tests/test_lab12.py re-measures some draws, so they cannot go stale.
REFERENCE_BAD = {"ncc": 0.044, "dp_stereo": 0.25}
BLOCK_MATCHING = {"block_size": 9, "reference": 0.05, "legitimate": 0.0618, "far_legitimate": 0.0}


def with_noise(scene, noise: float, rng):
    """``scene`` with Gaussian sensor noise of ``noise`` grey levels on both views, drawn
    from ``rng`` (as ``fixtures.lab12.render_pair`` adds it)."""
    left, right = (np.clip(np.rint(image + rng.normal(0, noise, image.shape)), 0, 255).astype(np.uint8)
                   for image in (scene.left, scene.right))
    left.setflags(write=False)
    right.setflags(write=False)
    return replace(scene, left=left, right=right)


def block_matching_scene(rng):
    """Three random-dot squares before a wall (fixed), with drawn noise of 3 grey levels."""
    return with_noise(truth.random_dot_scene(seed=4242, n_boxes=3), 3.0, np.random.default_rng(seed(rng)))


def darker(rng) -> tuple[float, float]:
    """A drawn gain (0.4 to 0.6) and offset (20 to 40 grey levels) of the NCC scene's right view."""
    return uniform(rng, 0.4, 0.6), uniform(rng, 20.0, 40.0, 1)


def ncc_scene(gain: float, offset: float):
    """Two random-dot squares before a wall (fixed), the right view ``gain * right + offset``."""
    return truth.with_gain(truth.random_dot_scene(seed=777, n_boxes=2), gain, offset)


def dp_scene(rng):
    """A weakly textured square over random dots (fixed), with drawn noise of 1 grey level."""
    textures = np.random.default_rng(2024)
    wall = truth.fronto_plane(truth.random_dot_texture(textures, (150, 150)), 11.0, (0.0, 0.0), 16.0)
    flat = truth.random_dot_texture(textures, (40, 40), blur=1.5, contrast=2.0 / 127.0, mean=90.0)
    square = truth.fronto_plane(flat, 3.6, (-0.3, 0.0), 2.0)
    return truth.render_pair("weak square on dots", [square, wall], noise=1.0, seed=seed(rng))


@ex1.check("hidden: triangulate about 200 points seen by two random cameras", points=1, hidden=True)
def hidden_triangulate_many(t):
    P1, P2, X, pts1, pts2 = truth.general_points(seed=seed(t.rng), n=int(t.rng.integers(150, 251)))
    return judge_triangulation(t, f"triangulate(P1, P2, pts1, pts2) with N={len(X)}",
                               t.call("triangulate", P1, P2, pts1, pts2), P1, P2, pts1, pts2, X)


@ex2.check("hidden: depth of a noisy disparity map with holes", points=1, hidden=True)
def hidden_depth_map(t):
    rng = t.rng
    shape = (int(rng.integers(30, 46)), int(rng.integers(45, 61)))
    f, baseline = uniform(rng, 600.0, 800.0, 1), uniform(rng, 0.4, 0.7, 3)
    d = rng.uniform(0.5, 70.0, size=shape)
    d[rng.random(d.shape) < 0.2] = 0.0
    d[rng.random(d.shape) < 0.05] = np.nan
    d[rng.random(d.shape) < 0.05] = -1.0
    judge_depth(t, f"depth_from_disparity({shape[0]} x {shape[1]} map with holes, f={f:g}, baseline={baseline:g})",
                t.call("depth_from_disparity", d, f, baseline), d, f, baseline)


@ex3.check("hidden: rectify a pair turned by up to 12 degrees", points=1, hidden=True)
def hidden_rectify(t):
    pair = truth.unrectified_pair(seed=seed(t.rng), max_angle_deg=12.0)
    _, _, H1, H2 = call_rectify(t, pair)
    worst, _ = judge_rows(t, pair, H1, H2)
    return passed(f"rows agree within {worst:.2g} px")


@ex4.check("hidden: block matching on noisy random-dot planes", points=2, hidden=True,
           timeout=STEREO_TIMEOUT)
def hidden_block_matching(t):
    scene = block_matching_scene(t.rng)
    got = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity, block_size=9)
    return judge_block_matching(t, "block_matching(left, right, block_size=9)", got, scene, BLOCK_MATCHING,
                                again=block_matcher(t, scene, block_size=9), show=False)


@ext1.check("hidden: NCC on random-dot planes with a darker right view", points=1, hidden=True,
            timeout=STEREO_TIMEOUT)
def hidden_ncc(t):
    gain, offset = darker(t.rng)
    scene = ncc_scene(gain, offset)
    got = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity, block_size=9, cost="ncc")
    what = f"block_matching(left, {gain:g} * right + {offset:g}, cost=\"ncc\")"
    return judge_disparity(t, what, got, scene, REFERENCE_BAD["ncc"], show=False,
                           probe=block_size_probe(t, what, scene, cost="ncc"),
                           mistakes=MatchingMistakes(scene, 9, "ncc"))


@ex5.check("hidden: dp_stereo on a weakly textured square over random dots", points=2, hidden=True,
           timeout=STEREO_TIMEOUT)
def hidden_dp(t):
    scene = dp_scene(t.rng)
    got = t.call("dp_stereo", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity)
    got = expect_disparity(t, "dp_stereo(left, right)", got, scene)  # a map, before its columns are read
    judge_last_column(t, "dp_stereo(left, right)", got, scene)
    return judge_disparity(t, "dp_stereo(left, right)", got, scene, REFERENCE_BAD["dp_stereo"],
                           show=False, probe=lambda: (smoothness_probe(t, scene),
                                                      name_no_backtracking(t, "dp_stereo(left, right)")))


@ex6.check("hidden: 10-bit patterns for a projector of 513 to 1024 pixels, and decoding them", points=2,
           hidden=True)
def hidden_structured_light(t):
    judge_patterns(t, int(t.rng.integers(513, 1025)), 10)
    depth, f, baseline = truth.structured_light_scene("tilted")
    baseline *= uniform(t.rng, 0.8, 1.2)   # the projector's disparities f b / Z scale with it
    n_bits = int(t.rng.integers(5, 8))
    images = truth.simulate_structured_light(depth, f, baseline, n_bits)
    judge_sl_depth(t, f"depth_from_structured_light({n_bits} images)",
                   t.call("depth_from_structured_light", images, f, baseline), images, f, baseline, depth)
    return passed("patterns bit-exact and decoding exact")
