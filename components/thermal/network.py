"""A lumped linear heat-transfer network, eq. (12) at every node, and its time integration.

    C_k dT_k/dt = sum_j G_kj (T_j - T_k) + g_k (T_ground,k - T_k) + q_k           (eq. 12 at node k)

i.e. ``C dT/dt = -K T + b + S u`` with K the conductance matrix (branches + ground conductances), b the ground
terms and S the map from the power inputs u to the node heat sources.

Integration, with the inputs held constant over a step (the master gives their mean over the step, so the energy
of a step is exactly ``u h``):

* ``"exact"`` (default): the exact solution of the linear ODE for a held input (zero-order-hold discretisation),
  ``T1 = Phi T0 + Gamma (b + S u)``, ``Phi = exp(A h)``, ``Gamma = int_0^h exp(A s) ds C^-1``, ``A = -C^-1 K``.
  It is unconditionally stable and L-stable like backward Euler, but without its O(h) error, so a 0.1 s
  thermal-only step and a 1 ms thermo-mechanical step give the same temperatures for the same held powers, and
  the energy balance holds to round-off. Phi and Gamma come from one matrix exponential (Van Loan) per step size.
* ``"backward-euler"``: ``(C/h + K) T1 = C/h T0 + b + S u``, first order, kept for comparison.

Both cache their step matrices per step size (a few step sizes are used in a run).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import expm

METHODS = ("exact", "backward-euler")


@dataclass
class LinearNetwork:
    """Heat masses ``C`` (n,), conductance matrix ``K`` (n, n), ground term ``b`` (n,), source map ``S`` (n, m)."""

    C: np.ndarray
    K: np.ndarray
    b: np.ndarray
    S: np.ndarray
    ground: np.ndarray = None            # (n,) conductance of each node to its ground (for heat-out bookkeeping)
    T_ground: np.ndarray = None          # (n,) temperature of that ground
    _cache: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        self.C = np.asarray(self.C, float)
        self.K = np.asarray(self.K, float)
        self.b = np.asarray(self.b, float)
        self.S = np.asarray(self.S, float).reshape(len(self.C), -1)
        n = len(self.C)
        if self.K.shape != (n, n) or self.b.shape != (n,):
            raise ValueError(f"network shapes: C {self.C.shape}, K {self.K.shape}, b {self.b.shape}")
        if not np.all(np.isfinite(self.C)) or np.any(self.C <= 0.0):
            raise ValueError(f"heat masses must be finite and > 0, got {self.C}")
        if not np.all(np.isfinite(self.K)):
            raise ValueError("conductance matrix has non-finite entries")
        if self.ground is None:
            self.ground = np.zeros(n)
        if self.T_ground is None:
            self.T_ground = np.zeros(n)

    @property
    def n(self) -> int:
        return len(self.C)

    def steady(self, u) -> np.ndarray:
        """The steady state K T = b + S u (the analytic solution the integration must reach)."""
        return np.linalg.solve(self.K, self.b + self.S @ np.asarray(u, float))

    def heat_out(self, T) -> float:
        """Heat flow to the grounds (ambient, oil supply) at temperatures T, W."""
        return float(self.ground @ (np.asarray(T, float) - self.T_ground))

    def stored(self, T, T_ref) -> float:
        """Heat stored relative to the temperatures T_ref, J."""
        return float(self.C @ (np.asarray(T, float) - np.asarray(T_ref, float)))

    def step_matrices(self, h: float, method: str = "exact"):
        """(Phi, Gamma_b, Gamma_S) with T1 = Phi T0 + Gamma_b + Gamma_S u, cached per (h, method)."""
        # the master's step sizes come from differences of times: round so that equal steps share an entry
        key = (float(f"{h:.12g}"), method)
        hit = self._cache.get(key)
        if hit is not None:
            return hit
        if not (np.isfinite(h) and h > 0.0):
            raise ValueError(f"step size must be finite and > 0, got {h}")
        n = self.n
        if method == "exact":
            A = -self.K / self.C[:, None]
            M = np.zeros((2 * n, 2 * n))
            M[:n, :n] = A * h
            M[:n, n:] = np.eye(n) * h
            E = expm(M)
            Phi = E[:n, :n]
            Gam = E[:n, n:] / self.C[None, :]      # int_0^h exp(A s) ds  C^-1
        elif method == "backward-euler":
            inv = np.linalg.inv(np.diag(self.C / h) + self.K)
            Phi = inv * (self.C / h)[None, :]
            Gam = inv
        else:
            raise ValueError(f"integration method {method!r} not in {METHODS}")
        out = (np.ascontiguousarray(Phi), Gam @ self.b, np.ascontiguousarray(Gam @ self.S))
        if len(self._cache) > 16:           # a run uses two or three step sizes; keep the cache bounded
            self._cache.clear()
        self._cache[key] = out
        return out

    def step(self, T, u, h: float, method: str = "exact") -> np.ndarray:
        last = self.__dict__.get("_last")
        if last is not None and last[0] == h and last[1] == method:
            Phi, gb, GS = last[2]
        else:
            Phi, gb, GS = self.step_matrices(h, method)
            self._last = (h, method, (Phi, gb, GS))
        return Phi @ T + gb + GS @ u
