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
  field by a numba kernel with the same force weights as the FE model. The nodes are grouped in small tiles
  whose force-weighted sums and field bounds are tabulated too: a tile the bounds show wholly full-film (or
  wholly cavitated) adds its interpolated sums (or the floor times its weights), and only the tiles the film's
  rupture boundary crosses are summed node by node (the same sum in another order: equal to round-off).

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
from numba import types

from ..numba_internals import address_of, by_address, call_at, kernel_jit
from . import table_cache
from .frame import EPS_DIFF, EPS_NEAR_CENTRE, frame, to_housing_axes
from .supply import condition
from .wall import NOT_FINITE, dry_land, spring_and_wall
from .reynolds_fe import EPS_FILM_MAX, build_mesh, film_force_aligned, unit_fields

EPS_MAX = EPS_FILM_MAX   # table end = the film model's limit (reynolds_fe); the film saturates beyond it
N_TABLE = 60        # table points in u = -ln(1 - eps); step 0.078 (convergence: see the tests / bench)


@kernel_jit
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


@kernel_jit(fastmath=True, inline="always")
def _clipped_nodes(NT, Wc, Ws, n, k, w0, w1, w2, w3, d0, d1, d2, d3, a, b, floor, i0, i1, acc):
    """The clipped sums over the nodes i0 <= i < i1 of one tile, added into acc[0:8] = F_r, F_t (without the
    factor -2), dF_r/da, dF_r/db, dF_t/da, dF_t/db, dF_r/du, dF_t/du.

    Per node: P_r, P_t interpolated at the step's eps, p = a P_r + b P_t, q = max(p, floor) summed with the force
    weights; the derivatives of the clipped sum move with the full-film nodes only. The tile's fields are one
    block of NT (FilmTable: P_r at the n table points, then P_t, each nt = i1 - i0 long). fastmath lets the
    sums vectorise (reassociation: the result is still the same for the same inputs on the same machine)."""
    nt = i1 - i0
    # views from offset 0, indexed by the loop counter: a computed index could be negative for all numba knows
    # (wraparound check per load), which stops the loop from vectorising
    br = i0 * 2 * n + k * nt
    bt = br + n * nt
    R0 = NT[br:br + nt]
    R1 = NT[br + nt:br + 2 * nt]
    R2 = NT[br + 2 * nt:br + 3 * nt]
    R3 = NT[br + 3 * nt:br + 4 * nt]
    Q0 = NT[bt:bt + nt]
    Q1 = NT[bt + nt:bt + 2 * nt]
    Q2 = NT[bt + 2 * nt:bt + 3 * nt]
    Q3 = NT[bt + 3 * nt:bt + 4 * nt]
    WC = Wc[i0:i1]
    WS = Ws[i0:i1]
    fc = 0.0
    fs = 0.0
    rc = 0.0
    rs = 0.0
    tc = 0.0
    ts = 0.0
    uc = 0.0
    us = 0.0
    for i in range(nt):
        r0 = R0[i]
        r1 = R1[i]
        r2 = R2[i]
        r3 = R3[i]
        q0 = Q0[i]
        q1 = Q1[i]
        q2 = Q2[i]
        q3 = Q3[i]
        pr = w0 * r0 + w1 * r1 + w2 * r2 + w3 * r3
        pt = w0 * q0 + w1 * q1 + w2 * q2 + w3 * q3
        p = a * pr + b * pt
        # branch-free (vectorises): m = 1 on the full-film nodes, 0 on the clipped ones
        m = 1.0 if p >= floor else 0.0
        q = m * p + (1.0 - m) * floor
        wc = WC[i]
        ws = WS[i]
        fc += wc * q
        fs += ws * q
        mwc = m * wc
        mws = m * ws
        rc += mwc * pr
        rs += mws * pr
        tc += mwc * pt
        ts += mws * pt
        dp = a * (d0 * r0 + d1 * r1 + d2 * r2 + d3 * r3) + b * (d0 * q0 + d1 * q1 + d2 * q2 + d3 * q3)
        uc += mwc * dp
        us += mws * dp
    acc[0] += fc
    acc[1] += fs
    acc[2] += rc
    acc[3] += tc
    acc[4] += rs
    acc[5] += ts
    acc[6] += uc
    acc[7] += us


