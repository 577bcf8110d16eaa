"""Discrete events of an interval: located in time, handed to their component, recorded.

A component may declare event indicators (contract ``event_indicators``, as FMI 3.0's): real functions of its state
and inputs, read after each step (``indicators()``), whose change of sign over a step is an event. A coupled
interval with such a component runs its base steps through an :class:`EventLocator`:

* before each base step it saves every active component (``get_state``, the snapshot the checkpoints and the
  iterative coupling use) and the links' state; after the step it reads the indicators;
* where one changed sign over the step [t, t + h], the event lies inside it. The locator goes back to t and steps
  the whole system from t over a shorter step tau (every component one step of length tau, the links as in a base
  step), bisecting tau until the bracket [tau_lo, tau_hi] (sign kept at tau_lo, changed at tau_hi) is no wider
  than the smallest ``event_tolerance()`` of the components whose indicator changed;
* the system then stands at t + tau_hi, just past the event: each of those components gets ``update_discrete``
  (its discrete state and the outputs that follow it change: a fuse's soft path), the event is recorded, and the
  base step is completed from there to t + h (an event in that remainder is located the same way). The base
  steps' grid, the observers' samples and the schedule are those of a run without events.

The event's time is t + tau_hi: at most one tolerance after the zero of the co-simulated indicator (the zero as
the coupled steps see it: the Gauss-Seidel coupling of a step of length tau). Bisection rather than a secant: the
indicator is known only through steps of the whole coupled system, which can bend it within the step (an input
held over the step, a contact switching on), and bisection's count is fixed in advance, log2(h / tolerance)
re-steps (8 for a 20 us step at 0.1 us).

Time events (a component's ``next_event``: the spool's fuel cut) go through the same locator in coupled intervals:
the base step that holds one is split at it (a single-rate interval; else it is applied at that step's end), one on
the grid is taken at the start of its step (the compiled loop runs to it and goes on), ``update_discrete(t, [])``
is called and the event recorded (``trigger`` "time"). A component whose own steps apply its time events
(``time_events_in_steps``: a change its steps apply from the end of the step that holds it) is left out of
this: a coupled interval runs its steps unchanged over its event and records nothing. A held interval ends
at a time event of any component (master/simulation.py; one of those is recorded there) and at a located event of
a component that steps in it (:attr:`EventLocator.ended_at`); a coupled interval follows (master/schedule).

In a multi-rate interval only the components at the base step are re-stepped (a slower one steps once per window,
at its end): the locator saves them and the slower ones whose window ends with the base step, and where an event
splits the base step those step once at its end, after the others (:meth:`EventLocator._locate`). At an event the
links that extrapolate the component's outputs restart their history (links.restart_history: the consumer's next
step holds the value after the jump).

What it needs: the components with a live indicator at the interval's base step (one stepping slower is refused
with the reason) and explicit coupling (one pass per step). A hand-off window of the thermal-only hold records the
base step's end only (the first, rolled back step's sample is replaced by the completed step's, at the same
time). The compiled loop runs such an interval too when the
components' kernels report their indicators' changes of sign (``KernelComponent.KERNEL_EVENTS``, status ``EVENT``):
it stops at the base step of an event, rolled back to its start (master/compiled/runner.py), the locator takes
that step (:meth:`EventLocator.resync` first: the compiled loop stepped the components since) and the compiled
loop goes on; a component whose kernel does not report them makes the interval the generic loop's, which
summary.json ``engine_note`` says (master/compiled/choice.why_not). A run with no indicator never builds a
locator: its base steps are the engine's own, untouched. A component that only takes part in coupled intervals
(a support fuse) is frozen in a held one, where its indicator cannot change.
"""
from __future__ import annotations

import numpy as np

from rotorcosim.components.contract import COUPLED, Component, ContractError
from rotorcosim.master.core import links

#: the most bisections of a step an event's location may take: a tolerance below step x 2^-MAX_BISECTIONS is
#: refused. Float64 resolves about 2^-52 of a step's length: finer, the bracket would stop shrinking and the
#: bisection never end (a tolerance of 1e-300 s did not).
MAX_BISECTIONS = 48


def timed(comp) -> bool:
    """Does the component schedule changes of its own (``next_event``: the spool's fuel cut)?"""
    return type(comp).next_event is not Component.next_event


def split_in_coupled(comp) -> bool:
    """Does a coupled interval take the component's time events (split the base step that holds one, record it)?
    Not for a component whose own steps apply them (``time_events_in_steps``): there only a held interval ends at
    one, and records it (master/simulation.py)."""
    return timed(comp) and not comp.time_events_in_steps


