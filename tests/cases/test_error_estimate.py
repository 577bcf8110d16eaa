"""The staggered scheme's estimated error against the true one: Table 6's protocol (`rotorcosim compare --duration 2
--unbalance F`: 3 TM + 2 TO intervals against one monolithic interval) at the paper's seven levels, from 712 N (no
rub) to 14 252 N (both rub rings rubbing, the film power falling steeply with the oil temperature). The reference
is the monolithic run itself. What it holds: the run's estimate (the largest of its Table 4 results') is never
below the largest true error and at most 3 times it; no temperature's estimate of either bearing is below its true
error (by more than FLOOR_PCT: two errors that small are alike), and none is above 6 times it (the target is 3;
one is above: #0's squeeze-film oil at 8 551 N, 0.26 % against 0.02 % of its 50 K rise, 5.3 times). The results
of the mechanics read as a window's largest value have true errors at 2 s that come mostly from the transient the
staggered mechanics still carry (the release's ringing, which they live only 32 revolutions of the 2 s to damp,
and each restart's own decay); their estimates take it from the window's own unsteadiness (results.unsteadiness:
what does not repeat each cycle beside the bearing's own ball-pass ripple, held on synthetic windows below). Held
here as a guard: none below 0.6 of its true error (measured: 0.70 at the least, #0's inner-race stress at 712 N;
the per-cycle range this measure replaced gave 0.40 there); above 3 times they are reported, not held
(bench/bench_error_estimate.py prints every row, docs/explanation/staggered-scheme.md has the table)."""
from __future__ import annotations

import json

import numpy as np
import pytest

from rotorcosim.cases.blade_loss import LEVELS, error_check, results
from rotorcosim.cases.blade_loss.compare import compare


@pytest.mark.slow   # ~11 s of CPU per level (a 2 s staggered and a 2 s monolithic run), 74 s for the seven (measured)
@pytest.mark.parametrize("level", LEVELS["paper"])
def test_the_estimate_brackets_the_true_error_of_table6(tmp_path, level):
    compare(tmp_path / "c", duration=2.0, unbalance=level, figures=False, timing_runs=1)
    runs = [json.loads((tmp_path / "c" / r / "summary.json").read_text()) for r in ("staggered", "monolithic")]
    rows = error_check.rows(*runs)
    assert {r["key"] for r in rows} >= {"T_inner_race_C", "T_ball_C", "whirl_amplitude_mm", "drag_power_W"}
    big = error_check.largest(rows)
    assert 1.0 <= big["ratio"] <= 3.0, (big, rows)
    assert runs[0]["hold"]["estimated_error_pct"] == big["estimated_pct"]
    temperatures = [r for r in rows if r["key"].startswith("T_")]
    assert len(temperatures) == 8
    for r in temperatures:
        assert r["ratio"] >= 1.0 or r["true_pct"] - r["estimated_pct"] < error_check.FLOOR_PCT, r
        assert r["ratio"] <= 6.0, r
    for r in rows:
        if r["key"] in results.PEAK_KEYS:
            assert r["ratio"] >= 0.6, r


def _window(amplitudes, samples=20):
    """A window of len(amplitudes) cycles of bearing 0: a circular whirl of the given radius in each cycle, the
    film force and the contact load and stresses following it, constant powers."""
    n = len(amplitudes)
    t = np.linspace(0.0, n * 1e-3, n * samples, endpoint=False)
    a = np.repeat(amplitudes, samples)
    ph = 2.0 * np.pi * t / 1e-3
    circle = np.column_stack([a * np.cos(ph), a * np.sin(ph)])
    return {"t": t, "rotor.X_brg0": np.column_stack([circle, np.zeros(len(t))]), "damper0.F_journal": 1e6 * circle,
            "bearing0.Q_max": np.column_stack([1e6 * a, 1e6 * a]), "bearing0.sigma_max": np.column_stack([1e9 * a] * 2),
            "bearing0.P_drag": np.full(len(t), 100.0), "damper0.P_film": np.full(len(t), 10.0), "revolutions": 5.0}


