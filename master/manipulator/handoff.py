"""A hand-off of the thermal-only hold (hold.py): one mechanical -> thermal connection, its window over a
thermo-mechanical interval and the value it holds over a thermal-only one.

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
* The group driver (:class:`Driver`): a producer's cycle means can drift with a temperature that is none of its
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
"""
from __future__ import annotations

import math

import numpy as np

from rotorcosim.master.core import window
from rotorcosim.master.core.window import Window

#: least spread of ln(y_TO) over the recorded cycles to measure an elasticity (5 %)
MIN_SPREAD = 0.05
#: elasticities outside this range are no viscous law: clipped
ELASTICITY_RANGE = (0.0, 2.0)
#: TM intervals whose cycles enter the elasticity fit (the latest ones: the law is local)
FIT_INTERVALS = 3
#: least spread (K) of a group temperature over the recorded cycles to drive a hand-off's TO law (Driver)
DRIVER_MIN_SPREAD_K = 1.0
#: the relative step of an input at which a TO law's sensitivity is probed (HandOff._gains; an input at zero is
#: not probed)
GAIN_STEP = 1e-3
#: the driver's factor exp(b dT) is bounded to exp(+-DRIVER_MAX_LOG) (a factor 3): a guard against extrapolating
#: a slope far beyond its data
DRIVER_MAX_LOG = 1.1


class HandOff:
    """One mechanical -> thermal connection: its window, its cycle means, its held value in TO."""

    def __init__(self, link, hold: str, thermal_ports: list[str]):
        self.link = link
        self.hold = hold
        self.ports = thermal_ports          # the producer's inputs that come from thermal components
        self.updates = bool(getattr(link.src, "holds_state_in_TO", False))
        self.elasticity: float | None = None
        self.history: list[list[tuple[np.ndarray, float]]] = []   # per TM interval: (thermal inputs, cycle mean)
        #: the current TM interval's cycles (none before the first: a timeline may begin thermal-only)
        self.cycles: list[tuple[np.ndarray, float]] = []
        self.held = None
        self.error: float | None = None
        self.delta: np.ndarray | None = None
        #: the share of its law's move over the last charged TO interval that the mechanics made (:func:`loop_share`:
        #: the error estimate's loop runs at this share of the law's sensitivity, hold.py)
        self.loop_share = 1.0
        self._to_end: np.ndarray | None = None
        self._to_start: np.ndarray | None = None
        #: the window's recording state (master/core/window.py: both loops record into it)
        self.w = Window()
        self.turns = None                   # (RevolutionCounter, turns of the window, the angle's component, port)
        self.hs = 0.0                       # the producer's step in the TM interval [s]
        #: the power's sensitivity to the thermal values it follows, from its last TO law: (component whose input
        #: it is, its port, element, dP/du [W per the input's unit]); the error estimate's feedback (error_estimate.replay)
        self.gains: list[tuple[str, str, int, float]] = []
        #: the held statistic the gains were taken at [W]: an error from them is a share of it
        self.gains_at = 0.0
        #: the last of ``gains`` is the driver's (:class:`Driver`: a temperature fitted to trend with the power,
        #: not the producer's own physics)
        self.driven = False

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
        self.loop_share = loop_share(self._to_end - self._to_start, self.delta)
        self._to_end = self._to_start = None
        return True

    def forget_restart(self) -> None:
        """The TO interval ended at a scheduled change of the system: its held value is not compared with the
        mechanics after the change."""
        self._to_end = self._to_start = None

    # -- TO: hold -----------------------------------------------------------------------------------------
    def start_to(self, probe, fired, cycles: int, group: list["HandOff"] | None = None) -> None:
        """A TO interval starts: hold the window's statistic, or a law that follows the producer's own TO
        output and, where one tracks it better, another hand-off's temperature (``group``: the hand-offs of the
        system). ``probe`` evaluates a producer's TO output at given inputs, ``fired`` tells whether a component
        has stepped in this interval, ``cycles`` is the number of rotor cycles of the window."""
        S = self.statistic(self.hold)
        self.held = Held(self.link, S)
        if not self.updates or self.link.src.y[self.link.sport].size != 1 or not float(S[0]) > 0.0:
            return
        ref = probe(self.link.src, self.ports, self.window_inputs(cycles), self.link.sport)
        if ref is None or not ref > 0.0:
            return
        # a driver only where another producer's temperature tracks the cycle means better than the producer's
        # own TO law does: its own inputs are that law's (physical) business, and an exponential fitted on a few K
        # of TM and extrapolated over a long TO interval is not (the 2-minute run: 0.07 % against the monolithic
        # run with this rule, 1.4 % with the producer's own temperatures as drivers)
        drive = Driver.choose(self, [g for g in (group or []) if g is not self], cycles)
        pts = self._settled_points(probe)
        if drive is not None and drive.r <= self._own_correlation(pts):
            drive = None
        e = self._fit(pts, drive)
        if e is not None:
            self.elasticity = e
        self.held = HeldLaw(self.link, S, ref, 1.0 if self.elasticity is None else self.elasticity, fired, drive)
        self.gains = self._gains(probe, self.window_inputs(cycles), ref, self.held)
        self.gains_at = float(S[0])
        self.driven = drive is not None

    def power_error(self, error_of) -> float:
        """The power in error [its unit] by its last law's sensitivity (``gains``) to the values it follows, each
        in error by ``error_of(component, port, element)`` (None: no estimate, left out): dP = sum g_i du_i, the
        driver's term at ``loop_share``. A driver is a temperature that trended with the power over the coupled
        cycles, not the producer's own physics; the restart measured how much of the law's move the mechanics
        made, and a driver the mechanics did not follow is a co-trend (the producer's own terms, its physics at
        the frozen state, keep the law's full sensitivity)."""
        driver = len(self.gains) - 1 if self.driven else None
        d = 0.0
        for n, (comp, port, k, g) in enumerate(self.gains):
            err = error_of(comp, port, k)
            if err is not None:
                d += g * err * (self.loop_share if n == driver else 1.0)
        return d

    def _gains(self, probe, u, ref: float, law: "HeldLaw") -> list[tuple[str, str, int, float]]:
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
    def _fit(pts, drive: "Driver | None" = None) -> float | None:
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
        """A TO interval ends: keep its first and last held values (the next TM restart measures the hand-off
        error and the share of the law's move the mechanics made)."""
        if self.held is not None:
            self._to_end = np.array(self.held.value(), dtype=float)
            self._to_start = np.array(self.held.S, dtype=float)
        self.held = None


