"""The browser face under load: 30 simulated learners, as ratios to an idle number check.

The real server, ``slamcourse serve --no-browser --port 0`` in its own process (waitress, the
app, the code-check limiter, a warm sandbox worker), on the bundled course with a private
progress folder and workspace. A server serves one learner's home (one token, one progress
database), so the learners are simulated as concurrent clients of that one server: each is a
thread of this process with its own keep-alive connection and its own cookie (it opens the
tokened address once, as a browser tab does), and its own three number exercises.

1. Idle: the median of sequential number checks, nothing else running (the baseline).
2. Load: every learner answers its number exercises in turn (every third answer wrong), with a
   think time drawn around ``--think`` seconds, and one action in ``--code-every`` (at random)
   is a code check (the reference solution; one in three a wrong solution). Reported: number-check
   p50/p99 (absolute and as ratios to the idle median), number and code checks per second,
   code-check p50, 503s from the code-check limiter.
3. Saturation (``--think 0`` for the second phase): the same learners with no think time and no
   code checks: number checks per second the server sustains.

Then the progress database is read back: every attempt sent is recorded exactly once (each
answer text is unique: ``value + 0*TAG``), on its exercise, the learner's variant, with the
verdict the answer deserves (computed in-process by the exercise's kind before the run); no
attempt appears that was not sent; each exercise's state (attempts, solved) agrees with its
log; and the summary the server returns (kept, not recomputed) equals the full recomputation
by an engine of this process on the same database.

    python benchmarks/load.py [--learners 30] [--duration 20] [--think 0.5] [--idle 50]
"""

from __future__ import annotations

import argparse
import hashlib
import http.client
import json
import os
import random
import signal
import statistics
import subprocess
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

from _common import BIN, REPO, environment

CODE = "observation/observation-model"
WRONG_CODE = (
    "import math\n\n\ndef observation_model(xr, yr, thr, xj, yj):\n"
    "    return math.hypot(xj - xr, yj - yr), math.atan2(yj - yr, xj - xr)\n"
)


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


@dataclass
class Sent:
    """One request a learner sent, and what it got back."""

    exercise: str
    answer: str  # number: the text; code: the source
    expected: str  # the verdict status the answer deserves
    code: bool
    http: int = 0
    got: str | None = None
    seconds: float = 0.0
    at: float = 0.0  # time.perf_counter() when sent


@dataclass
class Learner:
    index: int
    exercises: list[str]
    sent: list[Sent] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)


class Client:
    """One keep-alive connection with its own cookie (a browser tab)."""

    def __init__(self, port: int, token: str) -> None:
        self.port = port
        self.conn = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
        self.conn.request("GET", f"/?token={token}")
        resp = self.conn.getresponse()
        resp.read()
        self.headers = {
            "Cookie": resp.getheader("Set-Cookie", "").split(";")[0],
            "Content-Type": "application/json",
            "Origin": f"http://127.0.0.1:{port}",
            "Host": f"127.0.0.1:{port}",
        }

    def post(self, path: str, body: dict[str, Any]) -> tuple[int, dict[str, Any]]:
        self.conn.request("POST", path, body=json.dumps(body).encode(), headers=self.headers)
        resp = self.conn.getresponse()
        data = resp.read()
        try:
            parsed = json.loads(data)
        except ValueError:
            parsed = {}
        return resp.status, parsed if isinstance(parsed, dict) else {}

    def close(self) -> None:
        self.conn.close()


def number_answers(engine: Any) -> dict[str, tuple[float, list[tuple[float, str]]]]:
    """For each number exercise with an inexact answer: the learner's expected value, and for
    a right and a wrong offset the status the kind gives (checked in-process, before the run)."""
    from slamcourse.kinds import get_kind

    out: dict[str, tuple[float, list[tuple[float, str]]]] = {}
    for ex in engine.course.exercise_ids:
        spec = engine.exercise(ex)
        if spec.kind != "number" or spec.options.exact:
            continue
        kind = get_kind("number")
        variant = engine.variant(ex)
        want = float(kind.expected(spec, variant))
        cases: list[tuple[float, str]] = []
        for offset in (0.0, 1000 + 1000 * abs(want)):
            status: str = kind.check(spec, variant, answer_text(want, offset, 0)).status
            cases.append((offset, status))
        if [s for _, s in cases] == ["passed", "failed"]:
            out[ex] = (want, cases)
    return out


def answer_text(value: float, offset: float, tag: int) -> str:
    """A number answer whose text is unique to ``tag`` and whose value ``tag`` leaves alone."""
    return f"({value!r}) + {offset!r} + 0*{tag}"


