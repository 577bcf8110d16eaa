"""The staggered scheme's thermal-only hold: ONE master concept, in this module and the three it uses.

libcosim would call it a manipulator: it changes what crosses some connections, never a component's insides.

* Which components freeze in a thermal-only (TO) interval: those that take no part in TO, and those that declare
  ``holds_state_in_TO`` (stepped in TO only to update some outputs from their frozen state, e.g. a friction
  loss at the new oil viscosity). Both are *mechanical*.
* The hand-offs (handoff.py): the connections from a mechanical component to a thermal one (the power losses),
  their windows over a thermo-mechanical (TM) interval and the values they hold over a thermal-only one.
* The error estimate (error_estimate.py): what the hold measures of its own error at each TM restart and at the
  run's end (:meth:`StaggeredHold.end`, :meth:`StaggeredHold.finish`).
* The restart (restart.py): the hand-backs, from a thermal component to a mechanical one, fade in over the first
  cycles of the TM interval after a TO interval.
"""
from __future__ import annotations

import math

import numpy as np

from rotorcosim.components.contract import COUPLED, HELD, ContractError
from rotorcosim.master.core.cycle import WINDOW_MARGIN, Cycle
from rotorcosim.master.manipulator.error_estimate import RISE_FLOOR_K, HoldReport, Pulse, replay
from rotorcosim.master.manipulator.handoff import Fired, HandOff, Held, HeldLaw, Probe
from rotorcosim.master.manipulator.restart import RESTART_CYCLES, Restart

#: the default statistic: the mean keeps the energy of a power (the RMS overstates a fluctuating one)
DEFAULT_HOLD = "mean"


def mechanical(comp) -> bool:
    """Frozen in TO, or stepped there only for its TO update with its mechanical state frozen."""
    return HELD not in comp.phases or bool(getattr(comp, "holds_state_in_TO", False))


def feeds_thermal(src, dst) -> bool:
    """True for a hand-off: a connection from a mechanical component to a thermal one (stepped in TO)."""
    return mechanical(src) and not mechanical(dst)


def feeds_mechanics(src, dst) -> bool:
    """True for a hand-back: a connection from a thermal component (stepped in TO) to a mechanical one."""
    return HELD in src.phases and not mechanical(src) and mechanical(dst)


