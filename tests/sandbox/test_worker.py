"""The sandbox worker does its ordinary job at both isolation levels: load, call, report."""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
import pytest

from slamcourse.errors import GraderError, SandboxError
from slamcourse.sandbox import Limits, LoadResult, Unsupported, Worker, probe_isolation

MakeWorker = Callable[..., tuple[Worker, LoadResult]]  # the make_worker fixture (conftest.py)

OBSERVATION_MODEL = """
    import math

    def observation_model(xr, yr, thr, xj, yj):
        dx, dy = xj - xr, yj - yr
        return math.hypot(dx, dy), math.atan2(dy, dx) - thr
"""

BUILD_OMEGA = """
    import numpy as np

    def build_omega(n, edges):
        omega = np.zeros((n, n))
        for edge in edges:
            assert type(edge) is tuple, type(edge)
            i, j, w = edge
            omega[i, i] += w
            omega[j, j] += w
            omega[i, j] -= w
            omega[j, i] -= w
        return omega
"""


# -- normal calls ---------------------------------------------------------------------------


def test_floats_and_tuples(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        OBSERVATION_MODEL, "observation_model", ["xr", "yr", "thr", "xj", "yj"]
    )
    assert loaded.ok, loaded
    result = worker.call([0.0, 0.0, 0.0, 3.0, 4.0])
    assert result.status == "ok"
    rng, bearing = result.value
    assert rng == 5.0 and math.isclose(bearing, math.atan2(4, 3))
    assert worker.call([1.0, 1.0, math.pi / 2, 1.0, 2.0]).value == [1.0, 0.0]


