"""Load a course: a cheap index of chapters (for ordering) and exercises one at a time.

Only what a command needs is read: ``check`` loads one YAML file and one reference module;
``next`` reads the chapter index; ``validate`` loads everything. Every problem is collected as
``path:line: message`` and loading goes on, so one broken exercise does not hide the others.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from slamcourse.course.model import (
    FORMAT_VERSION,
    Chapter,
    ChapterFigure,
    ExerciseSpec,
    Misconception,
    ParamSpec,
    Text,
    Tolerance,
)
from slamcourse.course.schema import Checker, suggest
from slamcourse.course.yamlio import LineDict, LineList, load_yaml
from slamcourse.errors import CourseError, Problem, UsageError, relpath

__all__ = [
    "Course",
    "chapter_segments",
    "directive_id",
    "figure_id",
    "load_course",
    "load_exercise",
    "relpath",
]

_ID = re.compile(r"^[a-z0-9]+(?:-[a-z0-9]+)*$")
_FENCE = re.compile(r"^(?P<fence>`{3,}|~{3,})(?P<info>.*)$")
_FRONT = re.compile(r"\A---[ \t]*\n(?P<body>.*?\n)---[ \t]*(?:\n|\Z)", re.S)

COMMON_KEYS = {
    "format": True,
    "id": True,
    "kind": True,
    "title": True,
    "prompt": True,
    "explanation": True,
    "parameters": False,
    "require": False,
    "reference": False,
    "tolerance": False,
    "hints": False,
    "misconceptions": False,
    "tags": False,
}
CHAPTER_KEYS = {"id": True, "title": True, "summary": False}


def directive_id(info: str) -> str | None:
    """The exercise id of a fenced block's info string ``{exercise} ID`` (``""`` when the id is
    missing), or None when the block is not an exercise directive. The one parser of it."""
    words = info.split(None, 1)
    if not words or words[0] != "{exercise}":
        return None
    return words[1].strip() if len(words) > 1 else ""


def figure_id(info: str) -> str | None:
    """The figure id of a fenced block's info string ``{figure} ID`` (``""`` when the id is
    missing), or None when the block is not a figure. The block's content is the caption."""
    words = info.split(None, 1)
    if not words or words[0] != "{figure}":
        return None
    return words[1].strip() if len(words) > 1 else ""


def _directive(line: str) -> tuple[str, str] | None:
    """``(fence, exercise id)`` when ``line`` opens an exercise directive block."""
    match = _FENCE.match(line)
    if match is None:
        return None
    ex_id = directive_id(match.group("info"))
    return None if ex_id is None or " " in ex_id else (match.group("fence"), ex_id)


def read_course_file(path: Path, root: Path) -> str:
    """The text of a course file, decoded once, here, with one policy: the file must be
    UTF-8. A byte that is not, or a file that cannot be read (missing, a directory, a symlink
    loop, no permission), is a :class:`CourseError` naming ``path:line``, never a traceback."""
    rel = relpath(path, root)
    try:
        data = path.read_bytes()
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise CourseError(
            Problem(rel, None, f"cannot read this file ({reason}); fix or remove it")
        ) from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        column = exc.start - data.rfind(b"\n", 0, exc.start)
        raise CourseError(
            Problem(
                rel,
                line,
                f"byte 0x{data[exc.start]:02x} (column {column}) is not UTF-8; "
                "save the file as UTF-8",
            )
        ) from None


