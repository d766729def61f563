"""The server under misuse, over real sockets: half-open connections, short and oversized bodies,
odd tokens and JSON, IPv6 addresses, and where the token must never appear (the browser's
command line, the access log)."""

from __future__ import annotations

import contextlib
import http.client
import os
import resource
import signal
import socket
import stat
import subprocess
import sys
import threading
import time
import urllib.parse
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from slamcourse.engine import Engine
from tests.conftest import FIXTURE_COURSE, REPO
from tests.web.conftest import TOKEN

HALF_OPEN = 1200


def _port(live: Any) -> int:
    return int(urllib.parse.urlsplit(live.base).port or 0)


def _conn(live: Any, timeout: float = 10) -> http.client.HTTPConnection:
    return http.client.HTTPConnection("127.0.0.1", _port(live), timeout=timeout)


def _cookie(live: Any) -> str:
    """The token cookie, as the browser holds it after opening the printed address."""
    c = _conn(live)
    c.request("GET", f"/?token={TOKEN}")
    resp = c.getresponse()
    resp.read()
    c.close()
    assert resp.status == 303
    return resp.getheader("Set-Cookie", "").split(";")[0]


def _head(live: Any, path: str, extra: str = "", *, length: int | None = None) -> bytes:
    host = f"127.0.0.1:{_port(live)}"
    lines = [
        f"POST {path} HTTP/1.1",
        f"Host: {host}",
        f"Origin: http://{host}",
        f"Cookie: {_cookie(live)}",
        "Content-Type: application/json",
    ]
    if length is not None:
        lines.append(f"Content-Length: {length}")
    return ("\r\n".join(lines) + "\r\n" + extra + "\r\n").encode()


def _read_status(sock: socket.socket) -> tuple[int | None, float]:
    """The status of the first response on ``sock`` (None: closed without one) and the time
    it took."""
    start = time.monotonic()
    data = b""
    try:
        while b"\r\n" not in data:
            chunk = sock.recv(4096)
            if not chunk:
                break
            data += chunk
    except ConnectionResetError:
        pass
    took = time.monotonic() - start
    if not data:
        return None, took
    return int(data.split(b" ", 2)[1]), took


