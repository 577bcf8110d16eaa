"""A scenario's cycle source: the ``[schedule]`` keys that say what period the hold's windows, the restart ramp,
the automatic schedule and intervals given in ``cycles`` count in (master/core/cycle.py).

::

    [schedule]
    speed_rpm = 16000                                    # a constant speed [rev/min]: period 60 / speed_rpm s
    cycle = { period = 0.00375 }                         # a constant period [s]
    cycle = { signal = "shaft.Omega", unit = "rad/s" }   # the period of a speed (or frequency) output, read at
                                                         # the start of each thermo-mechanical interval
    cycle = { signal = "shaft.Omega", angle = "shaft.theta" }   # and the windows counted in turns of an angle
                                                                # output [rad] (a speed that changes within an
                                                                # interval: a speed that falls)

At most one of them; none: the run has no cycle (no thermal-only intervals, no automatic schedule). ``speed_rpm``
is the edge spelling of a constant speed (a quantity at the edge carries its unit in its name); the master itself
knows only the period.
"""
from __future__ import annotations

import math
from typing import Any, Mapping

from rotorcosim.master.core.cycle import ConstantCycle, Cycle, SignalCycle
from rotorcosim.master.scenario.compose import ScenarioError

#: the [schedule] keys of the cycle source
KEYS = ("speed_rpm", "cycle")
#: the keys of a ``cycle`` table
TABLE_KEYS = ("period", "signal", "unit", "angle")


def cycle_of(schedule: Mapping[str, Any]) -> Cycle | None:
    """The cycle source a ``[schedule]`` table declares (the module's docstring), or None."""
    speed, table = schedule.get("speed_rpm"), schedule.get("cycle")
    if speed is not None and table is not None:
        raise ScenarioError("[schedule]: give speed_rpm or cycle, not both (both say the cycle's period)")
    if speed is not None:
        if isinstance(speed, bool) or not isinstance(speed, (int, float)) or not 0.0 < speed < math.inf:
            # a value the schema checked can still come from an engine binding (a spool set turning backwards)
            raise ScenarioError(f"[schedule] speed_rpm: the cycle's speed must be a positive number of rev/min, got "
                                f"{speed!r} (a spool that turns the other way: give [schedule] cycle = "
                                "{ period = S })")
        # 60 / speed as a float division: the same period, bit for bit, wherever a run has it
        return ConstantCycle(60.0 / float(speed))
    if table is None:
        return None
    if not isinstance(table, Mapping):
        raise ScenarioError(f"[schedule] cycle: a table, {{ period = S }} or {{ signal = \"comp.port\" }}, "
                            f"got {table!r}")
    if ("period" in table) == ("signal" in table):
        raise ScenarioError("[schedule] cycle: give exactly one of period (s) or signal (\"component.port\")")
    if "period" in table:
        if "unit" in table or "angle" in table:
            raise ScenarioError("[schedule] cycle: unit and angle belong to a signal's cycle; a period is in seconds")
        return ConstantCycle(table["period"])
    return SignalCycle(table["signal"], table.get("unit"), table.get("angle"))


def constant_period(schedule: Mapping[str, Any]) -> float | None:
    """The cycle period [s] when it is known before the run (intervals in ``cycles`` need it), else None."""
    cycle = cycle_of(schedule)
    return cycle.constant if cycle is not None else None


def without_source(schedule: Mapping[str, Any]) -> dict:
    """The ``[schedule]`` table without its cycle source, as the schedules read it (master/schedule)."""
    return {k: v for k, v in schedule.items() if k not in KEYS}
