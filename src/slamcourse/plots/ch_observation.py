"""Chapter ``observation``: the range-bearing geometry and the sparsity of its Jacobian."""

from __future__ import annotations

import math

from slamcourse.plots.canvas import INK, MUTED, legend_box, text_width
from slamcourse.plots.geometry import observation_geometry
from slamcourse.plots.picture import Figure, Picture, answer, given
from slamcourse.plots.svg import document, el, text

LESSON = (2.0, 3.0, math.pi / 4, 5.0, 7.0)  # the chapter's robot (x, y, θ) and landmark (x, y)
FIGURE = (1.0, 1.0, 0.5, 4.0, 5.0)  # the prose figure's: not the exercises', whose answer it is


def jacobian_columns(landmarks: int, observed: int) -> str:
    """Which columns of the 2 × (3 + 2N) Jacobian of one range-bearing measurement of landmark
    ``observed`` (from 1) are non-zero: the pose's three and that landmark's two."""
    n = 3 + 2 * landmarks
    cell = min(30.0, 460.0 / n)
    x0, y0 = 72.0, 70.0
    title = f"H = ∂h/∂x for one measurement of landmark {observed}"
    body = [
        text(
            20,
            24,
            title,
            fill=INK,
            font_weight="bold",
        )
    ]
    names = ["x_r", "y_r", "θ_r"] + [f"{a}{j + 1}" for j in range(landmarks) for a in ("x", "y")]
    nonzero = set(range(3)) | {3 + 2 * (observed - 1), 4 + 2 * (observed - 1)}
    for c in range(n):
        cx = x0 + c * cell
        body.append(
            text(cx + cell / 2, y0 - 8, names[c], text_anchor="middle", fill=MUTED, font_size="10")
        )
        for r in range(2):
            filled = c in nonzero
            body.append(
                el(
                    "rect",
                    x=cx + 0.5,
                    y=y0 + r * cell + 0.5,
                    width=cell - 1,
                    height=cell - 1,
                    fill="#1f4e79" if filled else "#fff",
                    stroke="#bbb",
                )
            )
            if not filled:
                body.append(
                    text(
                        cx + cell / 2,
                        y0 + r * cell + cell / 2 + 4,
                        "0",
                        text_anchor="middle",
                        fill="#999",
                        font_size="10",
                    )
                )
    for r, name in enumerate(("range r", "bearing φ")):
        body.append(
            text(
                x0 - 6,
                y0 + r * cell + cell / 2 + 4,
                name,
                text_anchor="end",
                fill=MUTED,
                font_size="10",
            )
        )
    body += legend_box([("may be non-zero", "#1f4e79", "marker:square")], x0, y0 + 2 * cell + 16)
    width = max(x0 + n * cell + 30, 20 + text_width(title, 13))
    desc = (
        f"The Jacobian of one range-bearing measurement of landmark {observed} in a state with "
        f"a pose and {landmarks} landmarks has 2 rows and {n} columns. Only the 3 pose columns "
        f"and the 2 columns of landmark {observed} can be non-zero; the other {n - 5} columns "
        "are zero."
    )
    return document(width, y0 + 2 * cell + 60, "Sparsity of the measurement Jacobian", desc, body)


FIGURES: dict[str, Figure] = {
    "observation/range-bearing": lambda: observation_geometry(*FIGURE),
    "observation/jacobian-sparsity": lambda: jacobian_columns(3, 2),
}

PICTURES: dict[str, Picture] = {
    "observation/jacobian": given(lambda p: observation_geometry(*LESSON)),
    # which columns are non-zero is what the exercise asks
    "observation/jacobian-columns": answer(
        lambda p: jacobian_columns(int(p["num_landmarks"]), int(p["observed"]))
    ),
}
