"""``rotorcosim damper-force``: the squeeze film damper force at one journal position and velocity.

The damper is any damper of an engine (``--engine FILE --damper ID``: its ``[damper.ID]``; ``--scenario SCENARIO
--damper ID``: the scenario's component ``damper<ID>``), or the paper's Table 3 damper #0 or #5 by number alone."""
from __future__ import annotations

import json
import math
import sys

from .component import DAMPERS, LAMINAR_FILM_RE, FastDamper, FEDamper
from ..part_options import add_part_arguments, part_id
from ..validity import once, warning_line
from .viscosity import oil_constants, sae30_viscosity


def add_arguments(parser):
    add_part_arguments(parser, "damper", "damper", "damper", "the engine file whose [damper.ID] gives the damper")
    parser.add_argument("--position", type=float, nargs=2, metavar=("X", "Y"), required=True,
                        help="journal position relative to the housing, m")
    parser.add_argument("--velocity", type=float, nargs=2, metavar=("VX", "VY"), required=True,
                        help="journal velocity relative to the housing, m/s")
    parser.add_argument("--temperature", type=float, required=True, metavar="C",
                        help="squeeze-film oil temperature, degrees C")
    parser.add_argument("--model", choices=("fe", "fast"), default="fast",
                        help="direct FE solve or the fast tabulated model (default)")
    parser.add_argument("--no-cavitation", action="store_true", help="full film (no Guembel clipping)")
    parser.add_argument("--json", action="store_true", help="print a JSON object")



def evaluate(damper, position, velocity, temperature_C: float, model: str = "fast",
             cavitation: bool = True, parameters: dict | None = None) -> dict:
    """The film force, spring force, power loss and viscosity (SI) for the CLI and scripts; ``parameters``: the
    damper component's (an engine's, a scenario's), else the paper's Table 3 damper of that number."""
    damper = part_id(str(damper))
    if parameters is None and damper not in DAMPERS:
        raise ValueError(f"--damper {damper}: the paper's Table 3 has dampers {sorted(DAMPERS)}; for another damper "
                         "give its engine (--engine FILE) or a scenario (--scenario)")
    values = [*position, *velocity, temperature_C]
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"position, velocity and temperature must be finite numbers, got {values}")
    cls = FEDamper if model == "fe" else FastDamper
    d = cls(f"damper{damper}", {**(parameters if parameters is not None else {"damper": damper}),
                                "cavitation": cavitation})
    d.setup(0.0)
    T = temperature_C + 273.15
    try:
        mu = sae30_viscosity(T)
    except ValueError as exc:
        raise ValueError(f"--temperature {temperature_C:g} C: {exc}") from None
    A, B, rho300, drho = oil_constants()
    speed = math.hypot(*velocity)
    re = (rho300 + drho * (T - 300.0)) * speed * d.p["clearance"] / mu
    if re > LAMINAR_FILM_RE:
        raise ValueError(f"--velocity {speed:g} m/s gives a film Reynolds number rho |V| c / mu = {re:.3g} at "
                         f"{temperature_C:g} C, above {LAMINAR_FILM_RE:g}: a turbulent film, outside the laminar "
                         f"Reynolds equation of the model (velocities are in m/s; at this temperature the limit is "
                         f"{LAMINAR_FILM_RE * speed / re:.3g} m/s)")
    d.set_inputs({"X_journal": position, "V_journal": velocity, "T_oil": [temperature_C + 273.15]})
    try:
        d.do_step(0.0, d.preferred_step)
    except RuntimeError as exc:   # the journal far beyond the wall (see wall.py): a position, not a run
        msg = str(exc).replace(" at t = 1e-05 s", "").replace(": the simulation diverged", "")
        raise ValueError(f"--position: {msg}; the clearance is {d.p['clearance'] * 1e3:g} mm and positions are "
                         f"in metres") from None
    y = d.get_outputs()
    return {
        "damper": damper,
        "model": model,
        "force_N": [float(v) for v in y["F_film"]],
        "spring_force_N": [float(v) for v in y["F_spring"]],
        "contact_force_N": [float(v) for v in y["F_contact"]],
        "power_W": float(y["P_film"][0]),
        "viscosity_Pa_s": float(y["mu"][0]),
        "eccentricity_ratio": math.hypot(*position) / d.p["clearance"],
        # the damper component's envelope (validity) at this position and velocity
        "validity": once(d.validity(), {**d.u, **y}, f"damper{damper}"),
    }


def run(args) -> int:
    out = evaluate(args.damper, args.position, args.velocity, args.temperature, args.model, not args.no_cavitation,
                   getattr(args, "parameters", None))
    for entry in out["validity"]:
        print(warning_line("rotorcosim damper-force", entry), file=sys.stderr)
    if args.json:
        print(json.dumps(out))
    else:
        print(f"damper #{out['damper']} ({out['model']} model), eccentricity ratio {out['eccentricity_ratio']:.4f},"
              f" viscosity {out['viscosity_Pa_s'] * 1e3:.3f} cP")
        print(f"  film force   Fx = {out['force_N'][0]:12.4f} N   Fy = {out['force_N'][1]:12.4f} N")
        print(f"  spring force Fx = {out['spring_force_N'][0]:12.4f} N   Fy = {out['spring_force_N'][1]:12.4f} N")
        if any(out["contact_force_N"]):
            print(f"  wall contact Fx = {out['contact_force_N'][0]:12.4f} N   Fy = {out['contact_force_N'][1]:12.4f} N")
        print(f"  film power loss {out['power_W']:.4f} W")
    return 0
