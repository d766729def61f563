"""Eviction of the learner's cache: unused entries go after 30 days, the least recently used
go first when it is too big, and the sweep runs at most once a day."""

from __future__ import annotations

import os
import time
from pathlib import Path

from slamcourse import cache

DAY = 86400.0


def entry(root: Path, name: str, size: int, used_days_ago: float, now: float) -> Path:
    path = root / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"x" * size)
    used = now - used_days_ago * DAY
    os.utime(path, (used, used))
    return path


def test_entries_unused_for_30_days_are_deleted(tmp_path: Path) -> None:
    now = time.time()
    old = entry(tmp_path, "inputs/old.json", 10, 31, now)
    recent = entry(tmp_path, "yaml/recent.json", 10, 29, now)
    assert cache.evict(tmp_path, now=now) == [old]
    assert recent.exists() and not old.exists()


def test_least_recently_used_go_first_when_over_the_cap(tmp_path: Path) -> None:
    now = time.time()
    a = entry(tmp_path, "inputs/a.json", 400, 3, now)
    b = entry(tmp_path, "yaml/b.json", 400, 2, now)
    c = entry(tmp_path, "inputs/c.json", 400, 1, now)
    assert cache.evict(tmp_path, now=now, max_bytes=900) == [a]
    assert cache.evict(tmp_path, now=now, max_bytes=100) == [b, c]


def test_touch_marks_an_entry_used(tmp_path: Path) -> None:
    now = time.time()
    path = entry(tmp_path, "inputs/a.json", 10, 40, now)
    cache.touch(path)
    assert cache.evict(tmp_path, now=now) == []
    cache.touch(tmp_path / "missing.json")  # never raises


def test_the_sweep_runs_at_most_once_a_day(tmp_path: Path) -> None:
    now = time.time()
    entry(tmp_path, "inputs/old.json", 10, 40, now)
    assert cache.evict_if_due(tmp_path, now=now) is True
    assert not (tmp_path / "inputs/old.json").exists()
    entry(tmp_path, "inputs/old.json", 10, 40, now)
    assert cache.evict_if_due(tmp_path, now=now + 3600) is False  # swept an hour ago
    assert (tmp_path / "inputs/old.json").exists()
    assert cache.evict_if_due(tmp_path, now=now + 1.1 * DAY) is True
    assert not (tmp_path / "inputs/old.json").exists()
    assert (tmp_path / cache.STAMP).exists()  # the stamp itself is never evicted


def test_a_cache_write_sweeps_and_a_hit_touches(private_home: Path) -> None:
    from slamcourse.grading import replay

    now = time.time()
    root = private_home / "cache"
    stale = entry(root, "inputs/stale.json", 10, 45, now)
    replay.save("some-key", [{"x": 1.5}])  # a write: due, so it sweeps first
    assert not stale.exists()
    saved = root / "inputs" / "some-key.json"
    os.utime(saved, (now - 40 * DAY, now - 40 * DAY))
    assert replay.load("some-key") == [{"x": 1.5}]  # a hit marks it used
    assert cache.evict(root, now=now) == []
