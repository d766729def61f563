# mistake: splits the text on '\n' only and matches each edge line with a regular expression anchored at its end ($), which the '\r' left by a CRLF file (or trailing spaces) defeats
import re

EDGE = re.compile(r"^EDGE_SE2" + r"\s+(\S+)" * 11 + r"$")


def read_edges(text):
    rows = []
    for line in text.split("\n"):
        m = EDGE.match(line)
        if m is None:
            continue
        i, j = int(m.group(1)), int(m.group(2))
        dx, dy, dth, a, b, c, d, e, g = (float(v) for v in m.groups()[2:])
        rows.append([i, j, dx, dy, dth, a, b, c, b, d, e, c, e, g])
    return rows
