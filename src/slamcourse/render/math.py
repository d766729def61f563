"""LaTeX math to readable Unicode text for the terminal.

A small converter of its own (tokenizer, parser to a tiny tree, renderer) rather than pylatexenc:
pylatexenc's ``LatexNodes2Text`` loses parentheses (``\\frac{a+b}{c}`` becomes ``a+b/c``), drops
unknown macros with their arguments and keeps ``^T``/``_r`` as ASCII. This module knows what SLAM
prompts use: Greek letters, sub/superscripts (Unicode when every character has a form, else
``x_(...)``), fractions with parentheses where precedence needs them, square roots, accents,
matrices (inline ``[[1, 2], [3, 4]]``; a bracketed grid for display math), relations and
operators with normalised spacing. Unknown commands degrade to their name; nothing raises.

Imports only ``unicodedata`` at module level, so importing it costs well under a millisecond.
"""

from __future__ import annotations

import unicodedata

__all__ = ["latex_to_unicode", "text_width"]

TYPE_CHECKING = False
if TYPE_CHECKING:
    from collections.abc import Iterable

# --------------------------------------------------------------------------- symbol tables

# Atom classes; they decide the spacing between neighbours.
ORD = "ord"  # letters, numbers, most symbols
BIN = "bin"  # binary operators: + - · × ±
REL = "rel"  # relations: = ≤ ≈ → ∈ ∼
OPEN = "open"
CLOSE = "close"
PUNCT = "punct"  # , ;
BIGOP = "bigop"  # ∑ ∏ ∫
FUNC = "func"  # sin, log, atan2 via \operatorname
PREFIX = "prefix"  # ∂ Δ ∇ d: bind to the following atom (∂x is one atom)
POSTFIX = "postfix"  # ' !
TEXT = "text"  # \text{...}
SPACE = "space"
UNARY = "unary"  # a BIN in unary position (leading minus)

_GREEK = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "varepsilon": "ε",
    "zeta": "ζ", "eta": "η", "theta": "θ", "vartheta": "ϑ", "iota": "ι", "kappa": "κ",
    "lambda": "λ", "mu": "μ", "nu": "ν", "xi": "ξ", "pi": "π", "varpi": "ϖ", "rho": "ρ",
    "varrho": "ϱ", "sigma": "σ", "varsigma": "ς", "tau": "τ", "upsilon": "υ", "phi": "φ",
    "varphi": "φ", "chi": "χ", "psi": "ψ", "omega": "ω", "Gamma": "Γ", "Delta": "Δ",
    "Theta": "Θ", "Lambda": "Λ", "Xi": "Ξ", "Pi": "Π", "Sigma": "Σ", "Upsilon": "Υ",
    "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω",
}  # fmt: skip

_SYMBOLS: dict[str, tuple[str, str]] = {
    # binary operators
    "cdot": ("·", BIN), "times": ("×", BIN), "pm": ("±", BIN), "mp": ("∓", BIN),
    "div": ("÷", BIN), "ast": ("∗", BIN), "star": ("⋆", BIN), "circ": ("∘", BIN),
    "bullet": ("•", BIN), "oplus": ("⊕", BIN), "ominus": ("⊖", BIN), "otimes": ("⊗", BIN),
    "odot": ("⊙", BIN), "boxplus": ("⊞", BIN), "boxminus": ("⊟", BIN), "cup": ("∪", BIN),
    "cap": ("∩", BIN), "setminus": ("∖", BIN), "wedge": ("∧", BIN), "land": ("∧", BIN),
    "vee": ("∨", BIN), "lor": ("∨", BIN), "bmod": ("mod", REL), "mod": ("mod", REL),
    # relations
    "le": ("≤", REL), "leq": ("≤", REL), "leqslant": ("≤", REL), "ge": ("≥", REL),
    "geq": ("≥", REL), "geqslant": ("≥", REL), "ne": ("≠", REL), "neq": ("≠", REL),
    "approx": ("≈", REL), "sim": ("∼", REL), "simeq": ("≃", REL), "cong": ("≅", REL),
    "equiv": ("≡", REL), "propto": ("∝", REL), "in": ("∈", REL), "notin": ("∉", REL),
    "ni": ("∋", REL), "subset": ("⊂", REL), "subseteq": ("⊆", REL), "supset": ("⊃", REL),
    "supseteq": ("⊇", REL), "to": ("→", REL), "rightarrow": ("→", REL),
    "leftarrow": ("←", REL), "gets": ("←", REL), "leftrightarrow": ("↔", REL),
    "Rightarrow": ("⇒", REL), "Leftarrow": ("⇐", REL), "Leftrightarrow": ("⇔", REL),
    "implies": ("⟹", REL), "impliedby": ("⟸", REL), "iff": ("⟺", REL),
    "mapsto": ("↦", REL), "longrightarrow": ("⟶", REL), "longmapsto": ("⟼", REL),
    "ll": ("≪", REL), "gg": ("≫", REL), "coloneqq": ("≔", REL), "triangleq": ("≜", REL),
    "doteq": ("≐", REL), "perp": ("⊥", REL), "parallel": ("∥", REL), "mid": ("|", REL),
    "lt": ("<", REL), "gt": (">", REL), "prec": ("≺", REL), "succ": ("≻", REL),
    "preceq": ("⪯", REL), "succeq": ("⪰", REL), "models": ("⊨", REL), "vdash": ("⊢", REL),
    "uparrow": ("↑", REL), "downarrow": ("↓", REL),
    # big operators
    "sum": ("∑", BIGOP), "prod": ("∏", BIGOP), "coprod": ("∐", BIGOP), "int": ("∫", BIGOP),
    "iint": ("∬", BIGOP), "iiint": ("∭", BIGOP), "oint": ("∮", BIGOP),
    "bigcup": ("⋃", BIGOP), "bigcap": ("⋂", BIGOP), "bigoplus": ("⨁", BIGOP),
    "bigotimes": ("⨂", BIGOP), "bigvee": ("⋁", BIGOP), "bigwedge": ("⋀", BIGOP),
    # prefixes binding to the next atom
    "partial": ("∂", PREFIX), "nabla": ("∇", PREFIX), "Delta": ("Δ", PREFIX),
    "delta": ("δ", PREFIX), "neg": ("¬", PREFIX), "lnot": ("¬", PREFIX),
    # delimiters
    "langle": ("⟨", OPEN), "rangle": ("⟩", CLOSE), "lvert": ("|", OPEN), "rvert": ("|", CLOSE),
    "lVert": ("‖", OPEN), "rVert": ("‖", CLOSE), "lfloor": ("⌊", OPEN), "rfloor": ("⌋", CLOSE),
    "lceil": ("⌈", OPEN), "rceil": ("⌉", CLOSE), "lbrace": ("{", OPEN), "rbrace": ("}", CLOSE),
    "lbrack": ("[", OPEN), "rbrack": ("]", CLOSE), "vert": ("|", ORD), "Vert": ("‖", ORD),
    "{": ("{", OPEN), "}": ("}", CLOSE), "|": ("‖", ORD),
    # ordinary symbols
    "infty": ("∞", ORD), "forall": ("∀", ORD), "exists": ("∃", ORD), "nexists": ("∄", ORD),
    "emptyset": ("∅", ORD), "varnothing": ("∅", ORD), "ell": ("ℓ", ORD), "hbar": ("ℏ", ORD),
    "prime": ("′", POSTFIX), "degree": ("°", POSTFIX), "angle": ("∠", ORD), "dots": ("…", ORD),
    "ldots": ("…", ORD), "cdots": ("⋯", ORD), "vdots": ("⋮", ORD), "ddots": ("⋱", ORD),
    "top": ("⊤", ORD), "bot": ("⊥", ORD), "intercal": ("ᵀ", POSTFIX), "dagger": ("†", ORD),
    "ddagger": ("‡", ORD), "aleph": ("ℵ", ORD), "Re": ("ℜ", ORD), "Im": ("ℑ", ORD),
    "wp": ("℘", ORD), "checkmark": ("✓", ORD), "square": ("□", ORD), "triangle": ("△", ORD),
    "backslash": ("\\", ORD), "sharp": ("♯", ORD), "flat": ("♭", ORD), "S": ("§", ORD),
    "imath": ("ı", ORD), "jmath": ("ȷ", ORD), "colon": (":", PUNCT),
    # escaped characters
    "_": ("_", ORD), "%": ("%", ORD), "$": ("$", ORD), "#": ("#", ORD), "&": ("&", ORD),
}  # fmt: skip

