# mistake: computes (xi^-1 (+) xj)^-1 (+) z, the inverse of the g2o error
import math

def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx + s * dy, -s * dx + c * dy, b[2] - a[2]


def edge_error(xi, xj, z):
    return between(between(xi, xj), z)
