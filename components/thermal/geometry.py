"""The bearing heat-transfer network of the paper's Fig. 5: geometry, Table 1 resistances, heat masses, sources.

Nodes (this order everywhere): 0 shaft, 1 inner_race, 2 lub_inner, 3 ball, 4 lub_outer, 5 outer_race, 6 journal,
7 sfd_oil, 8 housing; grounds: the ambient (secondary air, at the shaft end) and the oil supply (jet, damper feed,
chamber oil on the housing).

Radii: r_s = bore/2 (shaft), r_i = (d_m - D)/2 and r_e = (d_m + D)/2 (inner/outer raceway, d_m = (bore + OD)/2),
r_o = OD/2 (outer race outside = journal bore), r_j = damper radius (journal outside), r_hi = r_j + c_sf (housing
bore), r_h = r_hi + wall (housing outside); r_b = D/2; W_i = W_e = bearing width. What Table 3 does not give
is a rule of data/thermal.toml [defaults] unless set (:func:`bearing_data`): the shaft length L_s, the wall, the
housing length L_h = 2 L_j, the rub ring's radius R_r = bore/2, no oil jet.

Branches (Table 1 resistances; a lubricant node sits in the middle of its layer, so each side gets half of R_L):

    shaft  - ambient      R_sa = L_s/(k_s pi r_s^2) + 1/(h_s pi r_s^2)
    shaft  - inner_race   R_sr + R_i,  R_sr = 1/(pi k_s W_i),  R_i = ln(r_i/r_s)/(2 pi k_i W_i)
    inner_race - lub_inner - ball          R_Li/2 + R_Li/2,  R_Li = r_b / (k_l (2 pi r_i W_i - pi n r_b^2))
    inner_race - ball, ball - outer_race   R_b = 1/(n k_b pi r_b) each (ball centre to each contact)
    ball - lub_outer - outer_race          R_Le/2 + R_Le/2,  R_Le = r_b / (k_l (2 pi r_e W_e - pi n r_b^2))
    outer_race - journal  R_e + R_j,   R_e = ln(r_o/r_e)/(2 pi k_e W_e),  R_j = ln(r_j/r_o)/(2 pi k_j W_e)
                          (R_j in N radial shells of the journal sleeve, see below)
    journal - sfd_oil     R_sf1 = ln((r_j + c_sf/2)/r_j) / (2 pi k_sf L_j)
    sfd_oil - housing     R_sf2 = ln(r_hi/(r_j + c_sf/2)) / (2 pi k_sf L_j)
    housing - oil supply  R_h = R_hr R_ha / (R_hr + R_ha)   (oil-wetted in the bearing chamber, see below)
                          R_hr = ln(r_h/r_hi)/(2 pi k_h L_h) + 1/(h_h 2 pi r_h L_h)
                          R_ha = L_h/(2 pi k_h (r_h^2 - r_hi^2)) + 1/(pi h_h (r_h^2 - r_hi^2))

Table 1 prints R_hr, R_ha with r_o (the outer race radius): with the damper between the journal and the housing,
the housing's bore is r_hi, used here. Its h_h is the oil-wetted bearing-chamber wall value and its sink the oil
supply (docs/explanation/paper-components.md, "Convection").

Added to Table 1 (physically real paths of a jet-lubricated bearing, values in data/thermal.toml, sources in
docs/explanation/paper-components.md):

    inner_race - lub_inner   1/(h_i A_i)          oil-wetted convection (Harris), in parallel with R_Li/2
    ball - lub_inner         1/(h_b A_b/2)        A_b = n 4 pi r_b^2, half of it facing each lubricant node
    ball - lub_outer         1/(h_b A_b/2)
    lub_outer - outer_race   1/(h_e A_e)          in parallel with R_Le/2
    lub_inner, lub_outer - supply   rho c_p Q_jet / 2 each   oil renewal by the jet (well-mixed nodes)
    sfd_oil - supply                rho c_p Q_sfd            damper feed

with A_i = 2 pi r_i W - pi n r_b^2 and A_e = 2 pi r_e W - pi n r_b^2 (the lubricated areas of Table 1).

Heat masses m c_p (eq. 12): shaft, solid cylinder r_s over L_s; inner race, annulus r_s..r_i over W_i; balls,
n (4/3) pi r_b^3; lubricant, the free annulus r_i..r_e over W minus the balls, half to each lubricant node;
(only the oil actually in the bearing: ``lubricant_fill_fraction`` of that free volume); outer race, annulus
r_e..r_o over W_e; journal, annulus r_o..r_j over L_j; SFD oil, the film 2 pi r_j c_sf L_j;
housing, annulus r_hi..r_h over L_h.

The journal sleeve in radial shells (data/thermal.toml [lumping] ``journal_shells`` = N): the sleeve r_o..r_j is
thick (25-45 mm) and its own conduction time r^2/kappa (~60-180 s) is that of the 2-minute run, so one node at r_j
holding the whole sleeve's heat mass behind the whole R_j (N = 1, the paper's Fig. 5 node) misstates the
transient: the sleeve's inner layers, which take the outer race's heat at once, sit behind all of R_j. With N > 1
the sleeve is N nodes at the radii rr_m = r_o (r_j/r_o)^(m/N), m = 1..N (the last one the journal node at r_j),
joined by ln(rr_{m+1}/rr_m)/(2 pi k_j W_e) (summing to Table 1's R_j exactly: the steady state is that of the
paper's network for any N), each holding the sleeve between the midpoints to its neighbours (the first from r_o,
the last to r_j). Nodes 9.. are the inner shells (rr_1 .. rr_{N-1}); the nine named nodes keep their indices.

Heat sources (the three power inputs, W):

* P_drag (bearing drag torque): a fraction ``drag_inner_fraction`` at the inner ball/race contacts, the rest at
  the outer ones; the heat of a contact is shared between the race (``contact_race_fraction``) and the ball.
* P_sfd (film viscous power): all into the SFD oil node, where it is dissipated.
* P_rub (rub friction, eq. 11): ``rub_shaft_fraction`` into the shaft node (the rotor at the ring, next to the
  bearing), the rest into the housing (which carries the ring); by default the Blok partition of
  :func:`rub_partition` (~1-2 % into the rotor: in synchronous whirl the contact is a stationary source on the
  rotor and a fast-moving one on the ring).
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np

from .network import LinearNetwork

DATA = Path(__file__).with_name("data") / "thermal.toml"
with open(DATA, "rb") as _f:
    THERMAL_DATA = tomllib.load(_f)   # the whole of thermal.toml, read once
BEARINGS = {int(k): v for k, v in THERMAL_DATA["bearing"].items()}
#: the keys of a bearing record that have no default (the paper's Table 3 gives them for #0 and #5)
REQUIRED = ("bore_diameter_mm", "outside_diameter_mm", "width_mm", "n_balls", "ball_diameter_mm",
            "contact_angle_deg", "damper_radius_mm", "damper_length_mm", "damper_clearance_mm")

NODES = ("shaft", "inner_race", "lub_inner", "ball", "lub_outer", "outer_race", "journal", "sfd_oil", "housing")
SHAFT, IR, LI, BALL, LE, OR, JOURNAL, SFD, HOUSING = range(9)
INPUTS = ("P_drag", "P_sfd", "P_rub")


def bearing_data(bearing: int | dict) -> dict:
    """The full geometry record (mm, deg) of bearing 0 or 5 (data file [bearing.N]), or of ``bearing`` itself
    when it is a record of the same keys (a bearing described by its parameters,
    :class:`~.component.ThermalNetwork`); the keys a record leaves out take the data file's [defaults]:
    ``shaft_length_mm``, ``housing_wall_mm``, ``jet_L_per_min`` its values, ``housing_length_mm`` =
    ``housing_length_per_damper_length`` x ``damper_length_mm``, ``rub_ring_radius_mm`` = ``bore_diameter_mm`` / 2
    (the ring on the shaft next to the bearing)."""
    if isinstance(bearing, dict):
        d = dict(bearing)
    elif bearing in BEARINGS:
        d = dict(BEARINGS[bearing])
    else:
        raise ValueError(f"bearing must be one of {sorted(BEARINGS)}, got {bearing!r}")
    missing = [key for key in REQUIRED if key not in d]
    if missing:
        raise ValueError(f"bearing record lacks {', '.join(missing)}")
    dflt = THERMAL_DATA["defaults"]
    for key in ("shaft_length_mm", "housing_wall_mm", "jet_L_per_min"):
        d.setdefault(key, dflt[key])
    d.setdefault("housing_length_mm", dflt["housing_length_per_damper_length"] * d["damper_length_mm"])
    d.setdefault("rub_ring_radius_mm", d["bore_diameter_mm"] / 2)
    return d


def radii(bearing: int | dict) -> dict:
    """Radii and lengths (m) of the bearing, journal and housing used by Table 1 and eqs. (13)-(15)."""
    d = bearing_data(bearing)
    name = bearing if isinstance(bearing, int) else "(parameters)"
    mm = 1e-3
    bore, od, D = d["bore_diameter_mm"] * mm, d["outside_diameter_mm"] * mm, d["ball_diameter_mm"] * mm
    dm = 0.5 * (bore + od)   # pitch diameter ~ mean of bore and OD (Harris & Kotzalas)
    g = {
        "r_s": bore / 2, "r_i": (dm - D) / 2, "r_e": (dm + D) / 2, "r_o": od / 2, "r_b": D / 2,
        "W": d["width_mm"] * mm, "n": int(d["n_balls"]),
        "r_j": d["damper_radius_mm"] * mm, "L_j": d["damper_length_mm"] * mm, "c_sf": d["damper_clearance_mm"] * mm,
        "L_s": d["shaft_length_mm"] * mm, "L_h": d["housing_length_mm"] * mm,
    }
    g["r_hi"] = g["r_j"] + g["c_sf"]
    g["r_h"] = g["r_hi"] + d["housing_wall_mm"] * mm
    for key, value in g.items():
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"bearing {name}: {key} must be > 0, got {value}")
    if not g["r_s"] < g["r_i"] < g["r_e"] < g["r_o"] < g["r_j"] < g["r_hi"] < g["r_h"]:
        raise ValueError(f"bearing {name}: radii are not nested (shaft bore/2 < inner raceway < outer raceway < "
                         f"outside diameter/2 < damper radius < housing): "
                         + ", ".join(f"{k} = {1e3 * g[k]:.4g} mm" for k in ("r_s", "r_i", "r_e", "r_o", "r_j",
                                                                            "r_hi", "r_h")))
    return g


def shaft_convection(omega: float, r: float) -> float:
    """h of a rotating cylinder in air, W/(m^2 K) (data/thermal.toml [convection])."""
    c = THERMAL_DATA["convection"]
    return c["shaft_a"] * abs(omega) ** c["shaft_b"] * r ** c["shaft_c"]


def oil_viscosity(T: float) -> float:
    """Kinematic viscosity (m^2/s) of the SAE 30 oil at T (K): Walther / ASTM D341 fit of data/thermal.toml."""
    c = THERMAL_DATA["convection"]
    return (10.0 ** (10.0 ** (c["walther_A"] - c["walther_B"] * math.log10(T))) - 0.7) * 1e-6


def oil_convection(bearing: int, omega: float) -> dict:
    """Harris's film coefficients (W/(m^2 K)) of the inner race, outer race and balls in the bearing oil at shaft
    speed omega (rad/s), at the oil film temperature of data/thermal.toml, and the wetted areas (m^2)."""
    g, d = radii(bearing), bearing_data(bearing)
    c, oil = THERMAL_DATA["convection"], THERMAL_DATA["oil"]
    nu = oil_viscosity(c["oil_film_temperature_C"] + 273.15)
    k = oil["conductivity"]
    pr = nu * oil["density"] * oil["specific_heat"] / k
    n_rpm = abs(omega) * 60.0 / (2.0 * math.pi)
    dm = g["r_i"] + g["r_e"]
    gamma = 2.0 * g["r_b"] * math.cos(math.radians(d["contact_angle_deg"])) / dm
    h_i = c["harris_coefficient"] * math.sqrt(n_rpm / nu * (1.0 + gamma)) * k * pr ** (1.0 / 3.0)
    h_e = c["harris_coefficient"] * math.sqrt(n_rpm / nu * (1.0 - gamma)) * k * pr ** (1.0 / 3.0)
    r_b, W, n = g["r_b"], g["W"], g["n"]
    return {
        "h_i": h_i, "h_e": h_e, "h_b": 0.5 * (h_i + h_e), "nu": nu, "Pr": pr, "gamma": gamma,
        "A_i": 2 * math.pi * g["r_i"] * W - math.pi * n * r_b ** 2,
        "A_e": 2 * math.pi * g["r_e"] * W - math.pi * n * r_b ** 2,
        "A_b": n * 4.0 * math.pi * r_b ** 2,
    }


def rub_partition(bearing: int, omega: float) -> float:
    """Blok partition: the fraction of the rub heat entering the rotor (data/thermal.toml [rub]).

    Rotor: stationary uniform disk source of radius a (synchronous whirl), mean rise per flux R_1 = 8 a/(3 pi k);
    ring: fast-moving source at V = omega R_r, R_2 = (4/3) sqrt(2 kappa a/(pi V)) / k; f = R_2 / (R_1 + R_2)."""
    d, st = bearing_data(bearing), THERMAL_DATA["steel"]
    a = THERMAL_DATA["rub"]["contact_half_width_mm"] * 1e-3
    V = abs(omega) * d["rub_ring_radius_mm"] * 1e-3
    if not V > 0.0:
        return 1.0          # no sliding speed: no moving source, nothing to partition by speed (and no rub heat)
    k = st["conductivity"]
    kappa = k / (st["density"] * st["specific_heat"])
    R1 = 8.0 * a / (3.0 * math.pi * k)
    R2 = 4.0 / 3.0 * math.sqrt(2.0 * kappa * a / (math.pi * V)) / k
    return R2 / (R1 + R2)


def jet_flow(bearing: int) -> float:
    """The bearing's oil-jet flow from the data file, m^3/s."""
    return bearing_data(bearing)["jet_L_per_min"] * 1e-3 / 60.0


