"""The seven-level blade-loss sweep on a local Dask cluster against the same cases one after another.

    python bench/bench_sweep.py [--duration 24.5] [--workers N]

Prints both wall times and their ratio (serial / Dask), measured in this one process. --duration cuts the paper's
timeline (default 24.5 s: the first two thermo-mechanical intervals and the first thermal-only one, enough for the
ratio; pass 120 for the full 2-minute runs, about 7 times longer).
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import tempfile
from pathlib import Path

from rotorcosim.master.cli.sweep import sweep
from rotorcosim.cases.blade_loss.table5 import PAPER_LEVELS

if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=24.5)
    ap.add_argument("--workers", type=int, default=None)
    a = ap.parse_args()
    levels = list(PAPER_LEVELS)
    with tempfile.TemporaryDirectory() as tmp:
        par = sweep(levels, Path(tmp) / "dask", duration=a.duration, workers=a.workers)
        ser = sweep(levels, Path(tmp) / "serial", duration=a.duration, serial=True)
    print(f"{len(levels)} levels, {a.duration:g} s each: Dask ({par['executed_on']}) {par['wall_time_s']:.1f} s, "
          f"serial {ser['wall_time_s']:.1f} s, ratio serial/Dask {ser['wall_time_s'] / par['wall_time_s']:.2f}")
    for name, info in (("dask", par), ("serial", ser)):
        if info["errors"]:
            print(f"  {name} errors: {info['errors']}")
