"""The default blade-loss run (2850 N, the paper's 2-minute staggered timeline): wall time and profile.

    python bench/bench_blade_loss.py [--unbalance 2850] [--profile-seconds 0.05]

Prints (1) the wall time of the full 2-minute run as `rotorcosim run` makes it (recording and result extraction
included), and (2) a profile of the thermo-mechanical step: the wall time inside each component's do_step and in
the master around them, over a thermo-mechanical interval of --profile-seconds after the blade loss.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import tempfile
import time
from pathlib import Path

from rotorcosim.master.cli.run import execute, resolve
from rotorcosim.cases.blade_loss.results import apply_unbalance
from rotorcosim.master.run.profiling import StepTimer
from rotorcosim.master.scenario.build import build_simulation
from rotorcosim.master.schedule import Interval, Timeline


def full_run(unbalance: float) -> dict:
    sc = resolve("blade_loss")
    apply_unbalance(sc, unbalance)
    with tempfile.TemporaryDirectory() as tmp:
        return execute(sc, Path(tmp), figures=True)


def profile(unbalance: float, seconds: float) -> str:
    sc = resolve("blade_loss")
    apply_unbalance(sc, unbalance)
    sim = build_simulation(sc)
    sim.engine_choice = "python"  # the profile by component is the generic loop's (bench_compiled.py: both paths)
    h = float(sc.schedule.get("step", 1e-5))
    sim.run(Timeline([Interval("TM", 0.02, h)]))  # past the blade-loss onset, numba kernels compiled
    timer = StepTimer(sim.system)
    t0 = time.perf_counter()
    sim.run_interval("TM", seconds, h)
    wall = time.perf_counter() - t0
    steps = round(seconds / h)
    return (f"thermo-mechanical step profile over {seconds} s ({steps} steps of {h:g} s): "
            f"{1e6 * wall / steps:.1f} us per system step\n" + timer.table(wall))


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--unbalance", type=float, default=2850.0)
    ap.add_argument("--profile-seconds", type=float, default=0.05)
    ap.add_argument("--skip-full", action="store_true", help="profile only")
    a = ap.parse_args()
    print(profile(a.unbalance, a.profile_seconds), flush=True)
    if not a.skip_full:
        s = full_run(a.unbalance)
        print(f"\nfull 2-minute run ({s['duration_s']:.1f} s simulated, {len(s['timeline'])} intervals): "
              f"wall time {s['wall_time_s']:.1f} s")
        for b, r in s.get("bearings", {}).items():
            print(f"bearing #{b}: " + ", ".join(f"{k}={v:.4g}" for k, v in r.items() if isinstance(v, float)))
