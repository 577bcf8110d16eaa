"""Runs a system through a schedule: intervals, phases, observers.

The staggered scheme of the paper (section 3.2) alternates thermo-mechanical (TM) and thermal-only (TO)
intervals; what is frozen and held in a TO interval is the thermal-only hold's (master/hold.py). The next TM
interval resumes from the frozen state with the new temperatures.
"""
from __future__ import annotations

import math
import time as _time
from typing import Callable, Sequence

import numpy as np

from rotorcosim.components.contract import ContractError

from .algorithm import Engine, EngineSettings, SimulationDiverged
from .hold import DEFAULT_HOLD, HOLDS, StaggeredHold, feeds_thermal
from .schedule import AutoSchedule, Interval, RunReport, ScheduleError, Timeline, UsedInterval
from .system import System

#: floors of the relative drift test of the automatic schedule, by unit (a change smaller than this is no drift)
DRIFT_FLOORS = {"K": 0.5, "m": 1e-7, "Pa.s": 1e-4, "W": 1.0, "N": 1.0}


class Simulation:
    def __init__(self, system: System, *, order: Sequence[str] | None = None,
                 settings: EngineSettings | None = None, steps: dict[str, float] | None = None,
                 hold: str = DEFAULT_HOLD, hold_cycles: float = 5.0, speed_rpm: float | None = None,
                 observers: Sequence = (), t0: float = 0.0):
        if hold not in HOLDS:
            raise ContractError(f"hold {hold!r} not in {HOLDS}")
        if not (hold_cycles > 0 and math.isfinite(hold_cycles)):
            raise ContractError(f"hold_cycles must be positive, got {hold_cycles}")
        if speed_rpm is not None and not (speed_rpm > 0 and math.isfinite(speed_rpm)):
            raise ContractError(f"speed_rpm must be positive, got {speed_rpm}")
        self.system = system
        self.settings = settings or EngineSettings()
        self.engine = Engine(system, list(order or system.components), self.settings)
        self.steps = dict(steps or {})
        for name, s in self.steps.items():
            system.component(name)
            if not (s > 0 and math.isfinite(s)):
                raise ContractError(f"communication step of {name} must be positive, got {s}")
        self.speed_rpm = speed_rpm
        self.hold = StaggeredHold(system, self.engine.links, hold, hold_cycles, speed_rpm)
        self.observers = list(observers)
        self.t = float(t0)
        self.t0 = float(t0)
        self.phase = None
        self.report = RunReport()
        self._initialised = False
        self.interval_index = 0
        #: set by checkpoint.resume: where an interrupted run continues
        self.resume_point = None

    # -- helpers ---------------------------------------------------------------------------------------
    @property
    def cycle(self) -> float | None:
        return 60.0 / self.speed_rpm if self.speed_rpm else None

    def value(self, ref: str) -> np.ndarray:
        comp, _, port = ref.partition(".")
        return self.system.components[comp].y[port]

    def components_in(self, phase: str) -> list[str]:
        return [n for n in self.engine.order if phase in self.system.components[n].phases]

    def initialise(self) -> None:
        if self._initialised:
            return
        by_comp: dict[str, dict] = {}
        for ref, value in self.system.inputs.items():
            comp, _, port = ref.partition(".")
            by_comp.setdefault(comp, {})[port] = value
        for name in self.engine.order:
            comp = self.system.components[name]
            if name in by_comp:
                comp.set_inputs(by_comp[name])
            comp.setup(self.t)
            if name in by_comp:  # setup may reset inputs to their start values
                comp.set_inputs(by_comp[name])
        self._initialised = True

    def _multiples(self, names: Sequence[str], h: float) -> dict[str, int]:
        out = {}
        for n in names:
            s = self.steps.get(n)
            if s is None or self.phase == "TO":
                out[n] = 1
                continue
            m = s / h
            if m < 1 - 1e-9 or abs(m - round(m)) > 1e-6 * m:
                raise ContractError(f"communication step of {n} ({s} s) is not a whole multiple of the "
                                    f"interval step {h} s")
            out[n] = int(round(m))
        return out

    # -- one interval ----------------------------------------------------------------------------------
    def run_interval(self, phase: str, duration: float, step: float, stop: "_StopTest | None" = None,
                     reason: str = "") -> UsedInterval:
        """Run one interval of ``phase``; ``stop`` (automatic schedule) may end it early."""
        self.initialise()
        self.phase = phase
        active = self.components_in(phase)
        if not active:
            raise ScheduleError(f"no component takes part in phase {phase}")
        mult = self._multiples(active, step)
        lcm = math.lcm(*mult.values())
        nsteps = max(1, round(duration / step))
        if lcm == 1 and abs(nsteps * step - duration) > 1e-9 * duration:
            # single rate (thermal-only intervals): keep the interval's duration exact with the nearest step
            # not larger than the one asked for, rather than a duration rounded to whole steps
            nsteps = int(math.ceil(duration / step - 1e-9))
            step = duration / nsteps
        nsteps = int(math.ceil(nsteps / lcm) * lcm)
        for comp in self.system.components.values():
            comp.enter_phase(phase)
        self.hold.start(phase, active, mult, step, self.t, self.engine.steps_taken)
        self.engine.prepare(active, mult, step)
        t_start = self.t
        for obs in self.observers:
            obs.interval_start(self, phase, step)
        k = 0
        rp, self.resume_point = self.resume_point, None
        if rp is not None and rp.k:  # resumed mid-interval: the preparation above reset what the checkpoint holds
            rp.restore(self)
            k = rp.k
        strides = [max(1, int(getattr(obs, "stride", 1))) for obs in self.observers]
        why = reason
        try:
            while k < nsteps:
                self.engine.base_step(t_start, k)
                k += 1
                self.t = t_start + k * step
                req = self.engine.stop
                if req is not None:
                    # a component asked to stop: the run ends at the time it asked for, sampled there
                    self.t = req.t_stop
                    self.report.stopped = {"component": req.component, "t_s": req.t_stop, "reason": req.reason}
                    for obs in self.observers:
                        obs.step(self, self.t)
                    why = "stopped"
                    break
                for obs, stride in zip(self.observers, strides):
                    if k % stride == 0:
                        obs.step(self, self.t)
                if stop is not None:
                    stop.sample(self)
                    if k % stop.every == 0 and k % lcm == 0:
                        why = stop.check(self, self.t) or ""
                        if why:
                            break
            self.engine.check_finite(self.t)
        finally:
            used = UsedInterval(phase, t_start, self.t, step, k, why)
            if k:
                self.report.timeline.append(used)
            self.report.t_end = self.t
            self.report.component_steps = dict(self.engine.steps_taken)
        self.hold.end(phase)
        self.report.hold = self.hold.report
        for obs in self.observers:
            obs.interval_end(self, used)
        return used

    # -- whole runs ------------------------------------------------------------------------------------
    def run(self, schedule: Timeline | AutoSchedule) -> RunReport:
        """Run ``schedule``. The components are initialised first, so the first recorded sample (at t0) holds
        the outputs after initialisation. A stop request of a component ends the run early and cleanly:
        ``report.status`` is then ``"stopped"`` and ``report.stopped`` names the component and the time."""
        t_wall = _time.perf_counter()
        error = None
        try:
            if isinstance(schedule, Timeline) and any(iv.phase == "TO" for iv in schedule.intervals) \
                    and not self.speed_rpm:
                raise ScheduleError("a schedule with thermal-only intervals needs speed_rpm (the rotor cycle "
                                    "over which the held outputs are averaged)")
            self.initialise()
            first = 0
            if self.resume_point is not None:  # checkpoint.py: an interrupted run continues where it was saved
                self.resume_point.restore(self)
                first = self.resume_point.interval
            for obs in self.observers:
                obs.start(self, schedule)
            if isinstance(schedule, Timeline):
                for i, iv in enumerate(schedule.intervals[first:], first):
                    self.interval_index = i
                    self.run_interval(iv.phase, iv.duration, iv.step)
                    if self.report.stopped:
                        break
            else:
                self._run_auto(schedule)
            self.report.status = "stopped" if self.report.stopped else "complete"
        except BaseException as exc:
            error = exc
            self.report.error = f"{type(exc).__name__}: {exc}"
            self.report.status = "interrupted" if isinstance(exc, KeyboardInterrupt) else "failed"
            raise
        finally:
            self.report.wall_time_s = _time.perf_counter() - t_wall
            failure = None
            for obs in self.observers:  # every observer closes what it holds, even when one of them fails
                try:
                    obs.end(self, error)
                except Exception as exc:
                    failure = failure or exc
            if failure is not None and error is None:
                raise failure
        return self.report

    def _run_auto(self, sch: AutoSchedule) -> None:
        if not self.speed_rpm:
            raise ScheduleError("the automatic schedule needs speed_rpm (its steadiness test works cycle by cycle)")
        end = self.t0 + sch.duration
        eps = 1e-9
        while self.t < end - eps:
            remaining = end - self.t
            if remaining <= sch.tm_max + sch.to_min:
                # no room left for a thermal-only interval: one thermo-mechanical interval to the end (stopping
                # it early when steady would only start another one)
                self.run_interval("TM", remaining, sch.step, reason="end")
                break
            self.run_interval("TM", sch.tm_max, sch.step, _SteadyTest(self, sch), reason="tm_max")
            if self.report.stopped:
                break
            remaining = end - self.t
            if remaining <= eps:
                break
            # keep room for a final thermo-mechanical interval, where the results are read
            d_to = min(sch.to_max, remaining - sch.tm_max)
            if d_to < sch.to_min:
                continue
            self.run_interval("TO", d_to, sch.thermal_step, _DriftTest(self, sch), reason="to_max")
            if self.report.stopped:
                break


