"""Convergence study of the thermo-mechanical communication step.

    python bench/bench_convergence.py [--unbalance 2850] [--steps 2e-5 1e-5 5e-6]

Runs the blade-loss system on a shortened staggered timeline (TM 0.15 s with the blade loss at 0.01 s, TO 10 s,
TM 0.1 s, as the paper timeline's) at each communication step and prints every Table 4 result of both bearings, and the largest relative
change between consecutive steps. The scenario's step is acceptable when halving it changes no result by more
than 1 %.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import tempfile
from pathlib import Path

from rotorcosim.master.cli.run import execute, resolve
from rotorcosim.cases.blade_loss.results import apply_unbalance
from rotorcosim.cases.blade_loss.results import RESULT_KEYS as KEYS
from rotorcosim.master.schedule import Interval, Timeline


def timeline(h: float, thermal_step: float) -> Timeline:
    return Timeline([Interval("TM", 0.15, h), Interval("TO", 10.0, thermal_step), Interval("TM", 0.1, h)])


def study(unbalance: float, steps: list[float]) -> dict[float, dict]:
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for h in steps:
            sc = resolve("blade_loss")
            apply_unbalance(sc, unbalance)
            summary = execute(sc, Path(tmp) / f"h{h:g}", figures=False,
                              schedule=timeline(h, float(sc.schedule.get("thermal_step", 0.1))))
            out[h] = summary
            print(f"h = {h:g} s: wall {summary['wall_time_s']:.1f} s", flush=True)
    return out


def rel(a, b):
    if a is None or b is None:
        return None
    scale = max(abs(a), abs(b))
    return 0.0 if scale == 0 else 100.0 * abs(a - b) / scale


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--unbalance", type=float, default=2850.0)
    ap.add_argument("--steps", type=float, nargs="+", default=[2e-5, 1e-5, 5e-6])
    a = ap.parse_args()
    steps = sorted(a.steps, reverse=True)
    res = study(a.unbalance, steps)
    for b in ("0", "5"):
        print(f"\nbearing #{b}")
        print(f"{'result':<26}" + "".join(f"{'h=' + format(h, 'g'):>14}" for h in steps)
              + "".join(f"{'d% ' + format(h1, 'g') + '->' + format(h2, 'g'):>22}" for h1, h2 in zip(steps, steps[1:])))
        worst = {}
        for key in KEYS:
            vals = [res[h]["bearings"][b].get(key) for h in steps]
            diffs = [rel(x, y) for x, y in zip(vals, vals[1:])]
            for (h1, h2), d in zip(zip(steps, steps[1:]), diffs):
                if d is not None:
                    worst[h2] = max(worst.get(h2, 0.0), d)
            print(f"{key:<26}" + "".join(f"{v:>14.5g}" if v is not None else f"{'-':>14}" for v in vals)
                  + "".join(f"{d:>22.3f}" if d is not None else f"{'-':>22}" for d in diffs))
        for h2, w in worst.items():
            print(f"largest change halving to h = {h2:g}: {w:.3f} %")
