# mistake: returns the best inlier count instead of the index of the best sample
import math


def best_line(points, samples, threshold):
    best = 0
    for a, b in samples:
        (ax, ay), (bx, by) = points[a], points[b]
        length = math.hypot(bx - ax, by - ay)
        count = sum(abs((bx - ax) * (qy - ay) - (by - ay) * (qx - ax)) / length < threshold
                    for qx, qy in points)
        best = max(best, count)
    return best
