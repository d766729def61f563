"""Chapter ``capstone``: one frame's time budget, stage by stage."""

from __future__ import annotations

from collections.abc import Sequence

from slamcourse.plots.canvas import INK, MUTED, RED
from slamcourse.plots.picture import Figure, Params, Picture, answer
from slamcourse.plots.svg import document, el, num, polyline, text
from slamcourse.slam.capstone import frame_budget, frame_headroom

COLOURS = ("#1f4e79", "#9cc3e6", "#2e7d32", "#c9e3c0", "#b3541e", "#f3d9c4")


def frame_budget_chart(rate_hz: float, stages: Sequence[tuple[str, float]]) -> str:
    """The stages (name, ms) of one frame stacked along a bar, against the budget 1000/rate ms."""
    budget_ms = frame_budget(rate_hz)  # ms
    used, spare = frame_headroom(rate_hz, [ms for _, ms in stages])
    total = max(budget_ms, sum(ms for _, ms in stages))
    x0, width = 40.0, 480.0
    scale = width / total
    body = [
        text(
            x0,
            24,
            f"one frame at {num(rate_hz)} Hz: {num(budget_ms)} ms",
            fill=INK,
            font_weight="bold",
        )
    ]
    at = x0
    for k, (name, ms) in enumerate(stages):
        w = ms * scale
        body.append(
            el(
                "rect",
                x=at,
                y=50.0,
                width=max(w, 1.0),
                height=40.0,
                fill=COLOURS[k % len(COLOURS)],
                stroke="#fff",
            )
        )
        row = 118 + 16 * k
        body.append(
            polyline([(at + w / 2, 90), (at + w / 2, row - 4)], stroke=MUTED, stroke_width=0.8)
        )
        body.append(text(at + w / 2 + 4, row, f"{name}: {num(ms)} ms", fill=INK, font_size="11"))
        at += w
    bx = x0 + budget_ms * scale
    body.append(
        polyline([(bx, 40), (bx, 100)], stroke=RED, stroke_width=2.0, stroke_dasharray="6 3")
    )
    body.append(text(bx - 4, 38, "budget", fill=RED, text_anchor="end", font_size="11"))
    height = 118 + 16 * len(stages) + 10
    desc = (
        f"At {num(rate_hz)} Hz a frame has {num(budget_ms)} ms. The stages take "
        + ", ".join(f"{name} {num(ms)} ms" for name, ms in stages)
        + f": {num(used)} ms in all, leaving {num(spare)} ms"
        + (" (over budget)." if spare < 0 else " spare.")
    )
    return document(x0 + width + 40, height, "Where one frame's time goes", desc, body)


def _stages(p: Params) -> list[tuple[str, float]]:
    return [
        ("odometry", float(p["t_odometry"])),
        ("features", float(p["t_features"])),
        ("association", float(p["t_association"])),
        ("loop closure", float(p["t_loop"])),
        ("optimisation", float(p["t_optimise"])),
        ("map update", float(p["t_map"])),
    ]


# other numbers than the time-budget exercise's, whose answer this would be
LESSON = {
    "rate_hz": 15,
    "t_odometry": 1,
    "t_features": 12,
    "t_association": 6,
    "t_loop": 8,
    "t_optimise": 25,
    "t_map": 10,
}

FIGURES: dict[str, Figure] = {
    "capstone/frame-budget": lambda: frame_budget_chart(LESSON["rate_hz"], _stages(LESSON)),
}

PICTURES: dict[str, Picture] = {
    "capstone/time-budget": answer(lambda p: frame_budget_chart(float(p["rate_hz"]), _stages(p))),
}
