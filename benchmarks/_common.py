"""Helpers shared by the benchmark scripts: interleaved whole-process timing in one venv."""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path

BIN = Path(sys.executable).parent
REPO = Path(__file__).resolve().parent.parent


def environment() -> dict[str, str]:
    """A private progress folder, no colour, and bytecode caching on (as installed packages
    have it: a PYTHONDONTWRITEBYTECODE left in the environment would recompile every module on
    every start and measure the compiler, not slamcourse)."""
    env = dict(os.environ, NO_COLOR="1", SLAMCOURSE_HOME=tempfile.mkdtemp(prefix="slambench-"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def run_once(cmd: Sequence[str], env: dict[str, str]) -> float:
    start = time.perf_counter()
    done = subprocess.run(
        cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, check=False
    )
    elapsed = time.perf_counter() - start
    if done.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)} failed ({done.returncode}): {done.stderr.decode()}")
    return elapsed


def interleaved(
    commands: dict[str, Sequence[str]], runs: int, env: dict[str, str], warmup: int = 2
) -> dict[str, float]:
    """Median wall time (s) of each command, runs interleaved so load drifts hit all alike."""
    for cmd in commands.values():
        for _ in range(warmup):
            run_once(cmd, env)
    samples: dict[str, list[float]] = {name: [] for name in commands}
    for _ in range(runs):
        for name, cmd in commands.items():
            samples[name].append(run_once(cmd, env))
    return {name: statistics.median(values) for name, values in samples.items()}


def report(title: str, medians: dict[str, float], baseline: str, target: float) -> None:
    base = medians[baseline]
    print(title)
    for name, value in medians.items():
        ratio = value / base
        mark = "" if name == baseline else ("  ok" if ratio <= target else f"  over {target}×")
        print(f"  {name:<44} {value * 1000:8.1f} ms  {ratio:5.2f}×{mark}")
