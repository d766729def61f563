"""Chapter ``association``: the gate as an ellipse, and the chi-square curve behind it."""

from __future__ import annotations

import math
from collections.abc import Sequence

from slamcourse.plots.canvas import BLUE, GREEN, INK, MUTED, ORANGE, RED, Chart, Plane
from slamcourse.plots.picture import Figure, Params, Picture, answer, given
from slamcourse.plots.svg import num
from slamcourse.slam.association import chi2_cdf, chi2_quantile, mahalanobis_squared

SHAPES = ("circle", "square", "diamond", "star")
COLOURS = (BLUE, ORANGE, GREEN, RED)


def gate_ellipse(
    s00: float,
    s11: float,
    innovations: Sequence[tuple[str, float, float]],
    *,
    confidence: float = 0.95,
    show_results: bool = True,
    axes: tuple[str, str] = ("range", "bearing"),
    units: tuple[str, str] = ("m", "rad"),
) -> str:
    """Innovation space: the predicted measurement at the origin, its 1σ and 2σ ellipses of
    S = diag(s00, s11) and the gate d² < χ²(confidence, 2), with each named innovation and its
    d² ("?" when ``show_results`` is False)."""
    gate = chi2_quantile(confidence, 2)
    k = math.sqrt(gate)
    pts = [
        (0.0, 0.0),
        (k * math.sqrt(s00), k * math.sqrt(s11)),
        (-k * math.sqrt(s00), -k * math.sqrt(s11)),
    ]
    pts += [(a, b) for _, a, b in innovations]
    plane = Plane(pts, width=520, height=380, pad=46, top=20)
    cov = [[s00, 0.0], [0.0, s11]]
    plane.ellipse(0, 0, cov, k=1.0, colour=MUTED, dash="2 3")
    plane.ellipse(0, 0, cov, k=2.0, colour=MUTED, dash="2 3")
    plane.ellipse(0, 0, cov, k=k, colour=BLUE, fill=BLUE)
    plane.point(0, 0, colour=INK, shape="cross", label="predicted ẑ")
    facts = []
    for i, (name, a, b) in enumerate(innovations):
        d2 = mahalanobis_squared([a, b], cov)
        inside = d2 < gate
        plane.segment((0, 0), (a, b), colour=COLOURS[i % 4], dash="4 3", arrow=True)
        shown = f"d² = {num(d2)}" if show_results else "d² = ?"
        plane.point(a, b, colour=COLOURS[i % 4], shape=SHAPES[i % 4], label=f"{name}: {shown}")
        if show_results:
            facts.append(
                f"{name} at ν = ({num(a)} {units[0]}, {num(b)} {units[1]}) has d² = {num(d2)}, "
                + ("inside" if inside else "outside")
                + " the gate."
            )
        else:
            facts.append(f"{name} at ν = ({num(a)} {units[0]}, {num(b)} {units[1]}).")
    plane.label(
        0,
        -k * math.sqrt(s11),
        f"gate d² < {num(gate)}",
        colour=BLUE,
        bold=True,
        prefer=("s", "se", "sw", "n"),
    )
    desc = (
        f"Innovation space, {axes[0]} error ({units[0]}) across and {axes[1]} error "
        f"({units[1]}) up, drawn to the same scale. With S = diag({num(s00)}, {num(s11)}) the "
        f"1σ and 2σ ellipses are dotted and the {num(100 * confidence)}% gate, "
        f"d² < {num(gate)}, is the shaded ellipse: a long thin shape, because a metre of range "
        "error is far more plausible than a radian of bearing error. " + " ".join(facts)
    )
    legend = [("1σ and 2σ", MUTED, "2 3"), (f"{num(100 * confidence)}% gate", BLUE, "")]
    return plane.svg("The gate as an ellipse in innovation space", desc, legend)


def chi2_density(x: float, dof: int) -> float:
    """The chi-square probability density with ``dof`` degrees of freedom at ``x`` > 0."""
    half = dof / 2
    return math.exp((half - 1) * math.log(x) - x / 2 - half * math.log(2) - math.lgamma(half))


