# method: plain lists and triple loops, no numpy
import math


def matmul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def transpose(A):
    return [[A[j][i] for j in range(3)] for i in range(3)]


def predict_covariance(pose, u, sigma, motion_cov):
    rot1, trans, _ = u
    c, s = math.cos(pose[2] + rot1), math.sin(pose[2] + rot1)
    G = [[1, 0, -trans * s], [0, 1, trans * c], [0, 0, 1]]
    V = [[-trans * s, c, 0], [trans * c, s, 0], [1, 0, 1]]
    a = matmul(matmul(G, sigma), transpose(G))
    b = matmul(matmul(V, motion_cov), transpose(V))
    return [[a[i][j] + b[i][j] for j in range(3)] for i in range(3)]
