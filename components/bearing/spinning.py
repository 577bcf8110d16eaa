"""The ball bearing at a varying speed (``bearing.hertz_spinning``): the inner race speed is an input.

The same bearing as component.BallBearing, with ``Omega`` [rad/s] (the spool's speed, components/spool) as an
input instead of the constant ``omega``; at each step whose speed differs from the last one it sets the speed
terms: the cage (ball orbit) speed ``omega_c = Omega/2 (1 - D cos a0 / d_m)``, the balls' centrifugal force
``m_b (d_m/2) omega_c^2`` of eq. (4), and the speed of Palmgren's drag torque (its ``(nu n)^(2/3)`` term and
``P_drag = M Omega``) and the inner race's axial offset z0 at which the balls carry the preload with no radial
load (component.BallBearing): the balls' centrifugal force pushes them outward, opening the inner contact's angle
and lowering the offset that carries the same preload (bearing #5: 22.5 um at rest, 16.2 um at 16 000 rev/min).
z0 is read from a cubic spline over 0 to ``TABLE_TOP`` x omega (static.preload_offset_spline: equally spaced
knots, enough of them for a relative error of ``TABLE_TOLERANCE`` at the intervals' midpoints, checked at set-up
against the static solve), evaluated in the kernel (:func:`preload_offset_at`); a speed beyond the table is an
error naming ``omega``. The preload is a constant force (a spring preload), so the bearing's axial force on the
rotor at X_inner = 0 stays zero at every speed. It also outputs the drag torque ``T_drag = P_drag / Omega`` [N m]
that decelerates the spool (0 on a stopped spool). At Omega = omega throughout every number is the constant-speed
bearing's, bit for bit (the speed terms, z0 among them, are set only when the speed differs from the last one).

Example (a scenario)::

    [components.bearing0]
    implementation = "bearing.hertz_spinning"
    parameters = { bearing = 0 }     # connection: spool_pt.Omega -> bearing0.Omega
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..contract import ContractError, Variable
from ..kernels import port_tuple
from ..numba_internals import kernel_jit
from .component import BallBearing
from .kernel import D_OMEGA, G_F_C, G_OMEGA, G_OMEGA_CAGE, G_Z0, O_P_DRAG, BearingState, tm_step
from .static import preload_offset_spline

#: the constant-speed bearing's containers (its kernel, kernel.tm_step, is called with its own types: a call with
#: this class's types would put them in tm_step's on-disk cache index, unreadable by a process without them), the
#: speed terms' ratios [cage speed per rad/s, centrifugal force per (rad/s of the cage)^2], the preload offset's
#: spline against the speed (coefficients (4, n), knot spacing [rad/s]: static.preload_offset_spline)
SpinBearingParams = namedtuple("SpinBearingParams", "base spin z0_c z0_h")
#: the preload offset's table: its top speed / omega, its largest relative interpolation error
TABLE_TOP = 1.5
TABLE_TOLERANCE = 1e-6
#: status of a speed beyond the table
BEYOND_TABLE = 14


@kernel_jit
def preload_offset_at(c, h, w):
    """z0 at the speed w [rad/s] from the spline (c, h): interval k = floor(|w| / h), d = |w| - k h,
    z0 = ((c0 d + c1) d + c2) d + c3 (z0 is even in w); NaN beyond the table."""
    x = abs(w) / h
    n = c.shape[1]
    k = int(x)
    if k >= n:
        if x > n:
            return np.nan
        k = n - 1                          # the top knot itself
    d = abs(w) - k * h
    return ((c[0, k] * d + c[1, k]) * d + c[2, k]) * d + c[3, k]


@kernel_jit
def set_speed(p, w):
    """The speed terms at w [rad/s]: the cage speed, the balls' centrifugal force, the preload offset, Palmgren's
    speed. False (nothing changed) when w is beyond the preload offset's table."""
    z0 = preload_offset_at(p.z0_c, p.z0_h, w)
    if not math.isfinite(z0):
        return False
    b = p.base
    geo = b.geo
    wc = p.spin[0] * w
    geo[G_OMEGA] = w
    geo[G_OMEGA_CAGE] = wc
    geo[G_F_C] = p.spin[1] * wc * wc
    geo[G_Z0] = z0
    b.drag[D_OMEGA] = w
    b.cache[1] = np.nan                  # the viscous drag power of the last T_oil was at the old speed
    return True
_IN = port_tuple("BallBearing", "Inputs", ("X_inner", "V_inner", "F_journal", "K_journal", "C_journal", "eps",
                                           "T_oil"))
_OUT = port_tuple("BallBearing", "Outputs", ("F_rotor", "X_journal", "V_journal", "Q_max", "Q_max_step",
                                             "sigma_max", "sigma_max_step", "P_drag"))


@kernel_jit
def spinning_step(s, p, u, y, t, h):
    """Set the speed terms at the input speed (when it changed), then the bearing's step (kernel.tm_step)."""
    w = u.Omega[0]
    if not math.isfinite(w):
        return 11
    b = p.base
    if w != b.geo[G_OMEGA] and not set_speed(p, w):
        return BEYOND_TABLE
    status = tm_step(s, b, _IN(u.X_inner, u.V_inner, u.F_journal, u.K_journal, u.C_journal, u.eps, u.T_oil),
                     _OUT(y.F_rotor, y.X_journal, y.V_journal, y.Q_max, y.Q_max_step, y.sigma_max,
                          y.sigma_max_step, y.P_drag), t, h)
    if status == 0:
        y.T_drag[0] = b.out[O_P_DRAG] / w if w > 0.0 else 0.0
    return status


