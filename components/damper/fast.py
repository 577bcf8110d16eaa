"""The fast film model: exact structure of the FE solution plus a table over the eccentricity ratio.

Structure exploited (see reynolds_fe): in the frame of the eccentricity the film depends on the eccentricity
ratio eps only, and before cavitation the pressure is linear in the velocities and the viscosity:

    p - p_s = mu (v_r P_r(eps) + v_t P_t(eps)).

The nodal unit fields P_r, P_t of the paper's FE mesh are tabulated at eps_k = 1 - exp(-u_k), u uniform in
[0, -ln(1 - eps_max)] (the fields grow like (1 - eps)^-2.5: uniform in u they vary smoothly), and interpolated
with 4-point Lagrange polynomials in u. Then:

* without cavitation the force is mu (v_r F_r + v_t F_t) with the tabulated unit forces (a few flops);
* with Guembel cavitation the force is the integral of the clipped field max(p, p_cav), which is NOT linear
  (and with p_s != p_cav not even homogeneous in |v|), so it is evaluated exactly on the interpolated nodal
  field by a numba kernel (one pass over the nodes, the same force weights as the FE model).

The only difference from the direct FE model is the interpolation in eps (measured in bench_damper.py and the
tests). Above eps_max the model calls the direct FE solve (slow, exact). Tables are built lazily once per
process and geometry (cache key: radius, length, clearance, mesh, table size): about a second.
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit

from .reynolds_fe import build_mesh, film_force_aligned, unit_fields

EPS_MAX = 0.99      # table end; beyond it the direct FE solve is used
N_TABLE = 60        # table points in u = -ln(1 - eps); step 0.078 (convergence: see the tests / bench)


@njit(cache=True)
def _lagrange4(u, u0, du, n):
    """Start index and 4-point Lagrange weights at u on the uniform grid u0 + k du, k < n."""
    s = (u - u0) / du
    k = int(math.floor(s)) - 1
    if k < 0:
        k = 0
    if k > n - 4:
        k = n - 4
    x = s - k
    w0 = -(x - 1.0) * (x - 2.0) * (x - 3.0) / 6.0
    w1 = x * (x - 2.0) * (x - 3.0) / 2.0
    w2 = -x * (x - 1.0) * (x - 3.0) / 2.0
    w3 = x * (x - 1.0) * (x - 2.0) / 6.0
    return k, w0, w1, w2, w3


@njit(cache=True)
def _clipped_force(tab, Wc, Ws, k, w0, w1, w2, w3, a, b, floor):
    """(F_r, F_t) = -2 sum_i max(a P_r,i + b P_t,i, floor) (Wc_i, Ws_i), P interpolated in the table.

    tab has shape (n_table, n_nodes, 2): (P_r, P_t) per node; a = mu v_r, b = mu v_t, floor = p_cav - p_s.
    """
    sc = 0.0
    ss = 0.0
    t0 = tab[k]
    t1 = tab[k + 1]
    t2 = tab[k + 2]
    t3 = tab[k + 3]
    for n in range(Wc.shape[0]):
        pr = w0 * t0[n, 0] + w1 * t1[n, 0] + w2 * t2[n, 0] + w3 * t3[n, 0]
        pt = w0 * t0[n, 1] + w1 * t1[n, 1] + w2 * t2[n, 1] + w3 * t3[n, 1]
        p = a * pr + b * pt
        if p < floor:
            p = floor
        sc += Wc[n] * p
        ss += Ws[n] * p
    return -2.0 * sc, -2.0 * ss


@njit(cache=True)
def _linear_force(ftab, k, w0, w1, w2, w3, a, b):
    """(F_r, F_t) without cavitation: ftab (n_table, 4) = unit forces [F_r(v_r), F_t(v_r), F_r(v_t), F_t(v_t)]."""
    f = w0 * ftab[k] + w1 * ftab[k + 1] + w2 * ftab[k + 2] + w3 * ftab[k + 3]
    return a * f[0] + b * f[2], a * f[1] + b * f[3]


class FilmTable:
    """Tabulated unit fields of one damper geometry and mesh (build with :func:`film_table`)."""

    def __init__(self, radius, length, clearance, n_theta, n_z, n_table=N_TABLE, eps_max=EPS_MAX):
        if n_table < 4:
            raise ValueError(f"n_table must be >= 4, got {n_table}")
        self.mesh = build_mesh(radius, length, n_theta, n_z)
        self.clearance = clearance
        self.eps_max = eps_max
        self.u0 = 0.0
        self.du = -math.log(1.0 - eps_max) / (n_table - 1)
        self.n = n_table
        self.eps = 1.0 - np.exp(-self.du * np.arange(n_table))
        tab = np.empty((n_table, self.mesh.n_nodes, 2))
        ftab = np.empty((n_table, 4))
        for k, e in enumerate(self.eps):
            Pr, Pt = unit_fields(self.mesh, clearance, float(e))
            tab[k, :, 0], tab[k, :, 1] = Pr, Pt
            ftab[k, :2] = film_force_aligned(self.mesh, Pr)
            ftab[k, 2:] = film_force_aligned(self.mesh, Pt)
        self.tab, self.ftab = tab, ftab
        self.Wc = np.ascontiguousarray(self.mesh.Wc)
        self.Ws = np.ascontiguousarray(self.mesh.Ws)

    def force_aligned(self, eps, a, b, floor, cavitation):
        """(F_r, F_t) at eccentricity ratio eps < eps_max, a = mu v_r, b = mu v_t, floor = p_cav - p_s."""
        u = -math.log1p(-eps)
        k, w0, w1, w2, w3 = _lagrange4(u, self.u0, self.du, self.n)
        if cavitation:
            return _clipped_force(self.tab, self.Wc, self.Ws, k, w0, w1, w2, w3, a, b, floor)
        return _linear_force(self.ftab, k, w0, w1, w2, w3, a, b)


@lru_cache(maxsize=4)
def film_table(radius, length, clearance, n_theta, n_z, n_table=N_TABLE, eps_max=EPS_MAX) -> FilmTable:
    """The table of a geometry, built once per process (the arguments are the cache key)."""
    return FilmTable(float(radius), float(length), float(clearance), int(n_theta), int(n_z), int(n_table),
                     float(eps_max))


def fast_film_force(table: FilmTable, dx, dy, dvx, dvy, mu, supply_pressure, cavitation_pressure, cavitation):
    """(Fx, Fy) like reynolds_fe.fe_film_force, from the table (direct FE above the table's eps_max)."""
    e = math.hypot(dx, dy)
    if e > 0.0:
        c, s = dx / e, dy / e
    else:
        c, s = 1.0, 0.0
    eps = e / table.clearance
    if eps > table.eps_max:
        from .reynolds_fe import fe_film_force
        return fe_film_force(table.mesh, table.clearance, dx, dy, dvx, dvy, mu, supply_pressure,
                             cavitation_pressure, cavitation)
    vr, vt = c * dvx + s * dvy, -s * dvx + c * dvy
    Fr, Ft = table.force_aligned(eps, mu * vr, mu * vt, cavitation_pressure - supply_pressure, cavitation)
    return c * Fr - s * Ft, s * Fr + c * Ft
