"""The jeffcott_rundown check case against an independent integration of the Jeffcott equations
(tests/cases/jeffcott_reference.py: scipy solve_ivp of the textbook equations, sharing no code with the rotor
component), and its slow limit against the steady-state peak (u / m) / (2 zeta) of the textbook."""
from __future__ import annotations

import numpy as np
import pytest

from rotorcosim.master.api import load_scenario, simulate
from tests.cases.jeffcott_reference import rundown

M, K, ZETA, U = 10.0, 4.0e6, 0.02, 1.0e-4


def _peak(res):
    x = res["rotor.X_brg0"]
    r = np.hypot(x[:, 0], x[:, 1])
    j = int(np.argmax(r))
    return r[j], float(np.asarray(res["spool.Omega"]).reshape(len(r), -1)[j, 0]) * 30.0 / np.pi


def test_rundown_peak_against_independent_integration(tmp_path):
    """1 s rundown 9000 -> 3000 rev/min: the peak orbit radius within 1 % and the speed at the peak within 0.5 %
    of the independent integration; summary.json's crossing says the same."""
    res = simulate("jeffcott_rundown", out=tmp_path / "run", figures=False)
    t, rpm, r = rundown(M, K, ZETA, U, 9000.0, 3000.0, 1.0, samples=100_001)
    j = int(np.argmax(r))
    peak, speed = _peak(res)
    assert peak == pytest.approx(r[j], rel=0.01)
    assert speed == pytest.approx(rpm[j], rel=0.005)
    (c,) = res.summary["crossings"]
    assert c["critical_speed_rpm"] == pytest.approx(6039.5)
    assert c["bearings"]["disk"]["peak_whirl_mm"] == pytest.approx(r[j] * 1e3, rel=0.01)
    assert c["peak_speed_rpm"] == pytest.approx(rpm[j], rel=0.005)
    assert c["direction"] == "down"
    # a prescribed profile's drive torque does all the work: the balance closes to round-off
    e = res.summary["energy"]["spool"]
    assert abs(e["residual_pct"]) < 1e-6


def test_slow_rundown_approaches_steady_peak():
    """10 s rundown: the peak within 1 % of the independent integration and within 5 % of the steady-state peak
    (u / m) / (2 zeta) (the textbook's resonance amplitude of the Jeffcott rotor), closer to it than the 1 s
    rundown's."""
    sc = load_scenario("jeffcott_rundown").set({"spool.duration": 10.0})
    sc.schedule["duration"] = 10.0
    res = simulate(sc, figures=False)
    peak, _ = _peak(res)
    _, _, r = rundown(M, K, ZETA, U, 9000.0, 3000.0, 10.0, samples=400_001)
    steady = (U / M) / (2.0 * ZETA)
    assert peak == pytest.approx(r.max(), rel=0.01)
    assert abs(peak - steady) < 0.05 * steady
    _, _, r1 = rundown(M, K, ZETA, U, 9000.0, 3000.0, 1.0, samples=100_001)
    assert abs(peak - steady) < abs(r1.max() - steady)
