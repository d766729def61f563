import math


def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx + s * dy, -s * dx + c * dy, b[2] - a[2]


def edge_error(xi, xj, z):
    ex, ey, et = between(z, between(xi, xj))
    return ex, ey, math.remainder(et, 2 * math.pi)
