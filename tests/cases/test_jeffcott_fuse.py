"""The jeffcott_fuse check case against an independent integration (tests/cases/fuse_reference.py: scipy solve_ivp of
a disk on a breaking support with its own event location, sharing no code with the rotor or the fuse component):
the break time, the support force after the transient, the rundown's peak and its speed; the energy balance over
the break; the fuse's bad inputs as one-line errors."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from rotorcosim.master.api import load_scenario, simulate
from tests.cases.fuse_reference import fuse_run

M, K, C, F_BREAK, K_BROKEN = 10.0, 4.0e6, 252.98, 1500.0, 4.0e5
U_R, U_B, T_B = 1.0e-4, 2.0e-3, 0.01


def _reference(t_end, samples):
    return fuse_run(M, K, C, F_BREAK, K_BROKEN, U_R, U_B, T_B, 5000.0, 500.0, 0.5, 2.0, t_end, samples)


def test_break_time_and_energy_over_the_break(tmp_path):
    """The first 0.1 s (the blade loss at 0.01 s, the break in its transient): the break, the fuse's only event,
    within 10 us of the independent integration's (7.7 us measured: the co-simulation's blade loss enters Newmark's
    step that ends at 0.01 s, half a step, 10 us, early in effect; with the reference's onset moved so, 2.3 us); the
    event's values those of the break load. Energy: the disk's kinetic and strain energy at 0.1 s equal their start
    value plus the unbalance's work, less the damping's and the strain energy the break takes out of the intact
    element's share, (k_intact - k_broken) |x_break|^2 / 2, within 0.5 % of the unbalance's work (nothing is created
    at the break)."""
    sc = load_scenario("jeffcott_fuse")
    sc.outputs["record_step"] = 2e-5
    res = simulate(sc, duration=0.1, out=tmp_path / "run", figures=False, progress=False)
    *_, (t_break,) = _reference(0.03, 3)
    (ev,) = res.summary["events"]
    assert ev["component"] == "fuse" and ev["kind"] == "break"
    assert ev["t_s"] == pytest.approx(t_break, abs=10e-6)
    assert ev["values"]["F_elastic_N"] == pytest.approx(F_BREAK, rel=1e-4)
    assert res.summary["engine"] == "compiled"
    # the time series holds the events too (what the time-history figures mark)
    from rotorcosim.master.observer.series import SeriesFile
    assert SeriesFile(tmp_path / "run" / "timeseries.h5").events() == res.summary["events"]
    t = res.time
    x, v, fu = res["rotor.X_brg0"][:, :2], res["rotor.V_brg0"][:, :2], res["rotor.F_u"]
    broken = np.asarray(res["fuse.broken"]).reshape(len(t), -1)[:, 0]
    assert broken[t < ev["t_s"]].max() == 0.0 and broken[-1] == 1.0
    k = np.where(broken > 0.0, K_BROKEN, K)
    energy = 0.5 * M * (v ** 2).sum(axis=1) + 0.5 * k * (x ** 2).sum(axis=1)
    w_unbalance = np.trapezoid((fu * v).sum(axis=1), t)
    w_damping = np.trapezoid(C * (v ** 2).sum(axis=1), t)
    released = 0.5 * (K - K_BROKEN) * float(np.sum(np.square(ev["values"]["X_m"])))
    residual = energy[-1] - energy[0] - w_unbalance + w_damping + released
    assert released > 0.0
    assert abs(residual) < 5e-3 * w_unbalance


def test_two_stage_breaks_against_independent_integration(tmp_path):
    """A two-stage fuse (--set fuse.stages=2: the soft path breaks again when k_broken |x| reaches 400 N, into
    1.0e5 N/m) on the same disk, against the reference with the same second stage: both breaks within 10 us (7.7 us
    early and 0.8 us late, measured). The first is early by the blade loss's half step (above); with the reference's
    onset moved so, the second is 10.8 us late: the step after each break holds the fuse's new force (the links'
    extrapolation history restarts at an event, master/core/links.restart_history), a lag of that one step. A slope
    through the force's jump carried into the next step would make the orbit 0.6 % larger for a few milliseconds
    and bring the second break 28 us sooner. Each event's values are its stage's load."""
    sc = load_scenario("jeffcott_fuse").set({"fuse.stages": 2, "fuse.break_load_2": 400.0, "fuse.k_broken_2": 1.0e5})
    res = simulate(sc, duration=0.025, figures=False, progress=False)
    *_, breaks = fuse_run(M, K, C, F_BREAK, K_BROKEN, U_R, U_B, T_B, 5000.0, 500.0, 0.5, 2.0, 0.025, 3,
                          break_load_2=400.0, k_broken_2=1.0e5)
    first, second = res.summary["events"]
    assert len(breaks) == 2
    assert first["t_s"] == pytest.approx(breaks[0], abs=10e-6)
    assert second["t_s"] == pytest.approx(breaks[1], abs=10e-6)
    assert (first["values"]["stage"], second["values"]["stage"]) == (1, 2)
    assert first["values"]["F_elastic_N"] == pytest.approx(F_BREAK, rel=1e-4)
    assert second["values"]["F_elastic_N"] == pytest.approx(400.0, rel=1e-4)
    assert np.asarray(res["fuse.broken"]).reshape(-1)[-1] == 2.0


@pytest.mark.slow
def test_against_independent_integration(tmp_path):
    """The whole run (2.5 s; 11 s of CPU, measured: the run in the compiled loop and the reference, slow): the
    mean support force over 0.40-0.50 s within 1 % of the reference's (0.09 % measured), the rundown's peak whirl
    within 1 % (0.06 %) and its speed within 0.5 % (0.04 %); one crossing, labelled with the post-fuse critical
    speed."""
    res = simulate("jeffcott_fuse", out=tmp_path / "run", figures=False, progress=False)
    t, rpm, x, y, vx, vy, _ = _reference(2.5, 250_001)
    sel = (t >= 0.40) & (t <= 0.50)
    f_ref = np.hypot(K_BROKEN * x + C * vx, K_BROKEN * y + C * vy)[sel].mean()
    ts = res.time
    f = res["fuse.F_support"]
    f_run = np.hypot(f[:, 0], f[:, 1])[(ts >= 0.40) & (ts <= 0.50)].mean()
    assert f_run == pytest.approx(f_ref, rel=0.01)
    r = np.where(t > 0.5, np.hypot(x, y), 0.0)
    j = int(np.argmax(r))
    (c,) = res.summary["crossings"]
    assert c["peak_found"] and c["critical_speed_rpm"] == pytest.approx(1909.86)
    assert c["bearings"]["disk"]["peak_whirl_mm"] == pytest.approx(r[j] * 1e3, rel=0.01)
    assert c["peak_speed_rpm"] == pytest.approx(rpm[j], rel=0.005)
    assert [e["component"] for e in res.summary["events"]] == ["fuse"]


def test_the_compiled_loop_locates_the_break_as_the_generic_loop(monkeypatch):
    """The compiled loop stops at the break (the fuse's kernel returns EVENT), the master locates it with the
    generic loop's bisection and goes on compiled: the same event, at the same time, and the same time series as the
    generic loop's, bit for bit; the loop's state is saved before a chunk only while the fuse's indicator is live
    (none after the break)."""
    from rotorcosim.master.compiled import runner as compiled_runner

    saves = []
    save = compiled_runner.Runner._save

    def counted(self, *args):
        saves.append(self.sim.t)
        return save(self, *args)

    monkeypatch.setattr(compiled_runner.Runner, "_save", counted)
    runs = {e: simulate("jeffcott_fuse", duration=0.03, figures=False, progress=False, engine=e)
            for e in ("compiled", "python")}
    c, g = runs["compiled"], runs["python"]
    assert c.summary["engine"] == "compiled" and g.summary["engine"] == "python"
    assert c.summary["events"] == g.summary["events"]
    (ev,) = c.summary["events"]
    for ref in c.signals:
        assert np.array_equal(c[ref], g[ref]), ref
    assert saves and max(saves) < ev["t_s"]


def test_a_python_step_while_the_indicator_is_live_goes_through_the_generic_loop(monkeypatch):
    """The rotor asks for a Python step (status PYTHON: its speed moved past the refactorisation threshold, here a
    rundown from t = 0) while the fuse's indicator is live (a break load never reached): the compiled loop rolls the
    chunk back to that base step, which the generic loop takes, and goes on; the time series are the generic
    loop's, bit for bit, and the roll-backs happened."""
    from rotorcosim.master.compiled import runner as compiled_runner

    restores = []
    restore = compiled_runner.Runner._restore

    def counted(self, *args):
        restores.append(self.sim.t)
        return restore(self, *args)

    monkeypatch.setattr(compiled_runner.Runner, "_restore", counted)
    sc = load_scenario("jeffcott_fuse").set({"fuse.break_load": 1e9, "spool.t_start": 0.0, "spool.duration": 0.2})
    c, g = (simulate(sc, duration=0.03, figures=False, progress=False, engine=e) for e in ("compiled", "python"))
    assert c.summary["engine"] == "compiled" and not c.summary["events"] and restores
    for ref in c.signals:
        assert np.array_equal(c[ref], g[ref]), ref


@pytest.mark.parametrize("value, message", [
    ("fuse.break_load=0", "fuse.break_load must be > 0"),
    ("fuse.k_broken=5e6", "fuse.k_broken must be within [0, k_intact"),
    ("fuse.bumper_clearance=-1e-3", "fuse.bumper_clearance must be >= 0"),
    ("fuse.event_tolerance=1e-4", "fuse.event_tolerance: 0.0001 s must be within (0, 2e-05 s]"),
])
def test_bad_fuse_inputs_are_one_line(tmp_path, value, message):
    out = tmp_path / "o"
    r = subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", "run", "jeffcott_fuse", "--set", value,
                        "--duration", "0.02", "--quiet", "--no-figures", "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert message in r.stderr and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert not out.exists() or not any(out.iterdir())


def test_nan_break_load_is_named(tmp_path):
    """A NaN break load, from the scenario file (the schema refuses it) or a component's parameters (the contract
    does), is named."""
    f = tmp_path / "nan.toml"
    f.write_text('[scenario]\nextends = "jeffcott_fuse"\nname = "nan"\n'
                 '[components.fuse]\nparameters = { break_load = nan }\n')
    with pytest.raises(Exception, match="break_load: must be a finite number, got nan"):
        simulate(str(f), duration=0.001, figures=False, progress=False)
    from rotorcosim.components.contract import ContractError
    from rotorcosim.components.registry import create
    with pytest.raises(ContractError, match=r"fuse\.break_load: value is not finite"):
        create("fuse.support", "fuse", {"k_intact": 4e6, "break_load": float("nan")})


@pytest.mark.parametrize("t_signal", [0.012, 0.025])
def test_a_resumed_run_locates_and_keeps_the_break(tmp_path, sigint_at, t_signal):
    """Interrupted (a real SIGINT) before the break (0.012 s) or after it (0.025 s), then resumed: the break is
    where the uninterrupted run has it, bit for bit, listed once."""
    from rotorcosim.master.run import checkpoint

    whole = simulate("jeffcott_fuse", duration=0.03, figures=False, progress=False)
    fired = sigint_at(t_signal)
    out = tmp_path / "r"
    with pytest.raises(checkpoint.RunInterrupted):
        simulate("jeffcott_fuse", duration=0.03, out=out, figures=False)
    assert fired
    res = simulate("jeffcott_fuse", duration=0.03, out=out, figures=False, resume=True)
    assert res.summary["resumed_from_t_s"] > 0.0
    assert res.summary["events"] == whole.summary["events"]
