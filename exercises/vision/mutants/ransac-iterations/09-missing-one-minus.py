# mistake: log(w^s) in the denominator instead of log(1 - w^s)
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    return math.ceil(math.log(1 - confidence) / math.log(inlier_ratio**sample_size))
