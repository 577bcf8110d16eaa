"""Bearing drag (friction) torque after Palmgren, as given by Harris & Kotzalas (Rolling Bearing Analysis,
"Friction in rolling bearings") and the bearing makers' catalogues; the paper's Ref. [13] (section 2.3).

In Palmgren's units (M in N mm, nu in cSt, n in rev/min, d_m in mm):
    M = M_l + M_v,
    M_v = 1e-7 f0 (nu n)^(2/3) d_m^3   if nu n >= 2000,   else 160e-7 f0 d_m^3     (viscous, lubricant),
    M_l = f1 P1 d_m,   f1 = z (P0 / C0)^y,   P1 = max(Fa - 0.1 Fr, Fr)             (load, single-row ACBB),
    P0 = max(X0 Fr + Y0 Fa, Fr)                                                     (ISO 76 static equivalent load).
The functions take and return SI (N, m^2/s, rad/s, m, N m); the conversion to Palmgren's units is inside.
"""
from __future__ import annotations

import math

from ..numba_internals import kernel_jit

RPM_PER_RAD_S = 30.0 / math.pi


@kernel_jit
def palmgren_torque(Fr, Fa, nu, omega, d_m, f0, z, y, X0, Y0, C0):
    """Drag torque (N m) for radial load Fr and axial load Fa (N), kinematic viscosity nu (m^2/s), speed of the
    inner race relative to the outer race omega (rad/s), pitch diameter d_m (m), static load rating C0 (N)."""
    n = abs(omega) * 30.0 / math.pi
    nu_cst = nu * 1e6
    dm_mm = d_m * 1e3
    nun = nu_cst * n
    if nun >= 2000.0:
        Mv = 1e-7 * f0 * nun ** (2.0 / 3.0) * dm_mm ** 3
    else:
        Mv = 160e-7 * f0 * dm_mm ** 3
    P0 = max(X0 * Fr + Y0 * Fa, Fr)
    P1 = max(Fa - 0.1 * Fr, Fr)
    Ml = 0.0
    if P0 > 0.0:
        Ml = z * (P0 / C0) ** y * P1 * dm_mm
    return 1e-3 * (Mv + Ml)


def static_load_rating(Z: int, alpha0: float, stress_coeff: float, stress_limit: float, stribeck: float) -> float:
    """C0 from its ISO 76 definition: the radial load whose most heavily loaded ball (Q_max = stribeck Fr /
    (Z cos alpha0)) reaches ``stress_limit`` (Pa) at the more highly stressed contact (coefficient of eq. 10)."""
    Q = (stress_limit / stress_coeff) ** 3
    return Z * math.cos(alpha0) * Q / stribeck
