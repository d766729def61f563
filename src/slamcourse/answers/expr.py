"""A safe evaluator for the small formulas learners and course authors write.

``compile_expression("-dx/sqrt(q)", ["dx", "q"])`` returns an :class:`Expression` that evaluates
with Python's ``math`` module on scalars or, on request, with numpy on arrays. Nothing is ever
handed to ``eval``/``exec``/``compile``: the text is parsed with :func:`ast.parse` (mode
``"eval"``), every node is checked against a strict whitelist, and a tree of closures is built.

Preprocessing rules, applied to the text before parsing (in this order):

1. Unicode look-alikes: ``−`` (minus) and ``–`` (en dash) become ``-``; ``×``, ``·`` and ``⋅``
   become ``*``; ``÷`` becomes ``/``; ``²`` and ``³`` become ``**2`` and ``**3``; ``^`` becomes
   ``**`` (so ``^`` always means power); every whitespace character becomes a space.
2. ``π`` is the name ``pi`` and ``τ`` the name ``tau``.
3. ``√`` takes the number, name (with its call brackets, if any) or bracketed group right after
   it: ``√2`` → ``sqrt(2)``, ``√x`` → ``sqrt(x)``, ``√(x+1)`` → ``sqrt(x+1)``,
   ``√sin(x)`` → ``sqrt(sin(x))``.
4. Implicit multiplication, only where unambiguous: a number immediately followed (no space) by
   a name or by ``(`` gets a ``*``: ``2pi`` → ``2*pi``, ``2(x+1)`` → ``2*(x+1)``,
   ``3sqrt(2)`` → ``3*sqrt(2)``, ``2π`` → ``2*pi``. Scientific notation is a number first
   (``1e-3``, ``2E5``, ``1.5e+2``), so it is never split; a lone ``e`` after a number is the
   constant (``2e`` → ``2*e``). Digits inside a name belong to it (``x2`` is one name), and
   nothing else is implied: ``x y``, ``x(1+y)`` and ``(a)(b)`` are errors.

Allowed after preprocessing: int/float literals (at most 30 characters, used as floats), the
given variables and the constants ``pi``, ``e``, ``tau`` (a variable of the same name wins),
``+ - * / **``, unary ``+ -``, calls by bare name of the functions in :data:`FUNCTIONS`, and, with
``logic=True``, comparisons (chained too) and ``and``/``or``/``not``. Limits: 1000 characters,
300 AST nodes, nesting depth 40.
"""

from __future__ import annotations

import ast
import functools
import keyword
import math
import operator
import re
import warnings
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, cast

from slamcourse.answers.text import decode_answer
from slamcourse.errors import AnswerFormatError, GraderError

__all__ = [
    "CONSTANTS",
    "FUNCTIONS",
    "Expression",
    "compile_expression",
    "evaluate_number",
    "preprocess",
]

MAX_CHARS = 1000
MAX_NODES = 300
MAX_DEPTH = 40
MAX_LITERAL = 30

CONSTANTS: dict[str, float] = {"pi": math.pi, "e": math.e, "tau": math.tau}

# name -> (minimum, maximum) number of positional arguments (None: no maximum)
FUNCTIONS: dict[str, tuple[int, int | None]] = {
    "sqrt": (1, 1),
    "exp": (1, 1),
    "log": (1, 2),
    "log10": (1, 1),
    "sin": (1, 1),
    "cos": (1, 1),
    "tan": (1, 1),
    "asin": (1, 1),
    "acos": (1, 1),
    "atan": (1, 1),
    "atan2": (2, 2),
    "hypot": (2, 2),
    "abs": (1, 1),
    "floor": (1, 1),
    "ceil": (1, 1),
    "min": (2, None),
    "max": (2, None),
}

_EXAMPLE_CALL = {"atan2": "atan2(y, x)", "hypot": "hypot(x, y)", "log": "log(x) or log(x, 2)"}

Env = dict[str, Any]
Fn = Callable[[Env], Any]

# --------------------------------------------------------------------------------------------
# Preprocessing
# --------------------------------------------------------------------------------------------

