# method: no logarithm: add samples one by one until the chance of at least one clean sample reaches p
def ransac_iterations(inlier_ratio, sample_size, confidence):
    clean = 1.0
    for _ in range(sample_size):
        clean *= inlier_ratio
    n, all_bad = 0, 1.0
    while 1 - all_bad < confidence:
        n += 1
        all_bad *= 1 - clean
    return n
