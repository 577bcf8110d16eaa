"""The engine format (docs/reference/engine-format.md): a spool on ground supports against beam theory, the
problems of a file listed by name, pedestals, and the MTA basis of a spool held only by the co-simulated
bearings."""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest
import scipy.linalg as sla

from rotorcosim.components.rotor import engine_check, mta
from rotorcosim.components.rotor import model as fem

E, RHO, NU = 208e9, 7800.0, 0.3


def _beam(n_el=40, L_mm=2000.0, d_mm=40.0, k=1e14):
    """A slender solid shaft pinned at both ends (ground supports of stiffness k, x and y)."""
    return {"engine": {"format": 1}, "material": {"steel": {"E": E, "nu": NU, "rho": RHO}},
            "damping": {"zeta": 0.0, "f1_Hz": 1.0, "f2_Hz": 2.0},
            "spool": {"s": {"speed_rpm": 1000.0, "material": "steel",
                            "z_mm": list(np.linspace(0.0, L_mm, n_el + 1)), "d_out_mm": [d_mm] * n_el,
                            "d_in_mm": [0.0] * n_el, "drive_node": 0, "axial_node": 0}},
            "support": [{"name": "left", "a": ["s", 0], "b": "ground", "k": k},
                        {"name": "right", "a": ["s", n_el], "b": "ground", "k": k}]}


def test_pinned_shaft_first_bending_frequency_equals_euler_bernoulli():
    """Textbook: f1 = (pi / L)^2 sqrt(E I / (rho A)) / 2 pi for a pinned-pinned beam; with L / d = 50 shear and
    rotary inertia lower it by ~(1 + pi^2 (r_g / L)^2 (1 + E / kappa G)) / 2 ~ 0.03 %, well under the 0.2 %
    allowed here."""
    m = fem.build(_beam())
    w2 = sla.eigh(m.K, m.M, eigvals_only=True, subset_by_index=[0, 5])
    f = np.sqrt(np.abs(w2)) / (2 * math.pi)
    L, d = 2.0, 0.04
    f1 = (math.pi / L) ** 2 * math.sqrt(E * math.pi * d ** 4 / 64 / (RHO * math.pi * d ** 2 / 4)) / (2 * math.pi)
    lateral = f[f > 1.0]
    assert abs(lateral[0] / f1 - 1) < 2e-3, (lateral[:2], f1)
    assert abs(lateral[1] / f1 - 1) < 2e-3          # x and y: the same pair


def test_anisotropic_supports_and_pedestal():
    """kxx != kyy splits the rigid-body bounce pair: a rigid shaft (short, thick) of mass m on two springs per
    direction bounces at sqrt(2 k / m) in each; a (nearly) massless pedestal adds its spring in series."""
    d = _beam(n_el=4, L_mm=100.0, d_mm=100.0)
    for s in d["support"]:
        s.pop("k")
        s.update(kxx=1e6, kyy=4e6)
    m = fem.build(d)
    mass = RHO * math.pi * 0.1 ** 2 / 4 * 0.1
    w = np.sqrt(sla.eigh(m.K, m.M, eigvals_only=True, subset_by_index=[0, 3]))
    # (the shaft's own bending, ~10^4 times stiffer than the springs, lowers them by ~1e-5)
    assert w[0] == pytest.approx(math.sqrt(2e6 / mass), rel=1e-4)
    assert np.any(np.isclose(w, math.sqrt(8e6 / mass), rtol=1e-4))
    p = copy.deepcopy(d)
    p["pedestal"] = {"h": {"mass": 1e-6, "k": 1e6}}
    p["support"][0]["b"] = p["support"][1]["b"] = ["hub", "h"]
    # both ends on one 1e6 N/m pedestal: x bounce on (2e6 in series with 1e6) = 2/3 e6 N/m
    Kc = fem.build(p)
    w2 = sla.eigh(Kc.K, Kc.M, eigvals_only=True, subset_by_index=[0, 0])
    assert math.sqrt(w2[0]) == pytest.approx(math.sqrt(2e6 / 3 / mass), rel=1e-4)


