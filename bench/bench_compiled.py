"""Thermo-mechanical system step of the blade-loss system: the compiled path against the generic path, same run.

    python bench/bench_compiled.py [--unbalance 2850] [--seconds 0.02] [--repeat 3]

Both simulations are built from the scenario with the observers of `rotorcosim run` (time-series recorder, steady
windows, peaks), advanced 0.015 s past set-up (kernels compiled or loaded from the disk cache, blade-loss onset at
0.01 s included), then each is timed over --seconds of thermo-mechanical interval, alternately, --repeat times
(the best of each kept: the machine is shared). Prints the wall time per system step of each path, the ratio, the
generic path's profile by component, and the largest relative difference of the two paths' outputs at the end
(0 expected: the same kernels, the same arithmetic).
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import time

import numpy as np

from numba import njit

from rotorcosim.components.kernels import KernelComponent
from rotorcosim.master.cli.run import resolve
from rotorcosim.cases.blade_loss.results import apply_unbalance
from rotorcosim.master.observer.recorder import Recorder
from rotorcosim.master.run.profiling import StepTimer
from rotorcosim.cases.blade_loss.results import observers as result_observers
from rotorcosim.master.scenario.cycle import cycle_of
from rotorcosim.master.scenario.build import build_simulation
from rotorcosim.master.schedule import Interval, Timeline


def build(unbalance: float, engine: str):
    sc = resolve("blade_loss")
    apply_unbalance(sc, unbalance)
    o = sc.outputs
    # in memory: the timed intervals run after the warm-up's end, which closes a recorder's file
    obs = [Recorder(None, list(o["record"]), float(o["record_step"]))]
    obs += result_observers(sc, cycle_of(sc.schedule))
    sim = build_simulation(sc, obs)
    sim.engine_choice = engine
    h = float(sc.schedule["step"])
    t0 = time.perf_counter()
    sim.run(Timeline([Interval("TM", 0.015, h)]))
    return sim, h, time.perf_counter() - t0


def timed(sim, seconds: float, h: float) -> tuple[float, float]:
    """(wall, CPU) seconds per step: the CPU time of this thread is what a shared machine's other processes
    disturb least (the wall time counts the time they hold the cores)."""
    t0, c0 = time.perf_counter(), time.thread_time()
    sim.run_interval("TM", seconds, h)
    n = round(seconds / h)
    return (time.perf_counter() - t0) / n, (time.thread_time() - c0) / n


@njit
def _repeat(kernel, s, p, u, y, t, h, n):
    st = 0
    for i in range(n):
        st = kernel(s, p, u, y, t + i * h, h)
    return st


def kernel_costs(sim, h: float, n: int = 2000) -> str:
    """Each component's compiled kernel alone: n steps from its present state with its present inputs held,
    inside numba (no Python call per step), on a copy of its state (restored afterwards)."""
    lines = [f"{'component':<12} {'us/step':>9}   (kernel alone, {n} steps with the inputs held, CPU time, best of 3)"]
    total = 0.0
    for name in sim.engine.order:
        c = sim.system.components[name]
        if not isinstance(c, KernelComponent):
            continue
        m = sim.engine.mult.get(name, 1)
        snap = c.get_state()
        c.kernel_prepare(m * h)
        args = c.kernel_args()
        _repeat(c.STEP, *args, sim.t, m * h, 1)      # compiled
        dt = float("inf")
        for _ in range(3):   # best of 3, thread CPU time (see timed)
            t0 = time.thread_time()
            _repeat(c.STEP, *args, sim.t, m * h, n)
            dt = min(dt, (time.thread_time() - t0) / n)
        c.set_state(snap)
        total += dt / m
        lines.append(f"{name:<12} {1e6 * dt:>9.2f}" + (f"   (every {m} steps: {1e6 * dt / m:.2f} per system step)"
                                                       if m > 1 else ""))
    lines.append(f"{'sum':<12} {1e6 * total:>9.2f}   per system step")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--unbalance", type=float, default=2850.0)
    ap.add_argument("--seconds", type=float, default=0.02)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    sims = {}
    for engine in ("compiled", "python"):
        sim, h, warm = build(a.unbalance, engine)
        sims[engine] = sim
        print(f"{engine:>8}: set-up + 0.015 s warm-up {warm:.1f} s wall (engines {sim.engines_used})", flush=True)
    best = {"compiled": float("inf"), "python": float("inf")}
    cpu = dict(best)
    for _ in range(a.repeat):
        for engine, sim in sims.items():
            wall, c = timed(sim, a.seconds, h)
            best[engine] = min(best[engine], wall)
            cpu[engine] = min(cpu[engine], c)
    steps = round(a.seconds / h)
    print(f"\nthermo-mechanical system step, best of {a.repeat} x {steps} steps of {h:g} s "
          f"(recording and result observers included), wall and CPU time of the thread:")
    for engine, label in (("python", "generic (python) path:"), ("compiled", "compiled path:        ")):
        print(f"  {label} {1e6 * best[engine]:8.1f} us per step wall, {1e6 * cpu[engine]:8.1f} CPU")
    print(f"  ratio generic / compiled: {best['python'] / best['compiled']:.2f} wall, "
          f"{cpu['python'] / cpu['compiled']:.2f} CPU")
    ya = {f"{n}.{k}": np.array(v) for n, c in sims["compiled"].system.components.items() for k, v in c.y.items()}
    yb = {f"{n}.{k}": np.array(v) for n, c in sims["python"].system.components.items() for k, v in c.y.items()}
    worst = max(float(np.max(np.abs(ya[k] - yb[k]) / np.maximum(np.maximum(np.abs(ya[k]), np.abs(yb[k])),
                                                                  1e-300))) for k in ya)
    print(f"  largest relative difference of the outputs after {a.repeat * 2 * a.seconds + 0.015:g} s: {worst:.3g}")
    print("\ncompiled kernels by component:")
    print(kernel_costs(sims["compiled"], h))
    sim = sims["python"]
    timer = StepTimer(sim.system)
    t0 = time.perf_counter()
    sim.run_interval("TM", a.seconds, h)
    wall = time.perf_counter() - t0
    print(f"\ngeneric path by component ({1e6 * wall / steps:.1f} us per step with the timers):")
    print(timer.table(wall))


if __name__ == "__main__":
    main()
