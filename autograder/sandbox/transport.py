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
        For any other type (the message names it), or a frame over ``max_bytes``;
        :class:`TooManyElements` for arrays holding more than ``max_elements`` numbers.
    """
    buffers: list[bytes] = []
    size = [0]
    elements = [0, ()]  # numbers in the arrays so far, the largest array's shape

    def node(v, depth):
        if depth > MAX_DEPTH:
            raise TransportError(f"returned a value nested deeper than {MAX_DEPTH} levels")
        t = type(v)
        if v is None or t is bool or t is str:
            return v
        if t is int:
            return v if -INT64 <= v < INT64 else _float_node(_int_as_float(v))
        if t is float:
            return _float_node(v)
        if t is complex:
            return {"c": [_float_node(v.real), _float_node(v.imag)]}
        if isinstance(v, np.generic) and type(v).__module__ == "numpy":
            if v.dtype.kind not in _ALLOWED_KINDS:
                raise TransportError(f"returned a NumPy scalar of dtype {v.dtype}; return a number")
            item = v.item()  # a long double stays one: it crosses as the nearest float
            if isinstance(item, np.generic):
                item = complex(item) if v.dtype.kind == "c" else float(item)
            return node(item, depth + 1)
        if t is np.ndarray:
            if not _allowed(v.dtype):
                use = {"f": "float32 or float64", "c": "complex64 or complex128"}.get(
                    v.dtype.kind, "a numeric or bool dtype")
                raise TransportError(f"returned an array of dtype {v.dtype}; use {use}")
            # Counted before the bytes are made: a broadcast view (zero strides) of a few
            # bytes can stand for gigabytes.
            size[0] += v.nbytes
            if size[0] > max_bytes:
                raise TransportError(f"returned more than {max_bytes // 2**20} MiB")
            elements[0] += v.size
            elements[1] = max(elements[1], v.shape, key=math.prod)
            if max_elements is not None and elements[0] > max_elements:
                raise TooManyElements(elements[0], elements[1], max_elements)
            buffers.append(np.ascontiguousarray(v).tobytes())
            return {"a": len(buffers) - 1, "dtype": v.dtype.str, "shape": list(v.shape)}
        if isinstance(v, np.ndarray):
            raise TransportError(
                f"returned a {t.__module__}.{t.__qualname__} (an ndarray subclass); "
                "return a plain numpy.ndarray (np.asarray(x))"
            )
        if t is list:
            return {"l": [node(x, depth + 1) for x in v]}
        if t is tuple:
            return {"t": [node(x, depth + 1) for x in v]}
        if t is dict:
            items = []
            for k, x in v.items():
                if type(k) is not str:
                    raise TransportError("returned a dict with non-string keys")
                items.append([k, node(x, depth + 1)])
            return {"d": items}
        raise TransportError(
            f"returned a {t.__module__}.{t.__qualname__}; expected arrays, numbers, "
            "strings, or lists/tuples/dicts of those"
        )

    header = json.dumps(node(value, 0), separators=(",", ":")).encode()
    if len(header) > MAX_HEADER_BYTES:
        raise TransportError(f"returned more than {MAX_HEADER_BYTES // 2**20} MiB of numbers and text "
                             "outside arrays (return an array)")
    total = PREFIX.size + len(header) + size[0]
    if total > max_bytes:
        raise TransportError(f"returned more than {max_bytes // 2**20} MiB")
    return b"".join([PREFIX.pack(MAGIC, len(header)), header, *buffers])


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
