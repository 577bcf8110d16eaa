"""The staggered scheme's error estimate: what the thermal-only hold (hold.py) measures of its own error, and the
replay that carries a held interval's hand-off errors to the thermal components' outputs.

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
  film power that falls as its oil warms pulls a too warm oil back. The loop runs at the mechanics' sensitivity as
  far as the restart shows it: the law's gains times the share of the law's move over the last charged interval
  that the mechanics made (``HandOff.loop_share``, at most 1: a mechanics that moved less than the law pulls back
  less; one that moved more may have followed values the law does not, and is not credited with a stronger
  pull-back). The mechanics' sensitivity lies between that share of the law's and the law's own, and an output
  whose error is a difference of two inputs' responses (a ball between a drag and a rub that err apart) may grow
  with a stronger loop: each output takes the larger of its errors in the two loops (hold.py ``_response``). The interval's own estimate is its pulse's
  response at the restart; the run's, at its end, the response
  of all the charged intervals' pulses together (a later interval's error that undoes an earlier one's cancels
  it: the mechanics restarted at erring temperatures give powers that pull them back). Temperatures are judged
  against their rise since the run's start (at least ``RISE_FLOOR_K``), not their absolute values; what the
  thermal components hand back to the mechanics (oil temperatures, growths) is in error by a share of its move
  over the last charged interval (``mechanics_fraction``), which the mechanical results share. A TO interval
  that ends at a scheduled change of a component (its ``next_event``: a fuel cut) is not charged: the mechanics
  after the change are not what its held values stood for.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np
import scipy.linalg
from scipy.linalg.lapack import dgetrs

#: least rise [K] a temperature's relative error is taken of (a node that barely warms has no relative error to speak
#: of: its absolute one is reported in ``output_errors``)
RISE_FLOOR_K = 1.0


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
    #: per hand-off with a law: the share of its law's move over the last charged TO interval the mechanics made
    #: (HandOff.loop_share, at most 1), at which the replay's loop runs besides the law's own
    loop_share: dict[str, float] = field(default_factory=dict)
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
    #: sensitivity to the estimated errors of the values its producer takes back (hand-offs with a law only;
    #: HandOff.power_error: a driver's term at the share of the law's move the mechanics made)
    handoff_errors_end: dict[str, float] = field(default_factory=dict)
    #: the same, percent of the power the law held when its sensitivity was taken: the share that carries over to
    #: another operating point (after the last held interval a rundown's powers fall with the speed, and the error
    #: in watts of a law made at the higher speed would be read against a far smaller power)
    handoff_errors_end_pct: dict[str, float] = field(default_factory=dict)
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
               "loop_share": dict(self.loop_share),
               "interval_estimates_pct": list(self.interval_estimates_pct),
               "intervals": [dict(i) for i in self.intervals],
               "output_errors": dict(self.output_errors), "output_rise": dict(self.output_rise),
               "output_move": dict(self.output_move), "mechanics_fraction": dict(self.mechanics_fraction),
               "handoff_errors_end": dict(self.handoff_errors_end),
               "handoff_errors_end_pct": dict(self.handoff_errors_end_pct),
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


def replay(comp, name: str, pulses: list[Pulse], now: float, feedback: list[tuple[str, str, int, float]] = (),
           also: Sequence[list[tuple[str, str, int, float]]] = ()) -> dict[str, np.ndarray]:
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
    without it. ``also``: other loops of the same kind; each output then takes the largest of its errors (in
    magnitude, per element) over ``feedback``'s and theirs (the replay without errors is run once for all)."""
    outs = [v.name for v in comp.variables if v.causality == "output" and v.type == "Real"]
    try:
        snap = comp.get_state()
    except Exception:  # cannot save its state: no estimate from it
        return {}
    loops = [[(i, o, k, float(g)) for i, o, k, g in f if i in comp.u and o in comp.y and g != 0.0]
             for f in (feedback, *also)]
    ins = sorted({i for fb in loops for i, _, _, _ in fb})
    taps = sorted({(o, k) for fb in loops for _, o, k, _ in fb})
    Gs = []
    for fb in loops:
        G = np.zeros((len(ins), len(taps)))
        for i, o, k, g in fb:
            G[ins.index(i), taps.index((o, k))] += g
        Gs.append(G)
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
        y = comp.y
        return np.array([y[o].item(k) if type(y[o]) is np.ndarray else float(np.ravel(y[o])[k]) for o, k in taps])

    def inputs(delta, c=None) -> dict:
        u = {p: u0[p] + (delta[p] if delta is not None and p in delta else 0.0) for p in ports}
        for n, p in enumerate(ins if c is not None else ()):
            u[p] = u[p] + c[n]
        return u

    def run(perturbed: bool, base: list | None, G: np.ndarray | None = None) -> tuple[dict[str, np.ndarray], list]:
        comp.set_state(snap)
        taken, n_step = [], 0
        for length, step, delta in segs:
            if length <= 0.0:
                continue
            n = max(1, int(math.ceil(length / step - 1e-9)))
            h = length / n
            d = delta if perturbed else None
            u_d = inputs(d)   # made once: a component reads its inputs and never writes them
            B = lu = None
            for _ in range(n):
                if perturbed and ins:
                    s0 = comp.get_state()
                    if B is None:   # the step's response to each added input (linear: once per segment)
                        comp.set_inputs(u_d)
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
                        lu = scipy.linalg.lu_factor(np.eye(len(ins)) - G @ B)
                    comp.set_inputs(u_d)
                    comp.do_step(comp.time, h)
                    dy0 = tap() - base[n_step]
                    comp.restore_state(s0)
                    c, _ = dgetrs(*lu, G @ dy0)   # lu_solve's own LAPACK call, without its checks (per step)
                    comp.set_inputs(inputs(d, c))
                else:
                    comp.set_inputs(u_d)
                comp.do_step(comp.time, h)
                if not perturbed:
                    taken.append(tap())
                n_step += 1
        return {o: np.array(comp.y[o], dtype=float).ravel() for o in outs}, taken

    try:
        base, path = run(False, None)
        out = {o: None for o in outs}
        for G in Gs:
            pert, _ = run(True, path, G)
            for o in outs:
                e = pert[o] - base[o]
                out[o] = e if out[o] is None else np.where(np.abs(e) > np.abs(out[o]), e, out[o])
    finally:
        comp.set_state(snap)
    return {f"{name}.{o}": e for o, e in out.items()}
