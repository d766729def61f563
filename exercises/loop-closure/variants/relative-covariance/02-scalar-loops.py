# method: plain Python loops over the entries, no numpy
import math


def relative_pose_covariance(xi, xj, P):
    c, s = math.cos(xi[2]), math.sin(xi[2])
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    J = [
        [-c, -s, -s * dx + c * dy, c, s, 0.0],
        [s, -c, -c * dx - s * dy, -s, c, 0.0],
        [0.0, 0.0, -1.0, 0.0, 0.0, 1.0],
    ]
    Q = [[float(P[a][b]) for b in range(6)] for a in range(6)]
    out = [[0.0] * 3 for _ in range(3)]
    for r in range(3):
        for q in range(3):
            out[r][q] = sum(J[r][a] * Q[a][b] * J[q][b] for a in range(6) for b in range(6))
    return out
