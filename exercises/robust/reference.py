"""Reference answers for chapter ``robust``: Levenberg-Marquardt and robust kernels.

Conventions (:mod:`slamcourse.slam.robust`): a kernel ``ρ`` is applied to an edge's squared
Mahalanobis error ``s = eᵀ Ω e``; its weight is ``w(s) = ρ'(s)``; IRLS scales each loop
closure's ``Ω`` by ``w`` in the next Gauss-Newton step (odometry edges, ``|i − j| = 1``, keep
weight 1); DCS uses ``Φ = k²``. The INTEL graph is read from the intel chapter's data folder.
False loop closures are added by :func:`slamcourse.slam.robust.false_loop_closures` with the
seed :data:`OUTLIER_SEED`. Functions whose name starts with ``mistake_`` compute the answer of a
named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from slamcourse.slam import posegraph as pg
from slamcourse.slam import robust as rb

Matrix = NDArray[np.float64]
DATA = Path(__file__).resolve().parent.parent / "intel" / "data" / "input_INTEL.g2o"
OUTLIER_SEED = 2013
"""The seed of every set of false loop closures added to INTEL (Agarwal et al.'s year)."""
CLEAN_ITERATIONS = 10
ROBUST_ITERATIONS = 30
WHOLE = {"count": 50, "kernel": "dcs", "k": 3.0, "iterations": 20}
"""The whole-graph input of ``robust/robust-optimise``: INTEL with 50 false loop closures."""


@lru_cache(maxsize=1)
def intel() -> pg.PoseGraph:
    return pg.parse_g2o(DATA.read_text(encoding="utf-8"))


@lru_cache(maxsize=1)
def clean_optimum() -> Matrix:
    """INTEL after 10 undamped Gauss-Newton steps (converged: χ² = 215.83)."""
    graph = intel()
    x, _ = pg.gauss_newton(graph.poses, graph.edges, CLEAN_ITERATIONS)
    return x


def intel_with_outliers(count: int) -> tuple[Matrix, list[pg.Edge]]:
    """INTEL's initial guess and its edges followed by ``count`` false loop closures (seeded with
    :data:`OUTLIER_SEED`; the first ``c`` of them are the same for every ``count ≥ c``)."""
    graph = intel()
    bad = rb.false_loop_closures(graph.poses, graph.edges, count, OUTLIER_SEED)
    return graph.poses, [*graph.edges, *bad]


@lru_cache(maxsize=8)
def robust_run(kind: str, k: float, count: int) -> tuple[Matrix, list[float], list[pg.Edge]]:
    """INTEL with ``count`` false closures, optimised by IRLS with ``kind`` (``"l2"``: plain
    Gauss-Newton) for 30 steps: the poses, the robust cost of each step, and the edges (the
    false closures last). Made once: an answer and the misconceptions beside it read it."""
    poses, edges = intel_with_outliers(count)
    x, history = rb.irls(poses, edges, kind, k, ROBUST_ITERATIONS)
    return x, history, edges


@lru_cache(maxsize=32)
def survival(kind: str, k: float, count: int) -> tuple[float, float]:
    """:func:`robust_run`'s (χ² of the real edges, RMS position error in metres against the
    clean optimum, poses seen from pose 0)."""
    x, _, _ = robust_run(kind, k, count)
    return pg.chi2(x, intel().edges), rb.position_error(x, clean_optimum())


# --- numeric exercises ------------------------------------------------------------------------


@lru_cache(maxsize=1)
def _first_steps() -> list[float]:
    graph = intel()
    _, history = pg.gauss_newton(graph.poses, graph.edges, 2)
    return history


def first_step_ratio() -> float:
    """χ² after the first undamped Gauss-Newton step on INTEL, divided by the initial χ²."""
    h = _first_steps()
    return h[1] / h[0]


def mistake_first_step_inverted() -> float:
    h = _first_steps()
    return h[0] / h[1]


def mistake_first_step_two_steps() -> float:
    """The ratio after two steps (when the iteration is already recovering)."""
    h = _first_steps()
    return h[2] / h[0]


def gain_ratio(before: float, after: float, model: float) -> float:
    """``ϱ = (χ² before − χ² after) / (χ² before − L(Δ))``, ``model`` = ``L(Δ)``."""
    return rb.gain_ratio(before, after, before - model)


def mistake_gain_over_model(before: float, after: float, model: float) -> float:
    """The actual reduction divided by the model's value ``L(Δ)`` instead of its reduction."""
    return (before - after) / model


def mistake_gain_inverted(before: float, after: float, model: float) -> float:
    """Predicted over actual."""
    return (before - model) / (before - after)


def huber_weight(s: float, k: float) -> float:
    return float(rb.kernel_weights("huber", [s], k)[0])


def mistake_huber_over_s(s: float, k: float) -> float:
    """``k/s``: the weight of a kernel on the norm ``|r|`` divided by ``|r|`` once too often."""
    return min(1.0, k / s)


def mistake_huber_threshold_k(s: float, k: float) -> float:
    """The boundary taken at ``s = k`` (so ``w = √k/√s``, the norm compared with ``√k``)."""
    return 1.0 if s <= k else math.sqrt(k / s)


def mistake_huber_cost(s: float, k: float) -> float:
    """``ρ(s)`` itself instead of its derivative."""
    return float(rb.kernel_cost("huber", [s], k)[0])


def dcs_weight(s: float, k: float) -> float:
    return float(rb.kernel_weights("dcs", [s], k)[0])


def mistake_dcs_not_squared(s: float, k: float) -> float:
    """The DCS scale of the error, ``min(1, 2Φ/(Φ + s))``, used as the weight of ``Ω``."""
    return min(1.0, 2 * k**2 / (k**2 + s))


def mistake_dcs_phi_k(s: float, k: float) -> float:
    """``Φ = k`` instead of ``k²``."""
    return min(1.0, 2 * k / (k + s)) ** 2


def one_closure_error() -> float:
    """RMS position error (m) of plain Gauss-Newton on INTEL with one false closure."""
    return survival("l2", 1.0, 1)[1]


def mistake_one_closure_in_cm() -> float:
    return 100 * one_closure_error()


def dcs_hundred_chi2() -> float:
    """χ² of INTEL's own edges after DCS (k = 3) with 100 false loop closures."""
    return survival("dcs", 3.0, 100)[0]


def mistake_dcs_hundred_with_outliers() -> float:
    """χ² of every edge, false closures included."""
    x, _, edges = robust_run("dcs", 3.0, 100)
    return pg.chi2(x, edges)


def mistake_dcs_hundred_robust_cost() -> float:
    """The robust cost ``Σ ρ`` that IRLS minimises, not the χ² of the real edges."""
    _, history, _ = robust_run("dcs", 3.0, 100)
    return history[-1]


# --- code: robust_weights ---------------------------------------------------------------------


def robust_weights(kind: str, s: Sequence[float], k: float) -> Matrix:
    """``w(s) = ρ'(s)`` of every entry of ``s`` for the kernel ``kind`` of width ``k``."""
    return rb.kernel_weights(kind, np.array(s, dtype=float).reshape(-1), float(k))


def weights_inputs() -> Any:
    """A kernel, a width ``k`` in [0.5, 10] and 1–13 squared errors in [0, 10⁴], with entries
    right at and next to the boundary ``s = k²`` and at 0 among them."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    def build(kind: str, k: float, values: list[float], near: list[int]) -> dict[str, Any]:
        s = list(values)
        for place, how in enumerate(near):
            value = [k * k, k * k * 0.999, k * k * 1.001, 0.0][how]
            s.insert(min(place * 2, len(s)), float(f"{value:.12g}"))
        return {"kind": kind, "s": s, "k": k}

    return st.builds(
        build,
        st.sampled_from(rb.KERNELS),
        real(0.5, 10.0),
        st.lists(real(0.0, 1e4), min_size=1, max_size=10),
        st.lists(st.integers(0, 3), min_size=0, max_size=3),
    )


def _weights_with(
    function: Callable[[float, float], float],
) -> Callable[[str, Sequence[float], float], Matrix]:
    """A wrong ``robust_weights`` that replaces one kernel's weight by ``function(s, k)``."""

    def wrong(kind: str, s: Sequence[float], k: float) -> Matrix:
        return np.array([function(float(v), float(k)) for v in np.array(s, float).reshape(-1)])

    return wrong


def mistake_weights_huber_over_s(kind: str, s: Sequence[float], k: float) -> Matrix:
    if kind == "huber":
        return np.array([1.0 if v <= k * k else k / v for v in np.asarray(s, float).reshape(-1)])
    return robust_weights(kind, s, k)


def mistake_weights_threshold_k(kind: str, s: Sequence[float], k: float) -> Matrix:
    """Huber's and DCS's boundary taken at ``s = k`` (``Φ = k`` for DCS)."""
    if kind in ("huber", "dcs"):
        return rb.kernel_weights(kind, np.array(s, dtype=float).reshape(-1), math.sqrt(k))
    return robust_weights(kind, s, k)


def mistake_weights_dcs_not_squared(kind: str, s: Sequence[float], k: float) -> Matrix:
    if kind == "dcs":
        return _weights_with(mistake_dcs_not_squared)(kind, s, k)
    return robust_weights(kind, s, k)


def mistake_weights_cauchy_k(kind: str, s: Sequence[float], k: float) -> Matrix:
    """Cauchy's ``1/(1 + s/k)``: ``k`` not squared."""
    if kind == "cauchy":
        return 1.0 / (1.0 + np.array(s, dtype=float).reshape(-1) / k)
    return robust_weights(kind, s, k)


def mistake_weights_cost(kind: str, s: Sequence[float], k: float) -> Matrix:
    """``ρ(s)`` returned instead of ``ρ'(s)``."""
    return rb.kernel_cost(kind, np.array(s, dtype=float).reshape(-1), float(k))


# --- code: robust_optimise --------------------------------------------------------------------

Weights = Callable[[str, Matrix, float], Matrix]


def _irls(
    text: str,
    kernel: str,
    k: float,
    iterations: int,
    *,
    weights: Weights = rb.kernel_weights,
    everywhere: bool = False,
    frozen: bool = False,
    relative: bool = True,
) -> Matrix:
    """IRLS on a g2o text (see :func:`robust_optimise`), with the switches of the mistakes."""
    graph = pg.parse_g2o(text)
    x = graph.poses.copy()
    edges = graph.edges
    lc = rb.loop_closures(edges) | everywhere
    w = np.ones(len(edges))
    for step in range(int(iterations)):
        if not (frozen and step > 0):
            w = np.where(lc, weights(kernel, rb.edge_chi2s(x, edges), float(k)), 1.0)
        x = pg.gauss_newton_step(x, edges, 0, rb._weighted(w))
    return pg.relative_to_first(x) if relative else x


def robust_optimise(text: str, kernel: str, k: float, iterations: int) -> Matrix:
    """Parse a g2o text and run ``iterations`` IRLS steps with pose 0 fixed: at each step the
    weight ``w(s)`` of every loop closure (``|i − j| ≠ 1``) at the current poses, weight 1 for
    odometry edges, then one Gauss-Newton step with each ``Ω`` scaled by its weight. Returns
    every pose seen from pose 0 (n×3, angles in (−π, π])."""
    return _irls(text, kernel, k, iterations)


def mistake_optimise_everywhere(text: str, kernel: str, k: float, iterations: int) -> Matrix:
    """The kernel applied to the odometry edges too."""
    return _irls(text, kernel, k, iterations, everywhere=True)


def mistake_optimise_frozen(text: str, kernel: str, k: float, iterations: int) -> Matrix:
    """The weights computed once, at the initial guess, and never updated."""
    return _irls(text, kernel, k, iterations, frozen=True)


def _unsquared(kind: str, s: Matrix, k: float) -> Matrix:
    w = rb.kernel_weights(kind, s, k)
    return np.sqrt(w) if kind == "dcs" else w


def mistake_optimise_dcs_not_squared(text: str, kernel: str, k: float, iterations: int) -> Matrix:
    """DCS's scale of the error used as the weight of ``Ω`` (not squared)."""
    return _irls(text, kernel, k, iterations, weights=_unsquared)


def _on_norm(kind: str, s: Matrix, k: float) -> Matrix:
    """The weight of the kernel applied to ``√s`` with boundary ``k`` (``ρ'`` at the norm)."""
    return rb.kernel_weights(kind, np.sqrt(s), k)


def mistake_optimise_weight_of_norm(text: str, kernel: str, k: float, iterations: int) -> Matrix:
    """``w`` evaluated at ``√s`` (the Mahalanobis distance) instead of ``s``."""
    return _irls(text, kernel, k, iterations, weights=_on_norm)


def mistake_optimise_absolute(text: str, kernel: str, k: float, iterations: int) -> Matrix:
    return _irls(text, kernel, k, iterations, relative=False)


def _with_outliers(
    poses: Matrix, edges: Sequence[pg.Edge], count: int, seed: int, min_gap: int
) -> str:
    bad = rb.false_loop_closures(poses, edges, count, seed, min_gap) if count else []
    return pg.to_g2o(poses, [*edges, *bad])


@lru_cache(maxsize=8)
def intel_window_with_outliers(first: int, count: int, outliers: int) -> str:
    """INTEL poses ``first … first+count−1`` and every edge among them (renumbered from 0), then
    ``outliers`` false loop closures (seed :data:`OUTLIER_SEED`), as g2o text."""
    graph = intel()
    keep = range(first, first + count)
    edges = [
        pg.Edge(e.i - first, e.j - first, e.z, e.information)
        for e in graph.edges
        if e.i in keep and e.j in keep
    ]
    poses = graph.poses[first : first + count]
    return _with_outliers(poses, edges, outliers, OUTLIER_SEED, 50)


@lru_cache(maxsize=1)
def intel_whole_with_outliers() -> str:
    """The whole INTEL graph and its 50 false loop closures (seed :data:`OUTLIER_SEED`)."""
    poses, edges = intel_with_outliers(int(WHOLE["count"]))
    return pg.to_g2o(poses, edges)


def _converged(text: str, kernel: str, k: float, iterations: int) -> bool:
    """Whether IRLS has settled after ``iterations`` steps: three more move no pose (seen from
    pose 0) by more than 10⁻⁸."""
    graph = pg.parse_g2o(text)
    if iterations == 0:
        return True
    x, _ = rb.irls(graph.poses, graph.edges, kernel, k, iterations)
    y, _ = rb.irls(x, graph.edges, kernel, k, 3)
    a, b = pg.relative_to_first(x), pg.relative_to_first(y)
    return bool(np.all(np.isfinite(a)) and np.max(np.abs(a - b)) < 1e-8)


ROBUST_PIECE = 160
"""Poses in each INTEL piece ``robust/robust-optimise`` is graded on."""


def optimise_inputs() -> Any:
    """Two 160-pose pieces of INTEL with 5 false closures each (DCS and Huber, k = 3, 20 or 40
    steps) and synthetic graphs of 6–25 poses with 0–3 loop closures and 0–3 false
    ones, every kernel, widths 1–5, that settle within their steps. (The whole graph with 50
    false closures is the chapter's demonstration and ``dcs-hundred``'s, not a graded input: a
    dense learner's solve would take minutes per learner.)"""
    from hypothesis import strategies as st

    real = st.sampled_from(
        [
            {
                "text": intel_window_with_outliers(150, ROBUST_PIECE, 5),
                "kernel": "dcs",
                "k": 3.0,
                "iterations": 20,
            },
            {
                "text": intel_window_with_outliers(1060, ROBUST_PIECE, 5),
                "kernel": "huber",
                "k": 3.0,
                "iterations": 40,
            },
        ]
    )

    def synthetic(
        seed: int, n: int, loops: int, outliers: int, kernel: str, k: float, iterations: int
    ) -> dict[str, Any]:
        poses, edges = pg.simulate(seed, n, loops)
        text = _with_outliers(poses, edges, outliers, seed, 3)
        return {"text": text, "kernel": kernel, "k": k, "iterations": iterations}

    made = st.builds(
        synthetic,
        st.integers(0, 2**32 - 1),
        st.integers(6, 25),
        st.integers(0, 3),
        st.integers(0, 3),
        st.sampled_from(rb.KERNELS),
        st.sampled_from([1.0, 2.0, 3.0, 5.0]),
        st.sampled_from([15, 25]),
    ).filter(lambda d: _converged(**d))
    return st.one_of(real, made)


def optimise_valid(text: str, kernel: str, k: float, iterations: int) -> bool:
    """``robust_optimise``'s domain for derived inputs: a g2o text of at most 200 poses whose ids
    run from 0 to n − 1, a kernel of the four, ``k`` in [1, 10], 0–40 steps, within which
    IRLS settles (where it has not, the iterate depends on the gauge a correct method picks)."""
    try:
        graph = pg.parse_g2o(text)
    except Exception:  # not a g2o text the prompt describes
        return False
    n = len(graph.poses)
    if not 2 <= n <= 200 or any(not (0 <= e.i < n and 0 <= e.j < n) for e in graph.edges):
        return False
    if kernel not in rb.KERNELS or not 1 <= k <= 10 or not 0 <= iterations <= 40:
        return False
    return _converged(text, kernel, k, iterations)


def figure_intel(count: int, kind: str, k: float) -> Matrix:
    """Poses (n×3, world frame with pose 0 at the origin) of INTEL with ``count`` false closures
    after IRLS with ``kind`` (for the chapter's figures)."""
    poses, edges = intel_with_outliers(count)
    x, _ = rb.irls(poses, edges, kind, k, ROBUST_ITERATIONS)
    return x


# --- parametrised numeric exercises (keyword arguments of the YAML parameters) -----------------


def gain_ratio_scaled(before: float, model: float, after: float, **_: float) -> float:
    return gain_ratio(before, after, model)


def mistake_gain_over_model_scaled(before: float, model: float, after: float, **_: float) -> float:
    return mistake_gain_over_model(before, after, model)


def mistake_gain_inverted_scaled(before: float, model: float, after: float, **_: float) -> float:
    return mistake_gain_inverted(before, after, model)


# --- code: levenberg_marquardt ----------------------------------------------------------------

LM_MAX_POSES = 160
"""The largest graph ``robust/levenberg-marquardt`` is tested on (an INTEL window)."""
LM_WINDOWS = (
    # (first pose, poses, λ₀, trials): 160- and 100-pose pieces of INTEL with their loop
    # closures, where small λ₀ makes the first trials fail and large λ₀ crawls
    (80, 160, 1e-6, 10),
    (1100, 100, 1e-6, 8),
    (120, 160, 1000.0, 10),
)


def _lm_trials(
    poses: Sequence[Sequence[float]],
    edges: Sequence[Sequence[Any]],
    lam0: float,
    trials: int,
    *,
    marquardt: bool = True,
    predicted: Callable[[float, float, float], float] | None = None,
    actual_scale: float = 1.0,
    accept_all: bool = False,
    move_on_reject: bool = False,
    stale_chi2: bool = False,
    reset_nu: bool = True,
    update: str = "nielsen",
    count_accepted: bool = False,
    frozen_damping: bool = False,
) -> tuple[Matrix, list[tuple[float, float, float]]]:
    """Levenberg-Marquardt as the prompt of ``robust/levenberg-marquardt`` states it, with the
    switches of the named mistakes. ``predicted(btd, dhd, ddd)`` computes the predicted
    reduction from ``bᵀΔ``, ``ΔᵀHΔ`` and ``λ ΔᵀDΔ``. Returns the world-frame poses and, per
    trial, ``(λ, ϱ, largest |Δ|)``."""
    x = np.array(poses, dtype=float)
    graph = _as_edges(edges)
    n = len(x)
    current = pg.chi2(x, graph)
    start = current
    lam, nu = float(lam0), 2.0
    record: list[tuple[float, float, float]] = []
    d_fixed: Matrix | None = None
    done = 0
    attempts = 0
    while (done if count_accepted else attempts) < int(trials) and attempts < 200:
        attempts += 1
        h, b = pg.linear_system(x, graph)
        h, b = h[3:, 3:], b[3:]
        if marquardt:
            if d_fixed is None or not frozen_damping:
                d_fixed = np.diag(h).copy()
            d = d_fixed
        else:
            d = np.ones(len(b))
        delta = np.linalg.solve(h + np.diag(lam * d), -b) if n > 1 else np.zeros(0)
        y = x.copy()
        y[1:] += delta.reshape(-1, 3)
        y[:, 2] = np.remainder(y[:, 2] + math.pi, 2 * math.pi) - math.pi
        new = pg.chi2(y, graph)
        btd, dhd, ddd = float(b @ delta), float(delta @ h @ delta), float(lam * delta @ (d * delta))
        pred = predicted(btd, dhd, ddd) if predicted else -(2.0 * btd + dhd)
        before = start if stale_chi2 else current
        actual = actual_scale * (before - new)
        if predicted is None:
            rho = actual / pred if pred > 0 else -1.0
        else:
            rho = actual / pred if pred != 0 else -1.0
        record.append((lam, rho, float(np.max(np.abs(delta), initial=0.0))))
        if rho > 0 or accept_all:
            x, current = y, new
            done += 1
            if update == "nielsen":
                lam *= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
            elif update == "inverted":
                lam /= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
            else:  # "ten"
                lam /= 10.0
            if reset_nu:
                nu = 2.0
        else:
            if move_on_reject:
                x = y
            if update == "nielsen":
                lam *= nu
            elif update == "inverted":
                lam /= nu
            else:
                lam *= 10.0
            nu *= 2.0
    return x, record


def _as_edges(raw: Sequence[Sequence[Any]]) -> list[pg.Edge]:
    return [
        pg.Edge(int(i), int(j), (float(z[0]), float(z[1]), float(z[2])), np.array(om, float))
        for i, j, z, om in raw
    ]


def _plain(edges: Sequence[pg.Edge]) -> list[list[Any]]:
    return [[e.i, e.j, [float(v) for v in e.z], e.information.tolist()] for e in edges]


def levenberg_marquardt(
    poses: Sequence[Sequence[float]], edges: Sequence[Sequence[Any]], lam0: float, trials: int
) -> Matrix:
    """``trials`` Levenberg-Marquardt trials from ``poses`` with pose 0 fixed: solve
    ``(H + λ diag H) Δ = −b``, ``ϱ = (χ²(x) − χ²(x + Δ)) / (−2bᵀΔ − ΔᵀHΔ)``; ``ϱ > 0``: accept,
    ``λ ← λ max(1/3, 1 − (2ϱ − 1)³)``, ``ν ← 2``; else keep the poses, ``λ ← νλ``, ``ν ← 2ν``
    (a predicted reduction ≤ 0 counts as a rejection). Every pose seen from pose 0 (n×3)."""
    x, _, _ = rb.levenberg_marquardt(
        np.array(poses, dtype=float), _as_edges(edges), int(trials), float(lam0)
    )
    return pg.relative_to_first(x)


def lm_record(
    poses: Sequence[Sequence[float]], edges: Sequence[Sequence[Any]], lam0: float, trials: int
) -> list[tuple[float, float, float]]:
    """Per trial of the prompt's method: (λ used, ϱ, largest |Δ|)."""
    return _lm_trials(poses, edges, lam0, trials)[1]


@lru_cache(maxsize=8)
def intel_window(first: int, count: int) -> tuple[list[list[float]], list[list[Any]]]:
    """INTEL poses ``first … first+count−1`` and every edge among them, renumbered from 0, as
    plain lists (poses n×3, edges ``[i, j, z, Ω]``)."""
    graph = intel()
    keep = range(first, first + count)
    edges = [
        pg.Edge(e.i - first, e.j - first, e.z, e.information)
        for e in graph.edges
        if e.i in keep and e.j in keep
    ]
    return graph.poses[first : first + count].tolist(), _plain(edges)


def drifted_graph(seed: int, n: int, loops: int, drift: float) -> tuple[Matrix, list[pg.Edge]]:
    """A synthetic graph (:func:`slamcourse.slam.posegraph.simulate`) whose initial guess is
    dead reckoning with every odometry heading off by a normal error of ``drift`` rad (seeded
    with ``seed + 1``): the loop closures then disagree with the guess by metres and radians,
    as INTEL's do, and undamped steps overshoot."""
    from slamcourse.slam.se2 import compose

    poses, edges = pg.simulate(seed, n, loops)
    rng = np.random.default_rng(seed + 1)
    guess = [tuple(float(v) for v in poses[0])]
    for e in edges[: n - 1]:
        z = (e.z[0], e.z[1], e.z[2] + float(rng.normal(0.0, drift)))
        guess.append(compose(guess[-1], z))
    return np.array(guess, dtype=float), list(edges)


def _lm_settled(
    poses: Sequence[Sequence[float]], edges: Sequence[Sequence[Any]], lam0: float, trials: int
) -> bool:
    """Every trial's decision is clear: ``|ϱ| ≥ 10⁻³`` (or the step moves nothing by more than
    10⁻⁹, so accepting or rejecting it changes no pose), and λ stays finite."""
    for lam, rho, size in lm_record(poses, edges, lam0, trials):
        if not math.isfinite(lam) or not 1e-300 < lam < 1e200:
            return False
        if size > 1e-9 and not abs(rho) >= 1e-3:
            return False
    return True


def lm_inputs() -> Any:
    """Three INTEL windows (100 or 160 poses, their own loop closures; small λ₀ where the first
    trials are rejected, large λ₀ where the steps crawl), and synthetic graphs of 3–15 poses
    with 1–4 loop closures and a drifted initial guess, λ₀ log-uniform in [10⁻⁶, 10⁴], 0–15
    trials."""
    from hypothesis import strategies as st

    windows = [
        {"poses": p, "edges": e, "lam0": lam0, "trials": trials}
        for first, count, lam0, trials in LM_WINDOWS
        for p, e in [intel_window(first, count)]
    ]

    def synthetic(
        seed: int, n: int, loops: int, drift: float, exponent: int, mantissa: float, trials: int
    ) -> dict[str, Any]:
        poses, edges = drifted_graph(seed, n, loops, drift)
        lam0 = float(f"{mantissa * 10.0**exponent:.6g}")
        return {
            "poses": [[round(float(v), 9) for v in p] for p in poses],
            "edges": _plain(edges),
            "lam0": lam0,
            "trials": trials,
        }

    made = st.builds(
        synthetic,
        st.integers(0, 2**32 - 2),
        st.integers(3, 15),
        st.integers(1, 4),
        st.sampled_from([0.6, 0.9, 1.2]),
        st.integers(-6, 3),
        st.sampled_from([1.0, 2.5, 5.0]),
        st.integers(0, 15),
    ).filter(lambda d: _lm_settled(**d))
    return st.one_of(st.sampled_from(windows), made)


def lm_valid(
    poses: Sequence[Sequence[float]], edges: Sequence[Sequence[Any]], lam0: float, trials: int
) -> bool:
    """``levenberg_marquardt``'s domain: 2–160 poses of three numbers, edges between two
    different poses with a symmetric positive-definite 3×3 information matrix, every pose
    joined to pose 0 through edges, ``λ₀`` in [10⁻⁶, 10⁴], 0–15 trials, and no trial whose
    gain ratio is within 10⁻³ of the threshold 0 (where rounding decides the verdict)."""
    n = len(poses)
    if not 2 <= n <= LM_MAX_POSES or any(len(p) != 3 for p in poses):
        return False
    if not 1e-6 <= float(lam0) <= 1e4 or not 0 <= int(trials) <= 15:
        return False
    reached = {0}
    pairs = []
    for e in edges:
        if len(e) != 4:
            return False
        i, j, z, om = e
        if not (0 <= i < n and 0 <= j < n) or i == j or len(z) != 3:
            return False
        a = np.asarray(om, dtype=float)
        if a.shape != (3, 3) or not np.allclose(a, a.T, atol=1e-12):
            return False
        if np.min(np.linalg.eigvalsh(a)) <= 0:
            return False
        pairs.append((int(i), int(j)))
    grew = True
    while grew:
        grew = False
        for i, j in pairs:
            if (i in reached) != (j in reached):
                reached |= {i, j}
                grew = True
    if len(reached) != n:
        return False
    return _lm_settled(poses, edges, lam0, trials)


def _lm_mistake(**switches: Any) -> Callable[..., Matrix]:
    def wrong(
        poses: Sequence[Sequence[float]],
        edges: Sequence[Sequence[Any]],
        lam0: float,
        trials: int,
    ) -> Matrix:
        x, _ = _lm_trials(poses, edges, lam0, trials, **switches)
        return pg.relative_to_first(x)

    return wrong


mistake_lm_inverted = _lm_mistake(update="inverted")
"""λ lowered after a rejection and raised after an acceptance."""
mistake_lm_accept_all = _lm_mistake(accept_all=True)
"""Every trial accepted, whatever ``ϱ``."""
mistake_lm_predicted_sign = _lm_mistake(predicted=lambda btd, dhd, ddd: 2.0 * btd + dhd)
"""The predicted reduction written ``L(Δ) − χ²`` (wrong sign)."""
mistake_lm_predicted_half = _lm_mistake(predicted=lambda btd, dhd, ddd: 0.5 * (ddd - btd))
"""The ½χ² form ``½Δᵀ(λDΔ − b)`` of the predicted reduction against the full χ²."""
mistake_lm_predicted_no_lambda = _lm_mistake(predicted=lambda btd, dhd, ddd: -btd)
"""The predicted reduction without its ``λΔᵀDΔ`` term (the damped model's reduction)."""
mistake_lm_identity = _lm_mistake(marquardt=False)
"""Levenberg's ``H + λI`` instead of ``H + λ diag H``."""
mistake_lm_rejected_poses = _lm_mistake(move_on_reject=True)
"""The poses moved to ``x + Δ`` also when the trial is rejected."""
mistake_lm_ten = _lm_mistake(update="ten")
"""Marquardt's old rule: λ divided by 10 after an accepted trial, multiplied by 10 after a
rejected one."""


def mistake_lm_absolute(
    poses: Sequence[Sequence[float]], edges: Sequence[Sequence[Any]], lam0: float, trials: int
) -> Matrix:
    """The world-frame poses, not seen from pose 0."""
    x, _, _ = rb.levenberg_marquardt(
        np.array(poses, dtype=float), _as_edges(edges), int(trials), float(lam0)
    )
    return x
