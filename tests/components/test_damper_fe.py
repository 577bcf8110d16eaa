"""The direct FE squeeze-film model (damper.fe) against independent references: the short-damper analytic
solution, its own mesh refinement, the symmetry of a centred journal and the film's dissipation integral."""
import math

import numpy as np
import pytest

from rotorcosim.components.damper.component import FEDamper
from rotorcosim.components.damper.reynolds_fe import build_mesh, unit_fields

C = 0.635e-3          # Table 3 radial clearance
R = 0.08              # Table 3 journal radius, damper #0
T_OIL = 343.15        # 70 C


def _force(damper, x, v, T=T_OIL):
    damper.set_inputs({"X_journal": x, "V_journal": v, "T_oil": [T]})
    damper.do_step(0.0, 1e-5)
    return damper.y["F_film"].copy()


@pytest.fixture(scope="module")
def short_dampers():
    """Damper #0's radius and clearance with a 4 mm length (L/D = 0.025): the short-damper limit. Supply and
    cavitation pressures 0 so that Guembel clipping is the classical pi-film (half-Sommerfeld) condition."""
    out = {}
    for cav in (False, True):
        d = FEDamper("short", {"damper": 0, "length": 0.004, "cavitation": cav, "supply_pressure": 0.0,
                               "cavitation_pressure": 0.0})
        d.setup(0.0)
        out[cav] = d
    return out


@pytest.mark.parametrize("cav", [False, True])
def test_short_damper_centred_radial_squeeze(short_dampers, cav):
    """Centred journal, pure radial squeeze: short-damper theory (Reynolds without the circumferential flow
    term, p = p_s at both ends) gives F = -C v, C = pi mu R L^3 / c^3 (2 pi film) and half of it with the
    pi-film (physics-notes, "Squeeze film damper"; San Andres, SFD notes). Within 2 %."""
    d = short_dampers[cav]
    L = d.p["length"]
    mu = d.viscosity(T_OIL)
    v = 0.1
    Cexp = math.pi * mu * R * L**3 / C**3 * (0.5 if cav else 1.0)
    F = _force(d, [0.0, 0.0], [v, 0.0])
    assert F[0] == pytest.approx(-Cexp * v, rel=0.02)
    assert abs(F[1]) < 1e-6 * abs(F[0])


@pytest.mark.parametrize("eps", [0.3, 0.5, 0.7])
@pytest.mark.parametrize("cav", [False, True])
def test_short_damper_circular_centred_orbit(short_dampers, eps, cav):
    """Circular centred orbit (journal at eccentricity eps moving tangentially with v_t = e Omega), short damper:
    2 pi film F_r = 0, F_t = -pi mu R L^3 v_t / (c^3 (1 - eps^2)^1.5); pi film (half-Sommerfeld)
    F_r = -2 mu R L^3 eps v_t / (c^3 (1 - eps^2)^2), F_t = half the 2 pi value (integrals of the short-bearing
    pressure p = 6 mu v_t sin(theta) (L^2/4 - z^2) / h^3 over the full / positive half film). Within 2 %."""
    d = short_dampers[cav]
    L = d.p["length"]
    mu = d.viscosity(T_OIL)
    vt = 0.2
    Ft = -math.pi * mu * R * L**3 * vt / (C**3 * (1 - eps**2) ** 1.5) * (0.5 if cav else 1.0)
    F = _force(d, [eps * C, 0.0], [0.0, vt])
    assert F[1] == pytest.approx(Ft, rel=0.02)
    if cav:
        Fr = -2.0 * mu * R * L**3 * eps * vt / (C**3 * (1 - eps**2) ** 2)
        assert F[0] == pytest.approx(Fr, rel=0.02)
    else:
        assert abs(F[0]) < 0.02 * abs(Ft)


@pytest.mark.slow   # three meshes up to 256x128 cells: about a minute of CPU
@pytest.mark.parametrize("supply_pressure", [0.2e6, 0.0])
def test_mesh_convergence_second_order(supply_pressure):
    """Force of the Table 3 damper #0 (eps = 0.5, oblique velocity) on 64x32, 128x64 and 256x128 cells: the
    observed order log2(|F64 - F128| / |F128 - F256|) is that of linear elements for a smooth functional (2; with
    the clipped pi-film, p_s = 0, the clipping line is also refined). The paper's 128x64 mesh is then within
    0.3 % of the finest."""
    forces = []
    for nt, nz in ((64, 32), (128, 64), (256, 128)):
        d = FEDamper("conv", {"damper": 0, "n_theta": nt, "n_z": nz, "supply_pressure": supply_pressure})
        d.setup(0.0)
        forces.append(_force(d, [0.3 * C, 0.4 * C], [0.1, -0.2]))
    d1 = np.linalg.norm(forces[0] - forces[1])
    d2 = np.linalg.norm(forces[1] - forces[2])
    order = math.log2(d1 / d2)
    print(f"p_s = {supply_pressure:g} Pa: forces {forces}, observed order {order:.3f}")
    assert 1.8 < order < 2.5
    # Richardson: the 128x64 error is about d2 * 2^p / (2^p - 1) ~ 4/3 d2
    assert 4.0 / 3.0 * d2 < 0.003 * np.linalg.norm(forces[2])


