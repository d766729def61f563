"""Chapter ``consistency``: the average NEES of a filter against its χ² band, and one NEES as
an ellipse test."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from slamcourse.plots.canvas import BLUE, GREEN, INK, ORANGE, Chart, Plane
from slamcourse.plots.picture import Figure, Picture, answer, given
from slamcourse.plots.svg import num
from slamcourse.slam.consistency import average_band, nees, simulate_anees


def nees_band_figure(runs: int = 50, steps: int = 40, scales: Sequence[float] = (1.0, 0.1)) -> str:
    """Average NEES per step of the chapter's 1-D constant-velocity filter (2 dof) over ``runs``
    runs, for each process-noise scale, against the 95% band of the average."""
    low, high = average_band(2, runs, 0.95)
    series = [(s, simulate_anees(s, runs=runs, steps=steps)) for s in scales]
    top = max(high * 1.3, max(float(a.max()) for _, a in series) * 1.45)
    chart = Chart((0.0, float(steps)), (0.0, top), x_label="time step", y_label="average NEES")
    chart.band(low, high)
    chart.hline(2.0, colour=INK, dash="2 3")
    legend = [
        (f"95% band [{num(low)}, {num(high)}]", GREEN, "marker:square"),
        ("expected value 2", INK, "2 3"),
    ]
    facts = []
    for (scale, anees), colour, dash in zip(series, (BLUE, ORANGE), ("", "6 4"), strict=False):
        chart.line(
            [(k + 1.0, float(v)) for k, v in enumerate(anees)], colour=colour, dash=dash or None
        )
        name = "consistent (q as simulated)" if scale == 1 else f"q scaled by {num(scale)}"
        legend.append((name, colour, dash))
        outside = int(np.sum((anees < low) | (anees > high)))
        facts.append(
            f"with the filter's process noise {name}, the average NEES is "
            f"{num(float(anees.mean()))} over the run and {outside} of {steps} steps "
            "fall outside the band"
        )
    desc = (
        f"The average NEES over {runs} runs of a 1-D constant-velocity Kalman filter (state of "
        f"2: position and velocity), step by step, against the 95% band of an average of {runs} "
        f"χ²₂ values, [{num(low)}, {num(high)}]: " + "; ".join(facts) + "."
    )
    return chart.svg("Average NEES against its band", desc, legend)


def nees_ellipse(
    truth: Sequence[float],
    estimate: Sequence[float],
    P: Sequence[Sequence[float]],
    *,
    show_results: bool = True,
) -> str:
    """The estimate, its 1σ and 2σ ellipses and the true position; the NEES when shown."""
    value = nees(truth, estimate, P)
    pts = [(float(truth[0]), float(truth[1])), (float(estimate[0]), float(estimate[1]))]
    Pm = np.asarray(P, float)
    r = 2.2 * float(np.sqrt(max(np.linalg.eigvalsh(Pm))))
    pts += [(estimate[0] - r, estimate[1] - r), (estimate[0] + r, estimate[1] + r)]
    plane = Plane(pts, width=440, height=360, pad=30, grid=0.5)
    plane.ellipse(estimate[0], estimate[1], Pm, k=1.0, colour=BLUE, dash="4 3")
    plane.ellipse(estimate[0], estimate[1], Pm, k=2.0, colour=BLUE)
    plane.point(estimate[0], estimate[1], colour=BLUE, shape="cross", label="estimate x̂")
    plane.point(truth[0], truth[1], colour=GREEN, shape="star", size=8, label="truth x")
    text = f"NEES = {num(value)}" if show_results else "NEES = ?"
    plane.label(
        estimate[0], estimate[1] - r * 0.9, text, colour=ORANGE, bold=True, prefer=("s", "se", "sw")
    )
    desc = (
        f"The estimate ({num(estimate[0])}, {num(estimate[1])}) m with its 1σ (dashed) and 2σ "
        f"ellipses, and the true position ({num(truth[0])}, {num(truth[1])}) m. "
        + (
            f"The NEES, the squared Mahalanobis distance of the error, is {num(value)}."
            if show_results
            else "The NEES is asked."
        )
    )
    return plane.svg("One NEES: the error measured by the ellipse", desc)


def band_chart(dof: int, runs: int, confidence: float, average: float | None = None) -> str:
    low, high = average_band(dof, runs, confidence)
    top = max(high, average or 0) * 1.4
    chart = Chart((0.0, 1.0), (0.0, top), x_label="", y_label="average NEES", width=300)
    chart.band(low, high)
    chart.hline(float(dof), colour=INK, dash="2 3")
    legend = [(f"band [{num(low)}, {num(high)}]", GREEN, "marker:square")]
    if average is not None:
        chart.points([(0.5, average)], colour=ORANGE, shape="diamond", size=6)
        legend.append((f"ANEES {num(average)}", ORANGE, "marker:diamond"))
    desc = (
        f"The {num(100 * confidence)}% band of an average of {runs} χ² values with {dof} "
        f"degrees of freedom: [{num(low)}, {num(high)}] around {dof}."
        + (f" The filter's average NEES, {num(average)}, is marked." if average else "")
    )
    return chart.svg("The band of the average NEES", desc, legend)


FIGURES: dict[str, Figure] = {
    "consistency/nees-over-time": nees_band_figure,
}

PICTURES: dict[str, Picture] = {
    "consistency/nees-value": Picture(
        lambda p, shown: nees_ellipse(
            [float(p["xt"]), float(p["yt"])],
            [float(p["xh"]), float(p["yh"])],
            [[float(p["pxx"]), float(p["pxy"])], [float(p["pxy"]), float(p["pyy"])]],
            show_results=shown,
        )
    ),
    "consistency/nees": given(
        lambda p: nees_ellipse(
            [1.0, 2.0], [1.1, 1.9], [[0.04, 0.01], [0.01, 0.04]], show_results=False
        )
    ),
    "consistency/anees-band": answer(
        lambda p: band_chart(int(p["dof"]), int(p["runs"]), float(p["confidence"]))
    ),
    "consistency/diagnose": answer(
        lambda p: band_chart(int(p["dof"]), int(p["runs"]), 0.95, float(p["anees"]))
    ),
}
