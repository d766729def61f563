"""Running learners' code: a sandboxed worker process that can only hand back plain values.

See ``docs/grading.md`` (section *Sandbox*) for the threat model, the limits and the isolation
levels. The public API:

- :class:`Worker`: ``spawn()``, ``load()``, ``call()``, ``call_many()``, ``close()``;
- :class:`Zygote`: ``spawn()``, ``worker(limits)``: workers forked with numpy imported;
- :class:`Limits`, :func:`probe_isolation` and :class:`IsolationReport`;
- results: :class:`LoadResult`, :class:`CallResult`, :class:`LearnerFrame`, :class:`Unsupported`.
"""

from slamcourse.sandbox.isolation import IsolationReport, Limits, probe_isolation
from slamcourse.sandbox.protocol import LearnerFrame, Unsupported
from slamcourse.sandbox.runner import (
    CallResult,
    CallStatus,
    LoadResult,
    LoadStatus,
    Worker,
    Zygote,
)

__all__ = [
    "CallResult",
    "CallStatus",
    "IsolationReport",
    "LearnerFrame",
    "Limits",
    "LoadResult",
    "LoadStatus",
    "Unsupported",
    "Worker",
    "Zygote",
    "probe_isolation",
]
