"""SAE 30 dynamic viscosity against temperature for the drag torque: Walther / ASTM D341 through the paper's
two points (Table 3: 92 cP at 40 C, 11 cP at 100 C).

ASTM D341 (Walther):  log10 log10(nu + 0.7) = A - B log10(T),  nu in cSt, T in K; nu = mu / rho with the engine
oil density rho(T) = 884.1 - 0.590 (T - 300) kg/m^3 (Incropera Table A.5; physics-notes). A, B are solved from the
two table points, so the fit passes through them exactly (A ~ 8.488, B ~ 3.278 as in physics-notes).
"""
from __future__ import annotations

import math

from ..oil_fit import check_oil_temperature
from .geometry import DATA

_OIL = DATA["oil"]
_RHO300, _DRHO = float(_OIL["rho_300K"]), float(_OIL["drho_dT"])


def oil_density(T_K: float) -> float:
    """Engine-oil density, kg/m^3."""
    return _RHO300 + _DRHO * (T_K - 300.0)


def _loglog(mu: float, T: float) -> float:
    return math.log10(math.log10(mu / oil_density(T) * 1e6 + 0.7))


_T1, _T2 = 313.15, 373.15
_Y1, _Y2 = _loglog(float(_OIL["mu_40C"]), _T1), _loglog(float(_OIL["mu_100C"]), _T2)
WALTHER_B = (_Y1 - _Y2) / (math.log10(_T2) - math.log10(_T1))
WALTHER_A = _Y1 + WALTHER_B * math.log10(_T1)


def sae30_kinematic_viscosity(T_K: float) -> float:
    """Kinematic viscosity of SAE 30 in m^2/s."""
    T = check_oil_temperature(T_K)
    return (10.0 ** (10.0 ** (WALTHER_A - WALTHER_B * math.log10(T))) - 0.7) * 1e-6


def sae30_viscosity(T_K: float) -> float:
    """Dynamic viscosity of SAE 30 in Pa s at ``T_K`` kelvin."""
    T = check_oil_temperature(T_K)
    return sae30_kinematic_viscosity(T) * oil_density(T)
