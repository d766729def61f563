"""Recorded inputs of a passing property-test run, replayed to make repeated checks fast.

With a fixed seed, no example database and a test that passes on every input, Hypothesis draws
exactly the same sequence of inputs every run. So after a passing run the grader records that
sequence; the next check replays it without Hypothesis (one loop of calls). If every replayed
input passes, the full run would have drawn and passed the same inputs: the verdict is the
same. On the first input that fails, the grader runs Hypothesis in full, which finds and shrinks
the failure exactly as it would have without the recording.

Only inputs are recorded (never expected values): the reference recomputes those in the grader.
A check looks for a recording in this order:

1. the course's own, **shipped** with it: ``exercises/<chapter>/recordings/<slug>.json``, written
   by ``slamcourse validate --record`` from a run of the reference against itself, and keyed by
   :func:`draw_key` (the parts of the exercise that shape the draw, reference.py, the grader's
   strategies.py and properties.py, and Hypothesis's major version). A stale one (its key differs)
   is ignored, and ``validate`` reports it. So even the first check on a new machine replays;
2. the learner's cache, ``<home>/cache/inputs/``, written after a passing Hypothesis run and keyed
   by the whole exercise file, reference.py, the grader's sources and the exact versions;
3. neither: Hypothesis runs (and a pass fills the cache).

Every recording holds inputs drawn by the exercise's current strategy, from its declared domain,
so a replayed input on which a learner's function fails is a real failure even when a fresh run
(another Hypothesis version) would not meet it: the verdict then shows that input.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import tempfile
from functools import lru_cache
from pathlib import Path
from typing import Any

from slamcourse import __version__
from slamcourse.course.model import ExerciseSpec

SHIPPED_FORMAT = 1


@lru_cache(maxsize=1)
def _grader_digest() -> str:
    """The grader's own code that decides how inputs are drawn (the strategies, and the draw
    in :mod:`~slamcourse.grading.testset`)."""
    import inspect

    from slamcourse.grading import strategies, testset

    digest = hashlib.sha256()
    digest.update(Path(str(strategies.__file__)).read_bytes())
    digest.update(inspect.getsource(testset.draw).encode())  # the draw only: grading may change
    return digest.hexdigest()


@lru_cache(maxsize=1)
def hypothesis_version() -> str:
    """Hypothesis's version without importing it or importlib.metadata (together ~25 ms of a
    check): the name of its ``.dist-info`` folder, first on ``sys.path`` as imports search."""
    for entry in sys.path:
        try:
            names = os.listdir(entry or ".")
        except OSError:
            continue
        for name in names:
            if name.startswith("hypothesis-") and name.endswith(".dist-info"):
                return name[len("hypothesis-") : -len(".dist-info")]
    from importlib.metadata import version  # e.g. an egg or a source checkout

    return version("hypothesis")


def recording_key(spec: ExerciseSpec, seed: int, max_examples: int) -> str:
    """The name of the learner-cache recording (exact versions; any edit of the files)."""
    digest = hashlib.sha256()
    for part in (spec.path.read_bytes(), spec.reference_path.read_bytes()):
        digest.update(hashlib.sha256(part).digest())
    digest.update(
        f"{__version__}|{hypothesis_version()}|{seed}|{max_examples}|{_grader_digest()}".encode()
    )
    return f"{spec.id.replace('/', '--')}-{digest.hexdigest()[:24]}"


def draw_key(spec: ExerciseSpec, seed: int) -> str:
    """The key of a shipped recording: a hash of exactly what determines the inputs drawn.

    The exercise's id, signature, arguments, strategy, assume, examples and max_examples (not its
    prose), its reference.py (which holds the reference and any strategy function), the grader's
    strategies.py and properties.py, the seed, and Hypothesis's major version.
    """
    opts = spec.options
    described = {
        "id": spec.id,
        "signature": list(opts.signature),
        "arguments": [[a.name, a.dist, [_encode(v) for v in a.args]] for a in opts.arguments],
        "strategy": opts.strategy,
        "assume": list(opts.assume),
        "examples": [_encode(e) for e in opts.examples],
        "max_examples": opts.max_examples,
        "seed": seed,
        "reference": hashlib.sha256(spec.reference_path.read_bytes()).hexdigest(),
        "grader": _grader_digest(),
        "hypothesis": hypothesis_version().split(".")[0],
    }
    text = json.dumps(described, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return hashlib.sha256(text.encode()).hexdigest()


def shipped_path(spec: ExerciseSpec) -> Path:
    """``exercises/<chapter>/recordings/<slug>.json``."""
    return spec.path.parent / "recordings" / f"{spec.path.stem}.json"


def shipped_state(spec: ExerciseSpec, seed: int) -> str:
    """``"ok"``, ``"missing"``, ``"stale"`` (another key) or ``"broken"`` (unreadable)."""
    try:
        data = json.loads(shipped_path(spec).read_text(encoding="utf-8"))
    except FileNotFoundError:
        return "missing"
    except (OSError, ValueError):
        return "broken"
    if not isinstance(data, dict) or not isinstance(data.get("inputs"), list):
        return "broken"
    return "ok" if data.get("key") == draw_key(spec, seed) else "stale"


def load_shipped(spec: ExerciseSpec, seed: int) -> list[dict[str, Any]] | None:
    """The course's recorded inputs for this exercise, or None (missing, stale or broken)."""
    try:
        data = json.loads(shipped_path(spec).read_text(encoding="utf-8"))
        if data["key"] != draw_key(spec, seed):
            return None
        return [
            {str(name): _decode(value) for name, value in item.items()} for item in data["inputs"]
        ]
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def write_shipped(spec: ExerciseSpec, seed: int, inputs: list[dict[str, Any]]) -> Path:
    """Write the course's recording (one input per line, so a diff shows what changed)."""
    path = shipped_path(spec)
    lines = ",\n".join(  # keyword arguments as a plain object; their values tagged
        "    " + json.dumps({k: _encode(v) for k, v in i.items()}, allow_nan=False) for i in inputs
    )
    head = {
        "format": SHIPPED_FORMAT,
        "exercise": spec.id,
        "key": draw_key(spec, seed),
        "hypothesis": hypothesis_version(),
        "count": len(inputs),
    }
    text = json.dumps(head, indent=2)[:-2] + ',\n  "inputs": [\n' + lines + "\n  ]\n}\n"
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".rec-")
    with os.fdopen(fd, "w", encoding="utf-8") as handle:
        handle.write(text)
    os.chmod(tmp, 0o644)  # a course file, committed and shipped like the YAML beside it
    os.replace(tmp, path)
    return path


def _path(key: str) -> Path | None:
    from slamcourse.settings import cache_dir

    root = cache_dir()
    return None if root is None else root / "inputs" / f"{key}.json"


def load(key: str) -> list[dict[str, Any]] | None:
    """The recorded inputs, or None when there is no (readable) recording."""
    from slamcourse import cache

    path = _path(key)
    if path is None:
        return None
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        inputs = [_decode(item) for item in data["inputs"]]
    except (OSError, ValueError, KeyError, TypeError):
        return None
    cache.touch(path)
    return inputs


def save(key: str, inputs: list[dict[str, Any]]) -> None:
    """Record ``inputs`` atomically; a cache that cannot be written is simply skipped."""
    from slamcourse import cache

    cache.evict_if_due()
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


def encode(value: Any) -> Any:
    """Plain JSON data for recorded inputs: tuples, dicts and arrays tagged as on the wire."""
    return _encode(value)


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
