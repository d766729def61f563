"""Tests of the terminal renderer (slamcourse.render): exact text a learner sees."""

from __future__ import annotations

import io
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.render import (
    latex_to_unicode,
    render_code_listing,
    render_markdown,
    style,
    terminal_width,
    use_color,
)

ANSI = re.compile(r"\x1b\[[0-9;]*m")


def strip_ansi(text: str) -> str:
    return ANSI.sub("", text)


# --------------------------------------------------------------------------- latex_to_unicode

LATEX_CASES = [
    # the formulas SLAM prompts use
    (r"\nu = z - h(x)", "ν = z - h(x)"),
    (r"d^2 = \nu^T S^{-1} \nu", "d² = νᵀ S⁻¹ ν"),
    (r"\frac{\partial r}{\partial x_r} = -\frac{\Delta x}{\sqrt{q}}", "∂r/∂xᵣ = -Δx/√q"),
    (r"\sqrt{\Delta x^2 + \Delta y^2}", "√(Δx² + Δy²)"),
    (r"E = [t]_\times R", "E = [t]ₓ R"),
    (r"x_{k+1} = f(x_k, u_k) + w_k", "xₖ₊₁ = f(xₖ, uₖ) + wₖ"),
    (r"x \sim \mathcal{N}(\mu, \Sigma)", "x ∼ 𝒩(μ, Σ)"),
    (r"\Sigma = \Sigma^\top", "Σ = Σᵀ"),
    (r"\theta \in [-\pi, \pi)", "θ ∈ [-π, π)"),
    (r"\phi \omega \Omega \xi \epsilon", "φ ω Ω ξ ε"),
    (r"K = \Sigma H^T S^{-1}", "K = Σ Hᵀ S⁻¹"),
    (r"\Omega\mu", "Ωμ"),
    # sub/superscripts: Unicode when every character has a form, else readable ASCII
    (r"x_r", "xᵣ"),
    (r"x_{r}", "xᵣ"),
    (r"x_b", "x_b"),
    (r"P_{k|k-1}", "P_(k|k-1)"),
    (r"x_{\text{odom}}", "x_odom"),
    (r"J^{-T}", "J⁻ᵀ"),
    (r"x^*", "x*"),
    (r"90^\circ", "90°"),
    (r"\sum_{i=1}^n x_i", "∑ᵢ₌₁ⁿ xᵢ"),
    # fractions: parentheses only where precedence needs them
    (r"\frac{a}{b}", "a/b"),
    (r"\frac{a+b}{c}", "(a+b)/c"),
    (r"\frac{1}{2\sigma^2}", "1/(2σ²)"),
    (r"\frac{1}{2} x^T P x", "(1/2) xᵀ P x"),
    (r"\sqrt{q}", "√q"),
    (r"\sqrt[3]{x}", "∛x"),
    # accents and fonts
    (r"\hat{t}", "t̂"),
    (r"\tilde{x}", "x̃"),
    (r"\bar{x}", "x̄"),
    (r"\hat{x}_k", "x̂ₖ"),
    (r"\mathbf{x}", "x"),
    (r"\mathbb{R}^3", "ℝ³"),
    (r"\mathrm{atan2}(y, x)", "atan2(y, x)"),
    (r"\operatorname{atan2}(\Delta y, \Delta x)", "atan2(Δy, Δx)"),
    (r"\cos\theta - \sin\theta", "cos θ - sin θ"),
    # operators, relations, spacing commands, text
    (r"a \cdot b \times c \pm d", "a · b × c ± d"),
    (r"a \approx b \le c \ge d \ne e \to \infty", "a ≈ b ≤ c ≥ d ≠ e → ∞"),
    (r"\prod_i p_i", "∏ᵢ pᵢ"),
    (r"\left( a + b \right)^2", "(a + b)²"),
    (r"a \quad b \, c \; d", "a  b c d"),
    (r"x = 1 \text{ if } y", "x = 1 if y"),
    (r"\not\in", "∉"),
    # matrices inline
    (r"\begin{bmatrix} 1 & 2 \\ 3 & 4 \end{bmatrix}", "[[1, 2], [3, 4]]"),
    (r"\begin{pmatrix} a & b \end{pmatrix}", "[a, b]"),
    (r"\begin{bmatrix} x_r \\ y_r \\ \theta_r \end{bmatrix}", "[xᵣ, yᵣ, θᵣ]ᵀ"),
    (r"\begin{bmatrix} x \\ y \end{bmatrix}^T", "[x, y]"),
    # unknown commands degrade to their name
    (r"\foo{x} + \qux", "foo(x) + qux"),
    (r"\unknowncmd", "unknowncmd"),
]


