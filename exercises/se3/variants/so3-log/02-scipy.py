# method: scipy's Rotation.as_rotvec, with the largest-component convention applied at exactly pi

import numpy as np
from scipy.spatial.transform import Rotation


def so3_log(R):
    m = np.array(R, dtype=float)
    w = Rotation.from_matrix(m).as_rotvec()
    if np.array_equal(m, m.T) and not np.array_equal(m, np.eye(3)):
        k = int(np.argmax(np.abs(w)))
        if w[k] < 0:
            w = -w
    return w
