"""``rotorcosim bearing-static``: the static (or quasi-static at a speed) equilibrium of a ball bearing under a
radial and axial load: load distribution over the balls, contact angles and stresses (eqs. 1-10 at rest).

The bearing is any bearing of an engine (``--engine FILE --bearing ID``: its ``[bearing.ID]``, the values a run
of that engine gives it; ``--scenario SCENARIO --bearing ID``: the scenario's component ``bearing<ID>``), or
the paper's Table 3 bearing #0 or #5 by number alone."""
from __future__ import annotations

import json
import math
import sys

import numpy as np

from ..part_options import add_part_arguments, part_id
from ..validity import once, warning_line
from ..records import NO_RECORD
from .component import CHECKS, ELASTIC_LIMIT_PA, GEOMETRY
from .geometry import BEARINGS, build_geometry
from .static import static_equilibrium, stiffness

RPM = math.pi / 30.0
ELASTIC_LIMIT_MPA = ELASTIC_LIMIT_PA * 1e-6


def add_arguments(parser):
    add_part_arguments(parser, "bearing", "bearing", "bearing",
                       "the engine file whose [bearing.ID] (and [damper.ID]: the journal) give the bearing")
    parser.add_argument("--radial-load", type=float, required=True, metavar="N",
                        help="radial load on the inner race, N (along x)")
    parser.add_argument("--axial-load", type=float, default=None, metavar="N",
                        help="axial load on the inner race, N (default: the Table 3 preload)")
    parser.add_argument("--speed-rpm", type=float, default=0.0, metavar="R",
                        help="inner race speed for the balls' centrifugal force, rev/min (default 0: static)")
    parser.add_argument("--json", action="store_true", help="print a JSON object")


def geometry_of(bearing, parameters: dict | None = None):
    """The geometry of bearing ``bearing``: from its component ``parameters`` (an engine's, a scenario's), or the
    paper's Table 3 record of that number."""
    if parameters is None:
        if part_id(str(bearing)) not in BEARINGS:
            raise ValueError(f"--bearing {bearing}: the paper's Table 3 has bearings {sorted(BEARINGS)}; for another "
                             "bearing give its engine (--engine FILE) or a scenario (--scenario)")
        return build_geometry(part_id(str(bearing)))
    table = {key: (int(parameters[name]) if name == "balls" else parameters[name] / scale)
             for name, key, scale in GEOMETRY if name in parameters}
    record = parameters.get("bearing", NO_RECORD)
    return build_geometry(None if record == NO_RECORD else record, f_i=parameters.get("groove_curvature_inner"),
                          f_o=parameters.get("groove_curvature_outer"), preload=parameters.get("preload"), table=table)

