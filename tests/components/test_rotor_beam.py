"""Shaft element checks against textbook beam and rotor results (independent closed forms)."""
import math

import numpy as np
import pytest
import scipy.linalg as sla

from rotorcosim.components.rotor.beam import disk, section, shaft_element, shear_coefficient

E, NU, RHO = 2.08e11, 0.3, 7800.0
G = E / (2 * (1 + NU))
XZ = [0, 4]          # (ux, ry) of a node: the x-z bending plane


def planar_beam(L, d, n_el, shear=True, rotary=True, rho=RHO):
    """Assemble the x-z bending DOFs (ux, ry per node) of a uniform solid shaft of n_el elements."""
    n = 2 * (n_el + 1)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    le = L / n_el
    ke, me, _ = shaft_element(le, E, G, rho, d, 0.0, shear=shear, rotary=rotary)
    idx = [0, 4, 6, 10]
    ke, me = ke[np.ix_(idx, idx)], me[np.ix_(idx, idx)]
    for e in range(n_el):
        sl = slice(2 * e, 2 * e + 4)
        K[sl, sl] += ke
        M[sl, sl] += me
    return K, M


def test_euler_bernoulli_free_free_first_four():
    """Uniform free-free beam, Euler-Bernoulli limit of the element (no shear, no rotary inertia): first 4 bending
    frequencies vs the textbook beta L = 4.7300, 7.8532, 10.9956, 14.1372 (Blevins, Formulas for Natural
    Frequency and Mode Shape, table 8-1), omega = (beta L)^2 sqrt(E I / (rho A L^4)); within 0.5 %."""
    L, d = 1.0, 0.02
    K, M = planar_beam(L, d, 30, shear=False, rotary=False)
    w = np.sqrt(np.abs(sla.eigh(K, M, eigvals_only=True)))
    A, I, _ = section(d, 0.0)
    bl = np.array([4.730040745, 7.853204624, 10.99560784, 14.13716549])
    exact = bl ** 2 * math.sqrt(E * I / (RHO * A * L ** 4))
    fe = np.sort(w)[2:6]                       # two rigid-body modes first
    assert np.all(np.sort(w)[:2] < 1e-3 * exact[0])
    np.testing.assert_allclose(fe, exact, rtol=5e-3)


def test_euler_bernoulli_simply_supported_first_four():
    """Simply supported uniform beam (EB limit): omega_n = (n pi / L)^2 sqrt(E I / rho A) (any vibration
    textbook, e.g. Rao, Mechanical Vibrations, 8.5); first 4 within 0.5 %."""
    L, d, n_el = 1.2, 0.03, 24
    K, M = planar_beam(L, d, n_el, shear=False, rotary=False)
    free = [i for i in range(K.shape[0]) if i not in (0, 2 * n_el)]   # ux = 0 at both ends
    w = np.sqrt(sla.eigh(K[np.ix_(free, free)], M[np.ix_(free, free)], eigvals_only=True))[:4]
    A, I, _ = section(d, 0.0)
    exact = (np.arange(1, 5) * math.pi / L) ** 2 * math.sqrt(E * I / (RHO * A))
    np.testing.assert_allclose(w, exact, rtol=5e-3)


def test_timoshenko_simply_supported_stocky_beam():
    """Stocky simply supported beam (L/d = 4), full Timoshenko element (shear + rotary inertia): first 4 vs the
    exact Timoshenko solution v = V sin(kx), psi = Psi cos(kx), k = n pi / L, whose frequency equation is
    (kGA k^2 - rho A w^2)(E I k^2 + kGA - rho I w^2) - (kGA k)^2 = 0 (Timoshenko 1921; Han, Benaroya & Wei,
    J. Sound Vib. 225, 1999), lower root; within 0.5 %. The Euler-Bernoulli values are > 10 % off here."""
    L, d, n_el = 0.2, 0.05, 40
    K, M = planar_beam(L, d, n_el)
    free = [i for i in range(K.shape[0]) if i not in (0, 2 * n_el)]
    w = np.sqrt(sla.eigh(K[np.ix_(free, free)], M[np.ix_(free, free)], eigvals_only=True))[:4]
    A, I, _ = section(d, 0.0)
    kap = shear_coefficient(NU, 0.0)
    kga = kap * G * A
    exact, eb = [], []
    for n in range(1, 5):
        k = n * math.pi / L
        a = RHO * A * RHO * I
        b = -(RHO * A * (E * I * k * k + kga) + RHO * I * kga * k * k)
        c = kga * k * k * (E * I * k * k + kga) - (kga * k) ** 2
        exact.append(math.sqrt((-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)))
        eb.append(k * k * math.sqrt(E * I / (RHO * A)))
    np.testing.assert_allclose(w, exact, rtol=5e-3)
    assert abs(w[3] / eb[3] - 1) > 0.1


