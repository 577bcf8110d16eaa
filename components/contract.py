"""The component contract: what every component, native or imported FMU, offers the master.

Modelled on FMI 2.0 co-simulation (and on fmpy's flat model description):

* declared variables (:class:`Variable`): name, causality (parameter / input / output), vector size,
  SI unit, description and start value;
* ``setup(t0)`` (enter/exit initialisation), ``set_inputs``, ``do_step(t, h)``, ``get_outputs``, ``terminate``;
* ``get_state`` / ``set_state``: a full snapshot (FMI getFMUstate / setFMUstate), used for rollback and by
  the staggered schedule;
* a preferred communication step and the phases it takes part in, named by their role: ``COUPLED``
  (``"TM"``: every component steps, the thermo-mechanical phase of a staggered scheme) and ``HELD`` (``"TO"``:
  only the components that declare it step, the master holds the others' outputs: thermal-only). A scenario may
  call its phases otherwise (master/core/phases.py); a component speaks of them by these roles.

A component owns its internal integration and never reaches into another component.
"""
from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import Any, Iterable, Mapping

import numpy as np

from .errors import ContractError, StopRequested
from .value_types import KINDS, UNCARRIED, check_value, dtype_of

CAUSALITIES = ("parameter", "input", "output")
TYPES = KINDS
#: the roles of the two phases a component can take part in (see the module docstring)
COUPLED, HELD = "TM", "TO"
PHASES = (COUPLED, HELD)


@dataclass(frozen=True)
class Variable:
    """One declared variable. Ports are vectors of ``size`` values of one kind (value_types.py): Real for every
    native port; imported FMUs also have Integer, Boolean, String (and uncarried Binary / Clock) ports.

    ``fmi_type`` is the FMI type it came from (``"Float32"``, ``"Int8"``, ``"Enumeration"``...; ``""`` for native
    variables), ``min``/``max`` its declared range, ``choices`` an enumeration's item values, ``unit_definition``
    its unit as ``(base-unit exponents, factor, offset)`` when the FMU defines it (else the unit string is parsed,
    fmus/units.py). ``has_default``: an input that may stay unconnected, keeping its ``start`` value (an imported
    FMU's input with a declared start; a native input only when its component declares it so: the others must be
    connected or given a constant)."""

    name: str
    causality: str
    size: int = 1
    unit: str = "1"
    description: str = ""
    start: Any = 0.0
    type: str = "Real"
    fmi_type: str = ""
    min: float | None = None
    max: float | None = None
    choices: tuple | None = None
    unit_definition: tuple | None = None
    #: names of a vector's elements (``("inner", "outer")``); by default x, y(, z) for a 2- or 3-vector of a
    #: displacement, velocity or force, else 1..size (see :meth:`column_labels`)
    labels: tuple[str, ...] = ()
    has_default: bool = False
    #: a parameter's plausible values (SI), ``(low, high)``: a value outside is legal but likely a unit slip (an
    #: O-ring given in N/mm where N/m is meant), which a run warns about (components/plausibility.py); unlike
    #: ``min``/``max``, which are hard limits
    plausible: tuple[float, float] | None = None
    #: a parameter that is the time of an event (``"the fuel cut"``): set at or after the end of a run, the event
    #: never happens in it, which the run warns about (components/plausibility.py); a negative time means never
    event: str | None = None

    def __post_init__(self):
        if self.causality not in CAUSALITIES:
            raise ContractError(f"variable {self.name!r}: causality {self.causality!r} not in {CAUSALITIES}")
        if self.type not in TYPES:
            raise ContractError(f"variable {self.name!r}: type {self.type!r} not in {TYPES}")
        if int(self.size) < 1:
            raise ContractError(f"variable {self.name!r}: size must be >= 1, got {self.size}")
        if self.labels and len(self.labels) != int(self.size):
            raise ContractError(f"variable {self.name!r}: {len(self.labels)} labels for size {self.size}")

    @property
    def carried(self) -> bool:
        """False for Binary and Clock variables: declared, but holding no value the master can pass on."""
        return self.type not in UNCARRIED

    def column_labels(self) -> list[str]:
        """One label per element: the declared ``labels``; x, y(, z) for a 2-/3-vector in m, m/s or N; else
        1..size ("" for a scalar)."""
        if self.labels:
            return list(self.labels)
        if self.size == 1:
            return [""]
        if self.size in (2, 3) and self.unit in ("m", "m/s", "N"):
            return list("xyz"[: self.size])
        return [str(i + 1) for i in range(self.size)]

    def start_array(self) -> np.ndarray:
        """The start value as a vector of ``size`` of the variable's kind (a scalar start is broadcast)."""
        dtype = dtype_of(self.type, self.fmi_type)
        if dtype is object:
            start = self.start if isinstance(self.start, (list, tuple)) else [self.start] * self.size
            return np.array(list(start), dtype=object)
        return np.broadcast_to(np.asarray(self.start, dtype=dtype), (self.size,)).copy()


