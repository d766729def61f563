"""The whole hub: a real JupyterHub (configurable-http-proxy from npm in front, a local process
spawner) spawns a learner's Jupyter server; the course page and an API check are fetched
through the hub's proxy and the learner's jupyter-server-proxy, with the hub's token.

Needs `jupyterhub` (PyPI, in the test extra) and `configurable-http-proxy` (npm; scripts/
setup.sh installs it into .venv/chp). Skipped where either is missing, failed under CI."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.conftest import FIXTURE_COURSE, REPO
from tests.notebook.test_notebook_hub import fetch, free_port

pytestmark = pytest.mark.slow

API_TOKEN = "hub-test-service-token-0123456789abcdef"
USER = "ada"


def _chp() -> str | None:
    local = REPO / ".venv" / "chp" / "node_modules" / ".bin" / "configurable-http-proxy"
    return str(local) if local.exists() else shutil.which("configurable-http-proxy")


def _need(what: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(f"{what} is missing: scripts/setup.sh installs it for the tests")
    pytest.skip(f"{what} is missing (scripts/setup.sh installs it; failed under CI)")


@pytest.fixture
def hub(tmp_path: Path, private_home: Path) -> Iterator[str]:
    try:
        import jupyterhub  # noqa: F401
    except ImportError:
        _need("jupyterhub")
    chp = _chp()
    if chp is None:
        _need("configurable-http-proxy (npm)")
    port, hub_port, api_port = free_port(), free_port(), free_port()
    env_for_learner = {
        "SLAMCOURSE_COURSE": str(FIXTURE_COURSE),
        "SLAMCOURSE_HOME": str(private_home),
        "JUPYTER_CONFIG_DIR": str(tmp_path / "jupyter-config"),
        "JUPYTER_DATA_DIR": str(tmp_path / "jupyter-data"),
        "JUPYTER_RUNTIME_DIR": str(tmp_path / "jupyter-runtime"),
    }
    config = tmp_path / "jupyterhub_config.py"
    config.write_text(
        f"""
c = get_config()  # noqa
c.JupyterHub.bind_url = "http://127.0.0.1:{port}"
c.JupyterHub.hub_bind_url = "http://127.0.0.1:{hub_port}"
c.ConfigurableHTTPProxy.api_url = "http://127.0.0.1:{api_port}"
c.ConfigurableHTTPProxy.command = [{chp!r}]
c.ConfigurableHTTPProxy.should_start = True
c.JupyterHub.db_url = "sqlite:///{tmp_path}/jupyterhub.sqlite"
c.JupyterHub.cookie_secret_file = "{tmp_path}/cookie_secret"
c.JupyterHub.pid_file = "{tmp_path}/jupyterhub.pid"
c.JupyterHub.authenticator_class = "dummy"
c.Authenticator.allowed_users = {{"{USER}"}}
c.JupyterHub.spawner_class = "simple"
c.SimpleLocalProcessSpawner.home_dir_template = "{tmp_path}/home/{{username}}"
c.Spawner.cmd = [{sys.executable!r}, "-m", "jupyterhub.singleuser"]
c.Spawner.args = ["--allow-root"]
c.Spawner.environment = {env_for_learner!r}
c.Spawner.start_timeout = 120
c.Spawner.http_timeout = 120
c.JupyterHub.services = [{{"name": "grader", "api_token": "{API_TOKEN}"}}]
c.JupyterHub.load_roles = [{{
    "name": "grader",
    "scopes": ["admin:users", "admin:servers", "access:servers"],
    "services": ["grader"],
}}]
"""
    )
    (tmp_path / "home" / USER).mkdir(parents=True)
    log = (tmp_path / "jupyterhub.log").open("wb")
    proc = subprocess.Popen(
        [sys.executable, "-m", "jupyterhub", "-f", str(config)],
        cwd=tmp_path,
        stdout=log,
        stderr=subprocess.STDOUT,
        env={**os.environ, "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}"},
    )
    base = f"http://127.0.0.1:{port}"
    try:
        _wait(lambda: fetch(f"{base}/hub/api/", headers=_auth())[0] == 200, proc, tmp_path)
        yield base
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        log.close()


def _auth() -> dict[str, str]:
    return {"Authorization": f"token {API_TOKEN}"}


def _wait(
    ready: object, proc: subprocess.Popen[bytes], tmp_path: Path, timeout: float = 90
) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            pytest.fail(f"jupyterhub exited:\n{(tmp_path / 'jupyterhub.log').read_text()[-4000:]}")
        try:
            if ready():  # type: ignore[operator]
                return
        except OSError:
            pass
        time.sleep(0.5)
    pytest.fail(f"timed out:\n{(tmp_path / 'jupyterhub.log').read_text()[-4000:]}")


def test_the_course_through_a_real_jupyterhub(hub: str, tmp_path: Path) -> None:
    status, body, _ = fetch(f"{hub}/hub/api/users/{USER}/server", data=b"", headers=_auth())
    assert status in (201, 202), body[:500]

    def spawned() -> bool:
        _, data, _ = fetch(f"{hub}/hub/api/users/{USER}", headers=_auth())
        server = json.loads(data).get("servers", {}).get("", {})
        return bool(server.get("ready"))

    proc_log = tmp_path / "jupyterhub.log"
    deadline = time.monotonic() + 120
    while not spawned():
        assert time.monotonic() < deadline, proc_log.read_text()[-4000:]
        time.sleep(0.5)
    page = f"{hub}/user/{USER}/slamcourse/chapter/basics"
    status, body, _ = fetch(page, headers=_auth())
    assert status == 200, body[:500]
    html = body.decode()
    assert f'<meta name="slamcourse-root" content="/user/{USER}/slamcourse">' in html
    assert f'src="/user/{USER}/slamcourse/static/course.js"' in html
    status, js, _ = fetch(f"{hub}/user/{USER}/slamcourse/static/course.js", headers=_auth())
    assert status == 200 and b"slamcourse-root" in js
    post = {**_auth(), "Content-Type": "application/json", "Origin": hub}
    status, body, _ = fetch(
        f"{hub}/user/{USER}/slamcourse/api/answer/basics/count",
        data=b'{"answer": "1"}',
        headers=post,
    )
    assert status == 200, body[:500]
    assert json.loads(body)["status"] == "failed"
    # without the hub's credentials: sent to log in, never to the course
    status, _, _ = fetch(page)
    assert status in (302, 401, 403)
