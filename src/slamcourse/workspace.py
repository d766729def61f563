"""The learner's workspace: where starter files of code exercises are written and edited.

``$SLAMCOURSE_WORKSPACE`` if set; else ``workspace/`` inside ``$SLAMCOURSE_HOME`` when that is
set; else ``~/slamcourse-workspace`` (visible, so learners find their files). A file is written
once and never overwritten: the learner's work is theirs.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from slamcourse.course.model import ExerciseSpec

ENV_WORKSPACE = "SLAMCOURSE_WORKSPACE"


def workspace_dir() -> Path:
    if os.environ.get(ENV_WORKSPACE):
        return Path(os.environ[ENV_WORKSPACE]).expanduser()
    if os.environ.get("SLAMCOURSE_HOME"):
        return Path(os.environ["SLAMCOURSE_HOME"]).expanduser() / "workspace"
    return Path.home() / "slamcourse-workspace"


def exercise_file(spec: ExerciseSpec) -> Path:
    """``<workspace>/<chapter>/<exercise_slug>.py`` for a code exercise."""
    return workspace_dir() / spec.chapter / (spec.slug.replace("-", "_") + ".py")


def ensure_starter(spec: ExerciseSpec) -> tuple[Path, bool]:
    """The learner's file, copied from the starter if missing; ``(path, newly_written)``."""
    path = exercise_file(spec)
    if path.exists():
        return path, False
    path.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(spec.options.starter, path)
    return path, True


def reset_file(spec: ExerciseSpec) -> Path | None:
    """Move the learner's file aside (``.py.bak``) so the next run starts from the starter."""
    path = exercise_file(spec)
    if not path.exists():
        return None
    backup = path.with_suffix(".py.bak")
    path.replace(backup)
    return backup