@pytest.mark.parametrize(("tex", "expected"), LATEX_CASES)
def test_latex_to_unicode(tex: str, expected: str) -> None:
    assert latex_to_unicode(tex) == expected


def test_display_matrix_is_a_bracketed_grid_with_aligned_columns() -> None:
    tex = (
        r"H = \begin{bmatrix} -\frac{\Delta x}{\sqrt{q}} & -\frac{\Delta y}{\sqrt{q}} & 0 \\"
        r" \frac{\Delta y}{q} & -\frac{\Delta x}{q} & -1 \end{bmatrix}"
    )
    assert latex_to_unicode(tex, display=True) == (
        "H = ⎡ -Δx/√q  -Δy/√q   0 ⎤\n"
        "    ⎣  Δy/q   -Δx/q   -1 ⎦"
    )  # fmt: skip


def test_display_three_row_vector_and_transposed_inverse() -> None:
    assert latex_to_unicode(r"t = \begin{bmatrix} 1 \\ 2 \\ 3 \end{bmatrix}", display=True) == (
        "    ⎡ 1 ⎤\n"
        "t = ⎢ 2 ⎥\n"
        "    ⎣ 3 ⎦"
    )  # fmt: skip
    tex = r"\Sigma^{-1} = \begin{bmatrix} 1.5 & 0.25 \\ 0.25 & 10 \end{bmatrix}^{-1}"
    assert latex_to_unicode(tex, display=True) == (
        "Σ⁻¹ = ⎡  1.5  0.25 ⎤⁻¹\n"
        "      ⎣ 0.25    10 ⎦"
    )  # fmt: skip


def test_display_aligned_rows() -> None:
    tex = r"\begin{aligned} \Delta x &= x_j - x_r \\ q &= \Delta x^2 + \Delta y^2 \end{aligned}"
    assert latex_to_unicode(tex, display=True) == "Δx = xⱼ - xᵣ\n q = Δx² + Δy²"


@pytest.mark.parametrize(
    "tex", [r"\frac{", r"x^", r"\left(", r"\begin{bmatrix} 1 &", "}}{{", "\\", r"\sqrt[3"]
)
def test_malformed_latex_degrades_without_raising(tex: str) -> None:
    out = latex_to_unicode(tex)
    assert "\\" not in out
    assert "\n" not in out


def test_deep_nesting_falls_back_instead_of_recursing_forever() -> None:
    assert latex_to_unicode("{" * 2000 + "x" + "}" * 2000) == "x"
    assert "x" in latex_to_unicode(r"\frac" * 2000 + "x")


# --------------------------------------------------------------------------- render_markdown


def test_slam_paragraph_with_inline_math() -> None:
    md = r"The innovation $\nu = z - h(x)$ and $d^2 = \nu^T S^{-1} \nu$."
    out = render_markdown(md, width=80)
    assert out == "The innovation ν = z - h(x) and d² = νᵀ S⁻¹ ν."
    assert "$" not in out
    assert "\\" not in out


def test_math_with_star_and_underscore_is_not_eaten_by_emphasis() -> None:
    md = r"Both $x^*$ and $y_*$ are *optimal*, __$a_b$ is strong__ and $p_i * q_j$ stays."
    assert render_markdown(md, width=80) == (
        "Both x* and y_* are optimal, a_b is strong and pᵢ * qⱼ stays."
    )
    colored = render_markdown(md, width=80, color=True)
    assert "\x1b[3moptimal\x1b[0m" in colored
    assert "\x1b[1ma_b is strong\x1b[0m" in colored


def test_headings_paragraphs_and_rules() -> None:
    md = "# The state\n\nSome *prose*.\n\n## Covariance\n\n### Detail\n\nText\n\n---\n\nEnd"
    assert render_markdown(md, width=40) == (
        "The state\n"
        "═════════\n"
        "\n"
        "Some prose.\n"
        "\n"
        "Covariance\n"
        "──────────\n"
        "\n"
        "Detail\n"
        "\n"
        "Text\n"
        "\n"
        "────────────────────────────────────────\n"
        "\n"
        "End"
    )  # fmt: skip


