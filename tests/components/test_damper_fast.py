"""The fast film model (damper.fast) against the direct FE model (damper.fe), and both models' interface
Jacobians (K_film, C_film) against finite differences of their own forces."""
import math

import numpy as np
import pytest

from rotorcosim.components.damper.component import FastDamper, FEDamper
from rotorcosim.components.damper.fast import film_table

C = 0.635e-3
T_OIL = 343.15

EPS_GRID = [0.0, 0.13, 0.37, 0.5, 0.71, 0.85, 0.93, 0.95]
# (radial, tangential) velocity of the journal in m/s: pure squeeze, whirl-like, mixed; 2 m/s makes the
# clipped region large even with the 0.2 MPa supply
VELOCITIES = [(0.3, 0.0), (0.0, 0.3), (-0.2, 0.25), (0.0, 2.0), (1.5, -1.0)]


def _pair(damper, cav, ps):
    params = {"damper": damper, "cavitation": cav, "supply_pressure": ps}
    fe, fast = FEDamper("fe", params), FastDamper("fast", params)
    fe.setup(0.0)
    fast.setup(0.0)
    return fe, fast


def _eval(d, x, v, T=T_OIL):
    d.set_inputs({"X_journal": x, "V_journal": v, "T_oil": [T]})
    d.do_step(0.0, 1e-5)
    return {k: d.y[k].copy() for k in ("F_film", "F_journal", "K_film", "C_film", "P_film")}


@pytest.mark.parametrize("damper,cav,ps", [(0, True, 0.2e6), (0, False, 0.2e6), (5, True, 0.0)])
def test_fast_agrees_with_fe_within_1_percent(damper, cav, ps):
    """Over eccentricity ratios 0 to 0.95 (off the table's nodes too), at a position angle that is not a mesh
    angle, and for radial, tangential and mixed velocities, the fast model's film force is within 1 % of the
    direct FE solve (|F_fast - F_fe| / |F_fe|). The required bound; the measured worst case is printed."""
    fe, fast = _pair(damper, cav, ps)
    worst = 0.0
    ang = 0.7
    for eps in EPS_GRID:
        x = eps * C * np.array([math.cos(ang), math.sin(ang)])
        for vr, vt in VELOCITIES:
            v = np.array([vr * math.cos(ang) - vt * math.sin(ang), vr * math.sin(ang) + vt * math.cos(ang)])
            a, b = _eval(fe, x, v)["F_film"], _eval(fast, x, v)["F_film"]
            worst = max(worst, np.linalg.norm(a - b) / np.linalg.norm(a))
    print(f"damper {damper} cavitation {cav} p_s {ps:g}: worst relative force difference {worst:.2e}")
    assert worst < 0.01


def _finite_difference(d, x, v):
    """Central differences of F_journal in X_journal and V_journal (steps 1e-8 c and 1e-8 |v|).

    Small steps on purpose: with Guembel clipping the discrete force is only piecewise smooth (a node's
    pressure crossing the floor changes the slope), and near the centre the eccentricity frame turns fast
    (d phi = dx / e), so steps of 1e-6 c already straddle such kinks at eps ~ 0.005."""
    hx, hv = 1e-8 * C, 1e-8 * max(np.linalg.norm(v), 1e-3)
    K, Cm = np.zeros((2, 2)), np.zeros((2, 2))
    for m in range(2):
        for sgn in (1.0, -1.0):
            dx = np.zeros(2)
            dx[m] = sgn * hx
            K[:, m] += sgn * _eval(d, x + dx, v)["F_journal"] / (2 * hx)
            dv = np.zeros(2)
            dv[m] = sgn * hv
            Cm[:, m] += sgn * _eval(d, x, v + dv)["F_journal"] / (2 * hv)
    return K, Cm


STATES = [  # (position / c, velocity m/s)
    ((0.3, 0.4), (0.1, -0.2)),
    ((0.55, -0.72), (-0.3, 1.5)),     # eps 0.906, strongly clipped film
    ((0.004, 0.002), (0.2, 0.1)),     # near the centre (the g_phi / e limit)
    ((-0.98, 0.1), (0.5, 0.5)),       # eps 0.985, near the table's end
    ((1.003, 0.0), (0.0, 0.2)),       # in wall contact (film saturated at eps_max)
]


