"""Reference results kept for scalar arguments (course/reference.py): the same call is not
computed twice, a copy is handed out, and nothing stale or unsafe is ever returned."""

from __future__ import annotations

import os
import textwrap
from pathlib import Path

import pytest

from slamcourse.course import reference
from slamcourse.course.model import ExerciseSpec
from slamcourse.errors import CourseError

SOURCE = """
CALLS = []

def answer(n, scale=1.0):
    CALLS.append((n, scale))
    if n < 0:
        raise ValueError("negative")
    return [n * scale, {SHIFT}]

def rows(values):
    CALLS.append(tuple(values))
    return list(values)
"""


def write_reference(folder: Path, shift: int) -> ExerciseSpec:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "reference.py").write_text(textwrap.dedent(SOURCE.replace("{SHIFT}", str(shift))))
    return spec_at(folder)


def spec_at(folder: Path) -> ExerciseSpec:
    return ExerciseSpec(
        id="ch/ex",
        chapter="ch",
        path=folder / "ex.yaml",
        kind="number",
        title="t",
        prompt=None,  # type: ignore[arg-type]
        explanation=None,  # type: ignore[arg-type]
        course_root=folder.parent,
    )


def calls(spec: ExerciseSpec) -> list:
    return reference.module_for(spec).CALLS  # type: ignore[no-any-return]


def test_a_scalar_call_is_computed_once_and_handed_out_as_a_copy(tmp_path: Path) -> None:
    spec = write_reference(tmp_path / "ch", shift=0)
    first = reference.call(spec, "answer", 1, {"n": 3, "scale": 0.5})
    first.append("changed by the caller")
    second = reference.call(spec, "answer", 1, {"scale": 0.5, "n": 3})  # (order does not matter)
    assert second == [1.5, 0]
    assert calls(spec) == [(3, 0.5)]
    reference.call(spec, "answer", 1, {"n": 3, "scale": -0.0})  # another float, bit for bit
    reference.call(spec, "answer", 1, {"n": True})  # True is not 1 here
    reference.call(spec, "answer", 1, {"n": 1})
    assert calls(spec) == [(3, 0.5), (3, -0.0), (True, 1.0), (1, 1.0)]


def test_other_arguments_and_failures_are_never_kept(tmp_path: Path) -> None:
    spec = write_reference(tmp_path / "ch", shift=0)
    for _ in range(2):
        assert reference.call(spec, "rows", 1, {"values": [1.0, 2.0]}) == [1.0, 2.0]
        with pytest.raises(CourseError, match="negative"):
            reference.call(spec, "answer", 1, {"n": -1})
    assert calls(spec) == [(1.0, 2.0), (-1, 1.0), (1.0, 2.0), (-1, 1.0)]


def test_a_changed_reference_module_is_called_again(tmp_path: Path) -> None:
    spec = write_reference(tmp_path / "ch", shift=0)
    assert reference.call(spec, "answer", 1, {"n": 2}) == [2.0, 0]
    write_reference(tmp_path / "ch", shift=7)  # the instructor edits it (watch reloads it)
    stat = (tmp_path / "ch" / "reference.py").stat()
    os.utime(tmp_path / "ch" / "reference.py", ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))
    assert reference.call(spec, "answer", 1, {"n": 2}) == [2.0, 7]


def _kept_elsewhere(folder: str) -> dict:
    """What another process (a batch's pool) computes and hands over."""
    return reference.kept_results(
        spec_at(Path(folder)),
        [("answer", 1, {"n": 2}), ("answer", 1, {"n": -1}), ("rows", 1, {"values": [1]})],
    )


def test_a_result_computed_in_another_process_is_adopted_for_the_same_file(
    tmp_path: Path,
) -> None:
    """A batch computes the answers every learner shares once, in one process; the others
    adopt them (keyed by the reference file, not by a process's module object). Failures and
    calls with array-like arguments are not handed over."""
    import multiprocessing

    folder = tmp_path / "ch"
    spec = write_reference(folder, shift=7)
    with multiprocessing.get_context("spawn").Pool(1) as pool:
        kept = pool.apply(_kept_elsewhere, (str(folder),))
    assert list(kept.values()) == [[2.0, 7]]  # the failure and the list argument: not kept
    reference.adopt_results(kept)
    assert reference.call(spec, "answer", 1, {"n": 2}) == [2.0, 7]
    assert calls(spec) == []  # adopted, not computed here
    (folder / "reference.py").write_text(SOURCE.replace("{SHIFT}", "8"))  # another file now
    os.utime(folder / "reference.py", ns=(1, 1))
    assert reference.call(spec, "answer", 1, {"n": 2}) == [2.0, 8]