for _name, _char in _GREEK.items():
    _SYMBOLS.setdefault(_name, (_char, ORD))

_FUNCTIONS = frozenset({
    "sin", "cos", "tan", "cot", "sec", "csc", "arcsin", "arccos", "arctan", "sinh", "cosh",
    "tanh", "coth", "exp", "log", "ln", "lg", "det", "dim", "ker", "min", "max", "sup", "inf",
    "lim", "liminf", "limsup", "arg", "deg", "gcd", "hom", "Pr", "tr", "rank", "diag", "sgn",
})  # fmt: skip

_SPACES = {
    ",": " ", ":": " ", ";": " ", ">": " ", " ": " ", "!": "", "quad": "  ", "qquad": "    ",
    "enspace": " ", "thinspace": " ", "medspace": " ", "thickspace": " ", "negthinspace": "",
    "space": " ", "hfill": " ", "hspace": " ",
}  # fmt: skip

# Commands that produce nothing (sizing, style, layout hints).
_IGNORED = frozenset({
    "displaystyle", "textstyle", "scriptstyle", "scriptscriptstyle", "limits", "nolimits",
    "nonumber", "notag", "big", "Big", "bigg", "Bigg", "bigl", "bigr", "Bigl", "Bigr", "biggl",
    "biggr", "Biggl", "Biggr", "bigm", "Bigm", "strut", "relax", "allowbreak", "centering",
    "hline", "cline", "midrule", "toprule", "bottomrule", "nobreak", "mathstrut", "tiny",
    "small", "large", "Large", "normalsize",
})  # fmt: skip

# Commands whose single argument is dropped.
_DROP_ARG = frozenset(["label", "phantom", "hphantom", "vphantom", "color", "hspace", "vspace"])

_ACCENTS = {
    "hat": "\u0302", "widehat": "\u0302", "tilde": "\u0303", "widetilde": "\u0303",
    "bar": "\u0304", "overline": "\u0305", "underline": "\u0332", "dot": "\u0307",
    "ddot": "\u0308", "dddot": "\u20db", "vec": "\u20d7", "overrightarrow": "\u20d7",
    "check": "\u030c", "breve": "\u0306", "acute": "\u0301", "grave": "\u0300",
    "mathring": "\u030a",
}  # fmt: skip

_FONTS = frozenset({
    "mathbf", "mathit", "mathsf", "mathtt", "mathnormal", "boldsymbol", "bm", "pmb", "mathbfit",
    "mathfrak", "mathscr", "ensuremath", "boxed", "mathop", "mathbin", "mathrel", "mathord",
    "mathpunct",
})  # fmt: skip
_TEXT_COMMANDS = frozenset({
    "text", "textrm", "textit", "textbf", "textsf", "texttt", "textnormal", "mbox", "hbox",
    "textup", "textmd", "emph",
})  # fmt: skip

_CAL = dict(zip("ABCDEFGHIJKLMNOPQRSTUVWXYZ", "𝒜ℬ𝒞𝒟ℰℱ𝒢ℋℐ𝒥𝒦ℒℳ𝒩𝒪𝒫𝒬ℛ𝒮𝒯𝒰𝒱𝒲𝒳𝒴𝒵", strict=True))
_BB = dict(zip("ABCDEFGHIJKLMNOPQRSTUVWXYZ1", "𝔸𝔹ℂ𝔻𝔼𝔽𝔾ℍ𝕀𝕁𝕂𝕃𝕄ℕ𝕆ℙℚℝ𝕊𝕋𝕌𝕍𝕎𝕏𝕐ℤ𝟙", strict=True))

_SUB = dict(
    zip(
        "0123456789+-−=()aehijklmnoprstuvxβγρφχ",
        "₀₁₂₃₄₅₆₇₈₉₊₋₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓᵦᵧᵨᵩᵪ",
        strict=True,
    )
)
_SUP = dict(
    zip(
        "0123456789+-−=()abcdefghijklmnoprstuvwxyzABDEGHIJKLMNOPRTUVWαβγδεθιφχ⊤∘",
        "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁻⁼⁽⁾ᵃᵇᶜᵈᵉᶠᵍʰⁱʲᵏˡᵐⁿᵒᵖʳˢᵗᵘᵛʷˣʸᶻᴬᴮᴰᴱᴳᴴᴵᴶᴷᴸᴹᴺᴼᴾᴿᵀᵁⱽᵂᵅᵝᵞᵟᵋᶿᶥᵠᵡᵀ°",
        strict=True,
    )
)
# Written after the base as they are: x*, x′, x†, 90°.
for _char in "*∗′″‴†‡°'ᵀ":
    _SUP[_char] = _char
