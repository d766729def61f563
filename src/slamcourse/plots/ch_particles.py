"""Figures and pictures of chapter ``particles``: sampled clouds, resampling, depletion.

Everything is drawn from :mod:`slamcourse.slam.particles` with fixed seeds, so the same numbers
give the same SVG.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from slamcourse.plots.picture import Figure, Params, Picture, given
from slamcourse.plots.svg import document, el, fmt, num, polyline, text
from slamcourse.slam import particles as pf

W, H = 560.0, 320.0
LEFT, RIGHT, TOP, BOTTOM = 56.0, 20.0, 40.0, 46.0
COLOURS = ("#1f6fb2", "#b3541e", "#2e8540", "#7a3fa0")

# --- the chapter's numbers ------------------------------------------------------------------------

CLOUD_ALPHAS = (0.05, 0.03, 0.002, 0.0005)
CLOUD_U = (0.0, 1.0, 0.0)
CLOUD_STEPS = 4
CLOUD_N = 250
DEPLETION_N = 50
DEPLETION_STEPS = 40


def cloud_steps(
    steps: int = CLOUD_STEPS,
    n: int = CLOUD_N,
    u: Sequence[float] = CLOUD_U,
    alphas: Sequence[float] = CLOUD_ALPHAS,
    seed: int = 23,
) -> list[np.ndarray]:
    """The particle set after each of ``steps`` identical odometry readings (no observations),
    every particle moved by its own noisy controls."""
    rng = np.random.default_rng(seed)
    particles = np.zeros((n, 3))
    out = []
    for _ in range(steps):
        particles = np.array([pf.sample_motion(p, u, alphas, 1, rng)[0] for p in particles])
        out.append(particles.copy())
    return out


def distinct_ancestors(n: int, steps: int, method: str, seed: int = 7) -> list[int]:
    """How many of the ``n`` original particles still have descendants after each of ``steps``
    resamplings with equal weights (observations that tell the particles nothing)."""
    rng = np.random.default_rng(seed)
    ancestors = np.arange(n)
    weights = np.ones(n)
    counts = []
    for _ in range(steps):
        if method == "multinomial":
            idx = pf.multinomial_resample(weights, rng)
        else:
            idx = pf.low_variance_resample(weights, float(rng.uniform()))
        ancestors = ancestors[idx]
        counts.append(len(set(ancestors.tolist())))
    return counts


# --- drawing helpers ------------------------------------------------------------------------------


def _frame(pw: float, ph: float, xlabel: str, ylabel: str) -> list[str]:
    return [
        el("rect", x=LEFT, y=TOP, width=pw, height=ph, fill="#fbfbf8", stroke="#999"),
        text(LEFT + pw / 2, H - 10, xlabel, text_anchor="middle", fill="#333"),
        text(
            14,
            TOP + ph / 2,
            ylabel,
            text_anchor="middle",
            fill="#333",
            transform=f"rotate(-90 14 {fmt(TOP + ph / 2)})",
        ),
    ]


def particle_cloud() -> str:
    """Plan view of the particle set after each odometry step: the banana of the motion model."""
    clouds = cloud_steps()
    pts = np.vstack([np.zeros((1, 3)), *clouds])
    xmin, xmax = float(pts[:, 0].min()) - 0.2, float(pts[:, 0].max()) + 0.2
    ymin, ymax = float(pts[:, 1].min()) - 0.2, float(pts[:, 1].max()) + 0.2
    pw, ph = W - LEFT - RIGHT - 90, H - TOP - BOTTOM
    scale = min(pw / (xmax - xmin), ph / (ymax - ymin))  # one scale on both axes
    pw, ph = (xmax - xmin) * scale, (ymax - ymin) * scale

    def sx(x: float) -> float:
        return LEFT + (x - xmin) * scale

    def sy(y: float) -> float:
        return TOP + (ymax - y) * scale

    body = _frame(pw, ph, "x (m)", "y (m)")
    body += [
        text(LEFT, 22, "Particles after each odometry step (same scale on both axes)"),
        text(LEFT, TOP + ph + 14, num(xmin), text_anchor="middle", fill="#333"),
        text(LEFT + pw, TOP + ph + 14, num(xmax), text_anchor="middle", fill="#333"),
        text(LEFT - 4, TOP + 4, num(ymax), text_anchor="end", fill="#333"),
        text(LEFT - 4, TOP + ph, num(ymin), text_anchor="end", fill="#333"),
    ]
    for k, cloud in enumerate(clouds):
        colour = COLOURS[k % len(COLOURS)]
        for x, y, _ in cloud:
            body.append(el("circle", cx=sx(float(x)), cy=sy(float(y)), r=1.4, fill=colour))
        ly = TOP + 12 + 18 * k
        body.append(el("circle", cx=LEFT + pw + 16, cy=ly - 4, r=4.0, fill=colour))
        body.append(text(LEFT + pw + 26, ly, f"step {k + 1}", fill=colour))
    noise_free = [(0.0, 0.0)]
    pose = np.zeros(3)
    for _ in clouds:
        pose = pf.move(pose, CLOUD_U)
        noise_free.append((float(pose[0]), float(pose[1])))
    body.append(
        polyline([(sx(x), sy(y)) for x, y in noise_free], stroke="#222", stroke_dasharray="5 3")
    )
    for x, y in noise_free:
        body.append(el("circle", cx=sx(x), cy=sy(y), r=3.0, fill="#222"))
    body.append(text(LEFT + pw + 16, TOP + 12 + 18 * len(clouds), "● noise-free", fill="#222"))
    last = clouds[-1]
    along = float(last[:, 0].std())
    across = float(last[:, 1].std())
    behind = noise_free[-1][0] - float(last[:, 0].mean())
    desc = (
        f"{CLOUD_N} particles start at the origin facing along x and are moved "
        f"{CLOUD_STEPS} times by the odometry reading turn {num(CLOUD_U[0])} rad, drive "
        f"{num(CLOUD_U[1])} m, turn {num(CLOUD_U[2])} rad, each particle with its own noise "
        f"(alphas {', '.join(num(a) for a in CLOUD_ALPHAS)}). The clouds after steps 1 to "
        f"{CLOUD_STEPS} are drawn in four colours, the noise-free positions as black dots on a "
        f"dashed line. The clouds grow with every step and bend into bananas: heading noise "
        f"moves a particle along an arc, not along a straight line. After step {CLOUD_STEPS} "
        f"the cloud's standard deviation is {num(along)} m along the drive and "
        f"{num(across)} m across it, and its mean lies {num(behind)} m short of the noise-free "
        f"end, inside the bend."
    )
    return document(W, H, "Sampling the odometry motion model", desc, body)


def depletion() -> str:
    """Distinct ancestors left after repeated resampling with equal weights."""
    multi = distinct_ancestors(DEPLETION_N, DEPLETION_STEPS, "multinomial")
    low = distinct_ancestors(DEPLETION_N, DEPLETION_STEPS, "low-variance")
    pw, ph = W - LEFT - RIGHT - 150, H - TOP - BOTTOM

    def sx(k: float) -> float:
        return LEFT + k / DEPLETION_STEPS * pw

    def sy(v: float) -> float:
        return TOP + (1 - v / DEPLETION_N) * ph

    body = _frame(pw, ph, "resampling steps", "distinct ancestors")
    body.append(text(LEFT, 22, f"{DEPLETION_N} particles, equal weights, resampled every step"))
    for v in (0, DEPLETION_N // 2, DEPLETION_N):
        body.append(text(LEFT - 4, sy(v) + 4, str(v), text_anchor="end", fill="#333"))
    for k in (0, DEPLETION_STEPS // 2, DEPLETION_STEPS):
        body.append(text(sx(k), TOP + ph + 14, str(k), text_anchor="middle", fill="#333"))
    series = [
        ("low-variance", low, COLOURS[0], ""),
        ("multinomial", multi, COLOURS[1], "6 3"),
    ]
    for i, (name, counts, colour, dash) in enumerate(series):
        pts = [(sx(0), sy(DEPLETION_N))] + [(sx(k + 1), sy(c)) for k, c in enumerate(counts)]
        body.append(polyline(pts, stroke=colour, stroke_width=2.0, stroke_dasharray=dash or None))
        ly = TOP + 16 + 20 * i
        body.append(
            polyline(
                [(LEFT + pw + 12, ly - 4), (LEFT + pw + 40, ly - 4)],
                stroke=colour,
                stroke_width=2.0,
                stroke_dasharray=dash or None,
            )
        )
        body.append(text(LEFT + pw + 46, ly, name, fill=colour))
    desc = (
        f"{DEPLETION_N} equally weighted particles are resampled {DEPLETION_STEPS} times, as if "
        f"every observation fitted all of them equally well. Low-variance resampling keeps every "
        f"particle exactly once, so all {low[-1]} ancestors survive (solid line). Multinomial "
        f"resampling draws copies at random: after one step {multi[0]} of {DEPLETION_N} "
        f"particles have descendants, after 10 steps {multi[9]}, and after "
        f"{DEPLETION_STEPS} steps {multi[-1]} (dashed line). Diversity lost this way never "
        "comes back."
    )
    return document(W, H, "Particle depletion under repeated resampling", desc, body)


def resampling_bars(weights: Sequence[float], u: float) -> str:
    """Each particle's expected number of copies N·w̄ and the copies low-variance resampling
    with ``u`` gives it (the givens of ``low-variance-resample``'s example)."""
    w = pf.normalise(weights)
    n = len(w)
    kept = pf.copies(pf.low_variance_resample(w, u), n)
    pw, ph = W - LEFT - RIGHT, H - TOP - BOTTOM
    top = max(float(n * w.max()), float(kept.max()), 1.0) * 1.15
    band = pw / n

    def sy(v: float) -> float:
        return TOP + (1 - v / top) * ph

    body = _frame(pw, ph, "particle index", "copies")
    body.append(text(LEFT, 22, f"Expected copies N·w of each of {n} particles"))
    thresholds = [(u + m) / n for m in range(n)]
    cum = np.cumsum(w)
    for i in range(n):
        x0 = LEFT + i * band
        body.append(
            el(
                "rect",
                x=x0 + band * 0.2,
                y=sy(float(n * w[i])),
                width=band * 0.6,
                height=sy(0) - sy(float(n * w[i])),
                fill="#cfdff0",
                stroke=COLOURS[0],
            )
        )
        body.append(text(x0 + band / 2, TOP + ph + 14, str(i), text_anchor="middle"))
        body.append(
            text(x0 + band / 2, sy(float(n * w[i])) - 4, f"N·w = {num(float(n * w[i]))}",
                 text_anchor="middle", font_size="10", fill="#333")
        )  # fmt: skip
    desc = (
        f"{n} particles with normalised weights {', '.join(num(float(v)) for v in w)} "
        f"(cumulative {', '.join(num(float(c)) for c in cum)}). Bars show each particle's "
        f"expected number of copies, N times its weight. Low-variance resampling with "
        f"u = {num(u)} uses the thresholds {', '.join(num(t) for t in thresholds)}."
    )
    return document(W, H, "Expected copies of each particle", desc, body)


def motion_givens(params: Params) -> str:
    """The givens of ``sample-motion``'s first example: the cloud the learner should draw is not
    shown, only where the noise-free motion goes."""
    return particle_cloud_for((0.0, 0.0, 0.0), (0.3, 1.0, -0.2))


def particle_cloud_for(pose: Sequence[float], u: Sequence[float]) -> str:
    """The start pose and the noise-free end of one odometry step (plan view)."""
    end = pf.move(pose, u)
    pts = [(float(pose[0]), float(pose[1])), (float(end[0]), float(end[1]))]
    xmin = min(p[0] for p in pts) - 0.5
    xmax = max(p[0] for p in pts) + 0.5
    ymin = min(p[1] for p in pts) - 0.5
    ymax = max(p[1] for p in pts) + 0.5
    pw, ph = W - LEFT - RIGHT, H - TOP - BOTTOM
    scale = min(pw / (xmax - xmin), ph / (ymax - ymin))

    def sx(x: float) -> float:
        return LEFT + (x - xmin) * scale

    def sy(y: float) -> float:
        return TOP + (ymax - y) * scale

    body = _frame(pw, ph, "x (m)", "y (m)")
    body += [
        text(LEFT, 22, "One odometry step: your samples should scatter around its end"),
        el("circle", cx=sx(pts[0][0]), cy=sy(pts[0][1]), r=5.0, fill="#222"),
        text(sx(pts[0][0]), sy(pts[0][1]) + 18, "start", text_anchor="middle"),
        polyline([(sx(x), sy(y)) for x, y in pts], stroke="#222", stroke_dasharray="5 3"),
        el("circle", cx=sx(pts[1][0]), cy=sy(pts[1][1]), r=5.0, fill=COLOURS[0]),
        text(sx(pts[1][0]) + 8, sy(pts[1][1]) - 8, "noise-free end", fill=COLOURS[0]),
    ]
    desc = (
        f"The robot starts at ({num(float(pose[0]))}, {num(float(pose[1]))}) facing "
        f"{num(float(pose[2]))} rad, turns {num(float(u[0]))} rad, drives {num(float(u[1]))} m "
        f"and turns {num(float(u[2]))} rad, ending without noise at ({num(pts[1][0])}, "
        f"{num(pts[1][1])}) facing {num(float(end[2]))} rad. The samples the exercise asks for "
        "are not drawn."
    )
    return document(W, H, "The motion the samples are drawn around", desc, body)


FIGURES: dict[str, Figure] = {
    "particles/cloud": particle_cloud,
    "particles/ancestors": depletion,
}

PICTURES: dict[str, Picture] = {
    "particles/low-variance-resample": given(lambda p: resampling_bars([0.1, 0.4, 0.3, 0.2], 0.5)),
    "particles/sample-motion": given(motion_givens),
}
