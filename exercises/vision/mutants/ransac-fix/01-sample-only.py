# mistake: the original bug: inliers counted among the sample's own two points only
import math


def best_line(points, samples, threshold):
    best_index, best_count = 0, -1
    for k, (a, b) in enumerate(samples):
        (ax, ay), (bx, by) = points[a], points[b]
        length = math.hypot(bx - ax, by - ay)
        count = 0
        for qx, qy in (points[a], points[b]):
            if abs((bx - ax) * (qy - ay) - (by - ay) * (qx - ax)) / length < threshold:
                count += 1
        if count > best_count:
            best_index, best_count = k, count
    return best_index
