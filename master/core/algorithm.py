"""Co-simulation algorithms: fixed-step Jacobi and Gauss-Seidel (classes behind a registry), multi-rate, optional
iterative coupling.

The master advances in base steps of size ``h``. Component ``c`` has a communication step ``n_c * h``; it fires
at the end of each of its windows, i.e. at base step ``k`` when ``(k + 1) % n_c == 0``, stepping over
``[t_{k+1} - n_c h, t_{k+1}]``. Within a base step, components fire in the given order (Gauss-Seidel: each
sees the outputs its predecessors have just produced) or all from the outputs at the start of the base step
(Jacobi). Ordering the fast components first lets a slow consumer see the whole of its window.

Inputs crossing rates (per connection):
* fast producer -> slow consumer: the mean (or RMS) of the producer's outputs over the consumer's window,
  weighted by the producer's step, so that a power signal (itself a step mean) delivers its exact energy;
* slow producer -> fast consumer: hold the last output, or extrapolate linearly from the last two outputs to
  the middle of the consumer's step;
* ``linear-end`` (any rate but fast -> slow): extrapolate linearly to the END of the consumer's step, for a
  consumer that enforces equilibrium there with the held input (Newmark): the one-step lag of a Gauss-Seidel
  feedback becomes second order. Not meant for iterative coupling (a repeated step would shift its history),
  and unstable on stiff contact forces that switch on and off within a step.

Iterative coupling (single rate only): each base step is repeated from the snapshot taken by ``get_state``
until the exchanged inputs change by less than ``tolerance`` (relative), up to ``iterations`` passes.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from time import monotonic as _monotonic
from typing import Sequence

import numpy as np

from rotorcosim.components.contract import Component, ContractError, StopRequested, output_problem
from rotorcosim.components.registry import is_plugin_class
from rotorcosim.components.errors import Diverged, ProcessDied, StepTimeout

from rotorcosim.master.core import links
from rotorcosim.master.core.system import Connection, System

#: the component call in progress, ``[(name, t, time.monotonic() at its start)]``, while a step time limit is
#: watched (master/run/watchdog.py); None otherwise
CALL: list | None = None
#: the algorithms by name (a registry, like the components'): a new algorithm is a new class, registered here
ALGORITHM_CLASSES: dict[str, type["Algorithm"]] = {}


def register_algorithm(name: str):
    """Class decorator: make an :class:`Algorithm` available under ``name`` (scenario ``[algorithm] kind``)."""

    def add(cls):
        cls.name = name
        ALGORITHM_CLASSES[name] = cls
        return cls

    return add


class Algorithm:
    """How the components that fire in a base step see each other's outputs (one pass of the step)."""

    name = ""
    #: iterative coupling: which inputs of a firing component are fed back from the pass just made (True: all
    #: of them, Jacobi; False: only those from components that fire at or after it in the order, Gauss-Seidel)
    feedback_from_all = False

    def run_pass(self, engine: "Engine", firing: list[str], t_end: float) -> None:
        """Step the components ``firing`` (names, in the engine's order) of ``engine`` over the base step that
        ends at ``t_end`` [s], each fed its inputs as this algorithm couples them."""
        raise NotImplementedError


def _step_size(engine: "Engine", n: str, t_end: float) -> tuple[float, float]:
    """(t, hc) of component n's step ending at t_end, cut at a requested stop (hc <= 0: nothing left to do)."""
    hc = engine.mult[n] * engine.h
    t = t_end - hc
    if engine.stop is not None:
        hc = engine.stop.t_stop - t
        if hc <= 1e-12 * max(1.0, abs(t)):
            hc = 0.0
    return t, hc


@register_algorithm("gauss-seidel")
class GaussSeidel(Algorithm):
    """Each component, in the given order, sees the outputs its predecessors have just produced."""

    def run_pass(self, engine, firing, t_end):
        direct = engine._direct
        for n in firing:
            t, hc = _step_size(engine, n, t_end)
            if hc <= 0.0:
                continue
            if n in direct:
                engine._fire_direct(n, t, hc)
            else:
                engine._fire(n, engine._gather(n, t + 0.5 * hc, t + hc), t, hc)


