"""A submission: what a learner hands in, and how the grader reads one it cannot trust.

A submission is a folder or a zip holding ``submission.json`` (the manifest, specified field by
field in docs/submissions.md) and, for code exercises, the learner's files under ``code/``.
:func:`build` makes one from a learner's progress and workspace; :func:`write` saves it;
:func:`read` loads one for grading without ever extracting it: every file is read into memory
through :class:`Limits`, so nothing in a submission can write anywhere.
"""

from __future__ import annotations

import hashlib
import io
import json
import os
import re
import stat
import zipfile
from collections.abc import Iterator
from dataclasses import dataclass, field, replace
from pathlib import Path, PurePosixPath
from typing import TYPE_CHECKING, Any

from slamcourse.errors import SlamcourseError

if TYPE_CHECKING:
    from slamcourse.engine import Engine

FORMAT = 1
"""The manifest's ``format``: bumped whenever a field changes meaning."""
MANIFEST = "submission.json"
LEARNER_ID_PREFIX = "learner-"
_SAFE_PART = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")


class SubmissionError(SlamcourseError):
    """A submission cannot be read or is not what it claims; one submission's problem only.

    The batch grader reports it for that submission and goes on with the others.
    """


@dataclass(frozen=True)
class Limits:
    """What a grader accepts from one submission before it refuses to read further."""

    max_entries: int = 2000
    max_total_bytes: int = 32 * 1024 * 1024
    max_file_bytes: int = 2 * 1024 * 1024


# ------------------------------------------------------------------------------ identity


def course_hash(root: Path) -> str:
    """``sha256:<hex>`` over every file of ``chapters/`` and ``exercises/`` (relative POSIX
    path, then content, in path order; ``__pycache__``, ``.pyc`` and hidden files and folders
    left out), so the same course content has the same hash on every machine, in a checkout
    or installed, and any edit changes it."""
    digest = hashlib.sha256()
    files: list[tuple[str, Path]] = []
    for top in ("chapters", "exercises"):
        base = root / top
        for dirpath, dirnames, filenames in os.walk(base):
            dirnames[:] = sorted(
                d for d in dirnames if d != "__pycache__" and not d.startswith(".")
            )
            for name in filenames:
                if name.endswith(".pyc") or name.startswith("."):
                    continue
                path = Path(dirpath) / name
                files.append((path.relative_to(root).as_posix(), path))
    for rel, path in sorted(files):
        data = path.read_bytes()
        digest.update(f"{rel}\0{len(data)}\0".encode())
        digest.update(data)
    return "sha256:" + digest.hexdigest()


def learner_id(learner_seed: int) -> str:
    """The stable id of an unnamed learner: ``learner-`` and 12 hex digits of
    ``sha256("slamcourse-learner:<seed>")``. It names the learner without revealing the seed."""
    digest = hashlib.sha256(f"slamcourse-learner:{learner_seed}".encode()).hexdigest()
    return LEARNER_ID_PREFIX + digest[:12]


# ------------------------------------------------------------------------------ the manifest


@dataclass(frozen=True)
class Answer:
    """One exercise's answer: ``text`` (every kind but code) or ``file`` (code, a path inside the
    submission); ``variant`` the seed the learner was given (0 when the exercise has none);
    ``attempts`` the learner's counted attempts, if recorded."""

    exercise: str
    variant: int
    text: str | None = None
    file: str | None = None
    attempts: int | None = None
    origin: str | None = None  # a notebook's cell (``ch.ipynb, cell 7``); None: the manifest
    own_variant: bool = False  # the variant is the learner's own, set by the grader

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"exercise": self.exercise, "variant": self.variant}
        if self.file is not None:
            out["file"] = self.file
        else:
            out["answer"] = self.text
        if self.attempts is not None:
            out["attempts"] = self.attempts
        return out


@dataclass(frozen=True)
class Manifest:
    learner_id: str
    learner_seed: int
    engine: str
    course_version: str
    course_hash: str
    answers: tuple[Answer, ...]
    learner_name: str | None = None
    created: str | None = None

    def to_dict(self) -> dict[str, Any]:
        return {
            "format": FORMAT,
            "learner": {
                "id": self.learner_id,
                "name": self.learner_name,
                "seed": self.learner_seed,
            },
            "engine": self.engine,
            "course": {"version": self.course_version, "hash": self.course_hash},
            "created": self.created,
            "answers": [a.to_dict() for a in self.answers],
        }