_REPLACE = str.maketrans(
    {
        "−": "-",
        "–": "-",
        "×": "*",
        "·": "*",
        "⋅": "*",
        "÷": "/",
        "²": "**2",
        "³": "**3",
        "^": "**",
    }
)

_PLAIN_OK = frozenset(
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_ +-*/().,<>=!√"
)

_CHAR_HINTS = {
    "[": "use round brackets ( ) in a formula",
    "]": "use round brackets ( ) in a formula",
    "{": "use round brackets ( ) in a formula",
    "}": "use round brackets ( ) in a formula",
    "%": "write a percentage as a fraction (50% is 0.5)",
    "'": "text in quotes is not a formula",
    '"': "text in quotes is not a formula",
    "#": "comments are not allowed",
    ";": "give a single formula",
    "&": "write 'and' in a condition",
    "|": "write 'or' in a condition",
    "°": "angles are in radians (45° is pi/4)",
}

_TOKEN = re.compile(
    r"""
    (?P<num>(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)
  | (?P<greek>[πτ])
  | (?P<name>(?:(?![πτ])[^\W\d])(?:(?![πτ])\w)*)
  | (?P<space>\s+)
  | (?P<other>.)
    """,
    re.VERBOSE | re.DOTALL,
)

_GREEK = {"π": "pi", "τ": "tau"}


@dataclass(frozen=True)
class _Piece:
    """A run of output text and what kind of token it starts and ends with."""

    text: str
    first: str  # "num", "word", "open", "space" or "other"
    last: str


def _snippet(text: str, limit: int = 40) -> str:
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _normalise(text: str) -> str:
    """Rule 1: unicode look-alikes and whitespace."""
    text = text.translate(_REPLACE)
    return "".join(" " if c.isspace() else c for c in text)


def _check_chars(text: str) -> None:
    for c in text:
        if c in _PLAIN_OK or (c.isalpha() and c.isprintable()):
            continue
        hint = _CHAR_HINTS.get(c)
        if hint is None and c in "⁰¹⁴⁵⁶⁷⁸⁹":
            hint = "write powers as x**4 or x^4"
        raise AnswerFormatError(
            f"{c!r} cannot be used in a formula" + (f"; {hint}" if hint else "")
        )


def _check_brackets(text: str) -> None:
    depth = 0
    for c in text:
        if c == "(":
            depth += 1
            if depth > MAX_DEPTH:
                raise AnswerFormatError(
                    f"the formula is nested too deeply (more than {MAX_DEPTH} brackets)"
                )
        elif c == ")":
            depth -= 1
            if depth < 0:
                raise AnswerFormatError("unbalanced brackets: a ')' has no matching '('")
    if depth > 0:
        raise AnswerFormatError(
            f"unbalanced brackets: {depth} '(' never closed — add the missing ')'"
        )


def _tokenize(text: str) -> list[tuple[str, str]]:
    tokens: list[tuple[str, str]] = []
    for m in _TOKEN.finditer(text):
        kind = m.lastgroup or "other"
        value = m.group()
        if kind == "num" and len(value) > MAX_LITERAL:
            raise AnswerFormatError(
                f"the number '{_snippet(value, 20)}' is too long (at most {MAX_LITERAL} characters)"
            )
        if kind == "num" and not math.isfinite(float(value)):
            raise AnswerFormatError(f"the number '{value}' is too large")
        tokens.append((kind, value))
    return tokens


def _matching(tokens: Sequence[tuple[str, str]], start: int) -> int:
    """Index of the ')' closing the '(' at ``start`` (brackets are known to balance)."""
    depth = 0
    for i in range(start, len(tokens)):
        if tokens[i][1] == "(":
            depth += 1
        elif tokens[i][1] == ")":
            depth -= 1
            if depth == 0:
                return i
    raise AnswerFormatError("unbalanced brackets: a '(' is never closed")


def _skip_spaces(tokens: Sequence[tuple[str, str]], i: int) -> int:
    while i < len(tokens) and tokens[i][0] == "space":
        i += 1
    return i


