"""The grader's side of the sandbox: start a worker, load learner code, call it, kill it.

Typical use::

    with Worker.spawn() as worker:          # starts the worker (it imports numpy meanwhile)
        loaded = worker.load(source, "observation_model.py", "observation_model",
                             params=["xr", "yr", "thr", "xj", "yj"])
        if loaded.status == "ok":
            result = worker.call([0.0, 0.0, 0.0, 3.0, 4.0])   # CallResult(status="ok", ...)

:meth:`Worker.spawn` returns at once; the worker imports numpy in the background, so a caller can
start it early (e.g. before its own imports, or keep one ready for the next check) and
:meth:`Worker.load` waits for it. A worker runs one submission; after ``timeout``, ``crashed``
or ``protocol_error`` it is dead and every later request returns the same status.

The worker never returns Python objects: every reply is one size-limited line of JSON, decoded
and re-validated here (see :mod:`slamcourse.sandbox.protocol`). A ``Worker`` is not thread-safe.
"""

from __future__ import annotations

import contextlib
import json
import os
import select
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import weakref
from collections.abc import Sequence
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass, field, fields, replace
from types import TracebackType
from typing import Any, Literal, get_args

from slamcourse.errors import GraderError, SandboxError
from slamcourse.sandbox.isolation import (
    SANDBOX_WORKER_PATH,
    WORKER_SCRIPT,
    IsolationReport,
    Limits,
    WorkerCgroups,
    bwrap_command,
    probe_isolation,
    worker_env,
)
from slamcourse.sandbox.protocol import (
    LearnerFrame,
    ProtocolViolation,
    clean_text,
    decode_frame,
    encode_calls,
    encode_request,
    frames_field,
    int_or_none,
    names_field,
    text_field,
    value_and_array,
)

LoadStatus = Literal[
    "ok",
    "syntax_error",
    "import_error",
    "missing_function",
    "not_callable",
    "signature",
    "timeout",
    "crashed",
    "protocol_error",
]
CallStatus = Literal["ok", "raised", "timeout", "crashed", "protocol_error"]
Fatal = Literal["timeout", "crashed", "protocol_error"]
StopReason = Literal["flooded", "processes"]
STOP_REASONS: frozenset[str] = frozenset(get_args(StopReason))
FLOOD_MESSAGE = "your code printed more than"  # how a worker killed for its output is described
_POLL = 0.05  # seconds between checks that the worker is still alive while waiting
_POLL_REPLIES = 0.02  # ... and between reads of replies written without the bell (a call that
# returned just before one that hangs: the worker rings the bell every few ms, not per reply)
_LOAD_STATUSES = frozenset(
    {"ok", "syntax_error", "import_error", "missing_function", "not_callable", "signature"}
)


@dataclass(frozen=True)
class LoadResult:
    """Outcome of loading the learner's file.

    - ``ok``: the function exists and accepts the expected number of positional arguments;
    - ``syntax_error``: ``line`` and ``message``;
    - ``import_error``: the file raised while it ran; ``message`` and learner-only ``frames``;
    - ``missing_function``: ``found`` lists the functions the file does define;
    - ``not_callable``: the name exists but is not callable (``found`` holds its type);
    - ``signature``: ``expected`` parameters versus ``found`` (names may differ, counts may not);
    - ``timeout`` / ``crashed`` / ``protocol_error``: the worker is dead; see ``message``.
    """

    status: LoadStatus
    message: str = ""
    line: int | None = None
    frames: tuple[LearnerFrame, ...] = ()
    expected: tuple[str, ...] = ()
    found: tuple[str, ...] = ()
    stdout: str = ""
    stderr: str = ""
    exit_code: int | None = None
    output_cut: bool = False

    @property
    def ok(self) -> bool:
        return self.status == "ok"


@dataclass(frozen=True)
class CallResult:
    """Outcome of one call.

    - ``ok``: ``value`` is plain data (None, bool, int, float (maybe NaN/inf), str, lists,
      :class:`~slamcourse.sandbox.protocol.Unsupported` markers); tuples arrive as lists;
    - ``raised``: ``error`` is ``"TypeName: message"``, ``frames`` the learner's own frames;
    - ``timeout`` / ``crashed`` / ``protocol_error``: ``error`` says what happened.

    ``stdout`` and ``stderr`` hold what the learner printed during the call (cleaned, capped);
    ``output_cut`` is True once any of the worker's output was discarded (see
    :class:`~slamcourse.sandbox.isolation.Limits`). ``mutated``: the positions of the arguments
    the call left changed (the worker compares them with what it was sent).
    """

    status: CallStatus
    value: Any = None
    error: str = ""
    frames: tuple[LearnerFrame, ...] = ()
    stdout: str = ""
    stderr: str = ""
    seconds: float = 0.0
    exit_code: int | None = None
    output_cut: bool = False
    mutated: tuple[int, ...] = ()
    """Positions of the arguments the call changed in place (checked unless told not to)."""
    stopped: StopReason | None = None
    """Why :meth:`Worker.call_many` stopped after this call: ``"flooded"``, it alone printed
    more than ``Limits.muted_after``; ``"processes"``, it left a process it started running
    (a child of the worker, none exited)."""
    array: Any = field(default=None, compare=False, repr=False)
    """``value`` as a float64 ndarray when it came as one (a float array sent as its bytes),
    else None: compared as it is, not converted back from ``value``'s lists."""

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    @classmethod
    def returned(
        cls, value: Any, seconds: float, output_cut: bool, array: Any = None
    ) -> CallResult:
        """``CallResult("ok", value=value, seconds=seconds, output_cut=output_cut,
        array=array)``, made without the frozen ``__init__``'s cost per field (the reply of
        almost every call)."""
        result = object.__new__(cls)
        result.__dict__.update(
            _RETURNED, value=value, seconds=seconds, output_cut=output_cut, array=array
        )
        return result


_RETURNED = {f.name: f.default for f in fields(CallResult)} | {"status": "ok"}


@dataclass
class _Outcome:
    """What one request produced: a frame, or a fatal status with a message."""

    status: Literal["frame"] | Fatal
    frame: dict[str, Any] | None = None
    message: str = ""
    stdout: str = ""
    stderr: str = ""
    seconds: float = 0.0
    exit_code: int | None = None
    output_cut: bool = False


