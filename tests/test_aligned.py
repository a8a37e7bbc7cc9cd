"""Statements written as the reference's but for a slip, made their counterparts again (aligned.py)."""

import ast
from pathlib import Path

import pytest

from autograder.engine.mutants.aligned import SHOWN, aligned_changes, aligned_mutants
from autograder.engine.mutants.operators import _defs, apply_edits

REFERENCE = '''
import numpy as np

def project(points, K):
    homogeneous = np.hstack([points, np.ones((len(points), 1))])
    mapped = homogeneous @ K.T
    mapped = mapped / mapped[:, 2:3]
    return mapped[:, :2]
'''

ROOT = Path(__file__).resolve().parents[1]


def _changed(student: str, function: str = "project") -> list[str]:
    """The student's def after each aligned change, as code."""
    tree, reference = ast.parse(student), ast.parse(REFERENCE)
    return [ast.unparse(_defs(ast.parse(apply_edits(student, m.edits)))[function])
            for m in aligned_mutants(tree, reference, function)]


def _reference_def(function: str = "project") -> str:
    return ast.unparse(_defs(ast.parse(REFERENCE))[function])


def test_one_expression_slip_is_made_the_counterparts():
    student = REFERENCE.replace("homogeneous @ K.T", "homogeneous @ K")
    assert _reference_def() in _changed(student)


def test_a_slip_at_two_places_of_one_statement_is_one_change():
    student = REFERENCE.replace("mapped / mapped[:, 2:3]", "mapped / mapped[:, 1:2]").replace("mapped[:, :2]", "mapped[:, :1]")
    changed = _changed(student)
    assert _reference_def() not in changed   # (two statements: two changes, each tried alone)
    student = REFERENCE.replace("np.ones((len(points), 1))", "np.zeros((len(points), 2))")
    assert _reference_def() in _changed(student)


def test_a_missing_step_is_added_after_the_statement_written_alike():
    student = REFERENCE.replace("    mapped = mapped / mapped[:, 2:3]\n", "")
    tree, reference = ast.parse(student), ast.parse(REFERENCE)
    added = [m for m in aligned_mutants(tree, reference, "project") if m.operator == "add_step"]
    assert len(added) == 1
    made = apply_edits(student, added[0].edits)
    assert "mapped = mapped / mapped[:, 2:3]" in made


def test_an_extra_rebinding_is_taken_out():
    student = REFERENCE.replace("    return mapped[:, :2]", "    mapped = np.round(mapped)\n    return mapped[:, :2]")
    tree, reference = ast.parse(student), ast.parse(REFERENCE)
    # (the extra `mapped = np.round(mapped)` has counterparts of its signature -- `mapped = ...` -- that differ
    # everywhere: made one of them it would show the reference's line, so it is not; each of them is written
    # word for word elsewhere, so it is a step of the student's own, to take out)
    made = aligned_mutants(tree, reference, "project")
    assert [m.operator for m in made] == ["extra_step"]
    assert "np.round" not in apply_edits(student, made[0].edits)
    student = REFERENCE.replace("    mapped = mapped / mapped[:, 2:3]\n", "    mapped = np.round(mapped)\n")
    tree = ast.parse(student)
    # (where a `mapped = ...` of the reference is not written, the other one's place is its counterpart's)
    assert not [m for m in aligned_mutants(tree, reference, "project") if m.operator == "extra_step"]
    student = REFERENCE.replace("    return mapped[:, :2]", "    points = points[::-1]\n    return mapped[:, :2]")
    tree = ast.parse(student)
    extra = [m for m in aligned_mutants(tree, reference, "project") if m.operator == "extra_step"]
    assert len(extra) == 1 and "points[::-1]" not in apply_edits(student, extra[0].edits)


def test_code_of_ones_own_has_no_counterparts_to_align():
    student = '''
import numpy as np

def project(points, K):
    out = []
    for x, y, z in points:
        u = K[0, 0] * x / z + K[0, 2]
        v = K[1, 1] * y / z + K[1, 2]
        out.append((u, v))
    return np.array(out)
'''
    assert _changed(student) == []


