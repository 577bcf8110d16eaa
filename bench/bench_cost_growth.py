"""How the cost of a blade-loss run grows: wall time against simulated duration and against the TM step, and the
memory of the paper's 2-minute run.

    python bench/bench_cost_growth.py [--scenario blade_loss_2850] [--skip-memory]

1. Monolithic (one TM interval) runs of 0.02, 0.04 and 0.08 s at the scenario's TM step: wall time per simulated
   second should be the same for each (cost linear in duration).
2. Monolithic 0.02 s at the step, half of it and a quarter of it: wall time per step should be the same (cost
   linear in the number of steps).
3. The scenario's own 2-minute timeline in a fresh process (``rotorcosim run --no-figures``): its wall time and
   its peak resident memory (the recorder streams to disk, so memory should not grow with the duration).
Runs 1 and 2 share this process (caches warm after a first untimed run); no figures are drawn.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from rotorcosim import scenarios
from rotorcosim.master.cli.run import execute
from rotorcosim.master.scenario.build import load_scenario
from rotorcosim.master.schedule import Interval, Timeline


def timed(name: str, duration: float, step: float, folder: Path) -> float:
    sc = load_scenario(scenarios.path(name))
    t0 = time.perf_counter()
    execute(sc, folder, schedule=Timeline([Interval("TM", duration, step)]), figures=False, quiet=True)
    return time.perf_counter() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", default="blade_loss_2850")
    ap.add_argument("--skip-memory", action="store_true", help="skip the 2-minute run in a fresh process")
    a = ap.parse_args(argv)
    h = float(load_scenario(scenarios.path(a.scenario)).schedule["step"])
    with tempfile.TemporaryDirectory(prefix="bench_growth_") as tmp:
        out = Path(tmp)
        timed(a.scenario, 0.005, h, out / "warm")           # caches and compilation out of the way
        print(f"wall time against simulated duration (monolithic, step {h:g} s):")
        base = None
        for d in (0.02, 0.04, 0.08):
            w = timed(a.scenario, d, h, out / f"d{d}")
            per = w / d
            base = base or per
            print(f"  {d:5.2f} s simulated: {w:6.2f} s wall, {per:6.1f} s per simulated s ({per / base:.2f} x the first)")
        print("wall time against the TM step (0.02 s simulated):")
        base = None
        for f in (1, 2, 4):
            step = h / f
            w = timed(a.scenario, 0.02, step, out / f"h{f}")
            per = w / round(0.02 / step) * 1e6
            base = base or per
            print(f"  step {step:.3g} s: {w:6.2f} s wall, {per:6.1f} us per step ({per / base:.2f} x the first)")
        if a.skip_memory:
            return 0
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", "run", a.scenario, "--no-figures",
                               "--quiet", "--out", str(out / "full")], capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if proc.returncode:
            print(f"2-minute run failed: {proc.stderr.strip()[-400:]}")
            return 1
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024  # kB on Linux
        size = sum(p.stat().st_size for p in (out / "full").iterdir()) / 1e6
        print(f"2-minute timeline in a fresh process: {wall:.1f} s wall (imports and set-up included), "
              f"peak resident memory {peak:.0f} MB, result files {size:.1f} MB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
