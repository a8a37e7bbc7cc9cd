"""No verdict rests on bytes the graded code could have written: the store of ground truth and
recorded examples (autograder.sandbox.cache) trusts an entry only under its key's HMAC, and a worker
that runs as the grader's user (process-group) neither finds that key nor leaves behind anything a
later grading trusts. And a grader started through a relative interpreter path still confines."""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from autograder.sandbox import cache, confine, supervisor as sandbox, transport
from autograder.engine import examples, runner
from autograder.engine.checks import Fail, Trial
from autograder.engine.inputs import Inputs
from autograder.engine.registry import select
from autograder.engine.results import GradingResult
from autograder.loading.submission import load_submission
from conftest import REFERENCE, ROOT, mutant
from test_cache import InProcess, _reference

MODULE = "lab07_transformations"
PROPERTY = "translation_matrix for any tx, ty"


@pytest.fixture
def store(tmp_path, monkeypatch):
    monkeypatch.setenv("AUTOGRADER_CACHE_DIR", str(tmp_path / "store"))
    return tmp_path / "store"


calls = []


@cache.persistent
def _truth(n: int):
    calls.append(n)
    return np.arange(n, dtype=np.float64) * 0.5


def _entries(store: Path, name: str) -> list[Path]:
    return sorted(p for p in (store / name).rglob("*") if p.is_file())


def _rewrite(entry: Path, change, authenticate) -> None:
    """Decode ``entry``, ``change`` its value, and write it back behind ``authenticate(frame)``."""
    frame = transport.encode(change(transport.decode(entry.read_bytes()[32:])))
    entry.write_bytes(authenticate(frame) + frame)


def _sha256(frame: bytes) -> bytes:  # what anyone can recompute (the store's old checksum)
    return hashlib.sha256(frame).digest()


def _other_key(frame: bytes) -> bytes:
    import hmac

    return hmac.new(b"k" * 32, frame, hashlib.sha256).digest()


@pytest.mark.parametrize("authenticate", [_sha256, _other_key])
def test_changed_ground_truth_is_computed_again(store, authenticate):
    calls.clear()
    with cache.enabled():
        expected = _truth(7)
        [entry] = _entries(store, f"{__name__}._truth")
        _rewrite(entry, lambda value: value + 1.0, authenticate)
        again = _truth(7)
    assert calls == [7, 7] and np.array_equal(again, expected)


def _translation_property():
    [exercise] = select(["lab07.ex1"])
    return next(c for c in exercise.checks if c.name == PROPERTY)


def _run(check, sandbox_):
    try:
        check.func(Trial(sandbox_, check))
    except Fail as failure:
        return failure.message
    return "passed"


@pytest.mark.parametrize("authenticate", [_sha256, _other_key])
def test_recorded_examples_cut_to_one_are_not_replayed(store, authenticate):
    check, module = _translation_property(), _reference(MODULE)
    with cache.enabled():
        assert _run(check, InProcess(module)) == "passed"      # records its examples
        [entry] = _entries(store, examples.NAME)
        _rewrite(entry, lambda drawn: drawn[:1], authenticate)
        wrong_after_one = InProcess(module, wrong_from=2)
        assert _run(check, wrong_after_one) != "passed"        # drawn again: the second example fails
    assert wrong_after_one.calls > 1


def test_an_entry_moved_to_another_name_is_not_trusted(store):
    calls.clear()
    with cache.enabled():
        _truth(3), _truth(4)
        first, second = _entries(store, f"{__name__}._truth")
        first_bytes = first.read_bytes()
        first.write_bytes(second.read_bytes())
        second.write_bytes(first_bytes)
        _truth(3), _truth(4)
    assert sorted(calls) == [3, 3, 4, 4]


@pytest.mark.parametrize("spoil", ["readable by others", "too short", "a link"])
def test_a_key_file_that_is_not_ours_alone_is_replaced_and_nothing_under_it_trusted(store, spoil):
    calls.clear()
    with cache.enabled():
        _truth(5)
    cache._keys.clear()  # the key forgotten in memory, as a new process starts
    key = store / "key"
    if spoil == "readable by others":
        key.chmod(0o644)
    elif spoil == "too short":
        key.write_bytes(key.read_bytes()[:16])
    else:
        (store / "elsewhere").write_bytes(key.read_bytes())
        key.unlink()
        key.symlink_to(store / "elsewhere")
    with cache.enabled():
        _truth(5)
    assert calls == [5, 5]
    assert not key.is_symlink() and key.stat().st_mode & 0o077 == 0 and key.stat().st_size == 32


def test_revoking_forgets_every_entry(store):
    calls.clear()
    with cache.enabled():
        _truth(6)
        _truth(6)
        cache.revoke()
        assert not (store / "key").exists()
        _truth(6)
    assert calls == [6, 6]


