"""The parent's side of the worker protocol: encoding arguments, decoding untrusted replies.

Frames are single lines of JSON. Requests (parent → worker)::

    {"id": 1, "op": "load", "source": "...", "filename": "f.py", "function": "f", "params": [...]}
    {"id": 2, "op": "call", "args": [...]}
    {"id": 3, "op": "calls", "calls": [[...], [...], ...]}   (answered by frames 3, 4, ...)

A ``check: false`` member turns off the worker's comparison of the arguments before and after
each call (``mutated`` in a reply lists the positions of the arguments a call changed).

A batch's ``calls`` request (:func:`encode_calls`) carries its argument lists after the line
instead of in it: ``{"id": 3, "op": "calls", "pickled": N}`` is followed by N bytes, the pickle
of a list holding each call's argument list pickled on its own, each argument already in the
exact form the tags below rebuild (:func:`plain_arg`). Those per-call bytes are also the
worker's record for the in-place check: arguments that pickle to the same bytes after the call
are unchanged. Pickle goes from the grader to the worker only, never back: the worker is the
side at risk from what it unpickles, and it already runs the learner's code; the grader's
reads stay JSON.

Inside ``args`` tuples, dicts and numpy arrays are tagged so that they arrive as such:
``{"$tuple": [...]}``, ``{"$dict": [[key, value], ...]}`` and
``{"$ndarray": [...], "$dtype": "float64", "$shape": [...]}`` (the shape: an empty array keeps its
other dimensions).

Replies (worker → parent) are *untrusted*: :func:`decode_frame` accepts at most one JSON object
of at most ``frame_bytes`` bytes, refuses huge integers and deep nesting, maps ``NaN`` and
``Infinity`` to floats (callers must reject non-finite values), and turns
``{"unsupported": "<type>"}`` markers into :class:`Unsupported` values, and float arrays sent as
bytes (``{"$f8": "<base64>", "shape": [...]}``) into the nested lists of their values. Nothing
is ever unpickled or evaluated.
"""

from __future__ import annotations

import binascii
import itertools
import json
import math
import pickle
import re
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from slamcourse.errors import GraderError

MAX_DEPTH = 64
MAX_INT_DIGITS = 4000  # Python refuses int(str) beyond 4300 digits; stay below
MAX_TEXT = 2000
MAX_FRAMES = 20

_CONSTANTS = {"NaN": math.nan, "Infinity": math.inf, "-Infinity": -math.inf}
_DIGITS_AS_D = bytes.maketrans(b"0123456789", b"d" * 10)
_LONG_RUN = b"d" * (MAX_INT_DIGITS + 1)  # (a run of the letter d, too, takes the careful path)


class ProtocolViolation(Exception):
    """A reply that breaks the protocol. Never shown as a pass; the worker is killed."""


@dataclass(frozen=True)
class Unsupported:
    """A value the learner returned that cannot cross the sandbox boundary (e.g. a dict,
    a generator, a float subclass or an object with a custom ``__eq__``)."""

    type_name: str

    def __str__(self) -> str:
        return f"<unsupported value of type {self.type_name}>"


@dataclass(frozen=True)
class LearnerFrame:
    """One traceback frame from the learner's own file."""

    line: int
    text: str
    function: str


# -- text -----------------------------------------------------------------------------------

_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f\u200e\u200f\u202a-\u202e\u2066-\u2069]")


def clean_text(data: bytes | str, limit: int | None = None) -> str:
    """Decode untrusted output for display: invalid UTF-8 replaced, control characters
    (escape sequences, bidi overrides; not newlines and tabs) removed."""
    text = data.decode("utf-8", errors="replace") if isinstance(data, bytes) else data
    text = _CONTROL.sub("", text.replace("\r\n", "\n"))
    if limit is not None and len(text) > limit:
        text = text[:limit] + "…"
    return text


# -- requests -------------------------------------------------------------------------------


def encode_request(frame: dict[str, Any]) -> bytes:
    """One request line. ``args`` (if present) is tagged with :func:`encode_arg`."""
    if "args" in frame:
        frame = {**frame, "args": [encode_arg(a, 0) for a in frame["args"]]}
    if "calls" in frame:
        frame = {**frame, "calls": [[encode_arg(a, 0) for a in args] for args in frame["calls"]]}
    return (json.dumps(frame, allow_nan=True, separators=(",", ":")) + "\n").encode()


def encode_calls(calls: Sequence[Sequence[Any]]) -> bytes:
    """The body of a ``calls`` request without its id (``"op":"calls",...}``, the line end and
    the pickled argument lists): :meth:`Worker.call_many` prefixes the id, so a body can be
    encoded once and sent to many workers. Each call's argument list is pickled on its own:
    the worker reads a call's arguments from its pickle and, after the call, pickles them again
    to see whether the call changed them (same bytes: unchanged), so no copy is made before
    each call. Decoding a pickle costs the worker a fifth of what JSON with tags costs."""
    data = pickle.dumps(
        [pickle.dumps([plain_arg(a, 0) for a in one], protocol=5) for one in calls], protocol=5
    )
    head = json.dumps({"op": "calls", "pickled": len(data)})
    return (head[1:] + "\n").encode() + data


