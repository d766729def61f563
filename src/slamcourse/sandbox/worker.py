"""The sandbox worker: the only program that ever runs a learner's code.

This file is executed as a script by :mod:`slamcourse.sandbox.runner`, never imported by the
grader. It uses the standard library and (optionally) numpy only: it must not import slamcourse,
hypothesis or anything from the course, because under namespace isolation none of those exist in
its file system, and because everything in this process is under the learner's control once
their code has run.

Invocation (all values are decimal integers)::

    python -I -B worker.py req=FD resp=FD bell=FD as=BYTES cpu=SECONDS fsize=BYTES nofile=N \
        nproc=N frame=BYTES [out=CHARS] [cg=FD,FD,...]

Order of events:

1. join the cgroups whose ``cgroup.procs`` files the parent opened for us (``cg=``), close those
   descriptors, then set every resource limit with soft = hard so nothing can raise them again;
2. import numpy (if installed) and send a ``ready`` frame;
3. answer requests read from ``req`` (one JSON object per line) with one JSON line each on
   ``resp``: ``load`` (source text, file name, function name, expected parameters), ``call``
   (arguments) and ``calls`` (many argument lists, one reply each; a batch's are pickled after
   the line: ``"pickled": N`` bytes, from the parent only). End of file on ``req`` means "exit
   now".

Replies and the bell: every reply is written to ``resp`` as soon as its call returns, so that
whatever has returned is in the pipe even if the next call never does; but the parent waits on
``bell`` (a byte written there), not on ``resp``. The bell rings after the last reply of a
request, and within a batch once :data:`RING_SECONDS` have passed or :data:`RING_BYTES` have been
written since it last rang: a batch of quick calls wakes the parent every few milliseconds
instead of once per call. (While it waits, the parent also reads ``resp`` every few tens of
milliseconds, so replies written just before a call that hangs are found without a bell.)

Learner output is muted past ``out`` characters per stream (over the worker's whole life):
``sys.stdout`` and ``sys.stderr`` become writers that keep the first ``out`` characters and
count the rest, so a ``print`` in a loop costs almost nothing once the budget is spent. Every
reply carries ``dropped``, the characters discarded so far. A call that has written more than
:data:`FLOOD_FACTOR` times ``out`` characters is stopped there: the muted write raises
:class:`OutputFlood` (a ``BaseException``, which ``except Exception`` does not catch), so a
``print`` in a loop that never ends gets its verdict in about a second instead of running to
the call's time limit. (Such a call floods anyway: more than ``out`` in one call fails it.)
(Output written around these writers, e.g. with ``os.write(1, ...)``, reaches the parent,
which kills a worker that floods.)

Return values are converted to plain JSON data here, with exact type checks only (``type(x) is
float``), so no method of a learner object is called while encoding; anything else becomes an
``{"unsupported": "<type name>"}`` marker. A float array of at least ``BINARY_FLOATS`` entries is
sent as its bytes, ``{"$f8": "<base64 of its float64 values, little-endian, C order>", "shape":
[...]}``, which the parent turns back into the same nested lists: exact, and without writing
and parsing every float as text. Exceptions become text here, so no learner object ever
crosses the pipe. The parent re-validates everything it receives: this encoding is a courtesy,
not a defence.
"""

from __future__ import annotations

import os
import resource
import sys


def _parse_argv(argv: list[str]) -> dict[str, str]:
    out: dict[str, str] = {}
    for token in argv:
        key, _, value = token.partition("=")
        out[key] = value
    return out


def _contain(cfg: dict[str, str]) -> tuple[int, list[str]]:
    """Join the parent's cgroups, then set the resource limits.

    Returns the number of cgroups joined and the limits the system refused to set.
    """
    joined = 0
    for text in filter(None, cfg.get("cg", "").split(",")):
        fd = int(text)
        try:
            os.write(fd, b"0\n")  # "0" = the writing process; its children inherit the cgroup
            joined += 1
        except OSError:
            pass
        finally:
            os.close(fd)
    limits = (
        ("core", 0),
        ("as", int(cfg["as"])),
        ("cpu", int(cfg["cpu"])),
        ("fsize", int(cfg["fsize"])),
        ("nofile", int(cfg["nofile"])),
        ("nproc", int(cfg["nproc"])),
    )
    refused = []
    for name, wanted in limits:
        which: int = getattr(resource, "RLIMIT_" + name.upper(), -1)
        try:
            _soft, hard = resource.getrlimit(which)
            value = wanted if hard == resource.RLIM_INFINITY else min(wanted, hard)
            resource.setrlimit(which, (value, value))
        except (TypeError, ValueError, OSError):  # e.g. RLIMIT_AS on macOS
            refused.append(name)
    return joined, refused


# Step 1 runs before anything else is imported. A zygote contains each child it forks
# instead (see ``_zygote``): its own code is the worker's, never a learner's.
_CFG = _parse_argv(sys.argv[1:])
_ZYGOTE = "zygote" in _CFG
_JOINED, _REFUSED = (0, []) if _ZYGOTE else _contain(_CFG)

import binascii  # noqa: E402
import builtins  # noqa: E402
import contextlib  # noqa: E402
import io  # noqa: E402
import json  # noqa: E402
import pickle  # noqa: E402
import time  # noqa: E402
import types  # noqa: E402
from typing import Any  # noqa: E402

