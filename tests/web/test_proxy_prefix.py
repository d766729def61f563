"""The browser face behind a proxy that authenticates first (jupyter-server-proxy on a hub):
the token in a header, the app mounted under the proxy's prefix (links, static files, API
calls), the hub's host and origin; and nothing of that without the token."""

from __future__ import annotations

import re
from typing import Any

from slamcourse.web.app import PROXY_HEADER
from tests.web.conftest import TOKEN

PREFIX = "/user/ada/slamcourse"
HUB = "hub.example.org"


def proxied(token: str = TOKEN, prefix: str = PREFIX) -> dict[str, str]:
    return {PROXY_HEADER: token, "X-Forwarded-Prefix": prefix, "Host": HUB}


def test_pages_under_the_prefix(client: Any) -> None:
    page = client.get("/chapter/basics", headers=proxied())
    assert page.status_code == 200
    html = page.get_data(as_text=True)
    assert f'<meta name="slamcourse-root" content="{PREFIX}">' in html
    links = re.findall(r'(?:href|src)="(/[^"]*)"', html)
    assert links and all(link.startswith(PREFIX + "/") for link in links), links
    with client.get("/static/course.js", headers=proxied()) as static:
        assert static.status_code == 200 and b"slamcourse-root" in static.data
    nxt = client.get("/next", headers=proxied())
    assert nxt.status_code == 303 and nxt.headers["Location"].startswith(PREFIX + "/chapter/")
    api = client.get("/api/next", headers=proxied()).get_json()
    assert api["url"].startswith(PREFIX + "/chapter/basics#")


def test_api_check_through_the_proxy(client: Any) -> None:
    headers = {**proxied(), "Origin": f"https://{HUB}"}
    resp = client.post("/api/answer/basics/count", json={"answer": "1"}, headers=headers)
    assert resp.status_code == 200 and resp.get_json()["status"] == "failed"
    assert resp.get_json()["next_url"] is None or resp.get_json()["next_url"].startswith(PREFIX)
    evil = {**proxied(), "Origin": "https://evil.example"}
    resp = client.post("/api/answer/basics/count", json={"answer": "1"}, headers=evil)
    assert resp.status_code == 403 and "Origin" in resp.get_json()["error"]
    form = client.post("/api/answer/basics/count", data="answer=1", headers=headers)
    assert form.status_code == 415


def test_without_the_token_nothing_changes(client: Any) -> None:
    # a wrong token in the header: refused, whatever else the request says
    assert client.get("/chapter/basics", headers=proxied("nope")).status_code == 403
    # the prefix header alone is ignored, and the hub's host is not this server's
    only_prefix = {"X-Forwarded-Prefix": PREFIX}
    resp = client.get(f"/?token={TOKEN}", headers=only_prefix)
    assert resp.status_code == 303 and resp.headers["Location"] == "/"
    assert re.search(r"Path=/(;|$)", resp.headers["Set-Cookie"])
    page = client.get("/chapter/basics", headers=only_prefix).get_data(as_text=True)
    assert '<meta name="slamcourse-root" content="">' in page
    assert 'href="/static/course.css"' in page
    assert client.get("/chapter/basics", headers={"Host": HUB}).status_code == 400
    fresh = client.application.test_client()
    assert fresh.get("/chapter/basics").status_code == 403  # no token at all
