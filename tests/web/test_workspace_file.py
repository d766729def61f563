"""The workspace file behind the browser's code editor (issue 15): nothing lost, nothing raced.

A real server (conftest's ``live``) on the fixture course; every test here works on its one
code exercise, ``basics/range-bearing``, whose file the terminal's ``check`` and ``watch`` read.
"""

from __future__ import annotations

import http.client
import json
import threading
import time
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import pytest

from tests.web.conftest import TOKEN

EX = "basics/range-bearing"
PAD = "".join(f"# padding line {i:05d}: makes a torn write visible\n" for i in range(600))
CORRECT = (
    "import math\n\n"
    + PAD
    + "\ndef range_bearing(dx, dy, theta):\n"
    + "    return math.hypot(dx, dy), math.atan2(dy, dx) - theta\n"
)
WRONG = PAD + "\ndef range_bearing(dx, dy, theta):\n    return 0, 0\n"


class Client:
    """A minimal HTTP client of the live server: the token once, then the cookie."""

    def __init__(self, live: Any) -> None:
        parts = urlsplit(live.base)
        self.host, self.port = parts.hostname or "127.0.0.1", parts.port or 80
        self.origin = f"http://{parts.netloc}"
        conn = http.client.HTTPConnection(self.host, self.port, timeout=30)
        conn.request("GET", f"/?token={TOKEN}")
        resp = conn.getresponse()
        resp.read()
        self.cookie = (resp.getheader("Set-Cookie") or "").split(";")[0]
        conn.close()
        assert self.cookie, "no token cookie"

    def request(self, method: str, path: str, body: Any = None) -> tuple[int, Any]:
        conn = http.client.HTTPConnection(self.host, self.port, timeout=120)
        headers = {"Cookie": self.cookie, "Origin": self.origin}
        data = None
        if body is not None:
            data = json.dumps(body).encode()
            headers["Content-Type"] = "application/json"
        try:
            conn.request(method, path, body=data, headers=headers)
            resp = conn.getresponse()
            return resp.status, json.loads(resp.read() or b"null")
        finally:
            conn.close()


def code_file(live: Any) -> Path:
    path: Path = live.engine.code_file(EX)
    return path


def test_simultaneous_checks_grade_their_own_source(live: Any) -> None:
    """Six concurrent checks of one exercise (three right, three wrong), several rounds: each
    verdict is the verdict of the source sent, and the file is never seen half-written."""
    client = Client(live)
    path = code_file(live)
    starter = path.read_text(encoding="utf-8")
    whole = {starter, CORRECT, WRONG}
    seen_torn: list[str] = []
    stop = threading.Event()

    def reader() -> None:  # what `slamcourse check` / `watch` would read meanwhile
        while not stop.is_set():
            text = path.read_bytes().decode("utf-8", "replace")
            if text not in whole:
                seen_torn.append(text)

    outcomes: list[tuple[str, int, Any]] = []
    lock = threading.Lock()

    def post(source: str) -> None:
        while True:  # the server runs a few checks at once and refuses more (503): retry
            status, data = client.request(
                "POST", f"/api/code/{EX}", {"source": source, "overwrite": True}
            )
            if status != 503:
                break
            time.sleep(0.5)
        with lock:
            outcomes.append((source, status, data))

    watcher = threading.Thread(target=reader)
    watcher.start()
    try:
        for _ in range(4):
            threads = [threading.Thread(target=post, args=(src,)) for src in [CORRECT, WRONG] * 3]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
    finally:
        stop.set()
        watcher.join()

    assert len(outcomes) == 24
    wrong_verdicts = []
    for source, status, data in outcomes:
        assert status == 200, data
        expected = "passed" if source is CORRECT else "failed"
        if data["status"] != expected:
            wrong_verdicts.append((expected, data["status"], data["feedback"][:80]))
    assert not wrong_verdicts, (
        f"{len(wrong_verdicts)} of 24 graded another source: {wrong_verdicts}"
    )
    assert not seen_torn, f"a half-written file was read ({len(seen_torn)} times)"
    assert path.read_text(encoding="utf-8") in (CORRECT, WRONG)


