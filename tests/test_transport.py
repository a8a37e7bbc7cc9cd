"""The transport: plain data round-trips exactly; nothing else crosses; bad bytes never crash."""

import math
import struct

import numpy as np
import pytest
from hypothesis import given, strategies as st
from hypothesis.extra import numpy as hnp

from autograder.loading.text import printable
from autograder.sandbox.transport import MAX_HEADER_BYTES, TransportError, decode, encode

scalars = st.one_of(st.none(), st.booleans(), st.integers(-2**63, 2**63 - 1), st.floats(),
                    st.text(max_size=20), st.complex_numbers(allow_nan=False))
arrays = hnp.arrays(dtype=st.one_of(hnp.integer_dtypes(endianness="="),
                                    hnp.floating_dtypes(endianness="=", sizes=(32, 64)),
                                    hnp.boolean_dtypes()),
                    shape=hnp.array_shapes(min_dims=0, max_dims=3, min_side=0, max_side=4))
values = st.recursive(st.one_of(scalars, arrays),
                      lambda inner: st.one_of(st.lists(inner, max_size=4),
                                              st.tuples(inner, inner),
                                              st.dictionaries(st.text(max_size=5), inner, max_size=3)),
                      max_leaves=12)


def same(a, b):
    if isinstance(a, np.ndarray):
        return type(b) is np.ndarray and a.dtype == b.dtype and a.shape == b.shape and \
            np.array_equal(a, b, equal_nan=a.dtype.kind in "fc")
    if isinstance(a, float) and math.isnan(a):
        return isinstance(b, float) and math.isnan(b)
    if isinstance(a, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, dict):
        return type(b) is dict and a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    return type(a) is type(b) and a == b


@given(values)
def test_plain_data_round_trips_exactly(value):
    assert same(value, decode(encode(value)))


def test_arrays_come_back_as_exact_writeable_ndarrays():
    out = decode(encode(np.arange(6, dtype=np.uint8).reshape(2, 3)))
    assert type(out) is np.ndarray and out.flags.writeable and out.flags.owndata


def test_numpy_scalars_become_python_numbers():
    assert decode(encode([np.float32(1.5), np.int64(3), np.bool_(True)])) == [1.5, 3, True]


class AlwaysEqual(np.ndarray):
    def __eq__(self, other):
        return True


@pytest.mark.parametrize("value, fragment", [
    (np.zeros(3).view(AlwaysEqual), "ndarray subclass"),
    (np.array([object()]), "dtype object"),
    (object(), "returned an object, which cannot be sent back"),
    ({1: 2}, "non-string keys"),
    (np.ma.masked_array([1, 2]), "ndarray subclass"),
    (lambda: 0, "function"),
])
def test_everything_else_is_refused_with_a_reason(value, fragment):
    with pytest.raises(TransportError, match=fragment):
        encode(value)


def test_size_cap():
    with pytest.raises(TransportError, match="more than"):
        encode(np.zeros(1000), max_bytes=1000)
    with pytest.raises(TransportError, match="too large"):
        decode(encode(np.zeros(1000)), max_bytes=1000)


@given(st.binary(max_size=300))
def test_random_bytes_never_crash_the_decoder(data):
    try:
        decode(data)
    except TransportError:
        pass


@given(values, st.data())
def test_corrupted_frames_are_rejected_or_decode_to_plain_data(value, data):
    frame = bytearray(encode(value))
    for _ in range(data.draw(st.integers(1, 4))):
        frame[data.draw(st.integers(0, len(frame) - 1))] = data.draw(st.integers(0, 255))
    try:
        decoded = decode(bytes(frame))
    except TransportError:
        return
    assert_plain(decoded)


def assert_plain(value):
    if isinstance(value, (list, tuple)):
        for v in value:
            assert_plain(v)
    elif isinstance(value, dict):
        for v in value.values():
            assert_plain(v)
    else:
        assert type(value) in (type(None), bool, int, float, complex, str, np.ndarray)


@pytest.mark.parametrize("header", [
    b'{"a":0,"dtype":"|O","shape":[1]}',                       # object dtype
    b'{"a":0,"dtype":"<f8","shape":[100]}',                    # more data than sent
    b'{"a":0,"dtype":"<f8","shape":[-1]}',                     # negative shape
    b'{"a":0,"dtype":"V8","shape":[1]}',                       # void
    b'{"a":0,"dtype":"<f8","shape":[1],"x":1}',                # extra keys
    b'{"__reduce__":"os.system"}',                             # not a node
    b'{"l":' * 200 + b'1' + b'}' * 200,                        # too deep
    b'{"f":"NaN"}',                                            # unknown float spelling
    b'NaN',                                                    # non-standard JSON
])
def test_hand_made_hostile_frames(header):
    frame = struct.pack(">4sQ", b"AGT1", len(header)) + header + b"\0" * 8
    with pytest.raises(TransportError):
        decode(frame)


def test_oversized_header_is_refused_before_it_is_parsed():
    header = b"[" * (MAX_HEADER_BYTES + 1)   # parsing this would recurse, then cost ~25x
    frame = struct.pack(">4sQ", b"AGT1", len(header)) + header
    with pytest.raises(TransportError, match="header larger than"):
        decode(frame)
    claimed = struct.pack(">4sQ", b"AGT1", 90 * 2**20) + b"[1]"  # a header longer than the frame
    with pytest.raises(TransportError):
        decode(claimed)


@pytest.mark.parametrize("header", [
    b'{"a":0,"dtype":"<f8","shape":[99999999999,99999999999,99999999999]}',  # size overflow
    b'{"a":0,"dtype":"<M8[s]","shape":[1]}',                                  # datetime
    b'{"a":0,"dtype":"\\u0000","shape":[1]}',                                 # nonsense dtype
    b'{"c":[{"f":"nan"},{"l":[]}]}',                                          # bad complex part
])
def test_any_decoding_error_is_a_transport_error(header):
    frame = struct.pack(">4sQ", b"AGT1", len(header)) + header + b"\0" * 8
    with pytest.raises(TransportError):
        decode(frame)


def test_control_characters_are_stripped_for_the_terminal():
    shown = printable("\x1b[2J\x1b[Hok\x1b]0;title\x07 \u202eevil\r\nnext\tcolumn\x9b")
    assert shown == "[2J[Hok]0;title evil\nnext\tcolumn"


def test_unicode_line_separators_break_lines_as_newlines_do_and_invisible_marks_go():
    """U+2028/U+2029 start a line in some renderers: they become the newline a message may hold anyway (kept
    inside its labelled block); bidirectional marks (U+061C), word joiners and byte-order marks are removed,
    zero-width joiners kept (names written in Persian or Hindi need them) -- hostile round of 2026-12-07."""
    assert printable("raised\u2028\u2502 total \u2502 65 / 65\u2029x") == "raised\n\u2502 total \u2502 65 / 65\nx"
    assert printable("a\u061cb\u2060c\ufeffd\u200de") == "abcd\u200de"
    from autograder.loading.text import one_line, shown
    assert shown("a\u2028b") == "a\\u2028b" and one_line("a\u2029b") == "a b"
