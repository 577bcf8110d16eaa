"""Quasi-static equilibrium of the bearing: every ball in equilibrium (eq. 4 with zero acceleration, centrifugal
force included) and the inner race in equilibrium with an external load (eq. 2 with zero acceleration), the outer
race held at a given position. Contact geometry eqs. (1), (3), (6)-(8), Hertz eq. (9) without the damping term,
stress eq. (10). Used by the component's set-up (the preloaded rest state) and by ``rotorcosim bearing-static``.
"""
from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np

from .geometry import BearingGeometry


class PreloadSolveError(ValueError):
    """The preload offset has no solution in the searched range (the message says the preload and the force)."""


@dataclass
class BallState:
    """Contacts of all balls at one configuration (arrays over the balls)."""

    phi: np.ndarray
    v: np.ndarray          # (2, Z) ball centre displacement [v_r, v_z]
    Q_i: np.ndarray
    Q_e: np.ndarray
    alpha_i: np.ndarray    # rad
    alpha_e: np.ndarray
    delta_i: np.ndarray
    delta_e: np.ndarray

    def race_force(self) -> np.ndarray:
        """Force of the balls on the inner race (x, y, z), eqs. (2)-(3): sum of T^T Q."""
        qr = -self.Q_i * np.cos(self.alpha_i)
        return np.array([np.sum(qr * np.cos(self.phi)), np.sum(qr * np.sin(self.phi)),
                         np.sum(-self.Q_i * np.sin(self.alpha_i))])

    def outer_race_force(self) -> np.ndarray:
        """Force of the balls on the outer race (x, y), eq. (5)."""
        qr = self.Q_e * np.cos(self.alpha_e)
        return np.array([np.sum(qr * np.cos(self.phi)), np.sum(qr * np.sin(self.phi))])


def ball_angles(Z: int, phi0: float = 0.0) -> np.ndarray:
    return phi0 + 2.0 * math.pi * np.arange(Z) / Z


def _groove_centres(g: BearingGeometry, ur, uz, wr, eps):
    """Groove centres p (inner) and q (outer) relative to the nominal ball centre (v = 0), eq. (6)."""
    eps_i, eps_e, _ = eps
    ca, sa = math.cos(g.alpha0), math.sin(g.alpha0)
    p = np.array([g.l_oi * ca + ur + eps_i, g.l_oi * sa + uz + 0.0 * ur])
    q = np.array([wr + eps_e - g.l_oe * ca + 0.0 * ur, -g.l_oe * sa + 0.0 * ur])
    return p, q


def _contacts(g: BearingGeometry, p, q, v, eps_b):
    A = p - v
    B = v - q
    Li = np.hypot(A[0], A[1])
    Le = np.hypot(B[0], B[1])
    di = eps_b + Li - g.l_oi
    de = eps_b + Le - g.l_oe
    Qi = g.K_i * np.maximum(di, 0.0) ** 1.5
    Qe = g.K_e * np.maximum(de, 0.0) ** 1.5
    return A, B, Li, Le, di, de, Qi, Qe


#: a ball's force residual, relative to its contact loads, below which its equilibrium holds to the precision of
#: float64 sums of forces of that size (a few hundred ulps): the test once the iterations are spent
ROUNDING = 1e-12


