# mistake: always steps along x: a steep line leaves gaps (and a vertical one has one cell)
def bresenham(x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    n = abs(dx)
    if n == 0:
        return [[x0, y0]] if dy == 0 else [[x0, y0], [x1, y1]]
    return [[x0 + k * (1 if dx > 0 else -1), y0 + (2 * k * dy + n) // (2 * n)] for k in range(n + 1)]
