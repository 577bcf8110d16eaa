"""Thermal network (paper section 2.3): integration against analytic solutions, energy balance, growths, errors."""
import json
import math

import numpy as np
import pytest

from rotorcosim.components.contract import ContractError
from rotorcosim.components.thermal.component import ThermalNetwork
from rotorcosim.components.thermal.geometry import NODES, radii, resistances
from rotorcosim.components.thermal.network import LinearNetwork
from rotorcosim.master.cli import main

TA = 303.15


def make(bearing=0, **params):
    # every watt of rub into the network (the ring's share into the housing node), so that the energy checks see
    # all the input power; the shipped default keeps the ring's share out (test_ring_share_leaves_the_network)
    params.setdefault("rub_ring_housing_fraction", 1.0)
    c = ThermalNetwork(f"thermal{bearing}", {"bearing": bearing, **params})
    c.setup(0.0)
    return c


def powers(c, drag, sfd, rub):
    c.set_inputs({"P_drag": [drag], "P_sfd": [sfd], "P_rub": [rub]})


@pytest.mark.parametrize("bearing", [0, 5])
@pytest.mark.parametrize("method", ["exact", "backward-euler"])
def test_integration_reaches_the_analytic_steady_state(bearing, method):
    """Integrated for 30 slowest time constants (1 s steps), the temperature rises equal the linear solve
    K T = b + S u within 0.1 % (the analytic steady state of eq. 12 at every node)."""
    c = make(bearing, method=method)
    P = (400.0, 600.0, 1000.0)
    powers(c, *P)
    tau = 1.0 / np.min(np.linalg.eigvals(c.network.K / c.network.C[:, None]).real)
    n = int(30 * tau) + 1
    for i in range(n):
        c.do_step(float(i), 1.0)
    T_ss = np.linalg.solve(c.network.K, c.network.b + c.network.S @ np.array(P))
    rise = c.state["T"] - TA                 # every node: the nine named ones and the journal's inner shells
    assert np.array_equal(c.y["T_nodes"], c.state["T"][:9])
    assert np.max(np.abs(rise - (T_ss - TA)) / (T_ss - TA)) < 1e-3
    # and at the steady state all the heat put in leaves through the grounds (ambient, oil supply)
    assert c.network.heat_out(T_ss) == pytest.approx(sum(P), rel=1e-9)


def test_energy_balance_over_a_transient():
    """Heat in = heat out + heat stored over a 60 s transient with power steps (5 ms steps): heat in is the sum
    of P h, heat out the trapezoidal integral of the ground flows sum g (T - T_ground) of the recorded temperatures
    (ambient air at the shaft; the oil supply at the jet-renewed lubricant nodes, the damper feed and the
    oil-wetted housing), stored the sum of m c_p dT; within 0.1 % of the heat in. The jet oil (advection from the
    lubricant nodes; the jet option, 2 L/min) carries a real share of it."""
    c = make(0, bearing_oil_flow=2e-3 / 60.0)
    net = c.network
    h, n = 0.005, 12000
    e_in = e_out = e_jet = 0.0
    T0 = c.state["T"].copy()                 # every node, the journal's inner shells included
    jet = np.zeros(net.n)
    jet[[2, 4]] = net.ground[[2, 4]]

    def q_jet(T):
        return float(jet @ (T - net.T_ground))

    q_prev, j_prev = net.heat_out(T0), q_jet(T0)
    for i in range(n):
        t = i * h
        drag = 350.0 if t < 20.0 else 500.0
        sfd = 600.0 if t < 40.0 else 50.0
        rub = 2000.0 if 10.0 <= t < 30.0 else 0.0
        powers(c, drag, sfd, rub)
        c.do_step(t, h)
        e_in += (drag + sfd + rub) * h
        T = c.state["T"]
        q, j = net.heat_out(T), q_jet(T)
        e_out += 0.5 * (q + q_prev) * h
        e_jet += 0.5 * (j + j_prev) * h
        q_prev, j_prev = q, j
    stored = net.stored(c.state["T"], T0)
    assert stored > 0.25 * e_in         # a genuine transient: a large share of the heat is still stored
    assert e_jet > 0.05 * e_in          # the jet renewal is one of the ways out
    assert abs(e_in - e_out - stored) / e_in < 1e-3