def test_check_with_a_stale_base_does_not_overwrite(live: Any) -> None:
    """The page sends the hash of the text it loaded; an edit on disk since is a conflict."""
    client = Client(live)
    path = code_file(live)
    status, shown = client.request("GET", f"/api/exercise/{EX}")
    assert status == 200
    edited = "# edited in my own editor\n" + CORRECT
    path.write_text(edited, encoding="utf-8")
    status, data = client.request(
        "POST", f"/api/code/{EX}", {"source": WRONG, "based_on": shown.get("source_hash")}
    )
    assert path.read_text(encoding="utf-8") == edited, "the edit on disk was overwritten"
    assert shown["source"] != edited and shown["source_hash"]
    assert status == 409, data
    conflict = data["conflict"]
    assert "range_bearing.py changed on disk" in conflict["message"]
    assert conflict["disk_source"] == edited
    assert conflict["file"] == str(path)
    # the learner chose "keep mine": the same text, based on the version now on disk
    status, data = client.request(
        "POST", f"/api/code/{EX}", {"source": WRONG, "based_on": conflict["disk_hash"]}
    )
    assert status == 200 and data["status"] == "failed"
    assert path.read_text(encoding="utf-8") == WRONG
    status, again = client.request("GET", f"/api/exercise/{EX}")
    assert data["file_hash"] == again["source_hash"] != conflict["disk_hash"]


# ------------------------------------------------------------------ in the browser


def _settled(
    page: Any, state: str = ":is(.is-conflict, .is-passed, .is-failed, .is-error)"
) -> None:
    fb = page.locator("#ex-basics--range-bearing .feedback")
    try:
        page.locator(f"#ex-basics--range-bearing .feedback{state}").wait_for(timeout=30_000)
    except Exception as exc:
        raise AssertionError(f"feedback never became {state}: {fb.inner_text()!r}") from exc


@pytest.mark.browser
def test_browser_check_after_an_edit_on_disk_shows_the_conflict(page: Any, live: Any) -> None:
    path = code_file(live)
    path.write_text(WRONG, encoding="utf-8")
    page.goto(live.base + "chapter/basics")
    page.wait_for_selector("html[data-ready='1']")
    sec = page.locator(f'section[data-exercise="{EX}"]')
    fb = sec.locator("[data-feedback]")
    # the learner edits the file in their own editor after the page loaded it
    on_disk = "# edited on disk\n" + CORRECT
    path.write_text(on_disk, encoding="utf-8")
    sec.locator("[data-check]").click()
    _settled(page)
    assert path.read_text(encoding="utf-8") == on_disk, "Check overwrote the edit on disk"
    assert "is-conflict" in (fb.get_attribute("class") or "")
    assert "range_bearing.py changed on disk" in fb.inner_text()
    # the page's text is still there, and nothing was graded
    assert "return 0, 0" in sec.locator(".cm-content").inner_text()
    # "load the file's version": the editor shows the disk's text; the file is untouched
    sec.locator("[data-load-disk]").click()
    assert "# edited on disk" in sec.locator(".cm-content").inner_text()
    assert path.read_text(encoding="utf-8") == on_disk
    sec.locator("[data-check]").click()
    _settled(page, ".is-passed")
    assert path.read_text(encoding="utf-8") == on_disk

    # a second edit on disk; this time the learner keeps the page's text
    path.write_text(WRONG, encoding="utf-8")
    sec.locator("[data-check]").click()
    _settled(page, ".is-conflict")
    assert path.read_text(encoding="utf-8") == WRONG
    sec.locator("[data-keep-mine]").click()
    _settled(page, ".is-passed")
    assert path.read_text(encoding="utf-8") == on_disk


# ------------------------------------------------------------------ the save itself


def test_save_source_is_conditional_atomic_and_keeps_the_file(tmp_path: Path) -> None:
    from slamcourse.watch import signature, wait_for_change
    from slamcourse.workspace import read_source_and_hash, save_source

    target = tmp_path / "mine" / "attempt.py"
    target.parent.mkdir()
    target.write_text("v1\n", encoding="utf-8")
    target.chmod(0o640)
    link = tmp_path / "attempt.py"
    link.symlink_to(target)  # the learner keeps the file elsewhere and links it in
    text, loaded = read_source_and_hash(link)
    assert text == "v1\n" and loaded.startswith("sha256:")

    before = signature(link)
    saved = save_source(link, "v2\n", based_on=loaded)
    assert saved.written and saved.text == "v2\n"
    assert wait_for_change(link, since=before, timeout=5) != "timeout"  # `watch` sees it
    assert link.is_symlink() and target.read_text(encoding="utf-8") == "v2\n"
    assert target.stat().st_mode & 0o777 == 0o640
    assert [p.name for p in target.parent.iterdir()] == ["attempt.py"]  # no temporary left

    target.write_text("edited elsewhere\n", encoding="utf-8")
    stale = save_source(link, "v3\n", based_on=saved.hash)
    assert not stale.written and stale.text == "edited elsewhere\n"
    assert target.read_text(encoding="utf-8") == "edited elsewhere\n"
    assert save_source(link, "v3\n", based_on=stale.hash).written
    assert save_source(link, "v4\n", based_on=None).written  # the learner chose to overwrite
    assert target.read_text(encoding="utf-8") == "v4\n"
