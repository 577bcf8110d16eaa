"""How the windmilling law follows the flight: the windmill speed and the torque level at any flight condition
from their values at a reference condition.

The spool's law is ``T_aero = c (Omega - Omega_wm) |Omega - Omega_wm|`` (component.py). Its dependence on the flight
condition comes from turbomachinery similarity:

* a turbomachine's referred torque ``TRQ / delta`` is a function of its referred speed ``N / sqrt(theta)`` and of
  the flight Mach number ``M`` (Walsh & Fletcher, *Gas Turbine Performance*, 2nd ed., Blackwell 2004: the referred
  parameter groups; ``theta``, ``delta`` the inlet's total temperature and pressure over ISA sea level,
  atmosphere.py). Written in referred terms the law is
  ``TRQ / delta = k (n - n_wm(M)) |n - n_wm(M)|`` with ``n = Omega / sqrt(theta)``, hence

      Omega_wm = n_wm(M) sqrt(theta),        c = k delta / theta;

  ``delta / theta = rho_t / rho_0`` (the inlet's total density over sea level's): the fan-law scaling of a
  turbomachine's torque with density at a fixed flow coefficient, ``TRQ ~ rho N^2 D^5`` (Dixon & Hall, *Fluid
  Mechanics and Thermodynamics of Turbomachinery*, 7th ed., 2014, ch. 1, dimensional analysis). ``k`` constant is
  ASSUMED: the shape of the torque characteristic about the windmill point does not change with Mach number;
* ``n_wm(M)``: Walsh & Fletcher's windmilling correlation of the low-pressure spool's referred speed with flight
  Mach number, as a fraction of the maximum, ``f(M) = 0.5 M`` up to M 0.4, ``0.20 + 0.33 (M - 0.4)`` above
  (the correlation the shipped rundown's 4 900 rev/min comes from: M 0.8 at 35 000 ft). At low Mach number the
  windmill speed ``0.5 M sqrt(theta) N_max`` is proportional to the flight speed ``V = M a``. The gas generator's
  windmill speed is taken to follow the same ratio (ASSUMED: the source gives the low-pressure spool's).

Relative to the reference condition (``M_r``, ``theta_r``, ``delta_r``) at which ``windmill_rpm`` and
``aero_torque`` are given:

    Omega_wm(t) = Omega_wm,r f(M) sqrt(theta) / (f(M_r) sqrt(theta_r))
    c(t)        = c_r (delta / theta) / (delta_r / theta_r)

Example (the reference, M 0.8 at 35 000 ft, and an approach at M 0.25, 1 500 ft)::

    >>> import numpy as np
    >>> from rotorcosim.components.spool.atmosphere import isa, total_ratios
    >>> T, p, _ = isa(np.array([10668.0, 457.2]))
    >>> theta, delta = total_ratios(T, p, np.array([0.8, 0.25]))
    >>> speed, torque = scales(np.array([0.8, 0.25]), theta, delta)
    >>> [round(float(x), 3) for x in speed], [round(float(x), 3) for x in torque]
    ([1.0, 0.407], [1.0, 2.357])
"""
from __future__ import annotations

import numpy as np

#: the knee of Walsh & Fletcher's windmilling correlation: Mach number, and the referred speed fraction there
KNEE_MACH, KNEE_FRACTION = 0.4, 0.20
#: the correlation's slopes below and above the knee (fraction of maximum referred speed per unit Mach number)
SLOPE_LOW, SLOPE_HIGH = 0.5, 0.33


def referred_windmill_fraction(mach):
    """``f(M)``: the windmilling referred speed over the maximum (Walsh & Fletcher's correlation)."""
    m = np.asarray(mach, dtype=float)
    return np.where(m <= KNEE_MACH, SLOPE_LOW * m, KNEE_FRACTION + SLOPE_HIGH * (m - KNEE_MACH))


def scales(mach, theta, delta):
    """The windmill speed and the torque coefficient at each flight condition over their values at the first
    (the reference; module docstring). ``mach[0]`` must be > 0 (a windmill speed to scale)."""
    f = referred_windmill_fraction(mach) * np.sqrt(theta)
    rho = np.asarray(delta, dtype=float) / np.asarray(theta, dtype=float)
    return f / f[0], rho / rho[0]
