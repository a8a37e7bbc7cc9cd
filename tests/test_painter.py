"""Pictures drawn on other threads while grading goes on (autograder.engine.runner.Painter): the same
pictures as drawn at once, never a verdict changed by a picture, never student code called
from a drawing thread."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from autograder.engine.registry import select
from autograder.engine.runner import Painter, run_check
from test_cache import InProcess, _reference


def _lab07_checks():
    return [c for ex in select(["lab07.ex1", "lab07.ex2"]) for c in ex.checks if not c.advice]


def test_pictures_drawn_on_threads_are_those_drawn_at_once():
    module = _reference("lab07_transformations")
    at_once = [run_check(InProcess(module), check) for check in _lab07_checks()]
    with Painter() as painter:
        later = [run_check(InProcess(module), check, painter=painter) for check in _lab07_checks()]
        painter.finish()
    assert sum(len(r.artifacts) for r in at_once) >= 4
    assert [r.to_dict() | {"seconds": 0} for r in later] == [r.to_dict() | {"seconds": 0} for r in at_once]


def _check_drawing(draw):
    """A lab07.ex1 check that passes and attaches one picture drawn by ``draw(t)``."""
    template = _lab07_checks()[0]

    def draws(t):
        t.images("a picture", fine=np.zeros((4, 4), np.uint8), drawn=lambda: draw(t))

    draws.__name__ = "draws"
    return replace(template, func=draws)


def test_a_picture_that_cannot_be_drawn_is_left_out_and_the_verdict_kept(caplog):
    with Painter() as painter:
        later = run_check(InProcess(None), _check_drawing(lambda t: 1 / 0), painter=painter)
        painter.finish()
    at_once = run_check(InProcess(None), _check_drawing(lambda t: 1 / 0))
    for result in (later, at_once):
        assert result.status == "passed" and result.score == result.max_score
        assert result.artifacts == []
    assert "ZeroDivisionError" in caplog.text


def test_a_drawing_never_calls_student_code(caplog):
    sandbox = InProcess(_reference("lab07_transformations"))
    with Painter() as painter:
        result = run_check(sandbox, _check_drawing(lambda t: t.call("translation_matrix", 1, 2)),
                           painter=painter)
        painter.finish()
    assert sandbox.calls == 0 and result.status == "passed" and result.artifacts == []
    assert "never while a picture is drawn" in caplog.text
