"""Drift: how odometry errors accumulate along a straight drive (plan view).

Three error models, each drawn from the exercise's own numbers:

- systematic: every step of ``step_length`` m is over-counted by ``bias`` m, so after ``steps``
  steps the believed position is ``steps · bias`` m ahead of the true one;
- random walk: every step adds an independent error of standard deviation ``sigma`` m on each
  axis; one seeded sample path is drawn with its 1σ circle of radius ``sigma · √steps`` m;
- heading bias: step ``k`` is driven ``heading_rate · k`` rad off the intended line, so the
  path curls away sideways.
"""

from __future__ import annotations

import math
import random

from slamcourse.plots.svg import document, el, fmt, num, polyline, text

W, H = 560.0, 300.0
LEFT, RIGHT, TOP, BOTTOM = 60.0, 20.0, 40.0, 50.0
MAX_POINTS = 400


def _every(steps: int) -> int:
    return max(1, math.ceil(steps / MAX_POINTS))


def heading_path(step_length: float, heading_rate: float, steps: int) -> list[tuple[float, float]]:
    """Positions (m) after each step when step ``k`` is driven at ``heading_rate · k`` rad."""
    x = y = 0.0
    out = [(x, y)]
    for k in range(1, steps + 1):
        x += step_length * math.cos(heading_rate * k)
        y += step_length * math.sin(heading_rate * k)
        out.append((x, y))
    return out


def random_walk_path(
    step_length: float, sigma: float, steps: int, seed: int
) -> list[tuple[float, float]]:
    """Positions (m) of one sample path: intended steps plus N(0, sigma²) noise on each axis."""
    rng = random.Random(f"drift:{seed}")
    x = y = 0.0
    out = [(x, y)]
    for _ in range(steps):
        x += step_length + rng.gauss(0.0, sigma)
        y += rng.gauss(0.0, sigma)
        out.append((x, y))
    return out


INSET = 96.0  # side of the close-up of the end, in px


def _sigma_inset(
    end: tuple[float, float], intended: tuple[float, float], r: float, colour: str
) -> list[str]:
    """A close-up of the end of the drive at one scale on both axes: the plan view stretches
    the sideways axis, where a circle would be drawn as a thin sliver, so the 1σ circle
    (radius ``r`` m about the intended end) and the sample's end are drawn here, true to shape."""
    x0, y0 = W - RIGHT - INSET, TOP
    cx, cy = x0 + INSET / 2, y0 + INSET / 2 + 6
    reach = max(r, math.hypot(end[0] - intended[0], end[1] - intended[1]), 1e-9) * 1.15
    scale = (INSET / 2 - 8) / reach
    ex, ey = cx + (end[0] - intended[0]) * scale, cy - (end[1] - intended[1]) * scale
    return [
        el("rect", x=x0, y=y0, width=INSET, height=INSET + 12, fill="#fff", stroke="#999"),
        text(x0 + 4, y0 + 12, "end, true scale", fill="#333", font_size="10"),
        el(
            "circle",
            cx=cx,
            cy=cy,
            r=r * scale,
            fill="none",
            stroke=colour,
            stroke_dasharray="3 2",
            stroke_width=1.5,
        ),
        el("circle", cx=cx, cy=cy, r=3.0, fill="#222"),
        el("circle", cx=ex, cy=ey, r=3.5, fill=colour),
        text(x0 + 4, y0 + INSET + 8, f"1σ = {num(r)} m", fill=colour, font_size="10"),
    ]


