"""The eccentricity frame: from the film's force and derivatives in that frame to the housing axes.

The FE model (reynolds_fe) and the fast model (fast) both solve in the frame rotated to the eccentricity,
d = e (cos phi, sin phi): v_r, v_t = R^T w with R = [[cos, -sin], [sin, cos]], and give the aligned force
f = (F_r, F_t)(eps, a, b) with a = mu v_r, b = mu v_t, eps = e / c. Then F = R f and, by the chain rule
(d(v_r, v_t)/d phi = (v_t, -v_r), dR/d phi = R [[0, -1], [1, 0]]):

    dF/dw = mu R J R^T,          J = d(F_r, F_t)/d(a, b),
    dF/dd = R [g_e | g_phi / e] R^T,   g_e = (df/d eps) / c,   g_phi = (-F_t, F_r) + J (b, -a).

These are the K_film and C_film outputs the bearing uses for its linearly implicit journal integration.
The exact film is rotation-equivariant, so g_phi -> 0 as e -> 0 and g_phi / e has a finite limit; the discrete
aligned model is equivariant only up to its mesh error, which g_phi / e would amplify near the centre. The
callers therefore pass g_phi minus its value at eps = 0 for the same (a, b) (which is pure mesh error) when
the journal is near the centre (eps < EPS_NEAR_CENTRE).
"""
from __future__ import annotations

import math

from ..numba_internals import kernel_jit

#: below this eccentricity ratio the callers remove the centred model's g_phi (mesh error) before dividing by e
EPS_NEAR_CENTRE = 0.02
#: at exactly e = 0 the limit g_phi / e is taken as a difference quotient over this eccentricity ratio
EPS_DIFF = 1e-4


@kernel_jit(inline="always")
def frame(dx, dy):
    """(e, cos phi, sin phi); phi = 0 for a centred journal."""
    e = math.sqrt(dx * dx + dy * dy)
    if e > 0.0:
        return e, dx / e, dy / e
    return 0.0, 1.0, 0.0


@kernel_jit(inline="always")
def to_housing_axes(c, s, e_div, clearance, mu, Fr, Ft, Jra, Jrb, Jta, Jtb, dFr_deps, dFt_deps, gphi_r, gphi_t,
                    out):
    """Write F (2), K = dF/dd (4, row-major) and C = dF/dw (4, row-major) into out[0:10].

    e_div is the eccentricity that divides g_phi (the caller's e, or EPS_DIFF c at the centre).
    """
    out[0] = c * Fr - s * Ft
    out[1] = s * Fr + c * Ft
    # G = [g_e | g_phi / e] in the aligned frame, then K = R G R^T
    g11 = dFr_deps / clearance
    g21 = dFt_deps / clearance
    g12 = gphi_r / e_div
    g22 = gphi_t / e_div
    _rotate(c, s, g11, g12, g21, g22, out, 2)
    _rotate(c, s, mu * Jra, mu * Jrb, mu * Jta, mu * Jtb, out, 6)


@kernel_jit(inline="always")
def _rotate(c, s, a11, a12, a21, a22, out, i):
    """out[i:i+4] = R A R^T (row-major)."""
    # B = R A
    b11 = c * a11 - s * a21
    b12 = c * a12 - s * a22
    b21 = s * a11 + c * a21
    b22 = s * a12 + c * a22
    # B R^T, R^T = [[c, s], [-s, c]]
    out[i] = b11 * c - b12 * s
    out[i + 1] = b11 * s + b12 * c
    out[i + 2] = b21 * c - b22 * s
    out[i + 3] = b21 * s + b22 * c


def gphi(Fr, Ft, Jra, Jrb, Jta, Jtb, a, b):
    """g_phi = (-F_t, F_r) + J (b, -a) (python helper for the FE path)."""
    return -Ft + Jra * b - Jrb * a, Fr + Jta * b - Jtb * a


__all__ = ["EPS_NEAR_CENTRE", "EPS_DIFF", "frame", "to_housing_axes", "gphi"]
