"""The 8-node solid of the casing and the assembled casing model: exact-solution checks."""
import numpy as np
import scipy.linalg as sla

from rotorcosim.components.rotor.component import full_model
from rotorcosim.components.rotor.hexa import hex8

E, NU, RHO = 2.0e11, 0.3, 7800.0


def _box(a, b, c, skew=0.0):
    x = np.array([[0, 0, 0], [a, 0, 0], [a, b, 0], [0, b, 0], [0, 0, c], [a, 0, c], [a, b, c], [0, b, c]], float)
    x[4:, 0] += skew
    return x


def test_hex_rigid_body_modes_and_mass():
    """A single (skewed) element has exactly 6 zero-energy modes (3 translations, 3 rotations) and its consistent
    mass sums to rho * volume in each direction (volume of a parallelepiped = a b c)."""
    xyz = _box(0.3, 0.2, 0.1, skew=0.05)
    K, M = hex8(xyz, E, NU, RHO)
    w = sla.eigh(K, M, eigvals_only=True)
    assert np.sum(np.abs(w) < 1e-6 * w.max()) == 6
    one = np.zeros(24)
    one[0::3] = 1.0
    assert abs(one @ M @ one / (RHO * 0.3 * 0.2 * 0.1) - 1) < 1e-12


def test_hex_patch_uniform_tension_exact():
    """Patch test: a bar of 4 elements pulled by nodal forces equivalent to a uniform stress sigma reproduces the
    exact uniform strain state (trilinear elements are exact for constant strain): axial elongation sigma L / E
    and lateral contraction -nu sigma b / E (Zienkiewicz & Taylor, vol. 1, ch. 10)."""
    L, b, c, n = 1.0, 0.1, 0.1, 4
    nodes = np.array([[i * L / n, j * b, k * c] for i in range(n + 1) for j in (0, 1) for k in (0, 1)])

    def idx(i, j, k):
        return 4 * i + 2 * j + k

    N = nodes.shape[0]
    K = np.zeros((3 * N, 3 * N))
    for i in range(n):
        conn = [idx(i, 0, 0), idx(i + 1, 0, 0), idx(i + 1, 1, 0), idx(i, 1, 0),
                idx(i, 0, 1), idx(i + 1, 0, 1), idx(i + 1, 1, 1), idx(i, 1, 1)]
        ke, _ = hex8(nodes[conn], E, NU, RHO)
        dofs = (3 * np.asarray(conn)[:, None] + np.arange(3)).ravel()
        K[np.ix_(dofs, dofs)] += ke
    sigma = 1e8
    f = np.zeros(3 * N)
    for j in (0, 1):
        for k in (0, 1):
            f[3 * idx(n, j, k)] = sigma * b * c / 4
    # supports: x = 0 face fixed in x; one node fixed in y, z; one more in z (no rigid rotation), free contraction
    fixed = [3 * idx(0, j, k) for j in (0, 1) for k in (0, 1)] + [3 * idx(0, 0, 0) + 1, 3 * idx(0, 0, 0) + 2,
                                                                  3 * idx(0, 1, 0) + 2]
    free = np.setdiff1d(np.arange(3 * N), fixed)
    u = np.zeros(3 * N)
    u[free] = np.linalg.solve(K[np.ix_(free, free)], f[free])
    np.testing.assert_allclose(u[3 * idx(n, 1, 1)], sigma * L / E, rtol=1e-9)
    np.testing.assert_allclose(u[3 * idx(n, 1, 1) + 1] - u[3 * idx(n, 0, 1) + 1], -NU * sigma * b / E, rtol=1e-9)


def test_assembled_model_is_symmetric_definite_and_mass_is_conserved():
    """The assembled engine: M, K symmetric, K positive definite without bearings #0/#5 (the PT is held by the
    intermediate bearings and the thrust restraint; the spin DOFs are prescribed), G skew; total translational
    mass equals the sum of the parts computed independently (shaft tubes rho A L, disks, casing shell
    rho A_ring L_c with the area of the polygonal ring the n_circ nodes span, hubs)."""
    m = full_model()
    assert np.allclose(m.M, m.M.T) and np.allclose(m.K, m.K.T, atol=1e-6 * np.abs(m.K).max())
    assert np.allclose(m.G_pt, -m.G_pt.T) and np.allclose(m.G_gg, -m.G_gg.T)
    np.linalg.cholesky(m.K)
    d = m.data
    total = 0.0
    for key in ("pt", "gg"):
        sp = d["spool"][key]
        z = np.asarray(sp["z_mm"], float) * 1e-3
        do = np.asarray(sp["d_out_mm"], float) * 1e-3
        di = np.asarray(sp["d_in_mm"], float) * 1e-3
        total += np.sum(d["material"]["rotor"]["rho"] * np.pi * (do ** 2 - di ** 2) / 4 * np.diff(z))
        for dk in sp["disks"]:
            mass = dk["mass"]
            total += d["calibration"][mass] if isinstance(mass, str) else mass
    cas = d["casing"]
    R, t, nc = cas["radius_mm"] * 1e-3, cas["thickness_mm"] * 1e-3, cas["n_circ"]
    ring_area = 0.5 * nc * np.sin(2 * np.pi / nc) * ((R + t / 2) ** 2 - (R - t / 2) ** 2)   # polygon ring
    Lc = (cas["ring_z_mm"][-1] - cas["ring_z_mm"][0]) * 1e-3
    total += d["material"]["casing"]["rho"] * ring_area * Lc
    total += sum(h["mass"] for h in cas["hubs"].values())
    ux = np.zeros(m.n)
    for body, nn in (("pt", 22), ("gg", 16)):
        for n in range(nn):
            ux[m.info["dof"](body, n, 0)] = 1.0
    nrot = 6 * 38 - 2                      # rotor DOFs (two spin DOFs prescribed); then 3-DOF casing nodes
    ux[nrot::3] = 1.0
    assert abs(ux @ m.M @ ux / total - 1) < 1e-9


def test_per_hub_bearing_frame():
    """A hub's own ``struts`` entry replaces the common frame for that hub only: equal values give the same K; a
    frame 10x softer at hub h0 changes K only in rows/columns of h0 and its ring's inner shell nodes, by -0.9 x
    the common strut stiffness (lateral frame stiffness 4 (k_r + k_t) at the hub, 8 k_a axially)."""
    import copy

    from rotorcosim.components.rotor import model

    data, _ = model.load_data()
    ref = model.build(data)
    same = copy.deepcopy(data)
    same["casing"]["hubs"]["h0"]["struts"] = dict(data["casing"]["struts"])
    assert np.array_equal(model.build(same).K, ref.K)
    soft = copy.deepcopy(data)
    st = data["casing"]["struts"]
    soft["casing"]["hubs"]["h0"]["struts"] = {k: 0.1 * v for k, v in st.items()}
    dK = model.build(soft).K - ref.K
    hub = [ref.info["dof"]("hub", "h0", d) for d in range(3)]
    assert np.allclose(np.diag(dK)[hub], [-0.9 * 4 * (st["k_r"] + st["k_t"])] * 2 + [-0.9 * 8 * st["k_a"]])
    others = [h for h in data["casing"]["hubs"] if h != "h0"]
    for h in others:
        i = [ref.info["dof"]("hub", h, d) for d in range(3)]
        assert not np.any(dK[i])
