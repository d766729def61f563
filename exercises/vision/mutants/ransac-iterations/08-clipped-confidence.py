# mistake: the confidence clipped to 0.999 "to avoid log(0)": too few samples at p = 0.9999
import numpy as np


def ransac_iterations(inlier_ratio, sample_size, confidence):
    p = np.clip(confidence, 0.5, 0.999)
    return int(np.ceil(np.log(1 - p) / np.log(1 - inlier_ratio**sample_size)))
