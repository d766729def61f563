"""Terminal rendering: Markdown prose and prompts with LaTeX math as plain or ANSI-styled text.

Importing this package is cheap (no markdown-it until the first :func:`render_markdown` call).
"""

from slamcourse.render.math import latex_to_unicode
from slamcourse.render.terminal import (
    render_code_listing,
    render_markdown,
    style,
    terminal_width,
    use_color,
)

__all__ = [
    "latex_to_unicode",
    "render_code_listing",
    "render_markdown",
    "style",
    "terminal_width",
    "use_color",
]