def test_lists_wrap_with_hanging_indent() -> None:
    md = (
        "- a bullet item that is long enough to need wrapping at forty columns\n"
        "- second, with $q = \\Delta x^2 + \\Delta y^2$\n"
        "  1. nested one\n"
        "  2. nested two\n"
        "\n"
        "9. nine\n"
        "10. ten\n"
    )
    assert render_markdown(md, width=40) == (
        "• a bullet item that is long enough to\n"
        "  need wrapping at forty columns\n"
        "• second, with q = Δx² + Δy²\n"
        "  1. nested one\n"
        "  2. nested two\n"
        "\n"
        " 9. nine\n"
        "10. ten"
    )  # fmt: skip


def test_nested_bullets_change_marker_and_loose_lists_keep_blank_lines() -> None:
    md = "- outer\n  - inner\n\n"
    assert render_markdown(md) == "• outer\n  ◦ inner"
    assert render_markdown("- one\n\n- two\n") == "• one\n\n• two"


def test_code_blocks_are_indented_not_wrapped() -> None:
    long_line = "x = " + " + ".join(["value"] * 12)
    md = f"Code:\n\n```python\n{long_line}\n    return x\n```\n\n    indented block\n"
    assert render_markdown(md, width=40) == (
        f"Code:\n\n    {long_line}\n        return x\n\n    indented block"
    )


def test_blockquote_table_link_and_inline_code() -> None:
    md = (
        "> A quoted remark with $\\Sigma^{-1}$ in it, wrapped.\n"
        "\n"
        "| key | value |\n"
        "|-----|------:|\n"
        "| `n` | 10 |\n"
        "| dim | 3 |\n"
        "\n"
        "See [the guide](https://example.org/guide) or <https://example.org>."
    )
    assert render_markdown(md, width=30) == (
        "│ A quoted remark with Σ⁻¹ in\n"
        "│ it, wrapped.\n"
        "\n"
        "key  value\n"
        "───  ─────\n"
        "`n`     10\n"
        "dim      3\n"
        "\n"
        "See the guide\n"
        "(https://example.org/guide) or\n"
        "https://example.org."
    )  # fmt: skip


def test_wide_table_wraps_cells() -> None:
    md = "| key | meaning |\n|---|---|\n| `id` | " + "word " * 12 + "|\n"
    assert render_markdown(md, width=30) == (
        "key   meaning\n"
        "────  ────────────────────────\n"
        "`id`  word word word word word\n"
        "      word word word word word\n"
        "      word word"
    )  # fmt: skip


def test_display_math_block_is_indented() -> None:
    md = (
        "Where\n\n$$\nd^2 = \\nu^T S^{-1} \\nu\n$$\n\n"
        "and\n\n$$\\begin{bmatrix} 1 & 2 \\\\ 3 & 4 \\end{bmatrix}$$"
    )
    assert render_markdown(md) == (
        "Where\n\n    d² = νᵀ S⁻¹ ν\n\nand\n\n    ⎡ 1  2 ⎤\n    ⎣ 3  4 ⎦"
    )


def test_display_math_inside_a_paragraph_breaks_it() -> None:
    md = "The essential matrix\n$$\nE = [t]_\\times R\n$$\nrelates the two views."
    assert render_markdown(md) == (
        "The essential matrix\n\n    E = [t]ₓ R\n\nrelates the two views."
    )


def test_labelled_display_math() -> None:
    assert render_markdown("$$x = 1$$ (eq-one)") == "    x = 1    (eq-one)"


def test_wrapping_never_splits_a_math_span() -> None:
    spans = [
        r"\nu = z - h(x)",
        r"d^2 = \nu^T S^{-1} \nu",
        r"\frac{\partial r}{\partial x_r} = -\frac{\Delta x}{\sqrt{q}}",
        r"\sqrt{\Delta x^2 + \Delta y^2}",
    ]
    md = " ".join(
        f"word number {i} then ${tex}$ and more filler text" for i, tex in enumerate(spans)
    )
    rendered = [latex_to_unicode(tex) for tex in spans]
    for width in range(10, 81, 7):
        out = render_markdown(md, width=width)
        lines = out.splitlines()
        for math in rendered:
            assert any(math in line for line in lines), (width, math, out)
        for line in lines:
            assert len(line) <= width or any(math in line for math in rendered), (width, line)


def test_front_matter_is_skipped() -> None:
    md = "---\nid: state\ntitle: The state vector\n---\n\nProse starts here."
    assert render_markdown(md) == "Prose starts here."


