# method: the error taken the other way round (x̂ − x), plain-Python Gaussian elimination
import math


def nees(x_true, x_hat, P):
    n = len(x_true)
    e = [float(x_hat[i]) - float(x_true[i]) for i in range(n)]
    e[2] = math.atan2(math.sin(e[2]), math.cos(e[2]))
    if e[2] == math.pi:  # x̂ − x is minus the error, so it lies in [-pi, pi)
        e[2] = -math.pi
    a = [[float(v) for v in P[i]] + [e[i]] for i in range(n)]
    for c in range(n):
        piv = max(range(c, n), key=lambda r: abs(a[r][c]))
        a[c], a[piv] = a[piv], a[c]
        for r in range(c + 1, n):
            f = a[r][c] / a[c][c]
            a[r] = [x - f * y for x, y in zip(a[r], a[c])]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (a[r][n] - sum(a[r][k] * x[k] for k in range(r + 1, n))) / a[r][r]
    return sum(e[i] * x[i] for i in range(n))
