"""The browser face: a Flask app that renders what the engine returns.

Every rule (grading, practice on the canonical variant, the explanation locked until solved,
hint nudges, what counts as an attempt) lives in :class:`slamcourse.engine.Engine`; this module
only turns its results into HTML and JSON. Security model (docs/architecture.md, "Browser"):

- a random token is required on every request that reads progress or runs code: given once as
  ``?token=`` (then dropped from the address), kept in an HttpOnly SameSite=Strict cookie;
- the Host header must name this server (``127.0.0.1:PORT`` / ``localhost:PORT``), which stops
  DNS rebinding; a POST must come from this origin and carry JSON, which stops cross-site posts;
- behind a proxy that authenticates the learner first (jupyter-server-proxy under
  JupyterHub: docs/deploying.md), the proxy adds the token as the ``X-Slamcourse-Token``
  header to every request it forwards; such a request may name any host (the hub's), may be
  mounted under the prefix the proxy names (``X-Forwarded-Prefix``: links, static files and
  API calls follow it) and a POST must come from the origin of that host. A request without
  the header still needs the token, whoever can reach the port;
- bodies are limited to 256 KiB; every learner text reaches the page escaped (Jinja autoescape,
  Markdown with raw HTML disabled, ``textContent`` in the script); a strict CSP forbids inline
  scripts; learner code only ever runs through the engine's sandbox.
"""

from __future__ import annotations

import hmac
import re
import secrets
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any
from urllib.parse import urlencode, urlsplit

from flask import Flask, Response, abort, g, jsonify, redirect, render_template, request, url_for
from markupsafe import Markup

from slamcourse.engine import STATUS_MARK, STATUS_WORD, FileChanged, Locked
from slamcourse.errors import SlamcourseError
from slamcourse.web.markdown import to_html, to_inline_html

if TYPE_CHECKING:
    from werkzeug.wrappers import Response as BaseResponse

    from slamcourse.engine import Engine, Prompt, Result

MAX_BODY = 256 * 1024
MAX_ANSWER = 64 * 1024
CSP = (
    "default-src 'none'; script-src 'self'; style-src 'self' 'nonce-{nonce}'; "
    "img-src 'self' data:; font-src 'self'; connect-src 'self'; base-uri 'none'; "
    "form-action 'self'; frame-ancestors 'none'"
)
"""The page's policy. The per-response style nonce is for the one ``<style>`` element the code
editor (CodeMirror) injects; no script runs inline."""


PROXY_HEADER = "X-Slamcourse-Token"
"""The header a trusted proxy (jupyter-server-proxy) adds, holding the server's token."""
_PREFIX = re.compile(r"^(/[A-Za-z0-9._~%!$&'()*+,;=:@-]+)*/?$")


class ProxyPrefix:
    """WSGI middleware: a request that carries the token in :data:`PROXY_HEADER` came
    through the learner's own proxy, so its ``X-Forwarded-Prefix`` (where the proxy mounts
    this app, e.g. ``/user/ada/slamcourse``) becomes the script root every URL is built on.
    Without the token the header is ignored."""

    def __init__(self, app: Any, token: str) -> None:
        self.app = app
        self.token = token

    def __call__(self, environ: dict[str, Any], start_response: Any) -> Any:
        given = environ.get("HTTP_" + PROXY_HEADER.upper().replace("-", "_"))
        prefix = environ.get("HTTP_X_FORWARDED_PREFIX", "")
        if given is not None and _same(given, self.token) and prefix and _PREFIX.match(prefix):
            environ["SCRIPT_NAME"] = prefix.rstrip("/")
        return self.app(environ, start_response)


def anchor(exercise_id: str) -> str:
    """The HTML id of an exercise's section: ``basics/distance`` → ``ex-basics--distance``."""
    return "ex-" + exercise_id.replace("/", "--")


