# method: one multivariate_normal draw of the three noisy controls with a diagonal covariance, wrapped with %
import numpy as np


def sample_motion(pose, u, alphas, n, seed):
    rng = np.random.default_rng(seed)
    a1, a2, a3, a4 = alphas
    rot1, trans, rot2 = u
    cov = np.diag([a1 * rot1**2 + a2 * trans**2, a3 * trans**2 + a4 * (rot1**2 + rot2**2), a1 * rot2**2 + a2 * trans**2])
    ctrl = rng.multivariate_normal(np.array(u, dtype=float), cov, size=n)
    h = pose[2] + ctrl[:, 0]
    heading = (h + ctrl[:, 2] + np.pi) % (2 * np.pi) - np.pi
    heading[heading == -np.pi] = np.pi
    return np.column_stack([pose[0] + ctrl[:, 1] * np.cos(h), pose[1] + ctrl[:, 1] * np.sin(h), heading])
