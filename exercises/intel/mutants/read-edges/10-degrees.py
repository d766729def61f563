# mistake: converts the measured turn from degrees although g2o stores radians
def read_edges(text):
    rows = []
    for line in text.splitlines():
        f = line.split()
        if not f or f[0] != "EDGE_SE2":
            continue
        i, j = int(f[1]), int(f[2])
        dx, dy, dth = (float(v) for v in f[3:6])
        dth = dth * 3.141592653589793 / 180
        a, b, c, d, e, g = (float(v) for v in f[6:12])
        rows.append([i, j, dx, dy, dth, a, b, c, b, d, e, c, e, g])
    return rows
