"""Hostile learner code is contained and reported; the grader survives every outcome.

Every attack is bounded (a fixed number of forks, a fixed allocation, a finite sleep), so a
broken sandbox makes a test fail rather than the machine fall over. Each runs at both isolation
levels unless the defence is one the fallback does not claim (files, network, signals): those
run under namespaces only, and ``docs/grading.md`` says what the fallback cannot defend.
"""

from __future__ import annotations

import contextlib
import dataclasses
import json
import math
import os
import socket
import subprocess
import sys
import textwrap
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import slamcourse
from slamcourse.sandbox import Limits, LoadResult, Unsupported, Worker, probe_isolation
from tests.sandbox.conftest import require_process_limit

MakeWorker = Callable[..., tuple[Worker, LoadResult]]  # the make_worker fixture (conftest.py)
FAST = Limits(call_seconds=1.0)


# -- helpers --------------------------------------------------------------------------------


def processes_with(token: str) -> list[int]:
    """Host pids whose command line contains ``token`` (learner processes exec 'sleep TOKEN')."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            cmdline = (entry / "cmdline").read_bytes()
        except OSError:
            continue
        if token.encode() in cmdline:
            found.append(int(entry.name))
    return found


def wait_gone(token: str, seconds: float = 5.0) -> list[int]:
    """Wait until no process carries ``token``; returns the survivors (empty when all gone)."""
    deadline = time.monotonic() + seconds
    while True:
        alive = processes_with(token)
        if not alive or time.monotonic() > deadline:
            return alive
        time.sleep(0.02)


def kill_all(token: str) -> None:
    for pid in processes_with(token):
        with contextlib.suppress(OSError):
            os.kill(pid, 9)


def sleep_token() -> str:
    """A unique argument for /bin/sleep: 30 s with unique decimals."""
    return "30." + str(int.from_bytes(os.urandom(6), "big")).rjust(15, "1")


def machine_healthy() -> None:
    assert subprocess.run(["true"], check=False, timeout=10).returncode == 0


# -- time -----------------------------------------------------------------------------------


def test_infinite_loop_in_call(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker("def f():\n    while True:\n        pass\n", limits=FAST)
    assert loaded.ok
    started = time.monotonic()
    result = worker.call([])
    assert result.status == "timeout"
    assert "did not finish within 1 s" in result.error
    assert time.monotonic() - started < 4
    proc = worker._res.proc
    assert proc is not None and proc.returncode is not None  # gone, reaped
    again = worker.call([])
    assert again.status == "timeout" and "already stopped" in again.error


def test_busy_loop_at_import(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker("while True:\n    pass\ndef f():\n    return 1\n", limits=FAST)
    assert loaded.status == "timeout"
    assert worker.call([]).status == "timeout"


def test_sleep_in_call_counts_against_total_time(make_worker: MakeWorker) -> None:
    limits = Limits(call_seconds=1.0, total_seconds=1.5)
    worker, loaded = make_worker("import time\ndef f():\n    time.sleep(0.6)\n", limits=limits)
    assert loaded.ok
    assert worker.call([]).status == "ok"  # ~0.1 s start + 0.6 s
    worker.call([])  # ~1.3 s used: ok, or out of time if the machine is slow
    result = worker.call([])  # cannot fit in what is left of the 1.5 s
    assert result.status == "timeout" and "total" in result.error


def test_cpu_limit_kills(make_worker: MakeWorker) -> None:
    limits = Limits(call_seconds=10.0, cpu_seconds=1)
    worker, loaded = make_worker("def f():\n    while True:\n        pass\n", limits=limits)
    assert loaded.ok
    started = time.monotonic()
    result = worker.call([])
    assert result.status == "crashed", result
    assert "SIGKILL" in result.error or "SIGXCPU" in result.error
    assert time.monotonic() - started < 6


def test_thread_left_running_dies_with_worker(make_worker: MakeWorker) -> None:
    token = sleep_token()
    worker, loaded = make_worker(
        f"""
        import subprocess, threading
        def f():
            threading.Thread(target=subprocess.run, args=(["sleep", "{token}"],)).start()
            return 1
        """
    )
    assert loaded.ok and worker.call([]).value == 1
    deadline = time.monotonic() + 5
    while not processes_with(token) and time.monotonic() < deadline:
        time.sleep(0.02)
    assert processes_with(token), "the child never started: the test proves nothing"
    worker.close()
    assert wait_gone(token) == []


# -- memory and processes -------------------------------------------------------------------


@pytest.mark.parametrize(
    "allocation",
    ["bytearray(4 << 30)", "np.ones((4 << 30) // 8)", "[np.zeros(100 << 17) for _ in range(40)]"],
)
def test_memory_bomb(make_worker: MakeWorker, allocation: str) -> None:
    worker, loaded = make_worker(f"import numpy as np\ndef f():\n    return len({allocation})\n")
    assert loaded.ok
    result = worker.call([])
    assert result.status in ("raised", "crashed"), result
    if result.status == "raised":
        assert result.error.startswith(("MemoryError", "_ArrayMemoryError"))
        assert worker.call([]).status == "raised"  # still usable afterwards
    machine_healthy()


def test_fork_bomb_is_limited_and_cleaned_up(make_worker: MakeWorker, level: str) -> None:
    report = probe_isolation(level)
    require_process_limit(report.process_limit)
    token = sleep_token()
    worker, loaded = make_worker(
        f"""
        import os
        def f():
            made = 0
            for _ in range(300):
                try:
                    pid = os.fork()
                except OSError:
                    break
                if pid == 0:
                    try:
                        os.execv("/bin/sleep", ["sleep", "{token}"])
                    finally:
                        os._exit(0)
                made += 1
            return made
        """
    )
    assert loaded.ok
    try:
        result = worker.call([])
        assert result.status == "ok", result
        assert 0 <= result.value < Limits().processes
        worker.close()
        assert wait_gone(token) == []
    finally:
        kill_all(token)
    machine_healthy()
    with Worker.spawn(force=level) as fresh:  # and the sandbox still works
        assert fresh.load("def f():\n    return 2\n", "f.py", "f").ok
        assert fresh.call([]).value == 2


def test_thread_bomb_is_limited(make_worker: MakeWorker, level: str) -> None:
    report = probe_isolation(level)
    require_process_limit(report.process_limit)
    worker, _ = make_worker(
        """
        import threading
        def f():
            stop = threading.Event()
            started = []
            try:
                for _ in range(300):
                    t = threading.Thread(target=stop.wait, args=(5,))
                    t.start()
                    started.append(t)
            except RuntimeError:
                pass
            stop.set()
            return len(started)
        """
    )
    result = worker.call([])
    assert result.status == "ok" and result.value < Limits().processes


def test_setsid_double_fork_daemon_is_killed(make_worker: MakeWorker) -> None:
    token = sleep_token()
    worker, loaded = make_worker(
        f"""
        import os
        def f():
            r, w = os.pipe()  # close-on-exec: EOF once the daemon has exec'd
            pid = os.fork()
            if pid == 0:
                os.setsid()
                if os.fork() == 0:
                    os.execv("/bin/sleep", ["sleep", "{token}"])
                os._exit(0)
            os.close(w)
            os.read(r, 1)
            os.waitpid(pid, 0)
            return "daemonised"
        """
    )
    assert loaded.ok
    try:
        assert worker.call([]).value == "daemonised"
        assert processes_with(token), "the daemon never started: the test proves nothing"
        worker.close()
        assert wait_gone(token) == []
    finally:
        kill_all(token)


def test_fallback_without_cgroups_cannot_kill_daemons() -> None:
    """Documents the weakest level: rlimits and a process group only (no cgroup, no
    namespaces), as on a laptop without a delegated cgroup. A setsid() daemon survives."""
    base = probe_isolation("rlimits")
    report = dataclasses.replace(base, cgroups=None)
    worker = Worker(limits=Limits(), isolation=report)
    worker._start()
    token = sleep_token()
    source = textwrap.dedent(
        f"""
        import os
        def f():
            r, w = os.pipe()  # close-on-exec: EOF once the daemon has exec'd
            if os.fork() == 0:
                os.setsid()
                if os.fork() == 0:
                    os.execv("/bin/sleep", ["sleep", "{token}"])
                os._exit(0)
            os.close(w)
            os.read(r, 1)
            return 1
        """
    )
    try:
        assert worker.load(source, "f.py", "f").ok
        assert worker.call([]).value == 1
        worker.close()
        time.sleep(0.2)
        assert processes_with(token), "expected the daemon to survive (documented limitation)"
    finally:
        worker.close()
        kill_all(token)
    assert wait_gone(token) == []


# -- forging results ------------------------------------------------------------------------


def test_forged_stdout_has_no_effect(make_worker: MakeWorker) -> None:
    forged = json.dumps({"id": 2, "ok": True, "status": "ok", "value": 42})
    worker, loaded = make_worker(
        f"""
        import sys
        print({forged!r}); print("PASSED")
        def f():
            print({forged!r})
            print("PASSED", file=sys.stderr)
            sys.stdout.flush()
            return 1.0
        """
    )
    assert loaded.ok
    result = worker.call([])
    assert result.status == "ok" and result.value == 1.0
    assert "PASSED" in result.stderr and forged in result.stdout


@pytest.mark.parametrize("when", ["import", "call"])
def test_exit_is_a_crash(make_worker: MakeWorker, when: str) -> None:
    for how in ("sys.exit(0)", "os._exit(0)", "raise SystemExit(0)"):
        body = f"import os, sys\n{how}\ndef f():\n    return 1\n"
        if when == "call":
            body = f"import os, sys\ndef f():\n    {how}\n"
        worker, loaded = make_worker(body)
        if when == "import":
            assert loaded.status == "crashed", (how, loaded)
            assert "exited (status 0)" in loaded.message
            continue
        assert loaded.ok
        result = worker.call([])
        assert result.status == "crashed", (how, result)
        assert result.exit_code == 0
        assert worker.call([]).status == "crashed"


# The learner can find its reply descriptor (it is in sys.argv) and write anything to it.
WRITE_TO_RESPONSE_FD = """
import os, sys, json
RESP = int([a for a in sys.argv if a.startswith("resp=")][0][5:])
calls = 0