def chi2_curve(
    dof: int,
    *,
    confidence: float | None = None,
    mark: float | None = None,
    show_results: bool = True,
) -> str:
    """The χ² density of ``dof`` degrees of freedom, with its ``confidence`` quantile (the gate)
    and a value ``mark`` (a d²), whose tail probability is written when ``show_results``."""
    gate = chi2_quantile(confidence, dof) if confidence is not None else None
    hi = max(chi2_quantile(0.995, dof), (mark or 0) * 1.1, (gate or 0) * 1.1)
    xs = [hi * (i + 0.5) / 200 for i in range(200)]
    ys = [min(chi2_density(x, dof), 1.0) for x in xs]
    top = max(ys) * 1.1
    chart = Chart(
        (0.0, hi), (0.0, top), x_label="d² (squared Mahalanobis distance)", y_label="density"
    )
    chart.line(list(zip(xs, ys, strict=True)), colour=BLUE)
    facts = [f"The chi-square density with {dof} degree{'s' if dof != 1 else ''} of freedom."]
    legend = [(f"χ² density, {dof} dof", BLUE, "")]
    if gate is not None:
        chart.line([(gate, 0.0), (gate, top)], colour=ORANGE, dash="6 4")
        legend.append(
            (
                f"gate at {num(100 * (confidence or 0))}%: {num(gate)}" if show_results else "gate",
                ORANGE,
                "6 4",
            )
        )
        if show_results:
            facts.append(f"The {num(100 * (confidence or 0))}% quantile, the gate, is {num(gate)}.")
    if mark is not None:
        chart.line([(mark, 0.0), (mark, top)], colour=GREEN, dash="2 3")
        tail = 1 - chi2_cdf(mark, dof)
        legend.append(
            (f"d² = {num(mark)}" + (f": tail {num(tail)}" if show_results else ""), GREEN, "2 3")
        )
        if show_results:
            facts.append(f"A d² of {num(mark)} leaves {num(tail)} of the probability above it.")
        else:
            facts.append(f"A d² of {num(mark)} is marked.")
    return chart.svg("The chi-square distribution of d²", " ".join(facts), legend)


def _innovations(p: Params) -> list[tuple[str, float, float]]:
    return [("a", float(p["nua0"]), float(p["nua1"])), ("b", float(p["nub0"]), float(p["nub1"]))]


def _nn_scene(
    z: Sequence[float], landmarks: Sequence[Sequence[float]], s00: float, s11: float
) -> str:
    return gate_ellipse(
        s00,
        s11,
        [
            (f"candidate {j}", float(z[0]) - float(c[0]), float(z[1]) - float(c[1]))
            for j, c in enumerate(landmarks)
        ],
        show_results=False,
    )


FIGURES: dict[str, Figure] = {
    # other numbers than the exercises', whose answers these would be
    "association/gate-ellipse": lambda: gate_ellipse(
        0.16, 0.0025, [("a", 0.2, 0.06), ("b", 0.1, -0.14)]
    ),
    "association/chi2-density": lambda: chi2_curve(2, confidence=0.95, mark=7.0),
}

PICTURES: dict[str, Picture] = {
    "association/mahalanobis-2d": Picture(
        lambda p, shown: gate_ellipse(
            float(p["s00"]),
            float(p["s11"]),
            [("ν", float(p["nu0"]), float(p["nu1"]))],
            show_results=shown,
        )
    ),
    "association/gate-decision": Picture(
        lambda p, shown: gate_ellipse(
            float(p["s00"]),
            float(p["s11"]),
            _innovations(p),
            confidence=float(p["confidence"]),
            show_results=shown,
        )
    ),
    "association/chi2-percentile": answer(lambda p: chi2_curve(int(p["dof"]), mark=float(p["d2"]))),
    "association/gate-threshold": answer(
        lambda p: chi2_curve(int(p["dof"]), confidence=float(p["confidence"]))
    ),
    "association/gate-tail": answer(lambda p: chi2_curve(int(p["dof"]), mark=float(p["d2"]))),
    # code exercises: the lesson's numbers (their first example), the answers not written
    "association/mahalanobis": given(
        lambda p: gate_ellipse(0.25, 0.01, [("ν", 0.3, -0.09)], show_results=False)
    ),
    "association/chi2-gate": given(
        lambda p: chi2_curve(1, confidence=0.95, mark=1.0, show_results=False)
    ),
    "association/nearest-neighbour-fix": given(
        lambda p: _nn_scene([5.3, 0.05], [[5.7, 0.06], [5.0, 0.14]], 0.25, 0.01)
    ),
}
