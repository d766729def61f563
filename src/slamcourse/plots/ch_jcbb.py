"""Chapter ``jcbb``: the two-landmark scene where nearest neighbour pairs wrongly and JCBB
does not."""

from __future__ import annotations

import numpy as np

from slamcourse.plots.canvas import BLUE, GREEN, INK, MUTED, ORANGE, PURPLE, Plane
from slamcourse.plots.picture import Figure, Picture, given
from slamcourse.plots.svg import num
from slamcourse.slam import ekfslam
from slamcourse.slam.jcbb import greedy_nn, hypothesis_d2, jcbb

# the chapter's scene: landmarks A (10, 0) and B (10, 1.2) m; the robot believes it faces 0 rad
# with a heading variance of 0.02 rad², and truly faces 0.1 rad
MU = (0.0, 0.0, 0.0, 10.0, 0.0, 10.0, 1.2)
P = np.diag([0.01, 0.01, 0.02, 0.01, 0.01, 0.01, 0.01])
R = np.diag([0.04, 0.0004])
TRUE_POSE = (0.0, 0.0, 0.1)
NAMES = ("A", "B")


def measurements() -> list[list[float]]:
    return [
        ekfslam.observe(TRUE_POSE, MU[3:5]).tolist(),
        ekfslam.observe(TRUE_POSE, MU[5:7]).tolist(),
    ]


def scene(*, pairings: bool = False) -> str:
    """The believed robot, the landmarks where the map has them, and where each measurement
    puts its landmark if the believed pose were right; ``pairings``: greedy's and JCBB's."""
    zs = measurements()
    seen = [ekfslam.inverse_observation(MU[:3], z) for z in zs]
    marks = [(MU[3], MU[4]), (MU[5], MU[6])]
    plane = Plane([(8.6, -1.3), (10.9, 1.7)], width=480, height=400, pad=30)
    plane.segment((8.7, 0), (10.6, 0), colour=MUTED, dash="2 4", width=1.0)
    plane.label(8.75, 0.0, "← robot 10 m away, believed heading 0", colour=INK, prefer=("n", "s"))
    facts = []
    for (x, y), name in zip(marks, NAMES, strict=True):
        plane.point(x, y, colour=GREEN, shape="diamond", size=8, label=f"landmark {name}")
    for k, (x, y) in enumerate(seen):
        plane.point(
            float(x),
            float(y),
            colour=BLUE if k == 0 else ORANGE,
            shape="circle",
            label=f"z{k + 1}",
            bold=True,
        )
        facts.append(
            f"z{k + 1} (range {num(zs[k][0])} m, bearing {num(zs[k][1])} rad) lands at "
            f"({num(float(x))}, {num(float(y))}) m"
        )
    desc = (
        "Two landmarks, A at (10, 0) m and B at (10, 1.2) m. The robot believes it faces 0 rad "
        "but truly faces 0.1 rad, so both measurements read 0.1 rad low. Drawn from the believed "
        "pose, " + "; ".join(facts) + ": z2, the measurement of B, falls almost on A."
    )
    title = "The JCBB scene"
    if pairings:
        greedy = greedy_nn(MU, P, zs, R, 0.95)
        joint = jcbb(MU, P, zs, R, 0.95)
        for pairing, colour, dash in ((greedy, PURPLE, "3 3"), (joint, GREEN, "")):
            for k, j in enumerate(pairing):
                if j >= 0 and not (colour == PURPLE and joint[k] == j):
                    plane.segment(
                        (float(seen[k][0]), float(seen[k][1])),
                        marks[j],
                        colour=colour,
                        dash=dash or None,
                        width=2.0,
                        arrow=True,
                    )

        def said(p: tuple[int, ...]) -> str:
            return ", ".join(f"z{k + 1} → {NAMES[j] if j >= 0 else 'new'}" for k, j in enumerate(p))

        desc += (
            f" Nearest neighbour pairs {said(greedy)} (joint d² "
            f"{num(hypothesis_d2(MU, P, zs, R, greedy))}); JCBB pairs {said(joint)} (joint "
            f"d² {num(hypothesis_d2(MU, P, zs, R, joint))}), which explains both "
            "measurements with one heading error."
        )
        title = "Nearest neighbour against JCBB in the scene"
        legend = [("nearest neighbour", PURPLE, "3 3"), ("JCBB", GREEN, "")]
        return plane.svg(title, desc, legend)
    return plane.svg(title, desc)


def correlated_pair(
    nu1: float, nu2: float, s1: float, s2: float, c: float, *, show_results: bool = True
) -> str:
    """Two bearing innovations with the joint covariance [[s1, c], [c, s2]]: its 1σ and 2σ
    ellipses, the innovation pair, and (when shown) its joint d²."""
    cov = [[s1, c], [c, s2]]
    d2 = float(np.array([nu1, nu2]) @ np.linalg.inv(cov) @ np.array([nu1, nu2]))
    r = 2.3 * max(s1, s2) ** 0.5
    plane = Plane([(-r, -r), (r, r), (nu1, nu2)], width=400, height=380, pad=34)
    plane.segment((-r, 0), (r, 0), colour=MUTED, width=0.8)
    plane.segment((0, -r), (0, r), colour=MUTED, width=0.8)
    plane.ellipse(0, 0, cov, k=1.0, colour=BLUE, dash="4 3")
    plane.ellipse(0, 0, cov, k=2.0, colour=BLUE)
    shown = f"joint d² = {num(d2)}" if show_results else "joint d² = ?"
    plane.point(nu1, nu2, colour=ORANGE, shape="circle", label=f"(ν1, ν2): {shown}", bold=True)
    desc = (
        f"Innovations ν1 = {num(nu1)} and ν2 = {num(nu2)} rad of two measurements whose "
        f"predictions share an error: variances {num(s1)} and {num(s2)}, covariance {num(c)}. "
        "The ellipses (1σ dashed, 2σ solid) lean along the diagonal, so a pair of errors with "
        "the same sign is far more plausible than either alone suggests"
        + (f": joint d² = {num(d2)}." if show_results else ".")
    )
    return plane.svg("Two correlated innovations", desc)


FIGURES: dict[str, Figure] = {
    "jcbb/scene": scene,
    "jcbb/scene-pairings": lambda: scene(pairings=True),
}

PICTURES: dict[str, Picture] = {
    "jcbb/correlated-pair": Picture(
        lambda p, shown: correlated_pair(
            float(p["nu1"]),
            float(p["nu2"]),
            float(p["s1"]),
            float(p["s2"]),
            float(p["c"]),
            show_results=shown,
        )
    ),
    "jcbb/scene-greedy": given(lambda p: scene()),
    "jcbb/scene-jcbb": given(lambda p: scene()),
    "jcbb/joint-d2": given(lambda p: scene()),
    "jcbb/joint-compatible": given(lambda p: scene()),
}
