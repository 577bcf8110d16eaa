"""The heat paths added to the paper's Table 1 network (data/thermal.toml), each against a hand calculation:
oil-wetted convection races/balls <-> lubricant (Harris), oil-jet renewal of the lubricant and its heat mass,
the oil-wetted housing (bearing chamber), and the Blok partition of the rub heat."""
import math

import numpy as np
import pytest

from rotorcosim.components.thermal.component import PT_OMEGA, ThermalNetwork
from rotorcosim.components.thermal.geometry import (BALL, HOUSING, IR, LE, LI, OR, SFD, SHAFT, heat_masses,
                                                    oil_convection, oil_viscosity, resistances, rub_partition)

TA = 303.15


def make(bearing=0, **params):
    # every watt of rub into the network (the ring's share into the housing node), so that the energy checks see
    # all the input power; the shipped default keeps the ring's share out (test_ring_share_leaves_the_network)
    params.setdefault("rub_ring_housing_fraction", 1.0)
    c = ThermalNetwork(f"thermal{bearing}", {"bearing": bearing, **params})
    c.setup(0.0)
    return c


def test_film_viscosity_agrees_with_the_physics_notes():
    """The Walther fit at the 70 C film temperature against physics-notes' independent value for SAE 30
    (~26 cP at 70 C, both the Walther and the Vogel fits) over the Incropera density 884.1 - 0.590 (343.15 - 300)
    = 858.6 kg/m^3: 30.3 cSt; within 3 %."""
    assert oil_viscosity(343.15) == pytest.approx(0.026 / 858.6, rel=0.03)


def test_harris_film_coefficients_by_hand():
    """Bearing 0 at 16 000 rev/min, film at 70 C. By hand: nu = 30.87 cSt (Walther), Pr = nu rho cp / k =
    30.87e-6 * 870 * 2000 / 0.14 = 383.6; gamma = 8.73 cos 15 / 70.4 = 0.11978;
    h_i = 0.0986 sqrt(16000 / 30.87e-6 * 1.11978) * 0.14 * 383.6^(1/3) = 2417 W/(m^2 K), h_e (1 - gamma) = 2142;
    A_i = 2 pi 30.835e-3 * 0.02 - pi 21 (4.365e-3)^2 = 2.618e-3 m^2, A_e = 3.715e-3 m^2, balls 21 * 4 pi r_b^2 =
    5.028e-3 m^2. The assembled conductance inner race - inner lubricant is the Table 1 layer 2/R_Li = 0.1679 W/K
    plus h_i A_i = 6.326 W/K: 6.494 W/K; ball - each lubricant node (h_i + h_e)/2 * A_b/2 = 5.731 W/K plus its
    layer half."""
    h = oil_convection(0, PT_OMEGA)
    assert h["nu"] == pytest.approx(30.867e-6, rel=1e-4)
    assert h["Pr"] == pytest.approx(383.6, rel=1e-3)
    assert h["h_i"] == pytest.approx(2416.5, rel=1e-4)
    assert h["h_e"] == pytest.approx(2142.5, rel=1e-4)
    assert h["A_i"] == pytest.approx(2.6178e-3, rel=1e-4)
    assert h["A_e"] == pytest.approx(3.7149e-3, rel=1e-4)
    assert h["A_b"] == pytest.approx(5.0280e-3, rel=1e-4)
    K = make(0).network.K
    assert -K[IR, LI] == pytest.approx(6.49396, rel=1e-5)
    R = resistances(0, PT_OMEGA)
    assert -K[BALL, LI] == pytest.approx(2.0 / R["R_Li"] + 5.73070, rel=1e-5)
    assert -K[BALL, LE] == pytest.approx(2.0 / R["R_Le"] + 5.73070, rel=1e-5)
    assert -K[LE, OR] == pytest.approx(2.0 / R["R_Le"] + 2142.49 * 3.71488e-3, rel=1e-5)
    # within the range physics-notes gives for oil-wetted surfaces (hundreds to thousands W/(m^2 K))
    assert 300.0 < h["h_e"] < h["h_i"] < 5000.0


JET = {0: 2e-3 / 60.0, 5: 3e-3 / 60.0}      # the jet option's flows (2 and 3 L/min), m^3/s


def test_jet_renewal_and_lubricant_heat_mass_by_hand():
    """Jet (an option; the default is none, the paper's Table 1 network) 2 L/min at #0, 3 L/min at #5:
    rho cp Q / 2 per lubricant node = 870 * 2000 * 2e-3/60 / 2 = 29.0 W/K and 43.5 W/K, to the oil supply.
    Lubricant heat mass (#0): 5 % of the free volume between the raceways,
    pi (39.565^2 - 30.835^2) 20 - 21 (4/3) pi 4.365^3 = 31 300 mm^3, half per node:
    0.05 * 0.5 * 31.2996e-6 * 870 * 2000 = 1.3615 J/K."""
    for bearing in (0, 5):
        net = make(bearing).network
        assert net.ground[LI] == net.ground[LE] == 0.0      # default: no renewal of the bearing's oil
    for bearing, g in ((0, 29.0), (5, 43.5)):
        net = make(bearing, T_supply=323.15, bearing_oil_flow=JET[bearing]).network
        assert net.ground[LI] == pytest.approx(g, rel=1e-12)
        assert net.ground[LE] == pytest.approx(g, rel=1e-12)
        assert net.T_ground[LI] == net.T_ground[LE] == 323.15
    assert heat_masses(0)[LI] == pytest.approx(1.3615, rel=1e-4)
    # an explicit flow overrides the data file
    assert make(0, bearing_oil_flow=1e-4).network.ground[LI] == pytest.approx(870 * 2000 * 1e-4 / 2, rel=1e-12)