_SUP["∗"] = "*"
_SUP["'"] = "′"

_CHAR_CLASS = {
    "+": BIN, "-": BIN, "*": BIN, "/": BIN, "·": BIN, "×": BIN, "±": BIN, "∓": BIN, "÷": BIN,
    "=": REL, "<": REL, ">": REL, "≤": REL, "≥": REL, "≠": REL, "≈": REL, "∈": REL, "→": REL,
    "←": REL, "⇒": REL, "∼": REL, "≡": REL, "∝": REL,
    "(": OPEN, "[": OPEN, ")": CLOSE, "]": CLOSE,
    ",": PUNCT, ";": PUNCT, ":": PUNCT,
    "'": POSTFIX, "!": POSTFIX, "∂": PREFIX, "∇": PREFIX,
    "∑": BIGOP, "∏": BIGOP, "∫": BIGOP,
}  # fmt: skip

_DELIMS = {
    "(": "(", ")": ")", "[": "[", "]": "]", "|": "|", ".": "", "/": "/", "<": "⟨", ">": "⟩",
    "{": "{", "}": "}", "langle": "⟨", "rangle": "⟩", "lvert": "|", "rvert": "|", "vert": "|",
    "lVert": "‖", "rVert": "‖", "Vert": "‖", "lfloor": "⌊", "rfloor": "⌋",
    "lceil": "⌈", "rceil": "⌉", "lbrace": "{", "rbrace": "}", "lbrack": "[", "rbrack": "]",
}  # fmt: skip

_MATRIX_ENVS = {
    # env: (left, right) delimiters used inline; "" for none
    "matrix": ("", ""), "smallmatrix": ("", ""), "array": ("", ""), "pmatrix": ("(", ")"),
    "bmatrix": ("[", "]"), "Bmatrix": ("{", "}"), "vmatrix": ("|", "|"),
    "Vmatrix": ("‖", "‖"), "pmatrix*": ("(", ")"), "bmatrix*": ("[", "]"),
}  # fmt: skip
_CASES_ENVS = frozenset({"cases", "dcases", "rcases", "cases*"})
_ALIGN_ENVS = frozenset({
    "aligned", "align", "align*", "alignat", "alignat*", "alignedat", "split", "gathered",
    "gather", "gather*", "eqnarray", "eqnarray*", "multline", "multline*", "flalign",
    "flalign*",
})  # fmt: skip

_CONTROL = {c: "\ufffd" for c in [*range(0x20), 0x7F, *range(0x80, 0xA0)]}
_CONTROL[0x09] = " "
_CONTROL[0x0A] = "\n"
_CONTROL[0x0D] = None  # type: ignore[assignment]


def _sanitize(text: str) -> str:
    """Replace control characters (ESC and friends) so nothing can reach the terminal raw."""
    return text.translate(_CONTROL)


def text_width(text: str) -> int:
    """Number of terminal columns ``text`` takes (combining marks 0, wide East Asian chars 2)."""
    width = 0
    for ch in text:
        if ch < "\u0300":
            width += 1
        elif unicodedata.combining(ch) or ch in "\u200b\u200c\u200d\u2060\ufeff":
            continue
        elif unicodedata.east_asian_width(ch) in "WF":
            width += 2
        else:
            width += 1
    return width


# --------------------------------------------------------------------------- tree nodes


class _Node:
    """Base of the parse tree; carries whether source whitespace preceded the node."""

    __slots__ = ("space",)

    def __init__(self) -> None:
        self.space = False  # whitespace preceded it in the source


class _Sym(_Node):
    __slots__ = ("cls", "text")

    def __init__(self, text: str, cls: str) -> None:
        super().__init__()
        self.text = text
        self.cls = cls


class _Group(_Node):
    __slots__ = ("items",)

    def __init__(self, items: list[_Node]) -> None:
        super().__init__()
        self.items = items


class _Frac(_Node):
    __slots__ = ("den", "num")

    def __init__(self, num: list[_Node], den: list[_Node]) -> None:
        super().__init__()
        self.num = num
        self.den = den


class _Sqrt(_Node):
    __slots__ = ("arg", "index")

    def __init__(self, arg: list[_Node], index: list[_Node] | None) -> None:
        super().__init__()
        self.arg = arg
        self.index = index


class _Accent(_Node):
    __slots__ = ("arg", "mark")

    def __init__(self, arg: list[_Node], mark: str) -> None:
        super().__init__()
        self.arg = arg
        self.mark = mark


class _Scripts(_Node):
    __slots__ = ("base", "sub", "sup")

    def __init__(self, base: _Node | None) -> None:
        super().__init__()
        self.base = base
        self.sub: list[_Node] | None = None
        self.sup: list[_Node] | None = None


class _Fenced(_Node):
    __slots__ = ("close", "items", "open")

    def __init__(self, open_: str, items: list[_Node], close: str) -> None:
        super().__init__()
        self.open = open_
        self.items = items
        self.close = close


class _Call(_Node):
    """``name(arg1, arg2)``: unknown commands with arguments, \\binom."""

    __slots__ = ("args", "name")

    def __init__(self, name: str, args: list[list[_Node]]) -> None:
        super().__init__()
        self.name = name
        self.args = args


class _Table(_Node):
    """A matrix-like environment: rows of cells, each a node list."""

    __slots__ = ("env", "rows")

    def __init__(self, env: str, rows: list[list[list[_Node]]]) -> None:
        super().__init__()
        self.env = env
        self.rows = rows


class _Space(_Node):
    __slots__ = ("text",)

    def __init__(self, text: str) -> None:
        super().__init__()
        self.text = text


class _Newline(_Node):
    __slots__ = ()


class _Amp(_Node):
    """An ``&`` outside any environment (column separator of an implicit alignment)."""

    __slots__ = ()


# --------------------------------------------------------------------------- lexer


