"""The course's end says where every chapter belongs: the map lists each numbered chapter once,
in order, with what it builds on, and the related lessons of the source are all there."""

from __future__ import annotations

import re

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root

ROOT = bundled_course_root()
MAP = (ROOT / "chapters" / "98-where-next.md").read_text(encoding="utf-8")


def _rows(heading: str) -> list[list[str]]:
    section = MAP.split(f"## {heading}", 1)[1].split("\n## ", 1)[0]
    rows = [line for line in section.splitlines() if line.startswith("| ")]
    return [[cell.strip() for cell in row.strip("|").split("|")] for row in rows[1:]]


def test_the_map_lists_every_numbered_chapter_in_order() -> None:
    numbered = sorted(
        int(path.name[:2])
        for path in (ROOT / "chapters").glob("[0-9][0-9]-*.md")
        if int(path.name[:2]) < 90
    )
    listed = [int(row[0].split()[0]) for row in _rows("The map")]
    assert listed == numbered


def test_each_chapter_builds_only_on_earlier_or_named_chapters() -> None:
    for row in _rows("The map"):
        number = int(row[0].split()[0])
        needs = [int(n) for n in re.findall(r"\d+", row[1].split("(")[0])]
        # "1–8" is a range: both ends are earlier chapters
        assert all(n < number for n in needs), row


def test_the_end_pages_come_after_every_chapter_with_exercises() -> None:
    course = load_course(ROOT)
    ids = [chapter.id for chapter in course.chapters]
    assert ids[-2:] == ["where-next", "notation"]
    assert course.problems == []


def test_related_lessons_each_say_what_they_add() -> None:
    lessons = _rows("Related lessons")
    names = [row[0] for row in lessons]
    assert names == [
        "Classical SLAM — From Absolute Zero",
        "Classical VIO — From Absolute Zero",
        "Extended Kalman Filter — From Absolute Zero",
        "Bayesian Estimation — From Absolute Zero",
    ]
    assert all(len(row[1].split()) >= 6 for row in lessons)


def test_the_map_figure_draws_the_table() -> None:
    """The figure is drawn from the table itself: one box per chapter, one line per
    "builds on" entry (a range such as 1–8 counts each chapter in it)."""
    import xml.etree.ElementTree as ET

    from slamcourse.plots.ch_where_next import _numbers, course_map, map_rows

    assert _numbers("1–8") == tuple(range(1, 9)) and _numbers(
        "7 (and 17, which it introduces)"
    ) == (7,)
    rows = map_rows(MAP)
    svg = ET.fromstring(course_map(rows))
    ns = "{http://www.w3.org/2000/svg}"
    assert len(list(svg.iter(f"{ns}rect"))) == len(rows)
    assert len(list(svg.iter(f"{ns}line"))) == sum(len(r.needs) for r in rows)
