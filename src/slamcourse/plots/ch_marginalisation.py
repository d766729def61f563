"""Figures of chapter ``marginalisation`` and pictures of its exercises.

- the marginal and the conditional of a two-variable Gaussian (the chapter's rail example);
- the marginal and conditional heading uncertainty along INTEL's odometry chain;
- the information matrix of a sliding window before and after marginalising its oldest pose
  (the fill-in of the prior), also drawn for the exercises' own numbers.

Every number drawn comes from :mod:`slamcourse.slam.marginal` and the INTEL file the intel
chapter ships (``exercises/intel/data/input_INTEL.g2o``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache

import numpy as np

from slamcourse.plots.picture import Figure, Params, Picture, answer, given
from slamcourse.plots.sparsity import cell_marks
from slamcourse.plots.svg import document, el, fmt, num, polyline, text
from slamcourse.slam import marginal as mg

Cell = tuple[int, int]

# the chapter's two-variable example: prior 4 m⁻² on x0, odometry 25 m⁻² on x1 − x0
RAIL_H = ((29.0, -25.0), (-25.0, 25.0))
INTEL_LAST = 150


# --- marginal and conditional of a 2-D Gaussian -----------------------------------------------


def marginal_vs_conditional(h: Sequence[Sequence[float]] = RAIL_H) -> str:
    """The 1σ ellipse of a zero-mean Gaussian with 2×2 information ``h``, with the marginal
    (shadow on the x₁ axis) and the conditional (slice at x₀ = 0) standard deviations of x₁."""
    hh = np.array(h, dtype=float)
    sigma = np.linalg.inv(hh)
    s_marg = math.sqrt(sigma[1, 1])
    s_cond = 1 / math.sqrt(hh[1, 1])
    root = np.linalg.cholesky(sigma)
    ts = np.linspace(0, 2 * math.pi, 121)
    pts = root @ np.vstack([np.cos(ts), np.sin(ts)])
    extent = 1.25 * float(np.abs(pts).max())
    w, h_px, left, top, side = 600.0, 380.0, 70.0, 30.0, 300.0

    def sx(v: float) -> float:
        return left + (v + extent) / (2 * extent) * side

    def sy(v: float) -> float:
        return top + (extent - v) / (2 * extent) * side

    body = [
        el("rect", x=left, y=top, width=side, height=side, fill="#fff", stroke="#888"),
        el("line", x1=sx(0), y1=top, x2=sx(0), y2=top + side, stroke="#ccc"),
        el("line", x1=left, y1=sy(0), x2=left + side, y2=sy(0), stroke="#ccc"),
        text(left + side / 2, top + side + 34, "x₀ (m)", text_anchor="middle", fill="#222"),
        text(left, top - 10, "x₁ (m)", fill="#222"),
        polyline(((sx(x), sy(y)) for x, y in pts.T), stroke="#1f4e79", stroke_width=2),
    ]
    step = 0.5 if extent > 0.6 else 0.1
    for k in range(-int(extent / step), int(extent / step) + 1):
        v = k * step
        body.append(text(sx(v), top + side + 16, fmt(v), text_anchor="middle", fill="#444"))
        body.append(text(left - 6, sy(v) + 4, fmt(v), text_anchor="end", fill="#444"))
    for v in (-s_marg, s_marg):  # the shadow: tangents to the ellipse
        body.append(
            el(
                "line",
                x1=left,
                y1=sy(v),
                x2=left + side,
                y2=sy(v),
                stroke="#b3541e",
                stroke_dasharray="6 4",
            )
        )
    body += [
        el(
            "line",
            x1=sx(0),
            y1=sy(-s_cond),
            x2=sx(0),
            y2=sy(s_cond),
            stroke="#2e7d32",
            stroke_width=5,
        ),
        el(
            "line",
            x1=left + side + 12,
            y1=sy(-s_marg),
            x2=left + side + 12,
            y2=sy(s_marg),
            stroke="#b3541e",
            stroke_width=3,
        ),
    ]
    lx = left + side + 30
    body += [
        text(lx, top + 40, "marginal σ of x₁:", fill="#b3541e"),
        text(lx, top + 58, f"{num(s_marg)} m (shadow, dashed)", fill="#b3541e"),
        text(lx, top + 100, "conditional σ of x₁", fill="#2e7d32"),
        text(lx, top + 118, f"given x₀ = 0: {num(s_cond)} m", fill="#2e7d32"),
        text(lx, top + 136, "(slice, thick line)", fill="#2e7d32"),
        text(lx, top + 178, "ellipse: 1σ contour", fill="#1f4e79"),
    ]
    desc = (
        f"The 1-sigma ellipse of two positions x0 and x1 with information matrix "
        f"[[{fmt(hh[0, 0])}, {fmt(hh[0, 1])}], [{fmt(hh[1, 0])}, {fmt(hh[1, 1])}]]. The marginal "
        f"standard deviation of x1, the shadow of the ellipse on the x1 axis, is {num(s_marg)} m; "
        f"the conditional standard deviation of x1 given x0, the slice through the ellipse at "
        f"x0 = 0, is {num(s_cond)} m."
    )
    return document(w, h_px, "Marginal and conditional of a Gaussian", desc, body)


# --- INTEL's odometry chain ---------------------------------------------------------------------


@lru_cache(maxsize=1)
def intel_chain_sigmas(last: int = INTEL_LAST) -> tuple[list[float], list[float]]:
    """Marginal and conditional heading standard deviations (rad) of INTEL's poses 1 … ``last``
    (pose 0 fixed), ``H`` linearised at the file's initial guess (odometry only)."""
    from slamcourse.course.locate import bundled_course_root
    from slamcourse.slam import posegraph as pg

    path = bundled_course_root() / "exercises" / "intel" / "data" / "input_INTEL.g2o"
    graph = pg.parse_g2o(path.read_text(encoding="utf-8"))
    edges = [e for e in graph.edges if e.i <= last and e.j <= last]
    h, _ = pg.linear_system(graph.poses[: last + 1], edges)
    h = h[3:, 3:]
    heading = [3 * k + 2 for k in range(last)]
    full = mg.marginal_covariance(h, list(range(len(h))))
    marginal = [math.sqrt(full[i, i]) for i in heading]
    conditional = [1 / math.sqrt(h[i, i]) for i in heading]
    return marginal, conditional


