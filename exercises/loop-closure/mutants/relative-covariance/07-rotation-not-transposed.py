# mistake: rotates the offset into pose i's frame with R_i instead of R_i^T
import math

import numpy as np


def jacobians(xi, xj):
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    Ji = np.array([[-ci, si, -si * dx - ci * dy], [-si, -ci, ci * dx - si * dy], [0.0, 0.0, -1.0]])
    Jj = np.array([[ci, -si, 0.0], [si, ci, 0.0], [0.0, 0.0, 1.0]])
    return Ji, Jj


def relative_pose_covariance(xi, xj, P):
    P = np.asarray(P, dtype=float)
    Sii, Sij, Sjj = P[:3, :3], P[:3, 3:], P[3:, 3:]
    Ji, Jj = jacobians(xi, xj)
    return Ji @ Sii @ Ji.T + Ji @ Sij @ Jj.T + Jj @ Sij.T @ Ji.T + Jj @ Sjj @ Jj.T
