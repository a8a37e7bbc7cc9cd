"""A parameter the failing check gave a value and the student's function never reads is named
(issue 35: "returned shape (120, 160, 3); expected (100, 220, 3)" located a dsize left unused
without its cause). The body is read, never run; only a value the check chose counts."""

from __future__ import annotations

import textwrap

import pytest

from autograder.engine.hints import read_code
from autograder.engine.ignored import MISTAKE, never_read, unused_given
from autograder.engine.runner import grade
from conftest import check_results, edited_reference, mutant


def code(source: str):
    return read_code(textwrap.dedent(source))


def test_a_parameter_never_loaded_is_found_and_one_read_anywhere_is_not():
    fn = code("""
        def f(image, A, dsize=None, center=None, scale=1.0):
            helper = lambda: scale * 2
            h, w = image.shape[:2]
            return cv2.warpAffine(image, A, (w, h)), helper()
        """).functions["f"]
    assert never_read(fn) == {"dsize", "center"}


def test_a_parameter_read_only_to_convert_it_into_itself_is_never_read():
    """`P1 = np.asarray(P1, float)` (alone or in a tuple of conversions) and no other read: the converted value
    goes unused, and so does the parameter; one read after its conversion, or converted into another name, is read."""
    fn = code("""
        def f(P1, P2, pts1, pts2, K):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            P1 = np.asarray(P1, float)
            pts1 = np.asarray(pts1)
            K_inv = np.linalg.inv(K)
            return P2 @ pts2, pts1, K_inv
        """).functions["f"]
    assert never_read(fn) == {"P1"}


def test_a_function_reading_locals_is_not_judged():
    fn = code("""
        def f(image, dsize=None):
            return g(**locals())
        """).functions["f"]
    assert never_read(fn) == set()


@pytest.mark.parametrize("call, found", [
    (("f", ("img", "A"), {"dsize": (220, 100)}), ("f", "dsize", (220, 100))),
    (("f", ("img", "A", (220, 100)), {}), ("f", "dsize", (220, 100))),    # positionally
    (("f", ("img", "A"), {}), None),                                        # the default: nothing chosen
    (("f", ("img", "A"), {"dsize": None}), None),                           # None: nothing given
    (("f", ("img", "A"), {"seed": 3}), None),                               # randomness: its own checks
])
def test_only_a_value_the_check_gave_names_it(call, found):
    source = code("""
        def f(image, A, dsize=None, seed=None):
            return image @ A
        """)
    assert unused_given(source, [call + ("answer",)]) == found


def test_the_literal_default_given_again_names_nothing():
    source = code("""
        def f(points, f=1.0, z_avg=10.0):
            return points * f
        """)
    assert unused_given(source, [("f", ([1.0],), {"z_avg": 10.0}, None)]) is None
    assert unused_given(source, [("f", ([1.0],), {"z_avg": 12.0}, None)]) == ("f", "z_avg", 12.0)


def test_a_warp_that_ignores_dsize_is_named_in_grading(tmp_path):
    source = """
        def warp_affine(image, A, dsize=None):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, np.asarray(A, float)[:2], (w, h))
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex5"], pictures="none")
    named = [c for c in check_results(result, "lab07.ex5") if c.mistake == MISTAKE]
    assert named and all("never uses its parameter `dsize`" in c.message for c in named), \
        [c.message for c in check_results(result, "lab07.ex5") if not c.passed]


# ------------------------------------------------------------------ a value computed, never read
@pytest.mark.parametrize("body, found", [
    ("c1 = corners(a)\n    c2 = corners(b)\n    return box(c2)", ("graded", "c1", 2)),   # a step left out
    ("h, w = a.shape\n    return a[:h]", None),          # one name of a tuple unpacked: no step missing
    ("scale = 1.0\n    return a", None),                # a constant: no computation left unused
    ("_ = setup(a)\n    return a", None),               # marked unused on purpose
    ("c = corners(a)\n    return [c for _ in b]", None),  # read in a comprehension
    ("c = corners(a)\n    return eval('c')", None),      # read in ways a reading cannot follow
])
def test_a_value_computed_and_never_read_is_found(body, found):
    from autograder.engine.ignored import computed_unused

    code = read_code(f"def graded(a, b):\n    {body}\n")
    assert computed_unused(code, ["graded"]) == found


def test_a_value_computed_and_never_read_is_told_where_nothing_else_names_the_failure(tmp_path):
    from autograder.engine.ignored import UNUSED_VALUE

    folder = mutant(tmp_path, "lab09_camera", """
        def pinhole_project(points, f):
            pts = np.asarray(points, dtype=np.float64)
            depth = pts[..., 2:3]
            return f * pts[..., :2]
        """)
    result = grade(folder, ["lab09.ex1"], pictures="none", include_hidden=False)
    told = [c for c in check_results(result, "lab09.ex1") if c.mistake == UNUSED_VALUE]
    assert told and "computes `depth` (line" in told[0].message, \
        [(c.mistake, c.message) for c in check_results(result, "lab09.ex1")]


def test_a_parameter_that_reaches_a_use_flows_and_one_passed_only_to_a_helper_that_ignores_it_does_not():
    from autograder.engine.hints import parameter_flows

    source = code("""
        def ransac(src, dst, threshold=3.0):
            inliers = errors(src, dst) < threshold
            return inliers
        def fixed(src, dst, threshold=3.0):
            return _count(src, dst, threshold)
        def _count(src, dst, limit):
            return (errors(src, dst) < 1.0).sum()
        def passed_on(src, dst, threshold=3.0):
            return _count2(src, dst, limit=threshold)
        def _count2(src, dst, limit):
            return (errors(src, dst) < limit).sum()
        def converted(src, dst, threshold=3.0):
            return _count(src, dst, int(threshold))
        def overwritten(src, dst, threshold=3.0):
            threshold = 1.0
            return errors(src, dst) < threshold
        """)
    assert parameter_flows(source, "ransac", "threshold")
    assert not parameter_flows(source, "fixed", "threshold")
    assert parameter_flows(source, "passed_on", "threshold")
    assert not parameter_flows(source, "overwritten", "threshold")
    assert not parameter_flows(source, "converted", "threshold")   # (int() on the way to a helper ignoring it)


def test_a_threshold_the_code_uses_that_changes_nothing_on_the_input_is_not_named_ignored(tmp_path):
    # the blind set's RANSAC keeping the sample with the FEWEST inliers (a 4-point sample fits itself at any
    # threshold): 1 px and 20 px give the same H, yet the code uses its threshold -- "ignored" would be false
    submission = edited_reference(tmp_path, "lab08_homographies",
                                  ("np.lexsort((spread, -counts))[0]", "np.lexsort((spread, counts))[0]"))
    failed = [c for c in check_results(grade(submission, ["lab08.ex4"]), "lab08.ex4") if c.score < c.max_score]
    assert failed and not any("threshold is ignored" in c.message or c.mistake == "threshold is ignored"
                              for c in failed)
    # (nor told that its threshold "decides nothing": that sent the student to the right comparison --
    # the blind set 1202i's 08/05, whose sample count was the slip; the check's own diagnoses speak)
    assert not any("decides nothing" in c.message for c in failed)
