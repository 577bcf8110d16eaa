"""Why the rotor overshoots a soft rub ring: the linear engine with the ring in contact (the rubbing branch).

The co-simulated engine linearised (cases/blade_loss/linear_engine.py: film at 30 C about the centred journal) with the rub
ring in contact represented as a radial spring k_r between the power-turbine node of the ring and the casing hub
of bearing #0. Prints

* the receptance of the rotor relative to the hub at the ring node at 16 000 rev/min (a rotating unit force pair):
  its phase near -155 deg says the rotor there is mass-controlled (above its critical speeds), so a radial
  constraint there ADDS to a negative dynamic stiffness: about 1/|H| of it puts a mode on the running speed;
* the forward synchronous critical speeds against k_r at the ring node: the #0 mode (10 200 rev/min free) climbs
  through 16 000 rev/min between about 1.5e7 and 3e7 N/m and settles near 17 900 rev/min;
* the same with the film's secant radial stiffness at e ~ 0.96 (3.3e7 N/m, measured in the co-simulation at
  8551 N with the former ring) added to bearing #0's support;
* the ring's normal force N estimated on the linear engine (film linearised at 85 C, the film oil
  of the rubbing cases) for a circular synchronous orbit held at the clearance: the ring pushes inward on a rotor
  point whose receptance to the hub is mass-controlled (phase near -175 deg), so the only orbit it can hold is the
  one turned in phase with the unbalance, N = |c + N/k_r + H_u F_u| / |H_g| ~ (c + |H_u| F_u) / |H_g|, at least
  c / |H_g| ~ 10 kN at contact; against the co-simulation's N = P_rub / (mu omega (R + c)) from
  docs/results/paper_comparison.csv and the paper's (its rub power over the same speed: 2.2-15 kN);
* N with the Table 2 intermediate bearings at 0.5 / 2 / 4 x: they move the third forward critical speed (the power
  turbine's tube on the intermediate bearings and #5, 17 900 rev/min) by -4 / +2 / +3 % and N by under 4 %: that
  mode is not what loads the ring (its strain energy in the ring is nil), the receptance at the bearing is;
* N with a radial film stiffness added at #0 (the cavitated film's secant at large orbits): it flips the bearing
  point to stiffness-controlled past ~2.1e7 N/m, after which the ring holds the rotor with less force.

    python bench/bench_rub_modes.py
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import copy
import csv
import math
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from rotorcosim.components.rotor import critical
from rotorcosim.components.rotor import model as fem
from rotorcosim.cases.blade_loss import linear_engine as le


def with_ring(full: fem.FullModel, node: int, k: float) -> fem.FullModel:
    """A shallow copy of ``full`` with a radial spring k (x and y) between PT node ``node`` and hub h0."""
    out = copy.copy(full)
    K = full.K.copy()
    for d in range(2):
        i = full.info["dof"]("pt", node, d)
        h = full.info["dof"]("hub", "h0", d)
        K[i, i] += k
        K[h, h] += k
        K[i, h] -= k
        K[h, i] -= k
    out.K = K
    return out


def _forced(full: fem.FullModel, sup: dict, force: dict[int, complex]) -> np.ndarray:
    """The forward synchronous response (complex amplitudes of every DOF) to rotating forces {dof: amplitude} at
    the power-turbine speed."""
    W = full.omega_pt
    s = full.coupled(sup)
    r = full.omega_gg / full.omega_pt
    A = s["K"] - W ** 2 * s["M"] + 1j * W * (s["C"] + W * s["G_pt"] + W * r * s["G_gg"])
    f = np.zeros(A.shape[0], complex)
    for dof, amp in force.items():
        f[dof] += amp
    return np.linalg.solve(A, f)


def receptance(full: fem.FullModel, sup: dict, node: int) -> complex:
    """Forward-orbit receptance (m/N) of the PT node relative to hub h0 under a unit force pair between them
    rotating at the power-turbine speed."""
    ix, iy = (full.info["dof"]("pt", node, d) for d in range(2))
    hx, hy = full.ports["housing0"]
    Y = _forced(full, sup, {ix: 1.0, iy: -1j, hx: -1.0, hy: 1j})
    return complex(Y[ix] - Y[hx])


RUB_LEVELS = (5700.0, 8551.0, 11401.0, 14252.0)
DOCS = Path(__file__).resolve().parents[1] / "docs" / "results" / "paper_comparison.csv"


def ring_receptances(full: fem.FullModel, sup: dict, node: int) -> tuple[complex, complex]:
    """(H_u, H_g): forward-orbit displacement of PT node ``node`` relative to hub h0 per newton of the rotating
    unbalance, and per newton of a rotating force pair between the node and the hub."""
    ix = full.info["dof"]("pt", node, 0)
    hx, _ = full.ports["housing0"]
    ux, uy = full.ports["unbalance"]
    Yu = _forced(full, sup, {ux: 1.0, uy: -1j})
    return complex(Yu[ix] - Yu[hx]), receptance(full, sup, node)


def ring_force(Hu: complex, Hg: complex, F_u: float, c: float, k_r: float, mu: float) -> float:
    """Normal force N (N) of a ring of clearance c and stiffness k_r holding the node on a circular synchronous
    orbit of radius c + N/k_r, friction mu N against the forward spin: x (1 + H_g N (1 + i mu) / |x|) = H_u F_u.
    0 when the free orbit stays inside the clearance."""
    if abs(Hu * F_u) <= c:
        return 0.0

    def resid(N):
        r = c + N / k_r
        return abs(Hu * F_u) / abs(1.0 + Hg * N * (1.0 + 1j * mu) / r) - r
    return brentq(resid, 0.0, 1e6)


def cosim_ring_forces(c: float, R: float, mu: float) -> dict:
    """The shipped sweep's ring normal force at #0 per level, from its rub power: N = P / (mu omega (R + c))."""
    W = 16000.0 * math.pi / 30.0
    out = {}
    with open(DOCS) as f:
        for r in csv.DictReader(f):
            if r["result"] == "rub_power_W" and r["bearing"] == "0" and float(r["unbalance_N"]) in RUB_LEVELS:
                out[float(r["unbalance_N"])] = (float(r["ours"]) / (mu * W * (R + c)),
                                                float(r["paper"]) / (mu * W * (R + c)))
    return out