def _root(tokens: Sequence[tuple[str, str]], i: int) -> tuple[str, int]:
    """Rule 3: the operand of the '√' at ``tokens[i]``; returns its text and the next index."""
    count = 0
    while i < len(tokens) and tokens[i][1] == "√":
        count += 1
        i = _skip_spaces(tokens, i + 1)
    bad = AnswerFormatError(
        "'√' must be followed by a number, a name or a bracketed group, e.g. √2, √x or √(x+1)"
    )
    if i >= len(tokens):
        raise bad
    kind, value = tokens[i]
    if kind == "num":
        inner, i = value, i + 1
    elif kind in ("name", "greek"):
        inner, i = _GREEK.get(value, value), i + 1
        if kind == "name" and i < len(tokens) and tokens[i][1] == "(":
            end = _matching(tokens, i)
            inner += "(" + _rewrite(tokens[i + 1 : end]) + ")"
            i = end + 1
    elif value == "(":
        end = _matching(tokens, i)
        inner, i = _rewrite(tokens[i + 1 : end]), end + 1
    else:
        raise bad
    return "sqrt(" * count + inner + ")" * count, i


def _pieces(tokens: Sequence[tuple[str, str]]) -> list[_Piece]:
    pieces: list[_Piece] = []
    i = 0
    while i < len(tokens):
        kind, value = tokens[i]
        if value == "√":
            text, i = _root(tokens, i)
            pieces.append(_Piece(text, "word", "other"))
            continue
        if kind == "greek":
            pieces.append(_Piece(_GREEK[value], "word", "word"))
        elif kind == "name":
            pieces.append(_Piece(value, "word", "word"))
        elif kind == "num":
            pieces.append(_Piece(value, "num", "num"))
        elif kind == "space":
            pieces.append(_Piece(value, "space", "space"))
        else:
            role = "open" if value == "(" else "other"
            pieces.append(_Piece(value, role, role))
        i += 1
    return pieces


def _rewrite(tokens: Sequence[tuple[str, str]]) -> str:
    """Rules 2-4 on a token list: greek names, roots and implicit multiplication."""
    out: list[str] = []
    prev: _Piece | None = None
    for piece in _pieces(tokens):
        if prev is not None:
            if prev.last == "num" and piece.first in ("word", "open"):
                out.append("*")
            elif prev.last in ("word", "num") and piece.first in ("word", "num"):
                out.append(" ")  # keep 'a π' from gluing into one name 'api'
        out.append(piece.text)
        prev = piece
    return "".join(out)


def preprocess(text: str) -> str:
    """Apply the module's preprocessing rules; return Python-syntax text (not yet checked).

    >>> preprocess("2π − √(x+1)·3²")
    '2*pi - sqrt(x+1)*3**2'
    """
    text = _normalise(text)
    _check_chars(text)
    _check_brackets(text)
    return _rewrite(_tokenize(text))


# --------------------------------------------------------------------------------------------
# Parsing and checking
# --------------------------------------------------------------------------------------------

_LOGIC_WORDS = frozenset({"and", "or", "not"})

_FORBIDDEN_NODES: dict[type[ast.AST], str] = {
    ast.Attribute: "attribute access ('.name')",
    ast.Subscript: "indexing with [ ]",
    ast.Lambda: "'lambda'",
    ast.ListComp: "'for … in …'",
    ast.SetComp: "'for … in …'",
    ast.DictComp: "'for … in …'",
    ast.GeneratorExp: "'for … in …'",
    ast.List: "a list in [ ]",
    ast.Tuple: "several values separated by commas",
    ast.Set: "{ }",
    ast.Dict: "{ }",
    ast.IfExp: "'if … else'",
    ast.NamedExpr: "':='",
    ast.Starred: "'*' unpacking",
    ast.JoinedStr: "text in quotes",
    ast.Await: "'await'",
    ast.Yield: "'yield'",
    ast.YieldFrom: "'yield'",
    ast.Slice: "slices",
}

_BINOPS: dict[type[ast.operator], str] = {
    ast.Add: "+",
    ast.Sub: "-",
    ast.Mult: "*",
    ast.Div: "/",
    ast.Pow: "**",
}

_OTHER_BINOPS: dict[type[ast.operator], str] = {
    ast.FloorDiv: "'//' (use '/' or floor(a/b))",
    ast.Mod: "'%'",
    ast.MatMult: "'@'",
    ast.LShift: "'<<'",
    ast.RShift: "'>>'",
    ast.BitOr: "'|'",
    ast.BitAnd: "'&'",
    ast.BitXor: "'^'",
}

