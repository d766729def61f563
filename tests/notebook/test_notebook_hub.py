"""`slamcourse serve` behind a real `jupyter server` with jupyter-server-proxy, as JupyterLab's
launcher starts it on a hub: a course page and an API check through the proxy (the server's
token added by the proxy), and the same port refused when reached directly."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from slamcourse.notebook.hub import setup_slamcourse
from slamcourse.web.app import PROXY_HEADER
from slamcourse.web.server import ENV_TOKEN
from tests.conftest import FIXTURE_COURSE

pytestmark = pytest.mark.slow

JUPYTER_TOKEN = "jupyter-test-token-42"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class _NoRedirect(urllib.request.HTTPRedirectHandler):
    def redirect_request(self, *args: object, **kwargs: object) -> None:
        return None  # a redirect (to a login page) is the answer


_OPENER = urllib.request.build_opener(_NoRedirect)


def fetch(
    url: str, *, data: bytes | None = None, headers: dict[str, str] | None = None
) -> tuple[int, bytes, dict[str, str]]:
    req = urllib.request.Request(url, data=data, headers=headers or {})
    try:
        with _OPENER.open(req, timeout=60) as resp:
            return resp.status, resp.read(), dict(resp.headers)
    except urllib.error.HTTPError as exc:
        with exc:
            return exc.code, exc.read(), dict(exc.headers)


def test_the_launcher_entry() -> None:
    first, second = setup_slamcourse(), setup_slamcourse()
    assert first["command"][-4:] == ["serve", "--no-browser", "--port", "{port}"]
    token = first["environment"][ENV_TOKEN]
    assert first["request_headers_override"] == {PROXY_HEADER: token}
    assert len(token) >= 32 and token != second["environment"][ENV_TOKEN]
    assert token not in " ".join(first["command"])  # never on a command line
    assert Path(first["launcher_entry"]["icon_path"]).is_file()
    from importlib.metadata import entry_points

    (entry,) = [
        e for e in entry_points(group="jupyter_serverproxy_servers") if e.name == "slamcourse"
    ]
    assert entry.load() is setup_slamcourse


@pytest.fixture
def jupyter(tmp_path: Path, private_home: Path) -> Iterator[str]:
    """A real `jupyter server` (jupyter-server-proxy loaded) on a free port; its base URL."""
    pytest.importorskip("jupyter_server_proxy")
    port = free_port()
    env = {
        **os.environ,
        "SLAMCOURSE_COURSE": str(FIXTURE_COURSE),
        "SLAMCOURSE_HOME": str(private_home),
        "JUPYTER_CONFIG_DIR": str(tmp_path / "config"),
        "JUPYTER_DATA_DIR": str(tmp_path / "data"),
        "JUPYTER_RUNTIME_DIR": str(tmp_path / "runtime"),
    }
    log = (tmp_path / "jupyter.log").open("wb")
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "jupyter_server",
            "--no-browser",
            "--allow-root",
            f"--port={port}",
            "--ip=127.0.0.1",
            f"--IdentityProvider.token={JUPYTER_TOKEN}",
            f"--ServerApp.root_dir={tmp_path}",
        ],
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            if proc.poll() is not None:
                pytest.fail(f"jupyter server exited: {(tmp_path / 'jupyter.log').read_text()}")
            try:
                status, _, _ = fetch(f"{base}/api/status", headers=_auth())
                if status == 200:
                    break
            except OSError:
                pass
            time.sleep(0.3)
        else:
            pytest.fail("jupyter server did not start within 60 s")
        yield base
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        log.close()


def _auth() -> dict[str, str]:
    return {"Authorization": f"token {JUPYTER_TOKEN}"}


def _serve_port() -> int | None:
    """The port of the `slamcourse serve` a proxy started (from its command line)."""
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            args = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        words = [a.decode(errors="replace") for a in args]
        if "slamcourse" in words and "serve" in words and "--port" in words:
            env = Path(f"/proc/{pid}/environ").read_bytes()
            if f"SLAMCOURSE_HOME={os.environ['SLAMCOURSE_HOME']}".encode() in env:
                return int(words[words.index("--port") + 1])
    return None


def test_a_course_page_and_a_check_through_jupyter_server_proxy(jupyter: str) -> None:
    status, body, _ = fetch(f"{jupyter}/slamcourse/chapter/basics", headers=_auth())
    assert status == 200, body[:500]
    html = body.decode()
    assert '<meta name="slamcourse-root" content="/slamcourse">' in html
    assert 'src="/slamcourse/static/course.js"' in html
    status, js, _ = fetch(f"{jupyter}/slamcourse/static/course.js", headers=_auth())
    assert status == 200 and b"slamcourse-root" in js
    # an API check, as the page's script sends it (same origin as the Jupyter server)
    post = {**_auth(), "Content-Type": "application/json", "Origin": jupyter}
    status, body, _ = fetch(
        f"{jupyter}/slamcourse/api/answer/basics/count", data=b'{"answer": "1"}', headers=post
    )
    assert status == 200, body[:500]
    result = json.loads(body)
    assert result["status"] == "failed" and result["attempts"] == 1
    # another site's page cannot post through the learner's proxy
    evil = {**post, "Origin": "https://evil.example"}
    status, _, _ = fetch(
        f"{jupyter}/slamcourse/api/answer/basics/count", data=b'{"answer": "1"}', headers=evil
    )
    assert status == 403
    # the hub's (here the Jupyter server's) own authentication stands in front
    status, _, _ = fetch(f"{jupyter}/slamcourse/chapter/basics")
    assert status in (302, 401, 403)
    # the port itself, reached directly, still needs the server's token
    port = _serve_port()
    assert port is not None, "no `slamcourse serve` process found"
    direct = f"http://127.0.0.1:{port}/chapter/basics"
    assert fetch(direct)[0] == 403
    assert fetch(direct, headers={PROXY_HEADER: "guess"})[0] == 403
    status, _, _ = fetch(
        f"http://127.0.0.1:{port}/api/answer/basics/count",
        data=b'{"answer": "1"}',
        headers={"Content-Type": "application/json"},
    )
    assert status == 403


@pytest.mark.browser
def test_the_page_works_in_a_browser_through_the_proxy(jupyter: str, browser: Any) -> None:
    """The page's own script (math, answers, the sidebar) under the proxy's prefix, in
    chromium: an answer checked through the proxy reaches the engine."""
    page = browser.new_page()
    try:
        page.set_default_timeout(30_000)
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        # Jupyter's own login (its token), then the proxied course page
        page.goto(f"{jupyter}/api/status?token={JUPYTER_TOKEN}")
        page.goto(f"{jupyter}/slamcourse/chapter/basics")
        page.wait_for_selector("html[data-ready='1']")
        assert page.locator(".katex").count() > 0  # static files under the prefix
        section = page.locator('[data-exercise="basics/count"]')
        section.locator("[data-input]").fill("1")
        section.locator("[data-check]").click()
        feedback = section.locator("[data-feedback]")
        feedback.filter(has_text="Not quite").wait_for()
        assert "1 attempt" in section.locator("[data-attempts]").inner_text()
        assert not errors, errors
    finally:
        page.close()
