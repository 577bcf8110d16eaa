"""Scenarios: TOML files naming the components, their parameters, the connections, the schedule and outputs.

::

    [scenario]
    name = "two masses"
    unconnected_inputs = "start"         # an input nothing drives keeps the start value it declares (an FMU's
                                         # inputs; a native one only if it declares a default); "error": refused

    [components.m1]
    implementation = "testing.mass"      # a registry name, or: fmu = "path/to/model.fmu"
    step = 1e-3                          # optional communication step (a whole multiple of the interval step)
    parameters = { m = 1.0, k = 4.0 }
    start = { "x" = 0.1 }                # FMUs only: start values of states / initial = "exact" variables

    [[connections]]
    from = "m1.x"
    to = "m2.x_in"                       # optional: average = "mean"|"rms"|"last", extrapolation = "hold"|"linear"|"linear-end",
                                         # hold = "rms"|"mean"|"last" (thermal-only substitute),
                                         # convert = "round"|... (type conversion), unit = "mm" (unit of a
                                         # unit-less side): see master/core/conversions.py
    [inputs]
    "m1.F_ext" = 0.0                     # constant inputs

    [algorithm]
    kind = "gauss-seidel"                # or "jacobi"
    order = ["m1", "m2"]
    iterations = 1
    tolerance = 1e-10

    [schedule]                           # see master/schedule/timeline.py: timeline | monolithic | auto
    kind = "monolithic"
    duration = 1.0
    step = 1e-3
    speed_rpm = 16000                    # the cycle of the thermal-only holds and the automatic schedule: a
                                         # constant speed, or cycle = { period = S } | { signal = "comp.port" }
                                         # (master/scenario/cycle.py)
    hold = "mean"                        # held statistic of the hand-offs (mean | rms | last), master/manipulator/handoff.py
    hold_cycles = 5
    restart_cycles = 2                   # TM restart: rotor cycles over which the thermal inputs of the
                                         # mechanical components go from their pre-TO to their new values

    [outputs]
    record = ["m1.x", "m2.x"]
    record_step = 1e-3
    format = "h5"                        # or "csv"

A scenario may start from another one: ``[scenario] extends = "base.toml"`` (relative to the file). The
composition rules (an ``implementation`` replaces an inherited ``fmu`` and the other way round,
``remove_parameters``, connections added to the inherited ones, ``remove_connections``) are in
:mod:`rotorcosim.master.scenario.compose`; errors found after composition name the file that brought the entry.

An implementation may also be a plug-in class written ``"module:Class"``: the module is imported from the
folder of the scenario file that names it first, then from ``sys.path`` (no packaging needed; docs/how-to/plugins.md).

Relative paths (FMU files, model files) are resolved against the scenario file's folder. Everything SI;
quantities at the edges carry their unit in the key name (``speed_rpm``).
"""
from __future__ import annotations

import copy
import math
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Mapping

from rotorcosim.components import registry
from rotorcosim.components.contract import Component, ContractError

from rotorcosim.master.scenario import engine as engine_binding
from rotorcosim.master.scenario import schema
from rotorcosim.master.scenario.cycle import constant_period, cycle_of, without_source
from rotorcosim.master.core.algorithm import EngineSettings
from rotorcosim.master.manipulator.hold import DEFAULT_HOLD
from rotorcosim.master.manipulator.restart import RESTART_CYCLES
from rotorcosim.master.scenario.compose import Origins, ScenarioError, compose, real_path
from rotorcosim.master.scenario.overrides import resolve_file_parameters
from rotorcosim.master.schedule.timeline import from_spec, phases_of
from rotorcosim.master.simulation import Simulation
from rotorcosim.master.core.system import Connection, System, defaulted_line, split_port