class Course:
    """A course folder: chapters (indexed on first use) and exercises (loaded on demand).

    ``check`` needs one exercise file and no index at all; ``next`` and ``list`` need the
    chapter order; ``validate`` needs everything.
    """

    def __init__(self, root: Path) -> None:
        self.root = root
        self._chapters: list[Chapter] | None = None
        self._problems: list[Problem] = []
        self._figures_checked = False
        self._exercises: dict[str, ExerciseSpec] = {}

    def __repr__(self) -> str:
        return f"Course({self.root})"

    @property
    def chapters(self) -> list[Chapter]:
        if self._chapters is None:
            self._chapters, self._problems = _index_course(self.root)
        return self._chapters

    @property
    def problems(self) -> list[Problem]:
        """Problems found while indexing the chapters, and figures no plots module draws.

        The figure ids are checked here, not while indexing: that imports the pictures'
        registry, which ``next`` and ``check`` have no need of."""
        _ = self.chapters
        if not self._figures_checked:
            self._figures_checked = True
            self._problems.extend(figure_problems(self.chapters, self.root))
        return self._problems

    @property
    def exercise_ids(self) -> list[str]:
        return [ex for ch in self.chapters for ex in ch.exercises]

    def chapter(self, chapter_id: str) -> Chapter:
        for ch in self.chapters:
            if ch.id == chapter_id:
                return ch
        raise UsageError(
            f"no chapter '{chapter_id}'{suggest(chapter_id, [c.id for c in self.chapters])}"
        )

    def chapter_of(self, exercise_id: str) -> Chapter:
        for ch in self.chapters:
            if exercise_id in ch.exercises:
                return ch
        raise self._unknown(exercise_id)

    def exercise_path(self, exercise_id: str) -> Path:
        chapter, _, slug = exercise_id.partition("/")
        return self.root / "exercises" / chapter / f"{slug}.yaml"

    def exercise(self, exercise_id: str) -> ExerciseSpec:
        """Load (once) and return one exercise; :class:`UsageError` for an unknown id."""
        if exercise_id in self._exercises:
            return self._exercises[exercise_id]
        path = self.exercise_path(exercise_id)
        if "/" not in exercise_id or not path.is_file():
            raise self._unknown(exercise_id)
        spec = load_exercise(path, self.root)
        self._exercises[exercise_id] = spec
        return spec

    def _unknown(self, exercise_id: str) -> UsageError:
        hint = suggest(exercise_id, self.exercise_ids)
        return UsageError(
            f"no exercise '{exercise_id}' in this course{hint} "
            "(slamcourse list shows every exercise id)"
        )


def load_course(root: Path) -> Course:
    """The course at ``root`` (chapters are indexed when first needed)."""
    return Course(root)


def _index_course(root: Path) -> tuple[list[Chapter], list[Problem]]:
    """Index the chapters of the course at ``root`` (reads only the Markdown files)."""
    chapters: list[Chapter] = []
    problems: list[Problem] = []
    seen: dict[str, str] = {}
    files = sorted((root / "chapters").glob("*.md"))
    for number, path in enumerate(files, start=1):
        try:
            chapter = _index_chapter(path, root, number, problems)
        except CourseError as exc:
            problems.extend(exc.problems)
            continue
        rel = relpath(path, root)
        if chapter.id in seen:
            problems.append(
                Problem(
                    rel,
                    2,
                    f"chapter id '{chapter.id}' is also used by "
                    f"{seen[chapter.id]}; chapter ids must be unique",
                )
            )
            continue
        seen[chapter.id] = rel
        chapters.append(chapter)
    placed: dict[str, str] = {}
    for chapter in chapters:
        rel = relpath(chapter.path, root)
        for ex_id in list(chapter.exercises):
            line = chapter.exercise_lines[ex_id]
            if ex_id in placed:
                problems.append(
                    Problem(
                        rel,
                        line,
                        f"exercise '{ex_id}' is already placed in "
                        f"{placed[ex_id]}; place each exercise once",
                    )
                )
                chapter.exercises.remove(ex_id)
            placed[ex_id] = rel
    if not files:
        problems.append(
            Problem(
                relpath(root / "chapters", root),
                None,
                "no chapters: add chapters/01-<id>.md (see docs/authoring.md)",
            )
        )
    return chapters, problems


def figure_problems(chapters: list[Chapter], root: Path) -> list[Problem]:
    """``path:line`` problems for every placed figure that no ``plots/ch_*.py`` module defines."""
    from slamcourse.plots.registry import FIGURES

    out = []
    for chapter in chapters:
        for fig in chapter.figures:
            if fig.id in FIGURES:
                continue
            ours = sorted(f for f in FIGURES if f.startswith(chapter.id + "/"))
            hint = suggest(fig.id, list(FIGURES)) or (
                f" (this chapter's figures: {', '.join(ours)})" if ours else ""
            )
            module = "ch_" + chapter.id.replace("-", "_")
            out.append(
                Problem(
                    relpath(chapter.path, root),
                    fig.line,
                    f"figure '{fig.id}' is not drawn by any plots module: define it in "
                    f"FIGURES of src/slamcourse/plots/{module}.py, or fix the id{hint}",
                )
            )
    return out


