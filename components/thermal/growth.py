"""Thermal growths of the bearing parts, the paper's eqs. (13)-(15).

Sign convention (as the bearing uses them in eqs. (6)-(8)): each eps is the radial displacement of a part's
contact surface caused by heating, positive = expansion (outwards for the races, a larger ball radius), in m:

* eps_i, eq. (14): eps_i = xi_i/3 (dT_s + dT_Li) (1 + nu_i) r_i  -- the inner raceway moves outwards (at r_i);
* eps_e, eq. (13): eps_e = xi_e (1 + nu_e) r_e / (3 r_e + r_j) [dT_Le (2 r_e + r_j) + dT_j (2 r_j + r_e)]
  -- the outer raceway (with the damper journal fitted on it) moves outwards (at r_e);
* eps_b, eq. (15): eps_b = xi_b r_b dT_b -- the ball radius grows.

The temperature rises dT are from the initial (zero-growth, assembly) temperature. As eqs. (13)-(14) are printed,
the raceway surfaces take the temperature of the lubricant at them (T_Li, T_Le); eq. (14) uses the shaft and
inner lubricant, eq. (13) the outer lubricant and the journal.
"""
from __future__ import annotations


def growths(T_shaft, T_lub_inner, T_ball, T_lub_outer, T_journal, T_ref, xi, nu, r_i, r_e, r_j, r_b):
    """(eps_i, eps_e, eps_b) in m; xi expansion coefficient (1/K), nu Poisson's ratio, radii in m."""
    dTs, dTLi, dTb = T_shaft - T_ref, T_lub_inner - T_ref, T_ball - T_ref
    dTLe, dTj = T_lub_outer - T_ref, T_journal - T_ref
    eps_i = xi / 3.0 * (dTs + dTLi) * (1.0 + nu) * r_i
    eps_e = xi * (1.0 + nu) * r_e / (3.0 * r_e + r_j) * (dTLe * (2.0 * r_e + r_j) + dTj * (2.0 * r_j + r_e))
    eps_b = xi * r_b * dTb
    return eps_i, eps_e, eps_b
