def marginal_covariance(H, block):
    """The marginal covariance of the variables in `block`: the block (H^-1)[block, block].

    H:     n x n symmetric positive-definite information matrix (nested lists or array).
    block: 1 ... n distinct indices, in the order the result must use.

    Returns a k x k array (k = len(block)) whose entry (r, s) is the covariance of variables
    block[r] and block[s]. Do not change H or block.
    """
    raise NotImplementedError("TODO: recover a block of the inverse of H")
