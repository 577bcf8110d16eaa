"""``rotorcosim check-engine FILE``: an engine file's problems by name, or its model: nodes, masses, spool
polar inertias, critical speeds with their separation margins, warnings and a Campbell diagram.

Every problem of the file is listed (one line each, exit status 2), not only the first, a value of the wrong
TOML shape first (components/rotor/engine_shape.py). A valid file gets its report; every synchronous critical
speed up to 1.5 x each spool's highest operating speed, excited by that spool's unbalance, with the whirl of its
mode, its amplification factor (1 / (2 zeta), zeta the damping ratio of its mode in the damped engine at that
speed) and its separation margin from each operating speed against the margin API 684 asks for that factor
(components/rotor/engine_check.required_margin; 15 % for an undamped mode), on the linearised supports (the
co-simulated bearings it attaches, linearised from the components of ``--scenario``, default the shipped
blade-loss scenario); one warning line each (exit status 0) for a critical speed nearer an operating speed than
that margin, a bearing
bore that fits no shaft section at its node, dimensions implausible for mm, a spool turning a bearing beyond
its model's speed range and, for an engine with cross-coupled supports (the only ones that can feed a whirl), a
whirl mode of negative damping at the operating speed; and a Campbell diagram PNG. Example::

    rotorcosim check-engine my_engine/engine.toml --scenario my_engine/blade_loss.toml
"""
from __future__ import annotations

import json
import math

from rotorcosim.cases.blade_loss import critical_speeds as cs
from rotorcosim.cases.blade_loss import linear_engine
from rotorcosim.components.airframe.installed import installed_model
from rotorcosim.components.airframe.mounting import installed
from rotorcosim.components.bearing.geometry import DN_LIMIT, speed_limit
from rotorcosim.components.rotor import attach, critical, engine_check
from rotorcosim.components.rotor import model as fem
from rotorcosim.master.scenario.build import create_component


def check_engine(path: str, scenario: str | None = None, campbell: str | None = None,
                 max_rpm: float | None = None, count: int = 6,
                 windmill_rpm: tuple[float, float] | None = None) -> dict:
    """``{"problems": [...]}`` for a file with problems; else the report (:func:`engine_check.report`) with
    ``critical_speeds`` (:func:`critical_speeds.critical_speeds`), ``separation`` (every synchronous critical
    speed up to :data:`SPAN` x each spool's highest operating speed, excited by that spool's unbalance, with its
    whirl and its separation margin from each operating speed: :func:`engine_check.separation`), ``warnings``
    (one line each: :func:`warnings`) and ``campbell`` (the PNG written, when ``campbell`` names one).
    ``max_rpm`` None: twice the first spool's speed (the list of ``critical_speeds`` and the diagram)."""
    data, _ = fem.load_data(path)
    found = engine_check.problems(data) or (mount_problems(path) if "mount" in data or "airframe" in data else [])
    if found:
        return {"engine_file": str(path), "problems": found}
    full = installed_model(path)
    out = {"engine_file": str(path), "problems": [], **engine_check.report(full)}
    sc = None
    if scenario:
        from rotorcosim.master.api import load_scenario

        sc = load_scenario(scenario)
    if max_rpm is None:
        max_rpm = 2.0 * abs(next(iter(out["spools"].values()))["speed_rpm"])
    crit = cs.critical_speeds(str(path), count=count, max_rpm=max_rpm, scenario=sc)
    out["critical_speeds"] = crit
    sup = cs.linearised_supports(full, None, sc)
    ops = engine_check.operating_speeds(data)
    first = next(iter(ops.values()))[0]
    out["operating_speeds_rpm"] = ops
    out["separation"], warn = [], []
    for s, speeds in ops.items():
        ratio = speeds[0] / first
        every = critical.damping_ratios(full, sup, critical.every_synchronous_critical_speed(
            full, sup, SPAN * max(speeds), excited=ratio), excited=ratio)
        rows, w = engine_check.separation(every, s, data["spool"][s].get("name", s), speeds)
        out["separation"] += rows
        warn += w
    out["stability"] = None
    feeding = engine_check.destabilising(data)
    if feeding:
        rpm = abs(first)
        modes = critical.whirl_modes(full, sup, rpm, SPAN * max(max(v) for v in ops.values()) / 60.0)
        out["stability"] = {"first_spool_rpm": rpm, "cross_coupled_supports": feeding, "modes": modes}
        warn += engine_check.stability(modes, rpm)
    out["warnings"] = warn + warnings(data, sc)
    if campbell:
        cs.check_figure_path(campbell)
        cs.draw_campbell(campbell, str(path), max_rpm, crit, scenario=sc, windmill_rpm=windmill_rpm)
        out["campbell"] = str(campbell)
    return out


