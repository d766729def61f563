# method: fully vectorised over edges with numpy (einsum and add.at), numpy-only parser
import numpy as np


def parse(text):
    verts, edges = {}, []
    for line in text.splitlines():
        f = line.split()
        if f[:1] == ["VERTEX_SE2"]:
            verts[int(f[1])] = np.array(f[2:5], dtype=float)
        elif f[:1] == ["EDGE_SE2"]:
            edges.append(np.array(f[1:12], dtype=float))
    x = np.array([verts[k] for k in sorted(verts)])
    E = np.array(edges).reshape(-1, 11)
    i, j = E[:, 0].astype(int), E[:, 1].astype(int)
    u = E[:, 5:]
    om = np.stack(
        [u[:, [0, 1, 2]], u[:, [1, 3, 4]], u[:, [2, 4, 5]]], axis=1
    )  # rows of the symmetric matrices
    return x, i, j, E[:, 2:5], om


def rot_t(t):
    c, s = np.cos(t), np.sin(t)
    R = np.empty((len(t), 2, 2))
    R[:, 0, 0], R[:, 0, 1], R[:, 1, 0], R[:, 1, 1] = c, s, -s, c
    return R


def linearise(x, i, j, z, om):
    d = x[j, :2] - x[i, :2]
    Ri, Rz = rot_t(x[i, 2]), rot_t(z[:, 2])
    RzRi = Rz @ Ri
    exy = np.einsum("kab,kb->ka", Rz, np.einsum("kab,kb->ka", Ri, d) - z[:, :2])
    et = np.angle(np.exp(1j * (x[j, 2] - x[i, 2] - z[:, 2])))
    e = np.column_stack([exy, et])
    dRi = np.empty_like(Ri)
    c, s = np.cos(x[i, 2]), np.sin(x[i, 2])
    dRi[:, 0, 0], dRi[:, 0, 1], dRi[:, 1, 0], dRi[:, 1, 1] = -s, c, -c, -s
    m = len(i)
    A, B = np.zeros((m, 3, 3)), np.zeros((m, 3, 3))
    A[:, :2, :2] = -RzRi
    A[:, :2, 2] = np.einsum("kab,kb->ka", Rz @ dRi, d)
    A[:, 2, 2] = -1
    B[:, :2, :2] = RzRi
    B[:, 2, 2] = 1
    return e, A, B


def optimise_g2o(text, iterations):
    x, i, j, z, om = parse(text)
    n = len(x)
    for _ in range(iterations):
        e, A, B = linearise(x, i, j, z, om)
        H = np.zeros((n, 3, n, 3))
        b = np.zeros((n, 3))
        AtO, BtO = np.einsum("kba,kbc->kac", A, om), np.einsum("kba,kbc->kac", B, om)
        np.add.at(H, (i, slice(None), i), AtO @ A)
        np.add.at(H, (i, slice(None), j), AtO @ B)
        np.add.at(H, (j, slice(None), i), BtO @ A)
        np.add.at(H, (j, slice(None), j), BtO @ B)
        np.add.at(b, i, np.einsum("kab,kb->ka", AtO, e))
        np.add.at(b, j, np.einsum("kab,kb->ka", BtO, e))
        H = H.reshape(3 * n, 3 * n)
        step = np.linalg.solve(H[3:, 3:], -b.reshape(-1)[3:])
        x[1:] += step.reshape(-1, 3)
        x[:, 2] = np.angle(np.exp(1j * x[:, 2]))
    d = x[:, :2] - x[0, :2]
    c, s = np.cos(x[0, 2]), np.sin(x[0, 2])
    rel = np.column_stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1], x[:, 2] - x[0, 2]])
    rel[:, 2] = np.angle(np.exp(1j * rel[:, 2]))
    return rel
