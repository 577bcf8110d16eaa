"""The rub ring at a varying speed (``rubring.contact_spinning``): the rotor's spin speed is an input.

The same contact as component.RubRing (contact.py) with ``Omega`` [rad/s] (the spool's speed, components/spool)
as an input instead of the constant ``omega``: the sliding speed ``Omega R + w . t``, the friction force and the
rub power ``F_f R Omega`` follow the speed. It also outputs the friction torque on the spool
``T_rub = R mu F_n s(v_s)`` [N m] (eq. (11)'s force times the radius; positive opposing the spin). At Omega =
omega every force and power is the constant-speed ring's, bit for bit.
"""
from __future__ import annotations

import math

import numpy as np

from ..contract import ContractError, Variable
from ..numba_internals import kernel_jit
from .component import RubRing
from .contact import rub_force


@kernel_jit
def spinning_step(s, p, u, y, t, h):
    """One evaluation at the step's inputs and speed; status 2: non-finite motion or speed."""
    dx = u.X_rotor[0] - u.X_housing[0]
    dy = u.X_rotor[1] - u.X_housing[1]
    wx = u.V_rotor[0] - u.V_housing[0]
    wy = u.V_rotor[1] - u.V_housing[1]
    w = u.Omega[0]
    if not math.isfinite(dx + dy + wx + wy + w):
        return 2
    fx, fy, power, fn = rub_force(dx, dy, wx, wy, p.clearance, p.stiffness, p.damping, p.friction, p.radius,
                                  w, p.v_reg)
    torque = 0.0
    if fn > 0.0:
        r = math.hypot(dx, dy)
        vs = w * p.radius + (wx * (-dy) + wy * dx) / r
        a = abs(vs)
        torque = p.radius * p.friction * fn * vs / (a if a > p.v_reg else p.v_reg)
    y.F_rotor[0] = fx
    y.F_rotor[1] = fy
    y.F_housing[0] = -fx
    y.F_housing[1] = -fy
    y.P_rub[0] = power
    y.F_normal[0] = fn
    y.T_rub[0] = torque
    return 0


class SpinningRubRing(RubRing):
    """The rub ring with the spool speed as an input (module docstring)."""

    description = RubRing.description + " (spin speed as an input)"
    #: the speed is the Omega input; omega is only the reference of the speed terms' tables, free to differ
    fixed_speed = None
    variables = RubRing.variables + (
        Variable("Omega", "input", 1, "rad/s", "rotor spin speed (counter-clockwise +)"),
        Variable("T_rub", "output", 1, "N.m", "friction torque on the spool (opposing the spin)"),
    )

    def setup(self, t0=0.0):
        # the set-up evaluation at the reference speed (the input is not yet known)
        self.u["Omega"] = np.array([float(self.p["omega"])])
        super().setup(t0)

    STEP = staticmethod(spinning_step)

    def kernel_status(self, status, t, h):
        if not np.all(np.isfinite(self.u["Omega"])):
            raise ContractError(f"{self.name}: non-finite input Omega at t = {t + h:.9g} s")
        super().kernel_status(status, t, h)
