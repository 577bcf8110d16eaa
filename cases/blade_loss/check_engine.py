"""``rotorcosim check-engine FILE``: an engine file's problems by name, or its model: nodes, masses, spool
polar inertias, critical speeds and a Campbell diagram.

Every problem of the file is listed (one line each, exit status 2), not only the first; a valid file gets its
report, its synchronous critical speeds on the linearised supports (the co-simulated bearings it attaches,
linearised from the components of ``--scenario``, default the shipped blade-loss scenario) and a Campbell
diagram PNG. Example::

    rotorcosim check-engine my_engine/engine.toml --scenario my_engine/blade_loss.toml
"""
from __future__ import annotations

import json
from pathlib import Path

from rotorcosim.cases.blade_loss import critical_speeds as cs
from rotorcosim.components.rotor import engine_check
from rotorcosim.components.rotor import model as fem


def check_engine(path: str, scenario: str | None = None, campbell: str | None = None,
                 max_rpm: float | None = None, count: int = 6) -> dict:
    """``{"problems": [...]}`` for a file with problems; else the report (:func:`engine_check.report`) with
    ``critical_speeds`` (:func:`critical_speeds.critical_speeds`) and ``campbell`` (the PNG written, when
    ``campbell`` names one). ``max_rpm`` None: twice the first spool's speed."""
    data, _ = fem.load_data(path)
    found = engine_check.problems(data)
    if found:
        return {"engine_file": str(path), "problems": found}
    full = fem.build(data, source=path)
    out = {"engine_file": str(path), "problems": [], **engine_check.report(full)}
    sc = None
    if scenario:
        from rotorcosim.master.api import load_scenario

        sc = load_scenario(scenario)
    if max_rpm is None:
        max_rpm = 2.0 * abs(next(iter(out["spools"].values()))["speed_rpm"])
    crit = cs.critical_speeds(str(path), count=count, max_rpm=max_rpm, scenario=sc)
    out["critical_speeds"] = crit
    if campbell:
        cs._check_figure_path(campbell)
        cs.draw_campbell(campbell, str(path), max_rpm, crit, scenario=sc)
        out["campbell"] = str(campbell)
    return out


def add_arguments(parser):
    """The options of ``rotorcosim check-engine`` on ``parser``."""
    parser.add_argument("file", metavar="FILE", help="engine file (TOML, docs/reference/engine-format.md)")
    parser.add_argument("--scenario", metavar="SCENARIO", default=None,
                        help="the scenario whose bearing and damper components linearise the attached bearings "
                             "(default: the shipped blade-loss scenario)")
    parser.add_argument("--campbell", metavar="FILE.png", default=None,
                        help="where to draw the Campbell diagram (default: FILE's name + _campbell.png in the "
                             "current folder)")
    parser.add_argument("--max-rpm", type=float, default=None, metavar="RPM",
                        help="highest speed of the critical speeds and the diagram (default: twice the first "
                             "spool's speed)")
    parser.add_argument("--json", action="store_true", help="print a JSON object")


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status."""
    campbell = args.campbell or f"{Path(args.file).stem}_campbell.png"
    out = check_engine(args.file, args.scenario, campbell, args.max_rpm)
    if args.json:
        print(json.dumps(out, default=str))
        return 2 if out["problems"] else 0
    if out["problems"]:
        print(f"{args.file}: {len(out['problems'])} problem(s):")
        for line in out["problems"]:
            print(f"  {line}")
        return 2
    print(f"{args.file}: no problem found; {out['dof']} DOF")
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
    print("  forward synchronous critical speeds [rev/min]: "
          + ", ".join(f"{v:.0f}" for v in c["forward_synchronous_rpm"]))
    print("  backward synchronous critical speeds [rev/min]: "
          + ", ".join(f"{v:.0f}" for v in c["backward_synchronous_rpm"]))
    print(f"  supports: {c['support_model']['description']}")
    print(f"Campbell diagram: {out['campbell']}")
    return 0
