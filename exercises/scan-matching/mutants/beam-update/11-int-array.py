# mistake: updates np.array(grid), an integer array when the map holds whole numbers (a fresh map of zeros), so the added log-odds are truncated
import numpy as np


def bresenham(x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[x0, y0]]
    return [[x0 + (2 * k * dx + n) // (2 * n), y0 + (2 * k * dy + n) // (2 * n)] for k in range(n + 1)]


def update_beam(grid, x0, y0, x1, y1, l_occ, l_free):
    out = np.array(grid)
    cells = bresenham(x0, y0, x1, y1)
    for x, y in cells[:-1]:
        out[y, x] += l_free
    x, y = cells[-1]
    out[y, x] += l_occ
    return out
