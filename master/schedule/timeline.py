"""Schedules: which phase runs when, at which step (the staggered scheme).

* the coupled phase (``TM``, thermo-mechanical, by default): every component steps at small steps;
* the held phase (``TO``, thermal-only): components that take no part in it are frozen, the others step at a
  large step, fed with the frozen components' outputs held at their mean (or RMS) over the last N cycles of the
  previous coupled interval (the cycle: master/core/cycle.py).

A scenario names the two phases (``[schedule.phases]``, master/core/phases.py); intervals use those names.

A schedule is a class behind a registry (``kind`` of a scenario's ``[schedule]``): an explicit ``timeline``,
``monolithic`` (one TM interval) or ``auto`` (master/schedule/auto.py: decided while the run goes, optionally to an error
tolerance). A new schedule is a new registered class with ``from_spec`` and ``run``. Every run reports the timeline
it actually used.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

from rotorcosim.components.contract import COUPLED, HELD, ContractError
from rotorcosim.master.core.phases import Phases


class ScheduleError(ContractError):
    """A schedule that cannot run: a bad ``[schedule]`` table or interval (the message names the key)."""


def check_positive(name: str, value: Any) -> float:
    """``value`` as a positive finite float, else a ScheduleError naming ``name``."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ScheduleError(f"schedule: {name} must be a number, got {value!r}") from None
    if not math.isfinite(x) or x <= 0.0:
        raise ScheduleError(f"schedule: {name} must be a positive finite number, got {value!r}")
    return x


@dataclass(frozen=True)
class Interval:
    """One interval of a timeline: ``phase`` (a name the scenario declares: by default "TM" thermo-mechanical or
    "TO" thermal-only; checked when the interval runs), ``duration`` [s]
    and base ``step`` [s] (at most the duration; the last step is shortened to end on the duration).

    >>> iv = Interval("TM", duration=0.25, step=1e-5)
    >>> iv.steps
    25000
    >>> Interval("TO", duration=1.0, step=2.0)
    Traceback (most recent call last):
    ...
    rotorcosim.master.schedule.timeline.ScheduleError: schedule: TO interval step 2.0 s is longer than its duration 1.0 s
    """
    phase: str
    duration: float
    step: float

    def __post_init__(self):
        if not isinstance(self.phase, str) or not self.phase:
            raise ScheduleError(f"schedule: interval phase must be a phase's name, got {self.phase!r}")
        check_positive("interval duration", self.duration)
        check_positive("interval step", self.step)
        if self.step > self.duration * (1 + 1e-12):
            raise ScheduleError(f"schedule: {self.phase} interval step {self.step} s is longer than its duration {self.duration} s")

    @property
    def steps(self) -> int:
        """Number of steps; the last one may be shortened so the interval ends exactly at its duration."""
        return max(1, math.ceil(self.duration / self.step - 1e-9))


#: the schedules by kind (a registry, like the components'): a new schedule is a new class, registered here
SCHEDULES: dict[str, type["Schedule"]] = {}
#: [schedule] keys every kind accepts (the step defaults, and the Simulation's: its cycle source and hold, which
#: the scenario layer reads)
COMMON_KEYS = ("kind", "duration", "step", "thermal_step", "cycle", "hold", "hold_cycles", "restart_cycles",
               "phases")


def phases_of(spec: Mapping[str, Any]) -> Phases:
    """The phases a ``[schedule]`` table declares (its ``phases`` sub-table; default "TM" / "TO")."""
    try:
        return Phases.from_spec(spec.get("phases"))
    except ContractError as exc:
        raise ScheduleError(f"schedule: {exc}") from None


def register_schedule(kind: str):
    """Class decorator: make a :class:`Schedule` available as ``[schedule] kind``."""

    def add(cls):
        cls.kind = kind
        SCHEDULES[kind] = cls
        return cls

    return add


class Schedule:
    """What runs when. ``from_spec`` builds one from a scenario's ``[schedule]`` table (its own keys in
    ``keys``; ``cycle`` the constant cycle period in seconds, or None); ``run`` drives a Simulation through
    it."""

    kind = ""
    #: the [schedule] keys this kind reads beyond COMMON_KEYS
    keys: tuple[str, ...] = ()

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any], duration: float | None, step: float, thermal_step: float,
                  cycle: float | None) -> "Schedule":
        """The schedule of a ``[schedule]`` table ``spec`` (its ``kind`` is this class's): ``duration`` [s]
        overrides the table's (None: the table's own), ``step`` and ``thermal_step`` [s] are the default steps
        of thermo-mechanical and thermal-only intervals, ``cycle`` [s] is the constant cycle period that converts
        interval lengths given in cycles to seconds (None: none declared)."""
        raise NotImplementedError

    # every schedule has a ``duration`` (s): the simulated time it covers

    def run(self, sim, first: int = 0) -> None:
        """Drive ``sim`` through the schedule, from its interval ``first`` on (a resumed run)."""
        raise NotImplementedError


