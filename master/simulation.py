"""Runs a system through a schedule: intervals, phases, observers.

The staggered scheme alternates intervals of the coupled phase (every component steps) and of the held phase
(only the components that declare it step); what is frozen and held in a held interval is the hold's
(master/manipulator/hold.py). The next coupled interval resumes from the frozen state with the new values. The
scenario names its phases (master/core/phases.py; the staggered scheme's thermo-mechanical "TM" and
thermal-only "TO" by default).
"""
from __future__ import annotations

import math
import threading
import time as _time
from typing import Sequence

import numpy as np

from rotorcosim.components import registry
from rotorcosim.components.contract import COUPLED, HELD, ContractError, output_problem

from rotorcosim.master.compiled import ahead
from rotorcosim.master.compiled import choice as compiled
from rotorcosim.master.core import events
from rotorcosim.master.core.algorithm import Engine, EngineSettings, SimulationFailed
from rotorcosim.master.core.cycle import Cycle, RevolutionCounter, as_cycle
from rotorcosim.master.core.phases import Phases
from rotorcosim.master.core.system import HOLDS
from rotorcosim.master.manipulator.hold import DEFAULT_HOLD, StaggeredHold
from rotorcosim.master.manipulator.restart import RESTART_CYCLES
from rotorcosim.master.schedule.timeline import RunReport, Schedule, ScheduleError, UsedInterval
from rotorcosim.master.core.system import System

