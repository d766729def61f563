# method: Gauss-Jordan elimination on lists of floats (no numpy), solving only for the block's unit columns
def marginal_covariance(H, block):
    n = len(H)
    block = [int(k) for k in block]
    k = len(block)
    rows = []
    for i in range(n):
        unit = [1.0 if i == b else 0.0 for b in block]
        rows.append([float(H[i][j]) for j in range(n)] + unit)
    for v in range(n):
        p = rows[v][v]
        rows[v] = [x / p for x in rows[v]]
        for i in range(n):
            if i != v and rows[i][v] != 0.0:
                f = rows[i][v]
                rows[i] = [x - f * y for x, y in zip(rows[i], rows[v])]
    return [[rows[r][n + c] for c in range(k)] for r in block]