def send(obj, newline=True):
    os.write(RESP, (json.dumps(obj) + ("\\n" if newline else "")).encode())

def f(mode):
    global calls
    calls += 1
    my_id = calls + 1          # load was request 1
    if mode == "future":       # answer the *next* request in advance
        send({"id": my_id + 1, "status": "ok", "value": 42})
    elif mode == "same":       # answer this request twice: forged first, then the real reply
        send({"id": my_id, "status": "ok", "value": 42})
    elif mode == "past":
        send({"id": my_id - 1, "status": "ok", "value": 42})
    elif mode == "partial":
        send({"id": my_id, "status": "ok", "value": 42}, newline=False)
    elif mode == "huge":
        os.write(RESP, b"[" * (2 << 20))
    elif mode == "bad_status":
        send({"id": my_id, "status": "passed", "value": 42})
    elif mode == "dict_value":
        send({"id": my_id, "status": "ok", "value": {"__reduce__": "os.system"}})
    elif mode == "deep":
        os.write(RESP, b'{"id": %d, "status": "ok", "value": %s%s}\\n'
                 % (my_id, b"[" * 100000, b"]" * 100000))
    elif mode == "bigint":
        os.write(RESP, b'{"id": %d, "status": "ok", "value": 1%s}\\n' % (my_id, b"0" * 5000))
    elif mode == "close":
        os.close(RESP)
    return 1.0
