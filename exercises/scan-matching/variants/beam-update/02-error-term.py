# method: integer error-term walk along the major axis (ties towards the larger coordinate), updating as it goes
def update_beam(grid, x0, y0, x1, y1, l_occ, l_free):
    out = [[float(v) for v in row] for row in grid]
    dx, dy = x1 - x0, y1 - y0
    steep = abs(dy) > abs(dx)
    a, b = (abs(dy), dx) if steep else (abs(dx), dy)
    sa = (1 if dy > 0 else -1) if steep else (1 if dx > 0 else -1)
    for k in range(a + 1):
        # minor offset k*b/a rounded half up, exactly
        minor = (2 * k * b + a) // (2 * a) if a else 0
        x, y = (x0 + minor, y0 + k * sa) if steep else (x0 + k * sa, y0 + minor)
        out[y][x] += l_occ if k == a else l_free
    return out
