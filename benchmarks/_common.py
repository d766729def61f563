"""Helpers shared by the benchmark scripts: interleaved whole-process timing in one venv."""

from __future__ import annotations

import atexit
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path

BIN = Path(sys.executable).parent
REPO = Path(__file__).resolve().parent.parent


CGROUPS = (  # (where a new cgroup may be made, the file that holds its CPU time)
    (Path("/sys/fs/cgroup/cpuacct"), "cpuacct.usage"),  # cgroup v1
    (Path("/sys/fs/cgroup"), "cpu.stat"),  # cgroup v2
    (Path("/sys/fs/cgroup/unified"), "cpu.stat"),  # cgroup v2 beside v1 (hybrid)
)


class Meter:
    """CPU-seconds used by this process and its descendants since it joined the meter: a
    ``cpuacct`` cgroup (v1) or a cgroup v2's ``cpu.stat``, which count every process of the
    cgroup whether or not anyone waits for it (``getrusage`` of the children would miss a
    forkserver's processes and a sandbox's workers). Without either, the machine's busy time
    from ``/proc/stat`` (noisier: it counts everything running; ``kind`` says so)."""

    def __init__(self) -> None:
        name = f"slambench-cpu-{os.getpid()}"
        self.kind = "/proc/stat (whole machine)"
        self.path: Path | None = None
        self.file = ""
        self._home: Path | None = None  # the cgroup this process came from (to go back)
        for root, file in CGROUPS:
            path = root / name
            home = _own_cgroup(root)
            try:
                path.mkdir()
            except OSError:
                continue
            try:
                (path / "cgroup.procs").write_text(str(os.getpid()))
                (path / file).read_text()
            except OSError:
                path.rmdir()
                continue
            self.path, self.file, self.kind, self._home = path, file, f"{path / file}", home
            break

    def read(self) -> float:
        if self.path is None:
            fields = [int(v) for v in Path("/proc/stat").read_text().split("\n")[0].split()[1:]]
            return (sum(fields) - fields[3] - fields[4]) / os.sysconf("SC_CLK_TCK")
        text = (self.path / self.file).read_text()
        if self.file == "cpuacct.usage":
            return int(text) / 1e9
        usage = dict(line.split() for line in text.splitlines())
        return int(usage["usage_usec"]) / 1e6

    def close(self) -> None:
        """Go back to the cgroup this process came from and remove the meter's (once the
        processes metered have exited)."""
        if self.path is None or self._home is None:
            return
        try:
            (self._home / "cgroup.procs").write_text(str(os.getpid()))
            for _ in range(100):  # (an exiting descendant may still be listed a moment)
                try:
                    self.path.rmdir()
                    break
                except OSError:
                    time.sleep(0.05)
        except OSError:
            pass
        self.path = None


def _own_cgroup(root: Path) -> Path | None:
    """This process's cgroup in the hierarchy mounted at ``root`` (None if not found)."""
    v1 = root.name if root.name not in ("cgroup", "unified") else ""
    try:
        lines = Path("/proc/self/cgroup").read_text().splitlines()
    except OSError:
        return None
    for line in lines:
        _id, controllers, path = line.split(":", 2)
        if (v1 and v1 in controllers.split(",")) or (not v1 and controllers == ""):
            return root / path.lstrip("/")
    return None


def environment() -> dict[str, str]:
    """A private progress folder, no colour, and bytecode caching on (as installed packages
    have it: a PYTHONDONTWRITEBYTECODE left in the environment would recompile every module on
    every start and measure the compiler, not slamcourse)."""
    home = tempfile.mkdtemp(prefix="slambench-")
    atexit.register(shutil.rmtree, home, True)  # (the runs' learner home, gone with the script)
    env = dict(os.environ, NO_COLOR="1", SLAMCOURSE_HOME=home)
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
