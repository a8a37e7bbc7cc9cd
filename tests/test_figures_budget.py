"""Hostile figures: the figure pass is part of a submission's grading and held to its limits.

A student's figures (``--figures``, ``--report``, a batch's reviewed exercises) call the
student's functions like the checks do. Each attack here is written as the student would
(a function of their lab module, :func:`conftest.mutant`) and must be contained like a graded
call: a sleep ends at the submission's deadline (grading and figures share it: figures made
after grading get what is left, the rest are skipped with one sentence), an allocation at the
graded calls' memory share, and a reply too large for a figure is refused before the grader
reads its arrays (the grader's own memory stays small). Points the grader does take back are
thinned before Matplotlib draws them. Limits are small so the file stays quick.
"""

import contextlib
import json
import textwrap
import time
import tracemalloc
from dataclasses import replace

import cv2
import numpy as np
import pytest

from autograder import cli, figures
from autograder.figures import (FIGURE_REPLY_BYTES, FIGURE_REPLY_ELEMENTS, MAX_POINTS_DRAWN, figure_limits,
                                make_figures)
from autograder.sandbox import transport
from autograder.sandbox.supervisor import Limits, Sandbox
from conftest import REFERENCE, mutant
from test_hostile_v3 import HOG, cgroup  # noqa: F401 - a fixture: with the kernel's cgroup, and without

LAB07, LAB09 = "lab07_transformations", "lab09_camera"
SPENT = "the submission's time budget (grading and its figures together) is spent"


def submission(tmp_path, module: str, source: str, *others: str):
    """The reference solutions with ``source`` appended to ``module`` (and the reference ``others``)."""
    folder = mutant(tmp_path, module, textwrap.dedent(source))
    for other in others:
        (folder / f"{other}.py").write_text((REFERENCE / f"{other}.py").read_text())
    return folder


def by_id(outcomes):
    return {o.figure_id: o for o in outcomes}


# ================================================================ time: the submission's deadline
# The call timeout (60 s) is far longer than the budget: only the deadline can stop these.
# (A sleeper after a figure that must be made gets longer: the worker boots within the budget.)
SLOW = Limits(call_timeout=60.0, import_timeout=60.0, submission_budget=5.0)
SLEEPERS = {
    "translate (an image, the first figure)": (LAB07, """
        import time as _time

        def translate(image, tx=100, ty=50):
            _time.sleep(120)
        """, ["lab07.ex1", "lab07.ex2", "lab07.ex3"], "lab07.ex1", "translate"),
    "rotate (its figure's second call)": (LAB07, """
        import time as _time
        _calls = []

        def rotate(image, angle_deg=45):
            _calls.append(angle_deg)
            if len(_calls) == 2:
                _time.sleep(120)
            return image
        """, ["lab07.ex1", "lab07.ex2", "lab07.ex3"], "lab07.ex2", "rotate"),
    "pinhole_project (points)": (LAB09, """
        import time as _time

        def pinhole_project(points, f):
            while True:
                _time.sleep(1)
        """, ["lab09.ex1", "lab09.ex2"], "lab09.ex1", "pinhole_project"),
    "the module's import": (LAB07, """
        import time as _time
        _time.sleep(120)
        """, ["lab07.ex1", "lab07.ex2"], "lab07.ex1", "translate"),
}


