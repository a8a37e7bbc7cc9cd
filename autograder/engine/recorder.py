"""The recorder that :mod:`autograder.engine.traced` sends, as text, ahead of the student's functions it
rewrites: it runs in the companion sandbox with the student's code, never in the grader. Each rewritten
expression calls ``__ag_seen__(place, value)``, which keeps a description of the value (an array's shape
and dtype, and its numbers when it is small; a number; a short tuple) under the expression's place and
returns the value unchanged; ``__ag_recorded__`` calls the function named ``__ag_target__`` and answers
the descriptions -- plain data (the text sent ends by naming the target).
"""
import numpy as __ag_np__

SMALL_ARRAY = 128             # an array of at most this many numbers is described with its numbers
RECORDS_PER_CALL = 200_000    # evaluations described per call (a pixel loop stops recording, not running)
INDEX_ARRAY = 65_536          # an integer array of at most this many is described with its range (not an image
                              # read at every pixel of a loop: its range would cost a pass over it each time)
__ag_target__ = ""
__ag_record__ = {}
__ag_count__ = [0]


def __ag_describe__(value, depth=0):
    kind = type(value)
    if kind is __ag_np__.ndarray:
        if value.size <= SMALL_ARRAY and value.dtype.kind in "biuf":   # (a small one's numbers too)
            return ["array", [int(n) for n in value.shape], str(value.dtype), value.astype(float).ravel().tolist()]
        if value.dtype.kind in "iu" and 0 < value.size <= INDEX_ARRAY:   # (an index array: its range)
            return ["array", [int(n) for n in value.shape], str(value.dtype), None, int(value.min()), int(value.max())]
        return ["array", [int(n) for n in value.shape], str(value.dtype)]
    if kind in (bool, int, float) or isinstance(value, (__ag_np__.integer, __ag_np__.floating, __ag_np__.bool_)):
        return ["number", float(value)]
    if kind in (tuple, list):
        if depth == 0 and len(value) <= 8 and all(type(v) in (int, float, bool) for v in value):
            return ["tuple", [float(v) for v in value]]
        first = __ag_describe__(value[0], 1) if depth == 0 and len(value) else None
        return ["sequence", kind.__name__, len(value), first]
    return ["other", kind.__name__[:40]]


def __ag_seen__(key, value):
    if __ag_count__[0] < RECORDS_PER_CALL:
        __ag_count__[0] += 1
        try:
            __ag_record__[key] = __ag_describe__(value)
        except Exception:   # (a value of the student's whose description fails is not recorded)
            pass
    return value


def __ag_recorded__(*args, **kwargs):
    __ag_record__.clear()
    __ag_count__[0] = 0
    try:
        value = globals()[__ag_target__](*args, **kwargs)
    except Exception as exc:
        return {"record": dict(__ag_record__), "raised": type(exc).__name__}
    return {"record": dict(__ag_record__), "returned": __ag_describe__(value)}
