"""Damper viscosity fit, spring, wall contact, bad inputs and the ``damper-force`` command."""
import json
import math

import numpy as np
import pytest

from rotorcosim.components.contract import ContractError
from rotorcosim.components.damper.component import FastDamper, FEDamper, WallContactError
from rotorcosim.components.damper.viscosity import sae30_viscosity, walther_constants
from rotorcosim.master.cli import main

C = 0.635e-3


@pytest.fixture(scope="module")
def fast0():
    d = FastDamper("damper0", {"damper": 0})
    d.setup(0.0)
    return d


def _step(d, x, v=(0.0, 0.0), T=343.15):
    d.set_inputs({"X_journal": x, "V_journal": v, "T_oil": [T]})
    d.do_step(0.0, 1e-5)
    return d.y


# -- viscosity ------------------------------------------------------------------------------------------
def test_viscosity_through_the_paper_points():
    """SAE 30 (paper Table 3): 92 cP at 40 C and 11 cP at 100 C."""
    assert sae30_viscosity(313.15) == pytest.approx(0.092, rel=1e-9)
    assert sae30_viscosity(373.15) == pytest.approx(0.011, rel=1e-9)


def test_viscosity_between_points_matches_vogel_and_constants():
    """Independent checks from physics-notes: its Walther constants (A = 8.4882, B = 3.2784, to the printed
    digits) and the Vogel fit mu = 9.873e-5 exp(910.4 / (T - 180)) Pa s, which must agree with the Walther fit
    within 3 % at 70 C and 85 C (two standard fits through the same data)."""
    A, B = walther_constants()
    assert A == pytest.approx(8.4882, abs=2e-3) and B == pytest.approx(3.2784, abs=1e-3)
    for T in (343.15, 358.15):
        vogel = 9.873e-5 * math.exp(910.4 / (T - 180.0))
        assert sae30_viscosity(T) == pytest.approx(vogel, rel=0.03)
    assert sae30_viscosity(350.0) < sae30_viscosity(340.0)


# -- spring, outputs ----------------------------------------------------------------------------------------
def test_spring_and_reactions(fast0):
    """O-ring spring of Table 3 (5254 N/mm) in parallel with the film, reactions equal and opposite, and the
    housing's motion enters only relative to the journal."""
    x = np.array([1e-4, -2e-4])
    y = _step(fast0, x, (0.1, 0.05))
    assert np.allclose(y["F_spring"], -5254e3 * x, rtol=1e-12)
    assert np.allclose(y["F_journal"], y["F_film"] + y["F_spring"], rtol=1e-12)
    assert np.allclose(y["F_housing"], -y["F_journal"], rtol=0, atol=0)
    assert float(y["P_film"][0]) == pytest.approx(-float(y["F_film"] @ [0.1, 0.05]), rel=1e-12)
    F = y["F_journal"].copy()
    fast0.set_inputs({"X_journal": x + 3e-5, "V_journal": [0.2, 0.1], "X_housing": [3e-5, 3e-5],
                      "V_housing": [0.1, 0.05]})
    fast0.do_step(0.0, 1e-5)
    assert np.allclose(fast0.y["F_journal"], F, rtol=1e-12)
    fast0.set_inputs({"X_housing": [0.0, 0.0], "V_housing": [0.0, 0.0]})


def test_state_snapshot_roundtrip(fast0):
    """get_state / set_state restore the outputs exactly (the component is memoryless)."""
    _step(fast0, [1e-4, 0.0], (0.1, 0.2))
    snap = fast0.get_state()
    F = fast0.y["F_journal"].copy()
    _step(fast0, [3e-4, 1e-4], (0.3, -0.2))
    fast0.set_state(snap)
    assert np.array_equal(fast0.y["F_journal"], F)


# -- the journal at the wall ----------------------------------------------------------------------------
def test_wall_contact_spring(fast0):
    """Beyond the clearance a radial contact spring k_wall acts: F_contact = -k_wall (e - c) e_hat, with its
    stiffness -k_wall e_hat e_hat^T (+ the tangential term (1 - c/e)) in K_film."""
    k = fast0.p["k_wall"]
    ang = 0.4
    n = np.array([math.cos(ang), math.sin(ang)])
    e = 1.002 * C
    y = _step(fast0, e * n, (0.0, 0.0))
    assert np.allclose(y["F_contact"], -k * (e - C) * n, rtol=1e-9)
    K = y["K_film"].reshape(2, 2)
    t = np.array([-n[1], n[0]])
    # radial stiffness: spring + contact (the film is held at eps_max: no radial film stiffness, no velocity)
    assert n @ K @ n == pytest.approx(-fast0.p["k_spring"] - k, rel=1e-9)
    assert t @ K @ t == pytest.approx(-fast0.p["k_spring"] - k * (1 - C / e), rel=1e-6)


