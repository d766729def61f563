# method: threshold array indexed by dof - 1 (numpy); 1 DOF as the square of NormalDist's quantile
from statistics import NormalDist

import numpy as np


def in_gate(d2, dof, confidence):
    z = NormalDist().inv_cdf((1 + confidence) / 2)
    thresholds = np.array([z * z, -2 * np.log(1 - confidence)])
    return bool(d2 < thresholds[dof - 1])
