"""Table 6 at the paper's seven unbalance levels: `rotorcosim compare --duration 2 --unbalance F` for each, in one
process, printed as one table (speed-up in wall and CPU time, each timing of the staggered run, the largest
relative error of the Table 4 results against the monolithic run, the load average around the runs).

    python bench/bench_table6_levels.py [--levels paper] [--rounds 1] [--out DIR] [--timing-runs N]

The target: every result within 2 % and a speed-up of at least 12 at every level. The machine's speed
drifts by 10-20 % over seconds, which is why `compare` times the staggered run before and after the monolithic
one (cases/blade_loss/compare.py: --timing-runs, default 6, half before and half after, their mean reported);
--rounds repeats the whole table to show the spread that is left, and the last lines pool every round per level
(the mean of all its monolithic timings over the mean of all its staggered timings).
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import statistics
import tempfile
from pathlib import Path

from rotorcosim.cases.blade_loss.compare import compare
from rotorcosim.cases.blade_loss import LEVELS
from rotorcosim.master.cli.sweep import parse_levels


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", default="paper", help="comma-separated forces [N] or 'paper' (default)")
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--duration", type=float, default=2.0)
    ap.add_argument("--out", default=None, help="keep the comparisons here (default: a temporary folder)")
    ap.add_argument("--timing-runs", type=int, default=None, help="staggered timings per comparison (default: compare's)")
    a = ap.parse_args()
    try:
        levels = parse_levels(a.levels, LEVELS)
    except ValueError as exc:
        ap.error(str(exc).replace("--unbalance", "--levels"))
    if a.rounds < 1:
        ap.error(f"--rounds must be at least 1, got {a.rounds}")
    if a.timing_runs is not None and a.timing_runs < 1:
        ap.error(f"--timing-runs must be at least 1, got {a.timing_runs}")
    keep = Path(a.out) if a.out else None
    ratios = {f: [] for f in levels}
    pooled = {f: ([], []) for f in levels}  # every staggered and monolithic wall time of the level
    with tempfile.TemporaryDirectory() as tmp:
        base = keep or Path(tmp)
        print("round | F_u [N] | speed-up wall (CPU) | staggered wall [s], each timing (the first half before the "
              "monolithic run) | monolithic wall [s] | largest error % | load")
        for r in range(a.rounds):
            for f in levels:
                t = compare(base / f"r{r}_{f:g}N", duration=a.duration, unbalance=f, figures=False, overwrite=True,
                            timing_runs=a.timing_runs)
                runs = t.get("staggered_runs") or {"wall_time_s": [t["wall_time_s"]["staggered"]]}
                load = [x for v in t["load_average"].values() for x in v if x is not None]
                ratios[f].append(t["speedup"])
                pooled[f][0].extend(runs["wall_time_s"])
                pooled[f][1].append(t["wall_time_s"]["monolithic"])
                print(f"{r} | {f:g} | {t['speedup']:.2f} ({t['speedup_cpu'] or float('nan'):.2f}) | "
                      f"{' / '.join(f'{x:.3f}' for x in runs['wall_time_s'])} | {t['wall_time_s']['monolithic']:.2f} | "
                      f"{t['largest_error_pct']:.2f} | {min(load, default=float('nan')):.1f}-"
                      f"{max(load, default=float('nan')):.1f}", flush=True)
    if a.rounds > 1:
        print("pooled over the rounds (mean monolithic / mean staggered wall): " + ", ".join(
            f"{f:g} N {statistics.mean(m) / statistics.mean(st):.2f}" for f, (st, m) in pooled.items()))
    every = [x for v in ratios.values() for x in v]
    print(f"speed-up: lowest {min(every):.2f}, median {statistics.median(every):.2f}, highest {max(every):.2f}; "
          f"levels below 12 in some round: {[f'{f:g}' for f, v in ratios.items() if min(v) < 12] or 'none'}")


if __name__ == "__main__":
    main()
