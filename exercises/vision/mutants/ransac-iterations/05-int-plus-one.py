# mistake: int(x) + 1 used as "round up": one too many when the ratio is a whole number
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    return int(math.log(1 - confidence) / math.log(1 - inlier_ratio**sample_size)) + 1
