"""What the figures call the engine's parts: the engine file's own spool names and the run's own clearances.

A figure of a run names what that run simulated, never the paper's engine by default:

- :func:`bearing_spools`: the spool each co-simulated bearing's inner race is on, by the engine file's
  ``[spool.NAME] name`` (``[attach] bearing<ID> = { node = [NAME, n] }``): "power turbine" for both bearings of the
  paper's engine, "rotor" for a single-spool engine whose spool is so named; a test rotor without spools
  (``[shaft]``) gives "rotor";
- :func:`spool_name`: the engine's name of the spool a spool component turns (its ``model_file`` and ``spool``);
- :func:`rub_clearances_mm`: the radial clearance each rub ring ran with [mm], as the run's provenance records it
  (the component's resolved parameter, its default included), else as the scenario sets it.
"""
from __future__ import annotations

from pathlib import Path

from rotorcosim.components.bounded_read import read_json
from rotorcosim.components.rotor import model as fem

#: what a part is called when its engine file does not name it
ROTOR = "rotor"


def _engine(model_file: str | None) -> dict:
    try:
        data, _ = fem.load_data(model_file or None)
    except (OSError, ValueError):  # a figure never fails for a name: the generic word instead
        return {}
    return data if isinstance(data, dict) else {}


def _spool_label(data: dict, key: str) -> str:
    spool = (data.get("spool") or {}).get(key)
    name = spool.get("name") if isinstance(spool, dict) else None
    return str(name) if name else str(key)


def bearing_spools(sc, ids) -> dict[str, str]:
    """Bearing id -> the name of the spool its inner race is on (see the module's docstring)."""
    rotor = sc.components.get("rotor")
    data = _engine(rotor.parameters.get("model_file", "") if rotor is not None else "")
    attach = data.get("attach") or {}
    out = {}
    for k in ids:
        node = (attach.get(f"bearing{k}") or {}).get("node") if isinstance(attach, dict) else None
        key = node[0] if isinstance(node, (list, tuple)) and node and isinstance(node[0], str) else None
        out[str(k)] = _spool_label(data, key) if key is not None else ROTOR
    return out


def spool_name(sc, component: str) -> str:
    """The engine's name of the spool the spool component ``component`` turns (its ``spool`` in its
    ``model_file``); the component's name where the engine does not say."""
    spec = sc.components.get(component)
    if spec is None:
        return component
    key = spec.parameters.get("spool", "pt")
    data = _engine(spec.parameters.get("model_file", ""))
    return _spool_label(data, key) if key in (data.get("spool") or {}) else component


def rub_clearances_mm(sc, ids, out: str | Path | None = None) -> dict[str, float | None]:
    """Bearing id -> the radial clearance [mm] of its rub ring in this run (None: no rub ring, or no value
    known): the run's ``summary.json`` provenance (every parameter the component ran with) in ``out``, else the
    scenario's own parameter."""
    ran = {}
    if out is not None:
        try:
            ran = read_json(Path(out) / "summary.json", "summary")["provenance"]["parameters"]
        except (OSError, ValueError, KeyError, TypeError):
            ran = {}
    result = {}
    for k in ids:
        name = f"rubring{k}"
        value = ((ran.get(name) or {}).get("parameters") or {}).get("clearance") if isinstance(ran, dict) else None
        if value is None and name in sc.components:
            value = sc.components[name].parameters.get("clearance")
            if value is None and sc.components[name].implementation == "rubring.contact":
                # the shipped ring's own default, by the ring it selects (components/rubring/data/rubrings.toml)
                from rotorcosim.components.rubring.component import RINGS
                ring = RINGS.get(_int(sc.components[name].parameters.get("bearing")))
                value = 1e-3 * ring["clearance_mm"] if ring else None
        result[str(k)] = 1e3 * float(value) if isinstance(value, (int, float)) and name in sc.components else None
    return result


def _int(v):
    try:
        return int(v)
    except (TypeError, ValueError):
        return None
