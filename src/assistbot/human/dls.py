"""One damped-least-squares IK step of the arm, compiled with numba when available.

`dls_step` does, in one call, what costs ~25 small numpy calls otherwise (the error, the
6x7 Jacobian's normal matrix, a Cholesky solve, joint limits):

    e  = [p_t - p, 0.4 log(R_t R')]            (position m, rotation rad, weighted)
    J  = [Jp; 0.4 Jr]
    r  = 0.02 (q_rest - q)                      (a weak pull toward the rest posture)
    dq = r + J' (J J' + 4e-4 I)^-1 (e - J r)    (DLS with r in the null space)
    q' = clip(q + dq, lo, hi)

`dls_step_numpy` is the same in numpy (the reference; used without numba).
"""

from __future__ import annotations

import math

import numpy as np

DAMPING = 4e-4
ROT_WEIGHT = 0.4
REST_PULL = 0.02


def dls_step_numpy(p_t, R_t, p, R, jacp, jacr, q, q_rest, lo, hi):
    from assistbot.human.arm import _log_rot

    e = np.concatenate([p_t - p, ROT_WEIGHT * _log_rot(R_t @ R.T)])
    J = np.vstack([jacp, ROT_WEIGHT * jacr])
    A = J @ J.T + DAMPING * np.eye(6)
    r = REST_PULL * (q_rest - q)
    y = np.linalg.solve(A, e - J @ r)
    return np.minimum(np.maximum(q + r + J.T @ y, lo), hi)


def _dls_step_py(p_t, R_t, p, R, jacp, jacr, q, q_rest, lo, hi):  # pragma: no cover - compiled by numba
    n = q.shape[0]
    # rotation error: log of M = R_t R'
    M = R_t @ R.T
    c = (M[0, 0] + M[1, 1] + M[2, 2] - 1.0) * 0.5
    c = min(1.0, max(-1.0, c))
    a = math.acos(c)
    w = np.empty(3)
    w[0] = M[2, 1] - M[1, 2]
    w[1] = M[0, 2] - M[2, 0]
    w[2] = M[1, 0] - M[0, 1]
    if a < 1e-6:
        w *= 0.5
    elif a > math.pi - 1e-4:
        k = 0
        for i in range(1, 3):
            if M[i, i] > M[k, k]:
                k = i
        v = M[:, k].copy()
        v[k] += 1.0
        w = a * v / math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    else:
        w *= a / (2.0 * math.sin(a))
    e = np.empty(6)
    J = np.empty((6, n))
    for i in range(3):
        e[i] = p_t[i] - p[i]
        e[3 + i] = ROT_WEIGHT * w[i]
        for j in range(n):
            J[i, j] = jacp[i, j]
            J[3 + i, j] = ROT_WEIGHT * jacr[i, j]
    r = REST_PULL * (q_rest - q)
    b = e - J @ r
    A = J @ J.T
    for i in range(6):
        A[i, i] += DAMPING
    # Cholesky A = L L', then L L' y = b
    L = np.zeros((6, 6))
    for i in range(6):
        for j in range(i + 1):
            s = A[i, j]
            for k in range(j):
                s -= L[i, k] * L[j, k]
            if i == j:
                L[i, i] = math.sqrt(s)
            else:
                L[i, j] = s / L[j, j]
    z = np.empty(6)
    for i in range(6):
        s = b[i]
        for k in range(i):
            s -= L[i, k] * z[k]
        z[i] = s / L[i, i]
    y = np.empty(6)
    for i in range(5, -1, -1):
        s = z[i]
        for k in range(i + 1, 6):
            s -= L[k, i] * y[k]
        y[i] = s / L[i, i]
    out = q + r + J.T @ y
    for j in range(n):
        out[j] = min(max(out[j], lo[j]), hi[j])
    return out


def _bounded_py(q_new, q_cmd, lo, hi, max_step):  # pragma: no cover - compiled by numba
    """Move the commanded angles toward q_new by at most max_step each, within [lo, hi];
    returns the new command and the largest step taken."""
    out = q_cmd.copy()
    big = 0.0
    for j in range(q_cmd.shape[0]):
        d = min(max(q_new[j] - q_cmd[j], -max_step), max_step)
        out[j] = min(max(q_cmd[j] + d, lo[j]), hi[j])
        big = max(big, abs(out[j] - q_cmd[j]))
    return out, big


def _pose_at_py(s, p0, dp, R0, K, K2, angle):  # pragma: no cover - compiled by numba
    """Position p0 + s dp and rotation R0 + sin(s angle) K + (1 - cos(s angle)) K2 (a segment at progress s)."""
    a = s * angle
    sa, ca = math.sin(a), 1.0 - math.cos(a)
    return p0 + s * dp, R0 + sa * K + ca * K2


def _bounded_numpy(q_new, q_cmd, lo, hi, max_step):
    out = np.minimum(np.maximum(q_cmd + np.clip(q_new - q_cmd, -max_step, max_step), lo), hi)
    return out, float(np.abs(out - q_cmd).max())


try:
    from numba import njit

    dls_step = njit(cache=True)(_dls_step_py)
    bounded = njit(cache=True)(_bounded_py)
    pose_at = njit(cache=True)(_pose_at_py)
    BACKEND = "numba"
except ImportError:  # pragma: no cover
    dls_step = dls_step_numpy
    bounded = _bounded_numpy
    pose_at = _pose_at_py
    BACKEND = "numpy"
