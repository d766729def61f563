"""Exercise kinds. Each kind parses its own YAML keys, computes the expected answer, checks an
answer into a :class:`~slamcourse.verdict.Verdict`, and proves itself sound for the validator.

Kinds are imported lazily: a command loads only the module of the kind it needs.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from slamcourse.kinds.base import Kind

_REGISTRY = {
    "number": "slamcourse.kinds.numeric:NumberKind",
    "vector": "slamcourse.kinds.numeric:VectorKind",
    "matrix": "slamcourse.kinds.numeric:MatrixKind",
    "expression": "slamcourse.kinds.expression:ExpressionKind",
    "choice": "slamcourse.kinds.choice:ChoiceKind",
    "multi": "slamcourse.kinds.choice:MultiKind",
    "order": "slamcourse.kinds.order:OrderKind",
    "line": "slamcourse.kinds.line:LineKind",
    "code": "slamcourse.kinds.code:CodeKind",
}
_instances: dict[str, Kind] = {}


def kind_names() -> list[str]:
    return list(_REGISTRY)


def get_kind(name: str) -> Kind:
    """The (shared, stateless) kind object for ``name``."""
    if name not in _instances:
        module, _, attr = _REGISTRY[name].partition(":")
        _instances[name] = getattr(importlib.import_module(module), attr)()
    return _instances[name]