class Simulation:
    """A system run through a schedule: its coupling engine, the thermal-only hold, the observers, the clock.

    Parameters: ``system`` (:class:`~rotorcosim.master.core.system.System`); ``order``: the components' order
    of a Gauss-Seidel pass (default: the system's); ``settings``: the coupling algorithm
    (:class:`~rotorcosim.master.core.algorithm.EngineSettings`); ``steps``: component -> its own communication
    step [s] in thermo-mechanical intervals (a whole multiple of the interval's step); ``hold``: the statistic a
    thermal-only interval holds of a frozen output ("mean", "rms", "last"); ``hold_cycles``: over how many
    cycles [-] it is taken; ``cycle``: the cycle source (:mod:`rotorcosim.master.core.cycle`: a constant period
    [s] or a declared speed signal) that sets a cycle's length (needed by thermal-only intervals); ``observers``: what watches the run
    (:class:`~rotorcosim.master.observer.observer.Observer`); ``t0``: the start time [s]; ``restart_cycles``:
    cycles [-] over which the thermal inputs of the mechanical components go to their new values when a
    thermo-mechanical interval restarts; ``phases``: the
    scenario's names of its coupled and held phases (:class:`~rotorcosim.master.core.phases.Phases`; default
    "TM" and "TO"). :attr:`phase` is the role of the running interval (``COUPLED`` / ``HELD`` of the component
    contract), :attr:`phase_name` its name.

    A scenario's simulation is built by :func:`rotorcosim.master.scenario.build.build_simulation`.

    >>> from rotorcosim.components.registry import create
    >>> from rotorcosim.master.core.system import Connection, System
    >>> from rotorcosim.master.schedule import Interval, Timeline
    >>> comps = {"m1": create("testing.mass", "m1", {"m": 1.0, "k": 40.0, "x0": 0.1}),
    ...          "m2": create("testing.spring", "m2", {"m": 2.0, "k": 30.0, "kc": 100.0})}
    >>> system = System(comps, [Connection("m1.x", "m2.x_in"), Connection("m1.v", "m2.v_in"),
    ...                         Connection("m2.F", "m1.F")])
    >>> sim = Simulation(system, order=["m1", "m2"])
    >>> report = sim.run(Timeline([Interval("TM", duration=0.1, step=1e-3)]))
    >>> report.status, report.component_steps
    ('complete', {'m1': 100, 'm2': 100})
    >>> round(float(sim.value("m1.x")[0]), 4)                  # m1's position [m] at t = 0.1 s
    0.0412
    """

    def __init__(self, system: System, *, order: Sequence[str] | None = None,
                 settings: EngineSettings | None = None, steps: dict[str, float] | None = None,
                 hold: str = DEFAULT_HOLD, hold_cycles: float = 5.0, cycle: Cycle | float | None = None,
                 observers: Sequence = (), t0: float = 0.0, restart_cycles: float = RESTART_CYCLES,
                 phases: Phases | None = None):
        if hold not in HOLDS:
            raise ContractError(f"hold {hold!r} not in {HOLDS}")
        if not (hold_cycles > 0 and math.isfinite(hold_cycles)):
            raise ContractError(f"hold_cycles must be positive, got {hold_cycles}")
        if not (restart_cycles >= 0 and math.isfinite(restart_cycles)):
            raise ContractError(f"restart_cycles must be a number >= 0, got {restart_cycles}")
        self.system = system
        self.phases = phases or Phases()
        self.settings = settings or EngineSettings()
        self.engine = Engine(system, list(order or system.components), self.settings)
        self.steps = dict(steps or {})
        for name, s in self.steps.items():
            system.component(name)
            if not (s > 0 and math.isfinite(s)):
                raise ContractError(f"communication step of {name} must be positive, got {s}")
        #: where the cycle period of the hold's windows, the restart and the steadiness test comes from
        #: (master/core/cycle.py; a number is a constant period in seconds), or None: no cycle
        self.cycle_source = as_cycle(cycle)
        if self.cycle_source is not None:
            self.cycle_source.check(system)
        self.hold = StaggeredHold(system, self.engine.links, hold, hold_cycles, self.cycle_source, restart_cycles)
        #: the turns of the cycle's angle (a cycle source with ``angle``: windows counted in revolutions), or None;
        #: it watches the run as its first observer
        self.revolutions = None
        if self.cycle_source is not None and self.cycle_source.angle is not None:
            self.revolutions = self.hold.revolutions = RevolutionCounter(self.cycle_source.angle)
        self.observers = ([self.revolutions] if self.revolutions is not None else []) + list(observers)
        self.t = float(t0)
        self.t0 = float(t0)
        self.phase = None
        self.phase_name = None
        #: base steps of the current interval when it runs to its end (None: the automatic schedule may end it)
        self.interval_steps = None
        self.report = RunReport()
        self._initialised = False
        self._ahead = None
        #: set once the set-up and the first interval's compilations (or loads from the caches) are over
        self.first_compiled = threading.Event()
        self.interval_index = 0
        #: a schedule's own loop state (the automatic schedule's; a timeline's position), saved in checkpoints
        self.schedule_state = None
        #: set by checkpoint.resume: where an interrupted run continues
        self.resume_point = None
        #: "auto" (the compiled loop for a thermo-mechanical interval whenever it can run it), "python" or
        #: "compiled" (an error when it cannot); see compiled.py. engines_used: the engine of each thermo-mechanical
        #: interval (thermal-only intervals always run the generic loop)
        self.engine_choice = "auto"
        self.engine_note: str | None = None
        self.engines_used: list[str] = []
        if any(c.event_indicators for c in system.components.values()) or events.pending_time_event(
                self, [n for n, c in system.components.items() if events.split_in_coupled(c)], self.t) is not None:
            self.report.events = []

    # -- helpers ---------------------------------------------------------------------------------------
    @property
    def cycle(self) -> float | None:
        """The cycle period now [s] (None: the run has no cycle)."""
        return self.cycle_source.period(self.system) if self.cycle_source is not None else None

    def value(self, ref: str) -> np.ndarray:
        """The current value of the output ``ref`` (``"component.port"``), in the port's unit."""
        comp, _, port = ref.partition(".")
        return self.system.components[comp].y[port]

    def components_in(self, role: str) -> list[str]:
        """The components that step in the phase of ``role`` (``COUPLED`` or ``HELD``), in the engine's order."""
        return [n for n in self.engine.order if role in self.system.components[n].phases]

    def initialise(self) -> None:
        """Set the constant inputs and set up every component at the start time, in the run's order (once; :meth:`run`
        calls it); a component that reads its inputs at set-up (``inputs_at_setup``) first gets the outputs of those
        set up before it. A component that cannot start from its parameters raises a ContractError naming it."""
        if self._initialised:
            return
        by_comp: dict[str, dict] = {}
        for ref, value in self.system.inputs.items():
            comp, _, port = ref.partition(".")
            by_comp.setdefault(comp, {})[port] = value
        comps = [self.system.components[name] for name in self.engine.order]
        # a fresh machine: a helper process builds the caches' missing kernels and tables meanwhile (ahead.py)
        self._ahead = ahead.start(comps, self.engine_choice != "python")
        if self._ahead is None:
            self.first_compiled.set()
        ready: set[str] = set()
        for name, comp in zip(self.engine.order, comps):
            if name in by_comp:
                comp.set_inputs(by_comp[name])
            if getattr(comp, "inputs_at_setup", False):
                # FMI's initialisation mode: the initial outputs of the producers already set up
                comp.set_inputs({link.dport: link.value(self.t) for link in self.engine.links
                                 if link.con.dst_component == name and link.con.src_component in ready})
            try:
                comp.setup(self.t)
            except (ContractError, SimulationFailed, KeyboardInterrupt, MemoryError, OSError):
                raise
            except (RuntimeError, ArithmeticError, FloatingPointError) as exc:
                # a set-up that cannot start from the component's parameters (e.g. the balls' static equilibrium
                # under a preload of 1e300 N): an input mistake named with its component, not "a bug"
                raise ContractError(f"{name} could not be set up with its parameters: {exc}") from exc
            except Exception as exc:
                if not registry.is_plugin_class(type(comp)):
                    raise
                raise ContractError(f"{name} could not be set up with its parameters: {type(exc).__name__}: "
                                    f"{exc}") from exc
            if registry.is_plugin_class(type(comp)) and (problem := output_problem(comp)):
                raise ContractError(f"after its set-up: {problem}")
            if name in by_comp:  # setup may reset inputs to their start values
                comp.set_inputs(by_comp[name])
            ready.add(name)
        if self.engine_choice == "python":
            self.compiled_done()
        self._initialised = True

    @property
    def computed(self) -> bool:
        """True once a component has taken a step: a run that failed before computed nothing (refused at its
        start: set-up, an observer that could not open its file, a cycle with no period at the start time)."""
        return any(self.engine.steps_taken.values())

    @property
    def initialised(self) -> bool:
        """True once every component is set up (:meth:`initialise` returned): a run that failed before is one
        refused at set-up (a parameter no component starts from), with nothing computed."""
        return self._initialised

    def compiled_done(self) -> None:
        """The first compilations are over (the compiled runner's first kernels loaded, or the run ended): stop the
        helper process of a fresh machine (ahead.py) and set :attr:`first_compiled`."""
        if self._ahead is not None:
            self._ahead.close()
            self._ahead = None
        self.first_compiled.set()

    @property
    def ahead(self):
        """The helper process building the caches' missing kernels and tables on a fresh machine
        (master/compiled/ahead.py), or None."""
        return self._ahead

    def _multiples(self, names: Sequence[str], h: float) -> dict[str, int]:
        out = {}
        for n in names:
            s = self.steps.get(n)
            if s is None or self.phase == HELD:
                out[n] = 1
                continue
            m = s / h
            if m < 1 - 1e-9 or abs(m - round(m)) > 1e-6 * m:
                raise ContractError(f"communication step of {n} ({s} s) is not a whole multiple of the "
                                    f"interval step {h} s")
            out[n] = int(round(m))
        return out

    # -- one interval ----------------------------------------------------------------------------------
    def run_interval(self, phase: str, duration: float, step: float, stop=None,
                     reason: str = "") -> UsedInterval:
        """Run one interval of the phase called ``phase`` (one of :attr:`phases`' names) for ``duration`` [s] at
        base step ``step`` [s]; ``stop`` (the automatic schedule's stop test, schedule/auto.py) may end it early."""
        try:
            role = self.phases.role(phase)
        except ContractError as exc:
            raise ScheduleError(f"schedule: {exc}") from None
        self.initialise()
        self.phase, self.phase_name = role, phase
        active = self.components_in(role)
        if not active:
            raise ScheduleError(f"no component takes part in phase {phase}")
        mult = self._multiples(active, step)
        lcm = math.lcm(*mult.values())
        #: a time event this held interval ends at whose component's steps apply it (time_events_in_steps): recorded
        #: at the interval's end, as (time [s], names); a coupled interval does not record it
        at_end = None
        if role == HELD:
            # a held interval ends at a scheduled change (a fuel cut): it happens in the coupled interval after
            nxt = events.pending_time_event(self, list(self.system.components), self.t)
            tol = 1e-9 * max(1.0, self.t + duration)
            if nxt is not None and nxt[0] <= self.t + tol:
                # due where the coupled interval before ended (its last step's end): recorded there
                events.record_time(self, nxt[1], nxt[0])
                nxt = events.pending_time_event(self, list(self.system.components), self.t)
            if nxt is not None and self.t + tol < nxt[0] < self.t + duration - tol:
                duration, reason = nxt[0] - self.t, "event"
            if nxt is not None and self.t + tol < nxt[0] <= self.t + duration + tol:
                in_steps = [n for n in nxt[1] if not events.split_in_coupled(self.system.components[n])]
                at_end = (nxt[0], in_steps) if in_steps else None
        nsteps = max(1, round(duration / step))
        if lcm == 1 and abs(nsteps * step - duration) > 1e-9 * duration:
            # single rate (thermal-only intervals): keep the interval's duration exact with the nearest step
            # not larger than the one asked for, rather than a duration rounded to whole steps
            nsteps = int(math.ceil(duration / step - 1e-9))
            step = duration / nsteps
        nsteps = int(math.ceil(nsteps / lcm) * lcm)
        for comp in self.system.components.values():
            comp.enter_phase(role)
        self.hold.start(role, active, mult, step, self.t, self.engine.steps_taken, nsteps)
        self.engine.prepare(active, mult, step)
        t_start = self.t
        self.interval_steps = nsteps if stop is None else None
        for obs in self.observers:
            obs.interval_start(self, role, step)
        k = 0
        rp, self.resume_point = self.resume_point, None
        if rp is not None and rp.k:  # resumed mid-interval: the preparation above reset what the checkpoint holds
            rp.restore(self)
            k = rp.k
        # events located in the base steps (events.py; its indicators read from the state the interval goes on
        # from); without an indicator, the engine's own step unchanged
        located = events.locator(self, role, active, mult, step)
        base_step = self.engine.base_step if located is None else located.base_step
        strides = [max(1, int(getattr(obs, "stride", 1))) for obs in self.observers]
        why = reason
        if self.engine_choice not in compiled.ENGINES:
            raise ContractError(f"engine {self.engine_choice!r} not in {compiled.ENGINES}")
        if stop is not None:
            stop.check_steps = stop.cadence(lcm)   # the base steps between two of its checks
        runner = compiled.runner(self, role, active, mult, step, stop, self.engine_choice)
        if role == COUPLED:
            self.engines_used.append("compiled" if runner is not None else "python")
        try:
            while k < nsteps:
                if runner is not None:
                    # the compiled loop up to the base step of the next time event (events.py), if any
                    ke = located.time_event_step(t_start, k) if located is not None else None
                    k_end = nsteps if ke is None else min(ke[0], nsteps)
                    if k < k_end:
                        try:
                            k = runner.run(k, k_end, t_start, stop,
                                           stop.check_steps if stop is not None else 0)
                            why = runner.why or why
                        finally:
                            k = runner.k
                        if runner.why:
                            break
                    if k >= nsteps:
                        break
                    if ke is not None and ke[1] and k == ke[0]:
                        # a time event on the grid: recorded there, and the compiled loop goes on
                        located.record_due(t_start + k * step)
                        continue
                    # base step k is the generic loop's (a time event in it, or an event the compiled loop stopped
                    # at: runner.Runner.run), then the compiled loop again
                    if located is not None:
                        located.resync()
                base_step(t_start, k)
                k += 1
                self.t = t_start + k * step
                if located is not None and located.ended_at is not None:
                    # an event ended the held interval (events.py): sampled there, and a coupled interval follows
                    self.t = located.ended_at
                    for obs in self.observers:
                        obs.step(self, self.t)
                    why = "event"
                    break
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
                    if k % stop.check_steps == 0:
                        found = stop.check(self, self.t)
                        if found:  # otherwise the interval keeps the reason it was given (its maximum reached)
                            why = found
                            break
            self.engine.check_finite(self.t)
        finally:
            used = UsedInterval(phase, t_start, self.t, step, k, why)
            if k:
                self.report.timeline.append(used)
            self.report.t_end = self.t
            self.report.component_steps = dict(self.engine.steps_taken)
        if at_end is not None and events.near(self.t, at_end[0]):
            # the held interval reached the time event (no earlier event or stop ended it): its components apply it
            # in their first coupled step from here, and it is recorded here
            events.record_time(self, at_end[1], at_end[0])
        self.hold.end(role, self.t)
        self.report.hold = self.hold.report
        for obs in self.observers:
            obs.interval_end(self, used)
        return used

    # -- whole runs ------------------------------------------------------------------------------------
    def run(self, schedule: Schedule) -> RunReport:
        """Run ``schedule``. The components are initialised first, so the first recorded sample (at t0) holds
        the outputs after initialisation. A stop request of a component ends the run early and cleanly:
        ``report.status`` is then ``"stopped"`` and ``report.stopped`` names the component and the time."""
        t_wall, t_cpu = _time.perf_counter(), _time.process_time()
        error = None
        started: list = []
        try:
            self.initialise()
            first = 0
            if self.resume_point is not None:  # checkpoint.py: an interrupted run continues where it was saved
                self.resume_point.restore(self)
                first = self.resume_point.interval
            for obs in self.observers:
                started.append(obs)   # one whose start fails may hold something half-open: it is ended too
                obs.start(self, schedule)
            schedule.run(self, first)
            self.hold.finish()
            self.report.hold = self.hold.report
            self.report.status = "stopped" if self.report.stopped else "complete"
        except BaseException as exc:
            error = exc
            self.report.error = f"{type(exc).__name__}: {exc}"
            self.report.status = "interrupted" if isinstance(exc, KeyboardInterrupt) else "failed"
            raise
        finally:
            self.compiled_done()
            self.report.wall_time_s = _time.perf_counter() - t_wall
            self.report.cpu_time_s = _time.process_time() - t_cpu
            failure = None
            # every observer started closes what it holds, even when one of them fails; one never started holds
            # nothing (ending it would report a second, meaningless error after a failure at set-up)
            for obs in started:
                try:
                    obs.end(self, error)
                except Exception as exc:
                    failure = failure or exc
            if failure is not None and error is None:
                raise failure
        return self.report


def engine_summary(sim: Simulation) -> dict:
    """Which engine ran the thermo-mechanical intervals (for the run's summary): ``engine`` "compiled",
    "python" or "mixed" (none ran: None), and ``engine_note`` why the generic loop ran where it did."""
    used = set(sim.engines_used)
    engine = None if not used else (used.pop() if len(used) == 1 else "mixed")
    return {"engine": engine, "engine_requested": sim.engine_choice,
            "engine_note": sim.engine_note if "python" in sim.engines_used else None}
