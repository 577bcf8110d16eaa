"""Rotor/rub-ring contact force and the friction power of the paper's eq. (11).

The rotor node at the ring is at d = X_rotor - X_housing (m) relative to the ring's centre, moving at
w = V_rotor - V_housing (m/s); the ring has radial clearance c.

* inside the clearance (|d| <= c): no force, no power;
* in contact: with n = d/|d| (outward normal) and t = (-n_y, n_x) (counter-clockwise tangent), the penetration
  delta = |d| - c and its rate delta' = w . n give the normal force F_n = max(0, k delta + c_d delta') (a pure
  push: clipped at zero so the damping never pulls the rotor back into the ring);
* the rotor's surface slides over the ring at v_s = omega R + w . t along t (the spin's surface speed at the
  contact point plus the whirl's tangential velocity; omega > 0 is counter-clockwise spin about z);
* Coulomb friction opposes the slip: F_f = -mu F_n s(v_s) t, with s(v) = v / max(|v|, v_reg) (the sign, made
  continuous below the regularisation speed v_reg);
* force on the rotor F = -F_n n + F_f; the friction power is H_s = mu F_n |v_s| s(|v_s|) = -F_f . (v_s t) >= 0,
  eq. (11) H_s = F_f R_r omega_r with the whirl's share of the sliding speed included (v_s = omega R when the
  rotor does not whirl).
"""
from __future__ import annotations

import math
from collections import namedtuple

from ..numba_internals import kernel_jit


@kernel_jit(inline="always")
def rub_force(dx, dy, wx, wy, clearance, stiffness, damping, friction, radius, omega, v_reg):
    """(Fx, Fy, P_rub, F_normal) on the rotor; arguments as in the module docstring (SI)."""
    r = math.hypot(dx, dy)
    if r <= clearance:
        return 0.0, 0.0, 0.0, 0.0
    nx, ny = dx / r, dy / r
    fn = stiffness * (r - clearance) + damping * (wx * nx + wy * ny)
    if fn <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    tx, ty = -ny, nx
    vs = omega * radius + wx * tx + wy * ty
    a = abs(vs)
    sgn = vs / (a if a > v_reg else v_reg)
    ff = friction * fn * sgn
    return -fn * nx - ff * tx, -fn * ny - ff * ty, ff * vs, fn


#: the rub ring's kernel constants (components/kernels.py; the ring has no state): the contact law's parameters
RubParams = namedtuple("RubParams", "clearance stiffness damping friction radius omega v_reg")


@kernel_jit
def tm_step(s, p, u, y, t, h):
    """One evaluation at the step's inputs (components/kernels.py contract); status 2: non-finite motion."""
    dx = u.X_rotor[0] - u.X_housing[0]
    dy = u.X_rotor[1] - u.X_housing[1]
    wx = u.V_rotor[0] - u.V_housing[0]
    wy = u.V_rotor[1] - u.V_housing[1]
    if not math.isfinite(dx + dy + wx + wy):
        return 2
    fx, fy, power, fn = rub_force(dx, dy, wx, wy, p.clearance, p.stiffness, p.damping, p.friction, p.radius,
                                  p.omega, p.v_reg)
    y.F_rotor[0] = fx
    y.F_rotor[1] = fy
    y.F_housing[0] = -fx
    y.F_housing[1] = -fy
    y.P_rub[0] = power
    y.F_normal[0] = fn
    return 0
