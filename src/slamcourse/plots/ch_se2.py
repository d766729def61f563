"""Chapter ``se2``: frames for ⊕, the inverse and the motion between two poses; wrapping."""

from __future__ import annotations

import math
from collections.abc import Sequence

from slamcourse.plots.canvas import BLUE, GREEN, INK, MUTED, ORANGE, PURPLE, Plane, arrowhead
from slamcourse.plots.picture import Figure, Params, Picture, given
from slamcourse.plots.svg import el, num
from slamcourse.slam.se2 import between, compose, inverse, wrap_angle


def _pose_text(p: Sequence[float]) -> str:
    return f"({num(p[0])}, {num(p[1])}, {num(p[2])})"


def _scene(poses: Sequence[Sequence[float]], reach: float) -> list[tuple[float, float]]:
    pts = [(-0.3, -0.3), (reach, reach)]
    for x, y, _ in poses:
        pts += [(x - reach, y - reach), (x + reach, y + reach)]
    return pts


def frames_figure(
    a: Sequence[float], b: Sequence[float], *, mode: str = "compose", show_results: bool = True
) -> str:
    """``mode`` "compose": pose a, the motion b drawn in a's frame, and a ⊕ b; "between": poses
    a and b and the motion a⁻¹ ⊕ b between them; "inverse": pose a and a⁻¹ (the world origin
    seen from a). Derived poses are "?" when ``show_results`` is False."""
    a = [float(v) for v in a]
    b = [float(v) for v in b]
    if mode == "compose":
        c = list(compose(a, b))
        shown = [a, c]
    elif mode == "between":
        c = list(between(a, b))
        shown = [a, b]
    else:
        c = list(inverse(a))
        shown = [a]
    axes = 0.35 * max(1.0, max(math.hypot(p[0], p[1]) for p in [*shown, [1.0, 1.0, 0.0]]))
    plane = Plane(_scene(shown, axes + 0.2), width=500, height=400, pad=30, grid=1.0)
    plane.pose(0, 0, 0, colour=MUTED, axes=axes, label="world", hollow=True)
    plane.pose(*a, colour=BLUE, axes=axes, label=f"a = {_pose_text(a)}")
    facts = [f"Pose a = {_pose_text(a)} (x m, y m, θ rad) with its own axes."]
    if mode == "compose":
        if show_results:
            plane.pose(*c, colour=ORANGE, axes=axes, label=f"a ⊕ b = {_pose_text(c)}")
        else:
            plane.point(c[0], c[1], colour=ORANGE, shape="ring", label="a ⊕ b = ?")
        plane.segment((a[0], a[1]), (c[0], c[1]), colour=ORANGE, dash="6 4", arrow=True)
        plane.label((a[0] + c[0]) / 2, (a[1] + c[1]) / 2, "b, in a's frame", colour=ORANGE)
        facts.append(
            f"The motion b = {_pose_text(b)} is written in a's frame: "
            f"{num(b[0])} m along a's x axis and {num(b[1])} m along its y axis."
        )
        if show_results:
            facts.append(f"It ends at a ⊕ b = {_pose_text(c)}.")
    elif mode == "between":
        plane.pose(*b, colour=GREEN, axes=axes, label=f"b = {_pose_text(b)}")
        plane.segment((a[0], a[1]), (b[0], b[1]), colour=PURPLE, dash="6 4", arrow=True)
        text = f"a⁻¹ ⊕ b = {_pose_text(c)}" if show_results else "a⁻¹ ⊕ b = ?"
        plane.label((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, text, colour=PURPLE, bold=True)
        facts.append(
            f"Pose b = {_pose_text(b)}. The motion from a to b, written in a's frame, "
            + (f"is a⁻¹ ⊕ b = {_pose_text(c)}." if show_results else "is asked.")
        )
    else:
        plane.segment((a[0], a[1]), (0, 0), colour=PURPLE, dash="6 4", arrow=True)
        text = f"a⁻¹ = {_pose_text(c)}" if show_results else "a⁻¹ = ?"
        plane.label(a[0] / 2, a[1] / 2, text + ": the origin seen from a", colour=PURPLE, bold=True)
        facts.append(
            "The inverse a⁻¹ is the world origin seen from a, written in a's frame"
            + (f": {_pose_text(c)}." if show_results else ".")
        )
    titles = {
        "compose": "Composing poses: a ⊕ b",
        "between": "The motion between two poses",
        "inverse": "The inverse of a pose",
    }
    return plane.svg(titles[mode], " ".join(facts))


def wrap_figure(a: float, *, show_results: bool = True) -> str:
    """The unit circle: the angle ``a`` (its turns drawn as a spiral) and where it points, the
    wrapped value in (−π, π]."""
    w = wrap_angle(a)
    plane = Plane([(-1.6, -1.6), (1.6, 1.6)], width=380, height=380, pad=30)
    plane.body.append(
        el("circle", cx=plane.sx(0), cy=plane.sy(0), r=plane.scale, fill="none", stroke=MUTED)
    )
    pts = []
    steps = max(8, int(abs(a) * 20))
    for k in range(steps + 1):
        t = a * k / steps
        r = 0.2 + 0.6 * k / steps
        pts.append((r * math.cos(t), r * math.sin(t)))
    plane.path(pts, colour=BLUE, dash="4 3", width=1.5)
    end = plane.px(*pts[-1])
    before = plane.px(*pts[-2])
    plane.body.append(arrowhead(before, end, BLUE))
    plane.segment((0, 0), (math.cos(w), math.sin(w)), colour=ORANGE, width=2.5)
    plane.segment((-1.4, 0), (1.4, 0), colour=MUTED, width=0.8)
    plane.point(-1.0, 0.0, colour=INK, shape="circle", size=3, label="π kept, −π excluded")
    plane.label(pts[-1][0], pts[-1][1], f"a = {num(a)} rad", colour=BLUE, bold=True)
    text = f"wrap(a) = {num(w)} rad" if show_results else "wrap(a) = ?"
    plane.label(1.08 * math.cos(w), 1.08 * math.sin(w), text, colour=ORANGE, bold=True)
    desc = (
        f"The angle a = {num(a)} rad, drawn as a spiral from the x axis turning "
        f"{num(abs(a) / (2 * math.pi))} times"
        + (
            f"; it points the same way as {num(w)} rad, its representative in (−π, π]."
            if show_results
            else "; its representative in (−π, π] is asked."
        )
    )
    return plane.svg("Wrapping an angle into (−π, π]", desc)


def _p(p: Params, *names: str) -> list[float]:
    return [float(p[n]) for n in names]


FIGURES: dict[str, Figure] = {
    "se2/frames": lambda: frames_figure([2, 1, 0.6], [1.5, 0.5, 0.8]),
    "se2/between-frames": lambda: frames_figure([1, 2, -0.4], [3, 3, 1.2], mode="between"),
    "se2/wrap-circle": lambda: wrap_figure(8.0),
}

PICTURES: dict[str, Picture] = {
    "se2/wrap-value": Picture(lambda p, shown: wrap_figure(float(p["a"]), show_results=shown)),
    "se2/compose-value": Picture(
        lambda p, shown: frames_figure(
            _p(p, "xa", "ya", "ta"), _p(p, "xb", "yb", "tb"), show_results=shown
        )
    ),
    "se2/inverse-value": Picture(
        lambda p, shown: frames_figure(
            _p(p, "x", "y", "t"), [0, 0, 0], mode="inverse", show_results=shown
        )
    ),
    "se2/between-value": Picture(
        lambda p, shown: frames_figure(
            _p(p, "xa", "ya", "ta"), _p(p, "xb", "yb", "tb"), mode="between", show_results=shown
        )
    ),
    # code exercises: the lesson's numbers, nothing derived written
    "se2/wrap-angle": given(lambda p: wrap_figure(-3 * math.pi / 2 - 0.3, show_results=False)),
    "se2/between": given(
        lambda p: frames_figure([0, 0, 0], [3, -2, 0.5], mode="between", show_results=False)
    ),
}
