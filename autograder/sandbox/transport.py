"""Plain-data transport between the grader and the sandboxed worker.

Values cross the process boundary as one *frame*: a JSON header describing the
value tree, followed by the raw bytes of every array in it. Decoding builds only
``None``, ``bool``, ``int`` (64-bit), ``float``, ``complex``, ``str`` (valid
Unicode), ``list``, ``tuple``, ``dict`` (string keys) and exact ``numpy.ndarray``
objects of boolean, integer, float32/64 or complex64/128 dtype in the machine's
byte order: what the grader's checks compute with. An integer beyond 64 bits
crosses as the nearest float (infinite beyond a float's range), as NumPy would
hold it. Nothing in a frame can name a class, a function or a module,
so decoding can never execute code (this is why we do not use pickle), and an
``ndarray`` subclass or an object whose ``__eq__`` always says yes cannot come
back.

This module imports only the standard library and NumPy: the worker runs a copy
of it next to the student's code.

Frame layout::

    b"AGT1" | header length (8 bytes, big endian) | header JSON | array bytes...

Examples
--------
>>> import numpy as np
>>> frame = encode({"H": np.eye(3), "ok": True})
>>> decode(frame)["H"].shape
(3, 3)
"""

from __future__ import annotations

import json
import math
import os
import struct

import numpy as np

MAGIC = b"AGT1"
PREFIX = struct.Struct(">4sQ")
DEFAULT_MAX_BYTES = 256 * 1024 * 1024
MAX_HEADER_BYTES = 4 * 1024 * 1024  # checked before parsing: JSON costs ~25x its size in objects
MAX_DEPTH = 64
MAX_NODES = 1_000_000

# Dtypes that can cross: booleans, integers, and the floats and complex numbers NumPy's
# linear algebra and OpenCV compute with (not float16 or long double), in either byte order.
_ALLOWED_KINDS = {"b", "i", "u", "f", "c"}
_ALLOWED_SIZES = {"f": (4, 8), "c": (8, 16)}
INT64 = 2**63


class TransportError(ValueError):
    """A value cannot be encoded, or a frame is malformed or too large."""


class TooManyElements(TransportError):
    """A value whose arrays hold more numbers than the receiver takes (see :func:`count_elements`)."""

    def __init__(self, elements: int, largest: tuple[int, ...], limit: int):
        # ``elements``: those counted when the limit was passed (a sender stops there), or all
        super().__init__(f"returned more numbers in arrays than the {limit:,} accepted ({elements:,} "
                         f"counted; the largest array of shape {tuple(largest)})")
        self.elements, self.largest, self.limit = elements, tuple(largest), limit


# --------------------------------------------------------------------- encoding
def encode(value, max_bytes: int = DEFAULT_MAX_BYTES, max_elements: int | None = None) -> bytes:
    """Encode plain data into one frame.

    Parameters
    ----------
    value : plain data
        ``None``, bool, int, float, complex, str, NumPy scalars, exact
        ``numpy.ndarray`` of numeric/bool dtype, and lists, tuples and
        string-keyed dicts of those.
    max_bytes : int
        Largest frame allowed.
    max_elements : int, optional
        Most numbers the value's arrays may hold together (None: any number).

    Raises
    ------
    TransportError
        For anything else, a frame over ``max_bytes``, or more than :data:`MAX_HEADER_BYTES`
        of numbers and text outside arrays: its message is one sentence, "returned <what the
        value is>, which cannot be sent back: <why>" (see :func:`frame_parts`);
        :class:`TooManyElements` for arrays holding more than ``max_elements`` numbers.
    """
    return b"".join(piece for part in frame_parts(value, max_bytes, max_elements) for piece in pieces(part))