def solve_balls(g: BearingGeometry, ur, uz, wr, eps=(0.0, 0.0, 0.0), Fc: float = 0.0, v0=None,
                tol: float = 1e-10, max_iter: int = 200) -> tuple[np.ndarray, tuple]:
    """Ball centre displacements (2, n) in equilibrium for inner groove displacements (ur, uz) and outer groove
    radial displacement wr (arrays over the balls): Newton on eq. (4) with the analytic 2x2 Jacobian, started from
    the collinear solution (exact when F_c = 0)."""
    ur = np.atleast_1d(np.asarray(ur, dtype=float))
    uz = np.broadcast_to(np.asarray(uz, dtype=float), ur.shape)
    wr = np.broadcast_to(np.asarray(wr, dtype=float), ur.shape)
    eps_b = float(eps[2])
    p, q = _groove_centres(g, ur, uz, wr, eps)
    if v0 is None:
        d = p - q
        L = np.hypot(d[0], d[1])
        n = d / L
        overlap = L - g.l_oi - g.l_oe + 2.0 * eps_b
        share = 1.0 / (1.0 + (g.K_i / g.K_e) ** (2.0 / 3.0))      # K_i d_i^1.5 = K_e d_e^1.5
        di = np.where(overlap > 0.0, overlap * share, 0.5 * overlap)
        v = p - n * (g.l_oi + di - eps_b)
    else:
        v = np.array(v0, dtype=float).copy()
    scale = max(g.K_i * (1e-6) ** 1.5, Fc, 1.0)
    for _ in range(max_iter):
        A, B, Li, Le, di, de, Qi, Qe = _contacts(g, p, q, v, eps_b)
        ni, ne = A / Li, B / Le
        R = Qi * ni - Qe * ne
        R[0] += Fc
        if Fc == 0.0:
            # a ball touching neither race at zero speed carries nothing and sits anywhere in its gap
            R = np.where((di > 0.0) | (de > 0.0), R, 0.0)
        if np.max(np.abs(R)) < tol * scale:
            break
        dQi = 1.5 * g.K_i * np.sqrt(np.maximum(di, 0.0))
        dQe = 1.5 * g.K_e * np.sqrt(np.maximum(de, 0.0))
        # S = Q' n n^T + Q / L (I - n n^T) for each contact; dR/dv = -(S_i + S_e)
        S = np.zeros((2, 2) + ur.shape)
        for Qc, dQ, nn, L in ((Qi, dQi, ni, Li), (Qe, dQe, ne, Le)):
            for a in range(2):
                for b in range(2):
                    S[a, b] += (dQ - Qc / L) * nn[a] * nn[b] + (Qc / L if a == b else 0.0)
        S[0, 0] += 1.0
        S[1, 1] += 1.0                  # keeps a ball in its gap (F_c > 0) from a singular step
        det = S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0]
        dv = np.array([(S[1, 1] * R[0] - S[0, 1] * R[1]) / det, (S[0, 0] * R[1] - S[1, 0] * R[0]) / det])
        # no step longer than 2 um while in contact (the contact law has a kink at delta = 0); a free ball may
        # travel a fifth of the groove-centre distance per iteration
        mag = np.hypot(dv[0], dv[1])
        cap = np.where((di > 0.0) | (de > 0.0), 2e-6, 0.2 * min(g.l_oi, g.l_oe))
        dv *= np.minimum(1.0, cap / np.maximum(mag, 1e-300))
        v = v + dv
    else:
        # under loads of 1e8 N the contact forces carry a rounding error of ~1e-8 N that no iteration removes: a
        # residual that small against the balls' own loads is converged (at the precision of the numbers)
        A, B, Li, Le, di, de, Qi, Qe = _contacts(g, p, q, v, eps_b)
        R = Qi * A / Li - Qe * B / Le
        R[0] += Fc
        if Fc == 0.0:
            R = np.where((di > 0.0) | (de > 0.0), R, 0.0)
        load = max(float(np.max(Qi)), float(np.max(Qe)), scale)
        residual = float(np.max(np.abs(R)))
        if not (math.isfinite(residual) and math.isfinite(load) and residual < ROUNDING * load):
            raise RuntimeError(f"ball equilibrium did not converge (residual {residual:.3e} N against "
                               f"contact loads up to {load:.3g} N)")
    return v, _contacts(g, p, q, v, eps_b)


