"""The conventions a notebook and the batch grader share: which cell answers which exercise.

Standard library only: the batch grader reads handed-in notebooks with it (never running
them) and the notebook face writes what the grader reads. docs/submissions.md, "Notebooks",
is the contract:

- an exported notebook marks its cells with metadata ``{"slamcourse": {"exercise": ID,
  "role": "prompt" | "answer"}}`` (and ``{"role": "setup"}`` for its first code cell);
- a code exercise is answered by a cell whose first line is ``%%slamcourse check ID``: the
  rest of the cell is the source graded;
- any exercise by a top-level call ``check("ID", ANSWER)`` in a code cell: a literal
  ``ANSWER`` (a string, a number, a list of numbers) is the answer; anything else is read from
  what the cell displayed when it last ran (the answer text, or the source of a function, the
  notebook graded: recorded in the output's metadata), else from its source text;
- every output of the notebook face carries ``{"slamcourse": {...}}`` metadata naming the
  learner (seed and id), the course (version and hash) and, for a checked answer, the
  exercise and the answer text (or source) graded.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from typing import Any

META = "slamcourse"
"""The key of slamcourse's cell and output metadata."""
MAGIC = "slamcourse"
"""The cell magic's name: ``%%slamcourse check ID``."""
CHECK = "check"
"""The function a text answer calls: ``check("ID", answer)``."""

_MAGIC_LINE = re.compile(r"^%%" + MAGIC + r"(?:[ \t]+(?P<args>.*))?$")


def magic_line(exercise_id: str) -> str:
    """The first line of a code exercise's answer cell."""
    return f"%%{MAGIC} {CHECK} {exercise_id}"


def parse_magic_args(args: str) -> tuple[str, str] | None:
    """``check ID`` → ``("check", ID)``; None when the arguments are not that."""
    words = args.split()
    if len(words) == 2 and words[0] == CHECK:
        return words[0], words[1]
    return None


@dataclass(frozen=True)
class CodeCell:
    """A code exercise's answer: the cell's source after its magic line."""

    exercise: str
    source: str


def code_answer(cell_source: str) -> CodeCell | None:
    """The code answer a cell holds (its first line is ``%%slamcourse check ID``), or None."""
    first, _, rest = cell_source.partition("\n")
    match = _MAGIC_LINE.match(first.strip())
    if match is None:
        return None
    parsed = parse_magic_args(match.group("args") or "")
    if parsed is None:
        return None
    return CodeCell(parsed[1], rest)


@dataclass(frozen=True)
class CheckCall:
    """A top-level ``check("ID", ANSWER)`` in a cell. ``text``: the answer as the notebook
    would grade it when ``ANSWER`` is a literal (None: not a literal); ``expression``: the
    source text of ``ANSWER``; ``empty``: no answer given yet (``""``, ``...``, ``None``)."""

    exercise: str
    text: str | None
    expression: str
    empty: bool


def _python(cell_source: str) -> str:
    """A cell's source as Python: IPython's line magics and shell escapes (``%time``,
    ``!ls``) blanked, so the rest parses; line numbers are kept."""
    lines = []
    for line in cell_source.splitlines():
        stripped = line.lstrip()
        lines.append("" if stripped.startswith(("%", "!")) else line)
    return "\n".join(lines)


def check_calls(cell_source: str) -> list[CheckCall]:
    """Every top-level ``check("ID", ANSWER)`` statement of a code cell, in order (a cell that
    does not parse holds none). The cell is parsed, never run."""
    source = _python(cell_source)
    try:
        tree = ast.parse(source)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return []
    calls: list[CheckCall] = []
    for stmt in tree.body:
        node = stmt.value if isinstance(stmt, ast.Expr) else None
        if isinstance(stmt, ast.Assign):
            node = stmt.value  # result = check("ID", ...)
        if not (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Name)
            and node.func.id == CHECK
            and len(node.args) >= 2
            and isinstance(node.args[0], ast.Constant)
            and isinstance(node.args[0].value, str)
        ):
            continue
        arg = node.args[1]
        expression = ast.get_source_segment(source, arg) or ""
        try:
            value = ast.literal_eval(arg)
        except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
            calls.append(CheckCall(node.args[0].value, None, expression, False))
            continue
        text = answer_text(value)
        calls.append(CheckCall(node.args[0].value, text, expression, text is None or not text))
    return calls


def answer_text(value: Any) -> str | None:
    """A Python value as the answer text the engine reads, or None for "no answer yet"
    (``None``, ``...``). A string is used as it is; a number in full precision; a list,
    tuple or array as ``[a, b]`` (nested for a matrix); choice ids as ``a, c``. Anything
    else becomes its ``repr``, which the engine then reports as unreadable."""
    if value is None or value is Ellipsis:
        return None
    if isinstance(value, str):
        return value
    tolist = getattr(value, "tolist", None)
    if callable(tolist) and not isinstance(value, (list, tuple)):
        value = tolist()  # numpy arrays and scalars
    if isinstance(value, bool):
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, (list, tuple)):
        if value and all(isinstance(v, str) for v in value):
            return ", ".join(value)
        parts = [answer_text(v) for v in value]
        if any(p is None for p in parts):
            return repr(value)
        return "[" + ", ".join(p for p in parts if p is not None) + "]"
    return repr(value)
