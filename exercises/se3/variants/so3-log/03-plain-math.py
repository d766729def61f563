# method: plain math with loops; near pi the axis from the diagonal, signs from the off-diagonals
import math


def so3_log(R):
    r = [[float(x) for x in row] for row in R]
    v = [(r[2][1] - r[1][2]) / 2, (r[0][2] - r[2][0]) / 2, (r[1][0] - r[0][1]) / 2]
    s = math.sqrt(sum(x * x for x in v))
    c = (r[0][0] + r[1][1] + r[2][2] - 1) / 2
    theta = math.atan2(s, c)
    if theta < 1e-3:
        factor = 1 + theta**2 / 6 + 7 * theta**4 / 360
        return [factor * x for x in v]
    if c > -0.5:
        return [theta / s * x for x in v]
    # n_k^2 = (R_kk - c) / (1 - c); the largest one first, the others from R_kj + R_jk
    d = [(r[k][k] - c) / (1 - c) for k in range(3)]
    k = max(range(3), key=lambda i: d[i])
    n = [0.0, 0.0, 0.0]
    n[k] = math.sqrt(d[k])
    for j in range(3):
        if j != k:
            n[j] = (r[k][j] + r[j][k]) / (2 * (1 - c) * n[k])
    norm = math.sqrt(sum(x * x for x in n))
    n = [x / norm for x in n]
    if sum(a * b for a, b in zip(n, v)) < 0:
        n = [-x for x in n]
    return [theta * x for x in n]
