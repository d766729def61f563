# method: plain Python loops, the 2D cross product divided by the length, a running best
import math


def best_line(points, samples, threshold):
    best_index = 0
    best_count = -1
    for k, (a, b) in enumerate(samples):
        (ax, ay), (bx, by) = points[a], points[b]
        length = math.hypot(bx - ax, by - ay)
        count = 0
        for qx, qy in points:
            distance = abs((bx - ax) * (qy - ay) - (by - ay) * (qx - ax)) / length
            if distance < threshold:
                count += 1
        if count > best_count:
            best_count = count
            best_index = k
    return best_index
