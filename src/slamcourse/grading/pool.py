"""A pre-started worker for the next check, for engines that live longer than one check.

Each submission still gets a fresh interpreter (a worker is never reused); the pool only starts
the next one early, so its numpy import is done by the time the learner checks again.
"""

from __future__ import annotations

from slamcourse.sandbox import Limits, Worker


class WorkerPool:
    """Hands out fresh sandboxed workers, keeping one spare already starting."""

    def __init__(self, *, require_isolation: bool = False, limits: Limits | None = None) -> None:
        self.require_isolation = require_isolation
        self.limits = limits
        self._spare: Worker | None = None

    def _spawn(self) -> Worker:
        return Worker.spawn(limits=self.limits, require_isolation=self.require_isolation)

    def take(self) -> Worker:
        """A fresh worker (the spare if it is alive), and start the next spare."""
        worker = self._spare if self._spare is not None and self._spare.alive else None
        if worker is None:
            worker = self._spawn()
        self._spare = self._spawn()
        return worker

    def warm(self) -> None:
        """Start a spare now (e.g. when a code exercise is shown, before the learner checks)."""
        if self._spare is None or not self._spare.alive:
            self._spare = self._spawn()

    def close(self) -> None:
        if self._spare is not None:
            self._spare.close()
            self._spare = None