class _Capture:
    """The bytes a stream produced during one request (shown: the first ``limit``)."""

    def __init__(self, limit: int, carried: bytes = b"") -> None:
        self.limit = limit
        self.data = bytearray(carried)  # read earlier, produced during this request
        self.seen = 0  # bytes read from the pipe during this request

    def add(self, chunk: bytes) -> None:
        self.seen += len(chunk)
        self.data += chunk

    def keep(self, count: int) -> bytes:
        """Keep the first ``count`` bytes; return the rest (a later call's output)."""
        if not 0 <= count < len(self.data):
            return b""
        rest = bytes(self.data[count:])
        del self.data[count:]
        return rest

    @property
    def dropped(self) -> int:
        return max(0, len(self.data) - self.limit)

    def text(self) -> str:
        if not self.data:
            return ""
        text = clean_text(bytes(self.data[: self.limit]))
        if self.dropped:
            text += f"\n[… {self.dropped} more bytes of output discarded]"
        return text


class _Resources:
    """Everything that must be released when a worker goes away (also via weakref.finalize)."""

    def __init__(self) -> None:
        self.proc: subprocess.Popen[bytes] | _Forked | None = None
        self.fds: list[int] = []
        self.cgroups: WorkerCgroups | None = None
        self.tmpdir: str | None = None
        self.closed = False

    def kill(self, closing: bool = False) -> None:
        """SIGKILL the worker's process group, its cgroups (daemons too) and reap it.
        ``closing``: the worker is being closed (see below)."""
        proc = self.proc
        if isinstance(proc, _Forked):  # its pid is the zygote's to signal, not ours
            if closing:  # SIGKILL to its process group, asked of the zygote without waiting
                # for an answer (it forks the next worker meanwhile; it reaps this one at its
                # next request: waiting for it to unmap its memory, ~2 ms, would only delay
                # the next exercise); what is left in its cgroups (anything it started that
                # left its process group) is killed and the cgroups removed in the background
                proc.signal()
                if self.cgroups is not None:
                    cgroups, self.cgroups = self.cgroups, None
                    proc.zygote._reap_later(cgroups)
                return
            proc.kill()  # (a timeout or crash: its end is reported, so it is awaited)
            if self.cgroups is not None:
                proc.wait(timeout=2.0)  # (its cgroups can be removed once it has exited)
                self.cgroups.kill()
            return
        if proc is not None and proc.returncode is None:
            with contextlib.suppress(OSError):
                os.killpg(proc.pid, signal.SIGKILL)
        if self.cgroups is not None:
            self.cgroups.kill()
        if proc is not None:
            with contextlib.suppress(OSError):
                proc.kill()
            with contextlib.suppress(subprocess.TimeoutExpired):
                proc.wait(timeout=10)

    def close(self) -> None:
        if self.closed:
            return
        self.closed = True
        try:
            self.kill(closing=True)
        finally:
            for fd in self.fds:
                with contextlib.suppress(OSError):
                    os.close(fd)
            self.fds = []
            if isinstance(self.proc, subprocess.Popen):
                for stream in (self.proc.stdout, self.proc.stderr):
                    if stream is not None:
                        with contextlib.suppress(OSError):
                            stream.close()
            if self.cgroups is not None:
                self.cgroups.close_fds()
                self.cgroups.remove(wait=2.0)
            if self.tmpdir is not None:
                shutil.rmtree(self.tmpdir, ignore_errors=True)


def _process_config(limits: Limits) -> dict[str, int]:
    """The :class:`Limits` a worker process is started with, as ``worker.py`` reads them (its
    resource limits, the cgroup's ``pids.max``, its largest frame, its muted output); the
    others are kept by the grader's side only."""
    return {
        "as": limits.memory_bytes,
        "cpu": limits.cpu_seconds,
        "fsize": limits.file_bytes,
        "nofile": limits.open_files,
        "nproc": limits.processes,
        "frame": limits.frame_bytes,
        "out": limits.muted_after,
    }


