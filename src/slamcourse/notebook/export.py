"""``slamcourse export notebooks DIR``: the course as Jupyter notebooks, one per chapter.

Each notebook is the chapter's prose (Markdown cells, math as ``$…$``, prose figures as SVG
attachments of their Markdown cell, the caption under the picture) and, where the chapter
places an exercise, two code cells: one that poses it (``show("ID")``: the learner's own
variant, drawn when it runs) and one that answers it (``check("ID", "")`` for a text answer,
a ``%%slamcourse check ID`` cell holding the starter for a code exercise), each marked with
``{"slamcourse": {"exercise": ID, "role": ...}}`` metadata (docs/submissions.md,
"Notebooks"). Running a notebook top to bottom checks every answer in it.

The notebooks are written as plain nbformat 4.5 JSON with the standard library, so exporting
needs neither IPython nor nbformat; running them needs ``slamcourse[jupyter]``.
"""

from __future__ import annotations

import base64
import json
import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from slamcourse.errors import UsageError
from slamcourse.notebook.cells import CHECK, META, magic_line

NBFORMAT = 4
NBFORMAT_MINOR = 5

_FENCE = re.compile(r"^(?P<fence>`{3,}|~{3,})(?P<info>.*)$")

ANSWER_FORM = {
    "number": 'a number, e.g. "0.25", "7/5" or "pi/4"',
    "vector": 'a vector, e.g. "[0.3, -0.09]"',
    "matrix": 'a matrix, e.g. "[[1, 2], [3, 4]]"',
    "expression": 'a formula in the variables the prompt names, e.g. "2*x + sqrt(y)"',
    "choice": 'one option, e.g. "b"',
    "multi": 'every option that applies, e.g. "a, c"',
    "order": 'the steps in order, e.g. "c a b"',
    "line": 'the number of the buggy line, e.g. "3"',
}
"""What the answer cell's comment says of each kind (``show`` above it says it exactly)."""


@dataclass(frozen=True)
class Prose:
    markdown: str


@dataclass(frozen=True)
class FigureBlock:
    figure_id: str
    caption: str


def split_figures(markdown: str) -> Iterator[Prose | FigureBlock]:
    """Chapter prose split at its ```{figure} ID``` blocks (each block's content is the
    caption); other fenced blocks stay in the prose."""
    buf: list[str] = []
    lines = markdown.splitlines(keepends=True)
    i = 0
    while i < len(lines):
        match = _FENCE.match(lines[i].rstrip("\n"))
        if match is None:
            buf.append(lines[i])
            i += 1
            continue
        fence, info = match.group("fence"), match.group("info").split(None, 1)
        end = i + 1
        while end < len(lines) and not (
            lines[end].strip().startswith(fence[0] * len(fence))
            and not lines[end].strip().strip(fence[0])
        ):
            end += 1
        if info and info[0] == "{figure}" and len(info) > 1:
            if "".join(buf).strip():
                yield Prose("".join(buf))
            buf = []
            yield FigureBlock(info[1].strip(), "".join(lines[i + 1 : end]).strip())
        else:
            buf.extend(lines[i : end + 1])
        i = end + 1
    if "".join(buf).strip():
        yield Prose("".join(buf))


class _Cells:
    """The cells of one notebook, with stable ids (``c001`` …)."""

    def __init__(self) -> None:
        self.cells: list[dict[str, Any]] = []

    def _id(self) -> str:
        return f"c{len(self.cells) + 1:03d}"

    def markdown(self, text: str, attachments: dict[str, Any] | None = None) -> None:
        cell: dict[str, Any] = {
            "cell_type": "markdown",
            "id": self._id(),
            "metadata": {},
            "source": _lines(text.strip() + "\n"),
        }
        if attachments:
            cell["attachments"] = attachments
        self.cells.append(cell)

    def code(self, source: str, meta: dict[str, Any] | None = None) -> None:
        self.cells.append(
            {
                "cell_type": "code",
                "execution_count": None,
                "id": self._id(),
                "metadata": {META: meta} if meta else {},
                "outputs": [],
                "source": _lines(source.rstrip("\n")),
            }
        )


def _lines(text: str) -> list[str]:
    return text.splitlines(keepends=True)


def _svg_title(svg: str) -> str:
    match = re.search(r"<title[^>]*>(.*?)</title>", svg, re.S)
    title = re.sub(r"\s+", " ", match.group(1)).strip() if match else ""
    return title.replace("[", "(").replace("]", ")") or "Figure"


