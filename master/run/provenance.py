"""What made a run: the record a run folder keeps of the code, the scenario and every change to it.

``summary.json`` gets it under ``provenance`` and the HDF5 time series as attributes of its root (flat values,
and the whole record as JSON in ``provenance``), so that either file alone says how to make the run again:

* ``rotorcosim_version``: the version of the code that ran;
* ``scenario_file``: the scenario file (absolute path) or SSP archive it was loaded from (None: built in Python);
* ``scenario_name``: the scenario's name as loaded (``run NAME_<level> --level L`` ran ``NAME_<level>``,
  while the summary's ``scenario`` names the run ``NAME_L``);
* ``edits``: every change made to it after loading, in order: ``{"set": "comp.param", "value", "origin"}``
  (``--set``, :meth:`Scenario.set`), ``{"swap": "comp", "implementation", "origin"}`` (``--swap``,
  :meth:`Scenario.swap`), ``{<level name>: value, "parameter", "origin"}`` (the level option; its name is its case's, master/case.py);
* ``parameters``: per component its implementation (a registry name, ``module:Class`` or an FMU file) and the
  value of every parameter it ran with, those the scenario left at their defaults included;
* ``engine``: the engine file the scenario takes the machine from (master/scenario/engine.py), the quantities
  changed by name (``overrides``) and, per bound parameter, where its value came from (``bound``); None for a
  scenario without an engine;
* ``defaults``: every default the run used, with its source: ``{"parameter": "comp.param", "value",
  "source"}`` for each parameter neither the scenario nor its engine gave (the engine format's documented default,
  or the implementation's declared default and its description).

>>> import rotorcosim
>>> p = provenance(rotorcosim.load_scenario("toy_thermomechanical").set({"node.C": 20.0}))
>>> p["scenario_name"], p["edits"][0]["set"], p["parameters"]["node"]["parameters"]["C"]
('toy_thermomechanical', 'node.C', 20.0)
"""
from __future__ import annotations

import json
from typing import Any

import numpy as np

#: the root attributes of the time series file that hold single values of the record (the rest is in its JSON)
H5_ATTRIBUTES = ("rotorcosim_version", "scenario_file", "scenario_name")


def _value(v: Any) -> Any:
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, np.generic):
        return v.item()
    return v


def provenance(sc, system=None) -> dict:
    """The record of scenario ``sc`` (see the module's docstring); ``system``: the built system, whose
    components give the parameters they resolved (their defaults included); without it, the scenario's own."""
    from rotorcosim import __version__

    params = {}
    for name, spec in sc.components.items():
        comp = system.components.get(name) if system is not None else None
        values = getattr(comp, "p", None)
        if not isinstance(values, dict):  # an FMU: the values the scenario gives it
            values = spec.parameters
        params[name] = {"implementation": spec.fmu or spec.implementation,
                        "parameters": {k: _value(v) for k, v in values.items()}}
    binding = getattr(sc, "engine", None)
    return {"rotorcosim_version": __version__,
            "scenario_file": str(sc.source) if sc.source else None,
            "scenario_name": sc.loaded_name or sc.name,
            "edits": [dict(e) for e in sc.edits],
            "parameters": params,
            "engine": binding.provenance() if binding is not None else None,
            "defaults": defaults(sc, params)}


def defaults(sc, params: dict) -> list[dict]:
    """The parameters a run took from a default (module docstring), from ``params`` (:func:`provenance`'s)."""
    from rotorcosim.components import registry

    binding = getattr(sc, "engine", None)
    engine_src = {t: s for t, s in (binding.sources.items() if binding is not None else ())
                  if s.startswith("default")}
    out = []
    for name, spec in sc.components.items():
        if spec.implementation is None:
            continue
        try:
            declared = registry.lookup(spec.implementation, spec.folder).variables
        except Exception:  # noqa: BLE001 - a record of what ran: an implementation it cannot look up has no defaults
            continue
        for v in declared:
            ref = f"{name}.{v.name}"
            if v.causality != "parameter" or (v.name in spec.parameters and ref not in engine_src):
                continue
            src = engine_src.get(ref) or f"{spec.implementation} default: {v.description}"
            out.append({"parameter": ref, "value": params[name]["parameters"].get(v.name, _value(v.start)),
                        "source": src})
    for ref, src in engine_src.items():
        if ref.startswith("schedule."):
            out.append({"parameter": ref, "value": sc.schedule.get(ref.partition(".")[2]), "source": src})
    return out


def h5_attributes(record: dict) -> dict[str, str]:
    """The root attributes of the time series file for ``record``: the single values, and the whole as JSON
    (``provenance``); HDF5 attributes hold no nested dicts, and a missing file reads as an empty string."""
    out = {k: "" if record.get(k) is None else str(record[k]) for k in H5_ATTRIBUTES}
    out["provenance"] = json.dumps(record, default=str)
    return out
