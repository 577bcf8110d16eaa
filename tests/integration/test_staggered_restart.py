"""The staggered scheme on a rubbing level (14 252 N): across a thermo-mechanical restart the Table 4 temperatures
of bearing #0 change as the monolithic run's do over the same time (within 2 K), and the paper's plain hold (the
powers held at their RMS over the last cycles, nothing updated in TO) does not: the check can fail.

Kept cheap: a 10 us step (the same in both runs), TM 0.04 s (past the blade loss at 0.01 s) - TO 0.2 s at the
paper's 0.1 s thermal step - TM 0.025 s, against a monolithic run of the same 0.265 s. In the rubbing cases the SFD
oil node is fast (time constant ~0.25 s) and its film power falls steeply as it warms: holding the cold-oil power
over the TO interval overheats it, and the restart then cools it by several K in the first cycles (the 43-70 K
jumps over the paper's 24 s TO intervals)."""
import numpy as np
import pytest

from rotorcosim.master.cli.run import resolve
from rotorcosim.cases.blade_loss.results import apply_unbalance
from rotorcosim.master.scenario.build import build_simulation

STEP = 1e-5
TM1, TO, TM2 = 0.04, 0.2, 0.025
#: T_nodes indices of Table 4's temperatures: inner race, ball, outer race, SFD oil
NODES = {"inner_race": 1, "ball": 3, "outer_race": 5, "sfd_oil": 7}


def _sim(paper_hold=False):
    sc = resolve("blade_loss")
    apply_unbalance(sc, 14252.0)
    if paper_hold:
        sc.schedule["hold"] = "rms"
        sc.schedule["restart_cycles"] = 0   # the thermal inputs stepped into the frozen mechanics at the restart
        for k in (0, 5):
            sc.components[f"bearing{k}"].parameters["drag_in_thermal_only"] = False
            sc.components[f"damper{k}"].parameters["power_in_thermal_only"] = False
    return build_simulation(sc)


def _change_across_restart(sim, staggered: bool) -> np.ndarray:
    sim.run_interval("TM", TM1, STEP)
    if staggered:
        sim.run_interval("TO", TO, 0.1)
    else:
        sim.run_interval("TM", TO, STEP)
    before = np.array(sim.value("thermal0.T_nodes"))[list(NODES.values())]
    sim.run_interval("TM", TM2, STEP)
    after = np.array(sim.value("thermal0.T_nodes"))[list(NODES.values())]
    return after - before


@pytest.fixture(scope="module")
def monolithic():
    return _change_across_restart(_sim(), staggered=False)


def test_no_temperature_jump_across_a_restart(monolithic):
    staggered = _change_across_restart(_sim(), staggered=True)
    print("staggered - monolithic change across the restart [K]:", dict(zip(NODES, staggered - monolithic)))
    assert np.max(np.abs(staggered - monolithic)) < 2.0, dict(zip(NODES, staggered - monolithic))


def test_the_paper_hold_jumps(monolithic):
    """The check above can fail: with the paper's hold and restart the SFD oil cools by more than 2 K beyond the
    monolithic run in the 25 ms after the restart (measured 1.6 K after 10 ms)."""
    paper = _change_across_restart(_sim(paper_hold=True), staggered=True)
    print("paper hold - monolithic change across the restart [K]:", dict(zip(NODES, paper - monolithic)))
    assert np.max(np.abs(paper - monolithic)) > 2.0, dict(zip(NODES, paper - monolithic))
