"""How learner code is isolated: limits, the isolation probe, the bwrap command and cgroups.

Two levels exist (see ``docs/grading.md``, section *Sandbox*):

``namespaces``
    bubblewrap: new user, PID, network, IPC, UTS, mount and cgroup namespaces; a file system that
    holds the interpreter, numpy and the worker script only; no capabilities; a private /tmp.
``rlimits``
    the fallback: a plain child process with resource limits, its own session and a scrubbed
    environment. It bounds time and memory but does not hide files or the network.

On both levels a cgroup is used when one can be created (Linux, root or a delegated cgroup v2
subtree): a ``pids`` cgroup enforces the process limit (``RLIMIT_NPROC`` is not enforced for
root), and ``cgroup.kill`` or a sweep of the pids cgroup kills every descendant, including
daemons that left the process group with ``setsid()``.
"""

from __future__ import annotations

import contextlib
import importlib.util
import os
import re
import shutil
import signal
import subprocess
import sys
import sysconfig
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

from slamcourse.errors import SandboxError

Level = Literal["namespaces", "rlimits"]

#: Environment variable that selects the isolation level: ``auto`` (default), ``namespaces``
#: (fail when unavailable) or ``rlimits`` (force the fallback, e.g. for tests).
ENV_VAR = "SLAMCOURSE_SANDBOX"

ONE_BLAS_THREAD = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
"""Environment variables that, set to 1, have a BLAS library loaded afterwards use one thread
(the learners' code; the batch grader's processes)."""

WORKER_SCRIPT = Path(__file__).with_name("worker.py")
SANDBOX_WORKER_PATH = "/sandbox/worker.py"
CGROUP_PREFIX = "slamcourse-"
_PROBE_SECONDS = 15.0


@dataclass(frozen=True)
class Limits:
    """Resource limits for one worker (one learner submission). All values are per worker.

    - ``call_seconds``: wall time for one ``load`` or ``call`` (the parent's clock).
    - ``total_seconds``: wall time of all requests to one worker together (start, load and
      calls; idle time between requests does not count).
    - ``cpu_seconds``: ``RLIMIT_CPU`` of the worker (and of each process it forks).
    - ``memory_bytes``: ``RLIMIT_AS``, address space per process (numpy needs ~100 MiB).
    - ``processes``: ``pids.max`` of the worker's cgroup and ``RLIMIT_NPROC``.
    - ``file_bytes``: ``RLIMIT_FSIZE``, largest file the learner can write.
    - ``open_files``: ``RLIMIT_NOFILE``.
    - ``output_bytes``: stdout and stderr kept per request and stream; the rest is discarded.
    - ``muted_after``: characters per stream the worker passes on over its whole life; later
      output is counted but never written (so printing in a loop costs nothing).
    - ``flood_bytes``: bytes of stdout and stderr together the parent reads from one worker
      before it kills it (only output written around the muted streams gets that far).
    - ``start_seconds``: wall time for the worker to start (interpreter + numpy import).
    - ``frame_bytes``: largest protocol frame (one reply line) accepted from the worker.
    - ``tmp_bytes``: size of the private writable ``/tmp`` under namespaces.
    """

    call_seconds: float = 5.0
    total_seconds: float = 60.0
    cpu_seconds: int = 30
    memory_bytes: int = 1 << 30
    processes: int = 64
    file_bytes: int = 16 << 20
    open_files: int = 64
    output_bytes: int = 64 << 10
    muted_after: int = 1 << 20
    flood_bytes: int = 8 << 20
    start_seconds: float = 20.0
    frame_bytes: int = 1 << 20
    tmp_bytes: int = 16 << 20

    def __post_init__(self) -> None:
        for name, value in vars(self).items():
            if not value > 0:
                raise ValueError(f"Limits.{name} must be positive, got {value!r}")
        if self.open_files < 16:
            raise ValueError("Limits.open_files must be at least 16 (the interpreter needs them)")