def create_app(engine: Engine, *, token: str, hosts: Iterable[str]) -> Flask:
    """The app for one learner's ``engine``. ``hosts``: the Host header values accepted
    (e.g. ``127.0.0.1:8123`` and ``localhost:8123``)."""
    app = Flask(__name__, static_folder="static", template_folder="templates")
    app.wsgi_app = ProxyPrefix(app.wsgi_app, token)  # type: ignore[method-assign]
    app.config.update(MAX_CONTENT_LENGTH=MAX_BODY, JSON_SORT_KEYS=False)
    app.json.ensure_ascii = False  # type: ignore[attr-defined]
    allowed = frozenset(hosts)
    origins = frozenset(f"http://{h}" for h in allowed)
    cookie = "slamcourse_token_" + "".join(c for c in sorted(allowed)[0] if c.isalnum())

    app.jinja_env.globals.update(
        md=to_html, md_inline=to_inline_html, anchor=anchor, mark=STATUS_MARK, word=STATUS_WORD
    )

    def is_api() -> bool:
        return request.path.startswith("/api/")

    def refuse(status: int, message: str) -> BaseResponse:
        if is_api() or request.method != "GET":
            return Response(_json({"error": message}), status=status, mimetype="application/json")
        html = render_template("refused.html", message=message)
        return Response(html, status=status, mimetype="text/html")

    def style_nonce() -> str:
        if "style_nonce" not in g:
            g.style_nonce = secrets.token_urlsafe(16)
        nonce: str = g.style_nonce
        return nonce

    app.jinja_env.globals["style_nonce"] = style_nonce

    @app.before_request
    def guard() -> BaseResponse | None:
        proxied = request.headers.get(PROXY_HEADER)
        if proxied is not None:
            # forwarded by the learner's proxy, which authenticated them: the token is in the
            # header, the host is the hub's, the origin of a POST must be that host's
            if not _same(proxied, token):
                return refuse(403, f"Wrong token in {PROXY_HEADER}.")
            if request.method == "POST":
                return same_origin(lambda origin: urlsplit(origin).netloc == request.host)
            return None
        if request.host not in allowed:
            return refuse(400, "This server answers only to its own address (Host header).")
        if request.endpoint == "static":
            return None
        given = request.args.get("token")
        if given is not None:
            if not _same(given, token):
                return refuse(403, "Wrong token: open the address `slamcourse serve` printed.")
            if request.method == "GET":
                rest = {k: v for k, v in request.args.items() if k != "token"}
                root = request.script_root
                target = root + request.path + ("?" + urlencode(rest) if rest else "")
                resp = redirect(target, code=303)
                resp.set_cookie(cookie, token, httponly=True, samesite="Strict", path=root + "/")
                return resp
        elif not _same(request.cookies.get(cookie, ""), token):
            return refuse(
                403, "This page needs the token: open the address `slamcourse serve` printed."
            )
        if request.method == "POST":
            return same_origin(lambda origin: origin in origins)
        return None

    def same_origin(allowed_origin: Callable[[str], bool]) -> BaseResponse | None:
        """A POST must come from this page: its Origin (when sent) and Sec-Fetch-Site say so,
        and it carries JSON (which a cross-site form cannot send)."""
        origin = request.headers.get("Origin")
        fetch_site = request.headers.get("Sec-Fetch-Site")
        if origin is not None and not allowed_origin(origin):
            return refuse(403, "Cross-site request refused (Origin).")
        if fetch_site is not None and fetch_site not in ("same-origin", "none"):
            return refuse(403, "Cross-site request refused (Sec-Fetch-Site).")
        if not request.is_json:
            return refuse(415, "Send the answer as JSON (Content-Type: application/json).")
        return None

    @app.after_request
    def headers(resp: Response) -> Response:
        resp.headers["Content-Security-Policy"] = CSP.format(nonce=style_nonce())
        resp.headers["X-Content-Type-Options"] = "nosniff"
        resp.headers["Referrer-Policy"] = "no-referrer"
        resp.headers["X-Frame-Options"] = "DENY"
        resp.headers["Cross-Origin-Opener-Policy"] = "same-origin"
        if request.endpoint != "static":
            resp.headers["Cache-Control"] = "no-store"
        return resp

    @app.errorhandler(413)
    def too_large(_: Exception) -> BaseResponse:
        return refuse(413, f"Request too large (the limit is {MAX_BODY // 1024} KiB).")

    @app.errorhandler(Locked)
    def locked(exc: Locked) -> BaseResponse:
        return refuse(403, str(exc))

    @app.errorhandler(FileChanged)
    def file_changed(exc: FileChanged) -> BaseResponse:
        body = {"error": str(exc), "conflict": exc.to_dict()}
        return Response(_json(body), status=409, mimetype="application/json")

    @app.errorhandler(SlamcourseError)
    def usage(exc: SlamcourseError) -> BaseResponse:
        return refuse(400, str(exc))

    # ------------------------------------------------------------------ pages
    def sidebar(current_chapter: str | None) -> dict[str, Any]:
        return {"summary": engine.summary(), "current_chapter": current_chapter}

    @app.get("/")
    def home() -> str:
        nxt = engine.next_exercise()
        return render_template(
            "home.html",
            chapters=engine.chapters(),
            next_title=engine.exercise(nxt).title if nxt else None,
            next_url=_exercise_url(engine, nxt) if nxt else None,
            **sidebar(None),
        )

    @app.get("/next")
    def next_page() -> BaseResponse:
        nxt = engine.next_exercise()
        if nxt is None:
            return redirect(url_for("home"), code=303)
        return redirect(_exercise_url(engine, nxt), code=303)

    @app.get("/chapter/<chapter_id>")
    def chapter(chapter_id: str) -> str:
        infos = {c.id: c for c in engine.chapters()}
        if chapter_id not in infos:
            abort(404)
        ids = list(infos)
        pos = ids.index(chapter_id)
        segments = []
        for seg in engine.chapter_segments(chapter_id):
            view = _exercise_view(engine, seg.exercise_id) if seg.exercise_id else None
            segments.append({"html": to_html(seg.markdown), "exercise": view})
        return render_template(
            "chapter.html",
            chapter=infos[chapter_id],
            segments=segments,
            prev=infos[ids[pos - 1]] if pos > 0 else None,
            next=infos[ids[pos + 1]] if pos + 1 < len(ids) else None,
            **sidebar(chapter_id),
        )

    @app.get("/plot/<path:exercise_id>")
    def plot(exercise_id: str) -> Response:
        canonical = request.args.get("canonical") == "1"
        svg = _plot(engine, engine.pose(exercise_id, canonical=canonical))
        if svg is None:
            abort(404)
        return Response(svg, mimetype="image/svg+xml")

    # ------------------------------------------------------------------ API
    @app.get("/api/summary")
    def api_summary() -> Response:
        return jsonify(engine.summary())

    @app.get("/api/next")
    def api_next() -> Response:
        nxt = engine.next_exercise()
        return jsonify({"exercise": nxt, "url": _exercise_url(engine, nxt) if nxt else None})

    @app.get("/api/exercise/<path:exercise_id>")
    def api_exercise(exercise_id: str) -> Response:
        canonical = request.args.get("canonical") == "1"
        prompt = engine.pose(exercise_id, canonical=canonical)
        data = prompt.to_dict()
        data["text_html"] = str(to_html(prompt.text))
        data["plot_svg"] = _plot(engine, prompt)
        if prompt.kind == "code":  # the editor's text and the base a check sends back
            data["source"], data["source_hash"] = engine.code_source(exercise_id)
        return jsonify(data)

    @app.post("/api/answer/<path:exercise_id>")
    def api_answer(exercise_id: str) -> Response:
        body = _body()
        answer = body.get("answer")
        if not isinstance(answer, str) or len(answer) > MAX_ANSWER:
            raise _BadRequest("`answer` must be a text of at most 64 KiB")
        result = engine.submit(exercise_id, answer, canonical=bool(body.get("canonical")))
        return jsonify(_result_json(engine, result))

    @app.post("/api/code/<path:exercise_id>")
    def api_code(exercise_id: str) -> Response:
        body = _body()
        source, based_on = body.get("source"), body.get("based_on")
        if not isinstance(source, str) or len(source) > MAX_ANSWER:
            raise _BadRequest("`source` must be a text of at most 64 KiB")
        if based_on is not None and not isinstance(based_on, str):
            raise _BadRequest("`based_on` must be the content hash the page received")
        # The page's editor and the learner's workspace file are one file: the terminal's
        # `slamcourse check ID` and `watch` grade what was last checked here. The engine saves
        # only over the version the page loaded (else FileChanged: 409) and grades `source`.
        result, file_hash = engine.submit_edit(
            exercise_id, source, based_on=based_on, overwrite=body.get("overwrite") is True
        )
        return jsonify({**_result_json(engine, result), "file_hash": file_hash})

    @app.post("/api/hint/<path:exercise_id>")
    def api_hint(exercise_id: str) -> Response:
        _body()
        hint = engine.hint(exercise_id)
        data = hint.to_dict()
        data["hint_html"] = str(to_html(hint.text)) if hint.text else None
        return jsonify(data)

    @app.post("/api/giveup/<path:exercise_id>")
    def api_giveup(exercise_id: str) -> Response:
        _body()
        text = engine.give_up(exercise_id)
        return jsonify(
            {
                "plot_svg": _plot(engine, engine.pose(exercise_id)),
                "explanation": text,
                "explanation_html": str(to_html(text)),
                "exercise_status": engine.state(exercise_id).status,
                "summary": engine.summary(),
            }
        )

    @app.get("/api/explanation/<path:exercise_id>")
    def api_explanation(exercise_id: str) -> Response:
        text = engine.explanation(exercise_id)
        return jsonify({"explanation": text, "explanation_html": str(to_html(text))})

    @app.errorhandler(_BadRequest)
    def bad_request(exc: _BadRequest) -> BaseResponse:
        return refuse(400, str(exc))

    return app


