"""The automatic staggered schedule (``[schedule] kind = "auto"``, ``rotorcosim run --schedule auto``).

TM intervals run until the mechanical outputs handed to the thermal side are steady cycle to cycle (the
staggered scheme's assumption: once the mechanics are steady, their response changes only with the slow
temperatures) and have run the cycles the hold reads at their end (the restart's ramp, ``restart_cycles``, then
the window of ``hold_cycles``: a shorter interval would hand over powers partly from the ramp); TO intervals run
until the thermal outputs that feed the mechanical side have drifted by more than ``drift_tolerance``, within
min/max durations. The last stretch is one TM interval, where results are read.

Non-stationary runs (a cycle that follows a speed signal, [schedule] cycle): a TM interval is not steady while
the cycle's speed changes by more than ``speed_tolerance`` (default ``drift_tolerance``) over ``to_min`` (a spool running down:
a held interval would skip that much of it; a steadiness test counted in turns of the cycle's angle sees a response
that changes little from one turn to the next even through a critical speed, so this is the test that keeps a
run-down coupled), and one that ends at ``tm_max`` without having become steady while the speed moved by more
than half that tolerance over it is followed by another TM interval, not a TO one; a spool's
speed is an output of a component stepped in TO intervals, so the drift test returns to TM when it has drifted by
more than ``drift_tolerance``; a TO interval ends before a component's next scheduled event
(``Component.next_event``: a fuel cut). With a constant cycle none of this changes a run.

Error control (``tolerance``, percent; ``--tolerance PCT``): every TO interval's error is estimated at the next
restart by the thermal-only hold (master/manipulator/hold.py: the hand-off error of each held power, carried
through the thermal components over the interval, relative to the temperatures' rise since the run's start), and
the next TO interval's length is scaled by tolerance / estimate (at most halved or doubled per interval; the
estimate grows with the extrapolation over the interval). The first TO interval is ``to_min`` long. The run
reports its estimated error at the end (``estimated_error_pct``: every charged interval's response carried to the
end, the largest of the results' when the scenario's case gives them, else of the temperatures).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from rotorcosim.components.contract import COUPLED, HELD
from rotorcosim.master.manipulator.hold import feeds_thermal
from rotorcosim.master.schedule.timeline import Schedule, ScheduleError, check_positive, register_schedule

#: floors of the relative drift test, by unit (a change smaller than this is no drift)
DRIFT_FLOORS = {"K": 0.5, "m": 1e-7, "Pa.s": 1e-4, "W": 1.0, "N": 1.0, "rad/s": 1.0, "rad/s2": 1.0}
#: the largest ``tolerance`` [%]: an error of a result larger than the result itself accepts anything
TOLERANCE_MAX_PCT = 100.0
#: the TO length controller: never more than these factors down or up from one interval to the next
GROWTH_LIMITS = (0.5, 2.0)
#: and a safety factor on tolerance / estimate
SAFETY = 0.8


@register_schedule("auto")
@dataclass
class AutoSchedule(Schedule):
    """TM until the tracked mechanical outputs are steady cycle to cycle, TO until the thermal outputs that
    feed the mechanical side have drifted by more than ``drift_tolerance`` (relative), within min/max durations;
    with ``tolerance`` (percent), TO lengths follow the estimated error (module docstring)."""

    duration: float
    step: float
    thermal_step: float
    steady_tolerance: float = 0.01
    steady_cycles: int = 3
    drift_tolerance: float = 0.02
    tm_min: float = 0.02
    tm_max: float = 0.5
    to_min: float = 0.5
    to_max: float = 30.0
    tracked: Sequence[str] = ()
    tolerance: float | None = None
    speed_tolerance: float | None = None

    keys = ("steady_tolerance", "steady_cycles", "drift_tolerance", "tm_min", "tm_max", "to_min", "to_max",
            "tracked", "tolerance", "speed_tolerance")

    def __post_init__(self):
        for name in ("duration", "step", "thermal_step", "steady_tolerance", "drift_tolerance",
                     "tm_min", "tm_max", "to_min", "to_max"):
            setattr(self, name, check_positive(name, getattr(self, name)))
        if self.speed_tolerance is not None:
            self.speed_tolerance = check_positive("speed_tolerance", self.speed_tolerance)
        for name in ("steady_tolerance", "drift_tolerance", "speed_tolerance"):
            if (getattr(self, name) or 0.0) > 1.0:
                raise ScheduleError(f"schedule: {name} is a fraction (0.02 = 2 %), at most 1, got "
                                    f"{getattr(self, name):g}: it accepts a change larger than the value itself")
        if self.tolerance is not None:
            self.tolerance = check_positive("tolerance (percent)", self.tolerance)
            if self.tolerance > TOLERANCE_MAX_PCT:
                raise ScheduleError(f"schedule: tolerance {self.tolerance:g} % accepts results off by more than "
                                    f"they are (at most {TOLERANCE_MAX_PCT:g} %; it is in percent)")
        for lo, hi in (("tm_min", "tm_max"), ("to_min", "to_max")):
            if getattr(self, lo) > getattr(self, hi):
                raise ScheduleError(f"schedule: {lo} = {getattr(self, lo):g} s is above {hi} = {getattr(self, hi):g} s "
                                    "(an interval's shortest duration cannot exceed its longest)")
        if int(self.steady_cycles) < 1:
            raise ScheduleError("schedule: steady_cycles must be >= 1")
        # an interval shorter than its step would be stretched to a step: with tm_max = 1e-9 s or a thermal_step of
        # 1e-12 s the run went on without end (it is priced all thermo-mechanical, an upper bound only then)
        for key, step, what in (("tm_min", self.step, "step"), ("to_min", self.thermal_step, "thermal_step")):
            if getattr(self, key) < step * (1.0 - 1e-9):
                raise ScheduleError(f"schedule: {key} = {getattr(self, key):g} s is shorter than one {what} "
                                    f"({step:g} s): an interval holds at least one step")
        if self.thermal_step < self.step * (1.0 - 1e-9):
            raise ScheduleError(f"schedule: thermal_step = {self.thermal_step:g} s is shorter than the "
                                f"thermo-mechanical step ({self.step:g} s): the thermal-only intervals are the long "
                                "steps of the automatic schedule")

    @property
    def speed_limit(self) -> float:
        """The relative speed change of the non-stationary tests: ``speed_tolerance``, else ``drift_tolerance``."""
        return self.speed_tolerance if self.speed_tolerance is not None else self.drift_tolerance

    @classmethod
    def from_spec(cls, spec, duration, step, thermal_step, cycle):
        total = check_positive("duration", duration if duration is not None else spec.get("duration"))
        return cls(total, step, thermal_step, **{k: spec[k] for k in cls.keys if k in spec})

    def run(self, sim, first: int = 0) -> None:
        """Drive ``sim`` to the end. The loop's own state (which phase comes next, the TO length the error
        control reached) lives in ``sim.schedule_state``, so that a checkpoint taken at an interval end carries
        it and a resumed run makes the same decisions (master/run/checkpoint.py); ``first`` is not used."""
        if sim.cycle_source is None:
            raise ScheduleError("the automatic schedule needs a cycle (its steadiness test works cycle by cycle: "
                                "the scenario's [schedule] cycle)")
        end = sim.t0 + self.duration
        eps = 1e-9
        state = sim.schedule_state = sim.schedule_state or {"next": COUPLED, "to_len": self.to_min}
        while sim.t < end - eps:
            remaining = end - sim.t
            if state["next"] == COUPLED:
                if remaining <= self.tm_max + self.to_min:
                    # no room left for a thermal-only interval: one thermo-mechanical interval to the end
                    # (stopping it early when steady would only start another one)
                    state["next"] = "end"
                    sim.run_interval(sim.phases.coupled, remaining, self.step, reason="end")
                    break
                # the TO length is set after this interval, from the estimate its restart gave: flagged before
                # it runs, so that a checkpoint at its end (which precedes the update) resumes the same way
                state.update(next=HELD, adjust=True)
                test = _SteadyTest(sim, self)
                sim.run_interval(sim.phases.coupled, self.tm_max, self.step, test, reason="tm_max")
                if sim.report.stopped:
                    break
                if not test.ended_steady and test.speed_change(sim) > 0.5 * self.speed_limit:
                    # not steady, and the cycle's speed moved by more than half the speed tolerance over the
                    # interval (a spool running down): no held interval yet, coupled again (a constant cycle never does)
                    state["next"] = COUPLED
                continue
            if state.pop("adjust", False):
                estimate = sim.hold.report.last_estimate_pct
                if self.tolerance is not None and estimate is not None:
                    factor = SAFETY * self.tolerance / max(estimate, 1e-12)
                    state["to_len"] = min(max(state["to_len"] * min(max(factor, GROWTH_LIMITS[0]),
                                                                    GROWTH_LIMITS[1]), self.to_min), self.to_max)
                elif self.tolerance is None:
                    state["to_len"] = self.to_max
            # keep room for a final thermo-mechanical interval, where the results are read
            state["next"] = COUPLED
            d_to = min(state["to_len"], remaining - self.tm_max)
            # a component's scheduled change (a fuel cut) happens in a coupled interval: the held one ends before
            events = [e for c in sim.system.components.values()
                      for e in [getattr(c, "next_event", lambda t: None)(sim.t)] if e is not None]
            if events:
                d_to = min(d_to, min(events) - sim.t)
            if d_to < self.to_min:
                continue
            sim.run_interval(sim.phases.held, d_to, self.thermal_step, _DriftTest(sim, self), reason="to_max")
            if sim.report.stopped:
                break


class _StopTest:
    every = 1
    #: base steps between two checks (run_interval sets it from :meth:`cadence`)
    check_steps = 1

    def cadence(self, period: int) -> int:
        """The base steps between two checks in an interval whose components all complete a step every
        ``period`` base steps (its multi-rate period): whole multiples of both ``every`` and ``period``."""
        return math.lcm(self.every, period)

    def sample(self, sim) -> None:
        pass

    def block_refs(self) -> list[str]:
        """The outputs ``sample`` reads (the compiled loop hands their rows to ``sample_block``)."""
        return []

    def sample_block(self, cols) -> None:
        """``sample`` for a block of base steps: ``cols[ref]`` holds one row per step."""

    def check(self, sim, t: float) -> str | None:
        return None


class _SteadyTest(_StopTest):
    """Steady when the RMS of the tracked outputs over a cycle changes by less than the tolerance
    (relative) for ``steady_cycles`` consecutive cycles, after ``tm_min`` and the hold's window
    (:meth:`_window_full`).

    A cycle is the ``check_steps`` base steps between two checks (a period at the interval's start, ``every``,
    or the whole number of periods of the multi-rate period); with a cycle source that has an angle, it is as
    many whole turns of that angle, counted from the interval's start, as there are periods between two checks
    at the starting speed (one turn, or the turns of a multi-rate period when that is longer: :meth:`cadence`;
    the RMS over each such span of turns is compared with the previous span's), and the checks, every
    ``check_steps`` base steps, take the spans completed since the last one in order."""

    def __init__(self, sim, sch: AutoSchedule):
        self.sch = sch
        comps = sim.system.components
        self.refs = list(sch.tracked) or sorted({l.con.src for l in sim.engine.links if feeds_thermal(
            comps[l.con.src_component], comps[l.con.dst_component])})
        for r in self.refs:
            sim.system.port(r, "output")
        self.every = max(1, int(round(sim.cycle / sch.step)))
        self.t_begin = sim.t
        self.acc = None
        self.n = 0
        self.last = None
        self.steady = 0
        # the cycle's speed (a speed signal's): not steady while it changes by more than speed_tolerance over a
        # minimal held interval (to_min), which would skip that much of a speed change; a constant cycle never does
        self.speed_changing = False
        self.ended_steady = False
        self._period = (sim.t, sim.hold.cycle)
        self._p_start = self._period[1]
        # the cycles the hold's windows read at the interval's end: the restart's ramp, then hold_cycles
        self.window = math.ceil(sim.hold.restart_cycles - 1e-9) + max(1, int(round(sim.hold.hold_cycles)))
        # counted in turns: (the angle's outputs, its port, its ref), the next whole turn, the direction, and the
        # RMS of each turn completed since the last check
        self.turns = None
        counter = getattr(sim, "revolutions", None)
        if counter is not None:
            comp, _, port = counter.ref.partition(".")
            self.turns = (comps[comp].y, port, counter.ref)
            self.dir = sim.cycle_source.direction(sim.system)
            self.next = float(comps[comp].y[port][0]) + 2.0 * np.pi * self.dir
            self.done: list[np.ndarray] = []
            self.turn_count = 0

    def cadence(self, period: int) -> int:
        """Counted in turns, a check need not fall on a whole period: the first multi-rate period boundary at
        least a period (``every``) after the last check. (The whole multiple of both would be one every
        ``every * period / gcd`` steps, which with a speed whose period is no round number of base steps is
        hundreds of turns: 3 503 base steps a turn and a 200-step multi-rate period are checked every 700 600
        steps, 3.5 s at a 5 us step, never within a coupled interval of 0.5 s.)"""
        if self.turns is None:
            return super().cadence(period)
        return period * max(1, -(-self.every // period))

    def _turn_done(self, theta: float) -> None:
        """A turn ends at this sample: the RMS of the span if it is its last turn, and the next whole turn past
        ``theta``."""
        self.turn_count += 1
        if self.turn_count % max(1, int(round(self.check_steps / self.every))) == 0:
            self.done.append(np.sqrt(self.acc / self.n))
            self.acc, self.n = None, 0
        turn = 2.0 * np.pi * self.dir
        self.next += turn
        while (theta - self.next) * self.dir >= 0.0:
            self.next += turn

    def sample(self, sim):
        if not self.refs:
            return
        vals = np.concatenate([np.ravel(sim.value(r)) for r in self.refs])
        self.acc = vals * vals if self.acc is None else self.acc + vals * vals
        self.n += 1
        if self.turns is not None:
            theta = float(self.turns[0][self.turns[1]][0])
            if (theta - self.next) * self.dir >= 0.0:
                self._turn_done(theta)

    def block_refs(self):
        return list(self.refs) + ([self.turns[2]] if self.turns is not None else [])

    def _accumulate(self, rows) -> None:
        sq = rows * rows
        if self.acc is not None:
            sq = np.vstack([self.acc[None, :], sq])
        # added in order, row after row, as ``sample`` does step by step (np.sum would pair them otherwise)
        self.acc = np.add.accumulate(sq, axis=0)[-1]
        self.n += rows.shape[0]

    def sample_block(self, cols):
        if not self.refs:
            return
        rows = np.concatenate([cols[r] for r in self.refs], axis=1)
        if self.turns is None:
            self._accumulate(rows)
            return
        theta = np.asarray(cols[self.turns[2]])[:, 0]
        start = 0
        while start < rows.shape[0]:   # the block cut at the samples that end a turn, as ``sample`` would
            passed = np.flatnonzero((theta[start:] - self.next) * self.dir >= 0.0)
            end = start + int(passed[0]) + 1 if len(passed) else rows.shape[0]
            self._accumulate(rows[start:end])
            if len(passed):
                self._turn_done(float(theta[end - 1]))
            start = end

    def _compare(self, rms) -> None:
        if self.last is not None:
            scale = np.maximum(np.abs(self.last), 1e-12)
            change = float(np.max(np.abs(rms - self.last) / scale))
            self.steady = self.steady + 1 if change < self.sch.steady_tolerance else 0
        self.last = rms

    def check(self, sim, t):
        changing = self._speed_changing(sim, t)
        if self.turns is not None and self.refs:
            for rms in self.done:   # the turns completed since the last check
                self._compare(rms)
            self.done = []
        else:
            if self.acc is None:
                if not changing and t - self.t_begin >= self.sch.tm_min - 1e-12:
                    self.ended_steady = True
                    return "steady"
                return None
            rms = np.sqrt(self.acc / self.n)
            self.acc, self.n = None, 0
            self._compare(rms)
        if changing:
            self.steady = 0
        if (t - self.t_begin >= self.sch.tm_min - 1e-12 and self.steady >= self.sch.steady_cycles
                and self._window_full(t)):
            self.ended_steady = True
            return "steady"
        return None

    def _window_full(self, t: float) -> bool:
        """Whether the interval has run the cycles the hold reads after it (``window`` cycles: the restart's
        ramp, then ``hold_cycles``), in turns of the cycle's angle or in periods of its starting speed: a
        held interval after a shorter one would hold powers partly from the restart's ramp."""
        if self.turns is not None:
            return self.turn_count >= self.window
        return t - self.t_begin >= self.window * self._p_start - 1e-12 if self._p_start else True

    def speed_change(self, sim) -> float:
        """The relative change of the cycle's speed since the interval started (0 for a constant cycle)."""
        try:
            p = sim.hold.cycle
        except ValueError:
            return 0.0
        p0 = self._p_start
        return abs(p - p0) / p if p and p0 else 0.0

    def _speed_changing(self, sim, t) -> bool:
        """Whether the cycle's speed changed since the last check faster than speed_tolerance per to_min (a
        constant cycle never does; a stopped speed signal has no period: not changing)."""
        t0, p0 = self._period
        try:
            p = sim.hold.cycle
        except ValueError:
            p = None
        if p and p0 and t > t0:
            self.speed_changing = abs(p - p0) / p / (t - t0) * self.sch.to_min > self.sch.speed_limit
        self._period = (t, p)
        return self.speed_changing


class _DriftTest(_StopTest):
    """Ends a thermal-only interval when an output of a thermal component that feeds a frozen (mechanical)
    component has drifted from its value at the interval start by more than the tolerance, after ``to_min``."""

    def __init__(self, sim, sch: AutoSchedule):
        self.sch = sch
        comps = sim.system.components
        self.refs = sorted({l.con.src for l in sim.engine.links
                            if feeds_thermal(comps[l.con.dst_component], comps[l.con.src_component])})
        self.start = {r: np.array(sim.value(r), dtype=float) for r in self.refs}
        self.floors = {r: DRIFT_FLOORS.get(sim.system.port(r, "output").unit, 0.0) for r in self.refs}
        self.t_begin = sim.t

    def check(self, sim, t):
        if t - self.t_begin < self.sch.to_min - 1e-12:
            return None
        for r in self.refs:
            d = np.abs(sim.value(r) - self.start[r])
            if np.any(d > self.sch.drift_tolerance * np.abs(self.start[r]) + self.floors[r]):
                return f"drift of {r}"
        return None
