"""Property examples recorded once and replayed: Hypothesis's verdict without its engine.

With the grading profile (no database) and one seed (the submission's, see
:class:`autograder.engine.properties.Inputs`) Hypothesis draws the same examples for the
same strategy on every run, as long as every example passes: its engine sees
nothing of the test but "passed". Drawing them costs about a millisecond and a
half each, more than most student calls. So a property that passed keeps the list
of examples its body was called with (in :mod:`autograder.sandbox.cache`, keyed by the
check, the strategy, the bound on examples, the seed and the grader's code and
library versions), and the next grading of the same files calls
the body with that list directly. If every example passes again, that is exactly
what Hypothesis would have found. At the first example that does not, Hypothesis
runs as usual (it finds the same examples up to that one: the body is not called
again for those, since they just passed) and shrinks the failure itself, so
messages and counterexamples are Hypothesis's own.

Only examples made of plain data that come back from the store exactly as they
were (same types, same bits) are recorded.
"""

from __future__ import annotations

import functools
import hashlib
import math
import sys
from pathlib import Path

import numpy as np

from ..sandbox import cache, transport

NAME = "property-examples"


_ROOTS = (Path(__file__).resolve().parents[1], Path(__file__).resolve().parents[2] / "fixtures")


@functools.lru_cache(maxsize=1)
def _grader_version() -> str:
    """What examples depend on besides the check and its strategy: the grader's code
    (lab suites, fixtures, this engine) and the libraries."""
    digest = hashlib.sha256(f"{sys.version}|{_hypothesis_version()}|{np.__version__}".encode())
    for path in sorted(p for root in _ROOTS if root.is_dir() for p in root.rglob("*.py")):
        digest.update(str(path.relative_to(path.parents[1])).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:24]


def _hypothesis_version() -> str:
    """Hypothesis's version, read without importing it (half a second that a replay
    saves): the name of its installed distribution's metadata folder."""
    from importlib.util import find_spec

    spec = find_spec("hypothesis")
    if spec is None or not spec.origin:
        return "none"
    package = Path(spec.origin).parent
    found = sorted(p.name for p in package.parent.glob("hypothesis-*.dist-info"))
    return "|".join(found) or str(package)


@functools.lru_cache(maxsize=None)
def _version(suite_file: str) -> str:
    """:func:`_grader_version`, and the suite's own file when it is a plug-in's."""
    suite = Path(suite_file).resolve()
    if any(root in suite.parents for root in _ROOTS):
        return _grader_version()
    return hashlib.sha256((_grader_version() + "|").encode() + suite.read_bytes()).hexdigest()[:24]


def key(check, index: int, strategy, max_examples, seed: int) -> tuple[str, str] | None:
    """``(version, key)`` naming the examples of the ``index``-th property of ``check``
    drawn with Hypothesis's ``seed``, or None when nothing may be stored."""
    if not cache.is_enabled():
        return None
    try:
        import inspect

        version = _version(inspect.getfile(check.func))
        return version, f"{check.id}|{index}|{max_examples}|{seed}|{strategy!r}"
    except (OSError, TypeError, ValueError):
        return None


def recorded(where) -> list | None:
    """The examples kept under ``where`` (from :func:`key`), or None."""
    if where is None:
        return None
    examples = cache.load(NAME, *where)
    return examples if type(examples) is list else None


def record(where, examples: list) -> None:
    """Keep ``examples`` (those of a property that passed) if each comes back exactly."""
    if where is not None and examples and roundtrips(examples):
        cache.save(NAME, *where, examples)


def same(a, b) -> bool:
    """Whether two examples are identical: same types all the way down, same bits."""
    if type(a) is not type(b):
        return False
    if type(a) is float:
        return a == b and math.copysign(1.0, a) == math.copysign(1.0, b) or (a != a and b != b)
    if type(a) is complex:
        return same(a.real, b.real) and same(a.imag, b.imag)
    if type(a) is np.ndarray:
        return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()
    if type(a) in (list, tuple):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if type(a) is dict:
        return list(a) == list(b) and all(same(a[k], b[k]) for k in a)
    return a == b


def roundtrips(examples: list) -> bool:
    """Whether the store gives ``examples`` back exactly (checked before recording)."""
    try:
        back = transport.decode(transport.encode(examples))
    except transport.TransportError:
        return False
    return same(examples, back)
