# mistake: reads the six numbers in TORO's order (Ixx Ixy Iyy Itt Ixt Iyt)
def read_edges(text):
    rows = []
    for line in text.splitlines():
        f = line.split()
        if not f or f[0] != "EDGE_SE2":
            continue
        i, j = int(f[1]), int(f[2])
        dx, dy, dth = (float(v) for v in f[3:6])
        a, b, c, d, e, g = (float(v) for v in f[6:12])
        xx, xy, yy, tt, xt, yt = a, b, c, d, e, g
        rows.append([i, j, dx, dy, dth, xx, xy, xt, xy, yy, yt, xt, yt, tt])
    return rows
