"""Naming a mistake by repairing the student's own code (issue 35): variants of the student's
functions run in a companion sandbox, and a change is told only when it makes the answers the
reference's on the failing inputs, the other calls and confirmation inputs."""

from __future__ import annotations

import ast
import dataclasses
import re
import textwrap
from pathlib import Path

import numpy as np
import pytest

from autograder.engine import traced
from autograder.engine.mutants import repair
from autograder.loading.parsing import parse
from autograder.engine.mutants.operators import Mutant
from autograder.engine.runner import grade
from autograder.sandbox.supervisor import Limits, Sandbox
from conftest import check_results, edited_reference, failing_messages, mutant, submission_from_source, told_or_pointed

SMALL = Limits(call_timeout=5.0)


def _told_in(told: str, message: str) -> bool:
    """Whether a message tells one of the ways ``told`` lists (" || " between them): the operator's change,
    or the same place made as the reference writes it (aligned.py)."""
    return any(way in message for way in told.split(" || "))


# ------------------------------------------------------------------ the sandbox's variants
@pytest.fixture
def box(tmp_path):
    folder = submission_from_source(tmp_path, "student", """
        import numpy as np

        def helper(x):
            return x + 1

        def graded(x):
            return helper(x) * 2
    """)
    with Sandbox(folder, SMALL) as sandbox:
        yield sandbox


def test_a_variant_of_a_helper_is_the_one_the_function_calls(box):
    companion = box.companion()
    outcome = companion.call_variant("student", "def helper(x):\n    return x - 1\n", "graded",
                                     [((3,), {}), ((np.arange(3.0),), {})], timeout=5.0)
    assert outcome.ok, outcome.message
    assert outcome.value[0] == 4
    np.testing.assert_array_equal(outcome.value[1], [-2.0, 0.0, 2.0])
    # the module itself is left as it was, in the companion and in the student's own worker
    assert companion.call("student", "graded", (3,)).value == 8
    assert box.call("student", "graded", (3,)).value == 8


def test_an_unchanged_helpers_answers_are_kept_across_variants(tmp_path):
    """A helper the rewrite leaves alone, calling nothing it changes, answers a variant's call as it
    answered the same arguments for an earlier variant (its work is not done again); a helper that
    calls a changed one, or writes into its arguments, runs each time."""
    folder = submission_from_source(tmp_path, "student", """
        import numpy as np
        RUNS = {"slow": 0, "writer": 0, "caller": 0}

        def slow(x):
            RUNS["slow"] += 1
            return np.asarray(x, float) * 10

        def changed(x):
            return x

        def caller(x):
            RUNS["caller"] += 1
            return changed(x)

        def writer(x):
            RUNS["writer"] += 1
            x[0] = -1
            return x.sum()

        def graded(x):
            return slow(x).sum() + caller(x).sum() + writer(np.array(x, float)), dict(RUNS)
    """)
    with Sandbox(folder, SMALL) as sandbox:
        companion = sandbox.companion()
        answers = []
        for rewrite in ("def changed(x):\n    return x + 1\n", "def changed(x):\n    return x + 2\n"):
            outcome = companion.call_variant("student", rewrite, "graded", [((np.arange(3.0),), {})], timeout=5.0)
            assert outcome.ok, outcome.message
            answers.append(outcome.value[0])
    (first, runs_first), (second, runs_second) = answers
    assert (first, second) == (30.0 + 6.0 + 2.0, 30.0 + 9.0 + 2.0)   # each variant's own change shows
    assert runs_second["slow"] == runs_first["slow"] == 1               # kept from the first variant
    assert runs_second["caller"] == 2 and runs_second["writer"] == 2     # run again each time


def test_each_call_of_a_variant_answers_or_raises_on_its_own(box):
    source = "def helper(x):\n    return 1 / x\n"
    outcome = box.companion().call_variant("student", source, "graded", [((0,), {}), ((2,), {})], timeout=5.0)
    assert outcome.ok
    assert outcome.value[0] == {"__error__": "ZeroDivisionError: division by zero"}
    assert outcome.value[1] == 1.0


def test_a_variant_that_hangs_costs_the_students_worker_nothing(box):
    before = box.call("student", "graded", (1,))
    outcome = box.companion().call_variant("student", "def helper(x):\n    while True:\n        pass\n", "graded",
                                           [((1,), {})], timeout=0.5)
    assert not outcome.ok and outcome.kind in ("timeout", "budget")
    assert box.restarts == 0 and box.student_seconds == pytest.approx(before.seconds, abs=0.05)
    assert box.call("student", "graded", (1,)).value == 4


def test_a_variant_meets_the_same_forbidden_calls(tmp_path):
    folder = submission_from_source(tmp_path, "student", """
        import cv2
        import numpy as np

        def graded(src, dst):
            return np.eye(3)
    """)
    source = "def graded(src, dst):\n    return cv2.findHomography(src, dst)[0]\n"
    points = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], np.float64)
    with Sandbox(folder, SMALL) as sandbox:
        outcome = sandbox.companion().call_variant("student", source, "graded", [((points, points), {})],
                                                   timeout=5.0, forbid=("cv2.findHomography",))
    assert outcome.ok
    assert outcome.value[0]["__error__"].startswith("ForbiddenCall")


def test_the_companion_closes_with_its_sandbox(tmp_path):
    folder = submission_from_source(tmp_path, "student", "def graded(x):\n    return x\n")
    sandbox = Sandbox(folder, SMALL)
    companion = sandbox.companion()
    assert companion is not sandbox and sandbox.companion() is companion
    assert companion.limits.memory == sandbox.limits.memory // 2   # the two hold at most 1.5 shares
    assert companion.call("student", "graded", (5,)).value == 5
    sandbox.close()
    assert companion._closed


# ------------------------------------------------------------------ judging and showing
def test_right_is_the_reference_up_to_rounding_not_merely_near():
    H = np.array([[1.0, 0.2, 30.0], [0.1, 0.9, -4.0], [1e-4, 2e-4, 1.0]])
    assert repair.right(H * (1 + 1e-9), H)
    assert repair.right(-3.0 * H, H)                   # a homography up to scale and sign
    assert not repair.right(H + 1e-2, H)
    points = np.array([[1.0, 2.0], [np.nan, np.nan]])
    assert repair.right(points.copy(), points)
    assert not repair.right(np.array([[1.0, 2.0], [3.0, 4.0]]), points)
    image = np.full((40, 40), 100, np.uint8)
    moved = image.copy()
    moved[:, :4] = 255                                  # a thin band drawn elsewhere: not the same image
    assert repair.right(image + 1, image) and not repair.right(moved, image)
    assert not repair.right({"__error__": "ValueError: x"}, H)


def test_right_closely_where_the_students_code_differs_legitimately():
    """Within 1% when the variant is a hundred times nearer the reference than the student's own
    answer (a failing input), or on a confirmation input; never for an answer merely nearer; up to
    scale only where scale is not the student's mistake."""
    points = np.array([[120.0, 80.0], [-40.0, 300.0], [15.0, -7.5]])
    close = points * (1 + 3e-3)
    assert repair.right(close, points)                                   # (a 3x2 array: up to scale)
    assert not repair.right(close, points, projective=False)
    assert repair.right(close, points, student=points + 60, projective=False)
    assert not repair.right(close, points, student=points + 10, projective=False)   # 28 times nearer
    assert repair.right(close, points, confirming=True, projective=False)
    assert not repair.right(points + 10, points, student=points + 1e4, projective=False)   # beyond 1%


def _read(source: str, api=("graded",)):
    source = textwrap.dedent(source)
    tree = ast.parse(source)
    mutants = repair.mutants_of(source, api, phrased=False)
    return repair._Student(source, tree, mutants), mutants["graded"]


def test_a_changed_name_is_shown_with_the_expression_around_it():
    student, mutants = _read("""
        def graded(std_l, std_r):
            denominator = std_l * std_l
            return denominator
    """)
    shown = {student.shown(m.edits[0]) for m in mutants if m.operator == "other_name"}
    assert (3, "std_l * std_l", "std_r * std_l") in shown
    assert (3, "std_l * std_l", "std_l * std_r") in shown


# ------------------------------------------------------------------ whole gradings
# Both of view 2's rows made with camera 1's third row: a line copied and half edited, twice.
# No single change of the reference reproduces it (the error model names nothing); two changes of
# the student's own code repair it.
_VIEW_2_ROWS = [("pts2[:, :1] * P2[2] - P2[0],", "pts2[:, :1] * P1[2] - P2[0],"),
                ("pts2[:, 1:] * P2[2] - P2[1],", "pts2[:, 1:] * P1[2] - P2[1],")]


def test_a_slip_made_twice_is_told_as_the_two_changes_that_repair_it(tmp_path):
    result = grade(edited_reference(tmp_path, "lab12_stereo", *_VIEW_2_ROWS), ["lab12.ex1"], pictures="none",
                   include_hidden=False)
    told = [c for c in check_results(result, "lab12.ex1") if c.mistake.startswith(repair.MISTAKE)]
    assert told, [c.message for c in check_results(result, "lab12.ex1")]
    assert "changing `pts2[:, :1] * P1[2]` to `pts2[:, :1] * P2[2]`" in told[0].message
    assert "`pts2[:, 1:] * P1[2]` to `pts2[:, 1:] * P2[2]`" in told[0].message


_LOOP_TRIANGULATION = """
    def triangulate(P1, P2, pts1, pts2):
        P1, P2 = np.asarray(P1, np.float64), np.asarray(P2, np.float64)
        single = np.ndim(pts1) == 1
        pts1, pts2 = np.atleast_2d(np.asarray(pts1, np.float64)), np.atleast_2d(np.asarray(pts2, np.float64))
        out = []
        for (x1, y1), (x2, y2) in zip(pts1, pts2):
            A = np.array([x1 * P1[2] - P1[0], y1 * P1[2] - P1[1], x2 * P2[2] - P2[0], y2 * P2[2] - P2[1]])
            X = np.linalg.svd(A)[2][-1]
            out.append(X[:3] / X[2])
        out = np.array(out)
        return {one}
    """


@pytest.mark.parametrize("one", ["out[0] if single else out", "out"])
def test_a_single_pair_answered_either_way_confirms_the_same_repair(tmp_path, one):
    """Lab 11's triangulate divided by Z where w belongs: one pair given alone (a confirmation input) gives (3,)
    in the lab 12 reference's way, (1, 3) in lab 11's; the API says neither, so either confirms the repair --
    the (3,) one was refused it on three checks of four."""
    result = grade(mutant(tmp_path, "lab11_two_view", _LOOP_TRIANGULATION.format(one=one)), ["lab11.ex1"],
                   pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab11.ex1") if c.score < c.max_score]
    assert failed and all(told_or_pointed(c, failed, "changing `X[:3] / X[2]` to `X[:3] / X[-1]`") for c in failed), \
        [c.message for c in failed]


def test_three_slips_get_no_repair(tmp_path):
    """No one change and no pair repairs them: nothing is claimed (a pair that mends two of them
    gives answers still wrong, and is not told)."""
    edits = [_VIEW_2_ROWS[0], ("X = X[:, :3] / X[:, 3:]", "X = X[:, :3] / X[:, 2:3]"),
             ("pts1[:, 1:] * P1[2] - P1[1],", "pts1[:, 1:] * P1[2] - P1[0],")]
    result = grade(edited_reference(tmp_path, "lab12_stereo", *edits), ["lab12.ex1"], pictures="none",
                   include_hidden=False)
    checks = check_results(result, "lab12.ex1")
    assert any(c.score < c.max_score for c in checks)
    assert not any("Trying small changes" in c.message for c in checks)


def test_the_reference_is_never_told_a_repair(tmp_path):
    result = grade(edited_reference(tmp_path, "lab12_stereo"), ["lab12.ex1"], pictures="none", include_hidden=False)
    assert all(c.score == c.max_score for c in check_results(result, "lab12.ex1"))


def test_changes_of_the_students_own_code_only():
    """A function applied where it does not belong, one mistaken for its sibling, a reshape for a
    transpose: offered for the student's code (shown, not told), never as a mutant of the reference."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(s, X, P):
            x = (P @ X.T).T
            return np.tan(s) * np.sin(s) + X.reshape(3, 2) + x[:, :2]
    """)
    student = {(m.operator, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]}
    assert {("unwrap", None), ("function", "np.cos"), ("function", "np.arctan"), ("transpose", "for_reshape"),
            ("inverse", "wrap"), ("dehomogenise", 2)} <= student
    reference = {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]}
    assert not reference & {"unwrap", "function", "dehomogenise"}
    assert ("inverse", "wrap") not in {(m.operator, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"})["graded"]}


def test_a_default_written_out_a_count_for_a_share_and_twin_names_crossed_in_one_entry():
    """`_pyramid(a, 4)` beside `levels=4` (the parameter where its default is written), `w = best.sum()`
    (a share where a count is), `beta * cy + (1 - alpha) * cx` (cx and cy exchanged throughout one entry,
    and each of two pairs of twins in one formula),
    and a method taken on a sum bracketed (`(x - 0.5).astype(...)`, not `x - 0.5.astype(...)`): the
    student's code only."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(a, cx, cy, levels=4, radius=1):
            best = a > 0
            w = best.sum()
            entry = np.sin(a) * cy + (1 - np.cos(a)) * cx
            column = ((a + 0.5) * 3 - 0.5).astype(np.int64)
            y_d = cy * a + p2 * (a + 2 * cy ** 2) + 2 * p1 * cx * cy
            return _pyramid(a, 4), w, [entry, column], radius + 1, y_d
    """)
    student = {(m.operator, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]}
    assert {("default_written", "levels"), ("fraction", "best.mean()"),
            ("crossed", "np.sin(a) * cx + (1 - np.cos(a)) * cy"),
            # (a formula holding two pairs of twins, cx/cy and p1/p2: each pair exchanged on its own -- 07e lab09/08)
            ("crossed", "cy * a + p1 * (a + 2 * cy ** 2) + 2 * p2 * cx * cy"),
            ("crossed", "cx * a + p2 * (a + 2 * cx ** 2) + 2 * p1 * cy * cx"),
            ("astype_float", "((a + 0.5) * 3 - 0.5).astype(np.float64)")} <= student
    assert ("default_written", "radius") not in student   # (1 is everywhere: no default told from it)
    for operator, text in student:   # every change written out is code
        if isinstance(text, str) and operator in ("fraction", "crossed", "astype_float", "reduced", "middle_axis"):
            ast.parse(text)
    reference = {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]}
    assert not reference & {"default_written", "fraction", "crossed"}


def test_a_loop_restarting_from_a_fixed_item_of_its_input_is_offered_the_running_result():
    """`panorama = images[0]`, then `panorama = stitch(images[0], image)` each time round: the running
    result where the loop restarts from the first item (a stale name: only the first and last stitched)."""
    source = textwrap.dedent("""
        def graded(images):
            panorama = images[0]
            for image in images[1:]:
                panorama = stitch(images[0], image)
            return panorama
    """)
    student = [(m.operator, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]]
    assert ("carry", "panorama") in student


def test_a_fixed_item_read_in_a_loop_over_its_items_and_a_factor_divided_first():
    """`disparity[-1]` in a backtracking loop over x that writes `disparity[x - 1]`: the column just chosen
    (`disparity[x]`) or the loop's other index; `u * (n / w)` (a rounded factor) regrouped to divide last.
    Student-only; a fixed item outside a loop, or of an array the loop never indexes by its variable, is not."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(energy, ramp, u, n, w):
            disparity = np.empty(energy.shape[:2], dtype=int)
            disparity[-1] = np.argmin(energy[-1], axis=1)
            for x in range(len(energy) - 1, 0, -1):
                jump = ramp[disparity[-1]] + energy[0]
                disparity[x - 1] = np.argmin(energy[x - 1] + jump, axis=1)
            return disparity, (u * (n / w)).astype(int)
    """)
    items = [m for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator == "loop_item"]
    # (energy[0] in the loop too: the loop indexes energy by x as well)
    assert {m.edits[0][3] for m in items} == {"disparity[x]", "disparity[x - 1]", "energy[x]", "energy[x - 1]"}
    assert {m.line for m in items} == {8}   # (not the items read before the loop)
    regrouped = [m for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator == "regroup"]
    tree = ast.parse(source)
    made = {ast.unparse(repair._MAKE["regroup"](list(ast.walk(tree.body[1]))[m.edits[0][1]], m.edits[0][3]))
            for m in regrouped}
    assert "u * n / w" in made
    assert "loop_item" not in {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]}


def test_a_ufuncs_output_buffer_made_as_a_copy_of_its_data_is_offered_zeros():
    """`depth = d.copy()` then `np.divide(fb, d, out=depth, where=ok)`: where ok is false the buffer keeps d;
    a buffer never given as a masked ufunc's out= is left alone."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(disparity, fb):
            d = np.asarray(disparity, dtype=np.float64)
            depth = d.copy()
            kept = d.copy()
            np.divide(fb, d, out=depth, where=d > 0)
            return depth, kept
    """)
    made = [(m.line, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
            if m.operator == "initial"]
    assert made == [(6, "np.zeros_like(d, dtype=np.float64)")]


def test_an_angle_conversion_upside_down_and_a_list_started_with_the_first_items_result():
    """`a * 180 / np.pi` where `a * np.pi / 180` belongs (the factor upside down, one change of the whole
    product, not of its inner half); `views = [f(X, fs[0])]` then `for f in fs: views.append(f(X, f))` (the
    first item twice): the list started empty. Student-only."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(angle_deg, X, fs):
            a = angle_deg * 180.0 / np.pi
            views = [project(X, fs[0])]
            for f in fs:
                views.append(project(X, f))
            kept = [project(X, fs[0])]
            return np.cos(a), views, kept
    """)
    student = [(m.operator, m.line, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]]
    assert [c for c in student if c[0] == "conversion_inverted"] == [("conversion_inverted", 5, "angle_deg * np.pi / 180.0")]
    assert [c for c in student if c[0] == "initial"] == [("initial", 6, "[]")]   # (not `kept`: no loop appends to it)
    assert not {"conversion_inverted", "initial"} & {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]}


def test_two_entries_of_a_sequence_written_in_each_others_place():
    """A size given as (rows, cols), a matrix row's entries, names assigned the other way round: every
    pair of a short tuple or list is exchanged (the student's code only); a stacking call's pieces are
    `stack_order`'s, not exchanged twice."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(image, tx, ty):
            w, h = image.shape[:2]
            M = np.float32([[1, 0, tx], [0, ty, 1]])
            return M, (h, w), np.hstack([M, M.T])
    """)
    swapped = {repair.ast.unparse(repair._MAKE["swap_items"](node, m.edits[0][3]))
               for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator == "swap_items"
               for node in [list(ast.walk(ast.parse(source).body[1]))[m.edits[0][1]]]}
    assert {"(h, w)", "(w, h)", "[0, 1, ty]", "[ty, 0, 1]", "[tx, 0, 1]"} <= swapped
    assert "[M.T, M]" not in swapped and "[0, ty, 1]" not in swapped   # (stacked pieces; two equal entries)
    assert "swap_items" not in {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]}


def test_three_channels_merged_in_reversed_order_are_given_back_in_order():
    """`r, g, b = cv2.split(image)` then `cv2.merge([f(b), f(g), f(r)])` (blind set 2026-12-06d): the outer
    two of three merged channels are exchanged (the B, G, R order reversed), once, as `stack_order`."""
    source = textwrap.dedent("""
        import cv2

        def graded(image):
            r, g, b = cv2.split(image)
            return cv2.merge([b + 1, g + 1, r + 1])
    """)
    fn = ast.parse(source).body[1]
    changed = [(m.operator, repair.ast.unparse(repair._MAKE[m.operator](node, m.edits[0][3])))
               for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
               if m.operator in ("stack_order", "swap_items")
               for node in [list(ast.walk(fn))[m.edits[0][1]]] if isinstance(node, ast.Call)]
    assert ("stack_order", "cv2.merge([r + 1, g + 1, b + 1])") in changed
    assert [text for _, text in changed].count("cv2.merge([r + 1, g + 1, b + 1])") == 1


def test_einsum_subscripts_a_student_gets_wrong_are_offered_right():
    """`np.einsum('ni,nj->ij', ...)` sums the point index the rows keep (blind set 2026-12-06d); an answer's
    axes in another order and an operand used transposed are the neighbours of that slip. Implicit
    subscripts and ellipses are left alone."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(x1, x2, M):
            A = np.einsum('ni,nj->ij', x2, x1)
            B = np.einsum('ij,nj->ni', M, x1)
            return A, B, np.einsum('ij,jk', M, M), np.einsum('...i,...i->...', x1, x1)
    """)
    written = {m.edits[0][3] for m in repair.mutants_of(source, {"graded"})["graded"] if m.operator == "einsum"}
    assert {"'ni,nj->nij'", "'ni,nj->ijn'", "'ni,nj->ji'", "'in,nj->ij'"} <= written, written
    assert {"'ij,nj->in'", "'ji,nj->ni'", "'ij,jn->ni'"} <= written, written
    assert not any("..." in w or w.startswith("'ij,jk") for w in written), written
    fixed = [m for m in repair.mutants_of(source, {"graded"})["graded"] if m.edits[0][3] == "'ni,nj->nij'"]
    assert "the index n is summed over" in fixed[0].sentence, fixed[0]


def test_containers_made_by_hand_a_list_grown_and_a_loop_bound_stored_elsewhere_are_offered():
    """The blind set 2026-12-06e's lab 7 and 8 slips: `np.zeros((h, w))` for an image's black frame (channels and
    dtype lost), `rhs.append([x, y])` where the items belong one by one, a homogeneous row stacked as
    `np.ones(3)`, and RANSAC's adaptive count stored in `n` where the loop tests `needed`; and lab 9's
    `map(pinhole_project, X, fs)`."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(image, A, src):
            h, w = image.shape[:2]
            black = np.zeros((h, w))
            rhs = []
            for x, y in src:
                rhs.append([x, y])
            H = np.vstack([A[:2], np.ones(3)])
            n = len(src)
            needed, drawn = 100, 0
            while drawn < needed:
                drawn += 1
                n = int(np.ceil(drawn / 2))
            views = list(map(np.dot, src, A))
            best = np.zeros((3, len(src)))
            for y in range(3):
                for x in range(len(src) - 1, 0, -1):
                    best[y, x] = x
            top, left = src.min(axis=0)
            shift = np.array([[1.0, 0.0, -top], [0.0, 1.0, -left], [0.0, 0.0, 1.0]])
            end = (left, h - 1 - top)
            return black, rhs, H, n, views, best, shift, end
    """)
    changes = {(m.operator, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]}
    assert ("like_input", "np.zeros_like(image)") in changes
    assert ("append_extend", "rhs.extend([x, y])") in changes
    assert ("last_row", "[0.0, 0.0, 1.0]") in changes
    assert ("store_name", "needed") in changes
    # (and map zipping two iterables where one is meant whole: `map(f, X, fs)`, the blind set's 09/03)
    assert ("map_whole", "map(lambda each_: np.dot(src, each_), A)") in changes
    # (and a value written one place off along its innermost loop: a backtrack's column x - 1 stored in x)
    assert ("index_step", (1, -1)) in changes and ("index_step", (0, -1)) not in changes
    # (and the two offsets of a canvas shift crossed between its rows -- lab 8's 06 -- but never two numbers
    # written out, the 1s and 0s of the matrix's own structure)
    crossed = {m.edits[0][3] for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
               if m.operator == "cross_items"}
    assert (0, 1, 2) in crossed and (0, 1, 0) not in crossed and (0, 1, 1) not in crossed, crossed
    # (and a coordinate counted from the far end, `h - 1 - y`, offered as counted: lab 11's 03)
    assert ("unflip", "top") in changes
    # (never the loop's own counter, set in the loop, nor a name first set after the loop starts)
    assert ("store_name", "drawn") not in changes


def test_a_step_done_to_one_input_only_and_an_argument_another_call_is_given():
    """`xl = xl[:, 0]` with no `xr = xr[:, 0]`: the two done together; `warp(weight, H)` beside
    `warp(image, shift @ H)`: the other call's argument. Student-only, never a step already done."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(xl, xr, image, weight, H, shift):
            xl = np.asarray(xl)
            xr = np.asarray(xr)
            xl = xl[:, 0]
            a = warp(image, shift @ H)
            b = warp(weight, H)
            return xl - xr, a, b
    """)
    made = set()
    fn = ast.parse(source).body[1]
    for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]:
        if m.operator in ("sibling_step", "sibling_argument"):
            node = list(ast.walk(fn))[m.edits[0][1]]
            made.add(ast.unparse(repair._MAKE[m.operator](node, m.edits[0][3])))
    assert "xl, xr = (xl[:, 0], xr[:, 0])" in made and "warp(weight, shift @ H)" in made, made
    assert not any(text.startswith("xl, xr = (np.asarray(xl)") for text in made)   # (xr's is done already)
    assert not {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]} & {"sibling_step", "sibling_argument"}


def test_an_array_made_of_the_wrong_type():
    """A canvas allocated without its dtype (float64, where an image is uint8), a zeros_like of an image
    summed into (uint8 wraps round), focal lengths cast to int: each given the other type."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(image, focal_lengths):
            canvas = np.zeros((4, 4, 3))
            total = np.zeros_like(image)
            f = np.asarray(focal_lengths, dtype=int)
            kept = np.zeros((4, 4), np.float32)
            return canvas, total, f, kept
    """)
    fn = ast.parse(source).body[1]
    made = {ast.unparse(repair._MAKE["dtype"](list(ast.walk(fn))[m.edits[0][1]], m.edits[0][3]))
            for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator == "dtype"}
    assert {"np.zeros((4, 4, 3), dtype=np.uint8)", "np.zeros_like(image, dtype=np.float64)",
            "np.asarray(focal_lengths, dtype=np.float64)"} <= made, made
    assert not any(text.startswith("np.zeros((4, 4), np.float32") for text in made)   # (its dtype is given)


def test_a_comparison_and_a_grouping_a_student_gets_wrong():
    """`x > 0` where `x >= 0` belongs (or the other way round), and `a - b + c` written for `a - (b + c)`
    (or `a / b * c` for `a / (b * c)`, and back): student-only changes."""
    source = textwrap.dedent("""
        def graded(x, a, b, c):
            return x > 0, x - a + b, a / b * c, a - (b - c)
    """)
    fn = ast.parse(source).body[0]
    made = {ast.unparse(repair._MAKE[m.operator](list(ast.walk(fn))[m.edits[0][1]], m.edits[0][3]))
            for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator in ("compare", "regroup")}
    assert {"x >= 0", "x < 0", "x - (a + b)", "a / (b * c)", "a - b - c"} <= made, made
    assert not {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]} & {"compare", "regroup"}


def test_a_use_in_a_long_function_is_compared_with_the_nearest_locals_only():
    """Reading the student's code stays linear in its length: a name is replaced only by the parameters
    and the last few locals assigned before its use, not by every local of a long function."""
    from autograder.engine.mutants import operators

    lines = "\n".join(f"    a{i} = x + {i}" for i in range(60))
    source = f"def graded(x, y):\n{lines}\n    return a59 * a58\n"
    fn = ast.parse(source).body[0]
    replaced = {m.edits[0][3] for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
                if m.operator == "other_name" and isinstance(list(ast.walk(fn))[m.edits[0][1]], ast.Name)
                and list(ast.walk(fn))[m.edits[0][1]].id == "a59"}
    assert replaced and replaced <= {"x", "y"} | {f"a{i}" for i in range(60 - operators._NEAREST_LOCALS, 60)}, replaced


def test_a_loop_started_late_another_column_and_another_axis():
    """`range(1, n)` for `range(n)`, `P[:, 2]` for `P[:, 3]` (a 3x4 camera's fourth column), `axis=1`
    for `axis=2`: student-only (the reference's mutants keep their phrased, narrower set)."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(P, fs, A):
            out = [fs[i] for i in range(1, len(fs))]
            return out, P[:, 2], np.linalg.norm(A, axis=1)
    """)
    fn = ast.parse(source).body[1]
    made = {(ast.unparse(list(ast.walk(fn))[m.edits[0][1]]),
             ast.unparse(repair._MAKE[m.operator](list(ast.walk(fn))[m.edits[0][1]], m.edits[0][3])))
            for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator in ("bound", "axis")}
    assert {("1", "0"), ("2", "3"), ("1", "2"), ("2", "-1")} <= made, made
    reference = {(m.operator, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"})["graded"]}
    assert ("axis", 3) not in reference and ("bound", 0) not in reference


def test_a_translation_matrix_with_an_entry_in_the_wrong_place_is_shown(tmp_path):
    """A student's own translation: `[0, ty, 1]` where the row is `[0, 1, ty]`."""
    folder = edited_reference(tmp_path, "lab07_transformations", (
        "    return _warp(image, translation_matrix(tx, ty))",
        "    M = np.float32([[1, 0, tx], [0, ty, 1]])\n"
        "    return cv2.warpAffine(image, M, image.shape[1::-1], borderMode=cv2.BORDER_CONSTANT)"))
    result = grade(folder, ["lab07.ex1"], pictures="none", include_hidden=False)
    checks = [c for c in check_results(result, "lab07.ex1") if c.score < c.max_score]
    told = [c for c in checks if c.mistake == repair.MISTAKE + "swap_items"]
    assert told and "[0, ty, 1]]` to `" in told[0].message and "[0, 1, ty]]` (line 29)" in told[0].message, \
        [c.message for c in checks]


def test_a_change_the_check_itself_accepts_is_told_for_a_students_own_recipe(tmp_path):
    """A scale written with cv2.resize and a crop (the sheet allows it; its answers differ from the
    reference's warp by a couple of grey levels, more than a repair's rounding) with the size given as
    (rows, cols): the swap is judged by running the failed check again with the changed code."""
    folder = edited_reference(tmp_path, "lab07_transformations", (
        "    return _warp(image, scaling_matrix(sx, sy))",
        "    h, w = image.shape[:2]\n"
        "    big = cv2.resize(image, (int(round(h * sy)), int(round(w * sx))))\n"
        "    out = np.zeros_like(image)\n"
        "    out[:min(h, big.shape[0]), :min(w, big.shape[1])] = big[:h, :w]\n"
        "    return out"))
    result = grade(folder, ["lab07.ex3"], pictures="none", include_hidden=False)
    checks = [c for c in check_results(result, "lab07.ex3") if c.score < c.max_score]
    told = [c for c in checks if c.mistake == repair.MISTAKE + "swap_items"]
    assert told, [c.message for c in checks]
    assert "`(int(round(h * sy)), int(round(w * sx)))` to `(int(round(w * sx)), int(round(h * sy)))`" \
        in told[0].message and "makes `scale` pass this check, and its answers on the" in told[0].message


def test_a_failure_too_small_for_a_repairs_rounding_is_judged_by_the_check(tmp_path):
    """Epipolar lines drawn from x = 0 to the image's height instead of its width: a few lines short,
    the images a fraction of a grey level apart. Only the check tells a change right there; the
    changes that alter nothing on its lines (`/` -> `//`) are not told."""
    folder = edited_reference(tmp_path, "lab11_two_view", (
        "p, q = (0.0, -c / b), (width - 1.0, -(c + a * (width - 1)) / b)",
        "p, q = (0.0, -c / b), (height - 1.0, -(c + a * (height - 1)) / b)"))
    result = grade(folder, ["lab11.ex2"], pictures="none", include_hidden=False)
    checks = [c for c in check_results(result, "lab11.ex2") if c.score < c.max_score]
    assert checks
    told = [c for c in checks if c.mistake.startswith(repair.MISTAKE)]
    # (told by the two places as the reference writes them, or by the pair of ends whole)
    assert told and all(("`height - 1.0` to `width - 1.0` (line 65) and `a * (height - 1)` to `a * (width - 1)` (line 65)"
                         in c.message) or ("(height - 1.0, -(c + a * (height - 1)) / b))` to `" in c.message
                                           and "(width - 1.0, -(c + a * (width - 1)) / b))` (line 65)" in c.message)
                        for c in told), [c.message for c in checks]
    assert not any("//" in c.message for c in checks)


def test_a_function_with_many_right_answers_is_repaired_by_its_check(tmp_path):
    """A rectification through cv2.stereoRectify (right, but far from the reference's own rectifying
    maps) that builds the right image's map with the left camera's rotation: mending it brings its
    answers only somewhat nearer the reference's, so the check itself, run again, judges it."""
    folder = edited_reference(tmp_path, "lab12_stereo", ("def rectify(img_l, img_r, K1, K2, R, T):", """def rectify(img_l, img_r, K1, K2, R, T):
    K1, K2 = np.asarray(K1, np.float64), np.asarray(K2, np.float64)
    h, w = img_l.shape[:2]
    R1, R2, Pn1, Pn2 = cv2.stereoRectify(K1, np.zeros(5), K2, np.zeros(5), (w, h), np.asarray(R, np.float64),
                                         np.asarray(T, np.float64).reshape(3, 1))[:4]
    H1 = Pn1[:, :3] @ R1 @ np.linalg.inv(K1)
    H2 = Pn2[:, :3] @ R1 @ np.linalg.inv(K2)
    return cv2.warpPerspective(img_l, H1, (w, h)), cv2.warpPerspective(img_r, H2, (w, h)), H1, H2


def _unused_rectify(img_l, img_r, K1, K2, R, T):"""))
    result = grade(folder, ["lab12.ex3"], pictures="none", include_hidden=False)
    checks = [c for c in check_results(result, "lab12.ex3") if c.score < c.max_score]
    told = [c for c in checks if c.mistake.startswith(repair.MISTAKE)]
    assert told, [c.message for c in checks]
    assert "changing `Pn2[:, :3] @ R1` to `Pn2[:, :3] @ R2`" in told[0].message
    assert "makes `rectify` pass this check" in told[0].message and not told[0].hint


def test_a_transform_applied_twice_in_an_estimator_is_repaired(tmp_path):
    """E from K^-1-normalised points, then K2^T E K1 applied again: dropping the outer factors gives
    the reference's E exactly on the check's exact correspondences; on noisy derived points every
    8-point answer is its own least squares', so the check, run again, confirms it."""
    folder = edited_reference(tmp_path, "lab11_two_view", (
        "    E = _eight_point_core(x1, x2)\n", "    E = K2.T @ _eight_point_core(x1, x2) @ K1\n"))
    result = grade(folder, ["lab11.ex3"], pictures="none", include_hidden=False)
    checks = [c for c in check_results(result, "lab11.ex3") if c.score < c.max_score]
    told = [c for c in checks if c.mistake.startswith(repair.MISTAKE)]
    assert told, [c.message for c in checks]
    assert "changing `K2.T @ _eight_point_core(x1, x2) @ K1` to `_eight_point_core(x1, x2)`" in told[0].message


def test_a_change_a_check_cannot_tell_from_the_fix_is_not_told_on_numbers_nearer_by_chance(tmp_path):
    """e2 taken as the last row of U: on the hidden check's forward motion e1 = e2, so `U[-1]` -> `Vt[-1]`
    passes that check too; on derived inputs (a perturbed F is no longer of rank 2) nearer or farther
    is chance, so only the change the grading's checks all accept, to `U[:, -1]`, is told."""
    # (the blind set's file itself: a submission's hidden inputs are drawn from its bytes)
    written = Path(__file__).parents[1] / "benchmarks/blind_mistakes/2026-11-28e/lab11_two_view/07_epipoles_U_last_row.py"
    (tmp_path / "lab11_two_view.py").write_text(written.read_text())
    result = grade(tmp_path, ["lab11.ex5"], pictures="none")
    told = [c for c in check_results(result, "lab11.ex5") if c.mistake.startswith(repair.MISTAKE)]
    assert not any("Vt[-1], Vt[-1]" in c.message for c in told), [c.message for c in told]
    assert all("`Vt[-1], U[:, -1]`" in c.message for c in told), [c.message for c in told]


def test_a_degenerate_change_nearer_than_far_off_answers_is_not_told(tmp_path):
    """Laplacian bands built on uint8 images (they wrap round): a pyramid of no levels blends an image
    with itself exactly, so the check passes with `range(1 - levels)`, and on derived inputs it is
    nearer the reference than the wrapped bands; it is no fix, and is not told."""
    written = Path(__file__).parents[1] / "benchmarks/blind_mistakes/2026-11-28/lab08_homographies/10_multiband_uint8.py"
    (tmp_path / "lab08_homographies.py").write_text(written.read_text())
    result = grade(tmp_path, ["lab08.ext3"], pictures="none")
    said = " ".join(c.message for c in check_results(result, "lab08.ext3"))
    assert "range(1 - levels)" not in said, said


def test_a_change_far_from_the_reference_is_not_confirmed_by_its_own_spread(tmp_path):
    """A canvas with img1's channels into which a grey img2 cannot be copied (it raises): removing the
    copy passes the shape check, far from the reference's picture; a spread that far would let any
    answer through, so only the grading's other checks could confirm it (they do not)."""
    written = Path(__file__).parents[1] / "benchmarks/blind_mistakes/2026-11-28d/lab08_homographies/02_draw_matches_grey_canvas.py"
    (tmp_path / "lab08_homographies.py").write_text(written.read_text())
    result = grade(tmp_path, ["lab08.ex3"], pictures="none")
    said = " ".join(c.message for c in check_results(result, "lab08.ex3"))
    assert "removing `canvas[:h2, w1:] = img2`" not in said, said


def test_one_naming_time_per_grading_public_and_hidden(tmp_path, monkeypatch):
    """The error model's and repairs' seconds are counted once per grading: the hidden phase's fresh
    workers (and every lane) hold the public phase's counter, not one of their own."""
    from autograder.engine.mutants import naming

    counters, hidden = set(), []

    def recording(original):
        def named(trial, seconds=repair.CHECK_SECONDS):
            counters.add(id(trial.sandbox.shared.get(naming.SPENT)))
            hidden.append(trial.check.hidden)
            return original(trial, seconds)
        return named

    monkeypatch.setattr(repair, "name_by_repair", recording(repair.name_by_repair))
    monkeypatch.setattr(naming, "name_failure", recording(naming.name_failure))
    folder = edited_reference(tmp_path, "lab09_camera", ("    return np.stack([pinhole_project(X, f) for f in", "    return np.stack([pinhole_project(X, f / 2) for f in"))
    grade(folder, ["lab09"], pictures="none", lanes=2)
    assert True in hidden and False in hidden, hidden
    assert len(counters) == 1, counters


def test_a_function_applied_where_it_does_not_belong_is_shown(tmp_path):
    """A student's own shear matrix built with tan(s), as if s were an angle."""
    folder = edited_reference(tmp_path, "lab07_transformations", (
        "    return np.array([[1.0, s, 0.0],", "    k = np.tan(s)\n    return np.array([[1.0, k, 0.0],"))
    result = grade(folder, ["lab07.ex4"], pictures="none", include_hidden=False)
    checks = [c for c in check_results(result, "lab07.ex4") if c.score < c.max_score]
    assert checks
    told = [c for c in checks if c.mistake.startswith(repair.MISTAKE)]
    assert told and "`k = np.tan(s)` to `k = s` (line 72)" in told[0].message, [c.message for c in checks]


def test_a_repair_takes_the_place_of_a_mutants_sentence_and_the_smallest_change_is_told(tmp_path):
    """`c - R.T @ c`: the error model names it (a mutant of the reference), and so do two changes of
    the student's line -- dropping the `.T`, or `c @ R.T`, which compensates; the smallest is told,
    in place of the mutant's sentence."""
    folder = edited_reference(tmp_path, "lab07_transformations", ("    M[:2, 2] = c - R @ c", "    M[:2, 2] = c - R.T @ c"))
    result = grade(folder, ["lab07.ex2"], pictures="none", include_hidden=False)
    told = [c for c in check_results(result, "lab07.ex2") if c.mistake.startswith(repair.MISTAKE)]
    assert told
    assert "changing `M[:2, 2] = c - R.T @ c` to `M[:2, 2] = c - R @ c`" in told[0].message
    assert "c @ R.T" not in told[0].message and "The error model" not in told[0].message


def test_a_long_line_is_shown_around_the_change_and_a_slip_made_twice_is_found(tmp_path):
    """transform_points written with two reshapes where two transposes belong (neither alone brings
    the answers nearer), and E = K2^T F * K1 on one long line: each shown around its change."""
    folder = edited_reference(
        tmp_path, "lab08_homographies",
        ("    homogeneous = np.hstack([pts, np.ones((len(pts), 1))]) @ np.asarray(H, dtype=np.float64).T",
         "    homogeneous = np.asarray(H, dtype=np.float64) @ np.hstack([pts, np.ones((len(pts), 1))]).reshape(3, -1)\n"
         "    homogeneous = homogeneous.reshape(-1, 3)"))
    result = grade(folder, ["lab08.ex1"], pictures="none", include_hidden=False)
    told = [c for c in check_results(result, "lab08.ex1") if c.mistake.startswith(repair.MISTAKE)]
    assert told, [c.message for c in check_results(result, "lab08.ex1")]
    assert ".reshape(3, -1)` to `" in told[0].message and ".reshape(-1, 3)` to `" in told[0].message
    before, after = repair._elided("a" * 10 + " x = f(b, c) * g(d) " + "z " * 40, "a" * 10 + " x = f(b, c) @ g(d) " + "z " * 40)
    assert before.startswith("aaaaaaaaaa x = f(b, c) * g(d) z") and before.endswith(" ...") and len(before) <= 70
    assert after == before.replace("*", "@")


def test_verify_counts_a_repaired_mutant_as_named():
    """`autograder verify --error-model`: a mutant whose failing check shows a change mending it is
    "repaired", and counts in the naming rate."""
    from types import SimpleNamespace

    from autograder.instructor.error_model import ErrorModelReport, classify

    mutant = SimpleNamespace(sentence="in `f`, the sine has the wrong sign", operator="sign")
    shown = SimpleNamespace(score=0.0, max_score=2.0, mistake="repair:sign",
                            message="f(1) is wrong. Trying small changes to your code: changing `-s` to `s` (line 3) ...")
    plain = SimpleNamespace(score=0.0, max_score=2.0, mistake="", message="f(1) is wrong.")
    outcome = classify(mutant, "lab07.ex2", [plain, shown])
    assert outcome.outcome == "repaired" and outcome.said.startswith("changing `-s` to `s`")
    assert classify(mutant, "lab07.ex2", [plain]).outcome == "described"
    report = ErrorModelReport("lab07", 2, [outcome, classify(mutant, "lab07.ex2", [plain])])
    assert report.naming_rate == 0.5


def test_a_helper_shared_with_other_graded_functions_and_a_search_cut_short():
    """A change in a helper another graded function runs too is told only when nothing else mends
    the answers; one found before the time ran out says the mistake *may* be there."""
    student, _ = _read("""
        def _shared(x):
            return x + 1

        def _own(x):
            return x * 2

        def graded(x):
            return _shared(_own(x))

        def other(x):
            return _shared(x)
    """, api=("graded", "other"))
    assert student.shared("_shared", "graded") and not student.shared("_own", "graded")
    assert not student.shared("graded", "graded")
    fix = repair.Fix(((3, "x + 1", "x - 1"),), "_shared", "add_sub", (("_shared", 1, "add_sub", None),))
    cut_short = repair.Repair("graded", (fix,), 5, complete=False)
    assert "so the mistake may be there (other changes were not all tried" in cut_short.sentence
    assert "so the mistake is likely there" in repair.Repair("graded", (fix,), 5).sentence
    swapped = repair.Fix(((3, "a_long_name - another_long_name", "another_long_name - a_long_name"),), "graded",
                         "swap_operands", (("graded", 4, "swap_operands", None),))
    assert swapped.size == 3   # two things exchanged: one slip, however long the names


def test_a_module_too_large_to_read_in_time_gets_no_repairs(tmp_path):
    """The operators' reading grows faster than the code: a module several times the largest lab's
    is not read at all (none of its changes could be tried in the time), and is answered at once."""
    from types import SimpleNamespace

    from autograder.engine.registry import discover

    lab = discover()["lab07"]
    body = "\n".join(f"    a{i} = x * {i} + x" for i in range(2500))   # about 25 000 nodes
    (tmp_path / f"{lab.module}.py").write_text(f"def translation_matrix(x, y=0):\n{body}\n    return x\n")
    trial = SimpleNamespace(sandbox=SimpleNamespace(submission_dir=tmp_path), lab=lab)
    assert repair._student_code(trial) is None
    (tmp_path / f"{lab.module}.py").write_text("def translation_matrix(x, y=0):\n    return x + y\n")
    assert repair._student_code(trial) is not None


def _made(source, operators):
    """(before, after) of each change the given operators make to `graded` in the student's ``source``."""
    fn = next(node for node in ast.parse(source).body if isinstance(node, ast.FunctionDef))
    return {(ast.unparse(list(ast.walk(fn))[m.edits[0][1]]),
             ast.unparse(repair._MAKE[m.operator](list(ast.walk(fn))[m.edits[0][1]], m.edits[0][3])))
            for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator in operators}


def test_a_step_done_to_one_twin_only_is_done_to_both():
    """`(x / w, y)`: the division done to x is tried on y too; in twin assignments (`u = X / Z`,
    `v = Y`) and inside a call's tuple (`(int(u), v)`) the same."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(q, X, Y, Z, img):
            out = np.column_stack([q[:, 0] / q[:, 2], q[:, 1]])
            u = X / Z
            v = Y
            for i, (x, y) in enumerate(q):
                out[i, 0] = x / Z
                out[i, 1] = y
            return out, (int(u), v), u, v
    """)
    made = _made(source, {"twin_step"})
    assert ("[q[:, 0] / q[:, 2], q[:, 1]]", "[q[:, 0] / q[:, 2], q[:, 1] / q[:, 2]]") in made, made
    assert ("v = Y", "v = Y / Z") in made, made
    assert ("(int(u), v)", "(int(u), int(v))") in made, made
    assert ("out[i, 1] = y", "out[i, 1] = y / Z") in made, made
    assert not any(after.startswith("u =") for _, after in made), made   # (the stepped one is left as it is)


def test_a_difference_measured_the_other_way_and_a_power_moved_across_an_average():
    source = textwrap.dedent("""
        import numpy as np
        import cv2

        def graded(d, e, lines, A, pts):
            cost = cv2.blur(d, (5, 5)) ** 2 + np.abs(e) + np.mean(e ** 2)
            n = lines / np.linalg.norm(lines[:, 1:], axis=1, keepdims=True)
            A[1, 3:7] = pts[0]
            return cost, n, pts[:8], (e - d) ** 2
    """)
    made = _made(source, {"measure", "power_inside", "slice", "drop_slice"})
    for pair in [("cv2.blur(d, (5, 5)) ** 2", "cv2.blur(d ** 2, (5, 5))"), ("np.abs(e)", "e ** 2"),
                 ("np.mean(e ** 2)", "np.mean(e) ** 2"), ("(e - d) ** 2", "np.abs(e - d)"),
                 ("1:", ":2"), ("3:7", "4:8"), ("3:7", "2:6"), ("pts[:8]", "pts")]:
        assert pair in made, (pair, made)
    reference = {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]}
    assert not reference & {"measure", "power_inside", "slice", "drop_slice", "twin_step"}


def test_a_canvas_sized_by_one_image_is_sized_by_both():
    source = textwrap.dedent("""
        import numpy as np

        def graded(img1, img2):
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((h1, w1, 3), np.uint8)
            return canvas
    """)
    made = _made(source, {"canvas"})
    assert {("h1", "max(h1, h2)"), ("w1", "w1 + w2")} <= made, made
    assert ("h1", "max(h1, w1)") not in made, made


def test_a_loop_over_a_fixed_count_is_made_a_loop_over_every_item():
    source = textwrap.dedent("""
        def graded(p1, p2):
            rows = []
            for i in range(8):
                rows.append([p1[i, 0] * p2[i, 0], 1])
            return rows
    """)
    assert {("8", "len(p1)"), ("8", "len(p2)")} <= _made(source, {"loop_all"})


def test_a_traced_call_reports_the_lines_of_the_students_file_it_ran(tmp_path):
    """The student's code as it is, traced: the lines run (the branch taken, the helper called), not
    the branch left; a change there would mend nothing on this input, so it is not tried."""
    folder = submission_from_source(tmp_path, "student", """
        def helper(x):
            return x + 1

        def graded(x, cost="ssd"):
            if cost == "ncc":
                return -x
            return helper(x) * 2
    """)
    source = (folder / "student.py").read_text().splitlines()
    line_of = {text.strip(): number for number, text in enumerate(source, 1)}
    with Sandbox(folder, SMALL) as sandbox:
        outcome = sandbox.companion().call_variant("student", "", "graded", [((3,), {})], timeout=5.0, trace=True)
    assert outcome.ok, outcome.message
    assert outcome.value["values"] == [8]
    ran = set(outcome.value["lines"])
    assert {line_of['if cost == "ncc":'], line_of["return helper(x) * 2"], line_of["return x + 1"]} <= ran, ran
    assert line_of["return -x"] not in ran, ran


def test_a_long_change_is_shown_with_the_arguments_it_leaves_as_dots():
    before = ast.parse("cv2.blur(difference, (block_size, block_size), borderType=cv2.BORDER_REFLECT) ** 2").body[0].value
    after = ast.parse("cv2.blur(difference ** 2, (block_size, block_size), borderType=cv2.BORDER_REFLECT)").body[0].value
    assert repair._abbreviated(before, after) == ("cv2.blur(difference, ...) ** 2", "cv2.blur(difference ** 2, ...)")
    # (arguments and keywords the change leaves as they were, after the one it changes: one "...")
    before = ast.parse("cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT)").body[0].value
    after = ast.parse("cv2.remap(image, np.float32(map_x), np.float32(map_y), cv2.INTER_LINEAR, "
                      "borderMode=cv2.BORDER_CONSTANT)").body[0].value
    assert repair._abbreviated(before, after) == ("cv2.remap(image, map_x, map_y, ...)",
                                                  "cv2.remap(image, np.float32(map_x), np.float32(map_y), ...)")


def test_changes_just_before_the_line_that_raised_are_tried_first():
    from autograder.engine.checks import _lines_of

    traceback = ('Traceback (your code):\n  File "lab08_homographies.py", line 150, in draw_matches\n'
                 '    canvas[:h2, w1:] = img2\nValueError: could not broadcast')
    assert _lines_of(traceback, "lab08_homographies") == (150,)
    far, near, after = (Mutant("sign", "f", "f", line, (), "") for line in (120, 147, 151))

    class Raised:
        raised, raised_lines = ("f", (), {}, "f() raised ValueError"), (150,)

    assert repair._near_the_raise([far, after, near], Raised(), "f") == [near, far, after]
    assert repair._near_the_raise([far, near], Raised(), "g") == [far, near]   # another function raised


def test_a_change_found_beside_a_checks_own_name_is_told_after_it(tmp_path):
    """rotate() through cv2.getRotationMatrix2D given -angle_deg: the check names the effect (the
    rotation goes the opposite way); the change of the student's code that mends it is told after
    that name, which stays (label and hint as they were)."""
    folder = edited_reference(tmp_path, "lab07_transformations", (
        "    return _warp(image, rotation_matrix(angle_deg, centre))\n",
        "    return cv2.warpAffine(image, cv2.getRotationMatrix2D(centre, -angle_deg, 1.0), (width, height))\n"))
    result = grade(folder, ["lab07.ex2"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab07.ex2") if c.score < c.max_score]
    told = [c for c in failed if "to `cv2.getRotationMatrix2D(centre, angle_deg, 1.0)`" in c.message]
    assert told, [c.message for c in failed]
    assert "opposite way" in told[0].message and not told[0].mistake.startswith(repair.MISTAKE)
    assert told[0].message.index("opposite way") < told[0].message.index("Trying small changes")


def test_a_change_of_a_guard_that_does_not_matter_is_not_told(tmp_path):
    """A bounds test before cv2.circle (which clips by itself) with the shape read as (width, height):
    points right of the image's height are skipped. Changing the test (`and` -> `or`, `cx` -> `cy`)
    passes the checks only as removing the test does, so no change of it is told; the unpacking may be."""
    folder = edited_reference(tmp_path, "lab09_camera", (
        "            cv2.circle(out, (int(round(x)), int(round(y))), int(radius), color, thickness=-1)",
        "            cx, cy = int(round(x)), int(round(y))\n"
        "            w, h = out.shape[:2]\n"
        "            if 0 <= cx < w and 0 <= cy < h:\n"
        "                cv2.circle(out, (cx, cy), int(radius), color, thickness=-1)"))
    result = grade(folder, ["lab09.ex5"], pictures="none", include_hidden=False)
    checks = [c for c in check_results(result, "lab09.ex5") if c.score < c.max_score]
    assert checks
    guard = "0 <= cx < w and 0 <= cy < h"
    for check in checks:
        told = check.message.split("Trying small changes", 1)[1:] or [""]
        assert f"`{guard}` to" not in told[0] and "`0 <= cx < w` to" not in told[0] \
            and "`0 <= cy < h` to" not in told[0], check.message


def test_names_swapped_where_every_mode_reads_them_are_not_told_for_one_modes_call(tmp_path):
    """The SSD branch takes the images in the wrong order, the NCC branch in the right one: swapping
    them where they are made mends the SSD calls by breaking the NCC ones (confirmed on the function's
    other mode), so only the SSD line's swap is told."""
    folder = edited_reference(tmp_path, "lab12_stereo", (
        "    volume = (_ssd_volume if cost == \"ssd\" else _ncc_volume)(\n"
        "        left, right, int(max_disparity), int(block_size))\n",
        "    if cost == \"ncc\":\n"
        "        volume = _ncc_volume(left, right, int(max_disparity), int(block_size))\n"
        "    else:\n"
        "        volume = _ssd_volume(right, left, int(max_disparity), int(block_size))\n"))
    checks, told = _failed_and_repaired(folder, "lab12.ex4")
    assert told and any("_ssd_volume(left, right" in message for message in told), [c.message for c in checks]
    made = "left, right = (_grey_float(left), _grey_float(right))"   # where the names are made
    assert not any(f"`{made}` to" in message or "(_grey_float(right), _grey_float(left))" in message
                   for message in told), told


def test_a_pair_of_changes_that_breaks_another_check_of_the_function_is_not_told(tmp_path):
    """The default depth taken as the harmonic mean (`len(z) / np.sum(1.0 / z)`): `/` -> `*` there and in
    `f / float(z_avg)` mend the default by breaking a given z_avg (another check's): no such pair is told."""
    folder = mutant(tmp_path, "lab10_camera2", """
        def weak_perspective_project(points, f, z_avg=None):
            pts = np.asarray(points, dtype=np.float64)
            single = pts.ndim == 1
            pts = pts.reshape(-1, 3)
            if z_avg is None:
                z_avg = len(pts) / np.sum(1.0 / pts[:, 2])
            scale = f / float(z_avg)
            out = scale * pts[:, :2]
            return out[0] if single else out
        """)
    checks, told = _failed_and_repaired(folder, "lab10.ex2")
    assert checks and not any("f * float(z_avg)" in message for message in told), told


def test_an_entry_made_0_is_told_before_a_change_that_makes_it_vanish_on_large_images(tmp_path):
    """A shear about the middle row (`-s * (h - 1) / 2` in the matrix): `*` -> `/` leaves a shift of a
    thousandth of a pixel on the check's images, within rounding of the answers; the entry made 0 gives
    the reference's very numbers, and is the change told."""
    folder = mutant(tmp_path, "lab07_transformations", """
        def shear(image, s=0.5):
            h, w = image.shape[:2]
            M = np.float32([[1, s, -s * (h - 1) / 2], [0, 1, 0]])
            return cv2.warpAffine(image, M, (w, h), flags=cv2.INTER_LINEAR,
                                  borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """)
    checks, told = _failed_and_repaired(folder, "lab07.ex4")
    assert told and all("changing `-s * (h - 1) / 2` to `0`" in message for message in told), \
        [c.message for c in checks]


def test_a_loop_that_starts_each_step_from_the_input_again_is_told_to_carry_its_result(tmp_path):
    """`canvas = cv2.line(image.copy(), ...)` in the loop over lines: each line drawn on a fresh copy,
    only the last one kept. The change told is to draw on the running canvas; drawing on `image` itself
    (the caller's array) would mend the picture by writing into the input, so it is not told."""
    folder = edited_reference(tmp_path, "lab11_two_view", (
        "            cv2.line(canvas, p, q, colour, 1, cv2.LINE_8)",
        "            canvas = cv2.line(image.copy(), p, q, colour, 1, cv2.LINE_8)"))
    checks, told = _failed_and_repaired(folder, "lab11.ex2")
    assert any("changing `image.copy()` to `canvas`" in message for message in told), [c.message for c in checks]
    assert not any("`image.copy()` to `image`" in message for message in told), told


def test_the_running_result_is_offered_only_where_the_loop_restarts_from_its_own_input():
    """`out = f(image.copy(), ...)` in a loop, `out` made from `image` before it: `image.copy()` -> `out`.
    Not for a loop that already carries its result, nor for other names of the line."""
    carried = {m.edits[0][3] for m in repair.mutants_of(textwrap.dedent("""
        def graded(image, items):
            out = image.copy()
            for item in items:
                out = draw(image.copy(), item, scale)
            return out
    """), {"graded"}, phrased=False)["graded"] if m.operator == "carry"}
    assert carried == {"out"}
    right = textwrap.dedent("""
        def graded(image, items):
            out = image.copy()
            for item in items:
                out = draw(out, item, scale)
            return out
    """)
    assert not [m for m in repair.mutants_of(right, {"graded"}, phrased=False)["graded"] if m.operator == "carry"]


def test_an_eigenvector_picked_by_the_smallest_value_where_its_magnitude_belongs(tmp_path):
    """Epipoles from np.linalg.eig with np.argmin(values) twice: a negative eigenvalue wins over the
    zero one. Mended by taking the magnitude at both places (the same slip twice), confirmed on inputs
    of F's own rank (a perturbed F of rank 3 has no null vector) and up to the sign of a unit vector."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab11_two_view", """
        def epipoles(F):
            F = np.asarray(F, dtype=float)
            w, V = np.linalg.eig(F)
            w_t, V_t = np.linalg.eig(F.T)
            e1 = np.real(V[:, np.argmin(w)])
            e2 = np.real(V_t[:, np.argmin(w_t)])
            return e1 / np.linalg.norm(e1), e2 / np.linalg.norm(e2)
        """)
    checks, told = _failed_and_repaired(folder, "lab11.ex5")
    assert any("`np.argmin(w)` to `np.argmin(np.abs(w))`" in m and "`np.argmin(w_t)` to `np.argmin(np.abs(w_t))`" in m
               for m in told), [c.message for c in checks]


def test_a_perturbed_matrix_short_of_full_rank_keeps_its_rank():
    from autograder.engine.mutants import naming

    F = np.array([[0.0, -1.0, 2.0], [1.0, 0.0, -3.0], [-2.0, 3.0, 0.0]])   # a cross-product matrix: rank 2
    moved = naming._perturbed(F, np.random.default_rng(0))
    assert not np.allclose(moved, F) and np.linalg.matrix_rank(moved) == 2
    full = np.diag([1.0, 2.0, 3.0])
    assert np.linalg.matrix_rank(naming._perturbed(full, np.random.default_rng(0))) == 3


def test_a_unit_vector_is_right_up_to_its_sign_only():
    e = np.array([0.6, 0.8, 0.0])
    assert repair.right((-e, e), (e, e))
    assert not repair.right((-2 * e, e), (e, e)) and not repair.right((np.array([0.8, 0.6, 0.0]), e), (e, e))
    assert not repair.right((-e, e), (e, e), projective=False)


def test_a_change_of_code_written_twice_in_a_statement_is_shown_with_enough_to_say_which():
    source = textwrap.dedent("""
        import numpy as np

        def graded(r, a):
            return np.stack([r * np.cos(a), r * np.cos(a)], axis=-1)
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    shown = {student.fix(m).changes[0][1:] for m in student.mutants("graded")
             if m.operator == "function" and student.fix(m) is not None}
    assert ("[r * np.cos(a), r * np.cos(a)]", "[r * np.cos(a), r * np.sin(a)]") in shown, shown


def test_two_neighbouring_names_copied_from_the_other_image_are_told_as_one_change(tmp_path):
    """An 8-point row written out with image 2's `x2, y2` where image 1's `x1, y1` belong, side by side:
    the slip made twice (both names' `2` for `1`), found among the pairs of neighbours, and told as one
    change of the row."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab11_two_view", """
        def essential_8point(pts1, pts2, K1, K2):
            a = np.column_stack([pts1, np.ones(len(pts1))]) @ np.linalg.inv(K1).T
            b = np.column_stack([pts2, np.ones(len(pts2))]) @ np.linalg.inv(K2).T
            x1, y1 = a[:, 0] / a[:, 2], a[:, 1] / a[:, 2]
            x2, y2 = b[:, 0] / b[:, 2], b[:, 1] / b[:, 2]
            rows = np.column_stack([x2 * x1, x2 * y1, x2, y2 * x1, y2 * y1, y2, x2, y2, np.ones(len(x1))])
            E = np.linalg.svd(rows)[2][-1].reshape(3, 3)
            U, _, Vt = np.linalg.svd(E)
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """)
    checks, told = _failed_and_repaired(folder, "lab11.ex3")
    assert any("y2 * y1, y2, x1, y1, np.ones(len(x1))]` (line" in m and " and `" not in m.split("Trying", 1)[1]
               for m in told), [c.message for c in checks]


def test_two_changes_of_one_line_are_shown_together_unless_they_overlap():
    line = (7, "[a, b2, c2, 1]", "[a, b1, c2, 1]")
    assert repair._together([line, (7, "[a, b2, c2, 1]", "[a, b2, c1, 1]")]) == [(7, "[a, b2, c2, 1]", "[a, b1, c1, 1]")]
    assert len(repair._together([line, (7, "[a, b2, c2, 1]", "[a, b3, c2, 1]")])) == 2
    assert len(repair._together([line, (8, "[a, b2, c2, 1]", "[a, b2, c1, 1]")])) == 2


def test_one_item_taken_where_the_mean_belongs_is_told_at_both_places(tmp_path):
    """An affine fit on centred points whose translation comes from the first pair, `dst[0] - A @ src[0]`,
    where the centroids belong: the same slip at two places, told as one change."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab07_transformations", """
        def affine_lstsq(src, dst):
            src, dst = np.asarray(src, float), np.asarray(dst, float)
            c_src, c_dst = src.mean(axis=0), dst.mean(axis=0)
            At, *_ = np.linalg.lstsq(src - c_src, dst - c_dst, rcond=None)
            A = At.T
            return np.column_stack([A, dst[0] - A @ src[0]])
        """)
    checks, told = _failed_and_repaired(folder, "lab07.ex6")
    assert any("`dst[0] - A @ src[0]` to `c_dst - A @ c_src`" in m for m in told), [c.message for c in checks]


def test_twins_are_names_not_numbers_and_an_answer_with_rows_for_columns_is_seen():
    from autograder.engine.mutants.operators import twin_names

    assert twin_names("x1", "x2") and twin_names("img_l", "img_r") and twin_names("y_max", "x_max")
    assert not twin_names("1", "0") and not twin_names("x1", "y2") and not twin_names("width", "depth")
    assert repair._rows_for_columns(np.zeros((5, 7, 3)), np.zeros((7, 5, 3)))
    assert not repair._rows_for_columns(np.zeros((5, 7, 3)), np.zeros((5, 7, 3)))
    assert not repair._rows_for_columns(np.zeros((5, 7)), np.zeros((7, 5, 3)))


def test_of_two_changes_that_pass_the_checks_the_one_nearer_the_reference_on_noisy_points_is_told(tmp_path):
    """The normalisation undone with T1 transposed: mended where it is undone, or -- compensating --
    by transposing T1 where the points are normalised. Both pass the checks; on noisy confirmation
    points only the fix gives the reference's least squares, so only it is told."""
    folder = edited_reference(tmp_path, "lab11_two_view", ("    F = T2.T @ Fn @ T1\n", "    F = T2.T @ Fn @ T1.T\n"))
    checks, told = _failed_and_repaired(folder, "lab11.ex4")
    assert told and all("`T2.T @ Fn @ T1.T` to `T2.T @ Fn @ T1`" in m for m in told), [c.message for c in checks]
    assert not any("_homogeneous(pts1) @ T1.T` to" in m for m in told), told


def test_a_change_that_mends_a_colour_image_by_breaking_a_grey_one_is_not_told(tmp_path):
    """The warp's size read as `image.shape[::-1][:2]` (channels, width for a colour image):
    `[1:]` mends the colour images and makes every grey one raise, where the student's own code
    was right: confirmed on the image in the other number of channels, it is not told."""
    folder = edited_reference(tmp_path, "lab07_transformations", (
        "    return _warp(image, A, dsize)\n",
        "    return cv2.warpAffine(image, np.asarray(A, np.float64), dsize or image.shape[::-1][:2])\n"))
    checks, told = _failed_and_repaired(folder, "lab07.ex5")
    assert checks
    assert not any("`image.shape[::-1][1:]`" in m for m in told), told


def test_a_condition_is_told_where_removing_it_would_be_wrong_on_the_other_kind_of_image(tmp_path):
    """The colour chosen with the test the wrong way round (`canvas.ndim == 2` for `== 3`): a grey
    drawing gets palette tuples. Always taking 255 would mend the grey images too, but not the colour
    ones (a colour per line): the condition matters, and its change is told."""
    folder = edited_reference(tmp_path, "lab11_two_view", (
        "colour = _PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 255",
        "colour = _PALETTE[i % len(_PALETTE)] if canvas.ndim == 2 else 255"))
    checks, told = _failed_and_repaired(folder, "lab11.ex2")
    assert any("`canvas.ndim == 2` to" in m for m in told), [c.message for c in checks]


def _failed_and_repaired(folder, exercise):
    """The exercise's failed checks, and the messages of those that tell a repair."""
    result = grade(folder, [exercise], pictures="none", include_hidden=False)
    checks = [c for c in check_results(result, exercise) if c.score < c.max_score]
    return checks, [c.message for c in checks if c.mistake and c.mistake.startswith(repair.MISTAKE)]


def test_a_power_moved_across_a_students_own_average_is_a_change_tried():
    """`_box_mean(x, k) ** 2` where `_box_mean(x ** 2, k)` belongs: the student's own averaging helper,
    known by its name, takes the power inside as NumPy's and OpenCV's averages do."""
    source = textwrap.dedent("""
        def graded(x, k):
            m = _box_mean(x, k)
            return _box_mean(x, k) ** 2 - m ** 2
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    shown = {student.fix(m).changes[0][1:] for m in student.mutants("graded") if m.operator == "power_inside"}
    assert ("_box_mean(x, k) ** 2", "_box_mean(x ** 2, k)") in shown, shown


def test_a_mean_of_ratios_where_the_ratio_to_the_mean_belongs_is_a_change_tried():
    """A weak-perspective scale taken as the mean of every point's f / Z where f over the mean depth
    belongs: the mean moved inside the ratio's denominator."""
    shown = _shown_changes(textwrap.dedent("""
        def graded(X, f):
            return np.mean(f / X[:, 2]) * X[:, :2]
    """), "power_inside")
    assert ("np.mean(f / X[:, 2])", "f / np.mean(X[:, 2])") in shown, shown


def _shown_changes(source: str, operator: str) -> list:
    """(before, after) of the operator's changes of `graded` in ``source``, in the order they are made."""
    student = repair._Student(source, ast.parse(source), {"graded"})
    return list(dict.fromkeys(student.fix(m).changes[0][1:] for m in student.mutants("graded")
                              if m.operator == operator and student.fix(m) is not None))


def test_a_clip_of_an_intermediate_value_is_a_change_tried_and_the_final_conversions_is_not():
    """`np.clip(w * a + (1 - w) * b, 0, 255)` on a band-pass level (signed): the clip taken out; the clip of the
    final `.astype(np.uint8)` conversion stays (taking it out lets values wrap: never the fix)."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(a, b, w):
            band = np.clip(w * a + (1 - w) * b, 0, 255)
            return np.clip(np.round(band), 0, 255).astype(np.uint8)
        """)
    changes = _shown_changes(source, "unwrap")
    assert ("np.clip(w * a + (1 - w) * b, 0, 255)", "w * a + (1 - w) * b") in changes, changes
    assert not any(before.startswith("np.clip(np.round(band)") and after.startswith("np.round(band)")
                   for before, after in changes), changes


def test_a_factor_a_number_given_to_opencv_a_wrapped_index_and_a_whole_for_its_part_are_changes_tried():
    """Four slips of a student's own code: a factor that does not belong (`f * X[:, 2]` in the depth), an
    OpenCV argument given as the wrong number (nearest first), a difference of two arrays used as an index
    (a negative index wraps round silently), and a statistic of the whole array where a part of it the
    function takes elsewhere belongs. Not offered: a product with -1 (the sign's slip), a difference with a
    constant as an index (`e[x - 1]`: a loop's previous step), a number given to a function of NumPy's."""
    source = textwrap.dedent("""
        def graded(X, f, F, ramp, a, b, e, x):
            depth = np.linalg.norm(X, axis=1)
            xy = np.column_stack([f * X[:, 0], -1 * X[:, 1], f * X[:, 2]])
            lines = cv2.computeCorrespondEpilines(X[:, :2], 2, F)
            flipped = cv2.flip(F, flipCode=0)
            jump = ramp[a - b] + e[x - 1] + np.roll(a, 2)
            return xy / depth[:, None], lines, flipped, jump
    """)
    dropped = _shown_changes(source, "drop_factor")
    assert any(after.endswith("-1 * X[:, 1], X[:, 2]]") for _, after in dropped), dropped
    assert not any("-1 * X[:, 1]" not in after for _, after in dropped if "f * X[:, 2]" in after), dropped
    literals = _shown_changes(source, "literal")
    assert [after for before, after in literals if "computeCorrespondEpilines" in before][0] \
        == "cv2.computeCorrespondEpilines(X[:, :2], 1, F)", literals   # the nearest number first
    assert {after for before, after in literals if "flip" in before} \
        == {"cv2.flip(F, flipCode=1)", "cv2.flip(F, flipCode=-1)", "cv2.flip(F, flipCode=2)"}
    assert not any("np.roll" in before for before, _ in literals)
    assert {after for _, after in _shown_changes(source, "negative_index")} == {"ramp[np.abs(a - b)] + e[x - 1]"}
    parts = _shown_changes(source, "part")
    assert ("np.linalg.norm(X, axis=1)", "X[:, 2]") in parts, parts


def test_an_opencv_argument_given_as_the_wrong_number_is_told(tmp_path):
    """Epipolar lines from cv2.computeCorrespondEpilines with the points said to be of image 2: the lines
    are F^T x (the check's own name says F looks transposed); the change told is the number."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab11_two_view", """
        def epipolar_lines(F, pts1):
            points = np.asarray(pts1, dtype=np.float64).reshape(-1, 1, 2)
            found = cv2.computeCorrespondEpilines(points, 2, np.asarray(F, dtype=np.float64))
            return found.reshape(-1, 3)
        """)
    checks, _ = _failed_and_repaired(folder, "lab11.ex2")
    change = "`cv2.computeCorrespondEpilines(points, 2, ...)` to `cv2.computeCorrespondEpilines(points, 1, ...)`"
    assert checks and change in checks[0].message and all(told_or_pointed(c, checks, change) for c in checks), \
        [c.message for c in checks]


def test_a_change_told_beside_a_checks_own_name_is_pointed_to_by_its_later_checks(tmp_path, monkeypatch):
    """One slip named alike by a function's every check (F^T x where F x belongs): the first tells the change beside
    the name, the later ones point to that check -- not searched again (a block matcher's ten checks on photographs
    each confirmed the same change, and the grading's naming time ran out before its later functions)."""
    from conftest import mutant

    searched = []
    original = repair.name_by_repair
    monkeypatch.setattr(repair, "name_by_repair", lambda trial, *a, **k: searched.append(trial.check.name)
                        or original(trial, *a, **k))
    folder = mutant(tmp_path, "lab11_two_view", """
        def epipolar_lines(F, pts1):
            points = np.asarray(pts1, dtype=np.float64).reshape(-1, 1, 2)
            found = cv2.computeCorrespondEpilines(points, 2, np.asarray(F, dtype=np.float64))
            return found.reshape(-1, 3)
        """)
    checks, _ = _failed_and_repaired(folder, "lab11.ex2")
    named_alike = [c for c in checks if c.mistake == checks[0].mistake]
    assert len(named_alike) >= 2 and "computeCorrespondEpilines(points, 1, ...)" in named_alike[0].message
    for later in named_alike[1:]:
        assert f'The same mistake is named at the check "{named_alike[0].name}"' in later.message, later.message
        assert later.hint == "" and later.name not in searched
    assert named_alike[0].name in searched


def test_a_statistic_of_the_whole_array_where_one_column_belongs_is_told(tmp_path):
    """A pinhole projection dividing by each point's distance from the centre where its depth belongs."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab09_camera", """
        def pinhole_project(points, f):
            P = np.atleast_2d(np.asarray(points, dtype=np.float64))
            r = np.linalg.norm(P, axis=1)
            out = f * P[:, :2] / r[:, None]
            out[P[:, 2] <= 0] = np.nan
            return out[0] if np.ndim(points) == 1 else out
        """)
    checks, told = _failed_and_repaired(folder, "lab09.ex1")
    assert any("`np.linalg.norm(P, axis=1)` to `P[:, 2]`" in m for m in told), [c.message for c in checks]


def test_a_sibling_of_the_students_own_helper_or_of_an_opencv_function_is_a_change_tried():
    """`_laplacian_pyramid(mask, n)` where the weights are the mask's Gaussian pyramid: another of the
    student's defs whose name shares a word and that takes the call's arguments; and OpenCV's affine
    fit of 4 degrees of freedom where the full affine one belongs. Not offered: a def of another name,
    or one that cannot take the call's arguments."""
    source = textwrap.dedent("""
        def _gaussian_pyramid(image, levels):
            return [image] * levels

        def _laplacian_pyramid(image, levels):
            return [image] * levels

        def _pyramid_depth(image):
            return 3

        def _blend(a, b):
            return a

        def graded(a, mask, levels, src, dst):
            weights = _laplacian_pyramid(mask, levels)
            M, _ = cv2.estimateAffinePartial2D(src, dst)
            return weights, M
    """)
    offered = _shown_changes(source, "function")
    assert ("_laplacian_pyramid(mask, levels)", "_gaussian_pyramid(mask, levels)") in offered, offered
    assert ("cv2.estimateAffinePartial2D(src, dst)", "cv2.estimateAffine2D(src, dst)") in offered, offered
    assert not any("_pyramid_depth" in after or "_blend" in after for _, after in offered), offered


def test_the_same_slip_in_two_lines_written_alike_or_down_a_matrix_column_is_a_pair_of_neighbours():
    """A pad written before the image in two lines copied from each other (one for each image), and a
    translation entry's sign in two rows of a matrix literal: pairs of the same slip tried first. Not
    neighbours: the same change in two lines written differently."""
    source = textwrap.dedent("""
        def graded(a, b, h, s, c):
            a = np.pad(a, ((h - a.shape[0], 0), (0, 0)))
            b = np.pad(b, ((h - b.shape[0], 0), (0, 0)))
            other = np.pad(a, ((0, 0), (h - 1, 0)))
            T = np.array([[s, 0.0, s * c[0]], [0.0, s, s * c[1]], [0.0, 0.0, 1.0]])
            return a, b, other, T, 2 ^ h, np.column_stack([a, b])
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    mutants = student.mutants("graded")

    def change(operator, line, after):   # (the change shown: the smallest expression around it)
        return next(m for m in mutants if m.operator == operator and student.fix(m).changes[0][0] == line
                    and student.fix(m).changes[0][2] == after)

    pad_a, pad_b = change("swap_items", 3, "(0, h - a.shape[0])"), change("swap_items", 4, "(0, h - b.shape[0])")
    other = change("swap_items", 5, "((0, 0), (0, h - 1))")
    assert student.mirrored(pad_a, pad_b) and not student.mirrored(pad_a, other)
    sign_x, sign_y = change("sign", 6, "[s, 0.0, -(s * c[0])]"), change("sign", 6, "[0.0, s, -(s * c[1])]")
    assert student.neighbours(sign_x, sign_y) and not student.neighbours(sign_x, change("sign", 6, "[-s, 0.0, s * c[0]]"))
    assert any("2 ** h" in student.fix(m).changes[0][2] for m in mutants if m.operator == "arithmetic")
    assert ("np.column_stack([a, b])", "np.vstack([a, b])") in \
        [student.fix(m).changes[0][1:] for m in mutants if m.operator == "function"]


def test_a_slip_copied_into_the_line_written_alike_for_the_other_image_is_told_at_both(tmp_path):
    """Side-by-side matches with each image padded at the top where the padding belongs below it, in two
    lines written alike (one per image): mending one line passes the check whose shorter image it pads,
    not the others; the pair of the same change in both lines is tried first and told."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab08_homographies", """
        def draw_matches(img1, img2, pts1, pts2):
            a = cv2.cvtColor(img1, cv2.COLOR_GRAY2BGR) if img1.ndim == 2 else img1
            b = cv2.cvtColor(img2, cv2.COLOR_GRAY2BGR) if img2.ndim == 2 else img2
            height = max(a.shape[0], b.shape[0])
            a = np.pad(a, ((height - a.shape[0], 0), (0, 0), (0, 0)))
            b = np.pad(b, ((height - b.shape[0], 0), (0, 0), (0, 0)))
            canvas = np.ascontiguousarray(np.hstack([a, b]))
            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                p = (int(round(x1)), int(round(y1)))
                q = (int(round(x2 + a.shape[1])), int(round(y2)))
                cv2.line(canvas, p, q, (0, 255, 0), 1)
            return canvas
        """)
    checks, told = _failed_and_repaired(folder, "lab08.ex3")
    assert checks and any("`(height - a.shape[0], 0)` to `(0, height - a.shape[0])`" in m
                          and "`(height - b.shape[0], 0)` to `(0, height - b.shape[0])`" in m for m in told), \
        [c.message for c in checks]


def test_opencvs_zero_one_mask_taken_as_indices_is_made_a_boolean_mask():
    """`inliers = mask.ravel()` then `pts1[inliers]`: the 0/1 mask findFundamentalMat returns picks points
    0 and 1 over and over; `.astype(bool)` where it is made or where it indexes. Not offered for an index
    that is no mask by its name, nor for a mask already made boolean."""
    source = textwrap.dedent("""
        def graded(pts1, pts2, mask, k):
            inliers = mask.ravel()
            kept = pts1[inliers], pts2[k], pts2[mask.astype(bool)]
            return kept
    """)
    offered = [after for _, after in _shown_changes(source, "boolean_mask")]
    assert "mask.ravel().astype(bool)" in offered and any("pts1[inliers.astype(bool)]" in a for a in offered), offered
    assert not any("k.astype" in a or "astype(bool).astype" in a for a in offered), offered


def test_a_step_taken_out_below_the_line_another_fix_mends_is_read_as_working_on_its_value():
    """`den = std_l * std_r` reads what the line making `std_l` makes: dropping `std_l` there works on the
    value the other fix mends (a compensation, when both are confirmed, is not told: `nearest`); a line
    that reads nothing the first makes is not fed by it."""
    source = textwrap.dedent("""
        def graded(left, right, k):
            std_l = np.sqrt(box(left, k) ** 2 - box(left, k) ** 2)
            std_r = np.sqrt(box(right * right, k))
            den = std_l * std_r
            return den
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    mutants = student.mutants("graded")
    inside = next(m for m in mutants if m.operator == "power_inside" and m.line == 3)
    dropped = next(m for m in mutants if m.operator == "drop_factor" and m.line == 5
                   and student.fix(m).changes[0][2] == "std_r")
    elsewhere = next(m for m in mutants if m.line == 4)
    assert student.feeds(inside, dropped) and not student.feeds(dropped, inside)
    assert not student.feeds(inside, elsewhere)


def test_a_change_leaving_the_twin_exchanged_input_as_wrong_as_it_was_is_not_told(tmp_path):
    """cv2.resize given a dsize of max(new size, old size) (fx, fy then ignored): right when both factors
    enlarge. `max(new_h, h)` -> `max(new_h, sx)` mends the check's sx=2.0, sy=0.8 and passes the other
    public checks, but on sx=0.8, sy=2.0 (the twin parameters exchanged, by keyword too) answers exactly
    as the student's code does, wrong: not told. The size given where the factors are to count is."""
    from autograder.engine.mutants import naming
    from autograder.engine.mutants.operators import twin_names
    from conftest import mutant

    assert twin_names("sx", "sy") and twin_names("tx", "ty") and not twin_names("sx", "sz")
    assert naming.twins_exchanged(("scale", ("image",), {"sx": 2.0, "sy": 0.8}), [(1, 2, "sx", "sy")]) == \
        [("scale", ("image",), {"sx": 0.8, "sy": 2.0})]
    assert naming.twins_exchanged(("scale", ("image", 2.0), {}), [(1, 2, "sx", "sy")]) == []
    a, b = np.zeros((2, 2)), np.ones((3, 2))   # arrays, given by position and by keyword
    [(_, turned, named)] = naming.twins_exchanged(("f", (a,), {"pts2": b}), [(0, 1, "pts1", "pts2")])
    assert turned[0] is b and named["pts2"] is a
    folder = mutant(tmp_path, "lab07_transformations", """
        def scale(image, sx=1.5, sy=1.5):
            h, w = image.shape[:2]
            new_w, new_h = int(round(w * sx)), int(round(h * sy))
            resized = cv2.resize(image, (max(new_w, w), max(new_h, h)), fx=sx, fy=sy)
            out = np.zeros_like(image)
            out[:min(h, new_h), :min(w, new_w)] = resized[:min(h, new_h), :min(w, new_w)]
            return out
        """)
    checks, told = _failed_and_repaired(folder, "lab07.ex3")
    assert checks and not any(re.search(r"max\(new_[wh], s[xy]\)", m) for m in told), told
    # (the fix is told: the size given by position where the factors are to count)
    assert any("`cv2.resize(image, None, fx=sx, fy=sy)`" in m for m in told), told


def test_a_change_mending_a_matrix_up_to_sign_is_judged_up_to_sign(tmp_path):
    """essential_8point passing K2, K1 to essential_from_fundamental in the wrong order: the swap mends E,
    whose SVD gives it back with either sign; measured plainly, the mended E is as far from the
    reference's as the student's own and the change was never tried on the check."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab11_two_view", """
        def essential_8point(pts1, pts2, K1, K2):
            F = fundamental_8point(pts1, pts2)
            E = essential_from_fundamental(F, K2, K1)
            U, _, Vt = np.linalg.svd(E)
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """)
    checks, told = _failed_and_repaired(folder, "lab11.ex3")
    assert any("`essential_from_fundamental(F, K1, K2)`" in m for m in told), [c.message for c in checks]


def test_a_homogeneous_vector_filled_with_zeros_is_mended_with_ones(tmp_path):
    """The second view's point made from np.zeros(3) (w = 0, a point at infinity) where np.ones(3)
    belongs; on the noisy inputs the student's cross-product equations legitimately give another least
    squares than the reference's, so the change is right on some failing inputs only: the check judges."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab11_two_view", """
        def triangulate(P1, P2, pts1, pts2):
            pts1 = np.asarray(pts1, np.float64).reshape(-1, 2)
            pts2 = np.asarray(pts2, np.float64).reshape(-1, 2)

            def cross(v):
                return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])

            points = np.empty((len(pts1), 3))
            for i in range(len(pts1)):
                h1 = np.ones(3)
                h1[:2] = pts1[i]
                h2 = np.zeros(3)
                h2[:2] = pts2[i]
                X = np.linalg.svd(np.vstack([cross(h1) @ P1, cross(h2) @ P2]))[2][-1]
                points[i] = X[:3] / X[3]
            return points
        """)
    checks, told = _failed_and_repaired(folder, "lab11.ex1")
    assert any("`h2 = np.ones(3)`" in m for m in told), [c.message for c in checks]


def test_a_validity_threshold_and_its_strictness_are_changed_together(tmp_path):
    """Disparities valid from 1 (`d >= 1`) where every positive one is (`d > 0`): neither the
    strictness alone (`d > 1`) nor the threshold alone (`d >= 0`) mends it."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab12_stereo", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=np.float64)
            ok = np.isfinite(d) & (d >= 1)
            depth = np.zeros(d.shape)
            depth[ok] = f * baseline / d[ok]
            return depth
        """)
    checks, told = _failed_and_repaired(folder, "lab12.ex2")
    assert told and all("`np.isfinite(d) & (d > 0)`" in m for m in told), [c.message for c in checks]


def test_a_term_of_a_row_of_signed_terms_has_its_sign_tried(tmp_path):
    """A DLT row typed out with `v` where `-v` belongs, among its other signed terms: a row built
    per point (a flat list, not a matrix literal) has each term's sign tried."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab10_camera2", """
        def camera_matrix_dlt(points3d, points2d):
            rows = []
            for (X, Y, Z), (u, v) in zip(np.asarray(points3d, float), np.asarray(points2d, float)):
                rows.append([X, Y, Z, 1, 0, 0, 0, 0, -u * X, -u * Y, -u * Z, -u])
                rows.append([0, 0, 0, 0, X, Y, Z, 1, -v * X, -v * Y, -v * Z, v])
            P = np.linalg.svd(np.array(rows))[2][-1].reshape(3, 4)
            return P / np.linalg.norm(P)
        """)
    checks, told = _failed_and_repaired(folder, "lab10.ex4")
    assert any("-v * Z, -v]`" in m for m in told), [c.message for c in checks]


def test_a_helper_a_passing_function_shares_has_its_changes_tried_last():
    """`_normalise` serves `fit`, which passed its checks, and `graded`, which failed: a change of it is
    likelier wrong than one of `graded`'s own `_blend`, and is tried after it."""
    source = textwrap.dedent("""
        def _normalise(p):
            return (p - p.mean(axis=0)) / p.std()

        def _blend(a, b):
            return (a + b) / 3

        def fit(p):
            return _normalise(p) * 2

        def graded(p, q):
            return _blend(_normalise(p), q)
    """)
    student = repair._Student(source, ast.parse(source), {"fit", "graded"})
    ordered = student.ordered("graded")
    assert {m.where for m in ordered} >= {"_normalise", "_blend"}
    last = student.vouched_last(ordered, "graded", {"fit"})
    wheres = [m.where for m in last]
    assert wheres.index("_normalise") > max(i for i, w in enumerate(wheres) if w != "_normalise")
    assert student.vouched_last(ordered, "graded", set()) == ordered


def test_a_matrix_used_without_its_last_column_has_it_added_back(tmp_path):
    """`pts @ M[:, :3].T` where the homogeneous 1 belongs: the translation column is added back (the
    fix at the slip), and dropping the later division by the third coordinate -- which compensates
    for the missing 1 there, as M's last row is [0, 0, 0, 1] -- is not told beside it."""
    from conftest import mutant

    folder = mutant(tmp_path, "lab10_camera2", """
        def orthographic_project(points):
            pts = np.atleast_2d(np.asarray(points, dtype=np.float64))
            M = np.array([[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 0, 1.0]])
            h = pts @ M[:, :3].T
            with np.errstate(divide="ignore", invalid="ignore"):
                xy = h[:, :2] / h[:, 2:3]
            return xy[0] if np.ndim(points) == 1 else xy
        """)
    checks, told = _failed_and_repaired(folder, "lab10.ex3")
    assert told and all("`pts @ M[:, :3].T + M[:, 3]`" in m and "`h[:, :2]`" not in m.split("Trying", 1)[1]
                        for m in told), [c.message for c in checks]


def test_a_copy_of_one_item_over_its_neighbour_comes_after_their_exchange():
    """`(0, 0, height, width)` where `(0, 0, width, height)` belongs: `width` copied over `height` is a
    smaller change, and right wherever the image is wider than high; the exchange is tried first."""
    source = textwrap.dedent("""
        def graded(canvas, p, q):
            height, width = canvas.shape[:2]
            return cv2.clipLine((0, 0, height, width), p, q)
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    copies = [m for m in student.ordered("graded") if student.copies_an_item(m)]
    shown = {student.fix(m).changes[0][2] for m in copies}
    assert "(0, 0, width, width)" in shown and "(0, 0, width, height)" not in shown, shown


@pytest.mark.parametrize("body, before, after", [
    ("return f * b // z", "f * b // z", "f * b / z"),                                   # floor for true division
    ("return a * np.pi / 360.0", "a * np.pi / 360.0", "a * np.pi / 180.0"),             # a factor of two
    ("return h[:, :2] / np.linalg.norm(h, axis=1, keepdims=True)",
     "np.linalg.norm(h, axis=1, keepdims=True)", "h[..., -1:]"),                        # unit length for w = 1
    ("return np.divide(f * b, z, where=z > 0)",
     "np.divide(f * b, z, where=z > 0)", "np.divide(f * b, z, where=z > 0, out=np.zeros(np.shape(z > 0)))"),
    ("s = np.zeros_like(h)\n    s[:, z:] = h[:, :-z]\n    return s",
     "s[:, z:] = h[:, :-z]", "s[:, z:] = h[:, :h.shape[1] - z]"),                       # empty for z = 0
    ("s = h @ b\n    return s[0]", "s[0]", "s[0] / s[2]"),                               # w never divided
])
def test_pythons_and_numpys_traps_are_changes_tried(body, before, after):
    """A floor division, a constant twice what it should be, a scaling to unit length where the last
    coordinate divides, a ufunc's `where=` without `out=` (the other entries are whatever the memory
    held), and `x[:, :-d]` (empty for d = 0): each undone by one change of the student's code."""
    source = f"def graded(h, f, b, z, a):\n    {body}\n"
    student = repair._Student(source, ast.parse(source), {"graded"})
    shown = {student.fix(m).changes[0][1:] for m in student.ordered("graded")}
    assert any(was.endswith(before) and now.endswith(after) for was, now in shown), sorted(shown)


def test_a_ufuncs_where_without_out_is_named(tmp_path):
    from conftest import mutant

    folder = mutant(tmp_path, "lab12_stereo", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=np.float64)
            return np.divide(f * baseline, d, where=np.isfinite(d) & (d > 0))
        """)
    checks, told = _failed_and_repaired(folder, "lab12.ex2")
    assert told and all("out=np.zeros(" in m for m in told), [c.message for c in checks]


def test_a_call_the_checks_name_quotes_has_its_lines_changes_tried_first():
    """A check's own name of the mistake that quotes the code ("your code fixes signs with np.sign")
    says where to look: the changes of the lines holding that call come first."""
    source = textwrap.dedent("""
        def graded(K, R):
            Q = K @ R.T
            signs = np.diag(np.sign(np.diag(R)))
            return K @ signs, signs @ Q
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    ordered = student.ordered("graded")
    first = student.quoted_first(ordered, "K has a negative diagonal entry: your code fixes signs with np.sign.")
    lines = [student.fix(m).changes[0][0] for m in first]
    quoted = sum(line == 4 for line in lines)
    assert quoted and set(lines[:quoted]) == {4} and lines != [student.fix(m).changes[0][0] for m in ordered]
    assert student.quoted_first(ordered, "the answer is wrong") == ordered


def test_an_angle_written_in_radians_is_not_converted_again():
    """`phi = 2 * np.pi * u` is in radians: `np.sin(np.deg2rad(phi))` is no slip of the student's (it shrinks
    the angles and can pass a check of spreads); an angle given as a parameter may be in degrees."""
    source = textwrap.dedent("""
        def graded(u, angle):
            phi = 2 * np.pi * u
            return np.sin(phi) + np.cos(angle) + np.tan(np.pi * u)
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    converted = {student.fix(m).changes[0][2] for m in student.ordered("graded") if m.operator == "degrees"}
    assert any("np.cos(np.deg2rad(angle))" in text for text in converted), converted
    assert not any("deg2rad(phi)" in text or "deg2rad(np.pi" in text for text in converted), converted


def test_a_change_of_what_an_argmin_reads_is_judged_by_the_other_checks_too():
    """An index chosen (argmin, argmax, argsort) is a branch: inputs near the failing ones choose the same,
    and `np.argmin(S)` -> `np.argmin(P)` picked the right row there by chance."""
    source = textwrap.dedent("""
        def graded(P):
            U, S, Vt = np.linalg.svd(P)
            return Vt[np.argmin(S)]
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    changes = {student.fix(m).changes[0][2]: student.chooses(m) for m in student.ordered("graded")}
    assert changes.get("np.argmin(P)") is True or changes.get("Vt[np.argmin(P)]") is True, changes
    assert not student.chooses(next(m for m in student.ordered("graded") if "U, S, Vt" in student.fix(m).changes[0][1]))


def test_a_twins_step_added_beside_a_line_is_not_told_where_the_name_used_is_mended(tmp_path):
    from conftest import mutant

    folder = mutant(tmp_path, "lab12_stereo", """
        def disparity_from_matches(xl, xr):
            xl = np.asarray(xl, dtype=np.float64)
            xr = np.asarray(xr, dtype=np.float64)
            if xl.ndim == 2:
                xl = xl[:, 0]
            if xr.ndim == 2:
                xr = xl[:, 0]
            return xl - xr
        """)
    checks, told = _failed_and_repaired(folder, "lab12.ex2")
    assert told and all("`xr = xr[:, 0]`" in m and "xl, xr =" not in m for m in told), [c.message for c in checks]


def test_a_keyword_a_row_index_a_column_and_an_update_a_student_gets_wrong_are_changes_tried():
    """Generic slips of a student's own code: a library call given a keyword that does not belong (`P=K`
    makes cv2.undistortPoints map the points back to pixels), rows written at `i` and `i + 1` where `2 * i`
    and `2 * i + 1` belong (only the rows written), one column of an (N, k) array in arithmetic where the
    column kept 2-D belongs, an accumulation's sign, and a coordinate updated before its twin is computed
    from it (both belong computed from the old values)."""
    source = textwrap.dedent("""
        def graded(pts, K, dist):
            q = cv2.undistortPoints(pts, K, None, P=K)
            A = np.zeros((2 * len(pts), 3))
            total = 0
            for i in range(len(pts)):
                A[i] = [pts[i, 0], 1, 0]
                A[i + 1] = [0, pts[i, 1], 1]
                total -= pts[i, 0]
            h = pts[:, :2] / pts[:, 2]
            x, y = pts[:, 0], pts[:, 1]
            x = x * dist + y
            y = y * dist + x
            return q, A, total, h, x, y
    """)
    assert ("cv2.undistortPoints(pts, K, None, P=K)", "cv2.undistortPoints(pts, K, None)") \
        in _shown_changes(source, "drop_keyword")
    assert _shown_changes(source, "stride") == [("A[i] = [pts[i, 0], 1, 0]", "A[2 * i] = [pts[i, 0], 1, 0]"),
                                                ("A[i + 1] = [0, pts[i, 1], 1]", "A[2 * i + 1] = [0, pts[i, 1], 1]")]
    assert _shown_changes(source, "keep_axis") == [("pts[:, :2] / pts[:, 2]", "pts[:, :2] / pts[:, 2:3]")]
    assert ("total -= pts[i, 0]", "total += pts[i, 0]") in _shown_changes(source, "add_sub")
    student = repair._Student(source, ast.parse(source), {"graded"})
    [update] = [m for m in student.mutants("graded") if m.operator == "simultaneous"]
    assert "assigning `x` and `y` together (`x, y = ..., ...`, line 12: `y` from the `x` of before that line" \
        in student.fix(update).told("graded")
    written = ast.unparse(repair.mutated_defs(ast.parse(source), update.edits, source))
    assert "x, y = (x * dist + y, y * dist + x)" in written and "y = y * dist + x\n" not in written


# A least-squares affine fit written with a loop whose rows overwrite each other (A[i], A[i + 1]) and
# a distortion whose y is computed from the x already distorted.
_ROWS_PER_PAIR = ("""    M = np.zeros((2 * n, 6))
    M[0::2, 0:2] = src
    M[0::2, 2] = 1.0
    M[1::2, 3:5] = src
    M[1::2, 5] = 1.0
    b = dst.reshape(-1)  # x'_0, y'_0, x'_1, y'_1, ...
""", """    M = np.zeros((2 * n, 6))
    b = np.zeros(2 * n)
    for i in range(n):
        M[i] = [src[i, 0], src[i, 1], 1.0, 0.0, 0.0, 0.0]
        M[i + 1] = [0.0, 0.0, 0.0, src[i, 0], src[i, 1], 1.0]
        b[i] = dst[i, 0]
        b[i + 1] = dst[i, 1]
""")
_UPDATED_X = ("""    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    out = np.column_stack([xd, yd])""", """    x = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    y = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    out = np.column_stack([x, y])""")


def test_one_slip_made_at_four_places_and_an_update_made_too_early_are_told(tmp_path):
    result = grade(edited_reference(tmp_path / "rows", "lab07_transformations", _ROWS_PER_PAIR), ["lab07.ex6"],
                   pictures="none", include_hidden=False)
    told = [c for c in check_results(result, "lab07.ex6") if c.mistake == repair.MISTAKE + "stride"]
    assert told, [c.message for c in check_results(result, "lab07.ex6")]
    for row in ("`M[2 * i] = [", "`M[2 * i + 1] = [", "`b[2 * i] = dst[i, 0]`", "`b[2 * i + 1] = dst[i, 1]`"):
        assert row in told[0].message
    result = grade(edited_reference(tmp_path / "update", "lab09_camera", _UPDATED_X), ["lab09.ext2"],
                   pictures="none", include_hidden=False)
    checks = check_results(result, "lab09.ext2")
    told = [c for c in checks if c.mistake == repair.MISTAKE + "simultaneous"]
    assert told and all(c.mistake == told[0].mistake for c in checks if c.score < c.max_score), \
        [c.message for c in checks]
    assert "assigning `x` and `y` together" in told[0].message


def test_a_measure_missing_its_square_root_or_its_absolute_value_and_row_column_pairs_are_changes_tried():
    source = textwrap.dedent("""
        def graded(d, left, right, mask):
            close = np.sum(d ** 2, axis=1) < 3.0
            sad = np.sum(left - right)
            points = np.argwhere(mask)
            return close, sad, points
    """)
    measures = _shown_changes(source, "measure")
    assert ("np.sum(d ** 2, axis=1)", "np.sqrt(np.sum(d ** 2, axis=1))") in measures, measures
    assert ("np.sum(left - right)", "np.sum(np.abs(left - right))") in measures, measures
    assert ("np.argwhere(mask)", "np.argwhere(mask)[:, ::-1]") in _shown_changes(source, "column_order")


def test_statements_in_the_wrong_place_are_changes_tried_and_told_in_words():
    """An update made before the statement that needs the old value (moved after it), a statement left
    after the `if` that was to guard it (moved in), a `return` inside a loop (moved after it)."""
    source = textwrap.dedent("""
        def graded(P, pts, n):
            K, R = rq(P[:, :3])
            K = K / K[2, 2]
            t = np.linalg.solve(K, P[:, 3])
            best, best_count = None, 0
            for i in range(n):
                inliers = pts > i
                count = inliers.sum()
                if count > best_count:
                    best_count = count
                best = inliers
            out = []
            for p in pts:
                out.append(p * 2)
                return out
            for q in pts:
                if q is None:
                    continue
                out.append(q)
            return K, t, best
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    told = {m.operator: [] for m in student.mutants("graded")}
    for m in student.mutants("graded"):
        told[m.operator].append((student.fix(m).told("graded"), m))
    said = {operator: [sentence for sentence, _ in pairs] for operator, pairs in told.items()}
    assert "moving `K = K / K[2, 2]` (line 4) after line 5" in said["move"]
    assert "moving `best = inliers` (line 12) into the `if` block above it (line 10), as its last statement" \
        in said["indent"]
    assert "moving `return out` (line 16) out of the `for` loop of line 14, to just after it" in said["dedent"]
    assert not any("out.append(q)" in sentence for sentence in said["indent"])   # (after a `continue`: never run)
    [(_, indent)] = [pair for pair in told["indent"] if "best = inliers" in pair[0]]
    written = ast.unparse(repair.mutated_defs(ast.parse(source), indent.edits, source))
    assert "best_count = count\n            best = inliers" in written.replace("    ", " " * 4), written


def test_a_value_read_before_or_after_the_update_it_belongs_beside_is_a_move_tried():
    """`scale = K[2, 2]` read before the sign fix `K = K @ signs` (moved after it); `norm` read after the
    centring it was to come before (moved before it); never moved past a statement using what it makes."""
    source = textwrap.dedent("""
        def graded(K, v, w):
            scale = K[2, 2]
            signs = np.diag(np.sign(np.diag(K)))
            K = K @ signs
            v = v - v.mean()
            norm = np.linalg.norm(v)
            size = w.sum()
            half = size / 2
            w = w * 2
            return K / scale, v / norm, half
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    said = [student.fix(m).told("graded") for m in student.mutants("graded") if m.operator == "move"]
    assert "moving `scale = K[2, 2]` (line 3) after line 5" in said, said
    assert "moving `norm = np.linalg.norm(v)` (line 7) before line 6" in said, said
    assert not any("`size = w.sum()`" in sentence for sentence in said), said   # (half reads it)


def test_an_opencv_point_set_may_be_transposed_but_not_its_matrices():
    """`cv2.convertPointsFromHomogeneous(X)` of a 4 x N result: the point set transposed is a change tried;
    the camera matrix given to `cv2.solvePnP` beside its points is not one (it is no point set)."""
    source = textwrap.dedent("""
        def graded(X, obj, img, K, dist):
            pts = cv2.convertPointsFromHomogeneous(X)
            ok, r, t = cv2.solvePnP(obj, img, K, dist)
            return pts, r, t
    """)
    changed = [after for _, after in _shown_changes(source, "transpose")]
    assert any("convertPointsFromHomogeneous(X.T)" in after for after in changed), changed
    assert any("solvePnP(obj.T" in after for after in changed), changed
    assert not any("K.T" in after or "dist.T" in after for after in changed), changed


def test_a_colour_conversion_made_whatever_the_image_is_is_guarded_by_its_channels():
    """`cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)` raises on a grey frame the API allows: the change
    converts only a frame with 3 channels (and GRAY2BGR only a grey one); another conversion is left."""
    source = textwrap.dedent("""
        def graded(frame, mask, image):
            grey = cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
            shown = cv2.cvtColor(mask, cv2.COLOR_GRAY2BGR)
            hsv = cv2.cvtColor(image, cv2.COLOR_BGR2HSV)
            return grey, shown, hsv
    """)
    changes = _shown_changes(source, "convert_if")
    assert changes == [
        ("cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)",
         "cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY) if frame.ndim == 3 else frame"),
        ("cv2.cvtColor(mask, cv2.COLOR_GRAY2BGR)", "cv2.cvtColor(mask, cv2.COLOR_GRAY2BGR) if mask.ndim == 2 else mask"),
    ], changes


def test_an_argument_given_to_an_own_helper_where_its_default_belongs_is_left_out():
    """`_warp(image, M, (w + tx, h + ty))` where the helper's default size (the input's) was due: the last
    positional argument a default covers and a defaulted keyword are left out; never a required one."""
    source = textwrap.dedent("""
        def _warp(image, M, dsize=None, *, border=0):
            return image

        def graded(image, M, w, h):
            shifted = _warp(image, M, (w + 5, h + 5))
            framed = _warp(image, M, border=1)
            return shifted, framed, _warp(image, M)
    """)
    changes = _shown_changes(source, "drop_argument")
    assert ("_warp(image, M, (w + 5, h + 5))", "_warp(image, M)") in changes, changes
    assert ("_warp(image, M, border=1)", "_warp(image, M)") in changes, changes
    assert len(changes) == 2, changes   # (the call giving only the required arguments keeps them)


def test_a_right_hand_side_moved_without_its_minus_is_negated_and_a_minus_in_every_item_dropped():
    """Fixing one unknown of A x = 0 to 1 moves its column to the right-hand side with a minus
    (`lstsq(A[:, :8], -A[:, 8])`); written without it, or with a minus in each item of a list of
    right-hand sides (`rhs.extend([-u, -v])`), the change is tried; an already negated one is not negated."""
    source = textwrap.dedent("""
        def graded(A, M, b, u, v, rhs):
            f = np.linalg.lstsq(A[:, :8], A[:, 8], rcond=None)[0]
            g = np.linalg.solve(M, -b)
            rhs.extend([-u, -v])
            return f, g, rhs
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    written = [ast.unparse(repair.mutated_defs(ast.parse(source), m.edits, source))
               for m in student.mutants("graded") if m.operator == "sign"]
    assert any("np.linalg.lstsq(A[:, :8], -A[:, 8], rcond=None)" in w for w in written), written
    assert any("rhs.extend([u, v])" in w for w in written), written
    assert not any("--b" in w or "-(-b)" in w for w in written), written


def test_the_two_parts_of_one_item_exchanged_in_a_comparison_are_a_change_tried_first():
    """A ratio test written the other way round (`n.distance < 0.75 * m.distance`, `m, n` one knnMatch
    pair): the two names exchanged throughout the comparison, among the first changes tried; names
    that are not parts of one item are not exchanged."""
    source = textwrap.dedent("""
        def graded(pairs, limit, scale):
            good = [m for m, n in pairs if n.distance < 0.75 * m.distance]
            few = limit < scale * len(good)
            return good, few
    """)
    assert _shown_changes(source, "exchange") == [
        ("n.distance < 0.75 * m.distance", "m.distance < 0.75 * n.distance")]
    student = repair._Student(source, ast.parse(source), {"graded"})
    first = student.ordered("graded")[:3]
    assert any(m.operator == "exchange" for m in first), [(m.operator, student.fix(m).changes) for m in first]


def test_a_grid_counted_from_1_an_integer_reciprocal_and_a_block_set_where_it_is_scaled_are_changes_tried():
    """`np.mgrid[1:cols + 1, 1:rows + 1]` (corners numbered from 1), `np.reciprocal(d)` of integers (1 // d),
    `T[:2, :2] = s` where the block was to be scaled (`*=`): each has its change."""
    source = textwrap.dedent("""
        def graded(cols, rows, d, s):
            grid = np.mgrid[1:cols + 1, 1:rows + 1]
            inverse = np.reciprocal(d)
            T = np.eye(3)
            T[:2, :2] = s
            return grid, inverse, T
    """)
    assert ("np.mgrid[1:cols + 1, 1:rows + 1]", "np.mgrid[0:cols, 0:rows]") in _shown_changes(source, "zero_based")
    assert ("np.reciprocal(d)", "np.reciprocal(np.asarray(d, dtype=np.float64))") in _shown_changes(source, "astype_float")
    assert ("T[:2, :2] = s", "T[:2, :2] *= s") in _shown_changes(source, "accumulate")


def test_an_entry_of_a_matrix_literal_that_does_not_belong_is_made_0():
    """`[[1, s, -s * (h - 1) / 2], [0, 1, 0]]`: a shear about the middle row where the origin's is asked;
    the computed entry made 0 is a change tried (constants and a flat list's items are not)."""
    source = textwrap.dedent("""
        def graded(s, h, t):
            M = np.float32([[1, s, -s * (h - 1) / 2], [0, 1, 0]])
            v = [t * 2, 1]
            return M, v
    """)
    assert _shown_changes(source, "zero_entry") == [("-s * (h - 1) / 2", "0")]


def test_a_truncation_a_wrapping_conversion_and_a_constant_one_off_are_changes_tried():
    source = textwrap.dedent("""
        def graded(x, image, n):
            column = int(x * 2.5)
            out = (image * 1.5).astype(np.uint8)
            levels = 2 ** n - 1
            return column, out, levels
    """)
    rounded = _shown_changes(source, "rounding")
    assert ("int(x * 2.5)", "int(round(x * 2.5))") in rounded, rounded
    assert ("(image * 1.5).astype(np.uint8)", "np.clip(np.round(image * 1.5), 0, 255).astype(np.uint8)") in rounded
    bounds = _shown_changes(source, "bound")
    assert ("levels = 2 ** n - 1", "levels = 2 ** n - 2") in bounds and ("levels = 2 ** n - 1", "levels = 2 ** n - 0") \
        not in bounds, bounds


def test_an_opencv_argument_that_does_not_belong_a_colour_image_and_a_flat_column_of_ones_are_changes_tried():
    source = textwrap.dedent("""
        def graded(image, size, s, pts, matcher, left, right):
            big = cv2.resize(image, size, fx=s, fy=s)
            corners = cv2.cornerSubPix(image, pts, (5, 5), (-1, -1), None)
            disparity = matcher.compute(left, right)
            h = np.hstack([pts, np.ones(len(pts))])
            return big, corners, disparity, h
    """)
    assert ("cv2.resize(image, size, fx=s, fy=s)", "cv2.resize(image, None, fx=s, fy=s)") \
        in _shown_changes(source, "drop_keyword")
    grey = [after for _, after in _shown_changes(source, "grey")]
    assert "giving `cv2.cornerSubPix` the grey view of `image` (`cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)` where it " \
           "has 3 channels, line 4{inside})" in grey, grey
    assert any("`matcher.compute` the grey view of `right`" in after for after in grey), grey
    student = repair._Student(source, ast.parse(source), {"graded"})
    [corner] = [m for m in student.mutants("graded") if m.operator == "grey" and m.line == 4]
    assert "if image.ndim == 3 else image" in ast.unparse(repair.mutated_defs(ast.parse(source), corner.edits, source))
    assert ("np.hstack([pts, np.ones(len(pts))])", "np.hstack([pts, np.ones((len(pts), 1))])") \
        in _shown_changes(source, "keep_axis")


def test_an_svd_recomposed_without_its_constraint_and_a_normalisation_never_undone_are_changes_tried():
    source = textwrap.dedent("""
        def graded(p1, p2):
            n1, T1 = _normalise(p1)
            n2, T2 = _normalise(p2)
            U, S, Vt = np.linalg.svd(_rows(n1, n2)[-1].reshape(3, 3))
            F = U @ np.diag(S) @ Vt
            return F
    """)
    ranks = [after for _, after in _shown_changes(source, "rank")]
    assert "U @ np.diag([S[0], S[1], 0])" in ranks and "U @ np.diag([1, 1, 0])" in ranks, ranks
    undone = [after for _, after in _shown_changes(source, "denormalise")]
    assert "return T2.T @ F @ T1" in undone and "return np.linalg.inv(T2) @ F @ T1" in undone, undone
    assert "return np.linalg.inv(T2) @ F" not in undone, undone   # (neither side undone: both together)
    # (one side only, where the other is undone already: a camera's world side, `P = p.reshape(3, 4) @ U`)
    source = textwrap.dedent("""
        def graded(x, X):
            T, U = _normalise(x), _normalise(X)
            Xn = X @ U.T
            p = np.linalg.svd(_rows(x @ T.T, Xn))[2][-1]
            P = p.reshape(3, 4) @ U
            return P
    """)
    undone = [after for _, after in _shown_changes(source, "denormalise")]
    assert "return np.linalg.inv(T) @ P" in undone and "return np.linalg.inv(U) @ P" not in undone, undone


_NEVER_UNDONE = ("    F = T2.T @ Fn @ T1\n    return F / np.linalg.norm(F)", "    return Fn / np.linalg.norm(Fn)")


def test_a_normalisation_never_undone_is_told(tmp_path):
    result = grade(edited_reference(tmp_path, "lab11_two_view", _NEVER_UNDONE), ["lab11.ex4"], pictures="none",
                   include_hidden=False)
    checks = check_results(result, "lab11.ex4")
    # (the check names the effect by hand; the change is told beside it -- not a compensation: the
    # normalisation taken out at both places, a pair of removals no longer tried beside a name)
    told = [c for c in checks if "Trying small changes" in c.message]
    assert told and all("T2.T @ Fn @ T1" in c.message for c in told), [c.message for c in checks if c.score < c.max_score]
    assert "`Fn / np.linalg.norm(Fn)` to `T2.T @ Fn @ T1 / np.linalg.norm(Fn)`" in told[0].message


def test_a_division_with_no_guard_is_given_one():
    source = textwrap.dedent("""
        def graded(disparity, f, b):
            return f * b / disparity
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    guards = [m for m in student.mutants("graded") if m.operator == "guard"]
    assert [student.fix(m).told("graded") for m in guards] == [
        "dividing by `disparity` only where it is > 0 (line 3; 0 elsewhere: `np.where(disparity > 0, ..., 0.0)`)",
        "dividing by `disparity` only where it is > 0 (line 3; NaN elsewhere: `np.where(disparity > 0, ..., np.nan)`)"]
    namespace = {"np": np}
    exec(ast.unparse(repair.mutated_defs(ast.parse(source), guards[0].edits, source)), namespace)
    assert namespace["graded"](np.array([0.0, -1.0, 2.0]), 10.0, 0.5).tolist() == [0.0, 0.0, 2.5]


def test_another_of_the_results_a_library_call_returns_is_a_change_tried():
    source = textwrap.dedent("""
        def graded(src, dst):
            H = cv2.findHomography(src, dst, cv2.RANSAC, 3.0)[1]
            return H
    """)
    assert ("cv2.findHomography(src, dst, cv2.RANSAC, 3.0)[1]", "cv2.findHomography(src, dst, cv2.RANSAC, 3.0)[0]") \
        in _shown_changes(source, "other_result")


def test_the_other_end_of_a_slice_with_a_computed_bound_is_a_change_tried():
    source = textwrap.dedent("""
        def graded(costs, d):
            costs[d, :, d:] = np.inf
            return costs[:, :-d]
    """)
    ends = _shown_changes(source, "slice")
    assert ("costs[d, :, d:]", "costs[d, :, :d]") in ends, ends
    assert ("costs[:, :-d]", "costs[:, -d:]") in ends, ends


def test_changes_that_are_no_ones_slip_are_not_tried_and_a_change_of_ties_alone_is_not_told_beside_a_fix():
    """Another name in a mode's test runs another mode's code (`cost == "ssd"` -> `block_size == "ssd"`);
    NumPy's data exchanged with a bound (`np.clip(limit, 0, v)`); a comparison made strict or not beside
    another fix changes ties alone. OpenCV's DECOMP_* flags are told one for another."""
    source = textwrap.dedent("""
        def graded(cost, block_size, v, limit, A, b):
            volume = (_ssd if cost == "ssd" else _ncc)(block_size)
            x = np.clip(v, 0, limit)
            return volume, x, cv2.solve(A, b, flags=cv2.DECOMP_LU)
    """)
    assert not any("block_size ==" in after for _, after in _shown_changes(source, "other_name"))
    assert not any(after.startswith("np.clip(limit") for _, after in _shown_changes(source, "swap_args"))
    assert ("cv2.solve(A, b, flags=cv2.DECOMP_LU)", "cv2.solve(A, b, flags=cv2.DECOMP_SVD)") \
        in _shown_changes(source, "flag")
    ties = repair.Fix(((3, "ssd < best_cost", "ssd <= best_cost"),), "graded", "compare", ())
    turned = repair.Fix(((3, "ssd < best_cost", "ssd > best_cost"),), "graded", "compare", ())
    assert repair._ties_only(ties) and not repair._ties_only(turned)


def test_a_homogeneous_coordinate_written_0_where_1_belongs_is_a_change_tried():
    source = textwrap.dedent("""
        def graded(M, X, Y, Z):
            x, y, w = M @ np.array([X, Y, Z, 0.0])
            return x / w, y / w
    """)
    assert ("[X, Y, Z, 0.0]", "[X, Y, Z, 1.0]") in _shown_changes(source, "literal")


# ------------------------------------------------------------------ values given otherwise; steps left out
def test_the_checks_values_are_given_otherwise_one_at_a_time():
    """Whole numbers made fractional, numbers given the other sign, a 0/1 float mask blurred, a
    whole-number default left out given fractional: one value changed per call (`levels=5.5` alone
    makes no input)."""
    mask = np.zeros((16, 16))
    mask[:, :8] = 1.0
    made = repair._beyond(("blend", (mask, 2.5), {"levels": 5}), defaults=[("tx", 9, 100)])
    changed = [(i, a) for _, args, kwargs in made for i, a in [*enumerate(args), *kwargs.items()]
               if not (a is mask or (not isinstance(a, np.ndarray) and a in (2.5, 5, 100)))]
    assert len(made) == len(changed) == 4
    soft = next(a for _, a in changed if isinstance(a, np.ndarray))
    assert 0 < soft.min() < 0.5 < soft.max() < 1 and not np.isin(soft, (0.0, 1.0)).all()
    assert {a for _, a in changed if not isinstance(a, np.ndarray)} == {-2.5, 5.5, 100.5}
    assert repair._beyond(("f", (np.eye(3), True, None, "ssd"), {})) == []   # (nothing of the kind)


def test_an_optional_number_the_reference_resolves_is_given_for_confirmation():
    """A parameter defaulting to None that the reference resolves to a fixed number (a module constant,
    a literal) is given four times that number, one argument at a time; None given counts as left out."""
    from autograder.engine.mutants.naming import _resolved_defaults

    source = textwrap.dedent("""
        DEFAULT = 6.0
        def f(x, k=5, smoothness=None, z=None, w=None):
            s = DEFAULT if smoothness is None else float(smoothness)
            if w is None:
                w = 2
            z = x.mean() if z is None else z
            return x * s * w * z
        """)
    resolved = _resolved_defaults(source)["f"]
    assert resolved == [("smoothness", 2, 6.0), ("w", 4, 2.0)]   # (z: the data's mean, no fixed number)
    made = repair._given(("f", (np.eye(2),), {"w": None}), resolved)
    assert [call[2] for call in made] == [{"w": None, "smoothness": 24.0}, {"w": 8.0}]
    assert repair._given(("f", (np.eye(2), 5, 1.0), {"w": 3}), resolved) == []


def test_a_logs_base_in_a_ratio_of_logs_is_never_the_slip_and_a_redraw_is_never_judged_by_the_check():
    """`np.log(a) / np.log(b)`: the base cancels, so one log made `np.log10` only scales the ratio (a RANSAC's
    count of samples, 2.3 times larger, passed by running longer): not offered there, offered elsewhere. A
    change of a random draw's keyword (`replace=False` -> `True`) draws other samples: never judged by a check
    on a few seeds."""
    from autograder.engine.mutants.operators import mutants_of

    source = textwrap.dedent("""
        import numpy as np
        def graded(w, p):
            n = np.log(1 - p) / np.log(1 - w)
            return n + np.log(p)
        """)
    offered = [m.edits for m in mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator == "function"]
    assert any("np.log10" in str(e) for e in offered)   # (the lone log)
    assert len([e for e in offered if "np.log10" in str(e)]) == 1, offered
    redraw = repair.Fix(((4, "rng.choice(n, 4, replace=False)", "rng.choice(n, 4, replace=True)"),), "graded",
                        "flip_keyword", ())
    assert repair._redraws(redraw)
    sized = repair.Fix(((4, "rng.choice(n, 3, replace=False)", "rng.choice(n, 4, replace=False)"),), "graded", "bound", ())
    assert not repair._redraws(sized) and not repair._redraws(None)


def test_the_numbers_a_students_tests_compare_a_parameter_with_are_confirmation_values():
    """`if angle_deg % 180 == 0:` -> angle_deg=180 (the modulus; 0, the value given, is not repeated), one
    value at a time, for a number given or left to its default; a parameter never tested gives none."""
    fn = _defs_of("""
        def rotate(image, angle_deg=45, scale=1.0):
            if angle_deg % 180 == 0 or scale < 0:
                return image[::-1, ::-1]
            return image
        """)["rotate"]
    image = np.zeros((4, 4))
    made = repair._branch_values(("rotate", (image, 0), {}), fn)
    assert [(call[1][1:], call[2]) for call in made] == [((180,), {}), ((0,), {"scale": 0.0})]
    assert repair._branch_values(("rotate", (image,), {}), fn)[0][2] == {"angle_deg": 180}
    assert repair._branch_values(("rotate", (image, 0), {}), None) == []


def test_a_change_right_only_with_the_defaults_own_number_is_no_repair(tmp_path):
    """A DP whose default smoothness is 400 (right: 6): `s` -> `block_size` (5) mends the default and
    breaks every smoothness the caller gives, which the student's code takes rightly: not told."""
    folder = edited_reference(tmp_path, "lab12_stereo", ("DEFAULT_SMOOTHNESS = 6.0", "DEFAULT_SMOOTHNESS = 400.0"))
    result = grade(folder, ["lab12.ex5"], pictures="none", include_hidden=False)
    checks = [c for c in check_results(result, "lab12.ex5") if c.score < c.max_score]
    assert checks and any("default smoothness is far too large" in c.message for c in checks)
    assert not any("block_size * np.arange(D)" in c.message for c in checks), [c.message for c in checks]


def _defs_of(source: str) -> dict:
    return {fn.name: fn for fn in ast.parse(textwrap.dedent(source)).body if isinstance(fn, ast.FunctionDef)}


LEFT_OUT = """
    def dlt(X, x):
        T = normalising(x)
        x_norm = (T @ np.vstack([x.T, np.ones(len(x))])).T
        A = rows(X, x)
        P_norm = solve(A)
        P = np.linalg.inv(T) @ P_norm
        return P
"""


def test_a_change_that_works_around_a_step_left_out_is_no_repair():
    """`x_norm` computed and never used (the rows built from `x`): dropping the undo of T mends the answers
    by cutting T out of them, and changing the helper that makes T works around it too; putting
    `x_norm` to use is the fix; a change elsewhere in a function with no such value is judged as ever."""
    before = _defs_of(LEFT_OUT)["dlt"]
    dropped = _defs_of(LEFT_OUT.replace("np.linalg.inv(T) @ P_norm", "P_norm"))["dlt"]
    used = _defs_of(LEFT_OUT.replace("rows(X, x)", "rows(X, x_norm)"))["dlt"]
    assert repair._disconnects(before, dropped)
    assert repair._disconnects(before, before, frozenset({"normalising"}))
    assert not repair._disconnects(before, used)
    assert not repair._disconnects(before, before, frozenset({"solve"}))   # (a helper the value does not read)
    spurious = _defs_of("""
        def project(X, f):
            norm = np.linalg.norm(X)
            return f * X[:, :2] / X[:, 2:] / norm
    """)["project"]
    assert not repair._disconnects(spurious, _defs_of("""
        def project(X, f):
            norm = np.linalg.norm(X)
            return f * X[:, :2] / X[:, 2:]
    """)["project"])


PADDED = """
    def scale(image, sx=1.5, sy=1.5):
        height, width = image.shape[:2]
        new_w, new_h = max(int(np.ceil(width * sx)), 1), max(int(np.ceil(height * sy)), 1)
        scaled = cv2.warpAffine(image, np.float32([[sx, 0, 0], [0, sy, 0]]), (new_w, new_h))
        part = scaled[:height, :width]
        missing_rows, missing_cols = height - part.shape[0], width - part.shape[1]
        return cv2.copyMakeBorder(part, 0, missing_cols, 0, missing_rows, cv2.BORDER_CONSTANT, value=0)
"""


def test_a_size_dropped_where_the_code_goes_on_to_fit_the_value_to_it_is_no_repair():
    """The blind set 1204b's 07/04: a canvas of the student's own size, cropped and padded back, with the
    paddings in the wrong order. `dsize` -> None makes the crop and the padding do nothing, and the
    answers come right: a compensation. The same size dropped where the warp is returned at once (a
    canvas widened to fit the whole shear) is the slip itself, and stays a repair."""
    before = _defs_of(PADDED)["scale"]
    assert repair._disconnects(before, _defs_of(PADDED.replace("(new_w, new_h))", "None)"))["scale"])
    assert not repair._disconnects(before, _defs_of(PADDED.replace(
        "missing_cols, 0, missing_rows", "missing_rows, 0, missing_cols"))["scale"])
    widened = """
        def shear(image, s=0.5):
            h, w = image.shape[:2]
            out_w = w + int(abs(s) * h)
            return cv2.warpAffine(image, np.float32([[1, s, 0], [0, 1, 0]]), (out_w, h))
    """
    assert not repair._disconnects(_defs_of(widened)["shear"], _defs_of(widened.replace("(out_w, h)", "(w, h)"))["shear"])


def test_a_float_mask_divided_by_255_is_mended_by_the_division_taken_out_not_a_product(tmp_path):
    """The mask scaled as an 8-bit image: on the checks' 0/1 masks `* 255` clipped to [0, 1] mends the
    blend as exactly as taking the division out; on a soft mask only the latter does."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, "lab08_homographies", (
        "np.clip(np.asarray(mask, dtype=np.float32), 0, 1)", "np.clip(np.asarray(mask, dtype=np.float32) / 255.0, 0, 1)"))
    checks, told = _failed_and_repaired(folder, "lab08.ext3")
    assert checks and told and not any("* 255" in m for m in told), told


def test_a_graded_functions_results_are_never_taken_in_another_order():
    """The API fixes what a graded function returns, in which order: `K, t, R = decompose(P)` mends
    `-R @ t` (a 1-D vector @ R is R^T t) but is never the fix; the product itself is changed instead."""
    source = textwrap.dedent("""
        def decompose(P):
            return P[:, :3], P[:, :3], P[:, 3]

        def centre(P):
            K, R, t = decompose(P)
            return -R @ t
    """)
    student = repair._Student(source, ast.parse(source), {"decompose", "centre"})
    told = [student.fix(m).told("centre") for m in student.ordered("centre")]
    assert told and not any("K, t, R" in said or "t, R" in said.split("=")[0] for said in told), told
    assert any("R" in said and "@" in said for said in told)


def test_a_repair_a_later_check_of_the_function_refutes_is_taken_back_with_its_sentence():
    """One account per function: the change told on one check, which another check of the same code
    ran again and failed with, is no account of the mistake; a hidden check's refutation changes no
    public word, and a hand-written name beside the change stays."""
    from autograder.engine.results import CheckResult

    change = "changing `ramp` to `-ramp` (line 318)"
    sentence = f"{repair.HEAD}: {change} makes `dp` pass this check, so the mistake may be there."
    public = CheckResult("a", 2.0, 4.0, "partial", f"dp(left, right): 60% of the square. {sentence}\nmore",
                         mistake="repair:negate")
    named = CheckResult("b", 0.0, 2.0, "failed", f"dp: it looks like the sign is wrong. {sentence}",
                        mistake="the sign is wrong", hidden=True)
    repair.take_back_refuted([public, named], [(change, True)])
    assert repair.HEAD in public.message and named.message == "dp: it looks like the sign is wrong."
    assert named.mistake == "the sign is wrong"
    repair.take_back_refuted([public], [(change, False)])
    assert public.message == "dp(left, right): 60% of the square.\nmore" and public.mistake == ""


def test_a_change_that_raises_on_a_nan_point_both_codes_answer_is_no_repair(tmp_path):
    """Removing the `continue` that skips points off the image (x <= 0 where x < 0 belongs) mends the
    border points and breaks every NaN point, which the student's code and the reference both skip:
    the change is not told (a point given as NaN, the API's value for one that has none)."""
    folder = mutant(tmp_path, "lab09_camera", '''
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    out = image.copy()
    fill = color if out.ndim == 3 else color[0]
    for x, y in np.asarray(pts, float).reshape(-1, 2):
        if not (x > 0 and y > 0):
            continue
        cv2.circle(out, (int(round(x)), int(round(y))), radius, fill, -1)
    return out
''')
    result = grade(str(folder), ["lab09.ex5"])
    failed = [c for c in check_results(result, "lab09.ex5") if c.score < c.max_score]
    assert failed and not any("removing `continue`" in c.message for c in failed), [c.message for c in failed]


def test_a_flag_too_many_is_dropped_not_turned_into_another_flag(tmp_path):
    """`INTER_LINEAR | WARP_INVERSE_MAP` beside a forward map: the fix drops the flag; `&` of the two
    (0: nearest-neighbour, another interpolation) is within the check's spread and no fix."""
    folder = mutant(tmp_path, "lab07_transformations", '''
def rotate(image, angle_deg=45):
    h, w = image.shape[:2]
    M = cv2.getRotationMatrix2D(((w - 1) / 2.0, (h - 1) / 2.0), angle_deg, 1.0)
    return cv2.warpAffine(image, M, (w, h), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP,
                          borderMode=cv2.BORDER_CONSTANT, borderValue=0)
''')
    messages = [c.message for c in check_results(grade(str(folder), ["lab07.ex2"]), "lab07.ex2") if c.score < c.max_score]
    assert any("to `cv2.INTER_LINEAR` (line" in m for m in messages), messages
    assert not any("cv2.INTER_LINEAR & cv2.WARP_INVERSE_MAP" in m for m in messages)


def test_an_image_of_floats_is_never_the_right_answer_for_an_8_bit_one():
    """A uint8 image warped as float32 and returned so: a change that keeps it float32 (the matrix's dtype
    changed) is no fix, however near its values are (30b's lab07/04 got `np.float32(...)` ->
    `np.asarray(...)`)."""
    from autograder.engine.mutants.repair import right

    reference = (np.arange(1200) % 251).astype(np.uint8).reshape(20, 20, 3)
    assert right(reference.copy(), reference)
    assert not right(reference.astype(np.float32), reference)
    assert not right(reference.astype(np.float32), reference, confirming=True)


def test_a_value_s_parts_named_as_the_reference_names_them_are_not_renamed(tmp_path):
    """`cols, rows = pattern_size` is right (the reference names the parts so); the grid built
    `np.mgrid[0:rows, 0:cols]` is the slip. Renaming the parts mends it too, by making the names lie."""
    folder = mutant(tmp_path, "lab10_camera2", '''
def _object_points(pattern_size, square_size):
    cols, rows = pattern_size
    objp = np.zeros((cols * rows, 3), np.float64)
    objp[:, :2] = np.mgrid[0:rows, 0:cols].T.reshape(-1, 2) * square_size
    return objp
''')
    messages = [c.message for c in check_results(grade(str(folder), ["lab10.ex6"]), "lab10.ex6") if c.score < c.max_score]
    assert any("`np.mgrid[0:rows, 0:cols]` to `np.mgrid[0:cols, 0:rows]`" in m for m in messages), messages
    assert not any("`rows, cols = pattern_size`" in m for m in messages)


ENLARGED_SCALE = '''
def scale(image, sx=1.5, sy=1.5):
    height, width = image.shape[:2]
    return _warp(image, scaling_matrix(sx, sy), (int(round(width * sx)), int(round(height * sy))))
'''


def test_a_factor_of_an_image_size_is_never_negated_and_a_helper_others_run_rightly_is_not_changed(tmp_path):
    """The canvas sized to the scaled image is the slip. `width * -sx` mends it only because OpenCV reads a
    negative size as the input's; `dsize or size` -> `dsize and size` in the warp helper mends it by
    breaking the warps translate and rotate (graded first, passing) run through it."""
    folder = mutant(tmp_path, "lab07_transformations", ENLARGED_SCALE)
    result = grade(str(folder), ["lab07.ex1", "lab07.ex3"])
    messages = [c.message for c in check_results(result, "lab07.ex3") if c.score < c.max_score]
    assert messages and all("the input's size times the transform's scale" in m for m in messages), messages
    assert not any("-sx" in m or "-sy" in m for m in messages), messages
    assert not any("`dsize and" in m for m in messages), messages


SWAPPED_DEFAULT_SIZE = '''
def _warp(image, M, dsize=None):
    height, width = image.shape[:2]
    return cv2.warpAffine(image, np.asarray(M, dtype=np.float64)[:2], dsize or (height, width))
'''


def test_a_change_in_a_shared_helper_must_not_lower_the_other_callers_scores_even_where_they_fail_too(tmp_path):
    """The helper's default size is (height, width). `dsize or` -> `dsize and` mends translate's calls (which give
    no size) by breaking every size a caller gives -- warp_affine's dsize check, graded after translate and
    passed by the student's own code; every caller fails elsewhere, so the passing-function rule cannot tell."""
    folder = mutant(tmp_path, "lab07_transformations", SWAPPED_DEFAULT_SIZE)
    result = grade(str(folder), ["lab07.ex1", "lab07.ex5"])
    messages = [c.message for c in check_results(result, "lab07.ex1") if c.score < c.max_score]
    assert messages and not any("`dsize and" in m for m in messages), messages
    assert any("`(height, width)` to `(width, height)`" in m for m in messages), messages
    dsize = [c for c in check_results(result, "lab07.ex5") if "dsize=" in c.name]
    assert dsize and all(c.score == c.max_score for c in dsize)   # (the student's own code is right there)


def test_confirmation_images_come_in_every_mix_of_channels():
    # a test of img1's channels where img2's belongs mends BGR + grey and breaks grey + grey: every mix is tried
    from autograder.engine.mutants.naming import other_channels

    bgr, grey = np.zeros((20, 30, 3), np.uint8), np.zeros((20, 30), np.uint8)
    mixes = [tuple(a.ndim for a in args[:2]) for _, args, _ in other_channels(("f", (bgr, grey, 5), {}))]
    assert mixes == [(2, 3), (2, 2), (3, 3)]   # (all turned first, as with one image)
    assert [args[0].ndim for _, args, _ in other_channels(("f", (grey,), {}))] == [3]
    assert [(args[0].ndim, kwargs["b"].ndim) for _, args, kwargs in other_channels(("f", (bgr,), {"b": bgr}))] \
        == [(2, 2), (2, 3), (3, 2)]
    assert other_channels(("f", (np.zeros((3, 2)),), {})) == []


def test_a_channel_test_of_the_other_image_is_not_mended_by_inverting_it(tmp_path):
    # the second image converted when the FIRST is grey: `not img1.ndim == 2` mends BGR + grey and breaks
    # grey + grey and BGR + BGR, which the student's code answers rightly: no such change is told
    submission = edited_reference(tmp_path, "lab08_homographies", (
        "    canvas[:h2, w1:] = _bgr(img2)\n",
        "    canvas[:h2, w1:] = cv2.cvtColor(img2, cv2.COLOR_GRAY2BGR) if img1.ndim == 2 else img2\n"))
    result = grade(submission, ["lab08.ex3"])
    failed = [c for e in result.exercises for c in e.checks if c.score < c.max_score]
    assert failed and not any("not img1.ndim == 2" in c.message for c in failed)


@pytest.mark.parametrize("module, exercise, source, told", [
    # an output allocated by the input's length: an IndexError for a disparity map (H, W)
    ("lab12_stereo", "lab12.ex2", '''
def depth_from_disparity(disparity, f, baseline):
    d = np.asarray(disparity, dtype=np.float64)
    valid = np.isfinite(d) & (d > 0)
    depth = np.zeros(len(d))
    depth[valid] = f * baseline / d[valid]
    return depth
''', "`np.zeros(len(d))` to `np.zeros(np.shape(d))` || `np.zeros(len(d))` to `np.zeros_like(d)`"),
    # a matrix made in the image's dtype: uint8 cannot hold a negative shift
    ("lab07_transformations", "lab07.ex1", '''
def translate(image, tx=100, ty=50):
    rows, cols = image.shape[:2]
    M = np.array([[1, 0, tx], [0, 1, ty]], dtype=image.dtype).astype(np.float32)
    return cv2.warpAffine(image, M, (cols, rows))
''', "dtype=np.float64)` (line"),
    # the first two points read where the two columns belong: one slip at two places
    ("lab09_camera", "lab09.ext2", '''
_reference_distort = distort_points
def distort_points(points, dist):
    pts = np.asarray(points, dtype=np.float64)
    x, y = pts[0], pts[1]
    return _reference_distort(np.column_stack([x, y]), dist)
''', "`pts[0], pts[1]` to `pts[:, 0], pts[:, 1]`"),   # (as written: no brackets)
    # the radial factor on x only: the first term of y's sum is bare where x's has the factor
    ("lab09_camera", "lab09.ext2", """
def distort_points(points, dist):
    pts = np.asarray(points, dtype=np.float64)
    k1, k2, p1, p2, k3 = (list(np.asarray(dist, dtype=np.float64).ravel()) + [0.0] * 5)[:5]
    x, y = pts[..., 0], pts[..., 1]
    r2 = x ** 2 + y ** 2
    radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    x_d = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x ** 2)
    y_d = y + p1 * (r2 + 2 * y ** 2) + 2 * p2 * x * y
    return np.stack([x_d, y_d], axis=-1)
""", "to `y_d = y * radial + p1 * (r2 + 2 * y ** 2) + 2 * p2 * x * y`"),
    # a term that does not belong (the depth plus f), and a conversion that does not (z_avg cut to an integer)
    ("lab09_camera", "lab09.ex1", """
def pinhole_project(points, f):
    X, single = _points(points)
    return _divide(np.column_stack([f * X[:, 0], f * X[:, 1], X[:, 2] + f]), single)
""", "to `[f * X[:, 0], f * X[:, 1], X[:, 2]]`"),
    ("lab10_camera2", "lab10.ex2", """
_reference_weak = weak_perspective_project
def weak_perspective_project(points, f, z_avg=None):
    X = np.atleast_2d(np.asarray(points, dtype=np.float64))
    z = X[:, 2].mean() if z_avg is None else int(z_avg)
    return _reference_weak(points, f, z)
""", "else int(z_avg)` to `X[:, 2].mean() if z_avg is None else z_avg` || else int(z_avg)` to `X[:, 2].mean() if z_avg is None else float(z_avg)`"),
])
def test_a_shape_a_dtype_and_a_row_for_a_column_are_told_as_the_change_that_mends_them(tmp_path, module, exercise,
                                                                                      source, told):
    result = grade(str(mutant(tmp_path, module, source)), [exercise], pictures="none")
    messages = [c.message for c in check_results(result, exercise) if c.score < c.max_score]
    assert any(_told_in(told, m) for m in messages), messages


def test_the_hidden_phase_gets_a_copy_of_what_the_public_checks_left_one_way():
    from types import SimpleNamespace

    from autograder.engine.inherited import SHARED_FAILING
    from autograder.engine.runner import _public_memory_to

    check_a, check_b = object(), object()
    public = [SimpleNamespace(shared={("checks calling", "f"): [(check_a, [])], (SHARED_FAILING, "m"): {"g"},
                                      "repair seen": {"f": [("f", (1,), {})]}, "error model named": ["x"]}),
              SimpleNamespace(shared={("checks calling", "f"): [(check_a, []), (check_b, [])]})]
    fresh = [SimpleNamespace(shared={})]
    _public_memory_to(fresh, public)
    hidden = fresh[0].shared
    assert [entry[0] for entry in hidden[("checks calling", "f")]] == [check_a, check_b]
    assert hidden[(SHARED_FAILING, "m")] == {"g"} and hidden["repair seen"] == {"f": [("f", (1,), {})]}
    assert "error model named" not in hidden
    hidden[("checks calling", "f")].append((object(), []))   # a hidden check remembered: never the public's
    assert len(public[0].shared[("checks calling", "f")]) == 1 and len(public[1].shared[("checks calling", "f")]) == 2


def test_a_factor_taken_inside_a_square_root_is_told_moved_out_not_dropped(tmp_path):
    # `np.sqrt(aperture * u)`: the fix moves the factor out; `aperture * u` (uniform radii, crowding the centre)
    # passes the checks too, but is not the reference's draw -- the nearest fix is told, never that one
    folder = edited_reference(tmp_path, "lab09_camera", (
        "radius = aperture * np.sqrt(rng.uniform(0.0, 1.0, size=(len(X), n_rays)))",
        "radius = np.sqrt(aperture * rng.uniform(0.0, 1.0, size=(len(X), n_rays)))"))
    messages = [c.message for c in check_results(grade(str(folder), ["lab09.ex4"]), "lab09.ex4") if c.score < c.max_score]
    assert any("to `aperture * np.sqrt(rng.uniform(0.0, 1.0, size=(len(X), n_rays)))`" in m for m in messages), messages
    assert not any("to `aperture * rng.uniform" in m for m in messages), messages


def test_a_matrix_divided_by_another_of_its_entries_is_not_the_fix_of_a_division_by_one_that_is_zero(tmp_path):
    # F / F[2, 2] fails where F[2, 2] = 0 (epipoles at infinity); F / F[1, 2] mends it only while F[1, 2] is not 0
    folder = mutant(tmp_path, "lab11_two_view", '''
def epipoles(F):
    F = np.asarray(F, dtype=np.float64)
    F = F / F[2, 2]
    U, _, Vt = np.linalg.svd(F)
    return Vt[-1], U[:, -1]
''')
    messages = [c.message for c in check_results(grade(str(folder), ["lab11.ex5"]), "lab11.ex5") if c.score < c.max_score]
    assert messages and not any("F / F[1, 2]" in m or "F / F[0, 2]" in m or "F / F[2, 1]" in m for m in messages), \
        messages


def test_renormalising_is_read_from_the_division_of_the_same_array_only():
    from types import SimpleNamespace

    source = "def f(F, G, v):\n    A = F / F[2, 2]\n    B = G / F[2, 2]\n    v /= v[-1]\n    return A, B, v\n"
    student = repair._Student(source, ast.parse(source), api=["f"])
    nodes, _ = student._walk("f")

    def divisor_index(line: str) -> int:   # the ordinal of the divisor's index in the statement `line...`
        statement = next(n for n in nodes if isinstance(n, (ast.Assign, ast.AugAssign)) and ast.unparse(n).startswith(line))
        index = next(n for n in ast.walk(statement) if isinstance(n, ast.Subscript)).slice
        return next(i for i, n in enumerate(nodes) if n is index)

    def renormalises(line: str) -> bool:
        return student.renormalises(SimpleNamespace(edits=(("f", divisor_index(line), "bound", 1),)))

    assert renormalises("A =") and renormalises("v /=")
    assert not renormalises("B =")   # (another array divided by F's entry: not F's own scale)


def test_a_comparison_beside_an_and_without_brackets_is_changed_to_the_bracketed_one():
    # `d > 0 & seen` is `d > (0 & seen)`; `m & d > 0` is `(m & d) > 0`: the brackets the precedence needs
    from autograder.engine.mutants.operators import _precedence_slips

    def changes(text):
        node = ast.parse(text, mode="eval").body
        return [payload for _, payload, _ in _precedence_slips(node)] if isinstance(node, ast.Compare) else []

    assert changes("disparity > 0 & seen") == ["(disparity > 0) & seen"]
    assert changes("mask & depth >= 1") == ["mask & (depth >= 1)"]
    assert changes("(disparity > 0) & seen") == [] and changes("a > b") == []


def test_slips_the_blind_sets_found_beyond_the_first_tables():
    """Each a class of slip, not a case: two functions applied at once (`np.tan(np.deg2rad(s))`), one
    value of a whole array where each item's own belongs (`depth.mean()`), a twin's step missing inside
    a wrapper both lines share, the smallest singular value kept in a diag written out, a canvas size made
    from both images another way, a value made once from a loop's first item, a grid along the other
    axis; none offered as a mutant of the reference."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(s, X, F, pts, img1, img2, height, u, v, w):
            depth = X[:, 2:3]
            shear = np.tan(np.deg2rad(s))
            x = X[:, :2] / depth.mean() + np.mean(depth)
            map_x = (u / w).astype(np.float32)
            map_y = v.astype(np.float32)
            U, S, Vt = np.linalg.svd(F)
            E = U @ np.diag([S[0], S[1], S[2]]) @ Vt
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((max(h1, h2), 2 * max(w1, w2), 3), np.uint8)
            first = F @ np.array([pts[0, 0], pts[0, 1], 1.0])
            norm = np.sqrt(first[0] ** 2 + first[1] ** 2)
            out = []
            for x0, y0 in pts:
                line = F @ np.array([x0, y0, 1.0])
                out.append(line / norm)
            rows = np.arange(height)[:, None] - x
            return shear, x, map_x, map_y, E, canvas, out, rows
    """)
    made = _made(source, {"unwrap", "twin_step", "rank", "canvas", "per_item", "grid_axis"})
    for pair in [("np.tan(np.deg2rad(s))", "s"), ("depth.mean()", "depth"), ("np.mean(depth)", "depth"),
                 ("map_y = v.astype(np.float32)", "map_y = (v / w).astype(np.float32)"),
                 ("np.diag([S[0], S[1], S[2]])", "np.diag([S[0], S[1], 0])"), ("2 * max(w1, w2)", "w1 + w2"),
                 ("np.arange(height)[:, None]", "np.arange(width)[None, :]")]:
        assert pair in made, (pair, made)
    assert ("norm", "np.sqrt(line[0] ** 2 + line[1] ** 2)") in made, made   # (inside the loop only)
    assert ("first", "line") not in made, made
    reference = {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]}
    assert not reference & {"unwrap", "per_item", "grid_axis", "twin_step"}


def test_a_value_copied_whole_and_a_last_entry_written_apart():
    """`poses[i, 3:] = rvec` (a copy-paste of the line above) gets the name unpacked with it; the last
    entry written apart from the first ones (`lines[i, 2] = line[2]` under `lines[i, :2] = line[:2] /
    norm`) gets their step."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(frames, F):
            poses = np.zeros((len(frames), 6))
            lines = np.zeros((len(frames), 3))
            for i, frame in enumerate(frames):
                rvec, tvec = frame[:3], frame[3:]
                poses[i, :3] = rvec
                poses[i, 3:] = rvec
                line = F @ frame[:3]
                norm = np.sqrt(line[0] ** 2 + line[1] ** 2)
                lines[i, :2] = line[:2] / norm
                lines[i, 2] = line[2]
            return poses, lines
    """)
    made = _made(source, {"other_name", "twin_step"})
    assert ("rvec", "tvec") in made, made
    assert ("lines[i, 2] = line[2]", "lines[i, 2] = line[2] / norm") in made, made
    reference = repair.mutants_of(source, {"graded"})["graded"]
    assert not any(m.operator == "other_name" and m.edits[0][3] == "tvec" and m.line == 10 for m in reference)
    # (a whole value copied: the student's code only)


def test_a_product_of_three_in_another_order_and_a_line_copied_from_its_twin():
    """`K2.T @ K1 @ F` gets its neighbouring factors exchanged; `grey2 = f(img1) if img2...` under
    `grey1 = f(img1) if img1...` gets its twin line's name at the one place they differ."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(F, K1, K2, img1, img2):
            E = K2.T @ K1 @ F
            grey1 = np.mean(img1, axis=2) if img1.ndim == 3 else img1
            grey2 = np.mean(img1, axis=2) if img2.ndim == 3 else img2
            return E, grey1, grey2
    """)
    made = _made(source, {"chain_order", "mirror"})
    assert ("K2.T @ K1 @ F", "K2.T @ F @ K1") in made, made
    assert ("grey2 = np.mean(img1, axis=2) if img2.ndim == 3 else img2",
            "grey2 = np.mean(img2, axis=2) if img2.ndim == 3 else img2") in made, made
    assert not any(before.startswith("grey1") for before, _ in made), made   # (the line its twin was copied from)
    reference = {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]}
    assert not reference & {"chain_order", "mirror"}


def test_a_running_best_started_at_zero_and_one_array_kept_at_every_turn():
    """`best = np.zeros(shape)` kept only where `cost < best` starts at +inf (or -inf); `frame =
    np.zeros(...)` made before a loop that appends it every turn is made anew inside the loop."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(costs, n):
            best = np.zeros(costs.shape[1:])
            shown = np.zeros(costs.shape[1:])
            for cost in costs:
                best = np.where(cost < best, cost, best)
            frames = []
            frame = np.zeros((4, 4))
            for i in range(n):
                frame[:] = i
                frames.append(frame)
            return best, shown, frames
    """)
    made = _made(source, {"initial"})
    assert ("np.zeros(costs.shape[1:])", "np.full(costs.shape[1:], np.inf)") in made, made
    assert len({before for before, _ in made}) == 1, made   # (`shown` is compared with nothing)
    fn = next(node for node in ast.parse(source).body if isinstance(node, ast.FunctionDef))
    moved = [m for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
             if m.operator == "indent" and m.edits[0][3][3] == "first"]
    assert [m.edits[0][3][1] for m in moved] == ["frame = np.zeros((4, 4))"], moved
    after = repair._MAKE["indent"](list(ast.walk(fn))[moved[0].edits[0][1]], moved[0].edits[0][3])
    assert ast.unparse(after.body[0]) == "frame = np.zeros((4, 4))"


def test_a_layout_a_type_an_order_of_division_a_colour_order_and_an_unread_parameter():
    """`lines.reshape(3, -1).T` for `reshape(-1, 3)`, `.astype(np.uint8)` where floats belong,
    `c // w * 2 ** n` for `c * 2 ** n // w`, a BGR image turned RGB, and a parameter never read where an
    operand is computed otherwise (each the student's code only)."""
    source = textwrap.dedent("""
        import numpy as np
        import cv2

        def graded(lines, volume, c, w, n, img, X, d, z0):
            out = lines.reshape(3, -1).T
            disparity = np.argmin(volume, axis=0).astype(np.uint8)
            k = c // w * 2 ** n
            rgb = cv2.cvtColor(img, cv2.COLOR_BGR2RGB)
            moved = X[:, 2] + d - X[:, 2].mean()
            return out, disparity, k, rgb, moved
    """)
    operators = {"reshape_back", "astype_float", "divide_last", "drop_colour", "unused"}
    made = _made(source, operators)
    for pair in [("lines.reshape(3, -1).T", "lines.reshape(-1, 3)"),
                 ("np.argmin(volume, axis=0).astype(np.uint8)", "np.argmin(volume, axis=0).astype(np.float64)"),
                 ("c // w * 2 ** n", "c * 2 ** n // w"), ("cv2.cvtColor(img, cv2.COLOR_BGR2RGB)", "img"),
                 ("X[:, 2].mean()", "z0")]:
        assert pair in made, (pair, made)
    reference = {m.operator for m in repair.mutants_of(source, {"graded"})["graded"]}
    assert not reference & operators


def test_a_step_done_to_one_of_two_locals_is_offered_for_its_twin_first():
    """`pts1 = pts1[inliers]` without the same for `pts2` (a local, not a parameter): the step done to
    both is offered, and comes before the same step given to the def's other parameters."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(matches, K, mask):
            pts1 = np.float64([m[0] for m in matches])
            pts2 = np.float64([m[1] for m in matches])
            inliers = mask.ravel().astype(bool)
            pts1 = pts1[inliers]
            return pts1, pts2, K
    """)
    made = _made(source, {"sibling_step"})
    assert ("pts1 = pts1[inliers]", "pts1, pts2 = (pts1[inliers], pts2[inliers])") in made, made
    student = repair._Student(source, ast.parse(source), ["graded"])
    siblings = [m for m in student.ordered("graded") if m.operator == "sibling_step"]
    assert siblings and siblings[0].edits[0][3] == "pts2", [m.edits[0][3] for m in siblings]


def test_a_truth_test_of_an_optional_array_and_positions_counted_from_one():
    """`... if dist else None` (an array has no truth value) gets `dist is not None`; `np.arange(1, w + 1)`
    where indices belong gets `np.arange(w)`, its keywords kept."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(K, w, dist=None):
            dist = np.asarray(dist) if dist else None
            if not dist:
                pass
            cols = np.arange(1, w + 1, dtype=np.float64)
            return dist, cols
    """)
    made = _made(source, {"default", "zero_based"})
    assert ("np.asarray(dist) if dist else None", "np.asarray(dist) if dist is not None else None") not in made
    assert ("dist", "dist is not None") in made, made
    assert ("not dist", "dist is None") in made, made
    assert ("np.arange(1, w + 1, dtype=np.float64)", "np.arange(w, dtype=np.float64)") in made, made


def test_names_unpacked_as_written_are_never_exchanged_by_a_repair():
    """`for x, y in pts` and `k1, k2, p1, p2, k3 = d` (named as the reference names them, or an axis
    pair in order): exchanging them mends a use by making the names lie; `w, h = image.shape[:2]` (a
    shape, rows first) stays a repair."""
    parts = frozenset({("", ("k1", "k2", "p1", "p2", "k3")), ("", ("w", "h"))})
    assert repair._names_as_written(["x", "y"], frozenset())
    assert repair._names_as_written(["u1", "v1"], frozenset())
    assert repair._names_as_written(["X", "Y", "Z"], frozenset())
    assert not repair._names_as_written(["Y", "X", "Z"], frozenset())
    assert not repair._names_as_written(["y", "x"], frozenset())
    assert repair._names_as_written(["k1", "k2", "p1", "p2", "k3"], parts)
    shape = ast.parse("image.shape[:2]", mode="eval").body
    assert not repair._names_as_written(["w", "h"], parts, shape)
    # (a shape's sides rows first by their own words, whatever the reference calls them: exchanging
    # `h, w = image.shape[:2]` mends a later `(h, w)` given where OpenCV reads (width, height) by
    # making the names lie)
    for rows_first in (["h", "w"], ["height", "width"], ["H1", "W1"], ["rows", "cols", "channels"]):
        assert repair._names_as_written(rows_first, frozenset(), shape), rows_first
    assert not repair._names_as_written(["w", "h"], frozenset(), shape)
    assert not repair._names_as_written(["hw", "ww"], frozenset(), shape)
    assert repair._names_as_written(["w", "h"], parts, ast.parse("dsize", mode="eval").body)
    rows_first = ast.parse("np.argwhere(mask)", mode="eval").body   # (rows first: `for x, y` is the slip)
    assert not repair._names_as_written(["x", "y"], parts, rows_first)
    source = textwrap.dedent("""
        import numpy as np

        def graded(image, pts, d):
            k1, k2, p1, p2, k3 = d
            for x, y in pts:
                image[int(x), int(y)] = k1 + p2
            for i, (X, Y, Z) in enumerate(pts):
                image[i] = Y / Z
            w, h = image.shape[:2]
            return image, w
    """)
    student = repair._Student(source, ast.parse(source), ["graded"])
    student.reference_parts = parts
    swaps = [m for m in student.mutants("graded") if m.operator == "swap_items" and m.edits[0][3] is not None]
    refused = {student.fix(m).changes[0][1] for m in swaps if student.fix(m) and student.reorders_api_results(m)}
    kept = {student.fix(m).changes[0][1] for m in swaps if student.fix(m) and not student.reorders_api_results(m)}
    assert any("k1, k2, p1, p2, k3" in text for text in refused), refused
    assert "x, y" in refused, refused   # (as written: no brackets)
    assert "i, (X, Y, Z)" in refused, refused   # (a point's coordinates in capitals, in a nested tuple)
    assert "w, h = image.shape[:2]" in kept, kept


def test_sizes_named_by_the_axis_they_measure_are_not_exchanged():
    """`missing_rows, missing_cols = height - ..., width - ...`: each name says the axis of its value (a word
    of it), so exchanging the names or the values mends a later swap by making the names lie; names that
    say nothing of an axis may be exchanged."""
    source = textwrap.dedent("""
        def graded(image, part):
            height, width = image.shape[:2]
            missing_rows, missing_cols = height - part.shape[0], width - part.shape[1]
            first, second = height - part.shape[0], width - part.shape[1]
            return missing_rows, missing_cols, first, second
    """)
    student = repair._Student(source, ast.parse(source), ["graded"])
    student.reference_parts = frozenset()
    swaps = [m for m in student.mutants("graded") if m.operator == "swap_items" and student.fix(m)
             and student.fix(m).changes[0][0] in (4, 5)]
    refused = {(student.fix(m).changes[0][0], student.fix(m).changes[0][1]) for m in swaps if student.reorders_api_results(m)}
    kept = {(student.fix(m).changes[0][0], student.fix(m).changes[0][1]) for m in swaps if not student.reorders_api_results(m)}
    assert {line for line, _ in refused} == {4}, (refused, kept)
    assert any(line == 5 for line, _ in kept), kept
    assert len(refused) >= 2, refused   # (the names exchanged, and the values)


def test_a_fix_downstream_of_another_in_the_same_def_is_dropped():
    """Two fixes each mending every input: the one at a line reading what the other's earlier line
    assigns (directly or through the lines between) undoes the first one's slip after the fact."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(width, d):
            cols = np.arange(1, width + 1)
            u = cols[None, :]
            proj = np.floor(u - d + 0.5)
            return proj
    """)
    fn = {f.name: f for f in ast.parse(source).body if isinstance(f, ast.FunctionDef)}
    code = type("Code", (), {"functions": fn})()
    upstream = repair.Fix(((5, "np.arange(1, width + 1)", "np.arange(width)"),), "graded", "zero_based", ())
    downstream = repair.Fix(((7, "u - d + 0.5", "u - d - 0.5"),), "graded", "sign", ())
    both = repair.Repair("graded", (upstream, downstream), 9)
    assert repair._downstream_dropped(both, code).fixes == (upstream,)
    apart = repair.Repair("graded", (downstream, repair.Fix(((8, "proj", "proj.T"),), "graded", "transpose", ())), 9)
    assert len(repair._downstream_dropped(apart, code).fixes) == 1   # (line 8 reads proj, which line 7 assigns)


def test_a_change_that_only_shrinks_a_size_term_is_refuted_on_small_images(tmp_path):
    """Scaling about the image centre where the top-left corner belongs: on large images `2 / w` where
    `w / 2` was shifts by a fraction of a pixel, as the translation made 0 does not; on the small-image
    confirmation input (judged to rounding) it is wrong, and the change told is the translation's."""
    folder = mutant(tmp_path, "lab07_transformations", """
        def scale(image, sx=1.5, sy=1.5):
            h, w = image.shape[:2]
            cx = w / 2
            cy = h / 2
            M = np.array([[sx, 0.0, cx - sx * cx], [0.0, sy, cy - sy * cy]], dtype=np.float32)
            return cv2.warpAffine(image, M, (w, h), flags=cv2.INTER_LINEAR,
                                  borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """)
    result = grade(folder, ["lab07.ex3"], pictures="none", include_hidden=False)
    told = [c.message for c in check_results(result, "lab07.ex3") if not c.passed and "Trying small changes" in c.message]
    assert told, [c.message for c in check_results(result, "lab07.ex3")]
    assert not any("to `2 / w`" in m or "to `2 / h`" in m for m in told), told
    assert any("to `0`" in m for m in told), told


def test_the_small_image_input_cuts_every_image_alike_and_reads_sizes_through_names():
    left, right = np.zeros((60, 80, 3), np.uint8), np.ones((60, 80, 3), np.uint8)
    [small] = repair._small(("f", (left, right, 3.0), {"mask": np.zeros((10, 10), np.uint8)}))
    assert small[1][0].shape == (*repair.SMALL_IMAGE, 3) and small[1][1].shape == (*repair.SMALL_IMAGE, 3)
    assert small[1][2] == 3.0 and small[2]["mask"].shape == (10, 10)   # (too small to cut: as it was)
    assert repair._small(("f", (np.zeros((5, 5), np.uint8),), {})) == []
    source = textwrap.dedent("""
        def graded(image, s):
            h, w = image.shape[:2]
            c = (w - 1) / 2
            t = c - s * c
            k = s * 2
            M = np.eye(3)
            M[0, 2] = t
            return image * k + t
    """)
    student = repair._Student(source, ast.parse(source), ["graded"])
    assert student._size_names("graded") == {"h", "w", "c", "t"}   # (M: an entry set from a size, not a size)
    lines = {m.line: student.reads_size(m) for m in student.mutants("graded")}
    assert lines.get(4) and lines.get(5) and lines.get(9) and lines.get(6) is False, lines


def test_a_pair_of_changes_that_divides_a_matrix_by_another_of_its_entries_is_never_told(tmp_path):
    """`P / P[2, 3]` (t_z: 0 for a camera at the world origin) made `P / P[0, 0]` by two index changes
    only changes P's scale -- by an entry that happens to be positive on the inputs tried -- as one
    index change does: the division taken out is the change told."""
    folder = mutant(tmp_path, "lab09_camera", """
        def project(P, points):
            X, single = _points(points)
            P = np.asarray(P, dtype=np.float64)
            Pn = P / P[2, 3]
            homogeneous = np.column_stack([X, np.ones(len(X))])
            return _divide(homogeneous @ Pn.T, single)
        """)
    result = grade(folder, ["lab09.ex3"], pictures="none", include_hidden=False)
    told = [c.message for c in check_results(result, "lab09.ex3") if not c.passed]
    assert told and not any(re.search(r"P\[\d, \d\]` \(line", m) for m in told), told
    assert any("to `Pn = P`" in m for m in told), told


def test_the_parts_of_an_item_unpacked_inside_the_loop_are_siblings_too():
    """`for pair in matches:` then `m, n = pair`: the second neighbour's index kept where the best's
    belongs (`kp2[n.trainIdx]`) is a change tried among the first of its kind, as for `for m, n in
    matches`; names unpacked from anything but a loop's item are not siblings."""
    source = textwrap.dedent("""
        def graded(matches, kp1, kp2, size):
            pts1, pts2 = [], []
            w, h = size
            for pair in matches:
                m, n = pair
                if m.distance < 0.75 * n.distance:
                    pts1.append(kp1[m.queryIdx].pt)
                    pts2.append(kp2[n.trainIdx].pt)
            return pts1, pts2, w * h
    """)
    tree = ast.parse(source)
    assert repair.unpacked_items(tree.body[0]) == [{"m", "n"}]
    student = repair._Student(source, tree, {"graded"})
    swaps = [m for m in student.mutants("graded") if student.zipped_swap(m)]
    assert any(student.fix(m).changes[0][1:] == ("kp2[n.trainIdx]", "kp2[m.trainIdx]") for m in swaps), \
        [student.fix(m).changes for m in swaps]
    assert not any("h" in re.findall(r"\w+", student.fix(m).changes[0][2]) for m in swaps)


def test_a_parameter_read_after_the_function_resolved_it_is_tried_among_the_first():
    """`s = DEFAULT if smoothness is None else smoothness`, then `DEFAULT * ramp` where `s` belongs (a
    module default read again), or a point set read raw after it was normalised: the resolved name
    for the raw one is a change tried first; the same change before the resolving line is not."""
    source = textwrap.dedent("""
        import numpy as np
        DEFAULT = 0.5

        def graded(costs, smoothness=None, pts=None):
            early = DEFAULT * costs
            s = DEFAULT if smoothness is None else smoothness
            pts_n = pts - pts.mean(axis=0)
            ramp = DEFAULT * np.arange(len(costs))
            spread = np.abs(pts).max()
            mixed = costs * spread
            total = np.sum(costs)
            return early + ramp + spread + s + pts_n.sum() + mixed + total
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    resolved = {student.fix(m).changes[0][1:] for m in student.mutants("graded") if student.resolved_name(m)}
    assert ("DEFAULT * np.arange(len(costs))", "s * np.arange(len(costs))") in resolved, resolved
    assert ("np.abs(pts).max()", "np.abs(pts_n).max()") in resolved, resolved
    assert not any("mixed" in after for _, after in resolved), resolved   # (made of two values: no stand-in)
    assert not any(before.startswith("DEFAULT * costs") for before, _ in resolved), resolved
    first = [m for m in student.ordered("graded") if m.operator == "other_name"][:2]   # (each kind has its turns)
    assert all(student.resolved_name(m) for m in first), [student.fix(m).changes for m in first]


def test_a_block_of_columns_moved_by_its_own_width_is_a_change_tried():
    """A design matrix's second row written with the first row's columns (`A[r + 1, 0:4] = X` where
    `4:8` belongs: the line copied, its block left): the window moved by its width, either way (never
    below 0), beside the window moved by one."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(X, r):
            A = np.zeros((2, 12))
            A[0, 0:4] = X
            A[1, 0:4] = X
            A[1, 8:12] = -r * X
            return A
    """)
    changes = _shown_changes(source, "slice")
    assert ("A[1, 0:4] = X", "A[1, 4:8] = X") in changes, changes
    assert ("A[1, 8:12] = -r * X", "A[1, 4:8] = -r * X") in changes, changes
    assert ("A[1, 0:4] = X", "A[1, 1:5] = X") in changes and not any("[1, -" in after for _, after in changes), changes


def test_a_function_changed_for_its_opposite_keeps_its_arguments():
    """`np.argmin(d, axis=2)` -> `np.argmax(d, axis=2)`, and an array's own method (`bits.all(axis=0)`
    -> `bits.any(axis=0)`: every bit lit where one lit bit belongs): the call with its arguments, never
    the bare function (`np.argmax`, a value no caller wants)."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(d, bits):
            best = np.argmin(d, axis=2)
            lit = bits.all(axis=0)
            return best, lit, max(1, 2)
    """)
    changes = _shown_changes(source, "minmax")
    assert ("np.argmin(d, axis=2)", "np.argmax(d, axis=2)") in changes, changes
    assert ("bits.all(axis=0)", "bits.any(axis=0)") in changes, changes
    assert ("best, lit, max(1, 2)", "best, lit, min(1, 2)") in changes, changes


def test_a_bound_over_two_values_is_changed_for_either_value_and_one_side_kept_twice_is_one_slip():
    """`max(reference.shape[0], moving.shape[0])` where the reference's own height belongs (a canvas sized
    by the larger image): each argument alone is a change tried, and keeping the first side at the height's
    line and at the width's is the same slip made twice (a pair the search tries first)."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(reference, moving, scores):
            height = max(reference.shape[0], moving.shape[0])
            width = max(reference.shape[1], moving.shape[1])
            depth = np.maximum(reference, 1.0)
            return height, width, depth, max(scores, key=len)
    """)
    changes = _shown_changes(source, "one_of_two")
    assert ("max(reference.shape[0], moving.shape[0])", "reference.shape[0]") in changes, changes
    assert ("max(reference.shape[0], moving.shape[0])", "moving.shape[0]") in changes, changes
    assert ("np.maximum(reference, 1.0)", "reference") in changes, changes
    assert not any("scores" in before for before, _ in changes), changes   # (one argument: no bound over two)
    student = repair._Student(source, ast.parse(source), {"graded"})
    slips = {student.fix(m).changes[0][1:]: student.slip(m) for m in student.mutants("graded")
             if m.operator == "one_of_two"}
    assert slips[("max(reference.shape[0], moving.shape[0])", "reference.shape[0]")] \
        == slips[("max(reference.shape[1], moving.shape[1])", "reference.shape[1]")]
    assert slips[("max(reference.shape[0], moving.shape[0])", "reference.shape[0]")] \
        != slips[("max(reference.shape[0], moving.shape[0])", "moving.shape[0]")]


def test_a_pixel_centred_on_the_principal_point_is_given_the_focal_lengths_division_it_lacks():
    """Normalised coordinates made halfway (K^-1 is a shift by the principal point AND a division by the focal
    length): `pts - K[:2, 2]` -> `(pts - K[:2, 2]) @ np.linalg.inv(K[:2, :2]).T`, `u - K[0, 2]` -> `/ K[0, 0]`;
    a coordinate divided already is left as it is."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(pts, K, u, v):
            xy = pts - K[:2, 2]
            x = u - K[0, 2]
            y = (v - K[1, 2]) / K[1, 1]
            return xy, x, y
    """)
    changes = _shown_changes(source, "focal_left_out")
    assert ("pts - K[:2, 2]", "(pts - K[:2, 2]) @ np.linalg.inv(K[:2, :2]).T") in changes, changes
    assert ("x = u - K[0, 2]", "x = (u - K[0, 2]) / K[0, 0]") in changes, changes   # (shown as the whole short line)
    assert not any("v -" in before for before, _ in changes), changes


def test_a_vector_of_two_plain_values_is_turned_a_quarter_either_way():
    """A line's normal walked along as its direction: `np.array([a, b])` -> `[-b, a]` or `[b, -a]` (a negated
    item written back without its sign); a pair computed in place (`(w - 1, h)`), or two values exchanged
    (`P1, P2 = P2, P1`: matrices), is no such vector."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(a, b, line, w, h, P1, P2):
            direction = np.array([a, b])
            normal = [-line[1], line[0]]
            P1, P2 = P2, P1
            return direction, normal, (w - 1, h), P1 @ P2
    """)
    changes = _shown_changes(source, "perpendicular")
    assert ("np.array([a, b])", "np.array([-b, a])") in changes and ("np.array([a, b])", "np.array([b, -a])") in changes
    assert ("[-line[1], line[0]]", "[-line[0], -line[1]]") in changes, changes
    assert ("[-line[1], line[0]]", "[line[0], line[1]]") in changes, changes
    assert not any("w - 1" in before or "P1" in before for before, _ in changes), changes


def test_an_inverse_trigonometric_angle_is_given_in_degrees_where_it_is_not_already():
    """`np.arctan2(b, a)` compared with 45 and 135: `np.degrees(np.arctan2(b, a))`; one converted already is not
    converted again."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(a, b, c):
            angle = np.arctan2(b, a)
            tilt = np.degrees(np.arccos(c))
            return 45.0 <= abs(angle) <= 135.0, tilt
    """)
    changes = _shown_changes(source, "to_degrees")
    assert changes == [("np.arctan2(b, a)", "np.degrees(np.arctan2(b, a))")], changes


def test_a_type_test_narrower_than_the_numbers_allowed_is_widened():
    """`isinstance(z_avg, float)` takes an int depth for none: -> `(int, float, np.number)`; a test of another
    kind (`isinstance(x, str)`) is left as it is."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(points, z_avg=None, method="x"):
            z = z_avg if isinstance(z_avg, float) else points[:, 2].mean()
            return z, isinstance(method, str)
    """)
    changes = _shown_changes(source, "type_widened")
    assert changes == [("isinstance(z_avg, float)", "isinstance(z_avg, (int, float, np.number))")], changes


def test_an_image_size_written_as_numbers_is_given_the_input_image_s_size():
    """`size = (640, 480)` for maps of whatever image is given -> `(image.shape[1], image.shape[0])`; small numbers
    (`(3, 3)`, a kernel) and a function with no image parameter have no such change."""
    source = textwrap.dedent("""
        import cv2
        def graded(image, K):
            size = (640, 480)
            kernel = (3, 3)
            return cv2.resize(image, size), kernel

        def other(points):
            return (640, 480)
    """)
    changes = _shown_changes(source, "size_written")
    assert changes == [("size = (640, 480)", "size = (image.shape[1], image.shape[0])")], changes


def test_a_dicts_entries_are_taken_in_the_order_of_their_keys():
    """A dict filled from the middle outwards and listed as it was filled: `d.values()` -> its values by their
    keys' order, `d.keys()` and `d.items()` sorted; a method given arguments (`d.get(k)`) is no listing."""
    source = textwrap.dedent("""
        def graded(to_reference, k):
            homographies = [H for H in to_reference.values()]
            return homographies, list(to_reference.keys()), list(to_reference.items()), to_reference.get(k)
    """)
    changes = _shown_changes(source, "key_order")
    assert ("to_reference.values()", "[to_reference[k] for k in sorted(to_reference)]") in changes, changes
    assert ("to_reference.keys()", "sorted(to_reference)") in changes, changes
    assert ("to_reference.items()", "sorted(to_reference.items())") in changes, changes
    assert len(changes) == 3, changes


def test_a_conjugation_turned_round_is_told_as_its_outer_factors_exchanged_not_as_a_passing_helpers_slip(tmp_path):
    """rotate as T(-c) R T(c) where T(c) R T(-c) belongs: the reference's rotate with rotation_matrix's
    subtraction swapped answers alike, but the student's rotation_matrix passes its own checks -- the
    error model names nothing there; the change told exchanges the product's outer factors."""
    folder = edited_reference(tmp_path, "lab07_transformations", (
        "    return _warp(image, rotation_matrix(angle_deg, centre))",
        "    M = translation_matrix(-centre[0], -centre[1]) @ rotation_matrix(angle_deg) @ translation_matrix(*centre)\n"
        "    return _warp(image, M)"))
    result = grade(folder, ["lab07.ex2"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab07.ex2") if not c.passed]
    assert failed and all("rotation_matrix`, which it calls" not in c.message for c in failed), \
        [c.message for c in failed]
    assert any("to `translation_matrix(*centre) @ ... @ translation_matrix(-centre[0], -centre[1])`" in c.message
               for c in failed), [c.message for c in failed]


def test_two_calls_of_one_function_moved_to_each_others_place_keep_their_arguments_when_shown():
    before = ast.parse("f(a_long_name, 1) @ g(x) @ f(another_long_name, 2)", mode="eval").body
    after = ast.parse("f(another_long_name, 2) @ g(x) @ f(a_long_name, 1)", mode="eval").body
    shown_before, shown_after = repair._abbreviated(before, after)
    assert shown_before != shown_after and "a_long_name" in shown_before and "another_long_name" in shown_after


def test_the_error_model_names_no_change_inside_a_graded_function_whose_checks_all_passed():
    """A mutant of rotate's reference whose change sits in rotation_matrix reproduces a rotate that
    composes its translations the other way round; the student's rotation_matrix passed every check of
    its own in this grading, so the slip is not there: nothing is named. Where it failed (or was not
    graded yet), the name stands."""
    from types import SimpleNamespace

    from autograder.engine.inherited import SHARED_FAILING
    from autograder.engine.mutants import naming

    inside = Mutant("swap_operands", "rotate", "rotation_matrix", 30, (("rotation_matrix", 5, "swap_operands", None),),
                    "in `rotate` (in `rotation_matrix`, which it calls), the subtraction has its operands swapped")
    own = Mutant("sign", "rotate", "rotate", 40, (("rotate", 3, "sign", None),), "in `rotate`, a sign")
    shared = {("checks calling", "rotation_matrix"): ["a check"], ("checks calling", "rotate"): ["a check"],
              (SHARED_FAILING, "lab07_transformations"): {"rotate"}}
    trial = SimpleNamespace(sandbox=SimpleNamespace(shared=shared), lab=SimpleNamespace(module="lab07_transformations"))
    assert naming._vouched_for(naming.Naming(inside, 1, 1), trial)
    assert not naming._vouched_for(naming.Naming(own, 1, 1), trial)
    shared[(SHARED_FAILING, "lab07_transformations")].add("rotation_matrix")
    assert not naming._vouched_for(naming.Naming(inside, 1, 1), trial)


def test_a_size_given_to_an_opencv_drawing_call_as_its_colour_is_never_a_fix():
    """`cv2.line(canvas, p, q, colour, 1)` -> `cv2.line(canvas, p, q, width, 1)`: on a grey image a line
    of the value 60 is drawn, which a check of lines drawn accepts; a size is no colour. Another local
    as the colour (`white`), or a size where a size belongs, stays a change tried."""
    source = textwrap.dedent("""
        import cv2

        def graded(canvas, lines, palette):
            height, width = canvas.shape[:2]
            white = 255
            for i, (p, q) in enumerate(lines):
                colour = palette[i]
                cv2.line(canvas, p, q, colour, 1)
                cv2.circle(canvas, p, 3, color=colour)
            return canvas, width
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    told = {(student.fix(m).changes[0][2], student.colours_with_a_size(m)) for m in student.mutants("graded")
            if m.operator == "other_name" and student.fix(m) is not None}
    flagged = {after for after, refused in told if refused}
    assert any(after.startswith("cv2.line(canvas, p, q, h") or after.startswith("cv2.line(canvas, p, q, w")
               for after in flagged), told
    assert any(after.startswith("cv2.circle(canvas, p, 3, color=") for after in flagged), told
    # (only the colour: the canvas or a point given a size is another change, judged as any other)
    assert all(re.search(r"(, (height|width), 1\)|color=(height|width)\))$", after) for after in flagged), flagged
    assert ("cv2.line(width, p, q, colour, 1)", False) in told or ("cv2.line(height, p, q, colour, 1)", False) in told


def test_a_name_bounding_a_slice_is_a_change_tried():
    """img2 pasted at its own width (`canvas[:h2, w2:]` where `w1:` belongs): a slice's bound is a
    place a name's twin is tried, as in a call or a product."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(img1, img2):
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((max(h1, h2), w1 + w2), np.uint8)
            canvas[:h1, :w1] = img1
            canvas[:h2, w2:] = img2
            return canvas
    """)
    assert ("canvas[:h2, w2:]", "canvas[:h2, w1:]") in _shown_changes(source, "other_name")


def test_every_product_of_a_chain_taken_element_by_element_is_one_change():
    """`K2.T * F * K1` where `K2.T @ F @ K1` belongs: one `*` made `@` at a time crosses the other's place
    (no pair of them can be made), so the chain's products are changed together; and the reverse."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(F, K1, K2):
            E = K2.T * F * K1
            H = K1 @ F @ K2
            return E, H
    """)
    changes = _shown_changes(source, "arithmetic")
    assert ("K2.T * F * K1", "K2.T @ F @ K1") in changes, changes
    assert ("H = K1 @ F @ K2", "H = K1 * F * K2") in changes, changes


def test_an_index_tested_against_its_upper_end_only_is_given_its_lower_end():
    """`cols < width` where a projector column may be negative (NumPy counts it from the end): the test
    with its lower end too is offered; a comparison with a number is left as it is."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(cols, width, d):
            lit = cols < width
            near = d < 3
            return lit, near
    """)
    made = _made(source, {"lower_bound"})
    assert made == {("cols < width", "(cols >= 0) & (cols < width)")}, made


def test_a_squared_distance_is_compared_with_a_squared_bound():
    """`dx ** 2 + dy ** 2 <= r` (a disc of radius sqrt(r)): the bound squared is offered; a distance with its
    root taken compared with `r ** 2` gets the bound unsquared; a comparison of two unsquared values is left."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(xx, yy, cx, cy, radius, a, b):
            disc = (xx - cx) ** 2 + (yy - cy) ** 2 <= radius
            ring = np.hypot(xx - cx, yy - cy) < radius ** 2
            plain = a < b
            return disc, ring, plain
    """)
    made = _made(source, {"squared_bound"})
    assert made == {("(xx - cx) ** 2 + (yy - cy) ** 2 <= radius", "(xx - cx) ** 2 + (yy - cy) ** 2 <= radius ** 2"),
                    ("np.hypot(xx - cx, yy - cy) < radius ** 2", "np.hypot(xx - cx, yy - cy) < radius")}, made


def test_an_entry_of_a_shape_is_read_on_the_next_axis_and_the_last():
    """`images.shape[1]` of an (n, H, W) stack where the width belongs: the next axis and the last are offered
    beside the swap of height and width (1202e 12/08)."""
    source = textwrap.dedent("""
        def graded(images, k, n):
            return (k + 0.5) * images.shape[1] / 2 ** n
    """)
    made = _made(source, {"axis"})   # (the index changed: `1` of `images.shape[1]`)
    assert {("1", "0"), ("1", "2"), ("1", "-1")} <= made, made


def test_a_value_rounded_to_some_decimals_is_offered_exact():
    """`np.round(np.cos(t), 2)`, `round(s, 3)` and `c.round(2)`: the rounding taken off is offered (as it is of
    `np.round(x)`, a one-argument call)."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(t, s, c, x):
            return np.round(np.cos(t), 2), round(s, 3), c.round(2), np.round(x)
    """)
    made = _made(source, {"unwrap"})
    assert {("np.round(np.cos(t), 2)", "np.cos(t)"), ("round(s, 3)", "s"), ("c.round(2)", "c")} <= made, made


def test_a_similarity_gets_its_translation_scaled_or_unscaled():
    """[[s, 0, -c[0]], [0, s, -c[1]], [0, 0, 1]] (the scale and the shift composed in the other order) gets
    `-s * c[0]`, `-s * c[1]`; the scaled one gets them unscaled; a matrix whose diagonal is not one name, not."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(s, c, a, b):
            T = np.array([[s, 0.0, -c[0]], [0.0, s, -c[1]], [0.0, 0.0, 1.0]])
            U = np.array([[s, 0.0, -s * c[0]], [0.0, s, -s * c[1]], [0.0, 0.0, 1.0]])
            V = np.array([[a, 0.0, -c[0]], [0.0, b, -c[1]], [0.0, 0.0, 1.0]])
            return T, U, V
    """)
    made = {after for _, after in _made(source, {"translation_scaled"})}
    assert made == {"[[s, 0.0, -s * c[0]], [0.0, s, -s * c[1]], [0.0, 0.0, 1.0]]",
                    "[[s, 0.0, -c[0]], [0.0, s, -c[1]], [0.0, 0.0, 1.0]]"}, made


def test_point_sets_given_to_opencv_are_transposed_together():
    """Both point sets of one OpenCV call made columns at once (each alone is refused by OpenCV)."""
    source = textwrap.dedent("""
        import cv2

        def graded(P1, P2, pts1, pts2):
            return cv2.triangulatePoints(P1, P2, pts1, pts2)
    """)
    made = _made(source, {"transpose"})
    assert ("cv2.triangulatePoints(P1, P2, pts1, pts2)", "cv2.triangulatePoints(P1, P2, pts1.T, pts2.T)") in made, made


def test_a_value_per_row_reduced_flat_is_kept_as_a_column():
    """`lines / np.linalg.norm(lines[:, :2], axis=1)`: the (N,) norms against the (N, 3) lines broadcast
    against the columns (or raise); the reduction with keepdims=True is offered, one without an axis not."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(lines, x):
            unit = lines / np.linalg.norm(lines[:, :2], axis=1)
            centred = x - x.mean(axis=0)
            return unit, centred, x / np.sum(x)
    """)
    made = _made(source, {"keep_axis"})
    assert ("np.linalg.norm(lines[:, :2], axis=1)", "np.linalg.norm(lines[:, :2], axis=1, keepdims=True)") in made
    assert ("x.mean(axis=0)", "x.mean(axis=0, keepdims=True)") in made, made
    assert not any(before == "np.sum(x)" for before, _ in made), made


def test_statements_taken_out_are_one_slip_only_where_written_alike():
    """Two statements removed are the same slip made twice only where they are written alike, names apart
    (`x /= 2`, `y /= 2`): the two halves of a normalisation, removed together, disable a step (30k's
    lab10/03: its scale and its shift taken out passed the checks and broke points far from the origin)."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(x, y, c, s):
            x /= 2
            y /= 2
            T = np.eye(3)
            T[:-1, :-1] *= s
            T[:-1, -1] = -s * c
            return x, y, T
    """)
    student = repair._Student(source, ast.parse(source), ["graded"])
    removed = {student.fix(m).changes[0][1]: student.slip(m) for m in student.mutants("graded")
               if m.operator == "drop_statement" and student.fix(m)}
    assert removed["x /= 2"] == removed["y /= 2"], removed
    assert removed["T[:-1, :-1] *= s"] != removed["T[:-1, -1] = -s * c"], removed


def test_a_bit_read_one_place_off_and_a_scaled_identity_are_changes_tried():
    """`(g >> (n - i)) & 1` where `n - 1 - i` belongs (no constant to move by one: the shift's amount
    given one more or less), and `f * np.eye(3)` for an intrinsic matrix whose last entry stays 1."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(g, n, i, f):
            bit = (g >> (n - i)) & 1
            K = f * np.eye(3)
            return bit, K
    """)
    made = _made(source, {"zero_based", "zero_entry"})
    assert ("g >> n - i", "g >> n - i - 1") in made and ("g >> n - i", "g >> n - i + 1") in made, made
    assert ("f * np.eye(3)", "np.diag([f, f, 1.0])") in made, made


# ------------------------------------------------------------------ places written as the reference writes them
def _anchored_lines(student: str, reference: str) -> set[int]:
    from autograder.engine.mutants import anchors

    mine, theirs = ast.parse(textwrap.dedent(student)).body[0], ast.parse(textwrap.dedent(reference)).body[0]
    ids = anchors.anchored(mine, theirs)
    return {node.lineno for node in ast.walk(mine) if id(node) in ids}


def test_a_statement_is_anchored_only_with_everything_it_reads():
    reference = """
        def f(a, b):
            x = a @ b
            y = x / x[2]
            z = y[:2] * 2
            return z
        """
    # one line changed: the lines above it are the reference's; the lines that read it are not
    changed = _anchored_lines(reference.replace("y = x / x[2]", "y = x / x[1]"), reference)
    assert 3 in changed and not {4, 5, 6} & changed
    # a step left out: `z = y[:2] * 2` is written alike but reads another value
    missing = """
        def f(a, b):
            x = a @ b
            y = x
            z = y[:2] * 2
            return z
        """
    assert _anchored_lines(missing, reference) == {3}
    # a parameter read is the same parameter; a name read in another's place is not
    assert _anchored_lines(reference.replace("x = a @ b", "x = b @ a"), reference) == set()
    assert _anchored_lines(reference, reference) == {3, 4, 5, 6}


def test_module_level_names_bound_otherwise_are_told_apart_even_through_a_helper():
    from autograder.engine.mutants.anchors import differing_names

    reference = ast.parse("import numpy as np\nK = 2\ndef core(x):\n    return x * K\ndef outer(x):\n    return core(x)\n")
    same = differing_names(reference, reference)
    assert same == frozenset()
    changed = ast.parse("import numpy as np\nK = 3\ndef core(x):\n    return x * K\ndef outer(x):\n    return core(x)\n")
    assert differing_names(changed, reference) == {"K", "core", "outer"}   # (core reads K, outer reads core)
    twice = ast.parse("import numpy as np\nK = 2\ndef core(x):\n    return x * K\ndef core(x):\n    return x * K\n"
                      "def outer(x):\n    return core(x)\n")
    assert {"core", "outer"} <= differing_names(twice, reference)


def test_a_change_of_a_line_written_as_the_reference_writes_it_is_not_told(tmp_path):
    # the lecture's R(theta) where the screen's R(-theta) belongs: flipping the sine where it is computed
    # (`np.sin(-theta)`, the reference's own line) mends the answers by compensating; the matrix is the slip
    folder = edited_reference(tmp_path, "lab07_transformations", (
        "R = np.array([[cos, sin],\n                  [-sin, cos]])",
        "R = np.array([[cos, -sin],\n                  [sin, cos]])"))
    messages = failing_messages(folder, "lab07.ex2")
    assert messages and not any("np.sin(-theta)" in m or "deg2rad(-" in m for m in messages), messages
    assert any("opposite way" in m for m in messages), messages


def test_of_two_places_that_mend_alike_the_one_written_as_the_reference_writes_it_is_not_told(tmp_path):
    # each bit read one place off (`g >> n_bits - i`); shifting the Gray code the other way (`k ^ k << 1`)
    # mends it too, but `k ^ k >> 1` is the Gray code as the reference writes it
    folder = mutant(tmp_path, "lab12_stereo", '''
def gray_code_patterns(width, n_bits):
    width, n_bits = int(width), int(n_bits)
    patterns = np.zeros((n_bits, width), dtype=np.uint8)
    for u in range(width):
        k = (u * 2 ** n_bits) // width
        g = k ^ (k >> 1)
        for i in range(n_bits):
            if (g >> (n_bits - i)) & 1:
                patterns[i, u] = 255
    return patterns
''')
    messages = failing_messages(folder, "lab12.ex6", startswith="gray_code_patterns")
    assert messages and all("`g >> n_bits - i - 1`" in m for m in messages), messages
    assert not any("k ^ k << 1" in m for m in messages), messages


def test_the_middle_of_a_range_where_the_mean_belongs_is_told_the_mean(tmp_path):
    # weak perspective's default depth taken as the middle of the depth range: the same on symmetric depths
    folder = edited_reference(tmp_path, "lab10_camera2", (
        "z = X[:, 2].mean() if z_avg is None", "z = (X[:, 2].min() + X[:, 2].max()) / 2 if z_avg is None"))
    messages = failing_messages(folder, "lab10.ex2")
    assert messages and all("to `np.mean(X[:, 2])` (line " in m for m in messages), messages


def test_one_view_left_without_its_twins_step_is_given_that_step(tmp_path):
    # the second image's points left unnormalised where the first's are: the step copied with its twin
    # names (T1 -> T2), not the denormalisation below changed to compensate
    folder = edited_reference(tmp_path, "lab11_two_view", (
        "Fn = _eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T)",
        "Fn = _eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2))"))
    messages = failing_messages(folder, "lab11.ex4")
    assert messages and all("to `_eight_point_core(..., _homogeneous(pts2) @ T2.T)`" in m
                            or "`_homogeneous(pts2)` to `_homogeneous(pts2) @ T2.T` (line 123)" in m for m in messages), messages
    assert not any("to `Fn @ T1`" in m for m in messages), messages


def test_a_step_taken_out_before_every_change_was_tried_is_not_told(tmp_path):
    # the matrix's last row copies Z where the 1 belongs, so w = Z: dropping the division by w mends the
    # answers too, but it compensates; told only when the search was complete, else a later check says more
    folder = mutant(tmp_path, "lab10_camera2", '''
def orthographic_project(points):
    pts = np.asarray(points, dtype=np.float64)
    single = pts.ndim == 1
    pts = pts.reshape(-1, 3)
    M = np.array([[1.0, 0.0, 0.0, 0.0],
                  [0.0, 1.0, 0.0, 0.0],
                  [0.0, 0.0, 1.0, 0.0]])
    Xh = np.hstack([pts, np.ones((len(pts), 1))])
    proj = (M @ Xh.T).T
    xy = proj[:, :2] / proj[:, 2:]
    return xy[0] if single else xy
''')
    messages = failing_messages(folder, "lab10.ex3")
    assert any("to `[0.0, 0.0, 0.0, 1.0]`" in m for m in messages), messages
    assert not any("to `proj[:, :2]` (line" in m for m in messages), messages


def test_a_change_that_mends_by_skipping_a_shortcut_is_told_as_the_shortcut(tmp_path):
    # quarter turns of a square image sent to cv2.rotate the wrong way round: making the angle anything
    # else (`float(width)`) mends every answer by never taking the shortcut, which is where the slip is
    folder = mutant(tmp_path, "lab07_transformations", '''
def rotate(image, angle_deg=45):
    height, width = image.shape[:2]
    quarter = {90: cv2.ROTATE_90_CLOCKWISE, 180: cv2.ROTATE_180, 270: cv2.ROTATE_90_COUNTERCLOCKWISE}
    angle = float(angle_deg) % 360
    if height == width and angle in quarter:
        return cv2.rotate(image, quarter[angle])
    if angle == 0:
        return image.copy()
    M = cv2.getRotationMatrix2D(((width - 1) / 2.0, (height - 1) / 2.0), angle_deg, 1.0)
    return cv2.warpAffine(image, M, (width, height))
''')
    messages = failing_messages(folder, "lab07.ex2")
    assert messages and all("skipping the branch `if height == width and angle in quarter:`" in m
                            for m in messages), messages


def test_a_row_of_values_given_to_a_square_block_is_given_as_its_diagonal(tmp_path):
    folder = mutant(tmp_path, "lab07_transformations", '''
def scaling_matrix(sx, sy):
    M = np.eye(3)
    M[:2, :2] = [sx, sy]
    return M
''')
    messages = failing_messages(folder, "lab07.ex3", startswith="scaling_matrix")
    assert messages and all("to `M[:2, :2] = np.diag([sx, sy])`" in m for m in messages), messages


def test_a_second_name_for_an_array_written_into_is_given_a_copy(tmp_path):
    # `moved = pts` then `moved[:, 2] += ...` in a loop: each pass starts from the last one's points
    folder = mutant(tmp_path, "lab10_camera2", '''
def dolly_zoom(points, f0, z0, distances):
    pts = np.atleast_2d(np.array(points, dtype=np.float64))
    focal_lengths, projections = [], []
    for d in np.ravel(distances):
        f = f0 * d / z0
        moved = pts
        moved[:, 2] += d - z0
        focal_lengths.append(f)
        projections.append(perspective_project(moved, f))
    return np.array(focal_lengths, dtype=np.float64), np.array(projections)
''')
    messages = failing_messages(folder, "lab10.ext2")
    assert messages and all("to `moved = pts.copy()`" in m for m in messages), messages


def test_an_opencv_method_left_at_its_default_is_given_each_method_as_a_change():
    """cv2.findFundamentalMat without a method runs RANSAC (its default), cv2.findHomography a least-squares
    fit of every point, cv2.warpAffine a forward map: each method is tried as a keyword; a method already
    given (by position or keyword) is left to the flag operator."""
    source = textwrap.dedent("""
        def graded(p1, p2, image, M):
            F, _ = cv2.findFundamentalMat(p1, p2)
            H, _ = cv2.findHomography(p1, p2, cv2.RANSAC)
            out = cv2.warpAffine(image, M, (40, 30))
            small = cv2.resize(image, (20, 15), interpolation=cv2.INTER_AREA)
            return F, H, out, small
    """)
    given = _shown_changes(source, "method_given")
    assert ("cv2.findFundamentalMat(p1, p2)", "cv2.findFundamentalMat(p1, p2, method=cv2.FM_8POINT)") in given, given
    assert any(after.endswith("(40, 30), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)") for _, after in given), given
    assert not any("findHomography" in before or "resize" in before for before, _ in given), given


def test_a_running_minimum_taken_from_the_far_end_is_given_its_reversal_back_as_a_change():
    """`np.minimum.accumulate(x[:, ::-1], axis=1)` never turned back (a DP's cost from above): the
    reversal after it is a change tried; one already turned back, or one over an axis not reversed, is not."""
    source = textwrap.dedent("""
        def graded(previous, ramp):
            above = np.minimum.accumulate((previous + ramp)[:, ::-1], axis=1) - ramp
            below = np.minimum.accumulate(previous - ramp, axis=1) + ramp
            turned = np.cumsum(previous[::-1], axis=0)[::-1]
            return above, below, turned
    """)
    assert _shown_changes(source, "reverse_back") == [
        ("np.minimum.accumulate((previous + ramp)[:, ::-1], axis=1)",
         "np.minimum.accumulate((previous + ramp)[:, ::-1], axis=1)[:, ::-1]")]


def test_a_reversal_dropped_after_a_running_minimum_is_a_mutant_of_the_reference():
    from autograder.engine.mutants.operators import mutants_of

    source = textwrap.dedent("""
        def graded(previous, ramp):
            return np.minimum.accumulate((previous + ramp)[:, ::-1], axis=1)[:, ::-1] - ramp
    """)
    dropped = [m for m in mutants_of(source, {"graded"})["graded"] if m.operator == "reverse_back"]
    assert len(dropped) == 1 and "running minimum taken from the far end" in dropped[0].sentence, dropped


def test_a_name_written_in_the_other_case_is_tried_first():
    """`f * Y / Z` (a point's own depth) where `z` (the common one) belongs, in a loop unpacking X, Y, Z:
    the names unpacked with Z would fill every place tried at that site; a name in the other case comes
    before them."""
    source = textwrap.dedent("""
        def graded(points, f, z_avg=None):
            pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
            z = pts[:, 2].mean() if z_avg is None else float(z_avg)
            out = np.empty((len(pts), 2))
            for i, (X, Y, Z) in enumerate(pts):
                out[i] = f * X / z, f * Y / Z
            return out
    """)
    assert ("f * X / z, f * Y / Z", "f * X / z, f * Y / z") in _shown_changes(source, "other_name")


def test_a_drawing_in_the_students_own_style_missing_matches_is_given_every_match(tmp_path):
    """cv2.drawMatches given `matches[:10]`: the student's own drawing (circles, random colours) stays far
    from the reference's whatever is changed, so the change drawing the two missing lines is only a few
    per cent nearer; the check itself judges it, and it is named."""
    source = """
        def draw_matches(img1, img2, pts1, pts2):
            kp1 = [cv2.KeyPoint(float(x), float(y), 6) for x, y in np.asarray(pts1, float).reshape(-1, 2)]
            kp2 = [cv2.KeyPoint(float(x), float(y), 6) for x, y in np.asarray(pts2, float).reshape(-1, 2)]
            matches = [cv2.DMatch(i, i, 0.0) for i in range(len(kp1))]
            return cv2.drawMatches(_bgr(img1), kp1, _bgr(img2), kp2, matches[:10], None,
                                   flags=cv2.DrawMatchesFlags_NOT_DRAW_SINGLE_POINTS)
        """
    messages = failing_messages(mutant(tmp_path, "lab08_homographies", source), "lab08.ex3")
    assert any("changing `matches[:10]` to `matches`" in m for m in messages), messages


def test_the_smallest_real_part_is_given_the_smallest_modulus_as_a_change():
    """`np.argmin(values.real)` of np.linalg.eig's eigenvalues (a pure translation's F has 0 and +-i lambda:
    every real part 0): the modulus of the complex values is the change tried, beside the real part's."""
    source = textwrap.dedent("""
        def graded(F):
            values, vectors = np.linalg.eig(F)
            return vectors[:, np.argmin(values.real)].real
    """)
    changes = _shown_changes(source, "magnitude")
    assert ("np.argmin(values.real)", "np.argmin(np.abs(values))") in changes, changes


def test_an_order_reversed_that_does_not_belong_is_given_its_removal_as_a_change():
    """`tuple(pattern_size)[::-1]` (NumPy's rows-first habit) given to cv2.findChessboardCorners, which
    takes (columns, rows): the reversal's removal is a change tried; a slice with bounds is not a reversal."""
    source = textwrap.dedent("""
        def graded(grey, pattern_size):
            found, corners = cv2.findChessboardCorners(grey, tuple(pattern_size)[::-1])
            top = corners[1:][::2]
            return corners, top
    """)
    assert _shown_changes(source, "drop_reversal") == [("tuple(pattern_size)[::-1]", "tuple(pattern_size)")]


def test_twin_names_in_each_others_places_in_a_matrix_written_as_rows_are_one_change():
    """The cross-product matrix of (x, y, 1) written with x and y in each other's places: exchanging them
    throughout the matrix is one change (one at a time gives a matrix of x twice, no nearer)."""
    source = textwrap.dedent("""
        def graded(x, y, P):
            skew = np.array([[0.0, -1.0, x], [1.0, 0.0, -y], [-x, y, 0.0]])
            return skew @ P
    """)
    assert ("[[0.0, -1.0, x], [1.0, 0.0, -y], [-x, y, 0.0]]", "[[0.0, -1.0, y], [1.0, 0.0, -x], [-y, x, 0.0]]") \
        in _shown_changes(source, "exchange")


def test_a_point_subtracted_without_the_matrix_the_function_made_is_given_its_image():
    """`t = dst[0] - src[0]` beside `L = E_dst @ inv(E_src)`: the translation leaves out the linear part's
    move of the point; `L @ src[0]` is the change tried (a matrix made above, never the name itself)."""
    source = textwrap.dedent("""
        def graded(src, dst):
            E_src = np.column_stack([src[1] - src[0], src[2] - src[0]])
            E_dst = np.column_stack([dst[1] - dst[0], dst[2] - dst[0]])
            L = E_dst @ np.linalg.inv(E_src)
            t = dst[0] - src[0]
            return np.column_stack([L, t])
    """)
    assert _shown_changes(source, "matrix_applied") == [("dst[0] - src[0]", "dst[0] - L @ src[0]")]


def test_a_series_in_the_wrong_powers_of_its_variable_is_given_them_doubled_or_halved():
    """`1 + k1 * r + k2 * r ** 2 + k3 * r ** 3` with r the radius, where the powers of r ** 2 belong: every
    power doubled is one change; a series in even powers only is also given them halved."""
    source = textwrap.dedent("""
        def graded(x, y, k1, k2, k3):
            r = np.sqrt(x * x + y * y)
            radial = 1 + k1 * r + k2 * r ** 2 + k3 * r ** 3
            other = 1 + k1 * y ** 2 + k2 * y ** 4
            return radial, other
    """)
    changes = _shown_changes(source, "series_powers")
    assert ("1 + k1 * r + k2 * r ** 2 + k3 * r ** 3", "1 + k1 * r ** 2 + k2 * r ** 4 + k3 * r ** 6") in changes
    assert ("1 + k1 * y ** 2 + k2 * y ** 4", "1 + k1 * y + k2 * y ** 2") in changes, changes


def test_a_term_taken_out_is_told_before_a_change_that_makes_it_vanish(tmp_path):
    """A canvas `w + int(abs(s) * h)` wide where the input's width belongs: `int(abs(s) / h)` makes the
    extra width 0 on every image tried (and is wrong for |s| >= h); taking the term out says the mistake."""
    source = """
        def shear(image, s=0.5):
            h, w = image.shape[:2]
            M = np.float32([[1, s, 0], [0, 1, 0]])
            out_w = w + int(abs(s) * h)
            return cv2.warpAffine(image, M, (out_w, h), borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """
    messages = failing_messages(mutant(tmp_path, "lab07_transformations", source), "lab07.ex4")
    assert messages and all("changing `w + int(abs(s) * h)` to `w`" in m for m in messages), messages
    assert not any("int(abs(s) / h)" in m for m in messages), messages


def test_a_loop_counted_by_a_number_is_given_a_parameters_length_and_a_list_one_shorter_refutes_a_bigger_number():
    source = textwrap.dedent("""
        def graded(images, scale):
            out = []
            for k in range(3):
                out.append(images[k] * scale)
            return out
    """)
    assert ("range(3)", "range(len(images))") in _shown_changes(source, "counted")
    images = [np.zeros((4, 4)), np.ones((4, 4)), np.ones((4, 4)), np.ones((4, 4))]
    [(function, args, kwargs)] = repair._fewer(("graded", (images, 2.0), {}))
    assert len(args[0]) == 3 and args[1] == 2.0 and repair._fewer(("graded", (images[:2], 2.0), {})) == []


def test_a_scale_given_where_its_neutral_one_belongs_is_a_change_tried():
    """cv2.getRotationMatrix2D given a zoom (so that the whole picture fits) where a rotation keeps the
    scale 1: its 1.0 is the change tried; a scale written 1 already is not changed."""
    source = textwrap.dedent("""
        def graded(image, angle_deg):
            h, w = image.shape[:2]
            zoom = min(w, h) / np.hypot(w, h)
            M = cv2.getRotationMatrix2D(((w - 1) / 2, (h - 1) / 2), angle_deg, zoom)
            N = cv2.getRotationMatrix2D((0, 0), angle_deg, 1)
            return M, N
    """)
    assert _shown_changes(source, "neutral_argument") == [
        ("cv2.getRotationMatrix2D(((w - 1) / 2, (h - 1) / 2), angle_deg, zoom)",
         "cv2.getRotationMatrix2D(((w - 1) / 2, (h - 1) / 2), angle_deg, 1.0)")]


def test_a_grid_reshaped_in_memory_order_is_given_its_transpose_first():
    """`np.mgrid[0:c, 0:r].reshape(-1, 2)` reads the grid's x's, then its y's, in runs: the transpose
    before the reshape is a change tried; a reshape of a transposed array already is not given another."""
    source = textwrap.dedent("""
        def graded(cols, rows):
            grid = np.mgrid[0:cols, 0:rows].reshape(-1, 2)
            done = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2)
            return grid, done
    """)
    given = [pair for pair in _shown_changes(source, "transpose") if pair[1].endswith(".T.reshape(-1, 2)")]
    assert given == [("np.mgrid[0:cols, 0:rows].reshape(-1, 2)", "np.mgrid[0:cols, 0:rows].T.reshape(-1, 2)")], given


def test_a_whole_arrays_norm_dividing_it_is_given_each_rows_with_its_axis_kept():
    source = textwrap.dedent("""
        def graded(lines):
            return lines / np.linalg.norm(lines[:, :2])
    """)
    assert ("np.linalg.norm(lines[:, :2])", "np.linalg.norm(lines[:, :2], axis=1, keepdims=True)") \
        in _shown_changes(source, "add_axis")


def test_a_transpose_of_a_whole_product_is_given_to_one_factor():
    source = textwrap.dedent("""
        def graded(F, K1, K2):
            return (K2 @ F).T @ K1
    """)
    changes = _shown_changes(source, "factor_transposed")
    assert changes == [("(K2 @ F).T @ K1", "K2.T @ F @ K1"), ("(K2 @ F).T @ K1", "K2 @ F.T @ K1")], changes


def test_a_twins_matrix_factor_is_given_to_the_other_twin():
    source = textwrap.dedent("""
        def graded(K, R, t):
            P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
            P2 = np.hstack([R, t])
            return P1, P2
    """)
    assert _shown_changes(source, "twin_factor") == [("np.hstack([R, t])", "K @ np.hstack([R, t])")]


def test_the_other_entry_of_a_diagonal_is_a_change_tried_in_a_nested_helper_too():
    """`y = (v - K[1, 2]) / K[0, 0]` (fx) where `K[1, 1]` (fy) belongs, written in a def inside the function."""
    source = textwrap.dedent("""
        def graded(p, K):
            def normalise(p, K):
                y = (p[:, 1] - K[1, 2]) / K[0, 0]
                x = (p[:, 0] - K[0, 2]) / K[0, 0]
                return x, y
            return normalise(p, K)
    """)
    changes = _shown_changes(source, "axis")
    assert ("(p[:, 1] - K[1, 2]) / K[0, 0]", "(p[:, 1] - K[1, 2]) / K[1, 1]") in changes, changes


def test_a_division_by_h33_kept_beside_the_one_by_w_is_refuted_by_a_rescaled_homography(tmp_path):
    """`p[:2] / H[2, 2]` where w belongs: adding the division by w beside it is exact where H[2, 2] = 1 (the
    check's homographies), and wrong for the same H twice as large, which the reference maps alike."""
    source = """
        def transform_points(H, pts):
            H = np.asarray(H, dtype=np.float64)
            out = []
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                p = H @ np.array([x, y, 1.0])
                out.append(p[:2] / H[2, 2])
            return np.array(out, dtype=np.float64).reshape(-1, 2)
        """
    messages = failing_messages(mutant(tmp_path, "lab08_homographies", source), "lab08.ex1")
    assert messages and not any("p[:2] / p[2:3] / H[2, 2]" in m for m in messages), messages
    H = np.array([[1.0, 0.1, 3.0], [0.0, 1.0, 2.0], [0.001, 0.0, 1.0]])
    [(_, args, _)] = repair._rescaled(("transform_points", (H, np.zeros((4, 2))), {}), [(0, "H")])
    assert np.allclose(args[0], 2 * H) and repair._rescaled(("f", (np.eye(2),), {}), [(0, "H")]) == []


def test_a_transpose_mending_the_batch_only_is_refuted_by_a_single_point(tmp_path):
    """`np.stack([u, v])` ((2, N)), then `result[0]` for a single point: `return result.T` mends every batch
    and leaves a single (3,) point wrong; the confirmation gives the first point alone, and the change at the
    stack is told."""
    source = """
        def perspective_project(points, f):
            pts = np.asarray(points, dtype=float)
            one_point = pts.ndim == 1
            pts = pts.reshape(-1, 3)
            with np.errstate(divide="ignore", invalid="ignore"):
                u = f * pts[:, 0] / pts[:, 2]
                v = f * pts[:, 1] / pts[:, 2]
            result = np.stack([u, v])
            if one_point:
                return result[0]
            return result
        """
    messages = failing_messages(mutant(tmp_path, "lab10_camera2", source), "lab10.ex1")
    assert not any("`return result.T`" in m for m in messages), messages
    assert any("`np.stack([u, v], axis=1)`" in m for m in messages), messages
    [(_, args, _)] = repair._single_point(("f", (np.ones((4, 3)), 2.0), {}))
    assert args[0].shape == (3,) and repair._single_point(("f", (np.ones((4, 3)), np.ones((5, 2))), {})) == []


def test_a_homography_is_also_confirmed_as_a_translation_both_ways():
    """A homography parameter given as a pure translation, right and down then left and up; never F or P."""
    H, F = np.diag([2.0, 2.0, 1.0]), np.eye(3)
    calls = repair._translated(("warp", (np.zeros((4, 4), np.uint8), H, F), {}), [(1, "H"), (2, "F")])
    assert [tuple(args[1][:2, 2]) for _, args, _ in calls] == list(repair.SHIFTS)
    assert all(args[2] is F and np.array_equal(args[1][:2, :2], np.eye(2)) for _, args, _ in calls)
    assert repair._translated(("fundamental", (F,), {}), [(0, "F")]) == []


@pytest.mark.slow
def test_a_shift_added_to_keep_the_image_visible_is_mended_by_its_removal_not_a_sign(tmp_path):
    """warp_to_reference pre-multiplying H by a translation that keeps the warped corners at x, y >= 0: on
    the check's scene (corners above the top) turning the y shift's sign round makes it 0 and passes, as
    using dx for dy does; a translation right and down refutes the one, left and up the other: the
    shift's removal is told."""
    folder = edited_reference(tmp_path, "lab08_homographies", (
        "    height, width = reference.shape[:2]\n    return apply_homography(moving, H, (width, height))",
        "    height, width = reference.shape[:2]\n    h, w = moving.shape[:2]\n"
        "    corners = cv2.perspectiveTransform(np.float32([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]])"
        ".reshape(-1, 1, 2), np.asarray(H, dtype=np.float64)).reshape(-1, 2)\n"
        "    dx = max(0.0, -float(corners[:, 0].min()))\n    dy = max(0.0, -float(corners[:, 1].min()))\n"
        "    H = np.array([[1.0, 0.0, dx], [0.0, 1.0, dy], [0.0, 0.0, 1.0]]) @ H\n"
        "    return apply_homography(moving, H, (width, height))"))
    failed = failing_messages(folder, "lab08.ex2")
    assert failed and all("to `H`" in message and "float(corners[:, 1].min())` (" not in message
                          and "dy]` to" not in message for message in failed), failed


def test_a_homogeneous_points_last_value_made_one_is_a_change_tried():
    """`[x / Z, y / Z, Z]` where the third value is 1 after the division: the last value of a stacked point
    made 1 (`np.ones_like`), at the place of the slip -- never offered for a matrix's rows or two values."""
    source = textwrap.dedent("""
        def graded(K, pts):
            Z = pts[:, 2]
            normalised = np.column_stack([pts[:, 0] / Z, pts[:, 1] / Z, Z])
            pair = np.column_stack([pts[:, 0], Z])
            M = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1]])
            return normalised @ K.T, pair, M
    """)
    assert _shown_changes(source, "homogeneous_one") == [
        ("np.column_stack([pts[:, 0] / Z, pts[:, 1] / Z, Z])",
         "np.column_stack([pts[:, 0] / Z, pts[:, 1] / Z, np.ones_like(Z)])")]


@pytest.mark.slow
def test_a_depth_left_in_the_homogeneous_slot_is_mended_there_not_by_undoing_the_division(tmp_path):
    """project_with_intrinsics normalising by depth into `[X/Z, Y/Z, Z]`: taking both divisions out makes the
    same answers, but changes two right lines, and projecting the points themselves skips the step that
    holds the slip; the third value made 1 is told alone."""
    folder = edited_reference(tmp_path, "lab09_camera", (
        "    X, single = _points(points)\n    return _divide(X @ np.asarray(K, dtype=np.float64).T, single)",
        "    X, single = _points(points)\n    Z = X[:, 2]\n"
        "    normalised = np.column_stack([X[:, 0] / Z, X[:, 1] / Z, Z])\n"
        "    pixels = _divide(normalised @ np.asarray(K, dtype=np.float64).T, False)\n"
        "    pixels[Z <= 0] = np.nan\n"
        "    return pixels[0] if single else pixels"))
    failed = failing_messages(folder, "lab09.ex2")
    assert failed and all("to `np.column_stack([X[:, 0] / Z, X[:, 1] / Z, np.ones_like(Z)])`" in message
                          and "/ Z` to `X[:, 0]`" not in message and "to `X @" not in message
                          for message in failed), failed


def test_a_term_added_to_one_coordinate_moved_to_its_twin_is_a_change_tried():
    """`(q[0], q[1] + w1)` where the offset belongs to x: the term moved to the twin item; a constant term
    (`q[1] + 1`) and items unlike each other are left alone."""
    source = textwrap.dedent("""
        def graded(q, w1, p):
            end = (int(round(q[0])), int(round(q[1] + w1)))
            other = (q[0], q[1] + 1)
            unlike = (p.sum(), q[1] + w1)
            return end, other, unlike
    """)
    assert _shown_changes(source, "moved_term") == [
        ("(int(round(q[0])), int(round(q[1] + w1)))", "(int(round(q[0] + w1)), int(round(q[1])))")]


def test_a_loop_counted_by_a_number_beside_an_array_sized_by_it_is_changed_with_its_sizes():
    """`A = np.zeros((12, 12))` filled by `for i in range(6)`: only six points enter the system; the count and
    the rows it sizes are changed together, a loop without such an array by its count alone."""
    source = textwrap.dedent("""
        def graded(points, other):
            A = np.zeros((12, 12))
            for i in range(6):
                A[2 * i] = points[i]
            for k in range(3):
                other = other + k
            return A, other
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    changes = [student.fix(m).changes for m in student.mutants("graded")
               if m.operator == "counted" and len(m.edits) == 2 and student.fix(m) is not None]
    assert [tuple(change[1:] for change in c) for c in changes if "points" in c[0][2]] == [
        (("range(6)", "range(len(points))"), ("np.zeros((12, 12))", "np.zeros((2 * len(points), 12))"))]
    assert not any("range(3)" in c[0][1] for c in changes)


def test_the_component_after_a_leading_slice_is_a_part_for_a_statistic_of_the_whole():
    """`np.linalg.norm(X, axis=1)` (the distance) beside `X[:, :2]` only: the depth `X[:, 2]` is offered too."""
    source = textwrap.dedent("""
        def graded(X, f):
            depth = np.linalg.norm(X, axis=1)
            return f * X[:, :2] / depth[:, None]
    """)
    assert ("np.linalg.norm(X, axis=1)", "X[:, 2]") in _shown_changes(source, "part")


def test_a_removal_of_a_step_the_reference_never_takes_is_the_fix_and_one_it_takes_a_compensation():
    """`T @ H` -> `H` where the reference warps by H as given (no product anywhere it runs): the step was the
    student's own, its removal the fix. A division taken out where the reference divides too stays a
    likely compensation (a w the student made Z), and a change that is no removal is never judged so."""
    reference = textwrap.dedent("""
        def _warp(image, H):
            return cv2.warpPerspective(image, H, (4, 4))
        def warp(image, H):
            return _warp(image, np.asarray(H, dtype=np.float64))
        def project(P, X):
            x = X @ P.T
            return x[:, :2] / x[:, 2:]
    """)
    removed_product = repair.Fix(((3, "T @ H", "H"),), "warp", "drop_factor", ())
    removed_division = repair.Fix(((5, "x[:, :2] / w", "x[:, :2]"),), "project", "drop_division", ())
    changed_sign = repair.Fix(((3, "T @ H", "-T @ H"),), "warp", "sign", ())
    assert repair._extra_step(removed_product, reference, "warp")
    assert not repair._extra_step(removed_division, reference, "project")
    assert not repair._extra_step(changed_sign, reference, "warp")


# ------------------------------------------------------------------ slips of 2026-12-01's blind sets, by class
def _changes(student, mutants, operator):
    return {student.fix(m).changes[0][1:] for m in mutants if m.operator == operator and student.fix(m) is not None}


def test_a_products_minus_a_cast_to_integers_and_the_last_axis_are_tried():
    student, mutants = _read("""
        import numpy as np

        def graded(R, T, pts, lines):
            C = R.T @ T
            p = np.int32(pts)
            q = lines.astype(int)
            r = np.asarray(lines, np.int32)
            return np.stack([C, p.sum(axis=0), q.sum(axis=0), r.sum(axis=0)], axis=1)
    """)
    assert ("C = R.T @ T", "C = -(R.T @ T)") in _changes(student, mutants, "sign")
    kept = _changes(student, mutants, "float_kept")
    assert ("np.int32(pts)", "pts") in kept
    assert ("lines.astype(int)", "lines.astype(np.float64)") in _changes(student, mutants, "astype_float")
    assert ("np.asarray(lines, np.int32)", "np.asarray(lines, np.float64)") in kept
    assert any(after.endswith("axis=-1)") for _, after in _changes(student, mutants, "axis"))


def test_a_row_used_otherwise_than_its_siblings_and_a_raw_value_beside_its_derived_twin():
    student, mutants = _read("""
        import numpy as np

        def graded(P, pts, K):
            Xh = np.hstack([pts, np.ones((len(pts), 1))])
            u = Xh @ P[0]
            v = Xh @ P[1]
            w = pts @ P[2, :3]
            X, Y, Z = pts[:, 0], pts[:, 1], pts[:, 2]
            xn = X / Z
            yn = Y / Z
            s = K[0, 0] * xn + K[0, 1] * Y
            return u / w, v / w, s, yn
    """)
    assert ("w = pts @ P[2, :3]", "w = Xh @ P[2]") in _changes(student, mutants, "mirror")
    derived = _changes(student, mutants, "derived_name")
    assert any("K[0, 1] * yn" in after for _, after in derived), derived
    assert not any("xn" in before and "yn" in after and "K[0, 1]" not in before for before, after in derived)


def test_a_unit_vectors_twin_is_normalised_too():
    student, mutants = _read("""
        import numpy as np

        def graded(c, axis):
            e1 = c / np.linalg.norm(c)
            e2 = np.cross(axis, e1)
            return np.vstack([e1, e2])
    """)
    assert ("e2 = np.cross(axis, e1)", "e2 = np.cross(axis, e1) / np.linalg.norm(np.cross(axis, e1))") \
        in _changes(student, mutants, "twin_step")


@pytest.mark.parametrize("edit, told, never", [
    # the camera centre's minus dropped: exchanging the cross product's factors (a line written as the
    # reference writes it) mends the images by turning R_rect into -R_rect; the slip is the centre's sign
    (("C2 = -R.T @ T", "C2 = R.T @ T"), "`C2 = -(R.T @ T)` || to `C2 = -R.T @ T` (line", "np.cross(e2, e1)"),
    # e2 never normalised: the reference's line right as far as it goes, the step after it left out
    (("    e2 /= np.linalg.norm(e2)\n", ""), "np.cross(mean_axis, e1) / np.linalg.norm(np.cross(mean_axis, e1))"
     " || adding the step `e2 /= np.linalg.norm(e2)` right after line",
     "np.cross(C2, e2)"),
])
def test_rectify_is_repaired_where_the_slip_is_not_where_it_is_compensated(tmp_path, edit, told, never):
    result = grade(edited_reference(tmp_path, "lab12_stereo", edit), ["lab12.ex3"], pictures="none",
                   include_hidden=False)
    messages = [c.message for c in check_results(result, "lab12.ex3") if c.score < c.max_score]
    assert messages and any(_told_in(told, m) for m in messages), messages
    assert not any(never in m for m in messages), messages


def test_a_term_its_sibling_rows_have_a_list_items_transpose_an_order_imposed_and_a_signed_guard():
    student, mutants = _read("""
        import numpy as np

        def graded(P, X, Y, Z, steps, d, area):
            if area <= 0:
                raise ValueError("degenerate")
            u = P[0, 0] * X + P[0, 1] * Y + P[0, 2] * Z + P[0, 3]
            v = P[1, 0] * X + P[1, 1] * Y + P[1, 2] * Z
            w = P[2, 0] * X + P[2, 1] * Y + P[2, 2] * Z + P[2, 3]
            H = steps[0].T @ steps[1]
            ds = np.unique(np.asarray(d))
            return u / w, v / w, H, ds
    """)
    assert ("v = P[1, 0] * X + P[1, 1] * Y + P[1, 2] * Z", "v = P[1, 0] * X + P[1, 1] * Y + P[1, 2] * Z + P[1, 3]") \
        in _changes(student, mutants, "mirror")
    assert any(after == "np.linalg.inv(steps[0])" or "np.linalg.inv(steps[0])" in after
               for _, after in _changes(student, mutants, "inverse"))
    assert ("np.unique(np.asarray(d))", "np.asarray(d)") in _changes(student, mutants, "unwrap")
    assert ("area <= 0", "np.abs(area) <= 0") in _changes(student, mutants, "magnitude")


def test_a_collection_started_once_where_each_turn_needs_its_own_is_started_in_the_loop():
    """`rows = []` above a loop that appends to it and solves `np.array(rows)` at each turn: moved into
    the loop; a list only appended to in the loop (read after it) is a legitimate accumulator."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(pts):
            points = []
            rows = []
            for x, y in pts:
                rows.append([x, y, 1.0])
                rows.append([y, -x, 0.0])
                points.append(np.linalg.svd(np.array(rows))[2][-1])
            return np.array(points)
    """)
    fn = next(node for node in ast.parse(source).body if isinstance(node, ast.FunctionDef))
    moved = [m for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
             if m.operator == "indent" and m.edits[0][3][3] == "first"]
    assert [m.edits[0][3][1] for m in moved] == ["rows = []"], moved
    after = repair._MAKE["indent"](list(ast.walk(fn))[moved[0].edits[0][1]], moved[0].edits[0][3])
    assert ast.unparse(after.body[0]) == "rows = []"


def test_a_loop_variable_nothing_reads_is_tried_first_where_a_name_on_its_line_is_used():
    """`[project(X, f) for fl in f]`: `fl`, never read, is the name tried first for `f` on its own line."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(X, focal_lengths):
            f = np.asarray(focal_lengths, dtype=float)
            return np.stack([X * f for fl in f])
    """)
    fn = next(node for node in ast.parse(source).body if isinstance(node, ast.FunctionDef))
    nodes = list(ast.walk(fn))
    first = {}
    for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]:
        node = nodes[m.edits[0][1]]
        if m.operator == "other_name" and isinstance(node, ast.Name) and node.id == "f" and node.lineno == 6:
            first.setdefault(node.col_offset, m.edits[0][3])
    assert first and set(first.values()) == {"fl"}, first


def test_a_shift_written_beside_a_sum_without_brackets_and_a_matrix_started_filled():
    """`k << 1 + bit` is `k << (1 + bit)` in Python: `(k << 1) + bit` tried; `np.ones((3, 3))` for a
    matrix whose entries are set one by one: `np.eye(3)` tried (the entries never set keep the fill)."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(k, bit, f):
            K = np.ones((3, 3))
            K[0, 0] = K[1, 1] = f
            return k << 1 + bit, K
    """)
    made = _made(source, {"regroup", "identity"})
    assert {("k << 1 + bit", "(k << 1) + bit"), ("np.ones((3, 3))", "np.eye(3)")} <= made, made


def test_points_a_mask_kept_where_every_point_belongs_are_given_whole():
    """`src[inliers]` (a mask made by a comparison, kept as the best one, refined): `src` tried; an index
    that is a loop's position is no mask and is kept."""
    source = textwrap.dedent("""
        def graded(src, errors, t):
            best = None
            for k in range(3):
                inliers = errors[k] < t
                best = inliers
            inliers = best
            refined = errors[0][inliers] < t
            return src[inliers], src[refined], src[k]
    """)
    made = _made(source, {"drop_slice"})
    assert {("src[inliers]", "src"), ("src[refined]", "src")} <= made, made
    assert ("src[k]", "src") not in made, made


def test_a_number_written_where_the_sibling_rows_read_their_own_entry_is_read_from_the_matrix():
    """`w = H[2, 0] * x + H[2, 1] * y + 1.0` beside `(H[0, 0] * x + H[0, 1] * y + H[0, 2]) / w`: the number
    replaced by row 2's own entry, `H[2, 2]`."""
    source = textwrap.dedent("""
        def graded(H, x, y):
            w = H[2, 0] * x + H[2, 1] * y + 1.0
            u = (H[0, 0] * x + H[0, 1] * y + H[0, 2]) / w
            v = (H[1, 0] * x + H[1, 1] * y + H[1, 2]) / w
            return u, v
    """)
    made = _made(source, {"mirror"})
    assert ("w = H[2, 0] * x + H[2, 1] * y + 1.0", "w = H[2, 0] * x + H[2, 1] * y + H[2, 2]") in made, made


def test_a_part_of_a_line_written_otherwise_than_in_its_twin_is_written_as_the_twin_writes_it():
    """`std_r = sqrt(mean(s * s) - mean_r)` beside `std_l = sqrt(mean(l * l) - mean_l ** 2)`: the differing
    part written as the twin writes it, in this line's names (`mean_r ** 2`), never the twin's step taken out;
    lines differing at two places besides their names are no twins' copies."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(left, shifted, a):
            mean_l = np.mean(left)
            mean_r = np.mean(shifted)
            std_l = np.sqrt(np.mean(left * left) - mean_l ** 2)
            std_r = np.sqrt(np.mean(shifted * shifted) - mean_r)
            x_l = np.abs(left) + 1
            x_r = np.sqrt(shifted) + 2
            return std_l, std_r, x_l, x_r
    """)
    made = {after for _, after in _made(source, {"twin_step"})}
    assert "std_r = np.sqrt(np.mean(shifted * shifted) - mean_r ** 2)" in made, made
    assert "std_l = np.sqrt(np.mean(left * left) - mean_l)" not in made, made   # (no step taken out of a twin)
    assert not any(after.startswith(("x_l =", "x_r =")) for after in made), made


def test_a_value_read_before_a_test_decides_it_is_moved_after_the_test():
    """`size = (w, h)` above `if dsize is not None: w, h = dsize`: the size read before it is decided;
    moved after the `if` block."""
    source = textwrap.dedent("""
        def graded(image, dsize=None):
            h, w = image.shape[:2]
            size = (w, h)
            if dsize is not None:
                w, h = dsize
            return size
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    moves = [student.fix(m) for m in student.mutants("graded") if m.operator == "move"]
    said = [fix.changes[0][2] for fix in moves if fix is not None]
    assert any("moving `size = (w, h)` (line 4" in text and "after the `if` block of line 5" in text for text in said), said


def test_the_statements_an_otherwise_reference_function_writes_its_own_way_are_tried_first():
    """Code written as the reference's but for one line of a helper: that line's changes come before the
    changes of the function's own lines; code of the student's own (many lines apart) keeps the usual order."""
    reference = textwrap.dedent("""
        import numpy as np

        def _errors(H, src, dst):
            mapped = np.column_stack([src, np.ones(len(src))]) @ H.T
            xy = mapped[:, :2] / mapped[:, 2:3]
            return np.linalg.norm(xy - dst, axis=1)

        def graded(H, src, dst, t):
            errors = _errors(H, src, dst)
            kept = errors < t
            count = int(kept.sum())
            return count, kept
    """)
    edited = reference.replace("xy = mapped[:, :2] / mapped[:, 2:3]", "xy = mapped[:, :2]")
    student = repair._Student(edited, ast.parse(edited), {"graded"})
    student.reference_source = reference
    ordered = student.ordered("graded")
    assert ordered[0].where == "_errors" and ordered[0].line == 6, [(m.where, m.line) for m in ordered[:5]]
    own = edited.replace("errors = _errors(H, src, dst)", "e = _errors(H, src, dst)").replace(
        "kept = errors < t", "kept = np.less(e, t)").replace("count = int(kept.sum())", "count = np.sum(kept)")
    student = repair._Student(own, ast.parse(own), {"graded"})
    student.reference_source = reference
    assert student.ordered("graded")[0].where == "graded"


def test_a_twins_step_added_beside_a_long_line_is_shown_whole():
    """`xl = xl.reshape(len(xl), -1)[:, 0]` with xr's step missing: the line with both steps is longer than a
    change usually shown, and is shown whole (the student writes it so)."""
    source = textwrap.dedent("""
        def graded(xl, xr):
            if xl.ndim == 2 or xr.ndim == 2:
                xl = xl.reshape(len(xl), -1)[:, 0]
            return xl - xr
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    shown = [student.fix(m) for m in student.mutants("graded") if m.operator == "sibling_step"]
    assert any(fix is not None and fix.changes[0][2] == "xl, xr = (xl.reshape(len(xl), -1)[:, 0], "
               "xr.reshape(len(xr), -1)[:, 0])" for fix in shown), shown


def test_a_difference_of_block_means_measured_where_the_mean_of_measured_differences_belongs():
    """`np.abs(box(l, k) - box(r, k))`: the absolute difference taken inside the filter, `box(np.abs(l - r), k)`
    (a block's sum of absolute differences); a pointwise function on both sides is no filter."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(l, r, k):
            sad = np.abs(box(l, k) - box(r, k))
            ssd = (box(l, k) - box(r, k)) ** 2
            flat = np.abs(np.sqrt(l) - np.sqrt(r))
            return sad, ssd, flat
    """)
    made = {after for _, after in _made(source, {"measure_first"})}
    assert {"box(np.abs(l - r), k)", "box((l - r) ** 2, k)"} <= made, made
    assert not any("sqrt" in after for after in made), made


def test_samples_of_a_closed_range_and_a_recurrence_started_at_zero():
    """`np.linspace(0, n, w)` where w samples of [0, n) belong: `endpoint=False` tried; `energy[0] = 0.0`
    above a loop `energy[x] = costs[x] + ...`: the first item is `costs[0]`."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(costs, n, w):
            k = np.floor(np.linspace(0, n, w))
            energy = np.empty_like(costs)
            energy[0] = 0.0
            for x in range(1, len(costs)):
                energy[x] = costs[x] + energy[x - 1].min()
            return k, energy
    """)
    made = _made(source, {"flip_keyword", "first_term"})
    assert {("np.linspace(0, n, w)", "np.linspace(0, n, w, endpoint=False)"), ("0.0", "costs[0]")} <= made, made


def test_a_shortcut_returning_early_for_a_special_value_is_taken_out():
    """`if aperture == 0: return pinhole(X, f)` (a shortcut answering otherwise than the general way): taken
    out; an `if` with an else, or one not ending in a return, is no shortcut."""
    source = textwrap.dedent("""
        def graded(X, f, aperture):
            if aperture == 0:
                return X * f
            if f > 1:
                f = 1
            else:
                return X
            return X * f + aperture
    """)
    fn = next(node for node in ast.parse(source).body if isinstance(node, ast.FunctionDef))
    nodes = list(ast.walk(fn))
    dropped = [nodes[m.edits[0][1]] for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
               if m.operator == "drop_statement" and isinstance(nodes[m.edits[0][1]], ast.If)]
    assert [node.lineno for node in dropped] == [3], dropped


def test_a_slices_stride_changed_is_told_as_a_stride_not_as_a_bound():
    """`M[0::2, 2]` read as `M[0::1, 2]`: "takes every element where every second element belongs" (the
    stride), never "stops one element early" (a bound)."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(n):
            M = np.zeros((2 * n, 6))
            M[0::2, 2] = 1.0
            return M
    """)
    said = [m.sentence for m in repair.mutants_of(source, {"graded"})["graded"] if m.operator == "bound"]
    assert any("takes every element where every second element belongs" in s for s in said), said
    assert not any("stops one element" in s for s in said), said


def test_points_made_homogeneous_with_zeros_is_never_the_fix_beside_another():
    """Of two changes that mend alike, `np.ones((len(pts), 1))` -> zeros beside the points (directions, not
    points) gives way; a camera's column of ones made zeros, `np.ones((3, 1))`, is a fix like any."""
    text = "def f(K, pts):\n    P = np.hstack([K, np.ones((3, 1))])\n    Xh = np.hstack([pts, np.ones((len(pts), 1))])\n"
    camera = repair.Fix(((2, "np.ones((3, 1))", "np.zeros((3, 1))"),), "f", "function", ())
    points = repair.Fix(((3, "np.ones((len(pts), 1))", "np.zeros((len(pts), 1))"),), "f", "function", ())
    assert repair._homogeneous_zeroed(points, text) and not repair._homogeneous_zeroed(camera, text)


@pytest.mark.parametrize("module, exercise, source, told", [
    # a slice written where one entry belongs: the translation M[0, 2] overwritten with the shear too
    ("lab07_transformations", "lab07.ex4", """
        def shear_matrix(s):
            M = np.eye(3)
            M[0, 1:] = s
            return M
        """, "to `M[0, 1] = s`"),
    # a square block written where its diagonal belongs: the skew entries set to f too
    ("lab09_camera", "lab09.ex2", """
        def intrinsic_matrix(f, px, py):
            K = np.zeros((3, 3))
            K[:2, :2] = f
            K[0, 2], K[1, 2], K[2, 2] = px, py, 1.0
            return K
        """, "to `K[[0, 1], [0, 1]] = f`"),
    # a term of one coordinate's sum left without the factor the twin coordinate's term has
    ("lab09_camera", "lab09.ex2", """
        def project_with_intrinsics(K, points):
            P3, single = _points(points)
            K = np.asarray(K, dtype=np.float64)
            X, Y, Z = P3[:, 0], P3[:, 1], P3[:, 2]
            with np.errstate(divide="ignore", invalid="ignore"):
                u = (K[0, 0] * X + K[0, 1] * Y + K[0, 2] * Z) / Z
                v = (K[1, 1] * Y + K[1, 2]) / Z
            out = np.column_stack([u, v])
            out[Z <= 0] = np.nan
            return out[0] if single else out
        """, "to `v = (K[1, 1] * Y + K[1, 2] * Z) / Z`"),
    # the whole tuple an OpenCV call returns kept where its first result (the matrix) belongs
    ("lab07_transformations", "lab07.ex5", """
        def affine_from_points(src, dst):
            src_pts = np.asarray(src, dtype=np.float64).reshape(-1, 2)
            dst_pts = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
            A = cv2.estimateAffine2D(src_pts, dst_pts)
            return A
        """, "to `cv2.estimateAffine2D(src_pts, dst_pts)[0]`"),
    # an input converted on its way into a call where the input itself belongs
    ("lab08_homographies", "lab08.ex2", [("apply_homography(moving, H, (width, height))",
                                          "apply_homography(_grey(moving), H, (width, height))")],
     "changing `_grey(moving)` to `moving`"),
    # a pyramid collapsed from its finest band up
    ("lab08_homographies", "lab08.ext3", [("for band in reversed(bands[:-1]):", "for band in bands[:-1]:")],
     "to `reversed(bands[:-1])`"),
    # the floor of a quotient taken before the product it should follow
    ("lab12_stereo", "lab12.ex6", [("k = (u * (1 << int(n_bits))) // int(width)",
                                    "k = u * ((1 << int(n_bits)) // int(width))")],
     "to `u * (1 << int(n_bits)) // int(width)`"),
    # in a private helper, a name used where its twin belongs (mean(L) twice in the covariance)
    ("lab12_stereo", "lab12.ext1", [("- mean_l * mean_r", "- mean_l * mean_l")],
     "changing `mean_l * mean_l` to `mean_r * mean_l` || changing `mean_l * mean_l` to `mean_l * mean_r`"),
    # a centre truncated to whole pixels in both coordinates: both truncations are told, not one (the inputs
    # tried move a 0 off it too, and the checks' centres are fractional in x and y)
    ("lab07_transformations", "lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            cx, cy = int(center[0]), int(center[1])
            M = cv2.getRotationMatrix2D((cx, cy), angle_deg, 1.0)
            return np.vstack([M, [0.0, 0.0, 1.0]])
        """, "changing `int(center[0])` to `center[0]` (line"),
    # every point's own depth where the mean depth belongs (an exception: a flat (N,) against (N, 2))
    ("lab10_camera2", "lab10.ex2", [("z = X[:, 2].mean() if z_avg is None", "z = X[:, 2] if z_avg is None")],
     "to `X[:, 2].mean() if z_avg is None"),
])
def test_slips_no_table_lists_are_repaired_in_the_students_terms(tmp_path, module, exercise, source, told):
    """A def written anew, or the reference with text edits (old, new), repaired by a change shown in
    the student's own code."""
    folder = mutant(tmp_path, module, source) if isinstance(source, str) else \
        edited_reference(tmp_path, module, *source)
    result = grade(folder, [exercise], pictures="none", include_hidden=False)
    messages = [c.message for c in check_results(result, exercise) if not c.passed]
    assert messages and any(_told_in(told, m) for m in messages), messages


def test_a_change_of_a_value_only_a_raising_guard_reads_is_never_told(tmp_path):
    """`if area <= 0: raise` rejects every triangle listed clockwise; a change of how `area` (or the edges
    it is made of) is computed mends the answers by steering round the guard, and is no account of the
    slip -- the guard is."""
    folder = mutant(tmp_path, "lab07_transformations", """
        def affine_from_points(src, dst):
            src = np.asarray(src, dtype=np.float64).reshape(3, 2)
            dst = np.asarray(dst, dtype=np.float64).reshape(3, 2)
            e1, e2 = src[1] - src[0], src[2] - src[0]
            area = e1[0] * e2[1] - e1[1] * e2[0]
            if area <= 0:
                raise ValueError("the three source points are collinear")
            S = np.column_stack([src, np.ones(3)])
            return np.stack([np.linalg.solve(S, dst[:, 0]), np.linalg.solve(S, dst[:, 1])])
        """)
    result = grade(folder, ["lab07.ex5"], pictures="none", include_hidden=False)
    failed = [c.message for c in check_results(result, "lab07.ex5") if not c.passed]
    assert failed, "the guard rejects valid triangles"
    assert not any(re.search(r"changing `(e1|e2|src\[\d\]|area)(?! <= 0`)", m) for m in failed), failed
    # (the guard's own test is the slip: a change of it may be told)
    assert all(re.search(r"changing `area <= 0`", m) or "changing" not in m for m in failed), failed


def test_a_division_by_the_homogeneous_coordinate_is_never_taken_out(tmp_path):
    """`x[:, :2] / x[:, 2:3]` is the recipe for any camera: where taking it out mends (a matrix whose third
    row reads Z), the matrix is wrong, and the division is never told as the place; the name of the effect
    then says where to look."""
    folder = mutant(tmp_path, "lab10_camera2", """
        def orthographic_project(points):
            pts = np.asarray(points, dtype=np.float64)
            single = pts.ndim == 1
            pts = pts.reshape(-1, 3)
            M = np.eye(3, 4)
            proj = (M @ np.hstack([pts, np.ones((len(pts), 1))]).T).T
            xy = proj[:, :2] / proj[:, 2:3]
            return xy[0] if single else xy
        """)
    result = grade(folder, ["lab10.ex3"], pictures="none", include_hidden=False)
    failed = [c.message for c in check_results(result, "lab10.ex3") if not c.passed]
    assert failed and not any("changing `proj[:, :2] / proj[:, 2:3]`" in m for m in failed), failed
    assert any("the matrix's third row that reads Z" in m for m in failed), failed


def test_a_name_read_in_place_of_a_right_step_made_from_it_is_a_skip_never_told():
    """Rows filled from the raw pixels, then F denormalised as the reference does (`F = T2.T @ Fn @ T1`):
    reading `Fn` where `F` is returned mends exact data by skipping the denormalisation, a right step
    (`_Student.skips_a_right_step`); a name read in place of one made by a step of the student's own is
    no such skip."""
    source = textwrap.dedent("""
        def graded(p1, p2, T1, T2):
            A = np.stack([p2[:, 0] * p1[:, 0], p1[:, 1], np.ones(len(p1))], axis=1)
            Fn = np.linalg.svd(A)[2][-1].reshape(3, 3)
            F = T2.T @ Fn @ T1
            G = Fn * 2 + T1
            return F / np.linalg.norm(F) + G
    """)
    student = repair._Student(source, ast.parse(source), ["graded"])
    student.reference_source = "def graded(x1, x2, A, B):\n    M = f(x1, x2)\n    return B.T @ M @ A\n"
    read_for = {(m.line, m.edits[0][3]): student.skips_a_right_step(m) for m in student.mutants("graded")
                if m.operator == "other_name"}
    assert read_for[(7, "Fn")] is True, read_for           # `Fn` for `F`: the denormalisation skipped
    assert read_for.get((7, "T1")) is not True, read_for   # (a name F is not made from)
    assert not any(done for (line, name), done in read_for.items() if name == "Fn" and line != 7), read_for


def test_names_read_only_by_raising_guards_are_found_through_a_chain_of_names():
    """`a0` makes `a1` ... makes `area`, read only by `if area <= 0: raise`: every name of the chain is
    read by the guard alone (a worklist: a long chain costs its length, not its square); `src`, also
    returned, is not."""
    chain = "".join(f"    a{k + 1} = a{k} * 2\n" for k in range(300))
    source = ("def graded(src):\n    a0 = src[0] - src[1]\n" + chain + "    area = a300 + 1\n"
              "    if area <= 0:\n        raise ValueError('flat')\n    return src\n")
    student = repair._Student(source, ast.parse(source), ["graded"])
    guarded = student._guard_only_names("graded")
    assert {"a0", "a150", "a300", "area"} <= guarded and "src" not in guarded


def test_a_change_before_the_first_departure_compensates_and_is_not_told(tmp_path):
    """A^T A where A A^T was written: building A transposed (`np.column_stack`) mends the answers as
    well as the product's order does, but A itself is right (each point's A is an item of the
    reference's stack): the change told, in the public checks and the hidden ones, is the product's."""
    folder = mutant(tmp_path, "lab11_two_view", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, np.float64), np.asarray(P2, np.float64)
            pts1 = np.asarray(pts1, np.float64).reshape(-1, 2)
            pts2 = np.asarray(pts2, np.float64).reshape(-1, 2)
            result = []
            for (x1, y1), (x2, y2) in zip(pts1, pts2):
                A = np.vstack([x1 * P1[2] - P1[0],
                               y1 * P1[2] - P1[1],
                               x2 * P2[2] - P2[0],
                               y2 * P2[2] - P2[1]])
                values, vectors = np.linalg.eigh(A @ A.T)
                X = vectors[:, 0]
                result.append(X[:3] / X[3])
            return np.array(result)
        """)
    result = grade(folder, ["lab11.ex1"], pictures="none", include_hidden=True)
    told = [c.message for c in check_results(result, "lab11.ex1") if c.score < c.max_score]
    assert told and all("A.T @ A" in m for m in told), told
    assert not any("column_stack" in m for m in told), told


def test_a_value_made_homogeneous_is_no_departure(tmp_path):
    """[dst | 1] and the 3 x 3 map with its [0, 0, 1] row hold the reference's numbers: the slip is the
    rows returned (`full[1:]`), not the ones column that, moved first, compensates for it (1202e 07/03)."""
    folder = mutant(tmp_path, "lab07_transformations", """
        def affine_from_points(src, dst):
            src_h = np.column_stack([np.asarray(src, dtype=np.float64), np.ones(3)])
            dst_h = np.column_stack([np.asarray(dst, dtype=np.float64), np.ones(3)])
            full = np.linalg.solve(src_h, dst_h).T
            return full[1:]
        """)
    _, repaired = _failed_and_repaired(folder, "lab07.ex5")
    assert repaired and all("`return full[:2]`" in said for said in repaired), repaired
    assert not any("column_stack" in said for said in repaired), repaired


def test_names_exchanged_between_twin_lines_are_exchanged_back_where_they_are_used(tmp_path):
    """Each image's points normalised with the other's K^-1 (`K2_inv @ p1`, `K1_inv @ p2`): exchanging the
    two inverses where they are made mends alike, but they are right; the exchange told is at their use
    (1202e 11/05)."""
    folder = mutant(tmp_path, "lab11_two_view", """
        def essential_8point(pts1, pts2, K1, K2):
            p1 = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
            p2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
            K1_inv = np.linalg.inv(np.asarray(K1, dtype=np.float64))
            K2_inv = np.linalg.inv(np.asarray(K2, dtype=np.float64))
            n1 = (K2_inv @ np.column_stack([p1, np.ones(len(p1))]).T).T
            n2 = (K1_inv @ np.column_stack([p2, np.ones(len(p2))]).T).T
            A = np.zeros((len(n1), 9))
            for i in range(len(n1)):
                x1, y1, w1 = n1[i]
                x2, y2, w2 = n2[i]
                A[i] = [x2 * x1, x2 * y1, x2 * w1, y2 * x1, y2 * y1, y2 * w1, w2 * x1, w2 * y1, w2 * w1]
            E = np.linalg.svd(A)[2][-1].reshape(3, 3)
            U, S, Vt = np.linalg.svd(E)
            s = (S[0] + S[1]) / 2.0
            return U @ np.diag([s, s, 0.0]) @ Vt
        """)
    result = grade(folder, ["lab11.ex3"], pictures="none", include_hidden=True)
    told = [c.message for c in check_results(result, "lab11.ex3") if c.score < c.max_score and "Trying small" in c.message]
    assert told and all("to `K1_inv @ np.column_stack" in m for m in told), told
    assert any("np.asarray(K1, dtype=np.float64)` to `np.asarray(K2" not in m for m in told), told


def test_made_homogeneous_needs_the_reference_numbers_and_a_constant_or_unit_slice():
    A = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
    assert traced._made_homogeneous(np.vstack([A, [0.0, 0.0, 1.0]]), A)
    assert traced._made_homogeneous(np.column_stack([np.ones(2), A]), A)
    assert not traced._made_homogeneous(np.vstack([A, [0.0, 2.0, 1.0]]), A)
    assert not traced._made_homogeneous(np.vstack([A[::-1], [0.0, 0.0, 1.0]]), A)
    assert not traced._made_homogeneous(np.vstack([A, A]), A)


def test_a_change_skipping_a_step_points_at_the_step(tmp_path):
    """`homogeneous[:, :2]` -> `X[:, :2]` mends a matrix typed with a wrong row by skipping the product:
    the sentence says which step is skipped, the module's matrix it reads, and that the step is where to look."""
    folder = mutant(tmp_path, "lab10_camera2", """
        ORTHOGRAPHIC = np.array([[1.0, 0.0, 0.0, 0.0],
                                 [0.0, 0.0, 1.0, 0.0],
                                 [0.0, 0.0, 0.0, 1.0]])

        def orthographic_project(points):
            X = np.atleast_2d(np.asarray(points, dtype=np.float64))
            homogeneous = np.column_stack([X, np.ones(len(X))]) @ ORTHOGRAPHIC.T
            x = homogeneous[:, :2] / homogeneous[:, 2:3]
            return x[0] if np.ndim(points) == 1 else x
        """)
    _, repaired = _failed_and_repaired(folder, "lab10.ex3")
    assert repaired, "no change told"
    said = repaired[0]
    assert "skips the step of line" in said and "computes `homogeneous` from `X`" in said, said
    assert "`ORTHOGRAPHIC`" in said and "likely in that step" in said, said
    assert "so the mistake is likely there" not in said, said


def test_a_name_replaced_by_what_it_is_computed_from_skips_a_step():
    """`y` -> `x1` where `y = x1 * 2` skips the step of line 3; `y` -> `x2` (y is not made from x2), a name
    replaced where it is assigned, or a name read in another's place (`x1` -> `y`) skip nothing."""
    source = textwrap.dedent("""
        def graded(x1, x2):
            y = x1 * 2
            return y + x1
    """)
    student = repair._Student(source, ast.parse(source), ["graded"])
    skips = {student.fix(m).changes[0][2]: student.skipped_step(m)
             for m in student.mutants("graded") if m.operator == "other_name" and student.fix(m)}
    assert skips["return x1 + x1"] == (3, "y", "x1", ())
    assert skips["return x2 + x1"] == () and skips["y = x2 * 2"] == () and skips["return y + y"] == ()


def test_a_name_read_in_place_of_its_stacked_form_skips_no_step():
    """`Xh[:, -1]` -> `pts[:, -1]` where `Xh = np.hstack([pts, ones])`: another column is read (Z, not the ones),
    no step is skipped (1202f 10/01); `y` -> `x1` where `y = x1 * 2` still skips one."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(pts, x1):
            Xh = np.hstack([pts, np.ones((len(pts), 1))])
            y = x1 * 2
            return Xh[:, -1].mean() + y
    """)
    student = repair._Student(source, ast.parse(source), ["graded"])
    skips = {student.fix(m).changes[0][2]: student.skipped_step(m)
             for m in student.mutants("graded") if m.operator == "other_name" and student.fix(m)}
    assert skips["pts[:, -1].mean()"] == (), skips
    assert skips["Xh[:, -1].mean() + x1"][:3] == (6, "y", "x1"), skips


def test_a_centring_taken_out_where_a_right_solution_centres_points_at_its_undoing(tmp_path):
    """U = diag(s, s, s, 1) without its translation: taking out the world points' centring mends the DLT, but
    the centring is right; the sentence sends the student to where it is undone (1202f 10/05)."""
    folder = mutant(tmp_path, "lab10_camera2", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.asarray(points3d, dtype=np.float64)
            x = np.asarray(points2d, dtype=np.float64)
            c2 = x.mean(axis=0)
            s2 = np.sqrt(2.0) / np.mean(np.linalg.norm(x - c2, axis=1))
            T = np.array([[s2, 0.0, -s2 * c2[0]], [0.0, s2, -s2 * c2[1]], [0.0, 0.0, 1.0]])
            c3 = X.mean(axis=0)
            s3 = np.sqrt(3.0) / np.mean(np.linalg.norm(X - c3, axis=1))
            U = np.diag([s3, s3, s3, 1.0])
            xn = s2 * (x - c2)
            Xn = s3 * (X - c3)
            A = []
            for (Xi, Yi, Zi), (ui, vi) in zip(Xn, xn):
                Xh = [Xi, Yi, Zi, 1.0]
                A.append(Xh + [0.0, 0.0, 0.0, 0.0] + [-ui * c for c in Xh])
                A.append([0.0, 0.0, 0.0, 0.0] + Xh + [-vi * c for c in Xh])
            _, _, Vt = np.linalg.svd(np.array(A))
            P = np.linalg.inv(T) @ Vt[-1].reshape(3, 4) @ U
            return P / np.linalg.norm(P)
        """)
    _, repaired = _failed_and_repaired(folder, "lab10.ex4")
    assert repaired, "no change told"
    centring = [said for said in repaired if "s3 * (X - c3)" in said]
    assert centring and all("more likely where the centring is undone" in said for said in centring), repaired
    assert not any("s3 * (X - c3)` to `s3 * X` (line" in said and "so the mistake is likely there" in said
                   for said in repaired), repaired


def test_a_built_copy_and_its_raw_name_are_tried_in_each_others_place():
    """`new_K` built from K's entries, passed where K belongs: `new_K` -> `K` is offered (a prefixed name is a
    processed copy, as a suffixed one is: 1202f 10/06)."""
    from autograder.engine.mutants.operators import _derived_names

    assert _derived_names("K", "new_K") and _derived_names("pts", "raw_pts") and _derived_names("x", "x_norm")
    assert not _derived_names("K", "mask") and not _derived_names("a", "banana")
    source = textwrap.dedent("""
        import numpy as np

        def graded(image, K, dist):
            K = np.asarray(K, dtype=np.float64)
            f, cx, cy = K[0, 0], K[0, 2], K[1, 2]
            new_K = np.array([[f, 0.0, cx], [0.0, f, cy], [0.0, 0.0, 1.0]])
            return np.dot(new_K, dist)
    """)
    assert ("new_K", "K") in _made(source, {"other_name"}), _made(source, {"other_name"})


def test_a_constant_typed_with_a_few_digits_is_offered_exact():
    """`3.14` -> `np.pi`, `57.3` -> `180 / np.pi`; a 3.0 or an exact np.pi is left as it is (1202g 07/02)."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(a, b):
            return a * 3.14 / 180, b * 57.3, a * 3.0, b * np.pi
    """)
    made = _made(source, {"exact_constant"})
    assert made == {("3.14", "np.pi"), ("57.3", "180 / np.pi")}, made


def test_a_sum_made_once_above_nested_loops_is_reset_in_the_loop_that_stores_it():
    """`total = 0.0` above `for i` / `for j`, grown in `for k` and stored as E[i, j] in `for j`: moved into
    `for j` as its first statement (1202g 11/04); not into `for k`, where nothing reads it."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(A, B):
            E = np.zeros((3, 3))
            total = 0.0
            for i in range(3):
                for j in range(3):
                    for k in range(3):
                        total += A[i, k] * B[k, j]
                    E[i, j] = total
            return E
    """)
    fn = next(node for node in ast.parse(source).body if isinstance(node, ast.FunctionDef))
    into = {ast.unparse(list(ast.walk(fn))[m.edits[0][1]]).splitlines()[0]
            for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
            if m.operator == "indent" and "total = 0.0" in str(m.edits[0][3])}
    assert "for j in range(3):" in into and "for k in range(3):" not in into, into


def test_a_chain_of_matrices_replaced_at_every_step_is_multiplied_instead():
    """`H = step[j]` in a loop after `H = np.eye(3)`: the chain's product never kept (an image two steps
    from the reference placed with its neighbour's homography). Both orders of the product are changes
    tried; an assignment in a loop that starts from no identity has none, and `H @= S` may be assigned."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(step, k, r, S):
            H = np.eye(3)
            for j in range(k - 1, r - 1, -1):
                H = step[j]
            total = 0
            for j in range(k):
                total = step[j]
            G = np.eye(3)
            G @= S
            return H, total, G
    """)
    changes = _shown_changes(source, "accumulate")
    assert ("H = step[j]", "H = step[j] @ H") in changes and ("H = step[j]", "H @= step[j]") in changes
    assert not any(after.endswith("@ total") or after == "total @= step[j]" for _, after in changes)
    assert ("G @= S", "G = S") in changes


def test_points_divided_by_another_value_than_their_last_coordinate_are_divided_by_it():
    """`homogeneous[:, :2] / depth` (the Z before K was applied) where `homogeneous[:, 2:3]` belongs: the divisor
    is made the points' own last coordinate; one that already is stays."""
    source = textwrap.dedent("""
        def graded(X, K):
            depth = X[:, 2:3]
            homogeneous = (X / depth) @ K.T
            right = homogeneous[:, :2] / homogeneous[:, 2:3]
            return homogeneous[:, :2] / depth, right
    """)
    changes = _shown_changes(source, "dehomogenise")
    assert ("homogeneous[:, :2] / depth", "homogeneous[:, :2] / homogeneous[:, 2:3]") in changes
    assert not any(before == "homogeneous[:, :2] / homogeneous[:, 2:3]" for before, _ in changes)


def test_a_table_started_at_zero_before_its_argmin_is_started_at_infinity():
    """`costs = np.zeros(...)` filled only where a match exists, then `np.argmin(costs, axis=0)`: the unfilled
    entries (0) win; started at np.inf they lose. A zeros array no minimum is taken of has no such change."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(d, shape, x):
            costs = np.zeros((d,) + shape)
            best = np.zeros_like(x)
            sums = np.zeros(shape)
            return np.argmin(costs, axis=0), best.min(), sums
    """)
    changes = _shown_changes(source, "fill_inf")
    assert ("np.zeros((d,) + shape)", "np.full((d,) + shape, np.inf)") in changes
    assert ("np.zeros_like(x)", "np.full_like(x, np.inf, dtype=np.float64)") in changes
    assert not any(before == "np.zeros(shape)" for before, _ in changes)


def test_a_penalty_for_any_jump_is_made_one_for_its_size():
    """`s * (labels[:, None] != labels[None, :])` (the Potts model) where the jump's size is paid, `s * |d - d'|`;
    a comparison not weighing anything is no penalty."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(labels, s, a, b):
            penalty = s * (labels[:, None] != labels[None, :])
            changed = a != b
            return penalty, changed
    """)
    changes = _shown_changes(source, "jump_size")
    assert changes == [("labels[:, None] != labels[None, :]", "np.abs(labels[:, None] - labels[None, :])")]


def test_a_change_comparing_a_value_with_its_own_length_is_never_a_fix():
    """`column < len(patterns)` made `depth < len(depth)` by two names changed: true wherever the depths stay
    below the image's height, so right on the inputs tried, and meaningless; a comparison the student wrote
    that way is not held against other changes."""
    source = textwrap.dedent("""
        def graded(column, patterns, depth):
            lit = (column >= 0) & (column < len(patterns))
            return lit
    """)
    student = repair._Student(source, ast.parse(source), {"graded"})
    both = [m for m in student.mutants("graded") if m.operator == "other_name"]
    column, bound = (next(m for m in both if student.fix(m).changes[0][1:] == pair)
                     for pair in (("column < len(patterns)", "depth < len(patterns)"), ("len(patterns)", "len(depth)")))
    paired = dataclasses.replace(column, edits=column.edits + bound.edits)
    assert student.compares_with_its_own_size(paired)
    assert not student.compares_with_its_own_size(column) and not student.compares_with_its_own_size(bound)


def test_a_bound_counted_by_len_is_counted_along_the_second_axis():
    """`column < len(patterns)` with patterns (n_bits, width): len counts the patterns, the columns were meant;
    a len not compared with anything (a loop's count) has no such change."""
    source = textwrap.dedent("""
        def graded(column, patterns):
            lit = (column >= 0) & (column < len(patterns))
            return lit, range(len(patterns))
    """)
    assert _shown_changes(source, "len_axis") == [("len(patterns)", "patterns.shape[1]")]


def test_a_number_given_where_an_array_is_reduced_is_no_repair():
    """The blind set 1204c's 12/03: `d > np.nanmin(d)` mended by `np.nanmin(baseline)` on inputs whose disparities
    all exceed the baseline: the minimum of one number is that number, a threshold nobody writes so. The array
    itself given there (`np.nanmin(depth)`) is judged as ever."""
    source = textwrap.dedent("""
        import numpy as np

        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=np.float64)
            depth = np.zeros_like(d)
            valid = d > np.nanmin(d)
            depth[valid] = f * baseline / d[valid]
            return depth
    """)
    student = repair._Student(source, ast.parse(source), ["depth_from_disparity"])
    inputs = [("depth_from_disparity", (np.array([10.0, 0.0]), 500.0, 0.1), {})]
    numbers = repair._numbers_given(student, "depth_from_disparity", inputs)
    assert numbers == {"f", "baseline"}
    names = [m for m in student.mutants("depth_from_disparity") if m.operator == "other_name"
             and student.fix(m) and "np.nanmin(" in student.fix(m).changes[0][2]]
    told = {student.fix(m).changes[0][2]: student.reduces_a_number(m, numbers) for m in names}
    assert told.get("np.nanmin(baseline)") is True, told
    assert not any(value for text, value in told.items() if "baseline" not in text and "(f)" not in text), told


def test_a_change_that_throws_away_a_drawing_is_no_repair_and_a_copy_is_tried_in_the_original_s_place():
    """The blind set 1204c's 08/05: lines drawn on `canvas`, circles on its copy `out`, `out` returned. Returning
    `canvas` keeps the lines and throws the circles away (out, drawn on, no longer reaches the answer); drawing
    the lines on `out` is the fix, and the operators offer the copy where the original is written."""
    source = textwrap.dedent("""
        import cv2
        import numpy as np

        def draw_matches(img1, img2, pts1, pts2):
            canvas = np.hstack([img1, img2])
            out = canvas.copy()
            for a, b in zip(pts1, pts2):
                cv2.line(canvas, a, b, (0, 255, 0), 1)
                cv2.circle(out, a, 3, (0, 0, 255), 1)
            return out
    """)
    before = _defs_of(source)["draw_matches"]
    assert repair._disconnects(before, _defs_of(source.replace("return out", "return canvas"))["draw_matches"])
    assert not repair._disconnects(before, _defs_of(source.replace("cv2.line(canvas", "cv2.line(out"))["draw_matches"])
    student = repair._Student(source, ast.parse(source), ["draw_matches"])
    made = {student.fix(m).changes[0][2] for m in student.mutants("draw_matches") if m.operator == "other_name"
            and student.fix(m)}
    assert "cv2.line(out, a, b, (0, 255, 0), 1)" in made, made


def test_a_change_mending_landscape_images_only_is_not_told(tmp_path):
    """The image padded into a square at its bottom and right and rotated about the square's centre: the
    check's images are all landscape, where a centre of ((side - 1) / 2, (height - 1) / 2) is the image's; on
    the same image turned portrait it mends nothing, so it is not told (the blind set 1204d's 07/03)."""
    source = """
        def rotate(image, angle_deg=45):
            height, width = image.shape[:2]
            side = max(height, width)
            padding = [(0, side - height), (0, side - width)] + [(0, 0)] * (image.ndim - 2)
            square = np.pad(image, padding)
            centre = ((side - 1) / 2.0, (side - 1) / 2.0)
            M = cv2.getRotationMatrix2D(centre, angle_deg, 1.0)
            rotated = cv2.warpAffine(square, M, (side, side), flags=cv2.INTER_LINEAR,
                                     borderMode=cv2.BORDER_CONSTANT, borderValue=0)
            return rotated[:height, :width]
        """
    messages = failing_messages(mutant(tmp_path, "lab07_transformations", source), "lab07.ex2")
    assert messages
    assert not any("`((side - 1) / 2.0, (height - 1) / 2.0)`" in m for m in messages), messages
    turned = repair._turned(("rotate", (np.zeros((30, 40, 3), np.uint8), 45), {}))
    assert turned and turned[0][1][0].shape == (40, 30, 3)
    assert repair._turned(("rotate", (np.zeros((30, 30), np.uint8), 45), {})) == []


def test_costs_without_a_partner_marked_nan_get_a_tip_not_a_repair(tmp_path):
    """The SSD volume made and its cells without a partner marked with NaN, which np.argmin picks first (the
    blind set 1204e's 12/04): only the left band, where x - d leaves the right image, is changed -- a band the
    skeleton leaves out of every judged rate and the API leaves open (the blind legitimate set 1206m): a tip
    naming it, no point lost, so no repair is searched."""
    folder = edited_reference(tmp_path, "lab12_stereo", (
        "    costs = np.full((max_disparity + 1, height, width), np.inf)\n"
        "    for d in range(min(max_disparity, width - 1) + 1):\n"
        "        squared = (left - _shift_right(right, d)) ** 2\n"
        "        costs[d] = _box_mean(squared, block_size)\n"
        "        costs[d, :, :d] = np.inf ",
        "    costs = np.full((max_disparity + 1, height, width), np.nan)\n"
        "    for d in range(min(max_disparity, width - 1) + 1):\n"
        "        squared = (left - _shift_right(right, d)) ** 2\n"
        "        costs[d] = _box_mean(squared, block_size)\n"
        "        costs[d, :, :d] = np.nan "))
    result = grade(folder, ["lab12.ex4"], pictures="none", include_hidden=False)
    checks = check_results(result, "lab12.ex4")
    assert all(c.score == c.max_score for c in checks), [c.message for c in checks if c.score < c.max_score]
    assert any(c.advice and "left of the right image's first column" in c.message for c in checks), \
        [c.message for c in checks if c.advice]
    assert not any("Trying small changes" in c.message for c in checks)


def test_a_name_given_where_it_makes_a_call_take_one_name_twice_is_no_fix():
    """`cv2.addWeighted(overlay, 0.6, image, 0.4, 0)` -> `(overlay, 0.6, overlay, 0.4, 0)` blends the drawing with
    itself: it works round the blend (blind set 1204e's 09/06), where a name made another's in a call that keeps two
    names apart may be the slip."""
    blended = repair.Fix(((105, "cv2.addWeighted(overlay, 0.6, image, 0.4, 0)",
                           "cv2.addWeighted(overlay, 0.6, overlay, 0.4, 0)"),), "draw_points", "other_name", ())
    apart = repair.Fix(((12, "f(pts1, pts1)", "f(pts1, pts2)"),), "graded", "other_name", ())
    assert repair._one_argument_twice(blended) and not repair._one_argument_twice(apart)


def test_a_whole_array_reduced_where_each_pixel_s_own_sum_belongs_is_given_its_own():
    """`total / weights.max()` where `weights` is summed up pixel by pixel (a feathered blend's weights): divided
    by each pixel's own sum, `weights[..., None]`; a reduction of a name never summed up has no such change."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(images, ws, image):
            total, weights = 0.0, 0.0
            for im, w in zip(images, ws):
                total += im * w[..., None]
                weights += w
            return total / weights.max(), image / image.max(), total / np.sum(weights)
    """)
    changes = _shown_changes(source, "own_values")
    assert ("weights.max()", "weights[..., None]") in changes and ("np.sum(weights)", "weights[..., None]") in changes
    assert not any(before == "image.max()" for before, _ in changes)


def test_a_spread_s_other_normalisation_and_a_count_beside_it_are_tried():
    """np.cov divides by n - 1: `np.cov(S.T)` -> `np.cov(S.T, bias=True)`, `x.std()` -> `x.std(ddof=1)`,
    `np.var(x, ddof=1)` -> `np.var(x)`; a sum divided by a count beside a spread -> `/ (n - 1)`. A mean divided by
    a count with no spread in the def is left as it is."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(S, D, x):
            n = len(S)
            spread = np.cov(S.T)
            cross = D.T @ S / n
            deviation = x.std()
            variance = np.var(x, ddof=1)
            return spread, cross, deviation, variance
        def other(S):
            n = S.shape[0]
            return S.sum(axis=0) / n
    """)
    changes = _shown_changes(source, "estimator")
    assert ("spread = np.cov(S.T)", "spread = np.cov(S.T, bias=True)") in changes
    assert ("deviation = x.std()", "deviation = x.std(ddof=1)") in changes and ("np.var(x, ddof=1)", "np.var(x)") in changes
    assert ("cross = D.T @ S / n", "cross = D.T @ S / (n - 1)") in changes, changes
    student = repair._Student(source, ast.parse(source), {"other"})
    assert not [m for m in student.mutants("other") if m.operator == "estimator"]


def test_planes_a_loop_made_stacked_channel_first_are_stacked_on_the_last_axis():
    """`np.array(planes)` of a list a comprehension or a loop made: `np.stack(planes, axis=-1)`; an array of a
    parameter is left as it is."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(image, pts):
            planes = [image[:, :, k] * 2 for k in range(3)]
            rows = []
            for p in pts:
                rows.append(p)
            return np.array(planes), np.asarray(rows), np.array(pts)
    """)
    changes = _shown_changes(source, "stack_last")
    assert ("np.array(planes)", "np.stack(planes, axis=-1)") in changes
    assert ("np.asarray(rows)", "np.stack(rows, axis=-1)") in changes
    assert not any(before == "np.array(pts)" for before, _ in changes)


def test_an_image_s_rows_and_columns_exchanged_with_t_are_swapped_axes():
    """`img.T` reverses every axis (a colour image's channels come first): `np.swapaxes(img, 0, 1)`; a `.T`
    nested in one is the same slip, swapped with it; a matrix's `.T` is left as it is."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(img, R, tx):
            flipped = img.T
            back = shift(img.T, tx).T
            return flipped, back, R.T
    """)
    changes = _shown_changes(source, "swap_axes")
    assert ("flipped = img.T", "flipped = np.swapaxes(img, 0, 1)") in changes, changes
    assert ("back = shift(img.T, tx).T", "back = np.swapaxes(shift(np.swapaxes(img, 0, 1), tx), 0, 1)") in changes
    assert not any("R" in before for before, _ in changes)


def test_points_scaled_whole_are_scaled_in_x_and_y_only():
    """`X * f` before a projection with unit focal length scales the depth too (it cancels): `X * np.array([f, f,
    1.0])`; a product of two names that read as points, or of a scalar by a scalar, is left as it is."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(X, f, s, t):
            scaled = X * f
            both = X * points
            plain = s * t
            return scaled, both, plain
    """)
    changes = _shown_changes(source, "scale_xy")
    assert changes == [("scaled = X * f", "scaled = X * np.array([f, f, 1.0])")], changes


def test_a_value_of_the_student_s_own_that_only_scales_or_shifts_is_made_neutral():
    """`scale = r.max()` read only in products and divisions -> `1.0`; `c = pts.mean()` read only in sums and
    differences is a centring, left to drop_centring; a value read otherwise too, or read once, has no such change."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(pts, k):
            scale = np.abs(pts).max()
            centre = pts.mean()
            kept = pts.sum()
            once = k * 2
            moved = (pts - centre) / scale * k + centre
            return moved * scale, kept * 2, np.sqrt(kept), once
    """)
    changes = _shown_changes(source, "neutral")
    assert ("np.abs(pts).max()", "1.0") in changes, changes
    assert not any("mean" in before for before, _ in changes), changes   # (a centring: drop_centring's)
    assert not any(before in ("pts.sum()", "k * 2") for before, _ in changes), changes


def test_a_number_of_the_student_s_own_only_added_is_made_zero():
    """`gap = 4` read only in sums (a separator between two pictures, a margin the API does not ask for) -> `0`;
    a number read in a product, or read once, has no such change."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(w1, w2, x):
            gap = 4
            factor = 3
            once = 7
            width = w1 + gap + w2
            offset = w1 + gap
            return width, offset, factor * x, factor + x, once + x
    """)
    changes = _shown_changes(source, "neutral")
    assert ("gap = 4", "gap = 0") in changes, changes
    assert not any(before.startswith(("factor", "once")) for before, _ in changes), changes


def test_a_name_made_and_never_read_is_tried_where_a_number_is_written_after_it():
    """`n = len(src)` never read, and a `1` in the normal matrix where the count of points belongs: `1` -> `n`;
    numbers in an index, a keyword, or before the name is made are left as they are."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(src, x):
            early = x * 2
            n = len(src)
            normal = np.array([[np.sum(x * x), np.sum(x)], [np.sum(x), 1]])
            return normal, src[:, 0], np.sum(x, axis=0), early
    """)
    changes = _shown_changes(source, "unused_name")
    assert ("[np.sum(x), 1]", "[np.sum(x), n]") in changes, changes
    assert len(changes) == 1, changes


def test_a_test_of_one_twin_is_given_the_other_s_half():
    """`if float(tx).is_integer():` before a shortcut that shifts by tx and ty: the twin's test added, `and
    float(ty).is_integer()`; a test reading both twins already, or a name with no twin, is left as it is."""
    source = textwrap.dedent("""
        def graded(image, tx, ty, k):
            if float(tx).is_integer():
                return image
            if tx > 0 and ty > 0:
                return image
            if k > 2:
                return None
            return image
    """)
    changes = _shown_changes(source, "twin_test")
    assert changes == [("float(tx).is_integer()", "float(tx).is_integer() and float(ty).is_integer()")], changes


def test_a_small_number_added_to_keep_a_division_finite_is_taken_out():
    """`X[:, 2:3] + 1e-6` -> `X[:, 2:3]`, `1e-9 - d` -> `-d`: only floats of at most 1e-3 count."""
    source = textwrap.dedent("""
        def graded(X, f, d):
            x = f * X[:, :2] / (X[:, 2:3] + 1e-6)
            y = d + 0.5
            return x, 1e-9 - d, y
    """)
    changes = _shown_changes(source, "drop_epsilon")
    assert ("X[:, 2:3] + 1e-06", "X[:, 2:3]") in changes and ("x, 1e-09 - d, y", "x, -d, y") in changes, changes
    assert not any("0.5" in before for before, _ in changes)


def test_a_scaling_done_in_place_is_undone_the_other_way_and_counts_as_one_slip_at_two_places():
    """`H[:2, 2] /= k` and `H[2, :2] *= k` (a denormalisation inverted): each flipped, and the two are the same slip,
    so they are paired."""
    source = textwrap.dedent("""
        def graded(H, k):
            H[:2, 2] /= k
            H[2, :2] *= k
            H += 1
            return H
    """)
    changes = _shown_changes(source, "scale_inverse")
    assert changes == [("H[:2, 2] /= k", "H[:2, 2] *= k"), ("H[2, :2] *= k", "H[2, :2] /= k")], changes
    student = repair._Student(source, ast.parse(source), {"graded"})
    flips = [m for m in student.mutants("graded") if m.operator == "scale_inverse"]
    assert len({student.slip(m) for m in flips}) == 1


def test_names_assigned_together_are_given_the_values_their_twins_are_made_with():
    """`y_min, y_max = 0.0, h - 1.0` below `x_min = corners[:, 0].min()` and `x_max = corners[:, 0].max()`:
    the y values made as the x ones are, for the other axis; a tuple whose names have no twins is left."""
    source = textwrap.dedent("""
        def graded(corners, h):
            x_min = corners[:, 0].min()
            x_max = corners[:, 0].max()
            y_min, y_max = 0.0, h - 1.0
            a, b = 1, 2
            return x_min, x_max, y_min, y_max, a, b
    """)
    changes = _shown_changes(source, "twin_values")
    assert changes == [("0.0, h - 1.0", "corners[:, 1].min(), corners[:, 1].max()")], changes


def test_a_branch_of_a_choice_read_where_the_choice_belongs_is_given_the_choice():
    """`z = centroid[2] if z_avg is None else float(z_avg)`, then `centroid[2]` read again: `z` in its place; the
    branch read before the choice is made, or a constant branch, is left."""
    source = textwrap.dedent("""
        def graded(c, z_avg, f):
            before = c[2] * 2
            z = c[2] if z_avg is None else float(z_avg)
            anchor = f * c[:2] / c[2]
            return anchor, z, before
    """)
    changes = _shown_changes(source, "chosen_value")
    assert changes == [("f * c[:2] / c[2]", "f * c[:2] / z")], changes


def test_the_array_a_loop_fills_made_anew_at_each_turn_is_made_before_the_loop():
    """`for i in range(n): points = np.zeros((n, 3)); ...; points[i] = X` keeps the last point only: the allocation
    moved before the loop; an array made in the loop and kept whole (appended) is left."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(n):
            for i in range(n):
                points = np.zeros((n, 3))
                points[i] = i
            frames = []
            for i in range(n):
                frame = np.zeros((2, 2))
                frames.append(frame)
            return points, frames
    """)
    changes = _shown_changes(source, "hoist")
    assert len(changes) == 1 and changes[0][0] == "points = np.zeros((n, 3))" and "just before it" in changes[0][1]


def test_discs_drawn_one_pixel_smaller_are_told_so_and_mended_beside_it(tmp_path):
    """`int(radius) - 1` for cv2.circle's radius: the check measures the discs smaller than the radius asked, and
    the change that mends it is told beside that name."""
    folder = edited_reference(tmp_path, "lab09_camera", (
        "cv2.circle(out, (int(round(x)), int(round(y))), int(radius), color, thickness=-1)",
        "cv2.circle(out, (int(round(x)), int(round(y))), int(radius) - 1, color, thickness=-1)"))
    result = grade(folder, ["lab09.ex5"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab09.ex5") if c.score < c.max_score]
    told = [c for c in failed if "drawn smaller than the radius asked" in c.message
            and "`int(radius) - 1` to `int(radius)`" in c.message]
    assert told, [c.message for c in failed]


def test_a_list_closed_one_item_early_in_a_numpy_call_takes_the_item_in():
    """`np.diag([sx, sy], 1)` (1 read as the diagonal's offset) -> `np.diag([sx, sy, 1])`; a call given a list and a
    string, or a keyword, is left as it is."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(sx, sy, x):
            S = np.diag([sx, sy], 1)
            a = np.array([x, x], "float64")
            b = np.sum([x, x], axis=0)
            return S, a, b
    """)
    changes = _shown_changes(source, "bracket")
    assert ("np.diag([sx, sy], 1)", "np.diag([sx, sy, 1])") in changes, changes
    assert not any("float64" in before or "axis" in before for before, _ in changes), changes


def test_an_angle_taken_where_the_ratio_belongs_is_made_the_ratio():
    """`f * np.arctan2(X, Z)` for the pinhole's `f * X / Z`: the arctan2 made the ratio it is the angle of."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(X, Z, f):
            return f * np.arctan2(X, Z)
    """)
    assert ("np.arctan2(X, Z)", "X / Z") in _shown_changes(source, "unwrap")


def test_twin_blocks_of_rows_added_where_they_stack_are_stacked():
    """`A = rows_u + rows_v` of two stacked blocks: `np.vstack([rows_u, rows_v])`; a sum of twins not made by
    stacking (`x1 + x2`) is left as it is."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(Xn, zeros, x1, x2):
            rows_u = np.hstack([Xn, zeros])
            rows_v = np.hstack([zeros, Xn])
            A = rows_u + rows_v
            return A, x1 + x2
    """)
    assert _shown_changes(source, "add_stacked") == [("rows_u + rows_v", "np.vstack([rows_u, rows_v])")]


def test_a_difference_made_negative_in_an_output_size_is_no_fix():
    # (OpenCV takes a non-positive dsize for the input's: `int(x0 - x1)` "mends" a canvas sized otherwise by
    # coincidence; the same exchange elsewhere, or of a size OpenCV is not given, stays a change to try)
    student, mutants = _read("""
        import cv2

        def graded(img, H, x0, x1, y0, y1):
            size = (int(x1 - x0) + 1, int(y1 - y0) + 1)
            shift = x1 - x0
            return cv2.warpPerspective(img, H, size), shift
    """)
    exchanged = {student.fix(m).changes[0][2]: m for m in mutants
                 if m.operator == "swap_operands" and student.fix(m) is not None}
    assert student.negates_a_size(exchanged["int(x0 - x1)"])
    assert student.negates_a_size(exchanged["int(y0 - y1)"])
    assert not student.negates_a_size(exchanged["shift = x0 - x1"])   # (the shift: no size)


def test_one_change_made_alike_on_several_lines_is_told_once():
    fix = repair.Fix(((7, "size", "(width, height)"), (8, "size", "(width, height)")), "graded", "aligned",
                     (("graded", 1, "aligned", "(width, height)"), ("graded", 2, "aligned", "(width, height)")))
    assert fix.told("graded") == "changing `size` to `(width, height)` (lines 7 and 8)"
    twice = repair.Fix(((7, "x", "y"), (7, "x", "y")), "graded", "other_name",
                       (("graded", 1, "other_name", "y"), ("graded", 2, "other_name", "y")))
    assert twice.told("graded").count("(line 7)") == 2   # (twice on one line: both told)


def test_arctan2_given_its_arguments_in_its_own_order_is_told_alone():
    # (y first, by their names: the exchange of a cos and a sin downstream mends alike and compensates)
    def exchanged(before, after):
        return repair.Fix(((160, before, after),), "graded", "swap_args", (("graded", 1, "swap_args", None),))
    assert repair._arctan2_ordered(exchanged("np.arctan2(x, y)", "np.arctan2(y, x)"))
    assert repair._arctan2_ordered(exchanged("math.atan2(u, v)", "math.atan2(v, u)"))
    assert not repair._arctan2_ordered(exchanged("np.arctan2(y, x)", "np.arctan2(x, y)"))
    assert not repair._arctan2_ordered(exchanged("(r * np.cos(phi), r * np.sin(phi))", "(r * np.sin(phi), r * np.cos(phi))"))


Z_BUFFERED = """
    def simulate_structured_light(depth, f, baseline, n_bits):
        depth = np.asarray(depth, dtype=np.float64)
        height, width = depth.shape
        patterns = gray_code_patterns(width, n_bits)
        images = np.zeros((int(n_bits), height, width), dtype=np.uint8)
        rows, cols = np.nonzero(np.isfinite(depth) & (depth > 0))
        z = depth[rows, cols]
        column = np.floor(cols - float(f) * float(baseline) / z + 0.5).astype(np.int64)
        on_projector = (column >= 0) & (column < width)
        rows, cols, column, z = rows[on_projector], cols[on_projector], column[on_projector], z[on_projector]
        nearest = np.full((height, width), np.inf)
        np.minimum.at(nearest, (rows, column), z)
        front = z <= nearest[rows, column]
        rows, cols, column = rows[front], cols[front], column[front]
        images[:, rows, cols] = patterns[:, column]
        return images
    """


def test_changes_that_all_make_one_filter_keep_everything_give_way_to_the_filter_taken_out():
    """A z-buffer of the student's own (only the nearest pixel of a projector column lit), which the API's model
    has not: its test turned round, the depth tested made the row index, the minimum taken of another number --
    each mends by making the filter keep every pixel (the 05c blind set's 12/06, told `z` -> `rows` before). Of
    the confirmed changes, the filter's removal is what is tried and told (the grading confirms it: how many of
    the others it confirms first depends on its time, so the choice is tested here, on the code alone)."""
    source = "import numpy as np\n" + textwrap.dedent(Z_BUFFERED)
    student = repair._Student(source, ast.parse(source), {"simulate_structured_light"})
    changes = {m.key: student.fix(m) for m in student.ordered("simulate_structured_light")}
    def confirmed(before, after):
        return next((m, f) for m in student.ordered("simulate_structured_light")
                    for f in [changes[m.key]] if f.changes[0][1:] == (before, after))
    for fixes in ([confirmed("z <= nearest[rows, column]", "z >= nearest[rows, column]")],
                  [confirmed("z[on_projector]", "rows[on_projector]"),
                   confirmed("np.minimum.at(nearest, (rows, column), z)",
                             "np.minimum.at(nearest, (rows, column), height)")]):
        taken_out = student.filter_all_feed(fixes)
        assert taken_out is not None and student.fix(taken_out).changes[0][1:] == (
            "rows, cols, column = (rows[front], cols[front], column[front])", "pass")
    # a change after the filter, of what it kept, feeds no mask: nothing is taken out for it
    after = [(m, f) for m in student.ordered("simulate_structured_light") for f in [changes[m.key]]
             if f.changes[0][1].startswith("images[:, rows, cols]")]
    assert after and all(student.filter_all_feed([pair]) is None for pair in after)


def test_a_filter_is_read_with_what_its_mask_is_computed_from():
    fn = ast.parse(textwrap.dedent(Z_BUFFERED)).body[0]
    nodes = list(ast.walk(fn))
    [kept] = [n for n in nodes if isinstance(n, ast.Assign) and repair._kept_by_mask(n) == "front"]
    lines = repair._feeding(nodes, kept, "front")
    text = textwrap.dedent(Z_BUFFERED).splitlines()
    fed = {text[line - 1].strip().split(" =")[0].split("(")[0] for line in lines}
    assert fed >= {"front", "np.minimum.at", "nearest", "rows, cols, column, z", "column", "z"}, fed
    assert "images" not in fed and "patterns" not in fed
    assert repair._kept_by_mask(ast.parse("a = b[m]").body[0]) == "m"
    assert repair._kept_by_mask(ast.parse("a, b = a[m], b[n]").body[0]) is None
    assert repair._kept_by_mask(ast.parse("a = b[0]").body[0]) is None


def test_a_square_written_where_a_power_of_two_belongs_is_told_base_and_exponent_swapped(tmp_path):
    """`n_bits ** 2` stripes where `2 ** n_bits` belong (right at 2 and 4 bits only: the 05d blind set's 12/05,
    only the wrong column told before)."""
    folder = edited_reference(tmp_path, "lab12_stereo", ("k = (u * (1 << int(n_bits))) // int(width)",
                                                         "k = (u * int(n_bits) ** 2) // int(width)"))
    said = " ".join(failing_messages(folder, "lab12.ex6"))
    assert "changing `int(n_bits) ** 2` to `2 ** int(n_bits)`" in said, said


def test_slips_of_the_blind_sets_1205d_and_1205e_are_changes_tried():
    """The student's code only: a bit string read as a decimal number (`int("".join(bits))`), points made
    columns by a reshape (`pts.reshape(3, -1)` where the transpose belongs, kept 2-D for one point), a
    running product kept in a list and updated in place (`chain @= step` after `out[k] = chain`), and a
    shift padded on the left then cut back at its start (`np.pad(...)[:, d:]`)."""
    student, mutants = _read("""
        import numpy as np

        def graded(bits, pts, steps, R, d):
            code = int("".join("1" if b else "0" for b in bits))
            cols = pts.reshape(3, -1)
            out = [None] * len(steps)
            chain = np.eye(3)
            for k, step in enumerate(steps):
                chain @= step
                out[k] = chain
            shifted = np.pad(R, ((0, 0), (d, 0)))[:, d:]
            total = 0
            total += code
            return code, cols, out, shifted, total
    """)
    changes = {student.fix(m).changes[0][1:] for m in mutants if student.fix(m) is not None}
    assert any(after.endswith(", 2)") and after.startswith("int(") for _, after in changes), changes
    assert ("pts.reshape(3, -1)", "pts.reshape(-1, 3).T") in changes, changes
    assert ("chain @= step", "chain = chain @ step") in changes, changes
    assert ("np.pad(R, ((0, 0), (d, 0)))[:, d:]", "np.pad(R, ((0, 0), (d, 0)))[:, :-d or None]") in changes, changes
    assert ("total += code", "total = total + code") not in changes, changes   # (kept in no list: not tried)


def test_each_small_whole_number_of_a_call_is_enlarged_alone_among_the_confirmations():
    """`max(2 ** n, width)` mends `min(2 ** n, width)` wherever every width is below 2 ** n (the blind set
    1205e's 12/04, told so before): a confirmation with the width alone made larger turns their order round."""
    made = repair._one_enlarged(("gray_code_patterns", (2, 2), {"scale": 3, "flag": True, "f": 2.0}))
    assert ("gray_code_patterns", (8, 2), {"scale": 3, "flag": True, "f": 2.0}) in made
    assert ("gray_code_patterns", (2, 8), {"scale": 3, "flag": True, "f": 2.0}) in made
    assert ("gray_code_patterns", (2, 2), {"scale": 12, "flag": True, "f": 2.0}) in made
    assert len(made) == 3   # (a flag and a float stay as they are)
    assert repair._one_enlarged(("f", (640, 0), {})) == []   # (large numbers and 0: none)


def test_more_slips_of_the_blind_set_1205e_are_changes_tried():
    """A last column kept 2-D where the flat one belongs (`P[:, 3:]` added to rows), every entry counted
    where the points' count belongs (`pts.size`), a helper's pair kept whole where the module unpacks it,
    a fixed index where the loop's own belongs, an image's whole shape reversed for (width, height)."""
    student, mutants = _read("""
        import numpy as np

        def _points(points):
            X = np.asarray(points, dtype=float)
            return X.reshape(-1, 3), X.ndim == 1

        def other(points):
            X, single = _points(points)
            return X

        def graded(P, points, image):
            X = _points(points)
            Y, _ = _points(points)
            p4 = P[:, 3:]
            z = Y[:, 2].sum() / Y.size
            rows = []
            for i in range(len(Y)):
                rows.append((Y[i, 0], Y[0, 1]))
            return X, Y @ P[:, :3].T + p4, z, rows, image.shape[::-1]
    """, api=("graded", "other"))
    changes = {student.fix(m).changes[0][1:] for m in mutants if student.fix(m) is not None}
    assert ("p4 = P[:, 3:]", "p4 = P[:, 3]") in changes, changes
    assert ("Y[:, 2].sum() / Y.size", "Y[:, 2].sum() / len(Y)") in changes, changes
    assert ("X = _points(points)", "X, _ = _points(points)") in changes, changes
    assert ("(Y[i, 0], Y[0, 1])", "(Y[i, 0], Y[i, 1])") in changes, changes
    assert ("image.shape[::-1]", "image.shape[1::-1]") in changes, changes


def test_a_column_kept_alone_is_tried_where_every_column_from_it_on_is_taken():
    """`-xn[:, 1:] * Xn` of points left homogeneous takes (y, 1) where y alone belongs (the blind set 1205e's
    10/09): `xn[:, 1:2]` is a change tried."""
    student, mutants = _read("""
        import numpy as np

        def graded(xn, Xn):
            return -xn[:, 1:] * Xn
    """)
    changes = {student.fix(m).changes[0][1:] for m in mutants if student.fix(m) is not None}
    assert ("-xn[:, 1:] * Xn", "-xn[:, 1:2] * Xn") in changes, changes


def test_a_formula_given_scaled_copies_where_their_sources_belong_is_a_change_tried():
    """`xr = x * radial` then the tangential terms written with xr, yr (the blind set 1205e's 09/04): the line
    with the sources read is a change; a name assigned twice is no scaled copy."""
    student, mutants = _read("""
        def graded(x, y, k, p):
            radial = 1 + k * (x * x + y * y)
            xr = x * radial
            yr = y * radial
            dx = 2 * p * xr * yr
            z = x * 2
            z = z + 1
            w = z * 3
            return xr + dx, yr, w
    """)
    changes = {student.fix(m).changes[0][1:] for m in mutants if student.fix(m) is not None and m.operator == "source_names"}
    assert ("dx = 2 * p * xr * yr", "dx = 2 * p * x * y") in changes, changes
    assert not any(before.startswith("w =") for before, _ in changes), changes


def test_numpy_slips_of_the_blind_set_1205f_are_changes_tried():
    """`np.tile` where `np.repeat` belongs (a value per point paired in the wrong order) and `math.pow` given an
    array (TypeError) are changes tried; a NumPy call is not made a math one."""
    student, mutants = _read("""
        import math
        import numpy as np

        def graded(fs, r2, n):
            every = np.tile(fs, n)
            radial = 1 + math.pow(r2, 2) + np.sqrt(r2)
            return every, radial
    """)
    changes = {student.fix(m).changes[0][1:] for m in mutants if student.fix(m) is not None}
    assert ("np.tile(fs, n)", "np.repeat(fs, n)") in changes, changes
    assert ("1 + math.pow(r2, 2) + np.sqrt(r2)", "1 + np.power(r2, 2) + np.sqrt(r2)") in changes \
        or ("math.pow(r2, 2)", "np.power(r2, 2)") in changes, changes
    assert not any("math.sqrt" in after for _, after in changes), changes


def test_a_test_of_one_value_where_a_bound_belongs_is_a_change_tried():
    """`rank != 8` where `rank < 8` belongs (the blind set 1205g's 08/03) is a change tried; a comparison of two
    names is not made a bound."""
    student, mutants = _read("""
        import numpy as np

        def graded(A, n, m):
            if np.linalg.matrix_rank(A) != 8:
                raise ValueError("degenerate")
            return n == m
    """)
    changes = {student.fix(m).changes[0][1:] for m in mutants if student.fix(m) is not None and m.operator == "compare"}
    assert ("np.linalg.matrix_rank(A) != 8", "np.linalg.matrix_rank(A) < 8") in changes, changes
    assert not any(before == "n == m" for before, _ in changes), changes


def test_a_conditional_binding_loosest_is_a_change_tried():
    """`f * X / z if z is not None else mean` where the conditional belongs to the last operand (the blind set
    1205g's 10/02) is a change tried: the brackets put round the conditional and its operand."""
    student, mutants = _read("""
        def graded(X, f, z=None):
            return f * X / float(z) if z is not None else X.mean()
    """)
    changes = {student.fix(m).changes[0][1:] for m in mutants if student.fix(m) is not None and m.operator == "precedence"}
    assert ("f * X / float(z) if z is not None else X.mean()",
            "f * X / (float(z) if z is not None else X.mean())") in changes, changes


def test_a_sum_of_squares_named_where_its_root_belongs_is_a_change_tried():
    """`r = x ** 2 + y ** 2` where the radius belongs (the blind set 1205g's 09/05) is a change tried: its root."""
    student, mutants = _read("""
        def graded(x, y, k1):
            r = x ** 2 + y ** 2
            return x * (1 + k1 * r ** 2)
    """)
    changes = {student.fix(m).changes[0][1:] for m in mutants if student.fix(m) is not None and m.operator == "measure"}
    assert ("x ** 2 + y ** 2", "np.sqrt(x ** 2 + y ** 2)") in changes, changes


def test_results_returned_in_another_order_are_told_in_the_order_asked(tmp_path):
    """`return R, t, K` where the API asks (K, R, t): one result moved past the others (cv2.calibrateCamera's
    rms-first order kept) is no exchange of two; the change that puts it back in its place is told."""
    folder = edited_reference(tmp_path, "lab10_camera2", ("    return K / scale, R, t\n", "    return R, t, K / scale\n"))
    result = grade(folder, ["lab10.ex5"], pictures="none", include_hidden=False)
    told = [c for c in check_results(result, "lab10.ex5") if c.mistake.startswith(repair.MISTAKE)]
    assert told, [c.message for c in check_results(result, "lab10.ex5")]
    assert "changing `R, t, K / scale` to `K / scale, R, t`" in told[0].message, told[0].message


def _changes_of(source: str, operator: str) -> set:
    student, mutants = _read(source)
    return {student.fix(m).changes[0][1:] for m in mutants if student.fix(m) is not None and m.operator == operator}


def test_a_matrix_named_from_another_or_from_lstsq_may_be_its_transpose():
    """`L = X` of lstsq's solution (one column per output: the transpose of the linear part) and a matrix taken
    from a linear-algebra call are offered their transpose (the blind set 1206a's 07/02); a name given a number is
    offered one too (it does not confirm), a name given itself is not."""
    changes = _changes_of("""
        def graded(src, dst):
            X, *_ = np.linalg.lstsq(src, dst, rcond=None)
            L = X
            W = np.linalg.lstsq(src, dst, rcond=None)[0]
            return L @ W
    """, "transpose")
    assert ("L = X", "L = X.T") in changes, changes
    assert any(before.endswith("lstsq(src, dst, rcond=None)[0]") and after.endswith("lstsq(src, dst, rcond=None)[0].T")
               for before, after in changes), changes


def test_a_row_written_after_its_names_were_given_the_next_points_values_moves_before_them():
    """`x, y = dst[i]` before the y'-row `M[r] = [0, 0, 0, x, y, 1]` that needs the source point's x, y (the blind
    set 1206a's 07/03): that row moved before the rebinding is a change tried; a name updated from itself is the
    other kind of move, and a name bound only once gives none."""
    changes = _changes_of("""
        def graded(src, dst):
            M, rhs = np.zeros((6, 6)), np.zeros(6)
            for i in range(3):
                x, y = src[i]
                M[2 * i] = [x, y, 1.0, 0.0, 0.0, 0.0]
                x, y = dst[i]
                rhs[2 * i] = x
                rhs[2 * i + 1] = y
                M[2 * i + 1] = [0.0, 0.0, 0.0, x, y, 1.0]
            return np.linalg.solve(M, rhs)
    """, "move")
    assert any(before == "M[2 * i + 1] = [0.0, 0.0, 0.0, x, y, 1.0]" and "before line" in after for before, after in changes), changes


def test_an_entrywise_reciprocal_where_the_inverse_belongs_is_a_change_tried():
    """`M ** -1` and `1 / M` (the sheet's M^-1 written entry by entry: the blind set 1206a's 10/06) are offered
    np.linalg.inv; a power of -2 is not."""
    changes = _changes_of("""
        def graded(M, N):
            return np.linalg.qr(M ** -1)[1] + 1 / N + M ** -2
    """, "inverse")
    afters = {after for _, after in changes}
    assert "np.linalg.qr(np.linalg.inv(M))[1]" in afters or any("np.linalg.inv(M)" in a for a in afters), changes
    assert any("np.linalg.inv(N)" in a for a in afters), changes
    assert not any("np.linalg.inv(M) ** " in a or "inv(M ** -2)" in a for a in afters), changes


def test_narrow_integers_and_an_images_dtype_for_coordinates_are_offered_int64():
    """Column indices in uint16 (`u * 2 ** n` wraps past 65535: the blind set 1206a's 12/04) and pixel coordinates
    counted in the image's dtype (uint8: 255 + 1 is 0, 07/05) are offered int64; an int64 array is not."""
    changes = _changes_of("""
        def graded(image, width):
            u = np.arange(width, dtype=np.uint16)
            xs = np.arange(image.shape[1], dtype=image.dtype)
            k = np.arange(width, dtype=np.int64)
            return u, xs, k
    """, "dtype")
    assert ("np.arange(width, dtype=np.uint16)", "np.arange(width, dtype=np.int64)") in changes, changes
    assert ("np.arange(image.shape[1], dtype=image.dtype)", "np.arange(image.shape[1], dtype=np.int64)") in changes
    assert not any(before.startswith("np.arange(width, dtype=np.int64)") and "int64" in after
                   for before, after in changes), changes


def test_a_stack_regrouped_by_reshape_and_a_loop_over_unique_items_are_changes_tried():
    """`rows.reshape(n, 4, 4)` of a (4, n, 4) stack (the blind set 1206a's 11/01) is offered the transpose of its
    first two axes; a loop over `np.unique(points, axis=0)` (11/02) is offered the points themselves."""
    source = """
        def graded(rows, points, n):
            A = rows.reshape(n, 4, 4)
            out = []
            for x, y in np.unique(points, axis=0):
                out.append(x + y)
            return A, out
    """
    assert ("rows.reshape(n, 4, 4)", "rows.reshape(4, n, 4).transpose(1, 0, 2)") in _changes_of(source, "reshape_order")
    assert ("np.unique(points, axis=0)", "points") in _changes_of(source, "unwrap")


def test_a_filter_given_a_stack_the_def_made_is_applied_to_each_image():
    """`cv2.blur(costs, (k, k))` and a helper `_box(costs, k)` of a (D, H, W) volume the def made with np.zeros
    (the blind set 1206a's 12/03: OpenCV reads the last axis as channels) are offered one call per image; a
    filter of an image given as a parameter is not."""
    changes = _changes_of("""
        def graded(left, k):
            costs = np.zeros((8, 20, 30))
            a = cv2.blur(costs, (k, k))
            b = _box(costs, k)
            c = cv2.blur(left, (k, k))
            return a + b, c
    """, "per_image")
    afters = {after for _, after in changes}
    assert "np.stack([cv2.blur(_image, (k, k)) for _image in costs])" in afters, changes
    assert "np.stack([_box(_image, k) for _image in costs])" in afters, changes
    assert not any("for _image in left" in after for after in afters), changes


def test_an_identity_given_to_opencv_is_offered_the_matrices_the_function_is_given():
    """`np.eye(3)` as initUndistortRectifyMap's new camera matrix (the blind set 1206a's 10/02) is offered K, a
    parameter the call is given; an identity outside an OpenCV call is not."""
    changes = _changes_of("""
        def graded(image, K, dist):
            h, w = image.shape[:2]
            maps = cv2.initUndistortRectifyMap(K, dist, None, np.eye(3), (w, h), cv2.CV_32FC1)
            return maps, np.eye(3)
    """, "other_name")
    assert any("np.eye(3)" in before and after.endswith("K, (w, h), cv2.CV_32FC1)") or (before, after) == ("np.eye(3)", "K")
               for before, after in changes), changes
    assert ("(maps, np.eye(3))", "(maps, K)") not in changes, changes


def test_a_negated_all_where_any_belongs_is_a_change_tried():
    """`~np.all(bits, axis=0)` for the pixels lit in some image (the blind set 1206b's 12/06: De Morgan's rule half
    applied) is offered `np.any(bits, axis=0)`, and `not x.any()` is offered `x.all()`; an all() not negated is not."""
    changes = _changes_of("""
        def graded(bits, x):
            decodable = ~np.all(bits, axis=0)
            empty = not x.any()
            full = np.all(bits)
            return decodable, empty, full
    """, "flip_reduction")
    assert ("~np.all(bits, axis=0)", "np.any(bits, axis=0)") in changes, changes
    assert ("empty = not x.any()", "empty = x.all()") in changes, changes
    assert not any(before == "np.all(bits)" for before, _ in changes), changes


def test_a_row_dividing_an_array_of_rows_is_offered_each_rows_own_column():
    """`x / x[-1]` on points in rows (the column-vector habit: the last point's row divides every point) is
    offered `x[:, -1:]`, each point's own w kept as a column; and that change is no renormalisation of `x` by
    another of its own entries (a divisor made a column changes more than the scale)."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(P, X):
            x = np.hstack([X, np.ones((len(X), 1))]) @ P.T
            x = x / x[-1]
            return x[:, :2]
    """)
    changes = [m for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator == "keep_axis"]
    assert [m.edits[0][3] for m in changes] == ["x[:, -1:]"]
    from autograder.loading.parsing import parse
    student = repair._Student(source, parse(source), ["graded(P, X)"])
    assert not student.renormalises(changes[0])


def test_a_names_other_variant_of_one_stem_is_tried_among_the_first():
    """`z_mean` where `z_avg` belongs (two variants of one word, `z`): among the few names tried at the place,
    however many other locals there are."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(points, f, z_avg=None):
            pts = np.atleast_2d(np.asarray(points, dtype=np.float64))
            X, Y, Z = pts[:, 0], pts[:, 1], pts[:, 2]
            z_mean = Z.mean()
            if z_avg is None:
                z_avg = z_mean
            x = f * X / z_avg
            y = f * Y / z_mean
            return np.column_stack([x, y])
    """)
    offered = {m.edits[0][3] for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
               if m.operator == "other_name" and m.line == 11}
    assert "z_avg" in offered


def test_a_calls_two_arguments_alike_but_for_a_size_twin_are_twins():
    """`np.meshgrid(np.arange(h), np.arange(w))` exchanged is a twin exchange (a grid made rows first), tried
    first where the answer's rows and columns are exchanged; two unlike arguments are not."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(image, k):
            h, w = image.shape[:2]
            u, v = np.meshgrid(np.arange(h), np.arange(w))
            return np.maximum(image, k) + u + v
    """)
    from autograder.loading.parsing import parse
    student = repair._Student(source, parse(source), ["graded(image, k)"])
    swaps = [m for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"] if m.operator == "swap_args"]
    told = {str(student.fix(m).changes): student.twin_items(m) for m in swaps if student.fix(m) is not None}
    assert any(twin for text, twin in told.items() if "meshgrid" in text)
    assert not any(twin for text, twin in told.items() if "maximum" in text)


def test_items_numbered_from_one_are_offered_their_index_from_zero():
    """`for i, frame in enumerate(frames, start=1)` writing row `i` (the blind set 1206b's 10/04): the numbering
    from 0 is offered; an enumerate from 0 is offered nothing of the kind."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(frames):
            out = np.full((len(frames), 2), np.nan)
            for i, frame in enumerate(frames, start=1):
                out[i] = frame
            return out
    """)
    offered = {m.edits[0][3] for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
               if m.operator == "zero_based"}
    assert "enumerate(frames)" in offered
    plain = source.replace("enumerate(frames, start=1)", "enumerate(frames)")
    assert not any(m.operator == "zero_based" for m in repair.mutants_of(plain, {"graded"}, phrased=False)["graded"])


def test_a_squeeze_is_offered_its_array_as_made():
    """`np.stack(...).squeeze()` (the blind set 1206d's 10/06): every length-1 axis dropped, those the API keeps
    too; the array as made is offered."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(parts):
            return np.stack(parts).squeeze()
    """)
    changes = [m for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
               if m.operator == "unwrap" and m.edits[0][3] == "method"]
    assert changes


def test_a_calibration_option_is_offered_its_removal_not_another_option():
    """`flags=cv2.CALIB_FIX_PRINCIPAL_POINT` (the blind set 1206d's 09/06): calibrateCamera's CALIB_ options are
    independent restrictions -- taken out, not swapped for another (CALIB_ZERO_TANGENT_DIST mends only where the
    lens has no tangential distortion)."""
    source = textwrap.dedent("""
        import cv2

        def graded(obj, img, size):
            return cv2.calibrateCamera(obj, img, size, None, None, flags=cv2.CALIB_FIX_PRINCIPAL_POINT)
    """)
    changes = {(m.operator, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]}
    assert ("drop_keyword", "flags") in changes
    assert not any(operator == "flag" and str(payload).startswith("CALIB_") for operator, payload in changes)


def test_a_check_replayed_says_nothing_of_a_change_when_the_repairs_time_stops_a_call():
    """A replay cut short by the repairs' own clock is no failure of the check: a slow function's change,
    right, is not refuted by a grading's other check for want of time (a Python scanline DP)."""
    from types import SimpleNamespace

    from autograder.sandbox.supervisor import CallOutcome

    def replayed(wall_left: float):
        companion = SimpleNamespace(call_variant=lambda *a, **k: CallOutcome(ok=False, kind="timeout", message="slow"))
        variants = SimpleNamespace(companion=companion, clock=SimpleNamespace(wall_left=lambda: wall_left),
                                   trial=SimpleNamespace(sandbox=None))
        return repair._Replayed(variants, "def f(): pass")

    short = replayed(0.5)
    short.call("m", "f", (), timeout=30.0)
    assert short.cut_short   # (stopped at the 0.5 s the repairs had left, not at the check's 30)
    own_limit = replayed(60.0)
    own_limit.call("m", "f", (), timeout=30.0)
    assert not own_limit.cut_short   # (the check's own limit: the variant is as slow as that, a failure)


_MOVED = {"dedent", "move", "indent", "hoist", "simultaneous"}


def test_a_statement_moved_out_of_a_branch_the_failing_input_skips_is_run_where_the_branch_is():
    """The float conversion written in the colour branch only (the blind set 2026-12-06h's 12/05): a grey input
    never enters the `if`, yet moving its last statement out of it changes what that input runs."""
    student, mutants = _read("""
        import numpy as np

        def graded(left, right):
            left, right = np.asarray(left), np.asarray(right)
            if left.ndim == 3:
                left = left.mean(axis=2)
                right = right.mean(axis=2)
                right = right.astype(np.float64)
            return np.abs(left - right)
    """)
    out = [m for m in mutants if m.operator == "dedent"]
    assert out, [m.operator for m in mutants]
    ran = {5, 6, 11}   # (the grey input's lines: the assignment, the test, the return)
    assert all(student.runs(m, ran) for m in out)
    inside = [m for m in mutants if m.operator not in _MOVED and student.fix(m) is not None
              and student.fix(m).changes[0][0] in (7, 8, 9)]
    assert inside and not any(student.runs(m, ran) for m in inside)   # (a change inside the branch still is not run)


def test_a_conversion_the_code_makes_is_not_said_missing():
    """'the result of `cv2.cvtColor` is not converted to float' is false of code converting it (06h 12/05)."""
    from autograder.engine.mutants import naming

    def fn(text):
        return ast.parse(textwrap.dedent(text)).body[0]

    converts = fn("""
        def f(img):
            grey = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
            grey = grey.astype(np.float64)
            return grey
    """)
    wraps = fn("""
        def f(img):
            return np.float32(cv2.cvtColor(img, cv2.COLOR_BGR2GRAY))
    """)
    keeps = fn("""
        def f(img):
            grey = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
            return grey.astype(np.uint8) - 1
    """)
    assert naming._converts_result_of(converts, "cvtColor") and naming._converts_result_of(wraps, "cvtColor")
    assert not naming._converts_result_of(keeps, "cvtColor")


@pytest.mark.parametrize("text, converts", [
    ("left, right = _grey_float(left), _grey_float(right)", True),      # a helper of the student's returning float
    ("left = left.astype(np.float32)", True),
    ("cost = np.zeros((h, w), dtype=np.float64)", True),
    ("left = np.float32(left)", True),
    ("left = cv2.cvtColor(left, cv2.COLOR_BGR2GRAY)", False),
    ("e2 /= np.linalg.norm(e2)", False),
    ("left = _grey(left)", False),                                      # a helper that keeps the dtype
])
def test_a_step_added_is_said_to_make_floats_only_where_it_does(text, converts):
    defs = {fn.name: fn for fn in ast.parse(textwrap.dedent("""
        def _grey_float(image):
            image = np.asarray(image)
            return image.astype(np.float64)
        def _grey(image):
            return cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
    """)).body}
    assert repair._makes_float(text, defs) is converts


def test_a_float_conversion_missing_from_a_dp_is_told_with_why_it_mends(tmp_path):
    # (06i 12/03: the repair's step `left, right = (_grey_float(left), _grey_float(right))` was the only name of
    # uint8 differences wrapping around)
    from autograder.labs.mistakes import reference_def_with

    source = reference_def_with("lab12_stereo", "dp_stereo", "left, right = _grey_float(left), _grey_float(right)",
                                "if left.ndim == 3:\n    left = cv2.cvtColor(left, cv2.COLOR_BGR2GRAY)\n"
                                "if right.ndim == 3:\n    right = cv2.cvtColor(right, cv2.COLOR_BGR2GRAY)")
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ex5"], pictures="none", include_hidden=False)
    messages = [c.message for c in check_results(result, "lab12.ex5") if c.score < c.max_score]
    assert any("adding the step" in m and "_grey_float(left)" in m and "wraps around" in m for m in messages), messages


@pytest.mark.parametrize("shown, code, told", [
    # (06k 10/06: pattern_size reversed for the corner search alone)
    ((3, "tuple(pattern_size)[::-1]", "tuple(pattern_size)"),
     "found, corners = cv2.findChessboardCorners(grey, tuple(pattern_size)[::-1])", "(columns, rows)"),
    ((3, "(h, w)", "(w, h)"), "return cv2.warpAffine(image, M, (h, w))", "(width, height)"),
    ((3, "(h, w)", "(w, h)"), "return np.zeros((h, w))", ""),             # (no OpenCV call reads the pair)
    # (a whole statement shown: the pair its names make, or the name it binds, is what the call reads)
    ((3, "w, h = image.shape[:2]", "h, w = image.shape[:2]"), "return cv2.warpAffine(image, M, (w, h))",
     "(width, height)"),
    ((3, "size = (h, w)", "size = (w, h)"), "return cv2.resize(image, size)", "(width, height)"),
    ((3, "pattern = pattern_size[::-1]", "pattern = pattern_size"),
     "found, corners = cv2.findChessboardCorners(grey, pattern)", "(columns, rows)"),
    ((3, "w, h = image.shape[:2]", "h, w = image.shape[:2]"), "return np.zeros((h, w))", ""),
    ((3, "size = (h, w)", "size = (w, h)"), "return cv2.resize(image, (h, w))", ""),   # (the call reads not `size`)
    ((3, "a, b = x, y", "b, a = x, y"), "return cv2.resize(image, (w, h))", ""),      # (another pair)
])
def test_a_pair_an_opencv_call_reads_in_its_own_order_is_told_why(shown, code, told):
    fn = ast.parse(f"def f(grey, image, M, pattern_size, h, w):\n    {code}\n").body[0]
    why = repair._why_it_mends([shown], fn)
    assert (told in why) if told else why == "", why


@pytest.mark.parametrize("shown, code, told", [
    ((3, "Vt[:, -1]", "Vt[-1, :]"), "U, S, Vt = np.linalg.svd(A)", "V transposed"),
    ((3, "np.linalg.svd(P)[2][:, -1]", "np.linalg.svd(P)[2][-1]"), "", "V transposed"),
    ((3, "U[-1]", "U[:, -1]"), "U, S, Vt = np.linalg.svd(A)", "a column of it"),
    ((3, "V[:, -1]", "V[-1, :]"), "V = A.T @ A", "is row -1 of `V`"),   # (no svd behind it: NumPy's rows and columns)
    ((3, "np.mean(pts[2])", "np.mean(pts[:, 2])"), "", "`pts[2]` is row 2"),   # (06j 10/01: the index inside a call)
    ((3, "pts[2]", "pts[:, 2]"), "", "`pts[2]` is row 2 of `pts`, `pts[:, 2]` its column"),
    ((3, "pts.mean(axis=1)", "pts.mean(axis=0)"), "", "one value per column"),
    ((3, "pts.mean(axis=1)", "pts.sum(axis=0)"), "", ""),                # (more than the axis changed)
    ((3, "Vt[:, 0]", "Vt[-1, :]"), "U, S, Vt = np.linalg.svd(A)", ""),   # (another index: not the transpose)
    # (a whole statement shown: 06l 08/02 was told "`h = Vt[-1]` is row -1 of `h = Vt`")
    ((3, "h = Vt[:, -1]", "h = Vt[-1, :]"), "U, S, Vt = np.linalg.svd(A)", "V transposed"),
    ((3, "c = pts[:, 2]", "c = pts[2]"), "", "`pts[2]` is row 2 of `pts`, `pts[:, 2]` its column"),
])
def test_a_column_taken_for_a_row_of_svd_is_told_why(shown, code, told):
    fn = ast.parse(f"def f(A, P):\n    {code or 'pass'}\n    return 0\n").body[0]
    why = repair._why_it_mends([shown], fn)
    assert (told in why) if told else why == "", why


def test_a_number_made_a_python_float_is_not_said_to_make_arrays_float():
    assert not repair._makes_float("n = float(n)", {})
    assert repair._makes_float("image = image.astype(float)", {})


def test_a_fix_given_to_one_factor_of_a_pair_is_a_change_made_to_both():
    """`K, R = rq(M)` then `K = K @ D` alone (the sign fix on K's columns, R's rows left): K @ R is no longer M;
    the change gives R the fix's inverse on its other side. Not offered where R is given a value again."""
    source = textwrap.dedent("""
        import numpy as np
        import scipy.linalg
        def graded(M):
            K, R = scipy.linalg.rq(M)
            D = np.diag(np.sign(np.diag(K)))
            K = K @ D
            return K, R
    """)
    changes = _shown_changes(source, "factor_pair")
    assert ("K = K @ D", "K, R = (K @ D, D @ R)") in changes, changes
    fixed = source.replace("    K = K @ D\n", "    K = K @ D\n    R = D @ R\n")
    assert fixed != source
    assert _shown_changes(fixed, "factor_pair") == []
    # (factors made each from one of a pair unpacked together: K = inv(U), R = Q.T of Q, U = qr(inv(M)))
    through_qr = textwrap.dedent("""
        import numpy as np
        def graded(M):
            Q, U = np.linalg.qr(np.linalg.inv(M))
            K = np.linalg.inv(U)
            R = Q.T
            D = np.diag(np.sign(np.diag(K)))
            K = K @ D
            return K, R
    """)
    assert ("K = K @ D", "K, R = (K @ D, D @ R)") in _shown_changes(through_qr, "factor_pair")


def test_a_sign_fix_made_to_k_alone_is_named_with_the_change_that_gives_r_its_rows(tmp_path):
    folder = mutant(tmp_path, "lab10_camera2", """
        import scipy.linalg

        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=float)
            if np.linalg.det(P[:, :3]) < 0:
                P = -P
            K, R = scipy.linalg.rq(P[:, :3])
            D = np.diag(np.sign(np.diag(K)))
            K = K @ D
            t = np.linalg.inv(K) @ P[:, 3]
            return K / K[2, 2], R, t
    """)
    result = grade(folder, ["lab10.ex5"], pictures="none", include_hidden=False)
    failed = [c for c in check_results(result, "lab10.ex5") if c.score < c.max_score]
    assert failed and any("`K = K @ D` to `K, R = (K @ D, D @ R)`" in c.message for c in failed), \
        [c.message for c in failed]


def test_a_copy_a_loop_changes_in_place_is_made_anew_at_each_turn():
    """`moved = X.copy()` above a loop shifting `moved[:, 2] += d` and projecting it: the shifts add up from one
    turn to the next; the copy moved into the loop as its first statement. A copy the loop only reads is left."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(X, distances):
            out = []
            moved = X.copy()
            for d in distances:
                moved[:, 2] += d
                out.append(moved[:, :2] / moved[:, 2:3])
            kept = X.copy()
            for d in distances:
                out.append(kept * d)
            return out
    """)
    changes = _shown_changes(source, "indent")
    assert any(before == "moved = X.copy()" and "first statement: a new one for each turn" in after
               for before, after in changes), changes
    assert not any(before == "kept = X.copy()" for before, _ in changes), changes


def test_a_call_given_every_point_is_offered_the_points_a_mask_keeps():
    """A refit after a RANSAC loop given `(src, dst)` whole, in code that selects `src[inliers]` elsewhere: the call
    given the arrays selected by the mask bound last above it (`best`), then the others; a call already given
    selected arrays, or given arrays nothing selects, is left."""
    source = textwrap.dedent("""
        import numpy as np
        def fit(a, b):
            return a.mean() + b.mean()
        def graded(src, dst, other, rng):
            best = np.zeros(len(src), dtype=bool)
            for _ in range(10):
                idx = rng.choice(len(src), 4)
                inliers = np.abs(src[idx].sum() - dst) < 1
                if inliers.sum() > best.sum():
                    best = inliers
            H = fit(src, dst)
            G = fit(src[best], dst[best])
            F = fit(other, other)
            return H, G, F, fit(src[inliers], dst[inliers])
    """)
    changes = _shown_changes(source, "select_mask")
    assert changes[0] == ("fit(src, dst)", "fit(src[best], dst[best])"), changes
    assert ("fit(src, dst)", "fit(src[inliers], dst[inliers])") in changes
    assert not any(before.startswith(("fit(src[", "fit(other")) for before, _ in changes), changes


def test_a_raw_input_read_where_a_value_made_from_it_belongs_is_offered_the_last_made_first():
    """`w = pts[:, 2]` (the world points' Z) where the projected points' third coordinate belongs: the values made
    from `pts` since -- `Xh`, then `x = P @ Xh`, made from it through `Xh` -- are offered in its place, the last
    made first; a name given a value of another making since is not one of them."""
    source = textwrap.dedent("""
        import numpy as np
        def graded(P, points):
            pts = np.atleast_2d(points)
            Xh = np.hstack([pts, np.ones((len(pts), 1))])
            x = (P @ Xh.T).T
            Xh = np.eye(4)
            w = pts[:, 2]
            return x[:, :2] / w[:, None]
    """)
    offered = [after for before, after in _shown_changes(source, "other_name") if before == "w = pts[:, 2]"]
    assert offered[0] == "w = x[:, 2]", offered
    assert "w = Xh[:, 2]" not in offered[:1]


INVERSE_FLAGGED_SHEAR = '''
def shear(image, s=0.5):
    h, w = image.shape[:2]
    M = np.float32([[1, s, 0],
                    [0, 1, 0]])
    return cv2.warpAffine(image, M, (w, h), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP,
                          borderMode=cv2.BORDER_CONSTANT, borderValue=0)
'''


def test_a_flag_the_reference_never_passes_is_told_taken_out_not_the_sign_that_compensates_for_it(tmp_path):
    """WARP_INVERSE_MAP with a shear's forward matrix: `s` -> `-s` mends exactly too (the inverse of a shear is the
    opposite shear), upstream of the flag; the flag no reference function passes is the slip (07e lab07/05)."""
    result = grade(str(mutant(tmp_path, "lab07_transformations", INVERSE_FLAGGED_SHEAR)), ["lab07.ex4"], pictures="none")
    failed = [c for c in check_results(result, "lab07.ex4") if c.score < c.max_score]
    assert failed and any("`cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP` to `cv2.INTER_LINEAR`" in c.message for c in failed), \
        [c.message for c in failed]
    assert not any("`[1, -s, 0]`" in c.message for c in failed), [c.message for c in failed]


def test_a_divisor_rounded_before_it_divides_is_offered_the_division_last():
    """`u // (width // 2 ** n)` (a stripe's width rounded first: wrong wherever 2 ** n does not divide the width,
    blind set 08a lab12/06) is offered `u * 2 ** n // width`; a single floor division is not regrouped."""
    source = textwrap.dedent("""
        def graded(u, width, n):
            return u // (width // 2 ** n), u // width
    """)
    changes = [(m.operator, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]]
    assert changes.count(("regroup", "divisor_rounded")) == 1, changes
    student = repair._Student(source, parse(source), frozenset({"graded"}))
    told = [student.fix(m).changes[0][2] for m in student.ordered("graded") if m.operator == "regroup"]
    assert "u * 2 ** n // width" in told, told


def test_a_line_unlike_its_siblings_is_offered_as_they_are_written():
    """The mask's pyramid made by a nearest-neighbour resize beside two images' pyrDown (blind set 08a lab08/08):
    the line written as its two siblings are, in its own name; a line beside a single other line is not."""
    source = textwrap.dedent("""
        import cv2

        def graded(A, B, M, levels):
            gA, gB, gM = [A], [B], [M]
            for i in range(levels - 1):
                gA.append(cv2.pyrDown(gA[-1]))
                gB.append(cv2.pyrDown(gB[-1]))
                gM.append(cv2.resize(gM[-1], (gA[-1].shape[1], gA[-1].shape[0]), interpolation=cv2.INTER_NEAREST))
            for i in range(levels - 1):
                gA.append(cv2.pyrUp(gA[-1]))
                gM.append(cv2.resize(gM[-1], None, fx=2, fy=2))
            return gA, gB, gM
    """)
    student = repair._Student(source, parse(source), frozenset({"graded"}))
    told = [student.fix(m).changes[0] for m in student.ordered("graded") if m.operator == "sibling_line"]
    assert [(line, after) for line, _, after in told] == [(9, "gM.append(cv2.pyrDown(gM[-1]))")], told


def test_a_names_twin_is_offered_beyond_the_nearer_values():
    """`w` in an else-branch below four values the if-branch made from it (blind set 08b lab11/03, `y0, y1 = 0.0,
    w - 1.0` where `h - 1.0` belongs): its twin `h` is offered all the same."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(image, lines):
            out = image.copy()
            h, w = out.shape[:2]
            lines = np.asarray(lines, dtype=float).reshape(-1, 3)
            for i, (a, b, c) in enumerate(lines):
                if abs(b) >= abs(a):
                    x0, x1 = 0.0, w - 1.0
                    y0 = -(a * x0 + c) / b
                    y1 = -(a * x1 + c) / b
                else:
                    y0, y1 = 0.0, w - 1.0
                    x0 = -(b * y0 + c) / a
                    x1 = -(b * y1 + c) / a
                pt0 = _to_int((x0, y0), w, h)
                pt1 = _to_int((x1, y1), w, h)
                colour = (0, 0, 255) if out.ndim == 3 else 255
                cv2.line(out, pt0, pt1, colour, 1)
            return out

        def _to_int(point, width, height):
            return tuple(int(round(v)) for v in point)
    """)
    offered = [(m.line, m.edits[0][3]) for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
               if m.operator == "other_name" and m.line == 14]
    assert (14, "h") in offered, offered


def test_twins_deeper_in_a_list_of_columns_are_exchanged_throughout_it():
    """`np.column_stack([x1[:, 0:1] * x2, ...])` (the rows kron(x1, x2) where kron(x2, x1) belongs, blind set 08c
    lab11/06): x1 and x2 are the formula's, not items of the list, and are exchanged throughout it; `(h, w)`, names
    that are the items themselves, stay swap_items'."""
    source = textwrap.dedent("""
        import numpy as np

        def graded(x1, x2, h, w):
            A = np.column_stack([x1[:, 0:1] * x2, x1[:, 1:2] * x2, x1[:, 2:3] * x2])
            size = np.zeros((h, w))
            return A, size
    """)
    crossed = {m.edits[0][3] for m in repair.mutants_of(source, {"graded"}, phrased=False)["graded"]
               if m.operator == "crossed"}
    assert "np.column_stack([x2[:, 0:1] * x1, x2[:, 1:2] * x1, x2[:, 2:3] * x1])" in crossed, crossed
    assert not any("(w, h)" in text for text in crossed), crossed


@pytest.mark.parametrize("before, after, written", [
    ("pano = total / 2.0", "pano = total / 1.0", True),    # (blind set 08d lab08/07: a sum left undivided)
    ("s = (S[0] + S[1]) // 2", "s = (S[0] + S[1]) // 1", True),
    ("x = a - 1", "x = a - 0", True),
    ("x = 2 * a", "x = 1 * a", True),
    ("pano = total / 2.0", "pano = total / count", False),
    ("x = a / 1.0", "x = b / 1.0", False),                 # (already written so: not the change's)
])
def test_a_change_writing_a_neutral_operand_is_no_repair(before, after, written):
    """`total / 2.0` -> `total / 1.0`: code nobody writes, mending by accident where it mends; never told."""
    from types import SimpleNamespace

    assert repair._neutral_operand_written(SimpleNamespace(changes=((1, before, after),))) == written
