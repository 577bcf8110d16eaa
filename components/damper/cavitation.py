"""Film rupture models applied to the Reynolds pressure field.

Guembel (half-Sommerfeld generalised): solve the full-film Reynolds equation, then set every pressure below the
cavitation pressure to it (physics-notes, "Cavitation"; San Andres, Squeeze Film Dampers lecture notes). It is
not mass-conserving, but it is the usual model in transient rotordynamics and the one that gives the classic
pi-film damper when p_s = p_cav = 0. With a supply pressure p_s > p_cav the clipped region shrinks (a higher
supply keeps the film whole, towards 2 pi-film behaviour): in terms of p_rel = p - p_s the clip is at
p_rel = p_cav - p_s.
"""
from __future__ import annotations

import numpy as np

MODELS = ("none", "guembel")


def guembel(p_rel: np.ndarray, supply_pressure: float, cavitation_pressure: float) -> np.ndarray:
    """p - p_s after Guembel clipping: max(p, p_cav) - p_s, elementwise."""
    return np.maximum(p_rel, cavitation_pressure - supply_pressure)
