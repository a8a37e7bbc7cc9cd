"""Lab 12 names what the student's code shows (issue 35), and offers the error model inputs it can
afford: the code-reading signs (autograder/labs/code_signs.py) on source alone, the band of rows a
failing matcher's check offers the model. The mistakes themselves are graded in tests/test_lab12.py
(the mistakes table: OpenCV's fixed point kept, smoothness=0 taken for the default, Vt[-1] of a
batched SVD, a map twice the disparity); the legitimate variants keep full marks there and here."""

from __future__ import annotations

import importlib.util
import textwrap

import numpy as np
import pytest

from autograder.engine.checks import Fail, Trial
from autograder.engine.hints import read_code
from autograder.engine.registry import select
from autograder.engine.runner import grade
from autograder.labs import code_signs, lab12
from autograder.sandbox.supervisor import CallOutcome
from conftest import REFERENCE, check_results, mutant

MODULE = "lab12_stereo"


def found(predicate, source: str, function: str) -> str:
    code = read_code(textwrap.dedent(source))
    assert function in code.functions, "the test's source does not parse"
    return predicate.found(code.reachable([function]))


BM = """
    import cv2
    import numpy as np
    def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
        n = 16 * -(-(max_disparity + 1) // 16)
        stereo = cv2.StereoBM_create(numDisparities=n, blockSize=block_size)
        {body}
    """


@pytest.mark.parametrize("body, undivided", [
    ("return stereo.compute(left, right).astype(np.float32)", True),
    ("d = np.float32(stereo.compute(left, right))\n        d[d < 0] = 0\n        return d", True),
    ("return np.clip(stereo.compute(left, right), 0, max_disparity).astype(float)", True),
    ("return stereo.compute(left, right).astype(np.float32) / 16.0", False),
    ("return stereo.compute(left, right) / 16", False),
    ("d = stereo.compute(left, right).astype(float)\n        d /= 16\n        return d", False),
    ("return np.divide(stereo.compute(left, right), 16.0)", False),
    ("return stereo.compute(left, right) * (1 / 16)", False),
    ("return (stereo.compute(left, right) // 16).astype(np.float64)", False),
])
def test_opencv_matcher_not_divided_by_16_is_read(body, undivided):
    """The range rounded up to a multiple of 16 (``-(-(max_disparity + 1) // 16)``) divides no disparity."""
    assert bool(found(lab12.STEREO_MATCHER_UNDIVIDED, BM.format(body=body), "block_matching")) == undivided


def test_own_matcher_is_no_opencv_matcher():
    source = "def block_matching(left, right, max_disparity=64, block_size=9, cost='ssd'):\n" \
             "    return np.argmin(costs(left, right), axis=0) * 16\n"
    assert not found(lab12.STEREO_MATCHER_UNDIVIDED, source, "block_matching")


@pytest.mark.parametrize("line, taken", [
    ("s = smoothness or DEFAULT_SMOOTHNESS", True),
    ("s = smoothness if smoothness else 6.0", True),
    ("if not smoothness:\n        smoothness = 6.0", True),
    ("s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)", False),
    ("if smoothness is None:\n        smoothness = 6.0", False),
    ("s = block_size or 5", False),
])
def test_zero_taken_for_missing_is_read(line, taken):
    source = f"def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):\n    {line}\n    return s\n"
    assert bool(found(code_signs.zero_taken_for_missing("smoothness"), source, "dp_stereo")) == taken


def test_batched_vt_row_is_read_and_each_systems_is_not():
    batched = "def triangulate(P1, P2, pts1, pts2):\n    _, _, Vt = np.linalg.svd(A)\n    X = Vt[-1]\n    return X\n"
    each = "def triangulate(P1, P2, pts1, pts2):\n    _, _, Vt = np.linalg.svd(A)\n    X = Vt[:, -1]\n    return X\n"
    assert found(code_signs.TAKES_LAST_ROW_OF_VT, batched, "triangulate")
    assert not found(code_signs.TAKES_LAST_ROW_OF_VT, each, "triangulate")


# ------------------------------------------------------------------ the band offered to the error model
class InProcess:
    """Stands in for the sandbox: calls a module's functions here (tests only)."""

    def __init__(self, module):
        self.module, self.shared, self.submission_dir = module, {}, None

    def call(self, module, function, args=(), kwargs=None, **_):
        return CallOutcome(ok=True, value=getattr(self.module, function)(*args, **(kwargs or {})))