class TestASleepingFigureEndsAtTheDeadline:
    @pytest.mark.parametrize("case", SLEEPERS)
    def test_the_sleeper_is_stopped_and_the_figures_after_it_skipped(self, tmp_path, case):
        module, source, selected, sleeper, function = SLEEPERS[case]
        budget = 5 if selected[0] == sleeper else 15
        started = time.monotonic()
        outcomes = by_id(make_figures(submission(tmp_path, module, source), selected, tmp_path / "f",
                                      replace(SLOW, submission_budget=budget)))
        # Stopped by the deadline, not after the 60 s call timeout nor the 120 s sleep (a worker
        # that boots slowly on a busy machine may leave it no time to start: then it is skipped).
        assert time.monotonic() - started < 40
        stopped = outcomes[sleeper]
        assert stopped.path is None
        assert stopped.reason in (f"{function}() was stopped: {SPENT}", f"skipped: {SPENT}"), stopped.reason
        after = selected[selected.index(sleeper) + 1:]
        assert [outcomes[f].reason for f in after] == [f"skipped: {SPENT}"] * len(after)
        before = selected[:selected.index(sleeper)]
        assert all(outcomes[f].path.is_file() for f in before)

    def test_figures_after_grading_get_only_what_is_left(self, tmp_path, capsys, monkeypatch):
        """``grade.py --figures``: grading spends the whole budget (translate sleeps in its checks),
        so the figures have nothing left: each is skipped, in one line, at once."""
        folder = submission(tmp_path, LAB07, SLEEPERS["translate (an image, the first figure)"][1])
        course = tmp_path / "course.json"
        course.write_text(json.dumps({"call_timeout": 60, "submission_budget": 5}))
        monkeypatch.chdir(tmp_path)
        started = time.monotonic()
        status = cli.main(["grade", str(folder), "lab07.ex1", "lab07.ex2", "--no-html", "--config", str(course),
                           "--figures", "figures"])
        assert status == 0 and time.monotonic() - started < 40
        printed = " ".join(capsys.readouterr().out.split())
        assert f"no figure for lab07.ex1, lab07.ex2: skipped: {SPENT}" in printed
        assert list((tmp_path / "figures").iterdir()) == []

    def test_the_command_line_and_a_batch_give_the_figures_the_gradings_limits(self, tmp_path, monkeypatch):
        """The figure pass gets the graded calls' limits (a lane's memory share) and the deadline
        counted from the grading's start, from ``grade.py`` and from a batch's task alike."""
        from autograder.engine import runner
        from autograder.instructor.batch import task

        given = []
        monkeypatch.setattr(figures, "make_figures",
                            lambda folder, selected, out, limits, deadline: given.append((limits, deadline)) or [])
        graded = []
        grade = runner.grade
        monkeypatch.setattr(runner, "grade", lambda *a, **k: graded.append((k["limits"], time.monotonic())) or
                            grade(*a, **k))
        monkeypatch.chdir(tmp_path)
        assert cli.main(["grade", str(REFERENCE), "lab07.ex1", "lab09.ex1", "--no-html", "--figures", "f"]) == 0
        task.grade_files({f"{LAB07}.py": (REFERENCE / f"{LAB07}.py").read_bytes()}, ["lab07.ex1"], 10.0, "none",
                         False, "", "student", rules={"figures": ["lab07.ex1"], "gradings": 3,
                                                      "submission_budget": 50})
        (cli_limits, _), (batch_limits, _) = given
        lanes = cli.lanes_for(["lab07.ex1", "lab09.ex1"])
        assert cli_limits == Limits().shared_by(lanes)  # what each lane's worker had
        assert batch_limits == graded[1][0] and batch_limits.memory <= Limits().memory
        for (limits, deadline), (_, began), selected in zip(given, graded, [["lab07.ex1", "lab09.ex1"], ["lab07.ex1"]]):
            assert began - 1 < deadline - figures.grading_budget(limits, selected) <= began


# ================================================================ memory: the graded calls' share
# Each holds 500 MiB or more for a while (the grader, where no cgroup enforces the share, looks
# every 50 ms): test_hostile_v3's hogs, called from a figure's function, and one of NumPy's.
HOGGING = textwrap.dedent(HOG)
HOGS = {
    "translate, page by page": (LAB07, "lab07.ex1", "translate", HOGGING + textwrap.dedent("""
        def translate(image, tx=100, ty=50):
            page_by_page()
            return image
        """)),
    "pinhole_project, in four children": (LAB09, "lab09.ex1", "pinhole_project", HOGGING + textwrap.dedent("""
        def pinhole_project(points, f):
            in_four_children()
            return points[:, :2]
        """)),
    "rotate, numpy at once": (LAB07, "lab07.ex2", "rotate", """
        def rotate(image, angle_deg=45):
            import time
            import numpy as np
            held = np.ones((500, 2**20), np.uint8)        # touched at once
            time.sleep(10)
            return image
        """),
}


class TestAFigureOverItsMemoryShareIsStoppedLikeAGradedCall:
    @pytest.mark.parametrize("case", HOGS)
    def test_stopped_at_the_lanes_share(self, tmp_path, case, cgroup):  # noqa: F811 - the fixture
        """640 MiB for the submission, graded in two lanes: 320 MiB each. The figure pass has a
        lane's share, and its hog is stopped there, in the words a graded call gets."""
        module, figure_id, function, source = HOGS[case]
        limits = Limits(call_timeout=8.0, memory=640 << 20, address_space=4 << 30).shared_by(2)
        assert limits.memory == 320 << 20
        [outcome] = make_figures(submission(tmp_path, module, source), [figure_id], tmp_path / "f", limits)
        assert outcome.path is None
        assert outcome.reason.startswith(f"{function}() used more than 320 MB of memory"), outcome.reason


# ================================================================ replies: bounded before decoding
REPLY_MIB = FIGURE_REPLY_BYTES // 2**20


# What the figures' calls here may answer: 16 MiB, their inputs being small (supervisor.answer_cap), below the
# figure's own REPLY_MIB, which binds where a figure's input is large.
CALL_MIB = 16


def too_many(function: str, counted: int, largest: tuple) -> str:
    return (f"{function}() returned more numbers in arrays than the {FIGURE_REPLY_ELEMENTS:,} accepted "
            f"({counted:,} counted; the largest array of shape {largest})")


