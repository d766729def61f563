"""Mutants and correct variants of the code exercises of chapters 5–8 (``graph``, ``vision``,
``factor-graphs``, ``occupancy``), graded through the real sandbox as ``slamcourse check`` does.

``exercises/<chapter>/mutants/<slug>/NN-name.py`` are plausible wrong implementations (first line
``# mistake: …``): each must be rejected. ``exercises/<chapter>/variants/<slug>/NN-name.py`` are
correct implementations written by other methods (first line ``# method: …``): each must pass.
The grading runs are slow (one sandboxed worker and up to a few hundred inputs per file), so they
are marked ``slow``; the inventory checks are fast.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

# The parent encodes list arguments with numpy's help; until the sandbox protocol stops needing
# numpy to be imported first (another branch fixes it), chapters whose reference.py does not
# import numpy (factor-graphs, occupancy) need it imported here.
import numpy  # noqa: F401
import pytest

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.kinds import get_kind

CHAPTERS = ("graph", "vision", "factor-graphs", "occupancy")
ROOT = bundled_course_root()
COURSE = load_course(ROOT)
CODE_EXERCISES = sorted(
    ex_id
    for ex_id in COURSE.exercise_ids
    if ex_id.split("/")[0] in CHAPTERS and COURSE.exercise(ex_id).kind == "code"
)


def _files(folder: str) -> list[tuple[str, Path]]:
    found = []
    for exercise_id in CODE_EXERCISES:
        chapter, slug = exercise_id.split("/")
        for path in sorted((ROOT / "exercises" / chapter / folder / slug).glob("*.py")):
            found.append((exercise_id, path))
    return found


MUTANTS = _files("mutants")
VARIANTS = _files("variants")


def _name(item: tuple[str, Path]) -> str:
    return f"{item[0]}:{item[1].stem}"


@pytest.fixture(scope="module")
def shared_home(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One learner home for this module's gradings, so that after the first passing check of an
    exercise the others replay its recorded inputs instead of drawing them again (the same
    verdicts, see docs/grading.md, Determinism)."""
    return tmp_path_factory.mktemp("mutants-home")


def _grade(exercise_id: str, path: Path, home: Path, monkeypatch: pytest.MonkeyPatch) -> Any:
    monkeypatch.setenv("SLAMCOURSE_HOME", str(home))
    return get_kind("code").check_source(
        COURSE.exercise(exercise_id), path.read_text(encoding="utf-8"), path.name
    )


def test_every_code_exercise_has_mutants_and_variants() -> None:
    assert len(CODE_EXERCISES) == 10
    for exercise_id in CODE_EXERCISES:
        mutants = [p for e, p in MUTANTS if e == exercise_id]
        variants = [p for e, p in VARIANTS if e == exercise_id]
        assert len(mutants) >= 8, f"{exercise_id}: {len(mutants)} mutants"
        assert len(variants) >= 3, f"{exercise_id}: {len(variants)} variants"


@pytest.mark.parametrize(
    ("folder", "tag"), [("mutants", "# mistake: "), ("variants", "# method: ")]
)
def test_each_file_says_what_it_is(folder: str, tag: str) -> None:
    for _, path in _files(folder):
        first = path.read_text(encoding="utf-8").splitlines()[0]
        assert first.startswith(tag) and len(first) > len(tag) + 5, f"{path}: {first!r}"


@pytest.mark.slow
@pytest.mark.parametrize("item", MUTANTS, ids=_name)
def test_mutant_is_rejected(
    item: tuple[str, Path], shared_home: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    exercise_id, path = item
    verdict = _grade(exercise_id, path, shared_home, monkeypatch)
    assert verdict.status == "failed", f"{path.name}: {verdict.status}: {verdict.feedback}"


@pytest.mark.slow
@pytest.mark.parametrize("item", VARIANTS, ids=_name)
def test_variant_passes(
    item: tuple[str, Path], shared_home: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    exercise_id, path = item
    verdict = _grade(exercise_id, path, shared_home, monkeypatch)
    assert verdict.status == "passed", f"{path.name}: {verdict.status}: {verdict.feedback}"