def mount_problems(path: str) -> list[str]:
    """The problem of an engine's mounts and airframe (components/rotor/mounts.py, components/airframe): its
    tables, its reduced model's file, a spring on a node the engine lacks; one line, or none."""
    where = f"rotor model file {path}: "
    try:
        installed(path)
        fem.load(path)
    except (ValueError, OSError) as exc:
        return [str(exc).removeprefix(where)]
    return []


#: the separation list spans the synchronous critical speeds up to this times each spool's highest operating speed
SPAN = 1.5


def warnings(data: dict, sc=None) -> list[str]:
    """One line per implausible dimension of the engine (:func:`engine_check.implausible`), and per attached
    bearing whose bore fits no shaft section at its node (:func:`engine_check.bore_fit`) or whose spool turns
    beyond its model's speed range; the bearings as the scenario ``sc`` (None: the shipped blade-loss
    scenario) makes them."""
    out = engine_check.implausible(data)
    ids = attach.layout(data.get("attach", {})).bearings
    if not ids:
        return out
    sc = linear_engine.scenario_or_default(sc)
    for b in ids:
        spec = sc.components.get(f"bearing{b}")
        if spec is None:
            continue
        comp = create_component(spec)
        if not hasattr(comp, "speed_range"):
            continue            # a bearing of another model (a plug-in, an FMU): its range is its own
        bore, w_max = comp.speed_range()
        own = data.get("bearing", {}).get(b, {}) if isinstance(data.get("bearing"), dict) else {}
        if isinstance(own, dict) and isinstance(own.get("bore_mm"), (int, float)) and own["bore_mm"] > 0:
            bore = float(own["bore_mm"]) * 1e-3         # the engine's own record of the bearing, when it has one
            w_max = speed_limit(bore)
        key = f"bearing{b}"
        line = engine_check.bore_fit(data, key, bore * 1e3)
        if line:
            out.append(line)
        spool = data["attach"][key]["node"][0]
        rpm = abs(float(data["spool"][spool]["speed_rpm"]))
        if rpm > w_max * 30.0 / math.pi:
            out.append(f"attach.{key}: the bearing turns with spool {spool} at {rpm:.0f} rev/min, above the ball "
                       f"bearing model's speed limit {w_max * 30.0 / math.pi:.0f} rev/min (bore {bore * 1e3:g} mm, "
                       f"bore x speed <= {DN_LIMIT:.3g} mm rev/min)")
    return out