# Each: the figure's reason, or (for a reply over the bytes) what its reason says.
TOO_LARGE = {
    "8 million points": (LAB09, "lab09.ex1", """
        def pinhole_project(points, f):
            import numpy as np
            return np.zeros((8_000_000, 2))
        """, ("pinhole_project() returned ", f"{CALL_MIB} MiB")),
    "6 million points of one byte": (LAB09, "lab09.ex1", """
        def pinhole_project(points, f):
            import numpy as np
            return np.ones((3_000_000, 2), bool)
        """, too_many("pinhole_project", 6_000_000, (3_000_000, 2))),
    "a 3000 x 3000 image": (LAB07, "lab07.ex1", """
        def translate(image, tx=100, ty=50):
            import numpy as np
            return np.zeros((2300, 2300, 3), np.uint8)
        """, too_many("translate", 15_870_000, (2300, 2300, 3))),
    "a float image over the bytes": (LAB07, "lab07.ex1", """
        def translate(image, tx=100, ty=50):
            import numpy as np
            return np.zeros((1500, 1500, 3))
        """, ("translate() returned ", f"{CALL_MIB} MiB")),
    # The worker stops counting where the limit is passed: the photo, then five of the arrays.
    "nested containers, each array small": (LAB09, "lab09.ex5", """
        def project_onto_image(image, P, points_3d):
            import numpy as np
            return image, {"more": [[np.zeros(900_000, np.uint8)] * 3] * 2}
        """, too_many("project_onto_image", 240 * 320 * 3 + 5 * 900_000, (900_000,))),
}


def warm(figure_id: str) -> None:
    """The grader's own first imports and inputs of a figure, made before its memory is measured (the lab suites
    too: loaded by the first figure a process makes, they would count as the grader's holding if measured)."""
    from autograder.engine.registry import discover

    discover()

    def refuse(*args):
        raise figures.FigureUnavailable("warming up")

    with contextlib.suppress(figures.FigureUnavailable):
        figures._discover()[figure_id].make(refuse)


def traced_peak(work):
    """What ``work()`` returns, and the most memory the grader's process allocated meanwhile
    (Python objects and NumPy arrays: tracemalloc sees both)."""
    tracemalloc.start()
    try:
        return work(), tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


class TestAReplyTooLargeForAFigureIsRefusedBeforeItIsDecoded:
    @pytest.mark.parametrize("case", TOO_LARGE)
    def test_refused_with_its_sizes_and_the_grader_stays_small(self, tmp_path, case):
        module, figure_id, source, reason = TOO_LARGE[case]
        folder = submission(tmp_path, module, source)
        warm(figure_id)
        [outcome], peak = traced_peak(lambda: make_figures(folder, [figure_id], tmp_path / "f"))
        assert outcome.path is None
        if isinstance(reason, str):
            assert outcome.reason == reason
        else:
            assert outcome.reason.startswith(reason[0]) and reason[1] in outcome.reason, outcome.reason
        # The reply is tens to hundreds of MB; the grader never held it (its own inputs: ~1 MB).
        assert peak < 8 * 2**20, peak

    def test_a_forged_reply_is_refused_on_its_header_before_its_arrays_are_read(self, tmp_path):
        """The worker's own encoder refuses a value too large; a submission that writes a frame to
        the grader's pipe itself is refused on the header, its 30 MB of arrays never read."""
        folder = tmp_path / "module"
        folder.mkdir()
        (folder / "m.py").write_text(textwrap.dedent("""
            import json, os, struct, sys, time

            def forged(n):
                header = json.dumps({"d": [["ok", True], ["value", {"a": 0, "dtype": "|b1", "shape": [n]}]]}).encode()
                frame = b"AGT1" + struct.pack(">Q", len(header)) + header + bytes(n)
                os.write(int(sys.argv[2]), struct.pack(">Q", len(frame)) + frame)
                time.sleep(30)

            def fine():
                return 1
            """))
        with Sandbox(folder, figure_limits(Limits(call_timeout=20.0))) as box:
            assert box.call("m", "fine").value == 1
            outcome, peak = traced_peak(lambda: box.call("m", "forged", (12_000_000,)))   # (12 MB: under the call's 16 MiB)
            assert (outcome.kind, outcome.message) == ("result_type", too_many("forged", 12_000_000, (12_000_000,)))
            assert peak < 4 * 2**20, peak
            assert outcome.seconds < 20  # refused at once, not waited out
            assert box.call("m", "fine").value == 1  # a fresh worker

    def test_counting_a_header_is_bounded_by_its_size_whatever_it_claims(self):
        """The count reads shapes as decode takes them: a shape decode would refuse counts nothing."""
        def header(tree):
            return json.dumps(tree).encode()

        assert transport.count_elements(header({"a": 0, "dtype": "<f8", "shape": [2**62, 2**62]})) == \
            (2**124, (2**62, 2**62))
        assert transport.count_elements(header({"a": 0, "dtype": "<f8", "shape": [2**63] * 3})) == (0, ())
        assert transport.count_elements(header({"a": 0, "dtype": "<f8", "shape": [2] * 33})) == (0, ())
        assert transport.count_elements(header({"l": [{"a": 0, "dtype": "|u1", "shape": [3, 4]},
                                                      {"d": [["k", {"a": 1, "dtype": "|u1", "shape": [5]}]]}]})) \
            == (17, (3, 4))
        deep = b"[" * 100_000 + b"]" * 100_000
        with pytest.raises(transport.TransportError):
            transport.count_elements(deep)
        with pytest.raises(transport.TransportError, match="header larger"):
            transport.count_elements(b" " * (transport.MAX_HEADER_BYTES + 1))