@pytest.mark.parametrize("cav,ps", [(False, 0.2e6), (True, 0.0), (True, 0.2e6)])
def test_centred_journal_force_opposes_motion(cav, ps):
    """A centred journal (uniform film) is axisymmetric: whatever the direction of its velocity, the film force
    must be exactly opposite to it (also with the clipped film, whose clipped half turns with the velocity)."""
    d = FEDamper("centred", {"damper": 5, "cavitation": cav, "supply_pressure": ps})
    d.setup(0.0)
    for ang in np.linspace(0.0, 2.0 * math.pi, 9)[:-1] + 0.1:
        v = 0.2 * np.array([math.cos(ang), math.sin(ang)])
        F = _force(d, [0.0, 0.0], v)
        assert F @ v < 0.0
        assert abs(F[0] * v[1] - F[1] * v[0]) < 1e-9 * np.linalg.norm(F) * np.linalg.norm(v)


def test_power_loss_equals_dissipation_integral():
    """Full film: the power -F . w that the component reports (P_film) equals the viscous dissipation of the
    Poiseuille flow, int h^3 / (12 mu) |grad p|^2 dA over the whole film (both halves), computed here directly
    from the nodal pressure with the triangles' own gradients (Reynolds' energy identity)."""
    d = FEDamper("power", {"damper": 0, "cavitation": False})
    d.setup(0.0)
    mu = d.viscosity(T_OIL)
    x, w = np.array([0.25 * C, -0.35 * C]), np.array([0.15, 0.25])
    d.set_inputs({"X_journal": x, "V_journal": w, "T_oil": [T_OIL]})
    d.do_step(0.0, 1e-5)
    P = float(d.y["P_film"][0])
    assert P == pytest.approx(-float(d.y["F_film"] @ w), rel=1e-12)

    mesh = build_mesh(d.p["radius"], d.p["length"], 128, 64)
    e = float(np.hypot(*x))
    cph, sph = x / e
    vr, vt = cph * w[0] + sph * w[1], -sph * w[0] + cph * w[1]
    Pr, Pt = unit_fields(mesh, C, e / C)
    p = mu * (vr * Pr + vt * Pt)
    nth = mesh.n_theta
    node = np.arange(mesh.n_nodes)
    xs = mesh.radius * 2.0 * math.pi * (node % nth) / nth
    zs = mesh.half_length * (node // nth) / mesh.n_z
    h = C * (1.0 - (e / C) * np.cos(mesh.theta))
    diss = 0.0
    for tri in mesh.tri:
        X = xs[tri].copy()
        # unwrap the periodic seam: vertices across theta = 2 pi get x + 2 pi R
        X[X < X.max() - math.pi * mesh.radius] += 2.0 * math.pi * mesh.radius
        Z = zs[tri]
        A = np.array([[X[1] - X[0], Z[1] - Z[0]], [X[2] - X[0], Z[2] - Z[0]]])
        g = np.linalg.solve(A, [p[tri[1]] - p[tri[0]], p[tri[2]] - p[tri[0]]])
        area = 0.5 * abs(np.linalg.det(A))
        h3 = np.mean(h[tri] ** 3)
        diss += h3 / (12.0 * mu) * (g @ g) * area
    assert 2.0 * diss == pytest.approx(P, rel=1e-9)
    assert P > 0.0


def test_banded_and_sparse_solvers_agree():
    """reynolds_fe._band_solver (the band assembled from the element matrices, banded Cholesky): on the paper's
    128 x 64 mesh (band half-width 129 for 8 192 unknowns) it solves the Reynolds operator to the same solution as
    SuperLU within 1e-12 relative, near the centre and near the wall; a mesh with a wide band (many cells around,
    few along) gets no banded solver (unit_fields then takes spd_solver, SuperLU), and each solution satisfies
    K x = b."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import splu

    from rotorcosim.components.damper.reynolds_fe import _band_solver, _reduced_operator, spd_solver

    c = 1.5e-4
    for n_theta, n_z in ((128, 64), (1024, 4)):
        mesh = build_mesh(0.05, 0.02, n_theta, n_z)
        for eps in (0.1, 0.95):
            h = c * (1.0 - eps * np.cos(mesh.theta))
            K = _reduced_operator(mesh, c, (h**3)[mesh.tri].mean(axis=1) / 12.0)
            b = np.stack([mesh.Wc[mesh.free], mesh.Ws[mesh.free]], axis=1)
            ref = splu(sp.csc_matrix(K), permc_spec="MMD_AT_PLUS_A").solve(b)
            coeff = (h**3)[mesh.tri].mean(axis=1) / 12.0
            direct = _band_solver(mesh, coeff)   # the band assembled from the element matrices (unit_fields)
            assert (direct is None) == (n_theta == 1024)
            for solve in (spd_solver(K), direct):
                if solve is None:
                    continue
                x = solve(b)
                assert np.max(np.abs(x - ref)) <= 1e-12 * np.max(np.abs(ref))
                assert np.max(np.abs(K @ x - b)) <= 1e-9 * np.max(np.abs(b))
