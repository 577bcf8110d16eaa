"""The co-simulated engine linearised: the one linear model behind ``rotorcosim critical-speeds`` and the
calibration of the rotor data (calibrated on the system that is simulated).

Each support of a co-simulated bearing (every ``bearing<ID>`` of the engine file's [attach]; #0 and #5 of the
paper's engine) is taken from the components the blade-loss scenario simulates, with the
scenario's parameters, at the preloaded rest state and the running speed:

* ball contacts: the radial stiffness d(sum T^T Q)/dX of the bearing's own quasi-static model (eqs. 1-9 at rest,
  balls re-equilibrated, centrifugal force at the running speed) about the preloaded rest state;
* outer race + SFD journal: the bearing's body of eq. (5) with its mass ``m_journal``;
* O-ring: the damper's centering spring ``k_spring``;
* film: the damper's own film model linearised about the centred journal, ``c_film = -F_t / v_t`` for a
  vanishing circular orbit (the full, uncavitated film: the 0.2 MPa supply keeps a small orbit's film whole), at
  a STATED oil temperature (the rotor data's [attach] ``oil_temperature_C``, or the caller's).

A fused bearing (the engine file's ``[fuse.ID]``) has its own housing on the fuse's stiffness and damping to the
hub: the stage asked for (``fuse_stage``: 0 intact, 1 after the first break, 2 after the second, for every fuse, or
per fuse id; a fuse with fewer stages stays at its last), from the scenario's ``fuse<ID>`` component or the engine
file's ``[fuse.ID]``.

The undamped critical speeds do not depend on the film; the forced response does (``response``).
"""
from __future__ import annotations

import math

import numpy as np

from rotorcosim import scenarios
from rotorcosim.components.rotor import attach, calibration, critical
from rotorcosim.components.rotor import model as fem

from rotorcosim.components import registry
from rotorcosim.master.scenario.build import create_component, load_scenario
from rotorcosim.master.scenario.engine import part_parameters

KELVIN = 273.15


def scenario_or_default(sc):
    """``sc``, or the shipped blade-loss scenario when it is None."""
    return load_scenario(scenarios.path("blade_loss")) if sc is None else sc


def fuse_stiffness(params: dict, stage: int) -> float:
    """A fuse's stiffness [N/m] at ``stage`` (0 intact, 1 after the first break, 2 after the second; a one-stage
    fuse stays at its soft path), from its component's parameters."""
    ks = [params["k_intact"], params.get("k_broken", 0.0)]
    if int(params.get("stages", 1)) == 2:
        ks.append(params.get("k_broken_2", 0.0))
    return float(ks[min(stage, len(ks) - 1)])


def fuse_stages(data: dict) -> int:
    """The most break stages among the engine file's fuses (0: no fuse)."""
    fuses = data.get("fuse", {}) if isinstance(data.get("fuse"), dict) else {}
    return max((int(f.get("stages", 1)) for f in fuses.values() if isinstance(f, dict)), default=0)


def fuse_combinations(data: dict) -> list[dict[str, int]]:
    """Every combination of the engine file's fuses' stages but the all-intact one, {fuse id: stage} (each fuse
    from 0 to its ``stages``), the first fuse's stage varying slowest: for one fuse, its stages in turn."""
    fuses = data.get("fuse", {}) if isinstance(data.get("fuse"), dict) else {}
    ids = [k for k, f in fuses.items() if isinstance(f, dict)]
    combos = [{}]
    for k in ids:
        combos = [dict(c, **{k: s}) for c in combos for s in range(int(fuses[k].get("stages", 1)) + 1)]
    return [c for c in combos if any(c.values())]