@dataclass
class ComponentSpec:
    """One ``[components.NAME]`` table: ``name``, its ``implementation`` (a registry name or ``"module:Class"``)
    or its ``fmu`` file, its ``parameters`` (SI), its communication ``step`` [s] (None: the interval's), and for
    FMUs the ``start`` values and ``options``; ``origin``, ``folder``, ``param_origins`` and ``fmu_label`` say
    where each came from, for messages and plug-in imports."""
    name: str
    implementation: str | None = None
    fmu: str | None = None
    parameters: dict[str, Any] = field(default_factory=dict)
    step: float | None = None
    #: start values of an FMU's states and other ``initial = "exact"`` variables (fmpy's ``start_values``)
    start: dict[str, Any] = field(default_factory=dict)
    #: FMU options: ``process`` (run it in a process of its own), ``step_timeout`` (s, implies ``process``)
    options: dict[str, Any] = field(default_factory=dict)
    #: the file that chose the implementation (for error messages) and the folder plug-ins import from
    origin: str | None = None
    folder: str | None = None
    param_origins: dict[str, str] = field(default_factory=dict)
    #: how messages name the FMU file when ``fmu`` is a temporary extraction (an SSP archive's entry)
    fmu_label: str | None = None


@dataclass
class Scenario:
    """A scenario: what to simulate, as read from its TOML file (or an SSP archive), not yet built.

    Parameters: ``name``; ``components`` (name -> :class:`ComponentSpec`); ``connections``
    (:class:`~rotorcosim.master.core.system.Connection`); ``inputs`` (``"component.port"`` -> constant value, SI); ``algorithm``,
    ``schedule`` and ``outputs``: the ``[algorithm]``, ``[schedule]`` and ``[outputs]`` tables as dicts;
    ``source``: the file it was read from (relative paths resolve against its folder); ``description``;
    ``extra``: the other top-level tables (``[results]``, read by the scenario's case); ``loaded_name``: the
    name it was loaded under (``name`` may change: setting the level renames a run); ``edits``: each change
    made since it was loaded, in order (``{"set": "comp.param", "value": ...}``, ``{"swap": "comp",
    "implementation": ...}``, ``{<level name>: value, "parameter": "comp.param"}`` (the level, named by its case: master/case.py), each
    with its ``origin``),
    which a run records in its summary (master/run/provenance.py); ``unconnected_inputs``:
    ``"start"`` (an input nothing drives keeps the start value it declares) or ``"error"`` (refused); ``engine``:
    the engine file the scenario takes the machine from and the parameters bound to its quantities
    (:class:`~rotorcosim.master.scenario.engine.EngineBinding`; None: no engine).

    :meth:`set` and :meth:`swap` return changed copies; :func:`build_system` and :func:`build_simulation` make
    it runnable; :func:`rotorcosim.simulate` runs it.

    >>> import rotorcosim
    >>> sc = rotorcosim.load_scenario("toy_thermomechanical")      # a shipped name, a TOML file or an .ssp
    >>> sc.name, sorted(sc.components)
    ('toy_thermomechanical', ['node', 'osc'])
    >>> heavier = sc.set({"node.C": 20.0})                           # heat capacity [J/K]; sc is unchanged
    >>> heavier.components["node"].parameters["C"], sc.components["node"].parameters["C"]
    (20.0, 10.0)
    """
    name: str
    components: dict[str, ComponentSpec]
    connections: list[Connection]
    inputs: dict[str, list[float]] = field(default_factory=dict)
    algorithm: dict = field(default_factory=dict)
    schedule: dict = field(default_factory=dict)
    outputs: dict = field(default_factory=dict)
    source: Path | None = None
    description: str = ""
    extra: dict = field(default_factory=dict)
    unconnected_inputs: str = "start"
    loaded_name: str | None = None
    edits: list[dict] = field(default_factory=list)
    #: the engine file and what the scenario takes from it (master/scenario/engine.py), or None
    engine: Any = None

    def __post_init__(self):
        if self.loaded_name is None:
            self.loaded_name = self.name

    def copy(self) -> "Scenario":
        """A deep copy: changing it leaves this scenario as it is."""
        return copy.deepcopy(self)

    def set(self, values: Mapping[str, Any]) -> "Scenario":
        """A new scenario with component parameters changed: ``sc.set({"osc.F0": 20.0})``.

        Keys are ``"component.parameter"`` (SI values; numbers, booleans, strings or lists). This scenario is
        left unchanged. An unknown component, or a parameter the component's implementation does not declare,
        is an error naming both."""
        from rotorcosim.master.scenario.overrides import apply_set

        return apply_set(self, values)

    def swap(self, component: str, implementation: str, parameters: Mapping[str, Any] | None = None) -> "Scenario":
        """A new scenario with ``component`` given another implementation: a registry name (``"damper.fe"``),
        a plug-in ``"module:Class"`` (its module imported from the working folder first, then from ``sys.path``),
        or an FMU file (``"my_damper.fmu"``, relative to the working folder).

        The component keeps its parameters unless ``parameters`` is given, which then replaces them all."""
        from rotorcosim.master.scenario.overrides import apply_swap

        return apply_swap(self, component, implementation, parameters)

    def parameters(self, component: str | None = None) -> list[dict]:
        """Every parameter of the components (or of ``component``): dicts with ``component``, ``name``,
        ``unit``, ``default``, ``value`` (what a run uses, after the component's set-up), ``source`` (the file
        that set it, "default" or "set-up") and ``description``. Example:
        ``rotorcosim.load_scenario("toy_thermomechanical").parameters("osc")``."""
        from rotorcosim.master.scenario.parameters import scenario_parameters

        return scenario_parameters(self, component)


