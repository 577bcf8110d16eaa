"""The compiled thermo-mechanical loop (master/compiled/runner.py) against the generic loop: one semantics.

The first test compiles the blade-loss system's loop (about a minute on a quiet machine; numba caches it on disk,
so later runs load it)."""
from __future__ import annotations

import numpy as np
import pytest

from rotorcosim.components.bearing.component import BallBearing
from rotorcosim.master.cli.run import resolve
from rotorcosim.cases.blade_loss.results import apply_unbalance
from rotorcosim.master.compiled.choice import CompiledUnavailable
from rotorcosim.master.observer.recorder import Recorder
from rotorcosim.cases.blade_loss.results import observers as result_observers
from rotorcosim.master.scenario.cycle import cycle_of
from rotorcosim.master.scenario.build import build_simulation
from rotorcosim.master.schedule import Interval, Timeline

RTOL = 1e-12


def _blade_loss(engine, folder, reseats, restart_cycles):
    sc = resolve("blade_loss")
    apply_unbalance(sc, 2850.0)
    sc.schedule["restart_cycles"] = restart_cycles
    signals = ["rotor.X_brg0", "bearing0.Q_max", "bearing5.sigma_max", "damper0.P_film", "rubring0.P_rub",
               "thermal0.T_nodes", "thermal5.eps"]
    obs = [Recorder(folder / f"{engine}{restart_cycles}.csv", signals, 2e-5)] + result_observers(
        sc, cycle_of(sc.schedule))
    sim = build_simulation(sc, obs)
    sim.engine_choice = engine
    h = float(sc.schedule["step"])
    # blade loss at 0.01 s, thermal steps every 1 ms; a thermal-only interval (held powers, the bearings'
    # thermal-only drag) and a second thermo-mechanical one that starts with the thermal growths ramped in (the
    # hold's restart, over 2 rotor cycles: longer than the interval) or, restart_cycles = 0, stepped in, the balls
    # re-seated (in Python)
    tl = Timeline([Interval("TM", 0.012, h), Interval("TO", 3.0, 0.1), Interval("TM", 0.004, h)])
    before = len(reseats)
    sim.run(tl)
    return sim, obs, len(reseats) - before


