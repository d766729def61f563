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
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO

from slamcourse import __version__
from slamcourse.errors import EXIT_USAGE, SlamcourseError, UsageError

if TYPE_CHECKING:
    from slamcourse.engine import Engine, Prompt, Result
    from slamcourse.settings import Settings

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

    def markdown(self, text: str, *, figures: Path | None = None) -> None:
        """Render Markdown; a prose figure is written as SVG under ``figures`` (a workspace)
        and named in one line (without ``figures``: named, with the command that draws it)."""
        from slamcourse.render.terminal import figure_writer, render_markdown

        figure = figure_writer(figures) if figures is not None else None
        self.line(render_markdown(text, width=self.width, color=self.color, figure=figure))

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
VERDICT_LABEL = {
    "passed": "✓ passed",
    "failed": "✗ not yet",
    "invalid": "? unreadable",
    "timeout": "⏱ timeout",
    "error": "! grader error",
}


def print_result(
    out: Out, result: Result, *, explanation: bool = True, interactive: bool = True
) -> None:
    """A result as the terminal shows it: the verdict line, feedback wrapped to the terminal,
    then what the engine's rules add (practice note, nudge, explanation once passed)."""
    verdict = result.verdict
    out.line(out.style(VERDICT_LABEL[verdict.status], *VERDICT_STYLE[verdict.status]))
    from slamcourse.verdict import capitalised

    out.markdown(capitalised(verdict.feedback))  # never `Syn.py:1` or `Mahalanobis(…)`
    if verdict.status in ("invalid", "error"):
        out.line(out.style("(no attempt counted)", "dim"))
    elif result.practice:
        out.line(
            out.style(
                "(practice on the canonical variant: graded, not counted; your own variant "
                "is what counts)",
                "dim",
            )
        )
    if result.nudge:
        how = ":hint" if interactive else f"slamcourse hint {result.exercise_id}"
        out.line(out.style(f"{result.nudge} Type `{how}`.", "dim"))
    if explanation and result.explanation:
        out.line(out.style("Explanation", "bold"))
        out.markdown(result.explanation)


# ------------------------------------------------------------------------------ helpers


def _math(text: str) -> str:
    """Inline ``$…$`` math in short messages, as Unicode (the renderer loads only when needed)."""
    if "$" not in text:
        return text
    import re

    from slamcourse.render.math import latex_to_unicode

    return re.sub(r"\$([^$]+)\$", lambda m: latex_to_unicode(m.group(1)), text)


def _settings(args: argparse.Namespace) -> Settings:
    from slamcourse.settings import Settings

    return Settings.from_env(
        course=args.course,
        require_isolation=getattr(args, "require_isolation", False),
        record=not getattr(args, "no_record", False),
    )


def _engine(
    args: argparse.Namespace, *, with_progress: bool = True, warm_sandbox: bool = False
) -> Engine:
    from slamcourse.engine import Engine

    return Engine.open(_settings(args), with_progress=with_progress, warm_sandbox=warm_sandbox)


def _target(engine: Engine, given: str | None) -> str:
    if given:
        engine.exercise(given)
        return given
    current = engine.next_exercise()
    if current is None:
        raise UsageError("every exercise is done; name one (slamcourse list shows them)")
    return current


def _form_markdown(out: Out, form: dict[str, Any]) -> str | None:
    """The parts of an input form the terminal shows as text (choices, items); None if none."""
    kind = form["type"]
    if kind in ("choice", "multi"):
        return "\n".join(f"- **{o['id']})** {o['text']}" for o in form["options"])
    if kind == "order":
        return "\n".join(f"- **{o['id']})** {o['text']}" for o in form["items"])
    return None


