# mistake: a DDA that adds the float slope at every step: rounding errors push some ties the wrong way
import math


def bresenham(x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[x0, y0]]
    sx, sy = dx / n, dy / n
    x, y = float(x0), float(y0)
    cells = []
    for _ in range(n + 1):
        cells.append([math.floor(x + 0.5), math.floor(y + 0.5)])
        x += sx
        y += sy
    return cells