class _Tok:
    __slots__ = ("end", "kind", "space", "value")

    def __init__(self, kind: str, value: str, end: int, space: bool) -> None:
        self.kind = kind  # cmd, char, {, }, ^, _, &, nl, eof
        self.value = value
        self.end = end
        self.space = space


class _TooDeep(Exception):
    """Nesting beyond what the recursive parser/renderer safely handles."""


class _Lexer:
    def __init__(self, src: str) -> None:
        self.src = src
        self.pos = 0
        self._cache: tuple[int, _Tok] | None = None

    def peek(self) -> _Tok:
        if self._cache is not None and self._cache[0] == self.pos:
            return self._cache[1]
        tok = self._scan()
        self._cache = (self.pos, tok)
        return tok

    def next(self) -> _Tok:
        tok = self.peek()
        self.pos = tok.end
        return tok

    def _scan(self) -> _Tok:
        src, pos, n = self.src, self.pos, len(self.src)
        start = pos
        while pos < n and src[pos] in " \t\n\r":
            pos += 1
        ws = pos > start
        if pos >= n:
            return _Tok("eof", "", pos, ws)
        c = src[pos]
        if c == "\\":
            if pos + 1 >= n:
                return _Tok("char", "", pos + 1, ws)
            d = src[pos + 1]
            if d.isascii() and d.isalpha():
                end = pos + 1
                while end < n and src[end].isascii() and src[end].isalpha():
                    end += 1
                return _Tok("cmd", src[pos + 1 : end], end, ws)
            if d == "\\":
                return _Tok("nl", "", pos + 2, ws)
            if d in " \t\n\r":  # control space
                return _Tok("cmd", " ", pos + 2, ws)
            return _Tok("cmd", d, pos + 2, ws)
        if c in "{}^_&":
            return _Tok(c, c, pos + 1, ws)
        return _Tok("char", c, pos + 1, ws)

    def skip_ws(self) -> None:
        while self.pos < len(self.src) and self.src[self.pos] in " \t\n\r":
            self.pos += 1

    def read_raw_group(self) -> str | None:
        """Read ``{...}`` verbatim (or one token when no brace follows); None at the end."""
        self.skip_ws()
        src, n = self.src, len(self.src)
        if self.pos >= n:
            return None
        if src[self.pos] != "{":
            tok = self.next()
            if tok.kind == "cmd":
                return "\\" + tok.value
            return tok.value if tok.kind in ("char", "^", "_", "&") else ""
        depth, i = 0, self.pos
        while i < n:
            ch = src[i]
            if ch == "\\":
                i += 2
                continue
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
                if depth == 0:
                    text = src[self.pos + 1 : i]
                    self.pos = i + 1
                    return text
            i += 1
        text = src[self.pos + 1 :]
        self.pos = n
        return text

    def read_optional(self) -> str | None:
        """Read an optional ``[...]`` argument verbatim, if present."""
        save = self.pos
        self.skip_ws()
        if self.pos < len(self.src) and self.src[self.pos] == "[":
            depth, i = 0, self.pos + 1
            while i < len(self.src):
                ch = self.src[i]
                if ch == "\\":
                    i += 2
                    continue
                if ch == "{":
                    depth += 1
                elif ch == "}":
                    depth -= 1
                elif ch == "]" and depth <= 0:
                    text = self.src[self.pos + 1 : i]
                    self.pos = i + 1
                    return text
                i += 1
        self.pos = save
        return None


# --------------------------------------------------------------------------- parser

_MAX_DEPTH = 60