class StaggeredHold:
    """The thermal-only hold of a system's run (see the module docstring)."""

    def __init__(self, system, links, hold: str = DEFAULT_HOLD, hold_cycles: float = 5.0,
                 cycle: Cycle | None = None, restart_cycles: float = RESTART_CYCLES):
        self.system = system
        self.restart_cycles = float(restart_cycles)
        self.handbacks: list = []
        self._tm_end: dict[int, np.ndarray] = {}   # hand-back index -> its value at the end of the last TM interval
        self._last_phase: str | None = None
        self.links = links
        self.hold = hold
        self.hold_cycles = float(hold_cycles)
        #: where the cycle period comes from (None: no cycle, no windows); read at the start of each TM interval
        self.cycle_source = cycle
        #: the period of the present TM interval's windows [s] (None before the first one)
        self.period: float | None = None
        #: the run's RevolutionCounter when the cycle has an angle (windows counted in its turns), set by the
        #: simulation; None: windows of hold_cycles periods
        self.revolutions = None
        self.handoffs: list[HandOff] | None = None
        self.report = HoldReport()
        self._to_start = 0.0
        self._to_length: float | None = None
        self._to_step = 0.0
        #: the scheduled change (a component's next_event) the last TO interval ended at, or None
        self._event: str | None = None
        #: the first event located in the running coupled interval (master/core/events.py), or None
        self._located: str | None = None
        #: per thermal component: the charged TO intervals' hand-off errors (the run's estimate replays them)
        self._pulses: dict[str, list[Pulse]] = {}
        #: "comp.port" -> the thermal components' outputs at the run's start
        self._initial: dict[str, np.ndarray] = {}
        #: "comp.port" -> the thermal components' outputs where the last TO interval started, and where the last
        #: charged one did
        self._at_to_start: dict[str, np.ndarray] = {}
        self._at_last_restart: dict[str, np.ndarray] = {}
        #: the cycle's period at the starts of the last two TM intervals
        self._tm_periods: list = []

    def _find_handoffs(self) -> None:
        """After set-up: a component may decide its phases from its parameters (whether it has a TO update)."""
        comps = self.system.components
        links = self.links
        self.handoffs = []
        for link in links:
            src, dst = comps[link.con.src_component], comps[link.con.dst_component]
            if feeds_thermal(src, dst) and link.real:   # (Integer/Boolean/String links: held at their last value)
                ports = sorted({l.con.dst_port for l in links if l.con.dst_component == link.con.src_component
                                and not mechanical(comps[l.con.src_component])})
                self.handoffs.append(HandOff(link, link.con.hold or self.hold, ports))
        self.handbacks = [link for link in links if link.real and
                          feeds_mechanics(comps[link.con.src_component], comps[link.con.dst_component])]

    def bind_revolutions(self, counter) -> None:
        """Count the windows with ``counter`` (the run's RevolutionCounter): a hold read back from a checkpoint
        holds a copy of the one it was saved with, which the resumed run's observers no longer feed."""
        self.revolutions = counter
        for ho in self.handoffs or []:
            if ho.turns is not None:
                ho.turns = (counter, *ho.turns[1:])

    @property
    def cycle(self) -> float | None:
        """The cycle period now [s], or None without a cycle source."""
        return self.cycle_source.period(self.system) if self.cycle_source is not None else None

    # -- intervals ---------------------------------------------------------------------------------------
    def start(self, phase: str, active: list[str], mult: dict[str, int], step: float, t: float = 0.0,
              steps_taken: dict[str, int] | None = None, nsteps: int | None = None) -> None:
        """Set the links up for an interval of the phase of role ``phase`` (``COUPLED`` / ``HELD``) with ``active``
        components at base step ``step`` (``nsteps`` base steps at most, if known: a ring counted in turns need
        not be longer)."""
        if self.handoffs is None:
            self._find_handoffs()
            self._initial = self._thermal_outputs()
        under_way = [link.ramp for link in self.handbacks]
        for link in self.links:
            link.held = None
            link.window = None
            link.ramp = None
        if phase == COUPLED:
            # one period for the whole interval, read where it starts (a speed signal's value there)
            cycle = self.period = self.cycle
            self._tm_periods = self._tm_periods[-1:] + [cycle]
            length = self.restart_cycles * cycle if cycle else 0.0
            if self._last_phase == HELD and length > 0.0:
                for i, link in enumerate(self.handbacks):
                    if i in self._tm_end:
                        link.ramp = Restart(self._tm_end[i] - np.array(link.src.y[link.sport], dtype=float),
                                            t, length)
            elif self._last_phase == COUPLED:  # TM after TM: a restart's ramp still under way goes on
                for link, ramp in zip(self.handbacks, under_way):
                    if ramp is not None and t < ramp.t0 + ramp.length:
                        link.ramp = ramp
            counter = self.revolutions
            if counter is not None:
                if counter.ref.partition(".")[0] not in active:
                    raise ContractError(f"cycle angle {counter.ref}: its component does not step in the coupled "
                                        "phase, so its turns cannot count the windows")
                counter.need(self.hold_cycles)
                self.report.revolutions_asked = self.hold_cycles
                comp, _, port = counter.ref.partition(".")
                angle_comp = self.system.components[comp]
                direction = self.cycle_source.direction(self.system)
                next_turn = float(angle_comp.y[port][0]) + 2.0 * math.pi * direction
            for ho in self.handoffs:
                ho.end_to()
                if cycle:
                    hs = mult.get(ho.link.con.src_component, 1) * step
                    n_cycle = int(math.ceil(cycle / hs - 1e-9))
                    size = ho.link.src.variable(ho.link.sport).size
                    if counter is None:
                        n = int(math.ceil(self.hold_cycles * cycle / hs - 1e-9))
                        ho.start_tm(n, n_cycle, size)
                    else:
                        # counted in turns: room for them at a fraction of the present speed (WINDOW_MARGIN), never
                        # more than the interval's samples
                        n = int(math.ceil(WINDOW_MARGIN * self.hold_cycles * cycle / hs - 1e-9))
                        if nsteps is not None:
                            n = min(n, nsteps // mult.get(ho.link.con.src_component, 1) + 1)
                        ho.start_tm(n, 0, size, hs, (counter, self.hold_cycles, angle_comp, port), next_turn,
                                    direction)
                    ho.link.window = ho
            return
        on = set(active)
        for link in self.links:  # inputs of stepped components from frozen ones: their last value
            if link.con.dst_component in on and link.con.src_component not in on:
                link.held = Held(link, link.src.y[link.sport])
        self._to_start, self._to_step = t, step
        self._at_to_start = self._thermal_outputs()
        probe = Probe(t, step)
        steps_taken = steps_taken if steps_taken is not None else {}
        turns = [r for r in (ho.window_revolutions() for ho in self.handoffs) if r is not None]
        if turns:
            self.report.window_revolutions.append(min(turns))
        for ho in self.handoffs:
            name, n0 = ho.link.con.src_component, steps_taken.get(ho.link.con.src_component, 0)
            group = [g for g in self.handoffs if g.link.con.dst_component == ho.link.con.dst_component]
            ho.start_to(probe, Fired(steps_taken, name, n0), max(1, int(round(self.hold_cycles))), group)
            ho.link.held = ho.held
            if isinstance(ho.held, HeldLaw):
                self.report.elasticity[f"{ho.link.con.src} -> {ho.link.con.dst}"] = ho.held.e
                d = ho.held.drive
                self.report.drivers[f"{ho.link.con.src} -> {ho.link.con.dst}"] = (
                    None if d is None else {"input": f"{d.owner.link.con.src_component}.{d.port}[{d.k}]",
                                            "slope_per_K": d.b, "window_K": d.w})

    def end(self, phase: str, t: float) -> None:
        """End of an interval at time t: after the first TM interval that follows a TO interval, the hand-off
        errors of that TO interval and the estimates (:meth:`_estimate`). A TO interval that ended at a scheduled
        change of a component (its ``next_event``: a fuel cut), or followed by a coupled interval in which an event
        was located (:meth:`located`), is not charged: the mechanics after the change are not what the held values
        stood for, and the change starts a fresh coupled interval."""
        self._last_phase = phase
        if phase == COUPLED:
            # an event located in the coupled interval after a thermal-only one is, like a scheduled change at
            # its end, no error of the hold: the mechanics after it are not what the held values stood for
            self._event, self._located = self._event or self._located, None
            self._tm_end = {i: np.array(link.src.y[link.sport], dtype=float) for i, link in enumerate(self.handbacks)}
        if phase == HELD:
            for ho in self.handoffs:
                ho.end_to()
            self._to_length = t - self._to_start
            self._event = self._scheduled_change(self._to_start, t)
            return
        if self._to_length is None:
            return
        t0, t1 = self._to_start, self._to_start + self._to_length
        self._to_length = None
        if self._event is not None:
            for ho in self.handoffs:
                ho.forget_restart()
            self.report.intervals.append({"t_start": t0, "t_end": t1, "estimate_pct": None, "event": self._event,
                                          "output": None})
            self._event = None
            return
        fresh = []
        skip, n = int(math.ceil(self.restart_cycles - 1e-9)), max(1, int(round(self.hold_cycles)))
        for ho in self.handoffs:
            if ho.measure_restart_error(skip, n):
                fresh.append(ho)
                self.report.errors[f"{ho.link.con.src} -> {ho.link.con.dst}"] = ho.error
                if ho.gains:
                    self.report.loop_share[f"{ho.link.con.src} -> {ho.link.con.dst}"] = ho.loop_share
        if fresh:
            self._estimate(fresh, t0, t1)

    def _response(self, comp, name: str, pulses: list[Pulse]) -> dict[str, np.ndarray]:
        """The response now of thermal component ``name`` to ``pulses`` (:func:`replay`), its loop at the law's
        sensitivity and at the share of it the mechanics showed (:meth:`feedback`): of the two, each output's
        larger error (the mechanics' sensitivity lies between them, and an output whose error is a difference of
        two inputs' responses may grow with a stronger loop)."""
        shared, law = self.feedback(name), self.feedback(name, shared=False)
        return replay(comp, name, pulses, comp.time, shared, [law] if law != shared else [])

    def feedback(self, name: str, shared: bool = True) -> list[tuple[str, str, int, float]]:
        """How thermal component ``name``'s inputs follow its own outputs through the mechanics, as the last TO
        laws measured it: (input port, output port, output element, dP/du) for each hand-off into it whose
        producer takes that output back (HandOff.gains; ``shared``: at the share of its law's move the mechanics
        made over the last charged TO interval, HandOff.loop_share); the error estimate's feedback
        (:func:`replay`)."""
        fed = {(l.con.dst_component, l.con.dst_port): l.sport for l in self.handbacks if l.con.src_component == name}
        out: dict[tuple[str, str, int], float] = {}
        for ho in self.handoffs or []:
            if ho.link.con.dst_component != name:
                continue
            for comp, port, k, g in ho.gains:
                o = fed.get((comp, port))
                if o is not None:
                    key = (ho.link.dport, o, k)
                    out[key] = out.get(key, 0.0) + g * (ho.loop_share if shared else 1.0)
        return [(*key, g) for key, g in out.items()]

    def located(self, name: str, t: float) -> None:
        """An event of component ``name`` located at ``t`` [s] in the running coupled interval
        (master/core/events.py): the thermal-only interval before it is not charged (:meth:`end`)."""
        if self._located is None:
            self._located = f"{name} at {t:.9g} s"

    def _scheduled_change(self, t0: float, t1: float) -> str | None:
        """The component whose scheduled change (``next_event``) falls at the end of the TO interval [t0, t1]
        (or within it), as "name at t s"; None if there is none."""
        tol = 1e-9 * max(1.0, abs(t1))
        for name, comp in self.system.components.items():
            e = getattr(comp, "next_event", lambda t: None)(t0)
            if e is not None and t0 - tol <= e <= t1 + tol:
                return f"{name} at {e:.9g} s"
        return None

    def _thermal_outputs(self) -> dict[str, np.ndarray]:
        """The Real outputs of the components that take hand-offs, "comp.port" -> values."""
        out = {}
        for name in sorted({ho.link.con.dst_component for ho in self.handoffs or []}):
            comp = self.system.components[name]
            for v in comp.variables:
                if v.causality == "output" and v.type == "Real":
                    out[f"{name}.{v.name}"] = np.array(comp.y[v.name], dtype=float).ravel()
        return out

    def _estimate(self, fresh: list[HandOff], t0: float, t1: float) -> None:
        """The interval's own estimate after the restart of the TO interval [t0, t1] (error_estimate.py's docstring, "The error
        estimate"): its hand-off errors become a pulse of input errors on each thermal component, whose response
        now the component gives by a replay (:func:`replay`)."""
        by_dst: dict[str, dict[str, np.ndarray]] = {}
        for ho in fresh:
            d = by_dst.setdefault(ho.link.con.dst_component, {})
            d[ho.link.dport] = d.get(ho.link.dport, 0.0) + ho.delta
        own: dict[str, np.ndarray] = {}
        for name, delta in by_dst.items():
            pulse = Pulse(t0, t1, self._to_step, delta)
            self._pulses.setdefault(name, []).append(pulse)
            comp = self.system.components[name]
            own.update(self._response(comp, name, [pulse]))
        worst, which = self._largest(own)
        self.report.interval_estimates_pct.append(worst)
        self.report.intervals.append({"t_start": t0, "t_end": t1, "estimate_pct": worst, "event": None,
                                      "output": which})
        self._at_last_restart = dict(self._at_to_start)

    def finish(self) -> None:
        """The run's estimate at its end (the simulation calls it after the last interval): each thermal
        component's outputs in error by the response now of every charged interval's pulse (one replay of them
        all: a later interval's error that undoes an earlier one's, as the mechanics at the erring temperatures
        do, cancels it), their rises since the run's start, their moves over the last charged interval, the
        share of that move in error of what each component hands back (``mechanics_fraction``) and the largest
        relative error of a temperature."""
        if not self._pulses:
            return
        errors: dict[str, np.ndarray] = {}
        for name, pulses in self._pulses.items():
            comp = self.system.components[name]
            errors.update(self._response(comp, name, pulses))
        present = self._thermal_outputs()
        rep = self.report
        rep.output_errors = {k: np.asarray(v, dtype=float).tolist() for k, v in errors.items()}
        rep.output_rise = {k: (v - self._initial[k]).tolist() for k, v in present.items() if k in self._initial}
        rep.output_move = {k: (present[k] - v).tolist() for k, v in self._at_last_restart.items() if k in present}
        rep.estimated_error_pct, rep.estimated_output = self._largest(errors)
        rep.handoff_errors_end, rep.handoff_errors_end_pct = self._handoff_errors(errors)
        frac: dict[str, float] = {}
        periods = self._tm_periods
        if len(periods) == 2 and periods[0] != periods[1]:
            # the speed changed between the last two TM intervals (a rundown): their results differ by more than
            # the hand-backs' move, and no share of that difference is the hold's
            rep.mechanics_fraction = {}
            return
        for link in self.handbacks:
            name = link.con.src_component
            ref = f"{name}.{link.sport}"
            err, move, rise = rep.output_errors.get(ref), rep.output_move.get(ref), rep.output_rise.get(ref)
            if err is None or move is None or not float(np.linalg.norm(move)) > 0.0:
                continue
            if link.src.variable(link.sport).unit == "K" and float(np.max(np.abs(rise))) < RISE_FLOOR_K:
                continue  # a temperature that barely moved over the run drives nothing (as RISE_FLOOR_K)
            frac[name] = max(frac.get(name, 0.0), float(np.linalg.norm(err)) / float(np.linalg.norm(move)))
        rep.mechanics_fraction = frac

    def _handoff_errors(self, errors: dict[str, np.ndarray]) -> tuple[dict[str, float], dict[str, float]]:
        """Each hand-off's power in error at the run's end by what its TO law says the erring values its producer
        takes back do to it (HandOff.power_error: its gains times their estimated errors ``errors``, "comp.port" ->
        values, a driver's at the share of the law's move the mechanics made): the
        mechanics' own power at the end, "producer.port" -> error [its unit], and that error in percent of the
        power the law held when its gains were taken (``HandOff.gains_at``); only hand-offs with a law."""
        feeds = {(l.con.dst_component, l.con.dst_port): f"{l.con.src_component}.{l.sport}" for l in self.handbacks}
        out, pct = {}, {}

        def error_of(comp, port, k):
            err = errors.get(feeds.get((comp, port), ""))
            return None if err is None else float(np.ravel(err)[k])

        for ho in self.handoffs or []:
            if not ho.gains:
                continue
            d = ho.power_error(error_of)
            key = f"{ho.link.con.src_component}.{ho.link.sport}"
            out[key] = d
            if ho.gains_at > 0.0:
                pct[key] = 100.0 * d / ho.gains_at
        return out, pct

    def _largest(self, errors: dict[str, np.ndarray]) -> tuple[float, str | None]:
        """The largest error [%] of a scalar temperature output (unit K, one element: a thermal model's reported
        temperatures; a vector of every node would let a barely warmed node rule) relative to its rise since the
        run's start (at least RISE_FLOOR_K), and its "comp.port"."""
        worst, which = 0.0, None
        for ref, err in errors.items():
            name, _, port = ref.partition(".")
            var = self.system.components[name].variable(port)
            if var.unit != "K" or var.size != 1 or ref not in self._initial:
                continue
            now = float(np.ravel(self.system.components[name].y[port])[0])
            rise = max(abs(now - float(self._initial[ref][0])), RISE_FLOOR_K)
            e = 100.0 * abs(float(err[0])) / rise
            if e > worst or which is None:
                worst, which = e, ref
        return worst, which
