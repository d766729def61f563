# mistake: cells returned as [row, column] = [y, x]
def bresenham(x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[y0, x0]]
    return [[y0 + (2 * k * dy + n) // (2 * n), x0 + (2 * k * dx + n) // (2 * n)] for k in range(n + 1)]
