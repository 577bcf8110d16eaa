"""The load cycles of a staggered run: counted where they were simulated, extrapolated over the held intervals.

A held (thermal-only) interval simulates no vibration: its samples of a mechanical output repeat the last value.
The cycles it stands for are those of the steady cycle the hold froze: the window of the last ``turns``
revolutions of the coupled interval before it (the hold's own window: ``hold_cycles`` turns of the cycle's angle,
master/manipulator/hold.py), counted per revolution and repeated over the revolutions the held interval spans:

    n_held(S) = n_window(S) x (theta(t_1) - theta(t_0)) / (theta_w,1 - theta_w,0)

with ``theta`` the cycle's angle [rad], ``[t_0, t_1]`` the held interval and ``[theta_w,0, theta_w,1]`` the
window's angles. The window is counted as a periodic history (started at its largest value and closed there:
ASTM E1049-85 5.4.4, the rainflow count of a repeated history), so that its count has no residue of where it was
cut. Each coupled interval's own samples are counted as they are (fatigue.rainflow). A held interval with no
coupled interval before it (a run that starts held) has no window and adds no cycles.

The count holds what the hold assumes: the response over a held interval is the steady cycle of its window, at the
window's amplitude. The schedule ends a held interval when the speed or a thermal state drifts by its tolerance,
so the amplitude the count repeats is off by what that drift does to it.
"""
from __future__ import annotations

import math

import numpy as np

from rotorcosim.components.contract import COUPLED
from rotorcosim.master.observer.fatigue import EMPTY, LOAD_CLASSES, Counts, combine, library, rainflow, scaled
from rotorcosim.master.observer.observer import Observer


def runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """The [start, stop) index ranges of the True runs of ``mask``."""
    m = np.concatenate([[False], np.asarray(mask, dtype=bool), [False]])
    edges = np.flatnonzero(np.diff(m.astype(np.int8)))
    return list(zip(edges[::2].tolist(), edges[1::2].tolist()))


def periodic_count(w: np.ndarray) -> Counts:
    """The cycles of ``w`` taken as one period of a repeated history (started and closed at its largest value)."""
    if w.size < 3:
        return EMPTY
    k = int(np.argmax(w))
    return rainflow(np.concatenate([w[k:], w[:k], w[k:k + 1]]))


def staggered_counts(y, held, angle, turns: float) -> Counts:
    """The cycles of load series ``y`` of a staggered run (module docstring): ``held`` True at the samples of a held
    interval, ``angle`` the cycle's angle at each sample [rad], ``turns`` the hold's window in revolutions."""
    y = np.asarray(y, dtype=float)
    held = np.asarray(held, dtype=bool)
    angle = np.asarray(angle, dtype=float)
    parts = [rainflow(y[a:b]) for a, b in runs(~held)]
    for a, b in runs(held):
        if a == 0:
            continue
        end = a - 1                                   # the coupled interval's last sample: the hold starts there
        start = a
        while start > 0 and not held[start - 1] and angle[end] - angle[start - 1] <= 2.0 * math.pi * turns:
            start -= 1
        span = angle[end] - angle[start]
        if not span > 0.0:
            continue
        parts.append(scaled(periodic_count(y[start:end + 1]), (angle[b - 1] - angle[end]) / span))
    return combine(*parts) if parts else EMPTY


def cycle_angle(t, speed) -> np.ndarray:
    """The angle [rad] from a recorded speed [rad/s] (trapezoids from 0 at the first sample), for a run whose
    cycle has no recorded angle."""
    t, w = np.asarray(t, dtype=float), np.abs(np.asarray(speed, dtype=float))
    out = np.zeros(t.size)
    out[1:] = np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))
    return out


#: the coupled samples counted: one every SAMPLE_STEP [s] (37 a turn at 267 Hz: a peak missed by at most
#: 1 - cos(pi / 37) = 0.4 % of the amplitude)
SAMPLE_STEP = 1e-4
#: samples gathered before they are counted (a generic loop hands them over one at a time)
FLUSH = 4096


class Stream:
    """A rainflow count fed chunk by chunk (a run's hours do not fit in memory at once): the cycles closed so far,
    and the residue's turning points, which the next chunk continues; :meth:`counts` adds the residue's half
    cycles."""

    def __init__(self):
        self.closed: list[Counts] = []
        self.residue = np.zeros(0)

    def add(self, y: np.ndarray) -> None:
        """Count the next chunk ``y`` of the series after the residue of the chunks before."""
        z = np.concatenate([self.residue, np.asarray(y, dtype=float)])
        if z.size < 3 or not np.ptp(z) > 0.0:
            self.residue = z[-2:] if z.size else z
            return
        try:
            _, at = library().find_reversals(z, k=LOAD_CLASSES)
        except IndexError:      # fatpack's answer to a series without an inner turning point
            at = np.array([0, z.size - 1])
        rev = z[at]
        if at[-1] != z.size - 1 and rev.size > 1:
            # the last sample may lead to a turning point yet to come: the residue ends at it, for the next chunk
            if (z[-1] - rev[-1]) * (rev[-1] - rev[-2]) < 0.0:
                rev = np.append(rev, z[-1])
            elif (z[-1] - rev[-1]) * (rev[-1] - rev[-2]) > 0.0:
                rev[-1] = z[-1]
        cycles, residue = library().find_rainflow_cycles(rev) if rev.size > 2 else (np.zeros((0, 2)), rev)
        if cycles.size:
            self.closed.append(Counts(np.abs(cycles[:, 1] - cycles[:, 0]), np.ones(cycles.shape[0])))
        self.residue = residue

    def counts(self) -> Counts:
        """Every cycle counted so far: the closed ones, and the residue's ranges as half cycles."""
        half = np.abs(np.diff(self.residue)) if self.residue.size > 1 else np.zeros(0)
        return combine(*self.closed, Counts(half, np.full(half.size, 0.5)))