def test_wall_contact_off_is_an_error():
    d = FastDamper("damper5", {"damper": 5, "k_wall": 0.0})
    d.setup(0.0)
    _step(d, [0.98 * C, 0.0])
    with pytest.raises(WallContactError, match=r"hit the damper wall .*eccentricity ratio 1\.0010"):
        _step(d, [1.001 * C, 0.0])


def test_deep_penetration_is_divergence(fast0):
    with pytest.raises(WallContactError, match="into the damper wall .* the simulation diverged"):
        _step(fast0, [0.0, -2.5 * C])


# -- bad inputs -----------------------------------------------------------------------------------------
@pytest.mark.parametrize("port,value", [("X_journal", [math.nan, 0.0]), ("V_housing", [0.0, math.inf])])
def test_non_finite_motion(port, value):
    d = FastDamper("damper0", {"damper": 0})
    d.setup(0.0)
    d.set_inputs({port: value})
    with pytest.raises(ContractError, match="damper0: non-finite journal/housing motion at t = 1e-05 s"):
        d.do_step(0.0, 1e-5)


@pytest.mark.parametrize("T", [math.nan, 150.0, 700.0])
def test_bad_oil_temperature(fast0, T):
    with pytest.raises(ContractError, match=r"damper0\.T_oil: oil temperature .* outside the viscosity fit"):
        _step(fast0, [0.0, 0.0], T=T)
    _step(fast0, [0.0, 0.0])


@pytest.mark.parametrize("params,match", [
    ({"damper": 3}, r"damper must be one of \[0, 5\]"),
    ({"damper": 0, "clearance": -1e-4}, r"clearance must be > 0"),
    ({"damper": 0, "length": 0.0}, r"length must be > 0"),
    ({"damper": 0, "k_spring": -1.0}, r"k_spring must be >= 0"),
    ({"damper": 0, "k_wall": -1.0}, r"k_wall must be >= 0"),
    ({"damper": 0, "n_theta": 4}, r"mesh n_theta=4"),
    # neither a record of the paper's nor its own values: the missing ones named
    ({}, r"no Table 3 record \(damper = -1\) and no radius, length, clearance, supply_pressure, k_spring given"),
    # a clearance in mm where metres are meant (Table 3: 0.635 mm): refused, with the conversion
    ({"damper": 0, "clearance": 0.635}, r"dmp\.clearance = 0\.635 m is not a thin film against the journal "
     r"radius 0\.08 m .*: 0\.635 mm = 0\.000635 m"),
    ({"damper": 5, "clearance": 0.03}, r"c/R = 0\.3 > 0\.05"),
])
def test_bad_parameters(params, match):
    d = FEDamper("dmp", params)
    with pytest.raises(ContractError, match=match):
        d.setup(0.0)


def test_nan_parameter_rejected():
    with pytest.raises(ContractError, match="not finite"):
        FastDamper("dmp", {"radius": math.nan})


# -- command line ---------------------------------------------------------------------------------------
def test_cli_json(capsys):
    """rotorcosim damper-force --json: keys and units as documented (film force, spring force, power,
    viscosity), the same numbers as the component."""
    assert main(["damper-force", "--damper", "0", "--position", "2e-4", "1e-4", "--velocity", "0.1", "-0.2",
                 "--temperature", "70", "--json"]) in (0, None)
    out = json.loads(capsys.readouterr().out)
    assert {"force_N", "spring_force_N", "power_W", "viscosity_Pa_s"} <= set(out)
    d = FastDamper("damper0", {"damper": 0})
    d.setup(0.0)
    y = _step(d, [2e-4, 1e-4], (0.1, -0.2), T=343.15)
    assert out["force_N"] == pytest.approx(list(y["F_film"]), rel=1e-12)
    assert out["spring_force_N"] == pytest.approx([-5254e3 * 2e-4, -5254e3 * 1e-4], rel=1e-12)
    assert out["power_W"] == pytest.approx(float(y["P_film"][0]), rel=1e-12)
    assert out["viscosity_Pa_s"] == pytest.approx(sae30_viscosity(343.15), rel=1e-12)


def test_cli_bad_input(capsys):
    code = main(["damper-force", "--damper", "0", "--position", "nan", "0", "--velocity", "0", "0",
                 "--temperature", "70", "--json"])
    assert code != 0
    assert "must be finite numbers" in capsys.readouterr().err


def test_cli_position_far_beyond_the_wall(capsys):
    """A position in mm where metres are meant (1 m): an input mistake named as one, not "the simulation
    diverged" (no simulation runs here)."""
    code = main(["damper-force", "--damper", "0", "--position", "1", "1", "--velocity", "0", "0",
                 "--temperature", "70"])
    err = capsys.readouterr().err
    assert code == 2 and "--position: damper0: the journal is 1414 mm into the damper wall" in err
    assert "clearance is 0.635 mm and positions are in metres" in err and "diverged" not in err


