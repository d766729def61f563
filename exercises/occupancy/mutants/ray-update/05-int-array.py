# mistake: numpy.array(log_odds) keeps an integer dtype when the cells are whole numbers, so the update is truncated
import numpy as np


def update_ray(log_odds, hit_index, l_occ, l_free):
    out = np.array(log_odds)
    for k in range(hit_index):
        out[k] = out[k] + l_free
    out[hit_index] = out[hit_index] + l_occ
    return out
