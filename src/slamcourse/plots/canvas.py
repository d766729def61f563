"""Drawing helpers shared by the chapters' figures: plan views, charts, ellipses, labels.

- :class:`Plane`: a plan view in metres with the same scale on both axes (x right, y up), for
  poses (triangles with their own axes), landmarks, paths and covariance ellipses;
- :class:`Chart`: a chart with numbered axes (a value against an index or a parameter);
- :class:`Labels`: places text where it overlaps neither other labels nor the markers drawn
  (a label never covers the robot), trying positions around its anchor in turn.

Everything is pure: numbers in, an SVG string out (:func:`slamcourse.plots.svg.document`, with
a ``<title>`` and a ``<desc>``). Colours never carry meaning alone: series also differ by dash
or marker, and legends name them.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Sequence
from typing import Any

from slamcourse.plots.svg import document, el, fmt, num, polyline, text

INK = "#222"
MUTED = "#666"
BLUE = "#1f6fb2"
ORANGE = "#b3541e"
GREEN = "#2e7d32"
PURPLE = "#7a3fa0"
RED = "#b0262b"
PAPER = "#fbfbf8"

Box = tuple[float, float, float, float]  # x0, y0, x1, y1 (px)


def text_width(content: str, size: float = 12.0) -> float:
    """An estimate of the width (px) of ``content`` in a sans-serif font of ``size`` px."""
    return 0.58 * size * len(content)


def _overlaps(a: Box, b: Box) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


class Labels:
    """Text placed so that it overlaps no other label and no marker (:meth:`block`)."""

    def __init__(self, width: float, height: float) -> None:
        self.width, self.height = width, height
        self.taken: list[Box] = []
        self.body: list[str] = []

    def block(self, x: float, y: float, radius: float) -> None:
        """Keep labels off a marker of ``radius`` px at (x, y) px."""
        self.taken.append((x - radius, y - radius, x + radius, y + radius))

    def block_segment(self, a: tuple[float, float], b: tuple[float, float], pad: float = 3) -> None:
        """Keep labels off a drawn segment (sampled as small boxes)."""
        steps = max(1, int(math.hypot(b[0] - a[0], b[1] - a[1]) / 8))
        for k in range(steps + 1):
            t = k / steps
            self.block(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), pad)

    def add(
        self,
        x: float,
        y: float,
        content: str,
        *,
        colour: str = INK,
        size: float = 12.0,
        gap: float = 10.0,
        bold: bool = False,
        prefer: Sequence[str] = ("ne", "e", "se", "n", "s", "nw", "w", "sw"),
    ) -> Box:
        """Place ``content`` near the anchor (x, y) px, at the first free side of ``prefer``
        (compass points), moving further out if all are taken; returns its box."""
        w, h = text_width(content, size), size
        offsets = {
            "e": (gap, h / 2 - 2),
            "w": (-gap - w, h / 2 - 2),
            "n": (-w / 2, -gap),
            "s": (-w / 2, gap + h - 2),
            "ne": (gap * 0.7, -gap * 0.7),
            "nw": (-gap * 0.7 - w, -gap * 0.7),
            "se": (gap * 0.7, gap * 0.7 + h - 2),
            "sw": (-gap * 0.7 - w, gap * 0.7 + h - 2),
        }
        best: Box | None = None
        for scale in (1.0, 1.8, 2.8, 4.0):
            for side in prefer:
                dx, dy = offsets[side]
                if scale != 1.0:
                    cx, cy = dx + w / 2, dy - h / 2 + 2
                    dx, dy = dx + (scale - 1) * cx * 0.8, dy + (scale - 1) * (cy * 0.8)
                x0, base = x + dx, y + dy
                box = (x0 - 1, base - h + 1, x0 + w + 1, base + 3)
                inside = box[0] >= 2 and box[2] <= self.width - 2 and box[1] >= 2
                inside = inside and box[3] <= self.height - 2
                if best is None and inside:
                    best = box
                if inside and not any(_overlaps(box, t) for t in self.taken):
                    return self._put(box, content, colour, size, bold)
        if best is None:
            x0 = min(max(2.0, x - w / 2), self.width - w - 2)
            base = min(max(h + 2, y - gap), self.height - 4)
            best = (x0 - 1, base - h + 1, x0 + w + 1, base + 3)
        return self._put(best, content, colour, size, bold)

    def _put(self, box: Box, content: str, colour: str, size: float, bold: bool) -> Box:
        self.taken.append(box)
        self.body.append(
            text(
                box[0] + 1,
                box[3] - 3,
                content,
                fill=colour,
                font_size=fmt(size) if size != 12.0 else None,
                font_weight="bold" if bold else None,
            )
        )
        return box


def ellipse_axes(cov: Any, k: float = 1.0) -> tuple[float, float, float]:
    """Semi-axes (a ≥ b) and the angle (rad, from x) of the ``k``-σ ellipse of a 2×2
    covariance: the eigen-decomposition of the symmetric matrix, in closed form."""
    sxx, sxy, syy = float(cov[0][0]), float(cov[0][1]), float(cov[1][1])
    mean = (sxx + syy) / 2
    radius = math.hypot((sxx - syy) / 2, sxy)
    big, small = mean + radius, max(mean - radius, 0.0)
    angle = 0.5 * math.atan2(2 * sxy, sxx - syy)
    return k * math.sqrt(big), k * math.sqrt(small), angle


class Plane:
    """A plan view: world metres → SVG px, equal scale on both axes, y up."""

    def __init__(
        self,
        points: Iterable[tuple[float, float]],
        *,
        width: float = 520.0,
        height: float = 380.0,
        pad: float = 40.0,
        top: float = 0.0,
        grid: float | None = None,
    ) -> None:
        pts = [(float(x), float(y)) for x, y in points] or [(0.0, 0.0)]
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        self.x0, self.x1, self.y0, self.y1 = min(xs), max(xs), min(ys), max(ys)
        span = max(self.x1 - self.x0, self.y1 - self.y0, 1e-9)
        sx_span = max(self.x1 - self.x0, span * 0.05)
        sy_span = max(self.y1 - self.y0, span * 0.05)
        self.width, self.height, self.top = width, height, top
        self.scale = min((width - 2 * pad) / sx_span, (height - top - 2 * pad) / sy_span)
        self.cx, self.cy = (self.x0 + self.x1) / 2, (self.y0 + self.y1) / 2
        self.labels = Labels(width, height)
        self.body: list[str] = [el("rect", x=0.0, y=0.0, width=width, height=height, fill=PAPER)]
        self.front: list[str] = []
        if grid:
            self._grid(grid)

    def sx(self, x: float) -> float:
        return self.width / 2 + (x - self.cx) * self.scale

    def sy(self, y: float) -> float:
        return self.top + (self.height - self.top) / 2 - (y - self.cy) * self.scale

    def px(self, x: float, y: float) -> tuple[float, float]:
        return self.sx(x), self.sy(y)

    def _grid(self, step: float) -> None:
        lo_x = math.floor((self.cx - self.width / 2 / self.scale) / step) * step
        hi_x = self.cx + self.width / 2 / self.scale
        k = lo_x
        while k <= hi_x:
            self.body.append(
                el("line", x1=self.sx(k), x2=self.sx(k), y1=self.top, y2=self.height, stroke="#eee")
            )
            k += step
        half = (self.height - self.top) / 2 / self.scale
        k = math.floor((self.cy - half) / step) * step
        while k <= self.cy + half:
            self.body.append(
                el("line", x1=0.0, x2=self.width, y1=self.sy(k), y2=self.sy(k), stroke="#eee")
            )
            k += step

    # ---- marks
    def path(
        self,
        pts: Iterable[tuple[float, float]],
        *,
        colour: str = INK,
        dash: str | None = None,
        width: float = 2.0,
        block: bool = False,
        every: int = 1,
    ) -> None:
        shown = [self.px(x, y) for x, y in pts]
        if every > 1:
            shown = shown[::every] + ([shown[-1]] if (len(shown) - 1) % every else [])
        self.body.append(polyline(shown, stroke=colour, stroke_width=width, stroke_dasharray=dash))
        if block:
            for a, b in itertools.pairwise(shown):
                self.labels.block_segment(a, b)

    def segment(
        self,
        a: tuple[float, float],
        b: tuple[float, float],
        *,
        colour: str = INK,
        dash: str | None = None,
        width: float = 1.5,
        arrow: bool = False,
    ) -> None:
        pa, pb = self.px(*a), self.px(*b)
        self.body.append(
            polyline([pa, pb], stroke=colour, stroke_width=width, stroke_dasharray=dash)
        )
        self.labels.block_segment(pa, pb)
        if arrow:
            self.body.append(arrowhead(pa, pb, colour))

    def pose(
        self,
        x: float,
        y: float,
        theta: float,
        *,
        colour: str = INK,
        label: str | None = None,
        size: float = 14.0,
        axes: float | None = None,
        hollow: bool = False,
    ) -> None:
        """A pose: a triangle pointing along θ; ``axes`` (m) also draws its own x and y axes."""
        px, py = self.px(x, y)
        if axes:
            for ang, name in ((theta, "x"), (theta + math.pi / 2, "y")):
                end = (x + axes * math.cos(ang), y + axes * math.sin(ang))
                pe = self.px(*end)
                self.body.append(polyline([(px, py), pe], stroke=colour, stroke_width=1.2))
                self.body.append(arrowhead((px, py), pe, colour, size=6))
                self.labels.block_segment((px, py), pe)
                self.labels.add(pe[0], pe[1], name, colour=colour, size=10, gap=4)
        tri = [
            (px + size * math.cos(theta), py - size * math.sin(theta)),
            (px + size * 0.7 * math.cos(theta + 2.5), py - size * 0.7 * math.sin(theta + 2.5)),
            (px + size * 0.7 * math.cos(theta - 2.5), py - size * 0.7 * math.sin(theta - 2.5)),
        ]
        points = " ".join(f"{fmt(a)},{fmt(b)}" for a, b in tri)
        if hollow:
            self.front.append(
                el("polygon", points=points, fill="#fff", stroke=colour, stroke_width=1.5)
            )
        else:
            self.front.append(el("polygon", points=points, fill=colour))
        self.labels.block(px, py, size)
        if label:
            self.labels.add(px, py, label, colour=colour, gap=size + 2)

    def point(
        self,
        x: float,
        y: float,
        *,
        colour: str = GREEN,
        shape: str = "diamond",
        label: str | None = None,
        size: float = 6.0,
        bold: bool = False,
    ) -> None:
        px, py = self.px(x, y)
        self.front.append(marker(px, py, shape, colour, size))
        self.labels.block(px, py, size + 1)
        if label:
            self.labels.add(px, py, label, colour=colour, gap=size + 4, bold=bold)

    def ellipse(
        self,
        x: float,
        y: float,
        cov: Any,
        *,
        k: float = 1.0,
        colour: str = BLUE,
        dash: str | None = None,
        fill: str = "none",
    ) -> None:
        """The ``k``-σ ellipse of the 2×2 covariance ``cov`` (m²) centred at (x, y)."""
        a, b, angle = ellipse_axes(cov, k)
        px, py = self.px(x, y)
        self.body.append(
            el(
                "ellipse",
                cx=px,
                cy=py,
                rx=max(a * self.scale, 0.5),
                ry=max(b * self.scale, 0.5),
                transform=f"rotate({fmt(-math.degrees(angle))} {fmt(px)} {fmt(py)})",
                fill=fill,
                fill_opacity="0.15" if fill != "none" else None,
                stroke=colour,
                stroke_width=1.5,
                stroke_dasharray=dash,
            )
        )

    def label(self, x: float, y: float, content: str, **kw: object) -> None:
        """A label near the world point (x, y), placed off the other marks."""
        px, py = self.px(x, y)
        self.labels.add(px, py, content, **kw)  # type: ignore[arg-type]

    def svg(self, title: str, desc: str, legend: Sequence[tuple[str, str, str]] = ()) -> str:
        extra = legend_box(legend, 10, 10, self.labels) if legend else []
        return document(
            self.width,
            self.height,
            title,
            desc,
            [*self.body, *self.front, *extra, *self.labels.body],
        )


def arrowhead(
    a: tuple[float, float], b: tuple[float, float], colour: str, size: float = 8.0
) -> str:
    """A filled arrowhead at ``b`` pointing from ``a`` (px)."""
    ang = math.atan2(b[1] - a[1], b[0] - a[0])
    left = (b[0] - size * math.cos(ang - 0.4), b[1] - size * math.sin(ang - 0.4))
    right = (b[0] - size * math.cos(ang + 0.4), b[1] - size * math.sin(ang + 0.4))
    pts = " ".join(f"{fmt(x)},{fmt(y)}" for x, y in (b, left, right))
    return el("polygon", points=pts, fill=colour)


def marker(x: float, y: float, shape: str, colour: str, size: float = 6.0) -> str:
    """A point marker: ``circle``, ``square``, ``diamond``, ``cross``, ``ring`` or ``star``."""
    if shape == "circle":
        return el("circle", cx=x, cy=y, r=size * 0.8, fill=colour)
    if shape == "ring":
        return el("circle", cx=x, cy=y, r=size * 0.8, fill="#fff", stroke=colour, stroke_width=2.0)
    if shape == "square":
        return el(
            "rect",
            x=x - size * 0.7,
            y=y - size * 0.7,
            width=size * 1.4,
            height=size * 1.4,
            fill=colour,
        )
    if shape == "cross":
        d = size * 0.8
        return el(
            "path",
            d=f"M{fmt(x - d)},{fmt(y - d)}L{fmt(x + d)},{fmt(y + d)}"
            f"M{fmt(x + d)},{fmt(y - d)}L{fmt(x - d)},{fmt(y + d)}",
            stroke=colour,
            stroke_width=2.0,
        )
    if shape == "star":
        pts = []
        for k in range(10):
            r = size * (1.1 if k % 2 == 0 else 0.5)
            a = -math.pi / 2 + k * math.pi / 5
            pts.append(f"{fmt(x + r * math.cos(a))},{fmt(y + r * math.sin(a))}")
        return el("polygon", points=" ".join(pts), fill=colour)
    diamond = (
        f"{fmt(x)},{fmt(y - size)} {fmt(x + size)},{fmt(y)} {fmt(x)},{fmt(y + size)} "
        f"{fmt(x - size)},{fmt(y)}"
    )
    return el("polygon", points=diamond, fill=colour)


def legend_box(
    entries: Sequence[tuple[str, str, str]], x: float, y: float, labels: Labels | None = None
) -> list[str]:
    """A legend: one row per (name, colour, style) — style is a dash pattern (``""`` solid)
    or ``marker:<shape>``."""
    width = 40 + max(text_width(name, 11) for name, _, _ in entries)
    height = 8 + 16 * len(entries)
    out = [
        el(
            "rect",
            x=x,
            y=y,
            width=width,
            height=height,
            fill="#fff",
            fill_opacity="0.85",
            stroke="#ccc",
        )
    ]
    for i, (name, colour, style) in enumerate(entries):
        ly = y + 16 + 16 * i
        if style.startswith("marker:"):
            out.append(marker(x + 18, ly - 4, style.split(":", 1)[1], colour, 5))
        else:
            out.append(
                polyline(
                    [(x + 6, ly - 4), (x + 30, ly - 4)],
                    stroke=colour,
                    stroke_width=2.0,
                    stroke_dasharray=style or None,
                )
            )
        out.append(text(x + 36, ly, name, fill=INK, font_size="11"))
    if labels is not None:
        labels.taken.append((x, y, x + width, y + height))
    return out


def nice_ticks(lo: float, hi: float, count: int = 5) -> list[float]:
    """About ``count`` round numbers covering [lo, hi]."""
    if hi <= lo:
        hi = lo + 1.0
    raw = (hi - lo) / count
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw)
    first = math.ceil(lo / step - 1e-9) * step
    out = []
    k = first
    while k <= hi + 1e-9 * step:
        out.append(0.0 if abs(k) < 1e-12 * step else k)
        k += step
    return out


class Chart:
    """A chart with numbered axes; ``log_y`` draws y on a log scale."""

    def __init__(
        self,
        x_range: tuple[float, float],
        y_range: tuple[float, float],
        *,
        x_label: str,
        y_label: str,
        width: float = 540.0,
        height: float = 320.0,
        log_y: bool = False,
        left: float = 64.0,
        bottom: float = 46.0,
        top: float = 24.0,
        right: float = 20.0,
    ) -> None:
        self.x0, self.x1 = x_range
        self.y0, self.y1 = y_range
        self.log_y = log_y
        self.width, self.height = width, height
        self.left, self.right, self.top, self.bottom = left, right, top, bottom
        self.pw, self.ph = width - left - right, height - top - bottom
        self.labels = Labels(width, height)
        self.body: list[str] = [
            el("rect", x=0.0, y=0.0, width=width, height=height, fill="#fff"),
            el("rect", x=left, y=top, width=self.pw, height=self.ph, fill=PAPER, stroke="#999"),
        ]
        for t in nice_ticks(self.x0, self.x1):
            px = self.sx(t)
            self.body.append(
                el("line", x1=px, x2=px, y1=top + self.ph, y2=top + self.ph + 4, stroke="#999")
            )
            self.body.append(
                text(
                    px,
                    top + self.ph + 16,
                    num(t, 4),
                    text_anchor="middle",
                    fill=MUTED,
                    font_size="11",
                )
            )
        if log_y:
            lo, hi = math.floor(math.log10(self.y0)), math.ceil(math.log10(self.y1))
            yt = [10.0**e for e in range(lo, hi + 1) if self.y0 <= 10.0**e <= self.y1]
        else:
            yt = nice_ticks(self.y0, self.y1)
        for t in yt:
            py = self.sy(t)
            self.body.append(
                el("line", x1=left - 4, x2=left + self.pw, y1=py, y2=py, stroke="#e4e4e4")
            )
            self.body.append(
                text(left - 6, py + 4, num(t, 4), text_anchor="end", fill=MUTED, font_size="11")
            )
        self.body.append(
            text(left + self.pw / 2, height - 8, x_label, text_anchor="middle", fill=INK)
        )
        self.body.append(
            text(
                14,
                top + self.ph / 2,
                y_label,
                text_anchor="middle",
                fill=INK,
                transform=f"rotate(-90 14 {fmt(top + self.ph / 2)})",
            )
        )
        self.front: list[str] = []

    def sx(self, x: float) -> float:
        return self.left + (x - self.x0) / (self.x1 - self.x0) * self.pw

    def sy(self, y: float) -> float:
        if self.log_y:
            y = max(y, self.y0)
            f = (math.log10(y) - math.log10(self.y0)) / (math.log10(self.y1) - math.log10(self.y0))
        else:
            f = (y - self.y0) / (self.y1 - self.y0)
        return self.top + (1 - f) * self.ph

    def line(
        self,
        pts: Iterable[tuple[float, float]],
        *,
        colour: str = BLUE,
        dash: str | None = None,
        width: float = 2.0,
    ) -> None:
        self.body.append(
            polyline(
                [(self.sx(x), self.sy(y)) for x, y in pts],
                stroke=colour,
                stroke_width=width,
                stroke_dasharray=dash,
            )
        )

    def band(self, lo: float, hi: float, *, colour: str = GREEN) -> None:
        """A horizontal band between two y values."""
        y0, y1 = self.sy(hi), self.sy(lo)
        self.body.append(
            el(
                "rect",
                x=self.left,
                y=y0,
                width=self.pw,
                height=max(y1 - y0, 1.0),
                fill=colour,
                fill_opacity="0.15",
            )
        )

    def points(
        self,
        pts: Iterable[tuple[float, float]],
        *,
        colour: str = BLUE,
        shape: str = "circle",
        size: float = 3.0,
    ) -> None:
        for x, y in pts:
            self.front.append(marker(self.sx(x), self.sy(y), shape, colour, size))

    def hline(self, y: float, *, colour: str = INK, dash: str | None = "6 4") -> None:
        py = self.sy(y)
        self.body.append(
            polyline(
                [(self.left, py), (self.left + self.pw, py)],
                stroke=colour,
                stroke_width=1.5,
                stroke_dasharray=dash,
            )
        )

    def svg(self, title: str, desc: str, legend: Sequence[tuple[str, str, str]] = ()) -> str:
        extra = legend_box(legend, self.left + 8, self.top + 8, self.labels) if legend else []
        return document(
            self.width,
            self.height,
            title,
            desc,
            [*self.body, *self.front, *extra, *self.labels.body],
        )