def resistances(bearing: int, omega: float) -> dict:
    """The Table 1 resistances (K/W) of bearing 0 or 5 at shaft speed omega (rad/s)."""
    g = radii(bearing)
    st, oil = THERMAL_DATA["steel"], THERMAL_DATA["oil"]
    k, kl = st["conductivity"], oil["conductivity"]
    r_s, r_i, r_e, r_o, r_b, W, n = g["r_s"], g["r_i"], g["r_e"], g["r_o"], g["r_b"], g["W"], g["n"]
    r_j, L_j, c_sf, r_hi, r_h, L_h, L_s = g["r_j"], g["L_j"], g["c_sf"], g["r_hi"], g["r_h"], g["L_h"], g["L_s"]
    h_s = shaft_convection(omega, r_s)
    h_h = THERMAL_DATA["convection"]["housing"]
    a_i = 2 * math.pi * r_i * W - math.pi * n * r_b ** 2
    a_e = 2 * math.pi * r_e * W - math.pi * n * r_b ** 2
    if a_i <= 0 or a_e <= 0:
        raise ValueError(f"bearing {bearing}: the balls cover the raceway (lubricant area <= 0)")
    ann = r_h ** 2 - r_hi ** 2
    R = {
        "R_Li": r_b / (kl * a_i),
        "R_Le": r_b / (kl * a_e),
        "R_b": 1.0 / (n * k * math.pi * r_b),
        "R_i": math.log(r_i / r_s) / (2 * math.pi * k * W),
        "R_sr": 1.0 / (math.pi * k * W),
        "R_sa": L_s / (k * math.pi * r_s ** 2) + 1.0 / (h_s * math.pi * r_s ** 2) if h_s > 0 else math.inf,
        "R_e": math.log(r_o / r_e) / (2 * math.pi * k * W),
        "R_j": math.log(r_j / r_o) / (2 * math.pi * k * W),
        "R_sf1": math.log((r_j + c_sf / 2) / r_j) / (2 * math.pi * kl * L_j),
        "R_sf2": math.log(r_hi / (r_j + c_sf / 2)) / (2 * math.pi * kl * L_j),
        "R_hr": math.log(r_h / r_hi) / (2 * math.pi * k * L_h) + 1.0 / (h_h * 2 * math.pi * r_h * L_h),
        "R_ha": L_h / (2 * math.pi * k * ann) + 1.0 / (math.pi * h_h * ann),
    }
    R["R_h"] = R["R_hr"] * R["R_ha"] / (R["R_hr"] + R["R_ha"])
    return R