class SpinningBearing(BallBearing):
    """The ball bearing with the spool speed as an input (module docstring)."""

    description = BallBearing.description + " (inner race speed as an input)"
    #: the speed is the Omega input; omega is only the reference of the speed terms' tables, free to differ
    fixed_speed = None
    variables = BallBearing.variables + (
        Variable("Omega", "input", 1, "rad/s", "inner race (spool) speed"),
        Variable("T_drag", "output", 1, "N.m", "drag torque on the spool, P_drag / Omega"),
    )

    def setup(self, t0=0.0):
        super().setup(t0)
        g = self.geometry
        wc1 = g.cage_speed(1.0)
        spin = np.array([wc1, g.centrifugal_force(1.0) / (wc1 * wc1)])
        w = self.p["omega"]
        if not w > 0.0:
            raise ContractError(f"{self.name}.omega must be > 0 rad/s for the speed-following bearing: the preload "
                                f"offset's table spans 0-{TABLE_TOP:g} x omega, got {w}")
        # the table ends at the model's speed limit when 1.5 x omega passes it (a speed beyond is refused)
        self.table_top = min(TABLE_TOP * w, max(w, self.omega_max))
        try:
            c, h, self.z0_table_error = preload_offset_spline(g, self.table_top, TABLE_TOLERANCE)
        except ValueError as exc:
            raise ContractError(f"{self.name}: {exc} (the table spans 0 to {self.table_top * 30.0 / math.pi:.0f} "
                                f"rev/min: {TABLE_TOP:g} x {self.name}.omega, at most the speed limit)") from None
        self._base_p = self._kernel_p
        self._spin_p = SpinBearingParams(self._kernel_p, spin, c, h)
        self.y["T_drag"] = np.array([self.y["P_drag"][0] / w if w > 0.0 else 0.0])

    def _advance(self, h, t):
        """component.BallBearing._advance through the constant-speed kernel with its own port types."""
        self._nu(float(self.u["T_oil"][0]))
        st = self.state
        s = BearingState(st["balls"].copy(), st["journal"].copy(), st["phi"].copy(), self.u["eps"].copy())
        y = _OUT(*[np.zeros_like(self.y[n]) for n in _OUT._fields])
        status = tm_step(s, self._kernel_p, _IN(*[self.u[n] for n in _IN._fields]), y, t, h)
        if status != 0:
            self._fail(float(status - 10), t + h)
        for n, a in zip(_OUT._fields, y):
            self.y[n] = a

    STEP = staticmethod(spinning_step)

    def kernel_params(self):
        # the base's own methods (the TO update, the viscosity) keep using the base container, _kernel_p
        return self._spin_p

    def kernel_status(self, status, t, h):
        if status == 11 and not np.all(np.isfinite(self.u["Omega"])):
            raise ContractError(f"{self.name}: non-finite input Omega at t = {t + h:.9g} s")
        if status == BEYOND_TABLE:
            self._beyond_table(float(self.u["Omega"][0]), t + h)
        super().kernel_status(status, t, h)

    def _beyond_table(self, w, t):
        top = self.table_top
        why = (f"{TABLE_TOP:g} x {self.name}.omega): set omega nearer the run's speeds" if top < self.omega_max
               else "the model's speed limit, data/bearings.toml dn_limit)")
        raise ContractError(f"{self.name}: inner race speed {abs(w) * 30.0 / math.pi:.0f} rev/min at t = {t:.9g} s "
                            f"is beyond the preload offset's table (0-{top * 30.0 / math.pi:.0f} rev/min, {why}")

    def preload_offset(self, w: float | None = None) -> float:
        """The inner race's axial offset z0 [m] at the speed w [rad/s] (None: the present one) as the kernel
        reads it (NaN beyond the table)."""
        p = self._spin_p
        if w is None:
            return float(p.base.geo[G_Z0])
        return float(preload_offset_at(p.z0_c, p.z0_h, float(w)))

    def _thermal_only_step(self, t, h):
        """The TO update (component.BallBearing) at the present spool speed: Palmgren's viscous term follows it;
        the load term, frozen as a power with the mechanical state, is scaled to it (a torque frozen)."""
        p = self._base_p
        w0, w = float(p.geo[G_OMEGA]), float(self.u["Omega"][0])
        if not math.isfinite(w):
            raise ContractError(f"{self.name}: non-finite input Omega at t = {t:.9g} s")
        if w != w0:
            # every speed term, so that the next coupled step starts with this speed's
            if not set_speed(self._spin_p, w):
                self._beyond_table(w, t)
            if w0 > 0.0:
                self._frozen_load = getattr(self, "_frozen_load", 0.0) * w / w0
        super()._thermal_only_step(t, h)
        self.y["T_drag"] = np.array([self.y["P_drag"][0] / w if w > 0.0 else 0.0])
