"""The thermal network's compiled step (components/kernels.py contract): eq. (12) over one step with the powers
held, T1 = Phi T0 + Gamma_b + Gamma_S u (network.py, step matrices formed in Python per step size), and the growths
of eqs. (13)-(15) (growth.py)."""
from __future__ import annotations

import math
from collections import namedtuple


from ..numba_internals import kernel_jit
from .geometry import BALL, IR, JOURNAL, LE, LI, OR, SFD, SHAFT
from .growth import growths as _growths

growths = kernel_jit(inline="always")(_growths)

#: state: the nine node temperatures; constants: the step matrices of the step size in use, a scratch vector,
#: the arguments of growths() after the temperatures
ThermalState = namedtuple("ThermalState", "T")
ThermalParams = namedtuple("ThermalParams", "Phi gb GS T_new T_ref xi nu r_i r_e r_j r_b")


@kernel_jit(inline="always")
def publish(p, T, y):
    """The outputs of node temperatures T."""
    ei, ee, eb = growths(T[SHAFT], T[LI], T[BALL], T[LE], T[JOURNAL], p.T_ref, p.xi, p.nu, p.r_i, p.r_e, p.r_j,
                         p.r_b)
    for k in range(9):
        y.T_nodes[k] = T[k]
    y.eps[0] = ei
    y.eps[1] = ee
    y.eps[2] = eb
    y.T_oil[0] = 0.5 * (T[LI] + T[LE])
    y.T_sfd_oil[0] = T[SFD]
    y.T_inner_race[0] = T[IR]
    y.T_ball[0] = T[BALL]
    y.T_outer_race[0] = T[OR]


@kernel_jit
def tm_step(s, p, u, y, t, h):
    """One step with the powers held; status 2: a non-finite power, 3: a negative one."""
    q0 = u.P_drag[0]
    q1 = u.P_sfd[0]
    q2 = u.P_rub[0]
    if not math.isfinite(q0 + q1 + q2):
        return 2
    if min(q0, q1, q2) < -1e-6:
        return 3
    T = s.T
    Tn = p.T_new
    n = T.shape[0]
    for i in range(n):
        a = 0.0
        for j in range(n):
            a += p.Phi[i, j] * T[j]
        Tn[i] = (a + p.gb[i]) + (p.GS[i, 0] * q0 + p.GS[i, 1] * q1 + p.GS[i, 2] * q2)
    for i in range(n):
        T[i] = Tn[i]
    publish(p, T, y)
    return 0
