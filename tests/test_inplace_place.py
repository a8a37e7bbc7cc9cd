"""Where the code writes into its caller's array: read from the student's code, told beside the measured effect."""

from __future__ import annotations

import ast
import textwrap

from autograder.engine.inplace import place_of_change, writes_into_arguments
from autograder.engine.runner import grade
from conftest import check_results, mutant


def _defs(source: str) -> list:
    return [node for node in ast.parse(textwrap.dedent(source)).body if isinstance(node, ast.FunctionDef)]


def test_a_name_holding_the_argument_without_a_copy_is_followed_to_the_write():
    functions = _defs('''
        def helper(points):
            centred = points
            centred -= centred.mean(axis=0)
            return centred

        def scaled(x, s):
            x = np.asarray(x, dtype=float).reshape(-1, 2)
            x[:, 0] /= s
            return x
    ''')
    found = writes_into_arguments(functions)
    assert [(fn.name, ast.unparse(node), parameter) for fn, node, parameter, _ in found] == \
        [("helper", "centred -= centred.mean(axis=0)", "points"), ("scaled", "x[:, 0] /= s", "x")]
    assert ast.unparse(found[0][3]) == "centred = points"
    # (the arithmetic the change showed keeps its own kind: a shift is no division)
    assert [fn.name for fn, *_ in writes_into_arguments(functions, "shifts")] == ["helper"]
    assert "line 4, in `helper`" in place_of_change(functions, "shifts (adds [1, 2] to every row of)")
    assert place_of_change(functions) == ""   # (two places: not certain)
    # (the parameter the change was measured on decides: a write into another array is not that change's place)
    assert "in `scaled`" in place_of_change(functions, "", "scaled", "x")
    assert place_of_change(functions, "", "scaled", "s") == ""


def test_a_write_in_a_helper_counts_only_where_the_changed_array_is_passed_to_it():
    functions = _defs('''
        def graded(points, other):
            T = centre(points)
            scale_in_place(other)
            return T

        def centre(p):
            p -= p.mean(axis=0)
            return p

        def scale_in_place(q):
            q /= 2
    ''')
    assert "in `centre`: `p -= p.mean(axis=0)`" in place_of_change(functions, "", "graded", "points")
    assert "in `scale_in_place`" in place_of_change(functions, "", "graded", "other")


def test_copies_and_names_rebound_are_not_writes_into_the_argument():
    functions = _defs('''
        def f(points, other):
            points = np.array(points, dtype=float)
            points -= 1
            view = other.astype(float)
            view /= 2
            kept = np.asarray(other, copy=True)
            kept[0] = 0
            return points, view, kept
    ''')
    assert writes_into_arguments(functions) == []


CENTRED_IN_PLACE = '''
def _normalising_transform(points):
    dim = points.shape[1]
    c = np.mean(points, axis=0)
    centred = points
    centred -= c
    s = np.sqrt(dim) / np.mean(np.sqrt(np.sum(centred ** 2, axis=1)))
    T = np.eye(dim + 1)
    for i in range(dim):
        T[i, i] = s
        T[i, dim] = -s * c[i]
    return T
'''


def test_the_helper_that_centres_the_callers_array_in_place_is_told_with_its_line(tmp_path):
    """The change shows on camera_matrix_dlt's caller's array; the write is in a helper it runs (07d lab10/03): a copy
    in camera_matrix_dlt, where the effect was measured, would mend the caller's array and leave P wrong."""
    result = grade(str(mutant(tmp_path, "lab10_camera2", CENTRED_IN_PLACE)), ["lab10.ex4"])
    messages = [c.message for c in check_results(result, "lab10.ex4") if c.score < c.max_score]
    assert any("in place" in m and "in `_normalising_transform`: `centred -= c` changes the array given, which "
               "`centred = points`" in m for m in messages), messages


def test_the_copy_hint_says_only_what_numpy_does():
    """The hint's aside on copies is NumPy's behaviour (blind set 08b's evaluator: it said `.astype(float)` of a
    float array does not copy, which it does): np.array copies, np.asarray of a float array does not."""
    import numpy as np

    from autograder.engine import inplace

    x = np.zeros(3)
    assert not np.shares_memory(np.array(x, dtype=float), x) and np.shares_memory(np.asarray(x, dtype=float), x)
    assert "np.asarray(x, dtype=float) of a float array does not" in inplace.HINT and "astype" not in inplace.HINT