def _figure_block(
    lines: list[str], start: int, fence: str, fig_id: str, chapter_id: str, check: Checker
) -> tuple[ChapterFigure | None, int]:
    """The figure whose block opens at ``lines[start]`` and the index of its closing fence."""
    lineno = start + 1
    end = start + 1
    while end < len(lines) and not lines[end].strip().startswith(fence):
        end += 1
    if end == len(lines):
        check.add(lineno, f"figure block '{fig_id}' is never closed: end it with a line {fence}")
        return None, end
    caption = "\n".join(lines[start + 1 : end]).strip()
    if not fig_id:
        check.add(
            lineno,
            f"figure directive without an id: write ```{{figure}} {chapter_id}/<figure-name>",
        )
        return None, end
    if " " in fig_id or "/" not in fig_id:
        check.add(
            lineno,
            f"figure id '{fig_id}' must look like '<chapter-id>/<figure-name>' (no spaces)",
        )
        return None, end
    if not caption:
        check.add(
            lineno,
            f"figure '{fig_id}' has no caption: write a one-paragraph caption (Markdown) inside "
            "the block, saying what the reader should see",
        )
        return None, end
    return ChapterFigure(fig_id, lineno, caption), end


def _index_chapter(path: Path, root: Path, number: int, problems: list[Problem]) -> Chapter:
    rel = relpath(path, root)
    text = read_course_file(path, root)
    check = Checker(rel)
    match = _FRONT.match(text)
    fallback = re.sub(r"^\d+-", "", path.stem)
    if not match:
        raise CourseError(
            Problem(
                rel,
                1,
                "missing front matter: start the file with '---', "
                "'id: <chapter-id>', 'title: <title>', '---'",
            )
        )
    meta = load_yaml(match.group("body"), rel, first_line=2)
    if not isinstance(meta, LineDict):
        raise CourseError(Problem(rel, 2, "front matter must be 'key: value' lines"))
    check.keys(meta, CHAPTER_KEYS, [k for k, req in CHAPTER_KEYS.items() if req], "front matter")
    chapter_id = check.typed(meta, "id", str, fallback)
    if not _ID.match(chapter_id):
        check.add(
            meta.line_of("id"),
            f"chapter id '{chapter_id}' must be lowercase words "
            "joined by '-' (e.g. 'observation-model')",
        )
    chapter = Chapter(
        chapter_id,
        check.typed(meta, "title", str, fallback),
        path,
        number,
        check.typed(meta, "summary", str, ""),
    )
    lines = text.splitlines()
    skip_to = -1
    for lineno, line in enumerate(lines, start=1):
        if lineno - 1 <= skip_to:
            continue
        opening = _FENCE.match(line)
        fig_id = figure_id(opening.group("info")) if opening else None
        if opening is not None and fig_id is not None:
            figure, skip_to = _figure_block(
                lines, lineno - 1, opening.group("fence"), fig_id, chapter_id, check
            )
            if figure is not None:
                chapter.figures.append(figure)
            continue
        found = _directive(line)
        if found is None:
            continue
        ex_id = found[1]
        if not ex_id:
            check.add(
                lineno,
                "exercise directive without an id: write ```{exercise} "
                f"{chapter_id}/<exercise-slug>",
            )
        elif not ex_id.startswith(chapter_id + "/"):
            check.add(
                lineno,
                f"exercise '{ex_id}' placed in chapter '{chapter_id}': exercise "
                f"ids of this chapter start with '{chapter_id}/'",
            )
        elif not (root / "exercises" / f"{ex_id}.yaml").is_file():
            check.add(lineno, f"exercise '{ex_id}' has no file exercises/{ex_id}.yaml")
        elif ex_id in chapter.exercise_lines:
            check.add(
                lineno,
                f"exercise '{ex_id}' is placed twice in this chapter "
                f"(first at line {chapter.exercise_lines[ex_id]})",
            )
        else:
            chapter.exercises.append(ex_id)
            chapter.exercise_lines[ex_id] = lineno
    problems.extend(check.problems)
    return chapter


def chapter_segments(chapter: Chapter) -> list[tuple[str | None, str]]:
    """The chapter's Markdown split at exercise directives: ``(exercise id or None, prose)``.

    The prose before an exercise's directive is its context; the last segment has id ``None``.
    """
    text = read_course_file(chapter.path, chapter.path.parent.parent)
    match = _FRONT.match(text)
    body = text[match.end() :] if match else text
    segments: list[tuple[str | None, str]] = []
    buf: list[str] = []
    fence: str | None = None
    pending: str | None = None
    for line in body.splitlines(keepends=True):
        if fence is not None:  # inside a directive block: skip to its closing fence
            if line.strip().startswith(fence):
                segments.append((pending, "".join(buf)))
                buf, fence, pending = [], None, None
            continue
        found = _directive(line.rstrip("\n"))
        if found is not None and found[1]:
            fence, pending = found
            continue
        buf.append(line)
    segments.append((None, "".join(buf)))
    return segments