_TOP_KEYS = {"scenario", "components", "connections", "inputs", "algorithm", "schedule", "outputs", "results"}
_COMPONENT_KEYS = {"implementation", "fmu", "parameters", "step", "start", "process", "step_timeout"}
_CONNECTION_KEYS = {"from", "to", "average", "extrapolation", "hold", "convert", "unit"}


def _fail(where: str, msg: str) -> ScenarioError:
    return ScenarioError(f"{where}: {msg}")


def _check_value(where: str, value: Any) -> None:
    if isinstance(value, bool) or isinstance(value, str):
        return
    if isinstance(value, (int, float)):
        if not math.isfinite(value):
            raise _fail(where, f"value {value!r} is not finite")
        return
    if isinstance(value, list):
        for v in value:
            _check_value(where, v)
        return
    raise _fail(where, f"unsupported value {value!r}")


def parse(data: Mapping[str, Any], source: Path | None = None, origins: Origins | None = None) -> Scenario:
    """A scenario from its (composed) dict; the strict schema (schema.py) is checked first. ``origins`` (from
    :func:`compose`) names the file of each entry in the messages (else ``source``)."""
    origins = origins or Origins()
    schema.check(data, source, origins)
    where = str(source) if source else "scenario"
    unknown = set(data) - _TOP_KEYS
    if unknown:
        raise _fail(where, f"unknown table(s) {sorted(unknown)}; known: {sorted(_TOP_KEYS)}")
    head = data.get("scenario", {})
    comps_raw = data.get("components")
    if not comps_raw:
        raise _fail(where, "no [components]")
    base = source.parent if source else Path.cwd()
    components = {}
    for name, spec in comps_raw.items():
        w = f"{origins.component(name) or where}: [components.{name}]"
        if not isinstance(spec, Mapping):
            raise _fail(w, "must be a table")
        if "." in name or not name:
            raise _fail(w, "component names must be non-empty and contain no '.'")
        bad = set(spec) - _COMPONENT_KEYS
        if bad:
            raise _fail(w, f"unknown key(s) {sorted(bad)}; known: {sorted(_COMPONENT_KEYS)}")
        impl, fmu = spec.get("implementation"), spec.get("fmu")
        if (impl is None) == (fmu is None):
            raise _fail(w, "give exactly one of 'implementation' (a registry name) or 'fmu' (a file)")
        if fmu is not None:
            fmu = str(real_path(base / fmu)) if not Path(fmu).is_absolute() else fmu
        params = dict(spec.get("parameters", {}))
        for k, v in params.items():
            _check_value(f"{w} parameter {k}", v)
        step = spec.get("step")
        if step is not None:
            _check_value(f"{w} step", step)
            if not isinstance(step, (int, float)) or step <= 0:
                raise _fail(w, f"step must be a positive number, got {step!r}")
        start = dict(spec.get("start", {}))
        for k, v in start.items():
            _check_value(f"{w} start {k}", v)
        if start and fmu is None:
            raise _fail(w, "'start' sets start values of an FMU's variables; a native component takes its "
                           "initial state from its parameters")
        options = {k: spec[k] for k in ("process", "step_timeout") if k in spec}
        came = origins.component(name)
        if impl is not None:
            def folder_of(p: str, name=name) -> Path:  # the folder of the file that wrote the parameter
                wrote = origins.parameter(name, p)
                return Path(wrote).parent if wrote else base

            resolve_file_parameters(impl, params, folder_of, str(Path(came).parent if came else base))
        components[name] = ComponentSpec(name, impl, fmu, params, None if step is None else float(step), start,
                                         options, origin=came or (str(source) if source else None),
                                         folder=str(Path(came).parent if came else base),
                                         param_origins={p: origins.parameter(name, p) or where for p in params})
    connections = []
    for i, spec in enumerate(data.get("connections", [])):
        came = origins.connections[i] if i < len(origins.connections) else where
        w = f"{came}: connection #{i + 1}"
        bad = set(spec) - _CONNECTION_KEYS
        if bad:
            raise _fail(w, f"unknown key(s) {sorted(bad)}; known: {sorted(_CONNECTION_KEYS)}")
        if "from" not in spec or "to" not in spec:
            raise _fail(w, "needs 'from' and 'to'")
        split_port(spec["from"]), split_port(spec["to"])
        for key in ("convert", "unit"):
            if key in spec and not isinstance(spec[key], str):
                raise _fail(w, f"{key} must be a string, got {spec[key]!r}")
        connections.append(Connection(spec["from"], spec["to"], spec.get("average", "mean"),
                                      spec.get("extrapolation", "hold"), spec.get("hold"),
                                      spec.get("convert"), spec.get("unit"), origin=came))
    inputs = {}
    for ref, value in data.get("inputs", {}).items():
        split_port(ref)
        _check_value(f"{where}: [inputs] {ref}", value)
        inputs[ref] = list(value) if isinstance(value, list) else [value]
    return Scenario(name=head.get("name", source.stem if source else "scenario"), components=components,
                    connections=connections, inputs=inputs, algorithm=dict(data.get("algorithm", {})),
                    schedule=dict(data.get("schedule", {})), outputs=dict(data.get("outputs", {})),
                    source=source, description=head.get("description", ""),
                    extra={"results": dict(data.get("results", {}))},
                    unconnected_inputs=head.get("unconnected_inputs", "start"))


