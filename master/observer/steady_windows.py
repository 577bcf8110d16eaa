"""The steady windows: the last cycles of chosen signals at the end of every thermo-mechanical interval, kept in
memory for a case's results (a case's steady-state results are read from them)."""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from rotorcosim.components.contract import COUPLED
from rotorcosim.master.core.cycle import WINDOW_MARGIN, Cycle, as_cycle
from rotorcosim.master.observer.observer import Observer, sampled_rows


class SteadyWindows(Observer):
    """Keeps the last ``cycles`` cycles of ``signals`` in each TM interval; at the interval end, the window is
    stored in ``windows`` as a dict with ``t`` and one array per signal. ``cycle``: the cycle period [s] or a
    cycle source (master/core/cycle.py), read at the start of each TM interval. A cycle source with an angle
    counts the window in its turns (the run's RevolutionCounter): the samples since the last ``cycles`` turns
    began, plus the one at or before that time, as a window of ``cycles`` periods has; the window's dict then has
    ``revolutions``, the turns it spans (fewer than ``cycles`` where the interval was shorter); its ring, sized for
    the turns at 1 / WINDOW_MARGIN of the speed at the interval's start, grows where the speed falls further (a
    monolithic run of a falling speed). ``keep``: how many of the last windows ``windows`` keeps (None: all); a
    run of hours has hundreds of TM intervals, whose windows would otherwise fill the memory and every checkpoint."""

    def __init__(self, signals: Sequence[str], cycle: Cycle | float, cycles: float = 5.0,
                 sample_step: float | None = None, keep: int | None = None):
        self.signals = list(signals)
        self.keep = keep
        self.cycle = as_cycle(cycle)
        self.cycles = cycles
        #: the window of the present TM interval [s]
        self.window = cycles * self.cycle.constant if self.cycle.constant is not None else None
        self.sample_step = sample_step
        self.windows: list[dict] = []

    def interval_start(self, sim, phase, step):
        self.active = phase == COUPLED
        counter = getattr(sim, "revolutions", None)
        # counted in the turns of the run's angle when this window's cycle has that angle
        self._turns = counter if counter is not None and self.cycle.angle == counter.ref else None
        if self.active:
            self.window = self.cycles * self.cycle.period(sim.system)
        self.stride = 1 if self.sample_step is None else max(1, int(round(self.sample_step / step)))
        self._h = step
        n = int(math.ceil((self.window or 0.0) / (self.stride * step))) + 1
        if self._turns is not None and self.active:
            self._turns.need(self.cycles)
            n = int(math.ceil(WINDOW_MARGIN * self.window / (self.stride * step))) + 1
            if sim.interval_steps is not None:
                n = min(n, sim.interval_steps // self.stride + 1)
        self._n = n
        self._t = np.full(n, np.nan)
        self._data = {r: np.zeros((n, len(sim.value(r)))) for r in self.signals}
        comps = sim.system.components
        # (component, port, buffer) resolved once: this runs at every step of a thermo-mechanical interval
        self._taps = [(comps[r.partition(".")[0]], r.partition(".")[2], self._data[r]) for r in self.signals]
        self._pos = 0
        self._count = 0
        # a step number at or below this cannot be among the interval's last n samples (sampled steps are
        # multiples of the stride): step_block leaves those ring slots for the later rows that overwrite them
        steps = sim.interval_steps
        self._old = None if steps is None else steps - (n + 1) * self.stride
        if self._turns is not None:   # the ring may grow (_room): every row is kept
            self._old = None

    def _room(self, t: float, more: int = 0) -> None:
        """Counted in turns: a ring that would drop samples the window still needs (the speed fell below
        1 / WINDOW_MARGIN of its value at the interval's start) grows, oldest samples first."""
        need = int(math.ceil((t - self._turns.began(self.cycles, t)) / (self.stride * self._h) - 1e-9)) + 2 + more
        if need <= self._n:
            return
        n, count = self._n, self._count
        a = (self._pos - count) % n
        size = max(need, 2 * n)

        def grown(x):
            y = np.zeros((size,) + x.shape[1:]) if x.ndim > 1 else np.full(size, np.nan)
            y[:count] = x[a:a + count] if a + count <= n else np.concatenate((x[a:], x[:a + count - n]))
            return y

        self._t = grown(self._t)
        self._data = {r: grown(b) for r, b in self._data.items()}
        self._taps = [(c, port, self._data[r]) for (c, port, _), r in zip(self._taps, self.signals)]
        self._n, self._pos = size, count % size

    def step(self, sim, t):
        if not self.active:
            return
        if self._turns is not None and self._count == self._n and self._pos % 64 == 0:
            self._room(t, 64)
        i = self._pos
        self._t[i] = t
        for comp, port, buf in self._taps:
            buf[i] = comp.y[port]
        self._pos = (i + 1) % self._n
        self._count = min(self._count + 1, self._n)

    def block_signals(self, sim):
        return list(self.signals)

    def step_block(self, sim, ks, ts, data):
        if not self.active:
            return
        rows = sampled_rows(ks, self.stride)
        nr = len(rows)
        if not nr:
            return
        if self._turns is not None:   # the run's RevolutionCounter has this block already (the first observer)
            self._room(float(np.asarray(ts)[rows[-1]]))
        n = self._n
        m = min(nr, n)  # the ring keeps the last n samples: rows[nr - m:], the first of them at ring slot pos
        pos = (self._pos + (nr - m)) % n
        j0 = nr - m
        if self._old is not None:  # and of those, the rows after step _old (ks increase: a tail of them)
            j0 = max(j0, int(np.searchsorted(np.asarray(ks)[rows], self._old, side="right")))
        count = nr - j0
        if count:
            # rows j0.. go to the ring slots from p0 on (wrapping once at most), as slices: the sampled rows are
            # every stride-th row of the block, copied by slices rather than index arrays (the same values; the
            # index arrays cost ~1 ms a block of 2 048 rows, the most of a staggered run's short intervals)
            p0 = (pos + j0 - (nr - m)) % n
            a, b = int(rows[j0]), int(rows[-1])
            src = slice(a, b + 1, self.stride) if b - a == (count - 1) * self.stride else rows[j0:]
            first = min(count, n - p0)
            parts = [(slice(p0, p0 + first), slice(0, first))]
            if count > first:
                parts.append((slice(0, count - first), slice(first, count)))
            block = np.asarray(ts)[src]
            for dst, part in parts:
                self._t[dst] = block[part]
            for r in self.signals:
                block, ring = data[r][src], self._data[r]
                for dst, part in parts:
                    ring[dst] = block[part]
        self._pos = (pos + m) % n
        self._count = min(self._count + nr, n)

    def interval_end(self, sim, used):
        if not getattr(self, "active", False) or self._count == 0:
            return
        n, count = self._n, self._count
        a = (self._pos - count) % n  # the oldest sample's slot; the ring holds count samples from there on

        def ordered(x):  # oldest first (slices, not an index array)
            return x[a:a + count].copy() if a + count <= n else np.concatenate((x[a:], x[:a + count - n]))

        win = {"t": ordered(self._t), "t_start": used.t_start, "t_end": used.t_end}
        for r in self.signals:
            win[r] = ordered(self._data[r])
        if self._turns is not None:
            # the samples since the last turns began, and the one at or before that time
            t = win["t"]
            began = self._turns.began(self.cycles, float(t[-1]))
            k = min(int(math.ceil((t[-1] - began) / (self.stride * self._h) - 1e-9)) + 1, len(t))
            for key in ["t", *self.signals]:
                win[key] = win[key][len(t) - k:]
            win["revolutions"] = self._turns.revolutions(float(win["t"][0]), float(win["t"][-1]))
        self.windows.append(win)
        if self.keep is not None:
            del self.windows[:-self.keep]