"""


@pytest.mark.parametrize(
    "mode", ["future", "past", "partial", "huge", "bad_status", "dict_value", "deep", "bigint"]
)
def test_protocol_fd_forgery_is_a_protocol_error(make_worker: MakeWorker, mode: str) -> None:
    worker, loaded = make_worker(WRITE_TO_RESPONSE_FD)
    assert loaded.ok
    assert worker.call(["none"]).value == 1.0
    result = worker.call([mode])
    assert result.status == "protocol_error", result
    assert worker.call(["none"]).status == "protocol_error"  # the worker is gone for good


def test_protocol_fd_can_only_lie_about_the_pending_request(make_worker: MakeWorker) -> None:
    """Two replies for one request: at most the first is taken as the answer (which the
    learner could have returned anyway); the extra frame can never answer a later request."""
    worker, loaded = make_worker(WRITE_TO_RESPONSE_FD)
    assert loaded.ok
    first = worker.call(["same"])
    assert first.status in ("ok", "protocol_error")
    if first.status == "ok":
        assert first.value == 42
    for _ in range(3):
        assert worker.call(["none"]).status == "protocol_error"


def test_closing_the_protocol_fd_is_a_crash(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(WRITE_TO_RESPONSE_FD)
    assert loaded.ok
    assert worker.call(["close"]).status in ("crashed", "protocol_error")


def test_forged_frame_at_import(make_worker: MakeWorker) -> None:
    """At import the learner predicts the first call's id and answers it in advance."""
    _worker, loaded = make_worker(
        """
        import os, sys
        RESP = int([a for a in sys.argv if a.startswith("resp=")][0][5:])
        os.write(RESP, b'{"id": 2, "status": "ok", "value": 42}\\n')
        def f():
            return 0
        """
    )
    assert loaded.status == "protocol_error"


