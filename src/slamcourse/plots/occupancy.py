"""Occupancy grids after log-odds updates.

A cell holds the log-odds ``l = log(p / (1 − p))`` of being occupied (0 = unknown, p = 0.5).
A beam from the robot to the cell it hit adds ``l_free`` (< 0) to every cell it crossed and
``l_occ`` (> 0) to the hit cell. Cells are shaded by p and also carry their value as text.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from slamcourse.plots.svg import document, el, fmt, num, text

CELL = 34.0


def probability(log_odds: float) -> float:
    """p = 1 / (1 + e^(−l)), the occupancy probability of log-odds ``l``."""
    return 1.0 / (1.0 + math.exp(-log_odds))


def beam_cells(a: tuple[int, int], b: tuple[int, int]) -> list[tuple[int, int]]:
    """Grid cells (col, row) on the segment from ``a`` to ``b`` (Bresenham), both included."""
    (x0, y0), (x1, y1) = a, b
    dx, dy = abs(x1 - x0), -abs(y1 - y0)
    step_x, step_y = (1 if x1 > x0 else -1), (1 if y1 > y0 else -1)
    err = dx + dy
    out = []
    while True:
        out.append((x0, y0))
        if (x0, y0) == (x1, y1):
            return out
        e2 = 2 * err
        if e2 >= dy:
            err += dy
            x0 += step_x
        if e2 <= dx:
            err += dx
            y0 += step_y


def update_grid(
    cols: int,
    rows: int,
    robot: tuple[int, int],
    hits: Sequence[tuple[int, int]],
    l_occ: float,
    l_free: float,
) -> list[list[float]]:
    """Log-odds grid (rows × cols, starting at 0) after one beam from ``robot`` to each hit."""
    grid = [[0.0] * cols for _ in range(rows)]
    for hit in hits:
        cells = beam_cells(robot, hit)
        for c, r in cells[1:-1]:
            grid[r][c] += l_free
        c, r = cells[-1]
        grid[r][c] += l_occ
    return grid


def _shade(log_odds: float) -> str:
    g = round(255 * (1.0 - probability(log_odds)))
    g = max(40, min(250, g))
    return f"#{g:02x}{g:02x}{g:02x}"


def _cell(x: float, y: float, value: float, *, hit: bool = False) -> list[str]:
    ink = "#fff" if probability(value) > 0.6 else "#111"
    out = [el("rect", x=x, y=y, width=CELL, height=CELL, fill=_shade(value), stroke="#888")]
    if hit:
        out.append(
            el(
                "rect",
                x=x + 2,
                y=y + 2,
                width=CELL - 4,
                height=CELL - 4,
                fill="none",
                stroke="#b3541e",
                stroke_width=2.0,
            )
        )
    out.append(
        text(
            x + CELL / 2,
            y + CELL / 2 + 4,
            fmt(value) if value else "0",
            text_anchor="middle",
            fill=ink,
            font_size="10",
        )
    )
    return out


def occupancy_grid(
    cols: int,
    rows: int,
    robot: tuple[int, int],
    hits: Sequence[tuple[int, int]],
    l_occ: float,
    l_free: float,
) -> str:
    """The grid after the beams, each cell shaded by p and labelled with its log-odds."""
    grid = update_grid(cols, rows, robot, hits, l_occ, l_free)
    w, h = max(cols * CELL + 40, 560.0), rows * CELL + 70
    body = [
        text(
            20,
            20,
            f"log-odds after {len(hits)} beams (l_occ = {num(l_occ)}, l_free = {num(l_free)})",
            fill="#222",
        )
    ]
    hitset = {tuple(hh) for hh in hits}
    for r in range(rows):
        for c in range(cols):
            body += _cell(20 + c * CELL, 30 + r * CELL, grid[r][c], hit=(c, r) in hitset)
    rc, rr = robot
    body.append(
        el(
            "circle",
            cx=20 + (rc + 0.5) * CELL,
            cy=30 + (rr + 0.5) * CELL,
            r=CELL / 3,
            fill="#1f6fb2",
            stroke="#fff",
            stroke_width=2.0,
        )
    )
    body.append(
        text(
            20,
            h - 12,
            "dark = likely occupied, light = likely free; circle = robot; framed = hit",
            fill="#333",
            font_size="11",
        )
    )
    occupied = sum(1 for row in grid for v in row if v > 0)
    free = sum(1 for row in grid for v in row if v < 0)
    desc = (
        f"A {cols} × {rows} grid, robot at column {rc}, row {rr}. After {len(hits)} beams "
        f"{occupied} cells have positive log-odds (hit, l_occ = {num(l_occ)} each time, "
        f"p = {num(probability(l_occ))} after one hit) and {free} cells negative "
        f"(crossed, l_free = {num(l_free)} each time)."
    )
    return document(w, h, "Occupancy grid after log-odds updates", desc, body)


def occupancy_ray(log_odds: Sequence[float], hit_index: int, l_occ: float, l_free: float) -> str:
    """One beam along a row of cells: the log-odds before and after the update."""
    before = [float(v) for v in log_odds]
    after = [
        v + (l_free if i < hit_index else l_occ if i == hit_index else 0.0)
        for i, v in enumerate(before)
    ]
    n = len(before)
    w, h = max(n * CELL + 120, 560.0), 2 * CELL + 70
    body = [text(20, 20, f"one beam hitting cell {hit_index}", fill="#222")]
    for row, (label, values) in enumerate((("before", before), ("after", after))):
        y = 34 + row * (CELL + 12)
        body.append(text(20, y + CELL / 2 + 4, label, fill="#222"))
        for i, v in enumerate(values):
            body += _cell(80 + i * CELL, y, v, hit=row == 1 and i == hit_index)
    body.append(
        text(
            80,
            h - 6,
            "cells before the hit add l_free; the hit cell adds l_occ; cells past it are unchanged",
            fill="#333",
            font_size="11",
        )
    )
    desc = (
        f"Log-odds before: {', '.join(num(v) for v in before)}. The beam crosses cells 0 to "
        f"{hit_index - 1} (each adds {num(l_free)}) and hits cell {hit_index} (adds {num(l_occ)}). "
        f"After: {', '.join(num(v) for v in after)}."
    )
    return document(w, h, "Log-odds update along one beam", desc, body)
