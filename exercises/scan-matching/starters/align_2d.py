import numpy as np


def align_2d(P, Q):
    """Best rigid motion mapping the points P onto Q (known correspondences P[i] <-> Q[i]).

    P, Q: lists of N >= 2 points [x, y] in metres (same length).

    Returns [theta, tx, ty] (radians, metres) minimising sum_i |R(theta) P[i] + t - Q[i]|^2,
    with R(theta) a rotation (det R = +1).
    """
    raise NotImplementedError("TODO: centre both sets, find the angle, then t = q_mean - R p_mean")
