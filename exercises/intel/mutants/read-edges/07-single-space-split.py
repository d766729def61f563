# mistake: splits on single spaces, so runs of blanks or tabs shift the fields
def read_edges(text):
    rows = []
    for line in text.splitlines():
        f = [t for t in line.strip().split(' ') if t != '']
        if not f or f[0] != "EDGE_SE2":
            continue
        if len(f) != 12:
            f = (f + ['0'] * 12)[:12]
        i, j = int(f[1]), int(f[2])
        dx, dy, dth = (float(v) for v in f[3:6])
        a, b, c, d, e, g = (float(v) for v in f[6:12])
        rows.append([i, j, dx, dy, dth, a, b, c, b, d, e, c, e, g])
    return rows
