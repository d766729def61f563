"""The course data model: what the loader produces and the engine, kinds and validator consume."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

FORMAT_VERSION = 1  # the newest exercise-file format this engine understands


@dataclass(frozen=True)
class Text:
    """A template or message from a course file, with the file line where its text starts."""

    source: str
    line: int


@dataclass(frozen=True)
class ParamSpec:
    """How one parameter is drawn. ``dist`` is ``int``, ``uniform``, ``choice``, ``value`` or
    ``expr``; ``args`` its arguments; ``canonical`` the value of variant 0."""

    name: str
    line: int
    dist: str
    args: tuple[Any, ...]
    canonical: Any = None
    round: int | None = None


@dataclass(frozen=True)
class Tolerance:
    """Accept ``|a − b| ≤ atol + rtol·|b|`` with ``b`` the reference value."""

    rtol: float = 0.01
    atol: float = 1e-9


@dataclass(frozen=True)
class Misconception:
    """A declared wrong idea: ``compute`` (numeric kinds) or ``function`` (code) names the
    reference.py function that reproduces it; ``message`` is shown when an answer matches it."""

    id: str
    message: Text
    line: int
    compute: str | None = None
    function: str | None = None


@dataclass(frozen=True)
class Variant:
    """One concrete version of an exercise: ``seed`` 0 is canonical (the lesson's own numbers)."""

    seed: int
    params: dict[str, Any]


@dataclass
class ExerciseSpec:
    """One exercise as declared in ``exercises/<chapter>/<slug>.yaml``."""

    id: str
    chapter: str
    path: Path
    kind: str
    title: str
    prompt: Text
    explanation: Text
    course_root: Path
    parameters: tuple[ParamSpec, ...] = ()
    require: tuple[Text, ...] = ()
    reference: str | None = None
    reference_line: int = 0
    tolerance: Tolerance = Tolerance()
    hints: tuple[Text, ...] = ()
    misconceptions: tuple[Misconception, ...] = ()
    tags: tuple[str, ...] = ()
    options: Any = None  # kind-specific settings, parsed by the kind
    line: int = 1

    @property
    def slug(self) -> str:
        return self.id.split("/", 1)[1]

    @property
    def reference_path(self) -> Path:
        return self.path.parent / "reference.py"

    @property
    def has_variants(self) -> bool:
        return any(p.dist not in ("value", "expr") for p in self.parameters)


@dataclass(frozen=True)
class ChapterFigure:
    """A prose figure placed by a ```{figure} ID``` block: its registry id, the line of the
    block and its caption (Markdown, the block's content)."""

    id: str
    line: int
    caption: str


@dataclass
class Chapter:
    """A chapter as indexed from ``chapters/NN-slug.md`` (prose is read only when shown)."""

    id: str
    title: str
    path: Path
    number: int
    summary: str = ""
    exercises: list[str] = field(default_factory=list)
    exercise_lines: dict[str, int] = field(default_factory=dict)
    figures: list[ChapterFigure] = field(default_factory=list)