class LoadCycles(Observer):
    """The rainflow cycles of each element of the loads ``refs`` ("comp.port") over a staggered run (module
    docstring): the coupled intervals' samples (one every ``sample_step``) counted as they come, each held interval
    counted from the last ``turns`` revolutions of the coupled interval before it times the revolutions it spans.
    ``cycle``: the run's cycle (master/core/cycle.py): its angle signal, or a constant period (the angle 2 pi t /
    period); None or a speed signal without an angle: held intervals cannot be counted (an error names it when one
    comes). :meth:`counts` gives ``{"comp.port[i]": Counts}``."""

    def __init__(self, refs, cycle=None, turns: float = 5.0, sample_step: float = SAMPLE_STEP):
        self.refs = list(refs)
        self.angle_ref = getattr(cycle, "angle", None)
        self.period = getattr(cycle, "constant", None)
        self.turns = float(turns)
        self.sample_step = float(sample_step)
        self.streams: dict[str, Stream] = {}
        self.held: list[Counts] = []
        self.coupled = False

    def start(self, sim, schedule) -> None:
        self.keys = []
        for ref in self.refs:
            n = int(np.asarray(sim.value(ref)).size)
            self.keys += [f"{ref}[{i}]" for i in range(n)] if n > 1 else [ref]
        self.streams = {k: Stream() for k in self.keys}
        self.held = {k: [] for k in self.keys}
        self.window: list[np.ndarray] = []
        self.pending: list[np.ndarray] = []
        self.n_pending = 0

    def _angle(self, sim, t: float) -> float:
        if self.angle_ref is not None:
            return float(np.asarray(sim.value(self.angle_ref)).ravel()[0])
        if self.period:
            return 2.0 * math.pi * t / self.period
        raise ValueError("the load cycles of a held interval need the cycle's angle ([schedule] cycle angle = "
                         "\"comp.port\") or a constant period")

    def interval_start(self, sim, phase, step) -> None:
        self.coupled = phase == COUPLED
        if self.coupled:
            self.window = []
            self.next_sample = sim.t
        else:
            self.held_from = self._angle(sim, sim.t)

    def interval_end(self, sim, used) -> None:
        self._flush()
        if self.coupled or not self.window:
            return
        rows = np.vstack(self.window)
        th = rows[:, 0]
        keep = th >= th[-1] - 2.0 * math.pi * self.turns
        span = th[-1] - th[keep][0]
        if not span > 0.0:
            return
        factor = abs(self._angle(sim, sim.t) - self.held_from) / abs(span)
        for j, key in enumerate(self.keys):
            self.held[key].append(scaled(periodic_count(rows[keep, 1 + j]), factor))

    def block_signals(self, sim) -> list[str]:
        return list(dict.fromkeys(self.refs + ([self.angle_ref] if self.angle_ref else [])))

    def _take(self, sim, ts, value) -> None:
        ts = np.asarray(ts, dtype=float)
        # one sample every sample_step: the first step at or after each sampling time
        slot = np.floor((ts - self.next_sample) / self.sample_step + 1e-9)
        pick = np.flatnonzero((slot >= 0) & np.concatenate([[True], np.diff(slot) > 0]))
        if not pick.size:
            return
        self.next_sample += (slot[pick[-1]] + 1.0) * self.sample_step
        cols = [np.asarray(value(ref)).reshape(len(ts), -1)[pick] for ref in self.refs]
        y = np.hstack(cols)
        if self.angle_ref is not None:
            th = np.asarray(value(self.angle_ref)).reshape(len(ts), -1)[pick, 0]
        elif self.period:
            th = 2.0 * math.pi * ts[pick] / self.period
        else:
            th = np.full(pick.size, np.nan)
        rows = np.column_stack([th, y])
        self.pending.append(rows)
        self.n_pending += rows.shape[0]
        if self.n_pending >= FLUSH:
            self._flush()
        self.window.append(rows)
        # keep the last `turns` revolutions (and one chunk more) for a held interval that may follow
        while len(self.window) > 1 and np.isfinite(th[-1]) and \
                self.window[1][0, 0] <= th[-1] - 2.0 * math.pi * self.turns:
            self.window.pop(0)

    def _flush(self) -> None:
        if self.pending:
            y = np.vstack(self.pending)[:, 1:]
            for j, key in enumerate(self.keys):
                self.streams[key].add(y[:, j])
        self.pending, self.n_pending = [], 0

    def step_block(self, sim, ks, ts, data) -> None:
        if self.coupled and len(ts):
            self._take(sim, ts, lambda ref: data[ref])

    def step(self, sim, t) -> None:
        if self.coupled:
            self._take(sim, [t], lambda ref: np.asarray(sim.value(ref))[None, :])

    def counts(self) -> dict[str, Counts]:
        """Every load element's cycles: its coupled samples' and its held intervals'."""
        self._flush()
        return {k: combine(self.streams[k].counts(), *self.held[k]) for k in self.keys}