# --------------------------------------------------------------------------- exercises


def load_exercise(path: Path, root: Path) -> ExerciseSpec:
    """Parse and check one exercise file; raise :class:`CourseError` with every problem."""
    from slamcourse.kinds import get_kind, kind_names

    rel = relpath(path, root)
    raw = load_yaml(read_course_file(path, root), rel)
    check = Checker(rel)
    if not isinstance(raw, LineDict):
        raise CourseError(
            Problem(rel, 1, "an exercise file must be a mapping of 'key: value' lines")
        )
    version = raw.get("format")
    if version is None:
        check.add(raw.line, f"missing 'format: {FORMAT_VERSION}' (the exercise format version)")
    elif not isinstance(version, int) or isinstance(version, bool) or version < 1:
        check.add(
            raw.line_of("format"), f"'format' must be a whole number such as {FORMAT_VERSION}"
        )
    elif version > FORMAT_VERSION:
        raise CourseError(
            Problem(
                rel,
                raw.line_of("format"),
                f"format {version} is newer than this slamcourse understands "
                f"(up to {FORMAT_VERSION}); upgrade slamcourse",
            )
        )
    kind_name = check.typed(raw, "kind", str, "")
    kind = None
    if kind_name:
        if kind_name in kind_names():
            kind = get_kind(kind_name)
        else:
            check.add(
                raw.line_of("kind"),
                f"unknown kind '{kind_name}'{suggest(kind_name, kind_names())}"
                f" (kinds: {', '.join(kind_names())})",
            )
    allowed = dict(COMMON_KEYS)
    if kind is not None:
        allowed.update(kind.keys)
    if kind is not None or not kind_name:  # with an unknown kind, its keys cannot be judged
        check.keys(raw, allowed, [k for k, req in allowed.items() if req], "the exercise")

    expected_id = f"{path.parent.name}/{path.stem}"
    ex_id = check.typed(raw, "id", str, expected_id)
    if ex_id != expected_id:
        check.add(
            raw.line_of("id"),
            f"id '{ex_id}' does not match the file's path; the id of "
            f"exercises/{expected_id}.yaml must be '{expected_id}'",
        )
    slug = expected_id.split("/")[1]
    if not _ID.match(slug):
        check.add(1, f"file name '{path.name}': use lowercase words joined by '-'")

    spec = ExerciseSpec(
        id=expected_id,
        chapter=path.parent.name,
        path=path,
        course_root=root,
        kind=kind_name,
        title=check.typed(raw, "title", str, slug),
        prompt=_text(raw, "prompt", check),
        explanation=_text(raw, "explanation", check),
        parameters=_parameters(raw, check),
        require=_texts(raw, "require", check),
        reference=check.typed(raw, "reference", str),
        reference_line=raw.line_of("reference"),
        tolerance=_tolerance(raw, check),
        hints=_texts(raw, "hints", check),
        misconceptions=_misconceptions(raw, check),
        line=raw.line,
        tags=tuple(str(t) for t in check.typed(raw, "tags", list, [])),
    )
    if kind is not None:
        if kind.reference_required and not spec.reference and not kind.reference_optional(raw):
            check.add(
                raw.line,
                f"a {kind_name} exercise needs 'reference: <function name in "
                "reference.py>' (the answer must come from reference code)",
            )
        spec.options = kind.parse(spec, raw, check)
    if spec.reference and not spec.reference_path.is_file():
        check.add(
            spec.reference_line,
            f"'reference: {spec.reference}' but there is no {relpath(spec.reference_path, root)}",
        )
    if check.problems:
        raise CourseError(check.problems)
    return spec


def _text(raw: LineDict, key: str, check: Checker) -> Text:
    value = check.typed(raw, key, str, "")
    return Text(value, raw.text_line(key))


def _texts(raw: LineDict, key: str, check: Checker) -> tuple[Text, ...]:
    items = check.typed(raw, key, list, [])
    out = []
    for i, item in enumerate(items):
        line = items.line_of(i) if isinstance(items, LineList) else raw.line_of(key)
        if not isinstance(item, str):
            check.add(line, f"each entry of '{key}' must be text, not {item!r}")
            continue
        out.append(Text(item, line))
    return tuple(out)