@dataclass(frozen=True)
class IsolationReport:
    """What the sandbox can do on this machine.

    ``level`` is ``"namespaces"`` (bubblewrap works) or ``"rlimits"`` (fallback); ``reason``
    says why, in a sentence fit for a warning. ``process_limit`` and ``cleanup`` say how the
    process count is bounded and how a worker's descendants are killed.
    """

    level: Level
    reason: str
    bwrap: str | None = None
    process_limit: str = ""
    cleanup: str = ""
    warnings: tuple[str, ...] = ()
    cgroups: CgroupPlan | None = field(default=None, repr=False, compare=False)

    @property
    def isolated(self) -> bool:
        return self.level == "namespaces"


# ---------------------------------------------------------------------------------------------
# cgroups
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class CgroupPlan:
    """Parent directories in which per-worker cgroups can be created."""

    pids_parent: Path | None  # children get pids.max (cgroup v1 pids, or v2 with pids enabled)
    kill_parent: Path | None  # cgroup v2: children get cgroup.kill

    @property
    def usable(self) -> bool:
        return self.pids_parent is not None or self.kill_parent is not None


def _cgroup_mounts() -> tuple[Path | None, Path | None]:
    """(v1 pids mount point, cgroup2 mount point) from /proc/self/mountinfo."""
    v1_pids: Path | None = None
    v2: Path | None = None
    try:
        text = Path("/proc/self/mountinfo").read_text()
    except OSError:
        return None, None
    for line in text.splitlines():
        left, _, right = line.partition(" - ")
        fields, tail = left.split(), right.split()
        if len(fields) < 5 or len(tail) < 3:
            continue
        mount_point = Path(fields[4].replace("\\040", " "))
        if tail[0] == "cgroup2" and v2 is None:
            v2 = mount_point
        elif tail[0] == "cgroup" and "pids" in tail[2].split(",") and v1_pids is None:
            v1_pids = mount_point
    return v1_pids, v2


def _own_cgroups() -> tuple[str | None, str | None]:
    """(own v1 pids cgroup path, own v2 cgroup path) from /proc/self/cgroup."""
    v1: str | None = None
    v2: str | None = None
    try:
        text = Path("/proc/self/cgroup").read_text()
    except OSError:
        return None, None
    for line in text.splitlines():
        parts = line.split(":", 2)
        if len(parts) != 3:
            continue
        if parts[0] == "0" and parts[1] == "":
            v2 = parts[2]
        elif "pids" in parts[1].split(","):
            v1 = parts[2]
    return v1, v2


def _try_child(parent: Path, needed: str) -> bool:
    """Can we create a child cgroup under ``parent`` that has the control file ``needed``?"""
    probe = parent / f"{CGROUP_PREFIX}probe-{os.getpid()}-{threading.get_ident()}"
    try:
        probe.mkdir()
    except OSError:
        return False
    try:
        ok = (probe / needed).exists() and os.access(probe / "cgroup.procs", os.W_OK)
        if ok and needed == "pids.max":
            (probe / "pids.max").write_text("64\n")
        return ok
    except OSError:
        return False
    finally:
        with contextlib.suppress(OSError):
            probe.rmdir()


def probe_cgroups() -> CgroupPlan:
    """Find where per-worker cgroups can be created (nothing is left behind)."""
    if not sys.platform.startswith("linux"):
        return CgroupPlan(None, None)
    v1_mount, v2_mount = _cgroup_mounts()
    v1_own, v2_own = _own_cgroups()
    pids_parent: Path | None = None
    kill_parent: Path | None = None
    if v2_mount is not None and v2_own is not None:
        parent = v2_mount / v2_own.lstrip("/")
        if _try_child(parent, "cgroup.kill"):
            kill_parent = parent
            if _try_child(parent, "pids.max"):
                pids_parent = parent
    if pids_parent is None and v1_mount is not None and v1_own is not None:
        parent = v1_mount / v1_own.lstrip("/")
        if _try_child(parent, "pids.max"):
            pids_parent = parent
    plan = CgroupPlan(pids_parent, kill_parent)
    _remove_stale(plan)
    return plan


_STALE = re.compile(re.escape(CGROUP_PREFIX) + r"(\d+)-")