def ball_state(g: BearingGeometry, X, Xe=(0.0, 0.0), eps=(0.0, 0.0, 0.0), Fc: float = 0.0, phi0: float = 0.0,
               v0=None) -> BallState:
    """All balls in quasi-static equilibrium with the inner race at X (x, y, z) and the outer race at Xe."""
    phi = ball_angles(g.Z, phi0)
    c, s = np.cos(phi), np.sin(phi)
    ur = X[0] * c + X[1] * s
    wr = Xe[0] * c + Xe[1] * s
    v, (A, B, Li, Le, di, de, Qi, Qe) = solve_balls(g, ur, X[2], wr, eps, Fc, v0)
    return BallState(phi, v, Qi, Qe, np.arctan2(A[1], A[0]), np.arctan2(B[1], B[0]), di, de)


def _initial_guess(g: BearingGeometry, F: np.ndarray) -> np.ndarray:
    """Inner race displacement from Stribeck's rules (Q_max = 5 Fr / (Z cos a), Q = Fa / (Z sin a)), the
    Newton start of :func:`static_equilibrium`."""
    from .hertz import series_stiffness
    Kn = series_stiffness(g.K_i, g.K_e)
    ca, sa = math.cos(g.alpha0), max(math.sin(g.alpha0), 0.05)
    Fr = math.hypot(F[0], F[1])
    X = np.zeros(3)
    if Fr > 0.0:
        d = (5.0 * Fr / (g.Z * ca * Kn)) ** (2.0 / 3.0) / ca
        X[0], X[1] = d * F[0] / Fr, d * F[1] / Fr
    if F[2] != 0.0:
        X[2] = math.copysign((abs(F[2]) / (g.Z * sa * Kn)) ** (2.0 / 3.0) / sa, F[2])
    return X


def static_equilibrium(g: BearingGeometry, F, Xe=(0.0, 0.0), eps=(0.0, 0.0, 0.0), Fc: float = 0.0,
                       X0=None, tol: float = 1e-9, max_iter: int = 200) -> tuple[np.ndarray, BallState]:
    """Inner race displacement X with F + sum T^T Q(X) = 0 (eq. 2 at rest) for the external load F (3, N) on
    the inner race. Newton with a finite-difference Jacobian and backtracking."""
    F = np.asarray(F, dtype=float)
    if F.shape != (3,) or not np.all(np.isfinite(F)):
        raise ValueError(f"external load must be 3 finite numbers (Fx, Fy, Fz) in N, got {F}")
    X = _initial_guess(g, F) if X0 is None else np.array(X0, dtype=float)
    if X0 is None:
        X[:2] += np.asarray(Xe, dtype=float)
    st = ball_state(g, X, Xe, eps, Fc)
    G = F + st.race_force()
    scale = max(float(np.max(np.abs(F))), g.K_i * (1e-6) ** 1.5)
    for _ in range(max_iter):
        if np.max(np.abs(G)) < tol * scale:
            return X, st
        J = stiffness(g, X, Xe, eps, Fc, st)
        J[np.diag_indices(3)] -= 1e-3 * scale / 1e-6 * 1e-6      # tiny regularisation (unloaded directions)
        dX = np.linalg.solve(J, -G)
        lam = 1.0
        for _ in range(40):
            Xn = X + lam * dX
            stn = ball_state(g, Xn, Xe, eps, Fc, v0=st.v)
            Gn = F + stn.race_force()
            if np.max(np.abs(Gn)) < np.max(np.abs(G)):
                break
            lam *= 0.5
        X, st, G = Xn, stn, Gn
    raise RuntimeError(f"static equilibrium did not converge (residual {np.max(np.abs(G)):.3e} N against a load of "
                       f"{scale:.3g} N)")