_np: Any
try:
    import numpy

    _np = numpy
except Exception:  # numpy missing or broken: learners get an ImportError of their own
    _np = None

# Keep private references: learner code may monkeypatch the public names. This is robustness,
# not security: the learner controls this whole process, and the parent trusts none of it.
_write = os.write
_monotonic = time.monotonic
_b2a = binascii.b2a_base64
_pickle, _unpickle = pickle.dumps, pickle.loads
_ENCODER = json.JSONEncoder(allow_nan=True, separators=(",", ":"))
_BUILTINS = builtins.__dict__
_BUILTINS_SNAPSHOT = dict(_BUILTINS)
_FunctionType = types.FunctionType
_ModuleType = types.ModuleType
_type_name_getter = type.__dict__["__name__"].__get__
_str = str
_len = len
_WAITID = getattr(os, "waitid", None)  # (not on every platform)
_P_ALL = getattr(os, "P_ALL", 0)
_WAIT_LOOK = getattr(os, "WEXITED", 0) | os.WNOHANG | getattr(os, "WNOWAIT", 0)
_isinstance = isinstance

MAX_DEPTH = 32  # nesting of lists/tuples in a return value
MAX_NODES = 600_000  # values in one return value; more cannot fit in a 1 MiB frame anyway
MAX_STR = 10_000  # characters of a returned string
MAX_INT_BITS = 10_000  # bigger ints are not sent (JSON ints over 4300 digits are refused)
MAX_ERROR = 2_000  # characters of an exception's text
MAX_FRAMES = 20  # learner traceback frames kept (the innermost ones)
RING_SECONDS = 0.005  # within a batch: the bell rings at least this often while calls return
RING_BYTES = 32 << 10  # ... and once this much has been written since it rang (pipe: 64 KiB)
BINARY_FLOATS = 16  # a float array of at least this many entries is sent as bytes, not text

if _np is not None:
    _NDARRAY: type | None = _np.ndarray
    _NP_SCALARS: frozenset[type] = frozenset(
        {
            _np.bool_,
            _np.int8,
            _np.int16,
            _np.int32,
            _np.int64,
            _np.uint8,
            _np.uint16,
            _np.uint32,
            _np.uint64,
            _np.float16,
            _np.float32,
            _np.float64,
        }
    )
    _ARRAY_FROM = _np.array
else:
    _NDARRAY = None
    _NP_SCALARS = frozenset()


FLOOD_FACTOR = 8
"""A call that writes more than this many times the output budget (``out=``) is stopped."""


class OutputFlood(BaseException):
    """Raised by a muted write once the running call has written more than
    :data:`FLOOD_FACTOR` times the output budget: it never ends well (the call floods)."""


_CALL_MARK = float("inf")
"""Characters written to stdout and stderr together when the running call began (infinite
between calls: output at import or between calls is only muted, never stopped)."""


class _MutedStream(io.TextIOBase):
    """A text stream that passes the first ``budget`` characters to ``real``, then only
    counts (``dropped``). stdout and stderr each get one; ``print`` works unchanged."""

    def __init__(self, real: Any, budget: int) -> None:
        self._real = real
        self._left = budget
        self.dropped = 0
        self.written = 0  # characters the learner wrote, kept or not
        self.passed = 0  # bytes passed on to the real stream

    def write(self, text: str) -> int:
        if not _isinstance(text, str):  # as io.TextIOWrapper.write
            raise TypeError(f"write() argument must be str, not {_type_name(type(text))}")
        size = _len(text)
        self.written += size
        if self._left > 0:
            part = text[: self._left]
            self._left -= _len(part)
            self._real.write(part)
            self.passed += _len(part.encode(self._real.encoding, self._real.errors))
            self.dropped += size - _len(part)
        else:
            self.dropped += size
            if _STDOUT.written + _STDERR.written - _CALL_MARK > FLOOD_FACTOR * _BUDGET:
                raise OutputFlood(
                    f"your function printed more than {FLOOD_FACTOR * _BUDGET >> 20} MiB in "
                    "one call, so it was stopped there (a print in a loop that does not end?)"
                )
        return size

    def flush(self) -> None:
        self._real.flush()

    def writable(self) -> bool:
        return True

    @property
    def buffer(self) -> Any:  # bytes written here bypass the budget; the parent caps them
        return self._real.buffer

    def fileno(self) -> int:
        return int(self._real.fileno())

    @property
    def encoding(self) -> str:  # type: ignore[override]
        return str(self._real.encoding)


def _restore_builtins() -> None:
    """Undo patches of ``builtins`` (e.g. ``builtins.len = ...``) before the worker's own code
    runs again; names the learner added are kept."""
    try:  # noqa: SIM105 (not contextlib.suppress: this runs twice per call)
        _BUILTINS.update(_BUILTINS_SNAPSHOT)
    except BaseException:
        pass


class _Oversize(Exception):
    """The return value is too large to send."""


def _type_name(t: type) -> str:
    """The class name read from the type slot itself (a metaclass property cannot intervene)."""
    try:
        name = _type_name_getter(t, type)
    except BaseException:
        name = "?"
    return _str(name)[:100] if type(name) is str else "?"


