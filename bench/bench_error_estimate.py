"""The staggered scheme's estimated error against its true error, result by result (master/manipulator/error_estimate.py,
cases/blade_loss/results.estimated_errors, cases/blade_loss/error_check.py).

    python bench/bench_error_estimate.py [--levels paper] [--duration 2] [--out DIR] [--monolithic-from DIR]
    python bench/bench_error_estimate.py --pair STAGGERED_DIR MONOLITHIC_DIR [--pair ...] [--label NAME ...]

The first form runs `rotorcosim compare --duration D --unbalance F` (Table 6 protocol: 3 TM + 2 TO intervals
against one monolithic interval) at each level, the second reads pairs of run folders made before (the 2-minute
main job: `rotorcosim run --out A` and `rotorcosim run --schedule monolithic --out B`; a rundown comparison's
staggered/ and monolithic/ folders). ``--monolithic-from DIR`` reuses the monolithic runs an earlier ``--out DIR``
kept (DIR/<F>N/monolithic), so that only the staggered runs are made again. Prints per run and result the
estimate, the true error in the same terms (temperatures: percent of the rise above the initial temperature) and
their ratio (both floored at 0.05 %), then per run the largest estimate against the largest true error, then the
same rows as one markdown table, result by result and run by run ("estimated / true (ratio)"; ``--label`` names
the pairs' columns). The target: every ratio of a run's largest in [1, 3].
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import json
import tempfile
from pathlib import Path

from rotorcosim.cases.blade_loss import LEVELS
from rotorcosim.cases.blade_loss import error_check
from rotorcosim.cases.blade_loss.compare import compare
from rotorcosim.master.cli.sweep import parse_levels


def table(label: str, staggered: dict, monolithic: dict, cells: dict) -> dict:
    rows = error_check.rows(staggered, monolithic)
    for r in rows:
        cells.setdefault(f"#{r['bearing']} {r['key']}", {})[label] = (
            f"{r['estimated_pct']:.3f} / {r['true_pct']:.3f} ({r['ratio']:.2f})")
    for r in rows:
        print(f"{label} | #{r['bearing']} {r['key']} | {r['estimated_pct']:.3f} | {r['true_pct']:.3f} | "
              f"{r['ratio']:.2f}")
    big = error_check.largest(rows)
    big["within"] = sum(1.0 <= r["ratio"] <= 3.0 for r in rows)
    big["below"] = sum(r["ratio"] < 1.0 for r in rows)
    big["results"] = len(rows)
    return big


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", default="paper")
    ap.add_argument("--duration", type=float, default=2.0)
    ap.add_argument("--out", default=None, help="keep the comparisons here (default: a temporary folder)")
    ap.add_argument("--monolithic-from", default=None, metavar="DIR",
                    help="reuse the monolithic runs an earlier --out DIR kept")
    ap.add_argument("--pair", nargs=2, action="append", metavar=("STAGGERED", "MONOLITHIC"), default=[])
    ap.add_argument("--label", action="append", default=[], help="a --pair's column name (in their order)")
    a = ap.parse_args()
    print("run | result | estimated % | true % | ratio")
    big, cells = {}, {}
    if a.pair:
        for i, (s, m) in enumerate(a.pair):
            load = [json.loads((Path(d) / "summary.json").read_text()) for d in (s, m)]
            label = a.label[i] if i < len(a.label) else s
            big[label] = table(label, *load, cells)
    else:
        levels = parse_levels(a.levels, LEVELS)
        with tempfile.TemporaryDirectory() as tmp:
            base = Path(a.out) if a.out else Path(tmp)
            for f in levels:
                d = base / f"{f:g}N"
                mono = Path(a.monolithic_from) / f"{f:g}N" / "monolithic" if a.monolithic_from else None
                compare(d, duration=a.duration, unbalance=f, figures=False, overwrite=True,
                        timing_runs=None if mono else 1, monolithic=mono)
                load = [json.loads((run / "summary.json").read_text())
                        for run in (d / "staggered", mono or d / "monolithic")]
                big[f"{f:g} N"] = table(f"{f:g} N", *load, cells)
    print("\nrun | largest estimate % | largest true % | ratio | results within 1-3x / below / all")
    for label, b in big.items():
        print(f"{label} | {b['estimated_pct']:.3f} | {b['true_pct']:.3f} | {b['ratio']:.2f} | {b['within']} / "
              f"{b['below']} / {b['results']}")
    print("\n| result | " + " | ".join(big) + " |\n|---|" + "---|" * len(big))
    for key, row in cells.items():
        print(f"| {key} | " + " | ".join(row.get(label, "") for label in big) + " |")


if __name__ == "__main__":
    main()
