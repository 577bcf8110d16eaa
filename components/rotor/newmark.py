"""Newmark-beta integration of M x'' + C x' + K x = f, the paper's integrator (section 4.1, its ref. [19]:
Newmark 1959; the algebra as in Bathe, Finite Element Procedures, 9.2.4), applied to the reduced eq. (21).

Displacement form with (beta, gamma) = (1/4, 1/2) by default (average acceleration: unconditionally stable, no
numerical damping, second order, period error ~ (w h)^2 / 12). The matrices are constant (constant speeds, so
the gyroscopic matrix is constant), so one step is a fixed linear map of the state s = (x, v, a) and of the force
at the end of the step:

    s_{n+1} = T s_n + B f_{n+1},

T and B are formed once per step size from the inverse of the effective matrix
A = K + gamma/(beta h) C + 1/(beta h^2) M. A step is then two small matrix-vector products.
"""
from __future__ import annotations

import numpy as np


def check_parameters(beta: float, gamma: float) -> None:
    if not (np.isfinite(beta) and np.isfinite(gamma) and beta > 0.0 and gamma >= 0.5):
        raise ValueError(f"Newmark parameters need beta > 0 and gamma >= 1/2 (stability), got beta={beta}, "
                         f"gamma={gamma}")


def step_operator(M, C, K, h: float, beta: float = 0.25, gamma: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    """(T, B) of one Newmark step of size h for the state s = [x, v, a]."""
    if not (np.isfinite(h) and h > 0.0):
        raise ValueError(f"step size must be finite and > 0, got {h}")
    check_parameters(beta, gamma)
    n = M.shape[0]
    I = np.eye(n)
    A = K + gamma / (beta * h) * C + M / (beta * h * h)
    Ainv = np.linalg.inv(A)
    Px = Ainv @ (M / (beta * h * h) + C * (gamma / (beta * h)))
    Pv = Ainv @ (M / (beta * h) + C * (gamma / beta - 1.0))
    Pa = Ainv @ (M * (1.0 / (2 * beta) - 1.0) + C * (h * (gamma / (2 * beta) - 1.0)))
    c0 = 1.0 / (beta * h * h)
    Ax = (Px - I) * c0
    Av = Pv * c0 - I / (beta * h)
    Aa = Pa * c0 - (1.0 / (2 * beta) - 1.0) * I
    Af = Ainv * c0
    T = np.zeros((3 * n, 3 * n))
    B = np.zeros((3 * n, n))
    T[:n, :n], T[:n, n:2 * n], T[:n, 2 * n:] = Px, Pv, Pa
    B[:n] = Ainv
    T[2 * n:, :n], T[2 * n:, n:2 * n], T[2 * n:, 2 * n:] = Ax, Av, Aa
    B[2 * n:] = Af
    # v1 = v + h (1 - gamma) a + h gamma a1
    T[n:2 * n, :n] = h * gamma * Ax
    T[n:2 * n, n:2 * n] = I + h * gamma * Av
    T[n:2 * n, 2 * n:] = h * (1.0 - gamma) * I + h * gamma * Aa
    B[n:2 * n] = h * gamma * Af
    return T, B


def initial_acceleration(M, C, K, x0, v0, f0) -> np.ndarray:
    """a0 from the equation of motion at t0 (consistent start)."""
    return np.linalg.solve(M, f0 - C @ v0 - K @ x0)


def integrate(M, C, K, force, x0, v0, h: float, n_steps: int, beta=0.25, gamma=0.5, record=None):
    """Integrate ``n_steps`` from t = 0 with force(t) -> vector; returns the displacement history
    (n_steps + 1, len(record)) (all rows without ``record``). The classical three-vector form (Bathe 9.2.4), cheaper
    than :func:`step_operator` for the full model; the reference integrator of the checks."""
    check_parameters(beta, gamma)
    n = M.shape[0]
    a0c, a1c = 1.0 / (beta * h * h), gamma / (beta * h)
    a2c, a3c = 1.0 / (beta * h), 1.0 / (2 * beta) - 1.0
    a4c, a5c = gamma / beta - 1.0, h * (gamma / (2 * beta) - 1.0)
    Ainv = np.linalg.inv(K + a1c * C + a0c * M)
    x, v = np.array(x0, float), np.array(v0, float)
    a = initial_acceleration(M, C, K, x, v, force(0.0))
    rows = np.arange(n) if record is None else np.asarray(record)
    out = np.empty((n_steps + 1, rows.size))
    out[0] = x[rows]
    for k in range(1, n_steps + 1):
        rhs = force(k * h) + M @ (a0c * x + a2c * v + a3c * a) + C @ (a1c * x + a4c * v + a5c * a)
        x1 = Ainv @ rhs
        a1 = a0c * (x1 - x) - a2c * v - a3c * a
        v = v + h * ((1.0 - gamma) * a + gamma * a1)
        x, a = x1, a1
        out[k] = x[rows]
    return out
