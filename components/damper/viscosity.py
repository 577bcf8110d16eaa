"""SAE 30 dynamic viscosity against temperature: Walther / ASTM D341 through the paper's two points.

ASTM D341 (Walther):  log10 log10(nu + 0.7) = A - B log10(T),  nu in cSt (mm^2/s), T in kelvin,
with A, B through nu(40 C) and nu(100 C); nu = mu / rho with rho(T) = rho_300 + drho_dT (T - 300)
(engine oil, Incropera Table A.5, as in physics-notes). mu = rho nu then reproduces 92 cP at 40 C and 11 cP at
100 C exactly (Table 3 of the paper) and gives ~26 cP at 70 C, ~16.5 cP at 85 C (physics-notes' check values).

Same formula as physics-notes' (A = 8.4882, B = 3.2784); the constants are recomputed from the data file so that
the fit stays exactly through the two table points.
"""
from __future__ import annotations

import math
import tomllib
from functools import lru_cache
from pathlib import Path

from ..oil_fit import check_oil_temperature

DATA = Path(__file__).with_name("data") / "dampers.toml"


@lru_cache(maxsize=1)
def oil_constants() -> tuple[float, float, float, float]:
    """The oil's Walther constants A, B, density at 300 K [kg/m3] and its temperature slope, from dampers.toml."""
    with open(DATA, "rb") as f:
        oil = tomllib.load(f)["oil"]
    rho300, drho = float(oil["rho_300K"]), float(oil["drho_dT"])

    def loglog(mu, T):
        nu_cst = mu / (rho300 + drho * (T - 300.0)) * 1e6
        return math.log10(math.log10(nu_cst + 0.7))

    T1, T2 = 313.15, 373.15
    y1, y2 = loglog(float(oil["mu_40C"]), T1), loglog(float(oil["mu_100C"]), T2)
    B = (y1 - y2) / (math.log10(T2) - math.log10(T1))
    A = y1 + B * math.log10(T1)
    return A, B, rho300, drho


def walther_constants() -> tuple[float, float]:
    """(A, B) of log10 log10(nu + 0.7) = A - B log10(T_K) for SAE 30 (nu in cSt)."""
    A, B, _, _ = oil_constants()
    return A, B


def sae30_viscosity(T_kelvin: float) -> float:
    """Dynamic viscosity of SAE 30 in Pa s at ``T_kelvin`` (ASTM D341 / Walther, see module docstring)."""
    T = check_oil_temperature(T_kelvin)
    A, B, rho300, drho = oil_constants()
    nu_cst = 10.0 ** (10.0 ** (A - B * math.log10(T))) - 0.7
    return nu_cst * 1e-6 * (rho300 + drho * (T - 300.0))