def intel_chain_sigma() -> str:
    marginal, conditional = intel_chain_sigmas()
    n = len(marginal)
    w, h_px, left, top, pw, ph = 560.0, 320.0, 60.0, 30.0, 420.0, 220.0
    ymax = 0.05 * math.ceil(max(marginal) / 0.05 + 1e-9)

    def sx(k: float) -> float:
        return left + k / n * pw

    def sy(v: float) -> float:
        return top + ph - v / ymax * ph

    body = [el("rect", x=left, y=top, width=pw, height=ph, fill="#fff", stroke="#888")]
    for k in range(0, n + 1, 25):
        body.append(text(sx(k), top + ph + 16, str(k), text_anchor="middle", fill="#444"))
    ticks = [0.05 * i for i in range(round(ymax / 0.05) + 1)]
    for v in ticks:
        body.append(el("line", x1=left, y1=sy(v), x2=left + pw, y2=sy(v), stroke="#eee"))
        body.append(text(left - 6, sy(v) + 4, fmt(v), text_anchor="end", fill="#444"))
    body += [
        text(left + pw / 2, top + ph + 36, "pose index", text_anchor="middle", fill="#222"),
        text(left, top - 10, "heading σ (rad)", fill="#222"),
        polyline(
            ((sx(k + 1), sy(v)) for k, v in enumerate(marginal)), stroke="#1f4e79", stroke_width=2
        ),
        polyline(
            ((sx(k + 1), sy(v)) for k, v in enumerate(conditional)),
            stroke="#b3541e",
            stroke_width=2,
            stroke_dasharray="6 4",
        ),
        el(
            "line",
            x1=left + 14,
            y1=top + 16,
            x2=left + 44,
            y2=top + 16,
            stroke="#1f4e79",
            stroke_width=2,
        ),
        text(left + 50, top + 20, "marginal: from H⁻¹", fill="#222"),
        el(
            "line",
            x1=left + 14,
            y1=top + 36,
            x2=left + 44,
            y2=top + 36,
            stroke="#b3541e",
            stroke_width=2,
            stroke_dasharray="6 4",
        ),
        text(left + 50, top + 40, "conditional: 1/√H_θθ", fill="#222"),
    ]
    desc = (
        f"Heading standard deviation of INTEL's poses 1 to {n}, pose 0 fixed, odometry only. "
        f"The marginal standard deviation grows from {num(marginal[0])} rad at pose 1 to "
        f"{num(marginal[-1])} rad at pose {n}; the conditional standard deviation read off the "
        f"diagonal of H stays between {num(min(conditional))} and {num(max(conditional))} rad."
    )
    return document(w, h_px, "Marginal and conditional uncertainty along INTEL's chain", desc, body)


# --- the fill of a sliding window -----------------------------------------------------------------


def window_graph(
    poses: int, sightings: Sequence[Sequence[int]]
) -> tuple[list[str], list[tuple[int, int]]]:
    """Variables (poses x0 … then landmarks l0 …) and the factors' pairs of a window: odometry
    between consecutive poses, and ``sightings[p]`` = the landmarks pose ``p`` saw."""
    landmarks = 1 + max((max(s) for s in sightings if s), default=-1)
    names = [f"x{p}" for p in range(poses)] + [f"l{k}" for k in range(landmarks)]
    edges = [(p, p + 1) for p in range(poses - 1)]
    edges += [(p, poses + k) for p, seen in enumerate(sightings) for k in seen]
    return names, edges


