"""Hypothesis strategies described now, built only when Hypothesis really runs.

The lab suites describe their examples with the names of ``hypothesis.strategies``::

    from autograder.engine import strategies as st

    seeds = st.integers(0, 2**32 - 1)
    t.for_all(st.tuples(seeds, st.floats(10.0, 2000.0)), holds, max_examples=15)

Each call gives a :class:`Described` strategy: what it is, in a stable text
(:func:`describe`, which keys the examples a passed property recorded, see
:mod:`autograder.engine.examples`), and :meth:`Described.build` makes Hypothesis's own
strategy. Importing Hypothesis costs about half a second, and a property whose
examples were recorded replays them without it, so it is imported only when a
property runs under Hypothesis (the first time, or when an example fails).

Any name of ``hypothesis.strategies`` may be used (``st.lists``, ``st.sampled_from``,
...), and a described strategy has ``map``, ``filter`` and ``flatmap``; arguments
that are described strategies are built with it. A suite may also pass
Hypothesis's own strategies to ``t.for_all``.
"""

from __future__ import annotations

import hashlib
import types


class Described:
    """``hypothesis.strategies.<name>(*args, **kwargs)``, or, with a ``base``,
    ``base.<name>(*args, **kwargs)`` (``map``, ``filter``, ``flatmap``), not built yet."""

    __slots__ = ("name", "args", "kwargs", "base")

    def __init__(self, name: str, args: tuple = (), kwargs: dict | None = None, base: "Described | None" = None):
        self.name, self.args, self.kwargs, self.base = name, tuple(args), dict(kwargs or {}), base

    def map(self, function) -> "Described":
        return Described("map", (function,), base=self)

    def filter(self, condition) -> "Described":
        return Described("filter", (condition,), base=self)

    def flatmap(self, expand) -> "Described":
        return Described("flatmap", (expand,), base=self)

    def build(self):
        """Hypothesis's strategy (importing Hypothesis)."""
        from hypothesis import strategies

        owner = strategies if self.base is None else self.base.build()
        return getattr(owner, self.name)(*build(self.args), **build(self.kwargs))

    def __repr__(self) -> str:
        return describe(self)


def build(value):
    """``value`` with every described strategy in it built (lists, tuples and dicts looked into)."""
    if isinstance(value, Described):
        return value.build()
    if type(value) in (list, tuple):
        return type(value)(build(v) for v in value)
    if type(value) is dict:
        return {k: build(v) for k, v in value.items()}
    return value


def describe(value) -> str:
    """A text that is the same for the same strategy in every process, and differs
    when any argument does (a function: by its code, constants and closure)."""
    if isinstance(value, Described):
        arguments = [describe(a) for a in value.args] + [f"{k}={describe(v)}" for k, v in value.kwargs.items()]
        call = f"{value.name}({', '.join(arguments)})"
        return f"{describe(value.base)}.{call}" if value.base is not None else call
    if isinstance(value, (list, tuple)):
        inner = ", ".join(describe(v) for v in value)
        return f"[{inner}]" if isinstance(value, list) else f"({inner}{',' if len(value) == 1 else ''})"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{describe(k)}: {describe(v)}" for k, v in value.items()) + "}"
    if isinstance(value, types.FunctionType):
        return f"{value.__qualname__}#{_fingerprint(value)}"
    if isinstance(value, (types.BuiltinFunctionType, type)):
        return f"{getattr(value, '__module__', '') or ''}.{value.__qualname__}"
    return repr(value)


def _fingerprint(function: types.FunctionType) -> str:
    digest = hashlib.sha256(_code_text(function.__code__).encode())
    if id(function) in _DESCRIBING:  # a function whose closure holds itself
        return digest.hexdigest()[:16]
    _DESCRIBING.add(id(function))
    try:
        digest.update(describe(function.__defaults__ or ()).encode())
        for cell in function.__closure__ or ():
            digest.update(describe(cell.cell_contents).encode())
    finally:
        _DESCRIBING.discard(id(function))
    return digest.hexdigest()[:16]


_DESCRIBING: set[int] = set()


def _code_text(code: types.CodeType) -> str:
    constants = [_code_text(c) if isinstance(c, types.CodeType) else repr(c) for c in code.co_consts]
    return f"{code.co_code.hex()}|{constants}|{code.co_names}"


def __getattr__(name: str):
    """``st.integers``, ``st.tuples``, ...: any strategy of ``hypothesis.strategies``, described."""
    if name.startswith("_"):
        raise AttributeError(name)

    def strategy(*args, **kwargs) -> Described:
        return Described(name, args, kwargs)

    strategy.__name__ = strategy.__qualname__ = name
    return strategy
