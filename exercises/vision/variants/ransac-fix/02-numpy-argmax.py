# method: numpy, all points at once per candidate; numpy.argmax returns the first maximum
import numpy as np


def best_line(points, samples, threshold):
    P = np.asarray(points, dtype=float)
    counts = []
    for a, b in samples:
        d = P[b] - P[a]
        r = P - P[a]
        dist = np.abs(d[0] * r[:, 1] - d[1] * r[:, 0]) / np.linalg.norm(d)
        counts.append(np.count_nonzero(dist < threshold))
    return int(np.argmax(counts))