@dataclass
class Submission:
    """A submission read into memory: the manifest and the code files it names."""

    manifest: Manifest
    files: dict[str, bytes] = field(default_factory=dict)
    notes: tuple[str, ...] = ()  # what reading it found worth saying (graded as warnings)

    def source(self, answer: Answer) -> bytes:
        assert answer.file is not None
        try:
            return self.files[answer.file]
        except KeyError:
            raise SubmissionError(
                f"{answer.exercise}: the file {answer.file} named in {MANIFEST} is missing"
            ) from None


def code_path(exercise_id: str) -> str:
    """Where a code exercise's file lives inside a submission: ``code/<exercise id>.py``."""
    return f"code/{exercise_id}.py"


def build(
    engine: Engine, *, learner_name: str | None = None, created: str | None = None
) -> Submission:
    """The learner's submission: per exercise of the course, the latest attempt (text kinds, on
    the learner's own variant) or the workspace file (code kinds), with counted attempts."""
    from slamcourse import __version__
    from slamcourse.course.locate import bundled_course_root, course_root

    if learner_name is not None and not _printable_name(learner_name):
        from slamcourse.errors import UsageError

        raise UsageError("--learner: give 1 to 100 printable characters (a name or an id)")
    store = engine.progress
    if store is None:
        raise SubmissionError("building a submission needs the learner's progress")
    root = course_root(engine.settings.course)
    states = store.states()
    latest: dict[str, str] = {}
    known = set(engine.course.exercise_ids)
    for attempt in store.attempts():  # oldest first: the last one wins
        ex = attempt.exercise_id
        if ex in known and attempt.reset_at is None and attempt.variant == engine.variant(ex).seed:
            latest[ex] = attempt.answer
    answers: list[Answer] = []
    files: dict[str, bytes] = {}
    for ex in engine.course.exercise_ids:
        spec = engine.exercise(ex)
        state = states.get(ex)
        counted = state.attempts if state is not None else 0
        if spec.kind == "code":
            from slamcourse.workspace import exercise_file

            path = exercise_file(spec, engine.settings.workspace)
            if not path.is_file():
                continue
            rel = code_path(ex)
            try:
                files[rel] = path.read_bytes()
            except OSError as exc:
                raise SubmissionError(f"cannot read {path}: {exc.strerror}") from None
            answers.append(Answer(ex, 0, file=rel, attempts=counted))
        elif ex in latest:
            variant = engine.variant(ex).seed
            answers.append(Answer(ex, variant, text=latest[ex], attempts=counted))
    seed = store.learner_seed
    manifest = Manifest(
        learner_id=learner_name or learner_id(seed),
        learner_name=learner_name,
        learner_seed=seed,
        engine=__version__,
        course_version=__version__ if root == bundled_course_root() else "custom",
        course_hash=course_hash(root),
        answers=tuple(answers),
        created=created or _now(),
    )
    return Submission(manifest, files)


def _now() -> str:
    from datetime import UTC, datetime

    return datetime.now(UTC).isoformat(timespec="seconds")


def write(submission: Submission, out: Path) -> Path:
    """Save as a zip (``out`` ends in ``.zip``) or a new folder; returns ``out``."""
    try:
        return _write(submission, out)
    except OSError as exc:
        raise SubmissionError(f"cannot write {out}: {exc.strerror or exc}") from None


def _write(submission: Submission, out: Path) -> Path:
    manifest = json.dumps(submission.manifest.to_dict(), indent=2, ensure_ascii=False) + "\n"
    if out.suffix.lower() == ".zip":
        out.parent.mkdir(parents=True, exist_ok=True)
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
            zf.writestr(MANIFEST, manifest)
            for rel, data in sorted(submission.files.items()):
                zf.writestr(rel, data)
        return out
    if out.exists() and (not out.is_dir() or any(out.iterdir())):
        raise SubmissionError(
            f"{out} exists and is not an empty folder; choose a new folder or a .zip"
        )
    out.mkdir(parents=True, exist_ok=True)
    (out / MANIFEST).write_text(manifest, encoding="utf-8")
    for rel, data in submission.files.items():
        target = out / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
    return out


# ------------------------------------------------------------------------------ reading


