"""Verdicts: what every checker returns. A learner's mistake is data, never an exception."""

from __future__ import annotations

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
    def unreadable(cls, feedback: str, **details: Any) -> Verdict:
        return cls("invalid", 0.0, feedback, details=details)
