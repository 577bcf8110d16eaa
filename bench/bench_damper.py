"""Squeeze film damper benchmarks: cost per call of the direct FE model and of the fast model, their ratio,
the cost of one fast do_step including the K_film / C_film Jacobian, and the fast/FE force agreement.

    python bench/bench_damper.py [--quick]

All figures are measured in this one process (timings: best of several repeats, and the median, over
distinct journal states on a whirl orbit so that nothing is reused between calls).
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import math
import statistics
import time

import numpy as np

from rotorcosim.components.damper.component import FastDamper, FEDamper

C = 0.635e-3
T_OIL = 343.15


def orbit_states(n, eps=0.6, whirl=1676.0):
    """Journal positions/velocities on a circular whirl orbit (16 000 rev/min) plus a radial squeeze."""
    out = []
    for k in range(n):
        th = 2.0 * math.pi * k / n + 0.05
        e = eps * C * (1.0 + 0.3 * math.sin(3 * th))
        x = e * np.array([math.cos(th), math.sin(th)])
        v = whirl * e * np.array([-math.sin(th), math.cos(th)]) + 0.1 * np.array([math.cos(th), math.sin(th)])
        out.append((x, v))
    return out


def time_calls(d, states, repeats):
    """Seconds per do_step over the states: (best, median) over repeats."""
    per = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for x, v in states:
            d.set_inputs({"X_journal": x, "V_journal": v})
            d.do_step(0.0, 1e-5)
        per.append((time.perf_counter() - t0) / len(states))
    return min(per), statistics.median(per)


def agreement(damper, cav, ps):
    params = {"damper": damper, "cavitation": cav, "supply_pressure": ps}
    fe, fast = FEDamper("fe", params), FastDamper("fast", params)
    fe.setup(0.0)
    fast.setup(0.0)
    worst, where = 0.0, None
    ang = 0.7
    for eps in (0.0, 0.13, 0.3, 0.45, 0.6, 0.75, 0.85, 0.9, 0.93, 0.95):
        x = eps * C * np.array([math.cos(ang), math.sin(ang)])
        for vr, vt in ((0.3, 0.0), (0.0, 0.3), (-0.2, 0.25), (0.0, 2.0), (1.5, -1.0)):
            v = np.array([vr * math.cos(ang) - vt * math.sin(ang), vr * math.sin(ang) + vt * math.cos(ang)])
            f = []
            for d in (fe, fast):
                d.set_inputs({"X_journal": x, "V_journal": v, "T_oil": [T_OIL]})
                d.do_step(0.0, 1e-5)
                f.append(d.y["F_film"].copy())
            err = np.linalg.norm(f[1] - f[0]) / np.linalg.norm(f[0])
            if err > worst:
                worst, where = err, (eps, vr, vt)
    return worst, where


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer FE calls")
    args = ap.parse_args(argv)

    t0 = time.perf_counter()
    fast = FastDamper("fast", {"damper": 0})
    fast.setup(0.0)
    t_build = time.perf_counter() - t0
    print(f"fast model set-up, damper #0 (table of 60 FE solves, or the on-disk cache; numba cache): {t_build:.2f} s")

    fe = FEDamper("fe", {"damper": 0})
    fe.setup(0.0)
    for d in (fe, fast):
        d.set_inputs({"T_oil": [T_OIL]})

    n_fe = 6 if args.quick else 20
    fe_best, fe_med = time_calls(fe, orbit_states(n_fe), 1 if args.quick else 2)
    states = orbit_states(2000)
    res = {}
    for cav in (True, False):
        fast.p["cavitation"] = cav
        fast.setup(0.0)
        fast.set_inputs({"T_oil": [T_OIL]})
        res[cav] = time_calls(fast, states, 10)
    # the paper's steady whirl at bearing #0 (0.2 mm, section 4.2): the film does not reach the cavitation
    # floor, so the fast model takes its exact linear path
    steady = time_calls(fast, orbit_states(2000, eps=0.2e-3 / C), 10)
    fast.p["cavitation"] = True
    fast.setup(0.0)
    fast.set_inputs({"T_oil": [T_OIL]})
    # the numba kernel alone (film + Jacobian + spring + wall), without the component's Python around it
    out = np.empty(fast.N_OUT)
    kern = []
    for _ in range(10):
        t0 = time.perf_counter()
        for x, v in states:
            fast.u["X_journal"], fast.u["V_journal"] = x, v
            fast._compute(0.03, out)
        kern.append((time.perf_counter() - t0) / len(states))

    print(f"FE model, one call (assembly + LU + 4 solves, F + K_film + C_film): best {fe_best * 1e3:.1f} ms,"
          f" median {fe_med * 1e3:.1f} ms  ({n_fe} distinct states)")
    for cav, (b, m) in res.items():
        what = "on, film clipped" if cav else "off"
        print(f"fast model do_step incl. K_film/C_film, cavitation {what}, eps ~0.6 orbit at 0.8 m/s:"
              f" best {b * 1e6:.1f} us, median {m * 1e6:.1f} us")
        if cav:
            print(f"  of which the numba kernel: best {min(kern) * 1e6:.1f} us")
    print(f"fast model do_step incl. K_film/C_film, cavitation on, the paper's 0.2 mm steady whirl (no clipping):"
          f" best {steady[0] * 1e6:.1f} us, median {steady[1] * 1e6:.1f} us")
    print("ratio FE / fast per call (cavitation on, the default; clipped orbit, the fast model's slow path):")
    print(f"  best/best {fe_best / res[True][0]:.0f},"
          f" median/median {fe_med / res[True][1]:.0f}  (target >= 100)")
    n_steps = 75_000
    print(f"2 dampers x {n_steps} steps, all on the clipped orbit (upper bound): {2 * n_steps * res[True][1]:.1f} s;"
          f" all at the steady whirl: {2 * n_steps * steady[1]:.1f} s")

    for damper, cav, ps in ((0, True, 0.2e6), (0, False, 0.2e6), (5, True, 0.0)):
        worst, where = agreement(damper, cav, ps)
        print(f"fast vs FE force, damper #{damper}, cavitation {cav}, p_s {ps / 1e6:g} MPa, eps 0..0.95 x 5"
              f" velocities: worst |dF|/|F| = {worst:.2e} at (eps, v_r, v_t) = {where}  (target < 1e-2)")


if __name__ == "__main__":
    main()