def test_lubricant_node_balance_at_the_steady_state_by_hand():
    """At the steady state under drag only (#0, 350 W), the inner lubricant node is a well-mixed control volume:
    what the inner race and the balls give it (hand conductances 6.494 W/K and 2/R_Li + 5.731 W/K) leaves with the
    jet, 29.0 W/K * (T_Li - T_supply)."""
    c = make(0, bearing_oil_flow=JET[0])
    c.set_inputs({"P_drag": [350.0], "P_sfd": [0.0], "P_rub": [0.0]})
    T = c.network.steady(c.powers())
    R = resistances(0, PT_OMEGA)
    q_in = 6.49396 * (T[IR] - T[LI]) + (2.0 / R["R_Li"] + 5.73070) * (T[BALL] - T[LI])
    assert q_in == pytest.approx(29.0 * (T[LI] - TA), rel=1e-4)
    assert q_in > 0.2 * 350.0       # the jet is a main way out of the bearing heat


def test_housing_chamber_cooling_by_hand():
    """Table 1's R_h with the oil-wetted chamber wall h_h = 1000 W/(m^2 K) (#0: r_hi = 80.635 mm, r_h = 95.635 mm,
    L_h = 64 mm, k = 40): R_hr = ln(r_h/r_hi)/(2 pi k L_h) + 1/(h 2 pi r_h L_h) = 0.036610 K/W,
    R_ha = L_h/(2 pi k (r_h^2 - r_hi^2)) + 1/(pi h (r_h^2 - r_hi^2)) = 0.21670 K/W, R_h = 0.031318 K/W, to the
    oil supply."""
    R = resistances(0, PT_OMEGA)
    assert R["R_hr"] == pytest.approx(0.0366096, rel=1e-5)
    assert R["R_ha"] == pytest.approx(0.216697, rel=1e-5)
    net = make(0, T_supply=323.15).network
    assert net.ground[HOUSING] == pytest.approx(1.0 / 0.0313185, rel=1e-5)
    assert net.T_ground[HOUSING] == 323.15 and net.T_ground[SFD] == 323.15 and net.T_ground[SHAFT] == TA


def test_rub_partition_by_hand():
    """Blok partition at #0: a = 3 mm, V = 1675.52 rad/s * 25.4 mm = 42.558 m/s, k = 40, kappa = 40/(7800 * 460)
    = 1.11483e-5 m^2/s: R_1 = 8 a / (3 pi k) = 6.3662e-5, R_2 = (4/3) sqrt(2 kappa a / (pi V)) / k = 7.4558e-7,
    f = R_2/(R_1 + R_2) = 0.011576 into the rotor. The fast-moving limit holds: Peclet V a/(2 kappa) = 5726.
    The rub column of the source map is then [f at the shaft, 1 - f at the housing]; an explicit fraction
    overrides it."""
    f = rub_partition(0, PT_OMEGA)
    assert f == pytest.approx(0.011576, rel=1e-4)
    assert 42.558 * 3e-3 / (2 * 1.11483e-5) > 1000.0
    S = make(0).network.S
    assert S[SHAFT, 2] == pytest.approx(f, rel=1e-12)
    assert S[HOUSING, 2] == pytest.approx(1.0 - f, rel=1e-12)
    assert S[:, 2].sum() == pytest.approx(1.0, rel=1e-12)
    assert make(0, rub_shaft_fraction=1.0).network.S[SHAFT, 2] == 1.0
    # #5 (R_r = 41.9 mm, V = 70.2 m/s): R_1/R_2 = 1/f - 1 scales as V^(1/2)
    assert rub_partition(5, PT_OMEGA) == pytest.approx(
        1 / (1 + (1 / f - 1) * math.sqrt(41.9 / 25.4)), rel=1e-9)


