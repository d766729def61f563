"""Fixtures for the sandbox tests: one worker per test, at both isolation levels.

Namespace tests are skipped only when bubblewrap truly cannot run here; with ``CI`` set they
fail instead, so a CI machine without namespaces is noticed.
"""

from __future__ import annotations

import os
import textwrap
from collections.abc import Callable, Iterator

import pytest

from slamcourse.sandbox import Limits, LoadResult, Worker, Zygote, probe_isolation

LEVELS = ["namespaces", "rlimits"]

MakeWorker = Callable[..., tuple[Worker, LoadResult]]


def require_level(level: str) -> None:
    """Skip (or fail under CI) when ``level`` is not available on this machine."""
    if level == "namespaces":
        report = probe_isolation("namespaces")
        if report.level != "namespaces":
            message = f"namespaces unavailable: {report.reason}"
            if os.environ.get("CI"):
                pytest.fail(message + " (CI is set: namespace tests must run)")
            pytest.skip(message)


def require_process_limit(process_limit: str) -> None:
    """Skip (or fail under CI) when this machine gives the sandbox no process limit."""
    if process_limit.startswith("none"):
        message = f"no process limit here: {process_limit}"
        if os.environ.get("CI"):
            pytest.fail(message + " (CI is set: the process-limit tests must run)")
        pytest.skip(message)


@pytest.fixture(params=LEVELS)
def level(request: pytest.FixtureRequest) -> str:
    value: str = request.param
    require_level(value)
    return value


@pytest.fixture
def ns_level() -> str:
    """Only the namespaces level (for defences the fallback does not claim)."""
    require_level("namespaces")
    return "namespaces"


@pytest.fixture(params=["spawned", "forked"])
def how(request: pytest.FixtureRequest) -> str:
    """How the worker starts: its own interpreter (``Worker.spawn``) or forked by a zygote
    (``Zygote.worker``, the batch grader's way); every defence must hold for both."""
    value: str = request.param
    return value


@pytest.fixture
def make_worker(level: str, how: str) -> Iterator[MakeWorker]:
    """``make_worker(source, function="f", params=None, limits=None, filename=None)`` →
    ``(worker, load_result)``; the source is dedented; every worker is closed after the test."""
    yield from _factory(level, how)


@pytest.fixture
def make_ns_worker(ns_level: str, how: str) -> Iterator[MakeWorker]:
    yield from _factory(ns_level, how)


def _factory(level: str, how: str = "spawned") -> Iterator[MakeWorker]:
    workers: list[Worker] = []
    zygotes: list[Zygote] = []

    def make(
        source: str,
        function: str = "f",
        params: list[str] | None = None,
        limits: Limits | None = None,
        filename: str | None = None,
    ) -> tuple[Worker, LoadResult]:
        if how == "forked":
            zygote = Zygote.spawn(force=level)
            zygotes.append(zygote)
            worker = zygote.worker(limits or Limits())
        else:
            worker = Worker.spawn(limits=limits or Limits(), force=level)
        workers.append(worker)
        name = filename or f"{function}.py"
        return worker, worker.load(textwrap.dedent(source), name, function, params)

    try:
        yield make
    finally:
        for worker in workers:
            worker.close()
        for zygote in zygotes:
            zygote.close()