def load_scenario(path: str | Path) -> Scenario:
    """The scenario file ``path`` (its ``extends`` chain composed). For shipped names see
    :func:`rotorcosim.load_scenario`."""
    path = real_path(path)
    data, origins = compose(path)
    binding = engine_binding.bind(data, origins, str(path))
    sc = parse(data, path, origins)
    sc.engine = binding
    return sc


def create_component(spec: ComponentSpec) -> Component:
    """The component ``spec`` names; a bad implementation or parameter is an error naming the file that
    chose it."""
    where = f"{spec.origin}: " if spec.origin else ""
    if spec.fmu is not None:
        if spec.options.get("process") or "step_timeout" in spec.options:
            from rotorcosim.fmus.process import STEP_TIMEOUT_S, ProcessFMU

            return ProcessFMU(spec.fmu, spec.name, spec.parameters, spec.options.get("step_timeout", STEP_TIMEOUT_S),
                              start=spec.start, label=spec.fmu_label)
        from rotorcosim.fmus.importer import load_fmu_component

        return load_fmu_component(spec.fmu, spec.name, spec.parameters, spec.start, spec.fmu_label)
    cls = None
    try:
        cls = registry.lookup(spec.implementation, spec.folder)
        return cls(spec.name, spec.parameters or {})
    except ContractError as exc:
        bad = [p for p in spec.parameters if f"{p!r}" in str(exc) and spec.param_origins.get(p)]
        if bad and spec.param_origins[bad[0]] != spec.origin:
            where = f"{spec.param_origins[bad[0]]}: "  # the file that set the offending parameter
        raise ScenarioError(f"{where}[components.{spec.name}]: {exc}") from None
    except Exception as exc:
        if cls is None or not registry.is_plugin_class(cls):
            raise
        raise ScenarioError(f"{where}[components.{spec.name}]: plug-in {spec.implementation!r} could not be made: "
                            f"{type(exc).__name__}: {exc}") from None


