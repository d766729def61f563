# mistake: the 2-DOF closed form -2 ln(1 - p) used for one DOF as well
import numpy as np


def in_gate(d2, dof, confidence):
    return bool(d2 < -2.0 * np.log(1.0 - confidence))
