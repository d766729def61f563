"""Prose figures: ```{figure} ID``` blocks in chapters, from the loader to every face."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import pytest

from slamcourse.cli import main
from slamcourse.course.loader import load_course
from slamcourse.engine import Engine
from slamcourse.render.terminal import render_markdown
from slamcourse.validate import figure_drawings, svg_problem
from tests.conftest import FIXTURE_COURSE

NS = "{http://www.w3.org/2000/svg}"
FIGURE = "se2/wrap-circle"  # the figure the fixture course places (a bundled one)


def _chapter(course: Path, body: str) -> Path:
    path = course / "chapters" / "02-boundaries.md"
    text = path.read_text(encoding="utf-8")
    head, _, rest = text.partition("```{exercise} boundaries/wrap\n")
    path.write_text(head.split("```{figure}")[0] + body + "```{exercise} boundaries/wrap\n" + rest)
    return path


def test_the_fixture_chapter_carries_its_figure() -> None:
    course = load_course(FIXTURE_COURSE)
    chapter = course.chapter("boundaries")
    assert [f.id for f in chapter.figures] == [FIGURE]
    fig = chapter.figures[0]
    lines = chapter.path.read_text(encoding="utf-8").splitlines()
    assert lines[fig.line - 1] == f"```{{figure}} {FIGURE}"
    assert fig.caption.startswith("An angle of more than a turn")
    assert course.problems == []
    # the figure stays in the prose that leads to the next exercise
    assert chapter.exercises[0] == "boundaries/wrap"


def test_an_unknown_figure_is_a_problem_at_its_line(course_copy: Path) -> None:
    _chapter(course_copy, "```{figure} se2/wrap-circel\nA caption.\n```\n\n")
    course = load_course(course_copy)
    problems = [str(p) for p in course.problems]
    assert len(problems) == 1
    assert problems[0].startswith("chapters/02-boundaries.md:")
    assert "figure 'se2/wrap-circel' is not drawn by any plots module" in problems[0]
    assert "ch_boundaries.py" in problems[0] and "did you mean 'se2/wrap-circle'" in problems[0]
    # the chapter's exercises are still indexed
    assert course.chapter("boundaries").exercises[0] == "boundaries/wrap"


@pytest.mark.parametrize(
    ("block", "message"),
    [
        ("```{figure}\nA caption.\n```\n\n", "figure directive without an id"),
        ("```{figure} se2/wrap-circle\n```\n\n", "has no caption"),
        ("```{figure} wrap circle\nA caption.\n```\n\n", "must look like"),
    ],
)
def test_malformed_figure_blocks(course_copy: Path, block: str, message: str) -> None:
    path = _chapter(course_copy, block)
    line = path.read_text().splitlines().index(block.splitlines()[0]) + 1
    problems = [str(p) for p in load_course(course_copy).problems]
    assert any(
        p.startswith(f"chapters/02-boundaries.md:{line}:") and message in p for p in problems
    )


def test_the_validator_draws_every_placed_figure(monkeypatch: pytest.MonkeyPatch) -> None:
    from slamcourse.plots import registry

    course = load_course(FIXTURE_COURSE)
    assert figure_drawings(course.chapters, course.root) == []

    def broken() -> str:
        raise ZeroDivisionError("bad drawing")

    monkeypatch.setitem(registry.FIGURES, FIGURE, broken)
    problems = [str(p) for p in figure_drawings(course.chapters, course.root)]
    assert len(problems) == 1 and "raised ZeroDivisionError: bad drawing" in problems[0]
    monkeypatch.setitem(registry.FIGURES, FIGURE, lambda: "<svg")
    assert "not well-formed" in str(figure_drawings(course.chapters, course.root)[0])
    assert svg_problem('<svg xmlns="http://www.w3.org/2000/svg" role="img"/>') is not None


def test_terminal_prose_writes_the_figure_and_says_where(tmp_path: Path) -> None:
    md = f"Before.\n\n```{{figure}} {FIGURE}\nThe *caption* with $\\pi$.\n```\n\nAfter.\n"
    written: list[str] = []

    def figure(fig_id: str) -> str:
        written.append(fig_id)
        return str(tmp_path / "x.svg")

    out = render_markdown(md, width=100, figure=figure)
    assert written == [FIGURE]
    # one paragraph (wrapped to the width): that it exists, its caption, where it is
    paragraph = out.split("\n\n")[1].replace("\n", " ")
    assert paragraph == f"Figure: The caption with π. (picture written to {tmp_path / 'x.svg'})"
    assert "<svg" not in out
    # without a place to write it, the line names the command that draws it
    assert f"(slamcourse plot {FIGURE} draws it)" in render_markdown(md, width=100)


def test_show_with_context_writes_the_figure_into_the_workspace(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("SLAMCOURSE_WORKSPACE", str(tmp_path / "ws"))
    assert main(["--course", str(FIXTURE_COURSE), "show", "boundaries/wrap", "--context"]) == 0
    out = capsys.readouterr().out
    svg = tmp_path / "ws" / "figures" / "se2" / "wrap-circle.svg"
    assert "Figure: An angle of more than a turn" in out and str(svg) in out
    assert "<svg" not in out
    assert ET.fromstring(svg.read_text()).find(f"{NS}title") is not None


def test_plot_draws_a_figure_and_never_prints_svg_unless_asked(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("SLAMCOURSE_WORKSPACE", str(tmp_path / "ws"))
    course = ["--course", str(FIXTURE_COURSE)]
    assert main([*course, "plot", FIGURE]) == 0
    out = capsys.readouterr().out
    path = tmp_path / "ws" / "figures" / "se2" / "wrap-circle.svg"
    assert "<svg" not in out and f"figure {FIGURE}" in out and str(path) in out
    assert path.read_text().startswith("<svg")
    assert main([*course, "plot", FIGURE, "--out", "-"]) == 0
    assert capsys.readouterr().out.startswith("<svg")
    assert main([*course, "plot", "se2/no-such-figure"]) == 2
    assert "no exercise or figure 'se2/no-such-figure'" in capsys.readouterr().err


def test_the_browser_renders_the_figure_inline(engine: Engine, client: Any) -> None:
    from tests.web.test_api import login

    login(client)
    page = client.get("/chapter/boundaries").get_data(as_text=True)
    start = page.index('<figure class="figure prose-figure"')
    figure = page[start : page.index("</figure>", start) + len("</figure>")]
    root = ET.fromstring(figure.replace("<figure", '<figure xmlns:svg="x"', 1))
    svg = root.find(f"{NS}svg")
    assert svg is not None and svg.get("role") == "img"
    title, desc = svg.find(f"{NS}title"), svg.find(f"{NS}desc")
    assert title is not None and desc is not None
    assert svg.get("aria-labelledby") == f"{title.get('id')} {desc.get('id')}"
    caption = root.find("figcaption")
    assert caption is not None and "An angle of more than a turn" in "".join(caption.itertext())
    assert root.get("data-figure") == FIGURE
    assert "{figure}" not in page  # the block is not shown as code


def test_an_undrawable_figure_is_a_note_not_an_error(monkeypatch: pytest.MonkeyPatch) -> None:
    from slamcourse.web.markdown import to_html

    html = str(to_html("```{figure} se2/nothing-here\nCaption <b>.\n```\n"))
    assert 'class="figure-missing"' in html and "se2/nothing-here" in html
    assert "<b>" not in html


@pytest.fixture
def engine(tmp_path: Path) -> Any:
    from tests.web.conftest import settings_for

    with Engine.open(settings_for(tmp_path)) as eng:
        yield eng


@pytest.fixture
def client(engine: Engine) -> Any:
    from slamcourse.web.app import create_app
    from tests.web.conftest import HOST, TOKEN

    return create_app(engine, token=TOKEN, hosts=[HOST]).test_client()
