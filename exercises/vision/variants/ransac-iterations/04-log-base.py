# method: a logarithm in base (1 - w^s) with math.log(x, base), then -floor(-x) as the ceiling
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    n = math.log(1 - confidence, 1 - inlier_ratio**sample_size)
    return -math.floor(-n)
