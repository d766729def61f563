# mistake: the textbook 95 % range-bearing gate 5.99, whatever dof and confidence
def in_gate(d2, dof, confidence):
    return d2 < 5.99