@kernel_jit(fastmath=True)
def _clipped(NT, G, TW, toff, bounds, Wc, Ws, eps, u0, du, n, a, b, floor):
    """Aligned force of the Guembel-clipped interpolated field and its derivatives.

    F = -2 sum_i max(a P_r,i + b P_t,i, floor) (Wc_i, Ws_i) with P_r, P_t interpolated at eps in the table.
    Returns F_r, F_t, dF_r/da, dF_r/db, dF_t/da, dF_t/db, dF_r/deps, dF_t/deps (derivatives of the clipped
    sum: only the nodes above the floor move).

    The nodes are grouped in tiles (FilmTable): per table point and tile, G holds the tile's force-weighted sums
    [sum Wc P_r, sum Ws P_r, sum Wc P_t, sum Ws P_t] and bounds [min P_r, max P_r, min P_t, max P_t]. The
    interpolated field of a tile lies between the Lagrange weights times those bounds; a tile whose lower bound
    clears the floor (by a round-off margin) is wholly full-film, and its share of every sum is its weighted
    sums interpolated (linear in the table values: the same numbers summed in another order); a tile wholly
    below the floor is wholly cavitated (floor times its weights, no derivative). Only the tiles the bounds
    cannot decide (those the film's rupture boundary crosses, ~8 % of the nodes on the blade-loss orbits) are
    summed node by node.
    """
    u = -math.log1p(-eps)
    k, w0, w1, w2, w3, d0, d1, d2, d3 = _lagrange4(u, u0, du, n)
    # the tile bounds lo <= p_i <= hi: sum over the table points j of w_j (a P_r + b P_t), each term bounded by
    # the tile's min or max of P_r and P_t as the signs of w_j a and w_j b say (columns 4-7 of G)
    a0, a1, a2, a3 = w0 * a, w1 * a, w2 * a, w3 * a
    b0, b1, b2, b3 = w0 * b, w1 * b, w2 * b, w3 * b
    r0 = 4 if a0 >= 0.0 else 5
    r1 = 4 if a1 >= 0.0 else 5
    r2 = 4 if a2 >= 0.0 else 5
    r3 = 4 if a3 >= 0.0 else 5
    q0 = 6 if b0 >= 0.0 else 7
    q1 = 6 if b1 >= 0.0 else 7
    q2 = 6 if b2 >= 0.0 else 7
    q3 = 6 if b3 >= 0.0 else 7
    # a round-off margin: a tile within it of the floor is summed node by node (as the untiled sum would)
    tol = 1e-9 * (abs(a) * (bounds[k, 0] + bounds[k + 1, 0] + bounds[k + 2, 0] + bounds[k + 3, 0])
                  + abs(b) * (bounds[k, 1] + bounds[k + 1, 1] + bounds[k + 2, 1] + bounds[k + 3, 1]))
    nt = G.shape[2]
    # (9 - r is the other column of the pair 4, 5; 13 - q of 6, 7)
    lr0, lr1, lr2, lr3 = G[k, r0], G[k + 1, r1], G[k + 2, r2], G[k + 3, r3]
    lt0, lt1, lt2, lt3 = G[k, q0], G[k + 1, q1], G[k + 2, q2], G[k + 3, q3]
    hr0, hr1, hr2, hr3 = G[k, 9 - r0], G[k + 1, 9 - r1], G[k + 2, 9 - r2], G[k + 3, 9 - r3]
    ht0, ht1, ht2, ht3 = G[k, 13 - q0], G[k + 1, 13 - q1], G[k + 2, 13 - q2], G[k + 3, 13 - q3]
    # one branch-free pass over the tiles (it vectorises): mf = 1 wholly full-film, mc = 1 wholly cavitated; the
    # full-film tiles' sums per table point j (columns as G's 0-3) and the cavitated tiles' weights
    flo = floor + tol
    fhi = floor - tol
    masks = np.empty(2 * nt)   # one allocation per call; views from offset 0 (see _clipped_nodes)
    mf = masks[:nt]
    mc = masks[nt:]
    g00, g01, g02, g03 = G[k, 0], G[k, 1], G[k, 2], G[k, 3]
    g10, g11, g12, g13 = G[k + 1, 0], G[k + 1, 1], G[k + 1, 2], G[k + 1, 3]
    g20, g21, g22, g23 = G[k + 2, 0], G[k + 2, 1], G[k + 2, 2], G[k + 2, 3]
    g30, g31, g32, g33 = G[k + 3, 0], G[k + 3, 1], G[k + 3, 2], G[k + 3, 3]
    TWc = TW[0]
    TWs = TW[1]
    s00 = s01 = s02 = s03 = s10 = s11 = s12 = s13 = 0.0
    s20 = s21 = s22 = s23 = s30 = s31 = s32 = s33 = 0.0
    cav_c = 0.0
    cav_s = 0.0
    for t in range(nt):
        lo = (a0 * lr0[t] + a1 * lr1[t] + a2 * lr2[t] + a3 * lr3[t]
              + b0 * lt0[t] + b1 * lt1[t] + b2 * lt2[t] + b3 * lt3[t])
        hi = (a0 * hr0[t] + a1 * hr1[t] + a2 * hr2[t] + a3 * hr3[t]
              + b0 * ht0[t] + b1 * ht1[t] + b2 * ht2[t] + b3 * ht3[t])
        f = 1.0 if lo > flo else 0.0
        v = 1.0 if hi < fhi else 0.0
        mf[t] = f
        mc[t] = v
        s00 += f * g00[t]
        s01 += f * g01[t]
        s02 += f * g02[t]
        s03 += f * g03[t]
        s10 += f * g10[t]
        s11 += f * g11[t]
        s12 += f * g12[t]
        s13 += f * g13[t]
        s20 += f * g20[t]
        s21 += f * g21[t]
        s22 += f * g22[t]
        s23 += f * g23[t]
        s30 += f * g30[t]
        s31 += f * g31[t]
        s32 += f * g32[t]
        s33 += f * g33[t]
        cav_c += v * TWc[t]
        cav_s += v * TWs[t]
    # the undecided tiles node by node
    acc = np.zeros(8)
    for t in range(nt):
        if mf[t] == 0.0 and mc[t] == 0.0:
            _clipped_nodes(NT, Wc, Ws, n, k, w0, w1, w2, w3, d0, d1, d2, d3, a, b, floor, toff[t], toff[t + 1],
                           acc)
    # the full-film tiles' sums interpolated (w) and differentiated (d) in u; G columns: 0 Wc P_r, 1 Ws P_r,
    # 2 Wc P_t, 3 Ws P_t
    sw0 = w0 * s00 + w1 * s10 + w2 * s20 + w3 * s30
    sw1 = w0 * s01 + w1 * s11 + w2 * s21 + w3 * s31
    sw2 = w0 * s02 + w1 * s12 + w2 * s22 + w3 * s32
    sw3 = w0 * s03 + w1 * s13 + w2 * s23 + w3 * s33
    sd0 = d0 * s00 + d1 * s10 + d2 * s20 + d3 * s30
    sd1 = d0 * s01 + d1 * s11 + d2 * s21 + d3 * s31
    sd2 = d0 * s02 + d1 * s12 + d2 * s22 + d3 * s32
    sd3 = d0 * s03 + d1 * s13 + d2 * s23 + d3 * s33
    fc = acc[0] + a * sw0 + b * sw2 + floor * cav_c
    fs = acc[1] + a * sw1 + b * sw3 + floor * cav_s
    du_deps = 1.0 / (1.0 - eps)
    return (-2.0 * fc, -2.0 * fs, -2.0 * (acc[2] + sw0), -2.0 * (acc[3] + sw2), -2.0 * (acc[4] + sw1),
            -2.0 * (acc[5] + sw3), -2.0 * (acc[6] + a * sd0 + b * sd2) * du_deps,
            -2.0 * (acc[7] + a * sd1 + b * sd3) * du_deps)


