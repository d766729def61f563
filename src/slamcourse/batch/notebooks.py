"""Handed-in notebooks: the answers in their exercise cells, read without running anything.

A submission may hold ``.ipynb`` files (the notebooks ``slamcourse export notebooks`` wrote,
as the learner saved them), beside a ``submission.json`` or instead of one. Each notebook is
parsed as JSON (no nbformat needed) and its code cells read with the conventions of
:mod:`slamcourse.notebook.cells` (docs/submissions.md, "Notebooks"):

- a cell whose first line is ``%%slamcourse check ID`` answers the code exercise ID with the
  rest of the cell (the last such cell of a notebook wins);
- a top-level ``check("ID", ANSWER)`` answers the exercise ID: a literal ``ANSWER`` as the
  notebook would write it, else what the notebook graded when the cell last ran (its
  output's ``slamcourse`` metadata: the answer text, or the source of a function), else
  ``ANSWER``'s source text; an empty answer (``""``, ``...``, ``None``) is no answer;
- within a notebook the last answer to an exercise (in cell order) is the one graded;
- who ran the notebook (learner seed and id) and for which course (hash) is read from the
  ``slamcourse`` metadata of the notebook face's outputs; a submission without a manifest
  takes its identity from there, one with a manifest must agree with it.

Nothing here trusts a notebook more than a manifest: the grader checks the same claims (the
course hash, the learner id derived from the seed, variants of the learner's own) and grades
the answers exactly as the other submission forms, code in the sandbox.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

from slamcourse.notebook.cells import META, check_calls, code_answer

NOTEBOOK_SUFFIX = ".ipynb"


@dataclass
class NotebookAnswers:
    """What a submission's notebooks hold: answers by exercise and who ran them."""

    code: dict[str, tuple[str, str]] = field(default_factory=dict)  # id -> (source, where)
    text: dict[str, tuple[str, str]] = field(default_factory=dict)  # id -> (answer, where)
    identities: dict[str, dict[str, Any]] = field(default_factory=dict)  # notebook -> identity

    @property
    def exercises(self) -> set[str]:
        return set(self.code) | set(self.text)


class NotebookError(ValueError):
    """A notebook cannot be read; the submission reports it (:class:`SubmissionError`)."""


def is_notebook(name: str) -> bool:
    return name.lower().endswith(NOTEBOOK_SUFFIX)


def _text(value: Any) -> str:
    """A cell's ``source`` (a string or a list of lines, nbformat allows both)."""
    if isinstance(value, str):
        return value
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return "".join(value)
    return ""


def _output_records(cell: dict[str, Any]) -> list[dict[str, Any]]:
    """The ``slamcourse`` metadata of a cell's outputs, in order."""
    records = []
    outputs = cell.get("outputs")
    for out in outputs if isinstance(outputs, list) else []:
        meta = out.get("metadata") if isinstance(out, dict) else None
        record = meta.get(META) if isinstance(meta, dict) else None
        if isinstance(record, dict):
            records.append(record)
    return records


def _identity(record: dict[str, Any]) -> dict[str, Any] | None:
    learner, course = record.get("learner"), record.get("course")
    if not (isinstance(learner, dict) and isinstance(course, dict)):
        return None
    seed = learner.get("seed")
    if not isinstance(seed, int) or isinstance(seed, bool):
        return None
    return {
        "learner": {"id": learner.get("id"), "name": learner.get("name"), "seed": seed},
        "course": {"version": course.get("version"), "hash": course.get("hash")},
        "engine": record.get("engine"),
    }


def read_notebook(name: str, data: bytes, into: NotebookAnswers) -> None:
    """Add one notebook's answers and identity to ``into``; raise :class:`NotebookError`
    for a notebook that is not one, or an exercise already answered in another notebook."""
    try:
        nb = json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise NotebookError(f"{name} is not a notebook (not JSON: {exc})") from None
    cells = nb.get("cells") if isinstance(nb, dict) else None
    if not isinstance(cells, list):
        raise NotebookError(f"{name} is not a notebook (no list of cells)")
    code: dict[str, tuple[str, str]] = {}
    text: dict[str, tuple[str, str]] = {}
    identities: list[dict[str, Any]] = []
    for index, cell in enumerate(cells, start=1):
        if not isinstance(cell, dict) or cell.get("cell_type") != "code":
            continue
        where = f"{name}, cell {index}"
        source = _text(cell.get("source"))
        records = _output_records(cell)
        identities += [i for i in map(_identity, records) if i is not None]
        found = code_answer(source)
        if found is not None:
            code[found.exercise] = (found.source, where)
            text.pop(found.exercise, None)
            continue
        for call in check_calls(source):
            if call.empty:
                continue
            ex, answer = call.exercise, call.text
            graded = [r for r in records if r.get("exercise") == ex]
            if answer is None and graded and isinstance(graded[-1].get("source"), str):
                code[ex] = (graded[-1]["source"], where)  # check("ID", function): its source
                text.pop(ex, None)
                continue
            if answer is None:  # not a literal: what the notebook graded, else the source
                said = [r["answer"] for r in graded if isinstance(r.get("answer"), str)]
                answer = said[-1] if said else call.expression
            text[ex] = (answer, where)
            code.pop(ex, None)
    for ex, (_, where) in {**code, **text}.items():
        earlier = into.code.get(ex) or into.text.get(ex)
        if earlier is not None:
            raise NotebookError(
                f"{ex} is answered in two notebooks ({earlier[1]} and {where}); hand in one"
            )
    seeds = {i["learner"]["seed"] for i in identities}
    if len(seeds) > 1:
        raise NotebookError(
            f"{name} holds the outputs of {len(seeds)} learners (learner seeds differ); run it "
            "again from the top and save it before handing it in"
        )
    into.code.update(code)
    into.text.update(text)
    if identities:
        into.identities[name] = identities[-1]


def read_notebooks(files: dict[str, bytes]) -> NotebookAnswers:
    """Every notebook among a submission's files, in path order."""
    found = NotebookAnswers()
    for name in sorted(files):
        if is_notebook(name):
            read_notebook(name, files[name], found)
    return found
