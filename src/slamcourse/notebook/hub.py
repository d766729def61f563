"""``slamcourse serve`` behind JupyterHub: the jupyter-server-proxy entry point.

With ``slamcourse[jupyter]`` installed in the single-user image, JupyterLab's launcher shows a
*slamcourse* tile (pyproject's ``jupyter_serverproxy_servers`` entry point names
:func:`setup_slamcourse`). Clicking it starts ``slamcourse serve`` on a free local port and
proxies ``<hub>/user/<name>/slamcourse/`` to it:

- the hub's authentication (and the Jupyter server's) stands in front of every request;
- this function draws a fresh random token each time the Jupyter server starts, hands it to
  the server through its environment (``$SLAMCOURSE_SERVE_TOKEN``: never on a command line,
  which other local users can read) and has the proxy add it to every request it forwards
  (the ``X-Slamcourse-Token`` header). A request that reaches the port directly, not through
  the proxy, still needs the token;
- the proxy says where it mounts the app (``X-Forwarded-Prefix``), which the app builds every
  link, static file and API call on (:class:`slamcourse.web.app.ProxyPrefix`).

docs/deploying.md shows a class deployment on Zero to JupyterHub.
"""

from __future__ import annotations

import secrets
import sys
from pathlib import Path
from typing import Any

NAME = "slamcourse"


def setup_slamcourse() -> dict[str, Any]:
    """The jupyter-server-proxy server process of slamcourse (called once per Jupyter server)."""
    from slamcourse.web.app import PROXY_HEADER
    from slamcourse.web.server import ENV_TOKEN

    token = secrets.token_urlsafe(24)
    return {
        "command": [
            sys.executable,
            "-m",
            "slamcourse",
            "serve",
            "--no-browser",
            "--port",
            "{port}",
        ],
        "environment": {ENV_TOKEN: token},
        "request_headers_override": {PROXY_HEADER: token},
        "absolute_url": False,
        "timeout": 60,
        "new_browser_tab": True,
        "launcher_entry": {
            "enabled": True,
            "title": "slamcourse",
            "icon_path": str(Path(__file__).with_name("icon.svg")),
        },
    }