# ================================================================ drawing: thinned before Matplotlib
MANY_POINTS = {
    "a million projections": (LAB09, "lab09.ex1", """
        def pinhole_project(points, f):
            import numpy as np
            return np.random.default_rng(0).normal(size=(1_000_000, 2))
        """, "pinhole_project(cube, f=1)", "projection", 1_000_000),
    "a cloud of 3D points": (LAB09, "lab09.ex2", """
        def project_with_intrinsics(K, points_3d):
            import numpy as np
            return np.random.default_rng(1).uniform(0, 300, (250_001, 2)).astype(np.float32)
        """, "pixels; grey: the 320 x 240 image", "projection", 250_001),
}


class TestPointsAreThinnedBeforeTheyAreDrawn:
    @pytest.mark.parametrize("case", MANY_POINTS)
    def test_a_figure_of_many_points_is_made_and_says_how_many_were_drawn(self, tmp_path, case):
        module, figure_id, source, panel, label, count = MANY_POINTS[case]
        folder = submission(tmp_path, module, source)
        [outcome] = make_figures(folder, [figure_id], tmp_path / "f")
        assert outcome.path.is_file() and cv2.imread(str(outcome.path)) is not None
        assert outcome.note == (f"your figure's panel “{panel}” has {count:,} points of “{label}”; "
                                f"at most {MAX_POINTS_DRAWN:,} are drawn.")

    def test_drawing_costs_what_the_points_drawn_cost(self):
        """render_png draws at most MAX_POINTS_DRAWN of a set, whoever made the panel."""
        panel = figures.Panel("many", points={"p": np.zeros((2_000_000, 2))})
        _, peak = traced_peak(lambda: figures.render_png("t", [panel]))
        assert peak < 64 * 2**20, peak  # the set itself is 32 MB; drawn whole, hundreds of MB

    def test_estimate_pose_returning_a_million_corners_draws_a_bounded_number(self, tmp_path):
        folder = submission(tmp_path, "lab10_camera2", """
            def estimate_pose(image, pattern_size, square_size, K, dist=None):
                import numpy as np
                return np.zeros(3), np.zeros(3), np.full((1_000_000, 2), 50.0)
            """)
        [outcome] = make_figures(folder, ["lab10.ex6"], tmp_path / "f")
        assert outcome.path.is_file() and outcome.reason == ""


# ================================================================ the reference's figures
class TestNormalFiguresStillWork:
    @pytest.mark.parametrize("selected", [["lab07.ex1", "lab07.ex2"], ["lab09.ex1", "lab09.ex4", "lab09.ex5"],
                                          ["lab08.ex3"]])
    def test_the_reference_makes_every_figure_without_notes(self, tmp_path, selected):
        limits = Limits().shared_by(2)
        outcomes = make_figures(REFERENCE, selected, tmp_path / "f", limits, time.monotonic() + 120)
        assert [(o.reason, o.note) for o in outcomes] == [("", "")] * len(outcomes)
        assert all(cv2.imread(str(o.path)) is not None for o in outcomes)

    def test_the_figure_limits_are_the_graded_calls_with_the_reply_caps(self):
        graded = Limits(memory=1 << 30, call_timeout=3.0, extra_processes=7).shared_by(2)
        limits = figure_limits(graded)
        assert (limits.memory, limits.call_timeout, limits.extra_processes, limits.threads) == \
            (graded.memory, 3.0, 7, graded.threads)
        assert (limits.max_result_bytes, limits.max_result_elements) == (FIGURE_REPLY_BYTES, FIGURE_REPLY_ELEMENTS)
        stricter = figure_limits(Limits(max_result_bytes=1 << 20, max_result_elements=10))
        assert (stricter.max_result_bytes, stricter.max_result_elements) == (1 << 20, 10)