def _remove_stale(plan: CgroupPlan) -> None:
    """Kill and remove cgroups left by slamcourse processes that died without cleaning up."""
    for parent in {plan.pids_parent, plan.kill_parent} - {None}:
        assert parent is not None
        try:
            entries = list(parent.iterdir())
        except OSError:
            continue
        for entry in entries:
            match = _STALE.match(entry.name)
            if match is None or _pid_alive(int(match.group(1))):
                continue
            group = WorkerCgroups([entry])
            group.kill()
            group.remove(wait=0.5)


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


class WorkerCgroups:
    """The cgroups of one worker: created before it starts, joined by the worker itself."""

    _counter = 0
    _lock = threading.Lock()

    def __init__(self, dirs: list[Path]) -> None:
        self.dirs = dirs
        self.fds: list[int] = []

    @classmethod
    def create(cls, plan: CgroupPlan, limits: Limits) -> WorkerCgroups | None:
        """Create the cgroups and open their ``cgroup.procs`` for the worker; None if impossible."""
        with cls._lock:
            cls._counter += 1
            name = f"{CGROUP_PREFIX}{os.getpid()}-{cls._counter}-{os.urandom(4).hex()}"
        parents = [p for p in dict.fromkeys([plan.kill_parent, plan.pids_parent]) if p]
        group = cls([])
        try:
            for parent in parents:
                path = parent / name
                path.mkdir(mode=0o755)
                group.dirs.append(path)
                if parent == plan.pids_parent:
                    (path / "pids.max").write_text(f"{limits.processes}\n")
            for path in group.dirs:
                group.fds.append(os.open(path / "cgroup.procs", os.O_WRONLY | os.O_CLOEXEC))
        except OSError:
            group.close_fds()
            group.remove(wait=0)
            return None
        return group

    def close_fds(self) -> None:
        for fd in self.fds:
            with contextlib.suppress(OSError):
                os.close(fd)
        self.fds = []

    def pids(self) -> set[int]:
        found: set[int] = set()
        for path in self.dirs:
            with contextlib.suppress(OSError, ValueError):
                found.update(int(x) for x in (path / "cgroup.procs").read_text().split())
        return found

    def kill(self) -> None:
        """SIGKILL every process in the cgroups (no new process can start meanwhile)."""
        for path in self.dirs:
            if (path / "cgroup.kill").exists():
                with contextlib.suppress(OSError):
                    (path / "cgroup.kill").write_text("1\n")
                    continue
            with contextlib.suppress(OSError):
                (path / "pids.max").write_text("0\n")  # freezes forking (v1 and v2)
        deadline = time.monotonic() + 2.0
        while time.monotonic() < deadline:
            pids = self.pids()
            if not pids:
                return
            for pid in pids:
                with contextlib.suppress(OSError):
                    os.kill(pid, signal.SIGKILL)
            time.sleep(0.005)

    def remove(self, wait: float) -> bool:
        """Remove the (empty) cgroup directories; wait up to ``wait`` s for them to empty."""
        deadline = time.monotonic() + wait
        while True:
            for path in list(self.dirs):
                try:
                    path.rmdir()
                    self.dirs.remove(path)
                except FileNotFoundError:
                    self.dirs.remove(path)
                except OSError:
                    pass
            if not self.dirs or time.monotonic() >= deadline:
                return not self.dirs
            time.sleep(0.01)


# ---------------------------------------------------------------------------------------------
# bubblewrap
# ---------------------------------------------------------------------------------------------


#: The packages a learner may import besides the standard library (the worker allows the same).
SANDBOX_PACKAGES = ("numpy", "scipy")


def _numpy_dirs() -> list[str]:
    """The package directories of :data:`SANDBOX_PACKAGES` and their bundled libraries
    (``numpy.libs``, ``scipy.libs``), where installed."""
    dirs: list[str] = []
    for name in SANDBOX_PACKAGES:
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            continue
        if spec is None or spec.origin is None:
            continue
        package = os.path.dirname(os.path.abspath(spec.origin))
        dirs.append(package)
        libs = package + ".libs"
        if os.path.isdir(libs):
            dirs.append(libs)
    return dirs


