# method: the line as a x + b y + c = 0 with (a, b) a unit normal; max() with a key picks the first best
import math


def best_line(points, samples, threshold):
    def inliers(pair):
        (x1, y1), (x2, y2) = points[pair[0]], points[pair[1]]
        a, b = y2 - y1, x1 - x2
        norm = math.sqrt(a * a + b * b)
        a, b = a / norm, b / norm
        c = -(a * x1 + b * y1)
        return sum(1 for x, y in points if abs(a * x + b * y + c) < threshold)

    counts = [inliers(pair) for pair in samples]
    return max(range(len(samples)), key=lambda k: counts[k])