def test_numpy_inside_and_arrays_returned(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(BUILD_OMEGA, "build_omega", ["n", "edges"])
    assert loaded.ok, loaded
    result = worker.call([3, [(0, 1, 1.0), (1, 2, 2.5)]])
    assert result.status == "ok", result
    expected = [[1.0, -1.0, 0.0], [-1.0, 3.5, -2.5], [0.0, -2.5, 2.5]]
    assert result.value == expected
    assert np.array_equal(np.asarray(result.value, dtype=np.float64), np.array(expected))


def test_large_float_arrays_cross_as_bytes_and_arrive_as_lists(make_worker: MakeWorker) -> None:
    """A float array of BINARY_FLOATS entries or more travels as its float64 bytes; the
    parent gets exactly what ``tolist()`` gives (special values and float32 included), and an
    int array stays ints."""
    worker, loaded = make_worker(
        """
        import numpy as np
        def f(kind):
            a = np.linspace(-3.0, 3.0, 60).reshape(20, 3)
            a[0] = [np.nan, -0.0, np.inf]
            return {
                "f64": a, "view": a[::2, 1:], "f32": a.astype(np.float32),
                "ints": np.arange(40).reshape(20, 2), "nested": (a[0], [a]),
            }[kind]
        """
    )
    assert loaded.ok
    a = np.linspace(-3.0, 3.0, 60).reshape(20, 3)
    a[0] = [np.nan, -0.0, np.inf]
    expected = {
        "f64": a.tolist(),
        "view": a[::2, 1:].tolist(),
        "f32": a.astype(np.float32).tolist(),
        "ints": np.arange(40).reshape(20, 2).tolist(),
        "nested": [a[0].tolist(), [a.tolist()]],
    }
    for kind, want in expected.items():
        result = worker.call([kind])
        assert result.status == "ok", (kind, result)
        assert repr(result.value) == repr(want), kind  # bit for bit: nan, -0.0, inf
    assert type(worker.call(["ints"]).value[0][0]) is int


def test_numpy_scalars_and_dtypes(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import numpy as np
        def f(kind):
            return {
                "f32": np.float32(1.5), "i64": np.int64(7), "u8": np.uint8(255),
                "bool": np.bool_(True), "iarr": np.arange(3), "barr": np.array([True, False]),
                "f16arr": np.ones(2, dtype=np.float16), "zero_d": np.array(2.5),
                "mixed": [np.float64(0.25), (1, np.array([[1, 2]]))],
            }[kind]
        """
    )
    assert loaded.ok
    cases = {
        "f32": 1.5,
        "i64": 7,
        "u8": 255,
        "bool": True,
        "iarr": [0, 1, 2],
        "barr": [True, False],
        "f16arr": [1.0, 1.0],
        "zero_d": 2.5,
        "mixed": [0.25, [1, [[1, 2]]]],
    }
    for kind, expected in cases.items():
        result = worker.call([kind])
        assert result.status == "ok" and result.value == expected, (kind, result)
        assert type(result.value) is type(expected)


def test_arguments_arrive_typed(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import numpy as np
        def f(a, t, d, arr, nested):
            return [type(a).__name__, type(t).__name__, type(d).__name__,
                    type(arr).__name__, str(arr.dtype), list(arr.shape),
                    type(nested[0]).__name__, sorted(d.items()), list(t)]
        """
    )
    assert loaded.ok
    result = worker.call([1.5, (1, 2), {"k": 3}, np.eye(2, dtype=np.float32), [(0, 1)]])
    assert result.value == [
        "float",
        "tuple",
        "dict",
        "ndarray",
        "float32",
        [2, 2],
        "tuple",
        [["k", 3]],
        [1, 2],
    ]


def test_bad_argument_is_a_grader_error(make_worker: MakeWorker) -> None:
    worker, _loaded = make_worker("def f(x):\n    return x\n")
    with pytest.raises(GraderError):
        worker.call([object()])
    assert worker.call([1]).value == 1


# -- loading problems -----------------------------------------------------------------------


def test_syntax_error_with_line(make_worker: MakeWorker) -> None:
    _worker, loaded = make_worker("import math\n\ndef f(x)\n    return x\n")
    assert loaded.status == "syntax_error"
    assert loaded.line == 3
    assert "expected ':'" in loaded.message


def test_null_byte_is_a_syntax_error(make_worker: MakeWorker) -> None:
    _worker, loaded = make_worker("def f():\n    return '\0'\n")
    assert loaded.status == "syntax_error"


def test_missing_function_lists_what_exists(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        "def observation(x):\n    return x\nhelper = 3\n", "observation_model"
    )
    assert loaded.status == "missing_function"
    assert loaded.found == ("observation",)
    with pytest.raises(GraderError):
        worker.call([1])


def test_not_callable(make_worker: MakeWorker) -> None:
    _worker, loaded = make_worker("f = 3\n")
    assert loaded.status == "not_callable"
    assert loaded.found == ("int",)


@pytest.mark.parametrize(
    ("signature", "ok"),
    [
        ("a, b", True),
        ("x, y", True),  # renamed parameters are fine
        ("a, b, c=1", True),
        ("*args", True),
        ("a, /, b", True),
        ("a", False),
        ("a, b, c", False),
        ("a, b, *, key", False),  # a required keyword-only parameter
    ],
)
def test_arity(make_worker: MakeWorker, signature: str, ok: bool) -> None:
    _worker, loaded = make_worker(f"def f({signature}):\n    return 0\n", params=["p", "q"])
    assert loaded.ok is ok, loaded
    if not ok:
        assert loaded.status == "signature"
        assert loaded.expected == ("p", "q")
        assert loaded.found


def test_import_error_with_learner_frames(make_worker: MakeWorker) -> None:
    _worker, loaded = make_worker(
        """
        def helper():
            return 1 / 0

        VALUE = helper()

        def f():
            return VALUE
        """
    )
    assert loaded.status == "import_error"
    assert loaded.message == "ZeroDivisionError: division by zero"
    assert [(fr.line, fr.function) for fr in loaded.frames] == [(5, "<module>"), (3, "helper")]
    assert loaded.frames[1].text == "return 1 / 0"


def test_import_of_unavailable_module(make_worker: MakeWorker) -> None:
    _worker, loaded = make_worker("import hypothesis\ndef f():\n    return 0\n")
    assert loaded.status == "import_error"
    assert loaded.message.startswith("ModuleNotFoundError")


# -- exceptions and output ------------------------------------------------------------------


def test_exception_has_only_learner_frames(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import numpy as np

        def invert(m):
            return np.linalg.inv(m)

        def f(m):
            return invert(np.array(m)).tolist()
        """,
        filename="mahalanobis.py",
    )
    assert loaded.ok
    result = worker.call([[[1.0, 2.0], [2.0, 4.0]]])
    assert result.status == "raised"
    assert result.error.startswith("LinAlgError: Singular matrix")
    assert [(fr.line, fr.function) for fr in result.frames] == [(8, "f"), (5, "invert")]
    assert result.frames[1].text == "return np.linalg.inv(m)"
    assert "numpy" not in repr(result.frames)
    # the worker is still usable after an exception
    assert worker.call([[[2.0, 0.0], [0.0, 4.0]]]).value == [[0.5, 0.0], [0.0, 0.25]]


def test_long_exception_text_is_truncated(make_worker: MakeWorker) -> None:
    worker, _ = make_worker("def f():\n    raise ValueError('x' * 100000)\n")
    result = worker.call([])
    assert result.status == "raised"
    assert len(result.error) <= 2001 and result.error.startswith("ValueError: xxx")


def test_stdout_captured_and_irrelevant(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import sys
        print("loading")
        def f(x):
            print("value is", x)
            print("\\x1b[31mred\\x1b[0m \\u202etxt", file=sys.stderr)
            return x * 2
        """
    )
    assert loaded.ok and loaded.stdout == "loading\n"
    result = worker.call([21])
    assert result.value == 42
    assert result.stdout == "value is 21\n"
    assert result.stderr == "[31mred[0m txt\n"  # escape and bidi characters removed
    assert worker.call([1]).stdout == "value is 1\n"  # per call, not cumulative


def test_unsupported_values_are_marked(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import numpy as np
        class MyFloat(float):
            pass
        def f(kind):
            return {
                "dict": {"a": 1}, "gen": (i for i in range(3)), "set": {1},
                "complex": 1j, "carr": np.ones(2, dtype=complex), "objarr": np.array([None]),
                "sub": MyFloat(1.0), "strarr": np.array(["a"]), "bytes": b"x",
                "in_list": [1.0, {"a": 1}],
            }[kind]
        """
    )
    assert loaded.ok
    names = {
        "dict": "dict",
        "gen": "generator",
        "set": "set",
        "complex": "complex",
        "carr": "ndarray[complex128]",
        "objarr": "ndarray[object]",
        "sub": "MyFloat",
        "strarr": "ndarray[str32]",
        "bytes": "bytes",
    }
    for kind, name in names.items():
        result = worker.call([kind])
        assert result.status == "ok" and result.value == Unsupported(name), (kind, result)
    assert worker.call(["in_list"]).value == [1.0, Unsupported("dict")]


def test_strings_and_none(make_worker: MakeWorker) -> None:
    worker, _ = make_worker("def f(x):\n    return [x, None, 'occupied']\n")
    assert worker.call(["é"]).value == ["é", None, "occupied"]


# -- lifecycle ------------------------------------------------------------------------------


def test_call_before_load_and_double_load(level: str) -> None:
    with Worker.spawn(force=level) as worker:
        with pytest.raises(GraderError):
            worker.call([])
        assert worker.load("def f():\n    return 1\n", "f.py", "f").ok
        with pytest.raises(GraderError):
            worker.load("def f():\n    return 1\n", "f.py", "f")
        assert worker.call([]).value == 1
    assert not worker.alive


def test_prestarted_worker(level: str) -> None:
    """A worker started early is ready (numpy imported) by the time the source arrives."""
    with Worker.spawn(force=level) as worker:
        time.sleep(0.5)
        started = time.monotonic()
        assert worker.load("def f():\n    return 1\n", "f.py", "f").ok
        assert time.monotonic() - started < 1.0
        assert worker.startup_seconds is not None and worker.startup_seconds < 5


def test_close_is_idempotent_and_kills(level: str) -> None:
    worker = Worker.spawn(force=level)
    assert worker.load("def f():\n    return 1\n", "f.py", "f").ok
    proc = worker._res.proc
    worker.close()
    worker.close()
    assert proc is not None and proc.returncode is not None
    assert worker.call([]).status == "crashed"


def test_isolation_report(level: str) -> None:
    report = probe_isolation(level)
    assert report.level == level
    assert report.reason
    assert probe_isolation(level) is report  # cached
    with Worker.spawn(force=level) as worker:
        assert worker.isolation is report


def test_require_isolation_refuses_fallback() -> None:
    with pytest.raises(SandboxError, match="without namespace isolation"):
        Worker.spawn(force="rlimits", require_isolation=True)


def test_unknown_mode_is_an_error() -> None:
    with pytest.raises(SandboxError, match="unknown sandbox mode"):
        probe_isolation("docker")


def test_limits_validation() -> None:
    with pytest.raises(ValueError):
        Limits(call_seconds=0)
    assert Limits().memory_bytes == 1 << 30
