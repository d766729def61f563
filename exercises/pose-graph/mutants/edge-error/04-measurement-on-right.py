# mistake: composes z^-1 on the right: (xi^-1 (+) xj) (+) z^-1
import math

def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx + s * dy, -s * dx + c * dy, b[2] - a[2]


def edge_error(xi, xj, z):
    m = between(xi, xj)
    zi = between(z, (0.0, 0.0, 0.0))  # z^-1
    c, s = math.cos(m[2]), math.sin(m[2])
    return m[0] + c * zi[0] - s * zi[1], m[1] + s * zi[0] + c * zi[1], m[2] + zi[2]
