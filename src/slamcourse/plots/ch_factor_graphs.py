"""Chapter ``factor-graphs``: a small SLAM problem drawn as variables and factors."""

from __future__ import annotations

from collections.abc import Sequence

from slamcourse.plots.canvas import BLUE, GREEN, INK, ORANGE, Labels, legend_box
from slamcourse.plots.picture import Figure, Picture, given
from slamcourse.plots.svg import document, el, polyline, text

W, H = 560.0, 340.0


def factor_graph(
    poses: int, landmarks: int, sightings: Sequence[tuple[int, int]], *, title: str = ""
) -> str:
    """Poses x0… in a row, landmarks l1… above them; factors (black squares) for the prior on
    x0, each odometry step and each sighting (pose k, landmark j from 1)."""
    labels = Labels(W, H)
    gap = (W - 120) / max(poses - 1, 1)
    pose_at = [(70 + k * gap, 210.0) for k in range(poses)]
    land_gap = (W - 160) / max(landmarks, 1)
    land_at = [(80 + land_gap * (j + 0.5), 80.0) for j in range(landmarks)]
    body: list[str] = [el("rect", x=0.0, y=0.0, width=W, height=H, fill="#fbfbf8")]
    factors: list[tuple[float, float, str]] = []

    def factor(a: tuple[float, float], b: tuple[float, float] | None, colour: str) -> None:
        if b is None:
            fx, fy = a[0] - 40, a[1]
            body.append(polyline([(fx, fy), a], stroke=colour, stroke_width=1.5))
        else:
            fx, fy = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
            body.append(polyline([a, b], stroke=colour, stroke_width=1.5))
        factors.append((fx, fy, colour))

    factor(pose_at[0], None, INK)
    for k in range(poses - 1):
        factor(pose_at[k], pose_at[k + 1], INK)
    for k, j in sightings:
        factor(pose_at[k], land_at[j - 1], ORANGE)
    for fx, fy, colour in factors:
        body.append(el("rect", x=fx - 5, y=fy - 5, width=10.0, height=10.0, fill=colour))
    for k, (x, y) in enumerate(pose_at):
        body.append(el("circle", cx=x, cy=y, r=16.0, fill="#fff", stroke=BLUE, stroke_width=2.0))
        body.append(text(x, y + 4, f"x{k}", text_anchor="middle", fill=INK))
    for j, (x, y) in enumerate(land_at):
        body.append(el("circle", cx=x, cy=y, r=16.0, fill="#fff", stroke=GREEN, stroke_width=2.0))
        body.append(text(x, y + 4, f"l{j + 1}", text_anchor="middle", fill=INK))
    body += legend_box(
        [
            ("pose variable", BLUE, "marker:ring"),
            ("landmark variable", GREEN, "marker:ring"),
            ("prior or odometry factor", INK, "marker:square"),
            ("measurement factor", ORANGE, "marker:square"),
        ],
        W - 200,
        250,
        labels,
    )
    desc = (
        f"A factor graph with {poses} pose variables and {landmarks} landmark variables "
        f"(circles) and {len(factors)} factors (squares): a prior on x0, {poses - 1} odometry "
        f"factors between consecutive poses and {len(sightings)} measurement factors, one per "
        "sighting of a landmark from a pose. Each factor touches exactly the variables its "
        "measurement depends on."
    )
    return document(W, H, title or "A factor graph", desc, body)


LESSON_SIGHTINGS = [(0, 1), (1, 1), (1, 2), (2, 2), (3, 2)]


FIGURES: dict[str, Figure] = {
    "factor-graphs/small-slam": lambda: factor_graph(4, 2, LESSON_SIGHTINGS),
}

PICTURES: dict[str, Picture] = {
    "factor-graphs/slam-steps": given(lambda p: factor_graph(4, 2, LESSON_SIGHTINGS)),
}
