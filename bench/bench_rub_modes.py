"""Why the rotor overshoots a soft rub ring: the linear engine with the ring in contact (issue 17, rubbing branch).

The co-simulated engine linearised (master/linear_engine.py: film at 30 C about the centred journal) with the rub
ring in contact represented as a radial spring k_r between the power-turbine node of the ring and the casing hub
of bearing #0. Prints

* the receptance of the rotor relative to the hub at the ring node at 16 000 rev/min (a rotating unit force pair):
  its phase near -155 deg says the rotor there is mass-controlled (above its critical speeds), so a radial
  constraint there ADDS to a negative dynamic stiffness: about 1/|H| of it puts a mode on the running speed;
* the forward synchronous critical speeds against k_r at the ring node: the #0 mode (10 200 rev/min free) climbs
  through 16 000 rev/min between about 1.5e7 and 3e7 N/m and settles near 17 900 rev/min;
* the same with the film's secant radial stiffness at e ~ 0.96 (3.3e7 N/m, measured in the co-simulation at
  8551 N with the former ring) added to bearing #0's support.

    python bench/bench_rub_modes.py
"""
from __future__ import annotations

import copy

import numpy as np

from rotorcosim.components.rotor import critical
from rotorcosim.components.rotor import model as fem
from rotorcosim.master import linear_engine as le


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


def receptance(full: fem.FullModel, sup: dict, node: int) -> complex:
    """Forward-orbit receptance (m/N) of the PT node relative to hub h0 under a unit force pair between them
    rotating at the power-turbine speed."""
    W = full.omega_pt
    s = full.coupled(sup)
    r = full.omega_gg / full.omega_pt
    A = s["K"] - W ** 2 * s["M"] + 1j * W * (s["C"] + W * s["G_pt"] + W * r * s["G_gg"])
    ix, iy = (full.info["dof"]("pt", node, d) for d in range(2))
    hx, hy = full.ports["housing0"]
    g = np.zeros(A.shape[0], complex)
    g[ix], g[iy], g[hx], g[hy] = 1.0, -1j, -1.0, 1j
    Y = np.linalg.solve(A, g)
    return complex(Y[ix] - Y[hx])


def main() -> None:
    data, _ = fem.load_data(None)
    full = fem.build(data)
    sup = le.supports()
    node0 = int(data["power_turbine"]["rub0_node"])
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


if __name__ == "__main__":
    main()
