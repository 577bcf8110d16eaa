"""Is there a plausible layout with bearing #0's support mode ABOVE the 16 000 rev/min running speed? (A
time-boxed structural study, linear engine only.)

The question (docs/results/calibration.md, "A layout with #0's support mode above the running speed"): a layout in which
  (a) the linear engine (master/linear_engine, as ``rotorcosim critical-speeds``) has its two lowest forward
      synchronous critical speeds at 8500 and 10 200 rev/min (+-3 %), whatever modes they are;
  (b) every forward mode that strains bearing #0's O-ring lies above 16 000 rev/min with a design separation
      margin (15-20 %, i.e. above 18 400-19 200 rev/min), so that the bearing #0 point is stiffness-controlled
      at the running speed (receptance phase well above -90 deg), the regime the paper's text describes;
  (c) with the paper's O-ring (5254 N/mm per support, or two in parallel) and every other shipped reading
      unchanged (rings-alone journal, bearings, damper, rub ring, thermal data).

Part 1 varies the power turbine only (each value with its reason above LAYOUTS below) and prints, per layout and O-ring
reading: the forward synchronous modes below 25 000 rev/min (share of their strain energy in #0's O-ring), the
lowest mode above the running speed that strains #0's O-ring by at least 5 % and its margin, the linear 712 N
whirl and transmissibility at #0 and #5 (film at 30 C), the receptance phase of the bearing #0 point relative to
its housing at 16 000 rev/min (film at 30 C and at 85 C, the film oil of the rubbing cases) and the rub ring's
normal force at 8551 N estimated as in bench_rub_modes.py (paper: 3.7 kN).

Part 2 takes the best plausible layout of part 1 (all its #0-straining modes above the running speed) and asks
whether its two lowest forward critical speeds can be put at 8500 / 10 200 rev/min: mount_k (the shipped second
knob) places the lowest, the casing on its mounts, at 8500; a second lever must bring another rotor mode to 10 200
without straining #0: the front / rear mount links apart, the mount planes moved inboard, the gas generator's
stage masses, the gas generator's bearing frames, the hub masses, the casing's smeared mass, an overhung gas-generator turbine, the power turbine's tube: each scanned over its
plausible range (and one value outside it, to show what it would take) with mount_k fitted to the first.

Part 3 tries (a) by the #5 end instead: the second critical speed as bearing #5's support mode (the power turbine's
output end on #5's O-ring, below the running speed, which leaves #0 alone), with bearing #5 further behind the aft
intermediate bearing and the output coupling's mass at #5 as a third knob (solved with mount_k).

    python bench/bench_support_above_running.py          # ~10 min on a quiet machine
    python bench/bench_support_above_running.py --write-candidate span120|end5 FILE [O-RING FACTOR]  # study files
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import copy
import math
import sys
from pathlib import Path

import numpy as np

from rotorcosim.components.rotor import calibration, critical
from rotorcosim.components.rotor import model as fem
from rotorcosim.cases.blade_loss import linear_engine as le

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_rub_modes as brm  # noqa: E402 - after the sys.path line above (the bench folder is not a package)
import bench_support_isolation as bsi  # noqa: E402 - after the sys.path line above (the bench folder is not a package)

RUN_RPM = 16000.0
#: a design separation margin of 15-20 % between a critical speed and the running speed (the brief's "typical
#: engine design margin"; API 617 / API 684 ask 10-26 % above the maximum continuous speed for a mode with an
#: amplification factor of 2.5 or more, none below 2.5)
MARGIN = 0.15
TARGET = (8500.0, 10200.0)

#: The power-turbine levers, each at its plausible end (shipped in brackets):
#: - stage mass 0.5 kg [1.17]: the light end for a bladed stage of ~0.22 m over the blades on a 50.8 mm bore;
#:   0.05 kg is a massless bound, not a design;
#: - overhang 30 mm [60], bearing #0's centre to the inner stage (stage 2 30 mm further out): half a 50.8 mm bore
#:   bearing (~10 mm) plus half a disk hub (~15 mm), the tightest that fits;
#: - span 120-150 mm [350], bearing #0 to the forward intermediate bearing (everything aft moves with it): the
#:   shortest that leaves room for the inter-turbine duct between the PT stages and the GG turbine;
#: - neck 60/30 mm [45/20] between #0 and the forward intermediate bearing: the largest that still passes the gas
#:   generator's 95 mm bore inside a thin-section bearing;
#: - stub 60/44 mm [60/20] under the stages: the disks' hubs carry the stage mass, the shaft there can be hollow.
LAYOUTS = [
    ("shipped", {}),
    ("overhang 30, stages 0.5 kg", dict(m_stage=0.5, overhang=30.0)),
    ("+ span 150, neck 60/30", dict(m_stage=0.5, overhang=30.0, span=150.0, neck=(60.0, 30.0))),
    ("+ hollow stub 60/44", dict(m_stage=0.5, overhang=30.0, span=150.0, neck=(60.0, 30.0), stub=(60.0, 44.0))),
    ("+ span 120", dict(m_stage=0.5, overhang=30.0, span=120.0, neck=(60.0, 30.0), stub=(60.0, 44.0))),
    ("bound: stages 0.05 kg, span 120", dict(m_stage=0.05, overhang=30.0, span=120.0, neck=(60.0, 30.0),
                                             stub=(60.0, 44.0))),
]


def variant(data: dict, m_stage=None, overhang=None, span=None, neck=None, stub=None) -> dict:
    """A copy of the rotor data with the power-turbine levers applied (node 3 is bearing #0, node 5 the forward
    intermediate bearing; a new span moves the gas generator, the casing rings and hubs aft of #0 with it)."""
    d = copy.deepcopy(data)
    p, g, cas = d["spool"]["pt"], d["spool"]["gg"], d["casing"]
    z = list(p["z_mm"])
    if span is not None:
        D = span - (z[5] - z[3])
        z = z[:4] + [z[3] + span / 2, z[3] + span] + [v + D for v in z[6:]]
        g["z_mm"] = [v + D for v in g["z_mm"]]
        cas["ring_z_mm"] = [v if v <= z[3] else v + D for v in cas["ring_z_mm"]]
        for hv in cas["hubs"].values():
            if hv["z_mm"] > z[3]:
                hv["z_mm"] += D
    if overhang is not None:
        z[0], z[1], z[2] = z[3] - overhang - 30.0, z[3] - overhang, z[3] - overhang / 2
    p["z_mm"] = z
    if neck is not None:
        for e in (3, 4):
            p["d_out_mm"][e], p["d_in_mm"][e] = neck
    if stub is not None:
        for e in (0, 1):
            p["d_out_mm"][e], p["d_in_mm"][e] = stub
    if m_stage is not None:
        d["calibration"]["pt_stage_mass_kg"] = m_stage
    return d


def supports(oring: float, T_C: float | None = None) -> dict:
    s = le.supports(oil_temperature_C=T_C)
    for key in s:
        s[key]["k_spring"] *= oring
    return s


def figures(d: dict, oring: float) -> dict:
    s30, s85 = supports(oring), supports(oring, 85.0)
    f = fem.build(d)
    modes = bsi.strain_shares(f, s30)
    above = [m for m in modes if m[0] > RUN_RPM and m[1] >= 0.05]
    below = [m for m in modes if m[0] <= RUN_RPM and m[1] >= 0.05]
    r = calibration.coupled_response(f, s30, 712.0)
    _, hg30 = brm.ring_receptances(f, s30, int(d["attach"]["rubring0"]["node"][1]))
    hu, hg = brm.ring_receptances(f, s85, int(d["attach"]["rubring0"]["node"][1]))
    return {"modes": modes, "first_above": above[0] if above else None, "below": below, "r": r,
            "phase30": math.degrees(np.angle(hg30)), "phase85": math.degrees(np.angle(hg)),
            "N8551": brm.ring_force(hu, hg, 8551.0, 0.508e-3, 3e8, 0.2)}


def part1(data: dict) -> None:
    print(f"1. power-turbine layouts (film 30 C; margin wanted {MARGIN:.0%}: #0-straining modes above "
          f"{RUN_RPM * (1 + MARGIN):.0f} rev/min)")
    for oring in (1.0, 2.0):
        print(f"  O-ring {oring:g} x 5254 N/mm")
        for name, kw in LAYOUTS:
            g = figures(variant(data, **kw), oring)
            modes = " ".join(f"{m[0]:.0f} ({m[1]:.2f})" for m in g["modes"][:4])
            fa = g["first_above"]
            fa_s = f"{fa[0]:.0f} ({fa[1]:.2f}, margin {fa[0] / RUN_RPM - 1:+.1%})" if fa else "none"
            r0, r5 = g["r"]["0"], g["r"]["5"]
            print(f"    {name:34s} modes {modes}")
            print(f"    {'':34s} #0-straining: {len(g['below'])} below 16 000, first above {fa_s}; 712 N #0 "
                  f"{r0['whirl_mm']:.4f} mm T {r0['transmissibility']:.2f}, #5 {r5['whirl_mm']:.4f} mm "
                  f"T {r5['transmissibility']:.3f}; #0 point phase {g['phase30']:.0f} deg (30 C) "
                  f"{g['phase85']:.0f} deg (85 C); ring force at 8551 N {g['N8551'] / 1e3:.1f} kN", flush=True)


def _mount_front_over_rear(d, s):
    """Front links at s x mount_k, rear at mount_k (the pitch / bounce ratio)."""
    r0 = min(m["ring"] for m in d["casing"]["mounts"])
    for m in d["casing"]["mounts"]:
        if m["ring"] == r0:
            m["k"] = d["calibration"]["mount_k"] * s


def _mount_planes(d, s):
    """Both mount planes moved inboard by s rings (0: the casing's end frames, as shipped)."""
    n = len(d["casing"]["ring_z_mm"]) - 1
    for m in d["casing"]["mounts"]:
        m["ring"] = int(s) if m["ring"] == 0 else n - int(s)


def _gg_mass(d, s):
    for dk in d["spool"]["gg"]["disks"]:
        for k in ("mass", "Ip", "Id"):
            dk[k] *= s


def _gg_frames(d, s):
    for h in ("b1", "b2", "b3", "b4"):
        d["casing"]["hubs"][h]["struts"] = {k: v * s for k, v in d["casing"]["struts"].items()}


def _hub_mass(d, s):
    for h in d["casing"]["hubs"].values():
        h["mass"] = s


def _casing_mass(d, s):
    d["material"]["casing"]["rho"] *= s


def _casing_wall(d, t_mm):
    d["casing"]["thickness_mm"] = t_mm


def _casing_radius(d, r_mm):
    d["casing"]["radius_mm"] = r_mm


def _gg_overhung(d, node):
    """GG bearing 4 moved from ahead of the GG turbine stages to GG node ``node`` behind them (an overhung gas
    generator turbine, as in engines whose compressor turbine sits outboard of its bearings)."""
    if node == 1:
        return
    g, cas = d["spool"]["gg"], d["casing"]
    zb4 = g["z_mm"][int(node)]
    for s in d["support"]:
        if s["name"] == "GG bearing 4":
            s["a"] = ["gg", int(node)]
    cas["ring_z_mm"] = sorted(set(cas["ring_z_mm"]) - {cas["hubs"]["b4"]["z_mm"]} | {zb4})
    cas["hubs"]["b4"]["z_mm"] = zb4


def _stretch_aft(d, s):
    """Everything aft of the forward intermediate bearing (gas generator, PT tube, casing, aft overhang) stretched
    by s: a longer gas generator (more or wider compressor stages)."""
    p, g, cas = d["spool"]["pt"], d["spool"]["gg"], d["casing"]
    z5 = p["z_mm"][5]

    def f(z):
        return z if z <= z5 else z5 + s * (z - z5)
    p["z_mm"] = [f(z) for z in p["z_mm"]]
    g["z_mm"] = [f(z) for z in g["z_mm"]]
    cas["ring_z_mm"] = [f(z) for z in cas["ring_z_mm"]]
    for h in cas["hubs"].values():
        h["z_mm"] = f(h["z_mm"])


def _pt_tube(d, d_out):
    p = d["spool"]["pt"]
    for e in range(5, 16):
        p["d_out_mm"][e], p["d_in_mm"][e] = d_out, d_out - 12.0     # a 6 mm wall


#: (lever, apply(data, value), values: the plausible range first, then (in brackets in the output) a value outside
#: it showing what the lever would need, why that range)
LEVERS2 = [
    ("front / rear mount links", _mount_front_over_rear, (0.3, 1.0, 3.0, 0.05), "ratio 0.3-3"),
    ("mount planes inboard by n rings", _mount_planes, (0, 1, 2), "the casing's rings"),
    ("GG stage masses x s", _gg_mass, (0.5, 1.0, 2.0, 4.0), "8 / 4 kg stages shipped: s 0.5-2"),
    ("GG bearing frames x s", _gg_frames, (0.25, 1.0, 0.05, 0.01),
     "s >= 0.25: a frame softer than the Table 2 bearing it carries makes the bearing data meaningless"),
    ("hub masses (kg)", _hub_mass, (3.0, 10.0, 20.0, 100.0), "3-20 kg (bearing housing + race + SFD housing)"),
    ("casing smeared mass x s", _casing_mass, (1.0, 2.0, 5.0), "s 1-2 (flanges, accessories)"),
    ("casing wall (mm)", _casing_wall, (12.0, 6.0, 3.0), "3-12 mm (an engine casing is a few mm thick)"),
    ("casing mean radius (mm)", _casing_radius, (300.0, 200.0), "200-300 mm (clears the 0.2 m turbine disks)"),
    ("GG bearing 4 at GG node (1 = shipped)", _gg_overhung, (1, 5, 6), "ahead of or behind the GG turbine"),
    ("engine aft of the forward intermediate bearing stretched x s", _stretch_aft, (1.0, 1.3, 1.5),
     "a 700-1050 mm gas generator"),
    ("PT tube outer diameter (mm, 6 mm wall)", _pt_tube, (66.0, 50.0, 40.0, 20.0), "40-70 mm (torque, the GG bore)"),
]


def _forward(d, sup, n=3):
    fw = critical.synchronous_critical_speeds(fem.build(d), sup, n=n)["forward_synchronous_rpm"]
    return (fw + [math.nan] * n)[:n]


def fit_mounts(d, sup, target=TARGET[0], iters=8):
    """mount_k (all links, as the shipped calibration) such that the lowest forward critical speed is ``target``
    (secant on log k: the casing-on-mounts mode goes about as sqrt(k)); returns (data, forward speeds)."""
    def at(k):
        d2 = copy.deepcopy(d)
        d2["calibration"]["mount_k"] = k
        for m in d2["casing"]["mounts"]:
            if not isinstance(m["k"], str):       # front / rear split: keep the ratio to mount_k
                m["k"] = m["k"] / d["calibration"]["mount_k"] * k
        return d2, _forward(d2, sup)
    k = float(d["calibration"]["mount_k"])
    for _ in range(iters):
        d2, f = at(k)
        if not math.isfinite(f[0]) or abs(f[0] - target) < 5.0:
            break
        k *= (target / f[0]) ** 2
    return d2, f


def part2(data: dict) -> None:
    name, kw = LAYOUTS[4]
    oring = 2.0
    base = variant(data, **kw)
    sup = supports(oring)
    print(f"2. criterion (a) on the layout '{name}' (O-rings {oring:g} x 5254 N/mm; its forward modes "
          f"{[round(m[0]) for m in bsi.strain_shares(fem.build(base), sup)[:4]]} rev/min): mount_k fitted so "
          f"that the lowest forward critical speed is {TARGET[0]:.0f}; is the second at {TARGET[1]:.0f} +-3 %?")
    for label, apply, values, why in LEVERS2:
        print(f"   {label} ({why}):")
        for v in values:
            d = copy.deepcopy(base)
            apply(d, v)
            d, f = fit_mounts(d, sup)
            g = figures(d, oring)
            fa = g["first_above"]
            ok = abs(f[0] / TARGET[0] - 1) < 0.03 and abs(f[1] / TARGET[1] - 1) < 0.03
            below = ", ".join(f"{m[0]:.0f} ({m[1]:.2f})" for m in g["below"]) or "none"
            above = f"{fa[0]:.0f} ({fa[1]:.2f})" if fa else "none"
            r0, r5 = g["r"]["0"], g["r"]["5"]
            print(f"      {v:>6g}: mount_k {d['calibration']['mount_k']:.3e} N/m, forward {[round(x) for x in f]} "
                  f"rev/min ({'MET' if ok else 'not met'}); #0-straining (O-ring share) below 16 000: {below}, "
                  f"first above: {above}; #0 point {g['phase30']:.0f} deg; 712 N whirl #0 {r0['whirl_mm']:.4f} "
                  f"mm T {r0['transmissibility']:.2f}, #5 {r5['whirl_mm']:.4f} mm", flush=True)


def _fmt(v) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


def _aft_overhang(d, L_mm):
    """Bearing #5 at L_mm behind the aft intermediate bearing (PT node 16; shipped 150 mm), its casing ring and hub
    with it: the power turbine's output end reaching further forward through the gas generator's inlet."""
    p, cas = d["spool"]["pt"], d["casing"]
    z16 = p["z_mm"][16]
    p["z_mm"] = p["z_mm"][:17] + [z16 + L_mm * k / 5.0 for k in range(1, 6)]
    cas["ring_z_mm"][-1] = z16 + L_mm
    cas["hubs"]["h5"]["z_mm"] = z16 + L_mm


#: gyration radius of the output coupling (flange + spline adapter of ~0.12 m diameter)
COUPLING_R = 0.06


def _coupling(d, m_kg):
    """The output coupling at the #5 end (PT node 21) as a rigid disk of m_kg (Ip = m r^2, Id = Ip / 2)."""
    if m_kg > 0:
        Ip = m_kg * COUPLING_R ** 2
        d["spool"]["pt"]["disks"].append({"node": 21, "name": "output coupling", "mass": m_kg, "Ip": Ip,
                                            "Id": Ip / 2.0})


def fit_mounts_coupling(d0, sup, x0=(7e7, 6.0), iters=10):
    """Newton on (mount_k, output coupling mass) to the two lowest forward critical speeds; returns (data, knobs,
    forward speeds)."""
    def build(x):
        d = copy.deepcopy(d0)
        d["calibration"]["mount_k"] = float(x[0])
        _coupling(d, float(x[1]))
        return d
    x, t = np.array(x0, float), np.array(TARGET)
    for _ in range(iters):
        f = np.array(_forward(build(x), sup)[:2])
        if np.max(np.abs(f - t)) < 3.0:
            break
        J = np.empty((2, 2))
        for j in range(2):
            dx = x.copy()
            dx[j] *= 1.02
            J[:, j] = (np.array(_forward(build(dx), sup)[:2]) - f) / (dx[j] - x[j])
        x = np.clip(x - np.linalg.solve(J, f - t), x / 2.0, 2.0 * x)
    d = build(x)
    return d, x, _forward(d, sup, n=4)


def part3(data: dict) -> None:
    """(a) by the #5 end: the second critical speed as bearing #5's support mode (the power turbine's output end on
    #5's O-ring), with a longer aft overhang and the output coupling's mass as a third knob."""
    oring = 2.0
    sup = supports(oring)
    print(f"3. (a) by the #5 end on '{LAYOUTS[4][0]}' (O-rings {oring:g} x): output coupling mass at #5 (third knob) "
          f"and mount_k solved for {TARGET[0]:.0f} / {TARGET[1]:.0f} rev/min, bearing #5 at L behind the aft "
          f"intermediate bearing (shipped 150 mm)")
    for L in (150.0, 250.0, 350.0):
        d0 = variant(data, **LAYOUTS[4][1])
        _aft_overhang(d0, L)
        try:
            d, x, f = fit_mounts_coupling(d0, sup)
        except np.linalg.LinAlgError as exc:
            print(f"   L {L:.0f} mm: fit failed ({exc})")
            continue
        g = figures(d, oring)
        modes = " ".join(f"{m[0]:.0f} (#0 {m[1]:.2f}, #5 {m[2]:.2f})" for m in g["modes"][:4])
        fa = g["first_above"]
        r0, r5 = g["r"]["0"], g["r"]["5"]
        above = f"{fa[0]:.0f} ({fa[0] / RUN_RPM - 1:+.1%})" if fa else "none"
        print(f"   L {L:.0f} mm: coupling {x[1]:.2f} kg, mount_k {x[0]:.3e} N/m, forward {[round(v) for v in f]}; "
              f"modes (O-ring strain shares) {modes}; #0-straining below 16 000: {len(g['below'])}, first above "
              f"{above}; #0 point {g['phase30']:.0f} / {g['phase85']:.0f} deg (30 / 85 C); 712 N #0 "
              f"{r0['whirl_mm']:.4f} mm T {r0['transmissibility']:.2f}, #5 {r5['whirl_mm']:.4f} mm T "
              f"{r5['transmissibility']:.3f}; ring force at 8551 N {g['N8551'] / 1e3:.1f} kN", flush=True)


def candidate(kind: str, oring: float) -> tuple[dict, list, str]:
    """The study layouts as data: 'span120' ('+ span 120', mount_k fitted to 8500 rev/min) or 'end5' (the same
    with bearing #5 350 mm behind the aft intermediate bearing and the output coupling and mount_k solved for
    8500 / 10 200 rev/min)."""
    data, _ = fem.load_data(None)
    d0 = variant(data, **LAYOUTS[4][1])
    if kind == "span120":
        d, f = fit_mounts(d0, supports(oring))
        return d, f, f"layout '{LAYOUTS[4][0]}' ({LAYOUTS[4][1]}), mount_k fitted to 8500 rev/min"
    if kind == "end5":
        _aft_overhang(d0, 350.0)
        d, x, f = fit_mounts_coupling(d0, supports(oring))
        return d, f, (f"layout '{LAYOUTS[4][0]}' ({LAYOUTS[4][1]}), bearing #5 350 mm behind the aft intermediate "
                      f"bearing, output coupling {x[1]:.3f} kg and mount_k solved for 8500 / 10 200 rev/min")
    raise ValueError(f"unknown candidate {kind!r} (span120, end5)")


def write_candidate(path: str, kind: str = "span120", oring: float = 2.0) -> None:
    """Write a study layout (:func:`candidate`) as an engine data file (the shipped file's text with the changed
    values replaced, its comments kept): a STUDY file for ``rotorcosim sweep --set rotor.model_file=FILE`` (with
    ``--set damper0.k_spring=... --set damper5.k_spring=...`` for the O-ring reading), not a shipped engine."""
    import re

    d, f, what = candidate(kind, oring)
    text = fem.DEFAULT_FILE.read_text().splitlines()
    section, out = "", []
    # (table of the file, key): where the value is in the data (engine format 1: [spool.pt], [spool.gg], [casing])
    lists = {("spool.pt", "z_mm"): ("spool", "pt", "z_mm"), ("spool.pt", "d_out_mm"): ("spool", "pt", "d_out_mm"),
             ("spool.pt", "d_in_mm"): ("spool", "pt", "d_in_mm"), ("spool.gg", "z_mm"): ("spool", "gg", "z_mm"),
             ("casing", "ring_z_mm"): ("casing", "ring_z_mm")}

    def at(data, where):
        for k in where:
            data = data[k]
        return data
    for line in text:
        m = re.match(r"^\[([\w.]+)\]", line)
        if m:
            section = m.group(1)
        key = line.split("=")[0].strip()
        if (section, key) in lists:
            line = f"{key} = [{', '.join(_fmt(float(v)) for v in at(d, lists[section, key]))}]"
        elif section == "calibration" and key in ("pt_stage_mass_kg", "mount_k"):
            line = f"{key} = {d['calibration'][key]:.6g}"
        elif section == "casing.hubs" and key in d["casing"]["hubs"]:
            h = d["casing"]["hubs"][key]
            line = f"{key} = {{ z_mm = {_fmt(float(h['z_mm']))}, mass = {_fmt(float(h['mass']))} }}"
        out.append(line)
        if section == "spool.pt" and line.lstrip().startswith('{ node = 1, name = "PT stage 1"'):
            for dk in d["spool"]["pt"]["disks"][2:]:
                out.append(f'  {{ node = {dk["node"]}, name = "{dk["name"]}", mass = {dk["mass"]:.6g}, '
                           f'Ip = {dk["Ip"]:.6g}, Id = {dk["Id"]:.6g} }},')
    header = (f"# STUDY FILE written by bench/bench_support_above_running.py --write-candidate {kind}: {what},\n"
              f"# O-rings {oring:g} x 5254 N/mm; forward critical speeds {[round(x) for x in f]} rev/min.\n")
    Path(path).write_text(header + "\n".join(out) + "\n")
    back, _ = fem.load_data(path)
    for where in lists.values():
        assert np.allclose(at(back, where), at(d, where)), where
    assert len(back["spool"]["pt"]["disks"]) == len(d["spool"]["pt"]["disks"])
    # the file written is the layout computed (mount_k and the coupling are written to 6 digits)
    again = _forward(back, supports(oring), n=len(f))
    assert np.allclose(again, f, rtol=1e-5), (again, f)
    print(f"wrote {path}: forward critical speeds {[round(x) for x in f]} rev/min")


def main() -> None:
    if len(sys.argv) > 3 and sys.argv[1] == "--write-candidate":
        write_candidate(sys.argv[3], sys.argv[2], float(sys.argv[4]) if len(sys.argv) > 4 else 2.0)
        return
    data, _ = fem.load_data(None)
    part1(data)
    part2(data)
    part3(data)


if __name__ == "__main__":
    main()
