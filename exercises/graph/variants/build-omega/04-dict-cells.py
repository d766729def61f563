# method: accumulate the nonzero cells in a dict (sparse), then expand to a tuple of rows
def build_omega(n, edges):
    cells = {}
    for i, j, w in edges:
        for key, value in (((i, i), w), ((j, j), w), ((i, j), -w), ((j, i), -w)):
            cells[key] = cells.get(key, 0.0) + value
    return tuple(tuple(cells.get((r, c), 0.0) for c in range(n)) for r in range(n))
