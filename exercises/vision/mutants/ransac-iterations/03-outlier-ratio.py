# mistake: (1 - w)^s, the chance of an all-outlier sample, in place of w^s
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    outliers = 1 - inlier_ratio
    return math.ceil(math.log(1 - confidence) / math.log(1 - outliers**sample_size))