class _StopTest:
    every = 1

    def sample(self, sim: Simulation) -> None:
        pass

    def check(self, sim: Simulation, t: float) -> str | None:
        return None


class _SteadyTest(_StopTest):
    """Steady when the RMS of the tracked outputs over a rotor cycle changes by less than the tolerance
    (relative) for ``steady_cycles`` consecutive cycles, after ``tm_min``."""

    def __init__(self, sim: Simulation, sch: AutoSchedule):
        self.sch = sch
        comps = sim.system.components
        self.refs = list(sch.tracked) or sorted({l.con.src for l in sim.engine.links if feeds_thermal(
            comps[l.con.src_component], comps[l.con.dst_component])})
        for r in self.refs:
            sim.system._port(r, "output")
        self.every = max(1, int(round(sim.cycle / sch.step)))
        self.t_begin = sim.t
        self.acc = None
        self.n = 0
        self.last = None
        self.steady = 0

    def sample(self, sim):
        if not self.refs:
            return
        vals = np.concatenate([np.ravel(sim.value(r)) for r in self.refs])
        self.acc = vals * vals if self.acc is None else self.acc + vals * vals
        self.n += 1

    def check(self, sim, t):
        if self.acc is None:
            return "steady" if t - self.t_begin >= self.sch.tm_min - 1e-12 else None
        rms = np.sqrt(self.acc / self.n)
        self.acc, self.n = None, 0
        if self.last is not None:
            scale = np.maximum(np.abs(self.last), 1e-12)
            change = float(np.max(np.abs(rms - self.last) / scale))
            self.steady = self.steady + 1 if change < self.sch.steady_tolerance else 0
        self.last = rms
        if t - self.t_begin >= self.sch.tm_min - 1e-12 and self.steady >= self.sch.steady_cycles:
            return "steady"
        return None


class _DriftTest(_StopTest):
    """Ends a thermal-only interval when an output of a thermal component that feeds a frozen (mechanical)
    component has drifted from its value at the interval start by more than the tolerance, after ``to_min``."""

    def __init__(self, sim: Simulation, sch: AutoSchedule):
        self.sch = sch
        comps = sim.system.components
        self.refs = sorted({l.con.src for l in sim.engine.links
                            if feeds_thermal(comps[l.con.dst_component], comps[l.con.src_component])})
        self.start = {r: np.array(sim.value(r), dtype=float) for r in self.refs}
        self.floors = {r: DRIFT_FLOORS.get(sim.system._port(r, "output").unit, 0.0) for r in self.refs}
        self.t_begin = sim.t

    def check(self, sim, t):
        if t - self.t_begin < self.sch.to_min - 1e-12:
            return None
        for r in self.refs:
            d = np.abs(sim.value(r) - self.start[r])
            if np.any(d > self.sch.drift_tolerance * np.abs(self.start[r]) + self.floors[r]):
                return f"drift of {r}"
        return None
