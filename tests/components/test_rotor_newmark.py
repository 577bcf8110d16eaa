"""Newmark-beta against the exact response of a damped single-degree-of-freedom oscillator."""
import math

import numpy as np
import pytest

from rotorcosim.components.rotor.newmark import integrate, step_operator

M, K, ZETA = 2.0, 8.0e5, 0.02
WN = math.sqrt(K / M)
C = 2 * ZETA * WN * M
F0, W = 100.0, 0.7 * WN


def exact(t):
    """x'' + 2 zeta wn x' + wn^2 x = (F0/M) cos(W t), x(0) = x'(0) = 0: steady part + free decay."""
    r = W / WN
    den = (1 - r * r) ** 2 + (2 * ZETA * r) ** 2
    A = F0 / K * (1 - r * r) / den
    B = F0 / K * 2 * ZETA * r / den
    wd = WN * math.sqrt(1 - ZETA ** 2)
    c1 = -A
    c2 = (ZETA * WN * c1 - B * W) / wd
    return A * np.cos(W * t) + B * np.sin(W * t) + np.exp(-ZETA * WN * t) * (c1 * np.cos(wd * t) + c2 * np.sin(wd * t))


def _run(h, T_end=0.02):
    n = int(round(T_end / h))
    x = integrate(np.array([[M]]), np.array([[C]]), np.array([[K]]), lambda t: np.array([F0 * math.cos(W * t)]),
                  np.zeros(1), np.zeros(1), h, n)[:, 0]
    t = np.arange(n + 1) * h
    return np.max(np.abs(x - exact(t)))


def test_newmark_second_order_against_exact_sdof():
    """Average acceleration (beta = 1/4, gamma = 1/2): the max error over 0.02 s (10 periods) against the exact
    SDOF solution falls by 4 per halving of h (observed order 2 +- 0.1 over three halvings)."""
    hs = [wn_h / WN for wn_h in (0.2, 0.1, 0.05, 0.025)]
    err = [_run(h) for h in hs]
    orders = np.log2(np.array(err[:-1]) / np.array(err[1:]))
    assert np.all(np.abs(orders - 2.0) < 0.1), orders
    assert err[-1] < 2e-3 * F0 / K


def test_step_operator_equals_classical_form():
    """The one-matrix step s_{n+1} = T s_n + B f_{n+1} used by the component reproduces the classical
    three-vector Newmark recursion (same algorithm, different algebra) to round-off, on a random damped
    gyroscopic-like (non-symmetric C) 3-DOF system."""
    rng = np.random.default_rng(0)
    A = rng.normal(size=(3, 3))
    Mm = A @ A.T + 3 * np.eye(3)
    Kk = 1e4 * (np.eye(3) * 3 + 0.5 * (A + A.T))
    Cc = 5.0 * np.eye(3) + 20.0 * (A - A.T)
    h, n = 1e-3, 200

    def force(t):
        return np.array([math.sin(50 * t), 0.0, math.cos(30 * t)])

    ref = integrate(Mm, Cc, Kk, force, np.zeros(3), np.zeros(3), h, n)
    T, B = step_operator(Mm, Cc, Kk, h)
    s = np.concatenate([np.zeros(3), np.zeros(3), np.linalg.solve(Mm, force(0.0))])
    for k in range(1, n + 1):
        s = T @ s + B @ force(k * h)
    np.testing.assert_allclose(s[:3], ref[-1], rtol=1e-9, atol=1e-12 * np.max(np.abs(ref)))


@pytest.mark.parametrize("beta,gamma", [(0.0, 0.5), (0.25, 0.4), (float("nan"), 0.5)])
def test_bad_newmark_parameters(beta, gamma):
    with pytest.raises(ValueError, match="Newmark"):
        step_operator(np.eye(1), np.eye(1), np.eye(1), 1e-3, beta, gamma)


@pytest.mark.parametrize("h", [0.0, -1e-5, float("nan")])
def test_bad_step(h):
    with pytest.raises(ValueError, match="step size"):
        step_operator(np.eye(1), np.eye(1), np.eye(1), h)