class Worker:
    """One sandboxed interpreter running one learner's file. Use as a context manager."""

    def __init__(self, *, limits: Limits, isolation: IsolationReport) -> None:
        """Use :meth:`spawn`."""
        self._limits = limits
        self._isolation = isolation
        self._res = _Resources()
        self._finalizer = weakref.finalize(self, self._res.close)
        self._next_id = 0
        self._ready = False
        self._loaded: LoadResult | None = None
        self._dead: tuple[Fatal, str, int | None] | None = None  # status, message, exit code
        self._budget = limits.total_seconds
        self._buffer = bytearray()
        self._output_seen = 0  # bytes of stdout + stderr read from this worker so far
        self._output_cut = False
        self._taken = [0, 0]  # bytes of stdout, stderr attributed to replies so far
        self._carry: tuple[bytes, bytes] = (b"", b"")  # read, but a later call's output
        self._req_w = -1
        self._resp_r = -1
        self._out_r = -1
        self._err_r = -1
        self._bell_r = -1
        self.startup_seconds: float | None = None
        """Seconds from :meth:`spawn` until the worker reported ready (None before)."""
        self.unenforced_limits: tuple[str, ...] = ()
        """Resource limits this system refused to set (e.g. ``("as",)`` on macOS)."""
        self._spawned_at = 0.0

    # -- start ----------------------------------------------------------------------------------

    @classmethod
    def spawn(
        cls,
        *,
        limits: Limits | None = None,
        require_isolation: bool = False,
        force: str | None = None,
    ) -> Worker:
        """Start a worker now and return at once (it imports numpy in the background).

        ``require_isolation=True`` (or ``force="namespaces"``) raises :class:`SandboxError` when
        namespaces are unavailable. ``force`` overrides ``SLAMCOURSE_SANDBOX`` (see
        :func:`~slamcourse.sandbox.isolation.probe_isolation`).
        """
        limits = limits if limits is not None else Limits()
        worker = cls(limits=limits, isolation=_isolation(require_isolation, force))
        worker._start()
        return worker

    def _start(self) -> None:
        res, limits = self._res, self._limits
        req_r, req_w = os.pipe()
        resp_r, resp_w = os.pipe()
        bell_r, bell_w = os.pipe()
        res.fds += [req_w, resp_r, bell_r]
        self._req_w, self._resp_r, self._bell_r = req_w, resp_r, bell_r
        try:
            if self._isolation.cgroups is not None:
                res.cgroups = WorkerCgroups.create(self._isolation.cgroups, limits)
            cg_fds = res.cgroups.fds if res.cgroups is not None else []
            worker_args = [
                f"req={req_r}",
                f"resp={resp_w}",
                f"bell={bell_w}",
                *(f"{key}={value}" for key, value in _process_config(limits).items()),
                "cg=" + ",".join(str(fd) for fd in cg_fds),
            ]
            cmd, env, cwd = _command(self._isolation, limits, res, worker_args, "worker")
            self._spawned_at = time.monotonic()
            res.proc = subprocess.Popen(
                cmd,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                pass_fds=(req_r, resp_w, bell_w, *cg_fds),
                start_new_session=True,
                env=env,
                cwd=cwd,
            )
        except OSError as exc:
            self._res.close()
            raise SandboxError(f"cannot start the sandbox worker: {exc}") from exc
        finally:
            os.close(req_r)
            os.close(resp_w)
            os.close(bell_w)
            if res.cgroups is not None:
                res.cgroups.close_fds()
        assert res.proc.stdout is not None and res.proc.stderr is not None
        self._out_r = res.proc.stdout.fileno()
        self._err_r = res.proc.stderr.fileno()
        for fd in (self._resp_r, self._out_r, self._err_r, self._req_w, self._bell_r):
            os.set_blocking(fd, False)

    def _start_forked(self, zygote: Zygote) -> None:
        """Have ``zygote`` fork this worker (see :class:`Zygote`)."""
        res, limits = self._res, self._limits
        try:
            if self._isolation.cgroups is not None:
                res.cgroups = WorkerCgroups.create(self._isolation.cgroups, limits)
            cg_fds = res.cgroups.fds if res.cgroups is not None else []
            self._spawned_at = time.monotonic()
            pid, fds = zygote._fork(_process_config(limits), cg_fds)
        except BaseException:
            self._res.close()
            raise
        finally:
            if res.cgroups is not None:
                res.cgroups.close_fds()
        res.proc = _Forked(zygote, pid)
        res.fds += fds
        self._req_w, self._resp_r, self._out_r, self._err_r, self._bell_r = fds
        for fd in fds:
            os.set_blocking(fd, False)

    # -- public ---------------------------------------------------------------------------------

    @property
    def isolation(self) -> IsolationReport:
        return self._isolation

    @property
    def limits(self) -> Limits:
        return self._limits

    @property
    def alive(self) -> bool:
        return self._dead is None and not self._res.closed

    @property
    def fresh(self) -> bool:
        """Started, never asked anything, and silent since: not dead, no output, no frame
        (a worker forked ahead that another process killed meanwhile is not fresh)."""
        return (
            self.alive
            and self._ready
            and self._loaded is None
            and not any(_readable(fd) for fd in (self._resp_r, self._out_r, self._err_r))
        )

    def adopt_limits(self, limits: Limits) -> bool:
        """Have a fresh worker keep ``limits`` from now on instead of the ones it was started
        with, when they differ only on the grader's side (time budgets, output kept per
        request, flood and start bounds): True. False, and nothing changed, when the process
        itself would differ (its resource limits and cgroup, its largest frame, its muted
        output: set when it started) or it is not fresh."""
        if not self.fresh or _process_config(limits) != _process_config(self._limits):
            return False
        used = self._limits.total_seconds - self._budget  # (its start counts)
        self._limits = limits
        self._budget = limits.total_seconds - used
        return True

    def wait_ready(self) -> None:
        """Wait until the worker has started (its ``ready`` frame); :meth:`load` does this
        itself. Raises :class:`SandboxError` if it cannot start."""
        if self._dead is None:
            self._await_ready()

    def load(
        self,
        source: str,
        filename: str,
        function: str,
        params: Sequence[str] | None = None,
    ) -> LoadResult:
        """Send the learner's source text; it is compiled as ``filename`` and run as a module.

        Raises :class:`SandboxError` if the worker cannot start at all (before any learner code
        ran) and :class:`GraderError` if called twice.
        """
        if self._loaded is not None:
            raise GraderError("Worker.load() called twice; use one worker per submission")
        if self._dead is not None or not self._await_ready():
            return self._remember(self._dead_load())
        request = {
            "op": "load",
            "source": source,
            "filename": filename,
            "function": function,
            "params": list(params) if params is not None else None,
        }
        out = self._request(request)
        if out.status != "frame":
            return self._remember(
                LoadResult(
                    out.status,
                    message=out.message,
                    stdout=out.stdout,
                    stderr=out.stderr,
                    exit_code=out.exit_code,
                    output_cut=out.output_cut,
                )
            )
        assert out.frame is not None
        try:
            result = self._load_result(out.frame, out)
        except ProtocolViolation as exc:
            self._fail("protocol_error", f"the worker broke the protocol: {exc}")
            return self._remember(self._dead_load(out))
        return self._remember(result)

    def call(self, args: Sequence[Any], *, check: bool = True) -> CallResult:
        """Call the loaded function with ``args`` (plain data; tuples, dicts and numpy arrays
        arrive as such). ``check``: compare the arguments after the call with what was sent
        (``CallResult.mutated``; a batch's record is each call's pickle). Raises
        :class:`GraderError` if there is no loaded function."""
        results = self._calls("call", [args], check)
        return results[0]

    def call_many(self, calls: Sequence[Sequence[Any]], *, check: bool = True) -> list[CallResult]:
        """Call the loaded function once per argument list of ``calls``, in one request.

        Each call is answered by a frame of its own, with its own deadline
        (``Limits.call_seconds``) and its own captured output; the result list is shorter than
        ``calls`` when the worker died (the last result says how: timeout, crash, broken
        protocol) or when the worker stopped the batch after a call (``stopped``: its output
        was muted, so a flood is not repeated on every input, or it left a process it started
        running, with which every later call would share the CPU). ``check`` as for
        :meth:`call`. ``calls`` may
        carry its request body already encoded (an ``encoded`` attribute, from
        :func:`~slamcourse.sandbox.protocol.encode_calls`): a batch encodes its inputs once;
        and a callback ``enough(index, result)``: when it returns True for a result that is not
        the last, the worker is stopped there (killed: it is done) and the results so far are
        returned.
        """
        if not calls:
            return []
        return self._calls("calls", calls, check)

    def _calls(self, op: str, calls: Sequence[Sequence[Any]], check: bool) -> list[CallResult]:
        if self._dead is not None:
            status, message, code = self._dead
            return [CallResult(status, error=f"worker already stopped: {message}", exit_code=code)]
        if self._loaded is None or not self._loaded.ok:
            raise GraderError("Worker.call() needs a successful Worker.load() first")
        first = self._next_id + 1
        self._next_id += len(calls)
        encoded = getattr(calls, "encoded", None)
        enough = getattr(calls, "enough", None)
        if op == "calls" and check:  # pickled, one record per call (encoded once for a batch)
            if not isinstance(encoded, bytes):
                encoded = encode_calls(calls)
            payload = b'{"id":%d,' % first + encoded
        else:
            if op == "call":
                request: dict[str, Any] = {"op": "call", "args": list(calls[0])}
            else:
                request = {"op": "calls", "calls": [list(args) for args in calls]}
            if not check:
                request["check"] = False
            payload = encode_request({"id": first, **request})
        results: list[CallResult] = []
        count = len(calls)
        index = 0
        while index < count:
            # the frames the worker has already sent for this batch (but its last) are taken
            # together; anything else (the first reply, the last, a call that printed, or
            # nothing read yet) goes through the full exchange, one frame
            ready = (
                self._ready_frames(first + index, count - 1 - index)
                if index and not self._carry[0] and not self._carry[1]
                else []
            )
            outs: list[_Outcome | None] = [None] * len(ready)
            if not ready:
                out = self._exchange(
                    payload if index == 0 else None, first + index, self._limits.call_seconds,
                    more=index + 1 < count,
                )  # fmt: skip
                if out.status != "frame":
                    self._fail(out.status, out.message, out.exit_code)
                    results.append(
                        CallResult(
                            out.status,
                            error=out.message,
                            stdout=out.stdout,
                            stderr=out.stderr,
                            seconds=out.seconds,
                            exit_code=out.exit_code,
                            output_cut=out.output_cut,
                        )
                    )
                    return results
                assert out.frame is not None
                ready, outs = [out.frame], [out]
            for frame, read in zip(ready, outs, strict=True):
                out = read or _Outcome("frame", frame, "", "", "", 0.0, None, self._output_cut)
                try:
                    result = self._call_result(frame, out, len(calls[index]))
                except ProtocolViolation as exc:
                    self._fail("protocol_error", f"the worker broke the protocol: {exc}")
                    results.append(
                        CallResult(
                            "protocol_error",
                            error=self._dead[1] if self._dead else "",
                            stdout=out.stdout,
                            stderr=out.stderr,
                            seconds=out.seconds,
                            output_cut=out.output_cut,
                        )
                    )
                    return results
                stop = frame.get("stop")
                if stop in STOP_REASONS:
                    results.append(replace(result, stopped=stop))
                    return results
                results.append(result)
                if enough is not None and index + 1 < count and enough(index, result):
                    # the caller has what it needs: stop the worker mid-batch, not read on
                    self._fail("crashed", "stopped by the grader after the results it needed")
                    return results
                index += 1
        return results

    def close(self) -> None:
        """Kill the worker and everything it started; release pipes, cgroups and temp files."""
        if self._dead is None:
            self._dead = ("crashed", "the worker was closed", None)
        self._finalizer()

    def __enter__(self) -> Worker:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    # -- replies --------------------------------------------------------------------------------

    def _remember(self, result: LoadResult) -> LoadResult:
        self._loaded = result
        return result

    def _dead_load(self, out: _Outcome | None = None) -> LoadResult:
        assert self._dead is not None
        status, message, code = self._dead
        return LoadResult(
            status,
            message=message,
            exit_code=code,
            stdout=out.stdout if out else "",
            stderr=out.stderr if out else "",
            output_cut=out.output_cut if out else False,
        )

    def _load_result(self, frame: dict[str, Any], out: _Outcome) -> LoadResult:
        status = frame["status"]
        if status not in _LOAD_STATUSES:
            raise ProtocolViolation(f"unexpected load status {status!r}")
        return LoadResult(
            status,
            message=text_field(frame, "message"),
            line=int_or_none(frame, "line"),
            frames=frames_field(frame),
            expected=names_field(frame, "expected"),
            found=names_field(frame, "found"),
            stdout=out.stdout,
            stderr=out.stderr,
            output_cut=self._note_dropped(frame, out),
        )

    def _call_result(self, frame: dict[str, Any], out: _Outcome, arity: int) -> CallResult:
        status = frame["status"]
        if (
            status == "ok"
            and "value" in frame
            and "mutated" not in frame
            and frame.get("dropped") == 0
            and type(frame["dropped"]) is int
            and not out.stdout
            and not out.stderr
        ):  # the common reply: a value, nothing printed, dropped or changed
            self._output_cut = self._output_cut or out.output_cut
            value, array = value_and_array(frame)
            return CallResult.returned(value, out.seconds, self._output_cut, array)
        mutated = frame.get("mutated", ())  # (absent: nothing changed, the common reply)
        if mutated != () and (
            type(mutated) is not list
            or any(type(i) is not int or not 0 <= i < arity for i in mutated)
        ):
            raise ProtocolViolation("reply field 'mutated' is not a list of argument positions")
        common: dict[str, Any] = {
            "stdout": out.stdout,
            "stderr": out.stderr,
            "seconds": out.seconds,
            "output_cut": self._note_dropped(frame, out),
            "mutated": tuple(sorted(set(mutated))) if mutated else (),
        }
        if status == "ok":
            if "value" not in frame:
                raise ProtocolViolation("ok reply without a value")
            value, array = value_and_array(frame)
            return CallResult("ok", value=value, array=array, **common)
        if status == "raised":
            return CallResult(
                "raised", error=text_field(frame, "error"), frames=frames_field(frame), **common
            )
        if status == "oversize":
            size = int_or_none(frame, "size")
            what = f"{size} bytes" if size else "too many values"
            return CallResult(
                "protocol_error",
                error=f"the return value is too large to check ({what}; the limit is "
                f"{self._limits.frame_bytes} bytes of JSON)",
                **common,
            )
        raise ProtocolViolation(f"unexpected call status {status!r}")

    def _note_dropped(self, frame: dict[str, Any], out: _Outcome) -> bool:
        """True once any output was discarded: muted by the worker (its ``dropped`` count, a
        courtesy: informational only) or dropped by this side's per-request capture."""
        if (int_or_none(frame, "dropped") or 0) > 0 or out.output_cut:
            self._output_cut = True
        return self._output_cut

    # -- transport ------------------------------------------------------------------------------

    def _fail(self, status: Fatal, message: str, exit_code: int | None = None) -> None:
        if self._dead is None:
            self._dead = (status, message, exit_code)
        self._res.kill()

    def _await_ready(self) -> bool:
        """Wait for the worker's ``ready`` frame; True, or SandboxError (no learner code ran)."""
        if self._ready:
            return True
        out = self._exchange(None, 0, self._limits.start_seconds, starting=True)
        frame = out.frame
        if out.status != "frame" or frame is None or frame.get("status") != "ready":
            stderr = out.stderr.strip()
            self.close()
            detail = f": {stderr[-500:]}" if stderr else ""
            raise SandboxError(f"the sandbox worker did not start ({out.message}){detail}")
        expected = len(self._res.cgroups.dirs) if self._res.cgroups is not None else 0
        if frame.get("cgroups") != expected:
            self.close()
            raise SandboxError("the sandbox worker could not join its cgroups")
        refused = frame.get("refused", [])
        if type(refused) is list and all(type(r) is str for r in refused):
            self.unenforced_limits = tuple(refused)
        self._ready = True
        self.startup_seconds = time.monotonic() - self._spawned_at
        return True

    def _request(self, request: dict[str, Any]) -> _Outcome:
        self._next_id += 1
        payload = encode_request({"id": self._next_id, **request})
        out = self._exchange(payload, self._next_id, self._limits.call_seconds)
        if out.status != "frame":
            self._fail(out.status, out.message, out.exit_code)
        return out

    def _exchange(
        self,
        payload: bytes | None,
        request_id: int,
        seconds: float,
        *,
        starting: bool = False,
        more: bool = False,
    ) -> _Outcome:
        """Send ``payload`` (None: just wait) and wait for the frame with ``request_id``;
        ``more``: further frames of the same request may follow it."""
        limits = self._limits
        start = time.monotonic()
        per_request = start + seconds
        overall = start + self._budget
        deadline = min(per_request, overall)
        out_cap = _Capture(limits.output_bytes, self._carry[0])
        err_cap = _Capture(limits.output_bytes, self._carry[1])
        self._carry = (b"", b"")
        proc = self._res.proc
        assert proc is not None

        def finish(
            status: Literal["frame"] | Fatal,
            message: str = "",
            frame: dict[str, Any] | None = None,
            exit_code: int | None = None,
        ) -> _Outcome:
            if frame is None or self._owed(frame, out_cap, err_cap):
                self._drain(out_cap, err_cap)  # (a frame that owes nothing: no system call)
            if frame is not None:  # a frame says how much output its call wrote
                self._attribute(frame, out_cap, err_cap)
            elapsed = time.monotonic() - start
            self._budget -= elapsed
            self._output_seen += out_cap.seen + err_cap.seen
            cut = bool(out_cap.dropped or err_cap.dropped or self._output_cut)
            self._output_cut = cut
            return _Outcome(
                status, frame, message, out_cap.text(), err_cap.text(), elapsed, exit_code, cut
            )

        def flooded() -> bool:
            return self._output_seen + out_cap.seen + err_cap.seen > limits.flood_bytes

        def stop_flood() -> _Outcome:
            self._res.kill()
            self._output_cut = True
            return finish(
                "crashed",
                f"{FLOOD_MESSAGE} {limits.flood_bytes >> 20} MiB of output, so it was stopped; "
                "print less (not on every call or in a loop)",
            )

        def timed_out() -> _Outcome:
            self._res.kill()
            if time.monotonic() >= overall and overall < per_request:
                msg = (
                    f"time limit exceeded: this submission used its total of "
                    f"{limits.total_seconds:g} s"
                )
            elif starting:
                msg = f"the worker did not start within {seconds:g} s"
            else:
                msg = f"your code did not finish within {seconds:g} s"
            return finish("timeout", msg)

        def crashed() -> _Outcome:
            with contextlib.suppress(subprocess.TimeoutExpired):
                proc.wait(timeout=1.0)  # let it finish exiting, to report its real status
            self._res.kill()
            code = proc.returncode
            return finish("crashed", _describe_exit(code), exit_code=code)

        if payload is not None:
            if not self._buffer and _readable(self._resp_r):
                try:
                    chunk = os.read(self._resp_r, 1 << 16)
                except BlockingIOError:
                    chunk = b"?"
                if not chunk:
                    return crashed()
                self._buffer += chunk
            if self._buffer:
                self._res.kill()
                return finish("protocol_error", "the worker sent a reply nobody asked for")
            view = memoryview(payload)
            while view:
                now = time.monotonic()
                if now >= deadline:
                    return timed_out()
                try:
                    _r, writable, _x = select.select(
                        [], [self._req_w], [], min(deadline - now, _POLL)
                    )
                except InterruptedError:  # pragma: no cover
                    continue
                if not writable:
                    if proc.poll() is not None:
                        return crashed()
                    continue
                try:
                    view = view[os.write(self._req_w, view) :]
                except BlockingIOError:
                    continue
                except BrokenPipeError:
                    return crashed()

        while True:
            newline = self._buffer.find(b"\n")
            if newline >= 0:
                line = bytes(self._buffer[:newline])
                del self._buffer[: newline + 1]
                if len(line) > limits.frame_bytes:
                    break  # oversize, reported below
                if self._buffer and not more:
                    self._res.kill()
                    return finish("protocol_error", "the worker sent more than one reply")
                try:
                    frame = decode_frame(line)
                except ProtocolViolation as exc:
                    self._res.kill()
                    return finish("protocol_error", f"the worker broke the protocol: {exc}")
                if frame["id"] != request_id:
                    self._res.kill()
                    return finish(
                        "protocol_error",
                        f"the worker answered request {frame['id']} instead of {request_id}",
                    )
                return finish("frame", frame=frame)
            if len(self._buffer) > limits.frame_bytes:
                break
            try:  # what the worker has written, rung or not (so never a reply left unread)
                replies = os.read(self._resp_r, 1 << 16)
            except BlockingIOError:
                replies = None
            except OSError:
                replies = b""
            if replies is not None:
                if not replies:
                    return crashed()
                self._buffer += replies
                continue
            now = time.monotonic()
            if now >= deadline:
                return timed_out()
            fds = [self._out_r, self._err_r]
            if self._bell_r >= 0:
                fds.append(self._bell_r)
            try:
                readable, _w, _x = select.select(fds, [], [], min(deadline - now, _POLL_REPLIES))
            except InterruptedError:  # pragma: no cover
                continue
            if self._out_r in readable:
                _read_into(self._out_r, out_cap)
            if self._err_r in readable:
                _read_into(self._err_r, err_cap)
            if (self._out_r in readable or self._err_r in readable) and flooded():
                return stop_flood()
            if self._bell_r in readable:
                try:
                    rung = os.read(self._bell_r, 1 << 12)
                except BlockingIOError:
                    rung = b"!"
                except OSError:
                    rung = b""
                if not rung:  # the bell was closed (the learner's code did it, or the worker
                    self._bell_r = -1  # died: then its reply pipe ends too): poll replies
                continue
            if not readable and proc.poll() is not None and not _readable(self._resp_r):
                return crashed()

        self._res.kill()
        return finish(
            "protocol_error",
            f"the reply is larger than the {limits.frame_bytes}-byte frame limit",
        )

    def _ready_frames(self, request_id: int, most: int) -> list[dict[str, Any]]:
        """The batch's next frames (from ``request_id``, at most ``most``) that are already
        read and whose calls printed nothing (the common case while the worker runs ahead of
        the grader): taken from the buffer together, what :meth:`_exchange` would return for
        each, without waiting or reading output pipes. Stops before anything else, which
        :meth:`_exchange` then handles in full (nothing of it consumed)."""
        buffer = self._buffer
        limit = self._limits.frame_bytes
        out, err = self._taken
        frames: list[dict[str, Any]] = []
        start = 0
        while len(frames) < most:
            newline = buffer.find(b"\n", start)
            if newline < 0 or newline - start > limit:
                break
            try:
                frame = decode_frame(bytes(buffer[start:newline]))
            except ProtocolViolation:
                break
            if (
                frame["id"] != request_id + len(frames)
                or frame.get("out") != out
                or frame.get("err") != err
                or type(frame.get("out")) is not int
                or type(frame.get("err")) is not int
            ):
                break
            frames.append(frame)
            start = newline + 1
        if start:
            del buffer[:start]
        return frames

    def _owed(self, frame: dict[str, Any], out_cap: _Capture, err_cap: _Capture) -> bool:
        """Whether output the frame's call wrote may still be in the pipes (always, for a
        frame without byte counts). Output written around the muted streams is not counted;
        it is collected with a later reply."""
        for i, (key, cap) in enumerate((("out", out_cap), ("err", err_cap))):
            total = frame.get(key)
            if type(total) is not int or total - self._taken[i] > len(cap.data):
                return True
        return False

    def _attribute(self, frame: dict[str, Any], out_cap: _Capture, err_cap: _Capture) -> None:
        """Batched calls run ahead of the replies read here: each frame carries the bytes
        written to stdout and stderr so far, so its call keeps only its own output and the
        rest is carried to the next call's result."""
        carry = []
        for i, (key, cap) in enumerate((("out", out_cap), ("err", err_cap))):
            total = frame.get(key)
            if type(total) is not int:
                carry.append(b"")
                continue
            carry.append(cap.keep(total - self._taken[i]))
            self._taken[i] = total
        self._carry = (carry[0], carry[1])

    def _drain(self, out_cap: _Capture, err_cap: _Capture) -> None:
        """Collect the output that is already in the pipes (bounded)."""
        for fd, cap in ((self._out_r, out_cap), (self._err_r, err_cap)):
            for _ in range(64):
                if not _read_into(fd, cap):
                    break