def encode(value: Any) -> Any:
    """Turn a learner's return value into plain JSON data without calling its methods."""
    budget = [MAX_NODES]
    return _encode(value, 0, budget)


def _encode(x: Any, depth: int, budget: list[int]) -> Any:
    budget[0] -= 1
    if budget[0] < 0:
        raise _Oversize
    t = type(x)
    if x is None or t is bool or t is float:
        return x
    if t is int:
        if x.bit_length() > MAX_INT_BITS:
            return {"unsupported": "int (too large)"}
        return x
    if t is str:
        return x if _len(x) <= MAX_STR else {"unsupported": "str (too long)"}
    if t is list or t is tuple:
        if depth >= MAX_DEPTH:
            return {"unsupported": f"{t.__name__} (nested too deeply)"}
        if _len(x) > budget[0]:
            raise _Oversize
        return [_encode(item, depth + 1, budget) for item in x]
    if t in _NP_SCALARS:
        return x.item()
    if t is _NDARRAY:
        kind = x.dtype.kind
        if kind not in "biuf" or x.dtype.itemsize > 8 or x.dtype.fields is not None:
            return {"unsupported": f"ndarray[{x.dtype.name}]"}
        if x.size > budget[0]:
            raise _Oversize
        budget[0] -= x.size
        if x.ndim > MAX_DEPTH - depth:
            return {"unsupported": "ndarray (too many dimensions)"}
        if kind == "f" and x.size >= BINARY_FLOATS:  # its float64 bytes: exact, and no text
            raw = x.astype("<f8").tobytes()  # (a float's decimal form costs ~20x more each way)
            return {"$f8": _b2a(raw, newline=False).decode("ascii"), "shape": list(x.shape)}
        return x.tolist()
    return {"unsupported": _type_name(t)}


def decode_arg(obj: dict[str, Any]) -> Any:
    """``json.loads`` object hook: rebuild the tagged tuples, dicts and arrays the parent sent.

    Inside ``args`` every JSON object is a tag (``{"$tuple": [...]}``, ``{"$dict": [[k, v],
    ...]}``, ``{"$ndarray": [...], "$dtype": "float64", "$shape": [...]}``); untagged objects
    are the request envelope itself.
    """
    if "$tuple" in obj:
        return tuple(obj["$tuple"])
    if "$dict" in obj:
        return {k: v for k, v in obj["$dict"]}
    if "$ndarray" in obj:
        if _np is None:
            return None  # the learner's own numpy use fails the same way
        array = _ARRAY_FROM(obj["$ndarray"], dtype=obj["$dtype"])
        return array.reshape(obj["$shape"]) if "$shape" in obj else array  # ([] of 0 x 3)
    return obj


