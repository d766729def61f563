def epipolar_residual(E, x, x2):
    """Residual of the epipolar constraint x2ᵀ E x.

    E:  essential matrix, shape (3, 3), list of rows.
    x:  point in the first image, normalised homogeneous coordinates [u, v, 1], shape (3,).
    x2: the matching point x′ in the second image, same form.

    Returns the number x2ᵀ E x (0 for a perfect correspondence; unitless).
    """
    raise NotImplementedError("TODO: return x2^T E x")