@register_algorithm("jacobi")
class Jacobi(Algorithm):
    """Every firing component sees the outputs as they were at the start of the base step."""

    feedback_from_all = True

    def run_pass(self, engine, firing, t_end):
        h = engine.h
        gathered = []
        for n in firing:
            hc = engine.mult[n] * h
            gathered.append((n, engine._gather(n, t_end - 0.5 * hc, t_end)))
        for n, values in gathered:
            t, hc = _step_size(engine, n, t_end)
            if hc > 0.0:
                engine._fire(n, values, t, hc)


ALGORITHMS = tuple(ALGORITHM_CLASSES)


class SimulationFailed(RuntimeError):
    """A run stopped by one of its components' steps; what was recorded is kept. ``what`` is the first words
    the command line says (each kind below has its own)."""
    what = "the simulation failed"

    def line(self) -> str:
        """What the command line says: ``what``, then the message without a closing ``what`` of its own (a
        divergence's message ends so, for summary.json, where no ``what`` precedes it)."""
        return f"{self.what}: {str(self).removesuffix(': ' + self.what)}"


class SimulationDiverged(SimulationFailed):
    """A component produced a non-finite value (NaN or inf) in an output another component reads."""
    what = "the simulation diverged"


class ComponentFailed(SimulationFailed):
    """A component's step raised an exception of its own (its message follows the component and the time)."""
    what = "a component failed"


class StepTimedOut(ComponentFailed):
    """A component's step did not return within its time limit (an FMU in a process of its own, stopped)."""
    what = "a component's step timed out"


class ComponentCrashed(ComponentFailed):
    """The process computing a component's step died (an FMU in a process of its own that crashed)."""
    what = "a component's process crashed"


def step_failure(name: str, t: float, exc: BaseException) -> SimulationFailed:
    """The run's error for component ``name``'s step from ``t`` that raised ``exc``: diverged (the component says
    its state left its equations' domain, components.errors.Diverged), timed out, crashed, or failed."""
    kind = (SimulationDiverged if isinstance(exc, Diverged) else StepTimedOut if isinstance(exc, StepTimeout)
            else ComponentCrashed if isinstance(exc, ProcessDied) else ComponentFailed)
    return kind(f"{name} failed in do_step at t = {t:.9g} s: {exc}")


