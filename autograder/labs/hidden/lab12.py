"""Lab 12 - stereo: hidden checks (instructor's copy and container only).

Every input is generated here from seeds and parameters written in this file.
Disparity maps are judged against the reference solution's bad-pixel rates on
these scenes, measured once and written here (the stored figures file only
covers the public scenes), with the same margin as the public checks.
"""

from __future__ import annotations

import numpy as np

from fixtures import lab12 as truth

from ...engine.checks import passed
from ..lab12 import (STEREO_TIMEOUT, MatchingMistakes, block_matcher, block_size_probe, call_rectify, ex1, ex2, ex3, ex4, ex5, ex6, ext1,
                     expect_disparity, judge_block_matching, judge_depth, judge_disparity, judge_last_column,
                     judge_patterns, judge_rows, judge_sl_depth, judge_triangulation, smoothness_probe)


# The reference solution's bad-pixel rates on the scenes below, and for block matching the
# legitimate matchers' (fixtures.make_lab12_figures.block_matching_figures); tests/test_lab12.py
# re-measures them, so they cannot go stale.
REFERENCE_BAD = {"ncc": 0.044, "dp_stereo": 0.214}
BLOCK_MATCHING = {"block_size": 9, "reference": 0.05, "legitimate": 0.0618, "far_legitimate": 0.0}


def block_matching_scene():
    return truth.random_dot_scene(seed=4242, n_boxes=3, noise=3.0)


def ncc_scene():
    return truth.with_gain(truth.random_dot_scene(seed=777, n_boxes=2), 0.5, 30.0)


def dp_scene():
    rng = np.random.default_rng(2024)
    wall = truth.fronto_plane(truth.random_dot_texture(rng, (150, 150)), 11.0, (0.0, 0.0), 16.0)
    flat = truth.random_dot_texture(rng, (40, 40), blur=1.5, contrast=2.0 / 127.0, mean=90.0)
    square = truth.fronto_plane(flat, 3.6, (-0.3, 0.0), 2.0)
    return truth.render_pair("weak square on dots", [square, wall], noise=1.0, seed=11)


@ex1.check("hidden: triangulate 200 points seen by two random cameras", points=1, hidden=True)
def hidden_triangulate_many(t):
    P1, P2, X, pts1, pts2 = truth.general_points(seed=90210, n=200)
    return judge_triangulation(t, "triangulate(P1, P2, pts1, pts2)",
                               t.call("triangulate", P1, P2, pts1, pts2), P1, P2, pts1, pts2, X)


@ex2.check("hidden: depth of a noisy disparity map with holes", points=1, hidden=True)
def hidden_depth_map(t):
    rng = np.random.default_rng(1234)
    d = rng.uniform(0.5, 70.0, size=(37, 53))
    d[rng.random(d.shape) < 0.2] = 0.0
    d[rng.random(d.shape) < 0.05] = np.nan
    d[rng.random(d.shape) < 0.05] = -1.0
    judge_depth(t, "depth_from_disparity(37 x 53 map with holes, f=725.5, baseline=0.54)",
                t.call("depth_from_disparity", d, 725.5, 0.54), d, 725.5, 0.54)


@ex3.check("hidden: rectify a pair turned by 12 degrees", points=1, hidden=True)
def hidden_rectify(t):
    pair = truth.unrectified_pair(seed=31337, max_angle_deg=12.0)
    _, _, H1, H2 = call_rectify(t, pair)
    worst, _ = judge_rows(t, pair, H1, H2)
    return passed(f"rows agree within {worst:.2g} px")


@ex4.check("hidden: block matching on noisy random-dot planes", points=2, hidden=True,
           timeout=STEREO_TIMEOUT)
def hidden_block_matching(t):
    scene = block_matching_scene()
    got = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity, block_size=9)
    return judge_block_matching(t, "block_matching(left, right, block_size=9)", got, scene, BLOCK_MATCHING,
                                again=block_matcher(t, scene, block_size=9), show=False)


@ext1.check("hidden: NCC on random-dot planes with a darker right view", points=1, hidden=True,
            timeout=STEREO_TIMEOUT)
def hidden_ncc(t):
    scene = ncc_scene()
    got = t.call("block_matching", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity, block_size=9, cost="ncc")
    what = "block_matching(left, 0.5 * right + 30, cost=\"ncc\")"
    return judge_disparity(t, what, got, scene, REFERENCE_BAD["ncc"], show=False,
                           probe=block_size_probe(t, what, scene, cost="ncc"),
                           mistakes=MatchingMistakes(scene, 9, "ncc"))


@ex5.check("hidden: dp_stereo on a weakly textured square over random dots", points=2, hidden=True,
           timeout=STEREO_TIMEOUT)
def hidden_dp(t):
    scene = dp_scene()
    got = t.call("dp_stereo", np.array(scene.left), np.array(scene.right),
                 max_disparity=scene.max_disparity)
    got = expect_disparity(t, "dp_stereo(left, right)", got, scene)  # a map, before its columns are read
    judge_last_column(t, "dp_stereo(left, right)", got, scene)
    return judge_disparity(t, "dp_stereo(left, right)", got, scene, REFERENCE_BAD["dp_stereo"],
                           show=False, probe=lambda: smoothness_probe(t, scene))


@ex6.check("hidden: 10-bit patterns for a 1024-pixel projector, and decoding them", points=2,
           hidden=True)
def hidden_structured_light(t):
    judge_patterns(t, 1024, 10)
    depth, f, baseline = truth.structured_light_scene("tilted")
    images = truth.simulate_structured_light(depth, f, baseline, 5)
    judge_sl_depth(t, "depth_from_structured_light(5 images)",
                   t.call("depth_from_structured_light", images, f, baseline), images, f, baseline, depth)
    return passed("patterns bit-exact and decoding exact")