def _grid(
    x0: float,
    y0: float,
    size: float,
    names: list[str],
    cells: set[Cell],
    fill: set[Cell],
    gone: set[int],
    label: str,
) -> list[str]:
    n = len(names)
    out = [text(x0, y0 - 26, label, fill="#222", font_weight="bold")]
    out.append(el("rect", x=x0, y=y0, width=size * n, height=size * n, fill="#fff", stroke="#888"))
    for k, name in enumerate(names):
        colour = "#aaa" if k in gone else "#222"
        out.append(
            text(
                x0 + (k + 0.5) * size, y0 - 6, name, text_anchor="middle", fill=colour, font_size=10
            )
        )
        out.append(
            text(x0 - 4, y0 + (k + 0.7) * size, name, text_anchor="end", fill=colour, font_size=10)
        )
    for k in gone:
        out.append(el("rect", x=x0, y=y0 + k * size, width=size * n, height=size, fill="#eee"))
        out.append(el("rect", x=x0 + k * size, y=y0, width=size, height=size * n, fill="#eee"))
    out.extend(cell_marks(cells, fill, x0, y0, size))
    return out


def window_fill(poses: int, sightings: Sequence[Sequence[int]], removed: int = 0) -> str:
    """The pattern of a window's information matrix before and after marginalising pose
    ``removed``; fill-in drawn as crossed cells."""
    names, edges = window_graph(poses, sightings)
    n = len(names)
    before = {(i, i) for i in range(n)} | {(i, j) for e in edges for i, j in (e, e[::-1])}
    fill_pairs = mg.marginal_fill(n, edges, [removed])
    fill = {(i, j) for p in fill_pairs for i, j in (p, p[::-1])}
    after = {c for c in before if removed not in c} | fill
    blanket = mg.markov_blanket(n, edges, [removed])
    size = min(22.0, 230.0 / n)
    side = size * n
    w, h_px = 2 * side + 150, side + 110
    body = _grid(40, 50, size, names, before, set(), set(), "H before")
    body += _grid(
        110 + side, 50, size, names, after, fill, {removed}, f"after marginalising {names[removed]}"
    )
    ly = 50 + side + 30
    body += [
        el("rect", x=40.0, y=ly - 10, width=12.0, height=12.0, fill="#1f4e79"),
        text(58, ly, "non-zero", fill="#222"),
        el("rect", x=140.0, y=ly - 10, width=12.0, height=12.0, fill="#f3d9c4", stroke="#b3541e"),
        text(158, ly, f"fill-in (×): {len(fill_pairs)} new pairs", fill="#222"),
    ]
    seen = ", ".join(
        f"{names[p]} saw {', '.join(names[poses + k] for k in s)}"
        for p, s in enumerate(sightings)
        if s
    )
    desc = (
        f"Information matrix of a sliding window with {poses} poses and {n - poses} landmarks; "
        f"{seen}. Marginalising {names[removed]} leaves a dense prior on its "
        f"{len(blanket)} neighbours ({', '.join(names[v] for v in blanket)}): "
        f"{len(fill_pairs)} pairs of variables are linked that were not linked before."
    )
    return document(w, h_px, "Fill-in from marginalising the oldest pose", desc, body)


# the chapter's window: x0 saw l0 … l3, x1 saw l0 and l3, x2 and x3 the last landmark
WINDOW_SIGHTINGS: tuple[tuple[int, ...], ...] = ((0, 1, 2, 3), (0, 3), (3, 4), (4,))


def _window_for(params: Params) -> str:
    """The exercises' window: x0 saw ``seen`` landmarks, x1 the first ``shared`` of them."""
    seen, shared = int(params["seen"]), int(params["shared"])
    return window_fill(2, [tuple(range(seen)), tuple(range(shared))])


def _rail_fill(params: Params) -> str:
    """The marginalise exercise's first example: the rail x0, x1, x2, x1 marginalised."""
    return window_fill(3, [(), (), ()], removed=1)


FIGURES: dict[str, Figure] = {
    "marginalisation/marginal-vs-conditional": marginal_vs_conditional,
    "marginalisation/intel-chain-sigma": intel_chain_sigma,
    "marginalisation/window-fill": lambda: window_fill(4, WINDOW_SIGHTINGS),
}

PICTURES: dict[str, Picture] = {
    # the count is the number of crossed cells: shown once solved
    "marginalisation/fill-count": answer(_window_for),
    "marginalisation/prior-size": answer(_window_for),
    # code exercises: the lesson's own numbers
    "marginalisation/marginalise": given(_rail_fill),
    "marginalisation/marginal-covariance": given(lambda p: marginal_vs_conditional()),
}