class _Link:
    """Run-time state of one connection: what its consumer sees of its producer's output (master/core/links.py:
    the semantics and the layout of ``state`` and ``vectors``, shared with the compiled loop)."""

    __slots__ = ("con", "src", "sport", "dst", "dport", "_mode", "take_kind", "produce_kind", "n", "state", "vectors",
                 "frozen", "held", "window", "conv", "real", "ramp")

    SAME, FAST_TO_SLOW, SLOW_TO_FAST = links.SAME, links.FAST_TO_SLOW, links.SLOW_TO_FAST

    def __init__(self, con: Connection, src: Component, dst: Component, conv=None):
        self.con = con
        self.src, self.sport = src, con.src_port
        self.dst, self.dport = dst, con.dst_port
        #: the type/unit conversion of the connection (conversions.py), None for a plain copy
        self.conv = conv
        var = src.variable(con.src_port)
        #: averaging, extrapolation and hold statistics apply to Real signals only; the others are held
        self.real = var.type == "Real"
        #: values carried (the producer's port size)
        self.n = var.size
        #: the link's state row and vectors (links.py's layout; a hand-off window records into the hold's own
        #: record, master/core/window.py). Lists of floats: the generic loop runs links.py's functions in Python,
        #: where a list's item costs a third of an array's (the compiled loop copies them into its tables and back)
        self.state = [0.0] * links.NM
        self.vectors = [0.0] * (links.NV * self.n)
        self.frozen = None      # an iteration's override (iterative coupling)
        self.held = None        # the thermal-only hold's value (master/manipulator/hold.py), or None
        self.window = None      # the thermal-only hold's recorder of this link's hand-off window, or None
        self.ramp = None        # the hold's restart offset of a hand-back after a thermal-only interval, or None
        self.mode = self.SAME
        self.reset()

    @property
    def mode(self) -> int:
        """The producer's rate against the consumer's (SAME, FAST_TO_SLOW, SLOW_TO_FAST); setting it sets what the
        consumer takes and what each production records (links.kinds)."""
        return self._mode

    @mode.setter
    def mode(self, mode: int) -> None:
        self._mode = mode
        self.take_kind, self.produce_kind = links.kinds(mode, self.con.average, self.con.extrapolation)

    def reset(self):
        """Forget averages and extrapolation history (a new interval); a hand-off window keeps its fields."""
        self.state[:links.OWN] = [0.0] * links.OWN
        self.vectors[:] = [0.0] * len(self.vectors)

    def value(self, t_mid: float, t_end: float | None = None) -> np.ndarray:
        """What the consumer sees, converted (type, unit) when the connection needs it (``conv``; one call,
        inlined here rather than wrapped so that a plain link costs what it did)."""
        conv = self.conv
        if self.frozen is not None:
            return self.frozen if conv is None else conv(self.frozen)
        if self.held is not None:
            return self.held.value() if conv is None else conv(self.held.value())
        y = self.src.y[self.sport]
        if not self.real:
            return np.array(y) if conv is None else conv(np.array(y))
        kind = self.take_kind
        if t_end is None:
            t_end = t_mid
        if kind == links.TAKE_COPY:
            out = np.array(y, dtype=float)
        else:
            out = np.empty(self.n)
            links.take(kind, out, 0, y, 0, self.vectors, 0, self.n, self.state, t_mid, t_end)
        ramp = self.ramp
        if ramp is not None:  # a hand-back just after a thermal-only interval (master/manipulator/restart.py)
            links.add_restart(out, 0, ramp.delta, 0, self.n, t_end, ramp.t0, ramp.length)
        return out if conv is None else conv(out)

    def produced(self, h_src: float, t_end: float) -> None:
        """Called after the producer has stepped."""
        if not self.real:
            return
        y = self.src.y[self.sport]
        if self.produce_kind != links.PROD_NONE:
            links.produce(self.produce_kind, y, 0, self.vectors, 0, self.n, self.state, h_src, t_end)
        if self.window is not None:
            self.window.record(y, t_end)


#: most coupling passes per step (``[algorithm] iterations``): fixed-point coupling converges linearly, and a
#: contraction of 0.98 per pass still gains 1e-9 in 1000 passes; a coupling not within its tolerance by then does
#: not converge, and each pass is a step of every component with a rollback (a much larger count can hang a run)
MAX_ITERATIONS = 1000


@dataclass
class EngineSettings:
    """The coupling algorithm (a scenario's ``[algorithm]``): ``algorithm`` ("gauss-seidel" or "jacobi"),
    ``iterations`` (passes per base step: 1 is explicit coupling, more repeat the step from the components'
    saved state until the outputs change by less than the relative ``tolerance``), ``check_every``: base steps
    between two checks that every real output is finite."""
    algorithm: str = "gauss-seidel"
    iterations: int = 1
    tolerance: float = 1e-10
    check_every: int = 64

    def __post_init__(self):
        if self.algorithm not in ALGORITHM_CLASSES:
            raise ContractError(f"algorithm {self.algorithm!r} not in {tuple(ALGORITHM_CLASSES)}")
        if not 1 <= int(self.iterations) <= MAX_ITERATIONS:
            raise ContractError(f"algorithm: iterations must be within [1, {MAX_ITERATIONS}] (passes per step), got "
                                f"{self.iterations}")
        if not (self.tolerance > 0 and math.isfinite(self.tolerance)):
            raise ContractError(f"algorithm: tolerance must be positive, got {self.tolerance}")


