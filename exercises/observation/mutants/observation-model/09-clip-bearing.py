# mistake: clips the bearing into [-pi, pi] instead of wrapping it
import numpy as np


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    bearing = np.clip(np.arctan2(dy, dx) - thr, -np.pi, np.pi)
    return np.hypot(dx, dy), bearing