@kernel_jit(inline="always")
def _linear(ftab, eps, u0, du, n, a, b):
    """Like _clipped without cavitation, from the unit forces ftab (n_table, 4) =
    [F_r(v_r), F_t(v_r), F_r(v_t), F_t(v_t)] per unit mu v: the force is exactly linear in (a, b).

    Column j of ftab interpolated (f_j) and differentiated in eps (g_j), in scalars: no temporary arrays. Inlined
    into _aligned (its only caller) at numba's level: a separate compiled function would be optimised and
    machine-coded once more inside every caller."""
    u = -math.log1p(-eps)
    k, w0, w1, w2, w3, d0, d1, d2, d3 = _lagrange4(u, u0, du, n)
    f0 = w0 * ftab[k, 0] + w1 * ftab[k + 1, 0] + w2 * ftab[k + 2, 0] + w3 * ftab[k + 3, 0]
    f1 = w0 * ftab[k, 1] + w1 * ftab[k + 1, 1] + w2 * ftab[k + 2, 1] + w3 * ftab[k + 3, 1]
    f2 = w0 * ftab[k, 2] + w1 * ftab[k + 1, 2] + w2 * ftab[k + 2, 2] + w3 * ftab[k + 3, 2]
    f3 = w0 * ftab[k, 3] + w1 * ftab[k + 1, 3] + w2 * ftab[k + 2, 3] + w3 * ftab[k + 3, 3]
    r = 1.0 - eps
    g0 = (d0 * ftab[k, 0] + d1 * ftab[k + 1, 0] + d2 * ftab[k + 2, 0] + d3 * ftab[k + 3, 0]) / r
    g1 = (d0 * ftab[k, 1] + d1 * ftab[k + 1, 1] + d2 * ftab[k + 2, 1] + d3 * ftab[k + 3, 1]) / r
    g2 = (d0 * ftab[k, 2] + d1 * ftab[k + 1, 2] + d2 * ftab[k + 2, 2] + d3 * ftab[k + 3, 2]) / r
    g3 = (d0 * ftab[k, 3] + d1 * ftab[k + 1, 3] + d2 * ftab[k + 2, 3] + d3 * ftab[k + 3, 3]) / r
    return a * f0 + b * f2, a * f1 + b * f3, f0, f2, f1, f3, a * g0 + b * g2, a * g1 + b * g3


