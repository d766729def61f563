"""Which exercise gets which picture, drawn from that exercise's own numbers.

A picture is chosen by exercise id (``BY_ID``) or, failing that, by a tag together with the
parameter names the picture needs (``BY_TAG``). Each entry maps the variant's parameters
(a dict, the learner's own numbers) to an SVG string. Code exercises have no variant
parameters; their entries draw the lesson's own numbers (the exercise's first documented
example). See docs/authoring.md, "Pictures".
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

from slamcourse.plots.drift import drift_trajectories
from slamcourse.plots.geometry import observation_geometry
from slamcourse.plots.occupancy import occupancy_grid, occupancy_ray
from slamcourse.plots.sparsity import MAX_N, information_sparsity

Params = Mapping[str, Any]
Plot = Callable[[Params], str]


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


def _geometry(params: Params) -> str:
    return observation_geometry(
        float(params["xr"]),
        float(params["yr"]),
        float(params["thr"]),
        float(params["xj"]),
        float(params["yj"]),
    )


_BEAMS = [(7, 1), (7, 3), (6, 5), (3, 5), (7, 2)]


def _grid(l_occ: float, l_free: float) -> str:
    return occupancy_grid(8, 6, (1, 3), _BEAMS, l_occ, l_free)


BY_ID: dict[str, Plot] = {
    "drift/systematic-drift": lambda p: drift_trajectories(int(p["steps"]), bias=p["bias"]),
    "drift/random-drift": lambda p: drift_trajectories(int(p["steps"]), sigma=p["sigma"]),
    # code exercises: the lesson's numbers (their first example)
    "drift/heading-drift": lambda p: drift_trajectories(100, step_length=0.5, heading_rate=0.01),
    "drift/random-walk": lambda p: drift_trajectories(400, sigma=0.05),
    "graph/chain-sparsity": _chain,
    "graph/omega-nonzeros": _chain,
    "factor-graphs/star-fill-in": _star,
    "factor-graphs/fill-in": lambda p: information_sparsity(
        5, [(0, 1), (1, 2), (2, 3), (3, 4)], order=[2, 0, 1, 3, 4]
    ),
    "observation/observation-model": lambda p: observation_geometry(2, 3, math.pi / 4, 5, 7),
    # an inverse sensor model that trusts "occupied" with p and "free" with the same p
    "occupancy/log-odds-value": lambda p: _grid(_logit(p["p"]), -_logit(p["p"])),
    "occupancy/two-readings": lambda p: _grid(_logit(p["p1"]), _logit(p["p2"])),
    "occupancy/log-odds-update": lambda p: _grid(_logit(0.9), _logit(0.3)),
    "occupancy/ray-update": lambda p: occupancy_ray([1.0, -0.5, 0.2, 2.0, 0.0], 3, 0.85, -0.4),
}

BY_TAG: list[tuple[str, frozenset[str], Plot]] = [
    ("observation-model", frozenset({"xr", "yr", "thr", "xj", "yj"}), _geometry),
    ("drift", frozenset({"bias", "steps"}), BY_ID["drift/systematic-drift"]),
    ("drift", frozenset({"sigma", "steps"}), BY_ID["drift/random-drift"]),
]


def plot_for(exercise_id: str, tags: tuple[str, ...] | list[str], params: Params) -> str | None:
    """The SVG picture of this exercise's variant, or None when it has none."""
    plot = BY_ID.get(exercise_id)
    if plot is None:
        for tag, needs, candidate in BY_TAG:
            if tag in tags and needs <= params.keys():
                plot = candidate
                break
    return None if plot is None else plot(params)


def has_plot(exercise_id: str, tags: tuple[str, ...] | list[str], params: Params) -> bool:
    return exercise_id in BY_ID or any(
        tag in tags and needs <= params.keys() for tag, needs, _ in BY_TAG
    )