def test_every_problem_of_a_file_is_named():
    """Every mistake of an engine file, all in one file: one line each."""
    d = _beam(n_el=4)
    sp = d["spool"]["s"]
    sp["z_mm"][2] = sp["z_mm"][1]                     # overlapping stations
    sp["d_out_mm"][0] = -40.0                          # negative dimension
    sp["d_in_mm"][1] = float("nan")                    # NaN dimension
    sp["disks"] = [{"node": 9, "name": "far", "mass": 1.0, "Ip": 0.0, "Id": 0.0}]   # node out of range
    d["support"][0]["a"] = ["s", 7]                    # support on a node that does not exist
    d["attach"] = {"bearing0": {"node": ["s", 12], "housing": "nowhere"}}   # bearing on no node, no hub
    found = engine_check.problems(d)
    text = "\n".join(found)
    for expected in ("spool.s.z_mm: stations overlap: node 2", "spool.s.d_out_mm[0]: must be a finite number > 0",
                     "spool.s.d_in_mm[1]: must be a finite number >= 0, got nan", "node 9 out of range 0-4",
                     "support[0] ('left').a: node 7 does not exist on spool 's'",
                     "attach.bearing0.node: node 12 does not exist", "attach.bearing0.housing: hub 'nowhere'"):
        assert expected in text, text
    assert len(found) == 7, found
    assert engine_check.problems(_beam()) == []
    assert engine_check.problems(fem.load_data()[0]) == []


def test_a_disk_key_that_would_not_be_read_is_named():
    """A disk's Ip and Id go with a mass in kg, r_gyration_mm with a mass named by [calibration]: a key of the
    other form was ignored (r_gyration_mm beside Ip, Id) or left a confusing 'r_gyration_mm: ... got None'."""
    d = _beam(n_el=4)
    d["calibration"] = {"m_disk": 2.0}
    d["spool"]["s"]["disks"] = [{"node": 1, "name": "a", "mass": 1.0, "Ip": 0.01, "Id": 0.005, "r_gyration_mm": 50.0},
                                {"node": 2, "name": "b", "mass": "m_disk", "Ip": 0.01, "Id": 0.005}]
    assert engine_check.problems(d) == [
        "spool.s.disks[0] ('a').r_gyration_mm: not read (it goes with a mass named by [calibration])",
        "spool.s.disks[1] ('b').r_gyration_mm: missing (a mass named by [calibration] takes Ip = m r_g^2, Id = Ip / 2)",
        "spool.s.disks[1] ('b').Ip: not read (a mass named by [calibration] takes them from r_gyration_mm)",
        "spool.s.disks[1] ('b').Id: not read (a mass named by [calibration] takes them from r_gyration_mm)"]


def test_a_problem_of_a_shared_k_is_listed_once():
    """k standing for kxx and kyy: its problem was listed twice ('support[0] ('left').k: must be ...' two lines)."""
    d = _beam(n_el=4)
    d["support"][0]["k"] = -1.0
    d["pedestal"] = {"h": {"mass": 1.0, "k": 0.0}}
    assert engine_check.problems(d) == ["pedestal.h.k: must be a finite number > 0, got 0.0",
                                        "support[0] ('left').k: must be a finite number > 0, got -1.0"]


def test_mta_basis_of_a_free_spool():
    """A spool held by nothing in K (its bearings are co-simulated) has rigid-body modes: the augmentation
    vectors come from the shifted K + sigma M and stay M-orthogonal to the retained modes (exactly, by
    construction); the static deflection under a load is still reproduced when a support is added back
    (the basis spans the load's response)."""
    d = _beam(n_el=10)
    d["support"] = []
    m = fem.build(d)
    load = [m.info["dof"]("s", 3, 0), m.info["dof"]("s", 8, 0)]
    basis, n_aug = mta.mta_basis(m.K, m.M, 6, load)
    assert n_aug == 2
    G = basis.T @ m.M @ basis
    assert np.allclose(G, np.eye(G.shape[0]), atol=1e-8)
    # with springs at the two load DOFs the reduced static response equals the full one
    Ks = m.K.copy()
    for i in load:
        Ks[i, i] += 1e7
    f = np.zeros(m.n)
    f[load[0]] = 1.0
    x_full = np.linalg.solve(Ks, f)
    x_red = basis @ np.linalg.solve(basis.T @ Ks @ basis, basis.T @ f)
    assert np.allclose(x_red[load], x_full[load], rtol=1e-6)