def loop_share(law_move: np.ndarray, delta: np.ndarray) -> float:
    """The share of a TO law's move over a held interval (``law_move``: its last value minus its first) that the
    mechanics made (the law's move less its hand-off error ``delta``: the restart's value minus the first), at most
    1; 1 where the law moved no more than its error (no share to measure: the law's own sensitivity stands) or the
    port has more than one element. A share below 1 is a mechanics less sensitive than the law to the
    values both follow, or a move of values the law does not follow; the error estimate's loop takes the first
    (the smaller pull-back, the larger estimate), and a power's own error the law's full sensitivity but for a
    driver's term, which counts at this share (:meth:`HandOff.power_error`)."""
    if law_move.size != 1 or delta.size != 1:
        return 1.0
    move, d = float(law_move[0]), float(delta[0])
    if not abs(move) > abs(d):
        return 1.0
    return min(1.0 - d / move, 1.0)


class Held:
    """The window statistic, constant over the TO interval."""

    def __init__(self, link, S):
        # a Real statistic as float; an Integer, Boolean or String value kept as it is (held, not averaged)
        self.link, self.S = link, (np.array(S, dtype=float) if link.real else np.array(S))

    def value(self) -> np.ndarray:
        """The value the link carries now."""
        return self.S


class HeldLaw(Held):
    """S_w * (y_TO(t) / y_TO,w) ** e * exp(b (T(t) - T_w)), y_TO(t) the producer's own TO output (its last TO
    step), T(t) the driver's present temperature (:class:`Driver`, if any)."""

    def __init__(self, link, S, ref, e, fired, drive=None):
        super().__init__(link, S)
        self.ref, self.e = float(ref), float(e)
        self.fired = fired     # false until the producer has stepped in this TO interval (its output is its TM one)
        self.drive = drive

    def value(self) -> np.ndarray:
        """The law's value now: the statistic until the producer has stepped in this TO interval."""
        if not self.fired():
            return self.S
        y = float(self.link.src.y[self.link.sport][0])
        if not y > 0.0:
            return self.S
        f = (y / self.ref) ** self.e
        if self.drive is not None:
            f *= self.drive.factor()
        return self.S * f


class Driver:
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
        """exp(b (T(t) - T_w)) at the driver's present temperature, bounded by DRIVER_MAX_LOG."""
        th = float(np.ravel(self.owner.link.src.u[self.port])[self.k])
        return math.exp(max(-DRIVER_MAX_LOG, min(DRIVER_MAX_LOG, self.b * (th - self.w))))

    @staticmethod
    def choose(ho: "HandOff", group: list["HandOff"], cycles: int) -> "Driver | None":
        """The driver of hand-off ``ho`` among the temperatures of ``group`` (its window's last ``cycles`` cycles
        give T_w), or None: none recorded cycle for cycle with it, or none moved by DRIVER_MIN_SPREAD_K."""
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
        return Driver(g, p, k, b, w, list(th), r)


class Fired:
    """True once component ``name`` has stepped since the count ``n0`` (a class, not a closure: checkpoints
    pickle the hold)."""

    def __init__(self, steps_taken: dict, name: str, n0: int):
        self.steps_taken, self.name, self.n0 = steps_taken, name, n0

    def __call__(self) -> bool:
        return self.steps_taken.get(self.name, 0) > self.n0


class Probe:
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
