"""Chapter ``occupancy``: beams through a grid, and the log-odds curve."""

from __future__ import annotations

from slamcourse.plots.canvas import BLUE, ORANGE, Chart
from slamcourse.plots.occupancy import occupancy_grid
from slamcourse.plots.picture import Figure, Picture, answer
from slamcourse.plots.svg import num
from slamcourse.slam.occupancy import log_odds, probability

BEAMS = [(7, 1), (7, 3), (6, 5), (3, 5), (7, 2)]


def log_odds_curve(marks: tuple[float, ...] = (0.3, 0.7, 0.9)) -> str:
    """p against l = log(p / (1 − p)), with a few sensor probabilities marked."""
    chart = Chart((-5.0, 5.0), (0.0, 1.0), x_label="log-odds l", y_label="probability p")
    chart.line([(x / 10, probability(x / 10)) for x in range(-50, 51)], colour=BLUE)
    chart.hline(0.5)
    chart.points([(log_odds(p), p) for p in marks], colour=ORANGE, shape="diamond", size=5)
    facts = ", ".join(f"p = {num(p)} is l = {num(log_odds(p))}" for p in marks)
    desc = (
        "The logistic curve p = 1 / (1 + e^(−l)) from l = −5 to 5: l = 0 is p = 0.5 (unknown), "
        f"and the curve flattens towards 0 and 1, so evidence adds in l without ever reaching "
        f"certainty. Marked: {facts}."
    )
    return chart.svg(
        "Probability against log-odds",
        desc,
        [("p(l)", BLUE, ""), ("sensor models", ORANGE, "marker:diamond")],
    )


def _grid(l_occ: float, l_free: float) -> str:
    return occupancy_grid(8, 6, (1, 3), BEAMS, l_occ, l_free)


FIGURES: dict[str, Figure] = {
    "occupancy/beams-through-grid": lambda: _grid(log_odds(0.85), log_odds(0.3)),
    "occupancy/log-odds-curve": log_odds_curve,
}

PICTURES: dict[str, Picture] = {
    "occupancy/readings-needed": answer(
        lambda p: log_odds_curve((float(p["sensor_prob"]), float(p["target"])))
    ),
}
