# mistake: computes a seen from b (b^-1 + a)
import math


def between(a, b):
    dx, dy = a[0] - b[0], a[1] - b[1]
    c, s = math.cos(b[2]), math.sin(b[2])
    return c * dx + s * dy, -s * dx + c * dy, a[2] - b[2]
