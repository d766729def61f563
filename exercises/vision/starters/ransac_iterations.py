import math


def ransac_iterations(inlier_ratio, sample_size, confidence):
    """Number of RANSAC samples needed.

    inlier_ratio: w, the fraction of the data that are inliers (0 < w < 1).
    sample_size:  s, points per minimal sample (int, e.g. 5 for the 5-point essential matrix).
    confidence:   p, the required probability of drawing at least one all-inlier sample
                  (0 < p < 1, e.g. 0.99).

    Returns the smallest whole number of samples N that reaches the confidence (an int).
    """
    raise NotImplementedError("TODO: return the number of RANSAC iterations")
