# mistake: rounds to the nearest whole number instead of up
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    return round(math.log(1 - confidence) / math.log(1 - inlier_ratio**sample_size))
