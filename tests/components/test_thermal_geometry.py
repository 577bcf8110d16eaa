"""The thermal network follows the bearing's and the damper's geometry (the paper's Table 1 from Table 3-like
dimensions), every other value a documented default: checked against textbook conduction / convection / heat
capacity formulas worked by hand for a bearing that is not the paper's, and the paper's own values reproduced."""
import json
import math
import re

import numpy as np
import pytest

from rotorcosim.components.contract import ContractError
from rotorcosim.components.thermal.component import PT_OMEGA, ThermalNetwork
from rotorcosim.components.thermal.geometry import (BALL, HOUSING, IR, JOURNAL, OR, SFD, SHAFT, bearing_data,
                                                    rub_partition, shell_nodes)

#: a 6208-size deep-groove bearing (bore 40, OD 80, width 18 mm, 9 balls of 12.7 mm) in a damper of 55 mm
#: journal radius, 25 mm length, 0.2 mm clearance: nothing of the paper's Table 3
USER = {"bore": 0.040, "outside_diameter": 0.080, "width": 0.018, "balls": 9, "ball_diameter": 0.0127,
        "contact_angle": 0.0, "damper_radius": 0.055, "damper_length": 0.025, "damper_clearance": 0.2e-3,
        "rub_radius": 0.022}


def make(bearing=0, **params):
    c = ThermalNetwork(f"thermal{bearing}", {"bearing": bearing, **params})
    c.setup(0.0)
    return c


def _chain(K, nodes):
    """The series resistance of the branches joining ``nodes`` one after the other, K/W."""
    return sum(-1.0 / K[a, b] for a, b in zip(nodes[:-1], nodes[1:]))


def test_papers_values_follow_from_the_defaults():
    """What the paper's Table 3 does not give are the rules of data/thermal.toml [defaults]; for the paper's two
    bearings they give exactly the values its results were computed with: L_s 100 mm, housing wall 15 mm,
    L_h = 2 L_j (64 and 80 mm), the rub ring at the bore radius (25.4 and 41.9 mm, as
    components/rubring/data/rubrings.toml), no oil jet."""
    shipped = {0: (100.0, 15.0, 64.0, 25.4, 0.0), 5: (100.0, 15.0, 80.0, 41.9, 0.0)}
    for k, values in shipped.items():
        d = bearing_data(k)
        assert (d["shaft_length_mm"], d["housing_wall_mm"], d["housing_length_mm"], d["rub_ring_radius_mm"],
                d["jet_L_per_min"]) == values


@pytest.mark.parametrize("bearing", [0, 5])
def test_table3_as_parameters_gives_the_papers_network(bearing):
    """The paper's bearing given by its dimensions (SI parameters) instead of its number: the same network to
    round-off (mm -> m); and bearing #0's record with #5's dimensions set is #5's network: the geometry decides,
    housing length and rub radius following it."""
    ref = make(bearing).network
    dims = {"bore": 0.0508, "outside_diameter": 0.090, "width": 0.020, "balls": 21, "ball_diameter": 8.73e-3,
            "contact_angle": math.radians(15.0), "damper_radius": 0.080, "damper_length": 0.032,
            "damper_clearance": 0.635e-3} if bearing == 0 else \
        {"bore": 0.0838, "outside_diameter": 0.110, "width": 0.016, "balls": 27, "ball_diameter": 9.53e-3,
         "contact_angle": math.radians(15.0), "damper_radius": 0.100, "damper_length": 0.040,
         "damper_clearance": 0.635e-3}
    for start in {0, bearing}:
        net = make(start, **dims).network
        for a, b in ((net.C, ref.C), (net.K, ref.K), (net.b, ref.b), (net.S, ref.S)):
            np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-15)


