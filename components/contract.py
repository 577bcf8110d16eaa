"""The component contract: what every component, native or imported FMU, offers the master.

Modelled on FMI 2.0 co-simulation (and on fmpy's flat model description):

* declared variables (:class:`Variable`): name, causality (parameter / input / output), vector size,
  SI unit, description and start value;
* ``setup(t0)`` (enter/exit initialisation), ``set_inputs``, ``do_step(t, h)``, ``get_outputs``, ``terminate``;
* ``get_state`` / ``set_state``: a full snapshot (FMI getFMUstate / setFMUstate), used for rollback and by
  the staggered schedule;
* a preferred communication step and the phases it takes part in (``"TM"`` thermo-mechanical,
  ``"TO"`` thermal-only).

A component owns its internal integration and never reaches into another component.
"""
from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field
from typing import Any, Iterable, Mapping

import numpy as np

CAUSALITIES = ("parameter", "input", "output")
TYPES = ("Real", "Integer", "Boolean", "String")
PHASES = ("TM", "TO")


class ContractError(ValueError):
    """A component or its use breaks the contract (unknown variable, wrong size, bad value)."""


@dataclass(frozen=True)
class Variable:
    """One declared variable. Ports are vectors of ``size`` reals; parameters may also be strings."""

    name: str
    causality: str
    size: int = 1
    unit: str = "1"
    description: str = ""
    start: Any = 0.0
    type: str = "Real"

    def __post_init__(self):
        if self.causality not in CAUSALITIES:
            raise ContractError(f"variable {self.name!r}: causality {self.causality!r} not in {CAUSALITIES}")
        if self.type not in TYPES:
            raise ContractError(f"variable {self.name!r}: type {self.type!r} not in {TYPES}")
        if int(self.size) < 1:
            raise ContractError(f"variable {self.name!r}: size must be >= 1, got {self.size}")
        if self.type == "String" and (self.causality != "parameter" or self.size != 1):
            raise ContractError(f"variable {self.name!r}: String variables must be scalar parameters")

    def start_array(self) -> np.ndarray:
        """The start value as a float vector of ``size`` (a scalar start is broadcast)."""
        return np.broadcast_to(np.asarray(self.start, dtype=float), (self.size,)).copy()


def check_finite(name: str, value: np.ndarray) -> None:
    if not np.all(np.isfinite(value)):
        raise ContractError(f"{name}: value is not finite ({value})")


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
    #: True for a component that takes part in thermal-only (TO) intervals only to update the outputs that depend
    #: on its thermal inputs (the bearing's drag power follows the oil viscosity) while its mechanical state stays
    #: frozen: the master treats it as mechanical (its inputs from frozen components are held at their last
    #: value, and the automatic schedule watches the thermal outputs it receives). See :meth:`enter_phase`.
    holds_state_in_TO: bool = False
    #: short description shown by ``rotorcosim`` and written to exported FMUs
    description: str = ""

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
        self.u = {v.name: v.start_array() for v in self.variables if v.causality == "input"}
        self.y = {v.name: v.start_array() for v in self.variables if v.causality == "output"}
        self.state: dict[str, Any] = {}
        self.time = 0.0

    # -- declarations -------------------------------------------------------------------------------
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
        if v.type == "String":
            if not isinstance(value, str):
                raise ContractError(f"{self.name}.{v.name}: expected a string, got {value!r}")
            return value
        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise ContractError(f"{self.name}.{v.name}: expected a number, got {value!r}") from None
        if arr.size != v.size:
            raise ContractError(f"{self.name}.{v.name}: expected {v.size} value(s), got {arr.size}")
        check_finite(f"{self.name}.{v.name}", arr)
        if v.type == "Boolean":
            return bool(arr.reshape(-1)[0]) if v.size == 1 else arr.astype(bool)
        if v.type == "Integer":
            if not np.all(arr == np.round(arr)):
                raise ContractError(f"{self.name}.{v.name}: expected an integer, got {value!r}")
            return int(arr.reshape(-1)[0]) if v.size == 1 else arr.astype(int)
        return float(arr.reshape(-1)[0]) if v.size == 1 else arr.reshape(-1).copy()

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

    def set_inputs(self, values: Mapping[str, Any]) -> None:
        for key, value in values.items():
            v = self._by_name.get(key)
            if v is None or v.causality != "input":
                raise ContractError(f"{self.name}: no input {key!r}")
            arr = np.asarray(value, dtype=float).reshape(-1)
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
        return copy.deepcopy((self.time, self.state, self.u, self.y))

    def set_state(self, snapshot: Any) -> None:
        self.time, self.state, self.u, self.y = copy.deepcopy(snapshot)

    def enter_phase(self, phase: str) -> None:
        """Called by the master at the start of every interval with its phase (``"TM"`` or ``"TO"``), for
        every component, stepped or frozen. Components that behave differently in thermal-only intervals
        (``holds_state_in_TO``) override it."""
        self.phase = phase

    # -- optional -----------------------------------------------------------------------------------
    def interface_jacobian(self) -> dict[tuple[str, str], np.ndarray] | None:
        """Optional d(output)/d(input) blocks at the current point, for the master's linear correction."""
        return None

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name!r}>"


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
    "Variable",
    "CAUSALITIES",
    "PHASES",
    "TYPES",
    "as_phases",
    "check_finite",
    "cycles_to_seconds",
]
