"""The staggered scheme's estimated error against the true one: Table 6's protocol (`rotorcosim compare --duration 2
--unbalance F`: 3 TM + 2 TO intervals against one monolithic interval) at the paper's seven levels, from 712 N (no
rub) to 14 252 N (both rub rings rubbing, the film power falling steeply with the oil temperature). The reference
is the monolithic run itself. What it holds: the run's estimate (the largest of its Table 4 results') is never
below the largest true error and at most 3 times it; no temperature's estimate of either bearing is below its true
error (by more than FLOOR_PCT: two errors that small are alike), and none is above 6 times it (the target is 3;
one is above: #0's squeeze-film oil at 8 551 N, 0.26 % against 0.02 % of its 50 K rise, 5.3 times). The results
of the mechanics are reported, not held: their true errors at 2 s come mostly from the transient each restart
starts in the 8-revolution TM intervals (a decay of some 12 revolutions' time constant, with a ringing on top),
which their estimates take from the window's own unsteadiness (results.unsteadiness, held on synthetic windows
below) only as far as the window shows it
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


def test_unsteadiness_of_a_window_is_the_range_of_its_cycles():
    """A window whose cycles repeat is steady (0 for every result read as a largest value). One whose cycles' whirl
    rings about a steady 1.00 (x 1e-4 m: 1.00, 1.02, 0.98, 1.01, 0.99) reads its crest, 1.02, 0.02 / 1.02 above the
    steady value; its estimate, the range of its cycles, 0.04 / 1.02, holds it. One whose cycles decay towards a
    steady 1.00 (1.00 + 0.05 q^k, q = 0.8) reads its first cycle, 0.05 / 1.05 above the steady value, of which the
    range shows 0.05 (1 - q^4) / 1.05 (the part of the decay within the window); the same for the results that
    follow the whirl; the powers (means) are not judged by it."""
    steady = results.unsteadiness(_window([1e-4] * 5), "0", 100.0, 5)
    assert set(steady) == set(results.PEAK_KEYS) and all(v == pytest.approx(0.0, abs=1e-9) for v in steady.values())
    ringing = results.unsteadiness(_window([1.00e-4, 1.02e-4, 0.98e-4, 1.01e-4, 0.99e-4]), "0", 100.0, 5)
    for key in results.PEAK_KEYS:
        assert ringing[key] == pytest.approx(100.0 * 0.04 / 1.02, rel=1e-6), key
        assert ringing[key] >= 100.0 * 0.02 / 1.02   # the crest's distance from the steady value
    q = 0.8
    decay = results.unsteadiness(_window([1e-4 * (1.0 + 0.05 * q ** k) for k in range(5)]), "0", 100.0, 5)
    for key in results.PEAK_KEYS:
        assert decay[key] == pytest.approx(100.0 * 0.05 * (1.0 - q ** 4) / 1.05, rel=1e-6), key
