"""Rotor component benchmark: build time, cost of one reduced Newmark step, full vs reduced accuracy and cost.

    python bench/bench_rotor.py [--quick]

Prints (all measured in this process):
* model build and MTA reduction times (cold, then the in-process cache);
* the cost of one component do_step at h = 1e-5 s (default reduced size 30 modes + 12 vectors), and of one step
  of the full model (classical Newmark, dense) for the ratio;
* the blade-loss transient on linear #0/#5 supports (2850 N, 0.03 s, h = 2e-5 s): peak radial displacement at
  bearings #0/#5, MTA and plain modal truncation of the same size against the full model, for several n_modes.
"""
from __future__ import annotations

import argparse
import math
import time

import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="only n_modes = 30 in the accuracy table")
    args = ap.parse_args()

    t0 = time.perf_counter()
    from rotorcosim.components.rotor import model as fem
    from rotorcosim.components.rotor import verification as ver
    from rotorcosim.components.rotor.component import Rotor, reduced_model
    t_import = time.perf_counter() - t0

    t0 = time.perf_counter()
    full = fem.load()
    t_build = time.perf_counter() - t0
    W_pt, W_gg = full.omega_pt, full.omega_gg
    t0 = time.perf_counter()
    red = reduced_model("", 30, W_pt, W_gg)
    t_reduce = time.perf_counter() - t0          # includes one more full build (cached afterwards)
    t0 = time.perf_counter()
    reduced_model("", 30, W_pt, W_gg)
    t_cached = time.perf_counter() - t0
    print(f"imports {t_import:.2f} s; full model build {t_build:.3f} s ({full.n} DOF); "
          f"build + MTA reduction {t_reduce:.3f} s (reduced size {red['n']}: 30 modes + {red['n_aug']} vectors); "
          f"cached {t_cached * 1e6:.1f} us")

    # one reduced step through the component (numba kernel), inputs changing every step like in the co-simulation
    r = Rotor("rotor", {})
    t0 = time.perf_counter()
    r.setup(0.0)
    t_setup = time.perf_counter() - t0
    h = 1e-5
    rng = np.random.default_rng(0)
    forces = rng.normal(scale=10.0, size=(1000, 3))
    for k in range(200):                        # compile / warm up
        r.do_step(k * h, h)
    n = 50000
    best = math.inf
    for rep in range(3):
        t0 = time.perf_counter()
        for k in range(n):
            r.set_inputs({"F_brg0": forces[k % 1000]})
            r.do_step(k * h, h)
        best = min(best, (time.perf_counter() - t0) / n)
    t0 = time.perf_counter()
    for k in range(n):
        r.set_inputs({"F_brg0": forces[k % 1000]})
    t_set = (time.perf_counter() - t0) / n
    print(f"component setup (cached model) {t_setup:.3f} s; one do_step at h = 1e-5 s: {(best - t_set) * 1e6:.2f} us "
          f"(+ {t_set * 1e6:.2f} us for set_inputs); 75 000 steps: {75000 * (best - t_set):.2f} s")

    # one step of the full model for comparison (classical Newmark, dense inverse, like verification)
    M, C, K = ver.linear_system(full)
    from rotorcosim.components.rotor.newmark import integrate
    nfull = 400
    zero = np.zeros(full.n)
    t0 = time.perf_counter()
    integrate(M, C, K, lambda t: zero, zero, zero, h, 1)
    t_fac = time.perf_counter() - t0
    t0 = time.perf_counter()
    integrate(M, C, K, lambda t: zero, zero, zero, h, nfull)
    t_full = (time.perf_counter() - t0 - t_fac) / nfull
    print(f"full model ({full.n} DOF) Newmark step: {t_full * 1e6:.1f} us (set-up {t_fac:.2f} s); "
          f"full / reduced step cost ratio {t_full / (best - t_set):.1f}")

    # accuracy: MTA vs plain modal truncation of the same size, against the full model
    t0 = time.perf_counter()
    ref = ver.blade_loss_transient(full, "full")
    print(f"\nblade-loss transient on linear supports, full model: peak #0 {ref['peak0'] * 1e3:.5f} mm, "
          f"#5 {ref['peak5'] * 1e3:.5f} mm ({time.perf_counter() - t0:.1f} s)")
    print("relative errors against the full model: peak radial displacement, and RMS of the x, y history")
    print(f"{'n_modes':>8} {'size':>5} | {'MTA peak #0':>11} {'#5':>8} {'RMS #0':>8} {'#5':>8} | "
          f"{'modal peak #0':>13} {'#5':>8} {'RMS #0':>8} {'#5':>8}")

    def rms(r, cols):
        return 100 * np.sqrt(np.mean((r["x"][:, cols] - ref["x"][:, cols]) ** 2) / np.mean(ref["x"][:, cols] ** 2))

    for nm in ((30,) if args.quick else (12, 20, 30, 40)):
        a = ver.blade_loss_transient(full, "mta", nm)
        b = ver.blade_loss_transient(full, "modal", nm)
        ea = [abs(a[k] / ref[k] - 1) * 100 for k in ("peak0", "peak5")] + [rms(a, slice(0, 2)), rms(a, slice(2, 4))]
        eb = [abs(b[k] / ref[k] - 1) * 100 for k in ("peak0", "peak5")] + [rms(b, slice(0, 2)), rms(b, slice(2, 4))]
        print(f"{nm:>8} {a['size']:>5} | {ea[0]:>10.3f}% {ea[1]:>7.3f}% {ea[2]:>7.3f}% {ea[3]:>7.3f}% | "
              f"{eb[0]:>12.3f}% {eb[1]:>7.3f}% {eb[2]:>7.3f}% {eb[3]:>7.3f}%")


if __name__ == "__main__":
    main()