def _isolation(require_isolation: bool, force: str | None) -> IsolationReport:
    """This machine's isolation level; SandboxError when namespaces are required but missing."""
    report = probe_isolation(force)
    wanted = force or os.environ.get("SLAMCOURSE_SANDBOX", "auto")
    if (require_isolation or wanted == "namespaces") and report.level != "namespaces":
        raise SandboxError(
            f"refusing to run learner code without namespace isolation: {report.reason}"
        )
    return report


def _command(
    isolation: IsolationReport, limits: Limits, res: _Resources, args: list[str], what: str
) -> tuple[list[str], dict[str, str], str]:
    """The command, environment and working directory that start ``worker.py`` with
    ``args``: inside bubblewrap, or (the fallback) in a private temporary directory."""
    python = os.path.abspath(sys.executable)
    if isolation.level == "namespaces":
        assert isolation.bwrap is not None
        program = [python, "-I", "-B", SANDBOX_WORKER_PATH, *args]
        cmd = bwrap_command(isolation.bwrap, limits, program, as_pid_1=what == "zygote")
        return cmd, {"PATH": "/usr/bin:/bin"}, "/"
    res.tmpdir = tempfile.mkdtemp(prefix=f"slamcourse-{what}-")
    cmd = [python, "-I", "-B", str(WORKER_SCRIPT), *args]
    return cmd, worker_env(res.tmpdir), res.tmpdir


