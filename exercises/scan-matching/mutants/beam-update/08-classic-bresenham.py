# mistake: the textbook Bresenham whose ties depend on the direction of travel
def bresenham(x0, y0, x1, y1):
    dx, dy = abs(x1 - x0), -abs(y1 - y0)
    sx = 1 if x0 < x1 else -1
    sy = 1 if y0 < y1 else -1
    err = dx + dy
    cells = []
    while True:
        cells.append([x0, y0])
        if x0 == x1 and y0 == y1:
            return cells
        e2 = 2 * err
        if e2 >= dy:
            err += dy
            x0 += sx
        if e2 <= dx:
            err += dx
            y0 += sy


def update_beam(grid, x0, y0, x1, y1, l_occ, l_free):
    out = [list(row) for row in grid]
    cells = bresenham(x0, y0, x1, y1)
    for x, y in cells[:-1]:
        out[y][x] += l_free
    x, y = cells[-1]
    out[y][x] += l_occ
    return out
