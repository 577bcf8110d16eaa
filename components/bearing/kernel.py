"""The time-stepping kernel of the ball bearing (numba): balls, cage and outer race + journal over one
communication step, eqs. (1)-(9).

Per ball j at angle phi_j = phi_cage + 2 pi j / Z, in its r-z plane (eq. 1, u_r = x cos phi + y sin phi,
u_z = z, w_r = x_e cos phi + y_e sin phi):
    A = (l_oi cos a0 + u_r + eps_i - v_r,  l_oi sin a0 + u_z - v_z)        inner groove centre p - ball centre
    B = (l_oe cos a0 + v_r - w_r - eps_e,  l_oe sin a0 + v_z)              ball centre - outer groove centre q
    l = eps_b + |A|,  tan alpha = A_z / A_r  (eqs. 6, 7);  delta = l - l_o (eq. 8);
    Q = K delta^1.5 (1 + 1.5 alpha_d d(delta)/dt) for delta > 0, else 0; never tensile (eq. 9);
    m_b dv/dt = Q_i n_i - Q_e n_e + (F_c, 0)                                 (eq. 4);
    force on the inner race  -Q_i (cos alpha_i cos phi, cos alpha_i sin phi, sin alpha_i)   (eqs. 2, 3);
    force on the outer race  +Q_e cos alpha_e (cos phi, sin phi)                             (eq. 5);
    plus a light viscous ball damping c_b (ball velocity minus the mean of the two groove centres' velocities,
    reacted half by each race; not in the paper, see docs/explanation/paper-components.md).
Integration: symplectic (semi-implicit) Euler sub-steps for the balls; the journal (eq. 5) with the damper force
linearised about the start of the step, F0 + K (x - x0) + C (v - v0), taken implicitly in each sub-step.
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np
from numba import types

from ..numba_internals import by_address, call_at, kernel_jit
from .drag import palmgren_torque

# -- The kernel's vectors, each place named once. component.setup packs geo, drag and num by name (:func:`pack`);
# numba freezes these module-level integers as constants, so the names cost nothing at run time. They live in this
# file so that numba's cache, keyed by this file, is invalidated when they change.

#: geo: the geometry and contact constants (eqs. 1-10)
#: (z0: the inner race's axial offset that carries the preload, component.py; it follows the speed in spinning.py)
GEO = ("l_oi", "l_oe", "cos_a0", "sin_a0", "K_i", "K_e", "alpha_d", "F_c", "m_b", "m_journal", "omega_cage",
       "preload", "stress_inner", "stress_outer", "omega", "eps_limit", "ball_damping", "axial_direction", "z0")
(G_L_OI, G_L_OE, G_COS_A0, G_SIN_A0, G_K_I, G_K_E, G_ALPHA_D, G_F_C, G_M_B, G_M_JOURNAL, G_OMEGA_CAGE, G_PRELOAD,
 G_STRESS_INNER, G_STRESS_OUTER, G_OMEGA, G_EPS_LIMIT, G_BALL_DAMPING, G_AXIAL_DIRECTION, G_Z0) = range(len(GEO))
#: drag: Palmgren's drag torque (drag.py): oil viscosity (kept for the last T_oil), speed, pitch diameter,
#: coefficients and the static load rating
DRAG = ("nu", "omega", "d_m", "f0", "f1_z", "f1_y", "X0", "Y0", "C0")
D_NU, D_OMEGA, D_DM, D_F0, D_F1_Z, D_F1_Y, D_X0, D_Y0, D_C0 = range(len(DRAG))
#: num: sub-stepping (cfl, the least sub-steps, a fixed count or 0 for automatic) and where the inputs are (1:
#: at the end of the step, 0: at its start)
NUM = ("cfl", "min_substeps", "substeps", "inputs_at_end")
N_CFL, N_MIN_SUBSTEPS, N_SUBSTEPS, N_INPUTS_AT_END = range(len(NUM))
#: the contact pass's results (_forces): force on the inner race (3), on the outer race (2), the largest ball
#: loads on the inner and outer race, the radial and axial load, the largest contact stiffness
C_F_INNER, C_F_OUTER, C_Q_I, C_Q_E, C_F_R, C_F_A, C_K_MAX, C_SIZE = 0, 3, 5, 6, 7, 8, 9, 10
#: step's results: force on the inner race (3), ball loads [inner, outer] at the end (2) and largest over the
#: step (2), the mean drag torque, the sub-steps used
R_F_INNER, R_Q, R_Q_STEP, R_TORQUE, R_SUBSTEPS, R_SIZE = 0, 3, 5, 7, 8, 9
#: the component's output buffer (p.out): its output ports in order, the status flag and the sub-steps used
(O_F_ROTOR, O_X_JOURNAL, O_V_JOURNAL, O_Q_MAX, O_Q_MAX_STEP, O_SIGMA_MAX, O_SIGMA_MAX_STEP, O_P_DRAG, O_FLAG,
 O_SUBSTEPS, O_SIZE) = 0, 3, 5, 7, 9, 11, 13, 15, 16, 17, 18


def pack(fields: tuple[str, ...], **values: float) -> np.ndarray:
    """The vector of ``fields`` (GEO, DRAG or NUM) from its values by name; every field exactly once."""
    if set(values) != set(fields):
        raise ValueError(f"vector fields {sorted(set(fields) ^ set(values))} missing or unknown")
    return np.array([float(values[f]) for f in fields])


@kernel_jit
def _forces(Xx, Xy, Xz, Vx, Vy, Vz, xe, ye, vxe, vye, cphi, sphi, wc, balls, Z, c_b, s_b, l_oi, l_oe, ca0, sa0,
            Ki, Ke, ad, Fc, m_b, eps_i, eps_e, eps_b, cb, acc, out):
    """Contact forces of all balls at one instant. Writes ball accelerations into ``acc`` (2, Z) and into
    ``out`` (C_SIZE): the contact pass's results (C_* above)."""
    Fx = 0.0
    Fy = 0.0
    Fz = 0.0
    Gx = 0.0
    Gy = 0.0
    qi_max = 0.0
    qe_max = 0.0
    kmax = 0.0
    for j in range(Z):
        c = cphi * c_b[j] - sphi * s_b[j]
        s = sphi * c_b[j] + cphi * s_b[j]
        vr = balls[0, j]
        vz = balls[1, j]
        dvr = balls[2, j]
        dvz = balls[3, j]
        ur = Xx * c + Xy * s
        dur = Vx * c + Vy * s + wc * (-Xx * s + Xy * c)
        wr = xe * c + ye * s
        dwr = vxe * c + vye * s + wc * (-xe * s + ye * c)
        # inner contact
        Ar = l_oi * ca0 + ur + eps_i - vr
        Az = l_oi * sa0 + Xz - vz
        Li = math.sqrt(Ar * Ar + Az * Az)
        di = eps_b + Li - l_oi
        Qi = 0.0
        ki = 0.0
        if di > 0.0:
            ddi = ((dur - dvr) * Ar + (Vz - dvz) * Az) / Li
            sq = math.sqrt(di)
            Qi = Ki * di * sq * (1.0 + 1.5 * ad * ddi)
            if Qi < 0.0:
                Qi = 0.0
            ki = 1.5 * Ki * sq
        # outer contact
        Br = l_oe * ca0 + vr - wr - eps_e
        Bz = l_oe * sa0 + vz
        Le = math.sqrt(Br * Br + Bz * Bz)
        de = eps_b + Le - l_oe
        Qe = 0.0
        ke = 0.0
        if de > 0.0:
            dde = ((dvr - dwr) * Br + dvz * Bz) / Le
            sq = math.sqrt(de)
            Qe = Ke * de * sq * (1.0 + 1.5 * ad * dde)
            if Qe < 0.0:
                Qe = 0.0
            ke = 1.5 * Ke * sq
        ci = Ar / Li
        si = Az / Li
        ce = Br / Le
        se = Bz / Le
        # ball damping against the mean motion of the two races, reacted half by each race
        fbr = -cb * (dvr - 0.5 * (dur + dwr))
        fbz = -cb * (dvz - 0.5 * Vz)
        acc[0, j] = (Qi * ci - Qe * ce + Fc + fbr) / m_b
        acc[1, j] = (Qi * si - Qe * se + fbz) / m_b
        Fx -= (Qi * ci + 0.5 * fbr) * c
        Fy -= (Qi * ci + 0.5 * fbr) * s
        Fz -= Qi * si + 0.5 * fbz
        Gx += (Qe * ce - 0.5 * fbr) * c
        Gy += (Qe * ce - 0.5 * fbr) * s
        if Qi > qi_max:
            qi_max = Qi
        if Qe > qe_max:
            qe_max = Qe
        if ki + ke > kmax:
            kmax = ki + ke
    out[C_F_INNER] = Fx
    out[C_F_INNER + 1] = Fy
    out[C_F_INNER + 2] = Fz
    out[C_F_OUTER] = Gx
    out[C_F_OUTER + 1] = Gy
    out[C_Q_I] = qi_max
    out[C_Q_E] = qe_max
    out[C_F_R] = math.sqrt(Fx * Fx + Fy * Fy)
    out[C_F_A] = abs(Fz)
    out[C_K_MAX] = kmax


