"""Lab 11 - two-view geometry: hidden checks (instructor copy and container only).

Every input comes from seeds written here, on the same ground-truth generators
as the public checks.
"""

from __future__ import annotations

from ...engine import strategies as st

from fixtures import lab11 as truth

from ...engine.checks import partial
from ..lab11 import (PIPELINE_TIMEOUT, call_reconstruction, conditioned_distance, ex1, ex2, ex3, ex4, ex5, ex6, judge_epipoles,
                     judge_lines, judge_pipeline_F, judge_projective, judge_structure, judge_triangulation)

HIDDEN_SEEDS = st.integers(10**6, 2 * 10**6)


# What linear triangulation reaches on this problem (python fixtures/make_lab11_figures.py prints it).
HIDDEN_TRIANGULATION = dict(seed=9101, n=80, sigma=1.0, depth_range=(20.0, 60.0), baseline=(2.0, 3.0))
HIDDEN_TRIANGULATION_GOLD = {"reprojection": 0.6135768339325061, "median_error": 0.04635259379931268}


@ex1.check("hidden: triangulate noisy far points (1 px noise, depth 20-60)", points=1, hidden=True)
def hidden_triangulate_far_noisy(t):
    views, pts1, pts2 = truth.noisy_triangulation_problem(**HIDDEN_TRIANGULATION)
    got = t.call("triangulate", views.P1, views.P2, pts1, pts2)
    return judge_triangulation(t, "triangulate(P1, P2, noisy pts1, noisy pts2)", got, views, pts1, pts2,
                               gold=HIDDEN_TRIANGULATION_GOLD)


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
    views = truth.sideways_views(seed=9201, n=15)
    judge_lines(t, "epipolar_lines(F, pts1) for a rectified pair",
                t.call("epipolar_lines", -7.0 * views.F, views.pts1), -7.0 * views.F, views.pts1)


@ex3.check("hidden: essential_8point from exactly 8 correspondences", points=1, hidden=True)
def hidden_essential_8(t):
    views = truth.two_views(seed=9301, n=8)
    judge_projective(t, "essential_8point(pts1, pts2, K1, K2) with N=8",
                     t.call("essential_8point", views.pts1, views.pts2, views.cam1.K, views.cam2.K),
                     views.E, {"pts1 and pts2 are swapped (this is E^T)": views.E.T}, tolerance=1e-5)


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
    views = truth.forward_views(seed=9501)
    judge_epipoles(t, "epipoles(1e-6 * F)", t.call("epipoles", 1e-6 * views.F), views)




@ex6.check("hidden: two_view_reconstruction on another rendered pair", points=2, hidden=True,
           timeout=PIPELINE_TIMEOUT)
def hidden_pipeline_other_scene(t):
    pair = truth.rendered_pair(seed=9601)
    F, pts1, pts2, points3d = call_reconstruction(t, pair)
    epipolar = judge_pipeline_F(t, pair, F)
    structure = judge_structure(t, pair, pts1, pts2, points3d, show=False, F=F)
    return partial(min(epipolar.fraction, structure.fraction), f"F: {epipolar.message}; 3D points: "
                   f"{structure.message}")