def _show_prompt(out: Out, engine: Engine, prompt: Prompt, *, context: bool) -> None:
    index, count = prompt.position
    out.line(
        out.style(f"── {prompt.chapter_title} · exercise {index} of {count} ", "dim")
        + out.style(f"[{prompt.exercise_id}]", "dim")
    )
    if context:
        prose = engine.context(prompt.exercise_id)
        if prose:
            out.markdown(prose, figures=engine.settings.workspace)
            out.line()
    out.line(out.style(_math(prompt.title), "bold", "cyan"))
    out.markdown(prompt.text)
    if prompt.kind in ("choice", "multi", "order", "line"):
        listing = _form_markdown(out, prompt.form)
        if listing:
            out.line()
            out.markdown(listing)
        elif prompt.kind == "line":
            from slamcourse.render.terminal import render_code_listing

            out.line()
            out.line(render_code_listing("\n".join(prompt.form["lines"]), color=out.color))
    if prompt.how_to_answer:
        import textwrap

        for row in textwrap.wrap(_math(prompt.how_to_answer), width=out.width):
            out.line(out.style(row, "dim"))
    if prompt.code_file is not None:
        out.line(f"Your file: {out.style(str(prompt.code_file), 'bold')}")
    if prompt.practice:
        out.line(
            out.style(
                "(canonical variant, the chapter's own numbers: practice, not counted)", "dim"
            )
        )


# ------------------------------------------------------------------------------ commands


def cmd_next(args: argparse.Namespace, out: Out) -> int:
    """The interactive learner loop (rustlings-style)."""
    with _engine(args) as engine:
        while True:
            step = engine.next_step()  # the browser's "Next exercise" asks the same
            exercise_id = step.exercise_id
            if exercise_id is None:
                out.line(
                    out.style("Every exercise is solved or given up. Well done!", "bold", "green")
                )
                out.line("`slamcourse list` shows them all; `slamcourse reset ID` opens one again.")
                return 0
            if step.note:
                out.line()
                out.markdown(step.note)
            if not _pose(out, engine, exercise_id, args):
                return 0


def _ask(out: Out, prompt: str) -> str | None:
    out.stream.write(prompt)
    out.stream.flush()
    line = sys.stdin.readline()
    return None if not line else line.rstrip("\n")


QUIT = (":q", ":quit", "quit", "exit")


def _pose(out: Out, engine: Engine, exercise_id: str, args: argparse.Namespace) -> bool:
    """Pose one exercise until solved, skipped or given up. False when the learner quits."""
    prompt = engine.pose(exercise_id)
    out.line()
    _show_prompt(out, engine, prompt, context=not args.no_context)
    for text in prompt.hints_shown:
        out.line(out.style("hint: ", "yellow") + _math(text))
    code_path = prompt.code_file
    if code_path is not None:
        engine.start_workers()
        out.line(out.style(f"Edit it, then press Enter to check it, or {COMMANDS}", "dim"))
    else:
        out.line(out.style(f"Type your answer, or {COMMANDS}", "dim"))
    while True:
        answer = _ask(out, out.style("check> " if code_path else "answer> ", "bold"))
        if answer is None:  # end of input
            out.line()
            return False
        command = answer.strip().lower()
        if not command and code_path is None:
            continue
        if command in QUIT:
            out.line("Progress saved. Run `slamcourse next` to continue.")
            return False
        if command in (":h", ":hint", "hint", "?"):
            hint = engine.hint(exercise_id)
            if hint.text is None:
                out.line("No more hints. `:giveup` shows the worked explanation.")
            else:
                out.line(out.style(f"hint {hint.number}/{hint.total}: ", "yellow"))
                out.markdown(hint.text)
            continue
        if command in (":s", ":skip", "skip"):
            engine.skip(exercise_id)
            out.line("Skipped: it stays open, and `next` comes back to it when the rest are done.")
            return True
        if command in (":g", ":giveup", "giveup", "give up"):
            out.line(out.style("Explanation", "bold"))
            out.markdown(engine.give_up(exercise_id))
            return _continue(out)
        if code_path is not None:
            if command:
                out.line(f"Edit {code_path} in your editor; press Enter here to check it.")
                continue
            out.line(out.style("checking…", "dim"))
            result = engine.submit_code(exercise_id, path=code_path)
        else:
            result = engine.submit(exercise_id, answer)
        print_result(out, result)
        if result.passed:
            return _continue(out)


