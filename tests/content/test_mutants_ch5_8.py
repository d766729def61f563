"""Mutants and correct variants of the code exercises of chapters 5–8 (``graph``, ``vision``,
``factor-graphs``, ``occupancy``): the inventory.

``exercises/<chapter>/mutants/<slug>/NN-name.py`` are plausible wrong implementations (first line
``# mistake: …``): each must be rejected. ``exercises/<chapter>/variants/<slug>/NN-name.py`` are
correct implementations written by other methods (first line ``# method: …``): each must pass.

They are graded through the real sandbox once, by the course's validation
(``test_bundled_course.py::test_exercise_is_sound``, which also requires these chapters' mutants
to be graded ``failed``); their first lines are checked there too. This file only counts them.
"""

from __future__ import annotations

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root

CHAPTERS = ("graph", "vision", "factor-graphs", "occupancy")
ROOT = bundled_course_root()
COURSE = load_course(ROOT)
CODE_EXERCISES = sorted(
    ex_id
    for ex_id in COURSE.exercise_ids
    if ex_id.split("/")[0] in CHAPTERS and COURSE.exercise(ex_id).kind == "code"
)


def test_every_code_exercise_has_mutants_and_variants() -> None:
    assert len(CODE_EXERCISES) == 10
    for exercise_id in CODE_EXERCISES:
        chapter, slug = exercise_id.split("/")
        folder = ROOT / "exercises" / chapter
        mutants = sorted((folder / "mutants" / slug).glob("*.py"))
        variants = sorted((folder / "variants" / slug).glob("*.py"))
        assert len(mutants) >= 8, f"{exercise_id}: {len(mutants)} mutants"
        assert len(variants) >= 3, f"{exercise_id}: {len(variants)} variants"
