"""Where bearing #0's and #5's heat goes (the #5 network's temperature rise per watt).

For each bearing, at the paper's below-rub powers (Table 5: #0 348.3 W drag + 30.56 W film at 712 N, #5 624.6 W
+ 0.95 W at 2850 N) and at ours (docs/results/table5.csv, 712 N: #0 312.8 + 35.2 W, #5 499.4 + 0.06 W), the network alone
(no mechanics) under those constant powers:

1. each path's conductance (W/K) and the heat masses (J/K);
2. after 120 s (the paper's Table 5 is the state at the end of its 2-minute run): the node temperatures, where
   the heat put in is (stored per node, and gone out through each ground: shaft end, damper feed, housing), and
   the heat flow on each branch out of the races (to the shaft, to the journal);
3. the steady state (what the network reaches after ~1 h; NOT what Table 5 compares);
4. the 120 s inner race under one change at a time of the values the paper does not give, and the journal's
   radial shells N (data/thermal.toml [lumping]) as a convergence study;
5. the 2 s state of bearing #0 against the paper's Table 6 (2850 N, 2 s: drag 599.85 W, film 587.7 W);
6. a reference for the inner race's way out: Table 1's shaft branch (R_i + R_sr, R_sr = 1/(pi k W_i), and the
   shaft node's heat mass behind it) against a resolved axisymmetric shaft (finite volumes, 100 mm long, the band
   under the race joined to the inner race through R_i): the band's rise per watt Z(t) of the shaft alone
   (checked at 2 s against the 1-D semi-infinite solid, 2 q sqrt(t / (pi rho c k)), an upper bound), and the
   whole network at the paper's powers with the resolved shaft (implicit Euler, 0.1 s).

    python bench/bench_thermal_paths.py
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import contextlib
import copy

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

import rotorcosim.components.thermal.geometry as geo
from rotorcosim.components.thermal.component import ThermalNetwork
from rotorcosim.components.speeds import PT_OMEGA
from rotorcosim.components.thermal.geometry import (BALL, HOUSING, IR, JOURNAL, LE, LI, OR, SFD, SHAFT,
                                                    build_network, radii, resistances, shell_nodes)

KELVIN = 273.15
PAPER = {0: (348.3, 30.56), 5: (624.6, 0.95)}          # Table 5 below rub (712 N at #0, 2850 N at #5)
OURS = {0: (312.756, 35.1559), 5: (499.443, 0.0564861)}  # docs/results/table5.csv at 712 N
PAPER_T = {0: (68.2, 68.9, 67.1, 33.0), 5: (86.1, 86.2, 83.0, 36.7)}   # inner race, ball, outer race, SFD oil


@contextlib.contextmanager
def data(changes):
    """The data file's values with ``changes`` {(table, ..., key): factor or ('=', value)} applied."""
    saved = copy.deepcopy(geo.THERMAL_DATA)
    try:
        for path, f in changes.items():
            d = geo.THERMAL_DATA
            for k in path[:-1]:
                d = d[k]
            d[path[-1]] = f[1] if isinstance(f, tuple) else d[path[-1]] * f
        geo.BEARINGS.clear()
        geo.BEARINGS.update({int(k): v for k, v in geo.THERMAL_DATA["bearing"].items()})
        yield
    finally:
        geo.THERMAL_DATA.clear()
        geo.THERMAL_DATA.update(saved)
        geo.BEARINGS.clear()
        geo.BEARINGS.update({int(k): v for k, v in geo.THERMAL_DATA["bearing"].items()})


def run(bearing, P, t=120.0, h=0.1):
    th = ThermalNetwork(f"thermal{bearing}", {"bearing": bearing})
    th.setup(0.0)
    th.set_inputs({"P_drag": [P[0]], "P_sfd": [P[1]], "P_rub": [0.0]})
    for i in range(int(round(t / h))):
        th.do_step(i * h, h)
    return th


