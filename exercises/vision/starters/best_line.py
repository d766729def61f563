import math


def best_line(points, samples, threshold):
    """Pick the best candidate line, RANSAC style.

    points:    list of [x, y] points (metres).
    samples:   list of [a, b] index pairs; candidate k is the line through points[a] and
               points[b] (the two points are distinct).
    threshold: a point is an inlier of a line when its perpendicular distance to it is less
               than this (metres).

    Returns the index k (int) of the candidate with the most inliers; the first on a tie.

    This version has the bug of the previous exercise: find it and fix it.
    """
    best_index = 0
    best_count = -1
    for k, (a, b) in enumerate(samples):
        (ax, ay), (bx, by) = points[a], points[b]
        length = math.hypot(bx - ax, by - ay)
        count = 0
        for qx, qy in (points[a], points[b]):
            distance = abs((bx - ax) * (qy - ay) - (by - ay) * (qx - ax)) / length
            if distance < threshold:
                count += 1
        if count > best_count:
            best_count = count
            best_index = k
    return best_index