def _site_dirs() -> list[str]:
    """Every site-packages style directory that must look empty inside the sandbox."""
    candidates: list[str] = []
    for base in dict.fromkeys([sys.prefix, sys.base_prefix, sys.exec_prefix]):
        paths = sysconfig.get_paths(vars={"base": base, "platbase": base})
        candidates += [paths["purelib"], paths["platlib"]]
    candidates += [p for p in sys.path if p.endswith(("site-packages", "dist-packages"))]
    numpy = _numpy_dirs()
    if numpy:
        candidates.append(os.path.dirname(numpy[0]))
    return [p for p in dict.fromkeys(os.path.abspath(c) for c in candidates) if os.path.isdir(p)]


def _interpreter() -> str:
    return os.path.abspath(sys.executable)


def bwrap_command(
    bwrap: str, limits: Limits, program: list[str], *, as_pid_1: bool = False
) -> list[str]:
    """The full bubblewrap command line running ``program`` (argv inside the sandbox);
    ``as_pid_1``: ``program`` is the sandbox's init (a zygote: it reaps orphans itself, and no
    bubblewrap init, which the sandbox's processes could ptrace, shares the sandbox)."""
    cmd = [
        bwrap,
        *(["--as-pid-1"] if as_pid_1 else []),
        "--unshare-all",
        "--unshare-user",
        "--uid", "65534",
        "--gid", "65534",
        "--disable-userns",
        "--die-with-parent",
        "--new-session",
        "--cap-drop", "ALL",
        "--hostname", "sandbox",
        "--clearenv",
        "--setenv", "PATH", "/usr/bin:/bin",
        "--setenv", "HOME", "/tmp",
        *(arg for name in ONE_BLAS_THREAD for arg in ("--setenv", name, "1")),
        "--proc", "/proc",
        "--dev", "/dev",
        # First, so that binds of things that live under the host's /tmp stay visible.
        "--size", str(limits.tmp_bytes), "--tmpfs", "/tmp",
    ]  # fmt: skip
    bound: list[str] = []

    def covered(path: str) -> bool:
        return any(path == b or path.startswith(b.rstrip("/") + "/") for b in bound)

    def ro_bind(path: str) -> None:
        if not covered(path):
            cmd.extend(["--ro-bind", path, path])
            bound.append(path)

    ro_bind("/usr")
    for name in ("bin", "sbin", "lib", "lib32", "lib64", "libx32"):
        path = "/" + name
        if os.path.islink(path):
            cmd.extend(["--symlink", os.readlink(path), path])
        elif os.path.isdir(path):
            ro_bind(path)
    if os.path.exists("/etc/ld.so.cache"):
        ro_bind("/etc/ld.so.cache")
    for prefix in dict.fromkeys([sys.base_prefix, sys.base_exec_prefix]):
        ro_bind(os.path.abspath(prefix))
    if sys.prefix != sys.base_prefix:  # a virtual environment: its config and interpreter only
        cfg = os.path.join(sys.prefix, "pyvenv.cfg")
        if os.path.exists(cfg):
            ro_bind(cfg)
    ro_bind(_interpreter())
    site_dirs = _site_dirs()
    for path in site_dirs:
        cmd.extend(["--tmpfs", path])
    for path in _numpy_dirs():
        cmd.extend(["--ro-bind", path, path])
    for path in site_dirs:
        cmd.extend(["--remount-ro", path])
    cmd.extend(["--ro-bind", str(WORKER_SCRIPT), SANDBOX_WORKER_PATH])
    cmd.extend(["--remount-ro", "/dev", "--remount-ro", "/", "--chdir", "/tmp", "--"])
    return cmd + program


def worker_env(home: str) -> dict[str, str]:
    """The complete environment of a worker started without namespaces."""
    return {"PATH": "/usr/bin:/bin", "HOME": home, **dict.fromkeys(ONE_BLAS_THREAD, "1")}


def _bwrap_path() -> str | None:
    found = shutil.which("bwrap")
    if found is None and os.access("/usr/bin/bwrap", os.X_OK):
        found = "/usr/bin/bwrap"
    return found


