"""The spool component (components/spool): prescribed profiles against their closed forms, the torque balance
against the analytic solution of J dW/dt = -c (W - W_wm)^2, its energy bookkeeping, and its bad inputs."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rotorcosim.components.contract import ContractError
from rotorcosim.components.spool.component import Spool
from rotorcosim.components.spool.profile import RPM

TORQUES = ("T_drag1", "T_drag2", "T_rub1", "T_rub2")


def _spool(**p):
    s = Spool("spool", {"inertia": 0.04, **p})
    s.setup(0.0)
    return s


def _run(s, t_end, h, torque=0.0):
    for k in TORQUES:
        s.u[k] = np.array([torque])
    n = int(round(t_end / h))
    for i in range(n):
        s.do_step(i * h, h)
    return s


def test_ramp_speed_and_angle_closed_form():
    """A ramp 9000 -> 3000 rev/min over 1 s from t = 0.2 s: speed and angle equal the closed form (the exact
    integral of the piecewise-linear speed), the acceleration the ramp's slope."""
    s = _run(_spool(profile="ramp", speed_rpm=9000.0, end_speed_rpm=3000.0, t_start=0.2, duration=1.0), 0.7, 1e-3)
    w0, a = 9000 * RPM, -6000 * RPM
    t = 0.5
    assert s.y["Omega"][0] == pytest.approx(w0 + a * t, rel=1e-12)
    assert s.y["theta"][0] == pytest.approx(w0 * 0.7 + 0.5 * a * t * t, rel=1e-12)
    assert s.y["dOmega"][0] == pytest.approx(a, rel=1e-12)


def test_table_profile_and_constant():
    s = _run(_spool(profile="table", table="0 1000, 1 2000, 3 2000"), 0.5, 1e-2)
    assert s.y["Omega"][0] == pytest.approx(1500 * RPM, rel=1e-12)
    c = _run(_spool(profile="constant", speed_rpm=16000.0), 0.25, 5e-3)
    assert c.y["theta"][0] == 16000 * RPM * 0.25         # W t exactly: the constant-speed angle


def test_torque_rundown_against_analytic_solution_and_energy():
    """Fuel cut at 0.1 s, then J dW/dt = -c (W - W_wm)^2 only (no other torque): W_wm + D0 / (1 + c D0 t / J)
    (separable ODE); the kinetic energy lost equals the aerodynamic work (0.5 % asked; round-off here)."""
    J, T0 = 0.04, 30.0
    s = _spool(profile="torque", inertia=J, speed_rpm=16000.0, t_fuel_cut=0.1, windmill_rpm=4900.0, aero_torque=T0)
    _run(s, 2.1, 1e-4)
    D0 = (16000 - 4900) * RPM
    c = T0 / D0 ** 2
    exact = 4900 * RPM + D0 / (1.0 + c * D0 * 2.0 / J)
    assert s.y["Omega"][0] == pytest.approx(exact, rel=1e-4)
    e = s.y["energy"]
    lost = 0.5 * J * (16000 * RPM) ** 2 - e[0]
    assert lost == pytest.approx(e[2] + e[3] + e[4] - e[1], rel=1e-10)
    assert e[1] > 0.0          # the governor's work before the cut


def test_drive_holds_speed_until_fuel_cut_and_event():
    s = _spool(profile="torque", speed_rpm=16000.0, t_fuel_cut=0.5, windmill_rpm=4900.0, aero_torque=30.0)
    assert s.next_event(0.0) == 0.5 and s.next_event(0.6) is None
    # a coupled interval that ends at the cut: the cut is still to come, so no held interval starts there
    assert s.next_event(0.5) == 0.5 and s.next_event(0.5 + 1e-12) == 0.5 and s.next_event(0.5 + 1e-6) is None
    _run(s, 0.5, 1e-3, torque=0.3)
    assert s.y["Omega"][0] == 16000 * RPM
    assert s.y["T_drive"][0] == pytest.approx(4 * 0.3 + 30.0)