def frame_parts(value, max_bytes: int = DEFAULT_MAX_BYTES, max_elements: int | None = None) -> list:
    """The frame of :func:`encode` in parts, each of ``len(part)`` bytes: the prefix and the
    header, then each array's bytes -- a contiguous array's memory itself, a non-contiguous
    one's copied a few MiB at a time as it is written (:func:`pieces` gives a part's
    bytes-like pieces). The worker writes them one after the other: sending a result costs
    it next to no memory beyond the result, where one joined frame costs its size twice over.

    Encoding runs none of the value's own code: only exact types are taken (a subclass of
    ``list``, ``float`` or ``ndarray`` is refused by its type, never asked anything), so a
    result whose methods raise, exit or recurse is refused like any other. A value that
    cannot cross is refused as early as it can be told -- its size before any copy, a
    list's length before its items -- with a :class:`TransportError` whose message names
    what was returned, the part that cannot cross (``its item [2]['H']``) and why."""
    buffers: list = []
    size = [0, 0]  # bytes of arrays, bytes of header at least (a lower bound, counted as it grows)
    elements = [0, ()]  # numbers in the arrays so far, the largest array's shape
    inside: set[int] = set()  # the containers being encoded, to tell a value that contains itself
    trail = [None] * (MAX_DEPTH + 2)  # the value being encoded at each depth: where a refusal is

    def grow_header(n: int) -> None:
        size[1] += n
        if size[1] > MAX_HEADER_BYTES:
            raise _Refused(f"it holds more than {size_words(MAX_HEADER_BYTES)} of numbers and text outside "
                           "arrays; at most that can cross (return an array)", whole=True)

    def node(v, depth):
        trail[depth] = v
        if depth > MAX_DEPTH:
            raise _Refused(f"it is nested deeper than {MAX_DEPTH} levels; at most {MAX_DEPTH} can cross",
                           whole=True)
        t = type(v)
        if v is None or t is bool:  # (two characters of header at least: counted by the container)
            return v
        if t is str:
            grow_header(len(v) + 1)
            return v
        if t is int:
            return v if -INT64 <= v < INT64 else _float_node(_int_as_float(v))
        if t is float:
            return _float_node(v)
        if t is complex:
            grow_header(10)
            return {"c": [_float_node(v.real), _float_node(v.imag)]}
        if t in _NUMPY_SCALARS:  # NumPy's own: its dtype and item() are NumPy's code
            if v.dtype.kind not in _ALLOWED_KINDS:
                raise _Refused(f"NumPy scalars of dtype {v.dtype} cannot cross; return a number", depth)
            item = v.item()  # a long double stays one: it crosses as the nearest float
            if isinstance(item, np.generic):
                item = complex(item) if v.dtype.kind == "c" else float(item)
            return node(item, depth)
        if t is np.ndarray:
            if not _allowed(v.dtype):
                use = {"f": "float32 or float64", "c": "complex64 or complex128"}.get(
                    v.dtype.kind, "a numeric or bool dtype")
                raise _Refused(f"arrays of dtype {v.dtype} cannot cross; use {use}", depth)
            # Counted before the bytes are made: a broadcast view (zero strides) of a few
            # bytes can stand for gigabytes.
            size[0] += v.nbytes
            if size[0] > max_bytes:
                raise _Refused(f"it is more than the {size_words(max_bytes)} a result may be", whole=True)
            elements[0] += v.size
            elements[1] = max(elements[1], v.shape, key=math.prod)
            if max_elements is not None and elements[0] > max_elements:
                raise TooManyElements(elements[0], elements[1], max_elements)
            grow_header(40 + 8 * v.ndim)
            buffers.append(_raw_bytes(v))
            return {"a": len(buffers) - 1, "dtype": v.dtype.str, "shape": list(v.shape)}
        if t is list or t is tuple or t is dict:
            grow_header(8 + 2 * len(v))  # each item takes a character and a comma at least
            if id(v) in inside:
                raise _Refused(f"that {t.__name__} itself (it contains itself, so it has no end)", depth)
            inside.add(id(v))
            if t is dict:
                keys = 0
                items = []
                for k, x in v.items():
                    if type(k) is not str:
                        raise _Refused(f"its keys must be strings, and one is {describe(k)} (non-string keys "
                                       "cannot cross)", depth)
                    keys += len(k) + 4
                    items.append([k, node(x, depth + 1)])
                grow_header(keys)
                encoded = {"d": items}
            else:
                encoded = {"l" if t is list else "t": [node(x, depth + 1) for x in v]}
            inside.discard(id(v))
            return encoded
        if issubclass(t, np.ndarray):  # (of its type: isinstance would ask the value its __class__)
            raise _Refused("an ndarray subclass cannot cross; return a plain numpy.ndarray (np.asarray(x))", depth)
        raise _Refused("only arrays, numbers, strings, and lists, tuples and string-keyed dicts of those "
                       "can cross" + _HINTS.get(t, ""), depth)

    try:
        header = json.dumps(node(value, 0), separators=(",", ":")).encode()
        if len(header) > MAX_HEADER_BYTES:
            raise _Refused(f"it holds more than {size_words(MAX_HEADER_BYTES)} of numbers and text outside "
                           "arrays; at most that can cross (return an array)", whole=True)
        if PREFIX.size + len(header) + size[0] > max_bytes:
            raise _Refused(f"it is more than the {size_words(max_bytes)} a result may be", whole=True)
    except _Refused as refused:
        refused.locate(trail)
        raise Unsendable(refused.sentence(value), refused) from None
    finally:
        # node() refers to itself: a cycle that only the garbage collector would free, with
        # the value in trail -- a result the worker no longer holds must be gone at once.
        node = None  # noqa: F841
    return [PREFIX.pack(MAGIC, len(header)) + header, *buffers]