def check_finite(name: str, value: np.ndarray) -> None:
    if not np.all(np.isfinite(value)):
        raise ContractError(f"{name}: value is not finite ({value})")


def output_problem(comp: "Component") -> str | None:
    """What is wrong with the first output of ``comp`` that is not what the contract makes it (a numpy array of
    its declared size), or None: a plug-in that writes a list, or three values into a port of two, made the
    readers fail far from it (numba's typing error in another component, numpy's broadcast message)."""
    for v in comp.variables:
        if v.causality != "output" or not v.carried:
            continue
        a = comp.y.get(v.name)
        if not isinstance(a, np.ndarray) or a.size != v.size:
            got = f"{a.size} value(s)" if isinstance(a, np.ndarray) else f"a {type(a).__name__} ({a!r:.40})"
            return f"{comp.name}.{v.name} must be a numpy array of {v.size} value(s), got {got}"
    return None


class Component:
    """Base class of native components.

    Subclasses declare ``variables`` (a tuple of :class:`Variable`), override :meth:`do_step`, and keep
    everything that evolves in time in ``self.state`` (a dict of numpy arrays / floats) so that the default
    :meth:`get_state` / :meth:`set_state` capture it. Parameters arrive in the constructor in SI units and are
    available as ``self.p[name]`` (floats for scalar Real parameters, arrays for vectors, str for String).
    Inputs are in ``self.u[name]`` (float arrays), outputs are written to ``self.y[name]``.
    """

    variables: tuple[Variable, ...] = ()
    preferred_step: float = 1e-4
    phases: frozenset[str] = frozenset({"TM"})
    #: True for a component that takes part in thermal-only (TO) intervals only for its TO update: in its TO phase
    #: (:meth:`enter_phase`) ``do_step`` recomputes, from its frozen mechanical state and its present thermal
    #: inputs, the outputs it hands to thermal components (the bearing's drag at the oil viscosity, the damper's
    #: film power), and changes nothing else. The master treats it as mechanical (master/manipulator/hold.py: its inputs from
    #: frozen components are held at their last value, and the held window of each of those outputs follows its
    #: TO update). It keeps no window or average of its own: those are the master's.
    holds_state_in_TO: bool = False
    #: True for a component whose set-up reads its inputs (FMI: initial values that depend on inputs): before its
    #: :meth:`setup` the master hands it the outputs of the components set up before it in the run's order (the
    #: spinning rotor starts on the synchronous orbit of its spool's start speed). False: inputs at set-up are the
    #: scenario's constants and the start values only
    inputs_at_setup: bool = False
    #: parameters a scenario must give: no default is right for all uses (the bearing, damper or ring number
    #: picks that one's Table 3 data; a forgotten ``bearing = 5`` must not silently give bearing #0's)
    required_parameters: tuple[str, ...] = ()
    #: String parameters that name a file: a relative path a scenario gives is read from the folder of the scenario
    #: file that wrote it, as an ``fmu = ...`` path is (it was read from the working folder: another folder's file
    #: of that name was used without a word)
    file_parameters: tuple[str, ...] = ()
    #: names of the component's event indicators (FMI 3.0): real functions of its state and inputs, given after
    #: each step by :meth:`indicators`, whose change of sign is an event that the master locates in time
    #: (master/core/events.py) and hands to :meth:`update_discrete`; empty: none, and the master never asks
    event_indicators: tuple[str, ...] = ()
    #: True for a component whose own steps apply its time events (:meth:`next_event`) at their time, to within its
    #: step (the rotor's blade release: the unbalance force from the end of the step that holds it): inside a
    #: coupled interval the master runs its steps as they are (no step split there, no record); a held interval
    #: still ends at it, and the event is recorded there. False: the master splits the coupled base step that
    #: holds one and records it (master/core/events.py)
    time_events_in_steps: bool = False
    #: short description shown by ``rotorcosim`` and written to exported FMUs
    description: str = ""
    #: what the component costs, for the estimate of a run's wall time before it starts
    #: (master/schedule/budget.py), in CPU seconds of one core of a 2-core x86 machine of 2025 (measured with
    #: ``python bench/bench_estimate.py``): one ``do_step`` in the generic Python loop, one step of its kernel in
    #: the compiled loop (components with a kernel), and its set-up in a fresh process (model reduction, kernels
    #: and tables loaded from the disk caches)
    step_cost_s: float = 30e-6
    kernel_step_cost_s: float = 5e-6
    setup_cost_s: float = 0.0

    def __init__(self, name: str = "component", parameters: Mapping[str, Any] | None = None):
        self.name = name
        self._by_name = {v.name: v for v in self.variables}
        if len(self._by_name) != len(self.variables):
            raise ContractError(f"{type(self).__name__}: duplicate variable names")
        self.p: dict[str, Any] = {}
        #: names of the parameters set by the user (constructor or set_parameter), not left at their start
        #: value: a component whose defaults depend on another parameter (the bearing/damper/ring number picks
        #: the Table 3 data) fills in only the ones not in here
        self.explicit: set[str] = set()
        for v in self.variables:
            if v.causality == "parameter":
                self.p[v.name] = self._coerce_parameter(v, v.start)
        for key, value in (parameters or {}).items():
            self.set_parameter(key, value)
        self.u = {v.name: v.start_array() for v in self.variables if v.causality == "input" and v.carried}
        self.y = {v.name: v.start_array() for v in self.variables if v.causality == "output" and v.carried}
        self.state: dict[str, Any] = {}
        self.time = 0.0

    # -- declarations -------------------------------------------------------------------------------
    @classmethod
    def step_cost(cls, parameters: Mapping[str, Any], compiled: bool) -> float:
        """CPU seconds of one step with ``parameters`` (those a scenario gives; the rest at their defaults), in
        the compiled loop or the Python one: :attr:`kernel_step_cost_s` or :attr:`step_cost_s`, unless a
        component's cost follows its parameters (the FE damper's mesh)."""
        return cls.kernel_step_cost_s if compiled else cls.step_cost_s

    @classmethod
    def declared(cls, causality: str) -> list[Variable]:
        return [v for v in cls.variables if v.causality == causality]

    def variable(self, name: str) -> Variable:
        try:
            return self._by_name[name]
        except KeyError:
            known = ", ".join(sorted(self._by_name))
            raise ContractError(f"{self.name}: no variable {name!r} (known: {known})") from None

    # -- parameters ---------------------------------------------------------------------------------
    def _coerce_parameter(self, v: Variable, value: Any) -> Any:
        """``value`` checked against ``v``'s kind and range (value_types.check_value): a scalar for size 1."""
        arr = check_value(v, value, f"{self.name}.{v.name}")
        if v.size == 1:
            return arr[0].item() if isinstance(arr[0], np.generic) else arr[0]
        return arr

    def set_parameter(self, name: str, value: Any) -> None:
        v = self.variable(name)
        if v.causality != "parameter":
            raise ContractError(f"{self.name}.{name} is an {v.causality}, not a parameter")
        self.p[name] = self._coerce_parameter(v, value)
        self.explicit.add(name)

    # -- the co-simulation calls --------------------------------------------------------------------
    def setup(self, t0: float = 0.0) -> None:
        """Initialise from the parameters (FMI enter/exit initialisation mode). Subclasses extend."""
        self.time = float(t0)

    def prebuild(self) -> list:
        """What :meth:`setup` and the first steps will build that depends on the parameters only and is kept in
        an on-disk cache (a compiled kernel, a table): a list of ``(key, function, args)``, run by a helper process
        on a fresh machine while this one sets up (master/compiled/ahead.py). ``function`` is a module-level function
        called with ``args`` (``key`` names its result for both processes: its builder here waits for it through
        components/cache.await_ahead), or a numba dispatcher compiled for the signature ``args`` (``key`` None).
        Nothing by default; an invalid parameter gives nothing here (setup names it)."""
        return []

    def set_inputs(self, values: Mapping[str, Any]) -> None:
        for key, value in values.items():
            v = self._by_name.get(key)
            if v is None or v.causality != "input":
                raise ContractError(f"{self.name}: no input {key!r}")
            if v.type == "Real" and type(value) is np.ndarray and value.ndim == 1 and value.dtype == np.float64:
                arr = value     # already what the line below makes (and shares its data the same way), faster
            else:
                arr = np.asarray(value, dtype=float if v.type == "Real" else dtype_of(v.type, v.fmi_type)).reshape(-1)
            if arr.size != v.size:
                raise ContractError(f"{self.name}.{key}: expected {v.size} value(s), got {arr.size}")
            self.u[key] = arr

    def do_step(self, t: float, h: float) -> None:
        """Advance from ``t`` to ``t + h`` with the inputs held; update ``self.y``."""
        raise NotImplementedError

    def get_outputs(self) -> dict[str, np.ndarray]:
        return self.y

    def terminate(self) -> None:
        pass

    def get_state(self) -> Any:
        return _copy_snapshot((self.time, self.state, self.u, self.y))

    def set_state(self, snapshot: Any) -> None:
        self.time, self.state, self.u, self.y = _copy_snapshot(snapshot)

    def restore_state(self, snapshot: Any) -> None:
        """:meth:`set_state` from a snapshot of :meth:`get_state` that the caller gives up (it never uses it
        again): taken as it is where this class keeps the base snapshot, without set_state's copy. For a trial
        step undone thousands of times (the error estimate's replay)."""
        if type(self).set_state is Component.set_state and type(self).get_state is Component.get_state:
            self.time, self.state, self.u, self.y = snapshot
        else:
            self.set_state(snapshot)

    def enter_phase(self, phase: str) -> None:
        """Called by the master at the start of every interval with its phase's role (``COUPLED`` or ``HELD``), for
        every component, stepped or frozen. Components that behave differently in thermal-only intervals
        (``holds_state_in_TO``) override it."""
        self.phase = phase

    def next_event(self, t: float) -> float | None:
        """The time of this component's next scheduled change of behaviour at or after ``t`` [s] (the spool's fuel
        cut, the rotor's blade release), or None. A held-phase interval ends there (the automatic schedule's and a
        timeline's), so that the change happens in a coupled interval (:attr:`time_events_in_steps`: where it is
        recorded). None by default."""
        return None

    def indicators(self) -> np.ndarray:
        """The values of the event indicators (one per name of :attr:`event_indicators`) after the last step or
        :meth:`update_discrete`. A change of sign of one of them over a step is an event. An empty array: none of
        them can change sign any more (a broken fuse); while no component has a live indicator, the master saves
        no state before a step."""
        return np.zeros(0)

    def event_tolerance(self) -> float:
        """The time [s] to which the master locates this component's events, at most the step: a component with
        event indicators declares it as its parameter ``event_tolerance`` (the master names that key when it is
        larger than the step). 1 us by default."""
        return float(self.p.get("event_tolerance", 1e-6))

    def update_discrete(self, t: float, which: list[int]) -> dict:
        """The event at ``t`` [s] of the indicators ``which`` (their positions in :attr:`event_indicators`): update
        the discrete state and the outputs that follow it (FMI 3.0 updateDiscreteStates), and say what happened:
        ``{"kind": str, "values": {name: float}}`` (the values that triggered it, for summary.json ``events``).

        ``which`` empty: the time event :meth:`next_event` scheduled at ``t``. By default nothing changes here (the
        component applies it in its steps: the spool's fuel cut) and the record names the parameter whose event
        it is (``Variable.event``)."""
        if not which:
            what = [v.event for v in self.variables if v.event and v.causality == "parameter"
                    and isinstance(self.p.get(v.name), (int, float)) and abs(float(self.p[v.name]) - t) <= 1e-9]
            return {"kind": "time", "values": {"event": what[0]} if what else {}}
        raise NotImplementedError(f"{type(self).__name__} declares event indicators but no update_discrete")

    def standalone_problem(self) -> str | None:
        """Why this component, with its parameters, cannot be set up on its own (an FMU made of it could not
        initialise: fmus/export.py refuses it), or None. Asked before :meth:`setup`, so it must be cheap; None by
        default."""
        return None

    def validity(self) -> tuple:
        """Where the model holds: :class:`~rotorcosim.components.validity.Check` objects on the outputs, asked for
        after :meth:`setup` (a limit may follow the parameters). None by default: a component that cannot say
        (an imported FMU) declares nothing."""
        return ()

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name!r}>"