def branch_flow(net, T, a, b):
    return -net.K[a, b] * (T[a] - T[b])


def breakdown(bearing, P, label):
    th = run(bearing, P)
    net, T = th.network, th.state["T"]
    Ta = net.T_ground[SHAFT]
    shells = shell_nodes()
    print(f"\n#{bearing}, {label}: drag {P[0]:.1f} W, film {P[1]:.2f} W, 120 s")
    g = {"race-shaft (R_i + R_sr)": -net.K[IR, SHAFT], "outer race-journal (R_e + R_j)":
         1.0 / sum(1.0 / -net.K[a, b] for a, b in zip([OR] + shells[:-1], shells)),
         "shaft-ambient (R_sa)": net.ground[SHAFT], "journal-SFD oil (R_sf1)": -net.K[JOURNAL, SFD],
         "SFD oil-housing (R_sf2)": -net.K[SFD, HOUSING], "SFD oil feed (rho c_p Q)": net.ground[SFD],
         "housing-chamber oil (R_h)": net.ground[HOUSING],
         "inner race-ball (R_b, direct)": 1.0 / geo.resistances(bearing, th.p["omega"])["R_b"]}
    print("  conductances W/K: " + ", ".join(f"{k} {v:.3g}" for k, v in g.items()))
    C = net.C
    Cj = C[shells].sum()
    print(f"  heat masses J/K: shaft {C[SHAFT]:.0f}, inner race {C[IR]:.1f}, balls {C[BALL]:.1f}, outer race"
          f" {C[OR]:.1f}, lubricant {C[LI] + C[LE]:.1f}, journal sleeve {Cj:.0f} ({len(shells)} shell node(s)),"
          f" SFD oil {C[SFD]:.1f}, housing {C[HOUSING]:.0f}")
    Tc = T - KELVIN
    print(f"  T at 120 s, C: inner race {Tc[IR]:.1f}, ball {Tc[BALL]:.1f}, outer race {Tc[OR]:.1f}, SFD oil"
          f" {Tc[SFD]:.1f} (paper {PAPER_T[bearing]}); shaft {Tc[SHAFT]:.1f}, journal at r_o"
          f" {Tc[shells[0]]:.1f} .. at r_j {Tc[JOURNAL]:.1f}, housing {Tc[HOUSING]:.1f}")
    rise = (T[IR] - Ta) / (P[0] + P[1])
    print(f"  inner race rise per watt at 120 s: {rise:.3f} K/W")
    E = (P[0] + P[1]) * 120.0
    stored = C * (T - Ta)
    parts = {"shaft": stored[SHAFT], "races+balls+lubricant": stored[[IR, LI, BALL, LE, OR]].sum(),
             "journal sleeve": stored[shells].sum(), "SFD oil": stored[SFD], "housing": stored[HOUSING]}
    print(f"  of the {E / 1e3:.1f} kJ put in: stored " + ", ".join(f"{k} {v / E:.0%}" for k, v in parts.items())
          + f"; gone out {1 - stored.sum() / E:.0%}")
    out = net.ground * (T - net.T_ground)
    print(f"  heat out at 120 s, W: shaft end {out[SHAFT]:.1f}, damper feed {out[SFD]:.1f}, housing"
          f" {out[HOUSING]:.1f}")
    races = {"inner race -> shaft": branch_flow(net, T, IR, SHAFT),
             "outer race -> journal": branch_flow(net, T, OR, shells[0])}
    print("  branch flows at 120 s, W: " + ", ".join(f"{k} {v:.0f}" for k, v in races.items()))
    Ts = net.steady(np.array([P[0], P[1], 0.0])) - KELVIN
    print(f"  steady state (not Table 5): inner race {Ts[IR]:.1f}, ball {Ts[BALL]:.1f}, outer race {Ts[OR]:.1f},"
          f" {(Ts[IR] + KELVIN - Ta) / (P[0] + P[1]):.3f} K/W")