def test_a_users_bearing_against_textbook_formulas():
    """USER's bearing and damper, by hand with the textbook formulas (Incropera & DeWitt, Fundamentals of Heat and
    Mass Transfer, ch. 3: a cylindrical wall ln(r2/r1)/(2 pi k L), eq. 3.28; a rod L/(k A); a surface 1/(h A);
    heat capacity rho c V), steel k 40, rho c 7800 x 460, oil k 0.14, rho c 870 x 2000, from the dimensions only:
    d_m = 60 mm, r_s 20, r_i (60 - 12.7)/2 = 23.65, r_e 36.35, r_o 40, r_b 6.35, r_j 55, r_hi 55.2, r_h 70.2 mm,
    L_s 100 mm (default), L_h 2 x 25 = 50 mm (default rule).

    shaft - inner race: 1/(pi 40 0.018) + ln(23.65/20)/(2 pi 40 0.018) = 0.44210 + 0.03706 = 0.47915 K/W
    outer race - journal (one wall r_e..r_j): ln(55/36.35)/(2 pi 40 0.018) = 0.091545 K/W
    journal - film - housing (one oil wall r_j..r_hi): ln(55.2/55)/(2 pi 0.14 0.025) = 0.16506 K/W
    shaft - ambient: h_s = 3.75 (1675.5 rad/s)^0.7 (0.02 m)^0.4 = 141.69 W/(m^2 K);
        0.1/(40 pi 0.02^2) + 1/(141.69 pi 0.02^2) = 1.9894 + 5.6162 = 7.6056 K/W
    housing - oil (h_h 1000): radial ln(70.2/55.2)/(2 pi 40 0.05) + 1/(1000 2 pi 0.0702 0.05) = 0.01913 + 0.04534,
        axial 0.05/(2 pi 40 A) + 1/(pi 1000 A), A = 0.0702^2 - 0.0552^2, in parallel: 0.052228 K/W
    heat masses, J/K: inner race pi (23.65^2 - 20^2) 18 mm^3 -> 32.326; balls 9 (4/3) pi 6.35^3 mm^3 -> 34.634;
        outer race pi (40^2 - 36.35^2) 18 -> 56.543; journal sleeve pi (55^2 - 40^2) 25 -> 401.57;
        film 2 pi 55 0.2 25 mm^3 x 870 x 2000 -> 3.0065; housing pi (70.2^2 - 55.2^2) 50 -> 1060.13;
        shaft pi 20^2 100 -> 450.88."""
    c = make(0, **USER)
    net = c.network
    K = net.K
    assert _chain(K, [SHAFT, IR]) == pytest.approx(0.47915, rel=1e-4)
    assert _chain(K, [OR, *shell_nodes()]) == pytest.approx(0.091545, rel=1e-4)
    assert shell_nodes()[-1] == JOURNAL
    assert _chain(K, [JOURNAL, SFD, HOUSING]) == pytest.approx(0.16506, rel=1e-4)
    assert 1.0 / net.ground[SHAFT] == pytest.approx(7.6056, rel=1e-4)
    assert 1.0 / net.ground[HOUSING] == pytest.approx(0.052228, rel=1e-4)
    C = net.C
    for node, hand in ((IR, 32.326), (BALL, 34.634), (OR, 56.543), (SFD, 3.0065), (HOUSING, 1060.13),
                       (SHAFT, 450.88)):
        assert C[node] == pytest.approx(hand, rel=1e-4), node
    assert C[shell_nodes()].sum() == pytest.approx(401.57, rel=1e-4)
    # the defaults the geometry sets, as the parameters list them
    assert c.p["housing_length"] == pytest.approx(0.050, rel=1e-12)
    assert c.p["shaft_length"] == pytest.approx(0.100, rel=1e-12) and c.p["housing_wall"] == pytest.approx(0.015)
    # growths follow the user's radii: a uniform 10 K rise, eq. (15) eps_b = xi r_b dT = 12e-6 * 6.35e-3 * 10
    eps = c.growths_at(np.full(net.n, 303.15 + 10.0))
    assert eps[2] == pytest.approx(12e-6 * 6.35e-3 * 10.0, rel=1e-12)


def test_rub_partition_follows_the_rub_radius():
    """Blok's partition (data/thermal.toml [rub]) at the sliding speed omega R_r of the set rub_radius: by hand at
    R_r = 22 mm, V = 1675.5 x 0.022 = 36.86 m/s, a = 3 mm, kappa = 40/(7800 x 460) = 1.1148e-5 m^2/s:
    R_1 = 8 a/(3 pi k) = 6.3662e-5, R_2 = (4/3) sqrt(2 kappa a/(pi V))/k = 8.0112e-7 (m^2 K/W), f = 1.2428 %."""
    rec = {**bearing_data(0), "rub_ring_radius_mm": 22.0}
    assert rub_partition(rec, PT_OMEGA) == pytest.approx(0.012428, rel=1e-4)
    # the component's default rub_shaft_fraction (< 0) is that partition: the shaft node's share of P_rub
    c = make(0, rub_radius=0.022)
    assert c.network.S[SHAFT, 2] == pytest.approx(rub_partition(rec, PT_OMEGA), rel=1e-12)


