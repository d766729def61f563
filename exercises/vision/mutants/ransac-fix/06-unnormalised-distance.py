# mistake: the cross product is not divided by |b - a|, so the "distance" scales with the sample's length
import numpy as np


def best_line(points, samples, threshold):
    P = np.asarray(points, dtype=float)
    counts = []
    for a, b in samples:
        d = P[b] - P[a]
        r = P - P[a]
        counts.append(int(np.sum(np.abs(d[0] * r[:, 1] - d[1] * r[:, 0]) < threshold)))
    return int(np.argmax(counts))