class _Parser:
    def __init__(self, src: str, depth: int = 0) -> None:
        self.lx = _Lexer(src)
        self.depth = depth

    def sub(self, src: str) -> list[_Node]:
        """Parse a verbatim argument with a fresh lexer (shares the nesting budget)."""
        return _Parser(src, self.depth + 1).parse_seq(frozenset())

    def parse_seq(self, stops: frozenset[str]) -> list[_Node]:
        self.depth += 1
        if self.depth > _MAX_DEPTH:
            raise _TooDeep
        items: list[_Node] = []
        lx = self.lx
        while True:
            tok = lx.peek()
            kind = tok.kind
            if kind == "eof" or kind in stops or (kind == "cmd" and tok.value in stops):
                break
            lx.next()
            node: _Node | None
            if kind == "}":
                continue
            if kind == "&":
                node = _Amp()
            elif kind == "nl":
                lx.read_optional()
                node = _Newline()
            elif kind in ("^", "_"):
                self._attach(items, kind, self.parse_arg(), tok)
                continue
            elif kind == "{":
                node = _Group(self._group_rest())
            elif kind == "char":
                node = self._char(tok.value)
            elif tok.value in ("over", "choose"):  # infix: {a \over b}
                rest = self.parse_seq(stops)
                node = _Frac(items, rest) if tok.value == "over" else _Call("C", [items, rest])
                items = []
            else:
                node = self._command(tok.value)
            if node is None:
                continue
            node.space = tok.space
            items.append(node)
        self.depth -= 1
        return items

    def _group_rest(self) -> list[_Node]:
        """After ``{``: the items up to the matching ``}`` (consumed)."""
        items = self.parse_seq(frozenset("}"))
        if self.lx.peek().kind == "}":
            self.lx.next()
        return items

    def parse_arg(self) -> list[_Node]:
        """One macro argument: a brace group, one command (with its arguments) or one char."""
        lx = self.lx
        tok = lx.peek()
        if tok.kind == "{":
            lx.next()
            return self._group_rest()
        if tok.kind == "char":
            lx.next()
            node = self._char(tok.value, merge=False)
            return [node] if node is not None else []
        if tok.kind == "cmd" and tok.value not in ("end", "right"):
            lx.next()
            self.depth += 1
            if self.depth > _MAX_DEPTH:
                raise _TooDeep
            cmd = self._command(tok.value)
            self.depth -= 1
            return [cmd] if cmd is not None else []
        return []

    def _attach(self, items: list[_Node], kind: str, arg: list[_Node], tok: _Tok) -> None:
        which = "sub" if kind == "_" else "sup"
        base = items[-1] if items and not isinstance(items[-1], (_Space, _Newline, _Amp)) else None
        if isinstance(base, _Scripts) and getattr(base, which) is None:
            setattr(base, which, arg)
            return
        scripts = _Scripts(base)
        if base is not None:
            items.pop()
            scripts.space = base.space
        else:
            scripts.space = tok.space
        setattr(scripts, which, arg)
        items.append(scripts)

    def _char(self, c: str, merge: bool = True) -> _Node | None:
        lx = self.lx
        if not c:
            return None
        if c.isdigit() and merge:
            src, i = lx.src, lx.pos
            while i < len(src) and (
                src[i].isdigit() or (src[i] == "." and i + 1 < len(src) and src[i + 1].isdigit())
            ):
                i += 1
            c += src[lx.pos : i]
            lx.pos = i
            return _Sym(c, ORD)
        if c == "~":
            return _Space(" ")
        if c == ":" and lx.pos < len(lx.src) and lx.src[lx.pos] == "=":
            lx.pos += 1
            return _Sym(":=", REL)
        if c == "-" and lx.src.startswith("->", lx.pos - 1):
            lx.pos += 1
            return _Sym("→", REL)
        return _Sym(c, _CHAR_CLASS.get(c, ORD))

    def _delimiter(self) -> str:
        tok = self.lx.next()
        if tok.kind == "cmd" and tok.value == "|":
            return "‖"
        if tok.kind in ("char", "cmd"):
            return _DELIMS.get(tok.value, tok.value if tok.kind == "char" else "")
        if tok.kind in ("{", "}"):  # malformed, e.g. \left{
            return tok.value
        return ""

    def _command(self, name: str) -> _Node | None:
        lx = self.lx
        if name in _SYMBOLS:
            text, cls = _SYMBOLS[name]
            return _Sym(text, cls)
        if name in _FUNCTIONS:
            return _Sym(name, FUNC)
        if name in _SPACES:
            if name == "hspace":
                lx.read_raw_group()
            return _Space(_SPACES[name])
        if name in ("frac", "dfrac", "tfrac", "cfrac"):
            if name == "cfrac":
                lx.read_optional()
            return _Frac(self.parse_arg(), self.parse_arg())
        if name == "sqrt":
            opt = lx.read_optional()
            return _Sqrt(self.parse_arg(), self.sub(opt) if opt else None)
        if name in _ACCENTS:
            return _Accent(self.parse_arg(), _ACCENTS[name])
        if name in _FONTS:
            return _Group(self.parse_arg())
        if name in ("mathcal", "mathbb", "Bbb", "mathds"):
            table = _CAL if name == "mathcal" else _BB
            return _Group(_map_letters(self.parse_arg(), table))
        if name in ("mathrm", "operatorname", "mathit", "mathup"):
            star = lx.src.startswith("*", lx.pos)
            if star:
                lx.pos += 1
            raw = lx.read_raw_group() or ""
            word = raw.strip()
            if word.replace(" ", "").isalnum():
                return _Sym(word, FUNC if name == "operatorname" else ORD)
            return _Group(self.sub(raw))
        if name in _TEXT_COMMANDS:
            return _Sym(_text_mode(lx.read_raw_group() or ""), TEXT)
        if name in _IGNORED:
            return None
        if name in _DROP_ARG:
            lx.read_raw_group()
            return None
        if name == "textcolor":
            lx.read_raw_group()
            return _Group(self.parse_arg())
        if name == "left":
            return self.left()
        if name == "right":  # a stray \right: drop it with its delimiter
            self._delimiter()
            return None
        if name == "middle":
            return _Sym(self._delimiter(), ORD)
        if name == "not":
            nxt = self.parse_arg()
            text = _plain(nxt)
            negated = {"=": "≠", "∈": "∉", "≡": "≢", "∼": "≁", "⊂": "⊄", "⊆": "⊈"}
            return _Sym(negated.get(text, text + "\u0338" if text else ""), REL)
        if name in ("overset", "stackrel", "underset"):
            over = self.parse_arg()
            scripts = _Scripts(_Group(self.parse_arg()))
            if name == "underset":
                scripts.sub = over
            else:
                scripts.sup = over
            return scripts
        if name in ("underbrace", "overbrace", "ensuremath", "boxed", "mathclap", "smash"):
            return _Group(self.parse_arg())
        if name in ("binom", "dbinom", "tbinom"):
            return _Call("C", [self.parse_arg(), self.parse_arg()])
        if name == "pmod":
            return _Fenced("(mod ", self.parse_arg(), ")")
        if name in ("tag", "ref", "eqref"):
            return _Sym("(" + _text_mode(lx.read_raw_group() or "") + ")", TEXT)
        if name == "begin":
            return self._environment(lx.read_raw_group() or "")
        if name == "end":
            lx.read_raw_group()
            return None
        if name in ("newline", "cr"):
            return _Newline()
        return self._unknown(name)

    def _unknown(self, name: str) -> _Node:
        """Unknown command: its name, with brace arguments as ``name(a, b)``."""
        args: list[list[_Node]] = []
        while self.lx.peek().kind == "{" and not self.lx.peek().space:
            self.lx.next()
            args.append(self._group_rest())
        if args:
            return _Call(name, args)
        return _Sym(name, ORD if len(name) == 1 or not name.isalpha() else FUNC)

    def left(self) -> _Node:
        open_ = self._delimiter()
        items = self.parse_seq(frozenset({"right", "}", "end", "&", "nl"}))
        close = ""
        tok = self.lx.peek()
        if tok.kind == "cmd" and tok.value == "right":
            self.lx.next()
            close = self._delimiter()
        return _Fenced(open_, items, close)

    def _environment(self, env: str) -> _Node:
        lx = self.lx
        env = env.strip()
        if env in ("array", "tabular"):
            lx.read_optional()
            lx.read_raw_group()
        elif env in ("alignat", "alignat*", "alignedat"):
            lx.read_raw_group()
        else:
            lx.read_optional()
        rows: list[list[list[_Node]]] = [[]]
        stops = frozenset({"&", "nl", "end"})
        while True:
            rows[-1].append(self.parse_seq(stops))
            tok = lx.peek()
            if tok.kind == "&":
                lx.next()
            elif tok.kind == "nl":
                lx.next()
                lx.read_optional()
                rows.append([])
            else:
                break
        if lx.peek().kind == "cmd" and lx.peek().value == "end":
            lx.next()
            lx.read_raw_group()
        while rows and all(not cell for cell in rows[-1]):
            rows.pop()
        if env not in _MATRIX_ENVS and env not in _CASES_ENVS and env not in _ALIGN_ENVS:
            if len(rows) <= 1:  # equation, unknown environments: their content
                return _Group([node for cell in (rows[0] if rows else []) for node in cell])
            env = "aligned"
        return _Table(env, rows)