# ------------------------------------------------------------------ the measured attack
class _Strategy(Exception):
    pass


class _Capture:
    """Stands in for the trial to read the property's strategy (what keys its examples)."""

    def for_all(self, strategy, body, *, max_examples=None, describe=repr):
        raise _Strategy(strategy, max_examples)


def _poisoned_entry(store: Path, target: Path) -> tuple[Path, bytes]:
    """Where the examples of the translation property are kept for the submission ``target``
    (whose content, and so inputs, anyone can know without a course secret), and a list of
    one example, (0.0, 0.0), which a wrong translation_matrix gets right."""
    check = _translation_property()
    with pytest.raises(_Strategy) as asked:
        check.func(_Capture())
    strategy, max_examples = asked.value.args
    with load_submission(target, [MODULE]) as submission:
        seed = Inputs.for_submission(submission.content_hash).seed(check.id, 0)
    with cache.enabled():
        version, key = examples.key(check, 0, strategy, max_examples, seed)
    return store / examples.NAME / version / cache._hashed(key), transport.encode([(0.0, 0.0)])


def _attacker(tmp_path: Path, store: Path, entry: Path, frame: bytes) -> Path:
    """A submission that, run as the grader's user, writes ``frame`` as ``entry`` behind the
    store's key (read if it finds one, planted if not), with the grader's own code."""
    return mutant(tmp_path / "attacker", MODULE, f"""
        import os as _os, secrets as _secrets, sys as _sys
        from pathlib import Path as _Path

        _sys.path.insert(0, {str(ROOT)!r})
        from autograder.sandbox import cache as _cache

        _store, _entry = _Path({str(store)!r}), _Path({str(entry)!r})
        try:
            _key, _found = (_store / "key").read_bytes(), "found the key"
        except OSError:
            _key, _found = _secrets.token_bytes(32), "planted a key"
            _fd = _os.open(_store / "key", _os.O_WRONLY | _os.O_CREAT | _os.O_EXCL, 0o600)
            _os.write(_fd, _key)
            _os.close(_fd)
        _entry.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
        _entry.write_bytes(_cache._mac(_key, _entry.parent, _entry.name, {frame!r}) + {frame!r})
        (_store.parent / "attack").write_text(_found)
        """)


WRONG = """
    def translation_matrix(tx, ty):
        return np.array([[1.0, 0.0, ty], [0.0, 1.0, tx], [0.0, 0.0, 1.0]])  # tx and ty swapped
    """

needs_namespaces = pytest.mark.skipif(confine.strongest_candidate().level == "process-group",
                                      reason="no namespaced confinement level on this machine")


def _property_of(submission) -> bool:
    result = runner.grade(submission, ["lab07.ex1"], pictures="none")
    [exercise] = result.exercises
    return next(c for c in exercise.checks if c.name == PROPERTY).passed


@needs_namespaces
@pytest.mark.parametrize("revoked", [True, False], ids=["as graded", "without revoking (the flaw)"])
def test_a_process_group_worker_leaves_nothing_a_later_grading_trusts(store, tmp_path, monkeypatch, revoked):
    if not revoked:
        monkeypatch.setattr(sandbox, "_distrust_store", lambda: None)
    wrong = mutant(tmp_path / "wrong", MODULE, WRONG)
    entry, frame = _poisoned_entry(store, wrong)
    assert _property_of(REFERENCE)                              # a namespaced grading made the key
    real_key = (store / "key").read_bytes()

    used = []
    with monkeypatch.context() as unconfined:
        unconfined.setenv("AUTOGRADER_CONFINEMENT", "process-group")
        unconfined.setattr(cache, "_read", lambda *args: used.append(args))
        unconfined.setattr(cache, "_write", lambda *args: used.append(args))
        runner.grade(_attacker(tmp_path, store, entry, frame), ["lab07.ex1"], pictures="none")
    assert used == []                                           # process-group: the store is not used
    assert entry.is_file()                                      # the attack ran
    if revoked:
        assert (tmp_path / "attack").read_text() == "planted a key"   # the real key was gone
        assert not (store / "key").exists()                           # and so is the planted one
        assert not _property_of(wrong)
        assert (store / "key").read_bytes() != real_key
    else:  # the same attack where the key outlives the worker: the wrong answer passes
        assert (tmp_path / "attack").read_text() == "found the key"
        assert _property_of(wrong)


# ------------------------------------------------------------------ relative interpreter
def test_an_interpreter_path_is_made_absolute():
    assert confine._absolute("bin/python3") == os.path.join(os.getcwd(), "bin/python3")
    assert confine._absolute("/usr/bin/python3") == "/usr/bin/python3"
    assert confine._absolute("") == ""
    assert os.path.isabs(confine.INTERPRETER)


