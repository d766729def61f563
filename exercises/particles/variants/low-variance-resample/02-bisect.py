# method: the standard library: an accumulated list and bisect_left per threshold
import bisect
import itertools


def low_variance_resample(weights, u):
    n = len(weights)
    total = sum(float(w) for w in weights)
    c = list(itertools.accumulate(float(w) / total for w in weights))
    return [min(bisect.bisect_left(c, (u + m) / n), n - 1) for m in range(n)]
