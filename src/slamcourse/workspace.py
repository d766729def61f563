"""The learner's workspace: where starter files of code exercises are written and edited.

The folder is :attr:`slamcourse.settings.Settings.workspace` (``$SLAMCOURSE_WORKSPACE``, else
``workspace/`` inside ``$SLAMCOURSE_HOME`` when that is set, else ``~/slamcourse-workspace``,
visible so learners find their files). A starter is written once and never overwritten: the
learner's work is theirs.

The browser's editor and the learner's own editor share one file, so a save from the editor is
conditional (:func:`save_source`): the editor sends the content hash of the text it loaded
(:func:`read_source_and_hash`), and if the file changed on disk since, nothing is written and
the file's version is returned for the learner to choose. Saves are atomic (a temporary file
in the same folder, then ``os.replace``) and serialised per file, so a reader (``slamcourse
check``, ``watch``) never sees a half-written file and two saves never interleave.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import stat
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

from slamcourse.course.model import ExerciseSpec

_LOCKS: dict[Path, threading.Lock] = {}
_LOCKS_LOCK = threading.Lock()


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


def content_hash(data: bytes) -> str:
    """The content hash of a file's bytes, as an editor sends it back: ``sha256:<hex>``."""
    return "sha256:" + hashlib.sha256(data).hexdigest()


def read_source_and_hash(path: Path) -> tuple[str, str]:
    """The file's text (undecodable bytes replaced, as grading reads it) and its content hash."""
    data = path.read_bytes()
    return data.decode("utf-8", errors="replace"), content_hash(data)


@dataclass(frozen=True)
class Saved:
    """What :func:`save_source` did. ``written``: the file now holds the source (written, or
    it held it already); otherwise the file changed since ``based_on`` and was left alone.
    ``text`` and ``hash``: the file's content now."""

    written: bool
    text: str
    hash: str


def _lock(path: Path) -> threading.Lock:
    with _LOCKS_LOCK:
        return _LOCKS.setdefault(path, threading.Lock())


def save_source(path: Path, source: str, *, based_on: str | None) -> Saved:
    """Write ``source`` to ``path`` if the file still holds the content hashed ``based_on``
    (None: unconditionally, the learner chose to overwrite). A file that changed since is left
    alone, unless it already holds ``source``. Atomic and serialised per file."""
    real = path.resolve()  # a symlinked file stays a symlink: its target is replaced
    with _lock(real):
        try:
            old = real.read_bytes()
        except FileNotFoundError:
            old = None
        data = source.encode("utf-8")
        if old == data:
            return Saved(True, source, content_hash(data))
        if old is not None and based_on is not None and based_on != content_hash(old):
            return Saved(False, old.decode("utf-8", errors="replace"), content_hash(old))
        write_atomic(real, data)
        return Saved(True, source, content_hash(data))


def write_atomic(path: Path, data: bytes) -> None:
    """Replace ``path`` by ``data`` at once: a temporary file in the same folder, flushed, then
    ``os.replace`` (a reader sees the old content or the new, never a part)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        mode: int | None = stat.S_IMODE(path.stat().st_mode)
    except FileNotFoundError:
        mode = None
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, mode if mode is not None else 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
