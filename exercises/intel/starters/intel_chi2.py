import math

import numpy as np


def intel_chi2(text, iterations):
    """The chi-squared of a 2-D g2o pose graph after Gauss-Newton, pose 0 fixed.

    text: the whole g2o file (VERTEX_SE2 id x y theta; EDGE_SE2 i j dx dy dtheta + the upper
          triangle I11 I12 I13 I22 I23 I33 of the information matrix).
    iterations: the number of undamped Gauss-Newton steps (0 or more).
    Returns one number: sum over the edges of e^T Omega e at the optimised poses.
    """
    raise NotImplementedError("copy in your optimiser, then sum e^T Omega e over the edges")
