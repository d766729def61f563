"""Chapter ``drift``: a square drive that does not close, and what a loop closure does to it."""

from __future__ import annotations

import numpy as np

from slamcourse.plots.canvas import BLUE, INK, ORANGE, Plane
from slamcourse.plots.picture import Figure, Params, Picture, answer, given
from slamcourse.plots.svg import num
from slamcourse.slam.drift import dead_reckoning, loop_closure_correction


def square_paths(
    side_steps: int, step: float, sigma: float, seed: int = 4
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The true square; the dead-reckoned path, each step off by independent errors of ``sigma``
    m on each axis (one seeded sample); and that path after a loop closure saying "back at the
    start" (the least-squares correction of
    :func:`slamcourse.slam.drift.loop_closure_correction`, on each axis)."""
    n = 4 * side_steps
    turns = np.repeat(np.arange(4) * np.pi / 2, side_steps)
    true = dead_reckoning(np.full(n, step), turns)
    noise = np.random.default_rng(seed).normal(0.0, sigma, size=(n, 2))
    drifted = true + np.vstack([np.zeros((1, 2)), np.cumsum(noise, axis=0)])
    error = -drifted[-1]  # the closure says the last pose is the first
    shares = loop_closure_correction([1.0] * n, 1.0)
    corrected = drifted + np.outer(shares, error)
    return true, drifted, corrected


def loop_closure_figure(side_steps: int = 20, step: float = 0.5, sigma: float = 0.06) -> str:
    true, drifted, corrected = square_paths(side_steps, step, sigma)
    pts = [tuple(p) for p in np.vstack([true, drifted, corrected])]
    plane = Plane(pts, width=520, height=420, pad=40, top=30)
    plane.path([tuple(p) for p in true], colour=INK, dash="2 3", width=1.5)
    plane.path([tuple(p) for p in drifted], colour=ORANGE, dash="8 4", block=True)
    plane.path([tuple(p) for p in corrected], colour=BLUE, block=True)
    plane.point(0, 0, colour=INK, shape="circle", label="start")
    end = drifted[-1]
    gap = float(np.hypot(*end))
    plane.point(
        float(end[0]),
        float(end[1]),
        colour=ORANGE,
        shape="square",
        label="dead-reckoned end",
    )
    before = float(np.mean(np.hypot(*(drifted - true).T)))
    after = float(np.mean(np.hypot(*(corrected - true).T)))
    desc = (
        f"A robot drives a square of side {num(side_steps * step)} m in {4 * side_steps} steps "
        f"of {num(step)} m; each step errs by a random {num(sigma)} m (1σ) on each axis. Dead "
        f"reckoning ends {num(gap)} m from the start. A loop closure saying that the robot is "
        "back at the start spreads that error along the loop, each pose moving by its share of "
        "the uncertainty accumulated up to it: the corrected path closes, and the average "
        f"distance of a pose from the truth falls from {num(before)} m to {num(after)} m."
    )
    legend = [
        ("true square", INK, "2 3"),
        ("dead reckoning", ORANGE, "8 4"),
        ("after the loop closure", BLUE, ""),
    ]
    return plane.svg("Drift with and without a loop closure", desc, legend)


def _correction(p: Params) -> str:
    n = int(p["num_steps"])
    return loop_closure_figure(max(2, n // 4 + 1))


def square_loop(bias: float, steps_per_side: int) -> str:
    """The square of the ``square-loop`` exercise driven with a step over-count of ``bias``."""
    steps = min(int(steps_per_side), 50)
    turns = np.repeat(np.arange(4) * np.pi / 2, steps)
    scale = steps_per_side / steps
    believed = dead_reckoning(np.full(4 * steps, scale * (1 + bias)), turns)
    true = dead_reckoning(np.full(4 * steps, scale), turns)
    plane = Plane([tuple(p) for p in np.vstack([true, believed])], width=420, height=380)
    plane.path([tuple(p) for p in true], colour=INK, dash="2 3")
    plane.path([tuple(p) for p in believed], colour=ORANGE, block=True)
    plane.point(0, 0, colour=INK, shape="circle", label="start")
    desc = (
        f"A square of {steps_per_side} steps per side, each step counted {num(bias)} m too "
        "long: the believed square is larger on every side, and its errors cancel around the "
        "loop."
    )
    return plane.svg(
        "A square driven with a systematic step error",
        desc,
        [("true", INK, "2 3"), ("believed", ORANGE, "")],
    )


FIGURES: dict[str, Figure] = {
    "drift/loop-closure": loop_closure_figure,
}

PICTURES: dict[str, Picture] = {
    "drift/square-loop": answer(lambda p: square_loop(float(p["bias"]), int(p["steps_per_side"]))),
    "drift/correction-share": given(_correction),
}
