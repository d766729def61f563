# mistake: rotates the offset by +thr instead of -thr into the robot frame (numpy rotation matrix)
import numpy as np


def observation_model(xr, yr, thr, xj, yj):
    c, s = np.cos(thr), np.sin(thr)
    R = np.array([[c, -s], [s, c]])
    local = R @ np.array([xj - xr, yj - yr])
    return float(np.linalg.norm(local)), float(np.arctan2(local[1], local[0]))