def drift_trajectories(
    steps: int,
    *,
    step_length: float = 1.0,
    bias: float | None = None,
    sigma: float | None = None,
    heading_rate: float | None = None,
    seed: int = 1,
) -> str:
    """Plan view of the intended straight drive and each given error model, as an SVG string.

    ``steps`` ≥ 1 steps of ``step_length`` m; ``bias`` (m per step), ``sigma`` (m per step, 1σ)
    and ``heading_rate`` (rad per step) each add one path when given.
    """
    steps = max(1, int(steps))
    length = steps * step_length
    series: list[tuple[str, list[tuple[float, float]], str, str]] = []
    facts: list[str] = []
    if heading_rate is not None:
        path = heading_path(step_length, heading_rate, steps)
        series.append(("heading bias", path, "#b3541e", "8 4"))
        facts.append(
            f"With a heading bias of {num(heading_rate)} rad per step the robot ends "
            f"{num(path[-1][1])} m to the side of the intended line."
        )
    if sigma is not None:
        path = random_walk_path(step_length, sigma, steps, seed)
        series.append(("random walk (one sample)", path, "#1f6fb2", "2 3"))
        facts.append(
            f"Random errors of {num(sigma)} m per step give a 1σ error of "
            f"{num(sigma * math.sqrt(steps))} m after {steps} steps (σ·√k), drawn as a circle "
            "about the intended end in a close-up at the same scale on both axes."
        )
    believed_end = None
    if bias is not None:
        believed_end = steps * (step_length + bias)
        facts.append(
            f"A systematic over-count of {num(bias)} m per step puts the believed position "
            f"{num(bias * steps)} m ahead of the true one after {steps} steps (b·k)."
        )

    xs = [0.0, length] + [p[0] for _, pts, _, _ in series for p in pts]
    ys = [0.0] + [p[1] for _, pts, _, _ in series for p in pts]
    if believed_end is not None:
        xs.append(believed_end)
    if sigma is not None:
        r = sigma * math.sqrt(steps)
        end = series[-1][1][-1] if series and series[-1][0].startswith("random") else (length, 0)
        ys += [end[1] - r, end[1] + r]
    xmin, xmax = min(xs), max(xs)
    ymin, ymax = min(ys), max(ys)
    span_y = max(ymax - ymin, 1e-9 + 0.05 * (xmax - xmin))
    ymin, ymax = ymin - 0.1 * span_y, ymax + 0.1 * span_y
    span_x = max(xmax - xmin, 1e-9)
    pw, ph = W - LEFT - RIGHT - (INSET + 12 if sigma is not None else 0), H - TOP - BOTTOM

    def sx(x: float) -> float:
        return LEFT + (x - xmin) / span_x * pw

    def sy(y: float) -> float:
        return TOP + (ymax - y) / (ymax - ymin) * ph

    body = [
        el("rect", x=LEFT, y=TOP, width=pw, height=ph, fill="#fbfbf8", stroke="#999"),
        text(LEFT, 20, "Plan view (sideways axis stretched to show the drift)", fill="#333"),
        text(LEFT + pw / 2, H - 12, "forward (m)", text_anchor="middle", fill="#333"),
        text(
            14,
            TOP + ph / 2,
            "sideways (m)",
            text_anchor="middle",
            fill="#333",
            transform=f"rotate(-90 14 {fmt(TOP + ph / 2)})",
        ),
        text(LEFT, TOP + ph + 16, num(xmin, 4), text_anchor="middle", fill="#333"),
        text(LEFT + pw, TOP + ph + 16, num(xmax, 4), text_anchor="end", fill="#333"),
        text(LEFT - 4, TOP + 4, num(ymax), text_anchor="end", fill="#333"),
        text(LEFT - 4, TOP + ph, num(ymin), text_anchor="end", fill="#333"),
        polyline([(sx(0), sy(0)), (sx(length), sy(0))], stroke="#222", stroke_width=2.0),
    ]
    legend = [("intended path", "#222", "")]
    for name, pts, colour, dash in series:
        every = _every(len(pts))
        shown = pts[::every] + ([pts[-1]] if (len(pts) - 1) % every else [])
        body.append(
            polyline(
                [(sx(x), sy(y)) for x, y in shown],
                stroke=colour,
                stroke_width=2.0,
                stroke_dasharray=dash,
            )
        )
        ex, ey = pts[-1]
        body.append(el("circle", cx=sx(ex), cy=sy(ey), r=4.0, fill=colour))
        legend.append((name, colour, dash))
        if name.startswith("random") and sigma is not None:
            body += _sigma_inset(pts[-1], (length, 0.0), sigma * math.sqrt(steps), colour)
    if believed_end is not None:
        y0 = sy(0)
        body += [
            el("circle", cx=sx(length), cy=y0, r=5.0, fill="#222"),
            el("rect", x=sx(believed_end) - 5, y=y0 - 5, width=10.0, height=10.0, fill="#7a3fa0"),
            text(sx(length), y0 + 20, "true end", text_anchor="end", fill="#222"),
            text(
                sx(believed_end),
                y0 - 10,
                f"believed (+{num(bias * steps if bias else 0)} m)",
                text_anchor="end",
                fill="#7a3fa0",
            ),
        ]
        legend.append(("systematic: believed end (square)", "#7a3fa0", ""))
    lx = LEFT + 8
    for i, (name, colour, dash) in enumerate(legend):
        ly = TOP + 14 + 16 * i
        body.append(
            polyline(
                [(lx, ly - 4), (lx + 24, ly - 4)],
                stroke=colour,
                stroke_width=2.0,
                stroke_dasharray=dash or None,
            )
        )
        body.append(text(lx + 30, ly, name, fill="#222"))
    desc = (
        f"The robot intends to drive {num(length)} m straight ahead in {steps} steps of "
        f"{num(step_length)} m. " + " ".join(facts)
    )
    return document(W, H, "Odometry drift along a straight drive", desc, body)
