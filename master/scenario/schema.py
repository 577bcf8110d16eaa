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
the key is written when it can be found (TOML parsers do not keep value positions, so the line is searched for).
"""
from __future__ import annotations

import difflib
import math
import os
import re
from pathlib import Path
from typing import Any, Callable, Mapping

from rotorcosim.components.contract import COUPLED, HELD, ContractError

from rotorcosim.master.core.algorithm import ALGORITHMS
from rotorcosim.master.core.phases import ROLES, Phases
from rotorcosim.master.manipulator.hold import RESTART_CYCLES
from rotorcosim.master.schedule.timeline import SCHEDULES
from rotorcosim.master.core.system import AVERAGES, EXTRAPOLATIONS, HOLDS, UNCONNECTED_INPUTS

SCHEDULE_KINDS = tuple(SCHEDULES)   # the schedule registry (master/schedule/timeline.py)
OUTPUT_FORMATS = ("h5", "csv")


class SchemaError(ContractError):
    """A scenario that breaks the schema; the message names the file, the table, the key (and the line)."""


# -- value checkers: each returns an error text or None ----------------------------------------------
def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _kind(v: Any) -> str:
    return {bool: "a boolean", str: "a string", list: "a list", dict: "a table"}.get(type(v), type(v).__name__)


def number(v: Any) -> str | None:
    """A finite number (not a boolean). Each checker returns None for a good value ``v`` and otherwise the
    error's text.

    >>> number(2.5) is None, number("2.5")
    (True, "must be a number, got a string ('2.5')")
    """
    if not _is_number(v):
        return f"must be a number, got {_kind(v)} ({v!r})"
    if not math.isfinite(v):
        return f"must be a finite number, got {v!r}"
    return None


def positive(v: Any) -> str | None:
    """A finite number > 0 (a step [s], a tolerance ...)."""
    err = number(v)
    if err is None and v <= 0:
        return f"must be a positive number, got {v!r}"
    return err


def not_negative(v: Any) -> str | None:
    """A finite number >= 0."""
    err = number(v)
    if err is None and v < 0:
        return f"must be a number >= 0, got {v!r}"
    return err


def whole_positive(v: Any) -> str | None:
    """A positive whole number, written as an integer or a float (5, 5.0, 1e12): a count of rotor cycles whose
    mean is taken. 2.5 cycles of a periodic power average to a value that depends on where the window starts."""
    err = positive(v)
    if err is None and v != int(v):
        return f"must be a whole number of rotor cycles, got {v!r}"
    return err


def count(v: Any) -> str | None:
    """An integer >= 1 (written as an integer: 3, not 3.0)."""
    if not isinstance(v, int) or isinstance(v, bool):
        return f"must be a whole number, got {_kind(v)} ({v!r})"
    return None if v >= 1 else f"must be >= 1, got {v!r}"


def text(v: Any) -> str | None:
    """A string."""
    return None if isinstance(v, str) else f"must be a string, got {_kind(v)} ({v!r})"


def boolean(v: Any) -> str | None:
    """true or false."""
    return None if isinstance(v, bool) else f"must be true or false, got {_kind(v)} ({v!r})"


def one_of(*allowed: str) -> Callable[[Any], str | None]:
    """A checker of a string among ``allowed`` (its error suggests the nearest one).

    >>> one_of("jacobi", "gauss-seidel")("gauss_seidel")
    "'gauss_seidel' is not one of 'jacobi', 'gauss-seidel' (did you mean 'gauss-seidel'?)"
    """
    def check(v: Any) -> str | None:
        if not isinstance(v, str) or v not in allowed:
            return f"{v!r} is not one of {', '.join(repr(a) for a in allowed)}" + _did_you_mean(v, allowed)
        return None
    return check


def port_ref(v: Any) -> str | None:
    """A port reference written ``"component.port"``."""
    if not isinstance(v, str):
        return f"must be a string 'component.port', got {_kind(v)} ({v!r})"
    comp, dot, port = v.partition(".")
    return None if dot and comp and port else f"{v!r} must be written 'component.port'"


def list_of(item: Callable[[Any], str | None]) -> Callable[[Any], str | None]:
    """A checker of a list whose every element passes ``item`` (the error names the element, from 1)."""
    def check(v: Any) -> str | None:
        if not isinstance(v, list):
            return f"must be a list, got {_kind(v)} ({v!r})"
        for i, x in enumerate(v):
            err = item(x)
            if err:
                return f"item {i + 1}: {err}"
        return None
    return check


def text_or_texts(v: Any) -> str | None:
    """A string or a list of strings (``extends``: one base file or several)."""
    return None if isinstance(v, str) else list_of(text)(v)


def numbers(v: Any) -> str | None:
    """A number or a non-empty list of numbers (a vector port's value)."""
    if isinstance(v, list):
        return "must not be an empty list" if not v else list_of(number)(v)
    return number(v)


def parameter_value(v: Any) -> str | None:
    """A component parameter's value: a boolean, a string, a finite number or a non-empty list of numbers (its
    unit is the parameter's own, SI)."""
    if isinstance(v, (bool, str)):
        return None
    if isinstance(v, list):
        return "must not be an empty list" if not v else list_of(number)(v)
    return number(v)


# -- the tables -------------------------------------------------------------------------------------
#: table -> key -> checker. ``None`` as a checker means "a sub-table checked on its own".
TABLES: dict[str, dict[str, Callable | None]] = {
    # unconnected_inputs: a policy of the whole system's wiring (every component, every file it extends), so
    # it sits with the scenario's name rather than in one component's table
    "scenario": {"name": text, "description": text, "extends": text_or_texts, "engine": text,
                 "unconnected_inputs": one_of(*UNCONNECTED_INPUTS)},
    "components": {},   # one sub-table per component: COMPONENT
    "connections": {},  # a list of CONNECTION tables
    "inputs": {},       # "component.port" -> number(s)
    "algorithm": {"kind": one_of(*ALGORITHMS), "order": list_of(text), "iterations": count, "tolerance": positive},
    "schedule": {"kind": one_of(*SCHEDULE_KINDS), "duration": positive, "step": positive, "thermal_step": positive,
                 "speed_rpm": positive, "cycle": None, "hold": one_of(*HOLDS),
                 "hold_cycles": whole_positive, "restart_cycles": not_negative,
                 "intervals": None, "phases": None,
                 "steady_tolerance": positive, "steady_cycles": count, "drift_tolerance": positive,
                 "speed_tolerance": positive,
                 "tm_min": positive, "tm_max": positive, "to_min": positive, "to_max": positive,
                 "tracked": list_of(port_ref), "tolerance": positive},
    "outputs": {"record": list_of(port_ref), "record_step": positive, "format": one_of(*OUTPUT_FORMATS)},
    # the generic keys; a scenario with a case (kind) may give the case's own keys too, which its case checks
    # when the scenario is loaded (master/case.py check_results, the case's RESULTS_KEYS)
    "results": {"kind": text, "level_parameter": port_ref, "speed_parameter": port_ref, "cycles": whole_positive},
}
COMPONENT = {"implementation": text, "fmu": text, "parameters": None, "step": positive,
             # FMUs only: start values of states / initial = "exact" variables (fmus/importer.py)
             "start": None,
             # FMUs only (fmus/process.py): run it in a process of its own, with a time limit on every call
             "process": boolean, "step_timeout": positive}
CONNECTION = {"from": port_ref, "to": port_ref, "average": one_of(*AVERAGES),
              "extrapolation": one_of(*EXTRAPOLATIONS), "hold": one_of(*HOLDS),
              # type conversion and the unit of a unit-less side (master/core/conversions.py checks the values)
              "convert": text, "unit": text}
INTERVAL = {"phase": text, "duration": positive, "cycles": positive, "step": positive}
#: ``[schedule] cycle``: a constant period [s], or a speed / frequency output and its unit (master/scenario/cycle.py)
CYCLE = {"period": positive, "signal": port_ref, "unit": text, "angle": port_ref}


def did_you_mean(word: Any, known) -> str:
    """`` (did you mean 'x'?)`` for the closest of ``known`` to ``word``, or an empty string."""
    return _did_you_mean(word, known)


def _did_you_mean(word: Any, known) -> str:
    if not isinstance(word, str):
        return ""
    close = difflib.get_close_matches(word, list(known), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


# -- locating a key in the file ---------------------------------------------------------------------
_HEADER = re.compile(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")


def locate(source: Path | None, table: str, key: str | None) -> int | None:
    """The 1-based line of ``source`` where ``key`` is written in ``table`` (best effort), or None."""
    if source is None:
        return None
    try:
        lines = Path(source).read_text().splitlines()
    except (OSError, UnicodeDecodeError):
        return None
    head = re.split(r"[ .]", table)[0]
    wanted = re.compile(r"(^|[{,\s])[\"']?" + re.escape(key) + r"[\"']?\s*=") if key else None
    current = ""
    fallback = None
    for i, line in enumerate(lines, 1):
        m = _HEADER.match(line)
        if m:
            current = m.group(1).replace('"', "").replace("'", "")
            if wanted is None and current == table:
                return i
            continue
        if wanted is None or not wanted.search(line.split("#")[0]):
            continue
        if current == table or (current == "" and table == head):
            return i
        if fallback is None and (current.startswith(head) or current == ""):
            fallback = i
    return fallback


_EXTENDS = re.compile(r"^\s*extends\s*=\s*(\[[^\]]*\]|\"[^\"]*\"|'[^']*')", re.M)


def _locate_in_bases(source: Path | None, table: str, key: str, seen=()) -> tuple[Path | None, int | None]:
    """(file, line) of ``key`` in the scenarios ``source`` extends (their text's ``extends = ...``), or Nones."""
    if source is None or source in seen or len(seen) > 20:
        return None, None
    try:
        text = Path(source).read_text()
    except (OSError, UnicodeDecodeError):
        return None, None
    for m in _EXTENDS.finditer(text):
        for name in re.findall(r"[\"']([^\"']+)[\"']", m.group(1)):
            base = Path(os.path.realpath(Path(source).parent / name))
            line = locate(base, table, key)
            if line:
                return base, line
            found = _locate_in_bases(base, table, key, seen + (source,))
            if found[1]:
                return found
    return None, None


class _Checker:
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
        source = self.file_of(table, key)
        where = str(source) if source else "scenario"
        short = key[len("parameters."):] if key and key.startswith("parameters.") else key
        line = locate(source, table, short)
        at = f"{where}:{line}" if line else where
        if not line and short:
            # the key may come from a scenario this one extends: name that file and line too
            base, bline = _locate_in_bases(self.source, table, short)
            if bline:
                at = f"{where} (from {base}:{bline})"
        what = f"[{table}]" + (f" {key}" if key else "")
        return SchemaError(f"{at}: {what}: {msg}")

    def table(self, table: str, data: Any, spec: Mapping[str, Callable | None]) -> None:
        if not isinstance(data, Mapping):
            raise self.fail(table, None, f"must be a table, got {_kind(data)}")
        for key, value in data.items():
            if key not in spec:
                raise self.fail(table, key, f"unknown key{_did_you_mean(key, spec)}; known: {', '.join(spec)}")
            check = spec[key]
            err = check(value) if check is not None else None
            if err:
                raise self.fail(table, key, err)


def check(data: Mapping[str, Any], source: str | Path | None = None, origins=None) -> None:
    """Raise :class:`SchemaError` for the first thing in ``data`` (a composed scenario dict) that breaks the
    schema; ``source`` is the file it came from, ``origins`` (compose.Origins) the file of the ``extends`` chain
    that brought each component, parameter, connection and input (for the message and the line)."""
    c = _Checker(source, origins)
    for name, value in data.items():
        if name not in TABLES:
            raise c.fail(name, None, f"unknown table{_did_you_mean(name, TABLES)}; known: {', '.join(TABLES)}")
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
        raise c.fail("components", None, f"must be a table of components, got {_kind(comps)}")
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
            _known_component(c, w, end, con[end], names)
    inputs = data.get("inputs", {})
    if not isinstance(inputs, Mapping):
        raise c.fail("inputs", None, f"must be a table of 'component.port' = value, got {_kind(inputs)}")
    for ref, value in inputs.items():
        # a value of the port's own type (number, boolean, string; a list for a vector port): the system checks
        # it against the port's declaration (value_types.check_value) when it is built
        err = port_ref(ref) or parameter_value(value)
        if err:
            raise c.fail("inputs", ref, err)
        _known_component(c, "inputs", ref, ref, names)
    _algorithm(c, data.get("algorithm", {}), names)
    _schedule(c, data.get("schedule", {}), comps)
    for i, ref in enumerate(data.get("outputs", {}).get("record", [])):
        _known_component(c, "outputs", "record", ref, names)
        if ref in data["outputs"]["record"][:i]:  # one dataset per signal: a second would collide in the file
            raise c.fail("outputs", "record", f"{ref!r} is listed twice")
    for key in ("level_parameter", "speed_parameter"):
        ref = data.get("results", {}).get(key)
        if ref:
            _known_component(c, "results", key, ref, names)


def _known_component(c: _Checker, table: str, key: str, ref: str, names) -> None:
    comp = ref.partition(".")[0]
    if comp not in names:
        raise c.fail(table, key, f"{ref!r}: no component {comp!r}{_did_you_mean(comp, names)}; "
                                 f"components: {', '.join(names)}")


def _component(c: _Checker, name: str, spec: Any) -> None:
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
        raise c.fail(table, "start", f"must be a table of variable = value, got {_kind(start)}")
    for key, value in start.items():
        err = parameter_value(value)
        if err:
            raise c.fail(table, f"start.{key}", err)
    params = spec.get("parameters", {})
    if not isinstance(params, Mapping):
        raise c.fail(table, "parameters", f"must be a table of name = value, got {_kind(params)}")
    for key, value in params.items():
        err = parameter_value(value)
        if err:
            raise c.fail(table, f"parameters.{key}", err)
    if impl is not None:
        _registry_parameters(c, table, impl, params)


def _registry_parameters(c: _Checker, table: str, impl: str, params: Mapping) -> None:
    """Names and kinds of the parameters against what the implementation declares."""
    from rotorcosim.components import registry

    came = c.file_of(table, None)
    try:
        # a plug-in "module:Class" imports from the folder of the file that names it
        cls = registry.lookup(impl, str(came.parent) if came else None)
    except ContractError as exc:
        raise c.fail(table, "implementation", f"{exc}{_did_you_mean(impl, registry.available())}") from None
    except (ImportError, AttributeError):  # registered but its code does not import: building it will say so
        return
    declared = {v.name: v for v in getattr(cls, "variables", ()) if v.causality == "parameter"}
    if not declared:
        return
    for key, value in params.items():
        v = declared.get(key)
        if v is None:
            raise c.fail(table, f"parameters.{key}", f"{impl} has no parameter {key!r}"
                         f"{_did_you_mean(key, declared)}; its parameters: {', '.join(declared)}")
        if v.type == "String" and not isinstance(value, str):
            raise c.fail(table, f"parameters.{key}", f"must be a string, got {_kind(value)} ({value!r})")
        if v.type == "Boolean" and not isinstance(value, bool):
            raise c.fail(table, f"parameters.{key}", f"must be true or false, got {_kind(value)} ({value!r})")
        if v.type in ("Real", "Integer") and isinstance(value, (bool, str)):
            raise c.fail(table, f"parameters.{key}", f"must be a number [{v.unit}], got {_kind(value)} ({value!r})")
        if v.type == "Integer" and _is_number(value) and value != int(value):
            raise c.fail(table, f"parameters.{key}", f"must be a whole number, got {value!r}")
    for key in getattr(cls, "required_parameters", ()):
        if key not in params:
            desc = declared[key].description if key in declared else ""
            raise c.fail(table, None, f"parameters.{key} is required by {impl} ({desc}); "
                                      f"write e.g. parameters = {{ {key} = ... }}")


def _algorithm(c: _Checker, a: Mapping, names) -> None:
    order = a.get("order")
    if order is None:
        return
    seen = set()
    for n in order:
        if n in seen:
            raise c.fail("algorithm", "order", f"component {n!r} is listed twice (it would be stepped twice)")
        seen.add(n)
        if n not in names:
            raise c.fail("algorithm", "order", f"no component {n!r}{_did_you_mean(n, names)}; "
                                               f"components: {', '.join(names)}")


def _cycle(c: _Checker, s: Mapping, comps: Mapping) -> tuple[float | None, str]:
    """The cycle source's constant period [s] (None: none, or a signal's) and how messages say it."""
    speed, cyc = s.get("speed_rpm"), s.get("cycle")
    if cyc is None:
        return (60.0 / speed if speed else None), f"at {speed:g} rev/min" if speed else ""
    if speed is not None:
        raise c.fail("schedule", "cycle", "give speed_rpm or cycle, not both (both say the cycle's period)")
    c.table("schedule.cycle", cyc, CYCLE)
    if ("period" in cyc) == ("signal" in cyc):
        raise c.fail("schedule.cycle", None, "give exactly one of period (s) or signal (\"component.port\")")
    if "period" in cyc:
        for key in ("unit", "angle"):
            if key in cyc:
                raise c.fail("schedule.cycle", key, f"is the {key} of a signal's cycle; a constant period counts "
                                                    "in seconds")
        return cyc["period"], f"of {cyc['period']:g} s"
    _known_component(c, "schedule.cycle", "signal", cyc["signal"], list(comps))
    if "angle" in cyc:
        _known_component(c, "schedule.cycle", "angle", cyc["angle"], list(comps))
    return None, ""


def _phases(c: _Checker, s: Mapping) -> Phases:
    """``[schedule.phases]``: the scenario's names of its coupled and held phases (master/core/phases.py)."""
    spec = s.get("phases", {})
    if not isinstance(spec, Mapping):
        raise c.fail("schedule", "phases", f"must be a table {{coupled = NAME, held = NAME}}, got {spec!r}")
    c.table("schedule.phases", spec, {role: text for role in ROLES})
    try:
        return Phases.from_spec(spec)
    except ContractError as exc:
        raise c.fail("schedule", "phases", str(exc)) from None


def _schedule(c: _Checker, s: Mapping, comps: Mapping) -> None:
    raw = s.get("intervals")
    tm_durations = []
    step = s.get("step", 1e-5)
    period, per = _cycle(c, s, comps)
    phases = _phases(c, s)
    if raw is not None:
        if not isinstance(raw, list) or not raw:
            raise c.fail("schedule", "intervals", "must be a non-empty list of {phase, duration} tables")
        for i, iv in enumerate(raw):
            w = f"schedule.intervals #{i + 1}"
            c.table(w, iv, INTERVAL)
            names = f"{phases.coupled!r} or {phases.held!r}"
            if "phase" not in iv:
                raise c.fail(w, "phase", f"missing: each interval needs phase = {names}")
            if iv["phase"] not in phases.names:
                raise c.fail(w, "phase", f"{iv['phase']!r} is not a phase of the scenario: {names} "
                                         "([schedule.phases])" + _did_you_mean(iv["phase"], phases.names))
            if ("duration" in iv) == ("cycles" in iv):
                raise c.fail(w, "duration", "give exactly one of duration (s) or cycles (rotor revolutions)")
            if "cycles" in iv and not period:
                raise c.fail(w, "cycles", "an interval in rotor cycles needs schedule.speed_rpm (or a cycle "
                                          "of constant period, schedule.cycle = { period = S })")
            d = iv["duration"] if "duration" in iv else iv["cycles"] * period
            if phases.role(iv["phase"]) == COUPLED:
                tm_durations.append((w, d, iv.get("step", step)))
    elif s.get("kind", "monolithic") == "monolithic" and "duration" in s:
        tm_durations.append(("schedule", s["duration"], step))
    if s.get("kind") == "auto" and "tm_min" in s:
        tm_durations.append(("schedule", s["tm_min"], step))
    speed, cycles = s.get("speed_rpm"), s.get("hold_cycles")
    if period:
        # the hold's windows, the restart and the results are counted in cycles sampled at the TM step: a
        # cycle must span two steps at least (Nyquist); 1e12 rev/min ran with windows of one sample
        h = max([step] + [hh for _, _, hh in tm_durations])
        if period < 2.0 * h:
            if speed:
                raise c.fail("schedule", "speed_rpm", f"{speed:g} rev/min turns once in {period:.3g} s, less "
                             f"than two thermo-mechanical steps ({h:g} s): no cycle can be sampled (speeds are in "
                             "rev/min)")
            raise c.fail("schedule.cycle", "period", f"{period:g} s is less than two thermo-mechanical steps "
                         f"({h:g} s): no cycle can be sampled")
    held = tm_durations
    if period and cycles and s.get("kind") == "auto":
        from rotorcosim.master.schedule.auto import AutoSchedule

        # the automatic schedule's TM intervals last at most tm_max (1e308 cycles overflowed the hold's buffers)
        held = [("schedule", s.get("tm_max", AutoSchedule.tm_max), step)]
    if period and cycles and held:
        # the hold averages the last hold_cycles cycles of a TM interval (and sizes its buffers by them): a
        # window longer than every TM interval never fills; 1e12 cycles asked for terabytes (out of memory)
        window, longest = (cycles * 60.0 / speed if speed else cycles * period), max(d for _, d, _ in held)
        if window > longest * (1 + 1e-9):
            raise c.fail("schedule", "hold_cycles", f"{cycles:g} cycles {per} last {window:.4g} s, "
                         f"longer than the longest thermo-mechanical interval ({longest:.4g} s): the hold's window "
                         "could never fill")
    _restart(c, s, raw, period, per, phases)
    for name, spec in comps.items():
        cs = spec.get("step")
        if cs is None:
            continue
        for w, d, h in tm_durations:
            if cs > d * (1 + 1e-12):
                raise c.fail(f"components.{name}", "step",
                             f"{cs} s is longer than the thermo-mechanical interval [{w}] of {d} s "
                             "(the interval would be stretched to one step of this component)")
            m = cs / h
            if m < 1 - 1e-9 or abs(m - round(m)) > 1e-6 * m:
                raise c.fail(f"components.{name}", "step",
                             f"{cs} s is not a whole multiple of the thermo-mechanical step {h} s")


def _restart(c: _Checker, s: Mapping, raw, period: float | None, per: str, phases: Phases) -> None:
    """restart_cycles against the thermo-mechanical time a restart's ramp has (master/manipulator/hold.py, Restart): it starts
    at a TO -> TM change and goes on through the TM intervals that follow, until the next TO interval. A ramp
    longer than the shortest such run never ends: the hand-backs would stay a blend of held and live values for
    the whole run. Under the automatic schedule a TM interval after a TO one lasts at
    most tm_max."""
    speed, cycles = s.get("speed_rpm"), s.get("restart_cycles")
    if not period or not cycles:
        return
    ramp = cycles * 60.0 / speed if speed else cycles * period
    runs, run, after_to = [], 0.0, False
    if isinstance(raw, list) and s.get("kind", "timeline") != "auto":
        for iv in raw:
            d = iv["duration"] if "duration" in iv else iv["cycles"] * period
            if phases.role(iv["phase"]) == HELD:
                if after_to and run > 0.0:
                    runs.append(run)
                run, after_to = 0.0, True
            elif after_to:
                run += d
        if after_to and run > 0.0:
            runs.append(run)
        what = "the shortest run of thermo-mechanical intervals after a thermal-only one"
    elif s.get("kind") == "auto":
        from rotorcosim.master.schedule.auto import AutoSchedule

        runs = [s.get("tm_max", AutoSchedule.tm_max)]
        what = "tm_max, the longest thermo-mechanical interval of the automatic schedule"
    if runs and ramp > min(runs) * (1 + 1e-9):
        raise c.fail("schedule", "restart_cycles", f"{cycles:g} cycles {per} last {ramp:.4g} s, "
                     f"longer than {what} ({min(runs):.4g} s): the restart's ramp would never end (the default is "
                     f"{RESTART_CYCLES:g} cycles)")
