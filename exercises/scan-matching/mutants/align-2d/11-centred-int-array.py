# mistake: centres the points one coordinate at a time in np.array(P), an integer array when the coordinates are whole numbers, so the centred points are truncated
import numpy as np


def align_2d(P, Q):
    a, b = np.array(P), np.array(Q)
    pm, qm = a.mean(axis=0), b.mean(axis=0)
    for i in range(len(a)):
        for k in range(2):
            a[i, k] -= pm[k]
            b[i, k] -= qm[k]
    s = np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    c = np.sum(a * b)
    theta = float(np.arctan2(s, c))
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = qm - R @ pm
    return [theta, float(t[0]), float(t[1])]
