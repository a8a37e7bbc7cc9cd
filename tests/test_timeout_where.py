"""A call stopped for its time says where it was (issue 35: a relayed fault says which line, and why): the
worker writes its Python stack shortly before the deadline; only the submission's own frames are named."""

from __future__ import annotations

import re
import textwrap

from autograder.sandbox.supervisor import Limits, Sandbox, where_stopped

HANGING = textwrap.dedent("""
    import numpy as np

    def spin():
        while True:
            pass

    def solve_inf():
        A = np.eye(4)
        A[0, 0] = np.inf
        return np.linalg.svd(A)
    """)


def test_a_call_stopped_for_its_time_says_its_line_and_the_library_call_it_was_in(tmp_path):
    (tmp_path / "hanging.py").write_text(HANGING)
    with Sandbox(tmp_path, Limits(call_timeout=1.5)) as sandbox:
        spun = sandbox.call("hanging", "spin")
        assert spun.kind == "timeout" and re.search(r"it was at line [56] of your `spin` \(hanging.py\)", spun.message)
        stuck = sandbox.call("hanging", "solve_inf")
    assert stuck.kind == "timeout" and "line 11 of your `solve_inf` (hanging.py), inside NumPy's `svd`" in stuck.message
    assert "inf or NaN" in stuck.message


def test_only_the_submission_s_frames_are_named_and_forged_text_is_bounded():
    dump = ('Thread 0x1 (most recent call first):\n'
            '  File "/s/worker/worker.py", line 500 in handle_call\n'
            '  File "/etc/passwd", line 1 in secret\n')
    assert where_stopped(dump, {"lab.py"}) == ""
    forged = 'Current thread 0x1 (most recent call first):\n  File "/x/submission/lab.py", line 3 in f; rm -rf\n'
    assert where_stopped(forged, {"lab.py"}) == ""
