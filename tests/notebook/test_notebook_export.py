"""`slamcourse export notebooks DIR`: one valid notebook per chapter, prose then each exercise
as cells that check themselves, prose figures inline."""

from __future__ import annotations

import base64
import json
from pathlib import Path

import nbformat
import pytest

from slamcourse.cli import main
from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.errors import UsageError
from slamcourse.notebook.cells import code_answer
from slamcourse.notebook.export import FigureBlock, Prose, export_notebooks, split_figures
from tests.conftest import FIXTURE_COURSE


def _read(path: Path) -> nbformat.NotebookNode:
    nb = nbformat.read(str(path), as_version=4)
    nbformat.validate(nb)
    return nb


def _roles(nb: nbformat.NotebookNode) -> list[tuple[str, str]]:
    return [
        (c.metadata["slamcourse"].get("exercise", ""), c.metadata["slamcourse"]["role"])
        for c in nb.cells
        if "slamcourse" in c.metadata
    ]


def test_the_bundled_course_exports_one_valid_notebook_per_chapter(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from slamcourse.plots import registry

    # the figures' drawings are the plots modules' own tests; here: where each one goes
    def stub(figure_id: str) -> str | None:
        if figure_id not in registry.FIGURES:
            return None
        return f'<svg xmlns="http://www.w3.org/2000/svg"><title>{figure_id}</title></svg>'

    monkeypatch.setattr(registry, "figure_svg", stub)
    course = load_course(bundled_course_root())
    paths = export_notebooks(None, tmp_path / "nb")
    assert [p.name for p in paths] == [f"{c.path.stem}.ipynb" for c in course.chapters]
    for chapter, path in zip(course.chapters, paths, strict=True):
        nb = _read(path)
        assert nb.metadata["slamcourse"]["chapter"] == chapter.id
        assert nb.cells[0].source.startswith(f"# {chapter.number}. ")
        setup = nb.cells[1]
        assert setup.source.startswith("%load_ext slamcourse.notebook")
        assert setup.metadata["slamcourse"] == {"role": "setup", "chapter": chapter.id}
        expected = [(ex, role) for ex in chapter.exercises for role in ("prompt", "answer")]
        assert _roles(nb)[1:] == expected  # every exercise posed, then answered, in order
        for cell in nb.cells:
            meta = cell.metadata.get("slamcourse", {})
            if meta.get("role") != "answer":
                continue
            spec = course.exercise(meta["exercise"])
            if spec.kind == "code":
                found = code_answer(cell.source)
                assert found is not None and found.exercise == spec.id
                assert found.source == spec.options.starter.read_text().rstrip("\n")
            else:
                assert cell.source.endswith(f'check("{spec.id}", "")')
        sources = "".join(c.source for c in nb.cells)
        assert "```{exercise}" not in sources and "```{figure}" not in sources
        blocks = chapter.path.read_text().count("```{figure}")
        assert sum("attachments" in c for c in nb.cells) + sources.count("not drawn here") == blocks


def test_prose_figures_become_attachments(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from slamcourse.plots import registry

    svg = '<svg xmlns="http://www.w3.org/2000/svg"><title>Two poses [drawn]</title></svg>'
    monkeypatch.setitem(registry.FIGURES, "basics/two-poses", lambda: svg)
    course = tmp_path / "course"
    import shutil

    shutil.copytree(FIXTURE_COURSE, course)
    chapter = course / "chapters" / "01-basics.md"
    text = chapter.read_text().replace(
        "Angles are in radians.",
        "Angles are in radians.\n\n```{figure} basics/two-poses\nTwo poses, $x$ apart.\n```\n\n"
        "```{figure} basics/missing\nNot drawn.\n```\n\n````python\n```{figure} not/one\n````\n",
    )
    chapter.write_text(text)
    nb = _read(export_notebooks(course, tmp_path / "nb")[0])
    figures = [c for c in nb.cells if "attachments" in c]
    assert len(figures) == 1
    cell = figures[0]
    assert cell.source.startswith("![Two poses (drawn)](attachment:basics-two-poses.svg)")
    assert "**Figure 1.** Two poses, $x$ apart." in cell.source
    data = cell.attachments["basics-two-poses.svg"]["image/svg+xml"]
    assert base64.b64decode(data).decode() == svg
    sources = "".join(c.source for c in nb.cells)
    assert "**Figure 2.** Not drawn." in sources and "not drawn here" in sources
    assert "```{figure} not/one" in sources  # inside another fence: prose, not a figure


def test_split_figures_keeps_other_fences() -> None:
    parts = list(
        split_figures("a\n~~~{figure} x/y\ncap\n~~~\nb\n```\n{figure} no\n```\n```{figure}\n```\n")
    )
    assert parts[0] == Prose("a\n") and parts[1] == FigureBlock("x/y", "cap")
    assert isinstance(parts[2], Prose) and "{figure} no" in parts[2].markdown


def test_export_command_and_overwrite(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "nb"
    assert main(["--course", str(FIXTURE_COURSE), "export", "notebooks", str(out)]) == 0
    assert "Wrote 2 notebooks" in capsys.readouterr().out
    first = out / "01-basics.ipynb"
    first.write_text("{}")  # a learner's work must not be lost
    assert main(["--course", str(FIXTURE_COURSE), "export", "notebooks", str(out)]) == 2
    assert "--force" in capsys.readouterr().err and first.read_text() == "{}"
    with pytest.raises(UsageError):
        export_notebooks(FIXTURE_COURSE, out)
    args = ["--course", str(FIXTURE_COURSE), "export", "notebooks", str(out), "--force"]
    assert main(args) == 0
    assert json.loads(first.read_text())["nbformat"] == 4
    assert main(["export", "notebooks"]) == 2
    assert main(["export", "gradescope", str(out)]) == 2
