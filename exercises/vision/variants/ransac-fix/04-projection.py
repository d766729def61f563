# method: subtract the projection onto the line's unit direction and measure what is left (numpy)
import numpy as np


def best_line(points, samples, threshold):
    P = np.array(points, dtype=float)
    best, best_count = None, -1
    for k, (a, b) in enumerate(samples):
        u = (P[b] - P[a]) / np.hypot(*(P[b] - P[a]))
        r = P - P[a]
        perp = r - np.outer(r @ u, u)
        count = int((np.hypot(perp[:, 0], perp[:, 1]) < threshold).sum())
        if count > best_count:
            best, best_count = k, count
    return best