@pytest.mark.parametrize("cav", [False, True])
@pytest.mark.parametrize("pos,vel", STATES)
def test_fast_jacobian_matches_finite_differences(pos, vel, cav):
    """K_film = dF_journal/dX_journal (film + spring + wall) and C_film = dF_journal/dV_journal are the exact
    derivatives of the fast model's force: compared with central finite differences of the force itself.
    The states lie off the table's nodes: there the 4-point Lagrange interpolant is only continuous (its slope
    in eps jumps by ~1e-4 relative, e.g. at eps = 0.9), and a difference quotient across a node is neither
    one-sided derivative."""
    d = FastDamper("fast", {"damper": 0, "cavitation": cav, "supply_pressure": 0.0 if cav else 0.2e6})
    d.setup(0.0)
    x, v = C * np.array(pos), np.array(vel)
    y = _eval(d, x, v)
    K, Cm = _finite_difference(d, x, v)
    assert np.allclose(y["K_film"].reshape(2, 2), K, rtol=0, atol=1e-5 * np.abs(K).max())
    assert np.allclose(y["C_film"].reshape(2, 2), Cm, rtol=0, atol=1e-6 * np.abs(Cm).max())


def test_fe_jacobian_matches_finite_differences():
    """The FE model's K_film, C_film (discrete sensitivity dP/deps = -K^-1 dK/deps P, exact for the FE
    solution) against central finite differences of the FE force, with a clipped film."""
    d = FEDamper("fe", {"damper": 5, "cavitation": True, "supply_pressure": 0.0, "k_spring": 0.0})
    d.setup(0.0)
    x, v = C * np.array([0.5, -0.3]), np.array([0.3, 0.4])
    y = _eval(d, x, v)
    K, Cm = _finite_difference(d, x, v)
    assert np.allclose(y["K_film"].reshape(2, 2), K, rtol=0, atol=1e-5 * np.abs(K).max())
    assert np.allclose(y["C_film"].reshape(2, 2), Cm, rtol=0, atol=1e-6 * np.abs(Cm).max())


def test_full_film_is_linear_in_velocity_and_viscosity():
    """Without cavitation the Reynolds pressure is linear in the squeeze velocity and in mu: F = C_film w
    exactly, and halving the viscosity halves the force (structure the fast model rests on)."""
    d = FastDamper("fast", {"damper": 0, "cavitation": False})
    d.setup(0.0)
    x, v = C * np.array([0.6, 0.2]), np.array([0.7, -0.4])
    y = _eval(d, x, v)
    assert np.allclose(y["C_film"].reshape(2, 2) @ v, y["F_film"], rtol=1e-12)
    mu1 = d.viscosity(T_OIL)
    T2 = 366.0
    y2 = _eval(d, x, v, T=T2)
    assert np.allclose(y2["F_film"], y["F_film"] * d.viscosity(T2) / mu1, rtol=1e-12)


def test_table_interpolation_converges():
    """The fast model's only approximation is the interpolation in eps: doubling the table size must shrink
    the difference to the direct FE force by about 2^4 (4-point Lagrange, smooth fields in u = -ln(1 - eps))."""
    from rotorcosim.components.damper.reynolds_fe import build_mesh, fe_film_force
    mesh = build_mesh(0.08, 0.032, 64, 16)  # a coarse mesh keeps the table builds short; same structure
    errs = []
    for n in (12, 24):
        tab = film_table(0.08, 0.032, C, 64, 16, n_table=n)
        worst = 0.0
        for eps in (0.21, 0.47, 0.66, 0.83, 0.91):
            x, v = (eps * C, 0.0), (0.2, 0.3)
            out = np.empty(10)
            tab.evaluate(x[0], x[1], v[0], v[1], 0.03, -1e30, False, out)
            ref = np.array(fe_film_force(mesh, C, *x, *v, 0.03, 0.0, -1e30, False))
            worst = max(worst, np.linalg.norm(out[:2] - ref) / np.linalg.norm(ref))
        errs.append(worst)
    ratio = errs[0] / errs[1]
    print(f"table 12 -> 24 points: worst errors {errs}, ratio {ratio:.1f}")
    assert ratio > 8.0


