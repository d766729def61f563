"""Which exercise gets which picture, drawn from that exercise's own numbers.

A picture is chosen by exercise id (``BY_ID``) or, failing that, by a tag together with the
parameter names the picture needs (``BY_TAG``). Each entry maps the variant's parameters
(a dict, the learner's own numbers) to an SVG string. A picture never gives an answer away:
one that would is shown only once the exercise is solved or given up (``after_solving``), and
others draw their derived figures as "?" until then. Code exercises have no variant
parameters; their entries draw the lesson's own numbers (the exercise's first documented
example). See docs/authoring.md, "Pictures".
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import importlib
import math
import os
import pkgutil
import tempfile
import threading
from collections.abc import Iterable
from pathlib import Path

from slamcourse import cache
from slamcourse.plots.drift import drift_trajectories
from slamcourse.plots.geometry import observation_geometry
from slamcourse.plots.occupancy import occupancy_grid, occupancy_ray
from slamcourse.plots.picture import Figure, Params, Picture, answer, given
from slamcourse.plots.sparsity import MAX_N, information_sparsity


def _logit(p: float) -> float:
    return math.log(p / (1.0 - p))


def _chain(params: Params) -> str:
    total = int(params["num_poses"])
    n = min(total, 12)
    edges = [(i, i + 1) for i in range(n - 1)]
    return information_sparsity(n, edges, of_total=total)


def _star(params: Params) -> str:
    leaves = min(int(params["leaves"]), MAX_N - 1)
    # the hub (variable 0) is eliminated first: every pair of leaves becomes linked
    return information_sparsity(leaves + 1, [(0, k) for k in range(1, leaves + 1)], order=[0])


def _geometry(params: Params, show_results: bool) -> str:
    return observation_geometry(
        float(params["xr"]),
        float(params["yr"]),
        float(params["thr"]),
        float(params["xj"]),
        float(params["yj"]),
        show_results=show_results,
    )


_BEAMS = [(7, 1), (7, 3), (6, 5), (3, 5), (7, 2)]


def _grid(l_occ: float, l_free: float) -> str:
    return occupancy_grid(8, 6, (1, 3), _BEAMS, l_occ, l_free)


_given = given
_answer = answer


BY_ID: dict[str, Picture] = {
    "drift/systematic-drift": _answer(
        lambda p: drift_trajectories(int(p["steps"]), bias=p["bias"])
    ),
    "drift/random-drift": _answer(lambda p: drift_trajectories(int(p["steps"]), sigma=p["sigma"])),
    # code exercises: the lesson's numbers (their first example); code is not graded by a number
    "drift/heading-drift": _given(
        lambda p: drift_trajectories(100, step_length=0.5, heading_rate=0.01)
    ),
    "drift/random-walk": _given(lambda p: drift_trajectories(400, sigma=0.05)),
    "graph/chain-sparsity": _given(_chain),  # 12 poses drawn; the answer is for thousands
    "graph/omega-nonzeros": _answer(_chain),
    "factor-graphs/star-fill-in": _answer(_star),
    "factor-graphs/fill-in": _given(
        lambda p: information_sparsity(5, [(0, 1), (1, 2), (2, 3), (3, 4)], order=[2, 0, 1, 3, 4])
    ),
    "observation/observation-model": _given(
        lambda p: observation_geometry(2, 3, math.pi / 4, 5, 7)
    ),
    # an inverse sensor model that trusts "occupied" with p and "free" with the same p
    "occupancy/log-odds-value": _answer(lambda p: _grid(_logit(p["p"]), -_logit(p["p"]))),
    "occupancy/two-readings": _answer(lambda p: _grid(_logit(p["p1"]), _logit(p["p2"]))),
    "occupancy/log-odds-update": _given(lambda p: _grid(_logit(0.9), _logit(0.3))),
    "occupancy/ray-update": _given(
        lambda p: occupancy_ray([1.0, -0.5, 0.2, 2.0, 0.0], 3, 0.85, -0.4)
    ),
}

FIGURES: dict[str, Figure] = {}
"""Figures of the chapters' prose, by ``<chapter-id>/<name>`` (a ```{figure} ID``` block)."""


