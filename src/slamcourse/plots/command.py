"""``slamcourse plot ID [--out FILE.svg | --out -]``: a picture the browser shows, for the terminal.

``ID`` is an exercise (the picture of the learner's own variant) or a prose figure of a chapter
(``<chapter-id>/<figure-name>``, as placed by a ```{figure} ID``` block). A terminal cannot show
SVG, so without ``--out`` the picture is written to the learner's workspace
(:func:`picture_path`) and one line says where; ``--out -`` prints the SVG itself.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from slamcourse.errors import UsageError

FIGURES_FOLDER = "figures"


def picture_path(workspace: Path, picture_id: str, *, exercise: bool) -> Path:
    """Where the terminal writes a picture: ``<workspace>/figures/<chapter>/<name>.svg`` for a
    prose figure, ``…/<chapter>/exercise-<slug>.svg`` for an exercise's picture."""
    chapter, _, name = picture_id.partition("/")
    safe = "".join(c if c.isalnum() or c in "-_" else "-" for c in name) or "figure"
    name = f"exercise-{safe}.svg" if exercise else f"{safe}.svg"
    return workspace / FIGURES_FOLDER / chapter / name


def write_svg(path: Path, svg: str) -> Path:
    """Write ``svg`` to ``path``, creating folders; an unchanged file is left alone.
    :class:`UsageError` when it cannot be written."""
    data = svg + "\n"
    try:
        if not (path.is_file() and path.read_text(encoding="utf-8") == data):
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(data, encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = getattr(exc, "strerror", None) or exc
        raise UsageError(f"cannot write {path}: {reason}") from exc
    return path


def figure_file(workspace: Path, figure_id: str) -> Path | None:
    """Draw the prose figure ``figure_id`` into the workspace; its path, or None when no plots
    module defines it (or its drawing fails: `slamcourse validate` reports both)."""
    from slamcourse.plots.registry import figure_svg

    try:
        svg = figure_svg(figure_id)
    except Exception:  # a drawing bug: the prose is still shown
        return None
    if svg is None:
        return None
    try:
        return write_svg(picture_path(workspace, figure_id, exercise=False), svg)
    except UsageError:
        return None


def _exercise_svg(engine: object, exercise_id: str) -> str:
    from slamcourse.engine import Engine
    from slamcourse.plots.registry import has_plot, plot_for

    assert isinstance(engine, Engine)
    prompt = engine.pose(exercise_id)
    spec = engine.exercise(exercise_id)
    solved = engine.state(exercise_id).status != "pending"
    svg = plot_for(exercise_id, spec.tags, dict(prompt.variant.params), solved=solved)
    if svg is None and has_plot(exercise_id, spec.tags, prompt.variant.params):
        raise UsageError(
            f"the picture of {exercise_id} shows its answer: it is drawn once the exercise "
            "is solved or given up"
        )
    if svg is None:
        with_pictures = [
            ex
            for ch in engine.chapters()
            for ex in ch.exercise_ids
            if has_plot(ex, engine.exercise(ex).tags, engine.variant(ex).params)
        ]
        raise UsageError(
            f"{exercise_id} has no picture; these exercises have one: "
            + ", ".join(with_pictures)
            + " (and every figure of the chapters' prose, by its id)"
        )
    return svg


def plot_command(
    *, course: str | None, exercise_id: str, out_file: str | None, say: Callable[[str], None]
) -> int:
    """Draw the picture of the learner's variant of an exercise, or a prose figure, and write
    it to ``out_file`` (``-``: stdout), else to the workspace's ``figures`` folder."""
    from slamcourse.engine import Engine
    from slamcourse.plots.registry import FIGURES, figure_svg
    from slamcourse.settings import Settings

    settings = Settings.from_env(course=course)
    with Engine.open(settings) as engine:
        ids = engine.course.exercise_ids
        if exercise_id not in ids and exercise_id not in FIGURES:
            from slamcourse.course.schema import suggest

            raise UsageError(
                f"no exercise or figure '{exercise_id}' in this course"
                f"{suggest(exercise_id, [*ids, *FIGURES])} (slamcourse list shows the "
                "exercises; a figure's id is in its chapter, e.g. ```{figure} se2/frames)"
            )
        is_exercise = exercise_id in ids
        if is_exercise:
            svg = _exercise_svg(engine, exercise_id)
            what = f"the picture of {exercise_id} (your variant)"
        else:
            svg = figure_svg(exercise_id) or ""
            what = f"figure {exercise_id}"
    if out_file == "-":
        say(svg)
        return 0
    if out_file is None:
        path = picture_path(settings.workspace, exercise_id, exercise=is_exercise)
    else:
        path = Path(out_file)
    written = write_svg(path, svg)
    say(f"Wrote {what} to {written} (SVG: open it in a browser or an image viewer)")
    return 0