def plain_arg(value: Any, depth: int = 0) -> Any:
    """``value`` as the worker receives it: lists, tuples and dicts of the basic types
    (subclasses such as IntEnum become the basic type, numpy scalars Python numbers), numpy
    arrays as fresh native C-ordered arrays of the same dtype name; raises
    :class:`GraderError` for anything else.

    Containers are recognised by type, whatever is imported; numpy is consulted only for a
    value that no other rule matched, and only if numpy is already loaded (a numpy value
    cannot exist otherwise), so encoding never imports numpy and never depends on which
    modules the process happens to have imported.
    """
    if depth > MAX_DEPTH:
        raise GraderError("argument nested too deeply to send to the sandbox")
    if value is None:
        return None
    if isinstance(value, bool | int | float | str):
        if isinstance(value, int) and value.bit_length() > 10_000:
            raise GraderError("integer argument too large to send to the sandbox")
        return value if type(value) in (bool, int, float, str) else _plain(value)
    if isinstance(value, tuple):
        return tuple(plain_arg(v, depth + 1) for v in value)
    if isinstance(value, list):
        return [plain_arg(v, depth + 1) for v in value]
    if isinstance(value, dict):
        return {plain_arg(k, depth + 1): plain_arg(v, depth + 1)
                for k, v in value.items()}  # fmt: skip
    np = sys.modules.get("numpy")
    if np is not None:
        if isinstance(value, np.generic) and value.dtype.kind in "biuf":
            return value.item()
        if isinstance(value, np.ndarray) and value.dtype.kind in "biuf":
            return value.astype(value.dtype.name, order="C")  # a copy, native byte order
    raise GraderError(f"cannot send a {type(value).__name__} to the sandbox")


def encode_arg(value: Any, depth: int = 0) -> Any:
    """One argument as JSON data (:func:`plain_arg`, then tuples, dicts and arrays tagged as
    the module docstring says); raises :class:`GraderError` as plain_arg."""
    return _tagged(plain_arg(value, depth))


def _tagged(value: Any) -> Any:
    """:func:`plain_arg`'s output with its tuples, dicts and arrays tagged for JSON."""
    kind = type(value)
    if kind is tuple:
        return {"$tuple": [_tagged(v) for v in value]}
    if kind is list:
        return [_tagged(v) for v in value]
    if kind is dict:
        return {"$dict": [[_tagged(k), _tagged(v)] for k, v in value.items()]}
    if value is None or kind in (bool, int, float, str):
        return value
    return {"$ndarray": value.tolist(), "$dtype": value.dtype.name, "$shape": list(value.shape)}


def _plain(value: bool | int | float | str) -> bool | int | float | str:
    """Subclasses of the basic types (e.g. IntEnum) become the basic type."""
    for kind in (bool, int, float, str):
        if isinstance(value, kind):
            return kind(value)
    raise GraderError(f"cannot send a {type(value).__name__} to the sandbox")


# -- replies --------------------------------------------------------------------------------


def _parse_int(text: str) -> int:
    if len(text) > MAX_INT_DIGITS:
        raise ProtocolViolation(f"integer with {len(text)} digits")
    return int(text)


_DECODER = json.JSONDecoder(parse_constant=_CONSTANTS.__getitem__)
_CAREFUL_DECODER = json.JSONDecoder(parse_constant=_CONSTANTS.__getitem__, parse_int=_parse_int)
"""Made once: ``json.loads`` with keyword arguments builds a new decoder for every reply (and
``raw_decode`` skips its two whitespace regular expressions)."""


def decode_frame(line: bytes) -> dict[str, Any]:
    """Parse one reply line into a dict with an integer ``id`` and a string ``status``."""
    try:
        text = line.decode("utf-8").strip(" \t\n\r")  # (JSON's whitespace, as json.loads)
        if len(line) <= MAX_INT_DIGITS or _LONG_RUN not in line.translate(_DIGITS_AS_D):
            obj, end = _DECODER.raw_decode(text)
        else:
            obj, end = _CAREFUL_DECODER.raw_decode(text)
        if end != len(text):
            raise ValueError("extra data after the reply")
    except ProtocolViolation:
        raise
    except (ValueError, RecursionError, KeyError, MemoryError) as exc:
        raise ProtocolViolation(f"unreadable reply ({type(exc).__name__})") from None
    if type(obj) is not dict:
        raise ProtocolViolation("reply is not a JSON object")
    if type(obj.get("id")) is not int or type(obj.get("status")) is not str:
        raise ProtocolViolation("reply without an integer id and a status")
    # the common reply: one JSON object (the envelope) and shallow lists, so its value holds
    # only JSON scalars and lists; :func:`value_of` then need not walk it
    obj["$plain"] = line.count(b"{") == 1 and line.count(b"[") <= MAX_DEPTH
    return obj