def _collect_chapter_modules() -> None:
    """Merge every ``slamcourse.plots.ch_*`` module's ``PICTURES`` (exercise id → Picture) and
    ``FIGURES`` (figure id → drawing) into the registry; an id defined twice is a bug."""
    import slamcourse.plots as package

    for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda m: m.name):
        if not info.name.startswith("ch_"):
            continue
        module = importlib.import_module(f"slamcourse.plots.{info.name}")
        for source, target in (
            (getattr(module, "PICTURES", {}), BY_ID),
            (getattr(module, "FIGURES", {}), FIGURES),
        ):
            for key, value in source.items():
                if key in target:
                    raise RuntimeError(f"plots/{info.name}.py: {key!r} is registered twice")
                target[key] = value


_collect_chapter_modules()


BY_TAG: list[tuple[str, frozenset[str], Picture]] = [
    # range and bearing are what these exercises ask: "?" until solved
    ("observation-model", frozenset({"xr", "yr", "thr", "xj", "yj"}), Picture(_geometry)),
]


def _picture(exercise_id: str, tags: Iterable[str], params: Params) -> Picture | None:
    picture = BY_ID.get(exercise_id)
    if picture is None:
        tagset = set(tags)
        for tag, needs, candidate in BY_TAG:
            if tag in tagset and needs <= params.keys():
                return candidate
    return picture


def plot_for(exercise_id: str, tags: Iterable[str], params: Params, *, solved: bool) -> str | None:
    """The SVG picture of this exercise's variant, or None when it has none (yet).

    ``solved``: the exercise is solved or given up, so the picture may show its answer."""
    picture = _picture(exercise_id, tags, params)
    if picture is None or (picture.after_solving and not solved):
        return None
    return picture.draw(params, solved)


def has_plot(exercise_id: str, tags: Iterable[str], params: Params) -> bool:
    """Whether the exercise has a picture (perhaps only once solved)."""
    return _picture(exercise_id, tags, params) is not None


_DRAWN: dict[str, str] = {}
_DRAWN_LOCK = threading.Lock()


@functools.cache
def _sources_digest() -> str:
    """A digest of everything a figure is drawn from: the drawing and reference mathematics
    (``plots/``, ``slam/``) and the bundled course's reference code and data files. Computed once
    per process (about 2 MB of files, a few milliseconds)."""
    from slamcourse.course.locate import bundled_course_root

    package = Path(__file__).resolve().parent.parent
    files = sorted((package / "plots").glob("*.py")) + sorted((package / "slam").glob("*.py"))
    exercises = bundled_course_root() / "exercises"
    files += sorted(exercises.glob("*/reference.py")) + sorted(exercises.glob("*/data/*"))
    digest = hashlib.sha256()
    for path in files:
        with contextlib.suppress(OSError):
            digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def _cached_path(figure_id: str) -> Path | None:
    from slamcourse.settings import cache_dir

    root = cache_dir()
    if root is None:
        return None
    key = hashlib.sha256(f"{_sources_digest()}\0{figure_id}".encode()).hexdigest()[:24]
    return root / "figures" / f"{key}.svg"


def _read_cached(path: Path | None) -> str | None:
    if path is None:
        return None
    try:
        svg = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    cache.touch(path)
    return svg if svg.startswith("<svg") and svg.rstrip().endswith("</svg>") else None


def _write_cached(path: Path | None, svg: str) -> None:
    if path is None:
        return
    cache.evict_if_due()
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".fig-")
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            handle.write(svg)
        os.replace(tmp, path)
    except OSError:
        return


def figure_svg(figure_id: str) -> str | None:
    """The SVG of a prose figure, or None when no chapter module defines ``figure_id``.

    A figure draws the chapter's own fixed numbers, so it is drawn once: kept in this process
    (the browser serves a chapter many times) and in the learner's cache (``figures/``), keyed
    by the figure id and a digest of the code and data it is drawn from, so a figure that runs
    an optimiser (sphere2500, INTEL with false loop closures) costs its seconds once per
    installation, not once per server start, and an edited drawing is never served stale."""
    with _DRAWN_LOCK:
        svg = _DRAWN.get(figure_id)
    if svg is not None:
        return svg
    draw = FIGURES.get(figure_id)
    if draw is None:
        return None
    path = _cached_path(figure_id)
    svg = _read_cached(path)
    if svg is None:
        svg = draw()
        _write_cached(path, svg)
    with _DRAWN_LOCK:
        _DRAWN[figure_id] = svg
    return svg
