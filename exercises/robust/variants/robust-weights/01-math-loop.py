# method: a loop over the entries with math, one formula per kernel, returning a list
import math


def robust_weights(kind, s, k):
    out = []
    for v in s:
        v = float(v)
        if kind == "huber":
            out.append(1.0 if v <= k * k else k / math.sqrt(v))
        elif kind == "cauchy":
            out.append(k * k / (k * k + v))
        elif kind == "dcs":
            out.append(min(1.0, 2 * k * k / (k * k + v)) ** 2)
        else:
            out.append(1.0)
    return out
