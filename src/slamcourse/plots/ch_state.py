"""Chapter ``state``: the state vector and its covariance Σ, drawn in blocks."""

from __future__ import annotations

from slamcourse.plots.matrix import matrix_legend, matrix_panel
from slamcourse.plots.picture import Figure, Params, Picture, answer, given
from slamcourse.plots.svg import document, text

STYLES = {
    "pose": ("#1f4e79", "pose block Σ_RR"),
    "landmark": ("#2e7d32", "landmark block Σ_jj"),
    "cross": ("#9cc3e6", "pose–landmark Σ_Rj"),
    "between": ("#c9e3c0", "landmark–landmark Σ_jk"),
}
MAX_SHOWN = 4


def block_kinds(pose_dim: int, landmark_dim: int, landmarks: int) -> dict[tuple[int, int], str]:
    """The kind of every cell of Σ: which pair of blocks (pose, landmark j) it links."""

    def owner(i: int) -> int:  # -1: the pose, else the landmark's number from 0
        return -1 if i < pose_dim else (i - pose_dim) // landmark_dim

    n = pose_dim + landmark_dim * landmarks
    kinds = {}
    for i in range(n):
        for j in range(n):
            a, b = owner(i), owner(j)
            if a == b:
                kinds[(i, j)] = "pose" if a < 0 else "landmark"
            else:
                kinds[(i, j)] = "cross" if min(a, b) < 0 else "between"
    return kinds


def covariance_blocks(pose_dim: int, landmark_dim: int, landmarks: int) -> str:
    """Σ of a state with one pose of ``pose_dim`` numbers and ``landmarks`` landmarks of
    ``landmark_dim`` numbers each (at most 4 drawn), every cell shaded by the blocks it links."""
    shown = min(landmarks, MAX_SHOWN)
    n_shown = pose_dim + landmark_dim * shown
    kinds = block_kinds(pose_dim, landmark_dim, shown)
    cell = min(22.0, 260.0 / n_shown)
    blocks = [("x_R", pose_dim)] + [(f"m{j + 1}", landmark_dim) for j in range(shown)]
    body = matrix_panel(70, 60, n_shown, cell, kinds, STYLES, blocks=blocks, caption="Σ")
    x_leg = 70 + cell * n_shown + 24
    body += matrix_legend(STYLES, set(kinds.values()), x_leg, 60)
    counts = {k: sum(1 for v in kinds.values() if v == k) for k in STYLES}
    note = (
        f"the first {shown} of {landmarks} landmarks drawn"
        if landmarks > shown
        else "one cell per entry; the lines separate the blocks"
    )
    body.append(text(70, 60 + cell * n_shown + 24, note, fill="#555", font_size="11"))
    width = x_leg + 200
    height = 60 + cell * n_shown + 40
    desc = (
        f"The covariance of a state with a {pose_dim}-number pose and {shown} landmarks of "
        f"{landmark_dim} numbers: a {n_shown} × {n_shown} matrix. The pose block holds "
        f"{counts['pose']} entries, the landmarks' own blocks {counts['landmark']}, the "
        f"pose–landmark blocks {counts['cross']} and the landmark–landmark blocks "
        f"{counts['between']}."
        + (f" Only {shown} of the {landmarks} landmarks are drawn." if landmarks > shown else "")
    )
    return document(width, height, "The covariance Σ in blocks", desc, body)


def _blocks(p: Params) -> str:
    return covariance_blocks(int(p["pose_dim"]), int(p["landmark_dim"]), int(p["num_landmarks"]))


FIGURES: dict[str, Figure] = {
    # four landmarks: the state-vector-size exercise asks about the chapter's three
    "state/covariance-blocks": lambda: covariance_blocks(3, 2, 4),
}

PICTURES: dict[str, Picture] = {
    # the drawing is the layout whose entries these exercises count: shown once solved
    "state/state-vector-size": answer(_blocks),
    "state/covariance-entries": answer(_blocks),
    "state/covariance-entries-3d": answer(_blocks),
    "state/symmetric-unique-entries": answer(_blocks),
    "state/landmark-index": answer(
        lambda p: covariance_blocks(3, 2, min(int(p["landmark"]), MAX_SHOWN))
    ),
    # code: the lesson's numbers (the first example); a function is not graded by a number
    "state/state-size": given(lambda p: covariance_blocks(3, 2, 50)),
}
