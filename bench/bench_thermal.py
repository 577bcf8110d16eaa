"""Benchmark and plausibility figures of the thermal network and the rub ring.

Prints: the cost of one do_step of each component (thermal at 1 ms and 0.1 s, rub ring in and out of contact,
measured within this process), the one-off cost of a new step size (matrix exponential), the cost of these
components in the blade-loss run (75 000 TM steps of 1e-5 s, 750 thermal steps of 1 ms, ~1 200 thermal-only steps
of 0.1 s, two of each component), the steady states of the two bearings at their Table 5 powers, and a
plausibility table: the networks after 120 s under the constant power losses of the paper's Table 5, next to its
final temperatures (the paper's powers were not constant over its 2 minutes, so only the orders of magnitude
compare; nothing is tuned to this), with the hottest node (the housing carrying the rub ring under rub) and an
energy bound: a rub power P for 120 s is P * 120 s of heat, which the bearing-sized heat masses cannot store at
a few hundred kelvin (see the printed adiabatic rise of the housing).

    python bench/bench_thermal.py
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import csv
import time

import numpy as np

from rotorcosim.components.rubring.component import RubRing
from rotorcosim.components.thermal.component import ThermalNetwork

from rotorcosim.cases.blade_loss.table5 import PAPER_TABLE5 as TABLE5  # the paper's Table 5, shipped


def per_call(fn, n):
    fn()
    t0 = time.perf_counter()
    for _ in range(n):
        fn()
    return (time.perf_counter() - t0) / n


def timing():
    th = ThermalNetwork("thermal0", {"bearing": 0})
    th.setup(0.0)
    th.set_inputs({"P_drag": [350.0], "P_sfd": [600.0], "P_rub": [0.0]})
    t_ms = per_call(lambda: th.do_step(0.0, 1e-3), 20000)
    t_to = per_call(lambda: th.do_step(0.0, 0.1), 20000)
    t0 = time.perf_counter()
    for k in range(20):
        th.network.step_matrices(0.0123 + k * 1e-4)
    t_new = (time.perf_counter() - t0) / 20

    rr = RubRing("rubring0", {})
    rr.setup(0.0)
    out_in = {"X_rotor": [0.3e-3, 0.0], "V_rotor": [0.0, 0.5], "X_housing": [0.0, 0.0], "V_housing": [0.0, 0.0]}
    contact = {"X_rotor": [0.55e-3, 0.0], "V_rotor": [0.0, 0.9], "X_housing": [1e-6, 0.0], "V_housing": [0.0, 0.0]}

    def rub(values):
        rr.set_inputs(values)
        rr.do_step(0.0, 1e-5)

    r_free = per_call(lambda: rub(out_in), 50000)
    r_contact = per_call(lambda: rub(contact), 50000)
    r_step = per_call(lambda: rr.do_step(0.0, 1e-5), 50000)
    total = 2 * (75000 * r_contact + 750 * t_ms + 1193 * t_to)
    print("cost per call (this machine, one process):")
    print(f"  thermal do_step, h = 1 ms         {t_ms * 1e6:8.2f} us")
    print(f"  thermal do_step, h = 0.1 s        {t_to * 1e6:8.2f} us")
    print(f"  thermal new step size (expm)      {t_new * 1e6:8.2f} us (once per step size, then cached)")
    print(f"  rub ring set_inputs + do_step     {r_free * 1e6:8.2f} us (inside the clearance)")
    print(f"  rub ring set_inputs + do_step     {r_contact * 1e6:8.2f} us (in contact)")
    print(f"  rub ring do_step alone            {r_step * 1e6:8.2f} us (in contact)")
    print(f"  blade-loss run share (2 rings in contact at every TM step, 2 networks): {total:.2f} s")


def steady_states():
    from rotorcosim.components.thermal.cli import steady

    print("\nsteady states (rotorcosim thermal-steady), C:")
    for b, P in ((0, (350.0, 640.0, 0.0)), (5, (625.0, 1.0, 0.0))):
        out = steady(b, *P)
        T = out["temperatures_C"]
        print(f"  #{b} drag {P[0]:g} W, sfd {P[1]:g} W, rub {P[2]:g} W: inner race {T['inner_race']:.1f}, ball"
              f" {T['ball']:.1f}, outer race {T['outer_race']:.1f}, bearing oil (T_oil) {out['bearing_oil_C']:.1f},"
              f" SFD oil {T['sfd_oil']:.1f}, shaft {T['shaft']:.1f}, housing {T['housing']:.1f}")


def plausibility():
    rows = {}
    with open(TABLE5) as f:
        for row in csv.reader(line for line in f if not line.startswith("#")):
            if row[0] == "result":
                levels = row[2:]
                continue
            rows[(row[0], int(row[1]))] = [float(v) for v in row[2:]]
    print("\nafter 120 s at Table 5's constant powers (model / paper, C):")
    print(f"  {'F_u N':>6s} brg {'drag W':>7s} {'sfd W':>7s} {'rub W':>7s} | {'inner race':>15s} {'ball':>15s}"
          f" {'outer race':>15s} {'SFD oil':>15s} | {'T_oil':>6s} {'shaft':>6s} {'housing':>7s}"
          f" {'adiab.':>7s}")
    for j, level in enumerate(levels):
        for b in (0, 5):
            P = [rows[(k, b)][j] for k in ("drag_power_W", "sfd_power_W", "rub_power_W")]
            th = ThermalNetwork(f"thermal{b}", {"bearing": b})
            th.setup(0.0)
            th.set_inputs({"P_drag": [P[0]], "P_sfd": [P[1]], "P_rub": [P[2]]})
            for i in range(1200):
                th.do_step(0.1 * i, 0.1)
            y = th.get_outputs()
            model = [y[k][0] - 273.15 for k in ("T_inner_race", "T_ball", "T_outer_race", "T_sfd_oil")]
            paper = [rows[(k, b)][j] for k in ("T_inner_race_C", "T_ball_C", "T_outer_race_C", "T_sfd_oil_C")]
            cells = " ".join(f"{m:7.1f}/{p:<7.1f}" for m, p in zip(model, paper))
            T = y["T_nodes"] - 273.15
            net = th.network
            # temperature rise of the housing if it kept all the heat that enters it over 120 s
            adiabatic = (net.S[8] @ np.array(P)) * 120.0 / net.C[8]
            print(f"  {level:>6s} #{b}  {P[0]:7.1f} {P[1]:7.1f} {P[2]:7.0f} | {cells} | {y['T_oil'][0] - 273.15:6.1f}"
                  f" {T[0]:6.1f} {T[8]:7.1f} {adiabatic:7.0f}")
    print("  (T_oil: bearing oil = mean of the lubricant nodes; adiab.: housing rise, K, were it to keep all its"
          " heat for 120 s)")


if __name__ == "__main__":
    timing()
    steady_states()
    plausibility()
