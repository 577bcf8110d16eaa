"""The scenario schema: every table, every key, every type, and the ranges physics gives.

``check(data, source)`` validates a scenario as a plain dict, after any composition (``extends``) has been
applied, so it does not care how the dict was put together. Rules:

* an unknown table or key is an error, with a "did you mean" for a near miss (``stpe`` -> ``step``);
* booleans are not numbers and strings are not numbers (TOML keeps them apart, so a scenario must too);
* every number is finite; steps, durations, speeds, tolerances are positive; counts are whole numbers >= 1;
* cross-checks: connection, input, recorded and order names refer to declared components; a component listed
  twice in ``order``; a component's communication step longer than a thermo-mechanical interval (it would
  stretch the interval silently) or not a whole multiple of the interval step;
* registry components: the implementation exists, parameter names exist, numbers go to numeric parameters and
  text to text ones, and the parameters a component declares *required* (``Component.required_parameters``:
  the bearing, damper or ring number that picks its Table 3 data) are given.

Every error is a :class:`SchemaError` naming the file, the table and the key, with the line of the file where
the key is written when it can be found (key_lines.py). The tables and their keys are in tables.py, the value
checkers in checkers.py, the checks of ``[schedule]`` in schedule_check.py.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any, Callable, Mapping

from rotorcosim.components.contract import ContractError
from rotorcosim.master.scenario.checkers import did_you_mean, is_number, kind_of, parameter_value, port_ref
from rotorcosim.master.scenario.key_lines import locate, locate_in_bases
from rotorcosim.master.scenario.schedule_check import check_record_step, check_schedule, known_component
from rotorcosim.master.scenario.tables import COMPONENT, CONNECTION, TABLES


class SchemaError(ContractError):
    """A scenario that breaks the schema; the message names the file, the table, the key (and the line)."""


class Checker:
    """The checks' context: the scenario's file (``source``) and the file of its ``extends`` chain that brought
    each entry (``origins``), for the error's ``file:line``."""

    def __init__(self, source: Path | None, origins=None):
        self.source = Path(source) if source is not None else None
        self.origins = origins  # compose.Origins: the file of the extends chain that brought each entry

    def file_of(self, table: str, key: str | None) -> Path | None:
        """The file that brought ``table``/``key`` (composition), else the scenario's own file."""
        o, found = self.origins, None
        if o is not None:
            if table.startswith("components."):
                comp = table[len("components."):]
                found = (o.parameter(comp, key[len("parameters."):]) if key and key.startswith("parameters.")
                         else o.component(comp))
            elif table.startswith("connections #"):
                i = int(table.split("#")[1]) - 1
                found = o.connections[i] if 0 <= i < len(o.connections) else None
            elif table == "inputs" and key:
                found = o.inputs.get(key)
        return Path(found) if found else self.source

    def fail(self, table: str, key: str | None, msg: str) -> SchemaError:
        """The error ``msg`` about ``key`` of ``table`` (None: the table itself), at the file and line that
        wrote it."""
        source = self.file_of(table, key)
        where = str(source) if source else "scenario"
        short = key[len("parameters."):] if key and key.startswith("parameters.") else key
        line = locate(source, table, short)
        at = f"{where}:{line}" if line else where
        if not line and short:
            # the key may come from a scenario this one extends: name that file and line too
            base, bline = locate_in_bases(self.source, table, short)
            if bline:
                at = f"{where} (from {base}:{bline})"
        what = f"[{table}]" + (f" {key}" if key else "")
        return SchemaError(f"{at}: {what}: {msg}")

    def table(self, table: str, data: Any, spec: Mapping[str, Callable | None]) -> None:
        """``data``, the table ``table``, against ``spec`` (key -> checker; None: a sub-table checked on its own):
        every key known, every value passing its checker."""
        if not isinstance(data, Mapping):
            raise self.fail(table, None, f"must be a table, got {kind_of(data)}")
        for key, value in data.items():
            if key not in spec:
                raise self.fail(table, key, f"unknown key{did_you_mean(key, spec)}; known: {', '.join(spec)}")
            check = spec[key]
            err = check(value) if check is not None else None
            if err:
                raise self.fail(table, key, err)