def journal_shells() -> int:
    """N, the journal sleeve's radial shells (data/thermal.toml [lumping]); 1 is the paper's single node."""
    n = THERMAL_DATA["lumping"]["journal_shells"]
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= 64:
        raise ValueError(f"{DATA}: [lumping] journal_shells must be an integer in [1, 64], got {n!r}")
    return n


def shell_radii(bearing: int) -> np.ndarray:
    """The radii r_o = rr_0 < rr_1 < ... < rr_N = r_j of the journal's shell nodes (equal log steps), m."""
    g = radii(bearing)
    N = journal_shells()
    return g["r_o"] * (g["r_j"] / g["r_o"]) ** (np.arange(N + 1) / N)


def shell_nodes() -> list:
    """Node indices of the journal sleeve from the outer race outwards: the N - 1 inner shells, then JOURNAL."""
    return list(range(9, 9 + journal_shells() - 1)) + [JOURNAL]


def heat_masses(bearing: int) -> np.ndarray:
    """m c_p of the nine named nodes, then the journal's inner shells (see the module docstring), J/K."""
    g = radii(bearing)
    st, oil = THERMAL_DATA["steel"], THERMAL_DATA["oil"]
    rc_s, rc_o = st["density"] * st["specific_heat"], oil["density"] * oil["specific_heat"]
    pi = math.pi
    v_balls = g["n"] * 4.0 / 3.0 * pi * g["r_b"] ** 3
    v_free = pi * (g["r_e"] ** 2 - g["r_i"] ** 2) * g["W"] - v_balls
    N = journal_shells()
    C = np.empty(9 + N - 1)
    C[SHAFT] = rc_s * pi * g["r_s"] ** 2 * g["L_s"]
    C[IR] = rc_s * pi * (g["r_i"] ** 2 - g["r_s"] ** 2) * g["W"]
    C[LI] = C[LE] = rc_o * 0.5 * v_free * THERMAL_DATA["oil_flow"]["lubricant_fill_fraction"]
    C[BALL] = rc_s * v_balls
    C[OR] = rc_s * pi * (g["r_o"] ** 2 - g["r_e"] ** 2) * g["W"]
    rr = shell_radii(bearing)
    edges = np.concatenate(([rr[0]], 0.5 * (rr[1:-1] + rr[2:]), [rr[-1]]))   # owned by node m: edges[m-1..m]
    for node, a, b in zip(shell_nodes(), edges[:-1], edges[1:]):
        C[node] = rc_s * pi * (b ** 2 - a ** 2) * g["L_j"]
    C[SFD] = rc_o * 2 * pi * g["r_j"] * g["c_sf"] * g["L_j"]
    C[HOUSING] = rc_s * pi * (g["r_h"] ** 2 - g["r_hi"] ** 2) * g["L_h"]
    return C


