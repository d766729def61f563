# mistake: a table of the 95 % thresholds, ignoring the confidence
THRESHOLDS = {1: 3.841, 2: 5.991}


def in_gate(d2, dof, confidence):
    return d2 < THRESHOLDS[dof]
