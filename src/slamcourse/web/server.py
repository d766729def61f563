"""``slamcourse serve``: run the browser face on a local port.

One :class:`~slamcourse.engine.Engine` (the same course, progress database and sandbox as the
terminal, from :meth:`Settings.from_env`) serves every request, from waitress: one event loop
reads requests, a fixed pool of threads runs the app. The address printed carries a fresh random
token, as Jupyter's does (or the token a launcher set in ``$SLAMCOURSE_SERVE_TOKEN``, then not
printed: docs/deploying.md); the browser is opened on a private local file that redirects to it, so
the token is never on a command line, and the access log names paths without their queries.

Limits (docs/architecture.md, "Serving"): at most :data:`CONNECTION_LIMIT` connections, the
longest-idle ones closed to make room (so half-open connections can neither exhaust descriptors
nor lock the learner out); a connection idle for :data:`IDLE_TIMEOUT` seconds without a request
in progress is closed (a header or body that never ends); bodies over the app's limit are
refused with 413 before they are read; at most :data:`CHECK_SLOTS` code checks run at once.
"""

from __future__ import annotations

import html
import logging
import os
import secrets
import shutil
import tempfile
import threading
import time
import webbrowser
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol
from urllib.parse import quote

from slamcourse.errors import UsageError

if TYPE_CHECKING:
    from slamcourse.engine import Engine

ENV_TOKEN = "SLAMCOURSE_SERVE_TOKEN"
"""The token to require instead of a fresh one: set by a launcher that starts the server and
holds the token itself (jupyter-server-proxy on a hub, :mod:`slamcourse.notebook.hub`); then
the address is printed without it."""
LOOPBACK = ("127.0.0.1", "localhost", "::1")
DEFAULT_PORT = 8765
CONNECTION_LIMIT = 256
"""Open connections at most (a browser uses about six); far below the usual 1024 descriptors,
which the sandbox's pipes (``select``) also need."""
IDLE_TIMEOUT = 5
"""Seconds a connection may stay silent with no request being answered (waitress's
``channel_timeout``; checked every second)."""
CHECK_SLOTS = 2 * (os.cpu_count() or 1)
"""Code checks (each a sandbox worker) running at once; as many more wait, then 503."""
CHECK_WAIT = 120.0
THREADS = 2 * CHECK_SLOTS + 4
"""The app's threads: every running and waiting code check, and four for pages besides."""

WSGIApp = Callable[[dict[str, Any], Callable[..., Any]], Iterable[bytes]]
log = logging.getLogger("slamcourse.web")
access_log = logging.getLogger("slamcourse.web.access")


def allowed_hosts(host: str, port: int) -> list[str]:
    """Host header values this server answers to: its loopback names (and ``host``) with port."""
    names = {"127.0.0.1", "localhost"}
    if host == "::":
        names.add("[::1]")
    elif host not in ("0.0.0.0", ""):
        names.add(f"[{host}]" if ":" in host else host)
    return sorted(f"{n}:{port}" for n in names)


def shown_host(host: str) -> str:
    """The host part of the printed address: a loopback name for a wildcard, IPv6 in brackets."""
    if host in ("0.0.0.0", ""):
        return "127.0.0.1"
    if host == "::":
        return "[::1]"  # waitress binds IPv6 only
    return f"[{host}]" if ":" in host else host


@dataclass
class Running:
    server: Server
    url: str  # with the token
    base: str
    token: str


@contextmanager
def running(
    engine: Engine, *, host: str = "127.0.0.1", port: int = 0, token: str | None = None
) -> Iterator[Running]:
    """Serve ``engine`` in a background thread (tests, benchmarks); stopped on exit."""
    srv = make(engine, host=host, port=port, token=token)
    thread = threading.Thread(target=srv.server.serve_forever, daemon=True)
    thread.start()
    try:
        yield srv
    finally:
        srv.server.shutdown()
        thread.join(timeout=10)


def make(
    engine: Engine, *, host: str = "127.0.0.1", port: int = 0, token: str | None = None
) -> Running:
    """Bind the server (port 0: any free port) and build the app for its real address."""
    from slamcourse.web.app import MAX_BODY, create_app

    token = token or secrets.token_urlsafe(24)
    try:
        # the app is replaced once the real port is known (Host checks name it)
        srv = bind(host, port, _placeholder, max_body=MAX_BODY)
    except OSError as exc:
        raise UsageError(f"cannot listen on {host}:{port}: {exc.strerror or exc}") from exc
    real_port = srv.server_port
    app = create_app(engine, token=token, hosts=allowed_hosts(host, real_port))
    srv.application = AccessLog(CodeCheckLimit(app, slots=CHECK_SLOTS, queue=CHECK_SLOTS))
    base = f"http://{shown_host(host)}:{real_port}/"
    return Running(srv, f"{base}?token={token}", base, token)


