def marginalise(H, b, keep):
    """Marginalise every variable not in `keep` out of the information form (H, b).

    H:    n x n symmetric positive-definite information matrix (nested lists or array).
    b:    n numbers, the information vector.
    keep: 1 ... n-1 distinct indices, in the order the result must use.

    Returns a k x (k+1) array [H' | b'] with k = len(keep):
        H' = H_aa - H_am H_mm^-1 H_ma,   b' = b_a - H_am H_mm^-1 b_m
    where a = keep and m = every other index. Do not change H, b or keep.
    """
    raise NotImplementedError("TODO: the Schur complement of the variables not in keep")
