"""Rotations and linear algebra for the kernels: Pinocchio's ``exp3`` and ``log3`` (same
Taylor branches and thresholds), and Cholesky factor, inverse and solve of symmetric positive
definite matrices (numba's ``np.linalg`` would need SciPy's LAPACK). Products sum in index
order, so results equal NumPy's and Pinocchio's to rounding, not bit for bit."""

from __future__ import annotations

import math

import numpy as np

from lightrocks.adapters.kernels.jit import kernel

_EPS = float(np.finfo(float).eps)
_PREC2 = _EPS ** (1.0 / 3.0)
_PREC3 = _EPS**0.25
"""Pinocchio's ``TaylorSeriesExpansion<double>::precision<2>()`` and ``<3>()``."""


@kernel
def exp3(v0: float, v1: float, v2: float, out: np.ndarray) -> None:
    """Rotation matrix of the rotation vector (Pinocchio's ``exp3``) into ``out`` (9, row-major:
    flat arrays, since a reshape costs a numba call ~25 ns)."""
    t2 = v0 * v0 + v1 * v1 + v2 * v2 + _EPS * _EPS
    t = math.sqrt(t2)
    st, ct = math.sin(t), math.cos(t)
    if t > _PREC3:
        a_vxvx, a_vx = (1 - ct) / t2, st / t
    else:
        a_vxvx, a_vx, ct = 0.5 - t2 / 24, 1.0 - t2 / 6, 1.0 - t2 / 2
    a0, a1, a2 = a_vxvx * v0, a_vxvx * v1, a_vxvx * v2
    out[0] = a0 * v0 + ct
    out[1] = a0 * v1 - a_vx * v2
    out[2] = a0 * v2 + a_vx * v1
    out[3] = a1 * v0 + a_vx * v2
    out[4] = a1 * v1 + ct
    out[5] = a1 * v2 - a_vx * v0
    out[6] = a2 * v0 - a_vx * v1
    out[7] = a2 * v1 + a_vx * v0
    out[8] = a2 * v2 + ct


@kernel
def _theta_axis(i0: int, val: float, r: np.ndarray, axis: np.ndarray) -> float:
    """Angle and axis of a rotation ``r`` (9, row-major) near π from its column ``i0``
    (Pinocchio's ``compute_theta_axis``); returns the angle, ``axis`` receives the unit axis."""
    i1, i2 = (i0 + 1) % 3, (i0 + 2) % 3
    s = math.sqrt(val + _EPS + _EPS * _EPS)
    if r[3 * i2 + i1] < r[3 * i1 + i2]:
        s = -s
    axis[i0] = s / 2
    axis[i1] = 1.0 / (2 * s) * (r[3 * i1 + i0] + r[3 * i0 + i1])
    axis[i2] = 1.0 / (2 * s) * (r[3 * i2 + i0] + r[3 * i0 + i2])
    w = 1.0 / (2 * s) * (r[3 * i2 + i1] - r[3 * i1 + i2])
    norm = math.sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2])
    axis[0] /= norm
    axis[1] /= norm
    axis[2] /= norm
    return 2 * math.atan2(norm, w)