# -- lying values ---------------------------------------------------------------------------


def test_lying_objects_become_unsupported(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import sys
        import numpy as np
        class Liar:
            def _tell(self, *a, **k):
                print("LIAR METHOD CALLED")
                return True
            __eq__ = __ne__ = __lt__ = __gt__ = _tell
            def __float__(self): self._tell(); return 1.0
            def __index__(self): self._tell(); return 1
            def __int__(self): self._tell(); return 1
            def __len__(self): self._tell(); return 2
            def __iter__(self): self._tell(); return iter([1.0, 2.0])
            def __array__(self, *a, **k): self._tell(); return np.array([1.0, 2.0])
            def __repr__(self): self._tell(); return "1.0"
            __str__ = __repr__
            @property
            def __class__(self): self._tell(); return float
        class Meta(type):
            @property
            def __name__(cls): print("LIAR METHOD CALLED"); return "float"
        class Sneaky(float, metaclass=Meta):
            def __eq__(self, other): print("LIAR METHOD CALLED"); return True
        class Arr(np.ndarray):
            pass
        def f(kind):
            return {"liar": Liar(), "sneaky": Sneaky(2.0), "sub": np.zeros(2).view(Arr),
                    "nested": [1.0, (Liar(),)]}[kind]
        """
    )
    assert loaded.ok
    expected = {
        "liar": Unsupported("Liar"),
        "sneaky": Unsupported("Sneaky"),
        "sub": Unsupported("Arr"),
        "nested": [1.0, [Unsupported("Liar")]],
    }
    for kind, value in expected.items():
        result = worker.call([kind])
        assert result.status == "ok" and result.value == value, (kind, result)
        assert "LIAR" not in result.stdout


def test_nan_and_inf_are_decoded_as_floats(make_worker: MakeWorker) -> None:
    worker, _ = make_worker(
        "import numpy as np\ndef f():\n"
        "    return [float('nan'), float('inf'), -np.inf, np.array([np.nan])]\n"
    )
    result = worker.call([])
    assert result.status == "ok"
    nan, inf, ninf, arr = result.value
    assert math.isnan(nan) and inf == math.inf and ninf == -math.inf and math.isnan(arr[0])
    assert all(type(v) is float for v in (nan, inf, ninf))


def test_huge_integers_are_refused(make_worker: MakeWorker) -> None:
    worker, _ = make_worker("def f():\n    return 10 ** 5000\n")
    assert worker.call([]).value == Unsupported("int (too large)")


def test_monkeypatching_in_child_has_no_effect_on_parent(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import builtins, json, math
        import numpy as np
        math.isclose = lambda *a, **k: True
        np.allclose = lambda *a, **k: True
        np.ndarray = float
        json.dumps = lambda *a, **k: '{"id": 99, "status": "ok", "value": 42}'
        json.loads = lambda *a, **k: {"op": "call", "args": []}
        builtins.len = lambda x: 0
        builtins.isinstance = lambda *a: True
        def f(x):
            return x + 1
        """
    )
    assert loaded.ok, loaded
    result = worker.call([1])
    assert result.status == "ok" and result.value == 2
    assert not math.isclose(1.0, 2.0)
    assert not np.allclose([1.0], [2.0])
    assert json.loads(json.dumps([1])) == [1]
    assert len([1, 2]) == 2


