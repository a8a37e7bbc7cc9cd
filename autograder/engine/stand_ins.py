"""Stand-ins for the student's functions, run in the error model's helper process (never imported
by the grader for use, never in the student's sandbox): this module's text is appended to a lab's
reference module there (:data:`autograder.engine.inherited.APPENDIX`), so ``globals()`` below is the
reference's namespace.

:func:`_autograder_given_answers` runs the reference ``function`` with each callee named in
``answers`` answered from ``answers`` (the student's answers, by the arguments given) and, for
arguments not there, by the reference's own callee, recording them (``needed``: the callee, its
arguments and the reference's answer). Calls made from inside a callee the reference answers are
the reference's own business (not recorded, not answered).
"""


def _autograder_same(a, b):
    """Whether two argument values are the same (arrays by their values; numbers by value, whatever
    their type: they crossed the transport as Python numbers)."""
    import numpy as _np
    if isinstance(a, _np.ndarray) or isinstance(b, _np.ndarray):
        return isinstance(a, _np.ndarray) and isinstance(b, _np.ndarray) and a.shape == b.shape \
            and a.dtype.kind == b.dtype.kind and _np.array_equal(a, b, equal_nan=a.dtype.kind in "fc")
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_autograder_same(x, y) for x, y in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return set(a) == set(b) and all(_autograder_same(a[k], b[k]) for k in a)
    if isinstance(a, (int, float, complex, _np.number)) and isinstance(b, (int, float, complex, _np.number)) \
            and not isinstance(a, bool) and not isinstance(b, bool):
        return a == b or (a != a and b != b)
    return type(a) is type(b) and a == b


def _autograder_copy(value):
    """A copy the reference may write into (and that it does not change afterwards)."""
    import numpy as _np
    if isinstance(value, _np.ndarray):
        return value.copy()
    if isinstance(value, (list, tuple)):
        return type(value)(_autograder_copy(v) for v in value)
    if isinstance(value, dict):
        return {k: _autograder_copy(v) for k, v in value.items()}
    return value


def _autograder_given_answers(function, answers, args, kwargs):
    """``{"value": function(*args, **kwargs), "needed": [[callee, args, kwargs, reference's answer], ...]}``
    with the callees of ``answers`` (``{callee: [[args, kwargs, answer], ...]}``) answered from it."""
    space = globals()   # the reference module's: its functions look their callees up here
    kept = {name: space[name] for name in answers}
    needed, inside = [], [0]

    def stand_in(name):
        real = kept[name]

        def call(*a, **k):
            if inside[0]:
                return real(*a, **k)
            for given, given_k, answer in answers[name]:
                if _autograder_same(list(a), list(given)) and _autograder_same(k, dict(given_k)):
                    return _autograder_copy(answer)
            given = (_autograder_copy(list(a)), _autograder_copy(dict(k)))
            inside[0] += 1
            try:
                value = real(*a, **k)
            finally:
                inside[0] -= 1
            needed.append([name, given[0], given[1], _autograder_copy(value)])
            return value
        return call

    try:
        for name in answers:
            space[name] = stand_in(name)
        value = space[function](*args, **kwargs)
    finally:
        space.update(kept)
    return {"value": value, "needed": needed}
