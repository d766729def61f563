# mistake: w instead of w^s, as if a sample were one point
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    return math.ceil(math.log(1 - confidence) / math.log(1 - inlier_ratio))