def build_system(sc: Scenario) -> System:
    """The :class:`System` of ``sc``: its components created (FMUs loaded) and its connections checked. A
    problem is a ScenarioError naming the file that brought it; the components made before it are terminated.
    Inputs left unconnected that keep their start values (``[scenario] unconnected_inputs = "start"``) are
    listed in one line on stderr."""
    comps = {}
    try:
        for name, spec in sc.components.items():
            comps[name] = create_component(spec)
        cons = [replace(c) for c in sc.connections]   # the system's own copies
        system = System(comps, cons, {k: v for k, v in sc.inputs.items()},
                        origins={n: c.origin for n, c in sc.components.items() if c.origin},
                        unconnected_inputs=sc.unconnected_inputs)
        check_speeds(system)
    except BaseException as exc:
        # the components made so far are let go now: an FMU's process or extraction folder is not left to the
        # garbage collector (a system refused for its units kept an FMU's child process running until then)
        for comp in comps.values():
            try:
                comp.terminate()
            except Exception:  # noqa: BLE001 - the error being raised is the one to report
                pass
        if not isinstance(exc, ContractError):
            raise
        # the file the problem is in, unless the message names one already (the composed file that brought it)
        named = {str(sc.source)} | {c.origin for c in sc.components.values() if c.origin} \
            | {c.origin for c in sc.connections if c.origin}
        if sc.source and not any(f and f in str(exc) for f in named):
            raise ScenarioError(f"{sc.source}: {exc}") from None
        raise
    if system.defaulted:
        # the other tools run such an FMU silently; a forgotten connection must still be seen
        print(f"{sc.name}: {defaulted_line(system.defaulted)} ([scenario] unconnected_inputs = \"error\" refuses "
              "them)", file=sys.stderr)
    return system


