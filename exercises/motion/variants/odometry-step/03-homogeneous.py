# method: homogeneous matrices for the pose and the three elementary motions, wrapped angle
import numpy as np


def T(x, y, t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, x], [s, c, y], [0.0, 0.0, 1.0]])


def odometry_step(pose, u):
    rot1, trans, rot2 = u
    M = T(*pose) @ T(0, 0, rot1) @ T(trans, 0, 0) @ T(0, 0, rot2)
    return np.array([M[0, 2], M[1, 2], np.arctan2(M[1, 0], M[0, 0])])
