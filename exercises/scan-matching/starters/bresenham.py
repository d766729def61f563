def bresenham(x0, y0, x1, y1):
    """Grid cells crossed by a beam from cell (x0, y0) to cell (x1, y1), both included.

    x0, y0, x1, y1: integers (cell indices).

    Returns a list of n + 1 cells [x, y], n = max(|x1 - x0|, |y1 - y0|), in order from the
    start: one per step of the major axis, the minor coordinate rounded half up.
    """
    raise NotImplementedError("TODO: step along the major axis and round the other coordinate")
