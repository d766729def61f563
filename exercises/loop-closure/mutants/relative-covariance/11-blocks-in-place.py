# mistake: transforms the blocks of P in place before adding them up, which changes the caller's array
import math

import numpy as np


def relative_pose_covariance(xi, xj, P):
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    Ji = np.array([[-ci, -si, -si * dx + ci * dy], [si, -ci, -ci * dx - si * dy], [0.0, 0.0, -1.0]])
    Jj = np.array([[ci, si, 0.0], [-si, ci, 0.0], [0.0, 0.0, 1.0]])
    S = np.asarray(P, dtype=float)
    S[:3, :3] = Ji @ S[:3, :3] @ Ji.T
    S[:3, 3:] = Ji @ S[:3, 3:] @ Jj.T
    S[3:, :3] = Jj @ S[3:, :3] @ Ji.T
    S[3:, 3:] = Jj @ S[3:, 3:] @ Jj.T
    return S[:3, :3] + S[:3, 3:] + S[3:, :3] + S[3:, 3:]
