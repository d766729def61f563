# mistake: fills the result into np.zeros_like(P), an integer array when P's entries are whole numbers
import numpy as np


def update_covariance(P, H, R):
    Pm = np.array(P, dtype=float)
    Hm = np.array(H, dtype=float)
    S = Hm @ Pm @ Hm.T + np.array(R, dtype=float)
    K = Pm @ Hm.T @ np.linalg.inv(S)
    new = (np.eye(len(Pm)) - K @ Hm) @ Pm
    out = np.zeros_like(P)
    for i in range(len(Pm)):
        for j in range(len(Pm)):
            out[i][j] = new[i, j]
    return out