@kernel_jit
def _aligned(NT, G, TW, toff, ftab, bounds, Wc, Ws, eps, u0, du, n, a, b, floor, cavitation):
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
            return _clipped(NT, G, TW, toff, bounds, Wc, Ws, eps, u0, du, n, a, b, floor)
    return _linear(ftab, eps, u0, du, n, a, b)


@kernel_jit(inline="always")
def film_eval(NT, G, TW, toff, ftab, bounds, Wc, Ws, u0, du, n, eps_max, clearance, dx, dy, dvx, dvy, mu, floor,
              cavitation, out):
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
    r = _aligned(NT, G, TW, toff, ftab, bounds, Wc, Ws, ef, u0, du, n, a, b, floor, cavitation)
    Fr, Ft, Jra, Jrb, Jta, Jtb, dr, dt = r
    if saturated:
        dr = 0.0
        dt = 0.0
    gr = -Ft + Jra * b - Jrb * a
    gt = Fr + Jta * b - Jtb * a
    e_div = e
    if eps < EPS_NEAR_CENTRE:
        r0 = _aligned(NT, G, TW, toff, ftab, bounds, Wc, Ws, 0.0, u0, du, n, a, b, floor, cavitation)
        g0r = -r0[1] + r0[2] * b - r0[3] * a
        g0t = r0[0] + r0[4] * b - r0[5] * a
        if e == 0.0:
            r1 = _aligned(NT, G, TW, toff, ftab, bounds, Wc, Ws, EPS_DIFF, u0, du, n, a, b, floor, cavitation)
            gr = -r1[1] + r1[2] * b - r1[3] * a
            gt = r1[0] + r1[4] * b - r1[5] * a
            e_div = EPS_DIFF * clearance
        gr -= g0r
        gt -= g0t
    to_housing_axes(c, s, e_div, clearance, mu, Fr, Ft, Jra, Jrb, Jta, Jtb, dr, dt, gr, gt, out)


@kernel_jit
def fast_step(NT, G, TW, toff, ftab, bounds, Wc, Ws, prm, xj, vj, xh, vh, mu, out):
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
    film_eval(NT, G, TW, toff, ftab, bounds, Wc, Ws, u0, du, n, eps_max, clearance, dx, dy, dvx, dvy, mu, floor,
              cavitation, out)
    out[16] = -(out[0] * dvx + out[1] * dvy)
    return spring_and_wall(dx, dy, clearance, k_spring, k_wall, out)


