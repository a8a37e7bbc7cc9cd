"""What a function could keep between calls, read from its code (autograder.engine.fresh_start.holders):
the gate and the pointer of the naming that makes a failing call again in a module imported anew.
The naming itself is held to the mistakes tables (lab07's rotate cache, lab12's stripe cache)."""

import textwrap

from autograder.engine.fresh_start import holders


def _held(source: str, function: str = "f") -> list[str]:
    return [name for name, _ in holders(textwrap.dedent(source), function)]


def test_a_cache_the_function_writes_into_is_named_before_a_table_it_only_reads():
    assert _held("""
        import numpy as np
        _PALETTE = [(255, 0, 0), (0, 255, 0)]
        _CACHE = {}
        def f(image, angle):
            key = image.shape
            if key not in _CACHE:
                _CACHE[key] = angle
            return _PALETTE[0], _CACHE[key]
        """) == ["_CACHE"]


def test_state_kept_by_a_helper_the_function_calls_counts():
    assert _held("""
        seen = []
        def _remember(x):
            seen.append(x)
            return len(seen)
        def f(x):
            return _remember(x)
        """) == ["seen"]


def test_globals_mutable_defaults_and_attributes_of_a_def():
    assert set(_held("""
        count = 0
        def f(x, memo={}):
            global count
            count += 1
            f.last = x
            return memo.setdefault(x, count)
        """)) == {"count", "a mutable default of f", "f.last"}


def test_an_array_of_the_module_changed_through_an_index():
    assert _held("""
        import numpy as np
        M = np.eye(3)
        def f(tx):
            M[0, 2] += tx
            return M
        """) == ["M"]


def test_a_function_keeping_nothing_has_no_holders():
    assert _held("""
        import numpy as np
        SCALE = 2.0
        def f(x):
            cache = {}
            cache[1] = x
            return np.asarray(x) * SCALE
        """) == []
    assert holders("def f(:", "f") == []   # (code that does not parse: nothing read)
