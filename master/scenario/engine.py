"""A scenario's engine: the component parameters and schedule values it takes from its engine file.

A scenario names its engine once, ``[scenario] engine = "engine.toml"`` (relative to the file that says it), and a
component parameter or a ``[schedule]`` value written ``"engine:NAME"`` takes the engine's quantity ``NAME``
(components/rotor/engine_parts.py: ``"damper.0.clearance"``, ``"bearing.0.omega"``, ``"spool#1.omega"``,
``"spool.pt.inertia"``, ``"file"``...)::

    [components.damperA]
    parameters = { clearance = "engine:damper.A.clearance" }
    [components.thermalA]
    parameters = { damper_clearance = "engine:damper.A.clearance" }

Every parameter bound to one quantity takes the same value: the machine is described once. Changing a bound
parameter by name (``--set damperA.clearance=...``, a sweep's, a calibration's or a UQ's parameter:
:func:`set_bound`) changes the quantity, and every parameter built from it follows (``thermalA.damper_clearance``
with it; ``rotor.omega_pt`` moves every speed of that spool and ``[schedule] speed_rpm``). A file further down
an ``extends`` chain that writes a plain value replaces the binding of that one parameter.

A quantity the engine file does not give and whose component has its own documented default leaves the parameter
unset (the component's default applies); a quantity the file must give is refused with the key named. A bound
parameter that the component's implementation does not declare (a plug-in or an FMU put in its place) is
dropped.
:attr:`EngineBinding.sources` says where each bound value came from (``summary.json`` provenance).
"""
from __future__ import annotations

import copy
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from rotorcosim.components import registry
from rotorcosim.components.contract import ContractError
from rotorcosim.components.rotor.engine_parts import EngineView

from rotorcosim.master.scenario.compose import ScenarioError

PREFIX = "engine:"
#: the schedule's keys that may take an engine quantity
SCHEDULE_KEYS = ("speed_rpm",)


def is_ref(value: Any) -> bool:
    """Whether ``value`` takes an engine quantity (``"engine:NAME"``)."""
    return isinstance(value, str) and value.startswith(PREFIX)


@dataclass
class EngineBinding:
    """The engine file, the bound targets (``"comp.param"`` or ``"schedule.speed_rpm"`` -> quantity name), the
    quantities changed by name (``overrides``, SI) and where each bound value came from (``sources``)."""

    file: str
    targets: dict[str, str] = field(default_factory=dict)
    overrides: dict[str, Any] = field(default_factory=dict)
    sources: dict[str, str] = field(default_factory=dict)

    def view(self) -> EngineView:
        """The engine's quantities with this binding's overrides (components/rotor/engine_parts.py)."""
        return EngineView(self.file, self.overrides)

    def provenance(self) -> dict:
        """The engine file, the quantities changed by name, and per bound target its value's source."""
        return {"file": self.file, "overrides": dict(self.overrides), "bound": dict(self.sources)}


def _declared(impl: str | None, folder: str | None, fmu: str | None = None,
              base: Path | None = None) -> set[str] | None:
    """The parameters the component's implementation, or its FMU (a relative path read from ``base``, the
    scenario file's folder, as the build reads it), declares; None when not known (the build names the problem)."""
    if impl is None:
        if not isinstance(fmu, str) or not fmu:
            return None
        from rotorcosim.fmus.description import parameter_names

        path = Path(fmu).expanduser()
        return parameter_names(path if path.is_absolute() or base is None else base / path)
    try:
        cls = registry.lookup(impl, folder)
    except (ContractError, ImportError, AttributeError):
        return None          # the schema names a bad implementation
    return {v.name for v in getattr(cls, "variables", ()) if v.causality == "parameter"}


def drop_undeclared(binding: EngineBinding | None, component: str, params: dict, declared: set[str]) -> None:
    """Drop from ``params`` (the parameters of ``component``, in place) and from ``binding`` the bound parameters
    that its implementation does not ``declare``: a plug-in swapped in for a bound component, as :func:`bind` does
    for one a scenario file puts in its place."""
    if binding is None:
        return
    for p in [p for p in params if f"{component}.{p}" in binding.targets and p not in declared]:
        del params[p]
        binding.targets.pop(f"{component}.{p}")
        binding.sources.pop(f"{component}.{p}", None)


