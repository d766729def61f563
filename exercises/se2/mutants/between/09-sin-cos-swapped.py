# mistake: cos and sin swapped in the rotation
import math


def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.sin(a[2]), math.cos(a[2])
    return c * dx + s * dy, -s * dx + c * dy, b[2] - a[2]
