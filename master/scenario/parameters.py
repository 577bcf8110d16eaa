"""Every parameter of a scenario's components: name, unit, default, current value and where the value comes
from (``rotorcosim parameters``, :meth:`Scenario.parameters`).

A value's ``source`` is the scenario file that set it, ``"default"`` (the implementation's declared start value)
or ``"set-up"`` (left unset, and the component derived another value when it set itself up, e.g. from a data
table its other parameters select). The current values are the component's after its set-up, so what is listed
is what a run uses.

Example::

    import rotorcosim
    for row in rotorcosim.load_scenario("toy_thermomechanical").parameters("osc"):
        print(row["name"], row["value"], row["unit"], row["source"])
"""
from __future__ import annotations

from typing import Any

from rotorcosim.components import registry
from rotorcosim.components.contract import ContractError
from rotorcosim.master.scenario.compose import ScenarioError

#: the keys of a parameter row
KEYS = ("component", "name", "unit", "default", "value", "source", "description")


def _plain(v: Any) -> Any:
    if hasattr(v, "tolist"):
        return v.tolist()
    return v


def implementation_parameters(implementation: str, folder: str | None = None) -> list[dict]:
    """The declared parameters of an implementation (a registry name or ``"module:Class"``): one row each,
    ``value`` = ``default``, ``component`` = the implementation's name."""
    cls = registry.lookup(implementation, folder)
    return [{"component": implementation, "name": v.name, "unit": v.unit, "default": _plain(v.start),
             "value": _plain(v.start), "source": "default", "description": v.description}
            for v in cls.variables if v.causality == "parameter"]


def scenario_parameters(sc, component: str | None = None) -> list[dict]:
    """The parameters of the scenario's components (or of ``component`` alone), with the values a run uses."""
    names = list(sc.components)
    if component is not None:
        if component not in sc.components:
            raise ScenarioError(f"no component {component!r} in scenario {sc.name!r} (it has {', '.join(names)})")
        names = [component]
    rows = []
    for name in names:
        spec = sc.components[name]
        if spec.fmu is not None:
            for p, v in spec.parameters.items():
                rows.append({"component": name, "name": p, "unit": "", "default": None, "value": _plain(v),
                             "source": spec.param_origins.get(p, spec.origin or ""), "description": "FMU parameter"})
            continue
        where = f"{spec.origin + ': ' if spec.origin else ''}[components.{name}]"
        cls = None
        try:
            cls = registry.lookup(spec.implementation, spec.folder)
            comp = cls(spec.name, spec.parameters or {})
            comp.setup(0.0)
        except ContractError as exc:
            raise ScenarioError(f"{where}: {exc}") from None
        except Exception as exc:
            if cls is None or not registry.is_plugin_class(cls):
                raise
            raise ScenarioError(f"{where}: plug-in {spec.implementation!r}: {type(exc).__name__}: {exc}") from None
        for v in type(comp).variables:
            if v.causality != "parameter":
                continue
            value = comp.p.get(v.name, v.start)
            if v.name in spec.parameters:
                source = spec.param_origins.get(v.name) or spec.origin or "scenario"
            else:
                same = value == v.start
                source = "default" if (same if isinstance(same, bool) else bool(getattr(same, "all", lambda: 0)())) \
                    else "set-up"
            rows.append({"component": name, "name": v.name, "unit": v.unit, "default": _plain(v.start),
                         "value": _plain(value), "source": str(source), "description": v.description})
    return rows
