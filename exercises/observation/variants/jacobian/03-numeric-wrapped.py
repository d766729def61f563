# method: numeric central differences (step 1e-6), bearing difference wrapped by atan2(sin, cos)
import math


def h(v):
    xr, yr, thr, xj, yj = v
    return math.hypot(xj - xr, yj - yr), math.atan2(yj - yr, xj - xr) - thr


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    x = [xr, yr, thr, xj, yj]
    step = 1e-6
    J = [[0.0] * 5, [0.0] * 5]
    for k in range(5):
        plus, minus = list(x), list(x)
        plus[k] += step
        minus[k] -= step
        (rp, bp), (rm, bm) = h(plus), h(minus)
        db = math.atan2(math.sin(bp - bm), math.cos(bp - bm))
        J[0][k] = (rp - rm) / (2 * step)
        J[1][k] = db / (2 * step)
    return J
