"""Timoshenko shaft element with 6 DOF per node, and the rigid disk.

Node DOF order: (ux, uy, uz, rx, ry, rz); z is the shaft axis, spin is about +z.

Bending uses the planar Timoshenko element of Przemieniecki / Nelson (1980) ("A finite rotating shaft element
using Timoshenko beam theory", J. Mech. Des. 102): stiffness with the shear factor phi = 12 E I / (kappa G A L^2),
consistent translational and rotary inertia. In the x-z plane the planar DOFs are (ux, ry) (ry = dux/dz); in the
y-z plane they are (uy, -rx) (rx = -duy/dz). The gyroscopic matrix per unit spin speed follows from the spinning
cross-section's angular momentum Ip * Omega * n with n = (ry, -rx, 1): for a disk it gives
Id rx'' + Omega Ip ry' = Mx, Id ry'' - Omega Ip rx' = My, and for the shaft the distributed version, which is
twice the rotary inertia matrix of one plane (Ip = 2 I) coupling the two planes (Nelson 1980).
Axial (bar) and torsional stiffness and consistent mass complete the 12 x 12 element.
"""
from __future__ import annotations

import math

import numpy as np

# planar DOF positions inside the 12 x 12 element: x-z plane (ux, ry), y-z plane (uy, rx with sign -1)
_XZ = np.array([0, 4, 6, 10])
_YZ = np.array([1, 3, 7, 9])
_YZ_SIGN = np.array([1.0, -1.0, 1.0, -1.0])
_AX = np.array([2, 8])
_TO = np.array([5, 11])


def shear_coefficient(nu: float, ri_over_ro: float) -> float:
    """Cowper's (1966) shear coefficient kappa of a hollow circular section (m = ri/ro; m = 0: solid)."""
    m2 = ri_over_ro ** 2
    return 6.0 * (1.0 + nu) * (1.0 + m2) ** 2 / ((7.0 + 6.0 * nu) * (1.0 + m2) ** 2 + (20.0 + 12.0 * nu) * m2)


def section(d_out: float, d_in: float) -> tuple[float, float, float]:
    """Area, diametral second moment I, polar moment J = 2 I of a tube."""
    if not (d_out > 0.0 and 0.0 <= d_in < d_out):
        raise ValueError(f"shaft section: need 0 <= d_in < d_out and d_out > 0, got d_out={d_out}, d_in={d_in}")
    A = math.pi * (d_out ** 2 - d_in ** 2) / 4.0
    I = math.pi * (d_out ** 4 - d_in ** 4) / 64.0
    return A, I, 2.0 * I


def planar_matrices(L, E, G, rho, A, I, kappa, shear=True, rotary=True):
    """Planar Timoshenko stiffness, translational + rotary mass, and rotary matrix R (4 x 4, DOFs v1 t1 v2 t2).

    Przemieniecki (1968) / Nelson (1980) forms; with shear=False, phi = 0 (Euler-Bernoulli)."""
    phi = 12.0 * E * I / (kappa * G * A * L * L) if shear else 0.0
    f = 1.0 + phi
    k = E * I / (f * L ** 3) * np.array([
        [12.0, 6 * L, -12.0, 6 * L],
        [6 * L, (4 + phi) * L * L, -6 * L, (2 - phi) * L * L],
        [-12.0, -6 * L, 12.0, -6 * L],
        [6 * L, (2 - phi) * L * L, -6 * L, (4 + phi) * L * L]])
    p2 = phi * phi
    m1 = 13 / 35 + 7 * phi / 10 + p2 / 3
    m2 = (11 / 210 + 11 * phi / 120 + p2 / 24) * L
    m3 = 9 / 70 + 3 * phi / 10 + p2 / 6
    m4 = (13 / 420 + 3 * phi / 40 + p2 / 24) * L
    m5 = (1 / 105 + phi / 60 + p2 / 120) * L * L
    m6 = (1 / 140 + phi / 60 + p2 / 120) * L * L
    mt = rho * A * L / f ** 2 * np.array([
        [m1, m2, m3, -m4],
        [m2, m5, m4, -m6],
        [m3, m4, m1, -m2],
        [-m4, -m6, -m2, m5]])
    r1 = 6 / 5
    r2 = (1 / 10 - phi / 2) * L
    r3 = (2 / 15 + phi / 6 + p2 / 3) * L * L
    r4 = (1 / 30 + phi / 6 - p2 / 6) * L * L
    R = rho * I / (f ** 2 * L) * np.array([
        [r1, r2, -r1, r2],
        [r2, r3, -r2, -r4],
        [-r1, -r2, r1, -r2],
        [r2, -r4, -r2, r3]])
    m = mt + (R if rotary else 0.0)
    return k, m, R


def shaft_element(L, E, G, rho, d_out, d_in, shear=True, rotary=True):
    """12 x 12 stiffness K, mass M and gyroscopic G (per rad/s of spin) of a tubular Timoshenko shaft element."""
    if not L > 0.0:
        raise ValueError(f"shaft element length must be > 0, got {L}")
    A, I, J = section(d_out, d_in)
    nu = E / (2.0 * G) - 1.0
    kappa = shear_coefficient(nu, d_in / d_out)
    kp, mp, R = planar_matrices(L, E, G, rho, A, I, kappa, shear, rotary)
    K = np.zeros((12, 12))
    M = np.zeros((12, 12))
    Gy = np.zeros((12, 12))
    K[np.ix_(_XZ, _XZ)] += kp
    M[np.ix_(_XZ, _XZ)] += mp
    S = np.diag(_YZ_SIGN)
    K[np.ix_(_YZ, _YZ)] += S @ kp @ S
    M[np.ix_(_YZ, _YZ)] += S @ mp @ S
    # gyroscopic: generalized force on the x-z plane from the y-z rates and vice versa (skew), 2 R = Ip-based
    Rs = 2.0 * R
    Gy[np.ix_(_XZ, _YZ)] += Rs @ S
    Gy[np.ix_(_YZ, _XZ)] -= S @ Rs
    bar = np.array([[1.0, -1.0], [-1.0, 1.0]])
    cm = np.array([[2.0, 1.0], [1.0, 2.0]]) / 6.0
    K[np.ix_(_AX, _AX)] += E * A / L * bar
    M[np.ix_(_AX, _AX)] += rho * A * L * cm
    K[np.ix_(_TO, _TO)] += G * J / L * bar
    M[np.ix_(_TO, _TO)] += rho * J * L * cm
    return K, M, Gy


def disk(mass: float, Ip: float, Id: float):
    """6 x 6 mass and gyroscopic (per rad/s) matrices of a rigid disk at a node (polar inertia about z)."""
    for name, v in (("mass", mass), ("Ip", Ip), ("Id", Id)):
        if not (math.isfinite(v) and v >= 0.0):
            raise ValueError(f"disk {name} must be finite and >= 0, got {v}")
    M = np.diag([mass, mass, mass, Id, Id, Ip])
    G = np.zeros((6, 6))
    G[3, 4] = Ip
    G[4, 3] = -Ip
    return M, G
