"""The load cycles of a staggered run (master/observer/held_cycles.py): the held intervals' cycles extrapolated
from the hold's window, against a monolithic run that simulates every cycle.

The toy thermo-mechanical system (scenarios/toy_thermomechanical.toml: a forced oscillator at 45 Hz whose damping
falls as its thermal node heats) on its timeline, 0.3 s coupled then 4.7 s held, twice: 94 % of its cycles fall in
held intervals. Its thermal node starts at the steady temperature it heats to (SETTLED), so that the response the
hold stands for is steady, as a windmilling engine's; the oscillator steps once per 1 ms (RK4 at omega h = 0.31). The engine's version, 10 minutes of windmilling after the rundown, is the slow test of
tests/cases/test_rundown_staggered.py (the rundown comparison's ``fatigue``)."""
from __future__ import annotations

import math

import numpy as np
import pytest

import rotorcosim
from rotorcosim.master.observer import fatigue as fg
from rotorcosim.master.observer import held_cycles as hc
from rotorcosim.master.scenario.build import build_simulation, schedule_of
from rotorcosim.master.scenario.cycle import cycle_of

DURATION = 10.0
#: the node's time constant cut to 1 s (R = 0.1 K/W) and its start at the steady temperature it reaches (306.74 K,
#: measured on a 30 s run): the held intervals hold a steady state, as over an engine's windmilling
SETTLED = {"node.R": 0.1, "node.T_init": 306.74, "osc.max_substep": 1e-3}


def _observed(sc, schedule):
    obs = hc.LoadCycles(["osc.x"], cycle_of(sc.schedule), 5.0, 1e-3)
    build_simulation(sc, [obs]).run(schedule_of(sc, schedule, DURATION))
    return obs


def test_staggered_damage_equivalent_loads_within_2pct_of_monolithic():
    """Damage-equivalent loads (m = 3, 5, 10) of the staggered run within 2 % of the monolithic run's (measured
    0.02-0.05 %), the cycle count within 0.5 %; without the held intervals' cycles the staggered count would miss
    94 % of them."""
    sc = rotorcosim.load_scenario("toy_thermomechanical").set(SETTLED)
    obs = _observed(sc, None)
    st, mono = obs.counts()["osc.x"], _observed(sc, "monolithic").counts()["osc.x"]
    assert mono.n.sum() == pytest.approx(45.0 * DURATION, abs=1.0)
    assert st.n.sum() == pytest.approx(mono.n.sum(), rel=5e-3)
    for m in (3.0, 5.0, 10.0):
        assert fg.del_load(st, m, 1e7) == pytest.approx(fg.del_load(mono, m, 1e7), rel=0.02)
    extrapolated = sum(c.n.sum() for c in obs.held["osc.x"])
    assert extrapolated > 0.9 * st.n.sum()


def test_the_count_of_recorded_samples_is_the_observers():
    """The same run's recorded series (timeseries: osc.x, phase) counted by staggered_counts, the angle 2 pi 45 t:
    the same cycles as the observer counted while it ran."""
    sc = rotorcosim.load_scenario("toy_thermomechanical").set(SETTLED)
    r = rotorcosim.simulate(sc, duration=DURATION)
    x, phase = r["osc.x"].ravel(), np.asarray(r.phase)
    rec = hc.staggered_counts(x, phase == "TO", 2.0 * math.pi * 45.0 * r.time, 5.0)
    obs = _observed(sc, None).counts()["osc.x"]
    assert rec.n.sum() == pytest.approx(obs.n.sum(), rel=5e-3)
    assert fg.del_load(rec, 4.0, 1e7) == pytest.approx(fg.del_load(obs, 4.0, 1e7), rel=2e-3)


def test_stream_counts_as_the_whole_series():
    """Chunks of any size (one sample at a time too) give the rainflow count of the whole series: the same cycles,
    their ranges to 1e-5 (a chunk's turning points are found on its own load classes)."""
    rng = np.random.default_rng(1)
    t = np.arange(0.0, 20.0, 1e-3)
    y = np.sin(2 * np.pi * 45 * t) * (1 + 0.3 * np.sin(0.3 * t)) + 0.05 * rng.standard_normal(t.size)
    for chunk, n in ((4096, y.size), (7, 5000), (1, 2000)):
        whole = fg.rainflow(y[:n])
        s = hc.Stream()
        for i in range(0, n, chunk):
            s.add(y[i:min(i + chunk, n)])
        c = s.counts()
        assert c.n.sum() == whole.n.sum()
        assert fg.del_load(c, 3.0, 1e7) == pytest.approx(fg.del_load(whole, 3.0, 1e7), rel=1e-5)
