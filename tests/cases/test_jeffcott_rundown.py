"""The jeffcott_rundown check case against an independent integration of the Jeffcott equations
(tests/cases/jeffcott_reference.py: scipy solve_ivp of the textbook equations, sharing no code with the rotor
component), and its slow limit against the steady-state peak (u / m) / (2 zeta) of the textbook; and, on the same
rotor, the rundown case's fatigue content (cases/rundown/fatigue.py: summary.json ``fatigue`` of a scenario that
names ``[results] fatigue_loads``; the counting itself is held against closed forms in tests/master/test_fatigue.py
and the held intervals' against monolithic runs in tests/master/test_held_cycles.py and, slow,
tests/cases/test_rundown_staggered.py)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorcosim
from rotorcosim.master.api import load_scenario, simulate
from rotorcosim.master.observer import fatigue as fg
from tests.cases.jeffcott_reference import rundown

M, K, ZETA, U = 10.0, 4.0e6, 0.02, 1.0e-4


def _peak(res):
    x = res["rotor.X_brg0"]
    r = np.hypot(x[:, 0], x[:, 1])
    j = int(np.argmax(r))
    return r[j], float(np.asarray(res["spool.Omega"]).reshape(len(r), -1)[j, 0]) * 30.0 / np.pi


#: the ramp time [s] of a 6 000 rev/min change at lambda = a / wn^2 = 0.02 (a = 200 pi rad/s / T, wn^2 = k / m =
#: 4e5 s^-2): the fastest rate the crossings are asked to find
T_LAMBDA_002 = 200.0 * np.pi / (0.02 * K / M)


@pytest.mark.parametrize("rpm0, rpm1, duration", [(9000.0, 3000.0, 0.1), (9000.0, 3000.0, 1.0),
                                                  (3000.0, 9000.0, 0.3), (9000.0, 3000.0, T_LAMBDA_002),
                                                  (3000.0, 9000.0, T_LAMBDA_002)])
def test_passage_against_independent_integration(tmp_path, rpm0, rpm1, duration):
    """Rundowns 9000 -> 3000 rev/min in 0.1 s (lambda = a / wn^2 = 0.0157: the peak 23 % below the critical speed)
    and 1 s, a run-up 3000 -> 9000 in 0.3 s from the synchronous state at 3000, and both at lambda = 0.02 (0.0785 s,
    the fastest rate asked for): the summary's crossing has found
    the peak, its whirl within 0.1 % and its speed within 0.2 % of the independent integration's, its time and
    speed those of the sample where the whirl is largest."""
    sc = load_scenario("jeffcott_rundown").set({"spool.speed_rpm": rpm0, "spool.end_speed_rpm": rpm1,
                                                "spool.duration": duration})
    sc.schedule["duration"] = duration
    res = simulate(sc, out=tmp_path / "run", figures=False)
    t, rpm, r = rundown(M, K, ZETA, U, rpm0, rpm1, duration, samples=int(duration * 2e5) + 1)
    j = int(np.argmax(r))
    (c,) = res.summary["crossings"]
    assert c["peak_found"] is True and c["critical_speed_rpm"] == pytest.approx(6039.5)
    assert c["bearings"]["disk"]["peak_whirl_mm"] == pytest.approx(r[j] * 1e3, rel=1e-3)
    assert c["peak_speed_rpm"] == pytest.approx(rpm[j], rel=2e-3)
    assert c["direction"] == ("down" if rpm1 < rpm0 else "up")
    # the time and the speed are those of one sample (the ramp's speed at that time), not of a bin's end
    assert c["peak_speed_rpm"] == pytest.approx(rpm0 + (rpm1 - rpm0) * c["t_s"] / duration, rel=1e-9)
    # a prescribed profile's drive torque does all the work; its step torque over the step's mean speed: the
    # balance closes to round-off
    e = res.summary["energy"]["spool"]
    assert abs(e["residual_pct"]) < 1e-6


def test_synchronous_start_at_the_spool_start_speed(tmp_path):
    """A run that starts at 3000 rev/min starts on that speed's synchronous orbit: its first unbalance force is
    u W0^2 (9.87 N, not the 88.8 N of the 9000 rev/min reference), its orbit radius the textbook steady one, |u W0^2 /
    (k - m W0^2 + i c W0)|; start_synchronous = 0 starts at rest."""
    sc = load_scenario("jeffcott_rundown").set({"spool.speed_rpm": 3000.0, "spool.end_speed_rpm": 3000.0})
    res = simulate(sc, duration=1e-3, figures=False)
    w0 = 3000.0 * np.pi / 30.0
    steady = U * w0 ** 2 / abs(K - M * w0 ** 2 + 1j * 2 * ZETA * np.sqrt(K * M) * w0)
    assert np.hypot(*res["rotor.F_u"][0]) == pytest.approx(U * w0 ** 2, rel=1e-9)
    r = np.hypot(res["rotor.X_brg0"][:, 0], res["rotor.X_brg0"][:, 1])
    # (the model is the textbook rotor to ~1e-4: its shaft mass, support and shear compliance)
    assert r[0] == pytest.approx(steady, rel=1e-3) and r.max() == pytest.approx(steady, rel=1e-3)
    rest = simulate(sc.set({"rotor.start_synchronous": 0}), duration=1e-3, figures=False)
    assert np.all(rest["rotor.X_brg0"][0] == 0.0)


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


# -- the fatigue content of the rundown case ------------------------------------------------------------------
JEFFCOTT = Path(__file__).parents[2] / "scenarios" / "jeffcott_rundown.toml"


def _scenario(tmp_path, extra=""):
    path = tmp_path / "jf.toml"
    path.write_text(f'[scenario]\nextends = "{JEFFCOTT.as_posix()}"\nname = "jf"\n[results]\n'
                    f'fatigue_loads = ["rotor.X_brg0"]\nwoehler_exponent = 4.0\n{extra}')
    return rotorcosim.load_scenario(str(path))


def test_summary_fatigue_is_the_count_of_the_recorded_series(tmp_path):
    """The Jeffcott rotor's run-down (monolithic, 0.1 s from 9 000 rev/min): one cycle of the disk's x and y per
    revolution, and the damage-equivalent load and Miner damage those of the recorded series (every 0.1 ms, the
    observer's own sampling) counted after the run."""
    sc = _scenario(tmp_path, "sn_range_N = 1e-4\n")
    r = rotorcosim.simulate(sc, duration=0.1)
    f = r.summary["fatigue"]
    assert (f["woehler_exponent"], f["reference_cycles"], f["sn_cycles"]) == (4.0, 2e6, 2e6)
    revolutions = np.trapezoid(r["spool.Omega"].ravel(), r.time) / (2 * np.pi)
    for i in (0, 1):
        c = fg.rainflow(r["rotor.X_brg0"][:, i])
        entry = f["loads"][f"rotor.X_brg0[{i}]"]
        assert entry["cycles"] == pytest.approx(revolutions, abs=1.0)
        assert entry["del_N"] == pytest.approx(fg.del_load(c, 4.0, 2e6), rel=1e-3)
        assert entry["miner_damage"] == pytest.approx(fg.miner_damage(c, 4.0, 1e-4, 2e6), rel=4e-3)


def test_without_an_sn_curve_no_miner_damage_and_bad_keys_named(tmp_path):
    sc = _scenario(tmp_path)
    assert rotorcosim.simulate(sc, duration=0.01).summary["fatigue"]["loads"]["rotor.X_brg0[0]"]["miner_damage"] \
        is None
    with pytest.raises(ValueError, match="woehler_exponent"):
        rotorcosim.load_scenario(str(_write(tmp_path, "woehler_exponent = -3.0")))


def _write(tmp_path, line):
    path = tmp_path / "bad.toml"
    path.write_text(f'[scenario]\nextends = "{JEFFCOTT.as_posix()}"\nname = "bad"\n[results]\n{line}\n')
    return path
