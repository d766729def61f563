import math

import numpy as np


def so3_log(R):
    """The rotation vector w = theta * n of a 3 x 3 rotation matrix R.

    R: nested lists or an array, R^T R = I, det R = +1; its angle is anywhere in [0, pi].
    Returns (wx, wy, wz) in radians with |w| in [0, pi]; at exactly pi, the one whose
    largest-magnitude component is positive.
    """
    raise NotImplementedError("the angle with atan2, then the axis (mind tiny angles and pi)")
