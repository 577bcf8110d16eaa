"""``rotorcosim parameters [COMP | IMPL | SCENARIO]``: every parameter with unit, default, current value and
source (:meth:`rotorcosim.master.scenario.build.Scenario.parameters`); the listing of one component or
implementation adds each parameter's description (where its default comes from).

WHAT is a component of the scenario (``osc``), an implementation (``bearing.hertz``: its declared
parameters and defaults) or a scenario (a shipped name or a TOML file: all its components); none lists the
default scenario's. Any listed parameter is set with ``--set COMP.NAME=VALUE`` or in the scenario file.
"""
from __future__ import annotations

import json
from pathlib import Path

from rotorcosim.components import registry
from rotorcosim.master.api import load_scenario
from rotorcosim.master.scenario.parameters import implementation_parameters


def parameters(what: str | None = None, scenario: str | None = None) -> list[dict]:
    """The parameter rows of ``what`` (see the module docstring) in ``scenario`` (None: the default)."""
    if what and scenario is None and (what.endswith((".toml", ".ssp")) or Path(what).is_file()):
        return load_scenario(what).parameters()
    sc = load_scenario(scenario) if scenario else None
    if what:
        if sc is None:
            sc = load_scenario(None)
        if what in sc.components:
            return sc.parameters(what)
        if what in registry.available() or registry.is_plugin_path(what):
            return implementation_parameters(what)
        try:
            return load_scenario(what).parameters()
        except (LookupError, FileNotFoundError, ValueError):
            raise ValueError(f"parameters {what}: not a component of scenario {sc.name!r} ("
                             f"{', '.join(sc.components)}), an implementation ({', '.join(registry.available())}) "
                             "or a scenario") from None
    return (sc or load_scenario(None)).parameters()


def add_arguments(parser):
    """The options of ``rotorcosim parameters`` on ``parser``."""
    parser.add_argument("what", nargs="?", default=None, metavar="COMP|IMPL|SCENARIO",
                        help="a component of the scenario, an implementation, or a scenario (default: every "
                             "component of the default scenario)")
    parser.add_argument("--scenario", default=None, metavar="SCENARIO",
                        help="the scenario whose components are listed (a shipped name, a TOML file or an SSP "
                             "archive; default: the default scenario)")
    parser.add_argument("--json", action="store_true", help="print a JSON list of rows")


def _fmt(v) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, list):
        return "[" + ", ".join(_fmt(x) for x in v) + "]"
    return str(v)


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status."""
    rows = parameters(args.what, args.scenario)
    if args.json:
        print(json.dumps(rows))
        return 0
    comp = None
    # one component (or implementation): each parameter's description too, which names its default's source
    described = len({r["component"] for r in rows}) == 1
    for r in rows:
        if r["component"] != comp:
            comp = r["component"]
            print(f"{comp}:")
        print(f"  {r['name']:<28} {_fmt(r['value']):>14} {r['unit'] or '':<8} default {_fmt(r['default']):<12} "
              f"{r['source']}")
        if described and r.get("description"):
            print(f"      {r['description']}")
    return 0