def test_a_long_counterpart_is_not_written_out():
    reference = "def f(a, b):\n    return np.concatenate([a * 2.0, b * 3.0, a + b, a - b, np.ones_like(a)], axis=0)\n"
    student = "def f(a, b):\n    return np.stack([a, b])\n"
    assert len("np.concatenate([a * 2.0, b * 3.0, a + b, a - b, np.ones_like(a)], axis=0)") > SHOWN
    assert aligned_changes(_defs(ast.parse(student))["f"], _defs(ast.parse(reference))["f"]) == []


@pytest.mark.parametrize("lab", sorted(p.stem for p in (ROOT / "reference_solutions").glob("lab*.py")))
def test_a_reference_beside_itself_has_nothing_to_align(lab):
    tree = ast.parse((ROOT / "reference_solutions" / f"{lab}.py").read_text())
    for function in _defs(tree):
        assert aligned_mutants(tree, tree, function) == []


def test_a_blind_slip_in_a_lab_is_mended_by_its_counterpart():
    source = (ROOT / "reference_solutions" / "lab10_camera2.py").read_text()
    fn = _defs(ast.parse(source))["camera_matrix_dlt"]
    stacked = [n for n in ast.walk(fn) if isinstance(n, ast.Call) and ast.unparse(n.func) == "np.vstack"]
    assert stacked, "the reference stacks its rows"
    student = source.replace(ast.unparse(stacked[0]), ast.unparse(stacked[0]).replace("np.vstack", "np.hstack"), 1)
    made = [apply_edits(student, m.edits) for m in aligned_mutants(ast.parse(student), ast.parse(source), "camera_matrix_dlt")]
    assert ast.unparse(fn) in [ast.unparse(_defs(ast.parse(text))["camera_matrix_dlt"]) for text in made]


def test_a_def_written_in_names_of_ones_own_is_aligned_through_them():
    student = '''
import numpy as np

def project(points, K):
    h = np.hstack([points, np.ones((len(points), 1))])
    m = h @ K
    m = m / m[:, 2:3]
    return m[:, :2]
'''
    fixed = student.replace("h @ K", "h @ K.T")
    assert ast.unparse(_defs(ast.parse(fixed))["project"]) in _changed(student)


def test_a_def_far_longer_than_any_labs_is_not_read():
    slip = REFERENCE.replace("homogeneous @ K.T", "homogeneous @ K")
    assert aligned_mutants(ast.parse(slip), ast.parse(REFERENCE), "project")   # (read: the slip has its counterpart)
    filler = "".join(f"    x{i} = points * {i}\n" for i in range(400))
    long = slip.replace("    return mapped[:, :2]", filler + "    return mapped[:, :2]")
    assert aligned_mutants(ast.parse(long), ast.parse(REFERENCE), "project") == []


def test_a_step_wrapped_round_the_counterparts_value_is_taken_off():
    student = REFERENCE.replace("homogeneous @ K.T", "np.flip(homogeneous, axis=1) @ K.T")
    assert _reference_def() in _changed(student)


def test_student_code_longer_than_a_slip_at_a_place_is_other_code():
    # (a wrapper round the counterpart's value is a slip; thousands of characters round it are code of one's own,
    # and are not compared character by character, which would cost the square of their length)
    wrapped = "(homogeneous + 0.0 * np.sum([" + ", ".join(["points"] * 400) + "], axis=0))"
    student = REFERENCE.replace("homogeneous @ K.T", f"{wrapped} @ K.T")
    assert _changed(student) == []
    assert _reference_def() in _changed(REFERENCE.replace("homogeneous @ K.T", "(homogeneous + 0.0 * points) @ K.T"))


def test_counterparts_are_left_out_while_the_operators_are_measured():
    from autograder.engine.mutants import aligned

    slip = REFERENCE.replace("homogeneous @ K.T", "homogeneous @ K")
    with aligned.left_out():
        assert aligned_mutants(ast.parse(slip), ast.parse(REFERENCE), "project") == []
    assert aligned_mutants(ast.parse(slip), ast.parse(REFERENCE), "project")   # (and back after the block)