def unique_source(source: str, tag: int) -> str:
    return f"{source}\n# attempt {tag}\n"


def run_learners(
    port: int,
    token: str,
    learners: list[Learner],
    answers: dict[str, tuple[float, list[tuple[float, str]]]],
    sources: dict[str, str],
    *,
    duration: float,
    think: float,
    code_every: int,
    tags: list[int],
) -> float:
    """Every learner acts until ``duration`` has passed; returns the wall time taken."""
    lock = threading.Lock()
    start_line = threading.Barrier(len(learners) + 1)
    stop_at = [0.0]

    def next_tag() -> int:
        with lock:
            tags[0] += 1
            return tags[0]

    def act(learner: Learner) -> None:
        rng = random.Random(learner.index)
        try:
            client = Client(port, token)
        except OSError as exc:
            learner.errors.append(f"connect: {exc}")
            start_line.wait()
            return
        start_line.wait()
        if think:  # learners do not answer in step: each starts somewhere in its first pause
            time.sleep(rng.uniform(0.0, 1.5 * think))
        step = 0
        try:
            while time.perf_counter() < stop_at[0]:
                step += 1
                tag = next_tag()
                if code_every and rng.random() < 1 / code_every:  # at random: not in step
                    right = rng.random() >= 1 / 3
                    src = unique_source(sources["right" if right else "wrong"], tag)
                    sent = Sent(CODE, src, "passed" if right else "failed", code=True)
                    path, body = f"/api/code/{CODE}", {"source": src}
                else:
                    ex = learner.exercises[step % len(learner.exercises)]
                    want, cases = answers[ex]
                    offset, status = cases[1] if step % 3 == 0 else cases[0]
                    text = answer_text(want, offset, tag)
                    sent = Sent(ex, text, status, code=False)
                    path, body = f"/api/answer/{ex}", {"answer": text}
                t0 = time.perf_counter()
                try:
                    sent.http, data = client.post(path, body)
                except (OSError, http.client.HTTPException) as exc:
                    learner.errors.append(f"{path}: {exc!r}")
                    client.close()
                    client = Client(port, token)
                    data = {}
                sent.seconds, sent.at = time.perf_counter() - t0, t0
                sent.got = data.get("status")
                learner.sent.append(sent)
                if think:
                    time.sleep(rng.uniform(0.5 * think, 1.5 * think))
        finally:
            client.close()

    threads = [threading.Thread(target=act, args=(ln,), daemon=True) for ln in learners]
    for t in threads:
        t.start()
    stop_at[0] = time.perf_counter() + duration + 1e9  # nobody stops before the start line
    start_line.wait()
    t0 = time.perf_counter()
    stop_at[0] = t0 + duration
    for t in threads:
        t.join()
    return time.perf_counter() - t0


def verify(engine: Any, sent: list[Sent], code_file: Path, served: Any) -> list[str]:
    """Problems found reading the progress store back (empty: none lost or misattributed)."""
    from slamcourse.progress import Progress

    problems: list[str] = []
    with Progress.open(engine.progress.path) as store:  # a fresh connection: what is on disk
        log = store.attempts()
        states = store.states()
    by_answer: dict[tuple[str, str], list[Any]] = {}
    for a in log:
        by_answer.setdefault((a.exercise_id, a.answer), []).append(a)
    expected_keys = set()
    for s in sent:
        if s.http == 503:
            continue  # refused by the code-check limiter: never graded, so never recorded
        if s.http != 200:
            problems.append(f"{s.exercise}: HTTP {s.http}")
            continue
        if s.code:
            digest = hashlib.sha256(s.answer.encode()).hexdigest()[:16]
            key = (s.exercise, f"{code_file} sha256:{digest}")
        else:
            key = (s.exercise, s.answer)
        expected_keys.add(key)
        rows = by_answer.get(key, [])
        if len(rows) != 1:
            problems.append(f"{key}: recorded {len(rows)} times")
            continue
        row = rows[0]
        if row.status != s.expected or s.got != s.expected:
            problems.append(f"{key}: deserved {s.expected}, got {s.got}, recorded {row.status}")
        if not s.code and row.variant != engine.variant(s.exercise).seed:
            problems.append(f"{key}: recorded on variant {row.variant}")
    extra = [k for k in by_answer if k not in expected_keys]
    if extra:
        problems.append(f"{len(extra)} attempts recorded that were never sent, e.g. {extra[0]}")
    for ex in {a.exercise_id for a in log}:
        rows = [a for a in log if a.exercise_id == ex and a.reset_at is None]
        st = states.get(ex)
        counted = sum(a.counted for a in rows)
        solved = any(a.status == "passed" and a.counted for a in rows)
        if st is None or st.attempts != counted or st.solved != solved:
            problems.append(f"{ex}: state {st} but the log has {counted} counted, {solved=}")
    if served != engine.summary_full():  # this process's engine reads the database afresh
        problems.append("the server's summary differs from the full recomputation")
    for ch in served:
        for row in ch["exercises"]:
            st = states.get(row["id"])
            want = (st.status, st.attempts) if st else ("pending", 0)
            if (row["status"], row["attempts"]) != want:
                problems.append(
                    f"{row['id']}: the summary shows {row['status']}, {row['attempts']}"
                )
    return problems


