"""Faults told in one true sentence, and charged to the code that caused them (issue 34).

- A value the worker cannot send back -- too large, of a type that cannot cross, an object
  array, a value that contains itself, one nested or spread too far, one whose own methods
  raise, exit or recurse -- is that call's failure, in a sentence that names what the
  function returned and why it cannot cross; the worker stays alive for the next call. A
  worker that ends while its reply is on the way is told as such.
- A memory bomb costs only the function that allocated: memory a call keeps (a global) is
  not the next function's missing memory, and a function stopped twice for its memory is
  not called again.
- A grading's deadline scales with what is selected (:meth:`Limits.budget_for`): a slow
  loris graded on one lab ends within that lab's time, not the whole submission's.

Limits are small so that the file stays fast; sizes are bounded.
"""

import re
import textwrap

import numpy as np
import pytest

from autograder.engine.registry import select
from autograder.engine.runner import grade
from autograder.sandbox import transport
from autograder.sandbox.supervisor import Limits
from conftest import REFERENCE, mutant
from test_hostile_v3 import LAB07, LAB09, SLOW_LORIS, assert_no_grader_error, cgroup, messages, sandbox_for  # noqa: F401

CROSS = "only arrays, numbers, strings, and lists, tuples and string-keyed dicts of those can cross"

UNSENDABLE = """
    import os, sys, threading, time
    import numpy as np

    def fine():
        return 1

    def too_large():
        return np.zeros(2**20)                               # 8 MiB, over the 4 MiB cap below

    def broadcast():
        return np.broadcast_to(np.zeros(1), (2**10, 2**10))  # 8 bytes of memory, 8 MiB to send

    def a_set():
        return {1, 2}

    def a_generator():
        return (i for i in range(3))

    def objects():
        return np.array([object(), object()])

    def half_floats():
        return np.ones(3, np.float16)

    def contains_itself():
        x = [1]
        x.append({"next": x})
        return x

    def nested():
        x = []
        for _ in range(100):
            x = [x]
        return x

    def many_numbers():
        return list(range(2 * 10**6))

    def long_text():
        return "x" * (5 * 2**20)

    def non_string_keys():
        return {"H": {1: 2.0}}

    class ArrayLike:
        def __array__(self, *args, **kwargs):
            raise RuntimeError("no array here")

    def array_like():
        return [np.eye(3), ArrayLike()]

    class Exits(float):
        def __getattribute__(self, name):
            raise SystemExit(3)
        def __reduce__(self):
            os._exit(4)

    def exits():
        return Exits(1.0)

    class Loops(dict):
        def __getattr__(self, name):
            return getattr(self, name)
        def items(self):
            return self.items()

    def loops():
        return Loops(a=1)

    class Interrupts(np.ndarray):
        def __getattribute__(self, name):
            raise KeyboardInterrupt

    def array_subclass():
        return np.zeros(3).view(Interrupts)

    class Meta(type):
        def __getattribute__(cls, name):
            raise SystemExit(5)

    class Sneaky(metaclass=Meta):
        pass

    def sneaky():
        return Sneaky()

    class Unprintable(Exception):
        def __str__(self):
            raise SystemExit(6)

    def unprintable():
        raise Unprintable()

    def long_exception():
        raise ValueError("x" * (5 * 2**20))
    """


@pytest.fixture(scope="module")
def box(tmp_path_factory):
    """One worker for every unsendable reply: each must leave it alive."""
    limits = Limits(call_timeout=10.0, max_result_bytes=4 * 2**20)
    with sandbox_for(tmp_path_factory.mktemp("unsendable"), UNSENDABLE, limits) as box:
        assert box.call("m", "fine").value == 1
        yield box