class _Refused(Exception):
    """Why a part of a value cannot cross: ``reason``, about the part at ``depth`` of the value
    (the whole value when ``whole``); :meth:`locate` finds its ``path`` (keys and indices
    from the value down), only once a value was refused."""

    def __init__(self, reason: str, depth: int = 0, whole: bool = False):
        super().__init__(reason)
        self.reason, self.depth, self.whole, self.path = reason, depth, whole, []

    def locate(self, trail: list) -> None:
        """The keys from ``trail[0]`` down to ``trail[depth]``, each container's (by identity)."""
        if self.whole:
            return
        for parent, child in zip(trail[:self.depth], trail[1:self.depth + 1]):
            keys = parent.items() if type(parent) is dict else enumerate(parent)
            self.path.append(next((key for key, item in keys if item is child), "?"))

    def sentence(self, value, path=None) -> str:
        """"returned <value>, which cannot be sent back: <why>", the part at ``path`` (by default
        :attr:`path`) of ``value`` named."""
        path = self.path if path is None else path
        if self.whole or not path:
            return f"returned {describe(value)}, which cannot be sent back: {self.reason}"
        where = "".join(f"[{key!r}]" for key in path)
        part = value
        for key in path:
            part = part[key]  # exact lists, tuples and dicts only: no code of the value runs
        what = self.reason if self.reason.startswith("that ") else f"{describe(part)}: {self.reason}"
        return f"returned {describe(value)}, which cannot be sent back: its item {where} is {what}"


class Unsendable(TransportError):
    """A value :func:`encode` refuses; the message is one sentence about it (see :func:`frame_parts`)."""

    def __init__(self, sentence: str, refused: _Refused):
        super().__init__(sentence)
        self._refused = refused

    def about(self, item, key) -> str:
        """The sentence about ``item``, the value at ``key`` of the dict that was encoded (a
        worker's reply: what the student's function returned, not the reply around it)."""
        refused = self._refused
        if refused.whole or refused.path[:1] == [key]:
            return refused.sentence(item, refused.path[1:])
        return str(self)


# What a value of these types can become before it is returned.
_HINTS = {t: " (make it a list: list(...))" for t in
          (set, frozenset, range, map, filter, zip, enumerate, reversed, type({}.keys()), type({}.values()),
           type({}.items()), type(x for x in ()))}
# NumPy's scalar types, exactly (a subclass of one is the submission's code).
_NUMPY_SCALARS = frozenset(np.sctypeDict.values())


def _raw_bytes(array: np.ndarray):
    """The bytes of ``array`` in C order: a view of its memory when it is contiguous, else a
    :class:`_Copied` part."""
    if not array.flags.c_contiguous:
        return _Copied(array)
    return memoryview(array.reshape(-1).view(np.uint8)) if array.size else b""


class _Copied:
    """A non-contiguous array's bytes in C order, copied :attr:`CHUNK` bytes or so at a time
    (a block of its first axis, or of a row's) while they are written."""

    CHUNK = 4 * 2**20

    def __init__(self, array: np.ndarray):
        self.array = array

    def __len__(self):
        return self.array.nbytes

    def __iter__(self):
        return self._blocks(self.array)

    def _blocks(self, a):
        if a.ndim == 0 or a.nbytes <= self.CHUNK:
            yield np.ascontiguousarray(a).tobytes()
            return
        row = a.nbytes // len(a)
        if row > self.CHUNK:
            for sub in a:
                yield from self._blocks(sub)
            return
        step = self.CHUNK // row
        for start in range(0, len(a), step):
            yield np.ascontiguousarray(a[start:start + step]).tobytes()


def pieces(part):
    """The bytes-like pieces of one part of :func:`frame_parts`, in order."""
    return part if isinstance(part, _Copied) else (part,)


