"""The prices of the run-time estimate (master/schedule/budget.py, the components' ``step_cost_s`` /
``kernel_step_cost_s``), measured, and the estimate against measured runs.

    python bench/bench_estimate.py

Part 1: CPU seconds per ``do_step`` of each component of the blade-loss system and of the toy system in the
generic Python loop (each component's own time; the rest of the run is the master's, per step and component
step), the FE damper at two meshes. Part 2: the compiled loop's CPU per base step (the slope between a 0.1 s
and a 0.2 s monolithic run). Part 3: the estimate of runs like tests/master/test_estimate.py's against their CPU
time, in this process (warm: the set-up of a fresh process, which the estimate includes, is not paid here, so the
shortest runs read high). CPU time, not wall time: on a loaded machine the wall time of a run is up to 2.5 times
its CPU time; the estimate is for an unloaded machine.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import time

import rotorcosim
from rotorcosim.master.run import profiling
from rotorcosim.master.run.profiling import StepTimer
from rotorcosim.master.scenario.build import build_simulation, schedule_of


def per_component(sc, kind: str, duration: float, engine: str = "python") -> None:
    sim = build_simulation(sc, [])
    sim.engine_choice = engine
    sim.initialise()
    clock = profiling.time.perf_counter
    profiling.time.perf_counter = time.process_time  # each do_step's CPU time
    try:
        timer = StepTimer(sim.system)
        t0 = time.process_time()
        sim.run(schedule_of(sc, kind, duration))
        cpu = time.process_time() - t0
    finally:
        profiling.time.perf_counter = clock
    print(f"\n{sc.name}, {kind} {duration:g} s, {engine} loop: {cpu:.3f} s CPU")
    print(timer.table(cpu))
    steps = sum(u.steps for u in sim.report.timeline)
    master = cpu - sum(timer.seconds.values())
    calls = sum(timer.calls.values())
    print(f"master: {1e6 * master / steps:.1f} us per base step, or {1e6 * master / max(calls, 1):.1f} us per "
          "component step")


def compiled_slope() -> None:
    sc = rotorcosim.load_scenario("blade_loss_2850")
    rotorcosim.simulate(sc, schedule="monolithic", duration=0.01, figures=False)  # warm
    cpu = {}
    for d in (0.1, 0.2):
        cpu[d] = rotorcosim.simulate(sc, schedule="monolithic", duration=d, figures=False).summary["cpu_time_s"]
    steps = (0.2 - 0.1) / 5e-6
    print(f"\ncompiled loop, blade-loss system: {1e6 * (cpu[0.2] - cpu[0.1]) / steps:.1f} us CPU per base step")


def estimates() -> None:
    bl = rotorcosim.load_scenario("blade_loss_2850")
    toy = rotorcosim.load_scenario("toy_thermomechanical")
    cases = [("staggered 24.2 s", bl, {"duration": 24.2}),
             ("monolithic 0.1 s", bl, {"schedule": "monolithic", "duration": 0.1}),
             ("monolithic 0.02 s, Python loop", bl, {"schedule": "monolithic", "duration": 0.02, "engine": "python"}),
             ("FE damper 64 x 32, 0.003 s", bl.swap("damper0", "damper.fe").set({"damper0.n_theta": 64,
                                                                                 "damper0.n_z": 32}),
              {"schedule": "monolithic", "duration": 0.003}),
             ("toy staggered 30 s", toy, {"duration": 30.0})]
    print("\nestimate against the run (CPU), this process:")
    for label, sc, kw in cases:
        s = rotorcosim.simulate(sc, figures=False, **kw).summary
        e = s["estimate"]
        print(f"  {label:34s} estimated {e['wall_s']:6.2f} s ({e['engine']}), ran {s['cpu_time_s']:6.2f} s CPU "
              f"({s['wall_time_s']:6.2f} s wall): ratio {e['wall_s'] / s['cpu_time_s']:.2f}")


def main() -> None:
    bl = rotorcosim.load_scenario("blade_loss_2850")
    per_component(bl, "monolithic", 0.02)
    per_component(bl.swap("damper0", "damper.fe").set({"damper0.n_theta": 64, "damper0.n_z": 32}), "monolithic",
                  0.002)
    per_component(bl.swap("damper0", "damper.fe"), "monolithic", 0.001)
    per_component(rotorcosim.load_scenario("toy_thermomechanical"), "monolithic", 2.0)
    compiled_slope()
    estimates()


if __name__ == "__main__":
    main()