@kernel_jit
def _torque(Fr, Fa, d):
    """Palmgren's drag torque (drag.py) for the radial and axial loads, with the drag vector ``d`` (DRAG)."""
    return palmgren_torque(Fr, Fa, d[D_NU], d[D_OMEGA], d[D_DM], d[D_F0], d[D_F1_Z], d[D_F1_Y], d[D_X0], d[D_Y0],
                           d[D_C0])


@kernel_jit
def _bad(a, lim):
    for v in a:
        if not (abs(v) <= lim):
            return True
    return False


@kernel_jit
def step(h, Xa, Va, z0, eps, F0, Kj, Cj, balls, jour, phi, c_b, s_b, geo, drag, num, res):
    """Advance balls, cage angle and journal over h with the inner race on X(tau) = Xa + Va tau (+ z0 axially).

    geo, drag, num: the vectors GEO, DRAG, NUM (above). balls (4, Z) [v_r, v_z, dv_r/dt, dv_z/dt] and jour (4)
    [x, y, vx, vy] are updated in place; phi (1) too. res (R_SIZE) <- step's results (R_* above)."""
    Z = balls.shape[1]
    l_oi, l_oe, ca0, sa0 = geo[G_L_OI], geo[G_L_OE], geo[G_COS_A0], geo[G_SIN_A0]
    Ki, Ke, ad, Fc, m_b = geo[G_K_I], geo[G_K_E], geo[G_ALPHA_D], geo[G_F_C], geo[G_M_B]
    m_j, wc, cb = geo[G_M_JOURNAL], geo[G_OMEGA_CAGE], geo[G_BALL_DAMPING]
    eps_i = eps[0]
    eps_e = eps[1]
    eps_b = eps[2]
    acc = np.empty((2, Z))
    out = np.empty(C_SIZE)
    x0 = jour[0]
    y0 = jour[1]
    vx0 = jour[2]
    vy0 = jour[3]
    _forces(Xa[0], Xa[1], Xa[2] + z0, Va[0], Va[1], Va[2], jour[0], jour[1], jour[2], jour[3],
            math.cos(phi[0]), math.sin(phi[0]), wc, balls, Z, c_b, s_b, l_oi, l_oe, ca0, sa0, Ki, Ke, ad, Fc, m_b,
            eps_i, eps_e, eps_b, cb, acc, out)
    if h <= 0.0:
        # outputs of the present state only (set-up)
        M = _torque(out[C_F_R], out[C_F_A], drag)
        for k in range(3):
            res[R_F_INNER + k] = out[C_F_INNER + k]
        res[R_Q] = out[C_Q_I]
        res[R_Q + 1] = out[C_Q_E]
        res[R_Q_STEP] = out[C_Q_I]
        res[R_Q_STEP + 1] = out[C_Q_E]
        res[R_TORQUE] = M
        res[R_SUBSTEPS] = 0
        return
    n = int(num[N_SUBSTEPS])
    if n <= 0:
        w = math.sqrt(out[C_K_MAX] / m_b)
        n = int(math.ceil(h * w / num[N_CFL]))
        if n < int(num[N_MIN_SUBSTEPS]):
            n = int(num[N_MIN_SUBSTEPS])
    dt = h / n
    # journal: (m/dt - dt K - C) v+ = m/dt v + F_contact + F0 + K (x - x0) - C v0, x+ = x + dt v+
    a11 = m_j / dt - dt * Kj[0] - Cj[0]
    a12 = -dt * Kj[1] - Cj[1]
    a21 = -dt * Kj[2] - Cj[2]
    a22 = m_j / dt - dt * Kj[3] - Cj[3]
    det = a11 * a22 - a12 * a21
    qi_step = out[C_Q_I]
    qe_step = out[C_Q_E]
    drag_sum = 0.0
    cdt = math.cos(wc * dt)
    sdt = math.sin(wc * dt)
    cphi = math.cos(phi[0])
    sphi = math.sin(phi[0])
    for k in range(n):
        if k > 0:
            tau = k * dt
            _forces(Xa[0] + Va[0] * tau, Xa[1] + Va[1] * tau, Xa[2] + z0 + Va[2] * tau, Va[0], Va[1], Va[2],
                    jour[0], jour[1], jour[2], jour[3], cphi, sphi, wc, balls, Z, c_b, s_b, l_oi, l_oe, ca0, sa0,
                    Ki, Ke, ad, Fc, m_b, eps_i, eps_e, eps_b, cb, acc, out)
            if out[C_Q_I] > qi_step:
                qi_step = out[C_Q_I]
            if out[C_Q_E] > qe_step:
                qe_step = out[C_Q_E]
        M = _torque(out[C_F_R], out[C_F_A], drag)
        drag_sum += M if k > 0 else 0.5 * M
        for j in range(Z):
            balls[2, j] += dt * acc[0, j]
            balls[3, j] += dt * acc[1, j]
            balls[0, j] += dt * balls[2, j]
            balls[1, j] += dt * balls[3, j]
        dx = jour[0] - x0
        dy = jour[1] - y0
        r1 = m_j / dt * jour[2] + out[C_F_OUTER] + F0[0] + Kj[0] * dx + Kj[1] * dy - Cj[0] * vx0 - Cj[1] * vy0
        r2 = m_j / dt * jour[3] + out[C_F_OUTER + 1] + F0[1] + Kj[2] * dx + Kj[3] * dy - Cj[2] * vx0 - Cj[3] * vy0
        vxn = (a22 * r1 - a12 * r2) / det
        vyn = (a11 * r2 - a21 * r1) / det
        jour[2] = vxn
        jour[3] = vyn
        jour[0] += dt * vxn
        jour[1] += dt * vyn
        c = cphi * cdt - sphi * sdt
        sphi = sphi * cdt + cphi * sdt
        cphi = c
    phi[0] = (phi[0] + wc * h) % (2.0 * math.pi)
    cphi = math.cos(phi[0])
    sphi = math.sin(phi[0])
    _forces(Xa[0] + Va[0] * h, Xa[1] + Va[1] * h, Xa[2] + z0 + Va[2] * h, Va[0], Va[1], Va[2], jour[0], jour[1],
            jour[2], jour[3], cphi, sphi, wc, balls, Z, c_b, s_b, l_oi, l_oe, ca0, sa0, Ki, Ke, ad, Fc, m_b,
            eps_i, eps_e, eps_b, cb, acc, out)
    if out[C_Q_I] > qi_step:
        qi_step = out[C_Q_I]
    if out[C_Q_E] > qe_step:
        qe_step = out[C_Q_E]
    M = _torque(out[C_F_R], out[C_F_A], drag)
    drag_sum += 0.5 * M
    for k in range(3):
        res[R_F_INNER + k] = out[C_F_INNER + k]
    res[R_Q] = out[C_Q_I]
    res[R_Q + 1] = out[C_Q_E]
    res[R_Q_STEP] = qi_step
    res[R_Q_STEP + 1] = qe_step
    res[R_TORQUE] = drag_sum / n
    res[R_SUBSTEPS] = n


