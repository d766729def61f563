# mistake: the count capped at 10000 "like a maximum iteration setting": wrong when more samples are needed
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    n = math.ceil(math.log(1 - confidence) / math.log(1 - inlier_ratio**sample_size))
    return min(n, 10000)
