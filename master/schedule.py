"""Schedules: which phase runs when, at which step (the paper's staggered scheme, section 3.2).

* ``TM`` (thermo-mechanical): every component steps at small steps;
* ``TO`` (thermal-only): components that take no part in TO are frozen, the others step at a large step,
  fed with the frozen components' outputs held at their RMS (or mean) over the last N rotor cycles of the
  previous TM interval.

A schedule is an explicit timeline, ``monolithic`` (one TM interval) or automatic (:class:`AutoSchedule`,
decided while the run goes). Every run reports the timeline it actually used.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

from rotorcosim.components.contract import ContractError, PHASES


class ScheduleError(ContractError):
    pass


def _positive(name: str, value: Any) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ScheduleError(f"schedule: {name} must be a number, got {value!r}") from None
    if not math.isfinite(x) or x <= 0.0:
        raise ScheduleError(f"schedule: {name} must be a positive finite number, got {value!r}")
    return x


@dataclass(frozen=True)
class Interval:
    phase: str
    duration: float
    step: float

    def __post_init__(self):
        if self.phase not in PHASES:
            raise ScheduleError(f"schedule: interval phase {self.phase!r} not in {PHASES}")
        _positive("interval duration", self.duration)
        _positive("interval step", self.step)
        if self.step > self.duration * (1 + 1e-12):
            raise ScheduleError(f"schedule: {self.phase} interval step {self.step} s is longer than its duration {self.duration} s")

    @property
    def steps(self) -> int:
        """Number of steps; the last one may be shortened so the interval ends exactly at its duration."""
        return max(1, math.ceil(self.duration / self.step - 1e-9))


@dataclass
class Timeline:
    """An explicit list of intervals (the paper's Fig. 8)."""

    intervals: list[Interval]

    @property
    def duration(self) -> float:
        return sum(i.duration for i in self.intervals)


@dataclass
class AutoSchedule:
    """TM until the tracked mechanical outputs are steady cycle to cycle, TO until the thermal outputs that
    feed the mechanical side have drifted by more than ``drift_tolerance`` (relative), within min/max durations."""

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

    def __post_init__(self):
        for name in ("duration", "step", "thermal_step", "steady_tolerance", "drift_tolerance",
                     "tm_min", "tm_max", "to_min", "to_max"):
            setattr(self, name, _positive(name, getattr(self, name)))
        if self.tm_min > self.tm_max or self.to_min > self.to_max:
            raise ScheduleError("schedule: minimum interval durations must not exceed the maxima")
        if int(self.steady_cycles) < 1:
            raise ScheduleError("schedule: steady_cycles must be >= 1")


def _interval_duration(spec: Mapping[str, Any], speed_rpm: float | None) -> float:
    if "duration" in spec and "cycles" in spec:
        raise ScheduleError(f"schedule: interval {dict(spec)} gives both duration and cycles")
    if "cycles" in spec:
        if not speed_rpm:
            raise ScheduleError("schedule: an interval in rotor cycles needs schedule.speed_rpm")
        return _positive("interval cycles", spec["cycles"]) * 60.0 / _positive("speed_rpm", speed_rpm)
    if "duration" not in spec:
        raise ScheduleError(f"schedule: interval {dict(spec)} needs a duration (s) or cycles")
    return _positive("interval duration", spec["duration"])


def from_spec(spec: Mapping[str, Any], duration: float | None = None) -> Timeline | AutoSchedule:
    """Build a schedule from a scenario's ``[schedule]`` table.

    ``kind = "timeline"`` with ``[[schedule.intervals]]`` (phase, duration or cycles, optional step);
    ``kind = "monolithic"`` with ``duration`` and ``step``; ``kind = "auto"`` with the AutoSchedule fields.
    ``duration`` overrides the scenario's total duration (a timeline is then cut or its last TO stretched).
    """
    known = {"kind", "duration", "step", "thermal_step", "speed_rpm", "hold", "hold_cycles", "intervals",
             "steady_tolerance", "steady_cycles", "drift_tolerance", "tm_min", "tm_max", "to_min", "to_max",
             "tracked"}
    unknown = set(spec) - known
    if unknown:
        raise ScheduleError(f"schedule: unknown key(s) {sorted(unknown)}; known: {sorted(known)}")
    kind = spec.get("kind", "monolithic")
    step = _positive("step", spec.get("step", 1e-5))
    thermal_step = _positive("thermal_step", spec.get("thermal_step", 0.1))
    speed = spec.get("speed_rpm")
    if kind == "monolithic":
        total = _positive("duration", duration if duration is not None else spec.get("duration"))
        return Timeline([Interval("TM", total, min(step, total))])
    if kind == "timeline":
        raw = spec.get("intervals")
        if not raw:
            raise ScheduleError("schedule: kind 'timeline' needs [[schedule.intervals]]")
        intervals = []
        for item in raw:
            phase = item.get("phase")
            d = _interval_duration(item, speed)
            h = item.get("step", step if phase == "TM" else thermal_step)
            intervals.append(Interval(phase, d, min(_positive("interval step", h), d)))
        tl = Timeline(intervals)
        if duration is not None:
            tl = cut_timeline(tl, _positive("duration", duration))
        return tl
    if kind == "auto":
        total = _positive("duration", duration if duration is not None else spec.get("duration"))
        kwargs = {k: spec[k] for k in ("steady_tolerance", "steady_cycles", "drift_tolerance", "tm_min",
                                       "tm_max", "to_min", "to_max", "tracked") if k in spec}
        return AutoSchedule(total, step, thermal_step, **kwargs)
    raise ScheduleError(f"schedule: kind {kind!r} not in ('timeline', 'monolithic', 'auto')")


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
    phase: str
    t_start: float
    t_end: float
    step: float
    steps: int
    reason: str = ""

    def as_dict(self) -> dict:
        return {"phase": self.phase, "t_start": self.t_start, "t_end": self.t_end, "step": self.step,
                "steps": self.steps, "reason": self.reason}


@dataclass
class RunReport:
    timeline: list[UsedInterval] = field(default_factory=list)
    wall_time_s: float = 0.0
    component_steps: dict[str, int] = field(default_factory=dict)
    t_end: float = 0.0
    error: str | None = None
    #: "complete", "stopped" (a component asked to stop: see ``stopped``), "failed" or "interrupted"
    status: str = "complete"
    #: ``{"component", "t_s", "reason"}`` of the stop request that ended the run, or None
    stopped: dict | None = None
    #: what the thermal-only hold measured (master/hold.py HoldReport), or None
    hold: object = None

    def as_dict(self) -> dict:
        return {"timeline": [u.as_dict() for u in self.timeline], "wall_time_s": self.wall_time_s,
                "component_steps": dict(self.component_steps), "t_end": self.t_end, "error": self.error,
                "status": self.status, "stopped": self.stopped,
                "hold": self.hold.as_dict() if self.hold is not None else None}