def _safe_name(name: str, where: str, *, plain: bool = True) -> str:
    """A path inside a submission: relative, POSIX, no ``..``; with ``plain``, every part made
    of letters, digits, ``_.-`` (what a manifest's ``file`` may name)."""
    if "\\" in name or name.startswith("/") or re.match(r"^[A-Za-z]:", name):
        raise SubmissionError(f"{where}: the entry {name!r} is an absolute path; refusing it")
    parts = PurePosixPath(name).parts
    if not parts or any(p == ".." for p in parts):
        raise SubmissionError(f"{where}: the entry {name!r} points outside the submission")
    if plain and not all(_SAFE_PART.match(p) for p in parts):
        raise SubmissionError(f"{where}: the entry name {name!r} is not a plain file name")
    return "/".join(parts)


def _ignored(name: str) -> bool:
    """Files an archiver or a checkout adds that are no part of the submission: hidden files
    and folders (``.git/``, ``.DS_Store``) and macOS's ``__MACOSX/``."""
    parts = name.split("/")
    return parts[0] == "__MACOSX" or any(p.startswith(".") and p not in (".", "..") for p in parts)


def _read_zip(path: Path, limits: Limits) -> dict[str, bytes]:
    where = path.name
    try:
        zf = zipfile.ZipFile(path)
    except (zipfile.BadZipFile, OSError, EOFError) as exc:
        raise SubmissionError(f"{where} is not a readable zip ({exc}); hand it in again") from None
    files: dict[str, bytes] = {}
    total = 0
    with zf:
        infos = zf.infolist()
        if len(infos) > limits.max_entries:
            raise SubmissionError(
                f"{where} has {len(infos)} entries (at most {limits.max_entries} accepted)"
            )
        for info in infos:
            if info.is_dir():
                continue
            name = _safe_name(info.filename, where, plain=False)
            if _ignored(name):
                continue
            if stat.S_ISLNK(info.external_attr >> 16):
                raise SubmissionError(f"{where}: {name} is a symbolic link; refusing it")
            budget = min(limits.max_file_bytes, limits.max_total_bytes - total)
            try:
                with zf.open(info) as fh:
                    data = _read_capped(fh, budget)
            except (zipfile.BadZipFile, OSError, EOFError, RuntimeError, ValueError) as exc:
                raise SubmissionError(f"{where}: {name} cannot be read ({exc})") from None
            if data is None:
                raise SubmissionError(
                    f"{where}: {name} unpacks to more than the grader accepts "
                    f"({limits.max_file_bytes // 1024} KiB a file, "
                    f"{limits.max_total_bytes // (1024 * 1024)} MiB in all)"
                )
            total += len(data)
            files[name] = data
    return files


def _read_capped(fh: Any, budget: int) -> bytes | None:
    """At most ``budget`` bytes from ``fh``; None when there is more (a zip bomb stops here)."""
    buf = io.BytesIO()
    while True:
        chunk = fh.read(min(65536, budget + 1 - buf.tell()))
        if not chunk:
            return buf.getvalue()
        buf.write(chunk)
        if buf.tell() > budget:
            return None


def _walk_folder(root: Path, limits: Limits) -> Iterator[tuple[str, Path]]:
    count = 0
    for dirpath, dirnames, filenames in os.walk(root, followlinks=False):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
        links = [d for d in dirnames if Path(dirpath, d).is_symlink()]
        for name in sorted(f for f in filenames if not f.startswith(".")) + links:
            count += 1
            if count > limits.max_entries:
                raise SubmissionError(
                    f"{root.name} has more than {limits.max_entries} files; refusing it"
                )
            path = Path(dirpath) / name
            yield path.relative_to(root).as_posix(), path


def _read_folder(root: Path, limits: Limits) -> dict[str, bytes]:
    files: dict[str, bytes] = {}
    total = 0
    for rel, path in _walk_folder(root, limits):
        name = _safe_name(rel, root.name, plain=False)
        if _ignored(name):
            continue
        info = path.lstat()
        if stat.S_ISLNK(info.st_mode):
            raise SubmissionError(f"{root.name}: {name} is a symbolic link; refusing it")
        if not stat.S_ISREG(info.st_mode):
            continue
        budget = min(limits.max_file_bytes, limits.max_total_bytes - total)
        try:
            fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
            with os.fdopen(fd, "rb") as fh:
                data = _read_capped(fh, budget)
        except OSError as exc:
            raise SubmissionError(f"{root.name}: {name} cannot be read ({exc.strerror})") from None
        if data is None:
            raise SubmissionError(f"{root.name}: {name} is larger than the grader accepts")
        total += len(data)
        files[name] = data
    return files