def ring_force_study(data: dict) -> None:
    from rotorcosim.components.rubring.component import CONTACT, RINGS

    c, R = 1e-3 * RINGS[0]["clearance_mm"], 1e-3 * RINGS[0]["radius_mm"]
    k_r, mu = CONTACT["stiffness"], CONTACT["friction"]
    node = int(data["attach"]["rubring0"]["node"][1])
    sup85 = le.supports(oil_temperature_C=85.0)
    full = fem.build(data)
    Hu, Hg = ring_receptances(full, sup85, node)
    print(f"ring normal force, linear estimate (film at 85 C): H_u = {abs(Hu):.3e} m/N at "
          f"{np.degrees(np.angle(Hu)):.0f} deg, H_g = {abs(Hg):.3e} m/N at {np.degrees(np.angle(Hg)):.0f} deg")
    cos = cosim_ring_forces(c, R, mu)
    for F in RUB_LEVELS:
        print(f"  {F:7.0f} N: linear N = {ring_force(Hu, Hg, F, c, k_r, mu) / 1e3:5.1f} kN; co-simulation "
              f"(docs/results/paper_comparison.csv) {cos[F][0] / 1e3:5.1f} kN; paper (its rub power) {cos[F][1] / 1e3:5.1f} kN")
    for fac in (0.5, 2.0, 4.0):
        d = copy.deepcopy(data)
        for s in d["support"]:
            if "intermediate" in s["name"]:
                s["k"] *= fac
        f = fem.build(d)
        crit = critical.synchronous_critical_speeds(f, le.supports(), n=3)["forward_synchronous_rpm"]
        hu, hg = ring_receptances(f, sup85, node)
        print(f"  intermediate bearings x {fac:g}: forward critical speeds {[int(round(v)) for v in crit]}; "
              f"linear N {[round(ring_force(hu, hg, F, c, k_r, mu) / 1e3, 1) for F in RUB_LEVELS]} kN")
    for extra in (1e7, 2e7, 3.3e7):
        s2 = copy.deepcopy(sup85)
        s2["h0"]["k_spring"] += extra
        hu, hg = ring_receptances(full, s2, node)
        print(f"  film radial stiffness +{extra:.1e} N/m at #0: H_g at {np.degrees(np.angle(hg)):.0f} deg; linear N "
              f"{[round(ring_force(hu, hg, F, c, k_r, mu) / 1e3, 1) for F in RUB_LEVELS]} kN")


def main() -> None:
    data, _ = fem.load_data(None)
    full = fem.build(data)
    sup = le.supports()
    node0 = int(data["attach"]["rubring0"]["node"][1])
    print(f"rub ring #0 at PT node {node0}; film linearised at {sup['h0']['oil_temperature_C']:.0f} C")
    for node in sorted({2, 3, node0}):
        H = receptance(full, sup, node)
        print(f"PT node {node}: receptance to hub h0 at 16 000 rev/min |H| = {abs(H):.3e} m/N at "
              f"{np.degrees(np.angle(H)):.1f} deg (1/|H| = {1 / abs(H):.3e} N/m)")
    for node in sorted({2, 3, node0}):
        for k in (0.0, 5e6, 1e7, 1.5e7, 2.2e7, 3e7, 6.8e7, 2e8, 3e8, 1e9):
            c = critical.synchronous_critical_speeds(with_ring(full, node, k), sup, n=4)["forward_synchronous_rpm"]
            print(f"ring at PT node {node}, k_r = {k:7.1e} N/m: forward critical speeds "
                  f"{[int(round(v)) for v in c]} rev/min")
    hard = copy.deepcopy(sup)
    hard["h0"]["k_spring"] += 3.33e7
    c = critical.synchronous_critical_speeds(full, hard, n=4)["forward_synchronous_rpm"]
    print(f"film at e ~ 0.96 (secant +3.33e7 N/m at #0), no ring: forward critical speeds "
          f"{[int(round(v)) for v in c]} rev/min")
    ring_force_study(data)


if __name__ == "__main__":
    main()