def _student(source: str):
    """The reference lab 12 module with ``source`` run in it (its defs win)."""
    spec = importlib.util.spec_from_file_location("student_lab12", REFERENCE / f"{MODULE}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    exec(textwrap.dedent(source), module.__dict__)   # noqa: S102 - the test's own mistake
    return module


BLOCK_SIZE_AS_RANGE = """
    def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
        volume = _ssd_volume(_grey_float(left), _grey_float(right), int(block_size), int(block_size))
        return np.argmin(volume, axis=0).astype(np.float64)
    """


def test_a_failing_matcher_check_offers_the_error_model_a_band_of_rows_only():
    """The model reproduces the trial's recorded calls with every mutant: after a failed check of
    block_matching they are one call, on NAMING_ROWS rows of the scene (7.4 s of mutants on the
    check's own calls, 2.1 s on the band, measured; the model has 3 s a check)."""
    [exercise] = select(["lab12.ex4"])
    check = next(c for c in exercise.checks if c.func.__name__ == "block_matching_slanted")
    trial = Trial(InProcess(_student(BLOCK_SIZE_AS_RANGE)), check)
    with pytest.raises(Fail):
        check.func(trial)
    recorded = [call for call in trial.calls if call[0] == "block_matching"]
    assert len(recorded) == 1
    _, (left, right), kwargs, answer = recorded[0]
    assert left.shape[0] == right.shape[0] == answer.shape[0] == lab12.NAMING_ROWS
    assert kwargs["max_disparity"] == lab12.truth.scene("slanted").max_disparity


def test_a_passing_matcher_check_offers_nothing():
    [exercise] = select(["lab12.ex4"])
    check = next(c for c in exercise.checks if c.func.__name__ == "block_matching_slanted")
    trial = Trial(InProcess(_student("")), check)
    check.func(trial)
    assert all(np.asarray(call[1][0]).shape[0] > lab12.NAMING_ROWS for call in trial.calls)


# ------------------------------------------------------------------ legitimate OpenCV recipes: no name
STEREO_BM_FLOAT32 = """
    _block_matching_own = block_matching
    def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
        if cost != "ssd":
            return _block_matching_own(left, right, max_disparity, block_size, cost)
        stereo = cv2.StereoBM_create(numDisparities=16 * int(np.ceil((max_disparity + 1) / 16)), blockSize=block_size)
        disparity = np.float32(stereo.compute(left, right)) / 16.0
        disparity[(disparity < 0) | (disparity > max_disparity)] = 0
        return disparity
    """


def test_stereo_bm_converted_to_float32_and_divided_keeps_full_marks(tmp_path):
    result = grade(mutant(tmp_path, MODULE, STEREO_BM_FLOAT32), ["lab12.ex4"], pictures="none")
    for check in check_results(result, "lab12.ex4"):
        assert check.passed and not check.mistake, f"{check.name}: {check.message}"


# ------------------------------------------------------------------ a hint reads the function its map comes from
def test_a_dp_check_reads_the_dp_not_block_matching():
    """dp_stereo's checks also name block_matching (a helper they share asks it): the block search's
    hints and OpenCV's fixed point are not said to a DP for what block_matching's code does."""
    assert lab12.judged_function("dp_stereo(left, right)") == "dp_stereo"
    assert lab12.judged_function('block_matching(left, 0.4 * right +150, cost="ncc")') == "block_matching"

    source = textwrap.dedent(BM.format(body="return stereo.compute(left, right) / 16.0")) + \
        "def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):\n    return left\n"
    code = read_code(source)
    assert lab12.OPENCV_MATCHER_HINT.contradicts(code, ["block_matching"])
    assert not lab12.OPENCV_MATCHER_HINT.contradicts(code, [lab12.judged_function("dp_stereo(left, right)")])
    assert lab12.matching_hint(None, "dp_stereo(left, right)") == lab12.DP_STEPS   # (no code read)


@pytest.mark.parametrize("factor, words", [(16.0, "16 times"), (1 / 16, "1/16 of"), (-1.0, "the negative of"),
                                           (1000.0, "1000 times"), (2.37, "2.37 times")])
def test_an_answer_off_by_a_constant_is_told_the_factor(factor, words):
    expected = np.array([[3.5, 17.25, 61.0], [8.75, 0.6, np.nan]])
    c = code_signs.constant_factor(factor * expected, expected)
    assert c == pytest.approx(factor) and code_signs.factor_words(c) == words


def test_no_factor_for_the_answer_itself_or_another_error():
    expected = np.array([3.5, 17.25, 61.0, 8.75])
    assert code_signs.constant_factor(expected, expected) is None
    assert code_signs.constant_factor(2 * expected + 1, expected) is None   # an offset too: no single factor
    assert code_signs.constant_factor(expected[:3], expected) is None


def test_a_dp_on_uint8_costs_is_not_told_its_backtracking_or_smoothness_is_missing(tmp_path):
    # the data cost computed on the uint8 images wraps round (10 - 12 = 254): the map is wrong all
    # over, the penalty acts but weakly at that scale; neither the backtracking's start nor an
    # ignored smoothness is the cause (the 28c evaluator read both names as false)
    source = """
        def _grey_float(image):
            image = np.asarray(image)
            return cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
        """
    result = grade(mutant(tmp_path, "lab12_stereo", source), ["lab12.ex5"], pictures="none")
    failed = [c for c in check_results(result, "lab12.ex5") if not c.passed and c.max_score > 0]
    assert failed, "uint8 costs lose points"
    said = " ".join(c.message + " " + (c.mistake or "") for c in failed)
    assert "where the backtracking starts, is wrong" not in said
    assert "the smoothness term is ignored" not in said


def test_two_costs_swapped_are_named_from_the_ssd_robust_to_a_gain(tmp_path):
    # the blind set's dispatch `(_ncc_volume if cost == "ssd" else _ssd_volume)`: not "your NCC is not normalised"
    from autograder.labs.lab12 import COSTS_SWAPPED

    submission = mutant(tmp_path, "lab12_stereo", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return _block_matching(left, right, max_disparity, block_size, "ncc" if cost == "ssd" else "ssd")
        """)
    failed = [c for c in check_results(grade(submission, ["lab12.ext1"]), "lab12.ext1") if c.score < c.max_score]
    gain = [c for c in failed if c.name.startswith("NCC is robust to a brightness")]
    assert gain and gain[0].mistake == COSTS_SWAPPED and "not fully normalised" not in gain[0].message


def test_a_dp_whose_penalty_rewards_jumps_is_told_so_not_that_its_smoothness_is_ignored(tmp_path):
    """The backtracking subtracting the jump's cost (`energy[x - 1] - jump`): the map is far jumpier than
    the student's own smoothness=0 map -- the penalty acts, with the wrong sign; "ignored" would be false."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, "lab12_stereo", ("energy[x - 1] + jump", "energy[x - 1] - jump"))
    result = grade(folder, ["lab12.ex5"], pictures="none", include_hidden=False)
    messages = [c.message for e in result.exercises for c in e.checks if not c.passed]
    assert any("rewards jumps instead of costing them" in m for m in messages), messages
    assert not any("smoothness term is ignored" in m for m in messages), messages


LIT_WITHOUT_VALIDITY = """
    def simulate_structured_light(depth, f, baseline, n_bits):
        depth = np.asarray(depth, dtype=np.float64)
        height, width = depth.shape
        patterns = gray_code_patterns(width, n_bits)
        valid = np.isfinite(depth) & (depth > 0)
        u = np.broadcast_to(np.arange(width, dtype=np.float64), depth.shape)
        disparity = np.divide(float(f) * float(baseline), depth, out=np.zeros_like(depth), where=valid)
        column = np.floor(u - disparity + 0.5).astype(np.int64)
        lit = (column >= 0) & (column < width)
        images = np.zeros((int(n_bits), height, width), dtype=np.uint8)
        images[:, lit] = patterns[:, column[lit]]
        return images
    """


def test_the_projector_column_is_read_however_rounded_and_divided(tmp_path):
    """`np.floor(u - np.divide(f * b, Z, where=valid) + 0.5)` computes the sheet's column: no hint asks for it;
    the lit mask without the validity test is told by what the check measured."""
    from autograder.engine.claims import GUARDED

    code = read_code(textwrap.dedent(LIT_WITHOUT_VALIDITY))
    told = GUARDED[lab12.PROJECTOR_MODEL].told(code, ["simulate_structured_light"])
    assert "round(u - f*baseline/Z)" not in told, told
    folder = mutant(tmp_path, MODULE, LIT_WITHOUT_VALIDITY)
    result = grade(folder, ["lab12.ex6"], pictures="none", include_hidden=False)
    black = next(c for c in check_results(result, "lab12.ex6") if "no depth in front black" in c.name)
    assert black.score < black.max_score
    assert "round(u - f*baseline/Z)" not in black.hint and "left out of the pixels" in black.hint, black.hint


@pytest.mark.parametrize("loop, said", [
    ("for x in range(1, w):\n        e[x] = c[x] + np.min(c[x - 1] + p, axis=1)", "`e[x]` (line 4) is computed from `c[x - 1]`"),
    ("for x in range(1, w):\n        e[:, x] = c[:, x] + np.min(c[:, x - 1] + p)", "`e[:, x]` (line 4) is computed from"),
    ("for x in range(1, w):\n        e[x] = c[x] + np.min(e[x - 1] + p, axis=1)", ""),             # the recurrence
    ("for x in range(1, w):\n        prev = e[x - 1]\n        e[x] = c[x] + prev.min()", ""),   # through a name
    ("for x in range(w - 1, 0, -1):\n        d[x - 1] = np.argmin(e[x - 1] + p[d[x]])", ""),  # a backtracking
    ("for x in range(1, w):\n        e[x] = c[x] + c[x - 1]", "`e[x]` (line 4) is computed from `c[x - 1]`"),
])
def test_a_recurrence_that_never_reads_its_own_previous_value_is_read(loop, said):
    source = "def dp(c, w, p, d):\n    e = np.empty_like(c)\n    " + loop + "\n    return e\n"
    found = lab12.recurrence_without_itself(read_code(source).reachable(["dp"]))
    assert (found.startswith(said) and said) or (found == said == ""), found


@pytest.mark.parametrize("edit", [
    # the forward pass's minimum over d' = d and d +- 1 only (the 05c blind set's loop over range(1, 2))
    ("best = np.minimum(from_below, from_above)",
     "best = previous.copy()\n"
     "        best[:, 1:] = np.minimum(best[:, 1:], previous[:, :-1] + ramp[1])\n"
     "        best[:, :-1] = np.minimum(best[:, :-1], previous[:, 1:] + ramp[1])"),
    # the walk back choosing among the neighbouring disparities only
    ("disparity[x - 1] = np.argmin(energy[x - 1] + jump, axis=1)",
     "near = np.abs(candidates[None, :] - disparity[x][:, None]) <= 1\n"
     "        disparity[x - 1] = np.argmin(np.where(near, energy[x - 1] + jump, np.inf), axis=1)"),
], ids=["forward pass", "walk back"])
def test_a_dp_that_cannot_jump_far_is_told_so_at_a_deep_edge(tmp_path, edit):
    """The public scenes' edges are at most 10 px deep; the deep step's 22 px is crossed by the reference
    in one step at any penalty. A DP whose minimum leaves far d' out misses it even at an almost-zero
    penalty, where its smoothness=0 map finds it: named, with the measurement."""
    from conftest import edited_reference

    result = grade(edited_reference(tmp_path, MODULE, edit), ["lab12.ex5"], pictures="none", include_hidden=False)
    edge = next(c for c in check_results(result, "lab12.ex5") if c.name.startswith("dp_stereo crosses a deep"))
    assert edge.score == 0, edge.message
    # (named by the measurement; or, where a change of the code was confirmed on an earlier check, by that
    # change -- the restriction itself taken out -- which the rule's guess then yields to)
    restrictions = ("np.where(near", "best[:, 1:]", "best[:, :-1]", "best = previous")
    assert (edge.mistake == lab12.JUMPS_LIMITED and "with smoothness=0.0001" in edge.message) or (
        edge.mistake.startswith("repair:") and any(text in edge.message for text in restrictions)), edge.message


def test_a_dp_whose_default_penalty_is_too_strong_for_a_deep_edge_is_not_told_its_jumps_are_limited(tmp_path):
    """A default penalty so strong the deep step is smoothed over: the same DP at an almost-zero penalty
    crosses the edge, so the jumps are free and the name would be false."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, MODULE, ("DEFAULT_SMOOTHNESS = 6.0", "DEFAULT_SMOOTHNESS = 200.0"))
    result = grade(folder, ["lab12.ex5"], pictures="none", include_hidden=False)
    edge = next(c for c in check_results(result, "lab12.ex5") if c.name.startswith("dp_stereo crosses a deep"))
    assert edge.score == 0, "the deep step smoothed over loses the point"
    assert edge.mistake != lab12.JUMPS_LIMITED and "is not taken at any penalty" not in edge.message, edge.message


def test_code_that_reads_cost_is_not_told_it_ignores_it_when_both_costs_give_one_map(tmp_path):
    """Course code with a branch per cost whose disparities come out the same under both (OpenCV-4 code reading
    cv2.minMaxLoc's location under OpenCV 5 -- third-party audit of 2026-12-07): it reads cost, so "the cost
    argument is ignored" would be untrue; the map is told as the same, and where to look. A block_matching that
    never reads cost is still told it ignores it (the table's case, tests/test_lab12.py)."""
    submission = mutant(tmp_path, "lab12_stereo", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost == "ncc":
                return _block_matching(left, right, max_disparity, block_size, "ssd")
            return _block_matching(left, right, max_disparity, block_size, cost)
        """)
    failed = [c for c in check_results(grade(submission, ["lab12.ext1"], pictures="none", include_hidden=False),
                                       "lab12.ext1") if c.score < c.max_score]
    gain = [c for c in failed if c.name.startswith("NCC is robust to a brightness")]
    assert gain, failed
    assert "ignored" not in gain[0].message and gain[0].mistake != "the cost argument is ignored", gain[0]
    assert "although your block_matching reads cost" in gain[0].message


def test_rows_blanked_where_columns_belong_are_not_told_as_a_loop_starting_late(tmp_path):
    """`costs[d, :d] = np.inf` (the first d rows of the d-th slice blanked where its first d columns belong, blind
    set 08a lab12/03) leaves the map's first row empty: the code loops over no rows, so no loop starting late is
    guessed; the slice made the next axis's is the change told."""
    from conftest import edited_reference

    folder = edited_reference(tmp_path, "lab12_stereo", (
        "costs[d, :, :d] = np.inf                 # x - d falls outside the right image", "costs[d, :d] = np.inf"))
    result = grade(str(folder), ["lab12.ex4"], pictures="none")
    failed = [c for c in check_results(result, "lab12.ex4") if c.score < c.max_score]
    assert failed and not any("a loop over the rows" in c.message for c in failed), [c.message for c in failed]
    assert any("to `costs[d, :, :d]`" in c.message for c in failed), [c.message for c in failed]
    assert any(c.mistake == lab12.EDGE_ROW_EMPTY for c in failed)


def test_a_colour_pair_turned_grey_is_told_with_the_conversion_read_in_the_code(tmp_path):
    """A rectification converting its inputs to grey (blind set 08a lab12/02) returns (H, W) for BGR: the shape is
    named, with the conversion quoted from the code; a channel taken (no conversion to read) is told the shape only."""
    source = """
        _rectify_as_given = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            img_l = cv2.cvtColor(img_l, cv2.COLOR_BGR2GRAY) if img_l.ndim == 3 else img_l
            img_r = cv2.cvtColor(img_r, cv2.COLOR_BGR2GRAY) if img_r.ndim == 3 else img_r
            return _rectify_as_given(img_l, img_r, K1, K2, R, T)
        """
    result = grade(str(mutant(tmp_path, "lab12_stereo", source)), ["lab12.ex3"], pictures="none")
    failed = [c for c in check_results(result, "lab12.ex3") if c.score < c.max_score]
    assert any("your code converts the colour images to grey (`cv2.cvtColor(img_l, cv2.COLOR_BGR2GRAY)`, line"
               in c.message for c in failed), [c.message for c in failed]
    taken = source.replace("cv2.cvtColor(img_l, cv2.COLOR_BGR2GRAY)", "img_l[..., 1]").replace(
        "cv2.cvtColor(img_r, cv2.COLOR_BGR2GRAY)", "img_r[..., 1]")
    result = grade(str(mutant(tmp_path / "taken", "lab12_stereo", taken)), ["lab12.ex3"], pictures="none")
    failed = [c for c in check_results(result, "lab12.ex3") if c.score < c.max_score]
    assert failed and not any("converts the colour images" in c.message for c in failed)
