"""Hertz point contact of a ball in a race groove (the constants of the paper's eqs. (9) and (10)).

Harris & Kotzalas (Rolling Bearing Analysis, ch. 6) / Hamrock & Dowson notation, with gamma = D cos(alpha) / d_m:
    R_x = D (1 -+ gamma) / 2  (inner -, outer +),   R_y = f D / (2 f - 1),   1/R = 1/R_x + 1/R_y;
    ellipticity k = a / b from  R_y / R_x = (k^2 E(m) - K(m)) / (K(m) - E(m)),  m = 1 - 1/k^2;
    a = (6 k^2 E Q R / (pi E'))^(1/3),  b = (6 E Q R / (pi k E'))^(1/3),  sigma = 3 Q / (2 pi a b)   (eq. 10);
    Q = K delta^(3/2),  K = pi k E' sqrt(2 E R / (9 F^3))                                              (eq. 9);
K(m), E(m) the complete elliptic integrals (here F = K(m), E = E(m)), E' = 2 / sum((1 - nu^2) / E).
The ellipticity is solved exactly (not with the Hamrock-Brewe fits, which the tests use as an independent check).
K(m) and E(m) come from the arithmetic-geometric mean (Abramowitz & Stegun 17.6), exact to round-off in a few
iterations, and k from bisection: scipy.special and scipy.optimize would add ~0.5 s of import to every run's
set-up for two numbers (tests/components/test_bearing_hertz.py checks both against scipy).
"""
from __future__ import annotations

import math
from dataclasses import dataclass



@dataclass(frozen=True)
class HertzContact:
    """Load-independent constants of one ball/race contact."""

    Rx: float          # m, rolling-direction radius of the curvature sum
    Ry: float          # m, transverse radius
    R: float           # m, 1/R = 1/Rx + 1/Ry
    k: float           # ellipticity a/b
    E_int: float       # E(m)
    F_int: float       # K(m)
    E_eff: float       # Pa, E'
    K: float           # N/m^1.5, Q = K delta^1.5
    stress_coeff: float  # Pa / N^(1/3), sigma_max = stress_coeff Q^(1/3)

    def semi_axes(self, Q: float) -> tuple[float, float]:
        """(a, b) in m at load Q in N."""
        if not (Q >= 0.0 and math.isfinite(Q)):
            raise ValueError(f"contact load must be a finite number >= 0, got {Q!r}")
        c = 6.0 * self.E_int * Q * self.R / (math.pi * self.E_eff)
        return (self.k * self.k * c) ** (1.0 / 3.0), (c / self.k) ** (1.0 / 3.0)

    def max_stress(self, Q: float) -> float:
        """Compressive stress at the centre of the contact ellipse (magnitude of eq. 10), Pa."""
        return self.stress_coeff * max(Q, 0.0) ** (1.0 / 3.0)

    def deflection(self, Q: float) -> float:
        """Approach of the two bodies (m) at load Q."""
        return (max(Q, 0.0) / self.K) ** (2.0 / 3.0)


def effective_modulus(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)."""
    return 2.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2)


def elliptic_KE(m: float) -> tuple[float, float]:
    """Complete elliptic integrals of the first and second kind, K(m) and E(m), parameter 0 <= m < 1, by the
    arithmetic-geometric mean (A&S 17.6.1-17.6.4): K = pi / (2 a_N), E = K (1 - sum 2^(n-1) c_n^2), c_0^2 = m."""
    if not (0.0 <= m < 1.0):
        raise ValueError(f"elliptic parameter m must be in [0, 1), got {m!r}")
    a, b = 1.0, math.sqrt(1.0 - m)
    total, weight = 0.5 * m, 0.5  # 2^(n-1) c_n^2 at n = 0
    for _ in range(64):  # converges quadratically: 5-6 passes; a and b may end one unit of round-off apart
        if abs(a - b) <= 4e-16 * a:
            break
        c = 0.5 * (a - b)
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        weight *= 2.0
        total += weight * c * c
    K = math.pi / (2.0 * a)
    return K, K * (1.0 - total)


def ellipticity(ratio: float) -> float:
    """k = a/b for curvature ratio R_y/R_x >= 1 (exact, complete elliptic integrals)."""
    if not (ratio >= 1.0 and math.isfinite(ratio)):
        raise ValueError(f"R_y/R_x must be a finite number >= 1, got {ratio!r}")
    if ratio == 1.0:
        return 1.0

    def g(k):
        K, E = elliptic_KE(1.0 - 1.0 / (k * k))
        return (k * k * E - K) / (K - E) - ratio

    # g grows with k from g(1+) = 1 - ratio < 0; bisection to round-off (ratio below ~1e4 keeps k < 100)
    lo, hi = 1.0 + 1e-9, 100.0
    if g(hi) < 0.0:
        raise ValueError(f"R_y/R_x = {ratio!r} is beyond a ball contact (ellipticity above 100)")
    while hi - lo > 1e-15 * hi:
        mid = 0.5 * (lo + hi)
        if g(mid) < 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def contact_from_radii(Rx: float, Ry: float, E_eff: float) -> HertzContact:
    """Constants of a contact with principal radii of the curvature sum Rx <= Ry (m)."""
    for name, v in (("Rx", Rx), ("Ry", Ry), ("E'", E_eff)):
        if not (v > 0.0 and math.isfinite(v)):
            raise ValueError(f"Hertz contact: {name} must be a finite number > 0, got {v!r}")
    if Ry < Rx:
        Rx, Ry = Ry, Rx
    R = 1.0 / (1.0 / Rx + 1.0 / Ry)
    k = ellipticity(Ry / Rx)
    m = 1.0 - 1.0 / (k * k)
    F, E = elliptic_KE(m)
    K = math.pi * k * E_eff * math.sqrt(2.0 * E * R / (9.0 * F ** 3))
    # a b = k^(1/3) (6 E R / (pi E'))^(2/3) Q^(2/3)  ->  sigma = 3 Q / (2 pi a b) = coeff Q^(1/3)
    ab_coeff = k ** (1.0 / 3.0) * (6.0 * E * R / (math.pi * E_eff)) ** (2.0 / 3.0)
    return HertzContact(Rx, Ry, R, k, E, F, E_eff, K, 3.0 / (2.0 * math.pi * ab_coeff))


def race_contact(D: float, d_m: float, alpha: float, f: float, E_eff: float, race: str) -> HertzContact:
    """Ball (diameter D) in the groove (curvature ratio f) of the inner or outer race, pitch diameter d_m,
    contact angle alpha (rad)."""
    if race not in ("inner", "outer"):
        raise ValueError(f"race must be 'inner' or 'outer', got {race!r}")
    if not (D > 0.0 and d_m > D):
        raise ValueError(f"need ball diameter D > 0 and pitch diameter d_m > D, got D={D!r}, d_m={d_m!r}")
    if not (f > 0.5 and math.isfinite(f)):
        raise ValueError(f"groove curvature ratio f must be > 0.5 (groove wider than the ball), got {f!r}")
    gamma = D * math.cos(alpha) / d_m
    Rx = 0.5 * D * (1.0 - gamma if race == "inner" else 1.0 + gamma)
    Ry = f * D / (2.0 * f - 1.0)
    return contact_from_radii(Rx, Ry, E_eff)


def series_stiffness(K_i: float, K_e: float) -> float:
    """K_n of the inner and outer contacts in series: (K_i^(-2/3) + K_e^(-2/3))^(-3/2)."""
    return (K_i ** (-2.0 / 3.0) + K_e ** (-2.0 / 3.0)) ** (-1.5)