def size_words(n: int) -> str:
    """``n`` bytes in words: ``"320 MiB"``, ``"12 KiB"``, ``"100 bytes"``."""
    for unit, scale in (("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if n >= scale:
            return f"{n / scale:.3g} {unit}"
    return f"{n} byte" + ("" if n == 1 else "s")


def describe(value) -> str:
    """What ``value`` is, in a few words (``"a float64 array of shape (480, 640) (2.34 MiB)"``,
    ``"a list of 3 items"``, ``"a m.Hostile (a float subclass)"``), from its type and NumPy's
    or Python's own attributes only: no code of the value runs, whatever it is."""
    try:
        t = type(value)
        if value is None:
            return "None"
        if t is np.ndarray:
            return f"{_a(str(value.dtype))} array of shape {tuple(value.shape)} ({size_words(value.nbytes)})"
        if t in (list, tuple, dict):
            return f"a {t.__name__} of {len(value)} item" + ("" if len(value) == 1 else "s")
        if t is str:
            return f"a string of {len(value)} characters"
        if t in (bool, int, float, complex) or t in _NUMPY_SCALARS:
            return _a(_type_name(t))
        mro = type.__dict__["__mro__"].__get__(t)
        base = next((b for b in mro[1:] if b in _PLAIN), None)
        return _a(_type_name(t)) + (f" ({_a(_type_name(base))} subclass)" if base is not None else "")
    except BaseException:  # noqa: BLE001 - a description is never worth a failure
        return "a value of an unknown type"


_PLAIN = (list, tuple, dict, str, bytes, int, float, complex, set, np.ndarray, np.generic)


def _a(noun: str) -> str:
    return ("an " if noun[:1] in "aeiou" else "a ") + noun


def _type_name(t: type) -> str:
    """``module.qualname`` of ``t`` (just the name for builtins), read without running any of its code."""
    module = type.__dict__["__module__"].__get__(t)
    name = type.__dict__["__qualname__"].__get__(t)
    module = module if type(module) is str else "?"
    name = name if type(name) is str else "?"
    return name if module == "builtins" else f"{module}.{name}"


def _int_as_float(n: int) -> float:
    """The float nearest ``n``, infinite beyond a float's range."""
    try:
        return float(n)
    except OverflowError:
        return math.inf if n > 0 else -math.inf


def _allowed(dtype: np.dtype) -> bool:
    return (dtype.kind in _ALLOWED_KINDS and dtype.fields is None
            and dtype.itemsize in _ALLOWED_SIZES.get(dtype.kind, (dtype.itemsize,)))


def _float_node(x: float):
    # JSON has no NaN/inf: tag them so the header stays strict JSON.
    if math.isfinite(x):
        return x
    return {"f": "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")}


# --------------------------------------------------------------------- decoding
def decode(frame: bytes, max_bytes: int = DEFAULT_MAX_BYTES, max_header: int = MAX_HEADER_BYTES):
    """Decode one frame made by :func:`encode`, trusting nothing in it.

    Raises
    ------
    TransportError
        If the frame is malformed, inconsistent, larger than ``max_bytes`` or
        its header larger than ``max_header``; never any other exception.
    """
    try:
        return _decode(frame, max_bytes, max_header)
    except TransportError:
        raise
    except (Exception, RecursionError) as exc:  # noqa: BLE001 - a frame must never crash the grader
        raise TransportError(f"undecodable frame ({type(exc).__name__})") from None


def _decode(frame, max_bytes, max_header):
    if not isinstance(frame, (bytes, bytearray, memoryview)):
        raise TransportError("frame must be bytes")
    frame = bytes(frame)
    if len(frame) > max_bytes:
        raise TransportError("frame too large")
    if len(frame) < PREFIX.size:
        raise TransportError("frame truncated")
    magic, header_len = PREFIX.unpack_from(frame)
    if magic != MAGIC:
        raise TransportError("bad frame magic")
    if header_len > max_header:
        raise TransportError(f"frame header larger than {max_header} bytes")
    body_start = PREFIX.size + header_len
    if body_start > len(frame):
        raise TransportError("frame header truncated")
    try:
        tree = json.loads(frame[PREFIX.size:body_start], parse_constant=_reject_constant)
    except (ValueError, RecursionError) as exc:
        raise TransportError(f"bad frame header: {exc}") from None

    offset = [body_start]
    expected_index = [0]
    nodes = [0]

    def value(n, depth):
        nodes[0] += 1
        if depth > MAX_DEPTH or nodes[0] > MAX_NODES:
            raise TransportError("frame too deeply nested or too large")
        if n is None or type(n) in (bool, float):
            return n
        if type(n) is str:
            return _unicode(n)
        if type(n) is int:
            if not -INT64 <= n < INT64:
                raise TransportError("integer out of range")
            return n
        if type(n) is not dict or len(n) == 0:
            raise TransportError("bad node")
        if "a" in n:
            return array(n)
        if len(n) != 1:
            raise TransportError("bad node")
        (tag, body), = n.items()
        if tag == "l" and type(body) is list:
            return [value(x, depth + 1) for x in body]
        if tag == "t" and type(body) is list:
            return tuple(value(x, depth + 1) for x in body)
        if tag == "d" and type(body) is list:
            out = {}
            for item in body:
                if type(item) is not list or len(item) != 2 or type(item[0]) is not str:
                    raise TransportError("bad dict item")
                out[_unicode(item[0])] = value(item[1], depth + 1)
            return out
        if tag == "f" and body in ("nan", "inf", "-inf"):
            return float(body)
        if tag == "c" and type(body) is list and len(body) == 2:
            re, im = (value(x, depth + 1) for x in body)
            if type(re) not in (float, int) or type(im) not in (float, int):
                raise TransportError("bad complex")
            return complex(re, im)
        raise TransportError("bad node")

    def array(n):
        if set(n) != {"a", "dtype", "shape"}:
            raise TransportError("bad array node")
        index, dtype_str, shape = n["a"], n["dtype"], n["shape"]
        if type(index) is not int or index != expected_index[0]:
            raise TransportError("arrays out of order")
        expected_index[0] += 1
        if type(dtype_str) is not str or len(dtype_str) > 8:
            raise TransportError("bad dtype")
        try:
            dtype = np.dtype(dtype_str)
        except TypeError:
            raise TransportError("bad dtype") from None
        if not _allowed(dtype) or dtype.str != dtype_str:
            raise TransportError(f"dtype {dtype_str!r} not allowed")
        if type(shape) is not list or len(shape) > 32:
            raise TransportError("bad shape")
        count = 1
        for s in shape:
            if type(s) is not int or not 0 <= s < INT64:
                raise TransportError("bad shape")
            count *= s
        nbytes = count * dtype.itemsize
        start = offset[0]
        if nbytes > len(frame) - start:
            raise TransportError("array data truncated")
        offset[0] = start + nbytes
        out = np.frombuffer(frame, dtype=dtype, count=count, offset=start).reshape(shape)
        # Writeable, owning its data, an exact ndarray, in the machine's byte order (which
        # OpenCV needs; the values are the same).
        return np.array(out, dtype=dtype.newbyteorder("="), copy=True)

    result = value(tree, 0)
    if offset[0] != len(frame):
        raise TransportError("trailing bytes after the last array")
    return result


def count_elements(header: bytes) -> tuple[int, tuple[int, ...]]:
    """The numbers the arrays of a frame hold together, and the largest array's shape, read
    from the frame's header alone (the JSON between the prefix and the array bytes): what a
    receiver checks before it reads the arrays, or decodes anything. A header too large
    (over :data:`MAX_HEADER_BYTES`) or malformed raises :class:`TransportError`; array nodes
    that are not well-formed count nothing here (:func:`decode` refuses them).
    """
    if len(header) > MAX_HEADER_BYTES:
        raise TransportError(f"frame header larger than {MAX_HEADER_BYTES} bytes")
    try:
        tree = json.loads(header, parse_constant=_reject_constant)
    except (ValueError, RecursionError) as exc:
        raise TransportError(f"bad frame header: {type(exc).__name__}") from None
    total, largest = 0, ()
    stack = [tree]  # walked without recursion: the depth is the sender's choice
    while stack:
        node = stack.pop()
        if type(node) is list:
            stack.extend(node)
        elif type(node) is dict:
            shape = node.get("shape")
            if "a" in node and type(shape) is list and len(shape) <= 32 \
                    and all(type(s) is int and 0 <= s < INT64 for s in shape):  # as decode takes them
                count = math.prod(shape)
                total += count
                largest = max(largest, tuple(shape), key=math.prod)
            else:
                stack.extend(node.values())
    return total, largest


def check_elements(header: bytes, max_elements: int) -> None:
    """Raise :class:`TooManyElements` if the frame whose header this is holds more than
    ``max_elements`` numbers in its arrays (see :func:`count_elements`)."""
    total, largest = count_elements(header)
    if total > max_elements:
        raise TooManyElements(total, largest, max_elements)


def _unicode(text: str) -> str:
    """``text``, with any lone surrogate (valid JSON, not valid Unicode) replaced: every
    string of a reply can be written to a page or a UTF-8 file."""
    try:
        text.encode("utf-8")
        return text
    except UnicodeEncodeError:
        return text.encode("utf-8", "replace").decode("utf-8")


def _reject_constant(name):
    raise ValueError(f"non-standard JSON constant {name}")


# ------------------------------------------------------------------ file streams
def write_frame(fd: int, frame: bytes) -> None:
    """Write a whole frame to a file descriptor (blocking)."""
    view = memoryview(frame)
    while view:
        written = os.write(fd, view)
        view = view[written:]
