"""Reading and comparing learners' answers.

- :mod:`~slamcourse.answers.expr`: the safe formula evaluator (also used for course parameters).
- :mod:`~slamcourse.answers.parse`: numbers, vectors, matrices and choice ids from text.
- :mod:`~slamcourse.answers.text`: the decoding policy (invalid bytes and lone surrogates make an
  answer unreadable) that every parser applies first.
- :mod:`~slamcourse.answers.compare`: tolerance windows, angle wrapping, entry comparison and
  number formatting.

Importing this package never imports numpy.
"""

from slamcourse.answers.compare import (
    EntryComparison,
    angle_is_close,
    compare_entries,
    format_about,
    format_number,
    format_window,
    is_close,
    plural,
    tolerance_window,
    wrap_angle,
)
from slamcourse.answers.expr import Expression, compile_expression, evaluate_number
from slamcourse.answers.parse import (
    parse_ids,
    parse_integer,
    parse_matrix,
    parse_number,
    parse_vector,
)
from slamcourse.answers.text import decode_answer

__all__ = [
    "EntryComparison",
    "Expression",
    "angle_is_close",
    "compare_entries",
    "compile_expression",
    "decode_answer",
    "evaluate_number",
    "format_about",
    "format_number",
    "format_window",
    "is_close",
    "parse_ids",
    "parse_integer",
    "parse_matrix",
    "parse_number",
    "parse_vector",
    "plural",
    "tolerance_window",
    "wrap_angle",
]
