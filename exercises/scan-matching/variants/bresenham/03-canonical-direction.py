# method: walk by major coordinate from the smaller end, pick the nearest cell by comparing doubled distances, then reverse if needed
def bresenham(x0, y0, x1, y1):
    if (x0, y0) == (x1, y1):
        return [[x0, y0]]
    steep = abs(y1 - y0) > abs(x1 - x0)
    a0, b0, a1, b1 = (y0, x0, y1, x1) if steep else (x0, y0, x1, y1)
    flipped = a0 > a1
    if flipped:
        a0, b0, a1, b1 = a1, b1, a0, b0
    da, db = a1 - a0, b1 - b0
    cells = []
    for a in range(a0, a1 + 1):
        # exact minor coordinate b0 + (a − a0)·db/da; candidate cells floor and floor + 1
        num = (a - a0) * db
        lo = b0 + num // da
        rem = num - (num // da) * da  # 0 <= rem < da: the fraction is rem / da
        b = lo + 1 if 2 * rem >= da else lo
        cells.append([b, a] if steep else [a, b])
    return cells[::-1] if flipped else cells
