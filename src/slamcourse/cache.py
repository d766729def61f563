"""The learner's cache, ``<home>/cache/``: what may be thrown away at any time.

It holds parsed exercise files (``yaml/``), recorded test inputs (``inputs/``) and drawn prose
figures (``figures/``). Every entry can be rebuilt (at the cost of a PyYAML parse, a Hypothesis
run or a figure's drawing), so the cache is kept small:

- an entry's *last use* is its modification time: written when it is created and refreshed
  (:func:`touch`) each time a check reads it;
- entries unused for :data:`MAX_AGE_DAYS` days are deleted, and while the cache holds more than
  :data:`MAX_BYTES`, the least recently used entries are deleted until it fits;
- this sweep runs at most once a day (:data:`STAMP`, a file whose modification time is the last
  sweep) and only when something new is written to the cache (a parse of a changed file, a
  recording after a Hypothesis run), never on the path of a check that hits the cache.

Nothing here raises: a cache that cannot be read, written or swept is simply not used.
"""

from __future__ import annotations

import contextlib
import os
import time
from pathlib import Path

MAX_AGE_DAYS = 30
MAX_BYTES = 64 << 20
SWEEP_EVERY_SECONDS = 24 * 3600
STAMP = ".last-sweep"


def touch(path: Path) -> None:
    """Mark ``path`` as used now (its modification time)."""
    with contextlib.suppress(OSError):
        os.utime(path)


def evict_if_due(root: Path | None = None, *, now: float | None = None) -> bool:
    """Sweep the cache if the last sweep is more than a day old; True if it swept."""
    if root is None:
        from slamcourse.settings import cache_dir  # set by Engine.open from its Settings

        root = cache_dir()
        if root is None:
            return False
    now = time.time() if now is None else now
    stamp = root / STAMP
    try:
        if now - stamp.stat().st_mtime < SWEEP_EVERY_SECONDS:
            return False
    except FileNotFoundError:
        pass
    except OSError:
        return False
    try:
        root.mkdir(parents=True, exist_ok=True)
        stamp.touch()
        os.utime(stamp, (now, now))
    except OSError:
        return False
    evict(root, now=now)
    return True


def evict(
    root: Path,
    *,
    now: float | None = None,
    max_age_days: float = MAX_AGE_DAYS,
    max_bytes: int = MAX_BYTES,
) -> list[Path]:
    """Delete entries of ``root`` unused for ``max_age_days``, then the least recently used
    ones while the rest exceeds ``max_bytes``. Returns the deleted paths."""
    now = time.time() if now is None else now
    entries: list[tuple[float, int, Path]] = []
    for folder, _dirs, files in os.walk(root):
        for name in files:
            if name == STAMP and folder == str(root):
                continue
            path = Path(folder) / name
            with contextlib.suppress(OSError):
                info = path.stat()
                entries.append((info.st_mtime, info.st_size, path))
    entries.sort(key=lambda e: e[0])  # least recently used first
    total = sum(size for _used, size, _path in entries)
    oldest = now - max_age_days * 86400
    deleted = []
    for used, size, path in entries:
        if used >= oldest and total <= max_bytes:
            break
        with contextlib.suppress(OSError):
            path.unlink()
            deleted.append(path)
        total -= size
    return deleted
