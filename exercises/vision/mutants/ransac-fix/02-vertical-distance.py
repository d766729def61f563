# mistake: the vertical gap |y - (m x + c)| instead of the perpendicular distance
def best_line(points, samples, threshold):
    counts = []
    for a, b in samples:
        (xa, ya), (xb, yb) = points[a], points[b]
        if xb == xa:
            counts.append(sum(1 for q in points if q[0] == xa))
            continue
        m = (yb - ya) / (xb - xa)
        c = ya - m * xa
        counts.append(sum(1 for qx, qy in points if abs(qy - (m * qx + c)) < threshold))
    return counts.index(max(counts))
