"""``rotorcosim thermal-steady``: the steady state of a bearing's thermal network under constant powers.

The network is that of any bearing of an engine (``--engine FILE --bearing ID``: its bearing's, damper's, rub
ring's and thermal tables, the values a run of that engine gives it; ``--scenario SCENARIO --bearing ID``: the
scenario's component ``thermal<ID>``), or of the paper's Table 3 bearing #0 or #5 by number alone."""
from __future__ import annotations

import json
import math
import sys

from ..oil_fit import check_oil_temperature
from ..part_options import add_part_arguments, part_id
from ..validity import once, warning_line
from .component import CHECKS, ThermalNetwork
from .geometry import BEARINGS, LE, LI, NODES, SFD

KELVIN = 273.15


def add_arguments(parser):
    add_part_arguments(parser, "thermal", "bearing", "network",
                       "the engine file whose parts at bearing ID give the network")
    parser.add_argument("--drag-power", type=float, required=True, metavar="W", help="bearing drag-torque power, W")
    parser.add_argument("--sfd-power", type=float, required=True, metavar="W", help="damper film viscous power, W")
    parser.add_argument("--rub-power", type=float, default=0.0, metavar="W", help="rub friction power, W (default 0)")
    parser.add_argument("--ambient", type=float, default=30.0, metavar="C",
                        help="ambient, oil supply and initial (zero-growth) temperature, degrees C (default 30)")
    parser.add_argument("--json", action="store_true", help="print a JSON object")



def steady(bearing, drag_power: float, sfd_power: float, rub_power: float = 0.0,
           ambient_C: float = 30.0, parameters: dict | None = None) -> dict:
    """Steady node temperatures (C) and growths (m) of a bearing's network under constant powers (W); ``parameters``:
    the network component's (an engine's, a scenario's), else the paper's Table 3 bearing of that number."""
    bearing = part_id(str(bearing))
    if parameters is None and bearing not in BEARINGS:
        raise ValueError(f"--bearing {bearing}: the paper's Table 3 has bearings {sorted(BEARINGS)}; for another "
                         "bearing give its engine (--engine FILE) or a scenario (--scenario)")
    values = {"drag power": drag_power, "sfd power": sfd_power, "rub power": rub_power, "ambient": ambient_C}
    for name, v in values.items():
        if not math.isfinite(v):
            raise ValueError(f"{name} must be a finite number, got {v}")
    for name in ("drag power", "sfd power", "rub power"):
        if values[name] < 0.0:
            raise ValueError(f"{name} must be >= 0 W, got {values[name]}")
    Ta = ambient_C + KELVIN
    if Ta <= 0.0:
        raise ValueError(f"ambient must be above absolute zero, got {ambient_C} C")
    try:  # the ambient is also the oil's supply temperature: an oil temperature of the model (components/oil_fit.py)
        check_oil_temperature(Ta)
    except ValueError as exc:
        raise ValueError(f"--ambient {ambient_C:g} C is also the oil supply temperature: {exc} (temperatures are "
                         "in degrees C)") from None
    own = parameters if parameters is not None else {"bearing": bearing}
    net = ThermalNetwork(f"thermal{bearing}", {**own, "T_ambient": Ta, "T_initial": Ta, "T_supply": Ta})
    net.setup(0.0)
    T = net.steady_state(drag_power, sfd_power, rub_power)
    for name, Tk in (("bearing oil", 0.5 * (T[LI] + T[LE])), ("squeeze-film oil", T[SFD])):
        # the network is linear: any power has a steady state, but past the oil's range it no longer describes a
        # lubricated bearing (a run stops there too: the bearing and damper refuse the oil temperature)
        try:
            check_oil_temperature(Tk)
        except ValueError as exc:
            raise ValueError(f"powers drag {drag_power:g} W, film {sfd_power:g} W, rub {rub_power:g} W put the "
                             f"{name} at {Tk - KELVIN:.4g} C in steady state: {exc}; the model does not hold "
                             "there (powers are in W)") from None
    eps = net.growths_at(T)
    return {
        "bearing": bearing,
        "powers_W": {"drag": drag_power, "sfd": sfd_power, "rub": rub_power},
        "temperatures_C": {name: float(T[i] - KELVIN) for i, name in enumerate(NODES)},
        "bearing_oil_C": float(0.5 * (T[2] + T[4]) - KELVIN),
        "growths_m": {"inner": float(eps[0]), "outer": float(eps[1]), "ball": float(eps[2])},
        # the thermal network's envelope (validity) in this steady state
        "validity": once(CHECKS, {"T_oil": [0.5 * (T[LI] + T[LE])], "T_sfd_oil": [T[SFD]]}, f"thermal{bearing}"),
    }


def run(args) -> int:
    out = steady(args.bearing, args.drag_power, args.sfd_power, args.rub_power, args.ambient,
                 getattr(args, "parameters", None))
    for entry in out["validity"]:
        print(warning_line("rotorcosim thermal-steady", entry), file=sys.stderr)
    if args.json:
        print(json.dumps(out))
        return 0
    pw = out["powers_W"]
    print(f"bearing #{out['bearing']} steady state: drag {pw['drag']:g} W, film {pw['sfd']:g} W, rub {pw['rub']:g} W")
    for name, value in out["temperatures_C"].items():
        print(f"  {name:<11s} {value:9.2f} C")
    g = out["growths_m"]
    print(f"  growths: inner race {g['inner'] * 1e6:.3f} um, outer race {g['outer'] * 1e6:.3f} um,"
          f" ball {g['ball'] * 1e6:.3f} um")
    return 0
