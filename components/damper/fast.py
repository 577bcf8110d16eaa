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

The same pass gives the exact derivatives of that force with respect to (mu v_r, mu v_t) (the full-film nodes'
unit fields) and to eps (the Lagrange weights' derivatives), from which frame.to_housing_axes makes the
K_film = dF/dd and C_film = dF/dw outputs: no extra evaluation, so the bearing's linearly implicit
integration costs nothing more here. Without cavitation dF/dw is exactly the tabulated unit forces.

The only difference from the direct FE model is the interpolation in eps (measured in bench_damper.py and the
tests). Above eps_max (the FE film's own limit, reynolds_fe.EPS_FILM_MAX) the film is held at its eps_max
value (wall.py). Tables are built lazily once per process and geometry (cache key: radius, length,
clearance, mesh, table size): 60 sparse factorisations, about 3 s, or read from the on-disk cache
(table_cache.py) in milliseconds.
"""
from __future__ import annotations

import math
from collections import namedtuple
from functools import lru_cache

import numpy as np
from numba import njit

from . import table_cache
from .frame import EPS_DIFF, EPS_NEAR_CENTRE, frame, to_housing_axes
from .wall import NOT_FINITE, spring_and_wall
from .reynolds_fe import EPS_FILM_MAX, build_mesh, film_force_aligned, unit_fields

EPS_MAX = EPS_FILM_MAX   # table end = the film model's limit (reynolds_fe); the film saturates beyond it
N_TABLE = 60        # table points in u = -ln(1 - eps); step 0.078 (convergence: see the tests / bench)


@njit(cache=True)
def _lagrange4(u, u0, du, n):
    """Start index, 4-point Lagrange weights and their u-derivatives at u on the grid u0 + k du, k < n."""
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
    d0 = -(3.0 * x * x - 12.0 * x + 11.0) / 6.0 / du
    d1 = (3.0 * x * x - 10.0 * x + 6.0) / 2.0 / du
    d2 = -(3.0 * x * x - 8.0 * x + 3.0) / 2.0 / du
    d3 = (3.0 * x * x - 6.0 * x + 2.0) / 6.0 / du
    return k, w0, w1, w2, w3, d0, d1, d2, d3


@njit(cache=True, fastmath=True)
def _clipped(TR, TT, Wc, Ws, eps, u0, du, n, a, b, floor):
    """Aligned force of the Guembel-clipped interpolated field and its derivatives, in one pass over the nodes.

    F = -2 sum_i max(a P_r,i + b P_t,i, floor) (Wc_i, Ws_i) with P_r, P_t interpolated at eps in the tables
    TR, TT (n_table, n_nodes). Returns F_r, F_t, dF_r/da, dF_r/db, dF_t/da, dF_t/db, dF_r/deps, dF_t/deps
    (derivatives of the clipped sum: only the nodes above the floor move). fastmath lets the sums vectorise
    (reassociation: the result is still the same for the same inputs on the same machine).
    """
    u = -math.log1p(-eps)
    k, w0, w1, w2, w3, d0, d1, d2, d3 = _lagrange4(u, u0, du, n)
    r0 = TR[k]
    r1 = TR[k + 1]
    r2 = TR[k + 2]
    r3 = TR[k + 3]
    q0 = TT[k]
    q1 = TT[k + 1]
    q2 = TT[k + 2]
    q3 = TT[k + 3]
    fc = 0.0
    fs = 0.0
    rc = 0.0
    rs = 0.0
    tc = 0.0
    ts = 0.0
    uc = 0.0
    us = 0.0
    for i in range(Wc.shape[0]):
        pr = w0 * r0[i] + w1 * r1[i] + w2 * r2[i] + w3 * r3[i]
        pt = w0 * q0[i] + w1 * q1[i] + w2 * q2[i] + w3 * q3[i]
        p = a * pr + b * pt
        # branch-free (vectorises): m = 1 on the full-film nodes, 0 on the clipped ones
        m = 1.0 if p >= floor else 0.0
        q = m * p + (1.0 - m) * floor
        wc = Wc[i]
        ws = Ws[i]
        fc += wc * q
        fs += ws * q
        mwc = m * wc
        mws = m * ws
        rc += mwc * pr
        rs += mws * pr
        tc += mwc * pt
        ts += mws * pt
        dp = (a * (d0 * r0[i] + d1 * r1[i] + d2 * r2[i] + d3 * r3[i])
              + b * (d0 * q0[i] + d1 * q1[i] + d2 * q2[i] + d3 * q3[i]))
        uc += mwc * dp
        us += mws * dp
    du_deps = 1.0 / (1.0 - eps)
    return (-2.0 * fc, -2.0 * fs, -2.0 * rc, -2.0 * tc, -2.0 * rs, -2.0 * ts,
            -2.0 * uc * du_deps, -2.0 * us * du_deps)


@njit(cache=True)
def _linear(ftab, eps, u0, du, n, a, b):
    """Like _clipped without cavitation, from the unit forces ftab (n_table, 4) =
    [F_r(v_r), F_t(v_r), F_r(v_t), F_t(v_t)] per unit mu v: the force is exactly linear in (a, b)."""
    u = -math.log1p(-eps)
    k, w0, w1, w2, w3, d0, d1, d2, d3 = _lagrange4(u, u0, du, n)
    f = w0 * ftab[k] + w1 * ftab[k + 1] + w2 * ftab[k + 2] + w3 * ftab[k + 3]
    g = (d0 * ftab[k] + d1 * ftab[k + 1] + d2 * ftab[k + 2] + d3 * ftab[k + 3]) / (1.0 - eps)
    return (a * f[0] + b * f[2], a * f[1] + b * f[3], f[0], f[2], f[1], f[3],
            a * g[0] + b * g[2], a * g[1] + b * g[3])


@njit(cache=True)
def _aligned(TR, TT, ftab, bounds, Wc, Ws, eps, u0, du, n, a, b, floor, cavitation):
    """Aligned force and derivatives. With cavitation, when no node can fall below the floor the clipped sum
    is the linear one (the same interpolated field, summed in the other order), so the cheap path is exact:
    |P_i(eps)| <= sum_k |w_k| max_i |P_k,i| (bounds[k] = (max |P_r|, max |P_t|) of table point k)."""
    if cavitation:
        u = -math.log1p(-eps)
        k, w0, w1, w2, w3, d0, d1, d2, d3 = _lagrange4(u, u0, du, n)
        mr = abs(w0) * bounds[k, 0] + abs(w1) * bounds[k + 1, 0] + abs(w2) * bounds[k + 2, 0] \
            + abs(w3) * bounds[k + 3, 0]
        mt = abs(w0) * bounds[k, 1] + abs(w1) * bounds[k + 1, 1] + abs(w2) * bounds[k + 2, 1] \
            + abs(w3) * bounds[k + 3, 1]
        if -(abs(a) * mr + abs(b) * mt) < floor:
            return _clipped(TR, TT, Wc, Ws, eps, u0, du, n, a, b, floor)
    return _linear(ftab, eps, u0, du, n, a, b)


@njit(cache=True)
def film_eval(TR, TT, ftab, bounds, Wc, Ws, u0, du, n, eps_max, clearance, dx, dy, dvx, dvy, mu, floor, cavitation,
              out):
    """Film force F (2), K = dF/dd (4) and C = dF/dw (4) in the housing axes into out[0:10].

    d = (dx, dy), w = (dvx, dvy): journal minus housing. Beyond eps_max the film is evaluated at eps_max in
    the direction of d (the saturated film of the component's wall model), so dF/de = 0 there.
    """
    e, c, s = frame(dx, dy)
    eps = e / clearance
    saturated = eps > eps_max
    ef = eps_max if saturated else eps
    vr = c * dvx + s * dvy
    vt = -s * dvx + c * dvy
    a = mu * vr
    b = mu * vt
    r = _aligned(TR, TT, ftab, bounds, Wc, Ws, ef, u0, du, n, a, b, floor, cavitation)
    Fr, Ft, Jra, Jrb, Jta, Jtb, dr, dt = r
    if saturated:
        dr = 0.0
        dt = 0.0
    gr = -Ft + Jra * b - Jrb * a
    gt = Fr + Jta * b - Jtb * a
    e_div = e
    if eps < EPS_NEAR_CENTRE:
        r0 = _aligned(TR, TT, ftab, bounds, Wc, Ws, 0.0, u0, du, n, a, b, floor, cavitation)
        g0r = -r0[1] + r0[2] * b - r0[3] * a
        g0t = r0[0] + r0[4] * b - r0[5] * a
        if e == 0.0:
            r1 = _aligned(TR, TT, ftab, bounds, Wc, Ws, EPS_DIFF, u0, du, n, a, b, floor, cavitation)
            gr = -r1[1] + r1[2] * b - r1[3] * a
            gt = r1[0] + r1[4] * b - r1[5] * a
            e_div = EPS_DIFF * clearance
        gr -= g0r
        gt -= g0t
    to_housing_axes(c, s, e_div, clearance, mu, Fr, Ft, Jra, Jrb, Jta, Jtb, dr, dt, gr, gt, out)


@njit(cache=True)
def fast_step(TR, TT, ftab, bounds, Wc, Ws, prm, xj, vj, xh, vh, mu, out):
    """One damper evaluation in a single call: film (F, K, C), spring, wall, F_journal and P_film into out
    (the component's layout: see component._Damper.OUT). Returns a wall.* status code.

    prm = [u0, du, n_table, eps_max, clearance, floor, cavitation, k_spring, k_wall] (one array: fewer
    arguments to type-check on each call from Python).
    """
    u0, du, n, eps_max, clearance = prm[0], prm[1], int(prm[2]), prm[3], prm[4]
    floor, cavitation, k_spring, k_wall = prm[5], prm[6] != 0.0, prm[7], prm[8]
    dx = xj[0] - xh[0]
    dy = xj[1] - xh[1]
    dvx = vj[0] - vh[0]
    dvy = vj[1] - vh[1]
    if not math.isfinite(dx + dy + dvx + dvy + mu):
        return NOT_FINITE
    film_eval(TR, TT, ftab, bounds, Wc, Ws, u0, du, n, eps_max, clearance, dx, dy, dvx, dvy, mu, floor, cavitation, out)
    out[16] = -(out[0] * dvx + out[1] * dvy)
    return spring_and_wall(dx, dy, clearance, k_spring, k_wall, out)


class FilmTable:
    """Tabulated unit fields of one damper geometry and mesh (build with :func:`film_table`)."""

    def __init__(self, radius, length, clearance, n_theta, n_z, n_table=N_TABLE, eps_max=EPS_MAX):
        if n_table < 10:   # also keeps the point below eps = 0 above eps = -1 (du < ln 2)
            raise ValueError(f"n_table must be >= 10, got {n_table}")
        self.mesh = build_mesh(radius, length, n_theta, n_z)
        self.clearance = clearance
        self.eps_max = eps_max
        # one point below eps = 0 (journal displaced the other way in the aligned frame) so that the stencil
        # about the centre is centred: the forces are even in eps, and a one-sided stencil would give them a
        # spurious slope at eps = 0 (a kink in K_film through the centre)
        self.du = -math.log(1.0 - eps_max) / (n_table - 2)
        self.u0 = -self.du
        self.n = n_table
        self.eps = 1.0 - np.exp(-(self.u0 + self.du * np.arange(n_table)))
        key = table_cache.key(radius, length, clearance, n_theta, n_z, n_table, eps_max)
        cached = table_cache.load(key)
        if cached is not None:
            TR, TT, ftab = cached["TR"], cached["TT"], cached["ftab"]
        else:
            # P_r and P_t in separate contiguous tables: unit-stride loads let the clipped-force loop vectorise
            TR = np.empty((n_table, self.mesh.n_nodes))
            TT = np.empty((n_table, self.mesh.n_nodes))
            ftab = np.empty((n_table, 4))
            for k, e in enumerate(self.eps):
                TR[k], TT[k] = unit_fields(self.mesh, clearance, float(e))
                ftab[k, :2] = film_force_aligned(self.mesh, TR[k])
                ftab[k, 2:] = film_force_aligned(self.mesh, TT[k])
            table_cache.save(key, {"TR": TR, "TT": TT, "ftab": ftab})
        self.TR, self.TT, self.ftab = TR, TT, ftab
        self.bounds = np.stack([np.abs(TR).max(axis=1), np.abs(TT).max(axis=1)], axis=1)
        self.Wc = np.ascontiguousarray(self.mesh.Wc)
        self.Ws = np.ascontiguousarray(self.mesh.Ws)

    def evaluate(self, dx, dy, dvx, dvy, mu, floor, cavitation, out):
        """F (2), K_film (4), C_film (4) of the film into out[0:10] (see film_eval)."""
        film_eval(self.TR, self.TT, self.ftab, self.bounds, self.Wc, self.Ws, self.u0, self.du, self.n,
                  self.eps_max, self.clearance, dx, dy, dvx, dvy, mu, floor, cavitation, out)


@lru_cache(maxsize=4)
def film_table(radius, length, clearance, n_theta, n_z, n_table=N_TABLE, eps_max=EPS_MAX) -> FilmTable:
    """The table of a geometry, built once per process (the arguments are the cache key)."""
    return FilmTable(float(radius), float(length), float(clearance), int(n_theta), int(n_z), int(n_table),
                     float(eps_max))


def fast_film_force(table: FilmTable, dx, dy, dvx, dvy, mu, supply_pressure, cavitation_pressure, cavitation):
    """(Fx, Fy) like reynolds_fe.fe_film_force, from the table (film saturated at the table's eps_max)."""
    out = np.empty(10)
    table.evaluate(float(dx), float(dy), float(dvx), float(dvy), float(mu),
                   float(cavitation_pressure - supply_pressure), bool(cavitation), out)
    return float(out[0]), float(out[1])


#: the fast damper's kernel constants (components/kernels.py; the damper has no state): the tables and parameters
#: of fast_step, its output buffer, a cache [T, mu(T)] and the oil's viscosity constants (viscosity.py)
DamperParams = namedtuple("DamperParams", "TR TT ftab bounds Wc Ws prm out cache walther_A walther_B rho300 drho")


@njit(cache=True)
def oil_viscosity(p, T):
    """SAE 30 dynamic viscosity at T (viscosity.sae30_viscosity), kept for the last T."""
    if T != p.cache[0]:
        nu_cst = 10.0 ** (10.0 ** (p.walther_A - p.walther_B * math.log10(T))) - 0.7
        p.cache[1] = nu_cst * 1e-6 * (p.rho300 + p.drho * (T - 300.0))
        p.cache[0] = T
    return p.cache[1]


@njit(cache=True)
def tm_step(s, p, u, y, t, h):
    """One evaluation at the step's inputs (components/kernels.py contract). Status 5: T_oil outside the
    viscosity fit; 10 + a wall.* code."""
    T = u.T_oil[0]
    if not (T > 200.0 and T <= 600.0):
        return 5
    mu = oil_viscosity(p, T)
    out = p.out
    status = fast_step(p.TR, p.TT, p.ftab, p.bounds, p.Wc, p.Ws, p.prm, u.X_journal, u.V_journal, u.X_housing,
                       u.V_housing, mu, out)
    if status != 0:
        return 10 + status
    for k in range(2):
        y.F_film[k] = out[k]
        y.F_spring[k] = out[10 + k]
        y.F_contact[k] = out[12 + k]
        y.F_journal[k] = out[14 + k]
        y.F_housing[k] = -out[14 + k]
    for k in range(4):
        y.K_film[k] = out[2 + k]
        y.C_film[k] = out[6 + k]
    y.P_film[0] = out[16]
    y.mu[0] = mu
    return 0