def stiffness(g: BearingGeometry, X, Xe=(0.0, 0.0), eps=(0.0, 0.0, 0.0), Fc: float = 0.0,
              st: BallState | None = None, step: float = 1e-9) -> np.ndarray:
    """d(sum T^T Q)/dX (3x3, N/m) with the balls re-equilibrated (quasi-static), central differences."""
    X = np.asarray(X, dtype=float)
    v0 = None if st is None else st.v
    J = np.empty((3, 3))
    for k in range(3):
        e = np.zeros(3)
        e[k] = step
        fp = ball_state(g, X + e, Xe, eps, Fc, v0=v0).race_force()
        fm = ball_state(g, X - e, Xe, eps, Fc, v0=v0).race_force()
        J[:, k] = (fp - fm) / (2.0 * step)
    return J


#: preload_offset's solutions in this process, by (geometry, centrifugal force): every bearing set-up solves the
#: same equilibrium (~0.05 s of CPU each, 2 per run: a tenth of a staggered Table 6 run's fixed cost, measured)
_PRELOAD: dict = {}


def preload_offset(g: BearingGeometry, Fc: float = 0.0) -> tuple[float, BallState]:
    """Axial inner race displacement z0 at which the balls (outer race centred, no radial load) carry the axial
    preload, and the ball state there (a copy: the caller may change it)."""
    key = (g, float(Fc))
    if key not in _PRELOAD:
        _PRELOAD[key] = _preload_offset(g, Fc)
    z0, st = _PRELOAD[key]
    return z0, copy.deepcopy(st)


def _preload_offset(g: BearingGeometry, Fc: float) -> tuple[float, BallState]:
    if g.preload == 0.0:
        X, st = np.zeros(3), ball_state(g, np.zeros(3), Fc=Fc)
        return 0.0, st
    X, st = static_equilibrium(g, np.array([0.0, 0.0, g.preload]), Fc=Fc)
    return float(X[2]), st


def axisymmetric_preload_offset(g: BearingGeometry, Fc: float, z_guess: float) -> float:
    """z0 of :func:`preload_offset` from one ball: with no radial load every ball sits alike, and the inner race
    carries the preload when Z Q_i sin(alpha_i) = P (eq. 2 axially), Q_i of the one ball in equilibrium (eq. 4,
    :func:`solve_balls`). A secant iteration from ``z_guess`` (a neighbouring speed's z0), bracketed (brentq) when
    it does not converge. For the speed table of z0 (:func:`preload_offset_table`): about a third of
    preload_offset's cost; the two agree to ~1e-10 (tests/components/test_bearing_spinning.py)."""
    from scipy.optimize import brentq

    if g.preload == 0.0:
        return 0.0
    seat = [None]

    def excess(z):
        v, (A, _, Li, _, _, _, Qi, _) = solve_balls(g, 0.0, z, 0.0, Fc=Fc, v0=seat[0])
        seat[0] = v
        return g.Z * float(Qi[0] * A[1, 0] / Li[0]) - g.preload

    z0, z1 = z_guess, z_guess * (1.0 + 1e-3)
    f0, f1 = excess(z0), excess(z1)
    for _ in range(30):
        if f1 == f0:
            break
        z0, z1, f0 = z1, z1 - f1 * (z1 - z0) / (f1 - f0), f1
        f1 = excess(z1)
        if abs(z1 - z0) <= 1e-13 * abs(z1):
            return float(z1)
    # bracketed: the axial force the balls carry grows with the offset. At a moderate speed no offset carries
    # nothing of the preload (the balls sit in their clearance) and the rest state's offset doubled carries more
    # than it; at a high speed z0 falls below zero: the balls' centrifugal force, thrown onto the outer race's
    # inclined contact, presses them on the inner race axially with no offset at all (bearing 5 above ~33 000
    # rev/min), so the bracket widens downwards until it holds
    seat[0] = None
    step = abs(preload_offset(g, 0.0)[0])
    lo, hi = 0.0, 2.0 * step
    f_lo, f_hi = excess(lo), excess(hi)
    for _ in range(60):
        if f_lo <= 0.0 <= f_hi:
            break
        if f_lo > 0.0:
            lo, f_lo = lo - step, excess(lo - step)
        if f_hi < 0.0:
            hi, f_hi = hi + step, excess(hi + step)
        step *= 2.0
    else:
        raise PreloadSolveError(f"no axial offset of the inner race carries the preload {g.preload:g} N at a ball "
                                f"centrifugal force of {Fc:.4g} N (searched {lo:.3g} to {hi:.3g} m)")
    seat[0] = None           # brentq's own first evaluations start cold, as they always have (same bits)
    return float(brentq(excess, lo, hi, xtol=1e-18, rtol=1e-14))


