"""The cycle a run counts in: the period (s) of the hold's windows, of a restart's ramp and of the automatic
schedule's steadiness test.

A scenario declares where the period comes from; the master reads it when a window starts:

* :class:`ConstantCycle`: a period known before the run (intervals given in cycles need one);
* :class:`SignalCycle`: the period of an output port that carries an angular speed (``rad/s``, ``rev/min``...:
  period = 2 pi / |omega|) or a frequency (``Hz``, ``1/s``: period = 1 / |f|), read at the start of each
  thermo-mechanical interval, so that windows follow a speed that changes from one interval to the next.

::

    from rotorcosim.master.core.cycle import ConstantCycle, SignalCycle
    ConstantCycle(0.02).period(system)                       # 0.02 s
    SignalCycle("shaft.Omega").period(system)                # 2 pi / |shaft.Omega| at this moment
"""
from __future__ import annotations

import math

from rotorcosim.components.contract import ContractError
from rotorcosim.fmus.units import definition, is_dimensionless


class CycleError(ContractError):
    """A cycle that cannot give a period (one line naming the source and why)."""


class Cycle:
    """Where a run's cycle period comes from. ``constant`` is the period (s) when it is known before the run,
    else None; :meth:`period` is the period at the present state of ``system``."""

    constant: float | None = None

    def check(self, system) -> None:
        """Before the run: the source exists in ``system`` (an error naming it otherwise)."""

    def period(self, system) -> float:
        """The cycle's length now [s], read from ``system`` where the source is a signal."""
        raise NotImplementedError


class ConstantCycle(Cycle):
    """A period fixed before the run [s]."""

    def __init__(self, period: float):
        try:
            p = float(period)
        except (TypeError, ValueError):
            raise CycleError(f"cycle period must be a number of seconds, got {period!r}") from None
        if not (p > 0.0 and math.isfinite(p)):
            raise CycleError(f"cycle period must be a positive number of seconds, got {period!r}")
        self.constant = p

    def period(self, system=None) -> float:
        """The constant period [s] (``system`` is not read)."""
        return self.constant

    def __repr__(self) -> str:
        return f"ConstantCycle({self.constant!r})"


#: the dimensions a cycle signal may have (fmus/units.py exponents) -> what one unit of it is, per second
_RATES = {(("rad", 1), ("s", -1)): "angular speed", (("s", -1),): "frequency"}


class SignalCycle(Cycle):
    """The period of a scalar output ``ref`` (``"component.port"``) carrying an angular speed or a frequency.
    ``unit``: the unit of the port's values when the port declares none (else the port's own unit is used and
    a different ``unit`` is an error)."""

    def __init__(self, ref: str, unit: str | None = None):
        if not isinstance(ref, str) or ref.count(".") < 1 or ref.startswith(".") or ref.endswith("."):
            raise CycleError(f"cycle signal {ref!r}: write it 'component.port'")
        self.ref, self.unit = ref, unit
        self._scale: tuple[float, bool] | None = None  # (SI factor, True for an angular speed)

    def check(self, system) -> None:
        var = system._port(self.ref, "output")
        if var.size != 1:
            raise CycleError(f"cycle signal {self.ref}: a scalar output is needed, it has {var.size} values")
        unit = var.unit
        if is_dimensionless(unit):
            if self.unit is None:
                raise CycleError(f"cycle signal {self.ref} has no unit: say which with unit = \"rad/s\" (or "
                                 "\"Hz\", \"rev/min\")")
            unit = self.unit
        elif self.unit is not None and self.unit != unit:
            raise CycleError(f"cycle signal {self.ref} is in [{unit}], not [{self.unit}]: leave unit out")
        d = definition(unit)
        kind = _RATES.get(tuple(sorted(d[0].items()))) if d is not None else None
        if kind is None or d[2] != 0.0:
            raise CycleError(f"cycle signal {self.ref} is in [{unit}]: an angular speed (rad/s, rev/min) or a "
                             "frequency (Hz) is needed")
        self._scale = (d[1], kind == "angular speed")

    def period(self, system) -> float:
        """2 pi / |omega| or 1 / |f| [s] from the signal's present value in ``system``."""
        if self._scale is None:
            self.check(system)
        comp, _, port = self.ref.partition(".")
        factor, angular = self._scale
        rate = abs(float(system.components[comp].y[port][0])) * factor
        if not (rate > 0.0 and math.isfinite(rate)):
            raise CycleError(f"cycle signal {self.ref} is {rate:g} (SI) at t = {system.components[comp].time:g} s: "
                             "no cycle period (a standing or undefined speed)")
        return 2.0 * math.pi / rate if angular else 1.0 / rate

    def __repr__(self) -> str:
        return f"SignalCycle({self.ref!r}, unit={self.unit!r})"


def as_cycle(cycle) -> Cycle | None:
    """A :class:`Cycle` from a period in seconds, a Cycle, or None (no cycle)."""
    if cycle is None or isinstance(cycle, Cycle):
        return cycle
    return ConstantCycle(cycle)
