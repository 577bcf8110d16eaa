"""The temperature range of the SAE 30 viscosity fit (ASTM D341 / Walther through Table 3's two points), shared by
the bearing's drag torque (bearing/oil.py) and the damper's film (damper/viscosity.py): one range, one message.

(200 K, 600 K] is a guard against a temperature that is not an oil temperature (a value in degrees C or in
another unit, a diverged thermal network), not the fit's validity: ASTM D341 holds over the liquid range, for an
SAE 30 oil roughly from its pour point (about 250 K) to its flash point (about 500 K). The guard is wider so that
an overshoot of a run stays computable; no run of the paper's cases comes near either end except the largest
unbalances (docs/results/calibration.md: bearing #0's oil passed 600 K at 14 252 N, and that run stops with this message).
"""
from __future__ import annotations

import math

#: the oil temperatures the viscosity fit accepts, kelvin: (low, high], the low end excluded
T_MIN_K, T_MAX_K = 200.0, 600.0
#: where the fit describes the oil (the thermal network's validity envelope, thermal/component.py): ASTM D341's
#: viscosity-temperature relation holds while the oil is a homogeneous liquid, for an SAE 30 mineral engine oil
#: from about its pour point (-20 to -25 C, ASTM D97) to its flash point (about 230 C, ASTM D92; both from oil
#: makers' product data). Between these and the guard above a run goes on and says so.
T_POUR_K, T_FLASH_K = 250.0, 500.0
SOURCE = ("ASTM D341 viscosity fit, valid while the SAE 30 oil is liquid: pour point ~250 K (ASTM D97) to flash "
          "point ~500 K (ASTM D92)")


def check_oil_temperature(T_K) -> float:
    """``T_K`` as a float if inside (T_MIN_K, T_MAX_K], else a ValueError that names the value and the range."""
    T = float(T_K)
    if not math.isfinite(T) or T <= T_MIN_K or T > T_MAX_K:
        raise ValueError(f"oil temperature {T:.6g} K is outside the viscosity fit's range "
                         f"({T_MIN_K:g} K, {T_MAX_K:g} K]")
    return T
