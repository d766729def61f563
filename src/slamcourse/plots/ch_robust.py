"""Figures of chapter ``robust`` (Levenberg-Marquardt and robust kernels), and its pictures.

Prose figures (no arguments; drawn from :mod:`slamcourse.slam.robust` and the INTEL graph that
ships in ``exercises/intel/data``):

- ``robust/kernels``: the weight ``w(s) = ρ'(s)`` of each kernel with ``k = 3`` against ``s``;
- ``robust/damping``: χ² of INTEL after each Gauss-Newton step and each Levenberg-Marquardt
  trial;
- ``robust/fold``: INTEL's clean optimum, plain Gauss-Newton with 10 false loop closures and
  DCS with 100;
- ``robust/lm-window``: χ² per trial of Levenberg-Marquardt from three λ₀ on the 160 INTEL
  poses from pose 100, rejected trials marked, with undamped Gauss-Newton.

Pictures of the code exercises draw givens only: the kernels' costs ``ρ(s)`` (the exercise
asks for their derivatives), the first example graph with its false closures marked, and the
initial guess of ``robust/levenberg-marquardt``'s first example.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from functools import lru_cache
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from slamcourse.plots.picture import Figure, Params, Picture, given
from slamcourse.plots.svg import document, el, fmt, num, polyline, text
from slamcourse.slam import posegraph as pg
from slamcourse.slam import robust as rb

W, H = 640.0, 320.0
LEFT, RIGHT, TOP, BOTTOM = 64.0, 200.0, 36.0, 46.0
SEED = 2013
K = 3.0
STYLES = {
    "l2": ("least squares", "#222222", ""),
    "huber": ("Huber", "#1f6fb2", "8 4"),
    "cauchy": ("Cauchy", "#b3541e", "2 3"),
    "dcs": ("DCS", "#2e8b57", "10 3 2 3"),
}


def _intel_path() -> Path:
    from slamcourse.course.locate import bundled_course_root

    return bundled_course_root() / "exercises" / "intel" / "data" / "input_INTEL.g2o"


@lru_cache(maxsize=1)
def _intel() -> pg.PoseGraph:
    return pg.parse_g2o(_intel_path().read_text(encoding="utf-8"))


def _axes(title: str, xlabel: str, ylabel: str) -> list[str]:
    pw, ph = W - LEFT - RIGHT, H - TOP - BOTTOM
    return [
        el("rect", x=LEFT, y=TOP, width=pw, height=ph, fill="#fbfbf8", stroke="#999"),
        text(LEFT, 20, title, fill="#333"),
        text(LEFT + pw / 2, H - 10, xlabel, text_anchor="middle", fill="#333"),
        text(
            16,
            TOP + ph / 2,
            ylabel,
            text_anchor="middle",
            fill="#333",
            transform=f"rotate(-90 16 {fmt(TOP + ph / 2)})",
        ),
    ]


def _legend(entries: Sequence[tuple[str, str, str]]) -> list[str]:
    """A legend to the right of the plot area (never over the curves)."""
    x0 = W - RIGHT + 12
    out = []
    for i, (name, colour, dash) in enumerate(entries):
        y = TOP + 14 + 18 * i
        out.append(
            polyline(
                [(x0, y - 4), (x0 + 24, y - 4)],
                stroke=colour,
                stroke_width=2.0,
                stroke_dasharray=dash or None,
            )
        )
        out.append(text(x0 + 30, y, name, fill="#222"))
    return out


# --- robust/kernels ---------------------------------------------------------------------------


def kernel_curves(k: float = K, *, derivative: bool = True) -> str:
    """The weight (or, with ``derivative=False``, the cost ``ρ``) of the four kernels of width
    ``k`` against ``s`` from 0.1 to 10⁴ on a logarithmic axis."""
    s = np.logspace(-1, 4, 200)
    pw, ph = W - LEFT - RIGHT, H - TOP - BOTTOM
    curves = {
        kind: (rb.kernel_weights if derivative else rb.kernel_cost)(kind, s, k)
        for kind in rb.KERNELS
    }
    if derivative:
        ymin, ymax = 0.0, 1.05
    else:
        ymin, ymax = 0.0, float(max(np.max(c) for kind, c in curves.items() if kind != "l2"))
        ymax *= 1.1

    def sx(v: float) -> float:
        return LEFT + (math.log10(v) + 1) / 5 * pw

    def sy(v: float) -> float:
        return TOP + (ymax - min(max(v, ymin), ymax)) / (ymax - ymin) * ph

    what = "weight w(s) = ρ'(s)" if derivative else "cost ρ(s)"
    body = _axes(
        f"Kernel {'weights' if derivative else 'costs'}, k = {num(k)}",
        "squared error s = eᵀΩe (log scale)",
        what,
    )
    for decade in range(-1, 5):
        x = sx(10.0**decade)
        body.append(el("line", x1=x, y1=TOP + ph, x2=x, y2=TOP + ph + 4, stroke="#666"))
        body.append(text(x, TOP + ph + 16, f"10^{decade}", text_anchor="middle", fill="#333"))
    ticks = (0.0, 0.5, 1.0) if derivative else (ymin, (ymin + ymax) / 2, ymax)
    for v in ticks:
        body.append(text(LEFT - 6, sy(v) + 4, num(v), text_anchor="end", fill="#333"))
    xb = sx(k * k)
    body.append(
        el("line", x1=xb, y1=TOP, x2=xb, y2=TOP + ph, stroke="#aaa", stroke_dasharray="3 3")
    )
    label = f"s = k² = {num(k * k)}"
    body.append(text(xb - 4, TOP + ph * 0.88, label, text_anchor="end", fill="#555"))
    for kind, values in curves.items():
        _, colour, dash = STYLES[kind]
        pts = [(sx(float(a)), sy(float(b))) for a, b in zip(s, values, strict=True)]
        body.append(polyline(pts, stroke=colour, stroke_width=2.0, stroke_dasharray=dash or None))
    body += _legend([STYLES[kind] for kind in rb.KERNELS])
    if derivative:
        at = [10.0, 100.0, 1000.0]
        facts = "; ".join(
            f"at s = {num(v)}: "
            + ", ".join(
                f"{STYLES[kind][0]} {num(float(rb.kernel_weights(kind, [v], k)[0]))}"
                for kind in rb.KERNELS
            )
            for v in at
        )
        desc = (
            f"The IRLS weight of each kernel of width k = {num(k)} against the squared error "
            f"s, with the boundary s = k² = {num(k * k)} marked. Least squares weighs every "
            f"edge 1; the robust kernels weigh large errors down. Weights {facts}."
        )
    else:
        desc = (
            f"The cost ρ(s) of each kernel of width k = {num(k)} for s from 0.1 to 10000 on a "
            f"logarithmic axis: least squares grows without bound (beyond the plot), Huber "
            f"like 2k√s, Cauchy like k² ln(s/k²), and DCS levels off at 3k² = {num(3 * k * k)}."
        )
    return document(W, H, f"Robust kernel {'weights' if derivative else 'costs'}", desc, body)


# --- robust/damping ---------------------------------------------------------------------------


@lru_cache(maxsize=1)
def damping_traces() -> tuple[list[float], list[float]]:
    """χ² of INTEL before and after each of 10 Gauss-Newton steps, and of 30
    Levenberg-Marquardt trials (Marquardt's scaling, λ₀ = 1)."""
    graph = _intel()
    _, gn = pg.gauss_newton(graph.poses, graph.edges, 10)
    _, lm, _ = rb.levenberg_marquardt(graph.poses, graph.edges, 30, 1.0)
    return gn, lm


def damping_figure() -> str:
    gn, lm = damping_traces()
    pw, ph = W - LEFT - RIGHT, H - TOP - BOTTOM
    lo, hi = 2.0, 9.0  # log10 χ²

    def sx(i: float) -> float:
        return LEFT + i / 30 * pw

    def sy(v: float) -> float:
        return TOP + (hi - math.log10(v)) / (hi - lo) * ph

    body = _axes("χ² of INTEL per iteration", "iteration (trial)", "χ² (log scale)")
    for d in range(int(lo), int(hi) + 1):
        body.append(text(LEFT - 6, sy(10.0**d) + 4, f"10^{d}", text_anchor="end", fill="#333"))
        body.append(
            el("line", x1=LEFT, y1=sy(10.0**d), x2=LEFT + pw, y2=sy(10.0**d), stroke="#e4e4e4")
        )
    for i in range(0, 31, 5):
        body.append(text(sx(i), TOP + ph + 16, str(i), text_anchor="middle", fill="#333"))
    series = [
        ("Gauss-Newton", gn, "#222222", ""),
        ("Levenberg-Marquardt", lm, "#1f6fb2", "8 4"),
    ]
    for _, values, colour, dash in series:
        pts = [(sx(i), sy(v)) for i, v in enumerate(values)]
        body.append(polyline(pts, stroke=colour, stroke_width=2.0, stroke_dasharray=dash or None))
        body += [el("circle", cx=x, cy=y, r=2.5, fill=colour) for x, y in pts]
    body += _legend([(name, colour, dash) for name, _, colour, dash in series])
    desc = (
        f"Start: χ² = {num(gn[0])}. Undamped Gauss-Newton: {', '.join(num(v) for v in gn[1:6])} "
        f"after steps 1 to 5, then {num(gn[-1])} after step 10. Levenberg-Marquardt "
        f"(Marquardt's scaling, λ₀ = 1, Nielsen's update) never increases χ²: {num(lm[1])} "
        f"after trial 1, {num(lm[10])} after 10, {num(lm[30])} after 30."
    )
    return document(W, H, "Gauss-Newton and Levenberg-Marquardt on INTEL", desc, body)


# --- robust/fold ------------------------------------------------------------------------------


@lru_cache(maxsize=1)
def fold_solutions() -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """INTEL's clean optimum, plain Gauss-Newton with 10 false closures, DCS (k = 3) with 100
    (30 steps each), each seen from its pose 0."""
    graph = _intel()
    clean, _ = pg.gauss_newton(graph.poses, graph.edges, 10)
    out = [pg.relative_to_first(clean)]
    for count, kind in ((10, "l2"), (100, "dcs")):
        bad = rb.false_loop_closures(graph.poses, graph.edges, count, SEED)
        x, _ = rb.irls(graph.poses, [*graph.edges, *bad], kind, K, 30)
        out.append(pg.relative_to_first(x))
    return out[0], out[1], out[2]


def _plan(
    trajectories: Sequence[tuple[str, NDArray[np.float64], str, str, float]],
    title: str,
    desc: str,
    extra: Callable[[Callable[[float, float], tuple[float, float]]], list[str]] | None = None,
    more_legend: Sequence[tuple[str, str, str]] = (),
) -> str:
    """Plan view of trajectories (name, n×3 poses, colour, dash, width), equal scales."""
    size = H - TOP - BOTTOM
    allxy = np.vstack([t[1][:, :2] for t in trajectories])
    lo, hi = allxy.min(axis=0), allxy.max(axis=0)
    span = float(max(hi - lo)) or 1.0
    width = size * (hi[0] - lo[0]) / span
    ox = LEFT + (W - LEFT - RIGHT - width) / 2

    def p(x: float, y: float) -> tuple[float, float]:
        return ox + (x - lo[0]) / span * size, TOP + (hi[1] - y) / span * size

    body = [text(LEFT, 20, title, fill="#333")]
    for _, poses, colour, dash, stroke in trajectories:
        body.append(
            polyline(
                [p(float(x), float(y)) for x, y in poses[:, :2]],
                stroke=colour,
                stroke_width=stroke,
                stroke_dasharray=dash or None,
            )
        )
    if extra is not None:
        body += extra(p)
    body += _legend(
        [(name, colour, dash) for name, _, colour, dash, _ in trajectories] + [*more_legend]
    )
    scale_m = 10.0 if span > 20 else 1.0
    x0, y0 = LEFT, H - 14
    body.append(polyline([(x0, y0), (x0 + scale_m / span * size, y0)], stroke="#333"))
    body.append(text(x0 + scale_m / span * size + 6, y0 + 4, f"{num(scale_m)} m", fill="#333"))
    return document(W, H, title, desc, body)


def fold_figure() -> str:
    clean, folded, dcs = fold_solutions()

    def rms(a: NDArray[np.float64]) -> float:
        return float(np.sqrt(np.mean(np.sum((a[:, :2] - clean[:, :2]) ** 2, axis=1))))

    desc = (
        f"Plan view of the INTEL pose graph ({len(clean)} poses, seen from pose 0). Grey: the "
        f"clean optimum. Red, solid: plain Gauss-Newton with 10 false loop closures, "
        f"{num(rms(folded))} m RMS from the clean optimum, the building folded over itself. "
        f"Blue, dashed: DCS with k = 3 and 100 false loop closures, {num(rms(dcs))} m RMS "
        f"from it, on top of the clean map."
    )
    return _plan(
        [
            ("clean optimum", clean, "#bbbbbb", "", 4.0),
            ("least squares, 10 false", folded, "#c0392b", "", 1.2),
            ("DCS, 100 false", dcs, "#1f6fb2", "4 3", 1.2),
        ],
        "INTEL with false loop closures",
        desc,
    )


# --- pictures of the code exercises -----------------------------------------------------------


def example_graph(text_g2o: str) -> str:
    """A small g2o graph's initial guess: odometry solid, loop closures dashed (green), and the
    edges listed as false in the exercise's example (its last two) red."""
    graph = pg.parse_g2o(text_g2o)
    x = graph.poses
    closures = [e for e in graph.edges if abs(e.i - e.j) != 1]
    false = closures[-2:]

    def extra(p: Callable[[float, float], tuple[float, float]]) -> list[str]:
        out = []
        for e in closures:
            colour = "#c0392b" if e in false else "#2e8b57"
            a, b = p(*x[e.i, :2]), p(*x[e.j, :2])
            out.append(polyline([a, b], stroke=colour, stroke_width=1.5, stroke_dasharray="5 3"))
        for k, (px, py, _) in enumerate(x):
            cx, cy = p(float(px), float(py))
            out.append(el("circle", cx=cx, cy=cy, r=3.5, fill="#222"))
            out.append(text(cx + 6, cy - 6, str(k), fill="#222"))
        return out

    desc = (
        f"The initial guess of the example graph: {len(x)} poses joined by odometry (solid), "
        f"{len(closures) - 2} real loop closures (green, dashed) and 2 false ones (red, "
        f"dashed) between poses {false[0].i}–{false[0].j} and {false[1].i}–{false[1].j}."
    )
    return _plan(
        [("odometry (initial guess)", x, "#222222", "", 1.5)],
        "Example graph with two false loop closures",
        desc,
        extra,
        [("real loop closure", "#2e8b57", "5 3"), ("false loop closure", "#c0392b", "5 3")],
    )


def _first_example(exercise: str) -> str:
    import yaml

    from slamcourse.course.locate import bundled_course_root

    path = bundled_course_root() / "exercises" / "robust" / f"{exercise}.yaml"
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    return str(data["examples"][0]["text"])


def _optimise_picture(_: Params) -> str:
    return example_graph(_first_example("robust-optimise"))


# --- robust/lm-window --------------------------------------------------------------------------

LM_WINDOW = (100, 160)
"""The INTEL piece of ``robust/lm-window``: 160 poses from pose 100, with their loop closures."""
LM_LAMBDAS = (1e-6, 1e-3, 1e3)
LM_TRIALS = 20


@lru_cache(maxsize=1)
def window_graph() -> tuple[NDArray[np.float64], list[pg.Edge]]:
    """The poses and the edges among them of INTEL's piece :data:`LM_WINDOW`, renumbered."""
    graph = _intel()
    first, count = LM_WINDOW
    keep = range(first, first + count)
    edges = [
        pg.Edge(e.i - first, e.j - first, e.z, e.information)
        for e in graph.edges
        if e.i in keep and e.j in keep
    ]
    return graph.poses[first : first + count].copy(), edges


@lru_cache(maxsize=1)
def window_traces() -> tuple[list[float], dict[float, tuple[list[float], list[float]]]]:
    """Gauss-Newton's χ² per step and, per λ₀ of :data:`LM_LAMBDAS`, Levenberg-Marquardt's χ²
    after every trial (the first entry before any) and the λ of every trial."""
    poses, edges = window_graph()
    _, gn = pg.gauss_newton(poses, edges, LM_TRIALS)
    lm = {}
    for lam0 in LM_LAMBDAS:
        _, history, lambdas = rb.levenberg_marquardt(poses, edges, LM_TRIALS, lam0)
        lm[lam0] = (history, lambdas)
    return gn, lm


def lm_window_figure() -> str:
    gn, lm = window_traces()
    pw, ph = W - LEFT - RIGHT, H - TOP - BOTTOM
    lo, hi = 0.0, 4.0  # log10 χ²

    def sx(i: float) -> float:
        return LEFT + i / LM_TRIALS * pw

    def sy(v: float) -> float:
        return TOP + (hi - min(max(math.log10(v), lo), hi)) / (hi - lo) * ph

    body = _axes("χ² per trial, INTEL poses 100-259", "trial", "χ² (log scale)")
    for d in range(int(lo), int(hi) + 1):
        body.append(text(LEFT - 6, sy(10.0**d) + 4, f"10^{d}", text_anchor="end", fill="#333"))
        body.append(
            el("line", x1=LEFT, y1=sy(10.0**d), x2=LEFT + pw, y2=sy(10.0**d), stroke="#e4e4e4")
        )
    for i in range(0, LM_TRIALS + 1, 5):
        body.append(text(sx(i), TOP + ph + 16, str(i), text_anchor="middle", fill="#333"))
    styles = {1e-6: ("#1f6fb2", "8 4"), 1e-3: ("#b3541e", "2 3"), 1e3: ("#2e8b57", "10 3 2 3")}
    gn_pts = [(sx(i), sy(v)) for i, v in enumerate(gn)]
    body.append(polyline(gn_pts, stroke="#999999", stroke_width=2.0))
    legend = [("Gauss-Newton", "#999999", "")]
    facts = []
    for lam0, (history, _) in lm.items():
        colour, dash = styles[lam0]
        pts = [(sx(i), sy(v)) for i, v in enumerate(history)]
        body.append(polyline(pts, stroke=colour, stroke_width=2.0, stroke_dasharray=dash))
        rejected = [i for i in range(1, len(history)) if history[i] == history[i - 1]]
        for i, (x, y) in enumerate(pts):
            hollow = i in rejected
            body.append(
                el(
                    "circle",
                    cx=x,
                    cy=y,
                    r=3.0,
                    fill="#ffffff" if hollow else colour,
                    stroke=colour,
                    stroke_width=1.2,
                )
            )
        name = f"LM, λ₀ = {num(lam0)}"
        legend.append((name, colour, dash))
        facts.append(
            f"from λ₀ = {num(lam0)}: {len(rejected)} of {LM_TRIALS} trials rejected"
            f"{' (trials ' + ', '.join(map(str, rejected)) + ')' if rejected else ''}, "
            f"χ² = {num(round(history[-1], 2))} after the last"
        )
    body += _legend(legend)
    body.append(text(W - RIGHT + 12, TOP + 14 + 18 * len(legend), "○ rejected trial", fill="#222"))
    desc = (
        f"χ² of the 160 INTEL poses from pose 100 and the edges among them, starting at "
        f"{num(round(gn[0], 1))}. Undamped Gauss-Newton: {num(round(gn[1], 1))} after step 1, "
        f"{num(round(gn[2], 2))} after step 2, {num(round(gn[-1], 3))} at the end. "
        f"Levenberg-Marquardt with Marquardt's scaling and Nielsen's update, "
        + "; ".join(facts)
        + "."
    )
    return document(W, H, "Levenberg-Marquardt trials on a piece of INTEL", desc, body)


def lm_example_graph(_: Params) -> str:
    """The initial guess of ``robust/levenberg-marquardt``'s first example: odometry solid,
    loop closures dashed. Givens only (the exercise asks for the optimised poses)."""
    import yaml

    from slamcourse.course.locate import bundled_course_root

    path = bundled_course_root() / "exercises" / "robust" / "levenberg-marquardt.yaml"
    example = yaml.safe_load(path.read_text(encoding="utf-8"))["examples"][0]
    x = np.array(example["poses"], dtype=float)
    closures = [(int(e[0]), int(e[1])) for e in example["edges"] if abs(e[0] - e[1]) != 1]

    def extra(p: Callable[[float, float], tuple[float, float]]) -> list[str]:
        out = []
        for i, j in closures:
            a, b = p(*x[i, :2]), p(*x[j, :2])
            out.append(polyline([a, b], stroke="#2e8b57", stroke_width=1.5, stroke_dasharray="5 3"))
        for k, (px, py, _) in enumerate(x):
            cx, cy = p(float(px), float(py))
            out.append(el("circle", cx=cx, cy=cy, r=3.5, fill="#222"))
            out.append(text(cx + 6, cy - 6, str(k), fill="#222"))
        return out

    pairs = ", ".join(f"{i}–{j}" for i, j in closures)
    desc = (
        f"The initial guess of the first example: {len(x)} poses joined by odometry (solid) "
        f"whose headings drifted, and {len(closures)} loop "
        f"{'closure' if len(closures) == 1 else 'closures'} (dashed) between poses {pairs}. "
        f"The example runs {example['trials']} trials from λ₀ = "
        f"{num(float(example['lam0']))}."
    )
    return _plan(
        [("odometry (initial guess)", x, "#222222", "", 1.5)],
        "Levenberg-Marquardt example: the initial guess",
        desc,
        extra,
        [("loop closure", "#2e8b57", "5 3")],
    )


FIGURES: dict[str, Figure] = {
    "robust/kernels": kernel_curves,
    "robust/damping": damping_figure,
    "robust/fold": fold_figure,
    "robust/lm-window": lm_window_figure,
}

PICTURES: dict[str, Picture] = {
    "robust/robust-weights": given(lambda p: kernel_curves(K, derivative=False)),
    "robust/robust-optimise": given(_optimise_picture),
    "robust/levenberg-marquardt": given(lm_example_graph),
}