def report_phase(
    name: str,
    learners: list[Learner],
    wall: float,
    idle: float,
    *,
    load: tuple[float, ...],
    cpu: tuple[float, float],
) -> None:
    sent = [s for ln in learners for s in ln.sent]
    numbers = [s.seconds for s in sent if not s.code and s.http == 200]
    codes = [s.seconds for s in sent if s.code and s.http == 200]
    busy = sum(s.code and s.http == 503 for s in sent)
    errors = [e for ln in learners for e in ln.errors]
    print(f"{name} ({len(learners)} learners, {wall:.1f} s, load average {load[0]:.2f})")
    if numbers:
        p50, p99 = statistics.median(numbers), percentile(numbers, 0.99)
        print(
            f"  number check  p50 {p50 * 1000:7.1f} ms  ({p50 / idle:5.1f}× idle)   "
            f"p99 {p99 * 1000:7.1f} ms  ({p99 / idle:5.1f}× idle)   "
            f"max {max(numbers) * 1000:7.1f} ms   {len(numbers) / wall:6.1f} checks/s"
        )
    if codes or busy:
        p50c = statistics.median(codes) if codes else float("nan")
        print(
            f"  code check    p50 {p50c * 1000:7.1f} ms  ({p50c / idle:5.1f}× idle)   "
            f"{len(codes) / wall:5.2f} checks/s   {busy} refused (503)"
        )
    print(
        f"  CPU seconds per second: the server process {cpu[0] / wall:4.2f}, the whole "
        f"machine {cpu[1] / wall:4.2f} of {os.cpu_count()} (sandbox workers, CI, these clients)"
    )
    if errors:
        print(f"  {len(errors)} client errors, e.g. {errors[0]}")


def start_server(env: dict[str, str]) -> tuple[subprocess.Popen[str], int, str]:
    """``slamcourse serve --no-browser --port 0`` in its own process; its port and token."""
    proc = subprocess.Popen(
        [str(BIN / "slamcourse"), "serve", "--no-browser", "--port", "0"],
        env={**env, "PYTHONUNBUFFERED": "1"},
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,  # the access log
        text=True,
    )
    assert proc.stdout is not None
    for line in proc.stdout:
        if "?token=" in line:
            url = urlsplit(line.strip())
            token = url.query.removeprefix("token=")
            assert url.port is not None
            return proc, url.port, token
    raise SystemExit(f"slamcourse serve stopped ({proc.wait()}) before printing its address")


def cpu_seconds(pid: int) -> tuple[float, float]:
    """CPU seconds (user + system) used so far by process ``pid``, and by the whole machine
    (every core, from /proc/stat); (nan, nan) where there is no /proc."""
    tick = os.sysconf("SC_CLK_TCK")
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()
        machine = Path("/proc/stat").read_text().splitlines()[0].split()[1:]
    except OSError:
        return float("nan"), float("nan")
    busy = sum(int(v) for k, v in enumerate(machine) if k not in (3, 4))  # not idle, iowait
    return (int(fields[11]) + int(fields[12])) / tick, busy / tick


def _spent(before: tuple[float, float], after: tuple[float, float]) -> tuple[float, float]:
    return after[0] - before[0], after[1] - before[1]