def source_map(drag_inner_fraction: float, contact_race_fraction: float, rub_shaft_fraction: float,
               rub_ring_housing_fraction: float = 1.0) -> np.ndarray:
    """S (9 x 3): node heat sources per watt of [P_drag, P_sfd, P_rub]. The drag and film columns sum to 1; the
    rub column to rub_shaft_fraction + (1 - rub_shaft_fraction) rub_ring_housing_fraction: the rest of the ring's
    share stays in the ring and the casing, which are not nodes of this network."""
    for name, f in (("drag_inner_fraction", drag_inner_fraction), ("contact_race_fraction", contact_race_fraction),
                    ("rub_shaft_fraction", rub_shaft_fraction),
                    ("rub_ring_housing_fraction", rub_ring_housing_fraction)):
        if not (math.isfinite(f) and 0.0 <= f <= 1.0):
            raise ValueError(f"{name} must be within [0, 1], got {f}")
    S = np.zeros((9, 3))
    fi, fr = drag_inner_fraction, contact_race_fraction
    S[IR, 0] = fi * fr
    S[OR, 0] = (1 - fi) * fr
    S[BALL, 0] = 1 - fr
    S[SFD, 1] = 1.0
    S[SHAFT, 2] = rub_shaft_fraction
    S[HOUSING, 2] = (1 - rub_shaft_fraction) * rub_ring_housing_fraction
    return S


