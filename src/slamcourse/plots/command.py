"""``slamcourse plot ID [--out FILE.svg]``: the picture the browser shows, for the terminal."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from slamcourse.errors import UsageError


def plot_command(
    *, course: str | None, exercise_id: str, out_file: str | None, say: Callable[[str], None]
) -> int:
    """Write the SVG picture of the learner's variant of ``exercise_id`` (stdout without a file)."""
    from slamcourse.engine import Engine
    from slamcourse.plots.registry import has_plot, plot_for
    from slamcourse.settings import Settings

    with Engine.open(Settings.from_env(course=course)) as engine:
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
            )
    if out_file is None:
        say(svg)
        return 0
    path = Path(out_file)
    try:
        path.write_text(svg + "\n", encoding="utf-8")
    except OSError as exc:
        raise UsageError(f"cannot write {path}: {exc.strerror or exc}") from exc
    say(f"Wrote the picture of {exercise_id} (your variant) to {path}")
    return 0