def test_timoshenko_slender_free_free_tends_to_euler_bernoulli():
    """Full Timoshenko element on a slender free-free beam (L/d = 100): within 0.5 % of the EB textbook values
    (shear and rotary corrections ~ (beta r_g / L)^2 are below 0.1 % here)."""
    L, d = 1.0, 0.01
    K, M = planar_beam(L, d, 30)
    w = np.sort(np.sqrt(np.abs(sla.eigh(K, M, eigvals_only=True))))[2:6]
    A, I, _ = section(d, 0.0)
    bl = np.array([4.730040745, 7.853204624, 10.99560784, 14.13716549])
    np.testing.assert_allclose(w, bl ** 2 * math.sqrt(E * I / (RHO * A * L ** 4)), rtol=5e-3)


def _whirl(M, G_, K, spin, lat_x, lat_y):
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, spin * G_)]])
    lam, V = np.linalg.eig(A)
    fw, bw = [], []
    for l, v in zip(lam, V.T):
        if l.imag <= 1e-6:
            continue
        X, Y = v[lat_x], v[lat_y]
        (fw if abs(X + 1j * Y) > abs(X - 1j * Y) else bw).append(l.imag)
    return np.sort(fw), np.sort(bw)


@pytest.mark.parametrize("spin_rpm", [0.0, 10000.0, 30000.0])
def test_overhung_disk_forward_backward_whirl(spin_rpm):
    """Spinning overhung disk on a massless cantilever shaft (Euler-Bernoulli), the classic gyroscopic rotor:
    with the tip stiffness k = inv([[L^3/3EI, L^2/2EI], [L^2/2EI, L/EI]]) the whirl frequencies solve
    det([[k_tt - m w^2, k_tr], [k_tr, k_rr - Id w^2 +- Ip Omega w]]) = 0, + forward, - backward
    (Genta, Dynamics of Rotating Systems, sec. 4.6; Friswell et al., Dynamics of Rotating Machines, 3.6).
    The FE model (shaft elements of negligible density + disk) must match both pairs within 0.1 %, forward
    stiffening and backward softening with speed."""
    L, d = 0.4, 0.03
    m, Ip, Id = 10.0, 0.2, 0.1
    n_el = 4
    ndof = 6 * (n_el + 1)
    K, M, Gy = np.zeros((ndof, ndof)), np.zeros((ndof, ndof)), np.zeros((ndof, ndof))
    for e in range(n_el):
        ke, me, ge = shaft_element(L / n_el, E, G, RHO * 1e-9, d, 0.0, shear=False, rotary=False)
        sl = slice(6 * e, 6 * e + 12)
        K[sl, sl] += ke
        M[sl, sl] += me
        Gy[sl, sl] += ge
    md, gd = disk(m, Ip, Id)
    M[-6:, -6:] += md
    Gy[-6:, -6:] += gd
    keep = [0, 1, 3, 4]                                     # tip lateral DOFs only (ux, uy, rx, ry)
    free = [6 * n_el + k for k in keep] + [i for i in range(6, 6 * n_el)]
    K, M, Gy = K[np.ix_(free, free)], M[np.ix_(free, free)], Gy[np.ix_(free, free)]
    # condense the massless interior exactly (static condensation) to keep only the disk's 4 DOFs
    t, r = np.arange(4), np.arange(4, K.shape[0])
    Kc = K[np.ix_(t, t)] - K[np.ix_(t, r)] @ np.linalg.solve(K[np.ix_(r, r)], K[np.ix_(r, t)])
    Mc, Gc = M[np.ix_(t, t)], Gy[np.ix_(t, t)]
    Om = spin_rpm * 2 * math.pi / 60
    fw, bw = _whirl(Mc, Gc, Kc, Om, 0, 1)
    A, I, _ = section(d, 0.0)
    kk = np.linalg.inv(np.array([[L ** 3 / 3, L ** 2 / 2], [L ** 2 / 2, L]]) / (E * I))
    ktt, ktr, krr = kk[0, 0], kk[0, 1], kk[1, 1]
    exact = {}
    for sgn, name in ((1, "fw"), (-1, "bw")):
        # (ktt - m w^2)(krr - Id w^2 + sgn Ip Om w) - ktr^2 = 0, quartic in w
        poly = np.polymul([-m, 0, ktt], [-Id, sgn * Ip * Om, krr])
        poly = np.polysub(poly, [ktr ** 2])
        roots = np.roots(poly)
        exact[name] = np.sort(roots[(abs(roots.imag) < 1e-6) & (roots.real > 0)].real)
    if spin_rpm == 0:
        # no spin: x and y modes coincide (the whirl direction of a degenerate pair is arbitrary)
        np.testing.assert_allclose(np.sort(np.r_[fw, bw]), np.sort(np.r_[exact["fw"], exact["bw"]]), rtol=1e-3)
        return
    np.testing.assert_allclose(fw, exact["fw"], rtol=1e-3)
    np.testing.assert_allclose(bw, exact["bw"], rtol=1e-3)
    assert fw[1] > bw[1]
