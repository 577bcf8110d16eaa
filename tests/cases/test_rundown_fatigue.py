"""The rundown case's fatigue content (cases/rundown/fatigue.py): summary.json ``fatigue`` of a scenario that names
``[results] fatigue_loads``, its keys checked, and the load spectra figure. The counting itself is held against
closed forms in tests/master/test_fatigue.py, the held intervals' against a monolithic run in
tests/master/test_held_cycles.py and tests/cases/test_rundown_staggered.py (slow)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorcosim
from rotorcosim.master.observer import fatigue as fg

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