def _read_notebook_file(path: Path, limits: Limits) -> dict[str, bytes]:
    """A submission that is one notebook file: ``{its name: its bytes}``."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
    with os.fdopen(fd, "rb") as fh:
        data = _read_capped(fh, min(limits.max_file_bytes, limits.max_total_bytes))
    if data is None:
        raise SubmissionError(f"{path.name} is larger than the grader accepts")
    return {path.name: data}


def read(path: Path, limits: Limits | None = None) -> Submission:
    """Load a submission (folder, zip, or one ``.ipynb`` notebook) into memory, checking only
    its form; what it claims (course, seeds) is checked by the grader. Notebooks in it add
    their answers (:func:`with_notebooks`)."""
    from slamcourse.batch.notebooks import is_notebook

    limits = limits or Limits()
    try:
        if path.is_symlink():
            raise SubmissionError(f"{path.name} is a symbolic link; pass the real file")
        if path.is_dir():
            files = _read_folder(path, limits)
        elif path.is_file() and is_notebook(path.name):
            files = _read_notebook_file(path, limits)
        elif path.is_file():
            files = _read_zip(path, limits)
        else:
            raise SubmissionError(f"{path}: no such file or folder")
    except OSError as exc:
        raise SubmissionError(f"{path}: cannot be read ({exc.strerror})") from None
    # a zip made by zipping the folder itself: accept one top-level folder around everything
    if MANIFEST not in files:
        tops = {name.split("/", 1)[0] for name in files}
        if len(tops) == 1 and (prefix := tops.pop() + "/") + MANIFEST in files:
            files = {k[len(prefix) :]: v for k, v in files.items() if k.startswith(prefix)}
    if MANIFEST not in files and not any(is_notebook(name) for name in files):
        raise SubmissionError(
            f"{path.name} has no {MANIFEST} and no notebook (.ipynb); see docs/submissions.md"
        )
    manifest = parse_manifest(files.pop(MANIFEST), path.name) if MANIFEST in files else None
    return with_notebooks(manifest, files, path.name)


def with_notebooks(manifest: Manifest | None, files: dict[str, bytes], where: str) -> Submission:
    """A submission whose notebooks' answers join the manifest's (a notebook's answer to an
    exercise the manifest answers too replaces it, with a note); without a manifest, the
    learner and course are the ones the notebooks' outputs name."""
    from slamcourse.batch.notebooks import NotebookError, read_notebooks

    try:
        found = read_notebooks(files)
    except NotebookError as exc:
        raise SubmissionError(f"{where}: {exc}") from None
    if manifest is None:
        manifest = _manifest_from_notebooks(found.identities, where)
    else:
        for name, ident in found.identities.items():
            if ident["learner"]["seed"] != manifest.learner_seed:
                raise SubmissionError(
                    f"{where}: {name} was run by another learner than {MANIFEST} names "
                    "(learner seeds differ); run it again under your own progress and save it"
                )
    if not found.exercises:
        return Submission(manifest, files)
    notes = []
    answers = []
    for answer in manifest.answers:
        if answer.exercise in found.exercises:
            notes.append(
                f"{answer.exercise} is answered both in {MANIFEST} and in a notebook; the "
                "notebook's answer is graded"
            )
        else:
            answers.append(answer)
    files = dict(files)
    for ex, (source, origin) in sorted(found.code.items()):
        rel = f"{origin}#{ex}.py"  # a name no manifest can give (it is not a plain path)
        files[rel] = source.encode("utf-8", "surrogatepass")
        answers.append(Answer(ex, 0, file=rel, origin=origin, own_variant=True))
    for ex, (text, origin) in sorted(found.text.items()):
        answers.append(Answer(ex, 0, text=text, origin=origin, own_variant=True))
    return Submission(replace(manifest, answers=tuple(answers)), files, tuple(notes))


