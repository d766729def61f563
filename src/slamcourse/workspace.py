"""The learner's workspace: where starter files of code exercises are written and edited.

The folder is :attr:`slamcourse.settings.Settings.workspace` (``$SLAMCOURSE_WORKSPACE``, else
``workspace/`` inside ``$SLAMCOURSE_HOME`` when that is set, else ``~/slamcourse-workspace``,
visible so learners find their files). A file is written once and never overwritten: the
learner's work is theirs.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from slamcourse.course.model import ExerciseSpec


def exercise_file(spec: ExerciseSpec, workspace: Path) -> Path:
    """``<workspace>/<chapter>/<exercise_slug>.py`` for a code exercise."""
    return workspace / spec.chapter / (spec.slug.replace("-", "_") + ".py")


def ensure_starter(spec: ExerciseSpec, workspace: Path) -> tuple[Path, bool]:
    """The learner's file, copied from the starter if missing; ``(path, newly_written)``."""
    path = exercise_file(spec, workspace)
    if path.exists():
        return path, False
    path.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(spec.options.starter, path)
    return path, True


def reset_file(spec: ExerciseSpec, workspace: Path) -> Path | None:
    """Move the learner's file aside (``.py.bak``) so the next run starts from the starter."""
    path = exercise_file(spec, workspace)
    if not path.exists():
        return None
    backup = path.with_suffix(".py.bak")
    path.replace(backup)
    return backup
