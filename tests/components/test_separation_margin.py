"""The separation margin check-engine asks of each critical speed (components/rotor/engine_check.py): API 684's
margin as a function of the mode's amplification factor AF = 1 / (2 zeta), zeta the damping ratio of the mode in
the damped engine at its critical speed (components/rotor/critical.damping_ratios).

Checked against: the textbook Jeffcott rotor (zeta = c / (2 sqrt(k m)) = 0.02 by construction,
components/rotor/data/jeffcott.toml); the full eigenproblem of the damped engine (critical._damped_modes: all its
eigenvalues by scipy's dense eig, an independent solve of the shift-invert Arnoldi's); the formula's values
worked by hand (API 684 SP6.8.2.10 as ROSS's ross/report.py implements it)."""
from __future__ import annotations

from pathlib import Path

import pytest

from rotorcosim.components.rotor import critical, engine_check, shaft_model
from rotorcosim.components.rotor import model as fem

DATA = Path(__file__).resolve().parents[2] / "components" / "rotor" / "data"
THREE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "three_bearings" / "engine.toml"


def test_required_margin_worked_by_hand():
    req = engine_check.required_margin
    assert req(2.4, above=False) == 0.0 and req(2.4, above=True) == 0.0          # AF < 2.5: none
    assert req(3.5, above=False) == pytest.approx(0.085)          # 17 (1 - 1/2) %
    assert req(3.5, above=True) == pytest.approx(0.185)           # 10 + 17 (1 - 1/2) %
    assert req(100.0, above=False) == 0.16 and req(100.0, above=True) == 0.26      # the caps
    assert req(None, above=False) == req(None, above=True) == engine_check.SEPARATION_MARGIN == 0.15
    assert engine_check.amplification_factor(0.02) == pytest.approx(25.0)
    assert engine_check.amplification_factor(0.0) is None and engine_check.amplification_factor(None) is None


def test_jeffcott_rotor_damping_ratio_is_its_textbook_value():
    """m = 10 kg, k = 4.0e6 N/m, c = 252.98 N s/m: zeta = c / (2 sqrt(k m)) = 0.02000 (the shaft's 0.08 % of the
    disk's mass moves it by less than that)."""
    data, digest = fem.load_data(DATA / "jeffcott.toml")
    m = shaft_model.build(data, digest)
    rows = critical.damping_ratios(m, None, critical.every_synchronous_critical_speed(m, None, 8000.0))
    fwd = [r for r in rows if r["whirl"] == "forward"]
    assert fwd and fwd[0]["rpm"] == pytest.approx(6039.5, rel=1e-3)
    assert fwd[0]["damping_ratio"] == pytest.approx(252.98 / (2 * (4.0e6 * 10.0) ** 0.5), rel=2e-3)


def test_damping_ratios_equal_those_of_the_full_eigenproblem():
    """Every eigenpair of the engine's first-order form (scipy's dense eig of the whole coupled model, axial and
    torsional DOFs included) at each critical speed: of the rotor whirl modes of the critical's whirl, the one of
    |lambda| nearest the critical speed has the damping ratio the shift-invert search found."""
    import numpy as np
    import scipy.linalg as sla

    from rotorcosim.cases.blade_loss import linear_engine
    from rotorcosim.master.core.threads import one_thread

    with one_thread():          # as every entry point computes (small matrices: threads only cost)
        m = fem.load(THREE)
        sup = linear_engine.supports(data=m.data)
        rows = critical.damping_ratios(m, sup, critical.every_synchronous_critical_speed(m, sup, 14000.0))
        s = m.coupled(sup)
        n = s["K"].shape[0]
        assert len(rows) >= 4
        for r in rows:
            w = r["rpm"] * critical.RPM
            D = s["C"] + w * (s["G_pt"] + critical.speed_ratio(m) * s["G_gg"])
            A = np.block([[np.zeros((n, n)), np.eye(n)], [-s["K"], -D]])
            B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), s["M"]]])
            lam, vec = sla.eig(A, B)
            lat = s["rotor_lateral"]
            same = []
            for k in np.flatnonzero(np.isfinite(lam) & (lam.imag > 0)):
                v = vec[:n, k]
                X, Y = v[lat[0::2]], v[lat[1::2]]
                lateral = np.sum(abs(v[lat]) ** 2) / np.sum(abs(v) ** 2)
                forward = np.sum(abs(X + 1j * Y) ** 2) >= np.sum(abs(X - 1j * Y) ** 2)
                if lateral > 0.05 and forward == (r["whirl"] == "forward"):
                    same.append(lam[k])
            near = min(same, key=lambda x: abs(abs(x) - w))
            # the QZ of the whole model (its stiff axial and torsional DOFs too) agrees to ~2e-7 (measured)
            assert r["damping_ratio"] == pytest.approx(-near.real / abs(near), rel=1e-6)


