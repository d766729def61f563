# method: separate compose and inverse helpers, e = compose(inverse(z), compose(inverse(xi), xj))
import math


def compose(a, b):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])


def inverse(a):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-c * a[0] - s * a[1], s * a[0] - c * a[1], -a[2])


def edge_error(xi, xj, z):
    e = compose(inverse(z), compose(inverse(xi), xj))
    return (e[0], e[1], math.remainder(e[2], 2 * math.pi))