class _BadRequest(Exception):
    pass


def _json(data: Any) -> str:
    import json

    return json.dumps(data, ensure_ascii=False)


def _same(given: str, token: str) -> bool:
    """Constant-time comparison of a token from the address or the cookie (any text, even
    non-ASCII or a lone surrogate, which ``compare_digest`` refuses as ``str``)."""
    return hmac.compare_digest(given.encode("utf-8", "surrogatepass"), token.encode("utf-8"))


def _body() -> dict[str, Any]:
    import json

    # past MAX_BODY, with a length or chunked, get_data raises RequestEntityTooLarge (413)
    raw = request.get_data(cache=True)
    try:
        data = json.loads(raw)
    except (ValueError, RecursionError):  # not JSON, not UTF-8, or nested too deeply
        data = None
    if not isinstance(data, dict):
        raise _BadRequest("the request body must be a JSON object")
    return data


def _exercise_url(engine: Engine, exercise_id: str) -> str:
    chapter = next(c.id for c in engine.chapters() if exercise_id in c.exercise_ids)
    return url_for("chapter", chapter_id=chapter) + "#" + anchor(exercise_id)


def _plot(engine: Engine, prompt: Prompt) -> str | None:
    """The exercise's picture; one that shows the answer only once the learner's own exercise
    is solved or given up (engine state), never for a pending one."""
    from slamcourse.plots.registry import plot_for

    spec = engine.exercise(prompt.exercise_id)
    solved = engine.state(prompt.exercise_id).status != "pending"
    return plot_for(prompt.exercise_id, spec.tags, dict(prompt.variant.params), solved=solved)


