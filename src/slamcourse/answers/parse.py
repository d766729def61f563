"""Reading learners' answers: numbers, vectors, matrices and choice ids.

Every parser takes any string and either returns a value or raises
:class:`~slamcourse.errors.AnswerFormatError` whose message says what was wrong and which form
was expected, with an example. No other exception escapes for any input string.

Entries are formulas read by :mod:`slamcourse.answers.expr` without variables, so ``pi/4``,
``-sqrt(2)``, ``7/5``, ``2π`` and ``1e-3`` are all numbers.

Splitting a list into entries (vectors and matrix rows): at top-level commas or semicolons when
there are any (brackets group, so ``atan2(1, 2)`` stays one entry); otherwise at top-level
whitespace, where a space next to ``*``, ``/``, ``**`` or ``^`` joins (``pi / 4`` is one entry),
a sign attached to a number starts an entry (``0.3 -0.09`` is two entries), and a sign standing
alone (``0.3 - 0.09``) is an error in a list because it is ambiguous. A single number follows
the same rule, except that a lone sign is simply subtraction (``1 - 0.5`` is 0.5).
"""

from __future__ import annotations

import re

from slamcourse.answers.compare import format_number
from slamcourse.answers.expr import CONSTANTS, FUNCTIONS, MAX_CHARS, evaluate_number
from slamcourse.answers.text import decode_answer
from slamcourse.errors import AnswerFormatError

__all__ = ["parse_ids", "parse_integer", "parse_matrix", "parse_number", "parse_vector"]

NUMBER_FORM = "a number such as 0.25, 7/5 or pi/4"
INTEGER_FORM = "a whole number such as 9"
VECTOR_FORM = "a vector such as [0.3, -0.09] or 0.3 -0.09"
MATRIX_FORM = "a matrix such as [[1, 2], [3, 4]] or [1 2; 3 4]"
IDS_FORM = "choice ids such as 'a', 'a c' or 'a, c'"

_OPENERS = {"(": ")", "[": "]", "{": "}"}
_CLOSERS = {v: k for k, v in _OPENERS.items()}
_BINARY_ONLY = ("*", "/", "^", "×", "÷", "·", "⋅", "²", "³", "=", "<", ">", "!")
_SIGNS = ("+", "-")

