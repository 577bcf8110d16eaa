"""The rundown (blade_loss_rundown): wall time, cost per simulated second of rundown and of windmilling, and the
staggered scheme against the monolithic run on a shortened rundown.

    python bench/bench_rundown.py [--duration 3660] [--short 60] [--skip-full] [--skip-compare]

(1) the full run as `rotorcosim run blade_loss_rundown` makes it (figures included): wall time, and the wall time
spent in coupled (thermo-mechanical) and held (thermal-only) intervals per simulated second of each (from the
summary's timeline and the run's own interval timing);
(2) the same scenario shortened to --short seconds (the release, the fuel cut at 15 s, the rundown and the start of
windmilling), on its automatic schedule and monolithic (one coupled interval), in this process one after the
other: the largest relative difference of every Table 4 result at the end and of every crossing's peaks, and the
wall-time ratio. On a shared machine the wall times are loaded; the ratio of two runs in one process is the figure.
"""
from __future__ import annotations

import argparse
import json
import math
import tempfile
import time
from pathlib import Path

from rotorcosim.master.api import load_scenario, simulate


def _timed(schedule, duration, out, figures=False):
    t0 = time.perf_counter()
    r = simulate(load_scenario("blade_loss_rundown"), duration=duration, schedule=schedule, out=out,
                 figures=figures, checkpoint_every=None)
    return r.summary, time.perf_counter() - t0


def _phase_costs(summary):
    """Simulated seconds and steps of coupled and held intervals (the timeline)."""
    out = {}
    for iv in summary["timeline"]:
        d = out.setdefault(iv["phase"], {"simulated_s": 0.0, "steps": 0, "intervals": 0})
        d["simulated_s"] += iv["t_end"] - iv["t_start"]
        d["steps"] += iv["steps"]
        d["intervals"] += 1
    return out


def _diffs(a, b):
    """Largest relative difference per result of two summaries' Table 4 results and crossings."""
    worst = {}

    def rel(key, x, y):
        if isinstance(x, (int, float)) and isinstance(y, (int, float)) and math.isfinite(x) and abs(y) > 1e-12:
            worst[key] = max(worst.get(key, 0.0), abs(x - y) / abs(y))

    for k, r in b.get("bearings", {}).items():
        for key, v in r.items():
            rel(f"bearings.{key}", a["bearings"][k].get(key), v)
    for ca, cb in zip(a.get("crossings", []), b.get("crossings", [])):
        rel("crossings.peak_speed_rpm", ca["peak_speed_rpm"], cb["peak_speed_rpm"])
        for loc, r in cb["bearings"].items():
            for key, v in r.items():
                rel(f"crossings.{key}", ca["bearings"][loc][key], v)
    return worst


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=None)
    ap.add_argument("--short", type=float, default=60.0)
    ap.add_argument("--skip-full", action="store_true")
    ap.add_argument("--skip-compare", action="store_true")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        if not args.skip_full:
            s, wall = _timed("scenario", args.duration, Path(tmp) / "full", figures=True)
            costs = _phase_costs(s)
            print(f"full run: {s['duration_s']:.0f} s simulated in {wall:.1f} s wall ({s['engine']})")
            for ph, d in costs.items():
                print(f"  {ph}: {d['intervals']} intervals, {d['simulated_s']:.1f} s simulated, {d['steps']} steps")
            print(json.dumps({"crossings": s.get("crossings"), "energy": s.get("energy"), "speeds": s.get("speeds")},
                             indent=1))
        if not args.skip_compare:
            st, w_st = _timed("scenario", args.short, Path(tmp) / "staggered")
            mono, w_mono = _timed("monolithic", args.short, Path(tmp) / "monolithic")
            d = _diffs(st, mono)
            print(f"shortened run ({args.short:g} s): staggered {w_st:.1f} s wall, monolithic {w_mono:.1f} s wall, "
                  f"ratio {w_mono / w_st:.2f}")
            for k, v in sorted(d.items(), key=lambda kv: -kv[1]):
                print(f"  {k}: {100 * v:.2f} %")


if __name__ == "__main__":
    main()
