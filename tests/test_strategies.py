"""Described strategies (autograder.engine.strategies): built, they are Hypothesis's own and draw the
same examples; described, they key recorded examples without importing Hypothesis."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings, strategies as hst

from autograder.engine import strategies as st
from autograder.engine.properties import grading_settings

ROOT = Path(__file__).resolve().parents[1]

finite = lambda lo, hi: st.floats(lo, hi, allow_nan=False, allow_infinity=False)  # noqa: E731
DESCRIBED_AND_OWN = [
    (st.integers(0, 2**32 - 1), hst.integers(0, 2**32 - 1)),
    (st.tuples(st.integers(0, 9), st.floats(10.0, 2000.0)), hst.tuples(hst.integers(0, 9), hst.floats(10.0, 2000.0))),
    (finite(-5, 5).filter(lambda s: abs(s) > 1e-3),
     hst.floats(-5, 5, allow_nan=False, allow_infinity=False).filter(lambda s: abs(s) > 1e-3)),
    (st.lists(st.integers(1, 6), min_size=1, max_size=3).map(tuple),
     hst.lists(hst.integers(1, 6), min_size=1, max_size=3).map(tuple)),
    (st.tuples(st.integers(0, 5), st.sampled_from([1.0, -3.0, 1e-3])),
     hst.tuples(hst.integers(0, 5), hst.sampled_from([1.0, -3.0, 1e-3]))),
]


def _drawn(strategy, count=12) -> list:
    seen = []

    @settings(grading_settings(count))
    @given(strategy)
    def collect(example):
        seen.append(example)

    collect()
    return seen


@pytest.mark.parametrize("described, own", DESCRIBED_AND_OWN)
def test_a_built_strategy_draws_what_hypothesis_own_draws(described, own):
    assert repr(described.build()) == repr(own)
    assert _drawn(described.build()) == _drawn(own)


def test_the_description_is_stable_and_tells_strategies_apart():
    def described(bound=1e-3, upper=5):
        return finite(-upper, upper).filter(lambda s: abs(s) > bound)

    assert repr(described()) == repr(described())
    texts = {repr(described()), repr(described(bound=1e-2)), repr(described(upper=6)),
             repr(finite(-5, 5).filter(lambda s: abs(s) >= 1e-3)), repr(finite(-5, 5))}
    assert len(texts) == 5
    assert repr(st.integers(0, 9)) == "integers(0, 9)"
    assert repr(st.lists(st.integers(1, 6), max_size=3).map(tuple)) == \
        "lists(integers(1, 6), max_size=3).map(builtins.tuple)"


def test_the_description_is_the_same_in_another_process():
    code = ("from autograder.engine import strategies as st; "
            "print(repr(st.floats(-5, 5, allow_nan=False).filter(lambda s: abs(s) > 1e-3).map(float)))")
    texts = {subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                            check=True).stdout for _ in range(2)}
    assert len(texts) == 1 and "filter(<lambda>#" in texts.pop()


def test_a_function_that_holds_itself_is_described():
    def again(n):
        return n if n < 1 else again(n - 1)

    assert repr(st.integers(0, 3).map(again)) == repr(st.integers(0, 3).map(again))


def test_loading_the_suites_and_grading_the_skeleton_import_no_hypothesis(tmp_path):
    code = ("import sys; from autograder.engine.registry import discover; from autograder.engine.runner import grade; "
            "discover(); r = grade('assignments', pictures='none'); "
            "print(r.total, 'hypothesis' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True,
                         env={"PATH": "/usr/bin:/bin", "AUTOGRADER_CACHE_DIR": str(tmp_path)}).stdout
    assert out.split() == ["0.0", "False"]


def test_a_process_killed_after_drawing_examples_leaves_no_folder_behind(tmp_path):
    """Hypothesis's storage is private and made only when written: a grading process killed with no
    chance to clean up (a batch stopped, a helper past its time) leaves nothing in the temp folder."""
    code = (
        "import os, signal\n"
        "from hypothesis import given, settings, strategies as s\n"
        "from autograder.engine.properties import grading_settings\n"
        "from hypothesis.configuration import storage_directory\n"
        "print(storage_directory(intent_to_write=False).path)\n"
        "@settings(grading_settings())\n"
        "@given(s.integers())\n"
        "def holds(x):\n"
        "    pass\n"
        "holds()\n"
        "os.kill(os.getpid(), signal.SIGKILL)\n")
    run = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                         env={**__import__("os").environ, "TMPDIR": str(tmp_path)}, timeout=120)
    assert run.returncode == -9, run.stderr
    assert Path(run.stdout.strip()).parent == tmp_path, run.stdout    # private, in the temp folder
    assert list(tmp_path.iterdir()) == []
