"""The spool's step (components/kernels.py contract): its speed, angle and the work of each torque.

State ``x`` = [Omega, theta, dOmega, W_drive, W_drag, W_rub, W_aero] (rad/s, rad, rad/s^2, J). Over a step from
Omega0 to Omega1 each torque T does the work T (Omega0 + Omega1) / 2 h, and the kinetic energy changes by
J (Omega1 - Omega0) (Omega0 + Omega1) / 2: with the torques of the step (the drive torque of a prescribed profile
being the one it implies) the balance ``dE_kin = W_drive - W_drag - W_rub - W_aero`` holds to round-off, step by
step, whatever the step size.

Torque-driven (mode 2): governed at the start speed until ``t_cut`` (the drive torque balances the others), then
``J dOmega/dt = -T_drag - T_rub - T_aero(Omega)`` with the aerodynamic torque and the spool's own viscous drag
linearised about Omega0 (linearly implicit Euler: stable at a thermal-only interval's 0.1 s step), the drag and
rub torques those its inputs report. A spool that would turn backwards stops (Omega = 0): what the ring's and
bearings' friction would do; on that step the torques act for the fraction ``J Omega0 / (h sum T)`` of it, and
their work is booked so. The run's energy balance is not this bookkeeping (an identity of the step) but the
rundown case's (cases/rundown/energy.py), from the torques the components report.
"""
from __future__ import annotations

import math
from collections import namedtuple

from ..numba_internals import kernel_jit

SpoolState = namedtuple("SpoolState", "x")
#: ``n_drag``: how many of the inputs, the first ones, are drag torques (the rest are rub torques: ports.py)
#: ``wm_t``, ``wm_w``, ``wm_c``: the windmilling law's table of times, windmill speeds and coefficients c (one point:
#: constant; a flight profile: one per row, linear in between, held outside)
SpoolParams = namedtuple("SpoolParams", "mode tab_t tab_w tab_th theta0 J t_cut wm_t wm_w wm_c c_visc n_drag")
#: modes
CONSTANT, TABLE, TORQUE = 0, 1, 2
X_OMEGA, X_THETA, X_DOMEGA, X_W_DRIVE, X_W_DRAG, X_W_RUB, X_W_AERO = range(7)


@kernel_jit
def profile_at(tt, tw, th, t):
    """(Omega, theta, dOmega/dt) of the piecewise-linear table at t (held before the first, after the last)."""
    n = tt.shape[0]
    if t <= tt[0]:
        return tw[0], th[0] + tw[0] * (t - tt[0]), 0.0
    if t >= tt[n - 1]:
        return tw[n - 1], th[n - 1] + tw[n - 1] * (t - tt[n - 1]), 0.0
    k = 0
    while tt[k + 1] <= t:
        k += 1
    s = (tw[k + 1] - tw[k]) / (tt[k + 1] - tt[k])
    w = tw[k] + s * (t - tt[k])
    return w, th[k] + 0.5 * (tw[k] + w) * (t - tt[k]), s


@kernel_jit(inline="always")
def held_linear(tt, v, t):
    """The table (tt, v) at t: linear in between, held before the first point and after the last (exactly)."""
    n = tt.shape[0]
    if t <= tt[0]:
        return v[0]
    if t >= tt[n - 1]:
        return v[n - 1]
    k = 0
    while tt[k + 1] <= t:
        k += 1
    return v[k] + (v[k + 1] - v[k]) * (t - tt[k]) / (tt[k + 1] - tt[k])


@kernel_jit(inline="always")
def aero_torque(p, w, t):
    """T_aero(Omega) = c (Omega - Omega_wm) |Omega - Omega_wm| at time t and its derivative in Omega."""
    c = held_linear(p.wm_t, p.wm_c, t)
    d = w - held_linear(p.wm_t, p.wm_w, t)
    return c * d * abs(d), 2.0 * c * abs(d)


@kernel_jit
def tm_step(s, p, u, y, t, h):
    """One step from t to t + h; status 2: a non-finite input torque."""
    x = s.x
    # u: a homogeneous tuple of the torque inputs, the n_drag drag torques first (component.Spool.kernel_io)
    t_drag = u[0][0]
    for j in range(1, p.n_drag):
        t_drag += u[j][0]
    t_rub = u[p.n_drag][0]
    for j in range(p.n_drag + 1, len(u)):
        t_rub += u[j][0]
    if not math.isfinite(t_drag + t_rub):
        return 2
    w0 = x[X_OMEGA]
    if p.mode == TORQUE:
        ta, dta = aero_torque(p, w0, t)
        if t + h <= p.t_cut or h == 0.0:
            w1 = w0
            t_drag += p.c_visc * w0
            t_drive = t_drag + t_rub + ta
        else:
            t_drive = 0.0
            w1 = w0 - h * (t_drag + p.c_visc * w0 + t_rub + ta) / (p.J + h * (dta + p.c_visc))
            stop = w1 < 0.0
            if stop:
                w1 = 0.0
            # the aerodynamic torque and the viscous drag at the step's end (linearly implicit)
            ta += dta * (w1 - w0)
            t_drag += p.c_visc * w1
            if stop:
                # friction stops the spool within the step: the torques act for that fraction of it
                total = t_drag + t_rub + ta
                f = p.J * w0 / (h * total) if total > 0.0 else 0.0
                t_drag *= f
                t_rub *= f
                ta *= f
        x[X_THETA] += 0.5 * (w0 + w1) * h
        x[X_DOMEGA] = (w1 - w0) / h if h > 0.0 else 0.0
    else:
        w1, th, dw = profile_at(p.tab_t, p.tab_w, p.tab_th, t + h)
        x[X_THETA] = th - p.theta0
        x[X_DOMEGA] = dw
        ta = aero_torque(p, w1, t + h)[0]
        t_drag += p.c_visc * w1
        t_drive = (p.J * (w1 - w0) / h if h > 0.0 else 0.0) + t_drag + t_rub + ta
    x[X_OMEGA] = w1
    wm = 0.5 * (w0 + w1) * h
    x[X_W_DRIVE] += t_drive * wm
    x[X_W_DRAG] += t_drag * wm
    x[X_W_RUB] += t_rub * wm
    x[X_W_AERO] += ta * wm
    y.Omega[0] = w1
    y.theta[0] = x[X_THETA]
    y.dOmega[0] = x[X_DOMEGA]
    y.T_drive[0] = t_drive
    y.T_aero[0] = ta
    e = y.energy
    e[0] = 0.5 * p.J * w1 * w1
    e[1] = x[X_W_DRIVE]
    e[2] = x[X_W_DRAG]
    e[3] = x[X_W_RUB]
    e[4] = x[X_W_AERO]
    return 0