class Session:
    """The state of one worker: the loaded learner module and the function to call."""

    def __init__(self, resp_fd: int, frame_limit: int, bell_fd: int = -1) -> None:
        self.resp_fd = resp_fd
        self.bell_fd = bell_fd
        self.frame_limit = frame_limit
        self.rung = _monotonic()  # when the bell last rang
        self.unrung = 0  # bytes written to resp since
        self.filename = "<learner>"
        self.lines: list[str] = []
        self.function: Any = None

    # -- output ---------------------------------------------------------------------------------

    def send(self, frame: dict[str, Any], last: bool = True) -> None:
        """Write ``frame`` to ``resp``; ring the bell if it is the ``last`` of its request, or
        if the bell is due (see the module's docstring)."""
        if _flush_learner_output():  # (the learner's own stream objects ran: undo patches)
            _restore_builtins()
        frame["dropped"] = _STDOUT.dropped + _STDERR.dropped
        frame["out"], frame["err"] = _STDOUT.passed, _STDERR.passed
        data = (_ENCODER.encode(frame) + "\n").encode()
        if _len(data) > self.frame_limit:
            oversize = {"id": frame.get("id"), "status": "oversize", "size": _len(data)}
            data = (_ENCODER.encode(oversize) + "\n").encode()
        view = memoryview(data)
        while view:
            written = _write(self.resp_fd, view)
            view = view[written:]
        self.unrung += _len(data)
        if last or self.unrung >= RING_BYTES or _monotonic() - self.rung >= RING_SECONDS:
            self.ring()

    def ring(self) -> None:
        try:  # noqa: SIM105 (a full bell pipe is ringing already; a closed one is noticed)
            _write(self.bell_fd, b"!")
        except OSError:
            pass
        self.rung = _monotonic()
        self.unrung = 0

    # -- errors ---------------------------------------------------------------------------------

    def describe(self, exc: BaseException) -> dict[str, Any]:
        name = _type_name(type(exc))
        try:
            message = _str(exc)
        except BaseException:
            message = "<exception text unavailable>"
        if type(message) is not str:
            message = "<exception text unavailable>"
        text = f"{name}: {message}" if message else name
        return {"error": text[:MAX_ERROR], "frames": self.frames(exc.__traceback__)}

    def frames(self, tb: Any) -> list[dict[str, Any]]:
        found: list[tuple[int, str]] = []
        while tb is not None:
            code = tb.tb_frame.f_code
            if code.co_filename == self.filename:
                found.append((tb.tb_lineno, _str(code.co_name)))
                if _len(found) > MAX_FRAMES:
                    del found[0]
            tb = tb.tb_next
        out = []
        for line, function in found:
            text = self.lines[line - 1].strip()[:200] if 0 < line <= _len(self.lines) else ""
            out.append({"line": line, "text": text, "function": function[:100]})
        return out

    # -- requests -------------------------------------------------------------------------------

    def load(self, req: dict[str, Any]) -> dict[str, Any]:
        source = req["source"]
        self.filename = req["filename"]
        # The line breaks Python itself counts (str.splitlines also splits at \f, \x1c, U+2028...)
        self.lines = source.replace("\r\n", "\n").replace("\r", "\n").split("\n")
        try:
            code = compile(source, self.filename, "exec", dont_inherit=True)
        except SyntaxError as exc:
            message = _str(exc.msg) if exc.msg else "invalid syntax"
            return {"status": "syntax_error", "line": exc.lineno, "message": message[:MAX_ERROR]}
        except (ValueError, RecursionError, MemoryError, OverflowError) as exc:
            return {"status": "syntax_error", "line": None, "message": _str(exc)[:MAX_ERROR]}
        stem = self.filename.rsplit("/", 1)[-1].removesuffix(".py")
        name = stem if stem.isidentifier() and stem not in sys.modules else "learner_submission"
        module = _ModuleType(name)
        module.__file__ = self.filename
        sys.modules[name] = module
        try:
            exec(code, module.__dict__)
        except (SystemExit, KeyboardInterrupt):
            raise
        except BaseException as exc:
            _restore_builtins()
            info = self.describe(exc)
            return {"status": "import_error", "message": info["error"], "frames": info["frames"]}
        _restore_builtins()
        namespace = module.__dict__
        function = namespace.get(req["function"]) if type(namespace) is dict else None
        if function is None:
            defined = sorted(
                k for k, v in namespace.items() if type(k) is str and type(v) is _FunctionType
            )[:20]
            return {"status": "missing_function", "found": defined}
        if not callable(function):
            return {"status": "not_callable", "found": [_type_name(type(function))]}
        params = req.get("params")
        if params is not None:
            problem = _arity_problem(function, _len(params))
            if problem is not None:
                return {"status": "signature", "expected": params, "found": problem}
        self.function = function
        return {"status": "ok"}

    def call(self, args: list[Any], check: bool, record: bytes | None = None) -> dict[str, Any]:
        """Call the function once. With ``check``, the arguments are compared afterwards with
        what they were: ``mutated`` lists the positions of those the call changed in place.
        ``record``: the pickle the arguments were read from (a batch sends one per call); a
        request sent as JSON has its arguments pickled here, before the call."""
        if check and record is None:
            record = _pickle(args, 5)
        global _CALL_MARK
        _CALL_MARK = _STDOUT.written + _STDERR.written
        try:
            try:
                result = self.function(*args)
            finally:
                _CALL_MARK = float("inf")
        except (SystemExit, KeyboardInterrupt):
            raise
        except BaseException as exc:
            _restore_builtins()
            reply = {"status": "raised", **self.describe(exc)}
        else:
            _restore_builtins()
            try:
                reply = {"status": "ok", "value": encode(result)}
            except (_Oversize, RecursionError, MemoryError):
                reply = {"status": "oversize", "size": None}
        if record is not None:
            changed = _changed(args, record)
            if changed:  # (only an argument changed can hold an object of the learner's, whose
                reply["mutated"] = changed  # code pickling it may have run)
                _restore_builtins()
        return reply

    def call_many(self, req: dict[str, Any]) -> None:
        """Answer every call of ``req["calls"]`` with a frame of its own (ids ``req["id"]``,
        ``req["id"] + 1``, ...), each sent as soon as its call returns. A call that alone
        printed more than the output budget (``out=``) floods: its frame carries ``stop:
        "flooded"`` and the batch ends there, so the flood is not repeated on every input; so
        does a call that left a process it started running (``stop: "processes"``,
        :func:`_left_running`). The calls are argument lists, or (a pickled batch) the pickle
        of each call's argument list."""
        check = req.get("check") is not False
        first = req.get("id")
        for index, call in enumerate(req["calls"]):
            before = _STDOUT.written + _STDERR.written
            if type(call) is bytes:
                reply = self.call(_unpickle(call), check, call)
            else:
                reply = self.call(call, check)
            reply["id"] = first + index if type(first) is int else None
            if _STDOUT.written + _STDERR.written - before > _BUDGET:
                reply["stop"] = "flooded"
            elif _left_running():
                reply["stop"] = "processes"
            stop = "stop" in reply
            self.send(reply, last=stop or index + 1 == _len(req["calls"]))
            if stop:
                return


def _left_running() -> bool:
    """Whether the call left a process it started still running: this worker has a child and
    none has exited (a child that exited is left as it is, for the learner's own wait). One
    system call; a child of a child is not seen (the worker's end kills it). Every later call
    would share the CPU with such processes (a fork bomb: 63 spinning children made each of
    the learner's exercises take seconds), so the batch stops there."""
    if _WAITID is None:
        return False
    try:
        return _WAITID(_P_ALL, 0, _WAIT_LOOK) is None
    except OSError:  # ChildProcessError: no child at all (the common case)
        return False


