# mistake: the covariance of xj - xi in world coordinates, without rotating into pose i's frame
import numpy as np


def relative_pose_covariance(xi, xj, P):
    P = np.asarray(P, dtype=float)
    Sii, Sij, Sjj = P[:3, :3], P[:3, 3:], P[3:, 3:]
    return Sii + Sjj - Sij - Sij.T
