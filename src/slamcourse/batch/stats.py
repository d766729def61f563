"""Class statistics from grade results (``slamcourse grade --format json`` output).

Per exercise: how many learners solved it, mean attempts (the counted attempts the submissions
recorded; when none did, 1 per graded answer), the misconceptions matched most often, and a
histogram of the attempt counts.
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from slamcourse.batch.grade import SubmissionGrade
from slamcourse.errors import UsageError


def load_results(paths: Iterable[Path]) -> list[SubmissionGrade]:
    """Grade results from files (one result, or a list) and folders (their ``*.json``)."""
    files: list[Path] = []
    for path in paths:
        if path.is_dir():
            files.extend(sorted(path.glob("*.json")))
        else:
            files.append(path)
    grades: list[SubmissionGrade] = []
    for f in files:
        try:
            data = json.loads(f.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, ValueError) as exc:
            raise UsageError(f"{f}: not a readable JSON grade result ({exc})") from None
        items = data if isinstance(data, list) else [data]
        for item in items:
            if not isinstance(item, dict):
                raise UsageError(f"{f}: not a slamcourse grade result")
            try:
                grades.append(SubmissionGrade.from_dict(item))
            except UsageError as exc:
                raise UsageError(f"{f}: {exc}") from None
    return grades


def statistics(grades: Sequence[SubmissionGrade]) -> dict[str, Any]:
    """Per exercise (in course order): learners, solved, solve rate, mean attempts, the top
    three misconceptions ``[[id, count], …]`` and the attempt histogram ``{attempts: count}``."""
    graded = [g for g in grades if g.status == "graded"]
    order: list[str] = []
    for g in graded:
        for e in g.exercises:
            if e.exercise not in order:
                order.append(e.exercise)
    rows = []
    for ex in order:
        entries = [e for g in graded for e in g.exercises if e.exercise == ex]
        answered = [e for e in entries if e.status != "missing"]
        solved = sum(e.passed for e in entries)
        recorded = [e.attempts for e in answered if e.attempts is not None]
        attempts = recorded if recorded else [1] * len(answered)
        misconceptions = Counter(e.misconception for e in entries if e.misconception)
        rows.append(
            {
                "exercise": ex,
                "title": entries[0].title,
                "learners": len(entries),
                "answered": len(answered),
                "solved": solved,
                "solve_rate": round(solved / len(entries), 4) if entries else 0.0,
                "mean_attempts": round(sum(attempts) / len(attempts), 2) if attempts else None,
                "attempts_source": "recorded" if recorded else "graded",
                "misconceptions": [[m, n] for m, n in misconceptions.most_common(3)],
                "histogram": {str(k): v for k, v in sorted(Counter(attempts).items())},
            }
        )
    return {
        "submissions": len(grades),
        "graded": len(graded),
        "errors": len(grades) - len(graded),
        "exercises": rows,
    }


def render_text(stats: dict[str, Any], width: int = 30) -> str:
    """The statistics as plain text, with a bar per attempt count."""
    lines = [
        f"{stats['submissions']} submissions: {stats['graded']} graded, "
        f"{stats['errors']} could not be graded"
    ]
    for row in stats["exercises"]:
        mean = row["mean_attempts"]
        lines.append("")
        lines.append(f"{row['exercise']}  ({row['title']})")
        lines.append(
            f"  solved {row['solved']}/{row['learners']} ({row['solve_rate']:.0%}); "
            + (
                f"mean attempts {mean} ({row['attempts_source']})"
                if mean is not None
                else "no answers"
            )
        )
        if row["misconceptions"]:
            top = ", ".join(f"{m} ×{n}" for m, n in row["misconceptions"])
            lines.append(f"  misconceptions: {top}")
        hist = row["histogram"]
        if hist:
            peak = max(hist.values())
            for attempts, count in hist.items():
                bar = "█" * max(1, round(width * count / peak))
                lines.append(
                    f"  {attempts:>3} attempt{'s' if attempts != '1' else ' '} {bar} {count}"
                )
    return "\n".join(lines)