class _Forked:
    """A worker forked by a :class:`Zygote`. Its pid is the zygote's (in the zygote's pid
    namespace), so it is signalled and reaped through the zygote, never directly."""

    def __init__(self, zygote: Zygote, pid: int) -> None:
        self.zygote = zygote
        self.pid = pid
        self.returncode: int | None = None

    def poll(self) -> int | None:
        return self.returncode  # its death shows as end of file on its pipes

    def wait(self, timeout: float) -> int | None:
        if self.returncode is None:
            self.returncode = self.zygote._wait(self.pid, timeout)
        return self.returncode

    def kill(self) -> None:
        if self.returncode is None:
            self.zygote._kill(self.pid)

    def signal(self) -> None:
        """SIGKILL it and its process group, without waiting for the zygote's answer."""
        if self.returncode is None:
            self.zygote._tell({"op": "kill", "pid": self.pid, "answer": False})


class Zygote:
    """A sandboxed interpreter that has imported numpy once and forks fresh workers.

    ::

        with Zygote.spawn() as zygote:            # one learner's submission at a time
            with zygote.worker(limits) as worker:  # a fresh process per exercise
                worker.load(...); worker.call_many(...)
            zygote.reset()                         # None: fit for the next learner

    A forked worker is a :class:`Worker` like a started one: a new process with its own
    pipes, resource limits (``limits``) and cgroups, its own session, not dumpable (no other
    process of the sandbox can ptrace it or read its memory), killed with the zygote. What it
    saves is the interpreter start and the numpy import (about 0.3 s each). Workers of one
    zygote share its namespaces (file system view, private ``/tmp``, pid namespace), so a
    zygote serves ONE learner at a time, and another only after :meth:`reset` has proven that
    nothing of the last one is left (under namespaces, where the zygote is the sandbox's
    init and sees every process in it). Thread-safe.
    """

    def __init__(self, *, limits: Limits, isolation: IsolationReport) -> None:
        """Use :meth:`spawn`."""
        self._limits = limits
        self._isolation = isolation
        self._res = _Resources()
        self._finalizer = weakref.finalize(self, self._res.close)
        self._lock = threading.Lock()
        self._sock: socket.socket | None = None
        self._dead = False
        self._reaping: list[Future[None]] = []
        self.startup_seconds: float | None = None

    @classmethod
    def spawn(
        cls,
        *,
        limits: Limits | None = None,
        require_isolation: bool = False,
        force: str | None = None,
        preload: Sequence[str] = (),
        preload_first: bool = False,
    ) -> Zygote:
        """Start a zygote and wait until it is ready (raises :class:`SandboxError` if it cannot
        start). ``require_isolation`` and ``force`` as for :meth:`Worker.spawn`; ``limits``
        gives the start-up time and the size of the private ``/tmp``; ``preload``: modules the
        zygote imports once it has forked its first worker (e.g. ``scipy.sparse``), so later
        workers do not import them again; with ``preload_first``, as soon as it is ready (a
        zygote started ahead, which nobody waits for yet)."""
        limits = limits if limits is not None else Limits()
        zygote = cls(limits=limits, isolation=_isolation(require_isolation, force))
        zygote._start(preload, preload_first)
        return zygote

    def _start(self, preload: Sequence[str] = (), preload_first: bool = False) -> None:
        res, limits = self._res, self._limits
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        started = time.monotonic()
        try:
            args = [f"zygote={theirs.fileno()}", f"frame={limits.frame_bytes}"]
            if preload:
                args.append("preload=" + ",".join(preload))
                if preload_first:
                    args.append("preload_first=1")
            cmd, env, cwd = _command(self._isolation, limits, res, args, "zygote")
            res.proc = subprocess.Popen(
                cmd,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.PIPE,
                pass_fds=(theirs.fileno(),),
                start_new_session=True,
                env=env,
                cwd=cwd,
            )
        except OSError as exc:
            ours.close()
            self._res.close()
            raise SandboxError(f"cannot start the sandbox zygote: {exc}") from exc
        finally:
            theirs.close()
        self._sock = ours
        try:
            reply, _fds = self._ask(None, (), limits.start_seconds)
        except SandboxError as exc:
            stderr = b""
            proc = res.proc
            self.close()
            if isinstance(proc, subprocess.Popen) and proc.stderr is not None:
                with contextlib.suppress(OSError, ValueError):
                    stderr = proc.stderr.read(4000) or b""
            detail = clean_text(stderr).strip()
            raise SandboxError(f"{exc}{': ' + detail[-500:] if detail else ''}") from None
        if reply.get("status") != "ready":
            self.close()
            raise SandboxError("the sandbox zygote did not start")
        self.startup_seconds = time.monotonic() - started

    @property
    def alive(self) -> bool:
        proc = self._res.proc
        return (
            not self._dead
            and not self._res.closed
            and isinstance(proc, subprocess.Popen)
            and proc.poll() is None
        )

    @property
    def isolation(self) -> IsolationReport:
        return self._isolation

    def worker(self, limits: Limits | None = None) -> Worker:
        """A fresh worker forked now, with ``limits`` (default: :class:`Limits`); use it as a
        :class:`Worker`. Raises :class:`SandboxError` if the zygote is gone."""
        worker = Worker(limits=limits or Limits(), isolation=self._isolation)
        worker._start_forked(self)
        return worker

    def reset(self) -> str | None:
        """Make the zygote fit to serve ANOTHER learner, or say why it is not (None: it is).

        Every worker it forked is killed and reaped (closed ones: their cgroups swept and
        removed first), and the zygote proves the sandbox holds nothing of the last learner:
        no process but its own and bubblewrap's init in the pid namespace, ``/tmp`` emptied,
        no System V IPC object, its own inheritable attributes (resource limits, nice value,
        affinity, scheduling, cgroups, ``/tmp``'s mode) as they were when it started (see
        ``reset`` in ``worker.py``). Only under namespaces: without a pid namespace the
        zygote cannot see every process a learner's code may have left. A zygote that is not
        fit should be closed."""
        if not self._isolation.isolated:
            return "no pid namespace: the processes a learner left cannot all be seen"
        self._await_reaping()
        try:
            reply, fds = self._ask({"op": "reset"}, (), self._limits.start_seconds)
        except SandboxError as exc:
            return str(exc)
        for fd in fds:
            os.close(fd)
        if reply.get("status") == "clean":
            return None
        why = reply.get("why")
        return why if type(why) is str else "the sandbox zygote could not be reset"

    def _await_reaping(self) -> None:
        with self._lock:
            reaping, self._reaping = self._reaping, []
        for done in reaping:
            with contextlib.suppress(Exception):
                done.result(timeout=10.0)

    def close(self) -> None:
        """Stop the zygote and every worker it forked (after the cgroups of the closed ones are
        swept and removed)."""
        self._await_reaping()
        self._dead = True
        with self._lock:
            sock, self._sock = self._sock, None
        if sock is not None:
            sock.close()  # the zygote kills its workers and exits at end of file
        proc = self._res.proc
        if isinstance(proc, subprocess.Popen):
            with contextlib.suppress(subprocess.TimeoutExpired):
                proc.wait(timeout=2.0)
        self._finalizer()

    def __enter__(self) -> Zygote:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    # -- control channel ------------------------------------------------------------------------

    def _ask(
        self, request: dict[str, Any] | None, fds: Sequence[int], seconds: float = 10.0
    ) -> tuple[dict[str, Any], list[int]]:
        """Send ``request`` (None: only read) with ``fds``; the reply and the descriptors in it."""
        with self._lock:
            sock = self._sock
            if sock is None or self._dead:
                raise SandboxError("the sandbox zygote has stopped")
            try:
                sock.settimeout(seconds)
                if request is not None:
                    data = json.dumps(request).encode()
                    if fds:
                        socket.send_fds(sock, [data], list(fds))
                    else:
                        sock.send(data)
                reply, got, _flags, _addr = socket.recv_fds(sock, 1 << 16, 8)
            except (OSError, ValueError) as exc:
                self._dead = True
                raise SandboxError(f"the sandbox zygote stopped answering ({exc})") from None
        if not reply:
            self._dead = True
            for fd in got:
                os.close(fd)
            raise SandboxError("the sandbox zygote has stopped")
        try:
            decoded = json.loads(reply)
        except ValueError:
            decoded = None
        if type(decoded) is not dict:
            for fd in got:
                os.close(fd)
            self._dead = True
            raise SandboxError("the sandbox zygote sent an unreadable reply")
        return decoded, got

    def _reap_later(self, cgroups: WorkerCgroups) -> None:
        """Kill whatever is left in a closed worker's cgroups, wait until they are empty and
        remove them, on a background thread; :meth:`close` and :meth:`reset` wait for it."""
        global _REAPER
        try:
            with _REAPER_LOCK:
                if _REAPER is None:
                    _REAPER = ThreadPoolExecutor(max_workers=1, thread_name_prefix="sandbox-reap")
                done = _REAPER.submit(_sweep, cgroups)
        except RuntimeError:  # the interpreter is shutting down: no new threads; sweep now
            _sweep(cgroups)
            return
        with self._lock:
            self._reaping = [f for f in self._reaping if not f.done()]
            self._reaping.append(done)

    def _fork(self, cfg: dict[str, int], cg_fds: Sequence[int]) -> tuple[int, list[int]]:
        reply, fds = self._ask({"op": "fork", "cfg": cfg}, cg_fds)
        pid = reply.get("pid")
        if reply.get("status") != "forked" or type(pid) is not int or len(fds) != 5:
            for fd in fds:
                os.close(fd)
            raise SandboxError("the sandbox zygote could not fork a worker")
        return pid, fds

    def _kill(self, pid: int) -> None:
        with contextlib.suppress(SandboxError):
            self._ask({"op": "kill", "pid": pid}, ())

    def _tell(self, request: dict[str, Any]) -> None:
        """Send a request the zygote does not answer (no lock: nothing is read back, and the
        zygote reads requests in the order they were sent)."""
        sock = self._sock
        if sock is None or self._dead:
            return
        with contextlib.suppress(OSError):
            sock.send(json.dumps(request).encode())

    def _wait(self, pid: int, timeout: float) -> int | None:
        try:
            reply, _fds = self._ask({"op": "wait", "pid": pid, "timeout": timeout}, ())
        except SandboxError:
            return None
        code = reply.get("code")
        return code if type(code) is int else None


