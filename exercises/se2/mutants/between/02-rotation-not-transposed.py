# mistake: rotates the offset by +theta_a (R) instead of -theta_a (R^T)
import math


def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx - s * dy, s * dx + c * dy, b[2] - a[2]
