"""The one exception family of slamcourse.

Library code raises these and never prints or exits; only :func:`slamcourse.cli.main` catches
them, prints ``Error: …`` to stderr and exits with the error's ``exit_code``.

A learner's mistake is never an exception: checkers turn it into a
:class:`~slamcourse.verdict.Verdict`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

# Process exit codes (documented in docs/grading.md).
EXIT_PASSED = 0
EXIT_NOT_PASSED = 1  # failed, invalid or timeout
EXIT_USAGE = 2
EXIT_GRADER = 3
EXIT_COURSE = 4
EXIT_PROGRESS = 5


@dataclass(frozen=True)
class Problem:
    """One thing wrong with a course file: where it is, what is wrong, and how to fix it."""

    path: str
    line: int | None
    message: str

    def __str__(self) -> str:
        where = f"{self.path}:{self.line}" if self.line else self.path
        return f"{where}: {self.message}"


def relpath(path: Path, root: Path) -> str:
    """``path`` relative to the course root: how problems name course files."""
    try:
        return str(path.relative_to(root.parent if root.name == "_course" else root))
    except ValueError:
        return str(path)


class SlamcourseError(Exception):
    """Root of every error slamcourse raises on purpose. Catch this, not ``Exception``."""

    exit_code = EXIT_GRADER


class UsageError(SlamcourseError):
    """The command line asks for something that cannot be done (unknown exercise id, bad option).

    Fix: read the message; ``slamcourse list`` shows the valid exercise ids.
    """

    exit_code = EXIT_USAGE


class CourseError(SlamcourseError):
    """Course content is broken: a chapter or exercise file the loader or validator rejected.

    Carries every :class:`Problem` found, each as ``path:line: message``. Fix the files named.
    """

    exit_code = EXIT_COURSE

    def __init__(self, problems: list[Problem] | Problem | str):
        if isinstance(problems, str):
            problems = [Problem("<course>", None, problems)]
        elif isinstance(problems, Problem):
            problems = [problems]
        self.problems: list[Problem] = list(problems)
        super().__init__("\n".join(str(p) for p in self.problems))


class AnswerFormatError(SlamcourseError):
    """A learner's answer could not be read. Checkers turn this into an ``invalid`` verdict.

    The message says what form was expected, e.g. ``expected a number such as 0.25, 7/5 or pi/4``.
    """

    exit_code = EXIT_NOT_PASSED


class ProgressError(SlamcourseError):
    """The progress database cannot be used: corrupt, written by a newer slamcourse, or unwritable.

    It is never replaced silently; the message names the file and what to do with it.
    """

    exit_code = EXIT_PROGRESS


class GraderError(SlamcourseError):
    """The grader itself failed (not the learner): a bug or a broken installation.

    Said as such to the learner; no attempt is counted.
    """

    exit_code = EXIT_GRADER


class SandboxError(GraderError):
    """Learner code cannot be run safely here (e.g. ``--require-isolation`` without namespaces)."""
