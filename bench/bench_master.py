"""Master benchmarks: overhead per component step (trivial components) and the toy staggered speed-up.

    python bench/bench_master.py [--blade-loss] [--ecos-steps N]

Prints: the master's overhead per component step (a do-nothing component, Gauss-Seidel, 2 components
exchanging one scalar each way), the wall-time ratio monolithic / staggered for the toy thermo-mechanical
system (tests/master/test_multirate_staggered.py), and the step rate of one exported SSP (the toy system; with
``--blade-loss`` also the paper's nine-FMU system) run for the same number of fixed steps in our master and in
the Ecos engine (ecospy; needs Debian's libtbb12), set-up excluded, all measured in this one process.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import sys
import tempfile
import time
from pathlib import Path


from rotorcosim.components.contract import Component, Variable
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation
from rotorcosim.master.core.system import Connection, System

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "master"))


class Nothing(Component):
    variables = (Variable("u", "input"), Variable("y", "output"))

    def do_step(self, t, h):
        pass


def master_overhead(n_steps=100_000):
    s = System({"a": Nothing("a"), "b": Nothing("b")}, [Connection("a.y", "b.u"), Connection("b.y", "a.u")])
    sim = Simulation(s)
    t0 = time.perf_counter()
    sim.run(Timeline([Interval("TM", n_steps * 1e-5, 1e-5)]))
    dt = time.perf_counter() - t0
    bare = Nothing("c")
    t0 = time.perf_counter()
    for k in range(n_steps):
        bare.do_step(k * 1e-5, 1e-5)
    call = (time.perf_counter() - t0) / n_steps
    return dt / (2 * n_steps), call


def toy_ratio():
    from test_multirate_staggered import staggered_vs_monolithic

    mono, stag, rep_m, rep_s = staggered_vs_monolithic()
    T_m = mono.components["node"].y["T"][0] - 303.15
    T_s = stag.components["node"].y["T"][0] - 303.15
    return rep_m.wall_time_s, rep_s.wall_time_s, T_m, T_s


def ecos_vs_master_rate(ssp: Path, n: int) -> tuple[float, float]:
    """Steps per second of ``ssp`` over ``n`` fixed steps at its default step: (our master, Ecos)."""
    from ecospy import EcosSimulation

    from rotorcosim.master.scenario.ssp import read_ssp
    from rotorcosim.master.scenario.build import build_simulation

    sc = read_ssp(ssp)
    sc.algorithm = {"kind": "jacobi", "order": sc.algorithm.get("order")}  # Ecos exchanges Jacobi-style
    h = float(sc.schedule.get("step", 1e-3))
    sim = build_simulation(sc, [])
    sim.initialise()
    t0 = time.perf_counter()
    sim.run(Timeline([Interval("TM", n * h, h)]))
    ours = n / (time.perf_counter() - t0)
    with EcosSimulation(ssp_path=str(ssp), step_size=h) as es:
        es.init(parameter_set="initialValues")
        t0 = time.perf_counter()
        for _ in range(n):
            es.step()
        ecos = n / (time.perf_counter() - t0)
        es.terminate()
    return ours, ecos


def ecos_comparison(blade_loss: bool, n: int) -> None:
    try:
        import ecospy  # noqa: F401 - only whether it imports
    except Exception as exc:  # not installed, or its library does not load (libtbb12 missing)
        print(f"Ecos vs our master: skipped, ecospy unavailable ({exc})")
        return
    from rotorcosim import scenarios
    from rotorcosim.master.scenario.ssp import write_ssp
    from rotorcosim.master.scenario.build import load_scenario

    names = ["toy_thermomechanical"] + (["blade_loss"] if blade_loss else [])
    with tempfile.TemporaryDirectory(prefix="bench_master_") as tmp:
        for name in names:
            ssp = write_ssp(load_scenario(scenarios.path(name)), Path(tmp) / f"{name}.ssp")
            ours, ecos = ecos_vs_master_rate(ssp, n)
            print(f"same SSP ({name}, {n} fixed steps, set-up excluded): our master {ours:.0f} steps/s, "
                  f"Ecos {ecos:.0f} steps/s, ratio ours/Ecos {ours / ecos:.2f}")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--blade-loss", action="store_true", help="also the nine-FMU blade-loss SSP against Ecos")
    ap.add_argument("--ecos-steps", type=int, default=2000, help="fixed steps of the SSP runs (default 2000)")
    args = ap.parse_args()
    per, call = master_overhead()
    print(f"master overhead per component step: {per * 1e6:.2f} us (gather + set_inputs + do_step call + "
          f"bookkeeping; the bare do_step call alone is {call * 1e6:.2f} us)")
    wm, ws, T_m, T_s = toy_ratio()
    print(f"toy thermo-mechanical, 30 s: monolithic {wm:.3f} s, staggered {ws:.3f} s, ratio {wm / ws:.1f}; "
          f"temperature rise {T_m:.3f} K vs {T_s:.3f} K ({100 * (T_s - T_m) / T_m:+.2f} %)")
    ecos_comparison(args.blade_loss, args.ecos_steps)
