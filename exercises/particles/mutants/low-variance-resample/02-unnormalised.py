# mistake: walks the raw cumulative weights without dividing by their sum
def low_variance_resample(weights, u):
    n = len(weights)
    out = []
    i = 0
    c = weights[0]
    for m in range(n):
        threshold = (u + m) / n
        while threshold > c and i < n - 1:
            i += 1
            c += weights[i]
        out.append(i)
    return out