def _tolerance(raw: LineDict, check: Checker) -> Tolerance:
    if "tolerance" not in raw:
        return Tolerance()
    data = check.mapping(raw["tolerance"], raw.line_of("tolerance"), "'tolerance'")
    if data is None:
        return Tolerance()
    check.keys(data, {"rtol", "atol"}, (), "'tolerance'")
    rtol = check.typed(data, "rtol", float, 0.01)
    atol = check.typed(data, "atol", float, 1e-9)
    if rtol < 0 or atol < 0:
        check.add(data.line, "tolerances must not be negative")
    return Tolerance(float(rtol), float(atol))


_DISTS = {"int": "int-range", "uniform": "range", "choice": "list", "value": "any", "expr": "text"}


def _parameters(raw: LineDict, check: Checker) -> tuple[ParamSpec, ...]:
    if "parameters" not in raw:
        return ()
    data = check.mapping(raw["parameters"], raw.line_of("parameters"), "'parameters'")
    if data is None:
        return ()
    specs = []
    for name, value in data.items():
        line = data.line_of(name)
        if not re.match(r"^[A-Za-z_][A-Za-z0-9_]*$", name):
            check.add(line, f"parameter name '{name}' must be a Python identifier")
            continue
        item = check.mapping(value, line, f"parameter '{name}'")
        if item is None:
            continue
        check.keys(item, {*_DISTS, "canonical", "round"}, (), f"parameter '{name}'")
        found = check.distribution(item, _DISTS, f"parameter '{name}'")
        if found is None:
            continue
        dist, args = found
        if dist in ("int", "uniform", "choice") and "canonical" not in item:
            check.add(
                line,
                f"parameter '{name}' needs 'canonical:' (its value in the lesson, "
                "used by variant 0)",
            )
            continue
        outside = _canonical_outside(dist, args, item.get("canonical"))
        if outside:
            check.add(item.line_of("canonical"), f"parameter '{name}': {outside}")
            continue
        if "canonical" in item and dist in ("value", "expr"):
            check.add(
                item.line_of("canonical"),
                f"parameter '{name}' is fixed by '{dist}'; remove 'canonical'",
            )
        rounding = check.typed(item, "round", int)
        specs.append(ParamSpec(name, line, dist, args, item.get("canonical"), rounding))
    return tuple(specs)


def _canonical_outside(dist: str, args: tuple[Any, ...], canonical: Any) -> str | None:
    """Why a literal ``canonical`` value cannot be drawn from its own distribution, or None.

    A formula (text, e.g. ``"pi/4"``) is checked when variant 0 is drawn
    (:func:`slamcourse.course.variants.variant`), since it may use other parameters."""
    if canonical is None or (isinstance(canonical, str) and dist != "choice"):
        return None
    if dist == "choice":
        if canonical in args:
            return None
        return f"canonical {canonical!r} is not one of its choices {list(args)}"
    if dist not in ("int", "uniform"):
        return None
    whole = dist == "int"
    number = int if whole else (int, float)
    if not isinstance(canonical, number) or isinstance(canonical, bool):
        return f"canonical {canonical!r} must be {'a whole number' if whole else 'a number'}"
    if not args[0] <= canonical <= args[1]:
        return (
            f"canonical {canonical} is outside its own range [{args[0]}, {args[1]}]; "
            "widen the range or fix the value"
        )
    return None


def _misconceptions(raw: LineDict, check: Checker) -> tuple[Misconception, ...]:
    items = check.typed(raw, "misconceptions", list, [])
    out: list[Misconception] = []
    ids: set[str] = set()
    for i, item in enumerate(items):
        line = items.line_of(i) if isinstance(items, LineList) else raw.line
        data = check.mapping(item, line, "a misconception")
        if data is None:
            continue
        check.keys(
            data, {"id", "compute", "function", "message"}, ("id", "message"), "a misconception"
        )
        mid = check.typed(data, "id", str, f"misconception-{i + 1}")
        if mid in ids:
            check.add(line, f"misconception id '{mid}' is used twice")
        ids.add(mid)
        message = check.typed(data, "message", str, "")
        out.append(
            Misconception(
                mid,
                Text(message, data.text_line("message")),
                line,
                check.typed(data, "compute", str),
                check.typed(data, "function", str),
            )
        )
    return tuple(out)
