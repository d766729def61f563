# method: Bresenham's integer error term along the major axis, with the tie rule folded into the comparison
def bresenham(x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    swap = abs(dy) > abs(dx)
    if swap:  # work as if x were the major axis
        x0, y0, x1, y1, dx, dy = y0, x0, y1, x1, dy, dx
    sx = 1 if dx >= 0 else -1
    sy = 1 if dy >= 0 else -1
    a, b = abs(dx), abs(dy)
    cells = []
    y = y0
    # err = 2·(k·b − a·(|y − y0|)) tracks twice the exact minor offset minus the one taken
    err = 0
    for k in range(a + 1):
        cells.append([y, x0 + k * sx] if swap else [x0 + k * sx, y])
        err += 2 * b
        # step when the exact offset passes the half: ties go up (towards larger y)
        if err > a or (err == a and sy > 0):
            y += sy
            err -= 2 * a
    return cells
