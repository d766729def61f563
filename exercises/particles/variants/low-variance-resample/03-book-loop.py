# method: Probabilistic Robotics' loop with r = u/N and the increment 1/N, in unnormalised units
def low_variance_resample(weights, u):
    n = len(weights)
    total = sum(weights)
    r = u / n * total
    step = total / n
    c = weights[0]
    i = 0
    out = []
    for m in range(n):
        threshold = r + m * step
        while threshold > c and i < n - 1:
            i += 1
            c += weights[i]
        out.append(i)
    return out
