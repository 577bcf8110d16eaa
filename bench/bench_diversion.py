"""The windmilling diversion (blade_loss_diversion): the wall time of ``rotorcosim run blade_loss_diversion --out
DIR`` (the rundown and 180 minutes of windmilling with mounts, airframe and fatigue; the goal: at most 5 minutes on
this 2-core machine, warm) and the cost per simulated hour of windmilling against blade_loss_rundown's.

    python bench/bench_diversion.py [--duration S] [--skip-cli] [--skip-cost]

(1) the command as a user runs it, in a process of its own from this checkout (``python -m rotorcosim run
blade_loss_diversion --out TMP``, figures included), after a warm-up run of 0.01 s (numba's caches, the compiled
loop's trampolines): its wall time against the 300 s goal. ``--duration S`` shortens the run (``--duration``).
(2) the cost: each scenario on its automatic schedule in this process, without recorder or figures (its result
observers only; bench_rundown.py's PhaseClock), CPU and wall time booked to the rundown (up to the fuel cut +
cases/rundown/compare.py RUNDOWN_S) and to the windmilling after it: the CPU seconds per simulated hour of
windmilling of each, and their ratio. Over ``--duration`` if given, else each scenario's own (the diversion
10 875 s, the rundown 3 660 s). Run it once, on a quiet machine: the machine is shared.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench_rundown import PhaseClock

from rotorcosim.cases.rundown import compare as rc
from rotorcosim.cases.rundown import results
from rotorcosim.master.api import load_scenario
from rotorcosim.master.scenario.build import build_simulation, schedule_of
from rotorcosim.master.scenario.cycle import cycle_of

CHECKOUT = Path(__file__).resolve().parents[1]
SCENARIO = "blade_loss_diversion"
#: the goal of the command's wall time [s]
GOAL_S = 300.0


def cli(duration: float | None) -> None:
    extra = ["--duration", f"{duration:g}"] if duration else []
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [sys.executable, "-m", "rotorcosim", "run", SCENARIO, "--quiet"]
        subprocess.run(cmd + ["--duration", "0.01", "--no-figures", "--out", str(Path(tmp) / "warm")],
                       cwd=CHECKOUT, check=True)
        t0 = time.perf_counter()
        subprocess.run(cmd + extra + ["--out", str(Path(tmp) / "run")], cwd=CHECKOUT, check=True)
        wall = time.perf_counter() - t0
    what = f"{duration:g} s simulated" if duration else "the scenario's duration"
    print(f"rotorcosim run {SCENARIO} ({what}): {wall:.1f} s wall, warm (goal: at most {GOAL_S:g} s for the whole "
          f"run{'' if duration else (': met' if wall <= GOAL_S else ': NOT met')})")


def windmilling_cost(name: str, duration: float | None) -> dict:
    sc = load_scenario(name)
    split = rc.fuel_cut(sc) + rc.RUNDOWN_S
    clock = PhaseClock(split)
    sim = build_simulation(sc, [*results.observers(sc, cycle_of(sc.schedule)), clock])
    report = sim.run(schedule_of(sc, None, duration))
    d = clock.book.get("windmilling")
    print(f"{name}: {report.t_end:g} s simulated, "
          f"{report.cpu_time_s:.1f} s CPU; windmilling after {split:g} s: "
          + (f"{d['simulated_s']:.0f} s simulated, {d['cpu_s']:.1f} s CPU: {3600.0 * d['cpu_s'] / d['simulated_s']:.1f}"
             f" s CPU per simulated hour ({3600.0 * d['wall_s'] / d['simulated_s']:.1f} s wall)" if d else
             "none (the run ends before)"))
    return d


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=None, help="simulated seconds (default: each scenario's)")
    ap.add_argument("--skip-cli", action="store_true")
    ap.add_argument("--skip-cost", action="store_true")
    args = ap.parse_args(argv)
    try:
        load_scenario(SCENARIO)
    except (ValueError, OSError) as exc:
        print(f"{SCENARIO} is not available here ({exc}): nothing to time")
        return 1
    if not args.skip_cli:
        cli(args.duration)
    if not args.skip_cost:
        div = windmilling_cost(SCENARIO, args.duration)
        run = windmilling_cost("blade_loss_rundown", args.duration)
        if div and run:
            a = div["cpu_s"] / div["simulated_s"]
            b = run["cpu_s"] / run["simulated_s"]
            print(f"cost per simulated hour of windmilling: {SCENARIO} {3600 * a:.1f} s CPU, blade_loss_rundown "
                  f"{3600 * b:.1f} s CPU: {a / b:.2f} times")
    return 0


if __name__ == "__main__":
    sys.exit(main())
