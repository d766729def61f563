# mistake: looks the threshold up in a 90/95/99 % table, taking the nearest confidence
TABLE = {
    1: {0.90: 2.706, 0.95: 3.841, 0.99: 6.635},
    2: {0.90: 4.605, 0.95: 5.991, 0.99: 9.210},
}


def in_gate(d2, dof, confidence):
    row = TABLE[dof]
    nearest = min(row, key=lambda p: abs(p - confidence))
    return d2 < row[nearest]