@pytest.mark.parametrize("method, tol", [("exact", 1e-12), ("backward-euler", 2e-3)])
def test_single_node_against_the_analytic_exponential(method, tol):
    """One node C dT/dt = P - g (T - Ta): T(t) = Ta + P/g (1 - exp(-g t / C)). The exact scheme matches to
    round-off at any step; backward Euler with h = tau/1000 within its O(h/tau) error."""
    C, g, P = 50.0, 2.0, 100.0
    net = LinearNetwork(C=[C], K=[[g]], b=[g * TA], S=[[1.0]], ground=[g], T_ground=[TA])
    tau = C / g
    h = tau / 1000.0 if method == "backward-euler" else tau / 7.0
    T = np.array([TA])
    t = 0.0
    worst = 0.0
    for _ in range(int(5 * tau / h)):
        T = net.step(T, np.array([P]), h, method)
        t += h
        exact = TA + P / g * (1.0 - math.exp(-t / tau))
        worst = max(worst, abs(T[0] - exact) / (P / g))
    assert worst < tol


def test_backward_euler_converges_at_first_order_to_the_exact_solution():
    """Convergence study: the backward-Euler error at t = 60 s (against the exact held-input solution) halves
    when the step halves (observed order 1 within 10 %)."""
    errs = []
    for h in (2.0, 1.0, 0.5):
        ce, cb = make(0), make(0, method="backward-euler")
        for c in (ce, cb):
            powers(c, 400.0, 600.0, 0.0)
            for i in range(int(round(60.0 / h))):
                c.do_step(i * h, h)
        errs.append(np.max(np.abs(cb.y["T_nodes"] - ce.y["T_nodes"])))
    orders = [math.log2(errs[i] / errs[i + 1]) for i in range(2)]
    assert all(abs(p - 1.0) < 0.1 for p in orders), orders


def test_step_size_independence_of_the_exact_scheme():
    """For a held power, 100 steps of 1 ms and one step of 0.1 s give the same temperatures (the property the
    staggered TM/TO schedule relies on), to 1e-9 K."""
    a, b = make(5), make(5)
    for c in (a, b):
        powers(c, 625.0, 1.0, 0.0)
    for i in range(100):
        a.do_step(i * 1e-3, 1e-3)
    b.do_step(0.0, 0.1)
    assert np.max(np.abs(a.state["T"] - b.state["T"])) < 1e-9


def test_uniform_temperature_growths_by_hand():
    """Eqs. (13)-(15) for a uniform 100 K rise of every node, by hand from Table 3 (bearing 0: r_b = 4.365 mm,
    d_m = 70.4 mm, r_i = 30.835 mm, r_e = 39.565 mm, r_j = 80 mm; xi = 12e-6 /K, nu = 0.3):
    eps_b = xi r_b dT = 5.238 um; eps_i = (2/3)(1 + nu) xi r_i dT = 32.07 um;
    eps_e = xi (1 + nu) r_e dT 3 (r_e + r_j) / (3 r_e + r_j) = 37.21 um; all positive (expansion)."""
    c = make(0)
    eps = c.growths_at(np.full(9, TA + 100.0))
    assert eps[2] == pytest.approx(12e-6 * 4.365e-3 * 100, rel=1e-9)
    assert eps[0] == pytest.approx(2 / 3 * 1.3 * 12e-6 * 30.835e-3 * 100, rel=1e-9)
    r_e, r_j = 39.565e-3, 80e-3
    assert eps[1] == pytest.approx(12e-6 * 1.3 * r_e * 100 * 3 * (r_e + r_j) / (3 * r_e + r_j), rel=1e-9)
    assert np.all(c.growths_at(np.full(9, TA)) == 0.0)


