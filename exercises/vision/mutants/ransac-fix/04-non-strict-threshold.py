# mistake: '<=' instead of '<': a point exactly at the threshold distance is counted as an inlier
import math


def best_line(points, samples, threshold):
    counts = []
    for a, b in samples:
        (ax, ay), (bx, by) = points[a], points[b]
        length = math.hypot(bx - ax, by - ay)
        counts.append(sum(abs((bx - ax) * (qy - ay) - (by - ay) * (qx - ax)) / length <= threshold
                          for qx, qy in points))
    return counts.index(max(counts))