@kernel
def log3(r_in: np.ndarray, out: np.ndarray, r: np.ndarray) -> None:
    """Rotation vector of a rotation matrix ``r_in`` (9, row-major) into ``out`` (3):
    Pinocchio's ``log3``, including its renormalisation and its branches near 0 and π. ``r``
    (9) is scratch space."""
    n0 = math.sqrt(r_in[0] ** 2 + r_in[3] ** 2 + r_in[6] ** 2)
    n1 = math.sqrt(r_in[1] ** 2 + r_in[4] ** 2 + r_in[7] ** 2)
    for i in range(3):
        r[3 * i] = r_in[3 * i] / n0
        r[3 * i + 1] = r_in[3 * i + 1] / n1
    r[2] = r[3] * r[7] - r[6] * r[4]  # col2 = col0 x col1
    r[5] = r[6] * r[1] - r[0] * r[7]
    r[8] = r[0] * r[4] - r[3] * r[1]
    c0 = r[4] * r[8] - r[7] * r[5]  # col0 = col1 x col2
    c1 = r[7] * r[2] - r[1] * r[8]
    c2 = r[1] * r[5] - r[4] * r[2]
    r[0], r[3], r[6] = c0, c1, c2
    tr = r[0] + r[4] + r[8]
    cos_value = (tr - 1) / 2
    if cos_value < -1 + _PREC2:  # θ near π: the axis from the largest diagonal element
        axis = np.empty(3)
        vals = (2 * r[0] - tr + 1, 2 * r[4] - tr + 1, 2 * r[8] - tr + 1)
        if vals[0] >= vals[1]:
            i0 = 0 if vals[0] >= vals[2] else 2
        else:
            i0 = 1 if vals[1] >= vals[2] else 2
        theta = _theta_axis(i0, vals[i0], r, axis)
        out[0], out[1], out[2] = theta * axis[0], theta * axis[1], theta * axis[2]
        return
    acos_expansion = math.sqrt(2 * (1 - cos_value) + _EPS * _EPS)
    if tr <= 3 - _PREC2:
        theta = math.acos(cos_value) if tr >= -1 + _PREC2 else math.pi - acos_expansion
    else:
        theta = acos_expansion
    a0 = 0.5 * (r[7] - r[5])
    a1 = 0.5 * (r[2] - r[6])
    a2 = 0.5 * (r[3] - r[1])
    if theta >= _PREC2:
        t = theta / math.sin(theta)
    else:
        n2 = a0 * a0 + a1 * a1 + a2 * a2
        t = 1.0 + n2 / 6 + n2 * n2 * 3 / 40
    out[0], out[1], out[2] = t * a0, t * a1, t * a2


@kernel
def cholesky(a: np.ndarray, low: np.ndarray) -> None:
    """The lower Cholesky factor L of a symmetric positive definite matrix ``a`` (its lower
    triangle is read) into ``low``, whose upper triangle is left alone."""
    n = a.shape[0]
    for j in range(n):
        total = a[j, j]
        for m in range(j):
            total -= low[j, m] * low[j, m]
        low[j, j] = math.sqrt(total)
        for i in range(j + 1, n):
            total = a[i, j]
            for m in range(j):
                total -= low[i, m] * low[j, m]
            low[i, j] = total / low[j, j]


@kernel
def spd_inverse(a: np.ndarray, out: np.ndarray) -> None:
    """Inverse of a symmetric positive definite matrix by its Cholesky factor L:
    ``a⁻¹ = L⁻ᵀ L⁻¹`` (numba's ``np.linalg.inv`` needs SciPy's LAPACK)."""
    n = a.shape[0]
    low = np.zeros((n, n))
    cholesky(a, low)
    inv = np.zeros((n, n))  # L⁻¹, lower triangular
    for j in range(n):
        inv[j, j] = 1.0 / low[j, j]
        for i in range(j + 1, n):
            total = 0.0
            for m in range(j, i):
                total += low[i, m] * inv[m, j]
            inv[i, j] = -total / low[i, i]
    for i in range(n):
        for j in range(i, n):
            total = 0.0
            for m in range(j, n):
                total += inv[m, i] * inv[m, j]
            out[i, j] = out[j, i] = total


@kernel
def cholesky_solve(low: np.ndarray, b: np.ndarray) -> None:
    """Solve ``L Lᵀ x = b`` in place of ``b``, with L the lower triangle of ``low``."""
    n = b.shape[0]
    for i in range(n):
        total = b[i]
        for m in range(i):
            total -= low[i, m] * b[m]
        b[i] = total / low[i, i]
    for i in range(n - 1, -1, -1):
        total = b[i]
        for m in range(i + 1, n):
            total -= low[m, i] * b[m]
        b[i] = total / low[i, i]
