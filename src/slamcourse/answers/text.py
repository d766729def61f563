"""The one decoding policy for a learner's answer text.

Answers reach the grader as bytes (a web request body, a pipe) or as ``str`` from places that
already decoded them leniently: Python decodes ``argv`` and ``stdin`` with ``surrogateescape``,
so ``--answer=$'6\\x80'`` arrives as ``'6\\udc80'``, and a JSON string may hold ``"\\ud800"``.
Such text cannot be stored (SQLite, JSON files), printed on a UTF-8 terminal, or parsed.

Policy: an answer is readable only if it is valid Unicode text, i.e. bytes that decode as
UTF-8, or a ``str`` without lone surrogates (U+D800–U+DFFF). Anything else raises
:class:`~slamcourse.errors.AnswerFormatError`, which every kind turns into an ``invalid``
verdict ("unreadable", no attempt counted). The message says where the bad character is and
never repeats it, so the verdict itself is always printable and storable.

Every answer parser (:mod:`~slamcourse.answers.parse`, :func:`~slamcourse.answers.expr.
compile_expression`) calls :func:`decode_answer` first, so every kind applies the policy
without a check of its own.
"""

from __future__ import annotations

import re

from slamcourse.errors import AnswerFormatError

__all__ = ["decode_answer", "unreadable_at"]

_SURROGATE = re.compile(r"[\ud800-\udfff]")

UNREADABLE = (
    "unreadable answer: character {position} is not text ({what}); retype the answer as plain "
    "text (UTF-8)"
)


def unreadable_at(text: str) -> tuple[int, str] | None:
    """The index of the first lone surrogate in ``text`` and what it stands for, or None.

    ``\\udc80``–``\\udcff`` are bytes that were not UTF-8 (Python's ``surrogateescape``);
    other surrogates are halves of a UTF-16 pair that lost its partner."""
    found = _SURROGATE.search(text)
    if found is None:
        return None
    code = ord(found.group())
    if 0xDC80 <= code <= 0xDCFF:
        return found.start(), f"the byte 0x{code - 0xDC00:02x} is not UTF-8"
    return found.start(), f"a lone UTF-16 surrogate U+{code:04X}"


def decode_answer(raw: str | bytes) -> str:
    """``raw`` as text, or :class:`AnswerFormatError` when it is not valid Unicode text.

    Bytes must be UTF-8; a ``str`` must not contain lone surrogates (:func:`unreadable_at`).
    Valid text is returned unchanged.
    """
    if isinstance(raw, bytes | bytearray):
        data = bytes(raw)
        try:
            return data.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise AnswerFormatError(
                UNREADABLE.format(
                    position=len(data[: exc.start].decode("utf-8", "replace")) + 1,
                    what=f"the byte 0x{data[exc.start]:02x} is not UTF-8",
                )
            ) from None
    bad = unreadable_at(raw)
    if bad is None:
        return raw
    raise AnswerFormatError(UNREADABLE.format(position=bad[0] + 1, what=bad[1]))
