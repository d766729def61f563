# mistake: the results clamped to [-5, 5] (a map's clamping bound, not part of this update)
import numpy as np


def update_ray(log_odds, hit_index, l_occ, l_free):
    out = np.array(log_odds, dtype=float)
    out[:hit_index] += l_free
    out[hit_index] += l_occ
    return np.clip(out, -5.0, 5.0)