# -- files, network, signals (namespaces only) ----------------------------------------------


def test_private_files_are_invisible(make_ns_worker: MakeWorker, tmp_path: Path) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text("expected values")
    package = Path(slamcourse.__file__).resolve().parent
    repo = package.parent.parent
    home = Path.home()
    interpreter_parts = {str(p) for p in Path(os.path.realpath(sys.executable)).parents}
    home_entries = [str(p) for p in home.iterdir() if str(p) not in interpreter_parts][:20]
    paths = [
        str(secret),
        str(package),
        str(package / "sandbox" / "worker.py"),
        str(repo / "exercises"),
        str(repo / "chapters"),
        str(repo / "src"),
        "/etc/passwd",
        "/etc/shadow",
        *home_entries,
    ]
    worker, loaded = make_ns_worker(
        """
        import os, sys
        def f(paths):
            try:
                import slamcourse
                imported = True
            except ImportError:
                imported = False
            return [imported, [p for p in paths if os.path.exists(p)], sys.path]
        """
    )
    assert loaded.ok
    result = worker.call([paths])
    assert result.status == "ok", result
    imported, visible, sys_path = result.value
    assert imported is False
    assert visible == []
    assert not any("site-packages" in p for p in sys_path)


def test_sandbox_file_system_is_read_only_except_tmp(make_ns_worker: MakeWorker) -> None:
    worker, _ = make_ns_worker(
        """
        import os
        def f():
            out = {}
            for path in ["/x", "/usr/x", "/dev/shm/x", "/tmp/x", os.path.join(os.__file__ + "x")]:
                try:
                    with open(path, "w") as fh:
                        fh.write("1")
                    out[path] = "written"
                except OSError as exc:
                    out[path] = type(exc).__name__
            return sorted(out.items())
        """
    )
    result = worker.call([])
    values = dict(result.value)
    assert values.pop("/tmp/x") == "written"
    assert set(values.values()) <= {"OSError", "PermissionError", "FileNotFoundError"}


def test_tmp_is_small(make_ns_worker: MakeWorker) -> None:
    worker, _ = make_ns_worker(
        """
        def f():
            with open("/tmp/big", "wb") as fh:
                for _ in range(40):
                    fh.write(b"x" * (1 << 20))
        """
    )
    result = worker.call([])
    assert result.status == "raised"
    assert "No space left" in result.error or "File too large" in result.error


def test_no_network(make_ns_worker: MakeWorker) -> None:
    listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    listener.bind(("127.0.0.1", 0))
    listener.listen(1)
    listener.settimeout(0.2)
    port = listener.getsockname()[1]
    try:
        worker, _ = make_ns_worker(
            """
            import socket
            def f(port):
                try:
                    socket.create_connection(("127.0.0.1", port), timeout=1).close()
                    return "connected"
                except OSError as exc:
                    return type(exc).__name__
            """
        )
        result = worker.call([port])
        assert result.status == "ok"
        assert result.value != "connected"
        with pytest.raises(TimeoutError):
            listener.accept()
    finally:
        listener.close()


def test_signals_cannot_reach_the_grader(make_ns_worker: MakeWorker) -> None:
    worker, loaded = make_ns_worker(
        """
        import os, signal
        def f():
            out = []
            for target in (os.getppid(), 1, -1):
                try:
                    os.kill(target, signal.SIGKILL)
                    out.append("sent")
                except OSError as exc:
                    out.append(type(exc).__name__)
            return [os.getpid(), out]
        """
    )
    assert loaded.ok
    result = worker.call([])
    assert result.status in ("ok", "crashed")
    machine_healthy()  # we are still here, and so is everything outside the sandbox