def test_unsteadiness_is_what_does_not_repeat_beside_the_bearings_own_ripple():
    """A window whose cycles repeat is steady (0 for every result read as a largest value). A ringing at 1.8 times
    the cycle's frequency on the whirl (2 % of it, the release's axial mode's ratio) reads as at least 80 % of its
    share of the result for every result that follows the whirl (the 5 cycles' synchronous average takes at most
    0.2 of it: test_synchronous.py). A ripple of the contact load at 11.796 times the cycle's frequency (the
    balls passing) counts as unsteadiness when the bearing does not report its period, and not (below 0.1 % of
    the result, from 1 %) when it does; the whirl has none either way."""
    steady = results.unsteadiness(_window([1e-4] * 5), "0", 100.0, 5)
    assert set(steady) == set(results.PEAK_KEYS) and all(v == pytest.approx(0.0, abs=1e-9) for v in steady.values())
    w = _window([1e-4] * 5, samples=750)
    ring = 1.0 + 0.02 * np.sin(2.0 * np.pi * 1.8 * w["t"] / 1e-3)
    rung = {**w, **{k: v * ring[:, None] for k, v in w.items() if k in ("rotor.X_brg0", "damper0.F_journal",
                                                                     "bearing0.Q_max", "bearing0.sigma_max")}}
    got = results.unsteadiness(rung, "0", 100.0, 5)
    for key in results.PEAK_KEYS:
        assert 0.8 * 2.0 / 1.02 <= got[key] <= 1.2 * 2.0 / 1.02, key
    order = 11.796
    ripple = 1.0 + 0.01 * np.cos(2.0 * np.pi * order * w["t"] / 1e-3)
    rippled = {**w, "bearing0.Q_max": w["bearing0.Q_max"] * ripple[:, None]}
    kept = results.unsteadiness(rippled, "0", 100.0, 5)
    out = results.unsteadiness(rippled, "0", 100.0, 5, ripple=(1e-3 / order,))
    assert kept["max_contact_load_N"] > 0.5 and out["max_contact_load_N"] < 0.1
    assert kept["whirl_amplitude_mm"] == pytest.approx(0.0, abs=1e-9)
    assert out["whirl_amplitude_mm"] == pytest.approx(0.0, abs=1e-9)


def _last_window(sc, schedule, duration):
    """The last 5 revolutions (16 000 rev/min) of a run of ``sc`` recorded at its 5 us TM step, as a window
    (``schedule``: a name, run for ``duration``, or a Timeline of its own length)."""
    import rotorcosim

    sc.outputs["record_step"] = 5e-6
    rec = [f"{p}{k}{q}" for k in (0, 5) for p, q in (("rotor.X_brg", ""), ("damper", ".F_journal"),
                                                      ("bearing", ".Q_max"), ("bearing", ".sigma_max"))]
    res = rotorcosim.simulate(sc, duration=duration if isinstance(schedule, str) else None, schedule=schedule,
                              record=rec, figures=False)
    t = res.time
    sel = t >= t[-1] - 5 * 60.0 / 16000.0 - 1e-9
    return {**{r: res[r][sel] for r in rec}, "t": t[sel]}


def test_unsteadiness_tells_the_staggered_runs_ringing_window_from_a_settled_one():
    """At 712 N, the monolithic run's window at 1 s (settled: the release's ringing decays over half a second)
    against the staggered run's last window at 2 s (its mechanics have lived 32 revolutions of the 2 s and still
    ring). Measured: the settled window's results 0.001-0.061 % unsteady, the ball-pass ripple left out by the
    bearing's own frequencies (with it, #0's and #5's contact loads 0.22 and 0.17 %: the ripple is most of what
    does not repeat each revolution); the staggered window's #0 contact load 0.18 %. Held: below 0.1 %, above
    0.15 % with the ripple, above 0.1 % in the staggered window."""
    import rotorcosim
    from rotorcosim.cases.blade_loss.compare import staggered_timeline
    from rotorcosim.components.bearing.component import BallBearing

    ripple = {}
    sc = rotorcosim.load_scenario("blade_loss_712")
    for k in ("0", "5"):
        b = BallBearing("b", dict(sc.components[f"bearing{k}"].parameters))
        b.setup(0.0)
        ripple[k] = tuple(1.0 / f for f in b.ball_pass_frequencies())
    settled = _last_window(sc, "monolithic", 1.0)
    for k in ("0", "5"):
        u = results.unsteadiness(settled, k, 712.0, 5, ripple[k])
        assert set(u) == set(results.PEAK_KEYS) and max(u.values()) < 0.1, (k, u)
        assert results.unsteadiness(settled, k, 712.0, 5)["max_contact_load_N"] > 0.15, k
    sc = rotorcosim.load_scenario("blade_loss_712")
    ringing = _last_window(sc, staggered_timeline(2.0, sc.schedule["step"], sc.schedule["thermal_step"], 16000.0),
                           2.0)
    assert results.unsteadiness(ringing, "0", 712.0, 5, ripple["0"])["max_contact_load_N"] > 0.1
