"""A class of submissions against a course, built as its learners would hand them in.

Three kinds of learner, each answering with the course's own material:

- ``complete``: every exercise right (text answers from the reference code of the learner's own
  variant, code from the exercise's shipped solution);
- ``partial``: about half the exercises, a third of those wrong (a text answer off by 10 %, or
  one of the exercise's shipped mutants), the right code from the solution or one of the
  exercise's correct variants (some of them slower: a dense solve of the whole INTEL graph);
- ``hostile``: code that floods its output, loops forever, exits, forks or raises, and text
  that cannot be read.

Used by ``benchmarks/batch.py`` and by the batch tests.
"""

from __future__ import annotations

import json
import random
from pathlib import Path
from typing import Any

from slamcourse.batch.submission import (
    Answer,
    Manifest,
    Submission,
    code_path,
    course_hash,
    learner_id,
    write,
)
from slamcourse.course.loader import load_course
from slamcourse.course.model import ExerciseSpec
from slamcourse.course.variants import variant
from slamcourse.kinds import get_kind
from slamcourse.kinds.code import submission_files
from slamcourse.progress import variant_seed_for

# formula answers (the reference of an expression exercise is numpy code, not a formula)
FORMULAS = {
    "observation/bearing-derivative": "dy/q",
    "observation/range-derivative": "-dx/sqrt(q)",
    "motion/jacobian-formula": "-trans*sin(theta + rot1)",
}

HOSTILE = {
    "flood": "def {f}(*args):\n    while True:\n        print('x' * 100000)\n",
    "hang": "def {f}(*args):\n    while True:\n        pass\n",
    "exit": "import os\n\ndef {f}(*args):\n    os._exit(3)\n",
    "fork": "import os\n\ndef {f}(*args):\n    for _ in range(200):\n        try:\n"
    "            if os.fork() == 0:\n                while True:\n                    pass\n"
    "        except OSError:\n            break\n    return 0\n",
    "raise": "def {f}(*args):\n    raise RuntimeError('nope')\n",
}


def _text(value: Any) -> str:
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, list) and value and all(isinstance(v, str) for v in value):
        return " ".join(value)
    if isinstance(value, str):
        return value
    return json.dumps(value)


def right_text(spec: ExerciseSpec, seed: int) -> str | None:
    """The accepted text answer of variant ``seed``, from the reference code (None if this
    builder cannot write one)."""
    if spec.kind == "expression":
        return FORMULAS.get(spec.id)
    kind = get_kind(spec.kind)
    shown = getattr(kind, "shown_answer", None)  # choice, multi, order: the letters shown
    if shown is not None:
        return _text(shown(spec, variant(spec, seed)))
    return _text(kind.expected(spec, variant(spec, seed)))


def wrong_text(spec: ExerciseSpec, seed: int) -> str:
    value = get_kind(spec.kind).expected(spec, variant(spec, seed))
    if spec.kind in ("number", "vector", "matrix"):
        if hasattr(value, "tolist"):
            value = value.tolist()
        scaled = json.loads(json.dumps(value), parse_float=lambda s: float(s) * 1.1 + 0.3)
        return _text(scaled if not isinstance(value, int) else value + 1)
    if spec.kind == "line":
        return str(int(value) % 2 + 1)
    return "a"


def make_class(
    course_root: Path, out: Path, kinds: list[str], *, first_seed: int = 1000
) -> list[Path]:
    """One zip per entry of ``kinds`` (``complete``, ``partial`` or ``hostile``) in ``out``."""
    course = load_course(course_root)
    digest = course_hash(course_root)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for i, kind in enumerate(kinds):
        seed = first_seed + i
        rng = random.Random(f"class:{seed}")
        answers, files = [], {}
        for ex in course.exercise_ids:
            spec = course.exercise(ex)
            if kind == "partial" and rng.random() < 0.5:
                continue
            wrong = kind == "partial" and rng.random() < 1 / 3
            v = variant_seed_for(seed, ex) if spec.has_variants else 0
            if spec.kind == "code":
                mutants, correct = submission_files(spec)
                if kind == "hostile":
                    style = sorted(HOSTILE)[i % len(HOSTILE)]
                    source = HOSTILE[style].format(f=spec.options.function)
                elif wrong and mutants:
                    source = mutants[rng.randrange(len(mutants))].read_text()
                elif kind == "complete":  # the course's own solution, as the issue measures
                    source = spec.options.solution.read_text()
                else:  # a partial learner's right answers: the solution or a correct variant
                    pick = [spec.options.solution, *correct]
                    source = pick[rng.randrange(len(pick))].read_text()
                files[code_path(ex)] = source.encode()
                answers.append(Answer(ex, 0, file=code_path(ex), attempts=1))
                continue
            if kind == "hostile":  # garbage, and (every eighth) an answer far too long; the
                # manifest itself stays under the grader's 2 MiB (a bigger one is rejected whole)
                long = i % 2 == 0 and len(answers) % 8 == 0
                text: str | None = "x" * 20000 if long else "1/0 )("
            else:
                text = wrong_text(spec, v) if wrong else right_text(spec, v)
            if text is not None:
                answers.append(Answer(ex, v, text=text, attempts=1))
        manifest = Manifest(learner_id(seed), seed, "0.1.0", "custom", digest, tuple(answers))
        paths.append(write(Submission(manifest, files), out / f"{kind}-{i:04d}.zip"))
    return paths
