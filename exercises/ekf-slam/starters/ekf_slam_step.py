import numpy as np


def ekf_slam_step(mu, Sigma, u, M, z, ids, R):
    """One full EKF-SLAM step: predict with the odometry u, then each measurement in turn.

    mu: (3 + 2N,) state, Sigma: its covariance; u = (rot1, trans, rot2) with noise
    covariance M (3×3); z: [[r, phi], ...] with ids[k] the landmark of z[k] (a mapped one,
    < N, is an update; N, N + 1, ... are new landmarks, appended); R: 2×2 measurement noise.
    Returns np.vstack([mu_new, Sigma_new]), shape (n' + 1, n').
    """
    raise NotImplementedError("predict, then update or augment for each measurement")
