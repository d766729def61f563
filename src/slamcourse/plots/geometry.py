"""Robot and landmark geometry of the observation model: range r and bearing φ.

The robot at (xr, yr) faces θ (rad, from the x axis, anticlockwise); the landmark is at (xj, yj)
(m). Range r = √(Δx² + Δy²); bearing φ = atan2(Δy, Δx) − θ, wrapped to (−π, π].
"""

from __future__ import annotations

import math

from slamcourse.plots.canvas import BLUE, GREEN, INK, ORANGE, Plane
from slamcourse.plots.svg import el, fmt, num, polyline

W, H = 440.0, 380.0
PAD = 60.0


def wrap(angle: float) -> float:
    """``angle`` (rad) wrapped to (−π, π]."""
    a = math.remainder(angle, 2 * math.pi)
    return math.pi if a == -math.pi else a


def observation_geometry(
    xr: float, yr: float, thr: float, xj: float, yj: float, *, show_results: bool = True
) -> str:
    """The robot (a triangle pointing along θ), the landmark, and the measured r and φ.

    ``show_results`` False labels r and φ with "?" (an exercise asking for them is open).
    Every label is placed where it covers neither the robot, the landmark, the lines nor
    another label (:class:`slamcourse.plots.canvas.Labels`)."""
    dx, dy = xj - xr, yj - yr
    r = math.hypot(dx, dy)
    phi = wrap(math.atan2(dy, dx) - thr)
    half = max(abs(dx), abs(dy), 1.0) * 0.5
    cx, cy = (xr + xj) / 2, (yr + yj) / 2
    plane = Plane([(cx - half, cy - half), (cx + half, cy + half)], width=W, height=H, pad=PAD)
    rx, ry = plane.px(xr, yr)
    lx, ly = plane.px(xj, yj)
    head = 0.45 * r * plane.scale if r > 0 else 40.0
    arc_r = min(40.0, 0.3 * r * plane.scale) if r > 0 else 20.0
    hx, hy = rx + head * math.cos(thr), ry - head * math.sin(thr)
    a0 = (rx + arc_r * math.cos(thr), ry - arc_r * math.sin(thr))
    a1 = (rx + arc_r * math.cos(thr + phi), ry - arc_r * math.sin(thr + phi))
    large = 1 if abs(phi) > math.pi else 0
    sweep = 0 if phi > 0 else 1  # SVG's y axis points down: anticlockwise is sweep 0
    mid = thr + phi / 2
    plane.body += [
        polyline([(rx, ry), (hx, hy)], stroke="#555", stroke_dasharray="6 4", stroke_width=1.5),
        polyline([(rx, ry), (lx, ly)], stroke=BLUE, stroke_width=2.0),
        el(
            "path",
            d=f"M{fmt(a0[0])},{fmt(a0[1])} A{fmt(arc_r)},{fmt(arc_r)} 0 {large} {sweep} "
            f"{fmt(a1[0])},{fmt(a1[1])}",
            fill="none",
            stroke=ORANGE,
            stroke_width=2.0,
        ),
    ]
    labels = plane.labels
    labels.block_segment((rx, ry), (hx, hy))
    labels.block_segment((rx, ry), (lx, ly))
    labels.block(a0[0], a0[1], 3)
    labels.block(a1[0], a1[1], 3)
    labels.block(rx + arc_r * math.cos(mid), ry - arc_r * math.sin(mid), 3)
    plane.pose(xr, yr, thr, colour=INK, size=14.0)
    plane.point(xj, yj, colour=GREEN, shape="diamond", size=8.0)
    # the most important labels first: they get the places nearest their marks
    labels.add(
        rx + (arc_r + 10) * math.cos(mid),
        ry - (arc_r + 10) * math.sin(mid),
        f"φ = {num(phi)} rad" if show_results else "φ = ?",
        colour=ORANGE,
        bold=True,
        gap=4,
    )
    labels.add(
        (rx + lx) / 2,
        (ry + ly) / 2,
        f"r = {num(r)} m" if show_results else "r = ?",
        colour=BLUE,
        bold=True,
        gap=8,
        prefer=("se", "nw", "sw", "ne", "e", "w", "s", "n"),
    )
    labels.add(lx, ly, f"landmark ({num(xj)}, {num(yj)})", colour=GREEN, gap=12)
    labels.add(
        rx,
        ry,
        f"robot ({num(xr)}, {num(yr)})",
        colour=INK,
        gap=18,
        prefer=("s", "sw", "se", "w", "e", "n", "nw", "ne"),
    )
    labels.add(hx, hy, "heading θ", colour="#555", gap=6)
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
    return plane.svg("Robot, landmark, range and bearing", desc)
