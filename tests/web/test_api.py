"""The web API with Flask's test client: security checks, then the engine's results in JSON."""

from __future__ import annotations

import math
from typing import Any

from slamcourse.engine import Engine
from tests.web.conftest import HOST, TOKEN

JSON = {"Origin": f"http://{HOST}"}


def login(client: Any) -> None:
    resp = client.get(f"/?token={TOKEN}")
    assert resp.status_code == 303
    assert resp.headers["Location"] == "/"
    cookie = resp.headers["Set-Cookie"]
    assert "HttpOnly" in cookie and "SameSite=Strict" in cookie


def answer(client: Any, ex: str, text: str, **extra: Any) -> Any:
    return client.post(f"/api/answer/{ex}", json={"answer": text, **extra}, headers=JSON)


def distance(engine: Engine, canonical: bool = False) -> float:
    p = engine.pose("basics/distance", canonical=canonical).variant.params
    return math.hypot(p["dx"], p["dy"])


# ------------------------------------------------------------------ security


def test_every_page_and_api_needs_the_token(client: Any) -> None:
    for url in ("/", "/chapter/basics", "/api/summary", "/api/exercise/basics/distance", "/next"):
        assert client.get(url).status_code == 403, url
    assert client.get("/?token=wrong").status_code == 403
    assert answer(client, "basics/distance", "5").status_code == 403
    # static files (KaTeX, the script) read no progress and need no token
    with client.get("/static/vendor/katex/katex.min.js") as resp:
        assert resp.status_code == 200


def test_token_once_then_cookie(client: Any) -> None:
    login(client)
    page = client.get("/chapter/basics")
    assert page.status_code == 200
    assert "Content-Security-Policy" in page.headers
    assert "script-src 'self'" in page.headers["Content-Security-Policy"]
    html = page.get_data(as_text=True)
    assert "<script>" not in html  # no inline scripts
    # the one style nonce (for the code editor's <style>) is fresh on every response
    nonce = page.headers["Content-Security-Policy"].split("'nonce-")[1].split("'")[0]
    assert f'name="slamcourse-style-nonce" content="{nonce}"' in html
    assert nonce not in client.get("/chapter/basics").headers["Content-Security-Policy"]


def test_foreign_host_is_refused(client: Any) -> None:
    login(client)
    resp = client.get("/api/summary", headers={"Host": "evil.example:5000"})
    assert resp.status_code == 400
    assert "Host" in resp.get_json()["error"]
    # the other loopback name passes the Host check (and is then asked for the token)
    assert client.get("/api/summary", headers={"Host": "127.0.0.1:5000"}).status_code == 403


def test_cross_site_post_is_refused(client: Any) -> None:
    login(client)
    resp = client.post(
        "/api/answer/basics/distance",
        json={"answer": "5"},
        headers={"Origin": "http://evil.example"},
    )
    assert resp.status_code == 403
    resp = client.post(
        "/api/answer/basics/distance",
        json={"answer": "5"},
        headers={"Sec-Fetch-Site": "cross-site"},
    )
    assert resp.status_code == 403
    # a form post (no JSON) is what a cross-site page could send without a preflight
    resp = client.post("/api/answer/basics/distance", data={"answer": "5"}, headers=JSON)
    assert resp.status_code == 415


def test_request_size_limit(client: Any) -> None:
    login(client)
    resp = answer(client, "basics/distance", "1" * (300 * 1024))
    assert resp.status_code == 413


# ------------------------------------------------------------------ answers


def test_number_wrong_then_right(client: Any, engine: Engine) -> None:
    login(client)
    d = distance(engine)
    wrong = answer(client, "basics/distance", repr(d * d)).get_json()
    assert wrong["status"] == "failed" and wrong["counted"]
    assert wrong["misconception"] == "squared"
    assert "square root" in wrong["feedback_html"]
    assert wrong["explanation"] is None
    right = answer(client, "basics/distance", repr(d)).get_json()
    assert right["status"] == "passed" and right["exercise_status"] == "solved"
    assert right["attempts"] == 2
    assert right["explanation_html"]
    solved = {e["id"]: e["status"] for ch in right["summary"] for e in ch["exercises"]}
    assert solved["basics/distance"] == "solved"
    assert engine.state("basics/distance").status == "solved"  # the terminal sees it too


def test_unreadable_answer_is_escaped_and_costs_nothing(client: Any) -> None:
    login(client)
    data = answer(client, "basics/distance", "<script>alert(1)</script>").get_json()
    assert data["status"] == "invalid" and not data["counted"]
    assert "<script>" not in data["feedback_html"]


def test_matrix_wrong_cell_is_named(client: Any) -> None:
    login(client)
    data = answer(client, "basics/identity", "[[1, 0], [5, 1]]").get_json()
    assert data["status"] == "failed"
    assert data["details"]["wrong"] == [[1, 0]]


def test_explanation_locked_until_solved(client: Any, engine: Engine) -> None:
    login(client)
    resp = client.get("/api/explanation/basics/distance")
    assert resp.status_code == 403
    assert "not solved" in resp.get_json()["error"]
    answer(client, "basics/distance", repr(distance(engine)))
    resp = client.get("/api/explanation/basics/distance")
    assert resp.status_code == 200 and resp.get_json()["explanation_html"]