def figure_cell(cells: _Cells, block: FigureBlock, number: int) -> None:
    """A prose figure: its SVG as the Markdown cell's attachment, the caption under it."""
    from slamcourse.plots.registry import figure_svg

    svg = figure_svg(block.figure_id)
    caption = f"**Figure {number}.** {block.caption}".strip()
    if svg is None:
        cells.markdown(f"{caption}\n\n*(figure `{block.figure_id}` is not drawn here)*")
        return
    name = block.figure_id.replace("/", "-") + ".svg"
    data = base64.b64encode(svg.encode("utf-8")).decode("ascii")
    cells.markdown(
        f"![{_svg_title(svg)}](attachment:{name})\n\n{caption}",
        attachments={name: {"image/svg+xml": data}},
    )


def exercise_cells(cells: _Cells, spec: Any) -> None:
    """The two cells of an exercise: one poses it, one answers it."""
    ex = spec.id
    cells.code(f'show("{ex}")', {"exercise": ex, "role": "prompt"})
    if spec.kind == "code":
        starter = spec.options.starter.read_text(encoding="utf-8")
        cells.code(magic_line(ex) + "\n" + starter, {"exercise": ex, "role": "answer"})
        return
    form = ANSWER_FORM.get(spec.kind, "your answer")
    cells.code(
        f'# Your answer between the quotes: {form}.\n{CHECK}("{ex}", "")',
        {"exercise": ex, "role": "answer"},
    )


def chapter_notebook(course: Any, chapter: Any, identity: dict[str, Any]) -> dict[str, Any]:
    """One chapter as a notebook (nbformat 4.5, as a JSON-ready dict)."""
    from slamcourse.course.loader import chapter_segments

    cells = _Cells()
    intro = [f"# {chapter.number}. {chapter.title}"]
    if chapter.summary:
        intro.append(chapter.summary)
    intro.append(
        "Run the cells from the top. Each exercise is posed with *your own* numbers when its "
        "`show` cell runs; answer it in the cell below it and run that cell to have it "
        "checked. Your progress is saved in the same place as `slamcourse` in a terminal and "
        '`slamcourse serve` in the browser. `hint("ID")` reveals a hint; `explain("ID")` '
        'shows the worked explanation once an exercise is solved (or `give_up("ID")`).'
    )
    cells.markdown("\n\n".join(intro))
    cells.code(
        "%load_ext slamcourse.notebook\n"
        "from slamcourse.notebook import check, explain, give_up, hint, progress, show\n\n"
        f'progress("{chapter.id}")',
        {"role": "setup", "chapter": chapter.id},
    )
    figures = 0
    for exercise_id, prose in chapter_segments(chapter):
        for part in split_figures(prose):
            if isinstance(part, Prose):
                cells.markdown(part.markdown)
            else:
                figures += 1
                figure_cell(cells, part, figures)
        if exercise_id is not None:
            exercise_cells(cells, course.exercise(exercise_id))
    return {
        "cells": cells.cells,
        "metadata": {
            "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
            "language_info": {"name": "python"},
            META: {"chapter": chapter.id, **identity},
        },
        "nbformat": NBFORMAT,
        "nbformat_minor": NBFORMAT_MINOR,
    }


def export_notebooks(course_path: Path | None, out: Path, *, force: bool = False) -> list[Path]:
    """Write one notebook per chapter of the course into ``out``; returns their paths.

    Existing notebooks are not overwritten (a learner's work may be in them) unless
    ``force``."""
    from slamcourse import __version__
    from slamcourse.batch.submission import course_hash
    from slamcourse.course.loader import load_course
    from slamcourse.course.locate import bundled_course_root, course_root

    root = course_root(course_path)
    course = load_course(root)
    if not course.chapters:
        raise UsageError(f"the course at {root} has no chapters to export")
    targets = [(chapter, out / f"{chapter.path.stem}.ipynb") for chapter in course.chapters]
    taken = [p for _, p in targets if p.exists()]
    if taken and not force:
        names = ", ".join(p.name for p in taken[:5]) + (" …" if len(taken) > 5 else "")
        raise UsageError(
            f"{out} already holds {names}: choose a new folder, or --force to overwrite"
        )
    identity = {
        "course": {
            "version": __version__ if root == bundled_course_root() else "custom",
            "hash": course_hash(root),
        }
    }
    notebooks = [(path, chapter_notebook(course, ch, identity)) for ch, path in targets]
    try:
        out.mkdir(parents=True, exist_ok=True)
        for path, nb in notebooks:
            path.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", "utf-8")
    except OSError as exc:
        raise UsageError(f"cannot write to {out}: {exc.strerror or exc}") from None
    return [path for path, _ in notebooks]
