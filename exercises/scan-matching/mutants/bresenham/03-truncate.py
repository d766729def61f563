# mistake: int() truncation instead of rounding to the nearest cell
def bresenham(x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[x0, y0]]
    return [[x0 + int(k * dx / n), y0 + int(k * dy / n)] for k in range(n + 1)]