def test_canonical_practice_is_not_counted(client: Any, engine: Engine) -> None:
    login(client)
    prompt = client.get("/api/exercise/basics/distance?canonical=1").get_json()
    assert prompt["practice"] and prompt["variant"] == 0
    data = answer(client, "basics/distance", repr(distance(engine, canonical=True)), canonical=True)
    result = data.get_json()
    assert result["status"] == "passed" and result["practice"] and not result["counted"]
    assert result["exercise_status"] == "pending"
    assert engine.state("basics/distance").status == "pending"


def test_hint_then_give_up(client: Any) -> None:
    login(client)
    hint = client.post("/api/hint/basics/distance", json={}, headers=JSON).get_json()
    assert hint["number"] == 1 and hint["total"] == 2 and hint["hint_html"]
    gave = client.post("/api/giveup/basics/distance", json={}, headers=JSON).get_json()
    assert gave["exercise_status"] == "given_up" and gave["explanation_html"]


def test_code_check_shows_counterexample(client: Any, engine: Engine) -> None:
    login(client)
    src = "import math\n\ndef range_bearing(dx, dy, theta):\n    return math.hypot(dx, dy), 0.0\n"
    base = client.get("/api/exercise/basics/range-bearing").get_json()["source_hash"]
    data = client.post(
        "/api/code/basics/range-bearing", json={"source": src, "based_on": base}, headers=JSON
    ).get_json()
    assert data["status"] == "failed"
    [test] = data["tests"]
    assert set(test["input"]) == {"dx", "dy", "theta"}
    assert test["got"] is not None and test["expected"] is not None
    # the page's editor and the learner's file are one file
    assert engine.code_file("basics/range-bearing").read_text() == src
    assert data["file_hash"] == engine.code_source("basics/range-bearing")[1]


def test_code_check_never_overwrites_an_edit_on_disk(client: Any, engine: Engine) -> None:
    """Issue 15: the page loaded the file, the learner edited it in their own editor, then
    clicked Check in the page: a conflict (409), nothing written, both versions offered."""
    login(client)
    url = "/api/code/basics/range-bearing"
    shown = client.get("/api/exercise/basics/range-bearing").get_json()
    path = engine.code_file("basics/range-bearing")
    mine = "def range_bearing(dx, dy, theta):\n    return 0, 0\n"
    on_disk = "# my own editor\n" + mine
    path.write_text(on_disk, encoding="utf-8")
    base = shown.get("source_hash")
    resp = client.post(url, json={"source": mine, "based_on": base}, headers=JSON)
    assert path.read_text(encoding="utf-8") == on_disk, "the edit on disk was overwritten"
    assert resp.status_code == 409
    assert shown["source"] != on_disk and base
    conflict = resp.get_json()["conflict"]
    assert conflict["message"].startswith("range_bearing.py changed on disk")
    assert conflict["disk_source"] == on_disk and conflict["name"] == "range_bearing.py"
    assert path.read_text(encoding="utf-8") == on_disk
    assert engine.state("basics/range-bearing").attempts == 0
    # the same text as on disk is no conflict (nothing would be lost)
    same = client.post(url, json={"source": on_disk, "based_on": "sha256:0"}, headers=JSON)
    assert same.status_code == 200 and same.get_json()["file_hash"] == conflict["disk_hash"]
    # without a base the source is graded, never saved; `overwrite` is the explicit choice
    blind = client.post(url, json={"source": mine}, headers=JSON).get_json()
    assert blind["status"] == "failed" and blind["file_hash"] is None
    assert path.read_text(encoding="utf-8") == on_disk
    forced = client.post(url, json={"source": mine, "overwrite": True}, headers=JSON)
    assert forced.status_code == 200 and path.read_text(encoding="utf-8") == mine
    bad = client.post(url, json={"source": mine, "based_on": 3}, headers=JSON)
    assert bad.status_code == 400


def test_chapter_page_renders_every_form(client: Any) -> None:
    login(client)
    html = client.get("/chapter/basics").get_data(as_text=True)
    for form in (
        "number",
        "vector",
        "matrix",
        "expression",
        "choice",
        "multi",
        "order",
        "line",
        "code",
    ):
        assert f'data-form="{form}"' in html, form
    assert 'class="math inline"' in html
    assert html.count('role="status"') == 11  # one live region per exercise


def test_next_redirects_to_the_open_exercise(client: Any, engine: Engine) -> None:
    login(client)
    answer(client, "basics/distance", repr(distance(engine)))
    resp = client.get("/next")
    assert resp.status_code == 303
    assert resp.headers["Location"].endswith("/chapter/basics#ex-basics--heading")


def test_plot_of_a_bundled_exercise(tmp_path: Any) -> None:
    from slamcourse.web.app import create_app
    from tests.conftest import REPO
    from tests.web.conftest import settings_for

    with Engine.open(settings_for(tmp_path, REPO)) as eng:
        c = create_app(eng, token=TOKEN, hosts=[HOST]).test_client()
        login(c)
        resp = c.get("/plot/observation/predicted-range")
        assert resp.status_code == 200 and resp.mimetype == "image/svg+xml"
        params = eng.pose("observation/predicted-range").variant.params
        r = math.hypot(params["xj"] - params["xr"], params["yj"] - params["yr"])
        assert f"r = {r:.3g} m".replace("-", "−") not in resp.get_data(as_text=True)
        assert "r = ?" in resp.get_data(as_text=True)  # not solved: the answer is not drawn
        assert c.get("/plot/state/why-dense").status_code == 404
        star = "factor-graphs/star-fill-in"
        assert c.get(f"/plot/{star}").status_code == 404  # the picture is the answer: later
        c.post(f"/api/giveup/{star}", json={}, headers=JSON)
        assert c.get(f"/plot/{star}").status_code == 200