#: preload_offset_table's tables in this process, by (geometry, top speed, intervals)
_TABLES: dict = {}


def preload_offset_table(g: BearingGeometry, omega_max: float, intervals: int) -> tuple[np.ndarray, np.ndarray]:
    """The preload offset z0 (:func:`axisymmetric_preload_offset`) at ``intervals + 1`` equally spaced inner race
    speeds from 0 to ``omega_max`` [rad/s]: (speeds, z0)."""
    key = (g, float(omega_max), int(intervals))
    if key not in _TABLES:
        w = np.linspace(0.0, float(omega_max), int(intervals) + 1)
        z = np.empty_like(w)
        guess = preload_offset(g, 0.0)[0]
        for k, wk in enumerate(w):
            try:
                z[k] = guess = axisymmetric_preload_offset(g, g.centrifugal_force(wk), guess)
            except (ValueError, RuntimeError) as exc:
                raise PreloadSolveError(f"the preload offset at {wk * 30.0 / math.pi:.0f} rev/min: {exc}") from None
        _TABLES[key] = (w, z)
    w, z = _TABLES[key]
    return w.copy(), z.copy()


#: preload_offset_spline's splines in this process, by (geometry, top speed, tolerance)
_SPLINES: dict = {}


def preload_offset_spline(g: BearingGeometry, omega_max: float, tol: float = 1e-6,
                          intervals: int = 48, max_intervals: int = 768) -> tuple[np.ndarray, float, float]:
    """A cubic spline of the preload offset z0 against the inner race speed over [0, omega_max] on equally spaced
    knots (:func:`preload_offset_table`; zero slope at rest: z0 is even in the speed), with as many intervals
    (``intervals``, doubled as needed) as make its largest relative error at the intervals' midpoints, against
    :func:`axisymmetric_preload_offset` there, at most ``tol``: (coefficients (4, n): interval k is
    c[0] d^3 + c[1] d^2 + c[2] d + c[3] at d = omega - k h, the knot spacing h, that error).
    ValueError when ``max_intervals`` are not enough."""
    from scipy.interpolate import CubicSpline

    key = (g, float(omega_max), float(tol))
    if key in _SPLINES:
        c, h, err = _SPLINES[key]
        return c.copy(), h, err
    n = int(intervals)
    while True:
        w, z = preload_offset_table(g, omega_max, n)
        s = CubicSpline(w, z, bc_type=((1, 0.0), "not-a-knot"))
        mid = 0.5 * (w[1:] + w[:-1])
        direct = np.array([axisymmetric_preload_offset(g, g.centrifugal_force(m), zk) for m, zk in zip(mid, z)])
        err = float(np.max(np.abs(s(mid) - direct) / np.maximum(np.abs(direct), 1e-300)))
        if err <= tol:
            break
        n *= 2
        if n > max_intervals:
            raise ValueError(f"the preload offset against speed needs more than {max_intervals} spline intervals "
                             f"over 0-{omega_max * 30.0 / math.pi:.0f} rev/min for a relative error of {tol:g} "
                             f"({err:.2g} with {n // 2})")
    _SPLINES[key] = (np.ascontiguousarray(s.c), float(w[1] - w[0]), err)
    return np.ascontiguousarray(s.c).copy(), float(w[1] - w[0]), err