def test_disk_cache_is_bit_for_bit(tmp_path, monkeypatch):
    """A table read from the on-disk cache is identical to a freshly built one (same numbers with or
    without the cache), and ROTORCOSIM_CACHE=off builds without writing."""
    from rotorcosim.components.damper.fast import FilmTable
    monkeypatch.setenv("ROTORCOSIM_CACHE", str(tmp_path))
    built = FilmTable(0.08, 0.032, C, 32, 8, n_table=10)
    assert len(list((tmp_path / "damper").glob("table_*.npz"))) == 1
    read = FilmTable(0.08, 0.032, C, 32, 8, n_table=10)
    for name in ("NT", "G", "TW", "ftab", "bounds"):
        assert np.array_equal(getattr(built, name), getattr(read, name))
    monkeypatch.setenv("ROTORCOSIM_CACHE", "off")
    off = FilmTable(0.08, 0.032, C, 32, 8, n_table=10)
    assert np.array_equal(off.NT, built.NT)


@pytest.mark.parametrize("tile", [(8, 4), (3, 5), (65, 128), (1, 1)])
def test_tiled_clipped_force_is_the_nodal_sum(tile, monkeypatch):
    """The clipped force sums its full-film and cavitated tiles from per-tile sums and bounds (fast._clipped):
    it must equal the plain sum over every node of the interpolated field (written here with numpy in the mesh's
    own node order, as reynolds_fe.aligned_force sums an FE field) to round-off, for any tile shape, over
    eccentricities, velocities and floors that put the rupture boundary anywhere (or nowhere) in the film."""
    from rotorcosim.components.damper import fast
    from rotorcosim.components.damper.reynolds_fe import unit_fields
    monkeypatch.setattr(fast, "TILE_Z", tile[0])
    monkeypatch.setattr(fast, "TILE_THETA", tile[1])
    monkeypatch.setenv("ROTORCOSIM_CACHE", "off")
    tab = fast.FilmTable(0.08, 0.032, C, 32, 12, n_table=12)
    TR = np.array([unit_fields(tab.mesh, C, float(e))[0] for e in tab.eps])
    TT = np.array([unit_fields(tab.mesh, C, float(e))[1] for e in tab.eps])
    Wc, Ws = tab.mesh.Wc, tab.mesh.Ws
    rng = np.random.default_rng(3)
    worst = 0.0
    for _ in range(300):
        eps = rng.uniform(0.0, 0.98)
        a, b = rng.normal(0.0, 1.0, 2) * 0.03 * rng.choice([0.01, 0.3, 2.0])
        floor = rng.choice([-2e5, -2e4, 0.0, 1e4])
        got = np.array(fast._clipped(tab.NT, tab.G, tab.TW, tab.toff, tab.bounds, tab.Wc, tab.Ws, eps, tab.u0,
                                     tab.du, tab.n, a, b, floor))
        u = -math.log1p(-eps)
        k, *w = fast._lagrange4(u, tab.u0, tab.du, tab.n)
        wv, dv = np.array(w[:4]), np.array(w[4:]) / (1.0 - eps)
        pr, pt = wv @ TR[k:k + 4], wv @ TT[k:k + 4]
        dpr, dpt = dv @ TR[k:k + 4], dv @ TT[k:k + 4]
        p = a * pr + b * pt
        m = p >= floor
        q = np.where(m, p, floor)
        dp = (a * dpr + b * dpt) * m
        want = -2.0 * np.array([Wc @ q, Ws @ q, Wc @ (m * pr), Wc @ (m * pt), Ws @ (m * pr), Ws @ (m * pt),
                                Wc @ dp, Ws @ dp])
        # scale: the same sums without clipping or cancellation (what round-off is relative to)
        scale = 2.0 * np.array([np.abs(Wc) @ np.abs(q), np.abs(Ws) @ np.abs(q)] + [np.abs(W) @ np.abs(f) for W, f in
                               ((Wc, pr), (Wc, pt), (Ws, pr), (Ws, pt), (Wc, dp), (Ws, dp))])
        worst = max(worst, float(np.max(np.abs(got - want) / np.maximum(scale, 1e-300))))
    print(f"tile {tile}: worst difference / scale {worst:.2e}")
    assert worst < 1e-12
