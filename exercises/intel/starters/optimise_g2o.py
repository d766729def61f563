import math

import numpy as np


def optimise_g2o(text, iterations):
    """Optimise the 2-D pose graph in a g2o file with undamped Gauss-Newton, pose 0 fixed.

    text: the whole g2o file (VERTEX_SE2 id x y theta; EDGE_SE2 i j dx dy dtheta + the upper
          triangle I11 I12 I13 I22 I23 I33 of the information matrix).
    iterations: the number of Gauss-Newton steps.
    Returns an n x 3 array: every optimised pose seen from pose 0, angles in (-pi, pi].
    """
    raise NotImplementedError("read the vertices and edges, then run your Gauss-Newton")