def evaluate(bearing, radial_load: float, axial_load: float | None = None, speed_rpm: float = 0.0,
             parameters: dict | None = None) -> dict:
    """The equilibrium under (radial_load, 0, axial_load) on the inner race, outer race fixed; SI inside, the
    result in the units of its keys. ``parameters``: the bearing component's (geometry_of)."""
    g = geometry_of(bearing, parameters)
    bearing = part_id(str(bearing))
    Fa = g.preload if axial_load is None else axial_load
    for name, v in (("radial load", radial_load), ("axial load", Fa), ("speed", speed_rpm)):
        if not math.isfinite(v) or v < 0.0:
            raise ValueError(f"{name} must be a finite number >= 0, got {v!r}")
    if Fa == 0.0 and radial_load == 0.0 and speed_rpm == 0.0:
        raise ValueError("no load at all: the balls' positions are undetermined (give a radial or axial load)")
    Fc = g.centrifugal_force(speed_rpm * RPM)
    try:
        X, st = static_equilibrium(g, np.array([radial_load, 0.0, Fa]), Fc=Fc)
    except (RuntimeError, FloatingPointError, np.linalg.LinAlgError) as exc:
        spin = f" at {speed_rpm:g} rev/min (ball centrifugal force {Fc:.3g} N)" if speed_rpm else ""
        raise ValueError(f"bearing #{bearing}: no static equilibrium found under {radial_load:g} N radial, {Fa:g} N "
                         f"axial{spin} ({exc}); loads this large are far beyond the elastic (Hertz) range of the "
                         "bearing" + (", or the speed is given in another unit than rev/min" if speed_rpm else "")) \
            from None
    k_r = -stiffness(g, X, Fc=Fc, st=st)[0, 0]
    s_i = np.array([g.inner.max_stress(q) for q in st.Q_i])
    s_e = np.array([g.outer.max_stress(q) for q in st.Q_e])
    return {
        "bearing": bearing,
        "radial_load_N": radial_load,
        "axial_load_N": Fa,
        "speed_rpm": speed_rpm,
        "ball_diameter_m": g.D,
        "pitch_diameter_m": g.d_m,
        "groove_curvature_inner": g.f_i,
        "groove_curvature_outer": g.f_o,
        "inner_race_displacement_m": [float(v) for v in X],
        "max_contact_load_N": float(max(st.Q_i.max(), st.Q_e.max())),
        "max_contact_stress_MPa": float(max(s_i.max(), s_e.max()) * 1e-6),
        "radial_stiffness_N_per_m": float(k_r),
        # Hertz contact theory is elastic: beyond ELASTIC_LIMIT_MPA the races deform permanently
        "elastic_limit_MPa": ELASTIC_LIMIT_MPA,
        "within_elastic_range": bool(max(s_i.max(), s_e.max()) <= ELASTIC_LIMIT_PA),
        # the bearing component's envelope (BallBearing.validity) at this equilibrium
        "validity": once(CHECKS, {"sigma_max_step": [s_i.max(), s_e.max()]}, f"bearing{bearing}"),
        "balls": [
            {"phi_deg": float(math.degrees(st.phi[j])), "Q_inner_N": float(st.Q_i[j]),
             "Q_outer_N": float(st.Q_e[j]), "alpha_inner_deg": float(math.degrees(st.alpha_i[j])),
             "alpha_outer_deg": float(math.degrees(st.alpha_e[j])), "stress_inner_MPa": float(s_i[j] * 1e-6),
             "stress_outer_MPa": float(s_e[j] * 1e-6)}
            for j in range(g.Z)
        ],
    }


def run(args) -> int:
    out = evaluate(args.bearing, args.radial_load, args.axial_load, args.speed_rpm, getattr(args, "parameters", None))
    for entry in out["validity"]:
        print(warning_line("rotorcosim bearing-static", entry), file=sys.stderr)
    if args.json:
        print(json.dumps(out))
        return 0
    x, y, z = out["inner_race_displacement_m"]
    print(f"bearing #{out['bearing']}: radial {out['radial_load_N']:.1f} N, axial {out['axial_load_N']:.1f} N, "
          f"{out['speed_rpm']:.0f} rev/min; D = {out['ball_diameter_m'] * 1e3:.2f} mm, "
          f"d_m = {out['pitch_diameter_m'] * 1e3:.2f} mm, f_i = {out['groove_curvature_inner']}, "
          f"f_o = {out['groove_curvature_outer']}")
    print(f"  inner race displacement x = {x * 1e6:.3f} um, y = {y * 1e6:.3f} um, z = {z * 1e6:.3f} um")
    print(f"  max contact load {out['max_contact_load_N']:.2f} N, max contact stress "
          f"{out['max_contact_stress_MPa']:.1f} MPa, radial stiffness {out['radial_stiffness_N_per_m']:.4e} N/m")
    print(f"  {'phi deg':>8} {'Q_i N':>9} {'Q_e N':>9} {'a_i deg':>8} {'a_e deg':>8} {'s_i MPa':>8} {'s_e MPa':>8}")
    for b in out["balls"]:
        print(f"  {b['phi_deg']:8.2f} {b['Q_inner_N']:9.2f} {b['Q_outer_N']:9.2f} {b['alpha_inner_deg']:8.3f} "
              f"{b['alpha_outer_deg']:8.3f} {b['stress_inner_MPa']:8.1f} {b['stress_outer_MPa']:8.1f}")
    return 0
