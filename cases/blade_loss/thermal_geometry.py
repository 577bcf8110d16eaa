"""Before a run: each thermal network has the geometry of the bearing, damper and rub ring whose heat it takes.

The thermal network (components/thermal) derives its Table 1 resistances and heat masses from a bearing's and a
damper's geometry, which it takes as its own parameters, as an FMU would. A scenario takes both from the same
records of its engine file ([bearing.ID], [damper.ID], [rubring.ID]: master/scenario/engine.py), so they agree by
construction, and a change by name moves both; a scenario file that writes a plain value into one of them, or a
component that is not bound to the engine, can still make them differ. No component reads another's; this
check, the case's, compares the values the components run with (:meth:`Scenario.parameters`), through the
connections that feed the network's power inputs (``bearingK.P_drag -> thermalK.P_drag``, ``damperK.P_film ->
thermalK.P_sfd``, ``rubringK.P_rub -> thermalK.P_rub``), and names every pair that differs. A component that
lacks one of the parameters (an FMU, a user's implementation) is not compared.
"""
from __future__ import annotations

import math

#: per power input of the thermal network: (its parameter, the producer's parameter)
SHARED = {
    "P_drag": (("bore", "bore"), ("outside_diameter", "outside_diameter"), ("width", "width"), ("balls", "balls"),
               ("ball_diameter", "ball_diameter"), ("contact_angle", "contact_angle")),
    "P_sfd": (("damper_radius", "radius"), ("damper_length", "length"), ("damper_clearance", "clearance")),
    "P_rub": (("rub_radius", "radius"),),
}


def _values(sc, name: str, cache: dict) -> dict:
    """The parameters component ``name`` runs with (after its set-up: :meth:`Scenario.parameters`); empty when it
    cannot be set up (the run's own set-up then names the problem)."""
    if name not in cache:
        try:
            cache[name] = {r["name"]: r["value"] for r in sc.parameters(name)}
        except (ValueError, RuntimeError, ArithmeticError):
            # the same set-up failures the run's own set-up turns into "could not be set up with its parameters"
            cache[name] = {}
    return cache[name]


def mismatches(sc, system) -> list[str]:
    """'thermal0.balls = 21 but bearing0.balls = 19' for every shared geometry value that differs (relative
    1e-9: the records are in mm, the parameters in m)."""
    out, cache = [], {}
    for con in system.connections:
        pairs = SHARED.get(con.dst_port)
        if pairs is None or con.dst_component not in sc.components or con.src_component not in sc.components:
            continue
        mine_p, theirs_p = _values(sc, con.dst_component, cache), _values(sc, con.src_component, cache)
        for mine, theirs in pairs:
            a, b = mine_p.get(mine), theirs_p.get(theirs)
            if isinstance(a, bool) or isinstance(b, bool) or not isinstance(a, (int, float)) \
                    or not isinstance(b, (int, float)):
                continue
            if not math.isclose(float(a), float(b), rel_tol=1e-9):
                out.append(f"{con.dst_component}.{mine} = {a:.6g} but {con.src_component}.{theirs} = {b:.6g}")
    return out


def check(sc, system) -> None:
    """A ValueError naming every mismatch, and how to resolve it."""
    bad = mismatches(sc, system)
    if bad:
        raise ValueError("the thermal network's geometry differs from the part whose heat it takes: "
                         + "; ".join(bad) + " (set the thermal network's parameter to the same value)")