def test_exercise_directive_calls_back_in_order() -> None:
    md = (
        "Intro.\n\n```{exercise} state/size\n```\n\nMiddle.\n\n"
        "```{exercise}   state/cov  \n```\n\nEnd."
    )
    calls: list[str] = []

    def exercise(ex_id: str) -> str:
        calls.append(ex_id)
        return f"[{ex_id}]\nprompt line\n"

    assert render_markdown(md, exercise=exercise) == (
        "Intro.\n\n[state/size]\nprompt line\n\nMiddle.\n\n[state/cov]\nprompt line\n\nEnd."
    )
    assert calls == ["state/size", "state/cov"]
    assert render_markdown(md) == "Intro.\n\nMiddle.\n\nEnd."


def test_color_false_has_no_escape_codes_and_color_true_does() -> None:
    md = "# Head\n\n*em* **strong** `code` [l](https://x.org) $x_r$\n\n> quote\n\n---\n"
    plain = render_markdown(md, color=False)
    colored = render_markdown(md, color=True)
    assert "\x1b" not in plain
    assert "\x1b[" in colored
    assert strip_ansi(colored) == plain


def test_control_characters_in_input_never_reach_the_terminal() -> None:
    out = render_markdown("evil \x1b[31mred\x1b[0m and $\x1b x$", color=False)
    assert "\x1b" not in out
    assert "\x1b" not in latex_to_unicode("\x1b[2J")


# --------------------------------------------------------------------------- code listing


def test_code_listing_with_line_numbers_and_highlight() -> None:
    code = "const dx = xj - xr;\nconst dy = yj - yr;\n\nconst d2 = dx * dx + dy;\n"
    assert render_code_listing(code, highlight=4) == (
        "  1 │ const dx = xj - xr;\n"
        "  2 │ const dy = yj - yr;\n"
        "  3 │\n"
        "> 4 │ const d2 = dx * dx + dy;"
    )  # fmt: skip
    wide = render_code_listing("\n".join(f"line{i}" for i in range(1, 12)), highlight=10)
    assert wide.splitlines()[5] == "   6 │ line6"
    assert wide.splitlines()[9] == "> 10 │ line10"


def test_code_listing_color() -> None:
    out = render_code_listing("a = 1\nb = 2", highlight=2, color=True)
    assert out == "\x1b[2m  1 │\x1b[0m a = 1\n\x1b[1;33m> 2 │\x1b[0m\x1b[1m b = 2\x1b[0m"
    assert "\x1b" not in render_code_listing("a = 1", highlight=1)


# --------------------------------------------------------------------------- colour decisions


class FakeTTY(io.StringIO):
    def isatty(self) -> bool:
        return True


@pytest.fixture
def clean_env(monkeypatch: pytest.MonkeyPatch) -> pytest.MonkeyPatch:
    for name in ("NO_COLOR", "FORCE_COLOR", "TERM", "COLUMNS"):
        monkeypatch.delenv(name, raising=False)
    return monkeypatch


def test_use_color_tty_and_non_tty(clean_env: pytest.MonkeyPatch) -> None:
    clean_env.setenv("TERM", "xterm-256color")
    assert use_color(FakeTTY()) is True
    assert use_color(io.StringIO()) is False


def test_use_color_no_color_and_dumb_terminal(clean_env: pytest.MonkeyPatch) -> None:
    clean_env.setenv("NO_COLOR", "1")
    assert use_color(FakeTTY()) is False
    clean_env.setenv("FORCE_COLOR", "1")
    assert use_color(FakeTTY()) is False  # NO_COLOR wins
    clean_env.delenv("NO_COLOR")
    clean_env.delenv("FORCE_COLOR")
    clean_env.setenv("TERM", "dumb")
    assert use_color(FakeTTY()) is False


def test_force_color(clean_env: pytest.MonkeyPatch) -> None:
    clean_env.setenv("FORCE_COLOR", "1")
    assert use_color(io.StringIO()) is True
    clean_env.setenv("TERM", "dumb")
    assert use_color(io.StringIO()) is True


def test_style() -> None:
    assert style("hi", "bold", "red", color=False) == "hi"
    assert style("hi", "bold", "red", color=True) == "\x1b[1;31mhi\x1b[0m"
    assert style("hi", color=True) == "hi"
    with pytest.raises(ValueError, match="unknown style"):
        style("hi", "blod", color=True)


