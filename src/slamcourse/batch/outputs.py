"""Writing a batch's results: each file lands inside the output folder, under a name made from
the submission's path as the grader was given it (never from anything inside a submission)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path

from slamcourse.batch import exporters
from slamcourse.batch.grade import SubmissionGrade, output_names
from slamcourse.errors import UsageError


def write_results(
    grades: Sequence[SubmissionGrade], paths: Sequence[Path], fmt: str, out: Path
) -> list[Path]:
    """``json``: ``<out>/<name>.json``; Gradescope, Exercism, PrairieLearn:
    ``<out>/<name>/results.json``; ``junit``: ``<out>/junit.xml``. Returns the files written."""
    if fmt not in exporters.FORMATS:
        raise UsageError(f"unknown format {fmt}; choose one of {', '.join(exporters.FORMATS)}")
    try:
        return _write_results(grades, paths, fmt, out)
    except OSError as exc:
        raise UsageError(f"cannot write the results to {out}: {exc.strerror}") from None


def _write_results(
    grades: Sequence[SubmissionGrade], paths: Sequence[Path], fmt: str, out: Path
) -> list[Path]:
    out.mkdir(parents=True, exist_ok=True)
    root = out.resolve()
    if fmt == "junit":
        target = root / "junit.xml"
        target.write_text(exporters.junit(grades), encoding="utf-8")
        return [target]
    written = []
    project = exporters.PER_SUBMISSION[fmt]
    for grade, name in zip(grades, output_names(paths), strict=True):
        target = root / f"{name}.json" if fmt == "json" else root / name / "results.json"
        if root not in target.resolve().parents:  # output_names makes this impossible
            raise UsageError(f"refusing to write {target} outside {root}")
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(dumps(project(grade)), encoding="utf-8")
        written.append(target)
    return written


def write_file(path: Path, text: str) -> None:
    """Write an output file (its folder made as needed); failure is a usage error."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise UsageError(f"cannot write {path}: {exc.strerror}") from None


def read_files(paths: Sequence[Path]) -> list[str]:
    try:
        return [p.read_text(encoding="utf-8") for p in paths]
    except (OSError, UnicodeDecodeError) as exc:
        raise UsageError(f"cannot read a gradebook: {exc}") from None


def dumps(data: object) -> str:
    return json.dumps(data, indent=2, ensure_ascii=False, default=_plain) + "\n"


def _plain(value: object) -> object:
    """What JSON cannot write as it is: a numpy array or number as its list or value (a result
    must be written whatever a test input held), anything else as its text."""
    tolist = getattr(value, "tolist", None)
    return tolist() if callable(tolist) else str(value)
