# method: a regular expression per record, then index arithmetic for the symmetric matrix
import re

NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
EDGE = re.compile(r"^\s*EDGE_SE2((?:\s+" + NUMBER + r"){11})\s*$", re.MULTILINE)
UPPER = {(0, 0): 0, (0, 1): 1, (0, 2): 2, (1, 1): 3, (1, 2): 4, (2, 2): 5}


def read_edges(text):
    out = []
    for match in EDGE.finditer(text):
        v = [float(x) for x in match.group(1).split()]
        info = v[5:]
        full = [info[UPPER[(min(r, c), max(r, c))]] for r in range(3) for c in range(3)]
        out.append(v[:5] + full)
    return out