def test_no_privileges_inside(make_ns_worker: MakeWorker) -> None:
    worker, _ = make_ns_worker(
        """
        import os
        def f():
            status = open("/proc/self/status").read()
            caps = [l.split()[1] for l in status.splitlines() if l.startswith("CapEff")]
            try:
                os.unshare(os.CLONE_NEWUSER)
                nested = "allowed"
            except (AttributeError, OSError) as exc:
                nested = type(exc).__name__
            return [os.getuid(), caps, nested, sorted(os.environ)]
        """
    )
    uid, caps, nested, env = worker.call([]).value
    assert uid == 65534 and caps == ["0000000000000000"] and nested != "allowed"
    assert set(env) <= {
        "PATH",
        "HOME",
        "OPENBLAS_NUM_THREADS",
        "OMP_NUM_THREADS",
        "MKL_NUM_THREADS",
        "LC_CTYPE",
        "PWD",
    }


def test_environment_is_scrubbed(make_worker: MakeWorker, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SLAMCOURSE_SECRET_TOKEN", "hunter2")
    worker, _ = make_worker("import os\ndef f():\n    return sorted(os.environ)\n")
    env = worker.call([]).value
    assert "SLAMCOURSE_SECRET_TOKEN" not in env and "SLAMCOURSE_HOME" not in env


# -- size -----------------------------------------------------------------------------------


def test_huge_output_is_truncated(make_worker: MakeWorker) -> None:
    worker, _ = make_worker(
        """
        import sys
        def f():
            chunk = "x" * (1 << 20)
            for _ in range(5):  # (past eight times the 1 MiB budget, a call is stopped)
                sys.stdout.write(chunk)
            sys.stderr.write("e" * (2 << 20))
            return 7
        """
    )
    result = worker.call([])
    assert result.status == "ok" and result.value == 7
    limit = Limits().output_bytes
    assert result.stdout.startswith("x" * 1000) and len(result.stdout) < limit + 200
    assert "more bytes of output discarded" in result.stdout
    assert len(result.stderr) < limit + 200


@pytest.mark.parametrize("value", ["[0.5] * 10 ** 7", "np.zeros(10 ** 7)", "['x' * 9000] * 200"])
def test_huge_return_value_is_refused(make_worker: MakeWorker, value: str) -> None:
    worker, _ = make_worker(f"import numpy as np\ndef f():\n    return {value}\n")
    result = worker.call([])
    assert result.status == "protocol_error"
    assert "too large" in result.error


def test_deep_recursion_is_raised(make_worker: MakeWorker) -> None:
    worker, _ = make_worker("def f(n=0):\n    return f(n + 1)\n")
    result = worker.call([])
    assert result.status == "raised"
    assert result.error.startswith("RecursionError")
    assert 0 < len(result.frames) <= 20 and result.frames[-1].function == "f"


def test_deeply_nested_return_value(make_worker: MakeWorker) -> None:
    worker, _ = make_worker(
        "def f():\n    x = []\n    for _ in range(10000):\n        x = [x]\n    return x\n"
    )
    result = worker.call([])
    assert result.status == "ok"
    value = result.value
    depth = 0
    while isinstance(value, list):
        value, depth = value[0], depth + 1
    assert isinstance(value, Unsupported) and depth < 40


def test_open_files_limit(make_worker: MakeWorker) -> None:
    worker, _ = make_worker(
        "import os\ndef f():\n    return [os.open('/dev/null', os.O_RDONLY) for _ in range(200)]\n"
    )
    result = worker.call([])
    assert result.status == "raised" and "Too many open files" in result.error


def test_grader_fine_after_everything(level: str) -> None:
    """After the attacks the grader still spawns, loads and calls normally."""
    with Worker.spawn(force=level) as worker:
        assert worker.load("def f(x):\n    return x\n", "f.py", "f", ["x"]).ok
        assert worker.call([np.float64(1.5)]).value == 1.5