def check(data: Mapping[str, Any], source: str | Path | None = None, origins=None) -> None:
    """Raise :class:`SchemaError` for the first thing in ``data`` (a composed scenario dict) that breaks the
    schema; ``source`` is the file it came from, ``origins`` (compose.Origins) the file of the ``extends`` chain
    that brought each component, parameter, connection and input (for the message and the line)."""
    c = Checker(source, origins)
    for name, value in data.items():
        if name not in TABLES:
            raise c.fail(name, None, f"unknown table{did_you_mean(name, TABLES)}; known: {', '.join(TABLES)}")
    for name in ("scenario", "algorithm", "schedule", "outputs", "results"):
        if name in data:
            spec = TABLES[name]
            if name == "results" and isinstance(data[name], Mapping) and data[name].get("kind"):
                # the case's own keys are its case's to check (master/case.py): the generic ones are checked here
                spec = {**spec, **{k: None for k in data[name] if k not in spec}}
            c.table(name, data[name], spec)
    comps = data.get("components")
    if not comps:
        raise c.fail("components", None, "no components: a scenario needs at least one [components.NAME] table")
    if not isinstance(comps, Mapping):
        raise c.fail("components", None, f"must be a table of components, got {kind_of(comps)}")
    for name, spec in comps.items():
        _component(c, name, spec)
    names = list(comps)
    cons = data.get("connections", [])
    if not isinstance(cons, list):
        raise c.fail("connections", None, "must be a list of {from, to} tables ([[connections]])")
    for i, con in enumerate(cons):
        w = f"connections #{i + 1}"
        c.table(w, con, CONNECTION)
        for end in ("from", "to"):
            if end not in con:
                raise c.fail(w, None, "needs 'from' and 'to'")
            known_component(c, w, end, con[end], names)
    inputs = data.get("inputs", {})
    if not isinstance(inputs, Mapping):
        raise c.fail("inputs", None, f"must be a table of 'component.port' = value, got {kind_of(inputs)}")
    for ref, value in inputs.items():
        # a value of the port's own type (number, boolean, string; a list for a vector port): the system checks
        # it against the port's declaration (value_types.check_value) when it is built
        err = port_ref(ref) or parameter_value(value)
        if err:
            raise c.fail("inputs", ref, err)
        known_component(c, "inputs", ref, ref, names)
    _algorithm(c, data.get("algorithm", {}), names)
    tm_steps = check_schedule(c, data.get("schedule", {}), comps)
    check_record_step(c, data.get("outputs", {}).get("record_step"), tm_steps)
    for i, ref in enumerate(data.get("outputs", {}).get("record", [])):
        known_component(c, "outputs", "record", ref, names)
        if ref in data["outputs"]["record"][:i]:  # one dataset per signal: a second would collide in the file
            raise c.fail("outputs", "record", f"{ref!r} is listed twice")
    for key in ("level_parameter", "speed_parameter"):
        ref = data.get("results", {}).get(key)
        if ref:
            known_component(c, "results", key, ref, names)


def _component(c: Checker, name: str, spec: Any) -> None:
    table = f"components.{name}"
    if not name or "." in name:
        raise c.fail(table, None, "component names must be non-empty and contain no '.'")
    c.table(table, spec, COMPONENT)
    impl, fmu = spec.get("implementation"), spec.get("fmu")
    if (impl is None) == (fmu is None):
        raise c.fail(table, None, "give exactly one of 'implementation' (a registry name) or 'fmu' (a file)")
    if "start" in spec and fmu is None:
        raise c.fail(table, "start", "'start' sets start values of an FMU's variables; a native component takes "
                                     "its initial state from its parameters")
    for key in ("process", "step_timeout"):
        if key in spec and fmu is None:
            raise c.fail(table, key, "applies to FMU components only (fmu = ...)")
    start = spec.get("start", {})
    if not isinstance(start, Mapping):
        raise c.fail(table, "start", f"must be a table of variable = value, got {kind_of(start)}")
    for key, value in start.items():
        err = parameter_value(value)
        if err:
            raise c.fail(table, f"start.{key}", err)
    params = spec.get("parameters", {})
    if not isinstance(params, Mapping):
        raise c.fail(table, "parameters", f"must be a table of name = value, got {kind_of(params)}")
    for key, value in params.items():
        err = parameter_value(value)
        if err:
            raise c.fail(table, f"parameters.{key}", err)
    if impl is not None:
        _registry_parameters(c, table, impl, params)


def _registry_parameters(c: Checker, table: str, impl: str, params: Mapping) -> None:
    """Names and kinds of the parameters against what the implementation declares."""
    from rotorcosim.components import registry

    came = c.file_of(table, None)
    try:
        # a plug-in "module:Class" imports from the folder of the file that names it
        cls = registry.lookup(impl, str(came.parent) if came else None)
    except ContractError as exc:
        raise c.fail(table, "implementation", f"{exc}{did_you_mean(impl, registry.available())}") from None
    except (ImportError, AttributeError):  # registered but its code does not import: building it will say so
        return
    declared = {v.name: v for v in getattr(cls, "variables", ()) if v.causality == "parameter"}
    if not declared:
        return
    for key, value in params.items():
        v = declared.get(key)
        if v is None:
            raise c.fail(table, f"parameters.{key}", f"{impl} has no parameter {key!r}"
                         f"{did_you_mean(key, declared)}; its parameters: {', '.join(declared)}")
        if v.type == "String" and not isinstance(value, str):
            raise c.fail(table, f"parameters.{key}", f"must be a string, got {kind_of(value)} ({value!r})")
        if v.type == "Boolean" and not isinstance(value, bool):
            raise c.fail(table, f"parameters.{key}", f"must be true or false, got {kind_of(value)} ({value!r})")
        if v.type in ("Real", "Integer") and isinstance(value, (bool, str)):
            raise c.fail(table, f"parameters.{key}", f"must be a number [{v.unit}], got {kind_of(value)} ({value!r})")
        if v.type == "Integer" and is_number(value) and value != int(value):
            raise c.fail(table, f"parameters.{key}", f"must be a whole number, got {value!r}")
    for key in getattr(cls, "required_parameters", ()):
        if key not in params:
            desc = declared[key].description if key in declared else ""
            raise c.fail(table, None, f"parameters.{key} is required by {impl} ({desc}); "
                                      f"write e.g. parameters = {{ {key} = ... }}")


def _algorithm(c: Checker, a: Mapping, names) -> None:
    order = a.get("order")
    if order is None:
        return
    seen = set()
    for n in order:
        if n in seen:
            raise c.fail("algorithm", "order", f"component {n!r} is listed twice (it would be stepped twice)")
        seen.add(n)
        if n not in names:
            raise c.fail("algorithm", "order", f"no component {n!r}{did_you_mean(n, names)}; "
                                               f"components: {', '.join(names)}")
