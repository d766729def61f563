"""Time to verdict of a submission that prints 300 MB, as a ratio to a quiet one.

Both are correct solutions of a code exercise, checked with `slamcourse check ... --file`, whole
process, interleaved in the same run; the flooding ones print 300 MB in total, spread over the
calls (1.5 MB per call) or all at import. The worker mutes learner output past 1 MiB per stream,
so the target is ≤ 1.2× the quiet check.

    python benchmarks/flood.py [--runs 7] [--exercise state/state-size]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from _common import BIN, REPO, environment, interleaved, report

DEFAULT = "state/state-size"
TOTAL = 300_000_000


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--exercise", default=DEFAULT)
    args = parser.parse_args()
    chapter, slug = args.exercise.split("/")
    solution = REPO / "exercises" / chapter / "solutions" / (slug.replace("-", "_") + ".py")
    quiet = solution.read_text()
    folder = Path(tempfile.mkdtemp(prefix="slambench-flood-"))
    per_call = folder / "per_call.py"
    per_call.write_text(
        quiet
        + "\n\n_quiet = "
        + _function_name(quiet)
        + "\n\n\ndef "
        + _function_name(quiet)
        + "(*args):\n"
        + "    for _ in range(3):\n"
        + "        print('x' * 500_000)\n"
        + "    return _quiet(*args)\n"
    )
    at_import = folder / "at_import.py"
    at_import.write_text(
        f"for _ in range({TOTAL // 1_000_000}):\n    print('x' * 1_000_000)\n\n" + quiet
    )
    slam = str(BIN / "slamcourse")

    def check(path: Path) -> list[str]:
        return [slam, "check", args.exercise, "--file", str(path), "--no-record"]

    baseline = f"check {args.exercise}, quiet solution (baseline)"
    commands = {
        baseline: check(solution),
        "same, printing 1.5 MB per call (~300 MB)": check(per_call),
        "same, printing 300 MB at import": check(at_import),
    }
    medians = interleaved(commands, args.runs, environment())
    report(f"time to verdict, median of {args.runs} interleaved runs", medians, baseline, 1.2)


def _function_name(source: str) -> str:
    for line in source.splitlines():
        if line.startswith("def "):
            return line[4:].split("(")[0]
    raise SystemExit("no function in the solution")


if __name__ == "__main__":
    main()