def _continue(out: Out) -> bool:
    answer = _ask(out, out.style("Enter for the next exercise, :quit to stop> ", "dim"))
    if answer is None or answer.strip().lower() in (*QUIT, "q"):
        out.line("Progress saved. Run `slamcourse next` to continue.")
        return False
    return True


def cmd_check(args: argparse.Namespace, out: Out) -> int:
    # Without --answer this is a code check (or a usage error): start the sandbox worker first,
    # so its interpreter imports numpy while this process loads the course.
    with _engine(
        args, with_progress=not args.no_record, warm_sandbox=args.answer is None
    ) as engine:
        if engine.is_code(args.exercise):
            if args.answer is not None:
                raise UsageError(
                    f"{args.exercise} is a code exercise: grade a file with --file PATH "
                    "(or leave it out to grade your workspace file)"
                )
            path = Path(args.file) if args.file is not None else engine.code_file(args.exercise)
            result = engine.submit_code(args.exercise, path=path)
            data: dict[str, Any] = {"exercise": args.exercise, "file": str(path)}
        else:
            if args.file is not None:
                raise UsageError(f"{args.exercise} is not a code exercise: use --answer TEXT")
            if args.answer is None:
                raise UsageError("give the answer with --answer TEXT (e.g. --answer 0.25)")
            result = engine.submit(
                args.exercise, args.answer, canonical=args.canonical, seed=args.seed
            )
            data = {"exercise": args.exercise, "variant": result.variant, "answer": args.answer}
        if args.json:
            out.json({**data, "verdict": result.verdict.to_dict(), "result": result.to_dict()})
        else:
            print_result(out, result, explanation=False, interactive=False)
        return result.exit_code


def cmd_show(args: argparse.Namespace, out: Out) -> int:
    with _engine(args, with_progress=not (args.canonical or args.seed is not None)) as engine:
        prompt = engine.pose(args.exercise, canonical=args.canonical, seed=args.seed)
        if args.json:
            out.json(prompt.to_dict())
        else:
            _show_prompt(out, engine, prompt, context=args.context)
        return 0


