# mistake: the result allocated with np.ones_like(s), the input dtype (ints truncate weights)
import numpy as np


def robust_weights(kind, s, k):
    s = np.asarray(s).reshape(-1)
    k2 = k * k
    if kind == "l2":
        return np.ones(len(s))
    if kind == "huber":
        out = np.ones_like(s)
        far = s > k2
        out[far] = k / np.sqrt(s[far])
        return out
    if kind == "cauchy":
        return 1.0 / (1.0 + s / k2)
    if kind == "dcs":
        scale = np.minimum(1.0, 2.0 * k2 / (k2 + s))  # the scale of the error
        return scale**2  # Omega is multiplied by its square
    raise ValueError(kind)