# -- thermal-only update ----------------------------------------------------------------------------------
def test_thermal_only_film_power_follows_the_viscosity_at_frozen_motion():
    """In a thermal-only interval the damper keeps its forces (the master holds its motion inputs at their frozen
    values); only its film power follows the SFD oil viscosity. The film's pressures at fixed kinematics are linear
    in mu (Reynolds), up to the cavitation clip at a fixed pressure: without cavitation the power scales exactly
    with mu."""
    d = FastDamper("damper0", {"damper": 0, "cavitation": False})
    d.setup(0.0)
    y = _step(d, (0.3 * C, 0.1 * C), (0.02, -0.05), T=343.15)
    frozen = {k: v.copy() for k, v in y.items() if k != "P_film"}
    P0 = float(y["P_film"][0])
    assert P0 > 0.0
    d.enter_phase("TO")
    d.set_inputs({"T_oil": [393.15]})
    d.do_step(0.0, 0.1)
    ratio = sae30_viscosity(393.15) / sae30_viscosity(343.15)
    assert float(d.y["P_film"][0]) == pytest.approx(P0 * ratio, rel=1e-9)
    for k, v in frozen.items():
        if k != "mu":
            np.testing.assert_array_equal(d.y[k], v)
    held = FastDamper("d", {"damper": 0, "power_in_thermal_only": False})
    held.setup(0.0)
    assert held.phases == frozenset({"TM"}) and not held.holds_state_in_TO


@pytest.mark.parametrize("velocity, temperature, message", [
    # 1e9 m/s was computed; a film Reynolds number above LAMINAR_FILM_RE is a turbulent film
    (["1e9", "0"], "70", "--velocity 1e+09 m/s gives a film Reynolds number rho |V| c / mu = 2.06e+10 at 70 C, "
                         "above 1000"),
    (["0", "-60"], "100", "above 1000: a turbulent film"),
    (["0", "0"], "5000", "--temperature 5000 C: oil temperature 5273.15 K is outside the viscosity fit's range"),
])
def test_cli_velocity_and_temperature_outside_the_model(capsys, velocity, temperature, message):
    code = main(["damper-force", "--damper", "0", "--position", "1e-5", "0", "--velocity", *velocity,
                 "--temperature", temperature])
    err = capsys.readouterr().err
    assert code == 2 and message in err and err.count("\n") == 1, err


def test_cli_a_fast_whirl_is_still_a_film(capsys):
    """The limit is far from the runs: 5 m/s (30 times the 0.17 m/s of a 0.1 mm whirl at 16 000 rev/min) computes."""
    assert main(["damper-force", "--damper", "5", "--position", "1e-4", "0", "--velocity", "0", "5",
                 "--temperature", "100", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["force_N"][1] < 0.0


@pytest.mark.parametrize("cls", [FastDamper, FEDamper])
@pytest.mark.parametrize("params, says", [
    # a mesh no table could be built for in a working day (n_theta = 100000 took 2.6 GB in a minute, no end)
    ({"n_theta": 100000}, r"100000 x 64 = 6.4e\+06 nodes, above 131072"),
    ({"n_z": 2049}, r"128 x 2049 = 2.623e\+05 nodes, above 131072"),
    # the film cannot rupture above the pressure it is fed at (1e9 Pa ran, the whole film clipped up to it)
    ({"cavitation_pressure": 1e9}, r"cavitation_pressure = 1e\+09 Pa must not exceed the supply pressure"),
    ({"cavitation_pressure": 1.0, "supply_pressure": 0.0}, r"must not exceed the supply pressure \(0 Pa"),
])
def test_parameters_outside_the_film_model(cls, params, says):
    d = cls("damper0", {"damper": 0, **params})
    with pytest.raises(ContractError, match=says):
        d.setup(0.0)


def test_cavitation_at_the_supply_pressure_is_the_half_film():
    """Equal pressures (0 and 0: the classic half-Sommerfeld film) stay allowed; full film ignores the value."""
    half = FastDamper("d", {"damper": 0, "cavitation_pressure": 0.0, "supply_pressure": 0.0})
    half.setup(0.0)
    full = FastDamper("d", {"damper": 0, "cavitation": False, "cavitation_pressure": 1e9})
    full.setup(0.0)
    # both set up with their values as given (no error, nothing replaced)
    assert half.p["cavitation_pressure"] == half.p["supply_pressure"] == 0.0
    assert full.p["cavitation"] is False and full.p["cavitation_pressure"] == 1e9
