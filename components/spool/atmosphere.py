"""The International Standard Atmosphere (ISA) to 20 km, and the total (stagnation) conditions of a flight.

Source: ICAO Doc 7488/3, *Manual of the ICAO Standard Atmosphere* (1993), identical to the U.S. Standard
Atmosphere 1976 below 32 km. Sea level ``T0 = 288.15 K``, ``p0 = 101 325 Pa``, ``R = 287.05287 J/(kg K)``,
``g0 = 9.80665 m/s^2``; geopotential altitude ``h`` [m]:

* troposphere (``h <= 11 000 m``): ``T = T0 - L h`` with ``L = 0.0065 K/m``, ``p = p0 (T / T0)^(g0 / (R L))``;
* lower stratosphere (``11 000 < h <= 20 000 m``): ``T = 216.65 K``, ``p = p11 exp(-g0 (h - 11 000) / (R T))``;
* ``rho = p / (R T)``.

A flight at Mach number ``M`` meets its total conditions at the engine's inlet (isentropic stagnation, perfect gas,
``gamma = 1.4``): ``T_t = T (1 + (gamma - 1) / 2 M^2)``, ``p_t = p (1 + (gamma - 1) / 2 M^2)^(gamma / (gamma - 1))``,
and the referred-parameter ratios ``theta = T_t / T0``, ``delta = p_t / p0`` (Walsh & Fletcher, *Gas Turbine
Performance*, 2nd ed., 2004: the inlet's total temperature and pressure over the ISA sea-level values).

``density_altitude`` inverts ``rho(h)`` (the altitude of the ISA whose density is ``rho``): a flight given by its
true airspeed and density takes the ISA temperature there.

Example::

    >>> T, p, rho = isa(11000.0)
    >>> round(float(T), 2), round(float(p)), round(float(rho), 4)
    (216.65, 22632, 0.3639)
"""
from __future__ import annotations

import numpy as np

T0, P0 = 288.15, 101325.0
R_AIR, G0, LAPSE = 287.05287, 9.80665, 0.0065
GAMMA = 1.4
H_TROPOPAUSE, H_TOP = 11000.0, 20000.0
#: the lowest altitude of the ISA's tables [m] (ICAO Doc 7488 starts at -5 000 m; airfields lie above -500 m)
H_BOTTOM = -500.0
T11 = T0 - LAPSE * H_TROPOPAUSE
EXPONENT = G0 / (R_AIR * LAPSE)
P11 = P0 * (T11 / T0) ** EXPONENT
RHO0, RHO11 = P0 / (R_AIR * T0), P11 / (R_AIR * T11)


def isa(h):
    """Static temperature [K], pressure [Pa] and density [kg/m^3] at geopotential altitude ``h`` [m]
    (``H_BOTTOM <= h <= H_TOP``; the caller checks the range)."""
    h = np.asarray(h, dtype=float)
    trop = h <= H_TROPOPAUSE
    T = np.where(trop, T0 - LAPSE * h, T11)
    p = np.where(trop, P0 * (np.where(trop, T, T0) / T0) ** EXPONENT,
                 P11 * np.exp(-G0 * (h - H_TROPOPAUSE) / (R_AIR * T11)))
    return T, p, p / (R_AIR * T)


def density_altitude(rho):
    """The ISA altitude [m] whose density is ``rho`` [kg/m^3] (the inverse of :func:`isa`'s density)."""
    rho = np.asarray(rho, dtype=float)
    # troposphere: rho = RHO0 (T / T0)^(EXPONENT - 1); stratosphere: rho = RHO11 exp(-g0 (h - 11 000) / (R T11))
    trop = rho >= RHO11
    h_trop = (T0 - T0 * (np.where(trop, rho, RHO0) / RHO0) ** (1.0 / (EXPONENT - 1.0))) / LAPSE
    h_strat = H_TROPOPAUSE - R_AIR * T11 / G0 * np.log(np.where(trop, RHO11, rho) / RHO11)
    return np.where(trop, h_trop, h_strat)


def total_ratios(T, p, mach):
    """``theta = T_t / T0`` and ``delta = p_t / p0`` of a flight at Mach ``mach`` in air at ``T`` [K], ``p`` [Pa]."""
    f = 1.0 + 0.5 * (GAMMA - 1.0) * np.asarray(mach, dtype=float) ** 2
    return T * f / T0, p * f ** (GAMMA / (GAMMA - 1.0)) / P0


def speed_of_sound(T):
    """``a = sqrt(gamma R T)`` [m/s]."""
    return np.sqrt(GAMMA * R_AIR * np.asarray(T, dtype=float))
