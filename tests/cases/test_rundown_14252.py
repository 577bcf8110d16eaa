"""The 14 252 N rundown at engine level (blade_loss_rundown at the paper's highest level, both rub rings rubbing):
the run passes both critical speeds of the power turbine within 0.4 s of the fuel cut at 15.01 s (the rub torque
decelerates it fast), and its summary finds both peaks and labels each to its mode: the lower mode (undamped
8 500 rev/min, `rotorcosim critical-speeds`) at bearing #0, the upper one (10 200 rev/min) at #5, each with the
damped critical speed of the linearised engine at the film temperatures the run had at the peak. The energy
balance is reported and closes (the work of every torque the components report, integrated apart from the
spool's own step: cases/rundown/energy.py), and so is the rub rings' dissipated energy, the rub torque's work plus
the whirl's share of the sliding speed."""
from __future__ import annotations

import pytest

import rotorcosim
from rotorcosim.cases.blade_loss.results import apply_unbalance

#: the shortest run that passes both critical speeds: the peaks are at 15.34 and 15.37 s
DURATION_S = 16.0


@pytest.mark.slow   # ~26 s of CPU time (measured): 15 s at speed, mostly held, then 1 s of rundown coupled
def test_both_crossings_found_and_labelled_and_the_energy_reported():
    sc = rotorcosim.load_scenario("blade_loss_rundown")
    apply_unbalance(sc, 14252.0)
    s = rotorcosim.simulate(sc, duration=DURATION_S, figures=False, progress=False).summary
    lower, upper = s["crossings"]
    assert lower["peak_found"] and upper["peak_found"]
    assert lower["critical_speed_rpm"] == pytest.approx(8500.0, rel=1e-3) and lower["location"] == "0"
    assert upper["critical_speed_rpm"] == pytest.approx(10200.0, rel=1e-3) and upper["location"] == "5"
    for c in (lower, upper):
        assert c["direction"] == "down" and 15.01 < c["t_s"] < DURATION_S
        assert set(c["film_temperature_C"]) == {"0", "5"} and c["damped_critical_speed_rpm"] > 0.0
        lo, hi = c["speed_range_rpm"]
        assert lo < c["peak_speed_rpm"] < hi
    e = s["energy"]["spool_pt"]
    assert e["kinetic_energy_lost_J"] > 0.0
    # the balance closes to well below a part in 10^4 of the energy lost: it is a check (a 1 % torque error moves
    # it by 1 % of that torque's work, tests/cases/test_rundown_energy.py), not an identity
    assert abs(e["residual_J"]) < 1e-4 * e["kinetic_energy_lost_J"]
    w = e["work_J"]
    assert w["rub"] > 0.0 and w["drag"] > 0.0 and w["aero"] > 0.0
    assert e["rub_dissipated_J"] == pytest.approx(w["rub"] + e["rub_whirl_share_J"], rel=1e-9)
    assert 0.0 < e["rub_whirl_share_J"] < 0.1 * e["rub_dissipated_J"]
