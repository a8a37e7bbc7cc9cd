"""Lab 11 - two-view geometry: hidden checks (instructor copy and container only).

Every input is drawn from ``t.rng``, the submission's own generator (or, for the
properties, from Hypothesis under the submission's seed), on the same ground-truth
generators as the public checks.
"""

from __future__ import annotations

import numpy as np

from ...engine import strategies as st

from fixtures import lab11 as truth
from fixtures.lab12 import triangulation_variants

from ...engine.checks import partial
from ..lab11 import (E_COLUMN_ORDER, PIPELINE_TIMEOUT, call_reconstruction, conditioned_distance, ex1, ex2, ex3, ex4,
                     ex5, ex6, judge_epipoles,
                     judge_lines, judge_pipeline_F, judge_projective, judge_structure, judge_triangulation)
from ._draws import seed, uniform

HIDDEN_SEEDS = st.integers(10**6, 2 * 10**6)


@ex1.check("hidden: triangulate noisy far points (about 1 px noise, depth 20-60)", points=1, hidden=True)
def hidden_triangulate_far_noisy(t):
    views, pts1, pts2 = truth.noisy_triangulation_problem(
        seed(t.rng), n=int(t.rng.integers(60, 101)), sigma=uniform(t.rng, 0.8, 1.2),
        depth_range=(20.0, 60.0), baseline=(2.0, 3.0))
    got = t.call("triangulate", views.P1, views.P2, pts1, pts2)
    # What linear triangulation (two rows per view, unscaled) reaches on these data, for the message.
    linear = triangulation_variants(views.P1, views.P2, pts1, pts2)["2 rows per view"]
    gold = {"reprojection": float(0.5 * (np.linalg.norm(truth.project(views.P1, linear) - pts1, axis=1)
                                         + np.linalg.norm(truth.project(views.P2, linear) - pts2, axis=1)).mean())}
    return judge_triangulation(t, "triangulate(P1, P2, noisy pts1, noisy pts2)", got, views, pts1, pts2,
                               gold=gold)


@ex1.check("hidden: triangulate exact problems with 640 x 480 cameras", points=1, hidden=True)
def hidden_triangulate_property(t):
    def holds(case):
        seed, n = case
        views = truth.two_views(seed, n=n, width=640, height=480)
        judge_triangulation(t, f"triangulate(P1, P2, pts1, pts2) with N={n}",
                            t.call("triangulate", views.P1, views.P2, views.pts1, views.pts2), views)

    t.for_all(st.tuples(HIDDEN_SEEDS, st.integers(2, 30)), holds, max_examples=8,
              describe=lambda c: f"two_views(seed={c[0]}, n={c[1]}, 640 x 480)")


@ex2.check("hidden: epipolar lines of a rectified pair are horizontal", points=1, hidden=True)
def hidden_lines_rectified(t):
    views = truth.sideways_views(seed=seed(t.rng), n=15)
    F = -uniform(t.rng, 3.0, 10.0) * views.F   # F at another scale and sign: lines are normalised
    judge_lines(t, "epipolar_lines(F, pts1) for a rectified pair",
                t.call("epipolar_lines", F, views.pts1), F, views.pts1)


@ex3.check("hidden: essential_8point from exactly 8 correspondences", points=1, hidden=True)
def hidden_essential_8(t):
    views = truth.two_views(seed=seed(t.rng), n=8)
    judge_projective(t, "essential_8point(pts1, pts2, K1, K2) with N=8",
                     t.call("essential_8point", views.pts1, views.pts2, views.cam1.K, views.cam2.K),
                     views.E, {"pts1 and pts2 are swapped (this is E^T)": views.E.T, E_COLUMN_ORDER: views.E.T},
                     tolerance=1e-5)


@ex4.check("hidden: fundamental_8point on exact problems of any size", points=1, hidden=True)
def hidden_fundamental_property(t):
    def holds(case):
        seed, n = case
        views = truth.two_views(seed, n=n, width=640, height=480)
        judge_projective(t, f"fundamental_8point(pts1, pts2) with N={n}",
                         t.call("fundamental_8point", views.pts1, views.pts2), views.F,
                         truth.fundamental_mistakes(views.F), tolerance=1e-4,
                         distance=conditioned_distance(views.pts1, views.pts2))

    t.for_all(st.tuples(HIDDEN_SEEDS, st.integers(8, 60)), holds, max_examples=8,
              describe=lambda c: f"two_views(seed={c[0]}, n={c[1]}, 640 x 480)")


@ex5.check("hidden: epipoles of a forward motion with a tiny scale of F", points=1, hidden=True)
def hidden_epipoles_forward(t):
    views = truth.forward_views(seed=seed(t.rng))
    scale = float(f"{10 ** t.rng.uniform(-7.0, -5.0):.2g}")
    judge_epipoles(t, f"epipoles({scale:g} * F)", t.call("epipoles", scale * views.F), views)




@ex6.check("hidden: two_view_reconstruction on another rendered pair", points=2, hidden=True,
           timeout=PIPELINE_TIMEOUT)
def hidden_pipeline_other_scene(t):
    scene = seed(t.rng)
    pair = truth.rendered_pair(seed=scene)
    truth._PAIRS.pop((scene, 320, 240), None)   # drawn for this submission only: not kept in memory
    F, pts1, pts2, points3d = call_reconstruction(t, pair)
    epipolar = judge_pipeline_F(t, pair, F)
    structure = judge_structure(t, pair, pts1, pts2, points3d, show=False, F=F)
    return partial(min(epipolar.fraction, structure.fraction), f"F: {epipolar.message}; 3D points: "
                   f"{structure.message}")