def _map_letters(items: list[_Node], table: dict[str, str]) -> list[_Node]:
    for node in items:
        if isinstance(node, _Sym):
            node.text = "".join(table.get(ch, ch) for ch in node.text)
        elif isinstance(node, _Group):
            _map_letters(node.items, table)
    return items


def _plain(items: list[_Node]) -> str:
    return _Renderer(display=False).seq(items)


def _text_mode(raw: str) -> str:
    """The content of ``\\text{...}``: escapes resolved, ``$...$`` inside converted."""
    out: list[str] = []
    i, n = 0, len(raw)
    while i < n:
        ch = raw[i]
        if ch == "\\" and i + 1 < n:
            d = raw[i + 1]
            if d.isascii() and d.isalpha():
                j = i + 1
                while j < n and raw[j].isascii() and raw[j].isalpha():
                    j += 1
                name = raw[i + 1 : j]
                sym = _SYMBOLS.get(name)
                out.append(sym[0] if sym else _SPACES.get(name, "" if name in _IGNORED else name))
                i = j
                continue
            out.append(" " if d in " ,;:" else "" if d == "\\" else d)
            i += 2
            continue
        if ch == "$":
            j = raw.find("$", i + 1)
            if j > i:
                out.append(_convert(raw[i + 1 : j], display=False))
                i = j + 1
                continue
        if ch in "{}":
            i += 1
            continue
        out.append(" " if ch in "~\n\t" else ch)
        i += 1
    return "".join(out)


# --------------------------------------------------------------------------- rendering


class _Box:
    """A multi-line block for display math; ``baseline`` is the row aligned with text."""

    __slots__ = ("baseline", "lines", "width")

    def __init__(self, lines: list[str], baseline: int) -> None:
        self.width = max((text_width(line) for line in lines), default=0)
        self.lines = [line + " " * (self.width - text_width(line)) for line in lines]
        self.baseline = baseline


def _klass(node: _Node) -> str:
    if isinstance(node, _Sym):
        return node.cls
    if isinstance(node, _Scripts):
        return _klass(node.base) if node.base is not None else ORD
    if isinstance(node, _Group):
        return _klass(node.items[0]) if len(node.items) == 1 else ORD
    if isinstance(node, (_Space, _Amp)):
        return SPACE
    return ORD


def _flatten(items: Iterable[_Node]) -> list[_Node]:
    out: list[_Node] = []
    for node in items:
        if isinstance(node, _Group):
            out.extend(_flatten(node.items))
        else:
            out.append(node)
    return out


def _atom_count(items: list[_Node]) -> int:
    count = 0
    glue = False  # previous was a prefix: the next atom belongs to it
    for node in items:
        cls = _klass(node)
        if cls == POSTFIX and count:
            continue
        if not glue:
            count += 1
        glue = cls == PREFIX
    return count


def _needs_parens(items: list[_Node], strict: bool) -> bool:
    """Whether ``items`` must be parenthesised as a fraction part / root / script base.

    Not strict (numerator): sums, relations, spaced products need parentheses.
    Strict (denominator, root, base): also any product of two atoms (``2σ²``).
    """
    flat = _flatten(items)
    for i, node in enumerate(flat):
        cls = _klass(node)
        if cls in (REL, PUNCT, SPACE, BIGOP) or isinstance(node, (_Newline, _Frac)):
            return True
        if cls == BIN and (i > 0 or strict):
            return True
        if cls == FUNC and len(flat) > 1:
            return True
        if cls == TEXT and isinstance(node, _Sym) and " " in node.text.strip():
            return True
        if i > 0 and node.space and _klass(flat[i - 1]) != PREFIX:
            return True
    return strict and _atom_count(flat) > 1


def _to_script(text: str, table: dict[str, str]) -> str | None:
    out = []
    for ch in text:
        mapped = table.get(ch)
        if mapped is None:
            return None
        out.append(mapped)
    return "".join(out)


def _script(text: str, sup: bool) -> str:
    if not text:
        return ""
    if not sup and text == "×":
        return "ₓ"
    converted = _to_script(text, _SUP if sup else _SUB)
    if converted is not None:
        return converted
    mark = "^" if sup else "_"
    if len(text) == 1 or text.isalnum():
        return mark + text
    return mark + "(" + text + ")"


def _combine(text: str, mark: str, first_only: bool) -> str:
    """Put the combining ``mark`` on the first base character (or on every one)."""
    out: list[str] = []
    placed = False
    i, n = 0, len(text)
    while i < n:
        ch = text[i]
        j = i + 1
        while j < n and unicodedata.combining(text[j]):
            j += 1
        out.append(text[i:j])
        if ch != " " and not unicodedata.combining(ch) and not (first_only and placed):
            out.append(mark)
            placed = True
        i = j
    return "".join(out)


_NOT_FACTOR_BEFORE = frozenset({None, BIN, UNARY, REL, PUNCT, OPEN, SPACE, BIGOP})
_NOT_FACTOR_AFTER = frozenset({None, BIN, REL, PUNCT, CLOSE, SPACE})