#: fast_step's argument types as the damper calls it (tm_step, _compute): NT, G, TW, toff, ftab, bounds, Wc, Ws,
#: prm, xj, vj, xh, vh, mu, out. A helper process compiles it ahead on a fresh machine (component.prebuild,
#: master/compiled/ahead.py); tests/master/test_ahead.py checks that these are the types of the calls.
_A1, _A2, _A3 = types.float64[::1], types.float64[:, ::1], types.float64[:, :, ::1]
FAST_STEP_SIG = (_A1, _A3, _A2, types.int64[::1], _A2, _A2, _A1, _A1, _A1, _A1, _A1, _A1, _A1, types.float64, _A1)
# the damper's tm_step calls it by address (components/numba_internals.call_at): linked by name, tm_step's compilation
# optimised and machine-coded the whole film kernel a second time (~2 s of CPU on a fresh machine)
by_address(fast_step, FAST_STEP_SIG)


def fast_step_address() -> int:
    """The address of fast_step for the damper's kernel constants (compiled, or loaded from the disk cache, if not
    yet)."""
    return address_of(fast_step)


#: tile of the clipped-force sum (_clipped): TILE_Z axial x TILE_THETA circumferential nodes. A performance
#: choice only (the force is the same sum in another order). Measured on damper #0's recorded inputs over
#: 0.012-0.06 s at 2850 N (blade loss at 0.01 s), 128 x 64 mesh, CPU time per film evaluation: 8 x 4 6.2 us
#: (24 of 288 tiles undecided on average), 4 x 4 7.3, 8 x 8 7.0, 16 x 4 7.3, 4 x 8 8.9; the untiled pass 22 us
TILE_Z, TILE_THETA = 8, 4


def tile_order(n_theta: int, n_z: int, tile_z: int = TILE_Z, tile_theta: int = TILE_THETA):
    """(order, toff): the mesh nodes (node = j n_theta + i, reynolds_fe.Mesh) tile by tile, and the offsets of
    the tiles in that order (tile t is order[toff[t]:toff[t + 1]]). Tiles are tile_z x tile_theta rectangles
    of (axial j, circumferential i), smaller at the ends; within a tile, row by row."""
    order = []
    toff = [0]
    for j0 in range(0, n_z + 1, tile_z):
        for i0 in range(0, n_theta, tile_theta):
            for j in range(j0, min(j0 + tile_z, n_z + 1)):
                order.extend(j * n_theta + i for i in range(i0, min(i0 + tile_theta, n_theta)))
            toff.append(len(order))
    return np.array(order, dtype=np.int64), np.array(toff, dtype=np.int64)


def tile_layout(TR, TT, Wc, Ws, toff):
    """The fields and tile data of _clipped from P_r, P_t (n_table, n_nodes) with the nodes in tile order:

    * NT: the fields tile by tile, each tile one block [P_r at every table point, then P_t] (a tile's nodal sum
      reads one contiguous block);
    * G (n_table, 8, n_tiles): per table point and tile [sum Wc P_r, sum Ws P_r, sum Wc P_t, sum Ws P_t,
      min P_r, max P_r, min P_t, max P_t] (a row per quantity: the pass over the tiles vectorises);
    * TW (2, n_tiles): [sum Wc, sum Ws] per tile."""
    n = TR.shape[0]
    start = toff[:-1]
    NT = np.empty(2 * TR.size)
    for t in range(len(start)):
        i0, i1 = toff[t], toff[t + 1]
        blk = NT[2 * n * i0:2 * n * i1]
        blk[:n * (i1 - i0)] = TR[:, i0:i1].ravel()
        blk[n * (i1 - i0):] = TT[:, i0:i1].ravel()
    G = np.empty((n, 8, len(start)))
    G[:, 0] = np.add.reduceat(TR * Wc, start, axis=1)
    G[:, 1] = np.add.reduceat(TR * Ws, start, axis=1)
    G[:, 2] = np.add.reduceat(TT * Wc, start, axis=1)
    G[:, 3] = np.add.reduceat(TT * Ws, start, axis=1)
    G[:, 4] = np.minimum.reduceat(TR, start, axis=1)
    G[:, 5] = np.maximum.reduceat(TR, start, axis=1)
    G[:, 6] = np.minimum.reduceat(TT, start, axis=1)
    G[:, 7] = np.maximum.reduceat(TT, start, axis=1)
    TW = np.stack([np.add.reduceat(Wc, start), np.add.reduceat(Ws, start)])
    return NT, G, TW


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
        self.ftab = ftab
        self.bounds = np.stack([np.abs(TR).max(axis=1), np.abs(TT).max(axis=1)], axis=1)
        # the clipped force's layout (_clipped): nodes regrouped tile by tile, each tile's sums and bounds
        self.order, self.toff = tile_order(n_theta, n_z, TILE_Z, TILE_THETA)
        self.Wc = np.ascontiguousarray(self.mesh.Wc[self.order])
        self.Ws = np.ascontiguousarray(self.mesh.Ws[self.order])
        self.NT, self.G, self.TW = tile_layout(TR[:, self.order], TT[:, self.order], self.Wc, self.Ws, self.toff)

    def evaluate(self, dx, dy, dvx, dvy, mu, floor, cavitation, out):
        """F (2), K_film (4), C_film (4) of the film into out[0:10] (see film_eval)."""
        film_eval(self.NT, self.G, self.TW, self.toff, self.ftab, self.bounds, self.Wc, self.Ws, self.u0, self.du,
                  self.n, self.eps_max, self.clearance, dx, dy, dvx, dvy, mu, floor, cavitation, out)


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


