"""Verdicts: what every checker returns. A learner's mistake is data, never an exception.

Feedback is Markdown, and only course text (a misconception's message, an option's feedback)
is written as Markdown. The engine's own words and whatever they quote of a learner's answer
are literal: they enter the feedback through :func:`literal` (``2*pi`` stays ``2*pi``, a
learner's ``$x$`` is never typeset, ``<b>`` is never a tag), which keeps only the ``code
spans`` the engine writes itself (:func:`engine_text`).
"""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass, field
from typing import Any, Literal

from slamcourse.errors import EXIT_GRADER, EXIT_NOT_PASSED, EXIT_PASSED

Status = Literal["passed", "failed", "invalid", "timeout", "error"]
STATUSES: tuple[Status, ...] = ("passed", "failed", "invalid", "timeout", "error")


@dataclass(frozen=True)
class Verdict:
    """The outcome of checking one answer.

    - ``passed``: accepted; ``failed``: readable but wrong; ``invalid``: could not be read
      (costs no attempt); ``timeout``: learner code ran out of time; ``error``: the grader's
      own fault (costs no attempt, said as such).
    - ``score`` is in [0, 1] (partial credit for order and multi-select answers).
    - ``feedback`` is the text shown to the learner; ``misconception`` the id of the declared
      misconception the answer matched, if any; ``details`` machine-readable extras
      (accepted window, wrong entries, counterexample, ...), JSON-serialisable.
    """

    status: Status
    score: float
    feedback: str
    misconception: str | None = None
    details: dict[str, Any] = field(default_factory=dict)
    learner_seconds: float = field(default=0.0, compare=False)
    """Wall time spent inside the learner's code (code exercises; a timing, so it is kept out
    of :meth:`to_dict`, which must be the same for the same answer)."""

    def __post_init__(self) -> None:
        if self.status not in STATUSES:
            raise ValueError(f"unknown verdict status {self.status!r}")
        if not 0.0 <= self.score <= 1.0:
            raise ValueError(f"score {self.score} outside [0, 1]")

    @property
    def passed(self) -> bool:
        return self.status == "passed"

    @property
    def counts_as_attempt(self) -> bool:
        """Unreadable answers and grader faults do not use up an attempt."""
        return self.status not in ("invalid", "error")

    @property
    def exit_code(self) -> int:
        if self.status == "passed":
            return EXIT_PASSED
        if self.status == "error":
            return EXIT_GRADER
        return EXIT_NOT_PASSED

    def to_dict(self) -> dict[str, Any]:
        data = asdict(self)
        del data["learner_seconds"]
        return data

    # Convenience constructors keep call sites short and uniform.
    @classmethod
    def ok(cls, feedback: str = "Correct.", **details: Any) -> Verdict:
        return cls("passed", 1.0, feedback, details=details)

    @classmethod
    def wrong(
        cls, feedback: str, *, score: float = 0.0, misconception: str | None = None, **details: Any
    ) -> Verdict:
        return cls("failed", score, feedback, misconception, details)

    @classmethod
    def unreadable(cls, message: str, **details: Any) -> Verdict:
        """An answer that could not be read. ``message`` is the engine's own text (a reader's
        message, quoting the learner's answer): it is made literal Markdown here
        (:func:`engine_text`), so nothing in it is emphasis, math or a link."""
        return cls("invalid", 0.0, engine_text(message), details=details)


# ------------------------------------------------------------------------------ literal text

_LINE_START = re.compile(
    r"^[ \t]*(?:(\d+)(?=[.)](?:\s|$))|(>|[#+=-](?=[\s#+=-]|$))?)", re.MULTILINE
)
_CODE_SPAN = re.compile(r"(?<!`)(`+)(?!`)(.+?)(?<!`)\1(?!`)", re.DOTALL)
_ENTITY = re.compile(r"&(?=#[0-9]+;|#[xX][0-9a-fA-F]+;|[A-Za-z][A-Za-z0-9]*;)")


def literal(text: str, *, line_start: bool = True) -> str:
    """Markdown that shows ``text`` exactly as written (to both faces' renderers): every
    character that could start emphasis, math (``$``), a code span, a link, an autolink or an
    HTML tag, an entity or strikethrough is backslash-escaped, and so is a block marker at the
    start of a line (``#``, ``>``, ``-``, ``1.``); indentation at a line's start is dropped (it
    would make a code block). Characters that mean nothing where they stand are left as they
    are (``range_bearing``, ``x < 3``), so the Markdown stays readable as text.
    ``line_start=False``: ``text`` continues a line, so its own start is no line's start."""
    if not text:
        return text
    out: list[str] = []
    n = len(text)
    for i, c in enumerate(text):
        before = text[i - 1] if i else " "
        after = text[i + 1] if i + 1 < n else " "
        if c in "\\`*$":
            out.append("\\" + c)
        elif c == "_":
            out.append("_" if before.isalnum() and after.isalnum() else "\\_")
        elif c == "~":
            out.append("\\~" if "~" in (before, after) else "~")
        elif c == "<":
            out.append("\\<" if after.isalpha() or after in "/!?" else "<")
        elif c == "[" or c == "]":
            out.append("\\" + c)
        elif c == "&":
            out.append("\\&" if _ENTITY.match(text, i) else "&")
        elif c == "|" and "\n" in text:
            out.append("\\|")
        else:
            out.append(c)
    escaped = "".join(out)

    def marker(m: re.Match[str]) -> str:
        if m.start() == 0 and not line_start:
            return m.group(0)
        if m.group(1):  # 1\. (the indentation dropped)
            return m.group(1) + "\\"
        return "\\" + m.group(2) if m.group(2) else ""  # \# or \-, or just no indentation

    return _LINE_START.sub(marker, escaped)


def engine_text(text: str) -> str:
    """Markdown for a message the engine wrote: literal (:func:`literal`) except for the
    ```code spans``` in it, which the engine writes by construction and which stay code."""
    out: list[str] = []
    pos = 0
    for match in _CODE_SPAN.finditer(text):
        out.append(literal(text[pos : match.start()], line_start=_starts_line(text, pos)))
        out.append(match.group(0))
        pos = match.end()
    out.append(literal(text[pos:], line_start=_starts_line(text, pos)))
    return "".join(out)


def _starts_line(text: str, pos: int) -> bool:
    return pos == 0 or text[pos - 1] == "\n"


_CODE_WORD = re.compile(r"[._()/\\:=\[\]{}<>'\"@#`]|[A-Za-z]\d|^\d")


def capitalised(text: str) -> str:
    """``text`` with its first letter capitalised, as a sentence starts, unless it starts
    with code or a file name, which keep their case: a code span, a word holding a dot, an
    underscore, a bracket or a digit after a letter (``syn.py:1``, ``range_bearing``,
    ``mahalanobis(nu0=…)``, ``nu0``), or a word the text shows as code elsewhere (``f in
    a.py is not a function; write `def f(x):```)."""
    stripped = text.lstrip()
    if not stripped or not stripped[0].islower():
        return text
    word = stripped.split(None, 1)[0].rstrip(",;:!?.")
    if _CODE_WORD.search(word) or re.search(rf"\b{re.escape(word)}\(", stripped[len(word) :]):
        return text
    spans = _CODE_SPAN.findall(stripped)
    if any(re.search(rf"\b{re.escape(word)}\b", body) for _, body in spans):
        return text
    start = len(text) - len(stripped)
    return text[:start] + stripped[0].upper() + stripped[1:]
