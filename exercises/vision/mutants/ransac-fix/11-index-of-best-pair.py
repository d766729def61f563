# mistake: remembers the best pair and returns samples.index(pair), which a numpy array of samples does not have
import math


def best_line(points, samples, threshold):
    best_pair, best_count = None, -1
    for a, b in samples:
        (ax, ay), (bx, by) = points[a], points[b]
        length = math.hypot(bx - ax, by - ay)
        count = sum(
            1 for qx, qy in points
            if abs((bx - ax) * (qy - ay) - (by - ay) * (qx - ax)) / length < threshold
        )
        if count > best_count:
            best_pair, best_count = [a, b], count
    return samples.index(best_pair)
