"""The cycle a run counts in: the period (s) of the hold's windows, of a restart's ramp and of the automatic
schedule's steadiness test.

A scenario declares where the period comes from; the master reads it when a window starts:

* :class:`ConstantCycle`: a period known before the run (intervals given in cycles need one);
* :class:`SignalCycle`: the period of an output port that carries an angular speed (``rad/s``, ``rev/min``...:
  period = 2 pi / |omega|) or a frequency (``Hz``, ``1/s``: period = 1 / |f|), read at the start of each
  thermo-mechanical interval, so that windows follow a speed that changes from one interval to the next;
  with ``angle`` (an output in rad, the shaft's angle), the windows are counted in revolutions of that angle
  instead: a window of N cycles starts where the angle was 2 pi N below its value at the window's end
  (:class:`RevolutionCounter`), so that it spans N turns even while the speed changes within the interval (a
  run-down). The period read at the interval's start then only sizes the buffers and sets how often the automatic
  schedule looks at its steadiness test.

Without an angle the windows are N periods long: for a constant speed, the same as N revolutions of
theta = Omega t.

::

    from rotorcosim.master.core.cycle import ConstantCycle, SignalCycle
    ConstantCycle(0.02).period(system)                       # 0.02 s
    SignalCycle("shaft.Omega").period(system)                # 2 pi / |shaft.Omega| at this moment
    SignalCycle("shaft.Omega", angle="shaft.theta")          # windows counted in turns of shaft.theta
"""
from __future__ import annotations

import math

import numpy as np

from rotorcosim.components.contract import COUPLED, ContractError
from rotorcosim.fmus.units import definition, is_dimensionless


class CycleError(ContractError):
    """A cycle that cannot give a period (one line naming the source and why)."""


class Cycle:
    """Where a run's cycle period comes from. ``constant`` is the period (s) when it is known before the run,
    else None; :meth:`period` is the period at the present state of ``system``."""

    constant: float | None = None
    #: the output ("component.port", rad) whose turns the windows count, or None: windows of N periods
    angle: str | None = None

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

    def __init__(self, ref: str, unit: str | None = None, angle: str | None = None):
        for what, r in (("signal", ref), ("angle", angle)):
            if r is None and what == "angle":
                continue
            if not isinstance(r, str) or r.count(".") < 1 or r.startswith(".") or r.endswith("."):
                raise CycleError(f"cycle {what} {r!r}: write it 'component.port'")
        self.ref, self.unit, self.angle = ref, unit, angle
        self._scale: tuple[float, bool] | None = None  # (SI factor, True for an angular speed)

    def check(self, system) -> None:
        var = system.port(self.ref, "output")
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
        if self.angle is not None:
            avar = system.port(self.angle, "output")
            if avar.size != 1 or avar.unit != "rad" or avar.type != "Real":
                raise CycleError(f"cycle angle {self.angle}: a scalar Real output in [rad] is needed (it has "
                                 f"{avar.size} value(s) in [{avar.unit}])")

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

    def direction(self, system) -> float:
        """+1 when the signal's speed is >= 0 now, else -1 (the way the cycle's angle turns)."""
        comp, _, port = self.ref.partition(".")
        return -1.0 if float(system.components[comp].y[port][0]) < 0.0 else 1.0

    def __repr__(self) -> str:
        return f"SignalCycle({self.ref!r}, unit={self.unit!r}, angle={self.angle!r})"


def as_cycle(cycle) -> Cycle | None:
    """A :class:`Cycle` from a period in seconds, a Cycle, or None (no cycle)."""
    if cycle is None or isinstance(cycle, Cycle):
        return cycle
    return ConstantCycle(cycle)


#: revolution-counted windows are kept in buffers sized for this many times the samples of their revolutions at
#: the speed of the interval's start (the speed may fall to 1 / WINDOW_MARGIN of it within a window); a window that
#: needs more is cut to its buffer and the run reports the revolutions it spanned (hold.window_revolutions)
WINDOW_MARGIN = 4.0