def _changed(args: list[Any], record: bytes) -> list[int]:
    """The positions of the arguments a call changed in place, by :func:`_unchanged`'s rule.
    ``record`` is the pickle they were read from (or made of them before the call): if they
    pickle to the same bytes again, they are unchanged (one C-speed pickling, no copy: the same
    structure pickles to the same bytes); otherwise they are compared one by one with the
    record read again (``-0.0`` for ``0.0`` is no change)."""
    try:
        if _pickle(args, 5) == record:
            return []
    except BaseException:  # the call put in something that cannot be pickled
        pass
    before = _unpickle(record)
    return [i for i in range(_len(before)) if not _unchanged(before[i], args[i])]


def _unchanged(before: Any, after: Any) -> bool:
    """True if ``after`` (an argument after the call) still equals ``before`` (what it was, read
    from the record): same types, same shapes and dtypes, same values bit for bit (NaN equals
    NaN; -0.0 equals 0.0)."""
    try:
        t = type(before)
        if type(after) is not t:
            return False
        if t is list or t is tuple:
            return _len(before) == _len(after) and all(
                _unchanged(b, a) for b, a in zip(before, after, strict=False)
            )
        if t is dict:
            return list(before) == list(after) and all(
                _unchanged(before[k], after[k]) for k in before
            )
        if t is _NDARRAY:
            return bool(
                before.dtype == after.dtype
                and before.shape == after.shape
                and before.tobytes() == after.tobytes()
            )
        if t is float:
            return bool(before == after or (before != before and after != after))
        if t in (int, str, bool) or before is None:
            return bool(before == after)
        return before is after
    except BaseException:  # e.g. a list the learner made contain itself
        return False


def _arity_problem(function: Any, count: int) -> list[str] | None:
    """``None`` if ``function`` accepts ``count`` positional arguments, else its parameters."""
    if type(function) is not _FunctionType:
        return None  # classes, builtins, partials...: let the call itself decide
    code = function.__code__
    flags = code.co_flags
    n_pos = code.co_argcount
    names = list(code.co_varnames[: n_pos + code.co_kwonlyargcount])
    defaults = function.__defaults__ or ()
    kwdefaults = function.__kwdefaults__ or {}
    has_varargs = bool(flags & 0x04)
    if has_varargs:
        names.insert(n_pos, "*" + code.co_varnames[n_pos + code.co_kwonlyargcount])
    required_kw = [
        n for n in code.co_varnames[n_pos : n_pos + code.co_kwonlyargcount] if n not in kwdefaults
    ]
    minimum = n_pos - _len(defaults)
    fits = minimum <= count and (count <= n_pos or has_varargs) and not required_kw
    return None if fits else [_str(n) for n in names]


def _flush_learner_output() -> bool:
    """Flush the learner's streams (sys.stdout and sys.stderr, which the learner may have
    replaced, and the worker's own), each once; True when the learner had replaced one (its
    own object's code ran)."""
    out: Any = getattr(sys, "stdout", None)
    err: Any = getattr(sys, "stderr", None)
    ours = out is _STDOUT and err is _STDERR
    for stream in (_STDOUT, _STDERR) if ours else (out, err, _STDOUT, _STDERR):
        try:  # noqa: SIM105 (runs on every reply: a try costs less than suppress)
            stream.flush()
        except BaseException:
            pass
    return not ours


_BUDGET = int(_CFG.get("out") or 1 << 20)
_STDOUT = _MutedStream(sys.stdout, _BUDGET)
_STDERR = _MutedStream(sys.stderr, _BUDGET)
sys.stdout, sys.stderr = _STDOUT, _STDERR
setattr(sys, "__stdout__", _STDOUT)  # noqa: B010 (the name is Final for type checkers)
setattr(sys, "__stderr__", _STDERR)  # noqa: B010


def serve(req_fd: int, resp_fd: int, bell_fd: int) -> int:
    """Send ``ready``, then answer requests until end of file on ``req_fd``."""
    session = Session(resp_fd, int(_CFG["frame"]), bell_fd)
    with contextlib.suppress(OSError):
        os.set_blocking(bell_fd, False)  # a full bell pipe must never stop a reply
    numpy_version = _np.__version__ if _np is not None else None
    ready = {"status": "ready", "numpy": numpy_version, "cgroups": _JOINED, "refused": _REFUSED}
    session.send({"id": 0, **ready})
    requests = os.fdopen(req_fd, "rb", buffering=1 << 16)
    decoder = json.JSONDecoder(object_hook=decode_arg)
    loaded = False
    while True:
        line = requests.readline()
        if not line:
            return 0
        req = decoder.decode(line.decode())
        size = req.get("pickled")
        if type(size) is int:  # a batch: one pickle per call's argument list follows the line
            body = requests.read(size)
            if _len(body) != size:
                return 0  # the parent went away mid-request
            req["calls"] = _unpickle(body)
        op = req.get("op")
        if op == "load" and not loaded:
            loaded = True
            reply = session.load(req)
        elif op == "call" and session.function is not None:
            reply = session.call(req["args"], req.get("check") is not False)
        elif op == "calls" and session.function is not None:
            session.call_many(req)
            continue
        else:
            reply = {"status": "bad_request"}
        reply["id"] = req.get("id")
        session.send(reply)