SENSITIVITY = [
    ("shaft length L_s x0.5", {("defaults", "shaft_length_mm"): 0.5}),
    ("shaft length L_s x2", {("defaults", "shaft_length_mm"): 2.0}),
    ("shaft-end convection x10", {("convection", "shaft_a"): 10.0}),
    ("housing wall x2", {("defaults", "housing_wall_mm"): 2.0}),
    ("housing oil-wetted h x3", {("convection", "housing"): 3.0}),
    ("damper oil feed x3", {("oil_flow", "sfd_L_per_min"): 3.0}),
    ("lubricant fill 100 %", {("oil_flow", "lubricant_fill_fraction"): ("=", 1.0)}),
    ("Harris convection off", {("convection", "harris_coefficient"): 1e-12}),
    ("steel k 46 W/(m K)", {("steel", "conductivity"): ("=", 46.0)}),
] + [(f"journal shells N = {n}", {("lumping", "journal_shells"): ("=", n)}) for n in (1, 2, 4, 8, 16, 32)]


def sensitivity():
    print("\n120 s inner race / ball / outer race (C) under one change at a time, at the paper's powers:")
    print(f"  {'':28s} {'#0':>20s} {'#5':>20s}")
    for name, changes in [("shipped", {})] + SENSITIVITY:
        with data(changes):
            cells = []
            for b in (0, 5):
                y = run(b, PAPER[b]).y
                cells.append("/".join(f"{y[k][0] - KELVIN:.1f}" for k in ("T_inner_race", "T_ball",
                                                                             "T_outer_race")))
        print(f"  {name:28s} {cells[0]:>20s} {cells[1]:>20s}")
    print(f"  {'paper (Table 5)':28s} {'/'.join(map(str, PAPER_T[0][:3])):>20s}"
          f" {'/'.join(map(str, PAPER_T[5][:3])):>20s}")


def table6():
    th = run(0, (599.85, 587.7), t=2.0, h=0.001)
    y = th.y
    got = [y[k][0] - KELVIN for k in ("T_inner_race", "T_ball", "T_outer_race", "T_sfd_oil")]
    print("\n#0 after 2 s at Table 6's powers (drag 599.85 W, film 587.7 W held), C (paper Table 6, staggered):")
    print("  inner race {:.1f} (33.2), ball {:.1f} (35.1), outer race {:.1f} (32.7), SFD oil {:.1f} (36.9)"
          .format(*got))


def shaft_grid(r_out, r_in, W, L, nr=30, nz=150):
    """Finite volumes of an axisymmetric shaft r_in..r_out, |z| < L/2 (adiabatic outside the band): conductance
    matrix, heat masses, and the surface cells under the race (|z| < W/2)."""
    st = geo.THERMAL_DATA["steel"]
    k, rc = st["conductivity"], st["density"] * st["specific_heat"]
    dr, dz = (r_out - r_in) / nr, L / nz
    r = r_in + (np.arange(nr) + 0.5) * dr
    z = -L / 2 + (np.arange(nz) + 0.5) * dz
    idx = np.arange(nr * nz).reshape(nr, nz)
    C = (rc * 2 * np.pi * r * dr * dz)[:, None].repeat(nz, axis=1).ravel()
    g_r = np.broadcast_to((k * 2 * np.pi * (r[:-1] + dr / 2) * dz / dr)[:, None], (nr - 1, nz))  # radial faces
    g_z = np.broadcast_to((k * 2 * np.pi * r * dr / dz)[:, None], (nr, nz - 1))                  # axial faces
    a = np.concatenate([idx[:-1, :].ravel(), idx[:, :-1].ravel()])
    b = np.concatenate([idx[1:, :].ravel(), idx[:, 1:].ravel()])
    g = np.concatenate([g_r.ravel(), g_z.ravel()])
    K = sp.csr_matrix((np.concatenate([g, g, -g, -g]), (np.concatenate([a, b, a, b]), np.concatenate([a, b, b, a]))),
                      shape=(C.size, C.size))
    band = idx[-1, np.abs(z) < W / 2]
    return K, C, band


