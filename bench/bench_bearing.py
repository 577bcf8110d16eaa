"""Ball bearing benchmarks and studies (components/bearing), all figures measured in this one process.

    python bench/bench_bearing.py [--quick]

Prints:
1. radial stiffness of bearings #0 and #5 at the preloaded rest state (static solver, 0 and 16 000 rev/min);
2. cost of one do_step at h = 1e-5 s (numba kernel, automatic sub-steps) at rest and on a blade-loss-like whirl
   orbit with the journal on the fast squeeze film damper (the damper's own Jacobian fed to K_journal/C_journal),
   and the same loop with the Jacobian inputs left at zero (held film force);
3. sub-step convergence: error of F_rotor and of the journal path against a 512-sub-step reference;
4. the cost of the quasi-static solver (``rotorcosim bearing-static``).
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import math
import sys
import time

import numpy as np

from rotorcosim.components.bearing.cli import evaluate
from rotorcosim.components.bearing.component import BallBearing
from rotorcosim.components.bearing.geometry import build_geometry
from rotorcosim.components.bearing.static import preload_offset, stiffness
from rotorcosim.components.damper.component import FastDamper

H = 1e-5
RPM = math.pi / 30


def stiffness_at_preload():
    print("1. radial stiffness at the preloaded rest state (dF_x/dx, y and z held; balls re-equilibrated)")
    for b in (0, 5):
        g = build_geometry(b)
        for rpm in (0.0, 16000.0):
            Fc = g.centrifugal_force(rpm * RPM)
            z0, st = preload_offset(g, Fc)
            K = -stiffness(g, [0, 0, z0], Fc=Fc, st=st)
            print(f"   bearing #{b} {rpm:7.0f} rev/min: k_xx = {K[0, 0]:.4e} N/m, k_zz = {K[2, 2]:.4e} N/m, "
                  f"z0 = {z0 * 1e6:.3f} um, Q_i = {st.Q_i[0]:.1f} N, Q_e = {st.Q_e[0]:.1f} N, "
                  f"alpha_i = {math.degrees(st.alpha_i[0]):.2f} deg, alpha_e = {math.degrees(st.alpha_e[0]):.2f} deg")


def whirl_loop(bearing, n, radius, jacobian=True, substeps=0, T_oil=343.15, record=False):
    """Inner race on a circular synchronous orbit of ``radius`` (from rest), journal on the fast damper."""
    brg = BallBearing(f"bearing{bearing}", {"bearing": bearing, "substeps": substeps})
    brg.setup(0.0)
    sfd = FastDamper(f"damper{bearing}", {"damper": bearing})
    sfd.setup(0.0)
    w = brg.p["omega"]
    zeros2, zeros4 = np.zeros(2), np.zeros(4)
    rec, t_brg, subs = [], 0.0, []
    brg.set_inputs({"T_oil": [T_oil]})
    for k in range(n):
        t = k * H
        ramp = min(1.0, (t + H) / 2e-3)        # 2 ms ramp of the orbit radius
        r = radius * ramp
        c, s = math.cos(w * (t + H)), math.sin(w * (t + H))
        sfd.set_inputs({"X_journal": brg.y["X_journal"], "V_journal": brg.y["V_journal"], "X_housing": zeros2,
                        "V_housing": zeros2, "T_oil": [T_oil]})
        sfd.do_step(t, H)
        if jacobian:
            K = sfd.y["K_film"]
            C = sfd.y["C_film"]
        else:
            K = C = zeros4
        brg.set_inputs({"X_inner": [r * c, r * s, 0.0], "V_inner": [-r * w * s, r * w * c, 0.0],
                        "F_journal": sfd.y["F_journal"], "K_journal": K, "C_journal": C})
        t0 = time.perf_counter()
        brg.do_step(t, H)
        t_brg += time.perf_counter() - t0
        subs.append(brg.substeps_used)
        if record:
            rec.append({key: v.copy() for key, v in brg.y.items()})
    return brg, t_brg / n, np.mean(subs), rec


def step_cost(quick):
    print("2. cost of one bearing do_step at h = 1e-5 s (numba kernel, automatic sub-steps)")
    n = 3000 if quick else 20000
    for b in (0, 5):
        brg = BallBearing("b", {"bearing": b})
        brg.setup(0.0)
        brg.do_step(0.0, H)
        t0 = time.perf_counter()
        for k in range(n):
            brg.do_step(k * H, H)
        dt = (time.perf_counter() - t0) / n
        print(f"   bearing #{b} at rest: {dt * 1e6:6.1f} us/step ({brg.substeps_used} sub-steps)")
    n = 3000 if quick else 10000
    for b, radius in ((0, 0.25e-3), (5, 0.01e-3)):
        try:
            brg, dt, subs, _ = whirl_loop(b, n, radius)
            xj = np.hypot(*brg.y["X_journal"])
            print(f"   bearing #{b} whirl r = {radius * 1e3:.3f} mm with the damper (Jacobian): {dt * 1e6:6.1f} us/step "
                  f"(mean {subs:.1f} sub-steps); at {n * H * 1e3:.0f} ms: Q_max = {brg.y['Q_max']} N, "
                  f"sigma_max = {brg.y['sigma_max'] * 1e-6} MPa, P_drag = {brg.y['P_drag'][0]:.1f} W, "
                  f"|X_journal| = {xj * 1e3:.4f} mm, |F_rotor| = {np.hypot(*brg.y['F_rotor'][:2]):.1f} N")
        except Exception as exc:
            print(f"   bearing #{b} whirl r = {radius * 1e3:.3f} mm: FAILED {exc}")
        try:
            brg, dt, subs, _ = whirl_loop(b, n, radius, jacobian=False)
            print(f"   bearing #{b} same without the damper Jacobian: ran, |X_journal| = "
                  f"{np.hypot(*brg.y['X_journal']) * 1e3:.4f} mm")
        except Exception as exc:
            print(f"   bearing #{b} same without the damper Jacobian: FAILED ({type(exc).__name__}: {exc})")


def film_coupling(quick):
    print("2b. bearing #0 on the fast damper at high eccentricity (orbit radius r / clearance 0.635 mm), "
          "with and without the damper's Jacobian in the journal update")
    n = 1000 if quick else 3000
    for r in (0.25e-3, 0.5e-3, 0.58e-3, 0.62e-3):
        res = {}
        for jac in (True, False):
            try:
                brg, dt, subs, _ = whirl_loop(0, n, r, jacobian=jac)
                res[jac] = (brg.y["Q_max"].copy(), np.hypot(*brg.y["X_journal"]))
            except Exception as exc:
                res[jac] = (None, f"{type(exc).__name__}")
        if res[True][0] is None or res[False][0] is None:
            print(f"   r = {r * 1e3:.2f} mm: with Jacobian {res[True][1]}, without {res[False][1]}")
            continue
        dq = np.max(np.abs(res[True][0] - res[False][0]) / res[True][0])
        print(f"   r = {r * 1e3:.2f} mm: journal orbit {res[True][1] * 1e3:.4f} mm, Q_max {res[True][0]} N (Jacobian); "
              f"held force: stable, Q_max differs by {dq * 100:.2f} %")


def film_coupling_accuracy(quick):
    global H
    print("2c. accuracy of the journal/film coupling: bearing #0, r = 0.5 mm, 10 ms; error at the end against the "
          "master step h = 1e-6 s with the Jacobian")
    T, keep = (0.004 if quick else 0.01), H
    out = {}
    try:
        for h in (1e-6, 1e-5):
            H = h
            for jac in (True, False):
                b, _, _, _ = whirl_loop(0, int(round(T / h)), 0.5e-3, jacobian=jac)
                out[(h, jac)] = (b.y["Q_max"].copy(), b.y["F_rotor"].copy())
    finally:
        H = keep
    ref = out[(1e-6, True)]
    for (h, jac), (q, f) in out.items():
        eq = np.max(np.abs(q - ref[0]) / ref[0])
        ef = np.linalg.norm(f - ref[1]) / np.linalg.norm(ref[1])
        print(f"   h = {h:.0e} s, {'with' if jac else 'without'} Jacobian: Q_max error {eq * 100:.2f} %, "
              f"F_rotor error {ef * 100:.2f} %")


def convergence(quick):
    print("3. sub-step convergence, bearing #0, whirl r = 0.25 mm on the damper, 5 ms from rest; "
          "error vs 512 sub-steps")
    n = 200 if quick else 500
    _, _, _, ref = whirl_loop(0, n, 0.25e-3, substeps=512, record=True)
    rF = np.array([y["F_rotor"] for y in ref])
    rX = np.array([y["X_journal"] for y in ref])
    rQ = np.array([y["Q_max_step"] for y in ref])
    prev = None
    for m in (2, 4, 8, 16, 32, 64, 0):
        try:
            _, dt, subs, rec = whirl_loop(0, n, 0.25e-3, substeps=m, record=True)
        except Exception as exc:
            print(f"   sub-steps {m:3d}: unstable ({type(exc).__name__})")
            continue
        F = np.array([y["F_rotor"] for y in rec])
        X = np.array([y["X_journal"] for y in rec])
        Q = np.array([y["Q_max_step"] for y in rec])
        eF = np.max(np.abs(F - rF)) / np.max(np.abs(rF))
        eX = np.max(np.abs(X - rX)) / np.max(np.abs(rX))
        eQ = np.max(np.abs(Q - rQ)) / np.max(np.abs(rQ))
        label = f"{m:3d}" if m else f"auto ({subs:.1f})"
        order = f"  order F {math.log2(prev / eF):.2f}" if (prev and m) else ""
        print(f"   sub-steps {label}: max rel. error F_rotor {eF:.3e}, X_journal {eX:.3e}, Q_max_step {eQ:.3e}, "
              f"{dt * 1e6:.1f} us/step{order}")
        prev = eF if m else prev


def static_cost():
    print("4. quasi-static solver (rotorcosim bearing-static)")
    for b, Fr, rpm in ((0, 2000.0, 0.0), (0, 2000.0, 16000.0), (5, 1000.0, 16000.0)):
        t0 = time.perf_counter()
        out = evaluate(b, Fr, None, rpm)
        dt = time.perf_counter() - t0
        print(f"   bearing #{b}, Fr = {Fr:.0f} N, {rpm:.0f} rev/min: {dt * 1e3:.0f} ms; Q_max = "
              f"{out['max_contact_load_N']:.1f} N, sigma_max = {out['max_contact_stress_MPa']:.0f} MPa, "
              f"k_r = {out['radial_stiffness_N_per_m']:.4e} N/m")


if __name__ == "__main__":
    quick = "--quick" in sys.argv
    stiffness_at_preload()
    step_cost(quick)
    film_coupling(quick)
    film_coupling_accuracy(quick)
    convergence(quick)
    static_cost()
