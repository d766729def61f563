"""PrairieLearn external-grader entry point: ``python -m slamcourse.batch.prairielearn``.

PrairieLearn mounts the job at ``/grade``: ``/grade/data/data.json`` (the question's data),
``/grade/student`` (the learner's files: a submission folder, or a submission zip inside it),
and expects ``/grade/results/results.json``. Options come from ``data.json`` →
``params.slamcourse`` (``course``: a course folder inside the image, ``hidden``: hidden runs)
and the environment (``SLAMCOURSE_GRADING_SECRET``). Isolation is required unless the
environment sets ``SLAMCOURSE_ALLOW_NO_ISOLATION=1`` (PrairieLearn's container is then the
only sandbox). It always writes a results file and exits 0, as the external grader expects.
"""

from __future__ import annotations

import json
import os
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any


def grade_job(root: Path, environ: Mapping[str, str]) -> dict[str, Any]:
    """The PrairieLearn ``results.json`` for the job mounted at ``root``."""
    from slamcourse.batch import exporters
    from slamcourse.batch.grade import GradeOptions, grade_submission
    from slamcourse.batch.submission import MANIFEST
    from slamcourse.settings import grading_secret, isolation_waived

    try:
        data = json.loads((root / "data" / "data.json").read_text(encoding="utf-8"))
        params = (data.get("params") or {}).get("slamcourse") or {}
    except (OSError, ValueError, AttributeError):
        params = {}
    student = root / "student"
    target = student
    if not (student / MANIFEST).is_file():
        zips = sorted(student.glob("*.zip")) if student.is_dir() else []
        if zips:
            target = zips[0]
    course = params.get("course")
    options = GradeOptions(
        course=Path(course) if isinstance(course, str) else None,
        require_isolation=not isolation_waived(environ),
        secret=grading_secret(environ),
        hidden_runs=int(params.get("hidden", 1)),
    )
    return exporters.prairielearn(grade_submission(target, options))


def main(root: Path = Path("/grade")) -> int:
    results = grade_job(root, os.environ)
    out = root / "results"
    out.mkdir(parents=True, exist_ok=True)
    (out / "results.json").write_text(json.dumps(results, indent=2) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("/grade")))
