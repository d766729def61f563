"""Waiting for a file to be saved: inotify on Linux, polling elsewhere (or when asked)."""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import select
import struct
import time
from pathlib import Path

_IN_CLOSE_WRITE, _IN_MOVED_TO, _IN_CREATE = 0x8, 0x80, 0x100
_EVENT = struct.Struct("iIII")


def _signature(path: Path) -> tuple[int, int] | None:
    try:
        st = path.stat()
    except OSError:
        return None
    return st.st_mtime_ns, st.st_size


def signature(path: Path) -> tuple[int, int] | None:
    """What identifies one saved version of ``path`` (modification time and size)."""
    return _signature(path)


def wait_for_change(
    path: Path,
    *,
    poll: bool = False,
    interval: float = 0.5,
    timeout: float | None = None,
    since: tuple[int, int] | None = None,
) -> str:
    """Block until ``path`` is written (or replaced, as editors do); returns the mechanism used
    (``inotify`` or ``polling``). With ``timeout``, returns ``timeout`` when nothing changed.

    ``since`` is the file's :func:`signature` when the caller last read it: a save that landed
    in between (e.g. while the caller was grading) returns at once, as ``changed``.
    """
    if not poll:
        fd = _inotify_watch(path.parent)
        if fd is not None:
            try:
                if since is not None and _signature(path) != since:
                    return "changed"
                return _wait_inotify(fd, path, timeout)
            finally:
                os.close(fd)
    if since is not None and _signature(path) != since:
        return "changed"
    return _wait_polling(path, interval, timeout, since)


def _wait_polling(
    path: Path, interval: float, timeout: float | None, since: tuple[int, int] | None = None
) -> str:
    before = since if since is not None else _signature(path)
    deadline = None if timeout is None else time.monotonic() + timeout
    while deadline is None or time.monotonic() < deadline:
        time.sleep(interval)
        if _signature(path) != before:
            return "polling"
    return "timeout"


def _inotify_watch(directory: Path) -> int | None:
    """An inotify descriptor watching ``directory``, or None where file events are unavailable."""
    name = ctypes.util.find_library("c")
    if os.name != "posix" or not name:
        return None
    try:
        libc = ctypes.CDLL(name, use_errno=True)
        fd = int(libc.inotify_init1(os.O_CLOEXEC | os.O_NONBLOCK))
    except (OSError, AttributeError):
        return None
    if fd < 0:
        return None
    mask = _IN_CLOSE_WRITE | _IN_MOVED_TO | _IN_CREATE
    if libc.inotify_add_watch(fd, os.fsencode(directory), mask) < 0:
        os.close(fd)
        return None
    return fd


def _wait_inotify(fd: int, path: Path, timeout: float | None) -> str:
    target = os.fsencode(path.name)
    deadline = None if timeout is None else time.monotonic() + timeout
    while True:
        left = None if deadline is None else max(0.0, deadline - time.monotonic())
        ready, _, _ = select.select([fd], [], [], left)
        if not ready:
            return "timeout"
        data = os.read(fd, 64 * 1024)
        offset = 0
        while offset + _EVENT.size <= len(data):
            _wd, _mask, _cookie, length = _EVENT.unpack_from(data, offset)
            name = data[offset + _EVENT.size : offset + _EVENT.size + length].rstrip(b"\0")
            offset += _EVENT.size + length
            if name == target:
                return "inotify"
