# mistake: ties rounded away from zero (int(v + 0.5) for v ≥ 0, int(v − 0.5) below), wrong for negative ties
def _round(v):
    return int(v + 0.5) if v >= 0 else int(v - 0.5)


def bresenham(x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[x0, y0]]
    return [[x0 + _round(k * dx / n), y0 + _round(k * dy / n)] for k in range(n + 1)]
