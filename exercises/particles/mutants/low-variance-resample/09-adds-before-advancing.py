# mistake: in the walk, adds the current weight again before moving the pointer on
def low_variance_resample(weights, u):
    n = len(weights)
    total = float(sum(weights))
    out = []
    i = 0
    c = weights[0] / total
    for m in range(n):
        threshold = (u + m) / n
        while threshold > c and i < n - 1:
            c += weights[i] / total
            i += 1
        out.append(i)
    return out
