# mistake: the squared distance compared with the threshold (the square root forgotten)
def best_line(points, samples, threshold):
    counts = []
    for a, b in samples:
        (ax, ay), (bx, by) = points[a], points[b]
        dx, dy = bx - ax, by - ay
        counts.append(sum(((dx * (qy - ay) - dy * (qx - ax)) ** 2) / (dx * dx + dy * dy) < threshold
                          for qx, qy in points))
    return counts.index(max(counts))
