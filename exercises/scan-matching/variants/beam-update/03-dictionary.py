# method: a dictionary of additions per cell built first, then a new grid assembled row by row
def update_beam(grid, x0, y0, x1, y1, l_occ, l_free):
    n = max(abs(x1 - x0), abs(y1 - y0))
    add = {}
    for k in range(n + 1):
        if n:
            x = x0 + (2 * k * (x1 - x0) + n) // (2 * n)
            y = y0 + (2 * k * (y1 - y0) + n) // (2 * n)
        else:
            x, y = x0, y0
        add[(x, y)] = l_occ if k == n else l_free
    return [
        [value + add.get((x, y), 0.0) for x, value in enumerate(row)]
        for y, row in enumerate(grid)
    ]
