# method: str.split per line, the full matrix built as nested lists and flattened
def read_edges(text):
    out = []
    for line in text.splitlines():
        f = line.split()
        if f[:1] == ["EDGE_SE2"]:
            v = [float(x) for x in f[1:12]]
            i11, i12, i13, i22, i23, i33 = v[5:]
            omega = [[i11, i12, i13], [i12, i22, i23], [i13, i23, i33]]
            out.append(v[:5] + [x for row in omega for x in row])
    return out