class _Renderer:
    def __init__(self, display: bool) -> None:
        self.display = display

    # ---- sequences
    def seq(self, items: list[_Node], compact: bool = False) -> str:
        return "".join(p for p in self.pieces(items, compact, boxes=False) if isinstance(p, str))

    def pieces(self, items: list[_Node], compact: bool, boxes: bool) -> list[str | _Box]:
        """Render a sequence with TeX-like spacing; Tables become boxes when ``boxes``."""
        rendered: list[tuple[_Node, str, str | _Box]] = []
        prev_cls: str | None = None
        for node in items:
            if isinstance(node, (_Newline, _Amp)):
                out: str | _Box = " " if isinstance(node, _Amp) else "  "
                rendered.append((node, SPACE, out))
                prev_cls = SPACE
                continue
            out = self.node(node, compact, boxes)
            if out == "":
                continue
            cls = _klass(node)
            if cls == BIN and prev_cls in (None, BIN, UNARY, REL, OPEN, PUNCT, BIGOP, SPACE):
                cls = UNARY
            rendered.append((node, cls, out))
            prev_cls = cls
        # a fraction multiplied by a neighbour is parenthesised: (1/2) xᵀ P x, 2(a/b)
        for i, (node, cls, out) in enumerate(rendered):
            if isinstance(node, _Frac) and isinstance(out, str):
                before = rendered[i - 1][1] if i > 0 else None
                after = rendered[i + 1][1] if i + 1 < len(rendered) else None
                if before not in _NOT_FACTOR_BEFORE or after not in _NOT_FACTOR_AFTER:
                    rendered[i] = (node, cls, "(" + out + ")")
        result: list[str | _Box] = []
        last_text = ""
        for i, (node, cls, out) in enumerate(rendered):
            if i > 0 and not compact:
                prev_node, prev, _ = rendered[i - 1]
                nxt = rendered[i + 1][0] if i + 1 < len(rendered) else None
                if self._space_between(prev_node, prev, node, cls, nxt):
                    first = out if isinstance(out, str) else "x"
                    if not last_text.endswith(" ") and not first.startswith(" "):
                        result.append(" ")
            result.append(out)
            last_text = out if isinstance(out, str) else "x"
        return result

    @staticmethod
    def _bin_spaced(node: _Node, nxt: _Node | None) -> bool:
        return node.space or (nxt is not None and nxt.space)

    def _space_between(
        self, left: _Node, lcls: str, right: _Node, rcls: str, after: _Node | None
    ) -> bool:
        if SPACE in (lcls, rcls) or lcls == UNARY or rcls == POSTFIX:
            return False
        if REL in (lcls, rcls):
            return True
        if rcls == BIN:
            return self._bin_spaced(right, after)
        if lcls == BIN:
            return self._bin_spaced(left, right)
        if rcls in (CLOSE, PUNCT) or lcls == OPEN:
            return False
        if lcls == PUNCT:
            return right.space
        if lcls == PREFIX:
            return False
        if lcls == FUNC:
            if right.space:
                return True
            return rcls != OPEN and not isinstance(right, _Fenced)
        return right.space  # ordinary neighbours: as the author spaced them

    # ---- nodes
    def node(self, node: _Node, compact: bool, boxes: bool = False) -> str | _Box:
        if isinstance(node, _Sym):
            return node.text
        if isinstance(node, _Space):
            return node.text
        if isinstance(node, _Group):
            if boxes:
                parts = self.pieces(node.items, compact, boxes)
                if any(isinstance(p, _Box) for p in parts):
                    return _hconcat(parts)
            return self.seq(node.items, compact)
        if isinstance(node, _Scripts):
            return self.scripts(node, compact, boxes)
        if isinstance(node, _Frac):
            num = self.seq(node.num, compact)
            den = self.seq(node.den, compact)
            if _needs_parens(node.num, strict=False):
                num = "(" + num + ")"
            if _needs_parens(node.den, strict=True):
                den = "(" + den + ")"
            return num + "/" + den
        if isinstance(node, _Sqrt):
            arg = self.seq(node.arg, compact)
            if _needs_parens(node.arg, strict=True):
                arg = "(" + arg + ")"
            index = self.seq(node.index, compact=True) if node.index else ""
            root = {"": "√", "2": "√", "3": "∛", "4": "∜"}.get(index)
            if root is None:
                root = _script(index, sup=True) + "√"
            return root + arg
        if isinstance(node, _Accent):
            text = self.seq(node.arg, compact)
            return _combine(text, node.mark, first_only=_atom_count(_flatten(node.arg)) <= 1)
        if isinstance(node, _Fenced):
            inner = [n for n in node.items if not isinstance(n, _Space)]
            if (
                len(inner) == 1
                and isinstance(inner[0], _Table)
                and inner[0].env
                in (
                    "matrix",
                    "array",
                    "smallmatrix",
                )
            ):
                return self.table(inner[0], boxes, (node.open, node.close))
            if boxes:
                parts = self.pieces(node.items, compact, boxes)
                if any(isinstance(p, _Box) for p in parts):
                    return _hconcat([node.open, *parts, node.close])
            return node.open + self.seq(node.items, compact) + node.close
        if isinstance(node, _Call):
            args = ", ".join(self.seq(arg, compact) for arg in node.args)
            return node.name + "(" + args + ")"
        if isinstance(node, _Table):
            return self.table(node, boxes, None)
        return ""

    def scripts(self, node: _Scripts, compact: bool, boxes: bool) -> str | _Box:
        base = node.base
        sup_items = node.sup
        # a column vector transposed reads best as a plain row: [x, y, θ]
        if (
            isinstance(base, _Table)
            and sup_items is not None
            and _plain(sup_items) in ("T", "⊤", "ᵀ")
            and _is_vector(base)
        ):
            return self.vector(base, transposed=True) + self.sub_text(node)
        base_out: str | _Box = "" if base is None else self.node(base, compact, boxes)
        sub = self.sub_text(node)
        sup = self.script_text(sup_items, sup=True)
        if isinstance(base_out, _Box):
            lines = list(base_out.lines)
            if len(lines) == 1:
                lines[0] += sub + sup
            else:
                lines[0] += sup
                lines[-1] += sub
            return _Box(lines, base_out.baseline)
        if base is not None and (
            isinstance(base, _Frac)
            or (isinstance(base, _Group) and _needs_parens(base.items, strict=True))
        ):
            base_out = "(" + base_out + ")"
        return base_out + sub + sup

    def sub_text(self, node: _Scripts) -> str:
        return self.script_text(node.sub, sup=False)

    def script_text(self, items: list[_Node] | None, sup: bool) -> str:
        """Unicode sub/superscript when possible, else ``_x`` / ``^(a b)`` in normal spacing."""
        if not items:
            return ""
        compact = self.seq(items, compact=True)
        if not sup and compact == "×":
            return "ₓ"
        if _to_script(compact, _SUP if sup else _SUB) is not None:
            return _script(compact, sup)
        return _script(self.seq(items), sup)

    def vector(self, table: _Table, transposed: bool) -> str:
        cells = [self.seq(row[0]) if row else "" for row in table.rows]
        return "[" + ", ".join(cells) + "]" + ("" if transposed else "ᵀ")

    def table(self, table: _Table, boxes: bool, fence: tuple[str, str] | None) -> str | _Box:
        env = table.env
        rows = [[self.seq(cell).strip() for cell in row] for row in table.rows]
        if env in _CASES_ENVS:
            delims = ("{", "")
        elif env in _ALIGN_ENVS:
            delims = ("", "")
        else:
            delims = fence if fence is not None else _MATRIX_ENVS.get(env, ("", ""))
        if boxes and (len(rows) > 1 or env in _MATRIX_ENVS):
            return _grid(rows, env, delims)
        if env in _ALIGN_ENVS:
            return "; ".join(" ".join(c for c in row if c) for row in rows)
        if env in _CASES_ENVS:
            return "{" + "; ".join(" ".join(c for c in row if c) for row in rows) + "}"
        if delims == ("", ""):  # bare matrix/array: the delimiters are around it
            return "; ".join(", ".join(row) for row in rows)
        if _is_vector(table):
            return self.vector(table, transposed=False)
        if len(rows) == 1:
            inner = ", ".join(rows[0])
        else:
            inner = ", ".join("[" + ", ".join(row) + "]" for row in rows)
        prefix = {"|": "det", "‖": "‖"}.get(delims[0], "")
        if prefix == "det":
            return "det[" + inner + "]"
        if prefix == "‖":
            return "‖[" + inner + "]‖"
        return "[" + inner + "]"