class TestUnsendableReplies:
    """Every kind of reply the worker cannot send: one true sentence, and the same worker answers
    the next call."""

    CASES = {
        "too_large": "returned a float64 array of shape (1048576,) (8 MiB), which cannot be sent back: "
                     "it is more than the 4 MiB a result may be",
        "broadcast": "returned a float64 array of shape (1024, 1024) (8 MiB), which cannot be sent back: "
                     "it is more than the 4 MiB a result may be",
        "a_set": f"returned a set, which cannot be sent back: {CROSS} (make it a list: list(...))",
        "a_generator": f"returned a generator, which cannot be sent back: {CROSS} (make it a list: list(...))",
        "objects": "returned an object array of shape (2,) (16 bytes), which cannot be sent back: arrays of "
                   "dtype object cannot cross; use a numeric or bool dtype",
        "half_floats": "returned a float16 array of shape (3,) (6 bytes), which cannot be sent back: arrays of "
                       "dtype float16 cannot cross; use float32 or float64",
        "contains_itself": "returned a list of 2 items, which cannot be sent back: its item [1]['next'] is that "
                           "list itself (it contains itself, so it has no end)",
        "nested": "returned a list of 1 item, which cannot be sent back: it is nested deeper than 64 levels; "
                  "at most 64 can cross",
        "many_numbers": "returned a list of 2000000 items, which cannot be sent back: it holds more than 4 MiB "
                        "of numbers and text outside arrays; at most that can cross (return an array)",
        "long_text": "returned a string of 5242880 characters, which cannot be sent back: it holds more than "
                     "4 MiB of numbers and text outside arrays; at most that can cross (return an array)",
        "non_string_keys": "returned a dict of 1 item, which cannot be sent back: its item ['H'] is a dict of "
                           "1 item: its keys must be strings, and one is an int (non-string keys cannot cross)",
        "array_like": f"returned a list of 2 items, which cannot be sent back: its item [1] is a m.ArrayLike: "
                      f"{CROSS}",
        "exits": f"returned a m.Exits (a float subclass), which cannot be sent back: {CROSS}",
        "loops": f"returned a m.Loops (a dict subclass), which cannot be sent back: {CROSS}",
        "array_subclass": "returned a m.Interrupts (a numpy.ndarray subclass), which cannot be sent back: an "
                          "ndarray subclass cannot cross; return a plain numpy.ndarray (np.asarray(x))",
        "sneaky": f"returned a m.Sneaky, which cannot be sent back: {CROSS}",
    }

    @pytest.mark.parametrize("function", CASES)
    def test_the_sentence_names_what_was_returned_and_the_worker_stays(self, box, function):
        worker = box.proc.pid
        outcome = box.call("m", function)
        assert (outcome.kind, outcome.message) == ("result_type", f"{function}() {self.CASES[function]}")
        assert box.call("m", "fine").value == 1
        assert box.proc.pid == worker  # the same worker: nothing ended it

    def test_an_exception_that_cannot_be_printed_or_is_huge_is_still_told(self, box):
        worker = box.proc.pid
        outcome = box.call("m", "unprintable")
        assert (outcome.kind, outcome.message) == \
            ("exception", "unprintable() raised Unprintable: (its message could not be read: str() of it raised)")
        outcome = box.call("m", "long_exception")
        assert outcome.kind == "exception"
        assert outcome.message.startswith("long_exception() raised ValueError: xxx")
        assert box.call("m", "fine").value == 1
        assert box.proc.pid == worker

    def test_refusals_are_told_before_the_value_is_walked_or_copied(self):
        """The encoder's own sentences, in the grader's process: what the worker uses."""
        with pytest.raises(transport.TransportError) as refused:
            transport.encode({"ok": True, "value": [np.zeros(3), {"k": (1, {2})}]})
        assert str(refused.value).endswith("its item ['value'][1]['k'][1] is a set: " + CROSS +
                                           " (make it a list: list(...))")
        assert transport.size_words(5) == "5 bytes" and transport.size_words(3 * 2**20 // 2) == "1.5 MiB"


SENDING = """
    import os, sys, threading, time
    import numpy as np

    def _when_sending(then):
        main = threading.main_thread().ident

        def watch():
            for _ in range(20000):                           # 10 s at most
                frame = sys._current_frames().get(main)
                if frame is not None and frame.f_code.co_name == "write_frame" \\
                        and len(frame.f_locals.get("frame", b"")) > 2**20:
                    then()
                time.sleep(0.0005)
        threading.Thread(target=watch, daemon=True).start()

    def exit_while_sending(given):
        _when_sending(lambda: os._exit(3))
        return np.ones(64 * 2**20, np.uint8)

    def contiguous(mb, given):
        return np.ones(mb * 2**20, np.uint8)

    def strided(mb, given):
        return np.ones((mb, 2, 2**20), np.uint8)[:, 0]    # half of what it holds, not contiguous

    def fine():
        return 1
    """


# (a reply may hold 64 times what its call is given: 2 MiB given allows these replies of up to 128 MiB)
GIVEN = np.zeros(2 << 20, np.uint8)


class TestRepliesOnTheirWay:
    def test_a_worker_ending_while_it_sends_is_told_so(self, tmp_path):
        """The grader read the reply's length: the call had returned; the worker ended after."""
        with sandbox_for(tmp_path, SENDING, Limits(call_timeout=10.0)) as box:
            outcome = box.call("m", "exit_while_sending", (GIVEN,))
            assert (outcome.kind, outcome.message) == (
                "crashed", "exit_while_sending() returned 64 MiB, and the worker ended (exit code 3) while "
                           "sending it back; a thread or process your code left running can end it")
            assert box.call("m", "fine").value == 1

    def test_sending_a_result_costs_next_to_no_memory_beyond_it(self, tmp_path):
        """A result of 80 MB, and one of 64 MB cut from 128 MB, in a worker of 300 MB: sent from the
        array's own memory, or copied a few MiB at a time (one joined frame was three copies)."""
        with sandbox_for(tmp_path, SENDING, Limits(call_timeout=20.0, memory=300 << 20)) as box:
            for function, mb, size in (("contiguous", 80, 80 << 20), ("strided", 64, 64 << 20)):
                outcome = box.call("m", function, (mb, GIVEN))
                assert outcome.ok, outcome.message
                assert outcome.value.nbytes == size and outcome.value.min() == 1


MEMORY = """
    import numpy as np
    _kept = []

    def keep(mb):                                            # a cache that grows, in a global
        _kept.append(np.ones(mb * 2**20, np.uint8))
        return len(_kept)

    def use(mb):
        block = np.ones(mb * 2**20, np.uint8)
        return int(block[::4096].sum())

    def bomb():
        held = []
        for _ in range(64):                                  # 64 x 32 MiB, touched: far over the limit
            held.append(np.ones(32 * 2**20, np.uint8))
        return len(held)
    """

# Lab 9 with one function that allocates without end: 10 GiB, 64 MiB at a time, every page touched.
LAB09_BOMB = """
    _intrinsic_matrix = intrinsic_matrix

    def intrinsic_matrix(f, px, py):
        held = []
        for _ in range(160):
            held.append(np.ones(64 * 2**20, np.uint8))
        return _intrinsic_matrix(f, px, py)
    """


class TestMemoryBombs:
    LIMITS = Limits(call_timeout=10.0, memory=384 << 20)

    def test_memory_a_call_keeps_is_not_the_next_functions_missing(self, tmp_path, cgroup):
        """A call that keeps 200 MB of 384 in a global: the next call of another function gets a
        worker with all of its memory (it was told "used more than 384 MB" before)."""
        with sandbox_for(tmp_path, MEMORY, self.LIMITS) as box:
            assert box.call("m", "keep", (200,)).value == 1
            outcome = box.call("m", "use", (200,))
            assert outcome.ok, outcome.message
            assert box.call("m", "keep", (50,)).value == 1  # a fresh worker: the module imported again

    def test_memory_kept_by_earlier_calls_is_told_with_a_bomb(self, tmp_path, cgroup):
        """70 MB kept (less than a quarter of 384: the worker stays), then a bomb: its sentence says
        how much was already held when it was called."""
        with sandbox_for(tmp_path, MEMORY, self.LIMITS) as box:
            assert box.call("m", "keep", (70,)).value == 1
            outcome = box.call("m", "bomb")
            kept = re.fullmatch(r"bomb\(\) used more than 384 MB of memory \((\d+) MB of it already held when "
                                r"it was called, kept by earlier calls\)", outcome.message)
            assert outcome.kind == "memory" and kept and 65 <= int(kept[1]) <= 80, outcome.message

    def test_a_bomb_is_charged_twice_then_not_called_again(self, tmp_path, cgroup):
        with sandbox_for(tmp_path, MEMORY, self.LIMITS) as box:
            for _ in range(2):
                outcome = box.call("m", "bomb")
                assert (outcome.kind, outcome.message) == ("memory", "bomb() used more than 384 MB of memory")
                assert box.call("m", "use", (100,)).ok
            worker = box.proc.pid
            outcome = box.call("m", "bomb")
            assert (outcome.kind, outcome.message) == \
                ("memory", "bomb() ran out of memory 2 times already; not called again")
            assert box.proc.pid == worker and box.call("m", "use", (100,)).ok

    def test_a_memory_bomb_in_one_lab_9_function_leaves_the_others_graded(self, tmp_path):
        """intrinsic_matrix allocates 10 GiB: its checks score 0 for its memory; every other check
        of lab 9 (project_with_intrinsics in the same exercise included) passes."""
        submission = mutant(tmp_path, LAB09, textwrap.dedent(LAB09_BOMB))
        result = grade(submission, ["lab09"], limits=Limits(call_timeout=10.0, memory=512 << 20),
                       pictures="none")
        assert_no_grader_error(result)
        failed = [(exercise.id, check.name, check.message) for exercise in result.exercises
                  for check in exercise.checks if check.score < check.max_score]
        assert failed and all(exercise_id == "lab09.ex2" and "intrinsic_matrix" in name
                              and "intrinsic_matrix() " in message and "memory" in message
                              for exercise_id, name, message in failed), failed
        assert any(check.name.startswith("project_with_intrinsics") and check.score == check.max_score
                   for exercise in result.exercises for check in exercise.checks)


class TestBudgetScalesWithSelection:
    def test_a_lab_has_a_third_of_the_submissions_time(self):
        limits = Limits()
        assert limits.budget_for(select(["lab07"])) == 80
        assert limits.budget_for(select(["lab07.ex4"])) == 80
        assert limits.budget_for(select(["lab07", "lab09"])) == 160
        assert limits.budget_for(select([])) == 240  # never more than the submission's
        assert Limits(lab_budget=10, exercise_budget=5).budget_for(select(["lab07", "lab08"])) == 20
        assert Limits(lab_budget=10, exercise_budget=30).budget_for(select(["lab07"])) == 30  # an exercise's at least

    def test_a_slow_loris_graded_on_lab_7_ends_within_lab_7s_time(self, tmp_path):
        """Every call sleeps just under its timeout: grading lab 7 alone ends at a third of the
        submission's 24 s, and says so (8 s: past two exercises' 3 s budgets, well before 24)."""
        source = textwrap.dedent(SLOW_LORIS["sleeps"]) + textwrap.dedent("""
            for _name, _function in list(globals().items()):
                if callable(_function) and not _name.startswith("_") and getattr(_function, "__module__", "") == __name__:
                    globals()[_name] = _slowly(_function)
            """)
        submission = mutant(tmp_path, LAB07, source)
        (submission / f"{LAB09}.py").write_text((REFERENCE / f"{LAB09}.py").read_text())
        limits = Limits(call_timeout=1.0, import_timeout=4.0, exercise_budget=3.0, submission_budget=24.0)
        result = grade(submission, ["lab07"], limits=limits, pictures="none")
        assert_no_grader_error(result)
        assert "time budget exhausted (the submission's 8 s)" in " ".join(
            messages(result, exercise.id) for exercise in result.exercises)
        assert result.seconds < limits.submission_budget  # (8 s and a call's timeout, on a busy machine more)
