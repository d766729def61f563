import numpy as np


def icp_step(P, Q):
    """One ICP iteration from the identity: nearest-neighbour pairs, then closed-form alignment.

    P: new scan, list of N >= 2 points [x, y] in metres.
    Q: reference scan, list of M >= 2 points [x, y] in metres.

    Returns [theta, tx, ty] (radians, metres): the rigid motion best mapping each P[i] onto its
    nearest point of Q (ties: the smaller index in Q).
    """
    raise NotImplementedError("TODO: pair each P[i] with its nearest Q[j], then align the pairs")
