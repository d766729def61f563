"""``slamcourse serve``: run the browser face on a local port.

One :class:`~slamcourse.engine.Engine` (the same course, progress database and sandbox as the
terminal, from :meth:`Settings.from_env`) serves every request, from Werkzeug's threaded
server. The address printed carries a fresh random token, as Jupyter's does.
"""

from __future__ import annotations

import secrets
import threading
import webbrowser
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING

from slamcourse.errors import UsageError

if TYPE_CHECKING:
    from werkzeug.serving import BaseWSGIServer

    from slamcourse.engine import Engine

LOOPBACK = ("127.0.0.1", "localhost", "::1")
DEFAULT_PORT = 8765


def allowed_hosts(host: str, port: int) -> list[str]:
    """Host header values this server answers to: its loopback names (and ``host``) with port."""
    names = {"127.0.0.1", "localhost"}
    if host not in ("0.0.0.0", "::", ""):
        names.add(f"[{host}]" if ":" in host else host)
    return sorted(f"{n}:{port}" for n in names)


@dataclass
class Running:
    server: BaseWSGIServer
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
        srv.server.server_close()
        thread.join(timeout=5)


def make(
    engine: Engine, *, host: str = "127.0.0.1", port: int = 0, token: str | None = None
) -> Running:
    """Bind the server (port 0: any free port) and build the app for its real address."""
    from werkzeug.serving import make_server

    from slamcourse.web.app import create_app

    token = token or secrets.token_urlsafe(24)
    try:
        # the app is replaced once the real port is known (Host checks name it)
        srv = make_server(host, port, _placeholder, threaded=True)
    except OSError as exc:
        raise UsageError(f"cannot listen on {host}:{port}: {exc.strerror or exc}") from exc
    real_port = srv.server_port
    srv.app = create_app(engine, token=token, hosts=allowed_hosts(host, real_port))
    shown = "127.0.0.1" if host in ("0.0.0.0", "::", "") else host
    base = f"http://{shown}:{real_port}/"
    return Running(srv, f"{base}?token={token}", base, token)


def _placeholder(environ: object, start_response: Callable[..., object]) -> list[bytes]:
    start_response("503 Service Unavailable", [("Content-Type", "text/plain")])
    return [b"starting"]


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
    with Engine.open(settings) as engine:
        engine.start_workers()
        try:
            srv = make(engine, host=host, port=DEFAULT_PORT if port is None else port)
        except UsageError:
            if port is not None:
                raise
            srv = make(engine, host=host, port=0)
        if host not in LOOPBACK:
            say(
                f"Warning: listening on {host}, not only this computer. Anyone who can reach it "
                "and has the token can run code as you."
            )
        say("slamcourse is running. Open this address in your browser (it holds your token):")
        say(f"    {srv.url}")
        say("Press Ctrl+C to stop; your progress is saved after every answer.")
        if open_browser:
            threading.Timer(0.3, webbrowser.open, args=(srv.url,)).start()
        try:
            srv.server.serve_forever()
        except KeyboardInterrupt:
            say("\nStopped; progress is saved.")
        finally:
            srv.server.server_close()
    return 0
