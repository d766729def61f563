"""The command line: the one place that prints, reads input and exits.

Every command is a function ``cmd_<name>(args, out) -> exit code``. Library code raises
:class:`~slamcourse.errors.SlamcourseError`; :func:`main` turns it into ``Error: …`` on stderr
and the error's exit code. Heavy modules are imported inside commands, so ``check`` starts fast.
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import sys
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, TextIO

from slamcourse import __version__
from slamcourse.errors import EXIT_USAGE, SlamcourseError, UsageError

if TYPE_CHECKING:
    from slamcourse.course.model import Variant
    from slamcourse.engine import Engine
    from slamcourse.verdict import Verdict

COMMANDS = ":hint  :skip  :giveup  :quit"


# ------------------------------------------------------------------------------ output


class Out:
    """Where the CLI writes: colour and width decided once from the stream and environment."""

    def __init__(self, stream: TextIO, *, no_color: bool = False) -> None:
        self.stream = stream
        self.color = False if no_color else _use_color(stream)
        self.width = _width(stream)

    def line(self, text: str = "") -> None:
        self.stream.write(text + "\n")
        self.stream.flush()

    def style(self, text: str, *names: str) -> str:
        if not self.color:
            return text
        from slamcourse.render.terminal import style

        return style(text, *names, color=True)

    def markdown(self, text: str) -> None:
        from slamcourse.render.terminal import render_markdown

        self.line(render_markdown(text, width=self.width, color=self.color))

    def json(self, data: Any) -> None:
        self.line(json.dumps(data, indent=2, ensure_ascii=False))


def _width(stream: TextIO) -> int:
    """Columns to wrap at: $COLUMNS, else the terminal's width, else 80; within [40, 100]."""
    try:
        columns = int(os.environ.get("COLUMNS", "0"))
    except ValueError:
        columns = 0
    if not columns:
        try:
            columns = os.get_terminal_size(stream.fileno()).columns
        except (AttributeError, OSError, ValueError):
            columns = 80
    return max(40, min(columns, 100))


def _use_color(stream: TextIO) -> bool:
    if os.environ.get("NO_COLOR") or os.environ.get("TERM") == "dumb":
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return bool(getattr(stream, "isatty", lambda: False)())


VERDICT_STYLE = {
    "passed": ("bold", "green"),
    "failed": ("bold", "red"),
    "invalid": ("bold", "yellow"),
    "timeout": ("bold", "red"),
    "error": ("bold", "magenta"),
}


def print_verdict(out: Out, verdict: Verdict) -> None:
    label = {
        "passed": "✓ passed",
        "failed": "✗ not yet",
        "invalid": "? unreadable",
        "timeout": "⏱ timeout",
        "error": "! grader error",
    }[verdict.status]
    out.line(f"{out.style(label, *VERDICT_STYLE[verdict.status])}  {_math(verdict.feedback)}")
    if verdict.status == "invalid":
        out.line(out.style("  (no attempt counted)", "dim"))


# ------------------------------------------------------------------------------ helpers


def _math(text: str) -> str:
    """Inline ``$…$`` math in short messages, as Unicode (the renderer loads only when needed)."""
    if "$" not in text:
        return text
    import re

    from slamcourse.render.math import latex_to_unicode

    return re.sub(r"\$([^$]+)\$", lambda m: latex_to_unicode(m.group(1)), text)


def _engine(args: argparse.Namespace, *, with_progress: bool = True) -> Engine:
    from slamcourse.engine import Engine

    return Engine.open(args.course, with_progress=with_progress)


def _variant(engine: Engine, args: argparse.Namespace, exercise_id: str) -> Variant:
    return engine.variant(
        exercise_id, canonical=getattr(args, "canonical", False), seed=getattr(args, "seed", None)
    )


def _target(engine: Engine, given: str | None) -> str:
    if given:
        engine.exercise(given)
        return given
    current = engine.next_exercise()
    if current is None:
        raise UsageError("every exercise is done; name one (slamcourse list shows them)")
    return current