def pending_time_event(sim, names, t: float):
    """The first time event still to come at ``t`` [s] of the components ``names`` (``next_event``, not yet
    recorded in ``sim.report.events``), as (time [s], the names of the components whose event it is), or None."""
    comps = sim.system.components
    done = {(e["component"], e["t_s"]) for e in sim.report.events or () if e.get("trigger") == "time"}
    found = []
    for n in names:
        c = comps[n]
        if not timed(c):
            continue
        te = c.next_event(t)
        if te is not None and (n, te) not in done:
            found.append((float(te), n))
    if not found:
        return None
    first = min(te for te, _ in found)
    return first, [n for te, n in found if near(te, first)]


def near(a: float, b: float) -> bool:
    """Equal up to the round-off of interval ends (sums of steps)."""
    return abs(a - b) <= 1e-9 * max(1.0, abs(b))


class EventLocator:
    """The base steps of an interval with event indicators or time events (module docstring). ``sim``: the
    :class:`~rotorcosim.master.simulation.Simulation`; ``role``: the interval's (``COUPLED`` or ``HELD``);
    ``active``, ``mult``: its components and their step multiples; ``step``: the base step [s]. Located events go
    to ``sim.report.events`` and to the hold (``sim.hold.located``); :attr:`ended_at`: where an event ended a held
    interval (None: it goes on)."""

    def __init__(self, sim, role: str, active, mult, step: float):
        comps = sim.system.components
        self.sim, self.engine, self.h, self.role = sim, sim.engine, float(step), role
        self.watched = [(n, comps[n]) for n in active if comps[n].event_indicators]
        self.timed = [n for n in active if split_in_coupled(comps[n])] if role == COUPLED else []
        names = ", ".join(n for n, _ in self.watched)
        multi = sorted(n for n in active if mult.get(n, 1) != 1)
        #: base steps can be split at a time event (a single-rate interval with explicit coupling); else the
        #: component applies it within its own step, and it is recorded at its time
        self.split = not multi and self.engine.settings.iterations == 1
        #: the components at the base step (the event location re-steps them) and those slower, each with its
        #: step multiple (they step at the end of a split base step that ends one of their windows)
        self.fast = [n for n in self.engine.active if mult.get(n, 1) == 1]
        self.slow = [(n, int(mult[n])) for n in self.engine.active if mult.get(n, 1) != 1]
        slow_live = [n for n, c in self.watched if mult.get(n, 1) != 1 and len(c.indicators())]
        if slow_live:
            raise ContractError(f"event indicators of {', '.join(slow_live)}: a component whose event the master "
                                "locates must step at the interval's step (it is re-stepped within a base step); "
                                f"{', '.join(slow_live)} step(s) slower")
        self.watched = [(n, c) for n, c in self.watched if mult.get(n, 1) == 1]
        if self.engine.settings.iterations != 1 and self.watched:
            raise ContractError(f"event indicators of {names}: the master locates events with explicit coupling "
                                "([algorithm] iterations = 1)")
        self.tolerance = {}
        for n, c in self.watched:
            tol = c.event_tolerance()
            if not (0.0 < tol <= step):
                raise ContractError(f"{n}.event_tolerance: {tol!r} s must be within (0, {step:g} s], the step "
                                    "of the interval it is located in")
            if tol < step * 2.0 ** -MAX_BISECTIONS:
                raise ContractError(f"{n}.event_tolerance: {tol!r} s is below {step * 2.0 ** -MAX_BISECTIONS:.3g} s, "
                                    f"the step {step:g} s bisected {MAX_BISECTIONS} times (a float64 time resolves "
                                    "no finer within a step)")
            self.tolerance[n] = tol
        self.comps = [(n, comps[n]) for n in self.engine.active]
        self._fast_comps = [(n, comps[n]) for n in self.fast]
        self.g = self._values()
        self.ended_at: float | None = None

    def resync(self) -> None:
        """Read the indicators again from the components' present state (the compiled loop stepped them since)."""
        self.g = self._values()

    def time_event_step(self, t0: float, k: int) -> tuple[int, bool] | None:
        """Where the next time event falls in the interval that starts at ``t0`` [s], from base step ``k`` on:
        (j, True) at the start of base step j (on the grid: the compiled loop runs to it, :meth:`record_due`
        records it and the compiled loop goes on), (j, False) inside base step j (the compiled loop stops before
        it, and :meth:`base_step` splits it); None: none to come."""
        nxt = pending_time_event(self.sim, self.timed, t0 + k * self.h)
        if nxt is None:
            return None
        x = (nxt[0] - t0) / self.h
        m = int(round(x))
        if m >= k and near(nxt[0], t0 + m * self.h):
            return m, True
        # step j spans (t0 + j h, t0 + (j + 1) h]
        return max(k, int(np.ceil(x - 1e-9)) - 1), False

    def record_due(self, t: float) -> None:
        """Record the time events due at ``t`` [s], the start of a base step (nothing to split)."""
        nxt = pending_time_event(self.sim, self.timed, t)
        if nxt is not None and (nxt[0] <= t or near(nxt[0], t)):
            record_time(self.sim, nxt[1], nxt[0])

    def _values(self) -> list[list[float]]:
        return [np.asarray(c.indicators(), dtype=float).tolist() for _, c in self.watched]

    def _crossed(self, g: list[list[float]]) -> list[tuple[int, list[int]]]:
        """(watched component's position, its indicators' positions) whose sign changed from ``self.g`` to ``g``."""
        out = []
        for i, (old, new) in enumerate(zip(self.g, g)):
            # (an indicator that went out, or came back, crossed nothing)
            which = [j for j, (a, b) in enumerate(zip(old, new)) if (a < 0.0) != (b < 0.0)] if len(old) == len(new) else []
            if which:
                out.append((i, which))
        return out

    def _save(self, comps):
        """What a base step from here changes: the components ``comps`` ((name, component): those that step in
        it), the links' state and the steps taken."""
        eng = self.engine
        return (comps, [c.get_state() for _, c in comps],
                [(link.state[:], link.vectors[:]) for link in eng.links], dict(eng.steps_taken))

    def _restore(self, saved) -> None:
        comps, states, links, steps = saved
        for (_, c), s in zip(comps, states):
            c.set_state(s)
        for link, (m, v) in zip(self.engine.links, links):
            link.state[:] = m
            link.vectors[:] = v
        self.engine.steps_taken.update(steps)

    def _step(self, t: float, tau: float, windows: bool, end: float | None = None) -> None:
        """The components at the base step one step from ``t`` over ``tau`` [s] (``end``: the base step's end it
        reaches, exactly); the hold's hand-off windows record it only with ``windows`` (a step that ends on the base
        steps' grid)."""
        eng = self.engine
        kept = []
        if not windows:
            kept = [(link, link.window) for link in eng.links if link.window is not None]
            for link, _ in kept:
                link.window = None
        try:
            eng.partial_step(t, tau, self.fast, t_end=end)
        finally:
            for link, w in kept:
                link.window = w

    def base_step(self, t0: float, k: int) -> None:
        """Base step ``k`` of the interval that starts at ``t0`` (the engine's), with its events located: a time
        event in it splits it there (a single-rate interval), an indicator's change of sign is bisected."""
        h = self.h
        a, b = t0 + k * h, t0 + (k + 1) * h
        nxt = pending_time_event(self.sim, self.timed, a) if self.timed else None
        # (an event at the step's end is the next step's, at its start: the sample at the end precedes it)
        if nxt is not None and nxt[0] < b and not near(nxt[0], b):
            te, names = nxt
            if te <= a or near(te, a):
                self._record_time(names, te)
                self._span(a, b, (t0, k))
            elif not self.split:
                # a multi-rate interval: applied at the end of the step that holds it (by the component within its
                # own step, or by update_discrete there), recorded at its time
                self._span(a, b, (t0, k))
                self._record_time(names, te)
            else:
                self._span(a, te, None, windows=False)
                self._record_time(names, te)
                self._span(te, b, None, windows=True)
            return
        self._span(a, b, (t0, k))

    def _span(self, a: float, b: float, base, windows: bool = True) -> None:
        """The system from ``a`` to ``b`` [s] in one step (``base``: (t0, k), the engine's base step k), its
        indicators' changes of sign located within."""
        if not any(self.g):
            # no live indicator (components.contract: indicators): nothing to go back for
            self._advance(a, b, base, windows)
            self.g = self._values()
            return
        # the slow components that step at this base step's end (a multi-rate interval): saved with the fast ones
        due = [] if base is None else [n for n, m in self.slow if (base[1] + 1) % m == 0]
        comps = self.engine.system.components
        saved = self._save(self._fast_comps + [(n, comps[n]) for n in due])
        self._advance(a, b, base, windows)
        g = self._values()
        crossed = self._crossed(g)
        if not crossed:
            self.g = g
            return
        self._locate(saved, a, b, crossed, windows, due)

    def _advance(self, a, b, base, windows) -> None:
        if base is not None:
            self.engine.base_step(*base)
        else:
            self._step(a, b - a, windows)

    def _locate(self, saved, a: float, b: float, crossed, windows: bool = True, due=()) -> None:
        """The system stepped from ``a`` (state ``saved``) to ``b`` [s] and the indicators ``crossed`` changed sign:
        find the first event, hand it over, complete the step to ``b``; again while the remainder has one. The
        components at the base step are re-stepped; the slow ones ``due`` (a multi-rate interval: those whose
        window ends at ``b``) step once at ``b``, after the fast ones have reached it. In a held interval the event
        ends it (:attr:`ended_at`): the step is not completed."""
        whole = True  # the state is still the first step's to b (the slow ones stepped in it)
        while True:
            tol = min(self.tolerance[self.watched[i][0]] for i, _ in crossed)
            lo, hi, at_hi = 0.0, b - a, True
            while hi - lo > tol:
                mid = 0.5 * (lo + hi)
                self._restore(saved)
                whole = False
                self._step(a, mid, windows=False)
                found = self._crossed(self._values())
                if found:
                    hi, at_hi, crossed = mid, True, found
                else:
                    lo, at_hi = mid, False
            t_event = a + hi
            at_end = b - t_event <= 1e-12 * max(1.0, abs(b))
            if not at_hi:
                self._restore(saved)
                whole = False
                self._step(a, hi, windows=at_end and windows, end=b if at_end else None)
            for i, which in crossed:
                name, comp = self.watched[i]
                self._record(name, comp, t_event, which)
            self.g = self._values()
            if self.role != COUPLED:
                self.ended_at = t_event
                return
            if at_end:
                break
            saved = self._save(self._fast_comps)
            whole = False
            self._step(t_event, b - t_event, windows=windows, end=b)
            g = self._values()
            crossed = self._crossed(g)
            if not crossed:
                self.g = g
                break
            a = t_event
        if not whole:
            self.engine.fire(due, b)

    def _append(self, entry: dict) -> None:
        append(self.sim, entry)

    def _record(self, name: str, comp, t: float, which: list[int]) -> None:
        what = comp.update_discrete(t, which)
        # its outputs may jump here: the links that extrapolate them restart their history from the new values
        for link in self.engine.links:
            if link.src is comp and link.real and link.produce_kind == links.PROD_HIST:
                links.restart_history(comp.y[link.sport], 0, link.vectors, 0, link.n, link.state, t)
        kind = what.get("kind", "event")
        indicators = [comp.event_indicators[j] for j in which]
        self._append({
            "t_s": t, "component": name, "kind": kind, "indicators": indicators,
            "values": what.get("values", {}), "tolerance_s": self.tolerance[name],
            "message": f"{name}: {kind} at t = {t:.9g} s (event indicator {', '.join(indicators)}, located within "
                       f"{self.tolerance[name]:.3g} s)"})

    def _record_time(self, names: list[str], t: float) -> None:
        record_time(self.sim, names, t)