def _probe_bwrap(bwrap: str) -> str | None:
    """Run the real sandbox command with ``-c pass``; None if it works, else why not."""
    cmd = bwrap_command(bwrap, Limits(), [_interpreter(), "-I", "-B", "-c", "pass"])
    try:
        done = subprocess.run(
            cmd,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            env={"PATH": "/usr/bin:/bin"},
            cwd="/",
            timeout=_PROBE_SECONDS,
            check=False,
        )
    except subprocess.TimeoutExpired:
        return f"bwrap did not finish a trivial command within {_PROBE_SECONDS:.0f} s"
    except OSError as exc:
        return f"bwrap could not be started: {exc}"
    if done.returncode != 0:
        text = done.stderr.decode(errors="replace").strip().splitlines()
        detail = text[-1][:300] if text else f"exit status {done.returncode}"
        return f"bwrap failed: {detail}"
    return None


_cache: dict[str, IsolationReport] = {}
_cache_lock = threading.Lock()


def probe_isolation(force: str | None = None) -> IsolationReport:
    """Find out (once per process and mode) which isolation level works here.

    ``force`` (or the environment variable ``SLAMCOURSE_SANDBOX`` when ``force`` is None) is
    ``"auto"`` (default: namespaces when bubblewrap works, else rlimits), ``"namespaces"``
    (probe; :meth:`Worker.spawn` then refuses to run without them) or ``"rlimits"`` (skip the
    probe and use the fallback). The probe runs the real sandbox command with ``-c pass``.
    """
    mode = force if force is not None else os.environ.get(ENV_VAR, "auto") or "auto"
    if mode not in ("auto", "namespaces", "rlimits"):
        raise SandboxError(
            f"unknown sandbox mode {mode!r} (from {ENV_VAR if force is None else 'force'}): "
            "use auto, namespaces or rlimits"
        )
    with _cache_lock:
        if mode not in _cache:
            _cache[mode] = _probe(mode, forced_by="caller" if force is not None else ENV_VAR)
        return _cache[mode]


def _probe(mode: str, forced_by: str) -> IsolationReport:
    plan = probe_cgroups()
    is_root = hasattr(os, "geteuid") and os.geteuid() == 0
    warnings: list[str] = []
    bwrap = _bwrap_path() if sys.platform.startswith("linux") else None
    if mode == "rlimits":
        level: Level = "rlimits"
        reason = f"namespaces turned off ({forced_by} asked for rlimits)"
    elif not sys.platform.startswith("linux"):
        level, reason = "rlimits", f"namespaces need Linux (this is {sys.platform})"
    elif bwrap is None:
        level, reason = "rlimits", "bubblewrap (bwrap) is not installed"
    else:
        failure = _probe_bwrap(bwrap)
        if failure is None:
            level, reason = "namespaces", f"bubblewrap works ({bwrap})"
        else:
            level, reason = "rlimits", failure
    if plan.pids_parent is not None:
        process_limit = f"pids cgroup ({plan.pids_parent}) and RLIMIT_NPROC"
    elif is_root:
        process_limit = "none: RLIMIT_NPROC is not enforced for root and no pids cgroup"
        warnings.append("the process limit is not enforced (running as root, no pids cgroup)")
    elif level == "namespaces":
        process_limit = "RLIMIT_NPROC (counted per user namespace)"
    else:
        process_limit = "RLIMIT_NPROC (counts every process of this user)"
    if level == "namespaces":
        cleanup = "PID namespace (killing bwrap kills every process inside)"
    elif plan.kill_parent is not None:
        cleanup = f"process group + cgroup.kill ({plan.kill_parent})"
    elif plan.pids_parent is not None:
        cleanup = f"process group + sweep of the pids cgroup ({plan.pids_parent})"
    else:
        cleanup = "process group only: a daemon that calls setsid() can survive"
        warnings.append("processes that leave the process group are not killed")
    if level == "rlimits":
        warnings.append("learner code can read your files and use the network (no namespaces)")
        if is_root:
            warnings.append("learner code runs as root without namespaces")
    return IsolationReport(
        level=level,
        reason=reason,
        bwrap=bwrap,
        process_limit=process_limit,
        cleanup=cleanup,
        warnings=tuple(warnings),
        cgroups=plan if plan.usable else None,
    )
