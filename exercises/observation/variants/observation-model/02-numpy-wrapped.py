# method: numpy arctan2 and linalg.norm, bearing wrapped by np.angle(exp(i b)); returns an array
import numpy as np


def observation_model(xr, yr, thr, xj, yj):
    d = np.array([xj - xr, yj - yr])
    bearing = np.angle(np.exp(1j * (np.arctan2(d[1], d[0]) - thr)))
    return np.array([np.linalg.norm(d), bearing])