def supports(sc=None, oil_temperature_C: float | None = None, data: dict | None = None,
             fuse_stage: int | dict = 0) -> dict:
    """{"h<ID>": {...}} for every bearing<ID> of the rotor data's [attach] (in its order; "h0", "h5" for the paper's
    engine): node, hub and k_contact, m_journal, k_spring, c_film, oil_temperature_C taken from the scenario's
    bearing<ID> and damper<ID> components (a scenario without them is an error naming the id); a fused bearing's
    fuse at ``fuse_stage`` (every fuse's, or {fuse id: stage}, 0 for an id not given)."""
    own = sc is None    # no scenario: the engine file's own parts ([bearing.ID], [damper.ID])
    sc = scenario_or_default(sc)
    if data is None:
        data, _ = fem.load_data(sc.components["rotor"].parameters.get("model_file") or None)
    ls = data.get("attach", {})
    T_C = float(ls.get("oil_temperature_C", 30.0) if oil_temperature_C is None else oil_temperature_C)
    if not (math.isfinite(T_C) and -20.0 < T_C < 300.0):
        raise ValueError(f"oil temperature for the linearised film must be a temperature in C, got {T_C!r}")
    out = {}
    ids = attach.layout(ls).bearings
    if not ids:
        raise ValueError("rotor model data: [attach] has no bearing<ID> entry (node, housing)")
    for k in ids:
        key = f"h{k}"
        if own:
            lacks = [t for t in (f"bearing.{k}", f"damper.{k}")
                     if not isinstance(data.get(t.split(".")[0], {}).get(k), dict)]
            if lacks:
                raise ValueError(f"the engine file has no [{'] or ['.join(lacks)}] for its [attach] bearing{k}: give "
                                 "them (docs/reference/engine-format.md) or a scenario that does (--scenario FILE)")
            brg = registry.create("bearing.hertz", f"bearing{k}", part_parameters(f"bearing{k}", data=data))
            dmp = registry.create("damper.fast", f"damper{k}", part_parameters(f"damper{k}", data=data))
        else:
            missing = [c for c in (f"bearing{k}", f"damper{k}") if c not in sc.components]
            if missing:
                raise ValueError(f"scenario {sc.name!r} has no {' or '.join(missing)} for the engine's [attach] "
                                 f"bearing{k}: give the engine's own blade-loss scenario (--scenario FILE)")
            brg = create_component(sc.components[f"bearing{k}"])
            dmp = create_component(sc.components[f"damper{k}"])
        brg.setup(0.0)
        dmp.setup(0.0)
        if not own:
            for comp, kind in ((brg, "bearing"), (dmp, "damper")):
                _check_linearisable(sc, comp, kind)
        at = ls[f"bearing{k}"]
        out[key] = {"node": tuple(at["node"]), "hub": at["housing"],
                    "k_contact": contact_stiffness(brg), "m_journal": float(brg.p["m_journal"]),
                    "k_spring": float(dmp.p["k_spring"]), "c_film": film_damping(dmp, T_C),
                    "oil_temperature_C": T_C}
        if k in fem.fuse_ids(data):
            name = f"fuse{k}"
            fp = (part_parameters(name, scenario=sc) if not own and name in sc.components
                  else part_parameters(name, data=data))
            stage = int(fuse_stage.get(k, 0) if isinstance(fuse_stage, dict) else fuse_stage)
            out[key]["fuse"] = {"housing": fem.fused_housing(k), "k": fuse_stiffness(fp, stage),
                                "c": float(fp.get("damping", 0.0)), "stage": stage}
    return out


#: what the linearisation reads of a bearing and a damper: the native models' (contact_stiffness, film_damping)
READS = {"bearing": (("geometry", "z0"), ("omega", "m_journal"), "the ball bearing (bearing.hertz)"),
         "damper": (("viscosity", "film_force"), ("k_spring", "clearance"), "the damper (damper.fast or damper.fe)")}


def _check_linearisable(sc, comp, kind: str) -> None:
    """A scenario's part in another implementation (an FMU of an SSP archive, a plug-in) has not what the
    linearisation reads: an error naming it ('FMUComponent' object has no attribute 'geometry' and "error:
    'k_spring'" were all it said)."""
    attributes, parameters, native = READS[kind]
    if all(hasattr(comp, a) for a in attributes) and all(p in comp.p for p in parameters):
        return
    spec = sc.components[comp.name]
    what = spec.fmu_label or spec.fmu or spec.implementation   # an SSP's FMU by its entry, not its extraction
    raise ValueError(f"scenario {sc.name!r}: {comp.name} is {what}, not {native} whose "
                     "model the linearised engine reads: give a scenario of the native parts (--scenario FILE)")