def _allow_imports() -> None:
    """Learners get the same imports at every isolation level: the standard library, numpy
    (already imported) and scipy, nothing else from site-packages. (Under namespaces nothing
    else exists there; without them, this is what keeps the rest out of reach.)"""
    stdlib = tuple(os.path.abspath(p) for p in {sys.base_prefix, sys.base_exec_prefix})
    sys.path[:] = [
        p
        for p in sys.path
        if "-packages" not in p and os.path.abspath(p).startswith(stdlib)  # not a .pth's paths
    ]
    if _np is None:
        return
    site = os.path.dirname(os.path.dirname(os.path.abspath(_np.__file__)))
    import importlib.machinery

    finder = importlib.machinery.PathFinder

    class _Allowed:
        """Finds the allowed top-level packages in numpy's site directory only."""

        @staticmethod
        def find_spec(name: str, path: Any = None, target: Any = None) -> Any:
            if path is None and name in ALLOWED_PACKAGES:
                return finder.find_spec(name, [site])
            return None

    sys.meta_path.append(_Allowed)


ALLOWED_PACKAGES = frozenset({"numpy", "scipy"})


def main() -> int:
    _allow_imports()
    if _ZYGOTE:
        return _zygote(int(_CFG["zygote"]))
    return serve(int(_CFG["req"]), int(_CFG["resp"]), int(_CFG["bell"]))


# -- zygote -------------------------------------------------------------------------------------
#
# ``python worker.py zygote=FD``: numpy is imported once, then every ``fork`` request on the
# control socket FD (a SOCK_SEQPACKET Unix socket; one JSON message per request, descriptors
# passed with SCM_RIGHTS) forks a fresh worker that contains itself exactly as a started one
# does (cgroups joined through the descriptors sent along, every resource limit set) and then
# serves its own pipes, which are sent back. The zygote runs no learner code itself.
#
# Under namespaces the zygote is the sandbox's init (pid 1, ``bwrap --as-pid-1``): it reaps
# orphans, no signal from inside the sandbox can kill or stop it, and no other process outside
# the learner's reach lives there (bubblewrap's own init, which a learner's code could
# ptrace, is not started).
#
# ``reset`` (asked only under namespaces, between two learners' submissions): kill and reap
# every worker, then prove that nothing of the last learner is left that could reach the next
# one: no process in the sandbox's pid namespace but the zygote;
# ``/tmp``, the one writable file system, emptied; no System V IPC object; and none of the
# zygote's own attributes that another process of the sandbox (same user) may change, and
# that its workers would inherit, changed since it started (resource limits, nice value, CPU
# affinity, scheduling policy, cgroups, ``/tmp``'s owner and mode). Its memory cannot have
# been touched: it is not dumpable, so no process of the sandbox may ptrace it or open its
# ``/proc/PID/mem``. Replies ``clean``, or ``dirty`` with the reason (the grader then closes
# it and starts another).


def _prctl(libc: Any, option: int, value: int) -> None:
    with contextlib.suppress(Exception):
        libc.prctl(option, value, 0, 0, 0)


PR_SET_PDEATHSIG = 1
PR_SET_DUMPABLE = 4


def _own_state(binds: set[str]) -> list[tuple[str, Any]]:
    """The zygote's attributes that a process of the sandbox could change from outside (see
    ``reset`` above) and its workers would inherit, each with its name; ``binds``: the paths
    below /tmp that are the sandbox's own (:func:`_sandbox_paths`)."""
    state: list[tuple[str, Any]] = []
    limits: dict[int, str] = {}  # (RLIMIT_OFILE is RLIMIT_NOFILE)
    for name in sorted(n for n in dir(resource) if n.startswith("RLIMIT_")):
        limits.setdefault(getattr(resource, name), name)
    for which, name in limits.items():
        try:
            state.append((name, resource.getrlimit(which)))
        except (ValueError, OSError):
            state.append((name, None))
    probes = (
        ("nice value", lambda: os.getpriority(os.PRIO_PROCESS, 0)),
        ("CPU affinity", lambda: sorted(os.sched_getaffinity(0))),
        ("scheduling policy", lambda: os.sched_getscheduler(0)),
        ("scheduling priority", lambda: os.sched_getparam(0).sched_priority),
        ("/tmp's mode or owner", lambda: (lambda st: (st.st_mode, st.st_uid))(os.stat("/tmp"))),
        ("mode or owner of a directory of /tmp's binds", lambda: _modes(binds)),
    )
    for name, probe in probes:
        try:
            state.append((name, probe()))
        except (AttributeError, OSError) as exc:
            state.append((name, type(exc).__name__))
    try:
        with open("/proc/self/cgroup", encoding="utf-8", errors="replace") as cgroups:
            state.append(("cgroups", cgroups.read()))
    except OSError as exc:
        state.append(("cgroups", type(exc).__name__))
    return state


def _mounts_under(root: str) -> set[str]:
    """The mount points below ``root`` (the sandbox's binds of files that live under the host's
    /tmp, e.g. a virtual environment there), from /proc/self/mountinfo."""
    found = set()
    with contextlib.suppress(OSError), open("/proc/self/mountinfo", encoding="utf-8") as info:
        for line in info:
            fields = line.split(" ")
            if len(fields) > 4 and fields[4].startswith(root.rstrip("/") + "/"):
                point = fields[4]
                for code, char in (("\\040", " "), ("\\011", "\t"), ("\\012", "\n")):
                    point = point.replace(code, char)
                found.add(point.replace("\\134", "\\"))
    return found