def get_json(port: int, token: str, path: str) -> Any:
    client = Client(port, token)
    try:
        client.conn.request("GET", path, headers=client.headers)
        resp = client.conn.getresponse()
        return json.loads(resp.read())
    finally:
        client.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--learners", type=int, default=30)
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--think", type=float, default=0.5, help="mean seconds between actions")
    parser.add_argument("--code-every", type=int, default=10, help="0: no code checks")
    parser.add_argument("--idle", type=int, default=50)
    parser.add_argument("--saturation", type=float, default=8.0, help="seconds (0: skip)")
    args = parser.parse_args()

    from slamcourse.engine import Engine
    from slamcourse.settings import Settings

    tmp = Path(tempfile.mkdtemp(prefix="slambench-load-"))
    home, workspace = tmp / "home", tmp / "ws"
    env = environment()
    env.update(
        SLAMCOURSE_HOME=str(home), SLAMCOURSE_WORKSPACE=str(workspace), SLAMCOURSE_COURSE=str(REPO)
    )
    solution = (REPO / "exercises/observation/solutions/observation_model.py").read_text()
    sources = {"right": solution, "wrong": WRONG_CODE}
    proc, port, token = start_server(env)
    try:
        # this process's own engine on the same home: the learner's variants, and (afterwards)
        # what the database holds; it never answers anything itself
        settings = Settings.from_env(course=REPO, home=home, workspace=workspace)
        with Engine.open(settings) as engine:
            answers = number_answers(engine)
            ids = sorted(answers)
            code_file = engine.code_file(CODE)
            get_json(port, token, "/api/summary")  # the first page: every exercise parsed once
            tags = [0]

            # 1. idle: sequential number checks, nothing else running
            client = Client(port, token)
            idle: list[float] = []
            idle_sent: list[Sent] = []
            for i in range(args.idle + len(ids)):
                ex = ids[i % len(ids)]
                want, cases = answers[ex]
                tags[0] += 1
                text = answer_text(want, cases[i % 2][0], tags[0])
                t0 = time.perf_counter()
                status, data = client.post(f"/api/answer/{ex}", {"answer": text})
                if i >= len(ids):  # the first round imports every exercise's reference
                    idle.append(time.perf_counter() - t0)
                idle_sent.append(
                    Sent(ex, text, cases[i % 2][1], code=False, http=status, got=data.get("status"))
                )
            client.close()
            idle_p50 = statistics.median(idle)
            print(
                f"`slamcourse serve` in its own process; {args.learners} learners = "
                f"{args.learners} concurrent clients (own connection and cookie each) of it, "
                "threads of this process"
            )
            print(f"number exercises in the rotation: {len(ids)}; CPUs: {os.cpu_count()}")
            print(
                f"idle number check (median of {len(idle)} sequential)  {idle_p50 * 1000:.1f} ms"
                f"  (p99 {percentile(idle, 0.99) * 1000:.1f} ms)   "
                f"load average {os.getloadavg()[0]:.2f}"
            )

            def make_learners() -> list[Learner]:
                return [
                    Learner(i, [ids[(3 * i + k) % len(ids)] for k in range(3)])
                    for i in range(args.learners)
                ]

            # 2. load: learners with think time and a share of code checks
            loaded = make_learners()
            before = cpu_seconds(proc.pid)
            wall = run_learners(
                port,
                token,
                loaded,
                answers,
                sources,
                duration=args.duration,
                think=args.think,
                code_every=args.code_every,
                tags=tags,
            )
            what = f"1 action in {args.code_every} a code check" if args.code_every else "no code"
            report_phase(
                f"load: think time ~{args.think:g} s, {what}",
                loaded,
                wall,
                idle_p50,
                load=os.getloadavg(),
                cpu=_spent(before, cpu_seconds(proc.pid)),
            )

            # 3. saturation: no think time, number checks only
            saturated: list[Learner] = []
            if args.saturation > 0:
                saturated = make_learners()
                before = cpu_seconds(proc.pid)
                wall = run_learners(
                    port,
                    token,
                    saturated,
                    answers,
                    sources,
                    duration=args.saturation,
                    think=0.0,
                    code_every=0,
                    tags=tags,
                )
                report_phase(
                    "saturation: no think time, number checks only",
                    saturated,
                    wall,
                    idle_p50,
                    load=os.getloadavg(),
                    cpu=_spent(before, cpu_seconds(proc.pid)),
                )

            everything = idle_sent + [s for ln in loaded + saturated for s in ln.sent]
            served = get_json(port, token, "/api/summary")
            problems = verify(engine, everything, code_file, served)
    finally:
        proc.send_signal(signal.SIGINT)  # as Ctrl+C: the server stops cleanly
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
    graded = sum(s.http == 200 for s in everything)
    if problems:
        print(f"progress store: {len(problems)} PROBLEMS among {graded} attempts")
        for p in problems[:20]:
            print(f"  {p}")
        raise SystemExit(1)
    print(
        f"progress store: all {graded} attempts recorded exactly once, on their exercise and "
        "variant, with the verdict deserved; the server's summary equals a full recomputation"
    )


if __name__ == "__main__":
    main()