#: step's argument types: called by address from tm_step (components/numba_internals.call_at), so that tm_step's compilation
#: does not optimise and machine-code the whole step once more (~2-3 s of CPU on a fresh machine)
_F1, _F2 = types.float64[::1], types.float64[:, ::1]
STEP_SIG = (types.float64, _F1, _F1, types.float64, _F1, _F1, _F1, _F1, _F2, _F1, _F1, _F1, _F1, _F1, _F1, _F1, _F1)
by_address(step, STEP_SIG)


#: the bearing's kernel containers (components/kernels.py). State: the balls (4, Z), the journal (4), the cage
#: angle (1), the growths the balls were last seated for (3).
#: Constants: the balls' angle cosines/sines, the geometry (the inner race's axial offset z0 with it), drag and numerics
#: vectors of tm_step, a cache [T of nu, T of P_v, P_v], the step's output buffer, the growth jump that
#: re-seats the balls, the Walther constants of the oil viscosity, the address of step (numba_internals.address_of).
BearingState = namedtuple("BearingState", "balls journal phi eps_seated")
BearingParams = namedtuple("BearingParams",
                           "c_b s_b geo drag num cache out eps_jump walther_A walther_B T_min T_max step_at")


@kernel_jit
def kinematic_viscosity(A, B, T):
    """SAE 30 kinematic viscosity (m^2/s) at T kelvin, Walther / ASTM D341 (oil.py)."""
    return (10.0 ** (10.0 ** (A - B * math.log10(T))) - 0.7) * 1e-6