def _sandbox_paths(root: str) -> tuple[set[str], set[str]]:
    """What below ``root`` is the sandbox's own and must stay: its mount points, and those and
    the directories that lead to them."""
    mounts = _mounts_under(root)
    keep = set(mounts)
    for point in mounts:
        parent = os.path.dirname(point)
        while parent.startswith(root.rstrip("/") + "/"):
            keep.add(parent)
            parent = os.path.dirname(parent)
    return mounts, keep


def _modes(paths: set[str]) -> list[tuple[str, int, int]]:
    out = []
    for path in sorted(paths):
        try:
            st = os.lstat(path)
            out.append((path, st.st_mode, st.st_uid))
        except OSError:
            out.append((path, -1, -1))  # (moved or removed: changed)
    return out


def _wipe(path: str, mounts: set[str], keep: set[str]) -> None:
    """Remove everything under ``path`` but ``keep`` (never following a symbolic link, never
    entering a mount point); raises OSError or RecursionError when something cannot go."""
    with os.scandir(path) as entries:
        found = list(entries)
    for entry in found:
        if entry.path in keep:
            if entry.path not in mounts and entry.is_dir(follow_symlinks=False):
                _wipe(entry.path, mounts, keep)  # (a directory on the way to a mount point)
            continue
        if entry.is_dir(follow_symlinks=False):
            with contextlib.suppress(OSError):
                os.chmod(entry.path, 0o700)  # (a directory its creator made unreadable)
            _wipe(entry.path, mounts, keep)
            os.rmdir(entry.path)
        else:
            os.unlink(entry.path)


def _leftovers(
    started: list[tuple[str, Any]], reap: Any, mounts: set[str], keep: set[str]
) -> str | None:
    """Why the sandbox is not as the zygote found it (None: it is); see ``reset`` above.
    Called once every worker has been reaped; ``reap`` reaps orphans; ``mounts`` and ``keep``
    as :func:`_sandbox_paths` found them at the zygote's start (no process of the sandbox may
    mount or unmount anything)."""
    if os.getpid() != 1:
        return "the zygote is not the sandbox's init (another process could outlive a learner)"
    pause = 0.001
    deadline = time.monotonic() + 2.0
    while True:  # a killed process may still be exiting (the zygote, as init, reaps orphans)
        reap()
        try:
            others = sorted(int(p) for p in os.listdir("/proc") if p.isdigit())
        except OSError as exc:
            return f"cannot list processes ({exc})"
        others = [p for p in others if p != 1]
        if not others:
            break
        if time.monotonic() > deadline:
            return f"{len(others)} process(es) of the last learner still running"
        time.sleep(pause)
        pause = min(2 * pause, 0.05)
    try:
        _wipe("/tmp", mounts, keep)
        with os.scandir("/tmp") as entries:
            if {e.path for e in entries} - keep:
                return "/tmp could not be emptied"
    except (OSError, RecursionError) as exc:
        return f"/tmp could not be emptied ({type(exc).__name__})"
    for kind in ("shm", "sem", "msg"):
        try:
            with open(f"/proc/sysvipc/{kind}", encoding="utf-8", errors="replace") as table:
                if len(table.read().strip().splitlines()) > 1:
                    return f"a System V IPC object ({kind}) was left"
        except OSError:
            pass
    now = _own_state(keep)
    changed = [name for (name, was), (_, is_) in zip(started, now, strict=True) if was != is_]
    if changed:
        return "the zygote's " + ", ".join(changed) + " changed"
    return None