def _is_vector(table: _Table) -> bool:
    return len(table.rows) >= 2 and all(len(row) == 1 for row in table.rows)


_BRACKETS = {
    # delimiter: (single, top, middle, bottom, centre)
    "[": ("[", "⎡", "⎢", "⎣", "⎢"),
    "]": ("]", "⎤", "⎥", "⎦", "⎥"),
    "(": ("(", "⎛", "⎜", "⎝", "⎜"),
    ")": (")", "⎞", "⎟", "⎠", "⎟"),
    "{": ("{", "⎧", "⎪", "⎩", "⎨"),
    "}": ("}", "⎫", "⎪", "⎭", "⎬"),
    "|": ("|", "│", "│", "│", "│"),
    "‖": ("‖", "‖", "‖", "‖", "‖"),
}


def _bracket_column(delim: str, height: int) -> list[str]:
    if not delim:
        return [""] * height
    single, top, mid, bottom, centre = _BRACKETS.get(delim, (delim,) * 5)
    if height == 1:
        return [single]
    column = [top] + [mid] * (height - 2) + [bottom]
    if delim in "{}" and height >= 3:
        column[(height - 1) // 2] = centre
    return column


def _looks_numeric(text: str) -> bool:
    return bool(text) and all(ch in "0123456789.-+e−" for ch in text)


def _grid(rows: list[list[str]], env: str, delims: tuple[str, str]) -> _Box:
    """Lay a table out as aligned columns between tall brackets."""
    ncols = max((len(row) for row in rows), default=0)
    rows = [row + [""] * (ncols - len(row)) for row in rows] or [[]]
    widths = [max(text_width(row[c]) for row in rows) for c in range(ncols)]
    aligned = env in _ALIGN_ENVS
    lines: list[str] = []
    for row in rows:
        cells = []
        for c, cell in enumerate(row):
            pad = widths[c] - text_width(cell)
            if aligned:
                cells.append(" " * pad + cell if c % 2 == 0 else cell + " " * pad)
            elif env in _CASES_ENVS:
                cells.append(cell + " " * pad)
            elif all(_looks_numeric(r[c]) or not r[c] for r in rows):
                cells.append(" " * pad + cell)
            else:
                cells.append(" " * (pad // 2) + cell + " " * (pad - pad // 2))
        lines.append((" " if aligned else "  ").join(cells))
    height = len(lines)
    left = _bracket_column(delims[0], height)
    right = _bracket_column(delims[1], height)
    out = []
    for i, line in enumerate(lines):
        text = line
        if delims[0]:
            text = left[i] + " " + text
        if delims[1]:
            text = text + " " + right[i]
        out.append(text)
    return _Box(out, (height - 1) // 2)


def _hconcat(parts: list[str | _Box]) -> _Box:
    boxes = [p if isinstance(p, _Box) else _Box([p], 0) for p in parts]
    above = max((b.baseline for b in boxes), default=0)
    below = max((len(b.lines) - 1 - b.baseline for b in boxes), default=0)
    lines = [""] * (above + below + 1)
    for box in boxes:
        top = above - box.baseline
        blank = " " * box.width
        for r in range(len(lines)):
            k = r - top
            lines[r] += box.lines[k] if 0 <= k < len(box.lines) else blank
    return _Box(lines, above)


# --------------------------------------------------------------------------- entry point


def _fallback(tex: str) -> str:
    """Last resort for pathological input: strip the markup characters."""
    return " ".join(tex.replace("\\", "").replace("{", "").replace("}", "").split())


def _convert(tex: str, display: bool) -> str:
    parser = _Parser(tex)
    items = parser.parse_seq(frozenset())
    renderer = _Renderer(display)
    if not display:
        return renderer.seq(items).replace("\n", " ").strip()
    rows: list[list[list[_Node]]] = [[[]]]
    for node in items:
        if isinstance(node, _Newline):
            rows.append([[]])
        elif isinstance(node, _Amp):
            rows[-1].append([])
        else:
            rows[-1][-1].append(node)
    while rows and all(not cell for cell in rows[-1]):
        rows.pop()
    if len(rows) > 1 or any(len(row) > 1 for row in rows):
        laid = renderer.table(_Table("aligned", rows), True, None)
        box = laid if isinstance(laid, _Box) else _Box([laid], 0)
    else:
        parts = renderer.pieces(items, compact=False, boxes=True)
        box = _hconcat(parts)
    lines = [line.rstrip() for line in box.lines]
    while lines and not lines[0].strip():
        lines.pop(0)
    while lines and not lines[-1].strip():
        lines.pop()
    indent = min((len(line) - len(line.lstrip(" ")) for line in lines if line.strip()), default=0)
    return "\n".join(line[indent:] for line in lines)


def latex_to_unicode(tex: str, *, display: bool = False) -> str:
    """Convert LaTeX math (the inside of ``$...$``) to readable Unicode text.

    ``display=True`` (for ``$$...$$``) may return several lines: matrices become bracketed
    grids with aligned columns and ``\\\\`` / ``&`` lay out aligned rows. Inline results are
    always one line. Unknown commands degrade to their name; the function never raises.

    >>> latex_to_unicode(r"d^2 = \\nu^T S^{-1} \\nu")
    'd² = νᵀ S⁻¹ ν'
    """
    tex = _sanitize(tex)
    try:
        return _convert(tex, display)
    except (_TooDeep, RecursionError):
        return _fallback(tex)