class Engine:
    """Steps the active components of a system over base steps (one interval at a time).

    Parameters: ``system`` (:class:`~rotorcosim.master.core.system.System`); ``order``: the components' order
    in a pass (those not named follow in the system's order); ``settings`` (:class:`EngineSettings`). A
    :class:`~rotorcosim.master.simulation.Simulation` owns one and drives it: :meth:`prepare` at the start of
    an interval, then :meth:`base_step` for each base step.

    >>> from rotorcosim.components.registry import create
    >>> from rotorcosim.master.core.system import Connection, System
    >>> comps = {"m1": create("testing.mass", "m1", {"m": 1.0, "k": 40.0, "x0": 0.1}),
    ...          "m2": create("testing.spring", "m2", {"m": 2.0, "k": 30.0, "kc": 100.0})}
    >>> system = System(comps, [Connection("m1.x", "m2.x_in"), Connection("m1.v", "m2.v_in"),
    ...                         Connection("m2.F", "m1.F")])
    >>> engine = Engine(system, ["m1", "m2"], EngineSettings("gauss-seidel"))
    >>> for comp in comps.values():
    ...     comp.setup(0.0)                                 # (Simulation.initialise does this)
    >>> engine.prepare(["m1", "m2"], {"m2": 2}, 1e-3)      # base step 1 ms; m2 communicates every 2 ms
    >>> for k in range(100):
    ...     engine.base_step(0.0, k)
    >>> engine.steps_taken
    {'m1': 100, 'm2': 50}
    """

    def __init__(self, system: System, order: Sequence[str], settings: EngineSettings):
        unknown = [n for n in order if n not in system.components]
        if unknown:
            raise ContractError(f"algorithm order names unknown component(s) {unknown}")
        rest = [n for n in system.components if n not in order]
        self.order = list(order) + rest
        self.system = system
        self.settings = settings
        self.algorithm = ALGORITHM_CLASSES[settings.algorithm]()
        conv = getattr(system, "converters", {})
        self.links = [_Link(c, system.components[c.src_component], system.components[c.dst_component],
                            conv.get(c.dst)) for c in system.connections]
        self.steps_taken = {n: 0 for n in self.order}
        #: the user's components (plug-ins): their outputs are checked against the contract after each step
        self._plugins = {n for n, c in system.components.items() if is_plugin_class(type(c))}
        #: the first stop request of the run (a StopRequested), or None; see _pass
        self.stop: StopRequested | None = None

    # -- interval preparation ------------------------------------------------------------------------
    def prepare(self, active: Sequence[str], multiples: dict[str, int], h: float) -> None:
        """Set up an interval: the components ``active`` in it step, each every ``multiples[name]`` base
        steps (default 1) of ``h`` [s]; the links are reset and told how their two sides' rates relate."""
        self.h = h
        self.active = [n for n in self.order if n in set(active)]
        self.mult = {n: int(multiples.get(n, 1)) for n in self.active}
        if self.settings.iterations > 1 and any(m != 1 for m in self.mult.values()):
            raise ContractError("iterative coupling needs all components at the same communication step")
        comps = self.system.components
        self._inputs = {n: [] for n in self.active}
        self._outgoing = {n: [] for n in self.active}
        for link in self.links:
            s, d = link.con.src_component, link.con.dst_component
            link.reset()
            if d not in self.mult:
                continue
            if s in self.mult:
                ms, md = self.mult[s], self.mult[d]
                link.mode = _Link.SAME if ms == md else (_Link.FAST_TO_SLOW if ms < md else _Link.SLOW_TO_FAST)
                self._outgoing[s].append(link)
            self._inputs[d].append(link)
        for link in self.links:  # links recording a hand-off window for a later thermal-only hold
            s = link.con.src_component
            if link.window is not None and s in self.mult and link not in self._outgoing[s]:
                self._outgoing[s].append(link)
        # only links that average, extrapolate or record need to hear about each production
        for n in self._outgoing:
            self._outgoing[n] = [link for link in self._outgoing[n]
                                 if link.mode != _Link.SAME or link.window is not None
                                 or link.con.extrapolation == "linear-end"]
        self._comp = {n: comps[n] for n in self.active}
        # per component: the outputs that feed another component, with a vector of ones of their size
        self._watch = {n: [] for n in self.active}
        for link in self.links:
            s = link.con.src_component
            var = comps[s].variable(link.sport) if s in self._watch else None
            # integers and booleans are always finite: only real outputs are watched
            if var is not None and var.type == "Real" and link.sport not in self._watch[s]:
                self._watch[s].append(link.sport)
        self._all_single = self.active if all(m == 1 for m in self.mult.values()) else None
        # Fast path of the hot loop: a component that keeps the contract's own set_inputs gets its same-rate,
        # unfrozen inputs copied straight into its input arrays (sizes were checked when the system was built),
        # the others through value(); an overriding set_inputs (an FMU) always gets the dict.
        self._direct = {}
        for n in self.active:
            if type(comps[n]).set_inputs is not Component.set_inputs or self.settings.iterations > 1:
                continue
            plain = [link for link in self._inputs[n] if link.mode == _Link.SAME and link.frozen is None
                     and link.held is None and link.ramp is None and link.con.extrapolation != "linear-end" and link.conv is None]
            same = [(link.src, link.sport, link.dport) for link in plain]
            other = [link for link in self._inputs[n] if link not in plain]
            self._direct[n] = (same, other)

    # -- what an interval's plan is made of (the compiled loop builds its tables from these) ---------------
    def inputs_of(self, name: str) -> list[_Link]:
        """The links into component ``name`` in this interval, in the order its inputs are gathered."""
        return self._inputs[name]

    def outgoing_of(self, name: str) -> list[_Link]:
        """The links out of component ``name`` that hear about each of its productions (they average,
        extrapolate or record a hand-off window), in the order they are told."""
        return self._outgoing[name]

    def watched_of(self, name: str) -> list[str]:
        """The Real outputs of component ``name`` that other components read, checked finite after each step."""
        return self._watch[name]

    # -- stepping ------------------------------------------------------------------------------------
    def _gather(self, name: str, t_mid: float, t_end: float | None = None) -> dict:
        return {link.dport: link.value(t_mid, t_end) for link in self._inputs[name]}

    def _fire(self, name: str, values: dict, t: float, hc: float) -> None:
        comp = self._comp[name]
        call = CALL
        if call is not None:
            call[0] = (name, t, _monotonic())
        try:
            if values:
                comp.set_inputs(values)
            comp.do_step(t, hc)
            if name in self._plugins and (problem := output_problem(comp)):
                raise ContractError(problem)
        except SimulationFailed:
            raise
        except StopRequested as req:
            # the component advanced to req.t_stop and asks to end there: keep its step, remember the request
            req.t_stop = min(max(req.t_stop, t), t + hc)
            if self.stop is None or req.t_stop < self.stop.t_stop:
                self.stop = req
            hc = req.t_stop - t
        except Exception as exc:  # a component's own failure: stop with its name, the time and what happened
            raise step_failure(name, t, exc) from exc
        finally:
            if call is not None:
                call[0] = None
        self.steps_taken[name] += 1
        t_end = t + hc
        # divergence caught at the step that produced it: the outputs other components read, summed (a NaN or
        # inf anywhere, or a sum beyond 1e308, makes it non-finite). tolist() and Python additions: measured 3x
        # cheaper than a numpy reduction per port on these 1-3 element vectors
        y = comp.y
        total = 0.0
        for port in self._watch[name]:
            for x in y[port].tolist():
                total += x
        if not math.isfinite(total):
            self.diverged(name, t, t_end)
        for link in self._outgoing[name]:
            link.produced(hc, t_end)

    def diverged(self, name: str, t: float, t_end: float) -> None:
        """Raise SimulationDiverged naming the first non-finite watched output of ``name`` after its step."""
        comp = self._comp[name]
        bad = [p for p in self._watch[name] if not np.all(np.isfinite(comp.y[p]))] or self._watch[name]
        raise SimulationDiverged(f"{name}.{bad[0]} is not finite at t = {t_end:.9g} s (after {name}'s step from "
                                 f"t = {t:.9g} s): the simulation diverged")

    def base_step(self, t0: float, k: int) -> None:
        """Base step k of the interval that starts at t0 (from t0 + k h to t0 + (k+1) h)."""
        h = self.h
        t_end = t0 + (k + 1) * h
        firing = self._all_single or [n for n in self.active if (k + 1) % self.mult[n] == 0]
        if self.settings.iterations == 1:
            self._pass(firing, t_end)
        else:
            self._iterate(firing, t_end)
        if (k + 1) % self.settings.check_every == 0:
            self.check_finite(t_end)

    def partial_step(self, t: float, tau: float, firing: Sequence[str] | None = None,
                     t_end: float | None = None) -> None:
        """The components ``firing`` (default: every active one; those of a multi-rate interval at its base
        step) one step from ``t`` over ``tau`` [s], coupled as in a base step: the re-steps of the event location
        (master/core/events.py). ``t_end``: the step's end when it is a base step's (exactly that float, not
        ``t + tau`` rounded: a hand-off window knows a sample by its time)."""
        h = self.h
        self.h = tau
        try:
            self._pass(self.active if firing is None else list(firing), t + tau if t_end is None else t_end)
        finally:
            self.h = h

    def fire(self, names: Sequence[str], t_end: float) -> None:
        """The components ``names`` one step each, over their own communication step ending at ``t_end`` [s] (a
        base step's end): the slow components of a multi-rate base step whose fast ones the event location split
        (master/core/events.py)."""
        if names:
            self._pass(list(names), t_end)

    def _fire_direct(self, name: str, t: float, hc: float) -> None:
        same, other = self._direct[name]
        u = self._comp[name].u
        for src, sport, dport in same:
            u[dport] = src.y[sport].copy()
        for link in other:
            # (typed by the link: a conversion yields the input's kind, a plain link the output's, which then match)
            u[link.dport] = np.asarray(link.value(t + 0.5 * hc, t + hc)).reshape(-1)
        self._fire(name, None, t, hc)

    def _pass(self, firing: list[str], t_end: float) -> None:
        """One pass over the firing components. After a stop request inside the pass, the components still to
        fire step only up to the requested time (not at all if they are already there), so that the run ends
        with every component that had not yet fired at that time; those fired before it have completed the
        base step (without FMU state they cannot be taken back)."""
        self.algorithm.run_pass(self, firing, t_end)

    def _iterate(self, firing: list[str], t_end: float) -> None:
        rank = {n: i for i, n in enumerate(self.active)}
        jacobi = self.algorithm.feedback_from_all
        snapshot = {n: self._comp[n].get_state() for n in firing}
        fired = set(firing)
        override: dict[_Link, np.ndarray] = {}
        for it in range(self.settings.iterations):
            if it:
                for n in firing:
                    self._comp[n].set_state(snapshot[n])
                    self.steps_taken[n] -= 1
                for link, val in override.items():
                    link.frozen = val
            try:
                self._pass(firing, t_end)
            finally:
                for link in override:
                    link.frozen = None
            if self.stop is not None:  # a stop request ends the run: the iterate in hand is kept
                break
            # inputs fed back from components that fire later in the order (all of them for Jacobi)
            fresh = {}
            for n in firing:
                for link in self._inputs[n]:
                    s = link.con.src_component
                    if link.frozen is None and link.held is None and s in fired and (jacobi or rank[s] >= rank[n]):
                        fresh[link] = np.array(link.src.y[link.sport])
            worst = 0.0 if override else math.inf
            for link, val in override.items():
                ref = fresh[link]
                if ref.dtype.kind not in "fiu":   # Boolean, String: converged when equal
                    worst = max(worst, 0.0 if np.array_equal(ref, val) else math.inf)
                    continue
                scale = max(float(np.max(np.abs(ref))), float(np.max(np.abs(val))), 1e-300)
                worst = max(worst, float(np.max(np.abs(val - ref))) / scale)
            override = fresh
            if not fresh or worst < self.settings.tolerance:
                break
        self.iterations_used = it + 1

    def check_finite(self, t: float) -> None:
        """Raise :class:`SimulationDiverged` naming the first active component's real output that is not finite
        at time ``t`` [s]."""
        # all real outputs in one test (~0.1 ms; a test per port cost ~0.4 ms, at every interval end), then the
        # ports one by one only to name the first that is not finite
        arrays = [y for n in self.active for y in self._comp[n].y.values() if y.dtype.kind == "f"]
        if not arrays or np.isfinite(np.concatenate(arrays, axis=None)).all():
            return
        for n in self.active:
            for port, y in self._comp[n].y.items():
                if y.dtype.kind == "f" and not np.all(np.isfinite(y)):
                    raise SimulationDiverged(f"{n}.{port} is not finite at t = {t:.9g} s: the simulation diverged")