def test_terminal_width_is_clamped(clean_env: pytest.MonkeyPatch) -> None:
    clean_env.setenv("COLUMNS", "20")
    assert terminal_width(io.StringIO()) == 40
    clean_env.setenv("COLUMNS", "72")
    assert terminal_width(io.StringIO()) == 72
    clean_env.setenv("COLUMNS", "300")
    assert terminal_width(io.StringIO()) == 100
    clean_env.delenv("COLUMNS")
    assert 40 <= terminal_width(io.StringIO()) <= 100


# --------------------------------------------------------------------------- properties

LATEXISH = st.lists(
    st.sampled_from(
        [
            *"\\{}^_&$ ab12()[]|.,=+-*'~%\n",
            *[r"\frac", r"\sqrt", r"\left", r"\right", r"\begin{bmatrix}", r"\end{bmatrix}"],
            *[r"\\", r"\text", r"\hat", r"\begin{aligned}", r"\not", r"\mathrm", r"\foo", "\x1b"],
        ]
    ),
    max_size=40,
).map("".join)
MARKDOWNISH = st.lists(
    st.sampled_from(
        [
            *"*_`$[]()#>-|\\ \nab1.!<~",
            *["$$", "\n\n", "- ", "1. ", "```", "---\n", "](http://x)", "\x1b", r"\frac", "^"],
        ]
    ),
    max_size=60,
).map("".join)


@settings(max_examples=200, deadline=None)
@given(st.one_of(st.text(), LATEXISH), st.booleans())
def test_latex_to_unicode_never_raises(tex: str, display: bool) -> None:
    out = latex_to_unicode(tex, display=display)
    assert "\x1b" not in out
    if not display:
        assert "\n" not in out


@settings(max_examples=200, deadline=None)
@given(st.one_of(st.text(), MARKDOWNISH), st.integers(min_value=1, max_value=120))
def test_render_markdown_never_raises_and_plain_has_no_escapes(md: str, width: int) -> None:
    plain = render_markdown(md, width=width, color=False)
    assert "\x1b" not in plain
    assert strip_ansi(render_markdown(md, width=width, color=True)) == plain


def _through_the_parser(md: str, width: int, color: bool) -> str:
    from slamcourse.render import terminal

    tree = terminal._parse_tree(md)
    lines = terminal._Markdown(color, None, None).blocks(tree.children, max(1, width))
    return "\n".join(line.rstrip() for line in lines)


_WORD = st.text(st.sampled_from("abcXYZ019,.;:'\"?!%/@^{}()πχ²éー"), min_size=1, max_size=9)
_LINE = st.lists(_WORD, min_size=1, max_size=9).map(" ".join)
_PARAGRAPH = st.lists(_LINE, min_size=1, max_size=3).map("\n".join)
_PLAIN = st.lists(_PARAGRAPH, min_size=1, max_size=3).map("\n\n".join)
_MARKDOWN = [*"*_`$[]<>#&\\|~+-=\t\n ", "\n\n", "1. ", "2) ", "\u2003", "\u00a0", "\x1b", "\u00ad"]


@st.composite
def _plainish(draw: st.DrawFn) -> str:
    """Plain text, sometimes with one piece of what makes text Markdown put in somewhere."""
    text = draw(_PLAIN)
    if draw(st.booleans()):
        at = draw(st.integers(0, len(text)))
        text = text[:at] + draw(st.sampled_from(_MARKDOWN)) + text[at:]
    return text


_PLAINISH = _plainish()


@given(_PLAINISH, st.integers(1, 90), st.booleans())
@settings(max_examples=400, deadline=None)
def test_plain_text_is_rendered_as_the_markdown_parser_renders_it(
    md: str, width: int, color: bool
) -> None:
    """Feedback that is plain text skips the Markdown parser (and its import, ~25 ms of a
    learner's first check); whatever it accepts must come out exactly as the parser's tree of
    it would, and anything with Markdown's syntax goes to the parser."""
    from slamcourse.render import terminal

    if terminal._plain_paragraphs(md) is not None:
        assert render_markdown(md, width=width, color=color) == _through_the_parser(
            md, width, color
        )


def test_the_plain_path_takes_feedback_and_leaves_markdown_to_the_parser() -> None:
    from slamcourse.render import terminal

    plain = "All 120 test inputs passed, edge cases and boundary inputs included.\n\nχ² is 14806."
    assert terminal._plain_paragraphs(plain) is not None
    for md in (
        "`f` returns",
        "x *y*",
        "1. a",
        "a\n===",
        "a  \nb",
        "    code",
        "a\n\n\nb",
        "a &amp; b",
    ):
        assert terminal._plain_paragraphs(md) is None, md
