"""Where the course is: ``--course PATH``, ``$SLAMCOURSE_COURSE``, or the bundled course."""

from __future__ import annotations

import os
from pathlib import Path

from slamcourse.errors import GraderError, UsageError

ENV_COURSE = "SLAMCOURSE_COURSE"


def bundled_course_root() -> Path:
    """The course shipped with slamcourse: inside the installed package, or the source checkout."""
    package = Path(__file__).resolve().parent.parent
    installed = package / "_course"
    if (installed / "chapters").is_dir():
        return installed
    checkout = package.parent.parent  # src/slamcourse -> repository root
    if (checkout / "chapters").is_dir() and (checkout / "exercises").is_dir():
        return checkout
    raise GraderError(
        f"the bundled course is missing (looked in {installed} and {checkout}); "
        "reinstall slamcourse (pip install --force-reinstall slamcourse)"
    )


def course_root(explicit: str | Path | None = None) -> Path:
    """Resolve the course folder to use and check that it looks like a course."""
    chosen = explicit or os.environ.get(ENV_COURSE)
    if not chosen:
        return bundled_course_root()
    source = "--course" if explicit else f"${ENV_COURSE}"
    try:
        root = Path(chosen).expanduser().resolve()
    except (OSError, RuntimeError) as exc:  # a symlink loop (RuntimeError before Python 3.13)
        raise UsageError(f"{source} {chosen}: cannot be resolved ({exc})") from None
    if not root.is_dir():
        raise UsageError(f"{source} {root}: no such folder")
    if not (root / "chapters").is_dir() or not (root / "exercises").is_dir():
        raise UsageError(
            f"{source} {root} is not a course: it needs a chapters/ and an exercises/ folder "
            "(see docs/authoring.md)"
        )
    return root
