# mistake: numeric central differences, the bearing difference not wrapped (2π jumps behind)
import math


def h(v):
    xr, yr, thr, xj, yj = v
    return [math.hypot(xj - xr, yj - yr), math.atan2(yj - yr, xj - xr) - thr]


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    x = [xr, yr, thr, xj, yj]
    eps = 1e-6
    J = [[0.0] * 5 for _ in range(2)]
    for k in range(5):
        plus = list(x)
        minus = list(x)
        plus[k] += eps
        minus[k] -= eps
        hp, hm = h(plus), h(minus)
        for i in range(2):
            J[i][k] = (hp[i] - hm[i]) / (2 * eps)
    return J