def add_arguments(parser):
    """The options of ``rotorcosim check-engine`` on ``parser``."""
    parser.add_argument("file", metavar="FILE", help="engine file (TOML, docs/reference/engine-format.md)")
    parser.add_argument("--scenario", metavar="SCENARIO", default=None,
                        help="the scenario whose bearing and damper components linearise the attached bearings "
                             "(default: the shipped blade-loss scenario)")
    parser.add_argument("--campbell", metavar="FILE.png", default=None,
                        help="draw the Campbell diagram into this PNG file (default: none drawn)")
    parser.add_argument("--max-rpm", type=float, default=None, metavar="RPM",
                        help="highest speed of the critical speeds and the diagram (default: twice the first "
                             "spool's speed)")
    parser.add_argument("--json", action="store_true", help="print a JSON object")
    cs.add_windmill_argument(parser)


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status."""
    # a figure only where --campbell asks: a check writes nothing into the working folder unasked
    out = check_engine(args.file, args.scenario, args.campbell, args.max_rpm, windmill_rpm=args.windmill_rpm)
    if args.json:
        print(json.dumps(out, default=str))
        return 2 if out["problems"] else 0
    if out["problems"]:
        print(f"{args.file}: {len(out['problems'])} problem(s):")
        for line in out["problems"]:
            print(f"  {line}")
        return 2
    n = len(out["warnings"])
    print(f"{args.file}: no problem found; {out['dof']} DOF" + (f"; {n} warning(s) below" if n else ""))
    for s, v in out["spools"].items():
        print(f"  spool {s} ({v['name']}): {v['nodes']} nodes over {v['length_mm']:.0f} mm, {v['mass_kg']:.2f} kg "
              f"(shaft {v['shaft_mass_kg']:.2f}, disks {v['disk_mass_kg']:.2f}), polar inertia "
              f"{v['polar_inertia_kgm2']:.4g} kg m^2, {v['speed_rpm']:.0f} rev/min")
    print(f"  hubs: {', '.join(out['hubs']) or 'none'} ({out['hub_mass_kg']:.2f} kg)"
          + (f"; casing shell {out['casing_mass_kg']:.2f} kg" if out["casing_mass_kg"] else ""))
    at = {k: v for k, v in out["attach"].items() if k != "oil_temperature_C"}
    print("  attached: " + (", ".join(f"{k} at {v['node']}" + (f" (housing {v['housing']})" if "housing" in v
                                                               else "") for k, v in at.items()) or "nothing"))
    c = out["critical_speeds"]
    for s, speeds in out["operating_speeds_rpm"].items():
        rows = [r for r in out["separation"] if r["spool"] == s]
        print(f"  synchronous critical speeds excited by spool {s} up to {SPAN:g} x its operating speed "
              f"{', '.join(f'{v:.0f}' for v in speeds)} rev/min (separation margin, amplification factor, the "
              "margin API 684 asks):")
        print("    " + (", ".join(f"{r['rpm']:.0f} {r['whirl']} ("
                                  + "/".join(f"{m['margin_percent']:+.1f} %" for m in r["margins"])
                                  + (f", AF {r['amplification_factor']:.1f}" if r["amplification_factor"] is not None
                                     else ", undamped")
                                  + ", needs " + "/".join(f"{m['required_percent']:.0f} %" for m in r["margins"])
                                  + ")" for r in rows) or "none"))
    for st in c.get("fuse_states", []):
        print(f"  forward synchronous critical speeds, {st['label']} (fuse stiffness "
              + ", ".join(f"#{b} {k:.3g} N/m" for b, k in st["fuse_stiffness_N_per_m"].items()) + "): "
              + (st["note"] if "note" in st else ", ".join(f"{v:.0f}" for v in st["forward_synchronous_rpm"])
                 + " rev/min"))
    st = out["stability"]
    if st is not None:
        least = min(st["modes"], key=lambda m: m["damping_ratio"], default=None)
        print(f"  stability at {st['first_spool_rpm']:.0f} rev/min (cross-coupled supports: "
              f"{', '.join(st['cross_coupled_supports'])}): {len(st['modes'])} whirl modes up to {SPAN:g} x the "
              "operating speeds" + (f"; least damped {least['frequency_Hz']:.4g} Hz {least['whirl']}, damping ratio "
                                    f"{least['damping_ratio']:.3g}" if least else ""))
    print(f"  supports: {c['support_model']['description']}")
    for line in out["warnings"]:
        print(f"  warning: {line}")
    if out.get("campbell"):
        print(f"Campbell diagram: {out['campbell']}")
    return 0