@pytest.mark.parametrize("params, message", [
    ({"contact_angle": 2.0}, "contact_angle must be in [0, pi/2) rad"),
    ({"balls": 8.5}, "thermal0.balls: expected an integer"),
    ({"balls": 0}, "thermal0.balls must be a whole number > 0"),
    ({"ball_diameter": 0.03}, "radii are not nested"),
    ({"damper_radius": 0.04}, "radii are not nested"),
    ({"rub_radius": float("nan")}, "thermal0.rub_radius: value is not finite"),
    ({"rub_radius": -0.02}, "thermal0.rub_radius must be a finite number > 0"),
])
def test_bad_geometry(params, message):
    with pytest.raises(ContractError, match=re.escape(message)):
        make(0, **params)


def test_parameters_list_the_geometry_with_unit_default_and_source(capsys):
    from rotorcosim.master.cli import main

    assert main(["parameters", "thermal0", "--json"]) == 0
    rows = {r["name"]: r for r in json.loads(capsys.readouterr().out)}
    for name, unit in (("contact_angle", "rad"), ("rub_radius", "m"), ("housing_length", "m"),
                       ("shaft_length", "m"), ("balls", "1"), ("damper_clearance", "m")):
        assert rows[name]["unit"] == unit and rows[name]["default"] is not None
    assert "2 x damper_length" in rows["housing_length"]["description"]
    assert "paper-components.md" in rows["shaft_length"]["description"]
    assert "Table 3" in rows["balls"]["description"]
    # the text listing of one component carries each parameter's description under its row
    assert main(["parameters", "thermal0"]) == 0
    lines = capsys.readouterr().out.splitlines()
    at = next(i for i, line in enumerate(lines) if line.split()[:1] == ["housing_length"])
    assert " m " in lines[at] and "default 0.064" in lines[at] and "2 x damper_length" in lines[at + 1]


def test_a_users_engine_passes_its_geometry_to_the_thermal_network(tmp_path):
    """The textbook engine (new-engine): its thermal networks run with its bearings', dampers' and rub rings'
    geometry, taken from the same records of the engine file (the case's check finds no difference); a bearing
    changed by name changes its network with it (19 balls: 19/21 of the balls' heat mass), and a scenario file
    that writes a different value into the network alone is refused naming both values."""
    from rotorcosim.cases.blade_loss import thermal_geometry
    from rotorcosim.cases.blade_loss.new_engine import new_engine
    from rotorcosim.master.api import load_scenario
    from rotorcosim.master.scenario.build import build_simulation, create_component

    new_engine(tmp_path / "X")
    sc = load_scenario(tmp_path / "X" / "blade_loss.toml")
    assert thermal_geometry.mismatches(sc, build_simulation(sc, []).system) == []
    rows = {r["name"]: r["value"] for r in sc.parameters("thermal0")}
    assert rows["rub_radius"] == sc.components["rubring0"].parameters["radius"] == 0.030
    good = sc.set({"bearing0.balls": 19})
    assert good.components["thermal0"].parameters["balls"] == 19
    thermal_geometry.check(good, build_simulation(good, []).system)
    th = create_component(good.components["thermal0"])
    th.setup(0.0)
    ref = create_component(sc.components["thermal0"])
    ref.setup(0.0)
    assert th.network.C[BALL] / ref.network.C[BALL] == pytest.approx(19 / 21, rel=1e-12)
    (tmp_path / "X" / "own.toml").write_text('[scenario]\nextends = "blade_loss.toml"\n'
                                             '[components.thermal0]\nparameters = { balls = 19 }\n')
    bad = load_scenario(tmp_path / "X" / "own.toml")
    with pytest.raises(ValueError, match="thermal0.balls = 19 but bearing0.balls = 21"):
        thermal_geometry.check(bad, build_simulation(bad, []).system)



def test_the_speed_following_network_rebuilds_with_its_own_geometry():
    """thermal.network_spinning rebuilds its speed terms when the spool's speed leaves the network's: the rebuilt
    network is that of the set geometry (USER's bearing) at the new speed, the constant-speed network's at
    omega = the new speed (not the paper's record the ``bearing`` number names)."""
    from rotorcosim.components.thermal.spinning import SpinningThermalNetwork

    sp = SpinningThermalNetwork("thermal0", {"bearing": 0, **USER})
    sp.setup(0.0)
    half = 0.5 * PT_OMEGA
    sp.set_inputs({"P_drag": [100.0], "P_sfd": [10.0], "P_rub": [0.0], "Omega": [half]})
    sp.do_step(0.0, 1e-3)      # the kernel hands the step to Python, which rebuilds at the input speed
    ref = make(0, omega=half, **USER).network
    for a, b in ((sp.network.C, ref.C), (sp.network.K, ref.K), (sp.network.b, ref.b), (sp.network.S, ref.S)):
        np.testing.assert_array_equal(a, b)
    assert not np.array_equal(sp.network.K, make(0, omega=half).network.K)
