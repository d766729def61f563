# mistake: rotates the offset by b's heading instead of a's
import math


def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(b[2]), math.sin(b[2])
    return c * dx + s * dy, -s * dx + c * dy, b[2] - a[2]
