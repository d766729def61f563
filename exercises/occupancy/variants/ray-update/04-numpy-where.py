# method: numpy.where over the cell indices builds the increment vector, added in one go
import numpy as np


def update_ray(log_odds, hit_index, l_occ, l_free):
    k = np.arange(len(log_odds))
    step = np.where(k < hit_index, l_free, np.where(k == hit_index, l_occ, 0.0))
    return np.asarray(log_odds) + step
