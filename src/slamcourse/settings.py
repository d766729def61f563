"""Settings: the one object that says which course, whose progress, and how learner code runs.

Faces (terminal, browser, batch grader) build a :class:`Settings` once (``Settings.from_env``
reads the ``SLAMCOURSE_*`` environment variables, the only place that does) and hand it to
:meth:`slamcourse.engine.Engine.open`. Nothing below the engine reads the environment for these
choices.

| variable | setting | default |
|---|---|---|
| ``SLAMCOURSE_COURSE`` | ``course``: the course folder | the bundled course |
| ``SLAMCOURSE_HOME`` | ``home``: progress database and caches | ``$XDG_DATA_HOME/slamcourse`` |
| ``SLAMCOURSE_WORKSPACE`` | ``workspace``: learners' code files | ``<home>/workspace`` when
  ``SLAMCOURSE_HOME`` is set, else ``~/slamcourse-workspace`` |
| ``SLAMCOURSE_GRADING_SECRET`` | batch grading: seeds hidden checks | empty |

This module is imported by every command, so it imports only the standard library.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path

ENV_COURSE = "SLAMCOURSE_COURSE"
ENV_HOME = "SLAMCOURSE_HOME"
ENV_WORKSPACE = "SLAMCOURSE_WORKSPACE"
ENV_GRADING_SECRET = "SLAMCOURSE_GRADING_SECRET"
ENV_ALLOW_NO_ISOLATION = "SLAMCOURSE_ALLOW_NO_ISOLATION"
ENVIRONMENT = (
    (ENV_HOME, "progress database and caches (default ~/.local/share/slamcourse)"),
    (ENV_WORKSPACE, "where your code exercise files live (default ~/slamcourse-workspace)"),
    (ENV_COURSE, "use another course folder instead of the bundled one"),
    ("SLAMCOURSE_SANDBOX", "auto | namespaces | rlimits: how learner code is isolated"),
    (ENV_GRADING_SECRET, "batch grading: the instructor's secret that seeds hidden checks"),
    (
        "SLAMCOURSE_SERVE_TOKEN",
        "serve: require this token instead of a fresh one, and do not print it (set by a hub's "
        "launcher)",
    ),
    ("NO_COLOR", "plain output"),
)

_LINUX: bool = sys.platform.startswith("linux")


def default_home(environ: Mapping[str, str] = os.environ) -> Path:
    """``$SLAMCOURSE_HOME`` if set (and not empty), else the platform's per-user data folder
    (``$XDG_DATA_HOME/slamcourse`` or ``~/.local/share/slamcourse`` on Linux)."""
    env = environ.get(ENV_HOME)
    if env:
        return Path(env).expanduser()
    if _LINUX:
        # platformdirs' own rule on Linux (XDG base directories), without its 15 ms import on
        # every command; other platforms ask platformdirs.
        xdg = environ.get("XDG_DATA_HOME", "").strip()
        base = Path(xdg) if xdg and Path(xdg).is_absolute() else Path.home() / ".local" / "share"
        return base / "slamcourse"
    import platformdirs

    return Path(platformdirs.user_data_dir("slamcourse", appauthor=False))


def default_workspace(environ: Mapping[str, str] = os.environ) -> Path:
    if environ.get(ENV_WORKSPACE):
        return Path(environ[ENV_WORKSPACE]).expanduser()
    if environ.get(ENV_HOME):
        return Path(environ[ENV_HOME]).expanduser() / "workspace"
    return Path.home() / "slamcourse-workspace"


@dataclass(frozen=True)
class Settings:
    """Which course, where the learner's progress and files live, and the isolation policy.

    ``course`` None means the bundled course. ``record`` False grades without writing progress
    (``check --no-record``). ``require_isolation`` refuses to run learner code without
    namespace isolation (CI grading). ``hidden_seed`` (grading mode, set by the batch grader
    from an instructor's secret) makes every code check also run inputs drawn with that seed.
    """

    home: Path
    workspace: Path
    course: Path | None = None
    require_isolation: bool = False
    record: bool = True
    hidden_seed: int | None = None  # grading mode: extra property inputs the learner never met

    @classmethod
    def from_env(
        cls,
        environ: Mapping[str, str] = os.environ,
        *,
        course: str | Path | None = None,
        home: str | Path | None = None,
        workspace: str | Path | None = None,
        require_isolation: bool = False,
        record: bool = True,
    ) -> Settings:
        """Settings from explicit values, falling back to the environment, then defaults."""
        chosen_course = course or environ.get(ENV_COURSE) or None
        return cls(
            home=Path(home).expanduser() if home else default_home(environ),
            workspace=Path(workspace).expanduser() if workspace else default_workspace(environ),
            course=Path(chosen_course).expanduser() if chosen_course else None,
            require_isolation=require_isolation,
            record=record,
        )

    def but(self, **changes: object) -> Settings:
        """A copy with some settings changed."""
        return replace(self, **changes)  # type: ignore[arg-type]

    @property
    def cache(self) -> Path:
        """``<home>/cache``: parsed YAML and recorded test inputs, keyed by content."""
        return self.home / "cache"


def grading_secret(environ: Mapping[str, str] = os.environ) -> str:
    """The batch grader's secret (``$SLAMCOURSE_GRADING_SECRET``; empty when unset)."""
    return environ.get(ENV_GRADING_SECRET, "")


def isolation_waived(environ: Mapping[str, str] = os.environ) -> bool:
    """``SLAMCOURSE_ALLOW_NO_ISOLATION=1``: an entry point without a command line (the
    PrairieLearn grader) may grade without namespaces, its container being the sandbox."""
    return environ.get(ENV_ALLOW_NO_ISOLATION) == "1"


_active_cache: Path | None = None


def activate_cache(path: Path | None) -> None:
    """Say where content-addressed caches live for this process (set by ``Engine.open``)."""
    global _active_cache
    _active_cache = path


def cache_dir() -> Path | None:
    """The cache folder set by the engine, or None (no caching) before an engine opened."""
    return _active_cache