#: the fast damper's kernel state: ``oil_lost`` (1 once its oil supply is lost: no film, the journal on the land),
#: ``reported`` and ``g``, the oil supply's condition (supply.py)
DamperState = namedtuple("DamperState", "oil_lost reported g")
#: the fast damper's kernel constants (components/kernels.py): the tables and parameters
#: of fast_step, its output buffer, a cache [T, mu(T)], the oil's viscosity constants (viscosity.py), the fit's
#: temperature range (components/oil_fit.py) and the address of fast_step (fast_step_address)
DamperParams = namedtuple("DamperParams", "NT G TW toff ftab bounds Wc Ws prm out cache walther_A walther_B rho300 "
                                          "drho T_min T_max fast_step_at")


@kernel_jit
def oil_viscosity(p, T):
    """SAE 30 dynamic viscosity at T (viscosity.sae30_viscosity), kept for the last T."""
    if T != p.cache[0]:
        nu_cst = 10.0 ** (10.0 ** (p.walther_A - p.walther_B * math.log10(T))) - 0.7
        p.cache[1] = nu_cst * 1e-6 * (p.rho300 + p.drho * (T - 300.0))
        p.cache[0] = T
    return p.cache[1]


@kernel_jit
def tm_step(s, p, u, y, t, h):
    """One evaluation at the step's inputs (components/kernels.py contract). Status 5: T_oil outside the
    viscosity fit; 10 + a wall.* code; EVENT: the oil supply lost on its condition at this step's end (supply.py)."""
    T = u.T_oil[0]
    if not (T > p.T_min and T <= p.T_max):   # the viscosity fit's range (components/oil_fit.py)
        return 5
    mu = oil_viscosity(p, T)
    out = p.out
    xj, vj, xh, vh = u.X_journal, u.V_journal, u.X_housing, u.V_housing
    # the oil supply lost on a condition (supply.py; prm: clearance (4), oil_loss_eccentricity (10))
    event = condition(s.oil_lost, s.reported, s.g, p.prm[10], p.prm[4], xj[0] - xh[0], xj[1] - xh[1])
    if s.oil_lost[0] != 0.0:
        # prm: [.., clearance (4), .., k_spring (7), k_wall (8), land_friction (9)]
        status = dry_land(xj[0] - xh[0], xj[1] - xh[1], vj[0] - vh[0], vj[1] - vh[1], p.prm[4], p.prm[7], p.prm[8],
                          p.prm[9], out)
    else:
        status = call_at(p.fast_step_at, fast_step, (p.NT, p.G, p.TW, p.toff, p.ftab, p.bounds, p.Wc, p.Ws, p.prm,
                                                     u.X_journal, u.V_journal, u.X_housing, u.V_housing, mu, out))
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
    return event