def check_speeds(system: System) -> None:
    """Refuse a part whose own fixed speed (its class's ``fixed_speed`` parameter: a constant-speed bearing's,
    rub ring's or thermal network's ``omega``) is not the speed of the rotor node it is linked to (the rotor's
    ``port_speeds``: its spool's speed parameter), or of the part whose input it follows (``speed_follows``: a
    thermal network takes its bearing's drag power, which turns at the bearing's speed). Such a run computed the
    part at one speed and the rotor at another without a word. A part that takes its speed as an input (a
    speed-following variant) declares no fixed speed and is not checked."""
    comps = system.components

    def fixed(name: str) -> float | None:
        param = getattr(comps[name], "fixed_speed", None)
        return comps[name].p.get(param) if param else None

    def agree(name: str, ref: str, speed: float, link: str, change: str) -> None:
        own = fixed(name)
        if own is not None and not math.isclose(own, speed, rel_tol=1e-9):
            raise ContractError(
                f"{name}.{comps[name].fixed_speed} = {own:.6g} rad/s is not the speed of what it is linked to "
                f"({link}): {ref} = {speed:.6g} rad/s; give them one speed (drop {name}'s own value where an engine "
                f"gives the speed, or change both with --set {change}=...)")

    for con in system.connections:
        speeds = getattr(comps[con.src_component], "port_speeds", None)
        at = speeds().get(split_port(con.src)[1]) if speeds is not None else None
        if at is not None:
            ref = f"{con.src_component}.{at[0]}"
            agree(con.dst_component, ref, at[1], f"{con.src} -> {con.dst}", ref)
    for con in system.connections:
        follows = getattr(comps[con.dst_component], "speed_follows", None)
        if follows and split_port(con.dst)[1] == follows and fixed(con.src_component) is not None:
            ref = f"{con.src_component}.{comps[con.src_component].fixed_speed}"
            agree(con.dst_component, ref, fixed(con.src_component), f"{con.src} -> {con.dst}", ref)


def engine_settings(sc: Scenario) -> EngineSettings:
    """The coupling algorithm of ``sc``'s ``[algorithm]`` table (kind, iterations, tolerance)."""
    a = sc.algorithm
    bad = set(a) - {"kind", "order", "iterations", "tolerance"}
    if bad:
        raise ScenarioError(f"[algorithm]: unknown key(s) {sorted(bad)}")
    return EngineSettings(a.get("kind", "gauss-seidel"), int(a.get("iterations", 1)), float(a.get("tolerance", 1e-10)))


def build_simulation(sc: Scenario, observers=(), system: System | None = None) -> Simulation:
    """A :class:`Simulation` of ``sc``, ready to run a schedule (:func:`schedule_of`).

    ``observers``: what watches the run (recorders, progress ...); ``system``: an already built system of ``sc``
    (default: :func:`build_system`)."""
    system = system or build_system(sc)
    s = sc.schedule
    cycle = cycle_of(s)
    if cycle is not None:
        try:
            cycle.check(system)
        except ContractError as exc:
            raise ScenarioError(f"{sc.source or sc.name}: [schedule] cycle: {exc}") from None
    # the automatic schedule's steadiness test reads them only once an interval has room for it: checked here, so
    # that a wrong name is refused whatever the duration
    for ref in s.get("tracked", ()):
        try:
            system.port(ref, "output")
        except ContractError as exc:
            raise ScenarioError(f"{sc.source or sc.name}: [schedule] tracked: {exc}") from None
    return Simulation(system, order=sc.algorithm.get("order"), settings=engine_settings(sc),
                      steps={n: c.step for n, c in sc.components.items() if c.step is not None},
                      hold=s.get("hold", DEFAULT_HOLD), hold_cycles=float(s.get("hold_cycles", 5)),
                      cycle=cycle, observers=observers,
                      restart_cycles=float(s.get("restart_cycles", RESTART_CYCLES)),
                      phases=phases_of(s))


def schedule_of(sc: Scenario, kind: str | None = None, duration: float | None = None):
    """The schedule of ``sc`` (a Timeline, Monolithic or AutoSchedule). ``kind`` replaces its ``[schedule]
    kind`` ("monolithic", "auto"; the same simulated time as the scenario's timeline unless ``duration`` [s]
    says otherwise); ``duration`` cuts or sets the simulated time."""
    own, period = without_source(sc.schedule), constant_period(sc.schedule)
    spec = dict(own)
    if kind is not None:
        spec["kind"] = kind
        if kind in ("monolithic", "auto"):
            spec.pop("intervals", None)
            # the same simulated time as the scenario's own timeline, unless told otherwise
            if duration is None and "duration" not in spec and sc.schedule.get("intervals"):
                duration = from_spec(own, cycle=period).duration
    return from_spec(spec, duration, cycle=period)
