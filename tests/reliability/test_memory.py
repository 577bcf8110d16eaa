"""Memory does not grow with a run's length: a file run ten times longer peaks within 10 % of the shorter one,
for ``run``, ``sweep`` (per worker) and ``compare`` (bench/bench_memory.py measures the same, printing the
figures). The reference is the shorter run of the same command in fresh processes: a run that kept its series in
memory, or leaked per step, would grow with the steps taken (the 0.5 s runs take 5-10 times the steps of the
0.05 s ones)."""
from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("bench_memory", ROOT / "bench" / "bench_memory.py")
bench_memory = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench_memory)


@pytest.mark.parametrize("command", [pytest.param(c, marks=pytest.mark.slow) if c == "sweep" else c   # sweep: ~33 s of CPU
                                     for c in bench_memory.COMMANDS])
def test_ten_times_longer_peaks_within_ten_percent(command, tmp_path):
    f = bench_memory.measure(0.05, tmp_path, [command])[command]
    assert f["short_MB"] > 50.0   # a real measure (the process with the blade-loss system loaded)
    assert f["ratio"] < 1.10, f
