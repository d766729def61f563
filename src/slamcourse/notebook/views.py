"""What the notebook face displays: the engine's results as HTML (math as ``$…$`` for the
notebook's MathJax) and as plain text.

Every view is data the engine returned, drawn; no view decides anything (what counts, what is
shown when: :class:`slamcourse.engine.Engine`). Each has ``_repr_html_`` and a plain-text
``repr``, and ``_repr_mimebundle_`` adds ``{"slamcourse": {...}}`` output metadata (who the
learner is, the course, and for a checked answer the exercise and the answer text graded),
which the batch grader reads from a handed-in notebook (:mod:`slamcourse.notebook.cells`).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from slamcourse.notebook.cells import CHECK, META, magic_line
from slamcourse.notebook.markup import escape, to_html, to_inline_html, to_text

if TYPE_CHECKING:
    from slamcourse.engine import Hint, Prompt, Result

STYLE = """<style>
.slamcourse-nb{border-left:4px solid #5b7db1;padding:.4em .9em;margin:.3em 0;line-height:1.45}
.slamcourse-nb .sc-kicker{color:#666;font-size:.85em;margin:0}
.slamcourse-nb .sc-title{font-size:1.15em;font-weight:600;margin:.1em 0 .4em}
.slamcourse-nb .sc-badge{font-size:.8em;font-weight:normal;color:#555;margin-left:.6em}
.slamcourse-nb .sc-verdict{font-weight:700;margin:.2em 0}
.slamcourse-nb.sc-passed{border-color:#2e7d32}.slamcourse-nb.sc-passed .sc-verdict{color:#2e7d32}
.slamcourse-nb.sc-failed,.slamcourse-nb.sc-timeout{border-color:#c62828}
.slamcourse-nb.sc-failed .sc-verdict,.slamcourse-nb.sc-timeout .sc-verdict{color:#c62828}
.slamcourse-nb.sc-invalid,.slamcourse-nb.sc-notice{border-color:#b8860b}
.slamcourse-nb.sc-error{border-color:#8e24aa}
.slamcourse-nb .sc-muted{color:#666;font-size:.9em}
.slamcourse-nb table.sc-tests td,.slamcourse-nb table.sc-tests th{text-align:left;
vertical-align:top;padding:.15em .6em .15em 0}
.slamcourse-nb figure{margin:.5em 0}.slamcourse-nb svg{max-width:100%;height:auto}
.slamcourse-nb .sc-explanation{border-top:1px solid #ddd;margin-top:.6em;padding-top:.3em}
</style>"""

VERDICT_LABEL = {
    "passed": "✓ Correct",
    "failed": "✗ Not yet",
    "invalid": "? Could not read that",
    "timeout": "⏱ Took too long",
    "error": "! Grader error",
}


def _code(text: str) -> str:
    return f"<code>{escape(text)}</code>"


class View(ABC):
    """A displayable result: HTML for a notebook, plain text for a console."""

    css_class = ""
    meta: dict[str, Any]

    @abstractmethod
    def html_body(self) -> str:
        """The view's HTML, inside the styled ``<div>`` that ``_repr_html_`` wraps it in."""

    @abstractmethod
    def text(self) -> str:
        """The same content as plain text (a console, a log)."""

    def _repr_html_(self) -> str:
        cls = f"slamcourse-nb {self.css_class}".strip()
        return f'{STYLE}<div class="{cls}">{self.html_body()}</div>'

    def _repr_mimebundle_(
        self, include: Any = None, exclude: Any = None
    ) -> tuple[dict[str, str], dict[str, Any]]:
        data = {"text/html": self._repr_html_(), "text/plain": self.text()}
        return data, {META: self.meta}

    def __repr__(self) -> str:
        return self.text()

    def __str__(self) -> str:
        return self.text()


# ------------------------------------------------------------------------------ an exercise


@dataclass(repr=False)
class ExerciseView(View):
    """An exercise posed (``show``): the prompt of the learner's variant, how to answer it in
    the notebook, its picture, the hints taken so far."""

    prompt: Prompt
    picture: str | None
    mark: str
    word: str
    meta: dict[str, Any] = field(default_factory=dict)

    @property
    def css_class(self) -> str:  # type: ignore[override]
        return f"sc-{'passed' if self.prompt.status == 'solved' else 'exercise'}"

    def _how_here(self) -> tuple[str, str]:
        """How to answer in a notebook, as (HTML, text)."""
        p = self.prompt
        if p.kind == "code":
            form = p.form
            sig = f"{form['function']}({', '.join(form['signature'])})"
            line = magic_line(p.exercise_id)
            return (
                f"<p>Write {_code(sig)} in a code cell whose first line is {_code(line)}, "
                "then run the cell: the cell is graded in the sandbox (and then defined "
                "here, so you can try it).</p>",
                f"Write {sig} in a code cell whose first line is `{line}`, then run it.",
            )
        call = f'{CHECK}("{p.exercise_id}", "your answer")'
        return (
            f"<p>Answer with {_code(call)}.</p>",
            f"Answer with {call}.",
        )

    def _form_html(self) -> str:
        form, kind = self.prompt.form, self.prompt.kind
        if kind in ("choice", "multi"):
            items = "".join(
                f"<li><strong>{escape(o['id'])})</strong> {to_inline_html(o['text'])}</li>"
                for o in form["options"]
            )
            return f'<ul class="sc-options">{items}</ul>'
        if kind == "order":
            items = "".join(
                f"<li><strong>{escape(o['id'])})</strong> {to_inline_html(o['text'])}</li>"
                for o in form["items"]
            )
            return f'<ul class="sc-options">{items}</ul>'
        if kind == "line":
            width = len(str(len(form["lines"])))
            listing = "\n".join(
                f"{i:>{width}}  {line}" for i, line in enumerate(form["lines"], start=1)
            )
            return f"<pre>{escape(listing)}</pre>"
        if kind == "code":
            starter = escape(form["starter"])
            return f"<details><summary>Starter</summary><pre>{starter}</pre></details>"
        return ""

    def _form_text(self) -> str:
        form, kind = self.prompt.form, self.prompt.kind
        if kind in ("choice", "multi", "order"):
            rows = form["options"] if kind != "order" else form["items"]
            return "\n".join(f"  {o['id']}) {to_text(o['text']).strip()}" for o in rows)
        if kind == "line":
            return "\n".join(f"  {i:>2}  {line}" for i, line in enumerate(form["lines"], 1))
        return ""

    def html_body(self) -> str:
        p = self.prompt
        index, count = p.position
        parts = [
            f'<p class="sc-kicker">Chapter {p.chapter_number} · {escape(p.chapter_title)} · '
            f"exercise {index} of {count} · {_code(p.exercise_id)}</p>",
            f'<p class="sc-title">{to_inline_html(p.title)}'
            f'<span class="sc-badge">{escape(self.mark)} {escape(self.word)}</span></p>',
            to_html(p.text),
        ]
        if self.picture:
            parts.append(f"<figure>{self.picture}</figure>")
        parts.append(self._form_html())
        if p.how_to_answer:
            parts.append(f'<div class="sc-muted">{to_html(p.how_to_answer)}</div>')
        parts.append(self._how_here()[0])
        if p.practice:
            parts.append(
                '<p class="sc-muted">The lesson\'s own numbers: practice, graded but never '
                "counted (your own variant is what counts).</p>"
            )
        if p.hints_shown:
            hints = "".join(f"<li>{to_html(h)}</li>" for h in p.hints_shown)
            parts.append(f"<p><strong>Hints</strong></p><ol>{hints}</ol>")
        tools = (
            [
                f"{_code(f'hint({p.exercise_id!r})')} for a hint ({len(p.hints_shown)} of "
                f"{p.hints_total} taken)"
            ]
            if p.hints_total
            else []
        )
        tools.append(f"{_code(f'explain({p.exercise_id!r})')} once solved or given up")
        parts.append(f'<p class="sc-muted">{"; ".join(tools)}. {self._attempts()}</p>')
        return "\n".join(x for x in parts if x)

    def _attempts(self) -> str:
        n = self.prompt.attempts
        return f"{n} attempt{'' if n == 1 else 's'} so far."

    def text(self) -> str:
        p = self.prompt
        index, count = p.position
        lines = [
            f"── {p.chapter_title} · exercise {index} of {count} [{p.exercise_id}]",
            f"{to_text(p.title).strip()}   {self.mark} {self.word}",
            to_text(p.text),
        ]
        form = self._form_text()
        if form:
            lines.append(form)
        if p.how_to_answer:
            lines.append(to_text(p.how_to_answer))
        lines.append(self._how_here()[1])
        if p.practice:
            lines.append("(the lesson's own numbers: practice, graded but never counted)")
        for i, h in enumerate(p.hints_shown, start=1):
            lines.append(f"Hint {i}: {to_text(h).strip()}")
        lines.append(self._attempts())
        return "\n".join(lines)


# ------------------------------------------------------------------------------ a verdict


@dataclass(repr=False)
class ResultView(View):
    """One graded answer: the verdict and what the engine's rules add (no attempt counted,
    practice, the nudge towards a hint, the explanation once passed)."""

    result: Result
    picture: str | None = None
    note: str | None = None  # the face's own remark (e.g. the cell raised when defined here)
    meta: dict[str, Any] = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        return self.result.passed

    @property
    def status(self) -> str:
        return self.result.verdict.status

    @property
    def css_class(self) -> str:  # type: ignore[override]
        return f"sc-{self.result.verdict.status}"

    def _remarks(self) -> list[str]:
        r, out = self.result, []
        if r.verdict.status in ("invalid", "error"):
            out.append("(no attempt counted)")
        elif r.practice:
            out.append(
                "(practice on the lesson's own numbers: graded, not counted; your own "
                "variant is what counts)"
            )
        if r.nudge:
            out.append(f"{r.nudge} Run `hint({r.exercise_id!r})`.")
        return out

    def _status_line(self) -> str:
        r = self.result
        word = {"solved": "solved", "given_up": "given up"}.get(r.exercise_status, "open")
        n = r.attempts
        return f"{r.exercise_id}: {word}, {n} attempt{'' if n == 1 else 's'}."

    def _tests_html(self) -> str:
        rows = []
        for t in self.result.tests:
            if "input" not in t:
                rows.append(f"<tr><td colspan=2>✓ {escape(t['name'])}</td></tr>")
                continue
            rows.append(f"<tr><th colspan=2>{escape(t['name'])} ({escape(t['status'])})</th></tr>")
            for key in ("input", "expected", "got"):
                if t.get(key) is not None:
                    rows.append(
                        f"<tr><td>{key}</td><td><pre>{escape(_show(t[key]))}</pre></td></tr>"
                    )
        return f'<table class="sc-tests">{"".join(rows)}</table>' if rows else ""

    def html_body(self) -> str:
        r = self.result
        parts = [
            f'<p class="sc-verdict">{escape(VERDICT_LABEL[r.verdict.status])}'
            f'<span class="sc-badge">{_code(r.exercise_id)}</span></p>',
            to_html(_capitalised(r.verdict.feedback)),
            self._tests_html(),
        ]
        if self.note:
            parts.append(f'<p class="sc-muted">{escape(self.note)}</p>')
        parts += [f'<p class="sc-muted">{to_inline_html(x)}</p>' for x in self._remarks()]
        if self.picture:
            parts.append(f"<figure>{self.picture}</figure>")
        if r.explanation:
            parts.append(
                f'<div class="sc-explanation"><strong>Explanation</strong>'
                f"{to_html(r.explanation)}</div>"
            )
        parts.append(f'<p class="sc-muted">{escape(self._status_line())}</p>')
        return "\n".join(x for x in parts if x)

    def text(self) -> str:
        r = self.result
        lines = [VERDICT_LABEL[r.verdict.status], to_text(_capitalised(r.verdict.feedback))]
        for t in r.tests:
            if "input" in t:
                lines.append(f"{t['name']}: input {_show(t.get('input'))}")
                lines.append(f"  expected {_show(t.get('expected'))}, got {_show(t.get('got'))}")
        if self.note:
            lines.append(self.note)
        lines += self._remarks()
        if r.explanation:
            lines += ["Explanation", to_text(r.explanation)]
        lines.append(self._status_line())
        return "\n".join(x for x in lines if x)


def _capitalised(text: str) -> str:
    from slamcourse.verdict import capitalised

    return capitalised(text)


def _show(value: Any) -> str:
    import json

    try:
        return json.dumps(value, ensure_ascii=False)
    except (TypeError, ValueError):
        return repr(value)


# ------------------------------------------------------------------------------ help


@dataclass(repr=False)
class HintView(View):
    exercise_id: str
    hint: Hint
    meta: dict[str, Any] = field(default_factory=dict)

    def html_body(self) -> str:
        h = self.hint
        if h.text is None:
            return f"<p>No more hints for {_code(self.exercise_id)} ({h.total} taken).</p>"
        return (
            f'<p class="sc-kicker">Hint {h.number} of {h.total} · {_code(self.exercise_id)}</p>'
            + to_html(h.text)
        )

    def text(self) -> str:
        h = self.hint
        if h.text is None:
            return f"No more hints for {self.exercise_id} ({h.total} taken)."
        return f"Hint {h.number} of {h.total} [{self.exercise_id}]\n{to_text(h.text)}"


@dataclass(repr=False)
class ExplanationView(View):
    exercise_id: str
    explanation: str
    picture: str | None = None
    meta: dict[str, Any] = field(default_factory=dict)

    def html_body(self) -> str:
        figure = f"<figure>{self.picture}</figure>" if self.picture else ""
        return (
            f'<p class="sc-kicker">Explanation · {_code(self.exercise_id)}</p>'
            + to_html(self.explanation)
            + figure
        )

    def text(self) -> str:
        return f"Explanation [{self.exercise_id}]\n{to_text(self.explanation)}"


@dataclass(repr=False)
class Notice(View):
    """What the engine refused, said as such (an unknown id, an explanation still locked):
    the learner's mistake is shown, never a traceback."""

    message: str
    meta: dict[str, Any] = field(default_factory=dict)
    css_class = "sc-notice"

    def html_body(self) -> str:
        return f"<p><strong>!</strong> {to_inline_html(self.message)}</p>"

    def text(self) -> str:
        return f"! {self.message}"


# ------------------------------------------------------------------------------ progress


@dataclass(repr=False)
class ProgressView(View):
    """Progress from the engine's summary (the terminal's ``status`` and the browser's
    sidebar show the same): every chapter, or one chapter's exercises."""

    summary: list[dict[str, Any]]
    marks: dict[str, str]
    words: dict[str, str]
    learner: str
    chapter: str | None = None
    meta: dict[str, Any] = field(default_factory=dict)

    def _rows(self) -> list[dict[str, Any]]:
        if self.chapter is None:
            return self.summary
        return [ch for ch in self.summary if ch["id"] == self.chapter]

    def _shown(self, ex: dict[str, Any]) -> str:
        return "skipped" if ex["status"] == "pending" and ex["skipped"] else str(ex["status"])

    def html_body(self) -> str:
        solved = sum(ch["solved"] for ch in self.summary)
        total = sum(ch["total"] for ch in self.summary)
        parts = [
            f'<p class="sc-kicker">Progress of {escape(self.learner)}: {solved}/{total} '
            "solved in all</p>"
        ]
        for ch in self._rows():
            head = (
                f"{ch['number']}. {to_inline_html(ch['title'])} "
                f'<progress max="{ch["total"]}" value="{ch["solved"]}"></progress> '
                f"{ch['solved']}/{ch['total']}"
            )
            if self.chapter is None:
                parts.append(f"<div>{head}</div>")
                continue
            items = "".join(
                f"<li>{escape(self.marks[self._shown(ex)])} {to_inline_html(ex['title'])} "
                f'<span class="sc-muted">{_code(ex["id"])} · {escape(self.words[self._shown(ex)])}'
                f"</span></li>"
                for ex in ch["exercises"]
            )
            parts.append(f'<p class="sc-title">{head}</p><ul style="list-style:none">{items}</ul>')
        return "\n".join(parts)

    def text(self) -> str:
        solved = sum(ch["solved"] for ch in self.summary)
        total = sum(ch["total"] for ch in self.summary)
        lines = [f"Progress of {self.learner}: {solved}/{total} solved in all"]
        for ch in self._rows():
            lines.append(f"{ch['number']:>2}. {ch['title']}  {ch['solved']}/{ch['total']}")
            if self.chapter is not None:
                for ex in ch["exercises"]:
                    shown = self._shown(ex)
                    lines.append(f"    {self.marks[shown]} {ex['id']}  {self.words[shown]}")
        return "\n".join(lines)