@kernel_jit
def oil_viscosity(p, T):
    """nu at T into drag[D_NU], kept for the last T (it changes only at the thermal network's step)."""
    if T != p.cache[0]:
        p.drag[D_NU] = kinematic_viscosity(p.walther_A, p.walther_B, T)
        p.cache[0] = T
    return p.drag[D_NU]


@kernel_jit
def viscous_power(p, T):
    """omega M_v, the load-independent part of the Palmgren drag power at T, kept for the last T."""
    if T != p.cache[1]:
        d = p.drag
        nu = oil_viscosity(p, T)
        p.cache[2] = d[D_OMEGA] * palmgren_torque(0.0, 0.0, nu, d[D_OMEGA], d[D_DM], d[D_F0], d[D_F1_Z],
                                                   d[D_F1_Y], d[D_X0], d[D_Y0], d[D_C0])
        p.cache[1] = T
    return p.cache[2]


@kernel_jit
def tm_step(s, p, u, y, t, h):
    """One thermo-mechanical step (component.BallBearing; components/kernels.py contract): :func:`step` plus the
    component's outputs. h = 0 gives the outputs of the present state (set-up: component._advance).

    Status PYTHON (1): the growths jumped (a thermal-only interval ended): the balls are re-seated in Python first;
    5: T_oil outside the viscosity fit; 10 + a flag: 1 non-finite input, 2 eps beyond +-eps_limit (5 % of the ball
    diameter), 3 non-finite state.

    The inner race path is X - V lag + V tau with lag = h if inputs_at_end else 0. axial_direction is +1, or -1
    for a bearing mounted the other way round (z is mirrored). p.out (O_SIZE) <- the output ports, the flag and
    the number of sub-steps (O_* above).

    One compiled function with what was step_outputs (a second entry point compiled the whole step, three
    contact passes and the drag, once more inside itself: ~1 s of CPU on a fresh machine); step is
    called by address (STEP_SIG)."""
    T = u.T_oil[0]
    if not (T > p.T_min and T <= p.T_max):   # the viscosity fit's range (components/oil_fit.py)
        return 5
    oil_viscosity(p, T)
    eps = u.eps
    finite = True
    jump = 0.0
    for k in range(3):
        if not math.isfinite(eps[k]):
            finite = False
        d = abs(eps[k] - s.eps_seated[k])
        if d > jump:
            jump = d
    if finite and jump > p.eps_jump:
        return 1
    for k in range(3):
        s.eps_seated[k] = eps[k]
    X, V, F0, Kj, Cj = u.X_inner, u.V_inner, u.F_journal, u.K_journal, u.C_journal
    geo, num, out = p.geo, p.num, p.out
    if (_bad(X, 1e300) or _bad(V, 1e300) or _bad(F0, 1e300) or _bad(Kj, 1e300) or _bad(Cj, 1e300)
            or _bad(eps, 1e300)):
        out[O_FLAG] = 1.0
        return 11
    if _bad(eps, geo[G_EPS_LIMIT]):
        out[O_FLAG] = 2.0
        return 12
    lag = h if num[N_INPUTS_AT_END] > 0.0 else 0.0
    ax = geo[G_AXIAL_DIRECTION]
    Vb = np.empty(3)
    Xa = np.empty(3)
    for k in range(3):
        Vb[k] = V[k]
    Vb[2] = ax * V[2]
    for k in range(3):
        Xa[k] = X[k] - V[k] * lag
    Xa[2] *= ax
    res = np.empty(R_SIZE)
    balls = s.balls
    call_at(p.step_at, step, (h, Xa, Vb, geo[G_Z0], eps, F0, Kj, Cj, balls, s.journal, s.phi, p.c_b, p.s_b, geo, p.drag,
                              num, res))
    jour = s.journal
    out[O_F_ROTOR] = res[R_F_INNER]
    out[O_F_ROTOR + 1] = res[R_F_INNER + 1]
    out[O_F_ROTOR + 2] = ax * (res[R_F_INNER + 2] + geo[G_PRELOAD])
    for k in range(2):
        out[O_X_JOURNAL + k] = jour[k]
        out[O_V_JOURNAL + k] = jour[2 + k]
        out[O_Q_MAX + k] = res[R_Q + k]
        out[O_Q_MAX_STEP + k] = res[R_Q_STEP + k]
    # eq. (10): sigma = (stress coefficient) Q^(1/3), inner and outer race
    out[O_SIGMA_MAX] = geo[G_STRESS_INNER] * res[R_Q] ** (1.0 / 3.0)
    out[O_SIGMA_MAX + 1] = geo[G_STRESS_OUTER] * res[R_Q + 1] ** (1.0 / 3.0)
    out[O_SIGMA_MAX_STEP] = geo[G_STRESS_INNER] * res[R_Q_STEP] ** (1.0 / 3.0)
    out[O_SIGMA_MAX_STEP + 1] = geo[G_STRESS_OUTER] * res[R_Q_STEP + 1] ** (1.0 / 3.0)
    out[O_P_DRAG] = res[R_TORQUE] * geo[G_OMEGA]
    ok = True
    for k in range(O_FLAG):
        if not (abs(out[k]) < 1e300):
            ok = False
    for v in balls.ravel():
        if not (abs(v) < 1e300):
            ok = False
    out[O_SUBSTEPS] = res[R_SUBSTEPS]
    if not ok:
        out[O_FLAG] = 3.0
        return 13
    out[O_FLAG] = 0.0
    for k in range(3):
        y.F_rotor[k] = out[O_F_ROTOR + k]
    for k in range(2):
        y.X_journal[k] = out[O_X_JOURNAL + k]
        y.V_journal[k] = out[O_V_JOURNAL + k]
        y.Q_max[k] = out[O_Q_MAX + k]
        y.Q_max_step[k] = out[O_Q_MAX_STEP + k]
        y.sigma_max[k] = out[O_SIGMA_MAX + k]
        y.sigma_max_step[k] = out[O_SIGMA_MAX_STEP + k]
    y.P_drag[0] = out[O_P_DRAG]
    return 0