def append(sim, entry: dict) -> None:
    """An event into the run's report (``sim.report.events``) and the hold's (``located``)."""
    if sim.report.events is None:
        sim.report.events = []
    sim.report.events.append(entry)
    sim.hold.located(entry["component"], entry["t_s"])


def record_time(sim, names: list[str], t: float) -> None:
    """The time event of the components ``names`` at ``t`` [s]: ``update_discrete(t, [])`` (FMI 3.0's time event)
    and the record (``trigger`` "time", no indicator, located exactly)."""
    for name in names:
        comp = sim.system.components[name]
        what = comp.update_discrete(t, [])
        kind = what.get("kind", "time")
        append(sim, {
            "t_s": t, "component": name, "kind": kind, "indicators": [], "trigger": "time",
            "values": what.get("values", {}), "tolerance_s": 0.0,
            "message": f"{name}: {kind} at t = {t:.9g} s (time event)"})


def locator(sim, role: str, active, mult, step: float) -> EventLocator | None:
    """The interval's :class:`EventLocator`, or None (no active component with an event indicator and, in a
    coupled interval, no time event to come: the engine's base steps run as they are)."""
    comps = sim.system.components
    watched = [n for n in active if comps[n].event_indicators]
    if not watched and (role != COUPLED or pending_time_event(
            sim, [n for n in active if split_in_coupled(comps[n])], sim.t) is None):
        return None
    return EventLocator(sim, role, active, mult, step)