_COMPARE: dict[type[ast.cmpop], Callable[[Any, Any], Any]] = {
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
}


def _summary(variables: Collection[str], logic: bool) -> str:
    names = ", ".join([*sorted(variables), *(c for c in CONSTANTS if c not in variables)])
    text = f"use numbers, + - * / ** (or ^), ( ), the names {names} and functions such as sqrt(x)"
    if logic:
        text += ", comparisons (< <= > >= == !=) and and/or/not"
    return text


def _suggest(name: str, options: Collection[str]) -> str:
    lower = {o.lower(): o for o in options}
    if name.lower() in lower:
        return f" (did you mean '{lower[name.lower()]}'?)"
    import difflib  # only when suggesting a name

    close = difflib.get_close_matches(name, list(options), n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""


_ADJACENT = re.compile(
    r"(?<![^\W\d_])(?!(?:and|or|not|in|is)\b)[\w.)]+\s+(?!(?:and|or|not|in|is)\b)[\w.(]"
)


def _syntax_message(text: str, err: SyntaxError, variables: Collection[str], logic: bool) -> str:
    words = set(re.findall(r"[^\W\d]\w*", text))
    for word in sorted(words):
        if keyword.iskeyword(word) and not (logic and word in _LOGIC_WORDS):
            return f"'{word}' is not allowed in a formula; {_summary(variables, logic)}"
    if re.search(r"(?<![<>=!])=(?!=)", text):
        if logic:
            return "use '==' to compare two values, e.g. x == 1 ('=' alone is not allowed)"
        return "give just the value, e.g. 2*pi, not an equation with '='"
    stripped = text.rstrip()
    if stripped and stripped[-1] in "+-*/<>=!,":
        return f"the formula ends with '{stripped[-1]}': something is missing after it"
    if _ADJACENT.search(text) or "Perhaps you forgot a comma" in (err.msg or ""):
        return (
            "two values stand next to each other; write '*' for a product (e.g. 2*x) "
            "or use one value"
        )
    offset = max((err.offset or 1) - 1, 0)
    near = _snippet(text[offset : offset + 12].strip() or text[-12:].strip(), 12)
    return (
        f"cannot read '{_snippet(text)}' as a formula (problem near '{near}'); "
        "write it like 2*pi/3 or sqrt(2)/2"
    )


def _parse(text: str, variables: Collection[str], logic: bool) -> ast.expr:
    code = preprocess(text)
    if not code.strip():
        raise AnswerFormatError("empty formula; write a value such as 2*pi/3 or sqrt(2)/2")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            tree = ast.parse(code, mode="eval")
    except SyntaxError as err:
        raise AnswerFormatError(_syntax_message(code, err, variables, logic)) from None
    except (ValueError, RecursionError, MemoryError, OverflowError):
        raise AnswerFormatError(
            f"cannot read '{_snippet(text)}' as a formula; write it like 2*pi/3 or sqrt(2)/2"
        ) from None
    count = sum(1 for node in ast.walk(tree.body) if isinstance(node, ast.expr))
    if count > MAX_NODES:
        raise AnswerFormatError(f"the formula is too long (more than {MAX_NODES} parts)")
    return tree.body


class _Checker:
    """Walks a parsed formula against the whitelist; returns each node's kind."""

    def __init__(self, variables: Collection[str], logic: bool) -> None:
        self.variables = frozenset(variables)
        self.logic = logic
        self.used: set[str] = set()

    def fail(self, what: str) -> AnswerFormatError:
        return AnswerFormatError(
            f"{what} is not allowed in a formula; {_summary(self.variables, self.logic)}"
        )

    def check(self, node: ast.expr, depth: int = 1) -> str:
        """Return ``"number"`` or ``"condition"``; raise AnswerFormatError if not allowed."""
        if depth > MAX_DEPTH:
            raise AnswerFormatError(f"the formula is nested too deeply (more than {MAX_DEPTH})")
        if isinstance(node, ast.Constant):
            return self.constant(node)
        if isinstance(node, ast.Name):
            return self.name(node)
        if isinstance(node, ast.BinOp):
            return self.binop(node, depth)
        if isinstance(node, ast.UnaryOp):
            return self.unaryop(node, depth)
        if isinstance(node, ast.Call):
            return self.call(node, depth)
        if isinstance(node, ast.Compare):
            return self.compare(node, depth)
        if isinstance(node, ast.BoolOp):
            return self.boolop(node, depth)
        raise self.fail(_FORBIDDEN_NODES.get(type(node), f"'{type(node).__name__}'"))

    def want(self, node: ast.expr, depth: int, kind: str, where: str) -> None:
        got = self.check(node, depth)
        if got != kind:
            if kind == "number":
                raise AnswerFormatError(f"{where} needs numbers, not a condition")
            raise AnswerFormatError(f"{where} joins conditions such as x > 1, not numbers")

    def constant(self, node: ast.Constant) -> str:
        value = node.value
        if isinstance(value, bool) or value is None or value is Ellipsis:
            raise self.fail(f"'{value}'")
        if isinstance(value, str | bytes):
            raise self.fail("text in quotes")
        if isinstance(value, complex):
            raise self.fail("a complex number")
        if not isinstance(value, int | float) or not math.isfinite(float(value)):
            raise AnswerFormatError(f"the number {value!r} is too large")
        return "number"

    def name(self, node: ast.Name) -> str:
        if node.id in self.variables:
            self.used.add(node.id)
            return "number"
        if node.id in CONSTANTS:
            return "number"
        if node.id in FUNCTIONS:
            raise AnswerFormatError(f"'{node.id}' is a function; write {node.id}(…)")
        known = [*sorted(self.variables), *(c for c in CONSTANTS if c not in self.variables)]
        raise AnswerFormatError(
            f"unknown name '{node.id}'{_suggest(node.id, known)}; you can use {', '.join(known)}"
        )

    def binop(self, node: ast.BinOp, depth: int) -> str:
        symbol = _BINOPS.get(type(node.op))
        if symbol is None:
            raise self.fail(_OTHER_BINOPS.get(type(node.op), "this operator"))
        self.want(node.left, depth + 1, "number", f"'{symbol}'")
        self.want(node.right, depth + 1, "number", f"'{symbol}'")
        return "number"

    def unaryop(self, node: ast.UnaryOp, depth: int) -> str:
        if isinstance(node.op, ast.Not):
            if not self.logic:
                raise self.fail("'not'")
            self.want(node.operand, depth + 1, "condition", "'not'")
            return "condition"
        if isinstance(node.op, ast.Invert):
            raise self.fail("'~'")
        self.want(node.operand, depth + 1, "number", "a sign")
        return "number"

    def call(self, node: ast.Call, depth: int) -> str:
        if not isinstance(node.func, ast.Name):
            raise AnswerFormatError("only named functions can be called, e.g. sqrt(x)")
        name = node.func.id
        if name not in FUNCTIONS:
            if name in self.variables or name in CONSTANTS:
                raise AnswerFormatError(f"'{name}' is not a function; write {name}*(…) to multiply")
            raise AnswerFormatError(
                f"unknown function '{name}'{_suggest(name, FUNCTIONS)}; "
                f"the functions are {', '.join(FUNCTIONS)}"
            )
        if node.keywords:
            raise self.fail(f"a named argument in {name}(…)")
        low, high = FUNCTIONS[name]
        n = len(node.args)
        if n < low or (high is not None and n > high):
            raise AnswerFormatError(_arity_message(name, n))
        for arg in node.args:
            if isinstance(arg, ast.Starred):
                raise self.fail("'*' unpacking")
            self.want(arg, depth + 1, "number", f"{name}(…)")
        return "number"

    def compare(self, node: ast.Compare, depth: int) -> str:
        if not self.logic:
            raise self.fail("a comparison")
        for op in node.ops:
            if type(op) not in _COMPARE:
                raise self.fail("'in'/'is'")
        for part in (node.left, *node.comparators):
            self.want(part, depth + 1, "number", "a comparison")
        return "condition"

    def boolop(self, node: ast.BoolOp, depth: int) -> str:
        word = "'and'" if isinstance(node.op, ast.And) else "'or'"
        if not self.logic:
            raise self.fail(word)
        for value in node.values:
            self.want(value, depth + 1, "condition", word)
        return "condition"


def _arity_message(name: str, n: int) -> str:
    low, high = FUNCTIONS[name]
    if high is None:
        takes = f"at least {low} arguments"
    elif low == high:
        takes = f"{low} argument" + ("s" if low > 1 else "")
    else:
        takes = f"{low} or {high} arguments"
    example = _EXAMPLE_CALL.get(name, f"{name}(a, b)" if low > 1 else f"{name}(x)")
    return f"{name} takes {takes}, got {n} — e.g. {example}"


# --------------------------------------------------------------------------------------------
# Backends
# --------------------------------------------------------------------------------------------


def _fmt(x: Any) -> str:
    try:
        return f"{float(x):.6g}"
    except (TypeError, ValueError, OverflowError):
        return str(x)


def _m_div(a: float, b: float) -> float:
    if b == 0:
        raise AnswerFormatError("division by zero")
    return a / b


def _m_pow(a: float, b: float) -> float:
    try:
        return math.pow(a, b)
    except OverflowError:
        raise AnswerFormatError(f"{_fmt(a)} ** {_fmt(b)} is too large") from None
    except (ValueError, ZeroDivisionError):
        if a == 0:
            raise AnswerFormatError("0 raised to a negative power (division by zero)") from None
        raise AnswerFormatError(
            f"({_fmt(a)}) ** {_fmt(b)} is not a real number "
            "(a negative number to a fractional power)"
        ) from None


def _m_log(x: float, base: float | None = None) -> float:
    return math.log(x) if base is None else math.log(x, base)


def _guard(name: str, fn: Callable[..., Any]) -> Callable[..., float]:
    def run(*args: float) -> float:
        try:
            return float(fn(*args))
        except (ValueError, ZeroDivisionError):
            shown = ", ".join(_fmt(a) for a in args)
            raise AnswerFormatError(f"{name}({shown}) is not defined") from None
        except OverflowError:
            shown = ", ".join(_fmt(a) for a in args)
            raise AnswerFormatError(f"{name}({shown}) is too large") from None

    return run


_MATH_RAW: dict[str, Callable[..., Any]] = {
    "sqrt": math.sqrt,
    "exp": math.exp,
    "log": _m_log,
    "log10": math.log10,
    "sin": math.sin,
    "cos": math.cos,
    "tan": math.tan,
    "asin": math.asin,
    "acos": math.acos,
    "atan": math.atan,
    "atan2": math.atan2,
    "hypot": math.hypot,
    "abs": abs,
    "floor": math.floor,
    "ceil": math.ceil,
    "min": min,
    "max": max,
}
_MATH_FUNCTIONS: dict[str, Callable[..., float]] = {n: _guard(n, f) for n, f in _MATH_RAW.items()}


@dataclass(frozen=True)
class _Backend:
    number: Callable[[float], Any]
    binary: Mapping[type[ast.operator], Callable[[Any, Any], Any]]
    functions: Mapping[str, Callable[..., Any]]
    both: Callable[[Any, Any], Any]
    either: Callable[[Any, Any], Any]
    negate: Callable[[Any], Any]
    short_circuit: bool


_MATH = _Backend(
    number=float,
    binary={
        ast.Add: operator.add,
        ast.Sub: operator.sub,
        ast.Mult: operator.mul,
        ast.Div: _m_div,
        ast.Pow: _m_pow,
    },
    functions=_MATH_FUNCTIONS,
    both=lambda a, b: bool(a and b),
    either=lambda a, b: bool(a or b),
    negate=lambda a: not a,
    short_circuit=True,
)


@functools.cache
def _numpy_backend() -> _Backend:
    import numpy as np  # lazily: the math backend never loads numpy

    def log(x: Any, base: Any = None) -> Any:
        return np.log(x) if base is None else np.log(x) / np.log(base)

    return _Backend(
        number=np.float64,
        binary={
            ast.Add: np.add,
            ast.Sub: np.subtract,
            ast.Mult: np.multiply,
            ast.Div: np.divide,
            ast.Pow: np.power,
        },
        functions={
            "sqrt": np.sqrt,
            "exp": np.exp,
            "log": log,
            "log10": np.log10,
            "sin": np.sin,
            "cos": np.cos,
            "tan": np.tan,
            "asin": np.arcsin,
            "acos": np.arccos,
            "atan": np.arctan,
            "atan2": np.arctan2,
            "hypot": np.hypot,
            "abs": np.abs,
            "floor": np.floor,
            "ceil": np.ceil,
            "min": lambda *a: functools.reduce(np.minimum, a),
            "max": lambda *a: functools.reduce(np.maximum, a),
        },
        both=np.logical_and,
        either=np.logical_or,
        negate=np.logical_not,
        short_circuit=False,
    )


# --------------------------------------------------------------------------------------------
# Closure building (the tree has been checked)
# --------------------------------------------------------------------------------------------


def _build(node: ast.expr, b: _Backend, variables: frozenset[str]) -> Fn:
    if isinstance(node, ast.Constant):
        value = b.number(float(cast(float, node.value)))
        return lambda env: value
    if isinstance(node, ast.Name):
        return _build_name(node.id, b, variables)
    if isinstance(node, ast.BinOp):
        op = b.binary[type(node.op)]
        left, right = _build(node.left, b, variables), _build(node.right, b, variables)
        return lambda env: op(left(env), right(env))
    if isinstance(node, ast.UnaryOp):
        operand = _build(node.operand, b, variables)
        if isinstance(node.op, ast.Not):
            negate = b.negate
            return lambda env: negate(operand(env))
        if isinstance(node.op, ast.USub):
            return lambda env: -operand(env)
        return operand
    if isinstance(node, ast.Call):
        assert isinstance(node.func, ast.Name)
        fn = b.functions[node.func.id]
        args = [_build(a, b, variables) for a in node.args]
        return lambda env: fn(*(a(env) for a in args))
    if isinstance(node, ast.Compare):
        return _build_compare(node, b, variables)
    if isinstance(node, ast.BoolOp):
        return _build_boolop(node, b, variables)
    raise GraderError(f"unchecked node {type(node).__name__} in a formula")  # pragma: no cover


def _build_name(name: str, b: _Backend, variables: frozenset[str]) -> Fn:
    if name in variables:
        return lambda env: env[name]
    value = b.number(CONSTANTS[name])
    return lambda env: value


def _build_compare(node: ast.Compare, b: _Backend, variables: frozenset[str]) -> Fn:
    first = _build(node.left, b, variables)
    rest = [
        (_COMPARE[type(op)], _build(c, b, variables))
        for op, c in zip(node.ops, node.comparators, strict=True)
    ]

    def run(env: Env) -> Any:
        left = first(env)
        result: Any = None
        for op, fn in rest:
            right = fn(env)
            step = op(left, right)
            result = step if result is None else b.both(result, step)
            if b.short_circuit and not result:
                return False
            left = right
        return result

    return run


def _build_boolop(node: ast.BoolOp, b: _Backend, variables: frozenset[str]) -> Fn:
    parts = [_build(v, b, variables) for v in node.values]
    is_and = isinstance(node.op, ast.And)
    join = b.both if is_and else b.either

    def run(env: Env) -> Any:
        result = parts[0](env)
        for part in parts[1:]:
            if b.short_circuit and bool(result) != is_and:
                break
            result = join(result, part(env))
        return bool(result) if b.short_circuit else result

    return run


# --------------------------------------------------------------------------------------------
# Public API
# --------------------------------------------------------------------------------------------


class Expression:
    """A checked formula, ready to evaluate.

    ``text`` is the original text, ``names`` the variables it actually uses, ``is_condition``
    whether it yields a truth value (only possible with ``logic=True``).
    """

    def __init__(
        self,
        text: str,
        tree: ast.expr,
        variables: frozenset[str],
        names: frozenset[str],
        is_condition: bool,
    ) -> None:
        self.text = text
        self.names = names
        self.is_condition = is_condition
        self._tree = tree
        self._variables = variables
        self._math = _build(tree, _MATH, variables)
        self._numpy: Fn | None = None

    def __repr__(self) -> str:
        return f"Expression({self.text!r})"

    def evaluate(self, env: Mapping[str, Any], *, backend: str = "math") -> Any:
        """Evaluate at the values in ``env`` (a mapping from each used name to its value).

        ``backend="math"``: scalars, pure Python ``math``; returns a float (a bool for a
        condition). Undefined results (division by zero, ``sqrt(-1)``, overflow, a non-finite
        result) raise :class:`AnswerFormatError` saying what failed and at which values.

        ``backend="numpy"``: values may be arrays; elementwise, errors give nan/inf; returns an
        ndarray broadcast to the shape of all of ``env``'s values together.
        """
        if backend == "math":
            return self._evaluate_math(env)
        if backend == "numpy":
            return self._evaluate_numpy(env)
        raise GraderError(f"unknown backend {backend!r}; use 'math' or 'numpy'")

    def _values(self, env: Mapping[str, Any], convert: Callable[[Any], Any]) -> Env:
        values: Env = {}
        for name in self.names:
            if name not in env:
                raise GraderError(f"no value given for '{name}' in formula {self.text!r}")
            try:
                values[name] = convert(env[name])
            except (TypeError, ValueError) as err:
                raise GraderError(f"value of '{name}' is not a number: {err}") from None
        return values

    def _evaluate_math(self, env: Mapping[str, Any]) -> Any:
        values = self._values(env, float)
        try:
            result = self._math(values)
            if not self.is_condition and not math.isfinite(result):
                raise AnswerFormatError("the result is not a finite number (overflow or 0/0)")
        except ZeroDivisionError:  # pragma: no cover - guarded above, kept as a net
            raise self._at(AnswerFormatError("division by zero"), values) from None
        except OverflowError:
            raise self._at(AnswerFormatError("the result is too large"), values) from None
        except AnswerFormatError as err:
            raise self._at(err, values) from None
        return result

    def _at(self, err: AnswerFormatError, values: Env) -> AnswerFormatError:
        if not values:
            return err
        where = ", ".join(f"{n}={_fmt(values[n])}" for n in sorted(values))
        return AnswerFormatError(f"{err} at {where}")

    def _evaluate_numpy(self, env: Mapping[str, Any]) -> Any:
        import numpy as np

        if self._numpy is None:
            self._numpy = _build(self._tree, _numpy_backend(), self._variables)
        values = self._values(env, lambda v: np.asarray(v, dtype=float))
        try:
            shape = np.broadcast_shapes(*(np.shape(v) for v in env.values()))
        except ValueError:
            raise GraderError(f"values for {self.text!r} have incompatible shapes") from None
        with np.errstate(all="ignore"):
            result = np.asarray(self._numpy(values))
        dtype = bool if self.is_condition else float
        return np.array(np.broadcast_to(result, np.broadcast_shapes(result.shape, shape)), dtype)


@functools.lru_cache(maxsize=1024)
def _compile(text: str, variables: frozenset[str], logic: bool) -> Expression:
    if len(text) > MAX_CHARS:
        raise AnswerFormatError(
            f"the formula is too long ({len(text)} characters; at most {MAX_CHARS})"
        )
    tree = _parse(text, variables, logic)
    checker = _Checker(variables, logic)
    kind = checker.check(tree)
    return Expression(text, tree, variables, frozenset(checker.used), kind == "condition")


def compile_expression(
    text: str, variables: Collection[str] = (), *, logic: bool = False
) -> Expression:
    """Check ``text`` and return an :class:`Expression`.

    Forms: ``-dx/sqrt(q)``, ``2pi/3``, ``atan2(dy, dx) - th``, ``√2/2``; with ``logic=True`` also
    conditions such as ``hypot(xj - xr, yj - yr) > 1 and not p == 0.5``. Raises
    :class:`AnswerFormatError` naming what is wrong and what is allowed, e.g.
    ``unknown name 'x'; you can use dx, dy, q, pi, e, tau``. Text that is not valid Unicode
    (lone surrogates) is refused first (:func:`~slamcourse.answers.text.decode_answer`).
    """
    return _compile(decode_answer(text), frozenset(variables), logic)


def evaluate_number(text: str) -> float:
    """Value of a constant formula with the math backend: ``"pi/4"`` → 0.7853981633974483."""
    result = compile_expression(text).evaluate({})
    return float(result)
