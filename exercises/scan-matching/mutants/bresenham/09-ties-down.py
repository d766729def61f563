# mistake: ties rounded down, ceil(v − 1/2)
import math


def bresenham(x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[x0, y0]]
    return [[x0 + math.ceil(k * dx / n - 0.5), y0 + math.ceil(k * dy / n - 0.5)] for k in range(n + 1)]
