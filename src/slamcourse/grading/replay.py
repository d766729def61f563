"""Recorded inputs of a passing property-test run, replayed to make repeated checks fast.

With a fixed seed, no example database and a test that passes on every input, Hypothesis draws
exactly the same sequence of inputs every run. So after a passing run the grader records that
sequence; the next check replays it without Hypothesis (one loop of calls). If every replayed
input passes, the full run would have drawn and passed the same inputs: the verdict is the
same. On the first input that fails, the grader runs Hypothesis in full, which finds and shrinks
the failure exactly as it would have without the recording.

Only inputs are recorded (never expected values): the reference recomputes those in the grader.
Recordings live in ``<home>/cache/inputs/`` and are keyed by everything that shapes the draw: the
exercise file, its reference.py, slamcourse's and Hypothesis's versions, the seed and the count.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from pathlib import Path
from typing import Any

from slamcourse import __version__
from slamcourse.course.model import ExerciseSpec


def recording_key(spec: ExerciseSpec, seed: int, max_examples: int) -> str:
    from importlib.metadata import version

    digest = hashlib.sha256()
    for part in (spec.path.read_bytes(), spec.reference_path.read_bytes()):
        digest.update(hashlib.sha256(part).digest())
    digest.update(f"{__version__}|{version('hypothesis')}|{seed}|{max_examples}".encode())
    return f"{spec.id.replace('/', '--')}-{digest.hexdigest()[:24]}"


def _path(key: str) -> Path | None:
    from slamcourse.settings import cache_dir

    root = cache_dir()
    return None if root is None else root / "inputs" / f"{key}.json"


def load(key: str) -> list[dict[str, Any]] | None:
    """The recorded inputs, or None when there is no (readable) recording."""
    path = _path(key)
    if path is None:
        return None
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        return [_decode(item) for item in data["inputs"]]
    except (OSError, ValueError, KeyError, TypeError):
        return None


def save(key: str, inputs: list[dict[str, Any]]) -> None:
    """Record ``inputs`` atomically; a cache that cannot be written is simply skipped."""
    path = _path(key)
    if path is None:
        return
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        payload = json.dumps({"inputs": [_encode(i) for i in inputs]}, allow_nan=False)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".rec-")
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            handle.write(payload)
        os.replace(tmp, path)
    except (OSError, ValueError, TypeError):
        return


def _encode(value: Any) -> Any:
    if isinstance(value, tuple):
        return {"$tuple": [_encode(v) for v in value]}
    if isinstance(value, list):
        return [_encode(v) for v in value]
    if isinstance(value, dict):
        return {"$dict": [[_encode(k), _encode(v)] for k, v in value.items()]}
    tolist = getattr(value, "tolist", None)
    if callable(tolist) and hasattr(value, "dtype"):
        if getattr(value, "ndim", 0) == 0:
            return tolist()
        return {"$ndarray": tolist(), "$dtype": str(value.dtype)}
    if value is None or isinstance(value, bool | int | float | str):
        return value
    raise TypeError(f"cannot record a {type(value).__name__}")


def _decode(value: Any) -> Any:
    if isinstance(value, list):
        return [_decode(v) for v in value]
    if isinstance(value, dict):
        if "$tuple" in value:
            return tuple(_decode(v) for v in value["$tuple"])
        if "$dict" in value:
            return {_decode(k): _decode(v) for k, v in value["$dict"]}
        if "$ndarray" in value:
            import numpy as np

            return np.asarray(value["$ndarray"], dtype=value["$dtype"])
        raise ValueError("untagged object in a recording")
    return value
