"""Start-up cost of the learner commands, as ratios to `python -c "import numpy"`.

Prints the median whole-process wall time of `slamcourse check <number exercise> --answer …`
and of `slamcourse show <id>`, each divided by the median of `python -c "import numpy"` run in
the same venv, interleaved in the same run. Target: ≤ 1.5× for both.

    python benchmarks/startup.py [--runs 21]
"""

from __future__ import annotations

import argparse
import sys

from _common import BIN, environment, interleaved, report


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=21)
    args = parser.parse_args()
    slam = str(BIN / "slamcourse")
    commands = {
        "python -c 'import numpy' (baseline)": [sys.executable, "-c", "import numpy"],
        "slamcourse check predicted-range --answer 5": [
            slam,
            "check",
            "observation/predicted-range",
            "--answer",
            "5",
            "--canonical",
        ],
        "slamcourse show predicted-bearing": [slam, "show", "observation/predicted-bearing"],
    }
    medians = interleaved(commands, args.runs, environment())
    report(
        f"start-up, median of {args.runs} interleaved runs",
        medians,
        "python -c 'import numpy' (baseline)",
        1.5,
    )


if __name__ == "__main__":
    main()