def cmd_hint(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        exercise_id = _target(engine, args.exercise)
        hint = engine.hint(exercise_id)
        if args.json:
            out.json({"exercise": exercise_id, **hint.to_dict()})
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
    from slamcourse.engine import Locked

    with _engine(args) as engine:
        try:
            text = engine.explanation(args.exercise)
        except Locked as exc:
            raise UsageError(f"{exc} (`slamcourse giveup {args.exercise}`)") from None
        if args.json:
            out.json({"exercise": args.exercise, "explanation": text})
        else:
            out.markdown(text)
        return 0


def cmd_giveup(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        out.markdown(engine.give_up(args.exercise))
        return 0


def cmd_list(args: argparse.Namespace, out: Out) -> int:
    with _engine(args) as engine:
        summary = engine.summary()
        if args.json:
            out.json(summary)
            return 0
        from slamcourse.engine import STATUS_MARK, STATUS_WORD

        styles = {"solved": ("green",), "given_up": ("yellow",), "pending": ("dim",)}
        styles["skipped"] = ("cyan",)
        marks = {state: out.style(STATUS_MARK[state], *style) for state, style in styles.items()}
        for ch in summary:
            out.line(
                out.style(f"{ch['number']:>2}. {ch['title']}", "bold")
                + f"  ({ch['solved']}/{ch['total']})"
            )
            for row in ch["exercises"]:
                pointer = out.style(" ← next", "cyan") if row["current"] else ""
                title = _math(row["title"])
                state = (
                    "skipped" if row["status"] == "pending" and row["skipped"] else row["status"]
                )
                out.line(f"    {marks[state]} {row['id']:<40} {title}{pointer}")
        legend = "   ".join(f"{marks[state]} {STATUS_WORD[state]}" for state in styles)
        out.line()
        out.line(f"{legend}   {out.style('← next', 'cyan')}: what `slamcourse next` poses")
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
        step = engine.goto(args.exercise)
        out.line(f"`slamcourse next` will pose {args.exercise}.")
        if step.note:
            out.markdown(step.note)
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
    from slamcourse.validate import validate_course

    root, only = _validate_targets(args.path, args.course)
    progress = None
    if sys.stderr.isatty() and not args.json:  # a live line on a terminal; nothing in logs

        def progress(exercise_id: str) -> None:
            sys.stderr.write(f"\r\033[2Kvalidating {exercise_id} …")
            sys.stderr.flush()

    try:
        report = validate_course(
            root,
            variants_per_exercise=args.variants,
            progress=progress,
            min_mutants=args.min_mutants,
            min_variants=args.min_variants,
            record=args.record,
            only=only,
        )
    finally:
        if progress is not None:
            sys.stderr.write("\r\033[2K")
            sys.stderr.flush()
    if args.json:
        out.json(
            {
                "ok": report.ok,
                "exercises": report.exercises,
                "variants": report.variants,
                "problems": [str(p) for p in report.problems],
                "warnings": [str(w) for w in report.warnings],
            }
        )
    else:
        for p in [*report.problems, *report.warnings]:
            out.line(str(p))
        summary = (
            f"{report.exercises} exercises, {report.variants} variants checked: "
            f"{len(report.problems)} problem{'s' if len(report.problems) != 1 else ''}"
        )
        if report.warnings:
            summary += f", {len(report.warnings)} warning{'s' if len(report.warnings) != 1 else ''}"
        out.line(out.style(summary, "bold", "green" if report.ok else "red"))
    return 0 if report.ok else 1


def _validate_targets(targets: list[str], course: str | None) -> tuple[Path, list[str] | None]:
    """The course to validate and, if the targets name exercises, just those (ids of the
    course, or paths of their YAML files: ``exercises/<chapter>/<slug>.yaml``)."""
    from slamcourse.course.locate import course_root

    folders = [t for t in targets if Path(t).is_dir()]
    if len(folders) > 1:
        raise UsageError("validate takes one course folder; name exercises by id or file")
    root: Path | None = course_root(folders[0] if folders else course) if folders else None
    only: list[str] = []
    for target in targets:
        path = Path(target)
        if path.is_dir():
            continue
        if path.suffix in (".yaml", ".yml") and path.is_file():
            found = path.resolve().parent.parent.parent
            if root is not None and found != root.resolve():
                raise UsageError(f"{target} is not an exercise of the course at {root}")
            root = found
            only.append(f"{path.parent.name}/{path.stem}")
        elif "/" in target and not path.exists():
            only.append(target)
        else:
            raise UsageError(
                f"{target}: not a course folder, an exercise file or an exercise id "
                "(write e.g. se2/between or exercises/se2/between.yaml)"
            )
    if root is None:
        root = course_root(course)
    return root, only or None


def cmd_doctor(args: argparse.Namespace, out: Out) -> int:
    """What this machine offers the grader: isolation level, paths, versions."""
    from slamcourse.engine import diagnostics

    info = diagnostics(_settings(args))
    if args.json:
        out.json(info)
        return 0
    for key, value in info.items():
        out.line(f"{key + ':':<18} {value}")
    if info["isolation"] != "namespaces":
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
        path = engine.code_file(exercise_id)
        engine.start_workers()
        out.line(
            f"Watching {out.style(str(path), 'bold')} ({exercise_id}): save it to check again. "
            f"Ctrl-C to stop; `slamcourse hint {exercise_id}` in another terminal for a hint."
        )
        while True:
            before = signature(path)
            result = engine.submit_code(exercise_id, path=path)
            # watch reads no commands, so the nudge names the command to run, not `:hint`
            print_result(out, result, interactive=False)
            if result.passed:
                return 0
            wait_for_change(path, poll=args.poll, since=before)
            out.line(out.style(f"{path.name} saved; checking again…", "dim"))


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


# ------------------------------------------------------------------------------ batch grading


def cmd_submit(args: argparse.Namespace, out: Out) -> int:
    """Write what the learner hands in: latest answers, code files, seeds, course hash."""
    from slamcourse.batch import submission

    with _engine(args) as engine:
        sub = submission.build(engine, learner_name=args.learner)
    path = submission.write(sub, Path(args.out))
    out.line(f"Wrote {path}: {len(sub.manifest.answers)} answers of {sub.manifest.learner_id}.")
    return 0


def cmd_grade(args: argparse.Namespace, out: Out) -> int:
    """Grade submissions in batch; exit 0 whenever grading ran, whatever the scores."""
    from slamcourse.batch import exporters, grade, outputs
    from slamcourse.settings import grading_secret

    if args.merge_csv:
        if not args.csv:
            raise UsageError("--merge-csv needs --csv FILE to write the merged gradebook to")
        texts = outputs.read_files([Path(p) for p in args.merge_csv])
        outputs.write_file(Path(args.csv), exporters.merge_gradebooks(texts))
        return 0
    if not args.submissions or args.hidden < 0:
        raise UsageError("give the submissions to grade (folders or .zip files), --hidden N ≥ 0")
    if args.format != "json" and not args.out:
        raise UsageError(f"--format {args.format} writes files: give --out DIR")
    options = grade.GradeOptions(
        course=Path(args.course) if args.course else None,
        require_isolation=not args.allow_no_isolation,
        secret=args.secret or grading_secret(),
        hidden_runs=args.hidden,
    )
    if options.require_isolation:
        from slamcourse.engine import diagnostics

        if diagnostics(_settings(args))["isolation"] != "namespaces":
            raise UsageError("no namespace isolation here; grade elsewhere or --allow-no-isolation")
    paths = grade.shard([Path(p) for p in args.submissions], args.shard)
    tty = sys.stderr.isatty()

    def bar(done: int, total: int, result: grade.SubmissionGrade) -> None:
        if tty:
            end = "\n" if done == total else ""
            print(
                "\r" + grade.bar_line(done, total, label=result.submission),
                end=end,
                file=sys.stderr,
                flush=True,
            )

    results = grade.grade_all(paths, options, jobs=args.jobs, pin=not args.no_pin, on_done=bar)
    if args.out:
        outputs.write_results(results, paths, args.format, Path(args.out))
    elif args.format == "json":
        out.line(outputs.dumps([r.to_dict() for r in results]).rstrip())
    if args.csv:
        outputs.write_file(Path(args.csv), exporters.gradebook(results))
    for line in grade.summary_lines(results):
        print(line, file=sys.stderr)
    if options.hidden_runs and not options.secret:
        print("note: no --secret: learners could compute the hidden checks' seeds", file=sys.stderr)
    return 0


def cmd_stats(args: argparse.Namespace, out: Out) -> int:
    """Solve rate, mean attempts and common misconceptions per exercise."""
    from slamcourse.batch import stats

    data = stats.statistics(stats.load_results(Path(p) for p in args.results))
    if args.json:
        out.json(data)
    else:
        out.line(stats.render_text(data))
    return 0


def cmd_export(args: argparse.Namespace, out: Out) -> int:
    """Build a platform's autograder bundle (Gradescope), or the course as notebooks."""
    if args.platform == "notebooks":
        from slamcourse.notebook.export import export_notebooks

        if args.wheel or args.secret:
            raise UsageError("export notebooks DIR takes no --wheel or --secret")
        folder = args.dir or args.out
        if folder is None:
            raise UsageError("export notebooks DIR: name the folder to write the notebooks to")
        paths = export_notebooks(
            Path(args.course) if args.course else None, Path(folder), force=args.force
        )
        out.line(f"Wrote {len(paths)} notebooks to {folder}")
        return 0
    if args.dir is not None or args.force:
        raise UsageError(
            "export gradescope writes --out PATH (a zip); DIR and --force are for notebooks"
        )
    from slamcourse.batch import bundle
    from slamcourse.settings import grading_secret

    if args.out is None:
        args.out = "autograder.zip"
    secret = args.secret or grading_secret()
    path = bundle.gradescope_bundle(
        Path(args.out), wheel=args.wheel, course=args.course, secret=secret
    )
    out.line(f"Wrote {path}")
    return 0


def _environment_help() -> str:
    from slamcourse.settings import ENVIRONMENT

    width = max(len(name) for name, _ in ENVIRONMENT)
    rows = "\n".join(f"  {name:<{width}}  {text}" for name, text in ENVIRONMENT)
    return "environment variables:\n" + rows


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The argument parser; with ``only``, just that subcommand is built in full."""
    # An explicit width: argparse's default formatter imports shutil (and bz2, lzma) to find it.
    formatter = functools.partial(argparse.HelpFormatter, width=_width(sys.stdout) - 2)
    parser = argparse.ArgumentParser(
        # the top level keeps its epilog's line breaks (the table of environment variables)
        formatter_class=functools.partial(
            argparse.RawDescriptionHelpFormatter, width=_width(sys.stdout) - 2
        ),
        prog="slamcourse",
        description="Learn classical SLAM by computing it: exercises with "
        "instant feedback, graded against numpy reference code.",
        epilog=_environment_help(),
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
    p = add(
        "check",
        cmd_check,
        "grade one answer or code file. Exit codes: 0 passed, 1 not passed (wrong, unreadable "
        "or timed out), 2 usage error, 3 grader error, 4 broken course, 5 progress database "
        "unusable",
    )
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
    p.add_argument(
        "path",
        metavar="TARGET",
        nargs="*",
        help="a course folder (default: the bundled course), or exercises of it to validate "
        "alone: ids (se2/between) or YAML files (exercises/se2/between.yaml)",
    )
    p.add_argument(
        "--variants",
        type=int,
        default=25,
        metavar="N",
        help="random variants per exercise (default 25)",
    )
    p.add_argument(
        "--min-mutants",
        type=int,
        default=None,
        metavar="N",
        help="wrong implementations required per code exercise (default 8)",
    )
    p.add_argument(
        "--min-variants",
        type=int,
        default=None,
        metavar="M",
        help="correct implementations by other methods required per code exercise (default 3)",
    )
    p.add_argument(
        "--record",
        action="store_true",
        help="(re)write each code exercise's shipped recording of test inputs first",
    )
    p.add_argument("--json", action="store_true")
    p = add("serve", cmd_serve, "the course in your browser, with instant feedback")
    p.add_argument(
        "--port", type=int, metavar="P", help="port (default 8765, or a free one if taken)"
    )
    p.add_argument(
        "--host", default="127.0.0.1", metavar="H", help="address to bind (default 127.0.0.1)"
    )
    p.add_argument("--no-browser", action="store_true", help="only print the address")
    p = add("plot", cmd_plot, "write the picture of an exercise (your numbers) or a figure as SVG")
    p.add_argument("exercise", metavar="ID", help="an exercise id or a chapter figure's id")
    p.add_argument(
        "--out",
        metavar="FILE.svg",
        help="write to FILE.svg ('-': print the SVG; default: your workspace's figures folder)",
    )

    p = add(
        "submit",
        cmd_submit,
        "write your submission: answers, code files, seeds (a .zip or a folder)",
    )
    p.add_argument("--out", default="submission.zip", metavar="PATH", help="default submission.zip")
    p.add_argument(
        "--learner", metavar="NAME", help="your name or id (default: derived from your seed)"
    )
    p = add("grade", cmd_grade, "grade submissions in batch (exit 0 whenever grading ran)")
    p.add_argument("submissions", metavar="SUBMISSION", nargs="*", help="folders or .zip files")
    p.add_argument("--jobs", type=int, default=1, metavar="N", help="worker processes")
    p.add_argument(
        "--no-pin",
        action="store_true",
        help="let the system move the --jobs processes between CPUs (by default each is "
        "pinned to a CPU of its own when there are enough)",
    )
    p.add_argument("--shard", metavar="K/N", help="grade every N-th submission from the K-th")
    p.add_argument(
        "--format",
        default="json",
        choices=("json", "junit", "gradescope", "exercism", "prairielearn"),
    )
    p.add_argument("--out", metavar="DIR", help="write results here (json: stdout without it)")
    p.add_argument("--csv", metavar="FILE", help="also write the gradebook CSV")
    p.add_argument(
        "--merge-csv", nargs="+", metavar="CSV", help="merge shards' gradebooks into --csv"
    )
    p.add_argument(
        "--secret", metavar="TEXT", help="seeds hidden checks (or SLAMCOURSE_GRADING_SECRET)"
    )
    p.add_argument(
        "--hidden",
        type=int,
        default=1,
        metavar="N",
        help="hidden property runs per code exercise (default 1)",
    )
    p.add_argument(
        "--allow-no-isolation", action="store_true", help="grade without namespace isolation"
    )
    p = add("stats", cmd_stats, "class statistics from grade results (files or folders)")
    p.add_argument("results", metavar="RESULTS", nargs="+")
    p.add_argument("--json", action="store_true")
    p = add(
        "export",
        cmd_export,
        "build a grading platform's autograder bundle (gradescope), or write the course as "
        "Jupyter notebooks, one per chapter (notebooks DIR)",
    )
    p.add_argument("platform", choices=("gradescope", "notebooks"))
    p.add_argument("dir", metavar="DIR", nargs="?", help="notebooks: the folder to write")
    p.add_argument(
        "--out", metavar="PATH", help="gradescope: the zip to write (default autograder.zip)"
    )
    p.add_argument(
        "--force", action="store_true", help="notebooks: overwrite notebooks already in DIR"
    )
    p.add_argument(
        "--wheel", metavar="PATH", help="install this wheel instead of slamcourse from PyPI"
    )
    p.add_argument(
        "--secret", metavar="TEXT", help="seeds hidden checks (or SLAMCOURSE_GRADING_SECRET)"
    )
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
        "submit",
        "grade",
        "stats",
        "export",
    }
)


def join_option_values(argv: list[str]) -> list[str]:
    """``--answer -dx/sqrt(q)`` → ``--answer=-dx/sqrt(q)``: an answer may start with ``-``.

    argparse takes any word that starts with ``-`` and is not a plain number for an option, so
    the value of an option that takes free text is joined to it before parsing.
    """
    out: list[str] = []
    it = iter(argv)
    for arg in it:
        if arg in TEXT_OPTIONS:
            value = next(it, None)
            out.append(arg if value is None else f"{arg}={value}")
        else:
            out.append(arg)
    return out


TEXT_OPTIONS = frozenset({"--answer"})


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI; the one exit point. Returns the process exit code."""
    argv = join_option_values(list(sys.argv[1:] if argv is None else argv))
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
        _flush_quietly()
        print(f"Error: {exc}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        print("\nInterrupted; progress is saved.", file=sys.stderr)
        return 130
    except BrokenPipeError:  # e.g. `slamcourse list | head -3`: the reader has gone
        _silence_stdout()
        return 0


def _flush_quietly() -> None:
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _silence_stdout()


def _silence_stdout() -> None:
    """Point stdout at /dev/null so the interpreter's final flush does not fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):
        pass


if __name__ == "__main__":
    raise SystemExit(main())
