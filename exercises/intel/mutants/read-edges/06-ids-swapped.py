# mistake: swaps the two pose ids
def read_edges(text):
    rows = []
    for line in text.splitlines():
        f = line.split()
        if not f or f[0] != "EDGE_SE2":
            continue
        i, j = int(f[1]), int(f[2])
        dx, dy, dth = (float(v) for v in f[3:6])
        a, b, c, d, e, g = (float(v) for v in f[6:12])
        rows.append([j, i, dx, dy, dth, a, b, c, b, d, e, c, e, g])
    return rows