def _interval_duration(spec: Mapping[str, Any], cycle: float | None) -> float:
    if "duration" in spec and "cycles" in spec:
        raise ScheduleError(f"schedule: interval {dict(spec)} gives both duration and cycles")
    if "cycles" in spec:
        if not cycle:
            raise ScheduleError("schedule: an interval in cycles needs a cycle of constant period (the "
                                "scenario's [schedule] cycle)")
        return check_positive("interval cycles", spec["cycles"]) * check_positive("cycle period", cycle)
    if "duration" not in spec:
        raise ScheduleError(f"schedule: interval {dict(spec)} needs a duration (s) or cycles")
    return check_positive("interval duration", spec["duration"])


@register_schedule("timeline")
@dataclass
class Timeline(Schedule):
    """An explicit list of intervals: ``[[schedule.intervals]]`` with phase, duration or
    cycles, and an optional step.

    Parameters: ``intervals``, the intervals (:class:`Interval`) in the order they run.

    >>> tl = Timeline([Interval("TM", 0.25, 1e-5), Interval("TO", 119.5, 0.1), Interval("TM", 0.25, 1e-5)])
    >>> tl.duration
    120.0
    >>> [iv.phase for iv in cut_timeline(tl, 1.0).intervals]
    ['TM', 'TO']
    >>> report = sim.run(tl)              # doctest: +SKIP
    >>> # (sim: a rotorcosim.master.simulation.Simulation)
    """

    intervals: list[Interval]
    keys = ("intervals",)

    @property
    def duration(self) -> float:
        """The simulated time the timeline covers [s]."""
        return sum(i.duration for i in self.intervals)

    @classmethod
    def from_spec(cls, spec, duration, step, thermal_step, cycle):
        raw = spec.get("intervals")
        if not raw:
            raise ScheduleError("schedule: kind 'timeline' needs [[schedule.intervals]]")
        intervals = []
        phases = phases_of(spec)
        for item in raw:
            phase = item.get("phase")
            d = _interval_duration(item, cycle)
            try:
                coupled = phases.role(phase) == COUPLED
            except ContractError as exc:
                raise ScheduleError(f"schedule: {exc}") from None
            h = item.get("step", step if coupled else thermal_step)
            intervals.append(Interval(phase, d, min(check_positive("interval step", h), d)))
        tl = cls(intervals)
        if duration is not None:
            tl = cut_timeline(tl, check_positive("duration", duration))
        return tl

    def run(self, sim, first: int = 0) -> None:
        if any(sim.phases.role(iv.phase) == HELD for iv in self.intervals) and sim.cycle_source is None:
            raise ScheduleError("a schedule with thermal-only intervals needs a cycle (the period over which the "
                                "held outputs are averaged: the scenario's [schedule] cycle)")
        coupled = [iv.step for iv in self.intervals if sim.phases.role(iv.phase) != HELD]
        #: the timeline's own end of the last interval [s] where the run went past it (the coupled rest after an
        #: event completes the slower components' windows: a multi-rate interval is whole windows), else None:
        #: the next intervals end where the timeline puts them, not that much later
        past = None
        #: the position a resumed run was interrupted at, inside an interval (master/run/checkpoint.py): that
        #: interval runs as it did then (its duration and step; the coupled rest of a held interval), else None
        resumed = None
        pos = sim.schedule_state
        if sim.resume_point is not None and isinstance(pos, TimelinePosition):
            if pos.interval < first:   # saved at that interval's end
                past = pos.past_after(sim.t)
            else:
                resumed = pos
        for i, iv in enumerate(self.intervals[first:], first):
            sim.interval_index = i
            if resumed is None or not resumed.rest:
                if resumed is not None:
                    duration, step, resumed = resumed.duration, resumed.step, None
                else:
                    duration, step = iv.duration, iv.step
                    if past is not None:
                        end, past = past + iv.duration, None
                        duration = end - sim.t
                        if duration <= 1e-9 * max(1.0, end):
                            past = end      # the rest before ran over the whole of this interval
                            continue
                        step = min(step, duration)
                t_end = sim.t + duration
                pos = sim.schedule_state = TimelinePosition(i, duration, step, t_end, carry=duration != iv.duration)
                used = sim.run_interval(iv.phase, duration, step)
                if sim.report.stopped:
                    break
                past = pos.past_after(sim.t)
                if not (used.reason == "event" and coupled and t_end - sim.t > 1e-9 * max(1.0, t_end)):
                    continue
                # an event ended a held interval (master/core/events.py): the rest of it runs coupled, at the
                # timeline's coupled step (checkpointed as any coupled interval: this position)
                pos = TimelinePosition(i, t_end - sim.t, min(coupled[0], t_end - sim.t), t_end, rest=True,
                                       carry=True)
            else:
                pos, resumed = resumed, None
            sim.schedule_state = pos
            sim.run_interval(sim.phases.coupled, pos.duration, pos.step, reason="after an event")
            if sim.report.stopped:
                break
            past = pos.past_after(sim.t)


