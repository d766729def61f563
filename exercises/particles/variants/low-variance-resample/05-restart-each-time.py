# method: for every threshold, scan the cumulative weights from the start (O(N^2), plain Python)
def low_variance_resample(weights, u):
    n = len(weights)
    total = sum(weights)
    out = []
    for m in range(n):
        threshold = (u + m) / n * total
        acc = 0.0
        chosen = n - 1
        for i, w in enumerate(weights):
            acc += w
            if acc >= threshold:
                chosen = i
                break
        out.append(chosen)
    return out
