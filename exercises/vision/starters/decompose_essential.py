import numpy as np


def decompose_essential(E, x1, x2):
    """The relative pose [R | t] (3×4, ‖t‖ = 1) encoded in the essential matrix E.

    E: 3×3, E = s·[t]×R for some scale s ≠ 0 (either sign), convention X2 = R X1 + t.
    x1, x2: one match in normalised coordinates [u, v, 1] (image 1, image 2).
    Of the four candidates (U W Vᵀ or U Wᵀ Vᵀ, with t = ±u₃) return the one that puts the
    triangulated point in front of both cameras.
    """
    raise NotImplementedError("SVD, four candidates, then the cheirality test")