def value_of(frame: dict[str, Any]) -> Any:
    """A decoded reply's validated return value (see :func:`plain_value`)."""
    value = frame["value"]
    return value if frame.get("$plain") is True else plain_value(value)


def value_and_array(frame: dict[str, Any]) -> tuple[Any, Any]:
    """:func:`value_of`, and the value as a float64 ndarray when it came as one (a float array
    sent as bytes, not empty: its lists have its shape), else None; the grader compares the
    array without converting the lists back."""
    value = frame["value"]
    if type(value) is dict and len(value) == 2 and "$f8" in value:
        array = float_ndarray(value)
        return array.tolist(), array if array.size else None
    return value_of(frame), None


_LEAVES = frozenset({type(None), bool, int, float, str})


def plain_value(value: Any, depth: int = 0) -> Any:
    """Validate a decoded return value: JSON scalars, lists, and unsupported markers only."""
    if depth > MAX_DEPTH:
        raise ProtocolViolation("return value nested too deeply")
    if value is None or type(value) in (bool, int, float, str):
        return value
    if type(value) is list:
        if _LEAVES.issuperset(map(type, value)):  # a row of numbers: decoded fresh, kept
            return value
        if (
            depth < MAX_DEPTH
            and set(map(type, value)) == {list}
            and _LEAVES.issuperset(map(type, itertools.chain.from_iterable(value)))
        ):  # a matrix
            return value
        return [plain_value(v, depth + 1) for v in value]
    if type(value) is dict and len(value) == 1 and type(value.get("unsupported")) is str:
        return Unsupported(clean_text(value["unsupported"], 100))
    if type(value) is dict and len(value) == 2 and "$f8" in value:
        return float_array(value, depth)
    raise ProtocolViolation("return value contains a JSON object that is not a marker")


def float_array(marker: dict[str, Any], depth: int = 0) -> list[Any]:
    """The nested lists of a float array sent as bytes: ``{"$f8": "<base64 of float64 values,
    little-endian, C order>", "shape": [d1, d2, ...]}``, checked strictly (canonical base64, a
    shape of at least one non-negative size that the bytes fill exactly)."""
    values: list[Any] = float_ndarray(marker, depth).tolist()
    return values


def float_ndarray(marker: dict[str, Any], depth: int = 0) -> Any:
    """:func:`float_array`'s values as a read-only float64 ndarray of the marker's shape."""
    import numpy as np

    data, shape = marker.get("$f8"), marker.get("shape")
    if (
        type(data) is not str
        or type(shape) is not list
        or not 1 <= len(shape) <= MAX_DEPTH - depth
        or any(type(n) is not int or n < 0 for n in shape)
    ):
        raise ProtocolViolation("malformed float array")
    try:
        raw = binascii.a2b_base64(data, strict_mode=True)
    except (binascii.Error, ValueError):
        raise ProtocolViolation("float array with malformed base64") from None
    if len(raw) != 8 * math.prod(shape):
        raise ProtocolViolation("float array whose bytes do not fill its shape")
    try:
        return np.frombuffer(raw, dtype="<f8").reshape(shape)
    except (ValueError, OverflowError):  # e.g. an empty array of a dimension numpy cannot hold
        raise ProtocolViolation("float array of an impossible shape") from None


def text_field(frame: dict[str, Any], key: str, limit: int = MAX_TEXT) -> str:
    value = frame.get(key, "")
    if type(value) is not str:
        raise ProtocolViolation(f"reply field {key!r} is not a string")
    return clean_text(value, limit)


def int_or_none(frame: dict[str, Any], key: str) -> int | None:
    value = frame.get(key)
    if value is None:
        return None
    if type(value) is not int:
        raise ProtocolViolation(f"reply field {key!r} is not an integer")
    return value


def names_field(frame: dict[str, Any], key: str) -> tuple[str, ...]:
    value = frame.get(key, [])
    if type(value) is not list or len(value) > 100 or any(type(v) is not str for v in value):
        raise ProtocolViolation(f"reply field {key!r} is not a list of names")
    return tuple(clean_text(v, 100) for v in value)


def frames_field(frame: dict[str, Any]) -> tuple[LearnerFrame, ...]:
    value = frame.get("frames", [])
    if type(value) is not list:
        raise ProtocolViolation("reply field 'frames' is not a list")
    out = []
    for item in value[-MAX_FRAMES:]:
        if (
            type(item) is not dict
            or type(item.get("line")) is not int
            or type(item.get("text")) is not str
            or type(item.get("function")) is not str
        ):
            raise ProtocolViolation("malformed traceback frame")
        out.append(
            LearnerFrame(
                item["line"], clean_text(item["text"], 200), clean_text(item["function"], 100)
            )
        )
    return tuple(out)