def test_separation_warns_by_the_modes_amplification_factor():
    rows, warn = engine_check.separation(
        [{"rpm": 11000.0, "whirl": "forward", "damping_ratio": 0.25},     # AF 2: no margin asked
         {"rpm": 14400.0, "whirl": "forward", "damping_ratio": 0.1},      # AF 5, 10 % below: 12.1 % asked
         {"rpm": 17000.0, "whirl": "backward", "damping_ratio": 0.1},     # AF 5, 6.25 % above: 22.1 % asked
         {"rpm": 18000.0, "whirl": "forward"}],                           # undamped, 12.5 % above: 15 %
        "pt", "power turbine", [16000.0])
    assert rows[0]["amplification_factor"] == pytest.approx(2.0) and rows[3]["amplification_factor"] is None
    assert [r["margins"][0]["required_percent"] for r in rows] == pytest.approx(
        [0.0, 17 * (1 - 1 / 3.5), 10 + 17 * (1 - 1 / 3.5), 15.0])
    assert len(warn) == 3 and all("\n" not in w for w in warn)
    assert "14400 rev/min is 10.0 % below" in warn[0] and "12.1% of a mode of amplification factor 5.00" in warn[0]
    assert "17000 rev/min is 6.2 % above" in warn[1] and "22.1%" in warn[1]
    assert "18000 rev/min is 12.5 % above" in warn[2] and "undamped mode" in warn[2] and "15%" in warn[2]


def test_an_engine_that_dissipates_nothing_has_undamped_modes(tmp_path):
    """ROSS's rotor_example (its saved file: no damping in its shaft or its bearings) is a conservative gyroscopic
    system, whose eigenvalues are purely imaginary (Genta, Dynamics of Rotating Systems, 4.7): every critical
    speed's damping ratio is exactly 0 and has no amplification factor, so API 684's flat margin applies. The
    eigensolvers leave 1e-31-1e-27 of either sign in Re lambda, which read as damping gave amplification
    factors of 1e27-1e30."""
    from rotorcosim.interop import from_ross, write_engine

    path = tmp_path / "engine.toml"
    write_engine(from_ross(Path(__file__).resolve().parents[1] / "interop" / "data" / "rotor_example.toml"), path)
    m = fem.load(path)
    rows = critical.damping_ratios(m, None, critical.every_synchronous_critical_speed(m, None, 15000.0))
    assert len(rows) >= 6
    assert all(r["damping_ratio"] == 0.0 for r in rows), rows
    sep, _ = engine_check.separation(rows, "shaft", "shaft", [10000.0])
    assert all(r["amplification_factor"] is None for r in sep)
    assert {mg["required_percent"] for r in sep for mg in r["margins"]} == {100 * engine_check.SEPARATION_MARGIN}


def test_round_off_below_the_resolution_is_no_damping():
    """The resolution's two sides: a ratio of round-off size reads 0, the least damped mode of the shipped engines
    (1.8e-2, three_spools) and a lightly damped machine's 1e-4 are kept as they are."""
    m = fem.load(THREE)
    sysm = {"C": m.C + 1.0, "K": m.K}
    for zeta in (1e-4, 1.8e-2):
        lam = complex(-zeta * 100.0, 100.0 * (1 - zeta ** 2) ** 0.5)
        assert critical.damping_ratio(lam, sysm, m, 0.0) == pytest.approx(zeta)
    assert critical.damping_ratio(complex(3e-29, 100.0), sysm, m, 0.0) == 0.0
    assert critical.damping_ratio(complex(-1e-12, 100.0), {"C": 0.0 * m.C, "K": m.K}, m, 0.0) == 0.0