class Memoryless:
    """Mixin (before Component in the bases) for a component whose outputs follow from its inputs and parameters
    alone, with nothing carried from one step to the next (the dampers' film, the rub ring's contact): its snapshot
    is the time and copies of its current inputs and outputs."""

    def get_state(self):
        return (self.time, {k: v.copy() for k, v in self.u.items()}, {k: v.copy() for k, v in self.y.items()})

    def set_state(self, snapshot):
        t, u, y = snapshot
        self.time = t
        self.u = {k: v.copy() for k, v in u.items()}
        self.y = {k: v.copy() for k, v in y.items()}


def _copy_snapshot(snap: tuple) -> tuple:
    """``copy.deepcopy(snap)`` of a snapshot ``(time, state, u, y)``. Where state, u and y are plain dicts of
    distinct numeric arrays (what the native components keep) the copy is made directly, the same copy 4-5 times
    faster than deepcopy's generic walk (12 against 56 us for a bearing, measured): the thermal-only hold probes
    the producers' TO outputs through get_state / set_state about a hundred times per staggered run."""
    if len(snap) == 4 and type(snap[0]) in (float, int):
        out, seen = [snap[0]], set()
        for d in snap[1:]:
            if type(d) is not dict:
                return copy.deepcopy(snap)
            c = {}
            for k, v in d.items():
                # an array met twice would be two copies here (deepcopy shares it); an object array is not numeric
                if type(v) is not np.ndarray or v.dtype.hasobject or id(v) in seen:
                    return copy.deepcopy(snap)
                seen.add(id(v))
                c[k] = v.copy(order="K")
            out.append(c)
        return tuple(out)
    return copy.deepcopy(snap)


def as_phases(values: Iterable[str]) -> frozenset[str]:
    out = frozenset(values)
    bad = out - set(PHASES)
    if bad:
        raise ContractError(f"unknown phase(s) {sorted(bad)}; known: {PHASES}")
    return out


def cycles_to_seconds(cycles: float, speed_rpm: float) -> float:
    return cycles * 60.0 / speed_rpm if speed_rpm > 0 else math.inf


__all__ = [
    "Component",
    "ContractError",
    "StopRequested",
    "Variable",
    "CAUSALITIES",
    "COUPLED",
    "HELD",
    "PHASES",
    "TYPES",
    "as_phases",
    "check_finite",
    "cycles_to_seconds",
]
