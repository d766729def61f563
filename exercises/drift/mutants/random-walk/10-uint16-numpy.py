# mistake: numpy array of step counts as uint16 (wraps to 0 at 65536 steps)
import numpy as np


def random_walk_error(sigma, steps):
    counts = np.array([steps]).astype(np.uint16)
    return float(sigma * np.sqrt(counts)[0])