def test_film_halves_add_up_to_the_whole_film():
    """R_sf1 + R_sf2 (film split at mid-thickness) equals the conduction resistance of the whole annular film,
    ln(r_hi/r_j) / (2 pi k L_j), with k = 0.14 W/(m K) (engine oil, Incropera Table A.5)."""
    for bearing in (0, 5):
        g, R = radii(bearing), resistances(bearing, 1675.5)
        whole = math.log(g["r_hi"] / g["r_j"]) / (2 * math.pi * 0.14 * g["L_j"])
        assert R["R_sf1"] + R["R_sf2"] == pytest.approx(whole, rel=1e-12)


def test_every_input_watt_enters_the_network():
    """Each power input is distributed over the nodes with fractions summing to 1 (no heat created or lost at
    the sources), for any admissible split."""
    for params in ({}, {"drag_inner_fraction": 0.7, "contact_race_fraction": 0.2, "rub_shaft_fraction": 0.4}):
        assert np.allclose(make(0, **params).network.S.sum(axis=0), 1.0)


def test_state_roundtrip_for_rollback():
    c = make(0)
    powers(c, 350.0, 600.0, 0.0)
    c.do_step(0.0, 1.0)
    snap = c.get_state()
    c.do_step(1.0, 1.0)
    after = c.y["T_nodes"].copy()
    c.set_state(snap)
    c.do_step(1.0, 1.0)
    assert np.array_equal(c.y["T_nodes"], after)


@pytest.mark.parametrize("params, message", [
    ({"bearing": 3}, "bearing must be one of"),
    ({"method": "euler"}, "method must be one of"),
    ({"T_ambient": -1.0}, "T_ambient must be > 0"),
    ({"rub_shaft_fraction": 1.5}, "rub_shaft_fraction must be within"),
    ({"sfd_oil_flow": -1e-5}, "sfd_oil_flow must be finite and >= 0"),
    # oil temperatures in degrees C where kelvin are meant (ran as "diverged", or silently for the supply)
    ({"T_supply": 30.0}, r"T_supply: oil temperature 30 K is outside the viscosity fit's range \(200 K, 600 K\]"),
    ({"T_initial": 5000.0}, "T_initial: oil temperature 5000 K is outside"),
])
def test_bad_parameters(params, message):
    with pytest.raises(ContractError, match=message):
        make(**{"bearing": 0, **params})


@pytest.mark.parametrize("inputs, message", [
    ((float("nan"), 0.0, 0.0), "non-finite power"),
    ((0.0, -5.0, 0.0), "negative heat source P_sfd"),
])
def test_bad_power_inputs(inputs, message):
    c = make(0)
    powers(c, *inputs)
    with pytest.raises(ContractError, match=message):
        c.do_step(0.0, 1e-3)


def test_cli_json(capsys):
    assert main(["thermal-steady", "--bearing", "5", "--drag-power", "625", "--sfd-power", "1", "--rub-power", "0",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out["temperatures_C"]) == set(NODES)
    assert set(out["growths_m"]) == {"inner", "outer", "ball"}
    # every node above ambient when heated, growths positive
    assert min(out["temperatures_C"].values()) > 30.0 and min(out["growths_m"].values()) > 0.0


def test_cli_rejects_negative_power(capsys):
    assert main(["thermal-steady", "--bearing", "0", "--drag-power", "-1", "--sfd-power", "0"]) == 2
    assert "drag power must be >= 0" in capsys.readouterr().err


@pytest.mark.parametrize("args, message", [
    # the ambient is the oil supply: an oil temperature of the viscosity fit (components/oil_fit.py)
    (["--ambient", "5000"], "--ambient 5000 C is also the oil supply temperature: oil temperature 5273.15 K is "
                            "outside the viscosity fit's range (200 K, 600 K]"),
    (["--ambient", "-100"], "outside the viscosity fit's range"),
    # any power has a steady state (linear network), but not one of a lubricated bearing
    (["--drag-power", "1e12"], "put the bearing oil at 3.228e+11 C in steady state: oil temperature"),
    (["--sfd-power", "1e9"], "in steady state: oil temperature"),
])
def test_cli_refuses_what_is_no_oil_temperature(capsys, args, message):
    base = {"--drag-power": "348", "--sfd-power": "10"}
    for k, v in zip(args[::2], args[1::2]):
        base[k] = v
    argv = ["thermal-steady", "--bearing", "0"] + [x for kv in base.items() for x in kv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1, err
