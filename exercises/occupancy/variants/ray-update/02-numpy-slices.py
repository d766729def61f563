# method: a float numpy array updated by slices
import numpy as np


def update_ray(log_odds, hit_index, l_occ, l_free):
    out = np.array(log_odds, dtype=float)
    out[:hit_index] += l_free
    out[hit_index] += l_occ
    return out