def bind(data: dict, origins, where: str) -> EngineBinding | None:
    """Resolve the ``"engine:NAME"`` values of a composed scenario ``data`` in place (before its schema check);
    returns the binding, or None when the scenario takes nothing from an engine."""
    comps = data.get("components") if isinstance(data.get("components"), Mapping) else {}
    targets: dict[str, str] = {}
    for cname, spec in comps.items():
        params = spec.get("parameters") if isinstance(spec, Mapping) else None
        if not isinstance(params, Mapping):
            continue
        came = origins.component(cname)
        folder = str(Path(came).parent) if came else None
        declared = _declared(spec.get("implementation"), folder, spec.get("fmu"),
                             Path(where).parent if where else None)
        for p, v in list(params.items()):
            if is_ref(v):
                if declared is not None and p not in declared:
                    del params[p]        # a plug-in or an FMU in the bound component's place
                    continue
                targets[f"{cname}.{p}"] = v[len(PREFIX):]
    sched = data.get("schedule") if isinstance(data.get("schedule"), Mapping) else {}
    for key in SCHEDULE_KEYS:
        if is_ref(sched.get(key)):
            targets[f"schedule.{key}"] = sched[key][len(PREFIX):]
    head = data.get("scenario") if isinstance(data.get("scenario"), Mapping) else {}
    file = head.get("engine")
    if not targets and file is None:
        return None
    if not isinstance(file, str) or not file:
        first = next(iter(targets))
        raise ScenarioError(f"{where}: {first} = \"{PREFIX}{targets[first]}\" takes a value from the engine, but "
                            "[scenario] engine names no engine file")
    for cname, spec in comps.items():
        mf = spec.get("parameters", {}).get("model_file") if isinstance(spec, Mapping) else None
        if isinstance(mf, str) and mf and not is_ref(mf) and "file" in targets.values():
            # the rotor of one file and the parts of another: the engine is named once, by [scenario] engine
            raise ScenarioError(f"{origins.parameter(cname, 'model_file') or where}: [components.{cname}] model_file "
                                f"= {mf!r}, but the scenario's engine is {file!r}: name the engine once, with "
                                "[scenario] engine = \"FILE\" (every part takes its values from it)")
    if not targets:
        raise ScenarioError(f"{where}: [scenario] engine = {file!r}, but no component takes a value from it (a "
                            f"parameter written \"{PREFIX}NAME\"): the run would not be of that engine")
    binding = EngineBinding(file, targets)
    apply(binding, data=data, where=where, origins=origins)
    return binding


def _values(binding: EngineBinding, where: str) -> dict[str, tuple[Any, str]]:
    try:
        view = binding.view()
        return {t: view.value(q) for t, q in binding.targets.items()}
    except (ValueError, OSError) as exc:
        raise ScenarioError(f"{where}: [scenario] engine: {exc}") from None


def apply(binding: EngineBinding, *, data: dict | None = None, sc=None, where: str = "scenario", origins=None,
          origin_note: str | None = None) -> None:
    """Write the bound values into the composed ``data`` or the scenario ``sc``."""
    values = _values(binding, where)
    for target, (value, source) in values.items():
        table, _, key = target.partition(".")
        src = source if source != "override" else f"{origin_note or 'set'} (engine quantity {binding.targets[target]})"
        binding.sources[target] = src
        if table == "schedule":
            sched = data["schedule"] if data is not None else sc.schedule
            sched[key] = value
            continue
        if data is not None:
            params = data["components"][table]["parameters"]
            if value is None:
                params.pop(key, None)
            else:
                params[key] = value
                if origins is not None:
                    origins.parameters[(table, key)] = src
        else:
            spec = sc.components[table]
            if value is None:
                spec.parameters.pop(key, None)
                spec.param_origins.pop(key, None)
            else:
                spec.parameters[key] = value
                spec.param_origins[key] = src


def set_bound(sc, ref: str, value: Any, origin: str) -> bool:
    """Change the engine quantity that ``ref`` (``"comp.param"``) is bound to, and every parameter bound to it;
    False if ``ref`` is bound to none (a plain parameter)."""
    binding = getattr(sc, "engine", None)
    if binding is None or ref not in binding.targets:
        return False
    trial = copy.deepcopy(binding)
    try:
        view = trial.view()
        view.set(binding.targets[ref], value, label=ref)
        trial.file, trial.overrides = view.path, view.overrides
    except (ValueError, OSError) as exc:
        raise ScenarioError(f"set {ref}: {exc}") from None
    apply(trial, sc=sc, where=f"set {ref}", origin_note=f"{origin} {ref}")
    sc.engine = trial
    return True


def part_parameters(component: str, *, engine: str | None = None, scenario=None, data: dict | None = None) -> dict:
    """The parameters component ``component`` (``"bearing1"``, ``"damper1"``, ``"thermal1"``, ``"rubring1"``)
    takes from the engine file ``engine`` (through the shipped templates: the same values a run of that engine
    gives it) or from the scenario ``scenario`` (a :class:`Scenario`); ``data``: the engine file's contents, already
    read; a ValueError naming what is missing."""
    if scenario is not None:
        if component not in scenario.components:
            raise ValueError(f"scenario {scenario.name!r} has no component {component!r} (it has "
                             f"{', '.join(scenario.components)})")
        return dict(scenario.components[component].parameters)
    from rotorcosim.master.scenario import templates

    for name in templates.shipped():
        for _, made in templates.instances({name: ["ID"]}, "rotorcosim"):
            for key in made["components"]:
                prefix, pid = key[:-2], component[len(key) - 2:]
                if component.startswith(prefix) and templates.ID.match(pid):
                    spec = templates.instances({name: [pid]}, "rotorcosim")[0][1]["components"][component]
                    view = EngineView(engine, data=data)
                    out = {}
                    for p, v in spec.get("parameters", {}).items():
                        value = view.value(v[len(PREFIX):])[0] if is_ref(v) else v
                        if value is not None:
                            out[p] = value
                    return out
    raise ValueError(f"no shipped template makes a component {component!r}")


def bound_together(sc, refs) -> list[str]:
    """Every component parameter (``"comp.param"``) bound to the same engine quantity as one of ``refs``, each once,
    in the order of ``refs`` (``"damperA.clearance"`` -> ``["damperA.clearance", "thermalA.damper_clearance"]``);
    a ref bound to nothing stands alone."""
    binding = getattr(sc, "engine", None)
    out: list[str] = []
    for ref in refs:
        q = binding.targets.get(ref) if binding is not None else None
        group = [ref] + ([t for t, tq in binding.targets.items() if tq == q and t != ref and not
                          t.startswith("schedule.")] if q is not None else [])
        out += [t for t in group if t not in out]
    return out
