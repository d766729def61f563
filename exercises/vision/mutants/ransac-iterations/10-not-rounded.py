# mistake: returns the real-valued bound without rounding it to a whole number of samples
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    return math.log(1 - confidence) / math.log(1 - inlier_ratio**sample_size)