_REAPER: ThreadPoolExecutor | None = None  # sweeps closed forked workers' cgroups
_REAPER_LOCK = threading.Lock()


def _sweep(cgroups: WorkerCgroups) -> None:
    cgroups.kill()  # (waits until every process in them has exited: a zombie is not listed
    # and does not keep a cgroup from being removed, so the zygote's reaping is not awaited)
    cgroups.close_fds()
    cgroups.remove(wait=2.0)


def _readable(fd: int) -> bool:
    try:
        readable, _w, _x = select.select([fd], [], [], 0)
    except (OSError, ValueError):
        return False
    return bool(readable)


def _read_into(fd: int, cap: _Capture) -> bool:
    """Read one chunk from ``fd`` into ``cap``; False when nothing (more) is available."""
    try:
        chunk = os.read(fd, 1 << 16)
    except (BlockingIOError, OSError):
        return False
    if not chunk:
        return False
    cap.add(chunk)
    return True


def _describe_exit(code: int | None) -> str:
    """A sentence about how the worker ended (bwrap reports a signal as 128 + number)."""
    if code is None:
        return "the process running your code stopped responding"
    signum = -code if code < 0 else code - 128 if code > 128 else 0
    if signum:
        try:
            name = signal.Signals(signum).name
        except ValueError:
            name = f"signal {signum}"
        hint = {
            "SIGKILL": " (a resource limit such as CPU time or memory, or it was killed)",
            "SIGXCPU": " (CPU time limit)",
            "SIGSEGV": " (for example a stack overflow from very deep recursion)",
        }.get(name, "")
        return f"the process running your code was killed by {name}{hint}"
    return (
        f"the process running your code exited (status {code}) before answering; "
        "does your file call sys.exit() or os._exit()?"
    )