def _zygote(control_fd: int) -> int:
    import ctypes
    import signal
    import socket

    try:
        libc: Any = ctypes.CDLL(None, use_errno=True)
    except OSError:
        libc = None
    _prctl(libc, PR_SET_DUMPABLE, 0)  # no process of the sandbox may ptrace or read it
    sock = socket.socket(fileno=control_fd)
    children: dict[int, int | None] = {}  # pid -> exit code once reaped

    def reap() -> None:  # its own workers, and (as the sandbox's init) any orphan
        while True:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                return
            if pid == 0:
                return
            if pid in children:
                children[pid] = os.waitstatus_to_exitcode(status)

    def kill(pid: int) -> None:  # a worker and its process group
        for signal_to in (os.killpg, os.kill):
            with contextlib.suppress(OSError):
                signal_to(pid, signal.SIGKILL)

    def answer(reply: dict[str, Any], fds: list[int] | None = None) -> None:
        data = json.dumps(reply).encode()
        if fds:
            socket.send_fds(sock, [data], fds)
        else:
            sock.send(data)

    version = _np.__version__ if _np is not None else None
    mounts, binds = _sandbox_paths("/tmp")
    started = _own_state(binds)
    answer({"status": "ready", "numpy": version, "pid": os.getpid()})
    preload = [name for name in _CFG.get("preload", "").split(",") if name]
    if preload and _CFG.get("preload_first") == "1":  # started ahead: nobody waits for a fork
        _preload(preload)
        preload = []
    while True:
        try:
            data, fds, _flags, _addr = socket.recv_fds(sock, 1 << 16, 16)
        except OSError:
            data, fds = b"", []
        if not data:
            break
        req = json.loads(data)
        reap()
        op = req.get("op")
        if op == "fork":
            pid, theirs = _fork_worker(req, fds, control_fd, libc)
            children[pid] = None
            answer({"status": "forked", "pid": pid}, theirs)
            for fd in theirs:
                os.close(fd)
            if preload:  # after the first fork (its worker starts meanwhile), before the next
                _preload(preload)
                preload = []
        elif op == "kill":
            pid = req.get("pid")
            if type(pid) is int and pid in children and children[pid] is None:
                kill(pid)
            if req.get("answer") is not False:
                answer({"status": "killed"})
        elif op == "wait":
            pid = req.get("pid")
            deadline = time.monotonic() + float(req.get("timeout", 0))
            pause = 0.0002
            while pid in children and children[pid] is None and time.monotonic() < deadline:
                time.sleep(pause)
                pause = min(pause * 2, 0.01)
                reap()
            answer({"status": "waited", "code": children.get(pid)})
        elif op == "reset":
            for pid, code in children.items():
                if code is None:
                    kill(pid)
                    with contextlib.suppress(ChildProcessError):
                        os.waitpid(pid, 0)  # (SIGKILLed: it exits)
            children.clear()
            why = _leftovers(started, reap, mounts, binds)
            answer({"status": "clean"} if why is None else {"status": "dirty", "why": why})
        else:
            answer({"status": "bad_request"})
    for pid, code in children.items():
        if code is None:
            kill(pid)
    return 0


_PRELOADED = 0
"""Bytes of address space the zygote's preload added: a worker forked after it gets that much
more ``RLIMIT_AS``, so a learner keeps the headroom of a worker with numpy alone."""


def _address_space() -> int:
    """This process's virtual memory size in bytes (0 where /proc cannot tell)."""
    try:
        with open("/proc/self/status", encoding="ascii", errors="replace") as status:
            for line in status:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return 0


def _preload(names: list[str]) -> None:
    """Import modules learners' code often imports (scipy), so that every worker forked from
    now on finds them imported; one that fails to import is left to the learner's own import.
    Sets :data:`_PRELOADED` to the address space they took."""
    import importlib

    global _PRELOADED
    before = _address_space()
    for name in names:
        with contextlib.suppress(Exception):
            importlib.import_module(name)
    _PRELOADED = max(0, _address_space() - before)


def _fork_worker(
    req: dict[str, Any], cg_fds: list[int], control_fd: int, libc: Any
) -> tuple[int, list[int]]:
    """Fork one worker; returns its pid and the parent's ends of its five pipes."""
    req_r, req_w = os.pipe()
    resp_r, resp_w = os.pipe()
    bell_r, bell_w = os.pipe()
    out_r, out_w = os.pipe()
    err_r, err_w = os.pipe()
    pid = os.fork()
    if pid == 0:  # the worker: never returns to the zygote's loop
        code = 1
        try:
            os.setsid()
            _prctl(libc, PR_SET_PDEATHSIG, 9)  # dies with the zygote
            os.dup2(out_w, 1)
            os.dup2(err_w, 2)
            keep = {0, 1, 2, req_r, resp_w, bell_w, *cg_fds}
            try:  # every other descriptor of the zygote goes (the control socket first)
                open_fds = {int(fd) for fd in os.listdir("/proc/self/fd")}
            except OSError:
                open_fds = set(range(3, 1024))
            for fd in sorted(open_fds | {control_fd, req_w, resp_r, out_r, err_r, bell_r}):
                if fd not in keep:
                    with contextlib.suppress(OSError):
                        os.close(fd)
            cfg = req.get("cfg", {})
            _CFG.update({k: str(v) for k, v in cfg.items()})
            _CFG["cg"] = ",".join(str(fd) for fd in cg_fds)
            _CFG.update({"req": str(req_r), "resp": str(resp_w), "bell": str(bell_w)})
            _CFG.pop("zygote", None)
            _CFG.pop("preload", None)
            _CFG.pop("preload_first", None)
            if _PRELOADED and "as" in _CFG:  # the preloaded modules are not the learner's
                _CFG["as"] = str(int(_CFG["as"]) + _PRELOADED)
            sys.argv[1:] = [f"{k}={v}" for k, v in _CFG.items()]  # as a started worker's
            global _JOINED, _REFUSED
            _JOINED, _REFUSED = _contain(_CFG)
            global _BUDGET
            _BUDGET = int(_CFG.get("out") or 1 << 20)
            for stream in (_STDOUT, _STDERR):
                stream._left = _BUDGET
                stream.dropped = stream.written = 0
            code = serve(req_r, resp_w, bell_w)
        except SystemExit as exc:
            code = exc.code if type(exc.code) is int else 1
        except BaseException:
            code = 1
        finally:
            with contextlib.suppress(BaseException):
                _flush_learner_output()
            os._exit(code)
    for fd in (req_r, resp_w, out_w, err_w, bell_w, *cg_fds):
        os.close(fd)
    return pid, [req_w, resp_r, out_r, err_r, bell_r]


if __name__ == "__main__":
    sys.exit(main())