def _exercise_view(engine: Engine, exercise_id: str) -> dict[str, Any]:
    """What the chapter template needs to draw one exercise (all of it from the engine)."""
    prompt = engine.pose(exercise_id)
    data = prompt.to_dict()
    spec = engine.exercise(exercise_id)
    explanation = None
    if data["status"] != "pending":
        explanation = engine.explanation(exercise_id)
    source = source_hash = None
    if data["kind"] == "code":
        source, source_hash = engine.code_source(exercise_id)
    svg = _plot(engine, prompt)
    return {
        **data,
        "anchor": anchor(exercise_id),
        "has_variants": spec.has_variants,
        "text_html": to_html(prompt.text),
        "how_html": to_html(prompt.how_to_answer),
        "hints_html": [to_html(h) for h in data["hints"]["shown"]],
        "explanation_html": to_html(explanation) if explanation else None,
        "source": source,
        "source_hash": source_hash,
        "plot": Markup(svg) if svg else None,
    }


def _result_json(engine: Engine, result: Result) -> dict[str, Any]:
    data = result.to_dict()
    data["feedback_html"] = str(to_html(data["feedback"]))
    data["explanation_html"] = str(to_html(data["explanation"])) if data["explanation"] else None
    data["nudge_html"] = str(to_html(data["nudge"])) if data["nudge"] else None
    step = engine.next_step()  # the terminal's `next` asks the same after an answer
    data["summary"] = engine.summary(step)
    if result.verdict.passed and not result.practice:
        data["plot_svg"] = _plot(engine, engine.pose(result.exercise_id))
    nxt = step.exercise_id
    moved = nxt is not None and nxt != result.exercise_id
    data["next_url"] = _exercise_url(engine, nxt) if moved and nxt else None
    data["next_note_html"] = str(to_inline_html(step.note)) if moved and step.note else None
    return data
