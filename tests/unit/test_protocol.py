"""Replies from the sandbox (slamcourse.sandbox.protocol): untrusted bytes decoded into plain
data, at the speed a batch needs (one reply per call, thousands per submission)."""

from __future__ import annotations

import base64
import json
import math
import struct

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from slamcourse.sandbox.protocol import (
    MAX_DEPTH,
    MAX_INT_DIGITS,
    ProtocolViolation,
    Unsupported,
    decode_frame,
    encode_calls,
    value_of,
)

# -- float arrays sent as bytes -----------------------------------------------------------


def f8(values: np.ndarray, shape: object = None) -> bytes:
    raw = base64.b64encode(np.asarray(values, dtype="<f8").tobytes()).decode()
    shape = list(np.shape(values)) if shape is None else shape
    return json.dumps({"$f8": raw, "shape": shape}).encode()


any_float = st.floats(allow_nan=True, allow_infinity=True)


def reply(value_json: bytes) -> bytes:
    return b'{"id":3,"status":"ok","value":' + value_json + b"}"


finite = st.floats(allow_nan=False, allow_infinity=False)
leaves = st.one_of(st.none(), st.booleans(), st.integers(-(10**30), 10**30), finite, st.text())
values = st.recursive(leaves, lambda inner: st.lists(inner, max_size=5), max_leaves=40)


@given(values)
def test_a_value_comes_back_as_it_was_sent(value: object) -> None:
    frame = decode_frame(json.dumps({"id": 3, "status": "ok", "value": value}).encode())
    assert value_of(frame) == value


@given(st.lists(st.lists(finite, min_size=3, max_size=3), min_size=70, max_size=90))
def test_a_matrix_with_more_rows_than_the_depth_limit_is_plain_data(rows: list) -> None:
    frame = decode_frame(reply(json.dumps(rows).encode()))
    assert value_of(frame) == rows


def test_long_integers_are_refused_in_short_and_long_replies() -> None:
    too_long = b"7" * (MAX_INT_DIGITS + 1)
    for padding in (b"", b"[" + b"1.5," * 2000 + b"1.5],"):
        with pytest.raises(ProtocolViolation, match="digits"):
            decode_frame(reply(b"[" + padding + too_long + b"]"))
    fine = b"7" * MAX_INT_DIGITS
    assert value_of(decode_frame(reply(b"[" + b"1.5," * 2000 + fine + b"]")))[-1] == int(fine)


def test_markers_nesting_and_constants() -> None:
    marker = value_of(decode_frame(reply(b'[[1.0], {"unsupported": "set"}]')))
    assert marker[0] == [1.0] and isinstance(marker[1], Unsupported)
    deep = b"[" * (MAX_DEPTH + 2) + b"]" * (MAX_DEPTH + 2)
    with pytest.raises(ProtocolViolation, match="deeply"):
        value_of(decode_frame(reply(deep)))
    with pytest.raises(ProtocolViolation, match="not a marker"):
        value_of(decode_frame(reply(b'[{"a": 1}, {"b": 2}]')))
    nan, inf = value_of(decode_frame(reply(b"[NaN, -Infinity]")))
    assert math.isnan(nan) and inf == -math.inf
    with pytest.raises(ProtocolViolation, match="unreadable"):
        decode_frame(b'{"id":3,"status":"ok","value":"\xff"}')


@given(
    st.lists(any_float, min_size=1, max_size=24).flatmap(
        lambda xs: st.sampled_from([(len(xs),), (1, len(xs)), (len(xs), 1, 1)]).map(
            lambda shape: np.array(xs).reshape(shape)
        )
    )
)
def test_a_float_array_sent_as_bytes_comes_back_bit_for_bit(array: np.ndarray) -> None:
    """The nested lists ``tolist`` gives, with every float's bits (NaN, −0.0, infinities)."""
    got = value_of(decode_frame(reply(b"[1, " + f8(array) + b"]")))[1]
    flat = np.array(got, dtype=float).reshape(-1)
    assert np.shape(got) == array.shape and type(np.asarray(got).tolist()) is list
    bits = [struct.pack("<d", v) for v in flat]
    assert bits == [struct.pack("<d", v) for v in array.reshape(-1).tolist()]


def test_a_float_array_marker_is_read_strictly() -> None:
    three = np.arange(3.0)
    assert value_of(decode_frame(reply(f8(three)))) == [0.0, 1.0, 2.0]
    assert value_of(decode_frame(reply(f8(np.zeros((0, 3)))))) == []
    bad = [
        f8(three, [4]),  # bytes that do not fill the shape
        f8(three, [-3]),
        f8(three, []),
        f8(three, [3.0]),
        f8(three, "3"),
        f8(three, [1] * (MAX_DEPTH + 1)),
        f8(np.zeros(0), [0, 10**30]),  # no bytes, a size numpy cannot hold
        b'{"$f8": "AAAA!AAA", "shape": [0]}',  # not canonical base64
        b'{"$f8": 3, "shape": [0]}',
        b'{"$f8": "", "shape": [0], "x": 1}',
        b'{"$f9": "", "shape": [0]}',
    ]
    for case in bad:
        with pytest.raises(ProtocolViolation):
            value_of(decode_frame(reply(case)))


arguments = st.recursive(
    st.one_of(
        leaves,
        st.floats(allow_nan=True, allow_infinity=True),
        st.sampled_from(["θ", "", "edge"]),
        st.lists(st.floats(-1e6, 1e6), max_size=8).map(np.array),
        st.lists(st.integers(-5, 5), max_size=6).map(lambda xs: np.array(xs, dtype=np.int32)),
        st.just(np.zeros((0, 3))),
    ),
    lambda inner: st.one_of(
        st.lists(inner, max_size=4),
        st.lists(inner, max_size=4).map(tuple),
        st.dictionaries(st.text(max_size=3), inner, max_size=3),
    ),
    max_leaves=30,
)


@given(st.lists(st.lists(arguments, min_size=1, max_size=3), min_size=1, max_size=4))
def test_a_calls_argument_pickle_is_its_own_record(calls: list) -> None:
    """The worker decides "unchanged" by pickling a call's arguments again and comparing the
    bytes with the pickle it read them from (encode_calls): for every argument the grader can
    send, untouched arguments must give the very same bytes, or every call would fall back to
    the slow comparison (the verdict would still be right, only slower)."""
    import pickle

    body = encode_calls(calls)
    head, data = body.split(b"\n", 1)
    assert json.loads(b"{" + head) == {"op": "calls", "pickled": len(data)}
    records = pickle.loads(data)
    assert len(records) == len(calls)
    for record in records:
        assert pickle.dumps(pickle.loads(record), protocol=5) == record
