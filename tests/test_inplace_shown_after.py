"""An argument the lab sheet shows after the call (engine/inplace.py's shown_after): its change
is the effect, told by the values that changed, with no second call."""

from types import SimpleNamespace

import numpy as np

from autograder.engine import inplace


def test_the_values_that_changed_are_told_nan_equal_to_nan():
    before = np.array([[4.0, 0.0, -3.0], [np.nan, 8.0, 1.0]])
    after = np.where(before > 0, before, np.inf)
    assert inplace.values_changed(before, after) == "3 of its 6 values: 0 became inf, -3 became inf, nan became inf"
    assert inplace.values_changed(before, before.copy()) == ""
    assert inplace.values_changed(np.array([0.0]), np.array([-0.0])) == ""   # other bytes, the same value
    many = np.arange(10.0)
    assert inplace.values_changed(many, -many).endswith("1 became -1, 2 became -2, 3 became -3, ...")


def test_a_declared_argument_changed_needs_no_second_call_and_others_do():
    lab = SimpleNamespace(module="shown_after_test")
    inplace.shown_after(lab, "depth", "disparity", "the sheet shows the map beside the depth")
    d = np.array([2.0, 0.0])
    outcome = SimpleNamespace(changed=[(0, None, np.array([2.0, np.inf]))], value=np.array([1.0, 0.0]))
    calls = []

    def call(args, kwargs):
        calls.append(args)
        return np.array([1.0, 0.0])

    said = inplace.effect_of_change(call, "depth", "depth(disparity, f, baseline)", (d, 1.0, 2.0), {}, outcome,
                                    repr, module="shown_after_test")
    assert said.startswith("depth() writes into the caller's `disparity` in place (1 of its 2 values: 0 became inf)")
    assert "the sheet shows the map beside the depth" in said and calls == []
    # another module's function of that name: the second call decides (the same answer: no effect)
    assert inplace.effect_of_change(call, "depth", "depth(disparity, f, baseline)", (d, 1.0, 2.0), {}, outcome,
                                    lambda value: repr(np.asarray(value).tolist()), module="elsewhere") == ""
    assert len(calls) == 2