def _rel(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = np.maximum(np.maximum(np.abs(a), np.abs(b)), 1e-300)
    return float(np.max(np.abs(a - b) / scale)) if a.size else 0.0


@pytest.mark.parametrize("restart_cycles", [2.0, 0.0])
def test_compiled_equals_generic_on_the_blade_loss_system(tmp_path, monkeypatch, restart_cycles):
    reseats = []
    original = BallBearing._reseat

    def counted(self, h):
        reseats.append(self.name)
        return original(self, h)

    monkeypatch.setattr(BallBearing, "_reseat", counted)
    runs = {e: _blade_loss(e, tmp_path, reseats, restart_cycles) for e in ("compiled", "python")}
    (cs, cobs, creseat), (ps, pobs, preseat) = runs["compiled"], runs["python"]
    assert cs.engines_used == ["compiled", "compiled"]
    assert ps.engines_used == ["python", "python"]
    if restart_cycles:
        # the restart's offsets were on (restart.Restart) in both: the growths and the two oil temperatures of each bearing
        for sim in (cs, ps):
            ramps = [link.ramp for link in sim.hold.handbacks if link.ramp is not None]
            assert len(ramps) == len(sim.hold.handbacks) == 6 and max(abs(r.delta).max() for r in ramps) > 1e-6
        assert creseat == preseat
    else:
        # the re-seating after the thermal-only interval ran in both (the compiled loop hands that step to Python)
        assert creseat == preseat == 2
    assert cs.t == ps.t
    assert cs.engine.steps_taken == ps.engine.steps_taken
    for name, comp in cs.system.components.items():
        other = ps.system.components[name]
        assert comp.time == other.time, name
        for port, y in comp.y.items():
            assert _rel(y, other.y[port]) <= RTOL, f"{name}.{port}"
        for key, s in comp.state.items():
            assert _rel(s, other.state[key]) <= RTOL, f"{name} state {key}"
    # the recorded samples: same rows, same times, same values
    ca = np.loadtxt(tmp_path / f"compiled{restart_cycles}.csv", delimiter=",", skiprows=1)
    pa = np.loadtxt(tmp_path / f"python{restart_cycles}.csv", delimiter=",", skiprows=1)
    assert ca.shape == pa.shape and ca.shape[0] > 500
    assert _rel(ca, pa) <= RTOL
    # the steady windows and peaks the results come from
    cw, pw = cobs[1].windows, pobs[1].windows
    assert len(cw) == len(pw) == 2
    for a, b in zip(cw, pw):
        assert a.keys() == b.keys()
        for key in a:
            assert _rel(a[key], b[key]) <= RTOL, key
    for k in cobs[2].peak:
        for q in cobs[2].peak[k]:
            a, b = cobs[2].peak[k][q], pobs[2].peak[k][q]
            # None: never happened in the run (no rub, no plastic flow), in both loops alike
            assert (a is None and b is None) or _rel(a, b) <= RTOL, (k, q, a, b)
    # the thermal-only hold (master/manipulator/hold.py) recorded the same windows and cycle means, hence the same held values
    for ch, ph in zip(cs.hold.handoffs, ps.hold.handoffs):
        assert (ch.w.pos, ch.w.count, ch.w.cn) == (ph.w.pos, ph.w.count, ph.w.cn)
        assert _rel(ch.ring, ph.ring) <= RTOL and _rel(ch.w.csum, ph.w.csum) <= RTOL
        assert len(ch.history) == len(ph.history) and len(ch.cycles) == len(ph.cycles) > 0
        for ca_, pa_ in zip(sum(ch.history, []), sum(ph.history, [])):
            assert _rel(ca_[0], pa_[0]) <= RTOL and _rel(ca_[1], pa_[1]) <= RTOL
    assert cs.report.hold.as_dict() == ps.report.hold.as_dict()


def test_components_without_kernels_take_the_generic_loop(tmp_path):
    """The toy system of the multi-rate tests has no compiled kernels: auto runs the generic loop and says why;
    --engine compiled is a clear error."""
    from tests.helpers.systems import two_masses

    from rotorcosim.master.simulation import Simulation

    sim = Simulation(two_masses())
    sim.run(Timeline([Interval("TM", 0.01, 1e-3)]))
    assert sim.engines_used == ["python"]
    assert "has no compiled kernel" in sim.engine_note
    sim = Simulation(two_masses())
    sim.engine_choice = "compiled"
    with pytest.raises(CompiledUnavailable, match="cannot compile the thermo-mechanical interval: component"):
        sim.run(Timeline([Interval("TM", 0.01, 1e-3)]))


@pytest.mark.slow   # ~10-40 s (measured; both loops through the automatic schedule)
def test_automatic_schedule_runs_compiled_and_decides_as_the_generic_loop(tmp_path):
    """The automatic schedule's thermo-mechanical intervals run compiled: its steadiness test gets each chunk's
    rows of the powers it samples (added in the generic loop's order) and is checked at the same base steps (the
    chunks end there), so both loops end the intervals at the same steps for the same reasons, with the same
    results. (The generic loop took ~250 us a step, five times the monolithic run's wall time at 14 252 N.)"""
    from rotorcosim.master.schedule.auto import AutoSchedule

    sims = {}
    for engine in ("compiled", "python"):
        sc = resolve("blade_loss")
        apply_unbalance(sc, 2850.0)
        sim = build_simulation(sc, result_observers(sc, cycle_of(sc.schedule)))
        sim.engine_choice = engine
        h = float(sc.schedule["step"])
        # the test is checked every 3000 base steps (4 rotor cycles, a whole number of thermal steps); a loose
        # tolerance so that it ends intervals early in a short run (it is the decision's step that is compared)
        sim.run(AutoSchedule(1.14, h, 0.1, steady_tolerance=0.5, steady_cycles=1, tm_min=0.005, tm_max=0.05,
                             to_min=0.5, to_max=0.5))
        sims[engine] = sim
    cs, ps = sims["compiled"], sims["python"]
    assert cs.engines_used == ["compiled"] * len(cs.engines_used) and ps.engines_used[0] == "python"
    ctl = [(u.phase, u.steps, u.reason) for u in cs.report.timeline]
    assert ctl == [(u.phase, u.steps, u.reason) for u in ps.report.timeline]
    # both TM intervals before the last ended steady (the test decided, not their maximum of 0.05 s)
    assert [why for p, n, why in ctl if p == "TM"] == ["steady", "steady", "end"], ctl
    assert cs.t == ps.t and cs.engine.steps_taken == ps.engine.steps_taken
    for name, comp in cs.system.components.items():
        for port, y in comp.y.items():
            assert _rel(y, ps.system.components[name].y[port]) <= RTOL, f"{name}.{port}"


@pytest.mark.slow   # 30 ms at the rotor's step in the Python loop: about 20 s of CPU
def test_compiled_equals_generic_with_windows_counted_in_turns(tmp_path):
    """blade_loss_rundown (its cycle counts the turns of spool_pt.theta), the fuel cut at once: the hand-off
    windows, the cycle means that end at each turn and the steady windows are the same in both loops, and span the
    5 turns asked for (the speed falls ~1.5 % over the first interval)."""
    runs = {}
    for engine in ("compiled", "python"):
        sc = resolve("blade_loss_rundown").set({"spool_pt.t_fuel_cut": 0.0, "spool_gg.t_fuel_cut": 0.0})
        obs = result_observers(sc, cycle_of(sc.schedule))
        sim = build_simulation(sc, obs)
        sim.engine_choice = engine
        h = float(sc.schedule["step"])
        sim.run(Timeline([Interval("TM", 0.03, h), Interval("TO", 1.0, 0.1), Interval("TM", 0.004, h)]))
        runs[engine] = (sim, obs)
    (cs, cobs), (ps, pobs) = runs["compiled"], runs["python"]
    assert cs.engines_used == ["compiled", "compiled"] and ps.engines_used == ["python", "python"]
    assert cs.revolutions is not None and cs.engine.steps_taken == ps.engine.steps_taken
    for ch, ph in zip(cs.hold.handoffs, ps.hold.handoffs):
        assert ch.turns is not None and (ch.w.pos, ch.w.count, ch.w.cn) == (ph.w.pos, ph.w.count, ph.w.cn)
        assert _rel(ch.ring, ph.ring) <= RTOL
        for ca_, pa_ in zip(sum(ch.history, []), sum(ph.history, [])):
            assert _rel(ca_[0], pa_[0]) <= RTOL and _rel(ca_[1], pa_[1]) <= RTOL
        assert len(ch.history[0]) == len(ph.history[0]) >= 7     # turns of the first interval: ~7.9
    rep = cs.report.hold.as_dict()
    assert rep == ps.report.hold.as_dict()
    assert rep["window_revolutions"]["asked"] == 5.0
    assert 5.0 <= rep["window_revolutions"]["smallest"] < 5.01
    for a, b in zip(cobs[0].windows, pobs[0].windows):
        assert a.keys() == b.keys() and "revolutions" in a
        for key in a:
            assert _rel(a[key], b[key]) <= RTOL, key
    assert 5.0 <= cobs[0].windows[0]["revolutions"] < 5.02
    for name, comp in cs.system.components.items():
        for port, y in comp.y.items():
            assert _rel(y, ps.system.components[name].y[port]) <= RTOL, f"{name}.{port}"


def test_a_run_resumed_inside_an_interval_counts_the_same_turns(tmp_path, monkeypatch, sigint_at):
    """blade_loss_rundown interrupted (a real SIGINT) inside its first thermo-mechanical interval and resumed from
    its checkpoint: the hold read back counts the turns the resumed run records, not the copy it was saved with
    (a copy whose angle ends at the interruption: its windows would begin ~3 turns early)."""
    import rotorcosim
    from rotorcosim.master.run import checkpoint

    sc = resolve("blade_loss_rundown").set({"spool_pt.t_fuel_cut": 0.0, "spool_gg.t_fuel_cut": 0.0})
    h = float(sc.schedule["step"])
    tl = Timeline([Interval("TM", 0.03, h), Interval("TO", 1.0, 0.1), Interval("TM", 0.004, h)])
    sigint_at(0.02)   # once: the resumed run below goes on undisturbed
    out = tmp_path / "cut"
    with pytest.raises(checkpoint.RunInterrupted):
        rotorcosim.simulate(sc, schedule=tl, out=out, figures=False, checkpoint_every=1e-6)
    restore, bound = checkpoint.ResumePoint.restore, []

    def watched(self, sim):
        restore(self, sim)
        hos = [ho for ho in sim.hold.handoffs if ho.turns is not None]
        bound.append(bool(hos) and sim.hold.revolutions is sim.revolutions
                     and all(ho.turns[0] is sim.revolutions for ho in hos))

    monkeypatch.setattr(checkpoint.ResumePoint, "restore", watched)
    res = rotorcosim.simulate(sc, schedule=tl, out=out, figures=False, resume=True)
    assert 0.0 < res.summary["resumed_from_t_s"] < 0.03
    assert bound and all(bound)
    revs = res.summary["hold"]["window_revolutions"]
    assert revs["asked"] == 5.0 and 5.0 <= revs["smallest"] < 5.01, revs