def _placeholder(environ: dict[str, Any], start_response: Callable[..., Any]) -> list[bytes]:
    start_response("503 Service Unavailable", [("Content-Type", "text/plain")])
    return [b"starting"]


def _server_class() -> type[Any]:
    from waitress.server import TcpWSGIServer

    class _Server(TcpWSGIServer):  # type: ignore[misc]
        """Waitress's TCP server that makes room at its connection limit by closing the
        longest-idle connections (never one whose request is being answered), so a flood of
        half-open connections cannot keep the learner out; stoppable from another thread."""

        next_channel_cleanup: float = 0.0
        _stopping = False
        _warned = 0.0

        def readable(self) -> bool:
            now = time.time()
            if now >= self.next_channel_cleanup:
                self.next_channel_cleanup = now + self.adj.cleanup_interval
                self.maintenance(now)
            if not self.accepting:
                return False
            if len(self._map) < self.adj.connection_limit:
                return True
            self._make_room(now)
            return False

        def _make_room(self, now: float) -> None:
            idle = [
                c
                for c in self.active_channels.values()
                if not (c.requests or c.will_close or c.close_when_flushed)
            ]
            idle.sort(key=lambda c: c.last_activity)
            for channel in idle[: max(1, self.adj.connection_limit // 8)]:
                channel.will_close = True
            if now - self._warned > 60:
                self._warned = now
                log.warning(
                    "%d connections open: closing the longest idle", len(self.active_channels)
                )

        @property
        def server_port(self) -> int:
            return int(self.effective_port)

        def serve_forever(self) -> None:
            try:
                while not self._stopping:
                    self.asyncore.loop(
                        timeout=self.adj.asyncore_loop_timeout,
                        map=self._map,
                        use_poll=True,
                        count=1,
                    )
            finally:
                self.task_dispatcher.shutdown(timeout=5)
                from waitress import wasyncore

                wasyncore.close_all(self._map)

        def shutdown(self) -> None:
            self._stopping = True
            self.pull_trigger()

    return _Server


class Server(Protocol):
    """The waitress server :func:`bind` returns."""

    application: WSGIApp

    @property
    def server_port(self) -> int: ...
    def serve_forever(self) -> None: ...
    def shutdown(self) -> None: ...


def bind(host: str, port: int, app: WSGIApp, *, max_body: int) -> Server:
    """Listen on ``host:port`` with slamcourse's limits (a connection cap, idle timeout, body
    size, the thread pool)."""
    from waitress.adjustments import Adjustments

    adj = Adjustments(
        listen=f"[{host}]:{port}" if ":" in host else f"{host}:{port}",
        threads=THREADS,
        connection_limit=CONNECTION_LIMIT,
        channel_timeout=IDLE_TIMEOUT,
        cleanup_interval=1,
        max_request_body_size=max_body,
        max_request_header_size=64 * 1024,
        asyncore_use_poll=True,
        ident="slamcourse",
    )
    srv: Server = _server_class()(app, adj=adj, sockinfo=adj.listen[0])
    return srv


class AccessLog:
    """One line per request, ``METHOD /path STATUS``: never the query (``?token=``)."""

    def __init__(self, app: WSGIApp) -> None:
        self.app = app

    def __call__(self, environ: dict[str, Any], start_response: Callable[..., Any]) -> Any:
        def logged(status: str, headers: list[tuple[str, str]], *exc: Any) -> Any:
            path = environ.get("PATH_INFO", "").encode("latin-1", "replace")
            method = "".join(c for c in environ.get("REQUEST_METHOD", "") if c.isalpha())
            access_log.info("%s %s %s", method[:16], quote(path, safe="/"), status.split()[0])
            return start_response(status, headers, *exc)

        return self.app(environ, logged)


class CodeCheckLimit:
    """At most ``slots`` code checks (``POST /api/code/…``, each a sandbox worker) at once; up to
    ``queue`` more wait their turn (at most ``wait`` seconds); beyond that, 503 with
    Retry-After."""

    def __init__(self, app: WSGIApp, *, slots: int, queue: int, wait: float = CHECK_WAIT) -> None:
        self.app = app
        self.slots = threading.BoundedSemaphore(slots)
        self.capacity = slots + queue
        self.wait = wait
        self.lock = threading.Lock()
        self.admitted = 0

    def __call__(self, environ: dict[str, Any], start_response: Callable[..., Any]) -> Any:
        if environ.get("REQUEST_METHOD") != "POST" or not environ.get("PATH_INFO", "").startswith(
            "/api/code/"
        ):
            return self.app(environ, start_response)
        with self.lock:
            if self.admitted >= self.capacity:
                return _busy(start_response)
            self.admitted += 1
        try:
            if not self.slots.acquire(timeout=self.wait):
                return _busy(start_response)
            try:
                body = self.app(environ, start_response)
                try:
                    return [b"".join(body)]  # the whole check runs inside the slot
                finally:
                    close = getattr(body, "close", None)
                    if close is not None:
                        close()
            finally:
                self.slots.release()
        finally:
            with self.lock:
                self.admitted -= 1


def _busy(start_response: Callable[..., Any]) -> list[bytes]:
    body = b'{"error": "Too many code checks at once: try again in a few seconds."}'
    start_response(
        "503 Service Unavailable",
        [
            ("Content-Type", "application/json"),
            ("Content-Length", str(len(body))),
            ("Retry-After", "5"),
            ("Cache-Control", "no-store"),
            ("X-Content-Type-Options", "nosniff"),
        ],
    )
    return [body]


def launch_file(url: str, folder: Path) -> Path:
    """A page that redirects to ``url`` (which holds the token), readable by this user only:
    mode 0600 in a fresh 0700 directory under ``folder``. The browser is opened on this file,
    so the token is not on its command line (``/proc/PID/cmdline`` is world-readable)."""
    folder.mkdir(parents=True, exist_ok=True)
    private = Path(tempfile.mkdtemp(prefix="serve-", dir=folder))  # mode 0700
    path = private / "open.html"
    href = html.escape(url, quote=True)
    page = (
        '<!DOCTYPE html>\n<html><head><meta charset="utf-8">\n'
        f'<meta http-equiv="refresh" content="0;url={href}">\n'
        "<title>slamcourse</title></head>\n"
        f'<body><p>Opening <a href="{href}">slamcourse</a>…</p></body></html>\n'
    )
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        f.write(page)
    return path


def open_in_browser(url: str, folder: Path) -> Path:
    """Open the default browser (``$BROWSER`` honoured) on :func:`launch_file`; returns it."""
    path = launch_file(url, folder)
    threading.Timer(0.3, webbrowser.open, args=(path.as_uri(),)).start()
    return path


def serve(
    *,
    course: str | None,
    host: str,
    port: int | None,
    open_browser: bool,
    say: Callable[[str], None],
) -> int:
    """Run until interrupted; returns the exit code. ``port`` None: 8765, or any free port
    when that one is taken (an explicit port that is taken is an error)."""
    from slamcourse.engine import Engine
    from slamcourse.settings import Settings

    settings = Settings.from_env(course=course)
    given = os.environ.get(ENV_TOKEN) or None
    with Engine.open(settings) as engine:
        engine.start_workers()
        try:
            srv = make(engine, host=host, port=DEFAULT_PORT if port is None else port, token=given)
        except UsageError:
            if port is not None:
                raise
            srv = make(engine, host=host, port=0, token=given)
        if host not in LOOPBACK:
            say(
                f"Warning: listening on {host}, not only this computer. Anyone who can reach it "
                "and has the token can run code as you."
            )
        if given is not None:  # the launcher holds the token and puts it in front
            say(f"slamcourse is running at {srv.base} (the token is ${ENV_TOKEN}).")
        else:
            say("slamcourse is running. Open this address in your browser (it holds your token):")
            say(f"    {srv.url}")
        say("Press Ctrl+C to stop; your progress is saved after every answer.")
        handler = logging.StreamHandler()  # stderr, as Werkzeug's log was
        handler.setFormatter(logging.Formatter("%(asctime)s %(message)s", "%H:%M:%S"))
        log.addHandler(handler)
        log.setLevel(logging.INFO)
        launch = None
        try:
            if open_browser:
                launch = open_in_browser(srv.url, settings.home / "run")
            srv.server.serve_forever()
        except KeyboardInterrupt:
            say("\nStopped; progress is saved.")
        finally:
            log.removeHandler(handler)
            if launch is not None:
                shutil.rmtree(launch.parent, ignore_errors=True)
    return 0
