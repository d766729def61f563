# method: separate compose and inverse helpers, between = compose(inverse(a), b)
import math


def compose(p, q):
    c, s = math.cos(p[2]), math.sin(p[2])
    return [p[0] + c * q[0] - s * q[1], p[1] + s * q[0] + c * q[1], p[2] + q[2]]


def inverse(p):
    c, s = math.cos(p[2]), math.sin(p[2])
    return [-c * p[0] - s * p[1], s * p[0] - c * p[1], -p[2]]


def between(a, b):
    return compose(inverse(a), b)