@dataclass(frozen=True)
class TimelinePosition:
    """Where :meth:`Timeline.run` is, kept in ``sim.schedule_state`` so that a checkpoint carries it and a run
    resumed inside an interval runs it as the interrupted run did (master/run/checkpoint.py): the ``interval``
    (its index), the ``duration`` and ``step`` [s] it runs (shortened when the run before went past its start),
    ``t_end`` [s] where it ends (for the coupled rest, ``rest`` True: the end of the held interval an event cut)
    and ``carry``: going past ``t_end`` shortens the next interval (a shortened interval, or a rest)."""
    interval: int
    duration: float
    step: float
    t_end: float
    rest: bool = False
    carry: bool = False

    def past_after(self, t: float) -> float | None:
        """The end [s] the next interval starts from when this one ended at ``t`` [s] past ``t_end`` and
        ``carry``s it (Timeline.run's ``past``), else None."""
        return self.t_end if self.carry and t > self.t_end + 1e-9 * max(1.0, self.t_end) else None


@register_schedule("monolithic")
class Monolithic(Timeline):
    """One thermo-mechanical interval over ``duration`` at ``step``."""

    keys = ()

    @classmethod
    def from_spec(cls, spec, duration, step, thermal_step, cycle):
        total = check_positive("duration", duration if duration is not None else spec.get("duration"))
        return cls([Interval(phases_of(spec).coupled, total, min(step, total))])


def from_spec(spec: Mapping[str, Any], duration: float | None = None, cycle: float | None = None) -> Schedule:
    """Build a schedule from a scenario's ``[schedule]`` table: ``kind`` names a registered :class:`Schedule`
    (default ``monolithic``), which reads its own keys. ``duration`` overrides the scenario's total duration
    (a timeline is then cut or its last interval stretched); ``cycle`` is the constant cycle period [s] that
    intervals given in ``cycles`` count in (the scenario layer reads it from the table's cycle source)."""
    known = set(COMMON_KEYS).union(*(c.keys for c in SCHEDULES.values()))
    unknown = set(spec) - known
    if unknown:
        raise ScheduleError(f"schedule: unknown key(s) {sorted(unknown)}; known: {sorted(known)}")
    kind = spec.get("kind", "monolithic")
    cls = SCHEDULES.get(kind)
    if cls is None:
        raise ScheduleError(f"schedule: kind {kind!r} not in {tuple(SCHEDULES)}")
    step = check_positive("step", spec.get("step", 1e-5))
    thermal_step = check_positive("thermal_step", spec.get("thermal_step", 0.1))
    return cls.from_spec(spec, duration, step, thermal_step, cycle)


def cut_timeline(tl: Timeline, duration: float) -> Timeline:
    """The timeline cut at ``duration``; if it is shorter, its last interval is stretched."""
    out: list[Interval] = []
    t = 0.0
    for iv in tl.intervals:
        if t + iv.duration >= duration - 1e-12:
            d = duration - t
            if d > 1e-12:
                out.append(Interval(iv.phase, d, min(iv.step, d)))
            return Timeline(out)
        out.append(iv)
        t += iv.duration
    last = out[-1]
    out[-1] = Interval(last.phase, last.duration + duration - t, last.step)
    return Timeline(out)


@dataclass
class UsedInterval:
    """An interval as it ran: ``phase``, ``t_start`` and ``t_end`` [s], ``step`` [s], the number of ``steps``
    and the ``reason`` it ended (the automatic schedule's decision; empty for a timeline's interval)."""
    phase: str
    t_start: float
    t_end: float
    step: float
    steps: int
    reason: str = ""

    def as_dict(self) -> dict:
        """The interval as summary.json writes it."""
        return {"phase": self.phase, "t_start": self.t_start, "t_end": self.t_end, "step": self.step,
                "steps": self.steps, "reason": self.reason}


@dataclass
class RunReport:
    """What a run did: the ``timeline`` it used (:class:`UsedInterval`), ``wall_time_s`` and ``cpu_time_s``
    [s], the ``component_steps`` each component took, the time it reached ``t_end`` [s], its ``error`` (None:
    none), ``status``, a component's stop request (``stopped``) and the thermal-only ``hold``'s report."""
    timeline: list[UsedInterval] = field(default_factory=list)
    wall_time_s: float = 0.0
    #: the process's CPU time over the run (with wall_time_s: the share the machine's other load took)
    cpu_time_s: float = 0.0
    component_steps: dict[str, int] = field(default_factory=dict)
    t_end: float = 0.0
    error: str | None = None
    #: "complete", "stopped" (a component asked to stop: see ``stopped``), "failed" or "interrupted"
    status: str = "complete"
    #: ``{"component", "t_s", "reason"}`` of the stop request that ended the run, or None
    stopped: dict | None = None
    #: what the thermal-only hold measured (master/manipulator/error_estimate.py HoldReport), or None
    hold: object = None
    #: the located events (master/core/events.py), in the order they happened; None: no component of the run
    #: declares an event indicator
    events: list | None = None

    def as_dict(self) -> dict:
        """The report as summary.json writes it."""
        return {"timeline": [u.as_dict() for u in self.timeline], "wall_time_s": self.wall_time_s,
                "cpu_time_s": self.cpu_time_s, "component_steps": dict(self.component_steps), "t_end": self.t_end, "error": self.error,
                "status": self.status, "stopped": self.stopped,
                "hold": self.hold.as_dict() if self.hold is not None else None}