def shaft_reference():
    st = geo.THERMAL_DATA["steel"]
    k, rc = st["conductivity"], st["density"] * st["specific_heat"]
    print("\nthe shaft under the inner race: band rise per watt Z(t), K/W (resolved 2-D shaft / Table 1's"
          " R_sr + t / C_shaft):")
    for b in (0, 5):
        g = radii(b)
        K, C, band = shaft_grid(g["r_s"], 0.0, g["W"], g["L_s"])
        q = np.zeros(C.size)
        q[band] = 1.0 / band.size
        dt, T, t, out = 0.05, np.zeros(C.size), 0.0, {}
        lu = spl.splu((sp.diags(C / dt) + K).tocsc())
        for mark in (2.0, 30.0, 120.0):
            while t < mark - 1e-9:
                T = lu.solve(C / dt * T + q)
                t += dt
            out[mark] = T[band].mean()
        A = 2 * np.pi * g["r_s"] * g["W"]
        semi = 2.0 / A * np.sqrt(2.0 / (np.pi * rc * k))
        R_sr = 1.0 / (np.pi * k * g["W"])
        print(f"  #{b}: " + ", ".join(f"{m:g} s {v:.3f} / {R_sr + m / C.sum():.3f}" for m, v in out.items())
              + f" (1-D semi-infinite at 2 s: {semi:.3f})")
    print("network at the paper's powers, 120 s, inner race / ball / outer race, C:")
    for b in (0, 5):
        for label, r_in in (("Table 1 shaft", None), ("resolved solid shaft", 0.0),
                            ("resolved hollow shaft (rotor model's bore)", {0: 10e-3, 5: 20e-3}[b])):
            net = build_network(b, PT_OMEGA, 303.15, 303.15)
            n, Kn = net.n, net.K.copy()
            rhs = net.b + net.S @ np.array([*PAPER[b], 0.0])
            if r_in is None:
                K, C = sp.csr_matrix(Kn), net.C
            else:
                g, R = radii(b), resistances(b, PT_OMEGA)
                gs = -Kn[SHAFT, IR]                      # Table 1's shaft branch out, the resolved shaft in
                Kn[SHAFT, SHAFT] -= gs
                Kn[IR, IR] -= gs
                Kn[SHAFT, IR] = Kn[IR, SHAFT] = 0.0
                Kg, Cg, band = shaft_grid(g["r_s"], r_in, g["W"], g["L_s"])
                gi = 1.0 / R["R_i"] / band.size         # the inner race's own R_i, shared over the band
                extra = sp.lil_matrix((n + Cg.size,) * 2)
                extra[IR, IR] = gi * band.size
                for m in n + band:
                    extra[m, m] = gi
                    extra[IR, m] = extra[m, IR] = -gi
                K = sp.block_diag([sp.csr_matrix(Kn), Kg]).tocsr() + extra
                C = np.concatenate([net.C, Cg])
                rhs = np.concatenate([rhs, np.zeros(Cg.size)])
            dt = 0.1
            lu = spl.splu((sp.diags(C / dt) + K).tocsc())
            T = np.full(C.size, 303.15)
            for _ in range(1200):
                T = lu.solve(C / dt * T + rhs)
            print(f"  #{b} {label:44s} {T[IR] - KELVIN:6.1f} {T[BALL] - KELVIN:6.1f} {T[OR] - KELVIN:6.1f}"
                  f"   (paper {PAPER_T[b][0]} {PAPER_T[b][1]} {PAPER_T[b][2]})")


if __name__ == "__main__":
    for b in (0, 5):
        breakdown(b, PAPER[b], "the paper's powers")
        breakdown(b, OURS[b], "our powers (docs/results/table5.csv, 712 N)")
    sensitivity()
    table6()
    shaft_reference()