WARP_REFERENCE = '''
import cv2
import numpy as np

def warp_pair(img_l, img_r, H1, H2):
    height, width = img_l.shape[:2]
    left = cv2.warpPerspective(img_l, H1, (width, height))
    right = cv2.warpPerspective(img_r, H2, (width, height))
    return left, right
'''


def test_a_name_of_ones_own_where_the_counterpart_writes_an_expression_is_a_place():
    # (the student's own step computes `size`, a canvas of their choosing; the counterpart writes the input's size
    # there, from names computed as the reference computes them: the change is made in every statement alike too)
    student = WARP_REFERENCE.replace("    left = ", "    size = (2 * width, height)\n    left = ") \
        .replace("H1, (width, height)", "H1, size").replace("H2, (width, height)", "H2, size")
    tree, reference = ast.parse(student), ast.parse(WARP_REFERENCE)
    made = [ast.unparse(_defs(ast.parse(apply_edits(student, m.edits)))["warp_pair"])
            for m in aligned_mutants(tree, reference, "warp_pair")]
    both = [text for text in made if text.count("(width, height)") == 2]
    assert len(both) == 1 and "size" in both[0]   # (the own step stays; both warps take the input's size)
    assert sum(text.count("(width, height)") == 1 for text in made) == 2   # (and each alone)


def test_a_name_is_not_replaced_by_an_expression_of_values_computed_otherwise():
    # (`height, width` of the student's own making: the counterpart's expression would read values the student's
    # code computes otherwise, so the name does not stand for it)
    student = WARP_REFERENCE.replace("height, width = img_l.shape[:2]", "height, width = img_l.shape[1::-1]") \
        .replace("    left = ", "    size = (width, height)\n    left = ").replace("H1, (width, height)", "H1, size")
    tree, reference = ast.parse(student), ast.parse(WARP_REFERENCE)
    assert not any("H1, (width, height)" in apply_edits(student, m.edits)
                   for m in aligned_mutants(tree, reference, "warp_pair"))


CLAMP_REFERENCE = '''
import numpy as np

def clamped(point, width, height):
    limit = 4.0 * (width + height)
    return tuple(int(round(np.clip(v, -limit, limit))) for v in point)
'''


def test_a_number_fixed_in_advance_where_the_counterpart_computes_it_from_the_inputs_is_a_place():
    # (`limit = 1000.0` where the reference sizes the clamp by the image: the number is the slip, and the change
    # writes the counterpart's expression of the parameters)
    student = CLAMP_REFERENCE.replace("4.0 * (width + height)", "1000.0")
    tree, reference = ast.parse(student), ast.parse(CLAMP_REFERENCE)
    made = [apply_edits(student, m.edits) for m in aligned_mutants(tree, reference, "clamped")]
    assert any("limit = 4.0 * (width + height)" in text for text in made), made
    # (an expression that calls something, or reads a value of the student's own, is no value of the inputs)
    called = CLAMP_REFERENCE.replace("4.0 * (width + height)", "4.0 * max(width, height)")
    assert not any("max(width, height)" in apply_edits(student, m.edits)
                   for m in aligned_mutants(tree, ast.parse(called), "clamped"))


COLLAPSE_REFERENCE = '''
def collapse(bands, up):
    result = bands[-1]
    for band in reversed(bands[:-1]):
        result = up(result) + band
    return result
'''


@pytest.mark.parametrize("slip, fixed", [("bands[1:-1]", "bands[:-1]"), ("bands[:]", "bands[:-1]")])
def test_a_part_one_side_leaves_out_makes_the_subscript_holding_it_the_place(slip, fixed):
    # (a slice's bound written where the counterpart has none, or left out where it has one: the subscript is the
    # place -- a bound of None is no expression to write, and reading it once stopped every change of the def)
    student = COLLAPSE_REFERENCE.replace("reversed(bands[:-1])", f"reversed({slip})")
    tree, reference = ast.parse(student), ast.parse(COLLAPSE_REFERENCE)
    made = [apply_edits(student, m.edits) for m in aligned_mutants(tree, reference, "collapse")]
    assert any(f"reversed({fixed})" in text for text in made), made
