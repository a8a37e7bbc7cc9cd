"""Hidden checks draw their inputs per submission (``t.rng``, :meth:`Inputs.generator`): a
hidden input that leaked from one grading is not the next submission's, while the same
files (and course secret) meet the same inputs on every run.

Each hidden check is run on the reference solutions under two submissions' inputs (one
with a course secret); the reference passes every one, the calls each check makes (its
``inputs_digest``) differ between the two, and the same inputs give the same calls again.
A realistic wrong submission (cases of the mistakes tables) still fails its exercise's
hidden check whatever it draws (how it is named is ``autograder verify``'s judgement).
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from autograder.engine.inputs import Inputs
from autograder.engine.registry import discover
from autograder.engine.runner import run_check
from autograder.sandbox.supervisor import Sandbox
from conftest import REFERENCE, mutant

# Two submissions' inputs: other content, and the second under a course secret.
DRAWS = (Inputs.for_submission("1" * 64, secret=""), Inputs.for_submission("2" * 64, secret="course secret"))


BUILT_IN = [f"lab{n:02d}" for n in range(7, 13)]


def hidden_checks(lab_key: str | None = None) -> list:
    """The hidden graded checks of every built-in lab (or of ``lab_key``)."""
    labs = discover()
    return [check for key in BUILT_IN if lab_key in (None, key) for exercise in labs[key].exercises.values()
            for check in exercise.checks if check.hidden and not check.advice]


def graded(folder, checks, inputs) -> dict:
    """Check id -> its CheckResult, ``checks`` run in one fresh worker (as one grading's hidden
    phase is) under ``inputs``."""
    with Sandbox(folder) as sandbox:
        return {check.id: run_check(sandbox, check, "none", inputs=inputs) for check in checks}


@pytest.fixture(scope="module")
def reference_draws() -> list[dict]:
    """Every hidden check on the reference, under each of DRAWS."""
    checks = hidden_checks()
    return [graded(REFERENCE, checks, inputs) for inputs in DRAWS]


# ------------------------------------------------------------------ the generator
def test_the_generator_follows_the_content_the_secret_and_the_check():
    def draws(inputs, check_id="lab07.ex2.rotate"):
        return inputs.generator(check_id).uniform(size=4).tolist()

    content = "ab" * 32
    plain = Inputs.for_submission(content, secret="")
    assert draws(plain) == draws(Inputs.for_submission(content, secret=""))    # every run, every machine
    others = [draws(Inputs.for_submission("cd" * 32, secret="")), draws(Inputs.for_submission(content, secret="s")),
              draws(plain, "lab07.ex3.scale"), plain.generator("lab07.ex2.rotate", "another purpose").uniform(size=4).tolist()]
    assert all(other != draws(plain) for other in others) and len({tuple(o) for o in others}) == len(others)
    # Apart from the properties' seeds: not the generator Hypothesis's seed would make.
    seeded = np.random.default_rng(plain.seed("lab07.ex2.rotate", 0)).uniform(size=4).tolist()
    assert seeded != draws(plain)


# ------------------------------------------------------------------ the reference, any draw
def test_every_hidden_check_is_graded_and_the_reference_passes_it_under_any_submissions_inputs(reference_draws):
    checks = hidden_checks()
    assert len(checks) >= 30
    for results in reference_draws:
        assert set(results) == {check.id for check in checks}
        failing = [f"{check_id}: {result.status}: {result.message[:200]}" for check_id, result in results.items()
                   if not result.passed]
        assert not failing, "\n".join(failing)


def test_the_vetted_scenes_are_of_hidden_checks_and_the_reference_passes_a_sample_of_them():
    """The scenes make_vetted kept (on which the reference and the sheet's recipe got full marks): each key a
    hidden check, hundreds of scenes each (a submission's draw stays its own), and a sample graded again."""
    from autograder.labs.hidden._draws import vetted
    from autograder.labs.hidden._vetted import VETTED

    ids = {check.id: check for check in hidden_checks()}
    assert VETTED and set(VETTED) <= set(ids)
    assert all(len(set(scenes)) >= 200 for scenes in VETTED.values())
    rng = np.random.default_rng(5)
    assert vetted(rng, "no such check") is rng
    for content in ("a" * 64, "b" * 64):   # (two more submissions' draws, through the vetted scenes)
        results = graded(REFERENCE, [ids[key] for key in VETTED], Inputs.for_submission(content, secret="sample"))
        failing = [f"{key}: {result.message[:300]}" for key, result in results.items() if not result.passed]
        assert not failing, "\n".join(failing)


def test_a_rendered_pair_drawn_for_one_submission_is_not_kept():
    from autograder.labs.hidden.lab11 import drawn_scene
    from fixtures import lab11 as truth

    kept = dict(truth._PAIRS)
    pair = drawn_scene(np.random.default_rng(3))
    assert pair.img1.shape == (240, 320, 3) and truth._PAIRS == kept


def test_other_submissions_draw_other_hidden_inputs(reference_draws):
    first, second = reference_draws
    same = [check_id for check_id in first if first[check_id].inputs_digest == second[check_id].inputs_digest]
    assert not same, f"hidden checks with the same inputs for two submissions: {same}"
    assert all(result.inputs_digest for result in first.values())


def test_the_same_submission_draws_the_same_hidden_inputs_again(reference_draws):
    """A new worker, the same inputs: the same calls (what ``autograder verify`` compares)."""
    checks = hidden_checks("lab07") + hidden_checks("lab10")
    again = graded(REFERENCE, checks, DRAWS[1])
    assert {check.id: again[check.id].inputs_digest for check in checks} == {
        check.id: reference_draws[1][check.id].inputs_digest for check in checks}


# ------------------------------------------------------------------ a wrong submission still fails
# (lab, mistakes-table case): cases whose hidden check fails them on every input measured.
WRONG = [("lab07", "rotation the wrong way"), ("lab07", "sy ignored"), ("lab10", "no sign fix"),
         ("lab12", "depth b / (f d)")]


@pytest.mark.parametrize("lab_key, case", WRONG)
def test_a_realistic_mistake_fails_its_exercises_hidden_check_whatever_it_draws(tmp_path, lab_key, case,
                                                                             no_naming):
    """(Naming off: what is asserted is the verdict on each draw; how it is named is verify's.)"""
    lab = discover()[lab_key]
    exercise, source = importlib.import_module(f"autograder.labs.mistakes.{lab_key}").MISTAKES[case][:2]
    folder = mutant(tmp_path, lab.module, source)
    checks = [check for check in hidden_checks(lab_key) if check.exercise.id == exercise]
    assert checks
    for inputs in DRAWS:
        for check_id, result in graded(folder, checks, inputs).items():
            assert not result.passed and result.score == 0, (check_id, result.message)