def contact_stiffness(bearing) -> float:
    """Radial stiffness (N/m) of the ball set about the preloaded rest state (inner race at the preload offset,
    outer race centred), from the bearing component's quasi-static model."""
    from rotorcosim.components.bearing.static import stiffness

    g = bearing.geometry
    Fc = g.centrifugal_force(bearing.p["omega"])
    J = stiffness(g, np.array([0.0, 0.0, bearing.z0]), Fc=Fc)
    return float(-(J[0, 0] + J[1, 1]) / 2.0)


def film_damping(damper, T_C: float) -> float:
    """Linear damping (N s/m) of the damper's film about the centred journal at oil temperature T_C: the
    tangential force over the speed of a vanishing circular orbit (radius 1e-4 of the clearance)."""
    mu = damper.viscosity(T_C + KELVIN)
    r = 1e-4 * damper.p["clearance"]
    W = 1000.0                          # rad/s; the ratio does not depend on it for a vanishing orbit
    _, Fy = damper.film_force(r, 0.0, 0.0, W * r, mu)
    return float(-Fy / (W * r))


def describe(sup: dict) -> dict:
    """The support model in words and numbers, for ``critical-speeds --json``."""
    return {"kind": "coupled", "description": "co-simulated system linearised: ball contacts at the preloaded "
            "rest -> outer race + journal body (eq. 5) -> O-ring spring + film (linearised at the oil temperature, "
            "centred journal) -> casing hub",
            "oil_temperature_C": next(iter(sup.values()))["oil_temperature_C"],
            "bearings": {k[1:]: {n: v for n, v in s.items() if n not in ("node", "pt_node", "hub", "oil_temperature_C",
                                                                         "fuse")}
                         | ({"fuse_k": s["fuse"]["k"], "fuse_c": s["fuse"]["c"]} if "fuse" in s else {})
                         for k, s in sup.items()}}


def critical_speeds(full: fem.FullModel, sup: dict, n: int = 6, max_rpm: float = 60000.0) -> dict:
    """The ``n`` lowest forward and backward synchronous critical speeds [rev/min] up to ``max_rpm`` of the rotor
    model ``full`` on the linear supports ``sup`` (:func:`supports`)."""
    return critical.synchronous_critical_speeds(full, sup, n=n, max_rpm=max_rpm)


def response(full: fem.FullModel, sup: dict, F_u: float, rpm: float | None = None, system: dict | None = None) -> dict:
    """Steady synchronous response of the linear engine (:func:`rotorcosim.components.rotor.calibration.
    coupled_response`): per bearing id ("0", "5" for the paper's engine) whirl_mm, journal_mm, transmissibility (eq. 23).
    ``system``: ``full.coupled(sup)``, built once by a caller that scans speeds."""
    return calibration.coupled_response(full, sup, F_u, rpm, system)


def main(argv=None) -> int:
    """``python -m rotorcosim.cases.blade_loss.linear_engine [FILE] [--layout-search | --response-study]``: the rotor
    calibration (components/rotor/calibration.py) on this linear engine; prints the knobs to write into the file."""
    import sys

    argv = sys.argv[1:] if argv is None else argv
    args = [a for a in argv if not a.startswith("--")]
    d, _ = fem.load_data(args[0] if args else None)
    sup = supports(data=d)
    if "--layout-search" in argv:
        calibration.layout_search(d, sup)
        return 0
    if "--response-study" in argv:
        calibration.response_study(d, sup)
        return 0
    x, f = calibration.calibrate(d, sup=sup)
    for k, v in zip(calibration.KNOBS, x):
        print(f"{k} = {v:.4f}")
    print("forward synchronous critical speeds:", f.round(1))
    d["calibration"].update(dict(zip(calibration.KNOBS, x)))
    for F in (712.0, 2850.0):
        for b, r in calibration.linear_response_detail(d, F_u=F, sup=sup).items():
            print(f"linear {F:g} N response at 16 000 rev/min, #{b}: whirl {r['whirl_mm']:.4f} mm (journal orbit "
                  f"{r['journal_mm']:.4f} mm), transmissibility {r['transmissibility']:.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
