# mistake: distance to the segment between the two sample points, not to the infinite line through them
import math


def best_line(points, samples, threshold):
    counts = []
    for a, b in samples:
        (ax, ay), (bx, by) = points[a], points[b]
        dx, dy = bx - ax, by - ay
        count = 0
        for qx, qy in points:
            s = max(0.0, min(1.0, ((qx - ax) * dx + (qy - ay) * dy) / (dx * dx + dy * dy)))
            if math.hypot(qx - (ax + s * dx), qy - (ay + s * dy)) < threshold:
                count += 1
        counts.append(count)
    return counts.index(max(counts))