def _show_prompt(
    out: Out, engine: Engine, exercise_id: str, variant: Variant, *, context: bool
) -> None:
    prompt = engine.prompt(exercise_id, variant)
    index, count = prompt.position
    out.line(
        out.style(f"── {prompt.chapter_title} · exercise {index} of {count} ", "dim")
        + out.style(f"[{exercise_id}]", "dim")
    )
    if context:
        prose = engine.context(exercise_id)
        if prose:
            out.markdown(prose)
            out.line()
    out.line(out.style(prompt.title, "bold", "cyan"))
    out.markdown(prompt.markdown)
    if prompt.how_to_answer:
        import textwrap

        width = getattr(out, "width", 80)
        for row in textwrap.wrap(_math(prompt.how_to_answer), width=width):
            out.line(out.style(row, "dim"))
    if variant.seed == 0 and engine.exercise(exercise_id).has_variants:
        out.line(out.style("(canonical variant: the lesson's own numbers)", "dim"))


# ------------------------------------------------------------------------------ commands


def cmd_next(args: argparse.Namespace, out: Out) -> int:
    """The interactive learner loop (rustlings-style)."""
    with _engine(args) as engine:
        while True:
            exercise_id = engine.next_exercise()
            if exercise_id is None:
                out.line(
                    out.style("Every exercise is solved or given up. Well done!", "bold", "green")
                )
                out.line("`slamcourse list` shows them all; `slamcourse reset ID` opens one again.")
                return 0
            engine.goto(exercise_id)
            if not _pose(out, engine, exercise_id, args):
                return 0


def _ask(out: Out, prompt: str) -> str | None:
    out.stream.write(prompt)
    out.stream.flush()
    line = sys.stdin.readline()
    return None if not line else line.rstrip("\n")


def _pose(out: Out, engine: Engine, exercise_id: str, args: argparse.Namespace) -> bool:
    """Pose one exercise until solved, skipped or given up. False when the learner quits."""
    variant = engine.variant(exercise_id)
    out.line()
    _show_prompt(out, engine, exercise_id, variant, context=not args.no_context)
    for text in engine.hints_shown(exercise_id, variant):
        out.line(out.style("hint: ", "yellow") + text)
    code_path = None
    if engine.exercise(exercise_id).kind == "code":
        code_path, fresh = engine.code_file(exercise_id)
        verb = "Starter written to" if fresh else "Your file:"
        out.line(f"{verb} {out.style(str(code_path), 'bold')}")
        out.line(out.style(f"Edit it, then press Enter to check it, or {COMMANDS}", "dim"))
    else:
        out.line(out.style(f"Type your answer, or {COMMANDS}", "dim"))
    failures = 0
    while True:
        answer = _ask(out, out.style("check> " if code_path else "answer> ", "bold"))
        if answer is None:  # end of input
            out.line()
            return False
        command = answer.strip().lower()
        if not command and code_path is None:
            continue
        if command in (":q", ":quit", "quit", "exit"):
            out.line("Progress saved. Run `slamcourse next` to continue.")
            return False
        if command in (":h", ":hint", "hint", "?"):
            hint = engine.hint(exercise_id, variant)
            if hint.text is None:
                out.line("No more hints. `:giveup` shows the worked explanation.")
            else:
                out.line(out.style(f"hint {hint.number}/{hint.total}: ", "yellow"))
                out.markdown(hint.text)
            continue
        if command in (":s", ":skip", "skip"):
            engine.skip(exercise_id)
            out.line("Skipped; it stays open for later.")
            return True
        if command in (":g", ":giveup", "giveup", "give up"):
            engine.give_up(exercise_id)
            out.line(out.style("Explanation", "bold"))
            out.markdown(engine.explanation(exercise_id, variant))
            return _continue(out)
        if code_path is not None:
            if command:
                out.line(f"Edit {code_path} in your editor; press Enter here to check it.")
                continue
            out.line(out.style("checking…", "dim"))
            verdict = engine.check_code(exercise_id, code_path)
        else:
            verdict = engine.check(exercise_id, answer, variant)
        print_verdict(out, verdict)
        if verdict.passed:
            out.line(out.style("Explanation", "bold"))
            out.markdown(engine.explanation(exercise_id, variant))
            return _continue(out)
        if verdict.counts_as_attempt:
            failures += 1
            if failures == 2 and engine.state(exercise_id).hints_shown == 0:
                out.line(out.style("Stuck? `:hint` shows a hint.", "dim"))


