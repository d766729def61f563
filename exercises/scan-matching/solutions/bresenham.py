def bresenham(x0, y0, x1, y1):
    """Grid cells crossed by a beam from (x0, y0) to (x1, y1), both included."""
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[x0, y0]]
    cells = []
    for k in range(n + 1):
        # k*dx/n and k*dy/n rounded half up, exactly: floor((2*k*d + n) / (2*n))
        cells.append([x0 + (2 * k * dx + n) // (2 * n), y0 + (2 * k * dy + n) // (2 * n)])
    return cells
