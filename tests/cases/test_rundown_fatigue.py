"""The staggered rundown's load cycles over windmilling against the monolithic run's: the held intervals' cycles
counted from the hold's window times their revolutions (master/observer/held_cycles.py). A file of its own: the
suite runs a file's tests in one worker, and this check and the default rundown comparison
(test_rundown_staggered.py) are the two longest."""
from __future__ import annotations

import json

import pytest

import rotorcosim
from rotorcosim.cases.rundown import compare as rc

CUT = 1.01


def _early_cut():
    return rotorcosim.load_scenario("blade_loss_rundown").set({"spool_pt.t_fuel_cut": CUT,
                                                               "spool_gg.t_fuel_cut": CUT})


@pytest.mark.slow   # ~14 min of CPU time (858 s measured: staggered 110 s, monolithic 741 s)
def test_windmilling_damage_equivalent_loads_within_2pct(tmp_path):
    """The fuel cut at 1.01 s, 166.01 s: the rundown and two minutes of windmilling from 46.01 s, 97 % of them in
    held intervals (seven, 9-22 s each). The damage-equivalent loads of the dampers' transmitted forces over the
    windmilling (x and y, m = 3, N_ref = 2e6), the held intervals' cycles from the hold's window times their
    revolutions, against the monolithic run that simulates every cycle: measured 0.23-0.30 % (m = 5: 0.25-0.32 %,
    m = 10: 0.27-0.34 %; 6 762 cycles counted against 6 749)."""
    out = tmp_path / "cmp"
    t = rc.compare_rundown(_early_cut(), CUT + rc.RUNDOWN_S + 120.0, out, figures=False, warm_up=False)
    f = t["fatigue"]
    assert f["t_from_s"] == pytest.approx(CUT + rc.RUNDOWN_S)
    assert len(f["loads"]) == 4 and f["within_2pct"], f
    timeline = json.loads((out / "staggered" / "summary.json").read_text())["timeline"]
    held = sum(iv["t_end"] - iv["t_start"] for iv in timeline if iv["phase"] == "TO" and iv["t_start"] >= CUT + 40)
    assert held > 100.0     # the comparison is of held intervals' cycles, not of coupled ones