@needs_namespaces
def test_a_grader_started_through_a_relative_path_confines_at_the_strongest_level(tmp_path):
    interpreter = Path(sys.executable)
    # Found through a relative PATH entry, Python's sys.executable is relative ("bin/python").
    environment = {**os.environ, "PATH": f"{interpreter.parent.name}:{os.environ.get('PATH', '')}"}
    environment.pop("AUTOGRADER_CONFINEMENT", None)
    asked = subprocess.run([interpreter.name, "-c", "import sys; print(sys.executable)"], env=environment,
                           cwd=interpreter.parent.parent, capture_output=True, text=True, timeout=60)
    assert not os.path.isabs(asked.stdout.strip())
    done = subprocess.run([interpreter.name, str(ROOT / "grade.py"), "lab07.ex1", "--submission", str(REFERENCE),
                           "--no-html", "--quiet", "--json", str(tmp_path / "results.json")],
                          cwd=interpreter.parent.parent, env=environment, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    results = json.loads((tmp_path / "results.json").read_text())
    assert results["confinement"] == confine.strongest_candidate().level
    assert results["confinement_warning"] == "" and results["total"] == results["max_total"]


# ------------------------------------------------------------------ the level, always said
def _marking(tmp_path: Path) -> Path:
    """A submission that leaves a file behind as soon as any of it runs."""
    return mutant(tmp_path / "marking", MODULE, f"""
        open({str(tmp_path / "ran")!r}, "w").close()
        """)


@needs_namespaces
def test_a_grading_names_its_level_and_warns_loudly_when_it_is_forced_weaker(tmp_path, monkeypatch):
    strongest = runner.grade(REFERENCE, ["lab07.ex1"], pictures="none")
    assert strongest.confinement == confine.strongest_candidate().level and strongest.confinement_warning == ""
    monkeypatch.setenv("AUTOGRADER_CONFINEMENT", "process-group")
    weaker = runner.grade(REFERENCE, ["lab07.ex1"], pictures="none")
    assert weaker.confinement == "process-group"
    assert "AUTOGRADER_CONFINEMENT=process-group" in weaker.confinement_warning
    assert strongest.confinement in weaker.confinement_warning
    data = weaker.to_dict()
    assert (data["confinement"], data["confinement_warning"]) == ("process-group", weaker.confinement_warning)
    assert GradingResult.from_dict(data).for_students().confinement_warning == weaker.confinement_warning

    from rich.console import Console

    from autograder.reports import terminal

    console = Console(record=True, width=200)
    terminal.render(weaker, console)
    printed = console.export_text()
    assert f"warning: {weaker.confinement_warning}" in printed
    assert "confined at the process-group level" in printed
    console = Console(record=True, width=200)
    terminal.render(strongest, console)
    printed = console.export_text()
    assert "warning" not in printed and f"confined at the {strongest.confinement} level" in printed

    with pytest.raises(confine.WeakerConfinement, match="process-group"):
        runner.grade(_marking(tmp_path), ["lab07.ex1"], pictures="none", refuse_weaker=True)
    assert not (tmp_path / "ran").exists()                      # refused before any of it ran


@needs_namespaces
def test_gradescope_refuses_a_weaker_level_unless_the_course_accepts_it(tmp_path, monkeypatch):
    from autograder.instructor import gradescope
    from autograder.instructor.course import CourseConfig

    monkeypatch.setenv("AUTOGRADER_CONFINEMENT", "process-group")
    refused = gradescope.run(_marking(tmp_path), tmp_path / "results.json", CourseConfig(select=["lab07.ex1"]))
    assert refused["score"] == 0 and refused["tests"] == [] and "tell your instructor" in refused["output"]
    assert not (tmp_path / "ran").exists()
    accepted = gradescope.run(REFERENCE, tmp_path / "results.json",
                              CourseConfig(select=["lab07.ex1"], allow_weaker_confinement=True))
    assert accepted["score"] > 0 and accepted["tests"]


@needs_namespaces
def test_a_batch_refuses_a_level_forced_weaker_than_this_machine_allows(tmp_path, monkeypatch):
    from autograder.instructor.batch.run import Unconfined, run_batch

    levels = [level for level in confine.LEVELS[:-1] if level != confine.strongest_candidate().level]
    for forced in levels[-1:] + ["process-group"]:
        monkeypatch.setenv("AUTOGRADER_CONFINEMENT", forced)
        with pytest.raises(Unconfined, match="allow-unconfined"):
            run_batch(tmp_path / "class", tmp_path / "out")
