"""Interrupt the 2-minute blade-loss run and resume it: is the result bit-identical, and what does it cost?

    python bench/bench_resume.py [--scenario blade_loss_2850] [--at 48.1] [--out /tmp/bench_resume]

Runs the scenario uninterrupted, then again with a real SIGINT when the simulated time passes ``--at`` (by default
in the middle of the third thermo-mechanical interval), then ``--resume``; prints the wall times, the checkpoints
taken and their size and save time, and compares every dataset of the time series and every result of the
summary bit for bit.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import os
import shutil
import signal
import time
from pathlib import Path

import h5py
import numpy as np

from rotorcosim import scenarios
from rotorcosim.master.run import checkpoint
from rotorcosim.master.cli.run import execute
from rotorcosim.master.observer.progress import Progress
from rotorcosim.master.scenario.build import load_scenario


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenario", default="blade_loss_2850")
    ap.add_argument("--at", type=float, default=48.1, help="simulated time of the SIGINT [s]")
    ap.add_argument("--out", default="/tmp/bench_resume")
    a = ap.parse_args()
    base = Path(a.out)
    shutil.rmtree(base, ignore_errors=True)

    def sc():
        return load_scenario(scenarios.path(a.scenario))

    saves = []
    original_save = checkpoint.Checkpointer.save

    def timed_save(self, sim, k, next_interval=False):
        t0 = time.perf_counter()
        original_save(self, sim, k, next_interval)
        if self.path is not None and self.path.exists():
            saves.append((time.perf_counter() - t0, self.path.stat().st_size))

    checkpoint.Checkpointer.save = timed_save
    t0 = time.perf_counter()
    ref = execute(sc(), base / "ref", figures=False)
    wall_ref = time.perf_counter() - t0
    n_ref_saves = len(saves)

    original_step = Progress.step
    fired = []

    def step(self, sim, t):
        if not fired and t >= a.at:
            fired.append(t)
            os.kill(os.getpid(), signal.SIGINT)
        original_step(self, sim, t)

    Progress.step = step
    t0 = time.perf_counter()
    try:
        execute(sc(), base / "run", figures=False)
    except checkpoint.RunInterrupted as exc:
        print(f"interrupted: {exc}")
    wall_first = time.perf_counter() - t0
    Progress.step = original_step
    t0 = time.perf_counter()
    got = execute(sc(), base / "run", figures=False, resume=True)
    wall_resume = time.perf_counter() - t0

    same_series = True
    with h5py.File(base / "ref/timeseries.h5") as f, h5py.File(base / "run/timeseries.h5") as g:
        for k in f:
            if not np.array_equal(f[k][...], g[k][...]):
                same_series = False
                print(f"time series differ: {k}")
        rows = f["time"].shape[0]
    same_results = got["bearings"] == ref["bearings"]
    print(f"scenario {a.scenario}: uninterrupted {wall_ref:.1f} s wall ({ref['t_end_s']:.4g} s simulated)")
    print(f"interrupted at t = {fired[0]:.6g} s after {wall_first:.1f} s wall; resumed from "
          f"t = {got['resumed_from_t_s']:.6g} s, {wall_resume:.1f} s wall (set-up included)")
    print(f"checkpoints in the uninterrupted run: {n_ref_saves}, each {np.mean([s for _, s in saves]) / 1024:.0f} KiB, "
          f"save time mean {1e3 * np.mean([t for t, _ in saves]):.1f} ms, max {1e3 * max(t for t, _ in saves):.1f} ms")
    print(f"time series ({rows} rows, every dataset) bit-identical: {same_series}; Table 4 results bit-identical: "
          f"{same_results}; timeline identical: {got['timeline'] == ref['timeline']}")


if __name__ == "__main__":
    main()
