# mistake: int() truncates, i.e. rounds down
import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    return int(math.log(1 - confidence) / math.log(1 - inlier_ratio**sample_size))