class RevolutionCounter:
    """The angle of a cycle (``Cycle.angle``) sampled at every base step of the present thermo-mechanical
    interval, and the times at which its revolutions began (an observer of the run, placed first by the
    simulation; it only reads the angle).

    For a window of N revolutions that ends at time t, :meth:`began` gives the time t_N at which
    theta(t_N) = theta(t) - 2 pi N, theta linear between two samples (the interval's start when fewer than N
    turns were recorded). The samples older than ``keep`` revolutions (the largest window asked for, see
    :meth:`need`) are dropped as the interval goes on. The angle must move one way over a window (its direction
    is the sign of its change since the interval's start)."""

    stride = 1

    def __init__(self, ref: str):
        self.ref = ref
        self._comp, _, self._port = ref.partition(".")   # read at every step: split once
        self.keep = 1.0
        self.active = False
        self._t = np.zeros(0)
        self._th = np.zeros(0)
        self._n = 0

    def need(self, revolutions: float) -> None:
        """A window of ``revolutions`` turns will be asked for: keep at least that many."""
        self.keep = max(self.keep, float(revolutions))

    # -- the observer's side ---------------------------------------------------------------------------------
    def start(self, sim, schedule) -> None:
        """The run begins: nothing to record before its first interval."""

    def interval_start(self, sim, phase, step) -> None:
        """A coupled interval starts a new record from the angle now; a held one records nothing."""
        self.active = phase == COUPLED
        if self.active:
            self._t = np.zeros(4096)
            self._th = np.zeros(4096)
            self._n = 0
            self._add(np.array([sim.t]), np.array([self._angle(sim)]))

    def _angle(self, sim) -> float:
        return float(sim.system.components[self._comp].y[self._port][0])

    def step(self, sim, t) -> None:
        """Record the angle at the step's end time ``t``."""
        if self.active:
            self._add(np.array([t]), np.array([self._angle(sim)]))

    def block_signals(self, sim) -> list[str]:
        """The one signal the compiled loop hands over per block: the angle."""
        return [self.ref]

    def step_block(self, sim, ks, ts, data) -> None:
        """Record a block of steps' angles (the compiled loop's form of :meth:`step`)."""
        if self.active and len(ts):
            self._add(np.asarray(ts, dtype=float), np.asarray(data[self.ref], dtype=float)[:, 0])

    def interval_end(self, sim, used) -> None:
        """Keep the record: the hold reads its windows after the interval ends."""

    def end(self, sim, error) -> None:
        """Nothing to write: the record is the hold's input, not a result."""

    def checkpoint_state(self):
        """The record and its bounds, for a checkpoint."""
        return {"t": self._t[:self._n].copy(), "th": self._th[:self._n].copy(), "active": self.active,
                "keep": self.keep}

    def restore_checkpoint(self, state) -> None:
        """Take back the record :meth:`checkpoint_state` gave."""
        self._t, self._th = state["t"].copy(), state["th"].copy()
        self._n, self.active, self.keep = len(self._t), state["active"], state["keep"]

    def _add(self, t: np.ndarray, th: np.ndarray) -> None:
        n, m = self._n, len(t)
        if n + m > len(self._t):
            # drop what no window reaches any more (older than ``keep`` turns before the newest sample), then grow
            last = th[-1] if m else self._th[n - 1]
            sgn = 1.0 if n == 0 or last >= self._th[0] else -1.0
            lo = int(np.searchsorted(sgn * self._th[:n], sgn * last - 2.0 * math.pi * (self.keep + 1.0)))
            lo = max(0, min(lo - 1, n - 1))
            if lo > 0:
                self._t[:n - lo] = self._t[lo:n]
                self._th[:n - lo] = self._th[lo:n]
                n -= lo
            if n + m > len(self._t):
                size = max(2 * len(self._t), n + m)
                self._t = np.concatenate([self._t[:n], np.zeros(size - n)])
                self._th = np.concatenate([self._th[:n], np.zeros(size - n)])
        self._t[n:n + m] = t
        self._th[n:n + m] = th
        self._n = n + m

    # -- what the windows ask -------------------------------------------------------------------------------
    def _signed(self):
        t, th = self._t[:self._n], self._th[:self._n]
        sgn = 1.0 if th[-1] >= th[0] else -1.0
        return t, sgn * th

    def angle_at(self, t: float) -> float:
        """The angle [rad] at time ``t``, linear between samples, in the direction of rotation (held at the
        recorded ends outside them)."""
        ts, th = self._signed()
        return float(np.interp(t, ts, th))

    def began(self, revolutions: float, t: float | None = None) -> float:
        """The time [s] at which the last ``revolutions`` turns before ``t`` (the newest sample: None) began; the
        first recorded time where fewer turns were recorded."""
        if self._n == 0:
            raise CycleError(f"cycle angle {self.ref}: no angle recorded yet")
        ts, th = self._signed()
        end = th[-1] if t is None else float(np.interp(t, ts, th))
        target = end - 2.0 * math.pi * float(revolutions)
        if target <= th[0]:
            return float(ts[0])
        i = int(np.searchsorted(th, target, side="left"))
        i = min(max(i, 1), len(th) - 1)
        if th[i] == th[i - 1]:
            return float(ts[i])
        return float(ts[i - 1] + (target - th[i - 1]) * (ts[i] - ts[i - 1]) / (th[i] - th[i - 1]))

    def revolutions(self, t0: float, t1: float) -> float:
        """The turns between times ``t0`` and ``t1`` [-] (within the recorded samples)."""
        return (self.angle_at(t1) - self.angle_at(t0)) / (2.0 * math.pi)
