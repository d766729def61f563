"""Robot and landmark geometry of the observation model: range r and bearing φ.

The robot at (xr, yr) faces θ (rad, from the x axis, anticlockwise); the landmark is at (xj, yj)
(m). Range r = √(Δx² + Δy²); bearing φ = atan2(Δy, Δx) − θ, wrapped to (−π, π].
"""

from __future__ import annotations

import math

from slamcourse.plots.svg import document, el, fmt, num, polyline, text

W, H = 440.0, 380.0
PAD = 60.0


def wrap(angle: float) -> float:
    """``angle`` (rad) wrapped to (−π, π]."""
    a = math.remainder(angle, 2 * math.pi)
    return math.pi if a == -math.pi else a


def _side(x: float) -> str:
    """Text anchor that keeps a label near ``x`` (px) inside the picture."""
    return "start" if x < W / 3 else "end" if x > 2 * W / 3 else "middle"


def observation_geometry(
    xr: float, yr: float, thr: float, xj: float, yj: float, *, show_results: bool = True
) -> str:
    """The robot (a triangle pointing along θ), the landmark, and the measured r and φ.

    ``show_results`` False labels r and φ with "?" (an exercise asking for them is open)."""
    dx, dy = xj - xr, yj - yr
    r = math.hypot(dx, dy)
    phi = wrap(math.atan2(dy, dx) - thr)
    half = max(abs(dx), abs(dy), 1.0) * 0.5  # half the extent of the scene (m)
    cx, cy = (xr + xj) / 2, (yr + yj) / 2
    scale = (min(W, H) / 2 - PAD) / half

    def sx(x: float) -> float:
        return W / 2 + (x - cx) * scale

    def sy(y: float) -> float:
        return H / 2 - (y - cy) * scale

    rx, ry = sx(xr), sy(yr)
    bearing = math.atan2(dy, dx)  # world angle of the robot → landmark line
    size = 14.0
    tri = [
        (rx + size * math.cos(thr), ry - size * math.sin(thr)),
        (rx + size * 0.7 * math.cos(thr + 2.5), ry - size * 0.7 * math.sin(thr + 2.5)),
        (rx + size * 0.7 * math.cos(thr - 2.5), ry - size * 0.7 * math.sin(thr - 2.5)),
    ]
    head = 0.45 * r * scale if r > 0 else 40.0
    arc_r = min(40.0, 0.3 * r * scale) if r > 0 else 20.0
    start = thr
    end = thr + phi
    a0 = (rx + arc_r * math.cos(start), ry - arc_r * math.sin(start))
    a1 = (rx + arc_r * math.cos(end), ry - arc_r * math.sin(end))
    large = 1 if abs(phi) > math.pi else 0
    sweep = 0 if phi > 0 else 1  # SVG's y axis points down: anticlockwise is sweep 0
    mid = thr + phi / 2
    body = [
        el("rect", x=0.0, y=0.0, width=W, height=H, fill="#fbfbf8"),
        polyline(
            [(rx, ry), (rx + head * math.cos(thr), ry - head * math.sin(thr))],
            stroke="#555",
            stroke_dasharray="6 4",
            stroke_width=1.5,
        ),
        text(
            rx + (head + 6) * math.cos(thr),
            ry - (head + 6) * math.sin(thr),
            "heading θ",
            fill="#555",
        ),
        polyline([(rx, ry), (sx(xj), sy(yj))], stroke="#1f6fb2", stroke_width=2.0),
        text(
            (rx + sx(xj)) / 2 + 10 * math.sin(bearing),
            (ry + sy(yj)) / 2 + 10 * math.cos(bearing),
            f"r = {num(r)} m" if show_results else "r = ?",
            fill="#1f6fb2",
            font_weight="bold",
        ),
        el(
            "path",
            d=f"M{fmt(a0[0])},{fmt(a0[1])} A{fmt(arc_r)},{fmt(arc_r)} 0 {large} {sweep} "
            f"{fmt(a1[0])},{fmt(a1[1])}",
            fill="none",
            stroke="#b3541e",
            stroke_width=2.0,
        ),
        text(
            rx + (arc_r + 16) * math.cos(mid),
            ry - (arc_r + 16) * math.sin(mid),
            f"φ = {num(phi)} rad" if show_results else "φ = ?",
            fill="#b3541e",
            font_weight="bold",
            text_anchor="start" if math.cos(mid) >= 0 else "end",
        ),
        el("polygon", points=" ".join(f"{fmt(x)},{fmt(y)}" for x, y in tri), fill="#222"),
        text(rx, ry + 24, f"robot ({num(xr)}, {num(yr)})", fill="#222", text_anchor=_side(rx)),
        el(
            "rect",
            x=sx(xj) - 6,
            y=sy(yj) - 6,
            width=12.0,
            height=12.0,
            fill="#2e7d32",
            transform=f"rotate(45 {fmt(sx(xj))} {fmt(sy(yj))})",
        ),
        text(
            sx(xj),
            sy(yj) - 12,
            f"landmark ({num(xj)}, {num(yj)})",
            fill="#2e7d32",
            text_anchor=_side(sx(xj)),
        ),
    ]
    desc = (
        f"The robot at ({num(xr)}, {num(yr)}) m faces {num(thr)} rad. The landmark is at "
        f"({num(xj)}, {num(yj)}) m. "
        + (
            f"It is Δx = {num(dx)} m, Δy = {num(dy)} m away: range r = {num(r)} m and bearing "
            f"φ = {num(phi)} rad relative to the heading."
            if show_results
            else "The range r and the bearing φ are marked but not given."
        )
    )
    return document(W, H, "Robot, landmark, range and bearing", desc, body)
