"""The compiled runner (master/compiled/runner.py) is built once per run and reused by every thermo-mechanical interval
of a staggered run (its plan, flat port array, buffers and packed containers): the same results, to the bit, as a
runner built anew for each interval, through thermal-only intervals, the hold's probes (which replace the
producers' arrays) and the bearings' re-seating in Python."""
from __future__ import annotations

import numpy as np
import pytest

from rotorcosim.master.compiled import runner as compiled
from rotorcosim.master.cli.run import resolve
from rotorcosim.cases.blade_loss.results import WINDOWS_KEPT, apply_unbalance
from rotorcosim.master.observer.recorder import Recorder
from rotorcosim.cases.blade_loss.results import observers as result_observers
from rotorcosim.master.scenario.cycle import cycle_of
from rotorcosim.master.scenario.build import build_simulation
from rotorcosim.master.schedule import Interval, Timeline

SIGNALS = ["rotor.X_brg0", "bearing0.Q_max", "bearing5.P_drag", "damper0.P_film", "rubring0.P_rub",
           "thermal0.T_nodes", "thermal5.eps"]


def _run(restart_cycles):
    sc = resolve("blade_loss")
    apply_unbalance(sc, 2850.0)
    sc.schedule["restart_cycles"] = restart_cycles
    rec = Recorder(None, SIGNALS, 1e-5)
    obs = [rec] + result_observers(sc, cycle_of(sc.schedule))
    sim = build_simulation(sc, obs)
    sim.engine_choice = "compiled"
    h = float(sc.schedule["step"])
    sim.run(Timeline([Interval("TM", 0.012, h), Interval("TO", 0.3, 0.1), Interval("TM", 0.004, h),
                      Interval("TO", 0.3, 0.1), Interval("TM", 0.004, h)]))
    return sim, rec.data(), obs[1].windows


@pytest.mark.parametrize("restart_cycles", [2.0, 0.0])
def test_one_runner_per_run_equals_one_per_interval(monkeypatch, restart_cycles):
    built = []
    plan = compiled.Plan

    def counted(*args, **kwargs):
        built.append(1)
        return plan(*args, **kwargs)

    monkeypatch.setattr(compiled, "Plan", counted)
    reused, data, windows = _run(restart_cycles)
    assert reused.engines_used == ["compiled"] * 3 and len(built) == 1
    monkeypatch.setattr(compiled, "_plan_key", lambda sim, mult: object())  # never equal: a runner per interval
    anew, data2, windows2 = _run(restart_cycles)
    assert len(built) == 1 + 3
    assert set(data) == set(data2) and len(data["time"]) > 1500
    for key in data:
        assert np.array_equal(data[key], data2[key]), key
    assert len(windows) == len(windows2) == WINDOWS_KEPT == 2   # of the three TM intervals, the last two kept
    for w, w2 in zip(windows, windows2):
        assert all(np.array_equal(w[k], w2[k]) for k in w), [k for k in w if not np.array_equal(w[k], w2[k])]
    for name, comp in reused.system.components.items():
        other = anew.system.components[name]
        for d, d2 in ((comp.state, other.state), (comp.y, other.y)):
            assert all(np.array_equal(d[k], d2[k]) for k in d), name
    assert reused.report.hold.as_dict() == anew.report.hold.as_dict()