def _continue(out: Out) -> bool:
    answer = _ask(out, out.style("Enter for the next exercise, :quit to stop> ", "dim"))
    return answer is not None and answer.strip().lower() not in (":q", ":quit", "quit", "q")


def cmd_check(args: argparse.Namespace, out: Out) -> int:
    worker = _early_worker(args) if args.answer is None else None
    try:
        with _engine(args, with_progress=not args.no_record) as engine:
            if engine.exercise(args.exercise).kind == "code":
                return _check_code(args, out, engine, worker)
            return _check_answer(args, out, engine)
    finally:
        if worker is not None:
            worker.close()


def _check_answer(args: argparse.Namespace, out: Out, engine: Engine) -> int:
    if args.file is not None:
        raise UsageError(f"{args.exercise} is not a code exercise: use --answer TEXT")
    if args.answer is None:
        raise UsageError("give the answer with --answer TEXT (e.g. --answer 0.25)")
    variant = _variant(engine, args, args.exercise)
    verdict = engine.check(args.exercise, args.answer, variant, record=not args.no_record)
    if args.json:
        out.json(
            {
                "exercise": args.exercise,
                "variant": variant.seed,
                "answer": args.answer,
                "verdict": verdict.to_dict(),
            }
        )
    else:
        print_verdict(out, verdict)
    return verdict.exit_code


def _early_worker(args: argparse.Namespace) -> Any:
    """Start the sandbox worker before loading the course: without --answer this is a code
    check (or a usage error, and the worker is closed), and the worker's interpreter then
    imports numpy while this process loads the course and the reference code."""
    from slamcourse.errors import SandboxError
    from slamcourse.sandbox import Worker

    try:
        return Worker.spawn(require_isolation=args.require_isolation)
    except SandboxError:
        return None  # graded later, where the refusal becomes an `error` verdict


def _check_code(args: argparse.Namespace, out: Out, engine: Engine, worker: Any = None) -> int:
    from pathlib import Path

    if args.answer is not None:
        raise UsageError(
            f"{args.exercise} is a code exercise: grade a file with --file PATH "
            "(or leave it out to grade your workspace file)"
        )
    if args.file is not None:
        path = Path(args.file)
    else:
        path, _ = engine.code_file(args.exercise, create=False)
        if not path.exists():
            raise UsageError(
                f"no file {path} yet: `slamcourse next` (or `goto {args.exercise}` "
                "then `next`) writes the starter; or pass --file PATH"
            )
    verdict = engine.check_code(
        args.exercise,
        path,
        require_isolation=args.require_isolation,
        record=not args.no_record,
        worker=worker,
    )
    if args.json:
        out.json({"exercise": args.exercise, "file": str(path), "verdict": verdict.to_dict()})
    else:
        print_verdict(out, verdict)
    return verdict.exit_code


def cmd_show(args: argparse.Namespace, out: Out) -> int:
    with _engine(args, with_progress=not (args.canonical or args.seed is not None)) as engine:
        variant = _variant(engine, args, args.exercise)
        if args.json:
            prompt = engine.prompt(args.exercise, variant)
            out.json(
                {
                    "exercise": args.exercise,
                    "title": prompt.title,
                    "kind": prompt.kind,
                    "chapter": prompt.chapter_title,
                    "variant": variant.seed,
                    "prompt": prompt.markdown,
                    "how_to_answer": prompt.how_to_answer,
                }
            )
        else:
            _show_prompt(out, engine, args.exercise, variant, context=args.context)
        return 0


