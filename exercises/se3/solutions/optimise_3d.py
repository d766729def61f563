import numpy as np
from scipy.linalg import solveh_banded
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import reverse_cuthill_mckee

# the generators of so(3): [w]× = w₀ G₀ + w₁ G₁ + w₂ G₂
_G = np.array(
    [
        [[0, 0, 0], [0, 0, -1], [0, 1, 0]],
        [[0, 0, 1], [0, 0, 0], [-1, 0, 0]],
        [[0, -1, 0], [1, 0, 0], [0, 0, 0]],
    ],
    dtype=float,
).reshape(3, 9)


def _hat(w):
    """``[w]×`` of every row of ``w``: shape (K, 3, 3)."""
    return (w @ _G).reshape(-1, 3, 3)


def _exp(w):
    """``Exp(w)`` and ``V(w)`` (Exp of a twist moves by ``V ρ``) of every rotation vector."""
    t = np.linalg.norm(w, axis=1)[:, None, None]
    small = t < 1e-4
    s = np.where(small, 1.0, t)
    sin, cos = np.sin(s), np.cos(s)
    a = np.where(small, 1 - t**2 / 6, sin / s)
    b = np.where(small, 0.5 - t**2 / 24, (1 - cos) / s**2)
    c = np.where(small, 1 / 6 - t**2 / 120, (s - sin) / s**3)
    k = _hat(w)
    kk = k @ k
    return np.eye(3) + a * k + b * kk, np.eye(3) + b * k + c * kk


def _log(r):
    """Rotation vectors of a stack of rotations (angles below pi: a pose graph's errors)."""
    v = 0.5 * np.stack(
        [r[:, 2, 1] - r[:, 1, 2], r[:, 0, 2] - r[:, 2, 0], r[:, 1, 0] - r[:, 0, 1]], 1
    )
    s = np.linalg.norm(v, axis=1)
    theta = np.arctan2(s, (np.trace(r, axis1=1, axis2=2) - 1) / 2)
    return np.where(theta < 1e-4, 1 + theta**2 / 6, theta / np.where(s > 0, s, 1.0))[:, None] * v


def _jr_inverse(w):
    """``J_r⁻¹(w)`` of every rotation vector: shape (K, 3, 3)."""
    t = np.linalg.norm(w, axis=1)[:, None, None]
    small = t < 1e-4
    s = np.where(small, 1.0, t)
    d = np.where(small, 1 / 12, 1 / s**2 - (1 + np.cos(s)) / (2 * s * np.sin(s)))
    k = _hat(w)
    return np.eye(3) + 0.5 * k + d * (k @ k)


def _rpy(roll, pitch, yaw):
    """``R_z(yaw) R_y(pitch) R_x(roll)``, in closed form: shape (K, 3, 3)."""
    cr, sr, cp, sp = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch)
    cy, sy = np.cos(yaw), np.sin(yaw)
    # fmt: off
    return np.stack([
        cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
        sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
        -sp,     cp * sr,                cp * cr,
    ], axis=-1).reshape(-1, 3, 3)
    # fmt: on