def test_stopping_spool_is_a_legal_end_state():
    """Friction alone (no windmilling airflow) stops the spool; it stays at 0 rev/min, never turning backwards."""
    s = _spool(profile="torque", speed_rpm=100.0, t_fuel_cut=0.0)
    _run(s, 3.0, 1e-3, torque=0.05)         # 0.2 N m on 0.04 kg m^2 at 10.5 rad/s: stops at 2.1 s
    assert s.y["Omega"][0] == 0.0
    e = s.y["energy"]
    assert e[0] == 0.0 and e[2] + e[3] == pytest.approx(0.5 * 0.04 * (100 * RPM) ** 2, rel=1e-9)


@pytest.mark.parametrize("params, message", [
    ({"inertia": -1.0}, "inertia"),
    ({"profile": "torque", "speed_rpm": 16000.0, "windmill_rpm": 17000.0, "aero_torque": 30.0}, "windmill_rpm"),
    ({"profile": "table", "table": "0 9000, 1 3000, 0.5 2000"}, "increase strictly"),
    ({"profile": "table", "table": "0 9000, 1 nan"}, "non-finite"),
    ({"profile": "table", "table": "0 9000 1"}, "two numbers"),
    ({"profile": "spin"}, "profile"),
    ({"profile": "ramp", "duration": 0.0}, "duration"),
])
def test_bad_parameters_are_named(params, message):
    with pytest.raises(ContractError, match=message):
        _spool(**params)


def test_nan_torque_is_named():
    s = _spool(profile="torque", t_fuel_cut=0.0, windmill_rpm=4900.0, aero_torque=30.0)
    for k in TORQUES:
        s.u[k] = np.array([0.0])
    s.u["T_rub2"] = np.array([math.nan])
    with pytest.raises(ContractError, match="T_rub2"):
        s.do_step(0.0, 1e-3)


THREE = Path(__file__).parents[2] / "docs" / "examples" / "three_bearings" / "engine.toml"


def test_one_drag_input_per_bearing_on_the_spool_and_their_sum_drives_it():
    """An engine with three co-simulated bearings and one rub ring on spool "rotor" (docs/examples/three_bearings):
    three drag inputs, two rub inputs (at least two of each), named for their parts; after the fuel cut the spool
    decelerates by the sum of all five torques over J (J dW/dt = -sum T, one explicit step: exact)."""
    s = Spool("spool", {"model_file": str(THREE), "spool": "rotor", "profile": "torque", "inertia": 0.25,
                        "speed_rpm": 16000.0, "t_fuel_cut": 0.0})
    ins = [v for v in s.variables if v.causality == "input"]
    assert [v.name for v in ins] == ["T_drag1", "T_drag2", "T_drag3", "T_rub1", "T_rub2"]
    assert all(v.unit == "N.m" and v.size == 1 for v in ins)
    assert [v.description.split(" on ")[0] for v in ins[:4]] == [
        "drag torque of bearing1", "drag torque of bearing2", "drag torque of bearing3", "friction torque of rubring1"]
    s.set_inputs({"T_drag1": 1.0, "T_drag2": 2.0, "T_drag3": 4.0, "T_rub1": 8.0, "T_rub2": 16.0})
    s.setup(0.0)
    s.do_step(0.0, 1e-3)
    assert s.y["dOmega"][0] == pytest.approx(-31.0 / 0.25, rel=1e-12)
    assert s.y["energy"][2] > 0.0 and s.y["energy"][3] / s.y["energy"][2] == pytest.approx(24.0 / 7.0, rel=1e-12)
    # no engine file: the two of each a spool always has
    assert [v.name for v in Spool("s", {}).variables if v.causality == "input"] == list(TORQUES)


def test_a_spool_the_engine_file_does_not_have_is_named(tmp_path):
    """Refused when made (before its ports are connected) and, set later, at set-up; an unreadable model file at
    set-up, by its parameter."""
    msg = r"spool\.spool = 'pt' is not a spool of model_file .*\(its spools: rotor\)"
    with pytest.raises(ContractError, match=msg):
        Spool("spool", {"model_file": str(THREE), "spool": "pt", "inertia": 1.0})
    s = Spool("spool", {"model_file": str(THREE), "spool": "rotor", "inertia": 1.0})
    s.set_parameter("spool", "pt")
    with pytest.raises(ContractError, match=msg):
        s.setup(0.0)
    s = Spool("spool", {"model_file": str(tmp_path / "none.toml"), "inertia": 1.0})
    with pytest.raises(ContractError, match=r"spool\.model_file: .*none\.toml"):
        s.setup(0.0)