def cmd_hint(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        exercise_id = _target(engine, args.exercise)
        hint = engine.hint(exercise_id, engine.variant(exercise_id))
        if args.json:
            out.json(
                {
                    "exercise": exercise_id,
                    "number": hint.number,
                    "total": hint.total,
                    "hint": hint.text,
                }
            )
        elif hint.text is None:
            out.line(
                f"No more hints for {exercise_id} ({hint.total} shown). "
                f"`slamcourse giveup {exercise_id}` shows the explanation."
            )
        else:
            out.line(out.style(f"hint {hint.number}/{hint.total} for {exercise_id}:", "yellow"))
            out.markdown(hint.text)
        return 0


def cmd_explain(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        state = engine.state(args.exercise)
        if state.status == "pending":
            raise UsageError(
                f"{args.exercise} is not solved yet: solve it first, or "
                f"`slamcourse giveup {args.exercise}` to see the explanation"
            )
        text = engine.explanation(args.exercise, engine.variant(args.exercise))
        if args.json:
            out.json({"exercise": args.exercise, "explanation": text})
        else:
            out.markdown(text)
        return 0


def cmd_giveup(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        engine.give_up(args.exercise)
        out.markdown(engine.explanation(args.exercise, engine.variant(args.exercise)))
        return 0


def cmd_list(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        summary = engine.summary()
        if args.json:
            out.json(summary)
            return 0
        marks = {
            "solved": out.style("✓", "green"),
            "given_up": out.style("~", "yellow"),
            "pending": out.style("·", "dim"),
        }
        for ch in summary:
            out.line(
                out.style(f"{ch['number']:>2}. {ch['title']}", "bold")
                + f"  ({ch['solved']}/{ch['total']})"
            )
            for row in ch["exercises"]:
                pointer = out.style(" ← next", "cyan") if row["current"] else ""
                title = engine.exercise(row["id"]).title
                out.line(f"    {marks[row['status']]} {row['id']:<40} {title}{pointer}")
        return 0


def cmd_status(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        summary = engine.summary()
        solved = sum(ch["solved"] for ch in summary)
        total = sum(ch["total"] for ch in summary)
        nxt = engine.next_exercise()
        if args.json:
            out.json(
                {
                    "solved": solved,
                    "total": total,
                    "next": nxt,
                    "chapters": [
                        {k: ch[k] for k in ("id", "title", "solved", "total")} for ch in summary
                    ],
                }
            )
            return 0
        for ch in summary:
            width = 20
            filled = round(width * ch["solved"] / ch["total"]) if ch["total"] else 0
            bar = out.style("█" * filled, "green") + out.style("░" * (width - filled), "dim")
            out.line(f"{ch['number']:>2}. {ch['title']:<44} {bar} {ch['solved']}/{ch['total']}")
        out.line(f"Overall: {solved}/{total} solved." + (f" Next: {nxt}" if nxt else ""))
        return 0


def cmd_goto(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        engine.goto(args.exercise)
        out.line(f"`slamcourse next` will pose {args.exercise}.")
        return 0


def cmd_reset(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        if args.exercise is None and not args.yes:
            if not sys.stdin.isatty():
                raise UsageError("resetting all progress needs --yes when not interactive")
            reply = _ask(out, "Reset progress of every exercise? Attempts stay in the log. [y/N] ")
            if (reply or "").strip().lower() not in ("y", "yes"):
                out.line("Nothing reset.")
                return 0
        engine.reset(args.exercise)
        out.line(f"Reset {args.exercise or 'all exercises'}.")
        return 0


def cmd_validate(args: argparse.Namespace, out: Out) -> int:
    from slamcourse.course.locate import course_root
    from slamcourse.validate import validate_course

    root = course_root(args.path or args.course)
    report = validate_course(root, variants_per_exercise=args.variants)
    if args.json:
        out.json(
            {
                "ok": report.ok,
                "exercises": report.exercises,
                "variants": report.variants,
                "problems": [str(p) for p in report.problems],
            }
        )
    else:
        for p in report.problems:
            out.line(str(p))
        summary = (
            f"{report.exercises} exercises, {report.variants} variants checked: "
            f"{len(report.problems)} problem{'s' if len(report.problems) != 1 else ''}"
        )
        out.line(out.style(summary, "bold", "green" if report.ok else "red"))
    return 0 if report.ok else 1


def cmd_doctor(args: argparse.Namespace, out: Out) -> int:
    """What this machine offers the grader: isolation level, paths, versions."""
    import platform

    import numpy

    from slamcourse.course.locate import course_root
    from slamcourse.progress import default_home
    from slamcourse.sandbox import probe_isolation
    from slamcourse.workspace import workspace_dir

    report = probe_isolation()
    info = {
        "slamcourse": __version__,
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "platform": platform.platform(),
        "isolation": report.level,
        "isolation_reason": report.reason,
        "course": str(course_root(args.course)),
        "home": str(default_home()),
        "workspace": str(workspace_dir()),
    }
    if args.json:
        out.json(info)
        return 0
    for key, value in info.items():
        out.line(f"{key + ':':<18} {value}")
    if report.level != "namespaces":
        out.line(
            out.style(
                "Learner code runs with resource limits only (no namespaces): fine "
                "for practice on your own machine; CI grading passes "
                "--require-isolation and refuses this.",
                "yellow",
            )
        )
    return 0


def cmd_watch(args: argparse.Namespace, out: Out) -> int:
    """Re-grade a code exercise's file every time it is saved."""
    from slamcourse.watch import signature, wait_for_change

    with _engine(args) as engine:
        exercise_id = _target(engine, args.exercise)
        path, _ = engine.code_file(exercise_id)
        out.line(f"Watching {out.style(str(path), 'bold')} ({exercise_id}); Ctrl-C to stop.")
        while True:
            before = signature(path)
            verdict = engine.check_code(exercise_id, path)
            print_verdict(out, verdict)
            if verdict.passed:
                out.line(out.style("Explanation", "bold"))
                out.markdown(engine.explanation(exercise_id, engine.variant(exercise_id)))
                return 0
            mechanism = wait_for_change(path, poll=args.poll, since=before)
            out.line(out.style(f"changed ({mechanism}); checking…", "dim"))


# ------------------------------------------------------------------------------ parser


class _Unused:
    """Stands in for the parser of a command that is not being run (building all fourteen
    subparsers costs every command several milliseconds)."""

    def add_argument(self, *args: Any, **kwargs: Any) -> None:
        return None

    def add_mutually_exclusive_group(self, **kwargs: Any) -> _Unused:
        return self


def requested_command(argv: Sequence[str]) -> str | None:
    """The subcommand named in ``argv`` (after the global options), if any."""
    args = iter(argv)
    for arg in args:
        if arg == "--course":
            next(args, None)
        elif arg.startswith("-"):
            if arg in ("-h", "--help", "--version"):
                return None
        else:
            return arg
    return None


def cmd_serve(args: argparse.Namespace, out: Out) -> int:
    from slamcourse.web.server import serve

    return serve(
        course=args.course,
        host=args.host,
        port=args.port,
        open_browser=not args.no_browser,
        say=out.line,
    )


def cmd_plot(args: argparse.Namespace, out: Out) -> int:
    from slamcourse.plots.command import plot_command

    return plot_command(
        course=args.course, exercise_id=args.exercise, out_file=args.out, say=out.line
    )


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The argument parser; with ``only``, just that subcommand is built in full."""
    # An explicit width: argparse's default formatter imports shutil (and bz2, lzma) to find it.
    formatter = functools.partial(argparse.HelpFormatter, width=_width(sys.stdout) - 2)
    parser = argparse.ArgumentParser(
        formatter_class=formatter,
        prog="slamcourse",
        description="Learn classical SLAM by computing it: exercises with "
        "instant feedback, graded against numpy reference code.",
    )
    parser.add_argument("--version", action="version", version=f"slamcourse {__version__}")
    parser.add_argument(
        "--course",
        metavar="PATH",
        help="use the course at PATH instead of the bundled one (or set SLAMCOURSE_COURSE)",
    )
    parser.add_argument("--no-color", action="store_true", help="plain output (also NO_COLOR=1)")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    def add(name: str, fn: Callable[[argparse.Namespace, Out], int], help_: str, **kw: Any) -> Any:
        if only is not None and name != only:
            return _Unused()
        p = sub.add_parser(name, help=help_, description=help_, formatter_class=formatter, **kw)
        p.set_defaults(func=fn)
        return p

    def variant_opts(p: Any) -> None:
        group = p.add_mutually_exclusive_group()
        group.add_argument(
            "--canonical", action="store_true", help="the lesson's own numbers (variant 0)"
        )
        group.add_argument("--seed", type=int, metavar="S", help="variant S (0 = canonical)")

    p = add("next", cmd_next, "pose the next open exercise and grade answers interactively")
    p.add_argument("--no-context", action="store_true", help="do not show the chapter prose")
    p = add("check", cmd_check, "grade one answer (exit 0 passed, 1 not passed, 2 usage)")
    p.add_argument("exercise", metavar="ID")
    p.add_argument("--answer", metavar="TEXT", help="the answer, e.g. 0.25, 7/5, [0.3, -0.09]")
    p.add_argument(
        "--file",
        metavar="PATH",
        help="code exercises: grade this file (default: your workspace file)",
    )
    p.add_argument(
        "--require-isolation",
        action="store_true",
        help="code exercises: refuse to grade without namespace isolation (CI)",
    )
    p.add_argument("--json", action="store_true", help="machine-readable verdict")
    p.add_argument("--no-record", action="store_true", help="do not record the attempt")
    variant_opts(p)
    p = add("show", cmd_show, "print an exercise's prompt")
    p.add_argument("exercise", metavar="ID")
    p.add_argument("--context", action="store_true", help="also print the chapter prose before it")
    p.add_argument("--json", action="store_true")
    variant_opts(p)
    p = add("hint", cmd_hint, "reveal the next hint (of ID, or of the current exercise)")
    p.add_argument("exercise", metavar="ID", nargs="?")
    p.add_argument("--json", action="store_true")
    p = add("explain", cmd_explain, "show the worked explanation (once solved or given up)")
    p.add_argument("exercise", metavar="ID")
    p.add_argument("--json", action="store_true")
    p = add("giveup", cmd_giveup, "give up on an exercise and show its explanation")
    p.add_argument("exercise", metavar="ID")
    p = add("list", cmd_list, "every exercise with its status")
    p.add_argument("--json", action="store_true")
    p = add("status", cmd_status, "progress per chapter")
    p.add_argument("--json", action="store_true")
    p = add("goto", cmd_goto, "make ID the exercise `next` poses")
    p.add_argument("exercise", metavar="ID")
    p = add("reset", cmd_reset, "reopen one exercise, or all (attempts stay in the log)")
    p.add_argument("exercise", metavar="ID", nargs="?")
    p.add_argument("--yes", action="store_true", help="do not ask before resetting everything")
    p = add("watch", cmd_watch, "re-grade a code exercise's file on every save")
    p.add_argument("exercise", metavar="ID", nargs="?")
    p.add_argument("--poll", action="store_true", help="poll instead of using file events")
    p = add("doctor", cmd_doctor, "report the sandbox isolation level and where files live")
    p.add_argument("--json", action="store_true")
    p = add("validate", cmd_validate, "prove a course sound (reference, variants, misconceptions)")
    p.add_argument("path", metavar="COURSE", nargs="?", help="course folder (default: bundled)")
    p.add_argument(
        "--variants",
        type=int,
        default=25,
        metavar="N",
        help="random variants per exercise (default 25)",
    )
    p.add_argument("--json", action="store_true")
    p = add("serve", cmd_serve, "the course in your browser, with instant feedback")
    p.add_argument("--port", type=int, default=8765, metavar="P", help="port (default 8765)")
    p.add_argument(
        "--host", default="127.0.0.1", metavar="H", help="address to bind (default 127.0.0.1)"
    )
    p.add_argument("--no-browser", action="store_true", help="only print the address")
    p = add("plot", cmd_plot, "write the picture of an exercise (your numbers) as SVG")
    p.add_argument("exercise", metavar="ID")
    p.add_argument("--out", metavar="FILE.svg", help="write to FILE.svg (default: stdout)")
    return parser


_COMMANDS = frozenset(
    {
        "next",
        "check",
        "show",
        "hint",
        "explain",
        "giveup",
        "list",
        "status",
        "goto",
        "reset",
        "watch",
        "doctor",
        "validate",
        "serve",
        "plot",
    }
)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI; the one exit point. Returns the process exit code."""
    argv = list(sys.argv[1:] if argv is None else argv)
    wanted = requested_command(argv)
    known = wanted in _COMMANDS
    parser = build_parser(only=wanted if known else None)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # argparse exits 2 on usage errors and 0 on --help
        return int(exc.code or 0)
    if not getattr(args, "func", None):
        parser.print_help()
        return EXIT_USAGE
    out = Out(sys.stdout, no_color=args.no_color)
    try:
        code: int = args.func(args, out)
        return code
    except SlamcourseError as exc:
        sys.stdout.flush()
        print(f"Error: {exc}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        print("\nInterrupted; progress is saved.", file=sys.stderr)
        return 130


if __name__ == "__main__":
    raise SystemExit(main())