def _manifest_from_notebooks(identities: dict[str, dict[str, Any]], where: str) -> Manifest:
    if not identities:
        raise SubmissionError(
            f"{where} has no {MANIFEST}, and no notebook in it says who ran it: run the "
            "notebook's first code cell (it records your learner id), save, and hand it in "
            f'again (docs/submissions.md, "Notebooks")'
        )
    first = next(iter(identities.values()))
    for name, ident in identities.items():
        if ident["learner"]["seed"] != first["learner"]["seed"]:
            raise SubmissionError(
                f"{where}: its notebooks were run by different learners ({name} differs); "
                "hand in one learner's notebooks"
            )
    learner, course = first["learner"], first["course"]
    fields = {
        "learner.id": learner.get("id"),
        "course.version": course.get("version"),
        "course.hash": course.get("hash"),
        "engine": first.get("engine"),
    }
    for label, value in fields.items():
        if not isinstance(value, str):
            raise SubmissionError(f"{where}: the notebooks' {label} is missing or not text")
    name = learner.get("name")
    return Manifest(
        learner_id=learner["id"],
        learner_name=name if isinstance(name, str) and _printable_name(name) else None,
        learner_seed=learner["seed"],
        engine=first["engine"],
        course_version=course["version"],
        course_hash=course["hash"],
        answers=(),
    )


def parse_manifest(data: bytes, where: str) -> Manifest:
    """``submission.json`` checked field by field; every problem names the field."""
    try:
        raw = json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError) as exc:
        raise SubmissionError(f"{where}: {MANIFEST} is not valid JSON ({exc})") from None
    if not isinstance(raw, dict):
        raise SubmissionError(f"{where}: {MANIFEST} must hold a JSON object")
    fmt = raw.get("format")
    if fmt != FORMAT:
        raise SubmissionError(
            f"{where}: {MANIFEST} has format {fmt!r}; this grader reads format {FORMAT}"
        )
    learner = _field(raw, "learner", dict, where)
    course = _field(raw, "course", dict, where)
    seed = _field(learner, "seed", int, where, "learner.seed")
    if isinstance(seed, bool) or seed < 0:
        raise SubmissionError(f"{where}: learner.seed must be a whole number ≥ 0")
    name = learner.get("name")
    if name is not None and not (isinstance(name, str) and _printable_name(name)):
        raise SubmissionError(
            f"{where}: learner.name must be null or 1 to 100 printable characters"
        )
    answers_raw = _field(raw, "answers", list, where)
    answers: list[Answer] = []
    seen: set[str] = set()
    for i, item in enumerate(answers_raw):
        at = f"answers[{i}]"
        if not isinstance(item, dict):
            raise SubmissionError(f"{where}: {at} must be an object")
        ex = _field(item, "exercise", str, where, f"{at}.exercise")
        if ex in seen:
            raise SubmissionError(f"{where}: {at}: {ex} is answered twice")
        seen.add(ex)
        variant = _field(item, "variant", int, where, f"{at}.variant")
        attempts = item.get("attempts")
        if attempts is not None and (not isinstance(attempts, int) or attempts < 0):
            raise SubmissionError(f"{where}: {at}.attempts must be a whole number ≥ 0")
        if ("file" in item) == ("answer" in item):
            raise SubmissionError(f"{where}: {at} needs exactly one of 'answer' and 'file'")
        if "file" in item:
            rel = _safe_name(_field(item, "file", str, where, f"{at}.file"), where)
            answers.append(Answer(ex, variant, file=rel, attempts=attempts))
        else:
            text = _field(item, "answer", str, where, f"{at}.answer")
            answers.append(Answer(ex, variant, text=text, attempts=attempts))
    created = raw.get("created")
    return Manifest(
        learner_id=_field(learner, "id", str, where, "learner.id"),
        learner_name=name,
        learner_seed=seed,
        engine=_field(raw, "engine", str, where),
        course_version=_field(course, "version", str, where, "course.version"),
        course_hash=_field(course, "hash", str, where, "course.hash"),
        answers=tuple(answers),
        created=created if isinstance(created, str) else None,
    )


def _printable_name(name: str) -> bool:
    return 0 < len(name) <= 100 and name.isprintable() and name.strip() == name


def _field(obj: dict[str, Any], key: str, typ: type, where: str, label: str | None = None) -> Any:
    value = obj.get(key)
    if not isinstance(value, typ) or (typ is int and isinstance(value, bool)):
        raise SubmissionError(
            f"{where}: {MANIFEST} field {label or key} must be a {typ.__name__}, got {value!r}"[
                :300
            ]
        )
    return value
