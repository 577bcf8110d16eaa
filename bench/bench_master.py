"""Master benchmarks: overhead per component step (trivial components) and the toy staggered speed-up.

    python bench/bench_master.py

Prints: the master's overhead per component step (a do-nothing component, Gauss-Seidel, 2 components
exchanging one scalar each way), and the wall-time ratio monolithic / staggered for the toy thermo-mechanical
system (tests/master/test_multirate_staggered.py), both measured in this one process.
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from rotorcosim.components.contract import Component, Variable
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation
from rotorcosim.master.system import Connection, System

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


if __name__ == "__main__":
    per, call = master_overhead()
    print(f"master overhead per component step: {per * 1e6:.2f} us (gather + set_inputs + do_step call + "
          f"bookkeeping; the bare do_step call alone is {call * 1e6:.2f} us)")
    wm, ws, T_m, T_s = toy_ratio()
    print(f"toy thermo-mechanical, 30 s: monolithic {wm:.3f} s, staggered {ws:.3f} s, ratio {wm / ws:.1f}; "
          f"temperature rise {T_m:.3f} K vs {T_s:.3f} K ({100 * (T_s - T_m) / T_m:+.2f} %)")
