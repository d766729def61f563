"""The course's map: every chapter as a box, an arrow from each chapter it builds on.

Drawn from the table in ``chapters/98-where-next.md`` itself (its "builds on" column), so the
picture and the table cannot disagree. Chapters sit in columns by depth: a chapter's column is
one more than the deepest chapter it builds on.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from slamcourse.plots.picture import Figure
from slamcourse.plots.svg import document, el, text

BOX_W, BOX_H, GAP_X, GAP_Y, MARGIN = 150.0, 22.0, 34.0, 6.0, 12.0


@dataclass(frozen=True)
class Row:
    number: int
    name: str
    needs: tuple[int, ...]


def _numbers(cell: str) -> tuple[int, ...]:
    """``"3, 11"`` → (3, 11); ``"1–8"`` → 1…8; words in parentheses are left out."""
    out: list[int] = []
    for a, b in re.findall(r"(\d+)(?:\s*[–-]\s*(\d+))?", cell.split("(")[0]):
        out.extend(range(int(a), int(b) + 1) if b else [int(a)])
    return tuple(out)


def map_rows(markdown: str) -> list[Row]:
    """The rows of the "The map" table of the where-next chapter."""
    section = markdown.split("## The map", 1)[1].split("\n## ", 1)[0]
    rows = [line for line in section.splitlines() if line.startswith("| ")][1:]
    out = []
    for line in rows:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        number, _, name = cells[0].partition(" ")
        out.append(Row(int(number), name, _numbers(cells[1])))
    return out


def _short(name: str, limit: int = 20) -> str:
    return name if len(name) <= limit else name[: limit - 1].rstrip() + "…"


def course_map(rows: list[Row]) -> str:
    depth: dict[int, int] = {}
    for row in sorted(rows, key=lambda r: r.number):
        depth[row.number] = 1 + max((depth.get(n, 0) for n in row.needs), default=-1)
    columns: dict[int, list[Row]] = {}
    for row in rows:
        columns.setdefault(depth[row.number], []).append(row)
    tallest = max(len(c) for c in columns.values())
    width = MARGIN * 2 + len(columns) * BOX_W + (len(columns) - 1) * GAP_X
    height = MARGIN * 2 + 18 + tallest * (BOX_H + GAP_Y)
    where: dict[int, tuple[float, float]] = {}
    boxes: list[str] = []
    for col, members in sorted(columns.items()):
        x = MARGIN + col * (BOX_W + GAP_X)
        boxes.append(text(x, MARGIN + 10, f"depth {col}", fill="#555", font_size=11))
        for k, row in enumerate(sorted(members, key=lambda r: r.number)):
            y = MARGIN + 18 + k * (BOX_H + GAP_Y)
            where[row.number] = (x, y)
            late = row.number >= 19
            boxes.append(
                el(
                    "rect",
                    x=x,
                    y=y,
                    width=BOX_W,
                    height=BOX_H,
                    rx=4.0,
                    fill="#eef4fb" if late else "#ffffff",
                    stroke="#2b5d8a",
                    stroke_dasharray="4 2" if late else None,
                )
            )
            boxes.append(text(x + 5, y + 15, f"{row.number} {_short(row.name)}", font_size=11))
    arrows = []
    for row in rows:
        x1, y1 = where[row.number]
        for need in row.needs:
            if need not in where:
                continue
            x0, y0 = where[need]
            arrows.append(
                el(
                    "line",
                    x1=x0 + BOX_W,
                    y1=y0 + BOX_H / 2,
                    x2=x1,
                    y2=y1 + BOX_H / 2,
                    stroke="#8aa",
                    stroke_width=1.0,
                )
            )
    beyond = sorted(r.number for r in rows if r.number >= 19)
    desc = (
        f"{len(rows)} chapters in {len(columns)} columns by depth: a chapter sits one column "
        "right of the deepest chapter it builds on, with a line from each. Chapters "
        f"{beyond[0]}–{beyond[-1]} (dashed boxes) go beyond the lesson. "
        + "; ".join(
            f"{r.number} builds on {', '.join(map(str, r.needs)) or 'nothing'}"
            for r in sorted(rows, key=lambda r: r.number)
        )
        + "."
    )
    return document(width, height, "What each chapter builds on", desc, [*arrows, *boxes])


def _draw() -> str:
    from slamcourse.course.locate import bundled_course_root

    path = bundled_course_root() / "chapters" / "98-where-next.md"
    return course_map(map_rows(path.read_text(encoding="utf-8")))


FIGURES: dict[str, Figure] = {"where-next/map": _draw}
