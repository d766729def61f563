# mistake: stores the step count as numpy int16, which wraps past 32767 steps
import numpy as np


def random_walk_error(sigma, steps):
    k = np.array(steps).astype(np.int16)
    return float(sigma * np.sqrt(k))
