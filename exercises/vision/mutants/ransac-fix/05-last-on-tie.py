# mistake: '>=' when keeping the best, so a tie goes to the last candidate instead of the first
import math


def best_line(points, samples, threshold):
    best_index, best_count = 0, -1
    for k, (a, b) in enumerate(samples):
        (ax, ay), (bx, by) = points[a], points[b]
        length = math.hypot(bx - ax, by - ay)
        count = sum(abs((bx - ax) * (qy - ay) - (by - ay) * (qx - ax)) / length < threshold
                    for qx, qy in points)
        if count >= best_count:
            best_index, best_count = k, count
    return best_index