@pytest.fixture
def many_descriptors() -> Iterator[None]:
    """Room in this process for the attacker's sockets and the server's (a shared process)."""
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    want = 4 * HALF_OPEN
    if soft >= want:
        yield
        return
    if hard != resource.RLIM_INFINITY and hard < want:
        pytest.skip(f"RLIMIT_NOFILE hard limit {hard} < {want}")
    resource.setrlimit(resource.RLIMIT_NOFILE, (want, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_NOFILE, (soft, hard))


def _open_fds() -> int:
    return len(os.listdir("/proc/self/fd"))


@pytest.mark.slow
def test_half_open_connections_do_not_stop_the_server(
    live: Any, many_descriptors: None, caplog: pytest.LogCaptureFixture
) -> None:
    """Anyone on the machine can open connections and send half a header; the server keeps a
    bounded number of them (never running out of descriptors) and still answers the learner."""
    from slamcourse.web.server import CONNECTION_LIMIT

    before = _open_fds()
    half = f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{_port(live)}\r\n".encode()
    socks: list[socket.socket] = []
    try:
        for _ in range(HALF_OPEN):
            s = socket.create_connection(("127.0.0.1", _port(live)), timeout=10)
            socks.append(s)
            with contextlib.suppress(OSError):  # the server may have closed it to make room
                s.sendall(half)
        time.sleep(0.5)
        server_side = _open_fds() - before - len(socks)
        start = time.monotonic()
        c = _conn(live, timeout=10)
        c.request("GET", f"/?token={TOKEN}")
        resp = c.getresponse()
        resp.read()
        c.close()
        took = time.monotonic() - start
        assert resp.status == 303
        assert took < 3, f"a normal request took {took:.1f} s behind {HALF_OPEN} half-open ones"
        # the server holds at most its connection limit, far below the usual 1024 descriptors
        assert server_side <= CONNECTION_LIMIT + 16, server_side
        print(
            f"\n{HALF_OPEN} half-open: server-side descriptors {server_side}, "
            f"a normal request took {took * 1000:.0f} ms"
        )
    finally:
        for s in socks:
            s.close()
    assert "Too many open files" not in caplog.text
    c = _conn(live)
    c.request("GET", "/static/course.css")
    assert c.getresponse().status == 200
    c.close()


def test_a_body_shorter_than_its_length_is_not_waited_for_forever(live: Any) -> None:
    with socket.create_connection(("127.0.0.1", _port(live)), timeout=15) as s:
        s.sendall(_head(live, "/api/answer/basics/distance", length=100) + b'{"answer": ')
        status, took = _read_status(s)
    assert status in (None, 400, 408), status
    assert took < 10, f"held {took:.1f} s"


def test_an_oversized_chunked_body_is_413_promptly(live: Any) -> None:
    chunk = b"x" * 16384
    with socket.create_connection(("127.0.0.1", _port(live)), timeout=15) as s:
        start = time.monotonic()
        s.sendall(_head(live, "/api/answer/basics/distance", "Transfer-Encoding: chunked\r\n"))
        try:
            for _ in range(20):  # 320 KiB, over the 256 KiB limit
                s.sendall(b"%x\r\n%s\r\n" % (len(chunk), chunk))
            s.sendall(b"0\r\n\r\n")
        except OSError:  # refused before the end: fine
            pass
        status, _ = _read_status(s)
        took = time.monotonic() - start
    assert status == 413
    assert took < 3, f"took {took:.1f} s"


def test_an_oversized_body_with_a_length_is_413(live: Any) -> None:
    with socket.create_connection(("127.0.0.1", _port(live)), timeout=15) as s:
        s.sendall(_head(live, "/api/answer/basics/distance", length=300 * 1024))
        status, took = _read_status(s)
    assert status == 413 and took < 3


def test_a_non_ascii_token_is_refused_not_an_error(live: Any) -> None:
    c = _conn(live)
    c.request("GET", "/?token=" + urllib.parse.quote("tökén"))
    resp = c.getresponse()
    resp.read()
    assert resp.status == 403
    name = _cookie(live).split("=")[0]
    c.request("GET", "/api/summary", headers={"Cookie": f"{name}=tökén"})
    resp = c.getresponse()
    resp.read()
    assert resp.status == 403
    c.close()


def test_deeply_nested_json_is_a_bad_request(live: Any) -> None:
    depth = 100_000
    body = b'{"answer": ' + b"[" * depth + b"]" * depth + b"}"
    with socket.create_connection(("127.0.0.1", _port(live)), timeout=15) as s:
        s.sendall(_head(live, "/api/answer/basics/distance", length=len(body)) + body)
        status, _ = _read_status(s)
    assert status == 400


def test_an_ipv6_address_is_printed_in_brackets(engine: Engine) -> None:
    from slamcourse.web.server import running

    if not socket.has_ipv6:
        pytest.skip("no IPv6")
    try:
        with socket.socket(socket.AF_INET6) as probe:
            probe.bind(("::1", 0))
    except OSError:
        pytest.skip("no IPv6 loopback")
    with running(engine, host="::1", token=TOKEN) as srv:
        assert srv.url.startswith("http://[::1]:")
        port = urllib.parse.urlsplit(srv.base).port
        c = http.client.HTTPConnection("::1", port, timeout=10)
        c.request("GET", f"/?token={TOKEN}")
        assert c.getresponse().status == 303
        c.close()


def test_code_checks_beyond_the_queue_are_told_to_retry() -> None:
    from slamcourse.web.server import CodeCheckLimit

    release = threading.Event()
    running_now: list[int] = []

    def slow(environ: dict[str, Any], start_response: Any) -> list[bytes]:
        running_now.append(1)
        release.wait(10)
        start_response("200 OK", [])
        return [b"ok"]

    app = CodeCheckLimit(slow, slots=1, queue=1, wait=10)
    statuses: list[str] = []

    def call(path: str) -> None:
        def start(status: str, headers: list[tuple[str, str]]) -> None:
            statuses.append(status)
            if status.startswith("503"):
                assert ("Retry-After", "5") in headers

        b"".join(app({"REQUEST_METHOD": "POST", "PATH_INFO": path}, start))

    threads = [threading.Thread(target=call, args=("/api/code/x",)) for _ in range(2)]
    for t in threads:
        t.start()
    deadline = time.monotonic() + 5
    while not running_now and time.monotonic() < deadline:
        time.sleep(0.01)
    time.sleep(0.1)
    assert len(running_now) == 1  # one slot: the second waits
    call("/api/code/x")  # the queue is full: refused at once
    assert statuses == ["503 Service Unavailable"]
    release.set()
    for t in threads:
        t.join(10)
    assert statuses.count("200 OK") == 2 and len(running_now) == 2


def test_the_browser_is_opened_on_a_private_file_and_the_log_has_no_token(
    tmp_path: Path,
) -> None:
    """``slamcourse serve`` with a fake browser: the token is neither in the browser's command
    line (every local user can read /proc/PID/cmdline) nor in the access log."""
    argv_file = tmp_path / "argv.txt"
    fake = tmp_path / "fakebrowser"
    fake.write_text(f'#!/bin/sh\nprintf "%s\\n" "$0" "$@" > "{argv_file}"\n')
    fake.chmod(0o755)
    env = {
        k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "BROWSER")
    }
    home = tmp_path / "home"
    env.update(
        SLAMCOURSE_HOME=str(home),
        PYTHONPATH=str(REPO / "src"),
        PYTHONUNBUFFERED="1",
        BROWSER=str(fake),
    )
    cmd = [sys.executable, "-m", "slamcourse", "--course", str(FIXTURE_COURSE), "serve"]
    proc = subprocess.Popen(
        [*cmd, "--port", "0"],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        # Ctrl+C reaches it as it reaches a server started in a terminal, even when this suite
        # runs in the background (a shell's background job, and what it starts, ignores SIGINT)
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        assert proc.stdout is not None and proc.stderr is not None
        url = ""
        for _ in range(5):
            line = proc.stdout.readline()
            if "?token=" in line:
                url = line.strip()
                break
        token = url.split("?token=")[1]
        deadline = time.monotonic() + 20
        while not argv_file.exists() and time.monotonic() < deadline:
            time.sleep(0.05)
        argv = argv_file.read_text().splitlines()
        assert token not in " ".join(argv)
        assert argv[1].startswith("file://"), argv
        launch = Path(urllib.parse.unquote(urllib.parse.urlsplit(argv[1]).path))
        assert launch.is_relative_to(home)
        assert stat.S_IMODE(launch.stat().st_mode) == 0o600
        assert stat.S_IMODE(launch.parent.stat().st_mode) == 0o700
        assert url in launch.read_text()  # it redirects to the tokened address
        opener = urllib.request.build_opener(urllib.request.HTTPCookieProcessor())
        with opener.open(url, timeout=10) as page:
            assert page.status == 200
        proc.send_signal(signal.SIGINT)  # Ctrl+C
        try:  # (both pipes read meanwhile: a full one would hold the server up)
            _said, log = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            _said, log = proc.communicate()
            pytest.fail(f"serve did not stop within 30 s of Ctrl+C; its log ends:\n{log[-3000:]}")
        assert token not in log
        assert "GET / 303" in log and "GET / 200" in log  # paths are logged, queries never
        assert not launch.exists()  # the file holding the token goes with the server
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=10)
        for stream in (proc.stdout, proc.stderr):
            if stream is not None:
                stream.close()
