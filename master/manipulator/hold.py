"""The staggered scheme's thermal-only hold: ONE master concept, in this module.

libcosim would call it a manipulator: it changes what crosses some connections, never a component's insides.

* Which components freeze in a thermal-only (TO) interval: those that take no part in TO, and those that declare
  ``holds_state_in_TO`` (stepped in TO only to update some outputs from their frozen state, e.g. a friction
  loss at the new oil viscosity). Both are *mechanical*.
* The hand-offs: the connections from a mechanical component to a thermal one (the power losses). Over each
  thermo-mechanical (TM) interval the master records, per hand-off, the window of its last ``hold_cycles``
  cycles and the cycle means of the signal and of the thermal inputs its producer received. The cycle period
  comes from the run's cycle source (master/core/cycle.py: a constant period, or a speed signal read at the
  start of each TM interval). A cycle source with an angle counts both in revolutions instead: the window is the
  samples since the time the last ``hold_cycles`` turns of the angle began (the run's RevolutionCounter), and a
  cycle mean ends at each whole turn of the angle from the interval's start, so that a window spans
  ``hold_cycles`` turns while the speed changes within the interval (a speed that falls); the turns each TO interval's
  windows spanned are reported (``HoldReport.window_revolutions``).
* The held value over a TO interval: the window's statistic, per connection (``hold`` of the connection, else the
  schedule's): ``mean`` by default (it keeps the energy of a power), ``rms``, or ``last``.
* The TO update of a producer that declares one: the held statistic S_w follows the producer's own TO output
  y_TO(t) (computed by the producer from its frozen state and its present thermal inputs) along the law

      y(t) = S_w * (y_TO(t) / y_TO,w) ** e

  where y_TO,w is the producer's TO output at the window's mean thermal inputs and ``e`` the *elasticity*
  measured by the master: the least-squares slope of ln(cycle mean of y) against ln(y_TO at that cycle's thermal
  inputs) over the settled halves of the TM intervals so far. The frozen state gives the shape (a film power at
  fixed kinematics scales with the oil viscosity); ``e`` measures how much of it survives once the mechanics
  adapt (an orbit that grows as the oil thins gives e well below 1). With too little temperature change to
  measure (``MIN_SPREAD``) the last measured ``e`` is kept, else e = 1 (the frozen law).
* The group driver (:class:`_Driver`): a producer's cycle means can drift with a temperature that is none of its
  own inputs (a friction loss that follows another component's oil through the orbit and the loads). Among the
  thermal inputs (unit K) of the producers whose hand-offs feed the same thermal component (the group), the one
  whose cycle values correlate best with ln(cycle mean) over the settled halves of the recorded TM intervals, if
  it moved by ``DRIVER_MIN_SPREAD_K``, is the driver; its least-squares slope b multiplies the law by
  exp(b (T(t) - T_w)), T(t) that input's present value in TO, T_w its window mean; ``e`` is then fitted to what
  the driver leaves. The candidates are the OTHER producers' temperatures, and a driver is kept only where it
  tracks the cycle means better than the producer's own TO law (|correlation| with ln of its own TO output at the
  cycle's inputs): the own inputs are that physical law's, and an exponential fitted on a few K of TM and stacked
  on it would extrapolate the same dependence again over a long TO interval. Only for producers with a TO update
  (a hand-off without one stays held). What both rules measured on a real system is in the docstring of the
  shipped case's package (rotorcosim.cases).
* The error estimate (:meth:`StaggeredHold.end`, :meth:`StaggeredHold.finish`). The scheme's only error is the
  held input of the thermal networks: over a TO interval a hand-off takes its held value (or law) instead of
  what the mechanics would give at the present temperatures. That error is measured where it can be, at the next
  TM restart: the held value the TO interval ended with minus the first window the mechanics produce after the
  restart's ramp, at the same temperatures and speed (``delta``, signed, in the power's unit). It is zero where the TO interval starts (the held value
  is the window's statistic) and grows while the temperatures move away from the window's; it is taken at its
  end value over the whole interval (a step, not a ramp: for a node slower than the interval the response to a
  ramp is half the step's, for a fast one the same, so the step bounds the response from above whatever the
  growth between). Each thermal component then answers, through get_state / set_inputs / do_step / set_state
  (any component that can save its state), what its outputs would be with those input errors: it replays, from
  its present state, the time since the pulse began with and without the errors (:func:`replay`; the difference
  is the response of the input error, for a network linear in its inputs independent of the state it starts
  from). The errors are not fixed inputs: where the staggered run's temperatures err, its mechanics (and its TO
  laws) give other powers than the monolithic run's, and those differences are input errors too. The replay
  closes that loop with the sensitivity of each hand-off's TO law to the values its producer takes back from the
  same thermal component (``HandOff.gains``: elasticity times the frozen law's slope, and the driver's slope): a
  film power that falls as its oil warms pulls a too warm oil back. The interval's own estimate is its pulse's
  response at the restart; the run's, at its end, the response
  of all the charged intervals' pulses together (a later interval's error that undoes an earlier one's cancels
  it: the mechanics restarted at erring temperatures give powers that pull them back). Temperatures are judged
  against their rise since the run's start (at least ``RISE_FLOOR_K``), not their absolute values; what the
  thermal components hand back to the mechanics (oil temperatures, growths) is in error by a share of its move
  over the last charged interval (``mechanics_fraction``), which the mechanical results share. A TO interval
  that ends at a scheduled change of a component (its ``next_event``: a fuel cut) is not charged: the mechanics
  after the change are not what its held values stood for.
* The restart (TO -> TM): the hand-backs are the connections from a thermal component to a mechanical one (the
  thermal growths, the oil temperatures). Over a TO interval they moved while the mechanical state stayed frozen
  on the old ones; stepping them into the frozen mechanics at once is a sudden load (a growth of micrometres is an
  axial force step on a preloaded support) that rings the lightly damped modes it meets. In a monolithic run they
  change over seconds, so the mechanics follow them quasi-statically. The restart does the same on a short
  scale: each hand-back enters the next TM interval as its value at the end of the previous TM interval and goes
  over to its present (live) value along a half cosine over ``restart_cycles`` cycles (:class:`Restart`; the
  link adds its offset with master/core/links.add_restart, in both loops). A mode of frequency f then keeps
  about 1 / ((2 f T)^2 - 1) of the step's response (T the ramp length: 0.02 for f = 480 Hz over 7.5 ms).
  ``restart_cycles = 0``: a step.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rotorcosim.components.contract import COUPLED, HELD, ContractError
from rotorcosim.master.core import links, window
from rotorcosim.master.core.window import Window
from rotorcosim.master.core.cycle import WINDOW_MARGIN, Cycle
from rotorcosim.master.core.system import HOLDS  # noqa: F401 - re-exported: the hold modes beside the hold

#: the default statistic: the mean keeps the energy of a power (the RMS overstates a fluctuating one)
DEFAULT_HOLD = "mean"
#: least spread of ln(y_TO) over the recorded cycles to measure an elasticity (5 %)
MIN_SPREAD = 0.05
#: elasticities outside this range are no viscous law: clipped
ELASTICITY_RANGE = (0.0, 2.0)
#: TM intervals whose cycles enter the elasticity fit (the latest ones: the law is local)
FIT_INTERVALS = 3
#: cycles over which the hand-backs go from their pre-TO to their present values at a TM restart (Restart):
#: long against the mechanical modes they would ring, short against the TM intervals whose last ``hold_cycles``
#: cycles give the results and the hand-off windows
RESTART_CYCLES = 2.0
#: least spread (K) of a group temperature over the recorded cycles to drive a hand-off's TO law (_Driver)
DRIVER_MIN_SPREAD_K = 1.0
#: least rise [K] a temperature's relative error is taken of (a node that barely warms has no relative error to speak
#: of: its absolute one is reported in ``output_errors``)
RISE_FLOOR_K = 1.0
#: the relative step of an input at which a TO law's sensitivity is probed (HandOff._gains; an input at zero is
#: not probed)
GAIN_STEP = 1e-3
#: the driver's factor exp(b dT) is bounded to exp(+-DRIVER_MAX_LOG) (a factor 3): a guard against extrapolating
#: a slope far beyond its data
DRIVER_MAX_LOG = 1.1


def mechanical(comp) -> bool:
    """Frozen in TO, or stepped there only for its TO update with its mechanical state frozen."""
    return HELD not in comp.phases or bool(getattr(comp, "holds_state_in_TO", False))


def feeds_thermal(src, dst) -> bool:
    """True for a hand-off: a connection from a mechanical component to a thermal one (stepped in TO)."""
    return mechanical(src) and not mechanical(dst)


def feeds_mechanics(src, dst) -> bool:
    """True for a hand-back: a connection from a thermal component (stepped in TO) to a mechanical one."""
    return HELD in src.phases and not mechanical(src) and mechanical(dst)


class Restart:
    """A hand-back's offset at a TM restart: ``delta`` (its value at the end of the previous TM interval minus its
    value at the restart) at t0, fading along a half cosine to nothing at t0 + length (links.add_restart, which
    both loops add to the link's value). A class, not a closure: checkpoints pickle the links."""

    def __init__(self, delta: np.ndarray, t0: float, length: float):
        self.delta, self.t0, self.length = np.array(delta, dtype=float), float(t0), float(length)

    def offset(self, t: float) -> np.ndarray:
        """The offset at time ``t`` [s] (in the hand-back's unit): ``delta`` before t0, 0 after t0 + length."""
        out = np.zeros_like(self.delta)
        links.add_restart(out, 0, self.delta, 0, self.delta.shape[0], t, self.t0, self.length)
        return out


class HandOff:
    """One mechanical -> thermal connection: its window, its cycle means, its held value in TO."""

    def __init__(self, link, hold: str, thermal_ports: list[str]):
        self.link = link
        self.hold = hold
        self.ports = thermal_ports          # the producer's inputs that come from thermal components
        self.updates = bool(getattr(link.src, "holds_state_in_TO", False))
        self.elasticity: float | None = None
        self.history: list[list[tuple[np.ndarray, float]]] = []   # per TM interval: (thermal inputs, cycle mean)
        self.held = None
        self.error: float | None = None
        self.delta: np.ndarray | None = None
        self._to_end: np.ndarray | None = None
        #: the window's recording state (master/core/window.py: both loops record into it)
        self.w = Window()
        self.turns = None                   # (RevolutionCounter, turns of the window, the angle's component, port)
        self.hs = 0.0                       # the producer's step in the TM interval [s]
        #: the power's sensitivity to the thermal values it follows, from its last TO law: (component whose input
        #: it is, its port, element, dP/du [W per the input's unit]); the error estimate's feedback (:func:`replay`)
        self.gains: list[tuple[str, str, int, float]] = []

    # -- TM: record -------------------------------------------------------------------------------------
    def start_tm(self, n_window: int, n_cycle: int, size: int, hs: float = 0.0, turns=None,
                 next_turn: float = 0.0, direction: float = 1.0) -> None:
        """A TM interval starts: record the producer's output (a port of ``size`` elements, every ``hs`` seconds)
        in a ring of ``n_window`` samples, in rotor cycles of ``n_cycle`` samples; or, with ``turns``
        (RevolutionCounter, turns of the window, the angle's component, the angle's port), in cycles that
        end at each whole turn of the angle (the first where it passes ``next_turn`` [rad], turning in
        ``direction``), the window being the samples of its last turns."""
        self.ring = np.zeros((max(1, n_window), size))
        w = self.w
        w.pos = w.count = 0
        w.has_t, w.t_last = False, 0.0
        self.hs, self.turns = float(hs), turns
        w.n_cycle = max(1, n_cycle) if turns is None else 0
        w.next_turn, w.direction = (float(next_turn), float(direction)) if turns is not None else (0.0, 0.0)
        w.csum, w.cn, w.last = 0.0, 0, 0.0     # the rotor cycle being recorded
        self.cycles: list[tuple[np.ndarray, float]] = []
        self.history.append(self.cycles)
        del self.history[:-FIT_INTERVALS]

    def record(self, y: np.ndarray, t_end: float) -> None:
        """One sample of the producer's output (every step it takes in a TM interval)."""
        w = self.w
        if w.has_t and w.t_last == t_end:  # a repeated iteration of the same step replaces its sample
            w.pos = (w.pos - 1) % len(self.ring)
            w.count -= 1
            if w.cn == 0 and self.cycles:
                _, mean = self.cycles.pop()
                w.csum, w.cn = mean * w.last_cn, w.last_cn
                if self.turns is not None:   # the turn it ended at is to be passed again
                    w.next_turn -= 2.0 * math.pi * w.direction
            w.csum -= w.last
            w.cn -= 1
        # the sample and the cycle it belongs to (window.record: the compiled loop records with the same function)
        ring = self.ring
        theta = float(self.turns[2].y[self.turns[3]][0]) if self.turns is not None else 0.0
        if window.record(y, 0, ring.shape[1], w, ring.reshape(-1), 0, ring.shape[0], t_end, theta):
            # a whole rotor cycle: its mean, and the thermal inputs at its end (they change at the thermal step, far
            # slower than the rotor)
            self.cycles.append((self._thermal_inputs(), float(w.cmean)))

    def _thermal_inputs(self) -> np.ndarray:
        u = self.link.src.u
        return np.concatenate([np.ravel(u[p]) for p in self.ports]) if self.ports else np.zeros(0)

    @property
    def count(self) -> int:
        """Samples in the window (none before the first TM interval)."""
        return self.w.count

    def _data(self):
        if self.turns is None:
            return self.ring if self.count == len(self.ring) else self.ring[: self.count]
        k = self.window_samples()
        return self.ring[(self.w.pos - k + np.arange(k)) % len(self.ring)]

    def window_samples(self) -> int:
        """The samples of the window: all (up to the ring's size) when counted in samples; counted in turns, those
        of the steps since the last turns of the window began (each sample stands for the producer's step that
        ends at it; the samples are ``hs`` apart and the newest is at ``t_last``)."""
        if self.turns is None or self.count == 0:
            return self.count
        counter, turns = self.turns[0], self.turns[1]
        t_last = self.w.t_last
        began = counter.began(turns, t_last)
        k = int(math.ceil((t_last - began) / self.hs - 1e-9))
        return min(max(k, 1), self.count)

    def window_revolutions(self) -> float | None:
        """The turns of the cycle's angle the window spans (None when it is not counted in turns)."""
        if self.turns is None or self.count == 0:
            return None
        k = self.window_samples()
        return self.turns[0].revolutions(self.w.t_last - k * self.hs, self.w.t_last)

    def statistic(self, how: str) -> np.ndarray:
        """RMS, mean or last of the window (the last ``hold_cycles`` rotor cycles of the TM interval)."""
        if self.count == 0:
            return np.array(self.link.src.y[self.link.sport], dtype=float)
        data = self._data()
        if how == "rms":
            return np.sqrt(np.mean(data * data, axis=0))
        if how == "mean":
            return data.mean(axis=0)
        return np.array(self.link.src.y[self.link.sport], dtype=float)

    def window_inputs(self, cycles: int) -> np.ndarray:
        """The producer's thermal inputs over the window: their mean over its last ``cycles`` whole cycles."""
        last = self.cycles[-cycles:] if self.cycles else []
        return np.mean([u for u, _ in last], axis=0) if last else self._thermal_inputs()

    def measure_restart_error(self, skip: int = 0, cycles: int = 0) -> bool:
        """At the end of the first TM interval after a TO interval: the held value the TO interval ended with
        against the first window the mechanics produced after the restart (the hand-off error of that TO interval,
        at the speed and temperatures it ended with: in a long TM interval, a rundown, the window at its end is
        at another speed). The first window: the mean of the ``cycles`` cycle means after the first ``skip``
        (the restart's ramp), for a mean hold of a scalar with that many cycles recorded; else the interval's
        last window. True if measured."""
        if self._to_end is None or self.count == 0:
            return False
        first = self.cycles[skip: skip + cycles]
        if self.hold == "mean" and cycles > 0 and len(first) == cycles and self._to_end.size == 1:
            now = np.array([np.mean([m for _, m in first])])
        else:
            now = self.statistic(self.hold)
        scale = max(float(np.max(np.abs(now))), 1e-300)
        #: the held value the TO interval ended with minus what the mechanics give at the restart [its unit]
        self.delta = self._to_end - now
        self.error = float(np.max(np.abs(self.delta))) / scale
        self._to_end = None
        return True

    def forget_restart(self) -> None:
        """The TO interval ended at a scheduled change of the system: its held value is not compared with the
        mechanics after the change."""
        self._to_end = None

    # -- TO: hold -----------------------------------------------------------------------------------------
    def start_to(self, probe, fired, cycles: int, group: list["HandOff"] | None = None) -> None:
        """A TO interval starts: hold the window's statistic, or a law that follows the producer's own TO
        output and, where one tracks it better, another hand-off's temperature (``group``: the hand-offs of the
        system). ``probe`` evaluates a producer's TO output at given inputs, ``fired`` tells whether a component
        has stepped in this interval, ``cycles`` is the number of rotor cycles of the window."""
        S = self.statistic(self.hold)
        self.held = _Held(self.link, S)
        if not self.updates or self.link.src.y[self.link.sport].size != 1 or not float(S[0]) > 0.0:
            return
        ref = probe(self.link.src, self.ports, self.window_inputs(cycles), self.link.sport)
        if ref is None or not ref > 0.0:
            return
        # a driver only where another producer's temperature tracks the cycle means better than the producer's
        # own TO law does: its own inputs are that law's (physical) business, and an exponential fitted on a few K
        # of TM and extrapolated over a long TO interval is not (the 2-minute run: 0.07 % against the monolithic
        # run with this rule, 1.4 % with the producer's own temperatures as drivers)
        drive = _Driver.choose(self, [g for g in (group or []) if g is not self], cycles)
        pts = self._settled_points(probe)
        if drive is not None and drive.r <= self._own_correlation(pts):
            drive = None
        e = self._fit(pts, drive)
        if e is not None:
            self.elasticity = e
        self.held = _HeldLaw(self.link, S, ref, 1.0 if self.elasticity is None else self.elasticity, fired, drive)
        self.gains = self._gains(probe, self.window_inputs(cycles), ref, self.held)

    def _gains(self, probe, u, ref: float, law: "_HeldLaw") -> list[tuple[str, str, int, float]]:
        """The law's sensitivity to each thermal input at the window's inputs ``u`` (``ref`` its own TO output
        there): dP/du_i = S e d ln y_TO / du_i (a one-sided difference over ``GAIN_STEP`` of the input, probed
        through the frozen state), and S b to the driver's temperature. What the mechanics would give at other
        temperatures, as far as the law knows it."""
        S = float(law.S[0])
        out, i = [], 0
        for p in self.ports:
            for k in range(np.asarray(self.link.src.u[p]).size):
                du = GAIN_STEP * abs(float(u[i]))
                v = np.array(u, dtype=float)
                v[i] += du
                y = probe(self.link.src, self.ports, v, self.link.sport) if law.e > 0.0 and du > 0.0 else None
                if y is not None and y > 0.0 and y != ref:
                    out.append((self.link.con.src_component, p, k, S * law.e * math.log(y / ref) / du))
                i += 1
        d = law.drive
        if d is not None:
            out.append((d.owner.link.con.src_component, d.port, d.k, S * d.b))
        return out

    def _settled_points(self, probe) -> list[tuple[float | None, float]]:
        """The fits' points, one per settled cycle of the recorded TM intervals: (ln of the producer's own TO
        output at the cycle's inputs, None where it or the cycle mean is not positive; the cycle mean). Probed once
        per TO interval for both the driver's test and the elasticity fit."""
        out = []
        for u, y in (c for cycles in self.history for c in cycles[len(cycles) // 2:]):
            v = probe(self.link.src, self.ports, u, self.link.sport) if y > 0.0 else None
            out.append((math.log(v) if v is not None and v > 0.0 else None, y))
        return out

    @staticmethod
    def _own_correlation(pts) -> float:
        """|correlation| of ln(cycle mean) with ln(the producer's own TO output at the cycle's inputs) over the
        settled points (0 when the own output did not move)."""
        xs = [x for x, _ in pts if x is not None]
        zs = [math.log(y) for x, y in pts if x is not None]
        if len(xs) < 3 or float(np.ptp(xs)) < MIN_SPREAD:
            return 0.0
        return abs(float(np.corrcoef(xs, zs)[0, 1]))

    @staticmethod
    def _fit(pts, drive: "_Driver | None" = None) -> float | None:
        if drive is not None:   # the elasticity of what the driver's law leaves
            pts = [(x, y * math.exp(-drive.b * (th - drive.w))) for (x, y), th in zip(pts, drive.series)]
        xs, zs = [], []
        for x, y in pts:
            if x is None or not y > 0.0:
                continue
            xs.append(x)
            zs.append(math.log(y))
        if len(xs) < 3:
            return None
        x, z = np.array(xs), np.array(zs)
        dx = x - x.mean()
        if float(np.ptp(x)) < MIN_SPREAD:
            return None
        e = float(np.dot(dx, z - z.mean()) / np.dot(dx, dx))
        return min(max(e, ELASTICITY_RANGE[0]), ELASTICITY_RANGE[1])

    def end_to(self) -> None:
        """A TO interval ends: keep its last held value (the next TM restart measures the hand-off error)."""
        if self.held is not None:
            self._to_end = np.array(self.held.value(), dtype=float)
        self.held = None


class _Held:
    """The window statistic, constant over the TO interval."""

    def __init__(self, link, S):
        # a Real statistic as float; an Integer, Boolean or String value kept as it is (held, not averaged)
        self.link, self.S = link, (np.array(S, dtype=float) if link.real else np.array(S))

    def value(self) -> np.ndarray:
        return self.S


class _HeldLaw(_Held):
    """S_w * (y_TO(t) / y_TO,w) ** e * exp(b (T(t) - T_w)), y_TO(t) the producer's own TO output (its last TO
    step), T(t) the driver's present temperature (:class:`_Driver`, if any)."""

    def __init__(self, link, S, ref, e, fired, drive=None):
        super().__init__(link, S)
        self.ref, self.e = float(ref), float(e)
        self.fired = fired     # false until the producer has stepped in this TO interval (its output is its TM one)
        self.drive = drive

    def value(self) -> np.ndarray:
        if not self.fired():
            return self.S
        y = float(self.link.src.y[self.link.sport][0])
        if not y > 0.0:
            return self.S
        f = (y / self.ref) ** self.e
        if self.drive is not None:
            f *= self.drive.factor()
        return self.S * f


class _Driver:
    """The temperature of a hand-off's group that drives its cycle means (DRIVER_* constants, module docstring):
    among the thermal inputs of the producers whose hand-offs feed the same thermal component (the oils of the
    components that load it...), the scalar temperature (unit K, moved by DRIVER_MIN_SPREAD_K) whose values correlate
    best with ln(cycle mean) over the settled cycles of the recorded TM intervals; ``b`` the least-squares slope
    of ln(cycle mean) against it. The group's hand-offs are recorded cycle for cycle (same TM intervals, same
    cycle); one recorded otherwise is skipped."""

    def __init__(self, owner: "HandOff", port: str, k: int, b: float, w: float, series: list[float], r: float = 1.0):
        self.owner, self.port, self.k = owner, port, k
        self.b, self.w, self.series, self.r = float(b), float(w), series, float(r)

    def factor(self) -> float:
        th = float(np.ravel(self.owner.link.src.u[self.port])[self.k])
        return math.exp(max(-DRIVER_MAX_LOG, min(DRIVER_MAX_LOG, self.b * (th - self.w))))

    @staticmethod
    def choose(ho: "HandOff", group: list["HandOff"], cycles: int) -> "_Driver | None":
        own = [[c for c in cyc[len(cyc) // 2:]] for cyc in ho.history]
        ys = [y for cyc in own for _, y in cyc]
        if len(ys) < 3 or not all(y > 0.0 for y in ys):
            return None
        z = np.log(np.array(ys))
        best = None
        for g in group:
            if len(g.history) != len(ho.history) or any(len(a) != len(b) for a, b in zip(g.history, ho.history)):
                continue    # not recorded cycle for cycle with this hand-off
            col = 0
            for p in g.ports:
                var = g.link.src.variable(p)
                for k in range(var.size):
                    if var.unit == "K":
                        th = np.array([u[col + k] for cyc in g.history for u, _ in cyc[len(cyc) // 2:]])
                        spread = float(np.ptp(th))
                        if spread < DRIVER_MIN_SPREAD_K:
                            continue
                        r = abs(float(np.corrcoef(th, z)[0, 1]))
                        if best is None or r > best[0]:
                            best = (r, g, p, k, th, col + k)
                col += var.size
        if best is None:
            return None
        r, g, p, k, th, col = best
        dth = th - th.mean()
        b = float(np.dot(dth, z - z.mean()) / np.dot(dth, dth))
        last = g.cycles[-cycles:] if g.cycles else []
        w = float(np.mean([u[col] for u, _ in last])) if last else float(np.ravel(g.link.src.u[p])[k])
        return _Driver(g, p, k, b, w, list(th), r)


@dataclass
class HoldReport:
    """What the hold measured: per hand-off, the elasticity of its last TO law and its last hand-off error
    (relative power, at the restart); per TO interval (``intervals``) its own estimated error, and for the run the
    estimated error of every output of the thermal components at the last restart (``output_errors``, in the
    output's unit) with each output's rise over the run (``output_rise``); ``estimated_error_pct``: the largest
    estimated error of a reported temperature (a scalar output in K), percent of its rise above its value at the
    run's start (:data:`RISE_FLOOR_K` at least)."""

    elasticity: dict[str, float] = field(default_factory=dict)
    errors: dict[str, float] = field(default_factory=dict)
    interval_estimates_pct: list[float] = field(default_factory=list)
    drivers: dict[str, dict | None] = field(default_factory=dict)
    #: windows counted in turns of the cycle's angle: the turns asked for (hold_cycles), and per TO interval the
    #: fewest turns a hand-off's window spanned (fewer than asked where the TM interval was shorter, or the speed
    #: fell below 1 / WINDOW_MARGIN of its start value within the window); None: windows counted in periods
    revolutions_asked: float | None = None
    window_revolutions: list[float] = field(default_factory=list)
    #: per TO interval: t_start, t_end [s], its own estimate [%] (None: not charged), ``event`` (the scheduled
    #: change its end met, if any), ``output`` (the temperature of its largest estimate)
    intervals: list[dict] = field(default_factory=list)
    #: "comp.port" -> the estimated error of each element at the last restart [the port's unit], signed
    output_errors: dict[str, list[float]] = field(default_factory=dict)
    #: "comp.port" -> each element's change since the run's start [the port's unit]
    output_rise: dict[str, list[float]] = field(default_factory=dict)
    #: "comp.port" -> each element's change over the last charged TO interval (a hand-back's move) [its unit]
    output_move: dict[str, list[float]] = field(default_factory=dict)
    #: per component that hands values back to the mechanics: the largest, over its hand-backs, of their estimated
    #: error against their move over the last charged TO interval (norms over the port's elements; a temperature
    #: that rose less than RISE_FLOOR_K over the run left out): the share of that move the mechanics took in error,
    #: which the results the mechanics give share; empty where the cycle's speed differed between the last two TM
    #: intervals (the mechanics then moved with the speed too)
    mechanics_fraction: dict[str, float] = field(default_factory=dict)
    #: "producer.port" -> the hand-off's power in error at the run's end [its unit], from its TO law's
    #: sensitivity to the estimated errors of the values its producer takes back (hand-offs with a law only)
    handoff_errors_end: dict[str, float] = field(default_factory=dict)
    #: the run's estimated error [%] (None before a TO interval was charged)
    estimated_error_pct: float | None = None
    #: the temperature whose estimate is the run's, "comp.port"
    estimated_output: str | None = None

    @property
    def last_estimate_pct(self) -> float | None:
        """The last charged TO interval's estimated error [%], or None before one."""
        return self.interval_estimates_pct[-1] if self.interval_estimates_pct else None

    def advice(self, estimate_pct: float, tolerance_pct: float) -> str | None:
        """What to change when the run's estimated error ``estimate_pct`` exceeds ``tolerance_pct`` (None when it
        does not, or no interval was charged): the held interval whose own estimate is the largest, to be held
        shorter (its length scaled by tolerance / estimate; the automatic schedule's shortest, ``to_min``), or a
        tighter drift tolerance."""
        charged = [i for i in self.intervals if i["estimate_pct"] is not None]
        if not charged or not estimate_pct > tolerance_pct:
            return None
        worst = max(charged, key=lambda i: i["estimate_pct"])
        length = worst["t_end"] - worst["t_start"]
        return (f"estimated error {estimate_pct:.2f} % is above the tolerance {tolerance_pct:g} %; the largest share "
                f"comes from the held interval {worst['t_start']:.6g}-{worst['t_end']:.6g} s (alone "
                f"{worst['estimate_pct']:.2f} % on {worst['output']}): hold shorter intervals there (about "
                f"{length * tolerance_pct / estimate_pct:.3g} s instead of {length:.3g} s; with the automatic "
                f"schedule a smaller to_min, or a tighter drift_tolerance)")

    def as_dict(self) -> dict:
        """The report as summary.json's ``hold`` (hand-off errors in percent)."""
        out = {"elasticity": dict(self.elasticity), "drivers": dict(self.drivers),
               "handoff_error_pct": {k: 100.0 * v for k, v in self.errors.items()},
               "interval_estimates_pct": list(self.interval_estimates_pct),
               "intervals": [dict(i) for i in self.intervals],
               "output_errors": dict(self.output_errors), "output_rise": dict(self.output_rise),
               "output_move": dict(self.output_move), "mechanics_fraction": dict(self.mechanics_fraction),
               "handoff_errors_end": dict(self.handoff_errors_end),
               "estimated_error_pct": self.estimated_error_pct, "estimated_output": self.estimated_output}
        if self.revolutions_asked is not None:
            w = self.window_revolutions
            out["window_revolutions"] = {"asked": self.revolutions_asked, "smallest": min(w) if w else None,
                                         "per_interval": list(w)}
        return out


class Pulse:
    """A charged TO interval's hand-off errors: from ``t0`` to ``t1`` [s] the thermal component took, on each
    port of ``delta``, its held value minus what the mechanics gave at the restart (signed, in the port's unit);
    ``step`` the interval's step [s]. A class, not a closure: checkpoints pickle the hold."""

    def __init__(self, t0: float, t1: float, step: float, delta: dict[str, np.ndarray]):
        self.t0, self.t1, self.step, self.delta = float(t0), float(t1), float(step), delta


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
                link.held = _Held(link, link.src.y[link.sport])
        self._to_start, self._to_step = t, step
        self._at_to_start = self._thermal_outputs()
        probe = _Probe(t, step)
        steps_taken = steps_taken if steps_taken is not None else {}
        turns = [r for r in (ho.window_revolutions() for ho in self.handoffs) if r is not None]
        if turns:
            self.report.window_revolutions.append(min(turns))
        for ho in self.handoffs:
            name, n0 = ho.link.con.src_component, steps_taken.get(ho.link.con.src_component, 0)
            group = [g for g in self.handoffs if g.link.con.dst_component == ho.link.con.dst_component]
            ho.start_to(probe, _Fired(steps_taken, name, n0), max(1, int(round(self.hold_cycles))), group)
            ho.link.held = ho.held
            if isinstance(ho.held, _HeldLaw):
                self.report.elasticity[f"{ho.link.con.src} -> {ho.link.con.dst}"] = ho.held.e
                d = ho.held.drive
                self.report.drivers[f"{ho.link.con.src} -> {ho.link.con.dst}"] = (
                    None if d is None else {"input": f"{d.owner.link.con.src_component}.{d.port}[{d.k}]",
                                            "slope_per_K": d.b, "window_K": d.w})

    def end(self, phase: str, t: float) -> None:
        """End of an interval at time t: after the first TM interval that follows a TO interval, the hand-off
        errors of that TO interval and the estimates (:meth:`_estimate`). A TO interval that ended at a scheduled
        change of a component (its ``next_event``: a fuel cut) is not charged: the mechanics after the change
        are not what the held values stood for, and the change starts a fresh coupled interval."""
        self._last_phase = phase
        if phase == COUPLED:
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
        if fresh:
            self._estimate(fresh, t0, t1)

    def feedback(self, name: str) -> list[tuple[str, str, int, float]]:
        """How thermal component ``name``'s inputs follow its own outputs through the mechanics, as the last TO
        laws measured it: (input port, output port, output element, dP/du) for each hand-off into it whose
        producer takes that output back (HandOff.gains); the error estimate's feedback (:func:`replay`)."""
        fed = {(l.con.dst_component, l.con.dst_port): l.sport for l in self.handbacks if l.con.src_component == name}
        out: dict[tuple[str, str, int], float] = {}
        for ho in self.handoffs or []:
            if ho.link.con.dst_component != name:
                continue
            for comp, port, k, g in ho.gains:
                o = fed.get((comp, port))
                if o is not None:
                    key = (ho.link.dport, o, k)
                    out[key] = out.get(key, 0.0) + g
        return [(*key, g) for key, g in out.items()]

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
        """The interval's own estimate after the restart of the TO interval [t0, t1] (module docstring, "The error
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
            own.update(replay(comp, name, [pulse], comp.time, self.feedback(name)))
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
            errors.update(replay(comp, name, pulses, comp.time, self.feedback(name)))
        present = self._thermal_outputs()
        rep = self.report
        rep.output_errors = {k: np.asarray(v, dtype=float).tolist() for k, v in errors.items()}
        rep.output_rise = {k: (v - self._initial[k]).tolist() for k, v in present.items() if k in self._initial}
        rep.output_move = {k: (present[k] - v).tolist() for k, v in self._at_last_restart.items() if k in present}
        rep.estimated_error_pct, rep.estimated_output = self._largest(errors)
        rep.handoff_errors_end = self._handoff_errors(errors)
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

    def _handoff_errors(self, errors: dict[str, np.ndarray]) -> dict[str, float]:
        """Each hand-off's power in error at the run's end by what its TO law says the erring values its producer
        takes back do to it (HandOff.gains times their estimated errors ``errors``, "comp.port" -> values): the
        mechanics' own power at the end, "producer.port" -> error [its unit]; only hand-offs with a law."""
        feeds = {(l.con.dst_component, l.con.dst_port): f"{l.con.src_component}.{l.sport}" for l in self.handbacks}
        out = {}
        for ho in self.handoffs or []:
            if not ho.gains:
                continue
            d = 0.0
            for comp, port, k, g in ho.gains:
                err = errors.get(feeds.get((comp, port), ""))
                if err is not None:
                    d += g * float(np.ravel(err)[k])
            out[f"{ho.link.con.src_component}.{ho.link.sport}"] = d
        return out

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


def replay(comp, name: str, pulses: list[Pulse], now: float,
           feedback: list[tuple[str, str, int, float]] = ()) -> dict[str, np.ndarray]:
    """The change of each Real output of thermal component ``comp`` at the end of a replay of [pulses[0].t0,
    now] from its present state, with each pulse's input errors added over [t0, t1] (at the pulse's step; the
    gaps at the next pulse's), against the same replay without: for a network linear in its inputs, the
    response at ``now`` of the input errors (a response to an input does not depend on the state it starts
    from). Through get_state / set_inputs / do_step / set_state: any component that can save its state; one
    that cannot gives no estimate (an empty dict). The state is restored.

    ``feedback``: (input port, output port, output element, g) entries: the input follows that output's error
    with the gain g (the mechanics, or a TO law, give another power at erring temperatures: a film power that
    falls as its oil warms pulls the oil back). The errors of the inputs are then closed-loop,

        du(t) = delta(t) + G dy(t),

    delta the pulses' errors and dy the outputs' errors at the end of each step, solved step by step implicitly:
    a step of a network linear in its inputs gives dy = dy0 + B c for an added input c (B measured once per
    segment, one step per input), so c = (I - G B)^-1 G (dy0 - 0) with dy0 the error the step would leave
    without it."""
    outs = [v.name for v in comp.variables if v.causality == "output" and v.type == "Real"]
    try:
        snap = comp.get_state()
    except Exception:  # cannot save its state: no estimate from it
        return {}
    fb = [(i, o, k, float(g)) for i, o, k, g in feedback if i in comp.u and o in comp.y and g != 0.0]
    ins = sorted({i for i, _, _, _ in fb})
    taps = sorted({(o, k) for _, o, k, _ in fb})
    G = np.zeros((len(ins), len(taps)))
    for i, o, k, g in fb:
        G[ins.index(i), taps.index((o, k))] += g
    ports = sorted({p for q in pulses for p in q.delta} | set(ins))
    # both replays take the present inputs raised by the errors' magnitude (the same in both: the difference is
    # the errors' response), so that a negative error never asks for a negative power
    lift = {p: sum(np.abs(q.delta[p]) for q in pulses if p in q.delta) for p in ports}
    u0 = {p: np.array(comp.u[p], dtype=float) + lift[p] for p in ports}
    # the segments: (length, step, input errors or None)
    segs, t = [], pulses[0].t0
    for q in pulses:
        if q.t0 > t:
            segs.append((q.t0 - t, q.step, None))
        segs.append((q.t1 - q.t0, q.step, q.delta))
        t = q.t1
    if now > t:
        segs.append((now - t, pulses[-1].step, None))

    def tap() -> np.ndarray:
        return np.array([float(np.ravel(comp.y[o])[k]) for o, k in taps])

    def inputs(delta, c=None) -> dict:
        u = {p: u0[p] + (delta[p] if delta is not None and p in delta else 0.0) for p in ports}
        for n, p in enumerate(ins if c is not None else ()):
            u[p] = u[p] + c[n]
        return u

    def run(perturbed: bool, base: list | None) -> tuple[dict[str, np.ndarray], list]:
        comp.set_state(snap)
        taken, n_step = [], 0
        for length, step, delta in segs:
            if length <= 0.0:
                continue
            n = max(1, int(math.ceil(length / step - 1e-9)))
            h = length / n
            d = delta if perturbed else None
            B = None
            for _ in range(n):
                if perturbed and ins:
                    s0 = comp.get_state()
                    if B is None:   # the step's response to each added input (linear: once per segment)
                        comp.set_inputs(inputs(d))
                        comp.do_step(comp.time, h)
                        y0 = tap()
                        B = np.zeros((len(taps), len(ins)))
                        for m in range(len(ins)):
                            comp.set_state(s0)
                            e = np.zeros(len(ins))
                            e[m] = 1.0
                            comp.set_inputs(inputs(d, e))
                            comp.do_step(comp.time, h)
                            B[:, m] = tap() - y0
                        comp.set_state(s0)
                    comp.set_inputs(inputs(d))
                    comp.do_step(comp.time, h)
                    dy0 = tap() - base[n_step]
                    comp.set_state(s0)
                    c = np.linalg.solve(np.eye(len(ins)) - G @ B, G @ dy0)
                    comp.set_inputs(inputs(d, c))
                else:
                    comp.set_inputs(inputs(d))
                comp.do_step(comp.time, h)
                if not perturbed:
                    taken.append(tap())
                n_step += 1
        return {o: np.array(comp.y[o], dtype=float).ravel() for o in outs}, taken

    try:
        base, path = run(False, None)
        pert, _ = run(True, path)
    finally:
        comp.set_state(snap)
    return {f"{name}.{o}": pert[o] - base[o] for o in outs}


class _Fired:
    """True once component ``name`` has stepped since the count ``n0`` (a class, not a closure: checkpoints
    pickle the hold)."""

    def __init__(self, steps_taken: dict, name: str, n0: int):
        self.steps_taken, self.name, self.n0 = steps_taken, name, n0

    def __call__(self) -> bool:
        return self.steps_taken.get(self.name, 0) > self.n0


class _Probe:
    """A producer's TO output at given thermal inputs with its frozen state, through the contract's own calls
    (get_state, set_inputs, do_step in its TO phase, set_state): the state is restored after each probe, so it
    works for any component that can save its state (FMUs included)."""

    def __init__(self, t: float, h: float):
        self.t, self.h = t, h
        # one snapshot per producer: every probe restores it, so the state each probe starts from is the same
        # (a fresh get_state per probe cost a copy of a large component's state ~100 times per staggered run)
        self._snaps: dict[int, object] = {}

    def __call__(self, comp, ports, u, port) -> float | None:
        snap = self._snaps.get(id(comp))
        if snap is None:
            try:
                snap = self._snaps[id(comp)] = comp.get_state()
            except Exception:  # a component (FMU) that cannot save its state: no TO law, the plain hold
                return None
        try:
            values, i = {}, 0
            for p in ports:
                n = comp.u[p].size
                values[p] = np.array(u[i:i + n], dtype=float)
                i += n
            if values:
                comp.set_inputs(values)
            comp.do_step(self.t, self.h)
            return float(comp.y[port][0])
        finally:
            comp.set_state(snap)
