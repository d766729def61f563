# mistake: the cells are set to l_free / l_occ instead of having them added
import numpy as np


def update_ray(log_odds, hit_index, l_occ, l_free):
    out = np.array(log_odds, dtype=float)
    out[:hit_index] = l_free
    out[hit_index] = l_occ
    return out
