import numpy as np


def essential_matrix(t, R):
    """Essential matrix E = [t]× R of a relative camera pose.

    t: translation between the camera centres, shape (3,) (any scale; E is defined up to scale).
    R: rotation matrix between the two camera frames, shape (3, 3), list of rows.

    Returns E, shape (3, 3), where [t]× is the skew matrix with [t]× @ v == cross(t, v).
    """
    raise NotImplementedError("TODO: build the skew matrix of t and return it times R")
