import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    clean = inlier_ratio ** sample_size
    return math.ceil(math.log(1 - confidence) / math.log(1 - clean))
