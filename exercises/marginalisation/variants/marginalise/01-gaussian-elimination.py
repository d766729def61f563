# method: Gaussian elimination on the augmented rows [H | b], one removed variable at a time, in plain Python
def marginalise(H, b, keep):
    n = len(H)
    rows = [[float(H[i][j]) for j in range(n)] + [float(b[i])] for i in range(n)]
    keep = [int(k) for k in keep]
    alive = set(range(n))
    for v in range(n):
        if v in keep:
            continue
        alive.discard(v)
        pivot = rows[v][v]
        for i in alive:
            f = rows[i][v] / pivot
            if f != 0.0:
                rows[i] = [x - f * y for x, y in zip(rows[i], rows[v])]
    return [[rows[i][j] for j in keep] + [rows[i][n]] for i in keep]