def test_the_largest_rub_stays_bounded_and_conserves_energy():
    """128.69 kW of rub (Table 5, 14 252 N) plus its drag and film powers for 120 s at #0 (0.1 s steps): the
    heat stored plus the heat that left equals the heat put in (energy of the linear solve, 1e-6), every node stays
    below its adiabatic bound (all the heat in that one node) and the network has a finite steady state (it cannot
    run away: K is positive definite)."""
    c = make(0)
    P = np.array([424.1, 2806.4, 128690.0])
    c.set_inputs({"P_drag": [P[0]], "P_sfd": [P[1]], "P_rub": [P[2]]})
    net = c.network
    n, h = 1200, 0.1
    e_out = 0.0
    q_prev = net.heat_out(c.state["T"])
    for i in range(n):
        c.do_step(i * h, h)
        q = net.heat_out(c.state["T"])
        e_out += 0.5 * (q + q_prev) * h
        q_prev = q
    T = c.state["T"]                       # every node, the journal's inner shells included
    stored = net.stored(T, np.full(net.n, TA))
    assert stored + e_out == pytest.approx(P.sum() * 120.0, rel=2e-3)
    assert np.all(T - TA <= P.sum() * 120.0 / net.C)
    assert np.all(np.linalg.eigvalsh(0.5 * (net.K + net.K.T)) > 0.0)


def test_ring_share_leaves_the_network():
    """Shipped default (data/thermal.toml [rub] ring_housing_fraction = 0): only the rotor's Blok share of the rub
    power enters the network (the ring and the casing are not nodes of Fig. 5); the drag and film columns still
    put every watt in. With the fraction 1 the ring's share enters the housing node."""
    c = ThermalNetwork("thermal0", {"bearing": 0})
    c.setup(0.0)
    f = rub_partition(0, PT_OMEGA)
    np.testing.assert_allclose(c.network.S.sum(axis=0), [1.0, 1.0, f], rtol=1e-12)
    half = make(0, rub_ring_housing_fraction=0.5)
    assert half.network.S[HOUSING, 2] == pytest.approx(0.5 * (1 - f), rel=1e-12)


def _sleeve_by_hand(bearing):
    """m c_p of the whole journal sleeve r_o..r_j over L_j, J/K (#5: pi (0.1^2 - 0.055^2) 0.04 * 7800 * 460)."""
    r_o, r_j, L = {0: (45e-3, 80e-3, 32e-3), 5: (55e-3, 100e-3, 40e-3)}[bearing]
    return math.pi * (r_j ** 2 - r_o ** 2) * L * 7800.0 * 460.0


@pytest.mark.parametrize("bearing", [0, 5])
def test_journal_shells_keep_the_papers_steady_state_and_heat_mass(bearing, monkeypatch):
    """The journal sleeve in N radial shells (data/thermal.toml [lumping]) only moves heat mass: the shells'
    resistances sum to Table 1's R_e + R_j, so the steady state of the nine named nodes is the single-node
    network's (the paper's Fig. 5) to round-off, and the shells' heat masses sum to the whole sleeve's (#5:
    3145.5 J/K by hand), each shell node holding a positive share."""
    from rotorcosim.components.thermal import geometry as geo
    P = np.array([625.0, 30.0, 500.0])
    steady, masses = {}, {}
    for N in (1, 8):
        monkeypatch.setitem(geo.THERMAL_DATA["lumping"], "journal_shells", N)
        c = make(bearing)
        assert c.network.n == 9 + N - 1
        steady[N] = c.network.steady(P)[:9]
        masses[N] = c.network.C[geo.shell_nodes()]
        assert np.all(masses[N] > 0.0)
        assert masses[N].sum() == pytest.approx(_sleeve_by_hand(bearing), rel=1e-12)
        totals = masses.setdefault("total", [])
        totals.append(c.network.C.sum())
    assert totals[1] == pytest.approx(totals[0], rel=1e-12)       # the network's whole heat mass is unchanged
    np.testing.assert_allclose(steady[8], steady[1], rtol=1e-10)
    if bearing == 5:
        assert _sleeve_by_hand(5) == pytest.approx(3144.9, abs=0.1)


def test_journal_shells_converge_over_the_two_minute_run(monkeypatch):
    """Convergence study of the sleeve's lumping: #5 at the paper's below-rub powers (624.6 W drag, 0.95 W film)
    held for 120 s (one exact step): the inner race with the shipped N = 8 is within 0.5 K of N = 32, while the
    single node (N = 1, the paper's Fig. 5 lumping with the whole sleeve at r_j) is more than 20 K hotter: the
    sleeve's own conduction time (45 mm)^2 / kappa = 180 s is that of the run, so one node does not represent it."""
    from rotorcosim.components.thermal import geometry as geo
    shipped = geo.journal_shells()
    assert shipped == 8
    T = {}
    for N in (1, 8, 32):
        monkeypatch.setitem(geo.THERMAL_DATA["lumping"], "journal_shells", N)
        c = make(5)
        c.set_inputs({"P_drag": [624.6], "P_sfd": [0.95], "P_rub": [0.0]})
        c.do_step(0.0, 120.0)
        T[N] = c.y["T_inner_race"][0]
    assert abs(T[8] - T[32]) < 0.5
    assert T[1] - T[32] > 20.0


def test_journal_shells_must_be_a_small_positive_integer(monkeypatch):
    from rotorcosim.components.contract import ContractError
    from rotorcosim.components.thermal import geometry as geo
    for bad in (0, 2.5, True, 65):
        monkeypatch.setitem(geo.THERMAL_DATA["lumping"], "journal_shells", bad)
        with pytest.raises((ValueError, ContractError), match="journal_shells"):
            make(5)
