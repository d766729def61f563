"""Round trips of the browser face (`slamcourse serve`), as ratios to same-run baselines.

An in-process server on the bundled course (a private progress folder and workspace, a warm
sandbox worker as `serve` keeps) is asked, interleaved:

- static: GET of a static file on the same server (the HTTP floor: the baseline of the others);
- number check: POST /api/answer/<number exercise> (parse, reference, compare, record, JSON);
- code check: POST /api/code/<code exercise> with the reference solution (sandboxed run);
- page: GET /chapter/<the chapter with the most prose> (every exercise posed, Markdown
  rendered, pictures drawn).

A second baseline is `python -c "import numpy"` (whole process, median), for scale.

    python benchmarks/web.py [--repeats 25] [--code-repeats 9]
"""

from __future__ import annotations

import argparse
import http.client
import json
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from _common import REPO, environment, run_once

NUMBER = "drift/systematic-drift"
CODE = "observation/observation-model"


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=25)
    parser.add_argument("--code-repeats", type=int, default=9)
    args = parser.parse_args()

    from slamcourse.engine import Engine
    from slamcourse.settings import Settings
    from slamcourse.web.server import running

    tmp = Path(tempfile.mkdtemp(prefix="slambench-web-"))
    settings = Settings.from_env(course=REPO, home=tmp / "home", workspace=tmp / "ws")
    solution = (REPO / "exercises/observation/solutions/observation_model.py").read_text()
    import logging

    logging.getLogger("werkzeug").setLevel(logging.ERROR)
    with Engine.open(settings) as engine, running(engine) as srv:
        engine.start_workers()
        longest = max(  # the most prose; ties broken by the number of exercises
            engine.chapters(),
            key=lambda c: (
                sum(len(seg.markdown) for seg in engine.chapter_segments(c.id)),
                len(c.exercise_ids),
            ),
        )
        port = srv.server.server_port
        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
        conn.request("GET", f"/?token={srv.token}")
        resp = conn.getresponse()
        resp.read()
        cookie = resp.getheader("Set-Cookie", "").split(";")[0]
        headers = {
            "Cookie": cookie,
            "Content-Type": "application/json",
            "Origin": f"http://127.0.0.1:{port}",
            "Host": f"127.0.0.1:{port}",
        }

        def call(method: str, path: str, body: dict[str, str] | None = None) -> Callable[[], int]:
            data = json.dumps(body).encode() if body is not None else None

            def go() -> int:
                conn.request(method, path, body=data, headers=headers)
                r = conn.getresponse()
                r.read()
                if r.status != 200:
                    raise SystemExit(f"{method} {path}: HTTP {r.status}")
                return r.status

            return go

        probes = {
            "static GET /static/course.css (baseline)": call("GET", "/static/course.css"),
            f"number check POST /api/answer/{NUMBER}": call(
                "POST", f"/api/answer/{NUMBER}", {"answer": "1.5"}
            ),
            f"page GET /chapter/{longest.id} ({len(longest.exercise_ids)} exercises)": call(
                "GET", f"/chapter/{longest.id}"
            ),
        }
        samples: dict[str, list[float]] = {name: [] for name in probes}
        for fn in probes.values():  # warm-up: imports, caches, the first worker
            fn()
        for _ in range(args.repeats):
            for name, fn in probes.items():
                start = time.perf_counter()
                fn()
                samples[name].append(time.perf_counter() - start)
        code_name = f"code check POST /api/code/{CODE}"
        code = call("POST", f"/api/code/{CODE}", {"source": solution})
        code()
        samples[code_name] = []
        for _ in range(args.code_repeats):
            time.sleep(0.3)  # the learner edits between checks; the pool refills its worker
            start = time.perf_counter()
            code()
            samples[code_name].append(time.perf_counter() - start)
        conn.close()

    env = environment()
    numpy_runs = [run_once([sys.executable, "-c", "import numpy"], env) for _ in range(7)]
    numpy_p50 = statistics.median(numpy_runs)
    base = statistics.median(samples["static GET /static/course.css (baseline)"])
    print("browser face round trips (in-process server, one keep-alive connection)")
    print(f"  {'':<58} {'p50':>9} {'p90':>9}  p50/static  p50/numpy")
    for name, values in samples.items():
        p50, p90 = statistics.median(values), percentile(values, 0.9)
        print(
            f"  {name:<58} {p50 * 1000:7.1f}ms {p90 * 1000:7.1f}ms "
            f"{p50 / base:10.1f}× {p50 / numpy_p50:9.2f}×"
        )
    label = 'python -c "import numpy" (whole process, baseline)'
    print(f"  {label:<58} {numpy_p50 * 1000:7.1f}ms")


if __name__ == "__main__":
    main()