def default_sources() -> dict:
    """drag_inner_fraction, contact_race_fraction from the data file; rub_shaft_fraction -1 (= rub_partition)."""
    return {**THERMAL_DATA["sources"], "rub_shaft_fraction": -1.0}


def build_network(bearing: int, omega: float, T_ambient: float, T_supply: float,
                  drag_inner_fraction: float | None = None, contact_race_fraction: float | None = None,
                  rub_shaft_fraction: float | None = None, bearing_oil_flow: float | None = None,
                  sfd_oil_flow: float | None = None, rub_ring_housing_fraction: float | None = None) -> LinearNetwork:
    """The network of bearing 0 or 5 (flows in m^3/s; None or < 0: the data-file value; rub_shaft_fraction None or
    < 0: the Blok partition of :func:`rub_partition`)."""
    src = default_sources()
    flows = THERMAL_DATA["oil_flow"]
    Lmin = 1e-3 / 60.0
    q_b = jet_flow(bearing) if bearing_oil_flow is None or bearing_oil_flow < 0.0 else bearing_oil_flow
    if rub_shaft_fraction is None or rub_shaft_fraction < 0.0:
        rub_shaft_fraction = rub_partition(bearing, omega)
    if rub_ring_housing_fraction is None or rub_ring_housing_fraction < 0.0:
        rub_ring_housing_fraction = THERMAL_DATA["rub"]["ring_housing_fraction"]
    q_s = flows["sfd_L_per_min"] * Lmin if sfd_oil_flow is None else sfd_oil_flow
    for name, v in (("bearing_oil_flow", q_b), ("sfd_oil_flow", q_s), ("T_ambient", T_ambient),
                    ("T_supply", T_supply)):
        if not (math.isfinite(v) and v >= 0.0):
            raise ValueError(f"{name} must be finite and >= 0, got {v}")
    if T_ambient <= 0 or T_supply <= 0:
        raise ValueError(f"temperatures must be > 0 K, got T_ambient={T_ambient}, T_supply={T_supply}")
    R = resistances(bearing, omega)
    oil = THERMAL_DATA["oil"]
    rc_o = oil["density"] * oil["specific_heat"]
    branches = [
        (SHAFT, IR, R["R_sr"] + R["R_i"]),
        (IR, LI, R["R_Li"] / 2), (LI, BALL, R["R_Li"] / 2),
        (IR, BALL, R["R_b"]), (BALL, OR, R["R_b"]),
        (BALL, LE, R["R_Le"] / 2), (LE, OR, R["R_Le"] / 2),
        (JOURNAL, SFD, R["R_sf1"]), (SFD, HOUSING, R["R_sf2"]),
    ]
    # outer race - journal (R_e + R_j), the journal sleeve in shells (module docstring; one branch for N = 1)
    rr, shells = shell_radii(bearing), shell_nodes()
    k_j = THERMAL_DATA["steel"]["conductivity"]
    seg = [math.log(rr[m + 1] / rr[m]) / (2 * math.pi * k_j * radii(bearing)["W"]) for m in range(len(shells))]
    seg[-1] = R["R_j"] - sum(seg[:-1])     # the segments sum to R_j to round-off
    branches.append((OR, shells[0], R["R_e"] + seg[0]))
    branches += [(shells[m - 1], shells[m], seg[m]) for m in range(1, len(shells))]
    if omega != 0.0:                      # oil-wetted convection (Harris), in parallel with the Table 1 layers
        h = oil_convection(bearing, omega)
        branches += [
            (IR, LI, 1.0 / (h["h_i"] * h["A_i"])),
            (BALL, LI, 2.0 / (h["h_b"] * h["A_b"])), (BALL, LE, 2.0 / (h["h_b"] * h["A_b"])),
            (LE, OR, 1.0 / (h["h_e"] * h["A_e"])),
        ]
    C = heat_masses(bearing)
    n = len(C)
    K = np.zeros((n, n))
    for a, b, r in branches:
        g = 1.0 / r
        K[a, a] += g
        K[b, b] += g
        K[a, b] -= g
        K[b, a] -= g
    ground = np.zeros(n)
    T_ground = np.full(n, float(T_ambient))
    ground[SHAFT] = 1.0 / R["R_sa"]
    ground[HOUSING] = 1.0 / R["R_h"]
    T_ground[HOUSING] = T_supply          # oil-wetted in the bearing chamber (data/thermal.toml [convection])
    for node, q in ((LI, 0.5 * q_b), (LE, 0.5 * q_b), (SFD, q_s)):
        ground[node] = rc_o * q
        T_ground[node] = T_supply
    K[np.diag_indices(n)] += ground
    S = np.zeros((n, 3))
    S[:9] = source_map(src["drag_inner_fraction"] if drag_inner_fraction is None else drag_inner_fraction,
                       src["contact_race_fraction"] if contact_race_fraction is None else contact_race_fraction,
                       rub_shaft_fraction, rub_ring_housing_fraction)
    return LinearNetwork(C=C, K=K, b=ground * T_ground, S=S, ground=ground, T_ground=T_ground)
