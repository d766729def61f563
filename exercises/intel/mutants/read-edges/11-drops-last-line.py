# mistake: splits on '\n' and drops the last piece, assuming the text ends with a newline (the last edge is lost when it does not)
def read_edges(text):
    rows = []
    for line in text.split("\n")[:-1]:  # the last piece is the empty one after the final newline
        f = line.split()
        if not f or f[0] != "EDGE_SE2":
            continue
        i, j = int(f[1]), int(f[2])
        dx, dy, dth = (float(v) for v in f[3:6])
        a, b, c, d, e, g = (float(v) for v in f[6:12])
        rows.append([i, j, dx, dy, dth, a, b, c, b, d, e, c, e, g])
    return rows
