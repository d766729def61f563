# mistake: a search loop that keeps going while the confidence is merely reached (<= instead of <): one too many on an exact tie
def ransac_iterations(inlier_ratio, sample_size, confidence):
    clean = inlier_ratio**sample_size
    n, all_bad = 0, 1.0
    while 1 - all_bad <= confidence:
        n += 1
        all_bad *= 1 - clean
    return n
