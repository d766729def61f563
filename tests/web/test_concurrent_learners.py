"""Thirty clients answering at once over real sockets (issue 15, item 7): every attempt is
recorded exactly once, on its own exercise and variant, with the verdict its answer deserves,
and the summary every answer returns stays equal to a full recomputation. Not timed (the load
figures are benchmarks/load.py's): correctness only.

One server serves one learner's home, so the thirty "learners" are thirty concurrent clients of
it, each with its own connection and cookie, as thirty browser tabs would be."""

from __future__ import annotations

import http.client
import json
import threading
from collections import Counter
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from slamcourse.engine import Engine
from slamcourse.kinds import get_kind
from slamcourse.progress import Progress
from tests.web.conftest import settings_for

CLIENTS = 30
ANSWERS_EACH = 6
EXERCISES = ["basics/distance", "basics/heading", "basics/offset"]


@pytest.fixture
def served(tmp_path: Path) -> Iterator[tuple[Engine, Any]]:
    from slamcourse.web.server import running

    with Engine.open(settings_for(tmp_path)) as eng, running(eng) as srv:
        yield eng, srv


def answer(engine: Engine, exercise_id: str, wrong: bool, tag: int) -> str:
    """A text unique to ``tag`` (``+ 0*tag`` leaves its value alone), right or wrong."""
    spec = engine.exercise(exercise_id)
    value = get_kind(spec.kind).expected(spec, engine.variant(exercise_id))
    shift = 1000.0 if wrong else 0.0
    if spec.kind == "vector":
        entries = [f"{v!r} + {shift!r} + 0*{tag}" for v in value]
        return "[" + ", ".join(entries) + "]"
    return f"{value!r} + {shift!r} + 0*{tag}"


def deserved(engine: Engine, exercise_id: str, text: str) -> str:
    spec = engine.exercise(exercise_id)
    return get_kind(spec.kind).check(spec, engine.variant(exercise_id), text).status


def test_thirty_concurrent_clients_lose_and_misattribute_no_attempt(
    served: tuple[Engine, Any],
) -> None:
    engine, srv = served
    assert engine.progress is not None
    port = srv.server.server_port
    plan: list[list[tuple[str, str, str]]] = []  # per client: (exercise, answer, verdict)
    for c in range(CLIENTS):
        mine = []
        for i in range(ANSWERS_EACH):
            ex = EXERCISES[(c + i) % len(EXERCISES)]
            text = answer(engine, ex, wrong=(c + i) % 3 == 0, tag=c * 100 + i)
            mine.append((ex, text, deserved(engine, ex, text)))
        plan.append(mine)
    assert {v for mine in plan for _, _, v in mine} == {"passed", "failed"}

    start = threading.Barrier(CLIENTS)
    got: list[list[tuple[int, dict[str, Any]]]] = [[] for _ in range(CLIENTS)]
    failures: list[BaseException] = []

    def learner(c: int) -> None:
        try:
            conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
            conn.request("GET", f"/?token={srv.token}")
            resp = conn.getresponse()
            resp.read()
            headers = {
                "Cookie": resp.getheader("Set-Cookie", "").split(";")[0],
                "Content-Type": "application/json",
                "Origin": f"http://127.0.0.1:{port}",
                "Host": f"127.0.0.1:{port}",
            }
            start.wait(timeout=60)
            for ex, text, _ in plan[c]:
                body = json.dumps({"answer": text}).encode()
                conn.request("POST", f"/api/answer/{ex}", body=body, headers=headers)
                r = conn.getresponse()
                got[c].append((r.status, json.loads(r.read())))
            conn.close()
        except BaseException as exc:  # reported by the main thread
            failures.append(exc)
            start.abort()

    threads = [threading.Thread(target=learner, args=(c,)) for c in range(CLIENTS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
    assert not failures, failures
    assert all(not t.is_alive() for t in threads)

    for c in range(CLIENTS):
        assert len(got[c]) == ANSWERS_EACH
        for (ex, text, verdict), (status, data) in zip(plan[c], got[c], strict=True):
            assert status == 200, data
            assert (data["exercise"], data["status"]) == (ex, verdict), text

    with Progress.open(engine.progress.path) as fresh:  # what is on disk
        log = fresh.attempts()
        states = fresh.states()
    sent = [(ex, text) for mine in plan for ex, text, _ in mine]
    recorded = Counter((a.exercise_id, a.answer) for a in log)
    assert len(log) == len(sent) == CLIENTS * ANSWERS_EACH
    assert all(recorded[key] == 1 for key in sent), "an attempt lost or recorded twice"
    verdict_of = {(ex, text): v for mine in plan for ex, text, v in mine}
    for a in log:
        assert a.status == verdict_of[(a.exercise_id, a.answer)], a
        assert a.variant == engine.variant(a.exercise_id).seed, a
        assert a.counted
    for ex in EXERCISES:
        mine = [a for a in log if a.exercise_id == ex]
        assert states[ex].attempts == len(mine)
        assert states[ex].solved == any(a.status == "passed" for a in mine)
    assert engine.progress.states() == states  # the server's in-memory copy, too
    assert engine.summary() == engine.summary_full()
    rows = {r["id"]: r for ch in engine.summary() for r in ch["exercises"]}
    assert all(rows[ex]["attempts"] == states[ex].attempts for ex in EXERCISES)