def optimise_3d(text, iterations):
    rows = [f[1:30] for f in map(str.split, text.splitlines()) if f and f[0] == "EDGE3"]
    v = np.array(rows, dtype=float)
    i, j = v[:, 0].astype(np.intp), v[:, 1].astype(np.intp)
    n, m = int(max(i.max(), j.max())) + 1, len(v)
    # the measurement Z = (rz, tz) of every edge and its information Ω = SᵀS
    rz, tz = _rpy(v[:, 5], v[:, 6], v[:, 7]), v[:, 2:5]
    upper = np.zeros((m, 6, 6))
    upper[:, *np.triu_indices(6)] = v[:, 8:]
    omega = upper.transpose(0, 2, 1) @ upper

    # initial guess: the odometry edges (k, k + 1) composed from pose 0 at the identity;
    # every pose k is (r[k], t[k])
    r, t = np.zeros((n, 3, 3)), np.zeros((n, 3))
    r[0] = np.eye(3)
    odometry = np.zeros(n - 1, dtype=np.intp)  # the line of edge (k, k + 1)
    odometry[i[j == i + 1]] = np.flatnonzero(j == i + 1)
    for k, e in enumerate(odometry):
        r[k + 1] = r[k] @ rz[e]
        t[k + 1] = t[k] + r[k] @ tz[e]

    # H without pose 0 is sparse, and banded once the free poses are renumbered so that every
    # edge links poses close in the new order (reverse Cuthill-McKee): on sphere2500's windows,
    # a ladder of odometry and loop closures 50 poses apart, 36 diagonals instead of up to 564.
    free = (i > 0) & (j > 0)
    fi, fj = i[free] - 1, j[free] - 1
    links = coo_matrix((np.ones(2 * len(fi)), (np.r_[fi, fj], np.r_[fj, fi])), (n - 1, n - 1))
    order = np.empty(n, dtype=np.intp)  # the new number of every pose; pose 0 is out (-1)
    order[0] = -1
    order[1 + reverse_cuthill_mckee(links.tocsr(), symmetric_mode=True)] = np.arange(n - 1)
    size = 6 * (n - 1)
    u = 6 * int(np.max(np.abs(order[fi + 1] - order[fj + 1]), initial=0)) + 5  # diagonals above
    # the columns of every edge's poses i and j, and where each entry of its Jᵀ Ω J lands in
    # H's upper band storage (entries of pose 0, and those below the diagonal, dropped)
    cols = np.concatenate([6 * order[i, None] + np.arange(6), 6 * order[j, None] + np.arange(6)], 1)
    row, col = np.broadcast_arrays(cols[:, :, None], cols[:, None, :])
    in_h = ((row >= 0) & (row <= col)).ravel()
    cells = ((u + row - col) * size + col).ravel()[in_h]
    in_b = cols.ravel() >= 0

    jac = np.zeros((m, 6, 13))  # [A | B | e] of every edge
    rzt = rz.transpose(0, 2, 1)
    jac[:, :3, 0:3] = -rzt
    for _ in range(int(iterations)):
        # Y = X_i⁻¹ X_j and E = Z⁻¹ Y
        ri_t = r[i].transpose(0, 2, 1)
        ry = ri_t @ r[j]
        ty = (ri_t @ (t[j] - t[i])[:, :, None])[:, :, 0]
        re = rzt @ ry
        te = (rzt @ (ty - tz)[:, :, None])[:, :, 0]
        phi = _log(re)
        # B = diag(R_E, J_r⁻¹(φ)) and A = -B Ad(Y⁻¹), Ad(Y⁻¹) = [[R_Yᵀ, -R_Yᵀ[t_Y]×], [0, R_Yᵀ]]:
        # A = [[-R_Zᵀ, R_Zᵀ [t_Y]×], [0, -J_r⁻¹ R_Yᵀ]] since R_E R_Yᵀ = R_Zᵀ
        jr_inv = _jr_inverse(phi)
        jac[:, :3, 6:9], jac[:, 3:, 9:12] = re, jr_inv
        jac[:, :3, 3:6] = rzt @ _hat(ty)
        jac[:, 3:, 3:6] = -jr_inv @ ry.transpose(0, 2, 1)
        jac[:, :3, 12], jac[:, 3:, 12] = te, phi
        # Jᵀ Ω [J | e] (m × 12 × 13) holds every edge's blocks of H and entries of b
        q = jac[:, :, :12].transpose(0, 2, 1) @ omega @ jac
        band = np.bincount(cells, q[:, :, :12].ravel()[in_h], (u + 1) * size)
        b = np.bincount(cols.ravel()[in_b], q[:, :, 12].ravel()[in_b], size)
        step = solveh_banded(band.reshape(u + 1, size), -b, check_finite=False)
        # X ⊞ δ = X Exp(δ): R ← R Exp(φ), t ← t + R V(φ) ρ (pose 0 stays)
        d = step.reshape(-1, 6)[order[1:]]  # back to the poses' order
        ex, vx = _exp(d[:, 3:])
        rho = d[:, :3]
        t[1:] += (r[1:] @ (vx @ rho[:, :, None]))[:, :, 0]
        r[1:] = r[1:] @ ex
    # positions seen from pose 0: R_0ᵀ (t_k - t_0)
    return (t - t[0]) @ r[0]
