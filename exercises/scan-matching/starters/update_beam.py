def update_beam(grid, x0, y0, x1, y1, l_occ, l_free):
    """Occupancy grid after one beam from cell (x0, y0) that hit an obstacle in cell (x1, y1).

    grid:   list of rows of log-odds; cell (x, y) is grid[y][x].
    x0, y0: the robot's cell; x1, y1: the hit cell (both inside the grid).
    l_occ:  log-odds added to the hit cell (positive).
    l_free: log-odds added to each beam cell before the hit, the robot's cell included (negative).

    Returns a new list of rows (same shape); the beam's cells are those of bresenham().
    """
    raise NotImplementedError("TODO: trace the beam's cells, then add l_free / l_occ")
