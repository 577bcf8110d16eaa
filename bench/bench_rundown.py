"""The rundown (blade_loss_rundown): the cost per simulated second of rundown and of windmilling on the staggered
(automatic) schedule, and the staggered scheme against the monolithic run on a short rundown.

    python bench/bench_rundown.py [--cost-duration 660.01] [--short 12] [--cut 1.01] [--full] [--skip-cost]
                                  [--skip-compare]

(1) cost: the scenario's automatic schedule over --cost-duration (default: the rundown plus 10 minutes of
windmilling, as ``rotorcosim compare blade_loss_rundown``; ~1.5 min of CPU), in this process without recorder or
figures (the result observers only): the CPU and wall time per simulated second of the rundown (release, the
15 s at full speed, the fuel cut and the rundown: up to the fuel cut + cases/rundown/compare.py RUNDOWN_S) and
of the windmilling after it, and per phase (coupled / held). An interval that straddles the split is shared in
proportion to its simulated time.
(2) compare: ``compare_rundown`` with the fuel cut moved to --cut (both spools) over --short seconds (both
crossings and the first thermal-only intervals of the windmilling; ~1 min of CPU): the staggered/monolithic
CPU and wall-time ratios and the largest relative errors. The CPU ratio is the figure on a shared machine (the
wall times hold the other processes' share).
(3) --full: the full run as ``rotorcosim run blade_loss_rundown`` makes it (figures included; ~4 min wall on a
quiet machine): its wall time and timeline. Run it once, not in a loop: the machine is shared.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import json
import tempfile
import time
from pathlib import Path

from rotorcosim.master.api import load_scenario, simulate
from rotorcosim.master.observer.observer import Observer
from rotorcosim.master.scenario.build import build_simulation, schedule_of
from rotorcosim.master.scenario.cycle import cycle_of
from rotorcosim.cases.rundown import compare as rc
from rotorcosim.cases.rundown import results


class PhaseClock(Observer):
    """CPU and wall time of each interval, booked to "rundown" (before ``split`` [s]) and "windmilling" (after),
    and to the interval's phase. Offers the block interface with no signals, so the compiled engine still runs."""

    def __init__(self, split: float):
        self.split = split
        self.book: dict[str, dict[str, float]] = {}

    def interval_start(self, sim, phase, step):
        self.t0, self.cpu0, self.wall0 = sim.t, time.process_time(), time.perf_counter()

    def interval_end(self, sim, used):
        cpu, wall = time.process_time() - self.cpu0, time.perf_counter() - self.wall0
        t0, t1 = used.t_start, used.t_end
        span = max(t1 - t0, 1e-30)
        for part, lo, hi in (("rundown", t0, min(t1, self.split)), ("windmilling", max(t0, self.split), t1)):
            if hi <= lo:
                continue
            f = (hi - lo) / span
            for key in (part, f"{part} {used.phase}"):
                d = self.book.setdefault(key, {"simulated_s": 0.0, "cpu_s": 0.0, "wall_s": 0.0})
                d["simulated_s"] += hi - lo
                d["cpu_s"] += f * cpu
                d["wall_s"] += f * wall

    def block_signals(self, sim):
        return []

    def step_block(self, sim, ks, ts, data):
        pass


def cost(duration: float | None) -> None:
    sc = load_scenario("blade_loss_rundown")
    duration = duration or rc.default_duration(sc)
    split = rc.fuel_cut(sc) + rc.RUNDOWN_S
    clock = PhaseClock(split)
    sim = build_simulation(sc, [*results.observers(sc, cycle_of(sc.schedule)), clock])
    report = sim.run(schedule_of(sc, None, duration))
    print(f"staggered, {duration:g} s simulated (rundown: 0-{split:g} s): {report.cpu_time_s:.1f} s CPU, "
          f"{report.wall_time_s:.1f} s wall")
    for key, d in sorted(clock.book.items()):
        s = d["simulated_s"]
        print(f"  {key:18s} {s:8.2f} s simulated  {d['cpu_s']:7.1f} s CPU  {d['cpu_s'] / s:7.4f} s CPU per "
              f"simulated s  ({d['wall_s'] / s:7.4f} s wall)")


def compare(short: float, cut: float) -> None:
    sc = load_scenario("blade_loss_rundown").set({"spool_pt.t_fuel_cut": cut, "spool_gg.t_fuel_cut": cut})
    with tempfile.TemporaryDirectory() as tmp:
        t = rc.compare_rundown(sc, short, Path(tmp) / "cmp", figures=False)
    cpu, wall = t["cpu_time_s"], t["wall_time_s"]
    print(f"short rundown (fuel cut {cut:g} s, {short:g} s): staggered {cpu['staggered']:.1f} s CPU "
          f"({wall['staggered']:.1f} s wall), monolithic {cpu['monolithic']:.1f} s CPU ({wall['monolithic']:.1f} s "
          f"wall); staggered/monolithic CPU {1 / t['speedup_cpu']:.3f} (speed-up {t['speedup_cpu']:.2f}), wall "
          f"{1 / t['speedup']:.3f}")
    print(f"  largest relative error [%]: {json.dumps(t['largest_error_pct'])}; within 2 %: "
          f"{json.dumps(t['within_2pct'])}")


def full(duration: float | None) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        s = simulate(load_scenario("blade_loss_rundown"), duration=duration, out=Path(tmp) / "full", figures=True,
                     checkpoint_every=None).summary
        wall = time.perf_counter() - t0
    print(f"full run: {s['t_end_s']:.0f} s simulated in {wall:.1f} s wall ({s['cpu_time_s']:.1f} s CPU, "
          f"{s['engine']})")
    phases = rc.phase_totals(s)
    for ph, d in phases.items():
        print(f"  {ph}: {d['intervals']} intervals, {d['simulated_s']:.1f} s simulated, {d['steps']} steps")
    print(json.dumps({"crossings": s.get("crossings"), "energy": s.get("energy"), "speeds": s.get("speeds")},
                     indent=1))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cost-duration", type=float, default=None,
                    help="simulated seconds of the cost run (default: the rundown plus 10 minutes of windmilling)")
    ap.add_argument("--short", type=float, default=12.0, help="simulated seconds of the short comparison")
    ap.add_argument("--cut", type=float, default=1.01, help="fuel cut of the short comparison [s]")
    ap.add_argument("--full", action="store_true", help="also the full run (3660 s simulated, figures)")
    ap.add_argument("--duration", type=float, default=None, help="with --full: cut the full run")
    ap.add_argument("--skip-cost", action="store_true")
    ap.add_argument("--skip-compare", action="store_true")
    args = ap.parse_args(argv)
    if not args.skip_cost:
        cost(args.cost_duration)
    if not args.skip_compare:
        compare(args.short, args.cut)
    if args.full:
        full(args.duration)


if __name__ == "__main__":
    main()
