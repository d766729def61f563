# method: math.log of both probabilities, math.ceil of the ratio
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    return math.ceil(math.log(1 - confidence) / math.log(1 - inlier_ratio**sample_size))
