import math

import numpy as np


def loop_candidates(poses, marginals, cross, gap, confidence):
    x = np.asarray(poses, dtype=float)
    k = len(x) - 1
    searched = max(k - int(gap) + 1, 0)  # poses 0 .. k - gap
    if searched == 0:
        return []
    m = np.asarray(marginals, dtype=float)
    c = np.asarray(cross, dtype=float)
    # r_xy = R_i' w with w = t_k - t_i, and Sigma_r = R_i' Sigma_w R_i, so
    # d^2 = r' Sigma_r^-1 r = w' Sigma_w^-1 w: the rotation cancels and the world frame will do.
    # To first order dw = L_i dx_i + L_k dx_k with L_i = [-I | (w_y, -w_x)'] (turning pose i
    # swings pose k around it) and L_k = [I | 0], for every searched pose at once.
    w = x[k, :2] - x[:searched, :2]
    L = np.zeros((searched, 2, 3))
    L[:, 0, 0] = L[:, 1, 1] = -1.0
    L[:, 0, 2], L[:, 1, 2] = w[:, 1], -w[:, 0]
    # Sigma_w = L_i S_ii L_i' + L_i S_ik L_k' + (L_i S_ik L_k')' + L_k S_kk L_k'
    shared = (L @ c[:searched])[:, :, :2]
    s = L @ m[:searched] @ L.transpose(0, 2, 1) + shared + shared.transpose(0, 2, 1)
    s += m[k, :2, :2]
    # w' Sigma_w^-1 w with the 2 x 2 inverse written out
    sxx, sxy, syy = s[:, 0, 0], s[:, 0, 1], s[:, 1, 1]
    wx, wy = w[:, 0], w[:, 1]
    d2 = (syy * wx * wx - 2.0 * sxy * wx * wy + sxx * wy * wy) / (sxx * syy - sxy * sxy)
    gate = -2.0 * math.log1p(-confidence)  # the chi-square quantile with 2 dof
    return np.flatnonzero(d2 <= gate).tolist()