_DEGREES = re.compile(r"°|(?<![^\W\d_])(?:deg|degs|degree|degrees)(?![^\W\d_])", re.IGNORECASE)
_NONFINITE = re.compile(r"∞|(?<![^\W\d_])(?:nan|inf|infinity)(?![^\W\d_])", re.IGNORECASE)
_DECIMAL_COMMA = re.compile(r"[-+]?[0-9]+,[0-9]+")
_UNIT = re.compile(r"(?P<value>.*[0-9.)])\s*(?P<unit>[^\W\d_][\w/^²³·]*|%)", re.DOTALL)
_PLAIN_NUMBER = re.compile(r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")
_EXPONENT = re.compile(r"[eE][-+]?[0-9]")
_KNOWN_UNITS = frozenset(
    {
        *("m", "cm", "mm", "km", "um", "µm", "nm", "meter", "meters", "metre", "metres"),
        *("s", "ms", "us", "µs", "ns", "sec", "secs", "second", "seconds", "min", "h", "hr"),
        *("rad", "rads", "radian", "radians", "hz", "khz", "px", "pix", "pixel", "pixels"),
        *("kg", "g", "n", "j", "w", "v", "a", "%", "mps"),
    }
)
_ID = re.compile(r"[a-z0-9][a-z0-9_\-]*", re.ASCII)


# --------------------------------------------------------------------------------------------
# Bracket-aware scanning
# --------------------------------------------------------------------------------------------


def _clean(text: str) -> str:
    return text.replace("−", "-").replace("–", "-").strip()


def _snippet(text: str, limit: int = 30) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _check_length(text: str) -> None:
    if len(text) > MAX_CHARS:
        raise AnswerFormatError(
            f"the answer is too long ({len(text)} characters; at most {MAX_CHARS})"
        )


def _check_brackets(text: str, form: str) -> None:
    stack: list[str] = []
    for c in text:
        if c in _OPENERS:
            stack.append(c)
        elif c in _CLOSERS:
            if not stack:
                raise AnswerFormatError(
                    f"unbalanced brackets: '{c}' has no opening — expected {form}"
                )
            if stack.pop() != _CLOSERS[c]:
                raise AnswerFormatError(f"mismatched brackets at '{c}' — expected {form}")
    if stack:
        raise AnswerFormatError(
            f"unbalanced brackets: '{stack[-1]}' is never closed — expected {form}"
        )


def _match(text: str, start: int) -> int:
    """Index of the bracket closing the one at ``start`` (brackets are known to balance)."""
    depth = 0
    for i in range(start, len(text)):
        if text[i] in _OPENERS:
            depth += 1
        elif text[i] in _CLOSERS:
            depth -= 1
            if depth == 0:
                return i
    return len(text) - 1  # pragma: no cover - unreachable after _check_brackets


def _unwrap(text: str) -> str | None:
    """Inside of ``[…]`` or ``(…)`` when that pair encloses all of ``text``; else None."""
    if text and text[0] in "[(" and _match(text, 0) == len(text) - 1:
        return text[1:-1].strip()
    return None


def _top_split(text: str, separators: str) -> list[str]:
    """Split at separator characters outside brackets."""
    parts: list[str] = []
    depth, start = 0, 0
    for i, c in enumerate(text):
        if c in _OPENERS:
            depth += 1
        elif c in _CLOSERS:
            depth -= 1
        elif depth == 0 and c in separators:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return parts


def _has_top(text: str, chars: str) -> bool:
    return len(_top_split(text, chars)) > 1


def _top_words(text: str) -> list[str]:
    """Split at whitespace outside brackets."""
    words: list[str] = []
    depth, current = 0, ""
    for c in text:
        if c in _OPENERS:
            depth += 1
        elif c in _CLOSERS:
            depth -= 1
        if depth == 0 and c.isspace():
            if current:
                words.append(current)
            current = ""
        else:
            current += c
    if current:
        words.append(current)
    return words


def _joins(prev: str, word: str) -> bool:
    if prev.endswith((*_BINARY_ONLY, *_SIGNS)):
        return True
    return word.startswith(_BINARY_ONLY) or word in _SIGNS


def _space_entries(body: str, strict: bool) -> list[str]:
    entries: list[str] = []
    for word in _top_words(body):
        if entries and _joins(entries[-1], word):
            sign_apart = entries[-1].endswith(_SIGNS) or word in _SIGNS
            if strict and sign_apart:
                raise AnswerFormatError(
                    f"a sign stands apart from its number in '{_snippet(body)}': write -0.09 "
                    "(no space) for a negative entry, or separate entries with commas, "
                    "e.g. [0.3, -0.09]"
                )
            entries[-1] += " " + word
        else:
            entries.append(word)
    return entries


def _entries(body: str, strict: bool) -> list[str]:
    """The entries of a list body, by the module's splitting rule (a trailing ',' is ignored)."""
    if _has_top(body, ",;"):
        parts = [p.strip() for p in _top_split(body, ",;")]
        if len(parts) > 1 and not parts[-1]:
            parts.pop()
        return parts
    return _space_entries(body, strict)


# --------------------------------------------------------------------------------------------
# Numbers
# --------------------------------------------------------------------------------------------


def _unit_of(text: str) -> tuple[str, str] | None:
    """Value and trailing unit of ``5 m``, ``5m``, ``3.2 m/s`` or ``pi/4 rad``; else None."""
    m = _UNIT.fullmatch(text)
    if m is None:
        return None
    unit, value = m.group("unit"), m.group("value").strip()
    if _EXPONENT.match(unit) and value[-1].isdigit():
        return None  # scientific notation such as 1e5 or 1e308*10, not a unit
    word = re.match(r"[^\W\d_]\w*", unit)
    lead = word.group() if word else unit
    if lead in CONSTANTS or lead in FUNCTIONS or lead[0] in "πτ":
        return None
    if lead.lower() in _KNOWN_UNITS or _PLAIN_NUMBER.fullmatch(value):
        return value, unit
    return None


def _scalar(text: str, where: str, form: str, units: str = "") -> float:
    """One number; ``where`` prefixes messages (``"entry 2 ('x'): "``), ``form`` ends them.
    ``units``: the unit the exercise asks for; written after the number, it is accepted and
    changes nothing (``98.6%`` is 98.6 where the answer is in %). Any other unit is refused."""
    s = _clean(text)
    if not s:
        raise AnswerFormatError(
            f"{where}is empty — expected {form}" if where else f"empty answer — expected {form}"
        )
    _check_length(s)
    if _DEGREES.search(s):
        raise AnswerFormatError(
            f"{where}angles are in radians, not degrees — write e.g. pi/4 or 0.785 instead of 45°"
        )
    if _NONFINITE.search(s):
        raise AnswerFormatError(f"{where}'nan' and 'inf' are not answers — expected {form}")
    if not where and _DECIMAL_COMMA.fullmatch(s):
        raise AnswerFormatError("use a point as the decimal separator: 0.5, not 0,5")
    with_unit = _unit_of(s)
    if with_unit is not None and units and with_unit[1] == units.strip():
        s = with_unit[0]
    elif with_unit is not None:
        value, _unit = with_unit
        raise AnswerFormatError(
            f"{where}write the number without its unit: {_snippet(value)}, not {_snippet(s)}"
        )
    _check_brackets(s, form)
    _check_single(s, where)
    try:
        return evaluate_number(s)
    except AnswerFormatError as err:
        raise AnswerFormatError(f"{where}{err} — expected {form}") from None


def _check_single(s: str, where: str) -> None:
    spaced = not _has_top(s, ",;")
    if spaced:
        parts = _space_entries(s, strict=False)
    else:
        parts = [p for p in _top_split(s, ",;") if p.strip()]
    n = len(parts)
    if n > 1:
        product = spaced and any(not p.startswith(_SIGNS) for p in parts[1:])
        tip = " (for a product write '*', e.g. 2*pi)" if product else ""
        if where:
            raise AnswerFormatError(
                f"{where}holds {n} numbers — separate entries with commas, e.g. [0.3, -0.09]{tip}"
            )
        raise AnswerFormatError(f"expected one number, got {n} — give a single value{tip}")
    if n == 1 and s.rstrip().endswith((",", ";")):
        raise AnswerFormatError(f"{where}a trailing '{s.rstrip()[-1]}' — give a single value")


def parse_number(text: str, units: str = "") -> float:
    """Read one finite number.

    Forms: ``42``, ``-0.09``, ``1.5e-3``, ``7/5``, ``pi/4``, ``sqrt(2)/2``, ``2π``, ``−1`` (unicode
    minus); surrounding whitespace is ignored. Specific messages for an empty answer, several
    numbers (``0.3 -0.09``), degrees (``45°``), units (``5 m``), a decimal comma (``0,5``) and
    ``nan``/``inf``. With ``units`` (the exercise's declared unit, e.g. ``%``), that unit may
    follow the number and means the number as written: ``98.6%`` and ``98.6 %`` are 98.6.
    """
    return _scalar(decode_answer(text), "", NUMBER_FORM, units)


def parse_integer(text: str, units: str = "") -> int:
    """Read a whole number: ``9``, ``9.0``, ``1e3``, ``18/2`` (within 1e-9 of an integer);
    ``units`` as for :func:`parse_number`."""
    value = _scalar(decode_answer(text), "", INTEGER_FORM, units)
    nearest = round(value)
    if abs(value - nearest) > 1e-9:
        raise AnswerFormatError(f"expected a whole number such as 9, got {format_number(value)}")
    return int(nearest)


# --------------------------------------------------------------------------------------------
# Vectors and matrices
# --------------------------------------------------------------------------------------------


def _start(text: str, form: str) -> str:
    s = _clean(decode_answer(text))
    if not s:
        raise AnswerFormatError(f"empty answer — expected {form}")
    _check_length(s)
    _check_brackets(s, form)
    return s


def _matrix_like(why: str) -> AnswerFormatError:
    return AnswerFormatError(
        f"expected a vector; this looks like a matrix ({why}) — write a vector as [0.3, -0.09]"
    )


def _row_values(body: str, label: str, form: str) -> list[float]:
    entries = _entries(body, strict=True)
    values: list[float] = []
    for i, entry in enumerate(entries, 1):
        if not entry:
            raise AnswerFormatError(f"{label}entry {i} is empty — expected {form}")
        where = f"{label}entry {i} ('{_snippet(entry)}'): "
        inner = _unwrap(entry)
        if inner is not None and _has_top(inner, ","):
            raise AnswerFormatError(f"{where}a bracketed list inside a list — expected {form}")
        values.append(_scalar(entry, where, form))
    return values


def parse_vector(text: str) -> list[float]:
    """Read a vector of finite numbers.

    Forms: ``[0.3, -0.09]``, ``(0.3, -0.09)``, ``0.3, -0.09``, ``0.3 -0.09``, ``[0.3 -0.09]``
    (numpy's print style, line breaks allowed), ``0.3; -0.09``. Entries may be formulas
    (``pi/4``, ``-sqrt(2)``). Nested brackets are refused as a matrix.
    """
    s = _start(text, VECTOR_FORM)
    inner = _unwrap(s)
    body = s if inner is None else inner
    if "[" in body:
        if inner is None:
            raise AnswerFormatError(
                f"brackets must enclose the whole vector — expected {VECTOR_FORM}"
            )
        raise _matrix_like("nested brackets")
    if _has_top(body, ";") and _has_top(body, ","):
        raise _matrix_like("';' separates rows")
    if not body or not _entries(body, strict=True):
        raise AnswerFormatError(f"the vector is empty — expected {VECTOR_FORM}")
    if _has_top(body, ";"):
        for part in _top_split(body, ";"):
            if len(_space_entries(part.strip(), strict=False)) > 1:
                raise _matrix_like("';' separates rows")
    return _row_values(body, "", VECTOR_FORM)


def _bracket_rows(body: str) -> list[str] | None:
    """Rows written as bracket groups (``[1, 2], [3, 4]`` or ``(1, 2), (3, 4)``), else None."""
    groups: list[tuple[str, str]] = []
    other = False
    i = 0
    while i < len(body):
        c = body[i]
        if c in "[(":
            end = _match(body, i)
            groups.append((c, body[i + 1 : end]))
            i = end + 1
            continue
        if not (c.isspace() or c in ",;"):
            other = True
        i += 1
    if any(c == "[" for c, _ in groups):
        if other:
            raise AnswerFormatError(
                f"every row of a matrix must be in its own brackets — expected {MATRIX_FORM}"
            )
        return [g for _, g in groups]
    if groups and not other and all(_has_top(g, ",") for _, g in groups):
        return [g for _, g in groups]
    return None


def parse_matrix(text: str) -> list[list[float]]:
    """Read a matrix (rectangular, at least one entry) of finite numbers.

    Forms: ``[[1, 2], [3, 4]]``, numpy's ``[[1. 2.]\\n [3. 4.]]``, ``((1, 2), (3, 4))``,
    MATLAB's ``[1 2; 3 4]``, ``1 2; 3 4``, and rows on separate lines. Entries may be formulas.
    """
    s = _start(text, MATRIX_FORM)
    inner = _unwrap(s)
    body = s if inner is None else inner
    rows = _bracket_rows(body)
    if rows is None:
        if not (_has_top(body, ";\n\r")):
            raise AnswerFormatError(
                "expected a matrix; this looks like a flat list — write each row in its own "
                "brackets, e.g. [[1, 2], [3, 4]], or separate rows with ';' as in [1 2; 3 4]"
            )
        rows = [r for r in _top_split(body, ";\n\r") if r.strip()]
    if not rows:
        raise AnswerFormatError(f"the matrix is empty — expected {MATRIX_FORM}")
    matrix: list[list[float]] = []
    for r, row in enumerate(rows, 1):
        if "[" in row or "]" in row:
            raise AnswerFormatError(f"row {r} has brackets inside it — expected {MATRIX_FORM}")
        if not row.strip() or not _entries(row.strip(), strict=True):
            raise AnswerFormatError(f"row {r} is empty — expected {MATRIX_FORM}")
        matrix.append(_row_values(row.strip(), f"row {r}, ", MATRIX_FORM))
    lengths = [len(row) for row in matrix]
    if len(set(lengths)) > 1:
        raise AnswerFormatError(
            f"rows have different lengths ({', '.join(map(str, lengths))}) — every row needs "
            "the same number of entries, e.g. [[1, 2], [3, 4]]"
        )
    return matrix


# --------------------------------------------------------------------------------------------
# Choice ids
# --------------------------------------------------------------------------------------------


def parse_ids(text: str) -> list[str]:
    """Read choice or order ids, lowercased, in the order given.

    Forms: ``a``, ``a c``, ``a,c``, ``A, C``, ``[c, a, b]``, ``c a b``. Duplicates are kept (the
    caller decides what they mean).
    """
    text = decode_answer(text)
    _check_length(text)
    ids: list[str] = []
    for token in re.split(r"[\s,;]+", text):
        word = token.strip("()[]{}.'\"").lower()
        if not word:
            continue
        if not _ID.fullmatch(word):
            raise AnswerFormatError(f"'{_snippet(token)}' is not a choice id — expected {IDS_FORM}")
        ids.append(word)
    if not ids:
        raise AnswerFormatError(f"empty answer — expected {IDS_FORM}")
    return ids
