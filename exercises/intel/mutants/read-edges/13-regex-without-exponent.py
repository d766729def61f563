# mistake: reads the numbers with a regular expression that has no exponent, so 1e-05 becomes the two numbers 1 and -05
import re

NUMBER = re.compile(r"-?\d+(?:\.\d*)?")


def read_edges(text):
    rows = []
    for line in text.splitlines():
        if not line.strip().startswith("EDGE_SE2"):
            continue
        values = [float(v) for v in NUMBER.findall(line.strip()[len("EDGE_SE2"):])]
        i, j, dx, dy, dth, a, b, c, d, e, g = values[:11]
        rows.append([int(i), int(j), dx, dy, dth, a, b, c, b, d, e, c, e, g])
    return rows
