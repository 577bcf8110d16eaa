"""The scenario schema's tables: every table and key a scenario file accepts, each with its value checker
(checkers.py). docs/reference/scenario.md is generated from them (docs/reference/generate.py)."""
from __future__ import annotations

from typing import Callable

from rotorcosim.master.core.algorithm import ALGORITHMS
from rotorcosim.master.core.phases import ROLES
from rotorcosim.master.core.system import AVERAGES, EXTRAPOLATIONS, HOLDS, UNCONNECTED_INPUTS
from rotorcosim.master.scenario.checkers import (boolean, count, fraction, list_of, not_negative, one_of, port_ref,
                                                 positive, text, text_or_texts, whole_positive)
from rotorcosim.master.schedule.timeline import SCHEDULES

SCHEDULE_KINDS = tuple(SCHEDULES)   # the schedule registry (master/schedule/timeline.py)
OUTPUT_FORMATS = ("h5", "csv")

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
                 "steady_tolerance": fraction, "steady_cycles": count, "drift_tolerance": fraction,
                 "speed_tolerance": fraction,
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
#: ``[schedule.phases]``: the scenario's names of its coupled and held phases (master/core/phases.py)
PHASES = {role: text for role in ROLES}
